//! Small polygon helpers shared by the operators of issue 18: centroids,
//! Newell normals, the frame of a face, rotations about an axis, and
//! least-squares fits. Nothing here touches a mesh.

use glam::{DQuat, DVec3};

/// Relative size below which a polygon's vector area counts as zero: the
/// area is compared with the squared mean edge length, so the test does
/// not depend on the model's scale.
const FLAT: f64 = 1e-12;

/// Newell's vector: twice the vector area of a closed polygon. Its
/// direction is the polygon's normal (counter-clockwise seen from its
/// tip) and its length twice the area of the projection.
pub(crate) fn newell(points: &[DVec3]) -> DVec3 {
    let n = points.len();
    (0..n).map(|k| points[k].cross(points[(k + 1) % n])).sum()
}

/// The vertex average of a polygon (`ZERO` for none).
pub(crate) fn centroid(points: &[DVec3]) -> DVec3 {
    if points.is_empty() {
        return DVec3::ZERO;
    }
    points.iter().copied().sum::<DVec3>() / points.len() as f64
}

/// Mean length of the polygon's edges (closing edge included).
pub(crate) fn mean_edge(points: &[DVec3]) -> f64 {
    let n = points.len();
    if n == 0 {
        return 0.0;
    }
    (0..n)
        .map(|k| points[k].distance(points[(k + 1) % n]))
        .sum::<f64>()
        / n as f64
}

/// What the extrusions need to know about a face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    /// Vertex average.
    pub centroid: DVec3,
    /// Unit Newell normal.
    pub normal: DVec3,
    /// Mean distance of the corners from the centroid.
    pub radius: f64,
    /// Mean edge length.
    pub edge: f64,
}

/// The frame of a polygon, or `None` when it has no normal: fewer than
/// three corners, zero area relative to its edges, or non-finite input.
pub(crate) fn frame(points: &[DVec3]) -> Option<Frame> {
    if points.len() < 3 {
        return None;
    }
    let c = centroid(points);
    let edge = mean_edge(points);
    let area = newell(points);
    let len = area.length();
    if !(len.is_finite() && edge.is_finite()) || len <= FLAT * edge * edge || edge == 0.0 {
        return None;
    }
    let radius = points.iter().map(|p| p.distance(c)).sum::<f64>() / points.len() as f64;
    Some(Frame {
        centroid: c,
        normal: area / len,
        radius,
        edge,
    })
}

/// Rotates `p` about the line through `centre` along the unit `axis` by
/// `degrees` (counter-clockwise seen from the axis's tip).
pub(crate) fn rotate_about(p: DVec3, centre: DVec3, axis: DVec3, degrees: f64) -> DVec3 {
    if degrees == 0.0 {
        return p;
    }
    centre + DQuat::from_axis_angle(axis, degrees.to_radians()) * (p - centre)
}

/// The unit normal direction of least variance of a point set and its
/// centroid: the least-squares plane (smallest eigenvector of the
/// covariance matrix, by Jacobi rotations). `None` for fewer than three
/// points or non-finite input.
pub(crate) fn best_fit_plane(points: &[DVec3]) -> Option<(DVec3, DVec3)> {
    if points.len() < 3 {
        return None;
    }
    let c = centroid(points);
    let mut a = [[0.0f64; 3]; 3];
    for p in points {
        let d = (*p - c).to_array();
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += d[i] * d[j];
            }
        }
    }
    let (values, vectors) = jacobi_eigen(a);
    let k = (0..3).min_by(|&i, &j| values[i].total_cmp(&values[j]))?;
    let n = DVec3::new(vectors[0][k], vectors[1][k], vectors[2][k]);
    let len = n.length();
    if !(len.is_finite() && len > 0.0 && c.is_finite()) {
        return None;
    }
    // Orient the plane like the polygon when the polygon has an area, so
    // callers that care about sides get a consistent answer.
    let newell_n = newell(points);
    let n = if newell_n.dot(n) < 0.0 { -n } else { n } / len;
    Some((c, n))
}

/// Eigenvalues and eigenvectors (columns) of a symmetric 3×3 matrix by
/// cyclic Jacobi rotations; converges in a handful of sweeps.
fn jacobi_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-18 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0usize, 1usize), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let cs = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * cs;
            // A ← Jᵀ A J, V ← V J, with J the rotation in the (p, q) plane.
            for row in a.iter_mut() {
                let (akp, akq) = (row[p], row[q]);
                row[p] = cs * akp - sn * akq;
                row[q] = sn * akp + cs * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            a[p] = std::array::from_fn(|k| cs * rp[k] - sn * rq[k]);
            a[q] = std::array::from_fn(|k| sn * rp[k] + cs * rq[k]);
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = cs * vp - sn * vq;
                row[q] = sn * vp + cs * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

/// The least-squares sphere through points (the algebraic fit
/// `|p|² = 2c·p + k`, `r² = k + |c|²`): centre and radius, or `None` when
/// the points do not determine one (fewer than four, all on a plane, or
/// non-finite).
pub(crate) fn best_fit_sphere(points: &[DVec3]) -> Option<(DVec3, f64)> {
    if points.len() < 4 {
        return None;
    }
    // Centre the data first: the normal equations are far better
    // conditioned about the centroid.
    let g = centroid(points);
    let mut m = [[0.0f64; 5]; 4];
    let mut scale = 0.0f64;
    for p in points {
        let d = *p - g;
        scale = scale.max(d.length_squared());
        let row = [2.0 * d.x, 2.0 * d.y, 2.0 * d.z, 1.0];
        let rhs = d.length_squared();
        for i in 0..4 {
            for j in 0..4 {
                m[i][j] += row[i] * row[j];
            }
            m[i][4] += row[i] * rhs;
        }
    }
    let x = solve4(m, scale)?;
    let c = DVec3::new(x[0], x[1], x[2]);
    let r2 = x[3] + c.length_squared();
    let centre = c + g;
    (r2 > 0.0 && r2.is_finite() && centre.is_finite()).then(|| (centre, r2.sqrt()))
}

/// Gaussian elimination with partial pivoting on an augmented 4×5 matrix;
/// `None` when a pivot is negligible against `scale` (a singular system).
fn solve4(mut m: [[f64; 5]; 4], scale: f64) -> Option<[f64; 4]> {
    let tiny = 1e-12 * (1.0 + scale) * (1.0 + scale);
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        let size = m[pivot][col].abs();
        if size.is_nan() || size <= tiny {
            return None;
        }
        m.swap(col, pivot);
        for row in 0..4 {
            if row != col {
                let f = m[row][col] / m[col][col];
                let pivot_row = m[col];
                for (x, y) in m[row].iter_mut().zip(pivot_row).skip(col) {
                    *x -= f * y;
                }
            }
        }
    }
    let x = [
        m[0][4] / m[0][0],
        m[1][4] / m[1][1],
        m[2][4] / m[2][2],
        m[3][4] / m[3][3],
    ];
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_of_a_tilted_square() {
        let n = DVec3::new(1.0, 2.0, 2.0) / 3.0;
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let pts: Vec<DVec3> = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)]
            .iter()
            .map(|&(a, b)| DVec3::new(5.0, 1.0, 0.0) + u * a + v * b)
            .collect();
        let (c, m) = best_fit_plane(&pts).unwrap();
        assert!((c - DVec3::new(5.0, 1.0, 0.0)).length() < 1e-12);
        assert!((m - n).length() < 1e-12, "{m}");
        let f = frame(&pts).unwrap();
        assert!((f.normal - n).length() < 1e-12);
        assert!((f.radius - 1.0).abs() < 1e-12);
    }

    #[test]
    fn sphere_through_points_on_a_sphere() {
        let centre = DVec3::new(0.5, -2.0, 3.0);
        let pts: Vec<DVec3> = (0..20)
            .map(|i| {
                let a = i as f64 * 0.7;
                let b = i as f64 * 1.3;
                centre + 2.5 * DVec3::new(a.cos() * b.sin(), a.sin() * b.sin(), b.cos())
            })
            .collect();
        let (c, r) = best_fit_sphere(&pts).unwrap();
        assert!((c - centre).length() < 1e-9 && (r - 2.5).abs() < 1e-9);
        // Coplanar points determine no sphere.
        let flat: Vec<DVec3> = pts.iter().map(|p| DVec3::new(p.x, p.y, 0.0)).collect();
        assert!(best_fit_sphere(&flat).is_none());
        assert!(best_fit_sphere(&pts[..3]).is_none());
    }

    #[test]
    fn degenerate_polygons_have_no_frame() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(frame(&line).is_none());
        assert!(frame(&[DVec3::ZERO, DVec3::X]).is_none());
        let nan = [DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0.0, 0.0)];
        assert!(frame(&nan).is_none());
    }
}
