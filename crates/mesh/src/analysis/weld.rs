//! Welding of bit-identical positions, and by distance.

use crate::{NonFinite, PolyMesh};

/// Merges vertices whose positions are exactly identical.
///
/// Two positions are identical when their coordinates are bit-for-bit the
/// same once `-0.0` is read as `0.0`: numerically equal, without any
/// tolerance. (Signed zeros do occur: teapot.obj prints `-0.000000` on
/// patch seams whose twins print `0.000000`, and the shared README's
/// "welded" column counts them as one.) A NaN merges only with a NaN of the
/// very same bits. The result keeps the
/// first occurrence of every distinct position, in the original order, and
/// all positions (referenced or not) take part. Faces keep their order,
/// sizes and offsets; only their indices are renumbered, even where a face
/// now repeats a vertex. Indices that were out of range stay out of range
/// (shifted down by the number of positions removed, so they remain
/// distinct), and malformed offsets are copied unchanged.
///
/// Runs in O(n log n) for n positions (a sort, no hashing).
pub fn weld_exact(mesh: &PolyMesh) -> PolyMesh {
    let n = mesh.positions.len();
    // 0.0 == -0.0, so both get the bits of 0.0.
    let key = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
    // Sorting (bits, index) puts every group of equal positions together,
    // its first occurrence at the front. The keys are materialised so the
    // sort compares contiguous memory.
    let mut order: Vec<([u64; 3], u32)> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| ([key(p.x), key(p.y), key(p.z)], i as u32))
        .collect();
    order.sort_unstable();
    let mut first = vec![0u32; n];
    for group in order.chunk_by(|a, b| a.0 == b.0) {
        let head = group[0].1;
        for &(_, i) in group {
            first[i as usize] = head;
        }
    }
    drop(order);
    // Survivors are numbered in their original order.
    let mut new_index = vec![0u32; n];
    let mut positions = Vec::new();
    for i in 0..n {
        if first[i] as usize == i {
            new_index[i] = positions.len() as u32;
            positions.push(mesh.positions[i]);
        } else {
            new_index[i] = new_index[first[i] as usize];
        }
    }
    let removed = (n - positions.len()) as u32;
    let face_indices = mesh
        .face_indices
        .iter()
        .map(|&i| match new_index.get(i as usize) {
            Some(&j) => j,
            None => i - removed,
        })
        .collect();
    PolyMesh {
        positions,
        face_offsets: mesh.face_offsets.clone(),
        face_indices,
    }
}

/// What [`weld_by_distance`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct Welded {
    /// The welded mesh: one position per merged group, faces renumbered to
    /// them, repeated consecutive corners merged, and faces left with fewer
    /// than three distinct corners removed.
    pub mesh: PolyMesh,
    /// Vertices merged into another.
    pub merged_vertices: usize,
    /// Faces left with fewer than three distinct corners, dropped.
    pub dropped_faces: usize,
}

/// Why [`weld_by_distance`] refused its input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WeldError {
    /// The weld distance given (this value) is NaN, infinite or negative.
    #[error("the weld distance must be finite and not negative, got {0}")]
    Distance(f64),
    /// A position has a NaN or infinite coordinate (the first such vertex).
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// A face refers to a vertex index at or past the number of positions.
    #[error("face {face} refers to vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Index of the first face found with such a corner.
        face: usize,
        /// The out-of-range vertex index it holds.
        index: u32,
        /// Number of positions the mesh has.
        count: usize,
    },
}

/// Merges the vertices that lie within `distance` of one another
/// (Euclidean, and transitively: a chain of close vertices becomes one),
/// the weld-by-distance of modelers, for scans and soups whose seams do
/// not meet exactly. Each group keeps the position of its lowest-numbered
/// vertex, so no coordinate is invented, and the survivors keep their
/// order. Within a face, consecutive corners that became one vertex are
/// merged; a face left with fewer than three distinct corners is dropped.
/// `distance` 0 merges exactly equal positions only (`-0.0 == 0.0`), like
/// [`weld_exact`].
///
/// Close pairs are found on a grid of cells `distance` wide, so each
/// vertex is compared with those in its 27 neighbouring cells: O(n) for
/// the sparse contacts of a mesh's seams.
pub fn weld_by_distance(mesh: &PolyMesh, distance: f64) -> Result<Welded, WeldError> {
    if !(distance.is_finite() && distance >= 0.0) {
        return Err(WeldError::Distance(distance));
    }
    let n = mesh.positions.len();
    NonFinite::check("vertex", &mesh.positions)?;
    for (face, f) in mesh.faces().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= n) {
            return Err(WeldError::IndexOutOfRange {
                face,
                index,
                count: n,
            });
        }
    }
    // Union of the exact classes, then of pairs within the distance.
    let mut sets = crate::union_find::UnionFind::new(n);
    let mut first_of: std::collections::HashMap<[u64; 3], u32> = std::collections::HashMap::new();
    let key = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
    for (i, p) in mesh.positions.iter().enumerate() {
        let k = [key(p.x), key(p.y), key(p.z)];
        let f = *first_of.entry(k).or_insert(i as u32);
        sets.union(f, i as u32);
    }
    if distance > 0.0 {
        let cell = |p: glam::DVec3| {
            let c = (p / distance).floor();
            (c.x as i64, c.y as i64, c.z as i64)
        };
        let mut grid: std::collections::HashMap<(i64, i64, i64), Vec<u32>> =
            std::collections::HashMap::new();
        for (i, &p) in mesh.positions.iter().enumerate() {
            grid.entry(cell(p)).or_default().push(i as u32);
        }
        let d2 = distance * distance;
        for (i, &p) in mesh.positions.iter().enumerate() {
            let (x, y, z) = cell(p);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(others) = grid.get(&(x + dx, y + dy, z + dz)) else {
                            continue;
                        };
                        for &j in others {
                            if (j as usize) > i
                                && p.distance_squared(mesh.positions[j as usize]) <= d2
                            {
                                sets.union(i as u32, j);
                            }
                        }
                    }
                }
            }
        }
    }
    // Roots are the lowest index of their group, so they come first and
    // every vertex finds its root's number already set.
    let mut new_index = vec![0u32; n];
    let mut positions = Vec::new();
    for (i, p) in mesh.positions.iter().enumerate() {
        let r = sets.find(i as u32) as usize;
        new_index[i] = if r == i {
            positions.push(*p);
            (positions.len() - 1) as u32
        } else {
            new_index[r]
        };
    }
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(mesh.face_count());
    let mut dropped = 0;
    for f in mesh.faces() {
        let mut g: Vec<u32> = Vec::with_capacity(f.len());
        for &i in f {
            let v = new_index[i as usize];
            if g.last() != Some(&v) {
                g.push(v);
            }
        }
        while g.len() > 1 && g.first() == g.last() {
            g.pop();
        }
        let mut distinct = g.clone();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() < 3 {
            dropped += 1;
        } else {
            faces.push(g);
        }
    }
    Ok(Welded {
        merged_vertices: n - positions.len(),
        dropped_faces: dropped,
        mesh: PolyMesh::from_faces(positions, &faces),
    })
}

#[cfg(test)]
mod distance_tests {
    use super::*;
    use glam::DVec3;

    /// Two unit squares side by side as separate quads, the second's
    /// shared corners off by `gap`.
    fn two_squares(gap: f64) -> PolyMesh {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0 + gap, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0 + gap, 0.0),
        ];
        PolyMesh::from_faces(positions, &[vec![0, 1, 2, 3], vec![4, 5, 6, 7]])
    }

    #[test]
    fn close_seams_are_welded_and_far_ones_kept() {
        let m = two_squares(1e-4);
        let w = weld_by_distance(&m, 1e-3).unwrap();
        assert_eq!(w.merged_vertices, 2);
        assert_eq!(w.mesh.positions.len(), 6);
        assert_eq!(w.dropped_faces, 0);
        // The survivors keep the first vertex's position exactly.
        assert_eq!(w.mesh.positions[1], DVec3::new(1.0, 0.0, 0.0));
        let faces: Vec<Vec<u32>> = w.mesh.faces().map(|f| f.to_vec()).collect();
        assert_eq!(faces, vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2]]);
        let kept = weld_by_distance(&m, 1e-5).unwrap();
        assert_eq!(kept.merged_vertices, 0);
    }

    #[test]
    fn collapsed_faces_are_dropped_and_bad_input_refused() {
        let m = two_squares(0.0);
        // Exact: only the identical corners.
        assert_eq!(weld_by_distance(&m, 0.0).unwrap().merged_vertices, 2);
        // So coarse the second square collapses to a segment.
        let w = weld_by_distance(&m, 1.5).unwrap();
        assert_eq!(w.dropped_faces, 2);
        assert!(matches!(
            weld_by_distance(&m, f64::NAN),
            Err(WeldError::Distance(_))
        ));
        assert!(matches!(
            weld_by_distance(&m, -1.0),
            Err(WeldError::Distance(_))
        ));
        let mut bad = m.clone();
        bad.positions[3].x = f64::INFINITY;
        assert_eq!(
            weld_by_distance(&bad, 0.1),
            Err(WeldError::NonFinite(NonFinite::vertex(3, bad.positions[3])))
        );
        let mut out = m;
        out.face_indices[2] = 99;
        assert!(matches!(
            weld_by_distance(&out, 0.1),
            Err(WeldError::IndexOutOfRange { face: 0, .. })
        ));
    }
}
