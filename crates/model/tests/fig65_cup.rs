//! Figure 65 (§VIII): a cup made with both interactive tools — rind
//! modeling for the body (peel the top off a thick shell), then a curved
//! handle between two outer side faces.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::DVec3;
use holey_model::handle::{HandleParams, create_handle};
use holey_model::rind::Rind;
use soups_and_oracles::*;

#[test]
fn a_cube_cup_with_a_handle() {
    let soup = poly("@cube:3");
    assert_eq!(counts(&mesh(&soup)), (56, 108, 54));
    let mut rind = Rind::new(mesh(&soup), 0.1).unwrap();
    // The top: faces 45..54, a 3×3 block with 12 inner edges and 4 inner vertices.
    let top: Vec<usize> = (45..54).collect();
    assert_eq!(region_interior(&soup, &top), (12, 4));
    for out in rind.peel_indices(&top).unwrap() {
        assert!(out.report().is_some());
    }
    rind.mesh().validate().unwrap();
    // 2V − 2·4; 2E + 36 − 4·12; 2F + 36 − 18 − 2·12.
    assert_eq!(counts(rind.mesh()), (104, 204, 102));
    assert_eq!(rind.mesh().genus(), 0);
    // Two faces of the +x side, middle column, top and bottom rows.
    let upper = rind.outer_face(34).unwrap();
    let lower = rind.outer_face(28).unwrap();
    let mut m = rind.into_mesh();
    let (c1, c2) = (m.face_corner(upper).unwrap(), m.face_corner(lower).unwrap());
    let r = create_handle(&mut m, c1, c2, &HandleParams::new(6, 1.5, 1.5)).unwrap();
    m.validate().unwrap();
    // A 6-segment handle between quads: V + 20, E + 44, F + 22.
    assert_eq!(counts(&m), (124, 248, 124));
    assert_eq!(m.genus(), 1);
    assert_eq!(m.topology().component_count(), 1);
    // The handle stands out from the +x side.
    for vs in &r.sections {
        let pts: Vec<DVec3> = vs.iter().map(|&v| m.position(v).unwrap()).collect();
        assert!(vertex_average(&pts).x > 1.0);
    }
}

#[test]
fn a_cylinder_cup_with_a_handle() {
    // 16 segments, 4 rings: the top cap (face 1) is a 16-gon.
    let soup = poly("@cylinder:16:4");
    let m0 = mesh(&soup);
    let (v, e, f) = counts(&m0);
    let mut rind = Rind::new(m0, 0.05).unwrap();
    rind.peel_index(1).unwrap();
    let m = rind.mesh();
    m.validate().unwrap();
    assert_eq!(counts(m), (2 * v, 2 * e + 16, 2 * f + 14));
    assert_eq!(m.genus(), 0);
    // Side faces 2 + k·16 + i: ring 3 (top) and ring 0 (bottom) at i = 0.
    let upper = rind.outer_face(2 + 3 * 16).unwrap();
    let lower = rind.outer_face(2).unwrap();
    let mut m = rind.into_mesh();
    let (c1, c2) = (m.face_corner(upper).unwrap(), m.face_corner(lower).unwrap());
    create_handle(&mut m, c1, c2, &HandleParams::new(8, 1.0, 1.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1);
    assert_eq!(
        counts(&m),
        (2 * v + 4 * 7, 2 * e + 16 + 4 * 15, 2 * f + 14 + 4 * 8 - 2)
    );
}
