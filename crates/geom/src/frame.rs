//! A frame in which triangles' bounding boxes are tight: the broad phase
//! of exact intersection on CAD meshes that were turned.
//!
//! Why: a CAD part is mostly flat faces, triangulated into long slivers
//! (an extruded outline's caps are thousands of triangles, each as long as
//! the part is wide). Along the axes it was drawn in, a cap triangle's box
//! is flat and a sliver's is thin; turned by any rotation (the EMBER
//! benchmark turns every part), each box spans the part in all three axes
//! and overlaps nearly every other. Thingi10K 79741 has 293k pairs of
//! overlapping triangle boxes as drawn and 15.5M turned; in the frame
//! [`BoxFrame::of_triangles`] finds, 282k.
//!
//! The frame: its third axis is the dominant face normal (the area-weighted
//! peak of the normals, sign-free), its first the dominant direction of
//! the edges across that normal (the peak of their projections on its
//! plane, weighted by projected length squared: the slivers' long sides),
//! its second their cross product. A mesh with no dominant normal (a scan,
//! a sphere: under [`MIN_SHARE`] of the area in one bin) keeps the
//! identity, at the cost of one pass over its normals.
//!
//! **Boxes stay conservative.** A box is only a filter, so the map need
//! not be exact, only its rounding bounded: for a row `a` with
//! `|a_j| ≤ 1 + 2u` and a point `p`, the computed `fl(a·p)` is within
//! `γ₃ Σ|a_j||p_j| < 4u (|x|+|y|+|z|)` of `a·p` (Higham, *Accuracy and
//! Stability*, §3.1), `u = 2⁻⁵³`. Each box is widened by twice that bound
//! of its own corners, so if two triangles share a point `x`, the exact
//! image `a·x` lies in both widened boxes: they overlap. Boxes in the
//! identity frame are the exact boxes, unwidened.

use crate::bvh::Aabb;
use glam::DVec3;
use rayon::prelude::*;

/// The smallest share of the total area the peak normal bin must hold for
/// a frame other than the identity: a sphere's finest bin holds about
/// 1/2500 of it, an extruded part's caps most of it.
pub const MIN_SHARE: f64 = 0.02;

/// Bins per unit of each normal coordinate (a bin spans about 3.6°).
const NORMAL_BINS: i32 = 16;
/// Side of the normal histogram's cube of bins.
const NORMAL_SIDE: usize = 2 * NORMAL_BINS as usize + 1;
/// Bins over the half-turn of undirected edge directions (0.7° each).
const EDGE_BINS: usize = 256;
/// Triangles per histogram task.
const CHUNK: usize = 1 << 15;
/// Widening of a turned box per unit of `|x|+|y|+|z|` of its corners: 8u,
/// twice the rounding bound of a dot product with a unit row.
const SLACK: f64 = 8.0 * f64::EPSILON / 2.0;
/// Coordinates beyond this keep the identity (the widening must not
/// overflow).
const HUGE: f64 = 1e300;

/// The axes boxes are measured along: the identity, or three orthonormal
/// rows (up to rounding) found by [`BoxFrame::of_triangles`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxFrame {
    axes: Option<[DVec3; 3]>,
}

impl BoxFrame {
    /// The world's own axes: boxes are the exact bounding boxes.
    pub const IDENTITY: BoxFrame = BoxFrame { axes: None };

    /// Whether boxes are measured along the world's axes.
    pub fn is_identity(&self) -> bool {
        self.axes.is_none()
    }

    /// The rows of the frame (`None` for the identity).
    pub fn axes(&self) -> Option<[DVec3; 3]> {
        self.axes
    }

    /// The frame of one or more triangle sets (each positions with its
    /// triangles; out-of-range corners and zero-area triangles are
    /// skipped). Pairs across the sets are best found in the frame of
    /// all of them together: the frame of either alone can leave the
    /// other's slivers turned (measured on the EMBER pairs).
    ///
    /// ```
    /// use glam::DVec3;
    /// use holey_geom::frame::BoxFrame;
    /// // A flat square turned about the x axis: its normal is the frame's
    /// // third axis.
    /// let (c, s) = (0.6, 0.8);
    /// let p = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    ///     .map(|[x, y]| DVec3::new(x, c * y, s * y));
    /// let frame = BoxFrame::of_triangles(&[(&p, &[[0, 1, 2], [0, 2, 3]])]);
    /// let axes = frame.axes().unwrap();
    /// assert!((axes[2].dot(DVec3::new(0.0, -s, c)).abs() - 1.0).abs() < 1e-12);
    /// ```
    pub fn of_triangles(parts: &[(&[DVec3], &[[u32; 3]])]) -> BoxFrame {
        let mut reach = 0.0f64;
        for (positions, _) in parts {
            reach = reach.max(
                positions
                    .par_iter()
                    .map(|p| p.abs().element_sum())
                    .reduce(|| 0.0, f64::max),
            );
        }
        if reach.is_nan() || reach >= HUGE {
            return BoxFrame::IDENTITY;
        }
        let Some(normal) = dominant_normal(parts) else {
            return BoxFrame::IDENTITY;
        };
        let across = dominant_edge(parts, normal).unwrap_or_else(|| any_across(normal));
        let first = (across - normal * across.dot(normal)).normalize();
        let second = normal.cross(first).normalize();
        let axes = [first, second, normal];
        // Already along the world's axes (an unturned part): the exact
        // boxes are as tight and need no widening.
        let aligned = axes
            .iter()
            .all(|a| a.abs().max_element() > 1.0 - 1e-12 && a.is_finite());
        if aligned || !axes.iter().all(|a| a.is_finite()) {
            return BoxFrame::IDENTITY;
        }
        BoxFrame { axes: Some(axes) }
    }

    /// The box, in this frame, of the triangle with corners `p`: exact in
    /// the identity, otherwise widened to contain the exact image of every
    /// point of the triangle (see the module's note).
    #[inline]
    pub fn triangle_box(&self, p: [DVec3; 3]) -> Aabb {
        match &self.axes {
            None => Aabb::from_points(&p),
            Some([a, b, c]) => {
                let image = |q: DVec3| DVec3::new(a.dot(q), b.dot(q), c.dot(q));
                let (q0, q1, q2) = (image(p[0]), image(p[1]), image(p[2]));
                let reach = p[0]
                    .abs()
                    .element_sum()
                    .max(p[1].abs().element_sum())
                    .max(p[2].abs().element_sum());
                let widen = DVec3::splat(SLACK * reach);
                Aabb::new(q0.min(q1).min(q2) - widen, q0.max(q1).max(q2) + widen)
            }
        }
    }
}

impl BoxFrame {
    /// A point from `start` along the frame's first axis (+x in the
    /// identity) whose exact image lies past `bounds`, a box in this
    /// frame holding boxes measured by [`BoxFrame::triangle_box`]: so it
    /// lies outside every triangle boxed within, and outside the solid
    /// they bound (the far end of a containment ray). The exact image is
    /// within `4u(|x|+|y|+|z|)` of the computed one (the module's note),
    /// so the computed one must clear `bounds` by twice that. `None`
    /// when the coordinates are too large for such a point.
    pub fn beyond(&self, start: DVec3, bounds: &Aabb) -> Option<DVec3> {
        let span = (bounds.max.x - bounds.min.x)
            .max(bounds.max.x.abs())
            .max(1.0);
        let Some([first, ..]) = self.axes else {
            let far_x = bounds.max.x.max(start.x) + span;
            return far_x
                .is_finite()
                .then_some(DVec3::new(far_x, start.y, start.z));
        };
        let mut step = (bounds.max.x - first.dot(start)).max(0.0) + span;
        // Rounding can leave the first tries short only by a few ulps of
        // the coordinates; doubling the step clears them.
        for _ in 0..8 {
            let end = start + first * step;
            if !end.is_finite() {
                return None;
            }
            if first.dot(end) - SLACK * end.abs().element_sum() > bounds.max.x {
                return Some(end);
            }
            step *= 2.0;
        }
        None
    }
}

/// A triangle's normal `n = (b − a) × (c − a)` made sign-free (its
/// largest coordinate positive), whose length is the doubled area; `None`
/// without area or corners.
#[inline]
fn unsigned_normal(positions: &[DVec3], t: &[u32; 3]) -> Option<DVec3> {
    let [a, b, c] = [
        positions.get(t[0] as usize)?,
        positions.get(t[1] as usize)?,
        positions.get(t[2] as usize)?,
    ];
    let n = (*b - *a).cross(*c - *a);
    let m = n.abs();
    let big = if m.x >= m.y && m.x >= m.z {
        n.x
    } else if m.y >= m.z {
        n.y
    } else {
        n.z
    };
    // Zero, NaN or infinite: no direction.
    if !(big != 0.0 && n.length_squared().is_finite()) {
        return None;
    }
    Some(if big < 0.0 { -n } else { n })
}

/// No histogram bin: the triangle has no normal.
const NO_BIN: u16 = u16::MAX;

/// The histogram bin of a sign-free normal `n` of length `w`: each
/// coordinate of the unit normal rounded to the nearest sixteenth (ties
/// up; the offset keeps the value positive, so truncation is the floor
/// and no library rounding call is needed).
#[inline]
fn normal_bin(n: DVec3, w: f64) -> u16 {
    let scale = NORMAL_BINS as f64 / w;
    let k = |x: f64| ((x * scale + (NORMAL_BINS as f64 + 0.5)) as usize).min(NORMAL_SIDE - 1);
    ((k(n.x) * NORMAL_SIDE + k(n.y)) * NORMAL_SIDE + k(n.z)) as u16
}

/// The area-weighted mean of the normals in the fullest bin, when that bin
/// holds at least [`MIN_SHARE`] of the area. One pass bins every triangle
/// (kept, two bytes each); the mean then reads only the peak's triangles.
fn dominant_normal(parts: &[(&[DVec3], &[[u32; 3]])]) -> Option<DVec3> {
    // A dense histogram is 287 KB to clear and scan, more than binning a
    // small mesh (a fresh process's pages: a tenth of `holey selfint` on
    // 1,116 triangles); there the bins are summed from a sorted list,
    // in the same order, to the same sums.
    let (binned, area) = if parts.iter().all(|(_, t)| t.len() <= CHUNK) {
        sparse_normal_bins(parts)
    } else {
        dense_normal_bins(parts)
    };
    let total: f64 = area.iter().map(|&(_, a)| a).sum();
    let &(peak, most) = area.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
    if !(total > 0.0 && most >= MIN_SHARE * total) {
        return None;
    }
    let mut sum = DVec3::ZERO;
    for ((positions, triangles), of) in parts.iter().zip(&binned) {
        sum += triangles
            .par_iter()
            .zip(of)
            .filter(|(_, b)| **b == peak)
            .filter_map(|(t, _)| unsigned_normal(positions, t))
            .reduce(|| DVec3::ZERO, |a, b| a + b);
    }
    let n = sum.normalize_or_zero();
    (n != DVec3::ZERO).then_some(n)
}

/// Each part's triangles' bins, and the area of every bin in bin order
/// (empty bins may be left out).
type NormalBins = (Vec<Vec<u16>>, Vec<(u16, f64)>);

/// A triangle's normal bin ([`NO_BIN`] without a normal) and the length
/// of its normal (twice its area).
#[inline]
fn bin_of(positions: &[DVec3], t: &[u32; 3]) -> (u16, f64) {
    match unsigned_normal(positions, t) {
        Some(n) => {
            let w = n.length();
            (normal_bin(n, w), w)
        }
        None => (NO_BIN, 0.0),
    }
}

/// [`NormalBins`] through a dense histogram per [`CHUNK`] of triangles,
/// in parallel.
fn dense_normal_bins(parts: &[(&[DVec3], &[[u32; 3]])]) -> NormalBins {
    let bins = NORMAL_SIDE * NORMAL_SIDE * NORMAL_SIDE;
    let mut area = vec![0.0f64; bins];
    let mut binned: Vec<Vec<u16>> = Vec::with_capacity(parts.len());
    for (positions, triangles) in parts {
        let partial: Vec<(Vec<u16>, Vec<f64>)> = triangles
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut h = vec![0.0f64; bins];
                let of = chunk
                    .iter()
                    .map(|t| {
                        let (bin, w) = bin_of(positions, t);
                        if bin != NO_BIN {
                            h[bin as usize] += w;
                        }
                        bin
                    })
                    .collect();
                (of, h)
            })
            .collect();
        let mut of = Vec::with_capacity(triangles.len());
        for (b, h) in partial {
            of.extend(b);
            for (sum, x) in area.iter_mut().zip(h) {
                *sum += x;
            }
        }
        binned.push(of);
    }
    let area = (0..bins as u16).zip(area).collect();
    (binned, area)
}

/// [`NormalBins`] of parts of at most [`CHUNK`] triangles each, without a
/// dense histogram: each part's (bin, area) list sorted by bin (stably:
/// in triangle order within a bin) and summed run by run from zero, as
/// the dense histogram sums them, then the parts added in order.
fn sparse_normal_bins(parts: &[(&[DVec3], &[[u32; 3]])]) -> NormalBins {
    let mut area: std::collections::BTreeMap<u16, f64> = Default::default();
    let mut binned: Vec<Vec<u16>> = Vec::with_capacity(parts.len());
    for (positions, triangles) in parts {
        let mut of = Vec::with_capacity(triangles.len());
        let mut weighted = Vec::with_capacity(triangles.len());
        for t in *triangles {
            let (bin, w) = bin_of(positions, t);
            of.push(bin);
            if bin != NO_BIN {
                weighted.push((bin, w));
            }
        }
        weighted.sort_by_key(|&(bin, _)| bin);
        for run in weighted.chunk_by(|x, y| x.0 == y.0) {
            let sum = run.iter().fold(0.0f64, |s, &(_, w)| s + w);
            *area.entry(run[0].0).or_insert(0.0) += sum;
        }
        binned.push(of);
    }
    (binned, area.into_iter().collect())
}

/// Some unit vector across `n`.
fn any_across(n: DVec3) -> DVec3 {
    let axis = if n.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
    axis.cross(n).normalize()
}

/// Per-bin sums of the edge histogram: the weights, and the projected
/// directions weighted by projected length cubed (`(x, y)·|(x, y)|`, the
/// weighted mean direction of the bin).
struct EdgeBins {
    weight: [f64; EDGE_BINS],
    x: [f64; EDGE_BINS],
    y: [f64; EDGE_BINS],
}

impl EdgeBins {
    fn new() -> EdgeBins {
        EdgeBins {
            weight: [0.0; EDGE_BINS],
            x: [0.0; EDGE_BINS],
            y: [0.0; EDGE_BINS],
        }
    }

    fn add(&mut self, other: &EdgeBins) {
        for k in 0..EDGE_BINS {
            self.weight[k] += other.weight[k];
            self.x[k] += other.x[k];
            self.y[k] += other.y[k];
        }
    }
}

/// The dominant undirected direction of the edges' projections on the
/// plane across `normal`, weighted by projected length squared; `None`
/// when no edge leaves the normal's line. One pass: each bin sums its
/// weights and its weighted directions together. An edge two triangles
/// share is taken once, from the triangle where it runs from the smaller
/// vertex index to the larger (an edge of one triangle, on a boundary,
/// may be taken once or not at all: the frame only has to be good).
fn dominant_edge(parts: &[(&[DVec3], &[[u32; 3]])], normal: DVec3) -> Option<DVec3> {
    let u = any_across(normal);
    let v = normal.cross(u);
    let mut bins = EdgeBins::new();
    for (positions, triangles) in parts {
        let partial: Vec<EdgeBins> = triangles
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut h = EdgeBins::new();
                for t in chunk {
                    for (i, j) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                        if i >= j {
                            continue;
                        }
                        let (Some(p), Some(q)) =
                            (positions.get(i as usize), positions.get(j as usize))
                        else {
                            continue;
                        };
                        let e = *q - *p;
                        // The undirected direction of the projected edge, in
                        // (u, v) coordinates over the upper half-plane, and
                        // its bin by the diamond angle (monotone in the
                        // angle, no trigonometry).
                        let (mut x, mut y) = (e.dot(u), e.dot(v));
                        if y < 0.0 || (y == 0.0 && x < 0.0) {
                            (x, y) = (-x, -y);
                        }
                        let w = x * x + y * y;
                        if !(w > 0.0 && w.is_finite()) {
                            continue;
                        }
                        let angle = if x >= 0.0 {
                            y / (x + y)
                        } else {
                            1.0 - x / (y - x)
                        };
                        let bin = ((angle * 0.5 * EDGE_BINS as f64) as usize).min(EDGE_BINS - 1);
                        let len = w.sqrt();
                        h.weight[bin] += w;
                        h.x[bin] += x * len;
                        h.y[bin] += y * len;
                    }
                }
                h
            })
            .collect();
        for h in &partial {
            bins.add(h);
        }
    }
    let (peak, _) = bins
        .weight
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .filter(|(_, w)| **w > 0.0)?;
    let d = u * bins.x[peak] + v * bins.y[peak];
    let d = d.normalize_or_zero();
    (d != DVec3::ZERO).then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slab `4 × 1 × 0.1` (the unit cube stretched) as 12 triangles,
    /// turned by `rotate`.
    fn slab(rotate: impl Fn(DVec3) -> DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (corners, quads) = holey_testkit::unit_cube();
        let size = DVec3::new(4.0, 1.0, 0.1);
        let p = corners
            .iter()
            .map(|&c| rotate(DVec3::from(c) * size))
            .collect();
        let tris = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        (p, tris)
    }

    fn turn(q: DVec3) -> DVec3 {
        // A rotation about (1, 2, 3) by 0.7 radians.
        let axis = DVec3::new(1.0, 2.0, 3.0).normalize();
        let (s, c) = 0.7f64.sin_cos();
        q * c + axis.cross(q) * s + axis * axis.dot(q) * (1.0 - c)
    }

    /// The sparse bins of a small mesh are the dense histogram's, bit for
    /// bit, empty bins aside: one part and two, random triangles with a
    /// few repeated normals, degenerate ones among them.
    #[test]
    fn sparse_normal_bins_sum_as_the_dense_histogram_does() {
        let mut rng = holey_testkit::Rng::new(37);
        let positions: Vec<DVec3> = (0..300)
            .map(|_| DVec3::from(rng.point(-1.0, 1.0)))
            .collect();
        let mut triangles: Vec<[u32; 3]> = (0..900u32)
            .map(|i| [i % 300, (i * 7 + 1) % 300, (i * 13 + 5) % 300])
            .collect();
        // Copies in other orders (same bins) and a degenerate one.
        let copies: Vec<[u32; 3]> = (0..100)
            .map(|i| {
                let t = triangles[i * 3];
                [t[1], t[2], t[0]]
            })
            .collect();
        triangles.extend(copies);
        triangles.push([4, 4, 9]);
        let (first, second) = triangles.split_at(500);
        for parts in [
            vec![(&positions[..], &triangles[..])],
            vec![(&positions[..], first), (&positions[..], second)],
        ] {
            let (dense_of, dense) = dense_normal_bins(&parts);
            let (sparse_of, sparse) = sparse_normal_bins(&parts);
            assert_eq!(dense_of, sparse_of);
            let filled: Vec<(u16, u64)> = dense
                .iter()
                .filter(|(_, a)| *a != 0.0)
                .map(|&(b, a)| (b, a.to_bits()))
                .collect();
            let bits: Vec<(u16, u64)> = sparse.iter().map(|&(b, a)| (b, a.to_bits())).collect();
            assert!(sparse.len() > 100, "{} bins", sparse.len());
            assert_eq!(filled, bits);
        }
    }

    #[test]
    fn a_turned_slab_is_measured_along_its_own_axes() {
        let (p, t) = slab(turn);
        let frame = BoxFrame::of_triangles(&[(&p, &t)]);
        let axes = frame.axes().expect("a turned slab has a frame");
        // The caps' normal is the third axis; the long side (x, weighted
        // by length squared) the first.
        assert!((axes[2].dot(turn(DVec3::Z)).abs() - 1.0).abs() < 1e-12);
        assert!((axes[0].dot(turn(DVec3::X)).abs() - 1.0).abs() < 1e-12);
        // In that frame every box is as thin as the slab was drawn: the
        // cap triangles' boxes are flat up to the widening.
        for tri in &t {
            let b = frame.triangle_box(tri.map(|v| p[v as usize]));
            let e = b.max - b.min;
            assert!(e.min_element() < 1e-12, "{e}");
        }
    }

    #[test]
    fn unturned_and_shapeless_meshes_keep_the_identity() {
        let (p, t) = slab(|q| q);
        assert!(BoxFrame::of_triangles(&[(&p, &t)]).is_identity());
        // A fine sphere: no bin holds MIN_SHARE of the area.
        let (p, t) = holey_testkit::meshes::uv_sphere(40, 80, [0.0; 3], 1.0);
        let p: Vec<DVec3> = p.into_iter().map(DVec3::from).collect();
        assert!(BoxFrame::of_triangles(&[(&p, &t)]).is_identity());
        assert!(BoxFrame::of_triangles(&[]).is_identity());
    }

    /// The widened box contains the exact image of every corner: checked
    /// in exact rationals (each product and sum of f64s is exact as an
    /// expansion) on coordinates from 1e-6 to 1e6 and offsets of 4096.
    #[test]
    fn turned_boxes_contain_the_exact_images() {
        use crate::expansion::Expansion;
        let (p, t) = slab(turn);
        let frame = BoxFrame::of_triangles(&[(&p, &t)]);
        let axes = frame.axes().expect("turned");
        for scale in [1e-6, 1.0, 1e6] {
            for offset in [0.0, 4096.0] {
                for tri in &t {
                    let c = tri.map(|v| p[v as usize] * scale + DVec3::splat(offset));
                    let b = frame.triangle_box(c);
                    for q in c {
                        for (k, a) in axes.iter().enumerate() {
                            let exact = Expansion::from_f64(a.x)
                                .scale(q.x)
                                .add(&Expansion::from_f64(a.y).scale(q.y))
                                .add(&Expansion::from_f64(a.z).scale(q.z));
                            let lo = exact.sub(&Expansion::from_f64(b.min[k])).sign();
                            let hi = Expansion::from_f64(b.max[k]).sub(&exact).sign();
                            assert!(lo >= 0 && hi >= 0, "axis {k} scale {scale} offset {offset}");
                        }
                    }
                }
            }
        }
    }
}
