//! `holey subdivide`: Catmull–Clark and Doo–Sabin smoothing.

use anyhow::Result;
use clap::ValueEnum;
use holey_io::WriteOptions;
use holey_subdiv::{Scheme, subdivide};

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

/// The subdivision scheme.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SchemeArg {
    CatmullClark,
    DooSabin,
}

#[derive(clap::Args)]
#[command(after_help = "\
Works on any mesh the kernel holds, including the self-loops, two-gons
and point-spheres that Sierpinski and Menger produce. Open meshes keep
B-spline boundary curves (Catmull–Clark: cubic, with corners kept sharp;
Doo–Sabin: quadratic, by corner cutting). A cube gives V/E/F 26/48/24
under Catmull–Clark and 24/48/26 under Doo–Sabin.

Examples:
  holey subdivide @cube smooth.obj --scheme catmull-clark -n 3
  holey sierpinski @tetrahedron s.dlfl -n 3 && holey subdivide s.dlfl fig43.obj --scheme doo-sabin -n 2")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: Options,
}

/// The options besides the two files, which `holey batch subdivide` shares.
#[derive(clap::Args)]
pub struct Options {
    /// The scheme.
    #[arg(long, value_enum)]
    pub scheme: SchemeArg,
    /// Number of levels.
    #[arg(short = 'n', long = "levels", default_value_t = 1)]
    pub levels: usize,
    /// Cut non-manifold edges and split non-manifold vertices of the input.
    #[arg(long)]
    pub split_nonmanifold: bool,
}

pub fn run(args: Args) -> Result<()> {
    run_file(&args.input, &args.output, &args.options)
}

/// Subdivides the mesh `input` names into the file `output`.
pub fn run_file(input: &str, output: &str, options: &Options) -> Result<()> {
    let scheme = match options.scheme {
        SchemeArg::CatmullClark => Scheme::CatmullClark,
        SchemeArg::DooSabin => Scheme::DooSabin,
    };
    let kernel = load(input)?.into_kernel(options.split_nonmanifold)?;
    let _p = Progress::start(format!("subdividing, {} level(s)", options.levels));
    let out = subdivide(&kernel.mesh, scheme, options.levels)
        .map_err(|e| bad_input(format!("{input}: {e}")))?;
    write_kernel(output, &out, &WriteOptions::default())
}
