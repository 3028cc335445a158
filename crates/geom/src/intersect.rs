//! Intersection predicates for the static-intersection stage (§3.3), exact
//! and decided in the perturbed world of [`crate::sos`].
//!
//! # Segment × triangle
//!
//! [`segment_triangle_intersect`]`(p, q, a, b, c)`: does the open segment
//! `pq` cross the open triangle `abc`? With everything perturbed into
//! general position this is the classical test
//!
//! ```text
//!   orient(a,b,c,p) ≠ orient(a,b,c,q)                 (p, q on both sides)
//!   orient(p,q,a,b) = orient(p,q,b,c) = orient(p,q,c,a) (line pq inside abc)
//! ```
//!
//! all evaluated with [`orient3d_sos`]. **Shared identities** are decided
//! combinatorially, before any arithmetic: if `p` or `q` is one of the
//! triangle's corners (same identity), or the segment or the triangle has a
//! repeated identity, the answer is `false`. Geometrically: a segment that
//! shares an endpoint `a` with the triangle meets the (perturbed, hence
//! non-coplanar) triangle only at `a`, which is not a crossing of the open
//! triangle. The engine's rule is therefore: edges of a triangle and edges
//! incident to a corner of a triangle never cross it; intersections along
//! shared vertices/edges are adjacency, not intersection.
//!
//! # Intersection segments, triple points, order along a segment
//!
//! Two triangles in general position meet in a segment whose ends are
//! edge × triangle crossings ([`triangle_triangle_segment`], [`SegEnd`]).
//! A point on such a segment is described *implicitly* by the planes it
//! lies on, and every question about it is reduced to signs of polynomials
//! in orientations of input points:
//!
//! - the side of a plane on which an end `E = pq ∩ T` lies
//!   ([`end_side`]): with `α = O(T,p)`, `β = O(T,q)`, `E = (αq − βp)/(α−β)`
//!   and, `O(T_k, ·)` being affine, `O(T_k, E) = (α O(T_k,q) − β
//!   O(T_k,p)) / (α − β)`: a product of two orientations over one;
//! - triple points ([`triangle_triangle_triangle_point`]): the segment
//!   `t_1 ∩ t_2` crosses plane 3 and `t_1 ∩ t_3` crosses plane 2;
//! - the order of two plane crossings along a segment
//!   ([`order_on_segment`]): a 2×2 determinant of such end sides.
//!
//! Keeping the polynomials as short sums of products of orientations (rather
//! than expanding homogeneous coordinates of constructed points, degree 7 to
//! 17) keeps the perturbed stage of the driver small: each perturbed
//! orientation has at most 73 monomials.

use crate::orient::orient3d_sos;
use crate::ring::{Ring, V3, orient3};
use crate::sos::{Poly, SosSign, SymPoint, sos_sign};
use std::cmp::Ordering;

/// True iff the open segment `pq` crosses the open triangle `abc` in the
/// perturbed world (see the module docs for the shared-identity rules).
pub fn segment_triangle_intersect(
    p: SymPoint,
    q: SymPoint,
    a: SymPoint,
    b: SymPoint,
    c: SymPoint,
) -> bool {
    let tri = [a.id, b.id, c.id];
    if p.id == q.id
        || a.id == b.id
        || b.id == c.id
        || a.id == c.id
        || tri.contains(&p.id)
        || tri.contains(&q.id)
    {
        return false;
    }
    let sp = orient3d_sos(a, b, c, p);
    let sq = orient3d_sos(a, b, c, q);
    if sp == sq {
        return false;
    }
    let e1 = orient3d_sos(p, q, a, b);
    let e2 = orient3d_sos(p, q, b, c);
    if e1 != e2 {
        return false;
    }
    orient3d_sos(p, q, c, a) == e1
}

/// One end of the intersection segment of two triangles (in the perturbed
/// world): an edge of one triangle crossing the other, or a shared vertex
/// from which the segment emanates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegEnd {
    /// Where edge `p q` crosses triangle `tri`.
    Edge {
        /// One end of the crossing edge, an edge of one of the two triangles.
        p: SymPoint,
        /// The other end of the crossing edge.
        q: SymPoint,
        /// The corners of the crossed triangle, the other of the two.
        tri: [SymPoint; 3],
    },
    /// A vertex shared by the two triangles.
    Vertex(SymPoint),
}

impl SegEnd {
    fn push(&self, out: &mut Vec<SymPoint>) {
        match self {
            SegEnd::Edge { p, q, tri } => out.extend_from_slice(&[*p, *q, tri[0], tri[1], tri[2]]),
            SegEnd::Vertex(v) => out.push(*v),
        }
    }
    fn is_edge(&self) -> bool {
        matches!(self, SegEnd::Edge { .. })
    }
    fn ids(&self) -> Vec<u32> {
        let mut v = Vec::new();
        self.push(&mut v);
        v.iter().map(|p| p.id).collect()
    }
}

/// A segment end whose points start at `p[off]`, with the orientations it
/// needs once however many planes it is measured against. For an edge
/// `p q` crossing plane `T` (the points `p, q, T` at `p[off..off + 5]`),
/// `α = O(T,p)` and `β = O(T,q)`, with `O` [`crate::orient3d`] with the
/// point last: the end is `E = (α q − β p)/(α − β)`. For a vertex, the
/// vertex.
enum EndTerms<'a, T> {
    Edge {
        al: T,
        be: T,
        p: &'a V3<T>,
        q: &'a V3<T>,
    },
    Vertex(&'a V3<T>),
}

impl<'a, T: Ring> EndTerms<'a, T> {
    fn of(edge: bool, p: &'a [V3<T>], off: usize) -> Self {
        if edge {
            let t = (&p[off + 2], &p[off + 3], &p[off + 4]);
            EndTerms::Edge {
                al: orient3(t.0, t.1, t.2, &p[off]),
                be: orient3(t.0, t.1, t.2, &p[off + 1]),
                p: &p[off],
                q: &p[off + 1],
            }
        } else {
            EndTerms::Vertex(&p[off])
        }
    }

    /// `ĥ` with `O(T_k, E) = ĥ / w` for the plane of the triangle at
    /// `p[k..k + 3]`: `O(T_k, ·)` is affine, so for an edge end
    /// `ĥ = α·O(T_k,q) − β·O(T_k,p)` and `w = α − β`, whose sign is `α`'s
    /// (`α` and `β` have opposite signs: the edge crosses `T`, in the
    /// perturbed world too); for a vertex `ĥ = O(T_k, v)`, `w = 1`.
    fn h(&self, p: &[V3<T>], k: usize) -> T {
        let tk = (&p[k], &p[k + 1], &p[k + 2]);
        match self {
            EndTerms::Edge { al, be, p, q } => {
                let gp = orient3(tk.0, tk.1, tk.2, p);
                let gq = orient3(tk.0, tk.1, tk.2, q);
                al.mul(&gq).sub(&be.mul(&gp))
            }
            EndTerms::Vertex(v) => orient3(tk.0, tk.1, tk.2, v),
        }
    }
}

/// `ĥ` of [`EndTerms::h`] as a predicate polynomial.
struct EndHat {
    edge: bool,
    off: usize,
    k: usize,
}
impl Poly for EndHat {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        EndTerms::of(self.edge, p, self.off).h(p, self.k)
    }
}

/// The sign of `w` of an edge end (see [`EndTerms::h`]): that of
/// `α = O(T, p)`; positive for a vertex.
fn end_w_sign(end: &SegEnd) -> SosSign {
    match end {
        SegEnd::Edge { p, tri, .. } => orient3d_sos(tri[0], tri[1], tri[2], *p),
        SegEnd::Vertex(_) => SosSign::Positive,
    }
}

/// The side of plane `tri` on which a segment end lies: the sign of
/// `orient3d(tri[0], tri[1], tri[2], E)` in the perturbed world.
/// `Degenerate` when the end is a vertex of `tri` or lies in its plane
/// through shared identities.
pub fn end_side(end: &SegEnd, tri: [SymPoint; 3]) -> SosSign {
    // An edge end `E = (α q − β p)/(α − β)` lies strictly inside its edge
    // (α and β have opposite signs, in the perturbed world too), and
    // `O(T, ·)` is affine: `O(T, E)` is a convex combination of `O(T, p)`
    // and `O(T, q)` with both weights positive. When those two agree, so
    // does `E`, decided by two orientations of input points instead of
    // the degree-six polynomial (on coplanar overlaps that polynomial goes
    // to the perturbed stage: a quarter of `holey selfint` on an OpenSCAD
    // export).
    if let SegEnd::Edge { p, q, .. } = end {
        let side = orient3d_sos(tri[0], tri[1], tri[2], *p);
        if side != SosSign::Degenerate && side == orient3d_sos(tri[0], tri[1], tri[2], *q) {
            return side;
        }
    }
    end_side_exact(end, tri)
}

/// [`end_side`] from the polynomial of the constructed end itself,
/// without the shortcut through the edge's ends.
fn end_side_exact(end: &SegEnd, tri: [SymPoint; 3]) -> SosSign {
    let mut pts = Vec::with_capacity(8);
    end.push(&mut pts);
    let k = pts.len();
    pts.extend_from_slice(&tri);
    match end {
        SegEnd::Vertex(v) => orient3d_sos(tri[0], tri[1], tri[2], *v),
        SegEnd::Edge { .. } => {
            let h = sos_sign(
                &EndHat {
                    edge: true,
                    off: 0,
                    k,
                },
                &pts,
            );
            SosSign::from_i8(h.as_i8() * end_w_sign(end).as_i8())
        }
    }
}

/// The intersection segment of two triangles in the perturbed world, as
/// its two ends, or `None` when they do not intersect along a segment
/// (disjoint, touching only at a shared vertex, or sharing an edge — which
/// is adjacency, not intersection).
///
/// In general position two triangles meet in a segment whose ends are
/// crossings of an edge of one with the other; if they share exactly one
/// vertex, the segment (if any) runs from that vertex to one such
/// crossing.
pub fn triangle_triangle_segment(t1: [SymPoint; 3], t2: [SymPoint; 3]) -> Option<[SegEnd; 2]> {
    let shared: Vec<SymPoint> = t1
        .iter()
        .filter(|a| t2.iter().any(|b| b.id == a.id))
        .copied()
        .collect();
    if shared.len() >= 2 {
        return None;
    }
    let mut ends: Vec<SegEnd> = Vec::with_capacity(2);
    for (ta, tb) in [(t1, t2), (t2, t1)] {
        for e in 0..3 {
            let (p, q) = (ta[e], ta[(e + 1) % 3]);
            if segment_triangle_intersect(p, q, tb[0], tb[1], tb[2]) {
                ends.push(SegEnd::Edge { p, q, tri: tb });
            }
        }
    }
    if let Some(&v) = shared.first() {
        if ends.len() == 1 {
            return Some([SegEnd::Vertex(v), ends[0]]);
        }
        return None;
    }
    if ends.len() == 2 {
        Some([ends[0], ends[1]])
    } else {
        None
    }
}

/// Do three triangles meet in a common point (a "triple point", §3.3)?
/// Exact, in the perturbed world.
///
/// With `s_ij = t_i ∩ t_j` (from [`triangle_triangle_segment`]) and `X`
/// the common point of the three planes: `X ∈ s_12` iff the ends of `s_12`
/// lie on opposite sides of plane 3 (`s_12` lies on the line of planes 1
/// and 2, which meets plane 3 only at `X`), likewise `X ∈ s_13` iff the ends
/// of `s_13` are on opposite sides of plane 2; and `X ∈ s_12 ∩ s_13` means
/// `X` lies in all three triangles. Every test is a product of two
/// orientations (degree 6), evaluated with the generic driver. `false` when
/// some pair does not intersect along a segment, or when the only candidate
/// is a vertex shared by all three (that is not a triple point).
pub fn triangle_triangle_triangle_point(
    t1: [SymPoint; 3],
    t2: [SymPoint; 3],
    t3: [SymPoint; 3],
) -> bool {
    let Some(s12) = triangle_triangle_segment(t1, t2) else {
        return false;
    };
    let Some(s13) = triangle_triangle_segment(t1, t3) else {
        return false;
    };
    if triangle_triangle_segment(t2, t3).is_none() {
        return false;
    }
    let crosses = |s: &[SegEnd; 2], t: [SymPoint; 3]| {
        let a = end_side(&s[0], t);
        let b = end_side(&s[1], t);
        a != SosSign::Degenerate && b != SosSign::Degenerate && a != b
    };
    crosses(&s12, t3) && crosses(&s13, t2)
}

/// `ĥ_k(E)·ĥ_m(F) − ĥ_k(F)·ĥ_m(E)` for ends `E`, `F` and planes `k`, `m`.
struct Cross2 {
    e_edge: bool,
    f_edge: bool,
    f_off: usize,
    k: usize,
    m: usize,
}
impl Poly for Cross2 {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        let e = EndTerms::of(self.e_edge, p, 0);
        let f = EndTerms::of(self.f_edge, p, self.f_off);
        let (hke, hme) = (e.h(p, self.k), e.h(p, self.m));
        let (hkf, hmf) = (f.h(p, self.k), f.h(p, self.m));
        hke.mul(&hmf).sub(&hkf.mul(&hme))
    }
}

/// Orders two points of an intersection segment `s = [E, F]`: the points
/// where `s` crosses the planes of triangles `tk` and `tm` (both crossings
/// assumed to exist, e.g. triple points found by
/// [`triangle_triangle_triangle_point`]). `Less` when the crossing with
/// `tk` is nearer to `E`. `Equal` only for degenerate input (the same
/// plane twice, or a crossing that does not exist).
///
/// With `O_k` the (affine) orientation with respect to plane `k`, `X_k =
/// E + τ_k (F − E)` with `τ_k = O_k(E)/(O_k(E) − O_k(F))`, and `X_k` comes
/// before `X_m` iff `X_k` is on `E`'s side of plane `m`; by affinity
/// `O_m(X_k)·(O_k(E) − O_k(F)) = O_k(E) O_m(F) − O_k(F) O_m(E)`. In the
/// homogeneous form of [`end_side`] that is
/// `sign O_m(X_k) = sign(ĥ_k(E)ĥ_m(F) − ĥ_k(F)ĥ_m(E)) · sign(w_F) ·
/// sign O_k(E)`, a sum of products of four orientations.
pub fn order_on_segment(s: &[SegEnd; 2], tk: [SymPoint; 3], tm: [SymPoint; 3]) -> Ordering {
    let (e, f) = (&s[0], &s[1]);
    let ok_e = end_side(e, tk);
    let om_e = end_side(e, tm);
    let ok_f = end_side(f, tk);
    if ok_e == SosSign::Degenerate || om_e == SosSign::Degenerate || ok_e == ok_f {
        return Ordering::Equal;
    }
    if tk.map(|p| p.id) == tm.map(|p| p.id) {
        return Ordering::Equal;
    }
    let mut pts = Vec::with_capacity(16);
    e.push(&mut pts);
    let f_off = pts.len();
    f.push(&mut pts);
    let k = pts.len();
    pts.extend_from_slice(&tk);
    let m = pts.len();
    pts.extend_from_slice(&tm);
    let big = sos_sign(
        &Cross2 {
            e_edge: e.is_edge(),
            f_edge: f.is_edge(),
            f_off,
            k,
            m,
        },
        &pts,
    );
    let wf = end_w_sign(f);
    let om_xk = big.as_i8() * wf.as_i8() * ok_e.as_i8();
    if om_xk == 0 {
        return Ordering::Equal;
    }
    // X_k before X_m iff X_k is on E's side of plane m.
    if om_xk == om_e.as_i8() {
        Ordering::Less
    } else {
        Ordering::Greater
    }
}

/// The identities involved in a segment end (for callers' bookkeeping).
pub fn seg_end_ids(end: &SegEnd) -> Vec<u32> {
    end.ids()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use holey_testkit::{Rng, octahedron};

    fn sp(x: f64, y: f64, z: f64, id: u32) -> SymPoint {
        SymPoint::new(DVec3::new(x, y, z), id)
    }

    /// The 27 points of a 3×3×3 grid, numbered as their own identities.
    fn grid() -> Vec<SymPoint> {
        (0..27)
            .map(|i| {
                let at = |k: u32| f64::from((i / 3u32.pow(k)) % 3);
                sp(at(0), at(1), at(2), i)
            })
            .collect()
    }

    /// A triangle of three distinct points of `grid`, drawn by `rng`.
    fn grid_triangle(rng: &mut Rng, grid: &[SymPoint]) -> [SymPoint; 3] {
        loop {
            let t = [*rng.pick(grid), *rng.pick(grid), *rng.pick(grid)];
            if t[0].id != t[1].id && t[1].id != t[2].id && t[0].id != t[2].id {
                return t;
            }
        }
    }

    /// `w = α − β` of an edge end, the polynomial itself: the oracle of
    /// [`end_w_sign`].
    struct AlphaMinusBeta;
    impl Poly for AlphaMinusBeta {
        fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
            let t = (&p[2], &p[3], &p[4]);
            orient3(t.0, t.1, t.2, &p[0]).sub(&orient3(t.0, t.1, t.2, &p[1]))
        }
    }

    /// The sign of an edge end's `w` is its first point's side of the
    /// plane the edge crosses, as the polynomial `α − β` says, on
    /// triangles drawn from a 3×3×3 grid of points (coplanar and collinear
    /// configurations are the rule there, decided in the perturbed world).
    #[test]
    fn an_edge_ends_w_has_the_sign_of_its_first_points_side() {
        let mut rng = Rng::new(30);
        let grid = grid();
        let mut compared = 0;
        while compared < 2000 {
            let (t1, t2) = (
                grid_triangle(&mut rng, &grid),
                grid_triangle(&mut rng, &grid),
            );
            let Some(ends) = triangle_triangle_segment(t1, t2) else {
                continue;
            };
            for end in &ends {
                if let SegEnd::Edge { p, q, tri } = end {
                    let pts = [*p, *q, tri[0], tri[1], tri[2]];
                    assert_eq!(end_w_sign(end), sos_sign(&AlphaMinusBeta, &pts), "{end:?}");
                    assert_ne!(end_w_sign(end), SosSign::Degenerate);
                    compared += 1;
                }
            }
        }
    }

    /// The shortcut of [`end_side`] (both ends of the crossing edge on one
    /// side) agrees with the constructed end's own polynomial, on
    /// triangles drawn from a 3×3×3 grid of points, where coplanar and
    /// collinear configurations are the rule and the perturbed stage
    /// decides most predicates.
    #[test]
    fn end_side_shortcut_agrees_with_the_ends_polynomial() {
        let mut rng = Rng::new(29);
        let grid = grid();
        let tri = |rng: &mut Rng| grid_triangle(rng, &grid);
        let (mut compared, mut shortcut) = (0, 0);
        while compared < 2000 {
            let (t1, t2, t3) = (tri(&mut rng), tri(&mut rng), tri(&mut rng));
            let Some(ends) = triangle_triangle_segment(t1, t2) else {
                continue;
            };
            for end in &ends {
                if let SegEnd::Edge { p, q, .. } = end {
                    let side = orient3d_sos(t3[0], t3[1], t3[2], *p);
                    if side != SosSign::Degenerate && side == orient3d_sos(t3[0], t3[1], t3[2], *q)
                    {
                        shortcut += 1;
                    }
                    assert_eq!(
                        end_side(end, t3),
                        end_side_exact(end, t3),
                        "{end:?} against {t3:?}"
                    );
                    compared += 1;
                }
            }
        }
        assert!(shortcut > 200, "the shortcut was taken {shortcut} times");
    }

    #[test]
    fn segment_through_triangle_interior_edge_and_vertex() {
        let a = sp(0.0, 0.0, 0.0, 0);
        let b = sp(2.0, 0.0, 0.0, 1);
        let c = sp(0.0, 2.0, 0.0, 2);
        let d = sp(2.0, 2.0, 0.0, 3); // b, d, c: the other half of a square
        // Interior crossing.
        assert!(segment_triangle_intersect(
            sp(0.5, 0.5, 1.0, 10),
            sp(0.5, 0.5, -1.0, 11),
            a,
            b,
            c
        ));
        // Through the shared diagonal b–c: exactly one of the two halves.
        let p = sp(1.0, 1.0, 1.0, 10);
        let q = sp(1.0, 1.0, -1.0, 11);
        let n = segment_triangle_intersect(p, q, a, b, c) as u32
            + segment_triangle_intersect(p, q, b, d, c) as u32;
        assert_eq!(n, 1);
        // Through the shared corner b of a fan: exactly one crossing.
        let e = sp(4.0, 0.0, 0.0, 4);
        let f = sp(2.0, -2.0, 0.0, 5);
        let p = sp(2.0, 0.0, 1.0, 10);
        let q = sp(2.0, 0.0, -1.0, 11);
        let fan = [[a, b, c], [b, d, c], [b, e, d], [b, f, e], [a, f, b]];
        // The fan around b: a-b-c, b-d-c, b-e-d, b-f-e, a-f-b closes
        // around b (angles 90+45+45+90+90 = 360).
        let n: u32 = fan
            .iter()
            .map(|t| segment_triangle_intersect(p, q, t[0], t[1], t[2]) as u32)
            .sum();
        assert_eq!(n, 1);
        // Shared endpoint identity: never a crossing.
        assert!(!segment_triangle_intersect(
            a,
            sp(0.5, 0.5, -1.0, 11),
            a,
            b,
            c
        ));
        // Coplanar segment through the triangle: decided by perturbation,
        // and the two orientations of the segment agree.
        let p = sp(-1.0, 0.5, 0.0, 10);
        let q = sp(3.0, 0.5, 0.0, 11);
        assert_eq!(
            segment_triangle_intersect(p, q, a, b, c),
            segment_triangle_intersect(q, p, a, b, c)
        );
    }

    /// A closed octahedron: any segment between two points strictly on
    /// different sides crosses it an odd number of times, whatever the
    /// degeneracies (segments through vertices, along edges, in face
    /// planes) — checked on a lattice where all of these happen.
    #[test]
    fn segment_crossing_parity_is_topological_on_a_closed_surface() {
        let (o, f) = octahedron();
        let v: Vec<SymPoint> = (0..6)
            .map(|i| SymPoint::new(DVec3::from_array(o[i]), i as u32))
            .collect();
        let f = f.map(|t| t.map(|i| i as usize));
        let inside = |p: DVec3| p.x.abs() + p.y.abs() + p.z.abs() < 1.0;
        let on = |p: DVec3| p.x.abs() + p.y.abs() + p.z.abs() == 1.0;
        let mut rng = Rng::new(4);
        let mut checked = 0;
        let lattice = |rng: &mut Rng| {
            DVec3::new(
                rng.below(9) as f64 * 0.5 - 2.0,
                rng.below(9) as f64 * 0.5 - 2.0,
                rng.below(9) as f64 * 0.5 - 2.0,
            )
        };
        for _ in 0..3000 {
            let p = lattice(&mut rng);
            let q = lattice(&mut rng);
            if on(p) || on(q) || p == q {
                continue;
            }
            let (ps, qs) = (SymPoint::new(p, 100), SymPoint::new(q, 101));
            let n: u32 = f
                .iter()
                .map(|t| segment_triangle_intersect(ps, qs, v[t[0]], v[t[1]], v[t[2]]) as u32)
                .sum();
            assert_eq!(n % 2 == 1, inside(p) != inside(q), "{p} {q}");
            checked += 1;
        }
        assert!(checked > 1000);
    }

    fn tri(rng: &mut Rng, id: u32, n: usize) -> [SymPoint; 3] {
        loop {
            let t: [SymPoint; 3] = std::array::from_fn(|i| {
                sp(
                    rng.below(n) as f64,
                    rng.below(n) as f64,
                    rng.below(n) as f64,
                    id + i as u32,
                )
            });
            let n = (t[1].pos - t[0].pos).cross(t[2].pos - t[0].pos);
            if n != DVec3::ZERO {
                return t;
            }
        }
    }

    fn random_tri(rng: &mut Rng, id: u32) -> [SymPoint; 3] {
        std::array::from_fn(|i| {
            sp(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                id + i as u32,
            )
        })
    }

    /// Float triple point and the smallest barycentric margin over the
    /// three triangles (positive: inside all three).
    fn float_triple(t: &[[SymPoint; 3]]) -> Option<f64> {
        let pl: Vec<(DVec3, f64)> = t
            .iter()
            .map(|x| {
                let n = (x[1].pos - x[0].pos).cross(x[2].pos - x[0].pos);
                (n, n.dot(x[0].pos))
            })
            .collect();
        let w = pl[0].0.dot(pl[1].0.cross(pl[2].0));
        if w.abs() < 1e-3 {
            return None;
        }
        let x = (pl[1].0.cross(pl[2].0) * pl[0].1
            + pl[2].0.cross(pl[0].0) * pl[1].1
            + pl[0].0.cross(pl[1].0) * pl[2].1)
            / w;
        let mut min_margin = f64::INFINITY;
        for (k, tt) in t.iter().enumerate() {
            let n = pl[k].0;
            for e in 0..3 {
                let u = tt[e].pos;
                let v = tt[(e + 1) % 3].pos;
                min_margin = min_margin.min((v - u).cross(x - u).dot(n) / n.length_squared());
            }
        }
        Some(min_margin)
    }

    #[test]
    fn triple_point_agrees_with_float_on_generic_input() {
        let mut rng = Rng::new(9);
        let mut hits = 0;
        for _ in 0..4000 {
            let t: Vec<[SymPoint; 3]> = (0..3).map(|k| random_tri(&mut rng, 3 * k)).collect();
            let got = triangle_triangle_triangle_point(t[0], t[1], t[2]);
            let Some(m) = float_triple(&t) else { continue };
            if m.abs() < 1e-6 {
                continue;
            }
            assert_eq!(got, m > 0.0);
            hits += got as u32;
        }
        assert!(hits > 5, "{hits}");
    }

    #[test]
    fn triple_point_is_symmetric_on_grids() {
        let mut rng = Rng::new(10);
        let mut hits = 0;
        for _ in 0..1500 {
            let t1 = tri(&mut rng, 0, 3);
            let t2 = tri(&mut rng, 3, 3);
            let t3 = tri(&mut rng, 6, 3);
            let r = triangle_triangle_triangle_point(t1, t2, t3);
            hits += r as u32;
            assert_eq!(r, triangle_triangle_triangle_point(t2, t3, t1));
            assert_eq!(r, triangle_triangle_triangle_point(t3, t2, t1));
            let t1r = [t1[1], t1[2], t1[0]];
            let t2f = [t2[0], t2[2], t2[1]];
            assert_eq!(r, triangle_triangle_triangle_point(t1r, t2f, t3));
        }
        assert!(hits > 0);
    }

    /// Crossings of random third triangles with the segment of two fixed
    /// triangles (lattice coordinates, so coincident crossings occur):
    /// a strict total order, agreeing with floating point where that is
    /// unambiguous.
    #[test]
    fn order_on_segment_is_a_consistent_total_order() {
        let t1 = [
            sp(0.0, 0.0, 0.0, 0),
            sp(8.0, 0.0, 0.0, 1),
            sp(0.0, 8.0, 0.0, 2),
        ];
        let t2 = [
            sp(0.0, 2.0, -2.0, 3),
            sp(8.0, 2.0, -2.0, 4),
            sp(0.0, 2.0, 6.0, 5),
        ];
        let s = triangle_triangle_segment(t1, t2).expect("they cross");
        let mut rng = Rng::new(3);
        let mut planes: Vec<([SymPoint; 3], f64)> = Vec::new();
        let mut id = 10;
        while planes.len() < 12 {
            // A triangle crossing the line y = 2, z = 0 at x = c (c on a
            // lattice, repeated values on purpose), tilted randomly.
            let c = rng.below(5) as f64 + 0.5 * rng.below(2) as f64 + 0.25;
            let tilt = rng.below(3) as f64 - 1.0;
            let t = [
                sp(c - tilt, -5.0, -5.0, id),
                sp(c + tilt, 9.0, -5.0, id + 1),
                sp(c, 2.0, 9.0, id + 2),
            ];
            id += 3;
            if triangle_triangle_triangle_point(t1, t2, t) {
                planes.push((t, c));
            }
        }
        let n = planes.len();
        let table: Vec<Vec<Ordering>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| order_on_segment(&s, planes[i].0, planes[j].0))
                    .collect()
            })
            .collect();
        let cmp = |i: usize, j: usize| table[i][j];
        for i in 0..n {
            assert_eq!(cmp(i, i), Ordering::Equal);
            for j in 0..n {
                if i == j {
                    continue;
                }
                let a = cmp(i, j);
                assert_ne!(a, Ordering::Equal);
                assert_eq!(a, cmp(j, i).reverse());
                for k in 0..n {
                    if k != i && k != j && a == Ordering::Less && cmp(j, k) == Ordering::Less {
                        assert_eq!(cmp(i, k), Ordering::Less);
                    }
                }
            }
        }
        // Agreement with the x order (E is the x = 0 end or x = 6 end).
        let e_x = match s[0] {
            SegEnd::Edge { p, q, tri } => {
                crate::construct::edge_triangle_point(p, q, tri[0], tri[1], tri[2])
                    .expect("exists")
                    .pos
                    .x
            }
            SegEnd::Vertex(v) => v.pos.x,
        };
        for i in 0..n {
            for j in 0..n {
                let (ci, cj) = (planes[i].1, planes[j].1);
                if (ci - cj).abs() > 0.1 {
                    let nearer_i = (ci - e_x).abs() < (cj - e_x).abs();
                    assert_eq!(cmp(i, j) == Ordering::Less, nearer_i);
                }
            }
        }
    }
}
