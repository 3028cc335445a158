//! `holey subdivide`: Catmull–Clark and Doo–Sabin smoothing.

use anyhow::Result;
use clap::ValueEnum;
use holey_io::WriteOptions;
use holey_subdiv::{Scheme, subdivide};

use crate::cmd::{FileArgs, MeshToFile};
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

const AFTER_HELP: &str = "\
Works on any mesh the kernel holds, including the self-loops, two-gons
and point-spheres that Sierpinski and Menger produce. Open meshes keep
B-spline boundary curves (Catmull–Clark: cubic, with corners kept sharp;
Doo–Sabin: quadratic, by corner cutting). A cube gives V/E/F 26/48/24
under Catmull–Clark and 24/48/26 under Doo–Sabin.

Examples:
  holey subdivide @cube smooth.obj --scheme catmull-clark -n 3
  holey sierpinski @tetrahedron s.dlfl -n 3 && holey subdivide s.dlfl fig43.obj --scheme doo-sabin -n 2";

pub type Args = FileArgs<Options>;

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

impl MeshToFile for Options {
    /// Subdivides the mesh `input` names into the file `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let scheme = match self.scheme {
            SchemeArg::CatmullClark => Scheme::CatmullClark,
            SchemeArg::DooSabin => Scheme::DooSabin,
        };
        let kernel = load(input)?.into_kernel(self.split_nonmanifold)?;
        let _p = Progress::start(format!("subdividing, {} level(s)", self.levels));
        let out = subdivide(&kernel.mesh, scheme, self.levels)
            .map_err(|e| bad_input(format!("{input}: {e}")))?;
        write_kernel(output, &out, &WriteOptions::default())
    }

    const INPUT: &str = "Input mesh (a file or a primitive)";
    const AFTER_HELP: &str = AFTER_HELP;
}
