//! Reading the mesh an argument names: a file, or a built-in primitive
//! written `@name[:params]`.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::{Mesh, RawMesh};
use holey_io::MeshFile;
use holey_mesh::PolyMesh;
use holey_mesh::convert::{ImportOptions, Imported, infer_edges, to_dlfl};

use crate::error::{bad_input, from_io};
use crate::progress::Progress;

/// A mesh as read: a soup, or a DLFL from a `.dlfl` file.
pub enum Input {
    Soup(PolyMesh),
    Dlfl(RawMesh),
}

/// A mesh argument and what it holds.
pub struct Loaded {
    /// The argument as given, for messages.
    pub name: String,
    pub input: Input,
}

/// A mesh in the kernel.
pub struct Kernel {
    pub mesh: Mesh,
}

/// Reads a mesh argument.
pub fn load(arg: &str) -> Result<Loaded> {
    if arg.starts_with('@') {
        let soup =
            holey_shapes::parse_primitive(arg).map_err(|e| bad_input(format!("{arg}: {e}")))?;
        return Ok(Loaded {
            name: arg.to_owned(),
            input: Input::Soup(soup),
        });
    }
    let _p = Progress::start(format!("reading {arg}"));
    let file = holey_io::read_path(Path::new(arg)).map_err(from_io)?;
    Ok(Loaded {
        name: arg.to_owned(),
        input: match file {
            MeshFile::Poly(p) => Input::Soup(p),
            MeshFile::Dlfl(r) => Input::Dlfl(r),
        },
    })
}

impl Loaded {
    /// Imports the mesh into the kernel. A soup must be an orientable
    /// 2-manifold (boundary allowed) unless `split_nonmanifold` is set.
    pub fn into_kernel(self, split_nonmanifold: bool) -> Result<Kernel> {
        let name = self.name;
        match self.input {
            Input::Soup(soup) => {
                let Imported { mesh, .. } = to_dlfl(&soup, ImportOptions { split_nonmanifold })
                    .map_err(|e| bad_input(format!("{name}: {e}")))?;
                Ok(Kernel { mesh })
            }
            Input::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                Ok(Kernel { mesh })
            }
        }
    }
}
