//! Sculpting (Bernstein & Wojtan §4): an inflate stroke dragged over an
//! icosphere, then smoothed, each frame through the topology-change
//! engine and dynamic remeshing, each stroke reported as `holey sculpt`
//! reports it. The result is written as OBJ.
//!
//! ```text
//! cargo run --release -p holey --example sculpt_bump -- [OUT.obj]
//! ```

use std::path::Path;

use holey::prelude::*;
use holey::sculpt::{Brush, Session, Stroke};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "sculpted.obj".to_string());
    let mut session = Session::new(triangles(&shapes::parse_primitive("@sphere:5")?))?;
    let arc: Vec<DVec3> = (0..20)
        .map(|i| {
            let a = 0.3 * f64::from(i) / 19.0;
            DVec3::new(a.sin(), 0.0, a.cos())
        })
        .collect();
    let strokes = [
        Stroke {
            brush: Brush::Inflate,
            radius: 0.3,
            strength: 0.01,
            path: arc.clone(),
            ..Stroke::default()
        },
        Stroke {
            brush: Brush::Smooth,
            radius: 0.3,
            strength: 0.5,
            path: arc,
            ..Stroke::default()
        },
    ];
    for stroke in &strokes {
        let r = session.apply_stroke(stroke)?;
        println!(
            "{}: {} frames, {} topology changes, {} -> {} triangles, {:.3} s",
            stroke.brush, r.frames, r.changes, r.triangles_before, r.triangles_after, r.seconds
        );
    }
    let mesh = session.into_mesh();
    let options = io::WriteOptions::default();
    io::write_poly(Path::new(&out), &PolyMesh::from(&mesh), &options)?;
    println!("{out}: {} triangles", mesh.triangles.len());
    Ok(())
}
