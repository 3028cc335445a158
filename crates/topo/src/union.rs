//! The union of two solids (Theorem 5.2), with the motion's collision
//! parity computed without simulating the motion.
//!
//! Theorem 5.2 builds the union of solids A and B by moving B from well
//! clear of A to its place: a vertex that ends inside the other solid
//! crossed the other's surface an odd number of times, so parity deletes
//! exactly the surface inside the other solid. `holey union` synthesizes
//! that motion and runs the whole pipeline (`topology_change`).
//!
//! For two closed surfaces the parities that motion produces are known in
//! advance. A vertex of B starts outside A (B starts clear) and moves in
//! a straight line to its place; the motion of A relative to it is rigid,
//! so its collisions with A's triangles are the crossings of A's surface
//! along a path from outside to its final position, and their number is
//! odd exactly when it ends inside A. Likewise every vertex of A is hit
//! by B's surface an odd number of times exactly when it ends inside B.
//! Collisions within A or within B never happen (each moves rigidly).
//! So the raw parity field is the *containment parity*: for each vertex,
//! whether it lies inside the other solid. This module computes it
//! directly:
//!
//! - The static intersections are needed only between A and B (the
//!   solids' own self-overlaps, 4.7 million neighbouring box pairs for
//!   two 262k-triangle spheres, are not visited): one tree per solid and a
//!   descent of one against the other.
//! - Containment is constant along every edge no triangle of the other
//!   solid crosses, so the vertices split into components joined by
//!   uncut edges, and one exact ray per component decides its parity (the
//!   crossings of a ray to infinity with the other solid's triangles,
//!   with simulation of simplicity, in the same perturbed world as the
//!   intersections).
//! - The field is exact, so error correction has nothing to correct, and
//!   every A × B curve separates inside from outside: the cut keeps every
//!   curve (`Deletion::OddExact`), and a region that holds no vertex
//!   (two ridges crossing) gets its parity from one more ray.
//!
//! The result is the one the motion gives when the collision parity is
//! right, without the cost of the motion (the collision stage over the
//! long swept paths of B's vertices was 60% of a union).
//!
//! Identities are per vertex: a vertex of A and a vertex of B at the same
//! position are two symbolic points, so the perturbation separates the
//! solids consistently where they touch exactly (faces of lattice-aligned
//! copies of one mesh), as a motion would.
//!
//! [`PreparedSolid`] keeps what a union builds of one solid alone (its
//! edge table, its tree, its orientation), for unions of one solid with
//! many others: [`union_prepared`] then does only the work of the pair.
//!
//! If A or B intersects itself away from the other, its own curves are
//! left as they are: each surface keeps what lies outside the other,
//! self-intersections included. If it intersects itself where it meets
//! the other, the points where the curves cross would be missing, so the
//! union refuses ([`UnionError::SelfIntersecting`]) and the motion
//! (`topology_change`) resolves it.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use glam::DVec3;
use holey_geom::{Aabb, BoxFrame, Bvh, SymPoint};
use rayon::prelude::*;

use crate::cut::{Cut, Deletion, cut};
use crate::engine::{Options, Outcome, Report, Timings, TopoError};
use crate::intersect::{
    Candidates, FramedTree, Primitives, any_intersection_among, default_pair_limit,
    intersections_among, triangle_boxes,
};
use crate::mesh::{Edges, MeshError, TriMesh};
use crate::orient::orient_consistently;
use crate::solid::{ray_crossings_odd, signed_volume};
use crate::union_find::UnionFind;

/// Which of the two solids.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solid {
    /// The first solid: the one that stays in place in the motion of Theorem
    /// 5.2.
    A,
    /// The second solid: the one that arrives from far away in the motion.
    B,
}

impl std::fmt::Display for Solid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Solid::A => "A",
            Solid::B => "B",
        })
    }
}

/// A Boolean operation on two solids, each point of space classified by
/// its containment in A and in B.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Operation {
    /// A ∪ B: the surface of each outside the other.
    #[default]
    Union,
    /// A ∩ B: the surface of each inside the other.
    Intersection,
    /// A − B: A's surface outside B, and B's surface inside A turned
    /// inside out (it faces into B's former volume, which is outside).
    Difference,
}

impl Operation {
    /// Whether the part of `solid`'s surface that lies inside the other
    /// solid (`inside`) or outside it is deleted.
    fn deletes(self, solid: Solid, inside: bool) -> bool {
        match (self, solid) {
            (Operation::Union, _) | (Operation::Difference, Solid::A) => inside,
            (Operation::Intersection, _) | (Operation::Difference, Solid::B) => !inside,
        }
    }

    /// The name used in messages and reports.
    pub fn name(self) -> &'static str {
        match self {
            Operation::Union => "union",
            Operation::Intersection => "intersection",
            Operation::Difference => "difference",
        }
    }
}

/// B as the operation takes it: for a difference, turned inside out (its
/// kept part is the wall of the hole it leaves in A, facing into it).
fn operand(b: &TriMesh, op: Operation) -> std::borrow::Cow<'_, TriMesh> {
    if op == Operation::Difference {
        std::borrow::Cow::Owned(TriMesh {
            positions: b.positions.clone(),
            triangles: b.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
        })
    } else {
        std::borrow::Cow::Borrowed(b)
    }
}

/// The combined mesh of A and B and what the union needs of it.
struct Pair {
    mesh: TriMesh,
    /// Vertices of A: `0..split_vertex`; triangles of A: `0..split`.
    split_vertex: u32,
    split: u32,
}

impl Pair {
    /// A's vertices and triangles, then B's (both checked already).
    fn join(a: &TriMesh, b: &TriMesh) -> Result<Pair, TopoError> {
        let n = a.positions.len() + b.positions.len();
        if n >= (1usize << 31) || a.triangles.len() + b.triangles.len() >= (1usize << 31) {
            return Err(MeshError::TooLarge(n).into());
        }
        let split_vertex = a.positions.len() as u32;
        let mut positions = Vec::with_capacity(n);
        positions.extend_from_slice(&a.positions);
        positions.extend_from_slice(&b.positions);
        let mut triangles = Vec::with_capacity(a.triangles.len() + b.triangles.len());
        triangles.extend_from_slice(&a.triangles);
        triangles.extend(b.triangles.iter().map(|t| t.map(|v| v + split_vertex)));
        Ok(Pair {
            mesh: TriMesh {
                positions,
                triangles,
            },
            split_vertex,
            split: a.triangles.len() as u32,
        })
    }

    fn solid_of_vertex(&self, v: u32) -> Solid {
        if v < self.split_vertex {
            Solid::A
        } else {
            Solid::B
        }
    }

    fn solid_of_triangle(&self, t: u32) -> Solid {
        if t < self.split { Solid::A } else { Solid::B }
    }
}

/// Identities: each vertex its own index. The union compares only A's
/// points with B's (never two points of one solid), so what matters is
/// that no point of A shares an identity with one of B: then the
/// perturbation separates the solids consistently where they touch
/// exactly. Two vertices of one solid at one position (a pinch) are
/// separated by it too, which is as consistent, and spares the exact
/// position classes (a hash of every vertex, a tenth of the union).
fn identities(pair: &Pair) -> Vec<u32> {
    (0..pair.mesh.positions.len() as u32).collect()
}

/// What a union needs of one solid besides its mesh, built once: its
/// edge table (with the closedness and orientation summary), its tree,
/// whether a triangle repeats a corner, and its orientation.
struct Parts {
    edges: Edges,
    tree: Bvh,
    /// No triangle repeats a corner.
    proper: bool,
    /// The signed volume is positive: the triangles face outward.
    outward: bool,
    /// The tree the self-crossing check of the solid was made with, in
    /// its own frame ([`crate::intersect::crosses_itself_keeping_tree`]),
    /// when one ran: [`Near`] reuses it.
    checked: Option<FramedTree>,
}

impl Parts {
    fn new(mesh: &TriMesh) -> Result<Parts, UnionError> {
        mesh.check()?;
        let ((edges, proper), (tree, outward)) = rayon::join(
            || {
                rayon::join(
                    || Edges::new(mesh),
                    || {
                        !mesh
                            .triangles
                            .par_iter()
                            .any(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                    },
                )
            },
            || {
                rayon::join(
                    || {
                        Bvh::build(&triangle_boxes(
                            mesh,
                            &mesh.positions,
                            0..mesh.triangles.len(),
                        ))
                    },
                    || signed_volume(&mesh.positions, &mesh.triangles) > 0.0,
                )
            },
        );
        Ok(Parts {
            edges,
            tree: tree.map_err(TopoError::from)?,
            proper,
            outward,
            checked: None,
        })
    }

    /// Every edge has an even number of triangles and no triangle repeats
    /// a corner: the surface bounds a solid, and containment means
    /// something.
    fn closed(&self) -> bool {
        self.proper && self.edges.summary.first_odd.is_none()
    }

    /// Closed, and the two triangles of every edge run along it in
    /// opposite directions.
    fn oriented(&self) -> bool {
        self.proper && self.edges.summary.all_opposite
    }
}

/// A closed surface made ready for unions: its edge table, its tree and
/// its orientation are built once and kept, so that unions of the same
/// solid with many others (a part placed many times, a tool applied
/// again and again) skip them. Peers keep the same on their mesh objects
/// (manifold3d at construction, trueform on first use).
pub struct PreparedSolid {
    mesh: TriMesh,
    parts: Parts,
}

impl PreparedSolid {
    /// Checks `mesh` (indices, finite coordinates) and builds what a union
    /// needs of it. A surface that is not closed is accepted here; the
    /// union refuses it ([`UnionError::NotClosed`]).
    pub fn new(mesh: TriMesh) -> Result<PreparedSolid, UnionError> {
        let parts = Parts::new(&mesh)?;
        Ok(PreparedSolid { mesh, parts })
    }

    /// The surface.
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// Whether it bounds a solid: every edge has an even number of
    /// triangles and no triangle repeats a corner.
    pub fn is_closed(&self) -> bool {
        self.parts.closed()
    }
}

/// Crossings, mod 2, of the ray from `start` towards +x with the
/// triangles of the solid `tree` holds (primitive `i` is triangle
/// `offset + i`): odd iff `start` is inside that solid.
struct Rays<'a> {
    positions: &'a [DVec3],
    triangles: &'a [[u32; 3]],
    ids: &'a [u32],
    /// Identity of every ray's far end: no vertex has it.
    far_id: u32,
}

impl Rays<'_> {
    fn inside(&self, start: SymPoint, tree: &Bvh, offset: u32) -> Option<bool> {
        let sym = |v: u32| SymPoint::new(self.positions[v as usize], self.ids[v as usize]);
        ray_crossings_odd(tree, start, self.far_id, |i| {
            self.triangles[(offset + i) as usize].map(sym)
        })
    }
}

/// Why [`union`] cannot take its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum UnionError {
    /// A solid failed mesh validation, or the geometry kernel or the static
    /// intersections between A and B failed ([`TopoError`] says which).
    #[error(transparent)]
    Topo(#[from] TopoError),
    /// Containment in a surface with boundary (or an edge an odd number
    /// of triangles share) means nothing; the motion (`topology_change`
    /// of the synthesized frame) still gives a result.
    #[error("solid {0} is not closed: an edge has an odd number of triangles")]
    NotClosed(Solid),
    /// The solid intersects itself where it meets the other: the points
    /// where its own curves cross the union's curves would be missing
    /// (the union finds only intersections between A and B), and the
    /// result would crack there. The motion resolves them.
    #[error(
        "solid {0} intersects itself where it meets the other; moving one into the other (the motion of Theorem 5.2) resolves that"
    )]
    SelfIntersecting(Solid),
    /// A ray could not leave the scene (coordinates near the largest
    /// float).
    #[error("the coordinates are too large to cast a ray past the solids")]
    TooLarge,
}

impl From<MeshError> for UnionError {
    fn from(e: MeshError) -> Self {
        UnionError::Topo(e.into())
    }
}

/// The union of the solids bounded by the closed surfaces `a` and `b`
/// (Theorem 5.2; the module docs give the parity this computes). The
/// output's vertices number A's first, then B's (`vertex_origin`),
/// `raw_odd` and `corrected_odd` are the containment parity of each
/// vertex (A's, then B's), and the report has no collisions.
/// `options.scheme`, `float_ccd` and `solid_guard` play no part.
pub fn union(a: &TriMesh, b: &TriMesh, options: &Options) -> Result<Outcome, UnionError> {
    boolean(a, b, Operation::Union, options)
}

/// The operation `op` on the solids bounded by the closed surfaces `a`
/// and `b`: [`union()`]'s containment parity, with the part of each
/// surface inside or outside the other deleted as `op` says (for a
/// difference, B turned inside out first, so that the kept part of B
/// faces into the hole). The output numbers A's vertices first, then
/// B's.
pub fn boolean(
    a: &TriMesh,
    b: &TriMesh,
    op: Operation,
    options: &Options,
) -> Result<Outcome, UnionError> {
    PreparedPair::new(a, b, op)?.exact(options)
}

/// B as `op` takes it ([`operand`]) and what a Boolean builds of each
/// solid alone.
fn prepare<'b>(
    a: &TriMesh,
    b: &'b TriMesh,
    op: Operation,
) -> Result<(std::borrow::Cow<'b, TriMesh>, Parts, Parts), UnionError> {
    let b = operand(b, op);
    let (pa, pb) = rayon::join(|| Parts::new(a), || Parts::new(&b));
    Ok((b, pa?, pb?))
}

/// What [`boolean_robust`] builds of two solids before it intersects
/// them, built once so that a caller can read their closedness from it
/// (the edge tables are a whole-mesh pass each) before it commits to the
/// containment method ([`crate::solids::solid_boolean`]).
pub(crate) struct PreparedPair<'a> {
    a: &'a TriMesh,
    b: std::borrow::Cow<'a, TriMesh>,
    pa: Parts,
    pb: Parts,
    op: Operation,
    /// How long [`prepare`] took: the stage times start that long before
    /// the Boolean itself, whatever a caller did in between (the
    /// self-crossing check).
    prepared_in: std::time::Duration,
}

impl<'a> PreparedPair<'a> {
    /// [`prepare`] of `a` and `b` for `op`.
    pub(crate) fn new(
        a: &'a TriMesh,
        b: &'a TriMesh,
        op: Operation,
    ) -> Result<PreparedPair<'a>, UnionError> {
        let started = Instant::now();
        let (b, pa, pb) = prepare(a, b, op)?;
        Ok(PreparedPair {
            a,
            b,
            pa,
            pb,
            op,
            prepared_in: started.elapsed(),
        })
    }

    /// When the Boolean counts as started: now, less the preparation.
    fn started(&self) -> Instant {
        let now = Instant::now();
        now.checked_sub(self.prepared_in).unwrap_or(now)
    }

    /// Both surfaces are closed: every edge has an even number of
    /// triangles and no triangle repeats a corner.
    pub(crate) fn closed(&self) -> bool {
        self.pa.closed() && self.pb.closed()
    }

    /// Keeps the trees the self-crossing checks of A and B were made
    /// with ([`crate::winding_boolean::needs_arrangement_when_closed`]),
    /// for the pairs across them to be found in.
    pub(crate) fn with_checked_trees(mut self, [ta, tb]: [Option<FramedTree>; 2]) -> Self {
        self.pa.checked = ta;
        self.pb.checked = tb;
        self
    }

    /// [`boolean_robust`] of the pair: the exact Boolean, and where
    /// inputs that are closed 2-manifolds give an output that is not, the
    /// same with B nudged ([`NUDGES`]).
    pub(crate) fn robust(&self, options: &Options) -> Result<Outcome, UnionError> {
        let (a, b, op) = (self.a, self.b.as_ref(), self.op);
        let manifold_inputs = self.pa.oriented() && self.pb.oriented();
        let started = self.started();
        let mut out = unite(a, &self.pa, b, &self.pb, op, options, started)?;
        for k in 1..NUDGES.len() {
            if !manifold_inputs || out.mesh.is_closed_manifold() {
                break;
            }
            let d = nudge(a, b, k);
            let moved = TriMesh {
                positions: b.positions.iter().map(|p| *p + d).collect(),
                triangles: b.triangles.clone(),
            };
            let pm = Parts::new(&moved)?;
            out = unite(a, &self.pa, &moved, &pm, op, options, started)?;
            out.report.perturbation_retries = k;
        }
        Ok(out)
    }

    /// [`boolean`] of the pair.
    pub(crate) fn exact(&self, options: &Options) -> Result<Outcome, UnionError> {
        unite(
            self.a,
            &self.pa,
            &self.b,
            &self.pb,
            self.op,
            options,
            self.started(),
        )
    }
}

/// A ∩ B of two closed solids ([`boolean`], robust as [`union_robust`]).
pub fn intersection(a: &TriMesh, b: &TriMesh, options: &Options) -> Result<Outcome, UnionError> {
    boolean_robust(a, b, Operation::Intersection, options)
}

/// A − B of two closed solids ([`boolean`], robust as [`union_robust`]).
pub fn difference(a: &TriMesh, b: &TriMesh, options: &Options) -> Result<Outcome, UnionError> {
    boolean_robust(a, b, Operation::Difference, options)
}

/// The perturbations of B that [`union_robust`] tries in turn, as
/// (fraction of the scene's diagonal, unit direction): none first, then
/// 2^-30, 2^-26 and 2^-22 of the diagonal along generic directions (along
/// no axis or lattice diagonal). Scale-relative, so they mean the same at
/// any size or offset, and far below any modelling precision.
pub const NUDGES: [(f64, [f64; 3]); 4] = [
    (0.0, [0.0, 0.0, 0.0]),
    (
        1.0 / 1_073_741_824.0,
        [0.801_783_7, 0.534_522_5, 0.267_261_2],
    ),
    (
        16.0 / 1_073_741_824.0,
        [-0.272_165_5, 0.952_579_3, 0.136_082_8],
    ),
    (
        256.0 / 1_073_741_824.0,
        [0.408_248_3, -0.408_248_3, 0.816_496_6],
    ),
];

/// The translation of B for attempt `k` of [`NUDGES`] (zero past the
/// list): its fraction of the diagonal of A's and B's joint bounding box.
pub fn nudge(a: &TriMesh, b: &TriMesh, k: usize) -> DVec3 {
    let Some(&(scale, dir)) = NUDGES.get(k) else {
        return DVec3::ZERO;
    };
    if scale == 0.0 {
        return DVec3::ZERO;
    }
    let (lo, hi) = a
        .positions
        .iter()
        .chain(&b.positions)
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    DVec3::from_array(dir) * (scale * (hi - lo).length())
}

/// [`union()`], robust to coplanar contact. Simulation of simplicity
/// decides every degenerate predicate consistently, but where faces of A
/// and B overlap in one plane the perturbed arrangement is embedded at
/// the unperturbed coordinates, points it keeps apart coincide, and the
/// result can have duplicate triangles or cracks. So when A and B are
/// closed 2-manifolds and the result is not, B is moved by the next of
/// [`NUDGES`] and the union redone (up to three times; the report's
/// `perturbation_retries` counts them, and the output has B where it was
/// moved to). The price is one closed-manifold check of the result. Exact
/// touching that the perturbation resolves well (faces meeting from
/// opposite sides) is left exact: the first attempt moves nothing.
pub fn union_robust(a: &TriMesh, b: &TriMesh, options: &Options) -> Result<Outcome, UnionError> {
    boolean_robust(a, b, Operation::Union, options)
}

/// [`boolean`], robust to coplanar contact as [`union_robust`] is.
pub fn boolean_robust(
    a: &TriMesh,
    b: &TriMesh,
    op: Operation,
    options: &Options,
) -> Result<Outcome, UnionError> {
    PreparedPair::new(a, b, op)?.robust(options)
}

/// [`union()`] of two prepared solids: their edge tables and trees are
/// reused, not rebuilt.
pub fn union_prepared(
    a: &PreparedSolid,
    b: &PreparedSolid,
    options: &Options,
) -> Result<Outcome, UnionError> {
    unite(
        &a.mesh,
        &a.parts,
        &b.mesh,
        &b.parts,
        Operation::Union,
        options,
        Instant::now(),
    )
}

/// The trees the pairs across A and B are found in, when the solids'
/// own trees are not the best ones: only the triangles whose boxes meet
/// the other solid's box can meet it (a small part placed on a big one
/// needs a few of the big one's triangles), and boxes are measured in
/// the [`BoxFrame`] of those triangles (turned CAD parts' flat faces then
/// have flat boxes: EMBER pairs 1.14M candidate pairs → 0.21M). The
/// solids' own trees stay in the world's axes for the containment rays.
struct Near<'p> {
    /// A's tree and B's; `None` when the solids' own trees serve.
    trees: Option<[NearTree<'p>; 2]>,
}

/// One solid's tree of [`Near`].
enum NearTree<'p> {
    /// A tree of the listed triangles (numbered in the joined mesh).
    Listed(Vec<u32>, Bvh),
    /// The self-crossing check's tree of every triangle of the solid
    /// ([`Parts::checked`]), whose triangles start at `offset` in the
    /// joined mesh.
    Checked(&'p Bvh, u32),
}

impl NearTree<'_> {
    fn tree_and_triangles(&self) -> (&Bvh, Primitives<'_>) {
        match self {
            NearTree::Listed(list, tree) => (tree, Primitives::Listed(list)),
            NearTree::Checked(tree, offset) => (tree, Primitives::From(*offset)),
        }
    }
}

/// Triangles of each near set sampled to cost a frame.
const FRAME_SAMPLE: usize = 256;

/// A tree build's cost per triangle (its box and its share of the
/// build), in candidate pairs tested: measured, a 68k-triangle tree took
/// about as long as 130k candidate pairs.
const BUILD_PER_TRIANGLE: f64 = 2.0;

/// Sampled triangles' corners, and how many triangles each stands for.
type Sample = (Vec<[DVec3; 3]>, f64);

/// The corners of every k-th triangle of `tris`, at most [`FRAME_SAMPLE`]
/// of them, and how many triangles each stands for.
fn sample(m: &TriMesh, tris: &[[u32; 3]]) -> Sample {
    let step = tris.len().div_ceil(FRAME_SAMPLE).max(1);
    let corners: Vec<[DVec3; 3]> = tris
        .iter()
        .step_by(step)
        .map(|t| t.map(|v| m.positions[v as usize]))
        .collect();
    let weight = tris.len() as f64 / corners.len().max(1) as f64;
    (corners, weight)
}

/// The cost of finding the pairs across two near sets in `frame`, in
/// candidate pairs: the pairs of the samples' boxes that overlap, scaled
/// up to the whole sets, plus building trees of `to_build` triangles.
fn frame_cost(frame: &BoxFrame, ((a, wa), (b, wb)): &(Sample, Sample), to_build: usize) -> f64 {
    let boxes_b: Vec<Aabb> = b.iter().map(|&p| frame.triangle_box(p)).collect();
    let overlapping: usize = a
        .iter()
        .map(|&p| {
            let x = frame.triangle_box(p);
            boxes_b.iter().filter(|y| x.overlaps(y)).count()
        })
        .sum();
    overlapping as f64 * wa * wb + BUILD_PER_TRIANGLE * to_build as f64
}

impl<'p> Near<'p> {
    fn of(a: &TriMesh, pa: &'p Parts, b: &TriMesh, pb: &'p Parts) -> Result<Near<'p>, UnionError> {
        // The solids' own trees hold every triangle's box already: a box
        // query finds the ones meeting the other's box without a pass
        // over all of them (sorted, for the order the mesh stores them in).
        let meeting = |tree: &Bvh, other: Aabb, offset: u32| -> Vec<u32> {
            let mut near = Vec::new();
            tree.for_each_overlap(&other, |t| near.push(t + offset));
            near.sort_unstable();
            near
        };
        let split = a.triangles.len() as u32;
        let (near_a, near_b) = rayon::join(
            || meeting(&pa.tree, pb.tree.bounds(), 0),
            || meeting(&pb.tree, pa.tree.bounds(), split),
        );
        let tris_a: Vec<[u32; 3]> = near_a.iter().map(|&t| a.triangles[t as usize]).collect();
        let tris_b: Vec<[u32; 3]> = near_b
            .iter()
            .map(|&t| b.triangles[(t - split) as usize])
            .collect();
        let mut frame = BoxFrame::of_triangles(&[(&a.positions, &tris_a), (&b.positions, &tris_b)]);
        let most = |near: usize, all: usize| 2 * near >= all;
        if frame.is_identity()
            && most(near_a.len(), a.triangles.len())
            && most(near_b.len(), b.triangles.len())
        {
            return Ok(Near { trees: None });
        }
        // The frame the pairs are found in: the joint one with new trees
        // of both near sets, or a solid's own, where most of it is near
        // the other and its self-crossing check left a tree of all its
        // triangles in that frame (then only the other's near triangles
        // need a tree, measured in that very frame). Neither is always
        // best: a small part turned otherwise than a big one can hold most
        // of the joint area, and the big one's slivers are then turned in
        // the joint frame (EMBER 79741 − 65004: 210,232 pairs of boxes
        // there, 25,302 in 79741's own frame), or it is the one whose
        // slivers turn (1063852 − 72214: 36,238 against 181,166). So each
        // is costed from a sample of both near sets.
        let samples = (sample(a, &tris_a), sample(b, &tris_b));
        let joint = frame_cost(&frame, &samples, tris_a.len() + tris_b.len());
        let reused = [
            (pa, &near_a, a, tris_b.len()),
            (pb, &near_b, b, tris_a.len()),
        ]
        .iter()
        .enumerate()
        .filter_map(|(k, (parts, near, mesh, other))| {
            let checked = parts.checked.as_ref()?;
            most(near.len(), mesh.triangles.len())
                .then(|| (k, frame_cost(&checked.frame, &samples, *other), checked))
        })
        .filter(|&(_, cost, _)| cost < joint)
        .min_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(k, _, checked)| (k, checked));
        if let Some((_, checked)) = reused {
            frame = checked.frame;
        }
        let listed =
            |m: &TriMesh, tris: &[[u32; 3]], near: Vec<u32>| -> Result<NearTree<'p>, UnionError> {
                let boxes: Vec<Aabb> = tris
                    .par_iter()
                    .map(|t| frame.triangle_box(t.map(|v| m.positions[v as usize])))
                    .collect();
                Ok(NearTree::Listed(
                    near,
                    Bvh::build(&boxes).map_err(TopoError::from)?,
                ))
            };
        let trees = match reused {
            Some((0, checked)) => [
                NearTree::Checked(&checked.tree, 0),
                listed(b, &tris_b, near_b)?,
            ],
            Some((_, checked)) => [
                listed(a, &tris_a, near_a)?,
                NearTree::Checked(&checked.tree, split),
            ],
            None => {
                let (ta, tb) =
                    rayon::join(|| listed(a, &tris_a, near_a), || listed(b, &tris_b, near_b));
                [ta?, tb?]
            }
        };
        Ok(Near { trees: Some(trees) })
    }

    fn candidates<'a>(&'a self, pa: &'a Parts, pb: &'a Parts, split: u32) -> Candidates<'a> {
        match &self.trees {
            None => Candidates::Across {
                first: &pa.tree,
                first_triangles: Primitives::From(0),
                second: &pb.tree,
                second_triangles: Primitives::From(split),
            },
            Some([ta, tb]) => {
                let (first, first_triangles) = ta.tree_and_triangles();
                let (second, second_triangles) = tb.tree_and_triangles();
                Candidates::Across {
                    first,
                    first_triangles,
                    second,
                    second_triangles,
                }
            }
        }
    }
}

// One argument per part of the problem; a struct would only rename them.
#[allow(clippy::too_many_arguments)]
fn unite(
    a: &TriMesh,
    pa: &Parts,
    b: &TriMesh,
    pb: &Parts,
    op: Operation,
    options: &Options,
    started: Instant,
) -> Result<Outcome, UnionError> {
    for (solid, parts) in [(Solid::A, pa), (Solid::B, pb)] {
        if !parts.closed() {
            return Err(UnionError::NotClosed(solid));
        }
    }
    let pair = Pair::join(a, b)?;
    let t = started;
    let mesh = &pair.mesh;
    let pos = &mesh.positions;
    let edges = pa.edges.joined(&pb.edges, pair.split_vertex, pair.split);
    let ids = identities(&pair);
    let near = Near::of(a, pa, b, pb)?;
    let oriented = pa.oriented() && pb.oriented();
    // A difference takes B inside out: then B faces inward.
    let outward = pa.outward && pb.outward == (op != Operation::Difference);
    let limit = options
        .max_intersecting_pairs
        .unwrap_or_else(|| default_pair_limit(mesh.triangles.len()));
    let x = intersections_among(
        mesh,
        pos,
        &edges,
        &ids,
        near.candidates(pa, pb, pair.split),
        limit,
        &AtomicBool::new(false),
    )
    .map_err(TopoError::from)?;
    // A triple point of A, A and B needs two triangles of A that both
    // meet B and meet each other: testing the triangles of each solid that
    // meet the other (a few thousand) finds every one the union would
    // miss.
    for (solid, side) in [(Solid::A, 0usize), (Solid::B, 1)] {
        let mut meeting: Vec<u32> = x
            .pairs
            .iter()
            .map(|p| if side == 0 { p.0 } else { p.1 })
            .collect();
        meeting.sort_unstable();
        meeting.dedup();
        if any_intersection_among(mesh, pos, &ids, &meeting).map_err(TopoError::from)? {
            return Err(UnionError::SelfIntersecting(solid));
        }
    }
    let t_intersect = t.elapsed().as_secs_f64();

    // Containment parity: one ray per component of uncut edges.
    let t = Instant::now();
    let n = pos.len();
    let mut sets = UnionFind::new(n);
    for (e, &[u, v]) in edges.ends.iter().enumerate() {
        if !x.cut_edges[e] {
            sets.union(u, v);
        }
    }
    let far_id = u32::try_from(n).map_err(|_| MeshError::TooLarge(n))?;
    let rays = Rays {
        positions: pos,
        triangles: &mesh.triangles,
        ids: &ids,
        far_id,
    };
    let other = |s: Solid| match s {
        Solid::A => (&pb.tree, pair.split),
        Solid::B => (&pa.tree, 0),
    };
    let mut odd = vec![false; n];
    let mut cast = 0usize;
    for v in 0..n as u32 {
        let root = sets.find(v);
        odd[v as usize] = if root == v {
            let solid = pair.solid_of_vertex(v);
            let (tree, offset) = other(solid);
            cast += 1;
            let inside = rays
                .inside(
                    SymPoint::new(pos[v as usize], ids[v as usize]),
                    tree,
                    offset,
                )
                .ok_or(UnionError::TooLarge)?;
            op.deletes(solid, inside)
        } else {
            // Roots are the smallest vertex of their component, so they
            // come first.
            odd[root as usize]
        };
    }
    // A region no vertex reaches: the ray starts at a point of the
    // region's triangle, with an identity no vertex or far end has.
    let sample = |k: u32, t: u32, w: [f64; 3]| {
        let corners = *mesh.triangles.get(t as usize)?;
        let p = corners
            .iter()
            .zip(w)
            .map(|(&c, wi)| pos[c as usize] * wi)
            .sum::<DVec3>();
        let id = far_id.checked_add(1)?.checked_add(k)?;
        let solid = pair.solid_of_triangle(t);
        let (tree, offset) = other(solid);
        let inside = rays.inside(SymPoint::new(p, id), tree, offset)?;
        Some(op.deletes(solid, inside))
    };
    let t_parity = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let Cut {
        mesh: mut out,
        report: cut_report,
        origin,
        ..
    } = cut(
        mesh,
        pos,
        &edges,
        &ids,
        &x,
        Deletion::OddExact(&odd),
        Some(&sample),
    );
    // Both surfaces closed and consistently oriented, both outward: each
    // kept piece keeps its triangle's orientation (the cut triangulates
    // in the triangle's own chart, counter-clockwise), and along a curve
    // the outward pieces of A and B meet running opposite ways, so the
    // union is consistently oriented by construction (points merged where
    // rounding made them equal only identify vertices). Otherwise, or if
    // rounding made curve pieces cross in a chart, the orientation pass
    // runs.
    let consistent = cut_report.constraint_splits == 0
        && cut_report.dropped_constraints == 0
        && oriented
        && outward;
    let flips = if options.orient && !consistent {
        orient_consistently(&mut out)
    } else {
        0
    };
    let t_cut = t.elapsed().as_secs_f64();
    let odd_count = odd.iter().filter(|&&o| o).count();
    let report = Report {
        collisions: 0,
        collision_tests: 0,
        containment_rays: cast + cut_report.sampled_regions,
        raw_odd_vertices: odd_count,
        corrected_odd_vertices: odd_count,
        cut: cut_report,
        solved_components: 0,
        unsolved_components: 0,
        perturbation_retries: 0,
        solid_input: oriented,
        orientation_flips: flips,
        timings: Timings {
            collisions: 0.0,
            intersections: t_intersect,
            correction: t_parity,
            cut: t_cut,
            total: started.elapsed().as_secs_f64(),
        },
        ..Report::of_intersections(&x)
    };
    Ok(Outcome {
        mesh: out,
        report,
        raw_odd: odd.clone(),
        corrected_odd: odd,
        intersections: x,
        vertex_origin: origin,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::winding_boolean::needs_arrangement_when_closed;

    /// A prism over an ellipse of `n` points (semi-axes `2r` and `r`,
    /// height 0.3), its caps fans from one outline point, turned by
    /// `turn` and moved by `at`.
    fn fan_prism(n: u32, r: f64, turn: impl Fn(DVec3) -> DVec3, at: DVec3) -> TriMesh {
        let outline = crate::intersect::tests::ellipse(n as usize, 2.0 * r, r);
        crate::intersect::tests::fan_prism(&outline, 0.3, turn, at)
    }

    /// Two turned CAD-like parts in one frame: the pairs across them are
    /// found in the tree A's self-crossing check built (A is the bigger
    /// one near B: the same pairs, one tree build less), with B's near
    /// triangles measured in A's very frame, and the difference is the
    /// same mesh, vertex for vertex, as with trees built for the pairs.
    #[test]
    fn the_self_crossing_checks_tree_finds_the_pairs_across_in_one_frame() {
        let turn = crate::intersect::tests::turn;
        let a = fan_prism(96, 1.0, turn, DVec3::ZERO);
        let b = fan_prism(40, 0.7, turn, turn(DVec3::new(0.9, 0.2, 0.15)));
        let op = Operation::Difference;
        let pair = PreparedPair::new(&a, &b, op).unwrap();
        assert!(pair.closed());
        let (needs, trees) = needs_arrangement_when_closed(&a, &b, pair.closed()).unwrap();
        assert!(!needs, "neither part crosses itself");
        assert!(trees.iter().all(Option::is_some));
        let pair = pair.with_checked_trees(trees);
        let near = Near::of(pair.a, &pair.pa, &pair.b, &pair.pb).unwrap();
        assert!(
            matches!(
                near.trees,
                Some([NearTree::Checked(_, 0), NearTree::Listed(..)])
            ),
            "A's checked tree serves"
        );
        let options = Options::default();
        let reused = pair.robust(&options).unwrap();
        let built = PreparedPair::new(&a, &b, op)
            .unwrap()
            .robust(&options)
            .unwrap();
        assert!(reused.report.intersecting_pairs > 0, "the parts cross");
        assert_eq!(reused.mesh, built.mesh);
        assert!(reused.mesh.is_closed_manifold());
    }
}
