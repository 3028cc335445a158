//! Figure 13 of Bernstein & Wojtan 2013: a closed cylinder plunged
//! through a single giant triangle. No vertex of the triangle lies inside
//! the cylinder, so the paper's method has no parity sample there, keeps
//! the disc and leaves a non-manifold junction. §7 proposes adaptive
//! refinement; holey samples the parity of one new point in every region
//! that no vertex reaches, and gets the right topology.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

/// Euler characteristic over used vertices, and the largest number of
/// triangles on one edge.
fn euler_and_max_edge_degree(m: &TriMesh) -> (i64, usize) {
    (euler(m), max_edge_degree(m))
}

#[test]
fn cylinder_through_one_giant_triangle() {
    let giant = triangle([
        DVec3::new(-20.0, -17.0, 0.0),
        DVec3::new(23.0, -15.0, 0.0),
        DVec3::new(1.0, 21.0, 0.0),
    ]);
    let cylinder = primitive("@cylinder:24:3");
    // From well above the plane (z in [2.1, 4.1]) to halfway through it
    // (z in [-0.9, 1.1]); no cylinder vertex ends on the plane.
    let start = join(&giant, &translate(&cylinder, DVec3::new(0.3, 0.2, 3.1)));
    let mut end = start.positions.clone();
    for p in &mut end[3..] {
        p.z -= 3.0;
    }
    let out = run(&start, &end, &Options::default());
    let r = &out.report;
    // The triangle's corners stay even; the cylinder's vertices below the
    // plane are odd; the disc of the triangle inside the cylinder has no
    // vertex and is decided by one sample.
    assert!(out.raw_odd[..3].iter().all(|&o| !o));
    assert_eq!(r.cut.sampled_regions, 1, "{r:?}");
    assert_eq!(r.cut.undecided, 0);
    let m = &out.mesh;
    let (chi, max_degree) = euler_and_max_edge_degree(m);
    // The upper half of the cylinder opens into a hole in the triangle: one
    // manifold disc (χ = 1) bounded by the triangle's outline.
    assert_eq!(max_degree, 2, "non-manifold junction");
    assert_eq!(components(m), 1);
    assert_eq!(boundary(m), (3, 1));
    assert_eq!(chi, 1);
    assert_eq!(self_intersecting_pairs(m), 0);
    let below = m
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&v| m.positions[v as usize].z < -1e-9))
        .count();
    assert_eq!(below, 0, "a part of the cylinder below the plane survived");

    // Without the extra sample and with T-junctions left as parity makes
    // them: the paper's failure, the disc kept and a non-manifold
    // junction where the cylinder meets it.
    let paper = run(
        &start,
        &end,
        &Options {
            refine: false,
            nonmanifold_joins: true,
            ..Options::default()
        },
    );
    assert_eq!(paper.report.cut.sampled_regions, 0);
    assert!(paper.report.cut.undecided > 0);
    assert!(euler_and_max_edge_degree(&paper.mesh).1 > 2);

    // Without the sample, orientation alone also opens the disc: the
    // cylinder's kept wall runs each curve edge as one half of the
    // triangle does, and the other half, the disc, is enclosed by the
    // curve (cut/junctions.rs).
    let oriented = run(
        &start,
        &end,
        &Options {
            refine: false,
            ..Options::default()
        },
    );
    assert_eq!(oriented.report.cut.sampled_regions, 0);
    assert!(oriented.report.cut.junctions_repaired > 0);
    let (chi, max_degree) = euler_and_max_edge_degree(&oriented.mesh);
    assert_eq!((chi, max_degree), (1, 2), "not one manifold disc");
    assert_eq!(boundary(&oriented.mesh), (3, 1));
}
