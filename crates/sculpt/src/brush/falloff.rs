//! The brush falloff: how much of a brush's displacement a vertex at
//! distance `d` from the centre gets, as a function of `t = d / r` in
//! `[0, 1]` (0 beyond the radius). The curves are the ones sculptors know
//! from SculptGL and Blender's sculpt mode.

use serde::{Deserialize, Serialize};

/// A falloff curve. All are 1 at the centre (`t = 0`) and 0 beyond the
/// radius; all but `Constant` reach 0 at the rim.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Falloff {
    /// `(1 − t²)²`: zero slope at both ends, so the displaced region
    /// blends into the rest with no crease (the default).
    #[default]
    Smooth,
    /// `√(1 − t²)`: a hemisphere's profile, full almost to the rim.
    Sphere,
    /// `√(1 − t)`: steep at the rim, flat nowhere.
    Root,
    /// `(1 − t)²`: a sharp peak at the centre.
    Sharp,
    /// `1 − t`: a cone.
    Linear,
    /// `1` within the radius: a flat stamp with a step at the rim.
    Constant,
    /// A curve through five values at `t = 0, ¼, ½, ¾, 1`, linear between
    /// them (each clamped to `[0, 1]`).
    Custom([f64; 5]),
}

impl Falloff {
    /// The weight at `distance` from the centre of a brush of `radius`:
    /// the curve at `t = distance / radius` within the radius, 0 beyond
    /// it, for a non-positive radius and for NaN.
    pub fn weight(self, distance: f64, radius: f64) -> f64 {
        // Written so that NaN falls outside.
        let inside = radius > 0.0 && distance < radius;
        if !inside {
            return 0.0;
        }
        let t = (distance / radius).max(0.0);
        match self {
            Falloff::Smooth => {
                let u = 1.0 - t * t;
                u * u
            }
            Falloff::Sphere => (1.0 - t * t).sqrt(),
            Falloff::Root => (1.0 - t).sqrt(),
            Falloff::Sharp => (1.0 - t) * (1.0 - t),
            Falloff::Linear => 1.0 - t,
            Falloff::Constant => 1.0,
            Falloff::Custom(values) => {
                let x = t * 4.0;
                let k = (x.floor() as usize).min(3);
                let f = x - k as f64;
                let at = |i: usize| {
                    let v = values[i];
                    if v.is_finite() {
                        v.clamp(0.0, 1.0)
                    } else {
                        0.0
                    }
                };
                at(k) * (1.0 - f) + at(k + 1) * f
            }
        }
    }

    /// The name used in stroke files (`custom` for a curve).
    pub fn name(self) -> &'static str {
        match self {
            Falloff::Smooth => "smooth",
            Falloff::Sphere => "sphere",
            Falloff::Root => "root",
            Falloff::Sharp => "sharp",
            Falloff::Linear => "linear",
            Falloff::Constant => "constant",
            Falloff::Custom(_) => "custom",
        }
    }
}

/// The plateau falloff: 1 within half the radius, then the smooth curve
/// over the outer half (`(1 − u²)²` with `u = (d − r/2) / (r/2)`), 0
/// beyond: a part held rigidly and blended into the rest (the local
/// move, the snake hook). Its slope is at most `2 × 8 / (3√3 r) ≈ 3.08/r`.
pub fn plateau(distance: f64, radius: f64) -> f64 {
    let half = 0.5 * radius;
    if distance <= half {
        if radius > 0.0 { 1.0 } else { 0.0 }
    } else {
        Falloff::Smooth.weight(distance - half, half)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_at_centre_middle_and_rim() {
        let half = |f: Falloff| f.weight(0.5, 1.0);
        assert_eq!(half(Falloff::Smooth), 0.5625);
        assert_eq!(half(Falloff::Sphere), 0.75f64.sqrt());
        assert_eq!(half(Falloff::Root), 0.5f64.sqrt());
        assert_eq!(half(Falloff::Sharp), 0.25);
        assert_eq!(half(Falloff::Linear), 0.5);
        assert_eq!(half(Falloff::Constant), 1.0);
        let curve = Falloff::Custom([1.0, 0.2, 0.6, 0.0, 0.0]);
        assert_eq!(curve.weight(0.5, 1.0), 0.6);
        assert!((curve.weight(0.125, 1.0) - 0.6).abs() < 1e-15);
        for f in [
            Falloff::Smooth,
            Falloff::Sphere,
            Falloff::Root,
            Falloff::Sharp,
            Falloff::Linear,
            Falloff::Constant,
            curve,
        ] {
            assert_eq!(f.weight(0.0, 2.0), 1.0, "{f:?} at the centre");
            assert_eq!(f.weight(2.0, 2.0), 0.0, "{f:?} at the rim");
            assert_eq!(f.weight(f64::NAN, 2.0), 0.0);
            assert_eq!(f.weight(0.0, 0.0), 0.0, "no radius, no brush");
            if f != Falloff::Constant {
                assert!(f.weight(1.999_999, 2.0) < 1e-2, "{f:?} near the rim");
            }
        }
        // Out-of-range and NaN control values are clamped, not passed on.
        let wild = Falloff::Custom([2.0, f64::NAN, -1.0, 0.5, 0.0]);
        assert_eq!(wild.weight(0.0, 1.0), 1.0);
        assert_eq!(wild.weight(0.25, 1.0), 0.0);
    }

    #[test]
    fn the_default_is_the_papers_smooth_curve() {
        for d in [0.0, 0.1, 0.37, 0.8, 0.999] {
            assert_eq!(
                Falloff::default().weight(d, 1.0),
                super::super::falloff(d, 1.0)
            );
        }
    }

    #[test]
    fn stroke_file_names() {
        let f: Falloff = serde_json::from_str("\"root\"").unwrap_or_default();
        assert_eq!(f, Falloff::Root);
        let c: Result<Falloff, _> = serde_json::from_str(r#"{"custom": [1, 0.5, 0.25, 0.1, 0]}"#);
        assert!(matches!(c, Ok(Falloff::Custom(_))));
        assert!(serde_json::from_str::<Falloff>("\"wobbly\"").is_err());
    }
}
