//! TopMod's toolbox for `holey.Mesh` (issue 18): remeshing schemes,
//! extrusions, wireframes and columns, cuts and truncations. Each function
//! takes the mesh and returns a new one; `kernel.rs` exposes them as
//! methods. Faces and vertices are numbered as `Mesh.to_arrays` lists
//! them; an edge is named by its two vertices.

use std::collections::HashSet;

use holey::dlfl::convert::to_poly;
use holey::dlfl::{EdgeId, FaceId, Mesh, VertexId};
use holey::model::cut::{CutError, CutOffset, CutTarget, cut};
use holey::model::extrude::{
    self, DomeParams, DooSabinParams, ExtrudeParams, MultiExtrudeParams, RegionDirection,
};
use holey::model::wireframe::{ColumnParams, WireframeError, columns, wireframe};
use holey::subdiv::{RemeshParams, RemeshScheme, SubdivError, remesh};
use pyo3::PyResult;

use crate::errors::bad;

/// The faces and vertices of a mesh as `to_arrays` numbers them.
pub struct Numbering {
    pub faces: Vec<FaceId>,
    pub vertices: Vec<VertexId>,
}

impl Numbering {
    pub fn of(mesh: &Mesh) -> PyResult<Numbering> {
        let exported = to_poly(mesh);
        let mut used = HashSet::new();
        for &f in &exported.faces {
            for c in mesh.face_corners(f).map_err(bad)? {
                used.insert(mesh.corner_vertex(c).map_err(bad)?);
            }
        }
        let vertices = mesh.vertices().filter(|v| used.contains(v)).collect();
        Ok(Numbering {
            faces: exported.faces,
            vertices,
        })
    }

    pub fn face(&self, index: usize) -> PyResult<FaceId> {
        self.faces.get(index).copied().ok_or_else(|| {
            bad(format!(
                "face {index} does not exist: the mesh has {} faces",
                self.faces.len()
            ))
        })
    }

    pub fn vertex(&self, index: usize) -> PyResult<VertexId> {
        self.vertices.get(index).copied().ok_or_else(|| {
            bad(format!(
                "vertex {index} does not exist: the mesh has {} vertices",
                self.vertices.len()
            ))
        })
    }

    /// `vertex N` as `to_arrays` numbers it (the kernel id if it has no number).
    fn vertex_name(&self, v: VertexId) -> String {
        match self.vertices.iter().position(|&w| w == v) {
            Some(n) => format!("vertex {n}"),
            None => format!("vertex {v}"),
        }
    }

    /// `edge (U, W)` by its vertices' numbers.
    fn edge_name(&self, mesh: &Mesh, e: EdgeId) -> String {
        let number = |v: VertexId| self.vertices.iter().position(|&w| w == v);
        match mesh.edge_vertices(e) {
            Ok([a, b]) => match (number(a), number(b)) {
                (Some(a), Some(b)) => format!("edge ({a}, {b})"),
                _ => format!("edge {e}"),
            },
            Err(_) => format!("edge {e}"),
        }
    }

    /// `face N` as `to_arrays` numbers it (a hole by its kernel id).
    fn face_name(&self, f: FaceId) -> String {
        match self.faces.iter().position(|&g| g == f) {
            Some(n) => format!("face {n}"),
            None => format!("face {f} (a hole)"),
        }
    }

    /// A cut's refusal in this numbering; the library names kernel ids.
    fn cut_error(&self, mesh: &Mesh, e: &CutError) -> String {
        let target = |t: &CutTarget| match *t {
            CutTarget::Vertex(v) => self.vertex_name(v),
            CutTarget::Edge(e) => self.edge_name(mesh, e),
            CutTarget::Face(f) => self.face_name(f),
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
                self.face_name(*f)
            ),
            other => other.to_string(),
        }
    }

    /// A wireframe's refusal in this numbering.
    fn wireframe_error(&self, mesh: &Mesh, e: &WireframeError) -> String {
        match e {
            WireframeError::DegenerateFace(f) => format!(
                "{} has zero area, so its corners cannot be moved into it",
                self.face_name(*f)
            ),
            WireframeError::ThicknessTooLarge { face, thickness } => format!(
                "at thickness {thickness} the shrunk copy of {} turns over; use a smaller thickness",
                self.face_name(*face)
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

    /// The edge between vertices `a` and `b`.
    pub fn edge(&self, mesh: &Mesh, (a, b): (usize, usize)) -> PyResult<EdgeId> {
        let (u, w) = (self.vertex(a)?, self.vertex(b)?);
        for c in mesh.vertex_corners(u).map_err(bad)? {
            if let Some(e) = mesh.corner_edge(c).map_err(bad)? {
                let [x, y] = mesh.edge_vertices(e).map_err(bad)?;
                if (x == u && y == w) || (x == w && y == u) {
                    return Ok(e);
                }
            }
        }
        Err(bad(format!(
            "vertices {a} and {b} are not joined by an edge"
        )))
    }
}

/// `levels` levels of the scheme named `scheme`, with its options.
pub fn run_remesh(
    mesh: &Mesh,
    scheme: &str,
    levels: usize,
    options: &[(String, f64)],
    triangles: bool,
) -> PyResult<Mesh> {
    let scheme: RemeshScheme = scheme.parse().map_err(bad)?;
    let mut p = RemeshParams::default();
    for (name, value) in options {
        p.set(scheme, name, *value).map_err(|e| match e {
            SubdivError::UnknownOption { .. } => bad(format!(
                "option {name:?} does not apply to scheme {scheme} (the options are alpha, thickness, offset, scale, length, weight, twist, height, curve and triangles, each read by some schemes; see `holey remesh --help`)"
            )),
            e => bad(e),
        })?;
    }
    if triangles {
        if scheme != RemeshScheme::SubdivideFace {
            return Err(bad(format!(
                "option \"triangles\" applies to scheme subdivide-face only, not {scheme}"
            )));
        }
        p.subdivide_face_quads = false;
    }
    remesh(mesh, scheme, &p, levels).map_err(bad)
}

/// What `Mesh.extrude` was asked for.
pub struct Extrusion {
    pub kind: String,
    pub distance: Option<f64>,
    pub scale: Option<f64>,
    pub rotation: Option<f64>,
    pub twist: Option<f64>,
    pub height: Option<f64>,
    pub count: Option<usize>,
    pub together: bool,
    pub vertex_normals: bool,
}

impl Extrusion {
    /// Refuses an option the kind does not read.
    fn check(&self) -> PyResult<()> {
        let reads: &[&str] = if self.together {
            &["distance", "count"]
        } else {
            match self.kind.as_str() {
                "plain" => &["distance", "scale", "rotation", "count"],
                "doo-sabin" => &["distance", "scale", "twist", "count"],
                "cubical" | "dome" => &["height", "count"],
                "dodecahedral" | "icosahedral" | "octahedral" => &["height"],
                "stellate" | "double-stellate" => &["distance"],
                other => {
                    return Err(bad(format!(
                        "extrusion kind {other:?} is not known: use plain, cubical, dodecahedral, icosahedral, octahedral, doo-sabin, dome, stellate or double-stellate"
                    )));
                }
            }
        };
        if self.together && self.kind != "plain" {
            return Err(bad(format!(
                "together=True extrudes plainly; it does not take kind {:?}",
                self.kind
            )));
        }
        let given = [
            ("distance", self.distance.is_some()),
            ("scale", self.scale.is_some()),
            ("rotation", self.rotation.is_some()),
            ("twist", self.twist.is_some()),
            ("height", self.height.is_some()),
            ("count", self.count.is_some()),
        ];
        for (name, set) in given {
            if set && !reads.contains(&name) {
                let what = if self.together {
                    "together=True".to_string()
                } else {
                    format!("kind {:?}", self.kind)
                };
                return Err(bad(format!("option {name:?} does not apply to {what}")));
            }
        }
        Ok(())
    }
}

/// Extrudes the faces numbered `faces`, one by one or together.
pub fn run_extrude(mesh: &Mesh, faces: &[usize], o: &Extrusion) -> PyResult<Mesh> {
    o.check()?;
    if faces.is_empty() {
        return Err(bad("no faces were given to extrude"));
    }
    let numbering = Numbering::of(mesh)?;
    let mut ids: Vec<(usize, FaceId)> = Vec::with_capacity(faces.len());
    for &n in faces {
        let f = numbering.face(n)?;
        if !ids.iter().any(|&(_, g)| g == f) {
            ids.push((n, f));
        }
    }
    let mut m = mesh.clone();
    if o.together {
        let params = MultiExtrudeParams {
            distance: o.distance.unwrap_or(1.0),
            direction: if o.vertex_normals {
                RegionDirection::VertexNormals
            } else {
                RegionDirection::Average
            },
            count: o.count.unwrap_or(1),
        };
        let list: Vec<FaceId> = ids.iter().map(|&(_, f)| f).collect();
        extrude::extrude_faces(&mut m, &list, &params).map_err(bad)?;
        return Ok(m);
    }
    for (n, face) in ids {
        let done = match o.kind.as_str() {
            "plain" => extrude::extrude_face(
                &mut m,
                face,
                &ExtrudeParams {
                    distance: o.distance.unwrap_or(1.0),
                    rotation_deg: o.rotation.unwrap_or(0.0),
                    scale: o.scale.unwrap_or(1.0),
                    count: o.count.unwrap_or(1),
                },
            ),
            "doo-sabin" => extrude::extrude_face_doo_sabin(
                &mut m,
                face,
                &DooSabinParams {
                    distance: o.distance.unwrap_or(1.0),
                    twist: o.twist.unwrap_or(0.0),
                    scale: o.scale.unwrap_or(1.0),
                    count: o.count.unwrap_or(1),
                },
            ),
            "cubical" => extrude::extrude_face_cubical(
                &mut m,
                face,
                o.height.unwrap_or(1.0),
                o.count.unwrap_or(1),
            ),
            "dome" => extrude::extrude_face_dome(
                &mut m,
                face,
                &DomeParams {
                    height_factor: o.height.unwrap_or(1.0),
                    rings: o.count.unwrap_or(DomeParams::default().rings),
                },
            ),
            "dodecahedral" => {
                extrude::extrude_face_dodecahedral(&mut m, face, o.height.unwrap_or(1.0))
            }
            "icosahedral" => {
                extrude::extrude_face_icosahedral(&mut m, face, o.height.unwrap_or(1.0))
            }
            "octahedral" => extrude::extrude_face_octahedral(&mut m, face, o.height.unwrap_or(1.0)),
            "stellate" => extrude::stellate_face(&mut m, face, o.distance.unwrap_or(0.0)),
            _ => extrude::double_stellate_face(&mut m, face, o.distance.unwrap_or(0.0)),
        };
        done.map_err(|e| bad(format!("face {n}: {e}")))?;
    }
    Ok(m)
}

/// The wireframe of `mesh`, or its `columns`-sided columns.
pub fn run_wireframe(mesh: &Mesh, thickness: f64, sides: Option<usize>) -> PyResult<Mesh> {
    let out = match sides {
        None => wireframe(mesh, thickness),
        Some(sides) => columns(
            mesh,
            &ColumnParams {
                sides,
                radius: thickness,
            },
        ),
    };
    match out {
        Ok(m) => Ok(m),
        Err(e) => Err(bad(Numbering::of(mesh)?.wireframe_error(mesh, &e))),
    }
}

/// The cut targets the numbers name.
fn targets(
    mesh: &Mesh,
    numbering: &Numbering,
    vertices: &[usize],
    edges: &[(usize, usize)],
    faces: &[usize],
) -> PyResult<Vec<CutTarget>> {
    let mut out = Vec::new();
    for &v in vertices {
        out.push(CutTarget::Vertex(numbering.vertex(v)?));
    }
    for &e in edges {
        out.push(CutTarget::Edge(numbering.edge(mesh, e)?));
    }
    for &f in faces {
        out.push(CutTarget::Face(numbering.face(f)?));
    }
    Ok(out)
}

/// Cuts the named vertices, edges and faces off, at `offset` model units
/// or at `fraction` of each spoke.
pub fn run_cut(
    mesh: &Mesh,
    vertices: &[usize],
    edges: &[(usize, usize)],
    faces: &[usize],
    offset: Option<f64>,
    fraction: Option<f64>,
) -> PyResult<Mesh> {
    let how = match (offset, fraction) {
        (Some(_), Some(_)) => return Err(bad("give offset or fraction, not both")),
        (Some(x), None) => CutOffset::Distance(x),
        (None, Some(t)) => CutOffset::Fraction(t),
        (None, None) => CutOffset::Fraction(0.25),
    };
    let numbering = Numbering::of(mesh)?;
    let list = targets(mesh, &numbering, vertices, edges, faces)?;
    if list.is_empty() {
        return Err(bad("no vertex, edge or face was given to cut"));
    }
    let mut m = mesh.clone();
    cut(&mut m, &list, how).map_err(|e| bad(numbering.cut_error(mesh, &e)))?;
    Ok(m)
}

/// Truncates the named vertices and edges (every vertex with an edge when
/// both are `None`) at `fraction` of each edge.
pub fn run_truncate(
    mesh: &Mesh,
    fraction: f64,
    vertices: Option<&[usize]>,
    edges: Option<&[(usize, usize)]>,
) -> PyResult<Mesh> {
    if !(fraction > 0.0 && fraction < 0.5) {
        return Err(bad(format!(
            "fraction must lie strictly between 0 and 0.5, got {fraction}"
        )));
    }
    let numbering = Numbering::of(mesh)?;
    let list = match (vertices, edges) {
        (None, None) => {
            let mut all = Vec::new();
            for v in mesh.vertices() {
                if mesh.valence(v).map_err(bad)? > 0 {
                    all.push(CutTarget::Vertex(v));
                }
            }
            all
        }
        (v, e) => targets(mesh, &numbering, v.unwrap_or(&[]), e.unwrap_or(&[]), &[])?,
    };
    if list.is_empty() {
        return Err(bad("there is nothing to truncate"));
    }
    let mut m = mesh.clone();
    cut(&mut m, &list, CutOffset::Fraction(fraction))
        .map_err(|e| bad(numbering.cut_error(mesh, &e)))?;
    Ok(m)
}
