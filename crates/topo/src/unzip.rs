//! A closed result made a 2-manifold where the solid touches itself.
//!
//! The boundary of a solid need not be a manifold: two parts of it can
//! meet along an edge (four faces around it, two cubes of a lattice
//! touching diagonally) or at a vertex (two fans). A Boolean of solids
//! on a lattice makes such contacts exactly, and the winding-number
//! arrangement finds them with their exact coordinates. The surface is
//! made a 2-manifold without moving a point:
//!
//! - around an edge of `2k` faces, sorted by their angle about it with
//!   exact predicates, forward and backward faces alternate (the solid's
//!   inside and outside alternate between them); each face is paired
//!   with its neighbour across the wedge of inside, so that each part of
//!   the solid keeps its own two faces there;
//! - every vertex is split into one vertex per fan, the fans now joined
//!   across manifold edges and paired faces only, each copy at the same
//!   position.
//!
//! An edge whose faces do not alternate, or two of whose faces lie at one
//! angle (a wall of no thickness, or a face with no area), is left as it
//! is and joins all its faces: a defect the caller counts, not a contact
//! to separate.

use glam::DVec3;
use holey_geom::{Sign, orient2d, orient3d};
use rustc_hash::FxHashMap as HashMap;

use crate::intersect::COORDINATE_PLANES;
use crate::mesh::Edges;
use crate::union_find::UnionFind;

/// What [`unzip`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Unzipped {
    /// Edges of more than two faces whose faces were paired.
    pub edges: usize,
    /// Vertices added: one per fan of a vertex after its first.
    pub vertices: usize,
    /// Points added on unzipped edges whose parts stay joined at both
    /// ends.
    pub points: usize,
}

/// Makes `faces` a 2-manifold where the surface touches itself (module
/// docs): pairs the faces around each edge of more than two, then splits
/// every vertex into its fans, appending the copies to `positions`. A
/// pair of faces whose edge still has both ends in common with another
/// pair's (the parts that meet along it are joined at both its ends, as
/// where diagonal contacts of lattice cubes run side by side) is split
/// at a point of the edge's segment, exactly on it.
pub(crate) fn unzip(positions: &mut Vec<DVec3>, faces: &mut Vec<[u32; 3]>) -> Unzipped {
    let edges = Edges::of_triangles(faces);
    let corner = |faces: &[[u32; 3]], t: u32, v: u32| -> u32 {
        let k = faces[t as usize].iter().position(|&w| w == v).unwrap_or(0);
        3 * t + k as u32
    };
    let mut fans = UnionFind::new(3 * faces.len());
    // The corners at the two ends of each pair of an unzipped edge.
    let mut paired: Vec<Vec<[u32; 4]>> = Vec::new();
    for (e, &[a, b]) in edges.ends.iter().enumerate() {
        let around = edges.triangles(e);
        if a == b || around.len() < 2 {
            continue;
        }
        let mut join = |t: u32, u: u32| {
            for v in [a, b] {
                fans.union(corner(faces, t, v), corner(faces, u, v));
            }
        };
        if let [t, u] = *around {
            join(t, u);
            continue;
        }
        match pair_around(positions, faces, a, b, around) {
            Some(pairs) => {
                paired.push(
                    pairs
                        .iter()
                        .map(|&(t, u)| {
                            [
                                corner(faces, t, a),
                                corner(faces, t, b),
                                corner(faces, u, a),
                                corner(faces, u, b),
                            ]
                        })
                        .collect(),
                );
                pairs.into_iter().for_each(|(t, u)| join(t, u));
            }
            // Not a contact to separate: all its faces stay one fan.
            None => around.windows(2).for_each(|w| join(w[0], w[1])),
        }
    }
    let before = positions.len();
    split_fans(positions, faces, &mut fans);
    let vertices = positions.len() - before;
    let mut split = vec![false; faces.len()];
    for pairs in &paired {
        split_shared_ends(positions, faces, pairs, &mut split);
    }
    Unzipped {
        edges: paired.len(),
        vertices,
        points: positions.len() - before - vertices,
    }
}

/// Gives every fan of a vertex but the one holding its first corner a
/// copy of the vertex (`fans` joins corners, `3·t + k`).
fn split_fans(positions: &mut Vec<DVec3>, faces: &mut [[u32; 3]], fans: &mut UnionFind) {
    let mut kept_fan = vec![u32::MAX; positions.len()];
    let mut copy_of_fan: HashMap<u32, u32> = HashMap::default();
    for (t, face) in faces.iter_mut().enumerate() {
        for (k, corner) in face.iter_mut().enumerate() {
            let v = *corner as usize;
            let fan = fans.find((3 * t + k) as u32);
            if kept_fan[v] == u32::MAX {
                kept_fan[v] = fan;
            } else if kept_fan[v] != fan {
                *corner = *copy_of_fan.entry(fan).or_insert_with(|| {
                    positions.push(positions[v]);
                    (positions.len() - 1) as u32
                });
            }
        }
    }
}

/// Splits both faces of every pair of an unzipped edge (`pairs`: each
/// pair's corners at the edge's ends) whose ends, after [`split_fans`],
/// are another pair's too, at one point of the edge, a copy of it for
/// each pair: the faces `(a, b, x)` and `(b, a, y)` become `(a, m, x)`,
/// `(m, b, x)`, `(b, m, y)` and `(m, a, y)`, a disk about `m`. The
/// copies are one point, as the vertices split into fans are. Left as
/// they are when no point tried lies exactly on the segment.
fn split_shared_ends(
    positions: &mut Vec<DVec3>,
    faces: &mut Vec<[u32; 3]>,
    pairs: &[[u32; 4]],
    split: &mut [bool],
) {
    let at = |faces: &[[u32; 3]], c: u32| faces[c as usize / 3][c as usize % 3];
    // A face split for another edge no longer has these corners.
    let pairs: Vec<&[u32; 4]> = pairs
        .iter()
        .filter(|ends| !ends.iter().any(|&c| split[c as usize / 3]))
        .collect();
    let key = |faces: &[[u32; 3]], ends: &[u32; 4]| [at(faces, ends[0]), at(faces, ends[1])];
    let shared: Vec<&[u32; 4]> = pairs
        .iter()
        .filter(|&&e| {
            pairs
                .iter()
                .filter(|&&o| key(faces, o) == key(faces, e))
                .count()
                > 1
        })
        .copied()
        .collect();
    let Some(first) = shared.first() else {
        return;
    };
    let [a, b] = key(faces, first);
    let Some(point) = point_on_segment(positions[a as usize], positions[b as usize]) else {
        return;
    };
    for ends in shared {
        positions.push(point);
        let m = (positions.len() - 1) as u32;
        for (ca, cb) in [(ends[0], ends[1]), (ends[2], ends[3])] {
            let t = ca as usize / 3;
            let mut half = faces[t];
            half[ca as usize % 3] = m;
            faces[t][cb as usize % 3] = m;
            faces.push(half);
            split[t] = true;
        }
    }
}

/// A point strictly inside the segment `a`–`b` and exactly on its line
/// (collinear in every coordinate plane, by exact `orient2d`): its
/// midpoint, or a point a quarter or three quarters along, whichever is
/// first found so after rounding.
fn point_on_segment(a: DVec3, b: DVec3) -> Option<DVec3> {
    [0.5, 0.25, 0.75, 0.375, 0.625]
        .iter()
        .map(|&t| a + (b - a) * t)
        .find(|&m| {
            m != a
                && m != b
                && m.cmpge(a.min(b)).all()
                && m.cmple(a.max(b)).all()
                && COORDINATE_PLANES
                    .iter()
                    .all(|proj| orient2d(proj(a), proj(b), proj(m)) == Sign::Zero)
        })
}

/// Where a face's third corner lies about the edge `a → b`, by its
/// angle θ from the first face's, turning right-handedly about `b − a`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Half {
    /// θ = 0: the first face's own half-plane.
    Start,
    /// 0 < θ < π.
    Ahead,
    /// θ = π.
    Opposite,
    /// π < θ < 2π.
    Behind,
}

/// The faces `around` the edge `a → b` (`a < b`, more than two faces)
/// paired across the wedges of inside (module docs), or `None` when two
/// lie at one angle, a corner lies on the edge's line, or forward and
/// backward faces do not alternate.
fn pair_around(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    a: u32,
    b: u32,
    around: &[u32],
) -> Option<Vec<(u32, u32)>> {
    let p = |v: u32| positions[v as usize];
    let (pa, pb) = (p(a), p(b));
    // Each face: (third corner, runs a → b).
    let sides: Vec<(DVec3, bool)> = around
        .iter()
        .map(|&t| {
            let f = faces[t as usize];
            let k = f.iter().position(|&v| v == a)?;
            let third = f.iter().copied().find(|&v| v != a && v != b)?;
            Some((p(third), f[(k + 1) % 3] == b))
        })
        .collect::<Option<_>>()?;
    // det[b − a; x − a; y − a] > 0: y lies ahead of x, less than π on.
    let turn = |x: DVec3, y: DVec3| orient3d(pb, x, y, pa);
    let start = sides[0].0;
    // A coordinate plane where the first face does not project to a line:
    // there, a corner in its plane lies on its side of the edge (θ = 0) or
    // on the other (θ = π).
    let plane = COORDINATE_PLANES
        .iter()
        .find(|proj| orient2d(proj(pa), proj(pb), proj(start)) != Sign::Zero)?;
    let start_side = orient2d(plane(pa), plane(pb), plane(start));
    let halves: Vec<Half> = sides
        .iter()
        .enumerate()
        .map(|(i, &(x, _))| {
            if i == 0 {
                return Some(Half::Start);
            }
            match turn(start, x) {
                Sign::Positive => Some(Half::Ahead),
                Sign::Negative => Some(Half::Behind),
                Sign::Zero => match orient2d(plane(pa), plane(pb), plane(x)) {
                    Sign::Zero => None,
                    s if s == start_side => Some(Half::Start),
                    _ => Some(Half::Opposite),
                },
            }
        })
        .collect::<Option<_>>()?;
    let mut order: Vec<usize> = (0..sides.len()).collect();
    let mut tied = false;
    order.sort_by(|&i, &j| {
        halves[i].cmp(&halves[j]).then_with(|| {
            if i == j {
                return std::cmp::Ordering::Equal;
            }
            match turn(sides[i].0, sides[j].0) {
                Sign::Positive => std::cmp::Ordering::Less,
                Sign::Negative => std::cmp::Ordering::Greater,
                Sign::Zero => {
                    tied = true;
                    std::cmp::Ordering::Equal
                }
            }
        })
    });
    let repeated = |h: Half| halves.iter().filter(|&&x| x == h).count() > 1;
    if tied || [Half::Start, Half::Opposite].iter().any(|&h| repeated(h)) {
        return None;
    }
    let n = order.len();
    if n % 2 == 1 || (0..n).any(|i| sides[order[i]].1 == sides[order[(i + 1) % n]].1) {
        return None;
    }
    // A forward face's outward normal, (b − a) × (x − a), points ahead:
    // the wedge after a backward face is inside.
    Some(
        (0..n)
            .filter(|&i| !sides[order[i]].1)
            .map(|i| (around[order[i]], around[order[(i + 1) % n]]))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriMesh;

    /// The closed surface of unit lattice cubes, as testkit builds it.
    fn cubes(cells: &[[i32; 3]]) -> TriMesh {
        let (positions, triangles) = holey_testkit::lattice_cubes(cells);
        TriMesh {
            positions: positions.into_iter().map(DVec3::from).collect(),
            triangles,
        }
    }

    /// `cells` as lattice cubes, unzipped: checks what [`unzip`] did
    /// against `want`, that the result is a closed 2-manifold without
    /// pinches, and that no point moved (the volume is the same).
    fn unzipped_as(cells: &[[i32; 3]], want: Unzipped) -> TriMesh {
        let mut m = cubes(cells);
        let volume = crate::solid::signed_volume(&m.positions, &m.triangles);
        assert_eq!(unzip(&mut m.positions, &mut m.triangles), want);
        assert!(m.is_closed_manifold());
        assert!(m.pinched_vertices().iter().all(|&p| !p));
        assert_eq!(
            crate::solid::signed_volume(&m.positions, &m.triangles),
            volume
        );
        assert_eq!(volume, cells.len() as f64);
        m
    }

    fn nonmanifold_edges(faces: &[[u32; 3]]) -> usize {
        let edges = Edges::of_triangles(faces);
        (0..edges.len())
            .filter(|&e| edges.triangles(e).len() > 2)
            .count()
    }

    #[test]
    fn two_cubes_meeting_along_an_edge_come_apart_there() {
        assert_eq!(
            nonmanifold_edges(&cubes(&[[0, 0, 0], [1, 1, 0]]).triangles),
            1
        );
        let want = Unzipped {
            edges: 1,
            vertices: 2,
            points: 0,
        };
        let m = unzipped_as(&[[0, 0, 0], [1, 1, 0]], want);
        // Two cubes again, each closed on its own.
        assert_eq!(crate::hidden::vertex_components(&m).iter().max(), Some(&1));
    }

    #[test]
    fn two_cubes_meeting_at_a_corner_get_a_vertex_each() {
        let before = cubes(&[[0, 0, 0], [1, 1, 1]]);
        assert_eq!(nonmanifold_edges(&before.triangles), 0);
        assert_eq!(before.pinched_vertices().iter().filter(|&&p| p).count(), 1);
        let want = Unzipped {
            edges: 0,
            vertices: 1,
            points: 0,
        };
        let m = unzipped_as(&[[0, 0, 0], [1, 1, 1]], want);
        assert_eq!(crate::hidden::vertex_components(&m).iter().max(), Some(&1));
    }

    #[test]
    fn an_edge_contact_joined_at_both_ends_is_split_at_its_midpoint() {
        // Two cubes meeting along the edge x = y = 1, 0 ≤ z ≤ 1, and an
        // L of three cubes below and another above, each joining them:
        // neither end of the edge comes apart into fans.
        let mut cells = vec![[0, 0, 0], [1, 1, 0]];
        for z in [-1, 1] {
            cells.extend([[0, 0, z], [1, 0, z], [1, 1, z]]);
        }
        assert_eq!(nonmanifold_edges(&cubes(&cells).triangles), 1);
        let want = Unzipped {
            edges: 1,
            vertices: 0,
            points: 2,
        };
        let m = unzipped_as(&cells, want);
        let mid = DVec3::new(1.0, 1.0, 0.5);
        assert_eq!(m.positions[m.positions.len() - 2..], [mid, mid]);
    }

    #[test]
    fn a_point_on_a_segment_is_exactly_on_it_or_not_offered() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(0.7, 1.9, -2.3);
        if let Some(m) = point_on_segment(a, b) {
            for proj in COORDINATE_PLANES {
                assert_eq!(orient2d(proj(a), proj(b), proj(m)), Sign::Zero);
            }
        }
        let (a, b) = (DVec3::new(3.0, 1.0, 1.0), DVec3::new(3.0, 1.0, 2.0));
        assert_eq!(point_on_segment(a, b), Some(DVec3::new(3.0, 1.0, 1.5)));
        assert_eq!(point_on_segment(a, a), None);
    }

    #[test]
    fn a_manifold_surface_is_left_alone() {
        let mut m = cubes(&[[0, 0, 0], [1, 0, 0], [1, 1, 0]]);
        let before = m.clone();
        assert_eq!(
            unzip(&mut m.positions, &mut m.triangles),
            Unzipped::default()
        );
        assert_eq!(m.positions, before.positions);
        assert_eq!(m.triangles, before.triangles);
    }

    #[test]
    fn a_wall_of_no_thickness_is_not_taken_for_a_contact() {
        // A cube with a second copy of its top face pair, facing down and
        // up again: three faces at one angle about the top edges.
        let mut m = cubes(&[[0, 0, 0]]);
        let top: Vec<[u32; 3]> = m
            .triangles
            .iter()
            .filter(|t| t.iter().all(|&v| m.positions[v as usize].z == 1.0))
            .copied()
            .collect();
        for t in &top {
            m.triangles.push([t[0], t[2], t[1]]);
            m.triangles.push(*t);
        }
        let bad = nonmanifold_edges(&m.triangles);
        assert!(bad > 0);
        let done = unzip(&mut m.positions, &mut m.triangles);
        assert_eq!(done.edges, 0);
        assert_eq!(nonmanifold_edges(&m.triangles), bad);
    }

    #[test]
    fn the_pairing_follows_the_inside_whichever_way_the_edge_runs() {
        // The same two cubes meeting along an edge, in each of the three
        // axes' directions and mirrored: always two closed cubes.
        for axis in 0..3 {
            for flip in [false, true] {
                let mut cells = [[0, 0, 0], [1, 1, 1]];
                cells[1][axis] = 0;
                if flip {
                    cells[1] = cells[1].map(|c| -c);
                }
                let mut m = cubes(&cells);
                let done = unzip(&mut m.positions, &mut m.triangles);
                assert_eq!(done.edges, 1, "axis {axis} flip {flip}");
                assert!(m.is_closed_manifold(), "axis {axis} flip {flip}");
                let parts = crate::hidden::vertex_components(&m);
                assert_eq!(parts.iter().max(), Some(&1), "axis {axis} flip {flip}");
            }
        }
    }
}
