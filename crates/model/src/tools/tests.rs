//! Tests of the mesh tools: flatness and sphericity measured from the
//! definitions, counts worked out per tool, refusals leaving the mesh
//! unchanged.

use crate::test_util::{counts, cube_with_split_edges, prim, unchanged};
use holey_dlfl::{DVec3, Mesh};
use holey_testkit::Rng;

use super::*;

fn jiggle(m: &mut Mesh, rng: &mut Rng, amount: f64) {
    let vs: Vec<VertexId> = m.vertices().collect();
    for v in vs {
        let p = m.position(v).unwrap();
        let d = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        m.set_position(v, p + d * amount).unwrap();
    }
}

/// Largest distance of a corner from its face's least-squares plane,
/// over faces of four or more corners.
fn worst_flatness(m: &Mesh) -> f64 {
    m.faces()
        .filter(|&f| m.face_len(f).unwrap() >= 4 && !m.is_hole(f).unwrap())
        .map(|f| {
            let p = m.face_positions(f).unwrap();
            let (c, n) = polygon::best_fit_plane(&p).unwrap();
            p.iter().map(|q| (*q - c).dot(n).abs()).fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

#[test]
fn planarize_flattens_a_jiggled_grid_cube() {
    let mut rng = Rng::new(11);
    let mut m = prim("@cube:3");
    jiggle(&mut m, &mut rng, 0.05);
    let before_counts = counts(&m);
    assert!(worst_flatness(&m) > 1e-3);
    let report = planarize_faces(&mut m, &[], &PlanarizeParams::default()).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), before_counts);
    assert!(report.iterations > 0 && report.converged, "{report:?}");
    assert_eq!(report.faces, 54);
    assert!(report.before > report.after);
    // The quads' mean edge is 2/3, so the tolerance is 2/3 · 10⁻⁹.
    assert!(worst_flatness(&m) <= 1e-9, "{}", worst_flatness(&m));
}

#[test]
fn planarize_counts_no_iteration_when_flat_and_stops_at_the_cap() {
    let mut m = prim("@dodecahedron");
    let r = planarize_faces(&mut m, &[], &PlanarizeParams::default()).unwrap();
    assert_eq!(r.iterations, 0);
    assert!(r.converged && r.before < 1e-9);
    let mut rng = Rng::new(3);
    let mut m = prim("@torus:8:6");
    jiggle(&mut m, &mut rng, 0.05);
    let capped = PlanarizeParams {
        max_iterations: 3,
        tolerance: 1e-12,
    };
    let r = planarize_faces(&mut m, &[], &capped).unwrap();
    assert_eq!(r.iterations, 3);
    assert!(!r.converged && r.after < r.before);
    // Only the chosen face is considered.
    let f = m.face_at(0).unwrap();
    let r = planarize_faces(&mut m, &[f], &PlanarizeParams::default()).unwrap();
    assert_eq!(r.faces, 1);
    assert!(r.converged);
}

#[test]
fn planarize_refusals() {
    let m0 = prim("@plane:2:2");
    let hole = m0.faces().find(|&f| m0.is_hole(f).unwrap()).unwrap();
    let mut m = m0.clone();
    assert_eq!(
        planarize_faces(&mut m, &[hole], &PlanarizeParams::default()),
        Err(ToolError::HoleFace(hole))
    );
    for t in [0.0, -1.0, f64::NAN] {
        let p = PlanarizeParams {
            max_iterations: 5,
            tolerance: t,
        };
        assert!(matches!(
            planarize_faces(&mut m, &[], &p),
            Err(ToolError::InvalidParameter { .. })
        ));
    }
    unchanged(&m, &m0);
}

#[test]
fn make_spherical_projects_onto_the_fitted_sphere() {
    let mut m = prim("@cube:3");
    let fit = make_spherical(&mut m, &[]).unwrap();
    m.validate().unwrap();
    // By symmetry the centre is the cube's.
    assert!(fit.centre.length() < 1e-12);
    for v in m.vertices() {
        let d = m.position(v).unwrap().distance(fit.centre);
        assert!((d - fit.radius).abs() < 1e-12);
    }
    // A cube's corners already lie on a sphere of radius √3.
    let mut m = prim("@cube");
    let before = m.clone();
    let fit = make_spherical(&mut m, &[]).unwrap();
    assert!((fit.radius - 3f64.sqrt()).abs() < 1e-12);
    for v in m.vertices() {
        assert!(m.position(v).unwrap().distance(before.position(v).unwrap()) < 1e-12);
    }
    // Coplanar points determine no sphere.
    let mut m = prim("@plane:3:3");
    let before = m.clone();
    assert!(matches!(
        make_spherical(&mut m, &[]),
        Err(ToolError::NoSphere(_))
    ));
    unchanged(&m, &before);
}

#[test]
fn cleanup_two_gons_merges_edges() {
    // Collapsing an edge of a tetrahedron leaves two two-gons.
    let mut m = prim("@tetrahedron");
    let e = m.edges().next().unwrap();
    m.collapse_edge(e).unwrap();
    let twos = m.faces().filter(|&f| m.face_len(f).unwrap() == 2).count();
    assert_eq!(twos, 2);
    let (v, e, f) = counts(&m);
    assert_eq!(cleanup_two_gons(&mut m), 2);
    m.validate().unwrap();
    // Each: −1 edge, −1 face.
    assert_eq!(counts(&m), (v, e - 2, f - 2));
    assert_eq!(counts(&m), (3, 3, 2));
    assert_eq!(cleanup_two_gons(&mut m), 0);
}

#[test]
fn valence_two_vertices_are_removed_and_split() {
    let m0 = cube_with_split_edges(Mesh::subdivide_edge);
    assert_eq!(counts(&m0), (20, 24, 6));
    let mut m = m0.clone();
    // Each removal: −1 vertex, −1 edge.
    assert_eq!(remove_valence_two_vertices(&mut m).unwrap(), 12);
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 12, 6));
    for v in m.vertices() {
        let p = m.position(v).unwrap();
        assert!((p.abs() - DVec3::ONE).length() < 1e-12, "{p}");
    }
    // Each split: +1 vertex, +1 edge; the two halves sit 0.25 from the
    // old midpoint, i.e. at 0.75 from the ends of the edge of length 2.
    let mut m = m0.clone();
    assert_eq!(split_valence_two_vertices(&mut m, 0.25).unwrap(), 12);
    m.validate().unwrap();
    assert_eq!(counts(&m), (32, 36, 6));
    let mut twos = 0;
    for v in m.vertices() {
        if m.valence(v).unwrap() == 2 {
            twos += 1;
            let p = m.position(v).unwrap();
            let coords = p.abs().to_array();
            assert_eq!(
                coords.iter().filter(|&&c| (c - 1.0).abs() < 1e-12).count(),
                2
            );
            assert_eq!(
                coords.iter().filter(|&&c| (c - 0.25).abs() < 1e-12).count(),
                1
            );
        }
    }
    assert_eq!(twos, 24);
    // Too far, or not a distance: refused, nothing changes.
    for d in [0.5, 1.0, 0.0, -0.1, f64::NAN] {
        let mut m = m0.clone();
        assert!(split_valence_two_vertices(&mut m, d).is_err(), "{d}");
        unchanged(&m, &m0);
    }
}

#[test]
fn adjacent_valence_two_vertices_split_cleanly() {
    // Trisected edges: two valence-2 vertices next to each other.
    let mut m = cube_with_split_edges(Mesh::trisect_edge);
    assert_eq!(counts(&m), (32, 36, 6));
    let n = split_valence_two_vertices(&mut m, 0.1).unwrap();
    assert_eq!(n, 24);
    m.validate().unwrap();
    assert_eq!(counts(&m), (56, 60, 6));
    let mut m2 = m.clone();
    assert_eq!(remove_valence_two_vertices(&mut m2).unwrap(), 48);
    m2.validate().unwrap();
    assert_eq!(counts(&m2), (8, 12, 6));
}
