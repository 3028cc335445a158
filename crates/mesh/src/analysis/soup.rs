//! The valid part of a [`PolyMesh`], copied into a compact corner table.

use rayon::prelude::*;

use crate::{PARALLEL_RUN, PolyMesh};

/// The faces of a [`PolyMesh`] that can be analysed, as a corner table.
///
/// A face is *invalid*, and left out, when its offsets are malformed
/// (decreasing, or past the end of `face_indices`), when it has no corner,
/// or when one of its indices is not below `positions.len()` (index
/// `u32::MAX` is always out of range, as [`PolyMesh::check`] allows fewer
/// positions). Every other
/// face is kept, in order, whatever it repeats or degenerates to.
pub(crate) struct Soup {
    /// The vertex of every corner, face after face.
    pub vert: Vec<u32>,
    /// The next corner around the same face (a 1-gon's corner is its own
    /// next), so a face's sides are the corners `c` with `next[c] != c`.
    pub next: Vec<u32>,
    /// The previous corner around the same face.
    pub prev: Vec<u32>,
    /// Offsets of the kept faces into `vert` (one more than faces).
    pub start: Vec<u32>,
    /// Faces left out (see above).
    pub invalid_faces: usize,
}

impl Soup {
    pub(crate) fn new(mesh: &PolyMesh) -> Soup {
        Soup::of_faces(mesh.positions.len(), &mesh.face_offsets, &mesh.face_indices)
    }

    /// The soup of `triangles` over `vertex_count` positions: what
    /// [`Soup::new`] makes of the same triangles as a [`PolyMesh`]
    /// (`PolyMesh::from` a `TriMesh`), without that copy of the mesh.
    /// When every triangle is kept, which is the common case, the corner
    /// table is filled in parallel runs (the modeller counts a
    /// million-triangle sculpture after every stroke); otherwise face by
    /// face under [`Soup::new`]'s rules.
    pub(crate) fn of_triangles(vertex_count: usize, triangles: &[[u32; 3]]) -> Soup {
        let n = vertex_count.min(u32::MAX as usize);
        let corners = 3 * triangles.len();
        let all_kept = corners <= i32::MAX as usize
            && triangles
                .par_iter()
                .with_min_len(PARALLEL_RUN)
                .all(|t| t.iter().all(|&i| (i as usize) < n));
        if !all_kept {
            let offsets: Vec<u32> = (0..=triangles.len()).map(|f| (3 * f) as u32).collect();
            return Soup::of_faces(vertex_count, &offsets, triangles.as_flattened());
        }
        // Each triangle's corners c, c + 1, c + 2 in a cycle.
        let corner = (0..corners as u32)
            .into_par_iter()
            .with_min_len(PARALLEL_RUN);
        Soup {
            vert: triangles.as_flattened().to_vec(),
            next: corner
                .clone()
                .map(|c| if c % 3 == 2 { c - 2 } else { c + 1 })
                .collect(),
            prev: corner
                .map(|c| if c % 3 == 0 { c + 2 } else { c - 1 })
                .collect(),
            start: (0..triangles.len() as u32 + 1)
                .into_par_iter()
                .with_min_len(PARALLEL_RUN)
                .map(|f| 3 * f)
                .collect(),
            invalid_faces: 0,
        }
    }

    /// [`Soup::new`] of the faces `face_offsets` and `face_indices` give
    /// over `vertex_count` positions.
    fn of_faces(vertex_count: usize, face_offsets: &[u32], face_indices: &[u32]) -> Soup {
        let n = vertex_count.min(u32::MAX as usize);
        let face_count = face_offsets.len().saturating_sub(1);
        let mut soup = Soup {
            vert: Vec::with_capacity(face_indices.len()),
            next: Vec::with_capacity(face_indices.len()),
            prev: Vec::with_capacity(face_indices.len()),
            start: Vec::with_capacity(face_count + 1),
            invalid_faces: 0,
        };
        soup.start.push(0);
        for w in face_offsets.windows(2) {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let face = match face_indices.get(a..b) {
                Some(face) if !face.is_empty() && face.iter().all(|&i| (i as usize) < n) => face,
                _ => {
                    soup.invalid_faces += 1;
                    continue;
                }
            };
            let base = soup.vert.len();
            // Corner ids are u32, and the link entries of the topology pass
            // need one bit more; a soup whose (possibly overlapping) faces
            // add up to more corners than 2^31 cannot be indexed, so the
            // excess is reported instead of wrapping around.
            if base + face.len() > i32::MAX as usize {
                soup.invalid_faces += 1;
                continue;
            }
            soup.vert.extend_from_slice(face);
            let end = (base + face.len()) as u32;
            soup.next.extend((base as u32 + 1)..end);
            soup.next.push(base as u32);
            soup.prev.push(end - 1);
            soup.prev.extend(base as u32..end - 1);
            soup.start.push(end);
        }
        soup
    }

    pub(crate) fn corner_count(&self) -> usize {
        self.vert.len()
    }

    /// Kept faces in order.
    pub(crate) fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.start
            .windows(2)
            .map(|w| &self.vert[w[0] as usize..w[1] as usize])
    }
}
