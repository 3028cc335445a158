//! TopMod's remeshing schemes (issue 18) at about a million output faces:
//! one benchmark per family of schemes that share an implementation, each
//! on a quad torus sized so that one level makes about 1M faces (the
//! kernel mesh built and, in release builds, not revalidated, as
//! `subdivide` does).
//!
//! cargo bench -p holey-bench --bench remesh

use divan::{Bencher, black_box};
use holey_bench::torus_mesh;
use holey_subdiv::{RemeshParams, RemeshScheme, remesh};

fn main() {
    divan::main();
}

/// One level of `scheme` on an `n × m` torus (`F = nm`, `C = 4F`).
fn run(bencher: Bencher, scheme: RemeshScheme, n: u32, m: u32) {
    let base = torus_mesh(n, m);
    let params = RemeshParams::default();
    bencher.bench(|| {
        black_box(remesh(&base, scheme, &params, 1))
            .map(|out| out.face_count())
            .unwrap_or_else(|e| panic!("{scheme}: {e}"))
    });
}

/// Dual: `F' = V = F`, from a 1M-face torus.
#[divan::bench(sample_count = 3)]
fn dual_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Dual, 1000, 1000);
}

/// Stellation family (stellate, triangulate, stellate with edge removal,
/// double stellate): stellate, `F' = C = 4F`.
#[divan::bench(sample_count = 3)]
fn stellate_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Stellate, 500, 500);
}

/// √3 family (√3, dual vertex truncation): `F' = C = 4F`.
#[divan::bench(sample_count = 3)]
fn sqrt3_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Sqrt3, 500, 500);
}

/// Midpoint-split family (Loop, loop-style, fractal): Loop, `F' = F + C
/// = 5F`.
#[divan::bench(sample_count = 3)]
fn loop_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Loop, 400, 500);
}

/// Linear vertex insertion (and subdivide face): `F' = C = 4F`.
#[divan::bench(sample_count = 3)]
fn linear_vertex_insertion_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::LinearVertexInsertion, 500, 500);
}

/// Truncation family (vertex truncation, simplest): `F' = F + V = 2F`.
#[divan::bench(sample_count = 3)]
fn vertex_truncation_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::VertexTruncation, 1000, 500);
}

/// Doo–Sabin connectivity family (corner cutting, modified corner
/// cutting, Doo–Sabin BC): corner cutting, `F' = F + E + V = 4F`.
#[divan::bench(sample_count = 3)]
fn corner_cutting_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::CornerCutting, 500, 500);
}

/// Honeycomb: `F' = F + V = 2F`.
#[divan::bench(sample_count = 3)]
fn honeycomb_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Honeycomb, 1000, 500);
}

/// Root-4 (hexagon preserving): `F' = F + E = 3F`.
#[divan::bench(sample_count = 3)]
fn root4_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Root4, 578, 577);
}

/// Pentagonal family (pentagonalization, pentagon preserving):
/// pentagonalization, `F' = C = 4F`.
#[divan::bench(sample_count = 3)]
fn pentagonalization_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Pentagonalization, 500, 500);
}

/// Checkerboard: `F' = F + 2C = 9F`.
#[divan::bench(sample_count = 3)]
fn checkerboard_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Checkerboard, 334, 333);
}

/// Extrusion family: global extrude, `F' = F + C = 5F`.
#[divan::bench(sample_count = 3)]
fn global_extrude_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::GlobalExtrude, 400, 500);
}

/// Dome, seven extrusions of every quartered face: `F' = F + 28C = 113F`.
#[divan::bench(sample_count = 3)]
fn dome_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Dome, 94, 94);
}

/// Omnitruncation family (dual 12.6.4; 12.6.4 is it between two duals):
/// dual 12.6.4, `F' = F + E + V = 4F`.
#[divan::bench(sample_count = 3)]
fn dual_12_6_4_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::Dual12_6_4, 500, 500);
}

/// A composite through two duals: dual Loop, `F' = F + E = 3F`.
#[divan::bench(sample_count = 3)]
fn dual_loop_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::DualLoop, 578, 577);
}

/// Doo–Sabin BC New (its own one-pass step): `F' = F + 2E = 5F` on a quad
/// torus (`E = 2F`).
#[divan::bench(sample_count = 3)]
fn doo_sabin_bc_new_1m(bencher: Bencher) {
    run(bencher, RemeshScheme::DooSabinBcNew, 500, 400);
}
