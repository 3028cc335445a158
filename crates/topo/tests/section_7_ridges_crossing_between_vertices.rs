//! §7's refinement where no vertex carries the change: two open tents,
//! one standing (ridge along x at height 1, eaves at y = ±1, z = 0) and
//! one hanging upside down above it (valley along y at height 1.5, eaves
//! at x = ±1, z = 2.5), the hanging one lowered by 1. Only the ridge and
//! the valley pass through each other: every vertex of each tent ends
//! outside the other's extent, so every vertex parity is even, yet the
//! tents end crossing along a closed loop around the point where the
//! edges crossed. The frame made that curve, so it is cut anyway and the
//! two diamonds it bounds (each swept by the other tent's crease, holding
//! no vertex) are sampled, found odd and deleted: the tents join along
//! the loop into one piece (each tent a disc with a diamond taken out,
//! an annulus of Euler characteristic 0; two annuli glued along a circle:
//! χ = 0, with the two tents' eaves as its two boundary loops).
//!
//! The same motion as a drag of §4 over five frames comes out the same:
//! its keyframes let the samples follow it (`holey_topo`'s drag path);
//! before them a drag left that curve uncut and the tents crossing.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

/// A tent over `[-a, a] × [-b, b]` (in its own x, y) with its crease along
/// x at height `top` and its eaves at height `eave`, split into `n`
/// strips along the crease so that the crossing lies inside triangles.
fn tent(a: f64, b: f64, top: f64, eave: f64, n: u32) -> TriMesh {
    let mut positions = Vec::new();
    for i in 0..=n {
        let x = -a + 2.0 * a * f64::from(i) / f64::from(n);
        positions.push(DVec3::new(x, -b, eave));
        positions.push(DVec3::new(x, 0.0, top));
        positions.push(DVec3::new(x, b, eave));
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let (p, q) = (3 * i, 3 * (i + 1));
        for k in 0..2 {
            triangles.push([p + k, q + k, q + k + 1]);
            triangles.push([p + k, q + k + 1, p + k + 1]);
        }
    }
    TriMesh {
        positions,
        triangles,
    }
}

/// The standing tent and the hanging one (turned a quarter about z and
/// upside down), and the hanging one lowered by 1.
fn tents() -> (TriMesh, Vec<DVec3>) {
    let standing = tent(2.0, 1.0, 1.0, 0.0, 3);
    let hanging = map_positions(&tent(2.0, 1.0, 1.5, 2.5, 3), |p| DVec3::new(p.y, p.x, p.z));
    let start = join(&standing, &hanging);
    let n = standing.positions.len();
    let end = start
        .positions
        .iter()
        .enumerate()
        .map(|(v, &p)| if v < n { p } else { p - DVec3::Z })
        .collect();
    (start, end)
}

fn check(what: &str, out: &TriMesh) {
    assert_eq!(
        self_intersecting_pairs(out),
        0,
        "{what}: the tents still cross"
    );
    assert!(max_edge_degree(out) <= 2, "{what}: non-manifold edges");
    assert_eq!(components(out), 1, "{what}: the tents joined");
    assert_eq!(euler(out), 0, "{what}: two annuli glued along a circle");
    assert_eq!(boundary(out).1, 2, "{what}: the two tents' eaves");
}

#[test]
fn crests_crossing_in_one_frame_join_the_tents() {
    let (start, end) = tents();
    let out = run(&start, &end, &Options::default());
    assert_eq!(out.report.raw_odd_vertices, 0, "no vertex crossed");
    check("one frame", &out.mesh);
}

#[test]
fn crests_crossing_over_a_drag_join_the_tents() {
    let (start, end) = tents();
    let out = dragged(&start, &end, 5).release().unwrap();
    assert_eq!(out.report.raw_odd_vertices, 0, "no vertex crossed");
    check("drag", &out.mesh);
}
