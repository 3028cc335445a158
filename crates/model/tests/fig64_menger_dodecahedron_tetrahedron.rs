//! Figure 64 of the thesis: the generalized Menger sponge algorithm applied
//! to non-cubic shapes, a dodecahedron and a tetrahedron; and figure 63, a
//! cube with another thickness.
#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

mod soups_and_oracles;

use holey_dlfl::Mesh;
use holey_dlfl::convert::to_poly;
use holey_mesh::analysis::analyze;
use holey_model::menger::{MengerParams, Thickness, menger};
use soups_and_oracles::prim;

fn run(spec: &str, ratio: f64) -> (Mesh, Mesh) {
    let before = prim(spec);
    let mut m = before.clone();
    let params = MengerParams {
        thickness: Thickness::RatioOfMeanEdge(ratio),
        ..MengerParams::default()
    };
    menger(&mut m, &params).unwrap();
    m.validate().unwrap();
    let info = analyze(&to_poly(&m).poly);
    assert!(info.closed && info.manifold && info.oriented, "{spec}");
    assert_eq!(info.degenerate_faces, 0, "{spec}");
    assert!(info.volume.unwrap() > 0.0);
    (before, m)
}

/// (V, E, F, genus): what each figure's counts give.
fn counts_and_genus(m: &Mesh) -> (usize, usize, usize, i64) {
    (m.vertex_count(), m.edge_count(), m.face_count(), m.genus())
}

#[test]
fn figure_64_dodecahedron() {
    // V, E, F = 20, 30, 12; every edge is case 3 (116.57°) and kept.
    // V + 6E, 15E, 7E + V; genus 2g + F − 1 = 11.
    let (_, m) = run("@dodecahedron", 1.0 / 3.0);
    assert_eq!(counts_and_genus(&m), (200, 450, 230, 11));
}

#[test]
fn figure_64_tetrahedron() {
    // Case 1 everywhere (70.53°): all strips and vertex faces collapse.
    // V = 4 + 2·6 + 2·6 + 4 (one inner vertex per corner), F = 6E, genus 3.
    let (_, m) = run("@tetrahedron", 0.25);
    assert_eq!(counts_and_genus(&m), (32, 72, 36, 3));
}

#[test]
fn figure_63_cube_with_another_thickness() {
    // D = a quarter of the edge: tunnels of side s = 1 and depth D = 0.5
    // meeting in a unit cube: volume 8 − 6·s²·D − s³ = 4.
    let (_, m) = run("@cube", 0.25);
    assert_eq!(counts_and_genus(&m), (64, 144, 72, 5));
    let info = analyze(&to_poly(&m).poly);
    assert!((info.volume.unwrap() - 4.0).abs() < 1e-12);
}

#[test]
fn other_solids_follow_the_genus_formula() {
    for (spec, ratio) in [
        ("@octahedron", 0.2),
        ("@icosahedron", 0.15),
        ("@cube:3", 0.3),
    ] {
        let (before, m) = run(spec, ratio);
        assert_eq!(m.genus(), before.face_count() as i64 - 1, "{spec}");
    }
}
