//! `holey wireframe`: TopMod's wireframe and column modeling (issue 18).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::wireframe::{ColumnParams, WireframeError, columns, wireframe};

use crate::error::bad_input;
use crate::input::{Kernel, load};
use crate::output::write_kernel;
use crate::progress::Progress;

#[derive(clap::Args)]
#[command(after_help = "\
Turns every edge into a tube and every vertex into a joint: the surface
of the thickened edge graph, a closed 2-manifold of genus E - V + C (C
the components of the graph); a closed genus-g surface gives F - 1 + 2g,
every face a window. Faces of the input's boundary loops become windows
too.

Without --columns: TopMod's wireframe, each face shrunk by --thickness
into a window with jambs down to an inner layer; four-sided tubes,
V' = 4E, E' = 10E, F' = 4E + 2V (a cube: 48/120/64, genus 5).

With --columns N: an N-sided column of radius --thickness along every
edge, joined at each vertex of valence k >= 3 by k side faces and two
k-gon caps; V' = 2NE.

Refused (nothing written): a thickness that is not positive and finite,
a face of zero area, a thickness so large that a shrunk face turns over,
columns of fewer than 3 sides, edges too short for their joints.

Examples:
  holey wireframe @dodecahedron frame.obj --thickness 0.1
  holey wireframe @dodecahedron f.dlfl --thickness 0.08 && holey subdivide f.dlfl smooth.obj --scheme catmull-clark -n 2
  holey wireframe @cube columns.obj --thickness 0.1 --columns 6")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: Options,
}

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

pub fn run(args: Args) -> Result<()> {
    run_file(&args.input, &args.output, &args.options)
}

/// The wireframe (or columns) of the mesh `input` names, into `output`.
pub fn run_file(input: &str, output: &str, options: &Options) -> Result<()> {
    let kernel = load(input)?.into_kernel(options.split_nonmanifold)?;
    let _p = Progress::start("building the wireframe");
    let out = match options.columns {
        None => wireframe(&kernel.mesh, options.thickness),
        Some(sides) => columns(
            &kernel.mesh,
            &ColumnParams {
                sides,
                radius: options.thickness,
            },
        ),
    }
    .map_err(|e| bad_input(format!("{input}: {}", describe(&kernel, &e))))?;
    write_kernel(output, &out, &WriteOptions::default())
}

/// A refusal in the input's numbering where the library names kernel ids.
fn describe(kernel: &Kernel, e: &WireframeError) -> String {
    match e {
        WireframeError::DegenerateFace(f) => format!(
            "{} has zero area, so its corners cannot be moved into it",
            kernel.face_name(*f)
        ),
        WireframeError::DegenerateCorner { face, corner } => {
            let index = kernel
                .mesh
                .face_corners(*face)
                .ok()
                .and_then(|mut cs| cs.position(|c| c == *corner));
            match index {
                Some(i) => format!(
                    "corner {i} of {} has no inward direction (its edges coincide or fold back)",
                    kernel.face_name(*face)
                ),
                None => e.to_string(),
            }
        }
        WireframeError::ThicknessTooLarge { face, thickness } => format!(
            "at thickness {thickness} the shrunk copy of {} turns over; use a smaller thickness",
            kernel.face_name(*face)
        ),
        WireframeError::EdgeTooShort { edge, radius } => format!(
            "at radius {radius} the joints at the ends of {} overlap (the edge is too short)",
            kernel.edge_name(*edge)
        ),
        WireframeError::CoincidentEdges(v) => format!(
            "two edges at {} point the same way; their columns would coincide",
            kernel.vertex_name(*v)
        ),
        WireframeError::NoNormal(v) => format!(
            "{} has no normal: the normals of its faces cancel out",
            kernel.vertex_name(*v)
        ),
        other => other.to_string(),
    }
}
