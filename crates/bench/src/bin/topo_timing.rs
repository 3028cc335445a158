//! In-process timings of the topology engine on mesh files, for the
//! side-by-side comparison with peers (`bench/peers/topo_spheres.py`).
//!
//! The peers are timed inside one long-lived Python process, each call
//! after the first reusing memory the process already has. A fresh
//! `holey` process instead pays for every page it touches: on the
//! benchmark machine (a virtual machine) first touches of fresh memory
//! cost up to 2.7 ms per MB. This program times the library the way the
//! peers are timed: the files are read once, then the job runs `--runs`
//! times in one process, and the best run and every run are printed as
//! JSON, with the union's stage times in its best run.
//!
//! ```text
//! topo_timing union A.obj B.obj [--runs N]
//! topo_timing union-prepared A.obj B.obj [--runs N]
//! topo_timing selfint MESH.obj [--runs N]
//! ```

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use holey_io::MeshFile;
use holey_topo::{Options, TriMesh};

// The allocator the `holey` command line uses, so that the timings are
// the library's as the command runs it.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn load(path: &str) -> Result<TriMesh, String> {
    match holey_io::read_path(Path::new(path)).map_err(|e| e.to_string())? {
        MeshFile::Poly(poly) => Ok(poly.triangulated()),
        MeshFile::Dlfl(_) => Err(format!("{path}: give a polygon file (OBJ, OFF, PLY, STL)")),
    }
}

fn run() -> Result<String, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut runs = 5usize;
    let mut files = Vec::new();
    let mut it = args.iter();
    let job = it
        .next()
        .ok_or("usage: topo_timing union A B | union-prepared A B | selfint MESH [--runs N]")?;
    while let Some(a) = it.next() {
        if a == "--runs" {
            runs = it
                .next()
                .and_then(|n| n.parse().ok())
                .filter(|&n| n > 0)
                .ok_or("--runs needs a positive number")?;
        } else {
            files.push(a.clone());
        }
    }
    let mut times = Vec::with_capacity(runs);
    let mut result = 0usize;
    // The union's stages in its best run: intersections, parity, cut.
    let mut stages: Option<[f64; 3]> = None;
    let triangles;
    match (job.as_str(), files.as_slice()) {
        ("union", [a, b]) => {
            let (a, b) = (load(a)?, load(b)?);
            triangles = a.triangles.len() + b.triangles.len();
            time_unions(runs, &mut times, &mut stages, &mut result, || {
                holey_topo::union(&a, &b, &Options::default())
            })?;
        }
        ("union-prepared", [a, b]) => {
            // Both solids prepared once, outside the clock (as the peers'
            // mesh objects are built once and reused).
            let (a, b) = (load(a)?, load(b)?);
            triangles = a.triangles.len() + b.triangles.len();
            let a = holey_topo::PreparedSolid::new(a).map_err(|e| e.to_string())?;
            let b = holey_topo::PreparedSolid::new(b).map_err(|e| e.to_string())?;
            time_unions(runs, &mut times, &mut stages, &mut result, || {
                holey_topo::union_prepared(&a, &b, &Options::default())
            })?;
        }
        ("selfint", [m]) => {
            let m = load(m)?;
            triangles = m.triangles.len();
            for _ in 0..runs {
                let t = Instant::now();
                let x = holey_topo::self_intersections(&m).map_err(|e| e.to_string())?;
                times.push(t.elapsed().as_secs_f64());
                result = x.pairs.len();
            }
        }
        _ => {
            return Err(
                "usage: topo_timing union A B | union-prepared A B | selfint MESH [--runs N]"
                    .into(),
            );
        }
    }
    let best = times.iter().copied().fold(f64::INFINITY, f64::min);
    let list: Vec<String> = times.iter().map(|t| format!("{t:.6}")).collect();
    let stages = match stages {
        Some([x, p, c]) => format!(
            ", \"stages\": {{\"intersections\": {x:.6}, \"parity\": {p:.6}, \"cut\": {c:.6}}}"
        ),
        None => String::new(),
    };
    Ok(format!(
        "{{\"job\": \"{job}\", \"triangles\": {triangles}, \"result\": {result}, \"best\": {best:.6}, \"runs\": [{}]{stages}}}",
        list.join(", ")
    ))
}

/// Runs `union` `runs` times: every time into `times`, the stages of the
/// fastest run into `stages`, its triangle count into `result`.
fn time_unions(
    runs: usize,
    times: &mut Vec<f64>,
    stages: &mut Option<[f64; 3]>,
    result: &mut usize,
    union: impl Fn() -> Result<holey_topo::Outcome, holey_topo::UnionError>,
) -> Result<(), String> {
    for _ in 0..runs {
        let t = Instant::now();
        let out = union().map_err(|e| e.to_string())?;
        let took = t.elapsed().as_secs_f64();
        if times.iter().all(|&b| took < b) {
            let s = out.report.timings;
            *stages = Some([s.intersections, s.correction, s.cut]);
        }
        times.push(took);
        *result = out.mesh.triangles.len();
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(json) => {
            println!("{json}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("topo_timing: {e}");
            ExitCode::FAILURE
        }
    }
}
