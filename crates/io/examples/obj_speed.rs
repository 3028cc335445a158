//! Measures how fast a big OBJ file reads (not a test: run it in release).
//!
//! ```text
//! cargo run --release -p holey-io --example obj_speed [FILE.obj]
//! ```
//!
//! Without an argument it generates, once, `holey-obj-speed.obj` in the
//! system's temporary directory: a 1000 × 500 torus grid, 500 000 vertices
//! with 6-decimal coordinates and 1 000 000 triangles (about 36 MB), and
//! times reading it (file read plus parse, best of five runs). Then it
//! writes the mesh with holey's OBJ writer and times reading that too.

use std::path::PathBuf;
use std::time::Instant;

fn generate(path: &PathBuf) -> std::io::Result<()> {
    use std::io::Write;
    let (nu, nv) = (1000usize, 500usize);
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        w,
        "# torus grid {nu} x {nv} for holey-io's OBJ speed measurement"
    )?;
    for i in 0..nu {
        let a = i as f64 / nu as f64 * std::f64::consts::TAU;
        for j in 0..nv {
            let b = j as f64 / nv as f64 * std::f64::consts::TAU;
            let r = 2.0 + 0.75 * b.cos();
            writeln!(
                w,
                "v {:.6} {:.6} {:.6}",
                r * a.cos(),
                r * a.sin(),
                0.75 * b.sin()
            )?;
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv) + 1;
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            writeln!(w, "f {a} {b} {c}")?;
            writeln!(w, "f {a} {c} {d}")?;
        }
    }
    w.flush()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = match std::env::args_os().nth(1) {
        Some(p) => PathBuf::from(p),
        None => {
            let p = std::env::temp_dir().join("holey-obj-speed.obj");
            if !p.exists() {
                eprintln!("generating {} ...", p.display());
                generate(&p)?;
            }
            p
        }
    };
    let m = measure(&path)?;
    // The same mesh as holey writes it: shortest round-trip coordinates
    // (up to 17 digits), which take the general float parser.
    let rt = std::env::temp_dir().join("holey-obj-speed-written.obj");
    let t = Instant::now();
    holey_io::write_poly(&rt, &m, &holey_io::WriteOptions::default())?;
    println!(
        "{}: written in {:.3} s",
        rt.display(),
        t.elapsed().as_secs_f64()
    );
    measure(&rt)?;
    std::fs::remove_file(&rt)?;
    Ok(())
}

/// Reads `path` five times and prints the best times.
fn measure(path: &PathBuf) -> Result<holey_io::PolyMesh, Box<dyn std::error::Error>> {
    let size = std::fs::metadata(path)?.len();
    let mut best = f64::INFINITY;
    let mut best_parse = f64::INFINITY;
    let mut mesh = None;
    for _ in 0..5 {
        let t0 = Instant::now();
        let bytes = std::fs::read(path)?;
        let t1 = Instant::now();
        let m = holey_io::obj::parse(&bytes, &path.display().to_string())?;
        let t2 = Instant::now();
        best = best.min((t2 - t0).as_secs_f64());
        best_parse = best_parse.min((t2 - t1).as_secs_f64());
        mesh = Some(m);
    }
    let m = mesh.ok_or("no run")?;
    println!(
        "{}: {:.1} MB, {} vertices, {} faces: read + parse {:.3} s (parse alone {:.3} s, {:.0} MB/s)",
        path.display(),
        size as f64 / 1e6,
        m.positions.len(),
        m.face_count(),
        best,
        best_parse,
        size as f64 / 1e6 / best_parse
    );
    Ok(m)
}
