//! Replays a stroke file frame by frame and prints, for every frame, what
//! the engine did and an exact audit of the surface; optionally writes the
//! motion of one frame as two OBJ files (the surface before it and the
//! positions the brush moves it to) for `holey topo`.
//!
//! ```text
//! cargo run --release -p holey-sculpt --example frame_trace -- MESH STROKES.json [--no-remesh] [--dump K]
//! ```

use std::path::Path;

use holey_io::MeshFile;
use holey_sculpt::brush::{inflate, smooth};
use holey_sculpt::{Brush, BrushSettings, LiveStroke, RemeshOptions, default_range, parse_strokes};
use holey_topo::{Options, SurfaceAudit, TriMesh};

fn write_obj(path: &str, positions: &[glam::DVec3], tris: &[[u32; 3]]) -> std::io::Result<()> {
    use std::fmt::Write;
    let mut s = String::new();
    for p in positions {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for t in tris {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    std::fs::write(path, s)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let no_remesh = args.iter().any(|a| a == "--no-remesh");
    let dump: Option<usize> = args
        .iter()
        .position(|a| a == "--dump")
        .and_then(|i| args.get(i + 1))
        .and_then(|k| k.parse().ok());
    let MeshFile::Poly(poly) = holey_io::read_path(Path::new(&args[1]))? else {
        return Err("a polygon mesh file, please".into());
    };
    let (triangles, _) = poly.fan_triangles();
    let mut mesh = TriMesh {
        positions: poly.positions,
        triangles,
    };
    let file = parse_strokes(&std::fs::read_to_string(&args[2])?)?;
    let range = file.remesh.or_else(|| default_range(&mesh));
    println!("input: {}", SurfaceAudit::of(&mesh)?);
    let mut frame_no = 0usize;
    for (s, stroke) in file.strokes.iter().enumerate() {
        let settings = BrushSettings {
            brush: stroke.brush,
            radius: stroke.radius,
            strength: stroke.strength,
        };
        let first = stroke.path.first().copied().unwrap_or_default();
        let mut live = LiveStroke::begin(&mesh, settings, first, Options::default())?;
        if !no_remesh {
            live.set_remesh(range.map(RemeshOptions::new));
        }
        let mut before = SurfaceAudit::of(&mesh)?;
        for (i, &point) in stroke.path.iter().enumerate() {
            if dump == Some(frame_no) && !stroke.brush.is_drag() {
                let m = live.mesh();
                let end = match stroke.brush {
                    Brush::Smooth => smooth(m, point, stroke.radius, stroke.strength),
                    _ => inflate(m, point, stroke.radius, stroke.strength),
                };
                write_obj("trace_before.obj", &m.positions, &m.triangles)?;
                write_obj("trace_after.obj", &end, &m.triangles)?;
                println!("wrote trace_before.obj and trace_after.obj (frame {frame_no})");
            }
            let f = live.frame(point)?;
            let seconds = f.seconds;
            let now = SurfaceAudit::of(live.mesh())?;
            let worse = before.regressions(&now);
            println!(
                "stroke {s} frame {i} (#{frame_no}) {:.1} ms: {now}{}",
                seconds * 1e3,
                if worse.is_empty() {
                    String::new()
                } else {
                    format!(" WORSE: {}", worse.join(", "))
                }
            );
            before = now;
            frame_no += 1;
        }
        mesh = live.finish()?.mesh;
        println!("stroke {s} done: {}", SurfaceAudit::of(&mesh)?);
    }
    Ok(())
}
