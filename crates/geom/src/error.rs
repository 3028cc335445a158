//! Errors of the geometry crate.

pub use holey_mesh::NonFinite;
use thiserror::Error;

/// What can go wrong with input to this crate's constructions, BVHs and
/// collision queries. Predicates never fail (they answer in the perturbed
/// world); constructions and bulk queries check their input.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GeomError {
    /// A coordinate is NaN or infinite: the first point (or box) found with
    /// one, by its index in the array checked.
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// A triangle refers to a vertex index past the end of the positions.
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    VertexOutOfRange {
        /// Index of the first triangle found with such a corner.
        triangle: usize,
        /// The out-of-range vertex index it holds.
        vertex: u32,
        /// Number of positions there are.
        count: usize,
    },
    /// Two arrays that must have the same length do not.
    #[error("length mismatch: {what} has {got} entries, expected {expected}")]
    LengthMismatch {
        /// Names the array whose length is wrong (or, for a BVH refit,
        /// `"changed primitive id"`).
        what: &'static str,
        /// The length it has (for a changed primitive id: that id, which is out
        /// of range).
        got: usize,
        /// The length it must have (the number of vertices, points or
        /// primitives).
        expected: usize,
    },
    /// A construction was asked for a point that does not exist in the
    /// perturbed world (e.g. the segment does not cross the plane, or the
    /// three planes share a line).
    #[error("degenerate construction: {0}")]
    Degenerate(&'static str),
    /// More elements than the 32-bit indices of this crate can address.
    #[error("too many elements: {0} (at most 2^31)")]
    TooMany(usize),
    /// The caller's cancel flag was raised while the work ran.
    #[error("cancelled")]
    Cancelled,
}
