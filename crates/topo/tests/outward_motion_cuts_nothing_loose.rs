//! Pieces a guarded frame ([`holey_topo::topology_change_guarded`]) may
//! not leave: specks, pieces hardly wider than the surface's edges where
//! it changed (`crate::hidden::specks`), and, for a motion
//! that only pushes outward ([`Options::outward`], an inflate), any new
//! piece at all. Parts such a motion pushes into each other still join.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh, topology_change_guarded};

/// A straight closed tube along x, from −2 to 2, radius 0.3, rings every
/// 0.1.
fn rod() -> TriMesh {
    let centre: Vec<DVec3> = (0..=40)
        .map(|i| DVec3::new(-2.0 + 0.1 * f64::from(i), 0.0, 0.0))
        .collect();
    tube(&centre, 0.3, 16, 0.21, DVec3::Z)
}

/// The rod's waist squeezed through its axis: the cross-section at x is
/// scaled by 1 − 1.7·b(x), b a smooth bump of half-width 0.75 (−0.7 at
/// the middle). The scale passes 0 between the rings at x = ±0.3 and
/// ±0.4, so the 32 triangles between them all cross the axis at one
/// point (up to rounding): a crumple at its worst.
fn squeezed(m: &TriMesh) -> Vec<DVec3> {
    m.positions
        .iter()
        .map(|&p| {
            let t = (p.x / 0.75).abs().min(1.0);
            let bump = (1.0 - t * t).powi(2);
            let s = 1.0 - 1.7 * bump;
            DVec3::new(p.x, p.y * s, p.z * s)
        })
        .collect()
}

/// Unguarded, the squeeze leaves the rod with a thinner neck and 33
/// closed pieces within 10⁻⁴ of the two crossing points (measured:
/// cells of the arrangement of the crossing triangles, with no volume to
/// speak of). The guard holds the frame instead, and says why; declared
/// outward, it also counts the new pieces.
#[test]
fn a_waist_squeezed_through_its_axis_leaves_no_specks() {
    let m = rod();
    assert!(closed_oriented(&m) && components(&m) == 1);
    let end = squeezed(&m);
    let unguarded = run(&m, &end, &Options::default()).mesh;
    let parts = split_components(&unguarded);
    assert!(parts.len() > 2, "{} pieces", parts.len());
    let specks = parts
        .iter()
        .filter(|p| {
            let (lo, hi) = used_bounds(p);
            (hi - lo).length() < 0.1
        })
        .count();
    assert_eq!(
        specks,
        parts.len() - 1,
        "every piece but the rod is a speck"
    );

    // The rod is one piece: told so ([`Options::one_piece`]), the guard
    // cannot show from the region that it stays one, so it counts, and
    // refuses as it does untold.
    for (outward, one_piece) in [(false, false), (true, false), (false, true), (true, true)] {
        let options = Options {
            outward,
            one_piece,
            ..Options::default()
        };
        let mut held = m.clone();
        let r = topology_change_guarded(&mut held, &end, &options).unwrap();
        assert!(r.held_all, "outward {outward}: {r:?}");
        assert_eq!(
            r.local.one_piece, one_piece,
            "held: the surface is as it was"
        );
        assert_eq!(held, m, "outward {outward}: a held frame changes nothing");
        let want = format!("specks cut off: 0 -> {specks}");
        assert!(r.refused.contains(&want), "{:?}", r.refused);
        let loose = format!("pieces cut loose: 1 -> {}", parts.len());
        assert_eq!(r.refused.contains(&loose), outward, "{:?}", r.refused);
        // The modeler says why in plain words: every reason has them.
        for why in &r.refused {
            assert_ne!(
                holey_topo::audit::in_plain_words(why),
                why.as_str(),
                "{why}"
            );
        }
    }
}

/// The same squeeze with [`Options::take_out_debris`] (what sculpting
/// sets for an inflate): the 33 specks are debris the guard takes out of
/// the result, so none is counted or cut loose, and what is left is
/// still a crumple, the rod glued along curves far smaller than its
/// edges, handles nobody can see: the frame is held for those.
#[test]
fn a_waist_squeezed_through_its_axis_is_held_for_its_handles_once_its_debris_is_out() {
    let m = rod();
    let end = squeezed(&m);
    let options = Options {
        outward: true,
        take_out_debris: true,
        ..Options::default()
    };
    let mut held = m.clone();
    let r = topology_change_guarded(&mut held, &end, &options).unwrap();
    assert!(r.held_all, "{r:?}");
    assert_eq!(held, m, "a held frame changes nothing");
    assert!(
        r.refused
            .iter()
            .any(|why| why.starts_with("tiny handles: 0 -> ")),
        "{:?}",
        r.refused
    );
    assert!(
        !r.refused
            .iter()
            .any(|why| why.starts_with("specks") || why.starts_with("pieces cut loose")),
        "the debris is taken out: {:?}",
        r.refused
    );
}

/// The engine's options for an inflate.
fn outward() -> Options {
    Options {
        outward: true,
        ..Options::default()
    }
}

/// `m`'s positions with those of the vertices in `which` mapped by `f`.
fn moved(
    m: &TriMesh,
    which: impl std::ops::RangeBounds<usize>,
    f: impl Fn(DVec3) -> DVec3,
) -> Vec<DVec3> {
    m.positions
        .iter()
        .enumerate()
        .map(|(i, &p)| if which.contains(&i) { f(p) } else { p })
        .collect()
}

/// Two boxes apart, the second pushed into the first: they join (one
/// piece, closed), with or without the outward flag: fewer pieces is
/// never worse.
#[test]
fn an_outward_motion_still_joins_parts() {
    let a = cuboid(DVec3::ZERO, DVec3::ONE);
    let b = cuboid(DVec3::new(1.5, 0.2, 0.3), DVec3::new(2.5, 0.9, 0.8));
    let m = join(&a, &b);
    let n = a.positions.len();
    let end = moved(&m, n.., |p| p - DVec3::new(0.8, 0.0, 0.0));
    let mut joined = m.clone();
    let r = topology_change_guarded(&mut joined, &end, &outward()).unwrap();
    assert!(r.refused.is_empty(), "{:?}", r.refused);
    assert_eq!(components(&joined), 1);
    assert!(closed_oriented(&joined));
    assert!(
        (volume(&joined) - (1.0 + 0.7 * 0.5 * 0.7)).abs() < 1e-12,
        "volume {}",
        volume(&joined)
    );
}

/// Pieces the surface already had are not new: a box hidden inside a
/// bigger one, and a box a hundredth wide beside it, stay as they were
/// while the big one is inflated into a third box and joins it.
#[test]
fn pieces_already_there_are_not_new() {
    let big = cuboid(DVec3::splat(-2.0), DVec3::splat(2.0));
    let small = cuboid(DVec3::splat(-0.5), DVec3::splat(0.5));
    let tiny = cuboid(DVec3::new(2.5, 0.0, 0.0), DVec3::new(2.51, 0.01, 0.01));
    let third = cuboid(DVec3::new(2.1, -0.5, -0.5), DVec3::new(3.0, 0.5, 0.5));
    let m = join(&join(&join(&big, &small), &tiny), &third);
    assert_eq!(components(&m), 4);
    let end = moved(&m, ..big.positions.len(), |p| p * 1.1);
    let mut grown = m.clone();
    let r = topology_change_guarded(&mut grown, &end, &outward()).unwrap();
    assert!(r.refused.is_empty(), "{:?}", r.refused);
    assert!(!r.local.positions_only, "the big box met the third");
    assert_eq!(components(&grown), 3);
    assert!(closed_oriented(&grown));
}
