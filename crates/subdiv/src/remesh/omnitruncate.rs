//! TopMod's dual 12.6.4 remeshing (`dual1264Subdivide`, Bei & Cansin):
//! Doo–Sabin's arrangement of faces with two points per corner. Every
//! face becomes the `2n`-gon through the points at thirds of its edges,
//! every edge a quad and every vertex a `2d`-gon; combinatorially the dual
//! of the barycentric subdivision (the omnitruncation).
//!
//! Written on the closed map with holes treated as faces (a hole's points
//! stay on the boundary, unscaled). Corner `c` (normal or hole corner `k`)
//! owns `T₁(c)` near `v(c)` and `T₂(c)` near `v(next c)` on its edge, as
//! vertices `2k` and `2k + 1`. Edges: `G(c) = k` from `T₁(c)` to `T₂(c)`,
//! `K(c) = C + k` from `T₂(prev c)` to `T₁(c)` (side 0 in the face), and
//! the rungs `2C + 2e + s` across old edge `e` near the vertex of its
//! side-`s` corner `x`, from `T₁(x)` to `T₂(twin x)` on side 0 (in the
//! edge's quad).

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab, scale_about_centroid};
use super::truncation::{next_point_sphere, point_sphere_vertices};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// One level; `scale` as in TopMod: `|scale|`, no scaling for 0 or 1.
pub(super) fn step(src: &Flat, budget: &Budget, scale: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let ac = st.nc + st.hc;
    let sizes = Sizes {
        v: 2 * ac + st.ps,
        e: 2 * ac + 2 * st.e,
        f: st.nf + st.hf + st.e + st.v,
        c: 4 * ac + 4 * st.e + st.ps,
    };
    budget.check(sizes)?;
    let scale = scale.abs();
    let mut pos = Vec::with_capacity(sizes.v);
    let mut pts = Vec::new();
    for face in 0..src.face_count() {
        if m.kind[face] == Kind::PointSphere {
            continue;
        }
        let (lo, hi) = m.range(face);
        pts.clear();
        for c in lo..hi {
            let (p, q) = (m.p(c), m.p(src.next(c)));
            pts.push((2.0 * p + q) / 3.0);
            pts.push((p + 2.0 * q) / 3.0);
        }
        if m.kind[face] == Kind::Normal && scale != 0.0 && scale != 1.0 {
            scale_about_centroid(&mut pts, scale);
        }
        pos.extend_from_slice(&pts);
    }
    let mut ps = point_sphere_vertices(&m, &mut pos);
    let t1 = |c: usize| (2 * m.aidx(c)) as u32;
    let t2 = |c: usize| (2 * m.aidx(c) + 1) as u32;
    let g = |c: usize, side: u32| lab(m.aidx(c), side);
    let k = |c: usize, side: u32| lab(ac + m.aidx(c), side);
    let rung = |x: usize, side: u32| lab(2 * ac + 2 * m.edge(x) + m.side(x) as usize, side);
    let mut b = Builder::new(pos, sizes);
    b.walked_faces(&m, next_point_sphere(&mut ps), |c, w| {
        w.push((t1(c), g(c, 0)));
        w.push((t2(c), k(src.next(c), 0)));
    });
    for &[a, bb] in &src.edges {
        let (a, bb) = (a as usize, bb as usize);
        b.face(&[
            (t2(a), g(a, 1)),
            (t1(a), rung(a, 0)),
            (t2(bb), g(bb, 1)),
            (t1(bb), rung(bb, 0)),
        ]);
    }
    b.vertex_faces(&m, |c, w| {
        let p = src.prev(c);
        w.push((t1(c), k(c, 1)));
        w.push((t2(p), rung(src.twin(p), 1)));
    })?;
    b.finish()
}
