//! Figure 18 (§IV.4): multi-segment curved handles — exact counts for
//! several face sizes and segment counts, in one component (genus + 1)
//! and between two components (they join), and the sections' placement on
//! the Hermite curve of eq. 4.1 with normals along its tangent.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::DVec3;
use holey_model::handle::{HandleParams, Orientation, create_handle, create_handle_observed};
use soups_and_oracles::*;

#[test]
fn a_handle_of_s_segments_between_d_gons_adds_d_s_minus_1_vertices() {
    for d in [3usize, 4, 5, 8] {
        for s in [1usize, 2, 3, 5] {
            // A cylinder's caps are d-gons; a tunnel from the top cap to the
            // bottom cap (negative weights) stays in one component.
            let mut m = prim(&format!("@cylinder:{d}:1"));
            assert_eq!(counts(&m), (2 * d, 3 * d, d + 2));
            let (top, bottom) = (corner(&m, 1), corner(&m, 0));
            let r = create_handle(&mut m, top, bottom, &HandleParams::new(s, -0.5, -0.5)).unwrap();
            m.validate().unwrap();
            assert_eq!(
                counts(&m),
                (
                    2 * d + d * (s - 1),
                    3 * d + d * (2 * s - 1),
                    d + 2 + d * s - 2
                ),
                "d={d} s={s}"
            );
            assert_eq!(m.genus(), 1, "d={d} s={s}");
            assert_eq!(m.topology().component_count(), 1);
            assert_eq!(r.pipes.len(), s);
            assert!(r.pipes.iter().all(|p| p.len() == d));
            assert_eq!(r.sections.len(), s - 1);
            assert_eq!(r.plan.subdivisions, 0);
        }
    }
}

#[test]
fn a_handle_between_two_components_joins_them_without_genus() {
    for d in [3usize, 4, 6] {
        for s in [1usize, 2, 4] {
            let c = poly(&format!("@cylinder:{d}:1"));
            let mut m = mesh(&union(&c, &c, DVec3::new(3.0, 0.0, 0.0)));
            assert_eq!(m.topology().component_count(), 2);
            // The two top caps: a U-shaped handle.
            let (a, b) = (corner(&m, 1), corner(&m, d + 2 + 1));
            create_handle(&mut m, a, b, &HandleParams::new(s, 2.0, 2.0)).unwrap();
            m.validate().unwrap();
            assert_eq!(
                counts(&m),
                (
                    4 * d + d * (s - 1),
                    6 * d + d * (2 * s - 1),
                    2 * d + 4 + d * s - 2
                ),
                "d={d} s={s}"
            );
            assert_eq!(m.topology().component_count(), 1);
            assert_eq!(m.genus(), 0);
        }
    }
}

/// Checks each section of a handle built between faces `f1`, `f2` of `m0`
/// against eq. 4.1 evaluated independently.
fn check_sections_on_curve(
    m0: &holey_dlfl::Mesh,
    f1: usize,
    f2: usize,
    k: usize,
    w1: f64,
    w2: f64,
) {
    let (a, b) = (m0.face_at(f1).unwrap(), m0.face_at(f2).unwrap());
    let (pa, pb) = (m0.face_positions(a).unwrap(), m0.face_positions(b).unwrap());
    let (p1, p2) = (vertex_average(&pa), vertex_average(&pb));
    let (n1, n2) = (unit_normal(m0, a), unit_normal(m0, b));
    let scale = (p2 - p1).length();
    let mut m = m0.clone();
    let r = create_handle(
        &mut m,
        corner(m0, f1),
        corner(m0, f2),
        &HandleParams::new(k, w1, w2),
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!(r.plan.orientation, Orientation::AlongTangent);
    assert_eq!(r.sections.len(), k - 1);
    for (i, vs) in r.sections.iter().enumerate() {
        let t = (i + 1) as f64 / k as f64;
        let pts: Vec<DVec3> = vs.iter().map(|&v| m.position(v).unwrap()).collect();
        let c = vertex_average(&pts);
        let h = hermite(p1, n1, w1, p2, n2, w2, t);
        assert!(
            (c - h).length() <= 1e-9 * scale,
            "section {i}: centroid {c} vs H({t}) = {h}"
        );
        let tangent = hermite_velocity(p1, n1, w1, p2, n2, w2, t).normalize();
        let normal = shoelace(&pts).normalize();
        assert!(
            normal.dot(tangent) > 1.0 - 1e-9,
            "section {i}: normal {normal} vs tangent {tangent}"
        );
        // Planar, perpendicular to the tangent.
        for p in &pts {
            assert!((*p - c).dot(tangent).abs() <= 1e-9 * scale);
        }
    }
}

#[test]
fn sections_lie_on_the_hermite_curve_with_normals_along_its_tangent() {
    // A U-shaped handle between two top faces of a 3×3 cube.
    let cube = prim("@cube:3");
    check_sections_on_curve(&cube, 45, 53, 6, 2.0, 2.0);
    check_sections_on_curve(&cube, 45, 53, 3, 0.5, 3.0);
    // Between a side face and a top face, sideways.
    check_sections_on_curve(&cube, 30, 51, 5, 1.5, 1.0);
    // Between two octagons of different cylinders, tilted against each other.
    let c = poly("@cylinder:8:1");
    let mut two = union(&c, &c, DVec3::new(4.0, 1.0, 0.5));
    for p in two.positions.iter_mut().skip(c.positions.len()) {
        *p = glam::DQuat::from_rotation_y(0.6) * *p;
    }
    check_sections_on_curve(&mesh(&two), 1, 10 + 1, 7, 3.0, 2.5);
}

#[test]
fn the_mesh_is_a_valid_manifold_after_every_step() {
    let mut m = prim("@cube:2");
    let (a, b) = (corner(&m, 20), corner(&m, 23));
    let mut steps = 0;
    create_handle_observed(&mut m, a, b, &HandleParams::new(5, 1.0, 1.0), |mesh, _| {
        mesh.validate().unwrap();
        steps += 1;
    })
    .unwrap();
    assert_eq!(steps, 4 + 5);
    assert_eq!(m.genus(), 1);
}
