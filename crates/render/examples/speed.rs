//! Times renders of primitives and, given a size, of a big icosphere
//! (release build): cargo run --release -p holey-render --example speed
use std::time::Instant;

use holey_render::{RenderOptions, render};

fn time(
    label: &str,
    mesh: &holey_mesh::PolyMesh,
    opts: &RenderOptions,
) -> Result<(), Box<dyn std::error::Error>> {
    if std::env::args()
        .nth(1)
        .is_some_and(|filter| filter != label)
    {
        return Ok(());
    }
    let mut best = f64::INFINITY;
    let mut png_best = f64::INFINITY;
    for _ in 0..5 {
        let t = Instant::now();
        let img = render(mesh, opts)?;
        best = best.min(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let _ = img.encode_png()?;
        png_best = png_best.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{label:<40} {:>9} faces {}x{} ss{} edges={} smooth={}: render {:.1} ms, png {:.1} ms",
        mesh.face_count(),
        opts.width,
        opts.height,
        opts.supersample,
        opts.edges,
        opts.smooth,
        best * 1e3,
        png_best * 1e3
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let big = RenderOptions {
        width: 1024,
        height: 768,
        ..RenderOptions::default()
    };
    let small = RenderOptions {
        width: 640,
        height: 480,
        ..RenderOptions::default()
    };
    // The variations timed: each run is one of these over its mesh's base.
    let ss = |o: &RenderOptions, supersample| RenderOptions {
        supersample,
        ..o.clone()
    };
    let smooth = |o: &RenderOptions| RenderOptions {
        smooth: true,
        ..o.clone()
    };
    let edges = |o: &RenderOptions| RenderOptions {
        edges: true,
        ..o.clone()
    };
    let t10k = holey_shapes::parse_primitive("@torus:100:50")?; // 5000 quads = 10k triangles
    time("10k", &t10k, &small)?;
    time("10k ss2", &t10k, &ss(&small, 2))?;
    time("10k ss1", &t10k, &ss(&small, 1))?;
    time("10k smooth", &t10k, &smooth(&small))?;
    time("10k edges", &t10k, &edges(&small))?;
    time("10k big", &t10k, &big)?;
    let t1m = holey_shapes::parse_primitive("@torus:1000:500")?; // 1M triangles
    time("1M", &t1m, &big)?;
    time("1M smooth", &t1m, &smooth(&big))?;
    time("1M edges", &t1m, &edges(&big))?;
    time("1M ss2", &t1m, &ss(&big, 2))?;
    let s1m = holey_shapes::parse_primitive("@sphere:8")?; // 1.3M triangles
    time("sphere 1.3M", &s1m, &big)?;
    time("sphere 1.3M smooth", &s1m, &smooth(&big))?;
    Ok(())
}
