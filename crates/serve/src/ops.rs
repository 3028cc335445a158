//! What each request does. See `web/PROTOCOL.md` for the messages.
//!
//! Short requests run on the connection's thread under the document's
//! lock. Long ones (Sierpinski, Menger, subdivision) run on a worker
//! thread from a copy of the mesh, report progress, and can be cancelled:
//! the document stays usable for viewing meanwhile, refuses other edits
//! ("busy"), and a cancelled result is dropped when the worker ends.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use glam::DVec3;
use holey_dlfl::Mesh;
use holey_io::{Format, MeshFile};
use holey_mesh::convert::{ImportOptions, infer_edges, to_dlfl};
use holey_model::handle::{HandleParams, create_handle};
use holey_model::menger::{MengerParams, menger_capped};
use holey_model::rind::{PunchOutcome, Rind};
use holey_model::sierpinski::sierpinski_capped;
use holey_sculpt::{Brush, BrushSettings, LiveStroke, Remesh, RemeshOptions, default_range};
use holey_subdiv::{Scheme, subdivide_capped};
use holey_topo::Options;
use serde_json::{Value, json};

use crate::doc::{ActiveStroke, Content, Document, RindMode, poly_to_tri};
use crate::frame::{
    FLAG_PREVIEW, display_model, display_triangles, encode, encode_positions, encode_sparse,
};
use crate::persist::Saver;
use crate::{Config, ConnId, ServeError};

/// A message queued for one connection.
#[derive(Clone, Debug)]
pub enum Out {
    Text(String),
    Binary(Vec<u8>),
}

/// The connected tabs.
#[derive(Default)]
pub struct Hub {
    next: AtomicU64,
    clients: Mutex<Vec<(ConnId, Sender<Out>)>>,
}

impl Hub {
    fn clients(&self) -> MutexGuard<'_, Vec<(ConnId, Sender<Out>)>> {
        // A thread that panicked while holding the list left it intact:
        // pushes and retains are the only mutations.
        self.clients.lock().unwrap_or_else(|p| p.into_inner())
    }

    pub fn join(&self) -> (ConnId, Receiver<Out>) {
        let id = self.next.fetch_add(1, Ordering::Relaxed) + 1;
        let (tx, rx) = mpsc::channel();
        self.clients().push((id, tx));
        (id, rx)
    }

    pub fn leave(&self, id: ConnId) {
        self.clients().retain(|(c, _)| *c != id);
    }

    pub fn send(&self, to: ConnId, out: Out) {
        if let Some((_, tx)) = self.clients().iter().find(|(c, _)| *c == to) {
            let _ = tx.send(out);
        }
    }

    pub fn broadcast(&self, out: &Out) {
        for (_, tx) in self.clients().iter() {
            let _ = tx.send(out.clone());
        }
    }

    pub fn count(&self) -> usize {
        self.clients().len()
    }
}

/// What every connection thread shares.
pub struct Shared {
    pub config: Config,
    pub hub: Hub,
    doc: Mutex<Document>,
    saver: Saver,
    cancel: Mutex<Option<Arc<AtomicBool>>>,
}

type Reply = Result<Value, ServeError>;

impl Shared {
    pub fn new(config: Config, doc: Document) -> Arc<Shared> {
        let saver = Saver::start(config.state_dir.clone());
        Arc::new(Shared {
            config,
            hub: Hub::default(),
            doc: Mutex::new(doc),
            saver,
            cancel: Mutex::new(None),
        })
    }

    fn doc(&self) -> MutexGuard<'_, Document> {
        // Operations build new content before committing it, so a panic
        // inside one leaves the document as it was.
        self.doc.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// A new tab: the state and the whole mesh.
    pub fn hello(&self, conn: ConnId) {
        let doc = self.doc();
        self.hub.send(conn, Out::Text(doc.state_json().to_string()));
        self.hub.send(
            conn,
            Out::Binary(encode(doc.display(), 0, doc.version(), None)),
        );
    }

    /// A tab went away: a stroke it was dragging is abandoned.
    pub fn disconnected(&self, conn: ConnId) {
        let mut doc = self.doc();
        if doc.stroke.as_ref().is_some_and(|s| s.owner == conn) {
            doc.stroke = None;
            self.publish(&doc);
        }
    }

    pub fn reply_error(&self, conn: ConnId, id: Option<&Value>, message: &str) {
        let msg = json!({"type": "error", "id": id, "message": message});
        self.hub.send(conn, Out::Text(msg.to_string()));
    }

    fn reply(&self, conn: ConnId, id: Option<&Value>, result: Reply) {
        let msg = match result {
            Ok(mut v) => {
                v["type"] = json!("ok");
                v["id"] = json!(id);
                v
            }
            Err(e) => json!({
                "type": "error",
                "id": id,
                "message": e.to_string(),
                "cancelled": matches!(e, ServeError::Cancelled),
            }),
        };
        self.hub.send(conn, Out::Text(msg.to_string()));
    }

    /// Sends every tab the state and the whole mesh, and saves.
    fn publish(&self, doc: &Document) {
        self.hub.broadcast(&Out::Text(doc.state_json().to_string()));
        self.hub
            .broadcast(&Out::Binary(encode(doc.display(), 0, doc.version(), None)));
        if doc.rind.is_none() {
            self.saver.save(doc.version(), doc.content().clone());
        }
    }

    /// Sends every tab the state only (busy flags, settings).
    fn publish_state(&self, doc: &Document) {
        self.hub.broadcast(&Out::Text(doc.state_json().to_string()));
    }

    /// Handles one request message.
    pub fn request(self: &Arc<Self>, conn: ConnId, text: &str) {
        let req: Value = match serde_json::from_str(text) {
            Ok(v) => v,
            Err(e) => return self.reply_error(conn, None, &format!("bad request: {e}")),
        };
        let id = req.get("id").cloned();
        let op = req.get("op").and_then(Value::as_str).unwrap_or("");
        let result = match op {
            "sierpinski" | "menger" | "subdivide" => {
                return self.start_long(conn, id, op, &req);
            }
            "cancel" => self.cancel(),
            "hello" => {
                self.hello(conn);
                Ok(json!({}))
            }
            "primitives" => Ok(primitives()),
            _ => self.edit(conn, op, &req),
        };
        self.reply(conn, id.as_ref(), result);
    }

    /// The requests that read or change the document under its lock.
    fn edit(&self, conn: ConnId, op: &str, req: &Value) -> Reply {
        let mut doc = self.doc();
        let stroking = matches!(op, "stroke_frame" | "stroke_end");
        if let Some((owner, what)) = &doc.busy
            && !matches!(op, "set_remesh")
        {
            let who = if *owner == conn {
                "this tab"
            } else {
                "another tab"
            };
            return Err(ServeError::Refused(format!(
                "busy: {what} is running in {who}; wait or cancel it"
            )));
        }
        if let Some(s) = &doc.stroke
            && (s.owner != conn || !stroking)
        {
            return Err(ServeError::Refused(
                "busy: a stroke is in progress; release the mouse first".into(),
            ));
        }
        match op {
            "primitive" => {
                let spec = str_field(req, "spec")?;
                let soup = holey_shapes::parse_primitive(spec)
                    .map_err(|e| ServeError::Refused(format!("{spec}: {e}")))?;
                if soup.face_count() > self.config.max_faces {
                    return Err(ServeError::Refused(format!(
                        "{spec} has {} faces; the modeler's limit is {}",
                        soup.face_count(),
                        self.config.max_faces
                    )));
                }
                let mesh = to_dlfl(&soup, ImportOptions::default())
                    .map_err(|e| ServeError::Refused(format!("{spec}: {e}")))?
                    .mesh;
                let content = keep_workspace(&doc, Content::Model(mesh))?;
                self.leave_rind(&mut doc);
                doc.commit(content);
                self.publish(&doc);
                Ok(json!({"message": format!("created {spec}")}))
            }
            "workspace" => {
                let to = str_field(req, "workspace")?;
                if doc.content().workspace() == to {
                    return Ok(json!({}));
                }
                self.leave_rind(&mut doc);
                let content = doc.content().clone();
                let next = match to {
                    "model" => content.into_model()?,
                    "sculpt" => content.into_sculpt()?,
                    _ => {
                        return Err(ServeError::BadRequest(format!(
                            "unknown workspace {to:?} (model or sculpt)"
                        )));
                    }
                };
                doc.commit(next);
                self.publish(&doc);
                Ok(json!({}))
            }
            "undo" | "redo" => {
                if doc.rind.is_some() {
                    return Err(ServeError::Refused(
                        "finish or cancel the rind first".into(),
                    ));
                }
                let done = if op == "undo" { doc.undo() } else { doc.redo() };
                if !done {
                    return Err(ServeError::Refused(format!("nothing to {op}")));
                }
                self.publish(&doc);
                Ok(json!({}))
            }
            "insert_edge" | "delete_edge" | "handle" => {
                doc.check_version(req)?;
                if doc.rind.is_some() {
                    return Err(ServeError::Refused(
                        "finish or cancel the rind first".into(),
                    ));
                }
                let mut mesh = doc.model(op)?.clone();
                let preview =
                    op == "handle" && req.get("preview").and_then(Value::as_bool) == Some(true);
                let message = match op {
                    "insert_edge" => insert_edge(&doc, &mut mesh, req)?,
                    "delete_edge" => delete_edge(&doc, &mut mesh, req)?,
                    _ => handle(&doc, &mut mesh, req)?,
                };
                if preview {
                    let (display, _) = display_model(&mesh);
                    self.hub.send(
                        conn,
                        Out::Binary(encode(&display, FLAG_PREVIEW, doc.version(), None)),
                    );
                    return Ok(json!({"message": message, "preview": true}));
                }
                doc.commit(Content::Model(mesh));
                self.publish(&doc);
                Ok(json!({"message": message}))
            }
            "rind_begin" => {
                let thickness = num_field(req, "thickness")?;
                if doc.rind.is_some() {
                    return Err(ServeError::Refused("already in rind mode".into()));
                }
                let rind = Rind::from_mesh(doc.model("rind")?, thickness)
                    .map_err(|e| ServeError::Refused(format!("rind: {e}")))?;
                doc.rind = Some(RindMode { rind, thickness });
                doc.touch();
                self.publish(&doc);
                Ok(json!({"message": "click faces to punch (shift: peel)"}))
            }
            "rind_punch" => {
                doc.check_version(req)?;
                let face = index_field(req, "face")?;
                let peel = req.get("peel").and_then(Value::as_bool) == Some(true);
                let f =
                    *doc.index().faces.get(face).ok_or_else(|| {
                        ServeError::Refused(format!("face {face} does not exist"))
                    })?;
                let Some(mode) = doc.rind.as_mut() else {
                    return Err(ServeError::Refused("not in rind mode".into()));
                };
                let outcome = if peel {
                    mode.rind.peel(f)
                } else {
                    mode.rind.punch(f)
                }
                .map_err(|e| ServeError::Refused(format!("rind: {e}")))?;
                if let PunchOutcome::NotPunchable { reason } = outcome {
                    return Err(ServeError::Refused(format!(
                        "that face cannot be {}: {reason}",
                        if peel { "peeled" } else { "punched" }
                    )));
                }
                doc.touch();
                self.publish(&doc);
                Ok(json!({}))
            }
            "rind_end" => {
                let Some(mode) = doc.rind.take() else {
                    return Err(ServeError::Refused("not in rind mode".into()));
                };
                if req.get("commit").and_then(Value::as_bool) == Some(true) {
                    let t = mode.thickness;
                    doc.commit(Content::Model(mode.rind.into_mesh()));
                    self.publish(&doc);
                    Ok(json!({"message": format!("rind of thickness {t} committed")}))
                } else {
                    doc.touch();
                    self.publish(&doc);
                    Ok(json!({"message": "rind cancelled"}))
                }
            }
            "set_remesh" => {
                let detail = num_field(req, "detail")?;
                doc.remesh_detail = detail.clamp(0.0, 1.0);
                self.publish_state(&doc);
                Ok(json!({}))
            }
            "stroke_begin" => self.stroke_begin(conn, &mut doc, req),
            "stroke_frame" => self.stroke_frame(&mut doc, req),
            "stroke_end" => {
                let Some(stroke) = doc.stroke.take() else {
                    return Err(ServeError::Refused("no stroke in progress".into()));
                };
                let done = stroke.live.finish()?;
                let r = done.report;
                let changed = done.mesh != *doc.sculpt_mesh("sculpting")?;
                if changed {
                    doc.commit(Content::Sculpt(done.mesh));
                }
                self.publish(&doc);
                Ok(json!({
                    "changes": r.changes,
                    "engine_runs": r.engine_runs,
                    "frames": r.frames,
                    "ms": r.seconds * 1e3,
                }))
            }
            "" => Err(ServeError::BadRequest("the request has no \"op\"".into())),
            _ => Err(ServeError::BadRequest(format!("unknown op {op:?}"))),
        }
    }

    fn leave_rind(&self, doc: &mut Document) {
        doc.rind = None;
    }

    fn stroke_begin(&self, conn: ConnId, doc: &mut Document, req: &Value) -> Reply {
        let mesh = doc.sculpt_mesh("sculpting")?;
        let brush = match str_field(req, "brush")? {
            "inflate" => Brush::Inflate,
            "smooth" => Brush::Smooth,
            "grab" => Brush::Grab,
            "move" => Brush::Move,
            other => {
                return Err(ServeError::BadRequest(format!(
                    "unknown brush {other:?} (inflate, smooth, grab, move)"
                )));
            }
        };
        let radius = num_field(req, "radius")?;
        let strength = match brush {
            Brush::Move => 1.0,
            _ => num_field(req, "strength")?,
        };
        if brush != Brush::Move && radius <= 0.0 {
            return Err(ServeError::BadRequest("the radius must be positive".into()));
        }
        let point = point_field(req)?;
        // A frame that pushes the surface farther than a fraction of the
        // brush folds it over itself many times at once; every tab would
        // wait for that frame. The modeler's slider stays far below.
        if brush == Brush::Inflate && strength.abs() > MAX_INFLATE_PER_RADIUS * radius {
            return Err(ServeError::Refused(format!(
                "inflate strength {strength} is more than {MAX_INFLATE_PER_RADIUS} of the radius {radius} per frame"
            )));
        }
        let settings = BrushSettings {
            brush,
            radius,
            strength,
        };
        let mut live = LiveStroke::begin(mesh, settings, point, Options::default())?;
        live.set_preview(brush.is_drag());
        live.set_remesh(remesh_options(mesh, doc.remesh_detail));
        let display = doc.display().clone();
        let sent = display.positions.clone();
        doc.stroke = Some(ActiveStroke {
            owner: conn,
            live,
            display,
            sent,
        });
        self.stroke_frame(doc, req)
    }

    fn stroke_frame(&self, doc: &mut Document, req: &Value) -> Reply {
        let point = point_field(req)?;
        let version = doc.version();
        let Some(stroke) = doc.stroke.as_mut() else {
            return Err(ServeError::Refused("no stroke in progress".into()));
        };
        let frame = stroke.live.frame(point)?;
        let ms = frame.seconds * 1e3;
        let vanish = frame.corrected_odd.as_deref();
        let moved = &frame.mesh.positions;
        let bytes = if frame.connectivity_changed {
            let display = display_triangles(frame.mesh);
            let bytes = encode(&display, FLAG_PREVIEW, version, vanish);
            stroke.display = display;
            bytes
        } else {
            // A brush moves few vertices: send those only.
            encode_sparse(
                &stroke.display,
                &stroke.sent,
                moved,
                FLAG_PREVIEW,
                version,
                vanish,
            )
            .unwrap_or_else(|| {
                encode_positions(&stroke.display, moved, FLAG_PREVIEW, version, vanish)
            })
        };
        stroke.sent.clone_from(moved);
        let vanishing = vanish.map_or(0, |m| m.iter().filter(|&&b| b).count());
        self.hub.broadcast(&Out::Binary(bytes));
        Ok(json!({"ms": ms, "vanishing": vanishing}))
    }

    fn cancel(&self) -> Reply {
        let flag = self
            .cancel
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone();
        match flag {
            Some(f) => {
                f.store(true, Ordering::SeqCst);
                Ok(json!({"message": "cancelling"}))
            }
            None => Err(ServeError::Refused("nothing to cancel".into())),
        }
    }

    /// Starts a long operation on a worker thread.
    fn start_long(self: &Arc<Self>, conn: ConnId, id: Option<Value>, op: &str, req: &Value) {
        let started = (|| -> Result<(Mesh, Job, String), ServeError> {
            let mut doc = self.doc();
            if let Some((_, what)) = &doc.busy {
                return Err(ServeError::Refused(format!("busy: {what} is running")));
            }
            if doc.stroke.is_some() || doc.rind.is_some() {
                return Err(ServeError::Refused(
                    "busy: finish the stroke or the rind first".into(),
                ));
            }
            let mesh = doc.model(op)?.clone();
            let level = |name: &str, max: usize| -> Result<usize, ServeError> {
                let v = index_field(req, name)?;
                if v > max {
                    return Err(ServeError::Refused(format!(
                        "{op}: {name} {v} is more than the modeler allows ({max})"
                    )));
                }
                Ok(v)
            };
            let (job, what) = match op {
                "sierpinski" => {
                    let n = level("level", 8)?;
                    (Job::Sierpinski(n), format!("Sierpinski level {n}"))
                }
                "menger" => {
                    let n = level("level", 5)?;
                    // The thesis's generalized sponge by default; `exact`
                    // builds the true Menger sponge of a box.
                    let exact = req.get("exact").and_then(Value::as_bool) == Some(true);
                    let what = if exact {
                        format!("true Menger sponge level {n}")
                    } else {
                        format!("Menger level {n}")
                    };
                    (Job::Menger(n, exact), what)
                }
                _ => {
                    let n = level("levels", 8)?;
                    let scheme = match req.get("scheme").and_then(Value::as_str) {
                        Some("doo-sabin") => Scheme::DooSabin,
                        Some("catmull-clark") | None => Scheme::CatmullClark,
                        Some(other) => {
                            return Err(ServeError::BadRequest(format!(
                                "unknown scheme {other:?} (catmull-clark, doo-sabin)"
                            )));
                        }
                    };
                    (Job::Subdivide(scheme, n), format!("subdivision ×{n}"))
                }
            };
            doc.busy = Some((conn, what.clone()));
            self.publish_state(&doc);
            Ok((mesh, job, what))
        })();
        let (mesh, job, what) = match started {
            Ok(s) => s,
            Err(e) => return self.reply(conn, id.as_ref(), Err(e)),
        };
        let flag = Arc::new(AtomicBool::new(false));
        *self.cancel.lock().unwrap_or_else(|p| p.into_inner()) = Some(Arc::clone(&flag));
        let shared = Arc::clone(self);
        std::thread::spawn(move || shared.run_long(conn, id, mesh, job, what, flag));
    }

    fn run_long(
        &self,
        conn: ConnId,
        id: Option<Value>,
        mesh: Mesh,
        job: Job,
        what: String,
        flag: Arc<AtomicBool>,
    ) {
        let max_faces = self.config.max_faces;
        let (tx, rx) = mpsc::channel();
        let progress = tx.clone();
        // The worker owns its copy; if cancelled, its result is dropped
        // when it finishes.
        std::thread::spawn(move || {
            let result = job.run(mesh, max_faces, &|fraction, stage: String| {
                let _ = progress.send(Step::Progress(fraction, stage));
            });
            let _ = tx.send(Step::Done(Box::new(result)));
        });
        let start = Instant::now();
        let result = loop {
            if flag.load(Ordering::SeqCst) {
                break Err(ServeError::Cancelled);
            }
            match rx.recv_timeout(Duration::from_millis(200)) {
                Ok(Step::Done(r)) => break *r,
                Ok(Step::Progress(fraction, stage)) => self.progress(conn, &id, fraction, &stage),
                Err(mpsc::RecvTimeoutError::Timeout) => self.progress(
                    conn,
                    &id,
                    None,
                    &format!("{what}: {:.1} s", start.elapsed().as_secs_f64()),
                ),
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    break Err(ServeError::Refused(format!("{what} failed unexpectedly")));
                }
            }
        };
        // A cancel that raced with the end still wins: the user asked for
        // nothing to change.
        let result = if flag.load(Ordering::SeqCst) {
            Err(ServeError::Cancelled)
        } else {
            result
        };
        *self.cancel.lock().unwrap_or_else(|p| p.into_inner()) = None;
        let mut doc = self.doc();
        doc.busy = None;
        let reply = match result {
            Ok(mesh) => {
                let faces = mesh.face_count();
                doc.commit(Content::Model(mesh));
                self.publish(&doc);
                Ok(
                    json!({"message": format!("{what}: {faces} faces in {:.2} s", start.elapsed().as_secs_f64())}),
                )
            }
            Err(e) => {
                self.publish_state(&doc);
                Err(e)
            }
        };
        drop(doc);
        self.reply(conn, id.as_ref(), reply);
    }

    fn progress(&self, conn: ConnId, id: &Option<Value>, fraction: Option<f64>, stage: &str) {
        let msg = json!({"type": "progress", "id": id, "fraction": fraction, "stage": stage});
        self.hub.send(conn, Out::Text(msg.to_string()));
    }

    /// Replaces the document with an uploaded file (one undo step).
    pub fn import(&self, name: &str, bytes: &[u8]) -> Result<String, ServeError> {
        let format = std::path::Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .and_then(Format::from_extension)
            .ok_or_else(|| {
                ServeError::Refused(format!(
                    "{name}: unknown format (obj, off, ply, stl or dlfl)"
                ))
            })?;
        let file =
            holey_io::parse(format, bytes, name).map_err(|e| ServeError::Refused(e.to_string()))?;
        let faces = match &file {
            MeshFile::Dlfl(raw) => raw.face_count(),
            MeshFile::Poly(poly) => poly.face_count(),
        };
        if faces == 0 {
            return Err(ServeError::Refused(format!(
                "{name} has no faces: nothing to model"
            )));
        }
        let (content, note) = match file {
            MeshFile::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw)
                        .map_err(|e| ServeError::Refused(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw)
                    .map_err(|e| ServeError::Refused(format!("{name}: {e}")))?;
                (Content::Model(mesh), String::new())
            }
            MeshFile::Poly(poly) => {
                if poly.face_count() > self.config.max_faces {
                    return Err(ServeError::Refused(format!(
                        "{name} has {} faces; the modeler's limit is {}",
                        poly.face_count(),
                        self.config.max_faces
                    )));
                }
                match to_dlfl(&poly, ImportOptions::default()) {
                    Ok(imported) => (Content::Model(imported.mesh), String::new()),
                    // Any soup can be sculpted; the thesis's tools need a
                    // 2-manifold.
                    Err(e) => (
                        Content::Sculpt(poly_to_tri(&poly)?),
                        format!(" (not a 2-manifold, {e}: opened for sculpting)"),
                    ),
                }
            }
        };
        let mut doc = self.doc();
        if let Some((_, what)) = &doc.busy {
            return Err(ServeError::Refused(format!("busy: {what} is running")));
        }
        if doc.stroke.is_some() {
            return Err(ServeError::Refused("busy: a stroke is in progress".into()));
        }
        let content = match (&content, doc.content()) {
            (Content::Model(_), Content::Sculpt(_)) => content.into_sculpt()?,
            _ => content,
        };
        doc.rind = None;
        doc.commit(content);
        self.publish(&doc);
        Ok(format!("imported {name}{note}"))
    }

    /// The document as a file: bytes and a file name.
    pub fn export(&self, format: &str) -> Result<(Vec<u8>, String), ServeError> {
        let content = self.doc().content().clone();
        let mut bytes = Vec::new();
        let io = |e| ServeError::io("export", e);
        match format {
            "obj" => holey_io::obj::write(&mut bytes, &content.to_poly()).map_err(io)?,
            "ply" => {
                holey_io::ply::write(&mut bytes, &content.to_poly(), false, None).map_err(io)?
            }
            "off" => holey_io::off::write(&mut bytes, &content.to_poly()).map_err(io)?,
            "stl" => holey_io::stl::write(&mut bytes, &content.to_poly(), false).map_err(io)?,
            "dlfl" => {
                let Content::Model(mesh) = content.into_model()? else {
                    return Err(ServeError::Refused("no DLFL to export".into()));
                };
                holey_io::dlfl::write(&mut bytes, &mesh.to_raw()).map_err(io)?;
            }
            other => {
                return Err(ServeError::BadRequest(format!(
                    "unknown export format {other:?} (obj, ply, off, stl, dlfl)"
                )));
            }
        }
        Ok((bytes, format!("holey.{format}")))
    }
}

enum Step {
    Progress(Option<f64>, String),
    Done(Box<Result<Mesh, ServeError>>),
}

/// A long operation.
enum Job {
    Sierpinski(usize),
    Menger(usize, bool),
    Subdivide(Scheme, usize),
}

impl Job {
    fn run(
        self,
        mut mesh: Mesh,
        max_faces: usize,
        progress: &dyn Fn(Option<f64>, String),
    ) -> Result<Mesh, ServeError> {
        let refused = |e: String| ServeError::Refused(e);
        match self {
            Job::Sierpinski(n) => {
                progress(None, format!("Sierpinski level {n}"));
                sierpinski_capped(&mut mesh, n, max_faces).map_err(|e| refused(e.to_string()))?;
                Ok(mesh)
            }
            Job::Menger(n, exact) => {
                progress(None, format!("Menger level {n}"));
                let params = MengerParams {
                    iterations: n,
                    exact,
                    ..MengerParams::default()
                };
                menger_capped(&mut mesh, &params, max_faces).map_err(|e| refused(e.to_string()))?;
                Ok(mesh)
            }
            Job::Subdivide(scheme, n) => {
                // Level by level: each costs about four times the last.
                let total: f64 = (0..n).map(|k| 4f64.powi(k as i32)).sum();
                let mut done = 0.0;
                for k in 0..n {
                    progress(
                        Some(done / total.max(1.0)),
                        format!("subdivision level {} of {n}", k + 1),
                    );
                    mesh = subdivide_capped(&mesh, scheme, 1, max_faces)
                        .map_err(|e| refused(e.to_string()))?;
                    done += 4f64.powi(k as i32);
                }
                Ok(mesh)
            }
        }
    }
}

/// The remeshing of the detail slider: off at 0; otherwise edges around
/// `ℓ = L · 4^(1/2 − detail)` (L the mesh's mean edge length: the mesh as
/// it is at 1/2, twice as fine at 1, twice as coarse near 0), kept within
/// half to one and a half times ℓ.
fn remesh_options(mesh: &holey_topo::TriMesh, detail: f64) -> Option<RemeshOptions> {
    if detail <= 0.0 {
        return None;
    }
    let base = default_range(mesh)?;
    let scale = 4f64.powf(0.5 - detail.min(1.0));
    Some(RemeshOptions::new(Remesh {
        min_edge: base.min_edge * scale,
        max_edge: base.max_edge * scale,
    }))
}

/// The largest inflate displacement per frame the server accepts, as a
/// share of the brush radius.
pub const MAX_INFLATE_PER_RADIUS: f64 = 0.25;

/// A model made while the sculpt workspace is open is sculpted too.
fn keep_workspace(doc: &Document, content: Content) -> Result<Content, ServeError> {
    match doc.content() {
        Content::Sculpt(_) => content.into_sculpt(),
        Content::Model(_) => Ok(content),
    }
}

fn primitives() -> Value {
    let list: Vec<Value> = holey_shapes::PRIMITIVES
        .iter()
        .map(|p| json!({"name": p.name, "spec": format!("@{}", p.name), "about": p.summary}))
        .collect();
    json!({"primitives": list})
}

fn str_field<'a>(req: &'a Value, name: &str) -> Result<&'a str, ServeError> {
    req.get(name)
        .and_then(Value::as_str)
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a string")))
}

fn num_field(req: &Value, name: &str) -> Result<f64, ServeError> {
    req.get(name)
        .and_then(Value::as_f64)
        .filter(|v| v.is_finite())
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a finite number")))
}

fn index_field(req: &Value, name: &str) -> Result<usize, ServeError> {
    req.get(name)
        .and_then(Value::as_u64)
        .and_then(|v| usize::try_from(v).ok())
        .ok_or_else(|| ServeError::BadRequest(format!("\"{name}\" must be a non-negative integer")))
}

fn point_field(req: &Value) -> Result<DVec3, ServeError> {
    let bad = || ServeError::BadRequest("\"point\" must be [x, y, z] of finite numbers".into());
    let a = req.get("point").and_then(Value::as_array).ok_or_else(bad)?;
    if a.len() != 3 {
        return Err(bad());
    }
    let c = |i: usize| a[i].as_f64().filter(|v| v.is_finite()).ok_or_else(bad);
    Ok(DVec3::new(c(0)?, c(1)?, c(2)?))
}

fn pair(req: &Value, name: &str) -> Result<[usize; 2], ServeError> {
    let bad = || ServeError::BadRequest(format!("\"{name}\" must be two non-negative integers"));
    let a = req.get(name).and_then(Value::as_array).ok_or_else(bad)?;
    let get = |i: usize| {
        a.get(i)
            .and_then(Value::as_u64)
            .and_then(|v| usize::try_from(v).ok())
            .ok_or_else(bad)
    };
    if a.len() != 2 {
        return Err(bad());
    }
    Ok([get(0)?, get(1)?])
}

fn insert_edge(doc: &Document, mesh: &mut Mesh, req: &Value) -> Result<String, ServeError> {
    let bad =
        || ServeError::BadRequest("\"corners\" must be [[face, vertex], [face, vertex]]".into());
    let cs = req
        .get("corners")
        .and_then(Value::as_array)
        .ok_or_else(bad)?;
    if cs.len() != 2 {
        return Err(bad());
    }
    let mut pairs = Vec::with_capacity(2);
    for c in cs {
        pairs.push(pair(&json!({"c": c}), "c").map_err(|_| bad())?);
    }
    let mut corners = Vec::with_capacity(2);
    for [f, v] in pairs {
        corners.push(doc.corner(mesh, f, v)?);
    }
    let before = mesh.genus();
    mesh.insert_edge(corners[0], corners[1])
        .map_err(|e| ServeError::Refused(format!("insert edge: {e}")))?;
    Ok(format!(
        "edge inserted (genus {} → {})",
        before,
        mesh.genus()
    ))
}

fn delete_edge(doc: &Document, mesh: &mut Mesh, req: &Value) -> Result<String, ServeError> {
    let e = index_field(req, "edge")?;
    let edge = *doc
        .index()
        .edges
        .get(e)
        .ok_or_else(|| ServeError::Refused(format!("edge {e} does not exist")))?;
    let before = mesh.genus();
    mesh.delete_edge(edge)
        .map_err(|e| ServeError::Refused(format!("delete edge: {e}")))?;
    Ok(format!(
        "edge deleted (genus {} → {})",
        before,
        mesh.genus()
    ))
}

fn handle(doc: &Document, mesh: &mut Mesh, req: &Value) -> Result<String, ServeError> {
    let [fa, fb] = pair(req, "faces")?;
    let corner = |face: usize, vertex: Option<usize>| -> Result<_, ServeError> {
        match vertex {
            Some(v) => doc.corner(mesh, face, v),
            None => {
                let f =
                    *doc.index().faces.get(face).ok_or_else(|| {
                        ServeError::Refused(format!("face {face} does not exist"))
                    })?;
                mesh.face_corners(f)
                    .map_err(|e| ServeError::Refused(e.to_string()))?
                    .next()
                    .ok_or_else(|| ServeError::Refused(format!("face {face} has no corners")))
            }
        }
    };
    let vs = if req.get("corners").is_some_and(|c| !c.is_null()) {
        let [a, b] = pair(req, "corners")?;
        [Some(a), Some(b)]
    } else {
        [None, None]
    };
    let a = corner(fa, vs[0])?;
    let b = corner(fb, vs[1])?;
    let segments = req.get("segments").and_then(Value::as_u64).unwrap_or(4) as usize;
    if !(1..=64).contains(&segments) {
        return Err(ServeError::BadRequest("segments must be 1 to 64".into()));
    }
    let w = |name: &str| match req.get(name) {
        None | Some(Value::Null) => Ok(1.0),
        Some(_) => num_field(req, name),
    };
    let params = HandleParams::new(segments, w("w1")?, w("w2")?);
    let before = mesh.genus();
    create_handle(mesh, a, b, &params).map_err(|e| ServeError::Refused(format!("handle: {e}")))?;
    Ok(format!("handle (genus {} → {})", before, mesh.genus()))
}
