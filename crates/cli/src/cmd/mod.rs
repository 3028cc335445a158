//! One module per command.

pub mod convert;
pub mod demo;
pub mod info;
pub mod primitive;
