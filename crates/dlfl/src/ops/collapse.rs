use crate::error::{Error, Result};
use crate::ids::{EdgeId, VertexId};
use crate::mesh::Mesh;

impl Mesh {
    /// `CollapseEdge(e)` (§III.6): merges the edge's second end into its
    /// first and puts the merged vertex at the midpoint. V−1, E−1, F and
    /// genus unchanged: a triangle beside the edge becomes a two-gon, as in
    /// the thesis (remove those with [`Mesh::remove_two_gons`]).
    ///
    /// The thesis lists this as `InsertEdge`s from the corners after the
    /// second end's corners to a corner of the first end, followed by
    /// `DeleteEdgeWithCleanup` of the second end's edges. Inserted in
    /// arbitrary corner order those edges pass through intermediate
    /// handles, so the kernel instead splices the second end's corners into
    /// the first end's rotation directly, which yields the same mesh in
    /// O(valence). Returns the surviving vertex. Self-loops are refused.
    pub fn collapse_edge(&mut self, e: EdgeId) -> Result<VertexId> {
        let ei = self.check_edge(e)?;
        let [a0, b0] = self.e(ei).corners;
        let (v1, v2) = (self.c(a0).vertex, self.c(b0).vertex);
        if v1 == v2 {
            return Err(Error::SelfLoop(e));
        }
        let mid = (self.v(v1).position + self.v(v2).position) * 0.5;
        let (a1, b1, pa, pb) = (
            self.c(a0).next,
            self.c(b0).next,
            self.c(a0).prev,
            self.c(b0).prev,
        );
        let (fa, fb) = (self.c(a0).face, self.c(b0).face);
        if a1 == b0 || b1 == a0 {
            // An end of valence 1: deleting the edge leaves it a point-sphere.
            let [sa, sb] = self.delete_edge_raw(ei);
            // Keep v1 unless it is the valence-1 end and v2 is not.
            let (keep, gone) = if sa != crate::mesh::NONE && sb == crate::mesh::NONE {
                (v2, v1)
            } else {
                (v1, v2)
            };
            let gone = self.vid(gone);
            self.delete_vertex(gone)?;
            self.v_mut(keep).position = mid;
            return Ok(self.vid(keep));
        }
        self.link(pa, a1);
        self.link(pb, b1);
        self.ring_remove(a0);
        self.ring_remove(b0);
        // Move the second end's corners to the first end.
        while self.v(v2).count > 0 {
            let c = self.v(v2).corner;
            self.ring_remove(c);
            self.c_mut(c).vertex = v1;
            self.ring_insert(v1, c);
        }
        self.f_mut(fa).len -= 1;
        self.f_mut(fb).len -= 1;
        // When both sides are one face, the start corner may be the other removed one.
        for f in [fa, fb] {
            let c = self.f(f).corner;
            if c == a0 {
                self.f_mut(f).corner = a1;
            } else if c == b0 {
                self.f_mut(f).corner = b1;
            }
        }
        self.corners.remove(a0);
        self.corners.remove(b0);
        self.edges.remove(ei);
        self.vertices.remove(v2);
        self.v_mut(v1).position = mid;
        Ok(self.vid(v1))
    }
}
