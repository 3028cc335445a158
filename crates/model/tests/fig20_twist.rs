//! Figure 20 (§IV.5): the choice of corners twists the handle. Every
//! choice gives the same counts and a valid manifold; the geometry of the
//! sections differs.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::DVec3;
use holey_model::handle::{HandleParams, create_handle};
use soups_and_oracles::*;

#[test]
fn each_corner_choice_gives_the_same_counts_and_a_different_twist() {
    let c = poly("@cylinder:5:1");
    let soup = union(&c, &c, DVec3::new(3.0, 0.0, 0.0));
    let m0 = mesh(&soup);
    let mut shapes: Vec<Vec<DVec3>> = Vec::new();
    let mut result_counts = Vec::new();
    for k in 0..5 {
        let mut m = m0.clone();
        let (a, b) = (corner(&m, 1), nth_corner(&m, 7 + 1, k));
        let r = create_handle(&mut m, a, b, &HandleParams::new(4, 2.0, 2.0)).unwrap();
        m.validate().unwrap();
        assert_eq!(m.genus(), 0);
        result_counts.push(counts(&m));
        // The middle section, vertex j matching vertex j of f1.
        shapes.push(
            r.sections[1]
                .iter()
                .map(|&v| m.position(v).unwrap())
                .collect(),
        );
        // Pipe edges of the first pipe run from f1's vertex j to the first
        // section's vertex j: the twist is in the sections.
        assert_eq!(r.pipes[0].len(), 5);
    }
    assert!(result_counts.windows(2).all(|w| w[0] == w[1]));
    for i in 0..5 {
        for j in i + 1..5 {
            let differ = shapes[i]
                .iter()
                .zip(&shapes[j])
                .any(|(p, q)| (*p - *q).length() > 1e-6);
            assert!(differ, "corner choices {i} and {j} gave the same handle");
        }
    }
}

#[test]
fn the_first_angles_differ_by_at_most_half_a_turn() {
    // The middle section's first vertex lies between the directions of the
    // two end faces' first vertices (seen from the section centre, after
    // interpolation): it never swings the long way round.
    let c = poly("@cylinder:4:1");
    let m0 = mesh(&union(&c, &c, DVec3::new(0.0, 0.0, 4.0)));
    // The first cylinder's top (1) and the second's bottom (6 + 0), facing.
    for k in 0..4 {
        let mut m = m0.clone();
        let (a, b) = (corner(&m, 1), nth_corner(&m, 6, k));
        let pa = m.position(m.corner_vertex(a).unwrap()).unwrap();
        let pb = m.position(m.corner_vertex(b).unwrap()).unwrap();
        let r = create_handle(&mut m, a, b, &HandleParams::new(2, 1.0, 1.0)).unwrap();
        m.validate().unwrap();
        let mid = m.position(r.sections[0][0]).unwrap();
        let ang = |p: DVec3| p.y.atan2(p.x);
        let (t1, t2, tm) = (ang(pa), ang(pb), ang(mid));
        let mut d = t2 - t1;
        d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
        assert!(d.abs() <= std::f64::consts::PI + 1e-12);
        let mut e = tm - t1;
        e -= (e / std::f64::consts::TAU).round() * std::f64::consts::TAU;
        if (d.abs() - std::f64::consts::PI).abs() < 1e-9 {
            // Half a turn either way is the same twist.
            assert!(
                (e.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
                "k={k}: {e}"
            );
        } else {
            assert!((e - d / 2.0).abs() < 1e-9, "k={k}: {e} vs {}", d / 2.0);
        }
    }
}
