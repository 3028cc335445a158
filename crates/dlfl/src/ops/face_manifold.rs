use glam::DVec3;

use crate::error::{Error, Result};
use crate::ids::{FaceId, VertexId};
use crate::mesh::Mesh;

/// The two faces made by [`Mesh::create_face_manifold`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceManifold {
    /// The face whose corners follow the points in the given order.
    pub front: FaceId,
    /// The same vertices in reverse order.
    pub back: FaceId,
    /// The new vertices, one per point, in order.
    pub vertices: Vec<VertexId>,
}

impl Mesh {
    /// `CreateFaceManifold(p0, …, pN−1)` (§III.4): a new sphere made of two
    /// faces on the same N vertices, one in the given order and one
    /// reversed. Built as the thesis lists it: N `CreateVertex`, then
    /// `InsertEdge(c_i, c_(i+1) mod N)`. Needs N ≥ 2 finite points.
    pub fn create_face_manifold(&mut self, points: &[DVec3]) -> Result<FaceManifold> {
        if points.len() < 2 {
            return Err(Error::Invalid(format!(
                "a face manifold needs at least 2 points, got {}",
                points.len()
            )));
        }
        for p in points {
            crate::mesh::check_finite(*p)?;
        }
        let mut vertices = Vec::with_capacity(points.len());
        let mut corners = Vec::with_capacity(points.len());
        for p in points {
            let (v, _, c) = self.create_vertex(*p)?;
            vertices.push(v);
            corners.push(c);
        }
        let n = corners.len();
        for i in 0..n {
            self.insert_edge(corners[i], corners[(i + 1) % n])?;
        }
        Ok(FaceManifold {
            front: self.corner_face(corners[0])?,
            back: self.corner_face(corners[n - 1])?,
            vertices,
        })
    }
}
