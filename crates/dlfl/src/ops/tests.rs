//! Unit tests of the chapter III operators: exact counts and genus.

use glam::DVec3;

use crate::test_util::{
    canonical, check, counts, cube, cube_face, cube_with_dangling_edge, loop_at_first_vertex,
    tetrahedron, torus,
};
use crate::{Error, Mesh};

#[test]
fn delete_edge_with_cleanup_removes_the_point_spheres_it_leaves() {
    let (mut m, e, v, _) = cube_with_dangling_edge(DVec3::splat(2.0));
    let deleted = m.delete_edge_with_cleanup(e).unwrap();
    check(&m);
    assert_eq!(deleted, vec![v]);
    assert_eq!(counts(&m), (8, 12, 6, 1, 0));
    // A lone segment: both ends go.
    let mut s = Mesh::new();
    let (_, _, a) = s.create_vertex(DVec3::ZERO).unwrap();
    let (_, _, b) = s.create_vertex(DVec3::X).unwrap();
    let e = s.insert_edge(a, b).unwrap();
    assert_eq!(s.delete_edge_with_cleanup(e).unwrap().len(), 2);
    assert!(s.is_empty());
    // Figure 8: an ordinary edge leaves no point-sphere.
    let e = m.edges().next().unwrap();
    assert!(m.delete_edge_with_cleanup(e).unwrap().is_empty());
    assert_eq!(counts(&m), (8, 11, 5, 1, 0));
}

#[test]
fn subdivide_edge_adds_a_midpoint_and_keeps_corners() {
    let mut m = cube();
    let corners: Vec<_> = m.corners().collect();
    let e = m.edges().next().unwrap();
    let [v1, v2] = m.edge_vertices(e).unwrap();
    let mid = (m.position(v1).unwrap() + m.position(v2).unwrap()) / 2.0;
    let faces = m.edge_faces(e).unwrap();
    let s = m.subdivide_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (9, 13, 6, 1, 0));
    assert_eq!(m.position(s.vertex).unwrap(), mid);
    assert_eq!(m.edge_vertices(s.edges[0]).unwrap(), [v1, s.vertex]);
    assert_eq!(m.edge_vertices(s.edges[1]).unwrap(), [s.vertex, v2]);
    for f in faces {
        assert_eq!(m.face_len(f).unwrap(), 5);
    }
    assert!(corners.iter().all(|&c| m.contains_corner(c)));
}

#[test]
fn subdivide_edge_matches_the_thesis_sequence() {
    for mesh in [cube(), tetrahedron(), torus(3, 4)] {
        for e in mesh.edges().collect::<Vec<_>>() {
            let mut direct = mesh.clone();
            let mut thesis = mesh.clone();
            direct.subdivide_edge(e).unwrap();
            thesis.subdivide_edge_fundamental(e).unwrap();
            check(&direct);
            check(&thesis);
            assert_eq!(canonical(&direct), canonical(&thesis));
        }
    }
}

#[test]
fn subdivide_self_loop() {
    let mut m = tetrahedron();
    let (lp, v0, _) = loop_at_first_vertex(&mut m);
    let before = counts(&m);
    let s = m.subdivide_edge(lp).unwrap();
    check(&m);
    assert_eq!(
        counts(&m),
        (before.0 + 1, before.1 + 1, before.2, 1, before.4)
    );
    assert_eq!(m.position(s.vertex).unwrap(), m.position(v0).unwrap());
}

#[test]
fn trisect_edge_places_thirds() {
    let mut m = cube();
    let e = m.edges().next().unwrap();
    let [v1, v2] = m.edge_vertices(e).unwrap();
    let (p1, p2) = (m.position(v1).unwrap(), m.position(v2).unwrap());
    let (vs, es) = m.trisect_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (10, 14, 6, 1, 0));
    assert!(m.position(vs[0]).unwrap().distance(p1.lerp(p2, 1.0 / 3.0)) < 1e-15);
    assert!(m.position(vs[1]).unwrap().distance(p1.lerp(p2, 2.0 / 3.0)) < 1e-15);
    assert_eq!(m.edge_vertices(es[0]).unwrap(), [v1, vs[0]]);
    assert_eq!(m.edge_vertices(es[1]).unwrap(), [vs[0], vs[1]]);
    assert_eq!(m.edge_vertices(es[2]).unwrap(), [vs[1], v2]);
}

#[test]
fn pipe_between_opposite_cube_faces_makes_a_torus() {
    let mut m = cube();
    let faces: Vec<_> = m.faces().collect();
    // Faces 0 (z=0) and 1 (z=1): match corners at vertices 0 and 4.
    let c1 = m.face_corner(faces[0]).unwrap();
    let v0 = m.corner_vertex(c1).unwrap();
    let target = m.vertices().nth(4).unwrap();
    let c2 = m.corner_of(faces[1], target).unwrap().unwrap();
    assert_eq!(
        m.position(v0).unwrap() + DVec3::Z,
        m.position(target).unwrap()
    );
    let edges = m.create_pipe(c1, c2).unwrap();
    check(&m);
    assert_eq!(edges.len(), 4);
    assert_eq!(counts(&m), (8, 16, 8, 1, 1));
    // Each pipe edge is vertical: the corners were matched in reverse order.
    for e in edges {
        let [a, b] = m.edge_vertices(e).unwrap();
        let d = m.position(a).unwrap() - m.position(b).unwrap();
        assert_eq!(d.x, 0.0);
        assert_eq!(d.y, 0.0);
        assert!(m.face_len(m.edge_faces(e).unwrap()[0]).unwrap() == 4);
    }
}

#[test]
fn pipe_between_components_joins_them() {
    let mut m = cube();
    let mut other = cube();
    for v in other.vertices().collect::<Vec<_>>() {
        let p = other.position(v).unwrap();
        other
            .set_position(v, p + DVec3::new(0.0, 0.0, 3.0))
            .unwrap();
    }
    // Append the second cube through raw parts.
    let mut raw = m.to_raw();
    raw.append(&other.to_raw()).unwrap();
    m = Mesh::from_raw(&raw).unwrap();
    assert_eq!(counts(&m), (16, 24, 12, 2, 0));
    let c1 = m.face_corner(m.face_at(1).unwrap()).unwrap(); // top of the first cube
    let c2 = m.face_corner(m.face_at(6).unwrap()).unwrap(); // bottom of the second
    m.create_pipe(c1, c2).unwrap();
    check(&m);
    assert_eq!(counts(&m), (16, 28, 14, 1, 0));
}

#[test]
fn pipe_matches_corner_counts_by_subdividing_the_smaller_face() {
    // A triangle and a quad of one mesh: split the cube's top into two
    // triangles, then pipe a triangle to the bottom quad.
    let (mut m, _, cs) = cube_face(1);
    m.insert_edge(cs[0], cs[2]).unwrap();
    let tri = m.corner_face(cs[0]).unwrap();
    assert_eq!(m.face_len(tri).unwrap(), 3);
    let bottom = m.face_at(0).unwrap();
    let before = counts(&m);
    m.create_pipe(m.face_corner(tri).unwrap(), m.face_corner(bottom).unwrap())
        .unwrap();
    check(&m);
    let after = counts(&m);
    // One subdivision (V+1, E+1), then a 4-edge pipe: E+4, F+2, genus+1.
    assert_eq!(after, (before.0 + 1, before.1 + 5, before.2 + 2, 1, 1));
}

#[test]
fn pipe_refuses_bad_operands() {
    let (mut m, f, cs) = cube_face(0);
    let before = canonical(&m);
    assert_eq!(m.create_pipe(cs[0], cs[1]), Err(Error::SameFace(f)));
    let (_, ps, pc) = m.create_vertex(DVec3::splat(3.0)).unwrap();
    assert_eq!(m.create_pipe(cs[0], pc), Err(Error::PointSphereFace(ps)));
    let mut n = m.clone();
    n.delete_vertex(n.corner_vertex(pc).unwrap()).unwrap();
    assert_eq!(canonical(&n), before);
}

#[test]
fn face_manifold_is_a_two_faced_sphere() {
    let pts: Vec<DVec3> = (0..5)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 5.0;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let mut m = Mesh::new();
    let fm = m.create_face_manifold(&pts).unwrap();
    check(&m);
    assert_eq!(counts(&m), (5, 5, 2, 1, 0));
    assert_eq!(m.face_positions(fm.front).unwrap(), pts);
    let mut back = m.face_positions(fm.back).unwrap();
    back.reverse();
    // The back face reads the same points backwards (from some start).
    let k = back.iter().position(|p| *p == pts[0]).unwrap();
    back.rotate_left(k);
    assert_eq!(back, pts);
    assert!(Mesh::new().create_face_manifold(&pts[..1]).is_err());
    assert!(
        Mesh::new()
            .create_face_manifold(&[DVec3::ZERO, DVec3::NAN])
            .is_err()
    );
}

#[test]
fn connect_edges_in_one_face_makes_three() {
    let (mut m, _, cs) = cube_face(0);
    let (quad, es) = m.connect_edges(cs[0], cs[2]).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 14, 8, 1, 0));
    assert_eq!(m.face_len(quad).unwrap(), 4);
    for e in es {
        let fs = m.edge_faces(e).unwrap();
        assert!(fs.contains(&quad));
    }
}

#[test]
fn connect_edges_across_faces_adds_a_handle() {
    let mut m = cube();
    let (f0, f1) = (m.face_at(0).unwrap(), m.face_at(1).unwrap());
    let (c1, c2) = (m.face_corner(f0).unwrap(), m.face_corner(f1).unwrap());
    let (quad, _) = m.connect_edges(c1, c2).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 14, 6, 1, 1));
    assert_eq!(m.face_len(quad).unwrap(), 4);
}

#[test]
fn connect_edges_refuses_degenerate_pairs() {
    let (mut m, _, cs) = cube_face(0);
    let e = m.corner_edge(cs[0]).unwrap().unwrap();
    let [a, b] = m.edge_corners(e).unwrap();
    assert_eq!(m.connect_edges(a, b), Err(Error::SameEdge(e)));
    assert!(m.connect_edges(cs[0], cs[1]).is_err());
    assert!(m.connect_edges(cs[1], cs[0]).is_err());
    check(&m);
    assert_eq!(counts(&m), (8, 12, 6, 1, 0));
}

#[test]
fn collapse_edge_of_a_cube() {
    let mut m = cube();
    let e = m.edges().next().unwrap();
    let [v1, v2] = m.edge_vertices(e).unwrap();
    let mid = (m.position(v1).unwrap() + m.position(v2).unwrap()) / 2.0;
    let kept = m.collapse_edge(e).unwrap();
    check(&m);
    assert_eq!(kept, v1);
    assert!(!m.contains_vertex(v2));
    assert_eq!(m.position(v1).unwrap(), mid);
    assert_eq!(counts(&m), (7, 11, 6, 1, 0));
    assert_eq!(
        m.faces().filter(|&f| m.face_len(f).unwrap() == 3).count(),
        2
    );
}

#[test]
fn collapse_edge_of_triangles_leaves_two_gons_that_cleanup_removes() {
    let mut m = tetrahedron();
    let e = m.edges().next().unwrap();
    m.collapse_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (3, 5, 4, 1, 0));
    assert_eq!(
        m.faces().filter(|&f| m.face_len(f).unwrap() == 2).count(),
        2
    );
    assert_eq!(m.remove_two_gons(), 2);
    check(&m);
    assert_eq!(counts(&m), (3, 3, 2, 1, 0));
}

#[test]
fn collapse_keeps_genus_on_a_torus_everywhere() {
    let base = torus(4, 4);
    for e in base.edges().collect::<Vec<_>>() {
        let mut m = base.clone();
        m.collapse_edge(e).unwrap();
        check(&m);
        assert_eq!(counts(&m), (15, 31, 16, 1, 1));
    }
}

#[test]
fn collapse_refuses_self_loops_and_handles_dangling_edges() {
    let mut m = tetrahedron();
    let (lp, _, _) = loop_at_first_vertex(&mut m);
    assert_eq!(m.collapse_edge(lp), Err(Error::SelfLoop(lp)));
    let (mut d, e, v, _) = cube_with_dangling_edge(DVec3::splat(5.0));
    let kept = d.collapse_edge(e).unwrap();
    check(&d);
    assert!(!d.contains_vertex(v));
    assert_ne!(kept, v);
    assert_eq!(counts(&d), (8, 12, 6, 1, 0));
    // A lone segment collapses to a point-sphere.
    let mut s = Mesh::new();
    let (a, _, ca) = s.create_vertex(DVec3::ZERO).unwrap();
    let (_, _, cb) = s.create_vertex(DVec3::X).unwrap();
    let e = s.insert_edge(ca, cb).unwrap();
    assert_eq!(s.collapse_edge(e).unwrap(), a);
    check(&s);
    assert_eq!(counts(&s), (1, 0, 1, 1, 0));
    assert_eq!(s.position(a).unwrap(), DVec3::new(0.5, 0.0, 0.0));
}

#[test]
fn reverse_component_twice_is_identity_and_flips_walks() {
    let mut m = torus(3, 4);
    let before = canonical(&m);
    let f = m.face_at(0).unwrap();
    let walk = m.face_vertices(f).unwrap();
    m.reverse_component(f).unwrap();
    check(&m);
    let mut rev = m.face_vertices(f).unwrap();
    rev.reverse();
    let k = rev.iter().position(|v| *v == walk[0]).unwrap();
    rev.rotate_left(k);
    assert_eq!(rev, walk);
    m.reverse_component(f).unwrap();
    check(&m);
    assert_eq!(canonical(&m), before);
}

#[test]
fn reverse_faces_needs_whole_components() {
    let mut m = cube();
    let f = m.face_at(0).unwrap();
    let before = canonical(&m);
    assert_eq!(m.reverse_faces(&[f]), Err(Error::NotWholeComponents(f)));
    assert_eq!(canonical(&m), before);
    let all: Vec<_> = m.faces().collect();
    m.reverse_faces(&all).unwrap();
    check(&m);
    // A point-sphere and a self-loop handle reverse too.
    let (_, ps, _) = m.create_vertex(DVec3::ZERO).unwrap();
    m.reverse_faces(&[ps]).unwrap();
    let (_, _, cs) = loop_at_first_vertex(&mut m);
    let f = m.corner_face(cs[0]).unwrap();
    m.reverse_component(f).unwrap();
    check(&m);
}

#[test]
fn remove_two_gons_merges_chains_and_keeps_holes() {
    let (mut m, _, cs) = cube_face(0);
    // Stack three two-gons on one edge of face 0.
    m.insert_edge(cs[0], cs[1]).unwrap();
    let c0_face = m.corner_face(cs[0]).unwrap();
    let inner: Vec<_> = m.face_corners(c0_face).unwrap().collect();
    m.insert_edge(inner[0], inner[1]).unwrap();
    check(&m);
    let before = counts(&m);
    assert_eq!(
        m.faces().filter(|&f| m.face_len(f).unwrap() == 2).count(),
        2
    );
    assert_eq!(m.remove_two_gons(), 2);
    check(&m);
    assert_eq!(counts(&m), (8, before.1 - 2, before.2 - 2, 1, 0));
    assert_eq!(canonical(&m), canonical(&cube()));
    // A two-gon hole is left alone.
    let (mut h, _, cs) = cube_face(0);
    let e = h.insert_edge(cs[0], cs[1]).unwrap();
    let two = h
        .edge_faces(e)
        .unwrap()
        .into_iter()
        .find(|&g| h.face_len(g).unwrap() == 2)
        .unwrap();
    h.set_hole(two, true).unwrap();
    assert_eq!(h.remove_two_gons(), 0);
}
