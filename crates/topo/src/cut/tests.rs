use glam::DVec3;
use holey_geom::position_classes;
use holey_testkit::oracles::edge_degrees;

use super::*;
use crate::intersect::intersections;
use crate::intersect::tests::{join, octahedron, two_octahedra};

fn volume(m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| m.positions[v as usize]);
            p[0].dot(p[1].cross(p[2])) / 6.0
        })
        .sum()
}

/// Directed edges each used once and their reverse once: closed and oriented.
fn closed_oriented(m: &TriMesh) -> bool {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::default();
    for t in &m.triangles {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    directed
        .iter()
        .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1))
}

/// What [`cut`] takes besides a mesh at rest: its edges, position classes
/// and intersections.
struct Setup {
    edges: Edges,
    ids: Vec<u32>,
    x: Intersections,
}

fn setup(m: &TriMesh) -> Setup {
    let edges = Edges::new(m);
    let ids = position_classes(&m.positions).unwrap();
    let x = intersections(m, &m.positions, &edges, &ids).unwrap();
    Setup { edges, ids, x }
}

impl Setup {
    /// [`cut`] of `m` (the mesh this was set up for) at its own positions,
    /// with no sampler.
    fn cut(&self, m: &TriMesh, deletion: Deletion<'_>) -> Cut {
        cut(
            m,
            &m.positions,
            &self.edges,
            &self.ids,
            &self.x,
            deletion,
            None,
        )
    }
}

fn inside_octahedron(p: DVec3, c: DVec3, r: f64) -> bool {
    let d = p - c;
    d.x.abs() + d.y.abs() + d.z.abs() < r
}

#[test]
fn resolve_cuts_and_glues_without_deleting() {
    let m = two_octahedra();
    let s = setup(&m);
    let x = &s.x;
    let out = s.cut(&m, Deletion::Nothing);
    assert_eq!(out.report.curves_kept, 1);
    assert_eq!(out.report.triangles_deleted, 0);
    assert!((out.mesh.area() - m.area()).abs() < 1e-12 * m.area());
    assert!((volume(&out.mesh) - volume(&m)).abs() < 1e-12);
    // The curve's edges are shared by four triangles, all others by two.
    let d = edge_degrees(&out.mesh.triangles);
    let fours = d.values().filter(|&&n| n == 4).count();
    assert_eq!(fours, x.pieces.len() + out.report.constraint_splits);
    assert!(d.values().all(|&n| n == 2 || n == 4));
    assert_eq!(out.mesh.positions.len(), m.positions.len() + x.points.len());
}

#[test]
fn deleting_the_odd_parts_of_two_octahedra_gives_their_union() {
    let (ca, cb) = (DVec3::ZERO, DVec3::new(0.7, 0.1, 0.05));
    let m = join(&octahedron(ca, 1.0), &octahedron(cb, 1.0));
    let s = setup(&m);
    // Odd: vertices of one solid inside the other.
    let odd: Vec<bool> = m
        .positions
        .iter()
        .enumerate()
        .map(|(v, &p)| {
            if v < 6 {
                inside_octahedron(p, cb, 1.0)
            } else {
                inside_octahedron(p, ca, 1.0)
            }
        })
        .collect();
    let out = s.cut(
        &m,
        Deletion::Odd {
            odd: &odd,
            open_ends: false,
        },
    );
    assert!(
        closed_oriented(&out.mesh),
        "the union is not closed and oriented"
    );
    // Volume of the union by sampling the two solids' indicator.
    let mut rng = holey_testkit::Rng::new(3);
    let (lo, hi) = (DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.7, 1.1, 1.05));
    let samples = 200_000;
    let hits = (0..samples)
        .filter(|_| {
            let p = DVec3::from_array(rng.in_box(lo.to_array(), hi.to_array()));
            inside_octahedron(p, ca, 1.0) || inside_octahedron(p, cb, 1.0)
        })
        .count();
    let box_volume = (hi - lo).x * (hi - lo).y * (hi - lo).z;
    let sampled = box_volume * hits as f64 / samples as f64;
    let v = volume(&out.mesh);
    assert!(
        (v - sampled).abs() < 0.02 * sampled,
        "volume {v} vs sampled {sampled}"
    );
}

#[test]
fn false_edges_close_a_parity_change_that_no_curve_separates() {
    // An open 8×8 grid, odd in a disk, with no intersections at all.
    let n = 8u32;
    let mut m = TriMesh::default();
    for j in 0..=n {
        for i in 0..=n {
            m.positions.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    m.triangles = holey_testkit::grid_triangles(n, n);
    let s = setup(&m);
    assert_eq!(s.x.curve_count, 0);
    let c = DVec3::new(4.0, 4.0, 0.0);
    let odd: Vec<bool> = m.positions.iter().map(|p| p.distance(c) < 2.5).collect();
    let out = s.cut(
        &m,
        Deletion::Odd {
            odd: &odd,
            open_ends: false,
        },
    );
    assert!(out.report.false_vertices > 0 && out.report.false_edges > 0);
    // A hole opened, and the remaining surface is a disk with one hole:
    // every edge has one or two triangle sides.
    let d = edge_degrees(&out.mesh.triangles);
    assert!(d.values().all(|&k| k == 1 || k == 2));
    let hole = m.area() - out.mesh.area();
    assert!(hole > 9.0 && hole < 30.0, "hole area {hole}");
    // No vertex of the result lies strictly inside the odd disk.
    assert!(out.mesh.positions.iter().all(|p| p.distance(c) > 1.4));
}
