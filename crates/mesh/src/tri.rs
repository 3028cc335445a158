//! Triangle meshes as the topology engine, the Booleans and sculpting take
//! them ([`TriMesh`]), with their checks and their edge tables.
//!
//! The engine works on *any* list of triangles (§2.1 of the paper): edges of
//! any degree, open, unoriented, disconnected, unwelded soups, duplicate and
//! zero-area triangles. Edges are identified by vertex *indices*: two
//! triangles of a soup that only touch at equal positions share no edge.

use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

use crate::NonFinite;
use crate::rows::Rows;

/// A triangle mesh: positions and triangles as index triples.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions; triangles refer to them by index.
    pub positions: Vec<DVec3>,
    /// Each triangle's three corners as indices into `positions`, in the order
    /// that sets its orientation.
    pub triangles: Vec<[u32; 3]>,
}

/// Why a mesh or a motion cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A position has a NaN or infinite coordinate: the first such vertex
    /// of the array its `input` names (`"mesh"` for a mesh's own positions;
    /// otherwise as given to [`check_positions`]).
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// A triangle refers to a vertex index at or past the number of positions.
    #[error("triangle {triangle} refers to vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Index of the first triangle found with such a corner.
        triangle: usize,
        /// The out-of-range vertex index it holds.
        index: u32,
        /// Number of positions the mesh has.
        count: usize,
    },
    /// A motion's end positions are not one per vertex of the mesh.
    #[error("the end positions give {got} vertices, the mesh has {expected}")]
    VertexCountMismatch {
        /// Number of vertices the mesh has.
        expected: usize,
        /// Number of end positions given.
        got: usize,
    },
    /// The mesh has this many positions, too many for 32-bit indices (at
    /// least `u32::MAX`).
    #[error("{0} vertices exceed 32-bit indices")]
    TooLarge(usize),
}

impl TriMesh {
    /// The mesh of plain arrays: positions as `[x, y, z]`, triangles as
    /// index triples, taken as they are (nothing is checked).
    pub fn from_arrays(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> TriMesh {
        TriMesh {
            positions: positions.iter().map(|&p| DVec3::from_array(p)).collect(),
            triangles: triangles.to_vec(),
        }
    }

    /// Appends `other`'s vertices and triangles (its indices shifted past
    /// this mesh's vertices): the two as one mesh, apart as they were.
    pub fn append(&mut self, other: &TriMesh) {
        let n = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|v| v + n)));
    }

    /// The mesh moved by `offset`.
    pub fn translated(&self, offset: DVec3) -> TriMesh {
        self.transformed(|p| p + offset)
    }

    /// The mesh with every position mapped by `f` (an affine map, a
    /// projection, anything), the triangles as they are.
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3) -> TriMesh {
        TriMesh {
            positions: self.positions.iter().map(|&p| f(p)).collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Every undirected edge used by exactly two triangles, in opposite
    /// directions, and no triangle with a repeated vertex: a closed,
    /// consistently oriented 2-manifold along its edges.
    ///
    /// Decided without an edge table ([`Edges`] answers the same, at
    /// three times the cost): each side `u → v` is filed under its smaller
    /// end as its larger end with a bit for its direction, and each file,
    /// sorted, must be pairs `(x, along), (x, against)` with `x` strictly
    /// increasing: every edge once each way and no more.
    pub fn is_closed_manifold(&self) -> bool {
        if self.triangles.par_iter().any(repeats_a_corner) {
            return false;
        }
        let vertices = vertex_bound(&self.triangles);
        if vertices >= 1 << 31 {
            return Edges::new(self).closed_oriented(&self.triangles);
        }
        let mut rows = Rows::file(vertices, || {
            self.triangles.iter().flat_map(|tri| {
                (0..3).map(move |k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    (a.min(b), (a.max(b) << 1) | u32::from(a > b))
                })
            })
        });
        rows.all_rows_mut(|file| {
            file.sort_unstable();
            file.len() % 2 == 0
                && file.chunks_exact(2).enumerate().all(|(i, pair)| {
                    pair[0] & 1 == 0
                        && pair[1] == pair[0] | 1
                        && (i == 0 || file[2 * i - 1] < pair[0])
                })
        })
    }

    /// Every undirected edge used by exactly two triangles and no triangle
    /// with a repeated vertex, whatever the orientations: closed and
    /// manifold along its edges.
    pub fn is_closed(&self) -> bool {
        Edges::new(self).closed(&self.triangles)
    }

    /// The mesh without the vertices no triangle uses, the others kept in
    /// order (the engine's output is always compacted this way).
    pub fn compacted(self) -> TriMesh {
        self.compacted_with_origin().0
    }

    /// [`TriMesh::compacted`], also giving for every kept vertex its index
    /// before compaction (increasing: the order is kept).
    pub fn compacted_with_origin(self) -> (TriMesh, Vec<u32>) {
        let index = marked_used(self.positions.len(), &self.triangles);
        if index.iter().all(|&i| i == 0) {
            let origin = (0..self.positions.len() as u32).collect();
            return (self, origin);
        }
        renumbered(&self.positions, self.triangles, index)
    }

    /// The mesh of `triangles` (indices into `positions`) with only the
    /// vertices they use, in increasing order, and for each of them its
    /// index in `positions`: a piece of a larger mesh cut out without
    /// copying the rest of it. Every index of `triangles` must be below
    /// `positions.len()`.
    pub fn of_used(positions: &[DVec3], triangles: Vec<[u32; 3]>) -> (TriMesh, Vec<u32>) {
        // A small piece of a large mesh (a brush's on a million
        // triangles) is numbered by its sorted vertices, without a pass
        // over every position.
        if triangles.len().saturating_mul(16) < positions.len() {
            let mut origin: Vec<u32> = triangles.iter().flatten().copied().collect();
            origin.sort_unstable();
            origin.dedup();
            let local = |v: u32| origin.binary_search(&v).unwrap_or_else(|i| i) as u32;
            let triangles = triangles.iter().map(|t| t.map(local)).collect();
            let positions = origin.iter().map(|&v| positions[v as usize]).collect();
            return (
                TriMesh {
                    positions,
                    triangles,
                },
                origin,
            );
        }
        let index = marked_used(positions.len(), &triangles);
        renumbered(positions, triangles, index)
    }

    /// The mesh as a soup: every triangle its own three corners (copies of
    /// the positions), in order.
    pub fn unwelded(&self) -> TriMesh {
        TriMesh {
            positions: self
                .triangles
                .iter()
                .flat_map(|t| t.map(|v| self.positions[v as usize]))
                .collect(),
            triangles: (0..self.triangles.len() as u32)
                .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                .collect(),
        }
    }

    /// Calls `f(v, corners, fan)` for every vertex with two or more
    /// corners: `corners` are its corner slots (`3t + k`), `fan[j]` the
    /// fan of `corners[j]`, numbered from 0 in order of first corner.
    /// Triangles around a vertex are in one fan when they are joined
    /// through edges at that vertex.
    fn for_each_fan(&self, mut f: impl FnMut(usize, &[u32], &[u32])) {
        let n = self.positions.len();
        let mut start = vec![0u32; n + 1];
        for t in &self.triangles {
            for &v in t {
                start[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut corners = vec![0u32; 3 * self.triangles.len()];
        for (i, t) in self.triangles.iter().enumerate() {
            for (k, &v) in t.iter().enumerate() {
                corners[fill[v as usize] as usize] = (3 * i + k) as u32;
                fill[v as usize] += 1;
            }
        }
        // Scratch reused across vertices.
        let mut sets = crate::union_find::UnionFind::default();
        let mut by_neighbour: Vec<(u32, usize)> = Vec::new();
        let mut fan: Vec<u32> = Vec::new();
        let mut number: Vec<u32> = Vec::new();
        for v in 0..n {
            let around = &corners[start[v] as usize..start[v + 1] as usize];
            if around.len() < 2 {
                continue;
            }
            sets.reset(around.len());
            by_neighbour.clear();
            for (j, &c) in around.iter().enumerate() {
                let t = self.triangles[c as usize / 3];
                let k = c as usize % 3;
                for u in [t[(k + 1) % 3], t[(k + 2) % 3]] {
                    if u as usize != v {
                        by_neighbour.push((u, j));
                    }
                }
            }
            by_neighbour.sort_unstable();
            for w in by_neighbour.windows(2) {
                if w[0].0 == w[1].0 {
                    sets.union(w[0].1 as u32, w[1].1 as u32);
                }
            }
            number.clear();
            number.resize(around.len(), u32::MAX);
            fan.clear();
            let mut fans = 0;
            for j in 0..around.len() {
                let r = sets.find(j as u32) as usize;
                if number[r] == u32::MAX {
                    number[r] = fans;
                    fans += 1;
                }
                fan.push(number[r]);
            }
            f(v, around, &fan);
        }
    }

    /// Per vertex: whether its triangles form more than one fan (sheets
    /// that touch at a point: a pinch).
    pub fn pinched_vertices(&self) -> Vec<bool> {
        let mut pinched = vec![false; self.positions.len()];
        self.for_each_fan(|v, _, fan| pinched[v] = fan.iter().any(|&f| f > 0));
        pinched
    }

    /// Splits every pinched vertex `v` (see [`TriMesh::pinched_vertices`])
    /// with `eligible(v)` into one vertex per fan, at the same position,
    /// so that the surface is a 2-manifold there (a DLFL needs that). The
    /// fan holding the vertex's first corner keeps it; each other fan
    /// gets a new vertex, appended. Returns, for each new vertex in order,
    /// the vertex it was split from. `eligible` is asked only about
    /// pinched vertices (so it may be costly the first time, and is
    /// never paid for on a mesh without pinches).
    pub fn split_pinches_where(&mut self, mut eligible: impl FnMut(usize) -> bool) -> Vec<u32> {
        // (corner, fan) of every corner that moves to a new vertex.
        let mut moves: Vec<(u32, u32, u32)> = Vec::new();
        self.for_each_fan(|v, corners, fan| {
            if fan.iter().any(|&f| f > 0) && eligible(v) {
                for (&c, &f) in corners.iter().zip(fan) {
                    if f > 0 {
                        moves.push((v as u32, f, c));
                    }
                }
            }
        });
        moves.sort_unstable();
        let mut split_from = Vec::new();
        let mut last = (u32::MAX, u32::MAX, 0u32);
        for (v, f, c) in moves {
            if (v, f) != (last.0, last.1) {
                let new = self.positions.len() as u32;
                self.positions.push(self.positions[v as usize]);
                split_from.push(v);
                last = (v, f, new);
            }
            self.triangles[c as usize / 3][c as usize % 3] = last.2;
        }
        split_from
    }

    /// Checks indices and that every position is finite.
    pub fn check(&self) -> Result<(), MeshError> {
        check_positions("mesh", &self.positions)?;
        let n = self.positions.len();
        if n >= u32::MAX as usize {
            return Err(MeshError::TooLarge(n));
        }
        // The largest index of each block first, branch-free and in
        // parallel runs; only the first block with a bad index is searched
        // for its first one.
        const BLOCK: usize = 256;
        let largest = |block: &[[u32; 3]]| block.iter().flatten().fold(0, |m, &i| m.max(i));
        let bad = self
            .triangles
            .par_chunks(BLOCK)
            .with_min_len(crate::PARALLEL_RUN / BLOCK)
            .position_first(|block| largest(block) as usize >= n);
        if let Some(b) = bad {
            let block = &self.triangles[b * BLOCK..self.triangles.len().min((b + 1) * BLOCK)];
            for (k, tri) in block.iter().enumerate() {
                if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: b * BLOCK + k,
                        index,
                        count: n,
                    });
                }
            }
        }
        Ok(())
    }

    /// The three corner positions of triangle `t`.
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Area of triangle `t`: half the length of the cross product of two of
    /// its edges (the parallelogram they span, halved).
    pub fn triangle_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.corners(t);
        0.5 * (b - a).cross(c - a).length()
    }

    /// Total surface area: the sum of [`TriMesh::triangle_area`] over the
    /// triangles, in order. Overlapping or coincident triangles each count.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| self.triangle_area(t))
            .sum()
    }
}

/// The numbers of the triangles of `triangles` with a vertex `pick`
/// takes, in order: one pass over a whole mesh in parallel runs, for a
/// caller that then handles the few it finds in order (a brush's piece, a
/// remeshing work set).
pub fn triangles_with_vertex(
    triangles: &[[u32; 3]],
    pick: impl Fn(u32) -> bool + Sync,
) -> Vec<usize> {
    triangles
        .par_iter()
        .with_min_len(crate::PARALLEL_RUN)
        .enumerate()
        .filter(|(_, t)| t.iter().any(|&v| pick(v)))
        .map(|(i, _)| i)
        .collect()
}

/// Per vertex of `n`: 0 where some triangle uses it, `u32::MAX` elsewhere.
fn marked_used(n: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    marked_used_where(n, triangles, None)
}

/// [`marked_used`] over the triangles `skip` does not flag (all of them
/// without `skip`).
fn marked_used_where(n: usize, triangles: &[[u32; 3]], skip: Option<&[bool]>) -> Vec<u32> {
    let kept = |t: usize| skip.is_none_or(|s| !s[t]);
    if triangles.len() < 2 * crate::PARALLEL_RUN {
        let mut index = vec![u32::MAX; n];
        for (_, t) in triangles.iter().enumerate().filter(|(t, _)| kept(*t)) {
            for &v in t {
                index[v as usize] = 0;
            }
        }
        return index;
    }
    // In parallel runs: threads that mark the same vertex store the
    // same value, so relaxed stores suffice.
    let marks: Vec<AtomicU32> = (0..n)
        .into_par_iter()
        .with_min_len(crate::PARALLEL_RUN)
        .map(|_| AtomicU32::new(u32::MAX))
        .collect();
    triangles
        .par_iter()
        .with_min_len(crate::PARALLEL_RUN)
        .enumerate()
        .for_each(|(t, tri)| {
            if kept(t) {
                for &v in tri {
                    marks[v as usize].store(0, Ordering::Relaxed);
                }
            }
        });
    marks.into_iter().map(AtomicU32::into_inner).collect()
}

/// Numbers the vertices `index` marks used (0; the rest `u32::MAX`) in
/// increasing order, in place, and gives each numbered vertex's old
/// index. The numbering goes in parallel runs: each run counts its used
/// vertices, and then numbers them from the count of the runs before it.
fn numbered(index: &mut [u32]) -> Vec<u32> {
    const RUN: usize = crate::PARALLEL_RUN;
    let counts: Vec<u32> = index
        .par_chunks(RUN)
        .map(|run| run.iter().filter(|&&i| i == 0).count() as u32)
        .collect();
    let firsts: Vec<u32> = counts
        .iter()
        .scan(0, |next, &c| {
            let first = *next;
            *next += c;
            Some(first)
        })
        .collect();
    index
        .par_chunks_mut(RUN)
        .zip(firsts)
        .for_each(|(run, mut next)| {
            for i in run.iter_mut().filter(|i| **i == 0) {
                *i = next;
                next += 1;
            }
        });
    index
        .par_iter()
        .with_min_len(RUN)
        .enumerate()
        .filter(|(_, i)| **i != u32::MAX)
        .map(|(k, _)| k as u32)
        .collect()
}

/// What [`splice_keeping_slots`] made.
#[derive(Clone, Debug, PartialEq)]
pub struct SlotSplice {
    /// The spliced mesh.
    pub mesh: TriMesh,
    /// What changed number or slot.
    pub changes: SlotChanges,
}

/// What a splice that keeps slots ([`splice_keeping_slots`],
/// [`splice_in_place`]) renumbered and wrote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SlotChanges {
    /// The vertices before the added ones that changed number, as
    /// `(from, to)`: the last ones, moved into the slots of those the
    /// splice dropped. Every other one kept its number.
    pub moved: Vec<(u32, u32)>,
    /// The number of the first added vertex: the surviving ones of
    /// `positions` come before it, the used added ones from it on.
    pub first_added: usize,
    /// The triangle slots written: those of the skipped triangles (each
    /// now holding an extra triangle or one moved from the end, or past
    /// the end) and the extra triangles appended. Every other slot holds
    /// its triangle, its vertices renumbered as `moved` says.
    pub written_triangles: Vec<u32>,
}

impl SlotChanges {
    /// The vertex slots the splice wrote: those the moved vertices went
    /// to, and the added vertices (`vertex_count` is the spliced mesh's).
    pub fn written_vertices(&self, vertex_count: usize) -> Vec<u32> {
        let mut vertices: Vec<u32> = self.moved.iter().map(|&(_, to)| to).collect();
        vertices.extend(self.first_added as u32..vertex_count as u32);
        vertices
    }
}

/// The mesh of the triangles of `triangles` that `skip` does not flag,
/// and `extra`, over the positions `positions` followed by `added`, with
/// every unused vertex dropped, numbered so that as little as possible
/// changes number:
/// - a kept triangle keeps its slot; `extra`'s triangles take the slots
///   of the skipped ones in order, the rest of them go after the last;
///   where fewer come than were skipped, the last triangles move into
///   the slots left over ([`crate::slots::fill_holes`]);
/// - a vertex of `positions` keeps its number, except the last ones,
///   which move into the slots of the dropped ones; the used added
///   vertices follow, in order.
///
/// A sculpting frame that cut the surface of a million triangles then
/// renumbers the few dozen things it touched, not everything after the
/// first vertex it dropped: the modeller sends the frame as a patch of
/// those slots, and the points a frame made are still the last ones
/// (which its snake hook reads). It is [`TriMesh::compacted`] of the
/// built mesh up to that numbering. `skip` has one flag per triangle,
/// and every index is below `positions.len() + added.len()`.
///
/// This finds the unused vertices by a pass over every triangle and
/// copies the mesh; [`splice_in_place`] does neither.
pub fn splice_keeping_slots(
    positions: &[DVec3],
    added: &[DVec3],
    triangles: &[[u32; 3]],
    skip: &[bool],
    extra: &[[u32; 3]],
) -> SlotSplice {
    const RUN: usize = crate::PARALLEL_RUN;
    let n = positions.len();
    // `u32::MAX` where no kept triangle nor `extra` uses the vertex.
    let mut used = marked_used_where(n, triangles, Some(skip));
    for &v in extra.iter().flatten().filter(|&&v| (v as usize) < n) {
        used[v as usize] = 0;
    }
    let dropped: Vec<u32> = used
        .par_iter()
        .with_min_len(RUN)
        .enumerate()
        .filter(|(_, i)| **i == u32::MAX)
        .map(|(v, _)| v as u32)
        .collect();
    let skipped: Vec<u32> = skip
        .par_iter()
        .with_min_len(RUN)
        .enumerate()
        .filter(|(_, s)| **s)
        .map(|(t, _)| t as u32)
        .collect();
    let mut mesh = TriMesh {
        positions: positions.to_vec(),
        triangles: triangles.to_vec(),
    };
    let changes = splice_in_place(&mut mesh, added, &skipped, &dropped, extra);
    SlotSplice { mesh, changes }
}

/// [`splice_keeping_slots`] written into `mesh` itself, for a caller
/// that knows what goes: `skipped` lists the slots of the triangles
/// taken out, and `dropped` the vertices of `mesh` that no triangle left
/// nor `extra` uses, both ascending and distinct; `added` and `extra`
/// are as there. With `dropped` every such vertex, the result and its
/// numbering are `splice_keeping_slots`'s for the mesh's triangles
/// without those `skipped`.
///
/// Its cost is what changes, plus one pass over the triangles to
/// renumber the vertices moved into the dropped ones' slots, made only
/// when some moved: no copy of the mesh. A sculpting frame that cuts a
/// million triangles spent 25 ms in the copying splice.
pub fn splice_in_place(
    mesh: &mut TriMesh,
    added: &[DVec3],
    skipped: &[u32],
    dropped: &[u32],
    extra: &[[u32; 3]],
) -> SlotChanges {
    const RUN: usize = crate::PARALLEL_RUN;
    let n = mesh.positions.len();
    let mut moved = Vec::new();
    crate::slots::fill_holes(&mut mesh.positions, dropped, |from, to| {
        moved.push((from as u32, to as u32));
    });
    let first_added = mesh.positions.len();
    // The new numbers of the vertices past the kept ones (each moved or
    // dropped) and of the added ones (used or not).
    let mut tail = vec![u32::MAX; n - first_added];
    for &(from, to) in &moved {
        tail[from as usize - first_added] = to;
    }
    let mut added_used = vec![false; added.len()];
    for &v in extra.iter().flatten() {
        if let Some(used) = (v as usize)
            .checked_sub(n)
            .and_then(|k| added_used.get_mut(k))
        {
            *used = true;
        }
    }
    let mut added_index = vec![u32::MAX; added.len()];
    for ((index, &used), &p) in added_index.iter_mut().zip(&added_used).zip(added) {
        if used {
            *index = mesh.positions.len() as u32;
            mesh.positions.push(p);
        }
    }
    let number = |v: u32| match (v as usize).checked_sub(first_added) {
        None => v,
        Some(k) if k < tail.len() => tail[k],
        Some(k) => added_index[k - tail.len()],
    };
    if !moved.is_empty() {
        mesh.triangles
            .par_iter_mut()
            .with_min_len(RUN)
            .for_each(|t| {
                if t.iter().any(|&v| v as usize >= first_added) {
                    *t = t.map(number);
                }
            });
    }
    let mut extra = extra.iter().map(|t| t.map(number));
    let mut holes = Vec::new();
    for &slot in skipped {
        match extra.next() {
            Some(t) => mesh.triangles[slot as usize] = t,
            None => holes.push(slot),
        }
    }
    let appended = mesh.triangles.len() as u32;
    mesh.triangles.extend(extra);
    // The holes are skipped slots, already among `skipped`.
    crate::slots::fill_holes(&mut mesh.triangles, &holes, |_, _| {});
    let mut written_triangles = skipped.to_vec();
    written_triangles.extend(appended..mesh.triangles.len() as u32);
    SlotChanges {
        moved,
        first_added,
        written_triangles,
    }
}

/// `triangles` over the positions `index` marks used ([`marked_used`]),
/// numbered in increasing order ([`numbered`]), and each kept vertex's
/// old index.
fn renumbered(
    positions: &[DVec3],
    mut triangles: Vec<[u32; 3]>,
    mut index: Vec<u32>,
) -> (TriMesh, Vec<u32>) {
    const RUN: usize = crate::PARALLEL_RUN;
    let origin = numbered(&mut index);
    let kept: Vec<DVec3> = origin
        .par_iter()
        .with_min_len(RUN)
        .map(|&k| positions[k as usize])
        .collect();
    triangles
        .par_iter_mut()
        .with_min_len(RUN)
        .for_each(|t| *t = t.map(|v| index[v as usize]));
    (
        TriMesh {
            positions: kept,
            triangles,
        },
        origin,
    )
}

/// Whether triangle `t` names one vertex twice: no triangle at all, but
/// what a weld or a snap leaves where it merged two of its corners. The
/// one test every stage that drops such triangles (or leaves them out of
/// its geometry) asks.
#[inline]
pub fn repeats_a_corner(t: &[u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[0] == t[2]
}

/// Checks that every position is finite; `what` names the array in errors.
pub fn check_positions(what: &'static str, positions: &[DVec3]) -> Result<(), MeshError> {
    NonFinite::check("vertex", positions).map_err(|e| MeshError::NonFinite(e.in_input(what)))
}

/// Every triangle side `(key, 3·t + k)` (side `k` of triangle `t` runs
/// from corner `k` to `k + 1`; `key` is `(smaller end << 32) | larger
/// end`), ordered by key, then side: the order of a sort of all 3n sides,
/// found by a counting sort on the smaller end and a sort of each bucket
/// (a vertex's few edges to larger vertices).
pub fn sides_by_edge(triangles: &[[u32; 3]]) -> Vec<(u64, u32)> {
    let (start, bucketed) = bucketed_sides(triangles);
    (0..start.len() - 1)
        .flat_map(|a| {
            bucketed[start[a] as usize..start[a + 1] as usize]
                .iter()
                .map(move |&(b, side)| (((a as u64) << 32) | u64::from(b), side))
        })
        .collect()
}

/// The row starts of a compressed table keyed by an edge's smaller end,
/// with room in row `a` for every triangle side whose smaller end is `a`
/// (a side shared by two triangles counts twice): row `a` is
/// `start[a]..start[a + 1]`, for `a` in `0..vertices` (every index of
/// `triangles` must be below `vertices`). The first step of a counting
/// sort of the sides by edge; [`sides_by_edge`] fills such a table with
/// the sides, icosphere subdivision with the edge midpoints.
pub fn rows_by_smaller_end(triangles: &[[u32; 3]], vertices: usize) -> Vec<u32> {
    let mut start = vec![0u32; vertices + 1];
    for tri in triangles {
        for k in 0..3 {
            start[tri[k].min(tri[(k + 1) % 3]) as usize + 1] += 1;
        }
    }
    for v in 0..vertices {
        start[v + 1] += start[v];
    }
    start
}

/// [`sides_by_edge`] before the keys are spelled out: `bucketed[start[a]
/// .. start[a + 1]]` holds `(larger end, side)` of the sides whose smaller
/// end is `a`, sorted.
fn bucketed_sides(triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut rows = Rows::file(vertex_bound(triangles), || {
        triangles.iter().enumerate().flat_map(|(t, tri)| {
            (0..3).map(move |k| {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                (a.min(b), (a.max(b), (t * 3 + k) as u32))
            })
        })
    });
    rows.rows_mut()
        .into_par_iter()
        .for_each(|b| b.sort_unstable());
    (rows.start, rows.items)
}

/// One past the largest index of `triangles` (0 for none).
fn vertex_bound(triangles: &[[u32; 3]]) -> usize {
    triangles
        .iter()
        .flatten()
        .max()
        .map_or(0, |&v| v as usize + 1)
}

/// The undirected edges of a triangle mesh, by vertex index, with the
/// triangles around each (any number: boundary, manifold, non-manifold).
#[derive(Clone, Debug, Default)]
pub struct Edges {
    /// Edge `e` joins `ends[e][0] < ends[e][1]` (or equal for a degenerate
    /// triangle that repeats a vertex).
    pub ends: Vec<[u32; 2]>,
    /// The edge of each triangle side `k` (from corner `k` to `k + 1`).
    pub of_triangle: Vec<[u32; 3]>,
    /// Triangles of edge `e`: `tris[offsets[e]..offsets[e + 1]]`.
    pub offsets: Vec<u32>,
    /// The triangles of every edge, concatenated edge by edge, each triangle
    /// listed once per edge (even one that uses the edge on two sides).
    pub tris: Vec<u32>,
    /// What the construction saw of every edge, in the same pass.
    pub summary: EdgeSummary,
}

/// The closedness and orientation of a mesh's edges, gathered while its
/// edge table is built (a separate pass over the edges cost as much as a
/// fifth of the table).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeSummary {
    /// The first edge with an odd number of triangles.
    pub first_odd: Option<u32>,
    /// Every edge has exactly two triangles, running along it in opposite
    /// directions ([`Edges::opposite`] of every edge).
    pub all_opposite: bool,
}

impl Default for EdgeSummary {
    /// The summary of no edges.
    fn default() -> Self {
        EdgeSummary {
            first_odd: None,
            all_opposite: true,
        }
    }
}

/// `a` then `b` with `shift` applied to each of `b`'s items (in parallel).
fn glue<T: Copy + Send + Sync>(a: &[T], b: &[T], shift: impl Fn(T) -> T + Sync + Send) -> Vec<T> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    out.extend_from_slice(a);
    out.par_extend(b.par_iter().map(|&x| shift(x)));
    out
}

impl Edges {
    /// Collects the edges of `mesh` (indices are assumed checked).
    pub fn new(mesh: &TriMesh) -> Edges {
        Edges::of_triangles(&mesh.triangles)
    }

    /// Collects the edges of `triangles` (indices are assumed checked;
    /// no positions needed).
    pub fn of_triangles(triangles: &[[u32; 3]]) -> Edges {
        let nt = triangles.len();
        let (start, sides) = bucketed_sides(triangles);
        let mut ends = Vec::with_capacity(sides.len() / 2 + 1);
        let mut of_triangle = vec![[0u32; 3]; nt];
        let mut offsets = Vec::with_capacity(sides.len() / 2 + 2);
        offsets.push(0u32);
        let mut tris = Vec::with_capacity(3 * nt);
        let mut summary = EdgeSummary::default();
        for a in 0..start.len() - 1 {
            let bucket = &sides[start[a] as usize..start[a + 1] as usize];
            let mut i = 0;
            while i < bucket.len() {
                let b = bucket[i].0;
                let e = ends.len() as u32;
                ends.push([a as u32, b]);
                let first = tris.len();
                // Sides along the edge from its first end, and against it.
                let mut runs = [0u32; 2];
                while i < bucket.len() && bucket[i].0 == b {
                    let side = bucket[i].1 as usize;
                    of_triangle[side / 3][side % 3] = e;
                    let t = (side / 3) as u32;
                    runs[usize::from(triangles[side / 3][side % 3] != a as u32)] += 1;
                    // A triangle with a repeated vertex may use one edge twice.
                    if tris.len() == first || tris.last() != Some(&t) {
                        tris.push(t);
                    }
                    i += 1;
                }
                let count = tris.len() - first;
                if count % 2 == 1 && summary.first_odd.is_none() {
                    summary.first_odd = Some(e);
                }
                // Two triangles, one running each way (a degenerate edge,
                // a == b, never qualifies: both its sides count as along).
                summary.all_opposite &= count == 2 && runs == [1, 1] && a as u32 != b;
                offsets.push(tris.len() as u32);
            }
        }
        Edges {
            ends,
            of_triangle,
            offsets,
            tris,
            summary,
        }
    }

    /// The edges of two meshes side by side, `self`'s (of a mesh with
    /// `vertices` vertices and `triangles` triangles) then `other`'s, its
    /// vertices and triangles numbered after them: [`Edges::new`] of the
    /// joined mesh, built from two independent halves.
    pub fn joined(&self, other: &Edges, vertices: u32, triangles: u32) -> Edges {
        let (edge_offset, tri_offset) = (self.ends.len() as u32, self.tris.len() as u32);
        let ends = glue(&self.ends, &other.ends, |e| e.map(|v| v + vertices));
        let of_triangle = glue(&self.of_triangle, &other.of_triangle, |s| {
            s.map(|e| e + edge_offset)
        });
        // `other`'s offsets start with its own 0, which `self`'s last
        // offset already stands for.
        let other_offsets = other.offsets.get(1..).unwrap_or(&[]);
        let offsets = glue(&self.offsets, other_offsets, |o| o + tri_offset);
        let tris = glue(&self.tris, &other.tris, |t| t + triangles);
        Edges {
            ends,
            of_triangle,
            offsets,
            tris,
            summary: EdgeSummary {
                first_odd: self
                    .summary
                    .first_odd
                    .or(other.summary.first_odd.map(|e| e + edge_offset)),
                all_opposite: self.summary.all_opposite && other.summary.all_opposite,
            },
        }
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// True when there are no edges.
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// The triangles that have edge `e` as a side.
    pub fn triangles(&self, e: usize) -> &[u32] {
        &self.tris[self.offsets[e] as usize..self.offsets[e + 1] as usize]
    }

    /// [`TriMesh::is_closed`] of the mesh these edges were collected from
    /// (`triangles`): no triangle repeats a vertex and every edge has
    /// exactly two triangles.
    pub fn closed(&self, triangles: &[[u32; 3]]) -> bool {
        !triangles.iter().any(repeats_a_corner)
            && (0..self.ends.len())
                .into_par_iter()
                .all(|e| self.triangles(e).len() == 2)
    }

    /// [`TriMesh::is_closed_manifold`] of the mesh these edges were
    /// collected from (`triangles`), in one pass over the edges: closed,
    /// and the two triangles of every edge run along it in opposite
    /// directions.
    pub fn closed_oriented(&self, triangles: &[[u32; 3]]) -> bool {
        self.summary.all_opposite && !triangles.par_iter().any(repeats_a_corner)
    }

    /// Whether triangle `t` (of `triangles`, the mesh these edges were
    /// collected from) runs along edge `e` from its first end; `None` if
    /// `e` is not one of its sides.
    pub fn runs_forward(&self, triangles: &[[u32; 3]], t: u32, e: usize) -> Option<bool> {
        (0..3)
            .find(|&k| self.of_triangle[t as usize][k] as usize == e)
            .map(|k| triangles[t as usize][k] == self.ends[e][0])
    }

    /// Whether edge `e` has exactly two triangles, running along it in
    /// opposite directions (consistently oriented there).
    pub fn opposite(&self, triangles: &[[u32; 3]], e: usize) -> bool {
        match *self.triangles(e) {
            [t, u] => matches!(
                (self.runs_forward(triangles, t, e), self.runs_forward(triangles, u, e)),
                (Some(a), Some(b)) if a != b
            ),
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> TriMesh {
        TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn area_sums_the_triangles() {
        // The unit square as two right triangles of area ½ each.
        let m = quad();
        assert_eq!(m.triangle_area(0), 0.5);
        assert_eq!(m.area(), 1.0);
        assert_eq!(TriMesh::default().area(), 0.0);
    }

    #[test]
    fn closed_manifold_check() {
        let tet = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        };
        assert!(tet.is_closed_manifold());
        let mut open = tet.clone();
        open.triangles.pop();
        assert!(!open.is_closed_manifold());
        let mut flipped = tet.clone();
        flipped.triangles[0] = [0, 1, 2];
        assert!(!flipped.is_closed_manifold());
        let mut doubled = tet.clone();
        doubled
            .triangles
            .extend(tet.triangles.iter().map(|t| [t[0], t[2], t[1]]));
        assert!(!doubled.is_closed_manifold());
        // The edge-table test and the unoriented one agree case by case.
        let mut pinched = tet.clone();
        pinched.triangles[0] = [0, 0, 1];
        for (m, oriented, closed) in [
            (&tet, true, true),
            (&open, false, false),
            (&flipped, false, true),
            (&doubled, false, false),
            (&pinched, false, false),
        ] {
            assert_eq!(m.is_closed_manifold(), oriented);
            assert_eq!(Edges::new(m).closed_oriented(&m.triangles), oriented);
            assert_eq!(m.is_closed(), closed);
            // The summary is the per-edge tests, gathered while building.
            let e = Edges::new(m);
            assert_eq!(
                e.summary.all_opposite,
                (0..e.len()).all(|k| e.opposite(&m.triangles, k))
            );
            assert_eq!(
                e.summary.first_odd,
                (0..e.len() as u32).find(|&k| e.triangles(k as usize).len() % 2 == 1)
            );
        }
    }

    /// The filed check agrees with the edge table's on closed meshes
    /// broken every way a side can be: a triangle flipped, dropped,
    /// doubled (either way), joined to a copy of one of its edges in a
    /// third triangle (a fin), or with a corner repeated.
    #[test]
    fn closed_manifold_check_agrees_with_the_edge_table() {
        let (corners, faces) = holey_testkit::octahedron();
        let octa = TriMesh {
            positions: corners.iter().map(|&c| DVec3::from(c)).collect(),
            triangles: faces.to_vec(),
        };
        let mut rng = holey_testkit::Rng::new(0x9e37_79b9);
        let mut next = |n: usize| rng.below(n);
        let mut agreed = [0usize; 2];
        for round in 0..400 {
            let mut m = octa.clone();
            for _ in 0..1 + round % 3 {
                let t = next(m.triangles.len());
                let tri = m.triangles[t];
                match next(6) {
                    0 => m.triangles[t] = [tri[0], tri[2], tri[1]],
                    1 => {
                        m.triangles.swap_remove(t);
                    }
                    2 => m.triangles.push(tri),
                    3 => m.triangles.push([tri[0], tri[2], tri[1]]),
                    4 => m.triangles.push([tri[1], tri[0], (tri[2] + 1) % 6]),
                    _ => m.triangles[t][next(3)] = tri[next(3)],
                }
            }
            if round % 5 == 0 {
                m = octa.clone();
            }
            let expected = Edges::new(&m).closed_oriented(&m.triangles);
            assert_eq!(m.is_closed_manifold(), expected, "{:?}", m.triangles);
            agreed[usize::from(expected)] += 1;
        }
        // Both answers were reached.
        assert!(agreed[0] > 100 && agreed[1] >= 80, "{agreed:?}");
    }

    #[test]
    fn split_pinches_gives_each_fan_its_own_vertex() {
        // Two tetrahedra sharing only vertex 0: a pinch.
        let tet = |o: DVec3, first: u32| {
            let [a, b, c] = [first, first + 1, first + 2];
            (
                vec![o + DVec3::X, o + DVec3::Y, o + DVec3::Z],
                vec![[0, b, a], [0, a, c], [a, b, c], [b, 0, c]],
            )
        };
        let (p1, t1) = tet(DVec3::ZERO, 1);
        let (p2, t2) = tet(DVec3::ZERO, 4);
        let mut m = TriMesh {
            positions: [vec![DVec3::ZERO], p1, p2.iter().map(|p| -*p).collect()].concat(),
            triangles: [t1, t2].concat(),
        };
        let before = m.clone();
        let split = m.split_pinches_where(|_| true);
        assert_eq!(split, vec![0]);
        assert_eq!(m.positions.len(), 8);
        assert_eq!(m.positions[7], m.positions[0]);
        // The first fan kept vertex 0, the second has the copy.
        assert!(m.triangles[..4].iter().all(|t| !t.contains(&7)));
        assert!(m.triangles[4..].iter().all(|t| !t.contains(&0)));
        assert!(m.is_closed_manifold());
        // Nothing else changed; a manifold is left alone.
        for (a, b) in m.triangles.iter().zip(&before.triangles) {
            assert_eq!(a.map(|v| if v == 7 { 0 } else { v }), *b);
        }
        let mut again = m.clone();
        assert!(again.split_pinches_where(|_| true).is_empty());
        assert_eq!(again.triangles, m.triangles);
        // Only eligible vertices are split.
        let mut kept = before.clone();
        assert_eq!(before.pinched_vertices().iter().filter(|&&p| p).count(), 1);
        assert!(before.pinched_vertices()[0]);
        assert!(kept.split_pinches_where(|v| v != 0).is_empty());
        assert_eq!(kept.triangles, before.triangles);
    }

    /// A polygon soup and its triangle mesh convert both ways; append,
    /// translate and transform keep the triangles and move the points; plain
    /// arrays make the same mesh.
    #[test]
    fn conversions_and_placement() {
        let square = crate::PolyMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            [[0u32, 1, 2, 3]],
        );
        let t = TriMesh::from(&square);
        assert_eq!(t.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(t, square.triangulated());
        let back = crate::PolyMesh::from(&t);
        assert_eq!(back.face_count(), 2);
        assert_eq!(back.face(1), &[0, 2, 3]);
        let mut two = t.clone();
        two.append(&t.translated(DVec3::Z));
        assert_eq!(two.positions.len(), 8);
        assert_eq!(two.triangles[2], [4, 5, 6]);
        assert_eq!(two.positions[6], DVec3::new(1.0, 1.0, 1.0));
        let scaled = t.transformed(|p| 2.0 * p);
        assert_eq!(scaled.positions[2], DVec3::new(2.0, 2.0, 0.0));
        assert_eq!(scaled.triangles, t.triangles);
        let arrays = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert_eq!(TriMesh::from_arrays(&arrays, &[[0, 1, 2], [0, 2, 3]]), t);
    }

    #[test]
    fn compaction_in_parallel_runs_numbers_as_one_pass_in_order_would() {
        // 100k points, 40k triangles over every third one (past the size
        // where marking and numbering go in parallel runs).
        let n = 100_000u32;
        let positions: Vec<DVec3> = (0..n).map(|i| DVec3::new(f64::from(i), 1.0, 2.0)).collect();
        let mut x = 12345u64;
        let mut next = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((x >> 33) as u32 % (n / 3)) * 3
        };
        let triangles: Vec<[u32; 3]> = (0..40_000).map(|_| [next(), next(), next()]).collect();
        // The oracle: one sequential pass in vertex order.
        let mut used = vec![false; n as usize];
        for &v in triangles.iter().flatten() {
            used[v as usize] = true;
        }
        let origin: Vec<u32> = (0..n).filter(|&v| used[v as usize]).collect();
        let new = |v: u32| origin.binary_search(&v).expect("used") as u32;
        let expected = TriMesh {
            positions: origin.iter().map(|&v| positions[v as usize]).collect(),
            triangles: triangles.iter().map(|t| t.map(new)).collect(),
        };
        let (m, o) = TriMesh {
            positions,
            triangles,
        }
        .compacted_with_origin();
        assert_eq!(o, origin);
        assert_eq!(m, expected);
    }

    /// A pseudo-random number below `m` per call (a linear congruential
    /// generator from `seed`): the splice tests' meshes.
    fn numbers(seed: u64) -> impl FnMut(u32) -> u32 {
        let mut x = seed;
        move |m: u32| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 33) as u32 % m
        }
    }

    /// `n` points of a mesh and `a` added ones, told apart by `y`.
    fn splice_points(n: u32, a: u32) -> (Vec<DVec3>, Vec<DVec3>) {
        let positions = (0..n).map(|i| DVec3::new(f64::from(i), 1.0, 0.5)).collect();
        let added = (0..a)
            .map(|i| DVec3::new(-f64::from(i), 2.0, 0.5))
            .collect();
        (positions, added)
    }

    /// The splice that keeps slots is the mesh built and then compacted,
    /// up to numbering (kept triangles, then the extra ones, over the
    /// positions and the added ones; vertices unused before, every fifth,
    /// and those only skipped triangles used are dropped), and it
    /// renumbers only what the splice touched: a kept triangle keeps its
    /// slot, the extra ones fill the skipped slots in order, a kept
    /// vertex keeps its number unless it is reported moved, and the used
    /// added vertices come last, in order. Small and large (parallel
    /// runs); with more, fewer and no extra triangles than skipped ones.
    #[test]
    fn a_splice_keeping_slots_is_the_built_mesh_compacted_and_renumbers_only_what_it_touched() {
        let mut next = numbers(99);
        for (n, t, a) in [(50u32, 30usize, 4u32), (100_000, 40_000, 300)] {
            let (positions, added) = splice_points(n, a);
            let mut used = || loop {
                let v = next(n);
                if !v.is_multiple_of(5) {
                    return v;
                }
            };
            let triangles: Vec<[u32; 3]> = (0..t).map(|_| [used(), used(), used()]).collect();
            for (share, e) in [(0, t / 20), (3, t / 20), (10, t / 5), (10, 0)] {
                let skip: Vec<bool> = (0..t).map(|_| share > 0 && next(share) == 0).collect();
                let extra: Vec<[u32; 3]> = (0..e)
                    .map(|_| [next(n + a), next(n + a), next(n + a)])
                    .collect();
                let mut all = positions.clone();
                all.extend(&added);
                let mut tris: Vec<[u32; 3]> = triangles
                    .iter()
                    .zip(&skip)
                    .filter(|(_, s)| !**s)
                    .map(|(t, _)| *t)
                    .collect();
                tris.extend(&extra);
                let expected = TriMesh {
                    positions: all.clone(),
                    triangles: tris,
                }
                .compacted();
                let got = splice_keeping_slots(&positions, &added, &triangles, &skip, &extra);
                let what = format!("{n} points, one in {share} skipped, {e} extra");
                let at = |m: &TriMesh, t: [u32; 3]| t.map(|v| m.positions[v as usize].to_array());
                let corners = |m: &TriMesh| {
                    let mut c: Vec<_> = m.triangles.iter().map(|&t| at(m, t)).collect();
                    c.sort_by(|p, q| p.partial_cmp(q).expect("finite"));
                    c
                };
                assert_eq!(corners(&got.mesh), corners(&expected), "{what}");
                assert_eq!(got.mesh.positions.len(), expected.positions.len(), "{what}");
                let old = |t: [u32; 3]| t.map(|v| all[v as usize].to_array());
                let free: Vec<usize> = (0..t).filter(|&s| skip[s]).collect();
                for (slot, &tri) in got.mesh.triangles.iter().enumerate() {
                    let want = if slot >= t {
                        extra[free.len() + slot - t]
                    } else if skip[slot] {
                        let k = free.iter().position(|&s| s == slot).expect("skipped");
                        if k < e { extra[k] } else { continue }
                    } else {
                        triangles[slot]
                    };
                    assert_eq!(at(&got.mesh, tri), old(want), "{what}: slot {slot}");
                }
                // A slot not reported written holds its own triangle.
                let written: std::collections::HashSet<u32> =
                    got.changes.written_triangles.iter().copied().collect();
                for (slot, &tri) in got.mesh.triangles.iter().enumerate() {
                    if !written.contains(&(slot as u32)) {
                        assert!(slot < t && !skip[slot], "{what}: slot {slot} not written");
                        assert_eq!(at(&got.mesh, tri), old(triangles[slot]), "{what}: {slot}");
                    }
                }
                let moved_from: std::collections::HashMap<u32, u32> =
                    got.changes.moved.iter().map(|&(f, to)| (to, f)).collect();
                for v in 0..got.changes.first_added {
                    let from = moved_from.get(&(v as u32)).map_or(v, |&f| f as usize);
                    assert!(
                        from == v || from >= got.changes.first_added,
                        "{what}: moves come from the end"
                    );
                    assert_eq!(got.mesh.positions[v], positions[from], "{what}: vertex {v}");
                }
                let used_added: Vec<DVec3> = expected.positions[got.changes.first_added..].to_vec();
                assert_eq!(
                    &got.mesh.positions[got.changes.first_added..],
                    &used_added[..],
                    "{what}"
                );
                assert!(
                    used_added.iter().all(|p| p.y == 2.0),
                    "{what}: added come last"
                );
            }
        }
    }

    /// The in-place splice, told only which vertices of the skipped
    /// triangles end up unused (as a sculpting frame knows them from its
    /// region's ring), gives the copying splice's mesh and numbering on a
    /// mesh that uses every vertex: small and large (parallel runs), with
    /// more, fewer and no extra triangles than skipped ones, with
    /// vertices dropped from the middle and from the end.
    #[test]
    fn a_splice_in_place_is_the_copying_splice() {
        let mut next = numbers(7);
        for (n, t, a) in [(40u32, 60usize, 5u32), (60_000, 150_000, 200)] {
            let (positions, added) = splice_points(n, a);
            // Every vertex used: the first n / 3 triangles run through
            // them all.
            let triangles: Vec<[u32; 3]> = (0..t)
                .map(|k| {
                    if (k as u32) < n.div_ceil(3) {
                        let v = 3 * k as u32;
                        [v % n, (v + 1) % n, (v + 2) % n]
                    } else {
                        [next(n), next(n), next(n)]
                    }
                })
                .collect();
            // Vertices moved into dropped ones' slots, over the cases.
            let mut moves = 0;
            for (share, e) in [(2, t / 3), (4, t / 20), (10, 0), (3, t / 4)] {
                let skip: Vec<bool> = (0..t).map(|_| next(share) == 0).collect();
                let extra: Vec<[u32; 3]> = (0..e)
                    .map(|_| [next(n + a), next(n + a), next(n / 2)])
                    .collect();
                let copied = splice_keeping_slots(&positions, &added, &triangles, &skip, &extra);
                // What the skipped triangles used and nothing else uses.
                let mut used = vec![false; n as usize];
                for (tri, _) in triangles.iter().zip(&skip).filter(|(_, s)| !**s) {
                    for &v in tri {
                        used[v as usize] = true;
                    }
                }
                for &v in extra.iter().flatten().filter(|&&v| v < n) {
                    used[v as usize] = true;
                }
                let mut candidates: Vec<u32> = triangles
                    .iter()
                    .zip(&skip)
                    .filter(|(_, s)| **s)
                    .flat_map(|(tri, _)| *tri)
                    .collect();
                candidates.sort_unstable();
                candidates.dedup();
                let dropped: Vec<u32> = candidates
                    .into_iter()
                    .filter(|&v| !used[v as usize])
                    .collect();
                let skipped: Vec<u32> = (0..t as u32).filter(|&s| skip[s as usize]).collect();
                let mut mesh = TriMesh {
                    positions: positions.clone(),
                    triangles: triangles.clone(),
                };
                let changes = splice_in_place(&mut mesh, &added, &skipped, &dropped, &extra);
                let what = format!("{n} points, one in {share} skipped, {e} extra");
                moves += changes.moved.len();
                assert_eq!(mesh, copied.mesh, "{what}");
                assert_eq!(changes, copied.changes, "{what}");
            }
            assert!(
                moves > 0,
                "{n} points: no vertex moved, the renumbering untried"
            );
        }
    }

    #[test]
    fn a_small_piece_is_numbered_as_the_pass_over_every_vertex_numbers_it() {
        // 200 points, and pieces of 1 to 12 triangles over scattered ones:
        // the sorted-vertex path and the whole pass must agree exactly.
        let positions: Vec<DVec3> = (0..200).map(|i| DVec3::new(i as f64, 0.5, -1.0)).collect();
        for k in 1..=12u32 {
            let tris: Vec<[u32; 3]> = (0..k)
                .map(|t| [(t * 37) % 200, (t * 91 + 5) % 200, (t * 13 + 150) % 200])
                .collect();
            assert!(tris.len() * 16 < positions.len());
            let small = TriMesh::of_used(&positions, tris.clone());
            let whole = renumbered(
                &positions,
                tris.clone(),
                marked_used(positions.len(), &tris),
            );
            assert_eq!(small, whole, "{k} triangles");
        }
    }

    #[test]
    fn a_piece_of_used_vertices_and_a_soup() {
        let positions = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE];
        let (piece, origin) = TriMesh::of_used(&positions, vec![[4, 1, 3], [3, 1, 0]]);
        assert_eq!(origin, vec![0, 1, 3, 4]);
        assert_eq!(piece.triangles, vec![[3, 1, 2], [2, 1, 0]]);
        assert_eq!(
            piece.positions,
            vec![DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::ONE]
        );
        let soup = piece.unwelded();
        assert_eq!(soup.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(
            soup.positions,
            vec![
                DVec3::ONE,
                DVec3::X,
                DVec3::Z,
                DVec3::Z,
                DVec3::X,
                DVec3::ZERO
            ]
        );
    }

    #[test]
    fn compacted_drops_unused_vertices_in_order() {
        let m = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::splat(9.0)],
            triangles: vec![[1, 3, 2]],
        };
        let c = m.compacted();
        assert_eq!(c.positions, vec![DVec3::X, DVec3::Y, DVec3::splat(9.0)]);
        assert_eq!(c.triangles, vec![[0, 2, 1]]);
    }

    #[test]
    fn edges_of_two_triangles() {
        let e = Edges::new(&quad());
        assert_eq!(e.len(), 5);
        let diagonal = e.of_triangle[0][2];
        assert_eq!(e.ends[diagonal as usize], [0, 2]);
        assert_eq!(e.triangles(diagonal as usize), &[0, 1]);
        assert_eq!(e.of_triangle[1][0], diagonal);
        let boundary = e.of_triangle[0][0];
        assert_eq!(e.triangles(boundary as usize), &[0]);
    }

    #[test]
    fn non_manifold_and_degenerate_edges() {
        let mut m = quad();
        m.positions.push(DVec3::Z);
        m.triangles.push([0, 2, 4]);
        m.triangles.push([1, 1, 3]);
        let e = Edges::new(&m);
        let diagonal = e.of_triangle[0][2] as usize;
        assert_eq!(e.triangles(diagonal), &[0, 1, 2]);
        let degenerate = e.of_triangle[3][0] as usize;
        assert_eq!(e.ends[degenerate], [1, 1]);
        assert_eq!(e.triangles(degenerate), &[3]);
    }

    #[test]
    fn joined_edges_are_those_of_the_joined_mesh() {
        // A non-manifold, degenerate mesh with an unused last vertex, then
        // the quad: numbering, triangle lists and degenerate edges carry
        // over.
        let mut a = quad();
        a.positions.push(DVec3::Z);
        a.positions.push(DVec3::splat(5.0));
        a.triangles.push([0, 2, 4]);
        a.triangles.push([1, 1, 3]);
        let b = quad();
        let n = a.positions.len() as u32;
        let mut joined = a.clone();
        joined.positions.extend_from_slice(&b.positions);
        joined
            .triangles
            .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
        let whole = Edges::new(&joined);
        let parts = Edges::new(&a).joined(&Edges::new(&b), n, a.triangles.len() as u32);
        assert_eq!(parts.ends, whole.ends);
        assert_eq!(parts.of_triangle, whole.of_triangle);
        assert_eq!(parts.offsets, whole.offsets);
        assert_eq!(parts.tris, whole.tris);
        assert_eq!(parts.summary, whole.summary);
        assert!(whole.summary.first_odd.is_some());
        // Two closed, oriented parts: so is the whole.
        let tet = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
        };
        let two = Edges::new(&tet).joined(&Edges::new(&tet), 4, 4);
        assert_eq!(two.summary, EdgeSummary::default());
        // An empty first part.
        let empty = TriMesh::default();
        let alone = Edges::new(&empty).joined(&Edges::new(&b), 0, 0);
        assert_eq!(alone.ends, Edges::new(&b).ends);
        assert_eq!(alone.offsets, Edges::new(&b).offsets);
    }

    #[test]
    fn check_names_the_problem() {
        let mut m = quad();
        m.triangles.push([0, 1, 9]);
        assert_eq!(
            m.check(),
            Err(MeshError::IndexOutOfRange {
                triangle: 2,
                index: 9,
                count: 4
            })
        );
        let mut n = quad();
        n.positions[2].y = f64::NAN;
        assert!(n.check().unwrap_err().to_string().contains("vertex 2"));
        // Past the first blocks the check reads: the first bad index and
        // the first bad point, by their own numbers.
        let mut long = quad();
        long.triangles = vec![[0, 1, 2]; 1000];
        long.triangles[700] = [0, 5, 1];
        long.triangles[900] = [0, 1, 7];
        assert_eq!(
            long.check(),
            Err(MeshError::IndexOutOfRange {
                triangle: 700,
                index: 5,
                count: 4
            })
        );
        let mut far = quad();
        far.positions = vec![DVec3::ONE; 1000];
        far.positions[613].z = f64::INFINITY;
        far.positions[999].x = f64::NAN;
        assert!(far.check().unwrap_err().to_string().contains("vertex 613"));
    }
}
