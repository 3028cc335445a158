//! Draw: raises the surface under the brush along the brush's normal
//! (negative strength carves).
//!
//! `u(x) = s · w(x) · N`, with `w` the falloff weight and `N` the brush's
//! normal ([`Region::normal`]), `s` in world units per frame. Unlike
//! inflate, which pushes each vertex along its own normal, every vertex
//! moves the same way, so a stroke builds a ridge instead of a balloon.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of draw on the gathered `region`.
pub fn draw(mesh: &TriMesh, region: &Region, strength: f64) -> Vec<DVec3> {
    let n = region.normal;
    region.displaced(mesh, |_, w, _| strength * w * n)
}
