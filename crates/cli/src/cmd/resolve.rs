//! `holey resolve`: the arrangement of a self-intersecting surface.

use anyhow::Result;
use holey_topo::resolve;

use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::load_triangles;

#[derive(clap::Args)]
#[command(after_help = "\
Cuts the surface along all its self-intersection curves and glues the
pieces there, deleting nothing: every intersection curve becomes a curve
of shared edges, so the output has no triangle crossing another. Where
four sheets meet along a curve the output has edges of degree four.
Triangles that lie in one plane and overlap there are merged: stacked
copies become one, facing the way most of them face, and where as many
face one way as the other (two shells meeting face to face, a fold) they
cancel, which leaves the surface's winding number as it was
(`holey selfint --overlaps` counts what is left).

Examples:
  holey resolve self_intersecting.obj arrangement.obj -v")]
pub struct Args {
    /// The mesh.
    pub mesh: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Print what was done.
    #[arg(short, long)]
    pub verbose: bool,
}

pub fn run(args: Args) -> Result<()> {
    let done = run_file(&args.mesh, &args.output)?;
    if args.verbose {
        eprintln!("{done}");
    }
    Ok(())
}

/// Resolves the mesh `input` names into the file `output`, and says what
/// was done in one line (what `-v` prints; `holey batch resolve` does not
/// print it, as it would not say which file it is about).
pub fn run_file(input: &str, output: &str) -> Result<String> {
    let mesh = load_triangles(input)?;
    let (out, x, report) = {
        let _p = Progress::start("resolving self-intersections");
        resolve(&mesh).map_err(|e| bad_input(format!("{input}: {e}")))?
    };
    crate::tri::write_triangles(output, &out)?;
    Ok(format!(
        "{} intersecting pairs, {} curves; {} triangles split into {} triangles total; \
         {} points within rounding of another welded; \
         {} groups of overlapping coplanar triangles merged, {} left",
        x.pairs.len(),
        x.curve_count,
        report.triangles_split,
        out.triangles.len(),
        report.points_welded,
        report.coplanar_groups_merged,
        report.coplanar_groups_left,
    ))
}
