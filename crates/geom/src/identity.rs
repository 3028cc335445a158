//! Symbolic identities for the points of a mesh or soup.
//!
//! Simulation of simplicity perturbs every identity differently
//! ([`crate::sos`]). Which input points should be *one* symbolic point is a
//! modelling decision:
//!
//! - **By exact position** ([`position_classes`]): all points with exactly
//!   the same coordinates get the same identity. This is what the
//!   static-intersection engine wants: in an unwelded soup two triangles
//!   whose corners coincide really do touch at that point, and they must
//!   keep touching after perturbation. Giving the corners different
//!   identities would pull them infinitesimally apart and could create (or
//!   remove) an intersection of vanishing size that no construction can
//!   represent — a phantom sliver of intersection curve at every welded
//!   seam of the soup.
//!   Equality is bitwise on the coordinates with `-0.0` identified with
//!   `0.0` (the only two distinct bit patterns of one finite real).
//! - **By index**: every vertex its own identity (`id = index`). Right when
//!   coincident vertices are meant to be different points (e.g. the two
//!   keyframe positions of a moving vertex in [`crate::ccd`]).
//!
//! Identities are `u32`; the identity of a class is the smallest index in
//! it, so the result is deterministic and independent of hashing.

use crate::error::GeomError;
use glam::DVec3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The bit pattern of a coordinate with `-0.0` mapped to `0.0`.
#[inline]
fn key_bits(x: f64) -> u64 {
    if x == 0.0 { 0 } else { x.to_bits() }
}

/// A small multiplicative hasher for `[u64; 3]` keys (keys are not
/// adversarial here; this keeps the pass at memory speed).
#[derive(Default)]
struct MulHasher(u64);

impl Hasher for MulHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(26) ^ x).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }
}

/// Identity of each point: the smallest index of a point with exactly the
/// same position (`-0.0 == 0.0`). Errors on NaN or infinite coordinates and
/// on more than 2³¹ points.
pub fn position_classes(positions: &[DVec3]) -> Result<Vec<u32>, GeomError> {
    if positions.len() > (1usize << 31) {
        return Err(GeomError::TooMany(positions.len()));
    }
    let mut map: HashMap<[u64; 3], u32, BuildHasherDefault<MulHasher>> =
        HashMap::with_capacity_and_hasher(positions.len(), Default::default());
    let mut ids = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        if !p.is_finite() {
            return Err(GeomError::NonFinite { index: i });
        }
        let k = [key_bits(p.x), key_bits(p.y), key_bits(p.z)];
        ids.push(*map.entry(k).or_insert(i as u32));
    }
    Ok(ids)
}

/// `id = index` for `n` points.
pub fn index_identities(n: usize) -> Result<Vec<u32>, GeomError> {
    if n > (1usize << 31) {
        return Err(GeomError::TooMany(n));
    }
    Ok((0..n as u32).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_by_exact_position() {
        let p = [
            DVec3::new(0.0, 1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-0.0, 1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0 + f64::EPSILON * 2.0),
            DVec3::new(1.0, 1.0, 2.0),
        ];
        assert_eq!(position_classes(&p), Ok(vec![0, 1, 0, 3, 1]));
        let bad = [DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)];
        assert_eq!(
            position_classes(&bad),
            Err(GeomError::NonFinite { index: 1 })
        );
        assert_eq!(index_identities(3), Ok(vec![0, 1, 2]));
    }
}
