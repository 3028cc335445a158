//! Coplanar overlaps merged in `holey resolve`'s arrangement (issue 14:
//! "`holey resolve` also merges coplanar overlaps, so that afterwards no
//! two triangles cross or overlap").
//!
//! The arrangement's cut works in a perturbed world in which coplanar
//! triangles do not meet, so triangles lying in one plane and
//! overlapping there (a CAD export's stacked duplicates, two shells
//! sharing a face) come out of it still overlapping. Each group of such
//! triangles is replaced by its overlay ([`crate::coplanar`], rule
//! [`Keep::Once`]): the constrained triangulation of all their sides in
//! the plane, each cell counted by the triangles covering it with their
//! facings (+1 one way, −1 the other) and kept once, facing by the
//! count's sign, where that is not 0. Stacked copies become one; faces
//! folded flat onto each other, or two sheets meeting face to face,
//! cancel where they overlap, which leaves the surface's winding number
//! unchanged off the plane. No cell is covered twice.
//!
//! The overlay splits the group's sides where other sides cross them (at
//! points rounded once and lifted onto the plane) and where other
//! corners lie on them. A triangle outside the group sharing such a side
//! must be split at the same points, or the surface would open along it:
//! every side a group split is recorded with its points, and each
//! triangle of the result is fanned from its opposite corners through
//! the points on its sides (those recorded for the side or the side it
//! is a piece of, and any other split point on its line, to rounding). This needs no orientation (the
//! arrangement has none to rely on: its sheets cross and stack). A
//! merge that would leave more sides on one triangle only than the
//! arrangement had (a rounded crossing that the sides around it do not
//! follow) is not made.

use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

use holey_geom::{Aabb, Bvh};

use crate::coplanar::{Keep, Overlay, for_each_overlapping_pair, overlap_groups, position_index};
use crate::mesh::{Edges, TriMesh, repeats_a_corner};
use crate::on_side::{near_line, on_side_between, on_side_reach, welded_classes};

/// What merging the overlaps did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Merged {
    /// Groups of overlapping coplanar triangles replaced by their overlay.
    pub groups: usize,
    /// Groups left as they were: the overlay could not be made (the
    /// splitting insertion of a side failed, or its split points could
    /// not be followed), or merging it would have opened the surface.
    pub left: usize,
}

/// The sides the overlays split, by their ends (smaller first), each with
/// its points in order from the smaller end; and the side each piece of
/// such a side belongs to.
#[derive(Default)]
struct SplitSides {
    points: HashMap<(u32, u32), Vec<u32>>,
    piece_of: HashMap<(u32, u32), (u32, u32)>,
    /// Every split point, and a tree of them: found again on a side with
    /// other ends along the same line (another group's cell side).
    all: Vec<u32>,
    tree: Option<Bvh>,
}

fn key(u: u32, v: u32) -> (u32, u32) {
    (u.min(v), u.max(v))
}

impl SplitSides {
    /// Records that the side `u → v` was split at `on` (in order from
    /// `u`), merging the points with those another group split it at.
    fn record(&mut self, positions: &[DVec3], (u, v): (u32, u32), on: &[u32]) {
        let side = key(u, v);
        self.all.extend_from_slice(on);
        let points = self.points.entry(side).or_default();
        let fresh = points.is_empty();
        if u > v {
            points.extend(on.iter().rev());
        } else {
            points.extend_from_slice(on);
        }
        if !fresh {
            let along = along(positions, side);
            points.sort_by(|&a, &b| along(a).total_cmp(&along(b)));
            points.dedup();
        }
        let mut chain = vec![side.0];
        chain.extend(points.iter().copied());
        chain.push(side.1);
        for w in chain.windows(2) {
            self.piece_of.entry(key(w[0], w[1])).or_insert(side);
        }
    }

    /// Builds the tree of all split points (after the last `record`).
    fn finish(&mut self, positions: &[DVec3]) {
        self.all.sort_unstable();
        self.all.dedup();
        let boxes: Vec<Aabb> = self
            .all
            .iter()
            .map(|&w| Aabb::from_points(&[positions[w as usize]]))
            .collect();
        self.tree = (!boxes.is_empty())
            .then(|| Bvh::build(&boxes).ok())
            .flatten();
    }

    /// The split points on the side `u → v` of a face of the result,
    /// in order from `u`: those recorded for it or the side it is a piece
    /// of ([`Self::between`]), and any other strictly between its ends
    /// within [`on_side_reach`] of its line.
    fn on_side(&self, positions: &[DVec3], u: u32, v: u32) -> Vec<u32> {
        let mut on = self.between(positions, u, v);
        let Some(tree) = &self.tree else {
            return on;
        };
        let (pu, pv) = (positions[u as usize], positions[v as usize]);
        let d = pv - pu;
        let length2 = d.length_squared();
        let size = pu.abs().max(pv.abs()).max_element();
        let margin = DVec3::splat(on_side_reach(length2.sqrt(), size) * 2.0);
        let reach = Aabb::from_points(&[pu, pv]);
        let reach = Aabb {
            min: reach.min - margin,
            max: reach.max + margin,
        };
        tree.for_each_overlap(&reach, |k| {
            let w = self.all[k as usize];
            if w != u && w != v && on_side_between(positions, u, v, w) {
                on.push(w);
            }
        });
        on.sort_by(|&a, &b| {
            let t = |w: u32| (positions[w as usize] - pu).dot(d);
            t(a).total_cmp(&t(b))
        });
        on.dedup();
        on
    }

    /// The points strictly between `u` and `v` that the side `u – v`, or
    /// the split side it is a piece of, was split at: in order from `u`.
    fn between(&self, positions: &[DVec3], u: u32, v: u32) -> Vec<u32> {
        let side = key(u, v);
        let mut on: Vec<u32> = if let Some(points) = self.points.get(&side) {
            points.clone()
        } else if let Some(&whole) = self.piece_of.get(&side) {
            let along = along(positions, whole);
            let (lo, hi) = (along(side.0), along(side.1));
            let (lo, hi) = (lo.min(hi), lo.max(hi));
            let mut on: Vec<u32> = self.points[&whole]
                .iter()
                .copied()
                .filter(|&w| along(w) > lo && along(w) < hi)
                .collect();
            if along(side.0) > along(side.1) {
                on.reverse();
            }
            on
        } else {
            return Vec::new();
        };
        if u > v {
            on.reverse();
        }
        on
    }
}

/// The parameter along the side `(a, b)` of a point: its projection on
/// `b − a` (unnormalized: only the order matters).
fn along(positions: &[DVec3], (a, b): (u32, u32)) -> impl Fn(u32) -> f64 + '_ {
    let (pa, d) = (
        positions[a as usize],
        positions[b as usize] - positions[a as usize],
    );
    move |w| (positions[w as usize] - pa).dot(d)
}

/// Replaces the groups of overlapping coplanar triangles of `faces` by
/// their overlays (module docs), appending the crossing points to
/// `positions`, and splits the triangles that share a side the overlays
/// split. A merge must not open the surface: every group at once when
/// that leaves no more sides on one triangle only than `faces` had; else
/// without the groups at the ends of the sides it left on one triangle
/// (a few rounds, and on while that closes it further), and the groups
/// so dropped one at a time after, each kept only if it opens nothing
/// more. (Trying every group one at a time costs a pass over the mesh
/// each: 1.6 s on the OpenSCAD export, against 0.7 s this way, with 121
/// of its 139 groups merged instead of 120, and the result closed.)
pub(crate) fn merge_overlaps(
    positions: &mut Vec<DVec3>,
    faces: Vec<[u32; 3]>,
) -> (Vec<[u32; 3]>, Merged) {
    let groups = overlap_groups(positions, &faces, false);
    if groups.is_empty() {
        return (faces, Merged::default());
    }
    let existing = position_index(positions);
    let overlays: Vec<(usize, Overlay)> =
        crate::coplanar::overlays(positions, &faces, &groups, &existing, Keep::Once)
            .into_iter()
            .enumerate()
            .filter_map(|(g, o)| o.map(|o| (g, o)))
            .collect();
    let positions_now: &[DVec3] = positions;
    // The faces with the overlays `taken` (indices into `overlays`) merged.
    let merge = |taken: &[usize]| -> Vec<[u32; 3]> {
        let mut gone = vec![false; faces.len()];
        let mut split = SplitSides::default();
        let mut added = Vec::new();
        let mut same: HashMap<u32, u32> = HashMap::default();
        for &k in taken {
            let (g, o) = &overlays[k];
            groups[*g].iter().for_each(|&i| gone[i] = true);
            added.extend_from_slice(&o.cells);
            for (side, on) in &o.sides {
                split.record(positions_now, *side, on);
            }
            same.extend(o.renamed.iter().copied());
        }
        let kept = faces
            .iter()
            .zip(&gone)
            .filter(|(_, g)| !**g)
            .map(|(f, _)| *f)
            .chain(added);
        split.finish(positions_now);
        let mut out = Vec::with_capacity(faces.len());
        for f in kept {
            split_along(positions_now, &split, f, &mut out);
        }
        if !same.is_empty() {
            // Corners an overlay took as another at the same point (a
            // chain of such ends at a vertex no overlay renamed).
            let named = |mut v: u32| {
                for _ in 0..same.len() {
                    match same.get(&v) {
                        Some(&w) if w != v => v = w,
                        _ => break,
                    }
                }
                v
            };
            out = out
                .into_iter()
                .map(|f| f.map(named))
                .filter(|f| !repeats_a_corner(f))
                .collect();
        }
        out
    };
    let before = lone_sides(&faces).len();
    // The overlays touching each vertex (their group's corners, their
    // cells' and their split sides' points): a lone side of a trial is
    // blamed on the overlays at its ends.
    let mut touching: HashMap<u32, Vec<usize>> = HashMap::default();
    for (k, (g, o)) in overlays.iter().enumerate() {
        let corners = groups[*g].iter().flat_map(|&i| faces[i]);
        let cells = o.cells.iter().flatten().copied();
        let points = o.sides.iter().flat_map(|(_, on)| on.iter().copied());
        for v in corners.chain(cells).chain(points) {
            let at = touching.entry(v).or_default();
            if at.last() != Some(&k) {
                at.push(k);
            }
        }
    }
    // Every overlay at once; while that opens the surface, without those
    // at the ends of its lone sides (a few rounds: each drops some), and
    // on while that closes it further.
    let blame = |lone: &[[u32; 2]]| -> rustc_hash::FxHashSet<usize> {
        lone.iter()
            .flat_map(|&[u, v]| [u, v])
            .flat_map(|v| touching.get(&v).into_iter().flatten().copied())
            .collect()
    };
    let mut taken: Vec<usize> = (0..overlays.len()).collect();
    let mut best: Option<(Vec<[u32; 3]>, Vec<usize>, usize)> = None;
    for _ in 0..6 {
        let trial = merge(&taken);
        let lone = lone_sides(&trial);
        let least = best
            .as_ref()
            .map_or(before, |(_, _, n)| n.saturating_sub(1));
        if lone.len() <= least {
            best = Some((trial, taken.clone(), lone.len()));
        } else if best.is_some() {
            break;
        }
        if lone.is_empty() {
            break;
        }
        let blamed = blame(&lone);
        let count = taken.len();
        taken.retain(|k| !blamed.contains(k));
        if taken.len() == count {
            break;
        }
    }
    let (mut best, mut taken, mut least) = best.unwrap_or((faces.clone(), Vec::new(), before));
    // The rest one at a time, each kept only if it opens nothing.
    let rest: Vec<usize> = (0..overlays.len()).filter(|k| !taken.contains(k)).collect();
    for k in rest {
        taken.push(k);
        let trial = merge(&taken);
        let lone = lone_sides(&trial).len();
        if lone <= least {
            (best, least) = (trial, lone);
        } else {
            taken.pop();
        }
    }
    let (out, taken) = (best, taken.len());
    let merged = Merged {
        groups: taken,
        left: groups.len() - taken,
    };
    (out, merged)
}

/// The faces with the cut's points taken as input corners or as each
/// other where they are one to rounding ([`welded_classes`]; the input's
/// own vertices are left as they are), without those whose corners then
/// repeat (the slivers between such points), and how many points were so
/// taken: the coplanar groups through a cluster of such points cannot be
/// overlaid without opening the surface (their slivers fold in the
/// plane's projection).
pub(crate) fn weld_constructed(
    positions: &[DVec3],
    faces: Vec<[u32; 3]>,
    origin: &[u32],
) -> Result<(Vec<[u32; 3]>, usize), holey_geom::GeomError> {
    // Only the cut's points move: the input's coincident vertices stay
    // apart, as `resolve` found them (the overlay renames those it needs
    // as one).
    let to: Vec<u32> = welded_classes(positions, origin)?
        .into_iter()
        .enumerate()
        .map(|(v, class)| {
            if origin.get(v) == Some(&u32::MAX) {
                class
            } else {
                v as u32
            }
        })
        .collect();
    let welded = to
        .iter()
        .enumerate()
        .filter(|&(i, &t)| i != t as usize)
        .count();
    if welded == 0 {
        return Ok((faces, 0));
    }
    let faces = faces
        .into_iter()
        .map(|f| f.map(|v| to[v as usize]))
        .filter(|f| !repeats_a_corner(f))
        .collect();
    Ok((faces, welded))
}

/// The sides that only one triangle of `faces` has (the surface's
/// boundary, whatever the orientations), by their ends.
fn lone_sides(faces: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let edges = Edges::of_triangles(faces);
    (0..edges.len())
        .filter(|&e| edges.triangles(e).len() == 1)
        .map(|e| edges.ends[e])
        .collect()
}

/// Pushes `f` onto `out`, split at the points on its sides
/// ([`SplitSides::on_side`]): fanned from the corner opposite a split
/// side, and the two pieces that keep its other sides fanned likewise.
/// The points are found for `f`'s own sides only, never for the sides a
/// fan adds (which run inside `f`): that ends, and nearly collinear
/// slivers cannot split one another in turn. A side whose opposite
/// corner lies on its line, to rounding, is not split (the fan would
/// fold).
fn split_along(positions: &[DVec3], split: &SplitSides, f: [u32; 3], out: &mut Vec<[u32; 3]>) {
    let on: [Vec<u32>; 3] = std::array::from_fn(|k| {
        let (u, v, x) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
        if near_line(positions, u, v, x) {
            Vec::new()
        } else {
            split.on_side(positions, u, v)
        }
    });
    let mut stack = vec![(f, on)];
    while let Some((f, mut on)) = stack.pop() {
        let Some(k) = (0..3).find(|&k| !on[k].is_empty()) else {
            out.push(f);
            continue;
        };
        let (u, v, x) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
        let mut along = vec![u];
        along.append(&mut on[k]);
        along.push(v);
        let last = along.len() - 2;
        let mut after = std::mem::take(&mut on[(k + 1) % 3]);
        let mut before = std::mem::take(&mut on[(k + 2) % 3]);
        for (i, w) in along.windows(2).enumerate() {
            // [w₀, w₁, x]: its side w₁ → x is f's v → x in the last
            // piece, and x → w₀ is f's x → u in the first.
            let to_x = if i == last {
                std::mem::take(&mut after)
            } else {
                Vec::new()
            };
            let from_x = if i == 0 {
                std::mem::take(&mut before)
            } else {
                Vec::new()
            };
            stack.push(([w[0], w[1], x], [Vec::new(), to_x, from_x]));
        }
    }
}

/// The pairs of triangles of `mesh` that lie in one plane and overlap
/// there (exactly: coplanar by `orient3d`, interiors meeting by
/// `orient2d`), facing either way: the overlaps the perturbed world of
/// [`crate::self_intersections`] does not count as crossings.
pub fn coplanar_overlaps(mesh: &TriMesh) -> usize {
    let mut pairs = 0;
    for_each_overlapping_pair(&mesh.positions, &mesh.triangles, |_, _, _| pairs += 1);
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square's corners and points of a cut beside them, the
    /// bound being 8 ulps of the largest coordinate (1): one 1e-15 from a
    /// corner (taken as it), two at one position (one point), one 3e-15
    /// from a corner and one 1e-9 from a point (both kept). A corner an
    /// ulp from another stays: the input is never moved. The faces whose
    /// corners then repeat go.
    #[test]
    fn cut_points_within_rounding_of_a_corner_or_at_one_position_are_welded() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            // Constructed: 1e-15 from corner 0, within 8·2⁻⁵² ≈ 1.8e-15.
            DVec3::new(1e-15, 0.0, 0.0),
            // Constructed: two at one position.
            DVec3::new(0.5, 0.5, 0.0),
            DVec3::new(0.5, 0.5, 0.0),
            // Constructed: 1e-9 from point 5.
            DVec3::new(0.5, 0.5 + 1e-9, 0.0),
            // A corner an ulp from corner 3.
            DVec3::new(0.0, 1.0 + f64::EPSILON, 0.0),
            // Constructed: 3e-15 from corner 0, beyond the bound.
            DVec3::new(0.0, 0.0, 3e-15),
        ];
        // The cut's mark for its own points, else the input vertex.
        const CUT: u32 = u32::MAX;
        let origin = [0, 1, 2, 3, CUT, CUT, CUT, CUT, 8, CUT];
        let faces = vec![
            [0, 1, 4],
            [5, 6, 2],
            [4, 1, 2],
            [3, 8, 7],
            [0, 6, 7],
            [9, 1, 2],
        ];
        let (welded_faces, welded) = weld_constructed(&positions, faces, &origin).expect("finite");
        assert_eq!(welded, 2);
        assert_eq!(
            welded_faces,
            vec![[0, 1, 2], [3, 8, 7], [0, 5, 7], [9, 1, 2]]
        );
    }

    #[test]
    fn nothing_within_rounding_leaves_the_faces_as_they_are() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.25, 0.25, 0.0)];
        let faces = vec![[0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let (same, welded) =
            weld_constructed(&positions, faces.clone(), &[0, 1, 2, u32::MAX]).expect("finite");
        assert_eq!((same, welded), (faces, 0));
    }
}
