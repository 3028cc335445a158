//! Figure 10: pinch closing. Two parts of one closed surface are pushed
//! together until they overlap: the overlap is deleted and the parts are
//! glued. The two arms of a U-shaped closed tube bent into each other
//! close the U into a ring: one closed component of genus 1.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

const RADIUS: f64 = 0.3;

/// A U: left arm x = −1 from y = 2 down, a half circle of radius 1 under
/// the origin, right arm x = 1 up to y = 2.25 (the ends at different
/// heights, so the end caps are not coplanar).
fn u_tube() -> TriMesh {
    let mut c = Vec::new();
    let step = 0.1;
    let mut y = 2.0;
    while y > 0.0 {
        c.push(DVec3::new(-1.0, y, 0.0));
        y -= step;
    }
    for k in 0..=31 {
        let a = std::f64::consts::PI * (1.0 + f64::from(k) / 31.0);
        c.push(DVec3::new(a.cos(), a.sin(), 0.0));
    }
    let mut y = step;
    while y < 2.25 + 1e-9 {
        c.push(DVec3::new(1.0, y, 0.0));
        y += step;
    }
    c.dedup_by(|a, b| (*a - *b).length() < 1e-9);
    tube(&c, RADIUS, 12, 0.37, DVec3::Z)
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The upper arms are moved towards each other by `d` (each).
fn bend(m: &TriMesh, d: f64) -> Vec<DVec3> {
    m.positions
        .iter()
        .map(|&p| {
            DVec3::new(
                p.x - d * (p.x / 0.3).tanh() * smoothstep(0.5, 1.6, p.y),
                p.y,
                p.z,
            )
        })
        .collect()
}

#[test]
fn arms_pushed_together_close_a_handle() {
    let m = u_tube();
    assert!(closed_oriented(&m) && genus(&m) == 0 && self_intersecting_pairs(&m) == 0);
    // Arm centres from ±1 to ±0.15: the tubes (radius 0.3) overlap.
    let end = bend(&m, 0.85);
    let out = run(&m, &end, &Options::default()).mesh;
    assert!(
        closed_oriented(&out),
        "defects {:?}",
        closedness_defects(&out)
    );
    assert_eq!(self_intersecting_pairs(&out), 0);
    assert_eq!(components(&out), 1);
    assert_eq!(genus(&out), 1, "the U did not close into a ring");
    let v_end = volume(&TriMesh {
        positions: end,
        triangles: m.triangles.clone(),
    });
    let v = volume(&out);
    // The overlap is counted once: less than the two overlapping arms.
    assert!(v > 0.0 && v < v_end - 0.01, "volume {v} vs {v_end} before");
    // The left arm's end cap (inside the right arm) is gone; the gap
    // between the arms below the overlap is outside.
    assert!(!inside(&out, DVec3::new(0.0, 0.2, 0.0)));
    assert!(inside(&out, DVec3::new(0.0, 1.9, 0.0)));
}

#[test]
fn arms_that_do_not_reach_change_nothing() {
    let m = u_tube();
    // Arm centres to ±0.7: the tubes (radius 0.3) stay 0.8 apart.
    let out = run(&m, &bend(&m, 0.3), &Options::default()).mesh;
    assert_eq!(out.triangles.len(), m.triangles.len());
    assert_eq!(genus(&out), 0);
}
