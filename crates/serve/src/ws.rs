//! One WebSocket connection: requests in, replies and broadcasts out.
//!
//! The connection's thread alternates between reading (with a short
//! timeout) and writing what other threads queued for it (broadcasts of
//! changes other tabs made, progress of long operations), so one thread
//! per tab suffices without splitting the socket.

use std::io::{self, Cursor, Read, Write};
use std::net::TcpStream;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::Duration;

use tungstenite::{Message, WebSocket};

use crate::ops::{Out, Shared};

/// The request head the HTTP reader already consumed, then the socket.
pub struct Replay {
    head: Cursor<Vec<u8>>,
    stream: TcpStream,
}

impl Read for Replay {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        if (self.head.position() as usize) < self.head.get_ref().len() {
            return self.head.read(buf);
        }
        self.stream.read(buf)
    }
}

impl Write for Replay {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.stream.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.stream.flush()
    }
}

/// Completes the handshake and serves the socket until it closes.
pub fn serve_socket(shared: &Arc<Shared>, stream: TcpStream, head: Vec<u8>) {
    let Ok(clone) = stream.try_clone() else {
        return;
    };
    let replay = Replay {
        head: Cursor::new(head),
        stream,
    };
    let Ok(mut socket) = tungstenite::accept(replay) else {
        return;
    };
    // Short reads let queued broadcasts out promptly.
    let _ = clone.set_read_timeout(Some(Duration::from_millis(15)));
    let _ = clone.set_nodelay(true);
    let (conn, outbox) = shared.hub.join();
    shared.hello(conn);
    run(shared, conn, &mut socket, &outbox);
    shared.hub.leave(conn);
    shared.disconnected(conn);
}

fn run(shared: &Arc<Shared>, conn: u64, socket: &mut WebSocket<Replay>, outbox: &Receiver<Out>) {
    loop {
        // Everything queued goes out before the next read.
        loop {
            match outbox.try_recv() {
                Ok(Out::Text(t)) => {
                    if socket.send(Message::text(t)).is_err() {
                        return;
                    }
                }
                Ok(Out::Binary(b)) => {
                    if socket.send(Message::binary(b)).is_err() {
                        return;
                    }
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => return,
            }
        }
        match socket.read() {
            Ok(Message::Text(text)) => shared.request(conn, text.as_str()),
            Ok(Message::Binary(_)) => shared.reply_error(
                conn,
                None,
                "binary messages are not requests; upload files with POST /api/import",
            ),
            Ok(Message::Close(_)) => return,
            Ok(_) => {}
            Err(tungstenite::Error::Io(e))
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
                ) =>
            {
                // Nothing to read: pending writes may still be buffered.
                if socket.flush().is_err() {
                    return;
                }
            }
            Err(_) => return,
        }
    }
}
