//! Figure 6: when a surface has holes, or the collision parity is
//! otherwise corrupted, error correction removes the isolated errors. The
//! ground truth is geometric: a vertex of one sphere should be odd exactly
//! when it ends inside the other (ray-parity oracle).

#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use glam::DVec3;
use holey_testkit::Rng;
use holey_topo::internals::{Edges, Graph, Weights, correct};
use holey_topo::{Options, Scheme, TriMesh, self_intersections};

fn two_spheres() -> (TriMesh, TriMesh, TriMesh) {
    let a = primitive("@sphere:3");
    let b = translate(&a, DVec3::new(0.93, 0.23, 0.11));
    (join(&a, &b), a, b)
}

/// Vertices of `a` inside `b` and of `b` inside `a`.
fn truth(a: &TriMesh, b: &TriMesh) -> Vec<bool> {
    a.positions
        .iter()
        .map(|&p| inside(b, p))
        .chain(b.positions.iter().map(|&p| inside(a, p)))
        .collect()
}

fn errors(x: &[bool], truth: &[bool]) -> usize {
    x.iter().zip(truth).filter(|(a, b)| a != b).count()
}

fn corrected(mesh: &TriMesh, raw: &[bool], scheme: Scheme) -> Vec<bool> {
    let edges = Edges::new(mesh);
    let w = Weights::new(mesh, &mesh.positions, &edges);
    let x = self_intersections(mesh).unwrap();
    let g = Graph {
        vertices: mesh.positions.len(),
        ends: &edges.ends,
        edge_weight: &w.edge,
        vertex_weight: &w.vertex,
        cut: &x.cut_edges,
        total_area: w.total_area,
    };
    correct(&g, raw, scheme).odd
}

#[test]
fn correction_keeps_a_consistent_field() {
    let (m, a, b) = two_spheres();
    let t = truth(&a, &b);
    assert!(t.iter().any(|&o| o));
    for scheme in [Scheme::Partition, Scheme::Majority] {
        assert_eq!(errors(&corrected(&m, &t, scheme), &t), 0, "{scheme:?}");
    }
}

#[test]
fn correction_removes_isolated_flips() {
    let (m, a, b) = two_spheres();
    let t = truth(&a, &b);
    for seed in 0..3 {
        let mut rng = Rng::new(seed);
        // Flip 3% of the vertices: isolated errors.
        let raw: Vec<bool> = t.iter().map(|&o| o ^ rng.chance(0.03)).collect();
        let raw_err = errors(&raw, &t);
        assert!(raw_err > 20);
        for scheme in [Scheme::Partition, Scheme::Majority] {
            let e = errors(&corrected(&m, &raw, scheme), &t);
            assert!(
                e * 10 <= raw_err,
                "{scheme:?} seed {seed}: {e} errors left of {raw_err}"
            );
        }
    }
}

/// A sphere with holes where the other comes in: vertices entering through
/// a hole collide with nothing and keep an even raw parity although they
/// end inside. The corrected parity is much closer to the truth.
#[test]
fn holes_corrupt_the_raw_parity_and_correction_repairs_it() {
    let full = primitive("@sphere:3");
    // Punch small holes (single triangles, spaced out) in the cap facing +x.
    let mut holey = full.clone();
    let mut taken: Vec<DVec3> = Vec::new();
    holey.triangles.retain(|t| {
        let c = t
            .map(|v| full.positions[v as usize])
            .iter()
            .copied()
            .sum::<DVec3>()
            / 3.0;
        let punch = c.x > 0.6 && taken.iter().all(|q| (*q - c).length() > 0.3);
        if punch {
            taken.push(c);
        }
        !punch
    });
    assert!(taken.len() >= 5, "{} holes", taken.len());
    let b = translate(&full, DVec3::new(0.93, 0.23, 0.11));
    let start = join(&holey, &translate(&b, DVec3::new(8.0, 0.0, 0.0)));
    let end: Vec<DVec3> = holey
        .positions
        .iter()
        .chain(&b.positions)
        .copied()
        .collect();
    let out = run(&start, &end, &Options::default());
    let t = truth(&full, &b);
    let raw_err = errors(&out.raw_odd, &t);
    let cor_err = errors(&out.corrected_odd, &t);
    assert!(raw_err > 0, "the holes corrupted nothing");
    assert!(
        cor_err * 4 <= raw_err,
        "corrected {cor_err} vs raw {raw_err} errors"
    );
    // The hole-free sphere's result is the reference: no worse than it.
    assert_eq!(self_intersecting_pairs(&out.mesh), 0);
}
