//! √3 subdivision (Kobbelt 2000) and TopMod's "dual vertex truncation"
//! (`sqrt3Subdivide`), which share the connectivity: stellate every face,
//! then flip every old edge between two faces so that it joins their
//! centres.
//!
//! Edge `(a, b)` between faces `f ∋ a` and `g ∋ b`, with centres `z_f`,
//! `z_g`, becomes the triangles `[v(a), z_g, z_f]` and `[z_g, v(b), z_f]`
//! around the flipped edge, which keeps the old edge's number (side 0 runs
//! `z_g → z_f`). Spoke `k` (normal corner `k` at `v`) runs `v → z` on side 0.
//! An edge next to a hole is not flipped: its normal side keeps the
//! stellation triangle and the hole keeps its corners.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab, move_interior};
use super::stellate::hole_side_triangles;
use crate::SubdivError;
use crate::flat::Flat;

/// One level. Output vertices: the input's, then the centres in
/// normal-face order; edges: the old ones (flipped or kept), then one spoke
/// per normal corner. With `smooth`, interior old vertices move by
/// Kobbelt's rule; otherwise they stay (TopMod's dual vertex truncation).
pub(super) fn step(src: &Flat, budget: &Budget, smooth: bool) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.nf,
        e: st.e + st.nc,
        f: 2 * st.e_nn + st.b_sides + st.hf + st.ps,
        c: 6 * st.e_nn + 3 * st.b_sides + st.hc + st.ps,
    };
    budget.check(sizes)?;
    let pos = positions(&m, sizes.v, smooth);
    let zc = |c: usize| st.v as u32 + m.nrank[src.cf[c] as usize];
    let spoke = |c: usize, side: u32| lab(st.e + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    hole_side_triangles(&mut b, &m, |c| m.own(c), zc, spoke);
    for (e, a, bb, na, nb) in m.interior_edges() {
        b.face(&[
            (src.cv[a], spoke(nb, 0)),
            (zc(bb), lab(e, 0)),
            (zc(a), spoke(a, 1)),
        ]);
        b.face(&[
            (zc(bb), spoke(bb, 1)),
            (src.cv[bb], spoke(na, 0)),
            (zc(a), lab(e, 1)),
        ]);
    }
    b.finish()
}

/// The input's positions (smoothed by Kobbelt's rule with `smooth`: an
/// interior vertex with `n` corners, all in normal faces, moves to
/// `(1 − αₙ)p + αₙ/n Σ p(next c)`, `αₙ = (4 − 2 cos(2π/n))/9`; boundary
/// vertices stay), then the face centroids.
fn positions(m: &Map, nv: usize, smooth: bool) -> Vec<DVec3> {
    let src = m.f;
    let mut pos = m.kept_positions(nv);
    if smooth {
        let sums = m.interior_sums(|c| m.p(src.next(c)));
        move_interior(&mut pos, sums, |p, sum, k| {
            let alpha = (4.0 - 2.0 * (std::f64::consts::TAU / k).cos()) / 9.0;
            (1.0 - alpha) * p + alpha * sum / k
        });
    }
    pos.extend(m.normal_faces().map(|face| m.centroid(face)));
    pos
}
