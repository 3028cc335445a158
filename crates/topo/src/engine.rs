//! The pipeline of §3: collision parity, static intersections, error
//! correction, then subdivision, gluing and deletion.
//!
//! [`topology_change`] runs one frame: a triangle mesh at its start
//! positions and the positions at the end of the frame (linear motion per
//! vertex). [`Accumulator`](crate::Accumulator) runs the drag of §4: raw parity accumulated
//! over many frames, the corrected field available on demand for live
//! preview, and the topology change applied once at release.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use glam::DVec3;
use holey_geom::ccd::{CcdOptions, Identities, Narrow, vertex_parities_cancellable};
use holey_geom::{motion_classes, position_classes};

use crate::correct::{Graph, Scheme, correct};
use crate::cut::{Cut, CutReport, Deletion, cut, mixed_curves};
use crate::drag_path::{DragPath, Keyframes, Numbering, PathSampler};
use crate::intersect::{
    Intersections, Node, PointKind, cut_edges_at_shared, default_pair_limit, intersections,
    intersections_limited, pair_count_at, pairs_intersect_at, shared_ids,
};
use crate::mesh::{Edges, MeshError, TriMesh, check_positions};
use crate::orient::orient_consistently;
use crate::solid::relabel;
use crate::weights::Weights;

/// Options of the engine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Error-correction scheme.
    pub scheme: Scheme,
    /// Collision narrow phase: the exact root parity (default) or the
    /// paper's floating-point cubic.
    pub float_ccd: bool,
    /// Make triangle orientations consistent across manifold edges after
    /// the change, where the surface allows.
    pub orient: bool,
    /// Sample the parity of regions cut off by intersection curves that
    /// contain no vertex (Figure 13's failure; the refinement §7
    /// proposes). Off reproduces the paper, which keeps such regions.
    pub refine: bool,
    /// When a solid (closed, consistently oriented) input comes out not
    /// closed — a motion that folds the surface makes collision parity
    /// inconsistent — label the arrangement by containment number instead
    /// (Lemma 8.1's interpretation; `crate::solid`). For one frame it
    /// also redoes a frame whose exact coincidences broke the solid
    /// ([`topology_change`]). Off reproduces the paper.
    pub solid_guard: bool,
    /// Most intersecting triangle pairs plus candidate triple points a
    /// frame may have at its end before the engine gives up with an error
    /// ([`IntersectError::TooManyPairs`](crate::intersect::IntersectError));
    /// `None` is [`default_pair_limit`]
    /// of the mesh's triangle count, `Some(usize::MAX)` no limit.
    pub max_intersecting_pairs: Option<usize>,
    /// Let a sculpting frame or drag ([`crate::topology_change_guarded`]) leave new
    /// non-manifold curves and pinched vertices: an open sheet glued to a
    /// surface along a curve (the T-junctions of Figures 9 and 11, part
    /// assembly and paper mâché). Off by default: the guard then refuses
    /// such a result (a frame holds the vertices that make it, a drag is
    /// undone).
    pub nonmanifold_joins: bool,
    /// The motion only pushes the surface outward along its normals (an
    /// inflate). Parts it sweeps into each other merge, as in a union
    /// (Theorem 5.2): the solid only grows, so every part of it stays
    /// joined to the rest, and a void it closes off is a piece hidden
    /// inside (which the guard refuses anyway). A sculpting frame
    /// ([`crate::topology_change_guarded`]) that leaves more connected
    /// components than it found has then cut a piece loose that the
    /// motion cannot have made, and the guard refuses it. Off by default:
    /// a deflate, a pinch or a drag may split a piece off. Sculpting also
    /// sets it for a frame that holds vertices earlier frames had to hold:
    /// a piece pinched off at the crease they make is the hold's making.
    pub outward: bool,
    /// A guarded frame ([`crate::topology_change_guarded`]) takes debris
    /// out of its result, new specks the cut closed off whole within its
    /// region (`crate::hidden::debris`), instead of holding the frame for
    /// them. Off by default. Sculpting sets it for an inflate: the specks
    /// of a frame that only grows the solid are the tip of a fold poked
    /// through a sheet, inside it. A deflate's specks mark a crumple, and
    /// carving on through it left the Stanford bunny's haunch in two
    /// pieces with genus 8 where holding keeps it one piece.
    pub take_out_debris: bool,
    /// The caller knows the mesh is one piece (its triangles connected
    /// through shared vertex numbers; [`crate::is_one_piece`]). A guarded
    /// frame ([`crate::topology_change_guarded`]) whose result provably
    /// stays one piece, from its region alone, then does not count the
    /// result's pieces (a pass over the whole mesh: 1.6 ms of a 14 ms
    /// topology frame on the Stanford bunny, 14-23 ms on a million
    /// triangles), and says so in [`crate::LocalReport::one_piece`], for
    /// the caller to pass on to its next frame; where it could not show
    /// it, the count that runs instead may (a frame that leaves two sheets
    /// of its region apart, joined through the rest of the mesh), so one
    /// such frame does not cost the rest of a stroke the shortcut. A
    /// caller that sets it for
    /// a mesh of more pieces may miss a piece the frame cut loose. Off by
    /// default.
    pub one_piece: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            scheme: Scheme::Partition,
            float_ccd: false,
            orient: true,
            refine: true,
            solid_guard: true,
            max_intersecting_pairs: None,
            nonmanifold_joins: false,
            outward: false,
            take_out_debris: false,
            one_piece: false,
        }
    }
}

/// Why the engine refused its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TopoError {
    /// The mesh or its end positions failed validation; the [`MeshError`] says
    /// which check.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The geometry kernel refused the positions (a non-finite coordinate, more
    /// points than its 32-bit identities address) while numbering them or
    /// detecting collisions (§3.2).
    #[error("collision detection: {0}")]
    Geometry(#[from] holey_geom::GeomError),
    /// Finding the static intersections at the end positions (§3.3) failed, or
    /// found more intersecting pairs than [`Options::max_intersecting_pairs`]
    /// allows.
    #[error("static intersections: {0}")]
    Intersections(#[from] crate::intersect::IntersectError),
}

/// Seconds spent in each stage (wall time). A one-frame run finds the
/// collisions and the intersections at the same time, so those two
/// overlap and `total` is less than the sum.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Continuous collision detection for the raw parity field (§3.2); 0 when
    /// the parity comes from containment instead.
    pub collisions: f64,
    /// Static intersections at the end positions (§3.3).
    pub intersections: f64,
    /// Error correction (§3.4); in a union by containment
    /// ([`crate::union()`]), which has nothing to correct, the rays that
    /// compute its exact parity.
    pub correction: f64,
    /// Subdivision, gluing and deletion (§3.5), with the solid guard, pinch
    /// splitting and reorientation that follow it.
    pub cut: f64,
    /// The whole call, from the input checks to the output.
    pub total: f64,
}

/// What one topology change did (the report of the issue).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// Vertex–triangle pairs with an odd number of collisions.
    pub collisions: usize,
    /// Narrow-phase collision tests run.
    pub collision_tests: u64,
    /// Rays cast to decide containment parity (the union of two solids,
    /// [`crate::union()`], computes the motion's parity this way).
    pub containment_rays: usize,
    /// Input vertices whose raw parity is odd: an odd number of collisions
    /// (§3.2).
    pub raw_odd_vertices: usize,
    /// Input vertices whose parity is odd after error correction (§3.4).
    pub corrected_odd_vertices: usize,
    /// Intersection points at the end positions (§3.3): edge × triangle
    /// crossings and triple points.
    pub intersection_points: usize,
    /// Of those, the triple points, where three triangles meet.
    pub triple_points: usize,
    /// Curve pieces: segments of intersection curves between consecutive
    /// intersection points (or shared vertices).
    pub intersection_edges: usize,
    /// Intersection curves: connected components of the curve pieces.
    pub intersection_curves: usize,
    /// Triangle pairs that intersect along a segment at the end positions.
    pub intersecting_pairs: usize,
    /// What subdivision, gluing and deletion did (§3.5).
    pub cut: CutReport,
    /// Components whose correction system was solved.
    pub solved_components: usize,
    /// Components whose correction system could not be factorised; they
    /// keep their raw parity.
    pub unsolved_components: usize,
    /// Retries with perturbed end positions (one frame:
    /// [`topology_change`]'s; the union: [`crate::union_robust`]'s
    /// nudges). Degeneracies are resolved by simulation of simplicity; a
    /// retry happens only when a closed 2-manifold input came out as
    /// something else (coplanar overlaps).
    pub perturbation_retries: usize,
    /// Triangle pairs of the output that cross, where they were counted
    /// exactly: a Boolean whose B was nudged off coplanar contact
    /// ([`crate::union_robust`]), where the nudge leaves slivers at its
    /// own scale and rounding their points can make them cross. `None`
    /// where not counted (an exact result in general position).
    pub output_intersecting_pairs: Option<usize>,
    /// The input was a closed, consistently oriented 2-manifold (a
    /// solid's surface): the solid guard and the coplanar retry apply.
    pub solid_input: bool,
    /// Zero-area triangles of a Boolean's inputs taken out before it
    /// ran, without moving the surface ([`crate::zero_area`]): pinched
    /// ones deleted after their coincident corners were welded, flat ones
    /// whose neighbour took their middle corner. 0 for a motion.
    pub zero_area_removed: usize,
    /// Output triangles flipped to agree in orientation with their neighbours
    /// ([`Options::orient`]); 0 when that is off.
    pub orientation_flips: usize,
    /// Wall-clock seconds per stage.
    pub timings: Timings,
}

impl Report {
    /// A report holding only the counts of the static intersections `x`
    /// (points, triple points, pieces, curves, pairs), for a run to fill
    /// in the rest.
    pub(crate) fn of_intersections(x: &Intersections) -> Report {
        Report {
            intersection_points: x.points.len(),
            triple_points: x.triple_points(),
            intersection_edges: x.pieces.len(),
            intersection_curves: x.curve_count,
            intersecting_pairs: x.pairs.len(),
            ..Report::default()
        }
    }
}

/// The result of a topology change.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    /// The surface after the topology change, at the end positions.
    pub mesh: TriMesh,
    /// What the run did: counts per stage and timings.
    pub report: Report,
    /// Raw parity per input vertex (`true` = odd).
    pub raw_odd: Vec<bool>,
    /// Corrected parity per input vertex.
    pub corrected_odd: Vec<bool>,
    /// The self-intersections of the input at its end positions.
    pub intersections: Intersections,
    /// Per output vertex: the input vertex it is, or `u32::MAX` for a
    /// point the cut made.
    pub vertex_origin: Vec<u32>,
}

/// The static intersections at the end positions (§3.3), with the edges
/// and identities the later stages share. It does not depend on the
/// collisions, so a frame computes both at once.
pub(crate) struct Geometry {
    pub(crate) edges: Edges,
    pub(crate) ids: Vec<u32>,
    pub(crate) x: Intersections,
    t_intersect: f64,
}

pub(crate) fn geometry_stage(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
    abort: &AtomicBool,
) -> Result<Geometry, TopoError> {
    let t = Instant::now();
    let (edges, ids) = rayon::join(|| Edges::new(mesh), || position_classes(end));
    let ids = ids?;
    let limit = options
        .max_intersecting_pairs
        .unwrap_or_else(|| default_pair_limit(mesh.triangles.len()));
    let x = intersections_limited(mesh, end, &edges, &ids, limit, abort)?;
    Ok(Geometry {
        edges,
        ids,
        x,
        t_intersect: t.elapsed().as_secs_f64(),
    })
}

/// The static half of the pipeline at given end positions, shared by the
/// one-frame run, the accumulator's preview and its release.
pub(crate) struct Static {
    geometry: Geometry,
    pub(crate) corrected: Vec<bool>,
    /// Per curve: some triangle pair of it intersected at the start (the
    /// mesh's own positions); the motion did not make it.
    old_curve: Vec<bool>,
    solved: usize,
    unsolved: usize,
    t_correct: f64,
}

pub(crate) fn static_stage(
    mesh: &TriMesh,
    end: &[DVec3],
    raw: &[bool],
    options: &Options,
) -> Result<Static, TopoError> {
    correction_stage(
        geometry(mesh, end, options)?,
        mesh,
        end,
        raw,
        options.scheme,
    )
}

/// [`geometry_stage`] with nothing running beside it to stop.
pub(crate) fn geometry(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
) -> Result<Geometry, TopoError> {
    geometry_stage(mesh, end, options, &AtomicBool::new(false))
}

/// Per curve of `x` (intersections at the end of a motion from the
/// positions of `mesh`): whether some triangle pair of it intersected at
/// the start already. Such a curve is the surface's own, carried along by
/// the motion; the others the motion made.
pub(crate) fn old_curves(mesh: &TriMesh, x: &Intersections) -> Result<Vec<bool>, TopoError> {
    let mut old = vec![false; x.curve_count];
    if x.pairs.is_empty() {
        return Ok(old);
    }
    let was = pairs_intersect_at(mesh, &mesh.positions, &x.pairs)?;
    for (piece, &c) in x.pieces.iter().zip(&x.curve_of_piece) {
        let [a, b] = piece.tris;
        if let Ok(i) = x.pairs.binary_search(&(a.min(b), a.max(b))) {
            old[c as usize] |= was[i];
        }
    }
    Ok(old)
}

/// The mesh edges the curves that are not `old` cross, and the edges at
/// the vertices they pass through: [`Intersections::cut_edges`] without
/// the surface's own intersections.
fn new_cut_edges(x: &Intersections, edges: &Edges, ids: &[u32], old: &[bool]) -> Vec<bool> {
    if !old.contains(&true) {
        return x.cut_edges.clone();
    }
    let new_pieces = || {
        x.pieces
            .iter()
            .zip(&x.curve_of_piece)
            .filter(|&(_, &c)| !old[c as usize])
            .map(|(piece, _)| piece)
    };
    let mut cut = vec![false; edges.len()];
    for piece in new_pieces() {
        for node in piece.ends {
            if let Node::Point(i) = node
                && let PointKind::EdgeTri { edge, .. } = x.points[i as usize].kind
            {
                cut[edge as usize] = true;
            }
        }
    }
    cut_edges_at_shared(edges, ids, &shared_ids(new_pieces()), &mut cut);
    cut
}

/// Error correction (§3.4) of `raw` given the intersections. Only the
/// curves the motion made decouple the two sides of the mesh edges they
/// cross: an intersection the surface already had at the start (a scan's
/// overlapping patches, a character's armpit) is no evidence of what
/// collided, and letting it cut the graph let the sweep cut's penalty on
/// unused intersections (eq. 3.3) flip whole parts of a surface odd to
/// "use" curves that were there all along.
fn correction_stage(
    geometry: Geometry,
    mesh: &TriMesh,
    end: &[DVec3],
    raw: &[bool],
    scheme: Scheme,
) -> Result<Static, TopoError> {
    let t = Instant::now();
    let old_curve = old_curves(mesh, &geometry.x)?;
    let cut = new_cut_edges(&geometry.x, &geometry.edges, &geometry.ids, &old_curve);
    let w = Weights::new(mesh, end, &geometry.edges);
    let g = Graph {
        vertices: end.len(),
        ends: &geometry.edges.ends,
        edge_weight: &w.edge,
        vertex_weight: &w.vertex,
        cut: &cut,
        total_area: w.total_area,
    };
    let c = correct(&g, raw, scheme);
    Ok(Static {
        geometry,
        corrected: c.odd,
        old_curve,
        solved: c.solved_components,
        unsolved: c.failed_components,
        t_correct: t.elapsed().as_secs_f64(),
    })
}

/// Whether `mesh` at `start` has no self-intersection (Theorem 5.1's
/// premise), stopping at the first intersecting pair.
fn starts_clear(mesh: &TriMesh, start: &[DVec3]) -> bool {
    pair_count_at(mesh, start, 0) == Ok(0)
}

pub(crate) fn check(mesh: &TriMesh, end: &[DVec3]) -> Result<(), TopoError> {
    mesh.check()?;
    if end.len() != mesh.positions.len() {
        return Err(MeshError::VertexCountMismatch {
            expected: mesh.positions.len(),
            got: end.len(),
        }
        .into());
    }
    check_positions("end positions", end)?;
    Ok(())
}

/// Per curve of `x`: whether the frame made it, so that no vertex parity
/// has to say it should be cut ([`Deletion::OddTracked`]): the curves
/// that are not `old` and whose vertices all have one parity under `odd`
/// (the others are cut by §3.5's rule anyway).
fn new_curves(mesh: &TriMesh, x: &Intersections, odd: &[bool], old: &[bool]) -> Vec<bool> {
    mixed_curves(&mesh.triangles, x, odd)
        .iter()
        .zip(old)
        .map(|(&mixed, &old)| !mixed && !old)
        .collect()
}

/// How the points the cut samples (regions without a vertex, the sides
/// of a T-junction) move over the motion `start` → `end` that
/// [`finish`] resolves.
#[derive(Clone, Copy)]
pub(crate) enum Path<'a> {
    /// One frame: every point moves straight from `start` to `end`, so
    /// the samples follow the surface exactly.
    Frame,
    /// A drag whose keyframes were kept: the samples follow them exactly
    /// (`crate::drag_path`); the mesh is numbered as `Numbering` says.
    Drag(&'a DragPath, Numbering<'a>),
    /// A drag whose keyframes were not kept: the samples go straight from
    /// its first positions to its last, near enough for a region's
    /// parity, too coarse beside a curve (junctions then go by
    /// orientation alone).
    Straight,
}

impl<'a> Path<'a> {
    /// How samples follow a drag of `frames` frames whose keyframes are
    /// `path` (if kept), its mesh numbered as `numbering` says.
    pub(crate) fn of_drag(
        frames: u64,
        path: Option<&'a DragPath>,
        numbering: Numbering<'a>,
    ) -> Path<'a> {
        match path {
            _ if frames <= 1 => Path::Frame,
            Some(p) => Path::Drag(p, numbering),
            None => Path::Straight,
        }
    }
}

/// The rest of a frame once collisions and intersections are known:
/// correction, cut, the solid guard, orientation and the report.
/// `start` → `end` is the motion (for a drag its first and last
/// positions); `path` says how sampled points follow it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish(
    mesh: &TriMesh,
    start: &[DVec3],
    end: &[DVec3],
    raw: Vec<bool>,
    collisions: (usize, u64, f64),
    options: &Options,
    started: Instant,
    geometry: Geometry,
    path: Path<'_>,
) -> Result<Outcome, TopoError> {
    let s = correction_stage(geometry, mesh, end, &raw, options.scheme)?;
    let t = Instant::now();
    // With `nonmanifold_joins` a drag keeps the paper's behaviour, where
    // an open part pushed rim first into a body stays glued along the
    // curve with the occluded cap (Figure 9). The exact samples would say
    // otherwise there: a dome narrowing past the body sweeps a thin ring
    // beside the curve that no vertex sits in, and deleting it would cut
    // the part and the cap off the body. So such a drag, like one whose
    // keyframes were not kept, samples along its straight path and
    // leaves its T-junctions to orientation.
    let (keyframes, tracked) = match path {
        Path::Frame => (Keyframes::Straight(end), true),
        Path::Drag(recorded, numbering) if !options.nonmanifold_joins => {
            (Keyframes::Recorded(recorded, numbering), true)
        }
        Path::Drag(..) | Path::Straight => (Keyframes::Straight(end), false),
    };
    let sampler = PathSampler::new(&mesh.triangles, start, keyframes);
    let sample = |k: u32, t: u32, w: [f64; 3]| sampler.parity(k, t, w);
    // A drag's keyframes let the samples follow it exactly too, so the
    // curves it made between vertices are cut and their regions sampled
    // as one frame's are (`old_curve` is taken at the drag's start).
    let new_curve = if tracked && options.refine {
        new_curves(mesh, &s.geometry.x, &s.corrected, &s.old_curve)
    } else {
        Vec::new()
    };
    let Cut {
        mesh: mut out,
        report: mut cut_report,
        mut origin,
        ..
    } = cut(
        mesh,
        end,
        &s.geometry.edges,
        &s.geometry.ids,
        &s.geometry.x,
        if tracked {
            Deletion::OddTracked {
                odd: &s.corrected,
                new_curve: &new_curve,
                open_ends: !options.nonmanifold_joins,
            }
        } else {
            Deletion::Odd {
                odd: &s.corrected,
                open_ends: !options.nonmanifold_joins,
            }
        },
        if options.refine { Some(&sample) } else { None },
    );
    // The solid guard: a solid whose parity result is not a solid (open,
    // or crossed by a curve parity left unresolved, or parity changing
    // where no curve runs) was folded by the motion; Theorem 5.1 holds
    // again by labelling with the containment number (crate::solid).
    // Cheapest tests first: the input's closedness from the edge table
    // the intersections already built, then the cut's counts, then a
    // sort of the output's sides.
    let suspicious =
        || cut_report.curves_dropped > 0 || cut_report.false_vertices > 0 || !out.is_closed();
    let solid_input = s.geometry.edges.closed_oriented(&mesh.triangles);
    if options.solid_guard
        && solid_input
        && suspicious()
        && starts_clear(mesh, start)
        && let Some((relabelled, o, deleted)) = relabel(
            mesh,
            start,
            end,
            &s.geometry.edges,
            &s.geometry.ids,
            &s.geometry.x,
        )
        && relabelled.is_closed()
    {
        cut_report.triangles_deleted = deleted;
        cut_report.solid_relabelled = true;
        out = relabelled;
        origin = o;
    }
    // Kept regions can meet at a single point (where a folded surface
    // branched, or two deleted wedges of one vertex's fan): the surface is
    // pinched there. One vertex per fan makes it a 2-manifold; the
    // input's own pinches are left as they were (found only if the output
    // has a pinch: a pass over the input that most frames never pay for).
    cut_report.pinches_split = split_new_pinches(&mut out, &mut origin, mesh);
    let flips = if options.orient {
        orient_consistently(&mut out)
    } else {
        0
    };
    let t_cut = t.elapsed().as_secs_f64();
    let report = Report {
        collisions: collisions.0,
        collision_tests: collisions.1,
        containment_rays: 0,
        raw_odd_vertices: raw.iter().filter(|&&o| o).count(),
        corrected_odd_vertices: s.corrected.iter().filter(|&&o| o).count(),
        cut: cut_report,
        solved_components: s.solved,
        unsolved_components: s.unsolved,
        perturbation_retries: 0,
        output_intersecting_pairs: None,
        solid_input,
        orientation_flips: flips,
        timings: Timings {
            collisions: collisions.2,
            intersections: s.geometry.t_intersect,
            correction: s.t_correct,
            cut: t_cut,
            total: started.elapsed().as_secs_f64(),
        },
        ..Report::of_intersections(&s.geometry.x)
    };
    Ok(Outcome {
        mesh: out,
        report,
        raw_odd: raw,
        corrected_odd: s.corrected,
        intersections: s.geometry.x,
        vertex_origin: origin,
    })
}

/// Splits the vertices of `out` where kept regions touch at a single
/// point into one vertex per fan (see [`TriMesh::split_pinches_where`]),
/// except where `input`, the mesh `out` was made from (`origin`: per
/// output vertex its input vertex, or `u32::MAX`), was already pinched;
/// each copy's origin is its vertex's. Returns the number of copies.
pub(crate) fn split_new_pinches(
    out: &mut TriMesh,
    origin: &mut Vec<u32>,
    input: &TriMesh,
) -> usize {
    let mut pinched_before: Option<Vec<bool>> = None;
    let split = out.split_pinches_where(|v| match origin.get(v) {
        Some(&o) if o != u32::MAX => {
            let before = pinched_before.get_or_insert_with(|| input.pinched_vertices());
            !before.get(o as usize).copied().unwrap_or(false)
        }
        _ => true,
    });
    for &v in &split {
        origin.push(origin[v as usize]);
    }
    split.len()
}

pub(crate) fn ccd_options(options: &Options, frame: u64) -> CcdOptions {
    CcdOptions {
        narrow: if options.float_ccd {
            Narrow::Float
        } else {
            Narrow::Exact
        },
        identities: Identities::ByIndex,
        frame,
    }
}

/// Topology change for one frame: `mesh` at its positions moves linearly to
/// `end`. Collided parts that should vanish are cut out along the
/// intersection curves and the rest is glued there.
///
/// Degeneracies are resolved by simulation of simplicity. One kind can
/// still break a solid: faces of two parts landing exactly in one plane
/// and overlapping there (a grid moved onto the lattice of another). The
/// perturbed arrangement is consistent, but placed at the exact
/// coordinates its distinct points coincide, and the result can come out
/// with duplicate triangles or cracks; and parts landing exactly on each
/// other's lattice can cross only at shared points, so that no
/// intersection is found for what collided. So with the solid guard on,
/// when the input is a closed 2-manifold and the result is not (or its
/// odd vertices have no intersection to explain them), the frame is
/// run again with every end position moved by a deterministic
/// pseudo-random offset of up to 2^-20 of the scene's diagonal (16 and
/// 256 times that on the next tries; smaller offsets leave slivers so
/// thin that rounding the constructed points makes them cross; equal for
/// vertices that are one point
/// throughout the motion, so a soup's corners stay together). The report
/// counts the retries. A retry that fails (the offsets tangle slivers far
/// thinner than themselves into more intersections than a frame may
/// have) ends the retries, and the last result stands.
pub fn topology_change(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
) -> Result<Outcome, TopoError> {
    let out = topology_change_once(mesh, end, options)?;
    if !options.solid_guard || !out.report.solid_input || !suspect(&out) {
        return Ok(out);
    }
    // Offsets by point of the surface (same place at both ends), so that
    // the copies of a soup's corner move together while parts that only
    // land on each other move apart.
    let ids = motion_classes(&mesh.positions, end)?;
    let diagonal = {
        let (lo, hi) = end
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
                (l.min(*p), h.max(*p))
            });
        (hi - lo).length()
    };
    let mut last = out;
    for k in 1..=3usize {
        let size = diagonal * (16f64).powi(k as i32 - 1) / 1_048_576.0;
        let jittered: Vec<DVec3> = end
            .iter()
            .zip(&ids)
            .map(|(p, &id)| *p + jitter(id, k) * size)
            .collect();
        // A retry only ever replaces a result: where the offsets tangle
        // a crumpled region (slivers far thinner than the offset) into
        // more intersections than a frame may have, the first result
        // stands and the caller's audit judges it.
        let Ok(mut out) = topology_change_once(mesh, &jittered, options) else {
            break;
        };
        out.report.perturbation_retries = k;
        let good = !suspect(&out);
        last = out;
        if good {
            break;
        }
    }
    Ok(last)
}

/// Whether a solid's result shows the marks of exact coincidence: it is
/// not a closed 2-manifold (coplanar overlaps placed at exact
/// coordinates), or collisions made vertices odd that no intersection at
/// the end accounts for (parts landing exactly on each other's lattice,
/// where every crossing is a shared point, edge or plane), so that
/// correction evened them out and both parts were kept whole.
fn suspect(out: &Outcome) -> bool {
    let r = &out.report;
    let unexplained = r.intersecting_pairs == 0
        && r.raw_odd_vertices > 0
        && r.corrected_odd_vertices != r.raw_odd_vertices;
    unexplained || !out.mesh.is_closed_manifold()
}

/// A deterministic offset in [-1, 1]³ for identity `id` on try `k` (a
/// 64-bit mix of the two: no state, no seed to pass around).
fn jitter(id: u32, k: usize) -> DVec3 {
    let mut x = (u64::from(id) << 8 | k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let mut next = || {
        x ^= x >> 31;
        x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x ^= x >> 29;
        // 53 random bits to [-1, 1).
        (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    DVec3::new(next(), next(), next())
}

/// The collision parity (§3.2) of `mesh` moving to `end`, with the
/// seconds it took, and the static intersections at the end (§3.3), both
/// at once: collisions need the motion, intersections only the end, and
/// each is parallel inside but has sequential stretches. A frame with too
/// many intersections stops the collision half too; its error is the one
/// to report.
fn collisions_and_geometry(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
) -> (
    Result<(holey_geom::ccd::CcdReport, f64), holey_geom::GeomError>,
    Result<Geometry, TopoError>,
) {
    let abort = AtomicBool::new(false);
    rayon::join(
        || {
            let t = Instant::now();
            vertex_parities_cancellable(
                &mesh.positions,
                end,
                &mesh.triangles,
                &ccd_options(options, 0),
                &abort,
            )
            .map(|c| (c, t.elapsed().as_secs_f64()))
        },
        || geometry_stage(mesh, end, options, &abort),
    )
}

/// What [`freedom`] found out about a motion.
pub(crate) enum Freedom {
    /// No collision and no crossing at the end: the motion only moves.
    Free,
    /// It collides or crosses: the static intersections at the end, for
    /// a later stage that needs them on the same mesh, and the raw
    /// collision parity (§3.2) as the (vertex, triangle) pairs that
    /// collide an odd number of times, sorted.
    Changes {
        geometry: Box<Geometry>,
        odd_pairs: Vec<(u32, u32)>,
    },
    /// One of the two halves failed (too many pairs, say): the full run
    /// reports it.
    Unknown,
}

/// Whether `mesh` moving to `end` neither collides (no vertex with an
/// odd number of collisions, §3.2) nor crosses itself at the end (no
/// intersecting pair, §3.3): then the engine can only move it, and a
/// frame needs nothing more. When it does collide or cross, the end's
/// intersections are kept for the next stage; an error (too many pairs,
/// say) answers [`Freedom::Unknown`], leaving the full run to report it.
pub(crate) fn freedom(mesh: &TriMesh, end: &[DVec3], options: &Options) -> Freedom {
    match collisions_and_geometry(mesh, end, options) {
        (Ok((c, _)), Ok(g)) if g.x.pairs.is_empty() && !c.odd.contains(&true) => Freedom::Free,
        (Ok((c, _)), Ok(g)) => Freedom::Changes {
            geometry: Box::new(g),
            odd_pairs: c.odd_pairs,
        },
        _ => Freedom::Unknown,
    }
}

/// [`topology_change`] without the retry.
fn topology_change_once(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
) -> Result<Outcome, TopoError> {
    let started = Instant::now();
    check(mesh, end)?;
    let (ccd, geometry) = collisions_and_geometry(mesh, end, options);
    let geometry = geometry?;
    let (ccd, t_ccd) = ccd?;
    let collisions = (ccd.odd_pairs.len(), ccd.candidates, t_ccd);
    finish(
        mesh,
        &mesh.positions,
        end,
        ccd.odd,
        collisions,
        options,
        started,
        geometry,
        Path::Frame,
    )
}

/// The self-intersection curves of a mesh cut and glued, nothing deleted:
/// the arrangement of the surface (`holey resolve`).
pub fn resolve(mesh: &TriMesh) -> Result<(TriMesh, Intersections, CutReport), TopoError> {
    mesh.check()?;
    let edges = Edges::new(mesh);
    let ids = position_classes(&mesh.positions)?;
    let x = intersections(mesh, &mesh.positions, &edges, &ids)?;
    let Cut {
        mesh: out,
        mut report,
        origin,
        ..
    } = cut(
        mesh,
        &mesh.positions,
        &edges,
        &ids,
        &x,
        Deletion::Nothing,
        None,
    );
    let TriMesh {
        mut positions,
        triangles,
    } = out;
    let (triangles, welded) = crate::overlaps::weld_constructed(&positions, triangles, &origin)?;
    report.points_welded = welded;
    let (triangles, merged) = crate::overlaps::merge_overlaps(&mut positions, triangles);
    report.coplanar_groups_merged = merged.groups;
    report.coplanar_groups_left = merged.left;
    // The crossings of overlays that were not merged, and corners taken
    // as another at the same point, are left unused.
    let out = TriMesh {
        positions,
        triangles,
    }
    .compacted();
    Ok((out, x, report))
}

/// Whether any two triangles of `mesh` intersect (exact, identities by
/// position class, as [`self_intersections`] decides), stopping at the
/// first pair: which Boolean a pair of solids needs. The containment
/// union of Theorem 5.2 is right for solids that do not cross
/// themselves; one that does needs the winding-number arrangement
/// ([`crate::boolean_by_winding`]).
pub fn crosses_itself(mesh: &TriMesh) -> Result<bool, TopoError> {
    Ok(crate::intersect::crosses_itself_keeping_tree(mesh, None)?.0)
}

/// The self-intersections of a mesh (`holey selfint`).
pub fn self_intersections(mesh: &TriMesh) -> Result<Intersections, TopoError> {
    mesh.check()?;
    let edges = Edges::new(mesh);
    let ids = position_classes(&mesh.positions)?;
    Ok(intersections(mesh, &mesh.positions, &edges, &ids)?)
}
