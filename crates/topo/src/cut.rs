//! Subdivision, gluing and deletion (§3.5).
//!
//! With the intersection curves and a parity field in hand:
//!
//! 1. **Decide which curves to resolve.** A curve component whose
//!    triangles' vertices are all even or all odd is dropped. Mesh edges
//!    whose ends have opposite parity but which no kept curve crosses get a
//!    *false intersection vertex* at their midpoint; a triangle untouched by
//!    kept curves with mixed parity gets a *false intersection edge* between
//!    the two false vertices on its edges.
//! 2. **Subdivide.** Each triangle touched by a kept curve, a false vertex
//!    or a false edge is re-triangulated with its points and segments by a
//!    constrained Delaunay triangulation (spade) in the triangle's own
//!    barycentric chart: corners at (0,0), (1,0), (0,1); a point on an edge
//!    placed exactly on that chart edge from its parameter along the mesh
//!    edge; an interior point at its correctly rounded barycentric
//!    coordinates. Constraints that cross (only possible through rounding)
//!    are split where they cross (`add_constraint_and_split`), so the
//!    triangulation never fails and never drops a constraint.
//! 3. **Glue.** Every intersection point is one global vertex, keyed by what
//!    generates it, so the triangles on both sides of a curve share it and
//!    are joined there by construction. (The paper duplicates curve
//!    vertices and then glues the duplicates.)
//! 4. **Delete.** A sub-triangle takes the parity of its original corners;
//!    one with none (all its corners on curves) is decided by 50 rounds of
//!    diffusion across sub-triangle edges that are not curve edges, and an
//!    undecided one is kept (even). Odd sub-triangles are deleted. A
//!    curve edge left with three kept sub-triangles (a T where a curve
//!    ends at a sheet's boundary) has, for one frame of motion, the two
//!    halves of its uncut sheet sampled, and the swept one deleted; where
//!    neither was swept (or over a drag), the half that runs against the
//!    crossing sheet's orientation goes when curve edges enclose it
//!    (`cut/junctions.rs`).
//!
//! In *resolve* mode (no parity field) every curve is kept and nothing is
//! deleted: the result is the mesh cut along all its self-intersections and
//! glued there, the arrangement.

use rustc_hash::FxHashMap as HashMap;

use glam::DVec3;
use rayon::prelude::*;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use crate::intersect::{Intersections, Node, PointKind, shared_ids};
use crate::mesh::{Edges, TriMesh, repeats_a_corner};

/// What the subdivision did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CutReport {
    /// Intersection curves resolved, cut along and glued (kept by step 1 of
    /// §3.5; every curve in resolve mode).
    pub curves_kept: usize,
    /// Intersection curves left uncut because every vertex of their triangles
    /// has one parity (§3.5 step 1).
    pub curves_dropped: usize,
    /// False intersection vertices (§3.5 step 1): one at the midpoint of each
    /// edge whose ends have opposite parity and that no kept curve crosses.
    pub false_vertices: usize,
    /// False intersection edges (§3.5 step 1): one between the two false
    /// vertices of each mixed-parity triangle no kept curve touches.
    pub false_edges: usize,
    /// Triangles re-triangulated.
    pub triangles_split: usize,
    /// Triangles (of the subdivided mesh) deleted as odd.
    pub triangles_deleted: usize,
    /// Sub-triangles with no original corner, decided by diffusion.
    pub diffused: usize,
    /// Sub-triangles still undecided after 50 rounds and sampling (kept).
    pub undecided: usize,
    /// Regions without an input vertex whose parity was sampled.
    pub sampled_regions: usize,
    /// The parity result of a solid input was not closed, and the regions
    /// were labelled by containment number instead (`crate::solid`).
    pub solid_relabelled: bool,
    /// Curve pieces that could not be inserted into their chart (spade
    /// failed on a rounding-induced crossing); 0 in every test case.
    pub dropped_constraints: usize,
    /// Sub-triangles whose original corners disagreed.
    pub conflicting: usize,
    /// Vertices added where constraints crossed after rounding.
    pub constraint_splits: usize,
    /// Points that rounded onto the same chart position as another.
    pub merged_points: usize,
    /// Curve edges where three sub-triangles were kept (a T: the swept
    /// sheet's parity missed the curve's last stretch) and the motion,
    /// sampled beside the edge, deleted the swept one (`cut/junctions.rs`).
    pub junctions_repaired: usize,
    /// Curve edges where all four sub-triangles were kept (two sheets
    /// crossing where parity deleted neither) and each half of one sheet
    /// was joined to the half of the other that its orientation allows
    /// (`cut/crossings.rs`).
    pub crossings_reconnected: usize,
    /// Sub-triangles taken out in pairs: one triangle twice, from two
    /// source triangles, facing opposite ways, a pillow of no volume
    /// (`cut/coincident.rs`).
    pub opposite_pairs_cancelled: usize,
    /// Closed-off debris the guard took out of a frame's result
    /// (`crate::guard`): pieces of their own, made with points of the cut,
    /// touching nothing outside the frame's region and smaller than
    /// [`crate::hidden`]'s speck scale.
    pub specks_removed: usize,
    /// Vertices split because the solid guard's result touched itself
    /// there at a single point (one vertex per fan).
    pub pinches_split: usize,
    /// Points of the cut that `resolve` took as an input corner or as
    /// another such point within rounding of them, before merging the
    /// coplanar overlaps (`crate::overlaps::weld_constructed`).
    pub points_welded: usize,
    /// Groups of coplanar triangles overlapping in their plane that
    /// `resolve` replaced by their overlay (`crate::overlaps`).
    pub coplanar_groups_merged: usize,
    /// Such groups `resolve` left overlapping: their overlay could not be
    /// made.
    pub coplanar_groups_left: usize,
}

/// A vertex of a chart triangulation (also the coplanar overlay's): its
/// position in the chart, and the mesh vertex it is (`NONE` for a point
/// the triangulation made where two constraints cross).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChartVertex {
    pub(crate) pos: Point2<f64>,
    pub(crate) global: u32,
}

impl HasPosition for ChartVertex {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.pos
    }
}

pub(crate) const NONE: u32 = u32::MAX;

/// Lists attached to a few of many items (the edges and triangles a cut
/// touches, out of a whole mesh's): a slot per item, storage only for the
/// items that have a list. A list per item cost 24 bytes per triangle and
/// per edge, fresh memory the kernel zeroed, for the few thousand that
/// are used.
struct Lists<T> {
    slot: Vec<u32>,
    lists: Vec<Vec<T>>,
    owner: Vec<u32>,
}

impl<T> Lists<T> {
    fn new(items: usize) -> Self {
        Lists {
            slot: vec![NONE; items],
            lists: Vec::new(),
            owner: Vec::new(),
        }
    }

    fn push(&mut self, item: usize, x: T) {
        let mut s = self.slot[item];
        if s == NONE {
            s = self.lists.len() as u32;
            self.slot[item] = s;
            self.lists.push(Vec::new());
            self.owner.push(item as u32);
        }
        self.lists[s as usize].push(x);
    }

    fn get(&self, item: usize) -> &[T] {
        match self.slot[item] {
            NONE => &[],
            s => &self.lists[s as usize],
        }
    }

    /// The items that have a list, in increasing order.
    fn owners_in_order(&self) -> Vec<usize> {
        let mut o: Vec<usize> = self.owner.iter().map(|&i| i as usize).collect();
        o.sort_unstable();
        o
    }
}

/// Most vertex-free regions sampled per cut (see `label`).
pub const MAX_SAMPLED_REGIONS: usize = 256;
const CHART: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

/// The point of the chart's hypotenuse `u + v = 1` with `v ≈ s`, chosen
/// so that `u + v = 1` holds exactly in floating point (Sterbenz: `1 − x`
/// is exact for `x ∈ [½, 1]`). The triangulation's exact orientation tests
/// then see it exactly on the chart edge, as it is symbolically.
fn on_hypotenuse(s: f64) -> [f64; 2] {
    let s = s.clamp(0.0, 1.0);
    if s <= 0.5 {
        let u = 1.0 - s;
        [u, 1.0 - u]
    } else {
        [1.0 - s, s]
    }
}

/// Chart position of the point at parameter `s` along side `k`, exactly on
/// that chart edge.
fn on_side(k: usize, s: f64) -> [f64; 2] {
    let s = s.clamp(0.0, 1.0);
    match k {
        0 => [s, 0.0],
        1 => on_hypotenuse(s),
        _ => [0.0, 1.0 - s],
    }
}

/// Chart position of barycentric coordinates (weights of the corners).
/// Symbolically such points lie strictly inside; if rounding put one
/// outside, it is moved exactly onto the nearest chart edge. A sum `u + v`
/// that rounds to 1 is on the hypotenuse too: its exact value can exceed
/// 1 by less than an ulp (a first weight of 0: a point whose limit is on
/// that side), which would put the point outside the chart, neither on the
/// side (so the neighbour across it never hears of it) nor inside.
fn from_bary(b: [f64; 3]) -> [f64; 2] {
    let (u, v) = (b[1].max(0.0), b[2].max(0.0));
    if u + v >= 1.0 {
        on_hypotenuse(v / (u + v))
    } else {
        [u, v]
    }
}

/// The chart side a chart position lies exactly on (in exact arithmetic,
/// as the triangulation's predicates see it), with the parameter along
/// that side from its first corner; `None` inside or at a corner.
fn chart_side(p: [f64; 2]) -> Option<(usize, f64)> {
    let [u, v] = p;
    let at_corner = (u == 0.0 && (v == 0.0 || v == 1.0)) || (u == 1.0 && v == 0.0);
    if at_corner {
        return None;
    }
    if v == 0.0 {
        return Some((0, u));
    }
    if u == 0.0 {
        return Some((2, 1.0 - v));
    }
    // u + v = 1 exactly: the rounded sum is 1 and its rounding error is 0.
    let sum = u + v;
    let err = v - (sum - u);
    if sum == 1.0 && err == 0.0 && (sum - v) == u {
        return Some((1, v));
    }
    None
}

/// Union-find over global vertex ids, for points that merge.
fn resolve(alias: &HashMap<u32, u32>, mut g: u32) -> u32 {
    while let Some(&h) = alias.get(&g) {
        g = h;
    }
    g
}

/// Merges the classes of `a` and `b`. The smaller id represents the class,
/// so input vertices (numbered first) survive merges, and no chain of
/// aliases can close into a cycle even when two charts merge the same
/// pair in opposite directions.
fn merge(alias: &mut HashMap<u32, u32>, a: u32, b: u32) -> bool {
    let (ra, rb) = (resolve(alias, a), resolve(alias, b));
    if ra == rb {
        return false;
    }
    alias.insert(ra.max(rb), ra.min(rb));
    true
}

/// An output triangle's input triangle and its centroid in that
/// triangle's chart.
pub type SourcePoint = (u32, [f64; 2]);

/// The subdivided (and, with a parity field, trimmed) mesh.
pub struct Cut {
    /// The subdivided mesh, glued along the kept curves, without its deleted
    /// (odd) sub-triangles.
    pub mesh: TriMesh,
    /// Counts of what the subdivision, gluing and deletion did.
    pub report: CutReport,
    /// Per output vertex: the input vertex it is, or `u32::MAX` for a new
    /// point (an intersection point or a split's vertex).
    pub origin: Vec<u32>,
    /// Per output triangle: the input triangle it is part of (its
    /// orientation is that triangle's), and its centroid in that
    /// triangle's chart (`(u, v)`: the point `p₀ + u (p₁ − p₀) + v (p₂ −
    /// p₀)`, as the subdivision placed it).
    pub source: Vec<SourcePoint>,
}

/// The source triangle of each output triangle, and its chart centroid:
/// the whole triangles first (the chart's centroid), then the
/// sub-triangles of the split ones. A whole triangle costs 4 bytes here,
/// not 24: it is nearly all of them.
pub(crate) struct Sources {
    whole: Vec<u32>,
    sub: Vec<(u32, [f64; 2])>,
}

impl Sources {
    /// Source triangle and chart centroid of output triangle `i`.
    fn get(&self, i: usize) -> (u32, [f64; 2]) {
        match self.whole.get(i) {
            Some(&t) => (t, [1.0 / 3.0; 2]),
            None => self.sub[i - self.whole.len()],
        }
    }

    /// Source triangle of output triangle `i`.
    fn triangle(&self, i: usize) -> u32 {
        self.get(i).0
    }

    /// The first output triangle that is a sub-triangle: curve edges are
    /// sides of sub-triangles only (a triangle a curve touches is split).
    fn first_sub(&self) -> usize {
        self.whole.len()
    }
}

/// The parity of a point of the surface that no vertex decides: called
/// with a number unique to the call, the triangle and barycentric weights
/// of its corners; `None` when it cannot tell.
pub type Sampler<'a> = dyn Fn(u32, u32, [f64; 3]) -> Option<bool> + 'a;

/// What the cut deletes.
#[derive(Clone, Copy, Debug)]
pub enum Deletion<'a> {
    /// Resolve mode: every curve is cut, nothing is deleted.
    Nothing,
    /// The odd part of a per-vertex parity field (`true` = odd), as in
    /// §3.5: a curve whose triangles' vertices all have one parity is not
    /// cut.
    Odd {
        /// Parity per input vertex (`true` = odd).
        odd: &'a [bool],
        /// Whether an open sheet's end that parity leaves standing on
        /// another sheet (a T-junction neither half of which was swept)
        /// opens into it: the enclosed half against its orientation is
        /// deleted (`cut/junctions.rs`). Off, the T stays: the paper's
        /// part assembly (Figure 9), with its occluded cap.
        open_ends: bool,
    },
    /// As [`Deletion::Odd`], where a sampled point follows the surface
    /// exactly: one frame of linear motion (a fixed barycentric point of
    /// a triangle whose corners move linearly), or a drag whose keyframes
    /// were kept (`crate::drag_path`). The sampler can then also decide
    /// the T-junctions vertex parity leaves where a curve ends at a
    /// sheet's boundary (Figure 7; `cut/junctions.rs`). A drag's straight
    /// path from its first positions to its last is only an approximation
    /// of the true one, too coarse beside a curve: without keyframes a
    /// drag deletes by [`Deletion::Odd`].
    ///
    /// `new_curve` flags the curves the frame (or the drag) made: none of
    /// their triangle pairs intersected at its start. Such a curve is cut even
    /// when every vertex around it has one parity: the parts of the
    /// surface it bounds swept through each other between vertices (two
    /// edges crossing, a fold between a fan's triangles), so they hold no
    /// vertex to carry their parity, and their regions are sampled. Left
    /// whole, the surface would come out crossing itself where it did not
    /// before.
    OddTracked {
        /// Parity per input vertex (`true` = odd), as in [`Deletion::Odd`].
        odd: &'a [bool],
        /// Per intersection curve (numbered as in
        /// [`Intersections::curve_of_piece`]): whether this frame made it; a
        /// curve past the end of the slice counts as not new.
        new_curve: &'a [bool],
        /// As in [`Deletion::Odd`].
        open_ends: bool,
    },
    /// The odd part of an exact parity field (containment numbers, in the
    /// union of two solids): every curve then separates odd from even,
    /// so every curve is cut, even one whose triangles have only even
    /// vertices (two ridges crossing: the lens between them holds no
    /// vertex, and its parity is sampled).
    OddExact(&'a [bool]),
}

impl<'a> Deletion<'a> {
    fn odd(self) -> Option<&'a [bool]> {
        match self {
            Deletion::Nothing => None,
            Deletion::Odd { odd: o, .. }
            | Deletion::OddTracked { odd: o, .. }
            | Deletion::OddExact(o) => Some(o),
        }
    }
}

/// Per curve of `x`: whether the vertices of its triangles have both
/// parities under `odd` (§3.5, step 1: a curve with only one is not cut).
pub fn mixed_curves(tris: &[[u32; 3]], x: &Intersections, odd: &[bool]) -> Vec<bool> {
    let mut seen = vec![[false; 2]; x.curve_count];
    for (p, piece) in x.pieces.iter().enumerate() {
        let c = x.curve_of_piece[p] as usize;
        for &t in &piece.tris {
            for &v in &tris[t as usize] {
                seen[c][usize::from(odd[v as usize])] = true;
            }
        }
    }
    seen.iter().map(|s| s[0] && s[1]).collect()
}

/// Subdivides `mesh` (at `positions`) along the intersection curves `x`,
/// glues, and deletes what `deletion` says.
///
/// A region cut off by intersection curves that holds no input vertex has
/// no parity sample (the paper's Figure 13: a cylinder plunged through one
/// huge triangle). With `sample`, such a region gets one: the parity of a
/// point inside it, computed as if a vertex had been placed there (the
/// adaptive refinement §7 proposes). Without it the region is kept.
///
/// The phases of the module documentation, one private function each:
/// the curves to resolve (`curves_to_resolve`), their points as global
/// vertices (`place_points`), what lies on each triangle and edge
/// (`OnMesh::gather`), false vertices and edges
/// (`OnMesh::add_false_vertices`), the subdivision (`subdivide`), the
/// gluing of shared vertices and merged points (`glue`), and the
/// labelling and deletion (`trim`).
pub fn cut(
    mesh: &TriMesh,
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    x: &Intersections,
    deletion: Deletion<'_>,
    sample: Option<&Sampler<'_>>,
) -> Cut {
    let tris = &mesh.triangles;
    let mut report = CutReport::default();
    let (kept_piece, active) = curves_to_resolve(tris, x, deletion, sample.is_some(), &mut report);
    let mut globals = place_points(positions, x, &active, &mut report);
    let mut on = OnMesh::gather(tris, edges, x, &active, &kept_piece, &globals.point);
    // Vertices a kept curve passes through (module docs, step 3).
    let shared_ids = shared_ids(
        x.pieces
            .iter()
            .zip(&kept_piece)
            .filter(|(_, k)| **k)
            .map(|(piece, _)| piece),
    );
    if let Some(odd) = deletion.odd() {
        let on_shared = |v: u32| shared_ids.binary_search(&ids[v as usize]).is_ok();
        on.add_false_vertices(edges, positions, odd, &on_shared, &mut globals, &mut report);
    }
    let mut sub = subdivide(tris, positions, edges, ids, &on, &mut globals, &mut report);
    glue(ids, &shared_ids, &mut globals, &mut sub, &mut report);
    trim(tris, positions, globals, sub, deletion, sample, report)
}

/// Step 1: which curves are resolved. Returns per curve piece whether its
/// curve is kept, and per intersection point whether a kept piece ends
/// there (an *active* point, which becomes a vertex).
fn curves_to_resolve(
    tris: &[[u32; 3]],
    x: &Intersections,
    deletion: Deletion<'_>,
    sampling: bool,
    report: &mut CutReport,
) -> (Vec<bool>, Vec<bool>) {
    let keep_curve: Vec<bool> = match deletion {
        Deletion::Nothing | Deletion::OddExact(_) => vec![true; x.curve_count],
        Deletion::Odd { odd, .. } => mixed_curves(tris, x, odd),
        Deletion::OddTracked { odd, new_curve, .. } => mixed_curves(tris, x, odd)
            .iter()
            .enumerate()
            .map(|(c, &mixed)| mixed || (sampling && new_curve.get(c).copied().unwrap_or(false)))
            .collect(),
    };
    report.curves_kept = keep_curve.iter().filter(|&&k| k).count();
    report.curves_dropped = x.curve_count - report.curves_kept;
    let kept_piece: Vec<bool> = x
        .curve_of_piece
        .iter()
        .map(|&c| keep_curve[c as usize])
        .collect();
    let mut active = vec![false; x.points.len()];
    for (p, piece) in x.pieces.iter().enumerate() {
        if kept_piece[p] {
            for node in piece.ends {
                if let Node::Point(i) = node {
                    active[i as usize] = true;
                }
            }
        }
    }
    (kept_piece, active)
}

/// The cut's global vertices: the input's, then active points, then false
/// vertices, then split vertices; each active point's global number, and
/// per input vertex whether a kept curve passes through it.
struct Globals {
    positions: Vec<DVec3>,
    point: Vec<u32>,
    on_curve: Vec<bool>,
    /// The input's vertex count: the first `inputs` globals are its
    /// vertices, in order.
    inputs: usize,
}

/// Numbers the active points as global vertices.
///
/// Points that are distinct symbolically but constructed at exactly the
/// same position (two edges crossing exactly, a curve through a vertex
/// of the other sheet: the degenerate configurations of aligned meshes)
/// are one vertex: the same position is the same point, so they are
/// glued, and a zero-length curve piece between them vanishes. Keeping
/// them apart would leave zero-area slivers whose side no vertex can
/// decide.
fn place_points(
    positions: &[DVec3],
    x: &Intersections,
    active: &[bool],
    report: &mut CutReport,
) -> Globals {
    let n = positions.len();
    let mut out_positions: Vec<DVec3> = positions.to_vec();
    let mut point_global = vec![NONE; x.points.len()];
    let mut on_curve = vec![false; n];
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    // The first input vertex at each active point's exact position: the
    // few active positions are hashed and the vertices scanned in
    // parallel against them, instead of hashing every vertex.
    let mut at: HashMap<[u64; 3], u32> = x
        .points
        .iter()
        .zip(active)
        .filter(|(_, a)| **a)
        .map(|(p, _)| (key(p.position), NONE))
        .collect();
    if !at.is_empty() {
        // Only vertices inside the active points' box can be at one: a
        // few comparisons reject the rest before any hashing.
        let (lo, hi) = x.points.iter().zip(active).filter(|(_, a)| **a).fold(
            (DVec3::INFINITY, DVec3::NEG_INFINITY),
            |(lo, hi), (p, _)| (lo.min(p.position), hi.max(p.position)),
        );
        let hits: Vec<([u64; 3], u32)> = positions
            .par_iter()
            .enumerate()
            .filter(|(_, p)| p.cmpge(lo).all() && p.cmple(hi).all())
            .filter_map(|(v, p)| {
                let k = key(*p);
                at.contains_key(&k).then_some((k, v as u32))
            })
            .collect();
        for (k, v) in hits {
            if let Some(first) = at.get_mut(&k) {
                *first = (*first).min(v);
            }
        }
        at.retain(|_, v| *v != NONE);
    }
    for (i, p) in x.points.iter().enumerate() {
        if active[i] {
            let next = out_positions.len() as u32;
            let g = *at.entry(key(p.position)).or_insert(next);
            if g == next {
                out_positions.push(p.position);
            } else {
                report.merged_points += 1;
                if (g as usize) < n {
                    on_curve[g as usize] = true;
                }
            }
            point_global[i] = g;
        }
    }
    Globals {
        positions: out_positions,
        point: point_global,
        on_curve,
        inputs: n,
    }
}

/// What lies on each triangle and edge of the input: points on edges
/// (global, parameter along the edge's ends), points inside triangles
/// (global, barycentric), curve pieces and false edges per triangle; the
/// edges a point cuts, the triangles anything touches, and the edges that
/// got a false vertex.
struct OnMesh {
    on_edge: Lists<(u32, f64)>,
    interior: Lists<(u32, [f64; 3])>,
    constraints: Lists<[Node; 2]>,
    false_edges: Lists<[u32; 2]>,
    cut_edge: Vec<bool>,
    touched: Vec<bool>,
    false_vertex_edges: Vec<usize>,
}

impl OnMesh {
    /// The points and kept curve pieces, placed on their triangles and
    /// edges.
    fn gather(
        tris: &[[u32; 3]],
        edges: &Edges,
        x: &Intersections,
        active: &[bool],
        kept_piece: &[bool],
        point_global: &[u32],
    ) -> OnMesh {
        let nt = tris.len();
        let mut on = OnMesh {
            on_edge: Lists::new(edges.len()),
            interior: Lists::new(nt),
            constraints: Lists::new(nt),
            false_edges: Lists::new(nt),
            cut_edge: vec![false; edges.len()],
            touched: vec![false; nt],
            false_vertex_edges: Vec::new(),
        };
        for (i, p) in x.points.iter().enumerate() {
            if !active[i] {
                continue;
            }
            let g = point_global[i];
            match p.kind {
                PointKind::EdgeTri { edge, tri, t, bary } => {
                    on.on_edge.push(edge as usize, (g, t));
                    on.cut_edge[edge as usize] = true;
                    on.interior.push(tri as usize, (g, bary));
                    on.touched[tri as usize] = true;
                    for &u in edges.triangles(edge as usize) {
                        on.touched[u as usize] = true;
                    }
                }
                PointKind::Triple { tris: ts, bary } => {
                    for k in 0..3 {
                        on.interior.push(ts[k] as usize, (g, bary[k]));
                        on.touched[ts[k] as usize] = true;
                    }
                }
            }
        }
        // A point inside a triangle symbolically but exactly on one of its
        // edges numerically (two ridges touching, an edge crossing an edge
        // exactly) lies on the neighbouring triangles' chart edge too: give
        // it to the edge, or the neighbour would keep the edge whole while
        // this triangle splits it, and the glued surface would crack there.
        for t in on.interior.owners_in_order() {
            for &(g, b) in on.interior.get(t) {
                let Some((side, s)) = chart_side(from_bary(b)) else {
                    continue;
                };
                let e = edges.of_triangle[t][side] as usize;
                let forward = tris[t][side] == edges.ends[e][0];
                if !on.on_edge.get(e).iter().any(|&(h, _)| h == g) {
                    on.on_edge.push(e, (g, if forward { s } else { 1.0 - s }));
                    on.cut_edge[e] = true;
                    for &u in edges.triangles(e) {
                        on.touched[u as usize] = true;
                    }
                }
            }
        }
        for (p, piece) in x.pieces.iter().enumerate() {
            if kept_piece[p] {
                for &t in &piece.tris {
                    on.constraints.push(t as usize, piece.ends);
                    on.touched[t as usize] = true;
                }
            }
        }
        on
    }

    /// False vertices and edges (step 1): a vertex at the midpoint of each
    /// edge whose ends' parities disagree with no curve between them, and
    /// an edge between the two such vertices of a triangle nothing else
    /// touches. A vertex on a curve (`on_shared`) has no side, so an edge
    /// to it never gets one: its parity says nothing.
    fn add_false_vertices(
        &mut self,
        edges: &Edges,
        positions: &[DVec3],
        odd: &[bool],
        on_shared: &(dyn Fn(u32) -> bool + Sync),
        globals: &mut Globals,
        report: &mut CutReport,
    ) {
        let mut false_vertex = vec![NONE; edges.len()];
        // The edges whose ends disagree with no curve between them, found
        // in parallel (few or none: a scan of every edge), then numbered in
        // order.
        let cut_edge = &self.cut_edge;
        let disagree: Vec<usize> = edges
            .ends
            .par_iter()
            .enumerate()
            .filter(|&(e, &[a, b])| {
                odd[a as usize] != odd[b as usize] && !cut_edge[e] && !on_shared(a) && !on_shared(b)
            })
            .map(|(e, _)| e)
            .collect();
        for e in disagree {
            let [a, b] = edges.ends[e];
            false_vertex[e] = globals.positions.len() as u32;
            self.false_vertex_edges.push(e);
            globals
                .positions
                .push((positions[a as usize] + positions[b as usize]) * 0.5);
            self.on_edge.push(e, (false_vertex[e], 0.5));
            report.false_vertices += 1;
        }
        if report.false_vertices == 0 {
            return;
        }
        for (t, &touched) in self.touched.iter().enumerate() {
            if touched {
                continue;
            }
            let fv: Vec<u32> = edges.of_triangle[t]
                .iter()
                .map(|&e| false_vertex[e as usize])
                .filter(|&g| g != NONE)
                .collect();
            if fv.len() == 2 {
                self.false_edges.push(t, [fv[0], fv[1]]);
                report.false_edges += 1;
            }
        }
    }
}

/// The subdivided mesh before gluing and deletion: its triangles, where
/// each came from, the curve edges, and the global vertices that rounding
/// made one (`alias`: a vertex to the one it is).
struct Subdivided {
    tris: Vec<[u32; 3]>,
    source: Sources,
    curve_edges: Vec<(u32, u32)>,
    alias: HashMap<u32, u32>,
}

/// Step 2: every affected triangle re-triangulated in its chart
/// ([`split_triangle`]). The triangles no point, curve piece or false edge
/// touches (nearly all of them) are copied first, in parallel; the split
/// ones follow, in order. `on.touched` has every triangle a point, a curve
/// piece or a false edge lies on, or whose side has a point; the sides
/// with a false vertex remain.
fn subdivide(
    tris: &[[u32; 3]],
    positions: &[DVec3],
    edges: &Edges,
    ids: &[u32],
    on: &OnMesh,
    globals: &mut Globals,
    report: &mut CutReport,
) -> Subdivided {
    let nt = tris.len();
    let mut whole: Vec<bool> = tris
        .par_iter()
        .zip(&on.touched)
        .map(|(tri, &touched)| {
            let degenerate = repeats_a_corner(tri);
            degenerate || !touched
        })
        .collect();
    for &e in &on.false_vertex_edges {
        for &t in edges.triangles(e) {
            let tri = tris[t as usize];
            // A degenerate triangle stays whole: its chart has no area.
            if !repeats_a_corner(&tri) {
                whole[t as usize] = false;
            }
        }
    }
    // A sequential copy: rayon's filtered collect into two vectors cost
    // more than the copy itself.
    let mut out_tris: Vec<[u32; 3]> = Vec::with_capacity(nt);
    let mut whole_source: Vec<u32> = Vec::with_capacity(nt);
    for (t, (tri, &w)) in tris.iter().zip(&whole).enumerate() {
        if w {
            out_tris.push(*tri);
            whole_source.push(t as u32);
        }
    }
    let mut sub = Subdivided {
        tris: out_tris,
        source: Sources {
            whole: whole_source,
            sub: Vec::new(),
        },
        curve_edges: Vec::new(),
        alias: HashMap::default(),
    };
    let chart = Chart {
        positions,
        edges,
        ids,
        on,
    };
    // Each chart is triangulated on its own, in parallel; what they add
    // to the shared tables (new points, merges) goes in afterwards in
    // triangle order, so the output is the same as one after another.
    let point = &globals.point;
    let splits: Vec<Split> = (0..nt)
        .into_par_iter()
        .filter(|&t| !whole[t])
        .map(|t| chart.split_triangle(t, tris[t], point))
        .collect();
    for split in splits {
        report.triangles_split += 1;
        split.append(globals, &mut sub, report);
    }
    sub
}

/// What triangulating one triangle's chart gives: its sub-triangles
/// with their chart centroids and its curve edges, by global vertex, new
/// points (split constraints) numbered [`NEW_POINT`]` | k` until they get
/// their global numbers, and the points its chart merged.
struct Split {
    t: u32,
    tris: Vec<[u32; 3]>,
    centroids: Vec<[f64; 2]>,
    curve_edges: Vec<(u32, u32)>,
    new_points: Vec<DVec3>,
    merges: Vec<(u32, u32)>,
    constraint_splits: usize,
    dropped_constraints: usize,
}

/// The mark of a chart's own new point in a [`Split`] (global numbers
/// stay below 2³¹).
const NEW_POINT: u32 = 1 << 31;

impl Split {
    /// Adds the split to the shared tables, numbering its new points.
    fn append(self, globals: &mut Globals, sub: &mut Subdivided, report: &mut CutReport) {
        let base = globals.positions.len() as u32;
        globals.positions.extend(self.new_points);
        let global = |v: u32| {
            if v & NEW_POINT != 0 {
                base + (v & !NEW_POINT)
            } else {
                v
            }
        };
        for (a, b) in self.merges {
            if merge(&mut sub.alias, a, b) {
                report.merged_points += 1;
            }
        }
        report.constraint_splits += self.constraint_splits;
        report.dropped_constraints += self.dropped_constraints;
        sub.tris.extend(self.tris.iter().map(|t| t.map(global)));
        sub.source
            .sub
            .extend(self.centroids.into_iter().map(|c| (self.t, c)));
        sub.curve_edges
            .extend(self.curve_edges.iter().map(|&(a, b)| {
                let (a, b) = (global(a), global(b));
                (a.min(b), a.max(b))
            }));
    }
}

/// What re-triangulating one input triangle needs to know.
struct Chart<'a> {
    positions: &'a [DVec3],
    edges: &'a Edges,
    ids: &'a [u32],
    on: &'a OnMesh,
}

impl Chart<'_> {
    /// Re-triangulates triangle `t` (corners `tri`) in its chart with its
    /// corners, the points on its sides and inside it, its curve pieces and
    /// false edges as constraints (constrained Delaunay, spade), and appends
    /// the sub-triangles, their sources and curve edges to `sub`.
    fn split_triangle(&self, t: usize, tri: [u32; 3], point: &[u32]) -> Split {
        let (edges, on) = (self.edges, self.on);
        let mut points = ChartPoints::default();
        for k in 0..3 {
            points.insert(tri[k], CHART[k]);
        }
        for (k, &corner) in tri.iter().enumerate() {
            let e = edges.of_triangle[t][k] as usize;
            let forward = corner == edges.ends[e][0];
            for &(g, s) in on.on_edge.get(e) {
                let s = if forward { s } else { 1.0 - s };
                points.insert(g, on_side(k, s));
            }
        }
        for &(g, b) in on.interior.get(t) {
            points.insert(g, from_bary(b));
        }
        let node_global = |node: Node| -> u32 {
            match node {
                Node::Point(i) => point[i as usize],
                Node::Shared(id) => tri
                    .iter()
                    .copied()
                    .find(|&v| self.ids[v as usize] == id)
                    .unwrap_or(NONE),
            }
        };
        let mut segs: Vec<[u32; 2]> = on
            .constraints
            .get(t)
            .iter()
            .map(|ends| [node_global(ends[0]), node_global(ends[1])])
            .collect();
        segs.extend_from_slice(on.false_edges.get(t));
        let dropped_constraints = points.constrain(&segs);
        // Numbers for split vertices; the corners' 3D frame for them.
        let p = tri.map(|v| self.positions[v as usize]);
        let mut global: Vec<u32> = Vec::with_capacity(points.cdt.num_vertices());
        let mut new_points = Vec::new();
        for v in points.cdt.vertices() {
            let cv = *v.data();
            let g = if cv.global == NONE {
                let g = NEW_POINT | new_points.len() as u32;
                let (u, w) = (cv.pos.x, cv.pos.y);
                new_points.push(p[0] + (p[1] - p[0]) * u + (p[2] - p[0]) * w);
                g
            } else {
                points
                    .global_of_handle
                    .get(&v.fix().index())
                    .copied()
                    .unwrap_or(cv.global)
            };
            global.push(g);
        }
        let mut split = Split {
            t: t as u32,
            tris: Vec::new(),
            centroids: Vec::new(),
            curve_edges: Vec::new(),
            constraint_splits: new_points.len(),
            new_points,
            merges: points.merges,
            dropped_constraints,
        };
        for f in points.cdt.inner_faces() {
            split
                .tris
                .push(f.vertices().map(|v| global[v.fix().index()]));
            let c = f.vertices().map(|v| v.position());
            split.centroids.push([
                (c[0].x + c[1].x + c[2].x) / 3.0,
                (c[0].y + c[1].y + c[2].y) / 3.0,
            ]);
        }
        for e in points.cdt.undirected_edges() {
            if e.is_constraint_edge() {
                let [a, b] = e.vertices().map(|v| global[v.fix().index()]);
                split.curve_edges.push((a, b));
            }
        }
        split
    }
}

/// One chart's constrained Delaunay triangulation with the global vertex
/// of each of its points.
#[derive(Default)]
struct ChartPoints {
    cdt: ConstrainedDelaunayTriangulation<ChartVertex>,
    handle_of: HashMap<u32, spade::handles::FixedVertexHandle>,
    global_of_handle: HashMap<usize, u32>,
    inserted: Vec<ChartVertex>,
    /// Global vertices that rounded onto another's chart point, with it:
    /// merged once the charts are done ([`Split::append`]).
    merges: Vec<(u32, u32)>,
}

impl ChartPoints {
    /// Inserts global vertex `global` at chart position `pos` (once); a
    /// point that rounds onto an existing one is merged with it.
    fn insert(&mut self, global: u32, pos: [f64; 2]) {
        if self.handle_of.contains_key(&global) {
            return;
        }
        let before = self.cdt.num_vertices();
        let v = ChartVertex {
            pos: Point2::new(pos[0], pos[1]),
            global,
        };
        self.inserted.push(v);
        let Ok(h) = self.cdt.insert(v) else {
            return;
        };
        if self.cdt.num_vertices() == before {
            // Rounded onto an existing point: the two are one.
            if let Some(&g0) = self.global_of_handle.get(&h.index())
                && g0 != global
            {
                self.merges.push((global, g0));
            }
        } else {
            self.global_of_handle.insert(h.index(), global);
        }
        self.handle_of.insert(global, h);
    }

    /// Adds the segments between global vertices as constraints.
    ///
    /// Symbolically the curve pieces of one triangle meet only at their
    /// shared points, so each goes in as a plain constraint. Only
    /// rounding in the chart can make two cross; then the crossing is
    /// split where the chart puts it. spade's splitting insertion can
    /// fail on such near-degenerate input (it panics); the chart is then
    /// rebuilt from its points and every constraint that fits is added
    /// without splitting, the others counted as dropped (the count is
    /// returned).
    fn constrain(&mut self, segs: &[[u32; 2]]) -> usize {
        let split = |p: Point2<f64>| ChartVertex {
            pos: p,
            global: NONE,
        };
        let pairs: Vec<_> = segs
            .iter()
            .filter_map(|[a, b]| Some((*self.handle_of.get(a)?, *self.handle_of.get(b)?)))
            .filter(|(ha, hb)| ha != hb)
            .collect();
        let (mut failed, mut dropped) = (false, 0);
        for &(ha, hb) in &pairs {
            if self.cdt.can_add_constraint(ha, hb) {
                self.cdt.add_constraint(ha, hb);
                continue;
            }
            let cdt = &mut self.cdt;
            let attempt = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                cdt.add_constraint_and_split(ha, hb, split);
            }));
            if attempt.is_err() {
                failed = true;
                break;
            }
        }
        if failed {
            // The same insertions in the same order give the same
            // vertices and handles (cloning every chart up front, for
            // this rare case, was a third of the subdivision's time).
            self.cdt = ConstrainedDelaunayTriangulation::new();
            for v in &self.inserted {
                let _ = self.cdt.insert(*v);
            }
            for &(ha, hb) in &pairs {
                if self.cdt.can_add_constraint(ha, hb) {
                    self.cdt.add_constraint(ha, hb);
                } else {
                    dropped += 1;
                }
            }
        }
        dropped
    }
}

/// Step 3: a curve through a vertex shared by both sheets (equal
/// positions, one identity): the sheets' copies of that vertex are one
/// point of the curve, glued like the constructed points. Such a vertex
/// lies on the cut, so it has no side and does not vote in the labelling.
/// Then every merged vertex is replaced by the one it is.
fn glue(
    ids: &[u32],
    shared_ids: &[u32],
    globals: &mut Globals,
    sub: &mut Subdivided,
    report: &mut CutReport,
) {
    let alias = &mut sub.alias;
    if !shared_ids.is_empty() {
        let mut first_of_id: HashMap<u32, u32> = HashMap::default();
        for v in 0..globals.inputs as u32 {
            let id = ids[v as usize];
            if shared_ids.binary_search(&id).is_ok() {
                globals.on_curve[v as usize] = true;
                let f = *first_of_id.entry(id).or_insert(v);
                if f != v && merge(alias, f, v) {
                    report.merged_points += 1;
                }
            }
        }
    }
    // Only the few merged vertices have aliases: flag them so the
    // triangles' other corners skip the lookup.
    let mut aliased = vec![false; globals.positions.len()];
    for &g in alias.keys() {
        if let Some(f) = aliased.get_mut(g as usize) {
            *f = true;
        }
    }
    for t in &mut sub.tris {
        for v in t.iter_mut() {
            if aliased.get(*v as usize).copied().unwrap_or(true) {
                *v = resolve(alias, *v);
            }
        }
    }
    for e in &mut sub.curve_edges {
        *e = (
            resolve(alias, e.0).min(resolve(alias, e.1)),
            resolve(alias, e.0).max(resolve(alias, e.1)),
        );
    }
}

/// Step 4: labels and deletion, then the result compacted to the
/// vertices its triangles use.
fn trim(
    input_tris: &[[u32; 3]],
    input_positions: &[DVec3],
    mut globals: Globals,
    mut sub: Subdivided,
    deletion: Deletion<'_>,
    sample: Option<&Sampler<'_>>,
    mut report: CutReport,
) -> Cut {
    let n = globals.inputs;
    let keep: Vec<bool> = match deletion.odd() {
        None => vec![true; sub.tris.len()],
        Some(odd) => {
            // An exact field's sampler casts one ray through the other
            // solid's tree, so every region no vertex reaches is sampled;
            // a motion's follows a point along its path, so its regions
            // are capped (see `label`).
            let max_samples = match deletion {
                Deletion::OddExact(_) => usize::MAX,
                _ => MAX_SAMPLED_REGIONS,
            };
            let labels = label(
                &sub.tris,
                n,
                &globals.on_curve,
                odd,
                &sub.curve_edges,
                &mut report,
                &sub.source,
                sample.map(|s| (s, max_samples)),
            );
            let mut keep: Vec<bool> = labels.iter().map(|&o| !o).collect();
            // The samples follow the true motion only for a frame or a
            // drag with its keyframes; otherwise T-junctions go by
            // orientation alone.
            let junctions = match deletion {
                Deletion::OddTracked { open_ends, .. } => Some((sample, open_ends)),
                Deletion::Odd { open_ends, .. } => Some((None, open_ends)),
                _ => None,
            };
            if let Some((sample, open_ends)) = junctions
                && (sample.is_some() || open_ends)
            {
                let mut curve = sub.curve_edges.clone();
                curve.sort_unstable();
                curve.dedup();
                let first = sub.source.first_sub();
                let around = around_curve(&sub.tris, first, &curve, globals.positions.len());
                report.junctions_repaired = junctions::Junctions {
                    tris: &sub.tris,
                    source: &sub.source,
                    positions: &globals.positions,
                    input_tris,
                    input_positions,
                    curve: &curve,
                    around: &around,
                }
                .repair(&mut keep, sample, open_ends, MAX_SAMPLED_REGIONS as u32);
                // Where parity kept all four sides, the sheets fuse
                // (`cut/crossings.rs`), once the pillows of no volume
                // two sheets' glued patches make are gone
                // (`cut/coincident.rs`); the paper's part assembly keeps
                // its X with its T.
                if open_ends {
                    let source = &sub.source;
                    let input = |i: usize| input_tris[source.triangle(i) as usize];
                    report.opposite_pairs_cancelled = coincident::cancel_opposite(
                        &sub.tris,
                        &mut keep,
                        |i| i >= first,
                        |i, j| !coincident::same_corners(input(i), input(j)),
                    );
                    report.crossings_reconnected = crossings::reconnect(
                        &mut sub.tris,
                        &mut keep,
                        &mut sub.source,
                        &around,
                        &mut globals.positions,
                    );
                }
            }
            keep
        }
    };
    report.triangles_deleted = keep.iter().filter(|&&k| !k).count();
    let (kept, kept_source): (Vec<[u32; 3]>, Vec<SourcePoint>) = sub
        .tris
        .par_iter()
        .enumerate()
        .zip(&keep)
        .filter(|(_, k)| **k)
        .map(|((i, t), _)| (*t, sub.source.get(i)))
        .filter(|(t, _)| !repeats_a_corner(t))
        .unzip();
    let (mesh, origin) = TriMesh {
        positions: globals.positions,
        triangles: kept,
    }
    .compacted_with_origin();
    // The first n positions are the input's vertices, in order.
    let origin = origin
        .into_iter()
        .map(|o| if (o as usize) < n { o } else { u32::MAX })
        .collect();
    Cut {
        mesh,
        report,
        origin,
        source: kept_source,
    }
}

/// Parity of each sub-triangle: from its original corners, else by
/// diffusion across non-curve edges; `true` = odd.
#[allow(clippy::too_many_arguments)]
fn label(
    tris: &[[u32; 3]],
    n_original: usize,
    on_curve: &[bool],
    odd: &[bool],
    curve_edges: &[(u32, u32)],
    report: &mut CutReport,
    source: &Sources,
    sample: Option<(&Sampler<'_>, usize)>,
) -> Vec<bool> {
    // Each triangle's vote, and whether its corners disagreed.
    let votes: Vec<(Option<bool>, bool)> = tris
        .par_iter()
        .map(|t| {
            let (mut o, mut e) = (0, 0);
            for &v in t {
                if (v as usize) < n_original && !on_curve[v as usize] {
                    if odd[v as usize] { o += 1 } else { e += 1 }
                }
            }
            (if o + e == 0 { None } else { Some(o > e) }, o > 0 && e > 0)
        })
        .collect();
    report.conflicting += votes.par_iter().filter(|v| v.1).count();
    let mut state: Vec<Option<bool>> = votes.into_par_iter().map(|v| v.0).collect();
    if state.par_iter().all(Option::is_some) {
        return state.into_par_iter().map(|s| s.unwrap_or(false)).collect();
    }
    let undecided: Vec<u32> = (0..tris.len() as u32)
        .filter(|&t| state[t as usize].is_none())
        .collect();
    let mut slot = vec![u32::MAX; tris.len()];
    for (k, &u) in undecided.iter().enumerate() {
        slot[u as usize] = k as u32;
    }
    let neighbours = undecided_neighbours(tris, &undecided, &slot, curve_edges);
    let undecided_before = undecided.len();
    // Rounds of majority votes, each from the states the round before
    // left (a triangle takes the parity most of its decided neighbours
    // have), visiting only the triangles next to one decided last round.
    let mut front: Vec<u32> = (0..undecided.len() as u32)
        .filter(|&k| {
            neighbours
                .of(k)
                .iter()
                .any(|&t| state[t as usize].is_some())
        })
        .collect();
    for _ in 0..50 {
        if front.is_empty() {
            break;
        }
        let decided: Vec<(u32, bool)> = front
            .iter()
            .filter_map(|&k| {
                let (mut o, mut e) = (0, 0);
                for &t in neighbours.of(k) {
                    match state[t as usize] {
                        Some(true) => o += 1,
                        Some(false) => e += 1,
                        None => {}
                    }
                }
                (o + e > 0).then_some((k, o > e))
            })
            .collect();
        for &(k, parity) in &decided {
            state[undecided[k as usize] as usize] = Some(parity);
        }
        let mut next: Vec<u32> = decided
            .iter()
            .flat_map(|&(k, _)| neighbours.of(k))
            .filter(|&&t| state[t as usize].is_none())
            .map(|&t| slot[t as usize])
            .collect();
        next.sort_unstable();
        next.dedup();
        front = next;
    }
    report.diffused = undecided_before - state.iter().filter(|s| s.is_none()).count();
    // Regions no vertex reaches: one sample each (Figure 13), at most
    // `max_samples`. A motion's sample is a moving point tested against
    // every triangle its path passes, so on a crumpled surface (thousands
    // of vertex-free slivers between curves) sampling them all took
    // minutes: a motion caps them at MAX_SAMPLED_REGIONS, and past the cap
    // regions stay undecided and are kept, as in the paper. The union's
    // exact field is not capped: two Menger sponges give thousands of
    // bands where one's slab crosses the other's wall between vertices,
    // and a band left kept is an edge of three triangles.
    if let Some((sample, max_samples)) = sample {
        let (mut region, mut tried) = (0u32, 0usize);
        for (k, &seed) in undecided.iter().enumerate() {
            if state[seed as usize].is_some() {
                continue;
            }
            if tried >= max_samples {
                break;
            }
            tried += 1;
            let (t, [u, v]) = source.get(seed as usize);
            let Some(parity) = sample(region, t, [1.0 - u - v, u, v]) else {
                continue;
            };
            region += 1;
            report.sampled_regions += 1;
            // Flood the region: undecided triangles joined across
            // non-curve edges.
            let mut stack = vec![k as u32];
            state[seed as usize] = Some(parity);
            while let Some(a) = stack.pop() {
                for &b in neighbours.of(a) {
                    if state[b as usize].is_none() {
                        state[b as usize] = Some(parity);
                        stack.push(slot[b as usize]);
                    }
                }
            }
        }
    }
    report.undecided = state.iter().filter(|s| s.is_none()).count();
    state.into_iter().map(|s| s.unwrap_or(false)).collect()
}

/// The neighbours of each undecided sub-triangle across its sides that
/// are not curve edges (every triangle having that side, but itself), by
/// slot in `undecided`: one sort of the sides whose ends both belong to
/// an undecided triangle, so the cost follows the cut, not the mesh.
fn undecided_neighbours(
    tris: &[[u32; 3]],
    undecided: &[u32],
    slot: &[u32],
    curve_edges: &[(u32, u32)],
) -> Neighbours {
    let mut curve: Vec<(u32, u32)> = curve_edges.to_vec();
    curve.sort_unstable();
    curve.dedup();
    let is_curve = |a: u32, b: u32| curve.binary_search(&(a.min(b), a.max(b))).is_ok();
    // Vertices of undecided triangles (new points included, so sized by
    // the largest of them).
    let size = undecided
        .iter()
        .flat_map(|&u| tris[u as usize])
        .max()
        .map_or(0, |v| v as usize + 1);
    let mut touched = vec![false; size];
    for &u in undecided {
        for v in tris[u as usize] {
            touched[v as usize] = true;
        }
    }
    let flagged = |v: u32| touched.get(v as usize).copied().unwrap_or(false);
    let mut sides: Vec<(u32, u32, u32)> = tris
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, t)| {
            (0..3).filter_map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                (flagged(a) && flagged(b) && !is_curve(a, b)).then_some((
                    a.min(b),
                    a.max(b),
                    i as u32,
                ))
            })
        })
        .collect();
    sides.par_sort_unstable();
    let mut count = vec![0u32; undecided.len() + 1];
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for group in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        for e in group {
            let k = slot[e.2 as usize];
            if k == u32::MAX {
                continue;
            }
            for f in group.iter().filter(|f| f.2 != e.2) {
                pairs.push((k, f.2));
                count[k as usize + 1] += 1;
            }
        }
    }
    for k in 0..undecided.len() {
        count[k + 1] += count[k];
    }
    let mut fill = count.clone();
    let mut list = vec![0u32; pairs.len()];
    for (k, t) in pairs {
        list[fill[k as usize] as usize] = t;
        fill[k as usize] += 1;
    }
    Neighbours { start: count, list }
}

/// Lists of triangles per undecided slot ([`undecided_neighbours`]).
struct Neighbours {
    start: Vec<u32>,
    list: Vec<u32>,
}

impl Neighbours {
    fn of(&self, k: u32) -> &[u32] {
        &self.list[self.start[k as usize] as usize..self.start[k as usize + 1] as usize]
    }
}

mod coincident;
mod crossings;
mod junctions;

pub(crate) use coincident::{cancel_opposite, same_corners};

/// The sub-triangles (those from `first` on) on each curve edge, kept
/// or not: where the repairs after the labelling look
/// (`cut/junctions.rs`, `cut/crossings.rs`). `curve` holds sorted `(min,
/// max)` pairs of vertices among `points`.
pub(crate) type AroundCurve = HashMap<(u32, u32), Vec<usize>>;

fn around_curve(
    tris: &[[u32; 3]],
    first: usize,
    curve: &[(u32, u32)],
    points: usize,
) -> AroundCurve {
    let mut around = AroundCurve::default();
    if curve.is_empty() {
        return around;
    }
    // A side is looked up only when both its ends are curve points.
    let mut on_curve = vec![false; points];
    for &(a, b) in curve {
        for v in [a, b] {
            if let Some(f) = on_curve.get_mut(v as usize) {
                *f = true;
            }
        }
    }
    let flagged = |v: u32| on_curve.get(v as usize).copied().unwrap_or(false);
    for (s, t) in tris.iter().enumerate().skip(first) {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            if !(flagged(a) && flagged(b)) {
                continue;
            }
            let key = (a.min(b), a.max(b));
            if curve.binary_search(&key).is_ok() {
                around.entry(key).or_default().push(s);
            }
        }
    }
    around
}

/// Fuses the crossings of an arrangement's kept triangles
/// (`cut/crossings.rs`): `tris` with their source triangles `source`
/// (`Cut::source`), `keep` what a labelling kept, `around` the triangles
/// on each edge where sheets meet. `tris`, `keep` and `positions` grow
/// where a one-edge crossing is split. Returns the edges reconnected.
pub(crate) fn reconnect_crossings(
    tris: &mut Vec<[u32; 3]>,
    keep: &mut Vec<bool>,
    source: Vec<SourcePoint>,
    around: &AroundCurve,
    positions: &mut Vec<DVec3>,
) -> usize {
    let mut sources = Sources {
        whole: Vec::new(),
        sub: source,
    };
    crossings::reconnect(tris, keep, &mut sources, around, positions)
}

#[cfg(test)]
mod tests;
