//! Booleans by the winding number: union, intersection and difference of
//! closed surfaces that may cross themselves, overlap one another or
//! nest, on the arrangement of all their triangles.
//!
//! A point x is inside input X when its winding number w_X(x) ≥ ½; for a
//! closed surface whose triangles pair up along every edge in opposite
//! directions, w_X is an integer off the surface, so inside means
//! w_X ≥ 1. The result bounds the points the operation's rule keeps:
//! inside any input (union), inside all (intersection), inside the first
//! and no other (difference). One input's union is the solid its surface
//! encloses, with its self-intersections and inner shells removed.
//!
//! The construction (Zhou, Grinspun, Zorin & Jacobson, *Mesh Arrangements
//! for Solid Geometry*, 2016, gives the same semantics with exact cells):
//!
//! 1. All triangles of all inputs are intersected exactly, each with each
//!    (the inputs with each other and each with itself), and cut and
//!    glued along the curves (the cut stage, the paper's §3.3 with
//!    nothing deleted): the arrangement. Its vertices are welded where
//!    their rounded positions are equal.
//! 2. Its *regions* are the triangles joined across edges that exactly two
//!    triangles share in opposite directions; the curves (edges of four or
//!    more) bound them, so the winding numbers on each side of a region
//!    are constant along it. Not so where an input triangle meets another
//!    degenerately (a vertex of one exactly in the other's plane: coplanar
//!    overlaps, an edge lying in a face): the perturbed world's curves
//!    between them can run, in the limit, along arrangement edges that
//!    are no curve, and the cut glues points that coincide only in the
//!    limit; such a triangle's cells are regions of their own.
//! 3. Each region gets them from one ray, decided exactly with simulation
//!    of simplicity, from a point of its largest triangle: the point
//!    `Σ wᵢ xᵢ` of its source triangle `x` at the cell's centroid, taken
//!    in the perturbed world as a point of the perturbed `x` (every
//!    predicate is affine in it, so its sign is that of `Σ wᵢ P(xᵢ)`).
//!    The cut made its cells in that world, coplanar overlaps included,
//!    so the sample sees every other sheet on the side the cell does. The
//!    triangles the point lies on (its source, and the sources of
//!    identical coincident cells) are left out of the ray, which leaves
//!    along the coordinate axis closest to the normal, towards the front:
//!    the crossings count w on the front side, and the back side differs
//!    by the signed count of the left-out sheets (each sheet changes w by
//!    one across it, by its orientation).
//! 4. A region whose two sides differ in being inside is kept, facing from
//!    inside to outside. Identical coincident cells of one symbolic source
//!    triangle (duplicate triangles, faces two solids share) are one sheet
//!    whose sheets' orientations add: of opposite ones nothing or one is
//!    kept, of equal ones one. Identical cells of different sources are
//!    apart in the perturbed world and classified each on its own. A cell
//!    of no area (collinear corners) is never a sample.
//! 5. Where coplanar sheets meet along an edge, a constructed point can
//!    land on a kept triangle's side without being its vertex (a
//!    T-junction); the side is split there (`repair_t_junctions`, and
//!    `split_open_sides` where the points come in different orders on the
//!    sheets that meet along the line).
//! 6. Coplanar faces of opposite orientation that touch are apart in the
//!    perturbed world, and where the perturbation leaves a gap between
//!    them both are kept: a wall of no thickness. Such walls are looked
//!    for in every result (inputs can touch without crossing in the
//!    perturbed world: a box resting on another's face), found exactly
//!    and replaced by their overlay, in which the faces cancel where they
//!    overlap ([`crate::coplanar`]); each wall is merged only when that
//!    leaves the result no more open and no less manifold
//!    (`coplanar_walls_merged`).
//! 7. Where the solid touches itself along an edge or at a point (two
//!    cubes of a lattice meeting diagonally), the faces around the edge
//!    are paired across the solid's inside by their exact angle about it
//!    and the vertices split into their fans ([`crate::unzip`]): a
//!    2-manifold with the same points (`unzipped_edges`,
//!    `split_vertices`).
//!
//! The inputs' zero-area triangles are taken out first, the points kept
//! ([`crate::zero_area`]): under the perturbation they would be slivers
//! crossing their neighbours.
//!
//! **Open inputs.** The winding number of a surface with holes is not an
//! integer; it is the generalized winding number (Jacobson, Kavan &
//! Sorkine-Hornung 2013), the sum of solid angles, which stays near the
//! closed surface's away from the holes. An open input is classified by
//! it under the same rule, w ≥ ½, evaluated with the dipole tree of
//! [`WindingField`] (Barill et al. 2018); on the cell's own sheets it is
//! the rest of the input's plus or minus half a turn. The report says
//! which inputs were open; the result keeps the open input's boundary.
//!
//! **Rounding.** The arrangement is exact, its output rounded to f64.
//! Where sheets nearly coincide, the rounded result can cross itself;
//! [`boolean_by_winding_robust`] then snap-rounds it
//! ([`crate::snap_round`]: onto a grid a few hundred ulps fine, resolved
//! by the winding number, checked exactly) before it nudges any input.
//!
//! **Not yet.** A wall whose overlay fails or would open the result
//! (stacked coplanar sheets whose crossings round a few ulps apart; on
//! the OpenSCAD export 19 of its walls merge, and snap rounding does
//! not clean it) is kept. A constructed point within a few ulps of an
//! input vertex it should be (nearly coincident shells) is not snapped
//! to it, which can leave the result open there. The report counts both
//! (`unpaired_edges`, and the CLI checks the result for crossings).

use rustc_hash::FxHashMap as HashMap;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use glam::{DVec2, DVec3};
use holey_geom::ring::{Ring, V3, orient3};
use holey_geom::sos::{Poly, sos_sign};
use holey_geom::{Aabb, Bvh, SosSign, SymPoint, orient3d_sos, position_classes};
use rayon::prelude::*;

use crate::coplanar::{Keep, Overlay, overlay, overlays, position_index};
use crate::cut::{Cut, CutReport, Deletion, SourcePoint, cut};
use crate::engine::{Options, TopoError};
use crate::hidden::vertex_components;
use crate::intersect::{default_pair_limit, intersections_limited, intersections_of_clean_parts};
use crate::mesh::{Edges, MeshError, TriMesh, repeats_a_corner};
use crate::on_side::on_side_between;
use crate::snap_round::{SnapRounding, snap_round};
use crate::union::Operation;
use crate::union_find::UnionFind;
use crate::winding::WindingField;

/// Why [`boolean_by_winding`] cannot take its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WindingError {
    /// An input failed mesh validation, or the geometry kernel or the static
    /// intersections failed ([`TopoError`] says which).
    #[error(transparent)]
    Topo(#[from] TopoError),
    /// No input mesh was given.
    #[error("an operation needs at least one input mesh")]
    NoInput,
    /// A difference was asked of a single input.
    #[error("a difference needs at least two input meshes")]
    DifferenceNeedsTwo,
    /// A ray could not leave the scene (coordinates near the largest
    /// float).
    #[error("the coordinates are too large to cast a ray past the inputs")]
    TooLarge,
}

impl From<MeshError> for WindingError {
    fn from(e: MeshError) -> Self {
        WindingError::Topo(e.into())
    }
}

/// What [`boolean_by_winding`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WindingReport {
    /// Per input: whether it is closed (its winding number is then exact;
    /// an open input's is the generalized one).
    pub inputs_closed: Vec<bool>,
    /// Zero-area triangles the inputs lost before the arrangement
    /// ([`crate::zero_area`]: the same points, the same solids).
    pub zero_area_removed: usize,
    /// Triangle pairs (of any inputs, or of one) that intersect.
    pub intersecting_pairs: usize,
    /// Intersection points among all the inputs' triangles: edge × triangle
    /// crossings and triple points.
    pub intersection_points: usize,
    /// Of those, the triple points, where three triangles meet.
    pub triple_points: usize,
    /// Intersection curves: connected components of the curve pieces.
    pub intersection_curves: usize,
    /// Triangles of the arrangement, and its regions (cells of the
    /// surface between curves).
    pub arrangement_triangles: usize,
    /// Regions of the arrangement; each group of coincident cells counts as
    /// one.
    pub regions: usize,
    /// Groups of identical coincident cells, treated as one sheet.
    pub coincident_groups: usize,
    /// Rays cast (one per region and group, more where a sample point lay
    /// on a coplanar triangle).
    pub rays: usize,
    /// Vertices of the arrangement merged because their rounded positions
    /// were equal.
    pub welded_points: usize,
    /// Regions no sample point could classify (slivers of no area), given
    /// the fate that leaves the result closed (`close_unsampled`).
    pub unsampled_regions: usize,
    /// Sides of result triangles split where a vertex of the other side
    /// lies on them (`repair_t_junctions`).
    pub t_junctions_repaired: usize,
    /// Walls of no thickness merged: groups of coplanar kept faces facing
    /// opposite ways, replaced by their overlay (`crate::coplanar`).
    pub coplanar_walls_merged: usize,
    /// Directed edges of the result without a partner running the other
    /// way: 0 for a closed, consistently oriented result.
    pub unpaired_edges: usize,
    /// Edges of the result on more than two triangles, and vertices whose
    /// triangles form more than one fan: 0 for a 2-manifold result. (Both
    /// appear where coplanar faces of opposite orientation overlap and are
    /// kept as a wall of no thickness that the coplanar overlay could not
    /// merge.)
    pub nonmanifold_edges: usize,
    /// See [`WindingReport::nonmanifold_edges`].
    pub pinched_vertices: usize,
    /// Edges of more than two kept faces where the solid touches itself
    /// (two parts meeting along the edge), whose faces were paired by
    /// their angle about it so that the result is a 2-manifold there
    /// (`crate::unzip`).
    pub unzipped_edges: usize,
    /// Vertices added where the solid touches itself at a point or along
    /// an unzipped edge: one copy, at the same position, per fan after
    /// the first.
    pub split_vertices: usize,
    /// Pairs of the result's triangles that cross, when they were counted
    /// ([`boolean_by_winding_robust`] does).
    pub output_intersecting_pairs: Option<usize>,
    /// How many nudges of the inputs after the first the result took
    /// ([`boolean_by_winding_robust`]).
    pub perturbation_retries: usize,
    /// Where the exact result was not clean (rounded points crossing,
    /// walls left, a few edges left open by rounding) and snap rounding
    /// made it so: the grid its points were snapped to, how many moved,
    /// the grids and rounds it took ([`crate::snap_round`]); `None` when
    /// it was not snapped.
    pub snap_rounding: Option<SnapRounding>,
    /// What cutting and gluing along every curve did (resolve mode: nothing
    /// deleted).
    pub cut: CutReport,
    /// Wall-clock seconds per stage.
    pub seconds: WindingTimings,
}

impl WindingReport {
    /// Unpaired edges, non-manifold edges and pinched vertices of the
    /// result: 0 for a closed 2-manifold.
    pub(crate) fn shape_defects(&self) -> usize {
        self.unpaired_edges + self.nonmanifold_edges + self.pinched_vertices
    }
}

/// Seconds spent in each stage.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WindingTimings {
    /// From the start of the call through the static intersections (joining the
    /// inputs included).
    pub intersections: f64,
    /// Cutting and gluing the arrangement, and welding its equal points.
    pub cut: f64,
    /// Casting the rays that classify the regions, choosing the kept triangles
    /// and repairing T-junctions.
    pub classify: f64,
    /// The whole call (for [`boolean_by_winding_robust`]: every attempt and
    /// check).
    pub total: f64,
}

/// The result of [`boolean_by_winding`].
#[derive(Clone, Debug)]
pub struct WindingOutcome {
    /// The resulting surface, holding only the vertices its triangles use.
    pub mesh: TriMesh,
    /// What the operation did.
    pub report: WindingReport,
}

impl Operation {
    /// Whether a point inside exactly the inputs flagged in `inside` is in
    /// the result: any (union), all (intersection), the first and no
    /// other (difference).
    pub fn contains(self, inside: &[bool]) -> bool {
        match self {
            Operation::Union => inside.iter().any(|&i| i),
            Operation::Intersection => !inside.is_empty() && inside.iter().all(|&i| i),
            Operation::Difference => inside.first() == Some(&true) && !inside[1..].contains(&true),
        }
    }
}

/// The operation `op` on the solids `inputs` bound, by the winding-number
/// rule (see the module docs): `Union` of one or more inputs,
/// `Intersection` of one or more, `Difference` of the first minus all the
/// others. An input may cross itself, hold several shells, overlap the
/// others, or face inward (an inward shell has winding number −1 inside:
/// a cavity in what holds it). A closed input (its triangles pair up
/// along every edge in opposite directions, vertices at equal positions
/// counting as one) is classified exactly, an open one by its
/// generalized winding number.
pub fn boolean_by_winding(
    inputs: &[&TriMesh],
    op: Operation,
    options: &Options,
) -> Result<WindingOutcome, WindingError> {
    arranged(inputs, op, options, true, false)
}

/// [`boolean_by_winding`] as a first try, for a caller that keeps only a
/// clean result: where merging every wall at once leaves the result more
/// open or less manifold, the walls are not tried one at a time (a pass
/// over the whole result per wall: a minute on a snapped sponge and its
/// copy a cell away, which came out unclean anyway).
///
/// `clean_solids`: the caller has checked that each of the two inputs,
/// with its zero-area triangles repaired ([`crate::union::solid`]),
/// crosses itself nowhere ([`crate::intersect::crosses_itself_keeping_tree`]):
/// then only the pairs across them, and the few of the second whose
/// decision the joined identities can change, are tested
/// ([`crate::intersect::intersections_of_clean_parts`]).
pub(crate) fn boolean_by_winding_first_try(
    inputs: &[&TriMesh],
    op: Operation,
    options: &Options,
    clean_solids: bool,
) -> Result<WindingOutcome, WindingError> {
    arranged(inputs, op, options, false, clean_solids)
}

/// [`boolean_by_winding`]; the walls are merged one at a time where all
/// at once is worse only with `walls_one_by_one`; `clean_solids` as
/// [`boolean_by_winding_first_try`] says.
fn arranged(
    inputs: &[&TriMesh],
    op: Operation,
    options: &Options,
    walls_one_by_one: bool,
    clean_solids: bool,
) -> Result<WindingOutcome, WindingError> {
    let started = Instant::now();
    if inputs.is_empty() {
        return Err(WindingError::NoInput);
    }
    if op == Operation::Difference && inputs.len() < 2 {
        return Err(WindingError::DifferenceNeedsTwo);
    }
    for m in inputs {
        m.check()?;
    }
    // Zero-area triangles repaired first, the points kept: the symbolic
    // perturbation would make slivers of them that cross their
    // neighbours, each a region of its own ([`crate::zero_area`]).
    let repaired: Vec<(std::borrow::Cow<'_, TriMesh>, usize)> =
        inputs.iter().map(|m| crate::union::solid(m)).collect();
    let inputs: Vec<&TriMesh> = repaired.iter().map(|(m, _)| m.as_ref()).collect();
    let inputs = &inputs[..];
    let (joined, owner) = join(inputs)?;
    let ids = position_classes(&joined.positions).map_err(TopoError::from)?;
    let mut report = WindingReport {
        inputs_closed: closed_inputs(&joined.triangles, &ids, &owner, inputs.len()),
        zero_area_removed: repaired.iter().map(|(_, n)| n).sum(),
        ..WindingReport::default()
    };

    let edges = Edges::new(&joined);
    let limit = options
        .max_intersecting_pairs
        .unwrap_or_else(|| default_pair_limit(joined.triangles.len()));
    let x = match inputs {
        [first, _] if clean_solids => intersections_of_clean_parts(
            &joined,
            &joined.positions,
            &edges,
            &ids,
            (first.triangles.len() as u32, first.positions.len() as u32),
            limit,
            &AtomicBool::new(false),
        ),
        _ => intersections_limited(
            &joined,
            &joined.positions,
            &edges,
            &ids,
            limit,
            &AtomicBool::new(false),
        ),
    }
    .map_err(TopoError::from)?;
    report.intersecting_pairs = x.pairs.len();
    report.intersection_points = x.points.len();
    report.triple_points = x.triple_points();
    report.intersection_curves = x.curve_count;
    let degenerate = degenerate_contacts(&joined, &ids, &x.pairs);
    report.seconds.intersections = started.elapsed().as_secs_f64();

    let t = Instant::now();
    let Cut {
        mesh: arrangement,
        report: cut_report,
        source,
        origin,
    } = cut(
        &joined,
        &joined.positions,
        &edges,
        &ids,
        &x,
        Deletion::Nothing,
        None,
    );
    report.cut = cut_report;
    let (arrangement, source, welded) = weld(arrangement, source, &origin)?;
    report.welded_points = welded;
    report.arrangement_triangles = arrangement.triangles.len();
    report.seconds.cut = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let corner: Vec<Corner<'_>> = inputs
        .iter()
        .map(|m| {
            let p = &m.positions;
            Box::new(move |v: u32| p[v as usize]) as Corner<'_>
        })
        .collect();
    let rays = Rays::new(
        &joined,
        &ids,
        &owner,
        inputs,
        &report.inputs_closed,
        &corner,
    )?;
    let mut faces = classify(&arrangement, &source, &degenerate, &rays, op, &mut report)?;
    cancel_opposite_twins(&mut faces);
    let mut positions = arrangement.positions;
    let faces = close_up(&mut positions, faces, walls_one_by_one, &mut report);
    let mut faces = faces;
    let unzipped = crate::unzip::unzip(&mut positions, &mut faces);
    report.unzipped_edges = unzipped.edges;
    report.split_vertices = unzipped.vertices;
    report.unpaired_edges = unpaired_edges(&faces).len();
    report.seconds.classify = t.elapsed().as_secs_f64();
    let mesh = TriMesh {
        positions,
        triangles: faces,
    }
    .compacted();
    report.nonmanifold_edges = nonmanifold_edges(&mesh.triangles);
    report.pinched_vertices = mesh.pinched_vertices().iter().filter(|&&p| p).count();
    report.seconds.total = started.elapsed().as_secs_f64();
    Ok(WindingOutcome { mesh, report })
}

/// The kept faces closed up: T-junctions repaired and walls of no
/// thickness (coplanar kept faces facing opposite ways that overlap,
/// wherever the inputs touch) merged by the coplanar overlay
/// ([`crate::coplanar`]) when that leaves the result no more open and no
/// less manifold than without: every wall at once (one repair pass over
/// the result, the common case), and when that is worse, one wall at a
/// time, each kept only if it is no worse than the result before it.
fn close_up(
    positions: &mut Vec<DVec3>,
    faces: Vec<[u32; 3]>,
    one_by_one: bool,
    report: &mut WindingReport,
) -> Vec<[u32; 3]> {
    let repaired = |positions: &[DVec3], mut faces: Vec<[u32; 3]>| {
        let n = repair_t_junctions(positions, &mut faces) + split_open_sides(positions, &mut faces);
        (faces, n)
    };
    // Walls are coplanar faces of opposite orientation that overlap.
    // They are looked for in every result: inputs that touch without
    // crossing in the perturbed world (a box resting on another's face,
    // lattice faces of two solids triangulated differently) leave them
    // as well as inputs that meet degenerately, and a wall can be whole
    // shells' faces with no defect of edges or vertices to show for it.
    let groups = crate::coplanar::wall_groups(positions, &faces);
    if groups.is_empty() {
        let (faces, n) = repaired(positions, faces);
        report.t_junctions_repaired = n;
        return faces;
    }
    let (mut best, mut n) = repaired(positions, faces.clone());
    let defects = |f: &[[u32; 3]]| (unpaired_edges(f).len(), nonmanifold_edges(f));
    let no_worse = |d: (usize, usize), than: (usize, usize)| d.0 <= than.0 && d.1 <= than.1;
    let mut least = defects(&best);
    let existing = position_index(positions);
    // The faces but those `gone` flags, with `added` after them.
    let with = |gone: &[bool], added: &[[u32; 3]]| -> Vec<[u32; 3]> {
        faces
            .iter()
            .zip(gone)
            .filter(|(_, g)| !**g)
            .map(|(f, _)| *f)
            .chain(added.iter().copied())
            .collect()
    };
    let first_new = positions.len();
    let mut gone = vec![false; faces.len()];
    let mut added: Vec<[u32; 3]> = Vec::new();
    let mut made = 0;
    let made_all = overlays(positions, &faces, &groups, &existing, Keep::Count);
    for (group, o) in groups.iter().zip(made_all) {
        if let Some(o) = o {
            group.iter().for_each(|&i| gone[i] = true);
            added.extend(o.cells);
            made += 1;
        }
    }
    if made > 0 {
        let (merged, m) = repaired(positions, with(&gone, &added));
        if no_worse(defects(&merged), least) {
            report.coplanar_walls_merged = made;
            report.t_junctions_repaired = m;
            return merged;
        }
    }
    positions.truncate(first_new);
    if !one_by_one {
        report.t_junctions_repaired = n;
        return best;
    }
    gone.fill(false);
    added.clear();
    for group in &groups {
        let mark = positions.len();
        let Some(Overlay { cells, .. }) = overlay(positions, &faces, group, &existing, Keep::Count)
        else {
            continue;
        };
        let mut trial = gone.clone();
        group.iter().for_each(|&i| trial[i] = true);
        let mut trial_added = added.clone();
        trial_added.extend(cells);
        let (merged, m) = repaired(positions, with(&trial, &trial_added));
        let d = defects(&merged);
        if no_worse(d, least) {
            (gone, added) = (trial, trial_added);
            (best, n, least) = (merged, m, d);
            report.coplanar_walls_merged += 1;
        } else {
            positions.truncate(mark);
        }
    }
    report.t_junctions_repaired = n;
    best
}

/// The undirected edges of `faces` that more than two faces share.
fn nonmanifold_edges(faces: &[[u32; 3]]) -> usize {
    let edges = Edges::of_triangles(faces);
    (0..edges.len())
        .filter(|&e| edges.triangles(e).len() > 2)
        .count()
}

/// [`boolean_by_winding`], robust to coplanar contact between inputs and
/// to rounding. Where faces of different inputs lie in one plane, the
/// perturbed arrangement is embedded at the unperturbed coordinates and
/// can come out open, or with coincident walls that cross in the limit;
/// where sheets nearly coincide, its rounded points can cross. So when
/// every input is closed and the result is not a 2-manifold (an edge on
/// more than two triangles, a pinched vertex) or crosses itself (checked
/// exactly: one self-intersection pass over the result), it is first
/// snap-rounded ([`crate::snap_round`]; kept if that makes it clean, the
/// report's `snap_rounding` saying how; a result that rounding left open
/// by a few edges is snapped too). Else every connected piece of every
/// input but the first piece of the first is moved its own generic way
/// by the next step of
/// [`crate::union::NUDGES`] (scale-relative: 2⁻³⁰ of the scene's
/// diagonal first, then 2⁻²⁶ and 2⁻²²) and the operation redone, up to
/// three times, until two nudges in a row do not lessen the defects
/// (open edges, non-manifold edges and vertices, and crossing pairs). The first clean result is returned, else the
/// exact one (a nudge moves the answer by its size: worth it only for a
/// clean result); the report says how many nudges it took and how many pairs of
/// its triangles cross.
pub fn boolean_by_winding_robust(
    inputs: &[&TriMesh],
    op: Operation,
    options: &Options,
) -> Result<WindingOutcome, WindingError> {
    let started = Instant::now();
    let mut best: Option<(usize, WindingOutcome)> = None;
    let mut previous: Option<usize> = None;
    let mut stalled = 0;
    let parts: Vec<Vec<u32>> = inputs.iter().map(|m| vertex_components(m)).collect();
    let (lo, hi) = inputs
        .iter()
        .flat_map(|m| m.positions.iter())
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    let diagonal = if lo.x <= hi.x {
        (hi - lo).length()
    } else {
        0.0
    };
    for (k, &(scale, _)) in crate::union::NUDGES.iter().enumerate() {
        // Every connected piece of every input but the very first moves
        // its own generic way, by the same scale-relative step: coplanar
        // contact between inputs and between the shells of one input is
        // broken alike.
        let mut piece = 0usize;
        let moved: Vec<TriMesh> = inputs
            .iter()
            .zip(&parts)
            .map(|(m, part)| {
                let count = part.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
                let steps: Vec<DVec3> = (0..count)
                    .map(|c| generic_direction(piece + c) * (scale * diagonal))
                    .collect();
                piece += count;
                TriMesh {
                    positions: m
                        .positions
                        .iter()
                        .zip(part)
                        .map(|(p, &c)| *p + steps[c as usize])
                        .collect(),
                    triangles: m.triangles.clone(),
                }
            })
            .collect();
        let refs: Vec<&TriMesh> = moved.iter().collect();
        let mut out = boolean_by_winding(&refs, op, options)?;
        let crossing = crate::engine::self_intersections(&out.mesh)?.pairs.len();
        out.report.output_intersecting_pairs = Some(crossing);
        out.report.perturbation_retries = k;
        let closed = out.report.inputs_closed.iter().all(|&c| c);
        let defects = out.report.shape_defects() + crossing;
        // The exact result, unclean: snapped to a grid a few hundred ulps
        // fine first, which moves it far less than the smallest nudge
        // (`snap_rounded` declines the results of open inputs).
        if k == 0
            && defects > 0
            && let Some(snapped) = snap_rounded(&out, options)?
        {
            best = Some((0, snapped));
            break;
        }
        // The exact attempt, unless a nudged one is clean: a nudge moves
        // the answer by its size, worth it only for a clean result.
        if best.is_none() || defects == 0 {
            best = Some((defects, out));
        }
        // Two nudges in a row that do not lessen the defects are futile:
        // the defects do not come from where the pieces sit against each
        // other (coplanar faces within one piece, say), and larger nudges
        // move the same pieces the same ways further. One is not enough:
        // the smallest nudge can turn a wall between two pieces into an
        // overlap so thin that its rounded points cross, which the next,
        // 16 times larger, clears.
        if previous.is_some_and(|p| defects >= p) {
            stalled += 1;
        } else {
            stalled = 0;
        }
        if defects == 0 || !closed || stalled == 2 {
            break;
        }
        previous = Some(defects);
    }
    let mut out = best.map(|(_, out)| out).ok_or(WindingError::NoInput)?;
    // Every attempt and check counts.
    out.report.seconds.total = started.elapsed().as_secs_f64();
    Ok(out)
}

/// `exact`, the result of [`boolean_by_winding`], snap-rounded
/// ([`crate::snap_round`]) until it is a closed 2-manifold that crosses
/// itself nowhere (checked exactly), each snapped surface resolved by
/// its own winding number (its union with nothing). Its report is
/// `exact`'s, with the clean shape, no crossing and
/// [`WindingReport::snap_rounding`]. `None` when an input was open (the
/// result's winding number is fractional by design), the result is
/// empty, or no grid gives a clean result.
///
/// A result of closed inputs left open by rounding (a few edges unpaired
/// where a constructed point missed the vertex it should be) is snapped
/// too: its generalized winding number is an integer but within reach of
/// those slits, which are a rounding wide, and only a closed result of
/// the snap is kept.
pub(crate) fn snap_rounded(
    exact: &WindingOutcome,
    options: &Options,
) -> Result<Option<WindingOutcome>, WindingError> {
    if !exact.report.inputs_closed.iter().all(|&c| c) || exact.mesh.triangles.is_empty() {
        return Ok(None);
    }
    let defects = exact.report.shape_defects()
        + exact
            .report
            .output_intersecting_pairs
            .unwrap_or(usize::MAX / 2);
    let resolve = |snapped: &TriMesh, before: usize| {
        let resolved = boolean_by_winding(&[snapped], Operation::Union, options)?;
        let shape = resolved.report.shape_defects();
        if shape >= before {
            return Ok((resolved.mesh, shape));
        }
        // Counted only up to where the round would be no better.
        let limit = before - shape - 1;
        let crossing = match crate::intersect::intersecting_pair_count(&resolved.mesh, limit) {
            Ok(n) => n,
            Err(crate::intersect::IntersectError::TooManyPairs { .. }) => limit + 1,
            Err(e) => return Err(WindingError::from(TopoError::from(e))),
        };
        Ok((resolved.mesh, shape + crossing))
    };
    let Some((mesh, how)) = snap_round(&exact.mesh, defects, resolve)? else {
        return Ok(None);
    };
    let mut report = exact.report.clone();
    report.unpaired_edges = 0;
    report.nonmanifold_edges = 0;
    report.pinched_vertices = 0;
    report.output_intersecting_pairs = Some(0);
    report.snap_rounding = Some(how);
    Ok(Some(WindingOutcome { mesh, report }))
}

/// A unit direction for piece `j`, none for piece 0: points of a
/// low-discrepancy sequence on the sphere (golden-ratio steps in azimuth
/// and height), along no axis or lattice diagonal.
fn generic_direction(j: usize) -> DVec3 {
    if j == 0 {
        return DVec3::ZERO;
    }
    let u = (0.5 + j as f64 * 0.618_033_988_749_895).fract();
    let v = (0.5 + j as f64 * 0.754_877_666_246_693).fract();
    let theta = std::f64::consts::TAU * u;
    let z = 2.0 * v - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(r * theta.cos(), r * theta.sin(), z)
}

/// All inputs (each checked already) in one mesh, and the input of each
/// triangle.
fn join(inputs: &[&TriMesh]) -> Result<(TriMesh, Vec<u32>), WindingError> {
    let mut joined = TriMesh::default();
    let mut owner = Vec::new();
    for (i, m) in inputs.iter().enumerate() {
        let base = joined.positions.len();
        let total = base + m.positions.len();
        if total >= u32::MAX as usize - 2 {
            return Err(MeshError::TooLarge(total).into());
        }
        joined.positions.extend_from_slice(&m.positions);
        joined
            .triangles
            .extend(m.triangles.iter().map(|t| t.map(|v| v + base as u32)));
        owner.extend(std::iter::repeat_n(i as u32, m.triangles.len()));
    }
    Ok((joined, owner))
}

/// Which inputs are closed: along each edge (vertices at one position
/// counting as one) as many of its triangles run one way as the other, so
/// that its winding number is an integer off the surface.
fn closed_inputs(triangles: &[[u32; 3]], ids: &[u32], owner: &[u32], inputs: usize) -> Vec<bool> {
    let mut balance: HashMap<(u32, u32, u32), i32> =
        HashMap::with_capacity_and_hasher(triangles.len() * 2, Default::default());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (ids[tri[k] as usize], ids[tri[(k + 1) % 3] as usize]);
            if a == b {
                continue;
            }
            let key = (owner[t], a.min(b), a.max(b));
            *balance.entry(key).or_insert(0) += if a < b { 1 } else { -1 };
        }
    }
    let mut closed = vec![true; inputs];
    for ((input, _, _), b) in balance {
        if b != 0 {
            closed[input as usize] = false;
        }
    }
    closed
}

/// The arrangement with vertices at equal positions merged (two
/// constructed points can round to one place, and the inputs' coincident
/// vertices are still apart), and each constructed point near an input
/// vertex snapped onto it ([`crate::on_side::welded_classes`]; `origin[v]`
/// is the input vertex an arrangement vertex is, or `u32::MAX`): nearly
/// coincident shells put curves through points a rounding away from
/// their vertices, which would otherwise leave the result open there.
/// Triangles that collapse are dropped with their sources. Returns how
/// many vertices merged.
fn weld(
    mesh: TriMesh,
    source: Vec<Source>,
    origin: &[u32],
) -> Result<(TriMesh, Vec<Source>, usize), WindingError> {
    let class = crate::on_side::welded_classes(&mesh.positions, origin).map_err(TopoError::from)?;
    let merged = class
        .iter()
        .enumerate()
        .filter(|&(v, &c)| c as usize != v)
        .count();
    let (triangles, source): (Vec<[u32; 3]>, Vec<Source>) = mesh
        .triangles
        .iter()
        .zip(source)
        .map(|(t, s)| (t.map(|v| class[v as usize]), s))
        .filter(|(t, _)| !repeats_a_corner(t))
        .unzip();
    Ok((
        TriMesh {
            positions: mesh.positions,
            triangles,
        },
        source,
        merged,
    ))
}

/// The directed edges of `faces` that no face runs the other way (with
/// multiplicity: an edge run twice one way and once the other is one).
fn unpaired_edges(faces: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut net: HashMap<(u32, u32), i32> =
        HashMap::with_capacity_and_hasher(faces.len() * 2, Default::default());
    for f in faces {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *net.entry((a.min(b), a.max(b))).or_insert(0) += if a < b { 1 } else { -1 };
        }
    }
    let mut out = Vec::new();
    for ((a, b), n) in net {
        let (from, to) = if n > 0 { (a, b) } else { (b, a) };
        out.extend(std::iter::repeat_n((from, to), n.unsigned_abs() as usize));
    }
    out.sort_unstable();
    out
}

/// Longest chain of vertices one side of a T-junction is searched for.
const T_JUNCTION_CHAIN: usize = 8;

/// Passes of [`repair_t_junctions`] (a side split once can hold another
/// junction; more passes than this mean a chain that is no junction).
const T_JUNCTION_PASSES: usize = 8;

/// Closes T-junctions: where the side `u → v` of a result triangle has no
/// partner and the other side runs `v → w₁ → … → wₖ → u` through vertices
/// between `u` and `v` (each a constructed point the perturbation put on
/// the other sheet, rounded onto the side's line: coplanar sheets meeting
/// along an edge), the triangle is split at `wₖ, …, w₁` so that both
/// sides have the same vertices. Returns how many sides were split.
fn repair_t_junctions(positions: &[DVec3], faces: &mut Vec<[u32; 3]>) -> usize {
    let mut repaired = 0;
    for _ in 0..T_JUNCTION_PASSES {
        let open = unpaired_edges(faces);
        if open.is_empty() {
            return repaired;
        }
        let mut from: HashMap<u32, Vec<u32>> = HashMap::default();
        for &(a, b) in &open {
            from.entry(a).or_default().push(b);
        }
        // On the side up to rounding: within a relative 2⁻³⁰ of its length
        // from its line (a constructed point rounded onto it; a hole's
        // corner is nowhere near).
        let between = |u: u32, v: u32, w: u32| on_side_between(positions, u, v, w);
        // The chain v → … → u of unpaired sides through points between u
        // and v, ordered from v towards u.
        let chain = |u: u32, v: u32| -> Option<Vec<u32>> {
            let mut path = vec![v];
            let mut at = v;
            for _ in 0..T_JUNCTION_CHAIN {
                let next = from.get(&at)?;
                if next.contains(&u) && path.len() > 1 {
                    return Some(path[1..].to_vec());
                }
                let w = *next
                    .iter()
                    .filter(|&&w| w != u && between(u, v, w) && !path.contains(&w))
                    .min_by(|&&a, &&b| {
                        let d = |w: u32| (positions[w as usize] - positions[at as usize]).length();
                        d(a).total_cmp(&d(b))
                    })?;
                path.push(w);
                at = w;
            }
            None
        };
        let open_set: rustc_hash::FxHashSet<(u32, u32)> = open.iter().copied().collect();
        let mut split_any = false;
        let mut done: rustc_hash::FxHashSet<(u32, u32)> = Default::default();
        let mut out = Vec::with_capacity(faces.len());
        for &f in faces.iter() {
            let side = (0..3).find_map(|k| {
                let (u, v) = (f[k], f[(k + 1) % 3]);
                if !open_set.contains(&(u, v)) || done.contains(&(u, v)) {
                    return None;
                }
                // A chain through the third corner would fold the split.
                chain(u, v)
                    .filter(|c| !c.contains(&f[(k + 2) % 3]))
                    .map(|c| (k, c))
            });
            let Some((k, c)) = side else {
                out.push(f);
                continue;
            };
            let (u, v, x) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            done.insert((u, v));
            // Along u → v the points come in the reverse of the chain.
            let mut along = vec![u];
            along.extend(c.iter().rev());
            along.push(v);
            out.extend(along.windows(2).map(|w| [w[0], w[1], x]));
            repaired += 1;
            split_any = true;
        }
        *faces = out;
        if !split_any {
            return repaired;
        }
    }
    repaired
}

/// Removes kept triangles in pairs where one is the other turned over
/// (the same three vertices in the opposite order): cells of different
/// source triangles that the perturbed world keeps apart, facing away
/// from each other, but that coincide in the limit, a wall of no
/// thickness with the same side on both faces. They bound no volume, and
/// each pair's sides pair up among themselves, so the result stays as
/// closed as it was.
fn cancel_opposite_twins(faces: &mut Vec<[u32; 3]>) {
    // Each triangle in its rotation starting at its smallest vertex.
    let canonical = |f: [u32; 3]| {
        let k = (0..3).min_by_key(|&k| f[k]).unwrap_or(0);
        [f[k], f[(k + 1) % 3], f[(k + 2) % 3]]
    };
    let mut count: HashMap<[u32; 3], usize> = HashMap::default();
    for &f in faces.iter() {
        *count.entry(canonical(f)).or_insert(0) += 1;
    }
    let mut cancel: HashMap<[u32; 3], usize> = HashMap::default();
    for (&f, &n) in &count {
        let turned = canonical([f[0], f[2], f[1]]);
        if let Some(&m) = count.get(&turned) {
            cancel.insert(f, n.min(m));
        }
    }
    if cancel.is_empty() {
        return;
    }
    faces.retain(|&f| match cancel.get_mut(&canonical(f)) {
        Some(n) if *n > 0 => {
            *n -= 1;
            false
        }
        _ => true,
    });
}

/// Closes what [`repair_t_junctions`] leaves where a curve runs along a
/// line in the limit and its constructed points, rounded onto it, come in
/// different orders on the sheets that meet there (the unpaired sides
/// zigzag along the line instead of forming one chain): every unpaired
/// side of a result triangle is split at the ends of unpaired sides that
/// lie on it, so that both sheets' sides run through the same points and
/// pair up. A pass that leaves more sides unpaired than it found is
/// undone. Returns how many sides were split.
fn split_open_sides(positions: &[DVec3], faces: &mut Vec<[u32; 3]>) -> usize {
    let mut repaired = 0;
    for _ in 0..T_JUNCTION_PASSES {
        let open = unpaired_edges(faces);
        if open.is_empty() {
            break;
        }
        let mut loose: Vec<u32> = open.iter().flat_map(|&(a, b)| [a, b]).collect();
        loose.sort_unstable();
        loose.dedup();
        let open_set: rustc_hash::FxHashSet<(u32, u32)> = open.iter().copied().collect();
        let mut out = Vec::with_capacity(faces.len());
        let mut split = 0;
        for &f in faces.iter() {
            let side = (0..3).find_map(|k| {
                let (u, v, x) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
                if !open_set.contains(&(u, v)) {
                    return None;
                }
                let mut on: Vec<u32> = loose
                    .iter()
                    .copied()
                    .filter(|&w| w != u && w != v && w != x && on_side_between(positions, u, v, w))
                    .collect();
                (!on.is_empty()).then(|| {
                    let pu = positions[u as usize];
                    on.sort_by(|&a, &b| {
                        let d = |w: u32| (positions[w as usize] - pu).length_squared();
                        d(a).total_cmp(&d(b))
                    });
                    (k, on)
                })
            });
            let Some((k, on)) = side else {
                out.push(f);
                continue;
            };
            let (u, v, x) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            let mut along = vec![u];
            along.extend(on);
            along.push(v);
            out.extend(along.windows(2).map(|w| [w[0], w[1], x]));
            split += 1;
        }
        if split == 0 || unpaired_edges(&out).len() > open.len() {
            break;
        }
        *faces = out;
        repaired += split;
    }
    repaired
}

/// An arrangement triangle's input triangle and its centroid in that
/// triangle's chart (see [`Cut::source`]).
type Source = SourcePoint;

/// The position of an input's vertex.
type Corner<'a> = Box<dyn Fn(u32) -> DVec3 + Sync + 'a>;

/// Exact rays through the closed inputs' triangles, generalized winding
/// numbers of the open ones.
struct Rays<'a> {
    joined: &'a TriMesh,
    ids: &'a [u32],
    owner: &'a [u32],
    /// Per input: the first of its triangles in `joined`, and for an open
    /// input the field of its generalized winding number.
    first: Vec<u32>,
    fields: Vec<Option<WindingField<'a>>>,
    inputs: usize,
    tree: Bvh,
    /// Identities of a ray's two ends: no vertex has them.
    start_id: u32,
}

/// A closed box that holds the exact axis-parallel ray from the exact
/// start `Σ wᵢ xᵢ` (its float `p`) to `far`. The float sum is within
/// `3u·Σ|wᵢ||xᵢ|` of the exact one per coordinate and the weights sum to
/// 1 within `3u` (`u = 2⁻⁵³`), so a margin of `16u·Σ|wᵢ||xᵢ|` (plus the
/// smallest normal number, for sums that underflow) holds the exact start;
/// the ray moves along one axis only. Triangles whose exact boxes miss it
/// miss the ray, in the perturbed world too (perturbations are
/// infinitesimal).
fn ray_box(xc: &[DVec3; 3], weights: [f64; 3], p: DVec3, far: DVec3) -> Aabb {
    let size = xc[0].abs() * weights[0].abs()
        + xc[1].abs() * weights[1].abs()
        + xc[2].abs() * weights[2].abs();
    let margin = size * (16.0 * f64::EPSILON / 2.0) + DVec3::splat(f64::MIN_POSITIVE);
    Aabb::new(p.min(far) - margin, p.max(far) + margin)
}

/// Which side of a region is inside: the inputs' winding numbers on its
/// front (where its normal points) and back.
struct Sides {
    front: Vec<f64>,
    back: Vec<f64>,
}

impl<'a> Rays<'a> {
    fn new(
        joined: &'a TriMesh,
        ids: &'a [u32],
        owner: &'a [u32],
        inputs: &[&'a TriMesh],
        closed: &[bool],
        corner: &'a [Corner<'a>],
    ) -> Result<Rays<'a>, WindingError> {
        let boxes: Vec<Aabb> = (0..joined.triangles.len())
            .map(|t| Aabb::from_points(&joined.corners(t)))
            .collect();
        let tree = Bvh::build(&boxes).map_err(|_| WindingError::TooLarge)?;
        let mut first = Vec::with_capacity(inputs.len());
        let mut fields = Vec::with_capacity(inputs.len());
        let mut at = 0u32;
        for ((m, &closed), corner) in inputs.iter().zip(closed).zip(corner) {
            first.push(at);
            at += m.triangles.len() as u32;
            fields.push((!closed).then(|| WindingField::new(&m.triangles, &**corner)));
        }
        Ok(Rays {
            joined,
            ids,
            owner,
            first,
            fields,
            inputs: inputs.len(),
            tree,
            start_id: joined.positions.len() as u32,
        })
    }

    fn sym(&self, t: u32) -> [SymPoint; 3] {
        self.joined.triangles[t as usize]
            .map(|v| SymPoint::new(self.joined.positions[v as usize], self.ids[v as usize]))
    }

    /// The winding numbers on the two sides of a cell of input triangle
    /// `x` (front: where `x`'s normal points), sampled at the point
    /// `p = Σ wᵢ xᵢ` of `x` with chart coordinates `(u, v)`, with the input
    /// triangles `on` that hold the cell left out of the ray (`x` among
    /// them; each with +1 when it faces as `x` does, −1 when opposite).
    /// `None` when `(u, v)` is not inside `x`.
    ///
    /// `p` is taken exactly and in the perturbed world, as a point of the
    /// perturbed `x`: every predicate with `p` among its points is affine
    /// in it, so its sign is that of `Σ wᵢ P(xᵢ)` ([`Weighted`]). That
    /// puts the sample on the side of every other sheet the cut saw the
    /// cell on, coplanar overlaps included (there the sheets are apart only
    /// in the perturbed world), which no rounded point could.
    fn sides(&self, (x, [u, v]): Source, on: &[(u32, i64)]) -> Result<Option<Sides>, WindingError> {
        let normal = area_vector(self.joined, x as usize);
        let n = normal.abs();
        let axis = if n.x >= n.y && n.x >= n.z {
            0
        } else if n.y >= n.z {
            1
        } else {
            2
        };
        let weights = [1.0 - u - v, u, v];
        if !weights.iter().all(|&w| w > 0.0 && w.is_finite()) {
            return Ok(None);
        }
        let xc = self.joined.corners(x as usize);
        let p = xc[0] * weights[0] + xc[1] * weights[1] + xc[2] * weights[2];
        // The ray leaves along the axis closest to the normal, towards
        // the front: it crosses none of the left-out sheets.
        let bounds = self.tree.bounds();
        let span = (bounds.max - bounds.min)
            .max_element()
            .max(bounds.max.abs().max_element())
            .max(bounds.min.abs().max_element())
            .max(1.0);
        let mut far = p;
        far[axis] = if normal[axis] > 0.0 {
            bounds.max[axis].max(p[axis]) + span
        } else {
            bounds.min[axis].min(p[axis]) - span
        };
        if !far.is_finite() {
            return Err(WindingError::TooLarge);
        }
        let ray = WeightedRay {
            x: self.sym(x),
            weights,
            end: SymPoint::new(far, self.start_id),
            apart: Apart::new(axis, p, &xc),
        };
        // A group of coincident cells can hold 300,000 sheets (a degenerate
        // storm): looked up sorted, not by scanning `on` per triangle.
        let mut left: Vec<u32> = on.iter().map(|&(s, _)| s).collect();
        left.sort_unstable();
        let left_out = |t: u32| left.binary_search(&t).is_ok();
        let mut count = vec![0i64; self.inputs];
        // A thin box around the ray: only triangles whose boxes meet the
        // line can be crossed, and the triangles of a coplanar stack all
        // meet `x`'s own box, not the line.
        let reach = ray_box(&xc, weights, p, far);
        self.tree.for_each_overlap(&reach, |t| {
            let input = self.owner[t as usize] as usize;
            if left_out(t) || self.fields[input].is_some() {
                return;
            }
            let [a, b, c] = self.sym(t);
            if let Some(behind) = ray.crosses(a, b, c) {
                // Leaving from behind a triangle (the side its normal
                // points away from) is leaving its inside: +1.
                count[input] += if behind { 1 } else { -1 };
            }
        });
        // Each sheet the cell lies on adds its orientation across it.
        let mut across = vec![0i64; self.inputs];
        for &(t, sign) in on {
            across[self.owner[t as usize] as usize] += sign;
        }
        let mut front = vec![0.0; self.inputs];
        let mut back = vec![0.0; self.inputs];
        for i in 0..self.inputs {
            let jump = across[i] as f64;
            match &self.fields[i] {
                None => {
                    front[i] = count[i] as f64;
                    back[i] = (count[i] + across[i]) as f64;
                }
                Some(field) => {
                    // The generalized winding number of the rest of the
                    // open input at `p`; each sheet `p` lies on is half a
                    // turn on either side of it.
                    let skip: Vec<usize> = on
                        .iter()
                        .filter(|&&(t, _)| self.owner[t as usize] as usize == i)
                        .map(|&(t, _)| (t - self.first[i]) as usize)
                        .collect();
                    let rest = field.at_skipping(p, &skip);
                    front[i] = rest - 0.5 * jump;
                    back[i] = rest + 0.5 * jump;
                }
            }
        }
        Ok(Some(Sides { front, back }))
    }
}

/// A segment from the point `Σ wᵢ xᵢ` of a triangle `x` (perturbed with
/// it) to `end`.
struct WeightedRay {
    x: [SymPoint; 3],
    weights: [f64; 3],
    end: SymPoint,
    /// The float test that rejects most triangles before the exact ones.
    apart: Apart,
}

/// A float test of an axis-aligned ray's line against triangles, seen
/// along the axis: the line misses a triangle where, across one of its
/// edges, the line's point and the opposite corner lie on opposite sides,
/// both beyond the rounding error. A ray from a dense CAD mesh's
/// cell crosses the boxes of thousands of slivers that it misses; the
/// symbolic predicates ran on every one (a part against its mirror
/// image: 43% of its union in interval orientations).
struct Apart {
    /// The two coordinates across the ray's axis.
    across: [usize; 2],
    /// The start point, rounded, in those coordinates.
    p: DVec2,
    /// How far the rounded start may be from the exact weighted point,
    /// in either coordinate.
    slack: f64,
}

impl Apart {
    /// The test for a ray along `axis` from `p`, the rounded weighted
    /// point of the triangle with corners `xc`.
    fn new(axis: usize, p: DVec3, xc: &[DVec3; 3]) -> Apart {
        let across = [(axis + 1) % 3, (axis + 2) % 3];
        let largest = xc.iter().map(|c| c.abs().max_element()).fold(0.0, f64::max);
        Apart {
            across,
            p: DVec2::new(p[across[0]], p[across[1]]),
            // p = Σ wᵢ xᵢ takes three products and two sums, each within
            // half an ulp: 4ε of the largest corner coordinate, doubled.
            slack: 8.0 * f64::EPSILON * largest,
        }
    }

    /// Whether the line surely misses the triangle `abc`: for some edge,
    /// the third corner and the line's point lie strictly on opposite
    /// sides, each decided with a float orientation whose error bound
    /// (generous: 8ε of the products' magnitudes, and the start's slack
    /// times the edge's length) it clears. Then the exact orientations
    /// have those signs, and the three orientations of the point against
    /// the edges, which add up to the triangle's, cannot all agree: the
    /// exact test would say the same.
    fn misses(&self, a: DVec3, b: DVec3, c: DVec3) -> bool {
        let [i, j] = self.across;
        let flat = |q: DVec3| DVec2::new(q[i], q[j]);
        let (a, b, c) = (flat(a), flat(b), flat(c));
        let side = |u: DVec2, v: DVec2, q: DVec2, slack: f64| {
            let (e, d) = (v - u, q - u);
            let (l, r) = (e.x * d.y, e.y * d.x);
            let det = l - r;
            let bound =
                8.0 * f64::EPSILON * (l.abs() + r.abs()) + 2.0 * slack * (e.x.abs() + e.y.abs());
            if det > bound {
                1
            } else if det < -bound {
                -1
            } else {
                0
            }
        };
        [(a, b, c), (b, c, a), (c, a, b)].iter().any(|&(u, v, w)| {
            let corner = side(u, v, w, 0.0);
            let point = side(u, v, self.p, self.slack);
            corner != 0 && point == -corner
        })
    }
}

impl WeightedRay {
    /// orient3d with the start point in argument `slot` of `rest` (the
    /// three other points, in order).
    fn orient(&self, slot: usize, rest: [SymPoint; 3]) -> SosSign {
        let pts = [self.x[0], self.x[1], self.x[2], rest[0], rest[1], rest[2]];
        sos_sign(
            &Weighted {
                weights: self.weights,
                slot,
            },
            &pts,
        )
    }

    /// Whether the segment crosses the open triangle `abc` in the
    /// perturbed world, and if it does, whether it starts behind it (the
    /// side its normal points away from): the test of
    /// [`segment_triangle_intersect`] with the start a weighted point.
    fn crosses(&self, a: SymPoint, b: SymPoint, c: SymPoint) -> Option<bool> {
        if a.id == b.id || b.id == c.id || a.id == c.id || [a.id, b.id, c.id].contains(&self.end.id)
        {
            return None;
        }
        if self.apart.misses(a.pos, b.pos, c.pos) {
            return None;
        }
        self.crosses_exactly(a, b, c)
    }

    /// [`WeightedRay::crosses`] by the symbolic predicates alone.
    fn crosses_exactly(&self, a: SymPoint, b: SymPoint, c: SymPoint) -> Option<bool> {
        let sp = self.orient(3, [a, b, c]);
        let sq = orient3d_sos(a, b, c, self.end);
        if sp == SosSign::Degenerate || sp == sq {
            return None;
        }
        let e1 = self.orient(0, [self.end, a, b]);
        if e1 == SosSign::Degenerate
            || self.orient(0, [self.end, b, c]) != e1
            || self.orient(0, [self.end, c, a]) != e1
        {
            return None;
        }
        Some(sp == SosSign::Positive)
    }
}

/// orient3d of four points, one of which (argument `slot`) is the point
/// `Σ wᵢ xᵢ` of a triangle: points 0–2 are the triangle's corners, points
/// 3–5 the other three arguments in order. The determinant is affine in
/// each argument, so its value there is `Σ wᵢ orient3d(…, xᵢ, …)` when the
/// weights add up to one, and has the sign of the point `Σ wᵢ xᵢ / Σ wᵢ`
/// otherwise: only signs are asked.
struct Weighted {
    weights: [f64; 3],
    slot: usize,
}

impl Poly for Weighted {
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
        let (a, b, c) = (&p[3], &p[4], &p[5]);
        let term = |i: usize| {
            let x = &p[i];
            let o = match self.slot {
                0 => orient3(x, a, b, c),
                1 => orient3(a, x, b, c),
                2 => orient3(a, b, x, c),
                _ => orient3(a, b, c, x),
            };
            o.mul(&T::cst(self.weights[i]))
        };
        term(0).add(&term(1)).add(&term(2))
    }
}

/// Area vector of triangle `t` (twice its area, along its normal).
fn area_vector(mesh: &TriMesh, t: usize) -> DVec3 {
    let [a, b, c] = mesh.corners(t);
    (b - a).cross(c - a)
}

/// Per edge of the arrangement: whether some vertex lies exactly inside
/// it (collinear in every coordinate projection, strictly between its
/// ends). Such an edge is one side of a T-junction: where an intersection
/// curve runs along a triangle's side in the limit (coplanar sheets
/// meeting at an edge), the cut puts the curve's points on one sheet's
/// side but not on the other's, and the two triangles that seem to share
/// the side are on opposite sides of another sheet. Regions are not
/// joined across it.
fn vertices_on_edges(arr: &TriMesh, edges: &Edges) -> Vec<bool> {
    let pos = &arr.positions;
    let mut used = vec![false; pos.len()];
    for t in &arr.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let boxes: Vec<Aabb> = edges
        .ends
        .iter()
        .map(|&[u, v]| Aabb::from_points(&[pos[u as usize], pos[v as usize]]))
        .collect();
    let Ok(tree) = Bvh::build(&boxes) else {
        return vec![false; edges.len()];
    };
    // The vertices in parallel (a serial walk was 6% of a CAD part's
    // union with its mirror image: long edges, whose boxes hold many
    // vertices).
    let hits: Vec<u32> = (0..pos.len())
        .into_par_iter()
        .with_min_len(1 << 10)
        .filter(|&w| used[w])
        .flat_map_iter(|w| {
            let p = pos[w];
            let mut found = Vec::new();
            tree.for_each_overlap(&Aabb::new(p, p), |e| {
                let [u, v] = edges.ends[e as usize];
                if u as usize == w || v as usize == w {
                    return;
                }
                let (a, b) = (pos[u as usize], pos[v as usize]);
                let collinear = crate::intersect::COORDINATE_PLANES.iter().all(|proj| {
                    holey_geom::orient2d(proj(a), proj(b), proj(p)) == holey_geom::Sign::Zero
                });
                let t = (p - a).dot(b - a);
                if collinear && t > 0.0 && t < (b - a).dot(b - a) {
                    found.push(e);
                }
            });
            found
        })
        .collect();
    let mut through = vec![false; edges.len()];
    for e in hits {
        through[e as usize] = true;
    }
    through
}

/// How a region or group comes out: deleted, kept as it faces, or kept
/// turned over.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Fate {
    Deleted,
    Kept,
    Flipped,
}

fn fate(op: Operation, sides: &Sides) -> Fate {
    // w ≥ ½: for a closed input, whose w is an integer, w ≥ 1.
    let inside = |w: &[f64]| op.contains(&w.iter().map(|&w| w >= 0.5).collect::<Vec<_>>());
    match (inside(&sides.back), inside(&sides.front)) {
        (true, false) => Fate::Kept,
        (false, true) => Fate::Flipped,
        _ => Fate::Deleted,
    }
}

/// How many triangles of a region are tried as its sample before the
/// region is left to [`close_unsampled`].
const SAMPLE_TRIES: usize = 16;

/// Groups of identical coincident cells: cells with the same three
/// vertices whose source triangles are the same symbolic triangle
/// (duplicate triangles, faces two solids share exactly), which coincide
/// in the perturbed world too. Identical cells of different source
/// triangles are apart there (the cut glued points that coincide only in
/// the limit) and are classified each on its own. Returns the groups and
/// which cells are in one.
fn coincident_groups(
    arr: &TriMesh,
    source: &[Source],
    rays: &Rays<'_>,
) -> (Vec<Vec<u32>>, Vec<bool>) {
    let tris = &arr.triangles;
    let symbolic = |t: u32| {
        let mut k =
            rays.joined.triangles[source[t as usize].0 as usize].map(|v| rays.ids[v as usize]);
        k.sort_unstable();
        k
    };
    let mut keyed: Vec<([u32; 3], [u32; 3], u32)> = tris
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            let mut k = *tri;
            k.sort_unstable();
            (k, symbolic(t as u32), t as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let mut in_group = vec![false; tris.len()];
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for run in keyed.chunk_by(|a, b| a.0 == b.0 && a.1 == b.1) {
        if run.len() > 1 {
            groups.push(run.iter().map(|&(_, _, t)| t).collect());
            for &(_, _, t) in run {
                in_group[t as usize] = true;
            }
        }
    }
    (groups, in_group)
}

/// Per input triangle of `mesh`: whether it meets a triangle it
/// intersects degenerately, a vertex of one lying exactly in the other's
/// plane (coplanar overlaps, an edge lying in a face). There the perturbed
/// world's curves between the two can run, in the limit, along edges of
/// the arrangement that are no curve (a sliver between them has no area),
/// and the cut glues points that only coincide in the limit; the cells of
/// such a triangle are not joined into regions (module docs, step 2).
fn degenerate_contacts(mesh: &TriMesh, ids: &[u32], pairs: &[(u32, u32)]) -> Vec<bool> {
    let on_plane = |s: u32, t: u32| {
        let [a, b, c] = mesh.triangles[s as usize];
        let own = [ids[a as usize], ids[b as usize], ids[c as usize]];
        let p = |v: u32| mesh.positions[v as usize];
        mesh.triangles[t as usize].iter().any(|&v| {
            !own.contains(&ids[v as usize])
                && holey_geom::orient3d(p(a), p(b), p(c), p(v)) == holey_geom::Sign::Zero
        })
    };
    let hits: Vec<(u32, u32)> = pairs
        .par_iter()
        .copied()
        .filter(|&(s, t)| on_plane(s, t) || on_plane(t, s))
        .collect();
    let mut degenerate = vec![false; mesh.triangles.len()];
    for (s, t) in hits {
        degenerate[s as usize] = true;
        degenerate[t as usize] = true;
    }
    degenerate
}

/// Whether the triangle's three corners are collinear (exactly, in every
/// coordinate projection): a cell of no area, whose centroid lies where
/// other sheets meet and says nothing of its sides.
fn flat(arr: &TriMesh, t: u32) -> bool {
    let [a, b, c] = arr.corners(t as usize);
    crate::intersect::COORDINATE_PLANES
        .iter()
        .all(|proj| holey_geom::orient2d(proj(a), proj(b), proj(c)) == holey_geom::Sign::Zero)
}

/// The result's triangles: each region and each group of identical
/// coincident cells classified by one ray (module docs, steps 2–4).
/// `degenerate` flags the input triangles whose cells are regions of
/// their own ([`degenerate_contacts`]); cells of no area are never
/// samples, and a region of only such cells is left to
/// [`close_unsampled`].
fn classify(
    arr: &TriMesh,
    source: &[Source],
    degenerate: &[bool],
    rays: &Rays<'_>,
    op: Operation,
    report: &mut WindingReport,
) -> Result<Vec<[u32; 3]>, WindingError> {
    let tris = &arr.triangles;
    let (groups, in_group) = coincident_groups(arr, source, rays);
    report.coincident_groups = groups.len();

    // Regions: joined across edges two triangles share in opposite
    // directions, unless either comes from a triangle met degenerately.
    let edges = Edges::new(arr);
    let through = vertices_on_edges(arr, &edges);
    let alone = |t: u32| degenerate[source[t as usize].0 as usize];
    let mut sets = UnionFind::new(tris.len());
    for (e, &t_junction) in through.iter().enumerate() {
        if !t_junction
            && edges.opposite(tris, e)
            && let [t, u] = *edges.triangles(e)
            && !alone(t)
            && !alone(u)
        {
            sets.union(t, u);
        }
    }
    let root: Vec<u32> = (0..tris.len() as u32).map(|t| sets.find(t)).collect();
    // Each region's triangles, largest first.
    let mut order: Vec<(u32, f64, u32)> = (0..tris.len())
        .filter(|&t| !in_group[t])
        .map(|t| (root[t], -area_vector(arr, t).length(), t as u32))
        .collect();
    order.par_sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));

    // One ray per region (more where a sample is not inside its
    // triangle), the regions in parallel: degenerate contacts make many
    // small ones, and their rays decide ties symbolically.
    let runs: Vec<&[(u32, f64, u32)]> = order.chunk_by(|a, b| a.0 == b.0).collect();
    let decided: Vec<(u32, usize, Option<Fate>)> = runs
        .par_iter()
        .map(|run| {
            let mut tried = 0;
            for &(_, _, t) in run
                .iter()
                .filter(|&&(_, _, t)| !flat(arr, t))
                .take(SAMPLE_TRIES)
            {
                tried += 1;
                let x = source[t as usize];
                if let Some(sides) = rays.sides(x, &[(x.0, 1)])? {
                    return Ok((run[0].0, tried, Some(fate(op, &sides))));
                }
            }
            Ok((run[0].0, tried, None))
        })
        .collect::<Result<_, WindingError>>()?;
    let mut region_fate: HashMap<u32, Fate> = HashMap::default();
    for (root, tried, f) in decided {
        report.rays += tried;
        if let Some(f) = f {
            region_fate.insert(root, f);
        }
    }
    report.regions = order.chunk_by(|a, b| a.0 == b.0).count() + groups.len();

    let mut out: Vec<[u32; 3]> = Vec::new();
    let mut unsampled: HashMap<u32, Vec<[u32; 3]>> = HashMap::default();
    for (t, tri) in tris.iter().enumerate() {
        if in_group[t] {
            continue;
        }
        match region_fate.get(&root[t]) {
            Some(Fate::Deleted) => {}
            Some(Fate::Kept) => out.push(*tri),
            Some(Fate::Flipped) => out.push([tri[0], tri[2], tri[1]]),
            None => unsampled.entry(root[t]).or_default().push(*tri),
        }
    }
    let mut unsampled: Vec<Vec<[u32; 3]>> = unsampled.into_values().collect();
    let joined_groups = stacks(arr, &edges, &through, &groups, alone);
    for (group, fate) in groups.iter().zip(classify_stacks(
        arr,
        source,
        &groups,
        &joined_groups,
        rays,
        op,
        report,
    )?) {
        let reference = tris[group[0] as usize];
        match fate {
            Some(Fate::Deleted) => {}
            Some(Fate::Kept) => out.push(reference),
            Some(Fate::Flipped) => out.push([reference[0], reference[2], reference[1]]),
            None => unsampled.push(vec![reference]),
        }
    }
    // Largest first: a big piece's choice settles its small neighbours'.
    unsampled.sort_by_key(|piece| std::cmp::Reverse(piece.len()));
    report.unsampled_regions = unsampled.len();
    close_unsampled(&mut out, unsampled);
    Ok(out)
}

/// The groups of identical coincident cells ([`coincident_groups`])
/// joined into stacks: two groups whose cells are all the faces of an
/// edge they share (no other sheet meets there, nor a vertex inside it),
/// their first cells running it opposite ways, bound the same two wedges
/// of space about it, so the winding numbers on their fronts are one and
/// on their backs are one, and so are their fates (a solid united with
/// itself is one stack of pairs). Returns the stack of each group, as the
/// union-find root of group indices. Cells from a triangle met
/// degenerately (`alone`) are joined to nothing.
fn stacks(
    arr: &TriMesh,
    edges: &Edges,
    through: &[bool],
    groups: &[Vec<u32>],
    alone: impl Fn(u32) -> bool,
) -> Vec<u32> {
    let tris = &arr.triangles;
    let mut group_of = vec![u32::MAX; tris.len()];
    for (g, group) in groups.iter().enumerate() {
        for &t in group {
            group_of[t as usize] = g as u32;
        }
    }
    let runs = |t: [u32; 3], a: u32, b: u32| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b);
    let mut sets = UnionFind::new(groups.len());
    for (e, &t_junction) in through.iter().enumerate() {
        let faces = edges.triangles(e);
        if t_junction || faces.len() < 4 || faces.iter().any(|&t| alone(t)) {
            continue;
        }
        let g = group_of[faces[0] as usize];
        let Some(&h) = faces
            .iter()
            .map(|&t| &group_of[t as usize])
            .find(|&&h| h != g)
        else {
            continue;
        };
        if g == u32::MAX
            || h == u32::MAX
            || groups[g as usize].len() + groups[h as usize].len() != faces.len()
            || faces
                .iter()
                .any(|&t| group_of[t as usize] != g && group_of[t as usize] != h)
        {
            continue;
        }
        let [a, b] = edges.ends[e];
        let (r, s) = (
            tris[groups[g as usize][0] as usize],
            tris[groups[h as usize][0] as usize],
        );
        if runs(r, a, b) != runs(s, a, b) {
            sets.union(g, h);
        }
    }
    (0..groups.len() as u32).map(|g| sets.find(g)).collect()
}

/// The fate of each group of identical coincident cells, its first cell
/// the reference: one ray per stack ([`stacks`]), from the first of its
/// groups (up to [`SAMPLE_TRIES`]) whose ray decides, the stacks in
/// parallel; `None` where none does.
fn classify_stacks(
    arr: &TriMesh,
    source: &[Source],
    groups: &[Vec<u32>],
    stack_of: &[u32],
    rays: &Rays<'_>,
    op: Operation,
    report: &mut WindingReport,
) -> Result<Vec<Option<Fate>>, WindingError> {
    let tris = &arr.triangles;
    let mut members: Vec<(u32, u32)> = stack_of
        .iter()
        .enumerate()
        .map(|(g, &s)| (s, g as u32))
        .collect();
    members.sort_unstable();
    let runs: Vec<&[(u32, u32)]> = members.chunk_by(|a, b| a.0 == b.0).collect();
    let decided: Vec<(u32, usize, Option<Fate>)> = runs
        .par_iter()
        .map(|run| {
            let mut tried = 0;
            for &(_, g) in run.iter().take(SAMPLE_TRIES) {
                let group = &groups[g as usize];
                let first = group[0] as usize;
                let reference = tris[first];
                // Same cyclic order as the first cell: faces the same way.
                let same = |t: [u32; 3]| {
                    (0..3).any(|k| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]] == reference)
                };
                let on: Vec<(u32, i64)> = group
                    .iter()
                    .map(|&c| {
                        let sign = if same(tris[c as usize]) { 1 } else { -1 };
                        (source[c as usize].0, sign)
                    })
                    .collect();
                tried += 1;
                if let Some(sides) = rays.sides(source[first], &on)? {
                    return Ok((run[0].0, tried, Some(fate(op, &sides))));
                }
            }
            Ok((run[0].0, tried, None))
        })
        .collect::<Result<_, WindingError>>()?;
    let mut stack_fate: HashMap<u32, Option<Fate>> = HashMap::default();
    for (stack, tried, f) in decided {
        report.rays += tried;
        stack_fate.insert(stack, f);
    }
    Ok(stack_of
        .iter()
        .map(|s| stack_fate.get(s).copied().flatten())
        .collect())
}

/// Gives each region no sample could classify (slivers of no area along
/// an edge, where coplanar sheets cross in the perturbed world only) the
/// fate, of deleted, kept and turned over, that leaves the fewest of the
/// edges it touches unpaired among the faces already chosen: such a
/// region bounds no volume, and only the result's closedness depends on
/// it.
fn close_unsampled(out: &mut Vec<[u32; 3]>, pieces: Vec<Vec<[u32; 3]>>) {
    if pieces.is_empty() {
        return;
    }
    // Net direction count per undirected edge: + for min → max.
    let mut net: HashMap<(u32, u32), i32> = HashMap::default();
    let add = |net: &mut HashMap<(u32, u32), i32>, f: [u32; 3], sign: i32| {
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *net.entry((a.min(b), a.max(b))).or_insert(0) += if a < b { sign } else { -sign };
        }
    };
    for &f in out.iter() {
        add(&mut net, f, 1);
    }
    for piece in pieces {
        let keys: Vec<(u32, u32)> = piece
            .iter()
            .flat_map(|f| (0..3).map(move |k| (f[k].min(f[(k + 1) % 3]), f[k].max(f[(k + 1) % 3]))))
            .collect();
        let score = |sign: i32| -> i32 {
            let mut local: HashMap<(u32, u32), i32> = keys
                .iter()
                .map(|k| (*k, net.get(k).copied().unwrap_or(0)))
                .collect();
            for &f in &piece {
                add(&mut local, f, sign);
            }
            local.values().map(|v| v.abs()).sum()
        };
        // Deleted (0), kept (+1), turned over (−1); ties keep it deleted.
        let best = [0, 1, -1]
            .into_iter()
            .min_by_key(|&sign| score(sign))
            .unwrap_or(0);
        if best != 0 {
            for &f in &piece {
                add(&mut net, f, best);
                out.push(if best > 0 { f } else { [f[0], f[2], f[1]] });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::Rng;

    /// `Apart::misses` rejects only what the exact test also finds
    /// missed: rays along each axis from weighted points of random
    /// triangles, at scales 1e-3 to 1e6 and offsets up to 4096, against
    /// random triangles whose corners lie close to the ray's line
    /// (within a few units of rounding to a few percent of the scale),
    /// half of them with an edge whose line passes through the rounded
    /// start, where only the error bound keeps the float test from
    /// deciding a side the exact weighted point is not on. Every
    /// triangle it rejects, `crosses_exactly` finds missed; and it
    /// rejects most of those the line clearly misses.
    #[test]
    fn the_float_rejection_agrees_with_the_exact_ray_test() {
        let mut rng = Rng::new(54);
        let (mut rejected, mut crossed, mut clear_misses, mut clear_rejected) = (0, 0, 0, 0);
        for round in 0..4000 {
            let scale = [1e-3, 1.0, 1e6][round % 3];
            let offset = DVec3::splat([0.0, 4096.0][round / 3 % 2]);
            let point = |rng: &mut Rng| DVec3::from_array(rng.point(-1.0, 1.0)) * scale + offset;
            let xc = [point(&mut rng), point(&mut rng), point(&mut rng)];
            let (u, v) = (rng.range(0.05, 0.45), rng.range(0.05, 0.45));
            let weights = [1.0 - u - v, u, v];
            let p = xc[0] * weights[0] + xc[1] * weights[1] + xc[2] * weights[2];
            let axis = rng.below(3);
            let mut far = p;
            far[axis] += 10.0 * scale;
            let ray = WeightedRay {
                x: [0, 1, 2].map(|i| SymPoint::new(xc[i], i as u32)),
                weights,
                end: SymPoint::new(far, 99),
                apart: Apart::new(axis, p, &xc),
            };
            // Corners around the line, from far off to a hair away.
            let spread = scale * [1e-1, 1e-6, 1e-13][rng.below(3)];
            let near = |rng: &mut Rng| {
                let mut q = p + DVec3::from_array(rng.point(-1.0, 1.0)) * spread;
                q[axis] = p[axis] + rng.range(0.5, 2.0) * scale;
                q
            };
            let mut t = [near(&mut rng), near(&mut rng), near(&mut rng)];
            if round % 2 == 1 {
                // An edge whose line passes through the rounded start, seen
                // along the axis: the exact side is the weighted point's,
                // a rounding away.
                let mut d = DVec3::from_array(rng.point(-1.0, 1.0)) * scale;
                d[axis] = 0.0;
                let (s0, s1) = (rng.range(0.2, 1.0), rng.range(0.2, 1.0));
                t[0] = p + d * s0;
                t[1] = p - d * s1;
                t[0][axis] = p[axis] + rng.range(0.5, 2.0) * scale;
                t[1][axis] = p[axis] + rng.range(0.5, 2.0) * scale;
            }
            let [a, b, c] = [3u32, 4, 5].map(|i| SymPoint::new(t[i as usize - 3], i));
            let exact = ray.crosses_exactly(a, b, c);
            crossed += usize::from(exact.is_some());
            if ray.apart.misses(t[0], t[1], t[2]) {
                rejected += 1;
                assert_eq!(
                    exact, None,
                    "round {round}: rejected, but the exact test crosses"
                );
            }
            // A miss by far more than rounding: all corners on one side
            // of the line in one coordinate, by a thousandth of the spread.
            let [i, j] = [(axis + 1) % 3, (axis + 2) % 3];
            let gap = 1e-3 * spread;
            let clear = [i, j].iter().any(|&k| {
                t.iter().all(|q| q[k] > p[k] + gap) || t.iter().all(|q| q[k] < p[k] - gap)
            });
            if clear && spread > scale * 1e-9 {
                clear_misses += 1;
                clear_rejected += usize::from(ray.apart.misses(t[0], t[1], t[2]));
            }
        }
        assert!(
            crossed > 100,
            "the exact test crosses too rarely to check: {crossed}"
        );
        assert!(
            rejected > 1000,
            "the float test rejects too rarely: {rejected}"
        );
        assert!(
            clear_rejected * 10 >= clear_misses * 9,
            "clear misses rejected: {clear_rejected} of {clear_misses}"
        );
    }
}
