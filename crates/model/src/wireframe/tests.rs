//! Wireframe and column tests: counts from the module's formulas (worked
//! out here from the input's V, E, valences), genus `E − V + C` of the
//! input's edge graph, validity, outward orientation, refusals.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{DVec3, Mesh};
use holey_mesh::PolyMesh;

use super::*;
use crate::test_util::{counts, prim, signed_volume};

fn poly(spec: &str) -> PolyMesh {
    holey_shapes::parse_primitive(spec).unwrap()
}

fn mesh(p: &PolyMesh) -> Mesh {
    to_dlfl(p, ImportOptions::default()).unwrap().mesh
}

/// The primitives `a` and `b`, the second moved 10 along x, as one mesh:
/// two components, for the tests that run over many meshes.
fn two_apart(a: &str, b: &str) -> Mesh {
    let mut out = poly(a);
    out.append(&poly(b).translated(DVec3::new(10.0, 0.0, 0.0)));
    mesh(&out)
}

/// The cycle rank of the edge graph: E − V + C.
fn graph_genus(m: &Mesh) -> i64 {
    m.edge_count() as i64 - m.vertex_count() as i64 + m.topology().component_count() as i64
}

fn valences(m: &Mesh) -> Vec<usize> {
    m.vertices().map(|v| m.valence(v).unwrap()).collect()
}

/// The wireframe counts of the module documentation from E and the
/// valences: (4E, 10E − 2(V₁ + V₂), 4E + 2V₃) for a mesh with no
/// point-spheres (`V_k` the vertices of valence k, `V₃` of 3 or more).
fn wire_counts(m: &Mesh) -> (usize, usize, usize) {
    let e = m.edge_count();
    let low = valences(m).iter().filter(|&&k| k == 1 || k == 2).count();
    let high = valences(m).iter().filter(|&&k| k >= 3).count();
    (4 * e, 10 * e - 2 * low, 4 * e + 2 * high)
}

/// Every face but a point-sphere's has three sides or more and no edge
/// is a loop.
fn no_two_gons_or_loops(w: &Mesh) {
    for f in w.faces() {
        let point_sphere = w
            .face_vertices(f)
            .unwrap()
            .iter()
            .all(|&v| w.valence(v).unwrap() == 0);
        assert!(point_sphere || w.face_len(f).unwrap() >= 3, "face {f:?}");
    }
    for e in w.edges() {
        let [a, b] = w.edge_vertices(e).unwrap();
        assert_ne!(a, b, "edge {e:?} is a loop");
    }
}

/// The column counts of the module documentation from E and the valences.
fn column_counts(m: &Mesh, n: usize) -> (usize, usize, usize) {
    let e = m.edge_count();
    let (mut extra_e, mut extra_f) = (0, 0);
    for k in valences(m) {
        match k {
            0 => {}
            1 => extra_f += 1,
            2 => {
                extra_e += 2;
                extra_f += 2;
            }
            k => {
                extra_e += 2 * k;
                extra_f += k + 2;
            }
        }
    }
    (2 * n * e, 3 * n * e + extra_e, n * e + extra_f)
}

#[test]
fn wireframe_of_a_cube() {
    let m = prim("@cube");
    let w = wireframe(&m, 0.1).unwrap();
    w.validate().unwrap();
    // Worked out: E = 12, V = 8: 48 vertices, 120 edges, 48 + 16 faces,
    // genus 12 − 8 + 1 = 5 (χ = 48 − 120 + 64 = −8).
    assert_eq!(counts(&w), (48, 120, 64));
    assert_eq!(counts(&w), wire_counts(&m));
    assert_eq!(w.genus(), 5);
    assert_eq!(w.topology().component_count(), 1);
    assert_eq!(w.hole_count(), 0);
    let (v0, v1) = (signed_volume(&m), signed_volume(&w));
    assert!(v1 > 0.0 && v1 < v0, "volume {v1} vs {v0}");
    // The input is untouched.
    assert_eq!(m.to_raw(), prim("@cube").to_raw());
}

#[test]
fn wireframe_genus_is_the_cycle_rank_of_the_edge_graph() {
    let two = two_apart("@tetrahedron", "@torus:6:4");
    for m in [
        prim("@tetrahedron"),
        prim("@octahedron"),
        prim("@dodecahedron"),
        prim("@torus:8:5"),
        prim("@cylinder:5"),
        prim("@plane:3:2"),
        prim("@sphere:1"),
        two,
    ] {
        let w = wireframe(&m, 0.02).unwrap();
        w.validate().unwrap();
        no_two_gons_or_loops(&w);
        assert_eq!(w.genus(), graph_genus(&m));
        assert_eq!(
            w.topology().component_count(),
            m.topology().component_count()
        );
        assert_eq!(counts(&w), wire_counts(&m));
        assert!(signed_volume(&w) > 0.0);
    }
}

#[test]
fn wireframe_of_a_closed_genus_zero_mesh_has_genus_f_minus_one() {
    for spec in ["@cube", "@icosahedron", "@cone:6"] {
        let m = prim(spec);
        let w = wireframe(&m, 0.01).unwrap();
        assert_eq!(w.genus(), m.face_count() as i64 - 1, "{spec}");
    }
}

#[test]
fn wireframe_handles_dangling_edges_and_point_spheres() {
    let mut m = prim("@cube");
    let f = m.face_at(5).unwrap();
    let c = m.face_corner(f).unwrap();
    let (_, _, s) = m.create_vertex(DVec3::new(0.0, 0.0, 1.0)).unwrap();
    m.insert_edge(c, s).unwrap();
    m.create_vertex(DVec3::new(5.0, 5.0, 5.0)).unwrap();
    m.validate().unwrap();
    // Straight corners arise on both sides of the dangling edge; the
    // point-sphere is copied as a point-sphere.
    let w = wireframe(&m, 0.05).unwrap();
    w.validate().unwrap();
    let (v, e, f) = wire_counts(&m);
    // The point-sphere: one vertex and one face more, no edge (its vertex
    // has valence 0, so no joint). The dangling edge's tip has valence 1:
    // its strips are triangles, with no monogon joint.
    assert_eq!(counts(&w), (v + 1, e, f + 1));
    assert_eq!(w.genus(), graph_genus(&m));
    no_two_gons_or_loops(&w);
}

/// A lone `n`-gon (one face and its hole) of radius 1 in the plane z = 0.
fn polygon(n: usize) -> Mesh {
    let mut p = PolyMesh::new();
    for k in 0..n {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        p.positions.push(DVec3::new(t.cos(), t.sin(), 0.0));
    }
    p.face_offsets = vec![0, n as u32];
    p.face_indices = (0..n as u32).collect();
    mesh(&p)
}

#[test]
fn wireframe_at_valence_two_has_no_two_gons_and_the_graph_genus() {
    // A cube with one edge split at its midpoint (a vertex of valence 2
    // between two faces), lone polygons (every vertex of valence 2, so
    // the wireframe of an n-gon is a ring: genus n − n + 1 = 1), an open
    // grid (its four corners have valence 2), a cylinder's side (open at
    // both ends) and a prism whose side edges are split twice.
    let mut split = prim("@cube");
    let e = split.edge_at(0).unwrap();
    split.subdivide_edge(e).unwrap();
    let mut prism = prim("@cylinder:5");
    for k in 0..3 {
        let e = prism.edge_at(k).unwrap();
        let half = prism.subdivide_edge(e).unwrap().edges[1];
        prism.subdivide_edge(half).unwrap();
    }
    let cases = [
        ("split cube", split),
        ("triangle", polygon(3)),
        ("hexagon", polygon(6)),
        ("grid", prim("@plane:3:2")),
        ("prism", prism),
    ];
    for (name, m) in cases {
        m.validate().unwrap();
        let two = valences(&m).iter().filter(|&&k| k == 2).count();
        assert!(two > 0, "{name} has vertices of valence 2");
        let w = wireframe(&m, 0.02).unwrap();
        w.validate().unwrap();
        no_two_gons_or_loops(&w);
        assert_eq!(counts(&w), wire_counts(&m), "{name}");
        // Euler's formula over the counts gives the genus E − V + 1 of
        // the (connected) edge graph: χ' = 2V − 2E = 2 − 2g.
        let (v, e) = (m.vertex_count() as i64, m.edge_count() as i64);
        assert_eq!(m.topology().component_count(), 1);
        assert_eq!(w.genus(), e - v + 1, "{name}");
        assert_eq!(w.topology().component_count(), 1, "{name}");
        assert_eq!(w.hole_count(), 0, "{name}");
        assert!(signed_volume(&w) > 0.0, "{name}");
    }
    // The triangle worked out: 3 edges, 3 vertices of valence 2, none of
    // 3 or more: 4·3 = 12 vertices, 10·3 − 2·3 = 24 edges, 4·3 + 0 = 12
    // faces (6 jambs, 3 outer and 3 inner strips): χ = 0, a torus.
    let w = wireframe(&polygon(3), 0.05).unwrap();
    assert_eq!(counts(&w), (12, 24, 12));
    assert_eq!(w.genus(), 1);
}

#[test]
fn wireframe_refusals() {
    let m = prim("@cube");
    for t in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            wireframe(&m, t),
            Err(WireframeError::InvalidThickness(_))
        ));
    }
    // Sides of length 2: an inset of 1.5 turns every face over.
    assert!(matches!(
        wireframe(&m, 1.5),
        Err(WireframeError::ThicknessTooLarge { .. })
    ));
}

#[test]
fn columns_of_a_cube() {
    let m = prim("@cube");
    for n in [3usize, 4, 6] {
        let c = columns(
            &m,
            &ColumnParams {
                sides: n,
                radius: 0.1,
            },
        )
        .unwrap();
        c.validate().unwrap();
        // Worked out for n = 4: 2·4·12 = 96 vertices, 3·4·12 + 8·(2·3) =
        // 192 edges, 4·12 + 8·(3 + 2) = 88 faces; genus 5.
        if n == 4 {
            assert_eq!(counts(&c), (96, 192, 88));
        }
        assert_eq!(counts(&c), column_counts(&m, n));
        assert_eq!(c.genus(), 5);
        assert!(signed_volume(&c) > 0.0, "n = {n}");
    }
}

#[test]
fn columns_genus_and_counts_on_many_meshes() {
    let two = two_apart("@cube", "@octahedron");
    for m in [
        prim("@tetrahedron"),
        prim("@dodecahedron"),
        prim("@torus:8:5"),
        prim("@plane:2:2"),
        prim("@sphere:1"),
        two,
    ] {
        for n in [3usize, 5] {
            let c = columns(
                &m,
                &ColumnParams {
                    sides: n,
                    radius: 0.02,
                },
            )
            .unwrap();
            c.validate().unwrap();
            assert_eq!(counts(&c), column_counts(&m, n));
            assert_eq!(c.genus(), graph_genus(&m));
            assert!(signed_volume(&c) > 0.0);
        }
    }
}

#[test]
fn columns_at_valence_one_and_two() {
    // A lone segment: one column closed at both ends, a prism: 2n, 3n, n + 2.
    let mut m = Mesh::new();
    let (_, _, a) = m.create_vertex(DVec3::ZERO).unwrap();
    let (_, _, b) = m.create_vertex(DVec3::new(3.0, 0.0, 0.0)).unwrap();
    m.insert_edge(a, b).unwrap();
    let c = columns(
        &m,
        &ColumnParams {
            sides: 5,
            radius: 0.2,
        },
    )
    .unwrap();
    c.validate().unwrap();
    assert_eq!(counts(&c), (10, 15, 7));
    assert_eq!(c.genus(), 0);
    // A triangle "sphere" (two triangles back to back): three vertices of
    // valence 2, a ring of three columns: genus 3 − 3 + 1 = 1.
    let mut m = Mesh::new();
    m.create_face_manifold(&[
        DVec3::ZERO,
        DVec3::new(4.0, 0.0, 0.0),
        DVec3::new(0.0, 4.0, 0.0),
    ])
    .unwrap();
    let c = columns(
        &m,
        &ColumnParams {
            sides: 4,
            radius: 0.2,
        },
    )
    .unwrap();
    c.validate().unwrap();
    assert_eq!(counts(&c), column_counts(&m, 4));
    assert_eq!(c.genus(), 1);
}

#[test]
fn column_refusals() {
    let m = prim("@cube");
    assert_eq!(
        columns(
            &m,
            &ColumnParams {
                sides: 2,
                radius: 0.1
            }
        )
        .unwrap_err(),
        WireframeError::TooFewSides(2)
    );
    for r in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            columns(
                &m,
                &ColumnParams {
                    sides: 4,
                    radius: r
                }
            ),
            Err(WireframeError::InvalidThickness(_))
        ));
    }
    // Edges of length 2 with right angles: ports sit r/sin 45° from each
    // vertex, so r = 0.8 makes them overlap.
    assert!(matches!(
        columns(
            &m,
            &ColumnParams {
                sides: 4,
                radius: 0.8
            }
        ),
        Err(WireframeError::EdgeTooShort { .. })
    ));
}

#[test]
fn wireframe_of_an_open_grid_straddles_its_boundary() {
    // @plane:2:2 covers [-1,1]²: the tubes along its boundary reach out to
    // the thickness beyond it and no further; no vertex folds back.
    let m = prim("@plane:2:2");
    let w = wireframe(&m, 0.1).unwrap();
    w.validate().unwrap();
    assert_eq!(w.genus(), graph_genus(&m));
    assert_eq!(w.genus(), 12 - 9 + 1);
    let mut outside = 0;
    for v in w.vertices() {
        let p = w.position(v).unwrap();
        assert!(p.x.abs() <= 1.1 + 1e-12 && p.y.abs() <= 1.1 + 1e-12, "{p}");
        if p.x.abs() > 1.0 + 1e-12 || p.y.abs() > 1.0 + 1e-12 {
            outside += 1;
        }
    }
    // The hole's 8 corners, each with an outer and an inner copy.
    assert_eq!(outside, 16);
}

/// The lone quad (−1,0,0), (0,ε,h), (1,0,0), (0,1,h): bent along its
/// diagonals, so its second corner (157° between its edges) lies almost
/// straight in the face's plane (in-plane sine about ε), like Suzanne's
/// face 466. Measuring the corner's angle in that plane against its
/// edges' own sum put its copy 0.05 / 2·10⁻⁴ ≈ 100 units away and the
/// quad was refused at every thickness.
fn bent_quad(eps: f64, h: f64) -> Mesh {
    let mut p = PolyMesh::new();
    p.positions = vec![
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(0.0, eps, h),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, h),
    ];
    p.face_offsets = vec![0, 4];
    p.face_indices = vec![0, 1, 2, 3];
    mesh(&p)
}

#[test]
fn wireframe_of_a_non_planar_quad_keeps_its_corners_near() {
    for eps in [0.0, 1e-4, 1e-3, -1e-4] {
        let m = bent_quad(eps, 0.2);
        for w in [0.01, 0.05] {
            let out = wireframe(&m, w).unwrap();
            out.validate().unwrap();
            assert_eq!(counts(&out), wire_counts(&m));
            assert_eq!(out.genus(), graph_genus(&m));
            // Every corner's copy (and the inner layer w below it) stays
            // near the corner: the miter is w / sin(θ/2) for the corner's
            // in-plane angle θ, here at most w / sin(22°) < 3w, so every
            // vertex is within 4w of an input vertex.
            let input: Vec<DVec3> = m.vertices().map(|v| m.position(v).unwrap()).collect();
            for v in out.vertices() {
                let q = out.position(v).unwrap();
                let near = input.iter().map(|p| p.distance(q)).fold(f64::MAX, f64::min);
                assert!(near <= 4.0 * w, "eps {eps}, w {w}: {q} is {near} away");
            }
        }
    }
}

#[test]
fn wireframe_thins_its_tubes_in_a_sliver_instead_of_refusing() {
    // A 2×2 square with a sliver triangle 10⁻³ high along one side:
    // tubes of 0.05 do not fit in the sliver, so its copy is held back
    // to a third of its edges (it keeps its orientation) and the rest of
    // the mesh gets the full thickness.
    let mut p = PolyMesh::new();
    p.positions = vec![
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
        DVec3::new(0.0, -1.001, 0.0),
    ];
    p.face_offsets = vec![0, 4, 7];
    p.face_indices = vec![0, 1, 2, 3, 0, 4, 1];
    let m = mesh(&p);
    let out = wireframe(&m, 0.05).unwrap();
    out.validate().unwrap();
    assert_eq!(counts(&out), wire_counts(&m));
    assert_eq!(out.genus(), graph_genus(&m));
    // Inside the square's window: the copy of the square's corner
    // (1, 1) sits at (0.95, 0.95), the full thickness in from both sides.
    let hits = out
        .vertices()
        .filter(|&v| {
            let q = out.position(v).unwrap();
            (q.x - 0.95).abs() < 1e-12 && (q.y - 0.95).abs() < 1e-12 && q.z.abs() < 1e-12
        })
        .count();
    assert_eq!(hits, 1);
    // Too thick for every corner: refused, the mesh unchanged.
    assert!(matches!(
        wireframe(&m, 5.0),
        Err(WireframeError::ThicknessTooLarge { .. })
    ));
}
