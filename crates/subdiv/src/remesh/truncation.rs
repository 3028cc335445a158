//! Vertex truncation (TopMod's `vertexCuttingSubdivide`) and the simplest
//! scheme (Peters & Reif 1997, TopMod's `simplestSubdivide`, truncation at
//! one half where the two cut points of an edge are one).
//!
//! Both are written on the closed map with holes treated as faces: every
//! face (normal or hole) becomes the polygon of the cut points along its
//! walk, every vertex the polygon of the cut edges around it, in the
//! backward rotation. The cut edge of corner `c` (normal or hole corner `k`)
//! runs, inside `c`'s face, from the point on `prev c`'s edge to the point
//! on `c`'s edge on side 0, and back on side 1 in the vertex's polygon.
//! A boundary loop is thereby truncated too, like a Chaikin step.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// Vertex truncation at `offset ∈ (0, ½)`. Output vertex `2e + k` is the
/// point of edge `e` at `offset` from the vertex of its corner
/// `edges[e][k]`; point-sphere vertices follow. Edges: the middle of old
/// edge `e` keeps number `e`; cut edges follow by corner.
pub(super) fn truncate(src: &Flat, budget: &Budget, offset: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let ac = st.nc + st.hc;
    let sizes = Sizes {
        v: 2 * st.e + st.ps,
        e: st.e + ac,
        f: st.nf + st.hf + st.v,
        c: 3 * ac + st.ps,
    };
    budget.check(sizes)?;
    let mut pos: Vec<DVec3> = Vec::with_capacity(sizes.v);
    pos.extend(m.cut_points(offset));
    let mut ps = point_sphere_vertices(&m, &mut pos);
    let point = |c: usize, far: bool| m.cut_point(c, far) as u32;
    let cut = |c: usize, side: u32| lab(st.e + m.aidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.walked_faces(&m, next_point_sphere(&mut ps), |c, w| {
        w.push((point(c, false), m.own(c)));
        w.push((point(c, true), cut(src.next(c), 0)));
    });
    b.vertex_faces(&m, |c, w| w.push((point(c, false), cut(c, 1))))?;
    b.finish()
}

/// The simplest scheme: output vertex `e` is the midpoint of edge `e`,
/// point-sphere vertices follow; the cut edge of corner `k` is edge `k`.
pub(super) fn simplest(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let ac = st.nc + st.hc;
    let sizes = Sizes {
        v: st.e + st.ps,
        e: ac,
        f: st.nf + st.hf + st.v,
        c: 2 * ac + st.ps,
    };
    budget.check(sizes)?;
    let mut pos: Vec<DVec3> = Vec::with_capacity(sizes.v);
    pos.extend(m.midpoints());
    let mut ps = point_sphere_vertices(&m, &mut pos);
    let cut = |c: usize, side: u32| lab(m.aidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.walked_faces(&m, next_point_sphere(&mut ps), |c, w| {
        w.push((m.edge(c) as u32, cut(src.next(c), 0)));
    });
    b.vertex_faces(&m, |c, w| w.push((m.edge(c) as u32, cut(c, 1))))?;
    b.finish()
}

/// Appends the point-spheres' positions to `pos`, in face order, and
/// returns the output vertex of the first.
pub(super) fn point_sphere_vertices(m: &Map, pos: &mut Vec<DVec3>) -> u32 {
    let first = pos.len() as u32;
    for face in 0..m.f.face_count() {
        if m.kind[face] == Kind::PointSphere {
            pos.push(m.p(m.f.off[face] as usize));
        }
    }
    first
}

/// The output vertices of the point-spheres one after the other, from the
/// first at `*ps`: what [`Builder::walked_faces`] asks for each.
pub(super) fn next_point_sphere(ps: &mut u32) -> impl FnMut(usize) -> u32 + '_ {
    move |_| {
        *ps += 1;
        *ps - 1
    }
}
