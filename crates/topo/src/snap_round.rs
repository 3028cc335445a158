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
//! (but where rounding left a slit: see `winding_boolean::snap_rounded`),
//! so its winding number is an integer off it; the snapped surface's
//! differs from it only within √3·h/2 of the surface, where the snap
//! moved it.

use std::time::Instant;

use glam::DVec3;

use crate::mesh::TriMesh;

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
    let exponent = holey_geom::expansion::exponent_of(largest);
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

/// `mesh` snap-rounded until `resolve` calls it clean, on the first grid
/// of [`SNAP_ULPS_LOG2`] that gives a clean result, and how.
///
/// `resolve(snapped, before)` resolves a snapped surface (by its winding
/// number: [`crate::winding_boolean`]) and counts its defects (open and
/// non-manifold edges, pinched vertices, crossing pairs), any count at or
/// above `before` standing for "no better". `defects` are `mesh`'s own.
/// On one grid the rounds go on from the last result, up to
/// [`SNAP_ROUNDS`], while the defects fall; each grid starts from `mesh`.
/// `None` when `mesh` has no scale (no grid) or no grid gives a clean
/// result.
pub(crate) fn snap_round<E>(
    mesh: &TriMesh,
    defects: usize,
    mut resolve: impl FnMut(&TriMesh, usize) -> Result<(TriMesh, usize), E>,
) -> Result<Option<(TriMesh, SnapRounding)>, E> {
    let started = Instant::now();
    for (tried, &ulps_log2) in (1..).zip(&SNAP_ULPS_LOG2) {
        let Some(h) = grid_step(&mesh.positions, ulps_log2) else {
            return Ok(None);
        };
        let mut current = std::borrow::Cow::Borrowed(mesh);
        let mut moved = 0;
        let mut before = defects;
        for round in 1..=SNAP_ROUNDS {
            let (positions, n) = snapped_to_grid(&current.positions, h);
            moved += n;
            let snapped = TriMesh {
                positions,
                triangles: current.triangles.clone(),
            };
            let (resolved, left) = resolve(&snapped, before)?;
            if left == 0 {
                let how = SnapRounding {
                    grid: h,
                    moved_points: moved,
                    grids_tried: tried,
                    rounds: round,
                    seconds: started.elapsed().as_secs_f64(),
                };
                return Ok(Some((resolved, how)));
            }
            if left >= before {
                break;
            }
            before = left;
            current = std::borrow::Cow::Owned(resolved);
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

    /// The rounds on one grid go on while the defects fall and stop when
    /// they do not; the next grid starts again from the mesh; the first
    /// clean result is kept, with the grid, the rounds and the points
    /// moved. A resolver that never cleans gives `None` after every grid.
    #[test]
    fn rounds_go_on_while_the_defects_fall_and_grids_coarsen() {
        let mesh = TriMesh {
            positions: vec![
                DVec3::new(0.1, 0.2, 0.3),
                DVec3::new(1.7, 0.2, 0.3),
                DVec3::new(0.1, 1.9, 0.3),
            ],
            triangles: vec![[0, 1, 2]],
        };
        // Defects after each call: grid 1 falls to 5, then rises to 7
        // (stop); grid 2 falls to 3, then 0 (clean).
        let script = [5, 7, 3, 0];
        let mut calls = Vec::new();
        let found = snap_round(&mesh, 10, |snapped: &TriMesh, before| {
            calls.push((snapped.positions.clone(), before));
            Ok::<_, ()>((snapped.clone(), script[calls.len() - 1]))
        })
        .unwrap()
        .expect("clean on the second grid");
        let h2 = grid_step(&mesh.positions, SNAP_ULPS_LOG2[1]).unwrap();
        assert_eq!(
            (found.1.grid, found.1.grids_tried, found.1.rounds),
            (h2, 2, 2)
        );
        assert_eq!(found.1.moved_points, 3, "moved on the first round only");
        let befores: Vec<usize> = calls.iter().map(|c| c.1).collect();
        assert_eq!(befores, [10, 5, 10, 3]);
        // Each grid's first round starts from the mesh itself.
        assert_eq!(calls[2].0, snapped_to_grid(&mesh.positions, h2).0);
        let none = snap_round(&mesh, 10, |m: &TriMesh, _| Ok::<_, ()>((m.clone(), 1))).unwrap();
        assert!(none.is_none());
    }
}
