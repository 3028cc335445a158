//! Hull tests: counts worked out from the definitions (a convex
//! polyhedron is its own hull, the dual convex hull of a regular one is
//! its dual, points in general position give triangles and a simple
//! polytope, both by Euler's formula), convexity and containment checked
//! face by face, refusals.

use crate::test_util::{counts, cube_with_split_edges, prim};
use holey_dlfl::{DVec3, Mesh};
use holey_testkit::Rng;

use super::*;

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

/// Whether a face's corners lie exactly on one plane.
fn exactly_planar(ps: &[DVec3]) -> bool {
    ps.iter()
        .all(|&p| holey_geom::orient3d(ps[0], ps[1], ps[2], p) == holey_geom::Sign::Zero)
}

/// The number of clusters of `ps` at most `tol` apart (greedy).
fn clusters(ps: &[DVec3], tol: f64) -> usize {
    let mut centres: Vec<DVec3> = Vec::new();
    for &p in ps {
        if !centres.iter().any(|c| c.distance(p) <= tol) {
            centres.push(p);
        }
    }
    centres.len()
}

#[test]
fn a_convex_polyhedron_is_its_own_hull() {
    // The hull's planes are decided exactly on the f64 corners: a face
    // planar only to rounding (the dodecahedron's and the soccer ball's
    // irrational pentagons and hexagons) is not one face but several
    // (triangles, or polygons where some corners are exactly coplanar).
    // So: the same corners, an exactly planar input face is a hull face,
    // every hull face lies in one input face, and with V unchanged
    // Euler's formula keeps E − F. Where every face is exactly planar
    // (tetrahedron, cube, octahedron, icosahedron: triangles and squares
    // on the axes) the counts are the input's.
    for (spec, all_planar) in [
        ("@tetrahedron", true),
        ("@cube", true),
        ("@octahedron", true),
        ("@icosahedron", true),
        ("@dodecahedron", false),
        ("@soccerball", false),
    ] {
        let m = prim(spec);
        let h = convex_hull(&m).unwrap();
        let (v, e, f) = counts(&h);
        let (v0, e0, f0) = counts(&m);
        assert_eq!(v, v0, "{spec}");
        assert_eq!(e as i64 - f as i64, e0 as i64 - f0 as i64, "{spec}");
        convex(&h, &points(&m), 1e-9);
        let faces_of = |x: &Mesh| -> Vec<Vec<DVec3>> {
            x.faces().map(|g| x.face_positions(g).unwrap()).collect()
        };
        let (ours, theirs) = (faces_of(&h), faces_of(&m));
        let mut planar = 0;
        for input in &theirs {
            if exactly_planar(input) {
                planar += 1;
                let same =
                    |o: &Vec<DVec3>| o.len() == input.len() && o.iter().all(|p| input.contains(p));
                assert!(ours.iter().any(same), "{spec}: a planar face is lost");
            }
        }
        assert_eq!(planar == theirs.len(), all_planar, "{spec}");
        if all_planar {
            assert_eq!((v, e, f), (v0, e0, f0), "{spec}");
        } else {
            assert!(f > f0, "{spec}");
        }
        for face in &ours {
            assert!(
                theirs
                    .iter()
                    .any(|input| face.iter().all(|p| input.contains(p))),
                "{spec}: a hull face across input faces"
            );
        }
        // The input is untouched.
        assert_eq!(m.to_raw(), prim(spec).to_raw());
    }
}

#[test]
fn the_dual_convex_hull_of_a_regular_polyhedron_is_its_dual() {
    // One face per vertex, and the dual's corners are where the faces of
    // the polyhedron's dual are: F of them, to within rounding. Where the
    // input's faces are exactly planar the counts are the dual's, V, E, F
    // of the dual being F, E, V; the dodecahedron's pentagons are planar
    // only to rounding, so five planes meet within rounding of a point
    // and the exact polar hull may split that corner into several, a
    // rounding apart.
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
        assert_eq!(d.face_count(), v, "{spec}");
        assert_eq!(clusters(&points(&d), 1e-9), f, "{spec}");
        if spec != "@dodecahedron" {
            assert_eq!(counts(&d), (f, e, v), "{spec}");
        }
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
    let mut m = cube_with_split_edges(Mesh::subdivide_edge);
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
fn flat_and_empty_inputs_are_refused_and_huge_or_tiny_ones_are_not() {
    for m in [Mesh::new(), prim("@plane:3:3")] {
        for r in [convex_hull(&m), dual_convex_hull(&m)] {
            assert!(matches!(r, Err(HullError::Flat { .. })), "{r:?}");
        }
    }
    // Coordinates whose products would overflow are scaled by a power of
    // two first, so the hull of a cube scaled by 10³⁰⁰ is the cube and its
    // dual the octahedron at 3·10³⁰⁰; at 10³⁰⁸ the dual's corners (3·10³⁰⁸)
    // overflow and are refused. A cube 10⁻³⁰⁰ across works alike.
    let scaled_cube = |s: f64| {
        let mut m = prim("@cube");
        for v in m.vertices().collect::<Vec<_>>() {
            let p = m.position(v).unwrap();
            m.set_position(v, p * s).unwrap();
        }
        m
    };
    for s in [1e300, 1e-300] {
        let m = scaled_cube(s);
        assert_eq!(counts(&convex_hull(&m).unwrap()), (8, 12, 6), "{s}");
        let d = dual_convex_hull(&m).unwrap();
        assert_eq!(counts(&d), (6, 12, 8), "{s}");
        for p in points(&d) {
            let mut a = (p / s).abs().to_array();
            a.sort_by(f64::total_cmp);
            assert!(
                a[0] < 1e-12 && a[1] < 1e-12 && (a[2] - 3.0).abs() < 1e-12,
                "{s}"
            );
        }
    }
    let huge = scaled_cube(1e308);
    assert_eq!(counts(&convex_hull(&huge).unwrap()), (8, 12, 6));
    let r = dual_convex_hull(&huge);
    assert!(matches!(r, Err(HullError::Overflow(_))), "{r:?}");
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

/// The unit cube `[o, o + size]³` as point-spheres with, on each face, a
/// 5 × 5 grid of points exactly on it and the same grid one step inward
/// (both inside or on the hull, never corners), the midpoints of the
/// edges (on straight edges) and every corner twice; and `out` pushes the
/// centres of the faces `x = o`, `y = o`, `z = o` and `x = o + size` out
/// by one step each, `low` and `high` the pushed coordinates of the low
/// and high faces, `low_in` and `high_in` the inward ones.
fn jittered_cube(o: f64, size: f64, low: [f64; 2], high: [f64; 2], out: bool) -> Mesh {
    let ([low_out, low_in], [high_out, high_in]) = (low, high);
    let mut m = Mesh::new();
    let mut add = |p: DVec3| {
        m.create_vertex(p).unwrap();
    };
    let at = |t: f64| o + size * t;
    let place = |axis: usize, w: f64, u: f64, v: f64| {
        let mut a = [0.0; 3];
        a[axis] = w;
        a[(axis + 1) % 3] = u;
        a[(axis + 2) % 3] = v;
        DVec3::from_array(a)
    };
    for k in 0..16 {
        let c = |bit: usize| at(((k >> bit) & 1) as f64);
        add(DVec3::new(c(0), c(1), c(2)));
    }
    for axis in 0..3 {
        for (w, inward) in [(o, low_in), (at(1.0), high_in)] {
            for i in 1..=5 {
                for j in 1..=5 {
                    let (u, v) = (at(i as f64 / 6.0), at(j as f64 / 6.0));
                    add(place(axis, w, u, v));
                    add(place(axis, inward, u, v));
                }
            }
            for u in [o, at(1.0)] {
                add(place(axis, w, u, at(0.5)));
            }
        }
    }
    if out {
        for axis in 0..3 {
            add(place(axis, low_out, at(0.5), at(0.5)));
        }
        add(place(0, high_out, at(0.5), at(0.5)));
    }
    m
}

#[test]
fn nearly_coplanar_points_are_decided_exactly_at_any_offset() {
    // Two worlds: the cube [0, 1]³ with its low faces at 0 pushed by
    // ±10⁻¹⁷ and its high face x = 1 by one ulp (1 + 2⁻⁵², 1 − 2⁻⁵³); and
    // the cube [10⁶, 10⁶ + 1024]³ pushed by one ulp (2⁻³³ ≈ 1.2·10⁻¹⁰ at
    // 10⁶), below the old tolerance 10⁻¹¹ of the diagonal there (1.8·10⁻⁸).
    let o: f64 = 1e6;
    let worlds = [
        (
            0.0,
            1.0,
            [-1e-17, 1e-17],
            [1f64.next_up(), 1f64.next_down()],
            1e-9,
        ),
        (
            o,
            1024.0,
            [o.next_down(), o.next_up()],
            [(o + 1024.0).next_up(), (o + 1024.0).next_down()],
            1e-5,
        ),
    ];
    for (o, size, low, high, tol) in worlds {
        // Without the pushed centres every extra point lies on a face, on
        // an edge, inside or on a corner: the hull is the cube, 8/12/6.
        let m = jittered_cube(o, size, low, high, false);
        let h = convex_hull(&m).unwrap();
        assert_eq!(counts(&h), (8, 12, 6), "plain cube at {o}");
        convex(&h, &points(&m), tol);
        // Each pushed centre is outside its face by one step, so it is a
        // corner and its face a pyramid: the quad gives way to four
        // triangles, one vertex, four edges and three faces more each:
        // 8 + 4, 12 + 4·4, 6 + 4·3.
        let m = jittered_cube(o, size, low, high, true);
        let h = convex_hull(&m).unwrap();
        assert_eq!(counts(&h), (12, 28, 18), "pushed cube at {o}");
        convex(&h, &points(&m), tol);
        for face in h.faces() {
            assert!(h.face_len(face).unwrap() == 3 || h.face_len(face).unwrap() == 4);
        }
        // The dual: a valid polytope, at most one face per hull corner
        // (a plane meeting the others within rounding bounds none),
        // containing the input.
        let d = dual_convex_hull(&m).unwrap();
        assert!((8..=12).contains(&d.face_count()), "dual at {o}");
        convex(&d, &points(&m), tol);
    }
}

#[test]
fn a_solid_one_rounding_step_thick_is_a_solid() {
    // A 7 × 7 grid on z = 0 with one point 10⁻¹⁷ above its centre: not
    // flat, the pyramid over the square, 5/8/5 (the grid's other points
    // lie on the base or its edges). Exactly on the plane it is flat.
    for (z, expected) in [(1e-17, Some((5, 8, 5))), (0.0, None)] {
        let mut m = Mesh::new();
        for i in 0..7 {
            for j in 0..7 {
                m.create_vertex(DVec3::new(i as f64, j as f64, 0.0))
                    .unwrap();
            }
        }
        m.create_vertex(DVec3::new(3.0, 3.0, z)).unwrap();
        match expected {
            Some(c) => {
                let h = convex_hull(&m).unwrap();
                assert_eq!(counts(&h), c);
                convex(&h, &points(&m), 1e-12);
                let d = dual_convex_hull(&m).unwrap();
                d.validate().unwrap();
                assert_eq!(d.genus(), 0);
            }
            None => {
                for r in [convex_hull(&m), dual_convex_hull(&m)] {
                    assert!(matches!(r, Err(HullError::Flat { points: 50 })), "{r:?}");
                }
            }
        }
    }
    // Collinear points but one: a line of points with one off it is
    // still flat; a second off the plane makes a tetrahedron, 4/6/4.
    let mut m = Mesh::new();
    for x in 0..9 {
        m.create_vertex(DVec3::new(x as f64, 2.0 * x as f64, 3.0 * x as f64))
            .unwrap();
    }
    m.create_vertex(DVec3::new(1.0, 0.0, 0.0)).unwrap();
    assert!(matches!(
        convex_hull(&m),
        Err(HullError::Flat { points: 10 })
    ));
    m.create_vertex(DVec3::new(0.0, 0.0, 1e-300)).unwrap();
    assert_eq!(counts(&convex_hull(&m).unwrap()), (4, 6, 4));
}
