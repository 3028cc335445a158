//! Unit tests of the four fundamental operators: exact changes in V, E, F,
//! components and genus, inverse pairs, and refusal of bad operands.

use glam::DVec3;

use crate::test_util::{
    canonical, check, corners_at, counts, cube, cube_face, cube_with_dangling_edge,
    cube_with_handle, loop_at_first_vertex, tetrahedron, torus,
};
use crate::{Error, Mesh};

#[test]
fn create_vertex_makes_a_point_sphere() {
    let mut m = Mesh::new();
    let (v, f, c) = m.create_vertex(DVec3::new(1.0, 2.0, 3.0)).unwrap();
    check(&m);
    assert_eq!(counts(&m), (1, 0, 1, 1, 0));
    assert!(m.is_point_sphere(f).unwrap());
    assert_eq!(m.corner_vertex(c).unwrap(), v);
    assert_eq!(m.corner_edge(c).unwrap(), None);
    assert_eq!(m.valence(v).unwrap(), 0);
    assert_eq!(m.euler_characteristic(), 2);
}

#[test]
fn create_vertex_refuses_non_finite_points() {
    let mut m = cube();
    let before = canonical(&m);
    for p in [
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(0.0, f64::INFINITY, 0.0),
    ] {
        assert!(matches!(m.create_vertex(p), Err(Error::NonFinite(_))));
    }
    assert_eq!(canonical(&m), before);
    assert_eq!(m.vertex_count(), 8);
}

#[test]
fn delete_vertex_removes_only_point_spheres() {
    let mut m = cube();
    let (v, _, _) = m.create_vertex(DVec3::ZERO).unwrap();
    assert_eq!(counts(&m), (9, 12, 7, 2, 0));
    let cube_vertex = m.vertices().next().unwrap();
    let before = canonical(&m);
    assert_eq!(
        m.delete_vertex(cube_vertex),
        Err(Error::NotPointSphere(cube_vertex))
    );
    assert_eq!(canonical(&m), before);
    m.delete_vertex(v).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 12, 6, 1, 0));
    // The handle is now stale.
    assert!(matches!(m.delete_vertex(v), Err(Error::Stale { .. })));
    assert!(matches!(m.position(v), Err(Error::Stale { .. })));
}

#[test]
fn insert_edge_in_one_face_splits_it() {
    let (mut m, _, cs) = cube_face(0);
    let e = m.insert_edge(cs[0], cs[2]).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 13, 7, 1, 0));
    let [fa, fb] = m.edge_faces(e).unwrap();
    assert_ne!(fa, fb);
    assert_eq!(m.face_len(fa).unwrap(), 3);
    assert_eq!(m.face_len(fb).unwrap(), 3);
    // The old corners keep their outgoing edges.
    assert!(m.corner_edge(cs[0]).unwrap().is_some());
    assert_ne!(m.corner_edge(cs[0]).unwrap(), Some(e));
}

#[test]
fn insert_edge_between_adjacent_corners_makes_a_two_gon() {
    let (mut m, _, cs) = cube_face(0);
    let e = m.insert_edge(cs[0], cs[1]).unwrap();
    check(&m);
    let lens: Vec<usize> = m
        .edge_faces(e)
        .unwrap()
        .iter()
        .map(|&f| m.face_len(f).unwrap())
        .collect();
    assert!(lens.contains(&2) && lens.contains(&4), "{lens:?}");
    assert_eq!(counts(&m), (8, 13, 7, 1, 0));
}

#[test]
fn insert_edge_between_faces_of_one_component_adds_a_handle() {
    let (m, e) = cube_with_handle();
    check(&m);
    assert_eq!(counts(&m), (8, 13, 5, 1, 1));
    let [fa, fb] = m.edge_faces(e).unwrap();
    assert_eq!(fa, fb);
    assert_eq!(m.face_len(fa).unwrap(), 10);
}

#[test]
fn insert_edge_between_components_joins_them() {
    let mut m = cube();
    let c1 = m.face_corner(m.faces().next().unwrap()).unwrap();
    let (_, _, c2) = m.create_vertex(DVec3::splat(5.0)).unwrap();
    assert_eq!(counts(&m).3, 2);
    let e = m.insert_edge(c1, c2).unwrap();
    check(&m);
    // A dangling edge to a valence-1 vertex: the point-sphere's corner is reused.
    assert_eq!(counts(&m), (9, 13, 6, 1, 0));
    let [v1, v2] = m.edge_vertices(e).unwrap();
    assert_eq!(m.valence(v2).unwrap() + m.valence(v1).unwrap(), 1 + 4);
}

#[test]
fn insert_edge_between_two_point_spheres_makes_a_segment() {
    let mut m = Mesh::new();
    let (_, _, a) = m.create_vertex(DVec3::ZERO).unwrap();
    let (_, _, b) = m.create_vertex(DVec3::X).unwrap();
    let e = m.insert_edge(a, b).unwrap();
    check(&m);
    assert_eq!(counts(&m), (2, 1, 1, 1, 0));
    let [fa, fb] = m.edge_faces(e).unwrap();
    assert_eq!(fa, fb);
    assert_eq!(m.face_len(fa).unwrap(), 2);
    // Deleting restores two point-spheres with the same corner handles.
    m.delete_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (2, 0, 2, 2, 0));
    assert!(m.is_point_sphere(m.corner_face(a).unwrap()).unwrap());
    assert!(m.is_point_sphere(m.corner_face(b).unwrap()).unwrap());
}

#[test]
fn insert_edge_makes_self_loops_between_corners_of_one_vertex() {
    // Two corners of one vertex in one face: the tetrahedron's vertex 0
    // has three corners, in three faces; join two faces first so that a
    // face holds two corners of vertex 0.
    let mut m = tetrahedron();
    let (e, v0, _) = loop_at_first_vertex(&mut m);
    check(&m);
    assert!(m.is_self_loop(e).unwrap());
    // Two different faces: a handle made of a self-loop.
    assert_eq!(counts(&m), (4, 7, 3, 1, 1));
    let f = m.edge_faces(e).unwrap()[0];
    let at_v0 = corners_at(&m, f, v0);
    assert!(at_v0.len() >= 2);
    let loop2 = m.insert_edge(at_v0[0], at_v0[1]).unwrap();
    check(&m);
    assert!(m.is_self_loop(loop2).unwrap());
    assert_eq!(counts(&m), (4, 8, 4, 1, 1));
}

#[test]
fn insert_edge_refuses_bad_operands_and_leaves_the_mesh() {
    let mut m = cube();
    let before = canonical(&m);
    let c = m.corners().next().unwrap();
    assert_eq!(m.insert_edge(c, c), Err(Error::SameCorner(c)));
    let mut other = cube();
    let (_, _, foreign) = other.create_vertex(DVec3::ZERO).unwrap();
    // A handle of another mesh whose slot this mesh never used.
    assert!(matches!(
        m.insert_edge(c, foreign),
        Err(Error::Stale { .. })
    ));
    assert_eq!(canonical(&m), before);
    check(&m);
}

#[test]
fn delete_edge_merging_two_faces() {
    let mut m = cube();
    let e = m.edges().next().unwrap();
    m.delete_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 11, 5, 1, 0));
    assert!(matches!(m.delete_edge(e), Err(Error::Stale { .. })));
}

#[test]
fn delete_edge_is_the_inverse_of_insert_edge() {
    for mesh in [cube(), tetrahedron(), torus(4, 3)] {
        let corners: Vec<_> = mesh.corners().collect();
        for (i, &c1) in corners.iter().enumerate() {
            for &c2 in corners.iter().skip(i + 1).step_by(3) {
                let mut m = mesh.clone();
                let before = canonical(&m);
                let e = m.insert_edge(c1, c2).unwrap();
                check(&m);
                m.delete_edge(e).unwrap();
                check(&m);
                assert_eq!(canonical(&m), before);
                assert_eq!(counts(&m), counts(&mesh));
                // The operand corners survive the round trip.
                assert!(m.contains_corner(c1) && m.contains_corner(c2));
            }
        }
    }
}

#[test]
fn insert_edge_is_the_inverse_of_delete_edge() {
    for mesh in [cube(), torus(3, 3)] {
        for e in mesh.edges().collect::<Vec<_>>() {
            let mut m = mesh.clone();
            let before = canonical(&m);
            let [a, b] = m.edge_corners(e).unwrap();
            // After deletion the sectors are those of next(b) and next(a).
            let (na, nb) = (m.corner_next(a).unwrap(), m.corner_next(b).unwrap());
            m.delete_edge(e).unwrap();
            check(&m);
            m.insert_edge(nb, na).unwrap();
            check(&m);
            assert_eq!(canonical(&m), before);
        }
    }
}

#[test]
fn deleting_a_handle_edge_lowers_the_genus() {
    let (mut m, e) = cube_with_handle();
    assert_eq!(m.genus(), 1);
    m.delete_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 12, 6, 1, 0));
}

#[test]
fn deleting_a_dangling_edge_leaves_a_point_sphere() {
    let (mut m, e, v, c2) = cube_with_dangling_edge(DVec3::splat(3.0));
    m.delete_edge(e).unwrap();
    check(&m);
    assert_eq!(counts(&m), (9, 12, 7, 2, 0));
    assert!(m.is_point_sphere(m.corner_face(c2).unwrap()).unwrap());
    m.delete_vertex(v).unwrap();
    check(&m);
}

#[test]
fn monogons_bounded_by_self_loops_are_represented() {
    // Delete an edge so that a face is left with a single corner whose
    // edge is a self-loop: make a loop at a cube vertex, then a two-gon
    // beside it, then delete the two-gon's other edge.
    let mut m = cube();
    // Loop between two corners of v0 in different faces (a handle).
    let (l, v0, _) = loop_at_first_vertex(&mut m);
    check(&m);
    let f = m.edge_faces(l).unwrap()[0];
    let at = corners_at(&m, f, v0);
    // A second loop in the same face, adjacent: splits off a face made of loops.
    let l2 = m.insert_edge(at[0], at[1]).unwrap();
    check(&m);
    let mut found_monogon = false;
    for e in [l, l2] {
        let mut mm = m.clone();
        for g in mm.edges().collect::<Vec<_>>() {
            if g == e {
                continue;
            }
            let mut t = mm.clone();
            t.delete_edge(g).unwrap();
            check(&t);
            if t.faces()
                .any(|f| t.face_len(f).unwrap() == 1 && !t.is_point_sphere(f).unwrap())
            {
                found_monogon = true;
                // Deleting the monogon's loop is fine too.
                let f = t
                    .faces()
                    .find(|&f| t.face_len(f).unwrap() == 1 && !t.is_point_sphere(f).unwrap())
                    .unwrap();
                let c = t.face_corner(f).unwrap();
                let lp = t.corner_edge(c).unwrap().unwrap();
                t.delete_edge(lp).unwrap();
                check(&t);
            }
        }
        mm.delete_edge(e).unwrap();
        check(&mm);
    }
    assert!(found_monogon, "no deletion produced a monogon");
}

#[test]
fn stale_handles_are_errors_not_wrong_answers() {
    let mut m = cube();
    let e = m.edges().next().unwrap();
    m.delete_edge(e).unwrap();
    // The freed slot is reused by the next edge; the old handle stays stale.
    let f = m.faces().next().unwrap();
    let cs: Vec<_> = m.face_corners(f).unwrap().collect();
    let e2 = m.insert_edge(cs[0], cs[2]).unwrap();
    assert_eq!(e2.index(), e.index());
    assert_ne!(e2, e);
    assert!(matches!(m.edge_corners(e), Err(Error::Stale { .. })));
    assert!(m.edge_corners(e2).is_ok());
}

#[test]
fn point_sphere_to_point_sphere_chain_and_back() {
    let mut m = Mesh::new();
    let mut corners = Vec::new();
    for i in 0..5 {
        corners.push(m.create_vertex(DVec3::new(i as f64, 0.0, 0.0)).unwrap().2);
    }
    let mut edges = Vec::new();
    for w in corners.windows(2) {
        edges.push(m.insert_edge(w[0], w[1]).unwrap());
        check(&m);
    }
    // A tree: one face walking each edge twice.
    assert_eq!(counts(&m), (5, 4, 1, 1, 0));
    for e in edges.into_iter().rev() {
        m.delete_edge(e).unwrap();
        check(&m);
    }
    assert_eq!(counts(&m), (5, 0, 5, 5, 0));
}

#[test]
fn raw_append_renumbers_and_keeps_hole_flags() {
    let a = cube().to_raw();
    assert!(a.holes.is_empty(), "a closed cube has no hole flags");
    // No flags on either side stay no flags.
    let mut joined = a.clone();
    joined.append(&a).unwrap();
    assert_eq!(joined.face_count(), 12);
    assert!(joined.holes.is_empty());
    let m = Mesh::from_raw(&joined).unwrap();
    check(&m);
    assert_eq!(counts(&m), (16, 24, 12, 2, 0));
    // A flag on the appended side lands on its face, renumbered.
    let mut flagged = a.clone();
    flagged.holes = vec![false; 6];
    flagged.holes[2] = true;
    let mut x = a;
    x.append(&flagged).unwrap();
    assert_eq!(x.holes.len(), 12);
    assert_eq!((0..12).filter(|&f| x.is_hole(f)).collect::<Vec<_>>(), [8]);
}

#[test]
fn surface_faces_leave_out_holes_in_slot_order() {
    let mut m = cube();
    assert_eq!(
        m.surface_faces().collect::<Vec<_>>(),
        m.faces().collect::<Vec<_>>()
    );
    let f = m.face_at(2).unwrap();
    m.set_hole(f, true).unwrap();
    let want: Vec<_> = m.faces().filter(|&g| g != f).collect();
    assert_eq!(m.surface_faces().collect::<Vec<_>>(), want);
}
