//! Flatten: pulls the surface under the brush towards the brush plane
//! from both sides.
//!
//! `u(x) = s · w(x) · ((o − x) · N) · N`, with `o` and `N` the brush
//! plane's point and normal ([`Region`]) and `s` in `[0, 1]` the share of
//! the way to the plane taken per frame.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of flatten on the gathered `region`.
pub fn flatten(mesh: &TriMesh, region: &Region, strength: f64) -> Vec<DVec3> {
    let n = region.normal;
    region.displaced(mesh, |p, w, _| -strength * w * region.height(p) * n)
}
