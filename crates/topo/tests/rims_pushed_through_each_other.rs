//! Two open sheets whose rims pass through each other (§7's rims sweeping
//! through a sheet; on real meshes, an inflate dwelling on a scan's hole
//! next to a sheet it raised before).
//!
//! Sheet A lies in the plane z = 0 with its rim on x = x_A; sheet B in
//! the plane y = 0 with its rim on x = x_B > x_A. A slides along its own
//! plane, +x, until its rim is past x_B: the sheets now cross along the
//! segment y = z = 0 from B's rim to A's. Only rims swept anything, and
//! no vertex passed through a sheet, so parity deletes nothing: every
//! half of both sheets is kept along the curve, and the paper's glued
//! curve is an X, four triangles on every edge (non-manifold).
//!
//! Expected (`cut/crossings.rs`): the sheets fuse at the crossing, each
//! half of A joined to the half of B its orientation allows. Counted by
//! hand: cutting A along the segment (from its rim inward) and B (from
//! its rim inward) changes no Euler characteristic; gluing A's two sides
//! to B's identifies the segment's 2k + 1 points of each sheet into 2k
//! and its 2k edges of each into 2k, so χ drops by 2, from 1 + 1 to 0.
//! Each rim still passes through its end of the segment, so the two
//! boundary loops stay two: one piece, χ = 0, two loops, genus 0 (an
//! annulus), manifold, consistently oriented, crossing nothing.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

/// A grid of `nu` × `nv` quads (two triangles each) over the unit
/// square, placed by `at(u, v)`.
fn sheet(nu: u32, nv: u32, at: impl Fn(f64, f64) -> DVec3) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            positions.push(at(
                f64::from(i) / f64::from(nu),
                f64::from(j) / f64::from(nv),
            ));
        }
    }
    TriMesh {
        positions,
        triangles: holey_testkit::grid_triangles(nu, nv),
    }
}

/// A (z = 0, x in [-2, 0], |y| ≤ 1) slides by `slide` in x; B (y = 0,
/// x in [x_b, x_b + 2], |z| ≤ 1) stays. Odd numbers of rows keep grid
/// lines off the line y = z = 0 where the sheets will cross.
fn rims_crossing(n: u32, x_b: f64, slide: f64, options: &Options) -> holey_topo::Outcome {
    let a = sheet(n, 9, |u, v| DVec3::new(-2.0 + 2.0 * u, -1.0 + 2.0 * v, 0.0));
    let b = sheet(n, 7, |u, v| DVec3::new(x_b + 2.0 * u, 0.0, -1.0 + 2.0 * v));
    let (start, end) = still_and_moving(&b, &a, DVec3::ZERO, DVec3::X * slide);
    assert_eq!(self_intersecting_pairs(&start), 0, "the sheets start apart");
    run(&start, &end, options)
}

/// Whether no directed edge is used twice: the triangles agree on an
/// orientation wherever they meet.
fn consistently_oriented(m: &TriMesh) -> bool {
    let mut seen = std::collections::HashSet::new();
    m.triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .all(|e| seen.insert(e))
}

fn assert_fused_into_an_annulus(out: &holey_topo::Outcome) {
    let m = &out.mesh;
    assert_eq!(
        out.report.cut.triangles_deleted, 0,
        "parity deletes nothing"
    );
    assert_eq!(max_edge_degree(m), 2, "non-manifold edges");
    assert!(
        out.report.cut.crossings_reconnected > 0,
        "{:?}",
        out.report.cut
    );
    assert_eq!(pinch_vertices(m), 0, "pinched vertices");
    assert!(consistently_oriented(m), "orientation");
    assert_eq!(self_intersecting_pairs(m), 0, "the result crosses itself");
    assert_eq!(components(m), 1, "components");
    assert_eq!(boundary(m).1, 2, "boundary loops");
    assert_eq!(euler(m), 0, "Euler characteristic");
}

/// The crossing spans several triangles of each sheet: the curve's inner
/// points split in two, its ends (on the rims) stay one vertex each.
#[test]
fn rims_pushed_through_each_other_fuse_into_an_annulus() {
    assert_fused_into_an_annulus(&rims_crossing(16, 0.3, 1.0, &Options::default()));
}

/// The crossing is a single curve edge (the overlap, 0.02 long, lies in
/// one triangle of each sheet): both its points are rim points, so the
/// edge is split at its midpoint for the halves to part there.
#[test]
fn rims_barely_pushed_through_each_other_fuse_at_one_edge() {
    let out = rims_crossing(8, 0.03, 0.05, &Options::default());
    assert_eq!(out.report.intersection_edges, 1, "{:?}", out.report);
    assert_fused_into_an_annulus(&out);
}

/// The paper's part assembly (`nonmanifold_joins`) keeps its X: four
/// triangles on each curve edge.
#[test]
fn rims_crossing_keep_the_papers_x_when_asked() {
    let papers = Options {
        nonmanifold_joins: true,
        ..Options::default()
    };
    let out = rims_crossing(16, 0.3, 1.0, &papers);
    assert_eq!(out.report.cut.crossings_reconnected, 0);
    assert_eq!(max_edge_degree(&out.mesh), 4);
}
