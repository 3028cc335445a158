use glam::DVec3;

use super::*;
use crate::mesh::{Edges, TriMesh};
use crate::weights::Weights;

/// An n×n grid of unit squares (two triangles each), scaled by `s`.
fn grid(n: u32, s: f64) -> TriMesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(DVec3::new(i as f64, j as f64, 0.0) * s);
        }
    }
    TriMesh {
        positions,
        triangles: holey_testkit::grid_triangles(n, n),
    }
}

struct Setup {
    edges: Edges,
    weights: Weights,
    cut: Vec<bool>,
    n: usize,
}

fn setup(mesh: &TriMesh, cut_by: impl Fn(DVec3, DVec3) -> bool) -> Setup {
    let edges = Edges::new(mesh);
    let weights = Weights::new(mesh, &mesh.positions, &edges);
    let cut = edges
        .ends
        .iter()
        .map(|&[a, b]| cut_by(mesh.positions[a as usize], mesh.positions[b as usize]))
        .collect();
    Setup {
        edges,
        weights,
        cut,
        n: mesh.positions.len(),
    }
}

fn run(s: &Setup, raw: &[bool], scheme: Scheme) -> Correction {
    let g = Graph {
        vertices: s.n,
        ends: &s.edges.ends,
        edge_weight: &s.weights.edge,
        vertex_weight: &s.weights.vertex,
        cut: &s.cut,
        total_area: s.weights.total_area,
    };
    correct(&g, raw, scheme)
}

/// Odd inside the disk of radius `r` around the grid's centre.
fn disk(mesh: &TriMesh, c: DVec3, r: f64) -> Vec<bool> {
    mesh.positions.iter().map(|p| p.distance(c) < r).collect()
}

#[test]
fn clean_parity_is_the_minimiser_and_is_kept() {
    let mesh = grid(20, 1.0);
    let c = DVec3::new(10.0, 10.0, 0.0);
    let raw = disk(&mesh, c, 5.5);
    let s = setup(&mesh, |a, b| (a.distance(c) < 5.5) != (b.distance(c) < 5.5));
    for scheme in [Scheme::Partition, Scheme::Majority] {
        let out = run(&s, &raw, scheme);
        assert_eq!(out.odd, raw, "{scheme:?}");
        assert_eq!(out.solved_components, 0);
    }
}

#[test]
fn isolated_errors_are_removed() {
    let mesh = grid(20, 1.0);
    let s = setup(&mesh, |_, _| false);
    let mut raw = vec![false; s.n];
    // One odd vertex and a cluster of three, far from each other.
    for (i, j) in [(5u32, 5u32), (14, 13), (15, 13), (14, 14)] {
        raw[(j * 21 + i) as usize] = true;
    }
    let out = run(&s, &raw, Scheme::Partition);
    assert!(out.odd.iter().all(|&o| !o), "errors survived");
    assert_eq!(out.solved_components, 1);
    assert_eq!(out.solved_unknowns, s.n);
}

#[test]
fn a_large_uncut_odd_region_is_kept() {
    // Half the square odd: flipping it costs 2π·(1/2) of area, keeping it
    // a squared boundary of length 1 (in units where the area is 1).
    let mesh = grid(20, 1.0);
    let s = setup(&mesh, |_, _| false);
    let raw: Vec<bool> = mesh.positions.iter().map(|p| p.x < 9.5).collect();
    let out = run(&s, &raw, Scheme::Partition);
    assert_eq!(out.odd, raw);
}

#[test]
fn errors_next_to_a_cut_region_are_fixed_and_the_region_kept() {
    let mesh = grid(24, 1.0);
    let c = DVec3::new(12.0, 12.0, 0.0);
    let inside = |p: DVec3| p.distance(c) < 6.5;
    let s = setup(&mesh, |a, b| inside(a) != inside(b));
    let mut raw = disk(&mesh, c, 6.5);
    let expect = raw.clone();
    // Corrupt: two odd vertices outside, one even vertex inside.
    for (i, j) in [(2u32, 3u32), (20, 21), (12, 12)] {
        let v = (j * 25 + i) as usize;
        raw[v] = !raw[v];
    }
    let out = run(&s, &raw, Scheme::Partition);
    assert_eq!(out.odd, expect);
    // Majority voting fixes these too: each region votes on its own.
    assert_eq!(run(&s, &raw, Scheme::Majority).odd, expect);
}

#[test]
fn majority_fails_where_curves_do_not_separate_but_partition_cuts() {
    // Figure 7: an intersection curve that ends inside the surface does
    // not bound a region, so the vote sees one region; partitioning can
    // introduce the missing cut.
    let mesh = grid(24, 1.0);
    let raw: Vec<bool> = mesh.positions.iter().map(|p| p.x < 8.5).collect();
    // Cuts only along part of the parity change.
    let s = setup(&mesh, |a, b| {
        (a.x < 8.5) != (b.x < 8.5) && a.y.min(b.y) < 12.0
    });
    let major = run(&s, &raw, Scheme::Majority);
    assert!(
        major.odd.iter().all(|&o| !o),
        "the vote wipes out the odd third"
    );
    let part = run(&s, &raw, Scheme::Partition);
    assert_eq!(part.odd, raw, "partitioning keeps the odd region");
}

#[test]
fn the_result_does_not_depend_on_scale() {
    let mut labels = Vec::new();
    for scale in [1e-9, 1.0, 1e9] {
        let mesh = grid(16, scale);
        let c = DVec3::new(8.0, 8.0, 0.0) * scale;
        let mut raw = disk(&mesh, c, 4.5 * scale);
        raw[3] = true;
        raw[200] = !raw[200];
        let s = setup(&mesh, |a, b| {
            (a.distance(c) < 4.5 * scale) != (b.distance(c) < 4.5 * scale)
        });
        labels.push(run(&s, &raw, Scheme::Partition).odd);
    }
    assert_eq!(labels[0], labels[1]);
    assert_eq!(labels[1], labels[2]);
}

#[test]
fn components_are_corrected_independently() {
    // Two separate grids: an error on one must not touch the other.
    let a = grid(8, 1.0);
    let mut mesh = a.clone();
    let off = mesh.positions.len() as u32;
    mesh.positions
        .extend(a.positions.iter().map(|p| *p + DVec3::new(100.0, 0.0, 0.0)));
    mesh.triangles
        .extend(a.triangles.iter().map(|t| t.map(|i| i + off)));
    let s = setup(&mesh, |_, _| false);
    let mut raw = vec![false; s.n];
    raw[40] = true; // an error in the first grid
    // The second grid all odd: consistent, kept.
    raw[off as usize..].fill(true);
    let out = run(&s, &raw, Scheme::Partition);
    assert!(!out.odd[40]);
    assert!(out.odd[off as usize..].iter().all(|&o| o));
    assert_eq!(out.solved_unknowns, off as usize);
}
