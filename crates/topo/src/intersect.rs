//! Static intersections at the end of the frame (§3.3).
//!
//! The paper finds edge × triangle crossings with a BVH over edges, infers
//! the triangle × triangle intersection segments combinatorially from
//! them, then finds the points where three triangles meet. We run the same
//! three steps from the triangle side: a BVH self-overlap query gives the
//! candidate triangle pairs, a cheap exact plane-side test rejects most of
//! them, and [`holey_geom::triangle_triangle_segment`] returns the two ends
//! of each intersection segment — each end an edge × triangle crossing (or
//! a vertex the two triangles share). Everything is decided exactly, with
//! simulation of simplicity for degeneracies, in the perturbed world of
//! `holey-geom`: identities are given by exact position classes, so the
//! corners of an unwelded soup that sit at one position are one symbolic
//! point.
//!
//! **Each intersection point exists once, keyed by what generates it**:
//! `(mesh edge, triangle)` for a crossing, `{t1, t2, t3}` for a triple
//! point. Every triangle the point lies on refers to the same point, so
//! neighbouring triangles share it exactly; its coordinates are computed
//! once, rounded once from exact values.
//!
//! The pieces of intersection segments between consecutive points form the
//! intersection curves; their connected components are the curves.

use rustc_hash::FxHashMap as HashMap;
use std::cmp::Ordering;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering as AtomicOrdering};

use glam::{DVec2, DVec3};
use holey_geom::orient::{Sign, orient2d, orient3d};
use holey_geom::{
    Aabb, BoxFrame, Bvh, SegEnd, SymPoint, edge_triangle_point, triangle_triangle_segment,
    triangle_triangle_triangle_point, triple_point,
};
use rayon::prelude::*;

use crate::mesh::{Edges, TriMesh};
use holey_mesh::rows::Rows;

/// A node of an intersection curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Node {
    /// An intersection point (index into [`Intersections::points`]).
    Point(u32),
    /// A vertex the two intersecting triangles share, by identity (its
    /// position class): each triangle resolves it to its own corner.
    Shared(u32),
}

/// What generates an intersection point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PointKind {
    /// Mesh edge `edge` crosses triangle `tri`. `t` is the parameter along
    /// the edge from `ends[0]` to `ends[1]`; `bary` are the barycentric
    /// coordinates in `tri`.
    EdgeTri {
        /// The crossing mesh edge: index into [`Edges`], whose `ends` give its
        /// two vertices.
        edge: u32,
        /// The crossed triangle: index into the mesh's triangles.
        tri: u32,
        /// Position along the edge, 0 at `ends[0]` and 1 at `ends[1]`
        /// (correctly rounded).
        t: f64,
        /// Barycentric coordinates of the point in `tri`, the weights of its
        /// corners in order (correctly rounded).
        bary: [f64; 3],
    },
    /// Three triangles meet; `bary[k]` are the coordinates in `tris[k]`.
    Triple {
        /// The three triangles, by index in increasing order.
        tris: [u32; 3],
        /// `bary[k]`: barycentric coordinates of the point in `tris[k]`.
        bary: [[f64; 3]; 3],
    },
}

/// An intersection point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IPoint {
    /// What generates the point, with its coordinates on the triangles it lies
    /// on.
    pub kind: PointKind,
    /// Its position, rounded once from the exact intersection.
    pub position: DVec3,
}

/// A piece of an intersection curve: the segment between two consecutive
/// nodes on the intersection of two triangles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// The nodes the piece joins, in their order along the intersection
    /// segment.
    pub ends: [Node; 2],
    /// The two triangles whose intersection segment the piece lies on, lower
    /// index first.
    pub tris: [u32; 2],
}

/// The self-intersections of a mesh at one set of positions.
#[derive(Clone, Debug, Default)]
pub struct Intersections {
    /// Every intersection point, once; [`Node::Point`] indexes this list.
    pub points: Vec<IPoint>,
    /// The curve pieces, grouped by intersecting pair in the order of
    /// [`Intersections::pairs`].
    pub pieces: Vec<Piece>,
    /// Curve (connected component of pieces) of each piece.
    pub curve_of_piece: Vec<u32>,
    /// Number of curves; [`Intersections::curve_of_piece`] numbers them
    /// `0..curve_count`.
    pub curve_count: usize,
    /// Triangle pairs that intersect along a segment, `t1 < t2`, sorted.
    pub pairs: Vec<(u32, u32)>,
    /// Mesh edges crossed by some triangle, and the edges of vertices a
    /// curve passes through ([`Node::Shared`]): the edges whose coupling
    /// error correction drops.
    pub cut_edges: Vec<bool>,
    /// Candidate pairs from the bounding-box pass, and how many the exact
    /// plane-side filter rejected.
    pub candidates: usize,
    /// Of the candidates, those that gave no intersection segment (`candidates`
    /// minus the segments found).
    pub filtered: usize,
    /// Of the candidates, the pairs whose triangles lie exactly in one
    /// plane and are not told apart in a coordinate projection: where
    /// they touch, the perturbation decides whether they overlap, and
    /// the exact coordinates can put faces on faces (walls). Counted
    /// where the stage prepared every triangle's plane (whole meshes and
    /// two parts); 0 for a subset's pairs.
    pub coplanar_candidates: usize,
}

impl Intersections {
    /// Number of triple points.
    pub fn triple_points(&self) -> usize {
        self.points
            .iter()
            .filter(|p| matches!(p.kind, PointKind::Triple { .. }))
            .count()
    }
}

/// Why the static intersection stage failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntersectError {
    /// The geometry kernel refused the positions: a non-finite coordinate, or
    /// more points or triangles than 32-bit indices address.
    #[error("geometry: {0}")]
    Geometry(#[from] holey_geom::GeomError),
    /// The mesh failed validation; the [`MeshError`](crate::mesh::MeshError)
    /// says which check.
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
    /// The exact predicates found an intersection point whose coordinates could
    /// not then be constructed.
    #[error(
        "the intersection point of edge {edge} and triangle {tri} could not be constructed: {reason}"
    )]
    Construction {
        /// The crossing mesh edge, or `u32::MAX` for a triple point.
        edge: u32,
        /// The crossed triangle, or for a triple point the first of its three.
        tri: u32,
        /// What the construction reported, in words.
        reason: String,
    },
    /// More intersecting triangle pairs, plus candidate triples (three
    /// pairwise intersecting triangles), than the caller allows: every
    /// pair makes a curve piece and every triple an exact test, so such a
    /// surface (a motion that crumples long triangles through each other)
    /// would hold the engine for minutes.
    #[error(
        "the surface intersects itself in more than {limit} triangle pairs and triples \
         ({triangles} triangles); the motion crumples it too much for one frame: \
         move less per frame or remesh first"
    )]
    TooManyPairs {
        /// The limit exceeded, on intersecting pairs plus candidate triples.
        limit: usize,
        /// Number of triangles of the mesh tested.
        triangles: usize,
    },
}

/// The default limit on intersecting triangle pairs plus candidate
/// triples of a surface with `triangles` triangles: 250,000 plus four per
/// triangle. Real surfaces stay far below it (two 262k-triangle spheres
/// crossing: 2,472 pairs and no triple; the most self-intersecting file of
/// the shared data set: 7,518 pairs on 1,442 triangles). It stops frames
/// that crumple the surface: an unremeshed inflate of 0.3 at radius 0.28
/// made 11.7 million pairs on 106k triangles, one of 0.1 after seven
/// frames 169k pairs and 1.45 million triples on 89k triangles (minutes
/// of exact tests on triangles sharing corners).
pub fn default_pair_limit(triangles: usize) -> usize {
    250_000usize.saturating_add(triangles.saturating_mul(4))
}

/// Orders the triple points `(point, third triangle)` on one intersection
/// segment from end `a` to end `b`.
///
/// The points are collinear and their coordinates are rounded once from
/// exact values, so one coordinate — along the axis where the segment
/// spreads most — orders them wherever they are farther apart than
/// rounding. Points with bit-equal keys sit at one position (up to
/// rounding) and are glued by the cut stage anyway; they keep index
/// order. The exact symbolic comparison of every pair, used before, is
/// correct but its expansion ran for minutes on lattice-aligned input.
fn order_along_segment(
    interior: &mut [(u32, u32)],
    a: DVec3,
    b: DVec3,
    position: &dyn Fn(u32) -> DVec3,
) {
    let d = b - a;
    let axis = if d.x.abs() >= d.y.abs() && d.x.abs() >= d.z.abs() {
        0
    } else if d.y.abs() >= d.z.abs() {
        1
    } else {
        2
    };
    let sign = if d[axis] < 0.0 { -1.0 } else { 1.0 };
    let key = |p: u32| sign * position(p)[axis];
    interior.sort_by(|x, y| key(x.0).total_cmp(&key(y.0)).then(x.0.cmp(&y.0)));
}

/// The symbolic points of a mesh: positions with identities.
pub(crate) struct Symbolic<'a> {
    pub positions: &'a [DVec3],
    pub ids: &'a [u32],
}

impl Symbolic<'_> {
    pub fn point(&self, v: u32) -> SymPoint {
        SymPoint::new(self.positions[v as usize], self.ids[v as usize])
    }
    pub fn tri(&self, t: [u32; 3]) -> [SymPoint; 3] {
        t.map(|v| self.point(v))
    }
}

/// Cheap exact rejection: true when all corners of `b` that are not
/// corners of `a` lie strictly on one side of `a`'s plane.
fn separated(a: [DVec3; 3], b: [DVec3; 3], b_shared: [bool; 3]) -> bool {
    let mut side = 0i8;
    for k in 0..3 {
        if b_shared[k] {
            continue;
        }
        let o = robust::orient3d(coord(a[0]), coord(a[1]), coord(a[2]), coord(b[k]));
        let s = if o > 0.0 {
            1
        } else if o < 0.0 {
            -1
        } else {
            return false;
        };
        if side != 0 && s != side {
            return false;
        }
        side = s;
    }
    side != 0
}

/// What the floating-point filter says of `b`'s corners (those not
/// shared with `a`) against `a`'s plane.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// All strictly on one side: the triangles cannot meet.
    Separated,
    /// Not all on one side (or all shared).
    Straddles,
    /// Some corner lies within rounding of the plane: only the exact
    /// predicate can tell.
    Unsure,
}

/// [`separated`] as far as floating point decides it: each corner's
/// orient3d is certified by Shewchuk's first error bound, (7 + 56ε)ε
/// times the permanent (`o3derrboundA` of his adaptive orient3d, here with
/// the cofactors taken along the first vector), and [`Side::Unsure`] is
/// returned when a corner is within it. The plane is computed here; the
/// candidate pass computes every triangle's once ([`Plane`]).
fn side_filter(a: [DVec3; 3], b: [DVec3; 3], b_shared: [bool; 3]) -> Side {
    side_filter_plane(a[0], &Plane::of(a), b, b_shared)
}

/// The projections onto the three coordinate planes (xy, yz, zx).
pub(crate) const COORDINATE_PLANES: [fn(DVec3) -> DVec2; 3] = [
    |p| DVec2::new(p.x, p.y),
    |p| DVec2::new(p.y, p.z),
    |p| DVec2::new(p.z, p.x),
];

/// Exact rejection of two nearly coplanar triangles without orient3d:
/// true when, in the projection onto some coordinate plane, an edge of one
/// triangle has the other triangle's three corners strictly on its outer
/// side. Triangles that meet in space meet in every projection, and a
/// strict separation survives any infinitesimal perturbation, so this
/// agrees with the perturbed world. Where both lie almost in one plane
/// (the flat bases of CAD parts placed on one another) each orient3d of
/// the rejection above falls through to expansion arithmetic, while these
/// orient2d tests decide at once: the profile of an EMBER pair had 5
/// million such predicates.
fn apart_in_projection(p1: [DVec3; 3], p2: [DVec3; 3], i1: [u32; 3], i2: [u32; 3]) -> bool {
    COORDINATE_PLANES.iter().any(|proj| {
        let (a, b) = (p1.map(proj), p2.map(proj));
        edge_separates(a, b, i1, i2) || edge_separates(b, a, i2, i1)
    })
}

/// Some edge of `a` has `a`'s third corner strictly on one side and all of
/// `b` strictly on the other (exact), but for a corner of `b` that is an
/// end of that edge (the same identity): two triangles sharing a vertex
/// and lying on either side of an edge through it meet only there, which
/// is no intersection (a fan of exactly coplanar CAD triangles, whose
/// every neighbouring pair otherwise went to the perturbed predicates).
fn edge_separates(a: [DVec2; 3], b: [DVec2; 3], a_ids: [u32; 3], b_ids: [u32; 3]) -> bool {
    (0..3).any(|k| {
        let (i, j, o) = (a[k], a[(k + 1) % 3], a[(k + 2) % 3]);
        let ends = [a_ids[k], a_ids[(k + 1) % 3]];
        let inner = orient2d(i, j, o);
        inner != Sign::Zero
            && b.iter().zip(b_ids).all(|(&q, id)| {
                if ends.contains(&id) {
                    return true;
                }
                let s = orient2d(i, j, q);
                s != Sign::Zero && s != inner
            })
    })
}

fn coord(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// The intersection segment of triangles `t1` and `t2` of `tris` (exact,
/// in the perturbed world of `sym`), or `None` when they do not
/// intersect other than along a shared vertex or edge.
fn pair_segment(tris: &[[u32; 3]], sym: &Symbolic<'_>, t1: u32, t2: u32) -> Option<[SegEnd; 2]> {
    pair_segment_with(tris, sym, None, t1, t2)
}

/// What [`pair_segment_with`] can use when it was computed for the whole
/// mesh beforehand: every triangle's [`Plane`], and which vertex stars
/// are certified flat ([`stars`]; only where pairs can share a vertex,
/// not across two parts).
struct Prepared {
    planes: Vec<Plane>,
    flat_stars: Option<Vec<bool>>,
    /// Pairs tested whose triangles lie exactly in one plane and overlap
    /// in every coordinate projection ([`Intersections::coplanar_candidates`]).
    coplanar: AtomicUsize,
}

/// A triangle's plane as [`side_filter`] evaluates it, computed once: the
/// cross product `q × r` of its edges from its first corner and the
/// absolute values of its terms, so that each corner of another triangle
/// costs one difference and two dot products (`p · (q × r)` and the
/// permanent `|p| · (|q_y r_z| + |q_z r_y|, …)`), the same floating-point
/// operations and so the same error bound. The side filter was more than
/// half of `holey selfint` on rotated CAD meshes, whose long thin
/// triangles have boxes that overlap many others.
#[derive(Clone, Copy)]
pub(crate) struct Plane {
    normal: DVec3,
    terms: DVec3,
}

impl Plane {
    fn of(a: [DVec3; 3]) -> Plane {
        let (q, r) = (a[1] - a[0], a[2] - a[0]);
        Plane {
            normal: q.cross(r),
            terms: DVec3::new(
                (q.y * r.z).abs() + (q.z * r.y).abs(),
                (q.z * r.x).abs() + (q.x * r.z).abs(),
                (q.x * r.y).abs() + (q.y * r.x).abs(),
            ),
        }
    }

    /// The planes of all of `tris` at `positions`.
    pub(crate) fn all(tris: &[[u32; 3]], positions: &[DVec3]) -> Vec<Plane> {
        tris.par_iter()
            .map(|t| Plane::of(t.map(|v| positions[v as usize])))
            .collect()
    }
}

/// [`side_filter`] with `a`'s plane computed beforehand: orient3d of
/// `(b_k, a₁, a₂, a₀)`, expanded along `b_k − a₀` (the first vector).
fn side_filter_plane(a0: DVec3, plane: &Plane, b: [DVec3; 3], b_shared: [bool; 3]) -> Side {
    const BOUND: f64 = 7.771_561_172_376_103e-16;
    let mut side = 0i8;
    let mut unsure = false;
    for k in 0..3 {
        if b_shared[k] {
            continue;
        }
        let p = b[k] - a0;
        let det = p.dot(plane.normal);
        if det.abs() <= BOUND * p.abs().dot(plane.terms) {
            unsure = true;
            continue;
        }
        let s = if det > 0.0 { 1 } else { -1 };
        if side != 0 && s != side {
            return Side::Straddles;
        }
        side = s;
    }
    match (unsure, side) {
        (true, _) => Side::Unsure,
        (false, 0) => Side::Straddles,
        (false, _) => Side::Separated,
    }
}

/// [`pair_segment`], with the triangles' planes when they were computed.
fn pair_segment_with(
    tris: &[[u32; 3]],
    sym: &Symbolic<'_>,
    prepared: Option<&Prepared>,
    t1: u32,
    t2: u32,
) -> Option<[SegEnd; 2]> {
    let tid = |t: u32| tris[t as usize].map(|v| sym.ids[v as usize]);
    let (i1, i2) = (tid(t1), tid(t2));
    let s2 = i2.map(|i| i1.contains(&i));
    match s2.iter().filter(|&&s| s).count() {
        0 => {}
        // Two triangles of a flat star that share only its centre meet
        // only there ([`stars`]).
        1 => {
            if let Some(flat) = prepared.and_then(|pre| pre.flat_stars.as_ref()) {
                let k = s2.iter().position(|&s| s).unwrap_or(0);
                if flat[i2[k] as usize] {
                    return None;
                }
            }
        }
        _ => return None,
    }
    let s1 = i1.map(|i| i2.contains(&i));
    let p1 = tris[t1 as usize].map(|v| sym.positions[v as usize]);
    let p2 = tris[t2 as usize].map(|v| sym.positions[v as usize]);
    let (f1, f2) = match prepared {
        Some(Prepared { planes: pl, .. }) => (
            side_filter_plane(p1[0], &pl[t1 as usize], p2, s2),
            side_filter_plane(p2[0], &pl[t2 as usize], p1, s1),
        ),
        None => (side_filter(p1, p2, s2), side_filter(p2, p1, s1)),
    };
    if f1 == Side::Separated || f2 == Side::Separated {
        return None;
    }
    // Nearly coplanar neighbours (the fans of a rotated CAD mesh) bend
    // through each other's planes yet lie apart in some projection: the
    // exact 2-D test is far cheaper than the perturbed segment.
    if apart_in_projection(p1, p2, i1, i2) {
        return None;
    }
    if (f1 == Side::Unsure && separated(p1, p2, s2))
        || (f2 == Side::Unsure && separated(p2, p1, s1))
    {
        return None;
    }
    // Exactly coplanar triangles leave every corner within rounding of
    // the other's plane, so the exact test runs only after both filters
    // were unsure.
    if let Some(pre) = prepared
        && f1 == Side::Unsure
        && f2 == Side::Unsure
        && p2
            .iter()
            .all(|&q| orient3d(p1[0], p1[1], p1[2], q) == Sign::Zero)
    {
        pre.coplanar.fetch_add(1, AtomicOrdering::Relaxed);
    }
    triangle_triangle_segment(sym.tri(tris[t1 as usize]), sym.tri(tris[t2 as usize]))
}

/// Which of the triangle pairs `pairs` of `mesh` intersect at `positions`
/// (exact, identities by position class, as [`intersections`] decides):
/// whether an intersection of a frame's end was there at its start.
pub(crate) fn pairs_intersect_at(
    mesh: &TriMesh,
    positions: &[DVec3],
    pairs: &[(u32, u32)],
) -> Result<Vec<bool>, IntersectError> {
    let ids = holey_geom::position_classes(positions)?;
    let sym = Symbolic {
        positions,
        ids: &ids,
    };
    Ok(pairs
        .par_iter()
        .map(|&(a, b)| pair_segment(&mesh.triangles, &sym, a, b).is_some())
        .collect())
}

/// An intersection segment of triangles `t1 < t2` and its two ends.
type Segment = (u32, u32, [SegEnd; 2]);

/// Where the candidate triangle pairs come from.
#[derive(Clone, Copy)]
pub(crate) enum Candidates<'a> {
    /// Every pair of the mesh's triangles whose boxes overlap: one tree
    /// over all of them.
    Within(&'a Bvh),
    /// Only pairs across two parts: the triangles of tree `first` against
    /// those of tree `second`, each tree's primitives numbered as its
    /// [`Primitives`] says.
    Across {
        first: &'a Bvh,
        first_triangles: Primitives<'a>,
        second: &'a Bvh,
        second_triangles: Primitives<'a>,
    },
    /// Pairs among a subset of the triangles: `tree`'s primitive `i` is
    /// triangle `triangles[i]`.
    Among { tree: &'a Bvh, triangles: &'a [u32] },
    /// Every pair of distinct triangles ([`Distinct`]): `tree` holds one
    /// of each set of identical triangles, and each pair found stands for
    /// every pair of their copies.
    Distinct {
        tree: &'a Bvh,
        distinct: &'a Distinct,
    },
}

/// Which triangle a tree's primitive `i` is.
#[derive(Clone, Copy)]
pub(crate) enum Primitives<'a> {
    /// Triangle `offset + i`.
    From(u32),
    /// Triangle `list[i]`.
    Listed(&'a [u32]),
}

impl Primitives<'_> {
    #[inline]
    fn triangle(self, i: u32) -> u32 {
        match self {
            Primitives::From(offset) => offset + i,
            Primitives::Listed(list) => list[i as usize],
        }
    }
}

/// The triangles that can meet another, when some cannot or repeat
/// another: one of each set of identical triangles (the same three
/// identities, in any order: they share every point, and two triangles
/// sharing an edge never intersect), and none whose identities repeat
/// (no area even in the perturbed world). A face of 900,000 corners over
/// three points fans into 300,000 copies of one triangle and 600,000 of
/// no area: one triangle to test, not 4.5 × 10¹⁰ pairs of boxes.
pub(crate) struct Distinct {
    /// One triangle of each set, in order.
    pub(crate) triangles: Vec<u32>,
    /// The other members of each set that has more than one.
    copies: HashMap<u32, Vec<u32>>,
}

impl Distinct {
    /// `None` when every triangle is distinct and has area.
    pub(crate) fn of(tris: &[[u32; 3]], ids: &[u32]) -> Option<Distinct> {
        let keys: Vec<[u32; 3]> = tris
            .par_iter()
            .map(|tri| {
                let mut k = tri.map(|v| ids[v as usize]);
                k.sort_unstable();
                k
            })
            .collect();
        let flat = keys.par_iter().any(|k| k[0] == k[1] || k[1] == k[2]);
        // Most meshes have neither: repeats are looked for among the
        // triangles of each smallest identity only (a counting sort, a
        // fifth of a sort of all the keys on 68k triangles).
        let repeats = flat || {
            let rows = keys.iter().map(|k| k[0] as usize + 1).max().unwrap_or(0);
            let mut by_smallest = Rows::file(rows, || {
                keys.iter()
                    .map(|k| (k[0], (u64::from(k[1]) << 32) | u64::from(k[2])))
            });
            !by_smallest.all_rows_mut(|row| {
                row.sort_unstable();
                row.windows(2).all(|w| w[0] != w[1])
            })
        };
        if !repeats {
            return None;
        }
        let mut keyed: Vec<([u32; 3], u32)> = keys.into_iter().zip(0..).collect();
        keyed.par_sort_unstable();
        let mut triangles = Vec::new();
        let mut copies = HashMap::default();
        for run in keyed.chunk_by(|a, b| a.0 == b.0) {
            let k = run[0].0;
            if k[0] == k[1] || k[1] == k[2] {
                continue;
            }
            triangles.push(run[0].1);
            if run.len() > 1 {
                copies.insert(run[0].1, run[1..].iter().map(|&(_, t)| t).collect());
            }
        }
        triangles.sort_unstable();
        Some(Distinct { triangles, copies })
    }

    /// Triangle `t` (one of [`Distinct::triangles`]) and its copies.
    fn members(&self, t: u32) -> impl Iterator<Item = u32> + '_ {
        std::iter::once(t).chain(self.copies.get(&t).into_iter().flatten().copied())
    }
}

/// The tree and candidates of every pair of `mesh`'s triangles at
/// `positions`: all of them, or the distinct ones ([`Distinct`]), with
/// boxes measured in the mesh's [`BoxFrame`] (a turned CAD part's flat
/// faces give flat boxes there: 282k overlapping pairs instead of 15.5M
/// on Thingi10K 79741 as EMBER turns it).
pub(crate) fn within(
    mesh: &TriMesh,
    positions: &[DVec3],
    ids: &[u32],
) -> Result<(Bvh, Option<Distinct>), IntersectError> {
    framed_within(mesh, positions, ids, None).map(|(tree, distinct, _)| (tree, distinct))
}

/// [`within`], and the frame its boxes are measured in: `frame`, or the
/// mesh's own when `None`.
fn framed_within(
    mesh: &TriMesh,
    positions: &[DVec3],
    ids: &[u32],
    frame: Option<BoxFrame>,
) -> Result<(Bvh, Option<Distinct>, BoxFrame), IntersectError> {
    // Two whole-mesh passes that need nothing of each other.
    let (frame, distinct) = rayon::join(
        || frame.unwrap_or_else(|| BoxFrame::of_triangles(&[(positions, &mesh.triangles)])),
        || Distinct::of(&mesh.triangles, ids),
    );
    match distinct {
        None => Ok((
            Bvh::build(&framed_triangle_boxes(
                mesh,
                positions,
                0..mesh.triangles.len(),
                &frame,
            ))?,
            None,
            frame,
        )),
        Some(d) => {
            let boxes: Vec<Aabb> = d
                .triangles
                .par_iter()
                .map(|&t| {
                    frame.triangle_box(mesh.triangles[t as usize].map(|v| positions[v as usize]))
                })
                .collect();
            Ok((Bvh::build(&boxes)?, Some(d), frame))
        }
    }
}

impl<'a> Candidates<'a> {
    /// The candidates [`within`] gives.
    pub(crate) fn within(tree: &'a Bvh, distinct: &'a Option<Distinct>) -> Candidates<'a> {
        match distinct {
            None => Candidates::Within(tree),
            Some(distinct) => Candidates::Distinct { tree, distinct },
        }
    }
}

/// The bounding boxes of triangles `range` of `mesh` at `positions`.
pub(crate) fn triangle_boxes(
    mesh: &TriMesh,
    positions: &[DVec3],
    range: std::ops::Range<usize>,
) -> Vec<Aabb> {
    framed_triangle_boxes(mesh, positions, range, &BoxFrame::IDENTITY)
}

/// The boxes of triangles `range` of `mesh` at `positions`, measured in
/// `frame` (conservative: triangles that share a point have overlapping
/// boxes; exact bounding boxes in the identity).
pub(crate) fn framed_triangle_boxes(
    mesh: &TriMesh,
    positions: &[DVec3],
    range: std::ops::Range<usize>,
    frame: &BoxFrame,
) -> Vec<Aabb> {
    mesh.triangles[range]
        .par_iter()
        .map(|t| frame.triangle_box(t.map(|v| positions[v as usize])))
        .collect()
}

/// The intersection segments of every candidate pair of triangles (in the
/// BVH descent's order, possibly repeated) and the number of candidate
/// pairs tested, and how many of those were exactly coplanar
/// ([`Intersections::coplanar_candidates`]; 0 for [`Candidates::Among`],
/// which tests without prepared planes); [`IntersectError::TooManyPairs`]
/// past `limit` (see [`intersections_limited`]).
fn segments(
    mesh: &TriMesh,
    positions: &[DVec3],
    ids: &[u32],
    candidates: Candidates<'_>,
    limit: usize,
    abort: &AtomicBool,
) -> Result<(Vec<Segment>, usize, usize), IntersectError> {
    let sym = Symbolic { positions, ids };
    let tris = &mesh.triangles;
    let hits = AtomicUsize::new(0);

    // Exact tests, in parallel, as the descent finds each pair of
    // overlapping boxes; the output keeps the descent's order. Only hits
    // are kept: candidates outnumber hits by orders of magnitude (4.7M
    // against 2.5k for two 262k-triangle spheres).
    // Every triangle's plane, every flat star and every flat patch, once,
    // where most triangles take part.
    let (prepared, flat_patches) = match candidates {
        Candidates::Among { .. } => (None, Vec::new()),
        Candidates::Across { .. } => (
            Some(Prepared {
                planes: Plane::all(tris, positions),
                flat_stars: None,
                coplanar: AtomicUsize::new(0),
            }),
            Vec::new(),
        ),
        Candidates::Within(tree) | Candidates::Distinct { tree, .. } => {
            let triangle_of = |i: u32| match candidates {
                Candidates::Distinct { distinct, .. } => distinct.triangles[i as usize],
                _ => i,
            };
            let pays = patches::pay(tree, triangle_of, tris, ids);
            let (planes, (flat_stars, flat_patches)) = rayon::join(
                || Plane::all(tris, positions),
                || {
                    rayon::join(
                        || stars::flat_stars(tris, positions, ids),
                        || match pays {
                            true => patches::flat_patches(tris, positions, ids),
                            false => Vec::new(),
                        },
                    )
                },
            );
            let prepared = Prepared {
                planes,
                flat_stars: Some(flat_stars),
                coplanar: AtomicUsize::new(0),
            };
            (Some(prepared), flat_patches)
        }
    };
    let test = |t1: u32, t2: u32| {
        if abort.load(AtomicOrdering::Relaxed) {
            return None;
        }
        let seg = pair_segment_with(tris, &sym, prepared.as_ref(), t1, t2)?;
        if hits.fetch_add(1, AtomicOrdering::Relaxed) >= limit {
            abort.store(true, AtomicOrdering::Relaxed);
            return None;
        }
        Some((t1, t2, seg))
    };
    // Two triangles of one certified flat patch meet only where they
    // share a vertex or an edge ([`patches`]): the descent skips them.
    let (segs, candidates): (Vec<Segment>, usize) = match candidates {
        Candidates::Within(bvh) if flat_patches.is_empty() => bvh.self_overlaps_filter_map(test),
        Candidates::Within(bvh) => {
            bvh.self_overlaps_apart_filter_map(&bvh.node_groups(&flat_patches), test)
        }
        Candidates::Across {
            first,
            first_triangles,
            second,
            second_triangles,
        } => first.overlaps_with_filter_map(second, |i, j| {
            // The lower number first, as for a pair found within one tree
            // (two parts of one mesh may come in either order).
            let (t1, t2) = (first_triangles.triangle(i), second_triangles.triangle(j));
            test(t1.min(t2), t1.max(t2))
        }),
        Candidates::Among { tree, triangles } => tree.self_overlaps_filter_map(|i, j| {
            let (t1, t2) = (triangles[i as usize], triangles[j as usize]);
            test(t1.min(t2), t1.max(t2))
        }),
        Candidates::Distinct { tree, distinct } => {
            let triangles = &distinct.triangles;
            let test_pair = |i: u32, j: u32| {
                let (t1, t2) = (triangles[i as usize], triangles[j as usize]);
                test(t1.min(t2), t1.max(t2))
            };
            let (found, candidates) = if flat_patches.is_empty() {
                tree.self_overlaps_filter_map(test_pair)
            } else {
                let patch_of: Vec<u32> = triangles
                    .iter()
                    .map(|&t| flat_patches[t as usize])
                    .collect();
                tree.self_overlaps_apart_filter_map(&tree.node_groups(&patch_of), test_pair)
            };
            // Every copy of one crosses every copy of the other alike.
            let mut all = Vec::with_capacity(found.len());
            for (t1, t2, seg) in found {
                for c1 in distinct.members(t1) {
                    for c2 in distinct.members(t2) {
                        if all.len() >= limit {
                            abort.store(true, AtomicOrdering::Relaxed);
                            break;
                        }
                        all.push((c1.min(c2), c1.max(c2), seg));
                    }
                }
            }
            (all, candidates)
        }
    };
    if abort.load(AtomicOrdering::Relaxed) {
        return Err(IntersectError::TooManyPairs {
            limit,
            triangles: tris.len(),
        });
    }
    let coplanar = prepared
        .as_ref()
        .map_or(0, |pre| pre.coplanar.load(AtomicOrdering::Relaxed));
    Ok((segs, candidates, coplanar))
}

/// Whether any two of `triangles` (of `mesh` at `positions`, with
/// identities `ids`) intersect, stopping at the first pair that does.
pub(crate) fn any_intersection_among(
    mesh: &TriMesh,
    positions: &[DVec3],
    ids: &[u32],
    triangles: &[u32],
) -> Result<bool, IntersectError> {
    // The triangles of a solid that meet another are often its flat
    // faces' slivers: measured in their own frame, their boxes are thin.
    let subset: Vec<[u32; 3]> = triangles
        .iter()
        .map(|&t| mesh.triangles[t as usize])
        .collect();
    let frame = BoxFrame::of_triangles(&[(positions, &subset)]);
    let boxes: Vec<Aabb> = subset
        .par_iter()
        .map(|t| frame.triangle_box(t.map(|v| positions[v as usize])))
        .collect();
    let tree = Bvh::build(&boxes)?;
    let found = segments(
        mesh,
        positions,
        ids,
        Candidates::Among {
            tree: &tree,
            triangles,
        },
        0,
        &AtomicBool::new(false),
    );
    match found {
        Ok(_) => Ok(false),
        Err(IntersectError::TooManyPairs { .. }) => Ok(true),
        Err(e) => Err(e),
    }
}

/// [`segments`] over all pairs of `mesh`'s triangles.
fn all_segments(
    mesh: &TriMesh,
    positions: &[DVec3],
    ids: &[u32],
    limit: usize,
    abort: &AtomicBool,
) -> Result<(Vec<Segment>, usize), IntersectError> {
    let (tree, distinct) = within(mesh, positions, ids)?;
    segments(
        mesh,
        positions,
        ids,
        Candidates::within(&tree, &distinct),
        limit,
        abort,
    )
    .map(|(found, candidates, _)| (found, candidates))
}

/// A surface's tree of every triangle's box, in the frame the boxes are
/// measured in: primitive `i` is triangle `i`.
pub(crate) struct FramedTree {
    pub(crate) frame: BoxFrame,
    pub(crate) tree: Bvh,
}

/// Whether `mesh` crosses itself (exactly, as [`intersections`] decides),
/// and the tree the check found its candidate pairs in, when it holds
/// every triangle (none repeats another): a caller pairing this surface
/// with another can query it again instead of building one more. The
/// boxes are measured in `frame`, or in the mesh's own when `None`.
pub(crate) fn crosses_itself_keeping_tree(
    mesh: &TriMesh,
    frame: Option<BoxFrame>,
) -> Result<(bool, Option<FramedTree>), IntersectError> {
    mesh.check()?;
    let ids = holey_geom::position_classes(&mesh.positions)?;
    let (tree, distinct, frame) = framed_within(mesh, &mesh.positions, &ids, frame)?;
    let crosses = match segments(
        mesh,
        &mesh.positions,
        &ids,
        Candidates::within(&tree, &distinct),
        0,
        &AtomicBool::new(false),
    ) {
        Ok(_) => false,
        Err(IntersectError::TooManyPairs { .. }) => true,
        Err(e) => return Err(e),
    };
    Ok((
        crosses,
        distinct.is_none().then_some(FramedTree { frame, tree }),
    ))
}

/// How many triangle pairs of `mesh` intersect (exactly, as
/// [`intersections`] finds them), without building points or curves;
/// [`IntersectError::TooManyPairs`] once more than `limit` do.
pub fn intersecting_pair_count(mesh: &TriMesh, limit: usize) -> Result<usize, IntersectError> {
    mesh.check()?;
    pair_count_at(mesh, &mesh.positions, limit)
}

/// [`intersecting_pair_count`] of the triangles of `mesh` whose bounding
/// boxes meet the box `region` (`(lo, hi)`), taken as a mesh of their
/// own: every crossing pair with a triangle inside `region` is among
/// them, since its partner's box meets that triangle's box. 0 when the
/// count cannot be made (more than `usize::MAX` pairs cannot happen; an
/// out-of-range index or non-finite position can).
pub fn crossing_pairs_within(mesh: &TriMesh, region: (DVec3, DVec3)) -> usize {
    let mut local = vec![u32::MAX; mesh.positions.len()];
    let mut part = TriMesh::default();
    for t in &mesh.triangles {
        if t.iter().any(|&v| v as usize >= mesh.positions.len()) {
            continue;
        }
        let p = t.map(|v| mesh.positions[v as usize]);
        let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
        if lo.cmpgt(region.1).any() || hi.cmplt(region.0).any() {
            continue;
        }
        part.triangles.push(t.map(|v| {
            if local[v as usize] == u32::MAX {
                local[v as usize] = part.positions.len() as u32;
                part.positions.push(mesh.positions[v as usize]);
            }
            local[v as usize]
        }));
    }
    intersecting_pair_count(&part, usize::MAX).unwrap_or(0)
}

/// [`crossing_pairs_involving`] of the triangles of `mesh` flagged in
/// `marked` (one flag per triangle), against the others whose boxes meet
/// one of theirs: every crossing pair a marked triangle takes part in.
/// Where the unmarked triangles are known not to cross one another (the
/// whole input triangles a cut kept), it is the count of the whole mesh,
/// at the cost of the marked ones. Triangles with a corner out of range
/// are left out.
pub fn crossing_pairs_of_marked(mesh: &TriMesh, marked: &[bool]) -> usize {
    let corners = |t: &[u32; 3]| {
        t.iter()
            .all(|&v| (v as usize) < mesh.positions.len())
            .then(|| t.map(|v| mesh.positions[v as usize]))
    };
    let is_marked = |i: usize| marked.get(i).copied().unwrap_or(false);
    let chosen: Vec<[DVec3; 3]> = (mesh.triangles.iter().enumerate())
        .filter(|&(i, _)| is_marked(i))
        .filter_map(|(_, t)| corners(t))
        .collect();
    if chosen.is_empty() {
        return 0;
    }
    let boxes: Vec<Aabb> = chosen.iter().map(|p| Aabb::from_points(p)).collect();
    let Ok(tree) = Bvh::build(&boxes) else {
        return 0;
    };
    let rest: Vec<[DVec3; 3]> = (mesh.triangles.par_iter().enumerate())
        .filter(|&(i, _)| !is_marked(i))
        .filter_map(|(_, t)| corners(t))
        .filter(|p| {
            let mut meets = false;
            tree.for_each_overlap(&Aabb::from_points(p), |_| meets = true);
            meets
        })
        .collect();
    crossing_pairs_in_tree(&chosen, &rest, &tree)
}

/// How many pairs of triangles cross (tested exactly, as
/// [`intersections`] tests them) among `marked` and `rest` taken as one
/// surface, counting only the pairs a `marked` triangle takes part in.
/// Corners are one vertex where their positions are the same, so the
/// triangles may come from different meshes or moments: the ones a
/// local edit made, against the untouched surface around them. The
/// marked triangles get a tree, every `rest` triangle queries it with
/// its box, so the cost follows the edit, not the surface. 0 when a
/// corner is not finite.
///
/// Two surfaces that differ only in their marked triangles have the same
/// unmarked pairs, so their full counts compare as these do.
pub fn crossing_pairs_involving(marked: &[[DVec3; 3]], rest: &[[DVec3; 3]]) -> usize {
    let boxes: Vec<Aabb> = marked.iter().map(|p| Aabb::from_points(p)).collect();
    match Bvh::build(&boxes) {
        Ok(tree) => crossing_pairs_in_tree(marked, rest, &tree),
        Err(_) => 0,
    }
}

/// [`crossing_pairs_involving`] with the tree of the marked triangles'
/// boxes (primitive `i` is `marked[i]`) already built.
fn crossing_pairs_in_tree(marked: &[[DVec3; 3]], rest: &[[DVec3; 3]], tree: &Bvh) -> usize {
    if marked.is_empty() {
        return 0;
    }
    // One part mesh, the marked triangles first, three corners each.
    let part = TriMesh {
        positions: marked.iter().chain(rest).flatten().copied().collect(),
        triangles: (0..(marked.len() + rest.len()) as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect(),
    };
    let Ok(ids) = holey_geom::position_classes(&part.positions) else {
        return 0;
    };
    let tris = &part.triangles;
    let bounds = |t: &[u32; 3]| Aabb::from_points(&t.map(|v| part.positions[v as usize]));
    let split = marked.len();
    let sym = Symbolic {
        positions: &part.positions,
        ids: &ids,
    };
    let hit = |a: u32, b: u32| pair_segment_with(tris, &sym, None, a.min(b), a.max(b)).is_some();
    let (among, _) =
        tree.self_overlaps_filter_map(|i, j| hit(i, j).then_some((i.min(j), i.max(j))));
    let mut pairs: Vec<(u32, u32)> = among;
    let across: Vec<(u32, u32)> = (split..tris.len())
        .into_par_iter()
        .flat_map_iter(|k| {
            let mut found = Vec::new();
            tree.for_each_overlap(&bounds(&tris[k]), |i| {
                if hit(i, k as u32) {
                    found.push((i, k as u32));
                }
            });
            found
        })
        .collect();
    pairs.extend(across);
    pairs.sort_unstable();
    pairs.dedup();
    pairs.len()
}

/// [`intersecting_pair_count`] of `mesh`'s triangles at `positions`
/// (indices already checked).
pub(crate) fn pair_count_at(
    mesh: &TriMesh,
    positions: &[DVec3],
    limit: usize,
) -> Result<usize, IntersectError> {
    let ids = holey_geom::position_classes(positions)?;
    let (mut segs, _) = all_segments(mesh, positions, &ids, limit, &AtomicBool::new(false))?;
    segs.sort_by_key(|s| (s.0, s.1));
    segs.dedup_by_key(|s| (s.0, s.1));
    Ok(segs.len())
}

/// Finds every self-intersection of `mesh` at `positions`, with identities
/// `ids` (normally [`holey_geom::position_classes`] of `positions`).
pub fn intersections(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
) -> Result<Intersections, IntersectError> {
    intersections_limited(
        mesh,
        positions,
        edges,
        ids,
        usize::MAX,
        &AtomicBool::new(false),
    )
}

/// [`intersections`] that stops with [`IntersectError::TooManyPairs`] once
/// more than `limit` triangle pairs intersect, raising `abort` so that
/// work running beside it can stop too; it also stops (with the same
/// error) when `abort` is raised from outside.
pub fn intersections_limited(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    limit: usize,
    abort: &AtomicBool,
) -> Result<Intersections, IntersectError> {
    let (tree, distinct) = within(mesh, positions, ids)?;
    intersections_among(
        mesh,
        positions,
        edges,
        ids,
        Candidates::within(&tree, &distinct),
        limit,
        abort,
    )
}

/// [`intersections_limited`] of the candidate pairs `candidates` only.
pub(crate) fn intersections_among(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    candidates: Candidates<'_>,
    limit: usize,
    abort: &AtomicBool,
) -> Result<Intersections, IntersectError> {
    let found = segments(mesh, positions, ids, candidates, limit, abort)?;
    assembled(mesh, positions, edges, ids, found, limit, abort)
}

/// [`intersections_limited`] of a mesh made of two parts, each of which
/// crosses itself nowhere: triangles `..split` with vertices
/// `..split_vertex`, and the rest (two solids joined, as the
/// winding-number arrangement joins them, each checked by
/// [`crosses_itself_keeping_tree`] on its own).
///
/// A crossing is decided by exact predicates with simulation of
/// simplicity, where the perturbation follows the order of the corners'
/// identities. The first part's identities here are the ones its own
/// check used (an identity is the smallest index of a point at the same
/// position, and the first part's vertices come first), so its pairs
/// cross nowhere here either. The second part's are its own shifted by
/// `split_vertex`, in the same order, except where a vertex lies exactly
/// on a point of the first part: it takes that point's identity, which
/// comes before every other. So a pair of the second part can be decided
/// differently only if one of its triangles has such a corner; those
/// pairs are tested again. The rest of the candidates are the pairs
/// across the parts. The result is [`intersections_limited`]'s, without
/// the pairs that touch within each part (most of a closed surface's
/// candidates: every triangle's box meets its neighbours'), except its
/// counts of candidates: the coplanar ones among the retested pairs are
/// not counted ([`Candidates::Among`] tests without prepared planes).
pub(crate) fn intersections_of_clean_parts(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    (split, split_vertex): (u32, u32),
    limit: usize,
    abort: &AtomicBool,
) -> Result<Intersections, IntersectError> {
    let n = mesh.triangles.len() as u32;
    let split = split.min(n);
    let frame = BoxFrame::of_triangles(&[(positions, &mesh.triangles)]);
    let boxes = framed_triangle_boxes(mesh, positions, 0..n as usize, &frame);
    let tree_of = |list: &[u32]| {
        let listed: Vec<Aabb> = list.iter().map(|&t| boxes[t as usize]).collect();
        Bvh::build(&listed)
    };
    let (first, second) = boxes.split_at(split as usize);
    let (tree_a, tree_b) = rayon::join(|| Bvh::build(first), || Bvh::build(second));
    let (tree_a, tree_b) = (tree_a?, tree_b?);
    let mut found = segments(
        mesh,
        positions,
        ids,
        Candidates::Across {
            first: &tree_a,
            first_triangles: Primitives::From(0),
            second: &tree_b,
            second_triangles: Primitives::From(split),
        },
        limit,
        abort,
    )?;
    let (touching, rest): (Vec<u32>, Vec<u32>) = (split..n).partition(|&t| {
        mesh.triangles[t as usize]
            .iter()
            .any(|&v| ids[v as usize] < split_vertex)
    });
    if !touching.is_empty() {
        let tree_t = tree_of(&touching)?;
        let mut more = vec![segments(
            mesh,
            positions,
            ids,
            Candidates::Among {
                tree: &tree_t,
                triangles: &touching,
            },
            limit,
            abort,
        )?];
        if !rest.is_empty() {
            let tree_r = tree_of(&rest)?;
            more.push(segments(
                mesh,
                positions,
                ids,
                Candidates::Across {
                    first: &tree_t,
                    first_triangles: Primitives::Listed(&touching),
                    second: &tree_r,
                    second_triangles: Primitives::Listed(&rest),
                },
                limit,
                abort,
            )?);
        }
        for (segs, candidates, coplanar) in more {
            found.0.extend(segs);
            found.1 += candidates;
            found.2 += coplanar;
        }
    }
    if found.0.len() > limit {
        return Err(IntersectError::TooManyPairs {
            limit,
            triangles: n as usize,
        });
    }
    assembled(mesh, positions, edges, ids, found, limit, abort)
}

/// The intersections of the segments `found` ([`segments`]: the segments,
/// how many candidate pairs were tested, how many of them lay exactly in
/// one plane): their points, triple points, pieces and curves.
fn assembled(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    (mut segs, candidates, coplanar_candidates): (Vec<Segment>, usize, usize),
    limit: usize,
    abort: &AtomicBool,
) -> Result<Intersections, IntersectError> {
    let tris = &mesh.triangles;
    let sym = Symbolic { positions, ids };
    // Copies of a repeated triangle ([`Distinct`]) add pairs the
    // descent never counted.
    let filtered = candidates.saturating_sub(segs.len());
    segs.sort_by_key(|s| (s.0, s.1));
    segs.dedup_by_key(|s| (s.0, s.1));

    // Edge × triangle points, keyed by (mesh edge, crossed triangle).
    let EdgeTriPoints {
        mut points,
        seg_nodes,
        point_of,
    } = edge_triangle_points(tris, &sym, edges, &segs)?;

    // Triple points: three pairwise-intersecting triangles meeting in a point.
    let triples = candidate_triples(tris.len(), &segs, limit, abort)?;
    let on_seg = triple_points(tris, &sym, &segs, &triples, &mut points)?;

    // Pieces: consecutive nodes along each segment.
    let pieces = segment_pieces(&segs, &seg_nodes, &point_of, on_seg, &points);

    // Curves: connected components of the pieces.
    let (curve_of_piece, curve_count) = curves(&pieces);

    let cut_edges = cut_edge_flags(&points, &pieces, edges, ids);
    Ok(Intersections {
        points,
        pieces,
        curve_of_piece,
        curve_count: curve_count as usize,
        pairs: segs.iter().map(|s| (s.0, s.1)).collect(),
        cut_edges,
        candidates,
        filtered,
        coplanar_candidates,
    })
}

/// The edge × triangle points of a set of intersection segments, and
/// which segment ends they are.
struct EdgeTriPoints {
    /// One point per distinct `(mesh edge, crossed triangle)` key, in key
    /// order.
    points: Vec<IPoint>,
    /// Per segment, the key of each of its two ends (`None` for a shared
    /// vertex).
    seg_nodes: Vec<[Option<(u32, u32)>; 2]>,
    /// The index in `points` of each key.
    point_of: HashMap<(u32, u32), u32>,
}

/// The `(mesh edge, crossed triangle)` key of `end`, an end of the
/// intersection segment of triangles `t1` and `t2`: `None` when the end
/// is a shared vertex, or an edge matching no edge of its triangle.
fn key_of_end(
    tris: &[[u32; 3]],
    ids: &[u32],
    edges: &Edges,
    t1: u32,
    t2: u32,
    end: &SegEnd,
) -> Option<(u32, u32)> {
    let tid = |t: u32| tris[t as usize].map(|v| ids[v as usize]);
    let SegEnd::Edge { p, q, tri } = end else {
        return None;
    };
    // The edge belongs to whichever triangle is not `tri`.
    let (owner, other) = if tri.map(|s| s.id) == tid(t2) {
        (t1, t2)
    } else {
        (t2, t1)
    };
    let t = tris[owner as usize];
    let k = (0..3).find(|&k| {
        let (a, b) = (ids[t[k] as usize], ids[t[(k + 1) % 3] as usize]);
        (a == p.id && b == q.id) || (a == q.id && b == p.id)
    })?;
    Some((edges.of_triangle[owner as usize][k], other))
}

/// Constructs every edge × triangle point that ends one of `segs`, once
/// per key, in parallel; the first construction failure in key order is
/// the error.
fn edge_triangle_points(
    tris: &[[u32; 3]],
    sym: &Symbolic<'_>,
    edges: &Edges,
    segs: &[Segment],
) -> Result<EdgeTriPoints, IntersectError> {
    let ids = sym.ids;
    let mut keys: Vec<(u32, u32)> = Vec::new();
    let mut seg_nodes: Vec<[Option<(u32, u32)>; 2]> = Vec::with_capacity(segs.len());
    for (t1, t2, ends) in segs {
        let a = key_of_end(tris, ids, edges, *t1, *t2, &ends[0]);
        let b = key_of_end(tris, ids, edges, *t1, *t2, &ends[1]);
        keys.extend(a.iter().chain(b.iter()).copied());
        seg_nodes.push([a, b]);
    }
    keys.sort_unstable();
    keys.dedup();
    let constructed: Vec<Result<IPoint, IntersectError>> = keys
        .par_iter()
        .map(|&(e, t)| {
            let [u, v] = edges.ends[e as usize];
            let c = tris[t as usize];
            let r = edge_triangle_point(
                sym.point(u),
                sym.point(v),
                sym.point(c[0]),
                sym.point(c[1]),
                sym.point(c[2]),
            )
            .map_err(|err| IntersectError::Construction {
                edge: e,
                tri: t,
                reason: err.to_string(),
            })?;
            Ok(IPoint {
                kind: PointKind::EdgeTri {
                    edge: e,
                    tri: t,
                    t: r.t,
                    bary: r.bary,
                },
                position: r.pos,
            })
        })
        .collect();
    let mut points = Vec::with_capacity(constructed.len());
    for p in constructed {
        points.push(p?);
    }
    let point_of: HashMap<(u32, u32), u32> = keys
        .iter()
        .enumerate()
        .map(|(i, &k)| (k, i as u32))
        .collect();
    Ok(EdgeTriPoints {
        points,
        seg_nodes,
        point_of,
    })
}

/// The curve node at segment end `end`, whose edge × triangle key (from
/// [`EdgeTriPoints::seg_nodes`]) is `key`.
fn node_of(point_of: &HashMap<(u32, u32), u32>, key: Option<(u32, u32)>, end: &SegEnd) -> Node {
    match (key, end) {
        (Some(k), _) => Node::Point(point_of[&k]),
        (None, SegEnd::Vertex(v)) => Node::Shared(v.id),
        // An edge end whose edge could not be matched (cannot happen
        // for a consistent mesh): treat as its first point's identity.
        (None, SegEnd::Edge { p, .. }) => Node::Shared(p.id),
    }
}

/// The triples `[t1, t2, t3]` (increasing) of triangles that pairwise
/// intersect along one of `segs`, in the order of `segs`;
/// [`IntersectError::TooManyPairs`] (raising `abort`) once pairs and
/// triples together exceed `limit`.
fn candidate_triples(
    triangles: usize,
    segs: &[Segment],
    limit: usize,
    abort: &AtomicBool,
) -> Result<Vec<[u32; 3]>, IntersectError> {
    let mut partners: Vec<Vec<u32>> = vec![Vec::new(); triangles];
    for (t1, t2, _) in segs {
        partners[*t1 as usize].push(*t2);
        partners[*t2 as usize].push(*t1);
    }
    for p in &mut partners {
        p.sort_unstable();
    }
    let mut triples: Vec<[u32; 3]> = Vec::new();
    for (t1, t2, _) in segs {
        let (a, b) = (&partners[*t1 as usize], &partners[*t2 as usize]);
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].cmp(&b[j]) {
                Ordering::Less => i += 1,
                Ordering::Greater => j += 1,
                Ordering::Equal => {
                    if a[i] > *t2 {
                        triples.push([*t1, *t2, a[i]]);
                        // Each candidate triple costs an exact test (with
                        // symbolic perturbation when the three share
                        // corners, as in a crumpled fan): they count
                        // against the same limit as the pairs.
                        if segs.len().saturating_add(triples.len()) > limit {
                            abort.store(true, AtomicOrdering::Relaxed);
                            return Err(IntersectError::TooManyPairs { limit, triangles });
                        }
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
    }
    Ok(triples)
}

/// Tests `triples` exactly (in parallel) and appends the triple points
/// found to `points`, in the order of `triples`; returns, per segment of
/// `segs`, the triple points on its interior as `(point, third
/// triangle)`.
fn triple_points(
    tris: &[[u32; 3]],
    sym: &Symbolic<'_>,
    segs: &[Segment],
    triples: &[[u32; 3]],
    points: &mut Vec<IPoint>,
) -> Result<Vec<Vec<(u32, u32)>>, IntersectError> {
    let seg_index: HashMap<(u32, u32), usize> = segs
        .iter()
        .enumerate()
        .map(|(i, s)| ((s.0, s.1), i))
        .collect();
    let triple_found: Vec<Option<Result<IPoint, IntersectError>>> = triples
        .par_iter()
        .map(|&t| {
            let s = t.map(|k| sym.tri(tris[k as usize]));
            if !triangle_triangle_triangle_point(s[0], s[1], s[2]) {
                return None;
            }
            Some(
                triple_point(s[0], s[1], s[2])
                    .map(|tp| IPoint {
                        kind: PointKind::Triple {
                            tris: t,
                            bary: tp.bary,
                        },
                        position: tp.pos,
                    })
                    .map_err(|err| IntersectError::Construction {
                        edge: u32::MAX,
                        tri: t[0],
                        reason: format!("triple point of triangles {t:?}: {err}"),
                    }),
            )
        })
        .collect();
    // Points on the interior of each segment.
    let mut on_seg: Vec<Vec<(u32, u32)>> = vec![Vec::new(); segs.len()]; // (point, third triangle)
    for r in triple_found.into_iter().flatten() {
        let p = r?;
        let PointKind::Triple { tris: t, .. } = p.kind else {
            continue;
        };
        let id = points.len() as u32;
        points.push(p);
        for (x, y, z) in [(t[0], t[1], t[2]), (t[0], t[2], t[1]), (t[1], t[2], t[0])] {
            if let Some(&s) = seg_index.get(&(x.min(y), x.max(y))) {
                on_seg[s].push((id, z));
            }
        }
    }
    Ok(on_seg)
}

/// The curve pieces: per segment of `segs`, in order, the pieces between
/// consecutive nodes along it — its two ends (keyed by `seg_nodes`, see
/// [`node_of`]) with the triple points `on_seg` on its interior between.
fn segment_pieces(
    segs: &[Segment],
    seg_nodes: &[[Option<(u32, u32)>; 2]],
    point_of: &HashMap<(u32, u32), u32>,
    mut on_seg: Vec<Vec<(u32, u32)>>,
    points: &[IPoint],
) -> Vec<Piece> {
    let mut pieces = Vec::new();
    for (s, (t1, t2, ends)) in segs.iter().enumerate() {
        let mut interior = std::mem::take(&mut on_seg[s]);
        let first = node_of(point_of, seg_nodes[s][0], &ends[0]);
        let last = node_of(point_of, seg_nodes[s][1], &ends[1]);
        if interior.len() > 1 {
            let at = |node: Node, end: &SegEnd| match (node, end) {
                (Node::Point(p), _) => points[p as usize].position,
                (_, SegEnd::Vertex(v)) => v.pos,
                (_, SegEnd::Edge { p, .. }) => p.pos,
            };
            let (a, b) = (at(first, &ends[0]), at(last, &ends[1]));
            let triple = |p: u32| points[p as usize].position;
            order_along_segment(&mut interior, a, b, &triple);
        }
        let mut chain = vec![first];
        chain.extend(interior.iter().map(|&(p, _)| Node::Point(p)));
        chain.push(last);
        for w in chain.windows(2) {
            pieces.push(Piece {
                ends: [w[0], w[1]],
                tris: [*t1, *t2],
            });
        }
    }
    pieces
}

/// The curve of each piece (connected components of `pieces`, numbered
/// in order of their first piece) and the number of curves.
fn curves(pieces: &[Piece]) -> (Vec<u32>, u32) {
    let mut nodes: Vec<Node> = pieces.iter().flat_map(|p| p.ends).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let index = |n: &Node| nodes.binary_search(n).unwrap_or(0);
    let mut sets = crate::union_find::UnionFind::new(nodes.len());
    for p in pieces {
        sets.union(index(&p.ends[0]) as u32, index(&p.ends[1]) as u32);
    }
    let mut curve_id = vec![u32::MAX; nodes.len()];
    let mut curve_count = 0u32;
    let curve_of_piece = pieces
        .iter()
        .map(|p| {
            let r = sets.find(index(&p.ends[0]) as u32) as usize;
            if curve_id[r] == u32::MAX {
                curve_id[r] = curve_count;
                curve_count += 1;
            }
            curve_id[r]
        })
        .collect();
    (curve_of_piece, curve_count)
}

/// [`Intersections::cut_edges`]: the mesh edges crossed by a triangle at
/// one of `points`, and the edges at vertices whose identity (in `ids`)
/// a piece passes through.
fn cut_edge_flags(points: &[IPoint], pieces: &[Piece], edges: &Edges, ids: &[u32]) -> Vec<bool> {
    let mut cut_edges = vec![false; edges.len()];
    for p in points {
        if let PointKind::EdgeTri { edge, .. } = p.kind {
            cut_edges[edge as usize] = true;
        }
    }
    // A curve through a vertex both triangles share (a fold's branch
    // point, or sheets meeting at a welded vertex) puts that vertex on the
    // curve even after perturbation: it has no side, so its edges carry no
    // coupling either.
    cut_edges_at_shared(edges, ids, &shared_ids(pieces), &mut cut_edges);
    cut_edges
}

/// Marks in `cut` the mesh edges with an end whose identity (in `ids`) is
/// one of `shared` (sorted, as [`shared_ids`] gives them): a curve through
/// a vertex keeps it on the curve even after perturbation, so the vertex
/// has no side and its edges carry no coupling.
pub(crate) fn cut_edges_at_shared(edges: &Edges, ids: &[u32], shared: &[u32], cut: &mut [bool]) {
    if shared.is_empty() {
        return;
    }
    for (e, ends) in edges.ends.iter().enumerate() {
        if ends
            .iter()
            .any(|&v| shared.binary_search(&ids[v as usize]).is_ok())
        {
            cut[e] = true;
        }
    }
}

/// The identities of the vertices that curve pieces pass through
/// ([`Node::Shared`]), sorted and without repeats.
pub fn shared_ids<'a>(pieces: impl IntoIterator<Item = &'a Piece>) -> Vec<u32> {
    let mut ids: Vec<u32> = pieces
        .into_iter()
        .flat_map(|piece| piece.ends)
        .filter_map(|node| match node {
            Node::Shared(id) => Some(id),
            Node::Point(_) => None,
        })
        .collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

#[cfg(test)]
pub(crate) mod tests;

mod patches;
mod stars;
