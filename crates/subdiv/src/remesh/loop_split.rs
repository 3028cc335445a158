//! The midpoint split that Loop subdivision (Loop 1987), TopMod's
//! loop-style remeshing and its fractal scheme share: every edge split at
//! a new point, every corner cut off by an edge between the points of its
//! two edges. An `n`-gon becomes `n` corner triangles and the `n`-gon of
//! its edge points, which the fractal scheme fans from a raised centre.
//!
//! Edge `e` becomes the halves `2e` (at the end of corner `edges[e][0]`)
//! and `2e + 1`. Corner `c` on side `s` of `e` walks `v(c) → mₑ` along half
//! `2e + s` and `mₑ → v(next c)` along half `2e + 1 − s`, both on side `s`.
//! The cut edge of normal corner `k` runs from the point of `c`'s edge to
//! the point of the edge before `c` on side 0 (inside the corner triangle).

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab, move_interior};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// Where Loop's connectivity puts the points.
#[derive(Clone, Copy, Debug)]
pub(super) enum Rule {
    /// Loop's masks (see [`RemeshScheme::Loop`](super::RemeshScheme::Loop)).
    Loop,
    /// Edge midpoints; interior old vertices moved to
    /// `ℓ p + (1 − ℓ) avg(midpoints of their edges)`.
    Style(f64),
}

/// Writes the corner triangles of every normal face and the refined
/// holes; `middle(b, face, lo, hi)` writes what goes inside the midpoint
/// polygon. Edge points are vertices `V + e`; cut edge of normal corner
/// `k` is edge `2E + k`.
fn corners_and_holes(
    m: &Map,
    b: &mut Builder,
    mut middle: impl FnMut(&mut Builder, usize, usize, usize),
) {
    let src = m.f;
    let (nv, ne) = (m.st.v as u32, m.st.e);
    let ep = |c: usize| nv + m.edge(c) as u32;
    let cut = |c: usize, side: u32| lab(2 * ne + m.nidx(c), side);
    b.kept_faces(
        m,
        |c, hole| m.push_halves(c, nv as usize, hole),
        |b, face, lo, hi| {
            for c in lo..hi {
                let p = src.prev(c);
                b.face(&[
                    (src.cv[c], m.half(c, false)),
                    (ep(c), cut(c, 0)),
                    (ep(p), m.half(p, true)),
                ]);
            }
            middle(b, face, lo, hi);
        },
    );
}

/// One level of Loop's connectivity with `rule`'s positions: the input's
/// vertices, then the edge points in edge order.
pub(super) fn step(src: &Flat, budget: &Budget, rule: Rule) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.e,
        e: 2 * st.e + st.nc,
        f: st.nf + st.nc + st.hf + st.ps,
        c: 4 * st.nc + 2 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let pos = match rule {
        Rule::Loop => loop_positions(&m, sizes.v),
        Rule::Style(length) => style_positions(&m, sizes.v, length),
    };
    let mut b = Builder::new(pos, sizes);
    let (nv, ne) = (st.v as u32, st.e);
    corners_and_holes(&m, &mut b, |b, _, lo, hi| {
        // The midpoint polygon walks mⱼ → mⱼ₊₁ along the cut edge of
        // corner j+1, on the side away from its corner triangle.
        b.walk(false, lo..hi, |c, w| {
            w.push((nv + m.edge(c) as u32, lab(2 * ne + m.nidx(src.next(c)), 1)));
        });
    });
    b.finish()
}

/// Loop's rules (see [`RemeshScheme::Loop`](super::RemeshScheme::Loop)).
fn loop_positions(m: &Map, nv: usize) -> Vec<DVec3> {
    let src = m.f;
    let (n, h) = m.corner_counts();
    let mut sum = vec![DVec3::ZERO; src.pos.len()];
    let mut bsum = vec![DVec3::ZERO; src.pos.len()];
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        match m.kind[face] {
            Kind::Normal => {
                for c in lo..hi {
                    sum[src.cv[c] as usize] += m.p(src.next(c));
                }
            }
            Kind::Hole => {
                for c in lo..hi {
                    bsum[src.cv[c] as usize] += m.p(src.prev(c)) + m.p(src.next(c));
                }
            }
            Kind::PointSphere => {}
        }
    }
    let mut pos = Vec::with_capacity(nv);
    for (v, &p) in src.pos.iter().enumerate() {
        let (k, kh) = (n[v], h[v]);
        pos.push(if kh == 0 && k > 0 {
            let kf = f64::from(k);
            let t = 0.375 + 0.25 * (std::f64::consts::TAU / kf).cos();
            let beta = (0.625 - t * t) / kf;
            (1.0 - kf * beta) * p + beta * sum[v]
        } else if kh == 1 && k + kh >= 3 {
            (bsum[v] + 6.0 * p) / 8.0
        } else {
            p
        });
    }
    for (e, &[a, b]) in src.edges.iter().enumerate() {
        let (a, b) = (a as usize, b as usize);
        let (p0, p1) = (m.p(a), m.p(b));
        pos.push(if m.interior(e) {
            // On each side, the corner before the edge and the one two
            // after its start: a triangle's opposite vertex, twice.
            let wing = |c: usize| m.p(src.prev(c)) + m.p(src.next(src.next(c)));
            0.375 * (p0 + p1) + (wing(a) + wing(b)) / 16.0
        } else {
            0.5 * (p0 + p1)
        });
    }
    pos
}

/// TopMod's loop-style positions: midpoints, and each interior old vertex
/// moved to `ℓ p + (1 − ℓ) avg(midpoints of its edges)`, one midpoint per
/// corner (a self-loop counts twice). Boundary vertices stay, so open
/// boundaries keep their shape.
fn style_positions(m: &Map, nv: usize, length: f64) -> Vec<DVec3> {
    let mut pos = m.kept_positions(nv);
    if length != 1.0 {
        let sums = m.interior_sums(|c| m.midpoint(m.edge(c)));
        move_interior(&mut pos, sums, |p, sum, k| {
            length * p + (1.0 - length) * sum / k
        });
    }
    pos.extend(m.midpoints());
    pos
}

/// TopMod's fractal scheme: Loop's connectivity with edge midpoints, the
/// midpoint polygon of each face fanned from its apex. Output vertices:
/// the input's, the midpoints by edge, the apexes by normal face; the
/// spoke from the apex to the midpoint of normal corner `k`'s edge is
/// edge `2E + C + k`, running midpoint → apex on side 0.
pub(super) fn fractal(src: &Flat, budget: &Budget, offset: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.e + st.nf,
        e: 2 * st.e + 2 * st.nc,
        f: 2 * st.nc + st.hf + st.ps,
        c: 6 * st.nc + 2 * st.hc + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = style_positions(&m, sizes.v, 1.0);
    pos.extend(m.normal_faces().map(|face| apex(&m, face, offset)));
    let mut b = Builder::new(pos, sizes);
    let (nv, ne, nc) = (st.v as u32, st.e, st.nc);
    let apex_base = nv + ne as u32;
    corners_and_holes(&m, &mut b, |b, face, lo, hi| {
        let z = apex_base + m.nrank[face];
        let spoke = |c: usize, side: u32| lab(2 * ne + nc + m.nidx(c), side);
        for c in lo..hi {
            let d = if c + 1 == hi { lo } else { c + 1 };
            b.face(&[
                (nv + m.edge(c) as u32, lab(2 * ne + m.nidx(d), 1)),
                (nv + m.edge(d) as u32, spoke(d, 0)),
                (z, spoke(c, 1)),
            ]);
        }
    });
    b.finish()
}

/// The fractal apex: the centroid raised along the unit normal by
/// `offset · √(max(0, |m₀ − m₁|² − (|m₀ − x|/2)²))` (TopMod's rule, see
/// [`RemeshScheme::Fractal`](super::RemeshScheme::Fractal)). In the walk
/// `v₀ m₀ v₁ m₁ …` of the midpoint-refined face, `x` is `n` steps after
/// `m₀`: the midpoint `m_{n/2}` for even `n`, the vertex `v_{(n+1)/2}` for
/// odd `n`.
fn apex(m: &Map, face: usize, offset: f64) -> DVec3 {
    let (lo, hi) = m.range(face);
    let n = hi - lo;
    let mid = |j: usize| {
        let c = lo + j % n;
        0.5 * (m.p(c) + m.p(m.f.next(c)))
    };
    let m0 = mid(0);
    let m1 = mid(1);
    let x = if n % 2 == 0 {
        mid(n / 2)
    } else {
        m.p(lo + n.div_ceil(2) % n)
    };
    let half = (m0 - x).length() / 2.0;
    let d = ((m0 - m1).length_squared() - half * half).max(0.0).sqrt();
    m.centroid(face) + offset * d * m.normal(face)
}
