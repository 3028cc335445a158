//! Pinch: draws the surface under the brush together towards the
//! centre, across the brush normal, sharpening ridges and creases.
//!
//! `u(x) = s · w(x) · P(c − x)`, with `P v = v − (v · N) N` the part
//! across the brush normal `N` ([`Region`]), `c` the brush centre and `s`
//! in `[0, 1]` the share of the way taken per frame (negative spreads).

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of pinch at `centre` on the gathered `region`.
pub fn pinch(mesh: &TriMesh, region: &Region, centre: DVec3, strength: f64) -> Vec<DVec3> {
    region.displaced(mesh, |p, w, _| strength * w * region.across(centre - p))
}
