//! Consistent constructions: coordinates of intersection points, rounded
//! once.
//!
//! Every constructed quantity is a ratio `N/D` of two polynomials in the
//! input coordinates (formulas in [`crate::intersect`]). Both are evaluated
//! exactly as expansions and the quotient is **correctly rounded** (round
//! to nearest, ties to even): the only error is the final rounding, at most
//! half an ulp of the result. Consequently the same point computed from the
//! same inputs is always the same double, whichever triangle asks, and a
//! coordinate that is exactly representable (e.g. an intersection landing on
//! a lattice point) comes out exact.
//!
//! Rounding: with `q₀ ≈ N/D` from the expansions' estimates, the sign of the
//! exact residual `N − q·D` says on which side of `q` the exact quotient
//! lies; stepping `q` one ulp at a time (usually zero or one step) brackets
//! it between two adjacent doubles `q_lo < N/D < q_hi`, and the sign of `N −
//! m·D` at their midpoint `m` (exact as a two-component expansion) picks the
//! nearer one.
//!
//! **Perturbed limits.** When `D` is exactly zero but the point exists in
//! the perturbed world (e.g. an edge lying in the plane of a triangle that it
//! crosses after perturbation), the constructed point is the limit as
//! ε → 0 of the perturbed point: with `m` the smallest monomial of the
//! perturbed `D` (as in [`crate::sos`]), the limit of `N/D` is the ratio of
//! the coefficients of `m` in `N` and `D` (the limit is finite because the
//! perturbed point lies on a bounded segment or triangle, so `N` has no
//! smaller monomial). All coordinates of one point share `D`, hence `m`, so
//! limits stay consistent with each other.
//!
//! Inputs are scaled by a power of two first (as in [`crate::sos`]) and the
//! result scaled back, both exact, so any input magnitude works.

use crate::dd::{Dd, certified_div};
use crate::error::{GeomError, NonFinite};
use crate::expansion::{Expansion, pow2};
use crate::ring::{Ring, V3, cross, dot, normal, orient3, scale3, sub3};
use crate::sos::{EpsPoly, Mono, Poly, Ranks, SymPoint, scale_exponent, scaled_by};
use glam::DVec3;

/// The correctly rounded quotient of two exact values (`d ≠ 0`).
pub fn div_round(n: &Expansion, d: &Expansion) -> f64 {
    let ds = d.sign();
    if n.is_zero() || ds == 0 {
        return 0.0;
    }
    // side(q) = sign(N/D − q).
    let side = |q: f64| -> i8 { n.sub(&d.scale(q)).sign() * ds };
    let mut q = n.estimate() / d.estimate();
    if !q.is_finite() {
        q = 0.0;
    }
    let mut s = side(q);
    if s == 0 {
        return q;
    }
    let (lo, hi);
    // Walk towards the exact value until it is bracketed.
    let mut steps = 0;
    loop {
        let next = if s > 0 { q.next_up() } else { q.next_down() };
        let sn = side(next);
        if sn == 0 {
            return next;
        }
        if sn != s {
            (lo, hi) = if s > 0 { (q, next) } else { (next, q) };
            break;
        }
        q = next;
        s = sn;
        steps += 1;
        if steps > 64 {
            // Only reachable if the estimate were far off; fall back to a
            // bisection on the bit patterns would be needed. Estimates of
            // nonoverlapping expansions are within a few ulps, so this is a
            // guard, not a path.
            return q;
        }
    }
    // Midpoint of two adjacent doubles, exactly.
    let half = (hi - lo) * 0.5;
    let mid = Expansion::from_f64(lo).add(&Expansion::from_f64(half));
    let sm = n.sub(&d.mul(&mid)).sign() * ds;
    // Nearer neighbour; on a tie, the one with an even last mantissa bit.
    if sm > 0 || (sm == 0 && lo.to_bits() & 1 == 1) {
        hi
    } else {
        lo
    }
}

/// The points scaled by `2^-k` (largest coordinate in `[1, 2)`) as exact
/// expansions, and `k`.
fn scaled_expansions(pts: &[SymPoint]) -> (Vec<V3<Expansion>>, i32) {
    let k = scale_exponent(pts.iter().map(|p| &p.pos));
    (scaled_by(pts, pow2(-k)), k)
}

/// Several polynomials evaluated together, sharing what they have in
/// common: the numerators of one constructed point's coordinates.
trait Polys {
    fn eval_all<T: Ring>(&self, p: &[V3<T>]) -> Vec<T>;
}

/// Evaluates every `num/den` of `nums` at the points, correctly rounded,
/// taking the perturbed limit when `den` vanishes exactly. `degree[i]`
/// is `deg(numᵢ) − deg(den)` (to undo the input scaling).
///
/// The numerators of one point share their denominator, so its lowest
/// monomial in the perturbed world is searched for once for all of them
/// (one call per coordinate searched it again each time: on the
/// coplanar overlaps of an OpenSCAD export the search was a quarter of
/// `holey selfint`).
fn ratios<N: Polys, D: Poly>(
    nums: &N,
    den: &D,
    pts: &[SymPoint],
    degree: &[i32],
) -> Result<Vec<f64>, GeomError> {
    let (ex, k) = scaled_expansions(pts);
    let s = pow2(-k);
    let d = den.eval(&ex);
    let q = if !d.is_zero() {
        nums.eval_all(&ex)
            .iter()
            .map(|n| div_round(n, &d))
            .collect()
    } else {
        limit_ratios(nums, den, pts, s)?
    };
    Ok(q.iter()
        .zip(degree)
        .map(|(q, &g)| q * pow2(k * g))
        .collect())
}

/// The perturbed limits of `nums/den` where `den` vanishes exactly: the
/// coefficients of the denominator's lowest monomial (see
/// [`crate::sos`]) in each numerator and in the denominator, divided.
/// The numerators are evaluated only up to that monomial (the
/// [`EpsPoly`] cap): nothing above it bears on the limit.
fn limit_ratios<N: Polys, D: Poly>(
    nums: &N,
    den: &D,
    pts: &[SymPoint],
    s: f64,
) -> Result<Vec<f64>, GeomError> {
    let (ep, d) = lowest_level(den, pts, s)?;
    let Some((lowest, _)) = d.lowest() else {
        return Err(GeomError::Degenerate(
            "the denominator vanishes identically in the perturbed world",
        ));
    };
    let ep = capped(ep, lowest);
    nums.eval_all(&ep).iter().map(|n| limit_of(n, &d)).collect()
}

/// The points `ep` with every coordinate capped at `cap` (see
/// [`EpsPoly`]).
fn capped(ep: Vec<V3<EpsPoly>>, cap: Mono) -> Vec<V3<EpsPoly>> {
    ep.into_iter().map(|p| p.map(|c| c.capped(cap))).collect()
}

/// The points (scaled by `s`) as polynomials in the first `L`
/// perturbation variables, for the first `L` of [`crate::sos::levels`]
/// at which `den` is not the zero polynomial, and `den` there. Its lowest
/// monomial is then the lowest of the whole perturbed polynomial (every
/// monomial in a later variable is larger), and so is every other
/// polynomial's below it.
fn lowest_level<D: Poly>(
    den: &D,
    pts: &[SymPoint],
    s: f64,
) -> Result<(Vec<V3<EpsPoly>>, EpsPoly), GeomError> {
    let ranks = Ranks::of(pts);
    for level in crate::sos::levels(ranks.nvars) {
        let ep = ranks.at_level(pts, s, level);
        let d = den.eval(&ep);
        if !d.is_empty() {
            return Ok((ep, d));
        }
    }
    Err(GeomError::Degenerate(
        "the denominator vanishes identically in the perturbed world",
    ))
}

/// The limit of `n/d` as ε → 0⁺, both restricted to the same variables
/// with `d` not zero there: `n`'s coefficient of `d`'s lowest monomial
/// over `d`'s; infinite (an error) when `n` has a lower monomial.
fn limit_of(n: &EpsPoly, d: &EpsPoly) -> Result<f64, GeomError> {
    let Some((m, dc)) = d.lowest() else {
        return Err(GeomError::Degenerate(
            "the denominator vanishes identically in the perturbed world",
        ));
    };
    if n.lowest().is_some_and(|(mn, _)| mn < m) {
        return Err(GeomError::Degenerate(
            "the perturbed point goes to infinity (parallel planes)",
        ));
    }
    Ok(div_round(&n.coefficient(m), dc))
}

/// Where segment `pq` crosses the plane of triangle `abc`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeTrianglePoint {
    /// Parameter along the segment: point = `p + t (q − p)`.
    pub t: f64,
    /// Coordinates.
    pub pos: DVec3,
    /// Barycentric coordinates in triangle `abc` (weights of `a, b, c`).
    pub bary: [f64; 3],
}

// Point layout for edge × triangle: [p, q, a, b, c].
fn et_h<T: Ring>(p: &[V3<T>]) -> (T, T) {
    let hp = orient3(&p[2], &p[3], &p[4], &p[0]);
    let hq = orient3(&p[2], &p[3], &p[4], &p[1]);
    (hp, hq)
}

struct EtDen;
impl Poly for EtDen {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        let (hp, hq) = et_h(p);
        hp.sub(&hq)
    }
}
/// The edge parameter's numerator and the three coordinates' (over
/// [`EtDen`]): `h_p` and `h_p q_j − h_q p_j`.
struct EtNums;
impl Polys for EtNums {
    fn eval_all<T: Ring>(&self, p: &[V3<T>]) -> Vec<T> {
        let (hp, hq) = et_h(p);
        let pos = |j: usize| hp.mul(&p[1][j]).sub(&hq.mul(&p[0][j]));
        vec![hp.clone(), pos(0), pos(1), pos(2)]
    }
}
/// Barycentric numerators `V(p,q,b,c), V(p,q,c,a), V(p,q,a,b)`.
struct EtBary(usize);
impl Poly for EtBary {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        let (a, b, c) = (&p[2], &p[3], &p[4]);
        let (u, v) = match self.0 {
            0 => (b, c),
            1 => (c, a),
            _ => (a, b),
        };
        orient3(&p[0], &p[1], u, v)
    }
}
/// The three barycentric numerators together.
struct EtBarys;
impl Polys for EtBarys {
    fn eval_all<T: Ring>(&self, p: &[V3<T>]) -> Vec<T> {
        (0..3).map(|i| EtBary(i).eval(p)).collect()
    }
}
/// The barycentric denominator as the sum of the numerators: `−EtDen`
/// as a polynomial, which [`edge_triangle_limit`] uses in its place; the
/// tests check the identity and compare against it.
#[cfg(test)]
struct EtBaryDen;
#[cfg(test)]
impl Poly for EtBaryDen {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        EtBary(0)
            .eval(p)
            .add(&EtBary(1).eval(p))
            .add(&EtBary(2).eval(p))
    }
}

/// The point where segment `pq` crosses the plane of `abc`, with its
/// parameter on the segment and its barycentric coordinates in `abc`, each
/// correctly rounded from exact values (see the module docs). Errors when
/// the point does not exist even in the perturbed world (e.g. the segment
/// shares identities with the triangle so that it lies in its plane) or a
/// coordinate is not finite.
pub fn edge_triangle_point(
    p: SymPoint,
    q: SymPoint,
    a: SymPoint,
    b: SymPoint,
    c: SymPoint,
) -> Result<EdgeTrianglePoint, GeomError> {
    construct(
        &[p, q, a, b, c],
        edge_triangle_point_dd,
        edge_triangle_point_exact,
    )
}

/// The way both constructions answer: refuse a non-finite point, take the
/// double-double path when it certifies every quotient (bit-identical to
/// the exact answer and far cheaper), and evaluate exactly otherwise.
fn construct<const N: usize, R>(
    pts: &[SymPoint; N],
    dd: fn(&[SymPoint; N]) -> Option<R>,
    exact: fn(&[SymPoint; N]) -> Result<R, GeomError>,
) -> Result<R, GeomError> {
    check_finite(pts)?;
    if let Some(point) = dd(pts) {
        return Ok(point);
    }
    exact(pts)
}

/// The polynomials of an edge × triangle point, evaluated at the scaled
/// points `[p, q, a, b, c]` in any ring, so that the exact and the
/// double-double paths divide the very same numerators.
struct EtTerms<T> {
    /// The heights of `p` and `q` over `abc`.
    hp: T,
    hq: T,
    /// `hp − hq`: the denominator of `t` and of the position.
    den: T,
    /// Barycentric numerators `V(p,q,b,c), V(p,q,c,a), V(p,q,a,b)`.
    bary: [T; 3],
    /// Their sum, the barycentric denominator.
    bary_sum: T,
}

impl<T: Ring> EtTerms<T> {
    fn new(ex: &[V3<T>]) -> Self {
        let o = |i: usize, j: usize, l: usize, m: usize| orient3(&ex[i], &ex[j], &ex[l], &ex[m]);
        let (hp, hq) = (o(2, 3, 4, 0), o(2, 3, 4, 1));
        let den = hp.sub(&hq);
        let bary = [o(0, 1, 3, 4), o(0, 1, 4, 2), o(0, 1, 2, 3)];
        let bary_sum = bary[0].add(&bary[1]).add(&bary[2]);
        EtTerms {
            hp,
            hq,
            den,
            bary,
            bary_sum,
        }
    }

    /// The numerator of coordinate `j` of the position, `hp·q − hq·p`.
    fn pos(&self, ex: &[V3<T>], j: usize) -> T {
        self.hp.mul(&ex[1][j]).sub(&self.hq.mul(&ex[0][j]))
    }
}

/// [`edge_triangle_point`] by exact expansions only.
fn edge_triangle_point_exact(pts: &[SymPoint; 5]) -> Result<EdgeTrianglePoint, GeomError> {
    // Every polynomial evaluated once, exactly.
    let (ex, k) = scaled_expansions(pts);
    let et = EtTerms::new(&ex);
    if !et.den.is_zero() && !et.bary_sum.is_zero() {
        let back = pow2(k);
        let pos: [f64; 3] = std::array::from_fn(|j| div_round(&et.pos(&ex, j), &et.den) * back);
        return Ok(EdgeTrianglePoint {
            t: div_round(&et.hp, &et.den),
            pos: DVec3::from_array(pos),
            bary: std::array::from_fn(|i| div_round(&et.bary[i], &et.bary_sum)),
        });
    }
    // The point exists only as a perturbed limit.
    edge_triangle_limit(pts, k)
}

/// [`edge_triangle_point`] as a perturbed limit, where `h_p − h_q`
/// vanishes exactly (the points scaled by `2^-k`).
///
/// The barycentric denominator `V(p,q,b,c) + V(p,q,c,a) + V(p,q,a,b)` is
/// `−(h_p − h_q)` as a polynomial (the tetrahedra that `pq` makes with the
/// triangle's three sides add up to the difference of the two heights;
/// [`EtBaryDen`]), so it vanishes with it, at every level of the
/// perturbed stage, and one search for the lowest monomial serves both
/// quotients (each searched for its own, half the time of `holey selfint`
/// on an OpenSCAD export's coplanar overlaps was these searches).
fn edge_triangle_limit(pts: &[SymPoint; 5], k: i32) -> Result<EdgeTrianglePoint, GeomError> {
    let (ep, den) = lowest_level(&EtDen, pts, pow2(-k))?;
    let Some((lowest, _)) = den.lowest() else {
        return Err(GeomError::Degenerate(
            "the denominator vanishes identically in the perturbed world",
        ));
    };
    let ep = capped(ep, lowest);
    let nums = EtNums.eval_all(&ep);
    let back = pow2(k);
    let mut pos = [0.0; 3];
    for (x, n) in pos.iter_mut().zip(&nums[1..]) {
        *x = limit_of(n, &den)? * back;
    }
    let bary_den = den.neg();
    let mut bary = [0.0; 3];
    for (x, n) in bary.iter_mut().zip(&EtBarys.eval_all(&ep)) {
        *x = limit_of(n, &bary_den)?;
    }
    Ok(EdgeTrianglePoint {
        t: limit_of(&nums[0], &den)?,
        pos: DVec3::from_array(pos),
        bary,
    })
}

/// Homogeneous intersection `(X_h, w)` of the planes of three triangles
/// given as nine points: planes `n_i·x = d_i` (`n_i = (b_i−a_i)×(c_i−a_i)`,
/// `d_i = n_i·a_i`), `X_h = d_1 (n_2×n_3) + d_2 (n_3×n_1) + d_3 (n_1×n_2)`,
/// `w = det[n_1; n_2; n_3]` (dotting `X_h` with `n_1` leaves `d_1 w`).
fn triple_h<T: Ring>(p: &[V3<T>]) -> (V3<T>, T) {
    let plane = |a: &V3<T>, b: &V3<T>, c: &V3<T>| {
        let n = normal(a, b, c);
        let d = dot(&n, a);
        (n, d)
    };
    let (n1, d1) = plane(&p[0], &p[1], &p[2]);
    let (n2, d2) = plane(&p[3], &p[4], &p[5]);
    let (n3, d3) = plane(&p[6], &p[7], &p[8]);
    let c23 = cross(&n2, &n3);
    let c31 = cross(&n3, &n1);
    let c12 = cross(&n1, &n2);
    let w = dot(&n1, &c23);
    let xh = [0, 1, 2].map(|k| d1.mul(&c23[k]).add(&d2.mul(&c31[k])).add(&d3.mul(&c12[k])));
    (xh, w)
}

/// `((v−u)×(X_h − w·u))·n` for the directed edge `u→v` of a triangle with
/// normal `n`: `w·|n|²` times the barycentric weight of the corner opposite
/// that edge.
fn edge_side<T: Ring>(u: &V3<T>, v: &V3<T>, n: &V3<T>, xh: &V3<T>, w: &T) -> T {
    let rel = sub3(xh, &scale3(w, u));
    dot(&cross(&sub3(v, u), &rel), n)
}

/// The common point of the planes of three triangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriplePoint {
    /// The point's coordinates, each correctly rounded from its exact value.
    pub pos: DVec3,
    /// `bary[i]` = barycentric coordinates in triangle `i` (weights of its
    /// corners in the order given).
    pub bary: [[f64; 3]; 3],
}

struct TpW;
impl Poly for TpW {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        triple_h(p).1
    }
}
/// The homogeneous coordinates `X_h` (over [`TpW`]).
struct TpPositions;
impl Polys for TpPositions {
    fn eval_all<T: Ring>(&self, p: &[V3<T>]) -> Vec<T> {
        triple_h(p).0.to_vec()
    }
}
/// The barycentric weights' numerators of the corners of triangle `.0`
/// ([`tp_bary_terms`]).
struct TpBarys(usize);
impl Polys for TpBarys {
    fn eval_all<T: Ring>(&self, p: &[V3<T>]) -> Vec<T> {
        let (xh, w) = triple_h(p);
        tp_bary_terms(p, &xh, &w, self.0).0.to_vec()
    }
}
struct TpBaryDen(usize);
impl Poly for TpBaryDen {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        let t = &p[3 * self.0..3 * self.0 + 3];
        let n = normal(&t[0], &t[1], &t[2]);
        triple_h(p).1.mul(&dot(&n, &n))
    }
}

/// The common point of the planes of three triangles and its barycentric
/// coordinates in each of them, correctly rounded from exact values.
pub fn triple_point(
    t1: [SymPoint; 3],
    t2: [SymPoint; 3],
    t3: [SymPoint; 3],
) -> Result<TriplePoint, GeomError> {
    let pts = [
        t1[0], t1[1], t1[2], t2[0], t2[1], t2[2], t3[0], t3[1], t3[2],
    ];
    construct(&pts, triple_point_dd, triple_point_exact)
}

/// The barycentric coordinates of the triple point `X_h / w` in triangle
/// `tri` of the scaled points, as numerators (one per corner, from the
/// opposite edge) over their common denominator `w·|n|²`; shared by the
/// exact and the double-double paths.
fn tp_bary_terms<T: Ring>(ex: &[V3<T>], xh: &V3<T>, w: &T, tri: usize) -> ([T; 3], T) {
    let t = &ex[3 * tri..3 * tri + 3];
    let n = normal(&t[0], &t[1], &t[2]);
    let den = w.mul(&dot(&n, &n));
    let num = std::array::from_fn(|corner| {
        edge_side(&t[(corner + 1) % 3], &t[(corner + 2) % 3], &n, xh, w)
    });
    (num, den)
}

/// [`triple_point`] by exact expansions only.
fn triple_point_exact(pts: &[SymPoint; 9]) -> Result<TriplePoint, GeomError> {
    // Every polynomial evaluated once, exactly.
    let (ex, k) = scaled_expansions(pts);
    let (xh, w) = triple_h(&ex);
    if !w.is_zero() {
        let back = pow2(k);
        let mut bary = [[0.0; 3]; 3];
        let mut ok = true;
        for (tri, b) in bary.iter_mut().enumerate() {
            let (num, den) = tp_bary_terms(&ex, &xh, &w, tri);
            if den.is_zero() {
                ok = false;
                break;
            }
            for (x, n) in b.iter_mut().zip(&num) {
                *x = div_round(n, &den);
            }
        }
        if ok {
            let pos: [f64; 3] = std::array::from_fn(|j| div_round(&xh[j], &w) * back);
            return Ok(TriplePoint {
                pos: DVec3::from_array(pos),
                bary,
            });
        }
    }
    // The point exists only as a perturbed limit (or not at all).
    if w.is_zero()
        && let Some(point) = triple_point_limit(pts, k)?
    {
        return Ok(point);
    }
    let x = ratios(&TpPositions, &TpW, pts, &[1, 1, 1])?;
    let mut bary = [[0.0; 3]; 3];
    for (tri, b) in bary.iter_mut().enumerate() {
        let w = ratios(&TpBarys(tri), &TpBaryDen(tri), pts, &[0, 0, 0])?;
        b.copy_from_slice(&w);
    }
    Ok(TriplePoint {
        pos: DVec3::new(x[0], x[1], x[2]),
        bary,
    })
}

/// The triple point as a perturbed limit where `w` vanishes exactly
/// (the points scaled by `2^-k`): `w`'s lowest perturbed monomial is
/// searched for once, and at its level `X_h` and every triangle's
/// barycentric numerators and denominator (`w |n|²`) are evaluated
/// together, sharing `X_h` and `w` (a search per triangle, each
/// evaluating them again, was most of `holey selfint` on coplanar
/// overlaps). `None` when a barycentric denominator is still zero at that
/// level (a triangle of no area), for the search per triangle to decide.
fn triple_point_limit(pts: &[SymPoint; 9], k: i32) -> Result<Option<TriplePoint>, GeomError> {
    let (ep, w) = lowest_level(&TpW, pts, pow2(-k))?;
    // Every denominator below is `w` or `w |n|²`; their lowest monomials
    // are `w`'s times `|n|²`'s (a product's lowest term is its factors'
    // lowest terms' product), so nothing above the largest of them bears
    // on a limit, and the evaluation keeps only what is below (the
    // [`EpsPoly`] cap).
    let Some((mut cap, _)) = w.lowest() else {
        return Ok(None);
    };
    let mut norms = Mono::default();
    for t in ep.chunks_exact(3) {
        let n = normal(&t[0], &t[1], &t[2]);
        let Some((m, _)) = dot(&n, &n).lowest() else {
            return Ok(None);
        };
        norms = norms.max(m);
    }
    cap = cap.mul(norms);
    let ep = capped(ep, cap);
    let (xh, w) = triple_h(&ep);
    let back = pow2(k);
    let mut pos = [0.0; 3];
    for (x, h) in pos.iter_mut().zip(&xh) {
        *x = limit_of(h, &w)? * back;
    }
    let mut bary = [[0.0; 3]; 3];
    for (tri, b) in bary.iter_mut().enumerate() {
        // `den` is `w |n|²`, not zero: its lowest term is at or below
        // the cap.
        let (num, den) = tp_bary_terms(&ep, &xh, &w, tri);
        for (x, n) in b.iter_mut().zip(&num) {
            *x = limit_of(n, &den)?;
        }
    }
    Ok(Some(TriplePoint {
        pos: DVec3::from_array(pos),
        bary,
    }))
}

/// The points scaled as [`scaled_expansions`] scales them, as
/// double-doubles.
fn scaled_dd(pts: &[SymPoint]) -> (Vec<V3<Dd>>, i32) {
    let k = scale_exponent(pts.iter().map(|p| &p.pos));
    let s = pow2(-k);
    let v = pts
        .iter()
        .map(|p| {
            let q = p.pos * s;
            [Dd::cst(q.x), Dd::cst(q.y), Dd::cst(q.z)]
        })
        .collect();
    (v, k)
}

/// [`edge_triangle_point`] in double-double arithmetic, when every
/// quotient is certified (see [`crate::dd`]): then bit-identical to the
/// exact path.
fn edge_triangle_point_dd(pts: &[SymPoint; 5]) -> Option<EdgeTrianglePoint> {
    let (ex, k) = scaled_dd(pts);
    let et = EtTerms::new(&ex);
    let back = pow2(k);
    let mut pos = [0.0; 3];
    for (j, x) in pos.iter_mut().enumerate() {
        *x = certified_div(&et.pos(&ex, j), &et.den)? * back;
    }
    let mut bary = [0.0; 3];
    for (x, n) in bary.iter_mut().zip(&et.bary) {
        *x = certified_div(n, &et.bary_sum)?;
    }
    Some(EdgeTrianglePoint {
        t: certified_div(&et.hp, &et.den)?,
        pos: DVec3::from_array(pos),
        bary,
    })
}

/// [`triple_point`] in double-double arithmetic, when every quotient is
/// certified (see [`crate::dd`]): then bit-identical to the exact path.
/// Many overlapping layers make many triple points; this keeps each one
/// a few hundred flops instead of products of long expansions.
fn triple_point_dd(pts: &[SymPoint; 9]) -> Option<TriplePoint> {
    let (ex, k) = scaled_dd(pts);
    let (xh, w) = triple_h(&ex);
    let back = pow2(k);
    let mut bary = [[0.0; 3]; 3];
    for (tri, b) in bary.iter_mut().enumerate() {
        let (num, den) = tp_bary_terms(&ex, &xh, &w, tri);
        for (x, n) in b.iter_mut().zip(&num) {
            *x = certified_div(n, &den)?;
        }
    }
    let mut pos = [0.0; 3];
    for (j, x) in pos.iter_mut().enumerate() {
        *x = certified_div(&xh[j], &w)? * back;
    }
    Some(TriplePoint {
        pos: DVec3::from_array(pos),
        bary,
    })
}

fn check_finite(pts: &[SymPoint]) -> Result<(), GeomError> {
    match pts.iter().position(|p| !p.pos.is_finite()) {
        Some(index) => Err(NonFinite::new("point", index, pts[index].pos).into()),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::Rng;
    use holey_testkit::exact::BigInt;
    use std::cmp::Ordering;

    fn sp(x: f64, y: f64, z: f64, id: u32) -> SymPoint {
        SymPoint::new(DVec3::new(x, y, z), id)
    }

    /// The scales and offsets the lattice cases are repeated at, by
    /// [`copy`]: far below and above 1, and offsets that leave the case
    /// fewer and fewer bits.
    const COPIES: [(f64, f64); 5] = [
        (1e-30, 0.0),
        (1e30, 0.0),
        (1.0, 4096.0),
        (1.0, 1e6),
        (1.0, 1e12),
    ];

    /// `x` scaled by `s` and moved by `off` along every axis, keeping its
    /// identity.
    fn copy(x: SymPoint, s: f64, off: f64) -> SymPoint {
        SymPoint::new(x.pos * s + DVec3::splat(off), x.id)
    }

    /// A random point: generic, snapped to a coarse lattice (many exact
    /// coincidences and representable answers), or scaled far up or down.
    fn random_point(rng: &mut Rng, kind: usize, id: u32) -> SymPoint {
        let mut p = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        match kind % 4 {
            1 => p = (p * 8.0).round() / 8.0,
            2 => p = p * 1e9 + DVec3::splat(4096.0),
            3 => p *= 1e-12,
            _ => {}
        }
        SymPoint::new(p, id)
    }

    /// The double-double path, whenever it answers, gives exactly the
    /// doubles the exact expansions give; and it answers almost always
    /// on generic input.
    #[test]
    fn double_double_constructions_match_the_exact_ones() {
        let mut rng = Rng::new(77);
        let (mut et_fast, mut et_all, mut tp_fast, mut tp_all) = (0, 0, 0, 0);
        for trial in 0..4000 {
            let kind = trial;
            let pts: [SymPoint; 9] =
                std::array::from_fn(|i| random_point(&mut rng, kind, i as u32));
            let et: [SymPoint; 5] = std::array::from_fn(|i| pts[i]);
            if let Ok(exact) = edge_triangle_point_exact(&et) {
                et_all += 1;
                if let Some(fast) = edge_triangle_point_dd(&et) {
                    et_fast += 1;
                    assert_eq!(fast.t.to_bits(), exact.t.to_bits(), "trial {trial}");
                    assert_eq!(fast.pos, exact.pos, "trial {trial}");
                    for (a, b) in fast.bary.iter().zip(&exact.bary) {
                        assert_eq!(a.to_bits(), b.to_bits(), "trial {trial}");
                    }
                }
            }
            if let Ok(exact) = triple_point_exact(&pts) {
                tp_all += 1;
                if let Some(fast) = triple_point_dd(&pts) {
                    tp_fast += 1;
                    assert_eq!(fast.pos, exact.pos, "trial {trial}");
                    for (a, b) in fast.bary.iter().flatten().zip(exact.bary.iter().flatten()) {
                        assert_eq!(a.to_bits(), b.to_bits(), "trial {trial}");
                    }
                }
            }
        }
        eprintln!(
            "edge x triangle: {et_fast} of {et_all} certified; triple: {tp_fast} of {tp_all}"
        );
        // Lattice inputs give exact ties and zeros, which go to the exact
        // path; the rest should almost all be certified.
        assert!(et_fast * 10 > et_all * 9, "{et_fast} of {et_all}");
        assert!(tp_fast * 10 > tp_all * 9, "{tp_fast} of {tp_all}");
    }

    /// Correct rounding checked against big integers: `q` is correctly
    /// rounded iff `|N − q D| ≤ |N − q' D|` for both neighbours `q'`.
    #[test]
    fn division_is_correctly_rounded() {
        let mut rng = Rng::new(2);
        for _ in 0..3000 {
            let a = rng.range(-1.0, 1.0) * pow2(rng.below(40) as i32 - 20);
            let b = rng.range(-1.0, 1.0);
            let c = rng.range(-1.0, 1.0) * pow2(rng.below(40) as i32 - 20);
            let n = Expansion::from_f64(a)
                .mul(&Expansion::from_f64(b))
                .add(&Expansion::from_f64(c));
            let d = Expansion::from_f64(rng.range(0.1, 3.0)).add(&Expansion::from_f64(1e-20));
            let q = div_round(&n, &d);
            let s = 1200;
            let big = |e: &Expansion| {
                e.components().iter().fold(BigInt::zero(), |acc, &x| {
                    acc.add(&BigInt::from_f64_scaled(x, s))
                })
            };
            let (nb, db) = (big(&n), big(&d));
            let err = |q: f64| {
                let r = nb
                    .shl(s as u32)
                    .sub(&BigInt::from_f64_scaled(q, s).mul(&db));
                if r.sign() < 0 { r.neg() } else { r }
            };
            let e0 = err(q);
            assert_ne!(e0.cmp(&err(q.next_up())), Ordering::Greater);
            assert_ne!(e0.cmp(&err(q.next_down())), Ordering::Greater);
        }
    }

    #[test]
    fn edge_triangle_point_on_lattice_is_exact() {
        let p = sp(1.0, 1.0, 3.0, 0);
        let q = sp(1.0, 1.0, -1.0, 1);
        let (a, b, c) = (
            sp(0.0, 0.0, 0.0, 2),
            sp(4.0, 0.0, 0.0, 3),
            sp(0.0, 4.0, 0.0, 4),
        );
        let e = edge_triangle_point(p, q, a, b, c).expect("exists");
        assert_eq!(e.t, 0.75);
        assert_eq!(e.pos, DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(e.bary, [0.5, 0.25, 0.25]);
        // Scaled and offset copies.
        for (s, off) in COPIES {
            let m = |x: SymPoint| copy(x, s, off);
            let e = edge_triangle_point(m(p), m(q), m(a), m(b), m(c)).expect("exists");
            assert_eq!(e.t, 0.75);
            let want = DVec3::new(1.0, 1.0, 0.0) * s + DVec3::splat(off);
            assert_eq!(e.pos, want, "{s} {off}");
        }
    }

    #[test]
    fn coplanar_edge_gives_the_perturbed_limit() {
        // Edge inside the plane z = 0 of the triangle: the perturbed
        // crossing point is a definite point of the segment.
        let p = sp(-1.0, 1.0, 0.0, 10);
        let q = sp(3.0, 1.0, 0.0, 11);
        let (a, b, c) = (
            sp(0.0, 0.0, 0.0, 2),
            sp(4.0, 0.0, 0.0, 3),
            sp(0.0, 4.0, 0.0, 4),
        );
        let e = edge_triangle_point(p, q, a, b, c).expect("limit exists");
        assert!((0.0..=1.0).contains(&e.t));
        let on = p.pos + (q.pos - p.pos) * e.t;
        assert!((on - e.pos).length() < 1e-12);
        // Shared identities that put the edge in the plane identically.
        assert!(edge_triangle_point(a, b, a, b, c).is_err());
    }

    #[test]
    fn random_edge_triangle_points_match_float() {
        let mut rng = Rng::new(6);
        for _ in 0..2000 {
            let r = |rng: &mut Rng, id| {
                sp(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    id,
                )
            };
            let (p, q, a, b, c) = (
                r(&mut rng, 0),
                r(&mut rng, 1),
                r(&mut rng, 2),
                r(&mut rng, 3),
                r(&mut rng, 4),
            );
            let n = (b.pos - a.pos).cross(c.pos - a.pos);
            let hp = n.dot(p.pos - a.pos);
            let hq = n.dot(q.pos - a.pos);
            if (hp - hq).abs() < 1e-3 {
                continue;
            }
            let e = edge_triangle_point(p, q, a, b, c).expect("exists");
            let t = hp / (hp - hq);
            assert!((e.t - t).abs() < 1e-9);
            let x = p.pos + (q.pos - p.pos) * t;
            assert!((e.pos - x).length() < 1e-9);
            let y = a.pos * e.bary[0] + b.pos * e.bary[1] + c.pos * e.bary[2];
            assert!((y - x).length() < 1e-8, "{y} {x}");
        }
    }

    /// Correct rounding makes constructions independent of how the same
    /// point is described: reversed edges, rotated triangles and permuted
    /// triangle orders give bit-identical coordinates.
    #[test]
    fn constructions_are_consistent_across_descriptions() {
        let mut rng = Rng::new(12);
        let r = |rng: &mut Rng, id| {
            sp(
                rng.range(-1.0, 1.0) * 1e3 + 4096.0,
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0) * 1e-3,
                id,
            )
        };
        for _ in 0..300 {
            let v: Vec<SymPoint> = (0..9).map(|i| r(&mut rng, i)).collect();
            if let Ok(e) = edge_triangle_point(v[0], v[1], v[2], v[3], v[4]) {
                let f = edge_triangle_point(v[1], v[0], v[3], v[4], v[2]).expect("same point");
                assert_eq!(e.pos, f.pos);
                assert_eq!(e.bary, [f.bary[2], f.bary[0], f.bary[1]]);
            }
            let (t1, t2, t3) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]);
            let x = triple_point(t1, t2, t3).expect("generic planes meet");
            let y = triple_point(t3, [t1[1], t1[2], t1[0]], t2).expect("same point");
            assert_eq!(x.pos, y.pos);
            assert_eq!(x.bary[2], y.bary[0]);
            assert_eq!(x.bary[0], [y.bary[1][2], y.bary[1][0], y.bary[1][1]]);
        }
    }

    /// The points as polynomials in the first `level` perturbation
    /// variables, uncapped.
    fn at_level(pts: &[SymPoint], s: f64, level: usize) -> Vec<V3<EpsPoly>> {
        Ranks::of(pts).at_level(pts, s, level)
    }

    /// The limits of `nums/den` as they were computed before the
    /// [`crate::sos::levels`] steps and the [`EpsPoly`] caps: every level
    /// in turn until `den` is not zero, everything evaluated in full.
    fn limits_level_by_level<N: Polys, D: Poly>(
        nums: &N,
        den: &D,
        pts: &[SymPoint],
        s: f64,
    ) -> Option<Vec<f64>> {
        let ep = (1..=3 * pts.len())
            .map(|l| at_level(pts, s, l))
            .find(|ep| !den.eval(ep).is_empty())?;
        let d = den.eval(&ep);
        let n = nums.eval_all(&ep);
        n.iter().map(|n| limit_of(n, &d).ok()).collect()
    }

    /// The triple point's limit as [`triple_point_limit`] computed it
    /// before the steps and caps.
    fn triple_limit_level_by_level(pts: &[SymPoint; 9], k: i32) -> Option<TriplePoint> {
        let ep = (1..=27)
            .map(|l| at_level(pts, pow2(-k), l))
            .find(|ep| !TpW.eval(ep).is_empty())?;
        let (xh, w) = triple_h(&ep);
        let pos = xh
            .clone()
            .map(|h| limit_of(&h, &w).ok().map(|x| x * pow2(k)));
        let mut bary = [[0.0; 3]; 3];
        for (tri, b) in bary.iter_mut().enumerate() {
            let (num, den) = tp_bary_terms(&ep, &xh, &w, tri);
            for (x, n) in b.iter_mut().zip(&num) {
                *x = limit_of(n, &den).ok()?;
            }
        }
        Some(TriplePoint {
            pos: DVec3::new(pos[0]?, pos[1]?, pos[2]?),
            bary,
        })
    }

    /// The premise of [`edge_triangle_limit`]: the barycentric
    /// denominator is the height difference negated, exactly, generic or
    /// degenerate.
    #[test]
    fn barycentric_denominator_is_the_height_difference_negated() {
        let mut rng = Rng::new(5);
        for kind in 0..800 {
            let pts: Vec<SymPoint> = (0..5).map(|i| random_point(&mut rng, kind, i)).collect();
            let ex = scaled_by(&pts, 1.0);
            // Expansions of one value may differ in their components:
            // the sum is what is exactly zero.
            let sum = EtBaryDen.eval(&ex).add(&EtDen.eval(&ex));
            assert!(sum.is_zero(), "{pts:?}");
        }
    }

    /// Lattice points with shared and repeated coordinates make planes
    /// that coincide and edges that lie in planes, so every construction
    /// below is a perturbed limit; the stepped levels and the caps give
    /// the doubles the full level-by-level evaluation gives.
    #[test]
    fn capped_limits_are_the_uncapped_ones() {
        let mut rng = Rng::new(2026);
        let (mut edge_limits, mut triple_limits) = (0, 0);
        for _ in 0..200 {
            let pts: [SymPoint; 9] = std::array::from_fn(|i| {
                let c = [0; 3].map(|_: i32| rng.below(3) as f64 - 1.0);
                let c = if i >= 3 && rng.chance(0.5) {
                    [c[0], c[1], 0.0]
                } else {
                    c
                };
                SymPoint::new(
                    DVec3::from_array(c),
                    if rng.chance(0.1) { 0 } else { i as u32 },
                )
            });
            let et = [pts[0], pts[1], pts[2], pts[3], pts[4]];
            let s = pow2(-scale_exponent(et.iter().map(|p| &p.pos)));
            if EtDen.eval(&scaled_by(&et, s)).is_zero() {
                let tp = limits_level_by_level(&EtNums, &EtDen, &et, s);
                let b = limits_level_by_level(&EtBarys, &EtBaryDen, &et, s);
                let want = tp.zip(b).map(|(tp, b)| EdgeTrianglePoint {
                    t: tp[0],
                    pos: DVec3::new(tp[1], tp[2], tp[3]) / s,
                    bary: [b[0], b[1], b[2]],
                });
                let k = scale_exponent(et.iter().map(|p| &p.pos));
                assert_eq!(edge_triangle_limit(&et, k).ok(), want, "{et:?}");
                edge_limits += 1;
            }
            let k = scale_exponent(pts.iter().map(|p| &p.pos));
            if TpW.eval(&scaled_by(&pts, pow2(-k))).is_zero() {
                let got = triple_point_limit(&pts, k).ok().flatten();
                assert_eq!(got, triple_limit_level_by_level(&pts, k), "{pts:?}");
                triple_limits += usize::from(got.is_some());
            }
        }
        assert!(
            edge_limits > 50 && triple_limits > 10,
            "{edge_limits} {triple_limits}"
        );
    }

    #[test]
    fn triple_point_and_barycentrics() {
        // Planes z = 0, y = 0, x = 0 meet at the origin.
        let t1 = [
            sp(-1.0, -1.0, 0.0, 0),
            sp(3.0, -1.0, 0.0, 1),
            sp(-1.0, 3.0, 0.0, 2),
        ];
        let t2 = [
            sp(-1.0, 0.0, -1.0, 3),
            sp(-1.0, 0.0, 3.0, 4),
            sp(3.0, 0.0, -1.0, 5),
        ];
        let t3 = [
            sp(0.0, -1.0, -1.0, 6),
            sp(0.0, 3.0, -1.0, 7),
            sp(0.0, -1.0, 3.0, 8),
        ];
        let x = triple_point(t1, t2, t3).expect("exists");
        assert_eq!(x.pos, DVec3::ZERO);
        assert_eq!(x.bary[0], [0.5, 0.25, 0.25]);
        assert_eq!(x.bary[1], [0.5, 0.25, 0.25]);
        assert_eq!(x.bary[2], [0.5, 0.25, 0.25]);
        assert!(crate::intersect::triangle_triangle_triangle_point(
            t1, t2, t3
        ));
        for (s, off) in COPIES {
            let m = |t: [SymPoint; 3]| t.map(|x| copy(x, s, off));
            let x = triple_point(m(t1), m(t2), m(t3)).expect("exists");
            assert_eq!(x.pos, DVec3::splat(off), "{s} {off}");
            // 1e±30 are not powers of two: the scaled corners are rounded,
            // so the weights are the correctly rounded weights of the
            // rounded triangle, within an ulp or two of the ideal ones.
            for (g, w) in x.bary[0].iter().zip([0.5, 0.25, 0.25]) {
                assert!((g - w).abs() < 1e-15, "{g}");
            }
            assert!(crate::intersect::triangle_triangle_triangle_point(
                m(t1),
                m(t2),
                m(t3)
            ));
        }
        // Parallel planes: no point even after perturbation? (Perturbation
        // tilts them, so a limit exists only if bounded; here the limit
        // point is at infinity and the construction must not panic.)
        let t4 = [
            sp(-1.0, -1.0, 1.0, 9),
            sp(3.0, -1.0, 1.0, 10),
            sp(-1.0, 3.0, 1.0, 11),
        ];
        let _ = triple_point(t1, t4, t3);
    }
}
