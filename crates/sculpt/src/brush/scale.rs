//! Local scale: grows (positive strength) or shrinks the part of the
//! surface under the brush about the brush centre.
//!
//! `u(x) = s · w(x) · (x − c)`, with `c` the centre and `s` in `[−1, 1]`
//! the relative growth per frame at full weight.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of local scale at `centre` on the gathered `region`.
pub fn scale(mesh: &TriMesh, region: &Region, centre: DVec3, strength: f64) -> Vec<DVec3> {
    region.displaced(mesh, |p, w, _| strength * w * (p - centre))
}
