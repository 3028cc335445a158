//! Hull tests: counts worked out from the definitions (a convex
//! polyhedron is its own hull, the dual convex hull of a regular one is
//! its dual, points in general position give triangles and a simple
//! polytope, both by Euler's formula), convexity and containment checked
//! face by face, refusals.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{DVec3, Mesh};
use holey_testkit::Rng;

use super::*;

fn prim(spec: &str) -> Mesh {
    let poly = holey_shapes::parse_primitive(spec).unwrap();
    to_dlfl(&poly, ImportOptions::default()).unwrap().mesh
}

fn counts(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

fn points(m: &Mesh) -> Vec<DVec3> {
    m.vertices().map(|v| m.position(v).unwrap()).collect()
}

/// A closed convex polyhedron of genus 0: valid, no holes, Euler's
/// formula, every face planar and every vertex (of `h` and of `inside`)
/// on or behind every face's plane, within `tol`.
fn convex(h: &Mesh, inside: &[DVec3], tol: f64) {
    h.validate().unwrap();
    assert_eq!(h.hole_count(), 0);
    assert_eq!(h.genus(), 0);
    assert_eq!(h.topology().component_count(), 1);
    let (v, e, f) = counts(h);
    assert_eq!(v as i64 - e as i64 + f as i64, 2);
    let own = points(h);
    for face in h.faces() {
        let ps = h.face_positions(face).unwrap();
        assert!(ps.len() >= 3);
        let n = newell(&ps).normalize();
        let q = ps[0];
        for p in ps.iter().chain(&own).chain(inside) {
            let d = n.dot(*p - q);
            assert!(d <= tol, "a point {d} in front of a face");
            if ps.contains(p) {
                assert!(d.abs() <= tol, "a face is not planar: {d}");
            }
        }
    }
}

#[test]
fn a_convex_polyhedron_is_its_own_hull() {
    for spec in [
        "@tetrahedron",
        "@cube",
        "@octahedron",
        "@dodecahedron",
        "@icosahedron",
        "@soccerball",
    ] {
        let m = prim(spec);
        let h = convex_hull(&m).unwrap();
        assert_eq!(counts(&h), counts(&m), "{spec}");
        convex(&h, &points(&m), 1e-9);
        // The input is untouched.
        assert_eq!(m.to_raw(), prim(spec).to_raw());
    }
}

#[test]
fn the_dual_convex_hull_of_a_regular_polyhedron_is_its_dual() {
    // V, E, F of the dual are F, E, V.
    for spec in [
        "@tetrahedron",
        "@cube",
        "@octahedron",
        "@dodecahedron",
        "@icosahedron",
    ] {
        let m = prim(spec);
        let d = dual_convex_hull(&m).unwrap();
        let (v, e, f) = counts(&m);
        assert_eq!(counts(&d), (f, e, v), "{spec}");
        convex(&d, &points(&m), 1e-9);
        // Each face's plane touches the polyhedron at one vertex.
        for face in d.faces() {
            let ps = d.face_positions(face).unwrap();
            let n = newell(&ps).normalize();
            let touching = points(&m)
                .iter()
                .filter(|p| n.dot(**p - ps[0]).abs() < 1e-9)
                .count();
            assert_eq!(touching, 1, "{spec}");
        }
    }
    // The cube [-1, 1]³: planes x ± y ± z = 3 through its corners bound
    // the octahedron |x| + |y| + |z| ≤ 3.
    let d = dual_convex_hull(&prim("@cube")).unwrap();
    for p in points(&d) {
        let mut a = p.abs().to_array();
        a.sort_by(f64::total_cmp);
        assert!(a[0].abs() < 1e-12 && a[1].abs() < 1e-12 && (a[2] - 3.0).abs() < 1e-12);
    }
}

#[test]
fn points_in_general_position_give_triangles_and_a_simple_dual() {
    // n random points on a sphere are all corners of their hull; every
    // face is a triangle, so 3F = 2E and Euler's formula give F = 2n − 4,
    // E = 3n − 6. The dual has a face per point and three planes at each
    // vertex: 3V* = 2E*, so V* = 2n − 4, E* = 3n − 6.
    let mut rng = Rng::new(18);
    for n in [5usize, 40, 700] {
        let mut m = Mesh::new();
        for _ in 0..n {
            let p = DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            m.create_vertex(p.normalize() * 2.0).unwrap();
        }
        let h = convex_hull(&m).unwrap();
        assert_eq!(counts(&h), (n, 3 * n - 6, 2 * n - 4), "hull of {n}");
        convex(&h, &points(&m), 1e-9);
        let d = dual_convex_hull(&m).unwrap();
        assert_eq!(counts(&d), (2 * n - 4, 3 * n - 6, n), "dual of {n}");
        convex(&d, &points(&m), 1e-8);
    }
}

#[test]
fn inner_points_and_points_on_faces_and_edges_are_not_corners() {
    // Every edge of the cube split at its midpoint, a point inside, and
    // point-spheres at the centre of the top face and of a top edge: the
    // hull is the cube, 8/12/6.
    let mut m = prim("@cube");
    let edges: Vec<_> = m.edges().collect();
    for e in edges {
        m.subdivide_edge(e).unwrap();
    }
    for p in [
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
    ] {
        m.create_vertex(p).unwrap();
    }
    m.validate().unwrap();
    let h = convex_hull(&m).unwrap();
    assert_eq!(counts(&h), (8, 12, 6));
    convex(&h, &points(&m), 1e-12);
    // A point above the top face makes a pyramid of it: one vertex more,
    // the top quad replaced by four triangles: 9, 12 + 4, 6 − 1 + 4.
    m.create_vertex(DVec3::new(0.0, 0.0, 3.0)).unwrap();
    let h = convex_hull(&m).unwrap();
    assert_eq!(counts(&h), (9, 16, 9));
    convex(&h, &points(&m), 1e-12);
}

#[test]
fn the_hulls_of_a_non_convex_mesh_contain_it() {
    for spec in ["@torus:8:5", "@sphere:2", "@cone:7"] {
        let m = prim(spec);
        let h = convex_hull(&m).unwrap();
        convex(&h, &points(&m), 1e-9);
        // The hull's corners are input vertices.
        let input = points(&m);
        assert!(points(&h).iter().all(|p| input.contains(p)), "{spec}");
        // One face of the dual per corner of the hull.
        let d = dual_convex_hull(&m).unwrap();
        assert_eq!(d.face_count(), h.vertex_count(), "{spec}");
        convex(&d, &input, 1e-8);
    }
}

#[test]
fn flat_empty_and_overflowing_inputs_are_refused() {
    for m in [Mesh::new(), prim("@plane:3:3")] {
        for r in [convex_hull(&m), dual_convex_hull(&m)] {
            assert!(matches!(r, Err(HullError::Flat { .. })), "{r:?}");
        }
    }
    // Coordinates whose products overflow.
    let mut huge = prim("@cube");
    for v in huge.vertices().collect::<Vec<_>>() {
        let p = huge.position(v).unwrap();
        huge.set_position(v, p * 1e300).unwrap();
    }
    for r in [convex_hull(&huge), dual_convex_hull(&huge)] {
        assert!(matches!(r, Err(HullError::Overflow(_))), "{r:?}");
    }
    // Three points on a line, and a cube squashed flat.
    let mut line = Mesh::new();
    for x in [0.0, 1.0, 2.0, 3.0] {
        line.create_vertex(DVec3::new(x, 2.0 * x, 0.0)).unwrap();
    }
    assert!(matches!(
        convex_hull(&line),
        Err(HullError::Flat { points: 4 })
    ));
}
