//! Tests of the conical cuts and truncation: counts from the module's
//! formula `ΔV = s − |S|, ΔE = s − |I|, ΔF = 1 − |Φ|` worked out per case,
//! positions of the cut points, refusals that leave the mesh unchanged.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{DVec3, EdgeId, Mesh, VertexId};

use super::*;
use crate::test_util::{check, counts, prim, unchanged};
use crate::truncate::{truncate_all_vertices, truncate_edges, truncate_vertices};

fn face_sizes(m: &Mesh) -> Vec<usize> {
    let mut s: Vec<usize> = m.faces().map(|f| m.face_len(f).unwrap()).collect();
    s.sort();
    s
}

#[test]
fn cutting_a_cube_corner_adds_two_vertices() {
    let mut m = prim("@cube");
    let v = m.vertex_at(0).unwrap(); // (-1,-1,-1), valence 3
    let k = m.valence(v).unwrap();
    // ΔV = k − 1, ΔE = k, ΔF = 1.
    let f = cut_vertex(&mut m, v, 0.5).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8 + k - 1, 12 + k, 6 + 1));
    assert_eq!(counts(&m), (10, 15, 7));
    assert_eq!(m.face_len(f).unwrap(), 3);
    assert!(!m.contains_vertex(v));
    // The triangle's corners lie 0.5 along the three edges from the corner.
    let mut pts: Vec<[i64; 3]> = m
        .face_positions(f)
        .unwrap()
        .iter()
        .map(|p| (*p * 2.0).round().as_i64vec3().to_array())
        .collect();
    pts.sort();
    assert_eq!(pts, [[-2, -2, -1], [-2, -1, -2], [-1, -2, -2]]);
    // Its normal points away from the cube (towards the removed corner).
    let n = crate::polygon::frame(&m.face_positions(f).unwrap())
        .unwrap()
        .normal;
    assert!(n.dot(DVec3::splat(-1.0)) > 0.0);
}

#[test]
fn vertex_cuts_of_every_valence() {
    // Icosahedron: valence 5 → pentagon; octahedron: 4 → square;
    // a cone's apex: 7 → heptagon; a torus vertex: 4.
    for (spec, v) in [
        ("@icosahedron", 0),
        ("@octahedron", 5),
        ("@cone:7", 7),
        ("@torus:6:5", 3),
    ] {
        let mut m = prim(spec);
        let v = m.vertex_at(v).unwrap();
        let k = m.valence(v).unwrap();
        let before = counts(&m);
        let g = m.genus();
        let f = cut_vertex(&mut m, v, 0.1).unwrap();
        check(&m);
        assert_eq!(
            counts(&m),
            (before.0 + k - 1, before.1 + k, before.2 + 1),
            "{spec}"
        );
        assert_eq!(m.face_len(f).unwrap(), k);
        assert_eq!(m.genus(), g);
    }
}

#[test]
fn cutting_a_cube_edge_and_a_cube_face() {
    let mut m = prim("@cube");
    let e = m.edges().next().unwrap();
    let [u, w] = m.edge_vertices(e).unwrap();
    let (ku, kw) = (m.valence(u).unwrap(), m.valence(w).unwrap());
    let f = cut_edge(&mut m, e, 0.5).unwrap();
    check(&m);
    // ΔV = ku + kw − 4, ΔE = ku + kw − 3, ΔF = 1; a (ku + kw − 2)-gon.
    assert_eq!(counts(&m), (8 + ku + kw - 4, 12 + ku + kw - 3, 7));
    assert_eq!(m.face_len(f).unwrap(), ku + kw - 2);
    assert!(!m.contains_edge(e) && !m.contains_vertex(u) && !m.contains_vertex(w));

    let mut m = prim("@cube");
    let top = m.face_at(5).unwrap();
    // S = 4 vertices, I = 4 edges, Φ = {top}, 4 spokes: no change in counts.
    let f = cut_face(&mut m, top, 0.5).unwrap();
    check(&m);
    assert_eq!(counts(&m), (8, 12, 6));
    assert_eq!(m.face_len(f).unwrap(), 4);
    for p in m.face_positions(f).unwrap() {
        assert!((p.z - 0.5).abs() < 1e-12);
    }
}

#[test]
fn truncating_every_vertex_of_a_cube() {
    let mut m = prim("@cube");
    let faces = truncate_all_vertices(&mut m, 0.25).unwrap();
    check(&m);
    // 2E, 3E, F + V.
    assert_eq!(counts(&m), (24, 36, 14));
    assert_eq!(faces.len(), 8);
    assert_eq!(face_sizes(&m), [3, 3, 3, 3, 3, 3, 3, 3, 8, 8, 8, 8, 8, 8]);
    // At t = 1/(2 + √2) the octagons are regular: all edges equal.
    let mut m = prim("@cube");
    truncate_all_vertices(&mut m, 1.0 / (2.0 + 2f64.sqrt())).unwrap();
    let lengths: Vec<f64> = m
        .edges()
        .map(|e| {
            let [a, b] = m.edge_vertices(e).unwrap();
            m.position(a).unwrap().distance(m.position(b).unwrap())
        })
        .collect();
    for l in &lengths {
        assert!((l - lengths[0]).abs() < 1e-12);
    }
}

#[test]
fn truncating_an_icosahedron_at_a_third_is_a_soccer_ball() {
    let mut m = prim("@icosahedron");
    truncate_all_vertices(&mut m, 1.0 / 3.0).unwrap();
    check(&m);
    assert_eq!(counts(&m), (60, 90, 32));
    let sizes = face_sizes(&m);
    assert_eq!(sizes.iter().filter(|&&s| s == 5).count(), 12);
    assert_eq!(sizes.iter().filter(|&&s| s == 6).count(), 20);
}

#[test]
fn truncating_edges_and_mixed_cuts() {
    // Two opposite edges of a cube share no vertex.
    let mut m = prim("@cube");
    let top = m.face_at(5).unwrap();
    let bottom = m.face_at(0).unwrap();
    let e1 = m.corner_edge(m.face_corner(top).unwrap()).unwrap().unwrap();
    let e2 = m
        .corner_edge(m.face_corner(bottom).unwrap())
        .unwrap()
        .unwrap();
    let faces = truncate_edges(&mut m, &[e1, e2], 0.25).unwrap();
    check(&m);
    // Each: +2, +3, +1.
    assert_eq!(counts(&m), (12, 18, 8));
    assert_eq!(faces.len(), 2);
    // An edge and a vertex far from it.
    cut_top_edge_and_far_corner(&mut prim("@cube"), 0.3, 0.3);
}

/// Cuts an edge of the cube `m`'s top face at `edge_offset` and a corner
/// far from it at `vertex_offset` in one cut, and checks the counts:
/// +2/+3/+1 for each target, one new face each. Returns the edge and the
/// corner cut.
fn cut_top_edge_and_far_corner(
    m: &mut Mesh,
    edge_offset: f64,
    vertex_offset: f64,
) -> (EdgeId, VertexId) {
    let e = m
        .corner_edge(m.face_corner(m.face_at(5).unwrap()).unwrap())
        .unwrap()
        .unwrap();
    let v = m.vertex_at(0).unwrap();
    let faces = cut_edges_and_vertices(m, &[e], &[v], edge_offset, vertex_offset).unwrap();
    check(m);
    assert_eq!(counts(m), (12, 18, 8));
    assert_eq!(faces.len(), 2);
    (e, v)
}

#[test]
fn edge_vertex_cuts_take_an_offset_each() {
    // TopMod's cut by edge-vertex with "Offset (Edge)" 0.3 and "Offset
    // (Vertex)" 0.7 on the cube of side 2: an edge and a corner far from
    // it, +2/+3/+1 each (12/18/8). Every new point lies on a cube edge at
    // its own target's offset from the corner it replaced: three at 0.7
    // (the corner's spokes), four at 0.3 (the edge's), and the five
    // untouched corners stay at distance 0.
    let mut m = prim("@cube");
    let corners: Vec<DVec3> = m.vertices().map(|v| m.position(v).unwrap()).collect();
    let (e, v) = cut_top_edge_and_far_corner(&mut m, 0.3, 0.7);
    let mut d: Vec<f64> = m
        .vertices()
        .map(|v| {
            let p = m.position(v).unwrap();
            corners
                .iter()
                .map(|c| c.distance(p))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    d.sort_by(f64::total_cmp);
    let want = [0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.3, 0.3, 0.7, 0.7, 0.7];
    for (got, want) in d.iter().zip(want) {
        assert!((got - want).abs() < 1e-12, "{d:?}");
    }
    // Each offset is checked against its own spokes: 1.0 reaches the
    // middle of the corner's edges (length 2) even though the edge's 0.3
    // does not, and nothing changes.
    let m0 = prim("@cube");
    let mut m = m0.clone();
    let err = cut_edges_and_vertices(&mut m, &[e], &[v], 0.3, 1.0).unwrap_err();
    assert!(
        matches!(err, CutError::OffsetTooLarge { offset, .. } if offset == 1.0),
        "{err}"
    );
    unchanged(&m, &m0);
}

#[test]
fn degenerate_offsets_are_refused_and_change_nothing() {
    let m0 = prim("@cube");
    let v = m0.vertex_at(0).unwrap();
    for x in [0.0, -0.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut m = m0.clone();
        assert!(
            matches!(cut_vertex(&mut m, v, x), Err(CutError::InvalidOffset(_))),
            "{x}"
        );
        unchanged(&m, &m0);
    }
    // Edges of length 2: a cut must stay below half of it.
    for x in [1.0, 1.5, 2.0, 3.0] {
        let mut m = m0.clone();
        let err = cut_vertex(&mut m, v, x).unwrap_err();
        assert!(matches!(err, CutError::OffsetTooLarge { .. }), "{err}");
        unchanged(&m, &m0);
    }
    let mut m = m0.clone();
    cut_vertex(&mut m, v, 0.99).unwrap();
    check(&m);
    // As fractions of the edge.
    for t in [0.5, 0.75, 1.0, 2.0] {
        let mut m = m0.clone();
        let err = truncate_all_vertices(&mut m, t).unwrap_err();
        assert!(matches!(err, CutError::OffsetTooLarge { .. }), "{t}: {err}");
        unchanged(&m, &m0);
    }
    let mut m = m0.clone();
    assert!(matches!(
        truncate_vertices(&mut m, &[v], 0.0),
        Err(CutError::InvalidOffset(_))
    ));
    unchanged(&m, &m0);
}

#[test]
fn overlapping_and_impossible_regions_are_refused() {
    let m0 = prim("@cube");
    let v = m0.vertex_at(0).unwrap();
    let edges: Vec<EdgeId> = m0
        .vertex_corners(v)
        .unwrap()
        .map(|c| m0.corner_edge(c).unwrap().unwrap())
        .collect();
    let mut m = m0.clone();
    assert_eq!(
        cut_edges(&mut m, &edges[..2], 0.2),
        Err(CutError::Overlap(v))
    );
    unchanged(&m, &m0);
    let mut m = m0.clone();
    assert_eq!(
        cut_edges_and_vertices(&mut m, &edges[..1], &[v], 0.2, 0.2),
        Err(CutError::Overlap(v))
    );
    unchanged(&m, &m0);
    // A second edge between the two ends of an edge, through a handle:
    // the edge's region is an annulus, not a disk.
    let mut m = prim("@tetrahedron");
    let e = m.edges().next().unwrap();
    let [a, b] = m.edge_corners(e).unwrap();
    let (fa, fb) = (m.corner_face(a).unwrap(), m.corner_face(b).unwrap());
    let va = m.corner_vertex(a).unwrap();
    let vb = m.corner_vertex(b).unwrap();
    // Corners of va and vb in faces other than the edge's own two.
    let ca = m
        .vertex_corners(va)
        .unwrap()
        .find(|&c| ![fa, fb].contains(&m.corner_face(c).unwrap()))
        .unwrap();
    let cb = m
        .vertex_corners(vb)
        .unwrap()
        .find(|&c| ![fa, fb, m.corner_face(ca).unwrap()].contains(&m.corner_face(c).unwrap()))
        .unwrap();
    m.insert_edge(ca, cb).unwrap();
    check(&m);
    let before = m.clone();
    assert_eq!(
        cut_edge(&mut m, e, 0.1),
        Err(CutError::NotADisk(CutTarget::Edge(e)))
    );
    unchanged(&m, &before);
    // A hole face, and a point-sphere.
    let mut m = prim("@plane:2:2");
    let hole = m.faces().find(|&f| m.is_hole(f).unwrap()).unwrap();
    let before = m.clone();
    assert_eq!(cut_face(&mut m, hole, 0.1), Err(CutError::HoleFace(hole)));
    unchanged(&m, &before);
    let (p, _, _) = m.create_vertex(DVec3::ONE).unwrap();
    assert_eq!(
        cut_vertex(&mut m, p, 0.1),
        Err(CutError::NothingToCut(CutTarget::Vertex(p)))
    );
}

#[test]
fn cuts_on_a_boundary() {
    // A boundary vertex of valence 3 on an open grid: +2/+3/+1, and the
    // boundary loop survives (one hole).
    let mut m = prim("@plane:2:2");
    let v = m.vertex_at(1).unwrap();
    assert_eq!(m.valence(v).unwrap(), 3);
    let before = counts(&m);
    cut_vertex(&mut m, v, 0.25).unwrap();
    check(&m);
    assert_eq!(counts(&m), (before.0 + 2, before.1 + 3, before.2 + 1));
    assert_eq!(m.hole_count(), 1);
    // A boundary edge of the grid: valences 2 and 3, a triangle.
    let mut m = prim("@plane:2:2");
    let e = m
        .edges()
        .find(|&e| {
            let [x, y] = m.edge_faces(e).unwrap();
            let [u, w] = m.edge_vertices(e).unwrap();
            (m.is_hole(x).unwrap() || m.is_hole(y).unwrap())
                && m.valence(u).unwrap() + m.valence(w).unwrap() == 5
        })
        .unwrap();
    let before = counts(&m);
    let f = cut_edge(&mut m, e, 0.25).unwrap();
    check(&m);
    assert_eq!(counts(&m), (before.0 + 1, before.1 + 2, before.2 + 1));
    assert_eq!(m.face_len(f).unwrap(), 3);
    assert_eq!(m.hole_count(), 1);
}

fn lone_triangle() -> Mesh {
    let mut p = holey_mesh::PolyMesh::new();
    p.positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ];
    p.face_offsets = vec![0, 3];
    p.face_indices = vec![0, 1, 2];
    to_dlfl(&p, ImportOptions::default()).unwrap().mesh
}

#[test]
fn cutting_a_corner_of_a_lone_triangle_makes_a_quad() {
    // A boundary vertex of valence 2 (S = 1, I = 0, Φ = 0, two spokes):
    // ΔV = 2 − 1, ΔE = 1 − 0, ΔF = 0: 3/3/2 → 4/4/2, the triangle and
    // its boundary loop both become quads, no two-gon.
    let mut m = lone_triangle();
    let v = m.vertex_at(0).unwrap();
    assert_eq!(m.valence(v).unwrap(), 2);
    let f = cut_vertex(&mut m, v, 0.25).unwrap();
    check(&m);
    assert_eq!(counts(&m), (4, 4, 2));
    assert_eq!(face_sizes(&m), vec![4, 4]);
    assert_eq!(m.hole_count(), 1);
    // The face returned is the one the corner opened into: the hole.
    assert!(m.is_hole(f).unwrap());
    // The new corners lie 0.25 along the two edges from the old corner.
    let mut at: Vec<DVec3> = m.vertices().map(|v| m.position(v).unwrap()).collect();
    at.retain(|p| p.x.abs() < 1e-12 || p.y.abs() < 1e-12);
    at.retain(|p| (p.length() - 0.25).abs() < 1e-12);
    assert_eq!(at.len(), 2);
}

#[test]
fn cutting_an_edge_of_a_lone_triangle_leaves_a_triangle() {
    // Edge between two valence-2 vertices: S = 2, I = 1, two spokes:
    // ΔV = 0, ΔE = 0, ΔF = 0; the triangle gets smaller.
    let mut m = lone_triangle();
    let e = m.edges().next().unwrap();
    cut_edge(&mut m, e, 0.25).unwrap();
    check(&m);
    assert_eq!(counts(&m), (3, 3, 2));
    assert_eq!(face_sizes(&m), vec![3, 3]);
    assert_eq!(m.hole_count(), 1);
}

#[test]
fn cutting_an_inner_vertex_of_valence_two_joins_its_faces_by_one_edge() {
    // A cube edge split at its middle: 9/13/6, two pentagons. Cutting the
    // middle vertex (valence 2, two spokes): +1/+1/+0, the pentagons
    // become hexagons sharing the new edge.
    let mut m = prim("@cube");
    let e = m.edges().next().unwrap();
    let s = m.subdivide_edge_at(e, 0.5).unwrap();
    let [a, b] = m.edge_vertices(s.edges[0]).unwrap();
    let mid = if m.valence(a).unwrap() == 2 { a } else { b };
    assert_eq!(counts(&m), (9, 13, 6));
    cut_vertex(&mut m, mid, 0.25).unwrap();
    check(&m);
    assert_eq!(counts(&m), (10, 14, 6));
    assert_eq!(face_sizes(&m), vec![4, 4, 4, 4, 6, 6]);
}
