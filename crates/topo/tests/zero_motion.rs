//! No motion, no collision: every vertex has even parity, every
//! intersection curve borders only even vertices and is dropped, and the
//! engine returns its input — same triangles, same positions — including
//! the static self-intersections it had.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

fn check_unchanged(m: &TriMesh, what: &str) {
    let pairs = self_intersecting_pairs(m);
    for orient in [false, true] {
        let out = run(
            m,
            &m.positions,
            &Options {
                orient,
                ..Options::default()
            },
        );
        assert_eq!(
            out.report.collisions, 0,
            "{what}: collisions without motion"
        );
        assert!(
            out.raw_odd.iter().chain(&out.corrected_odd).all(|&o| !o),
            "{what}: odd vertices"
        );
        assert_eq!(
            out.mesh.triangles.len(),
            m.triangles.len(),
            "{what}: triangle count"
        );
        if orient {
            // Orientation may be made consistent, nothing else.
            assert_eq!(
                unoriented_triangle_keys(&out.mesh),
                unoriented_triangle_keys(m),
                "{what}: triangles"
            );
        } else {
            assert_eq!(
                oriented_triangle_keys(&out.mesh),
                oriented_triangle_keys(m),
                "{what}: triangles"
            );
            assert_eq!(out.mesh.triangles, m.triangles, "{what}: triangle indices");
        }
        assert_eq!(
            &out.mesh.positions[..m.positions.len()],
            &m.positions[..],
            "{what}: positions"
        );
        assert_eq!(
            self_intersecting_pairs(&out.mesh),
            pairs,
            "{what}: static self-intersections"
        );
    }
}

#[test]
fn generated_meshes() {
    for spec in [
        "@sphere:3",
        "@torus:32:16",
        "@cube:4",
        "@tri-plane:8:8",
        "@cylinder:16:3",
        "@cone",
    ] {
        check_unchanged(&primitive(spec), spec);
    }
}

#[test]
fn self_intersecting_generated_meshes() {
    let s = primitive("@sphere:3");
    let two = join(&s, &translate(&s, DVec3::new(1.0, 0.2, 0.1)));
    assert!(self_intersecting_pairs(&two) > 0);
    check_unchanged(&two, "two overlapping spheres");
    let plane = scale(&primitive("@tri-plane:10:10"), 2.0);
    let through = join(
        &plane,
        &translate(&primitive("@cylinder:16:3"), DVec3::new(0.01, 0.02, 0.1)),
    );
    assert!(self_intersecting_pairs(&through) > 0);
    check_unchanged(&through, "cylinder through a plane");
}

/// Reads ../shared/data/meshes; skipped visibly when it is absent.
#[test]
fn shared_meshes() {
    let dir = holey_testkit::shared_meshes_or_return!("zero_motion::shared_meshes");
    let teapot = read_shared(&dir, "teapot.obj");
    check_unchanged(&teapot, "teapot");
    let a = read_shared(&dir, "self_intersectA.obj");
    assert!(
        self_intersecting_pairs(&a) > 0,
        "self_intersectA has no self-intersections"
    );
    check_unchanged(&a, "self_intersectA");
}
