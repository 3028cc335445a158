//! The valid part of a [`PolyMesh`], copied into a compact corner table.

use crate::PolyMesh;

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
        let n = mesh.positions.len().min(u32::MAX as usize);
        let face_count = mesh.face_offsets.len().saturating_sub(1);
        let mut soup = Soup {
            vert: Vec::with_capacity(mesh.face_indices.len()),
            next: Vec::with_capacity(mesh.face_indices.len()),
            prev: Vec::with_capacity(mesh.face_indices.len()),
            start: Vec::with_capacity(face_count + 1),
            invalid_faces: 0,
        };
        soup.start.push(0);
        for w in mesh.face_offsets.windows(2) {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let face = match mesh.face_indices.get(a..b) {
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
