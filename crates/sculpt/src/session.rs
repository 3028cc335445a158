//! A sculpting session (Bernstein & Wojtan 2013, §4): it owns the mesh,
//! applies strokes with incidental topology change, keeps undo and redo of
//! whole strokes and the diagnostics of the last change.
//!
//! - Inflate, smooth and the snake hook run the topology change between every pair of
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

use glam::DVec3;
use holey_topo::{Options, TriMesh};

use crate::live::{BrushSettings, Handover, LiveStroke};
use crate::remesh::{RemeshOptions, default_range};
pub use crate::report::{Diagnostics, ObserverError, SculptError, StrokeReport};
use crate::strokes::{Remesh, Stroke, StrokeFile};
use crate::symmetry::{About, Symmetry};

/// The state after one frame, for pictures and live preview.
#[derive(Debug)]
pub struct Frame<'a> {
    /// The frame within its stroke, from 0: one per path point, or per
    /// group of points the stroke's `frames` makes.
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

/// A sculpting session: the mesh, the undo and redo stacks of whole
/// strokes, the engine's options and the last diagnostics.
#[derive(Clone, Debug)]
pub struct Session {
    mesh: TriMesh,
    options: Options,
    preview: bool,
    /// The range of a stroke file; `None` uses `derived`.
    remesh: Option<Remesh>,
    /// The range derived from the starting mesh's mean edge length.
    derived: Option<Remesh>,
    remeshing: bool,
    undo: Vec<TriMesh>,
    redo: Vec<TriMesh>,
    diagnostics: Diagnostics,
    /// The far field the last paint stroke finished with, for the next
    /// stroke (`holey_topo::FarField`), and whether it knew the surface to
    /// be one piece: valid while `mesh` is the surface that stroke left,
    /// so every other change of `mesh` drops them.
    kept: KeptField,
}

/// What the last paint stroke handed on ([`Handover`]), kept between
/// strokes. A copy of a session starts without it: it is as cheap to
/// build again as to share safely.
#[derive(Debug, Default)]
struct KeptField(Handover);

impl Clone for KeptField {
    fn clone(&self) -> KeptField {
        KeptField::default()
    }
}

impl Session {
    /// Starts a session on `mesh` with the engine's default options.
    pub fn new(mesh: TriMesh) -> Result<Session, SculptError> {
        Session::with_options(mesh, Options::default())
    }

    /// Starts a session with the given engine options.
    pub fn with_options(mesh: TriMesh, options: Options) -> Result<Session, SculptError> {
        mesh.check().map_err(SculptError::Mesh)?;
        Ok(Session {
            derived: default_range(&mesh),
            mesh,
            options,
            preview: false,
            remesh: None,
            remeshing: true,
            undo: Vec::new(),
            redo: Vec::new(),
            diagnostics: Diagnostics::default(),
            kept: KeptField::default(),
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

    /// Sets the target edge-length range of dynamic remeshing (a stroke
    /// file's `remesh`); `None` uses the range derived from the starting
    /// mesh's mean edge length ([`default_range`]).
    pub fn set_remesh(&mut self, remesh: Option<Remesh>) {
        self.remesh = remesh;
    }

    /// Turns dynamic remeshing on (the default) or off.
    pub fn set_remeshing(&mut self, on: bool) {
        self.remeshing = on;
    }

    /// The edge-length range strokes remesh to, or `None` when remeshing
    /// is off (or the mesh has no edge to measure).
    pub fn remesh(&self) -> Option<Remesh> {
        if self.remeshing {
            self.remesh.or(self.derived)
        } else {
            None
        }
    }

    /// Whether there is a stroke to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether there is an undone stroke to redo (a new stroke clears them).
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Undoes the last stroke, restoring the exact mesh before it. False
    /// when there is nothing to undo.
    pub fn undo(&mut self) -> bool {
        let moved = step_back(&mut self.mesh, &mut self.undo, &mut self.redo);
        if moved {
            self.kept = KeptField::default();
        }
        moved
    }

    /// Redoes the last undone stroke, restoring the exact mesh after it.
    pub fn redo(&mut self) -> bool {
        let moved = step_back(&mut self.mesh, &mut self.redo, &mut self.undo);
        if moved {
            self.kept = KeptField::default();
        }
        moved
    }

    /// Applies one stroke (one undo step).
    pub fn apply_stroke(&mut self, stroke: &Stroke) -> Result<StrokeReport, SculptError> {
        self.apply_stroke_observed(stroke, &mut |_| Ok(()))
    }

    /// Applies one stroke, showing every frame to `observer`. On error the
    /// session is unchanged.
    ///
    /// The observer sees one frame per path point, or per group of points
    /// the stroke's `frames` makes ([`Stroke::frame_groups`]). The last
    /// frame of a drag shows the result of the release.
    pub fn apply_stroke_observed(
        &mut self,
        stroke: &Stroke,
        observer: &mut dyn FnMut(&Frame<'_>) -> Result<(), ObserverError>,
    ) -> Result<StrokeReport, SculptError> {
        let centre = match stroke.symmetry_about {
            About::Origin => DVec3::ZERO,
            About::Centre => box_centre(&self.mesh),
        };
        let settings = BrushSettings {
            falloff: stroke.falloff,
            symmetry: Symmetry {
                axes: stroke.symmetry,
                centre,
            },
            pressure: stroke.pressure_drives,
            ..BrushSettings::new(stroke.brush, stroke.radius, stroke.strength)
        };
        let first = stroke.path.first().copied().unwrap_or_default();
        let mut live = LiveStroke::begin(&self.mesh, settings, first, self.options)?;
        live.take_over(std::mem::take(&mut self.kept.0));
        // A stroke's own range wins over the file's, unless remeshing is
        // off altogether.
        let remesh = if self.remeshing {
            stroke.remesh_or(|| self.remesh())
        } else {
            None
        };
        live.set_remesh(remesh.map(RemeshOptions::new));
        if let Some(mask) = &stroke.mask {
            live.set_mask(mask.positions(&self.mesh.positions));
        }
        let drag = stroke.brush.is_drag();
        let groups = stroke.frame_groups();
        let last = groups.len().saturating_sub(1);
        for (index, dabs) in groups.iter().enumerate() {
            let release = drag && index == last;
            // The last frame of a drag is shown after the release.
            live.set_preview(self.preview && !release);
            let frame = live.frame_together(dabs)?;
            if !release {
                observer(&Frame {
                    index,
                    mesh: frame.mesh,
                    corrected_odd: frame.corrected_odd.as_deref(),
                })
                .map_err(|source| SculptError::Observer {
                    frame: index,
                    source,
                })?;
            }
        }
        let done = live.finish()?;
        if drag && !stroke.path.is_empty() {
            observer(&Frame {
                index: last,
                mesh: &done.mesh,
                corrected_odd: None,
            })
            .map_err(|source| SculptError::Observer {
                frame: last,
                source,
            })?;
        }
        self.commit(done.mesh, done.diagnostics);
        self.kept = KeptField(done.handover);
        Ok(done.report)
    }

    /// Makes `mesh` the current mesh as one undo step (a stroke finished
    /// elsewhere, by a [`LiveStroke`] the caller drove).
    pub fn commit(&mut self, mesh: TriMesh, diagnostics: Option<Diagnostics>) {
        self.kept = KeptField::default();
        self.undo.push(std::mem::replace(&mut self.mesh, mesh));
        self.redo.clear();
        if let Some(d) = diagnostics {
            self.diagnostics = d;
        }
    }

    /// The engine options strokes run with.
    pub fn options(&self) -> Options {
        self.options
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
}

/// Undo and redo alike: makes the last mesh of `from` the current one and
/// keeps the one it replaces on `to`. False when `from` is empty.
fn step_back(current: &mut TriMesh, from: &mut Vec<TriMesh>, to: &mut Vec<TriMesh>) -> bool {
    match from.pop() {
        Some(m) => {
            to.push(std::mem::replace(current, m));
            true
        }
        None => false,
    }
}

/// The centre of the bounding box of the vertices triangles use (the
/// origin for a mesh without triangles).
fn box_centre(mesh: &TriMesh) -> DVec3 {
    crate::live::used_bounds(mesh).map_or(DVec3::ZERO, |(lo, hi)| (lo + hi) * 0.5)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::brush::Brush;
    use crate::strokes::StrokeRemesh;
    use glam::DVec3;

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
            ..Stroke::default()
        };
        let e = s.apply_stroke(&grab).unwrap_err();
        assert!(matches!(e, SculptError::PickTooFar { .. }), "{e}");
        let mv = Stroke {
            brush: Brush::Move,
            radius: 0.0,
            strength: 1.0,
            path: vec![DVec3::new(0.2, 0.2, 0.2), DVec3::ZERO],
            ..Stroke::default()
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
                ..Stroke::default()
            })
            .unwrap();
        assert_eq!(r.engine_runs, 0);
        assert_eq!(s.mesh(), &triangle_mesh());
        assert!(s.can_undo());
    }

    /// A stroke's own `remesh` wins over the file's, and `--no-remesh`
    /// (remeshing off) wins over both: the modeler records the range each
    /// stroke remeshed to, and its replay must remesh to that.
    #[test]
    fn a_strokes_own_remeshing_wins_over_the_files() {
        let sphere = holey_shapes::icosphere(3).unwrap().triangulated();
        let inflate = |remesh| Stroke {
            brush: Brush::Inflate,
            radius: 0.6,
            strength: 0.05,
            path: vec![DVec3::new(0.0, 0.0, 1.0)],
            remesh,
            ..Stroke::default()
        };
        // The icosphere's edges are about 0.3 long: the file's range keeps
        // them, a stroke's range of a tenth splits them.
        let file = Remesh {
            min_edge: 0.15,
            max_edge: 0.45,
        };
        let fine = Remesh {
            min_edge: 0.015,
            max_edge: 0.045,
        };
        let run = |stroke: Stroke, remeshing: bool| {
            let mut s = Session::new(sphere.clone()).unwrap();
            s.set_remesh(Some(file));
            s.set_remeshing(remeshing);
            let r = s.apply_stroke(&stroke).unwrap();
            (r.remesh_operations, s.mesh().triangles.len())
        };
        let (file_ops, file_tris) = run(inflate(None), true);
        let (fine_ops, fine_tris) = run(inflate(Some(StrokeRemesh::Range(fine))), true);
        assert!(
            fine_tris > 2 * file_tris,
            "the stroke's finer range makes {fine_tris} triangles, the file's {file_tris}"
        );
        assert!(fine_ops > file_ops);
        assert_eq!(run(inflate(Some(StrokeRemesh::Off)), true).0, 0);
        assert_eq!(
            run(inflate(Some(StrokeRemesh::Range(fine))), false),
            (0, sphere.triangles.len())
        );
    }

    /// A paint stroke hands its far field to the session, which gives it
    /// to the next stroke; a drag keeps none, and undo, redo and a
    /// commit from elsewhere drop it (the mesh it describes is gone).
    /// A sphere, an inflate and a grab from its top.
    fn sphere_inflate_and_grab() -> (TriMesh, Stroke, Stroke) {
        let sphere = holey_shapes::icosphere(3).unwrap().triangulated();
        // From the top of the sphere to `to`.
        let stroke = |brush, strength, to| Stroke {
            brush,
            radius: 0.6,
            strength,
            path: vec![DVec3::new(0.0, 0.0, 1.0), to],
            ..Stroke::default()
        };
        let inflate = stroke(Brush::Inflate, 0.05, DVec3::new(0.1, 0.0, 1.0));
        let grab = stroke(Brush::Grab, 1.0, DVec3::new(0.0, 0.0, 1.2));
        (sphere, inflate, grab)
    }

    #[test]
    fn the_far_field_passes_from_stroke_to_stroke_while_the_mesh_is_theirs() {
        let (sphere, inflate, grab) = sphere_inflate_and_grab();
        let mut s = Session::new(sphere.clone()).unwrap();
        assert!(s.kept.0.far_field.is_none());
        s.apply_stroke(&inflate).unwrap();
        assert!(
            s.kept.0.far_field.is_some(),
            "a paint stroke hands its field on"
        );
        s.apply_stroke(&inflate).unwrap();
        assert!(
            s.kept.0.far_field.is_some(),
            "and the next one, given it, too"
        );
        assert!(
            s.clone().kept.0.far_field.is_none(),
            "a copy starts without one"
        );
        s.undo();
        assert!(s.kept.0.far_field.is_none(), "undo drops it");
        s.apply_stroke(&inflate).unwrap();
        s.undo();
        assert!(s.redo());
        assert!(s.kept.0.far_field.is_none(), "redo drops it");
        s.apply_stroke(&inflate).unwrap();
        assert!(!s.redo(), "nothing to redo after a stroke");
        assert!(s.kept.0.far_field.is_some(), "and nothing dropped");
        s.commit(sphere.clone(), None);
        assert!(
            s.kept.0.far_field.is_none(),
            "a commit from elsewhere drops it"
        );
        s.apply_stroke(&inflate).unwrap();
        s.apply_stroke(&grab).unwrap();
        assert!(s.kept.0.far_field.is_none(), "a drag keeps none");
    }

    /// What a paint stroke knew of its surface's pieces passes on as its
    /// far field does: a stroke on one sphere ends knowing it is one
    /// piece, and the next, handed that, ends knowing it too; on two
    /// spheres apart a stroke counts two and hands nothing on; a drag
    /// never does; undo drops it.
    #[test]
    fn one_piece_passes_from_stroke_to_stroke_while_the_mesh_is_theirs() {
        let (sphere, inflate, grab) = sphere_inflate_and_grab();
        let mut s = Session::new(sphere.clone()).unwrap();
        assert!(!s.kept.0.one_piece);
        s.apply_stroke(&inflate).unwrap();
        assert!(s.kept.0.one_piece, "one sphere is one piece");
        s.apply_stroke(&inflate).unwrap();
        assert!(s.kept.0.one_piece, "and stays one, handed on");
        assert!(!s.clone().kept.0.one_piece, "a copy starts without it");
        s.undo();
        assert!(!s.kept.0.one_piece, "undo drops it");
        s.apply_stroke(&grab).unwrap();
        assert!(!s.kept.0.one_piece, "a drag hands nothing on");
        let mut two = sphere.clone();
        two.append(&sphere.translated(DVec3::new(5.0, 0.0, 0.0)));
        let mut s = Session::new(two).unwrap();
        s.apply_stroke(&inflate).unwrap();
        assert!(!s.kept.0.one_piece, "two spheres are two pieces");
    }
}
