//! `holey convert`: change a mesh's file format.

use anyhow::Result;
use holey_io::WriteOptions;

use crate::input::{Input, load};
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
  holey convert sierpinski.dlfl sierpinski.obj")]
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
}

pub fn run(args: Args) -> Result<()> {
    let opts = WriteOptions {
        ascii: args.ascii,
        ..WriteOptions::default()
    };
    let loaded = load(&args.input)?;
    match loaded.input {
        Input::Soup(ref soup) => write_soup(&args.output, soup, &opts, args.split_nonmanifold),
        Input::Dlfl(_) => {
            let kernel = loaded.into_kernel(false)?;
            write_kernel(&args.output, &kernel.mesh, &opts)
        }
    }
}
