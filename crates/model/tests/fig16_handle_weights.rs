//! Figure 16 (§IV.2): the weights shape the Hermite curve. Negative
//! weights point its ends into the surface and make a hole (a tunnel)
//! instead of a handle; zero weights give a straight handle.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::DVec3;
use holey_model::handle::{HandleParams, Orientation, create_handle};
use soups_and_oracles::*;

/// The corner of face `f` whose vertex has the given x and y.
fn corner_at_xy(m: &holey_dlfl::Mesh, f: usize, x: f64, y: f64) -> holey_dlfl::CornerId {
    m.face_corners(m.face_at(f).unwrap())
        .unwrap()
        .find(|&c| {
            let p = m.position(m.corner_vertex(c).unwrap()).unwrap();
            (p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12
        })
        .unwrap()
}

#[test]
fn negative_weights_tunnel_through_the_solid() {
    // @cube:3: the middle top face (49) and the middle bottom face (4).
    let m0 = prim("@cube:3");
    let top = m0.face_at(49).unwrap();
    let c1 = m0.face_corner(top).unwrap();
    let p = m0.position(m0.corner_vertex(c1).unwrap()).unwrap();
    let c2 = corner_at_xy(&m0, 4, p.x, p.y);
    let mut m = m0.clone();
    let r = create_handle(&mut m, c1, c2, &HandleParams::new(4, -1.0, -1.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1);
    assert_eq!(r.plan.orientation, Orientation::AgainstTangent);
    // Every section vertex is strictly inside the cube, below the top face.
    for vs in &r.sections {
        for &v in vs {
            let q = m.position(v).unwrap();
            assert!(q.abs().max_element() < 1.0 - 1e-9, "{q}");
        }
        // Sections face back towards f1 (+z), against the downward tangent.
        let pts: Vec<DVec3> = vs.iter().map(|&v| m.position(v).unwrap()).collect();
        assert!(shoelace(&pts).normalize().dot(DVec3::Z) > 1.0 - 1e-12);
    }
    // The tunnel's walls face into the tunnel: each pipe quad's normal
    // points towards the z axis through the face centres.
    let axis = DVec3::new(0.0, 0.0, 0.0);
    for pipe in &r.pipes {
        for &e in pipe {
            for f in m.edge_faces(e).unwrap() {
                let pts = m.face_positions(f).unwrap();
                let c = vertex_average(&pts);
                let out = DVec3::new(c.x - axis.x, c.y - axis.y, 0.0);
                assert!(
                    shoelace(&pts).dot(out) < 0.0,
                    "a wall faces away from the tunnel"
                );
            }
        }
    }
}

#[test]
fn positive_weights_go_round_the_outside() {
    let m0 = prim("@cube:3");
    // A top face (x = 2/3, y = −2/3) to the +x side face beside it (z = 2/3).
    let (c1, c2) = (corner(&m0, 47), corner(&m0, 33));
    let mut m = m0.clone();
    let r = create_handle(&mut m, c1, c2, &HandleParams::new(8, 3.0, 3.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1);
    assert_eq!(r.plan.orientation, Orientation::AlongTangent);
    // The middle section's centre is outside the cube.
    let mid: Vec<DVec3> = r.sections[3]
        .iter()
        .map(|&v| m.position(v).unwrap())
        .collect();
    assert!(vertex_average(&mid).abs().max_element() > 1.0);
}

#[test]
fn zero_weights_give_a_straight_handle() {
    // Two cubes facing each other: the centroids of the sections lie on
    // the segment between the faces' centroids.
    let c = poly("@cube");
    let mut m = mesh(&union(&c, &c, DVec3::new(4.0, 0.0, 0.0)));
    // Face 3 is the first cube's +x side, face 6 + 2 the second's −x side.
    let (a, b) = (m.face_at(3).unwrap(), m.face_at(8).unwrap());
    let p1 = vertex_average(&m.face_positions(a).unwrap());
    let p2 = vertex_average(&m.face_positions(b).unwrap());
    let (c1, c2) = (m.face_corner(a).unwrap(), m.face_corner(b).unwrap());
    let r = create_handle(&mut m, c1, c2, &HandleParams::new(5, 0.0, 0.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.topology().component_count(), 1);
    for vs in &r.sections {
        let q = vertex_average(
            &vs.iter()
                .map(|&v| m.position(v).unwrap())
                .collect::<Vec<_>>(),
        );
        let d = (q - p1).cross(p2 - p1).length() / (p2 - p1).length();
        assert!(d < 1e-12, "off the line by {d}");
        assert!(q.x > p1.x && q.x < p2.x);
    }
}
