//! Invalid input is refused with an error that says what is wrong, never a
//! panic: non-finite coordinates (start or end), indices out of range, end
//! positions that do not match the vertex count — through every entry
//! point.

#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Accumulator, Options, TriMesh, resolve, self_intersections, topology_change};

fn quad() -> TriMesh {
    primitive("@tri-plane:1:1")
}

fn error_of(mesh: &TriMesh, end: &[DVec3]) -> String {
    match topology_change(mesh, end, &Options::default()) {
        Ok(_) => panic!("accepted invalid input"),
        Err(e) => e.to_string(),
    }
}

/// The errors of the other entry points that take a mesh alone
/// (`resolve`, `self_intersections`, `Accumulator::new`) on `mesh`, each
/// of which must refuse it.
fn errors_of_the_other_entries(mesh: &TriMesh) -> [String; 3] {
    [
        resolve(mesh).unwrap_err().to_string(),
        self_intersections(mesh).unwrap_err().to_string(),
        Accumulator::new(mesh.clone(), Options::default())
            .unwrap_err()
            .to_string(),
    ]
}

#[test]
fn non_finite_start_positions() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut m = quad();
        m.positions[2].y = bad;
        let end = quad().positions;
        let e = error_of(&m, &end);
        assert!(
            e.contains("non-finite") && e.contains("vertex 2") && e.contains("mesh"),
            "{e}"
        );
        for e in errors_of_the_other_entries(&m) {
            assert!(e.contains("non-finite") && e.contains("vertex 2"), "{e}");
        }
    }
}

#[test]
fn non_finite_end_positions() {
    let m = quad();
    let mut end = m.positions.clone();
    end[3].z = f64::NAN;
    let e = error_of(&m, &end);
    assert!(
        e.contains("end positions") && e.contains("vertex 3") && e.contains("non-finite"),
        "{e}"
    );
    let mut acc = Accumulator::new(m, Options::default()).unwrap();
    let e = acc.advance(&end).unwrap_err().to_string();
    assert!(e.contains("end positions") && e.contains("vertex 3"), "{e}");
    assert_eq!(acc.frames(), 0, "a refused frame was counted");
}

#[test]
fn index_out_of_range() {
    let mut m = quad();
    m.triangles.push([0, 1, 7]);
    let e = error_of(&m, &m.positions.clone());
    assert!(
        e.contains("triangle 2") && e.contains('7') && e.contains("only 4 vertices"),
        "{e}"
    );
    m.triangles[2] = [u32::MAX, 0, 1];
    let e = error_of(&m, &m.positions.clone());
    assert!(e.contains(&u32::MAX.to_string()), "{e}");
    for e in errors_of_the_other_entries(&m) {
        assert!(e.contains("triangle 2"), "{e}");
    }
}

#[test]
fn mismatched_vertex_counts() {
    let m = quad();
    for n in [0, 3, 5, 100] {
        let end = vec![DVec3::ZERO; n];
        let e = error_of(&m, &end);
        assert!(
            e.contains(&format!("give {n} vertices")) && e.contains("has 4"),
            "{e}"
        );
        let mut acc = Accumulator::new(m.clone(), Options::default()).unwrap();
        assert!(acc.advance(&end).unwrap_err().to_string().contains("has 4"));
    }
}

#[test]
fn empty_and_triangle_free_meshes_are_fine() {
    let empty = TriMesh::default();
    let out = topology_change(&empty, &[], &Options::default()).unwrap();
    assert!(out.mesh.triangles.is_empty());
    let points = TriMesh {
        positions: vec![DVec3::ZERO, DVec3::X],
        triangles: vec![],
    };
    let out = topology_change(&points, &[DVec3::Y, DVec3::Z], &Options::default()).unwrap();
    assert!(out.mesh.triangles.is_empty());
}

/// Finite but huge coordinates overflow products inside predicates: the
/// engine must answer (Ok or a typed error), not panic.
#[test]
fn huge_finite_coordinates_do_not_panic() {
    for s in [1e150, 1e300, f64::MAX / 4.0] {
        let a = scale(&primitive("@sphere:1"), s);
        let b = translate(&a, DVec3::new(0.5 * s, 0.0, 0.0));
        let start = join(&a, &translate(&b, DVec3::new(10.0 * s, 0.0, 0.0)));
        let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
        let end: Vec<DVec3> = end
            .into_iter()
            .map(|p| if p.is_finite() { p } else { DVec3::ZERO })
            .collect();
        let start = map_positions(&start, |p| if p.is_finite() { p } else { DVec3::ZERO });
        if let Ok(out) = topology_change(&start, &end, &Options::default()) {
            well_formed(&out.mesh);
        }
    }
}

/// A frame whose end crumples the surface into more intersecting pairs
/// than the limit is refused with a message saying so, from the one-frame
/// engine, its local twin and the accumulator's release alike; the mesh
/// handed to the local engine is left as it was.
#[test]
fn too_many_intersecting_pairs_is_an_error() {
    let a = primitive("@sphere:2");
    let b = translate(&a, DVec3::new(0.6, 0.05, 0.02));
    let start = join(&a, &translate(&b, DVec3::new(4.0, 0.0, 0.0)));
    let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
    let options = Options {
        max_intersecting_pairs: Some(5),
        ..Options::default()
    };
    let check = |e: String| assert!(e.contains("more than 5 triangle pairs"), "{e}");
    match topology_change(&start, &end, &options) {
        Ok(_) => panic!("a limit of 5 pairs must stop this union"),
        Err(e) => check(e.to_string()),
    }
    let mut local = start.clone();
    match holey_topo::topology_change_local(&mut local, &end, &options) {
        Ok(_) => panic!("the local engine must stop too"),
        Err(e) => check(e.to_string()),
    }
    assert_eq!(local.positions, start.positions);
    assert_eq!(local.triangles, start.triangles);
    let mut acc = Accumulator::new(start.clone(), options).unwrap();
    acc.advance(&end).unwrap();
    match acc.release() {
        Ok(_) => panic!("the release must stop too"),
        Err(e) => check(e.to_string()),
    }
    // Without the limit the same union goes through.
    assert!(topology_change(&start, &end, &Options::default()).is_ok());
}
