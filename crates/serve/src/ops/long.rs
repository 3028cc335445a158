//! Long operations on a worker thread, with progress and cancel.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use holey_dlfl::{FaceId, Mesh, VertexId};
use holey_model::hull::{convex_hull, dual_convex_hull};
use holey_model::menger::{MengerParams, menger_capped};
use holey_model::sierpinski::sierpinski_capped;
use holey_model::tools::{
    PlanarizeParams, cleanup_two_gons, make_spherical, planarize_faces,
    remove_valence_two_vertices, split_valence_two_vertices,
};
use holey_model::wireframe::{ColumnParams, columns, wireframe};
use holey_subdiv::{RemeshParams, RemeshScheme, Scheme, remesh_capped, subdivide_capped};
use serde_json::{Value, json};

use super::remesh::read_request;
use super::request::{Request, ToolRequest, missing};
use super::toolbox::{counts, faces_of, plain_ids, vertices_of};
use super::{Out, Shared};
use crate::doc::{Content, Document};
use crate::frame::ModelIndex;
use crate::{ConnId, ServeError};

/// The most sides a column may have.
pub(super) const MAX_COLUMN_SIDES: usize = 64;

impl Shared {
    /// Starts a long operation on a worker thread.
    pub(super) fn start_long(
        self: &Arc<Self>,
        conn: ConnId,
        id: Option<Value>,
        op: &str,
        request: Request,
    ) {
        let started = (|| -> Result<Started, ServeError> {
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
            // The ids in the library's messages are named as the picture
            // the request was made on names them.
            let index = doc.index().clone();
            let at_most = |name: &str, v: usize, max: usize| -> Result<usize, ServeError> {
                if v > max {
                    return Err(ServeError::Refused(format!(
                        "{op}: {name} {v} is more than the modeler allows ({max})"
                    )));
                }
                Ok(v)
            };
            let (job, what) = match request {
                Request::Sierpinski { level } => {
                    let n = at_most("level", level, 8)?;
                    (Job::Sierpinski(n), format!("Sierpinski level {n}"))
                }
                Request::Menger { level, exact } => {
                    let n = at_most("level", level, 5)?;
                    // The thesis's generalized sponge by default; `exact`
                    // builds the true Menger sponge of a box.
                    let exact = exact == Some(true);
                    let what = if exact {
                        format!("true Menger sponge level {n}")
                    } else {
                        format!("Menger level {n}")
                    };
                    (Job::Menger(n, exact), what)
                }
                Request::Remesh(r) => {
                    let (scheme, params, n) = read_request(&r)?;
                    let what = if n == 1 {
                        format!("{scheme} remeshing")
                    } else {
                        format!("{scheme} remeshing ×{n}")
                    };
                    (Job::Remesh(scheme, Box::new(params), n), what)
                }
                Request::Wireframe { thickness, columns } => {
                    wireframe_job(&mesh, thickness, columns, self.config.max_faces)?
                }
                Request::Tool(t) => tool_job(&doc, &t)?,
                Request::Hull { dual } => {
                    let dual = dual == Some(true);
                    (Job::Hull(dual), hull_name(dual).into())
                }
                Request::Subdivide { scheme, levels } => {
                    let n = at_most("levels", levels, 8)?;
                    let scheme = match scheme.as_deref() {
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
                // `Shared::request` sends only the long operations here.
                _ => {
                    return Err(ServeError::BadRequest(format!(
                        "{op:?} is not a long operation"
                    )));
                }
            };
            doc.busy = Some((conn, what.clone()));
            self.publish_state(&doc);
            Ok(Started {
                mesh,
                job,
                what,
                index,
            })
        })();
        let started = match started {
            Ok(s) => s,
            Err(e) => return self.reply(conn, id.as_ref(), Err(e)),
        };
        let flag = Arc::new(AtomicBool::new(false));
        *self.cancel.lock().unwrap_or_else(|p| p.into_inner()) = Some(Arc::clone(&flag));
        let shared = Arc::clone(self);
        std::thread::spawn(move || shared.run_long(conn, id, started, flag));
    }

    fn run_long(&self, conn: ConnId, id: Option<Value>, started: Started, flag: Arc<AtomicBool>) {
        let Started {
            mesh,
            job,
            what,
            index,
        } = started;
        let max_faces = self.config.max_faces;
        let (tx, rx) = mpsc::channel();
        let progress = tx.clone();
        // The worker owns its copy; if cancelled, its result is dropped
        // when it finishes.
        std::thread::spawn(move || {
            let result = job
                .run(mesh, max_faces, &|fraction, stage: String| {
                    let _ = progress.send(Step::Progress(fraction, stage));
                })
                .map_err(|e| match e {
                    ServeError::Refused(m) => ServeError::Refused(plain_ids(&m, &index)),
                    other => other,
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
            Ok((mesh, note)) => {
                let faces = mesh.face_count() - mesh.hole_count();
                doc.commit(Content::Model(mesh));
                self.publish(&doc);
                Ok(
                    json!({"message": format!("{what}: {faces} faces{note} in {:.2} s", start.elapsed().as_secs_f64())}),
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

/// A long operation about to run: a copy of the model, the job, its
/// name, and the display indices of the picture it was asked on (for the
/// library's messages).
struct Started {
    mesh: Mesh,
    job: Job,
    what: String,
    index: ModelIndex,
}

enum Step {
    Progress(Option<f64>, String),
    Done(Box<Result<(Mesh, String), ServeError>>),
}

/// A long operation.
pub(super) enum Job {
    Sierpinski(usize),
    Menger(usize, bool),
    Subdivide(Scheme, usize),
    /// A remeshing scheme, its parameters, levels.
    Remesh(RemeshScheme, Box<RemeshParams>, usize),
    /// TopMod's wireframe, tubes this thick.
    Wireframe(f64),
    /// Columns of these sides and radius.
    Columns(ColumnParams),
    /// A clean-up tool.
    Tool(Tool),
    /// The convex hull of the vertices, or (true) TopMod's dual convex
    /// hull.
    Hull(bool),
}

/// The tools of TopMod's Tools menu.
pub(super) enum Tool {
    /// Planarize these faces (all when empty).
    Planarize(Vec<FaceId>),
    /// Project these vertices (all when empty) onto their sphere.
    Spherical(Vec<VertexId>),
    /// Merge every two-gon's edges.
    CleanupTwoGons,
    /// Remove the vertices of valence 2.
    RemoveValenceTwo,
    /// Split the vertices of valence 2, this far apart.
    SplitValenceTwo(f64),
}

/// `wireframe`: `thickness`, and `columns` (sides, 0 or absent for the
/// wireframe) whose radius is the thickness. The output's faces are
/// known from the counts (wireframe.rs) and checked against the cap
/// before anything is built.
fn wireframe_job(
    mesh: &Mesh,
    thickness: f64,
    columns: Option<usize>,
    max_faces: usize,
) -> Result<(Job, String), ServeError> {
    let sides = columns.unwrap_or(0);
    if sides != 0 && !(3..=MAX_COLUMN_SIDES).contains(&sides) {
        return Err(ServeError::BadRequest(format!(
            "\"columns\" must be 0 (the wireframe) or the sides of each column, 3 to {MAX_COLUMN_SIDES}"
        )));
    }
    let [v, e, _] = counts(mesh).map(|n| n as usize);
    // Wireframe: F' = 4E + 2V. Columns: F' ≤ nE + 2E + 2V (Σ(k + 2) over
    // the vertices is at most 2E + 2V).
    let faces = if sides == 0 {
        4 * e + 2 * v
    } else {
        sides * e + 2 * e + 2 * v
    };
    if faces > max_faces {
        return Err(ServeError::Refused(format!(
            "that would make about {faces} faces; the modeler's limit is {max_faces}"
        )));
    }
    Ok(if sides == 0 {
        (Job::Wireframe(thickness), format!("wireframe {thickness}"))
    } else {
        (
            Job::Columns(ColumnParams {
                sides,
                radius: thickness,
            }),
            format!("{sides}-sided columns {thickness}"),
        )
    })
}

/// `tool`: `tool` and what it acts on (`faces` for planarize, `faces` or
/// `vertices` for spherical, `distance` for splitting valence 2).
fn tool_job(doc: &Document, req: &ToolRequest) -> Result<(Job, String), ServeError> {
    doc.check_version(req.version)?;
    let name = req.tool.as_str();
    let tool = match name {
        "planarize" => Tool::Planarize(faces_of(doc, req.faces.as_deref())?),
        "spherical" => {
            let mut vs = vertices_of(doc, req.vertices.as_deref())?;
            let mesh = doc.model("spherical")?;
            for f in faces_of(doc, req.faces.as_deref())? {
                let ring = mesh
                    .face_vertices(f)
                    .map_err(|e| ServeError::Refused(e.to_string()))?;
                for v in ring {
                    if !vs.contains(&v) {
                        vs.push(v);
                    }
                }
            }
            Tool::Spherical(vs)
        }
        "cleanup" => Tool::CleanupTwoGons,
        "remove-valence-2" => Tool::RemoveValenceTwo,
        "split-valence-2" => {
            Tool::SplitValenceTwo(req.distance.ok_or_else(|| missing("tool", "distance"))?)
        }
        other => {
            return Err(ServeError::BadRequest(format!(
                "unknown tool {other:?} (planarize, spherical, cleanup, remove-valence-2, split-valence-2)"
            )));
        }
    };
    Ok((Job::Tool(tool), name.replace('-', " ")))
}

/// `hull`'s name; with `dual`, TopMod's dual convex hull. Neither can
/// outgrow the cap by much: the hull has at most 2V − 4 faces and its
/// dual one face per hull corner; the result is checked against the cap
/// when built.
fn hull_name(dual: bool) -> &'static str {
    if dual {
        "dual convex hull"
    } else {
        "convex hull"
    }
}

/// Runs `n` levels of a scheme one at a time, so that progress and cancel
/// work between them. A level costs about its output, which grows about
/// fourfold per level for subdivision and most remeshing schemes, so level
/// `k` weighs `4^k` in the progress.
fn by_levels(
    mut mesh: Mesh,
    n: usize,
    progress: &dyn Fn(Option<f64>, String),
    stage: impl Fn(usize) -> String,
    mut level: impl FnMut(&Mesh, usize) -> Result<Mesh, ServeError>,
) -> Result<Mesh, ServeError> {
    let total: f64 = (0..n).map(|k| 4f64.powi(k as i32)).sum();
    let mut finished = 0.0;
    for k in 0..n {
        progress(Some(finished / total.max(1.0)), stage(k));
        mesh = level(&mesh, k)?;
        finished += 4f64.powi(k as i32);
    }
    Ok(mesh)
}

impl Job {
    fn run(
        self,
        mut mesh: Mesh,
        max_faces: usize,
        progress: &dyn Fn(Option<f64>, String),
    ) -> Result<(Mesh, String), ServeError> {
        let refused = |e: String| ServeError::Refused(e);
        let done = |mesh: Mesh| Ok((mesh, String::new()));
        match self {
            Job::Sierpinski(n) => {
                progress(None, format!("Sierpinski level {n}"));
                sierpinski_capped(&mut mesh, n, max_faces).map_err(|e| refused(e.to_string()))?;
                done(mesh)
            }
            Job::Menger(n, exact) => {
                progress(None, format!("Menger level {n}"));
                let params = MengerParams {
                    iterations: n,
                    exact,
                    ..MengerParams::default()
                };
                menger_capped(&mut mesh, &params, max_faces).map_err(|e| refused(e.to_string()))?;
                done(mesh)
            }
            Job::Subdivide(scheme, n) => {
                let stage = |k: usize| format!("subdivision level {} of {n}", k + 1);
                let out = by_levels(mesh, n, progress, stage, |mesh, _| {
                    subdivide_capped(mesh, scheme, 1, max_faces).map_err(|e| refused(e.to_string()))
                })?;
                done(out)
            }
            Job::Remesh(scheme, params, n) => {
                let stage = |k: usize| format!("{scheme}: level {} of {n}", k + 1);
                let out = by_levels(mesh, n, progress, stage, |mesh, k| {
                    remesh_capped(mesh, scheme, &params, 1, max_faces).map_err(|e| {
                        refused(if n == 1 {
                            e.to_string()
                        } else {
                            format!("level {} of {n}: {e}", k + 1)
                        })
                    })
                })?;
                done(out)
            }
            Job::Wireframe(thickness) => {
                progress(None, "wireframe".into());
                let out = wireframe(&mesh, thickness).map_err(|e| refused(e.to_string()))?;
                done(out)
            }
            Job::Columns(params) => {
                progress(None, format!("{}-sided columns", params.sides));
                let out = columns(&mesh, &params).map_err(|e| refused(e.to_string()))?;
                done(out)
            }
            Job::Tool(tool) => tool.run(mesh, progress),
            Job::Hull(dual) => {
                let what = hull_name(dual);
                progress(None, format!("building the {what}"));
                let out = if dual {
                    dual_convex_hull(&mesh)
                } else {
                    convex_hull(&mesh)
                }
                .map_err(|e| refused(format!("{what}: {e}")))?;
                let faces = out.face_count() - out.hole_count();
                if faces > max_faces {
                    return Err(refused(format!(
                        "{what}: that would make {faces} faces; the modeler's limit is {max_faces}"
                    )));
                }
                done(out)
            }
        }
    }
}

impl Tool {
    fn run(
        self,
        mut mesh: Mesh,
        progress: &dyn Fn(Option<f64>, String),
    ) -> Result<(Mesh, String), ServeError> {
        let refused = |e: &dyn std::fmt::Display| ServeError::Refused(e.to_string());
        let note = match self {
            Tool::Planarize(faces) => {
                progress(None, "planarizing".into());
                let r = planarize_faces(&mut mesh, &faces, &PlanarizeParams::default())
                    .map_err(|e| refused(&e))?;
                format!(
                    " ({} faces off their planes by {:.2e} → {:.2e} of the edge length after {} iterations{})",
                    r.faces,
                    r.before,
                    r.after,
                    r.iterations,
                    if r.converged { "" } else { ", not converged" }
                )
            }
            Tool::Spherical(vertices) => {
                let fit = make_spherical(&mut mesh, &vertices).map_err(|e| refused(&e))?;
                format!(
                    " (on the sphere of radius {:.4} about ({:.3}, {:.3}, {:.3}))",
                    fit.radius, fit.centre.x, fit.centre.y, fit.centre.z
                )
            }
            Tool::CleanupTwoGons => {
                let n = cleanup_two_gons(&mut mesh);
                format!(" ({n} two-gons removed)")
            }
            Tool::RemoveValenceTwo => {
                let n = remove_valence_two_vertices(&mut mesh).map_err(|e| refused(&e))?;
                format!(" ({n} vertices of valence 2 removed)")
            }
            Tool::SplitValenceTwo(d) => {
                let n = split_valence_two_vertices(&mut mesh, d).map_err(|e| refused(&e))?;
                format!(" ({n} vertices of valence 2 split)")
            }
        };
        Ok((mesh, note))
    }
}
