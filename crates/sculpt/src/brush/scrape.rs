//! Scrape: flattens only what stands above the brush plane, cutting
//! bumps down and leaving hollows alone.
//!
//! `u(x) = s · w(x) · min((o − x) · N, 0) · N`, with `o` and `N` the
//! brush plane's point and normal ([`Region`]) and `s` in `[0, 1]`.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of scrape on the gathered `region`.
pub fn scrape(mesh: &TriMesh, region: &Region, strength: f64) -> Vec<DVec3> {
    let n = region.normal;
    region.displaced(mesh, |p, w, _| {
        strength * w * (-region.height(p)).min(0.0) * n
    })
}
