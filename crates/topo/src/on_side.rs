//! Whether a point lies on a side, and which constructed points are one,
//! to the rounding of constructed points (issue 14). The coplanar overlay
//! (`coplanar`), the crossings of its sides (`side_crossings`), the merge
//! of `resolve`'s overlaps (`overlaps`) and the Booleans' T-junction
//! repair (`winding_boolean`) all decide by these bounds: ulps of the
//! coordinates, never a modelling tolerance.

use glam::{DVec2, DVec3};
use holey_geom::{Aabb, GeomError, position_classes};
use rustc_hash::FxHashMap as HashMap;

use crate::union_find::UnionFind;

/// How far from a side's line, relative to its length, a point may lie
/// and still be on it: the rounding of a constructed point (ulps), not a
/// modelling tolerance. The overlay follows its split sides, and the
/// Booleans and `resolve` split the sides around it, by this one bound.
pub(crate) const ON_SIDE: f64 = 1.0 / (1u64 << 30) as f64;

/// How far from a side's line, relative to the size of the coordinates,
/// a point may also lie and still be on it: a constructed point is off by
/// some ulps of its coordinates however short the side, so on a side of a
/// few ulps' length [`ON_SIDE`] alone would take a point rounded onto it
/// as off it (the OpenSCAD export has sides of 2·10⁻¹¹ at coordinates of
/// 200, with points 2·10⁻¹⁶ off them).
pub(crate) const ON_COORDINATES: f64 = 1.0 / (1u64 << 48) as f64;

/// The distance within which a point is on a side of length `length`
/// among points whose largest coordinate is `size` ([`ON_SIDE`] and
/// [`ON_COORDINATES`]).
pub(crate) fn on_side_reach(length: f64, size: f64) -> f64 {
    length * ON_SIDE + size * ON_COORDINATES
}

/// Whether `w` lies on the line through `u` and `v`, within
/// [`on_side_reach`] of it (or `u` and `v` coincide).
pub(crate) fn near_line(positions: &[DVec3], u: u32, v: u32, w: u32) -> bool {
    let (pu, pv, pw) = (
        positions[u as usize],
        positions[v as usize],
        positions[w as usize],
    );
    let d = pv - pu;
    let size = pu.abs().max(pv.abs()).max(pw.abs()).max_element();
    let length = d.length();
    (pw - pu).cross(d).length() <= length * on_side_reach(length, size)
}

/// [`near_line`] in a group's projection: whether `q` lies on the line
/// through `a` and `b` within [`on_side_reach`] of it, the size being
/// that of the projected coordinates (the projection drops an axis
/// exactly, and points constructed in it are rounded to its own).
pub(crate) fn near_line_2d(a: DVec2, b: DVec2, q: DVec2) -> bool {
    let d = b - a;
    let size = a.abs().max(b.abs()).max(q.abs()).max_element();
    let length = d.length();
    d.perp_dot(q - a).abs() <= length * on_side_reach(length, size)
}

/// Whether `w` lies strictly between `u` and `v` on their line, up to
/// [`on_side_reach`].
pub(crate) fn on_side_between(positions: &[DVec3], u: u32, v: u32, w: u32) -> bool {
    let (pu, pv) = (positions[u as usize], positions[v as usize]);
    let d = pv - pu;
    let t = (positions[w as usize] - pu).dot(d);
    t > 0.0 && t < d.dot(d) && near_line(positions, u, v, w)
}

/// Relative distance (to the size of the overlay's points) within which
/// a crossing point is taken as another point: the rounding of two
/// computations of one crossing (three sides through one point of a
/// degenerate input are split at two points an ulp apart, and the sliver
/// between them covers nothing), not a modelling tolerance.
pub(crate) const SNAP: f64 = 1.0 / (1u64 << 40) as f64;

/// For each of `points`, the point it is taken as: itself, or for a
/// crossing (`crossing[i]`), the nearest corner within [`SNAP`] of the
/// points' size, else the first crossing of its cluster of crossings
/// that lie within that of each other. Corners are never merged.
pub(crate) fn snap_crossings(points: &[DVec3], crossing: &[bool]) -> Vec<usize> {
    let mut to: Vec<usize> = (0..points.len()).collect();
    if !crossing.iter().any(|&c| c) {
        return to;
    }
    let size = Aabb::from_points(points);
    let tol = (size.max - size.min).length() * SNAP;
    if !(tol > 0.0 && tol.is_finite()) {
        return to;
    }
    let cell = |p: DVec3| ((p - size.min) / tol).floor().as_i64vec3();
    let mut grid: rustc_hash::FxHashMap<glam::I64Vec3, Vec<usize>> = Default::default();
    for (i, &p) in points.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(i);
    }
    let mut clusters = UnionFind::new(points.len());
    for i in (0..points.len()).filter(|&i| crossing[i]) {
        let c = cell(points[i]);
        let mut nearest: Option<(f64, usize)> = None;
        for d in (0..27).map(|k| glam::I64Vec3::new(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1)) {
            for &j in grid.get(&(c + d)).into_iter().flatten() {
                let dist = (points[j] - points[i]).length();
                if j == i || dist > tol {
                    continue;
                }
                if crossing[j] {
                    clusters.union(i as u32, j as u32);
                } else if nearest.is_none_or(|(n, _)| dist < n) {
                    nearest = Some((dist, j));
                }
            }
        }
        if let Some((_, j)) = nearest {
            to[i] = j;
        }
    }
    let mut first: rustc_hash::FxHashMap<u32, usize> = Default::default();
    for i in 0..points.len() {
        if crossing[i] && to[i] == i {
            to[i] = *first.entry(clusters.find(i as u32)).or_insert(i);
        }
    }
    to
}

/// How near, in units of the largest coordinate's ulp, a constructed
/// point is taken as an input vertex ([`welded_classes`]).
pub(crate) const WELD_ULPS: f64 = 8.0;

/// For each of `positions`, the vertex it is taken as: points at equal
/// positions are one (the first), and each constructed point (`origin[v]`
/// is `u32::MAX`, the cut's mark for a point rounded from an exact
/// crossing or a split point; else the input vertex it is) within
/// [`WELD_ULPS`] ulps of the largest coordinate of an input vertex (per
/// axis) is the nearest such vertex; input vertices never move.
///
/// Where sheets meet at or near a vertex, the exact arrangement has
/// points that rounding puts a few ulps from it: the Booleans' results
/// stay open there otherwise (nearly coincident shells), and `resolve`
/// could not overlay the coplanar groups through them (on the OpenSCAD
/// export, points of the cut lie within 4·10⁻¹⁵ of the corner
/// (−17.9, 0.6, −204) at coordinates of 200, and groups through them
/// opened the surface when overlaid).
pub(crate) fn welded_classes(positions: &[DVec3], origin: &[u32]) -> Result<Vec<u32>, GeomError> {
    let constructed = |v: usize| origin.get(v) == Some(&u32::MAX);
    let mut class = position_classes(positions)?;
    let scale = positions
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    let reach = WELD_ULPS * scale * f64::EPSILON;
    if reach > 0.0 {
        let cell = |p: DVec3| (p / (2.0 * reach)).floor().as_i64vec3().to_array();
        let mut anchors: HashMap<[i64; 3], Vec<u32>> = HashMap::default();
        for (v, p) in positions.iter().enumerate() {
            if !constructed(v) && class[v] as usize == v {
                anchors.entry(cell(*p)).or_default().push(v as u32);
            }
        }
        for (v, p) in positions.iter().enumerate() {
            if !constructed(v) || class[v] as usize != v {
                continue;
            }
            let c = cell(*p);
            let mut best: Option<(f64, u32)> = None;
            for d in 0..27i64 {
                let k = [c[0] + d / 9 - 1, c[1] + (d / 3) % 3 - 1, c[2] + d % 3 - 1];
                for &a in anchors.get(&k).into_iter().flatten() {
                    let gap = (positions[a as usize] - *p).abs().max_element();
                    if gap <= reach && best.is_none_or(|(g, _)| gap < g) {
                        best = Some((gap, a));
                    }
                }
            }
            if let Some((_, a)) = best {
                class[v] = a;
            }
        }
        // Points that shared a constructed point's position follow it.
        for v in 0..class.len() {
            class[v] = class[class[v] as usize];
        }
    }
    Ok(class)
}
