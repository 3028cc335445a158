//! Clay: adds material up to a plane just above the surface, flattening
//! as it builds (negative strength removes down to a plane below).
//!
//! With the brush plane through the weighted centroid `o` with normal
//! `N` ([`Region`]) raised by `s`, a vertex at height
//! `h(x) = (o + sN − x) · N` below it moves by
//! `u(x) = w(x) · clamp(h(x), min(0, s), max(0, s)) · N`:
//! points under the raised plane come up to it (by at most `s` a frame),
//! points already above it stay, so the strokes lay flat slabs.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of clay on the gathered `region`.
pub fn clay(mesh: &TriMesh, region: &Region, strength: f64) -> Vec<DVec3> {
    let n = region.normal;
    let (lo, hi) = (strength.min(0.0), strength.max(0.0));
    region.displaced(mesh, |p, w, _| {
        let h = strength - region.height(p);
        w * h.clamp(lo, hi) * n
    })
}
