//! The document: one mesh, its workspace, undo and redo, and the modes
//! that hold state between requests (a rind being punched, a stroke being
//! dragged). Every change goes through [`Document::commit`], which bumps
//! the version, so requests made against an older picture are refused.

use std::collections::HashSet;
use std::sync::Arc;

use glam::DVec3;
use holey_dlfl::convert::{ImportOptions, to_dlfl, to_poly};
use holey_dlfl::dlfl_info;
use holey_dlfl::{CornerId, Mesh};
use holey_mesh::PolyMesh;
use holey_mesh::analysis::{MeshInfo, analyze_triangle_topology};
use holey_model::rind::Rind;
use holey_sculpt::{Handover, LiveStroke};
use holey_topo::TriMesh;
use serde_json::{Value, json};

use crate::frame::{Display, EdgeBook, ModelIndex, display_model, display_triangles};
use crate::{ConnId, ServeError};

/// How many strokes and operations undo remembers. Each step keeps a
/// whole mesh, so the history is bounded.
pub const UNDO_LIMIT: usize = 64;

/// What the document holds. Few of these exist at once (the document,
/// its undo history), so the variants' size difference does not matter.
#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
pub enum Content {
    /// The model workspace: a DLFL (the thesis's tools need a 2-manifold).
    Model(Mesh),
    /// The sculpt workspace: any triangle mesh.
    Sculpt(TriMesh),
}

impl Content {
    pub fn workspace(&self) -> &'static str {
        match self {
            Content::Model(_) => "model",
            Content::Sculpt(_) => "sculpt",
        }
    }

    /// The mesh as polygons (holes left out), for export and stats.
    pub fn to_poly(&self) -> PolyMesh {
        match self {
            Content::Model(m) => to_poly(m).poly,
            Content::Sculpt(t) => tri_to_poly(&t.clone().compacted()),
        }
    }

    /// Converts to the model workspace. Fails on a mesh that is not an
    /// orientable 2-manifold with boundary.
    pub fn into_model(self) -> Result<Content, ServeError> {
        match self {
            Content::Model(_) => Ok(self),
            Content::Sculpt(t) => {
                let poly = tri_to_poly(&t.compacted());
                let imported = to_dlfl(&poly, ImportOptions::default()).map_err(|e| {
                    ServeError::Refused(format!(
                        "the model tools need an orientable 2-manifold and this mesh is not one ({}); press Make manifold first",
                        without_flag(&e)
                    ))
                })?;
                Ok(Content::Model(imported.mesh))
            }
        }
    }

    /// The same workspace with the vertices closer than `share` of the
    /// bounding-box diagonal welded (a scan's or a patch model's seams
    /// that do not meet exactly), and a message saying what merged.
    pub fn welded(&self, share: f64) -> Result<(Content, String), ServeError> {
        if !(share.is_finite() && share >= 0.0) {
            return Err(ServeError::BadRequest(format!(
                "the weld distance must be a share of the mesh size of 0 or more, got {share}"
            )));
        }
        let poly = self.to_poly();
        let info = holey_mesh::analysis::analyze(&poly);
        let diagonal = info.bbox.map_or(0.0, |[lo, hi]| {
            glam::DVec3::from_array(lo).distance(glam::DVec3::from_array(hi))
        });
        let w = holey_mesh::analysis::weld_by_distance(&poly, share * diagonal)
            .map_err(|e| ServeError::Refused(format!("weld: {e}")))?;
        let message = format!(
            "welded {} vertices closer than {:.3}% of the size{}",
            w.merged_vertices,
            share * 100.0,
            if w.dropped_faces > 0 {
                format!(", dropping {} collapsed faces", w.dropped_faces)
            } else {
                String::new()
            }
        );
        let content = match self {
            Content::Sculpt(_) => Content::Sculpt(poly_to_tri(&w.mesh)?),
            Content::Model(_) => Content::Model(
                to_dlfl(&w.mesh, ImportOptions::default())
                    .map_err(|e| {
                        ServeError::Refused(format!(
                            "welding leaves a mesh the model tools cannot take ({}); weld in Sculpt, then press Make manifold",
                            without_flag(&e)
                        ))
                    })?
                    .mesh,
            ),
        };
        Ok((content, message))
    }

    /// The mesh made a 2-manifold the model tools can take: non-manifold
    /// and misoriented edges cut, non-manifold vertices split into one
    /// copy per fan, degenerate faces dropped (the repair of `holey
    /// convert --split-nonmanifold`), in the same workspace.
    pub fn made_manifold(&self) -> Result<Content, ServeError> {
        let poly = self.to_poly();
        let imported = to_dlfl(
            &poly,
            ImportOptions {
                split_nonmanifold: true,
            },
        )
        .map_err(|e| ServeError::Refused(format!("the mesh cannot be made a 2-manifold: {e}")))?;
        Ok(match self {
            Content::Model(_) => Content::Model(imported.mesh),
            Content::Sculpt(_) => Content::Sculpt(poly_to_tri(&to_poly(&imported.mesh).poly)?),
        })
    }

    /// Converts to the sculpt workspace: faces are fan-triangulated.
    pub fn into_sculpt(self) -> Result<Content, ServeError> {
        match self {
            Content::Sculpt(_) => Ok(self),
            Content::Model(m) => Ok(Content::Sculpt(poly_to_tri(&to_poly(&m).poly)?)),
        }
    }
}

/// An import error without the command line's advice at its end (the
/// modeler's repair is a button).
fn without_flag(e: &holey_dlfl::convert::ImportError) -> String {
    let why = e.to_string();
    why.split("; split it with")
        .next()
        .unwrap_or(&why)
        .to_owned()
}

/// A polygon soup's faces fan-triangulated.
pub fn poly_to_tri(poly: &PolyMesh) -> Result<TriMesh, ServeError> {
    let mesh = poly.triangulated();
    mesh.check()
        .map_err(|e| ServeError::Refused(format!("the mesh cannot be sculpted: {e}")))?;
    Ok(mesh)
}

fn tri_to_poly(mesh: &TriMesh) -> PolyMesh {
    PolyMesh::from(mesh)
}

/// Dynamic remeshing's default detail: on, at the mesh's own resolution.
/// Sculpting with topology change wants it (§4 remeshes every frame): the
/// cut leaves short edges where curves pass near vertices, and a brush
/// stretches what it lifts.
pub const DEFAULT_REMESH_DETAIL: f64 = 0.5;

/// A rind being punched: the crust shown, and the mesh before it.
pub struct RindMode {
    pub rind: Rind,
    pub thickness: f64,
}

/// The sculpt mask: the exact positions (`holey_geom::position_key`) of
/// the vertices no brush moves. Kept by position, not by index, so that
/// it survives a stroke's topology change and remeshing (a masked vertex
/// never moves, so its key stays).
pub type Mask = HashSet<[u64; 3]>;

/// One step of the undo or redo history: what the document was before it.
/// The mask is shared, not copied, between the steps that leave it alone.
struct Step {
    /// The content before the step; `None` for a step that changed only
    /// the mask.
    content: Option<Content>,
    mask: Arc<Mask>,
}

/// A stroke being dragged by one tab.
pub struct ActiveStroke {
    pub owner: ConnId,
    pub live: LiveStroke,
    /// The connectivity the browser has (positions-only frames refer to it).
    pub display: Display,
    /// The positions the browser has (sparse frames are relative to them).
    pub sent: Vec<DVec3>,
    /// The slots of `display`'s edges, once a patch frame needed them
    /// (or the document had them from the stroke before).
    pub book: Option<EdgeBook>,
    /// A frame failed after it may have changed the surface (a dab of a
    /// frame painted before a later one failed): the next frame's
    /// connectivity is compared with `display` whatever it reports.
    pub stale: bool,
}

/// The document the server edits.
pub struct Document {
    content: Content,
    undo: Vec<Step>,
    redo: Vec<Step>,
    version: u64,
    pub rind: Option<RindMode>,
    pub stroke: Option<ActiveStroke>,
    /// What the last paint stroke handed on (its far field, whether it
    /// knew the surface to be one piece), and the version it describes:
    /// the next stroke takes it over while the document is still at that
    /// version (every change of the content bumps it).
    pub kept: Option<(u64, Handover)>,
    /// A long operation in progress: its owner and name.
    pub busy: Option<(ConnId, String)>,
    /// Dynamic remeshing detail in [0, 1]; 0 is off.
    pub remesh_detail: f64,
    /// The sculpt mask. Its changes are undo steps like the mesh's, and
    /// every undo step restores the mask it had.
    mask: Arc<Mask>,
    display: Display,
    /// The edge slots of `display`, where a stroke's frames left a book
    /// that describes it: the next stroke's first patch need not build
    /// one (a sixth of a second on a million triangles).
    book: Option<EdgeBook>,
    index: ModelIndex,
    stats: Value,
}

impl Document {
    pub fn new(content: Content, version: u64) -> Document {
        let mut doc = Document {
            content,
            undo: Vec::new(),
            redo: Vec::new(),
            version,
            rind: None,
            stroke: None,
            kept: None,
            busy: None,
            remesh_detail: DEFAULT_REMESH_DETAIL,
            mask: Arc::default(),
            display: Display::default(),
            book: None,
            index: ModelIndex::default(),
            stats: Value::Null,
        };
        doc.refresh();
        doc
    }

    pub fn content(&self) -> &Content {
        &self.content
    }

    pub fn version(&self) -> u64 {
        self.version
    }

    pub fn display(&self) -> &Display {
        &self.display
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Recomputes the display, the handle tables and the stats of what is
    /// shown (the rind's crust while punching).
    fn refresh(&mut self) {
        let (display, index) = match (&self.rind, &self.content) {
            (Some(r), _) => display_model(r.rind.mesh()),
            (None, Content::Model(m)) => display_model(m),
            (None, Content::Sculpt(t)) => (display_triangles(t), ModelIndex::default()),
        };
        self.show(display, None, index);
    }

    /// Makes `display` (with its edge book `book`, if known) what the
    /// document shows, and counts the stats of what it shows.
    fn show(&mut self, display: Display, book: Option<EdgeBook>, index: ModelIndex) {
        let triangles = display.triangles.len();
        self.stats = match (&self.rind, &self.content) {
            (Some(r), _) => stats_json(&dlfl_info(r.rind.mesh()), triangles),
            (None, Content::Model(m)) => stats_json(&dlfl_info(m), triangles),
            (None, Content::Sculpt(t)) => sculpt_stats_json(t, triangles),
        };
        self.display = display;
        self.book = book;
        self.index = index;
    }

    /// [`Document::commit`] of a stroke's sculpted mesh `mesh`, which the
    /// stroke's frames left shown as `display` (its edge book `book`):
    /// the document shows that display instead of building its own (a
    /// tenth of a second on a million triangles), in the slots the tabs
    /// already hold. `display` must show `mesh` ([`Display::shows`]);
    /// where it does not, the document builds its own. Whether it showed
    /// `display`: then the tabs that were sent the stroke's frames hold
    /// the document's display already.
    pub fn commit_shown(
        &mut self,
        mesh: TriMesh,
        display: Display,
        book: Option<EdgeBook>,
    ) -> bool {
        let shown = self.rind.is_none() && display.shows(&mesh);
        let old = std::mem::replace(&mut self.content, Content::Sculpt(mesh));
        self.record(Some(old));
        if shown {
            self.show(display, book, ModelIndex::default());
        } else {
            self.refresh();
        }
        shown
    }

    /// The edge book of [`Document::display`], when one is known, given
    /// to a stroke that starts from that display.
    pub fn take_book(&mut self) -> Option<EdgeBook> {
        self.book.take()
    }

    /// The same document with `mask` as its sculpt mask, not an undo step
    /// (a restored session's).
    pub fn with_mask(mut self, mask: Mask) -> Document {
        self.mask = Arc::new(mask);
        self
    }

    /// The sculpt mask.
    pub fn mask(&self) -> &Arc<Mask> {
        &self.mask
    }

    /// Replaces the content as one undo step; the mask stays.
    pub fn commit(&mut self, content: Content) {
        let old = std::mem::replace(&mut self.content, content);
        self.record(Some(old));
        self.refresh();
    }

    /// Replaces the content and clears the mask as one undo step (a new
    /// mesh starts unmasked; undo brings back both).
    pub fn commit_unmasked(&mut self, content: Content) {
        let old = std::mem::replace(&mut self.content, content);
        self.record(Some(old));
        self.mask = Arc::default();
        self.refresh();
    }

    /// Replaces the mask as one undo step, unless it is the same mask.
    /// Says whether it changed.
    pub fn commit_mask(&mut self, mask: Mask) -> bool {
        if mask == *self.mask {
            return false;
        }
        self.record(None);
        self.mask = Arc::new(mask);
        true
    }

    /// Pushes the step back to the state before a change (`old`, the
    /// content it replaces, or `None` when only the mask changes) and
    /// bumps the version.
    fn record(&mut self, old: Option<Content>) {
        self.undo.push(Step {
            content: old,
            mask: Arc::clone(&self.mask),
        });
        if self.undo.len() > UNDO_LIMIT {
            self.undo.remove(0);
        }
        self.redo.clear();
        self.version += 1;
    }

    /// Goes back to `step`, returning the step that comes back here.
    fn restore(&mut self, step: Step) -> Step {
        let content = step
            .content
            .map(|c| std::mem::replace(&mut self.content, c));
        let mask = std::mem::replace(&mut self.mask, step.mask);
        self.version += 1;
        if content.is_some() {
            self.refresh();
        }
        Step { content, mask }
    }

    /// Shows the rind's current crust (after a punch) without committing.
    pub fn touch(&mut self) {
        self.version += 1;
        self.refresh();
    }

    pub fn undo(&mut self) -> bool {
        self.travel(|d| &mut d.undo, |d| &mut d.redo)
    }

    pub fn redo(&mut self) -> bool {
        self.travel(|d| &mut d.redo, |d| &mut d.undo)
    }

    /// Restores the last step of the history `from` and files the step
    /// that comes back here on the history `to`; false (nothing changed)
    /// when `from` is empty. Undo and redo are this one move, mirrored.
    fn travel(
        &mut self,
        from: fn(&mut Self) -> &mut Vec<Step>,
        to: fn(&mut Self) -> &mut Vec<Step>,
    ) -> bool {
        let Some(step) = from(self).pop() else {
            return false;
        };
        let back = self.restore(step);
        to(self).push(back);
        true
    }

    /// The state message every tab receives after a change.
    pub fn state_json(&self) -> Value {
        json!({
            "type": "state",
            "version": self.version,
            "workspace": self.content.workspace(),
            "mode": if self.rind.is_some() { "rind" } else { "normal" },
            "can_undo": self.can_undo(),
            "can_redo": self.can_redo(),
            "stats": self.stats,
            "busy": self.busy.as_ref().map(|(_, op)| op.clone()),
            "remesh": {"detail": self.remesh_detail},
            "stroke": self.stroke.is_some(),
        })
    }

    /// Refuses a request made against another picture than the current.
    pub fn check_version(&self, version: Option<u64>) -> Result<(), ServeError> {
        match version {
            Some(v) if v != self.version => Err(ServeError::Refused(format!(
                "the mesh changed since that selection (version {v}, now {}); select again",
                self.version
            ))),
            _ => Ok(()),
        }
    }

    /// Refuses a request that would edit, select on or replace the
    /// document while a rind is being punched (it ends by committing or
    /// cancelling).
    pub fn check_no_rind(&self) -> Result<(), ServeError> {
        if self.rind.is_some() {
            return Err(ServeError::Refused(
                "finish or cancel the rind first".into(),
            ));
        }
        Ok(())
    }

    /// The model mesh (the rind's crust while punching) or an error
    /// saying the request needs the model workspace.
    pub fn model(&self, what: &str) -> Result<&Mesh, ServeError> {
        match &self.content {
            Content::Model(m) => Ok(m),
            Content::Sculpt(_) => Err(ServeError::Refused(format!(
                "{what} works in the model workspace; switch to it first"
            ))),
        }
    }

    pub fn index(&self) -> &ModelIndex {
        &self.index
    }

    /// The corner at display face `face` and display vertex `vertex`.
    pub fn corner(&self, mesh: &Mesh, face: usize, vertex: usize) -> Result<CornerId, ServeError> {
        let f = *self.index.faces.get(face).ok_or_else(|| {
            ServeError::Refused(format!(
                "face {face} does not exist ({} faces)",
                self.index.faces.len()
            ))
        })?;
        let v = *self.index.vertices.get(vertex).ok_or_else(|| {
            ServeError::Refused(format!(
                "vertex {vertex} does not exist ({} vertices)",
                self.index.vertices.len()
            ))
        })?;
        mesh.corner_of(f, v)
            .map_err(|e| ServeError::Refused(e.to_string()))?
            .ok_or_else(|| ServeError::Refused(format!("vertex {vertex} is not on face {face}")))
    }

    /// The sculpt mask as one flag per displayed vertex, or `None` when no
    /// displayed vertex is masked (or the model workspace is shown).
    pub fn mask_flags(&self) -> Option<Vec<bool>> {
        if self.rind.is_some() || !matches!(self.content, Content::Sculpt(_)) {
            return None;
        }
        mask_flags(&self.mask, &self.display.positions)
    }

    /// The sculpt mesh, or an error saying the request needs it.
    pub fn sculpt_mesh(&self, what: &str) -> Result<&TriMesh, ServeError> {
        match &self.content {
            Content::Sculpt(t) => Ok(t),
            Content::Model(_) => Err(ServeError::Refused(format!(
                "{what} works in the sculpt workspace; switch to it first"
            ))),
        }
    }
}

/// One flag per position, set where the position is in `mask`; `None`
/// when none is.
pub fn mask_flags(mask: &Mask, positions: &[DVec3]) -> Option<Vec<bool>> {
    if mask.is_empty() {
        return None;
    }
    let flags: Vec<bool> = positions
        .iter()
        .map(|&p| mask.contains(&holey_geom::position_key(p)))
        .collect();
    flags.contains(&true).then_some(flags)
}

fn stats_json(info: &MeshInfo, triangles: usize) -> Value {
    json!({
        "vertices": info.vertices,
        "edges": info.edges,
        "faces": info.faces,
        "triangles": triangles,
        "components": info.components,
        "genus": info.genus,
        "boundary_loops": info.boundary_loops,
        "closed": info.closed,
        "manifold": info.manifold,
    })
}

/// [`stats_json`] of a sculpture: only the counts the stats show
/// ([`analyze_triangle_topology`]; they count the vertices the triangles use, so
/// the mesh needs no compaction), not the areas and volumes of a whole
/// analysis, which the modeller would pay for after every stroke.
fn sculpt_stats_json(mesh: &TriMesh, triangles: usize) -> Value {
    let (counts, surface, components) = analyze_triangle_topology(mesh);
    json!({
        "vertices": counts.vertices,
        "edges": counts.edges,
        "faces": counts.faces,
        "triangles": triangles,
        "components": components,
        "genus": surface.genus,
        "boundary_loops": counts.boundary_loops,
        "closed": surface.closed,
        "manifold": surface.manifold,
    })
}

/// The kernel mesh of a built-in primitive, for the server's unit tests.
#[cfg(test)]
#[allow(clippy::unwrap_used)]
pub(crate) fn primitive_mesh(spec: &str) -> Mesh {
    let soup = holey_shapes::parse_primitive(spec).unwrap();
    to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn model(spec: &str) -> Content {
        Content::Model(primitive_mesh(spec))
    }

    /// A sculpture's stats, counted without the geometry and without
    /// compacting, are those of the whole analysis of the compacted
    /// mesh: a torus with a triangle taken out and an unused vertex, and
    /// two spheres.
    #[test]
    fn sculpt_stats_are_the_whole_analysis_counts() {
        let mut torus = holey_shapes::parse_primitive("@torus")
            .unwrap()
            .triangulated();
        torus.triangles.remove(7);
        torus.positions.push(DVec3::splat(9.0));
        let sphere = holey_shapes::parse_primitive("@sphere")
            .unwrap()
            .triangulated();
        let mut two = sphere.clone();
        two.append(&sphere.translated(DVec3::X * 3.0));
        for m in [torus, two] {
            let whole = holey_mesh::analysis::analyze(&tri_to_poly(&m.clone().compacted()));
            assert_eq!(
                sculpt_stats_json(&m, 5),
                stats_json(&whole, 5),
                "{} triangles",
                m.triangles.len()
            );
        }
    }

    #[test]
    fn undo_redo_and_versions() {
        let mut d = Document::new(model("@cube"), 1);
        assert_eq!(d.state_json()["stats"]["genus"], 0);
        d.commit(model("@torus"));
        assert_eq!(d.version(), 2);
        assert_eq!(d.state_json()["stats"]["genus"], 1);
        assert!(d.undo());
        assert_eq!(d.state_json()["stats"]["genus"], 0);
        assert!(d.redo());
        assert_eq!(d.state_json()["stats"]["genus"], 1);
        assert!(!d.redo());
        assert!(d.check_version(Some(1)).is_err());
        assert!(d.check_version(Some(4)).is_ok());
    }

    #[test]
    fn a_rind_in_progress_is_refused_until_it_ends() {
        let mut d = Document::new(model("@cube"), 1);
        assert!(d.check_no_rind().is_ok());
        let rind = holey_model::rind::Rind::from_mesh(d.model("rind").unwrap(), 0.1).unwrap();
        d.rind = Some(RindMode {
            rind,
            thickness: 0.1,
        });
        let err = d.check_no_rind().unwrap_err().to_string();
        assert!(err.contains("finish or cancel the rind first"), "{err}");
        d.rind = None;
        assert!(d.check_no_rind().is_ok());
    }

    #[test]
    fn workspaces_convert_both_ways() {
        let sculpt = model("@torus").into_sculpt().unwrap();
        let Content::Sculpt(t) = &sculpt else {
            panic!("not sculpt")
        };
        assert!(t.is_closed_manifold());
        let back = sculpt.into_model().unwrap();
        let d = Document::new(back, 1);
        assert_eq!(d.state_json()["stats"]["genus"], 1);
        // Three sheets on one edge are no 2-manifold.
        let fan = Content::Sculpt(TriMesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                DVec3::Z,
                DVec3::new(0.5, -1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 1, 3], [0, 1, 4]],
        });
        assert!(fan.into_model().is_err());
    }

    /// Mask edits are undo steps between the mesh's; undoing a mesh step
    /// brings back the mask it had, and a new mesh's cleared mask too.
    #[test]
    fn the_mask_is_undone_with_the_mesh() {
        let key = |x: f64| holey_geom::position_key(DVec3::splat(x));
        let mut d = Document::new(model("@cube").into_sculpt().unwrap(), 1);
        let one: Mask = [key(1.0)].into();
        let two: Mask = [key(1.0), key(2.0)].into();
        assert!(d.commit_mask(one.clone()));
        assert!(!d.commit_mask(one.clone()), "the same mask is no step");
        let after_mask = d.version();
        d.commit(model("@torus").into_sculpt().unwrap());
        assert!(d.commit_mask(two.clone()));
        d.commit_unmasked(model("@cube").into_sculpt().unwrap());
        assert!(d.mask().is_empty());
        // Back through the new mesh, the second mask, the torus, the first mask.
        assert!(d.undo());
        assert_eq!(**d.mask(), two);
        assert_eq!(d.state_json()["stats"]["genus"], 1);
        assert!(d.undo());
        assert_eq!(**d.mask(), one);
        assert_eq!(d.state_json()["stats"]["genus"], 1);
        assert!(d.undo());
        assert_eq!(**d.mask(), one);
        assert_eq!(d.state_json()["stats"]["genus"], 0);
        assert!(d.version() > after_mask);
        assert!(d.undo());
        assert!(d.mask().is_empty());
        assert!(!d.undo());
        // And forward again.
        assert!(d.redo());
        assert_eq!(**d.mask(), one);
        assert!(d.redo() && d.redo());
        assert_eq!(**d.mask(), two);
        assert!(d.redo());
        assert!(d.mask().is_empty());
        assert!(!d.redo());
        // A mask edit drops the redo history like any edit.
        assert!(d.undo());
        assert!(d.commit_mask(one));
        assert!(!d.can_redo());
    }
}
