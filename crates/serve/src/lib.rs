//! # holey-serve: the server of the interactive modeler
//!
//! `holey serve` runs this: one **document** (a mesh, its workspace, undo
//! and redo), edited by any number of browser tabs over a WebSocket. The
//! browser front end lives in `web/`; the wire format is `web/PROTOCOL.md`.
//!
//! - [`http`]: a small HTTP/1.1 reader for static files, uploads, downloads
//!   and the WebSocket upgrade. Loopback by default.
//! - [`auth`]: what every request must show: a `Host` naming this server
//!   (against DNS rebinding) and the access token made at every start.
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

pub mod auth;
pub mod doc;
pub mod embedded;
pub mod frame;
pub mod head;
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
#[derive(Clone)]
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
    /// The access token every request must carry (see [`auth`]); `None`
    /// makes a random one at every start, which is what users want. A
    /// fixed one is for tests and tools that must know it in advance; it
    /// must pass [`auth::check_token`].
    pub token: Option<String>,
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
            token: None,
        }
    }
}

impl std::fmt::Debug for Config {
    /// Says whether a token is fixed but never prints it, so that logging
    /// a configuration does not leak the key to the session.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Config")
            .field("host", &self.host)
            .field("port", &self.port)
            .field("state_dir", &self.state_dir)
            .field("web_dir", &self.web_dir)
            .field("max_upload", &self.max_upload)
            .field("max_faces", &self.max_faces)
            .field("token", &self.token.as_ref().map(|_| "(fixed, not shown)"))
            .finish()
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
        let token = match &config.token {
            Some(token) => {
                auth::check_token(token).map_err(ServeError::BadRequest)?;
                token.clone()
            }
            None => auth::random_token()?,
        };
        let (doc, note) = persist::restore(&config.state_dir)?;
        let addr = SocketAddr::new(config.host, config.port);
        let listener = TcpListener::bind(addr)
            .map_err(|e| ServeError::io(format!("cannot bind {addr}"), e))?;
        // The gate needs the port really bound (config.port may be 0).
        let bound = listener
            .local_addr()
            .map_err(|e| ServeError::io("cannot read the bound address", e))?;
        let gate = auth::Gate::new(token, bound);
        let shared = ops::Shared::new(config, gate, doc);
        Ok((Server { listener, shared }, note))
    }

    /// The address it listens on (with the port chosen when 0 was asked).
    pub fn local_addr(&self) -> Result<SocketAddr, ServeError> {
        self.listener
            .local_addr()
            .map_err(|e| ServeError::io("cannot read the bound address", e))
    }

    /// The access token requests must carry.
    pub fn token(&self) -> &str {
        self.shared.gate.token()
    }

    /// The URL to open: the page with the token, which the page load turns
    /// into a cookie. A server bound to every address (`0.0.0.0`, `::`) is
    /// given its loopback address, which is certain to reach it from here.
    pub fn url(&self) -> Result<String, ServeError> {
        let mut addr = self.local_addr()?;
        if addr.ip().is_unspecified() {
            addr.set_ip(match addr.ip() {
                IpAddr::V4(_) => IpAddr::from([127, 0, 0, 1]),
                IpAddr::V6(_) => IpAddr::from(std::net::Ipv6Addr::LOCALHOST),
            });
        }
        Ok(format!("http://{addr}/?token={}", self.token()))
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
