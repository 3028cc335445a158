//! Drags BEFORE.obj to AFTER.obj (same triangles) in FRAMES equal linear
//! steps with an [`Accumulator`], then prints the audit of the unguarded
//! release and of the guarded one (and what the guard refused).
//!
//! `cargo run --release -p holey-topo --example drag_release -- BEFORE.obj AFTER.obj FRAMES`

use glam::DVec3;
use holey_topo::{Accumulator, Options, SurfaceAudit, TriMesh, topology_change};

fn read_obj(path: &str) -> Result<TriMesh, Box<dyn std::error::Error>> {
    let mut m = TriMesh::default();
    for line in std::fs::read_to_string(path)?.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("v") => {
                let c: Vec<f64> = w.take(3).map(str::parse).collect::<Result<_, _>>()?;
                m.positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let idx: Vec<u32> = w
                    .map(|s| {
                        s.split('/')
                            .next()
                            .unwrap_or("")
                            .parse::<u32>()
                            .map(|i| i - 1)
                    })
                    .collect::<Result<_, _>>()?;
                for k in 1..idx.len() - 1 {
                    m.triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok(m)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (a, b) = (read_obj(&args[1])?, read_obj(&args[2])?);
    let frames: usize = args.get(3).map_or(Ok(10), |s| s.parse())?;
    let options = Options::default();
    let drag = |a: &TriMesh| -> Result<Accumulator, Box<dyn std::error::Error>> {
        let mut acc = Accumulator::new(a.clone(), options)?;
        for f in 1..=frames {
            let t = f as f64 / frames as f64;
            let next: Vec<DVec3> = a
                .positions
                .iter()
                .zip(&b.positions)
                .map(|(p, q)| p.lerp(*q, t))
                .collect();
            acc.advance(&next)?;
        }
        Ok(acc)
    };
    let acc = drag(&a)?;
    let raw = acc.raw_parity().iter().filter(|&&o| o).count();
    let whole = acc.release()?;
    println!(
        "release (whole, raw odd {raw}): {}",
        SurfaceAudit::of(&whole.mesh)?
    );
    println!("  {:?}", whole.report.cut);
    let one = topology_change(&a, &b.positions, &options)?;
    let raw1 = one.report.raw_odd_vertices;
    println!(
        "one frame (raw odd {raw1}): {}",
        SurfaceAudit::of(&one.mesh)?
    );
    let r = drag(&a)?.release_guarded()?;
    println!("guarded: {}", SurfaceAudit::of(&r.mesh)?);
    println!(
        "  refused {:?}; region {} whole {}",
        r.refused, r.report.region_triangles, r.report.whole_mesh
    );
    Ok(())
}
