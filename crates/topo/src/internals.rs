//! The engine's stages, for tests and benchmarks that drive one stage on
//! its own (the correction's graph and weights, the edge table). Not the
//! way to use holey: the functions at the crate root run the stages in
//! order (`topology_change`, `solid_boolean`, `self_intersections`,
//! `resolve`), and these may change without notice.

pub use crate::correct::{Graph, correct};
pub use crate::mesh::Edges;
pub use crate::weights::Weights;
