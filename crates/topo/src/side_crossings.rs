//! Where the sides of a coplanar group cross, in its projection: the
//! points each side is split at before it goes into the overlay's
//! constrained triangulation (`coplanar::triangulate`).
//!
//! Spade's splitting insertion finds crossings one constraint at a time
//! and rounds each crossing where it meets it. When many sides cross near
//! one point (the big coplanar fans of a CAD export, several faces
//! stacked on one strip), a later side meets the already rounded pieces
//! of an earlier one, and its conflict walk can fail outright (a panic in
//! spade: "previous_region.is_empty()"). Here every crossing is found
//! first, from the input's own coordinates:
//!
//! - two sides cross properly when each has the other's ends strictly on
//!   opposite sides, by exact `orient2d` (a side through another's end,
//!   or along it, is not a crossing: the triangulation splits a
//!   constraint at every vertex exactly on it, itself);
//! - the crossing point is rounded once, from the two sides' ends;
//! - points within `on_side::SNAP` of the group's size of a
//!   corner are that corner, and crossings that close of each other are
//!   one point (`on_side::snap_crossings`), so three sides through one
//!   point meet at one vertex.
//!
//! Each side is then inserted as the chain of its pieces between
//! consecutive split points, ordered along it.

use glam::{DVec2, DVec3};
use holey_geom::{Sign, orient2d};

use crate::on_side::{near_line_2d, snap_crossings};

/// A proper crossing: sides `i` and `j` meet at `point` (rounded).
struct Crossing {
    i: usize,
    j: usize,
    point: DVec2,
}

/// Whether segments `a–b` and `c–d` cross properly: each has the other's
/// ends strictly on opposite sides (exact).
fn cross_properly(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let opposite = |x: Sign, y: Sign| {
        matches!(
            (x, y),
            (Sign::Positive, Sign::Negative) | (Sign::Negative, Sign::Positive)
        )
    };
    opposite(orient2d(a, b, c), orient2d(a, b, d)) && opposite(orient2d(c, d, a), orient2d(c, d, b))
}

/// The crossing point of two properly crossing segments, rounded: on the
/// shorter one, at the parameter A_c / (A_c − A_d) that the signed areas
/// of its ends over the longer one's line give it (each area rounded
/// once), so the point lies on the shorter segment to rounding however
/// nearly parallel the two are.
fn crossing_point(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> DVec2 {
    let ((a, b), (c, d)) = if (b - a).length_squared() >= (d - c).length_squared() {
        ((a, b), (c, d))
    } else {
        ((c, d), (a, b))
    };
    // Signed areas of c and d over the line a → b.
    let u = b - a;
    let (ac, ad) = (u.perp_dot(c - a), u.perp_dot(d - a));
    let t = ac / (ac - ad);
    c + (d - c) * t
}

/// Every proper crossing among `sides`: the sides sorted by their
/// lowest x and swept, so only pairs whose x-ranges meet are tested.
fn crossings(sides: &[[DVec2; 2]]) -> Vec<Crossing> {
    let lo = |s: &[DVec2; 2]| s[0].min(s[1]);
    let hi = |s: &[DVec2; 2]| s[0].max(s[1]);
    let mut order: Vec<usize> = (0..sides.len()).collect();
    order.sort_by(|&i, &j| lo(&sides[i]).x.total_cmp(&lo(&sides[j]).x));
    let mut found = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        let (li, hi_i) = (lo(&sides[i]), hi(&sides[i]));
        for &j in &order[k + 1..] {
            let (lj, hj) = (lo(&sides[j]), hi(&sides[j]));
            if lj.x > hi_i.x {
                break;
            }
            if lj.y > hi_i.y || hj.y < li.y {
                continue;
            }
            let [a, b] = sides[i];
            let [c, d] = sides[j];
            if cross_properly(a, b, c, d) {
                let point = crossing_point(a, b, c, d);
                if point.is_finite() {
                    found.push(Crossing { i, j, point });
                }
            }
        }
    }
    found
}

/// How many times the pieces are searched for crossings again (see
/// [`split_points`]); what is left after these goes to spade's splitting
/// insertion.
const ROUNDS: usize = 8;

/// The pieces of `sides` between their `splits`: (the piece, its side).
fn pieces_of(sides: &[[DVec2; 2]], splits: &[Vec<DVec2>]) -> (Vec<[DVec2; 2]>, Vec<usize>) {
    let mut pieces = Vec::new();
    let mut side_of = Vec::new();
    for (k, &[a, b]) in sides.iter().enumerate() {
        let mut from = a;
        for &p in splits[k].iter().chain([&b]) {
            pieces.push([from, p]);
            side_of.push(k);
            from = p;
        }
    }
    (pieces, side_of)
}

/// Each side's split points ordered along it, without its ends or
/// repeats.
fn order_along(sides: &[[DVec2; 2]], splits: &mut [Vec<DVec2>]) {
    for (k, points) in splits.iter_mut().enumerate() {
        let [a, b] = sides[k];
        let u = b - a;
        // Strictly between the ends: a crossing within rounding of an end
        // can be snapped to a corner just beyond it, and a split there
        // would fold the side back on itself (a hairpin whose pieces
        // cross the sides at that end, failing the overlay).
        points.retain(|&p| {
            let t = (p - a).dot(u);
            t > 0.0 && t < u.dot(u)
        });
        points.sort_by(|p, q| (*p - a).dot(u).total_cmp(&(*q - a).dot(u)));
        points.dedup();
    }
}

/// The split points of each of `sides` (in the projection; `corners` are
/// all the group's corners, the sides' ends among them): for side `k`,
/// the points strictly between its ends where other sides cross it,
/// ordered from its first end to its second, each a corner's point or a
/// crossing point shared by every side through it.
///
/// The pieces between them can cross again: a piece whose end was
/// rounded can cross a nearly parallel one that its side did not cross.
/// Rounding such a crossing would only move the problem (on the OpenSCAD
/// export, each round of that found 20–36 new crossings), so it makes no
/// new point: each piece is split at the other's end nearest the
/// crossing (the two run side by side, so that end lies next to it). The
/// points are then fixed, each side takes each at most once, and the
/// rounds end.
pub(crate) fn split_points(corners: &[DVec2], sides: &[[DVec2; 2]]) -> Vec<Vec<DVec2>> {
    let mut splits: Vec<Vec<DVec2>> = vec![Vec::new(); sides.len()];
    let found = crossings(sides);
    if found.is_empty() {
        return splits;
    }
    // Corners first, then the crossings, lifted to z = 0 for the snap.
    let points: Vec<DVec3> = corners
        .iter()
        .chain(found.iter().map(|c| &c.point))
        .map(|p| p.extend(0.0))
        .collect();
    let crossing: Vec<bool> = (0..points.len()).map(|k| k >= corners.len()).collect();
    let to = snap_crossings(&points, &crossing);
    for (n, c) in found.iter().enumerate() {
        let p = points[to[corners.len() + n]].truncate();
        splits[c.i].push(p);
        splits[c.j].push(p);
    }
    order_along(sides, &mut splits);
    for _ in 0..ROUNDS {
        let (pieces, side_of) = pieces_of(sides, &splits);
        let again = crossings(&pieces);
        if again.is_empty() {
            break;
        }
        let before: usize = splits.iter().map(Vec::len).sum();
        for c in &again {
            let ([a, b], [d, e]) = (pieces[c.i], pieces[c.j]);
            let nearer = |x: DVec2, y: DVec2| {
                if (x - c.point).length() <= (y - c.point).length() {
                    x
                } else {
                    y
                }
            };
            // Each piece at the other's end nearest the crossing, unless
            // that is its side's own end or lies off its side's line by
            // more than rounding (a bend, not a split: left to spade).
            for (k, end) in [(side_of[c.i], nearer(d, e)), (side_of[c.j], nearer(a, b))] {
                let [p, q] = sides[k];
                if end != p && end != q && near_line_2d(p, q, end) {
                    splits[k].push(end);
                }
            }
        }
        order_along(sides, &mut splits);
        if splits.iter().map(Vec::len).sum::<usize>() == before {
            // No piece could be split at an end on its line: the rest
            // goes to spade.
            break;
        }
    }
    splits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_sides_through_one_point_meet_at_one_split_point() {
        // Three segments through (1/3, 1/3)-ish: a star of three lines
        // whose pairwise crossings round to points an ulp apart at most.
        let c = DVec2::new(0.1, 0.7);
        let dirs = [
            DVec2::new(1.0, 0.3),
            DVec2::new(-0.2, 1.0),
            DVec2::new(0.7, -0.9),
        ];
        let sides: Vec<[DVec2; 2]> = dirs.iter().map(|&d| [c - d * 0.37, c + d * 0.61]).collect();
        let corners: Vec<DVec2> = sides.iter().flatten().copied().collect();
        let splits = split_points(&corners, &sides);
        let all: Vec<DVec2> = splits.iter().flatten().copied().collect();
        assert_eq!(all.len(), 3, "each side split once: {splits:?}");
        assert!(all.iter().all(|&p| p == all[0]), "one point: {all:?}");
        assert!((all[0] - c).length() < 1e-12);
    }

    /// A split point snapped to a corner just beyond a side's end (a
    /// crossing within rounding of the end, computed on a nearly parallel
    /// side) is dropped: splitting there would fold the side back on
    /// itself, its first piece running backwards.
    #[test]
    fn split_points_beyond_a_sides_ends_are_dropped() {
        let sides = [[DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0)]];
        let mut splits = vec![vec![
            DVec2::new(0.5, 0.0),
            DVec2::new(-1e-12, 0.0),
            DVec2::new(1.0 + 1e-12, 1e-13),
            DVec2::new(0.25, 1e-17),
            DVec2::new(1.0, 0.0),
        ]];
        order_along(&sides, &mut splits);
        assert_eq!(
            splits[0],
            vec![DVec2::new(0.25, 1e-17), DVec2::new(0.5, 0.0)]
        );
    }

    #[test]
    fn touching_or_collinear_sides_are_not_crossings() {
        let sides = [
            [DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0)],
            // Ends on the first side: a T, and a side along it.
            [DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0)],
            [DVec2::new(0.5, 0.0), DVec2::new(3.0, 0.0)],
            // Crosses the T's stem properly.
            [DVec2::new(0.0, 0.5), DVec2::new(2.0, 0.5)],
        ];
        let corners: Vec<DVec2> = sides.iter().flatten().copied().collect();
        let splits = split_points(&corners, &sides);
        assert!(splits[0].is_empty() && splits[2].is_empty());
        assert_eq!(splits[1], vec![DVec2::new(1.0, 0.5)]);
        assert_eq!(splits[3], vec![DVec2::new(1.0, 0.5)]);
    }

    #[test]
    fn splits_are_ordered_along_each_side() {
        // One long side crossed by five short ones, given out of order.
        let long = [DVec2::new(4.0, 1.0), DVec2::new(-1.0, 0.0)];
        let mut sides = vec![long];
        for x in [2.0, 0.0, 3.0, 1.0, -0.5] {
            sides.push([DVec2::new(x, -1.0), DVec2::new(x, 2.0)]);
        }
        let corners: Vec<DVec2> = sides.iter().flatten().copied().collect();
        let splits = split_points(&corners, &sides);
        let xs: Vec<f64> = splits[0].iter().map(|p| p.x).collect();
        assert_eq!(xs, vec![3.0, 2.0, 1.0, 0.0, -0.5]);
        for (k, s) in splits.iter().enumerate().skip(1) {
            assert_eq!(s.len(), 1, "side {k}");
            // On the long side's line to rounding.
            let p = s[0];
            assert!((p.y - 0.2 * (p.x + 1.0)).abs() < 1e-15);
        }
    }
}
