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
use holey_sculpt::{Brush, BrushSettings, LiveStroke, RemeshOptions, default_range};
use holey_topo::{Options, TriMesh};

fn main() {
    divan::main();
}

fn sphere(level: u32) -> TriMesh {
    let soup = holey_shapes::parse_primitive(&format!("@sphere:{level}"))
        .unwrap_or_else(|e| panic!("sphere {level}: {e}"));
    let (triangles, _) = soup.fan_triangles();
    TriMesh {
        positions: soup.positions,
        triangles,
    }
}

/// The radius whose cap on the unit sphere holds about 2,000 triangles.
fn radius_for(mesh: &TriMesh) -> f64 {
    let share = 2000.0 / mesh.triangles.len() as f64;
    // A cap of geodesic radius r has area 2π(1 − cos r) of 4π.
    (1.0 - 2.0 * share).acos()
}

fn frame(bencher: Bencher, level: u32, brush: Brush, strength: f64, to: DVec3) {
    let mesh = sphere(level);
    let radius = radius_for(&mesh);
    let settings = BrushSettings {
        brush,
        radius,
        strength,
    };
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
