//! `holey sierpinski`: generalized Sierpinski polyhedra (thesis chapter VI).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::sierpinski::sierpinski;

use crate::cmd::{FileArgs, MeshToFile};
use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

const AFTER_HELP: &str = "\
Each iteration subdivides every edge that is not a self-loop, cuts every
corner off each face, and joins the cuts with self-loops, so the result
stays one connected 2-manifold. On a tetrahedron iterations 1, 2 and 3
give V/E/F 10/30/16 (genus 3), 34/126/64 (genus 15), 130/510/256 (genus 63).

Written as .dlfl the self-loops are kept exactly. Written as OBJ (or
another soup format) they are dropped from face lists, so the file shows
what the thesis renders: a hexagon with three zero-length loops is
written as the triangle it looks like.

Examples:
  holey sierpinski @tetrahedron tetra3.dlfl -n 3
  holey sierpinski @cube cube2.obj -n 2";

pub type Args = FileArgs<Options>;

/// The options besides the two files, which `holey batch sierpinski` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Number of iterations.
    #[arg(short = 'n', long = "iterations", default_value_t = 1)]
    pub iterations: usize,
    /// Cut non-manifold edges and split non-manifold vertices of the input.
    #[arg(long)]
    pub split_nonmanifold: bool,
}

impl MeshToFile for Options {
    /// The Sierpinski polyhedron of the mesh `input` names, into the file `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let mut kernel = load(input)?.into_kernel(self.split_nonmanifold)?;
        let _p = Progress::start(format!("Sierpinski, {} iteration(s)", self.iterations));
        let report = sierpinski(&mut kernel.mesh, self.iterations)
            .map_err(|e| bad_input(format!("{input}: {e}")))?;
        drop(report);
        write_kernel(output, &kernel.mesh, &WriteOptions::default())
    }

    const INPUT: &str =
        "Input mesh: a closed 2-manifold (a file or a primitive such as @tetrahedron)";
    const AFTER_HELP: &str = AFTER_HELP;
}
