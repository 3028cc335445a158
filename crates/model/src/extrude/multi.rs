//! Multi-face extrusion (TopMod's "extrude multiple faces"): the selected
//! faces are lifted together, so selected faces that share an edge keep
//! sharing it and walls rise only along the selection's boundary.

use std::collections::BTreeSet;

use holey_dlfl::{CornerId, DVec3, FaceId, Mesh, NonFinite, VertexId};

use super::{ExtrudeError, check_param, check_size, region};
use crate::polygon;

/// Which way the selection moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RegionDirection {
    /// Every vertex moves the same way: along the unit sum of the
    /// selected faces' vector areas (their area-weighted mean normal).
    /// Refused when that sum vanishes (a whole closed surface, say).
    #[default]
    Average,
    /// Each vertex moves along the unit sum of the unit normals of the
    /// selected faces around it (for a boundary vertex, those of its fan),
    /// so a curved selection is thickened rather than translated.
    VertexNormals,
}

impl RegionDirection {
    /// [`RegionDirection::VertexNormals`] when `vertex_normals`, else
    /// [`RegionDirection::Average`]: what a front end's on/off switch for
    /// vertex normals means.
    pub fn from_vertex_normals(vertex_normals: bool) -> RegionDirection {
        if vertex_normals {
            RegionDirection::VertexNormals
        } else {
            RegionDirection::Average
        }
    }
}

/// The parameters of [`extrude_faces`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiExtrudeParams {
    /// How far each repetition moves the selection, in model units
    /// (finite; negative pushes it in).
    pub distance: f64,
    /// Which way vertices move.
    pub direction: RegionDirection,
    /// Number of repetitions, at least 1.
    pub count: usize,
}

impl Default for MultiExtrudeParams {
    /// Distance 1 along the average normal, once.
    fn default() -> Self {
        MultiExtrudeParams {
            distance: 1.0,
            direction: RegionDirection::Average,
            count: 1,
        }
    }
}

/// What [`extrude_faces`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MultiExtruded {
    /// The selected faces in their final place, in slot order (as many as
    /// were selected; their ids may differ from the ones given).
    pub tops: Vec<FaceId>,
    /// The wall quads, `b` per repetition (`b` boundary sides).
    pub walls: Vec<FaceId>,
    /// The vertices created.
    pub vertices: Vec<VertexId>,
}

/// Extrudes the faces `faces` together, `params.count` times
/// (duplicates in `faces` are ignored).
///
/// Counts per repetition: with `b` boundary sides (edges with a selected
/// face on one side only; equivalently the fans of selected corners),
/// `+b` vertices, `+2b` edges, `+b` faces; genus unchanged. One face is
/// the plain extrusion ([`super::extrude_face`]); two quads sharing an
/// edge have `b = 6`: +6/+12/+6, where extruding them one by one would
/// add 8/16/8.
///
/// Refused, with the mesh unchanged: no faces, a stale id, a hole, a
/// point-sphere, a face with a self-loop, a non-finite distance, a count
/// of 0, or no direction (see [`RegionDirection`]); a repetition after
/// the first that is refused (its own faces, made by the earlier ones, are
/// what it found wrong) gives [`ExtrudeError::Repeated`] and the mesh as
/// it was before the first.
pub fn extrude_faces(
    mesh: &mut Mesh,
    faces: &[FaceId],
    params: &MultiExtrudeParams,
) -> Result<MultiExtruded, ExtrudeError> {
    check_param("distance", params.distance, "finite", |_| true)?;
    check_param("count", params.count as f64, "at least 1", |_| {
        params.count >= 1
    })?;
    if faces.is_empty() {
        return Err(ExtrudeError::EmptySelection);
    }
    let unique: Vec<FaceId> = faces
        .iter()
        .copied()
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let plan = plan_once(mesh, &unique, params)?;
    let corners: u64 = plan.fans.len() as u64 * 5 + unique.len() as u64;
    check_size(corners * params.count as u64)?;
    // A later repetition can be refused (moving along vertex normals
    // reshapes the selection so it may find no direction; a long distance
    // reaches non-finite coordinates): keep a copy to put back, so a
    // refusal leaves the mesh as it was (the copy has the same slots and
    // generations, so every handle stays good).
    let backup = (params.count > 1).then(|| mesh.clone());
    let mut walls = Vec::new();
    let mut vertices = Vec::new();
    let mut tops = unique;
    for k in 0..params.count {
        let step = if k == 0 {
            region::apply(mesh, &plan)
        } else {
            plan_once(mesh, &tops, params).and_then(|p| region::apply(mesh, &p))
        };
        let made = match step {
            Ok(made) => made,
            Err(e) => {
                if let Some(b) = backup {
                    *mesh = b;
                }
                return Err(if k == 0 {
                    e
                } else {
                    ExtrudeError::Repeated {
                        step: k + 1,
                        count: params.count,
                        cause: Box::new(e),
                    }
                });
            }
        };
        walls.extend(made.walls);
        vertices.extend(made.fan_vertices);
        tops = made.tops;
    }
    Ok(MultiExtruded {
        tops,
        walls,
        vertices,
    })
}

/// Plans one repetition, with targets from `params`.
fn plan_once(
    mesh: &Mesh,
    faces: &[FaceId],
    params: &MultiExtrudeParams,
) -> Result<region::RegionPlan, ExtrudeError> {
    let average = match params.direction {
        RegionDirection::Average => Some(average_normal(mesh, faces)?),
        RegionDirection::VertexNormals => None,
    };
    let selected: BTreeSet<FaceId> = faces.iter().copied().collect();
    let target = |v: VertexId, corners: &[CornerId]| -> Result<DVec3, ExtrudeError> {
        let dir = match average {
            Some(n) => n,
            None => fan_normal(mesh, v, corners, &selected)?,
        };
        let p = mesh.position(v)? + dir * params.distance;
        if p.is_finite() {
            Ok(p)
        } else {
            Err(non_finite_lift(mesh, corners, &selected, p)?)
        }
    };
    region::plan(mesh, faces, &target)
}

/// The refusal for a lifted vertex at the non-finite `p`: named as the
/// lift of its corner in the first selected face of its fan `corners`.
fn non_finite_lift(
    mesh: &Mesh,
    corners: &[CornerId],
    selected: &BTreeSet<FaceId>,
    p: DVec3,
) -> Result<ExtrudeError, ExtrudeError> {
    for &c in corners {
        let face = mesh.corner_face(c)?;
        if selected.contains(&face) {
            let index = mesh.face_corners(face)?.position(|o| o == c).unwrap_or(0);
            return Ok(ExtrudeError::NonFinite {
                face,
                point: NonFinite::new("the lift of corner", index, p),
            });
        }
    }
    // Every fan holds a selected corner; were it not so, the point is
    // named by its position alone, at the face of its first corner.
    let &c = corners.first().ok_or(ExtrudeError::EmptySelection)?;
    Ok(ExtrudeError::NonFinite {
        face: mesh.corner_face(c)?,
        point: NonFinite::position(p),
    })
}

/// The unit sum of the selected faces' vector areas.
fn average_normal(mesh: &Mesh, faces: &[FaceId]) -> Result<DVec3, ExtrudeError> {
    let mut sum = DVec3::ZERO;
    let mut scale = 0.0f64;
    for &f in faces {
        let pts = mesh.face_positions(f)?;
        sum += polygon::newell(&pts);
        scale = scale.max(polygon::mean_edge(&pts));
    }
    let len = sum.length();
    if len.is_finite() && len > 1e-12 * scale * scale && len > 0.0 {
        Ok(sum / len)
    } else {
        Err(ExtrudeError::NoDirection {
            at: "the selection".to_owned(),
        })
    }
}

/// The unit sum of the unit normals of the selected faces among `corners`.
fn fan_normal(
    mesh: &Mesh,
    v: VertexId,
    corners: &[CornerId],
    selected: &BTreeSet<FaceId>,
) -> Result<DVec3, ExtrudeError> {
    let mut sum = DVec3::ZERO;
    for &c in corners {
        let f = mesh.corner_face(c)?;
        if !selected.contains(&f) {
            continue;
        }
        if let Some(frame) = polygon::frame(&mesh.face_positions(f)?) {
            sum += frame.normal;
        }
    }
    let len = sum.length();
    if len > 1e-9 && len.is_finite() {
        Ok(sum / len)
    } else {
        Err(ExtrudeError::NoDirection {
            at: format!("vertex {v}"),
        })
    }
}
