//! What every remeshing scheme reads: a view of the input map with
//! per-face numbering, the labels of the edge pieces the schemes cut, and
//! the points and averages they place ([`Map`]); the writer that pairs
//! output corners into edges by these labels is [`super::build`].
//!
//! # Edge labels
//!
//! Every output corner names the edge that starts at it as a *label*
//! `2·edge + side`: the schemes number their output edges by arithmetic
//! (old edge `e`, the spoke of normal corner `k`, …) and say which of the
//! edge's two sides each corner is. The writer ([`Builder`](super::build::Builder)) puts corner `x` with label
//! `2e + s` into `edges[e][s]`; a slot filled twice or left empty is a bug
//! and an [`SubdivError::Internal`] error. Pairing by label needs no
//! search and no hashing, and it is indifferent to self-loops, multiple
//! edges and faces that visit a vertex or an edge twice, which a pairing
//! by vertex pairs could not tell apart.
//!
//! Within one scheme, the side of an output edge that agrees with the
//! input corner it comes from is written with the input corner's side
//! ([`Map::side`]), so the twin of a label is always `label ^ 1`.

use glam::DVec3;

use crate::SubdivError;
use crate::flat::{Flat, Kind, NONE};

/// The label of side `side` (0 or 1) of output edge `edge`.
#[inline]
pub(super) fn lab(edge: usize, side: u32) -> usize {
    (edge << 1) | side as usize
}

/// Counts of the input that decide the output sizes of every scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Stats {
    /// All vertices (point-sphere vertices included).
    pub v: usize,
    /// All edges.
    pub e: usize,
    /// Normal faces (neither holes nor point-spheres) and their corners.
    pub nf: usize,
    pub nc: usize,
    /// Hole faces and their corners.
    pub hf: usize,
    pub hc: usize,
    /// Point-spheres.
    pub ps: usize,
    /// Edges with a normal face on both sides.
    pub e_nn: usize,
    /// Corners of normal faces whose edge has a hole on its other side.
    pub b_sides: usize,
    /// Normal faces that are not triangles, and their corners.
    pub nt_faces: usize,
    pub nt_corners: usize,
}

impl Stats {
    /// The edges that do not have a normal face on both sides: what the
    /// schemes that delete the interior old edges keep (numbered by
    /// [`Map::kept_edges`]).
    pub fn kept_edge_count(&self) -> usize {
        self.e - self.e_nn
    }
}

/// A read-only view of one step's input: the flat map and, per face, its
/// kind and where its corners fall in the numberings the schemes use.
pub(super) struct Map<'a> {
    pub f: &'a Flat,
    pub kind: Vec<Kind>,
    /// Per face: normal corners before it (the rank of its first corner
    /// among normal corners, for normal faces).
    pub nbase: Vec<u32>,
    /// Per face: corners of normal and hole faces before it.
    pub abase: Vec<u32>,
    /// Per face: its rank among normal faces ([`NONE`] for the others).
    pub nrank: Vec<u32>,
    pub st: Stats,
}

impl<'a> Map<'a> {
    pub fn new(f: &'a Flat) -> Map<'a> {
        let nfaces = f.face_count();
        let mut kind = Vec::with_capacity(nfaces);
        let mut nbase = Vec::with_capacity(nfaces);
        let mut abase = Vec::with_capacity(nfaces);
        let mut nrank = Vec::with_capacity(nfaces);
        let mut st = Stats {
            v: f.pos.len(),
            e: f.edges.len(),
            ..Stats::default()
        };
        let (mut nc, mut ac) = (0u32, 0u32);
        for face in 0..nfaces {
            let k = f.kind(face);
            let n = (f.off[face + 1] - f.off[face]) as usize;
            kind.push(k);
            nbase.push(nc);
            abase.push(ac);
            match k {
                Kind::Normal => {
                    nrank.push(st.nf as u32);
                    st.nf += 1;
                    st.nc += n;
                    nc += n as u32;
                    ac += n as u32;
                    if n != 3 {
                        st.nt_faces += 1;
                        st.nt_corners += n;
                    }
                }
                Kind::Hole => {
                    nrank.push(NONE);
                    st.hf += 1;
                    st.hc += n;
                    ac += n as u32;
                }
                Kind::PointSphere => {
                    nrank.push(NONE);
                    st.ps += 1;
                }
            }
        }
        for &[a, b] in &f.edges {
            let na = kind[f.cf[a as usize] as usize] == Kind::Normal;
            let nb = kind[f.cf[b as usize] as usize] == Kind::Normal;
            if na && nb {
                st.e_nn += 1;
            } else if na || nb {
                st.b_sides += 1;
            }
        }
        Map {
            f,
            kind,
            nbase,
            abase,
            nrank,
            st,
        }
    }

    /// The corner range of face `face`.
    #[inline]
    pub fn range(&self, face: usize) -> (usize, usize) {
        (self.f.off[face] as usize, self.f.off[face + 1] as usize)
    }

    /// Which side of its edge corner `c` is (0 or 1).
    #[inline]
    pub fn side(&self, c: usize) -> u32 {
        u32::from(self.f.edges[self.f.cedge[c] as usize][1] as usize == c)
    }

    /// The edge that starts at corner `c`.
    #[inline]
    pub fn edge(&self, c: usize) -> usize {
        self.f.cedge[c] as usize
    }

    /// The kind of the face of corner `c`.
    #[inline]
    pub fn corner_kind(&self, c: usize) -> Kind {
        self.kind[self.f.cf[c] as usize]
    }

    /// The rank of normal corner `c` among all normal corners.
    #[inline]
    pub fn nidx(&self, c: usize) -> usize {
        let face = self.f.cf[c] as usize;
        self.nbase[face] as usize + c - self.f.off[face] as usize
    }

    /// The rank of corner `c` (of a normal or hole face) among all such
    /// corners.
    #[inline]
    pub fn aidx(&self, c: usize) -> usize {
        let face = self.f.cf[c] as usize;
        self.abase[face] as usize + c - self.f.off[face] as usize
    }

    /// The position of the vertex of corner `c`.
    #[inline]
    pub fn p(&self, c: usize) -> DVec3 {
        self.f.pos[self.f.cv[c] as usize]
    }

    /// True when edge `e` has a normal face on both sides.
    #[inline]
    pub fn interior(&self, e: usize) -> bool {
        let [a, b] = self.f.edges[e];
        self.corner_kind(a as usize) == Kind::Normal && self.corner_kind(b as usize) == Kind::Normal
    }

    /// The edges with a normal face on both sides, each as
    /// `(e, a, b, next(a), next(b))`: its index, its two corners (one per
    /// side) and the corners after them in their faces, which is what the
    /// schemes that build a face across every interior edge need.
    pub fn interior_edges(&self) -> impl Iterator<Item = (usize, usize, usize, usize, usize)> + '_ {
        self.f
            .edges
            .iter()
            .enumerate()
            .filter(|&(e, _)| self.interior(e))
            .map(|(e, &[a, b])| {
                let (a, b) = (a as usize, b as usize);
                (e, a, b, self.f.next(a), self.f.next(b))
            })
    }

    /// The normal faces, in face order.
    pub fn normal_faces(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.f.face_count()).filter(|&face| self.kind[face] == Kind::Normal)
    }

    /// The normal faces with their corner ranges, as `(face, lo, hi)`.
    pub fn normal_face_ranges(&self) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
        self.normal_faces().map(|face| {
            let (lo, hi) = self.range(face);
            (face, lo, hi)
        })
    }

    /// The corners `c` of face `lo..hi` whose edge is not interior, each
    /// as `(c, next c)`.
    pub fn boundary_corners(
        &self,
        lo: usize,
        hi: usize,
    ) -> impl Iterator<Item = (usize, usize)> + '_ {
        (lo..hi)
            .filter(|&c| !self.interior(self.edge(c)))
            .map(|c| (c, self.f.next(c)))
    }

    /// Per edge, its number among the edges that are not interior, in
    /// edge order (the old edges kept by the schemes that remove the
    /// interior ones; an interior edge's entry is meaningless).
    pub fn kept_edges(&self) -> Vec<u32> {
        let mut kept = vec![0u32; self.st.e];
        let mut next = 0u32;
        for (e, k) in kept.iter_mut().enumerate() {
            if !self.interior(e) {
                *k = next;
                next += 1;
            }
        }
        kept
    }

    /// The label of corner `c`'s own edge, kept under its number, on `c`'s
    /// side.
    #[inline]
    pub fn own(&self, c: usize) -> usize {
        lab(self.edge(c), self.side(c))
    }

    /// The label of a half of corner `c`'s edge `e` split at one point
    /// (halves `2e`, at the end of corner `edges[e][0]`, and `2e + 1`): the
    /// first along `c`'s walk, or with `second` the one after the point.
    #[inline]
    pub fn half(&self, c: usize, second: bool) -> usize {
        let (e, s) = (self.edge(c), self.side(c));
        let k = if second { 1 - s } else { s };
        lab(2 * e + k as usize, s)
    }

    /// The label of piece `k` (0, 1, 2 along `c`'s walk) of corner `c`'s
    /// edge `e` cut in three (pieces `3e`, `3e + 1`, `3e + 2` from the end of
    /// corner `edges[e][0]`).
    #[inline]
    pub fn third(&self, c: usize, k: usize) -> usize {
        let (e, s) = (self.edge(c), self.side(c));
        let along = if s == 0 { k } else { 2 - k };
        lab(3 * e + along, s)
    }

    /// Of the two points `2e`, `2e + 1` that cut corner `c`'s edge `e`
    /// (`2e + k` nearer the vertex of corner `edges[e][k]`), the one met
    /// first along `c`'s walk, or with `far` the one met second.
    #[inline]
    pub fn cut_point(&self, c: usize, far: bool) -> usize {
        let s = self.side(c) as usize;
        2 * self.edge(c) + if far { 1 - s } else { s }
    }

    /// Pushes corner `c`'s edge split at its point (output vertex `base +
    /// e`, halves as in [`Map::half`]) as the walk `v(c) → point`.
    pub fn push_halves(&self, c: usize, base: usize, walk: &mut Vec<(u32, usize)>) {
        walk.push((self.f.cv[c], self.half(c, false)));
        walk.push(((base + self.edge(c)) as u32, self.half(c, true)));
    }

    /// Pushes corner `c`'s edge cut in three (points `base +`
    /// [`Map::cut_point`], pieces as in [`Map::third`]) as the walk
    /// `v(c) → near → far`.
    pub fn push_thirds(&self, c: usize, base: usize, walk: &mut Vec<(u32, usize)>) {
        walk.extend_from_slice(&[
            (self.f.cv[c], self.third(c, 0)),
            ((base + self.cut_point(c, false)) as u32, self.third(c, 1)),
            ((base + self.cut_point(c, true)) as u32, self.third(c, 2)),
        ]);
    }

    /// The midpoint of edge `e`.
    #[inline]
    pub fn midpoint(&self, e: usize) -> DVec3 {
        let [a, b] = self.f.edges[e];
        0.5 * (self.p(a as usize) + self.p(b as usize))
    }

    /// The edges' midpoints, in edge order.
    pub fn midpoints(&self) -> impl Iterator<Item = DVec3> + '_ {
        (0..self.f.edges.len()).map(|e| self.midpoint(e))
    }

    /// Per edge `e`, in edge order, the points at `t` of its length from
    /// the vertex of corner `edges[e][0]`, then from the other end (the
    /// points `2e` and `2e + 1` of [`Map::cut_point`]).
    pub fn cut_points(&self, t: f64) -> impl Iterator<Item = DVec3> + '_ {
        self.f.edges.iter().flat_map(move |&[a, b]| {
            let (pa, pb) = (self.p(a as usize), self.p(b as usize));
            [pa + t * (pb - pa), pb + t * (pa - pb)]
        })
    }

    /// A position array with room for `cap`, starting with the input's
    /// positions (the output vertices of the schemes that keep them).
    pub fn kept_positions(&self, cap: usize) -> Vec<DVec3> {
        let mut pos = Vec::with_capacity(cap);
        pos.extend_from_slice(&self.f.pos);
        pos
    }

    /// Per input vertex: for an interior one (corners only in normal
    /// faces, at least one), the sum of `value(c)` over its corners `c` in
    /// face order and their number; `None` for the others, which the
    /// smoothing rules leave in place.
    pub fn interior_sums(&self, value: impl Fn(usize) -> DVec3) -> Vec<Option<(DVec3, f64)>> {
        let (n, h) = self.corner_counts();
        let mut sum = vec![DVec3::ZERO; self.f.pos.len()];
        for (_, lo, hi) in self.normal_face_ranges() {
            for c in lo..hi {
                sum[self.f.cv[c] as usize] += value(c);
            }
        }
        sum.into_iter()
            .zip(n.into_iter().zip(h))
            .map(|(s, (k, kh))| (kh == 0 && k > 0).then(|| (s, f64::from(k))))
            .collect()
    }

    /// The centroid of face `face`'s corners.
    pub fn centroid(&self, face: usize) -> DVec3 {
        let (lo, hi) = self.range(face);
        let sum: DVec3 = (lo..hi).map(|c| self.p(c)).sum();
        sum / (hi - lo) as f64
    }

    /// The unit normal of face `face` by Newell's method (the sum of the
    /// cross products of consecutive corners about the centroid, which is
    /// the area vector for planar faces and a robust average otherwise);
    /// zero for a face with no area.
    pub fn normal(&self, face: usize) -> DVec3 {
        self.newell(face).normalize_or_zero()
    }

    /// Twice the area vector of face `face` by Newell's method (see
    /// [`Map::normal`]).
    fn newell(&self, face: usize) -> DVec3 {
        let (lo, hi) = self.range(face);
        let c0 = self.centroid(face);
        let mut n = DVec3::ZERO;
        for c in lo..hi {
            let nc = if c + 1 == hi { lo } else { c + 1 };
            n += (self.p(c) - c0).cross(self.p(nc) - c0);
        }
        n
    }

    /// The size of face `face`: `√A`, `A` the length of its area vector
    /// (its area when planar), so the side of a square face, `0.66×` the
    /// side of an equilateral triangle. Extrusions measure their lengths
    /// in it, so they look the same on a mesh of any scale or density,
    /// and a sliver (little area, long edges) is barely raised.
    pub fn size(&self, face: usize) -> f64 {
        (self.newell(face).length() / 2.0).sqrt()
    }

    /// Calls `visit(v, ring)` for every vertex with corners outside
    /// point-spheres, `ring` its corners in the order of the backward
    /// rotation `c → twin(prev c)`: the order in which a face around `v`,
    /// oriented like the input's faces, meets them. An error when a
    /// rotation does not close over its vertex's corners.
    pub fn for_each_ring(&self, mut visit: impl FnMut(usize, &[usize])) -> Result<(), SubdivError> {
        let f = self.f;
        let nv = f.pos.len();
        let mut count = vec![0u32; nv];
        let mut start = vec![NONE; nv];
        for face in 0..f.face_count() {
            if self.kind[face] == Kind::PointSphere {
                continue;
            }
            let (lo, hi) = self.range(face);
            for c in lo..hi {
                let v = f.cv[c] as usize;
                count[v] += 1;
                if start[v] == NONE {
                    start[v] = c as u32;
                }
            }
        }
        let mut ring = Vec::new();
        for v in 0..nv {
            if start[v] == NONE {
                continue;
            }
            ring.clear();
            let first = start[v] as usize;
            let mut c = first;
            loop {
                ring.push(c);
                c = f.twin(f.prev(c));
                if c == first {
                    break;
                }
                if ring.len() >= count[v] as usize {
                    return Err(SubdivError::Internal(format!(
                        "the rotation at vertex {v} does not close after its {} corners",
                        count[v]
                    )));
                }
            }
            if ring.len() != count[v] as usize {
                return Err(SubdivError::Internal(format!(
                    "the rotation at vertex {v} covers {} of its {} corners",
                    ring.len(),
                    count[v]
                )));
            }
            visit(v, &ring);
        }
        Ok(())
    }

    /// Per vertex: (corners in normal faces, corners in holes).
    pub fn corner_counts(&self) -> (Vec<u32>, Vec<u32>) {
        let nv = self.f.pos.len();
        let (mut n, mut h) = (vec![0u32; nv], vec![0u32; nv]);
        for face in 0..self.f.face_count() {
            let (lo, hi) = self.range(face);
            let target = match self.kind[face] {
                Kind::Normal => &mut n,
                Kind::Hole => &mut h,
                Kind::PointSphere => continue,
            };
            for c in lo..hi {
                target[self.f.cv[c] as usize] += 1;
            }
        }
        (n, h)
    }
}

/// TopMod's tension mask of a polygon `s` (its corner points, edge
/// midpoints or twisted edge points), written to `out`:
///
/// ```text
/// outᵢ = α sᵢ + (1 − α)/(3n − 5) Σⱼ≠ᵢ (3 + 2 cos(2π(i − j)/n)) sⱼ
/// ```
///
/// The weights sum to 1 for every `n ≥ 2` (`Σⱼ≠ᵢ cos = −1`), and with
/// `α = 9/16` on a quad they are Doo–Sabin's. A monogon's point is its own.
/// With `C = Σ cos θⱼ sⱼ` and `S = Σ sin θⱼ sⱼ` the inner sum is
/// `3(Σ − sᵢ) + 2(cos θᵢ C + sin θᵢ S − sᵢ)`, so a face costs O(n).
pub(super) fn tension_mask(s: &[DVec3], alpha: impl Fn(usize) -> f64, out: &mut [DVec3]) {
    let n = s.len();
    if n == 1 {
        out[0] = s[0];
        return;
    }
    let a = alpha(n);
    let nf = n as f64;
    let (mut sum, mut cs, mut sn) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for (j, q) in s.iter().enumerate() {
        let (si, co) = (std::f64::consts::TAU * j as f64 / nf).sin_cos();
        sum += *q;
        cs += co * *q;
        sn += si * *q;
    }
    let w = (1.0 - a) / (3.0 * nf - 5.0);
    for (i, q) in s.iter().enumerate() {
        let (si, co) = (std::f64::consts::TAU * i as f64 / nf).sin_cos();
        let others = 3.0 * (sum - *q) + 2.0 * (co * cs + si * sn - *q);
        out[i] = a * *q + w * others;
    }
}

/// Moves every vertex that has a sum in `sums` (those of
/// [`Map::interior_sums`]) to `rule(p, sum, k)`, `p` its position, `sum`
/// and `k` its sum and corner count; the others stay. The smoothing
/// schemes differ only in `rule`.
pub(super) fn move_interior(
    pos: &mut [DVec3],
    sums: Vec<Option<(DVec3, f64)>>,
    rule: impl Fn(DVec3, DVec3, f64) -> DVec3,
) {
    for (p, sum) in pos.iter_mut().zip(sums) {
        if let Some((sum, k)) = sum {
            *p = rule(*p, sum, k);
        }
    }
}

/// Honeycomb's and root-4's α: `1/√2 − 1/4 + 5/(4n)` (TopMod).
pub(super) fn honeycomb_alpha(n: usize) -> f64 {
    std::f64::consts::FRAC_1_SQRT_2 - 0.25 + 5.0 / (4.0 * n as f64)
}

/// Scales `points` about their centroid by `scale`.
pub(super) fn scale_about_centroid(points: &mut [DVec3], scale: f64) {
    if points.is_empty() {
        return;
    }
    let c = points.iter().sum::<DVec3>() / points.len() as f64;
    for p in points {
        *p = c + scale * (*p - c);
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use holey_testkit::Rng;

    use super::tension_mask;

    #[test]
    fn the_tension_mask_matches_its_definition_and_is_affine() {
        let mut rng = Rng::new(41);
        for n in 1..=12 {
            let s: Vec<DVec3> = (0..n)
                .map(|_| DVec3::new(rng.unit(), rng.unit(), rng.unit()))
                .collect();
            let alpha = rng.range(0.3, 1.0);
            let mut out = vec![DVec3::ZERO; n];
            tension_mask(&s, |_| alpha, &mut out);
            for (i, got) in out.iter().enumerate() {
                let direct: DVec3 = if n == 1 {
                    s[0]
                } else {
                    (0..n)
                        .map(|j| {
                            let w = if i == j {
                                alpha
                            } else {
                                let t = std::f64::consts::TAU * (i as f64 - j as f64) / n as f64;
                                (1.0 - alpha) * (3.0 + 2.0 * t.cos()) / (3.0 * n as f64 - 5.0)
                            };
                            w * s[j]
                        })
                        .sum()
                };
                assert!((*got - direct).length() < 1e-12, "n = {n}, i = {i}");
            }
            // Affine: a translated polygon gives translated points.
            let moved: Vec<DVec3> = s.iter().map(|p| *p + DVec3::splat(3.0)).collect();
            let mut out2 = vec![DVec3::ZERO; n];
            tension_mask(&moved, |_| alpha, &mut out2);
            for (a, b) in out.iter().zip(&out2) {
                assert!((*b - *a - DVec3::splat(3.0)).length() < 1e-12);
            }
        }
        // α = 9/16 on a quad: Doo–Sabin's 9, 3, 1, 3 (/16).
        let q = [DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE];
        let mut out = [DVec3::ZERO; 4];
        tension_mask(&q, |_| 9.0 / 16.0, &mut out);
        let ds = (9.0 * DVec3::X + 3.0 * DVec3::Y + DVec3::Z + 3.0 * DVec3::ONE) / 16.0;
        assert!((out[0] - ds).length() < 1e-15);
    }
}
