//! Strokes fed one mouse event at a time.

use std::sync::Arc;

use glam::DVec3;
use holey_sculpt::{
    About, Brush, BrushSettings, LiveStroke, Remesh, RemeshOptions, Symmetry, default_range,
};
use holey_topo::Options;
use serde_json::json;

use super::request::{StrokeBegin, StrokeFrame, missing};
use super::{Out, Reply, Shared};
use crate::doc::{ActiveStroke, Document, Mask, mask_flags};
use crate::frame::{
    EdgeBook, FLAG_PREVIEW, Patch, changed_slots, display_triangles, encode_commit, encode_masked,
    encode_patch, encode_positions, encode_sparse, patch_changed,
};
use crate::{ConnId, ServeError};

impl Shared {
    /// `stroke_begin`: a stroke of a brush, its first frame included.
    pub(super) fn stroke_begin(
        &self,
        conn: ConnId,
        doc: &mut Document,
        req: &StrokeBegin,
    ) -> Reply {
        let mesh = doc.sculpt_mesh("sculpting")?;
        let brush = req.brush;
        let radius = req.radius;
        let strength = match brush {
            Brush::Move => 1.0,
            _ => req
                .strength
                .ok_or_else(|| missing("stroke_begin", "strength"))?,
        };
        if brush != Brush::Move && radius <= 0.0 {
            return Err(ServeError::BadRequest("the radius must be positive".into()));
        }
        if brush == Brush::Move && radius < 0.0 {
            return Err(ServeError::BadRequest(
                "a move's radius must be 0 (the whole piece) or positive".into(),
            ));
        }
        let point = DVec3::from_array(req.point);
        // A frame that pushes the surface farther than a fraction of the
        // brush folds it over itself many times at once; every tab would
        // wait for that frame. The modeler's slider stays far below.
        if brush.strength_is_a_share() {
            let (lo, hi) = brush.share_range();
            if !(lo..=hi).contains(&strength) {
                return Err(ServeError::BadRequest(format!(
                    "{brush}: the strength is a share of the way per frame, in [{lo}, {hi}]; got {strength}"
                )));
            }
        }
        let displaces = matches!(
            brush,
            Brush::Inflate | Brush::Draw | Brush::Clay | Brush::Crease | Brush::Layer
        );
        if displaces && strength.abs() > MAX_INFLATE_PER_RADIUS * radius {
            return Err(ServeError::Refused(format!(
                "{brush} strength {strength} is more than {MAX_INFLATE_PER_RADIUS} of the radius {radius} per frame"
            )));
        }
        let settings = BrushSettings {
            falloff: req.falloff.unwrap_or_default(),
            symmetry: symmetry(req, mesh)?,
            pressure: req.pressure_drives.unwrap_or_default(),
            ..BrushSettings::new(brush, radius, strength)
        };
        let mut live = LiveStroke::begin(mesh, settings, point, Options::default())?;
        if !doc.mask().is_empty() {
            live.set_mask(Mask::clone(doc.mask()));
        }
        live.set_preview(brush.is_drag());
        let remesh = remesh_range(mesh, doc.remesh_detail);
        live.set_remesh(remesh.map(RemeshOptions::new));
        // The last stroke's far field, if the document is still as that
        // stroke left it.
        if let Some((version, handover)) = doc.kept.take()
            && version == doc.version()
        {
            live.take_over(handover);
        }
        let display = doc.display().clone();
        let sent = display.positions.clone();
        let book = doc.take_book();
        doc.stroke = Some(ActiveStroke {
            owner: conn,
            live,
            display,
            sent,
            book,
            stale: false,
        });
        // The first frame goes out before the answer, as every frame
        // did: the page waits for this answer before sending any dab.
        let (reply, frame) = self.stroke_frame(doc, &req.first_frame());
        if let Some(bytes) = frame {
            self.hub.broadcast(&Out::Binary(bytes));
        }
        // The range this stroke remeshes to, as a stroke file's `remesh`
        // records it: derived from the mesh as the stroke began, so a
        // replay of the stroke needs it.
        reply.map(|mut ok| {
            ok["remesh"] = match remesh {
                Some(r) => json!(r),
                None => json!("off"),
            };
            ok
        })
    }

    /// `stroke_end`: the stroke finished and committed if it changed the mesh; a release the guard refused says why in plain words.
    pub(super) fn stroke_end(&self, doc: &mut Document) -> Reply {
        let Some(mut stroke) = doc.stroke.take() else {
            return Err(ServeError::Refused("no stroke in progress".into()));
        };
        let done = stroke.live.finish()?;
        let r = done.report;
        let changed = done.mesh != *doc.sculpt_mesh("sculpting")?;
        // What every tab shows: the stroke's connectivity at the positions
        // it was last sent (sparse frames move those only).
        if stroke.sent.len() == stroke.display.positions.len() {
            stroke.display.positions = stroke.sent;
        }
        let shown = if changed {
            // A paint stroke's frames left the tabs showing the mesh it
            // commits, in the slots its patches kept.
            doc.commit_shown(done.mesh, stroke.display, stroke.book)
        } else {
            // A stroke that moved nothing in the end shows the document's
            // display if its frames left that, edges in their slots too.
            stroke.display == *doc.display()
        };
        doc.kept = Some((doc.version(), done.handover));
        if shown {
            // Every tab holds the committed mesh already: a frame of a
            // few bytes commits it, where the whole mesh is 38 MB on a
            // million triangles.
            self.publish_with(doc, encode_commit(doc.display(), doc.version()));
        } else {
            self.publish(doc);
        }
        let mut reply = json!({
            "changes": r.changes,
            "engine_runs": r.engine_runs,
            "frames": r.frames,
            "ms": r.seconds * 1e3,
        });
        let plain = |reasons: &[String]| {
            reasons
                .iter()
                .map(|w| holey_topo::audit::in_plain_words(w))
                .collect::<Vec<&str>>()
                .join(" and ")
        };
        if !r.refused.is_empty() {
            reply["message"] = json!(format!(
                "The drag was undone: releasing it here would {}.",
                plain(&r.refused)
            ));
        } else if !r.held_because.is_empty() {
            // The brush stopped moving part of the surface: say why once
            // per stroke.
            reply["message"] = json!(format!(
                "Part of the stroke held still where moving it would {}.",
                plain(&r.held_because)
            ));
        }
        Ok(reply)
    }

    /// `stroke_frame`: the stroke's next frame, for every tab; with
    /// `points`, one frame per dab in order, as one frame message of the
    /// state after the last (against what the tabs were sent). The answer
    /// and the frame message to broadcast after it (none when no dab was
    /// applied).
    pub(super) fn stroke_frame(
        &self,
        doc: &mut Document,
        req: &StrokeFrame,
    ) -> (Reply, Option<Vec<u8>>) {
        match self.stroke_frames(doc, req) {
            Ok((reply, frame)) => (reply, Some(frame)),
            Err(e) => (Err(e), None),
        }
    }

    /// [`Self::stroke_frame`]: the answer and the frame, or `Err` when the
    /// request is malformed or the frame failed.
    fn stroke_frames(
        &self,
        doc: &mut Document,
        req: &StrokeFrame,
    ) -> Result<(Reply, Vec<u8>), ServeError> {
        let dabs = req.dabs()?;
        let version = doc.version();
        let mask = Arc::clone(doc.mask());
        let Some(stroke) = doc.stroke.as_mut() else {
            return Err(ServeError::Refused("no stroke in progress".into()));
        };
        // The dabs are one frame: the brush is applied at each (the
        // page's spacing), and the collision handling and remeshing run
        // once on their joint motion (`LiveStroke::frame_together`), so a
        // request that carries the dabs queued while the last frame was
        // computed costs little more than one dab. The tabs see the state
        // after the frame.
        let (seconds, connectivity_changed, vanish_mask) = match stroke.live.frame_together(&dabs) {
            Ok(frame) => (
                frame.seconds,
                frame.connectivity_changed || std::mem::take(&mut stroke.stale),
                frame.corrected_odd,
            ),
            Err(e) => {
                stroke.stale = true;
                return Err(e.into());
            }
        };
        let ms = seconds * 1e3;
        let mesh = stroke.live.mesh();
        let vanish = vanish_mask.as_deref();
        let moved = &mesh.positions;
        let bytes = if connectivity_changed {
            // Remeshing and the cut's splice keep most vertex and
            // triangle numbers: only the slots that changed travel (drag
            // previews, whose vanish mask covers every vertex, go whole).
            // Whether a patch can be made is known before the book is
            // built: a frame that changed much of the mesh goes whole.
            let patched = if vanish.is_none() {
                changed_slots(&stroke.display, mesh, MAX_PATCH_SHARE).and_then(|changed| {
                    let mut book = stroke
                        .book
                        .take()
                        .or_else(|| EdgeBook::of(&stroke.display))?;
                    let patch = patch_changed(&mut stroke.display, &mut book, mesh, changed)?;
                    Some((patch, book))
                })
            } else {
                None
            };
            match patched {
                Some((patch, book)) => {
                    stroke.book = Some(book);
                    let masked = patch_mask(&mask, &stroke.display.positions, &patch);
                    encode_patch(
                        &stroke.display,
                        &patch,
                        FLAG_PREVIEW,
                        version,
                        masked.as_deref(),
                    )
                }
                None => {
                    let display = display_triangles(mesh);
                    // New vertex numbers: the mask is sent again with them.
                    let masked = mask_flags(&mask, &display.positions);
                    let bytes =
                        encode_masked(&display, FLAG_PREVIEW, version, vanish, masked.as_deref());
                    stroke.display = display;
                    stroke.book = None;
                    bytes
                }
            }
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
        let reply = Ok(json!({"ms": ms, "vanishing": vanishing, "frames": dabs.len()}));
        Ok((reply, bytes))
    }
}

/// The sculpt mask of the vertices a patch lists, in its order; `None`
/// when none of them is masked.
fn patch_mask(mask: &Mask, positions: &[DVec3], patch: &Patch) -> Option<Vec<bool>> {
    if mask.is_empty() {
        return None;
    }
    let flags: Vec<bool> = patch
        .vertices
        .iter()
        .map(|&v| mask.contains(&holey_geom::position_key(positions[v as usize])))
        .collect();
    flags.contains(&true).then_some(flags)
}

/// The stroke's mirror planes: `symmetry` names the axes (`"xz"`),
/// `symmetry_about` is `origin` (the default) or `centre` (the centre of
/// the mesh's bounding box).
fn symmetry(req: &StrokeBegin, mesh: &holey_topo::TriMesh) -> Result<Symmetry, ServeError> {
    let axes = req.symmetry.as_deref().unwrap_or("");
    let about: About = req.symmetry_about.unwrap_or_default();
    let centre = match about {
        About::Origin => DVec3::ZERO,
        About::Centre => {
            let (lo, hi) = mesh.positions.iter().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), &p| (lo.min(p), hi.max(p)),
            );
            if lo.x <= hi.x {
                (lo + hi) * 0.5
            } else {
                DVec3::ZERO
            }
        }
    };
    Symmetry::parse(axes, centre).ok_or_else(|| {
        ServeError::BadRequest(format!(
            "symmetry names axes among x, y and z, got {axes:?}"
        ))
    })
}

/// The remeshing of the detail slider: off at 0; otherwise edges around
/// `ℓ = L · 4^(1/2 − detail)` (L the mesh's mean edge length: the mesh as
/// it is at 1/2, twice as fine at 1, twice as coarse near 0), kept within
/// half to one and a half times ℓ.
pub(super) fn remesh_range(mesh: &holey_topo::TriMesh, detail: f64) -> Option<Remesh> {
    if detail <= 0.0 {
        return None;
    }
    let base = default_range(mesh)?;
    let scale = 4f64.powf(0.5 - detail.min(1.0));
    Some(Remesh {
        min_edge: base.min_edge * scale,
        max_edge: base.max_edge * scale,
    })
}

/// The largest inflate displacement per frame the server accepts, as a
/// share of the brush radius.
pub const MAX_INFLATE_PER_RADIUS: f64 = 0.25;

/// A connectivity-changing frame goes as a patch while at most this share
/// of the vertices and of the triangles changed; whole beyond.
pub const MAX_PATCH_SHARE: f64 = 0.25;
