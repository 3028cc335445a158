//! `holey convert`: change a mesh's file format.

use anyhow::Result;
use holey_io::WriteOptions;

use crate::input::{Input, WeldDistance, load, weld};
use crate::output::{write_kernel, write_soup};

#[derive(clap::Args)]
#[command(after_help = "\
The output format is the output file's extension: .obj, .off, .ply, .stl
or .dlfl. Converting between soup formats keeps the mesh as it is
(non-manifold, open or unwelded meshes included). Writing .dlfl imports
the mesh into the DLFL kernel, which needs an orientable 2-manifold;
boundary loops become hole faces. Writing a .dlfl mesh to another format
drops self-loops from face lists and omits two-gons and point-spheres.

Examples:
  holey convert bunny.obj bunny.ply
  holey convert part.stl part.dlfl --split-nonmanifold
  holey convert sierpinski.dlfl sierpinski.obj
  holey convert teapot.obj teapot.ply --weld 0.01%")]
pub struct Args {
    /// Input mesh: a file or a primitive such as @torus.
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Write PLY or STL as text instead of binary.
    #[arg(long)]
    pub ascii: bool,
    /// When importing into the kernel (.dlfl output), cut non-manifold
    /// edges and split non-manifold vertices instead of failing.
    #[arg(long)]
    pub split_nonmanifold: bool,
    /// Merge vertices closer than this first (a length, or a share of the
    /// bounding-box diagonal such as 0.01%; 0 merges identical positions):
    /// the seams of scans and of patches that do not meet exactly.
    #[arg(long, value_name = "DIST")]
    pub weld: Option<WeldDistance>,
}

pub fn run(args: Args) -> Result<()> {
    let opts = WriteOptions {
        ascii: args.ascii,
        ..WriteOptions::default()
    };
    let mut loaded = load(&args.input)?;
    if let (Some(d), Input::Soup(soup)) = (args.weld, &loaded.input) {
        loaded.input = Input::Soup(weld(&args.input, soup, d)?);
    }
    match loaded.input {
        Input::Soup(ref soup) => write_soup(&args.output, soup, &opts, args.split_nonmanifold),
        Input::Dlfl(_) => {
            let kernel = loaded.into_kernel(false)?;
            write_kernel(&args.output, &kernel.mesh, &opts)
        }
    }
}
