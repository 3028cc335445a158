//! Coincident sub-triangles of opposite orientation cancel.
//!
//! Where two curves cross each other closely on two sheets, a patch of
//! each sheet can be bounded by curve edges alone, and when the curve
//! points round onto the same positions and are glued (`place_points`),
//! the two patches are one triangle twice: the same three vertices, one
//! copy from each sheet, facing opposite ways. Kept, they close up into
//! a pillow of no volume hung on whichever of its edges the sheets go on
//! through (an edge of four triangles, a non-manifold curve), and the
//! guard held such frames (a bunny's inflate over the haunch, where two
//! neighbouring triangles folded flat onto each other across their
//! shared edge). They bound nothing and show nothing, so they are taken
//! out, as a Boolean's opposite coincident faces cancel. Only
//! sub-triangles the cut made from two source triangles that are not
//! themselves one triangle twice are paired: an input's own double-sided
//! sheet stays as it was.

use crate::mesh::repeats_a_corner;
use rustc_hash::FxHashMap as HashMap;

/// The kept triangles on one set of three vertices: those running them
/// one way, and those running them the other.
type Facing = (Vec<usize>, Vec<usize>);

/// Drops (`keep[t] = false`) every pair of kept triangles with the same
/// three vertices in opposite orders that `may_cancel(i, j)` admits,
/// among the `candidate`s (a cheap test: the triangles the cut made, not
/// the many it left whole); a triangle pairs once. Returns the number of
/// triangles dropped.
pub(crate) fn cancel_opposite(
    tris: &[[u32; 3]],
    keep: &mut [bool],
    candidate: impl Fn(usize) -> bool,
    may_cancel: impl Fn(usize, usize) -> bool,
) -> usize {
    // Each triangle's vertices rotated to start at the smallest, and
    // whether the rest then run in increasing order (its orientation).
    let key = |t: [u32; 3]| {
        let k = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
        let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
        ((a, b.min(c), b.max(c)), b < c)
    };
    let mut open: HashMap<(u32, u32, u32), Facing> = HashMap::default();
    for (i, t) in tris.iter().enumerate() {
        if !keep[i] || !candidate(i) || repeats_a_corner(t) {
            continue;
        }
        let (k, forward) = key(*t);
        let (fwd, bwd) = open.entry(k).or_default();
        if forward { fwd.push(i) } else { bwd.push(i) }
    }
    let mut dropped = 0;
    for (fwd, bwd) in open.values() {
        if bwd.is_empty() {
            continue;
        }
        for &f in fwd {
            if let Some(&b) = bwd.iter().find(|&&b| keep[b] && may_cancel(f, b)) {
                keep[f] = false;
                keep[b] = false;
                dropped += 2;
            }
        }
    }
    dropped
}

/// Whether triangles `a` and `b` have the same three corners (in any
/// order): the same triangle twice.
pub(crate) fn same_corners(a: [u32; 3], b: [u32; 3]) -> bool {
    let (mut a, mut b) = (a, b);
    a.sort_unstable();
    b.sort_unstable();
    a == b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_and_its_reverse_cancel_where_admitted_and_odd_copies_stay() {
        let tris = [
            [0, 1, 2], // not candidates (an input's double-sided sheet, say)
            [2, 1, 0],
            [3, 4, 5],
            [4, 3, 5], // its reverse, rotated
            [5, 3, 4], // a third copy, facing as the first: no partner
            [6, 7, 8], // alone
        ];
        let mut keep = vec![true; tris.len()];
        assert_eq!(
            cancel_opposite(&tris, &mut keep, |i| i >= 2, |_, _| true),
            2
        );
        assert_eq!(keep, [true, true, false, false, true, true]);
        assert!(same_corners([1, 2, 3], [3, 1, 2]) && !same_corners([1, 2, 3], [1, 2, 4]));
    }
}
