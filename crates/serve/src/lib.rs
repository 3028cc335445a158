//! # holey-serve: the server of the interactive modeler
//!
//! `holey serve` runs this: one **document** (a mesh, its workspace, undo
//! and redo), edited by any number of browser tabs over a WebSocket. The
//! browser front end lives in `web/`; the wire format is `web/PROTOCOL.md`.
//!
//! - [`http`]: a small HTTP/1.1 reader for static files, uploads, downloads
//!   and the WebSocket upgrade. Loopback by default.
//! - [`frame`]: binary mesh frames (display indices and the kernel handles
//!   behind them).
//! - [`doc`]: the document, workspaces and undo.
//! - [`ops`]: what each request does, long operations with progress and
//!   cancellation, strokes fed one mouse event at a time.
//! - [`persist`]: autosave after every change (atomic writes) and restore
//!   at start, so a crash or restart loses no work.
//!
//! Requests are applied one at a time under the document's lock, and a
//! request names the version of the picture it was made on, so two tabs
//! cannot corrupt the session: the second of two conflicting requests is
//! refused with a message, never applied to the wrong faces.

pub mod doc;
pub mod frame;
pub mod http;
pub mod ops;
pub mod persist;
pub mod ws;

use std::net::{IpAddr, SocketAddr, TcpListener};
use std::path::PathBuf;
use std::sync::Arc;

/// A connection's number, unique for the server's life.
pub type ConnId = u64;

/// How the server runs.
#[derive(Clone, Debug)]
pub struct Config {
    pub host: IpAddr,
    /// 0 picks a free port.
    pub port: u16,
    /// Where the session is saved and restored from.
    pub state_dir: PathBuf,
    /// The built front end (`web/dist`); `None` serves a page saying how
    /// to build it.
    pub web_dir: Option<PathBuf>,
    /// Largest accepted upload, in bytes.
    pub max_upload: usize,
    /// Largest number of faces a tool may produce.
    pub max_faces: usize,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            host: IpAddr::from([127, 0, 0, 1]),
            port: 8080,
            state_dir: PathBuf::from("holey-session"),
            web_dir: None,
            max_upload: 256 << 20,
            max_faces: 4_000_000,
        }
    }
}

/// Why a request or the server failed.
#[derive(Debug, thiserror::Error)]
pub enum ServeError {
    /// The request is not possible now; the message is for the user.
    #[error("{0}")]
    Refused(String),
    /// The request itself is malformed.
    #[error("bad request: {0}")]
    BadRequest(String),
    #[error("{0}")]
    Sculpt(#[from] holey_sculpt::SculptError),
    #[error("cancelled")]
    Cancelled,
    #[error("{what}: {source}")]
    Io {
        what: String,
        source: std::io::Error,
    },
}

impl ServeError {
    pub(crate) fn io(what: impl Into<String>, source: std::io::Error) -> ServeError {
        ServeError::Io {
            what: what.into(),
            source,
        }
    }
}

/// A bound server, before it serves.
pub struct Server {
    listener: TcpListener,
    shared: Arc<ops::Shared>,
}

impl Server {
    /// Binds the address and restores the last session from the state
    /// directory (a fresh cube when there is none). Returns the server and
    /// a note about the restore for the terminal.
    pub fn bind(config: Config) -> Result<(Server, String), ServeError> {
        let (doc, note) = persist::restore(&config.state_dir)?;
        let addr = SocketAddr::new(config.host, config.port);
        let listener = TcpListener::bind(addr)
            .map_err(|e| ServeError::io(format!("cannot bind {addr}"), e))?;
        let shared = ops::Shared::new(config, doc);
        Ok((Server { listener, shared }, note))
    }

    /// The address it listens on (with the port chosen when 0 was asked).
    pub fn local_addr(&self) -> Result<SocketAddr, ServeError> {
        self.listener
            .local_addr()
            .map_err(|e| ServeError::io("cannot read the bound address", e))
    }

    /// Serves until the process ends: one thread per connection.
    pub fn run(self) -> Result<(), ServeError> {
        for stream in self.listener.incoming() {
            let Ok(stream) = stream else { continue };
            let shared = Arc::clone(&self.shared);
            std::thread::spawn(move || http::handle_connection(&shared, stream));
        }
        Ok(())
    }
}
