use crate::error::{Error, Result};
use crate::ids::{CornerId, EdgeId};
use crate::mesh::{Mesh, NONE};

impl Mesh {
    /// `CreatePipe(c1, c2)` (§III.3): joins the faces of `c1` and `c2` with
    /// a solid pipe: an edge from `c1` to `c2` and one between every further
    /// pair of matching corners, `c1`'s face read forwards and `c2`'s face
    /// backwards (the faces look at each other). Both faces are consumed;
    /// the pipe's side is a ring of quadrilaterals.
    ///
    /// Genus rises by one when the faces are in one component; otherwise
    /// the two components join. When the faces have different numbers of
    /// corners, the longest edges of the smaller face are first subdivided
    /// until they match (the thesis's preprocessing, after \[3\]); only
    /// edges that do not border the other face are split, so that the
    /// counts converge.
    ///
    /// Returns the inserted edges, the first one joining `c1` and `c2`.
    pub fn create_pipe(&mut self, c1: CornerId, c2: CornerId) -> Result<Vec<EdgeId>> {
        let p = self.check_corner(c1)?;
        let q = self.check_corner(c2)?;
        let (f1, f2) = (self.c(p).face, self.c(q).face);
        if f1 == f2 {
            return Err(Error::SameFace(self.fid(f1)));
        }
        for f in [f1, f2] {
            if self.c(self.f(f).corner).edge == NONE {
                return Err(Error::PointSphereFace(self.fid(f)));
            }
        }
        let (l1, l2) = (self.f(f1).len, self.f(f2).len);
        if l1 != l2 {
            let (small, large) = if l1 < l2 { (f1, f2) } else { (f2, f1) };
            if self.splittable_edge(small, large).is_none() {
                return Err(Error::Invalid(format!(
                    "cannot match the corner counts of faces {} and {}: every edge of the smaller face borders one of them",
                    self.fid(small),
                    self.fid(large)
                )));
            }
            while self.f(small).len < self.f(large).len {
                let Some(e) = self.splittable_edge(small, large) else {
                    break;
                };
                let [a, b] = self.e(e).corners;
                let mid =
                    (self.v(self.c(a).vertex).position + self.v(self.c(b).vertex).position) * 0.5;
                self.subdivide_raw(e, mid);
            }
        }
        let n = self.f(f1).len as usize;
        let mut ps = Vec::with_capacity(n);
        let mut qs = Vec::with_capacity(n);
        let (mut x, mut y) = (p, q);
        for _ in 0..n {
            ps.push(x);
            qs.push(y);
            x = self.c(x).next;
            y = self.c(y).prev;
        }
        let mut edges = Vec::with_capacity(n);
        for k in 0..n {
            let e = self.insert_edge_raw(ps[k], qs[k]);
            edges.push(self.eid(e));
        }
        // The pipe's sides are surface, whatever the two faces were.
        for &e in &edges {
            let [a, b] = self.e(e.index).corners;
            for c in [a, b] {
                let f = self.c(c).face;
                self.f_mut(f).hole = false;
            }
        }
        Ok(edges)
    }

    /// The longest edge of face `f` whose other side lies in neither `f`
    /// nor `other`, so that splitting it adds exactly one corner to `f`.
    fn splittable_edge(&self, f: u32, other: u32) -> Option<u32> {
        let mut best: Option<(f64, u32)> = None;
        for c in self.face_corner_slots(f) {
            let cc = self.c(c);
            let e = cc.edge;
            let far = self.mate(c, e);
            let g = self.c(far).face;
            if g != f && g != other {
                let len = self
                    .v(cc.vertex)
                    .position
                    .distance(self.v(self.c(cc.next).vertex).position);
                if best.is_none_or(|(l, _)| len > l) {
                    best = Some((len, e));
                }
            }
        }
        best.map(|(_, e)| e)
    }
}
