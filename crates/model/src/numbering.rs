//! # The user's numbers for a kernel mesh
//!
//! The kernel names its elements by generational ids ([`FaceId`],
//! [`VertexId`], …) that no user ever sees. Users name them by number:
//! face `N` and vertex `N` as the input file lists them (what `holey info`
//! counts), or as a mesh's arrays list them (Python's `Mesh.to_arrays`);
//! a corner as `F:C` (corner `C` of face `F`); an edge as `U-W` (between
//! vertices `U` and `W`) or by a corner that starts it.
//!
//! A [`Numbering`] maps those numbers to kernel ids and back:
//! - [`parse_index_list`], [`parse_edge_list`] and [`parse_face_corner`]
//!   read what a user writes;
//! - [`Numbering::face`], [`Numbering::vertex`], [`Numbering::corner`],
//!   [`Numbering::edge`] and [`Numbering::cut_targets`] resolve numbers to
//!   ids, refusing with a [`NumberingError`] that names the bad number;
//! - [`Numbering::face_name`], [`Numbering::vertex_name`] and
//!   [`Numbering::edge_name`] turn ids back into numbers, and
//!   [`Numbering::describe_cut`], [`Numbering::describe_extrude`] and
//!   [`Numbering::describe_wireframe`] restate the toolbox's refusals,
//!   which name kernel ids, in those numbers.
//!
//! The numbers are fixed when the numbering is made: resolve every number
//! before the first edit, and describe a refusal while the mesh is still as
//! it was (every tool of this crate leaves the mesh unchanged when it
//! refuses).
//!
//! ```
//! use holey_dlfl::convert::{ImportOptions, to_dlfl};
//! use holey_mesh::PolyMesh;
//! use holey_model::cut::{CutOffset, cut};
//! use holey_model::numbering::{Numbering, parse_edge_list, parse_index_list};
//! use glam::DVec3;
//!
//! // A square pyramid as a file would list it: five vertices, five faces.
//! let positions = vec![
//!     DVec3::new(0.0, 0.0, 0.0),
//!     DVec3::new(1.0, 0.0, 0.0),
//!     DVec3::new(1.0, 1.0, 0.0),
//!     DVec3::new(0.0, 1.0, 0.0),
//!     DVec3::new(0.5, 0.5, 1.0),
//! ];
//! let faces = vec![
//!     vec![3, 2, 1, 0],
//!     vec![0, 1, 4],
//!     vec![1, 2, 4],
//!     vec![2, 3, 4],
//!     vec![3, 0, 4],
//! ];
//! let soup = PolyMesh::from_faces(positions, faces);
//! let (mut mesh, numbering) =
//!     Numbering::from_import(to_dlfl(&soup, ImportOptions::default())?);
//!
//! // `--vertex 0 --edge 1-0` as a user writes them: they share vertex 0.
//! let vertices = parse_index_list("0", "vertex")?;
//! let edges = parse_edge_list("1-0")?;
//! let targets = numbering.cut_targets(&mesh, &vertices, &edges, &[])?;
//! let edge = numbering.edge(&mesh, edges[0])?;
//! assert_eq!(numbering.edge_name(&mesh, edge), "edge 1-0");
//!
//! // A refusal names numbers, not kernel ids.
//! assert_eq!(
//!     numbering.face(7).unwrap_err().to_string(),
//!     "face 7 does not exist: the input has 5 faces"
//! );
//! let refused = cut(&mut mesh, &targets, CutOffset::Fraction(0.25)).unwrap_err();
//! assert_eq!(
//!     numbering.describe_cut(&mesh, &refused),
//!     "two cut targets share vertex 0; cut them one at a time"
//! );
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::fmt;

use holey_dlfl::convert::{Imported, to_poly};
use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, NonFinite, RawMesh, VertexId};

use crate::cut::{CutError, CutTarget};
use crate::extrude::ExtrudeError;
use crate::handle::MultiHandleError;
use crate::wireframe::WireframeError;

/// Whose list the numbers follow, which also decides how an edge is
/// written back to the user.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    /// The input file's order (what `holey info` counts; for a `.dlfl`
    /// file its `f` and `h` lines together). Edges are written `U-W`.
    File,
    /// The order in which [`to_poly`] lists the mesh's faces and the
    /// vertices they use (Python's `Mesh.to_arrays`). Edges are written
    /// `(U, W)`.
    Arrays,
}

impl fmt::Display for Order {
    /// What the numbers count: "input" or "mesh".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Order::File => "input",
            Order::Arrays => "mesh",
        })
    }
}

/// An edge as a user names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeSpec {
    /// The edge between vertices `U` and `W`, written `U-W`.
    Vertices(usize, usize),
    /// The edge leaving corner `C` of face `F` towards the next corner,
    /// written `F:C`.
    Corner(usize, usize),
}

impl fmt::Display for EdgeSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EdgeSpec::Vertices(a, b) => write!(f, "{a}-{b}"),
            EdgeSpec::Corner(face, c) => write!(f, "{face}:{c}"),
        }
    }
}

/// A number that names nothing in the mesh, or text that is not a number.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NumberingError {
    /// A face number past the end.
    #[error("face {index} does not exist: the {order} has {count} faces")]
    NoSuchFace {
        /// The number asked for.
        index: usize,
        /// How many faces there are.
        count: usize,
        /// Whose numbers.
        order: Order,
    },
    /// A vertex number past the end.
    #[error("vertex {index} does not exist: the {order} has {count} vertices")]
    NoSuchVertex {
        /// The number asked for.
        index: usize,
        /// How many vertices there are.
        count: usize,
        /// Whose numbers.
        order: Order,
    },
    /// A vertex of the file that no face uses, so the kernel has none.
    #[error("vertex {index} is not used by any face, so it is not in the mesh")]
    UnusedVertex {
        /// The number asked for.
        index: usize,
    },
    /// A face number the numbering has but the mesh no longer does.
    #[error("face {index} is not in the mesh")]
    MissingFace {
        /// The number asked for.
        index: usize,
    },
    /// A corner number past the end of its face.
    #[error("face {face} has {len} corners; there is no corner {corner}")]
    NoSuchCorner {
        /// The face's number.
        face: usize,
        /// The corner asked for.
        corner: usize,
        /// How many corners the face has.
        len: usize,
    },
    /// A corner that starts no edge (a point-sphere's only corner).
    #[error("corner {face}:{corner} starts no edge (it is a point-sphere)")]
    NoEdgeAtCorner {
        /// The face's number.
        face: usize,
        /// The corner's number in the face.
        corner: usize,
    },
    /// Two vertices that no edge joins.
    #[error("vertices {0} and {1} are not joined by an edge")]
    NotJoined(usize, usize),
    /// An edge that could not be resolved, with the edge as the user
    /// wrote it.
    #[error("edge {edge}: {reason}")]
    BadEdge {
        /// The edge as written (`U-W`, `F:C` or `(U, W)`).
        edge: String,
        /// Why it names no edge.
        reason: Box<NumberingError>,
    },
    /// An entry of an edge list that is neither `U-W` nor `F:C`.
    #[error(
        "{token:?} in {list:?} is not an edge: write U-W (two vertex numbers) or F:C (face and corner)"
    )]
    NotAnEdge {
        /// The entry.
        token: String,
        /// The whole list.
        list: String,
    },
    /// An entry of a number list that is not a non-negative integer.
    #[error("{token:?} in {list:?} is not a {what} number")]
    NotANumber {
        /// The entry.
        token: String,
        /// The whole list.
        list: String,
        /// What the numbers name ("face", "vertex").
        what: &'static str,
    },
    /// Text that is not `FACE:CORNER`.
    #[error("{text:?} is not FACE:CORNER (two non-negative integers)")]
    NotFaceCorner {
        /// The text.
        text: String,
    },
    /// A kernel query failed: the mesh is not the one numbered.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// The faces and vertices of a kernel mesh in the user's numbers; see the
/// [module docs](self).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Numbering {
    /// Face `i` (`None`: dropped on import, or gone).
    faces: Vec<Option<FaceId>>,
    /// Vertex `i` (`None`: used by no face, so not in the kernel).
    vertices: Vec<Option<VertexId>>,
    order: Order,
}

impl Numbering {
    /// File order from the two maps an import gives: the kernel face of
    /// each file face and the kernel vertex of each file vertex.
    pub fn file_order(faces: Vec<Option<FaceId>>, vertices: Vec<Option<VertexId>>) -> Numbering {
        Numbering {
            faces,
            vertices,
            order: Order::File,
        }
    }

    /// A polygon soup's import split into its mesh and its file order.
    pub fn from_import(imported: Imported) -> (Mesh, Numbering) {
        let Imported {
            mesh,
            faces,
            vertices,
            ..
        } = imported;
        (mesh, Numbering::file_order(faces, vertices))
    }

    /// File order of a mesh built from `raw` by [`Mesh::from_raw`] (a
    /// `.dlfl` file): its faces, holes included, and vertices by slot.
    pub fn of_raw(mesh: &Mesh, raw: &RawMesh) -> Numbering {
        Numbering::file_order(
            (0..raw.face_count()).map(|f| mesh.face_at(f)).collect(),
            (0..raw.positions.len())
                .map(|v| mesh.vertex_at(v))
                .collect(),
        )
    }

    /// The order in which [`to_poly`] lists `mesh`: its exported faces and
    /// the vertices they use, by slot.
    pub fn of_arrays(mesh: &Mesh) -> Result<Numbering, NumberingError> {
        let faces = to_poly(mesh).faces;
        let mut used = vec![false; mesh.vertices().last().map_or(0, |v| v.index() + 1)];
        for &f in &faces {
            for c in mesh.face_corners(f)? {
                let v = mesh.corner_vertex(c)?;
                if let Some(slot) = used.get_mut(v.index()) {
                    *slot = true;
                }
            }
        }
        let vertices = mesh
            .vertices()
            .filter(|v| used.get(v.index()).copied().unwrap_or(false))
            .map(Some)
            .collect();
        Ok(Numbering {
            faces: faces.into_iter().map(Some).collect(),
            vertices,
            order: Order::Arrays,
        })
    }

    /// Whose list the numbers follow.
    pub fn order(&self) -> Order {
        self.order
    }

    /// The face numbered `index`.
    pub fn face(&self, index: usize) -> Result<FaceId, NumberingError> {
        match self.faces.get(index) {
            Some(Some(f)) => Ok(*f),
            Some(None) => Err(NumberingError::MissingFace { index }),
            None => Err(NumberingError::NoSuchFace {
                index,
                count: self.faces.len(),
                order: self.order,
            }),
        }
    }

    /// The faces numbered `indices`, each with its number, in the order
    /// given and without repeats: all resolved before any is edited, so
    /// the numbers are the original ones whatever an earlier edit makes.
    pub fn faces(&self, indices: &[usize]) -> Result<Vec<(usize, FaceId)>, NumberingError> {
        let mut out: Vec<(usize, FaceId)> = Vec::with_capacity(indices.len());
        for &n in indices {
            let f = self.face(n)?;
            if !out.iter().any(|&(_, g)| g == f) {
                out.push((n, f));
            }
        }
        Ok(out)
    }

    /// The vertex numbered `index`.
    pub fn vertex(&self, index: usize) -> Result<VertexId, NumberingError> {
        match self.vertices.get(index) {
            Some(Some(v)) => Ok(*v),
            Some(None) => Err(NumberingError::UnusedVertex { index }),
            None => Err(NumberingError::NoSuchVertex {
                index,
                count: self.vertices.len(),
                order: self.order,
            }),
        }
    }

    /// Corner `corner` of face `face` (corner `j` is the face's `j`-th
    /// vertex, from the corner [`Mesh::face_corner`] gives).
    pub fn corner(
        &self,
        mesh: &Mesh,
        face: usize,
        corner: usize,
    ) -> Result<CornerId, NumberingError> {
        let f = self.face(face)?;
        let len = mesh.face_len(f)?;
        mesh.face_corners(f)?
            .nth(corner)
            .ok_or(NumberingError::NoSuchCorner { face, corner, len })
    }

    /// The edge `spec` names.
    pub fn edge(&self, mesh: &Mesh, spec: EdgeSpec) -> Result<EdgeId, NumberingError> {
        match spec {
            EdgeSpec::Corner(face, corner) => {
                let c = self.corner(mesh, face, corner)?;
                mesh.corner_edge(c)?
                    .ok_or(NumberingError::NoEdgeAtCorner { face, corner })
            }
            EdgeSpec::Vertices(a, b) => {
                let (u, w) = (self.vertex(a)?, self.vertex(b)?);
                for c in mesh.vertex_corners(u)? {
                    if let Some(e) = mesh.corner_edge(c)? {
                        let [x, y] = mesh.edge_vertices(e)?;
                        if (x == u && y == w) || (x == w && y == u) {
                            return Ok(e);
                        }
                    }
                }
                Err(NumberingError::NotJoined(a, b))
            }
        }
    }

    /// The cut targets the numbers name: vertices, then edges, then faces,
    /// each in the order given. An edge that names nothing is refused with
    /// [`NumberingError::BadEdge`], which repeats it as written.
    pub fn cut_targets(
        &self,
        mesh: &Mesh,
        vertices: &[usize],
        edges: &[EdgeSpec],
        faces: &[usize],
    ) -> Result<Vec<CutTarget>, NumberingError> {
        let mut out = Vec::with_capacity(vertices.len() + edges.len() + faces.len());
        for &v in vertices {
            out.push(CutTarget::Vertex(self.vertex(v)?));
        }
        for &spec in edges {
            let e = self
                .edge(mesh, spec)
                .map_err(|reason| NumberingError::BadEdge {
                    edge: self.spec_text(spec),
                    reason: Box::new(reason),
                })?;
            out.push(CutTarget::Edge(e));
        }
        for &f in faces {
            out.push(CutTarget::Face(self.face(f)?));
        }
        Ok(out)
    }

    /// An edge as this numbering's users write it.
    fn spec_text(&self, spec: EdgeSpec) -> String {
        match (self.order, spec) {
            (Order::Arrays, EdgeSpec::Vertices(a, b)) => format!("({a}, {b})"),
            _ => spec.to_string(),
        }
    }

    /// `vertex N` in this numbering (by its kernel id if it has no number).
    pub fn vertex_name(&self, v: VertexId) -> String {
        match self.vertices.iter().position(|&w| w == Some(v)) {
            Some(n) => format!("vertex {n}"),
            None => format!("vertex {v}"),
        }
    }

    /// `edge U-W` (file order) or `edge (U, W)` (arrays) by its vertices'
    /// numbers (by its kernel id if either has none).
    pub fn edge_name(&self, mesh: &Mesh, e: EdgeId) -> String {
        let number = |v: VertexId| self.vertices.iter().position(|&w| w == Some(v));
        match mesh.edge_vertices(e) {
            Ok([a, b]) => match (number(a), number(b)) {
                (Some(a), Some(b)) => format!("edge {}", self.spec_text(EdgeSpec::Vertices(a, b))),
                _ => format!("edge {e}"),
            },
            Err(_) => format!("edge {e}"),
        }
    }

    /// `face N` in this numbering; a face without a number (a hole, which
    /// no list holds, or one made since) by its kernel id.
    pub fn face_name(&self, mesh: &Mesh, f: FaceId) -> String {
        if let Some(n) = self.faces.iter().position(|&g| g == Some(f)) {
            return format!("face {n}");
        }
        match (self.order, mesh.is_hole(f).unwrap_or(false)) {
            (Order::File, true) => format!("hole face {f}"),
            (Order::Arrays, true) => format!("face {f} (a hole)"),
            (_, false) => format!("face {f}"),
        }
    }

    /// A cut's or truncation's refusal in these numbers; `mesh` is the
    /// mesh it refused (unchanged).
    pub fn describe_cut(&self, mesh: &Mesh, e: &CutError) -> String {
        let target = |t: &CutTarget| match *t {
            CutTarget::Vertex(v) => self.vertex_name(v),
            CutTarget::Edge(e) => self.edge_name(mesh, e),
            CutTarget::Face(f) => self.face_name(mesh, f),
        };
        match e {
            CutError::OffsetTooLarge {
                edge,
                length,
                offset,
                limit,
            } => format!(
                "an offset of {offset} reaches the middle of {} (length {length}); it must be less than {limit}",
                self.edge_name(mesh, *edge)
            ),
            CutError::Overlap(v) => format!(
                "two cut targets share {}; cut them one at a time",
                self.vertex_name(*v)
            ),
            CutError::SelfLoop(e) => format!(
                "{} is a self-loop; regions with self-loops are not cut",
                self.edge_name(mesh, *e)
            ),
            CutError::NotADisk(t) => format!(
                "the neighbourhood of {} is not a disk (it wraps around a handle or a hole); it cannot be cut off by one face",
                target(t)
            ),
            CutError::NothingToCut(t) => format!(
                "{} has no edges leaving it (it is a whole component); there is nothing to cut",
                target(t)
            ),
            CutError::HoleFace(f) => format!(
                "{} is a hole (a boundary loop); it cannot be cut or cut away",
                self.face_name(mesh, *f)
            ),
            other => other.to_string(),
        }
    }

    /// A multi-face handle's refusal in these numbers; `mesh` is the mesh
    /// it refused (unchanged by a refusal).
    pub fn describe_multi_handle(&self, mesh: &Mesh, e: &MultiHandleError) -> String {
        let face = |f: FaceId| self.face_name(mesh, f);
        match e {
            MultiHandleError::DuplicateFace(f) => format!("{} is selected twice", face(*f)),
            MultiHandleError::AtCentre(f) => format!(
                "{} has its centroid at the hub's centre, so no direction from the hub",
                face(*f)
            ),
            MultiHandleError::SameDirection(f, g) => format!(
                "{} and {} lie in the same direction from the hub's centre",
                face(*f),
                face(*g)
            ),
            MultiHandleError::NoCommonView(faces) => format!(
                "{} look away from each other: no point near the selection (within four times its radius) lies in front of all of them, so a hub would sit inside the surface and the handles would pass through it; select faces that look at a common point from outside",
                self.face_list(mesh, faces)
            ),
            MultiHandleError::OneSided(faces) => format!(
                "{} all look into one side: every point in front of all of them sees them to one side, and a hub needs selected faces all around it",
                self.face_list(mesh, faces)
            ),
            MultiHandleError::Blind { faces, hub } => format!(
                "the hub's centre {hub} is not strictly in front of {}",
                self.face_list(mesh, faces)
            ),
            MultiHandleError::Blocked { face: f, by, hub } => format!(
                "{} cannot see the hub at {hub}: {} is in the way",
                face(*f),
                face(*by)
            ),
            MultiHandleError::Crosses { faces, pairs } => format!(
                "the handles from {} would cross the surface or each other ({pairs} crossing triangle pairs); try a smaller hub scale, smaller weights or more segments",
                self.face_list(mesh, faces)
            ),
            other => other.to_string(),
        }
    }

    /// Faces named in these numbers: "faces 3, 7 and 9" (one: "face 3").
    fn face_list(&self, mesh: &Mesh, faces: &[FaceId]) -> String {
        let names: Vec<String> = faces
            .iter()
            .map(|&f| {
                let name = self.face_name(mesh, f);
                name.strip_prefix("face ")
                    .map(str::to_string)
                    .unwrap_or(name)
            })
            .collect();
        match names.as_slice() {
            [] => "no faces".to_string(),
            [one] => format!("face {one}"),
            [rest @ .., last] => format!("faces {} and {last}", rest.join(", ")),
        }
    }

    /// An extrusion's refusal in these numbers; `mesh` is the mesh it
    /// refused.
    pub fn describe_extrude(&self, mesh: &Mesh, e: &ExtrudeError) -> String {
        let face = |f: FaceId| self.face_name(mesh, f);
        match e {
            ExtrudeError::HoleFace(f) => format!(
                "{} is a hole (a boundary loop), not surface; there is nothing to extrude",
                face(*f)
            ),
            ExtrudeError::PointSphere(f) => format!(
                "{} is a point-sphere (one corner, no edge); there is nothing to extrude",
                face(*f)
            ),
            ExtrudeError::SelfLoop { face: f, edge } => format!(
                "{} of {} is a self-loop; faces with self-loops are not extruded",
                self.edge_name(mesh, *edge),
                face(*f)
            ),
            ExtrudeError::DegenerateFace(f) => format!(
                "{} has zero area, so it has no normal to extrude along",
                face(*f)
            ),
            ExtrudeError::NonFinite { face: f, point } => format!(
                "a new vertex of {} would have non-finite coordinates ({point}); the parameters are too large for the model's scale",
                face(*f)
            ),
            ExtrudeError::Face { face: f, cause } => {
                format!("{}: {}", face(*f), self.describe_extrude(mesh, cause))
            }
            ExtrudeError::Repeated { step, count, cause } => {
                // The faces of a later repetition are ones the earlier
                // repetitions made, unknown to the caller: named so.
                let why = match cause.as_ref() {
                    ExtrudeError::NonFinite { point, .. } => format!(
                        "a new vertex would have non-finite coordinates ({}); the distance times the count is too large for the model's scale",
                        NonFinite {
                            what: "a lifted corner",
                            index: None,
                            ..*point
                        }
                    ),
                    ExtrudeError::DegenerateFace(_) => {
                        "a face made by the earlier repetitions has zero area, so it has no normal to extrude along".to_string()
                    }
                    ExtrudeError::NoDirection { .. } => {
                        "the normals of the faces made by the earlier repetitions cancel out; there is no direction to extrude along".to_string()
                    }
                    other => self.describe_extrude(mesh, other),
                };
                format!("repetition {step} of {count} was refused, so none was made: {why}")
            }
            other => other.to_string(),
        }
    }

    /// A wireframe's or columns' refusal in these numbers; `mesh` is the
    /// mesh it was asked of.
    pub fn describe_wireframe(&self, mesh: &Mesh, e: &WireframeError) -> String {
        match e {
            WireframeError::DegenerateFace(f) => format!(
                "{} has zero area, so its corners cannot be moved into it",
                self.face_name(mesh, *f)
            ),
            WireframeError::DegenerateCorner { face, corner } => {
                let index = mesh
                    .face_corners(*face)
                    .ok()
                    .and_then(|mut cs| cs.position(|c| c == *corner));
                match index {
                    Some(i) => format!(
                        "corner {i} of {} has no inward direction (its edges coincide or fold back)",
                        self.face_name(mesh, *face)
                    ),
                    None => e.to_string(),
                }
            }
            WireframeError::ThicknessTooLarge { face, thickness } => format!(
                "at thickness {thickness} the shrunk copy of {} turns over; use a smaller thickness",
                self.face_name(mesh, *face)
            ),
            WireframeError::EdgeTooShort { edge, radius } => format!(
                "at radius {radius} the joints at the ends of {} overlap (the edge is too short)",
                self.edge_name(mesh, *edge)
            ),
            WireframeError::CoincidentEdges(v) => format!(
                "two edges at {} point the same way; their columns would coincide",
                self.vertex_name(*v)
            ),
            WireframeError::NoNormal(v) => format!(
                "{} has no normal: the normals of its faces cancel out",
                self.vertex_name(*v)
            ),
            other => other.to_string(),
        }
    }
}

/// The entries of a comma-separated list, blank ones skipped.
fn entries(list: &str) -> impl Iterator<Item = &str> {
    list.split(',').filter(|t| !t.trim().is_empty())
}

/// A non-negative integer, blanks around it allowed.
fn number(text: &str) -> Option<usize> {
    text.trim().parse().ok()
}

/// Parses a comma-separated list of numbers such as `3,7,12`; `what`
/// names them in the error ("face", "vertex").
pub fn parse_index_list(list: &str, what: &'static str) -> Result<Vec<usize>, NumberingError> {
    entries(list)
        .map(|t| {
            number(t).ok_or_else(|| NumberingError::NotANumber {
                token: t.to_owned(),
                list: list.to_owned(),
                what,
            })
        })
        .collect()
}

/// Parses a comma-separated list of edges, each `U-W` or `F:C`.
pub fn parse_edge_list(list: &str) -> Result<Vec<EdgeSpec>, NumberingError> {
    entries(list)
        .map(|t| {
            let pair = t
                .split_once('-')
                .map(|(a, b)| (a, b, true))
                .or_else(|| t.split_once(':').map(|(f, c)| (f, c, false)));
            match pair.and_then(|(a, b, by_vertices)| Some((number(a)?, number(b)?, by_vertices))) {
                Some((a, b, true)) => Ok(EdgeSpec::Vertices(a, b)),
                Some((f, c, false)) => Ok(EdgeSpec::Corner(f, c)),
                None => Err(NumberingError::NotAnEdge {
                    token: t.to_owned(),
                    list: list.to_owned(),
                }),
            }
        })
        .collect()
}

/// Parses a corner written `FACE:CORNER` such as `12:0`; a lone face
/// number means its corner 0.
pub fn parse_face_corner(text: &str) -> Result<(usize, usize), NumberingError> {
    let parsed = match text.split_once(':') {
        Some((f, c)) => number(f).zip(number(c)),
        None => number(text).map(|f| (f, 0)),
    };
    parsed.ok_or_else(|| NumberingError::NotFaceCorner {
        text: text.to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_dlfl::convert::{ImportOptions, to_dlfl};
    use holey_mesh::PolyMesh;

    /// A unit cube as a file lists it, with an unused ninth vertex.
    fn cube() -> (Mesh, Numbering) {
        let mut soup = holey_shapes::cube(1).expect("a unit cube");
        soup.positions.push(glam::DVec3::splat(9.0));
        let imported = to_dlfl(&soup, ImportOptions::default()).expect("a cube imports");
        Numbering::from_import(imported)
    }

    #[test]
    fn lists_parse_and_refuse_by_entry() {
        assert_eq!(parse_index_list(" 3, 7,,12 ", "face"), Ok(vec![3, 7, 12]));
        assert_eq!(
            parse_index_list("3,x", "vertex").unwrap_err().to_string(),
            "\"x\" in \"3,x\" is not a vertex number"
        );
        assert_eq!(
            parse_edge_list("0-1, 2:3"),
            Ok(vec![EdgeSpec::Vertices(0, 1), EdgeSpec::Corner(2, 3)])
        );
        for bad in ["0-x", "5", "1:-2", "a:b"] {
            let e = parse_edge_list(bad).unwrap_err();
            assert!(matches!(e, NumberingError::NotAnEdge { .. }), "{bad}: {e}");
        }
        assert_eq!(parse_face_corner("12:0"), Ok((12, 0)));
        assert_eq!(parse_face_corner("4"), Ok((4, 0)));
        assert_eq!(
            parse_face_corner("4:").unwrap_err().to_string(),
            "\"4:\" is not FACE:CORNER (two non-negative integers)"
        );
    }

    #[test]
    fn numbers_resolve_and_name_back() -> Result<(), NumberingError> {
        let (mesh, n) = cube();
        for i in 0..6 {
            assert_eq!(n.face_name(&mesh, n.face(i)?), format!("face {i}"));
        }
        for i in 0..8 {
            assert_eq!(n.vertex_name(n.vertex(i)?), format!("vertex {i}"));
        }
        let e = n.edge(&mesh, EdgeSpec::Corner(0, 0))?;
        let [a, b] = mesh.edge_vertices(e)?;
        assert_eq!(mesh.corner_vertex(n.corner(&mesh, 0, 0)?)?, a);
        let spec = EdgeSpec::Vertices(
            n.vertices.iter().position(|&v| v == Some(a)).unwrap_or(99),
            n.vertices.iter().position(|&v| v == Some(b)).unwrap_or(99),
        );
        assert_eq!(n.edge(&mesh, spec)?, e);
        assert_eq!(n.edge_name(&mesh, e), format!("edge {spec}"));
        assert_eq!(n.faces(&[2, 0, 2])?.len(), 2);
        Ok(())
    }

    #[test]
    fn refusals_name_the_bad_number() {
        let (mesh, n) = cube();
        let text = |e: NumberingError| e.to_string();
        assert_eq!(
            text(n.face(6).unwrap_err()),
            "face 6 does not exist: the input has 6 faces"
        );
        assert_eq!(
            text(n.vertex(8).unwrap_err()),
            "vertex 8 is not used by any face, so it is not in the mesh"
        );
        assert_eq!(
            text(n.vertex(9).unwrap_err()),
            "vertex 9 does not exist: the input has 9 vertices"
        );
        assert_eq!(
            text(n.corner(&mesh, 1, 4).unwrap_err()),
            "face 1 has 4 corners; there is no corner 4"
        );
        // Opposite corners of the cube are not joined.
        let far = (1..8)
            .find(|&w| n.edge(&mesh, EdgeSpec::Vertices(0, w)).is_err())
            .unwrap_or(0);
        assert_eq!(
            text(
                n.cut_targets(&mesh, &[], &[EdgeSpec::Vertices(0, far)], &[])
                    .unwrap_err()
            ),
            format!("edge 0-{far}: vertices 0 and {far} are not joined by an edge")
        );
    }

    #[test]
    fn arrays_order_follows_to_poly() -> Result<(), NumberingError> {
        let (mesh, file) = cube();
        let arrays = Numbering::of_arrays(&mesh)?;
        assert_eq!(arrays.order(), Order::Arrays);
        let listed = to_poly(&mesh);
        assert_eq!(listed.faces.len(), 6);
        assert_eq!(arrays.vertices.len(), listed.poly.positions.len());
        for (i, &f) in listed.faces.iter().enumerate() {
            assert_eq!(arrays.face(i)?, f);
        }
        assert_eq!(
            arrays.face(6).unwrap_err().to_string(),
            "face 6 does not exist: the mesh has 6 faces"
        );
        let e = file.edge(&mesh, EdgeSpec::Corner(0, 0))?;
        assert!(arrays.edge_name(&mesh, e).starts_with("edge ("));
        Ok(())
    }

    #[test]
    fn extrusion_refusals_name_the_face_and_the_point() -> Result<(), NumberingError> {
        use crate::extrude::{ExtrudeKind, ExtrudeOptions, extrude_selection};

        let (mut mesh, n) = cube();
        let faces: Vec<FaceId> = n.faces(&[1, 2])?.into_iter().map(|(_, f)| f).collect();
        let options = ExtrudeOptions {
            distance: Some(1e308),
            count: Some(3),
            ..ExtrudeOptions::default()
        };
        let Err(e) = extrude_selection(&mut mesh, &faces, ExtrudeKind::Plain, &options) else {
            panic!("1e308 three times was not refused");
        };
        let text = n.describe_extrude(&mesh, &e);
        assert!(
            text.starts_with(
                "face 1: a new vertex of face 1 would have non-finite coordinates (new point 4 has a non-finite coordinate ("
            ) && text.ends_with("); the parameters are too large for the model's scale")
                && text.contains("inf"),
            "{text}"
        );
        Ok(())
    }

    #[test]
    fn open_meshes_name_their_holes() -> Result<(), NumberingError> {
        let square = PolyMesh::from_faces(
            vec![
                glam::DVec3::ZERO,
                glam::DVec3::X,
                glam::DVec3::new(1.0, 1.0, 0.0),
                glam::DVec3::Y,
            ],
            vec![vec![0u32, 1, 2, 3]],
        );
        let (mesh, n) = Numbering::from_import(
            to_dlfl(&square, ImportOptions::default())
                .map_err(|_| NumberingError::MissingFace { index: 0 })?,
        );
        let hole = mesh
            .faces()
            .find(|&f| mesh.is_hole(f).unwrap_or(false))
            .ok_or(NumberingError::MissingFace { index: 1 })?;
        assert_eq!(n.face_name(&mesh, hole), format!("hole face {hole}"));
        assert_eq!(
            Numbering::of_arrays(&mesh)?.face_name(&mesh, hole),
            format!("face {hole} (a hole)")
        );
        Ok(())
    }
}
