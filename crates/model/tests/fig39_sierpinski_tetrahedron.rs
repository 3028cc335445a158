//! Figure 39 of the thesis: the generalized Sierpinski scheme (§VI.5)
//! applied to a tetrahedron (A) and a cube (B), through the public API.
#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

mod soups_and_oracles;

use holey_dlfl::Mesh;
use holey_model::sierpinski::{SierpinskiError, sierpinski};
use soups_and_oracles::prim;

fn loops(m: &Mesh) -> usize {
    m.edges().filter(|&e| m.is_self_loop(e).unwrap()).count()
}

#[test]
fn figure_39a_sierpinski_tetrahedron() {
    let mut m = prim("@tetrahedron");
    // The thesis's numbers: V/E/F, genus, self-loops per iteration.
    for (v, e, f, g, l) in [
        (10, 30, 16, 3, 6),
        (34, 126, 64, 15, 30),
        (130, 510, 256, 63, 126),
    ] {
        sierpinski(&mut m, 1).unwrap();
        m.validate().unwrap();
        assert_eq!(
            (m.vertex_count(), m.edge_count(), m.face_count()),
            (v, e, f)
        );
        assert_eq!((m.genus(), loops(&m)), (g, l));
        assert_eq!(m.topology().component_count(), 1);
        assert_eq!(m.hole_count(), 0);
    }
    // The exported polygon soup drops the zero-length loops: every face is
    // a triangle, as figure 39A shows.
    let poly = holey_dlfl::convert::to_poly(&m).poly;
    assert_eq!(poly.face_count(), 256);
    assert!(poly.faces().all(|f| f.len() == 3));
}

#[test]
fn figure_39b_sierpinski_cube() {
    // §VI.6: a cube has only 3-valent convex vertices, so after one
    // iteration the mesh is made of tetrahedral pyramids only.
    let mut m = prim("@cube");
    sierpinski(&mut m, 3).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (260, 1020, 512)
    );
    assert_eq!((m.genus(), loops(&m)), (125, 252));
    let poly = holey_dlfl::convert::to_poly(&m).poly;
    assert!(poly.faces().all(|f| f.len() == 3));
}

#[test]
fn sierpinski_refuses_open_meshes() {
    let mut m = prim("@plane:2:2");
    assert!(matches!(
        sierpinski(&mut m, 1),
        Err(SierpinskiError::OpenSurface { .. })
    ));
}
