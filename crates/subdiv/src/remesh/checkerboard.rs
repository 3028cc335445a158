//! Checkerboard remeshing (TopMod's `checkerBoardRemeshing`): every edge
//! cut at a fraction `t` of its length from both ends, every normal face
//! inset (TopMod's fractional planar offset, `extrudeFacePlanarOffset`)
//! and joined to the cut points. TopMod builds it from an extrusion, a
//! trisection and corner cuts, then deletes the extrusion's joins at the
//! old vertices; the result, built here directly, is per face the inset
//! `n`-gon, a quad at each corner `[b(prev c), v(c), a(c), I(c)]` and a
//! quad along each edge `[a(c), b(c), I(next c), I(c)]`, where
//! `v(c) → a(c) → b(c) → v(next c)` is the cut edge's walk.
//!
//! Edges: the three segments of each old edge (numbered as in
//! pentagonalization), then per normal corner `k`: `L` (the inset's edge
//! from `I(c)` to `I(next c)`), `A` (`a(c)` to `I(c)`) and `B` (`I(c)` to
//! `b(prev c)`), side 0 in those directions.

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab};
use crate::SubdivError;
use crate::flat::Flat;

/// One level with thickness `t ∈ [0, ½]`. Output vertices: the input's,
/// the cut points `V + 2e + k` (at `t` from the vertex of corner
/// `edges[e][k]`), the inset corners by normal corner:
/// `I(c) = (1 − 2t) v(c) + t (v(prev c) + v(next c))`.
pub(super) fn step(src: &Flat, budget: &Budget, t: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + 2 * st.e + st.nc,
        e: 3 * st.e + 3 * st.nc,
        f: st.nf + 2 * st.nc + st.hf + st.ps,
        c: 9 * st.nc + 3 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(m.cut_points(t));
    for (_, lo, hi) in m.normal_face_ranges() {
        pos.extend(
            (lo..hi).map(|c| (1.0 - 2.0 * t) * m.p(c) + t * (m.p(src.prev(c)) + m.p(src.next(c)))),
        );
    }
    let (nv, ne, nc) = (st.v, st.e, st.nc);
    let near = |c: usize| (nv + m.cut_point(c, false)) as u32;
    let far = |c: usize| (nv + m.cut_point(c, true)) as u32;
    let inner = |c: usize| (nv + 2 * ne + m.nidx(c)) as u32;
    let l = |c: usize, side: u32| lab(3 * ne + m.nidx(c), side);
    let a_edge = |c: usize, side: u32| lab(3 * ne + nc + m.nidx(c), side);
    let b_edge = |c: usize, side: u32| lab(3 * ne + 2 * nc + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| m.push_thirds(c, nv, hole),
        |b, _, lo, hi| {
            b.walk(false, lo..hi, |c, w| w.push((inner(c), l(c, 0))));
            for c in lo..hi {
                let (p, d) = (src.prev(c), src.next(c));
                b.face(&[
                    (far(p), m.third(p, 2)),
                    (src.cv[c], m.third(c, 0)),
                    (near(c), a_edge(c, 0)),
                    (inner(c), b_edge(c, 0)),
                ]);
                b.face(&[
                    (near(c), m.third(c, 1)),
                    (far(c), b_edge(d, 1)),
                    (inner(d), l(c, 1)),
                    (inner(c), a_edge(c, 1)),
                ]);
            }
        },
    );
    b.finish()
}
