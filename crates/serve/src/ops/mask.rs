//! The sculpt mask: vertices no brush moves. Painted by a mask brush,
//! cleared and inverted; kept in the document as exact positions and
//! handed to every stroke (`LiveStroke::set_mask`). Every change is an
//! undo step, is saved with the session, and sends every tab the state
//! and the whole frame, which carries the mask (flag bit 4).

use std::collections::HashMap;

use glam::DVec3;
use holey_geom::position_key;
use holey_topo::TriMesh;
use serde_json::json;

use super::request::{MaskPaint, missing};
use super::{Reply, Shared};
use crate::ServeError;
use crate::doc::{Document, Mask};

/// The most dab centres one `mask_paint` takes (a long drag sends its
/// dabs in one request at release).
pub const MAX_MASK_POINTS: usize = 100_000;

impl Shared {
    /// `mask_paint`: masks (with `erase`, unmasks) every vertex within the
    /// radius of a dab centre (`points`, or one `point`).
    pub(super) fn mask_paint(&self, doc: &mut Document, req: &MaskPaint) -> Reply {
        let mesh = self.mask_mesh(doc)?;
        if req.radius <= 0.0 {
            return Err(ServeError::BadRequest(
                "the mask brush's radius must be positive".into(),
            ));
        }
        let dabs = Dabs::new(dab_points(req)?, req.radius);
        let erase = req.erase == Some(true);
        let mut mask = Mask::clone(doc.mask());
        for &p in &mesh.positions {
            if dabs.cover(p) {
                let key = position_key(p);
                if erase {
                    mask.remove(&key);
                } else {
                    mask.insert(key);
                }
            }
        }
        self.commit_mask(doc, mask)
    }

    /// `mask_clear` or `mask_invert` (`op`).
    pub(super) fn mask_clear_or_invert(&self, doc: &mut Document, op: &str) -> Reply {
        let mesh = self.mask_mesh(doc)?;
        let mask: Mask = if op == "mask_clear" {
            Mask::new()
        } else {
            mesh.positions
                .iter()
                .map(|&p| position_key(p))
                .filter(|k| !doc.mask().contains(k))
                .collect()
        };
        self.commit_mask(doc, mask)
    }

    /// The sculpt mesh a mask edit applies to.
    fn mask_mesh<'a>(&self, doc: &'a Document) -> Result<&'a TriMesh, ServeError> {
        let mesh = doc.sculpt_mesh("masking")?;
        doc.check_no_rind()?;
        Ok(mesh)
    }

    /// One undo step when the mask changes. Answers with `"masked"`, the
    /// number of the mesh's vertices masked now.
    fn commit_mask(&self, doc: &mut Document, mask: Mask) -> Reply {
        if doc.commit_mask(mask) {
            self.publish(doc);
        }
        let masked = doc
            .mask_flags()
            .map_or(0, |f| f.iter().filter(|&&b| b).count());
        Ok(json!({"masked": masked}))
    }
}

/// Dab centres filed in a grid of cells one radius wide, so that a long
/// drag over a big mesh costs the vertices plus the dabs, not their
/// product: a vertex looks only at the dabs of its cell's 27 neighbours.
struct Dabs {
    cells: HashMap<[i64; 3], Vec<DVec3>>,
    radius: f64,
}

impl Dabs {
    fn new(centres: Vec<DVec3>, radius: f64) -> Dabs {
        let mut cells: HashMap<[i64; 3], Vec<DVec3>> = HashMap::new();
        for c in centres {
            cells.entry(cell(c, radius)).or_default().push(c);
        }
        Dabs { cells, radius }
    }

    /// Whether `p` is within the radius of a dab centre.
    fn cover(&self, p: DVec3) -> bool {
        let [x, y, z] = cell(p, self.radius);
        let r2 = self.radius * self.radius;
        (-1..=1).any(|i| {
            (-1..=1).any(|j| {
                (-1..=1).any(|k| {
                    self.cells
                        .get(&[
                            x.saturating_add(i),
                            y.saturating_add(j),
                            z.saturating_add(k),
                        ])
                        .is_some_and(|cs| cs.iter().any(|c| c.distance_squared(p) <= r2))
                })
            })
        })
    }
}

/// The grid cell of a point: cells a hair wider than `radius`, so that
/// a point within the radius of a dab is in a neighbouring cell whatever
/// the division rounds (coordinates beyond `i64` saturate, which only
/// merges far cells).
fn cell(p: DVec3, radius: f64) -> [i64; 3] {
    (p / (radius * (1.0 + 1e-9)))
        .floor()
        .to_array()
        .map(|c| c as i64)
}

/// The dab centres of a `mask_paint`: `points` or one `point`.
fn dab_points(req: &MaskPaint) -> Result<Vec<DVec3>, ServeError> {
    let list = match (&req.points, &req.point) {
        (Some(list), _) => list.as_slice(),
        (None, Some(point)) => std::slice::from_ref(point),
        (None, None) => return Err(missing("mask_paint", "points")),
    };
    if list.is_empty() || list.len() > MAX_MASK_POINTS {
        return Err(ServeError::BadRequest(format!(
            "\"points\" holds 1 to {MAX_MASK_POINTS} dab centres, got {}",
            list.len()
        )));
    }
    Ok(list.iter().map(|&p| DVec3::from_array(p)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid answers exactly as comparing with every dab would.
    #[test]
    fn dab_grid_agrees_with_brute_force() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        for radius in [0.05, 0.3, 1.7, 1e-300] {
            let centres: Vec<DVec3> = (0..40)
                .map(|_| DVec3::new(next(), next(), next()))
                .collect();
            let dabs = Dabs::new(centres.clone(), radius);
            let mut covered = 0;
            for _ in 0..4000 {
                let p = DVec3::new(next(), next(), next());
                let brute = centres
                    .iter()
                    .any(|c| c.distance_squared(p) <= radius * radius);
                assert_eq!(dabs.cover(p), brute, "{p} at radius {radius}");
                covered += usize::from(brute);
            }
            // The centres themselves are covered, even at a tiny radius.
            assert!(centres.iter().all(|&c| dabs.cover(c)));
            if radius > 0.2 {
                assert!(covered > 0);
            }
        }
        // Far coordinates saturate instead of overflowing.
        let far = Dabs::new(vec![DVec3::splat(1e300)], 1e-10);
        assert!(far.cover(DVec3::splat(1e300)));
        assert!(!far.cover(DVec3::ZERO));
    }
}
