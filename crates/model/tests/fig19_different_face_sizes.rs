//! Figure 19 (§IV, after §III.3): handles between faces with different
//! numbers of corners. The smaller face's edges are subdivided first (the
//! longest first, never one bordering either face), then the handle is
//! built between two faces of the larger size.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::DVec3;
use holey_model::handle::{HandleParams, create_handle};
use soups_and_oracles::*;

#[test]
fn triangle_to_quad_in_one_component() {
    // @cone:4: face 0 is the square base, faces 1..=4 the triangles.
    for s in [1usize, 2, 3, 6] {
        for swap in [false, true] {
            let mut m = prim("@cone:4");
            assert_eq!(counts(&m), (5, 8, 5));
            let (tri, quad) = (corner(&m, 2), corner(&m, 0));
            let (c1, c2) = if swap { (quad, tri) } else { (tri, quad) };
            let r = create_handle(&mut m, c1, c2, &HandleParams::new(s, 1.0, 1.0)).unwrap();
            m.validate().unwrap();
            // Preprocessing: one vertex and one edge; then a handle between
            // two quads: V + 4(s−1), E + 4(2s−1), F + 4s − 2.
            assert_eq!(r.plan.subdivisions, 1);
            assert_eq!(r.plan.corners, 4);
            assert_eq!(
                counts(&m),
                (5 + 1 + 4 * (s - 1), 8 + 1 + 4 * (2 * s - 1), 5 + 4 * s - 2),
                "s={s} swap={swap}"
            );
            assert_eq!(m.genus(), 1);
            // The split edge is a slanted one (the base edge borders the
            // quad), so a neighbouring triangle became a quadrilateral.
            let quads = m.faces().filter(|&f| m.face_len(f).unwrap() == 4).count();
            assert_eq!(quads, 4 * s + 1);
        }
    }
}

#[test]
fn triangle_to_hexagon_between_two_components() {
    let tet = poly("@tetrahedron");
    let hex = poly("@cylinder:6:1");
    let mut m = mesh(&union(&hex, &tet, DVec3::new(0.0, 0.0, 5.0)));
    // The hexagon's top cap (face 1) and the tetrahedron's first face (8).
    let (a, b) = (corner(&m, 1), corner(&m, 8));
    let before = counts(&m);
    assert_eq!(before, (12 + 4, 18 + 6, 8 + 4));
    let s = 4;
    let r = create_handle(&mut m, a, b, &HandleParams::new(s, 1.0, 1.0)).unwrap();
    m.validate().unwrap();
    // Three subdivisions of the triangle (all its edges have one length,
    // and a half is never longer than an unsplit edge: one split each).
    assert_eq!(r.plan.subdivisions, 3);
    assert_eq!(
        counts(&m),
        (
            16 + 3 + 6 * (s - 1),
            24 + 3 + 6 * (2 * s - 1),
            12 + 6 * s - 2
        )
    );
    assert_eq!(m.topology().component_count(), 1);
    assert_eq!(m.genus(), 0);
}
