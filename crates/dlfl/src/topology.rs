//! Connected components, Euler characteristic and genus.

use crate::ids::{FaceId, VertexId};
use crate::mesh::Mesh;

/// Counts of one connected component of the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ComponentTopology {
    /// Live vertices in the component.
    pub vertices: usize,
    /// Edges in the component, including those that border hole faces.
    pub edges: usize,
    /// Faces that are not holes.
    pub faces: usize,
    /// Hole faces, i.e. boundary loops of the open surface.
    pub holes: usize,
}

impl ComponentTopology {
    /// χ = V − E + F of the open surface (hole faces not counted).
    pub fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }

    /// Genus g = (2 − χ − b)/2, with b the number of boundary loops. For the
    /// closed DLFL (holes counted as faces) this is (2 − χ_closed)/2.
    pub fn genus(&self) -> i64 {
        (2 - self.euler() - self.holes as i64) / 2
    }
}

/// Per-component topology of a mesh.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Topology {
    /// Components, ordered by their smallest vertex slot.
    pub components: Vec<ComponentTopology>,
}

impl Topology {
    /// Number of connected components.
    pub fn component_count(&self) -> usize {
        self.components.len()
    }
    /// Total Euler characteristic (hole faces not counted).
    pub fn euler(&self) -> i64 {
        self.components.iter().map(|c| c.euler()).sum()
    }
    /// Total genus: the sum of the components' genera.
    pub fn genus(&self) -> i64 {
        self.components.iter().map(|c| c.genus()).sum()
    }
    /// Total number of boundary loops (hole faces).
    pub fn holes(&self) -> usize {
        self.components.iter().map(|c| c.holes).sum()
    }
}

impl Mesh {
    /// Labels each vertex slot with its component number (components are
    /// numbered by their smallest vertex slot); dead slots get `u32::MAX`.
    pub(crate) fn component_labels(&self) -> (Vec<u32>, usize) {
        let n = self.vertices.capacity_slots();
        // Roots are the smallest slot of their set, which keeps the
        // numbering deterministic.
        let mut sets = holey_mesh::UnionFind::new(n);
        for e in self.edges.live_indices() {
            let [a, b] = self.e(e).corners;
            sets.union(self.c(a).vertex, self.c(b).vertex);
        }
        let mut label = vec![u32::MAX; n];
        let mut count = 0u32;
        for v in self.vertices.live_indices() {
            let r = sets.find(v);
            if label[r as usize] == u32::MAX {
                label[r as usize] = count;
                count += 1;
            }
            label[v as usize] = label[r as usize];
        }
        (label, count as usize)
    }

    /// The component number of every live vertex, numbered by smallest vertex slot.
    pub fn vertex_components(&self) -> Vec<(VertexId, usize)> {
        let (label, _) = self.component_labels();
        self.vertices
            .live_indices()
            .map(|v| (self.vid(v), label[v as usize] as usize))
            .collect()
    }

    /// The component number of a face, consistent with [`Mesh::topology`].
    pub fn face_components(&self) -> Vec<(FaceId, usize)> {
        let (label, _) = self.component_labels();
        self.faces
            .live_indices()
            .map(|f| {
                let v = self.c(self.f(f).corner).vertex;
                (self.fid(f), label[v as usize] as usize)
            })
            .collect()
    }

    /// Counts V, E, F and holes per connected component.
    pub fn topology(&self) -> Topology {
        let (label, count) = self.component_labels();
        let mut comps = vec![
            ComponentTopology {
                vertices: 0,
                edges: 0,
                faces: 0,
                holes: 0,
            };
            count
        ];
        for v in self.vertices.live_indices() {
            comps[label[v as usize] as usize].vertices += 1;
        }
        for e in self.edges.live_indices() {
            let v = self.c(self.e(e).corners[0]).vertex;
            comps[label[v as usize] as usize].edges += 1;
        }
        for f in self.faces.live_indices() {
            let fx = self.f(f);
            let v = self.c(fx.corner).vertex;
            let comp = &mut comps[label[v as usize] as usize];
            if fx.hole {
                comp.holes += 1;
            } else {
                comp.faces += 1;
            }
        }
        Topology { components: comps }
    }

    /// V − E + F over the whole mesh, hole faces not counted.
    pub fn euler_characteristic(&self) -> i64 {
        self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64
            - self.hole_count() as i64
    }

    /// The sum of the genera of the components.
    pub fn genus(&self) -> i64 {
        self.topology().genus()
    }
}
