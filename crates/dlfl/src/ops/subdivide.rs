use glam::DVec3;

use crate::error::Result;
use crate::ids::{EdgeId, VertexId};
use crate::mesh::{Edge, Mesh};

/// The result of subdividing an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Subdivided {
    /// The new vertex.
    pub vertex: VertexId,
    /// The half from the edge's first end (the vertex of its first corner)
    /// to the new vertex, and the half from the new vertex to the second end.
    pub edges: [EdgeId; 2],
}

impl Mesh {
    /// `SubDivideEdge(e)` (§III.2): a new vertex at the edge's midpoint
    /// splits it in two. Topology is unchanged: V+1, E+1, and each face
    /// beside the edge gains a corner.
    ///
    /// The thesis composes it from `CreateVertex`, two `InsertEdge`s and a
    /// `DeleteEdge` ([`Mesh::subdivide_edge_fundamental`]). That sequence
    /// retires the corners at which `e` started; this direct version
    /// produces the same mesh in O(1) and keeps every existing corner
    /// handle valid, which operators that subdivide while holding corners
    /// (such as [`Mesh::create_pipe`]) rely on.
    pub fn subdivide_edge(&mut self, e: EdgeId) -> Result<Subdivided> {
        self.subdivide_edge_at(e, 0.5)
    }

    /// Like [`Mesh::subdivide_edge`], placing the new vertex at parameter `t`
    /// from the edge's first end (the vertex of `edge_corners(e)[0]`) to its second.
    pub fn subdivide_edge_at(&mut self, e: EdgeId, t: f64) -> Result<Subdivided> {
        let ei = self.check_edge(e)?;
        let [a0, b0] = self.e(ei).corners;
        let (va, vb) = (self.c(a0).vertex, self.c(b0).vertex);
        let p = self.v(va).position.lerp(self.v(vb).position, t);
        crate::mesh::check_finite(p)?;
        let (vm, ma, mb, e2) = self.subdivide_raw(ei, p);
        let _ = (ma, mb);
        Ok(Subdivided {
            vertex: self.vid(vm),
            edges: [self.eid(ei), self.eid(e2)],
        })
    }

    /// Splits edge `ei` at point `p`. Returns the new vertex, its corners in
    /// the first and second side's faces, and the new edge (from the new
    /// vertex to the second end); `ei` keeps the first half.
    pub(crate) fn subdivide_raw(&mut self, ei: u32, p: DVec3) -> (u32, u32, u32, u32) {
        let [a0, b0] = self.e(ei).corners;
        let (fa, fb) = (self.c(a0).face, self.c(b0).face);
        let (vm, _) = self.vertices.insert(crate::mesh::Vertex {
            position: p,
            corner: crate::mesh::NONE,
            count: 0,
        });
        // Side a: a0 (va) -> ma (vm) -> a1 (vb); side b: b0 (vb) -> mb (vm) -> b1 (va).
        let ma = self.new_corner(vm, fa);
        let mb = self.new_corner(vm, fb);
        let a1 = self.c(a0).next;
        self.link(a0, ma);
        self.link(ma, a1);
        let b1 = self.c(b0).next;
        self.link(b0, mb);
        self.link(mb, b1);
        // Edge ei now joins a0 (va->vm) and mb (vm->va); the new edge joins
        // ma (vm->vb) and b0 (vb->vm).
        let (e2, _) = self.edges.insert(Edge { corners: [ma, b0] });
        self.edges.get_mut(ei).corners = [a0, mb];
        self.c_mut(mb).edge = ei;
        self.c_mut(ma).edge = e2;
        self.c_mut(b0).edge = e2;
        self.f_mut(fa).len += 1;
        self.f_mut(fb).len += 1;
        (vm, ma, mb, e2)
    }

    /// `SubDivideEdge(e)` exactly as §III.2 lists it: `CreateVertex` at the
    /// midpoint, `InsertEdge` from each end's corner in one adjacent face to
    /// the new point-sphere's corner, then `DeleteEdge(e)`. The resulting
    /// mesh equals [`Mesh::subdivide_edge`]'s, but the corners at which `e`
    /// started are retired. Kept as the thesis-faithful reference.
    pub fn subdivide_edge_fundamental(&mut self, e: EdgeId) -> Result<Subdivided> {
        let ei = self.check_edge(e)?;
        let [a0, _] = self.e(ei).corners;
        let c1 = self.cid(a0);
        let c2 = self.cid(self.c(a0).next);
        let [v1, v2] = self.edge_vertices(e)?;
        let pm = (self.position(v1)? + self.position(v2)?) * 0.5;
        let (vm, _, cm) = self.create_vertex(pm)?;
        let e1 = self.insert_edge(c1, cm)?;
        let e2 = self.insert_edge(c2, cm)?;
        self.delete_edge(e)?;
        Ok(Subdivided {
            vertex: vm,
            edges: [e1, e2],
        })
    }

    /// Trisects an edge: two new vertices at 1/3 and 2/3 from its first end.
    /// Returns them in that order, and the three edges from the first end on.
    pub fn trisect_edge(&mut self, e: EdgeId) -> Result<([VertexId; 2], [EdgeId; 3])> {
        let first = self.subdivide_edge_at(e, 1.0 / 3.0)?;
        // The second half runs from the new vertex to the far end.
        let second = self.subdivide_edge_at(first.edges[1], 0.5)?;
        Ok((
            [first.vertex, second.vertex],
            [first.edges[0], second.edges[0], second.edges[1]],
        ))
    }
}
