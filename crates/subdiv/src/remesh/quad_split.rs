//! Linear vertex insertion (TopMod's `subdivideAllFaces` with quads): the
//! Catmull–Clark connectivity with linear positions. Every edge is split
//! at its midpoint and every face fanned into quads from its centroid.
//!
//! Halves are numbered as in [`super::loop_split`] (edge `e` becomes
//! `2e` and `2e + 1`); the spoke of normal corner `k`, from the midpoint of
//! its edge to the face centroid, is edge `2E + k`, running midpoint →
//! centroid on side 0.

use super::map::{Budget, Builder, Map, Sizes, lab};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

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
    let mut pos = Vec::with_capacity(sizes.v);
    pos.extend_from_slice(&src.pos);
    pos.extend(
        src.edges
            .iter()
            .map(|&[a, b]| 0.5 * (m.p(a as usize) + m.p(b as usize))),
    );
    for face in 0..src.face_count() {
        if m.kind[face] == Kind::Normal {
            pos.push(m.centroid(face));
        }
    }
    let (nv, ne) = (st.v as u32, st.e);
    let zbase = nv + ne as u32;
    let ep = |c: usize| nv + m.edge(c) as u32;
    let half = |c: usize, second: bool| {
        let (e, s) = (m.edge(c), m.side(c));
        let k = if second { 1 - s } else { s };
        lab(2 * e + k as usize, s)
    };
    let spoke = |c: usize, side: u32| lab(2 * ne + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    let mut hole = Vec::new();
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        match m.kind[face] {
            Kind::PointSphere => b.point_sphere(src.cv[lo], src.hole[face]),
            Kind::Hole => {
                hole.clear();
                for c in lo..hi {
                    hole.push((src.cv[c], half(c, false)));
                    hole.push((ep(c), half(c, true)));
                }
                b.face(true, &hole);
            }
            Kind::Normal => {
                let z = zbase + m.nrank[face];
                for c in lo..hi {
                    let p = src.prev(c);
                    b.face(
                        false,
                        &[
                            (src.cv[c], half(c, false)),
                            (ep(c), spoke(c, 0)),
                            (z, spoke(p, 1)),
                            (ep(p), half(p, true)),
                        ],
                    );
                }
            }
        }
    }
    b.finish()
}
