//! A floating-point filter in front of the exact collision parity, for
//! pairs whose triangle moves nearly rigidly.
//!
//! In the frame that moves with the triangle's first corner (subtracting
//! `t·D` from every point at time `t`, which changes no contact), the
//! triangle stays within `δ` of its start position `T₀` for the whole
//! frame, where `δ` is the largest difference between a corner's
//! displacement and `D`, and the vertex moves along a straight segment `S`.
//! The parity of the number of hits can change, as the triangle deforms
//! from the rigid surrogate to the true one, only if at some moment the
//! vertex touches the triangle's boundary, or the vertex is on the
//! triangle at `t = 0` or `t = 1`. So if `S` stays farther than `δ` from
//! the three edges of `T₀` and both ends of `S` are farther than `δ` from
//! `T₀`, the parity is that of `S` crossing `T₀`, which those margins make
//! a well-conditioned floating-point question. Margins include a
//! scale-relative allowance for rounding far above the error of the
//! distance computations; anything closer goes to the exact test.

use glam::DVec3;

use crate::distance::point_segment_distance;

/// Rounding allowance, times the scale of the coordinates involved.
const ROUNDING: f64 = 1e-9;

/// `Some(odd)` when the filter decides, `None` when the exact test must.
/// `p` is the vertex's start and end, `c` the corners' starts and ends.
pub fn rigid_filter(p: [DVec3; 2], c: [[DVec3; 2]; 3]) -> Option<bool> {
    let d = c[0][1] - c[0][0];
    let delta = (1..3)
        .map(|i| ((c[i][1] - c[i][0]) - d).length())
        .fold(0.0f64, f64::max);
    let t0 = [c[0][0], c[1][0], c[2][0]];
    let (s0, s1) = (p[0], p[1] - d);
    let scale = [s0, s1, t0[0], t0[1], t0[2], d]
        .iter()
        .fold(0.0f64, |m, q| m.max(q.abs().max_element()));
    let margin = delta + ROUNDING * scale;
    if !margin.is_finite() {
        return None;
    }
    if point_triangle_distance(s0, t0) <= margin || point_triangle_distance(s1, t0) <= margin {
        return None;
    }
    for k in 0..3 {
        if segment_distance(s0, s1, t0[k], t0[(k + 1) % 3]) <= margin {
            return None;
        }
    }
    // Clear of the boundary: the crossing test is decided by plane sides
    // and the crossing point's barycentric signs, none near zero.
    let n = (t0[1] - t0[0]).cross(t0[2] - t0[0]);
    let (h0, h1) = ((s0 - t0[0]).dot(n), (s1 - t0[0]).dot(n));
    if (h0 > 0.0) == (h1 > 0.0) {
        return Some(false);
    }
    let x = s0 + (s1 - s0) * (h0 / (h0 - h1));
    let inside = (0..3).all(|k| {
        let (a, b) = (t0[k], t0[(k + 1) % 3]);
        (b - a).cross(x - a).dot(n) > 0.0
    });
    Some(inside)
}

/// Distance from `p` to the triangle `t`.
fn point_triangle_distance(p: DVec3, t: [DVec3; 3]) -> f64 {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let nn = n.length_squared();
    if nn > 0.0 {
        let inside = (0..3).all(|k| (t[(k + 1) % 3] - t[k]).cross(p - t[k]).dot(n) >= 0.0);
        if inside {
            return ((p - t[0]).dot(n)).abs() / nn.sqrt();
        }
    }
    (0..3)
        .map(|k| point_segment_distance(p, t[k], t[(k + 1) % 3]))
        .fold(f64::INFINITY, f64::min)
}

/// Distance between the segments `[p0, p1]` and `[q0, q1]`: the minimum
/// over the clamped closest points of the two lines and the four
/// endpoint-to-segment distances, so near-parallel segments are handled by
/// the endpoint terms.
fn segment_distance(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> f64 {
    let mut best = point_segment_distance(p0, q0, q1)
        .min(point_segment_distance(p1, q0, q1))
        .min(point_segment_distance(q0, p0, p1))
        .min(point_segment_distance(q1, p0, p1));
    let (u, v, w) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, b, c, d, e) = (u.dot(u), u.dot(v), v.dot(v), u.dot(w), v.dot(w));
    let den = a * c - b * b;
    if den > 1e-12 * a * c {
        let s = (b * e - c * d) / den;
        let t = (a * e - b * d) / den;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            best = best.min(((p0 + u * s) - (q0 + v * t)).length());
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ccd::parity::CcdParity;
    use crate::ccd::{MovingPoint, vertex_triangle_parity};
    use crate::sos::SymPoint;
    use holey_testkit::Rng;

    /// Whenever the filter decides, it agrees with the exact test: random
    /// near-rigid motions, many of them grazing.
    #[test]
    fn agrees_with_the_exact_parity() {
        let mut rng = Rng::new(11);
        let (mut decided, mut odd) = (0, 0);
        for _ in 0..20_000 {
            let mut r = || {
                DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                )
            };
            let d = r() * 2.0;
            let wobble = 10f64.powi(-(1 + (r().x.abs() * 6.0) as i32));
            let c: [[DVec3; 2]; 3] = std::array::from_fn(|_| {
                let s = r();
                [s, s + d + r() * wobble]
            });
            let p0 = r();
            let p = [p0, p0 + r() * 2.0];
            let mp = |q: [DVec3; 2], id: u32| MovingPoint {
                start: SymPoint::new(q[0], 2 * id),
                end: SymPoint::new(q[1], 2 * id + 1),
            };
            let exact = vertex_triangle_parity(mp(p, 0), mp(c[0], 1), mp(c[1], 2), mp(c[2], 3));
            if let Some(f) = rigid_filter(p, c) {
                decided += 1;
                odd += f as u32;
                assert_eq!(f, exact == CcdParity::Odd, "p {p:?} c {c:?}");
            }
        }
        assert!(decided > 10_000 && odd > 500, "decided {decided} odd {odd}");
    }
}
