//! Figure 7: an open sheet pushed through itself near its boundary. The
//! sheet is curled (profile: a floor, a half-circle up, a flap back over
//! the floor; the flap 0.8 wide, the floor 1.0) and the flap, boundary
//! first, is pushed down through the floor. The intersection curve runs
//! across the floor, but the floor strip the flap swept is bounded on its
//! other three sides by the trace of the flap's boundary, not by any
//! intersection: graph partitioning has to introduce that cut (§3.4).
//! Expected: the swept strip and the flap under the floor are deleted,
//! leaving a hole in the floor whose far edge is glued to the flap: one
//! sheet with a handle (floor–arc–flap) and one boundary loop, genus 1,
//! χ = −1. Majority voting, which the paper shows failing here, cannot
//! make the cut: the strip is one component with the rest of the floor.
//!
//! Where the curve ends at the flap's sides, the even/odd boundary drawn
//! along floor edges misses the curve's last stretch (floor triangles
//! with all corners even, partly swept); the motion sampled beside the
//! curve decides those (`cut/junctions.rs`), so no edge is left with
//! three sheets.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, Scheme, TriMesh};

const NU: u32 = 80;
const NV: u32 = 20;
/// x of the flap's boundary.
const TIP: f64 = 0.03;
/// The flap ends on the line z = 1 − SLOPE (1 − x).
const SLOPE: f64 = 1.3;

/// Profile point at parameter u in [0, 1].
fn profile(u: f64) -> (f64, f64) {
    if u <= 0.4 {
        (-1.0 + 2.0 * u / 0.4, 0.0)
    } else if u <= 0.6 {
        let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * (u - 0.4) / 0.2;
        (1.0 + 0.5 * a.cos(), 0.5 + 0.5 * a.sin())
    } else {
        (1.0 - (1.0 - TIP) * (u - 0.6) / 0.4, 1.0)
    }
}

/// Width of the sheet at u: 1 on the floor, 0.8 on the flap.
fn width(u: f64) -> f64 {
    let t = ((u - 0.4) / 0.2).clamp(0.0, 1.0);
    1.0 - 0.2 * t * t * (3.0 - 2.0 * t)
}

fn sheet() -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=NV {
        for i in 0..=NU {
            let u = f64::from(i) / f64::from(NU);
            let (x, z) = profile(u);
            positions.push(DVec3::new(
                x,
                width(u) * (-0.5 + f64::from(j) / f64::from(NV)),
                z,
            ));
        }
    }
    TriMesh {
        positions,
        triangles: holey_testkit::grid_triangles(NU, NV),
    }
}

/// The flap (u > 0.6) moves straight down onto the tilted line.
fn push(m: &TriMesh) -> Vec<DVec3> {
    m.positions
        .iter()
        .enumerate()
        .map(|(k, &p)| {
            let i = k as u32 % (NU + 1);
            if i > NU * 6 / 10 {
                DVec3::new(p.x, p.y, 1.0 - SLOPE * (1.0 - p.x))
            } else {
                p
            }
        })
        .collect()
}

fn check(scheme: Scheme) {
    let m = sheet();
    let end = push(&m);
    verify(&m, &end, run_with(&m, &end, scheme));
}

/// The engine on `m` moving to `end` with the default options but `scheme`.
fn run_with(m: &TriMesh, end: &[DVec3], scheme: Scheme) -> holey_topo::Outcome {
    run(
        m,
        end,
        &Options {
            scheme,
            ..Options::default()
        },
    )
}

/// The result is free of self-intersections and has no edge of three or
/// more triangles.
fn assert_manifold_and_embedded(out: &TriMesh) {
    assert_eq!(
        self_intersecting_pairs(out),
        0,
        "the result intersects itself"
    );
    assert!(max_edge_degree(out) <= 2, "non-manifold edges");
}

/// What [`check`] asserts of the result `outcome` of `m` moving to `end`.
fn verify(m: &TriMesh, end: &[DVec3], outcome: holey_topo::Outcome) {
    // The curve's last stretches, at both sides of the flap, were T's.
    assert!(
        outcome.report.cut.junctions_repaired >= 2,
        "{:?}",
        outcome.report.cut
    );
    let out = outcome.mesh;
    assert_manifold_and_embedded(&out);
    // Nothing is left under the floor.
    for v in out.triangles.iter().flatten() {
        assert!(
            out.positions[*v as usize].z > -1e-9,
            "vertex under the floor"
        );
    }
    // One sheet: the floor with a hole, a handle over it.
    assert_eq!(components(&out), 1, "components");
    assert_eq!(boundary(&out).1, 1, "boundary loops (χ {})", euler(&out));
    assert_eq!(euler(&out), -1, "Euler characteristic");
    assert_eq!(genus_with_boundary(&out), 1, "genus");
    // Deleted: the floor strip x in [TIP, X], |y| < 0.4, and the flap
    // below the floor.
    let x = 1.0 - 1.0 / SLOPE;
    let deleted = 0.8 * (x - TIP) * (1.0 + (1.0 + SLOPE * SLOPE).sqrt());
    let before = before_area(m, end);
    let a = out.area();
    // The new cut is within about one floor cell (0.0625 × 0.05) of the
    // trace, around the strip's perimeter of about 1.2.
    assert!(
        (before - a - deleted).abs() < 0.05,
        "deleted {} vs {deleted}",
        before - a
    );
    // Nothing of the floor is left inside the strip, away from its edges.
    assert_eq!(floor_triangles_in_strip(&out), 0, "floor left in the strip");
}

fn before_area(m: &TriMesh, end: &[DVec3]) -> f64 {
    TriMesh {
        positions: end.to_vec(),
        triangles: m.triangles.clone(),
    }
    .area()
}

/// Genus of a connected orientable surface with boundary: χ = 2 − 2g − b.
fn genus_with_boundary(m: &TriMesh) -> i64 {
    (2 - euler(m) - boundary(m).1 as i64) / 2
}

/// Floor triangles (z = 0) whose centroid lies inside the swept strip,
/// a floor cell in from its ends and two from its sides (partitioning may
/// round the strip's corners by a cell).
fn floor_triangles_in_strip(m: &TriMesh) -> usize {
    let x = 1.0 - 1.0 / SLOPE;
    m.triangles
        .iter()
        .map(|t| t.map(|v| m.positions[v as usize]))
        .filter(|p| p.iter().all(|q| q.z.abs() < 1e-12))
        .map(|p| (p[0] + p[1] + p[2]) / 3.0)
        .filter(|c| c.x > TIP + 0.0625 && c.x < x - 0.0625 && c.y.abs() < 0.3)
        .count()
}

#[test]
fn flap_through_the_floor_with_graph_partitioning() {
    check(Scheme::Partition);
}

/// The same push as a drag of §4 over ten frames, its parity accumulated
/// and the change made once at release: the samples beside the curve
/// follow the drag's keyframes, so the T-junctions at the flap's sides
/// are resolved as in one frame (before the drag kept its keyframes they
/// were left to orientation, which cannot decide a curve ending on a
/// boundary, and three sheets met there).
#[test]
fn flap_through_the_floor_dragged_over_ten_frames() {
    let m = sheet();
    let end = push(&m);
    verify(&m, &end, dragged(&m, &end, 10).release().unwrap());
}

/// The paper's point: majority voting cannot cut the strip out (it is one
/// component with the floor around it, mostly even). The result is still
/// a manifold without self-intersections: the motion, sampled beside the
/// curve, opens only a slot along it so that the flap joins the floor.
#[test]
fn flap_through_the_floor_with_majority_voting_keeps_the_strip() {
    let m = sheet();
    let end = push(&m);
    let out = run_with(&m, &end, Scheme::Majority).mesh;
    assert_manifold_and_embedded(&out);
    let whole = floor_triangles_in_strip(&TriMesh {
        positions: end,
        triangles: m.triangles.clone(),
    });
    assert!(whole > 0);
    assert_eq!(
        floor_triangles_in_strip(&out),
        whole,
        "majority voting cut into the strip"
    );
}

/// Random flap depths and tilts: whatever the outcome, manifold and free
/// of self-intersections.
#[test]
fn random_flaps_never_panic() {
    let m = sheet();
    let mut rng = holey_testkit::Rng::new(7);
    for _ in 0..8 {
        let (slope, twist) = (rng.range(1.05, 2.0), rng.range(-0.4, 0.4));
        let end: Vec<DVec3> = m
            .positions
            .iter()
            .enumerate()
            .map(|(k, &p)| {
                if k as u32 % (NU + 1) > NU * 6 / 10 {
                    DVec3::new(
                        p.x,
                        p.y,
                        1.0 - slope * (1.0 - p.x) + twist * p.y * (1.0 - p.x),
                    )
                } else {
                    p
                }
            })
            .collect();
        for scheme in [Scheme::Partition, Scheme::Majority] {
            let out = run_with(&m, &end, scheme);
            assert_eq!(
                self_intersecting_pairs(&out.mesh),
                0,
                "slope {slope} twist {twist} {scheme:?}: defects {:?}",
                closedness_defects(&out.mesh)
            );
            assert!(
                max_edge_degree(&out.mesh) <= 2,
                "slope {slope} twist {twist} {scheme:?}: non-manifold edges"
            );
        }
    }
}
