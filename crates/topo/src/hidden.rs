//! Pieces hidden inside the surface: connected components that lie
//! inside the rest of it.
//!
//! A change can cut a piece loose inside a body: a grab whose strand
//! folded over itself pushed its tip through a wall, the strand vanished
//! as swept and the tip stayed inside, unseen (issue 15: "a hidden second
//! component of 764 triangles inside the head"). For a solid that piece
//! has both sides inside, which Lemma 8.1 deletes; parity on a scan with
//! holes can keep it. The guard ([`crate::guard`]) counts such pieces
//! near what a frame changed, before and after, and a frame that adds
//! one is worse. Counting before too keeps what the surface already
//! held: a ship sculpted inside a bottle is inside the rest before and
//! after.
//!
//! Inside means the generalized winding number of the rest of the
//! surface (every other component) is at least ½ in magnitude (either
//! orientation; the rule of issue 14) at points spread over the piece,
//! every one of them: near the opening of an open sheet the winding
//! number passes ½ without anything being enclosed.

use glam::DVec3;

use crate::mesh::TriMesh;
use crate::union_find::UnionFind;
use crate::winding::winding_numbers_at;

/// Most candidate components a count examines (one pass over the
/// surface each); past that the frame has shattered the surface and the
/// other checks speak for it.
const MAX_CANDIDATES: usize = 16;

/// Points sampled on each candidate piece.
const SAMPLES: usize = 8;

/// How many connected components of `m` with a vertex that `near` flags
/// lie inside the rest of `m` (module docs), sampled at the centroids of
/// up to [`SAMPLES`] of their triangles. Components are joined through
/// shared vertices.
pub(crate) fn hidden_pieces(m: &TriMesh, near: &dyn Fn(u32) -> bool) -> usize {
    let n = m.positions.len();
    let mut uf = UnionFind::new(n);
    for t in &m.triangles {
        uf.union(t[0], t[1]);
        uf.union(t[0], t[2]);
    }
    let root: Vec<u32> = m.triangles.iter().map(|t| uf.find(t[0])).collect();
    // A single component has no rest to lie in.
    let Some(&first) = root.first() else {
        return 0;
    };
    if root.iter().all(|&r| r == first) {
        return 0;
    }
    // Candidates: the components near the change, with their triangles.
    let mut candidate: rustc_hash::FxHashMap<u32, Vec<usize>> = Default::default();
    for (i, t) in m.triangles.iter().enumerate() {
        if t.iter().any(|&v| near(v)) {
            candidate.entry(root[i]).or_default();
        }
    }
    if candidate.len() > MAX_CANDIDATES {
        return 0;
    }
    for (i, r) in root.iter().enumerate() {
        if let Some(list) = candidate.get_mut(r) {
            list.push(i);
        }
    }
    let position = |v: u32| m.positions[v as usize];
    candidate
        .iter()
        .filter(|&(&r, tris)| {
            // Samples spread over the piece: the centroids of every k-th
            // of its triangles. A piece near an open sheet can have a
            // point where that sheet's winding number passes ½; a hidden
            // piece is inside at every point.
            let step = tris.len().div_ceil(SAMPLES).max(1);
            let at: Vec<DVec3> = tris
                .iter()
                .step_by(step)
                .map(|&t| m.triangles[t].map(position).iter().sum::<DVec3>() / 3.0)
                .collect();
            winding_numbers_at(&m.triangles, &|u| root[u] != r, &position, &at)
                .iter()
                .all(|w| w.abs() >= 0.5)
        })
        .count()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// An axis-aligned box as 12 outward triangles (testkit's unit cube
    /// stretched over `lo`..`hi`).
    fn cube(lo: DVec3, hi: DVec3) -> TriMesh {
        let (corners, quads) = holey_testkit::unit_cube();
        TriMesh {
            positions: corners
                .iter()
                .map(|&c| lo + (hi - lo) * DVec3::from_array(c))
                .collect(),
            triangles: quads
                .iter()
                .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
                .collect(),
        }
    }

    fn joined(a: &TriMesh, b: &TriMesh) -> TriMesh {
        let mut m = a.clone();
        let n = m.positions.len() as u32;
        m.positions.extend(&b.positions);
        m.triangles
            .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
        m
    }

    /// A small box inside a big one is hidden, beside it is not; the big
    /// one is never inside the small one; only components near the
    /// change count.
    #[test]
    fn a_box_inside_a_box_is_hidden_one_beside_it_is_not() {
        let big = cube(DVec3::splat(-2.0), DVec3::splat(2.0));
        let inside = joined(&big, &cube(DVec3::splat(-0.5), DVec3::splat(0.5)));
        let beside = joined(
            &big,
            &cube(DVec3::new(3.0, -0.5, -0.5), DVec3::new(4.0, 0.5, 0.5)),
        );
        let all = |_: u32| true;
        assert_eq!(hidden_pieces(&inside, &all), 1);
        assert_eq!(hidden_pieces(&beside, &all), 0);
        assert_eq!(hidden_pieces(&big, &all), 0);
        // Inside-out (inward-facing) boxes count alike.
        let flipped = TriMesh {
            triangles: inside
                .triangles
                .iter()
                .map(|t| [t[0], t[2], t[1]])
                .collect(),
            ..inside.clone()
        };
        assert_eq!(hidden_pieces(&flipped, &all), 1);
        // Only the big box near the change: the small one is not looked at.
        assert_eq!(hidden_pieces(&inside, &|v| v < 8), 0);
    }
}
