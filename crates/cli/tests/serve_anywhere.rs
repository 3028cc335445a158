//! `holey serve` from a directory outside the repository, without
//! `--web`: the modeler's page and assets come from the front end embedded
//! in the binary at build time (issue 17: the modeler from a plain build).

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The status line and body of `GET path` with the token.
fn get(port: u16, path: &str, token: &str) -> (String, Vec<u8>) {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).expect("connect to holey serve");
    let sep = if path.contains('?') { '&' } else { '?' };
    write!(
        stream,
        "GET {path}{sep}token={token} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n"
    )
    .expect("send the request");
    let mut reply = Vec::new();
    stream.read_to_end(&mut reply).expect("read the reply");
    let split = reply
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&reply[..split]).into_owned();
    let status = head.lines().next().unwrap_or("").to_owned();
    (status, reply[split + 4..].to_vec())
}

#[test]
fn serves_the_embedded_front_end_from_any_directory() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let token = "serve-anywhere-test-token";
    let mut child = Command::new(env!("CARGO_BIN_EXE_holey"))
        .args(["serve", "--port", "0", "--token", token, "--state-dir"])
        .arg(dir.path().join("state"))
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start holey serve");
    let stdout = child.stdout.take().expect("its stdout");
    let server = Server(child);
    let mut port = None;
    for line in BufReader::new(stdout).lines().map_while(Result::ok) {
        if let Some(rest) = line.split("http://127.0.0.1:").nth(1) {
            port = rest.split('/').next().and_then(|p| p.parse::<u16>().ok());
            break;
        }
    }
    let port = port.expect("holey serve printed its address");
    let (status, page) = get(port, "/", token);
    assert!(status.contains("200"), "{status}");
    let page = String::from_utf8_lossy(&page).into_owned();
    if page.contains("front end is not built") {
        println!("SKIP: this binary was built without npm, so it embeds no front end");
        drop(server);
        return;
    }
    assert!(
        page.contains("<script"),
        "the page is the modeler's: {page}"
    );
    // The script the page loads is served too.
    let script = page
        .split("src=\"./")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .expect("index.html names its script");
    let (status, body) = get(port, &format!("/{script}"), token);
    assert!(
        status.contains("200") && body.len() > 1000,
        "{status}: {} bytes",
        body.len()
    );
    drop(server);
}
