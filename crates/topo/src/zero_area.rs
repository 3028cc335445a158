//! Zero-area triangles taken out of a surface without moving it.
//!
//! A triangle of zero area bounds nothing, yet the exact predicates see
//! it: under the symbolic perturbation of the Booleans, which tells
//! vertices apart by their numbers, it becomes a sliver that overlaps its
//! neighbours, and the Boolean finds the solid crossing itself there.
//! Snapping coordinates to a lattice makes such triangles (a Menger sponge
//! snapped to integers had 36), and so do CAD exporters that put a vertex
//! on an edge of the next face. They come in two kinds.
//!
//! **Pinched: two corners at one position** (two vertices the snap made
//! coincide). The two vertices are welded into one (the lower number),
//! and the triangles that then repeat a corner are deleted. The points do
//! not change. Every side keeps the parity of its number of triangles
//! (two sides that become one add their numbers; a deleted triangle
//! `(a, a, b)` takes `ab` away twice, once each way), so a closed surface
//! stays closed and a consistently oriented one stays so. The welded
//! vertex may become a pinch of the surface, which is what the snap made
//! of it.
//!
//! **Flat: three distinct corners on one line.** Let them be `a`, `m`, `b`
//! in their order along the line, so that the long side `ab` holds `m`.
//! The short sides `am` and `mb` lie on `ab`. The triangle `N = (x, y, c)`
//! across the long side (`{x, y} = {a, b}`) is split at `m` into
//! `(x, m, c)` and `(m, y, c)`, the same set of points since `m` lies on
//! its side, and the flat triangle is deleted. Every side keeps its number
//! of triangles (`am` and `mb` trade the flat triangle for a half of `N`;
//! `ab` loses both), so a closed 2-manifold stays one, with the same
//! orientation. On a boundary (no triangle across `ab`) the flat triangle
//! is only deleted: the rim runs along `am`, `mb` instead of `ab`, the
//! same points.
//!
//! Left alone: a flat triangle whose long side two or more other
//! triangles share (a non-manifold edge: which of them would take `m` is
//! not the surface's to say), and one whose neighbour is flat too until
//! that neighbour is resolved (a fan of them goes one by one).

use glam::DVec3;
use rayon::prelude::*;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use crate::audit::is_flat;
use crate::mesh::{MeshError, TriMesh, repeats_a_corner};
use crate::union_find::UnionFind;

/// The most passes over the mesh the flat repair makes: a fan of flat
/// triangles longer than this keeps the rest.
const MAX_ROUNDS: usize = 64;

/// What [`without_zero_area_triangles`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ZeroAreaRepair {
    /// Vertices welded into another at their position (pinched
    /// triangles' corners).
    pub welded_vertices: usize,
    /// Triangles deleted because the weld made them repeat a corner.
    pub pinched_removed: usize,
    /// Flat triangles deleted (and their neighbours split).
    pub flat_removed: usize,
    /// Flat triangles left: non-manifold long sides, or a fan of flat
    /// triangles with no way in.
    pub flat_kept: usize,
}

/// `mesh` with its zero-area triangles repaired as the module describes,
/// and what was done; `Ok(None)` when it has none of either kind (the
/// common case costs the mesh's check and one parallel pass). Vertices
/// keep their numbers (a welded vertex is left unused); the triangles
/// keep their order, split neighbours' second halves and the deletions
/// aside. Triangles that repeat a corner in `mesh` are left as they are.
/// An error says which position is not finite or which index is out of
/// range.
pub fn without_zero_area_triangles(
    mesh: &TriMesh,
) -> Result<Option<(TriMesh, ZeroAreaRepair)>, MeshError> {
    mesh.check()?;
    Ok(repaired(mesh))
}

/// [`without_zero_area_triangles`] of a checked mesh.
pub(crate) fn repaired(mesh: &TriMesh) -> Option<(TriMesh, ZeroAreaRepair)> {
    let positions = &mesh.positions;
    let proper = |t: &[u32; 3]| !repeats_a_corner(t);
    let zero: Vec<u32> = (0..mesh.triangles.len() as u32)
        .into_par_iter()
        .with_min_len(1 << 12)
        .filter(|&t| {
            let t = &mesh.triangles[t as usize];
            proper(t) && is_flat(t.map(|v| positions[v as usize]))
        })
        .collect();
    if zero.is_empty() {
        return None;
    }
    let mut repair = ZeroAreaRepair::default();
    let mut triangles = mesh.triangles.clone();
    let mut alive = vec![true; triangles.len()];
    // The pinched ones first: weld their coincident corners, then drop
    // what the weld made repeat a corner. Welding moves no point, so it
    // makes no triangle flat and unflattens none.
    let coincident: Vec<(u32, u32)> = zero
        .iter()
        .flat_map(|&t| {
            let c = triangles[t as usize];
            [(c[0], c[1]), (c[1], c[2]), (c[2], c[0])]
        })
        .filter(|&(u, v)| positions[u as usize] == positions[v as usize])
        .collect();
    if !coincident.is_empty() {
        let mut uf = UnionFind::new(positions.len());
        for &(u, v) in &coincident {
            uf.union(u, v);
        }
        // Each class goes to its lowest number.
        let mut lowest: HashMap<u32, u32> = HashMap::default();
        for &v in coincident.iter().flat_map(|(u, v)| [u, v]) {
            let low = lowest.entry(uf.find(v)).or_insert(v);
            *low = (*low).min(v);
        }
        let to: HashMap<u32, u32> = coincident
            .iter()
            .flat_map(|&(u, v)| [u, v])
            .map(|v| (v, lowest[&uf.find(v)]))
            .filter(|&(v, low)| v != low)
            .collect();
        repair.welded_vertices = to.len();
        for (t, live) in triangles.iter_mut().zip(&mut alive) {
            if t.iter().any(|v| to.contains_key(v)) {
                let was_proper = proper(t);
                *t = t.map(|v| to.get(&v).copied().unwrap_or(v));
                if was_proper && !proper(t) {
                    *live = false;
                    repair.pinched_removed += 1;
                }
            }
        }
    }
    // The flat ones: the zero-area triangles with three distinct corners.
    let flat: Vec<u32> = zero
        .into_iter()
        .filter(|&t| alive[t as usize] && along_line(positions, triangles[t as usize]).is_some())
        .collect();
    if !flat.is_empty() {
        repaired_flat(positions, &mut triangles, &mut alive, flat, &mut repair);
    }
    let triangles = triangles
        .into_iter()
        .zip(alive)
        .filter_map(|(t, alive)| alive.then_some(t))
        .collect();
    Some((
        TriMesh {
            positions: mesh.positions.clone(),
            triangles,
        },
        repair,
    ))
}

/// The corners of a flat triangle `t` in their order along its line,
/// `None` when two corners share a position. On a line `p + s·d` the
/// lexicographic order of the coordinates is the order of `s` (the first
/// nonzero component of `d` decides it), so sorting the corners by
/// `(x, y, z)` puts the middle one second, exactly.
fn along_line(positions: &[DVec3], t: [u32; 3]) -> Option<[u32; 3]> {
    let key = |v: u32| {
        let p = positions[v as usize];
        [p.x, p.y, p.z]
    };
    let mut c = t;
    c.sort_by(|&u, &v| {
        key(u)
            .partial_cmp(&key(v))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    (key(c[0]) != key(c[1]) && key(c[1]) != key(c[2])).then_some(c)
}

/// The flat triangles `pending` of `triangles` resolved as the module
/// describes: the neighbour across the long side split (its second half
/// appended), the flat one marked dead in `alive`.
fn repaired_flat(
    positions: &[DVec3],
    triangles: &mut Vec<[u32; 3]>,
    alive: &mut Vec<bool>,
    mut pending: Vec<u32>,
    repair: &mut ZeroAreaRepair,
) {
    let side = |a: u32, b: u32| (a.min(b), a.max(b));
    // Each round resolves every flat triangle whose neighbour is not
    // flat; a fan of them shrinks by one a round. A round that resolves
    // nothing ends it, and so does the last round there is time for (each
    // is a pass over the mesh).
    for round in 0.. {
        let lines: Vec<(u32, [u32; 3])> = pending
            .iter()
            .filter_map(|&t| Some((t, along_line(positions, triangles[t as usize])?)))
            .collect();
        let mut across: HashMap<(u32, u32), Vec<u32>> = lines
            .iter()
            .map(|&(_, [a, _, b])| (side(a, b), Vec::new()))
            .collect();
        for (i, t) in triangles.iter().enumerate() {
            if !alive[i] {
                continue;
            }
            for k in 0..3 {
                if let Some(list) = across.get_mut(&side(t[k], t[(k + 1) % 3])) {
                    list.push(i as u32);
                }
            }
        }
        let is_pending: HashSet<u32> = pending.iter().copied().collect();
        let mut touched = HashSet::default();
        let mut left = Vec::new();
        for (d, [a, m, b]) in lines {
            let others: Vec<u32> = across[&side(a, b)]
                .iter()
                .copied()
                .filter(|&n| n != d)
                .collect();
            match others[..] {
                [] => {
                    alive[d as usize] = false;
                    repair.flat_removed += 1;
                }
                [n] if !is_pending.contains(&n) && touched.insert(n) => {
                    let t = triangles[n as usize];
                    let Some(k) = (0..3).find(|&k| side(t[k], t[(k + 1) % 3]) == side(a, b)) else {
                        left.push(d);
                        continue;
                    };
                    let (x, y, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                    triangles[n as usize] = [x, m, c];
                    triangles.push([m, y, c]);
                    alive.push(true);
                    alive[d as usize] = false;
                    repair.flat_removed += 1;
                }
                _ => left.push(d),
            }
        }
        if left.is_empty() || left.len() == pending.len() || round + 1 == MAX_ROUNDS {
            repair.flat_kept = left.len();
            break;
        }
        pending = left;
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::audit::{SurfaceAudit, is_degenerate};
    use crate::solid::signed_volume;
    use crate::test_meshes::cuboid;
    use crate::union::{Operation, boolean};

    /// `mesh` with a new vertex `m` at `at`, a point of side `ab` of its
    /// triangle `t = (c, a, b)`, as a CAD exporter leaves a T-junction:
    /// `t` runs through `m` as `(c, a, m)` and `(c, m, b)`, the triangle
    /// across `ab` does not, and the flat triangle `(a, b, m)` closes the
    /// gap. Closed and oriented if `mesh` was.
    fn t_junction(mut mesh: TriMesh, t: [u32; 3], at: DVec3) -> TriMesh {
        let [c, a, b] = t;
        let m = mesh.positions.len() as u32;
        mesh.positions.push(at);
        let Some(i) = mesh.triangles.iter().position(|&u| u == t) else {
            panic!("no triangle {t:?}")
        };
        mesh.triangles[i] = [c, a, m];
        mesh.triangles.push([c, m, b]);
        mesh.triangles.push([a, b, m]);
        mesh
    }

    /// The unit cube with a T-junction at `m = (1/2, 0, 1)` = vertex 8 on
    /// its top front edge: the front face runs through it, the top face
    /// does not, and the flat triangle `(5, 4, 8)` closes the gap.
    fn cube_with_a_flat_triangle() -> TriMesh {
        t_junction(
            cuboid(DVec3::ZERO, DVec3::ONE),
            [0, 5, 4],
            DVec3::new(0.5, 0.0, 1.0),
        )
    }

    /// `mesh` with vertex `u` cut in two along its side `uw`, as a snap
    /// that made two vertices coincide leaves it: the triangle with the
    /// directed side `w → u` takes a copy `u'` of `u` (the same position),
    /// and two pinched triangles, `(w, u, u')` and `(q, u', u)` (`q` that
    /// triangle's third corner), close the surface again.
    fn pinched(mut mesh: TriMesh, u: u32, w: u32) -> TriMesh {
        let u2 = mesh.positions.len() as u32;
        mesh.positions.push(mesh.positions[u as usize]);
        let t = (0..mesh.triangles.len())
            .find(|&t| {
                (0..3).any(|k| mesh.triangles[t][k] == w && mesh.triangles[t][(k + 1) % 3] == u)
            })
            .unwrap();
        let q = *mesh.triangles[t]
            .iter()
            .find(|&&v| v != u && v != w)
            .unwrap();
        for v in &mut mesh.triangles[t] {
            if *v == u {
                *v = u2;
            }
        }
        mesh.triangles.push([w, u, u2]);
        mesh.triangles.push([q, u2, u]);
        mesh
    }

    fn zero_area_count(mesh: &TriMesh) -> usize {
        mesh.triangles
            .iter()
            .filter(|&&t| is_degenerate(mesh, t))
            .count()
    }

    /// The repair's promise: the same points (the volume, exactly, of
    /// coordinates that are halves), closed and oriented as before, and
    /// no zero-area triangle left.
    fn assert_same_solid(before: &TriMesh, after: &TriMesh) {
        assert!(after.is_closed_manifold(), "{:?}", after.triangles);
        assert_eq!(
            signed_volume(&after.positions, &after.triangles),
            signed_volume(&before.positions, &before.triangles)
        );
        assert_eq!(zero_area_count(after), 0);
        let audit = SurfaceAudit::of(after).unwrap();
        assert_eq!(audit.intersecting_pairs, 0);
        assert_eq!(audit.euler(), 2);
    }

    #[test]
    fn a_flat_triangle_at_a_t_junction_goes_and_its_neighbour_takes_the_vertex() {
        let cube = cube_with_a_flat_triangle();
        assert_eq!(zero_area_count(&cube), 1);
        assert!(cube.is_closed_manifold());
        let (out, repair) = without_zero_area_triangles(&cube).unwrap().unwrap();
        assert_eq!(
            repair,
            ZeroAreaRepair {
                flat_removed: 1,
                ..ZeroAreaRepair::default()
            }
        );
        // The top face's triangle (4, 5, 6) across the long side, split
        // at m = 8, in its own orientation.
        assert!(out.triangles.contains(&[4, 8, 6]));
        assert!(out.triangles.contains(&[8, 5, 6]));
        assert_eq!(out.triangles.len(), cube.triangles.len());
        assert_same_solid(&cube, &out);
    }

    #[test]
    fn a_fan_of_flat_triangles_goes_one_by_one() {
        // Two points on the top front edge: m = (1/4, 0, 1) and the cube's
        // 8 at (1/2, 0, 1). The front face runs through both; the flat
        // triangles (5, 4, 8) and (8, 4, m) close the gap, the second
        // across the first's short side 4–8.
        let cube = t_junction(
            cube_with_a_flat_triangle(),
            [0, 8, 4],
            DVec3::new(0.25, 0.0, 1.0),
        );
        assert!(cube.is_closed_manifold());
        assert_eq!(zero_area_count(&cube), 2);
        let (out, repair) = without_zero_area_triangles(&cube).unwrap().unwrap();
        assert_eq!((repair.flat_removed, repair.flat_kept), (2, 0));
        assert_same_solid(&cube, &out);
    }

    #[test]
    fn a_pinch_is_welded_and_its_triangles_go() {
        let cube = cuboid(DVec3::ZERO, DVec3::ONE);
        let t = cube.triangles[0];
        let snapped = pinched(cube.clone(), t[0], t[1]);
        assert!(snapped.is_closed_manifold());
        assert_eq!(zero_area_count(&snapped), 2);
        let (out, repair) = without_zero_area_triangles(&snapped).unwrap().unwrap();
        assert_eq!(
            repair,
            ZeroAreaRepair {
                welded_vertices: 1,
                pinched_removed: 2,
                ..ZeroAreaRepair::default()
            }
        );
        // The weld gives back the cube, triangle for triangle.
        assert_eq!(out.triangles, cube.triangles);
        assert_same_solid(&cube, &out);
    }

    #[test]
    fn a_surface_without_zero_area_triangles_is_not_copied() {
        assert_eq!(
            without_zero_area_triangles(&cuboid(DVec3::ZERO, DVec3::ONE)),
            Ok(None)
        );
        // A triangle that repeats a corner is the input's own, not a
        // pinch: left for the Boolean to say what it makes of it.
        let mut repeated = cuboid(DVec3::ZERO, DVec3::ONE);
        repeated.triangles.push([0, 0, 1]);
        assert_eq!(without_zero_area_triangles(&repeated), Ok(None));
        // Bad input is an error, not a panic.
        repeated.triangles.push([0, 1, 99]);
        assert!(matches!(
            without_zero_area_triangles(&repeated),
            Err(MeshError::IndexOutOfRange { index: 99, .. })
        ));
        let mut bad = cuboid(DVec3::ZERO, DVec3::ONE);
        bad.positions[3].x = f64::NAN;
        assert!(without_zero_area_triangles(&bad).is_err());
    }

    /// A snapped solid (a T-junction's flat triangle and a pinch at its
    /// middle vertex) where a box crosses it: the solid's zero-area
    /// triangles meet the box. Under the symbolic perturbation they were
    /// slivers crossing their neighbours, and the Boolean refused the
    /// solid as crossing itself there (the snapped Menger sponge's
    /// intersections and differences). Repaired, every operation gives a
    /// closed 2-manifold without crossings and the closed-form volume.
    #[test]
    fn booleans_take_a_snapped_solid_whose_zero_area_triangles_meet_the_other() {
        let snapped = pinched(cube_with_a_flat_triangle(), 8, 0);
        assert!(snapped.is_closed_manifold());
        assert_eq!(zero_area_count(&snapped), 3);
        let b = cuboid(DVec3::new(0.25, -0.5, 0.5), DVec3::new(0.75, 0.5, 1.5));
        let inside = 0.5 * 0.5 * 0.5;
        for (op, want) in [
            (Operation::Union, 1.0 + 0.5 - inside),
            (Operation::Intersection, inside),
            (Operation::Difference, 1.0 - inside),
        ] {
            let out = boolean(&snapped, &b, op, &crate::Options::default())
                .unwrap_or_else(|e| panic!("{}: {e}", op.name()));
            // The flat triangle and the two pinched ones.
            assert_eq!(out.report.zero_area_removed, 3, "{}", op.name());
            let m = &out.mesh;
            assert!(m.is_closed_manifold(), "{}", op.name());
            let got = signed_volume(&m.positions, &m.triangles);
            assert!(
                (got - want).abs() < 1e-12,
                "{}: {got}, want {want}",
                op.name()
            );
            let audit = SurfaceAudit::of(m).unwrap();
            assert_eq!(audit.intersecting_pairs, 0, "{}", op.name());
            assert_eq!(audit.components, 1, "{}", op.name());
        }
    }
}
