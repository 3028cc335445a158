//! Move (Bernstein & Wojtan 2013, §4): a part dragged rigidly,
//!
//! ```text
//! x(t) = x₀ + m(x₀) · (pointer(t) − pointer(0)),
//! ```
//!
//! with `m = 1` on the whole connected piece under the pick (radius 0:
//! "move piece"), or with a radius the plateau falloff of that piece's
//! vertices ([`super::falloff::plateau`]: rigid in the inner half,
//! blended out to the rim). The topology changes once, at release.

use holey_topo::TriMesh;

/// The vertices of the connected component (through shared vertex
/// indices) that contains `triangle`: the rigid body the move brush holds.
pub fn component_of(mesh: &TriMesh, triangle: usize) -> Vec<bool> {
    let n = mesh.positions.len();
    let mut sets = holey_mesh::UnionFind::new(n);
    for t in &mesh.triangles {
        sets.union(t[0], t[1]);
        sets.union(t[0], t[2]);
    }
    let Some(tri) = mesh.triangles.get(triangle) else {
        return vec![false; n];
    };
    let root = sets.find(tri[0]);
    (0..n as u32).map(|v| sets.find(v) == root).collect()
}
