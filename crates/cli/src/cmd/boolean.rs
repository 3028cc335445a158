//! `holey intersection` and `holey difference`: the other two Booleans of
//! closed solids, by the containment parity of `holey union`'s direct
//! path (no motion gives them: Theorem 5.2 is a union).

use anyhow::Result;
use holey_topo::union::nudge;
use holey_topo::{Operation, UnionError};

use crate::cmd::topo::{EngineArgs, write_outcome};
use crate::cmd::union::joined;
use crate::cmd::winding;
use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::load_triangle_pair;

#[derive(clap::Args)]
#[command(after_help = "\
What is inside: a point is inside a solid when the solid's winding number
there is at least 1/2. The intersection is what is inside both, the
difference A − B what is inside A and not inside B.

When A or B crosses itself (checked exactly first), or with --winding,
the winding-number arrangement of `holey union` computes it (see `holey
union --help`): self-crossing solids, overlapping and nested shells.

Otherwise, how it is computed: the intersections of A with B (exact, with symbolic
perturbation), then one exact ray per region of vertices between the
intersection curves says whether the region lies inside the other
solid. The intersection keeps the part of each surface inside the other;
the difference A − B keeps A's surface outside B and B's surface inside
A, turned to face into the hole. Both solids must be closed (every edge
shared by an even number of triangles); otherwise the command says which
one and stops.

As for `holey union`, where coplanar faces of A and B overlap and the
exactly placed result is not a closed surface, the run is retried with B
moved by a deterministic nudge of 2^-30 of the scene's diagonal (then 16
and 256 times that); --exact makes the first attempt the only one.

Examples:
  holey intersection a.obj b.obj meet.obj
  holey difference @cube:4 b.ply hollow.ply --report r.json")]
pub struct Args {
    /// The first solid (for a difference, the one cut into).
    pub a: String,
    /// The second solid (for a difference, the one taken away).
    pub b: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Do not perturb B's position where coplanar faces overlap.
    #[arg(long)]
    pub exact: bool,
    /// Use the winding-number arrangement even when neither solid crosses
    /// itself (see below).
    #[arg(long)]
    pub winding: bool,
    /// Skip the exact check that the two solids are closed 2-manifolds
    /// that do not cross themselves (about the time of `holey selfint` on
    /// both): for inputs known to be such solids. If one does cross
    /// itself, the result keeps its crossings.
    #[arg(long, conflicts_with = "winding")]
    pub no_check: bool,
    #[command(flatten)]
    pub engine: EngineArgs,
}

pub fn run(args: Args, op: Operation) -> Result<()> {
    args.engine.check_outputs()?;
    let (a, b) = load_triangle_pair(&args.a, &args.b)?;
    if a.positions.is_empty() || b.positions.is_empty() {
        return Err(bad_input("both solids must have vertices"));
    }
    let _p = Progress::start(op.name());
    let checked = std::time::Instant::now();
    if args.winding || (!args.no_check && winding::needs_winding(&a, &b)?) {
        let names = [args.a.as_str(), args.b.as_str()];
        return winding::run(&[a, b], &names, op, &args.output, &args.engine, args.exact);
    }
    let options = args.engine.options();
    let result = if args.exact {
        holey_topo::boolean(&a, &b, op, &options)
    } else {
        holey_topo::boolean_robust(&a, &b, op, &options)
    };
    let mut out = result.map_err(|e| match e {
        UnionError::NotClosed(_) | UnionError::SelfIntersecting(_) => {
            bad_input(format!("{e} (the {} needs two closed solids)", op.name()))
        }
        e => bad_input(e.to_string()),
    })?;
    // The engine's total includes the check that sent the pair here.
    out.report.timings.total = checked.elapsed().as_secs_f64();
    let retries = out.report.perturbation_retries;
    write_outcome(&out, &args.output, &args.engine, || {
        joined(&a, &b, nudge(&a, &b, retries))
    })
}
