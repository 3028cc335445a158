//! The topology-change engine (issue: topo, performance): Theorem 5.2
//! unions of two icospheres and their self-intersections, over sizes from
//! 41k to 655k triangles in all, to show how the time scales; and the
//! one-pass winding numbers at a few points.
//!
//! cargo bench -p holey-bench --bench topo

use divan::{Bencher, black_box};
use glam::DVec3;
use holey_topo::{Options, TriMesh, self_intersections, topology_change, union};

fn main() {
    divan::main();
}

/// Sphere A and sphere B = A + (0.5, 0.1, 0.05); B arrives from 4 units
/// away along a generic direction, as `holey union` moves it.
fn union_frame(level: u32) -> (TriMesh, Vec<DVec3>) {
    let a = holey_bench::icosphere(level);
    let shift = DVec3::new(0.5, 0.1, 0.05);
    let away = DVec3::new(1.0, 0.3127, 0.1731).normalize() * 4.0;
    let mut start = a.clone();
    start.append(&a.translated(shift + away));
    let end: Vec<DVec3> = a
        .positions
        .iter()
        .copied()
        .chain(a.positions.iter().map(|p| *p + shift))
        .collect();
    (start, end)
}

/// Levels 4 to 8: 10,240, 40,960, 163,840, 655,360 and 2,621,440
/// triangles in all.
#[divan::bench(args = [4, 5, 6, 7, 8], sample_count = 3)]
fn union_of_two_spheres(bencher: Bencher, level: u32) {
    let (start, end) = union_frame(level);
    bencher.bench_local(|| {
        black_box(
            topology_change(&start, &end, &Options::default()).map(|o| o.mesh.triangles.len()),
        )
    });
}

/// The same union by containment parity (`holey_topo::union`, what
/// `holey union` runs for closed solids): no motion, A × B only.
#[divan::bench(args = [4, 5, 6, 7, 8], sample_count = 3)]
fn union_of_two_spheres_by_containment(bencher: Bencher, level: u32) {
    let a = holey_bench::icosphere(level);
    let b = TriMesh {
        positions: a
            .positions
            .iter()
            .map(|p| *p + DVec3::new(0.5, 0.1, 0.05))
            .collect(),
        triangles: a.triangles.clone(),
    };
    bencher.bench_local(|| {
        black_box(union(&a, &b, &Options::default()).map(|o| o.mesh.triangles.len()))
    });
}

#[divan::bench(args = [4, 5, 6, 7, 8], sample_count = 3)]
fn self_intersections_of_two_spheres(bencher: Bencher, level: u32) {
    let (mut both, end) = union_frame(level);
    both.positions = end;
    bencher.bench_local(|| black_box(self_intersections(&both).map(|x| x.pairs.len())));
}

/// The winding numbers of a whole sphere at four points near its surface
/// in one pass (`winding::winding_numbers_at`, what a sculpting frame
/// that changes topology asks of the surface around its region): 20k to
/// 1.3M triangles.
#[divan::bench(args = [5, 6, 7, 8], sample_count = 10)]
fn winding_numbers_at_four_points(bencher: Bencher, level: u32) {
    let sphere = holey_bench::icosphere(level);
    let points = [
        DVec3::new(0.0, 0.0, 0.99),
        DVec3::new(0.3, -0.2, 0.9),
        DVec3::new(-0.7, 0.7, 0.05),
        DVec3::new(0.5, 0.5, -0.69),
    ];
    let at = |v: u32| sphere.positions[v as usize];
    bencher.bench_local(|| {
        black_box(holey_topo::winding::winding_numbers_at(
            &sphere.triangles,
            &|_| true,
            &at,
            &points,
        ))
    });
}
