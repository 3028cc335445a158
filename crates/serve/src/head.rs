//! The head of an HTTP/1.1 request, read and parsed: the request line,
//! the query and the headers. Its own room, below both the gate that
//! judges a request ([`crate::auth`]) and the server that answers it
//! ([`crate::http`]).

use std::io::{self, Read};
use std::net::TcpStream;

/// The largest request head accepted.
const MAX_HEAD: usize = 32 << 10;

/// A parsed request head.
#[derive(Debug, Default)]
pub struct Request {
    pub method: String,
    pub path: String,
    /// The protocol of the request line (`HTTP/1.1`), which decides
    /// whether a `Host` header is required.
    pub version: String,
    pub query: Vec<(String, String)>,
    pub headers: Vec<(String, String)>,
}

impl Request {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }

    pub fn param(&self, name: &str) -> Option<&str> {
        self.query
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// Whether the request comes from a page this server served (or from
    /// no page at all, like a script).
    pub fn same_origin(&self) -> bool {
        let Some(origin) = self.header("origin") else {
            return true;
        };
        let host = self.header("host").unwrap_or("");
        origin
            .strip_prefix("http://")
            .is_some_and(|rest| rest.trim_end_matches('/') == host)
    }
}

/// Reads the head. Returns it and every byte read so far (the head and
/// whatever of the body came with it), or `None` for a closed or
/// malformed connection.
pub fn read_head(stream: &mut TcpStream) -> io::Result<Option<(Request, Vec<u8>, usize)>> {
    let mut buf = Vec::with_capacity(1024);
    let mut chunk = [0u8; 4096];
    let end = loop {
        let n = stream.read(&mut chunk)?;
        if n == 0 {
            return Ok(None);
        }
        buf.extend_from_slice(&chunk[..n]);
        if let Some(p) = find(&buf, b"\r\n\r\n") {
            break p + 4;
        }
        if buf.len() > MAX_HEAD {
            return Ok(None);
        }
    };
    let head = String::from_utf8_lossy(&buf[..end]).into_owned();
    let mut lines = head.split("\r\n");
    let mut first = lines.next().unwrap_or("").split(' ');
    let method = first.next().unwrap_or("").to_owned();
    let target = first.next().unwrap_or("/");
    let version = first.next().unwrap_or("").to_owned();
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let query = query
        .split('&')
        .filter(|kv| !kv.is_empty())
        .map(|kv| {
            let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
            (percent_decode(k), percent_decode(v))
        })
        .collect();
    let headers = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_owned(), v.trim().to_owned()))
        .collect();
    Ok(Some((
        Request {
            method,
            path: percent_decode(path),
            version,
            query,
            headers,
        },
        buf,
        end,
    )))
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%'
            && let (Some(h), Some(l)) = (
                b.get(i + 1).and_then(|&c| hex(c)),
                b.get(i + 2).and_then(|&c| hex(c)),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(if b[i] == b'+' { b' ' } else { b[i] });
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_percent_and_plus() {
        assert_eq!(percent_decode("a%20b+c%2Fd"), "a b c/d");
        assert_eq!(percent_decode("bad%2"), "bad%2");
        assert_eq!(percent_decode("%zz"), "%zz");
    }

    #[test]
    fn origin_check() {
        let mut r = Request::default();
        assert!(r.same_origin());
        r.headers.push(("Host".into(), "127.0.0.1:9000".into()));
        r.headers
            .push(("Origin".into(), "http://127.0.0.1:9000".into()));
        assert!(r.same_origin());
        r.headers[1].1 = "http://evil.example".into();
        assert!(!r.same_origin());
    }
}
