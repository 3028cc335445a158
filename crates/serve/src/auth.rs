//! Who may talk to the server: the `Host` check and the per-start token.
//!
//! Checking `Origin` against `Host` is not enough on its own: a page on
//! any web site can point its own domain name at 127.0.0.1 once it has
//! loaded (DNS rebinding), and its requests then carry
//! `Host: evil.example:PORT` and a matching `Origin`, both chosen by the
//! attacker. Two checks close that door, on every request:
//!
//! 1. **Host.** The `Host` header must be a loopback name (`localhost`,
//!    `127.0.0.1`, `[::1]`) or the address the server was bound to, with
//!    the server's port or none. A rebinding page can only send its own
//!    domain name there, because the browser writes the header from the
//!    page's address. When the server is bound to every address (`0.0.0.0`
//!    or `::`) the machine's addresses are not known in advance, so any IP
//!    literal is accepted: an IP literal cannot be rebound, since the page
//!    would then be at that address, not at the attacker's domain.
//! 2. **Token.** A random token made at every start (or fixed by the
//!    configuration, for tests and tools) must come with the request: as
//!    the `token` query parameter (the URL `holey serve` prints), as the
//!    cookie the page load sets from it (so the front end's later requests
//!    carry it without knowing it), or as `Authorization: token ...` (for
//!    scripts). This also keeps out other users and processes of the
//!    machine, and the network when the server is bound beyond loopback,
//!    which the `Host` check alone cannot.
//!
//! The token is compared in constant time, so response times say nothing
//! about how much of a guess was right.

use std::fmt;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr};

use crate::ServeError;
use crate::head::Request;

/// Bytes of OS randomness in a generated token: 192 bits, as Jupyter.
const TOKEN_BYTES: usize = 24;

/// The longest token accepted from the configuration.
const MAX_TOKEN_LEN: usize = 256;

/// A fresh token from the operating system's random source, as lowercase
/// hexadecimal.
pub fn random_token() -> Result<String, ServeError> {
    let mut bytes = [0u8; TOKEN_BYTES];
    getrandom::fill(&mut bytes).map_err(|e| {
        ServeError::Refused(format!(
            "cannot read the operating system's random source for the access token: {e}"
        ))
    })?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Whether a token given by the user can be used. It must travel in a
/// URL, a cookie and a header without escaping, so only the characters
/// URLs leave alone (`A-Z a-z 0-9 - . _ ~`) are allowed.
pub fn check_token(token: &str) -> Result<(), String> {
    if token.is_empty() {
        return Err("the token is empty".into());
    }
    if token.len() > MAX_TOKEN_LEN {
        return Err(format!(
            "the token is {} characters; at most {MAX_TOKEN_LEN}",
            token.len()
        ));
    }
    if let Some(c) = token
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || matches!(c, '-' | '.' | '_' | '~')))
    {
        return Err(format!(
            "the token contains {c:?}; use only letters, digits and - . _ ~"
        ));
    }
    Ok(())
}

/// Why a request is turned away, before any routing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// An HTTP/1.1 request without exactly one `Host` header.
    NoHost,
    /// A `Host` that is not this server's.
    ForeignHost(String),
    /// No token came with the request.
    NoToken,
    /// Tokens came, none of them this server's.
    WrongToken,
}

impl Refusal {
    /// The HTTP status: a missing `Host` is a malformed request (RFC 9112
    /// says 400); the others are refusals (403).
    pub fn status(&self) -> u16 {
        match self {
            Refusal::NoHost => 400,
            _ => 403,
        }
    }
}

impl fmt::Display for Refusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Refusal::NoHost => write!(f, "an HTTP/1.1 request must carry exactly one Host header"),
            Refusal::ForeignHost(host) => write!(
                f,
                "Host {host:?} is not this server: holey serve answers only to \
                 localhost, 127.0.0.1, [::1] or the address it was bound to, so that \
                 a web site whose domain name is pointed at this machine (DNS \
                 rebinding) cannot drive the modeler; open the URL holey serve printed"
            ),
            Refusal::NoToken => write!(
                f,
                "this server needs its access token: open the URL holey serve printed \
                 (it ends in ?token=...), or send the header `Authorization: token ...`"
            ),
            Refusal::WrongToken => write!(
                f,
                "the access token is not this server's (a new one is made at every \
                 start): open the URL holey serve printed this time"
            ),
        }
    }
}

/// What an admitted request may need in its answer.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Admitted {
    /// A `Set-Cookie` header line (with its CRLF) when the token came in
    /// the URL, so the page's later requests carry it as a cookie.
    pub set_cookie: Option<String>,
}

/// The checks every request passes (see the module's docs).
pub struct Gate {
    token: String,
    port: u16,
    bound: IpAddr,
    cookie: String,
}

impl fmt::Debug for Gate {
    /// Leaves the token out, so that logging a gate never leaks it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Gate")
            .field("port", &self.port)
            .field("bound", &self.bound)
            .field("cookie", &self.cookie)
            .finish_non_exhaustive()
    }
}

impl Gate {
    /// A gate for a server bound to `addr` (the real port, not 0) with
    /// `token`, which [`check_token`] accepted or [`random_token`] made.
    pub fn new(token: String, addr: SocketAddr) -> Gate {
        // Cookies ignore ports, so two servers on one host would overwrite
        // each other's cookie under one name.
        let cookie = format!("holey-token-{}", addr.port());
        Gate {
            token,
            port: addr.port(),
            bound: addr.ip(),
            cookie,
        }
    }

    /// The token requests must carry.
    pub fn token(&self) -> &str {
        &self.token
    }

    /// The name of the cookie that carries the token.
    pub fn cookie_name(&self) -> &str {
        &self.cookie
    }

    /// Admits a request or says why not: the `Host` first, then the token.
    pub fn admit(&self, request: &Request) -> Result<Admitted, Refusal> {
        self.check_host(request)?;
        let from_query = request.param("token");
        let from_header = request
            .headers
            .iter()
            .filter(|(k, _)| k.eq_ignore_ascii_case("authorization"))
            .filter_map(|(_, v)| {
                let (scheme, value) = v.trim().split_once(' ')?;
                scheme.eq_ignore_ascii_case("token").then(|| value.trim())
            });
        let from_cookie = request
            .headers
            .iter()
            .filter(|(k, _)| k.eq_ignore_ascii_case("cookie"))
            .flat_map(|(_, v)| v.split(';'))
            .filter_map(|pair| pair.trim().split_once('='))
            .filter(|(name, _)| *name == self.cookie)
            .map(|(_, value)| value.trim());
        let mut presented = false;
        let mut valid = false;
        for candidate in from_query.into_iter().chain(from_header).chain(from_cookie) {
            presented = true;
            // No early exit: every candidate is compared in full.
            valid |= same_secret(candidate.as_bytes(), self.token.as_bytes());
        }
        if !valid {
            return Err(if presented {
                Refusal::WrongToken
            } else {
                Refusal::NoToken
            });
        }
        let query_valid =
            from_query.is_some_and(|t| same_secret(t.as_bytes(), self.token.as_bytes()));
        Ok(Admitted {
            set_cookie: query_valid.then(|| {
                format!(
                    "Set-Cookie: {}={}; HttpOnly; SameSite=Strict; Path=/\r\n",
                    self.cookie, self.token
                )
            }),
        })
    }

    fn check_host(&self, request: &Request) -> Result<(), Refusal> {
        let mut hosts = request
            .headers
            .iter()
            .filter(|(k, _)| k.eq_ignore_ascii_case("host"))
            .map(|(_, v)| v.as_str());
        match (hosts.next(), hosts.next()) {
            (Some(host), None) if self.host_allowed(host) => Ok(()),
            (Some(host), None) => Err(Refusal::ForeignHost(host.to_owned())),
            // HTTP/1.0 predates Host; no browser sends it without one, so
            // it cannot carry a rebinding page's request.
            (None, _) if request.version == "HTTP/1.0" => Ok(()),
            _ => Err(Refusal::NoHost),
        }
    }

    /// Whether `host` (a `Host` header's value) names this server.
    pub fn host_allowed(&self, host: &str) -> bool {
        let Some((name, port)) = split_host(host) else {
            return false;
        };
        if port.is_some_and(|p| p != self.port) {
            return false;
        }
        if name.eq_ignore_ascii_case("localhost") {
            return true;
        }
        let Some(ip) = ip_literal(name) else {
            return false;
        };
        ip == IpAddr::V4(Ipv4Addr::LOCALHOST)
            || ip == IpAddr::V6(Ipv6Addr::LOCALHOST)
            || ip == self.bound
            || self.bound.is_unspecified()
    }
}

/// Splits a `Host` value into its name and port (`None` when absent);
/// `None` for anything malformed (an empty name, a bad port).
fn split_host(host: &str) -> Option<(&str, Option<u16>)> {
    let (name, port) = if host.starts_with('[') {
        // An IPv6 literal keeps its brackets: "[::1]" or "[::1]:8080".
        let close = host.find(']')?;
        let (name, rest) = host.split_at(close + 1);
        match rest {
            "" => (name, None),
            _ => (name, Some(rest.strip_prefix(':')?)),
        }
    } else {
        match host.split_once(':') {
            Some((name, port)) => (name, Some(port)),
            None => (host, None),
        }
    };
    if name.is_empty() {
        return None;
    }
    let port = match port {
        None => None,
        Some(p) if !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()) => Some(p.parse().ok()?),
        Some(_) => return None,
    };
    Some((name, port))
}

/// The address an IP literal names: dotted IPv4 or bracketed IPv6.
fn ip_literal(name: &str) -> Option<IpAddr> {
    match name.strip_prefix('[') {
        Some(inner) => inner
            .strip_suffix(']')?
            .parse::<Ipv6Addr>()
            .ok()
            .map(IpAddr::V6),
        None => name.parse::<Ipv4Addr>().ok().map(IpAddr::V4),
    }
}

/// Equality whose time depends only on the lengths, never on where the
/// first difference is, so a guesser cannot find the token a byte at a
/// time. The length itself is no secret (every generated token has the
/// same one).
fn same_secret(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut diff = 0u8;
    for (x, y) in a.iter().zip(b) {
        // black_box keeps the compiler from turning the loop into an
        // early-exit comparison.
        diff = std::hint::black_box(diff | (x ^ y));
    }
    diff == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gate(bound: [u8; 4]) -> Gate {
        Gate::new("s3cret".into(), SocketAddr::from((bound, 8080)))
    }

    fn request(headers: &[(&str, &str)], query: &[(&str, &str)]) -> Request {
        Request {
            method: "GET".into(),
            path: "/".into(),
            version: "HTTP/1.1".into(),
            query: query
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
            headers: headers
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
        }
    }

    #[test]
    fn hosts() {
        let g = gate([127, 0, 0, 1]);
        for ok in [
            "localhost",
            "localhost:8080",
            "LocalHost:8080",
            "127.0.0.1",
            "127.0.0.1:8080",
            "[::1]",
            "[::1]:8080",
        ] {
            assert!(g.host_allowed(ok), "{ok}");
        }
        for bad in [
            "",
            ":8080",
            "evil.example",
            "evil.example:8080",
            "localhost:8081",
            "localhost:",
            "localhost:80a",
            "localhost:99999",
            "localhost.:8080",
            "127.0.0.2:8080",
            "[::1",
            "[::1]8080",
            "::1",
            "[127.0.0.1]",
            "192.168.1.5:8080",
            "localhost.evil.example:8080",
        ] {
            assert!(!g.host_allowed(bad), "{bad}");
        }
        let lan = gate([192, 168, 1, 5]);
        assert!(lan.host_allowed("192.168.1.5:8080"));
        assert!(lan.host_allowed("localhost:8080"));
        assert!(!lan.host_allowed("192.168.1.6:8080"));
        let any = gate([0, 0, 0, 0]);
        assert!(any.host_allowed("192.168.1.6:8080"));
        assert!(any.host_allowed("[fe80::1]:8080"));
        assert!(!any.host_allowed("evil.example:8080"));
    }

    #[test]
    fn missing_or_repeated_host() {
        let g = gate([127, 0, 0, 1]);
        let mut r = request(&[("Authorization", "token s3cret")], &[]);
        assert_eq!(g.admit(&r), Err(Refusal::NoHost));
        r.version = "HTTP/1.0".into();
        assert!(g.admit(&r).is_ok(), "HTTP/1.0 predates Host");
        let r = request(
            &[
                ("Host", "localhost:8080"),
                ("Host", "evil.example:8080"),
                ("Authorization", "token s3cret"),
            ],
            &[],
        );
        assert_eq!(g.admit(&r), Err(Refusal::NoHost));
    }

    #[test]
    fn tokens() {
        let g = gate([127, 0, 0, 1]);
        let host = ("Host", "127.0.0.1:8080");
        assert_eq!(g.admit(&request(&[host], &[])), Err(Refusal::NoToken));
        assert_eq!(
            g.admit(&request(&[host], &[("token", "s3creT")])),
            Err(Refusal::WrongToken)
        );
        let by_query = g.admit(&request(&[host], &[("token", "s3cret")]));
        let cookie = by_query.expect("query token").set_cookie.expect("a cookie");
        assert_eq!(
            cookie,
            "Set-Cookie: holey-token-8080=s3cret; HttpOnly; SameSite=Strict; Path=/\r\n"
        );
        for header in [
            ("Authorization", "token s3cret"),
            ("authorization", "Token  s3cret "),
            ("Cookie", "a=b; holey-token-8080=s3cret; c=d"),
        ] {
            let admitted = g.admit(&request(&[host, header], &[]));
            assert_eq!(admitted, Ok(Admitted::default()), "{header:?}");
        }
        for header in [
            ("Authorization", "Bearer s3cret"),
            ("Authorization", "token s3cre"),
            ("Cookie", "holey-token-8081=s3cret"),
            ("Cookie", "holey-token-8080=s3cretx"),
        ] {
            assert!(
                g.admit(&request(&[host, header], &[])).is_err(),
                "{header:?}"
            );
        }
        // One right token among wrong ones is enough.
        let r = request(
            &[host, ("Cookie", "holey-token-8080=s3cret")],
            &[("token", "old")],
        );
        assert_eq!(g.admit(&r), Ok(Admitted::default()));
    }

    #[test]
    fn token_text() {
        let t = random_token().expect("random");
        assert_eq!(t.len(), 2 * TOKEN_BYTES);
        assert!(check_token(&t).is_ok());
        assert_ne!(t, random_token().expect("random"));
        assert!(check_token("e2e-Token_1.~").is_ok());
        for bad in ["", "a b", "a;b", "a=b", "é", &"x".repeat(MAX_TOKEN_LEN + 1)] {
            assert!(check_token(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn constant_time_equality_is_equality() {
        assert!(same_secret(b"abc", b"abc"));
        assert!(same_secret(b"", b""));
        assert!(!same_secret(b"abc", b"abd"));
        assert!(!same_secret(b"abc", b"xbc"));
        assert!(!same_secret(b"abc", b"abcd"));
    }
}
