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

use std::borrow::Cow;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use glam::DVec3;
use holey_geom::{BoxFrame, Bvh, SymPoint};
use rayon::prelude::*;

use crate::clean_solids::needs_arrangement_when_closed;
use crate::cut::{Cut, Deletion, cut};
use crate::engine::{Options, Outcome, Report, Timings, TopoError, split_new_pinches};
use crate::intersect::{
    FramedTree, any_intersection_among, crossing_pairs_of_marked, default_pair_limit,
    intersecting_pair_count, intersections_among, triangle_boxes,
};
use crate::mesh::{Edges, MeshError, TriMesh, repeats_a_corner};
use crate::orient::orient_consistently;
use crate::solid::{ray_crossings_odd_in, signed_volume};
use crate::union_find::UnionFind;
use crate::zero_area::repaired;

mod near;
use near::{Near, NearSets};

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

/// A solid (checked) as a Boolean takes it: without its zero-area
/// triangles ([`crate::zero_area`]), which the symbolic perturbation
/// would turn into slivers overlapping their neighbours (the solid would
/// seem to cross itself there). The same points, so the same solid.
pub(crate) fn solid(m: &TriMesh) -> (Cow<'_, TriMesh>, usize) {
    match repaired(m) {
        Some((repaired, r)) => (Cow::Owned(repaired), r.pinched_removed + r.flat_removed),
        None => (Cow::Borrowed(m), 0),
    }
}

/// B as the operation takes it ([`solid`]): for a difference, turned
/// inside out (its kept part is the wall of the hole it leaves in A,
/// facing into it).
fn operand(b: &TriMesh, op: Operation) -> (Cow<'_, TriMesh>, usize) {
    let (b, removed) = solid(b);
    if op == Operation::Difference {
        let inside_out = TriMesh {
            positions: b.positions.clone(),
            triangles: b.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
        };
        (Cow::Owned(inside_out), removed)
    } else {
        (b, removed)
    }
}

/// A and B as a Boolean takes them ([`solid`], [`operand`]), and how many
/// zero-area triangles the two lost.
fn operands<'a>(a: &'a TriMesh, b: &'a TriMesh, op: Operation) -> Operands<'a> {
    let ((a, in_a), (b, in_b)) = (solid(a), operand(b, op));
    (a, b, in_a + in_b)
}

type Operands<'a> = (Cow<'a, TriMesh>, Cow<'a, TriMesh>, usize);

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
/// surface's edge table and orientation ([`Surface`]) and a tree of its
/// triangles.
struct Parts {
    surface: Surface,
    /// A tree of every triangle's box, for the containment rays and the
    /// pairs across: in the world's axes, or the self-crossing check's in
    /// the frame it chose ([`crate::intersect::crosses_itself_keeping_tree`],
    /// [`PreparedPair::with_checks`]), which [`Near`] then reuses.
    tree: FramedTree,
}

/// What a union needs of one solid's surface: its edge table (with the
/// closedness and orientation summary), whether a triangle repeats a
/// corner, and its orientation.
struct Surface {
    edges: Edges,
    /// No triangle repeats a corner.
    proper: bool,
    /// The signed volume is positive: the triangles face outward.
    outward: bool,
}

impl Surface {
    /// The surface of `mesh`, whose indices and coordinates are checked.
    fn of_checked(mesh: &TriMesh) -> Surface {
        let ((edges, proper), outward) = rayon::join(
            || {
                rayon::join(
                    || Edges::new(mesh),
                    || !mesh.triangles.par_iter().any(repeats_a_corner),
                )
            },
            || signed_volume(&mesh.positions, &mesh.triangles) > 0.0,
        );
        Surface {
            edges,
            proper,
            outward,
        }
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

    /// No edge has more than two triangles: where one has four (two
    /// cubes of a lattice meeting along an edge) the solid touches
    /// itself, which containment parity cannot tell from two sheets
    /// crossing.
    fn manifold_edges(&self) -> bool {
        self.edges.summary.all_opposite
            || (0..self.edges.len())
                .into_par_iter()
                .all(|e| self.edges.triangles(e).len() <= 2)
    }
}

/// A tree of every triangle of `mesh` (checked) in the world's axes.
fn world_tree(mesh: &TriMesh) -> Result<FramedTree, UnionError> {
    let boxes = triangle_boxes(mesh, &mesh.positions, 0..mesh.triangles.len());
    Ok(FramedTree {
        frame: BoxFrame::IDENTITY,
        tree: Bvh::build(&boxes).map_err(TopoError::from)?,
    })
}

impl Parts {
    fn new(mesh: &TriMesh) -> Result<Parts, UnionError> {
        mesh.check()?;
        Parts::of_checked(mesh)
    }

    /// [`Parts::new`] of a mesh already checked.
    fn of_checked(mesh: &TriMesh) -> Result<Parts, UnionError> {
        let (surface, tree) = rayon::join(|| Surface::of_checked(mesh), || world_tree(mesh));
        Ok(Parts {
            surface,
            tree: tree?,
        })
    }

    fn closed(&self) -> bool {
        self.surface.closed()
    }

    fn oriented(&self) -> bool {
        self.surface.oriented()
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

/// Containment in the other solid, by exact rays (simulation of
/// simplicity, in the same perturbed world as the intersections): a ray
/// from a point of one solid crosses the other's triangles an odd number
/// of times exactly when the point is inside it.
struct Containment<'a> {
    pair: &'a Pair,
    ids: &'a [u32],
    /// A's tree of all its triangles, then B's.
    trees: [&'a FramedTree; 2],
    op: Operation,
    /// Identity of every ray's far end: no vertex has it.
    far_id: u32,
}

impl<'a> Containment<'a> {
    fn new(
        pair: &'a Pair,
        ids: &'a [u32],
        trees: [&'a FramedTree; 2],
        op: Operation,
    ) -> Result<Containment<'a>, UnionError> {
        let n = pair.mesh.positions.len();
        let far_id = u32::try_from(n).map_err(|_| MeshError::TooLarge(n))?;
        Ok(Containment {
            pair,
            ids,
            trees,
            op,
            far_id,
        })
    }

    /// Whether `op` deletes `start`, a point of `solid`: whether it is
    /// inside the other solid, read as the operation reads it. `None`
    /// when the ray cannot leave the scene.
    fn deletes(&self, solid: Solid, start: SymPoint) -> Option<bool> {
        let (tree, offset) = match solid {
            Solid::A => (self.trees[1], self.pair.split),
            Solid::B => (self.trees[0], 0),
        };
        let (positions, triangles) = (&self.pair.mesh.positions, &self.pair.mesh.triangles);
        let sym = |v: u32| SymPoint::new(positions[v as usize], self.ids[v as usize]);
        let inside = ray_crossings_odd_in(&tree.frame, &tree.tree, start, self.far_id, |i| {
            triangles[(offset + i) as usize].map(sym)
        })?;
        Some(self.op.deletes(solid, inside))
    }

    /// Every vertex's parity (whether the operation deletes it), from one
    /// ray per component of the edges no curve cuts (containment is
    /// constant along them), and how many rays were cast.
    fn vertex_parities(
        &self,
        edges: &Edges,
        cut_edges: &[bool],
    ) -> Result<(Vec<bool>, usize), UnionError> {
        let positions = &self.pair.mesh.positions;
        let n = positions.len();
        let mut sets = UnionFind::new(n);
        for (e, &[u, v]) in edges.ends.iter().enumerate() {
            if !cut_edges[e] {
                sets.union(u, v);
            }
        }
        let mut odd = vec![false; n];
        let mut cast = 0usize;
        for v in 0..n as u32 {
            let root = sets.find(v);
            odd[v as usize] = if root == v {
                cast += 1;
                let start = SymPoint::new(positions[v as usize], self.ids[v as usize]);
                self.deletes(self.pair.solid_of_vertex(v), start)
                    .ok_or(UnionError::TooLarge)?
            } else {
                // Roots are the smallest vertex of their component, so
                // they come first.
                odd[root as usize]
            };
        }
        Ok((odd, cast))
    }

    /// The parity of a region no vertex reaches (the cut's `k`-th such):
    /// the ray starts at the point of weights `w` in triangle `t`, with an
    /// identity no vertex or far end has.
    fn sample(&self, k: u32, t: u32, w: [f64; 3]) -> Option<bool> {
        let mesh = &self.pair.mesh;
        let corners = *mesh.triangles.get(t as usize)?;
        let p = corners
            .iter()
            .zip(w)
            .map(|(&c, wi)| mesh.positions[c as usize] * wi)
            .sum::<DVec3>();
        let id = self.far_id.checked_add(1)?.checked_add(k)?;
        self.deletes(self.pair.solid_of_triangle(t), SymPoint::new(p, id))
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

/// What [`prepare`] gives: B as the operation takes it, what a Boolean
/// builds of each solid alone, and their near sets.
type Prepared<'a> = (Operands<'a>, Parts, Parts, NearSets);

/// B as `op` takes it ([`operand`]), what a Boolean builds of each
/// solid alone, and where the pairs across them are looked for.
fn prepare<'a>(a: &'a TriMesh, b: &'a TriMesh, op: Operation) -> Result<Prepared<'a>, UnionError> {
    a.check()?;
    b.check()?;
    let (a, b, removed) = operands(a, b, op);
    let ((pa, pb), sets) = rayon::join(
        || rayon::join(|| Parts::of_checked(&a), || Parts::of_checked(&b)),
        || NearSets::of(&a, &b),
    );
    Ok(((a, b, removed), pa?, pb?, sets))
}

/// What [`boolean_robust`] builds of two solids before it intersects
/// them, built once so that a caller can read their closedness from it
/// (the edge tables are a whole-mesh pass each) before it commits to the
/// containment method ([`crate::solids::solid_boolean`]).
pub(crate) struct PreparedPair<'a> {
    a: Cow<'a, TriMesh>,
    b: Cow<'a, TriMesh>,
    /// Zero-area triangles the two lost ([`solid`]).
    zero_area_removed: usize,
    pa: Parts,
    pb: Parts,
    op: Operation,
    /// Where the pairs across A and B are looked for.
    near: NearSets,
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
        let ((a, b, zero_area_removed), pa, pb, near) = prepare(a, b, op)?;
        Ok(PreparedPair {
            a,
            b,
            zero_area_removed,
            pa,
            pb,
            op,
            near,
            prepared_in: started.elapsed(),
        })
    }

    /// [`PreparedPair::new`], with the self-crossing checks of A and B
    /// ([`needs_arrangement_when_closed`]) run alongside the solids' edge
    /// tables (the two leave each other's idle core busy), and each
    /// check's tree built in the frame [`NearSets::with_check_frames`]
    /// picks, then kept for the rays and the pairs across. `None` when
    /// the winding-number arrangement is needed instead: a surface is
    /// open, has an edge of more than two triangles, crosses itself or
    /// has a piece inside another.
    pub(crate) fn with_checks(
        a: &'a TriMesh,
        b: &'a TriMesh,
        op: Operation,
    ) -> Result<Option<PreparedPair<'a>>, UnionError> {
        let started = Instant::now();
        a.check()?;
        b.check()?;
        let (a, b, zero_area_removed) = operands(a, b, op);
        let ((sa, sb), (near, checked)) = rayon::join(
            || rayon::join(|| Surface::of_checked(&a), || Surface::of_checked(&b)),
            || {
                let (near, frames) = NearSets::with_check_frames(&a, &b);
                // Closedness is known only from the edge tables: the
                // check assumes it, and an open surface needs the
                // arrangement whatever the check says.
                let checked = needs_arrangement_when_closed(&a, &b, true, frames);
                (near, checked)
            },
        );
        if !(sa.closed() && sb.closed() && sa.manifold_edges() && sb.manifold_edges()) {
            return Ok(None);
        }
        let (needs, [ta, tb]) = checked?;
        if needs {
            return Ok(None);
        }
        // A check whose tree does not hold every triangle (some repeat
        // another) leaves none to keep.
        let parts = |surface: Surface, tree: Option<FramedTree>, m: &TriMesh| {
            Ok::<_, UnionError>(Parts {
                surface,
                tree: tree.map_or_else(|| world_tree(m), Ok)?,
            })
        };
        Ok(Some(PreparedPair {
            pa: parts(sa, ta, &a)?,
            pb: parts(sb, tb, &b)?,
            a,
            b,
            zero_area_removed,
            op,
            near,
            prepared_in: started.elapsed(),
        }))
    }

    /// When the Boolean counts as started: now, less the preparation.
    fn started(&self) -> Instant {
        let now = Instant::now();
        now.checked_sub(self.prepared_in).unwrap_or(now)
    }

    /// [`boolean_robust`] of the pair: the exact Boolean, and where
    /// inputs that are closed 2-manifolds give an output that is not, the
    /// same with B nudged ([`NUDGES`]).
    pub(crate) fn robust(&self, options: &Options) -> Result<Outcome, UnionError> {
        let mut out = self.exact(options)?;
        let mut best = None;
        let checking = Instant::now();
        if self.first_is_clean(&mut out, &mut best) {
            // The check of the result is part of the Boolean.
            out.report.timings.total += checking.elapsed().as_secs_f64();
            return Ok(out);
        }
        self.nudged(options, out, best)
    }

    /// The outcome `out` of the pair, its report saying what the inputs'
    /// zero-area triangles lost.
    fn with_repair(&self, mut out: Outcome) -> Outcome {
        out.report.zero_area_removed = self.zero_area_removed;
        out
    }

    /// Whether the exact attempt `out` can be wrong at exact coordinates
    /// though the perturbed world's answer is right: its cut merged
    /// points, or A and B cross nowhere, where they may still touch (a
    /// face resting on a face, an edge along an edge), which the
    /// perturbation decides as apart or overlapping.
    pub(crate) fn suspect(&self, out: &Outcome) -> bool {
        out.report.cut.merged_points > 0 || out.intersections.pairs.is_empty()
    }

    /// Whether the exact attempt `out`, [`suspect`](Self::suspect) only
    /// for the points its cut merged, is the answer anyway: the merges
    /// are curve points meeting at exact coordinates (an edge crossing an
    /// edge, a vertex on a face: a solid against its mirror image), not
    /// faces lying on faces. Then, with both solids oriented, the
    /// perturbed world's surface is the boundary of the Boolean, and at
    /// exact coordinates it can only touch itself where points met,
    /// which the cut glued; what can still go wrong is rounding there,
    /// slivers of the cut that cross. So it must be:
    /// - crossing the other solid somewhere (solids that only touch are
    ///   the arrangement's to decide);
    /// - free of exactly coplanar candidate pairs of A and B
    ///   ([`Intersections::coplanar_candidates`]): without them no face
    ///   of the result lies on another (no wall), and no merge glued
    ///   points of a face's overlay;
    /// - a closed 2-manifold (the caller's test: both callers make it
    ///   anyway);
    /// - crossing itself nowhere, counted exactly among the triangles
    ///   with a point of the cut ([`crossing_pairs_of_marked`]): the
    ///   others are whole input triangles, which cross neither one
    ///   another (a triangle of A crossing one of B would have been cut,
    ///   and the check keeps each solid free of its own crossings) nor,
    ///   but through a marked one, anything else. The count goes in the
    ///   report: the whole output's, but for crossings an unchecked
    ///   input brought along.
    ///
    /// The cost follows the cut, not the surface: on two 262k-triangle
    /// spheres, one the other's mirror image (1,236 merged points), it
    /// replaces the arrangement and a whole-output check.
    pub(crate) fn clean_despite_merges(&self, out: &mut Outcome) -> bool {
        if !self.both_oriented()
            || out.intersections.pairs.is_empty()
            || out.intersections.coplanar_candidates > 0
        {
            return false;
        }
        let origin = &out.vertex_origin;
        let made = |v: u32| origin.get(v as usize).is_none_or(|&o| o == u32::MAX);
        let marked: Vec<bool> = (out.mesh.triangles.par_iter())
            .map(|t| t.iter().any(|&v| made(v)))
            .collect();
        let crossing = crossing_pairs_of_marked(&out.mesh, &marked);
        out.report.output_intersecting_pairs = Some(crossing);
        crossing == 0
    }

    /// Both surfaces are closed and consistently oriented: their winding
    /// numbers mean what containment means.
    pub(crate) fn both_oriented(&self) -> bool {
        self.pa.oriented() && self.pb.oriented()
    }

    /// Whether the first, exact attempt `out` is the answer: inputs that
    /// are not both oriented 2-manifolds get no other; otherwise it must
    /// be a closed 2-manifold that does not cross itself. An attempt that
    /// crosses itself may move into `best` ([`keep_if_clean`]).
    pub(crate) fn first_is_clean(&self, out: &mut Outcome, best: &mut Option<Outcome>) -> bool {
        if !self.both_oriented() {
            return true;
        }
        // Exact in the perturbed world, the result can cross itself only
        // where points it keeps apart were rounded onto each other (a cut
        // that merged points: mirror images, quarter turns) or where the
        // solids touch without crossing ([`PreparedPair::suspect`]); only
        // then is it counted. So can it fold onto itself there: faces
        // facing opposite ways over one another (a cube less its copy
        // came out as three of its faces, twice, closed and of no
        // volume).
        out.mesh.is_closed_manifold()
            && (!self.suspect(out)
                || self.clean_despite_merges(out)
                || (keep_if_clean(out, best)
                    && crate::coplanar::wall_groups(&out.mesh.positions, &out.mesh.triangles)
                        .is_empty()))
    }

    /// The attempts with B nudged ([`NUDGES`]) after the exact one `out`
    /// was not clean: the first closed 2-manifold that does not cross
    /// itself, else the closed one that crosses itself least (`best`
    /// holds the exact one's rank), its crossings counted in the report
    /// (never silently), else the last attempt.
    pub(crate) fn nudged(
        &self,
        options: &Options,
        mut out: Outcome,
        mut best: Option<Outcome>,
    ) -> Result<Outcome, UnionError> {
        let (a, b, op) = (self.a.as_ref(), self.b.as_ref(), self.op);
        let started = self.started();
        for k in 1..NUDGES.len() {
            let d = nudge(a, b, k);
            let moved = TriMesh {
                positions: b.positions.iter().map(|p| *p + d).collect(),
                triangles: b.triangles.clone(),
            };
            let pm = Parts::new(&moved)?;
            out = unite(a, &self.pa, &moved, &pm, op, options, started, None)?;
            out.report.perturbation_retries = k;
            if out.mesh.is_closed_manifold() && keep_if_clean(&mut out, &mut best) {
                return Ok(self.with_repair(out));
            }
        }
        Ok(self.with_repair(best.unwrap_or(out)))
    }

    /// [`boolean`] of the pair, its report saying what the inputs'
    /// zero-area triangles lost.
    pub(crate) fn exact(&self, options: &Options) -> Result<Outcome, UnionError> {
        unite(
            &self.a,
            &self.pa,
            &self.b,
            &self.pb,
            self.op,
            options,
            self.started(),
            Some(&self.near),
        )
        .map(|out| self.with_repair(out))
    }
}

/// Counts the crossing pairs of the closed result `out` into its report;
/// true when there are none. Otherwise `out` moves into `best` (leaving
/// an empty outcome) if it crosses itself less than `best` does (an
/// uncounted result ranks last).
fn keep_if_clean(out: &mut Outcome, best: &mut Option<Outcome>) -> bool {
    let crossing = intersecting_pair_count(&out.mesh, usize::MAX).ok();
    out.report.output_intersecting_pairs = crossing;
    if crossing == Some(0) {
        return true;
    }
    let rank = |c: Option<usize>| c.unwrap_or(usize::MAX);
    if best
        .as_ref()
        .is_none_or(|b| rank(crossing) < rank(b.report.output_intersecting_pairs))
    {
        // The caller only replaces `out` from here on: no copy needed.
        *best = Some(std::mem::take(out));
    }
    false
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
/// result can have duplicate triangles or cracks, or cross itself where
/// the cut rounded points it keeps apart onto each other. So when A and
/// B are closed 2-manifolds and the result is not, or crosses itself, B
/// is moved by the next of [`NUDGES`] and the union redone (up to three
/// times; the report's `perturbation_retries` counts them, and the output
/// has B where it was moved to). The first clean attempt is kept, else
/// the closed one that crosses itself least, its crossing pairs in
/// [`Report::output_intersecting_pairs`]. The price is one closed-manifold
/// check of the result, and an exact count of its crossing pairs only
/// where the cut merged points or B was moved. Exact touching that the
/// perturbation resolves well (faces meeting from opposite sides) is left
/// exact: the first attempt moves nothing.
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
        None,
    )
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
    near_sets: Option<&NearSets>,
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
    let edges = pa
        .surface
        .edges
        .joined(&pb.surface.edges, pair.split_vertex, pair.split);
    let ids = identities(&pair);
    // Near sets found for another B (moved by a nudge) would miss pairs.
    let found;
    let near_sets = match near_sets {
        Some(sets) => sets,
        None => {
            found = NearSets::of(a, b);
            &found
        }
    };
    let near = Near::of(a, pa, b, pb, near_sets)?;
    let oriented = pa.oriented() && pb.oriented();
    // A difference takes B inside out: then B faces inward.
    let outward = pa.surface.outward && pb.surface.outward == (op != Operation::Difference);
    let limit = options
        .max_intersecting_pairs
        .unwrap_or_else(|| default_pair_limit(mesh.triangles.len()));
    let x = intersections_among(
        mesh,
        pos,
        &edges,
        &ids,
        near.candidates(),
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
    let containment = Containment::new(&pair, &ids, [&pa.tree, &pb.tree], op)?;
    let (odd, cast) = containment.vertex_parities(&edges, &x.cut_edges)?;
    let sample = |k: u32, t: u32, w: [f64; 3]| containment.sample(k, t, w);
    let t_parity = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let Cut {
        mesh: mut out,
        report: mut cut_report,
        mut origin,
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
    // Kept pieces that touch at a point alone (curves crossing exactly
    // there: a solid and its mirror image, a copy turned a quarter turn
    // about its centre) get one vertex each, so the result is a
    // 2-manifold at vertices as well as at edges. In the perturbed world
    // the kept surface is the boundary of a solid in general position, a
    // 2-manifold: a pinch can only come from gluing points the
    // perturbation kept apart, so a cut that merged none is not searched
    // (the search is a pass over every vertex's fans, 5% of an EMBER
    // difference).
    if cut_report.merged_points > 0 {
        cut_report.pinches_split = split_new_pinches(&mut out, &mut origin, mesh);
    }
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
        output_intersecting_pairs: None,
        solid_input: oriented,
        zero_area_removed: 0,
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
    use crate::cut::MAX_SAMPLED_REGIONS;
    use crate::test_meshes::cuboid;
    use near::NearTree;

    /// A prism over an ellipse of `n` points (semi-axes `2r` and `r`,
    /// height 0.3), its caps fans from one outline point, turned by
    /// `turn` and moved by `at`.
    fn fan_prism(n: u32, r: f64, turn: impl Fn(DVec3) -> DVec3, at: DVec3) -> TriMesh {
        let outline = crate::intersect::tests::ellipse(n as usize, 2.0 * r, r);
        crate::intersect::tests::fan_prism(&outline, 0.3, turn, at)
    }

    /// A wall of one big box crossed by more thin slabs than a motion's
    /// cut samples (`MAX_SAMPLED_REGIONS`): where a slab passes through
    /// the wall, the wall's part inside the slab is a rectangle bounded
    /// by the curve alone, with no vertex of the box in it (the bands two
    /// Menger sponges make where one's slab crosses the other's wall).
    /// Every such region is sampled by a ray and deleted: the union is
    /// one closed 2-manifold whose volume is the closed form, the box's
    /// and the slabs' parts outside it. With the cap, the regions past it
    /// were kept, each leaving four edges of three triangles.
    #[test]
    fn a_union_samples_every_vertex_free_region_of_a_wall_crossed_by_many_slabs() {
        let slabs = MAX_SAMPLED_REGIONS + 44;
        let (h, step) = (0.002, 1.8 / slabs as f64);
        let mut a = TriMesh::default();
        for k in 0..slabs {
            let z = -0.9 + step * k as f64;
            a.append(&cuboid(
                DVec3::new(-2.0, -0.5, z),
                DVec3::new(0.0, 0.5, z + h),
            ));
        }
        let b = cuboid(DVec3::splat(-1.0), DVec3::splat(1.0));
        let out = union(&a, &b, &Options::default()).unwrap();
        let cut = &out.report.cut;
        assert_eq!(cut.undecided, 0, "{cut:?}");
        assert!(cut.sampled_regions >= slabs, "{cut:?}");
        assert!(out.mesh.is_closed_manifold());
        let want = 8.0 + slabs as f64 * h;
        let got = signed_volume(&out.mesh.positions, &out.mesh.triangles);
        assert!(
            (got - want).abs() < 1e-9 * want,
            "volume {got}, want {want}"
        );
        let info = holey_mesh::analysis::analyze(&holey_mesh::PolyMesh::from(&out.mesh));
        assert_eq!(info.components, 1);
    }

    /// The difference through the trees kept from the self-crossing
    /// checks, and the same through trees built for the pairs across
    /// ([`PreparedPair::new`]): the same mesh, vertex for vertex.
    fn same_as_with_trees_built(a: &TriMesh, b: &TriMesh, pair: &PreparedPair) {
        let options = Options::default();
        let reused = pair.robust(&options).unwrap();
        let built = PreparedPair::new(a, b, pair.op)
            .unwrap()
            .robust(&options)
            .unwrap();
        assert!(reused.report.intersecting_pairs > 0, "the parts cross");
        assert_eq!(reused.mesh, built.mesh);
        assert!(reused.mesh.is_closed_manifold());
    }

    /// Two turned CAD-like parts in one frame, each mostly near the
    /// other: the pairs across them are found in the trees their
    /// self-crossing checks built, in the joint frame, and no tree is
    /// built for them.
    #[test]
    fn the_self_crossing_checks_trees_find_the_pairs_across_in_one_frame() {
        let turn = crate::intersect::tests::turn;
        let a = fan_prism(96, 1.0, turn, DVec3::ZERO);
        let b = fan_prism(40, 0.7, turn, turn(DVec3::new(0.9, 0.2, 0.15)));
        let pair = PreparedPair::with_checks(&a, &b, Operation::Difference).unwrap();
        let pair = pair.expect("both closed, neither part crosses itself");
        let near = Near::of(&pair.a, &pair.pa, &pair.b, &pair.pb, &pair.near).unwrap();
        let split = a.triangles.len() as u32;
        assert!(
            matches!(near.trees, [NearTree::Whole(_, 0), NearTree::Whole(_, s)] if s == split),
            "both checked trees serve"
        );
        assert_eq!(pair.pa.tree.frame, pair.pb.tree.frame);
        assert!(!pair.pa.tree.frame.is_identity());
        same_as_with_trees_built(&a, &b, &pair);
    }

    /// A small part at one end of a long one: most of the small part is
    /// near the long one, and its checked tree serves; few of the long
    /// one's triangles are near the small part, and only they get a tree,
    /// measured in the small part's very frame.
    #[test]
    fn a_small_part_at_the_end_of_a_long_one_reuses_only_its_own_tree() {
        let turn = crate::intersect::tests::turn;
        let a = fan_prism(40, 0.7, turn, turn(DVec3::new(-5.6, 0.1, 0.15)));
        let b = fan_prism(200, 3.0, turn, DVec3::ZERO);
        let pair = PreparedPair::with_checks(&a, &b, Operation::Union).unwrap();
        let pair = pair.expect("both closed, neither part crosses itself");
        let near = Near::of(&pair.a, &pair.pa, &pair.b, &pair.pb, &pair.near).unwrap();
        let [NearTree::Whole(_, 0), NearTree::Listed(listed, _)] = &near.trees else {
            panic!("A's checked tree and a tree of B's near triangles");
        };
        assert!(
            !listed.is_empty() && 4 * listed.len() < b.triangles.len(),
            "{} of B's {} triangles near A",
            listed.len(),
            b.triangles.len()
        );
        same_as_with_trees_built(&a, &b, &pair);
    }
}
