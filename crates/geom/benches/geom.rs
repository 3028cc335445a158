//! divan benchmarks of holey-geom: `cargo bench -p holey-geom`.
//!
//! The 524k-triangle two-sphere scenes (UV spheres of 262,144 triangles,
//! 512 meridians × 258 parallels) come from `scenes`, which
//! `examples/measure.rs` shares.

use divan::Bencher;
use glam::DVec3;
use holey_geom::bvh::{Aabb, Bvh};
use holey_geom::ccd::{CcdOptions, vertex_parities};
use holey_geom::{SymPoint, orient3d, orient3d_sos};
use holey_testkit::Rng;

fn main() {
    divan::main();
}

mod scenes;

fn random_boxes(n: usize) -> Vec<Aabb> {
    let mut r = Rng::new(7);
    (0..n)
        .map(|_| {
            let c = DVec3::new(r.unit(), r.unit(), r.unit());
            let e = DVec3::new(r.unit(), r.unit(), r.unit()) * 0.002;
            Aabb::new(c - e, c + e)
        })
        .collect()
}

#[divan::bench(sample_count = 10)]
fn bvh_build_1m(b: Bencher) {
    let boxes = random_boxes(1_000_000);
    b.bench(|| Bvh::build(&boxes).map(|t| t.node_count()));
}

#[divan::bench(sample_count = 10)]
fn bvh_stream_1m_queries(b: Bencher) {
    let boxes = random_boxes(1_000_000);
    let bvh = Bvh::build(&boxes).expect("finite");
    b.bench(|| bvh.overlap_pairs(&boxes).len());
}

#[divan::bench(sample_count = 10)]
fn self_overlaps_two_spheres_524k(b: Bencher) {
    let (p, t) = scenes::two_spheres();
    let boxes = scenes::triangle_boxes(&p, &t);
    b.bench(|| {
        let bvh = Bvh::build(&boxes).expect("finite");
        bvh.self_overlaps().len()
    });
}

#[divan::bench(sample_count = 5)]
fn ccd_union_524k(b: Bencher) {
    let (p, end, t) = scenes::sphere_sweep();
    b.bench(|| vertex_parities(&p, &end, &t, &CcdOptions::default()).map(|r| r.odd_pairs.len()));
}

#[divan::bench]
fn orient3d_random(b: Bencher) {
    let mut r = Rng::new(1);
    let pts: Vec<DVec3> = (0..4096)
        .map(|_| DVec3::new(r.unit(), r.unit(), r.unit()))
        .collect();
    b.counter(divan::counter::ItemsCount::new(4093usize))
        .bench(|| {
            let mut s = 0i32;
            for w in pts.windows(4) {
                s += orient3d(w[0], w[1], w[2], w[3]) as i32;
            }
            s
        });
}

#[divan::bench]
fn orient3d_sos_grid(b: Bencher) {
    let mut r = Rng::new(2);
    let pts: Vec<SymPoint> = (0..4096u32)
        .map(|i| {
            let g = |r: &mut Rng| (r.unit() * 3.0).floor();
            SymPoint::new(DVec3::new(g(&mut r), g(&mut r), g(&mut r)), i)
        })
        .collect();
    b.counter(divan::counter::ItemsCount::new(4093usize))
        .bench(|| {
            let mut s = 0i32;
            for w in pts.windows(4) {
                s += orient3d_sos(w[0], w[1], w[2], w[3]).as_i8() as i32;
            }
            s
        });
}
