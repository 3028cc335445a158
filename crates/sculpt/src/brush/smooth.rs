//! Smooth (Bernstein & Wojtan 2013, §4): an explicit umbrella-Laplacian
//! step masked by the brush,
//!
//! ```text
//! u(x) = s · w(x) · (mean of x's edge neighbours − x),
//! ```
//!
//! `s` in `[0, 1]` the share of the step, `w` the falloff weight.

use glam::DVec3;
use holey_geom::position_key;
use holey_topo::TriMesh;

use super::{Falloff, coincident, touched};

/// One frame of smooth (§4): an explicit umbrella-Laplacian step, each
/// vertex moving the fraction `strength × falloff` of the way to the mean
/// of its edge neighbours. Jacobi-style (all from the old positions), so
/// the result does not depend on vertex order. Only the touched vertices'
/// rings are gathered. Coincident vertices are one point: they share
/// their rings, and a neighbour position counts once however many
/// vertices sit there, so a soup smooths as its welded surface would.
pub fn smooth(mesh: &TriMesh, centre: DVec3, radius: f64, strength: f64) -> Vec<DVec3> {
    smooth_with(mesh, centre, radius, strength, Falloff::Smooth)
}

/// [`smooth`] with the weight of another falloff curve.
pub fn smooth_with(
    mesh: &TriMesh,
    centre: DVec3,
    radius: f64,
    strength: f64,
    curve: Falloff,
) -> Vec<DVec3> {
    let hit = touched(mesh, centre, radius);
    let class = coincident(mesh, &hit);
    let mut slot = vec![u32::MAX; mesh.positions.len()];
    for (i, &v) in hit.iter().enumerate() {
        slot[v as usize] = class[i];
    }
    let mut rings: Vec<Vec<[u64; 3]>> = vec![Vec::new(); hit.len()];
    let key = |v: u32| position_key(mesh.positions[v as usize]);
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if key(a) == key(b) {
                continue;
            }
            if let Some(r) = rings.get_mut(slot[a as usize] as usize) {
                r.push(key(b));
            }
            if let Some(r) = rings.get_mut(slot[b as usize] as usize) {
                r.push(key(a));
            }
        }
    }
    for ring in &mut rings {
        ring.sort_unstable();
        ring.dedup();
    }
    let mut out = mesh.positions.clone();
    for (&v, &c) in hit.iter().zip(&class) {
        let ring = &rings[c as usize];
        let p = mesh.positions[v as usize];
        let w = strength * curve.weight(p.distance(centre), radius);
        if w == 0.0 || ring.is_empty() {
            continue;
        }
        let mean = ring
            .iter()
            .map(|k| {
                DVec3::new(
                    f64::from_bits(k[0]),
                    f64::from_bits(k[1]),
                    f64::from_bits(k[2]),
                )
            })
            .sum::<DVec3>()
            / ring.len() as f64;
        out[v as usize] = p + w * (mean - p);
    }
    out
}
