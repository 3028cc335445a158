//! The preprocessing of §IV (after §III.3): faces with different numbers
//! of corners are matched by subdividing edges of the smaller one.
//!
//! The rule is the kernel's `create_pipe` rule — repeatedly split the
//! longest edge of the smaller face at its midpoint, considering only
//! edges whose other side lies in neither face (so each split adds
//! exactly one corner to the smaller face and none to the larger) — but it
//! is *planned* first, without touching the mesh, so that the handle's
//! geometry can be computed (and refused) before anything changes, and so
//! that every section is built with the final corner count.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec3;
use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh};

use super::HandleError;

/// The new vertices to insert along one edge.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EdgeSplit {
    pub(crate) edge: EdgeId,
    /// The new points in the edge's own direction (from the vertex of
    /// `edge_corners(edge)[0]` to the other end).
    pub(crate) points: Vec<DVec3>,
}

/// A planned matching: the splits, and the smaller face's polygon as it
/// will be afterwards, read forwards from the given start corner.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Matching {
    pub(crate) splits: Vec<EdgeSplit>,
    pub(crate) polygon: Vec<DVec3>,
}

/// One piece of an edge in the simulation: `[a, b]` in the edge's walk
/// parameter, of length `len`.
#[derive(Clone, Copy, Debug)]
struct Piece {
    len: f64,
    seq: u64,
    edge: usize,
    a: f64,
    b: f64,
}

impl PartialEq for Piece {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Piece {}
impl PartialOrd for Piece {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Piece {
    /// Longest first; among equals, the earliest made (walk order first).
    fn cmp(&self, other: &Self) -> Ordering {
        self.len
            .total_cmp(&other.len)
            .then_with(|| other.seq.cmp(&self.seq))
    }
}

/// Plans the splits that bring face `small` (read from `start`) up to
/// `target` corners, without touching the mesh.
///
/// Cost: O(n + m log n) for a face of n corners and m splits. Fails with
/// [`HandleError::Unmatchable`] when corners are missing and no edge of
/// `small` may be split.
pub(crate) fn plan_matching(
    mesh: &Mesh,
    start: CornerId,
    large: FaceId,
    target: usize,
) -> Result<Matching, HandleError> {
    let small = mesh.corner_face(start)?;
    let corners: Vec<CornerId> = mesh.face_corners_from(start)?.collect();
    let n = corners.len();
    let mut ends = Vec::with_capacity(n);
    let mut heap = BinaryHeap::new();
    let mut seq = 0u64;
    for (i, &c) in corners.iter().enumerate() {
        let u = mesh.position(mesh.corner_vertex(c)?)?;
        let w = mesh.position(mesh.corner_vertex(mesh.corner_next(c)?)?)?;
        ends.push((u, w));
        let Some(e) = mesh.corner_edge(c)? else {
            continue;
        };
        let [x, y] = mesh.edge_corners(e)?;
        let far = if x == c { y } else { x };
        let g = mesh.corner_face(far)?;
        if g != small && g != large {
            heap.push(Piece {
                len: u.distance(w),
                seq,
                edge: i,
                a: 0.0,
                b: 1.0,
            });
            seq += 1;
        }
    }
    let need = target.saturating_sub(n);
    if need > 0 && heap.is_empty() {
        return Err(HandleError::Unmatchable { small, large });
    }
    let mut cuts: Vec<Vec<f64>> = vec![Vec::new(); n];
    for _ in 0..need {
        let Some(p) = heap.pop() else {
            // Unreachable: a split piece always leaves two splittable halves.
            return Err(HandleError::Unmatchable { small, large });
        };
        let mid = 0.5 * (p.a + p.b);
        cuts[p.edge].push(mid);
        for (a, b) in [(p.a, mid), (mid, p.b)] {
            heap.push(Piece {
                len: 0.5 * p.len,
                seq,
                edge: p.edge,
                a,
                b,
            });
            seq += 1;
        }
    }
    let mut polygon = Vec::with_capacity(n + need);
    let mut splits = Vec::new();
    for (i, &c) in corners.iter().enumerate() {
        let (u, w) = ends[i];
        polygon.push(u);
        let cut = &mut cuts[i];
        if cut.is_empty() {
            continue;
        }
        cut.sort_by(f64::total_cmp);
        polygon.extend(cut.iter().map(|&s| u.lerp(w, s)));
        let Some(e) = mesh.corner_edge(c)? else {
            continue;
        };
        // The edge runs u → w when it starts at this corner, else w → u.
        let forwards = mesh.edge_corners(e)?[0] == c;
        let points: Vec<DVec3> = if forwards {
            cut.iter().map(|&s| u.lerp(w, s)).collect()
        } else {
            cut.iter().rev().map(|&s| u.lerp(w, s)).collect()
        };
        splits.push(EdgeSplit { edge: e, points });
    }
    Ok(Matching { splits, polygon })
}
