//! TopMod's toolbox for `holey.Mesh` (issue 18): remeshing schemes,
//! extrusions, wireframes and columns, cuts and truncations, multi-face
//! handles. Each function
//! takes the mesh and returns a new one; `kernel.rs` exposes them as
//! methods. Faces and vertices are numbered as `Mesh.to_arrays` lists
//! them; an edge is named by its two vertices.

use holey::dlfl::{FaceId, Mesh};
use holey::model::cut::{CutOffset, CutTarget, cut, cut_each, offsets_by_kind};
use holey::model::extrude::{ExtrudeError, ExtrudeKind, ExtrudeOptions, extrude_selection};
use holey::model::handle::{MultiHandleParams, create_multi_face_handle};
use holey::model::numbering::{EdgeSpec, Numbering};
use holey::model::wireframe::{ColumnParams, columns, wireframe};
use holey::subdiv::{RemeshParams, RemeshScheme, SubdivError, remesh};
use pyo3::PyResult;

use crate::errors::bad;

/// The faces and vertices of `mesh` as `to_arrays` numbers them.
fn numbering(mesh: &Mesh) -> PyResult<Numbering> {
    Numbering::of_arrays(mesh).map_err(bad)
}

/// Edges given as pairs of vertex numbers.
fn edge_specs(edges: &[(usize, usize)]) -> Vec<EdgeSpec> {
    edges
        .iter()
        .map(|&(a, b)| EdgeSpec::Vertices(a, b))
        .collect()
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

/// An option refusal in the words of `Mesh.extrude`'s keywords; `None`
/// for any other refusal.
fn keyword_refusal(e: &ExtrudeError) -> Option<String> {
    Some(match e {
        ExtrudeError::TogetherNotPlain(kind) => {
            format!(
                "together=True extrudes plainly; it does not take kind {:?}",
                kind.name()
            )
        }
        ExtrudeError::UnreadTogether { option } => {
            format!("option {:?} does not apply to together=True", option.name())
        }
        ExtrudeError::Unread { option, kind } => format!(
            "option {:?} does not apply to kind {:?}",
            option.name(),
            kind.name()
        ),
        _ => return None,
    })
}

/// Extrudes the faces numbered `faces` by the kind named `kind`, one by
/// one or together.
pub fn run_extrude(
    mesh: &Mesh,
    faces: &[usize],
    kind: &str,
    options: &ExtrudeOptions,
) -> PyResult<Mesh> {
    let kind: ExtrudeKind = kind.parse().map_err(bad)?;
    options
        .check(kind)
        .map_err(|e| bad(keyword_refusal(&e).unwrap_or_else(|| e.to_string())))?;
    if faces.is_empty() {
        return Err(bad("no faces were given to extrude"));
    }
    let numbering = numbering(mesh)?;
    let ids: Vec<FaceId> = numbering
        .faces(faces)
        .map_err(bad)?
        .into_iter()
        .map(|(_, f)| f)
        .collect();
    let mut m = mesh.clone();
    extrude_selection(&mut m, &ids, kind, options)
        .map_err(|e| bad(numbering.describe_extrude(&m, &e)))?;
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
        Err(e) => Err(bad(numbering(mesh)?.describe_wireframe(mesh, &e))),
    }
}

/// The vertices, edges (vertex pairs) and faces named to cut.
pub struct CutTargets<'a> {
    pub vertices: &'a [usize],
    pub edges: &'a [(usize, usize)],
    pub faces: &'a [usize],
}

/// `offset` model units or `fraction` of each spoke (a quarter by
/// default); `prefix` names the keywords in the refusal.
pub fn cut_offset(offset: Option<f64>, fraction: Option<f64>, prefix: &str) -> PyResult<CutOffset> {
    Ok(match (offset, fraction) {
        (Some(_), Some(_)) => {
            return Err(bad(format!(
                "give {prefix}offset or {prefix}fraction, not both"
            )));
        }
        (Some(x), None) => CutOffset::Distance(x),
        (None, Some(t)) => CutOffset::Fraction(t),
        (None, None) => CutOffset::Fraction(0.25),
    })
}

/// Cuts the named vertices, edges and faces off, the vertices at `vertex`
/// and the others at `how`.
pub fn run_cut(
    mesh: &Mesh,
    targets: &CutTargets<'_>,
    how: CutOffset,
    vertex: CutOffset,
) -> PyResult<Mesh> {
    let numbering = numbering(mesh)?;
    let list = numbering
        .cut_targets(
            mesh,
            targets.vertices,
            &edge_specs(targets.edges),
            targets.faces,
        )
        .map_err(bad)?;
    if list.is_empty() {
        return Err(bad("no vertex, edge or face was given to cut"));
    }
    let each = offsets_by_kind(list, vertex, how);
    let mut m = mesh.clone();
    cut_each(&mut m, &each).map_err(|e| bad(numbering.describe_cut(mesh, &e)))?;
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
    let numbering = numbering(mesh)?;
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
        (v, e) => numbering
            .cut_targets(mesh, v.unwrap_or(&[]), &edge_specs(e.unwrap_or(&[])), &[])
            .map_err(bad)?,
    };
    if list.is_empty() {
        return Err(bad("there is nothing to truncate"));
    }
    let mut m = mesh.clone();
    cut(&mut m, &list, CutOffset::Fraction(fraction))
        .map_err(|e| bad(numbering.describe_cut(mesh, &e)))?;
    Ok(m)
}

/// Joins the faces numbered `faces` through a hub (a multi-face handle),
/// refusals naming the faces in the same numbers.
pub fn run_multi_face_handle(
    mesh: &Mesh,
    faces: &[usize],
    params: &MultiHandleParams,
) -> PyResult<Mesh> {
    let numbering = numbering(mesh)?;
    // One by one, not `Numbering::faces`, which drops repeats: a face
    // given twice is the library's refusal to name.
    let ids: Vec<FaceId> = faces
        .iter()
        .map(|&n| numbering.face(n).map_err(bad))
        .collect::<PyResult<_>>()?;
    let mut m = mesh.clone();
    create_multi_face_handle(&mut m, &ids, params)
        .map_err(|e| bad(numbering.describe_multi_handle(mesh, &e)))?;
    Ok(m)
}
