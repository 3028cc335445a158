//! `holey wireframe`: TopMod's wireframe and column modeling (issue 18).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::wireframe::{ColumnParams, columns, wireframe};

use crate::cmd::{FileArgs, MeshToFile};
use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

const AFTER_HELP: &str = "\
Turns every edge into a tube and every vertex into a joint: the surface
of the thickened edge graph, a closed 2-manifold of genus E - V + C (C
the components of the graph); a closed genus-g surface gives F - 1 + 2g,
every face a window. Faces of the input's boundary loops become windows
too.

Without --columns: TopMod's wireframe, each face shrunk by --thickness
into a window with jambs down to an inner layer; four-sided tubes,
V' = 4E, E' = 10E - 2(V1 + V2), F' = 4E + 2V3, Vk the vertices of
valence k (V3 those of valence 3 or more; no joint where two edges or
one meet); a cube: 48/120/64, genus 5.

With --columns N: an N-sided column of radius --thickness along every
edge, joined at each vertex of valence k >= 3 by k side faces and two
k-gon caps; V' = 2NE.

Refused (nothing written): a thickness that is not positive and finite,
a face of zero area, a thickness so large that a shrunk face turns over,
columns of fewer than 3 sides, edges too short for their joints.

Examples:
  holey wireframe @dodecahedron frame.obj --thickness 0.1
  holey wireframe @dodecahedron f.dlfl --thickness 0.08 && holey subdivide f.dlfl smooth.obj --scheme catmull-clark -n 2
  holey wireframe @cube columns.obj --thickness 0.1 --columns 6";

pub type Args = FileArgs<Options>;

/// The options besides the two files, which `holey batch wireframe` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Width of the tubes in model units (the columns' radius with --columns).
    #[arg(long, allow_hyphen_values = true)]
    pub thickness: f64,
    /// Build N-sided columns instead of the wireframe (N at least 3).
    #[arg(long, value_name = "N")]
    pub columns: Option<usize>,
    /// Cut non-manifold edges and split non-manifold vertices of the input.
    #[arg(long)]
    pub split_nonmanifold: bool,
}

impl MeshToFile for Options {
    /// The wireframe (or columns) of the mesh `input` names, into `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let kernel = load(input)?.into_kernel(self.split_nonmanifold)?;
        let _p = Progress::start("building the wireframe");
        let out = match self.columns {
            None => wireframe(&kernel.mesh, self.thickness),
            Some(sides) => columns(
                &kernel.mesh,
                &ColumnParams {
                    sides,
                    radius: self.thickness,
                },
            ),
        }
        .map_err(|e| {
            let why = kernel.numbering.describe_wireframe(&kernel.mesh, &e);
            bad_input(format!("{input}: {why}"))
        })?;
        write_kernel(output, &out, &WriteOptions::default())
    }

    const INPUT: &str = "Input mesh (a file or a primitive)";
    const AFTER_HELP: &str = AFTER_HELP;
}
