//! `holey rind`: rind modeling (thesis chapter V, the improved algorithm).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::numbering::parse_index_list;
use holey_model::rind::{PunchOutcome, Rind};

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;

#[derive(clap::Args)]
#[command(after_help = "\
Makes a crust of the given thickness: an inner copy of the mesh, reversed
and offset inwards along averaged vertex normals. --punch F,... joins
outer face F (numbered in file order, as `holey info` counts) to its
inner copy with a pipe; --peel F,... punches and also removes the thin
walls left between neighbouring holes and the two-gons they leave. k
holes in a genus-g crust give genus 2g+k-1. A face that was already
consumed by an earlier punch is skipped with a note.

Examples:
  holey rind @sphere:2 crust.obj --thickness 0.1 --punch 0,5,9
  holey rind @cube cup.dlfl --thickness 0.2 --peel 5")]
pub struct Args {
    /// Input mesh: a 2-manifold, outward oriented (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Crust thickness, in model units (inwards).
    #[arg(long)]
    pub thickness: f64,
    /// Outer faces to punch, comma-separated.
    #[arg(long, default_value = "")]
    pub punch: String,
    /// Outer faces to peel, comma-separated.
    #[arg(long, default_value = "")]
    pub peel: String,
}

pub fn run(args: Args) -> Result<()> {
    let punch = parse_index_list(&args.punch, "face").map_err(bad_input)?;
    let peel = parse_index_list(&args.peel, "face").map_err(bad_input)?;
    let kernel = load(&args.input)?.into_kernel(false)?;
    let name = &args.input;
    let mut rind =
        Rind::new(kernel.mesh, args.thickness).map_err(|e| bad_input(format!("{name}: {e}")))?;
    for (list, peeling) in [(&punch, false), (&peel, true)] {
        let outcomes = if peeling {
            rind.peel_indices(list)
        } else {
            rind.punch_indices(list)
        }
        .map_err(|e| bad_input(format!("{name}: {e}")))?;
        for (face, outcome) in list.iter().zip(outcomes) {
            if let PunchOutcome::NotPunchable { reason } = outcome {
                eprintln!(
                    "note: face {face} was not {}: {reason}",
                    if peeling { "peeled" } else { "punched" }
                );
            }
        }
    }
    write_kernel(&args.output, rind.mesh(), &WriteOptions::default())
}
