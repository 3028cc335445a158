//! # holey-topo: topology change for arbitrary triangle meshes
//!
//! Bernstein & Wojtan, *Putting Holes in Holey Geometry* (SIGGRAPH 2013),
//! section 3 and appendices A–C. (Being written.)

pub mod correct;
pub mod intersect;
pub mod mesh;
pub mod weights;
