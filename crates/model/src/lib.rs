//! # holey-model: the high-genus modeling tools
//!
//! The four tools of Srinivasan, *Modeling High-Genus Surfaces* (2004),
//! built on the DLFL kernel ([`holey_dlfl`]):
//! - [`handle`]: multi-segment curved handles (chapter IV);
//! - [`rind`]: rind modeling, the improved algorithm (chapter V);
//! - [`sierpinski`]: generalized Sierpinski polyhedra (chapter VI);
//! - [`menger`]: generalized Menger sponges (chapter VII).
//!
//! And TopMod's other modeling tools (issue 18):
//! - [`extrude`]: plain, multi-face, Doo–Sabin, cubical, octahedral,
//!   dodecahedral and icosahedral extrusions, stellations and domes;
//! - [`wireframe`]: wireframe and column modeling (a tube along every edge);
//! - [`cut`] and [`truncate`]: the conical tools (cut by vertex, edge or
//!   face; truncation of vertices and edges);
//! - [`hull`]: the convex hull and TopMod's dual convex hull;
//! - [`tools`]: planarize, make spherical, two-gon and valence-2 cleanup;
//! - [`select`]: face loops, edge loops and rings, grow, shrink, invert,
//!   similar, checkerboard.

#![warn(missing_docs)]

pub mod cut;
pub mod extrude;
pub mod handle;
pub mod hull;
pub mod menger;
pub mod numbering;
mod polygon;
#[cfg(test)]
mod properties;
pub mod rind;
pub mod select;
pub mod sierpinski;
#[cfg(test)]
mod test_util;
pub mod tools;
pub mod truncate;
pub mod wireframe;
