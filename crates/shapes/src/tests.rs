//! Tests for every primitive: counts, manifoldness, orientation, welding,
//! geometry, documented order, and spec parsing. The mesh checks are
//! written here on purpose, independent of holey-mesh's analysis.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;

use holey_mesh::{DVec3, PolyMesh};
use holey_testkit::Rng;

use crate::round::turn;
use crate::*;

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// Counts found by [`check`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Topology {
    v: usize,
    e: usize,
    f: usize,
    boundary_edges: usize,
    boundary_loops: usize,
}

impl Topology {
    fn euler(&self) -> i64 {
        self.v as i64 - self.e as i64 + self.f as i64
    }

    /// Genus of the orientable surface: χ = 2 − 2g − b.
    fn genus(&self) -> i64 {
        let g2 = 2 - self.euler() - self.boundary_loops as i64;
        assert_eq!(g2 % 2, 0, "odd 2g = {g2}");
        g2 / 2
    }
}

/// Checks everything every primitive promises and returns its counts:
/// valid indices, faces of at least three distinct corners and non-zero
/// area, each directed edge at most once (consistent orientation, at most
/// two faces per edge), boundary edges forming simple loops, one fan of
/// faces per vertex, every vertex used, and no two vertices at the same
/// position.
fn check(m: &PolyMesh) -> Topology {
    m.check().expect("offsets, indices and positions valid");
    let nv = m.positions.len();
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    // Per vertex, the (next, previous) corner of each face around it.
    let mut fans: Vec<Vec<(u32, u32)>> = vec![Vec::new(); nv];
    for (f, face) in m.faces().enumerate() {
        let n = face.len();
        assert!(n >= 3, "face {f} has {n} corners");
        let distinct: HashSet<u32> = face.iter().copied().collect();
        assert_eq!(distinct.len(), n, "face {f} repeats a vertex: {face:?}");
        let area = newell(m, face).length() / 2.0;
        assert!(area > 1e-12, "face {f} is degenerate (area {area})");
        for k in 0..n {
            let (prev, v, next) = (face[(k + n - 1) % n], face[k], face[(k + 1) % n]);
            *directed.entry((v, next)).or_default() += 1;
            fans[v as usize].push((next, prev));
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(count, 1, "directed edge {a}->{b} appears {count} times");
    }
    let boundary: Vec<(u32, u32)> = directed
        .keys()
        .filter(|&&(a, b)| !directed.contains_key(&(b, a)))
        .copied()
        .collect();
    let interior = directed.len() - boundary.len();
    assert_eq!(interior % 2, 0);
    let e = interior / 2 + boundary.len();

    let mut next_on_boundary: HashMap<u32, u32> = HashMap::new();
    for &(a, b) in &boundary {
        assert!(
            next_on_boundary.insert(a, b).is_none(),
            "vertex {a} starts two boundary edges"
        );
    }
    let mut seen = HashSet::new();
    let mut loops = 0;
    for &start in next_on_boundary.keys() {
        if seen.contains(&start) {
            continue;
        }
        loops += 1;
        let mut v = start;
        while seen.insert(v) {
            v = next_on_boundary[&v];
        }
        assert_eq!(v, start, "boundary walk from {start} does not close");
    }

    for (v, fan) in fans.iter().enumerate() {
        assert!(!fan.is_empty(), "vertex {v} is not used");
        check_fan(v, fan);
    }
    assert_no_duplicate_positions(&m.positions);
    Topology {
        v: nv,
        e,
        f: m.face_count(),
        boundary_edges: boundary.len(),
        boundary_loops: loops,
    }
}

/// The faces around a vertex, each given as (next, previous) neighbour,
/// must link into a single cycle (inner vertex) or a single chain
/// (boundary vertex): going around, a face's previous neighbour is the
/// next one of the following face.
fn check_fan(v: usize, fan: &[(u32, u32)]) {
    let step: HashMap<u32, u32> = fan.iter().copied().collect();
    assert_eq!(
        step.len(),
        fan.len(),
        "vertex {v}: two faces leave along the same edge"
    );
    let targets: HashSet<u32> = fan.iter().map(|c| c.1).collect();
    let starts: Vec<u32> = step
        .keys()
        .filter(|k| !targets.contains(k))
        .copied()
        .collect();
    assert!(starts.len() <= 1, "vertex {v} has {} fans", starts.len());
    let mut at = starts.first().copied().unwrap_or(fan[0].0);
    let first = at;
    let mut walked = 0;
    while let Some(&to) = step.get(&at) {
        walked += 1;
        at = to;
        if at == first || walked > fan.len() {
            break;
        }
    }
    assert_eq!(walked, fan.len(), "vertex {v} is not a single fan");
}

fn assert_no_duplicate_positions(positions: &[DVec3]) {
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&a, &b| positions[a].x.total_cmp(&positions[b].x));
    for (k, &a) in order.iter().enumerate() {
        for &b in &order[k + 1..] {
            if positions[b].x - positions[a].x > 1e-9 {
                break;
            }
            let d = positions[a].distance(positions[b]);
            assert!(
                d > 1e-9,
                "vertices {a} and {b} coincide at {:?}",
                positions[a]
            );
        }
    }
}

/// Newell's normal: twice the vector area of a polygon.
fn newell(m: &PolyMesh, face: &[u32]) -> DVec3 {
    let n = face.len();
    (0..n)
        .map(|k| m.positions[face[k] as usize].cross(m.positions[face[(k + 1) % n] as usize]))
        .sum()
}

/// Whether `v` points along the unit vector `dir`.
fn points(v: DVec3, dir: DVec3) -> bool {
    (v.normalize() - dir).length() < 1e-14
}

fn centre(m: &PolyMesh, face: &[u32]) -> DVec3 {
    face.iter().map(|&i| m.positions[i as usize]).sum::<DVec3>() / face.len() as f64
}

/// Signed volume enclosed (fan triangulation, divergence theorem).
fn volume(m: &PolyMesh) -> f64 {
    m.faces()
        .map(|face| {
            let p0 = m.positions[face[0] as usize];
            (1..face.len() - 1)
                .map(|k| {
                    p0.dot(m.positions[face[k] as usize].cross(m.positions[face[k + 1] as usize]))
                })
                .sum::<f64>()
        })
        .sum::<f64>()
        / 6.0
}

/// Largest distance of a corner from its face's plane.
fn max_non_planarity(m: &PolyMesh) -> f64 {
    m.faces()
        .map(|face| {
            let n = newell(m, face).normalize();
            let c = centre(m, face);
            face.iter()
                .map(|&i| (m.positions[i as usize] - c).dot(n).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn edge_lengths(m: &PolyMesh) -> Vec<f64> {
    m.faces()
        .flat_map(|face| (0..face.len()).map(move |k| (face[k], face[(k + 1) % face.len()])))
        .map(|(a, b)| m.positions[a as usize].distance(m.positions[b as usize]))
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Checks a closed primitive and its counts and genus.
fn closed(m: &PolyMesh, v: usize, e: usize, f: usize, genus: i64) -> Topology {
    let t = check(m);
    assert_eq!((t.v, t.e, t.f), (v, e, f), "V/E/F");
    assert_eq!(t.boundary_edges, 0, "closed");
    assert_eq!(t.genus(), genus);
    assert!(volume(m) > 0.0, "outward orientation");
    t
}

/// Checks a closed surface of six `n × n` grids of quads (a cube's or a
/// quad sphere's): `6n² + 2` vertices, `12n²` edges, `6n²` faces, genus 0.
fn closed_cube_surface(m: &PolyMesh, n: u32) {
    let nn = (n * n) as usize;
    closed(m, 6 * nn + 2, 12 * nn, 6 * nn, 0);
}

/// `(z, y, x)` order with ties up to rounding.
fn zyx_less(a: DVec3, b: DVec3) -> bool {
    let eps = 1e-9;
    for (p, q) in [(a.z, b.z), (a.y, b.y), (a.x, b.x)] {
        if p < q - eps {
            return true;
        }
        if p > q + eps {
            return false;
        }
    }
    false
}

/// The documented order of the platonic solids: vertices and face
/// centres strictly increasing by (z, y, x), faces starting at their
/// lowest vertex.
fn assert_solid_order(m: &PolyMesh) {
    for w in m.positions.windows(2) {
        assert!(zyx_less(w[0], w[1]), "vertices out of order: {w:?}");
    }
    let centres: Vec<DVec3> = m.faces().map(|f| centre(m, f)).collect();
    for (k, w) in centres.windows(2).enumerate() {
        assert!(zyx_less(w[0], w[1]), "faces {k}, {} out of order", k + 1);
    }
    for face in m.faces() {
        assert_eq!(
            Some(&face[0]),
            face.iter().min(),
            "face {face:?} does not start at its lowest vertex"
        );
    }
}

/// Equal edges, all vertices at distance √3, equal planar faces.
fn assert_regular(m: &PolyMesh, volume_expected: f64) {
    let lengths = edge_lengths(m);
    let l0 = lengths[0];
    assert!(lengths.iter().all(|&l| rel(l, l0) < 1e-12), "edges differ");
    for p in &m.positions {
        assert!(
            rel(p.length(), SQRT3) < 1e-14,
            "circumradius {}",
            p.length()
        );
    }
    assert!(max_non_planarity(m) < 1e-14);
    let areas: Vec<f64> = m.faces().map(|f| newell(m, f).length()).collect();
    assert!(
        areas.iter().all(|&a| rel(a, areas[0]) < 1e-12),
        "faces differ"
    );
    assert!(
        rel(volume(m), volume_expected) < 1e-13,
        "volume {} vs {volume_expected}",
        volume(m)
    );
    assert_solid_order(m);
}

// ---------------------------------------------------------------------
// Platonic solids.

#[test]
fn tetrahedron_is_regular_and_ordered() {
    let m = tetrahedron();
    closed(&m, 4, 6, 4, 0);
    assert_regular(&m, 8.0 / 3.0);
    assert!(
        edge_lengths(&m)
            .iter()
            .all(|&l| rel(l, 2.0 * 2f64.sqrt()) < 1e-15)
    );
    for (f, face) in m.faces().enumerate() {
        assert!(
            !face.contains(&(3 - f as u32)),
            "face {f} is opposite vertex {}",
            3 - f
        );
    }
    // Corners are alternate cube corners.
    for p in &m.positions {
        assert_eq!(p.abs(), DVec3::ONE);
        assert_eq!(p.x * p.y * p.z, 1.0);
    }
}

#[test]
fn cube_is_regular_and_ordered() {
    let m = cube(1).unwrap();
    closed(&m, 8, 12, 6, 0);
    assert_regular(&m, 8.0);
    assert_eq!(volume(&m), 8.0);
    for (i, p) in m.positions.iter().enumerate() {
        let bit = |k: usize| if i >> k & 1 == 1 { 1.0 } else { -1.0 };
        assert_eq!(*p, DVec3::new(bit(0), bit(1), bit(2)));
    }
    let faces: Vec<&[u32]> = m.faces().collect();
    assert_eq!(
        faces,
        [
            &[0, 2, 3, 1][..],
            &[0, 1, 5, 4],
            &[0, 4, 6, 2],
            &[1, 3, 7, 5],
            &[2, 6, 7, 3],
            &[4, 5, 7, 6]
        ]
    );
    assert_eq!(m, parse_primitive("@cube").unwrap());
    assert_eq!(m, parse_primitive("@hexahedron:1").unwrap());
}

#[test]
fn octahedron_is_regular_and_ordered() {
    let m = octahedron();
    closed(&m, 6, 12, 8, 0);
    assert_regular(&m, 4.0 * SQRT3);
    // Face i lies in the octant of cube corner i.
    let c = cube(1).unwrap();
    for (f, face) in m.faces().enumerate() {
        let centre = centre(&m, face);
        assert_eq!(centre.signum(), c.positions[f], "face {f}");
    }
    assert_eq!(m.positions[0], DVec3::new(0.0, 0.0, -SQRT3));
    assert_eq!(m.positions[5], DVec3::new(0.0, 0.0, SQRT3));
}

#[test]
fn dodecahedron_is_regular_and_ordered() {
    let m = dodecahedron();
    let t = closed(&m, 20, 30, 12, 0);
    assert_eq!(t.euler(), 2);
    assert!(m.faces().all(|f| f.len() == 5));
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let a = 2.0 / phi;
    assert_regular(&m, (15.0 + 7.0 * 5f64.sqrt()) / 4.0 * a * a * a);
    assert!(rel(edge_lengths(&m)[0], a) < 1e-14);
    // Contains the cube's corners; bottom and top edges.
    for p in cube(1).unwrap().positions {
        assert!(m.positions.contains(&p));
    }
    let has_edge = |f: usize, a: u32, b: u32| {
        let face = m.face(f);
        (0..5).any(|k| {
            (face[k], face[(k + 1) % 5]) == (a, b) || (face[k], face[(k + 1) % 5]) == (b, a)
        })
    };
    assert!(has_edge(0, 0, 1) && has_edge(1, 0, 1));
    assert!(has_edge(10, 18, 19) && has_edge(11, 18, 19));
}

#[test]
fn icosahedron_is_regular_and_ordered() {
    let m = icosahedron();
    closed(&m, 12, 30, 20, 0);
    let r = SQRT3;
    let a = r / (2.0 * PI / 5.0).sin();
    assert!(rel(edge_lengths(&m)[0], a) < 1e-14);
    assert_regular(&m, 5.0 * (3.0 + 5f64.sqrt()) / 12.0 * a * a * a);
    assert!(m.positions[0].z == m.positions[1].z && m.positions[0].x == m.positions[1].x);
    assert_eq!(m, parse_primitive("@ico").unwrap());
}

// ---------------------------------------------------------------------
// Cubes and planes.

#[test]
fn subdivided_cubes() {
    for n in [1u32, 2, 3, 7] {
        let m = cube(n).unwrap();
        closed_cube_surface(&m, n);
        assert!(m.faces().all(|f| f.len() == 4));
        assert!((volume(&m) - 8.0).abs() < 1e-12);
        assert!(max_non_planarity(&m) < 1e-15);
        // Vertices on the surface of [-1,1]^3, in (z, y, x) order.
        for p in &m.positions {
            assert_eq!(p.abs().max_element(), 1.0);
        }
        for w in m.positions.windows(2) {
            assert!(zyx_less(w[0], w[1]));
        }
        // Sides in order -z, -y, -x, +x, +y, +z; within a side by centre;
        // quads starting at their smallest corner.
        let sides = [
            DVec3::NEG_Z,
            DVec3::NEG_Y,
            DVec3::NEG_X,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
        ];
        let faces: Vec<&[u32]> = m.faces().collect();
        let nn = (n * n) as usize; // faces per side
        for (s, side) in sides.iter().enumerate() {
            let block = &faces[s * nn..(s + 1) * nn];
            for face in block {
                assert!(points(newell(&m, face), *side));
                assert_eq!(Some(&face[0]), face.iter().min());
                let p0 = m.positions[face[0] as usize];
                assert!(
                    face.iter()
                        .all(|&i| m.positions[i as usize].cmpge(p0).all())
                );
            }
            for w in block.windows(2) {
                assert!(zyx_less(centre(&m, w[0]), centre(&m, w[1])));
            }
        }
    }
    assert_eq!(
        parse_spec("@cube:1290").map(|s| s.face_count()),
        Ok(6 * 1290 * 1290)
    );
}

#[test]
fn planes() {
    for (nx, ny) in [(1u32, 1u32), (10, 10), (3, 7), (1, 5)] {
        let m = plane(nx, ny).unwrap();
        let (x, y) = (nx as usize, ny as usize);
        let t = check(&m);
        assert_eq!(
            (t.v, t.e, t.f),
            ((x + 1) * (y + 1), x * (y + 1) + y * (x + 1), x * y)
        );
        assert_eq!(t.boundary_loops, 1);
        assert_eq!(t.boundary_edges, 2 * (x + y));
        assert_eq!(t.euler(), 1);
        assert_eq!(t.genus(), 0);
        assert!(m.faces().all(|f| f.len() == 4));
        assert!(m.faces().all(|f| points(newell(&m, f), DVec3::Z)));
        assert_eq!(
            m.bounds(),
            Some((DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)))
        );
        let area: f64 = m.faces().map(|f| newell(&m, f).z / 2.0).sum();
        assert!((area - 4.0).abs() < 1e-12);
        // Face j*nx+i starts at vertex j*(nx+1)+i, its lowest.
        for (f, face) in m.faces().enumerate() {
            let (i, j) = (f % x, f / x);
            assert_eq!(face[0] as usize, j * (x + 1) + i);
            assert_eq!(Some(&face[0]), face.iter().min());
        }
    }
}

#[test]
fn triangle_planes() {
    for (nx, ny) in [(1u32, 1u32), (10, 10), (4, 9)] {
        let m = tri_plane(nx, ny).unwrap();
        let (x, y) = (nx as usize, ny as usize);
        let t = check(&m);
        assert_eq!(
            (t.v, t.e, t.f),
            (
                (x + 1) * (y + 1),
                x * (y + 1) + y * (x + 1) + x * y,
                2 * x * y
            )
        );
        assert_eq!((t.boundary_loops, t.euler()), (1, 1));
        assert!(
            m.faces()
                .all(|f| f.len() == 3 && points(newell(&m, f), DVec3::Z))
        );
        assert!(m.faces().all(|f| Some(&f[0]) == f.iter().min()));
        // Inner vertices have valence 6.
        let mut valence = vec![0usize; m.positions.len()];
        for f in m.faces() {
            for &v in f {
                valence[v as usize] += 1;
            }
        }
        for j in 1..y {
            for i in 1..x {
                assert_eq!(valence[j * (x + 1) + i], 6, "faces around ({i},{j})");
            }
        }
        // Same vertices as the quad plane.
        assert_eq!(m.positions, plane(nx, ny).unwrap().positions);
    }
}

// ---------------------------------------------------------------------
// Spheres.

#[test]
fn icospheres() {
    for level in 0..=5u32 {
        let m = icosphere(level).unwrap();
        let p = 4usize.pow(level);
        closed(&m, 10 * p + 2, 30 * p, 20 * p, 0);
        assert!(m.faces().all(|f| f.len() == 3));
        for v in &m.positions {
            assert!((v.length() - 1.0).abs() < 1e-15);
        }
    }
    let v5 = volume(&icosphere(5).unwrap());
    assert!(rel(v5, 4.0 / 3.0 * PI) < 0.005, "level 5 volume {v5}");
    // Volume increases towards the ball's.
    let vols: Vec<f64> = (0..5).map(|l| volume(&icosphere(l).unwrap())).collect();
    assert!(vols.windows(2).all(|w| w[0] < w[1]) && vols[4] < 4.0 / 3.0 * PI);
}

#[test]
fn icosphere_level_0_is_the_unit_icosahedron() {
    let s = icosphere(0).unwrap();
    let i = icosahedron();
    assert_eq!(s.face_indices, i.face_indices);
    for (a, b) in s.positions.iter().zip(&i.positions) {
        assert!((*a * SQRT3 - *b).length() < 1e-15);
    }
}

#[test]
fn icosphere_faces_follow_their_parents() {
    for level in 1..=3 {
        let parent = icosphere(level - 1).unwrap();
        let child = icosphere(level).unwrap();
        assert_eq!(
            parent.positions[..],
            child.positions[..parent.positions.len()]
        );
        let mut expected_new = parent.positions.len() as u32;
        let mut seen: HashSet<u32> = (0..expected_new).collect();
        for (t, pf) in parent.faces().enumerate() {
            let c: Vec<&[u32]> = (0..4).map(|k| child.face(4 * t + k)).collect();
            let (a, b, cc) = (pf[0], pf[1], pf[2]);
            let (ab, bc, ca) = (c[0][1], c[1][2], c[0][2]);
            assert_eq!(c[0], [a, ab, ca]);
            assert_eq!(c[1], [ab, b, bc]);
            assert_eq!(c[2], [ca, bc, cc]);
            assert_eq!(c[3], [ab, bc, ca]);
            // New vertices are numbered in order of first use.
            for m in [ab, bc, ca] {
                if seen.insert(m) {
                    assert_eq!(m, expected_new);
                    expected_new += 1;
                }
            }
            let mid = (parent.positions[a as usize] + parent.positions[b as usize]).normalize();
            assert!((child.positions[ab as usize] - mid).length() < 1e-15);
        }
    }
}

#[test]
fn icosphere_level_7_counts() {
    let m = icosphere(7).unwrap();
    let p = 4usize.pow(7);
    assert_eq!((m.positions.len(), m.face_count()), (10 * p + 2, 20 * p));
    assert!(m.positions.iter().all(|v| (v.length() - 1.0).abs() < 1e-15));
}

#[test]
fn uv_spheres() {
    for (s, r) in [(3u32, 2u32), (24, 12), (5, 7), (64, 32)] {
        let m = uv_sphere(s, r).unwrap();
        let (su, ru) = (s as usize, r as usize);
        closed(&m, su * (ru - 1) + 2, su * (2 * ru - 1), su * ru, 0);
        assert_eq!(m.faces().filter(|f| f.len() == 3).count(), 2 * su);
        assert!(max_non_planarity(&m) < 1e-14);
        assert!(m.positions.iter().all(|v| (v.length() - 1.0).abs() < 1e-15));
        assert_eq!(m.positions[0], DVec3::NEG_Z);
        assert_eq!(*m.positions.last().unwrap(), DVec3::Z);
        let a = PI / f64::from(r);
        assert!(m.positions[1].distance(DVec3::new(a.sin(), 0.0, -a.cos())) < 1e-15);
        assert_eq!(m.face(0), [0, 2, 1]);
    }
    let coarse = volume(&uv_sphere(24, 12).unwrap());
    let fine = volume(&uv_sphere(256, 128).unwrap());
    let ball = 4.0 / 3.0 * PI;
    assert!(coarse < fine && fine < ball && rel(fine, ball) < 1e-3);
}

#[test]
fn quad_spheres() {
    for n in [1u32, 2, 5, 8] {
        let m = quad_sphere(n).unwrap();
        closed_cube_surface(&m, n);
        assert!(m.positions.iter().all(|v| (v.length() - 1.0).abs() < 1e-15));
        // Same combinatorics as the cube.
        assert_eq!(m.face_indices, cube(n).unwrap().face_indices);
    }
    // Quads of nearly equal size thanks to the angular spacing.
    let m = quad_sphere(16).unwrap();
    let areas: Vec<f64> = m.faces().map(|f| newell(&m, f).length()).collect();
    let (lo, hi) = areas
        .iter()
        .fold((f64::MAX, 0f64), |(lo, hi), &a| (lo.min(a), hi.max(a)));
    assert!(hi / lo < 1.5, "area ratio {}", hi / lo);
    let v = volume(&quad_sphere(64).unwrap());
    assert!(rel(v, 4.0 / 3.0 * PI) < 2e-3, "volume {v}");
}

// ---------------------------------------------------------------------
// Torus, cylinder, cone.

#[test]
fn tori() {
    for (maj, min, big_r, small_r) in [
        (24u32, 12u32, 1.0, 0.4),
        (3, 3, 1.0, 0.4),
        (7, 5, 2.0, 0.5),
        (40, 3, 1.0, 0.9),
    ] {
        let m = torus(maj, min, big_r, small_r).unwrap();
        let f = (maj * min) as usize;
        let t = closed(&m, f, 2 * f, f, 1);
        assert_eq!(t.euler(), 0);
        assert!(m.faces().all(|f| f.len() == 4));
        assert!(max_non_planarity(&m) < 1e-14);
        let (lo, hi) = m.bounds().unwrap();
        if min % 4 == 0 {
            assert_eq!((lo.z, hi.z), (-small_r, small_r));
        }
        assert_eq!(m.positions[0], DVec3::new(big_r + small_r, 0.0, 0.0));
        // Every vertex is at distance r from the tube's centre circle.
        for p in &m.positions {
            let ring = DVec3::new(p.x, p.y, 0.0).normalize() * big_r;
            assert!((p.distance(ring) - small_r).abs() < 1e-14);
        }
    }
    // Volume tends to 2π²Rr².
    let exact = 2.0 * PI * PI * 2.0 * 0.5 * 0.5;
    let errors: Vec<f64> = [(12, 6), (48, 24), (256, 128)]
        .iter()
        .map(|&(a, b)| rel(volume(&torus(a, b, 2.0, 0.5).unwrap()), exact))
        .collect();
    assert!(errors.windows(2).all(|w| w[1] < w[0] / 4.0), "{errors:?}");
    assert!(errors[2] < 1e-3, "{errors:?}");
}

#[test]
fn cylinders() {
    for (s, r) in [(3u32, 1u32), (16, 1), (16, 4), (5, 3)] {
        let m = cylinder(s, r).unwrap();
        let (su, ru) = (s as usize, r as usize);
        closed(&m, su * (ru + 1), su * (2 * ru + 1), su * ru + 2, 0);
        assert!(max_non_planarity(&m) < 1e-15);
        let sf = f64::from(s);
        let exact = sf / 2.0 * (2.0 * PI / sf).sin() * 2.0;
        assert!(rel(volume(&m), exact) < 1e-14);
        assert_eq!(m.face(0).len(), su);
        assert_eq!(m.face(1).len(), su);
        assert!(points(newell(&m, m.face(0)), DVec3::NEG_Z));
        assert!(points(newell(&m, m.face(1)), DVec3::Z));
        assert_eq!((m.face(0)[0], m.face(1)[0]), (0, r * s));
        assert_eq!(m.face(2), [0, 1, s + 1, s]);
        for (k, ring) in m.positions.chunks(su).enumerate() {
            let z = (2.0 * k as f64 - f64::from(r)) / f64::from(r);
            assert!(
                ring.iter()
                    .all(|p| p.z == z && (p.truncate().length() - 1.0).abs() < 1e-15)
            );
        }
    }
    let v = volume(&cylinder(1000, 1).unwrap());
    assert!(rel(v, 2.0 * PI) < 1e-4);
}

#[test]
fn cones() {
    for s in [3u32, 4, 16, 100] {
        let m = cone(s).unwrap();
        let su = s as usize;
        closed(&m, su + 1, 2 * su, su + 1, 0);
        assert!(max_non_planarity(&m) < 1e-15);
        let sf = f64::from(s);
        let base = sf / 2.0 * (2.0 * PI / sf).sin();
        assert!(rel(volume(&m), base * 2.0 / 3.0) < 1e-14);
        assert!(points(newell(&m, m.face(0)), DVec3::NEG_Z));
        assert_eq!(m.face(1), [0, 1, s]);
        assert_eq!(m.positions[su], DVec3::Z);
    }
    assert!(rel(volume(&cone(2000).unwrap()), 2.0 * PI / 3.0) < 1e-5);
}

/// A spec (defaults filled in, aliases, case and `_` tolerated) builds
/// exactly what its generator builds with the same arguments.
#[test]
fn specs_build_what_their_generators_build() {
    for (spec, generated) in [
        ("@plane", plane(10, 10)),
        ("@grid:10:10", plane(10, 10)),
        ("@sphere", icosphere(3)),
        ("@IcoSphere:2", icosphere(2)),
        ("@uv-sphere", uv_sphere(24, 12)),
        ("@UV_Sphere:8:4", uv_sphere(8, 4)),
        ("@torus", torus(24, 12, 1.0, 0.4)),
        ("@torus::16::0.25", torus(24, 16, 1.0, 0.25)),
        ("@donut:8:6:3:1.5", torus(8, 6, 3.0, 1.5)),
        ("@cylinder", cylinder(16, 1)),
        ("@cone", cone(16)),
        ("@geosphere:3", geodesic(3)),
    ] {
        assert_eq!(generated.unwrap(), parse_primitive(spec).unwrap(), "{spec}");
    }
}

#[test]
fn quarter_turns_are_exact() {
    assert_eq!(turn(0, 8), (1.0, 0.0));
    assert_eq!(turn(2, 8), (0.0, 1.0));
    assert_eq!(turn(4, 8), (-1.0, 0.0));
    assert_eq!(turn(6, 8), (0.0, -1.0));
    assert_eq!(turn(8, 8), (1.0, 0.0));
    assert_eq!(turn(1, 8), (0.5f64.sqrt(), 0.5f64.sqrt()));
    assert_eq!(turn(3, 0), (1.0, 0.0));
    for n in [3u32, 5, 7, 12, 24, 100, 1001] {
        for i in 0..n {
            let (c, s) = turn(i, n);
            let a = 2.0 * PI * f64::from(i) / f64::from(n);
            assert!(
                (c - a.cos()).abs() < 1e-15 && (s - a.sin()).abs() < 1e-15,
                "{i}/{n}"
            );
            // Mirror images are exact, and there is no negative zero.
            assert_eq!(turn(n - i, n), (c, 0.0 - s));
            assert!((c != 0.0 || c.is_sign_positive()) && (s != 0.0 || s.is_sign_positive()));
        }
    }
}

// ---------------------------------------------------------------------
// The soccer ball and the geodesic spheres (issue 18).

#[test]
fn soccer_ball_is_a_truncated_icosahedron() {
    let m = soccer_ball();
    // Worked out from the icosahedron (12/30/20), every vertex cut:
    // V = 2E = 60, E = 3E = 90, F = F + V = 32; χ = 2.
    closed(&m, 60, 90, 32, 0);
    let sizes: Vec<usize> = m.faces().map(|f| f.len()).collect();
    assert_eq!(sizes.iter().filter(|&&s| s == 5).count(), 12);
    assert_eq!(sizes.iter().filter(|&&s| s == 6).count(), 20);
    assert!(sizes[..12].iter().all(|&s| s == 5) && sizes[12..].iter().all(|&s| s == 6));
    // Truncation at a third: all edges equal (a third of the
    // icosahedron's, scaled); regular planar faces on the sphere of √3.
    let lengths = edge_lengths(&m);
    assert!(lengths.iter().all(|&l| rel(l, lengths[0]) < 1e-12));
    assert!(m.positions.iter().all(|p| rel(p.length(), SQRT3) < 1e-14));
    assert!(max_non_planarity(&m) < 1e-12);
    // Each pentagon surrounds its icosahedron vertex's direction.
    let ico = icosahedron();
    for (a, face) in m.faces().take(12).enumerate() {
        assert!(points(centre(&m, face), ico.positions[a].normalize()));
    }
    assert_eq!(parse_primitive("@soccerball").unwrap(), m);
    assert_eq!(parse_primitive("@buckyball").unwrap(), m);
}

#[test]
fn geodesic_spheres() {
    for n in [1u32, 2, 3, 4, 7] {
        let m = geodesic(n).unwrap();
        let n2 = (n * n) as usize;
        // V = 10n² + 2, E = 30n², F = 20n²: χ = 2.
        closed(&m, 10 * n2 + 2, 30 * n2, 20 * n2, 0);
        assert!(m.faces().all(|f| f.len() == 3));
        for p in &m.positions {
            assert!((p.length() - 1.0).abs() < 1e-14);
        }
        // Edges shrink like 1/n: the flat grid's edges are the
        // icosahedron's chord over n (1.0515/n). The central projection
        // x/|x| of a face plane at distance r0 = 0.7947 (the unit
        // icosahedron's inradius) changes lengths near x by a factor
        // between r0 (the plane meets the rays at cosine ≥ r0/|x|) and
        // 1/|x| ≤ 1/r0.
        let chord = 4.0 / (10.0 + 2.0 * 5f64.sqrt()).sqrt();
        let flat = chord / f64::from(n);
        for l in edge_lengths(&m) {
            assert!(
                l <= flat / 0.7946 && l >= flat * 0.7946,
                "n {n}: {l} vs {flat}"
            );
        }
        // Faces of icosahedron face t lie around its direction.
        let ico = icosahedron();
        for (t, tri) in ico.faces().enumerate() {
            let dir = centre(&ico, tri).normalize();
            for k in 0..n2 {
                let f = m.face(t * n2 + k);
                assert!(centre(&m, f).normalize().dot(dir) > 0.7, "n {n}, face {t}");
            }
        }
    }
    // Frequency 1 is the unit icosahedron, in the same order.
    let one = geodesic(1).unwrap();
    let ico = icosphere(0).unwrap();
    assert_eq!(one, ico);
    // The spec's default and its canonical form.
    assert_eq!(parse_spec("@geodesic").unwrap().to_string(), "@geodesic:4");
    assert!(err("@geodesic:0").contains("from 1 to 707"));
    assert!(err("@geodesic:708").contains("708 or more would give over 10000000 faces"));
    assert!(geodesic(0).is_err() && geodesic(708).is_err());
}

// ---------------------------------------------------------------------
// Every primitive through the parser.

#[test]
fn every_primitive_and_alias_parses_and_is_a_good_mesh() {
    for p in PRIMITIVES {
        let m = parse_primitive(&format!("@{}", p.name)).unwrap();
        let t = check(&m);
        let spec = parse_spec(&format!("@{}", p.name)).unwrap();
        assert_eq!(spec.face_count(), t.f as u128, "{}", p.name);
        if p.name.contains("plane") {
            assert_eq!((t.boundary_loops, t.genus()), (1, 0));
        } else {
            assert_eq!(t.boundary_edges, 0, "{}", p.name);
            assert_eq!(t.genus(), i64::from(p.name == "torus"), "{}", p.name);
            assert!(volume(&m) > 0.0, "{}", p.name);
        }
        for alias in p.aliases {
            assert_eq!(
                parse_primitive(&format!("@{alias}")).unwrap(),
                m,
                "@{alias}"
            );
        }
        for name in [
            p.name.to_uppercase(),
            p.name.replace('-', ""),
            p.name.replace('-', "_"),
        ] {
            assert_eq!(parse_primitive(&format!("@{name}")).unwrap(), m, "@{name}");
        }
    }
}

#[test]
fn specs_have_a_canonical_form() {
    let s = parse_spec("@torus::16").unwrap();
    assert_eq!(s.to_string(), "@torus:24:16:1:0.4");
    assert_eq!(parse_spec(&s.to_string()).unwrap(), s);
    assert_eq!(parse_spec("@sphere").unwrap().to_string(), "@sphere:3");
    assert_eq!(parse_spec("@Ico").unwrap().to_string(), "@icosahedron");
    assert_eq!(parse_spec("@cube:").unwrap().to_string(), "@cube:1");
    assert_eq!(
        parse_spec("@torus:+30:12:1e0:.5").unwrap().args(),
        [30.0, 12.0, 1.0, 0.5]
    );
    assert!(is_primitive_spec("@cube") && !is_primitive_spec("cube.obj"));
    assert_eq!(
        find_primitive("Uv_Sphere").map(|p| p.name),
        Some("uv-sphere")
    );
    assert_eq!(PRIMITIVES[8].usage(), "@torus[:major[:minor[:R[:r]]]]");
    assert_eq!(PRIMITIVES[0].usage(), "@tetrahedron");
}

fn err(spec: &str) -> String {
    match parse_primitive(spec) {
        Ok(_) => panic!("{spec} parsed"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn parse_errors_say_what_is_wrong() {
    assert!(err("cube").contains("starts with '@'"));
    assert!(err("").contains("starts with '@'"));
    assert!(err("@").contains("missing primitive name"));
    assert!(err("@:3").contains("missing primitive name"));

    let unknown = err("@blob");
    assert!(
        unknown.starts_with("unknown primitive @blob; known primitives: @tetrahedron, @cube,"),
        "{unknown}"
    );
    assert!(unknown.contains("@torus") && unknown.contains("@tri-plane"));
    assert!(err("@cub").contains("unknown primitive @cub (did you mean @cube?)"));
    assert!(err("@tours").contains("(did you mean @torus?)"));
    assert!(err("@dodec").contains("(did you mean @dodecahedron?)"));
    assert!(err("@cube.obj").contains("unknown primitive @cube.obj"));

    assert_eq!(
        err("@cube:2:3"),
        "@cube takes at most 1 parameter (@cube[:n]), got 2"
    );
    assert_eq!(
        err("@tetrahedron:1"),
        "@tetrahedron takes at most 0 parameters (@tetrahedron), got 1"
    );
    assert_eq!(
        err("@torus:1:2:3:4:5"),
        "@torus takes at most 4 parameters (@torus[:major[:minor[:R[:r]]]]), got 5"
    );

    assert_eq!(
        err("@sphere:1.5"),
        "parameter 'level' of @sphere must be an integer, got \"1.5\""
    );
    assert_eq!(
        err("@sphere:x"),
        "parameter 'level' of @sphere must be an integer, got \"x\""
    );
    assert_eq!(
        err("@sphere: 2"),
        "parameter 'level' of @sphere must be an integer, got \" 2\""
    );
    assert_eq!(
        err("@sphere:99"),
        "parameter 'level' of @sphere must be an integer from 0 to 9, got 99 \
         (10 or more would give over 10000000 faces)"
    );
    assert!(err("@sphere:10").contains("10 or more would give over 10000000 faces"));
    assert!(err("@sphere:-1").contains("must be an integer from 0 to 9, got -1"));
    assert!(
        err("@sphere:99999999999999999999999").contains("from 0 to 9, got 99999999999999999999999")
    );
    assert!(
        err("@cube:0").contains("parameter 'n' of @cube must be an integer from 1 to 1290, got 0")
    );
    assert!(err("@cube:1291").contains("1291 or more would give over 10000000 faces"));
    assert!(
        err("@torus:2")
            .contains("parameter 'major' of @torus must be an integer from 3 to 3333333, got 2")
    );

    assert_eq!(
        err("@torus:5000:5000"),
        "@torus:5000:5000:1:0.4 would have 25000000 faces, more than the limit of 10000000 faces; \
         use smaller parameters"
    );
    assert!(err("@plane:4000:4000").contains("would have 16000000 faces"));
    assert_eq!(
        parse_spec("@plane:10000000:1").map(|s| s.face_count()),
        Ok(10_000_000)
    );

    assert_eq!(
        err("@torus:24:12:abc"),
        "parameter 'R' of @torus must be a finite number, got \"abc\""
    );
    assert!(err("@torus:24:12:inf").contains("must be a finite number, got \"inf\""));
    assert!(err("@torus:24:12:NaN").contains("must be a finite number"));
    assert!(err("@torus:24:12:1e999").contains("must be a finite number"));
    assert!(err("@torus:24:12:0").contains(
        "parameter 'R' of @torus must be a number greater than 0 and at most 1000000000, got 0"
    ));
    assert!(
        err("@torus:24:12:1:-0.5")
            .contains("parameter 'r' of @torus must be a number greater than 0")
    );
    assert_eq!(
        err("@torus:24:12:1:1"),
        "@torus: the tube radius r must be less than R, or the torus would meet itself at the z axis; \
         got R = 1, r = 1"
    );
    assert!(err("@torus:24:12:0.3").contains("got R = 0.3, r = 0.4"));
}

#[test]
fn generators_validate_when_called_directly() {
    assert!(icosphere(10).is_err());
    assert!(cube(0).is_err());
    assert!(torus(3, 3, 1.0, f64::NAN).is_err());
    assert!(torus(3, 3, f64::INFINITY, 1.0).is_err());
    assert!(plane(0, 5).is_err());
    assert!(tri_plane(5_000_000, 2).is_err());
    assert!(uv_sphere(3, 1).is_err());
    assert!(cylinder(2, 1).is_err());
    assert!(cone(2).is_err());
    assert!(quad_sphere(1291).is_err());
}

#[test]
fn arbitrary_specs_never_panic() {
    let names = [
        "",
        "cube",
        "sphere",
        "torus",
        "plane",
        "tri-plane",
        "cone",
        "x",
        "Cylinder",
        "uv_sphere",
    ];
    let pieces = [
        "", "0", "1", "3", "-2", "+4", "1.5", "e", "1e3", ".", ":", "@", "é", " ", "99", "0.3",
        "nan", "\u{0}",
    ];
    let mut rng = Rng::new(7);
    for _ in 0..5000 {
        let mut s = String::new();
        if rng.chance(0.9) {
            s.push('@');
        }
        let name: &&str = rng.pick(&names);
        s.push_str(name);
        for _ in 0..rng.below(6) {
            if rng.chance(0.8) {
                s.push(':');
            }
            for _ in 0..rng.below(3) {
                let piece: &&str = rng.pick(&pieces);
                s.push_str(piece);
            }
        }
        match parse_spec(&s) {
            Ok(spec) => {
                assert!(spec.face_count() <= u128::from(MAX_FACES));
                if spec.face_count() <= 2000 {
                    let m = spec.build().expect("valid spec builds");
                    assert_eq!(m.face_count() as u128, spec.face_count(), "{s}");
                }
            }
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
}

#[test]
fn help_lists_every_primitive() {
    let help = primitive_help();
    for p in PRIMITIVES {
        assert!(help.contains(&p.usage()), "{}", p.name);
        for a in p.aliases {
            assert!(help.contains(&format!("@{a}")), "{a}");
        }
        assert!(!p.description.is_empty() && !p.counts.is_empty() && !p.order.is_empty());
    }
    assert!(
        help.contains("    level     subdivision level; integer 0..9, default 3"),
        "{help}"
    );
    assert!(help.contains("default 0.4"));
    assert!(help.contains("10000000 faces"));
    let summary = primitive_summary();
    assert_eq!(
        summary.lines().filter(|l| l.starts_with('@')).count(),
        PRIMITIVES.len()
    );
    for line in help.lines().chain(summary.lines()) {
        assert!(line.chars().count() <= 79, "long help line: {line}");
    }
}

/// Builds the largest allowed instance of every primitive and checks its
/// counts (about 8 s in a release build; the test suite runs in release).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "slow in debug builds; scripts/test.sh runs it in release"
)]
fn largest_primitives_build() {
    for spec in [
        "@cube:1290",
        "@sphere:9",
        "@uv-sphere:5000000:2",
        "@uv-sphere:3:3333333",
        "@quad-sphere:1290",
        "@torus:3333333:3",
        "@torus:3000:3333",
        "@cylinder:9999998",
        "@cylinder:3:3333332",
        "@cone:9999999",
        "@plane:10000000:1",
        "@plane:1:10000000",
        "@tri-plane:5000000:1",
        "@geodesic:707",
    ] {
        let start = std::time::Instant::now();
        let parsed = parse_spec(spec).unwrap();
        let m = parsed.build().unwrap();
        assert_eq!(m.face_count() as u128, parsed.face_count(), "{spec}");
        assert!(m.face_count() as u64 <= MAX_FACES);
        m.check().unwrap();
        eprintln!(
            "{spec}: {} faces, {} vertices in {:?}",
            m.face_count(),
            m.positions.len(),
            start.elapsed()
        );
    }
}
