//! `holey union`: the Boolean union of two solids by Theorem 5.2 of
//! Bernstein & Wojtan 2013: move one solid into the other and let the
//! topology change delete what ends up inside.

use anyhow::Result;
use glam::DVec3;
use holey_topo::solids::{BooleanOptions, Method};
use holey_topo::{Operation, TriMesh};

use crate::cmd::boolean::{solid_boolean, write_boolean};
use crate::cmd::topo::EngineArgs;
use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::{load_triangle_pair, load_triangles};

#[derive(clap::Args)]
#[command(after_help = "\
What is inside: a point is inside a solid when the solid's winding number
there is at least 1/2 (for a closed surface, an integer: the number of
times the surface wraps around the point). The union is everything inside
any input.

Which computation: with one input, or three and more, and whenever an
input crosses itself (checked exactly first), or with --winding: the
winding-number arrangement. Every triangle of every input is intersected
with every other, the surfaces are cut and glued along the curves, and
each region between curves gets its inputs' winding numbers on both sides
from one exact ray (simulation of simplicity); the regions with inside on
one side and outside on the other are kept, facing out. One input alone
gives the solid its surface encloses: self-intersections and inner shells
removed. Every input must be closed. The output is checked for crossing
triangles. Where it has some (sheets that nearly coincide, whose
constructed points the rounding to f64 moved past one another), it is
snap-rounded (see below), and, if that does not clean it, every input
piece but the first is nudged as below; a result that still crosses is
written with a warning that says so.

Otherwise, for two solids that do not cross themselves, the union of
Theorem 5.2 below.

The motion (Theorem 5.2): B is first translated by s·d, where d is the
unit vector along --direction and s is the distance that puts B's shadow
on d wholly beyond A's plus 10% of the two shadows' combined length (so
B starts well clear of A's bounding box), and then moves in a straight
line back to its given position in one frame. A vertex of either solid
that ends inside the other hits the other's surface an odd number of
times, so the topology change deletes exactly the parts inside: the
union.

How it is computed: when A and B are both closed (every edge shared by
an even number of triangles), the parity that motion gives each vertex
is its containment in the other solid, so it is computed without
simulating the motion: the intersections of A with B only, then one
exact ray per region of vertices between the intersection curves (the
report counts the rays; it has no collisions). --via-motion runs the
synthesized frame through the whole pipeline of `holey topo` instead
(collisions, intersections, error correction), as it does by itself
for open input that --no-check let through. A solid found crossing
itself where it meets the other (slivers a hair wide that the check
passed) goes to the winding-number arrangement above; with --no-check,
its self-intersections away from the other are kept as they are. Zero-area
triangles (three corners on a line, or two at one position, as snapping
to a grid leaves them) are taken out of both solids first, without
moving the surface; the report counts them (zero_area_removed).

Degenerate contact (faces of A and B coplanar, vertices or edges
coinciding: a copy of a mesh shifted by a lattice step) is resolved by
symbolic perturbation. Where coplanar faces of A and B overlap, the
perturbed result, placed at the exact coordinates, can have duplicate
triangles or cracks, or be the wrong solid where its points were
rounded together or the solids only touch. There the winding-number
arrangement answers first, exactly: coplanar faces facing opposite ways
cancel, and where the result touches itself along an edge or at a point
it is split there into a 2-manifold without moving a point (the report
names the method: winding). Where that result's rounded points cross
(sheets that nearly coincide), it is snap-rounded: its points put on a
power-of-two grid of 256 ulps of its largest coordinate (then 2^14 and
2^20 ulps), resolved by its own winding number and checked exactly; the
report's snap_rounding gives the grid and the points moved. Only if
that is not clean either is the run retried with B moved by a deterministic, scale-relative nudge: 2^-30 of
the scene's diagonal along a fixed generic direction (about 1e-9
relative, far below any modelling precision), then 16 and 256 times
that along other directions, while each nudge leaves fewer open edges,
non-manifold edges and vertices, and crossing pairs. The report counts
the retries. --exact makes the containment's first attempt the only
one.

The default direction is generic (not along an axis) so that the paths
of B's vertices avoid A's vertices and edges even when A and B are
copies of one lattice-built mesh.

Examples:
  holey union a.obj b.obj union.obj
  holey union scan.stl repaired.stl        (one input: its enclosed solid)
  holey union a.obj b.obj c.obj all.obj --report r.json
  holey union @sphere:4 b.ply u.ply --via-motion --direction 0,0,1 --report r.json")]
pub struct Args {
    /// The first solid; it stays in place.
    pub a: String,
    /// The other solids (none, one, or more), then the output file, whose
    /// extension names the format.
    #[arg(required = true, num_args = 1.., value_name = "B... OUT")]
    pub rest: Vec<String>,
    #[command(flatten)]
    pub options: Options,
}

/// The options besides the files, which `holey batch union` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Use the winding-number arrangement even for two solids that do
    /// not cross themselves (see below).
    #[arg(long, conflicts_with = "via_motion")]
    pub winding: bool,
    /// Skip the exact check that the two solids are closed 2-manifolds
    /// that do not cross themselves (about the time of `holey selfint` on
    /// both): for inputs known to be such solids. If one does cross
    /// itself, the result keeps its crossings, and the report's
    /// `output_intersecting_pairs` may leave them out (where the cut
    /// merged points, it counts only pairs with a triangle of the cut).
    #[arg(long, conflicts_with = "winding")]
    pub no_check: bool,
    /// Direction B arrives from, as x,y,z.
    #[arg(long, value_name = "X,Y,Z")]
    pub direction: Option<String>,
    /// Do not perturb B's final position (see below).
    #[arg(long)]
    pub exact: bool,
    /// Run the synthesized motion through the whole pipeline even when
    /// both solids are closed (see below).
    #[arg(long)]
    pub via_motion: bool,
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

/// The inputs named on the command line, read once each (two at once).
fn load_inputs(names: &[&str]) -> Result<Vec<TriMesh>> {
    match names {
        [a, b] => {
            let (a, b) = load_triangle_pair(a, b)?;
            Ok(vec![a, b])
        }
        _ => names.iter().map(|n| load_triangles(n)).collect(),
    }
}

pub fn run(args: Args) -> Result<()> {
    let Some((output, others)) = args.rest.split_last() else {
        return Err(bad_input("union needs an output file"));
    };
    let names: Vec<&str> = std::iter::once(args.a.as_str())
        .chain(others.iter().map(String::as_str))
        .collect();
    unite(&names, output, &args.options)
}

/// The union of the meshes `names` names, written to the file `output`.
pub fn unite(names: &[&str], output: &str, args: &Options) -> Result<()> {
    args.engine.check_outputs()?;
    if args.via_motion && names.len() != 2 {
        return Err(bad_input("--via-motion unites exactly two solids"));
    }
    let direction = args.direction.as_deref().map(parse_direction).transpose()?;
    let inputs = load_inputs(names)?;
    let options = BooleanOptions {
        engine: args.engine.options(),
        exact: args.exact,
        check: !args.no_check,
        method: if args.via_motion {
            Some(Method::Motion)
        } else if args.winding {
            Some(Method::Winding)
        } else {
            None
        },
        direction,
    };
    let _p = Progress::start("uniting");
    let out = solid_boolean(&inputs, names, Operation::Union, &options)?;
    write_boolean(out, &inputs, names, output, &args.engine)
}
