//! The dual ([`RemeshScheme::Dual`](super::RemeshScheme::Dual)), TopMod's
//! `createDual`: a vertex at the centroid of each face, a face around each
//! vertex, an edge across each edge. The building block of every "dual …"
//! scheme.
//!
//! On the combinatorial map the dual face of vertex `v` visits, for each
//! corner `c` of `v` in the backward rotation `c → twin(prev c)`, the
//! vertex of face `f(c)`, and leaves it across edge `prev c`; the side of
//! that dual edge is the side of corner `prev c`, so the two dual faces
//! meeting across an edge take its two sides. A point-sphere is its own
//! dual.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::Map;
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// One dual of a closed map. Output vertex `f` is input face `f`; the
/// faces follow the input's vertices, point-spheres last.
pub(super) fn step(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    if st.hf > 0 {
        return Err(SubdivError::Boundary {
            scheme: budget.scheme,
            holes: st.hf,
        });
    }
    let sizes = Sizes {
        v: st.nf + st.ps,
        e: st.e,
        f: st.v,
        c: st.nc + st.ps,
    };
    budget.check(sizes)?;
    let pos: Vec<DVec3> = (0..src.face_count())
        .map(|face| match m.kind[face] {
            Kind::PointSphere => m.p(src.off[face] as usize),
            _ => m.centroid(face),
        })
        .collect();
    let mut b = Builder::new(pos, sizes);
    b.vertex_faces(&m, |c, w| w.push((src.cf[c], m.own(src.prev(c)))))?;
    for face in 0..src.face_count() {
        if m.kind[face] == Kind::PointSphere {
            b.point_sphere(face as u32, src.hole[face]);
        }
    }
    b.finish()
}
