//! Degenerate input: coplanar overlaps, edges through vertices and edges,
//! duplicate triangles, exactly aligned grids, and the same scenario at
//! huge, tiny and offset coordinates. Never a panic, always well formed;
//! scaled and offset copies give the same combinatorial result.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh, topology_change};

/// `b` starts at `b + from` and moves to its given place, `a` stays.
fn collide(a: &TriMesh, b: &TriMesh, from: DVec3) -> holey_topo::Outcome {
    let start = join(a, &translate(b, from));
    let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
    run(&start, &end, &Options::default())
}

#[test]
fn coplanar_overlapping_grids() {
    let g = primitive("@tri-plane:4:4");
    // Static coplanar overlap, sliding within the plane, and landing on it.
    let shifted = translate(&g, DVec3::new(0.3, 0.2, 0.0));
    for from in [
        DVec3::ZERO,
        DVec3::new(-1.0, 0.5, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    ] {
        let out = collide(&g, &shifted, from);
        assert!(!out.mesh.triangles.is_empty());
    }
    // Two single coplanar triangles.
    let t = triangle([DVec3::ZERO, DVec3::X, DVec3::Y]);
    let _ = collide(
        &t,
        &translate(&t, DVec3::new(0.25, 0.25, 0.0)),
        DVec3::new(0.0, 0.0, 0.5),
    );
}

#[test]
fn edge_through_vertex_and_edge() {
    let t = triangle([
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ]);
    // A vertical triangle whose edge passes exactly through t's vertex 2,
    // then exactly through t's edge 0–1 at its midpoint.
    for hit in [DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, -1.0, 0.0)] {
        let v = triangle([
            hit + DVec3::new(0.0, 0.0, -1.0),
            hit + DVec3::new(0.0, 0.0, 1.0),
            hit + DVec3::new(0.0, 0.5, 2.0),
        ]);
        let _ = collide(&t, &v, DVec3::new(3.0, 0.0, 0.0));
        let _ = collide(&t, &v, DVec3::ZERO);
    }
    // A cube whose edge lands exactly on a plane vertex line.
    let plane = scale(&primitive("@tri-plane:4:4"), 2.0);
    let cube = scale(&primitive("@cube"), 0.5);
    let _ = collide(&plane, &cube, DVec3::new(0.0, 0.0, 2.0));
}

#[test]
fn duplicate_triangles() {
    let s = primitive("@sphere:2");
    let mut doubled = s.clone();
    doubled.triangles.extend(s.triangles.clone());
    let out = collide(&doubled, &s, DVec3::new(0.0, 0.0, 3.0));
    well_formed(&out.mesh);
    // Every triangle doubled, including the mover.
    let b = translate(&doubled, DVec3::new(0.7, 0.1, 0.05));
    let _ = collide(&doubled, &b, DVec3::new(5.0, 0.0, 0.0));
}

/// A cube grid moved exactly onto the lattice of another: every vertex of
/// one lands on a vertex, edge or face plane of the other, and faces land
/// in one plane and overlap. Every crossing is then a shared point, edge
/// or plane, and exactly at the end no intersection explains what
/// collided; the engine retries with end positions moved by up to 2^-20
/// of the diagonal, and the result is their union: closed, one piece, the
/// volume to that offset. The same at huge, tiny and offset coordinates, where an
/// absolute perturbation (Cork's 1e-5) would vanish or swamp the model:
/// simulation of simplicity and the scale-relative retry do not care.
#[test]
fn aligned_grids_collide() {
    let c = primitive("@cube:4");
    let maps: [(&str, Map); 6] = [
        ("unit", Box::new(|p| p)),
        ("×2^20", Box::new(|p| p * 1048576.0)),
        ("×1e6", Box::new(|p| p * 1e6)),
        ("×1e-6", Box::new(|p| p * 1e-6)),
        ("+4096", Box::new(|p| p + DVec3::splat(4096.0))),
        (
            "×1e3 + 1e6",
            Box::new(|p| p * 1e3 + DVec3::new(1e6, -1e6, 1e6)),
        ),
    ];
    // (shift, volume of the union of two cubes [-1,1]³).
    let cases = [
        (DVec3::new(1.0, 0.0, 0.0), 12.0),
        (DVec3::new(0.5, 0.5, 0.5), 16.0 - 1.5 * 1.5 * 1.5),
        (DVec3::new(1.0, 0.5, 0.0), 13.0),
    ];
    for (what, f) in &maps {
        // Volume scale of the map: its derivative cubed.
        let k = (f(DVec3::X) - f(DVec3::ZERO)).length().powi(3);
        for (shift, want) in cases {
            for from in [DVec3::new(0.0, 0.0, 5.0), DVec3::new(6.0, 1.87, 1.03)] {
                let a = map_positions(&c, f.as_ref());
                let b = map_positions(&translate(&c, shift), f.as_ref());
                let d = f(from) - f(DVec3::ZERO);
                let out = collide(&a, &b, d);
                let m = &out.mesh;
                let case = format!("{what}, shift {shift}, from {from}");
                assert!(closed_oriented(m), "{case}: {:?}", closedness_defects(m));
                assert_eq!(components(m), 1, "{case}: components");
                assert_eq!(genus(m), 0, "{case}: genus");
                assert_eq!(self_intersecting_pairs(m), 0, "{case}: intersects itself");
                let v = volume(m) / k;
                // The retry moves end positions by up to 2^-20 of the
                // diagonal (about 1e-6): the volume moves by about that.
                assert!(
                    (v - want).abs() < 2e-5 * want,
                    "{case}: volume {v} vs {want}"
                );
                assert!(out.report.perturbation_retries >= 1, "{case}: no retry");
            }
        }
    }
}

#[test]
fn spheres_shifted_exactly_give_a_closed_union() {
    let s = primitive("@sphere:3");
    let out = collide(&s, &translate(&s, DVec3::X), DVec3::new(10.0, 0.0, 0.0));
    assert!(
        closed_oriented(&out.mesh),
        "defects {:?}",
        closedness_defects(&out.mesh)
    );
    assert_eq!(components(&out.mesh), 1);
    assert_eq!(genus(&out.mesh), 0);
}

/// Union of a cube and a sphere, placed generically, after mapping all
/// coordinates by `f`: (triangles, components, genus, closed).
fn signature(f: &dyn Fn(DVec3) -> DVec3) -> (usize, usize, i64, bool) {
    let a = primitive("@cube:4");
    let b = translate(&primitive("@sphere:2"), DVec3::new(0.93, 0.71, 0.55));
    let start = map_positions(&join(&a, &translate(&b, DVec3::new(6.0, 0.0, 0.0))), f);
    let end: Vec<DVec3> = a
        .positions
        .iter()
        .chain(&b.positions)
        .map(|&p| f(p))
        .collect();
    let out =
        topology_change(&start, &end, &Options::default()).expect("engine refused a valid input");
    well_formed(&out.mesh);
    assert_eq!(self_intersecting_pairs(&out.mesh), 0);
    let m = &out.mesh;
    (
        m.triangles.len(),
        components(m),
        genus(m),
        closed_oriented(m),
    )
}

type Map = Box<dyn Fn(DVec3) -> DVec3>;

#[test]
fn scale_and_offset_do_not_change_the_result() {
    let unit = signature(&|p| p);
    assert_eq!(
        (unit.1, unit.2, unit.3),
        (1, 0, true),
        "the union of a cube and a sphere"
    );
    // Powers of two and a 4096 offset are exact: the very same arithmetic.
    let exact: [(&str, Map); 3] = [
        ("×2^20", Box::new(|p| p * 1048576.0)),
        ("×2^-20", Box::new(|p| p / 1048576.0)),
        ("+4096", Box::new(|p| p + DVec3::splat(4096.0))),
    ];
    for (what, f) in &exact {
        assert_eq!(signature(f.as_ref()), unit, "{what}");
    }
    // Rounded copies: the configuration is generic, so the combinatorics
    // cannot change under relative errors of 1e-16.
    let rounded: [(&str, Map); 4] = [
        ("×1e6", Box::new(|p| p * 1e6)),
        ("×1e-6", Box::new(|p| p * 1e-6)),
        ("+1e5", Box::new(|p| p + DVec3::new(1e5, -1e5, 1e5))),
        (
            "×1e6 + 4096·1e6",
            Box::new(|p| p * 1e6 + DVec3::splat(4096e6)),
        ),
    ];
    for (what, f) in &rounded {
        assert_eq!(signature(f.as_ref()), unit, "{what}");
    }
}

/// A degenerate storm (issue 14): one polygon of 900,000 corners over
/// three points fans into 300,000 copies of one triangle and 600,000
/// triangles with a repeated corner. Copies share every point and a
/// repeated corner has no area, so there is one triangle to test: no
/// pair intersects, and the count comes back at once instead of after
/// 4.5 × 10¹⁰ box pairs. With a triangle crossing the copies, every copy
/// crosses it: 300,000 pairs, past the limit asked for, which refuses.
#[test]
fn a_degenerate_storm_is_one_triangle() {
    let corners = 900_000u32;
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let fan: Vec<[u32; 3]> = (1..corners - 1).map(|k| [0, k % 3, (k + 1) % 3]).collect();
    let storm = TriMesh {
        positions: positions.clone(),
        triangles: fan.clone(),
    };
    assert_eq!(
        holey_topo::self_intersections(&storm).unwrap().pairs.len(),
        0
    );
    assert!(!holey_topo::crosses_itself(&storm).unwrap());

    let mut crossed = storm.clone();
    crossed.positions.extend([
        DVec3::new(0.2, 0.2, -1.0),
        DVec3::new(0.3, 0.2, 1.0),
        DVec3::new(0.2, 0.3, 1.0),
    ]);
    crossed.triangles.push([3, 4, 5]);
    let copies = fan.iter().filter(|t| t[1] != 0 && t[2] != 0).count();
    assert_eq!(copies, 300_000);
    assert_eq!(
        holey_topo::intersect::intersecting_pair_count(&crossed, usize::MAX).unwrap(),
        copies
    );
    assert!(matches!(
        holey_topo::intersect::intersecting_pair_count(&crossed, 1000),
        Err(holey_topo::intersect::IntersectError::TooManyPairs { .. })
    ));
    assert!(holey_topo::crosses_itself(&crossed).unwrap());
}

/// The storm's solid (`holey union storm.obj`, one input, the winding
/// rule for an open input): the 300,000 copies put w = ∓300,000 Ω/4π on
/// the two sides of their triangle (solid angles summed in the test), so the
/// one boundary between inside and outside is that triangle, facing from
/// inside out. A group of coincident cells that large made every ray and
/// every generalized winding number scan the whole group per triangle
/// (151 s); looked up sorted, it is linear.
#[test]
fn a_degenerate_storms_solid_is_its_one_triangle() {
    let corners = 900_000u32;
    let storm = TriMesh {
        positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        triangles: (1..corners - 1).map(|k| [0, k % 3, (k + 1) % 3]).collect(),
    };
    let out = holey_topo::solid_boolean(
        &[&storm],
        holey_topo::Operation::Union,
        &holey_topo::BooleanOptions::default(),
    )
    .unwrap();
    let m = out.mesh();
    assert_eq!(m.triangles.len(), 1);
    let [a, b, c] = m.corners(0);
    let normal = (b - a).cross(c - a);
    let (front, back) = (DVec3::new(0.2, 0.2, 0.1), DVec3::new(0.2, 0.2, -0.1));
    let (w_front, w_back) = (winding(&storm, front), winding(&storm, back));
    // Opposite, and far past ½: one side is inside, the other outside.
    assert!(w_front.abs() > 1.0 && (w_front + w_back).abs() < 1e-6 * w_front.abs());
    // The kept triangle faces the side that is outside (w < ½).
    let outside = if w_front < 0.5 { front } else { back };
    assert!(normal.dot(outside - a) > 0.0);
    assert_eq!(normal.length(), 1.0);
}
