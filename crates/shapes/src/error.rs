use crate::spec::{known_list, suggestion};

/// Why a primitive spec or parameter set was rejected. The messages are
/// meant to be shown to users as they are.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// The spec does not start with `@`.
    #[error("a primitive spec starts with '@' (e.g. @cube or @torus:32:16), got {spec:?}")]
    MissingAt {
        /// The whole spec as given.
        spec: String,
    },

    /// Nothing (or only parameters) after the `@`.
    #[error("missing primitive name after '@'; known primitives: {}", known_list())]
    MissingName,

    /// The name is not one of [`crate::PRIMITIVES`] or their aliases.
    #[error(
        "unknown primitive @{name}{}; known primitives: {}",
        suggestion(name),
        known_list()
    )]
    UnknownName {
        /// The name as written between the `@` and the first `:`.
        name: String,
    },

    /// More parameters than the primitive takes.
    #[error("@{primitive} takes at most {max} parameter{} ({usage}), got {given}", if *max == 1 { "" } else { "s" })]
    TooManyParameters {
        /// Canonical name of the primitive, without the `@`.
        primitive: &'static str,
        /// The primitive's usage line, e.g. `@torus[:major[:minor[:R[:r]]]]`.
        usage: String,
        /// Number of parameters the primitive takes.
        max: usize,
        /// Number of parameters given (when a generator is called directly
        /// with the wrong number of arguments, possibly fewer than `max`).
        given: usize,
    },

    /// An integer parameter that is not a decimal integer.
    #[error("parameter '{param}' of @{primitive} must be an integer, got {value:?}")]
    NotAnInteger {
        /// Canonical name of the primitive, without the `@`.
        primitive: &'static str,
        /// Name of the parameter, as in the usage line.
        param: &'static str,
        /// The text given for it.
        value: String,
    },

    /// A real parameter that is not a finite decimal number.
    #[error("parameter '{param}' of @{primitive} must be a finite number, got {value:?}")]
    NotANumber {
        /// Canonical name of the primitive, without the `@`.
        primitive: &'static str,
        /// Name of the parameter, as in the usage line.
        param: &'static str,
        /// The text given for it.
        value: String,
    },

    /// A parameter outside its range; `range` reads like "an integer from
    /// 0 to 9" and `note` explains a limit when there is more to say.
    #[error("parameter '{param}' of @{primitive} must be {range}, got {value}{note}")]
    OutOfRange {
        /// Canonical name of the primitive, without the `@`.
        primitive: &'static str,
        /// Name of the parameter, as in the usage line.
        param: &'static str,
        /// The accepted values in words, e.g. "an integer from 0 to 9".
        range: String,
        /// The value given: the text from the spec, or the number written
        /// out when a generator is called directly.
        value: String,
        /// Empty, or a parenthesized remark starting with a space (that the
        /// maximum comes from the face limit).
        note: String,
    },

    /// Parameters that are each in range but do not fit together.
    #[error("@{primitive}: {message}")]
    Invalid {
        /// Canonical name of the primitive, without the `@`.
        primitive: &'static str,
        /// Why the parameters do not fit together.
        message: String,
    },

    /// The mesh would have more than [`crate::MAX_FACES`] faces.
    #[error(
        "{spec} would have {faces} faces, more than the limit of {limit} faces; use smaller parameters"
    )]
    TooManyFaces {
        /// The canonical spec with every parameter written out, e.g.
        /// `@torus:24:12:1:0.4`.
        spec: String,
        /// Number of faces the mesh would have.
        faces: u128,
        /// The face limit, [`crate::MAX_FACES`].
        limit: u64,
    },
}
