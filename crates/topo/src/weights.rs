//! Vertex and edge weights of §3.4 ("Edge and vertex weights").
//!
//! Each triangle is split into three quadrilaterals by the segments from
//! its edge midpoints to its barycenter. A vertex's weight is the total
//! area of its quadrilaterals (the barycentric dual area: a third of each
//! incident triangle's area), so summing vertex weights approximates
//! surface area. An edge's weight is the total length of the
//! midpoint-to-barycenter segments that cross it, one per incident
//! triangle, so summing the weights of the edges between two regions
//! approximates the length of the curve separating them.

use glam::DVec3;

use crate::mesh::{Edges, TriMesh};

/// Weights of the vertex–edge graph.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Weights {
    /// Barycentric dual area of each vertex.
    pub vertex: Vec<f64>,
    /// Dual edge length of each edge (indexed like [`Edges::ends`]).
    pub edge: Vec<f64>,
    /// Total surface area.
    pub total_area: f64,
}

impl Weights {
    /// Weights of `mesh` at `positions` (normally the end of the frame).
    pub fn new(mesh: &TriMesh, positions: &[DVec3], edges: &Edges) -> Weights {
        let mut vertex = vec![0.0; positions.len()];
        let mut edge = vec![0.0; edges.len()];
        let mut total_area = 0.0;
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let p = tri.map(|i| positions[i as usize]);
            let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            total_area += area;
            let center = (p[0] + p[1] + p[2]) / 3.0;
            for k in 0..3 {
                vertex[tri[k] as usize] += area / 3.0;
                let mid = (p[k] + p[(k + 1) % 3]) * 0.5;
                edge[edges.of_triangle[t][k] as usize] += mid.distance(center);
            }
        }
        Weights {
            vertex,
            edge,
            total_area,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_weights() {
        let mesh = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let edges = Edges::new(&mesh);
        let w = Weights::new(&mesh, &mesh.positions, &edges);
        assert!((w.total_area - 1.0).abs() < 1e-15);
        assert!((w.vertex.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!((w.vertex[0] - 1.0 / 3.0).abs() < 1e-15);
        assert!((w.vertex[1] - 1.0 / 6.0).abs() < 1e-15);
        // The diagonal is crossed by two dual segments of length √2/6 each.
        let d = edges.of_triangle[0][2] as usize;
        assert!((w.edge[d] - 2.0 * 2f64.sqrt() / 6.0).abs() < 1e-15);
        // A boundary edge of length 1: the dual segment from (0.5, 0) to (2/3, 1/3).
        let b = edges.of_triangle[0][0] as usize;
        assert!((w.edge[b] - (1.0f64 / 36.0 + 1.0 / 9.0).sqrt()).abs() < 1e-15);
    }
}
