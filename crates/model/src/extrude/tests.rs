//! Tests of the extrusions: counts worked out from the definitions (and
//! checked against Euler's formula), `validate()` after every call,
//! geometry where a kind promises a regular solid, refusals that leave the
//! mesh unchanged, faces of different sizes and meshes with holes.

use crate::test_util::{check, prim, shared_edge, signed_volume, state, unchanged};
use holey_dlfl::{DVec3, FaceId, Mesh, VertexId};

use super::*;
use crate::polygon;

fn face(m: &Mesh, i: usize) -> FaceId {
    m.face_at(i).unwrap()
}

/// Applies `op` and asserts the change (ΔV, ΔE, ΔF), and that genus and
/// components did not change.
fn expect_delta(m: &mut Mesh, delta: (i64, i64, i64), op: impl FnOnce(&mut Mesh)) {
    let before = state(m);
    op(m);
    check(m);
    let after = state(m);
    assert_eq!(
        (after.0 - before.0, after.1 - before.1, after.2 - before.2),
        delta,
        "ΔV, ΔE, ΔF"
    );
    assert_eq!(
        (after.3, after.4),
        (before.3, before.4),
        "components, genus"
    );
}

/// [`expect_delta`] of one plain extrusion of face `f` by `distance`,
/// `count` times.
fn expect_plain_delta(
    m: &mut Mesh,
    f: FaceId,
    distance: f64,
    count: usize,
    delta: (i64, i64, i64),
) {
    expect_delta(m, delta, |m| {
        extrude_face(m, f, &ExtrudeParams::new(distance, count)).unwrap();
    });
}

/// [`expect_delta`] on a copy of `m0`, leaving `m0` for the next
/// operation tried on the same face.
fn expect_delta_on_copy(m0: &Mesh, delta: (i64, i64, i64), op: impl FnOnce(&mut Mesh)) {
    expect_delta(&mut m0.clone(), delta, op);
}

fn edge_lengths(m: &Mesh) -> Vec<f64> {
    m.edges()
        .map(|e| {
            let [a, b] = m.edge_vertices(e).unwrap();
            m.position(a).unwrap().distance(m.position(b).unwrap())
        })
        .collect()
}

/// Every edge of `m` has length `a` (to a relative 1e-9).
fn every_edge_has_length(m: &Mesh, a: f64) {
    for l in edge_lengths(m) {
        assert!((l - a).abs() < 1e-9 * a, "{l} vs {a}");
    }
}

/// `m` holds twice the volume of the primitive `spec`: two copies of the
/// solid glued on a face.
fn is_two_glued(m: &Mesh, spec: &str) {
    let one = signed_volume(&prim(spec));
    assert!((signed_volume(m) - 2.0 * one).abs() < 1e-9);
}

fn max_non_planarity(m: &Mesh, f: FaceId) -> f64 {
    let p = m.face_positions(f).unwrap();
    let (c, n) = polygon::best_fit_plane(&p).unwrap();
    p.iter().map(|q| (*q - c).dot(n).abs()).fold(0.0, f64::max)
}

// ---------------------------------------------------------------------
// Plain extrusion.

#[test]
fn one_extrusion_of_a_quad_adds_4_8_4() {
    let mut m = prim("@cube");
    let f = face(&m, 5);
    let d = m.face_len(f).unwrap() as i64;
    // Definition: each of the d corners gets a new vertex, each of the d
    // edges a wall quad whose top edge is new, plus the d vertical edges.
    expect_delta(&mut m, (d, 2 * d, d), |m| {
        let out = extrude_face(m, f, &ExtrudeParams::new(1.0, 1)).unwrap();
        assert_eq!(m.face_len(out.top).unwrap(), 4);
        assert_eq!(out.sides.len(), 4);
        for s in &out.sides {
            assert_eq!(m.face_len(*s).unwrap(), 4);
        }
        assert_eq!(out.vertices.len(), 4);
    });
    assert_eq!(state(&m).0, 12);
    // The cube [-1,1]^3 with a unit-high box on top: 8 + 2·2·1.
    assert!((signed_volume(&m) - 12.0).abs() < 1e-12);
}

#[test]
fn repeated_extrusion_adds_one_ring_per_repetition() {
    for (spec, k) in [("@cube", 3usize), ("@tetrahedron", 2), ("@dodecahedron", 4)] {
        let mut m = prim(spec);
        let f = face(&m, 0);
        let d = m.face_len(f).unwrap() as i64;
        let k64 = k as i64;
        expect_delta(&mut m, (k64 * d, 2 * k64 * d, k64 * d), |m| {
            let params = ExtrudeParams {
                distance: 0.3,
                rotation_deg: 10.0,
                scale: 0.9,
                count: k,
            };
            let out = extrude_face(m, f, &params).unwrap();
            assert_eq!(out.sides.len(), k * d as usize);
            assert_eq!(m.face_len(out.top).unwrap() as i64, d);
        });
    }
}

#[test]
fn extrusion_moves_turns_and_scales_the_top() {
    let mut m = prim("@cube");
    let f = face(&m, 5); // the +z side
    let base = m.face_positions(f).unwrap();
    let params = ExtrudeParams {
        distance: 2.0,
        rotation_deg: 90.0,
        scale: 0.5,
        count: 1,
    };
    let out = extrude_face(&mut m, f, &params).unwrap();
    check(&m);
    let top: Vec<DVec3> = m
        .face_corners_from(out.top_start)
        .unwrap()
        .map(|c| m.position(m.corner_vertex(c).unwrap()).unwrap())
        .collect();
    // +z face of [-1,1]^3, centroid (0,0,1): halve, turn 90° about +z,
    // lift by 2.
    for (p, q) in base.iter().zip(&top) {
        let expect = DVec3::new(-p.y * 0.5, p.x * 0.5, 3.0);
        assert!((expect - *q).length() < 1e-12, "{q} vs {expect}");
    }
}

#[test]
fn zero_distance_and_next_to_a_hole_extrusions_are_valid() {
    for (spec, index, distance, count, delta) in [
        ("@cube", 0, 0.0, 1, (4, 8, 4)),
        // A corner quad of an open grid touches the boundary loop on two
        // edges.
        ("@plane:2:2", 0, 0.5, 2, (8, 16, 8)),
    ] {
        let mut m = prim(spec);
        let f = face(&m, index);
        expect_plain_delta(&mut m, f, distance, count, delta);
    }
}

/// Checks that an extrusion was refused as too large (a count whose size
/// would wrap) and left `m` as `m0` was.
fn too_large_and_unchanged(result: Result<Extruded, ExtrudeError>, m: &Mesh, m0: &Mesh) {
    let err = result.unwrap_err();
    assert!(matches!(err, ExtrudeError::TooLarge { .. }), "{err}");
    unchanged(m, m0);
}

#[test]
fn degenerate_parameters_are_refused_and_change_nothing() {
    let m0 = prim("@cube");
    let f = face(&m0, 0);
    for params in [
        ExtrudeParams::new(f64::NAN, 1),
        ExtrudeParams::new(f64::INFINITY, 1),
        ExtrudeParams::new(1.0, 0),
        ExtrudeParams {
            scale: 0.0,
            ..ExtrudeParams::default()
        },
        ExtrudeParams {
            scale: -1.0,
            ..ExtrudeParams::default()
        },
        ExtrudeParams {
            rotation_deg: f64::NAN,
            ..ExtrudeParams::default()
        },
        ExtrudeParams::new(1e308, 3),
    ] {
        let mut m = m0.clone();
        let err = extrude_face(&mut m, f, &params).unwrap_err();
        assert!(
            matches!(
                err,
                ExtrudeError::InvalidParameter { .. } | ExtrudeError::NonFinite { .. }
            ),
            "{params:?}: {err}"
        );
        unchanged(&m, &m0);
    }
    let mut m = m0.clone();
    let result = extrude_face(&mut m, f, &ExtrudeParams::new(1.0, usize::MAX));
    too_large_and_unchanged(result, &m, &m0);
}

#[test]
fn stale_hole_and_degenerate_faces_are_refused() {
    // A stale id.
    let mut m = prim("@cube");
    let f = face(&m, 0);
    extrude_face(&mut m, f, &ExtrudeParams::default()).unwrap();
    let before = m.clone();
    if !m.contains_face(f) {
        let err = extrude_face(&mut m, f, &ExtrudeParams::default()).unwrap_err();
        assert!(matches!(err, ExtrudeError::Kernel(_)), "{err}");
        unchanged(&m, &before);
    }
    // The hole of an open plane.
    let mut m = prim("@plane:2:2");
    let hole = m.faces().find(|&f| m.is_hole(f).unwrap()).unwrap();
    let before = m.clone();
    let err = extrude_face(&mut m, hole, &ExtrudeParams::default()).unwrap_err();
    assert_eq!(err, ExtrudeError::HoleFace(hole));
    unchanged(&m, &before);
    // A point-sphere and a two-gon (no area, no normal).
    let mut m = Mesh::new();
    let (_, ps, c0) = m.create_vertex(DVec3::ZERO).unwrap();
    let err = extrude_face(&mut m, ps, &ExtrudeParams::default()).unwrap_err();
    assert_eq!(err, ExtrudeError::PointSphere(ps));
    let (_, _, c1) = m.create_vertex(DVec3::X).unwrap();
    m.insert_edge(c0, c1).unwrap();
    let two = m.corner_face(c0).unwrap();
    // A segment's single face has corners v0, v1: zero area.
    let before = m.clone();
    let err = extrude_face(&mut m, two, &ExtrudeParams::default()).unwrap_err();
    assert_eq!(err, ExtrudeError::DegenerateFace(two));
    unchanged(&m, &before);
}

#[test]
fn faces_of_different_sizes_and_open_meshes() {
    // Triangles, quads, pentagons, a cylinder's 16-gon cap, and a plane
    // with a boundary: each extrusion adds d/2d/d and keeps the holes.
    for (spec, idx) in [
        ("@tetrahedron", 1),
        ("@octahedron", 3),
        ("@dodecahedron", 7),
        ("@cylinder", 0),
        ("@cone:7", 0),
        ("@plane:3:3", 4),
        ("@torus:8:6", 5),
    ] {
        let mut m = prim(spec);
        let f = face(&m, idx);
        let d = m.face_len(f).unwrap() as i64;
        let holes = m.hole_count();
        expect_plain_delta(&mut m, f, 0.25, 1, (d, 2 * d, d));
        assert_eq!(m.hole_count(), holes, "{spec}");
    }
}

#[test]
fn a_face_with_a_dangling_edge_extrudes() {
    // A dangling edge inside the top face: its loose end moves with the
    // face and the edge stays inside the lifted face.
    let mut m = prim("@cube");
    let f = face(&m, 5);
    let c = m.face_corner(f).unwrap();
    let (x, _, s) = m.create_vertex(DVec3::new(0.0, 0.0, 1.0)).unwrap();
    m.insert_edge(c, s).unwrap();
    check(&m);
    let f = m.corner_face(s).unwrap();
    let d = m.face_len(f).unwrap() as i64; // 4 corners + 2 for the dangling edge
    assert_eq!(d, 6);
    // Fans: the 3 plain corners, and at the attachment vertex one fan of
    // two corners (the dangling edge is inside the selection) — 4 fans,
    // as many as boundary edges. The loose end is interior and moves.
    expect_plain_delta(&mut m, f, 1.0, 1, (4, 8, 4));
    assert!((m.position(x).unwrap().z - 2.0).abs() < 1e-12);
}

// ---------------------------------------------------------------------
// Multi-face extrusion.

#[test]
fn two_adjacent_quads_share_their_walls() {
    // Two neighbouring quads of a 2×1 grid region of @cube:2's bottom:
    // b = 6 boundary sides, so +6/+12/+6 (one by one would be 8/16/8).
    let mut m = prim("@cube:2");
    let (a, b) = (face(&m, 0), face(&m, 1));
    assert!(shared_edge(&m, a, b).is_some());
    expect_delta(&mut m, (6, 12, 6), |m| {
        let out = extrude_faces(m, &[a, b], &MultiExtrudeParams::default()).unwrap();
        assert_eq!(out.tops.len(), 2);
        assert_eq!(out.walls.len(), 6);
        assert!(shared_edge(m, out.tops[0], out.tops[1]).is_some());
    });
}

/// Boundary sides of a selection, counted from the definition: edges
/// with a selected face on exactly one side.
fn boundary_sides(m: &Mesh, faces: &[FaceId]) -> i64 {
    m.edges()
        .filter(|&e| {
            let [x, y] = m.edge_faces(e).unwrap();
            faces.contains(&x) != faces.contains(&y)
        })
        .count() as i64
}

#[test]
fn multi_face_counts_follow_the_boundary() {
    let mut rng = holey_testkit::Rng::new(18);
    for spec in [
        "@cube:3",
        "@torus:8:6",
        "@sphere:1",
        "@plane:4:4",
        "@quad-sphere:3",
    ] {
        for _ in 0..6 {
            let mut m = prim(spec);
            let all: Vec<FaceId> = m.faces().filter(|&f| !m.is_hole(f).unwrap()).collect();
            let mut sel: Vec<FaceId> = all.iter().copied().filter(|_| rng.chance(0.3)).collect();
            if sel.is_empty() {
                sel.push(all[0]);
            }
            let b = boundary_sides(&m, &sel);
            let params = MultiExtrudeParams {
                distance: 0.1,
                direction: if rng.chance(0.5) {
                    RegionDirection::Average
                } else {
                    RegionDirection::VertexNormals
                },
                count: 1,
            };
            let before = m.clone();
            match extrude_faces(&mut m, &sel, &params) {
                Ok(out) => {
                    check(&m);
                    let (v0, e0, f0, c0, g0) = state(&before);
                    assert_eq!(state(&m), (v0 + b, e0 + 2 * b, f0 + b, c0, g0), "{spec}");
                    assert_eq!(out.tops.len(), sel.len(), "{spec}");
                    assert_eq!(out.walls.len() as i64, b);
                }
                Err(ExtrudeError::NoDirection { .. }) => unchanged(&m, &before),
                Err(e) => panic!("{spec}: {e}"),
            }
        }
    }
}

#[test]
fn multi_face_repeats_and_refusals() {
    let mut m = prim("@cube:2");
    let sel: Vec<FaceId> = (0..4).map(|i| face(&m, i)).collect(); // the whole -z side
    let b = boundary_sides(&m, &sel);
    assert_eq!(b, 8);
    expect_delta(&mut m, (3 * b, 6 * b, 3 * b), |m| {
        let p = MultiExtrudeParams {
            distance: 0.2,
            count: 3,
            ..MultiExtrudeParams::default()
        };
        let out = extrude_faces(m, &sel, &p).unwrap();
        assert_eq!(out.tops.len(), 4);
        // The lifted side is 0.6 below the cube's bottom.
        for t in out.tops {
            for p in m.face_positions(t).unwrap() {
                assert!((p.z + 1.6).abs() < 1e-12);
            }
        }
    });
    // Every face of a closed cube: the normals cancel.
    let m0 = prim("@cube");
    let mut m = m0.clone();
    let all: Vec<FaceId> = m.faces().collect();
    let err = extrude_faces(&mut m, &all, &MultiExtrudeParams::default()).unwrap_err();
    assert!(matches!(err, ExtrudeError::NoDirection { .. }), "{err}");
    unchanged(&m, &m0);
    // Empty, hole, NaN.
    let err = extrude_faces(&mut m, &[], &MultiExtrudeParams::default()).unwrap_err();
    assert_eq!(err, ExtrudeError::EmptySelection);
    let mut p = prim("@plane:2:2");
    let p0 = p.clone();
    let hole = p.faces().find(|&f| p.is_hole(f).unwrap()).unwrap();
    let f0 = face(&p, 0);
    let err = extrude_faces(&mut p, &[f0, hole], &MultiExtrudeParams::default()).unwrap_err();
    assert_eq!(err, ExtrudeError::HoleFace(hole));
    unchanged(&p, &p0);
    let nan = MultiExtrudeParams {
        distance: f64::NAN,
        ..MultiExtrudeParams::default()
    };
    assert!(matches!(
        extrude_faces(&mut p, &[f0], &nan),
        Err(ExtrudeError::InvalidParameter { .. })
    ));
    unchanged(&p, &p0);
}

#[test]
fn faces_meeting_at_a_vertex_only_get_two_fans_there() {
    // Two diagonal quads of a 2×2 grid meet at the centre vertex only:
    // it has two fans, so it splits in two; b = 8.
    let mut m = prim("@plane:2:2");
    let sel = [face(&m, 0), face(&m, 3)];
    assert_eq!(boundary_sides(&m, &sel), 8);
    expect_delta(&mut m, (8, 16, 8), |m| {
        extrude_faces(m, &sel, &MultiExtrudeParams::default()).unwrap();
    });
}

// ---------------------------------------------------------------------
// The polyhedral extrusions.

#[test]
fn doo_sabin_counts_and_shrink() {
    let mut m = prim("@cube");
    let f = face(&m, 5);
    expect_delta(&mut m, (8, 16, 8), |m| {
        let p = DooSabinParams {
            distance: 1.0,
            twist: 0.0,
            scale: 1.0,
            count: 2,
        };
        let out = extrude_face_doo_sabin(m, f, &p).unwrap();
        // The first Fourier mode of the Doo–Sabin mask has eigenvalue 1/2:
        // each ring is half as wide; two rings: a quarter of √2.
        let top = m.face_positions(out.top).unwrap();
        let c = polygon::centroid(&top);
        for p in &top {
            assert!(((*p - c).length() - 2f64.sqrt() / 4.0).abs() < 1e-12);
        }
        assert!((c - DVec3::new(0.0, 0.0, 3.0)).length() < 1e-12);
    });
}

#[test]
fn cubical_extrusion_grows_cubes() {
    let mut m = prim("@cube");
    let f = face(&m, 5);
    expect_delta(&mut m, (8, 16, 8), |m| {
        extrude_face_cubical(m, f, 1.0, 2).unwrap();
    });
    // The cube [-1,1]^3 and two more cubes of edge 2.
    assert!((signed_volume(&m) - 24.0).abs() < 1e-9);
}

/// Extrudes face `index` of the regular solid `spec` by `extrude` at
/// height factor 1 and returns the mesh, asserting the change `delta`
/// (ΔV, ΔE, ΔF), a top the size of the base, `sides` planar walls of
/// `side` corners each, and that every edge, old and new, keeps the
/// solid's edge length.
fn grows_regular(
    spec: &str,
    index: usize,
    extrude: fn(&mut Mesh, FaceId, f64) -> Result<Extruded, ExtrudeError>,
    delta: (i64, i64, i64),
    (sides, side): (usize, usize),
) -> Mesh {
    let mut m = prim(spec);
    let f = face(&m, index);
    let d = m.face_len(f).unwrap();
    let a = edge_lengths(&m)[0];
    expect_delta(&mut m, delta, |m| {
        let out = extrude(m, f, 1.0).unwrap();
        assert_eq!(m.face_len(out.top).unwrap(), d);
        assert_eq!(out.sides.len(), sides);
        for s in &out.sides {
            assert_eq!(m.face_len(*s).unwrap(), side);
            assert!(max_non_planarity(m, *s) < 1e-9);
        }
    });
    every_edge_has_length(&m, a);
    m
}

#[test]
fn octahedral_extrusion_of_a_regular_triangle_is_a_regular_octahedron() {
    grows_regular(
        "@tetrahedron",
        3,
        extrude_face_octahedral,
        (3, 9, 6),
        (6, 3),
    );
}

#[test]
fn golden_extrusions_of_a_regular_face_are_regular_solids() {
    // A regular pentagon grows a regular dodecahedron, a regular triangle
    // a regular icosahedron, glued to the solid it stood on.
    type Extrude = fn(&mut Mesh, FaceId, f64) -> Result<Extruded, ExtrudeError>;
    for (spec, index, extrude, delta, sides) in [
        (
            "@dodecahedron",
            11,
            extrude_face_dodecahedral as Extrude,
            (15, 25, 10),
            (10, 5),
        ),
        (
            "@icosahedron",
            19,
            extrude_face_icosahedral,
            (9, 27, 18),
            (18, 3),
        ),
    ] {
        let m = grows_regular(spec, index, extrude, delta, sides);
        is_two_glued(&m, spec);
    }
}

#[test]
fn polyhedral_extrusions_on_other_face_sizes() {
    // The counts hold for any d, whatever the shapes look like.
    for (spec, idx) in [
        ("@cube", 2),
        ("@cylinder:7", 1),
        ("@plane:2:2", 3),
        ("@tetrahedron", 0),
    ] {
        let m0 = prim(spec);
        let f = face(&m0, idx);
        let d = m0.face_len(f).unwrap() as i64;
        expect_delta_on_copy(&m0, (d, 3 * d, 2 * d), |m| {
            extrude_face_octahedral(m, f, 0.7).unwrap();
        });
        expect_delta_on_copy(&m0, (3 * d, 5 * d, 2 * d), |m| {
            extrude_face_dodecahedral(m, f, 0.7).unwrap();
        });
        expect_delta_on_copy(&m0, (3 * d, 9 * d, 6 * d), |m| {
            extrude_face_icosahedral(m, f, 0.7).unwrap();
        });
        expect_delta_on_copy(&m0, (1, d, d - 1), |m| {
            stellate_face(m, f, 0.5).unwrap();
        });
        expect_delta_on_copy(&m0, (d + 1, 4 * d, 3 * d - 1), |m| {
            double_stellate_face(m, f, 0.5).unwrap();
        });
        for k in [1usize, 3, 5] {
            let k64 = k as i64;
            expect_delta_on_copy(&m0, (k64 * d + 1, 2 * k64 * d + d, k64 * d + d - 1), |m| {
                let p = DomeParams {
                    height_factor: 1.0,
                    rings: k,
                };
                extrude_face_dome(m, f, &p).unwrap();
            });
        }
    }
}

#[test]
fn stellation_apex_and_refusals() {
    let mut m = prim("@cube");
    let f = face(&m, 5);
    let out = stellate_face(&mut m, f, 0.5).unwrap();
    check(&m);
    let apex: VertexId = out.vertices[0];
    assert!((m.position(apex).unwrap() - DVec3::new(0.0, 0.0, 1.5)).length() < 1e-12);
    assert_eq!(m.valence(apex).unwrap(), 4);
    let m0 = prim("@cube");
    for h in [f64::NAN, f64::INFINITY] {
        let mut m = m0.clone();
        assert!(stellate_face(&mut m, face(&m0, 0), h).is_err());
        assert!(double_stellate_face(&mut m, face(&m0, 0), h).is_err());
        unchanged(&m, &m0);
    }
    for hf in [0.0, -1.0, f64::NAN] {
        let mut m = m0.clone();
        let f = face(&m0, 0);
        assert!(extrude_face_octahedral(&mut m, f, hf).is_err());
        assert!(extrude_face_dodecahedral(&mut m, f, hf).is_err());
        assert!(extrude_face_icosahedral(&mut m, f, hf).is_err());
        assert!(extrude_face_cubical(&mut m, f, hf, 1).is_err());
        let dome = DomeParams {
            height_factor: hf,
            rings: 2,
        };
        assert!(extrude_face_dome(&mut m, f, &dome).is_err());
        unchanged(&m, &m0);
    }
    let mut m = m0.clone();
    let zero_rings = DomeParams {
        height_factor: 1.0,
        rings: 0,
    };
    assert!(extrude_face_dome(&mut m, face(&m0, 0), &zero_rings).is_err());
    unchanged(&m, &m0);
    // So many rings that their size would wrap: refused as too large.
    let endless = DomeParams {
        height_factor: 1.0,
        rings: usize::MAX,
    };
    let result = extrude_face_dome(&mut m, face(&m0, 0), &endless);
    too_large_and_unchanged(result, &m, &m0);
}

#[test]
fn dome_lies_on_a_half_sphere() {
    let mut m = prim("@cube");
    let f = face(&m, 5);
    let out = extrude_face_dome(&mut m, f, &DomeParams::default()).unwrap();
    check(&m);
    // Over the +z square (circumradius √2, centre (0,0,1)) every new
    // vertex is at distance √2 from the centre.
    for v in out.vertices {
        let d = m.position(v).unwrap().distance(DVec3::new(0.0, 0.0, 1.0));
        assert!((d - 2f64.sqrt()).abs() < 1e-12, "{d}");
    }
}

#[test]
fn a_refused_later_repetition_leaves_the_mesh_unchanged() {
    // The first step of 1e308 is finite, the second is not: refused as
    // repetition 2 of 5, with the mesh as before the first, along the
    // average direction and along vertex normals alike.
    for direction in [RegionDirection::Average, RegionDirection::VertexNormals] {
        let mut m = prim("@plane:4:4");
        let before = m.clone();
        let sel = [face(&m, 5), face(&m, 6)];
        let p = MultiExtrudeParams {
            distance: 1e308,
            direction,
            count: 5,
        };
        match extrude_faces(&mut m, &sel, &p) {
            Err(ExtrudeError::Repeated {
                step: 2,
                count: 5,
                cause,
            }) => {
                assert!(matches!(*cause, ExtrudeError::NonFinite { .. }), "{cause}");
            }
            other => panic!("{other:?}"),
        }
        unchanged(&m, &before);
        m.validate().unwrap();
    }
}

#[test]
fn a_non_finite_point_is_named_and_placed() {
    // Plain, 1e308 three times: ring 0 is finite, ring 1 (points 4..8 of
    // the quad) is the first to overflow, at its first corner.
    let mut m = prim("@cube");
    let before = m.clone();
    let f = face(&m, 2);
    match extrude_face(&mut m, f, &ExtrudeParams::new(1e308, 3)) {
        Err(ExtrudeError::NonFinite { face: g, point }) => {
            assert_eq!(g, f);
            assert_eq!((point.what, point.index), ("new point", Some(4)));
            assert!(point.position.is_some_and(|p| !p.is_finite()), "{point}");
        }
        other => panic!("{other:?}"),
    }
    unchanged(&m, &before);
    // Together: the second repetition's lifts overflow; the cause names a
    // corner of a face the first made, and where the lift would go.
    let mut m = prim("@plane:4:4");
    let p = MultiExtrudeParams {
        distance: 1e308,
        direction: RegionDirection::Average,
        count: 2,
    };
    let sel = [face(&m, 5)];
    let Err(ExtrudeError::Repeated { cause, .. }) = extrude_faces(&mut m, &sel, &p) else {
        panic!("not refused as a repetition");
    };
    let ExtrudeError::NonFinite { face: g, point } = *cause else {
        panic!("{cause}");
    };
    assert_eq!(point.what, "the lift of corner");
    assert!(point.index.is_some_and(|k| k < 4), "{point}");
    assert!(
        point.position.is_some_and(|p| p.z == f64::INFINITY),
        "{point}"
    );
    // That face was made by the first repetition, which was put back.
    assert!(m.is_hole(g).is_err());
}

#[test]
fn kinds_and_options_by_name() {
    for kind in ExtrudeKind::ALL {
        assert_eq!(kind.name().parse::<ExtrudeKind>(), Ok(kind));
    }
    assert_eq!(
        "pyramid".parse::<ExtrudeKind>().unwrap_err().to_string(),
        "extrusion kind \"pyramid\" is not known: use plain, cubical, dodecahedral, icosahedral, \
         octahedral, doo-sabin, dome, stellate or double-stellate"
    );
    let rotate = ExtrudeOptions {
        rotation_deg: Some(5.0),
        ..ExtrudeOptions::default()
    };
    assert_eq!(rotate.check(ExtrudeKind::Plain), Ok(()));
    assert_eq!(
        rotate.check(ExtrudeKind::Cubical),
        Err(ExtrudeError::Unread {
            option: ExtrudeOption::Rotation,
            kind: ExtrudeKind::Cubical
        })
    );
    let together = ExtrudeOptions {
        together: Some(RegionDirection::Average),
        ..rotate
    };
    assert_eq!(
        together.check(ExtrudeKind::Dome),
        Err(ExtrudeError::TogetherNotPlain(ExtrudeKind::Dome))
    );
    assert_eq!(
        together.check(ExtrudeKind::Plain),
        Err(ExtrudeError::UnreadTogether {
            option: ExtrudeOption::Rotation
        })
    );
    // Every kind reads something, and what it reads is accepted.
    for kind in ExtrudeKind::ALL {
        let read: Vec<_> = ExtrudeOption::ALL
            .into_iter()
            .filter(|&o| kind.reads(o))
            .collect();
        assert!(!read.is_empty(), "{kind}");
    }
}

#[test]
fn a_selection_extrudes_by_kind_with_the_kinds_counts() {
    // One by one, each kind on two faces of a cube adds twice its d = 4
    // counts (the module's table; dome with its default 5 rings).
    let d = 4i64;
    let cases = [
        (ExtrudeKind::Plain, (d, 2 * d, d)),
        (ExtrudeKind::Cubical, (d, 2 * d, d)),
        (ExtrudeKind::DooSabin, (d, 2 * d, d)),
        (ExtrudeKind::Octahedral, (d, 3 * d, 2 * d)),
        (ExtrudeKind::Dodecahedral, (3 * d, 5 * d, 2 * d)),
        (ExtrudeKind::Icosahedral, (3 * d, 9 * d, 6 * d)),
        (ExtrudeKind::Stellate, (1, d, d - 1)),
        (ExtrudeKind::DoubleStellate, (d + 1, 4 * d, 3 * d - 1)),
        (ExtrudeKind::Dome, (5 * d + 1, 10 * d + d, 5 * d + d - 1)),
    ];
    for (kind, (dv, de, df)) in cases {
        let mut m = prim("@cube");
        let (v, e, f, ..) = state(&m);
        let faces = [face(&m, 0), face(&m, 1)];
        let tops = extrude_selection(&mut m, &faces, kind, &ExtrudeOptions::default()).unwrap();
        assert_eq!(tops.len(), 2, "{kind}");
        check(&m);
        assert_eq!(state(&m).0 - v, 2 * dv, "{kind} V");
        assert_eq!(state(&m).1 - e, 2 * de, "{kind} E");
        assert_eq!(state(&m).2 - f, 2 * df, "{kind} F");
    }
    // Together: two quads sharing an edge have 6 boundary sides.
    let mut m = prim("@plane:4:4");
    let (v, e, f, ..) = state(&m);
    let options = ExtrudeOptions {
        distance: Some(0.5),
        together: Some(RegionDirection::Average),
        ..ExtrudeOptions::default()
    };
    let faces = [face(&m, 5), face(&m, 6)];
    let tops = extrude_selection(&mut m, &faces, ExtrudeKind::Plain, &options).unwrap();
    assert_eq!(tops.len(), 2);
    check(&m);
    assert_eq!(state(&m).0 - v, 6);
    assert_eq!(state(&m).1 - e, 12);
    assert_eq!(state(&m).2 - f, 6);
}

#[test]
fn a_refused_face_of_a_selection_puts_the_earlier_ones_back() {
    // Face 0 is extruded, then the hole is refused: the mesh is as before
    // and the refusal names the hole.
    let mut m = prim("@plane:2:2");
    let before = m.clone();
    let hole = m.faces().find(|&f| m.is_hole(f).unwrap()).unwrap();
    let faces = [face(&m, 0), hole];
    let err = extrude_selection(
        &mut m,
        &faces,
        ExtrudeKind::Plain,
        &ExtrudeOptions::default(),
    )
    .unwrap_err();
    assert_eq!(
        err,
        ExtrudeError::Face {
            face: hole,
            cause: Box::new(ExtrudeError::HoleFace(hole))
        }
    );
    unchanged(&m, &before);
    // Nothing selected, and options refused before anything is done.
    assert_eq!(
        extrude_selection(&mut m, &[], ExtrudeKind::Plain, &ExtrudeOptions::default()),
        Err(ExtrudeError::EmptySelection)
    );
    let twisted = ExtrudeOptions {
        twist: Some(0.1),
        ..ExtrudeOptions::default()
    };
    let first = [face(&m, 0)];
    assert!(matches!(
        extrude_selection(&mut m, &first, ExtrudeKind::Plain, &twisted),
        Err(ExtrudeError::Unread { .. })
    ));
    unchanged(&m, &before);
}
