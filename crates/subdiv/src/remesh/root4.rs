//! Root-4 remeshing (TopMod's `root4Subdivide`, also its "hexagon
//! preserving" entry): every normal face shrinks to a copy joined to it
//! corner by corner (an extrusion without length), then every old edge
//! between two faces is deleted, merging the two quads beside it into a
//! hexagon.
//!
//! Copy vertex `I(c)` (normal corner `k`) is joined to `v(c)` by edge
//! `J(c)` (side 0 runs `v → I`); the copy's edge from `I(c)` to
//! `I(next c)` is `L(c)` (side 0 in the copy). Edge `(a, b)` between faces
//! becomes the hexagon `[v(a), I(next b), I(b), v(b), I(next a), I(a)]`.
//! An edge next to a hole is kept, and its normal side keeps the quad
//! `[v(a), v(next a), I(next a), I(a)]`.

use glam::DVec3;

use super::Root4Params;
use super::build::{Budget, Builder, Sizes};
use super::map::{Map, honeycomb_alpha, lab, move_interior, tension_mask};
use crate::SubdivError;
use crate::flat::Flat;

/// One level. Output vertices: the input's, then `I(c)` by normal corner.
/// Edges: the kept old edges, then `L`, then `J`, each by normal corner.
pub(super) fn step(src: &Flat, budget: &Budget, params: Root4Params) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.nc,
        e: st.kept_edge_count() + 2 * st.nc,
        f: st.nf + st.e_nn + st.b_sides + st.hf + st.ps,
        c: st.nc + 6 * st.e_nn + 4 * st.b_sides + st.hc + st.ps,
    };
    budget.check(sizes)?;
    let pos = positions(&m, sizes.v, params);
    let kept = m.kept_edges();
    let old = |c: usize| lab(kept[m.edge(c)] as usize, m.side(c));
    let inner = |c: usize| (st.v + m.nidx(c)) as u32;
    let l = |c: usize, side: u32| lab(st.kept_edge_count() + m.nidx(c), side);
    let j = |c: usize, side: u32| lab(st.kept_edge_count() + st.nc + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| hole.push((src.cv[c], old(c))),
        |b, _, lo, hi| {
            b.walk(false, lo..hi, |c, w| w.push((inner(c), l(c, 0))));
            for (c, d) in m.boundary_corners(lo, hi) {
                b.face(&[
                    (src.cv[c], old(c)),
                    (src.cv[d], j(d, 0)),
                    (inner(d), l(c, 1)),
                    (inner(c), j(c, 1)),
                ]);
            }
        },
    );
    for (_, a, bb, na, nb) in m.interior_edges() {
        b.face(&[
            (src.cv[a], j(nb, 0)),
            (inner(nb), l(bb, 1)),
            (inner(bb), j(bb, 1)),
            (src.cv[bb], j(na, 0)),
            (inner(na), l(a, 1)),
            (inner(a), j(a, 1)),
        ]);
    }
    b.finish()
}

/// The copies: TopMod's mask (α = 1/√2 − 1/4 + 5/(4n)) of the points at
/// `twist` along each edge; then each interior old vertex moved by
/// `weight` towards the average of the copy vertices joined to it (TopMod
/// moves it towards the midpoints of its edges after the old edges are
/// gone, which are these). Boundary vertices stay.
fn positions(m: &Map, nv: usize, params: Root4Params) -> Vec<DVec3> {
    let Root4Params { weight, twist } = params;
    let src = m.f;
    let mut pos = m.kept_positions(nv);
    let mut pts = Vec::new();
    let mut out = Vec::new();
    for (_, lo, hi) in m.normal_face_ranges() {
        pts.clear();
        pts.extend((lo..hi).map(|c| (1.0 - twist) * m.p(c) + twist * m.p(src.next(c))));
        out.clear();
        out.resize(hi - lo, DVec3::ZERO);
        tension_mask(&pts, honeycomb_alpha, &mut out);
        pos.extend_from_slice(&out);
    }
    if weight != 0.0 {
        let sums = m.interior_sums(|c| pos[src.pos.len() + m.nidx(c)]);
        move_interior(&mut pos, sums, |p, sum, k| {
            (1.0 - weight) * p + weight * sum / k
        });
    }
    pos
}
