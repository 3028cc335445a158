//! Views, up axes and automatic framing.
//!
//! ## Conventions
//!
//! Named views are defined for a **z-up** world ([`Up::Z`], the default,
//! which is how holey's primitives and the thesis's figures stand): the
//! front view looks from −y toward +y with +x to the right, the iso view
//! looks from the front, right and above. For a **y-up** file
//! ([`Up::Y`], common for OBJ exports) every named view is rotated by the
//! map (x, y, z) ↦ (x, z, −y), so "front" looks from +z, "top" from +y,
//! and the pictures look the same as for the equivalent z-up model.
//!
//! The screen's up is the world up axis projected onto the picture plane;
//! when the view looks along the up axis (top, bottom), the screen's up is
//! the world's "back" direction (+y for z-up) seen from above and its
//! "front" direction seen from below, so +x points to the right in both.

use glam::{DVec2, DVec3};

use crate::{RenderError, unit};

/// A vertex in sample coordinates (x right, y down) with w = 1/z: what
/// a projection gives the rasterizer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SVert {
    pub x: f64,
    pub y: f64,
    pub w: f64,
}
/// How much of the shorter picture side the model fills.
pub const FILL: f64 = 0.85;

/// Where the model is seen from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum View {
    /// From the front, right and above: direction (1, −0.8, 1.2) z-up.
    #[default]
    Iso,
    /// From −y (z-up) / +z (y-up).
    Front,
    /// From +y (z-up) / −z (y-up).
    Back,
    /// From −x.
    Left,
    /// From +x.
    Right,
    /// From +z (z-up) / +y (y-up).
    Top,
    /// From −z (z-up) / −y (y-up).
    Bottom,
    /// From this world direction (model → camera), whatever the up axis;
    /// must be finite and non-zero.
    Direction(DVec3),
}

impl View {
    /// Parses `iso`, `front`, `back`, `left`, `right`, `top`, `bottom`
    /// (any case) or a direction `x,y,z` from the model toward the camera
    /// (three finite numbers, not all zero).
    pub fn parse(text: &str) -> Result<View, RenderError> {
        let bad = |reason: String| RenderError::View {
            text: text.to_owned(),
            reason,
        };
        let t = text.trim();
        let named = match t.to_ascii_lowercase().as_str() {
            "iso" | "isometric" => Some(View::Iso),
            "front" => Some(View::Front),
            "back" => Some(View::Back),
            "left" => Some(View::Left),
            "right" => Some(View::Right),
            "top" => Some(View::Top),
            "bottom" => Some(View::Bottom),
            _ => None,
        };
        if let Some(v) = named {
            return Ok(v);
        }
        if !t.contains(',') {
            return Err(bad("not a view name".into()));
        }
        let parts: Vec<&str> = t.split(',').map(str::trim).collect();
        if parts.len() != 3 {
            return Err(bad(format!(
                "a direction needs 3 numbers, not {}",
                parts.len()
            )));
        }
        let mut xyz = [0.0; 3];
        for (slot, p) in xyz.iter_mut().zip(&parts) {
            *slot = p
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(format!("{p:?} is not a finite number")))?;
        }
        let d = DVec3::from(xyz);
        if unit(d).is_none() {
            return Err(bad("the direction is zero".into()));
        }
        Ok(View::Direction(d))
    }

    /// The unit direction from the model toward the camera, in world
    /// coordinates.
    pub fn direction(&self, up: Up) -> Result<DVec3, RenderError> {
        let canonical = match *self {
            View::Iso => DVec3::new(1.0, -0.8, 1.2),
            View::Front => DVec3::NEG_Y,
            View::Back => DVec3::Y,
            View::Left => DVec3::NEG_X,
            View::Right => DVec3::X,
            View::Top => DVec3::Z,
            View::Bottom => DVec3::NEG_Z,
            View::Direction(d) => {
                return unit(d).ok_or_else(|| RenderError::View {
                    text: format!("{},{},{}", d.x, d.y, d.z),
                    reason: "the direction is zero or not finite".into(),
                });
            }
        };
        Ok(up.from_z_up(canonical).normalize())
    }
}

impl std::str::FromStr for View {
    type Err = RenderError;

    /// Same as [`View::parse`].
    fn from_str(s: &str) -> Result<View, RenderError> {
        View::parse(s)
    }
}

/// Which world axis points up in the pictures.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Up {
    /// +z is up (holey's primitives, CAD, the thesis's figures).
    #[default]
    Z,
    /// +y is up (most OBJ exports, OpenGL scenes).
    Y,
}

impl Up {
    /// Parses `z`, `+z`, `y` or `+y` (any case).
    pub fn parse(text: &str) -> Result<Up, RenderError> {
        match text.trim().to_ascii_lowercase().as_str() {
            "z" | "+z" => Ok(Up::Z),
            "y" | "+y" => Ok(Up::Y),
            _ => Err(RenderError::Up {
                text: text.to_owned(),
            }),
        }
    }

    /// Maps a direction of the canonical z-up frame into this frame:
    /// identity for z-up, (x, y, z) ↦ (x, z, −y) for y-up (a rotation, so
    /// handedness is kept).
    pub fn from_z_up(self, v: DVec3) -> DVec3 {
        match self {
            Up::Z => v,
            Up::Y => DVec3::new(v.x, v.z, -v.y),
        }
    }

    /// The world up axis.
    pub fn axis(self) -> DVec3 {
        self.from_z_up(DVec3::Z)
    }
}

impl std::str::FromStr for Up {
    type Err = RenderError;

    /// Same as [`Up::parse`].
    fn from_str(s: &str) -> Result<Up, RenderError> {
        Up::parse(s)
    }
}

/// A perspective camera in world coordinates, as [`frame`] computes it or
/// as a caller fixes it (e.g. the same camera for every frame of an
/// animation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The centre of projection.
    pub eye: DVec3,
    /// A point on the optical axis in front of the eye.
    pub target: DVec3,
    /// Approximate screen-up direction (not parallel to the axis).
    pub up: DVec3,
    /// Field of view across the shorter picture side, in degrees, in
    /// (0, 179].
    pub fov: f64,
    /// Lens shift: where the optical axis meets the picture, in units of
    /// half the shorter side, measured from the centre (+x right, +y up).
    /// A shifted lens keeps the perspective but recentres the picture.
    pub shift: DVec2,
}

impl Camera {
    /// Where the world point `p` appears in a `width` × `height` picture
    /// taken with this camera: pixel coordinates with x to the right and y
    /// down, pixel (i, j) covering [i, i + 1) × [j, j + 1). `None` when `p`
    /// is not in front of the eye or the camera is degenerate.
    pub fn project(&self, p: DVec3, width: u32, height: u32) -> Option<DVec2> {
        let fwd = unit(self.target - self.eye)?;
        let (right, up, fwd) = basis(fwd, self.up)?;
        let v = p - self.eye;
        let z = v.dot(fwd);
        if z.is_nan() || z <= 0.0 {
            return None;
        }
        let t = (self.fov.to_radians() / 2.0).tan();
        let u = DVec2::new(v.dot(right), v.dot(up)) / (z * t) - self.shift;
        let short = f64::from(width.min(height)) / 2.0;
        let px = DVec2::new(
            f64::from(width) / 2.0 + u.x * short,
            f64::from(height) / 2.0 - u.y * short,
        );
        px.is_finite().then_some(px)
    }
}

/// How the camera is placed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Framing {
    /// The camera stands where the bounding sphere fills [`FILL`] of the
    /// shorter side; then zoom and lens shift make the projected vertices
    /// fill [`FILL`] of the picture, centred. The tightest, best-looking
    /// framing; it changes when the model changes.
    #[default]
    Fit,
    /// Only the bounding sphere: stable under small changes of the model.
    Sphere,
    /// This camera.
    Fixed(Camera),
}

/// The camera [`crate::render`] would use for `mesh` and `opts` (for
/// [`Framing::Fixed`], that camera after checking it). Freeze it with
/// [`Framing::Fixed`] to render a changing model from a steady viewpoint.
pub fn frame(
    mesh: &holey_mesh::PolyMesh,
    opts: &crate::RenderOptions,
) -> Result<Camera, RenderError> {
    opts.validate()?;
    let prep = crate::prep::Prepared::new(mesh, false, 180.0)?;
    let proj = Projector::new(&prep, opts, 1)?;
    Ok(proj.world_camera(&prep))
}

/// The camera in the prepared mesh's normalized coordinates, with the
/// picture geometry: maps points to sample coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Projector {
    pub eye: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub fwd: DVec3,
    /// tan(fov/2) on the shorter side.
    pub tan_half: f64,
    pub shift: DVec2,
    /// Pixels per unit of the image plane at unit distance.
    pub scale: f64,
    /// Sample coordinates of the image-plane origin.
    pub cx: f64,
    pub cy: f64,
    /// Near clipping distance (normalized units).
    pub near: f64,
    /// Picture size in samples.
    pub width: f64,
    pub height: f64,
}

/// A point in view space: x right, y up, z the depth in front of the eye.
pub(crate) type ViewPoint = DVec3;

impl Projector {
    /// Sets up the camera for the prepared mesh, in a sample grid of
    /// `ss` samples per pixel side.
    pub fn new(
        prep: &crate::prep::Prepared,
        opts: &crate::RenderOptions,
        ss: u32,
    ) -> Result<Projector, RenderError> {
        let width = f64::from(opts.width) * f64::from(ss);
        let height = f64::from(opts.height) * f64::from(ss);
        match opts.framing {
            Framing::Fixed(cam) => Self::fixed(prep, &cam, width, height),
            framing => {
                let d = opts.view.direction(opts.up)?;
                let (right, up, fwd) = basis(-d, screen_up(d, opts.up)).ok_or_else(|| {
                    RenderError::Camera("the view direction is degenerate".into())
                })?;
                // The tangent cone from distance D to the unit sphere has
                // half-angle α with sin α = 1/D; its image radius is tan α at
                // unit focal distance, which should be FILL·tan(fov/2).
                let t0 = (opts.fov.to_radians() / 2.0).tan();
                let alpha = (FILL * t0).atan();
                let dist = 1.0 / alpha.sin();
                let mut p =
                    Self::unframed(d * dist, (right, up, fwd), t0, DVec2::ZERO, width, height);
                if framing == Framing::Fit {
                    p.fit(prep, width / height);
                }
                p.finish();
                Ok(p)
            }
        }
    }

    fn fixed(
        prep: &crate::prep::Prepared,
        cam: &Camera,
        width: f64,
        height: f64,
    ) -> Result<Projector, RenderError> {
        let bad = |m: &str| RenderError::Camera(m.to_owned());
        if !(cam.eye.is_finite() && cam.target.is_finite() && cam.up.is_finite()) {
            return Err(bad("eye, target and up must be finite"));
        }
        if !(cam.fov.is_finite() && cam.fov > 0.0 && cam.fov <= 179.0) {
            return Err(bad("fov must be in (0, 179] degrees"));
        }
        if !cam.shift.is_finite() || cam.shift.abs().max_element() > 1e6 {
            return Err(bad("shift must be finite and moderate"));
        }
        let eye = prep.to_normalized(cam.eye);
        let target = prep.to_normalized(cam.target);
        if !(eye.is_finite() && target.is_finite()) {
            return Err(bad("eye or target is too far from the model"));
        }
        let fwd = unit(target - eye).ok_or_else(|| bad("eye and target coincide"))?;
        let (right, up, fwd) =
            basis(fwd, cam.up).ok_or_else(|| bad("up is parallel to the line of sight"))?;
        let tan_half = (cam.fov.to_radians() / 2.0).tan();
        let mut p = Self::unframed(eye, (right, up, fwd), tan_half, cam.shift, width, height);
        p.finish();
        Ok(p)
    }

    /// Zoom and lens shift so the projected drawable vertices fill FILL of
    /// the picture, centred. Image-plane coordinates u = x/(z·t) are
    /// measured in half shorter sides; the picture spans ±aspect (or ±1)
    /// in them.
    fn fit(&mut self, prep: &crate::prep::Prepared, aspect: f64) {
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for (q, &used) in prep.q.iter().zip(&prep.used) {
            if !used {
                continue;
            }
            let v = self.view(*q);
            if v.z <= self.near {
                continue;
            }
            let u = DVec2::new(v.x, v.y) / (v.z * self.tan_half);
            lo = lo.min(u);
            hi = hi.max(u);
        }
        let half_extent = if aspect >= 1.0 {
            DVec2::new(aspect, 1.0)
        } else {
            DVec2::new(1.0, 1.0 / aspect)
        };
        let k = ((hi - lo) / 2.0 / (FILL * half_extent)).max_element();
        // k ≈ 1 for a sphere; tiny or non-finite when nothing (or a
        // single point) is visible, where the sphere framing is kept.
        if k.is_finite() && k > 1e-6 {
            self.tan_half *= k;
            self.shift = (lo + hi) / 2.0 / k;
        }
    }

    /// A camera at `eye` with the axes (right, up, forward), before its
    /// framing: [`Projector::finish`] sets the scale and the image origin.
    fn unframed(
        eye: DVec3,
        (right, up, fwd): (DVec3, DVec3, DVec3),
        tan_half: f64,
        shift: DVec2,
        width: f64,
        height: f64,
    ) -> Projector {
        Projector {
            eye,
            right,
            up,
            fwd,
            tan_half,
            shift,
            scale: 0.0,
            cx: 0.0,
            cy: 0.0,
            near: 1e-3,
            width,
            height,
        }
    }

    fn finish(&mut self) {
        let short = self.width.min(self.height);
        self.scale = short / 2.0 / self.tan_half;
        self.cx = self.width / 2.0 - self.shift.x * short / 2.0;
        self.cy = self.height / 2.0 + self.shift.y * short / 2.0;
    }

    /// Normalized world point → view space.
    #[inline]
    pub fn view(&self, q: DVec3) -> ViewPoint {
        let v = q - self.eye;
        DVec3::new(v.dot(self.right), v.dot(self.up), v.dot(self.fwd))
    }

    /// View space (z ≥ near) → sample coordinates (x right, y down) and
    /// w = 1/z.
    #[inline]
    pub fn project(&self, v: ViewPoint) -> SVert {
        let w = 1.0 / v.z;
        SVert {
            x: self.cx + self.scale * v.x * w,
            y: self.cy - self.scale * v.y * w,
            w,
        }
    }

    /// Normalized world direction → eye space (x right, y up, z toward
    /// the viewer), for lighting.
    #[inline]
    pub fn to_eye(&self, n: DVec3) -> DVec3 {
        DVec3::new(n.dot(self.right), n.dot(self.up), -n.dot(self.fwd))
    }

    /// The size in normalized units of one sample at the distance of the
    /// model's centre: the scale of depth tolerances.
    pub fn sample_size(&self) -> f64 {
        let dist = (-self.eye).dot(self.fwd).abs().max(self.near);
        dist / self.scale
    }

    /// This camera in world coordinates.
    pub fn world_camera(&self, prep: &crate::prep::Prepared) -> Camera {
        let dist = (-self.eye).dot(self.fwd).abs().max(1.0);
        Camera {
            eye: prep.to_world(self.eye),
            target: prep.to_world(self.eye + self.fwd * dist),
            up: self.up,
            fov: 2.0 * self.tan_half.atan().to_degrees(),
            shift: self.shift,
        }
    }
}

/// The screen-up hint for a camera at direction `d` (model → eye): the
/// world up axis, or when looking along it the world's back (+y z-up) from
/// above and front from below, so +x stays to the right.
fn screen_up(d: DVec3, up: Up) -> DVec3 {
    let axis = up.axis();
    let c = d.dot(axis);
    if c.abs() > 0.999 {
        up.from_z_up(if c > 0.0 { DVec3::Y } else { DVec3::NEG_Y })
    } else {
        axis
    }
}

/// Right-handed orthonormal camera basis (right, up, forward) from a
/// forward direction and an up hint, or `None` when they are parallel.
fn basis(fwd: DVec3, up_hint: DVec3) -> Option<(DVec3, DVec3, DVec3)> {
    let fwd = unit(fwd)?;
    let right = unit(fwd.cross(up_hint))?;
    if right.cross(fwd).dot(up_hint) <= 0.0 {
        return None;
    }
    Some((right, right.cross(fwd), fwd))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_names_and_directions() {
        assert_eq!(View::parse("ISO").unwrap(), View::Iso);
        assert_eq!(View::parse(" top ").unwrap(), View::Top);
        assert_eq!(View::parse("bottom").unwrap(), View::Bottom);
        assert_eq!(
            View::parse("1, 2 ,-3.5").unwrap(),
            View::Direction(DVec3::new(1.0, 2.0, -3.5))
        );
        for bad in [
            "", "sideways", "1,2", "1,2,3,4", "0,0,0", "1,nan,2", "1,inf,0", "a,b,c",
        ] {
            let e = View::parse(bad).unwrap_err();
            assert!(matches!(e, RenderError::View { .. }), "{bad:?}: {e}");
            assert!(e.to_string().contains("expected iso"), "{e}");
        }
        assert!(View::Direction(DVec3::ZERO).direction(Up::Z).is_err());
        assert!(
            View::Direction(DVec3::new(f64::NAN, 0.0, 1.0))
                .direction(Up::Z)
                .is_err()
        );
    }

    #[test]
    fn parse_up() {
        assert_eq!("y".parse::<Up>().unwrap(), Up::Y);
        assert_eq!("front".parse::<View>().unwrap(), View::Front);
        assert_eq!(Up::parse("Z").unwrap(), Up::Z);
        assert_eq!(Up::parse("+y").unwrap(), Up::Y);
        assert!(Up::parse("x").is_err());
    }

    #[test]
    fn named_views_are_rotated_for_y_up() {
        assert_eq!(View::Front.direction(Up::Z).unwrap(), DVec3::NEG_Y);
        assert_eq!(View::Front.direction(Up::Y).unwrap(), DVec3::Z);
        assert_eq!(View::Top.direction(Up::Y).unwrap(), DVec3::Y);
        assert_eq!(View::Right.direction(Up::Y).unwrap(), DVec3::X);
        let iso = View::Iso.direction(Up::Y).unwrap();
        assert!(iso.y > 0.0 && iso.z > 0.0 && iso.x > 0.0);
    }

    /// +x is on the right in every axis view where it is not the line of
    /// sight, and the up axis is up wherever it is not the line of sight.
    #[test]
    fn screen_axes() {
        for up in [Up::Z, Up::Y] {
            for view in [View::Front, View::Top, View::Bottom, View::Back, View::Iso] {
                let d = view.direction(up).unwrap();
                let (right, scr_up, fwd) = basis(-d, screen_up(d, up)).unwrap();
                // Right-handed: right × up = −forward (toward the viewer).
                assert!((right.cross(scr_up) + fwd).length() < 1e-12);
                if view == View::Back {
                    assert!(right.x < -0.99, "{view:?} {up:?}");
                } else {
                    assert!(right.x > 0.6, "{view:?} {up:?}: {right}");
                }
                if matches!(view, View::Front | View::Back) {
                    assert!(scr_up.dot(up.axis()) > 0.999);
                }
            }
        }
    }
}
