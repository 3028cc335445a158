//! Grab (Bernstein & Wojtan 2013, §4): the surface near the pick held
//! with weights frozen at the stroke's start and dragged,
//!
//! ```text
//! x(t) = x₀ + s · w(|x₀ − picked|) · (pointer(t) − pointer(0)),
//! ```
//!
//! `s` the strength (1 follows the pointer). The topology changes once,
//! at release ([`crate::live`]). The map folds once the drag exceeds
//! about 0.65 radius (see [`super::snake_hook`], which does not).

use glam::DVec3;
use holey_topo::TriMesh;

use super::{Falloff, referenced};

/// The grab weights of §4: `falloff(|x_v − picked|)` at the stroke's
/// start, zero for vertices no triangle uses.
pub fn grab_weights(mesh: &TriMesh, picked: DVec3, radius: f64) -> Vec<f64> {
    grab_weights_with(mesh, picked, radius, Falloff::Smooth)
}

/// [`grab_weights`] with another falloff curve.
pub fn grab_weights_with(mesh: &TriMesh, picked: DVec3, radius: f64, curve: Falloff) -> Vec<f64> {
    let used = referenced(mesh);
    mesh.positions
        .iter()
        .zip(&used)
        .map(|(&p, &u)| {
            if u {
                curve.weight(p.distance(picked), radius)
            } else {
                0.0
            }
        })
        .collect()
}
