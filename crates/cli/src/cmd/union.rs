//! `holey union`: the Boolean union of two solids by Theorem 5.2 of
//! Bernstein & Wojtan 2013: move one solid into the other and let the
//! topology change delete what ends up inside.

use anyhow::Result;
use glam::DVec3;
use holey_topo::TriMesh;

use crate::cmd::topo::{EngineArgs, run_engine};
use crate::error::bad_input;
use crate::tri::load_triangles;

/// The default direction B arrives from: generic, so that B's vertices
/// travel along lines that pass through none of the vertices and edges of
/// a mesh built on an axis-aligned lattice (a union of two copies of one
/// mesh shifted along an axis is the common case, and an axis-aligned
/// approach would make every collision degenerate).
const DEFAULT_DIRECTION: [f64; 3] = [1.0, 0.3127, 0.1731];

#[derive(clap::Args)]
#[command(after_help = "\
The motion: B is first translated by s·d, where d is the unit vector
along --direction and s is the distance that puts B's shadow on d wholly
beyond A's plus 10% of the two shadows' combined length (so B starts well
clear of A's bounding box), and then moves in a straight line back to its
given position in one frame. A vertex of either solid that ends inside the
other hits the other's surface an odd number of times (Theorem 5.2), so
the topology change deletes exactly the parts inside: the union.

A and B should be closed, consistently oriented solids; other meshes are
accepted and give what the same motion gives in `holey topo`. The default
direction is generic (not along an axis) so that the paths of B's
vertices avoid A's vertices and edges even when A and B are copies of one
lattice-built mesh.

Examples:
  holey union a.obj b.obj union.obj
  holey union @sphere:4 b.ply u.ply --direction 0,0,1 --report r.json")]
pub struct Args {
    /// The first solid; it stays in place.
    pub a: String,
    /// The second solid, at its final position.
    pub b: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Direction B arrives from, as x,y,z.
    #[arg(long, value_name = "X,Y,Z")]
    pub direction: Option<String>,
    #[command(flatten)]
    pub engine: EngineArgs,
}

fn parse_direction(s: &str) -> Result<DVec3> {
    let parts: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad_input(format!("--direction {s:?} is not three numbers x,y,z")))?;
    let [x, y, z] = parts[..] else {
        return Err(bad_input(format!(
            "--direction {s:?} is not three numbers x,y,z"
        )));
    };
    let d = DVec3::new(x, y, z);
    let len = d.length();
    if !len.is_finite() || len == 0.0 {
        return Err(bad_input(format!(
            "--direction {s:?} must be a finite, non-zero vector"
        )));
    }
    Ok(d / len)
}

/// The start positions of `a` joined with `b` moved away along `d`.
pub fn synthesize(a: &TriMesh, b: &TriMesh, d: DVec3) -> (TriMesh, Vec<DVec3>) {
    let shadow = |m: &TriMesh| {
        m.positions
            .iter()
            .map(|p| p.dot(d))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let (alo, ahi) = shadow(a);
    let (blo, bhi) = shadow(b);
    let (alen, blen) = ((ahi - alo).max(0.0), (bhi - blo).max(0.0));
    let s = (ahi - blo).max(0.0) + 0.1 * (alen + blen) + f64::MIN_POSITIVE;
    let offset = d * s;
    let n = a.positions.len() as u32;
    let mut start = a.clone();
    start
        .positions
        .extend(b.positions.iter().map(|p| *p + offset));
    start
        .triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
    (start, end)
}

pub fn run(args: Args) -> Result<()> {
    let a = load_triangles(&args.a)?;
    let b = load_triangles(&args.b)?;
    if a.positions.is_empty() || b.positions.is_empty() {
        return Err(bad_input("both solids must have vertices"));
    }
    if a.positions.len() + b.positions.len() >= u32::MAX as usize / 2 {
        return Err(bad_input("the two meshes together have too many vertices"));
    }
    let d = match &args.direction {
        Some(s) => parse_direction(s)?,
        None => DVec3::from_array(DEFAULT_DIRECTION).normalize(),
    };
    let (start, end) = synthesize(&a, &b, d);
    if start.positions.iter().any(|p| !p.is_finite()) {
        return Err(bad_input(
            "B's start position overflows: the coordinates are too large",
        ));
    }
    run_engine(&start, &end, &args.output, &args.engine)
}
