use glam::DVec3;

use crate::NonFinite;

/// An indexed polygon mesh: positions, and faces as lists of vertex
/// indices stored in compressed rows (`face_offsets` has one entry per
/// face plus a final one). Nothing about its topology is assumed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolyMesh {
    /// Vertex positions, which faces refer to by index (some may be unused).
    pub positions: Vec<DVec3>,
    /// Where each face starts in `face_indices`, then where the last one ends:
    /// face `f` is `face_indices[face_offsets[f]..face_offsets[f + 1]]`.
    pub face_offsets: Vec<u32>,
    /// The corners of all faces, concatenated face after face, as indices
    /// into `positions`.
    pub face_indices: Vec<u32>,
}

/// A structural problem in a [`PolyMesh`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolyMeshError {
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
    /// A position has a NaN or infinite coordinate (the first such vertex).
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// `face_offsets` does not start at 0, does not end at
    /// `face_indices.len()`, or decreases somewhere.
    #[error("face offsets are malformed")]
    Offsets,
    /// The mesh has this many positions, too many for 32-bit indices (at
    /// least `u32::MAX`).
    #[error("{0} entries exceed 32-bit indices")]
    TooLarge(usize),
}

impl PolyMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        PolyMesh {
            positions: Vec::new(),
            face_offsets: vec![0],
            face_indices: Vec::new(),
        }
    }

    /// Builds a mesh from positions and per-face index lists.
    pub fn from_faces<F: AsRef<[u32]>>(
        positions: Vec<DVec3>,
        faces: impl IntoIterator<Item = F>,
    ) -> Self {
        let mut m = PolyMesh {
            positions,
            ..PolyMesh::new()
        };
        for f in faces {
            m.push_face(f.as_ref());
        }
        m
    }

    /// Number of positions (referenced or not).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }

    /// The vertex indices of face `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_indices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// All faces in order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        (0..self.face_count()).map(|f| self.face(f))
    }

    /// Appends a face.
    pub fn push_face(&mut self, face: &[u32]) {
        if self.face_offsets.is_empty() {
            self.face_offsets.push(0);
        }
        self.face_indices.extend_from_slice(face);
        self.face_offsets.push(self.face_indices.len() as u32);
    }

    /// Appends `other`'s vertices and faces (its indices shifted past this
    /// mesh's vertices): the two as one mesh, apart as they were.
    pub fn append(&mut self, other: &PolyMesh) {
        let n = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        for f in other.faces() {
            if self.face_offsets.is_empty() {
                self.face_offsets.push(0);
            }
            self.face_indices.extend(f.iter().map(|v| v + n));
            self.face_offsets.push(self.face_indices.len() as u32);
        }
    }

    /// The mesh moved by `offset`, its faces as they are.
    pub fn translated(&self, offset: DVec3) -> PolyMesh {
        self.transformed(|p| p + offset)
    }

    /// The mesh with every position mapped by `f` (an affine map, a
    /// projection, anything), its faces as they are.
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3) -> PolyMesh {
        let mut m = self.clone();
        for p in &mut m.positions {
            *p = f(*p);
        }
        m
    }

    /// Checks offsets, index ranges and finiteness of positions.
    pub fn check(&self) -> Result<(), PolyMeshError> {
        if self.positions.len() >= u32::MAX as usize {
            return Err(PolyMeshError::TooLarge(self.positions.len()));
        }
        if self.face_offsets.first() != Some(&0)
            || self.face_offsets.last().map(|&o| o as usize) != Some(self.face_indices.len())
            || self.face_offsets.windows(2).any(|w| w[1] < w[0])
        {
            return Err(PolyMeshError::Offsets);
        }
        NonFinite::check("vertex", &self.positions)?;
        let n = self.positions.len();
        for f in 0..self.face_count() {
            if let Some(&index) = self.face(f).iter().find(|&&i| i as usize >= n) {
                return Err(PolyMeshError::IndexOutOfRange {
                    face: f,
                    index,
                    count: n,
                });
            }
        }
        Ok(())
    }

    /// Triangulates every face as a fan from its first corner (faces with
    /// fewer than three corners are dropped). Returns the triangles and,
    /// for each, the face it came from.
    pub fn fan_triangles(&self) -> (Vec<[u32; 3]>, Vec<u32>) {
        let mut tris = Vec::with_capacity(self.face_indices.len());
        let mut origin = Vec::with_capacity(self.face_indices.len());
        for (f, face) in self.faces().enumerate() {
            for k in 1..face.len().saturating_sub(1) {
                tris.push([face[0], face[k], face[k + 1]]);
                origin.push(f as u32);
            }
        }
        (tris, origin)
    }

    /// The triangle mesh of this soup: every face fanned from its first
    /// corner ([`PolyMesh::fan_triangles`]), the positions as they are.
    pub fn triangulated(&self) -> crate::tri::TriMesh {
        let (triangles, _) = self.fan_triangles();
        crate::tri::TriMesh {
            positions: self.positions.clone(),
            triangles,
        }
    }

    /// Axis-aligned bounds of the referenced vertices, or `None` if no face
    /// refers to any vertex.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut it = self
            .face_indices
            .iter()
            .filter_map(|&i| self.positions.get(i as usize).copied());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}

impl From<&PolyMesh> for crate::tri::TriMesh {
    /// [`PolyMesh::triangulated`].
    fn from(soup: &PolyMesh) -> crate::tri::TriMesh {
        soup.triangulated()
    }
}

impl From<crate::tri::TriMesh> for PolyMesh {
    /// The triangles as faces of three corners, the positions as they are
    /// (unreferenced ones included).
    fn from(mesh: crate::tri::TriMesh) -> PolyMesh {
        PolyMesh {
            face_offsets: (0..=mesh.triangles.len() as u32).map(|f| 3 * f).collect(),
            face_indices: mesh.triangles.iter().flatten().copied().collect(),
            positions: mesh.positions,
        }
    }
}

impl From<&crate::tri::TriMesh> for PolyMesh {
    /// As `From<TriMesh>`, copying.
    fn from(mesh: &crate::tri::TriMesh) -> PolyMesh {
        PolyMesh::from(mesh.clone())
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::PolyMesh;

    #[test]
    fn append_and_translated_join_two_soups_apart() {
        let quad = PolyMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            [[0u32, 1, 2, 3]],
        );
        let tri = PolyMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], [[0u32, 2, 1]]);
        let mut both = quad.clone();
        both.append(&tri.translated(DVec3::Z));
        assert_eq!(both.face_count(), 2);
        assert_eq!(both.face(0), quad.face(0));
        assert_eq!(both.face(1), &[4, 6, 5]);
        assert_eq!(both.positions[5], DVec3::new(1.0, 0.0, 1.0));
        assert_eq!(both.check(), Ok(()));
        // Into an empty soup with no offsets yet.
        let mut empty = PolyMesh::default();
        empty.append(&tri);
        assert_eq!(
            empty,
            PolyMesh::from_faces(tri.positions.clone(), [[0u32, 2, 1]])
        );
    }
}
