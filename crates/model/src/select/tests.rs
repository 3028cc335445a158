//! Selection tests on grids, tori and solids whose loops, rings and
//! colourings are known by construction.

use crate::test_util::prim;
use holey_dlfl::Mesh;

use super::*;

fn first_edge(m: &Mesh, f: FaceId) -> EdgeId {
    m.corner_edge(m.face_corner(f).unwrap()).unwrap().unwrap()
}

/// The edge from corner `k` of face `f` (from its first corner).
fn edge_k(m: &Mesh, f: FaceId, k: usize) -> EdgeId {
    let c = m.face_corners(f).unwrap().nth(k).unwrap();
    m.corner_edge(c).unwrap().unwrap()
}

#[test]
fn face_loops_on_a_torus_close_and_on_a_grid_stop() {
    // @torus:8:6, face i*6 + j = (i,j),(i+1,j),(i+1,j+1),(i,j+1): its
    // first edge runs along i, so crossing it steps in j: a loop of 6;
    // its second edge runs along j: a loop of 8.
    let m = prim("@torus:8:6");
    let f = m.face_at(0).unwrap();
    let around_j = face_loop(&m, f, edge_k(&m, f, 0)).unwrap();
    let around_i = face_loop(&m, f, edge_k(&m, f, 1)).unwrap();
    assert_eq!(around_j.len(), 6);
    assert_eq!(around_i.len(), 8);
    assert!(around_j.contains(&f) && around_i.contains(&f));
    // Consecutive faces share an edge.
    for w in around_i.windows(2) {
        assert!(m.edges().any(|e| {
            let [x, y] = m.edge_faces(e).unwrap();
            (x, y) == (w[0], w[1]) || (y, x) == (w[0], w[1])
        }));
    }
    // @plane:4:3: a row of 4 quads (stopped by the boundary) or a column of 3.
    let m = prim("@plane:4:3");
    let f = m.face_at(5).unwrap(); // (1,1)
    assert_eq!(face_loop(&m, f, edge_k(&m, f, 0)).unwrap().len(), 3);
    assert_eq!(face_loop(&m, f, edge_k(&m, f, 1)).unwrap().len(), 4);
    // @cube:3 has all quads: a loop goes round four sides, 12 faces.
    let m = prim("@cube:3");
    let f = m.face_at(4).unwrap();
    assert_eq!(face_loop(&m, f, first_edge(&m, f)).unwrap().len(), 12);
}

#[test]
fn face_loop_refusals_and_non_quads() {
    let m = prim("@cylinder:6");
    let cap = m.face_at(0).unwrap();
    assert_eq!(
        face_loop(&m, cap, first_edge(&m, cap)),
        Err(SelectError::NotAQuad(cap))
    );
    // A side quad's loop round the cylinder: 6; up and down it stops at the caps.
    let side = m.face_at(2).unwrap();
    let e = edge_k(&m, side, 1);
    assert_eq!(face_loop(&m, side, e).unwrap().len(), 6);
    assert_eq!(
        face_loop(&m, side, edge_k(&m, side, 0)).unwrap(),
        vec![side]
    );
    let other = m.face_at(4).unwrap();
    let far = first_edge(&m, other);
    assert!(matches!(
        face_loop(&m, side, far),
        Err(SelectError::NotOnFace { .. })
    ));
}

#[test]
fn edge_rings_and_loops() {
    let m = prim("@torus:8:6");
    let f = m.face_at(0).unwrap();
    let e_i = edge_k(&m, f, 0); // along i
    let e_j = edge_k(&m, f, 1); // along j
    // A ring crosses quads: edges along i are stacked in j (6 of them).
    assert_eq!(edge_ring(&m, e_i).unwrap().len(), 6);
    assert_eq!(edge_ring(&m, e_j).unwrap().len(), 8);
    // A loop continues straight: along i, 8 edges; along j, 6.
    assert_eq!(edge_loop(&m, e_i).unwrap().len(), 8);
    assert_eq!(edge_loop(&m, e_j).unwrap().len(), 6);
    // A loop and a ring through one edge share only that edge.
    let ring: HashSet<EdgeId> = edge_ring(&m, e_i).unwrap().into_iter().collect();
    let lp: HashSet<EdgeId> = edge_loop(&m, e_i).unwrap().into_iter().collect();
    assert_eq!(ring.intersection(&lp).count(), 1);
    // On @plane:4:3 an inner horizontal edge's loop runs the row (4
    // edges, stopping at boundary vertices of valence 3) and its ring the
    // column (4 edges: rows 0..=3 of horizontal edges).
    let m = prim("@plane:4:3");
    let f = m.face_at(5).unwrap();
    let horizontal = edge_k(&m, f, 0);
    assert_eq!(edge_loop(&m, horizontal).unwrap().len(), 4);
    assert_eq!(edge_ring(&m, horizontal).unwrap().len(), 4);
}

#[test]
fn grow_shrink_invert_similar() {
    let m = prim("@plane:5:5");
    let centre = m.face_at(12).unwrap();
    let grown = grow_faces(&m, &[centre]).unwrap();
    assert_eq!(grown.len(), 9);
    assert_eq!(shrink_faces(&m, &grown).unwrap(), vec![centre]);
    let twice = grow_faces(&m, &grown).unwrap();
    assert_eq!(twice.len(), 25);
    // Everything touches the boundary loop (a hole) after shrinking.
    assert_eq!(shrink_faces(&m, &twice).unwrap().len(), 9);
    assert_eq!(invert_faces(&m, &grown).unwrap().len(), 25 - 9);
    assert!(invert_faces(&m, &twice).unwrap().is_empty());
    // Vertices: the centre vertex of a 2×2 grid grows to all 9.
    let m = prim("@plane:2:2");
    let v = m.vertex_at(4).unwrap();
    let all = grow_vertices(&m, &[v]).unwrap();
    assert_eq!(all.len(), 5);
    assert_eq!(grow_vertices(&m, &all).unwrap().len(), 9);
    assert_eq!(shrink_vertices(&m, &all).unwrap(), vec![v]);
    assert_eq!(invert_vertices(&m, &all).len(), 4);
    let e = m.edges().next().unwrap();
    assert_eq!(invert_edges(&m, &[e]).len(), m.edge_count() - 1);
    // Similar: a cylinder's side quad selects the 6 quads, a cap the caps.
    let m = prim("@cylinder:6");
    assert_eq!(
        similar_faces(&m, &[m.face_at(3).unwrap()]).unwrap().len(),
        6
    );
    assert_eq!(
        similar_faces(&m, &[m.face_at(0).unwrap()]).unwrap().len(),
        2
    );
    // @cube:2: the 8 corners have valence 3, the rest 4.
    let m = prim("@cube:2");
    assert_eq!(
        similar_vertices(&m, &[m.vertex_at(0).unwrap()])
            .unwrap()
            .len(),
        8
    );
}

#[test]
fn checkerboard_colours_even_meshes_and_names_odd_ones() {
    for (spec, half) in [("@torus:8:6", 24), ("@plane:4:3", 6), ("@torus:4:4", 8)] {
        let m = prim(spec);
        let board = checkerboard(&m).unwrap();
        assert_eq!(
            (board.first.len(), board.second.len()),
            (half, half),
            "{spec}"
        );
        let first: HashSet<FaceId> = board.first.iter().copied().collect();
        for e in m.edges() {
            let [x, y] = m.edge_faces(e).unwrap();
            if m.is_hole(x).unwrap() || m.is_hole(y).unwrap() {
                continue;
            }
            assert_ne!(first.contains(&x), first.contains(&y), "{spec}");
        }
    }
    // Three faces meet at each corner of a cube: an odd cycle; a torus
    // with 5 faces round has one too.
    for spec in ["@cube", "@cube:2", "@tetrahedron", "@torus:5:4"] {
        let m = prim(spec);
        match checkerboard(&m) {
            Err(SelectError::NotBipartite { face, other, edge }) => {
                assert_eq!(
                    BTreeSet::from(m.edge_faces(edge).unwrap()),
                    BTreeSet::from([face, other])
                );
            }
            other => panic!("{spec}: {other:?}"),
        }
    }
}
