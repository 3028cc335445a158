use crate::error::{Error, Result};
use crate::ids::{CornerId, EdgeId, FaceId};
use crate::mesh::{Mesh, NONE};

impl Mesh {
    /// `ConnectEdges({e1, f1}, {e2, f2})` (§III.5). Each half-edge is given
    /// by the corner at which it starts in its face (`c1` starts `e1` in
    /// `f1`). Inserts an edge from the start of `e1` to the end of `e2`, then
    /// one from the end of `e1` to the start of `e2`, making a new
    /// quadrilateral bounded by `e1`, `e2` and the two new edges.
    ///
    /// In one face this splits it into three; across two faces the first
    /// insertion adds a handle (or joins components) and the second splits,
    /// so the face count is unchanged. Returns the new face and edges.
    pub fn connect_edges(&mut self, c1: CornerId, c2: CornerId) -> Result<(FaceId, [EdgeId; 2])> {
        let s1 = self.check_corner(c1)?;
        let s2 = self.check_corner(c2)?;
        for (c, id) in [(s1, c1), (s2, c2)] {
            if self.c(c).edge == NONE {
                return Err(Error::PointSphereFace(self.corner_face(id)?));
            }
        }
        if self.c(s1).edge == self.c(s2).edge {
            return Err(Error::SameEdge(self.eid(self.c(s1).edge)));
        }
        let (t1, t2) = (self.c(s1).next, self.c(s2).next);
        if t2 == s1 || t1 == s2 {
            return Err(Error::Invalid(
                "the two half-edges are consecutive in one face; the connecting edge would be degenerate".into(),
            ));
        }
        let ea = self.insert_edge_raw(s1, t2);
        let eb = self.insert_edge_raw(t1, s2);
        Ok((self.fid(self.c(s1).face), [self.eid(ea), self.eid(eb)]))
    }
}
