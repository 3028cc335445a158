//! The one error type of this crate.

use std::fmt;

/// Why reading or writing a mesh file failed.
///
/// Every message says *what* went wrong and *where*: the file name plus a
/// line number for text formats, or a byte offset for binary data. The
/// variants split into bad input (the file's content, the file name or the
/// mesh handed to a writer is wrong; [`IoError::is_bad_input`] is true) and
/// failures of the system ([`IoError::Io`]: permissions, a full disk, a
/// missing file or directory).
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// Malformed text at a line (1-based) of a text file or text section.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file name (or source label) given to the reader.
        file: String,
        /// The 1-based number, counted from the start of the file, of the offending line.
        line: usize,
        /// What is wrong on that line.
        message: String,
    },
    /// Malformed binary data at a byte offset (0-based) from the start of
    /// the file.
    #[error("{file}: byte {offset}: {message}")]
    Byte {
        /// The file name (or source label) given to the reader.
        file: String,
        /// The 0-based byte offset of the offending data from the start of the file.
        offset: u64,
        /// What is wrong with the data there.
        message: String,
    },
    /// Malformed content that has no better location (an empty file, say).
    #[error("{file}: {message}")]
    Content {
        /// The file name (or source label) given to the reader.
        file: String,
        /// What is wrong with the content.
        message: String,
    },
    /// The file name's extension names no supported format.
    #[error("{file}: {message}")]
    UnknownFormat {
        /// The path as given, whose extension was not recognised.
        file: String,
        /// The unknown extension (or its absence) and the list of known ones.
        message: String,
    },
    /// A writer was handed a mesh it cannot write (indices out of range,
    /// non-finite positions, colours that do not match the vertices, or a
    /// format that cannot hold it).
    #[error("{file}: cannot write this mesh: {message}")]
    InvalidMesh {
        /// The destination path that was not written.
        file: String,
        /// What makes the mesh unwritable, e.g. which face or vertex is at fault.
        message: String,
    },
    /// The operating system failed to read, create, write or rename a file.
    #[error("{file}: {action}: {source}")]
    Io {
        /// The path being read or written (for writes, the destination,
        /// not the temporary file).
        file: String,
        /// What was being attempted, e.g. `"cannot read the file"`.
        action: &'static str,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
}

impl IoError {
    /// True when the input was at fault (malformed content, an unknown
    /// extension, an unwritable mesh), false for a failure of the system
    /// such as a permission error or a full disk. Command-line tools exit
    /// with status 2 on bad input.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, IoError::Io { .. })
    }

    /// The file name the error is about.
    pub fn file(&self) -> &str {
        match self {
            IoError::Line { file, .. }
            | IoError::Byte { file, .. }
            | IoError::Content { file, .. }
            | IoError::UnknownFormat { file, .. }
            | IoError::InvalidMesh { file, .. }
            | IoError::Io { file, .. } => file,
        }
    }

    pub(crate) fn line(file: &str, line: usize, message: impl fmt::Display) -> Self {
        IoError::Line {
            file: file.to_owned(),
            line,
            message: message.to_string(),
        }
    }

    pub(crate) fn byte(file: &str, offset: usize, message: impl fmt::Display) -> Self {
        IoError::Byte {
            file: file.to_owned(),
            offset: offset as u64,
            message: message.to_string(),
        }
    }

    pub(crate) fn content(file: &str, message: impl fmt::Display) -> Self {
        IoError::Content {
            file: file.to_owned(),
            message: message.to_string(),
        }
    }

    pub(crate) fn invalid_mesh(file: &str, message: impl fmt::Display) -> Self {
        IoError::InvalidMesh {
            file: file.to_owned(),
            message: message.to_string(),
        }
    }

    pub(crate) fn io(file: &str, action: &'static str, source: std::io::Error) -> Self {
        IoError::Io {
            file: file.to_owned(),
            action,
            source,
        }
    }
}

/// Shows at most a few dozen characters of an offending token, so a
/// message about a binary file read as text stays one readable line.
pub(crate) fn show(token: &[u8]) -> String {
    const MAX: usize = 32;
    let cut = &token[..token.len().min(MAX)];
    let mut s: String = String::from_utf8_lossy(cut)
        .chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if token.len() > MAX {
        s.push('…');
    }
    s
}
