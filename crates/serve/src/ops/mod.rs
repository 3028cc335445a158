//! What each request does. See `web/PROTOCOL.md` for the messages.
//!
//! Short requests run on the connection's thread under the document's
//! lock. Long ones (Sierpinski, Menger, subdivision) run on a worker
//! thread from a copy of the mesh, report progress, and can be cancelled:
//! the document stays usable for viewing meanwhile, refuses other edits
//! ("busy"), and a cancelled result is dropped when the worker ends.
//!
//! This file holds the connections (`Hub`), the shared state and the
//! dispatch; one file per kind of request: `document` (primitives,
//! workspaces, undo and redo, repairs, settings), `model` (the thesis's
//! edits), `rind` (rind modeling), `sculpt` (strokes), `long` (long
//! operations: the fractals, subdivision, remeshing, wireframe, the
//! clean-up tools and the convex hulls), `mask` (the sculpt mask), `remesh` (TopMod's remeshing schemes and their
//! parameters), `toolbox` (extrusions, cuts and truncation of the
//! selection), `select` (selection queries), `files` (uploads and
//! downloads), and `fields` (reading a request).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, MutexGuard};

use serde_json::{Value, json};

use crate::auth::Gate;
use crate::doc::{Content, Document};
use crate::frame::encode_masked;
use crate::persist::Saver;
use crate::{Config, ConnId, ServeError};

mod document;
mod fields;
mod files;
mod long;
mod mask;
mod model;
mod remesh;
mod rind;
mod sculpt;
mod select;
mod toolbox;

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
}

/// What every connection thread shares.
pub struct Shared {
    pub config: Config,
    /// The `Host` check and the access token every request passes.
    pub gate: Gate,
    pub hub: Hub,
    doc: Mutex<Document>,
    saver: Saver,
    cancel: Mutex<Option<Arc<AtomicBool>>>,
}

type Reply = Result<Value, ServeError>;

impl Shared {
    pub fn new(config: Config, gate: Gate, doc: Document) -> Arc<Shared> {
        let saver = Saver::start(config.state_dir.clone());
        Arc::new(Shared {
            config,
            gate,
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
        self.hub.send(conn, Out::Binary(whole_frame(&doc)));
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

    /// Sends every tab the state and the whole mesh (with the mask), and
    /// saves both.
    fn publish(&self, doc: &Document) {
        self.hub.broadcast(&Out::Text(doc.state_json().to_string()));
        self.hub.broadcast(&Out::Binary(whole_frame(doc)));
        if doc.rind.is_none() {
            self.saver
                .save(doc.version(), doc.content().clone(), Arc::clone(doc.mask()));
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
            "sierpinski" | "menger" | "subdivide" | "remesh" | "wireframe" | "tool" | "hull" => {
                return self.start_long(conn, id, op, &req);
            }
            "cancel" => self.cancel(),
            "hello" => {
                self.hello(conn);
                Ok(json!({}))
            }
            "primitives" => Ok(primitives()),
            "remesh_schemes" => Ok(remesh::schemes_json()),
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
        let doc = &mut *doc;
        match op {
            "primitive" => self.create_primitive(doc, req),
            "workspace" => self.switch_workspace(doc, req),
            "undo" | "redo" => self.undo_redo(doc, op),
            "insert_edge" | "delete_edge" | "handle" => self.model_edit(conn, doc, op, req),
            "extrude" => self.extrude(doc, req),
            "cut" | "truncate" => self.cut_or_truncate(doc, op, req),
            "select" => self.select(doc, req),
            "rind_begin" => self.rind_begin(doc, req),
            "rind_punch" => self.rind_punch(doc, req),
            "rind_end" => self.rind_end(doc, req),
            "weld" | "make_manifold" => self.repair(doc, op, req),
            "set_remesh" => self.set_remesh(doc, req),
            "stroke_begin" => self.stroke_begin(conn, doc, req),
            "stroke_frame" => self.stroke_frame(doc, req),
            "stroke_end" => self.stroke_end(doc),
            "mask_paint" | "mask_clear" | "mask_invert" => self.mask_edit(doc, op, req),
            "" => Err(ServeError::BadRequest("the request has no \"op\"".into())),
            _ => Err(ServeError::BadRequest(format!("unknown op {op:?}"))),
        }
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
}

/// The committed document as a whole frame, with the sculpt mask.
fn whole_frame(doc: &Document) -> Vec<u8> {
    let masked = doc.mask_flags();
    encode_masked(doc.display(), 0, doc.version(), None, masked.as_deref())
}

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
