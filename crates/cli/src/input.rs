//! Reading the mesh an argument names: a file, or a built-in primitive
//! written `@name[:params]`.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::convert::{ImportOptions, infer_edges, to_dlfl};
use holey_dlfl::{Mesh, RawMesh};
use holey_io::MeshFile;
use holey_mesh::PolyMesh;
use holey_model::numbering::Numbering;

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

/// A mesh in the kernel, with the input's numbers for its faces and
/// vertices (file order; for a `.dlfl` file, `f` and `h` lines together).
pub struct Kernel {
    pub mesh: Mesh,
    pub numbering: Numbering,
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
                let imported = to_dlfl(&soup, ImportOptions { split_nonmanifold })
                    .map_err(|e| bad_input(format!("{name}: {e}")))?;
                let (mesh, numbering) = Numbering::from_import(imported);
                Ok(Kernel { mesh, numbering })
            }
            Input::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                let numbering = Numbering::of_raw(&mesh, &raw);
                Ok(Kernel { mesh, numbering })
            }
        }
    }
}

/// A weld distance as written on the command line: a length, or a share
/// of the bounding-box diagonal written with `%`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WeldDistance {
    Absolute(f64),
    OfDiagonal(f64),
}

impl std::str::FromStr for WeldDistance {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        let bad = || {
            format!(
                "{s:?} is not a weld distance (a length such as 0.001, or a share of the diagonal such as 0.1%)"
            )
        };
        let (number, relative) = match s.strip_suffix('%') {
            Some(n) => (n, true),
            None => (s, false),
        };
        let x: f64 = number.trim().parse().map_err(|_| bad())?;
        if !(x.is_finite() && x >= 0.0) {
            return Err(bad());
        }
        Ok(if relative {
            WeldDistance::OfDiagonal(x / 100.0)
        } else {
            WeldDistance::Absolute(x)
        })
    }
}

/// `soup` with its vertices within `distance` welded
/// ([`holey_mesh::analysis::weld_by_distance`]), telling on stderr what
/// was merged.
pub fn weld(name: &str, soup: &PolyMesh, distance: WeldDistance) -> Result<PolyMesh> {
    let length = match distance {
        WeldDistance::Absolute(d) => d,
        WeldDistance::OfDiagonal(share) => {
            let (mut lo, mut hi) = (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY);
            for f in soup.faces() {
                for &i in f {
                    if let Some(p) = soup.positions.get(i as usize) {
                        lo = lo.min(*p);
                        hi = hi.max(*p);
                    }
                }
            }
            if lo.x <= hi.x {
                share * lo.distance(hi)
            } else {
                0.0
            }
        }
    };
    let w = holey_mesh::analysis::weld_by_distance(soup, length)
        .map_err(|e| bad_input(format!("{name}: weld: {e}")))?;
    eprintln!(
        "{name}: welded at {length}: {} vertices merged, {} collapsed faces dropped",
        w.merged_vertices, w.dropped_faces
    );
    Ok(w.mesh)
}
