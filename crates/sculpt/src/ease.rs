//! The brush eased off the vertices its stroke had to hold.
//!
//! When the guard holds a frame (`holey_topo::guard`), every vertex that
//! frame moved stays where it was, and the stroke keeps holding them in
//! its later frames: the contact that made the frame worse is still
//! there, and retrying it every frame would only hold every frame. The
//! brush goes on moving their neighbours, so the held vertices were left
//! standing out of the surface the brush moved on, a spike or a pit one
//! edge wide at each (the rim of a deflate's groove over the bunny's
//! haunch, where the inflate before had fused a fold).
//!
//! Instead, every other vertex the frame moves goes the share
//! `1 − w(d)` of its way, `d` its distance from the nearest held vertex
//! and `w` the brush's smooth falloff over `width`
//! ([`Falloff::Smooth`]: `(1 − t²)²`, `t = d / width`): 0 at a held
//! vertex, 1 from `width` on, with no crease at either end. Around a held
//! patch the surface ramps from where it was held to where the brush
//! takes it over `width`, a shoulder rather than a spike. Neighbours of held vertices move little, so they
//! do not drive into the contact the hold is avoiding either.

use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

use crate::brush::Falloff;

/// Of the brush's radius: the width of the ramp around held vertices.
/// Half the radius keeps the ramp within the brush's own falloff.
pub(crate) const EASE_SHARE: f64 = 0.5;

/// `end` with the motion of every vertex that moves and is not `held`
/// scaled by `1 − w(d)` (module docs); `start` holds the positions at
/// the frame's start (the held vertices stay there). Unchanged when no
/// vertex is held or `width` is not a positive number.
pub(crate) fn eased_near_held(
    start: &[DVec3],
    end: &[DVec3],
    held: &[bool],
    width: f64,
) -> Vec<DVec3> {
    let mut eased = end.to_vec();
    if !(width > 0.0 && width.is_finite()) {
        return eased;
    }
    let cell = |p: DVec3| (p / width).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<DVec3>> = HashMap::default();
    for (v, _) in held.iter().enumerate().filter(|(_, h)| **h) {
        if let Some(&p) = start.get(v) {
            grid.entry(cell(p)).or_default().push(p);
        }
    }
    if grid.is_empty() {
        return eased;
    }
    for (v, (&p, q)) in start.iter().zip(eased.iter_mut()).enumerate() {
        if p == *q || held.get(v).copied().unwrap_or(false) {
            continue;
        }
        let [x, y, z] = cell(p);
        let mut nearest = width;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for h in grid.get(&[x + dx, y + dy, z + dz]).into_iter().flatten() {
                        nearest = nearest.min(p.distance(*h));
                    }
                }
            }
        }
        *q = p + (*q - p) * (1.0 - Falloff::Smooth.weight(nearest, width));
    }
    eased
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row of vertices at x = 0, 0.25, ..., 2 all lifted by 1, the one
    /// at 0 held: each other one goes 1 − (1 − x²)² of the way, and from
    /// x = 1 on all the way.
    #[test]
    fn motion_ramps_up_by_the_smooth_falloff_of_the_distance_to_a_held_vertex() {
        let start: Vec<DVec3> = (0..9).map(|i| DVec3::X * (0.25 * f64::from(i))).collect();
        let end: Vec<DVec3> = start.iter().map(|p| *p + DVec3::Z).collect();
        let mut held = vec![false; 9];
        held[0] = true;
        let eased = eased_near_held(&start, &end, &held, 1.0);
        // The held vertex is the guard's to keep; easing leaves its target.
        assert_eq!(eased[0], end[0]);
        for i in 1..9 {
            let t = (0.25 * i as f64).min(1.0);
            let rise = eased[i].z;
            let share = 1.0 - (1.0 - t * t) * (1.0 - t * t);
            assert!((rise - share).abs() < 1e-12, "{i}: {rise}");
            assert_eq!((eased[i].x, eased[i].y), (start[i].x, start[i].y));
        }
    }

    #[test]
    fn nothing_held_or_no_width_leaves_the_motion_alone() {
        let start = vec![DVec3::ZERO, DVec3::X];
        let end = vec![DVec3::Z, DVec3::X + DVec3::Z];
        assert_eq!(eased_near_held(&start, &end, &[false, false], 1.0), end);
        for width in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(eased_near_held(&start, &end, &[true, false], width), end);
        }
    }
}
