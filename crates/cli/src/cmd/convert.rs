//! `holey convert`: change a mesh's file format.

use anyhow::Result;
use holey_io::WriteOptions;

use crate::cmd::{FileArgs, MeshToFile};
use crate::input::{Input, WeldDistance, load, weld};
use crate::output::{write_kernel, write_soup};

const AFTER_HELP: &str = "\
The output format is the output file's extension: .obj, .off, .ply, .stl,
.gltf, .glb (glTF 2.0), .3mf or .dlfl. Converting between soup formats
keeps the mesh as it is (non-manifold, open or unwelded meshes included).
STL, glTF and 3MF hold triangles, so polygons are split into triangles;
STL (binary) and glTF store f32 coordinates, 3MF exact decimals. A .gltf
is written self-contained (its buffer embedded). Reading glTF or 3MF
gives the meshes of the default scene or of the build as one mesh, each
placed by its transforms. Writing .dlfl imports the mesh into the DLFL
kernel, which needs an orientable 2-manifold; boundary loops become hole
faces. Writing a .dlfl mesh to another format drops self-loops from face
lists and omits two-gons and point-spheres.

Examples:
  holey convert bunny.obj bunny.ply
  holey convert bunny.obj bunny.glb
  holey convert bracket.3mf bracket.obj --weld 0
  holey convert part.stl part.dlfl --split-nonmanifold
  holey convert sierpinski.dlfl sierpinski.obj
  holey convert teapot.obj teapot.ply --weld 0.01%";

pub type Args = FileArgs<Options>;

/// The options besides the two files, which `holey batch convert` shares.
#[derive(clap::Args)]
pub struct Options {
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

impl MeshToFile for Options {
    /// Converts the mesh `input` names into the file `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let opts = WriteOptions {
            ascii: self.ascii,
            ..WriteOptions::default()
        };
        let mut loaded = load(input)?;
        if let (Some(d), Input::Soup(soup)) = (self.weld, &loaded.input) {
            loaded.input = Input::Soup(weld(input, soup, d)?);
        }
        match loaded.input {
            Input::Soup(ref soup) => write_soup(output, soup, &opts, self.split_nonmanifold),
            Input::Dlfl(_) => {
                let kernel = loaded.into_kernel(false)?;
                write_kernel(output, &kernel.mesh, &opts)
            }
        }
    }

    const INPUT: &str = "Input mesh: a file or a primitive such as @torus";
    const AFTER_HELP: &str = AFTER_HELP;
}
