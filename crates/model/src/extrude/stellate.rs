//! Stellation (TopMod's `stellateFace`): the face becomes a cone of
//! triangles over a new apex.

use holey_dlfl::{CornerId, DVec3, FaceId, Mesh};

use super::{ExtrudeError, Extruded, base_face, check_param, check_points};

/// Replaces `face` by a cone: a new vertex at the centroid moved `height`
/// along the unit normal (negative: inwards), joined to every corner.
///
/// Counts: a `d`-gon gives `d` triangles: +1 vertex, +`d` edges,
/// +`d − 1` faces. `top` in the result is the triangle on the base's
/// first edge, and `top_start` the apex's corner in it.
pub fn stellate_face(mesh: &mut Mesh, face: FaceId, height: f64) -> Result<Extruded, ExtrudeError> {
    check_param("height", height, "finite", |_| true)?;
    let (corners, _, frame) = base_face(mesh, face)?;
    let apex = frame.centroid + frame.normal * height;
    check_points(face, 0, &[apex])?;
    stellate_at(mesh, face, corners[0], apex)
}

/// Stellates a face that has passed [`super::base_face`], with the apex
/// at `apex`, starting the fan at corner `start`.
pub(crate) fn stellate_at(
    mesh: &mut Mesh,
    face: FaceId,
    start: CornerId,
    apex: DVec3,
) -> Result<Extruded, ExtrudeError> {
    let ring: Vec<CornerId> = mesh.face_corners_from(start)?.collect();
    let (v, _, sigma) = mesh.create_vertex(apex)?;
    // The apex hangs inside the face on an edge to the first corner; the
    // walk reads σ → c_0 → c_1 → … and each cut takes the triangle
    // (apex, c_i, c_(i+1)) off the front, the apex's corner in the rest
    // being the one just before c_(i+1).
    mesh.insert_edge(ring[0], sigma)?;
    let mut at_apex = sigma;
    let mut first = None;
    for &next in ring.iter().skip(1) {
        let e = mesh.insert_edge(next, at_apex)?;
        if first.is_none() {
            first = Some(mesh.corner_face(mesh.edge_corners(e)?[0])?);
        }
        at_apex = mesh.corner_prev(next)?;
    }
    let top = match first {
        Some(f) => f,
        None => mesh.corner_face(sigma)?,
    };
    let top_start = mesh
        .face_corners(top)?
        .find(|&c| mesh.corner_vertex(c).is_ok_and(|w| w == v))
        .ok_or(ExtrudeError::DegenerateFace(face))?;
    Extruded::around(mesh, top, top_start, vec![v])
}
