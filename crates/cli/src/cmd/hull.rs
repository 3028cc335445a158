//! `holey hull`: the convex hull and TopMod's dual convex hull (issue 18).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::hull::{convex_hull, dual_convex_hull};

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

#[derive(clap::Args)]
#[command(after_help = "\
Replaces the mesh by the convex hull of its vertices: a convex polyhedron
of genus 0 whose faces are the hull's planar facets and whose vertices
are its corners (points inside, on a face or on a straight edge are
dropped), V - E + F = 2; with every face a triangle (points in general
position) F = 2V - 4. Every decision is exact, with no tolerance: a
point 1e-17 outside a face is a corner, and a face that is planar only
to rounding (a dodecahedron's pentagons) comes back as several.

With --dual: TopMod's dual convex hull, the solid bounded by the plane
through each hull corner perpendicular to its normal: one face per
corner of the hull (F* = V); with three planes at each of its vertices
V* = 2F* - 4, E* = 3F* - 6. A cube gives an octahedron, 6/12/8.

Refused (nothing written): points all on one plane, a line or a point;
a dual whose corners lie beyond the range of floating point.

Examples:
  holey hull @torus hull.obj
  holey hull @cube octahedron.obj --dual")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// The dual convex hull instead of the convex hull.
    #[arg(long)]
    pub dual: bool,
    /// Cut non-manifold edges and split non-manifold vertices of the input.
    #[arg(long)]
    pub split_nonmanifold: bool,
}

pub fn run(args: Args) -> Result<()> {
    let kernel = load(&args.input)?.into_kernel(args.split_nonmanifold)?;
    let _p = Progress::start(if args.dual {
        "building the dual convex hull"
    } else {
        "building the convex hull"
    });
    let out = if args.dual {
        dual_convex_hull(&kernel.mesh)
    } else {
        convex_hull(&kernel.mesh)
    }
    .map_err(|e| bad_input(format!("{}: {e}", args.input)))?;
    write_kernel(&args.output, &out, &WriteOptions::default())
}
