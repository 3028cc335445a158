//! Honeycomb remeshing (TopMod's `honeycombSubdivide`): every face shrinks
//! to a copy with one vertex per edge, the copies are joined by one edge
//! across each old edge, and each old vertex of valence `d` becomes a
//! `2d`-gon. On a trivalent (hexagonal) mesh every face stays a hexagon;
//! TopMod's root-3 is the dual of this scheme applied to the dual.
//!
//! Written on the closed map with holes treated as faces: the copy of a
//! hole is a hole through its edge midpoints. Copy vertex `I(c)` belongs
//! to corner `c` (normal or hole corner `k`) and to `c`'s edge; the copy's
//! edge from `I(c)` to `I(next c)` is edge `k` (side 0 in the copy), and
//! the edge across old edge `e` is edge `C + e`, whose side is that of the
//! corner it leaves from.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, honeycomb_alpha, lab, tension_mask};
use super::truncation::{next_point_sphere, point_sphere_vertices};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// One level. Output vertices: `I(c)` by normal and hole corner, then the
/// point-spheres'.
pub(super) fn step(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let ac = st.nc + st.hc;
    let sizes = Sizes {
        v: ac + st.ps,
        e: ac + st.e,
        f: st.nf + st.hf + st.v,
        c: 3 * ac + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = Vec::with_capacity(sizes.v);
    let mut mids = Vec::new();
    let mut out = Vec::new();
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        if m.kind[face] == Kind::PointSphere {
            continue;
        }
        mids.clear();
        mids.extend((lo..hi).map(|c| 0.5 * (m.p(c) + m.p(src.next(c)))));
        if m.kind[face] == Kind::Hole {
            pos.extend_from_slice(&mids);
        } else {
            out.clear();
            out.resize(hi - lo, DVec3::ZERO);
            tension_mask(&mids, honeycomb_alpha, &mut out);
            pos.extend_from_slice(&out);
        }
    }
    let mut ps = point_sphere_vertices(&m, &mut pos);
    let copy = |c: usize| m.aidx(c) as u32;
    let mut b = Builder::new(pos, sizes);
    b.walked_faces(&m, next_point_sphere(&mut ps), |c, w| {
        w.push((copy(c), lab(m.aidx(c), 0)));
    });
    b.vertex_faces(&m, |c, w| {
        let p = src.prev(c);
        w.push((copy(c), lab(m.aidx(p), 1)));
        w.push((copy(p), lab(ac + m.edge(p), m.side(p))));
    })?;
    b.finish()
}
