//! Errors of the command line: bad input (exit status 2) or a failure of
//! the system (exit status 1).

use std::fmt;

/// Marks an error as the user's input being at fault.
#[derive(Debug)]
pub struct BadInput(pub String);

impl fmt::Display for BadInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// An error for bad input, with a message.
pub fn bad_input(message: impl fmt::Display) -> anyhow::Error {
    anyhow::Error::new(BadInput(message.to_string()))
}

/// Converts a file error, keeping whether the input was at fault. A
/// missing input file counts as bad input.
pub fn from_io(e: holey_io::IoError) -> anyhow::Error {
    let missing = matches!(&e, holey_io::IoError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound);
    if e.is_bad_input() || missing {
        bad_input(e)
    } else {
        anyhow::Error::new(e)
    }
}

/// The process exit status for an error.
pub fn exit_status(e: &anyhow::Error) -> i32 {
    if e.chain().any(|c| c.is::<BadInput>()) {
        2
    } else {
        1
    }
}
