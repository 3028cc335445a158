//! Figure 7: an open sheet pushed through itself near its boundary. The
//! sheet is curled (profile: a floor, a half-circle up, a flap back over
//! the floor) and the flap, boundary first, is pushed down through the
//! floor. The intersection curve runs across the floor, but the floor
//! strip the flap swept is bounded on its other side by the trace of the
//! flap's boundary, not by any intersection: graph partitioning has to
//! introduce that cut. Expected: the swept floor strip and the flap under
//! the floor are deleted; the floor before the strip becomes a separate
//! sheet (a disk), the rest a tube (floor–arc–flap glued at the curve).

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
    let mut triangles = Vec::new();
    let id = |i: u32, j: u32| j * (NU + 1) + i;
    for j in 0..NV {
        for i in 0..NU {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh {
        positions,
        triangles,
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
    let out = run(
        &m,
        &end,
        &Options {
            scheme,
            ..Options::default()
        },
    )
    .mesh;
    assert_eq!(
        self_intersecting_pairs(&out),
        0,
        "the result intersects itself"
    );
    assert!(max_edge_degree(&out) <= 2, "non-manifold edges");
    // Nothing is left under the floor.
    for v in out.triangles.iter().flatten() {
        assert!(
            out.positions[*v as usize].z > -1e-9,
            "vertex under the floor"
        );
    }
    // A disk (the front of the floor) and a tube: χ = 1 + 0, 1 + 2 loops.
    assert_eq!(
        components(&out),
        2,
        "components (boundary {:?}, χ {})",
        boundary(&out),
        euler(&out)
    );
    assert_eq!(boundary(&out).1, 3, "boundary loops");
    assert_eq!(euler(&out), 1, "Euler characteristic");
    // Deleted: the floor strip x in [TIP, X] and the flap below the floor.
    let x = 1.0 - 1.0 / SLOPE;
    let deleted = (x - TIP) * (1.0 + (1.0 + SLOPE * SLOPE).sqrt());
    let before = area(&TriMesh {
        positions: end,
        triangles: m.triangles.clone(),
    });
    let a = area(&out);
    // The new cut is within one floor cell (0.125 wide) of the trace.
    assert!(
        (before - a - deleted).abs() < 0.13,
        "deleted {} vs {deleted}",
        before - a
    );
    // The front sheet ends near the trace of the flap's boundary.
    let front = split_components(&out)
        .into_iter()
        .find(|c| used_bounds(c).0.x < -0.9)
        .expect("front sheet");
    let xmax = used_bounds(&front).1.x;
    assert!((xmax - TIP).abs() < 0.13, "front sheet ends at x = {xmax}");
}

#[test]
#[ignore = "engine limit: near the corners of the swept floor strip a floor triangle has all corners even yet part of it was swept (the trace of the flap's side crosses it); no false vertex can mark that, so the curve's last stretch keeps the floor on both sides: 4 non-manifold edges. Partition also rounds the strip's tip corners (4 of 45 odd vertices)"]
fn flap_through_the_floor_with_graph_partitioning() {
    check(Scheme::Partition);
}

/// Random flap depths and tilts: whatever the outcome, well formed and
/// free of self-intersections.
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
            let out = run(
                &m,
                &end,
                &Options {
                    scheme,
                    ..Options::default()
                },
            );
            assert_eq!(
                self_intersecting_pairs(&out.mesh),
                0,
                "slope {slope} twist {twist} {scheme:?}: defects {:?}",
                closedness_defects(&out.mesh)
            );
        }
    }
}
