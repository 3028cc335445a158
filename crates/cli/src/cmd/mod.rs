//! One module per command.

pub mod convert;
pub mod info;
pub mod primitive;
