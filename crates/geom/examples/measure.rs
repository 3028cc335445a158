//! Prints the performance figures and disagreement rates of holey-geom:
//! `cargo run --release -p holey-geom --example measure`.

use glam::DVec3;
use holey_geom::bvh::{Aabb, Bvh};
use holey_geom::ccd::{CcdOptions, Narrow, vertex_parities};
use holey_geom::sos::stats;
use holey_geom::{
    Sign, SymPoint, edge_triangle_point, order_on_segment, orient3d, orient3d_sos,
    segment_triangle_intersect, triangle_triangle_segment, triangle_triangle_triangle_point,
};
use holey_testkit::Rng;
use std::time::Instant;

#[path = "../benches/scenes/mod.rs"]
mod scenes;

fn best_of<T>(n: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..n {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("n > 0"))
}

/// `points` as symbolic points, each with its index as its identity: the
/// inputs of the SoS predicates and constructions measured below.
fn symbolic(points: &[DVec3]) -> Vec<SymPoint> {
    points
        .iter()
        .enumerate()
        .map(|(i, &p)| SymPoint::new(p, i as u32))
        .collect()
}

fn main() {
    // Orientation throughput and fallback rates.
    let mut r = Rng::new(1);
    let n = 4_000_000;
    let rnd: Vec<DVec3> = (0..n)
        .map(|_| DVec3::new(r.unit(), r.unit(), r.unit()))
        .collect();
    let grid: Vec<DVec3> = (0..n)
        .map(|_| {
            DVec3::new(
                (r.unit() * 4.0).floor(),
                (r.unit() * 4.0).floor(),
                (r.unit() * 4.0).floor(),
            )
        })
        .collect();
    for (name, pts) in [("random", &rnd), ("4x4x4 grid", &grid)] {
        let (t, zeros) = best_of(3, || {
            pts.windows(4)
                .filter(|w| orient3d(w[0], w[1], w[2], w[3]) == Sign::Zero)
                .count()
        });
        println!(
            "orient3d {name}: {:.1} M/s, exact zero (SoS fallback) rate {:.4}%",
            (n - 3) as f64 / t / 1e6,
            100.0 * zeros as f64 / (n - 3) as f64
        );
        let sp = symbolic(pts);
        let (t, s) = best_of(3, || {
            sp.windows(4)
                .map(|w| orient3d_sos(w[0], w[1], w[2], w[3]).as_i8() as i64)
                .sum::<i64>()
        });
        println!(
            "orient3d_sos {name}: {:.1} M/s (checksum {s})",
            (n - 3) as f64 / t / 1e6
        );
    }

    // Derived predicates and constructions on random input.
    let sp = symbolic(&rnd[..300_000]);
    let (t, hits) = best_of(3, || {
        sp.chunks(5)
            .filter(|c| c.len() == 5 && segment_triangle_intersect(c[0], c[1], c[2], c[3], c[4]))
            .count()
    });
    println!(
        "segment_triangle_intersect random: {:.2} M/s ({hits} hits)",
        60_000.0 / t / 1e6
    );
    let (t, hits) = best_of(3, || {
        sp.chunks(9)
            .filter(|c| {
                c.len() == 9
                    && triangle_triangle_triangle_point(
                        [c[0], c[1], c[2]],
                        [c[3], c[4], c[5]],
                        [c[6], c[7], c[8]],
                    )
            })
            .count()
    });
    println!(
        "triangle_triangle_triangle_point random: {:.2} M/s ({hits} hits)",
        33_333.0 / t / 1e6
    );
    let (t, ok) = best_of(3, || {
        sp.chunks(5)
            .filter(|c| c.len() == 5 && edge_triangle_point(c[0], c[1], c[2], c[3], c[4]).is_ok())
            .count()
    });
    println!(
        "edge_triangle_point (10 correctly rounded values) random: {:.2} µs each ({ok})",
        t / 60_000.0 * 1e6
    );
    // Order along a segment where all crossings coincide (lattice planes):
    // the symbolic stage decides.
    let s3 = |x: f64, y: f64, z: f64, id: u32| SymPoint::new(DVec3::new(x, y, z), id);
    let t1 = [
        s3(0.0, 0.0, 0.0, 0),
        s3(8.0, 0.0, 0.0, 1),
        s3(0.0, 8.0, 0.0, 2),
    ];
    let t2 = [
        s3(0.0, 2.0, -2.0, 3),
        s3(8.0, 2.0, -2.0, 4),
        s3(0.0, 2.0, 6.0, 5),
    ];
    let seg = triangle_triangle_segment(t1, t2).expect("crossing");
    let planes: Vec<[SymPoint; 3]> = (0..8u32)
        .map(|k| {
            let tilt = k as f64 - 4.0;
            [
                s3(3.0 - tilt, -5.0, -5.0, 10 + 3 * k),
                s3(3.0 + tilt, 9.0, -5.0, 11 + 3 * k),
                s3(3.0, 2.0, 9.0, 12 + 3 * k),
            ]
        })
        .collect();
    stats::reset();
    let (t, _) = best_of(3, || {
        let mut c = 0;
        for a in &planes {
            for b in &planes {
                c += order_on_segment(&seg, *a, *b) as i32;
            }
        }
        c
    });
    let (calls, _, pert) = stats::read();
    println!(
        "order_on_segment, all 8 crossings at one point: {:.1} µs per comparison ({pert}/{calls} driver calls symbolic)",
        t / 64.0 * 1e6
    );

    // BVH on 1M boxes.
    let boxes: Vec<Aabb> = (0..1_000_000)
        .map(|_| {
            let c = DVec3::new(r.unit(), r.unit(), r.unit());
            let e = DVec3::new(r.unit(), r.unit(), r.unit()) * 0.002;
            Aabb::new(c - e, c + e)
        })
        .collect();
    let (t, bvh) = best_of(5, || Bvh::build(&boxes).expect("finite"));
    println!(
        "bvh build 1M boxes: {:.1} ms ({} nodes)",
        t * 1e3,
        bvh.node_count()
    );
    let (t, pairs) = best_of(3, || bvh.overlap_pairs(&boxes).len());
    println!(
        "bvh stream 1M query boxes over 1M: {:.1} ms ({pairs} pairs)",
        t * 1e3
    );
    let (t, pairs) = best_of(3, || bvh.self_overlaps().len());
    println!(
        "bvh self-overlaps 1M boxes: {:.1} ms ({pairs} pairs)",
        t * 1e3
    );

    // Two spheres of 262,144 triangles each.
    let (p, tr) = scenes::two_spheres();
    let tb = scenes::triangle_boxes(&p, &tr);
    let (tbuild, bvh) = best_of(5, || Bvh::build(&tb).expect("finite"));
    let (tq, pairs) = best_of(5, || bvh.self_overlaps().len());
    println!(
        "two spheres {} triangles: bvh build {:.1} ms, self-overlaps {:.1} ms ({pairs} pairs)",
        tr.len(),
        tbuild * 1e3,
        tq * 1e3
    );

    // CCD union: sphere B sweeps into sphere A.
    let (p, end, tr) = scenes::sphere_sweep();
    stats::reset();
    let (t, rep) = best_of(3, || {
        vertex_parities(&p, &end, &tr, &CcdOptions::default()).expect("valid")
    });
    let (calls, exact, pert) = stats::read();
    let odd = rep.odd.iter().filter(|&&o| o).count();
    println!(
        "ccd union {} triangles, exact: {:.1} ms, {} narrow tests, {odd} odd vertices; driver calls {} (exact stage {}, perturbed {}) over 3 runs",
        tr.len(),
        t * 1e3,
        rep.candidates,
        calls,
        exact,
        pert
    );
    let fopts = CcdOptions {
        narrow: Narrow::Float,
        ..Default::default()
    };
    let (t, frep) = best_of(3, || vertex_parities(&p, &end, &tr, &fopts).expect("valid"));
    let dis = rep
        .odd
        .iter()
        .zip(&frep.odd)
        .filter(|(a, b)| a != b)
        .count();
    let pair_dis = {
        let a: std::collections::BTreeSet<_> = rep.odd_pairs.iter().collect();
        let b: std::collections::BTreeSet<_> = frep.odd_pairs.iter().collect();
        a.symmetric_difference(&b).count()
    };
    println!(
        "ccd union, float cubic: {:.1} ms; vertices whose parity differs from exact: {dis}/{}; odd pairs differing: {pair_dis}/{}",
        t * 1e3,
        p.len(),
        rep.odd_pairs.len()
    );
}
