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

use super::map::{Budget, Builder, Map, Sizes, lab};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// Segment labels of corner `c`'s edge: (first, middle, last) along its
/// walk.
fn thirds(m: &Map, c: usize) -> [usize; 3] {
    let (e, s) = (m.edge(c), m.side(c));
    let su = s as usize;
    [
        lab(3 * e + 2 * su, s),
        lab(3 * e + 1, s),
        lab(3 * e + 2 - 2 * su, s),
    ]
}

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
    let mut pos = Vec::with_capacity(sizes.v);
    pos.extend_from_slice(&src.pos);
    for &[a, b] in &src.edges {
        let (pa, pb) = (m.p(a as usize), m.p(b as usize));
        pos.push((2.0 * pa + pb) / 3.0);
        pos.push((pa + 2.0 * pb) / 3.0);
    }
    let nv = st.v;
    let zbase = nv + 2 * st.e;
    for face in 0..src.face_count() {
        if m.kind[face] != Kind::Normal {
            continue;
        }
        let z = m.centroid(face);
        pos.push(z);
        if offset != 0.0 {
            let (lo, hi) = m.range(face);
            for c in lo..hi {
                let a = nv + 2 * m.edge(c) + m.side(c) as usize;
                let moved = pos[a] + offset * (z - pos[a]);
                pos[a] = moved;
            }
        }
    }
    let near = |c: usize| (nv + 2 * m.edge(c) + m.side(c) as usize) as u32;
    let far = |c: usize| (nv + 2 * m.edge(c) + 1 - m.side(c) as usize) as u32;
    let spoke = |c: usize, side: u32| lab(3 * st.e + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    let mut hole = Vec::new();
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        match m.kind[face] {
            Kind::PointSphere => b.point_sphere(src.cv[lo], src.hole[face]),
            Kind::Hole => {
                hole.clear();
                for c in lo..hi {
                    let [first, middle, last] = thirds(&m, c);
                    hole.extend_from_slice(&[
                        (src.cv[c], first),
                        (near(c), middle),
                        (far(c), last),
                    ]);
                }
                b.face(true, &hole);
            }
            Kind::Normal => {
                let z = (zbase + m.nrank[face] as usize) as u32;
                for c in lo..hi {
                    let d = src.next(c);
                    let [_, middle, last] = thirds(&m, c);
                    b.face(
                        false,
                        &[
                            (z, spoke(c, 0)),
                            (near(c), middle),
                            (far(c), last),
                            (src.cv[d], thirds(&m, d)[0]),
                            (near(d), spoke(d, 1)),
                        ],
                    );
                }
            }
        }
    }
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
    let mut pos = Vec::with_capacity(sizes.v);
    pos.extend_from_slice(&src.pos);
    pos.extend(
        src.edges
            .iter()
            .map(|&[a, b]| 0.5 * (m.p(a as usize) + m.p(b as usize))),
    );
    let nv = st.v;
    let mid = |c: usize| (nv + m.edge(c)) as u32;
    for face in 0..src.face_count() {
        if m.kind[face] != Kind::Normal {
            continue;
        }
        let (lo, hi) = m.range(face);
        let centre = m.centroid(face);
        // The midpoints' centroid is the corners' centroid.
        for c in lo..hi {
            let p = pos[mid(c) as usize];
            pos.push(centre + scale * (p - centre));
        }
    }
    let inner = |c: usize| (nv + st.e + m.nidx(c)) as u32;
    let half = |c: usize, second: bool| {
        let (e, s) = (m.edge(c), m.side(c));
        let k = if second { 1 - s } else { s };
        lab(2 * e + k as usize, s)
    };
    let l = |c: usize, side: u32| lab(2 * st.e + m.nidx(c), side);
    let q = |c: usize, side: u32| lab(2 * st.e + st.nc + m.nidx(c), side);
    let mut b = Builder::new(pos, sizes);
    let mut poly = Vec::new();
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        match m.kind[face] {
            Kind::PointSphere => b.point_sphere(src.cv[lo], src.hole[face]),
            Kind::Hole => {
                poly.clear();
                for c in lo..hi {
                    poly.push((src.cv[c], half(c, false)));
                    poly.push((mid(c), half(c, true)));
                }
                b.face(true, &poly);
            }
            Kind::Normal => {
                poly.clear();
                poly.extend((lo..hi).map(|c| (inner(c), l(src.next(c), 0))));
                b.face(false, &poly);
                for c in lo..hi {
                    let p = src.prev(c);
                    b.face(
                        false,
                        &[
                            (mid(p), half(p, true)),
                            (src.cv[c], half(c, false)),
                            (mid(c), q(c, 0)),
                            (inner(c), l(c, 1)),
                            (inner(p), q(p, 1)),
                        ],
                    );
                }
            }
        }
    }
    b.finish()
}
