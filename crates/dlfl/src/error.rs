//! Typed errors of the kernel. Every failing operation leaves the mesh unchanged.

use crate::ids::{CornerId, EdgeId, EntityKind, FaceId, VertexId};

/// Why a kernel operation refused its operands. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    #[error(
        "{kind} handle (slot {index}, generation {generation}) is stale or was never issued by this mesh"
    )]
    Stale {
        kind: EntityKind,
        index: u32,
        generation: u32,
    },
    #[error("an edge needs two different corners; got {0} twice")]
    SameCorner(CornerId),
    #[error("vertex {0} is not a point-sphere; DeleteVertex only removes point-spheres")]
    NotPointSphere(VertexId),
    #[error("both corners lie in face {0}; this operator needs two different faces")]
    SameFace(FaceId),
    #[error("face {0} is a point-sphere and has no edges")]
    PointSphereFace(FaceId),
    #[error("edge {0} is a self-loop")]
    SelfLoop(EdgeId),
    #[error("both half-edges belong to edge {0}")]
    SameEdge(EdgeId),
    #[error("position ({x}, {y}, {z}) is not finite")]
    NonFinite { x: f64, y: f64, z: f64 },
    #[error("face set is not a union of whole components: face {0} borders a face outside the set")]
    NotWholeComponents(FaceId),
    #[error("{0}")]
    Invalid(String),
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
