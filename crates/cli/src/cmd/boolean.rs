//! `holey intersection` and `holey difference`: the other two Booleans of
//! closed solids, by the containment parity of `holey union`'s direct
//! path (no motion gives them: Theorem 5.2 is a union).

use anyhow::Result;
use holey_topo::solids::{BooleanError, BooleanOptions, BooleanOutcome, Computed, Method};
use holey_topo::{Operation, TriMesh, UnionError};

use crate::cmd::topo::{EngineArgs, write_outcome};
use crate::cmd::winding;
use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::load_triangle_pair;

#[derive(clap::Args)]
#[command(after_help = "\
What is inside: a point is inside a solid when the solid's winding number
there is at least 1/2. The intersection is what is inside both, the
difference A − B what is inside A and not inside B.

When A or B crosses itself (checked exactly first, or found crossing
where it meets the other), or with --winding, the winding-number
arrangement of `holey union` computes it (see `holey union --help`):
self-crossing solids, overlapping and nested shells. Zero-area triangles
(three corners on a line, or two at one position, as snapping to a grid
leaves them) are taken out of both solids first, without moving the
surface; the report counts them (zero_area_removed).

Otherwise, how it is computed: the intersections of A with B (exact, with symbolic
perturbation), then one exact ray per region of vertices between the
intersection curves says whether the region lies inside the other
solid. The intersection keeps the part of each surface inside the other;
the difference A − B keeps A's surface outside B and B's surface inside
A, turned to face into the hole. Both solids must be closed (every edge
shared by an even number of triangles); otherwise the command says which
one and stops.

As for `holey union`, where coplanar faces of A and B overlap and the
exactly placed result is not a clean closed surface (or its points were
rounded together, or the solids only touch), the winding-number
arrangement answers first, exactly (snap-rounded where its rounded
points cross, as there); only if that is not clean is the run retried with B moved by a deterministic nudge of 2^-30 of the
scene's diagonal (then 16 and 256 times that, while each nudge leaves
fewer open edges, non-manifold edges and vertices, and crossing pairs);
--exact makes the containment's first attempt the only one.

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
    /// itself, the result keeps its crossings, and the report's
    /// `output_intersecting_pairs` may leave them out (where the cut
    /// merged points, it counts only pairs with a triangle of the cut).
    #[arg(long, conflicts_with = "winding")]
    pub no_check: bool,
    #[command(flatten)]
    pub engine: EngineArgs,
}

pub fn run(args: Args, op: Operation) -> Result<()> {
    args.engine.check_outputs()?;
    let (a, b) = load_triangle_pair(&args.a, &args.b)?;
    let names = [args.a.as_str(), args.b.as_str()];
    let options = BooleanOptions {
        engine: args.engine.options(),
        exact: args.exact,
        check: !args.no_check,
        method: args.winding.then_some(Method::Winding),
        direction: None,
    };
    let _p = Progress::start(op.name());
    let inputs = [a, b];
    let out = solid_boolean(&inputs, &names, op, &options)?;
    write_boolean(out, &inputs, &names, &args.output, &args.engine)
}

/// [`holey_topo::solid_boolean`] of `inputs` (named `names`), its errors
/// as bad input in words that name the operation's needs.
pub fn solid_boolean(
    inputs: &[TriMesh],
    names: &[&str],
    op: Operation,
    options: &BooleanOptions,
) -> Result<BooleanOutcome> {
    let refs: Vec<&TriMesh> = inputs.iter().collect();
    holey_topo::solid_boolean(&refs, op, options).map_err(|e| match e {
        BooleanError::Union(e @ (UnionError::NotClosed(_) | UnionError::SelfIntersecting(_))) => {
            bad_input(format!("{e} (the {} needs two closed solids)", op.name()))
        }
        BooleanError::Empty(_) if names.len() == 2 => bad_input("both solids must have vertices"),
        BooleanError::Empty(i) => bad_input(format!(
            "{} has no vertices",
            names.get(i).copied().unwrap_or("an input")
        )),
        e => bad_input(e.to_string()),
    })
}

/// Writes what [`solid_boolean`] made: the result, and its report and
/// parity picture where `engine` asks, in the form of its method.
pub fn write_boolean(
    out: BooleanOutcome,
    inputs: &[TriMesh],
    names: &[&str],
    output: &str,
    engine: &EngineArgs,
) -> Result<()> {
    let seconds = out.seconds;
    let method = out.method.name();
    // The parity picture copies both inputs: made only when asked for.
    let picture = match &engine.parity {
        Some(_) => out.at_end(&inputs.iter().collect::<Vec<_>>()),
        None => None,
    };
    match out.computed {
        Computed::Winding(w) => winding::write(&w, names, output, engine),
        Computed::Parity(mut o) => {
            // The total includes the check that chose the method.
            o.report.timings.total = seconds;
            write_outcome(&o, output, engine, Some(method), || {
                picture.unwrap_or_default()
            })
        }
    }
}
