//! Inflate (Bernstein & Wojtan 2013, §4): every vertex within the radius
//! moves along its own area-weighted normal,
//!
//! ```text
//! u(x) = s · w(x) · n(x),
//! ```
//!
//! `s` in world units per frame (negative deflates), `w` the falloff
//! weight, `n(x)` the vertex normal.

use glam::DVec3;
use holey_topo::TriMesh;

use super::{Falloff, normals_of, touched};

/// One frame of inflate (§4): every vertex within `radius` of `centre`
/// moves along its (area-weighted) normal by `strength × falloff`.
/// Normals are computed only for the vertices the brush touches, so the
/// cost beyond two linear scans is the brush's. Coincident vertices move
/// as one point.
pub fn inflate(mesh: &TriMesh, centre: DVec3, radius: f64, strength: f64) -> Vec<DVec3> {
    inflate_with(mesh, centre, radius, strength, Falloff::Smooth)
}

/// [`inflate`] with another falloff curve. Like smooth, and unlike the
/// sculptor's brushes ([`super::region`]), it moves every vertex within the
/// radius, whichever sheet it is on, as §4 does.
pub fn inflate_with(
    mesh: &TriMesh,
    centre: DVec3,
    radius: f64,
    strength: f64,
    curve: Falloff,
) -> Vec<DVec3> {
    let hit = touched(mesh, centre, radius);
    let normals = normals_of(mesh, &hit);
    let mut out = mesh.positions.clone();
    for (&v, n) in hit.iter().zip(&normals) {
        let p = out[v as usize];
        out[v as usize] = p + *n * (strength * curve.weight(p.distance(centre), radius));
    }
    out
}
