use crate::spec::{known_list, suggestion};

/// Why a primitive spec or parameter set was rejected. The messages are
/// meant to be shown to users as they are.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// The spec does not start with `@`.
    #[error("a primitive spec starts with '@' (e.g. @cube or @torus:32:16), got {spec:?}")]
    MissingAt { spec: String },

    /// Nothing (or only parameters) after the `@`.
    #[error("missing primitive name after '@'; known primitives: {}", known_list())]
    MissingName,

    /// The name is not one of [`crate::PRIMITIVES`] or their aliases.
    #[error(
        "unknown primitive @{name}{}; known primitives: {}",
        suggestion(name),
        known_list()
    )]
    UnknownName { name: String },

    /// More parameters than the primitive takes.
    #[error("@{primitive} takes at most {max} parameter{} ({usage}), got {given}", if *max == 1 { "" } else { "s" })]
    TooManyParameters {
        primitive: &'static str,
        usage: String,
        max: usize,
        given: usize,
    },

    /// An integer parameter that is not a decimal integer.
    #[error("parameter '{param}' of @{primitive} must be an integer, got {value:?}")]
    NotAnInteger {
        primitive: &'static str,
        param: &'static str,
        value: String,
    },

    /// A real parameter that is not a finite decimal number.
    #[error("parameter '{param}' of @{primitive} must be a finite number, got {value:?}")]
    NotANumber {
        primitive: &'static str,
        param: &'static str,
        value: String,
    },

    /// A parameter outside its range; `range` reads like "an integer from
    /// 0 to 9" and `note` explains a limit when there is more to say.
    #[error("parameter '{param}' of @{primitive} must be {range}, got {value}{note}")]
    OutOfRange {
        primitive: &'static str,
        param: &'static str,
        range: String,
        value: String,
        note: String,
    },

    /// Parameters that are each in range but do not fit together.
    #[error("@{primitive}: {message}")]
    Invalid {
        primitive: &'static str,
        message: String,
    },

    /// The mesh would have more than [`crate::MAX_FACES`] faces.
    #[error(
        "{spec} would have {faces} faces, more than the limit of {limit} faces; use smaller parameters"
    )]
    TooManyFaces {
        spec: String,
        faces: u128,
        limit: u64,
    },
}
