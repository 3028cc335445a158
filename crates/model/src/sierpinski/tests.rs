//! Unit tests of the Sierpinski scheme: exact counts against the thesis's
//! numbers and the closed-form counts of the module documentation,
//! `validate()` after every step.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{DVec3, Mesh, RawMesh};

use super::*;
use crate::test_util::prim;

fn loops(m: &Mesh) -> usize {
    m.edges().filter(|&e| m.is_self_loop(e).unwrap()).count()
}

/// (V, E, F, genus, self-loops).
fn counts(m: &Mesh) -> (usize, usize, usize, i64, usize) {
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.genus(),
        loops(m),
    )
}

/// The closed form of the module documentation: one iteration maps
/// (V, E, F, L) with n = E − L to (V + n, E + 4n, 2n + V + L, L + n).
fn predicted(m: &Mesh) -> (usize, usize, usize, usize) {
    let (v, e, l) = (m.vertex_count(), m.edge_count(), loops(m));
    let n = e - l;
    (v + n, e + 4 * n, 2 * n + v + l, l + n)
}

/// Iterates the primitive `spec` once per entry of `expected`, checking
/// after each iteration that the mesh is valid, in one piece, has those
/// [`counts`] and that the iteration's report says the same V, E, F.
fn iterate_expecting(spec: &str, expected: &[(usize, usize, usize, i64, usize)]) {
    let mut m = prim(spec);
    for &want in expected {
        let report = sierpinski(&mut m, 1).unwrap();
        m.validate().unwrap();
        assert_eq!(counts(&m), want);
        let step = report.steps[0];
        assert_eq!(
            (step.vertices, step.edges, step.faces),
            (want.0, want.1, want.2)
        );
        assert_eq!(m.topology().component_count(), 1);
    }
}

#[test]
fn tetrahedron_and_cube_match_the_thesis_and_the_closed_form() {
    for (spec, expected) in [
        // The thesis's counts.
        (
            "@tetrahedron",
            [
                (10, 30, 16, 3, 6),
                (34, 126, 64, 15, 30),
                (130, 510, 256, 63, 126),
            ],
        ),
        // Derived by hand from the closed form (module docs), starting
        // from (V, E, F, L) = (8, 12, 6, 0): n = 12, 48, 192.
        (
            "@cube",
            [
                (20, 60, 32, 5, 12),
                (68, 252, 128, 29, 60),
                (260, 1020, 512, 125, 252),
            ],
        ),
    ] {
        iterate_expecting(spec, &expected);
    }
}

#[test]
fn three_iterations_at_once_equal_three_single_ones() {
    let mut once = prim("@tetrahedron");
    let report = sierpinski(&mut once, 3).unwrap();
    once.validate().unwrap();
    assert_eq!(counts(&once), (130, 510, 256, 63, 126));
    assert_eq!(report.steps.len(), 3);
    let subdivided: Vec<usize> = report.steps.iter().map(|s| s.subdivided).collect();
    assert_eq!(subdivided, [6, 24, 96]);
    let cuts: Vec<usize> = report.steps.iter().map(|s| s.corner_cuts).collect();
    assert_eq!(cuts, [12, 48, 192]);
}

#[test]
fn genus_grows_by_a_factor_approaching_four() {
    // §VI.4: after the first iteration the genus grows by a factor of four
    // with every iteration. Exactly, genus' = genus + n/2 with n = 4^k·n0,
    // so the ratio falls towards 4 from above.
    let mut m = prim("@cube");
    sierpinski(&mut m, 1).unwrap();
    let mut genus = m.genus();
    let mut last_ratio = f64::INFINITY;
    for _ in 0..4 {
        sierpinski(&mut m, 1).unwrap();
        let ratio = m.genus() as f64 / genus as f64;
        assert!(ratio > 4.0 && ratio < last_ratio, "ratio {ratio}");
        last_ratio = ratio;
        genus = m.genus();
    }
    assert!(last_ratio < 4.02, "ratio {last_ratio}");
}

#[test]
fn every_step_leaves_a_valid_mesh() {
    let mut m = prim("@cube");
    for _ in 0..3 {
        let (corners, mids) = subdivide_step(&mut m).unwrap();
        m.validate().unwrap();
        let (central, _) = cut_step(&mut m, corners, &mids).unwrap();
        m.validate().unwrap();
        // Step 2 leaves every midpoint with exactly two central corners.
        assert!(central.iter().all(|p| p[0].is_some() && p[1].is_some()));
        loop_step(&mut m, &central).unwrap();
        m.validate().unwrap();
    }
    assert_eq!(counts(&m), (260, 1020, 512, 125, 252));
}

#[test]
fn closed_form_holds_on_other_solids_and_a_torus() {
    for spec in [
        "@octahedron",
        "@dodecahedron",
        "@icosahedron",
        "@torus:6:4",
        "@cube:2",
    ] {
        let mut m = prim(spec);
        let g0 = m.genus();
        let f0 = m.face_count() as i64;
        for k in 0..3 {
            let (v, e, f, l) = predicted(&m);
            sierpinski(&mut m, 1).unwrap();
            m.validate().unwrap();
            assert_eq!(
                (m.vertex_count(), m.edge_count(), m.face_count(), loops(&m)),
                (v, e, f, l),
                "{spec}, iteration {}",
                k + 1
            );
            assert_eq!(m.topology().component_count(), 1, "{spec}");
            if k == 0 {
                // genus' = 2g + F − 1 for a loop-free genus-g input.
                assert_eq!(m.genus(), 2 * g0 + f0 - 1, "{spec}");
            }
        }
    }
}

#[test]
fn components_stay_separate_and_connected() {
    // Two disjoint tetrahedra in one mesh.
    let poly = holey_shapes::parse_primitive("@tetrahedron").unwrap();
    let raw = to_dlfl(&poly, ImportOptions::default())
        .unwrap()
        .mesh
        .to_raw();
    let mut two = raw.clone();
    let nv = raw.positions.len() as u32;
    let nc = raw.face_vertices.len() as u32;
    two.positions.extend(
        raw.positions
            .iter()
            .map(|p| *p + DVec3::new(10.0, 0.0, 0.0)),
    );
    let last = *raw.face_offsets.last().unwrap();
    two.face_offsets
        .extend(raw.face_offsets[1..].iter().map(|o| o + last));
    two.face_vertices
        .extend(raw.face_vertices.iter().map(|v| v + nv));
    two.edges
        .extend(raw.edges.iter().map(|[a, b]| [a + nc, b + nc]));
    let mut m = Mesh::from_raw(&RawMesh { ..two }).unwrap();
    assert_eq!(m.topology().component_count(), 2);
    sierpinski(&mut m, 2).unwrap();
    m.validate().unwrap();
    let topo = m.topology();
    assert_eq!(topo.component_count(), 2);
    for c in &topo.components {
        assert_eq!((c.vertices, c.edges, c.faces, c.genus()), (34, 126, 64, 15));
    }
}

/// The visible polygon of a face: its positions with the zero-length
/// self-loop steps dropped.
fn visible(m: &Mesh, f: holey_dlfl::FaceId) -> Vec<DVec3> {
    let mut pts: Vec<DVec3> = Vec::new();
    for c in m.face_corners(f).unwrap() {
        let e = m.corner_edge(c).unwrap().unwrap();
        if !m.is_self_loop(e).unwrap() {
            pts.push(m.position(m.corner_vertex(c).unwrap()).unwrap());
        }
    }
    pts
}

#[test]
fn tetrahedron_faces_are_equilateral_triangles_of_halving_size() {
    // Every face, corner piece or back face, looks like a triangle (its
    // self-loops ignored, §VI.6) whose side halves at every iteration.
    let mut m = prim("@tetrahedron");
    let side0 = 8f64.sqrt();
    for k in 1..=4 {
        sierpinski(&mut m, 1).unwrap();
        let side = side0 / f64::from(1u32 << k);
        for f in m.faces().collect::<Vec<_>>() {
            let pts = visible(&m, f);
            assert_eq!(pts.len(), 3, "iteration {k}");
            for i in 0..3 {
                let d = pts[i].distance(pts[(i + 1) % 3]);
                assert!(
                    (d - side).abs() < 1e-12 * side0,
                    "iteration {k}: {d} vs {side}"
                );
            }
        }
        // Each vertex's loops separate its corners into 1 + loops fans; the
        // hexagon of figure 37 has one loop at each of its three corners.
        if k >= 2 {
            let hexagons = m.faces().filter(|&f| m.face_len(f).unwrap() == 6).count();
            assert!(hexagons > 0);
        }
    }
}

#[test]
fn zero_iterations_change_nothing() {
    let mut m = prim("@cube");
    let before = m.to_raw();
    let report = sierpinski(&mut m, 0).unwrap();
    assert!(report.steps.is_empty());
    assert_eq!(m.to_raw(), before);
}

#[test]
fn open_surfaces_are_refused_unchanged() {
    let mut m = prim("@plane");
    let before = m.to_raw();
    let err = sierpinski(&mut m, 1).unwrap_err();
    assert!(
        matches!(err, SierpinskiError::OpenSurface { holes: 1 }),
        "{err}"
    );
    assert_eq!(m.to_raw(), before);
}

#[test]
fn the_face_cap_is_checked_before_anything_changes() {
    let mut m = prim("@tetrahedron");
    let before = m.to_raw();
    // Bound after one iteration: 4 + (12 sides + 6 edges) = 22 ≥ 16 real.
    let err = sierpinski_capped(&mut m, 1, 21).unwrap_err();
    assert!(
        matches!(
            err,
            SierpinskiError::TooManyFaces {
                bound: 22,
                cap: 21,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(m.to_raw(), before);
    sierpinski_capped(&mut m, 1, 22).unwrap();
    assert_eq!(m.face_count(), 16);
    // A huge iteration count is refused without looping forever.
    let err = sierpinski(&mut m, usize::MAX).unwrap_err();
    assert!(matches!(err, SierpinskiError::TooManyFaces { .. }), "{err}");
}

#[test]
fn point_spheres_are_left_alone() {
    let mut m = prim("@tetrahedron");
    m.create_vertex(DVec3::splat(5.0)).unwrap();
    sierpinski(&mut m, 1).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (11, 30, 17, 3, 6));
    assert_eq!(m.topology().component_count(), 2);
}

#[test]
fn sierpinski_applies_to_a_menger_sponge() {
    // Figure 66 combines the two tools. A level-1 sponge has no loops:
    // genus' = 2g + F − 1 = 10 + 72 − 1.
    let mut m = prim("@cube");
    crate::menger::menger(&mut m, &crate::menger::MengerParams::default()).unwrap();
    let (v, e, f, l) = predicted(&m);
    sierpinski(&mut m, 1).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count(), loops(&m)),
        (v, e, f, l)
    );
    assert_eq!(m.genus(), 81);
}
