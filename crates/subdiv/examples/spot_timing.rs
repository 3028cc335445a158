//! Times six Catmull–Clark levels of the shared spot control mesh (or any
//! OBJ given as the first argument), best of several runs, with the
//! breakdown: subdivision on flat arrays, `Mesh::from_raw` (build and
//! validate), and `validate` alone.
//!
//! `cargo run --release -p holey-subdiv --example spot_timing [file.obj] [levels] [runs]`

use std::path::PathBuf;
use std::time::{Duration, Instant};

use holey_dlfl::Mesh;
use holey_subdiv::{Scheme, subdivide_to_raw};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = match args.next() {
        Some(p) => PathBuf::from(p),
        None => holey_testkit::shared_meshes()
            .ok_or("no shared meshes folder; pass an OBJ file")?
            .join("spot_control_mesh.obj"),
    };
    let levels: usize = args.next().map_or(Ok(6), |s| s.parse())?;
    let runs: usize = args.next().map_or(Ok(7), |s| s.parse())?;
    let scheme = match args.next().as_deref() {
        Some("ds") => Scheme::DooSabin,
        _ => Scheme::CatmullClark,
    };
    let holey_io::MeshFile::Poly(poly) = holey_io::read_path(&path)? else {
        return Err("expected a polygon file".into());
    };
    let mesh = holey_dlfl::convert::to_dlfl(&poly, Default::default())?.mesh;
    // The output as `subdivide` lays it out (localized), for timing the
    // kernel build alone.
    let localized = holey_subdiv::subdivide(&mesh, scheme, levels)?.to_raw();
    let (mut flat, mut build, mut valid, mut total) =
        (Duration::MAX, Duration::MAX, Duration::MAX, Duration::MAX);
    let mut out = Mesh::new();
    for _ in 0..runs {
        let t0 = Instant::now();
        let raw = subdivide_to_raw(&mesh, scheme, levels)?;
        let t1 = Instant::now();
        drop(raw);
        let t2 = Instant::now();
        eprintln!(
            "levels {:.1} ms, drop {:.1} ms",
            (t1 - t0).as_secs_f64() * 1e3,
            (t2 - t1).as_secs_f64() * 1e3
        );
        out = Mesh::from_raw(&localized)?;
        let t3 = Instant::now();
        out.validate()?;
        let t4 = Instant::now();
        let again = holey_subdiv::subdivide(&mesh, scheme, levels)?;
        let t5 = Instant::now();
        drop(again);
        flat = flat.min(t1 - t0);
        build = build.min(t3 - t2);
        valid = valid.min(t4 - t3);
        total = total.min(t5 - t4);
    }
    println!(
        "{scheme} x{levels} of {}: V {} E {} F {} corners {}",
        path.display(),
        out.vertex_count(),
        out.edge_count(),
        out.face_count(),
        out.corner_count()
    );
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!(
        "best of {runs}: subdivide() {:.1} ms; levels on flat arrays {:.1} ms; \
         localize ~{:.1} ms; Mesh::from_raw {:.1} ms, of which validate ~{:.1} ms",
        ms(total),
        ms(flat),
        ms(total.saturating_sub(flat + build)),
        ms(build),
        ms(valid)
    );
    Ok(())
}
