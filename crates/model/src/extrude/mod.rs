//! # Extrusions (TopMod's extrusion modes, issue 18)
//!
//! Every extrusion grows new geometry out of one face (or, for
//! [`extrude_faces`], a set of faces) of any DLFL mesh, using only the
//! kernel's operators (`CreateVertex`, `InsertEdge`, `DeleteEdge`), so
//! the mesh is a valid 2-manifold after every step and every handle of an
//! element the extrusion does not consume stays valid. The kinds are the
//! ones TopMod offers (the modeler of Akleman, Srinivasan, Chen and
//! others built on the thesis's DLFL: its `DLFLExtrude` functions and
//! extrusion modes, whose sequences of plain, dual and stellating steps
//! define the dodecahedral and icosahedral kinds); the code, the
//! placement of the new vertices and the checks are this crate's own.
//!
//! ## Counts
//! For a `d`-gon face (`V, E, F` before; genus and components unchanged):
//!
//! | kind | function | ΔV | ΔE | ΔF |
//! |---|---|---|---|---|
//! | plain, once (one ring of quads) | [`extrude_face`] | `d` | `2d` | `d` |
//! | plain, `k` times | [`extrude_face`] | `kd` | `2kd` | `kd` |
//! | Doo–Sabin, `k` times | [`extrude_face_doo_sabin`] | `kd` | `2kd` | `kd` |
//! | cubical, `k` times | [`extrude_face_cubical`] | `kd` | `2kd` | `kd` |
//! | octahedral (dual) | [`extrude_face_octahedral`] | `d` | `3d` | `2d` |
//! | dodecahedral | [`extrude_face_dodecahedral`] | `3d` | `5d` | `2d` |
//! | icosahedral | [`extrude_face_icosahedral`] | `3d` | `9d` | `6d` |
//! | stellate | [`stellate_face`] | `1` | `d` | `d − 1` |
//! | double stellate | [`double_stellate_face`] | `d + 1` | `4d` | `3d − 1` |
//! | dome of `k` rings | [`extrude_face_dome`] | `kd + 1` | `2kd + d` | `kd + d − 1` |
//! | several faces | [`extrude_faces`] | `b` | `2b` | `b` |
//!
//! For [`extrude_faces`], `b` is the number of *boundary sides* of the
//! selection: edges with a selected face on exactly one side (equal to
//! the number of *fans*, maximal runs of selected corners around a
//! vertex). Edges between two selected faces get no wall: neighbouring
//! selected faces move together and keep sharing their edge.
//!
//! ## Refusals
//! Every function checks its operands before the first mutation and
//! returns an [`ExtrudeError`], leaving the mesh unchanged, for: a stale
//! face id, a hole face (a boundary loop is not surface), a point-sphere,
//! a face with a self-loop edge, a face of zero area (no normal; any face
//! of fewer than three corners), a parameter that is NaN, infinite or out
//! of its range, or geometry that would overflow. Once the checks pass the
//! kernel calls cannot fail on the handles this module made; if one did,
//! that would be a bug, reported as [`ExtrudeError::Kernel`].

mod cubical;
mod dodecahedral;
mod dome;
mod doo_sabin;
mod double_stellate;
mod icosahedral;
mod kind;
mod multi;
mod octahedral;
mod plain;
mod region;
mod stellate;

#[cfg(test)]
mod tests;

use holey_dlfl::{CornerId, DVec3, EdgeId, FaceId, Mesh, VertexId};

pub use cubical::extrude_face_cubical;
pub use dodecahedral::extrude_face_dodecahedral;
pub use dome::{DomeParams, extrude_face_dome};
pub use doo_sabin::{DooSabinParams, extrude_face_doo_sabin};
pub use double_stellate::double_stellate_face;
pub use icosahedral::extrude_face_icosahedral;
pub use kind::{ExtrudeKind, ExtrudeOption, ExtrudeOptions, UnknownExtrudeKind, extrude_selection};
pub use multi::{MultiExtrudeParams, MultiExtruded, RegionDirection, extrude_faces};
pub use octahedral::extrude_face_octahedral;
pub use plain::{ExtrudeParams, extrude_face};
pub use stellate::stellate_face;

use crate::polygon::{self, Frame};

/// The most corners one call may add (about 50 million, a few gigabytes
/// of kernel storage); more is refused with [`ExtrudeError::TooLarge`].
pub const MAX_NEW_CORNERS: u64 = 50_000_000;

/// Why an extrusion was refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExtrudeError {
    /// No faces were given to a multi-face extrusion.
    #[error("no faces were given; select at least one face to extrude")]
    EmptySelection,
    /// The face is a hole (it closes a boundary loop); it is not surface.
    #[error("face {0} is a hole (a boundary loop), not surface; there is nothing to extrude")]
    HoleFace(FaceId),
    /// The face is a point-sphere: one corner and no edge.
    #[error("face {0} is a point-sphere (one corner, no edge); there is nothing to extrude")]
    PointSphere(FaceId),
    /// An edge of the face starts and ends at the same vertex; the walls
    /// of an extrusion would have to pass through themselves there.
    #[error("edge {edge} of face {face} is a self-loop; faces with self-loops are not extruded")]
    SelfLoop {
        /// The face asked for.
        face: FaceId,
        /// Its self-loop edge.
        edge: EdgeId,
    },
    /// The face has (nearly) zero area, so it has no normal to extrude
    /// along. Every face of fewer than three corners is such a face.
    #[error("face {0} has zero area, so it has no normal to extrude along")]
    DegenerateFace(FaceId),
    /// A parameter is NaN, infinite or outside its range.
    #[error("parameter '{name}' is {value}; it must be {expected}")]
    InvalidParameter {
        /// The parameter's name, as in the params struct.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The accepted range in words.
        expected: &'static str,
    },
    /// The selected faces' normals cancel out (a multi-face extrusion
    /// along their average), or a vertex's selected faces do (along
    /// vertex normals), so there is no direction to move along.
    #[error(
        "the normals of the selected faces cancel out at {at}; there is no direction to extrude along"
    )]
    NoDirection {
        /// Where: "the selection" for the average direction, or the vertex.
        at: String,
    },
    /// A new vertex would get a NaN or infinite coordinate: the distance,
    /// scale or count is too large for the model's scale.
    #[error(
        "a new vertex of face {face} would have non-finite coordinates ({point}); the parameters are too large for the model's scale"
    )]
    NonFinite {
        /// The face being extruded (for a multi-face extrusion, a selected
        /// face at the vertex that would move there).
        face: FaceId,
        /// Which new point and where: for one face, `new point i` counting
        /// the points the kind places ring by ring, each ring from the
        /// face's first corner ([`Mesh::face_corner`]); for a multi-face
        /// extrusion, `the lift of corner i` of `face`, counted the same way.
        point: holey_dlfl::NonFinite,
    },
    /// A repetition after the first of a repeated multi-face extrusion
    /// was refused (its faces are ones the earlier repetitions made, which
    /// the caller never named); the mesh is as it was before the first.
    #[error("repetition {step} of {count} was refused, so none was made: {cause}")]
    Repeated {
        /// Which repetition, from 1 (always at least 2).
        step: usize,
        /// How many were asked for.
        count: usize,
        /// Why it was refused, about faces that repetition would extrude.
        cause: Box<ExtrudeError>,
    },
    /// One face of a one-by-one extrusion ([`extrude_selection`]) was
    /// refused; the faces before it were put back as they were.
    #[error("face {face}: {cause}")]
    Face {
        /// The face refused, as given.
        face: FaceId,
        /// Why.
        cause: Box<ExtrudeError>,
    },
    /// A multi-face extrusion ([`ExtrudeOptions::together`]) was asked of
    /// a kind other than plain.
    #[error("a multi-face extrusion is plain; it does not take the {0} kind")]
    TogetherNotPlain(ExtrudeKind),
    /// An option was given to a kind that does not read it.
    #[error("option '{option}' does not apply to the {kind} extrusion")]
    Unread {
        /// The option given.
        option: ExtrudeOption,
        /// The kind asked for.
        kind: ExtrudeKind,
    },
    /// An option besides distance and count was given to a multi-face
    /// extrusion.
    #[error(
        "option '{option}' does not apply to a multi-face extrusion (it takes distance, count and the direction)"
    )]
    UnreadTogether {
        /// The option given.
        option: ExtrudeOption,
    },
    /// The extrusion would add more than [`MAX_NEW_CORNERS`] corners.
    #[error(
        "this extrusion would add about {corners} corners, more than the limit of {MAX_NEW_CORNERS}"
    )]
    TooLarge {
        /// An estimate of the corners it would add.
        corners: u64,
    },
    /// A kernel call failed: a face id that is not in the mesh (stale or
    /// from another mesh), or, once the checks have passed, a bug.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// What an extrusion of one face made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Extruded {
    /// The face at the far end: the last ring's face for the extrusions,
    /// the top face for the polyhedral ones. For the stellations, which
    /// leave no single far face, the face holding the apex's first corner.
    pub top: FaceId,
    /// The corner of `top` that corresponds to the base face's first
    /// corner (the one [`Mesh::face_corner`] gave before the call), so
    /// that the top can be read in the base's order.
    pub top_start: CornerId,
    /// Every other face made or reshaped by the extrusion (the side
    /// walls), in slot order; the base face itself is gone.
    pub sides: Vec<FaceId>,
    /// The vertices the extrusion created, in creation order.
    pub vertices: Vec<VertexId>,
}

/// Checks that a parameter is finite and satisfies `ok`.
pub(crate) fn check_param(
    name: &'static str,
    value: f64,
    expected: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), ExtrudeError> {
    if value.is_finite() && ok(value) {
        Ok(())
    } else {
        Err(ExtrudeError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}

/// [`base_face`] for the extrusions shaped like a solid, after refusing a
/// `height_factor` that is not finite and positive.
pub(crate) fn solid_base(
    mesh: &Mesh,
    face: FaceId,
    height_factor: f64,
) -> Result<(Vec<CornerId>, Vec<DVec3>, Frame), ExtrudeError> {
    check_param(
        "height_factor",
        height_factor,
        "finite and greater than 0",
        |h| h > 0.0,
    )?;
    base_face(mesh, face)
}

/// The checks shared by every single-face extrusion: a live surface face
/// with edges, no self-loops and a normal. Returns its corners from
/// [`Mesh::face_corner`], their positions and its frame.
pub(crate) fn base_face(
    mesh: &Mesh,
    face: FaceId,
) -> Result<(Vec<CornerId>, Vec<DVec3>, Frame), ExtrudeError> {
    check_surface_face(mesh, face)?;
    let corners: Vec<CornerId> = mesh.face_corners(face)?.collect();
    let points = mesh.face_positions(face)?;
    let frame = polygon::frame(&points).ok_or(ExtrudeError::DegenerateFace(face))?;
    Ok((corners, points, frame))
}

/// A live, non-hole face with edges and no self-loop.
pub(crate) fn check_surface_face(mesh: &Mesh, face: FaceId) -> Result<(), ExtrudeError> {
    if mesh.is_hole(face)? {
        return Err(ExtrudeError::HoleFace(face));
    }
    if mesh.is_point_sphere(face)? {
        return Err(ExtrudeError::PointSphere(face));
    }
    for c in mesh.face_corners(face)? {
        if let Some(edge) = mesh.corner_edge(c)?
            && mesh.is_self_loop(edge)?
        {
            return Err(ExtrudeError::SelfLoop { face, edge });
        }
    }
    Ok(())
}

/// [`check_points`] for the rings of new points of one extrusion, in the
/// order they are created: the points are numbered on from one ring to
/// the next, so an error names the bad point as the extrusion counts it.
pub(crate) fn check_rings(face: FaceId, rings: &[&[DVec3]]) -> Result<(), ExtrudeError> {
    let mut first = 0;
    for ring in rings {
        check_points(face, first, ring)?;
        first += ring.len();
    }
    Ok(())
}

/// Refuses non-finite points, naming the face they were computed for and
/// the first bad point as `new point first + i`.
pub(crate) fn check_points(
    face: FaceId,
    first: usize,
    points: &[DVec3],
) -> Result<(), ExtrudeError> {
    holey_dlfl::NonFinite::check("new point", points).map_err(|point| ExtrudeError::NonFinite {
        face,
        point: holey_dlfl::NonFinite {
            index: point.index.map(|i| first + i),
            ..point
        },
    })
}

/// Refuses an extrusion that would add more than [`MAX_NEW_CORNERS`].
pub(crate) fn check_size(corners: u64) -> Result<(), ExtrudeError> {
    if corners > MAX_NEW_CORNERS {
        Err(ExtrudeError::TooLarge { corners })
    } else {
        Ok(())
    }
}

/// The midpoint direction of edge `i` (from corner `i` to `i + 1`),
/// scaled by `1/cos(π/d)` so that for a regular polygon it has the
/// circumradius's length and points at the corner of the polygon turned
/// by half a step. The polyhedral extrusions place their rings with it.
pub(crate) fn half_step(points: &[DVec3], centre: DVec3, i: usize) -> DVec3 {
    let d = points.len();
    let mid = (points[i] + points[(i + 1) % d]) * 0.5 - centre;
    mid / (std::f64::consts::PI / d as f64).cos()
}

/// The base `points` turned by half a step about `centre` (see
/// [`half_step`]), scaled by `scale` and lifted by `height` along the unit
/// `normal`: the rings of the octahedral, dodecahedral and icosahedral
/// extrusions, which differ only in these two numbers.
pub(crate) fn turned_ring(
    points: &[DVec3],
    centre: DVec3,
    normal: DVec3,
    scale: f64,
    height: f64,
) -> Vec<DVec3> {
    (0..points.len())
        .map(|i| centre + half_step(points, centre, i) * scale + normal * height)
        .collect()
}

impl Extruded {
    /// What an extrusion made that created `vertices` and ended at `top`
    /// (read from `top_start`): its sides are every other face with a
    /// corner at one of those vertices, in slot order without repeats.
    /// Every extrusion reports its result this way, so `sides` means the
    /// same for all of them.
    pub(crate) fn around(
        mesh: &Mesh,
        top: FaceId,
        top_start: CornerId,
        vertices: Vec<VertexId>,
    ) -> Result<Self, ExtrudeError> {
        let mut faces = std::collections::BTreeSet::new();
        for &v in &vertices {
            for c in mesh.vertex_corners(v)? {
                faces.insert(mesh.corner_face(c)?);
            }
        }
        faces.remove(&top);
        Ok(Extruded {
            top,
            top_start,
            sides: faces.into_iter().collect(),
            vertices,
        })
    }
}
