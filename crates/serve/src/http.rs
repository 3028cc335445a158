//! A small HTTP/1.1 server: one request per connection (static files,
//! upload, download, health) or a WebSocket upgrade. Every answer closes
//! the connection, which keeps the reader simple and bounded.
//!
//! Every request first passes [`crate::auth::Gate`]: its `Host` must name
//! this server and it must carry the access token (see [`crate::auth`] for
//! why both). Requests that change the document (uploads, the WebSocket)
//! must also come from a page of this server: a foreign `Origin` is
//! refused, so another web site open in the same browser cannot drive the
//! modeler.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use serde_json::json;

use crate::auth::{Admitted, Refusal};
use crate::head::{Request, read_head};
use crate::ops::Shared;

/// Writes a whole response and closes.
pub fn respond(stream: &mut TcpStream, status: u16, content_type: &str, extra: &str, body: &[u8]) {
    let reason = match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        409 => "Conflict",
        411 => "Length Required",
        413 => "Payload Too Large",
        _ => "Error",
    };
    // The page's URL carries the access token: no-referrer keeps it out of
    // the Referer of anything the page links to.
    let head = format!(
        "HTTP/1.1 {status} {reason}\r\nContent-Type: {content_type}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nReferrer-Policy: no-referrer\r\n{extra}Connection: close\r\n\r\n",
        body.len()
    );
    // A browser that went away is not an error worth reporting.
    let _ = stream.write_all(head.as_bytes());
    let _ = stream.write_all(body);
    let _ = stream.flush();
}

fn respond_json(stream: &mut TcpStream, status: u16, value: &serde_json::Value) {
    respond(
        stream,
        status,
        "application/json",
        "",
        value.to_string().as_bytes(),
    );
}

fn error(stream: &mut TcpStream, status: u16, message: &str) {
    respond_json(stream, status, &json!({"ok": false, "error": message}));
}

/// Serves one connection.
pub fn handle_connection(shared: &Arc<Shared>, mut stream: TcpStream) {
    // A client that stops sending mid-head must not hold a thread forever.
    let _ = stream.set_read_timeout(Some(Duration::from_secs(30)));
    let Ok(Some((request, buf, head_end))) = read_head(&mut stream) else {
        return;
    };
    let admitted = match shared.gate.admit(&request) {
        Ok(admitted) => admitted,
        Err(refusal) => return refuse(&mut stream, &request, &refusal, buf.len() - head_end),
    };
    let upgrade = request
        .header("upgrade")
        .is_some_and(|u| u.eq_ignore_ascii_case("websocket"));
    match (request.method.as_str(), request.path.as_str()) {
        ("GET", "/ws") if upgrade => {
            if !request.same_origin() {
                error(&mut stream, 403, "WebSocket from a foreign origin refused");
                return;
            }
            crate::ws::serve_socket(shared, stream, buf);
        }
        ("GET", "/api/health") => respond_json(&mut stream, 200, &json!({"ok": true})),
        ("GET", "/api/export") => export(shared, &mut stream, &request),
        ("POST", "/api/import") => import(shared, &mut stream, &request, &buf[head_end..]),
        ("GET" | "HEAD", _) => static_file(shared, &mut stream, &request, &admitted),
        _ => error(&mut stream, 405, "method not allowed"),
    }
}

/// Answers a request the gate turned away: JSON for the API and the
/// WebSocket (what their callers parse), plain text for a page a person
/// opened. A body the client is still sending is drained (see [`linger`]).
fn refuse(stream: &mut TcpStream, request: &Request, refusal: &Refusal, body_read: usize) {
    let message = refusal.to_string();
    if request.path.starts_with("/api/") || request.path == "/ws" {
        error(stream, refusal.status(), &message);
    } else {
        let text = format!("holey serve: {message}\n");
        respond(
            stream,
            refusal.status(),
            "text/plain; charset=utf-8",
            "",
            text.as_bytes(),
        );
    }
    let length = request
        .header("content-length")
        .and_then(|l| l.parse::<usize>().ok())
        .unwrap_or(0);
    if length > body_read {
        linger(stream, length - body_read);
    }
}

fn export(shared: &Arc<Shared>, stream: &mut TcpStream, request: &Request) {
    let format = request.param("format").unwrap_or("obj");
    match shared.export(format) {
        Ok((bytes, file)) => respond(
            stream,
            200,
            "application/octet-stream",
            &format!("Content-Disposition: attachment; filename=\"{file}\"\r\n"),
            &bytes,
        ),
        Err(e) => error(stream, 400, &e.to_string()),
    }
}

fn import(shared: &Arc<Shared>, stream: &mut TcpStream, request: &Request, started: &[u8]) {
    if !request.same_origin() {
        return error(stream, 403, "upload from a foreign origin refused");
    }
    let name = request.param("name").unwrap_or("upload.obj").to_owned();
    let Some(length) = request
        .header("content-length")
        .and_then(|l| l.parse::<usize>().ok())
    else {
        return error(stream, 411, "the upload needs a Content-Length");
    };
    let limit = shared.config.max_upload;
    if length > limit {
        error(
            stream,
            413,
            &format!(
                "{name} is {} MiB; the upload limit is {} MiB (holey serve --max-upload)",
                length.div_ceil(1 << 20),
                limit >> 20
            ),
        );
        return linger(stream, length.saturating_sub(started.len()));
    }
    let mut body = Vec::with_capacity(length);
    body.extend_from_slice(&started[..started.len().min(length)]);
    let mut rest = (&mut *stream).take((length - body.len()) as u64);
    if rest.read_to_end(&mut body).is_err() || body.len() != length {
        return error(stream, 400, "the upload ended early");
    }
    match shared.import(&name, &body) {
        Ok(message) => respond_json(stream, 200, &json!({"ok": true, "message": message})),
        Err(e) => error(stream, 400, &e.to_string()),
    }
}

/// Most of a refused body read and dropped after the refusal.
const LINGER_BYTES: usize = 64 << 20;

/// Closes a connection whose client is still sending a body we refused:
/// closing with unread data makes the kernel reset the connection, and
/// the reset can destroy the refusal before the client reads it (the
/// client sees a broken connection instead of the reason). So the
/// response is followed by a half-close and the body, up to `pending`
/// bytes (at most [`LINGER_BYTES`]), is read and dropped, each read
/// waiting at most two seconds.
fn linger(stream: &mut TcpStream, pending: usize) {
    let _ = stream.shutdown(std::net::Shutdown::Write);
    let _ = stream.set_read_timeout(Some(Duration::from_secs(2)));
    let mut left = pending.min(LINGER_BYTES);
    let mut scratch = [0u8; 16 << 10];
    while left > 0 {
        match stream.read(&mut scratch[..left.min(16 << 10)]) {
            Ok(0) | Err(_) => break,
            Ok(n) => left -= n,
        }
    }
}

fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "html" => "text/html; charset=utf-8",
        "js" | "mjs" => "text/javascript",
        "css" => "text/css",
        "json" | "map" => "application/json",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "ico" => "image/x-icon",
        "wasm" => "application/wasm",
        _ => "application/octet-stream",
    }
}

/// A file of the built front end: from `--web DIR` when given (front-end
/// development), else the copy embedded at build time. Paths never leave
/// the web directory.
///
/// A page opened with the token in its URL gets the token back as a
/// cookie, so its scripts, assets and WebSocket carry it.
fn static_file(
    shared: &Arc<Shared>,
    stream: &mut TcpStream,
    request: &Request,
    admitted: &Admitted,
) {
    let cookie = admitted.set_cookie.as_deref().unwrap_or("");
    let relative = request.path.trim_start_matches('/');
    let relative = if relative.is_empty() {
        "index.html"
    } else {
        relative
    };
    let rel = Path::new(relative);
    if rel.components().any(|c| !matches!(c, Component::Normal(_))) {
        return error(stream, 400, "bad path");
    }
    let Some(root) = shared.config.web_dir.as_ref() else {
        if let Some(bytes) = crate::embedded::file(relative) {
            let body: &[u8] = if request.method == "HEAD" { &[] } else { bytes };
            return respond(stream, 200, content_type(rel), cookie, body);
        }
        if relative == "index.html" {
            return respond(
                stream,
                200,
                "text/html; charset=utf-8",
                cookie,
                NOT_BUILT.as_bytes(),
            );
        }
        return error(
            stream,
            404,
            &format!("{relative}: not found (front end not built)"),
        );
    };
    let path: PathBuf = root.join(rel);
    match std::fs::read(&path) {
        Ok(bytes) => {
            let body: &[u8] = if request.method == "HEAD" {
                &[]
            } else {
                &bytes
            };
            respond(stream, 200, content_type(&path), cookie, body)
        }
        Err(_) => error(stream, 404, &format!("{relative}: not found")),
    }
}

const NOT_BUILT: &str = "<!doctype html><meta charset=utf-8><title>holey</title>\
<h1>holey serve</h1><p>The server is running, but the browser front end is not built.\
 From the repository, run:</p><pre>npm --prefix web ci\nnpm --prefix web run build</pre>\
<p>then rebuild holey (<code>cargo build --release</code> embeds it) or pass <code>--web web/dist</code>.</p>";
