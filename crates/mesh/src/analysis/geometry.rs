//! Geometric measures: bounds, area and signed volume.

use glam::DVec3;

use super::soup::Soup;
use super::topology::NONE;

/// Bounds, area and volume sums over a soup's referenced vertices.
pub(crate) struct Geometry {
    /// Min and max over the referenced vertices whose coordinates are all
    /// finite.
    pub bbox: Option<(DVec3, DVec3)>,
    /// Referenced vertices with a NaN or infinite coordinate.
    pub nonfinite_vertices: usize,
    /// Per bin: area over fan triangles with finite corners.
    pub area: Vec<f64>,
    /// Per bin: signed volume over fan triangles, or `None` if one of its
    /// vertices is not finite.
    pub volume: Vec<Option<f64>>,
    /// Area of the whole mesh.
    pub total_area: f64,
    /// Signed volume of the whole mesh, `None` if a referenced vertex is
    /// not finite.
    pub total_volume: Option<f64>,
}

/// Measures per component (`bins` = `Some(number of components)`) or for
/// the whole mesh in one bin (`None`); `component` labels every vertex
/// slot, [`NONE`] where unreferenced.
pub(crate) fn geometry(
    soup: &Soup,
    positions: &[DVec3],
    component: &[u32],
    bins: Option<usize>,
) -> Geometry {
    let bin = |v: u32| {
        if bins.is_some() {
            component[v as usize] as usize
        } else {
            0
        }
    };
    let bins = bins.unwrap_or(1);
    let mut bbox: Option<(DVec3, DVec3)> = None;
    let mut nonfinite_vertices = 0;
    let mut finite = vec![true; bins];
    for (v, &p) in positions.iter().enumerate() {
        if component[v] == NONE {
            continue;
        }
        if p.is_finite() {
            bbox = Some(match bbox {
                Some((lo, hi)) => (lo.min(p), hi.max(p)),
                None => (p, p),
            });
        } else {
            nonfinite_vertices += 1;
            finite[bin(v as u32)] = false;
        }
    }
    // The signed volume of a closed oriented surface does not depend on the
    // origin; taking the middle of the bounds keeps the triple products
    // small, so far-from-origin meshes lose less precision to cancellation.
    let origin = bbox.map_or(DVec3::ZERO, |(lo, hi)| 0.5 * (lo + hi));
    let mut area = vec![0.0; bins];
    let mut volume6 = vec![0.0; bins];
    // Totals are summed in their own right, triangle by triangle, so they
    // are the same to the bit whether or not components are asked for.
    let (mut total_area, mut total_volume6) = (0.0, 0.0);
    for face in soup.faces() {
        let c = bin(face[0]);
        fan(face, positions, origin, |p0, p1, p2| {
            // Triangles touching a non-finite vertex are left out (their
            // component, and the mesh, then have no volume).
            if p0.is_finite() && p1.is_finite() && p2.is_finite() {
                let a = 0.5 * (p1 - p0).cross(p2 - p0).length();
                let v6 = p0.dot(p1.cross(p2));
                area[c] += a;
                volume6[c] += v6;
                total_area += a;
                total_volume6 += v6;
            }
        });
    }
    let volume = |v6: f64, ok: bool| (ok && v6.is_finite()).then_some(v6 / 6.0);
    Geometry {
        bbox,
        nonfinite_vertices,
        volume: volume6
            .iter()
            .zip(&finite)
            .map(|(&v6, &ok)| volume(v6, ok))
            .collect(),
        area,
        total_area,
        total_volume: volume(total_volume6, nonfinite_vertices == 0),
    }
}

/// Calls `tri` on the fan triangles (0, k, k+1) of a face, positions taken
/// relative to `origin`.
fn fan(face: &[u32], positions: &[DVec3], origin: DVec3, mut tri: impl FnMut(DVec3, DVec3, DVec3)) {
    if face.len() < 3 {
        return;
    }
    let p = |i: u32| positions[i as usize] - origin;
    let p0 = p(face[0]);
    let mut prev = p(face[1]);
    for &i in &face[2..] {
        let cur = p(i);
        tri(p0, prev, cur);
        prev = cur;
    }
}
