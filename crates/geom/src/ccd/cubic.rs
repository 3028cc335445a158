//! Floating-point vertex–triangle continuous collision detection, as in the
//! paper (appendix A).
//!
//! A point `p(t)` and a triangle `a(t), b(t), c(t)`, each moving linearly
//! from its position at `t = 0` to its position at `t = 1`, are coplanar
//! exactly when the triple product
//!
//! ```text
//!   f(t) = det[ A(t); B(t); C(t) ],   A(t) = (1−t)(a₀−p₀) + t(a₁−p₁), …
//! ```
//!
//! vanishes. With `A(t) = A₀ + t·dA` (and likewise `B`, `C`) it is the cubic
//! `f(t) = k₀ + k₁t + k₂t² + k₃t³` with
//!
//! ```text
//!   k₀ = [A₀ B₀ C₀]
//!   k₁ = [dA B₀ C₀] + [A₀ dB C₀] + [A₀ B₀ dC]
//!   k₂ = [A₀ dB dC] + [dA B₀ dC] + [dA dB C₀]
//!   k₃ = [dA dB dC]
//! ```
//!
//! Roots are found by interval search: `[0, 1]` is split at the critical
//! points of `f` (roots of `f'`), on each monotone piece a sign change is
//! bisected to full precision, and each root is kept if the point lies in
//! the triangle at that time (barycentric coordinates of the projection
//! onto the triangle's plane, all `≥ 0`). **Time convention**: roots in the
//! half-open interval `[0, 1)` count, so that a contact exactly at a frame
//! boundary is counted once when frames are chained (in the frame it
//! starts). Plain floating point: grazing contacts and coplanar motions
//! (`f ≡ 0`: no isolated roots, reported as none) can be misjudged; the
//! exact parity of [`super::parity`] is the robust alternative.

use glam::DVec3;

/// Collisions found by [`collisions_float`]: count and times (ascending).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FloatCollisions {
    /// Number of collisions found, 0 to 3.
    pub count: u8,
    /// Collision times in `[0, 1)`, ascending; only the first `count` entries
    /// hold times (the rest are 0).
    pub times: [f64; 3],
}

#[inline]
fn det(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    a.dot(b.cross(c))
}

/// Coefficients `[k₀, k₁, k₂, k₃]` of the coplanarity cubic.
pub fn coplanarity_cubic(p: [DVec3; 2], a: [DVec3; 2], b: [DVec3; 2], c: [DVec3; 2]) -> [f64; 4] {
    let a0 = a[0] - p[0];
    let b0 = b[0] - p[0];
    let c0 = c[0] - p[0];
    let da = (a[1] - p[1]) - a0;
    let db = (b[1] - p[1]) - b0;
    let dc = (c[1] - p[1]) - c0;
    [
        det(a0, b0, c0),
        det(da, b0, c0) + det(a0, db, c0) + det(a0, b0, dc),
        det(a0, db, dc) + det(da, b0, dc) + det(da, db, c0),
        det(da, db, dc),
    ]
}

#[inline]
fn eval(k: &[f64; 4], t: f64) -> f64 {
    ((k[3] * t + k[2]) * t + k[1]) * t + k[0]
}

/// Roots of the cubic in `[0, 1)` by interval search.
pub fn cubic_roots_01(k: &[f64; 4]) -> ([f64; 3], usize) {
    // Critical points: 3k₃t² + 2k₂t + k₁ = 0.
    let mut cuts = [0.0f64, 1.0, 1.0, 1.0];
    let mut nc = 1;
    let (qa, qb, qc) = (3.0 * k[3], 2.0 * k[2], k[1]);
    let push = |t: f64, cuts: &mut [f64; 4], nc: &mut usize| {
        if t > 0.0 && t < 1.0 {
            cuts[*nc] = t;
            *nc += 1;
        }
    };
    if qa != 0.0 {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let s = disc.sqrt();
            // Numerically stable pair.
            let q = -0.5 * (qb + qb.signum() * s);
            if q != 0.0 {
                push(q / qa, &mut cuts, &mut nc);
                push(qc / q, &mut cuts, &mut nc);
            } else {
                push(0.0, &mut cuts, &mut nc);
            }
        }
    } else if qb != 0.0 {
        push(-qc / qb, &mut cuts, &mut nc);
    }
    cuts[nc] = 1.0;
    nc += 1;
    cuts[..nc].sort_by(f64::total_cmp);
    let mut roots = [0.0; 3];
    let mut nr = 0;
    for w in 0..nc - 1 {
        let (mut lo, mut hi) = (cuts[w], cuts[w + 1]);
        if hi <= lo {
            continue;
        }
        let (flo, fhi) = (eval(k, lo), eval(k, hi));
        if flo == 0.0 {
            // A root at a cut point; count it once (from the piece it
            // starts). Skip if it equals the previous root.
            if (nr == 0 || roots[nr - 1] != lo) && nr < 3 {
                roots[nr] = lo;
                nr += 1;
            }
            continue;
        }
        if fhi == 0.0 || (flo < 0.0) == (fhi < 0.0) {
            // A root at `hi` is found by the next piece (or excluded at 1).
            continue;
        }
        let neg_lo = flo < 0.0;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            let fm = eval(k, mid);
            if fm == 0.0 {
                lo = mid;
                hi = mid;
                break;
            }
            if (fm < 0.0) == neg_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        if nr < 3 {
            roots[nr] = 0.5 * (lo + hi);
            nr += 1;
        }
    }
    (roots, nr)
}

/// Barycentric containment of `p` in triangle `abc` (projection onto the
/// triangle's plane): all weights `≥ 0`.
pub fn inside_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> bool {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let d00 = v0.dot(v0);
    let d01 = v0.dot(v1);
    let d11 = v1.dot(v1);
    let d20 = v2.dot(v0);
    let d21 = v2.dot(v1);
    let den = d00 * d11 - d01 * d01;
    if den <= 0.0 {
        return false;
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    v >= 0.0 && w >= 0.0 && v + w <= 1.0
}

/// The paper's floating-point test: collisions of the moving point `p`
/// with the moving triangle `abc` for `t ∈ [0, 1)`.
pub fn collisions_float(
    p: [DVec3; 2],
    a: [DVec3; 2],
    b: [DVec3; 2],
    c: [DVec3; 2],
) -> FloatCollisions {
    let k = coplanarity_cubic(p, a, b, c);
    let (roots, nr) = cubic_roots_01(&k);
    let mut out = FloatCollisions::default();
    let lerp = |x: [DVec3; 2], t: f64| x[0] + (x[1] - x[0]) * t;
    for &t in &roots[..nr] {
        if inside_triangle(lerp(p, t), lerp(a, t), lerp(b, t), lerp(c, t)) {
            out.times[out.count as usize] = t;
            out.count += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_falling_through_a_static_triangle() {
        let a = [DVec3::new(0.0, 0.0, 0.0); 2];
        let b = [DVec3::new(1.0, 0.0, 0.0); 2];
        let c = [DVec3::new(0.0, 1.0, 0.0); 2];
        let p = [DVec3::new(0.25, 0.25, 1.0), DVec3::new(0.25, 0.25, -3.0)];
        let r = collisions_float(p, a, b, c);
        assert_eq!(r.count, 1);
        assert_eq!(r.times[0], 0.25);
        // Missing the triangle.
        let p = [DVec3::new(2.0, 2.0, 1.0), DVec3::new(2.0, 2.0, -1.0)];
        assert_eq!(collisions_float(p, a, b, c).count, 0);
        // Contact exactly at t = 1 is not counted; at t = 0 it is.
        let p = [DVec3::new(0.25, 0.25, 1.0), DVec3::new(0.25, 0.25, 0.0)];
        assert_eq!(collisions_float(p, a, b, c).count, 0);
        let p = [DVec3::new(0.25, 0.25, 0.0), DVec3::new(0.25, 0.25, -1.0)];
        assert_eq!(collisions_float(p, a, b, c).count, 1);
    }

    #[test]
    fn three_roots_of_a_rotating_triangle() {
        // A cubic with three roots in (0, 1): check the root finder alone.
        let k = [-0.006, 0.11, -0.6, 1.0]; // (t-0.1)(t-0.2)(t-0.3)
        let (r, n) = cubic_roots_01(&k);
        assert_eq!(n, 3);
        for (got, want) in r.iter().zip([0.1, 0.2, 0.3]) {
            assert!((got - want).abs() < 1e-12);
        }
    }
}
