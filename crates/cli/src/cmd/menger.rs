//! `holey menger`: generalized Menger sponges (thesis chapter VII).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::menger::{MengerParams, Thickness, menger};

use crate::cmd::{FileArgs, MeshToFile};
use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

const AFTER_HELP: &str = "\
Each level remeshes every face around a smaller copy, offsets the copies
inwards by the thickness D, connects them along the original edges and
pipes each copy to its offset, drilling a tunnel through every face. D is
given directly (--thickness) or as a ratio of the mean edge length,
recomputed at each level (--thickness-ratio; 1/3 reproduces the thesis's
figure 62). Between 90° and 180° the interior angle at an edge decides
whether the connecting edges collapse (--collapse-angle).

--exact builds the true Menger sponge instead (the thesis's future-work
item 4), for a cube or any parallelepiped: genus 5, 81, 1409 at levels
1, 2, 3.

Examples:
  holey menger @cube sponge.obj -n 2
  holey menger @cube sponge.dlfl -n 2 --thickness 0.2
  holey menger @cube true3.obj -n 3 --exact
  holey menger @dodecahedron dodeca.obj --thickness-ratio 0.25";

pub type Args = FileArgs<Options>;

/// The options besides the two files, which `holey batch menger` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Number of levels.
    #[arg(short = 'n', long = "iterations", default_value_t = 1)]
    pub iterations: usize,
    /// Wall thickness D in model units, at every level.
    #[arg(long, conflicts_with = "thickness_ratio")]
    pub thickness: Option<f64>,
    /// Wall thickness as a ratio R of the mean edge length (D = R × mean edge), default 1/3.
    #[arg(long)]
    pub thickness_ratio: Option<f64>,
    /// Collapse the connecting edges where the interior angle is below this (90–180 degrees).
    #[arg(long, default_value_t = 90.0)]
    pub collapse_angle: f64,
    /// Build the true Menger sponge (input: a cube or parallelepiped).
    #[arg(long)]
    pub exact: bool,
}

impl MeshToFile for Options {
    /// The Menger sponge of the mesh `input` names, into the file `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let thickness = match (self.thickness, self.thickness_ratio) {
            (Some(d), _) => Thickness::Absolute(d),
            (None, Some(r)) => Thickness::RatioOfMeanEdge(r),
            (None, None) => Thickness::RatioOfMeanEdge(1.0 / 3.0),
        };
        let params = MengerParams {
            iterations: self.iterations,
            thickness,
            collapse_angle_deg: self.collapse_angle,
            exact: self.exact,
        };
        let mut kernel = load(input)?.into_kernel(false)?;
        let _p = Progress::start(format!("Menger sponge, {} level(s)", self.iterations));
        menger(&mut kernel.mesh, &params).map_err(|e| bad_input(format!("{input}: {e}")))?;
        write_kernel(output, &kernel.mesh, &WriteOptions::default())
    }

    const INPUT: &str = "Input mesh: a closed 2-manifold (a file or a primitive such as @cube)";
    const AFTER_HELP: &str = AFTER_HELP;
}
