//! Double stellation (TopMod's `doubleStellateFace`): a flat stellation,
//! a flat stellation of each of its triangles, then the first apex lifted
//! along the face normal.

use holey_dlfl::{FaceId, Mesh};

use super::stellate::stellate_at;
use super::{ExtrudeError, Extruded, base_face, check_param, check_points};
use crate::polygon;

/// Double stellation of `face`: the centroid `a` becomes a vertex joined
/// to every corner; each of the `d` triangles gets a vertex at its
/// centroid joined to its three corners; then `a` moves `height` along
/// the unit normal (negative: inwards).
///
/// Counts: a `d`-gon adds `d + 1` vertices, `4d` edges and `3d − 1`
/// faces (`3d` triangles in place of the face). A square of a cube:
/// 8/12/6 → 13/28/17.
pub fn double_stellate_face(
    mesh: &mut Mesh,
    face: FaceId,
    height: f64,
) -> Result<Extruded, ExtrudeError> {
    check_param("height", height, "finite", |_| true)?;
    let (corners, _, frame) = base_face(mesh, face)?;
    let lifted = frame.centroid + frame.normal * height;
    check_points(face, 0, &[lifted])?;
    let first = stellate_at(mesh, face, corners[0], frame.centroid)?;
    let apex = first.vertices[0];
    let mut triangles = vec![first.top];
    triangles.extend(first.sides.iter().copied());
    let mut vertices = first.vertices.clone();
    for t in triangles {
        let points = mesh.face_positions(t)?;
        let start = mesh.face_corner(t)?;
        let made = stellate_at(mesh, t, start, polygon::centroid(&points))?;
        vertices.extend(made.vertices);
    }
    mesh.set_position(apex, lifted)?;
    let top = mesh.corner_face(mesh.vertex_corners(apex)?.next().ok_or_else(|| {
        ExtrudeError::Kernel(holey_dlfl::Error::Invalid(
            "internal: the apex of a double stellation has no corner".to_owned(),
        ))
    })?)?;
    let top_start = mesh
        .face_corners(top)?
        .find(|&c| mesh.corner_vertex(c).is_ok_and(|v| v == apex))
        .ok_or(ExtrudeError::DegenerateFace(face))?;
    Extruded::around(mesh, top, top_start, vertices)
}
