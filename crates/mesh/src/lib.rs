//! # holey-mesh: plain meshes
//!
//! [`PolyMesh`] is an indexed polygon mesh exactly as files store it:
//! positions and faces of any size, with no connectivity and no promise of
//! being manifold, closed, oriented, welded or free of self-intersections.
//! [`TriMesh`] is the same for triangles, as the topology engine, the
//! Booleans and sculpting take it ([`tri`]: checks, edge tables,
//! closedness, pinches, compaction); the two convert into each other.
//!
//! - [`rows`] files items into numbered rows by a counting sort (the
//!   sides of a mesh under their smaller end).
//! - [`slots`] removes entries of a numbered array by filling the gaps
//!   from its end (what the sculpt remesher and the modeler's frames do).
//! - [`analysis`] measures any soup (`holey info`): counts, boundary,
//!   non-manifold edges and vertices, orientation, Euler characteristic,
//!   genus and volume.
//!
//! Nothing here knows the DLFL kernel: `holey_dlfl::convert` builds a
//! kernel mesh from a soup and back, on top of this crate.

#![warn(missing_docs)]

pub mod analysis;
mod finite;
mod poly;
pub mod rows;
pub mod slots;
pub mod tri;
pub mod union_find;

pub use finite::NonFinite;
pub use glam::DVec3;
pub use poly::{PolyMesh, PolyMeshError};
pub use tri::{MeshError, TriMesh};
pub use union_find::UnionFind;

/// The least number of items (vertices or triangles) one thread takes of
/// a whole-mesh pass that runs in parallel: below it, handing work to a
/// second thread costs about what it saves. A pass over a sculpted
/// million-triangle mesh splits into dozens of such runs, one over the
/// 70k-triangle bunny into a few.
pub const PARALLEL_RUN: usize = 1 << 14;
