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
    let mesh = load_triangles(&args.mesh)?;
    let (out, x, report) = {
        let _p = Progress::start("resolving self-intersections");
        resolve(&mesh).map_err(|e| bad_input(format!("{}: {e}", args.mesh)))?
    };
    crate::tri::write_triangles(&args.output, &out)?;
    if args.verbose {
        eprintln!(
            "{} intersecting pairs, {} curves; {} triangles split into {} triangles total",
            x.pairs.len(),
            x.curve_count,
            report.triangles_split,
            out.triangles.len()
        );
    }
    Ok(())
}
