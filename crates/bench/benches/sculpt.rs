//! Sculpting frames (issue: sculpt, performance): one frame of each brush
//! on icospheres of 82k and 1.3M triangles, the brush touching about 2,000
//! triangles, to show that the per-frame cost follows the brush, not the
//! mesh. The stroke is begun outside the timed part; each sample is one
//! frame: the brush, the local topology change, the remeshing of the
//! brushed region (inflate, smooth) and, for grab, the live preview of
//! what would vanish.
//!
//! cargo bench -p holey-bench --bench sculpt

use divan::{Bencher, black_box};
use glam::DVec3;
use holey_sculpt::{
    Brush, BrushSettings, LiveStroke, Remesh, RemeshOptions, default_range, remesh_in_place,
};
use holey_topo::{Options, TriMesh};

fn main() {
    divan::main();
}

/// The radius whose cap on the unit sphere holds about 2,000 triangles.
fn radius_for(mesh: &TriMesh) -> f64 {
    let share = 2000.0 / mesh.triangles.len() as f64;
    // A cap of geodesic radius r has area 2π(1 − cos r) of 4π.
    (1.0 - 2.0 * share).acos()
}

fn frame(bencher: Bencher, level: u32, brush: Brush, strength: f64, to: DVec3) {
    let mesh = holey_bench::icosphere(level);
    let radius = radius_for(&mesh);
    let settings = BrushSettings::new(brush, radius, strength);
    let top = DVec3::Z;
    bencher
        .with_inputs(|| {
            let mut live = LiveStroke::begin(&mesh, settings, top, Options::default())
                .unwrap_or_else(|e| panic!("{e}"));
            live.set_preview(brush.is_drag());
            // Remeshing as `holey sculpt` does by default.
            live.set_remesh(default_range(&mesh).map(RemeshOptions::new));
            live
        })
        .bench_local_values(|mut live| {
            black_box(
                live.frame(top + to * radius)
                    .map(|f| f.mesh.triangles.len()),
            )
        });
}

/// Levels 6 and 8: 81,920 and 1,310,720 triangles.
#[divan::bench(args = [6, 8], sample_count = 10)]
fn inflate_frame(bencher: Bencher, level: u32) {
    frame(bencher, level, Brush::Inflate, 0.002, DVec3::ZERO);
}

#[divan::bench(args = [6, 8], sample_count = 10)]
fn smooth_frame(bencher: Bencher, level: u32) {
    frame(bencher, level, Brush::Smooth, 0.5, DVec3::ZERO);
}

#[divan::bench(args = [6, 8], sample_count = 10)]
fn grab_frame_with_preview(bencher: Bencher, level: u32) {
    frame(bencher, level, Brush::Grab, 1.0, DVec3::new(0.0, 0.2, -0.2));
}

/// Dynamic remeshing alone: a region of about 2,000 triangles in flat
/// grids of 100k and 1M triangles, raised by one frame of inflate (which
/// stretches its edges: splits and flips) or left flat (nothing to do:
/// the cost of finding the region). Grids 224² and 708².
#[divan::bench(args = [224, 708], sample_count = 10)]
fn remesh_bumped_region(bencher: Bencher, n: u32) {
    remesh_region(bencher, n, true);
}

#[divan::bench(args = [224, 708], sample_count = 10)]
fn remesh_flat_region(bencher: Bencher, n: u32) {
    remesh_region(bencher, n, false);
}

fn remesh_region(bencher: Bencher, n: u32, bump: bool) {
    let mut mesh = holey_bench::tri_grid(n);
    let h = 2.0 / f64::from(n);
    let radius = (1000.0 * h * h / std::f64::consts::PI).sqrt();
    let active: Vec<bool> = mesh
        .positions
        .iter()
        .map(|p| p.truncate().length() < radius)
        .collect();
    if bump {
        for p in &mut mesh.positions {
            let d = p.truncate().length();
            if d < radius {
                let s = 1.0 - (d / radius).powi(2);
                p.z += 0.5 * radius * s * s;
            }
        }
    }
    let opts = RemeshOptions::new(Remesh {
        min_edge: 0.6 * h,
        max_edge: 1.5 * h,
    });
    bencher
        .with_inputs(|| {
            // Room to grow, as a session keeps, so splits do not copy.
            let mut m = mesh.clone();
            m.positions.reserve(100_000);
            m.triangles.reserve(100_000);
            m
        })
        .bench_local_values(|mut m| {
            black_box(remesh_in_place(&mut m, &active, &opts).map(|r| r.splits))
        });
}
