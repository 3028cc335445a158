//! Runs one frame (BEFORE moving to AFTER, same triangles) both on the
//! region the motion reaches and on the whole mesh, and prints the audit
//! of each result: a check that locality changes nothing. With FRAMES, the
//! same motion also runs as a drag of that many equal steps (an
//! [`Accumulator`]), released whole and guarded (with what the guard
//! refused): a check that a drag resolves as its one frame does.
//!
//! `cargo run --release -p holey-topo --example local_vs_whole -- BEFORE.obj AFTER.obj [FRAMES]`

use holey_topo::{
    Accumulator, Options, SurfaceAudit, TriMesh, topology_change, topology_change_local,
};

/// The mesh of any file holey reads, fan-triangulated.
fn read(path: &str) -> Result<TriMesh, Box<dyn std::error::Error>> {
    match holey_io::read_path(std::path::Path::new(path))? {
        holey_io::MeshFile::Poly(p) => Ok(p.triangulated()),
        _ => Err(format!("{path}: not a polygon mesh").into()),
    }
}

/// `a` dragged to `b` in `frames` equal linear steps.
fn drag(a: &TriMesh, b: &TriMesh, frames: u32) -> Result<Accumulator, Box<dyn std::error::Error>> {
    let mut acc = Accumulator::new(a.clone(), Options::default())?;
    for f in 1..=frames {
        let t = f64::from(f) / f64::from(frames);
        let next: Vec<_> = a
            .positions
            .iter()
            .zip(&b.positions)
            .map(|(p, q)| p.lerp(*q, t))
            .collect();
        acc.advance(&next)?;
    }
    Ok(acc)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 3 {
        return Err("usage: local_vs_whole BEFORE AFTER [FRAMES]".into());
    }
    let (a, b) = (read(&args[1])?, read(&args[2])?);
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
    if let Some(frames) = args.get(3) {
        let frames: u32 = frames.parse()?;
        let released = drag(&a, &b, frames)?.release()?;
        println!("drag released: {}", SurfaceAudit::of(&released.mesh)?);
        println!("  {:?}", released.report.cut);
        let guarded = drag(&a, &b, frames)?.release_guarded()?;
        println!("drag guarded: {}", SurfaceAudit::of(&guarded.mesh)?);
        println!("  refused {:?}", guarded.refused);
    }
    Ok(())
}
