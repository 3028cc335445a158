use crate::error::Result;
use crate::ids::{EdgeId, VertexId};
use crate::mesh::{Mesh, NONE};

impl Mesh {
    /// `DeleteEdgeWithCleanup(e)` (§III.1): [`Mesh::delete_edge`], then
    /// [`Mesh::delete_vertex`] on any end vertex the deletion left as a
    /// point-sphere. Returns the deleted vertices.
    pub fn delete_edge_with_cleanup(&mut self, e: EdgeId) -> Result<Vec<VertexId>> {
        let ei = self.check_edge(e)?;
        let spheres = self.delete_edge_raw(ei);
        let mut deleted = Vec::new();
        for v in spheres {
            if v != NONE {
                let id = self.vid(v);
                self.delete_vertex(id)?;
                deleted.push(id);
            }
        }
        Ok(deleted)
    }
}
