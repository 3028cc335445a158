//! The server end to end over real sockets: a WebSocket client per "tab",
//! HTTP uploads and downloads, restart from the autosave.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

use holey_serve::{Config, Server};
use serde_json::{Value, json};
use tungstenite::client::IntoClientRequest;
use tungstenite::{Message, WebSocket, stream::MaybeTlsStream};

type Socket = WebSocket<MaybeTlsStream<TcpStream>>;

/// The token the tests' servers are given (`Config::token`), so that their
/// requests can carry it.
const TOKEN: &str = "test-token-0123456789abcdef";

fn start(dir: &std::path::Path, max_upload: usize) -> SocketAddr {
    start_with(Config {
        port: 0,
        state_dir: dir.to_path_buf(),
        max_upload,
        token: Some(TOKEN.into()),
        ..Config::default()
    })
}

fn start_with(config: Config) -> SocketAddr {
    let (server, _) = Server::bind(config).expect("bind");
    let addr = server.local_addr().expect("addr");
    std::thread::spawn(move || server.run());
    addr
}

/// A server on a fresh state directory, which lives as long as the
/// returned guard.
fn server() -> (tempfile::TempDir, SocketAddr) {
    let dir = tempfile::tempdir().expect("tempdir");
    let addr = start(dir.path(), 1 << 20);
    (dir, addr)
}

/// A server on a fresh state directory, and one tab on it. The directory
/// lives as long as the returned guard.
fn session() -> (tempfile::TempDir, SocketAddr, Tab) {
    let (dir, addr) = server();
    let tab = Tab::open(addr);
    (dir, addr, tab)
}

/// [`session`] with the document made the primitive `spec` first.
fn tab_on(spec: &str) -> (tempfile::TempDir, SocketAddr, Tab) {
    let (dir, addr, mut tab) = session();
    tab.ok(json!({"op": "primitive", "spec": spec}));
    (dir, addr, tab)
}

/// A browser tab: it remembers the last state and counts frames.
struct Tab {
    socket: Socket,
    next: u64,
    state: Value,
    frames: Vec<Vec<u8>>,
}

impl Tab {
    fn open(addr: SocketAddr) -> Tab {
        let (socket, _) =
            tungstenite::connect(format!("ws://{addr}/ws?token={TOKEN}")).expect("connect");
        // A message that never comes fails the test instead of hanging it.
        if let MaybeTlsStream::Plain(stream) = socket.get_ref() {
            stream
                .set_read_timeout(Some(Duration::from_secs(150)))
                .expect("a read timeout");
        }
        let mut tab = Tab {
            socket,
            next: 0,
            state: Value::Null,
            frames: Vec::new(),
        };
        // The greeting: a state and a frame.
        while tab.frames.is_empty() || tab.state.is_null() {
            tab.pump_one();
        }
        tab
    }

    /// Reads one message; returns it if it is a reply.
    fn pump_one(&mut self) -> Option<Value> {
        match self.socket.read().expect("read") {
            Message::Text(t) => {
                let v: Value = serde_json::from_str(t.as_str()).expect("json");
                match v["type"].as_str() {
                    Some("state") => {
                        self.state = v;
                        None
                    }
                    Some("ok" | "error") => Some(v),
                    _ => None,
                }
            }
            Message::Binary(b) => {
                self.frames.push(b.to_vec());
                None
            }
            _ => None,
        }
    }

    /// Sends a request under the next id; returns the id.
    fn send(&mut self, mut req: Value) -> u64 {
        self.next += 1;
        req["id"] = json!(self.next);
        self.socket
            .send(Message::text(req.to_string()))
            .expect("send");
        self.next
    }

    /// Waits for the reply to request `id`.
    fn reply_to(&mut self, id: u64, within: Duration) -> Value {
        let deadline = Instant::now() + within;
        loop {
            assert!(Instant::now() < deadline, "no reply to request {id}");
            if let Some(v) = self.pump_one()
                && v["id"] == json!(id)
            {
                return v;
            }
        }
    }

    /// Sends a request and waits for its reply.
    fn call(&mut self, req: Value) -> Value {
        let stroke_frame = req["op"] == "stroke_frame";
        let id = self.send(req);
        let reply = self.reply_to(id, Duration::from_secs(120));
        // A stroke frame is answered first, and its frame follows at once
        // (the page sends its next dabs while it reads the frame).
        if stroke_frame && reply["type"] == "ok" {
            let n = self.frames.len();
            assert_eq!(self.pump_one(), None, "the frame follows the answer");
            assert_eq!(self.frames.len(), n + 1, "the frame follows the answer");
        }
        reply
    }

    /// Starts a long operation and cancels it at once: its reply must be
    /// an error saying it was cancelled.
    fn start_and_cancel(&mut self, req: Value) {
        let id = self.send(req);
        self.send(json!({"op": "cancel"}));
        let v = self.reply_to(id, Duration::from_secs(60));
        assert_eq!(v["type"], "error", "{v}");
        assert_eq!(v["cancelled"], true, "{v}");
    }

    fn ok(&mut self, req: Value) -> Value {
        let r = self.call(req.clone());
        assert_eq!(r["type"], "ok", "{req} -> {r}");
        r
    }

    /// Sends a request that must be refused with a message saying
    /// `says`; returns the message.
    fn refused(&mut self, req: Value, says: &str) -> String {
        let r = self.call(req.clone());
        assert_eq!(r["type"], "error", "{req} -> {r}");
        let m = r["message"].as_str().unwrap_or("").to_owned();
        assert!(m.contains(says), "{req}: {m:?} does not say {says:?}");
        m
    }

    fn genus(&self) -> Value {
        self.state["stats"]["genus"].clone()
    }
}

/// Whether a reply's message says `what`.
fn says(reply: &Value, what: &str) -> bool {
    reply["message"].as_str().unwrap_or("").contains(what)
}

/// Sends a request and reads the whole answer: status, head, body.
fn exchange(addr: SocketAddr, head: &str, body: &[u8]) -> (u16, String, Vec<u8>) {
    let mut s = TcpStream::connect(addr).expect("connect");
    s.write_all(head.as_bytes()).expect("write");
    let _ = s.write_all(body);
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text = String::from_utf8_lossy(&out);
    let status = text
        .split(' ')
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body_at = out
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .map_or(out.len(), |p| p + 4);
    let head = String::from_utf8_lossy(&out[..body_at]).into_owned();
    (status, head, out[body_at..].to_vec())
}

fn http(addr: SocketAddr, head: &str, body: &[u8]) -> (u16, Vec<u8>) {
    let (status, _, body) = exchange(addr, head, body);
    (status, body)
}

/// `GET target` as a script with the token asks it: status and body.
fn get(addr: SocketAddr, target: &str) -> (u16, Vec<u8>) {
    http(
        addr,
        &format!("GET {target} HTTP/1.1\r\nHost: {addr}\r\n{}\r\n", auth()),
        &[],
    )
}

/// The header that carries the token for a script.
fn auth() -> String {
    format!("Authorization: token {TOKEN}\r\n")
}

fn upload(addr: SocketAddr, name: &str, body: &[u8]) -> (u16, Value) {
    let head = format!(
        "POST /api/import?name={name} HTTP/1.1\r\nHost: {addr}\r\n{}Content-Length: {}\r\n\r\n",
        auth(),
        body.len()
    );
    let (status, body) = http(addr, &head, body);
    (status, serde_json::from_slice(&body).unwrap_or(Value::Null))
}

#[test]
fn modeling_sculpting_undo_and_two_tabs() {
    let (_dir, addr, mut a) = session();
    let mut b = Tab::open(addr);
    assert_eq!(a.genus(), 0, "a new session is a cube");

    a.ok(json!({"op": "primitive", "spec": "@torus"}));
    assert_eq!(a.genus(), 1);
    // The other tab hears about it.
    while b.state["stats"]["genus"] != 1 {
        b.pump_one();
    }

    a.ok(json!({"op": "primitive", "spec": "@tetrahedron"}));
    a.ok(json!({"op": "sierpinski", "level": 1}));
    assert_eq!(a.genus(), 3, "Sierpinski level 1 of a tetrahedron");

    // The true Menger sponge of level 2 has genus 81 (level 3: 1409, as
    // the shared data's sponge); the closed form is the oracle.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    a.ok(json!({"op": "menger", "level": 2, "exact": true}));
    let (v, e, f, g) = holey_model::menger::exact_counts(2).expect("counts");
    assert_eq!(g, 81);
    assert_eq!(a.genus(), json!(g));
    assert_eq!(a.state["stats"]["vertices"], json!(v));
    assert_eq!(a.state["stats"]["edges"], json!(e));
    assert_eq!(a.state["stats"]["faces"], json!(f));

    // A selection made on an older picture is refused, not misapplied.
    let stale = a.state["version"].as_u64().expect("version") - 1;
    let r = a.call(json!({"op": "delete_edge", "version": stale, "edge": 0}));
    assert_eq!(r["type"], "error");
    assert!(says(&r, "changed"), "{r}");

    // Handle between two faces of a cube: genus 1, preview first.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    let v = a.state["version"].clone();
    let frames = a.frames.len();
    let p = a.ok(
        json!({"op": "handle", "version": v, "faces": [0, 5], "segments": 3,
                        "w1": -1, "w2": -1, "preview": true}),
    );
    assert_eq!(p["preview"], true);
    assert_eq!(a.genus(), 0, "a preview does not commit");
    assert!(a.frames.len() > frames, "the preview frame was sent");
    a.ok(
        json!({"op": "handle", "version": v, "faces": [0, 5], "segments": 3,
                "w1": -1, "w2": -1}),
    );
    assert_eq!(a.genus(), 1);
    a.ok(json!({"op": "undo"}));
    assert_eq!(a.genus(), 0);
    a.ok(json!({"op": "redo"}));
    assert_eq!(a.genus(), 1);

    // Rind: a crust of a cube with two punched faces has genus 1.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    a.ok(json!({"op": "rind_begin", "thickness": 0.2}));
    assert_eq!(a.state["mode"], "rind");
    for face in [0, 1] {
        let v = a.state["version"].clone();
        a.ok(json!({"op": "rind_punch", "version": v, "face": face}));
    }
    a.ok(json!({"op": "rind_end", "commit": true}));
    assert_eq!(a.genus(), 1, "{}", a.state);

    // Sculpt: grab the top of a sphere down through the bottom.
    a.ok(json!({"op": "primitive", "spec": "@sphere"}));
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    a.ok(
        json!({"op": "stroke_begin", "brush": "grab", "radius": 0.5, "strength": 1,
                "point": [0, 0, 1]}),
    );
    // While a tab drags, the other cannot edit.
    let r = b.call(json!({"op": "undo"}));
    assert!(says(&r, "busy"), "{r}");
    for z in [0.5, -0.5, -1.6] {
        let r = a.ok(json!({"op": "stroke_frame", "point": [0, 0, z]}));
        assert!(r["ms"].as_f64().is_some());
    }
    a.ok(json!({"op": "stroke_end"}));
    assert_eq!(a.genus(), 1, "poke-through makes a tunnel: {}", a.state);
    assert_eq!(a.state["stats"]["closed"], true);
    a.ok(json!({"op": "undo"}));
    assert_eq!(a.genus(), 0);

    // The detail slider remeshes where the brush goes: finer at 1.
    let before = a.state["stats"]["triangles"].as_u64().expect("triangles");
    a.ok(json!({"op": "set_remesh", "detail": 1.0}));
    assert_eq!(a.state["remesh"]["detail"], 1.0);
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.4, "strength": 0.01,
                "point": [0, 0, 1]}),
    );
    a.ok(json!({"op": "stroke_frame", "point": [0, 0, 1]}));
    a.ok(json!({"op": "stroke_end"}));
    let after = a.state["stats"]["triangles"].as_u64().expect("triangles");
    assert!(after > before, "remeshed finer: {before} -> {after}");
    assert_eq!(a.genus(), 0);
    assert_eq!(a.state["stats"]["closed"], true);
}

#[test]
fn bad_requests_get_clear_errors() {
    let (_dir, _, mut a) = session();
    for (req, says) in [
        (json!({"op": "nope"}), "unknown op"),
        (json!({}), "no \"op\""),
        (json!({"op": "primitive", "spec": "@nosuch"}), "@nosuch"),
        (
            json!({"op": "primitive"}),
            "\"primitive\" request: missing field \"spec\"",
        ),
        (
            json!({"op": "handle", "faces": [0, 1], "segments": "four"}),
            "\"handle\" request, field \"segments\": invalid type",
        ),
        (
            json!({"op": "stroke_frame", "point": [0, 0]}),
            "\"stroke_frame\" request, field \"point\"",
        ),
        (
            json!({"op": "delete_edge", "edge": 99999}),
            "does not exist",
        ),
        (
            json!({"op": "insert_edge", "corners": [[0, 7], [0]]}),
            "corners",
        ),
        (
            json!({"op": "stroke_begin", "brush": "grab", "radius": 1, "strength": 1,
                "point": [0, 0, 0]}),
            "sculpt workspace",
        ),
        (json!({"op": "sierpinski", "level": 99}), "allows"),
        (
            json!({"op": "workspace", "workspace": "paint"}),
            "unknown workspace",
        ),
        (json!({"op": "cancel"}), "nothing to cancel"),
        (json!({"op": "undo"}), "nothing to undo"),
        (json!({"op": "rind_begin", "thickness": -1}), "rind"),
    ] {
        a.refused(req.clone(), says);
    }
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    let r = a.call(json!({"op": "stroke_begin", "brush": "grab", "radius": 0.1,
                          "strength": 1, "point": [9, 9, 9]}));
    assert!(says(&r, "from the surface"), "{r}");
    let r = a.call(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.28,
                          "strength": 0.3, "point": [0, 0, 1]}),
    );
    assert!(says(&r, "of the radius"), "{r}");
    let r = a.call(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.1,
                          "strength": 1, "point": [0, "x", 0]}),
    );
    assert!(says(&r, "point"), "{r}");
    // Malformed JSON is answered, and the connection stays usable.
    a.socket.send(Message::text("{not json")).expect("send");
    let mut got = None;
    while got.is_none() {
        got = a.pump_one();
    }
    assert_eq!(got.expect("reply")["type"], "error");
    a.ok(json!({"op": "primitives"}));
}

/// The document exported as glTF (both forms), 3MF and STL, which hold
/// triangles: each comes back with the torus's vertices and genus, its
/// quads split in two.
#[test]
fn exports_and_imports_gltf_3mf_and_stl() {
    let (_dir, addr, mut a) = tab_on("@torus");
    let torus = a.state["stats"].clone();
    let triangles = torus["triangles"].clone();
    assert_eq!(
        triangles,
        json!(2 * torus["faces"].as_u64().expect("faces"))
    );
    for (format, magic) in [
        ("glb", &b"glTF"[..]),
        ("gltf", b"{"),
        ("3mf", b"PK\x03\x04"),
        ("stl", b""),
    ] {
        let (status, head, body) = exchange(
            addr,
            &format!(
                "GET /api/export?format={format} HTTP/1.1\r\nHost: {addr}\r\n{}\r\n",
                auth()
            ),
            &[],
        );
        assert_eq!(status, 200, "{format}");
        assert!(
            head.contains(&format!("filename=\"holey.{format}\"")),
            "{head}"
        );
        assert!(body.starts_with(magic), "{format}");
        a.ok(json!({"op": "primitive", "spec": "@cube"}));
        let (status, r) = upload(addr, &format!("back.{format}"), &body);
        assert_eq!(status, 200, "{format}: {r}");
        while a.state["stats"]["faces"] != triangles {
            a.pump_one();
        }
        let back = &a.state["stats"];
        assert_eq!(back["vertices"], torus["vertices"], "{format}");
        assert_eq!(back["genus"], json!(1), "{format}");
        assert_eq!(back["closed"], json!(true), "{format}");
    }
    // A malformed file is refused with what is wrong with it.
    let (status, r) = upload(addr, "bad.glb", b"GLTF and more");
    assert_eq!(status, 400);
    let error = r["error"].as_str().unwrap_or("");
    assert!(error.starts_with("bad.glb: byte 0: not a GLB file"), "{r}");
    let (status, r) = upload(addr, "bad.3mf", b"not a zip");
    assert_eq!(status, 400);
    assert!(
        r["error"]
            .as_str()
            .unwrap_or("")
            .contains("not a readable ZIP archive"),
        "{r}"
    );
    let (status, body) = get(addr, "/api/export?format=fbx");
    assert_eq!(status, 400);
    assert!(String::from_utf8_lossy(&body).contains("glb"));
}

#[test]
fn uploads_downloads_limits_and_restart() {
    let (dir, addr, mut a) = session();

    // A torus exported as OBJ comes back with the same counts and genus.
    a.ok(json!({"op": "primitive", "spec": "@torus"}));
    let stats = a.state["stats"].clone();
    let (status, obj) = get(addr, "/api/export?format=obj");
    assert_eq!(status, 200);
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    let (status, r) = upload(addr, "back.obj", &obj);
    assert_eq!(status, 200, "{r}");
    while a.state["stats"] != stats {
        a.pump_one();
    }
    // The same through the DLFL format.
    let (status, dlfl) = get(addr, "/api/export?format=dlfl");
    assert_eq!(status, 200);
    let (status, _) = upload(addr, "back.dlfl", &dlfl);
    assert_eq!(status, 200);

    // Too big, unknown format, malformed, foreign origin.
    let (status, r) = upload(addr, "big.obj", &vec![b' '; (1 << 20) + 1]);
    assert_eq!(status, 413);
    assert!(r["error"].as_str().unwrap_or("").contains("limit"), "{r}");
    let (status, r) = upload(addr, "mesh.xyz", b"v 0 0 0");
    assert_eq!(status, 400);
    assert!(
        r["error"].as_str().unwrap_or("").contains("unknown format"),
        "{r}"
    );
    let (status, r) = upload(addr, "bad.obj", b"v 0 0 nan\nf 1 2 3\n");
    assert_eq!(status, 400, "{r}");
    let (status, r) = upload(addr, "empty.obj", b"garbage\n");
    assert_eq!(status, 400, "{r}");
    let (status, _) = http(
        addr,
        &format!(
            "POST /api/import?name=x.obj HTTP/1.1\r\nHost: {addr}\r\n{}Origin: http://evil.example\r\nContent-Length: 0\r\n\r\n",
            auth()
        ),
        &[],
    );
    assert_eq!(status, 403);
    let (status, _) = get(addr, "/../../etc/passwd");
    assert_ne!(status, 200);
    // A non-manifold soup opens in the sculpt workspace.
    let fan = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0.5\nf 1 2 3\nf 1 2 4\nf 1 2 5\n";
    let (status, r) = upload(addr, "fan.obj", fan);
    assert_eq!(status, 200, "{r}");
    while a.state["workspace"] != "sculpt" {
        a.pump_one();
    }
    assert_eq!(a.state["stats"]["faces"], 3);

    // Restart: the autosave restores the last document.
    let r = a.call(json!({"op": "workspace", "workspace": "model"}));
    assert!(says(&r, "2-manifold"), "{r}");
    drop(a);
    let deadline = Instant::now() + Duration::from_secs(20);
    let meta = dir.path().join("session.json");
    loop {
        let saved = std::fs::read_to_string(&meta).unwrap_or_default();
        if saved.contains("sculpt") {
            break;
        }
        assert!(Instant::now() < deadline, "no autosave: {saved}");
        std::thread::sleep(Duration::from_millis(50));
    }
    let again = start(dir.path(), 1 << 20);
    let b = Tab::open(again);
    assert_eq!(b.state["workspace"], "sculpt");
    assert_eq!(b.state["stats"]["faces"], 3);
}

#[test]
fn long_operations_report_progress_and_cancel() {
    let (_dir, _, mut a) = tab_on("@cube");
    a.start_and_cancel(json!({"op": "subdivide", "scheme": "catmull-clark", "levels": 8}));
    assert_eq!(
        a.state["stats"]["faces"], 6,
        "a cancelled operation changes nothing"
    );
    // The server is usable again at once.
    let r = a.ok(json!({"op": "subdivide", "scheme": "doo-sabin", "levels": 1}));
    assert!(says(&r, "faces"));
    assert_eq!(a.genus(), 0);
}

/// The repairs: an unwelded soup (two triangles of a square, corners
/// repeated and one nudged by 1e-6 of the size) welded into one piece,
/// and a bow tie (two triangles touching at a vertex, non-manifold) that
/// the model workspace refuses until Make manifold splits its vertex.
#[test]
fn weld_and_make_manifold_repair_what_the_model_refuses() {
    let (_dir, addr, mut a) = session();
    let soup = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1.000001 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n";
    let (status, r) = upload(addr, "soup.obj", soup);
    assert_eq!(status, 200, "{r}");
    while a.state["stats"]["components"] != 2 {
        a.pump_one();
    }
    // In the model workspace, welding the shared corner would pinch it.
    let r = a.call(json!({"op": "weld", "distance": 0}));
    assert_eq!(r["type"], "error");
    assert!(!says(&r, "--"), "{r}");
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    // Identical positions only: the nudged corner stays apart.
    a.ok(json!({"op": "weld", "distance": 0}));
    assert_eq!(a.state["stats"]["vertices"], 5, "{}", a.state);
    // Within 1e-4 of the diagonal: one square.
    let r = a.ok(json!({"op": "weld", "distance": 1e-4}));
    assert!(says(&r, "welded 1"), "{r}");
    assert_eq!(a.state["stats"]["vertices"], 4);
    assert_eq!(a.state["stats"]["components"], 1);
    let r = a.call(json!({"op": "weld", "distance": -1}));
    assert_eq!(r["type"], "error");

    let bowtie = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n";
    let (status, r) = upload(addr, "bowtie.obj", bowtie);
    assert_eq!(status, 200, "{r}");
    while a.state["workspace"] != "sculpt" {
        a.pump_one();
    }
    let r = a.call(json!({"op": "workspace", "workspace": "model"}));
    assert_eq!(r["type"], "error");
    let msg = r["message"].as_str().unwrap_or("");
    assert!(
        msg.contains("Make manifold") && !msg.contains("--"),
        "{msg}"
    );
    a.ok(json!({"op": "make_manifold"}));
    a.ok(json!({"op": "workspace", "workspace": "model"}));
    assert_eq!(a.state["stats"]["components"], 2);
    a.ok(json!({"op": "undo"}));
    a.ok(json!({"op": "undo"}));
    assert_eq!(a.state["stats"]["components"], 1, "the bow tie is back");
}

// ---- issue 17: DNS rebinding and the access token ---------------------------

/// A tetrahedron: a valid upload that replaces the session's cube.
const TETRAHEDRON: &[u8] =
    b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// The document as OBJ, asked for properly: what "the model" is.
fn model(addr: SocketAddr) -> Vec<u8> {
    let (status, body) = get(addr, "/api/export?format=obj");
    assert_eq!(status, 200);
    body
}

/// Sends a WebSocket upgrade and reads only the answer's head: an accepted
/// upgrade keeps the connection open, so reading to the end would wait
/// for ever.
fn upgrade(addr: SocketAddr, host: &str, extra: &str) -> String {
    let mut s = TcpStream::connect(addr).expect("connect");
    let head = format!(
        "GET /ws HTTP/1.1\r\nHost: {host}\r\nOrigin: http://{host}\r\nUpgrade: websocket\r\n\
         Connection: Upgrade\r\nSec-WebSocket-Version: 13\r\n\
         Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n{extra}\r\n"
    );
    s.write_all(head.as_bytes()).expect("write");
    let mut out = Vec::new();
    let mut byte = [0u8; 1];
    while !out.ends_with(b"\r\n\r\n") {
        match s.read(&mut byte) {
            Ok(1) => out.push(byte[0]),
            _ => break,
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The refusals before were the Host's or the token's doing, not the
/// body's: the same upload with this server's Host and the token goes
/// through and changes the model.
fn upload_goes_through(addr: SocketAddr, before: &[u8]) {
    let (status, _) = http(addr, &import_head(&addr.to_string(), &auth()), TETRAHEDRON);
    assert_eq!(status, 200);
    assert_ne!(model(addr), before);
}

fn import_head(host: &str, extra: &str) -> String {
    format!(
        "POST /api/import?name=t.obj HTTP/1.1\r\nHost: {host}\r\nOrigin: http://{host}\r\n{extra}\
         Content-Length: {}\r\n\r\n",
        TETRAHEDRON.len()
    )
}

/// A page whose domain was pointed at 127.0.0.1 after it loaded sends its
/// own name as Host and a matching Origin. Every request of it is refused:
/// the page, the WebSocket (no 101) and an upload (the model is unchanged).
/// The requests carry the token, which such a page would not have, so that
/// only the Host check can refuse them.
#[test]
fn dns_rebinding_host_is_refused() {
    let (_dir, addr) = server();
    let port = addr.port();
    let evil = format!("evil.example:{port}");
    let before = model(addr);

    let (status, _, body) = exchange(
        addr,
        &format!(
            "GET / HTTP/1.1\r\nHost: {evil}\r\nOrigin: http://{evil}\r\n{}\r\n",
            auth()
        ),
        &[],
    );
    let text = String::from_utf8_lossy(&body);
    assert_eq!(status, 403, "{text}");
    assert!(
        text.contains("evil.example") && text.contains("DNS rebinding"),
        "{text}"
    );

    let answer = upgrade(addr, &evil, &auth());
    assert!(answer.starts_with("HTTP/1.1 403"), "{answer}");

    let (status, body) = http(addr, &import_head(&evil, &auth()), TETRAHEDRON);
    assert_eq!(status, 403, "{}", String::from_utf8_lossy(&body));
    assert_eq!(model(addr), before, "the refused upload changed the model");

    // HTTP/1.1 without a Host is malformed; HTTP/1.0 predates Host.
    let (status, _) = http(
        addr,
        &format!("GET /api/health HTTP/1.1\r\n{}\r\n", auth()),
        &[],
    );
    assert_eq!(status, 400);
    let (status, _) = http(
        addr,
        &format!("GET /api/health HTTP/1.0\r\n{}\r\n", auth()),
        &[],
    );
    assert_eq!(status, 200);
    // The loopback names with this port or none are this server; another
    // port, or the loopback name under another domain, is not.
    for (host, expected) in [
        (format!("localhost:{port}"), 200),
        (format!("127.0.0.1:{port}"), 200),
        (format!("[::1]:{port}"), 200),
        ("localhost".to_owned(), 200),
        (format!("localhost:{}", port.wrapping_add(1)), 403),
        (format!("localhost.evil.example:{port}"), 403),
    ] {
        let (status, _) = http(
            addr,
            &format!("GET /api/health HTTP/1.1\r\nHost: {host}\r\n{}\r\n", auth()),
            &[],
        );
        assert_eq!(status, expected, "Host: {host}");
    }

    upload_goes_through(addr, &before);
}

/// With the right Host but no token (or a wrong one), the API and the
/// WebSocket are refused; the token as a query parameter, a cookie or an
/// `Authorization` header lets them through.
#[test]
fn api_and_socket_need_the_token() {
    let (_dir, addr) = server();
    let host = addr.to_string();
    let port = addr.port();
    let before = model(addr);

    for path in ["/api/export?format=obj", "/api/health", "/"] {
        let (status, body) = http(
            addr,
            &format!("GET {path} HTTP/1.1\r\nHost: {host}\r\n\r\n"),
            &[],
        );
        let text = String::from_utf8_lossy(&body);
        assert_eq!(status, 403, "{path}: {text}");
        assert!(text.contains("token"), "{path}: {text}");
    }
    let answer = upgrade(addr, &host, "");
    assert!(answer.starts_with("HTTP/1.1 403"), "{answer}");
    let (status, _) = http(addr, &import_head(&host, ""), TETRAHEDRON);
    assert_eq!(status, 403);
    assert_eq!(model(addr), before, "the refused upload changed the model");

    // A wrong token, one character off, by each way it can come.
    let wrong = format!("{}X", &TOKEN[..TOKEN.len() - 1]);
    for (query, extra) in [
        (format!("&token={wrong}"), String::new()),
        (String::new(), format!("Authorization: token {wrong}\r\n")),
        (
            String::new(),
            format!("Cookie: holey-token-{port}={wrong}\r\n"),
        ),
        // The right token under another server's cookie name.
        (String::new(), format!("Cookie: holey-token-1={TOKEN}\r\n")),
    ] {
        let (status, _) = http(
            addr,
            &format!("GET /api/export?format=obj{query} HTTP/1.1\r\nHost: {host}\r\n{extra}\r\n"),
            &[],
        );
        assert_eq!(status, 403, "{query}{extra}");
        if query.is_empty() {
            let answer = upgrade(addr, &host, &extra);
            assert!(answer.starts_with("HTTP/1.1 403"), "{extra}: {answer}");
        }
    }

    // The right token, by each way it can come.
    for (query, extra) in [
        (format!("&token={TOKEN}"), String::new()),
        (String::new(), auth()),
        (
            String::new(),
            format!("Cookie: a=b; holey-token-{port}={TOKEN}\r\n"),
        ),
    ] {
        let (status, body) = http(
            addr,
            &format!("GET /api/export?format=obj{query} HTTP/1.1\r\nHost: {host}\r\n{extra}\r\n"),
            &[],
        );
        assert_eq!(status, 200, "{query}{extra}");
        assert_eq!(body, before);
    }
    let (_, response) = tungstenite::connect(format!("ws://{addr}/ws?token={TOKEN}")).expect("ws");
    assert_eq!(response.status(), 101);
    for (name, value) in [
        ("Authorization", format!("token {TOKEN}")),
        ("Cookie", format!("holey-token-{port}={TOKEN}")),
    ] {
        let mut request = format!("ws://{addr}/ws")
            .into_client_request()
            .expect("request");
        request
            .headers_mut()
            .insert(name, value.parse().expect("header value"));
        let (_, response) = tungstenite::connect(request).expect("ws");
        assert_eq!(response.status(), 101, "{name}");
    }
    upload_goes_through(addr, &before);
}

/// Opening the URL `holey serve` prints sets the cookie (HttpOnly,
/// SameSite=Strict, Path=/), and that cookie alone then carries the
/// page's assets, API calls and WebSocket, as a browser would send it.
#[test]
fn the_page_load_sets_the_cookie() {
    let dir = tempfile::tempdir().expect("tempdir");
    let web = tempfile::tempdir().expect("tempdir");
    std::fs::write(web.path().join("index.html"), "<!doctype html>page").expect("write");
    std::fs::create_dir(web.path().join("assets")).expect("mkdir");
    std::fs::write(web.path().join("assets/app.js"), "app()").expect("write");
    let addr = start_with(Config {
        port: 0,
        state_dir: dir.path().to_path_buf(),
        web_dir: Some(web.path().to_path_buf()),
        token: Some(TOKEN.into()),
        ..Config::default()
    });
    let port = addr.port();

    let (status, head, body) = exchange(
        addr,
        &format!("GET /?token={TOKEN} HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
        &[],
    );
    assert_eq!(status, 200, "{head}");
    assert_eq!(body, b"<!doctype html>page");
    let set_cookie = head
        .lines()
        .find_map(|l| l.strip_prefix("Set-Cookie: "))
        .unwrap_or_else(|| panic!("no cookie set: {head}"));
    let mut parts = set_cookie.split("; ");
    let pair = parts.next().unwrap_or("");
    assert_eq!(pair, format!("holey-token-{port}={TOKEN}"));
    let attributes: Vec<&str> = parts.collect();
    for attribute in ["HttpOnly", "SameSite=Strict", "Path=/"] {
        assert!(attributes.contains(&attribute), "{set_cookie}");
    }
    // The URL carries the token: keep it out of Referer headers.
    assert!(head.contains("Referrer-Policy: no-referrer"), "{head}");

    // The cookie alone, as the browser sends it with the page's requests.
    let cookie = format!("Cookie: {pair}\r\n");
    for path in ["/assets/app.js", "/api/health", "/api/export?format=off"] {
        let (status, _) = http(
            addr,
            &format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\n{cookie}\r\n"),
            &[],
        );
        assert_eq!(status, 200, "{path}");
        let (status, _) = http(
            addr,
            &format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
            &[],
        );
        assert_eq!(status, 403, "{path} without the cookie");
    }
    let mut request = format!("ws://{addr}/ws")
        .into_client_request()
        .expect("request");
    request
        .headers_mut()
        .insert("Cookie", pair.parse().expect("header value"));
    let (_, response) = tungstenite::connect(request).expect("ws");
    assert_eq!(response.status(), 101);

    // Requests that did not bring the token in the URL set no cookie.
    let (status, head, _) = exchange(
        addr,
        &format!("GET / HTTP/1.1\r\nHost: {addr}\r\n{cookie}\r\n"),
        &[],
    );
    assert_eq!(status, 200);
    assert!(!head.contains("Set-Cookie"), "{head}");
}

/// Without a fixed token every start makes its own from the OS random
/// source (at least 128 bits), the printed URL carries it, and one
/// server's token opens nothing on another. A fixed token must be text a
/// URL and a cookie carry unchanged.
#[test]
fn a_random_token_at_every_start() {
    let dirs = [(); 2].map(|_| tempfile::tempdir().expect("tempdir"));
    let servers = dirs.each_ref().map(|dir| {
        let (server, _) = Server::bind(Config {
            port: 0,
            state_dir: dir.path().to_path_buf(),
            ..Config::default()
        })
        .expect("bind");
        server
    });
    let tokens = servers.each_ref().map(|s| s.token().to_owned());
    for (server, token) in servers.iter().zip(&tokens) {
        assert!(token.len() >= 32, "{token}");
        assert!(token.bytes().all(|b| b.is_ascii_hexdigit()), "{token}");
        let addr = server.local_addr().expect("addr");
        assert_eq!(
            server.url().expect("url"),
            format!("http://{addr}/?token={token}")
        );
    }
    assert_ne!(tokens[0], tokens[1]);
    let addrs = servers.map(|server| {
        let addr = server.local_addr().expect("addr");
        std::thread::spawn(move || server.run());
        addr
    });
    for (addr, token, expected) in [
        (addrs[0], &tokens[0], 200),
        (addrs[0], &tokens[1], 403),
        (addrs[1], &tokens[1], 200),
        (addrs[1], &tokens[0], 403),
    ] {
        let (status, _) = http(
            addr,
            &format!("GET /api/health?token={token} HTTP/1.1\r\nHost: {addr}\r\n\r\n"),
            &[],
        );
        assert_eq!(status, expected);
    }

    for bad in ["", "two words", "a;b"] {
        let refused = Server::bind(Config {
            port: 0,
            state_dir: dirs[0].path().to_path_buf(),
            token: Some(bad.into()),
            ..Config::default()
        });
        assert!(refused.is_err(), "{bad:?}");
    }
}

/// V, E, F of the stats a tab last received.
fn vef(tab: &Tab) -> [u64; 3] {
    let s = &tab.state["stats"];
    [
        s["vertices"].as_u64().unwrap_or(u64::MAX),
        s["edges"].as_u64().unwrap_or(u64::MAX),
        s["faces"].as_u64().unwrap_or(u64::MAX),
    ]
}

/// TopMod's toolbox over the socket (issue 18): remeshing schemes,
/// extrusion, wireframe and columns, cuts and truncation, the tools and
/// the selection queries, each checked against counts worked out from
/// its definition, and undone.
#[test]
fn toolbox_requests_change_the_counts_their_definitions_give() {
    let (_dir, _, mut a) = session();
    let listed = a.ok(json!({"op": "remesh_schemes"}));
    assert_eq!(
        listed["schemes"].as_array().map(Vec::len),
        Some(holey_subdiv::RemeshScheme::ALL.len())
    );

    // The cube, V E F = 8 12 6, C = 24 corners, every vertex of valence 3.
    let (v, e, f, c) = (8u64, 12u64, 6u64, 24u64);
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    assert_eq!(vef(&a), [v, e, f]);
    for (scheme, params, want) in [
        // The dual swaps vertices and faces.
        ("dual", json!({}), [f, e, v]),
        // Every corner cut off: V' = 2E, E' = E + C, F' = F + V.
        ("vertex-truncation", json!({}), [2 * e, e + c, f + v]),
        // A centroid per face joined to its corners: V + F, E + C, C.
        ("stellate", json!({}), [v + f, e + c, c]),
        // Doo–Sabin's connectivity: V' = C, E' = 2C, F' = F + E + V.
        (
            "corner-cutting",
            json!({"corner_cutting_alpha": 0.7}),
            [c, 2 * c, f + e + v],
        ),
        // Each face shrunk to a copy, each vertex a 2d-gon: C, E + C, F + V.
        ("honeycomb", json!({}), [c, e + c, f + v]),
    ] {
        a.ok(json!({"op": "remesh", "scheme": scheme, "params": params}));
        assert_eq!(vef(&a), want, "{scheme}");
        assert_eq!(a.genus(), 0, "{scheme}");
        a.ok(json!({"op": "undo"}));
        assert_eq!(vef(&a), [v, e, f], "undo of {scheme}");
    }
    // Two levels of the dual give the cube back.
    a.ok(json!({"op": "remesh", "scheme": "dual", "levels": 2}));
    assert_eq!(vef(&a), [v, e, f]);

    // √3 and Loop of a tetrahedron (4 6 4): 8 18 12, and V+E, 2E+3F, 4F.
    a.ok(json!({"op": "primitive", "spec": "@tetrahedron"}));
    a.ok(json!({"op": "remesh", "scheme": "sqrt3"}));
    assert_eq!(vef(&a), [8, 18, 12]);
    a.ok(json!({"op": "undo"}));
    a.ok(json!({"op": "remesh", "scheme": "loop"}));
    assert_eq!(vef(&a), [4 + 6, 2 * 6 + 3 * 4, 4 * 4]);

    // A plain extrusion of one quad adds 4/8/4 and answers the new top;
    // extruding that top again adds 4/8/4 more.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    let version = a.state["version"].clone();
    let r = a.ok(json!({"op": "extrude", "version": version, "faces": [0],
                        "kind": "plain", "distance": 0.5, "scale": 0.8, "rotation": 10}));
    assert_eq!(vef(&a), [v + 4, e + 8, f + 4]);
    let top = r["faces"].as_array().expect("faces").clone();
    assert_eq!(top.len(), 1, "{r}");
    assert_eq!(r["version"], a.state["version"]);
    a.ok(json!({"op": "extrude", "version": r["version"], "faces": top, "count": 2}));
    assert_eq!(vef(&a), [v + 12, e + 24, f + 12]);
    // Two neighbouring quads together: b = 6 boundary sides, +6/+12/+6.
    a.ok(json!({"op": "primitive", "spec": "@cube:2"}));
    let [v2, e2, f2] = vef(&a);
    let grown = a.ok(json!({"op": "select", "query": "face-loop", "faces": [0]}));
    let strip = grown["faces"].as_array().expect("faces").clone();
    assert_eq!(strip.len(), 8, "a face loop around @cube:2: {grown}");
    let pair = a.ok(json!({"op": "select", "query": "face-loop", "faces": [0]}))["faces"]
        .as_array()
        .map(|s| vec![s[0].clone(), s[1].clone()])
        .expect("faces");
    a.ok(json!({"op": "extrude", "faces": pair, "kind": "together", "distance": 0.3}));
    assert_eq!(vef(&a), [v2 + 6, e2 + 12, f2 + 6]);

    // The wireframe of the cube: V' = 4E, E' = 10E, F' = 4E + 2V, genus
    // E − V + 1; columns of 4 sides have the same genus.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    a.ok(json!({"op": "wireframe", "thickness": 0.1}));
    assert_eq!(vef(&a), [4 * e, 10 * e, 4 * e + 2 * v]);
    assert_eq!(a.genus(), json!(e - v + 1));
    a.ok(json!({"op": "undo"}));
    a.ok(json!({"op": "wireframe", "thickness": 0.1, "columns": 4}));
    assert_eq!(a.genus(), json!(e - v + 1));
    a.ok(json!({"op": "undo"}));

    // A cube corner cut off: +2/+3/+1; every vertex truncated: the
    // truncated cube 24/36/14.
    let version = a.state["version"].clone();
    let r = a.ok(json!({"op": "cut", "version": version, "vertices": [0], "distance": 0.3}));
    assert_eq!(vef(&a), [v + 2, e + 3, f + 1]);
    assert_eq!(r["faces"].as_array().map(Vec::len), Some(1), "{r}");
    a.ok(json!({"op": "undo"}));
    a.ok(json!({"op": "truncate", "all": true, "fraction": 0.25}));
    assert_eq!(vef(&a), [24, 36, 14]);
    a.ok(json!({"op": "undo"}));
    // An edge of the cube (valences 3 and 3): +2/+3/+1.
    a.ok(json!({"op": "truncate", "edges": [0], "fraction": 0.25}));
    assert_eq!(vef(&a), [v + 2, e + 3, f + 1]);
    a.ok(json!({"op": "undo"}));

    // Tools move vertices or merge, counts as documented.
    a.ok(json!({"op": "tool", "tool": "spherical"}));
    assert_eq!(vef(&a), [v, e, f]);
    a.ok(json!({"op": "tool", "tool": "planarize"}));
    let r = a.ok(json!({"op": "tool", "tool": "cleanup"}));
    assert!(says(&r, "0 two-gons"), "{r}");

    // Selection queries on a 2×2-per-side cube (24 quads).
    a.ok(json!({"op": "primitive", "spec": "@cube:2"}));
    let faces = |r: &Value| r["faces"].as_array().map(Vec::len).unwrap_or(0);
    let edges = |r: &Value| r["edges"].as_array().map(Vec::len).unwrap_or(0);
    let r = a.ok(json!({"op": "select", "query": "invert", "faces": [0]}));
    assert_eq!(faces(&r), 23);
    let r = a.ok(json!({"op": "select", "query": "similar", "faces": [0]}));
    assert_eq!(faces(&r), 24);
    let r = a.ok(json!({"op": "select", "query": "edge-ring", "edges": [0]}));
    assert_eq!(edges(&r), 8, "{r}");
    let r = a.ok(json!({"op": "select", "query": "grow", "faces": [0]}));
    let g = r["faces"].clone();
    let r = a.ok(json!({"op": "select", "query": "shrink", "faces": g}));
    assert_eq!(r["faces"], json!([0]));
    assert_eq!(vef(&a), [26, 48, 24], "queries change nothing");
    // Valence-3 corners make an odd cycle of faces; a torus of 8 × 6
    // quads has none, and half its faces take each colour.
    let r = a.call(json!({"op": "select", "query": "checkerboard"}));
    assert!(says(&r, "2-coloured"), "{r}");
    a.ok(json!({"op": "primitive", "spec": "@torus:8:6"}));
    let r = a.ok(json!({"op": "select", "query": "checkerboard"}));
    assert_eq!(faces(&r), 24, "{r}");
}

#[test]
fn toolbox_refusals_are_clear_and_change_nothing() {
    let (_dir, _, mut a) = tab_on("@plane");
    let open = vef(&a);
    for (req, says) in [
        (json!({"op": "remesh", "scheme": "dual"}), "boundary"),
        (
            json!({"op": "remesh", "scheme": "nope"}),
            "unknown remeshing scheme",
        ),
        (json!({"op": "remesh"}), "\"scheme\""),
        (
            json!({"op": "remesh", "scheme": "corner-cutting", "params": {"alpha": 1}}),
            "corner_cutting_alpha",
        ),
        (
            json!({"op": "remesh", "scheme": "vertex-truncation",
                   "params": {"vertex_truncation_offset": 0.9}}),
            "(0, 0.5]",
        ),
        (
            json!({"op": "remesh", "scheme": "loop", "levels": 9}),
            "levels",
        ),
        (json!({"op": "extrude", "faces": []}), "select the faces"),
        (json!({"op": "extrude", "faces": [99999]}), "does not exist"),
        (
            json!({"op": "extrude", "faces": [0], "kind": "sideways"}),
            "unknown kind",
        ),
        (json!({"op": "extrude", "faces": [0], "scale": 0}), "scale"),
        (
            json!({"op": "extrude", "faces": "all"}),
            "\"extrude\" request, field \"faces\"",
        ),
        (json!({"op": "wireframe", "thickness": -1}), "thickness"),
        (json!({"op": "wireframe"}), "\"thickness\""),
        (
            json!({"op": "wireframe", "thickness": 0.1, "columns": 2}),
            "columns",
        ),
        (json!({"op": "cut", "distance": 0.1}), "select the vertices"),
        (
            json!({"op": "cut", "vertices": [0], "distance": 99}),
            "middle of edge",
        ),
        (json!({"op": "cut", "vertices": [0]}), "\"distance\""),
        (
            json!({"op": "truncate", "edges": [99999], "fraction": 0.2}),
            "does not exist",
        ),
        (json!({"op": "tool", "tool": "melt"}), "unknown tool"),
        (
            json!({"op": "tool", "tool": "split-valence-2", "distance": -1}),
            "distance",
        ),
        (
            json!({"op": "select", "query": "edge-loop"}),
            "select one or more edges",
        ),
        (json!({"op": "select", "query": "zigzag"}), "unknown query"),
        (
            json!({"op": "select", "query": "grow", "version": 1}),
            "changed since",
        ),
    ] {
        a.refused(req.clone(), says);
        assert_eq!(vef(&a), open, "{req} changed the mesh");
    }
    // An error naming a face names it by the number the page shows: face
    // 1 of a tetrahedron is a triangle, so no face loop passes through it.
    a.ok(json!({"op": "primitive", "spec": "@tetrahedron"}));
    let r = a.call(json!({"op": "select", "query": "face-loop", "faces": [1]}));
    assert_eq!(
        r["message"],
        "face-loop: face 1 is not a quadrilateral, so a face loop cannot pass through it",
        "{r}"
    );
    // The sculpt workspace has no toolbox.
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    let r = a.call(json!({"op": "extrude", "faces": [0]}));
    assert!(says(&r, "model workspace"), "{r}");
    let r = a.call(json!({"op": "remesh", "scheme": "loop"}));
    assert!(says(&r, "model workspace"), "{r}");
}

#[test]
fn a_long_remesh_reports_progress_and_cancels() {
    let (_dir, _, mut a) = tab_on("@cube");
    a.start_and_cancel(json!({"op": "remesh", "scheme": "loop", "levels": 8}));
    assert_eq!(vef(&a), [8, 12, 6], "a cancelled remesh changes nothing");
    let r = a.ok(json!({"op": "remesh", "scheme": "loop", "levels": 2}));
    assert!(says(&r, "faces"), "{r}");
}

/// The convex hull and TopMod's dual convex hull (issue 18): one undo
/// step each, a flat mesh refused with the document unchanged.
#[test]
fn hull_and_dual_hull_replace_the_mesh_and_undo() {
    let (_dir, _, mut a) = tab_on("@cube");
    let (v, e, f) = (8u64, 12u64, 6u64);
    assert_eq!(vef(&a), [v, e, f]);
    // The cube's half side h, from the picture.
    let h = showing(&a)
        .positions
        .iter()
        .flatten()
        .fold(0f32, |m, c| m.max(c.abs()));
    assert!(h > 0.0);

    // The hull of a convex polyhedron's corners is itself.
    a.ok(json!({"op": "hull"}));
    assert_eq!(vef(&a), [v, e, f]);
    a.ok(json!({"op": "undo"}));

    // The dual hull: one face per hull corner (F* = V = 8); on a regular
    // polyhedron it is the polar dual, so V* = F = 6 and E* = E = 12: an
    // octahedron, genus 0 (6 − 12 + 8 = 2).
    let before = a.state["version"].clone();
    let r = a.ok(json!({"op": "hull", "dual": true}));
    assert!(says(&r, "dual convex hull"), "{r}");
    assert_eq!(vef(&a), [f, e, v]);
    assert_eq!(a.genus(), 0);
    assert_eq!(a.state["can_undo"], true);
    // The plane at the corner (h, h, h) is normal to (1, 1, 1): x + y + z
    // = 3h, which meets the axes at 3h; so every corner of the octahedron
    // lies on an axis, 3h from the centre.
    let oct = showing(&a);
    assert_eq!(oct.positions.len(), 6);
    for p in &oct.positions {
        let mut m: Vec<f32> = p.iter().map(|c| c.abs()).collect();
        m.sort_by(f32::total_cmp);
        assert!(m[0] < 1e-4 * h && m[1] < 1e-4 * h, "{p:?} is off the axes");
        assert!((m[2] - 3.0 * h).abs() < 1e-4 * h, "{p:?} is not 3h out");
    }
    // One undo step brings back the cube.
    a.ok(json!({"op": "undo"}));
    assert_eq!(vef(&a), [v, e, f]);
    assert!(a.state["version"].as_u64() > before.as_u64());
    a.ok(json!({"op": "redo"}));
    assert_eq!(vef(&a), [f, e, v]);

    // A flat mesh bounds no solid: refused in one error, nothing changed.
    a.ok(json!({"op": "primitive", "spec": "@plane"}));
    let flat = vef(&a);
    let version = a.state["version"].clone();
    let frames = a.frames.len();
    for dual in [false, true] {
        let r = a.call(json!({"op": "hull", "dual": dual}));
        assert_eq!(r["type"], "error", "{r}");
        assert_eq!(r["cancelled"], false, "{r}");
        let m = r["message"].as_str().unwrap_or("");
        assert!(m.contains("one plane"), "{m:?}");
        assert!(
            m.starts_with(if dual {
                "dual convex hull: "
            } else {
                "convex hull: "
            }),
            "{m:?}"
        );
        assert_eq!(vef(&a), flat);
        assert_eq!(a.state["version"], version);
        assert_eq!(a.state["busy"], Value::Null);
    }
    assert_eq!(a.frames.len(), frames, "a refusal sends no mesh");
    a.refused(json!({"op": "hull", "dual": "yes"}), "field \"dual\"");
    // The hull belongs to the model workspace, like the other whole-mesh tools.
    a.ok(json!({"op": "primitive", "spec": "@cube"}));
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    let r = a.call(json!({"op": "hull", "dual": true}));
    assert!(says(&r, "model workspace"), "{r}");
}

// ---- the sculpt workspace of issue 19: masks and the new stroke fields ----

/// What a whole frame carries that these tests read: its flags, the
/// positions (f32) and the sculpt mask (flag bit 4), if any.
struct Decoded {
    flags: u32,
    positions: Vec<[f32; 3]>,
    mask: Option<Vec<u8>>,
}

fn decode(b: &[u8]) -> Decoded {
    let word = |i: usize| u32::from_le_bytes(b[4 * i..4 * i + 4].try_into().expect("word"));
    assert_eq!(&b[..4], b"HMSH");
    let flags = word(2);
    assert_eq!(flags & 4, 0, "a whole frame, not positions only");
    let [nv, nt, ne] = [word(4), word(5), word(6)].map(|n| n as usize);
    let positions = (0..nv)
        .map(|v| {
            std::array::from_fn(|c| {
                let at = 32 + 12 * v + 4 * c;
                f32::from_le_bytes(b[at..at + 4].try_into().expect("f32"))
            })
        })
        .collect();
    let pad = |n: usize| n.div_ceil(4) * 4;
    let mut at = 32 + 12 * nv + 12 * nt + 4 * nt + 8 * ne;
    if flags & 2 != 0 {
        at += pad(nv);
    }
    let mask = (flags & 16 != 0).then(|| b[at..at + nv].to_vec());
    assert_eq!(b.len(), at + if flags & 16 != 0 { pad(nv) } else { 0 });
    Decoded {
        flags,
        positions,
        mask,
    }
}

/// What a tab shows: its last whole (not positions-only, not patch)
/// frame's flags and sculpt mask, at the positions every frame since
/// (positions only, sparse, patches, the commit) left, as a page applies
/// them ([`Shown::take`]).
fn showing(tab: &Tab) -> Decoded {
    let (whole, shown) = shown_since_whole(tab);
    let mut d = decode(&tab.frames[whole]);
    d.positions = shown
        .positions
        .iter()
        .map(|p| p.map(f32::from_bits))
        .collect();
    d
}

/// The index of a tab's last whole frame (not positions-only, not a
/// patch), and what the tab shows after it and every frame since.
fn shown_since_whole(tab: &Tab) -> (usize, Shown) {
    let flags = |f: &Vec<u8>| u32::from_le_bytes(f[8..12].try_into().expect("flags"));
    let whole = tab
        .frames
        .iter()
        .rposition(|f| flags(f) & (4 | 32) == 0)
        .expect("a whole frame");
    let mut shown = Shown::default();
    for f in &tab.frames[whole..] {
        shown.take(f);
    }
    (whole, shown)
}

/// The sculpt mask of a whole frame as flags (none masked without one).
fn masked_flags(d: &Decoded) -> Vec<bool> {
    match &d.mask {
        Some(m) => m.iter().map(|&b| b == 1).collect(),
        None => vec![false; d.positions.len()],
    }
}

fn dist(a: [f32; 3], b: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| (f64::from(a[i]) - b[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// A new tab whose document is `@sphere:3` (642 vertices on the unit
/// sphere) in the sculpt workspace, remeshing at `detail`.
fn sculpt_sphere_at(addr: SocketAddr, detail: f64) -> Tab {
    let mut a = Tab::open(addr);
    a.ok(json!({"op": "primitive", "spec": "@sphere:3"}));
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    a.ok(json!({"op": "set_remesh", "detail": detail}));
    a
}

/// A fresh sculpt session on `@sphere:3` with dynamic remeshing off, so
/// vertex numbers stay.
fn sculpt_sphere(addr: SocketAddr) -> Tab {
    let a = sculpt_sphere_at(addr, 0.0);
    assert_eq!(a.state["stats"]["vertices"], 642);
    a
}

#[test]
fn mask_paint_invert_clear_and_masked_vertices_never_move() {
    let (dir, addr) = server();
    let mut a = sculpt_sphere(addr);
    let start = showing(&a);
    assert!(start.mask.is_none(), "nothing masked at first");
    let nv = start.positions.len();

    // Paint two dabs: the vertices within 0.5 of either centre are masked.
    let centres = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0]];
    let want: Vec<bool> = start
        .positions
        .iter()
        .map(|&p| centres.iter().any(|&c| dist(p, c) <= 0.5 - 1e-6))
        .collect();
    let unsure = start
        .positions
        .iter()
        .filter(|&&p| centres.iter().any(|&c| (dist(p, c) - 0.5).abs() < 1e-6))
        .count();
    assert_eq!(unsure, 0, "no vertex on the brush's rim");
    let n = want.iter().filter(|&&m| m).count();
    assert!(n > 20 && n < nv / 2, "{n}");
    let r = a.ok(json!({"op": "mask_paint", "points": centres, "radius": 0.5}));
    assert_eq!(r["masked"], n);
    let painted = showing(&a);
    assert_eq!(painted.flags & 16, 16);
    let flags: Vec<bool> = painted
        .mask
        .clone()
        .expect("mask")
        .iter()
        .map(|&b| b == 1)
        .collect();
    assert_eq!(flags, want, "the frame marks exactly the painted vertices");

    // Erasing with one dab leaves the other; painting again restores it.
    let r = a.ok(json!({"op": "mask_paint", "point": [0, 1, 0], "radius": 0.5, "erase": true}));
    let top = start
        .positions
        .iter()
        .filter(|&&p| dist(p, [0.0, 0.0, 1.0]) <= 0.5)
        .count();
    assert_eq!(r["masked"], top);
    let r = a.ok(json!({"op": "mask_paint", "point": [0, 1, 0], "radius": 0.5}));
    assert_eq!(r["masked"], n);

    // Invert twice is the identity.
    let r = a.ok(json!({"op": "mask_invert"}));
    assert_eq!(r["masked"], nv - n);
    let r = a.ok(json!({"op": "mask_invert"}));
    assert_eq!(r["masked"], n);

    // A stroke over the masked cap and beyond it: masked vertices keep
    // their positions bit for bit, the others under the brush move.
    let v = a.state["version"].as_u64().expect("version");
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.9,
                "strength": 0.04, "point": [0, 0, 1]}),
    );
    for x in [0.2f64, 0.4, 0.5] {
        let z = (1.0f64 - x * x).sqrt();
        a.ok(json!({"op": "stroke_frame", "point": [x, 0, z]}));
    }
    a.ok(json!({"op": "stroke_end"}));
    assert!(
        a.state["version"].as_u64().expect("version") > v,
        "committed"
    );
    let after = showing(&a);
    assert_eq!(after.positions.len(), nv, "no topology change here");
    let mut moved = 0;
    for (i, (&p, &q)) in start.positions.iter().zip(&after.positions).enumerate() {
        if want[i] {
            assert_eq!(
                p.map(f32::to_bits),
                q.map(f32::to_bits),
                "masked vertex {i} moved"
            );
        } else if p != q {
            moved += 1;
        }
    }
    assert!(
        moved > 10,
        "the unmasked vertices under the brush moved: {moved}"
    );
    // The committed frame still carries the mask.
    let flags: Vec<bool> = after.mask.expect("mask").iter().map(|&b| b == 1).collect();
    assert_eq!(flags, want);

    // Undo takes back the stroke and keeps the mask it had; clear is an
    // undo step of its own.
    a.ok(json!({"op": "undo"}));
    assert_eq!(showing(&a).positions, start.positions);
    assert_eq!(masked_flags(&showing(&a)), want);
    let r = a.ok(json!({"op": "mask_clear"}));
    assert_eq!(r["masked"], 0);
    let cleared = showing(&a);
    assert_eq!(cleared.flags & 16, 0);
    assert!(cleared.mask.is_none());
    assert_eq!(a.state["can_undo"], true);
    assert_eq!(a.state["can_redo"], false, "an edit drops the redo history");
    a.ok(json!({"op": "undo"}));
    assert_eq!(
        masked_flags(&showing(&a)),
        want,
        "undo brings the mask back"
    );
    a.ok(json!({"op": "redo"}));
    assert!(showing(&a).mask.is_none(), "redo clears it again");
    a.ok(json!({"op": "undo"}));
    // Undo steps back through the mask edits too: the second invert, the
    // first, the paint, the erase, the first paint.
    a.ok(json!({"op": "undo"}));
    assert_eq!(
        masked_flags(&showing(&a)).iter().filter(|&&m| m).count(),
        nv - n
    );
    for _ in 0..4 {
        a.ok(json!({"op": "undo"}));
    }
    assert!(showing(&a).mask.is_none(), "before the first paint");
    for _ in 0..5 {
        a.ok(json!({"op": "redo"}));
    }
    assert_eq!(masked_flags(&showing(&a)), want);
    // Clearing an empty mask or painting where it is masked already
    // makes no undo step.
    let v = a.state["version"].as_u64().expect("version");
    let r = a.ok(json!({"op": "mask_paint", "point": [0, 0, 1], "radius": 0.3}));
    assert_eq!(r["masked"], n);
    assert_eq!(a.state["version"].as_u64(), Some(v), "no step");

    // The mask is saved with the session and comes back at a restart.
    let meta = dir.path().join("session.json");
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        let saved: Value = std::fs::read_to_string(&meta)
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or(Value::Null);
        if saved["version"].as_u64() == Some(v) {
            assert_eq!(saved["mask"].as_array().map(Vec::len), Some(n));
            break;
        }
        assert!(Instant::now() < deadline, "no autosave: {saved}");
        std::thread::sleep(Duration::from_millis(50));
    }
    let again = self::start(dir.path(), 1 << 20);
    let mut b = Tab::open(again);
    assert_eq!(masked_flags(&showing(&b)), want, "restored with the mask");
    assert_eq!(b.state["can_undo"], false);
    // A new primitive starts unmasked, and undo brings the mask back.
    b.ok(json!({"op": "primitive", "spec": "@sphere:3"}));
    assert!(showing(&b).mask.is_none());
    b.ok(json!({"op": "undo"}));
    assert_eq!(masked_flags(&showing(&b)), want);
    drop(b);

    // Refusals say why and change nothing.
    for (req, why) in [
        (
            json!({"op": "mask_paint", "point": [0, 0, 1], "radius": -1}),
            "radius",
        ),
        (
            json!({"op": "mask_paint", "point": [0, 0], "radius": 0.5}),
            "point",
        ),
        (
            json!({"op": "mask_paint", "points": [], "radius": 0.5}),
            "points",
        ),
        (
            json!({"op": "mask_paint", "points": [[0, 0, "x"]], "radius": 0.5}),
            "points",
        ),
    ] {
        let r = a.call(req.clone());
        assert_eq!(r["type"], "error", "{req}");
        assert!(says(&r, why), "{req} -> {r}");
    }
    a.ok(json!({"op": "workspace", "workspace": "model"}));
    let r = a.call(json!({"op": "mask_invert"}));
    assert!(says(&r, "sculpt workspace"), "{r}");
}

/// The displacement of every vertex between two whole frames over the
/// same vertices.
fn displacements(a: &Decoded, b: &Decoded) -> Vec<f64> {
    assert_eq!(a.positions.len(), b.positions.len());
    a.positions
        .iter()
        .zip(&b.positions)
        .map(|(p, q)| {
            (0..3)
                .map(|i| f64::from(q[i] - p[i]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .collect()
}

#[test]
fn strokes_read_falloff_symmetry_and_pressure() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere(addr);
    let start = showing(&a);
    let (r, s) = (0.6, 0.03);
    let centre = [0.6, 0.0, 0.8];

    // Constant falloff: one inflate frame moves every vertex well inside
    // the brush by the full strength, and none well outside.
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": r, "strength": s,
                "point": centre, "falloff": "constant"}),
    );
    a.ok(json!({"op": "stroke_end"}));
    let one = showing(&a);
    let d = displacements(&start, &one);
    let mut inside = 0;
    for (i, &p) in start.positions.iter().enumerate() {
        let from = dist(p, centre);
        if from < 0.95 * r {
            inside += 1;
            assert!(
                (d[i] - s).abs() < 1e-5,
                "vertex {i} at {from} moved {}",
                d[i]
            );
        } else if from > 1.05 * r {
            assert_eq!(d[i], 0.0, "vertex {i} at {from} outside the brush moved");
        }
    }
    assert!(inside > 10);
    a.ok(json!({"op": "undo"}));

    // The default (smooth) falloff tapers: moves differ inside the brush.
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": r, "strength": s,
                "point": centre}),
    );
    a.ok(json!({"op": "stroke_end"}));
    let d = displacements(&start, &showing(&a));
    let inner: Vec<f64> = (0..d.len())
        .filter(|&i| dist(start.positions[i], centre) < 0.95 * r)
        .map(|i| d[i])
        .collect();
    let (lo, hi) = inner
        .iter()
        .fold((f64::INFINITY, 0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!(
        hi <= s + 1e-6 && lo < 0.5 * hi,
        "smooth falloff: {lo}..{hi}"
    );
    a.ok(json!({"op": "undo"}));

    // Pressure 0 on strength moves nothing: no undo step.
    let v = a.state["version"].clone();
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": r, "strength": s,
                "point": centre, "pressure": 0.0}),
    );
    a.ok(json!({"op": "stroke_frame", "point": centre, "pressure": 0.0}));
    a.ok(json!({"op": "stroke_end"}));
    assert_eq!(a.state["version"], v, "nothing moved, nothing committed");

    // Pressure ½ on the radius: with a constant falloff only the vertices
    // within half the radius move.
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": r, "strength": s,
                "point": centre, "falloff": "constant", "pressure_drives": "radius",
                "pressure": 0.5}),
    );
    a.ok(json!({"op": "stroke_end"}));
    let d = displacements(&start, &showing(&a));
    for (i, &p) in start.positions.iter().enumerate() {
        let from = dist(p, centre);
        if from < 0.45 * r {
            assert!(
                (d[i] - s).abs() < 1e-5,
                "vertex {i} at {from} moved {}",
                d[i]
            );
        } else if from > 0.55 * r {
            assert_eq!(
                d[i], 0.0,
                "vertex {i} at {from} beyond half the radius moved"
            );
        }
    }
    a.ok(json!({"op": "undo"}));

    // Symmetry in x about the origin: a stroke on the +x side only leaves
    // a mesh that is its own mirror image (to f32 rounding), which the
    // same stroke without symmetry does not.
    let mirrored = |f: &Decoded| {
        let mut worst = 0f64;
        for p in &f.positions {
            let m = [-f64::from(p[0]), f64::from(p[1]), f64::from(p[2])];
            let near = f
                .positions
                .iter()
                .map(|&q| dist(q, m))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(near);
        }
        worst
    };
    assert!(
        mirrored(&start) < 1e-6,
        "the icosphere is symmetric to begin with"
    );
    for (symmetry, about) in [("x", "origin"), ("", "origin"), ("x", "centre")] {
        a.ok(
            json!({"op": "stroke_begin", "brush": "draw", "radius": r, "strength": 0.05,
                    "point": centre, "symmetry": symmetry, "symmetry_about": about}),
        );
        a.ok(json!({"op": "stroke_frame", "point": [0.8, 0.0, 0.6]}));
        a.ok(json!({"op": "stroke_end"}));
        let worst = mirrored(&showing(&a));
        if symmetry.is_empty() {
            assert!(
                worst > 1e-2,
                "without symmetry the stroke is one-sided: {worst}"
            );
        } else {
            assert!(
                worst < 1e-5,
                "{symmetry} about the {about}: a vertex is {worst} from its mirror"
            );
        }
        a.ok(json!({"op": "undo"}));
    }

    // Every brush name the server lists is accepted with a share or a
    // distance as its strength says.
    for (brush, strength) in [
        ("draw", 0.02),
        ("clay", 0.02),
        ("crease", 0.02),
        ("flatten", 0.5),
        ("pinch", -0.3),
        ("scrape", 0.5),
        ("scale", 0.1),
        ("smooth", 0.5),
        ("layer", 0.05),
    ] {
        a.ok(
            json!({"op": "stroke_begin", "brush": brush, "radius": r, "strength": strength,
                    "point": centre}),
        );
        a.ok(json!({"op": "stroke_end"}));
    }

    // Bad fields are refused by name.
    for (req, why) in [
        (json!({"falloff": "wobbly"}), "falloff"),
        (json!({"falloff": {"custom": [1, 2]}}), "falloff"),
        (json!({"symmetry": "w"}), "symmetry"),
        (json!({"symmetry_about": "moon"}), "symmetry_about"),
        (json!({"pressure_drives": "colour"}), "pressure_drives"),
        (json!({"brush": "flatten", "strength": 1.5}), "[0, 1]"),
        (json!({"brush": "scale", "strength": -1.5}), "[-1, 1]"),
        (json!({"brush": "layer", "strength": 0.2}), "of the radius"),
    ] {
        let mut req_full = json!({"op": "stroke_begin", "brush": "inflate", "radius": r,
                                  "strength": s, "point": centre});
        for (k, v) in req.as_object().expect("object") {
            req_full[k] = v.clone();
        }
        let r = a.call(req_full.clone());
        assert_eq!(r["type"], "error", "{req_full}");
        assert!(says(&r, why), "{req_full} -> {r}");
    }
    // A refused stroke leaves no stroke behind.
    assert_eq!(a.state["stroke"], false);
}

/// `extrude` is the library's: each kind on a quad of the cube (d = 4)
/// gives the counts its definition implies (see the unit test next to
/// the op for where each comes from) and is one undo step; an option a
/// kind does not read, or a face the library refuses, comes back as one
/// plain error naming faces as the page numbers them, and the document
/// (counts, version, undo history) is as it was.
#[test]
fn extrusions_are_the_librarys_and_a_refusal_changes_nothing() {
    let (_dir, _, mut a) = tab_on("@cube");
    let cube = [8u64, 12, 6];
    assert_eq!(vef(&a), cube);
    let d = 4u64;
    for (kind, extra, [dv, de, df]) in [
        ("plain", json!({}), [d, 2 * d, d]),
        ("plain", json!({"count": 2}), [2 * d, 4 * d, 2 * d]),
        ("together", json!({"distance": 0.5}), [d, 2 * d, d]),
        ("doo-sabin", json!({}), [d, 2 * d, d]),
        ("cubical", json!({"count": 2}), [2 * d, 4 * d, 2 * d]),
        ("octahedral", json!({}), [d, 3 * d, 2 * d]),
        ("dodecahedral", json!({}), [3 * d, 5 * d, 2 * d]),
        ("icosahedral", json!({}), [3 * d, 9 * d, 6 * d]),
        ("stellate", json!({}), [1, d, d - 1]),
        (
            "double-stellate",
            json!({"distance": 0.2}),
            [d + 1, 4 * d, 3 * d - 1],
        ),
        (
            "dome",
            json!({"count": 2}),
            [2 * d + 1, 4 * d + d, 2 * d + d - 1],
        ),
    ] {
        let mut req = json!({"op": "extrude", "faces": [0], "kind": kind});
        if let (Some(r), Some(x)) = (req.as_object_mut(), extra.as_object()) {
            r.extend(x.clone());
        }
        let r = a.ok(req.clone());
        assert_eq!(vef(&a), [cube[0] + dv, cube[1] + de, cube[2] + df], "{req}");
        assert_eq!(a.genus(), json!(0), "{req}");
        assert_eq!(r["faces"].as_array().map(Vec::len), Some(1), "{req}");
        a.ok(json!({"op": "undo"}));
        assert_eq!(vef(&a), cube, "one undo step undoes {req}");
    }

    // One plain extrusion to undo later; then refusals.
    a.ok(json!({"op": "extrude", "faces": [0]}));
    let grown = vef(&a);
    let version = a.state["version"].clone();
    for (req, says) in [
        (
            json!({"op": "extrude", "faces": [0], "kind": "stellate", "scale": 2}),
            "extrude: \"scale\" does not apply to the stellate extrusion (it reads \"distance\")",
        ),
        (
            json!({"op": "extrude", "faces": [0], "kind": "cubical", "distance": 2}),
            "extrude: \"distance\" does not apply to the cubical extrusion (it reads \"height\" and \"count\")",
        ),
        (
            json!({"op": "extrude", "faces": [0, 1], "kind": "together", "rotation": 5}),
            "extrude: \"rotation\" does not apply to the together extrusion (it reads \"distance\", \"count\" and \"direction\")",
        ),
        (
            json!({"op": "extrude", "faces": [0], "kind": "dome", "direction": "normals"}),
            "extrude: \"direction\" does not apply to the dome extrusion (only to together)",
        ),
    ] {
        let r = a.call(req.clone());
        assert_eq!(r["type"], "error", "{req} -> {r}");
        assert_eq!(r["message"], says, "{req}");
        assert_eq!(vef(&a), grown, "{req} changed the mesh");
        assert_eq!(a.state["version"], version, "{req} changed the version");
    }
    // Several faces, refused at the first by a value too large for the
    // model: nothing is extruded, and the face is named by its number.
    let r = a.call(json!({"op": "extrude", "faces": [3, 0, 1],
                          "distance": 1e308, "count": 2}));
    assert_eq!(r["type"], "error", "{r}");
    let m = r["message"].as_str().unwrap_or("");
    assert!(m.starts_with("extrude: ") && m.contains("face 3"), "{m}");
    assert!(!m.contains("v1"), "a kernel handle in {m:?}");
    assert_eq!(vef(&a), grown);
    assert_eq!(a.state["version"], version);
    // The refusals added no undo step: one undo is back to the cube.
    a.ok(json!({"op": "undo"}));
    assert_eq!(vef(&a), cube);
}

// ---- issue 18: the handle tool's curve and multi-face handles ----------------

/// Six cubes of side 1 (testkit's unit cube) centred on the axes at
/// distance 3, as OBJ: one component each, 48 / 72 / 36.
fn six_cubes_obj() -> String {
    let (corners, quads) = holey_testkit::unit_cube();
    let mut text = String::new();
    for k in 0..6 {
        let (axis, side) = (k / 2, if k % 2 == 0 { -3.0 } else { 3.0 });
        for c in corners {
            let p: Vec<String> = (0..3)
                .map(|i| (c[i] - 0.5 + if i == axis { side } else { 0.0 }).to_string())
                .collect();
            text += &format!("v {}\n", p.join(" "));
        }
        for q in quads {
            let v: Vec<String> = q
                .iter()
                .map(|&i| (8 * k + i as usize + 1).to_string())
                .collect();
            text += &format!("f {}\n", v.join(" "));
        }
    }
    text
}

/// The display faces of a whole mesh frame whose outward normal points
/// at the origin, worked out from the frame's own triangles (so the test
/// does not lean on how the server numbers faces).
fn faces_facing_origin(frame: &[u8]) -> Vec<usize> {
    let word = |i: usize| u32::from_le_bytes(frame[4 * i..4 * i + 4].try_into().expect("4 bytes"));
    let (nv, nt, nf) = (word(4) as usize, word(5) as usize, word(7) as usize);
    let position = |v: usize| {
        let at = 8 + 3 * v;
        [0, 1, 2].map(|k| f64::from(f32::from_bits(word(at + k))))
    };
    let tris = 8 + 3 * nv;
    let tri_face = tris + 3 * nt;
    // Per face: the sum of its triangles' area vectors and of their
    // corners (a centroid's direction is all that is compared).
    let mut normal = vec![[0.0f64; 3]; nf];
    let mut centre = vec![[0.0f64; 3]; nf];
    for t in 0..nt {
        let [a, b, c] = [0, 1, 2].map(|k| position(word(tris + 3 * t + k) as usize));
        let (u, w) = (
            [0, 1, 2].map(|i| b[i] - a[i]),
            [0, 1, 2].map(|i| c[i] - a[i]),
        );
        let n = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let f = word(tri_face + t) as usize;
        for i in 0..3 {
            normal[f][i] += n[i];
            centre[f][i] += a[i] + b[i] + c[i];
        }
    }
    (0..nf)
        .filter(|&f| (0..3).map(|i| -normal[f][i] * centre[f][i]).sum::<f64>() > 0.0)
        .collect()
}

#[test]
fn bezier_and_multi_face_handles() {
    // A Bézier tunnel through a cube, between opposite faces: a handle of
    // s segments between quads adds 4(s − 1) / 4(2s − 1) / 4s − 2 and,
    // on one component, one to the genus.
    let (_dir, addr, mut a) = tab_on("@cube");
    let s = 3;
    let r = a.ok(
        json!({"op": "handle", "version": a.state["version"], "faces": [0, 5],
        "segments": s, "w1": -1, "w2": -1, "curve": "bezier"}),
    );
    assert!(says(&r, "Bézier"), "{r}");
    assert_eq!(
        vef(&a),
        [8 + 4 * (s - 1), 12 + 4 * (2 * s - 1), 6 + 4 * s - 2]
    );
    assert_eq!(a.genus(), 1);
    a.ok(json!({"op": "undo"}));

    // Six cubes joined through a hub. Their directions from the centre are
    // the octahedron's, so the hub is its dual, a cube (8 / 12 / 6) with a
    // quad facing each selected quad; seven components joined by six
    // handles make one sphere.
    let (status, r) = upload(addr, "six.obj", six_cubes_obj().as_bytes());
    assert_eq!(status, 200, "{r}");
    // The state comes first, then the frame.
    let vertices =
        |frame: Option<&Vec<u8>>| frame.map(|f| u32::from_le_bytes([f[16], f[17], f[18], f[19]]));
    while vef(&a) != [48, 72, 36] || vertices(a.frames.last()) != Some(48) {
        a.pump_one();
    }
    assert_eq!(a.state["stats"]["components"], 6);
    let version = a.state["version"].clone();
    let facing = faces_facing_origin(a.frames.last().expect("a frame"));
    assert_eq!(facing.len(), 6, "{facing:?}");
    let refusals = [
        (json!({"faces": &facing[..3]}), "four or more"),
        (
            json!({"faces": facing, "corners": [0, 0]}),
            "\"corners\" choose the twist",
        ),
        (json!({"faces": facing, "curve": "spline"}), "spline"),
        (json!({"faces": facing, "hub_scale": 0}), "hub scale"),
        (json!({"faces": [0, 1], "hub_scale": 0.5}), "four or more"),
        (json!({"faces": [facing[0], 99999, 1, 2]}), "face 99999"),
    ];
    for (mut req, says) in refusals {
        req["op"] = json!("handle");
        req["version"] = version.clone();
        a.refused(req, says);
        assert_eq!(vef(&a), [48, 72, 36], "a refusal changes nothing");
    }
    for curve in ["hermite", "bezier"] {
        // Undo brings the faces back under a new version number.
        let version = a.state["version"].clone();
        let r = a.ok(json!({"op": "handle", "version": version, "faces": facing,
            "segments": s, "w1": 0.5, "w2": 0.5, "curve": curve, "hub_scale": 0.5}));
        assert!(says(&r, "of 6 faces"), "{r}");
        let k = 6;
        assert_eq!(
            vef(&a),
            [
                48 + 8 + k * 4 * (s - 1),
                72 + 12 + k * 4 * (2 * s - 1),
                36 + 6 + k * (4 * s - 2)
            ],
            "{curve}"
        );
        assert_eq!(a.state["stats"]["components"], 1, "{curve}");
        assert_eq!(a.genus(), 0, "{curve}");
        a.ok(json!({"op": "undo"}));
        assert_eq!(vef(&a), [48, 72, 36]);
    }
}

/// What a page holds after the frames it was sent: positions (f32 bits),
/// triangles and their faces, edges in slot order.
#[derive(Clone, Debug, Default, PartialEq)]
struct Shown {
    positions: Vec<[u32; 3]>,
    triangles: Vec<[u32; 3]>,
    faces: Vec<u32>,
    edges: Vec<[u32; 2]>,
}

impl Shown {
    /// Takes one frame as PROTOCOL.md says a page does: whole, positions
    /// only (dense or sparse), or a connectivity patch (bit 5).
    fn take(&mut self, b: &[u8]) {
        let w = |i: usize| u32::from_le_bytes(b[4 * i..4 * i + 4].try_into().expect("word"));
        let flags = w(2);
        let [nv, nt, ne] = [w(4), w(5), w(6)].map(|n| n as usize);
        let mut at = 8;
        let mut next = || {
            at += 1;
            w(at - 1)
        };
        if flags & 32 != 0 {
            assert_eq!(flags & (2 | 4 | 8), 0, "a patch is nothing else");
            let from = [next(), next(), next()].map(|n| n as usize);
            assert_eq!(
                from,
                [self.positions.len(), self.triangles.len(), self.edges.len()]
            );
            self.positions.resize(nv, [u32::MAX; 3]);
            self.triangles.resize(nt, [u32::MAX; 3]);
            self.faces.resize(nt, u32::MAX);
            self.edges.resize(ne, [u32::MAX; 2]);
            let k = next() as usize;
            let vs: Vec<u32> = (0..k).map(|_| next()).collect();
            for &v in &vs {
                self.positions[v as usize] = [next(), next(), next()];
            }
            let m = next() as usize;
            let ts: Vec<u32> = (0..m).map(|_| next()).collect();
            for &t in &ts {
                self.triangles[t as usize] = [next(), next(), next()];
            }
            for &t in &ts {
                self.faces[t as usize] = next();
            }
            let q = next() as usize;
            let es: Vec<u32> = (0..q).map(|_| next()).collect();
            for &e in &es {
                self.edges[e as usize] = [next(), next()];
            }
        } else if flags & 8 != 0 {
            assert_eq!(nv, self.positions.len());
            let k = next() as usize;
            let vs: Vec<u32> = (0..k).map(|_| next()).collect();
            for &v in &vs {
                self.positions[v as usize] = [next(), next(), next()];
            }
        } else {
            self.positions = (0..nv).map(|_| [next(), next(), next()]).collect();
            if flags & 4 == 0 {
                self.triangles = (0..nt).map(|_| [next(), next(), next()]).collect();
                self.faces = (0..nt).map(|_| next()).collect();
                self.edges = (0..ne).map(|_| [next(), next()]).collect();
            }
        }
    }

    /// The edges as a sorted list (a patch keeps slots, not the order).
    fn edge_set(&self) -> Vec<[u32; 2]> {
        let mut e = self.edges.clone();
        e.sort_unstable();
        e
    }
}

/// Whether `frame` is a commit frame (`web/PROTOCOL.md`): sparse, no
/// vertex moved, not a preview.
fn is_commit(frame: &[u8]) -> bool {
    let w = |i: usize| u32::from_le_bytes(frame[4 * i..4 * i + 4].try_into().expect("word"));
    w(2) == 4 | 8 && w(8) == 0 && frame.len() == 36
}

/// What the document shows, as a tab opened now is sent it (a whole
/// frame of the document's display): the oracle for what a stroke's
/// frames and its commit built on the tabs that were open.
fn document_shown(addr: SocketAddr) -> Shown {
    let late = Tab::open(addr);
    let mut shown = Shown::default();
    shown.take(late.frames.last().expect("the greeting's frame"));
    shown
}

/// Remeshing strokes travel as patches that build the committed mesh,
/// slot for slot, on every tab. Twice: the second stroke starts from the
/// display (and the edge book) the first one's frames left, which the
/// document keeps instead of building its own.
#[test]
fn remeshing_strokes_send_patches_that_build_the_committed_mesh() {
    let (_dir, addr) = server();
    let mut a = Tab::open(addr);
    let mut b = Tab::open(addr);
    a.ok(json!({"op": "primitive", "spec": "@sphere:3"}));
    a.ok(json!({"op": "workspace", "workspace": "sculpt"}));
    // Finer than the mesh: the brush splits edges at every frame.
    a.ok(json!({"op": "set_remesh", "detail": 0.8}));
    let mut shown = Shown::default();
    let first = a.frames.len() - 1;
    let flags = |f: &Vec<u8>| u32::from_le_bytes(f[8..12].try_into().expect("flags"));
    let mut triangles = 1280;
    for (round, y) in [0.0f64, 0.3].into_iter().enumerate() {
        let start = a.frames.len();
        a.ok(
            json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.5,
                    "strength": 0.02, "point": [0, y, (1.0 - y * y).sqrt()]}),
        );
        for i in 1..=12 {
            let x = 0.05 * f64::from(i);
            let z = (1.0 - x * x - y * y).sqrt();
            a.ok(json!({"op": "stroke_frame", "point": [x, y, z]}));
        }
        let before_end = a.frames.len();
        a.ok(json!({"op": "stroke_end"}));
        let patches = a.frames[start..before_end]
            .iter()
            .filter(|f| flags(f) & 32 != 0)
            .count();
        assert!(
            patches >= 3,
            "stroke {round}: frames went as patches: {patches}"
        );
        let from = if round == 0 { first } else { start };
        for f in &a.frames[from..before_end] {
            shown.take(f);
            // Every index names a vertex; every triangle's edges are edges.
            let nv = shown.positions.len() as u32;
            assert!(shown.triangles.iter().flatten().all(|&v| v < nv));
            assert!(shown.edges.iter().flatten().all(|&v| v < nv));
            assert_eq!(
                shown.faces,
                (0..shown.triangles.len() as u32).collect::<Vec<_>>()
            );
        }
        // The commit is a commit frame: the document shows what the
        // patches built, slot for slot (the stroke's display), and a tab
        // opened now is sent exactly that.
        let commit = a.frames.last().expect("the commit");
        assert!(is_commit(commit), "stroke {round}: the commit went whole");
        shown.take(commit);
        let committed = document_shown(addr);
        assert_eq!(shown, committed, "stroke {round}");
        assert!(
            committed.triangles.len() > triangles,
            "stroke {round} remeshed finer: {}",
            committed.triangles.len()
        );
        triangles = committed.triangles.len();
    }
    // The other tab was sent the same frames.
    while b.frames.len() < a.frames.len() {
        b.pump_one();
    }
    let mut other = Shown::default();
    let tail = &b.frames[b.frames.len() - (a.frames.len() - first)..];
    for f in tail {
        other.take(f);
    }
    assert_eq!(other, shown);
}

/// Issue 15 item 6, through the modeller: a frame that cuts the surface
/// keeps every vertex and triangle number the cut did not touch (the
/// engine's splice, `holey_mesh::tri::splice_in_place`), so it
/// travels as a patch, as a remeshing frame does, and not as the whole
/// mesh (38 MB a frame on a million triangles). The snake hook pulled
/// through the far side of a sphere opens a tunnel mid-stroke: each frame
/// whose Euler characteristic (counted on what the page built) changes
/// is a patch, and the patches build the committed mesh, of genus 1.
#[test]
fn frames_that_cut_the_surface_travel_as_patches() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere(addr);
    let mut shown = Shown::default();
    shown.take(a.frames.last().expect("the sphere"));
    let euler =
        |s: &Shown| s.positions.len() as i64 - s.edges.len() as i64 + s.triangles.len() as i64;
    assert_eq!(euler(&shown), 2);
    a.ok(
        json!({"op": "stroke_begin", "brush": "snake_hook", "radius": 0.45,
                "strength": 1, "point": [0, 0, 1]}),
    );
    let flags = |f: &[u8]| u32::from_le_bytes(f[8..12].try_into().expect("flags"));
    let (mut cuts, mut seen) = (0, a.frames.len());
    for i in 1..=20 {
        a.ok(json!({"op": "stroke_frame", "point": [0, 0, 1.0 - 2.4 * f64::from(i) / 20.0]}));
        for f in &a.frames[seen..] {
            let before = euler(&shown);
            shown.take(f);
            if euler(&shown) != before {
                cuts += 1;
                assert!(
                    flags(f) & 32 != 0,
                    "frame {i} cut the surface and went whole"
                );
            }
        }
        seen = a.frames.len();
    }
    assert!(cuts > 0, "the hook never cut the surface");
    a.ok(json!({"op": "stroke_end"}));
    assert_eq!(a.genus(), 1, "{}", a.state);
    let commit = a.frames.last().expect("the commit");
    assert!(is_commit(commit), "the commit went whole");
    shown.take(commit);
    let committed = document_shown(addr);
    assert_eq!(shown.positions, committed.positions);
    assert_eq!(shown.triangles, committed.triangles);
    assert_eq!(shown.edges, committed.edges);
}

/// A stroke on a fresh `@sphere:3` (remeshing at `detail`): `begin`, then
/// `path` sent as `stroke_frame` requests of `sizes` dabs each (the first
/// as `point`, the others as `points`), then `stroke_end`. Gives the
/// committed document as OBJ (exact `f64`s), what the frames built on the
/// page before the commit, what the document shows after it (as a tab
/// opened then is sent it), and the genus. A stroke that commits what its
/// frames showed ends with a commit frame, any other with a whole one.
fn stroke_in_batches(
    begin: &Value,
    detail: f64,
    path: &[[f64; 3]],
    sizes: &[usize],
) -> (Vec<u8>, Shown, Shown, Value) {
    assert_eq!(sizes.iter().sum::<usize>(), path.len());
    let (_dir, addr) = server();
    let mut a = sculpt_sphere_at(addr, detail);
    let first = a.frames.len() - 1;
    a.ok(begin.clone());
    let mut at = 0;
    for &k in sizes {
        let batch = &path[at..at + k];
        at += k;
        let mut req = json!({"op": "stroke_frame", "point": batch[0]});
        if k > 1 {
            req["points"] = json!(batch[1..]);
        }
        let r = a.ok(req);
        assert_eq!(r["frames"], k, "{r}");
    }
    let before_end = a.frames.len();
    a.ok(json!({"op": "stroke_end"}));
    let mut shown = Shown::default();
    for f in &a.frames[first..before_end] {
        shown.take(f);
    }
    let commit = a.frames.last().expect("the commit");
    let committed = document_shown(addr);
    let mut after = shown.clone();
    after.take(commit);
    assert_eq!(
        is_commit(commit),
        after == committed && after == shown,
        "{begin}: a commit frame where, and only where, the tabs showed the commit"
    );
    (model(addr), shown, committed, a.genus())
}

/// An inflate begun at the top of the unit sphere (radius 0.5, strength
/// 0.02) and the 12 dabs of its path down the arc towards +x.
fn inflate_along_an_arc() -> (Value, Vec<[f64; 3]>) {
    let begin = json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.5,
                        "strength": 0.02, "point": [0, 0, 1]});
    let arc = (1..=12)
        .map(|i| {
            let x = 0.05 * f64::from(i);
            [x, 0.0, (1.0 - x * x).sqrt()]
        })
        .collect();
    (begin, arc)
}

/// Issue 15 item 6: a `stroke_frame` carrying several dabs whose brush
/// depends on the dab before it (the snake hook's grip, a grab's drag)
/// applies them as that many single-point requests would, bit for bit, and
/// so does an inflate that neither collides nor remeshes (its one frame
/// moves the surface to where the brush alone takes it, dab after dab);
/// the one frame sent (positions, a patch or whole) brings the page to the
/// state after the last dab, also when the surface is cut in the middle
/// of a batch (a topology change).
#[test]
fn a_batch_of_dabs_is_the_same_stroke_as_single_frames() {
    let (inflate, arc) = inflate_along_an_arc();
    // The snake hook pulled through the far side (as in holey-sculpt's
    // brush tests): the surface opens into a tunnel at some frame.
    let hook = json!({"op": "stroke_begin", "brush": "snake_hook", "radius": 0.45,
                       "strength": 1, "point": [0, 0, 1]});
    let through: Vec<[f64; 3]> = (1..=20)
        .map(|i| [0.0, 0.0, 1.0 - 2.4 * f64::from(i) / 20.0])
        .collect();
    // A grab dragged down through the bottom: the preview's vanish mask
    // is the last frame's, the topology changes at release.
    let grab = json!({"op": "stroke_begin", "brush": "grab", "radius": 0.5,
                       "strength": 1, "point": [0, 0, 1]});
    let down = [[0.0, 0.0, 0.5], [0.0, 0.0, -0.5], [0.0, 0.0, -1.6]];
    for (begin, detail, path, batches, genus) in [
        (&inflate, 0.0, &arc[..], vec![3, 1, 8], 0),
        (&hook, 0.0, &through[..], vec![7, 8, 5], 1),
        (&hook, 0.5, &through[..], vec![2, 8, 8, 2], 1),
        (&grab, 0.5, &down[..], vec![3], 1),
    ] {
        let singles = vec![1; path.len()];
        let (one, one_shown, one_committed, one_genus) =
            stroke_in_batches(begin, detail, path, &singles);
        let (many, shown, committed, g) = stroke_in_batches(begin, detail, path, &batches);
        assert_eq!(one_genus, genus, "{begin}");
        assert_eq!(g, genus, "{begin}");
        assert!(
            one == many,
            "{begin} at detail {detail}: the batches {batches:?} committed another mesh"
        );
        // The same mesh; its edges are in the slots each stroke's own
        // patches left them.
        assert_eq!(one_committed.positions, committed.positions, "{begin}");
        assert_eq!(one_committed.triangles, committed.triangles, "{begin}");
        assert_eq!(one_committed.edge_set(), committed.edge_set(), "{begin}");
        // What the batched frames built on the page is the last frame's
        // surface (a paint stroke commits it as it is; a drag's preview
        // is its start moved).
        assert_eq!(shown.positions.len(), one_shown.positions.len(), "{begin}");
        assert_eq!(shown.positions, one_shown.positions, "{begin}");
        assert_eq!(shown.triangles, one_shown.triangles, "{begin}");
        assert_eq!(shown.edge_set(), one_shown.edge_set(), "{begin}");
        if begin["brush"] != "grab" {
            assert_eq!(shown.positions, committed.positions, "{begin}");
            assert_eq!(shown.triangles, committed.triangles, "{begin}");
            assert_eq!(shown.edges, committed.edges, "{begin}");
        }
    }
}

/// Issue 15 item 6: with remeshing, a `stroke_frame` of several inflate
/// dabs is one frame (the library's `LiveStroke::frame_together`, whose
/// own tests check it against the brush applied dab after dab): the brush
/// at every dab, then one topology change and one remeshing. So the
/// stroke commits another surface than the same dabs sent one a request
/// (remeshed after each), a closed sphere still, and the frames the page
/// was sent built exactly the committed surface.
#[test]
fn a_batch_of_inflate_dabs_with_remeshing_is_one_frame() {
    let (begin, arc) = inflate_along_an_arc();
    let detail = 0.8;
    let (batched, shown, committed, genus) = stroke_in_batches(&begin, detail, &arc, &[3, 1, 8]);
    let (singles, ..) = stroke_in_batches(&begin, detail, &arc, &[1; 12]);
    assert_eq!(genus, 0);
    assert!(batched != singles, "the batches were painted dab by dab");
    assert_eq!(shown.positions, committed.positions);
    assert_eq!(shown.triangles, committed.triangles);
    assert_eq!(shown.edges, committed.edges);
}

/// The document's mesh as the OBJ export gives it (exact `f64`s), as
/// triangles.
fn exported_triangles(addr: SocketAddr) -> holey_topo::TriMesh {
    match holey_io::parse(holey_io::Format::Obj, &model(addr), "export").expect("the export parses")
    {
        holey_io::MeshFile::Poly(p) => p.triangulated(),
        other => panic!("an OBJ export is a polygon mesh, got {other:?}"),
    }
}

/// The modeler's strokes replay faithfully: `stroke_begin` answers with
/// the range the stroke remeshes to (derived from the mesh as the stroke
/// begins, and from the detail slider), and a stroke file that records it
/// per stroke, with the frames as sent, replays through
/// `holey_sculpt::Session` to the very mesh the server committed. The
/// second stroke begins on the surface the first remeshed, so its range
/// is not the first's: one range for the whole file could not say both.
#[test]
fn the_modelers_strokes_replay_to_the_same_mesh_with_their_own_remeshing() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere_at(addr, 0.8);
    let start = exported_triangles(addr);
    let (begin, arc) = inflate_along_an_arc();
    // The second stroke deflates back along the same arc.
    let mut back = begin.clone();
    back["strength"] = json!(-0.01);
    back["point"] = json!(arc[11]);
    let back_path: Vec<[f64; 3]> = arc.iter().rev().skip(1).copied().collect();
    let mut strokes = Vec::new();
    for (begin, path, sizes) in [
        (&begin, &arc[..], [3, 1, 8]),
        (&back, &back_path[..], [5, 5, 1]),
    ] {
        let r = a.ok(begin.clone());
        let remesh = r["remesh"].clone();
        assert!(remesh["min_edge"].as_f64().unwrap_or(0.0) > 0.0, "{r}");
        let mut at = 0;
        for k in sizes {
            let batch = &path[at..at + k];
            at += k;
            let mut req = json!({"op": "stroke_frame", "point": batch[0]});
            if k > 1 {
                req["points"] = json!(batch[1..]);
            }
            a.ok(req);
        }
        a.ok(json!({"op": "stroke_end"}));
        let mut whole = vec![begin["point"].clone()];
        whole.extend(path.iter().map(|p| json!(p)));
        let mut frames = vec![1];
        frames.extend(sizes);
        strokes.push(json!({"brush": "inflate", "radius": begin["radius"],
            "strength": begin["strength"], "path": whole, "frames": frames, "remesh": remesh}));
    }
    assert_ne!(
        strokes[0]["remesh"], strokes[1]["remesh"],
        "the second stroke's range is derived from the remeshed surface"
    );
    let committed = exported_triangles(addr);
    let file = holey_sculpt::parse_strokes(&json!({ "strokes": strokes }).to_string())
        .expect("the recorded strokes parse");
    let mut session = holey_sculpt::Session::new(start).expect("the sphere can be sculpted");
    session
        .replay(&file, &mut |_, _| Ok(()))
        .expect("the replay");
    let replayed = session.mesh();
    assert_eq!(replayed.triangles.len(), committed.triangles.len());
    assert_eq!(replayed.triangles, committed.triangles);
    assert_eq!(replayed.positions, committed.positions);
}

#[test]
fn a_batch_of_dabs_is_refused_when_malformed() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere(addr);
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.5,
                "strength": 0.02, "point": [0, 0, 1]}),
    );
    a.refused(
        json!({"op": "stroke_frame", "point": [0, 0, 1], "points": [[0, 0, 1]], "pressures": [0.5, 0.5]}),
        "2 pressures for 1 points",
    );
    a.refused(
        json!({"op": "stroke_frame", "point": [0, 0, 1], "points": vec![[0, 0, 1]; 64]}),
        "at most 64 points",
    );
    let r = a.ok(json!({"op": "stroke_frame", "point": [0, 0, 1], "points": [[0, 0.1, 1]], "pressures": [0.5]}));
    assert_eq!(r["frames"], 2, "{r}");
    a.ok(json!({"op": "stroke_end"}));
}

/// Words of a frame's header and what follows it (little-endian u32).
fn frame_word(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes(b[4 * i..4 * i + 4].try_into().expect("word"))
}

/// A tab opened in the middle of a remeshing stroke gets the stroke's
/// mesh as the other tabs have it, so the stroke's next connectivity
/// patches apply to what it holds: each patch starts from the counts
/// (vertices, triangles, edges) of the frame before it, the new tab's
/// last frame included. Before, it held the mesh from before the stroke
/// and could apply none of them.
#[test]
fn a_tab_opened_mid_stroke_can_apply_its_patches() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere_at(addr, 1.0);
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.4, "strength": 0.02,
                "point": [0, 0, 1]}),
    );
    const PATCH: u32 = 32;
    const POSITIONS_ONLY: u32 = 4;
    let is_patch = |f: &Vec<u8>| frame_word(f, 2) & PATCH != 0;
    let mut x = 0.0;
    while !a.frames.iter().any(is_patch) {
        x += 0.02;
        assert!(x < 1.0, "remeshing made no patch frame");
        a.ok(json!({"op": "stroke_frame", "point": [x, 0, 1]}));
    }
    let mut b = Tab::open(addr);
    // Greeted again, once the first greeting is read to its end (replies
    // come in order): the document, then the stroke so far.
    b.call(json!({"op": "primitives"}));
    b.frames.clear();
    b.call(json!({"op": "hello"}));
    assert_eq!(b.frames.len(), 2, "the document and the stroke so far");
    let mut patches = 0;
    for _ in 0..20 {
        x += 0.02;
        a.ok(json!({"op": "stroke_frame", "point": [x, 0, 1]}));
    }
    // Let B read what the stroke broadcast.
    b.call(json!({"op": "primitives"}));
    let mut counts = None;
    for f in &b.frames {
        let flags = frame_word(f, 2);
        let new = [frame_word(f, 4), frame_word(f, 5), frame_word(f, 6)];
        if flags & PATCH != 0 {
            let from = [frame_word(f, 8), frame_word(f, 9), frame_word(f, 10)];
            assert_eq!(Some(from), counts, "a patch applies to what the tab holds");
            patches += 1;
        } else if flags & POSITIONS_ONLY != 0 {
            assert_eq!(Some(new), counts, "positions for the mesh the tab holds");
        }
        counts = Some(new);
    }
    assert!(patches > 0, "the stroke went on remeshing");
    a.ok(json!({"op": "stroke_end"}));
}

/// A stroke that in the end changes nothing (every vertex under the
/// brush masked) commits no undo step, and its commit frame keeps what
/// the tabs show: the document's display, as a tab opened afterwards is
/// sent it. A grab released where nothing vanishes commits what its
/// preview showed, with a commit frame that also clears the preview.
#[test]
fn strokes_that_leave_the_shown_mesh_end_with_a_commit_frame() {
    let (_dir, addr) = server();
    let mut a = sculpt_sphere(addr);
    let start = showing(&a);
    a.ok(json!({"op": "mask_invert"}));
    let v = a.state["version"].as_u64().expect("version");
    a.ok(
        json!({"op": "stroke_begin", "brush": "inflate", "radius": 0.5,
                "strength": 0.03, "point": [0, 0, 1]}),
    );
    a.ok(json!({"op": "stroke_frame", "point": [0.2, 0, 0.98]}));
    a.ok(json!({"op": "stroke_end"}));
    assert_eq!(
        a.state["version"], v,
        "no undo step for a stroke that moved nothing"
    );
    assert!(is_commit(a.frames.last().expect("the commit")));
    assert_eq!(shown_since_whole(&a).1, document_shown(addr));
    assert_eq!(showing(&a).positions, start.positions);

    // A grab that drags the top a little: nothing goes inside, nothing
    // vanishes, and the commit is what the preview showed.
    a.ok(json!({"op": "mask_clear"}));
    let v = a.state["version"].as_u64().expect("version");
    a.ok(json!({"op": "stroke_begin", "brush": "grab", "radius": 0.5,
                "strength": 1, "point": [0, 0, 1]}));
    a.ok(json!({"op": "stroke_frame", "point": [0, 0, 1.1]}));
    a.ok(json!({"op": "stroke_end"}));
    assert!(
        a.state["version"].as_u64().expect("version") > v,
        "committed"
    );
    let commit = a.frames.last().expect("the commit");
    assert!(
        is_commit(commit),
        "a grab that deleted nothing commits what it showed"
    );
    assert_eq!(shown_since_whole(&a).1, document_shown(addr));
    assert_ne!(showing(&a).positions, start.positions, "the top moved");
}
