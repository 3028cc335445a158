//! Why a multi-face handle ([`super::create_multi_face_handle`]) was
//! refused: one home for the error, so that the hub's placement
//! (`hub.rs`) and the handles to it (`multi.rs`) both report it without
//! importing each other.

use glam::DVec3;
use holey_dlfl::{BuildError, FaceId};

use super::HandleError;
use super::crossing::CrossingError;
use crate::hull::HullError;

/// Why a multi-face handle was refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MultiHandleError {
    /// Fewer than four faces were selected; a hub needs four directions
    /// that span space.
    #[error(
        "a multi-face handle needs at least four faces (got {0}); join two faces with a plain handle"
    )]
    TooFewFaces(usize),
    /// This face was selected twice.
    #[error("face {0} is selected twice")]
    DuplicateFace(FaceId),
    /// A selected face is unusable as a handle's end (a hole, a
    /// point-sphere, a stale id, …).
    #[error(transparent)]
    Face(#[from] HandleError),
    /// [`MultiHandleParams::hub_scale`](super::MultiHandleParams::hub_scale)
    /// is not finite and positive.
    #[error("the hub scale is {0}; it must be finite and positive")]
    BadHubScale(f64),
    /// This face's centroid is the hub's centre, so it has no direction
    /// from the hub.
    #[error("face {0} has its centroid at the hub's centre, so no direction from the hub")]
    AtCentre(FaceId),
    /// Two faces lie in the same direction from the hub's centre; one hub face
    /// cannot serve both.
    #[error("faces {0} and {1} lie in the same direction from the hub's centre")]
    SameDirection(FaceId, FaceId),
    /// The hub could not be built: the directions lie on one plane
    /// ([`HullError::Flat`]) or a numerical failure.
    #[error("the hub could not be built: {0}")]
    Hub(#[from] HullError),
    /// The hub's faces do not pair one-to-one with the directions (a
    /// direction whose plane only grazes the others).
    #[error(
        "the hub has {hub_faces} faces for {faces} selected faces, or they do not pair one-to-one"
    )]
    HubMismatch {
        /// Faces of the hub.
        hub_faces: usize,
        /// Faces selected.
        faces: usize,
    },
    /// Adding the hub to the mesh failed (a kernel bug).
    #[error("internal error adding the hub (please report): {0}")]
    Build(#[from] BuildError),
    /// The two-face handle to the hub failed for selected face `index`.
    #[error("the handle from selected face {index} to the hub failed: {source}")]
    Handle {
        /// Position of the face in the selection.
        index: usize,
        /// Why.
        source: HandleError,
    },
    /// No point within four selection radii of the centroids' average lies
    /// in front of all these faces (a smallest such set, at most four by
    /// Helly's theorem; the same four may share a point far away): a hub they
    /// could all reach from outside does not exist, as for faces all
    /// around one body looking outward.
    #[error(
        "faces {} look away from each other: no point near the selection (within four times its radius) lies in front of all of them, so a hub would sit inside the surface and the handles would pass through it; select faces that look at a common point from outside",
        list(.0)
    )]
    NoCommonView(Vec<FaceId>),
    /// Points in front of every selected face exist, but from each of them
    /// all the faces lie to one side, so the hub (one face turned to each
    /// selected face) would be unbounded.
    #[error(
        "faces {} all look into one side: every point in front of all of them sees them to one side, and a hub needs selected faces all around it",
        list(.0)
    )]
    OneSided(Vec<FaceId>),
    /// The hub's centre proposed by the (floating-point) choice is not
    /// strictly in front of every fan triangle of these faces by the exact
    /// test (a margin lost to rounding).
    #[error(
        "the hub's centre {hub} is not strictly in front of faces {}",
        list(faces)
    )]
    Blind {
        /// The faces that do not see the centre.
        faces: Vec<FaceId>,
        /// The centre proposed.
        hub: DVec3,
    },
    /// The straight line from a selected face's centroid to the hub's
    /// centre passes through another face.
    #[error("face {face} cannot see the hub at {hub}: face {by} is in the way")]
    Blocked {
        /// The selected face.
        face: FaceId,
        /// The face crossed first found.
        by: FaceId,
        /// The hub's centre.
        hub: DVec3,
    },
    /// The handles built cross the surface or each other (exact count of
    /// crossing triangle pairs, as `holey selfint` counts them).
    #[error(
        "the handles from faces {} would cross the surface or each other ({pairs} crossing triangle pairs); try a smaller hub scale, smaller weights or more segments",
        list(faces)
    )]
    Crosses {
        /// The selected faces whose handles cross something.
        faces: Vec<FaceId>,
        /// Crossing triangle pairs involving the new faces.
        pairs: usize,
    },
    /// The exact crossing check could not run (non-finite positions).
    #[error("the crossing check failed: {0}")]
    Check(#[from] CrossingError),
}

/// Faces as a comma-separated list.
fn list(faces: &[FaceId]) -> String {
    faces
        .iter()
        .map(|f| f.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
