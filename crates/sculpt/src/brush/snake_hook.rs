//! Snake hook: the part of the surface under the brush follows the
//! pointer, a small step at a time, and stretches into a tentacle behind
//! it. Pulled into another part of the surface, the tentacle's tip meets
//! it and the engine fuses the two (a tip pressed into a body makes a
//! handle); that is what a grab, whose displacement is fixed at the pick,
//! cannot do without folding (see below).
//!
//! # The displacement field
//!
//! One step moves the brush centre from `c` to `c + δ`. A vertex `x` of
//! the *hooked patch* moves by
//!
//! ```text
//! u(x) = s · f(|x − c|) · δ,   f(d) = 1 (d ≤ r/2),  (1 − u²)² with u = (d − r/2)/(r/2) (d < r),  0 beyond,
//! ```
//!
//! with `s` the strength ([`super::falloff::plateau`] is `f`). Every
//! other vertex stays put. The plateau keeps the inner half of the hooked
//! cap rigid: with a falloff that is 1 only at the centre, every vertex
//! but the one at the centre falls behind a little each step, and a long
//! pull tapers to a needle thinner than the edges, which folds into a
//! ribbon at the first bend; with the plateau the tentacle keeps a
//! cross-section of at least the plateau's. The hooked patch is the connected piece of the surface
//! inside the ball of radius `r` around `c` that holds the surface point
//! nearest `c`: vertices inside the ball joined by edges with both ends
//! inside (and coincident copies joined, so a soup or an unwelded seam
//! moves as one surface). Its rim lies where `f` is 0, so the surface
//! stays continuous; other sheets that enter the ball (the body the hook
//! is pulled into) do not move, and so the tip can collide with them.
//!
//! # Why steps of at most a quarter of the radius
//!
//! `|f′|` is largest at `d = r/2 + r/(2√3)`, where it is
//! `16 / (3√3 r) ≈ 3.08/r`, so `u` is Lipschitz with constant
//! `L = 3.08 · s|δ| / r`. For `L < 1`
//! the map `x ↦ x + u(x)` is one to one (`|φ(x) − φ(y)| ≥ (1 − L)|x − y|`),
//! and so is every straight-line motion to it: the hooked patch cannot
//! fold over itself within a step, whatever the path. A grab applies the
//! whole drag `D` at once with the falloff frozen at the pick, and folds
//! (inverting the surface, which the engine then deletes as swept) as
//! soon as `|D| > 0.65 r`. [`steps`] cuts a segment of the pointer's path
//! into steps with `s|δ| ≤ r/8` (`L ≤ 0.385`), and each step finds the
//! patch again on the surface the last one left: the flow of the
//! pointer's velocity field, a composition of one-to-one maps.

use glam::DVec3;
use holey_mesh::UnionFind;
use holey_topo::TriMesh;

use super::falloff::plateau;
use super::{closest_on_triangle, coincident, touched};

/// The longest step, as a share of the radius, that one evaluation of
/// the snake hook may take (see the module documentation).
pub const MAX_STEP_SHARE: f64 = 0.125;

/// How many steps the pull of `strength × (to − from)` takes so that no
/// step is longer than [`MAX_STEP_SHARE`] of `radius`: at least 1, and 1
/// for a zero or non-finite pull.
pub fn steps(from: DVec3, to: DVec3, radius: f64, strength: f64) -> usize {
    let pull = strength.abs() * from.distance(to);
    let per_step = MAX_STEP_SHARE * radius;
    let n = (pull / per_step).ceil();
    if n.is_finite() && n >= 1.0 {
        // A pull of more than 2³² radii is no stroke anyone drew.
        n.min(f64::from(u32::MAX)) as usize
    } else {
        1
    }
}

/// One step of the snake hook from `from` to `to`: the positions after
/// the hooked patch moved by `strength · falloff(|x − from|) · (to −
/// from)` (module documentation). The caller keeps each step short
/// ([`steps`]). Unchanged positions when no triangle has a corner within
/// `radius` of `from` (the hook has let go of the surface).
pub fn snake_hook(
    mesh: &TriMesh,
    from: DVec3,
    to: DVec3,
    radius: f64,
    strength: f64,
) -> Vec<DVec3> {
    let mut out = mesh.positions.clone();
    let patch = hooked_patch(mesh, from, radius);
    let pull = strength * (to - from);
    for v in patch {
        let p = mesh.positions[v as usize];
        out[v as usize] = p + plateau(p.distance(from), radius) * pull;
    }
    out
}

/// The vertices of the hooked patch around `centre` (module
/// documentation), in increasing order.
pub fn hooked_patch(mesh: &TriMesh, centre: DVec3, radius: f64) -> Vec<u32> {
    let inside = touched(mesh, centre, radius);
    if inside.is_empty() {
        return inside;
    }
    let mut slot = vec![u32::MAX; mesh.positions.len()];
    for (i, &v) in inside.iter().enumerate() {
        slot[v as usize] = i as u32;
    }
    let mut sets = UnionFind::new(inside.len());
    // Coincident copies are one point of the surface.
    for (i, &c) in coincident(mesh, &inside).iter().enumerate() {
        sets.union(i as u32, c);
    }
    // The seed: the triangle with a corner inside whose surface comes
    // nearest the centre (the first such on ties).
    let mut seed: Option<(f64, [u32; 3])> = None;
    for t in &mesh.triangles {
        let s = t.map(|v| slot[v as usize]);
        if s.iter().all(|&x| x == u32::MAX) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (s[k], s[(k + 1) % 3]);
            if a != u32::MAX && b != u32::MAX {
                sets.union(a, b);
            }
        }
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        let d = closest_on_triangle(centre, a, b, c).distance(centre);
        if seed.is_none_or(|(best, _)| d < best) {
            seed = Some((d, s));
        }
    }
    let Some((_, seed)) = seed else {
        return Vec::new();
    };
    let roots: Vec<u32> = seed
        .iter()
        .filter(|&&x| x != u32::MAX)
        .map(|&x| sets.find(x))
        .collect();
    inside
        .iter()
        .enumerate()
        .filter(|&(i, _)| roots.contains(&sets.find(i as u32)))
        .map(|(_, &v)| v)
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Two parallel unit squares (two triangles each), `gap` apart in z.
    fn two_sheets(gap: f64) -> TriMesh {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for z in [0.0, gap] {
            let b = positions.len() as u32;
            positions.extend([
                DVec3::new(-1.0, -1.0, z),
                DVec3::new(1.0, -1.0, z),
                DVec3::new(1.0, 1.0, z),
                DVec3::new(-1.0, 1.0, z),
                DVec3::new(0.0, 0.0, z),
            ]);
            for k in 0..4 {
                triangles.push([b + k, b + (k + 1) % 4, b + 4]);
            }
        }
        TriMesh {
            positions,
            triangles,
        }
    }

    #[test]
    fn only_the_hooked_sheet_moves() {
        // Both sheets' centres lie inside the ball; the lower one is
        // nearer the centre, so it alone is hooked.
        let m = two_sheets(0.3);
        let from = DVec3::new(0.0, 0.0, 0.1);
        let to = from + DVec3::new(0.0, 0.0, 0.2);
        let out = snake_hook(&m, from, to, 0.5, 1.0);
        let lift = plateau(0.1, 0.5) * 0.2;
        assert!((out[4].z - lift).abs() < 1e-15, "{}", out[4].z);
        assert_eq!(out[9], m.positions[9], "the other sheet stays put");
        // Corners are outside the ball.
        assert_eq!(&out[..4], &m.positions[..4]);
        assert_eq!(hooked_patch(&m, from, 0.5), vec![4]);
        // Nearer the upper sheet, the upper sheet is hooked.
        assert_eq!(hooked_patch(&m, DVec3::new(0.0, 0.0, 0.25), 0.5), vec![9]);
    }

    #[test]
    fn coincident_copies_move_together() {
        // A soup: two triangles sharing an edge by position only.
        let m = TriMesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [3, 5, 4]],
        };
        let from = DVec3::new(0.2, 0.2, 0.0);
        let out = snake_hook(&m, from, from + DVec3::Z * 0.1, 3.0, 1.0);
        assert_eq!(out[1], out[3]);
        assert_eq!(out[2], out[4]);
        assert!(
            out[5].z > 0.0,
            "the far triangle is hooked through the seam"
        );
    }

    #[test]
    fn no_surface_in_reach_moves_nothing() {
        let m = two_sheets(0.3);
        let far = DVec3::new(0.0, 0.0, 5.0);
        assert_eq!(snake_hook(&m, far, far + DVec3::X, 0.5, 1.0), m.positions);
        assert!(hooked_patch(&m, far, 0.5).is_empty());
    }

    #[test]
    fn steps_bound_the_pull() {
        let o = DVec3::ZERO;
        assert_eq!(steps(o, DVec3::X, 1.0, 1.0), 8);
        assert_eq!(steps(o, DVec3::X * 0.125, 1.0, 1.0), 1);
        assert_eq!(steps(o, DVec3::X, 1.0, 0.5), 4);
        assert_eq!(steps(o, o, 1.0, 1.0), 1);
        assert_eq!(steps(o, DVec3::X, 0.0, 1.0), 1, "no radius, no steps");
        assert_eq!(steps(o, DVec3::splat(f64::NAN), 1.0, 1.0), 1);
    }

    /// The step bound's promise: with `s|δ| ≤ r/8` the map is one to one,
    /// checked on a dense grid of points against the Lipschitz bound
    /// `|φ(x) − φ(y)| ≥ (1 − L)|x − y|`, `L = 16/(3√3) · s|δ|/r`.
    #[test]
    fn a_bounded_step_does_not_fold_space() {
        let r = 1.0;
        let delta = DVec3::new(0.125, 0.0, 0.0);
        let lipschitz = 16.0 / (3.0 * 3f64.sqrt()) * delta.length() / r;
        let phi = |x: DVec3| x + plateau(x.length(), r) * delta;
        let h = 0.05;
        for i in -24..24 {
            let x = DVec3::new(f64::from(i) * h, 0.1, 0.0);
            let y = x + DVec3::new(h, 0.0, 0.0);
            let stretched = phi(y).distance(phi(x));
            assert!(
                stretched >= (1.0 - lipschitz) * h - 1e-12,
                "at x = {x}: {stretched} < {}",
                (1.0 - lipschitz) * h
            );
        }
        // And a step of a whole radius does fold: the 1-D map loses
        // monotonicity ahead of the centre.
        let big = DVec3::new(1.0, 0.0, 0.0);
        let phi_big = |x: f64| x + plateau(x.abs(), r) * big.x;
        let folds = (0..200).any(|i| {
            let x = f64::from(i) * 0.005;
            phi_big(x + 0.005) < phi_big(x)
        });
        assert!(folds);
    }
}
