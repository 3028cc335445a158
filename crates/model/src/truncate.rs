//! # Truncation (TopMod's truncate vertex / edge, issue 18)
//!
//! Truncation is the conical cut of [`crate::cut`] with the offset given
//! as a fraction of each edge's length rather than as a distance, so that
//! it scales with the mesh: truncating every vertex of a polyhedron at
//! fraction `t` cuts each edge at `t` from both ends. The fraction must
//! lie strictly between 0 and 1/2; anything else (0, 1/2 or more,
//! negative, NaN) is a [`CutError`], never a crash.
//!
//! Counts (from the cut's `ΔV = s − |S|, ΔE = s − |I|, ΔF = 1 − |Φ|`):
//! truncating every vertex of a closed mesh with `V, E, F` gives
//! `2E` vertices, `3E` edges and `F + V` faces (each vertex of valence
//! `k` becomes a `k`-gon): a cube 8/12/6 → 24/36/14 (the truncated cube),
//! an icosahedron 12/30/20 → 60/90/32 (at `t = 1/3`, the soccer ball).
//! Truncating an edge between valences `k_u`, `k_w` adds
//! `k_u + k_w − 4` vertices, `k_u + k_w − 3` edges and one face.

use holey_dlfl::{EdgeId, FaceId, Mesh, VertexId};

use crate::cut::{CutError, CutOffset, CutTarget, cut_all};

/// Truncates the given vertices at `fraction` of each incident edge.
/// Returns the new face of each vertex, in order.
pub fn truncate_vertices(
    mesh: &mut Mesh,
    vertices: &[VertexId],
    fraction: f64,
) -> Result<Vec<FaceId>, CutError> {
    cut_all(
        mesh,
        vertices,
        CutTarget::Vertex,
        CutOffset::Fraction(fraction),
    )
}

/// Truncates every vertex that has an edge (point-spheres are left).
pub fn truncate_all_vertices(mesh: &mut Mesh, fraction: f64) -> Result<Vec<FaceId>, CutError> {
    let mut vertices = Vec::new();
    for v in mesh.vertices() {
        if mesh.valence(v)? > 0 {
            vertices.push(v);
        }
    }
    truncate_vertices(mesh, &vertices, fraction)
}

/// Truncates the given edges (no two may share a vertex) at `fraction` of
/// each edge leaving their ends. Returns the new face of each edge.
pub fn truncate_edges(
    mesh: &mut Mesh,
    edges: &[EdgeId],
    fraction: f64,
) -> Result<Vec<FaceId>, CutError> {
    cut_all(mesh, edges, CutTarget::Edge, CutOffset::Fraction(fraction))
}
