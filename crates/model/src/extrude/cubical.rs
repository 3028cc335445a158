//! Cubical extrusion (TopMod's "cubical" mode): the plain extrusion with
//! the height of a cube, so that a square face grows a cube per
//! repetition.

use holey_dlfl::{FaceId, Mesh};

use super::{ExtrudeError, ExtrudeParams, Extruded, extrude_face, solid_base};

/// Extrudes `face` `count` times, each time by `height_factor` times the
/// face's mean edge length (1 makes a square face grow cubes), without
/// turning or scaling.
///
/// Counts as [`extrude_face`]: `k` repetitions of a `d`-gon add `kd`
/// vertices, `2kd` edges and `kd` faces. Refused as [`extrude_face`],
/// and for a `height_factor` that is not finite and positive.
pub fn extrude_face_cubical(
    mesh: &mut Mesh,
    face: FaceId,
    height_factor: f64,
    count: usize,
) -> Result<Extruded, ExtrudeError> {
    let (_, _, frame) = solid_base(mesh, face, height_factor)?;
    let params = ExtrudeParams::new(frame.edge * height_factor, count);
    extrude_face(mesh, face, &params)
}
