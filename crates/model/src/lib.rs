//! # holey-model: the high-genus modeling tools
//!
//! The four tools of Srinivasan, *Modeling High-Genus Surfaces* (2004),
//! built on the DLFL kernel ([`holey_dlfl`]):
//! - [`handle`]: multi-segment curved handles (chapter IV);
//! - [`rind`]: rind modeling, the improved algorithm (chapter V);
//! - [`sierpinski`]: generalized Sierpinski polyhedra (chapter VI);
//! - [`menger`]: generalized Menger sponges (chapter VII).

#![warn(missing_docs)]

pub mod handle;
pub mod menger;
pub mod rind;
pub mod sierpinski;
