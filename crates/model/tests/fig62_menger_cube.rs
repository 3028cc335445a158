//! Figure 62 of the thesis: the generalized Menger sponge algorithm
//! (§VII.3) applied twice to a cube, the thickness a third of the edge
//! length at each level; and the true Menger sponge of exact mode, checked
//! against the shared level-3 mesh.
#![allow(clippy::unwrap_used)] // test helpers: a failure is a test failure

mod soups_and_oracles;

use holey_dlfl::convert::to_poly;
use holey_dlfl::dlfl_info;
use holey_dlfl::{DVec3, Mesh};
use holey_mesh::analysis::analyze;
use holey_model::handle::geometry::vector_area;
use holey_model::menger::{MengerParams, Thickness, exact_counts, menger};
use soups_and_oracles::prim;

fn thesis(iterations: usize) -> MengerParams {
    MengerParams {
        iterations,
        thickness: Thickness::RatioOfMeanEdge(1.0 / 3.0),
        ..MengerParams::default()
    }
}

fn exact(iterations: usize) -> MengerParams {
    MengerParams {
        iterations,
        exact: true,
        ..MengerParams::default()
    }
}

/// The smallest face area (the length of the face's vector area).
fn min_face_area(m: &Mesh) -> f64 {
    m.faces()
        .map(|f| vector_area(&m.face_positions(f).unwrap()).length())
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn figure_62_level_one() {
    let mut m = prim("@cube");
    menger(&mut m, &thesis(1)).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (64, 144, 72)
    );
    assert_eq!(m.genus(), 5);
    // Closed (no hole face; as a soup, every edge in exactly two faces),
    // manifold, oriented.
    let info = analyze(&to_poly(&m).poly);
    assert!(info.closed && info.manifold && info.oriented);
    assert_eq!(info.genus, Some(5));
    assert!(min_face_area(&m) > 0.44);
    assert!((info.volume.unwrap() - 8.0 * 20.0 / 27.0).abs() < 1e-12);
}

#[test]
fn figure_62_level_two() {
    let mut m = prim("@cube");
    let report = menger(&mut m, &thesis(2)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 81);
    assert_eq!(report.levels.len(), 2);
    assert_eq!(report.levels[1].faces, m.face_count());
    let info = analyze(&to_poly(&m).poly);
    assert!(info.closed && info.manifold && info.oriented);
    assert_eq!(info.genus, Some(81));
    assert!(min_face_area(&m) > 0.049);
}

#[test]
fn exact_mode_levels_one_to_three() {
    for level in 1..=3 {
        let mut m = prim("@cube");
        menger(&mut m, &exact(level)).unwrap();
        m.validate().unwrap();
        let (v, e, f, g) = exact_counts(level).unwrap();
        assert_eq!(
            (m.vertex_count(), m.edge_count(), m.face_count()),
            (v as usize, e as usize, f as usize)
        );
        assert_eq!(m.genus(), g as i64);
        let info = dlfl_info(&m);
        let volume = 8.0 * (20.0f64 / 27.0).powi(level as i32);
        assert!((info.volume.unwrap() - volume).abs() < 1e-9);
        assert_eq!(info.bbox, Some([[-1.0; 3], [1.0; 3]]));
    }
}

#[test]
fn exact_level_three_matches_the_shared_mesh() {
    // Reads ../shared/data/meshes/menger_sponge_level3.obj (a level-3
    // sponge on [-0.5, 0.5]³ from the Manifold library, triangulated).
    let dir = holey_testkit::shared_meshes_or_return!("exact_level_three_matches_the_shared_mesh");
    let file = match holey_io::read_path(&dir.join("menger_sponge_level3.obj")).unwrap() {
        holey_io::MeshFile::Poly(p) => p,
        holey_io::MeshFile::Dlfl(_) => panic!("expected a polygon mesh"),
    };
    let theirs = analyze(&file);
    assert!(theirs.closed && theirs.manifold);
    assert_eq!(theirs.genus, Some(1409));

    let mut m = prim("@cube");
    menger(&mut m, &exact(3)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1409);
    // Ours is on [-1, 1]³: halve it.
    let ours = dlfl_info(&m);
    let [lo, hi] = ours.bbox.unwrap();
    let [tlo, thi] = theirs.bbox.unwrap();
    for k in 0..3 {
        assert!((lo[k] / 2.0 - tlo[k]).abs() < 1e-6);
        assert!((hi[k] / 2.0 - thi[k]).abs() < 1e-6);
    }
    let v_ours = ours.volume.unwrap() / 8.0;
    let v_theirs = theirs.volume.unwrap();
    assert!((v_ours - v_theirs).abs() < 1e-6, "{v_ours} vs {v_theirs}");
    assert!((v_ours - (20.0f64 / 27.0).powi(3)).abs() < 1e-12);
    assert!((ours.area / 4.0 - theirs.area).abs() < 1e-5 * theirs.area);
    // Same shape: the corners and centroids of their triangles all lie on
    // the boundary of the level-3 sponge's cells (some cell around the
    // point kept, some removed). Our mesh is that boundary, cell face by
    // cell face (exact_mode_levels_one_to_three and the unit tests).
    for p in &file.positions {
        assert!(on_level3_boundary(*p), "vertex {p:?}");
    }
    for f in file.faces() {
        let c = f.iter().map(|&i| file.positions[i as usize]).sum::<DVec3>() / f.len() as f64;
        assert!(on_level3_boundary(c), "centroid {c:?}");
    }
}

/// Whether a point of [-0.5, 0.5]³ lies on the boundary of the level-3
/// sponge: among the cells of the 27-grid whose closure holds it, some are
/// kept and some removed or outside.
fn on_level3_boundary(p: DVec3) -> bool {
    let kept = |c: [i64; 3]| -> bool {
        if c.iter().any(|&x| !(0..27).contains(&x)) {
            return false;
        }
        let mut c = c;
        for _ in 0..3 {
            if c.iter().filter(|&&x| x % 3 == 1).count() >= 2 {
                return false;
            }
            for x in &mut c {
                *x /= 3;
            }
        }
        true
    };
    let q = (p + DVec3::splat(0.5)) * 27.0;
    let choices: Vec<Vec<i64>> = q
        .to_array()
        .iter()
        .map(|&x| {
            let r = x.round();
            if (x - r).abs() < 1e-5 {
                vec![r as i64 - 1, r as i64]
            } else {
                vec![x.floor() as i64]
            }
        })
        .collect();
    let (mut any_kept, mut any_removed) = (false, false);
    for &x in &choices[0] {
        for &y in &choices[1] {
            for &z in &choices[2] {
                if kept([x, y, z]) {
                    any_kept = true;
                } else {
                    any_removed = true;
                }
            }
        }
    }
    any_kept && any_removed
}
