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
//! downloads), and `request` (the requests as types, read by serde).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, MutexGuard};

use serde_json::{Value, json};

use holey_model::cut::CutOffset;

use crate::auth::Gate;
use crate::doc::{Content, Document};
use crate::frame::{FLAG_PREVIEW, encode_masked};
use crate::persist::Saver;
use crate::{Config, ConnId, ServeError};
use request::{Request, StrokeFrame};

mod document;
mod files;
mod long;
mod mask;
mod model;
mod remesh;
mod request;
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

/// What a request asks, as far as [`refusal`] cares.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Asks {
    /// A stroke's next frame or its end.
    StrokeFrame,
    /// The remeshing setting, which may change while a long operation runs.
    SetRemesh,
    Other,
}

/// Why a request from `conn` cannot run now: a long operation is running
/// (only the remeshing setting may change meanwhile), or a stroke is in
/// progress and this is not its owner's next frame or end.
fn refusal(doc: &Document, conn: ConnId, asks: Asks) -> Option<ServeError> {
    if let Some((owner, what)) = &doc.busy
        && asks != Asks::SetRemesh
    {
        let who = if *owner == conn {
            "this tab"
        } else {
            "another tab"
        };
        return Some(ServeError::Refused(format!(
            "busy: {what} is running in {who}; wait or cancel it"
        )));
    }
    if let Some(s) = &doc.stroke
        && (s.owner != conn || asks != Asks::StrokeFrame)
    {
        return Some(ServeError::Refused(
            "busy: a stroke is in progress; release the mouse first".into(),
        ));
    }
    None
}

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

    /// A new tab: the state and the whole mesh; mid-stroke, then also
    /// the stroke's mesh as the other tabs were last sent it, since the
    /// stroke's next frames patch that (a tab without it could apply
    /// none of them until the stroke ended).
    pub fn hello(&self, conn: ConnId) {
        let doc = self.doc();
        self.hub.send(conn, Out::Text(doc.state_json().to_string()));
        self.hub.send(conn, Out::Binary(whole_frame(&doc)));
        if let Some(frame) = stroke_so_far(&doc) {
            self.hub.send(conn, Out::Binary(frame));
        }
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
        self.publish_with(doc, whole_frame(doc));
    }

    /// [`Self::publish`] with `frame` for the whole mesh: a commit frame
    /// ([`crate::frame::encode_commit`]) where every tab shows the
    /// document's display already.
    fn publish_with(&self, doc: &Document, frame: Vec<u8>) {
        self.hub.broadcast(&Out::Text(doc.state_json().to_string()));
        self.hub.broadcast(&Out::Binary(frame));
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
        let message: Value = match serde_json::from_str(text) {
            Ok(v) => v,
            Err(e) => return self.reply_error(conn, None, &format!("bad request: {e}")),
        };
        let id = message.get("id").cloned();
        let request = match request::parse(&message) {
            Ok(r) => r,
            Err(e) => return self.reply(conn, id.as_ref(), Err(e)),
        };
        // `parse` accepted it, so the op is one of `request::OPS`.
        let op = message
            .get("op")
            .and_then(Value::as_str)
            .unwrap_or_default();
        let result = match request {
            Request::Sierpinski { .. }
            | Request::Menger { .. }
            | Request::Subdivide { .. }
            | Request::Remesh(_)
            | Request::Wireframe { .. }
            | Request::Tool(_)
            | Request::Hull { .. } => {
                return self.start_long(conn, id, op, request);
            }
            Request::Cancel => self.cancel(),
            Request::Hello => {
                self.hello(conn);
                Ok(json!({}))
            }
            Request::Primitives => Ok(primitives()),
            Request::RemeshSchemes => Ok(remesh::schemes_json()),
            Request::StrokeFrame(f) => return self.stroke_frame_answered(conn, id.as_ref(), &f),
            edit => self.edit(conn, op, edit),
        };
        self.reply(conn, id.as_ref(), result);
    }

    /// A stroke frame, answered before its frame goes out: the tab sends
    /// its next dabs as soon as the answer comes, so the server computes
    /// them while the tab reads and draws this frame (the other way round,
    /// the tab read and drew the frame first, and the server sat idle).
    /// Both go out under the document's lock, so every tab still gets the
    /// frames in the order of the strokes' state (a tab joining sees the
    /// stroke as it was before this frame, and then the frame).
    fn stroke_frame_answered(&self, conn: ConnId, id: Option<&Value>, req: &StrokeFrame) {
        let mut doc = self.doc();
        let (result, frame) = match refusal(&doc, conn, Asks::StrokeFrame) {
            Some(e) => (Err(e), None),
            None => self.stroke_frame(&mut doc, req),
        };
        self.reply(conn, id, result);
        if let Some(bytes) = frame {
            self.hub.broadcast(&Out::Binary(bytes));
        }
    }

    /// The requests that read or change the document under its lock.
    fn edit(&self, conn: ConnId, op: &str, request: Request) -> Reply {
        let mut doc = self.doc();
        let asks = match request {
            Request::StrokeFrame(_) | Request::StrokeEnd => Asks::StrokeFrame,
            Request::SetRemesh { .. } => Asks::SetRemesh,
            _ => Asks::Other,
        };
        if let Some(e) = refusal(&doc, conn, asks) {
            return Err(e);
        }
        let doc = &mut *doc;
        match request {
            Request::Primitive { spec } => self.create_primitive(doc, &spec),
            Request::Workspace { workspace } => self.switch_workspace(doc, &workspace),
            Request::Undo | Request::Redo => self.undo_redo(doc, op),
            Request::InsertEdge { version, corners } => {
                self.model_edit(conn, doc, op, version, false, |doc, mesh| {
                    model::insert_edge(doc, mesh, corners)
                })
            }
            Request::DeleteEdge { version, edge } => {
                self.model_edit(conn, doc, op, version, false, |doc, mesh| {
                    model::delete_edge(doc, mesh, edge)
                })
            }
            Request::Handle(h) => {
                let preview = h.preview == Some(true);
                self.model_edit(conn, doc, op, h.version, preview, |doc, mesh| {
                    model::handle(doc, mesh, &h)
                })
            }
            Request::Extrude(e) => self.extrude(doc, &e),
            Request::Cut(c) => {
                let offset = CutOffset::Distance(c.distance);
                self.cut_or_truncate(doc, op, c.version, &c.targets(), offset)
            }
            Request::Truncate(t) => {
                let offset = CutOffset::Fraction(t.fraction);
                if t.all == Some(true) {
                    self.truncate_all(doc, t.version, offset)
                } else {
                    self.cut_or_truncate(doc, op, t.version, &t.targets(), offset)
                }
            }
            Request::Select(s) => self.select(doc, &s),
            Request::RindBegin { thickness } => self.rind_begin(doc, thickness),
            Request::RindPunch {
                version,
                face,
                peel,
            } => self.rind_punch(doc, version, face, peel == Some(true)),
            Request::RindEnd { commit } => self.rind_end(doc, commit == Some(true)),
            Request::Weld { distance } => self.repair(doc, Some(distance)),
            Request::MakeManifold => self.repair(doc, None),
            Request::SetRemesh { detail } => self.set_remesh(doc, detail),
            Request::StrokeBegin(s) => self.stroke_begin(conn, doc, &s),
            Request::StrokeEnd => self.stroke_end(doc),
            Request::MaskPaint(p) => self.mask_paint(doc, &p),
            Request::MaskClear | Request::MaskInvert => self.mask_clear_or_invert(doc, op),
            // `request` answers these without the document's lock, or
            // (stroke frames) answers before it sends the frame.
            Request::Hello
            | Request::StrokeFrame(_)
            | Request::Primitives
            | Request::RemeshSchemes
            | Request::Cancel
            | Request::Sierpinski { .. }
            | Request::Menger { .. }
            | Request::Subdivide { .. }
            | Request::Remesh(_)
            | Request::Wireframe { .. }
            | Request::Tool(_)
            | Request::Hull { .. } => Err(ServeError::BadRequest(format!(
                "{op:?} is not an edit of the document"
            ))),
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

/// The live stroke's mesh as a whole preview frame: its display's
/// connectivity (what its patch frames apply to) at the positions the
/// tabs were last sent (its sparse frames move those); `None` without a
/// stroke.
fn stroke_so_far(doc: &Document) -> Option<Vec<u8>> {
    let stroke = doc.stroke.as_ref()?;
    let mut display = stroke.display.clone();
    if stroke.sent.len() == display.positions.len() {
        display.positions.clone_from(&stroke.sent);
    }
    let masked = crate::doc::mask_flags(doc.mask(), &display.positions);
    Some(encode_masked(
        &display,
        FLAG_PREVIEW,
        doc.version(),
        None,
        masked.as_deref(),
    ))
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
