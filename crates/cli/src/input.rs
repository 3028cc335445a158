//! Reading the mesh an argument names: a file, or a built-in primitive
//! written `@name[:params]`.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::convert::{ImportOptions, Imported, infer_edges, to_dlfl};
use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, RawMesh, VertexId};
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
    /// Vertex `i` of the input in file order (`None`: unused by any face).
    pub vertices: Vec<Option<VertexId>>,
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

impl Kernel {
    /// The vertex numbered `index` in file order.
    pub fn vertex(&self, index: usize) -> Result<VertexId> {
        match self.vertices.get(index) {
            Some(Some(v)) => Ok(*v),
            Some(None) => Err(bad_input(format!(
                "vertex {index} is not used by any face, so it is not in the mesh"
            ))),
            None => Err(bad_input(format!(
                "vertex {index} does not exist: the input has {} vertices",
                self.vertices.len()
            ))),
        }
    }

    /// A kernel vertex as the user numbers it: `vertex N` in file order.
    pub fn vertex_name(&self, v: VertexId) -> String {
        match self.vertices.iter().position(|&w| w == Some(v)) {
            Some(n) => format!("vertex {n}"),
            None => format!("vertex {v}"),
        }
    }

    /// A kernel edge as the user numbers it: `edge U-W` by its vertices.
    pub fn edge_name(&self, e: EdgeId) -> String {
        let number = |v: VertexId| self.vertices.iter().position(|&w| w == Some(v));
        match self.mesh.edge_vertices(e) {
            Ok([a, b]) => match (number(a), number(b)) {
                (Some(a), Some(b)) => format!("edge {a}-{b}"),
                _ => format!("edge {e}"),
            },
            Err(_) => format!("edge {e}"),
        }
    }

    /// A kernel face as the user numbers it: `face N` in file order (a
    /// hole face, which no file lists, by its kernel id).
    pub fn face_name(&self, f: FaceId) -> String {
        match self.faces.iter().position(|&g| g == Some(f)) {
            Some(n) => format!("face {n}"),
            None if self.mesh.is_hole(f).unwrap_or(false) => format!("hole face {f}"),
            None => format!("face {f}"),
        }
    }

    /// The edge an [`EdgeSpec`] names.
    pub fn edge(&self, spec: EdgeSpec) -> Result<EdgeId> {
        let kernel = |e: holey_dlfl::Error| bad_input(e.to_string());
        match spec {
            EdgeSpec::Corner(face, corner) => {
                let c = self.corner(face, corner)?;
                self.mesh.corner_edge(c).map_err(kernel)?.ok_or_else(|| {
                    bad_input(format!(
                        "corner {face}:{corner} starts no edge (it is a point-sphere)"
                    ))
                })
            }
            EdgeSpec::Vertices(a, b) => {
                let (u, w) = (self.vertex(a)?, self.vertex(b)?);
                for c in self.mesh.vertex_corners(u).map_err(kernel)? {
                    if let Some(e) = self.mesh.corner_edge(c).map_err(kernel)? {
                        let [x, y] = self.mesh.edge_vertices(e).map_err(kernel)?;
                        if (x == u && y == w) || (x == w && y == u) {
                            return Ok(e);
                        }
                    }
                }
                Err(bad_input(format!(
                    "vertices {a} and {b} are not joined by an edge"
                )))
            }
        }
    }
}

/// An edge as written on the command line: `U-W`, the edge between
/// vertices `U` and `W` (file order), or `F:C`, the edge leaving corner
/// `C` of face `F` towards the next corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeSpec {
    Vertices(usize, usize),
    Corner(usize, usize),
}

impl std::fmt::Display for EdgeSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EdgeSpec::Vertices(a, b) => write!(f, "{a}-{b}"),
            EdgeSpec::Corner(face, c) => write!(f, "{face}:{c}"),
        }
    }
}

/// Parses a comma-separated list of edges, each `U-W` or `F:C`.
pub fn parse_edge_list(s: &str) -> Result<Vec<EdgeSpec>> {
    let number = |t: &str| t.trim().parse::<usize>().ok();
    s.split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| {
            let pair = t
                .split_once('-')
                .map(|(a, b)| (a, b, true))
                .or_else(|| t.split_once(':').map(|(a, b)| (a, b, false)));
            match pair.and_then(|(a, b, by_vertices)| Some((number(a)?, number(b)?, by_vertices))) {
                Some((a, b, true)) => Ok(EdgeSpec::Vertices(a, b)),
                Some((f, c, false)) => Ok(EdgeSpec::Corner(f, c)),
                None => Err(bad_input(format!(
                    "{t:?} in {s:?} is not an edge: write U-W (two vertex numbers) or F:C (face and corner)"
                ))),
            }
        })
        .collect()
}

/// Parses a comma-separated list of numbers such as `3,7,12`; `what`
/// names them in messages ("face", "vertex").
pub fn parse_index_list(s: &str, what: &str) -> Result<Vec<usize>> {
    s.split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| bad_input(format!("{t:?} in {s:?} is not a {what} number")))
        })
        .collect()
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
                let Imported {
                    mesh,
                    faces,
                    vertices,
                    ..
                } = to_dlfl(&soup, ImportOptions { split_nonmanifold })
                    .map_err(|e| bad_input(format!("{name}: {e}")))?;
                Ok(Kernel {
                    mesh,
                    faces,
                    vertices,
                })
            }
            Input::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw).map_err(|e| bad_input(format!("{name}: {e}")))?;
                let faces = (0..raw.face_count()).map(|f| mesh.face_at(f)).collect();
                let vertices = (0..raw.positions.len())
                    .map(|v| mesh.vertex_at(v))
                    .collect();
                Ok(Kernel {
                    mesh,
                    faces,
                    vertices,
                })
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
