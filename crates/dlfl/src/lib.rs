//! # holey-dlfl: the Doubly Linked Face List
//!
//! The mesh kernel of holey, after Srinivasan, *Modeling High-Genus
//! Surfaces* (2004), chapters II and III, and Akleman & Chen's minimal
//! operator set.
//!
//! A [`Mesh`] is an orientable 2-manifold *without boundary* made of
//! vertices, edges, faces and **corners**. A corner is a vertex–face pair:
//! one step of a face's boundary walk. A face is a cyclic, doubly linked
//! sequence of corners; an edge stores the two corners at which it
//! originates, one in each face beside it; each corner knows the edge that
//! starts at it; each vertex lists its corners.
//!
//! Unlike half-edge libraries, the DLFL represents everything its operators
//! produce: self-loops, two-gons, multiple edges between two vertices,
//! point-spheres (a one-corner face with no edge), valence-1 vertices and
//! any number of components. Open surfaces are represented by closing each
//! boundary loop with a face flagged as a *hole*.
//!
//! ## Operators
//! The four fundamental operators (§II.5) change topology while keeping the
//! surface a valid 2-manifold, so every mesh they build passes
//! [`Mesh::validate`]:
//! - [`Mesh::create_vertex`] makes a point-sphere (Euler's MVFS);
//! - [`Mesh::delete_vertex`] removes one (KVFS);
//! - [`Mesh::insert_edge`] splits a face, or merges two faces (adding a
//!   handle or joining two components);
//! - [`Mesh::delete_edge`] is its exact inverse.
//!
//! The high-level operators of chapter III are in [`ops`].
//!
//! The kernel knows nothing of files or geometric algorithms: positions are
//! carried, interpolated where an operator places a new vertex, and
//! otherwise left to the caller.

#![warn(missing_docs)]

mod arena;
mod build;
pub mod convert;
mod error;
mod ids;
pub mod info;
mod mesh;
pub mod ops;
mod topology;
mod validate;

#[cfg(test)]
mod test_util;

#[cfg(test)]
mod properties;

pub use build::{BuildError, RawMesh};
pub use error::{Error, Result};
pub use glam::DVec3;
pub use holey_mesh::NonFinite;
pub use ids::{CornerId, EdgeId, EntityKind, FaceId, VertexId};
pub use info::dlfl_info;
pub use mesh::{CornerCycle, FaceCorners, Mesh, VertexCorners, VertexRotation};
pub use topology::{ComponentTopology, Topology};
pub use validate::ValidationError;
