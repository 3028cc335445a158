//! Unit tests of the Menger sponge algorithm: counts against the closed
//! forms of the module documentation, analytic volumes, `validate()` after
//! every call, the special cases of §VII.4–VII.5, and every refusal.

use std::f64::consts::PI;

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::dlfl_info;
use holey_dlfl::{DVec3, Mesh};
use holey_mesh::PolyMesh;

use super::plan::{Decision, angle_tol, classify, interior_angle};
use super::*;
use crate::handle::geometry::vector_area;
use crate::test_util::{counts, prim};

fn import(positions: Vec<DVec3>, faces: Vec<Vec<u32>>) -> Mesh {
    let poly = PolyMesh::from_faces(positions, faces);
    to_dlfl(&poly, ImportOptions::default()).unwrap().mesh
}

fn ratio(r: f64) -> MengerParams {
    MengerParams {
        thickness: Thickness::RatioOfMeanEdge(r),
        ..MengerParams::default()
    }
}

fn absolute(d: f64) -> MengerParams {
    MengerParams {
        thickness: Thickness::Absolute(d),
        ..MengerParams::default()
    }
}

/// The default parameters, `n` levels deep.
fn levels(n: usize) -> MengerParams {
    MengerParams {
        iterations: n,
        ..MengerParams::default()
    }
}

/// `@cube` with its corner 0 pushed by `by` along (1, 1, 1), off the
/// planes of its three faces (§VII.5.1's skewed faces).
fn cube_with_a_corner_pushed(by: f64) -> Mesh {
    let poly = holey_shapes::parse_primitive("@cube").unwrap();
    let mut positions = poly.positions.clone();
    positions[0] += DVec3::splat(by);
    let faces: Vec<Vec<u32>> = poly.faces().map(|f| f.to_vec()).collect();
    import(positions, faces)
}

/// The smallest face area (the length of the face's vector area).
fn min_face_area(m: &Mesh) -> f64 {
    m.faces()
        .map(|f| vector_area(&m.face_positions(f).unwrap()).length())
        .fold(f64::INFINITY, f64::min)
}

fn volume(m: &Mesh) -> f64 {
    dlfl_info(m).volume.unwrap()
}

/// A prism over a counter-clockwise outline in the xy plane.
fn prism(outline: &[(f64, f64)], height: f64) -> Mesh {
    let n = outline.len() as u32;
    let mut pos = Vec::new();
    for z in [0.0, height] {
        for &(x, y) in outline {
            pos.push(DVec3::new(x, y, z));
        }
    }
    let mut faces: Vec<Vec<u32>> = vec![(0..n).rev().collect(), (n..2 * n).collect()];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    import(pos, faces)
}

/// Runs [`menger`] on `m` and checks the result against the mesh it
/// started from ([`check_result`]), as most of these tests do first.
fn menger_checked(m: &mut Mesh, params: &MengerParams) -> MengerReport {
    let before = m.clone();
    let report = menger(m, params).unwrap();
    check_result(&before, m);
    report
}

/// Checks shared by every successful run: valid, closed, one component
/// per input component, genus 2g + F − 1, no face without area.
fn check_result(before: &Mesh, after: &Mesh) {
    after.validate().unwrap();
    assert_eq!(after.hole_count(), 0);
    let g = before.genus();
    let f = before.face_count() as i64;
    assert_eq!(after.topology().component_count(), 1);
    assert_eq!(after.genus(), 2 * g + f - 1);
    let size = dlfl_info(after)
        .bbox
        .map(|[lo, hi]| (DVec3::from_array(hi) - DVec3::from_array(lo)).length());
    assert!(min_face_area(after) > 1e-6 * size.unwrap().powi(2));
}

#[test]
fn cube_level_one_is_the_level_one_sponge() {
    let mut m = prim("@cube");
    let report = menger_checked(&mut m, &MengerParams::default());
    assert_eq!(counts(&m), (64, 144, 72));
    assert_eq!(m.genus(), 5);
    let level = &report.levels[0];
    assert_eq!(level.thickness, 2.0 / 3.0);
    // Every cube edge is case 2 (φ = 90°): all strips collapse.
    assert_eq!(level.angle_cases, [0, 12, 0, 0, 0, 0]);
    assert_eq!(level.collapsed_edges, 12);
    assert_eq!((level.vertices, level.edges, level.faces), (64, 144, 72));
    // The solid is 20 of 27 sub-cubes.
    assert!((volume(&m) - 8.0 * 20.0 / 27.0).abs() < 1e-12);
    // It is the true level-1 sponge: the same points as exact mode.
    let mut exact = prim("@cube");
    menger(
        &mut exact,
        &MengerParams {
            exact: true,
            ..MengerParams::default()
        },
    )
    .unwrap();
    let key = |p: DVec3| (p * 3.0).round().as_ivec3().to_array();
    let mut a: Vec<_> = m.vertices().map(|v| key(m.position(v).unwrap())).collect();
    let mut b: Vec<_> = exact
        .vertices()
        .map(|v| key(exact.position(v).unwrap()))
        .collect();
    a.sort_unstable();
    b.sort_unstable();
    assert_eq!(a, b);
    for v in m.vertices() {
        let p = (m.position(v).unwrap() + DVec3::ONE) * 1.5;
        assert!((p - p.round()).abs().max_element() < 1e-12);
    }
}

#[test]
fn cube_volume_follows_the_thickness() {
    // Cube [-1,1]³, thickness D: the tunnels have side s = 2 − 2D and depth
    // D, and meet in a central cube of side s, so the volume is
    // 8 − 6·s²·D − s³.
    for d in [0.2, 0.5, 2.0 / 3.0, 0.9] {
        let mut m = prim("@cube");
        menger_checked(&mut m, &absolute(d));
        assert_eq!(counts(&m), (64, 144, 72));
        let s = 2.0 - 2.0 * d;
        let expected = 8.0 - 6.0 * s * s * d - s * s * s;
        assert!((volume(&m) - expected).abs() < 1e-12, "D = {d}");
    }
}

#[test]
fn cube_level_two_has_genus_81_and_the_true_sponges_solid() {
    let mut m = prim("@cube");
    let params = levels(2);
    let report = menger(&mut m, &params).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 81);
    assert_eq!(m.hole_count(), 0);
    // Level 2 sees 72 right angles, 48 flat edges and 24 re-entrant edges
    // (the tunnels' corners, φ = 270°: case 6, bent).
    let level = &report.levels[1];
    assert!((level.thickness - 2.0 / 9.0).abs() < 1e-15);
    assert_eq!(level.angle_cases, [0, 72, 0, 48, 0, 24]);
    assert_eq!(level.bent_edges, 24);
    assert_eq!(counts(&m), (800, 1920, 960));
    // All quadrilaterals of positive area, whose corners lie on the 9-grid.
    assert!(m.faces().all(|f| m.face_len(f).unwrap() == 4));
    assert!(min_face_area(&m) > 0.049);
    for v in m.vertices() {
        let p = (m.position(v).unwrap() + DVec3::ONE) * 4.5;
        assert!((p - p.round()).abs().max_element() < 1e-9);
    }
    // With the figure-61 bends the thesis's level 2 encloses exactly the
    // true level-2 sponge (same volume and area), with coarser faces.
    let mut exact = prim("@cube");
    menger(
        &mut exact,
        &MengerParams {
            iterations: 2,
            exact: true,
            ..MengerParams::default()
        },
    )
    .unwrap();
    assert!((volume(&m) - 8.0 * (20.0f64 / 27.0).powi(2)).abs() < 1e-12);
    assert!((dlfl_info(&m).area - dlfl_info(&exact).area).abs() < 1e-9);
}

#[test]
fn cube_level_three_follows_the_genus_formula() {
    // genus' = 2g + F − 1 = 2·81 + 960 − 1. (The true level 3 has genus
    // 1409: from level 3 on the thesis's sponge is a different surface.)
    let mut m = prim("@cube");
    let params = levels(3);
    menger(&mut m, &params).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1121);
    assert!(min_face_area(&m) > 0.0);
}

#[test]
fn subdivided_cube_keeps_flat_strips() {
    // @cube:2 has 24 flat edges (case 4): their strips stay, 2D wide.
    let mut m = prim("@cube:2");
    let report = menger_checked(&mut m, &ratio(1.0 / 3.0));
    assert_eq!(report.levels[0].angle_cases, [0, 24, 0, 24, 0, 0]);
    assert_eq!(m.genus(), 23);
}

#[test]
fn dodecahedron_keeps_or_collapses_case_three_as_asked() {
    // φ = 116.57° at every edge: case 3, decided by the threshold.
    for (angle, collapsed) in [(90.0, 0), (116.0, 0), (117.0, 30), (180.0, 30)] {
        let mut m = prim("@dodecahedron");
        let params = MengerParams {
            collapse_angle_deg: angle,
            ..MengerParams::default()
        };
        let report = menger_checked(&mut m, &params);
        assert_eq!(report.levels[0].angle_cases, [0, 0, 30, 0, 0, 0]);
        assert_eq!(report.levels[0].collapsed_edges, collapsed);
        assert_eq!(m.genus(), 11);
        if collapsed == 0 {
            // No collapse: V + 6E, 15E, 7E + V.
            assert_eq!(counts(&m), (200, 450, 230));
        }
    }
}

#[test]
fn tetrahedron_collapses_case_one() {
    // φ = 70.53°: case 1. Each of the 4 vertex faces and 6 strips vanish:
    // V = 4 + 12 + 12 + 4, E = 90 − 12 − 6, F = 36.
    let mut m = prim("@tetrahedron");
    let report = menger_checked(&mut m, &ratio(0.25));
    assert_eq!(report.levels[0].angle_cases, [6, 0, 0, 0, 0, 0]);
    assert_eq!(counts(&m), (32, 72, 36));
    assert_eq!(m.genus(), 3);
}

#[test]
fn non_convex_faces_and_a_reentrant_edge() {
    // An L-shaped prism: two non-convex corners (§VII.5.2) and one edge
    // with φ = 270° (case 6), which is bent.
    let outline = [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ];
    let mut m = prism(&outline, 1.0);
    let report = menger_checked(&mut m, &absolute(0.25));
    let level = &report.levels[0];
    assert_eq!(level.nonconvex_corners, 2);
    assert_eq!(level.angle_cases, [0, 17, 0, 0, 0, 1]);
    assert_eq!(level.bent_edges, 1);
    assert_eq!(m.genus(), 7);
    // The bent strip's new vertices sit D behind both faces at the
    // re-entrant edge x = y = 1: at (1 − D, 1 − D, z).
    let d = 0.25;
    let bends: Vec<DVec3> = m
        .vertices()
        .map(|v| m.position(v).unwrap())
        .filter(|p| (p.x - (1.0 - d)).abs() < 1e-12 && (p.y - (1.0 - d)).abs() < 1e-12)
        .collect();
    assert!(!bends.is_empty());
}

#[test]
fn an_edge_between_180_and_270_degrees_is_bent() {
    // A chevron prism: one reflex corner of 233° makes a case-5 edge, and
    // its two acute neighbours case-1 edges.
    let mut m = prism(
        &[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 1.5), (0.0, 2.0)],
        1.0,
    );
    let report = menger_checked(&mut m, &ratio(0.15));
    assert_eq!(report.levels[0].angle_cases, [2, 12, 0, 0, 1, 0]);
    assert_eq!(report.levels[0].bent_edges, 1);
    assert_eq!(m.genus(), 6);
}

#[test]
fn winged_corners_move_into_the_face() {
    // A cube whose top front edge carries an extra vertex: the two faces
    // beside it get a 180° (winged) corner each (§VII.5.3).
    let poly = holey_shapes::parse_primitive("@cube").unwrap();
    let mut positions = poly.positions.clone();
    let mut faces: Vec<Vec<u32>> = poly.faces().map(|f| f.to_vec()).collect();
    let (a, b) = (faces[0][0], faces[0][1]);
    let mid = positions.len() as u32;
    positions.push((positions[a as usize] + positions[b as usize]) * 0.5);
    for f in &mut faces {
        let n = f.len();
        for i in 0..n {
            let (x, y) = (f[i], f[(i + 1) % n]);
            if (x, y) == (a, b) || (x, y) == (b, a) {
                f.insert(i + 1, mid);
                break;
            }
        }
    }
    let (positions_a, positions_b) = (positions[a as usize], positions[b as usize]);
    let mut m = import(positions, faces);
    let d = 0.3;
    let report = menger_checked(&mut m, &absolute(d));
    assert_eq!(report.levels[0].winged_corners, 2);
    assert_eq!(m.genus(), 5);
    // Each winged corner's remeshing point sits D from the midpoint,
    // perpendicular to the edge, inside its face.
    let pm = (positions_a + positions_b) * 0.5;
    let near: Vec<DVec3> = m
        .vertices()
        .map(|v| m.position(v).unwrap())
        .filter(|p| {
            ((*p - pm).length() - d).abs() < 1e-12
                && (*p - pm).dot(positions_b - positions_a).abs() < 1e-12
        })
        .collect();
    assert_eq!(near.len(), 2, "{near:?}");
}

#[test]
fn a_torus_follows_the_genus_formula() {
    let mut m = prim("@torus:8:6");
    let report = menger_checked(&mut m, &ratio(0.15));
    // The inner side of the torus is saddle-shaped: flat and re-entrant
    // edges (bent) besides the convex ones.
    assert_eq!(report.levels[0].angle_cases, [0, 0, 64, 16, 16, 0]);
    assert_eq!(m.genus(), 2 + 48 - 1);
}

#[test]
fn slightly_skewed_faces_are_counted_and_handled() {
    // §VII.5.1: a cube with one corner pushed a little off its three faces'
    // planes.
    let mut m = cube_with_a_corner_pushed(0.01);
    let report = menger_checked(&mut m, &MengerParams::default());
    assert_eq!(report.levels[0].nonplanar_faces, 3);
    assert_eq!(report.levels[0].skew_cuts, 0);
}

#[test]
fn strongly_skewed_faces_are_cut_into_planar_pieces() {
    // The same corner pushed far: its three quads are cut into triangles
    // first (the thesis's remedy), so the level sees 9 faces: genus 8.
    let mut m = cube_with_a_corner_pushed(0.3);
    let report = menger(&mut m, &absolute(0.25)).unwrap();
    m.validate().unwrap();
    assert_eq!(report.levels[0].skew_cuts, 3);
    assert_eq!(report.levels[0].nonplanar_faces, 0);
    assert_eq!(m.genus(), 8);
    assert!(min_face_area(&m) > 0.0);
}

#[test]
fn folded_hexagons_of_level_three_are_cut_in_two() {
    // After three levels on a cube, 48 offset faces are hexagons folded
    // over a box's inside corner (three re-entrant edges meet there).
    let mut m = prim("@cube");
    let params = levels(3);
    menger(&mut m, &params).unwrap();
    let hexagons = m.faces().filter(|&f| m.face_len(f).unwrap() == 6).count();
    assert_eq!(hexagons, 48);
    let (v, e, f, g) = (m.vertex_count(), m.edge_count(), m.face_count(), m.genus());
    let cuts = super::skew::split_skewed_faces(&mut m).unwrap();
    m.validate().unwrap();
    assert_eq!(cuts, 48);
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count(), m.genus()),
        (v, e + 48, f + 48, g)
    );
    // Every face is now planar, and the hexagons became quadrilaterals.
    assert!(m.faces().all(|f| m.face_len(f).unwrap() == 4));
    for f in m.faces() {
        let p = m.face_positions(f).unwrap();
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        assert!(p.iter().all(|q| (*q - p[0]).dot(n).abs() < 1e-12));
    }
}

#[test]
fn angle_tests_are_scale_relative() {
    // The same cube far from the origin, and tiny: still every edge is
    // exactly case 2 and collapses, which an absolute epsilon would miss
    // (far) or overreach (tiny).
    for (offset, scale) in [(1e6, 1.0), (0.0, 1e-7), (-3e4, 250.0)] {
        let poly = holey_shapes::parse_primitive("@cube").unwrap();
        let positions = poly
            .positions
            .iter()
            .map(|p| *p * scale + DVec3::splat(offset) + DVec3::new(0.0, 1.0 / 3.0, 0.1))
            .collect();
        let faces: Vec<Vec<u32>> = poly.faces().map(|f| f.to_vec()).collect();
        let mut m = import(positions, faces);
        let report = menger(&mut m, &MengerParams::default()).unwrap();
        m.validate().unwrap();
        assert_eq!(report.levels[0].angle_cases, [0, 12, 0, 0, 0, 0]);
        assert_eq!(counts(&m), (64, 144, 72));
        assert_eq!(m.genus(), 5);
    }
}

#[test]
fn interior_angles_and_cases() {
    let t = DVec3::Y;
    let deg = |phi: f64| phi * 180.0 / PI;
    // Cube edge: top (+z) and side (+x) faces, edge along +y.
    assert!((deg(interior_angle(t, DVec3::Z, DVec3::X)) - 90.0).abs() < 1e-12);
    assert!((deg(interior_angle(t, DVec3::Z, DVec3::Z)) - 180.0).abs() < 1e-12);
    assert!((deg(interior_angle(t, DVec3::Z, -DVec3::X)) - 270.0).abs() < 1e-12);
    let tol = angle_tol(1.0, 1.0);
    let below = (120f64).to_radians();
    let c = |d: f64| classify(d.to_radians(), tol, below);
    assert_eq!(c(45.0), (1, Decision::Collapse));
    assert_eq!(c(90.0), (2, Decision::Collapse));
    assert_eq!(classify(PI / 2.0 + 0.5 * tol, tol, below).0, 2);
    assert_eq!(classify(PI / 2.0 + 2.0 * tol, tol, below).0, 3);
    assert_eq!(c(100.0), (3, Decision::Collapse));
    assert_eq!(c(130.0), (3, Decision::Keep));
    assert_eq!(c(180.0), (4, Decision::Keep));
    assert_eq!(c(200.0), (5, Decision::Bend));
    assert_eq!(c(270.0), (6, Decision::Bend));
    assert_eq!(c(300.0), (6, Decision::Bend));
    // The tolerance grows with the coordinates' magnitude over the length.
    assert!(angle_tol(1e6, 1.0) > 1e5 * angle_tol(1.0, 1.0));
    assert_eq!(angle_tol(5.0, 2.0), angle_tol(50.0, 20.0));
}

#[test]
fn zero_iterations_change_nothing() {
    let mut m = prim("@cube");
    let before = m.to_raw();
    let params = levels(0);
    let report = menger(&mut m, &params).unwrap();
    assert!(report.levels.is_empty() && report.exact.is_none());
    assert_eq!(m.to_raw(), before);
}

/// Runs `params` and expects an error that leaves the mesh unchanged.
fn refused(mut m: Mesh, params: &MengerParams) -> MengerError {
    let before = m.to_raw();
    let err = menger(&mut m, params).unwrap_err();
    assert_eq!(m.to_raw(), before, "{err}");
    // Every message reads as a sentence.
    assert!(!err.to_string().is_empty());
    err
}

#[test]
fn bad_thickness_is_refused() {
    for v in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for t in [Thickness::Absolute(v), Thickness::RatioOfMeanEdge(v)] {
            let params = MengerParams {
                thickness: t,
                ..MengerParams::default()
            };
            let err = refused(prim("@cube"), &params);
            assert!(matches!(err, MengerError::InvalidThickness { .. }), "{err}");
        }
    }
}

#[test]
fn bad_collapse_angle_is_refused() {
    for angle in [f64::NAN, 45.0, 89.9, 180.5, f64::INFINITY] {
        let params = MengerParams {
            collapse_angle_deg: angle,
            ..MengerParams::default()
        };
        let err = refused(prim("@cube"), &params);
        assert!(
            matches!(err, MengerError::InvalidCollapseAngle { .. }),
            "{err}"
        );
    }
}

#[test]
fn too_thick_is_refused_naming_the_face() {
    // The cube's edges are 2 long: D = 1 leaves no middle segment.
    let m = prim("@cube");
    let first = m.faces().next().unwrap();
    let err = refused(m, &absolute(1.0));
    match err {
        MengerError::ThicknessTooLarge { face, level, .. } => {
            assert_eq!((face, level), (first, 1));
        }
        other => panic!("{other}"),
    }
    assert!(
        refused(prim("@cube"), &absolute(1.0))
            .to_string()
            .contains("f0")
    );
    // A tetrahedron at R = 1/3: the remeshing triangles (edge L − 3D)
    // vanish. At R = 0.32 they survive, but the offset faces would pass
    // the centre and come out inside out.
    for r in [1.0 / 3.0, 0.32] {
        let err = refused(prim("@tetrahedron"), &ratio(r));
        assert!(
            matches!(err, MengerError::ThicknessTooLarge { .. }),
            "{err}"
        );
    }
    // A thickness that fits level 1 but not level 2: nothing changes.
    let params = MengerParams {
        iterations: 2,
        thickness: Thickness::Absolute(2.0 / 3.0),
        ..MengerParams::default()
    };
    let err = refused(prim("@cube"), &params);
    assert!(
        matches!(err, MengerError::ThicknessTooLarge { level: 2, .. }),
        "{err}"
    );
}

#[test]
fn unsupported_inputs_are_refused() {
    let err = refused(prim("@plane"), &MengerParams::default());
    assert!(
        matches!(err, MengerError::OpenSurface { holes: 1 }),
        "{err}"
    );
    // A Sierpinski polyhedron has self-loops.
    let mut s = prim("@tetrahedron");
    crate::sierpinski::sierpinski(&mut s, 1).unwrap();
    let err = refused(s, &ratio(0.1));
    assert!(matches!(err, MengerError::SelfLoop { .. }), "{err}");
    // A point-sphere.
    let mut p = prim("@cube");
    p.create_vertex(DVec3::splat(4.0)).unwrap();
    let err = refused(p, &MengerParams::default());
    assert!(
        matches!(err, MengerError::ShortFace { len: 1, .. }),
        "{err}"
    );
    // A two-gon: an edge doubled inside a face of the cube.
    let mut two_gon = prim("@cube");
    let c = two_gon.corners().next().unwrap();
    let next = two_gon.corner_next(c).unwrap();
    two_gon.insert_edge(c, next).unwrap();
    two_gon.validate().unwrap();
    let err = refused(two_gon, &MengerParams::default());
    assert!(
        matches!(err, MengerError::ShortFace { len: 2, .. }),
        "{err}"
    );
    let err = refused(Mesh::new(), &MengerParams::default());
    assert!(matches!(err, MengerError::Empty), "{err}");
}

#[test]
fn the_face_cap_is_checked_before_each_level() {
    // Level 1 of a cube may make up to 8·12 + 8 = 104 faces.
    let err = {
        let mut m = prim("@cube");
        let before = m.to_raw();
        let err = menger_capped(&mut m, &MengerParams::default(), 103).unwrap_err();
        assert_eq!(m.to_raw(), before);
        err
    };
    assert!(
        matches!(
            err,
            MengerError::TooManyFaces {
                level: 1,
                bound: 104,
                cap: 103
            }
        ),
        "{err}"
    );
    let mut m = prim("@cube");
    menger_capped(&mut m, &MengerParams::default(), 104).unwrap();
    // Level 2 is refused after level 1 ran on the copy: unchanged.
    let mut m = prim("@cube");
    let before = m.to_raw();
    let params = levels(2);
    let err = menger_capped(&mut m, &params, 1000).unwrap_err();
    assert!(
        matches!(err, MengerError::TooManyFaces { level: 2, .. }),
        "{err}"
    );
    assert_eq!(m.to_raw(), before);
    // Exact mode knows its count in advance.
    let exact = MengerParams {
        iterations: 3,
        exact: true,
        ..MengerParams::default()
    };
    let err = menger_capped(&mut m, &exact, 18_047).unwrap_err();
    assert!(
        matches!(err, MengerError::TooManyFaces { bound: 18_048, .. }),
        "{err}"
    );
    let err = menger(
        &mut m,
        &MengerParams {
            iterations: usize::MAX,
            exact: true,
            ..MengerParams::default()
        },
    )
    .unwrap_err();
    assert!(matches!(err, MengerError::TooManyFaces { .. }), "{err}");
}

// ---- exact mode ----

fn exact(iterations: usize) -> MengerParams {
    MengerParams {
        iterations,
        exact: true,
        ..MengerParams::default()
    }
}

/// Independent count of the level-n sponge's surface by brute force over
/// its cells: V, E, F of the quadrilateral cell faces between a kept and a
/// removed (or outside) cell.
fn brute_force_counts(level: u32) -> (usize, usize, usize) {
    use std::collections::HashSet;
    let n = 3i64.pow(level);
    let kept = |c: [i64; 3]| -> bool {
        if c.iter().any(|&x| x < 0 || x >= n) {
            return false;
        }
        let mut c = c;
        for _ in 0..level {
            if c.iter().filter(|&&x| x % 3 == 1).count() >= 2 {
                return false;
            }
            for x in &mut c {
                *x /= 3;
            }
        }
        true
    };
    let (mut verts, mut edges, mut faces) = (HashSet::new(), HashSet::new(), 0);
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                if !kept([x, y, z]) {
                    continue;
                }
                for axis in 0..3 {
                    for side in [0, 1] {
                        let mut nb = [x, y, z];
                        nb[axis] += 2 * side - 1;
                        if kept(nb) {
                            continue;
                        }
                        faces += 1;
                        let mut base = [x, y, z];
                        base[axis] += side;
                        let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
                        let corner = |du: i64, dw: i64| {
                            let mut p = base;
                            p[u] += du;
                            p[w] += dw;
                            p
                        };
                        let quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                        for k in 0..4 {
                            verts.insert(quad[k]);
                            let (a, b) = (quad[k], quad[(k + 1) % 4]);
                            edges.insert(if a < b { (a, b) } else { (b, a) });
                        }
                    }
                }
            }
        }
    }
    (verts.len(), edges.len(), faces)
}

#[test]
fn exact_counts_match_a_brute_force_count() {
    for level in 1..=3 {
        let (v, e, f, genus) = exact_counts(level).unwrap();
        assert_eq!(
            brute_force_counts(level as u32),
            (v as usize, e as usize, f as usize)
        );
        assert_eq!(v as i64 - e as i64 + f as i64, 2 - 2 * genus as i64);
    }
    assert_eq!(exact_counts(1).unwrap().3, 5);
    assert_eq!(exact_counts(2).unwrap().3, 81);
    assert_eq!(exact_counts(3).unwrap().3, 1409);
    assert_eq!(exact_counts(0), Some((8, 12, 6, 0)));
}

#[test]
fn exact_levels_are_true_sponges() {
    for level in 1..=3usize {
        let mut m = prim("@cube");
        let report = menger(&mut m, &exact(level)).unwrap();
        m.validate().unwrap();
        let (v, e, f, genus) = exact_counts(level).unwrap();
        assert_eq!(counts(&m), (v as usize, e as usize, f as usize));
        assert_eq!(m.genus(), genus as i64);
        assert_eq!(m.hole_count(), 0);
        assert_eq!(m.topology().component_count(), 1);
        let sponge = report.exact.unwrap();
        assert_eq!(
            (sponge.level, sponge.vertices, sponge.edges, sponge.faces),
            (level, v as usize, e as usize, f as usize)
        );
        let expected = 8.0 * (20.0f64 / 27.0).powi(level as i32);
        assert!((volume(&m) - expected).abs() < 1e-9, "level {level}");
        // Surface area 2(20/9)^n + 4(8/9)^n times a side's area (4).
        let area = 4.0
            * (2.0 * (20.0f64 / 9.0).powi(level as i32) + 4.0 * (8.0f64 / 9.0).powi(level as i32));
        assert!((dlfl_info(&m).area - area).abs() < 1e-9, "level {level}");
        let side = 2.0 / 3f64.powi(level as i32);
        assert!((min_face_area(&m) - side * side).abs() < 1e-12);
    }
}

#[test]
fn exact_mode_maps_a_parallelepiped_and_keeps_orientation() {
    // A sheared, scaled, moved cube: the sponge follows the affine map, so
    // its volume is (20/27)^n of the input's.
    let poly = holey_shapes::parse_primitive("@cube").unwrap();
    let map = |p: DVec3| {
        DVec3::new(
            2.0 * p.x + 0.5 * p.y + 10.0,
            p.y - 0.3 * p.z,
            0.7 * p.z + 0.2 * p.x - 4.0,
        )
    };
    let faces: Vec<Vec<u32>> = poly.faces().map(|f| f.to_vec()).collect();
    let positions: Vec<DVec3> = poly.positions.iter().map(|&p| map(p)).collect();
    let input = import(positions.clone(), faces.clone());
    let v0 = volume(&input);
    let mut m = input.clone();
    menger(&mut m, &exact(2)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 81);
    assert!((volume(&m) - v0 * (20.0f64 / 27.0).powi(2)).abs() < 1e-9 * v0);
    // A mirrored input (negative determinant) still comes out outward.
    let mirrored: Vec<DVec3> = positions
        .iter()
        .map(|p| DVec3::new(-p.x, p.y, p.z))
        .collect();
    let flipped_faces: Vec<Vec<u32>> = faces
        .iter()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    let mut m = import(mirrored, flipped_faces);
    assert!(volume(&m) > 0.0);
    menger(&mut m, &exact(1)).unwrap();
    assert!(volume(&m) > 0.0);
    // An inside-out cube gives an inside-out sponge.
    let mut m = prim("@cube");
    let f = m.faces().next().unwrap();
    m.reverse_component(f).unwrap();
    menger(&mut m, &exact(1)).unwrap();
    assert!((volume(&m) + 8.0 * 20.0 / 27.0).abs() < 1e-12);
}

#[test]
fn exact_mode_refuses_other_shapes() {
    for spec in ["@tetrahedron", "@cube:2", "@octahedron"] {
        let err = refused(prim(spec), &exact(1));
        assert!(
            matches!(err, MengerError::NotAParallelepiped { .. }),
            "{spec}: {err}"
        );
    }
    // Eight corners, six quads, but not a parallelepiped.
    let poly = holey_shapes::parse_primitive("@cube").unwrap();
    let mut positions = poly.positions.clone();
    positions[7] *= 1.5;
    let faces: Vec<Vec<u32>> = poly.faces().map(|f| f.to_vec()).collect();
    let err = refused(import(positions, faces), &exact(1));
    assert!(
        matches!(err, MengerError::NotAParallelepiped { .. }),
        "{err}"
    );
}

#[test]
fn random_parameters_give_a_valid_sponge_or_a_clean_refusal() {
    let mut rng = holey_testkit::Rng::new(62);
    let specs = [
        "@cube",
        "@tetrahedron",
        "@octahedron",
        "@dodecahedron",
        "@icosahedron",
        "@cube:2",
        "@torus:8:6",
        "@sphere:1",
        "@cylinder",
    ];
    let (mut ok, mut refused_count) = (0, 0);
    for _ in 0..60 {
        let spec = *rng.pick(&specs);
        let mut m = prim(spec);
        let before = m.clone();
        let params = MengerParams {
            iterations: 1 + rng.below(2),
            thickness: Thickness::RatioOfMeanEdge(rng.range(0.02, 0.5)),
            collapse_angle_deg: rng.range(90.0, 180.0),
            exact: false,
        };
        match menger(&mut m, &params) {
            Ok(report) => {
                m.validate().unwrap();
                assert_eq!(m.hole_count(), 0);
                assert_eq!(m.topology().component_count(), 1);
                assert!(min_face_area(&m) > 0.0, "{spec} {params:?}");
                let first = &report.levels[0];
                let f = before.face_count() as i64 + first.skew_cuts as i64;
                if params.iterations == 1 {
                    assert_eq!(m.genus(), 2 * before.genus() + f - 1, "{spec}");
                }
                ok += 1;
            }
            Err(err) => {
                assert_eq!(m.to_raw(), before.to_raw(), "{err}");
                assert!(
                    matches!(err, MengerError::ThicknessTooLarge { .. }),
                    "{spec} {params:?}: {err}"
                );
                refused_count += 1;
            }
        }
    }
    // Both outcomes occur over this range of thicknesses.
    assert!(
        ok > 10 && refused_count > 5,
        "{ok} ok, {refused_count} refused"
    );
}
