//! Snap rounding of a winding-number result whose rounded points cross.
//!
//! The arrangement is exact, but its constructed points are rounded to
//! f64 on output. Where two sheets nearly coincide (shells offset by a
//! few ulps, coplanar faces a rounding apart), the exact result holds
//! wedges a hair wide: rounding a point by an ulp moves it across the
//! other side of its wedge, and the rounded result crosses itself,
//! though its volume and inside are still right.
//!
//! The cure is iterated snap rounding in the manner of CGAL's triangle
//! soup autorefinement (Lazard & Valque's iterative snap rounding): put
//! every point on a grid of power-of-two step h, which makes sheets
//! nearer than h coincide exactly (and the coincident parts cancel or
//! merge exactly in the coplanar overlay, [`crate::coplanar`]); resolve
//! what the snap made cross by the winding number of the snapped surface
//! (its union with nothing: the boundary of {w ≥ 1}); check the result
//! exactly; where it still crosses, snap again on a coarser grid.
//!
//! The grid step is scale-relative, never absolute: 2^m units in the last
//! place of the largest coordinate (m = 8, 14, 20 in turn), so a snap
//! moves each point by at most √3·h/2, below 2^(m−53) of the largest
//! coordinate. Dividing by a power of two, rounding to an integer and
//! multiplying back are exact in floating point, so the snapped points
//! are exactly on the grid.
//!
//! The exact result of closed inputs is closed and consistently oriented
//! (but where rounding left a slit: see [`snap_rounded`]), so its winding
//! number is an integer off it; the snapped surface's differs from it
//! only within √3·h/2 of the surface, where the snap moved it.

use std::time::Instant;

use glam::DVec3;

use crate::engine::Options;
use crate::intersect::{IntersectError, intersecting_pair_count};
use crate::mesh::TriMesh;
use crate::union::Operation;
use crate::winding_boolean::{WindingError, WindingOutcome, boolean_by_winding};

/// The grid steps tried, as base-2 logarithms of units in the last place
/// of the largest coordinate: 256, 16,384 and 1,048,576 ulps. On
/// `Offset1 ∩ Offset2` (coordinates near 2·10⁴) 4 ulps left 5 crossing
/// pairs and 256 none.
pub(crate) const SNAP_ULPS_LOG2: [i32; 3] = [8, 14, 20];

/// Rounds of snapping and resolving on one grid before a coarser one is
/// tried. Resolving a snapped surface constructs new points, which are
/// rounded again; on `Offset1 ∪ Offset2` each grid needed two or three
/// rounds (the first left 3 to 7 crossing pairs, the second none or a
/// few open edges).
pub(crate) const SNAP_ROUNDS: usize = 3;

/// What snap rounding did to a result.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SnapRounding {
    /// The grid step the result's points were snapped to.
    pub grid: f64,
    /// Points of the exact result the snap moved.
    pub moved_points: usize,
    /// Grids tried, this one included.
    pub grids_tried: usize,
    /// Rounds of snapping and resolving on this grid.
    pub rounds: usize,
    /// Seconds spent snapping, resolving and checking, every grid tried.
    pub seconds: f64,
}

/// The power-of-two grid step 2^`ulps_log2` units in the last place of
/// the largest coordinate magnitude of `positions`; `None` for no
/// positions, or positions all zero or too small for a normal step.
pub(crate) fn grid_step(positions: &[DVec3], ulps_log2: i32) -> Option<f64> {
    let largest = positions
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0_f64, f64::max);
    if !largest.is_normal() {
        return None;
    }
    // The unbiased binary exponent of a normal f64.
    let exponent = ((largest.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let step = 2f64.powi(exponent - 52 + ulps_log2);
    step.is_normal().then_some(step)
}

/// `positions` on the grid of step `h` (a power of two), and how many
/// moved. Exact: x / h and k · h only shift the exponent.
pub(crate) fn snapped_to_grid(positions: &[DVec3], h: f64) -> (Vec<DVec3>, usize) {
    let snapped: Vec<DVec3> = positions.iter().map(|p| (*p / h).round() * h).collect();
    let moved = positions
        .iter()
        .zip(&snapped)
        .filter(|(p, q)| p != q)
        .count();
    (snapped, moved)
}

/// `exact`, the result of [`boolean_by_winding`], snap-rounded until it
/// is a closed 2-manifold that crosses itself nowhere (checked exactly),
/// on the first grid of [`SNAP_ULPS_LOG2`] that gives one. Its report is
/// `exact`'s, with the shape of the snapped result, its crossings (0),
/// and [`SnapRounding`]. `None` when an input was open (the result's
/// winding number would be fractional by design), the result has no
/// points, or no grid gives a clean result.
///
/// A result of closed inputs left open by rounding (a few edges unpaired
/// where a constructed point missed the vertex it should be) is snapped
/// too: its generalized winding number is an integer but within reach of
/// those slits, which are a rounding wide, and the snap's result must
/// itself be closed to be kept.
pub(crate) fn snap_rounded(
    exact: &WindingOutcome,
    options: &Options,
) -> Result<Option<WindingOutcome>, WindingError> {
    let started = Instant::now();
    if !exact.report.inputs_closed.iter().all(|&c| c) || exact.mesh.triangles.is_empty() {
        return Ok(None);
    }
    for (tried, &ulps_log2) in (1..).zip(&SNAP_ULPS_LOG2) {
        let Some(h) = grid_step(&exact.mesh.positions, ulps_log2) else {
            return Ok(None);
        };
        let mut current = std::borrow::Cow::Borrowed(&exact.mesh);
        let mut moved = 0;
        // Defects (open and non-manifold edges, pinched vertices and
        // crossing pairs) before the round: another round on this grid
        // only while they fall.
        let mut before = exact.report.shape_defects()
            + exact
                .report
                .output_intersecting_pairs
                .unwrap_or(usize::MAX / 2);
        for round in 1..=SNAP_ROUNDS {
            let (positions, n) = snapped_to_grid(&current.positions, h);
            moved += n;
            let snapped = TriMesh {
                positions,
                triangles: current.triangles.clone(),
            };
            let resolved = boolean_by_winding(&[&snapped], Operation::Union, options)?;
            let report = &resolved.report;
            let shape = report.shape_defects();
            // Counted up to where the round would be no better.
            let limit = before.saturating_sub(shape + 1);
            let crossing = match intersecting_pair_count(&resolved.mesh, limit) {
                Ok(n) => n,
                Err(IntersectError::TooManyPairs { .. }) => limit + 1,
                Err(e) => return Err(crate::engine::TopoError::from(e).into()),
            };
            if shape == 0 && crossing == 0 {
                let mut report = exact.report.clone();
                report.unpaired_edges = 0;
                report.nonmanifold_edges = 0;
                report.pinched_vertices = 0;
                report.output_intersecting_pairs = Some(0);
                report.snap_rounding = Some(SnapRounding {
                    grid: h,
                    moved_points: moved,
                    grids_tried: tried,
                    rounds: round,
                    seconds: started.elapsed().as_secs_f64(),
                });
                return Ok(Some(WindingOutcome {
                    mesh: resolved.mesh,
                    report,
                }));
            }
            if shape + crossing >= before {
                break;
            }
            before = shape + crossing;
            current = std::borrow::Cow::Owned(resolved.mesh);
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step is a power of two, 2^m ulps of the largest magnitude, for
    /// coordinates at any scale and offset; nothing for no scale.
    #[test]
    fn grid_step_is_relative_to_the_largest_coordinate() {
        let at = |x: f64| [DVec3::new(x, -0.5 * x, 0.25 * x)];
        for (x, m) in [(1.0, 8), (1.5e6, 8), (-3.0e-6, 14), (4096.5, 20)] {
            let h = grid_step(&at(x), m).unwrap();
            let ulp = {
                let a = x.abs();
                f64::from_bits(a.to_bits() + 1) - a
            };
            assert_eq!(h, ulp * 2f64.powi(m), "{x}");
            assert_eq!(h.to_bits() & ((1 << 52) - 1), 0, "{x}: not a power of two");
        }
        assert_eq!(grid_step(&[], 8), None);
        assert_eq!(grid_step(&[DVec3::ZERO], 8), None);
        assert_eq!(grid_step(&[DVec3::splat(1e-300)], 8), None);
    }

    /// Snapping puts every coordinate on the grid, within h/2 of where it
    /// was, and moves nothing already on it.
    #[test]
    fn snapping_lands_on_the_grid_within_half_a_step() {
        let positions: Vec<DVec3> = (0..200)
            .map(|i| {
                let t = i as f64 * 0.618_033_988_749_895;
                DVec3::new(t.sin() * 3.1, t.cos() * 1e3, 4096.0 + t)
            })
            .collect();
        let h = grid_step(&positions, 14).unwrap();
        let (snapped, moved) = snapped_to_grid(&positions, h);
        assert!(moved > 0);
        for (p, q) in positions.iter().zip(&snapped) {
            assert!((*p - *q).abs().max_element() <= 0.5 * h, "{p} → {q}");
            for x in q.to_array() {
                assert_eq!((x / h).fract(), 0.0, "{x} is off the grid {h}");
            }
        }
        let (again, none) = snapped_to_grid(&snapped, h);
        assert_eq!((again, none), (snapped, 0));
    }
}
