//! A stroke fed one frame at a time, as a pointer drives it (§4).
//!
//! [`Session`](crate::Session) replays whole strokes through this type, and
//! the interactive modeler feeds it mouse events: [`LiveStroke::begin`]
//! picks, [`LiveStroke::frame`] moves the surface by one path point and
//! [`LiveStroke::finish`] ends the stroke (the release of a drag).
//!
//! - Inflate, smooth and the snake hook change topology between every
//!   pair of frames.
//! - Grab and move accumulate collision parity over the drag
//!   ([`Accumulator`]) and change topology once, at release; during the
//!   drag the corrected parity of the dragged surface is available for the
//!   live preview of what will vanish.

use std::time::Instant;

use glam::DVec3;
use holey_geom::distance::point_segment_distance;
use holey_geom::position_key;
use holey_mesh::PARALLEL_RUN;
use holey_mesh::tri::triangles_with_vertex;
use holey_topo::intersect::IntersectError;
use holey_topo::{
    Accumulator, FarField, Options, Report, TopoError, TriMesh, Window,
    topology_change_guarded_holding, topology_change_guarded_holding_in,
    topology_change_guarded_if_sure, topology_change_guarded_if_sure_in,
};
use rayon::prelude::*;

use crate::brush::region::Region;
use crate::brush::{
    Brush, Falloff, PressureDrives, closest_point, component_of, grab_weights_with, layer,
    paint_at, snake_hook,
};
use crate::ease::{self, EASE_SHARE};
use crate::remesh::{
    RemeshOptions, RemeshReport, default_range, remesh_in_place_checked,
    remesh_valid_in_place_checked,
};
use crate::report::{Diagnostics, SculptError, StrokeReport};
use crate::symmetry::{Mirror, Symmetry};

/// The share of the bounding-box diagonal within which a move's first
/// point must lie from the surface: a move picks a whole component, so it
/// tolerates more slack than a brush radius, but not a click in the void.
pub const MOVE_PICK_FRACTION: f64 = 0.1;

/// The brush settings of a stroke, without its path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrushSettings {
    /// The brush the stroke uses.
    pub brush: Brush,
    /// World-space radius (unused by move).
    pub radius: f64,
    /// See [`crate::Stroke::strength`].
    pub strength: f64,
    /// The falloff curve of the centred brushes and the grab (the snake
    /// hook keeps the smooth curve its step bound is worked out for, and
    /// move its plateau).
    pub falloff: Falloff,
    /// The mirror planes every frame is repeated across.
    pub symmetry: Symmetry,
    /// What a frame's pen pressure scales ([`LiveStroke::frame_pressed`]).
    pub pressure: PressureDrives,
}

impl BrushSettings {
    /// A brush with the smooth falloff, no symmetry, pressure on strength.
    pub fn new(brush: Brush, radius: f64, strength: f64) -> BrushSettings {
        BrushSettings {
            brush,
            radius,
            strength,
            falloff: Falloff::Smooth,
            symmetry: Symmetry::NONE,
            pressure: PressureDrives::Strength,
        }
    }

    /// The radius and strength of a dab with the pen's `pressure` (0 to
    /// 1; not finite counts as 1), scaled as [`BrushSettings::pressure`]
    /// says.
    fn pressed(&self, pressure: f64) -> (f64, f64) {
        let pressure = if pressure.is_finite() {
            pressure.clamp(0.0, 1.0)
        } else {
            1.0
        };
        match self.pressure {
            _ if pressure == 1.0 => (self.radius, self.strength),
            PressureDrives::Strength => (self.radius, self.strength * pressure),
            PressureDrives::Radius => (self.radius * pressure, self.strength),
        }
    }
}

/// What one frame shows.
#[derive(Debug)]
pub struct LiveFrame<'a> {
    /// The frame within its stroke, from 0.
    pub index: usize,
    /// The surface at the end of the frame (during a drag: before the
    /// topology change of the release).
    pub mesh: &'a TriMesh,
    /// Whether the triangles differ from the previous frame's (a paint
    /// frame that changed topology); false means only positions moved.
    pub connectivity_changed: bool,
    /// Whether the topology-change engine cut the surface this frame (a
    /// collision or a crossing resolved), as opposed to remeshing alone.
    pub topology_changed: bool,
    /// During a drag with preview on: the corrected parity per vertex of
    /// `mesh` (`true` = deleted at release).
    pub corrected_odd: Option<Vec<bool>>,
    /// The stroke knows the surface is one piece
    /// ([`holey_topo::is_one_piece`]): counted when a paint stroke began
    /// and carried since by the guard ([`holey_topo::Options::one_piece`]);
    /// false where it does not know (a drag, or a frame whose region could
    /// not show it), not that the surface is in pieces.
    pub one_piece: bool,
    /// Wall-clock time the frame took.
    pub seconds: f64,
}

enum State {
    Paint {
        mesh: TriMesh,
        /// For a snake hook: where the hook is and the pointer was.
        hook: Option<Hook>,
    },
    Drag {
        start: TriMesh,
        /// Per mirror image: each vertex's share of the pointer offset (0
        /// = held still) and the image the offset is reflected by.
        holds: Vec<(Vec<f64>, Mirror)>,
        first: DVec3,
        /// The surface point a grab holds.
        picked: DVec3,
        acc: Box<Accumulator>,
        view: TriMesh,
    },
}

/// The snake hook's grip: the centre it pulls from and the path point the
/// last frame reached. The centre advances by `strength ×` the pointer's
/// motion, so it stays on the part it pulls whatever the strength.
///
/// The hook lets go once a step changes the surface's topology within its
/// radius: what it pulled has met something and fused (a tip pressed into
/// a body is now a handle), or torn. Pulling on would drag the fused seam,
/// and the body around it, along after the pointer. A change elsewhere
/// (the thin tentacle touching itself far behind the tip) does not let
/// go, nor does a cut that leaves the Euler characteristic as it was: the
/// engine trimming the tip where one long step crumpled it through itself
/// (the Stanford bunny's ear hooked with the mouse in the modeler let go
/// that way above the head, short of the crown).
#[derive(Clone, Copy, Debug)]
struct Hook {
    centre: DVec3,
    pointer: DVec3,
    holding: bool,
}

/// Where one paint frame applies its brush.
#[derive(Clone, Copy, Debug)]
enum Dab {
    /// A centred brush (inflate, smooth, draw, ...) at the point.
    At(DVec3),
    /// The snake hook: the hooked patch pulled from the first point to
    /// the second (the strength already applied).
    Pull(DVec3, DVec3),
}

impl Dab {
    /// The positions at the end of the dab.
    fn end(
        self,
        mesh: &TriMesh,
        brush: Brush,
        (radius, strength, falloff): (f64, f64, Falloff),
        heights: &mut layer::Heights,
    ) -> Vec<DVec3> {
        match self {
            Dab::Pull(from, to) => snake_hook::snake_hook(mesh, from, to, radius, 1.0),
            Dab::At(p) if brush == Brush::Layer => {
                let region = Region::gather(mesh, p, radius, falloff);
                layer::layer(mesh, &region, strength, heights)
            }
            Dab::At(p) => paint_at(mesh, brush, p, radius, strength, falloff),
        }
    }

    /// The dab's mirror image.
    fn mirrored(self, m: &Mirror) -> Dab {
        match self {
            Dab::At(p) => Dab::At(m.point(p)),
            Dab::Pull(a, b) => Dab::Pull(m.point(a), m.point(b)),
        }
    }

    /// Whether `p` lies within `radius` of the dab: of its centre, or of
    /// the segment a pull swept.
    fn within(self, p: DVec3, radius: f64) -> bool {
        match self {
            Dab::At(c) => p.distance(c) < radius,
            Dab::Pull(a, b) => point_segment_distance(p, a, b) < radius,
        }
    }

    /// The dab's points grown by `radius` on every side (a box holding
    /// every point [`Dab::within`] admits).
    fn bounds(self, radius: f64) -> (DVec3, DVec3) {
        let (lo, hi) = match self {
            Dab::At(c) => (c, c),
            Dab::Pull(a, b) => (a.min(b), a.max(b)),
        };
        (lo - DVec3::splat(radius), hi + DVec3::splat(radius))
    }

    /// `steps` dabs that together make this one, each with its strength:
    /// a centred dab repeated with its strength shared out
    /// ([`sub_strength`]), a pull cut into equal consecutive pieces.
    fn split(self, brush: Brush, strength: f64, steps: usize) -> Vec<(Dab, f64)> {
        if steps <= 1 {
            return vec![(self, strength)];
        }
        match self {
            // The layer moves towards its plateau and never past it: each
            // piece aims at the whole height.
            Dab::At(_) if brush == Brush::Layer => vec![(self, strength); steps],
            Dab::At(_) => vec![(self, sub_strength(brush, strength, steps)); steps],
            Dab::Pull(a, b) => (0..steps)
                .map(|k| {
                    let at = |i: usize| a + (b - a) * (i as f64 / steps as f64);
                    let end = if k + 1 == steps { b } else { at(k + 1) };
                    (Dab::Pull(at(k), end), strength)
                })
                .collect(),
        }
    }
}

/// Where a frame's remeshing works, and its brush can read: the points
/// within the radius of some dab's centre, or of the segment a pull swept,
/// or of one of their mirror images. The dabs are mirrored once, and a box
/// around them all turns most of a large mesh away before any distance is
/// taken: a frame asks this of every vertex, several times.
struct Reach {
    /// Every dab and mirror image, with its radius.
    dabs: Vec<(Dab, f64)>,
    /// A box holding every point some dab admits, grown by a millionth of
    /// each radius, so that rounding in the distances cannot admit a point
    /// outside it.
    lo: DVec3,
    hi: DVec3,
}

impl Reach {
    fn new(dabs: impl IntoIterator<Item = (Dab, f64)>, mirrors: &[Mirror]) -> Reach {
        let mut all = Vec::new();
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for (dab, radius) in dabs {
            for m in mirrors {
                let d = dab.mirrored(m);
                let (a, b) = d.bounds(radius * (1.0 + 1e-6));
                lo = lo.min(a);
                hi = hi.max(b);
                all.push((d, radius));
            }
        }
        Reach { dabs: all, lo, hi }
    }

    /// The largest radius of the frame's dabs (0 for none).
    fn widest(&self) -> f64 {
        self.dabs.iter().map(|d| d.1).fold(0.0, f64::max)
    }

    /// Whether the frame reaches `p`.
    fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.lo).all()
            && p.cmple(self.hi).all()
            && self.dabs.iter().any(|&(d, r)| d.within(p, r))
    }
}

/// A stroke in progress. Dropping it abandons the stroke; the mesh it
/// began from was only borrowed, so nothing changes.
pub struct LiveStroke {
    settings: BrushSettings,
    /// The images of every frame (the identity first).
    mirrors: Vec<Mirror>,
    /// Positions of the masked vertices, which never move (a masked
    /// vertex keeps its position, so its position names it across the
    /// topology changes and remeshing that renumber vertices).
    mask: std::collections::HashSet<[u64; 3]>,
    /// The layer brush's heights added so far, by position.
    heights: layer::Heights,
    options: Options,
    preview: bool,
    remesh: Option<RemeshOptions>,
    /// Collapses of the short edges a topology change leaves, when
    /// remeshing is off ([`cleanup_options`] of the surface the stroke
    /// began on): `None` until the first frame of a stroke that does not
    /// remesh counts them, so that a stroke that remeshes (every stroke
    /// of the modeller's) skips a pass over every edge.
    cleanup: Option<Option<RemeshOptions>>,
    /// Positions of the vertices the guard held in earlier frames.
    held: std::collections::HashSet<[u64; 3]>,
    /// The mesh is one piece (`holey_topo::is_one_piece`): counted at a
    /// paint stroke's first frame (unless the stroke before handed it on,
    /// [`LiveStroke::take_over`]), then carried from frame to frame
    /// by the guard, which skips its count of the result's pieces while
    /// it can show from a frame's region that one piece stays one
    /// (`holey_topo::Options::one_piece`). Moving and remeshing keep a
    /// piece whole. `None` until counted or handed on; a drag, which
    /// never counts it, starts with `Some(false)` ("not known").
    one_piece: Option<bool>,
    /// The surface's far field, kept between a paint stroke's frames
    /// (`holey_topo::FarField`): built by the engine when frames keep
    /// asking for it, and told of every change a frame and its remeshing
    /// make.
    far: Option<FarField>,
    /// Whether `far` may be handed on when the stroke ends: false once a
    /// frame failed, since a failed frame may have changed the surface
    /// without telling the field.
    far_sound: bool,
    remeshed: RemeshTally,
    state: State,
    frames: usize,
    report: StrokeReport,
    diagnostics: Option<Diagnostics>,
    started: Instant,
    /// For a grab: the picked point and where it was dragged to.
    grab_tube: Option<(DVec3, DVec3)>,
    /// The paint frames' working window ([`Window`]): built when a frame
    /// reaches past the one before it, dropped when a frame changes
    /// topology.
    window: Option<Window>,
    /// The mesh size from which paint frames work in a window.
    window_min: usize,
    /// The engine has checked the paint mesh (indices, finite
    /// positions) at an earlier frame; everything since is the engine's
    /// and the remesher's making, so a frame in a window need only check
    /// what moves.
    engine_checked: bool,
    /// A paint frame's end positions, kept for the next frame's
    /// ([`PaintStep::end_buffer`]).
    end_positions: Vec<DVec3>,
}

impl LiveStroke {
    /// Starts a stroke on `mesh`. A grab, move or snake hook picks here:
    /// `first` must lie within the brush radius (grab, snake hook) or 10%
    /// of the bounding-box diagonal (move) of the surface. Inflate and smooth pick nothing;
    /// their first frame is the first call to [`LiveStroke::frame`].
    pub fn begin(
        mesh: &TriMesh,
        settings: BrushSettings,
        first: DVec3,
        options: Options,
    ) -> Result<LiveStroke, SculptError> {
        let report = StrokeReport {
            brush: Some(settings.brush),
            triangles_before: mesh.triangles.len(),
            ..StrokeReport::default()
        };
        let state = if settings.brush == Brush::SnakeHook {
            check_pick(mesh, settings, first)?;
            State::Paint {
                mesh: mesh.clone(),
                hook: Some(Hook {
                    centre: first,
                    pointer: first,
                    holding: true,
                }),
            }
        } else if settings.brush.is_drag() {
            let (weights, picked) = pick(mesh, settings, first)?;
            let mut holds = vec![(weights, Mirror::IDENTITY)];
            // A mirror image picks on its own; one that finds no surface
            // near it, or holds exactly what another image holds (the
            // same whole piece), adds nothing.
            for m in settings.symmetry.mirrors().into_iter().skip(1) {
                if let Ok((w, _)) = pick(mesh, settings, m.point(first))
                    && holds.iter().all(|(h, _)| *h != w)
                {
                    holds.push((w, m));
                }
            }
            let acc = Accumulator::new(mesh.clone(), options)
                .map_err(|source| SculptError::Topo { frame: 0, source })?;
            State::Drag {
                start: mesh.clone(),
                holds,
                first,
                picked,
                acc: Box::new(acc),
                view: mesh.clone(),
            }
        } else {
            State::Paint {
                mesh: mesh.clone(),
                hook: None,
            }
        };
        Ok(LiveStroke {
            settings,
            mirrors: settings.symmetry.mirrors(),
            mask: std::collections::HashSet::new(),
            heights: layer::Heights::new(),
            options,
            preview: false,
            remesh: None,
            cleanup: None,
            held: std::collections::HashSet::new(),
            one_piece: settings.brush.is_drag().then_some(false),
            far: (!settings.brush.is_drag()).then(FarField::new),
            far_sound: true,
            remeshed: RemeshTally::default(),
            state,
            frames: 0,
            report,
            diagnostics: None,
            started: Instant::now(),
            grab_tube: None,
            window: None,
            window_min: WINDOW_MIN_TRIANGLES,
            engine_checked: false,
            end_positions: Vec::new(),
        })
    }

    /// Takes over what an earlier paint stroke handed on
    /// ([`FinishedStroke::handover`]), so that this one need not build
    /// its far field or count its pieces. It must come from a stroke that
    /// finished on the very surface this stroke began on: a field that
    /// does not describe the surface gives wrong winding numbers. A drag
    /// uses neither and drops it.
    pub fn take_over(&mut self, handover: Handover) {
        if self.far.is_some()
            && let Some(far) = handover.far_field
        {
            self.far = Some(far);
        }
        if handover.one_piece && self.one_piece.is_none() {
            self.one_piece = Some(true);
        }
    }

    /// Masks the vertices at `positions` (exact positions, as
    /// [`holey_geom::position_key`] gives them): no frame moves them, and
    /// remeshing leaves them where they are. Replaces any earlier mask.
    pub fn set_mask(&mut self, positions: std::collections::HashSet<[u64; 3]>) {
        if let State::Drag { start, holds, .. } = &mut self.state {
            for (weights, _) in holds.iter_mut() {
                for (w, p) in weights.iter_mut().zip(&start.positions) {
                    if positions.contains(&position_key(*p)) {
                        *w = 0.0;
                    }
                }
            }
        }
        self.mask = positions;
    }

    /// Whether drag frames compute the corrected parity (a static
    /// intersection pass and a correction per frame).
    pub fn set_preview(&mut self, on: bool) {
        self.preview = on;
    }

    /// Dynamic remeshing (§4) after every inflate or smooth frame and
    /// after the release of a grab, around what the brush touched; `None`
    /// turns it off.
    pub fn set_remesh(&mut self, remesh: Option<RemeshOptions>) {
        self.remesh = remesh;
    }

    /// Paint frames on a mesh of at least `triangles` triangles find what
    /// their dabs touch in a working window kept from frame to frame,
    /// instead of passes over the whole mesh (by default from
    /// 32,768 triangles). The frames' results are the same either way,
    /// bit for bit; only their cost differs. `usize::MAX` turns the window
    /// off.
    pub fn set_window_min(&mut self, triangles: usize) {
        self.window_min = triangles;
    }

    /// Remeshing operations so far.
    pub fn remeshed(&self) -> RemeshTally {
        self.remeshed
    }

    /// The brush settings the stroke was begun with.
    pub fn settings(&self) -> BrushSettings {
        self.settings
    }

    /// The current surface (during a drag: the dragged one).
    pub fn mesh(&self) -> &TriMesh {
        match &self.state {
            State::Paint { mesh, .. } => mesh,
            State::Drag { view, .. } => view,
        }
    }

    /// Frames so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// One frame with the brush at `point` (a centred brush: its centre;
    /// grab, move, snake hook: the drag target). On error the stroke is
    /// left as it was before the call.
    pub fn frame(&mut self, point: DVec3) -> Result<LiveFrame<'_>, SculptError> {
        self.frame_pressed(point, 1.0)
    }

    /// [`LiveStroke::frame`] with the pen's `pressure` (0 to 1; not finite
    /// counts as 1), which scales the frame's strength or radius as the
    /// settings say ([`PressureDrives`]). Drags ignore it.
    pub fn frame_pressed(
        &mut self,
        point: DVec3,
        pressure: f64,
    ) -> Result<LiveFrame<'_>, SculptError> {
        self.frame_together(&[(point, pressure)])
    }

    /// One frame of several dabs, each `(point, pressure)` as for
    /// [`LiveStroke::frame_pressed`], in order: what a modeler sends when
    /// the pointer moved on while the last frame was computed.
    ///
    /// A centred brush (every paint brush but the layer and the snake
    /// hook) evaluates each dab on the surface the dab before it left,
    /// positions only, and moves the surface from where the frame began to
    /// where the last dab left it in one guarded topology change (§3: a
    /// frame's motion is the straight path between its two states), then
    /// remeshes once around every dab. The brush is applied at every dab,
    /// so the stroke keeps its spacing, and a dab longer than one frame's
    /// step goes in the sub-steps its own frame would take ([`substeps`]);
    /// only the collision handling and remeshing are shared. A frame of one
    /// dab goes the same way: its sub-steps too are evaluated on the piece
    /// of the surface they read and resolved as one motion (at 1.31M
    /// triangles the modeler's default brush took 190-210 ms a frame when
    /// each sub-step was a frame of its own on the whole mesh, 110 ms so).
    /// A joint motion the engine finds too crumpled for one frame
    /// ([`IntersectError::TooManyPairs`]) sends the dabs one by one, each
    /// split in halves while the engine still refuses it.
    ///
    /// The layer brush and the snake hook, whose dabs depend on what the
    /// dab before them did (its heights, its grip), and drags, which follow
    /// the pointer, take their dabs one after another within the frame.
    /// An empty `dabs` is a frame that changes nothing. On an error, dabs
    /// painted one by one before the failing one stay painted.
    pub fn frame_together(&mut self, dabs: &[(DVec3, f64)]) -> Result<LiveFrame<'_>, SculptError> {
        let started = Instant::now();
        // Unsound until the frame returns well (`far_sound`).
        let far_sound = std::mem::replace(&mut self.far_sound, false);
        let index = self.frames;
        let settings = self.settings;
        let mut connectivity_changed = false;
        let mut topology_changed = false;
        let mut corrected_odd = None;
        match &mut self.state {
            State::Paint { mesh, hook } => {
                // On a large surface the field is built beside the
                // frames, before any of them asks.
                if let Some(far) = &self.far {
                    far.prepare(mesh);
                }
                // What the stroke knows of the surface it began on,
                // counted before the first frame changes it.
                let one_piece = self
                    .one_piece
                    .get_or_insert_with(|| holey_topo::is_one_piece(mesh));
                if self.remesh.is_none() {
                    self.cleanup.get_or_insert_with(|| cleanup_options(mesh));
                }
                let mut step = PaintStep {
                    falloff: settings.falloff,
                    heights: &mut self.heights,
                    mirrors: &self.mirrors,
                    mask: &self.mask,
                    options: &self.options,
                    held: &mut self.held,
                    one_piece,
                    far: self.far.as_ref(),
                    remesh: self.remesh.as_ref(),
                    cleanup: self.cleanup.as_ref().and_then(Option::as_ref),
                    report: &mut self.report,
                    remeshed: &mut self.remeshed,
                    diagnostics: &mut self.diagnostics,
                    window: &mut self.window,
                    window_min: self.window_min,
                    engine_checked: &mut self.engine_checked,
                    end_positions: &mut self.end_positions,
                    connectivity_changed: false,
                    topology_changed: false,
                    hook_met: false,
                };
                let brush = settings.brush;
                if hook.is_none() && brush != Brush::Layer && !dabs.is_empty() {
                    let pressed: Vec<(DVec3, f64, f64)> = dabs
                        .iter()
                        .map(|&(point, pressure)| {
                            let (r, s) = settings.pressed(pressure);
                            (point, r, s)
                        })
                        .collect();
                    step.paint_together(mesh, brush, &pressed)
                        .map_err(|e| e.at_frame(index))?;
                } else {
                    for &(point, pressure) in dabs {
                        let (paint_radius, paint_strength) = settings.pressed(pressure);
                        let dab = match hook {
                            Some(h) if h.holding => Some(Dab::Pull(
                                h.centre,
                                h.centre + settings.strength * (point - h.pointer),
                            )),
                            Some(_) => None,
                            None => Some(Dab::At(point)),
                        };
                        let Some(dab) = dab else { continue };
                        // The snake hook's grip is sized by the radius alone.
                        let r = if hook.is_some() {
                            settings.radius
                        } else {
                            paint_radius
                        };
                        step.paint(mesh, brush, dab, r, paint_strength)
                            .map_err(|e| e.at_frame(index))?;
                        if let (Some(h), Dab::Pull(_, to)) = (hook.as_mut(), dab) {
                            *h = Hook {
                                centre: to,
                                pointer: point,
                                holding: !step.hook_met,
                            };
                        }
                    }
                }
                connectivity_changed = step.connectivity_changed;
                topology_changed = step.topology_changed;
            }
            State::Drag {
                start,
                holds,
                first,
                picked,
                acc,
                view,
            } => {
                for &(point, _) in dabs {
                    let offset = point - *first;
                    if settings.brush == Brush::Grab {
                        self.grab_tube = Some((*picked, *picked + offset * settings.strength));
                    }
                    // Weight 0 keeps a vertex bit-exact, and a zero offset
                    // (back at the start) restores every position exactly.
                    let mut next = start.positions.clone();
                    for (v, p) in next.iter_mut().enumerate() {
                        let mut moved = DVec3::ZERO;
                        let mut any = false;
                        for (weights, m) in holds.iter() {
                            let w = weights[v];
                            if w != 0.0 {
                                moved += w * m.vector(offset);
                                any = true;
                            }
                        }
                        if any {
                            *p += moved;
                        }
                    }
                    if next != view.positions {
                        acc.advance(&next).map_err(|source| SculptError::Topo {
                            frame: index,
                            source,
                        })?;
                        view.positions = next;
                    }
                }
                if self.preview {
                    corrected_odd = Some(acc.preview().map(|r| r.vanishing.clone()).map_err(
                        |source| SculptError::Topo {
                            frame: index,
                            source,
                        },
                    )?);
                }
            }
        }
        self.frames += 1;
        self.far_sound = far_sound;
        Ok(LiveFrame {
            index,
            mesh: self.mesh(),
            connectivity_changed,
            topology_changed,
            corrected_odd,
            one_piece: self.one_piece.unwrap_or(false),
            seconds: started.elapsed().as_secs_f64(),
        })
    }

    /// Ends the stroke: the final surface, the diagnostics of its last
    /// topology change (if any) and its report. A drag changes topology
    /// here, once; a drag that came back to its start (or never moved)
    /// gives back the starting surface unchanged.
    pub fn finish(mut self) -> Result<FinishedStroke, SculptError> {
        let mut report = self.report;
        report.frames = self.frames;
        let last = self.frames.saturating_sub(1);
        // A paint stroke's surface ends as its last frame left it, every
        // change told to its field: the next stroke on it may keep the
        // field. A drag's release is not told to any.
        let handover = match self.state {
            State::Paint { .. } if self.far_sound => Handover {
                far_field: self.far,
                one_piece: self.one_piece.unwrap_or(false),
            },
            _ => Handover::default(),
        };
        let (mesh, diagnostics) = match self.state {
            State::Paint { mesh, .. } => (mesh, self.diagnostics),
            State::Drag { start, acc, .. } => {
                if acc.frames() == 0 {
                    (start, None)
                } else {
                    let release = acc.release_guarded().map_err(|source| SculptError::Topo {
                        frame: last,
                        source,
                    })?;
                    if !release.refused.is_empty() {
                        // The drag would have left the surface worse: it
                        // is undone (the guard held every vertex).
                        report.held_frames += 1;
                        report.refused = release.refused.clone();
                    }
                    let (mesh, out) = (release.mesh, release.report);
                    tally(&mut report, &out.report);
                    let d = Diagnostics {
                        raw_odd: out.raw_odd,
                        corrected_odd: out.corrected_odd,
                        intersection_curves: out.intersection_curves,
                    };
                    (mesh, Some(d))
                }
            }
        };
        let mut mesh = mesh;
        if let (Some(opts), Some(tube)) = (&self.remesh, self.grab_tube) {
            // The stretched region of a grab: within the radius of the
            // segment from the picked point to where it was dragged.
            let radius = self.settings.radius;
            let active = remesh_active(
                &mesh,
                |p| point_segment_distance(p, tube.0, tube.1) < radius,
                None,
            );
            if active.contains(&true) {
                let r = remesh_in_place_checked(&mut mesh, &active, opts).map_err(|source| {
                    SculptError::Remesh {
                        frame: last,
                        source,
                    }
                })?;
                self.remeshed.add(&r);
            }
        }
        report.remesh_operations = self.remeshed.operations();
        report.triangles_after = mesh.triangles.len();
        report.seconds = self.started.elapsed().as_secs_f64();
        Ok(FinishedStroke {
            mesh,
            diagnostics,
            report,
            handover,
        })
    }
}

/// How many times a paint frame may be halved when the engine finds it
/// crumples the surface too much for one frame: 2⁶ = 64 sub-frames.
pub const MAX_SUBFRAME_DEPTH: u32 = 6;

/// The size of mesh from which a live stroke works in a window
/// ([`LiveStroke::set_window_min`]): below it a pass over the whole mesh
/// costs about what building the window does.
const WINDOW_MIN_TRIANGLES: usize = 2 * PARALLEL_RUN;

/// How far past a frame's reach a new working window reaches, in widest
/// dab radii: room for the frames after it, as the stroke moves on. A
/// wider one is built less often but read at every frame (on the 1.1M
/// bunny, moving frames took about 10 ms longer at 1.5 radii than at 0.5).
const WINDOW_GROWTH: f64 = 0.5;

/// How much room past a frame's reach the window it has must leave, in
/// widest dab radii, to be kept: enough for the rings around the reached
/// vertices to lie inside it as a rule (where they do not, a pass goes
/// over the whole mesh, and the result is the same).
const WINDOW_SLACK: f64 = 0.25;

/// What a paint frame writes into its stroke.
struct PaintStep<'a> {
    falloff: Falloff,
    /// The layer brush's heights so far in the stroke.
    heights: &'a mut layer::Heights,
    /// The images of every dab (the identity first).
    mirrors: &'a [Mirror],
    /// Positions that never move.
    mask: &'a std::collections::HashSet<[u64; 3]>,
    options: &'a Options,
    /// Positions of the vertices the stroke's frames had to hold.
    held: &'a mut std::collections::HashSet<[u64; 3]>,
    /// The mesh is one piece ([`LiveStroke`]'s `one_piece`).
    one_piece: &'a mut bool,
    /// The stroke's kept far field ([`LiveStroke`]'s `far`).
    far: Option<&'a FarField>,
    remesh: Option<&'a RemeshOptions>,
    cleanup: Option<&'a RemeshOptions>,
    report: &'a mut StrokeReport,
    remeshed: &'a mut RemeshTally,
    diagnostics: &'a mut Option<Diagnostics>,
    /// The stroke's working window ([`LiveStroke`]'s `window`).
    window: &'a mut Option<Window>,
    /// From how many triangles frames use it.
    window_min: usize,
    /// [`LiveStroke`]'s `engine_checked`.
    engine_checked: &'a mut bool,
    /// [`LiveStroke`]'s `end_positions`.
    end_positions: &'a mut Vec<DVec3>,
    connectivity_changed: bool,
    topology_changed: bool,
    /// A snake hook's step changed the topology (the Euler
    /// characteristic) within the hook's reach.
    hook_met: bool,
}

/// An error of a paint frame, before it knows its frame number.
enum StepError {
    Topo(holey_topo::TopoError),
    Remesh(crate::remesh::RemeshError),
}

impl StepError {
    fn at_frame(self, frame: usize) -> SculptError {
        match self {
            StepError::Topo(source) => SculptError::Topo { frame, source },
            StepError::Remesh(source) => SculptError::Remesh { frame, source },
        }
    }
}

impl PaintStep<'_> {
    /// The positions at the end of `dab` and its mirror images, all
    /// evaluated on the same surface and their displacements added
    /// ([`crate::symmetry`]); masked vertices stay.
    fn end(
        &mut self,
        mesh: &TriMesh,
        brush: Brush,
        dab: Dab,
        radius: f64,
        strength: f64,
    ) -> Vec<DVec3> {
        let how = (radius, strength, self.falloff);
        let mut end = dab.end(mesh, brush, how, self.heights);
        for m in self.mirrors.iter().skip(1) {
            let image = dab.mirrored(m).end(mesh, brush, how, self.heights);
            for ((e, q), p) in end.iter_mut().zip(&image).zip(&mesh.positions) {
                if q != p {
                    *e += *q - *p;
                }
            }
        }
        if !self.mask.is_empty() {
            for (e, p) in end.iter_mut().zip(&mesh.positions) {
                if self.mask.contains(&position_key(*p)) {
                    *e = *p;
                }
            }
        }
        end
    }

    /// Collapses the edges shorter than the cleanup length at the last
    /// `new` vertices of `mesh` (the points a topology change made), onto
    /// the vertices around them, which stay put. The cut inserts its
    /// points wherever curves cross edges, often a hair's breadth from a
    /// vertex; left alone, those slivers' normals send the next frames'
    /// brush every which way and the surface crumples into storms of
    /// ever smaller triangles. With remeshing on, remeshing does this.
    fn clean_up(&mut self, mesh: &mut TriMesh, new: usize) -> Result<(), StepError> {
        let Some(opts) = self.cleanup else {
            return Ok(());
        };
        let n = mesh.positions.len();
        let mut active = vec![false; n];
        for a in &mut active[n.saturating_sub(new)..] {
            *a = true;
        }
        let r = remesh_in_place_checked(mesh, &active, opts).map_err(StepError::Remesh)?;
        self.changed_within(r.changed);
        self.remeshed.add(&r);
        Ok(())
    }

    /// The stroke's working window for a frame of `reach`, on a mesh large
    /// enough for one: the window it has when that holds the reach's box
    /// with [`WINDOW_SLACK`] of the widest radius to spare, otherwise a
    /// new one over the box grown by [`WINDOW_GROWTH`] of it (one pass
    /// over the mesh), so that the next frames of a stroke moving on find
    /// it still holds theirs.
    fn window_over(&mut self, mesh: &TriMesh, reach: &Reach) -> Option<&Window> {
        if mesh.triangles.len() < self.window_min || !(reach.lo.is_finite() && reach.hi.is_finite())
        {
            *self.window = None;
            return None;
        }
        let slack = DVec3::splat(WINDOW_SLACK * reach.widest());
        let keeps = self
            .window
            .as_ref()
            .is_some_and(|w| w.fits(mesh) && w.holds_box(reach.lo - slack, reach.hi + slack));
        if !keeps {
            let grow = DVec3::splat(WINDOW_GROWTH * reach.widest());
            *self.window = Some(Window::build(mesh, reach.lo - grow, reach.hi + grow));
        }
        self.window.as_ref()
    }

    /// The stroke's buffer of end positions (taken: the caller gives it
    /// back), holding `mesh`'s positions: a copy into memory the stroke
    /// already has, not a fresh allocation of a million positions each
    /// frame, whose first touch of every page costs more than the copy.
    fn end_buffer(&mut self, mesh: &TriMesh) -> Vec<DVec3> {
        let mut end = std::mem::take(self.end_positions);
        end.clear();
        end.extend_from_slice(&mesh.positions);
        end
    }

    /// Tells the stroke's kept far field that the surface changed within
    /// `b` (a frame's or its remeshing's box), if it did.
    fn changed_within(&self, b: Option<(DVec3, DVec3)>) {
        if let (Some(far), Some(b)) = (self.far, b) {
            far.changed_within(b);
        }
    }

    /// One frame of a paint brush: a pull longer than the snake hook's
    /// step bound ([`snake_hook::steps`]) is cut into pieces first, each
    /// then painted by [`PaintStep::paint_piece`] on the surface the one
    /// before it left, until one changes topology within the hook's reach
    /// (the hook lets go: [`Hook`]).
    fn paint(
        &mut self,
        mesh: &mut TriMesh,
        brush: Brush,
        dab: Dab,
        radius: f64,
        strength: f64,
    ) -> Result<(), StepError> {
        let pieces = match dab {
            Dab::Pull(from, to) => snake_hook::steps(from, to, radius, 1.0),
            Dab::At(_) => 1,
        };
        if pieces > 1 {
            self.report.subframes += pieces - 1;
        }
        for (piece, s) in dab.split(brush, strength, pieces) {
            self.paint_piece(mesh, brush, piece, radius, s, 0)?;
            if self.hook_met {
                break;
            }
        }
        Ok(())
    }

    /// Centred dabs `(centre, radius, strength)` painted as one frame
    /// ([`LiveStroke::frame_together`]): each dab's brush on the positions
    /// the one before it left, then one guarded topology change from the
    /// frame's start to the last dab's end, and one remeshing around every
    /// dab. A dab whose step is longer than a frame's may be ([`substeps`])
    /// is evaluated in as many steps as a frame of its own would take, each
    /// on the positions the one before left.
    ///
    /// Dabs that together move the surface farther than one frame may are
    /// one frame only where they collide with nothing. Where they do, the
    /// collision parity of so long a straight motion over folding surface
    /// is the error-prone case (a frame of seven deflate dabs over the
    /// Stanford bunny's haunch, which an inflate had fused, cut off closed
    /// flakes outside the surface), so the dabs go in runs that each move
    /// it at most one frame's step, every run resolved on its own
    /// ([`PaintStep::paint_run`]); a single dab longer than that, or a run
    /// the engine finds too crumpled, goes as [`PaintStep::paint_piece`]
    /// paints it, step by step.
    fn paint_together(
        &mut self,
        mesh: &mut TriMesh,
        brush: Brush,
        dabs: &[(DVec3, f64, f64)],
    ) -> Result<(), StepError> {
        if self.paint_run(mesh, brush, dabs, Run::Whole)?.is_some() {
            return Ok(());
        }
        let mut rest = dabs;
        while let Some(&(centre, radius, strength)) = rest.first() {
            let taken = match self.paint_run(mesh, brush, rest, Run::Stepped)? {
                Some(taken) => taken,
                None => {
                    self.paint_piece(mesh, brush, Dab::At(centre), radius, strength, 0)?;
                    1
                }
            };
            rest = &rest[taken..];
        }
        Ok(())
    }

    /// The first dabs of `dabs` as one frame, on the piece of the surface
    /// they read ([`Piece`]): all of them ([`Run::Whole`]), or as many as
    /// move it at most one frame's step together, at least one
    /// ([`Run::Stepped`]). How many it painted, or `None` when it left the
    /// surface as it was: the engine found the motion too crumpled, or the
    /// motion was longer than a frame's step and collided.
    fn paint_run(
        &mut self,
        mesh: &mut TriMesh,
        brush: Brush,
        dabs: &[(DVec3, f64, f64)],
        run: Run,
    ) -> Result<Option<usize>, StepError> {
        let reach = Reach::new(dabs.iter().map(|&(c, r, _)| (Dab::At(c), r)), self.mirrors);
        // Each step of the brush sees the normals the step before it left,
        // so the surface folds nothing over between two evaluations of
        // them, as between frames; the motion is resolved once. The steps
        // run on the piece of the surface they can read, not on the whole
        // mesh.
        let window = self.window_over(mesh, &reach);
        let mut piece = Piece::around(mesh, &|p| reach.contains(p), window);
        let start = piece.mesh.positions.clone();
        let long =
            |piece: &Piece| substeps_of(&start, &piece.mesh.triangles, &piece.mesh.positions) > 1;
        let mut subframes = 0;
        let mut taken = 0;
        for &(centre, radius, strength) in dabs {
            let before = (run == Run::Stepped && taken > 0).then(|| piece.mesh.positions.clone());
            let dab = Dab::At(centre);
            let end = self.end(&piece.mesh, brush, dab, radius, strength);
            let steps = substeps(&piece.mesh, &end);
            let mut split = 0;
            if steps == 1 {
                piece.mesh.positions = end;
            } else {
                split = steps - 1;
                for (part, s) in dab.split(brush, strength, steps) {
                    piece.mesh.positions = self.end(&piece.mesh, brush, part, radius, s);
                }
            }
            if let Some(before) = before
                && long(&piece)
            {
                // This dab would take the run past one frame's step: the
                // run ends before it.
                piece.mesh.positions = before;
                break;
            }
            subframes += split;
            taken += 1;
        }
        let mut end = self.end_buffer(mesh);
        for (&g, &p) in piece.global.iter().zip(&piece.mesh.positions) {
            end[g as usize] = p;
        }
        let run_dabs = &dabs[..taken];
        // The remeshing goes around the dabs the run took.
        let reach = if taken == dabs.len() {
            reach
        } else {
            Reach::new(
                run_dabs.iter().map(|&(c, r, _)| (Dab::At(c), r)),
                self.mirrors,
            )
        };
        // The dabs share a brush, and pressure scales a strength without
        // turning its sign.
        let outward = brush == Brush::Inflate && run_dabs.iter().all(|d| d.2 > 0.0);
        let sure_only = long(&piece);
        let settled = self.settle(mesh, &end, outward, None, &reach, sure_only);
        *self.end_positions = end;
        match settled? {
            Settled::Done => {
                self.report.subframes += subframes;
                Ok(Some(taken))
            }
            Settled::TooCrumpled => Ok(None),
        }
    }

    /// One frame of inflate, smooth or a snake hook's step: the brush, the
    /// guarded topology change, then remeshing. A motion the engine refuses as
    /// too crumpled for one frame ([`IntersectError::TooManyPairs`]) is
    /// split into two frames of half the motion, each with the brush
    /// evaluated again on the surface it then finds, up to
    /// [`MAX_SUBFRAME_DEPTH`] halvings; past that the frame is held (the
    /// surface does not move), so a stroke never stops on a refusal.
    fn paint_piece(
        &mut self,
        mesh: &mut TriMesh,
        brush: Brush,
        dab: Dab,
        radius: f64,
        strength: f64,
        depth: u32,
    ) -> Result<(), StepError> {
        let reach = Reach::new([(dab, radius)], self.mirrors);
        // A centred dab of a brush that `paint_run` paints on pieces is
        // evaluated, and its step measured, on the piece of the surface
        // it reads, as `paint_run` evaluates its dabs: the same numbers,
        // where the brush's passes over the whole mesh cost 60 ms a dab
        // on a million triangles, and a crumpled frame there goes dab by
        // dab. (The layer brush and the snake hook's pulls are painted
        // on the whole mesh, as they always were.)
        let on_piece = matches!(dab, Dab::At(_)) && brush != Brush::Layer;
        let (end, steps) = if on_piece {
            let window = self.window_over(mesh, &reach);
            let piece = Piece::around(mesh, &|p| reach.contains(p), window);
            let moved = self.end(&piece.mesh, brush, dab, radius, strength);
            // Every triangle at a vertex the dab moves is in the piece,
            // in mesh order: the step is the whole mesh's.
            let steps = substeps_of(&piece.mesh.positions, &piece.mesh.triangles, &moved);
            let mut end = self.end_buffer(mesh);
            for (&g, &p) in piece.global.iter().zip(&moved) {
                end[g as usize] = p;
            }
            (end, steps)
        } else {
            // Not painted on a piece: the window's promise (only what the
            // reach admits moves) is not checked here.
            *self.window = None;
            let end = self.end(mesh, brush, dab, radius, strength);
            let steps = substeps(mesh, &end);
            (end, steps)
        };
        // A frame that moves a vertex farther than the edges around the
        // moving vertices are long is cut into as many sub-frames as it
        // takes (at most 2^MAX_SUBFRAME_DEPTH), each evaluating the brush
        // again on the surface it finds: the step control of deforming
        // meshes, which keeps a frame from folding the surface over itself
        // between two evaluations of its normals.
        if depth == 0 && steps > 1 {
            self.report.subframes += steps - 1;
            for (part, s) in dab.split(brush, strength, steps) {
                self.paint_piece(mesh, brush, part, radius, s, 1)?;
            }
            return Ok(());
        }
        // An inflate only pushes the surface outward: it may join parts,
        // never cut one loose (`Options::outward`).
        let outward = brush == Brush::Inflate && strength > 0.0;
        // A snake hook has met something when the cut changed the
        // topology and made points within its reach.
        let hook = match dab {
            Dab::Pull(_, to) => Some((to, radius)),
            Dab::At(_) => None,
        };
        let settled = self.settle(mesh, &end, outward, hook, &reach, false);
        *self.end_positions = end;
        match settled? {
            Settled::Done => Ok(()),
            Settled::TooCrumpled => {
                if depth >= MAX_SUBFRAME_DEPTH {
                    self.report.held_frames += 1;
                    return Ok(());
                }
                self.report.subframes += 1;
                for (half, s) in dab.split(brush, strength, 2) {
                    self.paint_piece(mesh, brush, half, radius, s, depth + 1)?;
                }
                Ok(())
            }
        }
    }

    /// The motion of `mesh` to `end` (a brush's frame): the guarded
    /// topology change, then remeshing around the vertices `reach`
    /// admits. `outward`: the brush only pushes the surface outward, so the
    /// frame may cut no piece loose. `hook`: a snake hook's target and
    /// radius, which has met something when the cut changes the Euler
    /// characteristic and makes points within that radius of it.
    /// `sure_only`: the motion is taken as one frame only where that is
    /// sure (`holey_topo::topology_change_guarded_if_sure`; otherwise
    /// [`Settled::TooCrumpled`]). Around the vertices held in earlier
    /// frames the motion ramps up over
    /// [`EASE_SHARE`] of the widest dab's radius (`crate::ease`).
    /// [`Settled::TooCrumpled`] leaves `mesh` as it was, for the caller to
    /// split the motion.
    fn settle(
        &mut self,
        mesh: &mut TriMesh,
        end: &[DVec3],
        outward: bool,
        hook: Option<(DVec3, f64)>,
        reach: &Reach,
        sure_only: bool,
    ) -> Result<Settled, StepError> {
        // A frame that moves nothing cannot collide; skipping it also
        // keeps a brush that wanders off the surface from re-cutting
        // intersections the mesh already had.
        // The window (kept only if it holds every vertex the reach admits,
        // so every vertex that can move) survives a frame that only moves
        // vertices, and one whose splice told it what it wrote; a frame
        // whose result was built whole drops it.
        let window = self
            .window
            .take()
            .filter(|w| w.holds_box(reach.lo, reach.hi));
        // Whether the guard checked the mesh and rebuilt it this frame
        // (only the window's vertices can have moved).
        let guarded = match &window {
            Some(w) => w
                .vertices()
                .iter()
                .any(|&v| end[v as usize] != mesh.positions[v as usize]),
            None => end != mesh.positions,
        };
        if !guarded {
            *self.window = window;
        } else {
            // Only the region the brush reaches is recomputed, and never
            // left worse than it was (the guard).
            // Vertices an earlier frame of the stroke had to hold stay
            // held: the contact that made them is still there.
            let already: Vec<bool> = if self.held.is_empty() {
                Vec::new()
            } else {
                mesh.positions
                    .iter()
                    .zip(end)
                    .map(|(p, q)| p != q && self.held.contains(&position_key(*p)))
                    .collect()
            };
            // Nor may a frame that holds vertices cut a piece loose: held
            // still while the brush moves their neighbours, they stand out
            // of the surface as a crease, and a piece the frame pinches off
            // there is the hold's making, not the brush's (a deflate over
            // the bunny's haunch cut off a closed bubble of 12 triangles
            // that way).
            let holds = already.contains(&true);
            // The rest of the brush eases off them (`crate::ease`).
            let eased;
            let end = if holds {
                let width = EASE_SHARE * reach.widest();
                eased = ease::eased_near_held(&mesh.positions, end, &already, width);
                &eased[..]
            } else {
                end
            };
            let options = Options {
                outward: outward || holds,
                // An inflate's specks are a fold's tip poked through a
                // sheet: debris, taken out (`holey_topo::guard`).
                take_out_debris: outward,
                one_piece: *self.one_piece,
                ..*self.options
            };
            let far = self.far;
            // The engine reads the window once it has checked the mesh
            // whole, and tells it what a topology change wrote.
            let in_window = *self.engine_checked && window.is_some();
            let mut window = window;
            let run = match window.as_mut().filter(|_| in_window) {
                Some(w) if sure_only => {
                    topology_change_guarded_if_sure_in(mesh, end, &options, &already, far, w)
                }
                Some(w) => {
                    topology_change_guarded_holding_in(mesh, end, &options, &already, far, w)
                        .map(Some)
                }
                None if sure_only => {
                    topology_change_guarded_if_sure(mesh, end, &options, &already, far)
                }
                None => {
                    topology_change_guarded_holding(mesh, end, &options, &already, far).map(Some)
                }
            };
            if run.is_ok() {
                *self.engine_checked = true;
            }
            match run {
                Ok(None) => {
                    *self.window = window;
                    return Ok(Settled::TooCrumpled);
                }
                Ok(Some(guarded)) => {
                    if guarded.local.positions_only || (in_window && guarded.window_kept) {
                        *self.window = window;
                    }
                    *self.one_piece = guarded.local.one_piece;
                    self.changed_within(guarded.local.changed);
                    self.held
                        .extend(guarded.held_positions.iter().map(|&p| position_key(p)));
                    for why in &guarded.refused {
                        if !self.report.held_because.contains(why) {
                            self.report.held_because.push(why.clone());
                        }
                    }
                    if guarded.attempts > 1 || guarded.held_vertices > 0 {
                        self.report.guarded_frames += 1;
                        self.report.held_vertices += guarded.held_vertices;
                        self.report.held_frames += usize::from(guarded.held_all);
                    }
                    let euler_change = guarded.euler_change;
                    let out = guarded.local;
                    self.report.whole_mesh_frames += usize::from(out.whole_mesh);
                    tally(self.report, &out.report);
                    *self.diagnostics = Some(Diagnostics {
                        raw_odd: out.raw_odd,
                        corrected_odd: out.corrected_odd,
                        intersection_curves: out.intersection_curves,
                    });
                    self.connectivity_changed |= !out.positions_only;
                    self.topology_changed |= !out.positions_only;
                    // The engine appends the points it makes.
                    if let Some((to, radius)) = hook
                        && !out.positions_only
                        && euler_change != 0
                    {
                        let n = mesh.positions.len();
                        self.hook_met |= mesh.positions[n.saturating_sub(out.new_vertices)..]
                            .iter()
                            .any(|p| p.distance(to) < radius);
                    }
                    if self.remesh.is_none() && out.new_vertices > 0 {
                        *self.window = None;
                        self.clean_up(mesh, out.new_vertices)?;
                    }
                }
                Err(TopoError::Intersections(IntersectError::TooManyPairs { .. })) => {
                    *self.window = window;
                    return Ok(Settled::TooCrumpled);
                }
                Err(e) => return Err(StepError::Topo(e)),
            }
        }
        if let Some(opts) = self.remesh {
            // After the topology change (§4): the vertices the brush
            // reaches, at their new positions.
            // The window holds every vertex the reach admits, or is not
            // used.
            if self
                .window
                .as_ref()
                .is_some_and(|w| !w.holds_box(reach.lo, reach.hi))
            {
                *self.window = None;
            }
            let active = remesh_active(
                mesh,
                |p| reach.contains(p) && !self.mask.contains(&position_key(p)),
                self.window.as_ref(),
            );
            if active.contains(&true) {
                // Once the guard has checked the mesh, remeshing need not.
                let r = if guarded {
                    remesh_valid_in_place_checked(mesh, &active, opts, self.window.as_mut())
                } else {
                    *self.window = None;
                    remesh_in_place_checked(mesh, &active, opts)
                }
                .map_err(StepError::Remesh)?;
                self.changed_within(r.changed);
                if self.remeshed.add(&r) {
                    self.connectivity_changed = true;
                }
            }
        }
        Ok(Settled::Done)
    }
}

/// The part of a surface that the centred brushes of a frame of dabs read
/// ([`PaintStep::paint_together`]): the triangles within two rings of the
/// vertices some dab reaches, in mesh order, with their vertices numbered
/// in mesh order, so that a brush computes on it bit for bit what it
/// computes on the whole mesh.
///
/// Why two rings suffice: a vertex moves only while a dab reaches it, and
/// until it first moves it is where the frame began, so every vertex any
/// dab of the frame moves is among those the dabs reach at the start. A
/// brush reads the triangles around the vertices it moves (their normals,
/// their rings of neighbours, the rim's sides), and a rim vertex also the
/// triangles around its neighbours ([`crate::brush`]'s two-ring normal),
/// which are those around the vertices of the first ring, and of the
/// vertices at their positions (unwelded copies, which the brushes take
/// for one point).
struct Piece {
    mesh: TriMesh,
    /// The mesh's vertex number of each of the piece's.
    global: Vec<u32>,
}

impl Piece {
    /// The piece of `mesh` around the vertices `reaches` admits. With a
    /// `window` whose box holds every such vertex ([`Window`]), the passes
    /// read the window's lists instead of the whole mesh: the first ring's
    /// triangles all meet its box, and so do the second ring's when the
    /// first ring's vertices lie in it (otherwise the second ring is found
    /// in the whole mesh). The piece is the same either way.
    fn around(
        mesh: &TriMesh,
        reaches: &(dyn Fn(DVec3) -> bool + Sync),
        window: Option<&Window>,
    ) -> Piece {
        // Each pass over the whole mesh runs in parallel runs and gathers
        // what the piece needs, which is small beside it.
        let n = mesh.positions.len();
        let mut near = vec![false; n];
        match window {
            Some(w) => {
                for v in w.vertices_where(|v| reaches(mesh.positions[v as usize])) {
                    near[v as usize] = true;
                }
            }
            None => near
                .par_iter_mut()
                .with_min_len(PARALLEL_RUN)
                .zip(&mesh.positions)
                .for_each(|(near, &p)| *near = reaches(p)),
        }
        let touching = |ring: &[bool], window: Option<&Window>| match window {
            Some(w) => w.triangles_with_vertex(&mesh.triangles, |v| ring[v as usize]),
            None => triangles_with_vertex(&mesh.triangles, |v| ring[v as usize]),
        };
        // The first ring: the vertices of the triangles at a reached one,
        // in mesh order.
        let mut first: Vec<u32> = touching(&near, window)
            .into_iter()
            .flat_map(|t| mesh.triangles[t])
            .collect();
        first.sort_unstable();
        first.dedup();
        let mut ring = near;
        ring.fill(false);
        for &v in &first {
            ring[v as usize] = true;
        }
        let window = window.filter(|w| w.holds_all(mesh, first.iter().copied()));
        // And every vertex at the position of one of them: only those in
        // the ring's box need their position looked up (in the window,
        // when that holds the box).
        let keys: rustc_hash::FxHashSet<[u64; 3]> = first
            .iter()
            .map(|&v| position_key(mesh.positions[v as usize]))
            .collect();
        if let Some((lo, hi)) = first.iter().map(|&v| mesh.positions[v as usize]).fold(
            None,
            |b: Option<(DVec3, DVec3)>, p| {
                Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            },
        ) {
            let copy = |v: usize| {
                let p = mesh.positions[v];
                !ring[v]
                    && p.cmpge(lo).all()
                    && p.cmple(hi).all()
                    && keys.contains(&position_key(p))
            };
            let copies: Vec<usize> = match window {
                Some(w) => w
                    .vertices()
                    .par_iter()
                    .with_min_len(PARALLEL_RUN)
                    .map(|&v| v as usize)
                    .filter(|&v| copy(v))
                    .collect(),
                None => (0..n)
                    .into_par_iter()
                    .with_min_len(PARALLEL_RUN)
                    .filter(|&v| copy(v))
                    .collect(),
            };
            for v in copies {
                ring[v] = true;
            }
        }
        // The second ring's triangles, and their vertices in mesh order.
        let kept: Vec<[u32; 3]> = touching(&ring, window)
            .into_iter()
            .map(|t| mesh.triangles[t])
            .collect();
        let (mesh, global) = TriMesh::of_used(&mesh.positions, kept);
        Piece { mesh, global }
    }
}

/// Which of a frame's dabs [`PaintStep::paint_run`] paints.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Run {
    /// All of them as one motion.
    Whole,
    /// The first ones that together move the surface at most one frame's
    /// step ([`substeps`]), at least one.
    Stepped,
}

/// What [`PaintStep::settle`] did with a motion.
enum Settled {
    /// The motion happened (or was held where it made things worse).
    Done,
    /// The engine found the motion too crumpled for one frame; nothing
    /// changed.
    TooCrumpled,
}

/// The strength of each of `steps` frames that together make one frame
/// of `strength`: the displacement shared out, or for a share of the way
/// (smooth, flatten, scrape, pinch) the step whose `steps`-th power is
/// the whole one, (1 − s')ⁿ = 1 − s.
fn sub_strength(brush: Brush, strength: f64, steps: usize) -> f64 {
    // The brushes that take a share of the way towards a target (the
    // neighbour mean, the brush plane, the centre) compound; the others
    // add up.
    let compounds = matches!(
        brush,
        Brush::Smooth | Brush::Flatten | Brush::Scrape | Brush::Pinch
    );
    if compounds && (0.0..=1.0).contains(&strength) {
        1.0 - (1.0 - strength).powf(1.0 / steps as f64)
    } else {
        strength / steps as f64
    }
}

/// How many frames the motion of `mesh` to `end` should take so that no
/// vertex moves farther in one than the mean length of the edges at the
/// moving vertices: ⌈largest displacement / that length⌉, at most
/// 2^[`MAX_SUBFRAME_DEPTH`].
fn substeps(mesh: &TriMesh, end: &[DVec3]) -> usize {
    substeps_of(&mesh.positions, &mesh.triangles, end)
}

/// [`substeps`] of the surface of `triangles` at `positions` moving to
/// `end`.
fn substeps_of(positions: &[DVec3], triangles: &[[u32; 3]], end: &[DVec3]) -> usize {
    let moved: Vec<bool> = positions.iter().zip(end).map(|(p, q)| p != q).collect();
    // The square root of the largest squared distance: the same number
    // (a correctly rounded square root is monotone), one root.
    let farthest = positions
        .iter()
        .zip(end)
        .map(|(p, q)| p.distance_squared(*q))
        .fold(0.0, f64::max)
        .sqrt();
    let (mut sum, mut count) = (0.0, 0usize);
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            if moved[a] || moved[b] {
                sum += positions[a].distance(positions[b]);
                count += 1;
            }
        }
    }
    let mean = sum / count.max(1) as f64;
    if !(mean > 0.0 && farthest.is_finite()) {
        return 1;
    }
    ((farthest / mean).ceil() as usize).clamp(1, 1 << MAX_SUBFRAME_DEPTH)
}

/// The result of [`LiveStroke::finish`].
#[derive(Debug)]
pub struct FinishedStroke {
    /// The surface at the end of the stroke: after the last paint frame, or
    /// after a drag's release and the remeshing that follows it.
    pub mesh: TriMesh,
    /// The diagnostics of the stroke's last topology change; `None` when no
    /// change ran (no frame moved the surface).
    pub diagnostics: Option<Diagnostics>,
    /// What the stroke did, its frame count, final triangle count and time
    /// filled in.
    pub report: StrokeReport,
    /// What a paint stroke knew of `mesh` when it ended: a caller that
    /// begins its next stroke on `mesh` unchanged passes it on
    /// ([`LiveStroke::take_over`]). Empty after a drag, or after a frame
    /// failed.
    pub handover: Handover,
}

/// What a paint stroke leaves the next stroke on the surface it finished
/// with ([`FinishedStroke::handover`], [`LiveStroke::take_over`]).
#[derive(Debug, Default)]
pub struct Handover {
    /// Its far field, valid for that surface: the next stroke is spared
    /// the field's build.
    pub far_field: Option<FarField>,
    /// It knew the surface to be one piece (the guard carried it; false
    /// is "not known"): the next stroke is spared the count.
    pub one_piece: bool,
}

/// The per-vertex drag weights of a grab or move, after checking that the
/// pick point is near the surface.
fn pick(
    mesh: &TriMesh,
    settings: BrushSettings,
    point: DVec3,
) -> Result<(Vec<f64>, DVec3), SculptError> {
    let (triangle, picked) = check_pick(mesh, settings, point)?;
    let weights = match settings.brush {
        // A radius makes the move local: the picked piece's vertices
        // within it, rigidly in the inner half (a plateau) and blending
        // out to the rim.
        Brush::Move if settings.radius > 0.0 => component_of(mesh, triangle)
            .into_iter()
            .zip(&mesh.positions)
            .map(|(held, p)| {
                if held {
                    move_falloff(p.distance(picked), settings.radius)
                } else {
                    0.0
                }
            })
            .collect(),
        Brush::Move => component_of(mesh, triangle)
            .into_iter()
            .map(|held| if held { 1.0 } else { 0.0 })
            .collect(),
        _ => grab_weights_with(mesh, picked, settings.radius, settings.falloff)
            .into_iter()
            .map(|w| w * settings.strength)
            .collect(),
    };
    Ok((weights, picked))
}

/// The triangle and surface point nearest `point`, after checking that it
/// lies within the brush radius (grab, snake hook) or
/// [`MOVE_PICK_FRACTION`] of the diagonal (move).
fn check_pick(
    mesh: &TriMesh,
    settings: BrushSettings,
    point: DVec3,
) -> Result<(usize, DVec3), SculptError> {
    let brush = settings.brush;
    let Some((triangle, picked, distance)) = closest_point(mesh, point) else {
        return Err(SculptError::NoSurface { brush });
    };
    let (limit, why) = match brush {
        Brush::Move => (
            MOVE_PICK_FRACTION * diagonal(mesh),
            "10% of the bounding-box diagonal",
        ),
        _ => (settings.radius, "the brush radius"),
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
    Ok((triangle, picked))
}

/// The local move's weight at `distance` from the pick: 1 within half
/// the radius, then the brush falloff over the outer half
/// (`falloff((d − r/2) / (r/2))`), 0 beyond: a part held rigidly,
/// blended into the rest.
pub fn move_falloff(distance: f64, radius: f64) -> f64 {
    crate::brush::falloff::plateau(distance, radius)
}

/// Remeshing operations counted over a stroke.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RemeshTally {
    /// Edge splits made so far in the stroke.
    pub splits: usize,
    /// Edge collapses made so far in the stroke, those of the cleanup after a
    /// topology change (when remeshing is off) included.
    pub collapses: usize,
    /// Edge flips made so far in the stroke.
    pub flips: usize,
}

impl RemeshTally {
    /// Adds a report; true when it changed the mesh.
    fn add(&mut self, r: &RemeshReport) -> bool {
        self.splits += r.splits;
        self.collapses += r.collapses;
        self.flips += r.flips;
        r.splits + r.collapses + r.flips > 0
    }

    /// Splits, collapses and flips together.
    pub fn operations(&self) -> usize {
        self.splits + self.collapses + self.flips
    }
}

fn tally(report: &mut StrokeReport, r: &Report) {
    report.engine_runs += 1;
    if r.cut.triangles_split > 0 || r.cut.triangles_deleted > 0 {
        report.changes += 1;
    }
    report.raw_odd_vertices += r.raw_odd_vertices;
    report.corrected_odd_vertices += r.corrected_odd_vertices;
    report.specks_removed += r.cut.specks_removed;
}

/// The cleanup after a topology change when remeshing is off: collapses
/// only (no edge is longer than the largest finite length), of edges
/// shorter than 0.3 of the mesh's mean edge length at the stroke's start,
/// with remeshing's angle bounds. `None` for a mesh without a measurable
/// edge.
fn cleanup_options(mesh: &TriMesh) -> Option<RemeshOptions> {
    let range = default_range(mesh)?;
    Some(RemeshOptions {
        min_edge: 0.6 * range.min_edge,
        max_edge: f64::MAX,
        passes: 2,
        ..RemeshOptions::new(range)
    })
}

/// The vertices remeshing may work around: those `near` picks, except
/// the ones sharing their exact position with another vertex. Such copies
/// are the seams of unwelded patches and the corners of a soup; one side
/// of a seam split or collapsed alone would open a crack there, so seams
/// are left as they are (the collapse of a neighbour onto them never
/// moves them: inactive vertices stay put).
///
/// With a `window` whose box holds every vertex `near` picks, only the
/// window's vertices are asked.
fn remesh_active(
    mesh: &TriMesh,
    near: impl Fn(DVec3) -> bool + Sync,
    window: Option<&Window>,
) -> Vec<bool> {
    let (mut active, picked): (Vec<bool>, Vec<u32>) = match window {
        Some(w) => {
            let picked = w.vertices_where(|v| near(mesh.positions[v as usize]));
            let mut active = vec![false; mesh.positions.len()];
            for &v in &picked {
                active[v as usize] = true;
            }
            (active, picked)
        }
        None => {
            let active: Vec<bool> = mesh
                .positions
                .par_iter()
                .with_min_len(PARALLEL_RUN)
                .map(|&p| near(p))
                .collect();
            let picked = (0..mesh.positions.len() as u32)
                .filter(|&v| active[v as usize])
                .collect();
            (active, picked)
        }
    };
    let key = holey_geom::position_key;
    let mut first: std::collections::HashMap<[u64; 3], u32> = std::collections::HashMap::new();
    let mut copies: Vec<u32> = Vec::new();
    for v in picked {
        let p = &mesh.positions[v as usize];
        match first.entry(key(*p)) {
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(v);
            }
            std::collections::hash_map::Entry::Occupied(e) => {
                copies.push(*e.get());
                copies.push(v);
            }
        }
    }
    for v in copies {
        active[v as usize] = false;
    }
    active
}

/// The bounding-box diagonal of the vertices triangles use.
fn diagonal(mesh: &TriMesh) -> f64 {
    used_bounds(mesh).map_or(0.0, |(lo, hi)| lo.distance(hi))
}

/// The bounding box of the vertices triangles use; `None` without
/// triangles.
pub(crate) fn used_bounds(mesh: &TriMesh) -> Option<(DVec3, DVec3)> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for t in &mesh.triangles {
        for &v in t {
            let p = mesh.positions[v as usize];
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo.x <= hi.x).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box in front of [`Reach::contains`] only saves work: it admits
    /// exactly the points within a radius of some dab or mirror image,
    /// here on a lattice through the dabs, including points a radius away
    /// along an axis, where the box's side and the sphere touch.
    #[test]
    fn reach_admits_what_the_distances_admit() {
        let centre = DVec3::new(0.3, -0.2, 0.1);
        let Some(symmetry) = Symmetry::parse("xz", centre) else {
            panic!("xz is a symmetry")
        };
        let mirrors = symmetry.mirrors();
        let dabs = [
            (Dab::At(DVec3::new(0.9, 0.1, -0.4)), 0.25),
            (
                Dab::Pull(DVec3::new(-0.5, 0.6, 0.2), DVec3::new(-0.1, 0.3, 0.7)),
                0.125,
            ),
            (Dab::At(DVec3::new(0.2, -0.8, 0.5)), 0.5),
        ];
        let reach = Reach::new(dabs, &mirrors);
        let plain = |p: DVec3| {
            dabs.iter()
                .any(|&(d, r)| mirrors.iter().any(|m| d.mirrored(m).within(p, r)))
        };
        let (mut admitted, mut refused) = (0, 0);
        let mut check = |p: DVec3| {
            assert_eq!(reach.contains(p), plain(p), "at {p}");
            if plain(p) {
                admitted += 1;
            } else {
                refused += 1;
            }
        };
        for i in -24..=24 {
            for j in -24..=24 {
                for k in -24..=24 {
                    check(DVec3::new(i as f64, j as f64, k as f64) / 16.0);
                }
            }
        }
        for &(d, r) in &dabs {
            for m in &mirrors {
                let Dab::At(c) = d.mirrored(m) else { continue };
                for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
                    for s in [-1.0, 1.0] {
                        for grow in [1.0 - 1e-12, 1.0, 1.0 + 1e-12] {
                            check(c + axis * (s * r * grow));
                        }
                    }
                }
            }
        }
        assert!(admitted > 1000 && refused > 1000, "{admitted} {refused}");
    }

    /// Replays `frames` (each a frame's dabs) as two strokes on `mesh`,
    /// one in a working window from any size and one never, and asserts
    /// they leave the same surface, bit for bit, after every frame, and
    /// that the window's invariant ([`Window`]) holds after every frame
    /// that kept one. Returns the frames that ended with a window, those
    /// that changed topology, and those that did both.
    fn windowed_and_whole_agree(
        what: &str,
        mesh: &TriMesh,
        settings: BrushSettings,
        frames: &[Vec<(DVec3, f64)>],
        remesh: Option<RemeshOptions>,
    ) -> (usize, usize, usize) {
        let first = frames[0][0].0;
        let begin = |window_min: usize| {
            let mut s = LiveStroke::begin(mesh, settings, first, Options::default())
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            s.set_remesh(remesh);
            s.set_window_min(window_min);
            s
        };
        let (mut windowed, mut whole) = (begin(0), begin(usize::MAX));
        let (mut kept, mut changed, mut kept_through_cuts) = (0, 0, 0);
        for (i, dabs) in frames.iter().enumerate() {
            let f = windowed
                .frame_together(dabs)
                .unwrap_or_else(|e| panic!("{what}: frame {i}: {e}"));
            let cut = f.topology_changed;
            changed += usize::from(cut);
            whole
                .frame_together(dabs)
                .unwrap_or_else(|e| panic!("{what}: frame {i}: {e}"));
            assert!(whole.window.is_none());
            assert!(
                windowed.mesh() == whole.mesh(),
                "{what}: frame {i}: the windowed stroke's surface differs"
            );
            if let Some(w) = &windowed.window {
                kept += 1;
                kept_through_cuts += usize::from(cut);
                if let Some(missed) = w.misses(windowed.mesh()) {
                    panic!("{what}: frame {i}: the window misses {missed}");
                }
            }
        }
        let a = windowed.finish().unwrap_or_else(|e| panic!("{what}: {e}"));
        let b = whole.finish().unwrap_or_else(|e| panic!("{what}: {e}"));
        assert!(a.mesh == b.mesh, "{what}: the finished surfaces differ");
        (kept, changed, kept_through_cuts)
    }

    /// Two sheets facing each other across a gap, `n` by `n` squares
    /// each: the lower one at z = 0 facing up, the upper one at z = `gap`
    /// facing down.
    fn facing_sheets(n: u32, gap: f64) -> TriMesh {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for (z, up) in [(0.0, true), (gap, false)] {
            let base = positions.len() as u32;
            for j in 0..=n {
                for i in 0..=n {
                    positions.push(DVec3::new(i as f64 / n as f64, j as f64 / n as f64, z));
                }
            }
            let at = |i: u32, j: u32| base + j * (n + 1) + i;
            for j in 0..n {
                for i in 0..n {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    if up {
                        triangles.extend([[a, b, c], [a, c, d]]);
                    } else {
                        triangles.extend([[a, c, b], [a, d, c]]);
                    }
                }
            }
        }
        TriMesh {
            positions,
            triangles,
        }
    }

    /// The window changes what a frame reads, never what it does: an
    /// inflate dragged across the lower of two facing sheets, remeshed,
    /// pushes it into the upper one (topology changes, which the window
    /// follows through the splice's report) and on, every frame the same with the
    /// window as without, and the window's invariant holding throughout.
    #[test]
    fn a_stroke_in_a_window_is_the_stroke_without_one() {
        let mesh = facing_sheets(48, 0.05);
        let settings = BrushSettings::new(Brush::Inflate, 0.09, 0.6);
        let frames: Vec<Vec<(DVec3, f64)>> = (0..36)
            .map(|k| {
                let x = 0.3 + 0.4 * k as f64 / 35.0;
                // Frames of one and of two dabs.
                let mut dabs = vec![(DVec3::new(x, 0.5, 0.0), 1.0)];
                if k % 3 == 0 {
                    dabs.push((DVec3::new(x + 0.005, 0.5, 0.0), 1.0));
                }
                dabs
            })
            .collect();
        let remesh = Some(RemeshOptions::new(crate::strokes::Remesh {
            min_edge: 0.012,
            max_edge: 0.03,
        }));
        let (kept, changed, through) =
            windowed_and_whole_agree("facing sheets", &mesh, settings, &frames, remesh);
        eprintln!(
            "facing sheets: {kept} frames kept a window, {changed} changed topology, {through} both"
        );
        assert!(changed >= 8, "{changed} frames changed topology");
        // A frame that cuts the surface keeps its window (the splice says
        // what it wrote), and the invariant held after each.
        assert!(through >= 8, "the window was kept through {through} cuts");
        assert!(kept >= frames.len() / 2, "the window was kept {kept} times");
    }

    /// The same with vertices no triangle uses (the Stanford bunny's
    /// file has 1,113), some under the brush's path, inside the window,
    /// some far from it: the frames that cut the surface splice in place
    /// around them, and every frame is the same with the window as
    /// without.
    #[test]
    fn a_stroke_in_a_window_among_unused_vertices_is_the_stroke_without_one() {
        let mut mesh = facing_sheets(32, 0.05);
        let under: Vec<DVec3> = (0..6)
            .map(|k| DVec3::new(0.3 + 0.08 * k as f64, 0.5, 0.02))
            .collect();
        let far = [DVec3::new(5.0, 5.0, 5.0), DVec3::new(-3.0, 0.5, 0.0)];
        mesh.positions.extend(&under);
        mesh.positions.extend(far);
        let settings = BrushSettings::new(Brush::Inflate, 0.09, 0.6);
        let frames: Vec<Vec<(DVec3, f64)>> = (0..16)
            .map(|k| vec![(DVec3::new(0.3 + 0.4 * k as f64 / 15.0, 0.5, 0.0), 1.0)])
            .collect();
        let remesh = Some(RemeshOptions::new(crate::strokes::Remesh {
            min_edge: 0.015,
            max_edge: 0.035,
        }));
        let (kept, changed, through) = windowed_and_whole_agree(
            "sheets with loose vertices",
            &mesh,
            settings,
            &frames,
            remesh,
        );
        assert!(changed >= 4, "{changed} frames changed topology");
        assert!(through >= 4, "the window was kept through {through} cuts");
        assert!(kept >= frames.len() / 2, "the window was kept {kept} times");
    }

    /// The same on a real scan: the first haunch stroke the modeler
    /// recorded on the Stanford bunny (`bench/sculpt/recorded`), frame by
    /// frame as it was sent, at the recorded remeshing range. Reads
    /// `../shared`; skips visibly without it.
    #[test]
    fn stanford_bunny_recorded_stroke_in_a_window_is_the_stroke_without_one() {
        let Some(dir) = holey_testkit::shared_meshes_or_skip("bunny_window") else {
            return;
        };
        let Ok(holey_io::MeshFile::Poly(poly)) =
            holey_io::read_path(&dir.join("stanford-bunny.obj"))
        else {
            panic!("stanford-bunny.obj: not a polygon mesh");
        };
        let mesh = poly.triangulated();
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../bench/sculpt/recorded/bunny_haunch_browser_1.json"
        ))
        .unwrap_or_else(|e| panic!("the recording: {e}"));
        let file = crate::parse_strokes(&text).unwrap_or_else(|e| panic!("the recording: {e}"));
        let stroke = &file.strokes[0];
        let settings = BrushSettings::new(stroke.brush, stroke.radius, stroke.strength);
        let frames: Vec<Vec<(DVec3, f64)>> = stroke.frame_groups();
        let remesh = stroke
            .remesh_or(|| default_range(&mesh))
            .map(RemeshOptions::new);
        let (kept, changed, _) =
            windowed_and_whole_agree("bunny haunch", &mesh, settings, &frames, remesh);
        eprintln!("bunny haunch: {kept} frames kept a window, {changed} changed topology");
        assert!(kept >= frames.len() / 2, "the window was kept {kept} times");
    }
}
