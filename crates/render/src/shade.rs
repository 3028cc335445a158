//! Lighting and colour conversion.
//!
//! Shading happens in linear light with lights fixed to the camera, as in
//! a modeler's viewport, so every view of a model is lit the same way:
//!
//! I = albedo · (ambient(n) + Σ kᵢ max(0, n·Lᵢ)) + s · max(0, n·H)³²
//!
//! in eye space (x right, y up, z toward the viewer), with a key light
//! from the upper left in front, a weaker fill light from the right, a
//! hemispherical ambient term that is brighter for normals facing up
//! (sky) than down (ground), and a faint Blinn highlight of the key light
//! (H the half vector between the key light and the viewer). Faces are
//! lit two-sidedly: the caller flips the normal of a face seen from
//! behind and gives it the back material.

use glam::Vec3;
use std::sync::OnceLock;

use crate::Rgb;

/// sRGB 8-bit value → linear intensity in [0, 1] (IEC 61966-2-1).
pub fn srgb_to_linear(c: u8) -> f32 {
    lut().to_linear[c as usize]
}

/// Linear intensity → nearest 8-bit sRGB value (values outside [0, 1]
/// are clamped).
#[inline]
pub fn linear_to_srgb(x: f32) -> u8 {
    lut().encode(x)
}

/// Resolution of the linear → sRGB table: fine enough that every 8-bit
/// output is reachable and rounding errors stay below half a step. A power
/// of two, so a masked index needs no bounds check.
const ENCODE_STEPS: usize = 8192;

/// Conversion tables between 8-bit sRGB and linear light.
pub(crate) struct Lut {
    pub to_linear: [f32; 256],
    to_srgb: Box<[u8; ENCODE_STEPS]>,
}

impl Lut {
    /// Linear intensity → nearest 8-bit sRGB value, clamped.
    #[inline]
    pub fn encode(&self, x: f32) -> u8 {
        // NaN stays NaN through clamp and `as` turns it into 0.
        let i = (x.clamp(0.0, 1.0) * (ENCODE_STEPS - 1) as f32 + 0.5) as usize;
        self.to_srgb[i & (ENCODE_STEPS - 1)]
    }

    /// A linear colour as an opaque packed sample.
    #[inline]
    pub fn pack(&self, c: Vec3) -> u32 {
        pack([self.encode(c.x), self.encode(c.y), self.encode(c.z)], 255)
    }
}

/// The tables, computed once.
pub(crate) fn lut() -> &'static Lut {
    static LUT: OnceLock<Lut> = OnceLock::new();
    LUT.get_or_init(|| {
        let decode = |s: f64| {
            if s <= 0.04045 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            }
        };
        let encode = |l: f64| {
            if l <= 0.003_130_8 {
                l * 12.92
            } else {
                1.055 * l.powf(1.0 / 2.4) - 0.055
            }
        };
        let mut to_linear = [0.0f32; 256];
        for (i, slot) in to_linear.iter_mut().enumerate() {
            *slot = decode(i as f64 / 255.0) as f32;
        }
        let mut to_srgb = Box::new([0u8; ENCODE_STEPS]);
        for (i, slot) in to_srgb.iter_mut().enumerate() {
            let l = i as f64 / (ENCODE_STEPS - 1) as f64;
            *slot = (encode(l) * 255.0).round().clamp(0.0, 255.0) as u8;
        }
        Lut { to_linear, to_srgb }
    })
}

/// An sRGB colour as linear RGB.
pub fn rgb_linear(c: Rgb) -> Vec3 {
    Vec3::new(
        srgb_to_linear(c[0]),
        srgb_to_linear(c[1]),
        srgb_to_linear(c[2]),
    )
}

/// Packs an opaque sRGB colour as a sample: r | g << 8 | b << 16 | a << 24.
#[inline]
pub fn pack(c: Rgb, a: u8) -> u32 {
    u32::from(c[0]) | u32::from(c[1]) << 8 | u32::from(c[2]) << 16 | u32::from(a) << 24
}

/// A linear colour as an opaque packed sample.
#[inline]
pub fn pack_linear(c: Vec3) -> u32 {
    lut().pack(c)
}

/// The light rig, in eye space.
#[derive(Clone, Debug)]
pub struct Shader {
    key_dir: Vec3,
    key: f32,
    fill_dir: Vec3,
    fill: f32,
    ambient: f32,
    sky: f32,
    half_vec: Vec3,
    spec: f32,
}

impl Default for Shader {
    fn default() -> Self {
        let key_dir = Vec3::new(-0.4, 0.5, 0.77).normalize();
        Shader {
            key_dir,
            key: 0.7,
            fill_dir: Vec3::new(0.6, -0.3, 0.74).normalize(),
            fill: 0.22,
            ambient: 0.14,
            sky: 0.05,
            half_vec: (key_dir + Vec3::Z).normalize(),
            spec: 0.06,
        }
    }
}

impl Shader {
    /// Linear colour of a surface with unit eye-space normal `n` (facing
    /// the viewer) and linear albedo.
    #[inline]
    pub fn shade(&self, n: Vec3, albedo: Vec3) -> Vec3 {
        let diffuse = self.ambient
            + self.sky * n.y
            + self.key * n.dot(self.key_dir).max(0.0)
            + self.fill * n.dot(self.fill_dir).max(0.0);
        let h = n.dot(self.half_vec).max(0.0);
        let h2 = h * h;
        let h4 = h2 * h2;
        let h8 = h4 * h4;
        let h16 = h8 * h8;
        albedo * diffuse + Vec3::splat(self.spec * h16 * h16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip_is_exact() {
        for c in 0..=255u8 {
            assert_eq!(linear_to_srgb(srgb_to_linear(c)), c);
        }
        assert_eq!(srgb_to_linear(0), 0.0);
        assert_eq!(srgb_to_linear(255), 1.0);
        // Mid-grey: sRGB 188 is about 50 % linear (0.5029).
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-3);
        assert_eq!(linear_to_srgb(-1.0), 0);
        assert_eq!(linear_to_srgb(7.0), 255);
        assert_eq!(linear_to_srgb(f32::NAN), 0);
    }

    #[test]
    fn lighting_prefers_the_key_light() {
        let s = Shader::default();
        let white = Vec3::ONE;
        let toward_key = s.shade(s.key_dir, white);
        let facing = s.shade(Vec3::Z, white);
        let away = s.shade(Vec3::new(0.0, -1.0, 0.0), white);
        assert!(toward_key.x > facing.x && facing.x > away.x);
        // Nothing is pitch black: the ambient term lights every normal.
        assert!(away.x > 0.1);
        // A face toward the viewer is neither blown out nor dim.
        assert!(facing.x > 0.6 && facing.x < 1.0, "{facing}");
    }
}
