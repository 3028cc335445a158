//! [`Options::one_piece`]: a guarded frame on a mesh the caller knows to
//! be one piece skips counting the result's pieces where its region shows
//! that one piece stays one, and counts them where it does not. Either
//! way the frame's result is what it is without the hint.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{GuardedReport, Options, TriMesh, is_one_piece, topology_change_guarded};

/// `m` moved to `end` by a guarded frame, told that `m` is one piece
/// when `hint`: the result and the report.
fn guarded(m: &TriMesh, end: &[DVec3], hint: bool) -> (TriMesh, GuardedReport) {
    let options = Options {
        one_piece: hint,
        ..Options::default()
    };
    let mut out = m.clone();
    let report = topology_change_guarded(&mut out, end, &options).expect("a valid frame");
    (out, report)
}

/// A closed tube bent into a U in the xy-plane: arms along x = ±1 from
/// y = 1 down to y = −3, joined by a half circle of radius 1 around
/// (0, −3); radius 0.3.
fn u_tube() -> TriMesh {
    let mut centre: Vec<DVec3> = (0..40)
        .map(|i| DVec3::new(-1.0, 1.0 - 0.1 * f64::from(i), 0.0))
        .collect();
    centre.extend((0..=30).map(|i| {
        let a = std::f64::consts::PI * (1.0 + f64::from(i) / 30.0);
        DVec3::new(a.cos(), -3.0 + a.sin(), 0.0)
    }));
    centre.extend((1..=40).map(|i| DVec3::new(1.0, -3.0 + 0.1 * f64::from(i), 0.0)));
    tube(&centre, 0.3, 16, 0.1, DVec3::Z)
}

/// The U's right arm bent over toward the left one above y = 0.3 (by 1.6
/// at y ≥ 0.6, smoothly less below): its top ends 0.2 deep in the left
/// arm.
fn arms_pushed_together(m: &TriMesh) -> Vec<DVec3> {
    m.positions
        .iter()
        .map(|&p| {
            if p.x <= 0.0 {
                return p;
            }
            let t = ((p.y - 0.3) / 0.3).clamp(0.0, 1.0);
            p - DVec3::X * 1.6 * t * t * (3.0 - 2.0 * t)
        })
        .collect()
}

/// The two arms fuse: a handle (Euler characteristic 2 less), the tube
/// still one piece. With the hint the guard shows that from the region
/// (every vertex where the region meets the rest of the tube ends in one
/// connected result) and says so; without, it counts the result's pieces
/// and says so from the count. The result is the same mesh either way,
/// one piece by an independent count, closed and consistently oriented.
#[test]
fn a_u_tube_whose_arms_fuse_stays_one_piece_without_a_count() {
    let m = u_tube();
    assert!(closed_oriented(&m) && components(&m) == 1 && is_one_piece(&m));
    let end = arms_pushed_together(&m);
    let (plain, without) = guarded(&m, &end, false);
    let (hinted, with) = guarded(&m, &end, true);
    assert!(
        !with.held_all && with.refused.is_empty(),
        "{:?}",
        with.refused
    );
    assert_eq!(with.euler_change, -2, "a handle");
    assert_eq!(euler(&hinted), euler(&m) - 2);
    assert!(with.local.one_piece, "shown from the region");
    assert!(without.local.one_piece, "counted");
    assert_eq!(hinted, plain, "the hint changes nothing of the result");
    assert!(is_one_piece(&hinted) && components(&hinted) == 1);
    assert!(closed_oriented(&hinted));
}

/// A frame that only moves the surface keeps it one piece: the report
/// says so with the hint.
#[test]
fn a_frame_that_only_moves_keeps_the_hint() {
    let m = u_tube();
    let end: Vec<DVec3> = m.positions.iter().map(|&p| p * 1.01).collect();
    let (moved, r) = guarded(&m, &end, true);
    assert!(
        r.local.positions_only && r.local.one_piece,
        "positions only {}, one piece {}",
        r.local.positions_only,
        r.local.one_piece
    );
    assert_eq!(moved.positions, end);
}
