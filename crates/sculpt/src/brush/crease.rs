//! Crease: cuts a sharp groove, drawing inwards while pinching the sides
//! together (negative strength raises a sharp ridge).
//!
//! `u(x) = −s · w(x)² · N + (|s| / r) · w(x) · P(c − x)`, with `N` the
//! brush normal, `P` the projection across it ([`Region::across`]), `c`
//! the centre, `r` the radius and `s` in world units per frame. The
//! squared weight makes the groove narrower than the brush; the pinch
//! moves a vertex at distance `d` by at most `|s| · d / r ≤ |s|`. Pressed
//! on through a thin wall, the groove meets the far side and the engine
//! opens a slit there.

use glam::DVec3;
use holey_topo::TriMesh;

use super::region::Region;

/// One frame of crease at `centre` on the gathered `region`.
pub fn crease(
    mesh: &TriMesh,
    region: &Region,
    centre: DVec3,
    radius: f64,
    strength: f64,
) -> Vec<DVec3> {
    let n = region.normal;
    let pinch = if radius > 0.0 {
        strength.abs() / radius
    } else {
        0.0
    };
    region.displaced(mesh, |p, w, _| {
        -strength * w * w * n + pinch * w * region.across(centre - p)
    })
}
