//! Times the two ways the engine gets the winding numbers of a whole mesh
//! at a few points, on any mesh holey reads: one pass over its triangles
//! per query set ([`winding_numbers_at`]) against building a
//! [`WindingField`] octree and querying it. A frame that changes topology
//! asks for the far field at its pieces' samples, and
//! [`holey_topo::winding::FEW_POINTS`] picks the pass up to that many
//! points: this shows where the two cost the same, and how far the
//! field's answers are from the pass's.
//!
//! `cargo run --release -p holey-topo --example winding_crossover -- MESH [POINTS ...]`
//!
//! The points sit on a short segment through the mesh's bounding box
//! centre; each figure is the best of three runs.

use std::time::Instant;

use glam::DVec3;
use holey_topo::winding::{FEW_POINTS, WindingField, winding_numbers_at};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        return Err("usage: winding_crossover MESH [POINTS ...]".into());
    };
    let holey_io::MeshFile::Poly(poly) = holey_io::read_path(std::path::Path::new(path))? else {
        return Err(format!("{path}: not a polygon mesh").into());
    };
    let mesh = poly.triangulated();
    let counts: Vec<usize> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|a| a.parse())
            .collect::<Result<_, _>>()?
    } else {
        vec![8, 16, 24, 32, 48, 64]
    };
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| {
            (l.min(p), h.max(p))
        });
    let (centre, step) = ((lo + hi) * 0.5, (hi - lo).length() * 1e-3);
    let at = |v: u32| mesh.positions[v as usize];
    println!(
        "{path}: {} triangles; FEW_POINTS = {FEW_POINTS}",
        mesh.triangles.len()
    );
    for n in counts {
        let points: Vec<DVec3> = (0..n)
            .map(|i| centre + DVec3::Y * (step * i as f64))
            .collect();
        let (mut pass_best, mut field_best, mut apart) = (f64::MAX, f64::MAX, 0.0f64);
        for _ in 0..3 {
            let t = Instant::now();
            let by_pass = winding_numbers_at(&mesh.triangles, &|_| true, &at, &points);
            pass_best = pass_best.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let field = WindingField::new(&mesh.triangles, &at);
            let by_field: Vec<f64> = points.iter().map(|&p| field.at(p, None)).collect();
            field_best = field_best.min(t.elapsed().as_secs_f64());
            apart = by_pass
                .iter()
                .zip(&by_field)
                .map(|(a, b)| (a - b).abs())
                .fold(apart, f64::max);
        }
        println!(
            "{n:4} points: one pass {:8.1} ms, field built and queried {:8.1} ms, largest difference {apart:.1e}",
            pass_best * 1e3,
            field_best * 1e3
        );
    }
    Ok(())
}
