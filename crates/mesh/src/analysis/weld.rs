//! Welding of bit-identical positions.

use crate::PolyMesh;

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
