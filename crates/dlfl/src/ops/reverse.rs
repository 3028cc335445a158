use crate::error::{Error, Result};
use crate::ids::FaceId;
use crate::mesh::{Mesh, NONE};

impl Mesh {
    /// Reverses the orientation of a set of faces: every face walk is read
    /// backwards, which swaps inside and outside (§V.1: "reverse the
    /// normals of the faces of the offset mesh").
    ///
    /// An orientable DLFL cannot mix orientations across an edge, so the
    /// set must be a union of whole components; otherwise
    /// [`Error::NotWholeComponents`] names a face on the set's border and
    /// nothing changes. Duplicates in `faces` are ignored.
    pub fn reverse_faces(&mut self, faces: &[FaceId]) -> Result<()> {
        let mut in_set = vec![false; self.faces.capacity_slots()];
        let mut list = Vec::with_capacity(faces.len());
        for &f in faces {
            let fi = self.check_face(f)?;
            if !in_set[fi as usize] {
                in_set[fi as usize] = true;
                list.push(fi);
            }
        }
        let mut corners = Vec::new();
        for &f in &list {
            for c in self.face_corner_slots(f) {
                let e = self.c(c).edge;
                if e != NONE {
                    let far = self.mate(c, e);
                    if !in_set[self.c(far).face as usize] {
                        return Err(Error::NotWholeComponents(self.fid(f)));
                    }
                }
                corners.push(c);
            }
        }
        self.reverse_corners(&corners);
        Ok(())
    }

    /// Reverses the orientation of the whole component containing `face`.
    pub fn reverse_component(&mut self, face: FaceId) -> Result<()> {
        let f0 = self.check_face(face)?;
        let faces = self.component_face_indices(f0);
        let mut corners = Vec::new();
        for f in faces {
            corners.extend(self.face_corner_slots(f));
        }
        self.reverse_corners(&corners);
        Ok(())
    }

    /// The faces of the component containing face `f0`, found by walking
    /// across edges.
    pub(crate) fn component_face_indices(&self, f0: u32) -> Vec<u32> {
        let mut seen = vec![false; self.faces.capacity_slots()];
        let mut stack = vec![f0];
        let mut out = Vec::new();
        seen[f0 as usize] = true;
        while let Some(f) = stack.pop() {
            out.push(f);
            for c in self.face_corner_slots(f) {
                let e = self.c(c).edge;
                if e != NONE {
                    let g = self.c(self.mate(c, e)).face;
                    if !seen[g as usize] {
                        seen[g as usize] = true;
                        stack.push(g);
                    }
                }
            }
        }
        out
    }

    /// The faces of the component containing `face`.
    pub fn component_faces(&self, face: FaceId) -> Result<Vec<FaceId>> {
        let f0 = self.check_face(face)?;
        Ok(self
            .component_face_indices(f0)
            .into_iter()
            .map(|f| self.fid(f))
            .collect())
    }

    /// Reverses every face walk through `corners`, which must be all the
    /// corners of a union of components. Read backwards, the edge that
    /// started at `c` now starts at the old `next(c)`, and `c` starts the
    /// edge that used to end at it.
    fn reverse_corners(&mut self, corners: &[u32]) {
        let mut new_edge = Vec::with_capacity(corners.len());
        for &c in corners {
            let cc = *self.c(c);
            new_edge.push(self.c(cc.prev).edge);
            if cc.edge != NONE {
                let e = self.edges.get_mut(cc.edge);
                let side = usize::from(e.corners[0] != c);
                e.corners[side] = cc.next;
            }
        }
        for (&c, &e) in corners.iter().zip(&new_edge) {
            let cm = self.c_mut(c);
            std::mem::swap(&mut cm.next, &mut cm.prev);
            cm.edge = e;
        }
    }
}
