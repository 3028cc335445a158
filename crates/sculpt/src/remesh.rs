//! Dynamic remeshing between frames (Bernstein & Wojtan 2013, §4): edge
//! splits, collapses and flips that keep the edge lengths of the brushed
//! region within a target range, within angle bounds, without ever
//! changing topology.
//!
//! - **Local.** Only edges with at least one *active* vertex are touched.
//!   The work set is the triangles around the active vertices and their
//!   neighbours' rings, found by two linear scans of the triangle list (no
//!   global adjacency, no hashing); every operation after that costs in
//!   proportion to the brushed region.
//! - **Any mesh.** Open, non-manifold, unoriented, many components,
//!   degenerate. Splits apply to any edge whose triangles repeat no vertex
//!   (all its triangles are split, so non-manifold and boundary edges stay
//!   what they were). Collapses and flips only involve *regular* vertices
//!   (one fan of triangles, every edge on one or two triangles, zero or two
//!   boundary edges): non-manifold edges and vertices are never collapsed
//!   or flipped across.
//! - **No topology change.** A collapse must pass the link condition
//!   (Dey et al. 1999), with the boundary closed by a virtual vertex: the
//!   two ends share no neighbour but the edge's opposite vertices, no
//!   triangle on both sides of the edge, no boundary pinched, no boundary
//!   loop of three edges collapsed. So Euler characteristic, components,
//!   boundary loops and the degree of every surviving edge are kept.
//! - **Geometry.** No changed triangle flips or turns its normal by more
//!   than [`RemeshOptions::max_normal_change`]; a collapse or flip never
//!   makes an angle outside `[min_angle, max_angle]` unless every
//!   triangle it replaces was already worse (so slivers left by a cut can
//!   be cleaned up, never made); a collapse never makes an edge longer
//!   than `max_edge`. Vertices outside the active region never move.
//! - **Deterministic.** Edges are visited in sorted order; no hashing.
//!
//! Remeshing does not check for new intersections with *other* parts of
//! the surface: a collapse moves the surface by less than `min_edge`, a
//! flip only within a nearly planar quad.

use glam::DVec3;
use holey_geom::Aabb;
use holey_mesh::PARALLEL_RUN;
use holey_mesh::slots::fill_holes;
use holey_mesh::tri::{repeats_a_corner, triangles_with_vertex};
use holey_topo::audit::{is_degenerate, is_flat};
use holey_topo::intersect::crossing_pairs_involving;
use holey_topo::mesh::MeshError;
use holey_topo::{TriMesh, Window};
use rayon::prelude::*;

use crate::strokes::Remesh;

/// Parameters of [`remesh_with`]. [`RemeshOptions::new`] takes the edge
/// range of a stroke file and the authors' angle bounds, 5° and 170°.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RemeshOptions {
    /// Edges shorter than this are collapsed.
    pub min_edge: f64,
    /// Edges longer than this are split.
    pub max_edge: f64,
    /// Angle bounds in degrees for triangles made by collapses and flips.
    pub min_angle: f64,
    /// The largest angle, in degrees, a collapse or flip may make (unless the
    /// triangles it replaces were already worse).
    pub max_angle: f64,
    /// The largest turn, in degrees, of a changed triangle's normal.
    pub max_normal_change: f64,
    /// Rounds of split, collapse and flip (stops early when one does
    /// nothing).
    pub passes: usize,
    /// The most edge splits one call may make (a guard against a range
    /// far below the mesh's scale).
    pub max_splits: usize,
}

impl RemeshOptions {
    /// The edge range `range`, angles 5°–170°, normals turning at most
    /// 45°, 4 passes, at most 2²⁰ splits.
    pub fn new(range: Remesh) -> RemeshOptions {
        RemeshOptions {
            min_edge: range.min_edge,
            max_edge: range.max_edge,
            min_angle: 5.0,
            max_angle: 170.0,
            max_normal_change: 45.0,
            passes: 4,
            max_splits: 1 << 20,
        }
    }

    fn check(&self) -> Result<(), RemeshError> {
        let (lo, hi) = (self.min_edge, self.max_edge);
        if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo < hi) {
            return Err(RemeshError::Range {
                min_edge: lo,
                max_edge: hi,
            });
        }
        let (a, b, n) = (self.min_angle, self.max_angle, self.max_normal_change);
        if !((0.0..60.0).contains(&a) && 60.0 < b && b <= 180.0 && 0.0 < n && n <= 180.0) {
            return Err(RemeshError::Angles {
                min_angle: a,
                max_angle: b,
                max_normal_change: n,
            });
        }
        Ok(())
    }
}

impl From<Remesh> for RemeshOptions {
    fn from(range: Remesh) -> RemeshOptions {
        RemeshOptions::new(range)
    }
}

/// What a remeshing did, and how vertex numbers changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RemeshReport {
    /// Edges split at their midpoint (each with all its triangles).
    pub splits: usize,
    /// Edges collapsed, each merging its two ends into one vertex.
    pub collapses: usize,
    /// Edges flipped: the shared edge of two triangles swapped for the
    /// other diagonal of their quad.
    pub flips: usize,
    /// Passes run.
    pub passes: usize,
    /// Triangles with an active vertex, and the work set around them.
    pub active_triangles: usize,
    /// Triangles of the work set: those around any vertex of an active
    /// triangle, the active ones included.
    pub loaded_triangles: usize,
    /// True when [`RemeshOptions::max_splits`] stopped the splitting.
    pub split_budget_exhausted: bool,
    /// True when [`remesh_in_place_checked`] undid the run because it made
    /// the surface cross itself where it had not (the counts above are
    /// what the undone run did).
    pub undone: bool,
    /// Input vertices removed by collapses (input numbering).
    pub removed_vertices: Vec<u32>,
    /// Vertices made by splits (output numbering).
    pub new_vertices: Vec<u32>,
    /// A box every triangle the run made or unmade meets (at its corners
    /// before or after; `None` when it wrote nothing): the box of the
    /// work set's vertices, before and after. A stroke's kept far field
    /// is told it (`holey_topo::FarField::changed_within`).
    pub changed: Option<(DVec3, DVec3)>,
    /// Surviving input vertices whose number changed, `(input, output)`:
    /// the last vertices move into the slots collapses freed, so the
    /// output has no unused vertex the input did not have. Every other
    /// surviving vertex keeps its number.
    pub renumbered: Vec<(u32, u32)>,
}

impl RemeshReport {
    /// The output number of every input vertex (`None` when removed).
    /// Costs O(vertices); for tests and callers that carry per-vertex data.
    pub fn vertex_map(&self, input_vertices: usize) -> Vec<Option<u32>> {
        let mut map: Vec<Option<u32>> = (0..input_vertices as u32).map(Some).collect();
        for &v in &self.removed_vertices {
            map[v as usize] = None;
        }
        for &(from, to) in &self.renumbered {
            map[from as usize] = Some(to);
        }
        map
    }
}

/// The range used when none is given (§4: the authors' lengths were
/// 0.3–1.0 relative units): half to one and a half times the mesh's mean
/// edge length, so a fresh mesh starts inside it and only what a brush
/// stretches or squeezes is remeshed. `None` without a measurable edge.
pub fn default_range(mesh: &TriMesh) -> Option<Remesh> {
    let (mut sum, mut count) = (0.0, 0usize);
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            if let (Some(p), Some(q)) = (mesh.positions.get(a), mesh.positions.get(b)) {
                sum += p.distance(*q);
                count += 1;
            }
        }
    }
    let mean = sum / count.max(1) as f64;
    (mean.is_finite() && mean > 0.0).then_some(Remesh {
        min_edge: 0.5 * mean,
        max_edge: 1.5 * mean,
    })
}

/// Why a remeshing was refused. The mesh is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RemeshError {
    /// The mesh failed its checks (an index out of range, a non-finite
    /// position, too many vertices).
    #[error("remesh: {0}")]
    Mesh(MeshError),
    /// The `active` mask does not hold one flag per vertex.
    #[error("remesh: the active mask has {got} entries, the mesh has {expected} vertices")]
    ActiveLength {
        /// Number of vertices the mesh has.
        expected: usize,
        /// Number of flags in the mask.
        got: usize,
    },
    /// The edge-length range is not finite with 0 < `min_edge` < `max_edge`.
    #[error(
        "remesh: need 0 < min_edge < max_edge, got min_edge {min_edge} and max_edge {max_edge}"
    )]
    Range {
        /// The [`RemeshOptions::min_edge`] given.
        min_edge: f64,
        /// The [`RemeshOptions::max_edge`] given.
        max_edge: f64,
    },
    /// An angle bound is out of range (in degrees, 0 ≤ `min_angle` < 60 <
    /// `max_angle` ≤ 180 and 0 < `max_normal_change` ≤ 180).
    #[error(
        "remesh: need 0 <= min_angle < 60 < max_angle <= 180 and 0 < max_normal_change <= 180 (degrees), got {min_angle}, {max_angle}, {max_normal_change}"
    )]
    Angles {
        /// The [`RemeshOptions::min_angle`] given, in degrees.
        min_angle: f64,
        /// The [`RemeshOptions::max_angle`] given, in degrees.
        max_angle: f64,
        /// The [`RemeshOptions::max_normal_change`] given, in degrees.
        max_normal_change: f64,
    },
}

/// Remeshes the region of `mesh` around the `active` vertices (one flag
/// per vertex) to edge lengths in `range`, with the default angle bounds
/// (see [`RemeshOptions::new`]).
pub fn remesh(
    mesh: &TriMesh,
    active: &[bool],
    range: Remesh,
) -> Result<(TriMesh, RemeshReport), RemeshError> {
    remesh_with(mesh, active, &RemeshOptions::new(range))
}

/// [`remesh`] with all options.
pub fn remesh_with(
    mesh: &TriMesh,
    active: &[bool],
    options: &RemeshOptions,
) -> Result<(TriMesh, RemeshReport), RemeshError> {
    // Room to grow, so that splits do not copy the whole mesh again.
    let roomy = |n: usize| n + n / 16 + 4096;
    let mut positions = Vec::with_capacity(roomy(mesh.positions.len()));
    positions.extend_from_slice(&mesh.positions);
    let mut triangles = Vec::with_capacity(roomy(mesh.triangles.len()));
    triangles.extend_from_slice(&mesh.triangles);
    let mut out = TriMesh {
        positions,
        triangles,
    };
    let report = remesh_in_place(&mut out, active, options)?;
    Ok((out, report))
}

/// [`remesh_with`] on the mesh itself, which is left unchanged on error.
/// Apart from the checks of the input (linear and cheap) and two scans
/// of the triangle list, the cost follows the active region: the first
/// pass looks at every active edge, each later one only at the edges
/// near what the passes before it changed.
pub fn remesh_in_place(
    mesh: &mut TriMesh,
    active: &[bool],
    options: &RemeshOptions,
) -> Result<RemeshReport, RemeshError> {
    mesh.check().map_err(RemeshError::Mesh)?;
    remesh_run(mesh, active, options, false, None)
}

/// [`remesh_in_place`] that never makes the surface intersect itself
/// more: a collapse or flip can swing a triangle through a sheet nearby
/// (the brushed region is often where sheets were just glued), and the
/// next frame's engine would then start from a self-intersecting surface.
/// The triangles near the ones the run changed are tested exactly before
/// and after; if the run added intersecting pairs or degenerate
/// (zero-area) triangles there, it is not written and
/// [`RemeshReport::undone`] says so.
pub fn remesh_in_place_checked(
    mesh: &mut TriMesh,
    active: &[bool],
    options: &RemeshOptions,
) -> Result<RemeshReport, RemeshError> {
    mesh.check().map_err(RemeshError::Mesh)?;
    remesh_run(mesh, active, options, true, None)
}

/// [`remesh_in_place_checked`] of a mesh known to be valid: a live
/// stroke's, which the guarded topology change has just checked and
/// rebuilt. The mesh is not read once more for its check (a whole-mesh
/// pass, a few milliseconds a frame at a million triangles). With a
/// `window` whose box holds every `active` vertex, the run finds its
/// work set and the triangles its check compares against in the window
/// where that is exact, and tells the window what it wrote.
pub(crate) fn remesh_valid_in_place_checked(
    mesh: &mut TriMesh,
    active: &[bool],
    options: &RemeshOptions,
    window: Option<&mut Window>,
) -> Result<RemeshReport, RemeshError> {
    debug_assert!(mesh.check().is_ok());
    remesh_run(mesh, active, options, true, window)
}

/// Loads the work set of `mesh` (checked by the caller), runs the passes,
/// and writes the result into `mesh` unless `checked` finds it worse
/// ([`Work::worse_than`]). The
/// check runs on the work set before anything is written, so an undone
/// run costs no copy of the mesh.
fn remesh_run(
    mesh: &mut TriMesh,
    active: &[bool],
    options: &RemeshOptions,
    checked: bool,
    window: Option<&mut Window>,
) -> Result<RemeshReport, RemeshError> {
    options.check()?;
    if active.len() != mesh.positions.len() {
        return Err(RemeshError::ActiveLength {
            expected: mesh.positions.len(),
            got: active.len(),
        });
    }
    let mut report = RemeshReport::default();
    let Some(mut work) = Work::load(mesh, active, options, &mut report, window.as_deref()) else {
        return Ok(report);
    };
    for _ in 0..options.passes {
        report.passes += 1;
        let before = (report.splits, report.collapses, report.flips);
        work.split_pass(&mut report);
        work.collapse_pass(&mut report);
        work.flip_pass(&mut report);
        if before == (report.splits, report.collapses, report.flips) {
            break;
        }
    }
    // Checked only when the run changed something (most frames of a
    // stroke over a remeshed surface change nothing).
    let changed = report.splits + report.collapses + report.flips > 0;
    if checked && changed && work.worse_than(mesh, window.as_deref()) {
        report.undone = true;
        return Ok(report);
    }
    if changed {
        report.changed = work.bounds(mesh);
    }
    let written = work.store(mesh, &mut report);
    if let Some(w) = window {
        let mut vertices = report.new_vertices.clone();
        vertices.extend(report.renumbered.iter().map(|&(_, to)| to));
        w.written(mesh, &written, &vertices);
    }
    Ok(report)
}

/// What a run changed, as corners: the triangles it made (at their new
/// corners) and those it unmade (as the mesh still has them), with the
/// mesh slots of the unmade ones, sorted. Every other triangle of the
/// mesh is the same, at the same place, before and after.
struct Changes {
    made: Vec<[DVec3; 3]>,
    made_flat: usize,
    unmade: Vec<[DVec3; 3]>,
    unmade_flat: usize,
    unmade_slots: Vec<u32>,
}

impl Changes {
    /// The triangles of `mesh` that are neither unmade nor beyond the
    /// box of every changed triangle: any triangle crossing a made or
    /// unmade one has a box meeting that triangle's, so it is among
    /// these. A triangle's box misses the region exactly when its three
    /// corners lie beyond one face of it ([`Aabb::outcode`]).
    ///
    /// With a `window` whose box holds the region, the window's triangles
    /// are all that can meet it ([`Window`]).
    fn rest(&self, mesh: &TriMesh, window: Option<&Window>) -> Vec<[DVec3; 3]> {
        let (lo, hi) = self
            .made
            .iter()
            .chain(&self.unmade)
            .flatten()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let region = Aabb::new(lo, hi);
        let kept = |slot: usize, t: &[u32; 3], code: &dyn Fn(u32) -> u8| {
            code(t[0]) & code(t[1]) & code(t[2]) == 0
                && self.unmade_slots.binary_search(&(slot as u32)).is_err()
        };
        if let Some(w) = window.filter(|w| w.holds_box(lo, hi)) {
            let code = |v: u32| region.outcode(mesh.positions[v as usize]);
            return w
                .triangles()
                .par_iter()
                .with_min_len(PARALLEL_RUN)
                .map(|&slot| (slot as usize, &mesh.triangles[slot as usize]))
                .filter(|(slot, t)| kept(*slot, t, &code))
                .map(|(_, t)| t.map(|v| mesh.positions[v as usize]))
                .collect();
        }
        let code = holey_topo::window::outcodes(&region, &mesh.positions);
        mesh.triangles
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .enumerate()
            .filter(|(slot, t)| kept(*slot, t, &|v| code[v as usize]))
            .map(|(_, t)| t.map(|v| mesh.positions[v as usize]))
            .collect()
    }
}

const NONE: u32 = u32::MAX;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    Interior,
    Boundary,
    /// Non-manifold, several fans, a degenerate triangle, or a ring not
    /// loaded: never collapsed, flipped around or moved.
    Singular,
}

/// The local work set: vertices and triangles by local number.
struct Work {
    opts: RemeshOptions,
    cos_normal: f64,
    min_angle: f64,
    max_angle: f64,
    /// Local vertex → input vertex (`NONE` for a vertex made by a split).
    global: Vec<u32>,
    pos: Vec<DVec3>,
    active: Vec<bool>,
    /// The vertex's whole ring of triangles is loaded.
    full: Vec<bool>,
    alive_v: Vec<bool>,
    /// Live local triangles around each local vertex.
    ring: Vec<Vec<u32>>,
    tris: Vec<[u32; 3]>,
    alive_t: Vec<bool>,
    /// Local triangle → its slot in the input (`NONE` for new ones).
    origin: Vec<u32>,
    /// Cached class and valence per local vertex.
    info: Vec<Option<(Class, i64)>>,
    /// Per local vertex: it is one of several loaded vertices at one exact
    /// position, one of them on a rim (a soup's copies of a corner, the
    /// sides of an unwelded seam, and any vertex the cut left there). Such
    /// a vertex is never collapsed, into or away, nor flipped across, and
    /// a rim edge between two of them is never split: each acted on one
    /// copy by number and not its twin, tearing the surface open by
    /// position (a T-junction on a seam, a copy pulled off its corner) or
    /// folding triangles of two copies onto one edge (a cut point
    /// collapsed into one of a soup corner's copies), where an audit that
    /// joins rim copies ([`holey_topo::SurfaceAudit::topology`]) sees the
    /// holes and fins remeshing made. Copies that all have whole fans
    /// (sheets fused at a crossing) are sheets of their own and are
    /// remeshed as any vertex.
    copy: Vec<bool>,
    /// Scratch of [`Work::classify`], reused: a ring's (neighbour,
    /// triangle) pairs and its union-find parents.
    scratch_pairs: Vec<(u32, u32)>,
    scratch_parents: Vec<u32>,
    /// Per local vertex, the tick of the last change to a triangle around
    /// it (its ring, a corner's position): what a pass after the first
    /// looks at ([`Work::edges_to_visit`]).
    changed: Vec<u64>,
    /// Ticks one per change.
    clock: u64,
    /// Per kind of pass (split, collapse, flip), the tick it last began
    /// at; 0 before its first run.
    visited: [u64; 3],
}

/// The kinds of pass, for [`Work::visited`].
const SPLITS: usize = 0;
const COLLAPSES: usize = 1;
const FLIPS: usize = 2;

/// Per loaded vertex (`global`: input numbers; `tris`: the loaded
/// triangles in local numbers, `ring` around each vertex, `full` where
/// the whole ring is loaded): whether it is one of several at one exact
/// position of which one is on a rim, or may be ([`Work::copy`]). Copies
/// that all have whole fans (sheets fused at a crossing) are not: each is
/// a sheet of its own.
fn copies(
    global: &[u32],
    positions: &[DVec3],
    tris: &[[u32; 3]],
    ring: &[Vec<u32>],
    full: &[bool],
) -> Vec<bool> {
    let mut keyed: Vec<([u64; 3], usize)> = global
        .iter()
        .enumerate()
        .map(|(i, &v)| (holey_geom::position_key(positions[v as usize]), i))
        .collect();
    keyed.sort_unstable();
    let mut copy = vec![false; global.len()];
    let mut sides: Vec<u32> = Vec::new();
    let mut rim = |v: usize| {
        if !full[v] {
            return true;
        }
        sides.clear();
        for &t in &ring[v] {
            sides.extend(tris[t as usize].iter().filter(|&&x| x as usize != v));
        }
        sides.sort_unstable();
        sides.chunk_by(|x, y| x == y).any(|run| run.len() == 1)
    };
    for run in keyed
        .chunk_by(|x, y| x.0 == y.0)
        .filter(|run| run.len() > 1)
    {
        if run.iter().any(|&(_, i)| rim(i)) {
            for &(_, i) in run {
                copy[i] = true;
            }
        }
    }
    copy
}

/// Edges packed one to a `u64` (smaller end high, so that the integers'
/// order is the pairs'), sorted, each once, unpacked.
fn unpacked(mut edges: Vec<u64>) -> Vec<(u32, u32)> {
    edges.sort_unstable();
    edges.dedup();
    edges
        .into_iter()
        .map(|e| ((e >> 32) as u32, e as u32))
        .collect()
}

fn normal(p: [DVec3; 3]) -> DVec3 {
    (p[1] - p[0]).cross(p[2] - p[0])
}

/// The three angles in radians; NaN-free for finite input (0 at a corner
/// with a zero-length side).
fn angles(p: [DVec3; 3]) -> [f64; 3] {
    let mut a = [0.0; 3];
    for (k, angle) in a.iter_mut().enumerate() {
        let u = p[(k + 1) % 3] - p[k];
        let w = p[(k + 2) % 3] - p[k];
        *angle = u.cross(w).length().atan2(u.dot(w));
    }
    a
}

impl Work {
    /// Loads the triangles with an active vertex and the rings of all
    /// their vertices. `None` when no triangle has an active vertex.
    fn load(
        mesh: &TriMesh,
        active: &[bool],
        opts: &RemeshOptions,
        report: &mut RemeshReport,
        window: Option<&Window>,
    ) -> Option<Work> {
        let n = mesh.positions.len();
        // The window holds every triangle at an active vertex (the
        // caller's promise); the rings of their vertices, when it holds
        // those vertices too.
        let triangles_with_vertex = |pick: &(dyn Fn(u32) -> bool + Sync), exact: bool| match window
        {
            Some(w) if exact => w.triangles_with_vertex(&mesh.triangles, pick),
            _ => triangles_with_vertex(&mesh.triangles, pick),
        };
        let mut local = vec![NONE; n];
        let mut global = Vec::new();
        // Scan 1: the vertices of triangles with an active vertex get
        // their whole rings loaded.
        let first = triangles_with_vertex(&|v| active[v as usize], true);
        report.active_triangles += first.len();
        for &slot in &first {
            for v in mesh.triangles[slot] {
                if local[v as usize] == NONE {
                    local[v as usize] = global.len() as u32;
                    global.push(v);
                }
            }
        }
        if global.is_empty() {
            return None;
        }
        let full_count = global.len() as u32;
        // Scan 2: every triangle around those vertices.
        let in_window = window.is_some_and(|w| w.holds_all(mesh, global.iter().copied()));
        let around = triangles_with_vertex(&|v| local[v as usize] < full_count, in_window);
        let mut tris = Vec::with_capacity(around.len());
        let mut origin = Vec::with_capacity(around.len());
        for slot in around {
            let lt = mesh.triangles[slot].map(|v| {
                if local[v as usize] == NONE {
                    local[v as usize] = global.len() as u32;
                    global.push(v);
                }
                local[v as usize]
            });
            tris.push(lt);
            origin.push(slot as u32);
        }
        report.loaded_triangles = tris.len();
        let nl = global.len();
        let mut ring = vec![Vec::new(); nl];
        for (i, t) in tris.iter().enumerate() {
            for (k, &v) in t.iter().enumerate() {
                // A triangle repeating a vertex is listed once per vertex.
                if !t[..k].contains(&v) {
                    ring[v as usize].push(i as u32);
                }
            }
        }
        let full: Vec<bool> = (0..nl).map(|i| (i as u32) < full_count).collect();
        let copy = copies(&global, &mesh.positions, &tris, &ring, &full);
        let deg = |d: f64| d.to_radians();
        Some(Work {
            opts: *opts,
            cos_normal: deg(opts.max_normal_change).cos(),
            min_angle: deg(opts.min_angle),
            max_angle: deg(opts.max_angle),
            pos: global.iter().map(|&v| mesh.positions[v as usize]).collect(),
            active: global.iter().map(|&v| active[v as usize]).collect(),
            full,
            alive_v: vec![true; nl],
            info: vec![None; nl],
            copy,
            scratch_pairs: Vec::new(),
            scratch_parents: Vec::new(),
            changed: vec![1; nl],
            clock: 1,
            visited: [0; 3],
            ring,
            alive_t: vec![true; tris.len()],
            tris,
            origin,
            global,
        })
    }

    fn corners(&self, t: [u32; 3]) -> [DVec3; 3] {
        t.map(|v| self.pos[v as usize])
    }

    /// How far the triangle's angles lie outside the bounds (radians).
    fn violation(&self, p: [DVec3; 3]) -> f64 {
        let a = angles(p);
        let lo = a.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = a.iter().copied().fold(0.0, f64::max);
        (self.min_angle - lo).max(0.0) + (hi - self.max_angle).max(0.0)
    }

    /// Live triangles with both `a` and `b`.
    fn edge_tris(&self, a: u32, b: u32) -> Vec<u32> {
        self.edge_triangles(a, b).collect()
    }

    /// [`Work::edge_tris`] without the list: the ring of `a`, filtered.
    fn edge_triangles(&self, a: u32, b: u32) -> impl Iterator<Item = u32> + '_ {
        self.ring[a as usize]
            .iter()
            .copied()
            .filter(move |&t| self.tris[t as usize].contains(&b))
    }

    /// The two live triangles with both `a` and `b`, in ring order, when
    /// there are exactly two ([`Work::edge_tris`] without a list).
    fn edge_pair(&self, a: u32, b: u32) -> Option<[u32; 2]> {
        let mut ts = self.edge_triangles(a, b);
        match (ts.next(), ts.next(), ts.next()) {
            (Some(t1), Some(t2), None) => Some([t1, t2]),
            _ => None,
        }
    }

    /// The edge neighbours of `v`, sorted.
    fn neighbours(&self, v: u32) -> Vec<u32> {
        let mut n: Vec<u32> = self.ring[v as usize]
            .iter()
            .flat_map(|&t| self.tris[t as usize])
            .filter(|&x| x != v)
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// The class and valence of `v`, cached until its ring changes.
    fn info(&mut self, v: u32) -> (Class, i64) {
        if let Some(i) = self.info[v as usize] {
            return i;
        }
        let i = self.classify(v);
        self.info[v as usize] = Some(i);
        i
    }

    fn class(&mut self, v: u32) -> Class {
        self.info(v).0
    }

    /// Forgets the cached class of the vertices of triangle `t`, and
    /// marks them changed.
    fn touch(&mut self, t: u32) {
        self.clock += 1;
        for v in self.tris[t as usize] {
            self.info[v as usize] = None;
            self.changed[v as usize] = self.clock;
        }
    }

    /// The active edges a pass of `kind` has to look at: on its first run
    /// all of them ([`Work::active_edges`]); after that only those near a
    /// change since its last run began, in the same order. An edge's
    /// every test (its length, its triangles, the rings, classes and
    /// valences of its ends and opposite corners, the distances from an
    /// end to its neighbours) reads the triangles around its two ends and
    /// their neighbours, so an edge with neither end within one edge of a
    /// changed vertex would be tested exactly as last time, and fail
    /// again: leaving it out reaches the same fixed point (no long edge,
    /// no collapse, no flip left) without testing the whole region again
    /// for each pass.
    fn edges_to_visit(&mut self, kind: usize) -> Vec<(u32, u32)> {
        let since = std::mem::replace(&mut self.visited[kind], self.clock);
        if since == 0 {
            return self.active_edges();
        }
        let n = self.pos.len();
        // The changed vertices and their neighbours: each edge of a
        // triangle around one of them.
        let mut near = vec![false; n];
        for v in (0..n).filter(|&v| self.alive_v[v] && self.changed[v] > since) {
            near[v] = true;
            for &t in &self.ring[v] {
                for x in self.tris[t as usize] {
                    near[x as usize] = true;
                }
            }
        }
        let live_active = |v: u32| self.active[v as usize] && self.alive_v[v as usize];
        let mut edges: Vec<u64> = Vec::new();
        for v in (0..n).filter(|&v| near[v] && self.alive_v[v]) {
            for &t in &self.ring[v] {
                let tri = self.tris[t as usize];
                for k in 0..3 {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    if a != b && (live_active(a) || live_active(b)) {
                        edges.push(u64::from(a.min(b)) << 32 | u64::from(a.max(b)));
                    }
                }
            }
        }
        unpacked(edges)
    }

    fn classify(&mut self, v: u32) -> (Class, i64) {
        let (mut pairs, mut parents) = (
            std::mem::take(&mut self.scratch_pairs),
            std::mem::take(&mut self.scratch_parents),
        );
        let info = self.classify_with(v, &mut pairs, &mut parents);
        (self.scratch_pairs, self.scratch_parents) = (pairs, parents);
        info
    }

    /// [`Work::classify`] with its scratch lists: the ring's triangles
    /// joined through shared neighbours must form one fan (a union-find
    /// over the ring), each neighbour on one or two of them.
    fn classify_with(
        &self,
        v: u32,
        pairs: &mut Vec<(u32, u32)>,
        parents: &mut Vec<u32>,
    ) -> (Class, i64) {
        let ring = &self.ring[v as usize];
        if !self.full[v as usize] || ring.is_empty() || self.copy[v as usize] {
            return (Class::Singular, 0);
        }
        pairs.clear();
        for (i, &t) in ring.iter().enumerate() {
            let tri = self.tris[t as usize];
            if repeats_a_corner(&tri) {
                return (Class::Singular, 0);
            }
            pairs.extend(tri.iter().filter(|&&x| x != v).map(|&x| (x, i as u32)));
        }
        pairs.sort_unstable();
        parents.clear();
        parents.extend(0..ring.len() as u32);
        let root = |parents: &mut Vec<u32>, mut x: u32| {
            while parents[x as usize] != x {
                let up = parents[parents[x as usize] as usize];
                parents[x as usize] = up;
                x = up;
            }
            x
        };
        let mut groups = ring.len();
        let mut boundary = 0;
        let mut valence = 0;
        for run in pairs.chunk_by(|x, y| x.0 == y.0) {
            valence += 1;
            match run.len() {
                1 => boundary += 1,
                2 => {
                    let (x, y) = (root(parents, run[0].1), root(parents, run[1].1));
                    if x != y {
                        parents[x as usize] = y;
                        groups -= 1;
                    }
                }
                _ => return (Class::Singular, 0),
            }
        }
        let class = match (groups, boundary) {
            (1, 0) => Class::Interior,
            (1, 2) => Class::Boundary,
            _ => Class::Singular,
        };
        (class, valence)
    }

    /// A boundary vertex whose two boundary edges turn by at most
    /// `max_normal_change`: removing it keeps the boundary's shape (a
    /// corner is never removed).
    fn boundary_straight(&self, v: u32) -> bool {
        let ends: Vec<u32> = self
            .neighbours(v)
            .into_iter()
            .filter(|&x| self.is_boundary_edge(v, x))
            .collect();
        let [p, q] = ends[..] else {
            return false;
        };
        let o = self.pos[v as usize];
        let (u, w) = (o - self.pos[p as usize], self.pos[q as usize] - o);
        let (lu, lw) = (u.length(), w.length());
        // Zero-length boundary edges have no direction: nothing to keep.
        lu == 0.0 || lw == 0.0 || u.dot(w) >= self.cos_normal * lu * lw
    }

    /// Degree of edge `a`–`b` (its ring is loaded).
    fn is_boundary_edge(&self, a: u32, b: u32) -> bool {
        self.edge_tris(a, b).len() == 1
    }

    /// Sorted, distinct edges with an active end, whose ends both live.
    fn active_edges(&self) -> Vec<(u32, u32)> {
        // Packed into one u64 each (smaller end high), whose order is the
        // pairs' order: one integer sort instead of a sort of tuples. Of
        // an edge with both ends active, only the smaller end emits it.
        let mut edges: Vec<u64> = Vec::new();
        for v in 0..self.pos.len() as u32 {
            if !(self.active[v as usize] && self.alive_v[v as usize]) {
                continue;
            }
            for &t in &self.ring[v as usize] {
                for &x in &self.tris[t as usize] {
                    if x != v && (x > v || !self.active[x as usize] || !self.alive_v[x as usize]) {
                        let (a, b) = (v.min(x), v.max(x));
                        edges.push(u64::from(a) << 32 | u64::from(b));
                    }
                }
            }
        }
        unpacked(edges)
    }

    fn length(&self, a: u32, b: u32) -> f64 {
        self.pos[a as usize].distance(self.pos[b as usize])
    }

    fn add_vertex(&mut self, p: DVec3) -> u32 {
        let v = self.pos.len() as u32;
        self.global.push(NONE);
        self.pos.push(p);
        self.active.push(true);
        self.full.push(true);
        self.alive_v.push(true);
        self.info.push(None);
        self.copy.push(false);
        self.clock += 1;
        self.changed.push(self.clock);
        self.ring.push(Vec::new());
        v
    }

    fn add_triangle(&mut self, t: [u32; 3]) -> u32 {
        let i = self.tris.len() as u32;
        self.tris.push(t);
        self.alive_t.push(true);
        self.origin.push(NONE);
        for &v in &t {
            self.ring[v as usize].push(i);
        }
        i
    }

    fn unlink(&mut self, v: u32, t: u32) {
        self.ring[v as usize].retain(|&x| x != t);
    }

    // ---- splits ----

    fn split_pass(&mut self, report: &mut RemeshReport) {
        // Each round halves the long edges; 64 rounds cover any ratio of
        // finite lengths the budget allows.
        for _ in 0..64 {
            let mut long: Vec<(f64, u32, u32)> = self
                .edges_to_visit(SPLITS)
                .into_iter()
                .map(|(a, b)| (self.length(a, b), a, b))
                .filter(|&(l, _, _)| l > self.opts.max_edge)
                .collect();
            if long.is_empty() {
                return;
            }
            long.sort_by(|x, y| y.0.total_cmp(&x.0).then((x.1, x.2).cmp(&(y.1, y.2))));
            let mut any = false;
            for (_, a, b) in long {
                if report.splits >= self.opts.max_splits {
                    report.split_budget_exhausted = true;
                    return;
                }
                if self.split(a, b) {
                    report.splits += 1;
                    any = true;
                }
            }
            if !any {
                return;
            }
        }
    }

    /// Splits edge `a`–`b` at its midpoint, with all its triangles.
    fn split(&mut self, a: u32, b: u32) -> bool {
        let ts = self.edge_tris(a, b);
        if ts.is_empty() || ts.iter().any(|&t| repeats_a_corner(&self.tris[t as usize])) {
            return false;
        }
        // A rim edge between two copies is one side of a seam, whose twin
        // would keep its ends ([`Work::copy`]).
        if ts.len() == 1 && self.copy[a as usize] && self.copy[b as usize] {
            return false;
        }
        // Both halves of every triangle must keep an area: a triangle
        // whose opposite corner lies exactly on the edge (a flat sliver a
        // scan or a cut left) would otherwise give a zero-length edge at
        // the midpoint, and the passes after would multiply it.
        let mid = 0.5 * (self.pos[a as usize] + self.pos[b as usize]);
        let halves_flat = ts.iter().any(|&t| {
            let tri = self.tris[t as usize];
            let place = |end: u32| tri.map(|v| if v == end { mid } else { self.pos[v as usize] });
            is_flat(place(a)) || is_flat(place(b))
        });
        if halves_flat {
            return false;
        }
        let m = self.add_vertex(mid);
        // The midpoint of an edge leaving the active region is not active:
        // a long edge reaching out of the brush (a CAD model's fan across
        // a whole face) is halved towards the region, not cut all along
        // its length into a strip the brush never touched.
        self.active[m as usize] = self.active[a as usize] && self.active[b as usize];
        for t in ts {
            self.touch(t);
            let tri = self.tris[t as usize];
            // (… a … b …) becomes (… a … m …) in place and (… m … b …).
            let mut near_a = tri;
            let mut near_b = tri;
            for k in 0..3 {
                if tri[k] == b {
                    near_a[k] = m;
                }
                if tri[k] == a {
                    near_b[k] = m;
                }
            }
            self.tris[t as usize] = near_a;
            self.unlink(b, t);
            self.ring[m as usize].push(t);
            self.add_triangle(near_b);
        }
        true
    }

    // ---- collapses ----

    fn collapse_pass(&mut self, report: &mut RemeshReport) {
        let mut short: Vec<(f64, u32, u32)> = self
            .edges_to_visit(COLLAPSES)
            .into_iter()
            .map(|(a, b)| (self.length(a, b), a, b))
            .filter(|&(l, _, _)| l < self.opts.min_edge)
            .collect();
        short.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
        for (_, a, b) in short {
            if !(self.alive_v[a as usize] && self.alive_v[b as usize])
                || self.length(a, b) >= self.opts.min_edge
                || self.edge_tris(a, b).is_empty()
            {
                continue;
            }
            if self.try_collapse(a, b) {
                report.collapses += 1;
            }
        }
    }

    /// Tries the ways of collapsing `a`–`b`: to the midpoint when both
    /// ends may move, else (or failing that) into either end.
    fn try_collapse(&mut self, a: u32, b: u32) -> bool {
        let (ca, cb) = (self.class(a), self.class(b));
        if ca == Class::Singular || cb == Class::Singular {
            return false;
        }
        let deg = self.edge_tris(a, b).len();
        // (removed, kept): may the removed end go into the kept one?
        let allowed = |x: u32, cx: Class, cy: Class| {
            self.active[x as usize]
                && (cx == Class::Interior || self.boundary_straight(x))
                && matches!(
                    (cx, cy, deg),
                    (Class::Interior, Class::Interior, 2)
                        | (Class::Interior, Class::Boundary, 2)
                        | (Class::Boundary, Class::Boundary, 1)
                )
        };
        let (x, y) = (a.max(b), a.min(b));
        let (cx, cy) = if x == a { (ca, cb) } else { (cb, ca) };
        let mut tries: Vec<(u32, u32, DVec3)> = Vec::with_capacity(3);
        if cx == Class::Interior && allowed(x, cx, cy) && allowed(y, cy, cx) {
            tries.push((x, y, 0.5 * (self.pos[a as usize] + self.pos[b as usize])));
        }
        if allowed(x, cx, cy) {
            tries.push((x, y, self.pos[y as usize]));
        }
        if allowed(y, cy, cx) {
            tries.push((y, x, self.pos[x as usize]));
        }
        if tries.is_empty() || !self.link_condition(a, b) {
            return false;
        }
        for (x, y, p) in tries {
            if self.collapse_geometry_ok(x, y, p) {
                self.collapse(x, y, p);
                return true;
            }
        }
        false
    }

    /// The link condition with the boundary closed by a virtual vertex:
    /// the ends' common neighbours are exactly the edge's opposite
    /// vertices, no triangle lies on both ends over the same opposite
    /// edge, and a boundary edge's triangle has no other boundary edge
    /// at both ends (a boundary loop of three edges).
    fn link_condition(&self, a: u32, b: u32) -> bool {
        let ts = self.edge_tris(a, b);
        let mut opposite: Vec<u32> = ts
            .iter()
            .flat_map(|&t| self.tris[t as usize])
            .filter(|&v| v != a && v != b)
            .collect();
        opposite.sort_unstable();
        let distinct = opposite.windows(2).all(|w| w[0] != w[1]);
        if !distinct || opposite.len() != ts.len() {
            return false;
        }
        let (na, nb) = (self.neighbours(a), self.neighbours(b));
        let common: Vec<u32> = na
            .iter()
            .copied()
            .filter(|v| nb.binary_search(v).is_ok())
            .collect();
        if common != opposite {
            return false;
        }
        // The same by position: copies of one point ([`Work::copy`]) are
        // one neighbour, so the ends must not have two copies of a point
        // for neighbours, one each: joined, their triangles would lie on
        // one edge by position (a cut point collapsed beside a soup's
        // corner once folded four triangles onto one). Valences are small:
        // a pair loop, no allocation.
        let copy_beside = |v: u32, other: u32| {
            v != other && self.copy[v as usize] && opposite.binary_search(&v).is_err()
        };
        let same_point = |u: u32, w: u32| self.pos[u as usize] == self.pos[w as usize];
        if na.iter().any(|&u| {
            copy_beside(u, b) && nb.iter().any(|&w| copy_beside(w, a) && same_point(u, w))
        }) {
            return false;
        }
        match opposite[..] {
            [c, d] => {
                let has = |v: u32| {
                    self.ring[v as usize].iter().any(|&t| {
                        let tri = self.tris[t as usize];
                        tri.contains(&c) && tri.contains(&d)
                    })
                };
                !(has(a) && has(b))
            }
            [c] => !(self.is_boundary_edge(a, c) && self.is_boundary_edge(b, c)),
            _ => false,
        }
    }

    /// The checks of collapsing `x` into `y` placed at `p`: new edges no
    /// longer than `max_edge`, no changed normal flipped or turned too
    /// far, no angle made worse than the bounds and what was there.
    fn collapse_geometry_ok(&self, x: u32, y: u32, p: DVec3) -> bool {
        let moves_y = p != self.pos[y as usize];
        for z in self.neighbours(x) {
            if z != y && p.distance(self.pos[z as usize]) > self.opts.max_edge {
                return false;
            }
        }
        if moves_y {
            for z in self.neighbours(y) {
                if z != x && p.distance(self.pos[z as usize]) > self.opts.max_edge {
                    return false;
                }
            }
        }
        let new_pos = |v: u32| {
            if v == x || v == y {
                p
            } else {
                self.pos[v as usize]
            }
        };
        let mut reference = DVec3::ZERO;
        let mut old_worst: f64 = 0.0;
        let mut changed: Vec<u32> = Vec::new();
        // The triangles of x, then (when y moves) those of y without x.
        let of_y = self.ring[y as usize]
            .iter()
            .filter(|&&t| moves_y && !self.tris[t as usize].contains(&x));
        for &t in self.ring[x as usize].iter().chain(of_y) {
            let tri = self.tris[t as usize];
            let old = self.corners(tri);
            reference += normal(old);
            old_worst = old_worst.max(self.violation(old));
            if !(tri.contains(&x) && tri.contains(&y)) {
                changed.push(t);
            }
        }
        let mut new_worst: f64 = 0.0;
        for &t in &changed {
            let tri = self.tris[t as usize];
            let old = self.corners(tri);
            let new = tri.map(new_pos);
            if !self.normal_ok(old, new, reference) || is_flat(new) {
                return false;
            }
            new_worst = new_worst.max(self.violation(new));
        }
        new_worst == 0.0 || new_worst < old_worst
    }

    /// A changed triangle keeps its side: its new normal turns at most
    /// `max_normal_change` from its old one, or, when the old triangle
    /// is a sliver whose normal means little, from `reference` (the area
    /// normal of the neighbourhood).
    fn normal_ok(&self, old: [DVec3; 3], new: [DVec3; 3], reference: DVec3) -> bool {
        let n1 = normal(new);
        let l1 = n1.length();
        if l1.is_nan() || l1 <= 0.0 {
            return false;
        }
        let n0 = if self.violation(old) > 0.0 {
            reference
        } else {
            normal(old)
        };
        let l0 = n0.length();
        let d = n0.dot(n1);
        l0 > 0.0 && d > 0.0 && d >= self.cos_normal * l0 * l1
    }

    fn collapse(&mut self, x: u32, y: u32, p: DVec3) {
        for i in 0..self.ring[x as usize].len() {
            self.touch(self.ring[x as usize][i]);
        }
        for t in self.edge_tris(x, y) {
            self.alive_t[t as usize] = false;
            for v in self.tris[t as usize] {
                self.unlink(v, t);
            }
        }
        let moved = std::mem::take(&mut self.ring[x as usize]);
        for &t in &moved {
            for v in &mut self.tris[t as usize] {
                if *v == x {
                    *v = y;
                }
            }
        }
        self.ring[y as usize].extend(moved);
        self.alive_v[x as usize] = false;
        self.pos[y as usize] = p;
        // `y` moved: every triangle around it changed shape.
        for i in 0..self.ring[y as usize].len() {
            self.touch(self.ring[y as usize][i]);
        }
    }

    // ---- flips ----

    fn flip_pass(&mut self, report: &mut RemeshReport) {
        for (a, b) in self.edges_to_visit(FLIPS) {
            if self.alive_v[a as usize] && self.alive_v[b as usize] && self.try_flip(a, b) {
                report.flips += 1;
            }
        }
    }

    /// Flips edge `a`–`b` when that lowers the valence excess of the four
    /// vertices, or keeps it and opens the smallest angle.
    fn try_flip(&mut self, a: u32, b: u32) -> bool {
        let Some([t1, t2]) = self.edge_pair(a, b) else {
            return false;
        };
        // Rotate so that t1 = (a, b, c) and t2 = (b, a, d): a consistently
        // oriented pair (otherwise there is no side to keep).
        let rot = |t: u32, first: u32| {
            let tri = self.tris[t as usize];
            let k = tri.iter().position(|&v| v == first).unwrap_or(0);
            [tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]]
        };
        let (mut t1, mut t2) = (t1, t2);
        if rot(t1, a)[1] != b {
            std::mem::swap(&mut t1, &mut t2);
        }
        let (r1, r2) = (rot(t1, a), rot(t2, b));
        if r1[1] != b || r2[1] != a || repeats_a_corner(&r1) || repeats_a_corner(&r2) {
            return false;
        }
        let (c, d) = (r1[2], r2[2]);
        if c == d {
            return false;
        }
        let info = [a, b, c, d].map(|v| self.info(v));
        let classes = info.map(|i| i.0);
        if classes.contains(&Class::Singular)
            || self.ring[c as usize]
                .iter()
                .any(|&t| self.tris[t as usize].contains(&d))
        {
            return false;
        }
        let valence = info.map(|i| i.1);
        let target = classes.map(|k| if k == Class::Interior { 6 } else { 4 });
        let least = classes.map(|k| if k == Class::Interior { 3 } else { 2 });
        if valence[0] - 1 < least[0] || valence[1] - 1 < least[1] {
            return false;
        }
        let after = [
            valence[0] - 1,
            valence[1] - 1,
            valence[2] + 1,
            valence[3] + 1,
        ];
        let excess = |v: &[i64; 4]| (0..4).map(|i| (v[i] - target[i]).abs()).sum::<i64>();
        let (before_excess, after_excess) = (excess(&valence), excess(&after));
        if after_excess > before_excess {
            return false;
        }
        let cd = self.length(c, d);
        if cd > self.opts.max_edge && cd >= self.length(a, b) {
            return false;
        }
        let old = [self.corners(r1), self.corners(r2)];
        let new_t1 = [a, d, c];
        let new_t2 = [d, b, c];
        let new = [self.corners(new_t1), self.corners(new_t2)];
        if new.iter().any(|&p| is_flat(p)) {
            return false;
        }
        let reference = normal(old[0]) + normal(old[1]);
        for n in &new {
            for o in &old {
                if !self.normal_ok(*o, *n, reference) {
                    return false;
                }
            }
        }
        let old_worst = self.violation(old[0]).max(self.violation(old[1]));
        let new_worst = self.violation(new[0]).max(self.violation(new[1]));
        if !(new_worst == 0.0 || new_worst < old_worst) {
            return false;
        }
        if after_excess == before_excess {
            // Equal valence excess: flip only to open the smallest angle
            // clearly (so that no flip is ever undone by the next).
            let smallest = |ts: &[[DVec3; 3]; 2]| {
                ts.iter()
                    .flat_map(|&t| angles(t))
                    .fold(f64::INFINITY, f64::min)
            };
            if smallest(&new) <= smallest(&old) + 1e-3 {
                return false;
            }
        }
        self.touch(t1);
        self.touch(t2);
        self.tris[t1 as usize] = new_t1;
        self.tris[t2 as usize] = new_t2;
        self.unlink(b, t1);
        self.ring[d as usize].push(t1);
        self.unlink(a, t2);
        self.ring[c as usize].push(t2);
        true
    }

    // ---- writing back ----

    /// Writes the work set back into `mesh`: freed slots are reused, then
    /// the last vertices and triangles fill what remains.
    // Local vertex numbers index several parallel arrays here.
    #[allow(clippy::needless_range_loop)]
    /// The box of the work set's vertices at their positions in `mesh`
    /// and after the run: every triangle the run makes or unmakes has its
    /// corners among them, and a vertex the run moves moves within it.
    fn bounds(&self, mesh: &TriMesh) -> Option<(DVec3, DVec3)> {
        let before = self
            .global
            .iter()
            .filter(|&&g| g != NONE)
            .map(|&g| mesh.positions[g as usize]);
        before
            .chain(self.pos.iter().copied())
            .fold(None, |b: Option<(DVec3, DVec3)>, p| {
                Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            })
    }

    /// The triangles the run made and unmade ([`Changes`]), found from
    /// the work set alone: a loaded triangle is unchanged when its
    /// corners are still the input's and none of them moved.
    fn changes(&self, mesh: &TriMesh) -> Changes {
        let moved: Vec<bool> = (0..self.pos.len())
            .map(|v| {
                let g = self.global[v];
                g == NONE || mesh.positions[g as usize] != self.pos[v]
            })
            .collect();
        let mut changes = Changes {
            made: Vec::new(),
            made_flat: 0,
            unmade: Vec::new(),
            unmade_flat: 0,
            unmade_slots: Vec::new(),
        };
        for (i, &t) in self.tris.iter().enumerate() {
            let slot = self.origin[i];
            let same = slot != NONE
                && self.alive_t[i]
                && !t.iter().any(|&v| moved[v as usize])
                && t.map(|v| self.global[v as usize]) == mesh.triangles[slot as usize];
            if same {
                continue;
            }
            if self.alive_t[i] {
                let corners = self.corners(t);
                changes.made_flat += usize::from(repeats_a_corner(&t) || is_flat(corners));
                changes.made.push(corners);
            }
            if slot != NONE {
                let old = mesh.triangles[slot as usize];
                changes.unmade_flat += usize::from(is_degenerate(mesh, old));
                changes.unmade.push(old.map(|v| mesh.positions[v as usize]));
                changes.unmade_slots.push(slot);
            }
        }
        changes.unmade_slots.sort_unstable();
        changes
    }

    /// Whether writing the run into `mesh` would add crossing pairs or
    /// degenerate triangles. The pairs among the triangles the run left
    /// alone are the same before and after, so the whole surface's
    /// counts compare as the counts of pairs a made (or unmade) triangle
    /// takes part in do ([`crossing_pairs_involving`]). The start is
    /// counted only when the result has any.
    fn worse_than(&self, mesh: &TriMesh, window: Option<&Window>) -> bool {
        let changes = self.changes(mesh);
        if changes.made_flat > 0 && changes.made_flat > changes.unmade_flat {
            return true;
        }
        let rest = changes.rest(mesh, window);
        let after = crossing_pairs_involving(&changes.made, &rest);
        after > 0 && after > crossing_pairs_involving(&changes.unmade, &rest)
    }

    /// Returns the triangle slots written: rewritten, filled, appended,
    /// or moved into by [`fill_holes`].
    fn store(self, mesh: &mut TriMesh, report: &mut RemeshReport) -> Vec<u32> {
        let nl = self.pos.len();
        let mut free_v: Vec<u32> = Vec::new();
        let mut final_id = vec![NONE; nl];
        for (v, id) in final_id.iter_mut().enumerate() {
            let g = self.global[v];
            if g == NONE {
                continue;
            }
            if self.alive_v[v] {
                *id = g;
                mesh.positions[g as usize] = self.pos[v];
            } else {
                free_v.push(g);
            }
        }
        free_v.sort_unstable();
        report.removed_vertices = free_v.clone();
        let mut next_free = 0;
        for (v, final_v) in final_id.iter_mut().enumerate() {
            if self.global[v] != NONE || !self.alive_v[v] || self.ring[v].is_empty() {
                continue;
            }
            let id = if let Some(&slot) = free_v.get(next_free) {
                next_free += 1;
                mesh.positions[slot as usize] = self.pos[v];
                slot
            } else {
                mesh.positions.push(self.pos[v]);
                (mesh.positions.len() - 1) as u32
            };
            *final_v = id;
            report.new_vertices.push(id);
        }
        // Triangles: changed ones in place, new ones into freed slots.
        let mut free_t: Vec<u32> = Vec::new();
        let mut fresh: Vec<[u32; 3]> = Vec::new();
        let mut written = Vec::new();
        for (i, t) in self.tris.iter().enumerate() {
            let mapped = t.map(|v| final_id[v as usize]);
            match (self.alive_t[i], self.origin[i]) {
                (true, NONE) => fresh.push(mapped),
                (true, slot) => {
                    mesh.triangles[slot as usize] = mapped;
                    written.push(slot);
                }
                (false, NONE) => {}
                (false, slot) => free_t.push(slot),
            }
        }
        free_t.sort_unstable();
        let mut fresh = fresh.into_iter();
        let mut holes_t = Vec::new();
        for &slot in &free_t {
            match fresh.next() {
                Some(t) => {
                    mesh.triangles[slot as usize] = t;
                    written.push(slot);
                }
                None => holes_t.push(slot),
            }
        }
        let appended = mesh.triangles.len() as u32;
        mesh.triangles.extend(fresh);
        written.extend(appended..mesh.triangles.len() as u32);
        fill_holes(&mut mesh.triangles, &holes_t, |_, to| {
            written.push(to as u32)
        });
        // Vertices: the last ones move into the slots left free.
        let holes_v = &free_v[next_free..];
        if holes_v.is_empty() {
            return written;
        }
        let mut moves = Vec::new();
        fill_holes(&mut mesh.positions, holes_v, |from, to| {
            moves.push((from as u32, to as u32))
        });
        let len = mesh.positions.len() as u32;
        if !moves.is_empty() {
            let mut to_of =
                vec![NONE; moves.iter().map(|m| m.0 - len + 1).max().unwrap_or(0) as usize];
            for &(from, to) in &moves {
                to_of[(from - len) as usize] = to;
            }
            for t in &mut mesh.triangles {
                for v in t {
                    if *v >= len {
                        *v = to_of[(*v - len) as usize];
                    }
                }
            }
        }
        report.renumbered = moves;
        written
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn tri(p: holey_shapes::PolyMesh) -> TriMesh {
        p.triangulated()
    }

    fn sphere(level: u32) -> TriMesh {
        tri(holey_shapes::icosphere(level).unwrap())
    }

    fn grid(n: u32) -> TriMesh {
        tri(holey_shapes::tri_plane(n, n).unwrap())
    }

    fn torus() -> TriMesh {
        tri(holey_shapes::torus(24, 12, 1.0, 0.4).unwrap())
    }

    /// Three square sheets sharing the edge along the x axis (a
    /// non-manifold edge of degree 3), each `n × n` squares.
    fn three_sheets(n: u32) -> TriMesh {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        let spine: Vec<u32> = (0..=n).collect();
        for i in 0..=n {
            positions.push(DVec3::new(
                -1.0 + 2.0 * f64::from(i) / f64::from(n),
                0.0,
                0.0,
            ));
        }
        for k in 0..3 {
            let th = f64::from(k) * std::f64::consts::TAU / 3.0;
            let mut rows = vec![spine.clone()];
            for j in 1..=n {
                let r = f64::from(j) / f64::from(n);
                rows.push(
                    (0..=n)
                        .map(|i| {
                            positions.push(DVec3::new(
                                -1.0 + 2.0 * f64::from(i) / f64::from(n),
                                r * th.cos(),
                                r * th.sin(),
                            ));
                            (positions.len() - 1) as u32
                        })
                        .collect(),
                );
            }
            for j in 0..n as usize {
                for i in 0..n as usize {
                    let (a, b) = (rows[j][i], rows[j][i + 1]);
                    let (c, d) = (rows[j + 1][i + 1], rows[j + 1][i]);
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                }
            }
        }
        TriMesh {
            positions,
            triangles,
        }
    }

    fn join(a: &TriMesh, b: &TriMesh) -> TriMesh {
        let mut m = a.clone();
        m.append(b);
        m
    }

    fn shifted(m: &TriMesh, by: DVec3) -> TriMesh {
        TriMesh {
            positions: m.positions.iter().map(|&p| p + by).collect(),
            triangles: m.triangles.clone(),
        }
    }

    fn undirected(m: &TriMesh) -> std::collections::BTreeMap<(u32, u32), usize> {
        let mut e = std::collections::BTreeMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if a != b {
                    *e.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
        }
        e
    }

    fn union_find_groups(
        n: usize,
        links: impl Iterator<Item = (u32, u32)>,
        used: &[bool],
    ) -> usize {
        let mut parent: Vec<usize> = (0..n).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for (a, b) in links {
            let (x, y) = (find(&mut parent, a as usize), find(&mut parent, b as usize));
            parent[x] = y;
        }
        let mut roots: Vec<usize> = (0..n)
            .filter(|&v| used[v])
            .map(|v| find(&mut parent, v))
            .collect();
        roots.sort_unstable();
        roots.dedup();
        roots.len()
    }

    /// What remeshing must keep: Euler characteristic, components, and for
    /// every edge degree other than 2 (boundaries, non-manifold edges) the
    /// number of connected curves those edges form.
    #[derive(Debug, PartialEq)]
    pub(crate) struct Topology {
        chi: i64,
        components: usize,
        curves_by_degree: Vec<(usize, usize)>,
    }

    /// The triangles of `m` as sorted vertex triples, in sorted order:
    /// triangles with the same three vertices, however turned, are equal.
    fn sorted_triangles(m: &TriMesh) -> Vec<[u32; 3]> {
        let mut keys: Vec<[u32; 3]> = m
            .triangles
            .iter()
            .map(|t| {
                let mut k = *t;
                k.sort_unstable();
                k
            })
            .collect();
        keys.sort_unstable();
        keys
    }

    /// Duplicate triangles (the same three vertices) count once: they are
    /// one simplex of the surface.
    pub(crate) fn topology(m: &TriMesh) -> Topology {
        let mut keys = sorted_triangles(m);
        keys.dedup();
        let m = &TriMesh {
            positions: m.positions.clone(),
            triangles: keys,
        };
        let e = undirected(m);
        let n = m.positions.len();
        let mut used = vec![false; n];
        for t in &m.triangles {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let v = used.iter().filter(|&&u| u).count() as i64;
        let chi = v - e.len() as i64 + m.triangles.len() as i64;
        let components = union_find_groups(
            n,
            m.triangles
                .iter()
                .flat_map(|t| [(t[0], t[1]), (t[1], t[2])]),
            &used,
        );
        let mut degrees: Vec<usize> = e.values().copied().filter(|&d| d != 2).collect();
        degrees.sort_unstable();
        degrees.dedup();
        let curves_by_degree = degrees
            .into_iter()
            .map(|d| {
                let mut on = vec![false; n];
                let links: Vec<(u32, u32)> = e
                    .iter()
                    .filter(|&(_, &k)| k == d)
                    .map(|(&ab, _)| ab)
                    .collect();
                for &(a, b) in &links {
                    on[a as usize] = true;
                    on[b as usize] = true;
                }
                (d, union_find_groups(n, links.into_iter(), &on))
            })
            .collect();
        Topology {
            chi,
            components,
            curves_by_degree,
        }
    }

    /// No triangle repeats a vertex or another triangle unless the input
    /// already had such triangles.
    fn clean_triangles(m: &TriMesh) -> bool {
        let keys = sorted_triangles(m);
        keys.windows(2).all(|w| w[0] != w[1]) && !m.triangles.iter().any(repeats_a_corner)
    }

    fn range(lo: f64, hi: f64) -> Remesh {
        Remesh {
            min_edge: lo,
            max_edge: hi,
        }
    }

    /// Edge lengths of the edges with an active end (output numbering).
    fn active_lengths(m: &TriMesh, active: &[bool]) -> Vec<f64> {
        undirected(m)
            .keys()
            .filter(|&&(a, b)| active[a as usize] || active[b as usize])
            .map(|&(a, b)| m.positions[a as usize].distance(m.positions[b as usize]))
            .collect()
    }

    /// `m` remeshed everywhere to `r` (see [`remesh_checked`]), with the
    /// lengths of its edges: the remesher must have split or collapsed
    /// something, and left no edge longer than `r.max_edge`.
    fn remesh_all_within(m: &TriMesh, r: Remesh) -> (TriMesh, Vec<f64>) {
        let (out, rep) = remesh_checked(m, &all(m), &RemeshOptions::new(r));
        assert!(rep.splits + rep.collapses > 0);
        let lengths = active_lengths(&out, &all(&out));
        assert!(lengths.iter().all(|&l| l <= r.max_edge), "{lengths:?}");
        (out, lengths)
    }

    /// The active flags of the output: input flags carried through the
    /// report's renumbering, new vertices active.
    fn active_after(input: &[bool], out: &TriMesh, r: &RemeshReport) -> Vec<bool> {
        let mut a = vec![false; out.positions.len()];
        for (v, to) in r.vertex_map(input.len()).into_iter().enumerate() {
            if let Some(to) = to {
                a[to as usize] = input[v];
            }
        }
        for &v in &r.new_vertices {
            a[v as usize] = true;
        }
        a
    }

    /// Remeshes and checks what must always hold; returns the output.
    fn remesh_checked(
        m: &TriMesh,
        active: &[bool],
        opts: &RemeshOptions,
    ) -> (TriMesh, RemeshReport) {
        let (out, r) = remesh_with(m, active, opts).unwrap();
        out.check().unwrap();
        assert_eq!(
            topology(&out),
            topology(m),
            "topology changed: {} splits, {} collapses, {} flips",
            r.splits,
            r.collapses,
            r.flips
        );
        // Inactive vertices keep their positions, wherever they now are.
        for (v, to) in r.vertex_map(m.positions.len()).into_iter().enumerate() {
            match to {
                Some(to) if !active[v] => {
                    assert_eq!(out.positions[to as usize], m.positions[v]);
                }
                None => assert!(active[v], "inactive vertex {v} was removed"),
                _ => {}
            }
        }
        // No unused vertex the input did not have.
        let used = |t: &TriMesh| {
            let mut u = vec![false; t.positions.len()];
            t.triangles
                .iter()
                .flatten()
                .for_each(|&v| u[v as usize] = true);
            u.iter().filter(|&&x| !x).count()
        };
        assert!(used(&out) <= used(m));
        // Deterministic.
        assert_eq!(remesh_with(m, active, opts).unwrap().0, out);
        (out, r)
    }

    fn all(m: &TriMesh) -> Vec<bool> {
        vec![true; m.positions.len()]
    }

    fn fraction_short(lengths: &[f64], lo: f64) -> f64 {
        lengths.iter().filter(|&&l| l < lo).count() as f64 / lengths.len().max(1) as f64
    }

    #[test]
    fn refining_a_sphere_brings_every_edge_into_range() {
        let m = sphere(1);
        let opts = RemeshOptions::new(range(0.1, 0.25));
        let (out, r) = remesh_checked(&m, &all(&m), &opts);
        assert!(r.splits > 0);
        let lengths = active_lengths(&out, &all(&out));
        assert!(lengths.iter().all(|&l| l <= 0.25), "{lengths:?}");
        assert!(fraction_short(&lengths, 0.1) < 0.02);
        assert!(out.is_closed_manifold());
        // Splits put new vertices on edges: the surface stays outside-facing.
        for t in 0..out.triangles.len() {
            let c = out.corners(t);
            assert!(normal(c).dot(c[0] + c[1] + c[2]) > 0.0, "inverted {t}");
        }
    }

    /// A flat sliver (its third corner exactly at the middle of its long
    /// edge, as a cut or a scan leaves them) beside a fair triangle: the
    /// long edge is not split there (its midpoint is the sliver's
    /// corner, so a split would make a zero-length edge), and no pass
    /// makes a triangle of zero area that was not there before, nor a
    /// zero-length edge. The fuzz loop once grew one such sliver into
    /// hundreds of coincident vertices over four remeshings.
    #[test]
    fn a_flat_sliver_is_never_split_into_a_zero_length_edge() {
        let m = TriMesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.5, 0.0, 0.0),
                DVec3::new(0.5, -0.8, 0.0),
                DVec3::new(0.5, 0.7, 0.1),
            ],
            // The sliver (0, 1, 2) over the edge 0–1, the fair (1, 0, 3)
            // under it, and (0, 2, 4), (2, 1, 4) closing the fan above.
            triangles: vec![[0, 1, 2], [1, 0, 3], [0, 2, 4], [2, 1, 4]],
        };
        let flat = |t: &TriMesh| {
            t.triangles
                .iter()
                .filter(|&&tri| holey_topo::audit::is_degenerate(t, tri))
                .count()
        };
        assert_eq!(flat(&m), 1);
        let opts = RemeshOptions::new(range(0.05, 0.3));
        // The split itself refuses (a collapse might otherwise remove the
        // zero-length edge again here, but cannot where the link
        // condition forbids it, as in the fuzz loop's case).
        let mut report = RemeshReport::default();
        let mut work = Work::load(&m, &all(&m), &opts, &mut report, None).unwrap();
        assert!(!work.split(0, 1), "the sliver's long edge was split");
        assert!(work.split(0, 3), "a fair edge is split");
        let (out, r) = remesh_checked(&m, &all(&m), &opts);
        assert!(r.splits > 0, "the fair triangles are refined: {r:?}");
        assert!(flat(&out) <= 1, "{} flat triangles", flat(&out));
        for t in &out.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                assert_ne!(
                    out.positions[a], out.positions[b],
                    "zero-length edge {a}-{b}"
                );
            }
        }
    }

    /// A CAD model's long thin triangles reaching into the brush: with
    /// one corner of a 10 × 0.1 strip active and edges to be at most
    /// 0.3 long, the long edges are halved towards the active corner (a
    /// logarithmic number of splits: the midpoint of an edge leaving the
    /// active region is not active), not cut along their whole length
    /// into some 70 pieces the brush never reached; and the far end of the
    /// strip keeps its triangle.
    #[test]
    fn long_edges_leaving_the_region_are_halved_towards_it() {
        let m = TriMesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(10.0, 0.0, 0.0),
                DVec3::new(10.0, 0.1, 0.0),
                DVec3::new(0.0, 0.1, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let active = vec![true, false, false, false];
        let opts = RemeshOptions::new(range(0.1, 0.3));
        let (out, r) = remesh_checked(&m, &active, &opts);
        assert!(r.splits > 0, "{r:?}");
        // Two long edges at the active corner, each halved about
        // log2(10 / 0.3) ≈ 5 times, and a few splits of the short edges
        // those leave.
        assert!(r.splits <= 20, "{} splits", r.splits);
        let near = out.positions.iter().filter(|p| p.x > 5.0).count();
        assert!(near <= 3, "{near} vertices in the strip's far half");
    }

    #[test]
    fn coarsening_a_sphere_collapses_short_edges() {
        let m = sphere(4);
        let opts = RemeshOptions::new(range(0.15, 0.4));
        let (out, r) = remesh_checked(&m, &all(&m), &opts);
        assert!(r.collapses > 0 && r.flips > 0, "{r:?}");
        assert!(
            out.triangles.len() < m.triangles.len() / 3,
            "{}",
            out.triangles.len()
        );
        let lengths = active_lengths(&out, &all(&out));
        assert!(lengths.iter().all(|&l| l <= 0.4));
        assert!(
            fraction_short(&lengths, 0.15) < 0.1,
            "{}",
            fraction_short(&lengths, 0.15)
        );
        assert!(out.is_closed_manifold());
        for t in 0..out.triangles.len() {
            let c = out.corners(t);
            assert!(normal(c).dot(c[0] + c[1] + c[2]) > 0.0, "inverted {t}");
            let a = angles(c);
            assert!(
                a.iter()
                    .all(|&x| (5f64.to_radians()..=170f64.to_radians()).contains(&x))
            );
        }
        assert!(clean_triangles(&out));
    }

    /// The passes after the first look only near what changed
    /// (`Work::edges_to_visit`). Run to the end, they must leave nothing
    /// that a run looking at every edge would still change: a second run
    /// on the result splits, collapses and flips nothing. Refining and
    /// coarsening a sphere, a grid (with a boundary) and a torus.
    /// A shallow tent (ridge `ab` at height 0.1 over the long diagonal of
    /// a rhombus) with a thin sheet just under its ridge, at height 0.09.
    /// Flipping the ridge to the short diagonal `cd` opens the smallest
    /// angle, within every bound, but turns the tent into a valley
    /// through the sheet: the valley is 0.098 high at x = ±0.98, where
    /// the sheet reaches, and 0 at the middle.
    fn tent_over_a_sheet() -> (TriMesh, Vec<bool>) {
        let (h, z) = (0.1, 0.09);
        let mesh = TriMesh {
            positions: vec![
                DVec3::new(-1.0, 0.0, h),
                DVec3::new(1.0, 0.0, h),
                DVec3::new(0.0, -0.5, 0.0),
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(-0.98, 0.0, z),
                DVec3::new(0.98, 0.0, z),
                DVec3::new(0.0, 0.02, z),
            ],
            triangles: vec![[0, 1, 2], [1, 0, 3], [4, 5, 6]],
        };
        let active = vec![true, true, true, true, false, false, false];
        (mesh, active)
    }

    /// The checked remeshing does not write a run that makes the surface
    /// cross itself where it did not, and leaves the mesh exactly as it
    /// was; the unchecked one makes the flip, and the exact pair count
    /// (an independent whole-mesh count) sees the two new crossings.
    /// Without the sheet, the checked run writes the same flip.
    #[test]
    fn checked_remeshing_leaves_a_flip_through_a_sheet_unwritten() {
        use holey_topo::intersect::intersecting_pair_count;
        let (mesh, active) = tent_over_a_sheet();
        let opts = RemeshOptions::new(range(0.5, 3.0));
        assert_eq!(intersecting_pair_count(&mesh, usize::MAX).unwrap(), 0);
        let (free, r) = remesh_with(&mesh, &active, &opts).unwrap();
        assert_eq!((r.splits, r.collapses, r.flips, r.undone), (0, 0, 1, false));
        assert_eq!(intersecting_pair_count(&free, usize::MAX).unwrap(), 2);
        let mut checked = mesh.clone();
        let r = remesh_in_place_checked(&mut checked, &active, &opts).unwrap();
        assert!(r.undone, "{r:?}");
        assert_eq!(checked, mesh);
        assert!(r.removed_vertices.is_empty() && r.new_vertices.is_empty());
        // The tent alone: nothing to cross, so the flip is written.
        let tent = TriMesh {
            positions: mesh.positions[..4].to_vec(),
            triangles: mesh.triangles[..2].to_vec(),
        };
        let mut checked = tent.clone();
        let r = remesh_in_place_checked(&mut checked, &active[..4], &opts).unwrap();
        assert!(!r.undone && r.flips == 1, "{r:?}");
        assert_eq!(checked, remesh_with(&tent, &active[..4], &opts).unwrap().0);
    }

    /// The made and unmade triangles the check reads from the work set
    /// are exactly the run's difference: the input's triangles less the
    /// unmade, plus the made, are the output's, as multisets of corner
    /// triples (an independent diff of the meshes before and after), on
    /// runs that split, collapse and flip; and no triangle is listed as
    /// unmade twice.
    #[test]
    fn the_checks_changes_are_the_difference_of_the_meshes() {
        let key = |t: [DVec3; 3]| t.map(|p| p.to_array().map(f64::to_bits));
        let cases = [
            (sphere(1), range(0.1, 0.25)),
            (sphere(3), range(0.15, 0.4)),
            (grid(12), range(0.03, 0.07)),
            (grid(12), range(0.2, 0.5)),
            (torus(), range(0.3, 0.7)),
        ];
        for (m, r) in cases {
            let opts = RemeshOptions::new(r);
            let active: Vec<bool> = (0..m.positions.len()).map(|v| v % 3 != 0).collect();
            let mut report = RemeshReport::default();
            let mut work = Work::load(&m, &active, &opts, &mut report, None).unwrap();
            work.split_pass(&mut report);
            work.collapse_pass(&mut report);
            work.flip_pass(&mut report);
            assert!(report.splits + report.collapses + report.flips > 0, "{r:?}");
            let changes = work.changes(&m);
            let slots = &changes.unmade_slots;
            assert!(slots.windows(2).all(|w| w[0] < w[1]), "{r:?}");
            let mut out = m.clone();
            work.store(&mut out, &mut report);
            let corners = |mesh: &TriMesh| -> Vec<_> {
                (0..mesh.triangles.len())
                    .map(|t| key(mesh.corners(t)))
                    .collect()
            };
            let mut want = corners(&out);
            let mut got = corners(&m);
            for u in changes.unmade.iter().map(|&t| key(t)) {
                let at = got.iter().position(|&g| g == u).unwrap();
                got.swap_remove(at);
            }
            got.extend(changes.made.iter().map(|&t| key(t)));
            got.sort_unstable();
            want.sort_unstable();
            assert_eq!(got, want, "{r:?}");
        }
    }

    #[test]
    fn passes_near_changes_end_where_a_full_look_finds_nothing_left() {
        let cases = [
            (sphere(1), range(0.1, 0.25)),
            (sphere(4), range(0.15, 0.4)),
            (grid(20), range(0.03, 0.07)),
            (grid(20), range(0.15, 0.4)),
            (torus(), range(0.05, 0.12)),
            (torus(), range(0.3, 0.7)),
        ];
        for (m, r) in cases {
            let opts = RemeshOptions {
                passes: 1000,
                ..RemeshOptions::new(r)
            };
            let (out, first) = remesh_checked(&m, &all(&m), &opts);
            assert!(first.passes < 1000, "{first:?}");
            assert!(
                first.splits + first.collapses + first.flips > 0,
                "{first:?}"
            );
            let mut copy = out.clone();
            let second = remesh_in_place(&mut copy, &all(&out), &opts).unwrap();
            assert_eq!(
                (second.splits, second.collapses, second.flips),
                (0, 0, 0),
                "{r:?}: {second:?} after {first:?}"
            );
            assert_eq!(copy, out);
        }
    }

    #[test]
    fn open_grid_keeps_its_boundary_and_faces_up() {
        let m = grid(20);
        for r in [range(0.15, 0.4), range(0.03, 0.07)] {
            let (out, lengths) = remesh_all_within(&m, r);
            assert!(fraction_short(&lengths, r.min_edge) < 0.1);
            for t in 0..out.triangles.len() {
                assert!(normal(out.corners(t)).z > 0.0, "inverted {t}");
            }
            // The boundary stays on the square's sides.
            for (&(a, b), &d) in &undirected(&out) {
                if d == 1 {
                    let (p, q) = (out.positions[a as usize], out.positions[b as usize]);
                    let on_side = |p: DVec3, q: DVec3| {
                        (p.x.abs() == 1.0 && q.x == p.x) || (p.y.abs() == 1.0 && q.y == p.y)
                    };
                    assert!(on_side(p, q), "boundary edge {p} {q}");
                }
            }
            assert!(clean_triangles(&out));
        }
    }

    /// The open grid cut along x = 0 into two patches that do not share
    /// their seam's vertices (each side has its own copies, as a
    /// teapot's patches do): remeshing finer and coarser never splits a
    /// seam edge on one side, nor moves a seam copy off its twin, so taken
    /// by position the surface keeps its seam closed: every edge with one
    /// triangle lies on the square's outline, none has more than two.
    #[test]
    fn an_unwelded_seam_stays_closed_by_position() {
        let mut m = grid(20);
        let n = m.positions.len() as u32;
        let mut copy_of = std::collections::HashMap::new();
        for t in 0..m.triangles.len() {
            let centre: f64 = m.corners(t).iter().map(|p| p.x).sum::<f64>() / 3.0;
            if centre <= 0.0 {
                continue;
            }
            for k in 0..3 {
                let v = m.triangles[t][k];
                if m.positions[v as usize].x == 0.0 {
                    let c = *copy_of.entry(v).or_insert_with(|| {
                        m.positions.push(m.positions[v as usize]);
                        m.positions.len() as u32 - 1
                    });
                    m.triangles[t][k] = c;
                }
            }
        }
        assert_eq!(m.positions.len() as u32, n + 21, "21 seam copies");
        for r in [range(0.15, 0.4), range(0.03, 0.07)] {
            let (out, rep) = remesh_checked(&m, &all(&m), &RemeshOptions::new(r));
            assert!(rep.splits + rep.collapses > 0);
            let key = |v: u32| out.positions[v as usize].to_array().map(f64::to_bits);
            let mut by_position: std::collections::HashMap<_, usize> = Default::default();
            for t in &out.triangles {
                for k in 0..3 {
                    let (a, b) = (key(t[k]), key(t[(k + 1) % 3]));
                    *by_position.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            for (&(a, b), &d) in &by_position {
                let (p, q) = (a.map(f64::from_bits), b.map(f64::from_bits));
                let on_side =
                    (p[0].abs() == 1.0 && q[0] == p[0]) || (p[1].abs() == 1.0 && q[1] == p[1]);
                assert!(d <= 2, "an edge of {d} triangles at {p:?} {q:?}");
                assert!(d == 2 || on_side, "a hole's edge at {p:?} {q:?}");
            }
            assert!(clean_triangles(&out));
        }
    }

    /// A short edge x–y whose ends each touch one copy of a point (a1 and
    /// a2 at the origin, each on a rim, as a soup's corner): collapsing
    /// it would put triangles of both copies on one edge by position, so
    /// the link condition refuses it; with the second copy moved off the
    /// point it allows it.
    #[test]
    fn a_collapse_never_joins_the_rings_of_two_copies_of_a_point() {
        let mesh = |a2: DVec3| TriMesh {
            positions: vec![
                DVec3::ZERO,                 // a1
                a2,                          // a2
                DVec3::new(1.0, 0.02, 0.0),  // x
                DVec3::new(1.0, -0.02, 0.0), // y
                DVec3::new(1.0, 1.0, 0.0),   // t
                DVec3::new(1.0, -1.0, 0.0),  // b
                DVec3::new(2.0, 0.0, 0.0),   // r
                DVec3::new(0.5, 0.0, 0.0),   // m
            ],
            triangles: vec![
                [0, 2, 4],
                [2, 6, 4],
                [2, 3, 6],
                [3, 2, 7],
                [0, 7, 2],
                [1, 3, 7],
                [1, 5, 3],
                [3, 5, 6],
            ],
        };
        let opts = RemeshOptions::new(range(0.05, 0.3));
        for (a2, joins) in [(DVec3::ZERO, false), (DVec3::new(0.0, -0.001, 0.0), true)] {
            let m = mesh(a2);
            let mut report = RemeshReport::default();
            let work = Work::load(&m, &all(&m), &opts, &mut report, None).unwrap();
            let local = |v: u32| work.global.iter().position(|&g| g == v).unwrap();
            assert_eq!([work.copy[local(0)], work.copy[local(1)]], [!joins; 2]);
            let (x, y) = (local(2) as u32, local(3) as u32);
            assert_eq!(work.link_condition(x, y), joins, "a2 at {a2}");
        }
    }

    #[test]
    fn torus_keeps_genus() {
        let m = torus();
        for r in [range(0.2, 0.5), range(0.05, 0.12)] {
            let (out, _) = remesh_all_within(&m, r);
            assert_eq!(topology(&out).chi, 0);
            assert!(out.is_closed_manifold());
        }
    }

    #[test]
    fn three_sheets_keep_their_non_manifold_edge() {
        let m = three_sheets(8);
        for r in [range(0.4, 0.9), range(0.06, 0.15)] {
            let (out, _) = remesh_all_within(&m, r);
            let e = undirected(&out);
            // The spine is still there, split or not, on the x axis.
            let spine: Vec<_> = e.iter().filter(|&(_, &d)| d == 3).collect();
            assert!(!spine.is_empty());
            for (&(a, b), _) in spine {
                for v in [a, b] {
                    let p = out.positions[v as usize];
                    assert!(p.y == 0.0 && p.z == 0.0);
                }
            }
            assert!(e.values().all(|&d| d <= 3));
        }
    }

    #[test]
    fn close_components_stay_apart() {
        let g = grid(10);
        let m = join(&g, &shifted(&g, DVec3::new(0.05, 0.0, 0.01)));
        let s = join(
            &sphere(2),
            &shifted(&sphere(2), DVec3::new(2.001, 0.0, 0.0)),
        );
        for m in [m, s] {
            for r in [range(0.3, 0.7), range(0.05, 0.12)] {
                let (out, _) = remesh_checked(&m, &all(&m), &RemeshOptions::new(r));
                assert_eq!(topology(&out).components, 2);
            }
        }
    }

    #[test]
    fn only_the_active_region_changes() {
        let m = grid(20);
        let active: Vec<bool> = m.positions.iter().map(|p| p.x < -0.3).collect();
        for r in [range(0.15, 0.4), range(0.03, 0.07)] {
            let (out, rep) = remesh_checked(&m, &active, &RemeshOptions::new(r));
            assert!(rep.active_triangles < m.triangles.len());
            let after = active_after(&active, &out, &rep);
            let lengths = active_lengths(&out, &after);
            // Edges between two inactive vertices are not split, so the
            // edges with an active end are in range but for those.
            assert!(fraction_short(&lengths, r.min_edge) < 0.15);
            // Far from the region the triangles are exactly the input's.
            let far = |t: &TriMesh| {
                let mut k: Vec<[u64; 9]> = (0..t.triangles.len())
                    .map(|i| t.corners(i))
                    .filter(|c| c.iter().all(|p| p.x > 0.0))
                    .map(|c| {
                        let f = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
                        let [a, b, d] = c.map(f);
                        [a[0], a[1], a[2], b[0], b[1], b[2], d[0], d[1], d[2]]
                    })
                    .collect();
                k.sort_unstable();
                k
            };
            assert_eq!(far(&out), far(&m));
        }
    }

    #[test]
    fn nothing_active_changes_nothing() {
        let m = sphere(2);
        let (out, r) = remesh(&m, &vec![false; m.positions.len()], range(0.5, 1.0)).unwrap();
        assert_eq!(out, m);
        assert_eq!(r, RemeshReport::default());
        let e = TriMesh::default();
        assert_eq!(remesh(&e, &[], range(0.5, 1.0)).unwrap().0, e);
    }

    #[test]
    fn degenerate_inputs_do_not_panic() {
        // Zero-length edges: a vertex moved onto its neighbour, and a
        // duplicated position pair.
        let mut z = grid(6);
        z.positions[8] = z.positions[9];
        z.positions[20] = z.positions[27];
        // Duplicate triangles and a triangle repeating a vertex.
        let mut d = grid(4);
        d.triangles.push(d.triangles[3]);
        d.triangles.push([6, 6, 7]);
        // All points on a line; a single triangle; two triangles on one
        // edge pointing both ways; unreferenced vertices.
        let line = TriMesh {
            positions: (0..5).map(|i| DVec3::X * f64::from(i)).collect(),
            triangles: vec![[0, 1, 2], [2, 3, 4], [0, 2, 4]],
        };
        let one = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z * 9.0],
            triangles: vec![[0, 1, 2]],
        };
        let pillow = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 1]],
        };
        let tet = tri(holey_shapes::tetrahedron());
        let tiny = shifted(&sphere(1), DVec3::ZERO);
        let tiny = TriMesh {
            positions: tiny.positions.iter().map(|&p| p * 1e-9).collect(),
            ..tiny
        };
        for m in [z, d, line, one, pillow, tet, tiny] {
            for r in [range(0.3, 0.8), range(1e-3, 0.05), range(10.0, 100.0)] {
                let (out, _) = remesh_checked(&m, &all(&m), &RemeshOptions::new(r));
                out.check().unwrap();
            }
        }
    }

    #[test]
    fn split_budget_stops_runaway_refinement() {
        let m = sphere(0);
        let opts = RemeshOptions {
            max_splits: 100,
            ..RemeshOptions::new(range(1e-6, 1e-5))
        };
        let (out, r) = remesh_checked(&m, &all(&m), &opts);
        assert!(r.split_budget_exhausted);
        assert_eq!(r.splits, 100);
        assert_eq!(out.positions.len(), m.positions.len() + 100);
    }

    #[test]
    fn bad_arguments_are_refused() {
        let m = sphere(0);
        assert!(matches!(
            remesh(&m, &[true], range(0.1, 0.2)),
            Err(RemeshError::ActiveLength { .. })
        ));
        assert!(matches!(
            remesh(&m, &all(&m), range(0.2, 0.1)),
            Err(RemeshError::Range { .. })
        ));
        let opts = RemeshOptions {
            min_angle: 70.0,
            ..RemeshOptions::new(range(0.1, 0.2))
        };
        assert!(matches!(
            remesh_with(&m, &all(&m), &opts),
            Err(RemeshError::Angles { .. })
        ));
        let mut bad = m.clone();
        bad.triangles.push([0, 1, 99]);
        assert!(matches!(
            remesh(&bad, &all(&bad), range(0.1, 0.2)),
            Err(RemeshError::Mesh(_))
        ));
    }
}
