//! Fixtures the unit tests of several modules share.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{EdgeId, FaceId, Mesh};

/// The built-in primitive `spec` (`@cube`, `@torus:8:4`, …) as a kernel
/// mesh, imported with the default options.
pub(crate) fn prim(spec: &str) -> Mesh {
    let poly = holey_shapes::parse_primitive(spec).unwrap();
    to_dlfl(&poly, ImportOptions::default()).unwrap().mesh
}

/// `@cube` with every original edge split by `split` (a subdivision or a
/// trisection): the cube's shape with valence-2 vertices along its edges,
/// which the hull and the mesh tools must see through or remove.
pub(crate) fn cube_with_split_edges<T>(
    split: impl Fn(&mut Mesh, EdgeId) -> holey_dlfl::Result<T>,
) -> Mesh {
    let mut m = prim("@cube");
    let edges: Vec<EdgeId> = m.edges().collect();
    for e in edges {
        split(&mut m, e).unwrap();
    }
    m
}

/// (V, E, F, components, genus) of `m`: what an operator's counting
/// formula predicts.
pub(crate) type State = (i64, i64, i64, usize, i64);

/// The [`State`] of `m`.
pub(crate) fn state(m: &Mesh) -> State {
    let t = m.topology();
    (
        m.vertex_count() as i64,
        m.edge_count() as i64,
        m.face_count() as i64,
        t.component_count(),
        t.genus(),
    )
}

/// (V, E, F) of `m`, holes counted as faces: the counts most operators'
/// tests compare with their formulas.
pub(crate) fn counts(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

/// Checks the mesh and that V − E + F (holes counted as faces) still
/// equals 2·components − 2·genus: Euler's formula for the closed DLFL.
pub(crate) fn check(m: &Mesh) {
    m.validate().unwrap();
    let (v, e, f, c, g) = state(m);
    assert_eq!(v - e + f, 2 * c as i64 - 2 * g, "Euler's formula");
}

/// Asserts that `m` is `before` as it was: what a refused operation
/// must leave.
pub(crate) fn unchanged(m: &Mesh, before: &Mesh) {
    assert_eq!(m.to_raw(), before.to_raw());
}

/// The signed volume of `m`'s faces (holes left out), each fanned from its
/// first corner: positive for a closed mesh whose faces turn
/// counter-clockwise seen from outside.
pub(crate) fn signed_volume(m: &Mesh) -> f64 {
    let mut vol = 0.0;
    for f in m.faces() {
        if m.is_hole(f).unwrap() {
            continue;
        }
        let p = m.face_positions(f).unwrap();
        for k in 1..p.len().saturating_sub(1) {
            vol += p[0].dot(p[k].cross(p[k + 1]));
        }
    }
    vol / 6.0
}

/// An edge of face `a` that has face `b` on its other side, if the two
/// faces are neighbours.
pub(crate) fn shared_edge(m: &Mesh, a: FaceId, b: FaceId) -> Option<EdgeId> {
    m.face_corners(a)
        .unwrap()
        .filter_map(|c| m.corner_edge(c).unwrap())
        .find(|&e| m.edge_faces(e).unwrap().contains(&b))
}
