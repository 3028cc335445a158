//! Patches of triangles that provably lie flat: two triangles of one
//! certified patch meet only where they share a vertex or an edge, so
//! their pair needs no test.
//!
//! [`stars`](super::stars) certify the triangles around one vertex. CAD
//! caps are not fans around a vertex: a flat end of a turned part is a
//! polygon of hundreds of outline points triangulated into long slivers
//! from no common corner, and every sliver's box overlaps most others'.
//! On Thingi10K 1514499, 740,190 of the 1,057,380 candidate pairs of its
//! self-intersection check shared no vertex, most of them within such
//! caps. A patch is certified as a whole instead.
//!
//! **The patches.** Each triangle gets a class: the coordinate axis `k`
//! of its normal's largest component, and the sign `σ` of its exact
//! orientation projected along `k` (the plane across `k`, its two
//! coordinates in cyclic order, so the sign is that of the normal's
//! component). A triangle whose projection has no area, or that repeats
//! an identity, has no class. Two triangles of one class are joined
//! across an edge (of identities) when they are the only two of that
//! class on it and traverse it in opposite directions; a patch is a
//! connected set of such joins. Its *boundary* is the chain of its
//! half-edges that were not joined.
//!
//! **The certificate.** A patch is certified when its boundary, projected
//! along `k`, is a set of disjoint simple closed polygons (checked exactly
//! and strictly, below) whose winding numbers add up to 0 or `σ`
//! everywhere. Then no two projected triangles of the patch overlap:
//! - every projected triangle is positively oriented in the sense `σ`, so
//!   the number of them covering a point `y` off their edges is
//!   `σ · Σ_T w(∂T, y)`, where `w` is the winding number;
//! - the joined half-edges cancel in pairs, so `Σ_T ∂T` is the boundary
//!   chain, and the count is `σ · w(boundary, y)`: at most 1.
//!
//! Two triangles whose projections share a point that is not the image of
//! a vertex or edge they share would overlap near it, or leave two
//! boundary edges of different identities on one segment, or pass the
//! boundary through that point twice; each is excluded (a boundary
//! polygon that touches itself, even collinearly, is not simple). Each
//! triangle projects one to one, so two triangles of a certified patch
//! meet in space only in the vertex or edge they share.
//!
//! Every sign used is strict (`orient2d ≠ 0`, boxes apart by a positive
//! gap), and an infinitesimal perturbation keeps strict signs and integer
//! winding numbers (two consecutive boundary edges are not compared: on
//! one line, they go on the same way, and still do when they bend a
//! little). So the same holds in the perturbed world of simulation of
//! simplicity. A patch that fails any test is not certified, and its
//! pairs are tested as before.
//!
//! **Where it pays.** The tree descent of a self-intersection check
//! skips every pair of subtrees of one certified patch
//! ([`holey_geom::Bvh::self_overlaps_apart_filter_map`]), so those pairs
//! cost neither a test nor a visit. On EMBER's turned parts most
//! triangles are certified (all 26,580 of 1514499's patches of four or
//! more, 66,705 of 1063852's 68,548 triangles).

use crate::mesh::repeats_a_corner;
use glam::{DVec2, DVec3};
use holey_geom::orient::{Sign, orient2d};
use holey_mesh::UnionFind;
use rayon::prelude::*;

/// A triangle in no certified patch.
pub(crate) const NO_PATCH: u32 = u32::MAX;

/// The class of a triangle with none ([module documentation](self)).
const NO_CLASS: u8 = u8::MAX;

/// Patches of fewer triangles hold at most a pair or two that share no
/// edge: not worth a boundary walk.
const MIN_TRIANGLES: usize = 4;

/// The most boundary cycles a patch may have: the winding sums cost one
/// pass over the boundary per cycle.
const MAX_CYCLES: usize = 32;

/// Each triangle's certified patch (numbered from 0), or [`NO_PATCH`]
/// ([module documentation](self)); `ids` are the vertices' identities, as
/// `holey_geom::position_classes` numbers them.
pub(crate) fn flat_patches(tris: &[[u32; 3]], positions: &[DVec3], ids: &[u32]) -> Vec<u32> {
    let classes: Vec<u8> = tris
        .par_iter()
        .map(|t| class_of(*t, positions, ids))
        .collect();
    let (joined, mut sets) = join_across_edges(tris, ids, &classes);
    let (label, count) = sets.labels();
    let mut size = vec![0u32; count];
    for &l in &label {
        size[l as usize] += 1;
    }
    // Each patch's boundary half-edges (`3t + j`: from corner `j` of
    // triangle `t` to the next), gathered by a counting sort.
    let big = |t: usize| size[label[t] as usize] as usize >= MIN_TRIANGLES;
    let mut start = vec![0u32; count + 1];
    for (h, &j) in joined.iter().enumerate() {
        if !j && big(h / 3) {
            start[label[h / 3] as usize + 1] += 1;
        }
    }
    for c in 0..count {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut boundary = vec![0u32; start[count] as usize];
    for (h, &j) in joined.iter().enumerate() {
        if !j && big(h / 3) {
            let at = &mut fill[label[h / 3] as usize];
            boundary[*at as usize] = h as u32;
            *at += 1;
        }
    }
    // The first triangle of each patch gives its class.
    let mut first = vec![u32::MAX; count];
    for (t, &l) in label.iter().enumerate().rev() {
        first[l as usize] = t as u32;
    }
    let certified: Vec<bool> = (0..count)
        .into_par_iter()
        .map(|c| {
            // Unclassed triangles are never joined: their sets are
            // singletons, below the size.
            let class = classes[first[c] as usize];
            size[c] as usize >= MIN_TRIANGLES
                && Boundary::of(
                    &boundary[start[c] as usize..start[c + 1] as usize],
                    tris,
                    positions,
                    ids,
                    class / 2,
                )
                .is_certified(if class % 2 == 1 { 1 } else { -1 })
        })
        .collect();
    let mut number = vec![NO_PATCH; count];
    let mut next = 0;
    for c in 0..count {
        if certified[c] {
            number[c] = next;
            next += 1;
        }
    }
    label.iter().map(|&l| number[l as usize]).collect()
}

/// The triangles a tree's box sample stands for: at most this many
/// queries decide whether certifying patches pays ([`pay`]).
const PAY_SAMPLE: usize = 256;

/// Candidate pairs per triangle, not counting pairs that share an edge,
/// past which certifying patches pays ([`pay`]). A smooth surface's
/// triangles meet about 4.5 other boxes each beyond their edge
/// neighbours: their vertex neighbours, which a flat star dismisses about
/// as cheaply as the descent would skip them (the bunny, spot, the
/// self-intersecting solids: 4.5 to 4.9). Certifying costs about as much
/// per triangle as testing two pairs (4–5 ms for 68,548 triangles), so it
/// pays where there are about two more: CAD parts' long slivers give 7
/// to 35 (Thingi10K 1063852: 7.3; 1514499: 35).
const PAYS_PER_TRIANGLE: f64 = 6.5;

/// Whether certifying flat patches is likely to pay on the mesh `tris`
/// whose triangles' boxes are in `tree` (primitive `i` is triangle
/// `triangle_of(i)`): the candidate pairs that share no edge, estimated
/// from a sample of the tree's boxes, against [`PAYS_PER_TRIANGLE`]. A
/// cost estimate only: either answer gives the same intersections.
pub(crate) fn pay(
    tree: &holey_geom::Bvh,
    triangle_of: impl Fn(u32) -> u32,
    tris: &[[u32; 3]],
    ids: &[u32],
) -> bool {
    let identities = |i: u32| tris[triangle_of(i) as usize].map(|v| ids[v as usize]);
    let pairs = tree.estimate_self_overlaps(PAY_SAMPLE, |a, b| {
        let (x, y) = (identities(a), identities(b));
        x.iter().filter(|i| y.contains(i)).count() < 2
    });
    pairs >= PAYS_PER_TRIANGLE * tree.len() as f64
}

/// `p` projected along coordinate axis `axis`, onto the other two in
/// cyclic order.
fn project(axis: u8, p: DVec3) -> DVec2 {
    match axis {
        0 => DVec2::new(p.y, p.z),
        1 => DVec2::new(p.z, p.x),
        _ => DVec2::new(p.x, p.y),
    }
}

/// A triangle's class: `2k + 1` or `2k` for axis `k` and a positive or
/// negative projected orientation; [`NO_CLASS`] when it has none.
fn class_of(t: [u32; 3], positions: &[DVec3], ids: &[u32]) -> u8 {
    let i = t.map(|v| ids[v as usize]);
    if repeats_a_corner(&i) {
        return NO_CLASS;
    }
    let p = t.map(|v| positions[v as usize]);
    let n = (p[1] - p[0]).cross(p[2] - p[0]).abs();
    let axis = if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    };
    match orient2d(
        project(axis, p[0]),
        project(axis, p[1]),
        project(axis, p[2]),
    ) {
        Sign::Positive => 2 * axis + 1,
        Sign::Negative => 2 * axis,
        Sign::Zero => NO_CLASS,
    }
}

/// Which half-edges were joined to their twin, and the sets of triangles
/// the joins make ([module documentation](self)).
fn join_across_edges(tris: &[[u32; 3]], ids: &[u32], classes: &[u8]) -> (Vec<bool>, UnionFind) {
    // Half-edges of classed triangles by their smaller identity (a
    // counting sort): each bucket holds a vertex's edges to larger
    // identities, a handful, keyed so that one edge's half-edges of one
    // class sort into a run.
    let n = ids.len();
    let edges_of = |t: usize| {
        let i = tris[t].map(|v| ids[v as usize]);
        [(i[0], i[1]), (i[1], i[2]), (i[2], i[0])]
    };
    let mut start = vec![0u32; n + 1];
    for t in (0..tris.len()).filter(|&t| classes[t] != NO_CLASS) {
        for (a, b) in edges_of(t) {
            start[a.min(b) as usize + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    // Each entry is (key, half-edge), the key `larger identity · 2⁸ +
    // class`, times 2, plus whether the edge runs to the larger identity.
    let mut bucket = vec![(0u64, 0u32); start[n] as usize];
    for t in (0..tris.len()).filter(|&t| classes[t] != NO_CLASS) {
        for (j, (a, b)) in edges_of(t).into_iter().enumerate() {
            let at = &mut fill[a.min(b) as usize];
            let key = ((u64::from(a.max(b)) << 8 | u64::from(classes[t])) << 1) | u64::from(a < b);
            bucket[*at as usize] = (key, (3 * t + j) as u32);
            *at += 1;
        }
    }
    let mut joined = vec![false; 3 * tris.len()];
    let mut sets = UnionFind::new(tris.len());
    for v in 0..n {
        let run = &mut bucket[start[v] as usize..start[v + 1] as usize];
        run.sort_unstable_by_key(|e| e.0);
        for group in run.chunk_by(|x, y| x.0 >> 1 == y.0 >> 1) {
            if let [(k1, h1), (k2, h2)] = group
                && k1 != k2
            {
                joined[*h1 as usize] = true;
                joined[*h2 as usize] = true;
                sets.union(h1 / 3, h2 / 3);
            }
        }
    }
    (joined, sets)
}

/// One boundary edge, projected: identities and points of its ends.
#[derive(Clone, Copy)]
struct Side {
    from: u32,
    to: u32,
    a: DVec2,
    b: DVec2,
}

impl Side {
    fn lo(&self) -> DVec2 {
        self.a.min(self.b)
    }

    fn hi(&self) -> DVec2 {
        self.a.max(self.b)
    }
}

/// A patch's boundary chain, projected, sorted by the identity each edge
/// starts from.
struct Boundary {
    sides: Vec<Side>,
}

impl Boundary {
    fn of(
        half_edges: &[u32],
        tris: &[[u32; 3]],
        positions: &[DVec3],
        ids: &[u32],
        axis: u8,
    ) -> Self {
        let mut sides: Vec<Side> = half_edges
            .iter()
            .map(|&h| {
                let t = tris[h as usize / 3];
                let j = h as usize % 3;
                let (u, v) = (t[j] as usize, t[(j + 1) % 3] as usize);
                Side {
                    from: ids[u],
                    to: ids[v],
                    a: project(axis, positions[u]),
                    b: project(axis, positions[v]),
                }
            })
            .collect();
        sides.sort_unstable_by_key(|s| s.from);
        Boundary { sides }
    }

    /// Whether the boundary is disjoint simple closed polygons whose
    /// winding numbers, times `sigma` (±1), sum to 0 or 1 everywhere.
    fn is_certified(&self, sigma: i32) -> bool {
        let Some(cycles) = self.cycles() else {
            return false;
        };
        cycles.len() <= MAX_CYCLES
            && self.apart_unless_consecutive()
            && self.windings_are_at_most_one(&cycles, sigma)
    }

    /// The boundary's cycles, as indices into `sides` in order; `None`
    /// unless every identity starts at most one edge and ends as many as
    /// it starts (so the chain closes into disjoint simple cycles of
    /// identities).
    fn cycles(&self) -> Option<Vec<Vec<u32>>> {
        let s = &self.sides;
        if s.windows(2).any(|w| w[0].from == w[1].from) {
            return None;
        }
        let mut seen = vec![false; s.len()];
        let mut cycles = Vec::new();
        for first in 0..s.len() {
            if seen[first] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut at = first;
            loop {
                if seen[at] {
                    return None;
                }
                seen[at] = true;
                cycle.push(at as u32);
                at = s.binary_search_by_key(&s[at].to, |x| x.from).ok()?;
                if at == first {
                    break;
                }
            }
            cycles.push(cycle);
            if cycles.len() > MAX_CYCLES {
                return None;
            }
        }
        Some(cycles)
    }

    /// Every two edges that are not consecutive in a cycle are apart:
    /// their boxes (closed) are disjoint, or one's line leaves the other
    /// strictly on one side. The sweep along x gives up (not certified)
    /// past a budget of box comparisons linear in the edges.
    ///
    /// Consecutive edges `a → b → c` need no test of their own: they
    /// overlap beyond `b` only on one line, with `c` back towards `a`.
    /// Then the edge after `c` starts on `a → b` (`c` between them, or at
    /// `a`), or `a` lies on `b → c` and the edge before `a` ends on it;
    /// either touches an edge it does not follow, unless the cycle is
    /// those three points alone, which has no orientation.
    fn apart_unless_consecutive(&self) -> bool {
        let s = &self.sides;
        let mut order: Vec<u32> = (0..s.len() as u32).collect();
        order.sort_unstable_by(|&i, &j| s[i as usize].lo().x.total_cmp(&s[j as usize].lo().x));
        let mut budget = 32 * s.len() + 256;
        for (k, &i) in order.iter().enumerate() {
            let e = s[i as usize];
            let (lo, hi) = (e.lo(), e.hi());
            for &j in &order[k + 1..] {
                let f = s[j as usize];
                let (flo, fhi) = (f.lo(), f.hi());
                if flo.x > hi.x {
                    break;
                }
                if budget == 0 {
                    return false;
                }
                budget -= 1;
                let consecutive = e.to == f.from || f.to == e.from;
                if consecutive || flo.y > hi.y || fhi.y < lo.y {
                    continue;
                }
                if !strictly_apart(e.a, e.b, f.a, f.b) {
                    return false;
                }
            }
        }
        true
    }

    /// The number of projected triangles over any point is `sigma` times
    /// the boundary's winding number there ([module documentation](self)):
    /// it must be 0 or 1 on both sides of every cycle. The other cycles'
    /// winding numbers are constant near a cycle (they are apart from it),
    /// so each cycle's first corner gives them.
    fn windings_are_at_most_one(&self, cycles: &[Vec<u32>], sigma: i32) -> bool {
        cycles.iter().enumerate().all(|(i, cycle)| {
            let p = self.sides[cycle[0] as usize].a;
            let around: i32 = cycles
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, other)| self.winding(other, p))
                .sum();
            let own = self.orientation(cycle);
            if own == 0 {
                return false;
            }
            let (outside, inside) = (sigma * around, sigma * (around + own));
            (0..=1).contains(&outside) && (0..=1).contains(&inside)
        })
    }

    /// The winding number of `cycle` around `p`, a point on no edge of it
    /// (exact: crossings of the ray from `p` along +x, each decided by
    /// `orient2d`).
    fn winding(&self, cycle: &[u32], p: DVec2) -> i32 {
        let mut w = 0;
        for &e in cycle {
            let Side { a, b, .. } = self.sides[e as usize];
            if a.y <= p.y {
                if b.y > p.y && orient2d(a, b, p) == Sign::Positive {
                    w += 1;
                }
            } else if b.y <= p.y && orient2d(a, b, p) == Sign::Negative {
                w -= 1;
            }
        }
        w
    }

    /// +1 when the simple polygon `cycle` runs counter-clockwise, −1 when
    /// clockwise: the turn at its lowest corner in (x, y) order; 0 when its
    /// corners are on one line.
    fn orientation(&self, cycle: &[u32]) -> i32 {
        let n = cycle.len();
        let corner = |i: usize| self.sides[cycle[i % n] as usize].a;
        let low = (0..n)
            .min_by(|&i, &j| {
                let (p, q) = (corner(i), corner(j));
                p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y))
            })
            .unwrap_or(0);
        match orient2d(corner(low + n - 1), corner(low), corner(low + 1)) {
            Sign::Positive => 1,
            Sign::Negative => -1,
            Sign::Zero => 0,
        }
    }
}

/// Whether segments `p` and `q` are strictly apart: one's line leaves
/// both ends of the other strictly on one side. Two segments whose boxes
/// meet and that are not strictly apart share a point.
fn strictly_apart(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> bool {
    let one_side = |a: DVec2, b: DVec2, c: DVec2, d: DVec2| {
        let s = orient2d(a, b, c);
        s != Sign::Zero && s == orient2d(a, b, d)
    };
    one_side(p0, p1, q0, q1) || one_side(q0, q1, p0, p1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::intersect::tests::ellipse;

    /// `p` turned about (1, 2, 3) by 0.7 radians and moved: no axis of
    /// the patch stays put.
    fn turned(p: DVec3) -> DVec3 {
        crate::intersect::tests::turn(p) + DVec3::new(3.0, -1.0, 0.5)
    }

    /// The polygon `outline` triangulated as a zigzag strip between its
    /// two ends, as CAD exports cap a face: long slivers, no vertex
    /// common to them all.
    fn zigzag(n: u32) -> Vec<[u32; 3]> {
        let (mut lo, mut hi) = (0u32, n - 1);
        let mut tris = Vec::new();
        let mut left = true;
        while hi - lo > 1 {
            if left {
                tris.push([lo, lo + 1, hi]);
                lo += 1;
            } else {
                tris.push([lo, hi - 1, hi]);
                hi -= 1;
            }
            left = !left;
        }
        tris
    }

    fn patches_of(positions: &[DVec3], tris: &[[u32; 3]]) -> Vec<u32> {
        let ids = holey_geom::position_classes(positions).unwrap();
        flat_patches(tris, positions, &ids)
    }

    /// One patch, not [`NO_PATCH`], holding every triangle.
    fn one_patch(patches: &[u32]) -> bool {
        patches[0] != NO_PATCH && patches.iter().all(|&p| p == patches[0])
    }

    /// A turned flat cap of 40 slivers is one certified patch, in either
    /// orientation.
    #[test]
    fn a_turned_zigzag_cap_is_one_certified_patch() {
        let positions: Vec<DVec3> = ellipse(42, 3.0, 1.0).into_iter().map(turned).collect();
        let tris = zigzag(42);
        assert_eq!(tris.len(), 40);
        assert!(one_patch(&patches_of(&positions, &tris)));
        let flipped: Vec<[u32; 3]> = tris.iter().map(|&[a, b, c]| [a, c, b]).collect();
        assert!(one_patch(&patches_of(&positions, &flipped)));
    }

    /// An annulus (a cap with a hole) has two boundary cycles, one inside
    /// the other with opposite orientations: one triangle over each
    /// point, certified.
    #[test]
    fn an_annulus_is_certified_with_two_boundary_cycles() {
        let n = 24u32;
        let mut positions = ellipse(n as usize, 3.0, 2.0);
        positions.extend(ellipse(n as usize, 1.5, 1.0));
        let positions: Vec<DVec3> = positions.into_iter().map(turned).collect();
        let mut tris = Vec::new();
        for i in 0..n {
            let j = (i + 1) % n;
            tris.push([i, j, n + j]);
            tris.push([i, n + j, n + i]);
        }
        assert!(one_patch(&patches_of(&positions, &tris)));
        // Two annuli stacked a little apart, joined by nothing: each is a
        // patch of its own, certified on its own.
        let mut two = positions.clone();
        two.extend(positions.iter().map(|p| *p + DVec3::new(0.0, 0.0, 0.1)));
        let mut both = tris.clone();
        both.extend(tris.iter().map(|t| t.map(|v| v + 2 * n)));
        let patches = patches_of(&two, &both);
        assert!(one_patch(&patches[..tris.len()]) && one_patch(&patches[tris.len()..]));
        assert_ne!(patches[0], patches[tris.len()]);
    }

    /// A ribbon of quads along an arc of `turn` radians between radii 1
    /// and 2, rising by `rise` per radian: past a full turn its ends lie
    /// over each other in projection.
    fn ramp(turn: f64, rise: f64, steps: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        for i in 0..=steps {
            let a = turn * i as f64 / steps as f64;
            for r in [1.0, 2.0] {
                positions.push(DVec3::new(r * a.cos(), r * a.sin(), rise * a));
            }
        }
        let mut tris = Vec::new();
        for i in 0..steps {
            let (inner, outer) = (2 * i, 2 * i + 1);
            tris.push([inner, outer, outer + 2]);
            tris.push([inner, outer + 2, inner + 2]);
        }
        (positions, tris)
    }

    /// A ramp short of a turn is certified. One past a full turn lies
    /// apart from itself in space, yet its boundary crosses itself in
    /// projection, so it is not: the certificate never looks at heights.
    #[test]
    fn a_ramp_is_certified_until_it_passes_over_itself() {
        let (p, t) = ramp(5.5, 0.02, 40);
        assert!(one_patch(&patches_of(&p, &t)));
        let (p, t) = ramp(8.0, 0.02, 60);
        assert!(patches_of(&p, &t).iter().all(|&q| q == NO_PATCH));
    }

    /// A square grid of 4 × 4 quads, turned, is one patch, also with its
    /// middle vertex moved a little. Moved onto the diagonal of a
    /// neighbouring quad, one triangle has no area and the rest is a grid
    /// with a hole whose boundary touches itself (two of its edges lie on
    /// the third): not certified. Moved past the diagonal, that triangle
    /// flips into another class, and the hole it leaves has the outer
    /// boundary's orientation: its neighbours cover it twice (the winding
    /// numbers sum to 2 there), so the rest is not certified either.
    #[test]
    fn touching_and_folded_grids_are_not_certified() {
        let grid = |mid: DVec3| {
            let mut positions = Vec::new();
            for y in 0..5 {
                for x in 0..5 {
                    positions.push(DVec3::new(x as f64, y as f64, 0.0));
                }
            }
            positions[12] = mid;
            let mut tris = Vec::new();
            for y in 0..4u32 {
                for x in 0..4u32 {
                    let v = 5 * y + x;
                    tris.push([v, v + 1, v + 6]);
                    tris.push([v, v + 6, v + 5]);
                }
            }
            let positions: Vec<DVec3> = positions.into_iter().map(turned).collect();
            patches_of(&positions, &tris)
        };
        assert!(one_patch(&grid(DVec3::new(2.0, 2.0, 0.0))));
        assert!(one_patch(&grid(DVec3::new(2.3, 2.1, 0.0))));
        // The quad from (2, 1) to (3, 2), split along its diagonal.
        for moved in [DVec3::new(2.5, 1.5, 0.0), DVec3::new(2.7, 1.5, 0.0)] {
            assert!(grid(moved).iter().all(|&q| q == NO_PATCH), "{moved}");
        }
    }

    /// A grid of `n` × `n` unit quads in the plane z = 0 (axis-aligned,
    /// so points on diagonals are exact), each split along the diagonal
    /// from its lower-left corner, without the quads `holes` (by lower-left
    /// corner).
    fn square_grid(n: u32, holes: &[(u32, u32)]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        for y in 0..=n {
            for x in 0..=n {
                positions.push(DVec3::new(x as f64, y as f64, 0.0));
            }
        }
        let mut tris = Vec::new();
        for y in 0..n {
            for x in (0..n).filter(|&x| !holes.contains(&(x, y))) {
                let v = (n + 1) * y + x;
                tris.push([v, v + 1, v + n + 2]);
                tris.push([v, v + n + 2, v + n + 1]);
            }
        }
        (positions, tris)
    }

    /// Two holes meeting at one corner make one boundary that passes a
    /// vertex twice (a pinch): not certified, though every triangle turns
    /// the same way and no two overlap. With one hole, an annulus,
    /// certified.
    #[test]
    fn a_boundary_through_a_vertex_twice_is_not_certified() {
        let (p, t) = square_grid(4, &[(1, 1)]);
        assert!(one_patch(&patches_of(&p, &t)));
        let (p, t) = square_grid(4, &[(1, 1), (2, 2)]);
        assert!(patches_of(&p, &t).iter().all(|&q| q == NO_PATCH));
    }

    /// A T-junction: one quad's diagonal split on one side by two points
    /// the other side does not have. The hole between the sides is a cycle
    /// of edges on one line: not certified, in the plane or with the two
    /// points lifted a little (still on the diagonal in projection, and
    /// their triangles still of the class of the plane: lifted much, they
    /// would leave the patch, and the hole they leave is a patch's own).
    #[test]
    fn a_t_junction_is_not_certified() {
        for lift in [0.0, 0.05] {
            let (mut p, mut t) = square_grid(3, &[]);
            // Quad (1, 1): corners 5, 6, 10, 9; its upper triangle
            // [5, 10, 9] becomes three through points on the diagonal 5–10.
            let m1 = p.len() as u32;
            p.push(DVec3::new(1.25, 1.25, lift));
            p.push(DVec3::new(1.75, 1.75, lift));
            let upper = t.iter().position(|&x| x == [5, 10, 9]).unwrap();
            t.remove(upper);
            t.extend([[5, m1, 9], [m1, m1 + 1, 9], [m1 + 1, 10, 9]]);
            assert!(
                patches_of(&p, &t).iter().all(|&q| q == NO_PATCH),
                "lift {lift}"
            );
        }
    }

    /// A fan around a centre sweeping exactly one turn whose last rim
    /// point lies straight above its first: the two edges from the centre
    /// along the boundary lie on one segment in projection (a fold at the
    /// centre), and the rim's last edge touches the first edge from the
    /// centre, which it does not follow. Not certified. Short of the
    /// turn, certified.
    #[test]
    fn a_fan_closing_over_itself_is_not_certified() {
        let fan = |turn: f64| {
            let steps = 12;
            let mut positions = vec![DVec3::ZERO];
            for i in 0..=steps {
                let a = turn * i as f64 / steps as f64;
                let (s, c) = if i == steps && turn == std::f64::consts::TAU {
                    (0.0, 1.0)
                } else {
                    a.sin_cos()
                };
                positions.push(DVec3::new(c, s, 0.01 * i as f64));
            }
            let tris: Vec<[u32; 3]> = (1..=steps).map(|i| [0, i, i + 1]).collect();
            patches_of(&positions, &tris)
        };
        assert!(one_patch(&fan(5.0)));
        assert!(fan(std::f64::consts::TAU).iter().all(|&q| q == NO_PATCH));
    }
}
