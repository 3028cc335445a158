//! Meshes and checks for the kernel's unit tests.

use std::collections::HashMap;

use glam::DVec3;

use crate::{CornerId, EdgeId, FaceId, Mesh, RawMesh, VertexId};

/// Builds a closed mesh from polygons by pairing each half-edge u→v with
/// the single v→u. Test meshes only: panics on anything non-manifold.
pub(crate) fn from_polygons(positions: &[[f64; 3]], faces: &[&[u32]]) -> Mesh {
    let mut raw = RawMesh {
        positions: positions.iter().map(|p| DVec3::from_array(*p)).collect(),
        face_offsets: vec![0],
        ..RawMesh::default()
    };
    for f in faces {
        raw.face_vertices.extend_from_slice(f);
        raw.face_offsets.push(raw.face_vertices.len() as u32);
    }
    let mut open: HashMap<(u32, u32), u32> = HashMap::new();
    for f in 0..raw.face_count() {
        let lo = raw.face_offsets[f];
        let n = raw.face_offsets[f + 1] - lo;
        for k in 0..n {
            let c = lo + k;
            let u = raw.face_vertices[c as usize];
            let v = raw.face_vertices[(lo + (k + 1) % n) as usize];
            if let Some(other) = open.remove(&(v, u)) {
                raw.edges.push([other, c]);
            } else {
                assert!(
                    open.insert((u, v), c).is_none(),
                    "test mesh edge {u}->{v} used twice"
                );
            }
        }
    }
    assert!(open.is_empty(), "test mesh is not closed");
    Mesh::from_raw(&raw).expect("test mesh builds")
}

/// Builds the kernel mesh of testkit's plain arrays. (The fixtures stay
/// arrays there: testkit depending on this crate would give its unit
/// tests a second, different `Mesh` type.)
fn of<const N: usize>(positions: &[[f64; 3]], faces: &[[u32; N]]) -> Mesh {
    let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
    from_polygons(positions, &refs)
}

/// The tetrahedron of [`holey_testkit::tetrahedron`].
pub(crate) fn tetrahedron() -> Mesh {
    let (p, t) = holey_testkit::tetrahedron();
    of(&p, &t)
}

/// The unit cube of [`holey_testkit::unit_cube`].
pub(crate) fn cube() -> Mesh {
    let (p, quads) = holey_testkit::unit_cube();
    of(&p, &quads)
}

/// The n×m quad torus of [`holey_testkit::quad_torus`].
pub(crate) fn torus(n: u32, m: u32) -> Mesh {
    let (p, quads) = holey_testkit::quad_torus(n, m);
    of(&p, &quads)
}

/// The unit cube, its face in slot `slot` and that face's corners in
/// order: most edits in the kernel's tests start from one cube face's
/// corners.
pub(crate) fn cube_face(slot: usize) -> (Mesh, FaceId, Vec<CornerId>) {
    let m = cube();
    let f = m.face_at(slot).expect("the cube has six faces");
    let cs = m.face_corners(f).expect("a live face").collect();
    (m, f, cs)
}

/// The unit cube with an edge from the corner of its first face to the
/// corner of its second (a handle: genus 1), and that edge.
pub(crate) fn cube_with_handle() -> (Mesh, EdgeId) {
    let mut m = cube();
    let faces: Vec<_> = m.faces().collect();
    let c1 = m.face_corner(faces[0]).expect("a live face");
    let c2 = m.face_corner(faces[1]).expect("a live face");
    let e = m.insert_edge(c1, c2).expect("the handle inserts");
    (m, e)
}

/// The unit cube with a new vertex at `at` joined to its first corner by a
/// dangling edge: the edge, the new vertex and the vertex's corner, where
/// the tests of deleting and collapsing a dangling edge start.
pub(crate) fn cube_with_dangling_edge(at: DVec3) -> (Mesh, EdgeId, VertexId, CornerId) {
    let mut m = cube();
    let c = m.corners().next().expect("a corner");
    let (v, _, cv) = m.create_vertex(at).expect("a vertex");
    let e = m.insert_edge(c, cv).expect("the dangling edge inserts");
    (m, e, v, cv)
}

/// The corners of face `f` at vertex `v`, in face order: where a self-loop
/// or a second loop at `v` can be inserted inside `f`.
pub(crate) fn corners_at(m: &Mesh, f: FaceId, v: VertexId) -> Vec<CornerId> {
    m.face_corners(f)
        .expect("a live face")
        .filter(|&c| m.corner_vertex(c).expect("a live corner") == v)
        .collect()
}

/// A self-loop between the first two corners of the mesh's first vertex
/// (in two faces: a handle), that vertex, and its corners in rotation
/// order.
pub(crate) fn loop_at_first_vertex(m: &mut Mesh) -> (EdgeId, VertexId, Vec<CornerId>) {
    let v0 = m.vertices().next().expect("a vertex");
    let cs: Vec<_> = m.vertex_corners(v0).expect("a live vertex").collect();
    let e = m.insert_edge(cs[0], cs[1]).expect("the loop inserts");
    (e, v0, cs)
}

/// (V, E, F incl. holes, components, genus).
pub(crate) fn counts(m: &Mesh) -> (usize, usize, usize, usize, i64) {
    let t = m.topology();
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        t.component_count(),
        t.genus(),
    )
}

/// A canonical description of the face structure: each face as its cycle
/// of vertex positions (rotated to start at the smallest), sorted.
pub(crate) fn canonical(m: &Mesh) -> Vec<(bool, Vec<[u64; 3]>)> {
    let mut faces: Vec<(bool, Vec<[u64; 3]>)> = m
        .faces()
        .map(|f| {
            let ps: Vec<[u64; 3]> = m
                .face_positions(f)
                .unwrap()
                .iter()
                .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .collect();
            let k = (0..ps.len()).min_by_key(|&i| ps[i]).unwrap();
            let mut r = ps[k..].to_vec();
            r.extend_from_slice(&ps[..k]);
            (m.is_hole(f).unwrap(), r)
        })
        .collect();
    faces.sort();
    faces
}

/// Validates and checks the kernel's own bookkeeping against a recount.
pub(crate) fn check(m: &Mesh) {
    if let Err(e) = m.validate() {
        panic!("{e}");
    }
    let t = m.topology();
    let closed_euler: i64 = m.vertex_count() as i64 - m.edge_count() as i64 + m.face_count() as i64;
    assert_eq!(
        closed_euler,
        2 * t.component_count() as i64 - 2 * t.genus(),
        "Euler bookkeeping"
    );
}
