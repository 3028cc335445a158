//! A bounding volume hierarchy over axis-aligned boxes (§3.2).
//!
//! **Build.** Top-down median split, as in the paper ("a fast, median-split,
//! top-down, divide-and-conquer build inspired by Wald 2007"): at each node
//! the primitives' centroid bounds are computed, the axis of largest extent
//! is chosen, and a quickselect (`select_nth_unstable_by`) partitions the
//! primitives at the median; the halves are built recursively (in parallel
//! with rayon above [`PARALLEL_THRESHOLD`] primitives). Each level costs
//! O(n), so the build is O(n log n), like a quicksort. No SAH: the median
//! split gives a balanced tree of depth ⌈log₂(n / leaf size)⌉ whose node
//! count is known from `n` alone, so each subtree is written straight into
//! its own slice of the node array (pre-order: the left child follows its
//! parent; the right child follows the left subtree).
//!
//! **Boxes** are closed: boxes that merely touch overlap. They are built
//! from exact coordinates with `min`/`max` only (no rounding), so a box
//! contains its primitive exactly and no overlap can be missed.
//!
//! **Queries.** One box against the tree ([`Bvh::query`]); a batch of boxes
//! streamed over the tree ([`Bvh::overlap_pairs`], parallel over chunks of
//! the batch, output in batch order then tree order: deterministic); all
//! pairs of overlapping primitives ([`Bvh::self_overlaps`], a simultaneous
//! descent of the tree against itself, parallel over the top levels, each
//! unordered pair once), or those of primitives in different groups
//! ([`Bvh::self_overlaps_apart_filter_map`], skipping whole subtrees of
//! one group); all pairs across two trees
//! ([`Bvh::overlaps_with_filter_map`], the same descent of one tree
//! against another, for two meshes whose own overlaps do not matter).
//! **Refit** recomputes boxes bottom-up after the
//! primitives moved, either everywhere ([`Bvh::refit`]) or only above the
//! primitives that changed ([`Bvh::refit_some`], O(k log n)): for local
//! edits such as a sculpting brush. Refitting keeps the topology, so the
//! tree degrades if primitives move far; rebuild then.

use crate::error::{GeomError, NonFinite};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// Most primitives in a leaf.
pub const LEAF_SIZE: usize = 4;
/// Subtrees with more primitives than this are built in parallel.
pub const PARALLEL_THRESHOLD: usize = 8192;

/// A closed axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The corner with the smallest coordinates (`+∞` in every axis for
    /// [`Aabb::EMPTY`]).
    pub min: DVec3,
    /// The corner with the largest coordinates (`−∞` in every axis for
    /// [`Aabb::EMPTY`]).
    pub max: DVec3,
}

impl Aabb {
    /// The empty box (overlaps nothing; identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The box with corners `min` and `max`, as given (neither checked nor
    /// reordered).
    pub fn new(min: DVec3, max: DVec3) -> Self {
        Aabb { min, max }
    }

    /// The smallest box containing the points.
    pub fn from_points(pts: &[DVec3]) -> Self {
        pts.iter().fold(Aabb::EMPTY, |b, &p| b.grow(p))
    }

    /// The smallest box containing this box and the point `p`.
    #[inline]
    pub fn grow(&self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both boxes.
    #[inline]
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Where `p` lies beyond the box's faces, a bit per face (below and
    /// above on x, y, z). Points all beyond one face share its bit, so the
    /// box around some points misses this box exactly when the AND of
    /// their codes is nonzero: a scan over many triangles then computes a
    /// code per vertex once and reads a byte per corner.
    #[inline]
    pub fn outcode(&self, p: DVec3) -> u8 {
        let (lo, hi) = (self.min, self.max);
        u8::from(p.x < lo.x)
            | u8::from(p.x > hi.x) << 1
            | u8::from(p.y < lo.y) << 2
            | u8::from(p.y > hi.y) << 3
            | u8::from(p.z < lo.z) << 4
            | u8::from(p.z > hi.z) << 5
    }

    /// Closed-box overlap (touching counts).
    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && o.min.x <= self.max.x
            && self.min.y <= o.max.y
            && o.min.y <= self.max.y
            && self.min.z <= o.max.z
            && o.min.z <= self.max.z
    }

    /// The centre of the box, halfway between its corners.
    #[inline]
    pub fn centroid(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// Whether every coordinate of both corners is finite (not so for
    /// [`Aabb::EMPTY`]).
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }
}

const LEAF: u32 = 1 << 31;

/// A piece of the self-overlap descent: the pairs within one subtree, or
/// across two.
#[derive(Clone, Copy)]
enum Task {
    Within(u32),
    Across(u32, u32),
}

#[derive(Clone, Copy, Debug)]
struct Node {
    bb: Aabb,
    /// Leaf: first slot in `prims`. Internal: left child.
    a: u32,
    /// Leaf: `LEAF | count`. Internal: right child.
    b: u32,
}

impl Node {
    #[inline]
    fn is_leaf(&self) -> bool {
        self.b & LEAF != 0
    }
    #[inline]
    fn range(&self) -> std::ops::Range<usize> {
        let first = self.a as usize;
        first..first + (self.b & !LEAF) as usize
    }
}

/// The hierarchy. Primitive ids are the indices of the boxes given to
/// [`Bvh::build`].
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Primitive ids in leaf order.
    prims: Vec<u32>,
    /// Their boxes, in the same order.
    prim_boxes: Vec<Aabb>,
    /// The upward links [`Bvh::refit_some`] walks, built on its first
    /// call: most hierarchies are built, queried and dropped, and filling
    /// these three arrays was a tenth of a build.
    refit_index: Option<RefitIndex>,
}

/// Links from primitives up to the root.
#[derive(Clone, Debug)]
struct RefitIndex {
    /// Slot of each primitive id in `prims`.
    slot_of: Vec<u32>,
    /// Leaf node of each slot's leaf, by slot.
    leaf_of_slot: Vec<u32>,
    /// Parent of each node (`u32::MAX` for the root).
    parent: Vec<u32>,
}

/// A primitive during the build: its box's centroid relative to the
/// first box's, rounded to `f32` (the centroid only chooses the split; the
/// boxes stay exact; relative to a point of the scene, its precision
/// follows the scene's extent, not its offset from the origin), and its
/// id. Sixteen bytes instead of thirty-two: the median selections that
/// dominate the build move half the memory.
#[derive(Clone, Copy)]
struct Item {
    c: [f32; 3],
    id: u32,
}

/// Node count of a subtree over `n` primitives (median split).
fn subtree_nodes(n: usize, memo: &mut HashMap<usize, usize>) -> usize {
    if n <= LEAF_SIZE {
        return 1;
    }
    if let Some(&v) = memo.get(&n) {
        return v;
    }
    let v = 1 + subtree_nodes(n / 2, memo) + subtree_nodes(n - n / 2, memo);
    memo.insert(n, v);
    v
}

fn build_rec(
    items: &mut [Item],
    nodes: &mut [Node],
    base: u32,
    first: u32,
    boxes: &[Aabb],
    sizes: &HashMap<usize, usize>,
) {
    let n = items.len();
    if n <= LEAF_SIZE {
        let bb = items
            .iter()
            .fold(Aabb::EMPTY, |b, it| b.union(&boxes[it.id as usize]));
        nodes[0] = Node {
            bb,
            a: first,
            b: LEAF | n as u32,
        };
        return;
    }
    // Axis of largest centroid extent, then the median by quickselect.
    let cb = items.iter().fold(Aabb::EMPTY, |b, it| {
        b.grow(DVec3::new(
            f64::from(it.c[0]),
            f64::from(it.c[1]),
            f64::from(it.c[2]),
        ))
    });
    let ext = cb.max - cb.min;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = n / 2;
    items.select_nth_unstable_by(mid, |p, q| p.c[axis].total_cmp(&q.c[axis]));
    let (li, ri) = items.split_at_mut(mid);
    let lsize = if mid <= LEAF_SIZE { 1 } else { sizes[&mid] };
    let (head, rest) = nodes.split_at_mut(1);
    let (ln, rn) = rest.split_at_mut(lsize);
    let left = base + 1;
    let right = base + 1 + lsize as u32;
    if n > PARALLEL_THRESHOLD {
        rayon::join(
            || build_rec(li, ln, left, first, boxes, sizes),
            || build_rec(ri, rn, right, first + mid as u32, boxes, sizes),
        );
    } else {
        build_rec(li, ln, left, first, boxes, sizes);
        build_rec(ri, rn, right, first + mid as u32, boxes, sizes);
    }
    head[0] = Node {
        bb: ln[0].bb.union(&rn[0].bb),
        a: left,
        b: right,
    };
}

impl Bvh {
    /// Builds the hierarchy over `boxes` (primitive `i` has box `boxes[i]`).
    /// Errors on non-finite boxes or more than 2³¹ boxes.
    pub fn build(boxes: &[Aabb]) -> Result<Bvh, GeomError> {
        let n = boxes.len();
        if n >= (1usize << 31) {
            return Err(GeomError::TooMany(n));
        }
        if let Some(index) = boxes.iter().position(|b| !b.is_finite()) {
            return Err(NonFinite::at("box", index).into());
        }
        if n == 0 {
            return Ok(Bvh {
                nodes: Vec::new(),
                prims: Vec::new(),
                prim_boxes: Vec::new(),
                refit_index: None,
            });
        }
        let origin = boxes[0].centroid();
        let mut items: Vec<Item> = boxes
            .par_iter()
            .enumerate()
            .map(|(i, b)| {
                let c = b.centroid() - origin;
                Item {
                    c: [c.x as f32, c.y as f32, c.z as f32],
                    id: i as u32,
                }
            })
            .collect();
        let mut memo = HashMap::new();
        let total = subtree_nodes(n, &mut memo);
        let dummy = Node {
            bb: Aabb::EMPTY,
            a: 0,
            b: 0,
        };
        let mut nodes = vec![dummy; total];
        build_rec(&mut items, &mut nodes, 0, 0, boxes, &memo);
        let prims: Vec<u32> = items.iter().map(|it| it.id).collect();
        let prim_boxes: Vec<Aabb> = prims.par_iter().map(|&i| boxes[i as usize]).collect();
        Ok(Bvh {
            nodes,
            prims,
            prim_boxes,
            refit_index: None,
        })
    }

    fn make_refit_index(&self) -> RefitIndex {
        let mut slot_of = vec![0u32; self.prims.len()];
        for (s, &p) in self.prims.iter().enumerate() {
            slot_of[p as usize] = s as u32;
        }
        let mut parent = vec![u32::MAX; self.nodes.len()];
        let mut leaf_of_slot = vec![0u32; self.prims.len()];
        for (i, nd) in self.nodes.iter().enumerate() {
            if nd.is_leaf() {
                for s in nd.range() {
                    leaf_of_slot[s] = i as u32;
                }
            } else {
                parent[nd.a as usize] = i as u32;
                parent[nd.b as usize] = i as u32;
            }
        }
        RefitIndex {
            slot_of,
            leaf_of_slot,
            parent,
        }
    }

    /// Number of primitives.
    pub fn len(&self) -> usize {
        self.prims.len()
    }

    /// Whether the tree holds no primitives.
    pub fn is_empty(&self) -> bool {
        self.prims.is_empty()
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The box of the whole tree (`EMPTY` for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bb)
    }

    /// Calls `f(id)` for every primitive whose box overlaps `bb`.
    pub fn for_each_overlap(&self, bb: &Aabb, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() || !self.nodes[0].bb.overlaps(bb) {
            return;
        }
        // The tree is balanced (depth ≤ 31 for < 2³¹ primitives), so a fixed
        // stack of 64 suffices; only nodes whose box overlaps are pushed.
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let nd = &self.nodes[stack[top] as usize];
            if nd.is_leaf() {
                for s in nd.range() {
                    if self.prim_boxes[s].overlaps(bb) {
                        f(self.prims[s]);
                    }
                }
            } else {
                if self.nodes[nd.b as usize].bb.overlaps(bb) {
                    stack[top] = nd.b;
                    top += 1;
                }
                if self.nodes[nd.a as usize].bb.overlaps(bb) {
                    stack[top] = nd.a;
                    top += 1;
                }
            }
        }
    }

    /// Ids of the primitives whose boxes overlap `bb`, in tree order.
    pub fn query(&self, bb: &Aabb) -> Vec<u32> {
        let mut out = Vec::new();
        self.for_each_overlap(bb, |i| out.push(i));
        out
    }

    /// Streams `queries` over the tree: all `(query index, primitive id)`
    /// with overlapping boxes, ordered by query index, then tree order.
    /// Parallel and deterministic.
    pub fn overlap_pairs(&self, queries: &[Aabb]) -> Vec<(u32, u32)> {
        const CHUNK: usize = 1024;
        let parts: Vec<Vec<(u32, u32)>> = queries
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut out = Vec::new();
                for (k, q) in chunk.iter().enumerate() {
                    let qi = (c * CHUNK + k) as u32;
                    self.for_each_overlap(q, |p| out.push((qi, p)));
                }
                out
            })
            .collect();
        concat(parts)
    }

    /// All unordered pairs of distinct primitives with overlapping boxes,
    /// each once as `(smaller id, larger id)`. Parallel and deterministic
    /// (the order is that of the simultaneous descent, independent of
    /// thread scheduling).
    pub fn self_overlaps(&self) -> Vec<(u32, u32)> {
        self.self_overlaps_filter_map(|a, b| Some((a, b))).0
    }

    /// [`Bvh::self_overlaps`] with each pair passed through `f` as it is
    /// found, keeping the `Some` results in the same deterministic order;
    /// also returns how many pairs were found. The pairs are never stored:
    /// on a mesh most overlapping boxes belong to neighbouring triangles
    /// (4.7M pairs against 2.5k intersecting ones for two 262k-triangle
    /// spheres), and storing them cost more than testing them.
    pub fn self_overlaps_filter_map<T: Send>(
        &self,
        f: impl Fn(u32, u32) -> Option<T> + Sync,
    ) -> (Vec<T>, usize) {
        self.self_overlaps_pruned(KeepAll, f)
    }

    /// An estimate of how many pairs [`Bvh::self_overlaps`] would find
    /// that satisfy `f`, from at most `samples` primitives spread over the
    /// tree: each one's overlapping primitives are counted, and the sum is
    /// scaled to the whole tree (each pair is seen from both ends).
    pub fn estimate_self_overlaps(&self, samples: usize, f: impl Fn(u32, u32) -> bool) -> f64 {
        let n = self.prims.len();
        if n == 0 || samples == 0 {
            return 0.0;
        }
        let step = n.div_ceil(samples).max(1);
        let mut seen = 0usize;
        let mut found = 0usize;
        for s in (0..n).step_by(step) {
            let p = self.prims[s];
            seen += 1;
            self.for_each_overlap(&self.prim_boxes[s], |q| {
                if q != p && f(p, q) {
                    found += 1;
                }
            });
        }
        found as f64 * n as f64 / seen as f64 / 2.0
    }

    /// Per node, the group every primitive below it belongs to, or
    /// [`NO_GROUP`] when they are not all of one group; `group_of` gives
    /// each primitive's group (by primitive id). Nodes come after their
    /// parents, so one backward pass fills them.
    pub fn node_groups(&self, group_of: &[u32]) -> NodeGroups {
        let slot: Vec<u32> = self.prims.iter().map(|&p| group_of[p as usize]).collect();
        let mut node = vec![NO_GROUP; self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let nd = self.nodes[i];
            node[i] = if nd.is_leaf() {
                let g = slot[nd.range()].first().copied().unwrap_or(NO_GROUP);
                if slot[nd.range()].iter().all(|&h| h == g) {
                    g
                } else {
                    NO_GROUP
                }
            } else if node[nd.a as usize] == node[nd.b as usize] {
                node[nd.a as usize]
            } else {
                NO_GROUP
            };
        }
        NodeGroups { node, slot }
    }

    /// [`Bvh::self_overlaps_filter_map`] without the pairs of primitives
    /// of one group (other than [`NO_GROUP`]): `groups` from
    /// [`Bvh::node_groups`] of this tree. A subtree of one group is not
    /// descended into at all, nor a pair of subtrees of the same group,
    /// so pairs known beforehand to need nothing (two triangles of one
    /// certified flat patch) cost neither a test nor a visit. The count
    /// returned is of the pairs passed to `f`.
    pub fn self_overlaps_apart_filter_map<T: Send>(
        &self,
        groups: &NodeGroups,
        f: impl Fn(u32, u32) -> Option<T> + Sync,
    ) -> (Vec<T>, usize) {
        self.self_overlaps_pruned(ApartGroups(groups), f)
    }

    fn self_overlaps_pruned<T: Send>(
        &self,
        prune: impl Prune,
        f: impl Fn(u32, u32) -> Option<T> + Sync,
    ) -> (Vec<T>, usize) {
        if self.nodes.is_empty() {
            return (Vec::new(), 0);
        }
        // Symbolic phase: cut the descent into tasks of at most
        // PARALLEL_THRESHOLD primitives, in descent order; numeric phase:
        // run them in parallel, each into its own output.
        let mut tasks = Vec::new();
        self.split_within(0, prune, &mut tasks);
        run_tasks(self, self, prune, &tasks, |a, b| {
            let (a, b) = pair(a, b);
            f(a, b)
        })
    }

    fn subtree_size(&self, i: u32) -> usize {
        let nd = &self.nodes[i as usize];
        if nd.is_leaf() {
            nd.range().len()
        } else {
            // Slots are contiguous per subtree: from the leftmost leaf's first
            // slot to the rightmost leaf's end.
            let mut l = i;
            while !self.nodes[l as usize].is_leaf() {
                l = self.nodes[l as usize].a;
            }
            let mut r = i;
            while !self.nodes[r as usize].is_leaf() {
                r = self.nodes[r as usize].b;
            }
            self.nodes[r as usize].range().end - self.nodes[l as usize].range().start
        }
    }

    /// The tasks of the pairs within subtree `i`: its two children's, then
    /// those across them.
    fn split_within(&self, i: u32, prune: impl Prune, tasks: &mut Vec<Task>) {
        let nd = self.nodes[i as usize];
        if prune.within(i) {
            return;
        }
        if nd.is_leaf() || self.subtree_size(i) <= PARALLEL_THRESHOLD {
            tasks.push(Task::Within(i));
            return;
        }
        self.split_within(nd.a, prune, tasks);
        self.split_within(nd.b, prune, tasks);
        split_across(self, nd.a, self, nd.b, prune, tasks);
    }

    fn within(&self, i: u32, prune: impl Prune, sink: &mut impl FnMut(u32, u32)) {
        let nd = self.nodes[i as usize];
        if prune.within(i) {
            return;
        }
        if nd.is_leaf() {
            let r = nd.range();
            for s in r.clone() {
                for t in s + 1..r.end {
                    if self.prim_boxes[s].overlaps(&self.prim_boxes[t]) && !prune.slots(s, t) {
                        sink(self.prims[s], self.prims[t]);
                    }
                }
            }
            return;
        }
        self.within(nd.a, prune, sink);
        self.within(nd.b, prune, sink);
        across(self, nd.a, self, nd.b, prune, sink);
    }

    /// [`Bvh::self_overlaps_filter_map`] across two trees: every pair
    /// `(primitive of self, primitive of other)` whose boxes overlap,
    /// passed through `f` as it is found, the `Some` results kept in the
    /// descent's deterministic order; also how many pairs were found. For
    /// two meshes whose own self-overlaps are of no interest (the union of
    /// two solids) this visits only the boxes near where they meet.
    pub fn overlaps_with_filter_map<T: Send>(
        &self,
        other: &Bvh,
        f: impl Fn(u32, u32) -> Option<T> + Sync,
    ) -> (Vec<T>, usize) {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return (Vec::new(), 0);
        }
        let mut tasks = Vec::new();
        split_across(self, 0, other, 0, KeepAll, &mut tasks);
        run_tasks(self, other, KeepAll, &tasks, f)
    }

    /// Recomputes all boxes from new primitive boxes (same count as built),
    /// keeping the tree's topology.
    pub fn refit(&mut self, boxes: &[Aabb]) -> Result<(), GeomError> {
        self.check_boxes(boxes)?;
        let prims = &self.prims;
        self.prim_boxes
            .par_iter_mut()
            .zip(prims.par_iter())
            .for_each(|(b, &p)| *b = boxes[p as usize]);
        for i in (0..self.nodes.len()).rev() {
            self.recompute(i);
        }
        Ok(())
    }

    /// Recomputes the boxes above the primitives in `changed` only
    /// (O(k log n) for k changed primitives); `boxes` holds every
    /// primitive's current box.
    pub fn refit_some(&mut self, boxes: &[Aabb], changed: &[u32]) -> Result<(), GeomError> {
        self.check_boxes(boxes)?;
        let index = match self.refit_index.take() {
            Some(index) => index,
            None => self.make_refit_index(),
        };
        let result = self.refit_some_with(&index, boxes, changed);
        self.refit_index = Some(index);
        result
    }

    fn refit_some_with(
        &mut self,
        index: &RefitIndex,
        boxes: &[Aabb],
        changed: &[u32],
    ) -> Result<(), GeomError> {
        let mut dirty: Vec<u32> = Vec::with_capacity(changed.len() * 8);
        for &p in changed {
            let Some(&slot) = index.slot_of.get(p as usize) else {
                return Err(GeomError::LengthMismatch {
                    what: "changed primitive id",
                    got: p as usize,
                    expected: self.prims.len(),
                });
            };
            self.prim_boxes[slot as usize] = boxes[p as usize];
            let mut n = index.leaf_of_slot[slot as usize];
            while n != u32::MAX {
                dirty.push(n);
                n = index.parent[n as usize];
            }
        }
        dirty.sort_unstable();
        dirty.dedup();
        // Children have larger indices than their parents (pre-order).
        for &n in dirty.iter().rev() {
            self.recompute(n as usize);
        }
        Ok(())
    }

    fn check_boxes(&self, boxes: &[Aabb]) -> Result<(), GeomError> {
        if boxes.len() != self.prims.len() {
            return Err(GeomError::LengthMismatch {
                what: "boxes",
                got: boxes.len(),
                expected: self.prims.len(),
            });
        }
        if let Some(index) = boxes.iter().position(|b| !b.is_finite()) {
            return Err(NonFinite::at("box", index).into());
        }
        Ok(())
    }

    fn recompute(&mut self, i: usize) {
        let nd = self.nodes[i];
        let bb = if nd.is_leaf() {
            self.prim_boxes[nd.range()]
                .iter()
                .fold(Aabb::EMPTY, |b, x| b.union(x))
        } else {
            self.nodes[nd.a as usize]
                .bb
                .union(&self.nodes[nd.b as usize].bb)
        };
        self.nodes[i].bb = bb;
    }

    /// Checks the structural invariants (every box contains its children's
    /// and primitives' boxes; every primitive in exactly one leaf). For
    /// tests.
    pub fn validate(&self) -> bool {
        let index = self.make_refit_index();
        let mut seen = vec![false; self.prims.len()];
        for (i, nd) in self.nodes.iter().enumerate() {
            let inside = |b: &Aabb| nd.bb.min.cmple(b.min).all() && b.max.cmple(nd.bb.max).all();
            if nd.is_leaf() {
                for s in nd.range() {
                    if seen[s] || !inside(&self.prim_boxes[s]) {
                        return false;
                    }
                    seen[s] = true;
                    if index.leaf_of_slot[s] as usize != i {
                        return false;
                    }
                }
            } else if !inside(&self.nodes[nd.a as usize].bb)
                || !inside(&self.nodes[nd.b as usize].bb)
            {
                return false;
            }
        }
        seen.iter().all(|&s| s)
    }
}

#[inline]
/// Runs the descent's tasks in parallel, each into its own output, and
/// joins the outputs in task order (the numeric phase of the two-phase
/// descent: the tasks themselves are the symbolic phase).
fn run_tasks<T: Send>(
    x: &Bvh,
    y: &Bvh,
    prune: impl Prune,
    tasks: &[Task],
    f: impl Fn(u32, u32) -> Option<T> + Sync,
) -> (Vec<T>, usize) {
    let parts: Vec<(Vec<T>, usize)> = tasks
        .par_iter()
        .map(|task| {
            let mut out = Vec::new();
            let mut found = 0usize;
            let mut sink = |a: u32, b: u32| {
                found += 1;
                if let Some(v) = f(a, b) {
                    out.push(v);
                }
            };
            match *task {
                Task::Within(i) => x.within(i, prune, &mut sink),
                Task::Across(i, j) => across(x, i, y, j, prune, &mut sink),
            }
            (out, found)
        })
        .collect();
    let found = parts.iter().map(|p| p.1).sum();
    (concat(parts.into_iter().map(|p| p.0).collect()), found)
}

/// The tasks of the pairs across subtree `i` of `x` and subtree `j` of
/// `y` (`x` and `y` may be one tree).
fn split_across(x: &Bvh, i: u32, y: &Bvh, j: u32, prune: impl Prune, tasks: &mut Vec<Task>) {
    let (ni, nj) = (x.nodes[i as usize], y.nodes[j as usize]);
    if !ni.bb.overlaps(&nj.bb) || prune.across(i, j) {
        return;
    }
    let (si, sj) = (x.subtree_size(i), y.subtree_size(j));
    if si + sj <= PARALLEL_THRESHOLD || (ni.is_leaf() && nj.is_leaf()) {
        tasks.push(Task::Across(i, j));
    } else if !ni.is_leaf() && (nj.is_leaf() || si >= sj) {
        split_across(x, ni.a, y, j, prune, tasks);
        split_across(x, ni.b, y, j, prune, tasks);
    } else {
        split_across(x, i, y, nj.a, prune, tasks);
        split_across(x, i, y, nj.b, prune, tasks);
    }
}

/// Every pair (primitive under node `i` of `x`, primitive under node `j`
/// of `y`) whose boxes overlap, in descent order.
fn across(x: &Bvh, i: u32, y: &Bvh, j: u32, prune: impl Prune, sink: &mut impl FnMut(u32, u32)) {
    let (ni, nj) = (x.nodes[i as usize], y.nodes[j as usize]);
    if !ni.bb.overlaps(&nj.bb) || prune.across(i, j) {
        return;
    }
    match (ni.is_leaf(), nj.is_leaf()) {
        (true, true) => {
            for s in ni.range() {
                let bs = &x.prim_boxes[s];
                if !bs.overlaps(&nj.bb) {
                    continue;
                }
                for t in nj.range() {
                    if bs.overlaps(&y.prim_boxes[t]) && !prune.slots(s, t) {
                        sink(x.prims[s], y.prims[t]);
                    }
                }
            }
        }
        (false, true) => {
            across(x, ni.a, y, j, prune, sink);
            across(x, ni.b, y, j, prune, sink);
        }
        (true, false) => {
            across(x, i, y, nj.a, prune, sink);
            across(x, i, y, nj.b, prune, sink);
        }
        (false, false) => {
            // Descend the larger box (keeps the recursion balanced).
            if volume(&ni.bb) >= volume(&nj.bb) {
                across(x, ni.a, y, j, prune, sink);
                across(x, ni.b, y, j, prune, sink);
            } else {
                across(x, i, y, nj.a, prune, sink);
                across(x, i, y, nj.b, prune, sink);
            }
        }
    }
}

/// No group: [`Bvh::node_groups`] of a node whose primitives are not all
/// of one group, and the group of a primitive in none.
pub const NO_GROUP: u32 = u32::MAX;

/// Which group each node's primitives all belong to, and each slot's
/// primitive ([`Bvh::node_groups`]).
#[derive(Clone, Debug)]
pub struct NodeGroups {
    node: Vec<u32>,
    slot: Vec<u32>,
}

/// What a descent of a tree against itself may skip: a generic parameter,
/// so that the descent that skips nothing compiles to the one it was.
trait Prune: Copy + Sync {
    /// Every pair within node `i`.
    fn within(self, i: u32) -> bool;
    /// Every pair across nodes `i` and `j`.
    fn across(self, i: u32, j: u32) -> bool;
    /// The pair of the primitives in slots `s` and `t`.
    fn slots(self, s: usize, t: usize) -> bool;
}

/// Skips nothing.
#[derive(Clone, Copy)]
struct KeepAll;

impl Prune for KeepAll {
    #[inline(always)]
    fn within(self, _: u32) -> bool {
        false
    }
    #[inline(always)]
    fn across(self, _: u32, _: u32) -> bool {
        false
    }
    #[inline(always)]
    fn slots(self, _: usize, _: usize) -> bool {
        false
    }
}

/// Skips the pairs of one group.
#[derive(Clone, Copy)]
struct ApartGroups<'a>(&'a NodeGroups);

impl Prune for ApartGroups<'_> {
    #[inline]
    fn within(self, i: u32) -> bool {
        self.0.node[i as usize] != NO_GROUP
    }
    #[inline]
    fn across(self, i: u32, j: u32) -> bool {
        let g = self.0.node[i as usize];
        g != NO_GROUP && g == self.0.node[j as usize]
    }
    #[inline]
    fn slots(self, s: usize, t: usize) -> bool {
        let g = self.0.slot[s];
        g != NO_GROUP && g == self.0.slot[t]
    }
}

fn pair(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

#[inline]
fn volume(b: &Aabb) -> f64 {
    let e = b.max - b.min;
    e.x * e.y * e.z + e.x + e.y + e.z
}

fn concat<T>(parts: Vec<Vec<T>>) -> Vec<T> {
    let n = parts.iter().map(Vec::len).sum();
    let mut out = Vec::with_capacity(n);
    for p in parts {
        out.extend(p);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::Rng;

    fn random_boxes(rng: &mut Rng, n: usize, size: f64) -> Vec<Aabb> {
        (0..n)
            .map(|_| {
                let c = DVec3::new(rng.unit(), rng.unit(), rng.unit());
                let e = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * size;
                Aabb::new(c - e, c + e)
            })
            .collect()
    }

    /// Checks `bvh.query(q)` against every box of `boxes` tried one by
    /// one (the order of the answer aside).
    fn assert_query_is_brute_force(bvh: &Bvh, boxes: &[Aabb], q: &Aabb) {
        let mut got = bvh.query(q);
        got.sort_unstable();
        let want: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| boxes[i as usize].overlaps(q))
            .collect();
        assert_eq!(got, want);
    }

    fn brute_pairs(b: &[Aabb]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..b.len() {
            for j in i + 1..b.len() {
                if b[i].overlaps(&b[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    #[test]
    fn queries_match_brute_force() {
        let mut rng = Rng::new(1);
        for &n in &[0usize, 1, 3, 4, 5, 17, 100, 1000, 20_000] {
            let boxes = random_boxes(&mut rng, n, 0.01);
            let bvh = Bvh::build(&boxes).expect("finite");
            assert!(bvh.validate());
            assert_eq!(bvh.len(), n);
            let queries = random_boxes(&mut rng, 300, 0.05);
            for q in &queries {
                assert_query_is_brute_force(&bvh, &boxes, q);
            }
            let pairs = bvh.overlap_pairs(&queries);
            let mut want = Vec::new();
            for (qi, q) in queries.iter().enumerate() {
                for p in bvh.query(q) {
                    want.push((qi as u32, p));
                }
            }
            assert_eq!(pairs, want);
            if n <= 1000 {
                let mut got = bvh.self_overlaps();
                got.sort_unstable();
                assert_eq!(got, brute_pairs(&boxes));
            }
        }
    }

    #[test]
    fn overlaps_with_another_tree_match_brute_force() {
        let mut rng = Rng::new(7);
        // Sizes that make leaves, small trees and trees split into many
        // parallel tasks (above PARALLEL_THRESHOLD together).
        for &(n, m) in &[(0usize, 5usize), (5, 0), (1, 1), (17, 300), (6000, 9000)] {
            let xs = random_boxes(&mut rng, n, 0.01);
            let ys = random_boxes(&mut rng, m, 0.01);
            let (x, y) = (
                Bvh::build(&xs).expect("finite"),
                Bvh::build(&ys).expect("finite"),
            );
            let (mut got, found) = x.overlaps_with_filter_map(&y, |a, b| Some((a, b)));
            assert_eq!(found, got.len());
            // Deterministic: the same order on a second run.
            assert_eq!(got, x.overlaps_with_filter_map(&y, |a, b| Some((a, b))).0);
            got.sort_unstable();
            let mut want = Vec::new();
            for (i, a) in xs.iter().enumerate() {
                for (j, b) in ys.iter().enumerate() {
                    if a.overlaps(b) {
                        want.push((i as u32, j as u32));
                    }
                }
            }
            assert_eq!(got, want, "{n} × {m} boxes");
            // The filter keeps only what it maps.
            let (odd, all) = x.overlaps_with_filter_map(&y, |a, b| ((a + b) % 2 == 1).then_some(a));
            assert_eq!(all, want.len());
            assert_eq!(
                odd.len(),
                want.iter().filter(|(a, b)| (a + b) % 2 == 1).count()
            );
        }
    }

    #[test]
    fn self_overlaps_large_is_deterministic_and_complete() {
        let mut rng = Rng::new(2);
        let boxes = random_boxes(&mut rng, 30_000, 0.004);
        let bvh = Bvh::build(&boxes).expect("finite");
        let a = bvh.self_overlaps();
        let b = Bvh::build(&boxes).expect("finite").self_overlaps();
        assert_eq!(a, b);
        // Completeness against a grid-free sweep on x.
        let mut idx: Vec<usize> = (0..boxes.len()).collect();
        idx.sort_by(|&i, &j| boxes[i].min.x.total_cmp(&boxes[j].min.x));
        let mut want = Vec::new();
        for (k, &i) in idx.iter().enumerate() {
            for &j in &idx[k + 1..] {
                if boxes[j].min.x > boxes[i].max.x {
                    break;
                }
                if boxes[i].overlaps(&boxes[j]) {
                    want.push(pair(i as u32, j as u32));
                }
            }
        }
        want.sort_unstable();
        let mut got = a;
        got.sort_unstable();
        assert_eq!(got, want);
    }

    /// The descent apart from groups finds exactly the overlapping pairs
    /// whose primitives are not of one group (other than [`NO_GROUP`]),
    /// in the same order as the full descent, and counts just those. The
    /// groups are spatial (boxes of one slab of x, as a flat patch's
    /// triangles lie together), so whole subtrees are of one group, and
    /// the tree is large enough to be split into parallel tasks.
    #[test]
    fn self_overlaps_apart_from_groups_skip_exactly_the_pairs_of_one_group() {
        let mut rng = Rng::new(36);
        let boxes = random_boxes(&mut rng, 30_000, 0.02);
        let group_of: Vec<u32> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| match (b.min.x * 20.0) as u32 {
                g if g % 5 == 4 || i % 97 == 0 => NO_GROUP,
                g => g / 2,
            })
            .collect();
        let bvh = Bvh::build(&boxes).expect("finite");
        let groups = bvh.node_groups(&group_of);
        let apart = |a: u32, b: u32| {
            let g = group_of[a as usize];
            g == NO_GROUP || g != group_of[b as usize]
        };
        let want: Vec<(u32, u32)> = bvh
            .self_overlaps()
            .into_iter()
            .filter(|&(a, b)| apart(a, b))
            .collect();
        let (got, count) = bvh.self_overlaps_apart_filter_map(&groups, |a, b| Some((a, b)));
        assert_eq!(got, want);
        assert_eq!(count, want.len());
        let skipped = bvh.self_overlaps().len() - want.len();
        assert!(skipped > want.len() / 4, "pairs of one group: {skipped}");
        // A group of its own for every primitive skips nothing.
        let own: Vec<u32> = (0..boxes.len() as u32).collect();
        let all = bvh.self_overlaps_apart_filter_map(&bvh.node_groups(&own), |a, b| Some((a, b)));
        assert_eq!(all.0, bvh.self_overlaps());
    }

    /// Sampled from every primitive, the estimate is the exact count of
    /// the pairs satisfying the predicate; from a sample, it is near it.
    #[test]
    fn estimated_self_overlaps_count_the_pairs_the_descent_finds() {
        let mut rng = Rng::new(7);
        let boxes = random_boxes(&mut rng, 5_000, 0.03);
        let bvh = Bvh::build(&boxes).expect("finite");
        let odd = |a: u32, b: u32| (a + b) % 2 == 1;
        let exact = bvh
            .self_overlaps()
            .iter()
            .filter(|&&(a, b)| odd(a, b))
            .count();
        assert!(exact > 1000, "{exact}");
        assert_eq!(bvh.estimate_self_overlaps(5_000, odd), exact as f64);
        let sampled = bvh.estimate_self_overlaps(500, odd);
        assert!(
            (sampled / exact as f64 - 1.0).abs() < 0.2,
            "{sampled} against {exact}"
        );
        assert_eq!(
            Bvh::build(&[])
                .expect("empty")
                .estimate_self_overlaps(10, odd),
            0.0
        );
    }

    #[test]
    fn touching_boxes_overlap_and_degenerate_inputs_work() {
        // Identical boxes, flat boxes, touching boxes.
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE);
        let mut boxes = vec![b; 10];
        boxes.push(Aabb::new(
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 1.0),
        ));
        boxes.push(Aabb::new(DVec3::splat(3.0), DVec3::splat(3.0)));
        let bvh = Bvh::build(&boxes).expect("finite");
        let mut got = bvh.self_overlaps();
        got.sort_unstable();
        assert_eq!(got, brute_pairs(&boxes));
        assert_eq!(got.len(), 45 + 10);
        let bad = vec![Aabb::new(DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0))];
        assert_eq!(
            Bvh::build(&bad).err(),
            Some(GeomError::NonFinite(NonFinite::at("box", 0)))
        );
    }

    #[test]
    fn refit_all_and_some() {
        let mut rng = Rng::new(3);
        let mut boxes = random_boxes(&mut rng, 5000, 0.01);
        let mut bvh = Bvh::build(&boxes).expect("finite");
        // Move 50 primitives.
        let changed: Vec<u32> = (0..50).map(|_| rng.below(5000) as u32).collect();
        for &c in &changed {
            let d = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 0.3;
            let b = boxes[c as usize];
            boxes[c as usize] = Aabb::new(b.min + d, b.max + d);
        }
        bvh.refit_some(&boxes, &changed).expect("ok");
        assert!(bvh.validate());
        let q = Aabb::new(DVec3::splat(0.2), DVec3::splat(0.6));
        assert_query_is_brute_force(&bvh, &boxes, &q);
        // Full refit after moving everything.
        for b in boxes.iter_mut() {
            *b = Aabb::new(b.min * 2.0, b.max * 2.0);
        }
        bvh.refit(&boxes).expect("ok");
        assert!(bvh.validate());
        assert_query_is_brute_force(&bvh, &boxes, &q);
        assert!(bvh.refit(&boxes[..10]).is_err());
        assert!(bvh.refit_some(&boxes, &[9999]).is_err());
    }
}
