//! Runs one frame (BEFORE.obj moving to AFTER.obj, same triangles) both on
//! the region the motion reaches and on the whole mesh, and prints the
//! audit of each result: a check that locality changes nothing.
//!
//! `cargo run --release -p holey-topo --example local_vs_whole -- BEFORE.obj AFTER.obj`

use glam::DVec3;
use holey_topo::{Options, SurfaceAudit, TriMesh, topology_change, topology_change_local};

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
    let options = Options::default();
    let whole = topology_change(&a, &b.positions, &options)?;
    println!("whole: {}", SurfaceAudit::of(&whole.mesh)?);
    println!("  {:?}", whole.report.cut);
    let mut local = a.clone();
    let r = topology_change_local(&mut local, &b.positions, &options)?;
    println!("local: {}", SurfaceAudit::of(&local)?);
    println!(
        "  region {} triangles, whole {}, {:?}",
        r.region_triangles, r.whole_mesh, r.report.cut
    );
    Ok(())
}
