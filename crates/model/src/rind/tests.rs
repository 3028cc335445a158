use super::*;
use crate::test_util::{counts, prim, shared_edge};
use glam::DVec3;

fn area_vector(points: &[DVec3]) -> DVec3 {
    let n = points.len();
    (0..n)
        .map(|i| points[i].cross(points[(i + 1) % n]))
        .sum::<DVec3>()
        * 0.5
}

fn no_two_gons(m: &Mesh) -> bool {
    m.faces().all(|f| m.face_len(f).unwrap() != 2)
}

#[test]
fn a_cube_rind_is_two_nested_opposite_shells() {
    let t = 0.25;
    let rind = Rind::new(prim("@cube"), t).unwrap();
    let m = rind.mesh();
    m.validate().unwrap();
    assert_eq!(counts(m), (16, 24, 12));
    let topo = m.topology();
    assert_eq!(topo.component_count(), 2);
    assert_eq!(topo.genus(), 0);
    // Each cube vertex p has the averaged normal p/√3 (three unit face normals).
    let s = 1.0 - t / 3f64.sqrt();
    for m8 in rind.unpunched() {
        let outer = m.face_positions(m8.outer).unwrap();
        let inner = m.face_positions(m8.inner).unwrap();
        assert_eq!(outer.len(), 4);
        // The inner face is the shrunk copy, reversed.
        let a = area_vector(&outer);
        let b = area_vector(&inner);
        assert!((b + a * (s * s)).length() < 1e-12, "{a} {b}");
        // Matching corners: forwards on the outer face, backwards on the inner.
        let mut ci = m8.inner_corner;
        for co in m.face_corners_from(m8.outer_corner).unwrap() {
            let p = m.position(m.corner_vertex(co).unwrap()).unwrap();
            let q = m.position(m.corner_vertex(ci).unwrap()).unwrap();
            assert!((q - p * s).length() < 1e-12);
            assert_eq!(rind.matching_corner(co), Some(ci));
            ci = m.corner_prev(ci).unwrap();
        }
    }
    assert_eq!(rind.unpunched().count(), 6);
    for i in 0..6 {
        let f = rind.outer_face(i).unwrap();
        assert_eq!(f, m.face_at(i).unwrap());
        assert_eq!(rind.matching(f).unwrap().index, i);
    }
    assert!(rind.outer_face(6).is_none());
}

#[test]
fn bad_thickness_and_degenerate_input_are_refused() {
    let cube = prim("@cube");
    for t in [0.0, -0.5, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Rind::from_mesh(&cube, t),
            Err(RindError::InvalidThickness(_))
        ));
    }
    // At √3 every inner vertex reaches the centre; beyond, the inner cube
    // is the point reflection of a smaller cube: every edge reversed.
    assert!(matches!(
        Rind::from_mesh(&cube, 3f64.sqrt()),
        Err(RindError::Collapsed { face: 0, .. })
    ));
    let err = Rind::from_mesh(&cube, 3.0).unwrap_err();
    assert!(matches!(err, RindError::Inverted { face: 0, .. }));
    assert!(err.to_string().contains("face 0"), "{err}");
    // Just below the limit is fine.
    Rind::from_mesh(&cube, 1.7)
        .unwrap()
        .mesh()
        .validate()
        .unwrap();
    assert!(matches!(
        Rind::from_mesh(&Mesh::new(), 0.1),
        Err(RindError::Empty)
    ));
    let mut lone = Mesh::new();
    lone.create_vertex(DVec3::ZERO).unwrap();
    assert!(matches!(
        Rind::from_mesh(&lone, 0.1),
        Err(RindError::NoVertexNormal { vertex: 0, .. })
    ));
    // A unit sphere offset by more than its radius.
    let sphere = prim("@sphere:1");
    assert!(matches!(
        Rind::from_mesh(&sphere, 1.5),
        Err(RindError::Inverted { .. })
    ));
}

#[test]
fn selections_the_table_does_not_hold_are_ignored() {
    let mut rind = Rind::new(prim("@cube"), 0.2).unwrap();
    let top = rind.outer_face(5).unwrap();
    let inner_top = rind.matching(top).unwrap().inner;
    let out = rind.punch(top).unwrap();
    let report = out.report().unwrap().clone();
    assert_eq!(report.index, 5);
    assert_eq!(report.pipe_edges.len(), 4);
    rind.mesh().validate().unwrap();
    assert_eq!(counts(rind.mesh()), (16, 28, 14));
    assert_eq!(rind.mesh().topology().component_count(), 1);
    let before = rind.mesh().to_raw();
    // Again, by index and by the (now stale or reused) id.
    assert_eq!(
        rind.punch_index(5).unwrap(),
        PunchOutcome::NotPunchable {
            reason: NotPunchable::AlreadyPunched { index: 5 }
        }
    );
    for f in [top, inner_top] {
        let out = rind.peel(f).unwrap();
        assert!(matches!(
            out,
            PunchOutcome::NotPunchable {
                reason: NotPunchable::Stale { .. } | NotPunchable::NotInTable { .. }
            }
        ));
    }
    // A wall face of the pipe, and an inner face.
    let wall = rind.mesh().edge_faces(report.pipe_edges[0]).unwrap()[0];
    let inner_bottom = rind.matching(rind.outer_face(0).unwrap()).unwrap().inner;
    for f in [wall, inner_bottom] {
        assert_eq!(
            rind.punch(f).unwrap(),
            PunchOutcome::NotPunchable {
                reason: NotPunchable::NotInTable { face: f }
            }
        );
    }
    assert_eq!(rind.mesh().to_raw(), before);
    // An index out of range is an error, and a batch with one does nothing.
    assert!(matches!(
        rind.punch_indices(&[0, 6]),
        Err(RindError::NoSuchFace { index: 6, count: 6 })
    ));
    assert_eq!(rind.mesh().to_raw(), before);
    // Repeats inside a batch are reported, not errors.
    let outs = rind.punch_indices(&[0, 0, 5]).unwrap();
    assert!(outs[0].report().is_some());
    assert!(outs[1].report().is_none() && outs[2].report().is_none());
    rind.mesh().validate().unwrap();
    assert_eq!(rind.mesh().genus(), 1);
}

#[test]
fn peeling_two_neighbours_removes_the_wall_between_them() {
    let mut rind = Rind::new(prim("@cube"), 0.2).unwrap();
    // Faces 0 (−z) and 1 (−y) share an edge.
    let a = rind.peel_index(0).unwrap().report().unwrap().clone();
    assert_eq!(a.walls_removed, 0);
    let b = rind.peel_index(1).unwrap().report().unwrap().clone();
    assert_eq!(
        (b.walls_removed, b.edges_deleted, b.vertices_deleted),
        (1, 4, 0)
    );
    assert_eq!(b.two_gons_removed, 0);
    let m = rind.mesh();
    m.validate().unwrap();
    // 2V; 2E + 4 + 4 − 4; 2F + 2 + 2 − 2.
    assert_eq!(counts(m), (16, 28, 14));
    assert_eq!(m.genus(), 0);
    assert_eq!(m.topology().component_count(), 1);
    assert!(no_two_gons(m));
}

#[test]
fn an_open_surface_becomes_a_closed_slab() {
    let plane = prim("@plane:2:2");
    assert_eq!(plane.hole_count(), 1);
    let mut rind = Rind::new(plane, 0.1).unwrap();
    assert_eq!(rind.rims(), 1);
    let m = rind.mesh();
    m.validate().unwrap();
    // V 9, E 12, 4 quads and a hole of 8 corners: 2V; 2E + 8; 2·5 − 2 + 8.
    assert_eq!(counts(m), (18, 32, 16));
    assert_eq!(m.hole_count(), 0);
    assert_eq!(m.genus(), 0);
    assert_eq!(rind.unpunched().count(), 4);
    // The hole face's index is not punchable.
    assert_eq!(
        rind.punch_index(4).unwrap(),
        PunchOutcome::NotPunchable {
            reason: NotPunchable::HoleFace { index: 4 }
        }
    );
    // The inner plane lies 0.1 below.
    let f = rind.outer_face(0).unwrap();
    let inner = rind.matching(f).unwrap().inner;
    for p in rind.mesh().face_positions(inner).unwrap() {
        assert!((p.z + 0.1).abs() < 1e-15);
    }
    // Punching two faces of the slab: genus 2.
    rind.punch_indices(&[0, 3]).unwrap();
    rind.mesh().validate().unwrap();
    assert_eq!(rind.mesh().genus(), 2);
    // Peeling face 1 (between 0 and 3, at the slab's corner) removes its
    // walls to both holes and the two rim walls along the border; its
    // corner vertex loses every pipe edge, so it and its copy go.
    let r = rind.peel_index(1).unwrap().report().unwrap().clone();
    assert_eq!((r.walls_removed, r.vertices_deleted), (4, 2), "{r:?}");
    rind.mesh().validate().unwrap();
    assert!(no_two_gons(rind.mesh()));
}

#[test]
fn faces_are_addressed_by_their_slot_in_an_edited_mesh() {
    // Split the top of a cube (a new face in slot 6), then merge faces 0
    // and 1 by deleting their shared edge (one slot dies).
    let mut m = prim("@cube");
    let top = m.face_at(5).unwrap();
    let cs: Vec<_> = m.face_corners(top).unwrap().collect();
    m.insert_edge(cs[0], cs[2]).unwrap();
    let (f0, f1) = (m.face_at(0).unwrap(), m.face_at(1).unwrap());
    let shared = shared_edge(&m, f0, f1).unwrap();
    m.delete_edge(shared).unwrap();
    m.validate().unwrap();
    let live: Vec<usize> = m.faces().map(|f| f.index()).collect();
    assert_eq!(live.len(), 6);
    let dead = (0..7).find(|i| !live.contains(i)).unwrap();
    let mut rind = Rind::from_mesh(&m, 0.1).unwrap();
    rind.mesh().validate().unwrap();
    assert_eq!(rind.input_face_slots(), 7);
    assert!(rind.outer_face(dead).is_none());
    assert!(matches!(
        rind.punch_index(dead),
        Err(RindError::NoSuchFace { .. })
    ));
    for &i in &live {
        let input = m.face_positions(m.face_at(i).unwrap()).unwrap();
        let outer = rind.outer_face(i).unwrap();
        assert_eq!(rind.mesh().face_positions(outer).unwrap(), input);
        assert_eq!(rind.matching(outer).unwrap().index, i);
    }
    // Punch every face: genus 2·0 + 6 − 1.
    for &i in &live {
        rind.punch_index(i).unwrap();
    }
    rind.mesh().validate().unwrap();
    assert_eq!(rind.mesh().genus(), 5);
}

#[test]
fn each_component_gets_its_own_rind() {
    // Two cubes: four shells; one punch in each cube joins its two shells.
    let mut raw = prim("@cube").to_raw();
    let mut b = raw.clone();
    for p in &mut b.positions {
        *p += DVec3::X * 5.0;
    }
    raw.append(&b).unwrap();
    let m = Mesh::from_raw(&raw).unwrap();
    let mut rind = Rind::new(m, 0.2).unwrap();
    assert_eq!(rind.mesh().topology().component_count(), 4);
    rind.punch_indices(&[5, 6]).unwrap();
    let topo = rind.mesh().topology();
    assert_eq!(topo.component_count(), 2);
    assert_eq!(topo.genus(), 0);
}
