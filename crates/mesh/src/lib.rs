//! # holey-mesh: polygon soups
//!
//! [`PolyMesh`] is an indexed polygon mesh exactly as files store it:
//! positions and faces of any size, with no connectivity and no promise of
//! being manifold, closed, oriented, welded or free of self-intersections.
//!
//! - [`analysis`] measures any soup (`holey info`): counts, boundary,
//!   non-manifold edges and vertices, orientation, Euler characteristic,
//!   genus and volume.
//! - [`convert`] turns a manifold soup into a DLFL [`holey_dlfl::Mesh`]
//!   (boundary loops become hole faces; non-manifold input is an error
//!   unless splitting is asked for) and back.

pub mod analysis;
pub mod convert;
mod poly;

pub use glam::DVec3;
pub use poly::{PolyMesh, PolyMeshError};
