//! Typed errors of the kernel. Every failing operation leaves the mesh unchanged.

use holey_mesh::NonFinite;

use crate::ids::{CornerId, EdgeId, EntityKind, FaceId, VertexId};

/// Why a kernel operation refused its operands. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A handle names a slot that is empty or whose generation has moved on
    /// (the entity was removed), or the handle was not issued by this mesh.
    #[error(
        "{kind} handle (slot {index}, generation {generation}) is stale or was never issued by this mesh"
    )]
    Stale {
        /// Which kind of entity the handle names.
        kind: EntityKind,
        /// The slot index the handle carries.
        index: u32,
        /// The generation the handle carries.
        generation: u32,
    },
    /// `InsertEdge` was given the same corner for both ends; the field is
    /// that corner.
    #[error("an edge needs two different corners; got {0} twice")]
    SameCorner(CornerId),
    /// `DeleteVertex` was asked to remove the named vertex, which is not a
    /// point-sphere (a lone vertex with one edgeless face).
    #[error("vertex {0} is not a point-sphere; DeleteVertex only removes point-spheres")]
    NotPointSphere(VertexId),
    /// `CreatePipe` was given two corners of the named face; it joins two
    /// different faces.
    #[error("both corners lie in face {0}; this operator needs two different faces")]
    SameFace(FaceId),
    /// An operand corner lies in the named face, a point-sphere, where the
    /// operator needs a face with edges.
    #[error("face {0} is a point-sphere and has no edges")]
    PointSphereFace(FaceId),
    /// `CollapseEdge` was given the named edge, whose two ends are the same
    /// vertex.
    #[error("edge {0} is a self-loop")]
    SelfLoop(EdgeId),
    /// `ConnectEdges` was given the two sides of the named edge; it needs
    /// half-edges of two different edges.
    #[error("both half-edges belong to edge {0}")]
    SameEdge(EdgeId),
    /// A vertex position has a NaN or infinite coordinate, whether given (a
    /// new or moved vertex) or computed (a point placed along an edge); it
    /// has no index, only its coordinates.
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// The faces given to reverse are not whole components: the named face
    /// of the set shares an edge with a face outside it.
    #[error("face set is not a union of whole components: face {0} borders a face outside the set")]
    NotWholeComponents(FaceId),
    /// Any other refusal, described by the text (too few points for a face
    /// manifold, a degenerate connecting edge, face sizes that cannot be
    /// matched for a pipe).
    #[error("{0}")]
    Invalid(String),
}

/// The result of a kernel operation, failing with [`Error`] by default.
pub type Result<T, E = Error> = std::result::Result<T, E>;
