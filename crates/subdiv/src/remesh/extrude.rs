//! The extrusion schemes: global extrude (every face extruded once along
//! its normal; TopMod lists the scheme but never implemented it, so this is
//! its face extrusion applied to all faces at once) and TopMod's dome
//! (`domeSubdivide`: edges cut in quarters, every face extruded seven times
//! by its Doo–Sabin extrusion `extrudeFaceDS`).
//!
//! Lengths are relative: a face moves `length × √A` along its unit normal,
//! `A` its area ([`Map::size`]), so the result looks the same on a mesh of
//! any scale or density (a square extruded by 1 becomes a cube) and a
//! sliver is barely raised.
//!
//! An extrusion of a face with ring `R₀` (its corners) adds a ring `R₁`
//! of as many vertices, the side quads `[R₀(i), R₀(i+1), R₁(i+1), R₁(i)]`
//! and moves the face to `R₁`. Per ring `r ≥ 1` of a face, the ring's edge
//! from `R_r(i)` to `R_r(i+1)` runs on side 0 in the quad above it (or the
//! final face) and the vertical edge from `R_{r−1}(i)` to `R_r(i)` on side
//! 0 in the quad on its left.

use glam::DVec3;

use super::Extrusion;
use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab, scale_about_centroid};
use crate::SubdivError;
use crate::doo_sabin::corner_points;
use crate::flat::Flat;

/// Global extrude. Output vertices: the input's, then ring 1 by normal
/// corner: `centroid + scale (v − centroid) + length √A n̂` (`A` the
/// face's area). Edges: the old
/// ones, then the ring's edges `L`, then the verticals `W`, by normal
/// corner.
pub(super) fn global(src: &Flat, budget: &Budget, lift: Extrusion) -> Result<Flat, SubdivError> {
    let Extrusion { length, scale } = lift;
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.nc,
        e: st.e + 2 * st.nc,
        f: st.nf + st.nc + st.hf + st.ps,
        c: 5 * st.nc + st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    for (face, lo, hi) in m.normal_face_ranges() {
        let (z, n) = (m.centroid(face), m.normal(face));
        let lift = length * m.size(face) * n;
        pos.extend((lo..hi).map(|c| z + scale * (m.p(c) - z) + lift));
    }
    let (nv, ne, nc) = (st.v, st.e, st.nc);
    let top = |c: usize| (nv + m.nidx(c)) as u32;
    let ring = |c: usize, side: u32| lab(ne + m.nidx(c), side);
    let up = |c: usize, side: u32| lab(ne + nc + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| hole.push((src.cv[c], m.own(c))),
        |b, _, lo, hi| {
            for c in lo..hi {
                let d = src.next(c);
                b.face(&[
                    (src.cv[c], m.own(c)),
                    (src.cv[d], up(d, 0)),
                    (top(d), ring(c, 1)),
                    (top(c), up(c, 1)),
                ]);
            }
            b.walk(false, lo..hi, |c, w| w.push((top(c), ring(c, 0))));
        },
    );
    b.finish()
}

/// The dome's seven extrusions: lengths and scales (TopMod's constants).
const DOME: [(f64, f64); 7] = [
    (0.0, 1.6),
    (0.3, 1.7),
    (0.18, 1.6),
    (0.1, 1.4),
    (0.05, 1.2),
    (0.025, 1.1),
    (0.01, 0.01),
];

/// Rings per face in the dome.
const RINGS: usize = DOME.len();

/// The dome. Output vertices: the input's, the quarter points `V + 3e +
/// k − 1` (`k/4` of the way from the vertex of corner `edges[e][0]`),
/// then per normal face its seven rings of `4n` vertices. Edges: the
/// quarters `4e + k` (`k` from corner `edges[e][0]`'s end), then per
/// normal face its ring edges and its verticals, ring by ring.
pub(super) fn dome(src: &Flat, budget: &Budget, lift: Extrusion) -> Result<Flat, SubdivError> {
    let Extrusion { length, scale } = lift;
    let m = Map::new(src);
    let st = m.st;
    let per = 4 * RINGS; // ring vertices per input corner
    let sizes = Sizes {
        v: st.v + 3 * st.e + per * st.nc,
        e: 4 * st.e + 2 * per * st.nc,
        f: st.nf + per * st.nc + st.hf + st.ps,
        c: 4 * per * st.nc + 4 * st.nc + 4 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let (nv, ne) = (st.v, st.e);
    let mut pos = m.kept_positions(sizes.v);
    for &[a, b] in &src.edges {
        let (pa, pb) = (m.p(a as usize), m.p(b as usize));
        pos.extend((1..4).map(|k| pa + 0.25 * k as f64 * (pb - pa)));
    }
    // Ring 0 of a face: (vertex, label of its edge to the next) along the
    // walk, 4 per corner.
    let ring0 = |c: usize, out: &mut Vec<(u32, usize)>| {
        let (e, s) = (m.edge(c), m.side(c));
        out.push((src.cv[c], lab(4 * e + if s == 0 { 0 } else { 3 }, s)));
        for i in 1..4 {
            let k = if s == 0 { i } else { 4 - i };
            let along = if s == 0 { i } else { 3 - i };
            out.push(((nv + 3 * e + k - 1) as u32, lab(4 * e + along, s)));
        }
    };
    let mut r0 = Vec::new();
    let mut pts = Vec::new();
    let mut next = Vec::new();
    let mut trig = Vec::new();
    for (face, lo, hi) in m.normal_face_ranges() {
        r0.clear();
        for c in lo..hi {
            ring0(c, &mut r0);
        }
        pts.clear();
        pts.extend(r0.iter().map(|&(v, _)| pos[v as usize]));
        // The lengths are in units of the face's size.
        let n = m.normal(face) * (length * m.size(face));
        for &(d, s) in &DOME {
            next.clear();
            next.resize(pts.len(), DVec3::ZERO);
            corner_points(&pts, &mut next, &mut trig);
            for q in &mut next {
                *q += d * n;
            }
            // TopMod scales by |s|, and not at all when that is 0 or 1.
            let s = (s * scale).abs();
            if s != 0.0 && s != 1.0 {
                scale_about_centroid(&mut next, s);
            }
            pos.extend_from_slice(&next);
            std::mem::swap(&mut pts, &mut next);
        }
    }
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(&m, ring0, |b, face, lo, hi| {
        r0.clear();
        for c in lo..hi {
            ring0(c, &mut r0);
        }
        let w = r0.len();
        let k = m.nbase[face] as usize;
        let vbase = nv + 3 * ne + per * k;
        let ebase = 4 * ne + 2 * per * k;
        let vert = |r: usize, i: usize| -> u32 {
            if r == 0 {
                r0[i % w].0
            } else {
                (vbase + (r - 1) * w + i % w) as u32
            }
        };
        let ring_edge = |r: usize, i: usize, side: u32| lab(ebase + (r - 1) * w + i % w, side);
        let up = |r: usize, i: usize, side: u32| lab(ebase + RINGS * w + (r - 1) * w + i % w, side);
        for r in 1..=RINGS {
            for (i, &(_, edge0)) in r0.iter().enumerate() {
                let below = if r == 1 {
                    edge0
                } else {
                    ring_edge(r - 1, i, 0)
                };
                b.face(&[
                    (vert(r - 1, i), below),
                    (vert(r - 1, i + 1), up(r, i + 1, 0)),
                    (vert(r, i + 1), ring_edge(r, i, 1)),
                    (vert(r, i), up(r, i, 1)),
                ]);
            }
        }
        b.walk(false, 0..w, |i, out| {
            out.push((vert(RINGS, i), ring_edge(RINGS, i, 0)))
        });
    });
    b.finish()
}
