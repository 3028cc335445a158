//! A crumple may not leave handles too small to see (the guard's crumple
//! rule, `crate::hidden::tiny_new_curves`): where many triangles cross
//! near one point, the cut glues the surface along intersection curves
//! far smaller than any edge, and each is a tunnel nobody can see or
//! select. A frame that makes two or more of them within an edge of each
//! other is held. One small curve (how every contact starts), and small
//! curves far apart (a brush and its mirror image: the sculpt crate's
//! `a_mirrored_crease_through_a_slab_opens_two_holes`), are not a
//! crumple, and a contact whose curve is larger than an edge fuses as
//! before.
//!
//! The rods are generated here; genus and pieces are counted by the test
//! helpers (Euler characteristic and a union-find of their own).

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh, topology_change_guarded};

/// A straight closed tube along x, from −2 to 2, radius 0.3, rings every
/// 0.1, `segments` around.
fn rod(segments: u32) -> TriMesh {
    let centre: Vec<DVec3> = (0..=40)
        .map(|i| DVec3::new(-2.0 + 0.1 * f64::from(i), 0.0, 0.0))
        .collect();
    tube(&centre, 0.3, segments, 0.21, DVec3::Z)
}

/// The rod's waist squeezed through its axis unevenly: the cross-section
/// at x is scaled by `1 − depth·b(x)·(1 + amp·cos(k·θ + 0.4))`, θ the
/// angle around the axis, and shifted by `(0.011, −0.007)·amp·b(x)`,
/// where `b` is a smooth bump of half-width 0.75 (1 at the middle). Each
/// ring near the waist passes through the axis at its own place.
fn crumpled(m: &TriMesh, depth: f64, k: f64, amp: f64) -> Vec<DVec3> {
    m.positions
        .iter()
        .map(|&p| {
            let t = (p.x / 0.75).abs().min(1.0);
            let b = (1.0 - t * t).powi(2);
            let s = 1.0 - depth * b * (1.0 + amp * (k * p.z.atan2(p.y) + 0.4).cos());
            DVec3::new(p.x, p.y * s + 0.011 * amp * b, p.z * s - 0.007 * amp * b)
        })
        .collect()
}

/// Two crumples the other rules let through (found by a search over
/// segments, depths and waves; the rods' edges are 0.1 and longer):
/// unguarded, the rod of 16 segments keeps one piece and gains genus 10,
/// the one of 12 segments breaks into three pieces of total genus 8, all
/// through curves of less than 10⁻⁴. Guarded, each frame is held: the
/// mesh is as it was, and the reason has plain words.
#[test]
fn a_rod_crumpled_through_its_axis_gains_no_tiny_handles() {
    for (segments, depth, k, amp) in [(16, 1.7, 2.0, 0.3), (12, 1.3, 3.0, 0.15)] {
        let what = format!("{segments} segments, depth {depth}, wave {k} × {amp}");
        let m = rod(segments);
        assert!(closed_oriented(&m) && components(&m) == 1 && genus(&m) == 0);
        let end = crumpled(&m, depth, k, amp);
        let unguarded = run(&m, &end, &Options::default()).mesh;
        let total_genus: i64 = split_components(&unguarded).iter().map(genus).sum();
        assert!(total_genus >= 5, "{what}: unguarded genus {total_genus}");

        let mut held = m.clone();
        let r = topology_change_guarded(&mut held, &end, &Options::default()).unwrap();
        assert!(r.held_all, "{what}: {r:?}");
        assert_eq!(held, m, "{what}: a held frame changes nothing");
        let why = r
            .refused
            .iter()
            .find(|w| w.starts_with("tiny handles"))
            .unwrap_or_else(|| panic!("{what}: {:?}", r.refused));
        assert_ne!(holey_topo::audit::in_plain_words(why), why.as_str());
    }
}

/// A U of tube whose second arm's end is pushed sideways through the
/// first arm: one contact with a curve as large as the tube, which fuses
/// the arms into a handle (genus 1, one closed piece), guarded or not.
#[test]
fn an_arm_pushed_through_the_other_still_makes_a_handle() {
    // A half circle of radius 1 in the xy plane, rings every 0.1 along it
    // (edges about 0.1 and 0.12), then straight arms 1.2 long along −x.
    let mut centre: Vec<DVec3> = (0..=12)
        .map(|i| DVec3::new(-1.2 + 0.1 * f64::from(i), -1.0, 0.0))
        .collect();
    centre.extend((1..32).map(|i| {
        let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * f64::from(i) / 32.0;
        DVec3::new(a.cos(), a.sin(), 0.0)
    }));
    centre.extend((0..=12).map(|i| DVec3::new(-0.1 * f64::from(i), 1.0, 0.0)));
    let m = tube(&centre, 0.3, 12, 0.21, DVec3::Z);
    assert!(closed_oriented(&m) && components(&m) == 1 && genus(&m) == 0);
    // The second arm's last 0.7 (the ring at x = −0.5 onwards, and its
    // cap) bends down through the first arm, whose axis is at y = −1.
    let end: Vec<DVec3> = m
        .positions
        .iter()
        .map(|&p| {
            if p.y > 0.5 && p.x < -0.45 {
                let t = ((-0.45 - p.x) / 0.75).min(1.0);
                p - DVec3::new(0.0, 2.0 * t, 0.0)
            } else {
                p
            }
        })
        .collect();
    let mut fused = m.clone();
    let r = topology_change_guarded(&mut fused, &end, &Options::default()).unwrap();
    assert!(r.refused.is_empty(), "{:?}", r.refused);
    assert_eq!(components(&fused), 1);
    assert!(closed_oriented(&fused));
    assert_eq!(genus(&fused), 1, "the arms fused into a handle");
}
