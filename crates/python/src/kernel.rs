//! `holey.Mesh`: the doubly linked face list of Srinivasan's thesis and
//! its high-genus tools. Every operator returns a new mesh and leaves
//! this one as it was, so a Python value never changes under the caller.
//!
//! Faces are numbered as [`Mesh::to_arrays`] lists them (the non-hole
//! faces in slot order; for a mesh made by `from_polygons`, the order of
//! the polygons given), and a face's corners from the corner its list
//! starts at.

use std::path::Path;

use holey::dlfl::convert::{ImportOptions, to_dlfl, to_poly};
use holey::dlfl::{CornerId, FaceId, dlfl_info};
use holey::model::extrude::{ExtrudeOptions, RegionDirection};
use holey::model::handle::{HandleCurve, HandleParams, MultiHandleParams, create_handle};
use holey::model::menger::{MengerParams, Thickness, menger};
use holey::model::rind::{PunchOutcome, Rind};
use holey::model::sierpinski::sierpinski;
use pyo3::prelude::*;

use crate::arrays::poly_mesh;
use crate::errors::{bad, io};
use crate::files::{PolyArrays, kernel_of_raw, poly_arrays};
use crate::toolbox;

/// A DLFL mesh: every vertex, edge, face and corner of an orientable
/// 2-manifold with boundary (holes are faces too), and the thesis's
/// operators on it.
#[pyclass(module = "holey._holey", name = "Mesh", frozen)]
#[derive(Clone)]
pub struct Mesh {
    mesh: holey::dlfl::Mesh,
}

impl Mesh {
    fn wrap(mesh: holey::dlfl::Mesh) -> Mesh {
        Mesh { mesh }
    }

    /// The face numbered `index` as `to_arrays` lists the faces.
    fn face(&self, index: usize) -> PyResult<FaceId> {
        let faces = to_poly(&self.mesh).faces;
        faces.get(index).copied().ok_or_else(|| {
            bad(format!(
                "face {index} does not exist: the mesh has {} faces",
                faces.len()
            ))
        })
    }

    /// Corner `corner` of face `face`.
    fn corner(&self, face: usize, corner: usize) -> PyResult<CornerId> {
        let f = self.face(face)?;
        let corners: Vec<CornerId> = self.mesh.face_corners(f).map_err(bad)?.collect();
        corners.get(corner).copied().ok_or_else(|| {
            bad(format!(
                "face {face} has {} corners; there is no corner {corner}",
                corners.len()
            ))
        })
    }
}

#[pymethods]
impl Mesh {
    /// A built-in primitive, as `holey primitive` names it (`@cube:3`).
    #[staticmethod]
    fn primitive(spec: &str) -> PyResult<Mesh> {
        let soup = holey::shapes::parse_primitive(spec).map_err(|e| bad(format!("{spec}: {e}")))?;
        Mesh::from_soup(&soup, spec)
    }

    /// The mesh of polygons given as positions, flat indices and offsets.
    #[staticmethod]
    fn from_arrays(v: &[u8], flat: &[u8], offsets: &[u8]) -> PyResult<Mesh> {
        Mesh::from_soup(&poly_mesh(v, flat, offsets, "polygons")?, "polygons")
    }

    /// Reads a mesh file (a `.dlfl` file as the DLFL it stores).
    #[staticmethod]
    fn read(path: &str) -> PyResult<Mesh> {
        match holey::io::read_path(Path::new(path)).map_err(io)? {
            holey::io::MeshFile::Poly(soup) => Mesh::from_soup(&soup, path),
            holey::io::MeshFile::Dlfl(raw) => Ok(Mesh::wrap(kernel_of_raw(raw, path)?)),
        }
    }

    /// Writes the mesh atomically, its format from the extension.
    fn write(&self, path: &str) -> PyResult<()> {
        let target = Path::new(path);
        if holey::io::Format::from_path(target).map_err(io)? == holey::io::Format::Dlfl {
            return holey::io::write_dlfl(target, &self.mesh.to_raw()).map_err(io);
        }
        holey::io::write_poly(target, &to_poly(&self.mesh).poly, &Default::default()).map_err(io)
    }

    /// The non-hole faces as positions, flat indices and offsets.
    fn to_arrays<'py>(&self, py: Python<'py>) -> PolyArrays<'py> {
        poly_arrays(py, &to_poly(&self.mesh).poly)
    }

    /// The measurements `holey info --json` prints for a `.dlfl` file.
    fn info(&self) -> PyResult<String> {
        serde_json::to_string(&dlfl_info(&self.mesh)).map_err(bad)
    }

    /// The Sierpinski polyhedron of `iterations` levels (thesis ch. VI).
    fn sierpinski(&self, py: Python<'_>, iterations: usize) -> PyResult<Mesh> {
        let mut m = self.mesh.clone();
        py.detach(|| sierpinski(&mut m, iterations)).map_err(bad)?;
        Ok(Mesh::wrap(m))
    }

    /// The Menger sponge of `iterations` levels (thesis ch. VII): `exact`
    /// for the true sponge of a parallelepiped; the wall thickness is
    /// `thickness` in model units, or else `ratio` times the mean edge.
    #[pyo3(signature = (iterations, *, exact=false, thickness=None, ratio=None, collapse_angle=90.0))]
    fn menger(
        &self,
        py: Python<'_>,
        iterations: usize,
        exact: bool,
        thickness: Option<f64>,
        ratio: Option<f64>,
        collapse_angle: f64,
    ) -> PyResult<Mesh> {
        let thickness = match (thickness, ratio) {
            (Some(_), Some(_)) => return Err(bad("give thickness or ratio, not both")),
            (Some(d), None) => Thickness::Absolute(d),
            (None, Some(r)) => Thickness::RatioOfMeanEdge(r),
            (None, None) => MengerParams::default().thickness,
        };
        let params = MengerParams {
            iterations,
            thickness,
            collapse_angle_deg: collapse_angle,
            exact,
        };
        let mut m = self.mesh.clone();
        py.detach(|| menger(&mut m, &params)).map_err(bad)?;
        Ok(Mesh::wrap(m))
    }

    /// `levels` of Catmull–Clark (`catmull-clark`) or Doo–Sabin
    /// (`doo-sabin`) subdivision.
    fn subdivide(&self, py: Python<'_>, scheme: &str, levels: usize) -> PyResult<Mesh> {
        let run = match scheme {
            "catmull-clark" => holey::subdiv::catmull_clark,
            "doo-sabin" => holey::subdiv::doo_sabin,
            other => {
                return Err(bad(format!(
                    "scheme {other:?} is not known: use \"catmull-clark\" or \"doo-sabin\""
                )));
            }
        };
        py.detach(|| run(&self.mesh, levels))
            .map(Mesh::wrap)
            .map_err(bad)
    }

    /// A handle of `segments` segments from corner `corners[0]` of face
    /// `faces[0]` to corner `corners[1]` of face `faces[1]` along a
    /// Hermite curve (thesis ch. IV) or TopMod's cubic Bézier (`curve`)
    /// with weights `w1`, `w2`; negative weights make a tunnel through
    /// the mesh.
    #[pyo3(signature = (faces, corners=(0, 0), *, segments=4, w1=1.0, w2=1.0, curve="hermite"))]
    fn handle(
        &self,
        faces: (usize, usize),
        corners: (usize, usize),
        segments: usize,
        w1: f64,
        w2: f64,
        curve: &str,
    ) -> PyResult<Mesh> {
        let curve: HandleCurve = curve.parse().map_err(bad)?;
        let a = self.corner(faces.0, corners.0)?;
        let b = self.corner(faces.1, corners.1)?;
        let mut m = self.mesh.clone();
        let params = HandleParams::new(segments, w1, w2).with_curve(curve);
        create_handle(&mut m, a, b, &params).map_err(bad)?;
        Ok(Mesh::wrap(m))
    }

    /// Joins the faces numbered `faces` (four or more) through a hub, one
    /// handle of `segments` segments from each (`holey handle --faces`):
    /// the hub's centre is a point every face sees from outside; faces
    /// with none, a blocked view, or handles that would cross anything are
    /// refused naming the faces.
    #[pyo3(signature = (faces, *, segments=4, w1=1.0, w2=1.0, curve="hermite", hub_scale=0.5))]
    #[allow(clippy::too_many_arguments)]
    fn multi_face_handle(
        &self,
        py: Python<'_>,
        faces: Vec<usize>,
        segments: usize,
        w1: f64,
        w2: f64,
        curve: &str,
        hub_scale: f64,
    ) -> PyResult<Mesh> {
        let curve: HandleCurve = curve.parse().map_err(bad)?;
        let handle = HandleParams::new(segments, w1, w2).with_curve(curve);
        let params = MultiHandleParams::new(handle, hub_scale);
        py.detach(|| toolbox::run_multi_face_handle(&self.mesh, &faces, &params))
            .map(Mesh::wrap)
    }

    /// A rind of `thickness` (thesis ch. V): the outer faces made from
    /// faces `punch` get a pipe to their inner copies, those of `peel`
    /// also lose the thin walls between neighbouring holes. Returns the
    /// new mesh and a note for each face that could not be punched.
    #[pyo3(signature = (thickness, *, punch=Vec::new(), peel=Vec::new()))]
    fn rind(
        &self,
        thickness: f64,
        punch: Vec<usize>,
        peel: Vec<usize>,
    ) -> PyResult<(Mesh, Vec<String>)> {
        let slot = |i: usize| self.face(i).map(|f| f.index());
        let punch: Vec<usize> = punch.into_iter().map(slot).collect::<PyResult<_>>()?;
        let peel: Vec<usize> = peel.into_iter().map(slot).collect::<PyResult<_>>()?;
        let mut rind = Rind::from_mesh(&self.mesh, thickness).map_err(bad)?;
        let mut notes = Vec::new();
        for (list, peeling) in [(&punch, false), (&peel, true)] {
            let outcomes = if peeling {
                rind.peel_indices(list)
            } else {
                rind.punch_indices(list)
            }
            .map_err(bad)?;
            for (slot, outcome) in list.iter().zip(outcomes) {
                if let PunchOutcome::NotPunchable { reason } = outcome {
                    let verb = if peeling { "peeled" } else { "punched" };
                    notes.push(format!("the face in slot {slot} was not {verb}: {reason}"));
                }
            }
        }
        Ok((Mesh::wrap(rind.into_mesh()), notes))
    }

    /// `levels` levels of one of TopMod's remeshing schemes (`holey
    /// remesh`), with its options as (name, value) pairs.
    #[pyo3(signature = (scheme, levels=1, *, options=Vec::new(), triangles=false))]
    fn remesh(
        &self,
        py: Python<'_>,
        scheme: &str,
        levels: usize,
        options: Vec<(String, f64)>,
        triangles: bool,
    ) -> PyResult<Mesh> {
        py.detach(|| toolbox::run_remesh(&self.mesh, scheme, levels, &options, triangles))
            .map(Mesh::wrap)
    }

    /// Extrudes the faces numbered `faces` (`holey extrude`).
    #[pyo3(signature = (faces, *, kind="plain", distance=None, scale=None, rotation=None, twist=None, height=None, count=None, together=false, vertex_normals=false))]
    #[allow(clippy::too_many_arguments)]
    fn extrude(
        &self,
        faces: Vec<usize>,
        kind: &str,
        distance: Option<f64>,
        scale: Option<f64>,
        rotation: Option<f64>,
        twist: Option<f64>,
        height: Option<f64>,
        count: Option<usize>,
        together: bool,
        vertex_normals: bool,
    ) -> PyResult<Mesh> {
        let options = ExtrudeOptions {
            distance,
            scale,
            rotation_deg: rotation,
            twist,
            height,
            count,
            together: together.then_some(RegionDirection::from_vertex_normals(vertex_normals)),
        };
        toolbox::run_extrude(&self.mesh, &faces, kind, &options).map(Mesh::wrap)
    }

    /// The wireframe of the mesh with tubes `thickness` wide, or columns
    /// of `columns` sides and radius `thickness` (`holey wireframe`).
    #[pyo3(signature = (thickness, *, columns=None))]
    fn wireframe(&self, py: Python<'_>, thickness: f64, columns: Option<usize>) -> PyResult<Mesh> {
        py.detach(|| toolbox::run_wireframe(&self.mesh, thickness, columns))
            .map(Mesh::wrap)
    }

    /// Cuts the vertices, edges (vertex pairs) and faces off (`holey cut`).
    /// `vertex_offset` or `vertex_fraction` cut the vertices at an offset
    /// of their own (TopMod's cut by edge-vertex).
    #[pyo3(signature = (*, vertices=Vec::new(), edges=Vec::new(), faces=Vec::new(), offset=None, fraction=None, vertex_offset=None, vertex_fraction=None))]
    #[allow(clippy::too_many_arguments)]
    fn cut(
        &self,
        vertices: Vec<usize>,
        edges: Vec<(usize, usize)>,
        faces: Vec<usize>,
        offset: Option<f64>,
        fraction: Option<f64>,
        vertex_offset: Option<f64>,
        vertex_fraction: Option<f64>,
    ) -> PyResult<Mesh> {
        let targets = toolbox::CutTargets {
            vertices: &vertices,
            edges: &edges,
            faces: &faces,
        };
        let how = toolbox::cut_offset(offset, fraction, "")?;
        let vertex_how = match (vertex_offset, vertex_fraction) {
            (None, None) => how,
            _ => toolbox::cut_offset(vertex_offset, vertex_fraction, "vertex_")?,
        };
        toolbox::run_cut(&self.mesh, &targets, how, vertex_how).map(Mesh::wrap)
    }

    /// Truncates the vertices and edges named (every vertex when neither
    /// is given) at `fraction` of each edge (`holey truncate`).
    #[pyo3(signature = (fraction, *, vertices=None, edges=None))]
    fn truncate(
        &self,
        fraction: f64,
        vertices: Option<Vec<usize>>,
        edges: Option<Vec<(usize, usize)>>,
    ) -> PyResult<Mesh> {
        toolbox::run_truncate(&self.mesh, fraction, vertices.as_deref(), edges.as_deref())
            .map(Mesh::wrap)
    }

    /// The convex hull of the mesh's vertices (`holey hull`).
    fn convex_hull(&self, py: Python<'_>) -> PyResult<Mesh> {
        py.detach(|| holey::model::hull::convex_hull(&self.mesh))
            .map(Mesh::wrap)
            .map_err(bad)
    }

    /// TopMod's dual convex hull of the mesh's vertices (`holey hull
    /// --dual`).
    fn dual_convex_hull(&self, py: Python<'_>) -> PyResult<Mesh> {
        py.detach(|| holey::model::hull::dual_convex_hull(&self.mesh))
            .map(Mesh::wrap)
            .map_err(bad)
    }

    /// Checks every invariant of the DLFL (for tests).
    fn validate(&self) -> PyResult<()> {
        self.mesh.validate().map_err(bad)
    }

    fn __repr__(&self) -> String {
        format!(
            "holey.Mesh(vertices={}, edges={}, faces={}, genus={})",
            self.mesh.vertex_count(),
            self.mesh.edge_count(),
            self.mesh.face_count(),
            self.mesh.genus()
        )
    }
}

impl Mesh {
    fn from_soup(soup: &holey::mesh::PolyMesh, what: &str) -> PyResult<Mesh> {
        let imported =
            to_dlfl(soup, ImportOptions::default()).map_err(|e| bad(format!("{what}: {e}")))?;
        Ok(Mesh::wrap(imported.mesh))
    }
}
