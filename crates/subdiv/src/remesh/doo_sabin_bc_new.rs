//! Doo–Sabin BC New (TopMod's `dooSabinSubdivideBCNew`, Bei & Cansin,
//! "Doo Sabin BC New" in its remeshing menu). TopMod's steps:
//!
//! 1. every edge split at its midpoint (an `n`-gon becomes a `2n`-gon);
//! 2. every old face Doo–Sabin-extruded (`extrudeFaceDS`) at distance 0
//!    with scale `sf`: a copy of the `2n`-gon whose points are Doo–Sabin's
//!    mask of its corners, joined to it corner by corner by quads;
//! 3. the edges of the split mesh deleted, merging the two quads beside
//!    each half-edge into a hexagon;
//! 4. at each midpoint (now of valence 2) its two edges replaced by one
//!    edge between its two neighbours, so the midpoint goes and the two
//!    hexagons at it become pentagons;
//! 5. each old vertex moved to `length · p + (1 − length) · q̄`, `q̄` the
//!    average of the corners that follow it in its faces.
//!
//! Here the result is written in one pass. Per normal corner `c`
//! (normal-corner rank `k`) the copy has two points: `P(c)`, the copy of
//! the vertex of `c`, and `Q(c)`, the copy of the midpoint of `c`'s edge.
//! Output edges: the spoke `S(c)` from `v(c)` to `P(c)` (edge `k`, side 0
//! runs `v → P`); the copy's rims `P(c) → Q(c)` (edge `nc + 2k`) and
//! `Q(c) → P(next c)` (edge `nc + 2k + 1`), side 0 in the copy; then every
//! old edge `e` as edge `3nc + e`: across an edge between two normal faces
//! it is the edge `Q(a)–Q(b)` that step 4 inserts, otherwise the old edge
//! itself, kept.
//!
//! Faces: the copy `[P(c), Q(c)]…` of every normal face; across an edge
//! with corners `a` (in `f`) and `b` (in `g`) between two normal faces the
//! two pentagons `[Q(a), P(a), v(a), P(next b), Q(b)]` and
//! `[Q(b), P(b), v(b), P(next a), Q(a)]`; across an edge next to a hole the
//! one pentagon `[Q(a), P(a), v(a), v(next a), P(next a)]` of its normal
//! side, the old edge kept, so holes keep their corners and their shape
//! (TopMod has no holes: a hole's "copy" would sit on its boundary). The
//! corner after `v(a)` in each of its pentagons is one of its points
//! `P`, each once, so step 5's `q̄` is the average of the points `P(c)` of
//! the corners `c` at the vertex. Vertices on a boundary stay.

use glam::DVec3;

use super::DooSabinBcNewParams;
use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab, move_interior, scale_about_centroid, tension_mask};
use crate::SubdivError;
use crate::flat::Flat;

/// Doo–Sabin's own weight of a corner of an `n`-gon, `1/4 + 5/(4n)`
/// (Doo & Sabin 1978; TopMod's `extrudeFaceDS`): with it, TopMod's
/// tension mask ([`tension_mask`], the others `(3 + 2cos(2π(i−j)/n))/(4n)`)
/// is Doo–Sabin's mask.
fn doo_sabin_alpha(n: usize) -> f64 {
    0.25 + 5.0 / (4.0 * n as f64)
}

/// One level. Output vertices: the input's (old vertices moved by
/// `length`), then `P(c)`, `Q(c)` by normal corner (`V + 2k`,
/// `V + 2k + 1`). `scale` as in TopMod: `|scale|`, no scaling for 0 or 1.
///
/// Counts: `V' = V + 2C`, `E' = E + 3C`, `F' = F + 2E_nn + B` (`C` the
/// normal corners, `E_nn` the edges between two normal faces, `B` the
/// normal sides of edges next to a hole); on a closed mesh
/// `V + 2C, 4C − E, F + 2E` (`C = 2E`).
pub(super) fn step(
    src: &Flat,
    budget: &Budget,
    params: DooSabinBcNewParams,
) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let nc = st.nc;
    let sizes = Sizes {
        v: st.v + 2 * nc,
        e: 3 * nc + st.e,
        f: st.nf + 2 * st.e_nn + st.b_sides + st.hf + st.ps,
        c: 2 * nc + 10 * st.e_nn + 5 * st.b_sides + st.hc + st.ps,
    };
    budget.check(sizes)?;
    let pos = positions(&m, sizes.v, params);
    let v = |c: usize| src.cv[c];
    let p = |c: usize| (st.v + 2 * m.nidx(c)) as u32;
    let q = |c: usize| (st.v + 2 * m.nidx(c) + 1) as u32;
    let spoke = |c: usize, side: u32| lab(m.nidx(c), side);
    let rim = |c: usize, second: usize, side: u32| lab(nc + 2 * m.nidx(c) + second, side);
    let old = |c: usize, side: u32| lab(3 * nc + m.edge(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| hole.push((v(c), old(c, m.side(c)))),
        |b, _, lo, hi| {
            b.walk(false, lo..hi, |c, w| {
                w.push((p(c), rim(c, 0, 0)));
                w.push((q(c), rim(c, 1, 0)));
            });
            for (c, d) in m.boundary_corners(lo, hi) {
                b.face(&[
                    (q(c), rim(c, 0, 1)),
                    (p(c), spoke(c, 1)),
                    (v(c), old(c, m.side(c))),
                    (v(d), spoke(d, 0)),
                    (p(d), rim(c, 1, 1)),
                ]);
            }
        },
    );
    for (_, a, bb, na, nb) in m.interior_edges() {
        for (x, y, ny) in [(a, bb, nb), (bb, a, na)] {
            b.face(&[
                (q(x), rim(x, 0, 1)),
                (p(x), spoke(x, 1)),
                (v(x), spoke(ny, 0)),
                (p(ny), rim(y, 1, 1)),
                (q(y), old(y, m.side(y))),
            ]);
        }
    }
    b.finish()
}

/// The copies: per normal face, Doo–Sabin's mask of its midpoint-split
/// polygon `[v(c₀), m(c₀), v(c₁), m(c₁), …]` (`m(c)` the midpoint of
/// `c`'s edge), scaled about its centroid by `|scale|` unless that is 0
/// or 1; then every interior old vertex moved to
/// `length · p + (1 − length) · avg P(c)` over its corners.
fn positions(m: &Map, nv: usize, params: DooSabinBcNewParams) -> Vec<DVec3> {
    let src = m.f;
    let mut pos = m.kept_positions(nv);
    let (scale, length) = (params.scale.abs(), params.length);
    let mut pts = Vec::new();
    let mut out = Vec::new();
    for (_, lo, hi) in m.normal_face_ranges() {
        pts.clear();
        for c in lo..hi {
            pts.push(m.p(c));
            pts.push(m.midpoint(m.edge(c)));
        }
        out.clear();
        out.resize(pts.len(), DVec3::ZERO);
        tension_mask(&pts, doo_sabin_alpha, &mut out);
        if scale != 0.0 && scale != 1.0 {
            scale_about_centroid(&mut out, scale);
        }
        pos.extend_from_slice(&out);
    }
    if length != 1.0 {
        let sums = m.interior_sums(|c| pos[src.pos.len() + 2 * m.nidx(c)]);
        move_interior(&mut pos, sums, |p, sum, k| {
            length * p + (1.0 - length) * sum / k
        });
    }
    pos
}
