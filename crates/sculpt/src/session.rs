//! A sculpting session (Bernstein & Wojtan 2013, §4): it owns the mesh,
//! applies strokes with incidental topology change, keeps undo and redo of
//! whole strokes and the diagnostics of the last change.
//!
//! - Inflate and smooth run the topology change between every pair of
//!   frames, so a collision changes topology at once.
//! - Grab and move accumulate raw collision parity over all frames of the
//!   drag ([`holey_topo::Accumulator`]) and change topology once, at
//!   release; dragging back to the start cancels the change, because every
//!   collision is then undone by its reverse.
//!
//! Everything is deterministic: the engine decides every tie exactly
//! (simulation of simplicity), and the brushes use no randomness, so a
//! session needs no seed and replaying the same strokes on the same mesh
//! gives the same mesh bit for bit.

use std::time::Instant;

use glam::DVec3;
use holey_topo::mesh::MeshError;
use holey_topo::{Accumulator, Options, Outcome, TopoError, TriMesh, topology_change};

use crate::brush::{Brush, closest_point, component_of, grab_weights, inflate, smooth};
use crate::strokes::{Remesh, Stroke, StrokeFile};

/// An error an observer of frames may return (writing a picture, say).
pub type ObserverError = Box<dyn std::error::Error + Send + Sync>;

/// Why a stroke was refused. The session is left as it was.
#[derive(Debug, thiserror::Error)]
pub enum SculptError {
    #[error("the mesh: {0}")]
    Mesh(MeshError),
    #[error("{brush}: nothing to pick, the mesh has no triangles")]
    NoSurface { brush: Brush },
    #[error(
        "{brush}: the first path point {point} is {distance:.6} from the surface, farther than {limit:.6} ({why})"
    )]
    PickTooFar {
        brush: Brush,
        point: DVec3,
        distance: f64,
        limit: f64,
        why: &'static str,
    },
    #[error("frame {frame}: topology change failed: {source}")]
    Topo { frame: usize, source: TopoError },
    #[error("frame {frame}: {source}")]
    Observer { frame: usize, source: ObserverError },
    /// An error of a stroke of a replayed file; `index` counts from 0.
    #[error("stroke {index} ({brush}): {source}")]
    Stroke {
        index: usize,
        brush: Brush,
        source: Box<SculptError>,
    },
}

/// The state after one frame, for pictures and live preview.
#[derive(Debug)]
pub struct Frame<'a> {
    /// The frame within its stroke: one per path point, from 0.
    pub index: usize,
    /// The surface at the end of the frame. During a drag it is the
    /// dragged surface before the topology change; the last frame of a
    /// drag shows the result of the release.
    pub mesh: &'a TriMesh,
    /// During a drag with preview on ([`Session::set_preview`]): the
    /// corrected parity of `mesh`'s vertices (`true` = would be deleted at
    /// release), the immediate feedback of §4.
    pub corrected_odd: Option<&'a [bool]>,
}

/// What one stroke did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrokeReport {
    pub brush: Option<Brush>,
    /// Path points replayed.
    pub frames: usize,
    /// Runs of the topology-change engine (frames that moved something,
    /// or the release of a drag).
    pub engine_runs: usize,
    /// Engine runs that cut the surface (some intersection curve was
    /// inserted or some triangle deleted).
    pub changes: usize,
    /// Odd vertices over all engine runs, before and after correction.
    pub raw_odd_vertices: usize,
    pub corrected_odd_vertices: usize,
    pub triangles_before: usize,
    pub triangles_after: usize,
    pub seconds: f64,
}

/// The diagnostics of the last topology change (§4's parity display).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// Raw parity per vertex of the mesh the change started from.
    pub raw_odd: Vec<bool>,
    /// Corrected parity per vertex of the same mesh.
    pub corrected_odd: Vec<bool>,
    /// Intersection curves at the end positions of that change.
    pub intersection_curves: usize,
}

impl Diagnostics {
    fn of(outcome: &Outcome) -> Diagnostics {
        Diagnostics {
            raw_odd: outcome.raw_odd.clone(),
            corrected_odd: outcome.corrected_odd.clone(),
            intersection_curves: outcome.intersections.curve_count,
        }
    }
}

/// A sculpting session: the mesh, the undo and redo stacks of whole
/// strokes, the engine's options and the last diagnostics.
#[derive(Clone, Debug)]
pub struct Session {
    mesh: TriMesh,
    options: Options,
    preview: bool,
    remesh: Option<Remesh>,
    undo: Vec<TriMesh>,
    redo: Vec<TriMesh>,
    diagnostics: Diagnostics,
}

/// The share of the bounding-box diagonal within which a move's first
/// point must lie from the surface: a move picks a whole component, so it
/// tolerates more slack than a brush radius, but not a click in the void.
pub const MOVE_PICK_FRACTION: f64 = 0.1;

impl Session {
    /// Starts a session on `mesh` with the engine's default options.
    pub fn new(mesh: TriMesh) -> Result<Session, SculptError> {
        Session::with_options(mesh, Options::default())
    }

    /// Starts a session with the given engine options.
    pub fn with_options(mesh: TriMesh, options: Options) -> Result<Session, SculptError> {
        mesh.check().map_err(SculptError::Mesh)?;
        Ok(Session {
            mesh,
            options,
            preview: false,
            remesh: None,
            undo: Vec::new(),
            redo: Vec::new(),
            diagnostics: Diagnostics::default(),
        })
    }

    /// The current mesh.
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// Ends the session, giving back the mesh.
    pub fn into_mesh(self) -> TriMesh {
        self.mesh
    }

    /// The diagnostics of the last topology change.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// Computes the corrected parity every frame of a drag for live
    /// preview (§4). Off by default: it costs a static-intersection pass
    /// and a correction per frame.
    pub fn set_preview(&mut self, on: bool) {
        self.preview = on;
    }

    /// Stores the remeshing range of a stroke file. Dynamic remeshing is
    /// not implemented yet, so this has no effect on strokes.
    pub fn set_remesh(&mut self, remesh: Option<Remesh>) {
        self.remesh = remesh;
    }

    /// The stored remeshing range (not applied; see [`Session::set_remesh`]).
    pub fn remesh(&self) -> Option<Remesh> {
        self.remesh
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Undoes the last stroke, restoring the exact mesh before it. False
    /// when there is nothing to undo.
    pub fn undo(&mut self) -> bool {
        match self.undo.pop() {
            Some(m) => {
                self.redo.push(std::mem::replace(&mut self.mesh, m));
                true
            }
            None => false,
        }
    }

    /// Redoes the last undone stroke, restoring the exact mesh after it.
    pub fn redo(&mut self) -> bool {
        match self.redo.pop() {
            Some(m) => {
                self.undo.push(std::mem::replace(&mut self.mesh, m));
                true
            }
            None => false,
        }
    }

    /// Applies one stroke (one undo step).
    pub fn apply_stroke(&mut self, stroke: &Stroke) -> Result<StrokeReport, SculptError> {
        self.apply_stroke_observed(stroke, &mut |_| Ok(()))
    }

    /// Applies one stroke, showing every frame to `observer`. On error the
    /// session is unchanged.
    pub fn apply_stroke_observed(
        &mut self,
        stroke: &Stroke,
        observer: &mut dyn FnMut(&Frame<'_>) -> Result<(), ObserverError>,
    ) -> Result<StrokeReport, SculptError> {
        let started = Instant::now();
        let mut report = StrokeReport {
            brush: Some(stroke.brush),
            frames: stroke.path.len(),
            triangles_before: self.mesh.triangles.len(),
            ..StrokeReport::default()
        };
        let (mesh, diagnostics) = if stroke.brush.is_drag() {
            self.drag(stroke, &mut report, observer)?
        } else {
            self.paint(stroke, &mut report, observer)?
        };
        report.triangles_after = mesh.triangles.len();
        report.seconds = started.elapsed().as_secs_f64();
        self.undo.push(std::mem::replace(&mut self.mesh, mesh));
        self.redo.clear();
        if let Some(d) = diagnostics {
            self.diagnostics = d;
        }
        Ok(report)
    }

    /// Replays a stroke file: its remeshing range is stored and every
    /// stroke applied in order, one undo step each. `observer` sees the
    /// stroke index and each frame. On error nothing is applied and the
    /// error names the stroke.
    pub fn replay(
        &mut self,
        file: &StrokeFile,
        observer: &mut dyn FnMut(usize, &Frame<'_>) -> Result<(), ObserverError>,
    ) -> Result<Vec<StrokeReport>, SculptError> {
        let saved = self.clone();
        self.set_remesh(file.remesh);
        let mut reports = Vec::with_capacity(file.strokes.len());
        for (index, stroke) in file.strokes.iter().enumerate() {
            match self.apply_stroke_observed(stroke, &mut |f| observer(index, f)) {
                Ok(r) => reports.push(r),
                Err(e) => {
                    *self = saved;
                    return Err(SculptError::Stroke {
                        index,
                        brush: stroke.brush,
                        source: Box::new(e),
                    });
                }
            }
        }
        Ok(reports)
    }

    /// Inflate and smooth: the engine between every pair of frames (§4).
    fn paint(
        &self,
        stroke: &Stroke,
        report: &mut StrokeReport,
        observer: &mut dyn FnMut(&Frame<'_>) -> Result<(), ObserverError>,
    ) -> Result<(TriMesh, Option<Diagnostics>), SculptError> {
        let mut mesh = self.mesh.clone();
        let mut diagnostics = None;
        for (frame, &centre) in stroke.path.iter().enumerate() {
            let end = match stroke.brush {
                Brush::Smooth => smooth(&mesh, centre, stroke.radius, stroke.strength),
                _ => inflate(&mesh, centre, stroke.radius, stroke.strength),
            };
            // A frame that moves nothing cannot collide; skipping it also
            // keeps a brush that wanders off the surface from re-cutting
            // intersections the mesh already had.
            if end != mesh.positions {
                let out = topology_change(&mesh, &end, &self.options)
                    .map_err(|source| SculptError::Topo { frame, source })?;
                tally(report, &out);
                diagnostics = Some(Diagnostics::of(&out));
                // The engine's output has no unused vertices.
                mesh = out.mesh;
            }
            observer(&Frame {
                index: frame,
                mesh: &mesh,
                corrected_odd: None,
            })
            .map_err(|source| SculptError::Observer { frame, source })?;
        }
        Ok((mesh, diagnostics))
    }

    /// Grab and move: parity accumulated over the drag, one topology
    /// change at release (§4).
    fn drag(
        &self,
        stroke: &Stroke,
        report: &mut StrokeReport,
        observer: &mut dyn FnMut(&Frame<'_>) -> Result<(), ObserverError>,
    ) -> Result<(TriMesh, Option<Diagnostics>), SculptError> {
        let start = &self.mesh;
        let weights = self.pick(stroke)?;
        let Some((&first, rest)) = stroke.path.split_first() else {
            return Ok((start.clone(), None));
        };
        let last = rest.len();
        let mut acc = Accumulator::new(start.clone(), self.options)
            .map_err(|source| SculptError::Topo { frame: 0, source })?;
        let mut view = start.clone();
        for (frame, &point) in stroke.path.iter().enumerate() {
            if frame > 0 {
                let offset = point - first;
                // Weight 0 keeps a vertex bit-exact, and a zero offset
                // (back at the start) restores every position exactly.
                let next: Vec<DVec3> = start
                    .positions
                    .iter()
                    .zip(&weights)
                    .map(|(&p, &w)| if w == 0.0 { p } else { p + w * offset })
                    .collect();
                acc.advance(&next)
                    .map_err(|source| SculptError::Topo { frame, source })?;
                view.positions = next;
            }
            if frame == last {
                break;
            }
            let preview = if self.preview {
                Some(
                    acc.corrected_parity()
                        .map_err(|source| SculptError::Topo { frame, source })?,
                )
            } else {
                None
            };
            observer(&Frame {
                index: frame,
                mesh: &view,
                corrected_odd: preview.as_deref(),
            })
            .map_err(|source| SculptError::Observer { frame, source })?;
        }
        if acc.frames() == 0 {
            // A click without a drag: nothing moved, nothing to change.
            observer(&Frame {
                index: last,
                mesh: start,
                corrected_odd: None,
            })
            .map_err(|source| SculptError::Observer {
                frame: last,
                source,
            })?;
            return Ok((start.clone(), None));
        }
        let out = acc.release().map_err(|source| SculptError::Topo {
            frame: last,
            source,
        })?;
        tally(report, &out);
        let diagnostics = Diagnostics::of(&out);
        let mesh = out.mesh;
        observer(&Frame {
            index: last,
            mesh: &mesh,
            corrected_odd: None,
        })
        .map_err(|source| SculptError::Observer {
            frame: last,
            source,
        })?;
        Ok((mesh, Some(diagnostics)))
    }

    /// The per-vertex drag weights of a grab or move, after checking that
    /// the first path point is near the surface.
    fn pick(&self, stroke: &Stroke) -> Result<Vec<f64>, SculptError> {
        let brush = stroke.brush;
        let point = stroke.path.first().copied().unwrap_or_default();
        let Some((triangle, picked, distance)) = closest_point(&self.mesh, point) else {
            return Err(SculptError::NoSurface { brush });
        };
        let (limit, why) = match brush {
            Brush::Move => (
                MOVE_PICK_FRACTION * diagonal(&self.mesh),
                "10% of the bounding-box diagonal",
            ),
            _ => (stroke.radius, "the brush radius"),
        };
        // Written so that a NaN distance is refused too.
        let near = distance <= limit;
        if !near {
            return Err(SculptError::PickTooFar {
                brush,
                point,
                distance,
                limit,
                why,
            });
        }
        Ok(match brush {
            Brush::Move => component_of(&self.mesh, triangle)
                .into_iter()
                .map(|held| if held { 1.0 } else { 0.0 })
                .collect(),
            _ => grab_weights(&self.mesh, picked, stroke.radius)
                .into_iter()
                .map(|w| w * stroke.strength)
                .collect(),
        })
    }
}

fn tally(report: &mut StrokeReport, out: &Outcome) {
    report.engine_runs += 1;
    let r = &out.report;
    if r.cut.triangles_split > 0 || r.cut.triangles_deleted > 0 {
        report.changes += 1;
    }
    report.raw_odd_vertices += r.raw_odd_vertices;
    report.corrected_odd_vertices += r.corrected_odd_vertices;
}

/// The bounding-box diagonal of the vertices triangles use.
fn diagonal(mesh: &TriMesh) -> f64 {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for t in &mesh.triangles {
        for &v in t {
            let p = mesh.positions[v as usize];
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    if lo.x <= hi.x { lo.distance(hi) } else { 0.0 }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn triangle_mesh() -> TriMesh {
        TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(9.0)],
            triangles: vec![[0, 1, 2]],
        }
    }

    #[test]
    fn bad_mesh_is_refused() {
        let mut m = triangle_mesh();
        m.triangles.push([0, 1, 7]);
        assert!(matches!(Session::new(m), Err(SculptError::Mesh(_))));
    }

    #[test]
    fn picks_must_be_near_the_surface() {
        let mut s = Session::new(triangle_mesh()).unwrap();
        let grab = Stroke {
            brush: Brush::Grab,
            radius: 0.5,
            strength: 1.0,
            path: vec![DVec3::new(0.2, 0.2, 0.6), DVec3::ZERO],
        };
        let e = s.apply_stroke(&grab).unwrap_err();
        assert!(matches!(e, SculptError::PickTooFar { .. }), "{e}");
        let mv = Stroke {
            brush: Brush::Move,
            radius: 0.0,
            strength: 1.0,
            path: vec![DVec3::new(0.2, 0.2, 0.2), DVec3::ZERO],
        };
        assert!(s.apply_stroke(&mv).is_err());
        assert!(!s.can_undo(), "a refused stroke is not an undo step");
        let mut empty = Session::new(TriMesh::default()).unwrap();
        assert!(matches!(
            empty.apply_stroke(&mv),
            Err(SculptError::NoSurface { .. })
        ));
    }

    #[test]
    fn inflate_off_the_surface_changes_nothing() {
        let mut s = Session::new(triangle_mesh()).unwrap();
        let r = s
            .apply_stroke(&Stroke {
                brush: Brush::Inflate,
                radius: 0.1,
                strength: 0.1,
                path: vec![DVec3::splat(5.0)],
            })
            .unwrap();
        assert_eq!(r.engine_runs, 0);
        assert_eq!(s.mesh(), &triangle_mesh());
        assert!(s.can_undo());
    }
}
