//! High-level operators of the thesis's chapter III, built on the four
//! fundamental operators where the thesis does so.
//!
//! | operator | thesis | file |
//! |---|---|---|
//! | [`Mesh::delete_edge_with_cleanup`] | §III.1 | `cleanup.rs` |
//! | [`Mesh::subdivide_edge`], [`Mesh::trisect_edge`] | §III.2 | `subdivide.rs` |
//! | [`Mesh::create_pipe`] | §III.3 | `pipe.rs` |
//! | [`Mesh::create_face_manifold`] | §III.4 | `face_manifold.rs` |
//! | [`Mesh::connect_edges`] | §III.5 | `connect.rs` |
//! | [`Mesh::collapse_edge`] | §III.6 | `collapse.rs` |
//! | [`Mesh::reverse_faces`], [`Mesh::reverse_component`] | §V.1, stage 1 | `reverse.rs` |
//! | [`Mesh::remove_two_gons`] | §V.2.3, figure 29 | `two_gons.rs` |
//!
//! [`Mesh`]: crate::Mesh
//! [`Mesh::delete_edge_with_cleanup`]: crate::Mesh::delete_edge_with_cleanup
//! [`Mesh::subdivide_edge`]: crate::Mesh::subdivide_edge
//! [`Mesh::trisect_edge`]: crate::Mesh::trisect_edge
//! [`Mesh::create_pipe`]: crate::Mesh::create_pipe
//! [`Mesh::create_face_manifold`]: crate::Mesh::create_face_manifold
//! [`Mesh::connect_edges`]: crate::Mesh::connect_edges
//! [`Mesh::collapse_edge`]: crate::Mesh::collapse_edge
//! [`Mesh::reverse_faces`]: crate::Mesh::reverse_faces
//! [`Mesh::reverse_component`]: crate::Mesh::reverse_component
//! [`Mesh::remove_two_gons`]: crate::Mesh::remove_two_gons

mod cleanup;
mod collapse;
mod connect;
mod face_manifold;
mod pipe;
mod reverse;
mod subdivide;
mod two_gons;

pub use face_manifold::FaceManifold;
pub use subdivide::Subdivided;

#[cfg(test)]
mod tests;
