//! Library errors as Python exceptions.
//!
//! Bad input (a malformed file, a non-finite coordinate, an index out of
//! range, an operator's refusal) raises `holey.HoleyError`, a subclass of
//! `ValueError` whose message is the library's, which says what and
//! where. A failure of the system (a file that cannot be read or
//! written) raises `OSError` (`FileNotFoundError` for a missing file).

use pyo3::PyErr;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};

pyo3::create_exception!(
    holey,
    HoleyError,
    PyValueError,
    "Bad input to holey: the message says what and where."
);

/// `HoleyError` with the message `what` (any error of the library).
pub fn bad(what: impl std::fmt::Display) -> PyErr {
    HoleyError::new_err(what.to_string())
}

/// A file error: the system's as `OSError`, the input's as `HoleyError`.
pub fn io(e: holey::io::IoError) -> PyErr {
    match &e {
        holey::io::IoError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(e.to_string())
        }
        holey::io::IoError::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => bad(e),
    }
}
