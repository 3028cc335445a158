//! Pentagonalization (TopMod's `pentagonalSubdivide`) and pentagon
//! preserving remeshing (`pentagonalSubdivide2`).
//!
//! Pentagonalization cuts every edge in thirds: edge `e` gets the points
//! `T(e, k)` a third of the way from the vertex of its corner
//! `edges[e][k]`, and the segments `3e` (at corner `edges[e][0]`'s end),
//! `3e + 1` (the middle), `3e + 2`. Corner `c` on side `s` walks
//! `v(c) → a_c = T(e, s) → b_c = T(e, 1 − s) → v(next c)`. A centre per
//! face is joined to every `a_c` by a spoke (normal corner `k`: edge
//! `3E + k`, side 0 running centre → `a_c`), which makes corner `cⱼ`'s
//! pentagon `[z, a_j, b_j, v_{j+1}, a_{j+1}]`. Every third point is
//! joined to exactly one centre (the one on the side where it comes
//! first), so the new vertices all have valence 3.
//!
//! Pentagon preserving splits every edge at its midpoint (halves as in
//! [`super::loop_split`]) and puts inside each face a copy through its
//! midpoints, scaled about their centroid; joining each midpoint to its
//! copy makes an `n`-gon into the copy and `n` pentagons
//! `[m(prev c), v(c), m(c), I(c), I(prev c)]`.

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab};
use crate::SubdivError;
use crate::flat::Flat;

/// Pentagonalization. Output vertices: the input's, `T(e, k)` as
/// `V + 2e + k`, the centres by normal face. The third point joined to a
/// centre moves `offset` of the way towards it.
pub(super) fn pentagonalize(src: &Flat, budget: &Budget, offset: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + 2 * st.e + st.nf,
        e: 3 * st.e + st.nc,
        f: st.nc + st.hf + st.ps,
        c: 5 * st.nc + 3 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    for &[a, b] in &src.edges {
        let (pa, pb) = (m.p(a as usize), m.p(b as usize));
        pos.push((2.0 * pa + pb) / 3.0);
        pos.push((pa + 2.0 * pb) / 3.0);
    }
    let nv = st.v;
    let zbase = nv + 2 * st.e;
    let near = |c: usize| (nv + m.cut_point(c, false)) as u32;
    let far = |c: usize| (nv + m.cut_point(c, true)) as u32;
    for face in m.normal_faces() {
        let z = m.centroid(face);
        pos.push(z);
        if offset != 0.0 {
            let (lo, hi) = m.range(face);
            for c in lo..hi {
                let a = near(c) as usize;
                let moved = pos[a] + offset * (z - pos[a]);
                pos[a] = moved;
            }
        }
    }
    let spoke = |c: usize, side: u32| lab(3 * st.e + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| m.push_thirds(c, nv, hole),
        |b, face, lo, hi| {
            let z = (zbase + m.nrank[face] as usize) as u32;
            for c in lo..hi {
                let d = src.next(c);
                b.face(&[
                    (z, spoke(c, 0)),
                    (near(c), m.third(c, 1)),
                    (far(c), m.third(c, 2)),
                    (src.cv[d], m.third(d, 0)),
                    (near(d), spoke(d, 1)),
                ]);
            }
        },
    );
    b.finish()
}

/// Pentagon preserving. Output vertices: the input's, the midpoints by
/// edge, the copies `I(c)` by normal corner. Edges: the halves, then the
/// copy's edge `L(c)` from `I(prev c)` to `I(c)`, then `Q(c)` from the
/// midpoint of `c`'s edge to `I(c)` (side 0 in that direction).
pub(super) fn preserve(src: &Flat, budget: &Budget, scale: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.e + st.nc,
        e: 2 * st.e + 2 * st.nc,
        f: st.nf + st.nc + st.hf + st.ps,
        c: 6 * st.nc + 2 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(m.midpoints());
    let nv = st.v;
    let mid = |c: usize| (nv + m.edge(c)) as u32;
    for (face, lo, hi) in m.normal_face_ranges() {
        let centre = m.centroid(face);
        // The midpoints' centroid is the corners' centroid.
        for c in lo..hi {
            let p = pos[mid(c) as usize];
            pos.push(centre + scale * (p - centre));
        }
    }
    let inner = |c: usize| (nv + st.e + m.nidx(c)) as u32;
    let l = |c: usize, side: u32| lab(2 * st.e + m.nidx(c), side);
    let q = |c: usize, side: u32| lab(2 * st.e + st.nc + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    b.kept_faces(
        &m,
        |c, hole| m.push_halves(c, nv, hole),
        |b, _, lo, hi| {
            b.walk(false, lo..hi, |c, w| w.push((inner(c), l(src.next(c), 0))));
            for c in lo..hi {
                let p = src.prev(c);
                b.face(&[
                    (mid(p), m.half(p, true)),
                    (src.cv[c], m.half(c, false)),
                    (mid(c), q(c, 0)),
                    (inner(c), l(c, 1)),
                    (inner(p), q(p, 1)),
                ]);
            }
        },
    );
    b.finish()
}
