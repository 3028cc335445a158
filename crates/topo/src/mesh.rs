//! Triangle meshes as the engine takes them, and their edges: the plain
//! triangle mesh of `holey-mesh` ([`holey_mesh::tri`]), re-exported where
//! the engine's stages have always found it.
//!
//! The engine works on *any* list of triangles (§2.1 of the paper): edges of
//! any degree, open, unoriented, disconnected, unwelded soups, duplicate and
//! zero-area triangles. Edges are identified by vertex *indices*: two
//! triangles of a soup that only touch at equal positions share no edge.

pub use holey_mesh::tri::*;
