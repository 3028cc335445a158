//! Dome extrusion (TopMod's `extrudeFaceDome`): rings of quads that close
//! over the face like a cap, finished by a stellation at the apex.
//!
//! TopMod builds its dome from five Doo–Sabin extrusions of fixed heights
//! and scales; here the rings lie on the cap explicitly: ring `j` of `k`
//! is the face scaled by `cos θ_j` about its centroid and lifted by
//! `h·sin θ_j`, with `θ_j = j·π/(2(k + 1))`, and the apex is the centroid
//! lifted by `h`. The topology is the same (rings of quads, then a cone).

use holey_dlfl::{DVec3, FaceId, Mesh};

use super::plain::extrude_rings;
use super::stellate::stellate_at;
use super::{ExtrudeError, Extruded, base_face, check_param, check_rings, check_size};

/// The parameters of [`extrude_face_dome`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DomeParams {
    /// The height of the apex over the face, as a multiple of the face's
    /// mean circumradius (finite and positive; 1 is a half sphere over a
    /// regular polygon).
    pub height_factor: f64,
    /// Rings of quads below the apex (at least 1).
    pub rings: usize,
}

impl Default for DomeParams {
    /// A half sphere of five rings, as TopMod's.
    fn default() -> Self {
        DomeParams {
            height_factor: 1.0,
            rings: 5,
        }
    }
}

/// Dome extrusion of `face` (see the module documentation).
///
/// Counts: a `d`-gon with `k` rings adds `kd + 1` vertices, `2kd + d`
/// edges and `kd + d − 1` faces (`kd` quads and `d` triangles in place
/// of the face). A square with 5 rings on a cube: 8/12/6 → 29/56/29.
pub fn extrude_face_dome(
    mesh: &mut Mesh,
    face: FaceId,
    params: &DomeParams,
) -> Result<Extruded, ExtrudeError> {
    check_param(
        "height_factor",
        params.height_factor,
        "finite and greater than 0",
        |h| h > 0.0,
    )?;
    check_param("rings", params.rings as f64, "at least 1", |_| {
        params.rings >= 1
    })?;
    let (corners, points, frame) = base_face(mesh, face)?;
    check_size(
        (params.rings as u64)
            .saturating_mul(5)
            .saturating_add(3)
            .saturating_mul(corners.len() as u64),
    )?;
    let (c, n) = (frame.centroid, frame.normal);
    let h = params.height_factor * frame.radius;
    let k = params.rings;
    let rings: Vec<Vec<DVec3>> = (1..=k)
        .map(|j| {
            let theta = j as f64 * std::f64::consts::FRAC_PI_2 / (k + 1) as f64;
            points
                .iter()
                .map(|&p| c + (p - c) * theta.cos() + n * (h * theta.sin()))
                .collect()
        })
        .collect();
    let apex = [c + n * h];
    let mut new_points: Vec<&[DVec3]> = rings.iter().map(Vec::as_slice).collect();
    new_points.push(&apex);
    check_rings(face, &new_points)?;
    let body = extrude_rings(mesh, face, corners[0], &rings)?;
    let cone = stellate_at(mesh, body.top, body.top_start, apex[0])?;
    let mut vertices = body.vertices;
    vertices.extend(cone.vertices);
    Extruded::around(mesh, cone.top, cone.top_start, vertices)
}
