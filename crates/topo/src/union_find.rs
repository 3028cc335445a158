//! The disjoint-set forest of `holey-mesh` ([`holey_mesh::union_find`]),
//! where the engine's stages find it.

pub use holey_mesh::union_find::UnionFind;
