//! Reading the mesh an argument names: a file, or a built-in primitive
//! written `@name[:params]`.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::convert::{ImportOptions, Imported, infer_edges, to_dlfl};
use holey_dlfl::{CornerId, FaceId, Mesh, RawMesh};
use holey_io::MeshFile;
use holey_mesh::PolyMesh;

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

/// A mesh in the kernel, with its faces in file order.
pub struct Kernel {
    pub mesh: Mesh,
    /// Face `i` of the input as `holey info` numbers it (file order; for a
    /// `.dlfl` file, `f` and `h` lines together).
    pub faces: Vec<Option<FaceId>>,
}

impl Kernel {
    /// The face numbered `index` in file order.
    pub fn face(&self, index: usize) -> Result<FaceId> {
        self.faces.get(index).copied().flatten().ok_or_else(|| {
            bad_input(format!(
                "face {index} does not exist: the input has {} faces",
                self.faces.len()
            ))
        })
    }

    /// Corner `corner` of face `face` (file order; corner j is the face's j-th vertex).
    pub fn corner(&self, face: usize, corner: usize) -> Result<CornerId> {
        let f = self.face(face)?;
        let len = self
            .mesh
            .face_len(f)
            .map_err(|e| bad_input(e.to_string()))?;
        self.mesh
            .face_corners(f)
            .map_err(|e| bad_input(e.to_string()))?
            .nth(corner)
            .ok_or_else(|| {
                bad_input(format!(
                    "face {face} has {len} corners; there is no corner {corner}"
                ))
            })
    }
}

/// Parses a face:corner address such as `12:0`.
pub fn parse_face_corner(s: &str) -> Result<(usize, usize)> {
    let parse = |t: &str| t.trim().parse::<usize>().ok();
    match s.split_once(':') {
        Some((f, c)) => match (parse(f), parse(c)) {
            (Some(f), Some(c)) => Ok((f, c)),
            _ => Err(bad_input(format!(
                "{s:?} is not FACE:CORNER (two non-negative integers)"
            ))),
        },
        None => parse(s).map(|f| (f, 0)).ok_or_else(|| {
            bad_input(format!(
                "{s:?} is not FACE:CORNER (two non-negative integers)"
            ))
        }),
    }
}

/// Parses a comma-separated list of face numbers such as `3,7,12`.
pub fn parse_face_list(s: &str) -> Result<Vec<usize>> {
    s.split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| bad_input(format!("{t:?} in {s:?} is not a face number")))
        })
        .collect()
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
                let Imported { mesh, faces, .. } =
                    to_dlfl(&soup, ImportOptions { split_nonmanifold })
                        .map_err(|e| bad_input(format!("{name}: {e}")))?;
                Ok(Kernel { mesh, faces })
            }
            Input::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                let faces = (0..raw.face_count()).map(|f| mesh.face_at(f)).collect();
                Ok(Kernel { mesh, faces })
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
