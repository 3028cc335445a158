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

use crate::error::{GeomError, NonFinite};
use glam::DVec3;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The bit pattern of a coordinate with `-0.0` mapped to `0.0`.
#[inline]
fn key_bits(x: f64) -> u64 {
    if x == 0.0 { 0 } else { x.to_bits() }
}

/// The key of a position's exact class: its coordinates' bit patterns,
/// `-0.0` mapped to `0.0` ([`position_classes`] groups points by it).
#[inline]
pub fn position_key(p: DVec3) -> [u64; 3] {
    [key_bits(p.x), key_bits(p.y), key_bits(p.z)]
}

/// A small multiplicative hasher for integer keys such as `[u64; 3]`
/// position keys or packed index pairs (keys are not adversarial here;
/// this keeps hash passes at memory speed). Use it through
/// [`std::hash::BuildHasherDefault`].
#[derive(Default)]
pub struct MulHasher(u64);

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
    NonFinite::check("point", positions)?;
    let mut ids = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        ids.push(*map.entry(position_key(*p)).or_insert(i as u32));
    }
    Ok(ids)
}

/// Class of each moving point: the smallest index of a point with
/// exactly the same position at the start and at the end of the motion
/// (the same point of a surface: the copies of a soup's shared corner).
/// Points that only meet at the end (two parts landing exactly on each
/// other, a grid moved onto the lattice of another) are in different
/// classes. Errors as [`position_classes`].
pub fn motion_classes(start: &[DVec3], end: &[DVec3]) -> Result<Vec<u32>, GeomError> {
    if start.len() != end.len() {
        return Err(GeomError::LengthMismatch {
            what: "start positions",
            got: start.len(),
            expected: end.len(),
        });
    }
    let mut ids = position_classes(end)?;
    NonFinite::check("point", start).map_err(|e| e.in_input("start positions"))?;
    // Most meshes have no two vertices at one place: nothing to refine.
    let mut size = vec![0u32; ids.len()];
    for &c in &ids {
        size[c as usize] += 1;
    }
    if size.iter().all(|&k| k <= 1) {
        return Ok(ids);
    }
    // Split the shared classes by the start position.
    let mut map: HashMap<(u32, [u64; 3]), u32, BuildHasherDefault<MulHasher>> = HashMap::default();
    for (v, id) in ids.iter_mut().enumerate() {
        if size[*id as usize] > 1 {
            let p = start[v];
            let k = (*id, [key_bits(p.x), key_bits(p.y), key_bits(p.z)]);
            *id = *map.entry(k).or_insert(v as u32);
        }
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
    fn motion_classes_need_both_ends() {
        let start = [
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::Y,
        ];
        // 0 and 1 are one point throughout; 2 and 3 land on it at the
        // end; 4 is alone.
        let end = [DVec3::Z, DVec3::Z, DVec3::Z, DVec3::Z, DVec3::Y];
        assert_eq!(motion_classes(&start, &end), Ok(vec![0, 0, 2, 3, 4]));
        // At rest the classes are the position classes.
        assert_eq!(motion_classes(&end, &end), position_classes(&end));
        let bad = [
            DVec3::ZERO,
            DVec3::new(0.0, f64::INFINITY, 0.0),
            DVec3::X,
            DVec3::X,
            DVec3::Y,
        ];
        assert!(matches!(
            motion_classes(&bad, &end),
            Err(GeomError::NonFinite(e)) if e.index == Some(1)
        ));
        assert!(motion_classes(&start[..2], &end).is_err());
    }

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
        assert!(matches!(
            position_classes(&bad),
            Err(GeomError::NonFinite(e)) if e.index == Some(1)
        ));
        assert_eq!(index_identities(3), Ok(vec![0, 1, 2]));
    }
}
