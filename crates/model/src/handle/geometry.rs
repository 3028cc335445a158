//! The geometry of a curved handle: the Hermite curve of eq. 4.1, its
//! cubic Bézier variant, the rotations of §IV.3, and the polar face
//! morphing of §IV.3.1.
//!
//! Nothing here touches a mesh; [`super::plan_handle`] feeds it the
//! positions of the two end faces.

use std::f64::consts::{PI, TAU};

use glam::{DQuat, DVec3};

/// `1 + a·b` below this counts as antipodal: the rotation axis `a × b` is
/// then too short to trust, and the caller's hint axis is used instead.
const ANTIPODAL: f64 = 1e-12;

/// The Hermite basis `[h1, h2, h3, h4]` of eq. 4.1 at `t`:
/// `h1 = 2t³ − 3t² + 1`, `h2 = −2t³ + 3t²`, `h3 = t³ − 2t² + t`,
/// `h4 = t³ − t²`. `h1`, `h2` weigh the end points, `h3`, `h4` the end
/// tangents.
pub fn hermite_basis(t: f64) -> [f64; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [
        2.0 * t3 - 3.0 * t2 + 1.0,
        -2.0 * t3 + 3.0 * t2,
        t3 - 2.0 * t2 + t,
        t3 - t2,
    ]
}

/// The derivatives of [`hermite_basis`]: `[6t² − 6t, −6t² + 6t,
/// 3t² − 4t + 1, 3t² − 2t]`.
pub fn hermite_basis_derivative(t: f64) -> [f64; 4] {
    let t2 = t * t;
    [
        6.0 * t2 - 6.0 * t,
        -6.0 * t2 + 6.0 * t,
        3.0 * t2 - 4.0 * t + 1.0,
        3.0 * t2 - 2.0 * t,
    ]
}

/// The path of a handle (§IV.2, eq. 4.1):
///
/// `H(t) = p1·h1(t) + p2·h2(t) + w1·n1·h3(t) − w2·n2·h4(t)`, `t ∈ [0, 1]`,
///
/// with `p1`, `p2` the centroids and `n1`, `n2` the unit normals of the
/// two faces. It leaves `p1` with velocity `w1·n1` (along the first
/// face's normal when `w1 > 0`) and reaches `p2` with velocity `−w2·n2`
/// (into the second face). Negative weights point the ends into the
/// surface, which makes a tunnel (a hole) instead of a handle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HermiteCurve {
    /// `H(0)`: the centroid of the first face, where the curve starts.
    pub p1: DVec3,
    /// `H(1)`: the centroid of the second face, where the curve ends.
    pub p2: DVec3,
    /// `w1·n1`: the velocity at `t = 0`.
    pub start_velocity: DVec3,
    /// `−w2·n2`: the velocity at `t = 1`.
    pub end_velocity: DVec3,
}

impl HermiteCurve {
    /// The curve of eq. 4.1 from the faces' centroids, unit normals and the weights.
    pub fn new(p1: DVec3, n1: DVec3, w1: f64, p2: DVec3, n2: DVec3, w2: f64) -> Self {
        HermiteCurve {
            p1,
            p2,
            start_velocity: n1 * w1,
            end_velocity: -(n2 * w2),
        }
    }

    /// `H(t)`.
    pub fn point(&self, t: f64) -> DVec3 {
        let [h1, h2, h3, h4] = hermite_basis(t);
        self.p1 * h1 + self.p2 * h2 + self.start_velocity * h3 + self.end_velocity * h4
    }

    /// `H′(t)`, the (unnormalised) tangent.
    pub fn velocity(&self, t: f64) -> DVec3 {
        let [d1, d2, d3, d4] = hermite_basis_derivative(t);
        self.p1 * d1 + self.p2 * d2 + self.start_velocity * d3 + self.end_velocity * d4
    }

    /// A length that sets the curve's scale, for relative tolerances.
    pub(crate) fn scale(&self) -> f64 {
        (self.p2 - self.p1).length() + self.start_velocity.length() + self.end_velocity.length()
    }

    /// The unit tangent at `t`, for a curve sampled every `step`. Where
    /// `H′(t)` vanishes (a cusp, which strong or opposed weights can make)
    /// the direction of the chord between the neighbouring samples
    /// `H(t ± step)` is used, and failing that `fallback`, so the result
    /// is always a finite unit vector.
    pub fn unit_tangent(&self, t: f64, step: f64, fallback: DVec3) -> DVec3 {
        HandlePath::Hermite(*self).unit_tangent(t, step, fallback)
    }
}

/// The cubic Bernstein basis `[(1 − t)³, 3t(1 − t)², 3t²(1 − t), t³]`.
pub fn bernstein_basis(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// The Bézier variant of a handle's path (TopMod's Bézier handle; the
/// thesis, §IV.2, defines only the Hermite curve of eq. 4.1):
///
/// `B(t) = (1 − t)³·P0 + 3t(1 − t)²·P1 + 3t²(1 − t)·P2 + t³·P3`, `t ∈ [0, 1]`,
///
/// with `P0 = p1`, `P1 = p1 + w1·n1`, `P2 = p2 + w2·n2`, `P3 = p2`:
/// `p1`, `p2` the faces' centroids and `n1`, `n2` their unit (outward)
/// normals, so each inner control point stands at distance `|w|` above
/// its face. The curve leaves `p1` with velocity `3·w1·n1` and reaches
/// `p2` with velocity `−3·w2·n2`, so it is the curve of eq. 4.1 with both
/// weights tripled: the weight here is a distance along the normal (where
/// the control point sits), there a speed. It stays inside the convex
/// hull of its four control points, which the Hermite form does not
/// show. Negative weights put the control points inside the surface: a
/// tunnel, as for eq. 4.1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BezierCurve {
    /// The control points `[P0, P1, P2, P3]`.
    pub control: [DVec3; 4],
}

impl BezierCurve {
    /// The curve from the faces' centroids, unit normals and the weights.
    pub fn new(p1: DVec3, n1: DVec3, w1: f64, p2: DVec3, n2: DVec3, w2: f64) -> Self {
        BezierCurve {
            control: [p1, p1 + n1 * w1, p2 + n2 * w2, p2],
        }
    }

    /// `B(t)`.
    pub fn point(&self, t: f64) -> DVec3 {
        let [b0, b1, b2, b3] = bernstein_basis(t);
        let [p0, p1, p2, p3] = self.control;
        p0 * b0 + p1 * b1 + p2 * b2 + p3 * b3
    }

    /// `B′(t) = 3(1 − t)²·(P1 − P0) + 6t(1 − t)·(P2 − P1) + 3t²·(P3 − P2)`.
    pub fn velocity(&self, t: f64) -> DVec3 {
        let s = 1.0 - t;
        let [p0, p1, p2, p3] = self.control;
        (p1 - p0) * (3.0 * s * s) + (p2 - p1) * (6.0 * t * s) + (p3 - p2) * (3.0 * t * t)
    }

    /// A length that sets the curve's scale: its control polygon's length.
    pub(crate) fn scale(&self) -> f64 {
        let [p0, p1, p2, p3] = self.control;
        p0.distance(p1) + p1.distance(p2) + p2.distance(p3)
    }

    /// The unit tangent at `t`, as [`HermiteCurve::unit_tangent`]: never
    /// NaN, also at cusps.
    pub fn unit_tangent(&self, t: f64, step: f64, fallback: DVec3) -> DVec3 {
        HandlePath::Bezier(*self).unit_tangent(t, step, fallback)
    }
}

/// The centre curve a handle follows: eq. 4.1 or its Bézier variant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HandlePath {
    /// The thesis's Hermite curve (eq. 4.1).
    Hermite(HermiteCurve),
    /// The cubic Bézier variant.
    Bezier(BezierCurve),
}

impl HandlePath {
    /// The point at `t`: `H(t)` or `B(t)`.
    pub fn point(&self, t: f64) -> DVec3 {
        match self {
            HandlePath::Hermite(c) => c.point(t),
            HandlePath::Bezier(c) => c.point(t),
        }
    }

    /// The (unnormalised) tangent at `t`.
    pub fn velocity(&self, t: f64) -> DVec3 {
        match self {
            HandlePath::Hermite(c) => c.velocity(t),
            HandlePath::Bezier(c) => c.velocity(t),
        }
    }

    /// The unit tangent at `t`, for a curve sampled every `step`, never NaN
    /// (see [`HermiteCurve::unit_tangent`]): `H′(t)` normalised, or where
    /// it vanishes (relative to the curve's scale) the chord between the
    /// neighbouring samples, or where that vanishes too (relative to the
    /// scale and the samples' size) `fallback`. Both curves' own
    /// `unit_tangent` come here.
    pub fn unit_tangent(&self, t: f64, step: f64, fallback: DVec3) -> DVec3 {
        let scale = match self {
            HandlePath::Hermite(c) => c.scale(),
            HandlePath::Bezier(c) => c.scale(),
        };
        let v = self.velocity(t);
        if v.length() > 1e-12 * scale {
            return v.normalize();
        }
        // Points carry rounding relative to their size, not the curve's.
        let (ahead, behind) = (
            self.point((t + step).min(1.0)),
            self.point((t - step).max(0.0)),
        );
        let chord = ahead - behind;
        if chord.length() > 1e-12 * (scale + ahead.length().max(behind.length())) {
            return chord.normalize();
        }
        fallback
    }
}

/// The centroid (vertex average) of a polygon, the `p` of eq. 4.1.
pub fn centroid(points: &[DVec3]) -> DVec3 {
    if points.is_empty() {
        return DVec3::ZERO;
    }
    points.iter().copied().sum::<DVec3>() / points.len() as f64
}

/// The vector area of a polygon (Newell's method, taken about the
/// centroid): its direction is the polygon's average normal and its
/// length the area of a planar polygon. It is the robust "average unit
/// normal" of a face once normalised, also for non-planar faces.
pub fn vector_area(points: &[DVec3]) -> DVec3 {
    let c = centroid(points);
    let n = points.len();
    let mut sum = DVec3::ZERO;
    for i in 0..n {
        sum += (points[i] - c).cross(points[(i + 1) % n] - c);
    }
    sum * 0.5
}

/// A unit vector perpendicular to unit `axis`: `hint` with its component
/// along `axis` removed, or any perpendicular when `hint` is (nearly)
/// parallel to `axis`.
pub(crate) fn perpendicular(axis: DVec3, hint: DVec3) -> DVec3 {
    let h = hint - axis * hint.dot(axis);
    let len = h.length();
    if len > 1e-9 * hint.length().max(f64::MIN_POSITIVE) && len.is_finite() && len > 0.0 {
        h / len
    } else {
        axis.any_orthonormal_vector()
    }
}

/// The shortest-arc rotation taking unit `from` to unit `to`, about the
/// axis `from × to` (§IV.3). When the two are opposite the axis vanishes
/// and any perpendicular axis would do; the thesis leaves that case out.
/// Here (and when `1 + from·to < 10⁻¹²`, where the axis is too short to
/// trust) the rotation is a half turn about `hint` made perpendicular to
/// `from`, followed by the small arc from `−from` to `to`: callers choose
/// the solution, it still maps `from` exactly onto `to`, and nothing
/// degenerates to NaN.
pub fn rotation_between(from: DVec3, to: DVec3, hint: DVec3) -> DQuat {
    let d = from.dot(to);
    if d <= -1.0 + ANTIPODAL {
        // A half turn to −from, then the (well-conditioned) small arc to `to`.
        let half = DQuat::from_axis_angle(perpendicular(from, hint), PI);
        return arc(-from, to) * half;
    }
    arc(from, to)
}

/// The shortest-arc rotation for `from·to > −1`: the quaternion
/// `(from × to, 1 + from·to)`, normalised, turns by the angle between
/// them about their common normal.
fn arc(from: DVec3, to: DVec3) -> DQuat {
    let c = from.cross(to);
    DQuat::from_xyzw(c.x, c.y, c.z, 1.0 + from.dot(to)).normalize()
}

/// Polar coordinates `(r, θ)` of planar points about the origin in the
/// axes `x`, `y` (§IV.3.1), with the angles unwrapped to increase
/// monotonically along the face: each `θ_j` is the first angle at or
/// above `θ_(j−1)` that names the point's direction. A point at the
/// origin gets the angle of its predecessor.
pub fn polar(points: &[DVec3], x: DVec3, y: DVec3) -> (Vec<f64>, Vec<f64>) {
    let mut r = Vec::with_capacity(points.len());
    let mut theta: Vec<f64> = Vec::with_capacity(points.len());
    for p in points {
        let (px, py) = (p.dot(x), p.dot(y));
        let len = px.hypot(py);
        let raw = py.atan2(px);
        let angle = match theta.last() {
            None => raw,
            Some(&prev) if len == 0.0 => prev,
            Some(&prev) => prev + (raw - prev).rem_euclid(TAU),
        };
        r.push(len);
        theta.push(angle);
    }
    (r, theta)
}

/// The two end faces resolved in a common reference plane, ready to be
/// interpolated (§IV.3–IV.3.1).
#[derive(Clone, Debug)]
pub(crate) struct Morph {
    /// The reference axes: `x`, `y` span the plane; `u = x × y` is the
    /// normal both resolved faces turn towards.
    pub(crate) x: DVec3,
    pub(crate) y: DVec3,
    pub(crate) u: DVec3,
    r1: Vec<f64>,
    theta1: Vec<f64>,
    r2: Vec<f64>,
    theta2: Vec<f64>,
}

impl Morph {
    /// Resolves face `a` (unit normal `n1`) and face `b` (already read in
    /// the matching order, unit normal `nb`) into polar coordinates about
    /// their centroids in the plane through the origin with unit normal
    /// `u`.
    ///
    /// Each face is rotated about its centroid so that its normal becomes
    /// `u`, then flattened onto the plane. The X axis points at the
    /// midpoint of `a`'s last edge (from its last vertex back to its
    /// first), Y = `u` × X. The angles of each face increase
    /// monotonically, and `b`'s are shifted by whole turns so that the
    /// first vertices differ by at most half a turn — more would twist the
    /// handle about its axis.
    pub(crate) fn new(a: &[DVec3], n1: DVec3, b: &[DVec3], nb: DVec3, u: DVec3) -> Morph {
        let n = a.len();
        let (p1, p2) = (centroid(a), centroid(b));
        let last_mid_a = (a[n - 1] + a[0]) * 0.5 - p1;
        let flatten = |q: DQuat, p: DVec3, c: DVec3| {
            let v = q * (p - c);
            v - u * v.dot(u)
        };
        let q1 = rotation_between(n1, u, last_mid_a);
        let fa: Vec<DVec3> = a.iter().map(|&p| flatten(q1, p, p1)).collect();
        let mid = (fa[n - 1] + fa[0]) * 0.5;
        // A last edge through the centroid (possible for non-star faces)
        // has no midpoint direction: use the first vertex's instead, and
        // failing that any direction in the plane.
        let x = if mid.length() > 1e-12 * fa[0].length().max(fa[n - 1].length()) {
            perpendicular(u, mid)
        } else {
            perpendicular(u, fa[0])
        };
        let y = u.cross(x);
        // The second face: a half turn, if it needs one, about X too.
        let q2 = rotation_between(nb, u, x);
        let fb: Vec<DVec3> = b.iter().map(|&p| flatten(q2, p, p2)).collect();
        let (r1, theta1) = polar(&fa, x, y);
        let (r2, mut theta2) = polar(&fb, x, y);
        let turns = ((theta2[0] - theta1[0]) / TAU).round();
        if turns != 0.0 {
            for t in &mut theta2 {
                *t -= turns * TAU;
            }
        }
        Morph {
            x,
            y,
            u,
            r1,
            theta1,
            r2,
            theta2,
        }
    }

    /// The interpolated face `f(t)` of eqs. 4.3–4.4, in the reference
    /// plane, with its centroid moved to the origin:
    ///
    /// `r′_j = (1 − t)·r1_j + t·r2_j`, `θ′_j = (1 − t)·θ1_j + t·θ2_j`.
    ///
    /// (The thesis prints `r′ = (1 − t)·r1 + t·r1`, a typo: the radius
    /// interpolates from the first face to the second like the angle.)
    /// Interpolating polar coordinates keeps a star-shaped pair of faces
    /// free of self-intersections. The interpolated polygon's vertex
    /// average is generally not the origin, so it is re-centred: the
    /// section's centroid then lies exactly on the curve.
    pub(crate) fn at(&self, t: f64) -> Vec<DVec3> {
        let pts: Vec<DVec3> = (0..self.r1.len())
            .map(|j| {
                let r = (1.0 - t) * self.r1[j] + t * self.r2[j];
                let th = (1.0 - t) * self.theta1[j] + t * self.theta2[j];
                let (s, c) = th.sin_cos();
                self.x * (r * c) + self.y * (r * s)
            })
            .collect();
        let c = centroid(&pts);
        pts.into_iter().map(|p| p - c).collect()
    }

    /// The angles of the first face, for tests.
    #[cfg(test)]
    pub(crate) fn angles(&self) -> (&[f64], &[f64]) {
        (&self.theta1, &self.theta2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
        (a - b).length() <= tol
    }

    #[test]
    fn basis_interpolates_ends_and_tangents() {
        assert_eq!(hermite_basis(0.0), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(hermite_basis(1.0), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(hermite_basis_derivative(0.0), [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(hermite_basis_derivative(1.0), [0.0, 0.0, 0.0, 1.0]);
        // h1 + h2 = 1: the curve is affine-invariant.
        for k in 0..=10 {
            let [h1, h2, _, _] = hermite_basis(k as f64 / 10.0);
            assert!((h1 + h2 - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn curve_ends_and_derivative_match_finite_differences() {
        let c = HermiteCurve::new(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::Z,
            2.0,
            DVec3::new(3.0, 0.0, 1.0),
            DVec3::Z,
            1.5,
        );
        assert_eq!(c.point(0.0), c.p1);
        assert_eq!(c.point(1.0), c.p2);
        assert!(close(c.velocity(0.0), DVec3::Z * 2.0, 1e-15));
        assert!(close(c.velocity(1.0), DVec3::NEG_Z * 1.5, 1e-15));
        for k in 1..10 {
            let t = k as f64 / 10.0;
            let h = 1e-6;
            let fd = (c.point(t + h) - c.point(t - h)) / (2.0 * h);
            assert!(close(fd, c.velocity(t), 1e-8), "t={t}");
        }
    }

    #[test]
    fn unit_tangent_survives_a_cusp() {
        // Straight up, back down through p1 and up again: H′ vanishes twice.
        let c = HermiteCurve::new(DVec3::Z, DVec3::Z, 1.0, DVec3::NEG_Z, DVec3::NEG_Z, 1.0);
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            let u = c.unit_tangent(t, 1e-3, DVec3::X);
            assert!(u.is_finite() && (u.length() - 1.0).abs() < 1e-12, "t={t}");
        }
        // An all-zero curve falls back.
        let z = HermiteCurve::new(DVec3::ONE, DVec3::Z, 0.0, DVec3::ONE, DVec3::Z, 0.0);
        assert_eq!(z.unit_tangent(0.5, 0.1, DVec3::Y), DVec3::Y);
    }

    #[test]
    fn bezier_interpolates_its_ends_and_is_hermite_with_tripled_weights() {
        let (p1, n1, p2, n2) = (
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::Z,
            DVec3::new(3.0, 1.0, 1.0),
            DVec3::new(0.0, 0.6, 0.8),
        );
        let b = BezierCurve::new(p1, n1, 2.0, p2, n2, -0.5);
        let h = HermiteCurve::new(p1, n1, 6.0, p2, n2, -1.5);
        assert_eq!(b.point(0.0), p1);
        assert_eq!(b.point(1.0), p2);
        assert!(close(b.velocity(0.0), n1 * 6.0, 1e-14));
        assert!(close(b.velocity(1.0), n2 * 1.5, 1e-14));
        // De Casteljau at ½ by hand: (P0 + 3·P1 + 3·P2 + P3) / 8.
        let [c0, c1, c2, c3] = b.control;
        assert!(close(
            b.point(0.5),
            (c0 + c1 * 3.0 + c2 * 3.0 + c3) / 8.0,
            1e-14
        ));
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            assert!(close(b.point(t), h.point(t), 1e-13), "t={t}");
            assert!(close(b.velocity(t), h.velocity(t), 1e-13), "t={t}");
            let s: f64 = bernstein_basis(t).iter().sum();
            assert!((s - 1.0).abs() < 1e-15);
        }
        // A degenerate curve (all control points equal) falls back.
        let z = BezierCurve::new(DVec3::ONE, DVec3::Z, 0.0, DVec3::ONE, DVec3::Z, 0.0);
        assert_eq!(z.unit_tangent(0.5, 0.1, DVec3::Y), DVec3::Y);
        let path = HandlePath::Bezier(b);
        assert_eq!(path.point(0.3), b.point(0.3));
        assert_eq!(path.velocity(0.3), b.velocity(0.3));
    }

    #[test]
    fn rotation_maps_from_to_to_and_handles_antipodes() {
        let pairs = [
            (DVec3::Z, DVec3::X),
            (DVec3::Z, DVec3::new(1.0, 2.0, -3.0).normalize()),
            (DVec3::X, DVec3::X),
        ];
        for (a, b) in pairs {
            let q = rotation_between(a, b, DVec3::Y);
            assert!(close(q * a, b, 1e-14));
        }
        // Opposite: a half turn about the hint, made perpendicular.
        let q = rotation_between(DVec3::Z, DVec3::NEG_Z, DVec3::new(1.0, 0.0, 0.7));
        assert!(close(q * DVec3::Z, DVec3::NEG_Z, 1e-14));
        assert!(
            close(q * DVec3::X, DVec3::X, 1e-14),
            "the hint axis is fixed"
        );
        assert!(close(q * DVec3::Y, DVec3::NEG_Y, 1e-14));
        // A hint along the axis itself still gives a valid half turn.
        let q = rotation_between(DVec3::Z, DVec3::NEG_Z, DVec3::Z);
        let v = q * DVec3::Z;
        assert!(v.is_finite() && close(v, DVec3::NEG_Z, 1e-14));
        // Nearly opposite stays finite and accurate.
        let b = DVec3::new(1e-7, 0.0, -1.0).normalize();
        let q = rotation_between(DVec3::Z, b, DVec3::Y);
        assert!(close(q * DVec3::Z, b, 1e-9));
    }

    #[test]
    fn polar_angles_increase_monotonically() {
        // A square starting at angle 135°: raw atan2 wraps at 180°.
        let sq = [
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        let (r, th) = polar(&sq, DVec3::X, DVec3::Y);
        for v in &r {
            assert!((v - 2f64.sqrt()).abs() < 1e-15);
        }
        let want = [0.75, 1.25, 1.75, 2.25].map(|q| q * PI);
        for (a, b) in th.iter().zip(want) {
            assert!((a - b).abs() < 1e-14, "{th:?}");
        }
        // A point at the origin keeps the previous angle (no NaN).
        let (_, th) = polar(&[DVec3::X, DVec3::ZERO, DVec3::Y], DVec3::X, DVec3::Y);
        assert_eq!(th, vec![0.0, 0.0, PI / 2.0]);
    }

    #[test]
    fn morph_reproduces_the_end_faces_and_limits_the_twist() {
        // A square in z = 0 facing +z and the same square rotated by 300°
        // in z = 5 read the other way (facing −z, so `b` faces +z).
        let sq: Vec<DVec3> = (0..4)
            .map(|j| {
                let a = PI / 4.0 + j as f64 * PI / 2.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let rot = DQuat::from_rotation_z(300f64.to_radians());
        let b: Vec<DVec3> = sq.iter().map(|&p| rot * p + DVec3::Z * 5.0).collect();
        let m = Morph::new(&sq, DVec3::Z, &b, DVec3::Z, DVec3::Z);
        let f0 = m.at(0.0);
        for (p, q) in f0.iter().zip(&sq) {
            assert!(close(*p, *q, 1e-14));
        }
        let f1 = m.at(1.0);
        for (p, q) in f1.iter().zip(&b) {
            assert!(close(*p, *q - DVec3::Z * 5.0, 1e-14));
        }
        let (t1, t2) = m.angles();
        // 300° is the same direction as −60°: the first angles differ by 60°.
        assert!((t2[0] - t1[0] + PI / 3.0).abs() < 1e-12, "{t1:?} {t2:?}");
        // Halfway the section is turned by −30°.
        let half = m.at(0.5);
        let want = DQuat::from_rotation_z(-PI / 6.0) * sq[0];
        assert!(close(half[0], want, 1e-12));
    }
}
