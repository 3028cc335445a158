//! One module per command.

pub mod batch;
pub mod boolean;
pub mod convert;
pub mod cut;
pub mod demo;
pub mod extrude;
pub mod handle;
pub mod hull;
pub mod info;
pub mod menger;
pub mod primitive;
pub mod remesh;
pub mod render;
pub mod resolve;
pub mod rind;
pub mod sculpt;
pub mod selfint;
pub mod serve;
pub mod sierpinski;
pub mod subdivide;
pub mod topo;
pub mod union;
pub mod winding;
pub mod wireframe;
