//! Plain face extrusion (TopMod's `extrudeFace`): the face is lifted
//! along its normal, turned and scaled, and joined to where it was by a
//! ring of quadrilaterals; repeated, each repetition extrudes the
//! previous top.

use holey_dlfl::{CornerId, DVec3, FaceId, Mesh};

use super::{ExtrudeError, Extruded, base_face, check_param, check_points, check_size, region};
use crate::polygon::{self, Frame};

/// The parameters of [`extrude_face`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExtrudeParams {
    /// How far each repetition moves the face along its unit normal, in
    /// model units; negative pushes it in. Any finite value (0 makes
    /// zero-height walls, as an inset with `scale` does).
    pub distance: f64,
    /// How far each repetition turns the face about its normal through
    /// its centroid, in degrees, counter-clockwise seen from outside.
    pub rotation_deg: f64,
    /// The size of each new face relative to the one before, about its
    /// centroid; finite and positive.
    pub scale: f64,
    /// Number of repetitions, at least 1; each adds one ring of quads.
    pub count: usize,
}

impl Default for ExtrudeParams {
    /// Distance 1, no turn, scale 1, once.
    fn default() -> Self {
        ExtrudeParams {
            distance: 1.0,
            rotation_deg: 0.0,
            scale: 1.0,
            count: 1,
        }
    }
}

impl ExtrudeParams {
    /// `count` repetitions of distance `distance`, no turn, scale 1.
    pub fn new(distance: f64, count: usize) -> Self {
        ExtrudeParams {
            distance,
            count,
            ..Self::default()
        }
    }

    pub(crate) fn check(&self) -> Result<(), ExtrudeError> {
        check_repeat_params(
            self.distance,
            ("rotation_deg", self.rotation_deg),
            self.scale,
            self.count,
        )
    }
}

/// Checks the parameters of a repeated extrusion (plain or Doo–Sabin), in
/// this order: a finite `distance`, a finite turn (`turn` is its name and
/// value), a finite `scale` greater than 0 and a `count` of at least 1.
pub(crate) fn check_repeat_params(
    distance: f64,
    (turn_name, turn): (&'static str, f64),
    scale: f64,
    count: usize,
) -> Result<(), ExtrudeError> {
    check_param("distance", distance, "finite", |_| true)?;
    check_param(turn_name, turn, "finite", |_| true)?;
    check_param("scale", scale, "finite and greater than 0", |s| s > 0.0)?;
    check_param("count", count as f64, "at least 1", |_| count >= 1)
}

/// Extrudes `face` `params.count` times (TopMod's cubical extrusion with
/// distance, rotation, scale and repetitions).
///
/// Counts: a `d`-gon extruded `k` times adds `kd` vertices, `2kd` edges
/// and `kd` faces (each repetition a ring of `d` quadrilaterals, the top
/// replacing the face); genus unchanged. A quad extruded once: 4/8/4.
///
/// The new faces are oriented like `face`; the walls face outwards when
/// the distance is positive. `face` is consumed (its id may name a wall
/// or the top afterwards; use the returned ids). Refused, with the mesh
/// unchanged: stale id, hole, point-sphere, self-loop edge, zero-area
/// face, non-finite or out-of-range parameters, non-finite new positions.
pub fn extrude_face(
    mesh: &mut Mesh,
    face: FaceId,
    params: &ExtrudeParams,
) -> Result<Extruded, ExtrudeError> {
    params.check()?;
    let (corners, points, frame) = base_face(mesh, face)?;
    let mut centre = frame.centroid;
    extrude_repeated(mesh, face, &corners, points, params.count, |ring| {
        let next = ring
            .iter()
            .map(|&p| transform(p, centre, &frame, params))
            .collect();
        centre += frame.normal * params.distance;
        next
    })
}

/// Extrudes `face` (which passed [`base_face`], giving `corners` and
/// their `points`) `count` times, each ring made by `next` from the one
/// before (the first from `points`): the loop of every repeated
/// extrusion. Refuses an oversized result and non-finite rings before
/// changing the mesh.
pub(crate) fn extrude_repeated(
    mesh: &mut Mesh,
    face: FaceId,
    corners: &[CornerId],
    points: Vec<DVec3>,
    count: usize,
    mut next: impl FnMut(&[DVec3]) -> Vec<DVec3>,
) -> Result<Extruded, ExtrudeError> {
    // Each ring adds d quads (4d corners) and d top corners.
    // Saturating: a count near `usize::MAX` is refused as oversized, not
    // wrapped into a small size.
    check_size(
        (count as u64)
            .saturating_mul(5)
            .saturating_mul(corners.len() as u64),
    )?;
    let mut rings: Vec<Vec<DVec3>> = Vec::with_capacity(count);
    for k in 0..count {
        let ring = next(rings.last().unwrap_or(&points));
        check_points(face, k * ring.len(), &ring)?;
        rings.push(ring);
    }
    extrude_rings(mesh, face, corners[0], &rings)
}

/// One repetition's map of a point: scale and turn about the centroid,
/// then move along the (unchanging) normal.
fn transform(p: DVec3, centre: DVec3, frame: &Frame, params: &ExtrudeParams) -> DVec3 {
    let scaled = centre + (p - centre) * params.scale;
    polygon::rotate_about(scaled, centre, frame.normal, params.rotation_deg)
        + frame.normal * params.distance
}

/// Extrudes `face` once per ring, ring `k` giving the new positions of
/// the corners read from `start` (the base face's corner order). The
/// face must already have passed [`base_face`]; the rings must be finite.
pub(crate) fn extrude_rings(
    mesh: &mut Mesh,
    face: FaceId,
    start: CornerId,
    rings: &[Vec<DVec3>],
) -> Result<Extruded, ExtrudeError> {
    let mut top = face;
    let mut top_start = start;
    let mut vertices = Vec::new();
    for ring in rings {
        let step = extrude_to(mesh, top, top_start, ring)?;
        vertices.extend(step.vertices);
        top = step.top;
        top_start = step.top_start;
    }
    Extruded::around(mesh, top, top_start, vertices)
}

/// One ring: the corner read `k`-th from `start` gets a new vertex at
/// `ring[k]`. The top's corners and walls come back in `Extruded`
/// (`sides` holds this ring's walls).
pub(crate) fn extrude_to(
    mesh: &mut Mesh,
    face: FaceId,
    start: CornerId,
    ring: &[DVec3],
) -> Result<Extruded, ExtrudeError> {
    let order: Vec<CornerId> = mesh.face_corners_from(start)?.collect();
    if order.len() != ring.len() {
        return Err(ExtrudeError::Kernel(holey_dlfl::Error::Invalid(format!(
            "internal: a ring of {} points for a face of {} corners",
            ring.len(),
            order.len()
        ))));
    }
    let target = |_v, cs: &[CornerId]| -> Result<DVec3, ExtrudeError> {
        // A vertex's fan (or its whole rotation) holds at least one corner
        // of the face; the first one found decides.
        cs.iter()
            .find_map(|c| order.iter().position(|o| o == c))
            .map(|k| ring[k])
            .ok_or(ExtrudeError::DegenerateFace(face))
    };
    let plan = region::plan(mesh, &[face], &target)?;
    let made = region::apply(mesh, &plan)?;
    let lifted = made
        .lifted
        .get(&start)
        .copied()
        .ok_or(ExtrudeError::DegenerateFace(face))?;
    let [top] = made.tops[..] else {
        return Err(ExtrudeError::Kernel(holey_dlfl::Error::Invalid(format!(
            "internal: extruding one face left {} top faces",
            made.tops.len()
        ))));
    };
    let top_start = mesh
        .face_corners(top)?
        .find(|&c| mesh.corner_vertex(c).is_ok_and(|v| v == lifted))
        .ok_or(ExtrudeError::DegenerateFace(face))?;
    Ok(Extruded {
        top,
        top_start,
        sides: made.walls,
        vertices: made.fan_vertices,
    })
}
