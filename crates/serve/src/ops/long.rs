//! Long operations on a worker thread, with progress and cancel.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use holey_dlfl::Mesh;
use holey_model::menger::{MengerParams, menger_capped};
use holey_model::sierpinski::sierpinski_capped;
use holey_subdiv::{Scheme, subdivide_capped};
use serde_json::{Value, json};

use super::fields::index_field;
use super::{Out, Shared};
use crate::doc::Content;
use crate::{ConnId, ServeError};

impl Shared {
    /// Starts a long operation on a worker thread.
    pub(super) fn start_long(
        self: &Arc<Self>,
        conn: ConnId,
        id: Option<Value>,
        op: &str,
        req: &Value,
    ) {
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
}

enum Step {
    Progress(Option<f64>, String),
    Done(Box<Result<Mesh, ServeError>>),
}

/// A long operation.
pub(super) enum Job {
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
