//! Linear vertex insertion (TopMod's `subdivideAllFaces` with quads): the
//! Catmull–Clark connectivity with linear positions. Every edge is split
//! at its midpoint and every face fanned into quads from its centroid.
//!
//! Halves are numbered as in [`super::loop_split`] (edge `e` becomes
//! `2e` and `2e + 1`); the spoke of normal corner `k`, from the midpoint of
//! its edge to the face centroid, is edge `2E + k`, running midpoint →
//! centroid on side 0.

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab};
use crate::SubdivError;
use crate::flat::Flat;

/// One level. Output vertices: the input's (unmoved), the midpoints by
/// edge, the centroids by normal face. Face `f`'s quad at corner `c` is
/// `[v(c), m(c), z_f, m(prev c)]`; a hole of `k` corners becomes one of
/// `2k`.
pub(super) fn step(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.e + st.nf,
        e: 2 * st.e + st.nc,
        f: st.nc + st.hf + st.ps,
        c: 4 * st.nc + 2 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(m.midpoints());
    pos.extend(m.normal_faces().map(|face| m.centroid(face)));
    let (nv, ne) = (st.v as u32, st.e);
    let zbase = nv + ne as u32;
    let ep = |c: usize| nv + m.edge(c) as u32;
    let spoke = |c: usize, side: u32| lab(2 * ne + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| m.push_halves(c, nv as usize, hole),
        |b, face, lo, hi| {
            let z = zbase + m.nrank[face];
            for c in lo..hi {
                let p = src.prev(c);
                b.face(&[
                    (src.cv[c], m.half(c, false)),
                    (ep(c), spoke(c, 0)),
                    (z, spoke(p, 1)),
                    (ep(p), m.half(p, true)),
                ]);
            }
        },
    );
    b.finish()
}
