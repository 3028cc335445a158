//! The coplanar overlay of a Boolean's kept faces (issue 14: "coplanar
//! faces of opposite orientation cancel").
//!
//! Where two inputs touch along coplanar faces from opposite sides (two
//! boxes side by side, a slab flush with a solid's face in a difference),
//! the arrangement's perturbed world keeps the sheets apart, and where it
//! leaves a gap between them both faces are kept: a wall of no thickness
//! whose two sides face away from each other. Its cells need not
//! coincide (the sheets have their own triangulations, cut by their own
//! perturbed curves), so cancelling identical twins
//! (`winding_boolean::cancel_opposite_twins`) does not remove it.
//!
//! Here such faces are found exactly (coplanar by `orient3d`, facing
//! opposite ways and overlapping in their plane by `orient2d` in a
//! coordinate projection, which keeps every orientation's sign), grouped
//! with the faces that overlap them from one side and the flat slivers on
//! their sides, and each group is replaced by its overlay: the constrained
//! triangulation of all its sides in the plane, each cell counted by the
//! faces covering it with their orientations (+1 facing one way, −1 the
//! other). A cell whose count is 0 lies in a wall and goes; a count of ±1
//! is kept, facing that way. Crossing sides meet at points found exactly
//! and rounded once, all before any side is inserted
//! ([`crate::side_crossings`]), and lifted back onto the plane; the
//! faces around the group are split at the points that land on their
//! sides by the Boolean's T-junction repair. Where spade's splitting
//! insertion panics (sides crossing a few ulps from a corner), the
//! crossings are found first, as `resolve` does. A group whose overlay
//! fails even so (a panic of the insertion, a count of ±2, a projection
//! that flattens a face) keeps its faces.

use glam::{DVec2, DVec3};
use holey_geom::expansion::Expansion;
use holey_geom::{Aabb, Bvh, Sign, orient2d, orient3d};
use rayon::prelude::*;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use crate::cut::{ChartVertex, NONE};
use crate::on_side::{near_line_2d, on_side_between, snap_crossings};

use crate::union_find::UnionFind;

/// The coordinate axis to drop for `f`'s plane: its normal's largest
/// component (in floating point; the projection only needs that
/// component to be nonzero, which [`projected_sign`] checks exactly).
fn drop_axis(positions: &[DVec3], f: [u32; 3]) -> usize {
    let [a, b, c] = f.map(|v| positions[v as usize]);
    let n = (b - a).cross(c - a).abs();
    if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    }
}

/// `p` without coordinate `axis`, in the order that keeps orientations:
/// (y, z), (z, x) or (x, y).
fn project(p: DVec3, axis: usize) -> DVec2 {
    match axis {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

/// The exact orientation of `f` in the projection along `axis`: the sign
/// of its normal's `axis` component.
fn projected_sign(positions: &[DVec3], f: [u32; 3], axis: usize) -> Sign {
    let [a, b, c] = f.map(|v| project(positions[v as usize], axis));
    orient2d(a, b, c)
}

/// Whether the closed triangles `a` and `b` (projected, counterclockwise)
/// share interior points: no side of either has the other wholly on its
/// outer closed half-plane.
fn interiors_meet(a: [DVec2; 3], b: [DVec2; 3]) -> bool {
    let separates = |t: [DVec2; 3], other: [DVec2; 3]| {
        (0..3).any(|k| {
            let (p, q) = (t[k], t[(k + 1) % 3]);
            other.iter().all(|&x| orient2d(p, q, x) != Sign::Positive)
        })
    };
    !separates(a, b) && !separates(b, a)
}

/// `t`'s corners in counterclockwise order of the projection, given its
/// sign there.
fn counterclockwise(t: [DVec2; 3], sign: Sign) -> [DVec2; 3] {
    if sign == Sign::Negative {
        [t[0], t[2], t[1]]
    } else {
        t
    }
}

/// The exact side of the line `p → q` on which the centroid of `cell`
/// lies (positive: to the left). `orient2d(p, q, x)` is affine in `x`, so
/// at the centroid it is the mean of its values at the corners: the sign
/// of `(q − p) × (Σ xₖ − 3p)`, decided in floating point when that is
/// clearly away from zero and by exact expansions otherwise. (A rounded
/// centroid can leave a sliver cell.)
fn centroid_side(p: DVec2, q: DVec2, cell: &[DVec2; 3]) -> Sign {
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    let sx = cell[0].x + cell[1].x + cell[2].x - 3.0 * p.x;
    let sy = cell[0].y + cell[1].y + cell[2].y - 3.0 * p.y;
    let det = dx * sy - dy * sx;
    // The rounding error is a few ulps of the terms' size (the corners'
    // and p's coordinates, times the side's); 2⁻⁴⁰ of it is far more.
    let size =
        cell.iter().map(|x| x.abs().element_sum()).sum::<f64>() + 3.0 * p.abs().element_sum();
    let bound = (dx.abs() + dy.abs()) * size;
    if det.abs() > bound * (1.0 / (1u64 << 40) as f64) {
        return Sign::of(det);
    }
    let sum = |c: fn(DVec2) -> f64| {
        cell.iter()
            .fold(Expansion::zero(), |acc, &x| {
                acc.add(&Expansion::from_f64(c(x)))
            })
            .sub(&Expansion::from_f64(c(p)).scale(3.0))
    };
    let exact = Expansion::diff(q.x, p.x)
        .mul(&sum(|v| v.y))
        .sub(&Expansion::diff(q.y, p.y).mul(&sum(|v| v.x)));
    match exact.sign() {
        1 => Sign::Positive,
        -1 => Sign::Negative,
        _ => Sign::Zero,
    }
}

/// How two faces overlap in a common plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Overlap {
    /// Not coplanar, or their interiors do not meet.
    Apart,
    /// Coplanar and overlapping, facing the same way.
    Same,
    /// Coplanar and overlapping, facing opposite ways: a piece of wall.
    Opposite,
}

/// A face's normal in floating point, and whether it means something
/// there: a sliver's can point anywhere, and goes to the exact tests.
fn float_normal(positions: &[DVec3], t: [u32; 3]) -> Option<DVec3> {
    let p = |v: u32| positions[v as usize];
    let (u, w) = (p(t[1]) - p(t[0]), p(t[2]) - p(t[0]));
    let n = u.cross(w);
    let size = u.length_squared().max(w.length_squared());
    (n.length() > 1e-6 * size).then_some(n)
}

/// Whether two faces with these float normals may overlap in one plane
/// facing `facing` ways (`None`: either way): coplanar faces have
/// parallel normals, and faces facing opposite ways opposite ones. Only
/// a filter: [`overlap`] decides exactly.
fn may_overlap(nf: Option<DVec3>, ng: Option<DVec3>, facing: Option<Overlap>) -> bool {
    let (Some(nf), Some(ng)) = (nf, ng) else {
        return true;
    };
    let (dot, scale) = (nf.dot(ng), nf.length() * ng.length());
    match facing {
        Some(Overlap::Opposite) => dot < -0.5 * scale,
        _ => dot.abs() >= 0.5 * scale,
    }
}

/// How faces `f` and `g` overlap: exactly coplanar, and interiors that
/// meet in their plane, facing the same or opposite ways.
fn overlap(positions: &[DVec3], f: [u32; 3], g: [u32; 3]) -> Overlap {
    let p = |v: u32| positions[v as usize];
    let [a, b, c] = f.map(p);
    if g.iter()
        .any(|&v| !f.contains(&v) && orient3d(a, b, c, p(v)) != Sign::Zero)
    {
        return Overlap::Apart;
    }
    let axis = drop_axis(positions, f);
    let (sf, sg) = (
        projected_sign(positions, f, axis),
        projected_sign(positions, g, axis),
    );
    if sf == Sign::Zero || sg == Sign::Zero {
        return Overlap::Apart;
    }
    let proj = |t: [u32; 3]| t.map(|v| project(p(v), axis));
    if !interiors_meet(counterclockwise(proj(f), sf), counterclockwise(proj(g), sg)) {
        Overlap::Apart
    } else if sf == sg {
        Overlap::Same
    } else {
        Overlap::Opposite
    }
}

/// Calls `f(i, j, how)` for every pair `i < j` of `faces` that overlap
/// in their plane ([`overlap`] is not [`Overlap::Apart`]), over a tree of
/// their boxes.
pub(crate) fn for_each_overlapping_pair(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    mut f: impl FnMut(usize, usize, Overlap),
) {
    let Some(tree) = FaceTree::new(positions, faces) else {
        return;
    };
    for (i, j, how) in tree.pairs(None) {
        f(i as usize, j as usize, how);
    }
}

/// Faces with a tree of their boxes and their float normals, for finding
/// the pairs that overlap in their plane: each pair whose boxes meet is
/// filtered by its normals ([`may_overlap`]) before the exact test (a
/// CAD part's union with its mirror image has 1.5M pairs of faces whose
/// boxes meet, long thin triangles, and none overlapping).
struct FaceTree<'a> {
    positions: &'a [DVec3],
    faces: &'a [[u32; 3]],
    boxes: Vec<Aabb>,
    tree: Bvh,
    normals: Vec<Option<DVec3>>,
}

impl<'a> FaceTree<'a> {
    /// `None` when a box is not finite.
    fn new(positions: &'a [DVec3], faces: &'a [[u32; 3]]) -> Option<FaceTree<'a>> {
        let boxes: Vec<Aabb> = faces
            .par_iter()
            .map(|t| Aabb::from_points(&t.map(|v| positions[v as usize])))
            .collect();
        let tree = Bvh::build(&boxes).ok()?;
        let normals = faces
            .par_iter()
            .map(|&t| float_normal(positions, t))
            .collect();
        Some(FaceTree {
            positions,
            faces,
            boxes,
            tree,
            normals,
        })
    }

    /// Calls `f(j, how)` for each face `j` after `i` that overlaps it in
    /// their plane, facing `facing` ways (`None`: either way).
    fn overlapping(&self, i: usize, facing: Option<Overlap>, mut f: impl FnMut(usize, Overlap)) {
        self.tree.for_each_overlap(&self.boxes[i], |j| {
            let j = j as usize;
            if j > i && may_overlap(self.normals[i], self.normals[j], facing) {
                let how = overlap(self.positions, self.faces[i], self.faces[j]);
                if how != Overlap::Apart && facing.is_none_or(|w| w == how) {
                    f(j, how);
                }
            }
        });
    }

    /// The pairs `i < j` that overlap facing `facing` ways, in order;
    /// the faces in parallel.
    fn pairs(&self, facing: Option<Overlap>) -> Vec<(u32, u32, Overlap)> {
        (0..self.faces.len())
            .into_par_iter()
            .with_min_len(1 << 10)
            .flat_map_iter(|i| {
                let mut hits = Vec::new();
                self.overlapping(i, facing, |j, how| hits.push((i as u32, j as u32, how)));
                hits
            })
            .collect()
    }

    /// Whether some pair overlaps facing `facing` ways: the faces in
    /// parallel, until one is found.
    fn any(&self, facing: Option<Overlap>) -> bool {
        (0..self.faces.len())
            .into_par_iter()
            .with_min_len(1 << 8)
            .any(|i| {
                let mut found = false;
                self.overlapping(i, facing, |_, _| found = true);
                found
            })
    }
}

/// Each vertex by its position's key ([`holey_geom::position_key`]): the
/// vertices an overlay's crossing point may land on.
pub(crate) fn position_index(positions: &[DVec3]) -> rustc_hash::FxHashMap<[u64; 3], u32> {
    positions
        .iter()
        .enumerate()
        .map(|(v, &p)| (holey_geom::position_key(p), v as u32))
        .collect()
}

/// The walls of `faces` (module docs): groups of face indices, each
/// group's faces coplanar, joined by pairs that overlap, with at least
/// one pair facing opposite ways (faces overlapping the wall from the
/// same side, a sliver the cut left along it, count in its overlay too);
/// in order of their first face.
pub(crate) fn wall_groups(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<Vec<usize>> {
    overlap_groups(positions, faces, true)
}

/// The groups of `faces` that overlap in their plane: face indices,
/// each group's faces coplanar and joined by pairs whose interiors meet
/// (facing either way), with the flat slivers on their sides; only those
/// with a pair facing opposite ways when `walls_only`. In order of their
/// first face.
pub(crate) fn overlap_groups(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    walls_only: bool,
) -> Vec<Vec<usize>> {
    let Some(tree) = FaceTree::new(positions, faces) else {
        return Vec::new();
    };
    // Without a pair facing opposite ways there is no wall: on most
    // results there is none, and faces facing the same way (every face's
    // coplanar neighbours on a CAD part) are rejected by their normals
    // (65–85 ms against 215–245 for every pair on the part's union with
    // its mirror image).
    if walls_only && !tree.any(Some(Overlap::Opposite)) {
        return Vec::new();
    }
    let pairs = tree.pairs(None);
    let mut sets = UnionFind::new(faces.len());
    let mut in_wall = vec![false; faces.len()];
    let mut joined = vec![false; faces.len()];
    for (i, j, o) in pairs {
        sets.union(i, j);
        let flag = if o == Overlap::Opposite {
            &mut in_wall
        } else {
            &mut joined
        };
        flag[i as usize] = true;
        flag[j as usize] = true;
    }
    let walls: rustc_hash::FxHashSet<u32> = (0..faces.len())
        .filter(|&i| in_wall[i])
        .map(|i| sets.find(i as u32))
        .collect();
    let mut groups: rustc_hash::FxHashMap<u32, Vec<usize>> = Default::default();
    for i in (0..faces.len()).filter(|&i| in_wall[i] || joined[i]) {
        let root = sets.find(i as u32);
        if !walls_only || walls.contains(&root) {
            groups.entry(root).or_default().push(i);
        }
    }
    let mut groups: Vec<Vec<usize>> = groups.into_values().collect();
    groups.sort_unstable();
    let grouped: Vec<bool> = {
        let mut g = vec![false; faces.len()];
        for &i in groups.iter().flatten() {
            g[i] = true;
        }
        g
    };
    absorb_flat_faces(positions, faces, &mut groups, &grouped);
    groups
}

/// Whether `f`'s corners are exactly collinear (or repeat): a face of no
/// area, which every projection flattens.
fn flat(positions: &[DVec3], f: [u32; 3]) -> bool {
    (0..3).all(|axis| projected_sign(positions, f, axis) == Sign::Zero)
}

/// Adds to each group the faces of no area that share a side with one of
/// its faces (the cut leaves such slivers along a wall's curves). They
/// lie on that side's line, in the group's plane; their sides pair with
/// the group's, so the overlay, which refines those sides, must replace
/// them too (they add nothing to a cell's count). Each group stays
/// sorted.
fn absorb_flat_faces(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    groups: &mut [Vec<usize>],
    grouped: &[bool],
) {
    let side = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut group_of_side: rustc_hash::FxHashMap<(u32, u32), usize> = Default::default();
    for (g, group) in groups.iter().enumerate() {
        for &i in group {
            let f = faces[i];
            for k in 0..3 {
                group_of_side.insert(side(f[k], f[(k + 1) % 3]), g);
            }
        }
    }
    for (i, &f) in faces.iter().enumerate() {
        if grouped[i] || !flat(positions, f) {
            continue;
        }
        let joined = (0..3).find_map(|k| group_of_side.get(&side(f[k], f[(k + 1) % 3])));
        if let Some(&g) = joined {
            groups[g].push(i);
        }
    }
    for group in groups.iter_mut() {
        group.sort_unstable();
    }
}

/// What an overlay keeps of a cell, given the faces covering it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Keep {
    /// A Boolean's rule (module docs): the count of the covering faces,
    /// +1 for each facing one way and −1 for each facing the other. A
    /// cell of count 0 goes, ±1 is kept facing that way, and any other
    /// count fails the overlay (stacked faces are no wall).
    Count,
    /// `holey resolve`'s rule: a covered cell is kept once, facing by the
    /// sign of the count, and goes where the count is 0. Faces facing
    /// opposite ways over one cell add −1 and +1 to the winding number on
    /// each side of it, so cancelling them leaves the winding number of
    /// the surface unchanged off the plane (keeping one, as a first
    /// version did, added a sheet; it also left the edge of a fold, two
    /// faces folded flat onto each other, on one triangle). Stacked faces
    /// facing one way are kept once: the merge the issue asks for.
    Once,
}

/// An overlay's result.
pub(crate) struct Overlay {
    /// The kept cells.
    pub cells: Vec<[u32; 3]>,
    /// Each side of the group's faces (its two ends, as the face runs it)
    /// with the points it was split at, in order from its first end: the
    /// faces around the group that share such a side must be split there
    /// too.
    pub sides: Vec<((u32, u32), Vec<u32>)>,
    /// Corners of the group taken as another corner at the same point
    /// (only by [`Keep::Once`]): (corner, the one it is taken as). The
    /// cells use the second; every face must.
    pub renamed: Vec<(u32, u32)>,
}

impl Overlay {
    /// The overlay with its new points (those from `first_new` on)
    /// numbered `by` later.
    pub(crate) fn shifted(mut self, first_new: u32, by: u32) -> Overlay {
        let shift = |v: &mut u32| {
            if *v >= first_new {
                *v += by;
            }
        };
        self.cells.iter_mut().flatten().for_each(shift);
        for ((a, b), on) in &mut self.sides {
            shift(a);
            shift(b);
            on.iter_mut().for_each(shift);
        }
        for (a, b) in &mut self.renamed {
            shift(a);
            shift(b);
        }
        self
    }
}

type Handle = spade::handles::FixedVertexHandle;

/// A group's triangulation: the vertex of each corner, and the corners
/// taken as another at the same point (corner, the one it is taken as).
struct Triangulated {
    cdt: ConstrainedDelaunayTriangulation<ChartVertex>,
    handle_of: rustc_hash::FxHashMap<u32, Handle>,
    renamed: Vec<(u32, u32)>,
    /// Each side's vertices, by its ends' handles (smaller index first):
    /// its ends, the split points between and the vertices spade split its
    /// pieces at, in order from the first (only for [`Keep::Once`]).
    split_sides: SideVertices,
}

/// Each side's vertices (see [`Triangulated`]).
type SideVertices = rustc_hash::FxHashMap<(Handle, Handle), Vec<Handle>>;

/// The constrained triangulation of a group's faces in the projection
/// along `axis`: every corner a vertex (`None` when two corners project
/// to one point and `keep` is [`Keep::Count`], or when the insertion of a
/// side panics), every side of a face with an area a constraint, split
/// where sides cross ([`crate::side_crossings`]: each side goes in as
/// its pieces between its crossings). `None` also where a piece's
/// rounded ends make it cross another: spade's splitting insertion,
/// which would split it, can circle forever (spade 2.15 ran ten minutes
/// on a 34-face wall of a snapped OpenSCAD export, turning about a
/// vertex in `trace_direction_out_of_vertex`), so it is never asked.
fn triangulate(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    group: &[usize],
    signs: &[Sign],
    axis: usize,
    keep: Keep,
) -> Option<Triangulated> {
    let proj = |v: u32| project(positions[v as usize], axis);
    let mut cdt: ConstrainedDelaunayTriangulation<ChartVertex> =
        ConstrainedDelaunayTriangulation::new();
    let mut handle_of: rustc_hash::FxHashMap<u32, Handle> = Default::default();
    let mut renamed = Vec::new();
    for &i in group {
        for v in faces[i] {
            if let std::collections::hash_map::Entry::Vacant(e) = handle_of.entry(v) {
                let q = proj(v);
                let at = Point2::new(q.x, q.y);
                if let Some(h) = cdt.locate_vertex(at) {
                    // Two corners at one point of the plane are at one
                    // point of space (the projection is one to one on the
                    // plane): the same point, by the engine's identities
                    // by position. `resolve` takes them as one; for a
                    // Boolean that is not the overlay's to decide.
                    if keep == Keep::Count {
                        return None;
                    }
                    renamed.push((v, h.data().global));
                    e.insert(h.fix());
                    continue;
                }
                let h = cdt.insert(ChartVertex { pos: at, global: v }).ok()?;
                e.insert(h);
            }
        }
    }
    // Every side of a face with an area, in the faces' order.
    let sides: Vec<(Handle, Handle)> = group
        .iter()
        .zip(signs)
        .filter(|(_, s)| **s != Sign::Zero)
        .flat_map(|(&i, _)| {
            let f = faces[i];
            (0..3).map(move |k| (f[k], f[(k + 1) % 3]))
        })
        .map(|(a, b)| (handle_of[&a], handle_of[&b]))
        .filter(|(a, b)| a != b)
        .collect();
    let (pieces, split_sides) = presplit(&mut cdt, &sides)?;
    // The vertices each piece went in through (`Once`): where spade split
    // it, at a vertex exactly on it or a crossing it met, in order.
    let mut through: rustc_hash::FxHashMap<(Handle, Handle), Vec<Handle>> = Default::default();
    let inserted = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        for &(a, b) in &pieces {
            let edges = if cdt.exists_constraint(a, b) {
                Vec::new()
            } else if cdt.can_add_constraint(a, b) {
                cdt.try_add_constraint(a, b)
            } else {
                // A piece that the rounding of its ends made cross
                // another (rare): no overlay (see above).
                return false;
            };
            let (pa, pb) = (cdt.vertex(a).position(), cdt.vertex(b).position());
            let along = |h: Handle| {
                let q = cdt.vertex(h).position();
                (q.x - pa.x) * (pb.x - pa.x) + (q.y - pa.y) * (pb.y - pa.y)
            };
            let mut mid: Vec<Handle> = edges
                .iter()
                .flat_map(|&e| cdt.directed_edge(e).vertices().map(|v| v.fix()))
                .filter(|&v| v != a && v != b)
                .collect();
            mid.sort_by(|&u, &v| along(u).total_cmp(&along(v)));
            mid.dedup();
            if !mid.is_empty() {
                through.insert((a, b), mid);
            }
        }
        true
    }));
    let mut split_sides = split_sides;
    for on in split_sides.values_mut() {
        let mut expanded = vec![on[0]];
        for w in on.windows(2) {
            if let Some(mid) = through.get(&(w[0], w[1])) {
                expanded.extend(mid);
            } else if let Some(mid) = through.get(&(w[1], w[0])) {
                expanded.extend(mid.iter().rev());
            }
            expanded.push(w[1]);
        }
        *on = expanded;
    }
    matches!(inserted, Ok(true)).then_some(Triangulated {
        cdt,
        handle_of,
        renamed,
        split_sides,
    })
}

/// The pieces of `sides` between their crossings, found before any
/// goes in ([`crate::side_crossings`]; the crossing points inserted as
/// vertices), and each side's vertices in order (its ends and the split
/// points between, by its ends' handles, smaller index first). `None`
/// when a point cannot be inserted.
fn presplit(
    cdt: &mut ConstrainedDelaunayTriangulation<ChartVertex>,
    sides: &[(Handle, Handle)],
) -> Option<(Vec<(Handle, Handle)>, SideVertices)> {
    // Once each, in the faces' order.
    let mut seen = rustc_hash::FxHashSet::default();
    let sides: Vec<(Handle, Handle)> = sides
        .iter()
        .map(|&(a, b)| {
            if a.index() <= b.index() {
                (a, b)
            } else {
                (b, a)
            }
        })
        .filter(|&s| seen.insert(s))
        .collect();
    let at = |h: Handle| {
        let p = cdt.vertex(h).position();
        DVec2::new(p.x, p.y)
    };
    let corners: Vec<DVec2> = cdt
        .vertices()
        .map(|v| DVec2::new(v.position().x, v.position().y))
        .collect();
    let segments: Vec<[DVec2; 2]> = sides.iter().map(|&(a, b)| [at(a), at(b)]).collect();
    let splits = crate::side_crossings::split_points(&corners, &segments);
    let mut split_sides = SideVertices::default();
    let mut pieces = Vec::new();
    for (&(a, b), points) in sides.iter().zip(&splits) {
        let mut on = vec![a];
        for p in points {
            let at = Point2::new(p.x, p.y);
            let h = match cdt.locate_vertex(at) {
                Some(h) => h.fix(),
                None => cdt
                    .insert(ChartVertex {
                        pos: at,
                        global: NONE,
                    })
                    .ok()?,
            };
            on.push(h);
        }
        on.push(b);
        on.dedup();
        pieces.extend(on.windows(2).map(|w| (w[0], w[1])));
        split_sides.insert((a, b), on);
    }
    Some((pieces, split_sides))
}

/// The chain of constraint edges of `cdt` from `from` to `to`: the
/// vertices strictly between, in order. Each step takes a constraint
/// edge to a vertex on the segment ([`near_line_2d`])
/// that is closer to `to`, the nearest such; `None` when there is none
/// before `to` (a crossing so ill-conditioned that its point lands
/// farther off leaves the group as it was).
fn chain(
    cdt: &ConstrainedDelaunayTriangulation<ChartVertex>,
    from: Handle,
    to: Handle,
) -> Option<Vec<Handle>> {
    let (a, b) = (cdt.vertex(from).position(), cdt.vertex(to).position());
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let length2 = dx * dx + dy * dy;
    // The parameter along the side, and whether the point is on it.
    let along = |q: Point2<f64>| ((q.x - a.x) * dx + (q.y - a.y) * dy) / length2;
    let on_line = |q: Point2<f64>| {
        near_line_2d(
            DVec2::new(a.x, a.y),
            DVec2::new(b.x, b.y),
            DVec2::new(q.x, q.y),
        )
    };
    let mut at = from;
    let mut t = 0.0;
    let mut between = Vec::new();
    for _ in 0..cdt.num_vertices() {
        let mut next: Option<(Handle, f64)> = None;
        for e in cdt.vertex(at).out_edges() {
            if !e.is_constraint_edge() {
                continue;
            }
            let v = e.to();
            if v.fix() == to {
                return Some(between);
            }
            let q = v.position();
            let s = along(q);
            if s > t && s < 1.0 && on_line(q) && next.is_none_or(|(_, n)| s < n) {
                next = Some((v.fix(), s));
            }
        }
        let (v, s) = next?;
        between.push(v);
        (at, t) = (v, s);
    }
    None
}

/// The vertices strictly between `from` and `to` along their side, in
/// order: its split points and the vertices its pieces went in through
/// (`split_sides`), each step followed by [`chain`] where a later piece
/// split it (crossing it where their rounded ends made them cross).
fn follow(
    cdt: &ConstrainedDelaunayTriangulation<ChartVertex>,
    split_sides: &SideVertices,
    from: Handle,
    to: Handle,
) -> Option<Vec<Handle>> {
    let key = if from.index() <= to.index() {
        (from, to)
    } else {
        (to, from)
    };
    let Some(on) = split_sides.get(&key) else {
        return chain(cdt, from, to);
    };
    // Read from `from`'s end.
    let at = |k: usize| {
        if key.0 == from {
            on[k]
        } else {
            on[on.len() - 1 - k]
        }
    };
    let mut between = Vec::new();
    for k in 1..on.len() {
        let (p, q) = (at(k - 1), at(k));
        if k > 1 {
            between.push(p);
        }
        if !cdt.exists_constraint(p, q) {
            between.extend(chain(cdt, p, q)?);
        }
    }
    Some(between)
}

/// The overlay of the coplanar faces `group` of `faces` (module docs):
/// its cells kept by `keep`, with the crossing points appended to
/// `positions` (those at the position of a vertex in `existing`, by
/// [`holey_geom::position_key`], are that vertex), and the points each
/// side of the group's faces was split at; `None` when it cannot be made
/// (and nothing is appended).
pub(crate) fn overlay(
    positions: &mut Vec<DVec3>,
    faces: &[[u32; 3]],
    group: &[usize],
    existing: &rustc_hash::FxHashMap<[u64; 3], u32>,
    keep: Keep,
) -> Option<Overlay> {
    let (made, new_points) = overlay_beside(positions, faces, group, existing, keep)?;
    positions.extend(new_points);
    Some(made)
}

/// [`overlay`] of each of `groups`, made side by side (a CAD part's
/// difference with its mirror image has 64 walls: 0.55 s one after
/// another), their crossing points appended in the groups' order, each
/// group's numbered after the last's: the points and cells of overlays
/// made one after another.
pub(crate) fn overlays(
    positions: &mut Vec<DVec3>,
    faces: &[[u32; 3]],
    groups: &[Vec<usize>],
    existing: &rustc_hash::FxHashMap<[u64; 3], u32>,
    keep: Keep,
) -> Vec<Option<Overlay>> {
    let made: Vec<Option<(Overlay, Vec<DVec3>)>> = groups
        .par_iter()
        .map(|group| overlay_beside(positions, faces, group, existing, keep))
        .collect();
    let first_new = positions.len() as u32;
    made.into_iter()
        .map(|o| {
            o.map(|(o, new_points)| {
                let o = o.shifted(first_new, positions.len() as u32 - first_new);
                positions.extend(new_points);
                o
            })
        })
        .collect()
}

/// [`overlay`] without appending: the crossing points it would append
/// are returned, numbered from `positions.len()` on, so that groups can
/// be overlaid side by side ([`Overlay::shifted`] numbers them after
/// another group's).
fn overlay_beside(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    group: &[usize],
    existing: &rustc_hash::FxHashMap<[u64; 3], u32>,
    keep: Keep,
) -> Option<(Overlay, Vec<DVec3>)> {
    // The plane's axis and face: the first face with an area (faces of no
    // area, absorbed by `absorb_flat_faces`, count nothing).
    let first = *group.iter().find(|&&i| !flat(positions, faces[i]))?;
    let axis = drop_axis(positions, faces[first]);
    let signs: Vec<Sign> = group
        .iter()
        .map(|&i| projected_sign(positions, faces[i], axis))
        .collect();
    if group
        .iter()
        .zip(&signs)
        .any(|(&i, &s)| s == Sign::Zero && !flat(positions, faces[i]))
    {
        return None;
    }
    let Triangulated {
        cdt,
        handle_of,
        renamed,
        split_sides,
    } = triangulate(positions, faces, group, &signs, axis, keep)?;
    let proj = |v: u32| project(positions[v as usize], axis);
    // The group's faces, counterclockwise in the projection, with the
    // count each adds inside it.
    let covers: Vec<([DVec2; 3], i32)> = group
        .iter()
        .zip(&signs)
        .filter(|(_, s)| **s != Sign::Zero)
        .map(|(&i, &s)| {
            let t = faces[i].map(proj);
            (
                counterclockwise(t, s),
                if s == Sign::Positive { 1 } else { -1 },
            )
        })
        .collect();
    let inside = |t: &[DVec2; 3], cell: &[DVec2; 3]| {
        (0..3).all(|k| centroid_side(t[k], t[(k + 1) % 3], cell) == Sign::Positive)
    };
    // A face holds a cell's centroid only if its box meets the cell's
    // (the centroid is in both): each cell tests only those faces, where
    // testing every face against every cell took 13% of a CAD part's
    // difference with its mirror image (walls of 300 faces).
    let flat_box = |t: &[DVec2; 3]| {
        let lo = t[0].min(t[1]).min(t[2]);
        let hi = t[0].max(t[1]).max(t[2]);
        Aabb::new(lo.extend(0.0), hi.extend(0.0))
    };
    let cover_boxes: Vec<Aabb> = covers.iter().map(|(t, _)| flat_box(t)).collect();
    let cover_tree = Bvh::build(&cover_boxes).ok()?;
    // The plane the crossing points are lifted onto: through the first
    // face's first corner, with its normal.
    let [a, b, c] = faces[first].map(|v| positions[v as usize]);
    let normal = (b - a).cross(c - a);
    let lift = |q: Point2<f64>| -> DVec3 {
        let (u, w) = (q.x, q.y);
        let mut p = match axis {
            0 => DVec3::new(a.x, u, w),
            1 => DVec3::new(w, a.y, u),
            _ => DVec3::new(u, w, a.z),
        };
        let off = (p - a).dot(normal) / normal[axis];
        p[axis] -= off;
        p
    };
    // Every vertex's point: a corner's own, a crossing's lifted.
    let mut points = Vec::with_capacity(cdt.num_vertices());
    for v in cdt.vertices() {
        let pv = v.data();
        points.push(if pv.global == NONE {
            let p = lift(pv.pos);
            if !p.is_finite() {
                return None;
            }
            p
        } else {
            positions[pv.global as usize]
        });
    }
    let crossing: Vec<bool> = cdt.vertices().map(|v| v.data().global == NONE).collect();
    let snapped = snap_crossings(&points, &crossing);
    let mut global: Vec<u32> = Vec::with_capacity(cdt.num_vertices());
    let mut new_points = Vec::new();
    for (i, v) in cdt.vertices().enumerate() {
        let pv = v.data();
        if pv.global != NONE {
            global.push(pv.global);
        } else if snapped[i] < i {
            global.push(global[snapped[i]]);
        } else if snapped[i] > i {
            // Snapped to a corner of a later vertex: filled in below.
            global.push(NONE);
        } else if let Some(&v) = existing.get(&holey_geom::position_key(points[i])) {
            // A crossing that lands on a vertex the result has (a point of
            // another sheet's curve in this plane) is that vertex.
            global.push(v);
        } else {
            global.push((positions.len() + new_points.len()) as u32);
            new_points.push(points[i]);
        }
    }
    for i in 0..global.len() {
        if global[i] == NONE {
            global[i] = global[snapped[i]];
        }
    }
    let mut cells = Vec::new();
    let mut flattened = Vec::new();
    for f in cdt.inner_faces() {
        let q = f.vertices().map(|v| {
            let p = v.position();
            DVec2::new(p.x, p.y)
        });
        let (mut covered, mut count) = (false, 0i32);
        cover_tree.for_each_overlap(&flat_box(&q), |c| {
            let (t, add) = &covers[c as usize];
            if inside(t, &q) {
                covered = true;
                count += add;
            }
        });
        let [i, j, k] = f.vertices().map(|v| global[v.fix().index()]);
        // A crossing taken as an existing vertex can make a cell's corners
        // repeat: a cell of no area, never kept (the check of the merge
        // decides whether the result stays closed without it).
        if !covered || i == j || j == k || i == k {
            continue;
        }
        // A cell with a corner on its opposite side's line, to rounding
        // (a rounded crossing or another group's point beside a side),
        // has no area: it is not kept, and the side is split at that
        // corner instead, so the faces across it meet the cells beside.
        if keep == Keep::Once {
            let at = f.vertices().map(|v| v.fix().index() as u32);
            if let Some(n) =
                (0..3).find(|&n| on_side_between(&points, at[(n + 1) % 3], at[(n + 2) % 3], at[n]))
            {
                let g = [i, j, k];
                flattened.push(((g[(n + 1) % 3], g[(n + 2) % 3]), vec![g[n]]));
                continue;
            }
        }
        let facing = match keep {
            Keep::Count if count.abs() > 1 => return None,
            Keep::Count => count,
            Keep::Once => count,
        };
        match facing.signum() {
            1 => cells.push([i, j, k]),
            -1 => cells.push([i, k, j]),
            _ => {}
        }
    }
    let mut sides = flattened;
    // (A Boolean repairs the T-junctions around its walls by their
    // orientation; it needs no chains.)
    let chained = if keep == Keep::Once { group } else { &[] };
    for (&i, _) in chained
        .iter()
        .zip(&signs)
        .filter(|(_, s)| **s != Sign::Zero)
    {
        let f = faces[i];
        for k in 0..3 {
            let (u, v) = (f[k], f[(k + 1) % 3]);
            let on = follow(&cdt, &split_sides, handle_of[&u], handle_of[&v])?;
            let mut on: Vec<u32> = on
                .iter()
                .map(|h| global[h.index()])
                .filter(|&w| w != u && w != v)
                .collect();
            on.dedup();
            if !on.is_empty() {
                sides.push(((u, v), on));
            }
        }
    }
    Some((
        Overlay {
            cells,
            sides,
            renamed,
        },
        new_points,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit squares in the plane z = 1, the second shifted by ½ along
    /// x: the first facing up (+z) and split along its diagonal 0–2, the
    /// second facing down and split along 5–7.
    fn two_squares() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let positions = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
            (1.5, 0.0),
            (1.5, 1.0),
            (0.5, 1.0),
        ]
        .map(|(x, y)| DVec3::new(x, y, 1.0))
        .to_vec();
        (positions, vec![[0, 1, 2], [0, 2, 3], [4, 7, 5], [5, 7, 6]])
    }

    /// Two walls (the two squares, and a copy of them in the plane
    /// z = 3) overlaid side by side ([`overlays`]: the second's new points
    /// numbered after the first's), give the points and cells of the two
    /// overlaid one after the other.
    #[test]
    fn walls_overlaid_side_by_side_are_walls_overlaid_in_turn() {
        let (mut positions, mut faces) = two_squares();
        let n = positions.len() as u32;
        positions.extend(
            positions
                .clone()
                .iter()
                .map(|p| *p + DVec3::new(0.0, 0.0, 2.0)),
        );
        faces.extend(faces.clone().iter().map(|f| f.map(|v| v + n)));
        let groups = wall_groups(&positions, &faces);
        assert_eq!(groups.len(), 2);
        let existing = Default::default();
        let mut in_turn = positions.clone();
        let cells_in_turn: Vec<Vec<[u32; 3]>> = groups
            .iter()
            .map(|g| {
                overlay(&mut in_turn, &faces, g, &existing, Keep::Count)
                    .unwrap()
                    .cells
            })
            .collect();
        let mut beside = positions.clone();
        let first_new = beside.len() as u32;
        let cells_beside: Vec<Vec<[u32; 3]>> =
            overlays(&mut beside, &faces, &groups, &existing, Keep::Count)
                .into_iter()
                .map(|o| o.unwrap().cells)
                .collect();
        assert!(beside.len() as u32 > first_new + 1, "no crossing points");
        assert!(
            cells_beside[1].iter().flatten().any(|&v| v >= first_new),
            "the second wall's cells use no new point"
        );
        assert_eq!(beside, in_turn);
        assert_eq!(cells_beside, cells_in_turn);
    }

    /// Two unit squares in the plane z = 1, the second shifted by ½ along
    /// x, triangulated along different diagonals and facing opposite
    /// ways: one wall where they overlap. The overlay keeps each square's
    /// half outside the other, facing as that square did, and nothing of
    /// the overlap; the oracle is the squares' areas and the normals'
    /// signs computed here.
    #[test]
    fn overlapping_opposite_squares_cancel_where_they_overlap() {
        let (mut positions, mut faces) = two_squares();
        // A face elsewhere, facing up in another plane: not a wall.
        positions.extend([
            DVec3::new(0.0, 0.0, 3.0),
            DVec3::new(1.0, 0.0, 3.0),
            DVec3::new(0.0, 1.0, 3.0),
        ]);
        faces.push([8, 9, 10]);
        let groups = wall_groups(&positions, &faces);
        assert_eq!(groups, vec![vec![0, 1, 2, 3]]);
        let existing = Default::default();
        let cells = overlay(&mut positions, &faces, &groups[0], &existing, Keep::Count)
            .unwrap()
            .cells;
        let (mut up, mut down) = (0.0, 0.0);
        for c in &cells {
            let [a, b, d] = c.map(|v| positions[v as usize]);
            let n = (b - a).cross(d - a);
            let centroid = (a + b + d) / 3.0;
            assert!(
                centroid.x < 0.5 || centroid.x > 1.0,
                "a cell in the overlap: {centroid}"
            );
            assert_eq!(n.x, 0.0);
            assert_eq!(n.y, 0.0);
            if n.z > 0.0 {
                assert!(centroid.x < 0.5, "facing up beyond the first square");
                up += 0.5 * n.z;
            } else {
                assert!(centroid.x > 1.0, "facing down before the second square");
                down -= 0.5 * n.z;
            }
        }
        assert!((up - 0.5).abs() < 1e-15 && (down - 0.5).abs() < 1e-15);
    }

    /// A side of 2·10⁻¹¹ at coordinates near 200 (as on the OpenSCAD
    /// export): a point 2·10⁻¹⁶ off it, a fraction of an ulp of the
    /// coordinates, is on it, though that is 10⁻⁵ of its length; a point
    /// 10⁻¹² off (several times 2⁻⁴⁸ · 200 ≈ 7·10⁻¹³) is not; and on a
    /// side of length 1 near the origin only 2⁻³⁰ of its length counts.
    #[test]
    fn on_a_side_to_the_rounding_of_its_coordinates() {
        let u = DVec3::new(-16.8, -6.08, -204.0);
        let along = DVec3::new(0.0, 2e-11, 0.0);
        let off = |d: f64| u + along * 0.4 + DVec3::new(d, 0.0, 0.0);
        let positions = vec![u, u + along, off(2e-16), off(1e-12)];
        assert!(on_side_between(&positions, 0, 1, 2));
        assert!(!on_side_between(&positions, 0, 1, 3));
        let unit = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.5, 5e-10, 0.0),
            DVec3::new(0.5, 2e-9, 0.0),
        ];
        assert!(on_side_between(&unit, 0, 1, 2));
        assert!(!on_side_between(&unit, 0, 1, 3));
    }

    /// A corner 10⁻¹⁰ inside a side of another face of its group (within
    /// [`ON_SIDE`](crate::on_side::ON_SIDE) of its line, and farther than
    /// [`SNAP`](crate::on_side::SNAP) from the crossing beside it): the
    /// triangulation makes a sliver
    /// cell between that corner and the side, which the rule `Once` does
    /// not keep; the side's piece is recorded as split at the corner
    /// instead, so the faces across it are fanned through it. Every kept
    /// cell has an area well away from rounding, and the cells cover the
    /// two triangles' union: 8 + the parts of the second outside the
    /// first, below y = 0 and beyond x + y = 4 (computed here).
    #[test]
    fn a_corner_beside_a_side_splits_it_instead_of_making_a_sliver() {
        let mut positions = [
            (0.0, 0.0),
            (4.0, 0.0),
            (0.0, 4.0),
            (1.0, 1e-10),
            (3.0, -1.0),
            (3.0, 2.0),
        ]
        .map(|(x, y)| DVec3::new(x, y, 0.0))
        .to_vec();
        let faces = vec![[0, 1, 2], [3, 4, 5]];
        let groups = overlap_groups(&positions, &faces, false);
        assert_eq!(groups, vec![vec![0, 1]]);
        let existing = Default::default();
        let o = overlay(&mut positions, &faces, &groups[0], &existing, Keep::Once).unwrap();
        let mut area = 0.0;
        for c in &o.cells {
            let [a, b, d] = c.map(|v| positions[v as usize]);
            let twice = (b - a).cross(d - a).z;
            let longest = [(b - a), (d - b), (a - d)]
                .iter()
                .map(|e| e.length_squared())
                .fold(0.0, f64::max);
            assert!(twice > longest * 1e-6, "a sliver cell {c:?}");
            area += 0.5 * twice;
        }
        // Below y = 0: the triangle (3, −1), (3, 0) and the crossing of
        // 3 → 4 with y = 0, at x = 1 + 2ε/(1 + ε). Beyond x + y = 4: the
        // triangle (3, 1), (3, 2) and the crossing of 3 → 5 with it, at
        // (2.5, 1.5) to ε: 1/4.
        let eps = 1e-10;
        let below = 0.5 * (3.0 - (1.0 + 2.0 * eps / (1.0 + eps)));
        assert!((area - (8.0 + below + 0.25)).abs() < 1e-9, "area {area}");
        assert!(
            o.sides.iter().any(|(_, on)| on.contains(&3)),
            "no side split at the corner beside it: {:?}",
            o.sides
        );
    }

    /// A face overlapping a wall from one side, and a face of no area on a
    /// wall face's side, belong to the wall's group: the overlay replaces
    /// them too. A face overlapping the second square beyond the first
    /// cancels it there (count −1 + 1), and the flat face adds nothing:
    /// the cells facing down cover the second square less that face.
    #[test]
    fn faces_over_a_wall_and_flat_faces_on_it_join_its_group() {
        let (mut positions, mut faces) = two_squares();
        positions.extend([
            // A triangle facing up over the second square beyond the first.
            DVec3::new(1.1, 0.1, 1.0),
            DVec3::new(1.4, 0.1, 1.0),
            DVec3::new(1.1, 0.4, 1.0),
            // On the line through corners 0 and 1, beyond 1.
            DVec3::new(2.0, 0.0, 1.0),
        ]);
        faces.extend([[8, 9, 10], [0, 1, 11]]);
        let groups = wall_groups(&positions, &faces);
        assert_eq!(groups, vec![vec![0, 1, 2, 3, 4, 5]]);
        let cells = overlay(
            &mut positions,
            &faces,
            &groups[0],
            &Default::default(),
            Keep::Count,
        )
        .unwrap()
        .cells;
        let down: f64 = cells
            .iter()
            .map(|c| {
                let [a, b, d] = c.map(|v| positions[v as usize]);
                -0.5 * (b - a).cross(d - a).z
            })
            .filter(|&z| z > 0.0)
            .sum();
        assert!((down - (0.5 - 0.045)).abs() < 1e-15, "{down}");
    }

    /// Coplanar faces facing the same way, and opposite faces in parallel
    /// planes, are no wall.
    #[test]
    fn same_facing_or_parallel_faces_are_no_wall() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(1.2, 0.2, 0.0),
            DVec3::new(0.2, 1.2, 0.0),
            DVec3::new(0.2, 0.2, 1e-300),
            DVec3::new(1.2, 0.2, 1e-300),
            DVec3::new(0.2, 1.2, 1e-300),
        ];
        assert!(wall_groups(&positions, &[[0, 1, 2], [3, 4, 5]]).is_empty());
        assert!(wall_groups(&positions, &[[0, 1, 2], [6, 8, 7]]).is_empty());
        assert_eq!(wall_groups(&positions, &[[0, 1, 2], [3, 5, 4]]).len(), 1);
    }

    /// Ten faces of one wall of `thingi10k_1063852.stl` minus its mirror
    /// image in x (all at y = 13.385283470153809, the part's face and
    /// its image's, with the cut's points on them), the smallest subset
    /// of the 16-face group on which spade's splitting insertion panics:
    /// sides crossing a few ulps from a corner. The overlay then inserts
    /// the crossings found first, and its cells cover the plane as the
    /// faces do: each cell counted by the faces over it, so the cells'
    /// signed areas (y dropped) add up to the faces'.
    #[test]
    fn a_wall_that_panics_the_splitting_insertion_is_overlaid_with_its_crossings_found_first() {
        let at = [
            (-3.019016248445839, -2.8433787218624027),
            (-2.5876708030700684, -2.989004135131836),
            (-3.045091595392058, -2.8349172599194614),
            (-3.031394471140626, -2.8391997423118034),
            (-2.722344398498535, -3.098073959350586),
            (-3.00341037264669, -2.9874120080475177),
            (-2.855867385864258, -3.2141571044921875),
            (-3.0032924523159252, -2.9878434308790656),
            (-2.912061358911717, -3.188620579798563),
            (-2.9504255694645125, -3.1711865284759155),
            (-2.951905247436828, -3.170514110580731),
            (-3.003309524356804, -2.987780971181332),
        ];
        let mut positions: Vec<DVec3> = at
            .iter()
            .map(|&(x, z)| DVec3::new(x, 13.385283470153809, z))
            .collect();
        let faces = vec![
            [0, 2, 3],
            [2, 1, 5],
            [6, 8, 7],
            [9, 10, 7],
            [7, 11, 4],
            [11, 5, 4],
            [9, 0, 3],
            [9, 3, 10],
            [3, 11, 7],
            [10, 3, 7],
        ];
        let group: Vec<usize> = (0..faces.len()).collect();
        let signs: Vec<Sign> = faces
            .iter()
            .map(|&f| projected_sign(&positions, f, 1))
            .collect();
        assert!(triangulate(&positions, &faces, &group, &signs, 1, Keep::Count).is_some());
        // Twice the signed area in the plane y = const, seen from +y.
        let twice = |p: &[DVec3], f: [u32; 3]| {
            let [a, b, c] = f.map(|v| p[v as usize]);
            (b - a).cross(c - a).y
        };
        let faces_area: f64 = faces.iter().map(|&f| twice(&positions, f)).sum();
        let o = overlay(
            &mut positions,
            &faces,
            &group,
            &Default::default(),
            Keep::Count,
        )
        .expect("overlaid with the crossings found first");
        let cells_area: f64 = o.cells.iter().map(|&c| twice(&positions, c)).sum();
        let scale: f64 = faces.iter().map(|&f| twice(&positions, f).abs()).sum();
        assert!(
            (cells_area - faces_area).abs() <= 1e-9 * scale,
            "cells {cells_area}, faces {faces_area}"
        );
        assert!(!o.cells.is_empty());
    }

    /// 34 faces of one wall (all at x = −16) met while snap-rounding the
    /// OpenSCAD export's self-union (`openscad-nonmanifold-crash.obj`,
    /// snapped to a grid of 2⁻³¹ and resolved): slivers whose sides cross
    /// a few ulps from each other. spade's splitting insertion turned
    /// about one of their vertices for ten minutes on them. The overlay no
    /// longer asks it: with the crossings found first, one piece still
    /// crosses another where its rounded ends put it, and the overlay
    /// returns at once, declining the wall (which the Boolean then keeps,
    /// and counts).
    #[test]
    fn a_wall_on_which_the_splitting_insertion_circled_is_declined_at_once() {
        let at = [
            (-7.847175987530775, -206.71203754984023),
            (-7.847175990977017, -206.71203755481974),
            (-7.847175988333235, -206.71198274030647),
            (-7.8471759884790435, -206.71198274020963),
            (-7.847194627393037, -207.1209882046096),
            (-7.847196641824835, -206.71206739351646),
            (-7.84717598748616, -206.7120405971352),
            (-7.847175991115918, -206.71204060280553),
            (-7.8471759876819185, -206.71202722646527),
            (-7.847175990862027, -206.71203503151537),
            (-7.847175990866654, -206.7120351330354),
            (-7.847175987567722, -206.71203502636908),
            (-7.847175987566235, -206.71203512787957),
            (-7.847175987641704, -206.7120299731957),
            (-7.847175990506528, -206.71202723057925),
            (-7.847175990631725, -206.71202997786665),
            (-7.847175988464453, -206.71198242004445),
            (-7.84717598836869, -206.7119803186506),
            (-9.79738093772903, -209.75860320031643),
        ];
        let faces = vec![
            [0, 1, 2],
            [3, 2, 1],
            [1, 4, 5],
            [4, 6, 7],
            [8, 9, 10],
            [11, 7, 12],
            [13, 7, 11],
            [12, 7, 0],
            [8, 7, 13],
            [0, 7, 6],
            [2, 3, 14],
            [9, 8, 15],
            [15, 8, 14],
            [8, 10, 1],
            [2, 14, 8],
            [8, 1, 7],
            [5, 4, 7],
            [5, 7, 1],
            [5, 3, 16],
            [5, 9, 15],
            [5, 15, 14],
            [5, 14, 3],
            [17, 14, 8],
            [5, 18, 1],
            [1, 0, 12],
            [18, 7, 1],
            [10, 1, 12],
            [11, 9, 12],
            [12, 9, 10],
            [13, 15, 11],
            [11, 15, 9],
            [13, 8, 14],
            [13, 14, 15],
            [4, 7, 18],
        ];
        let mut positions: Vec<DVec3> = at.iter().map(|&(y, z)| DVec3::new(-16.0, y, z)).collect();
        let group: Vec<usize> = (0..faces.len()).collect();
        let before = positions.len();
        let made = overlay(
            &mut positions,
            &faces,
            &group,
            &Default::default(),
            Keep::Count,
        );
        assert!(
            made.is_none(),
            "the wall was overlaid: check its cells' areas instead"
        );
        assert_eq!(
            positions.len(),
            before,
            "a declined overlay appends nothing"
        );
    }
}
