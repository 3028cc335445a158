//! Layer: raises the part of the surface under the brush to a plateau a
//! fixed height above where it was when the stroke began, however long
//! the brush dwells or however often it passes back (negative strength
//! sinks it). A stroke lays one even slab, not a pile.
//!
//! With `h` the strength (world units), `w(x)` the falloff weight, `N`
//! the brush normal ([`Region`]) and `a(x)` the height the stroke has
//! already added at `x`, one frame moves a vertex by
//!
//! ```text
//! u(x) = clamp(h · w(x) − a(x), min(0, h/2), max(0, h/2)) · N,
//! ```
//!
//! towards the plateau `h · w` and never past it, at most `h/2` a frame
//! (so a dwell reaches the plateau in two frames at the centre, and a
//! single frame cannot fold the surface more than half a layer).
//!
//! `a` is kept by the stroke, keyed by exact position (a vertex the
//! layer moved is named by where it went, which stays true across the
//! topology changes and remeshing that renumber vertices). A vertex the
//! stroke has not seen, such as one remeshing made by splitting an edge
//! of the slab, takes the mean height of its seen neighbours (0 if
//! none), so a split does not raise a bump.

use std::collections::HashMap;

use glam::DVec3;
use holey_geom::position_key;
use holey_topo::TriMesh;

use super::region::Region;

/// Heights a stroke has added so far, by exact position.
pub type Heights = HashMap<[u64; 3], f64>;

/// One frame of layer on the gathered `region`, recording in `heights`
/// the height each moved vertex reaches, under its new position.
pub fn layer(mesh: &TriMesh, region: &Region, strength: f64, heights: &mut Heights) -> Vec<DVec3> {
    let n = region.normal;
    let added = seen_heights(mesh, region, heights);
    let (lo, hi) = (0.5 * strength.min(0.0), 0.5 * strength.max(0.0));
    let mut out = mesh.positions.clone();
    for ((&v, &w), &a) in region.vertices.iter().zip(&region.weights).zip(&added) {
        if w == 0.0 {
            continue;
        }
        let step = (strength * w - a).clamp(lo, hi);
        if step == 0.0 {
            continue;
        }
        let q = mesh.positions[v as usize] + step * n;
        out[v as usize] = q;
        heights.insert(position_key(q), a + step);
    }
    out
}

/// The height already added at each region vertex: its own, or the mean
/// of its seen neighbours', or 0.
fn seen_heights(mesh: &TriMesh, region: &Region, heights: &Heights) -> Vec<f64> {
    let own: Vec<Option<f64>> = region
        .vertices
        .iter()
        .map(|&v| {
            heights
                .get(&position_key(mesh.positions[v as usize]))
                .copied()
        })
        .collect();
    if own.iter().all(Option::is_some) || heights.is_empty() {
        return own.into_iter().map(|a| a.unwrap_or(0.0)).collect();
    }
    let mut slot = vec![u32::MAX; mesh.positions.len()];
    for (i, &v) in region.vertices.iter().enumerate() {
        slot[v as usize] = i as u32;
    }
    let mut sums = vec![(0.0, 0usize); own.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (v, x) = (t[k], t[(k + 1) % 3]);
            for (a, b) in [(v, x), (x, v)] {
                let i = slot[a as usize] as usize;
                if i >= own.len() || own[i].is_some() {
                    continue;
                }
                let seen = match slot.get(b as usize).map(|&j| j as usize) {
                    Some(j) if j < own.len() => own[j],
                    _ => heights
                        .get(&position_key(mesh.positions[b as usize]))
                        .copied(),
                };
                if let Some(h) = seen {
                    sums[i].0 += h;
                    sums[i].1 += 1;
                }
            }
        }
    }
    own.iter()
        .zip(&sums)
        .map(|(a, &(sum, count))| a.unwrap_or(if count > 0 { sum / count as f64 } else { 0.0 }))
        .collect()
}
