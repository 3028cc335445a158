//! Full structural validation of a DLFL.

use crate::mesh::{Mesh, NONE};

/// The first inconsistency [`Mesh::validate`] found.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid DLFL: {0}")]
pub struct ValidationError(pub String);

macro_rules! ensure {
    ($cond:expr, $($arg:tt)*) => {
        if !$cond {
            return Err(ValidationError(format!($($arg)*)));
        }
    };
}

impl Mesh {
    /// Checks every link of the structure and that the surface is a
    /// 2-manifold:
    ///
    /// - corners point to live vertices, faces and edges, and `next`/`prev`
    ///   are inverse and stay within the face;
    /// - each face's walk has exactly `len` corners, all naming the face;
    /// - each edge's two origin corners name it, and run in opposite
    ///   directions between the same two vertices;
    /// - a corner lacks an edge exactly when it is a point-sphere;
    /// - each vertex's corner ring is consistent and non-empty;
    /// - each vertex's **rotation** (the cyclic order of its corners taken
    ///   through the faces) is exactly one cycle holding all its corners;
    ///   otherwise the surface is not a 2-manifold at that vertex.
    ///
    /// Cost is linear in the number of corners.
    pub fn validate(&self) -> Result<(), ValidationError> {
        let nc = self.corners.capacity_slots();
        // Corners.
        let mut in_faces = 0usize;
        for c in self.corners.live_indices() {
            let cc = self.c(c);
            ensure!(
                self.vertices.is_live(cc.vertex),
                "corner {c} names dead vertex {}",
                cc.vertex
            );
            ensure!(
                self.faces.is_live(cc.face),
                "corner {c} names dead face {}",
                cc.face
            );
            ensure!(
                self.corners.is_live(cc.next) && self.corners.is_live(cc.prev),
                "corner {c} links to a dead corner"
            );
            ensure!(
                self.c(cc.next).prev == c,
                "corner {c}: next.prev is not the corner"
            );
            ensure!(
                self.c(cc.prev).next == c,
                "corner {c}: prev.next is not the corner"
            );
            ensure!(
                self.c(cc.next).face == cc.face,
                "corner {c}: next corner is in another face"
            );
            ensure!(
                self.corners.is_live(cc.vnext) && self.corners.is_live(cc.vprev),
                "corner {c}: vertex ring links to a dead corner"
            );
            ensure!(
                self.c(cc.vnext).vprev == c,
                "corner {c}: vertex ring is not doubly linked"
            );
            ensure!(
                self.c(cc.vnext).vertex == cc.vertex,
                "corner {c}: vertex ring leaves its vertex"
            );
            let f = self.f(cc.face);
            if cc.edge == NONE {
                ensure!(
                    f.len == 1 && cc.next == c,
                    "corner {c} has no edge but is not a point-sphere"
                );
            } else {
                ensure!(
                    self.edges.is_live(cc.edge),
                    "corner {c} names dead edge {}",
                    cc.edge
                );
                let [a, b] = self.e(cc.edge).corners;
                ensure!(
                    a == c || b == c,
                    "corner {c}: its edge {} does not start here",
                    cc.edge
                );
            }
        }
        // Faces.
        for f in self.faces.live_indices() {
            let fx = self.f(f);
            ensure!(fx.len >= 1, "face {f} is empty");
            ensure!(
                self.corners.is_live(fx.corner),
                "face {f} starts at a dead corner"
            );
            let mut c = fx.corner;
            for k in 0..fx.len {
                ensure!(
                    self.c(c).face == f,
                    "face {f}: corner {c} at step {k} names face {}",
                    self.c(c).face
                );
                c = self.c(c).next;
            }
            ensure!(
                c == fx.corner,
                "face {f}: walk of {} corners does not close",
                fx.len
            );
            in_faces += fx.len as usize;
        }
        ensure!(
            in_faces == self.corners.len(),
            "faces hold {in_faces} corners, mesh has {}",
            self.corners.len()
        );
        // Edges.
        for e in self.edges.live_indices() {
            let [a, b] = self.e(e).corners;
            ensure!(a != b, "edge {e} has one corner on both sides");
            ensure!(
                self.corners.is_live(a) && self.corners.is_live(b),
                "edge {e} names a dead corner"
            );
            ensure!(
                self.c(a).edge == e && self.c(b).edge == e,
                "edge {e}: its corners do not start it"
            );
            let (ca, cb) = (self.c(a), self.c(b));
            ensure!(
                self.c(ca.next).vertex == cb.vertex && self.c(cb.next).vertex == ca.vertex,
                "edge {e}: its two sides do not run oppositely between the same vertices"
            );
        }
        // Vertices: ring sizes, then rotation cycles.
        let mut ring_total = 0usize;
        for v in self.vertices.live_indices() {
            let vx = self.v(v);
            ensure!(vx.count >= 1, "vertex {v} has no corner");
            ensure!(
                self.corners.is_live(vx.corner),
                "vertex {v} starts at a dead corner"
            );
            let mut c = vx.corner;
            for _ in 0..vx.count {
                ensure!(
                    self.c(c).vertex == v,
                    "vertex {v}: ring holds corner {c} of another vertex"
                );
                c = self.c(c).vnext;
            }
            ensure!(
                c == vx.corner,
                "vertex {v}: ring of {} corners does not close",
                vx.count
            );
            ring_total += vx.count as usize;
        }
        ensure!(
            ring_total == self.corners.len(),
            "vertex rings hold {ring_total} corners, mesh has {}",
            self.corners.len()
        );
        // Rotation: each vertex's corners form one cycle of `rot`.
        let mut seen = vec![false; nc];
        for v in self.vertices.live_indices() {
            let vx = self.v(v);
            let start = vx.corner;
            let mut c = start;
            let mut n = 0u32;
            loop {
                ensure!(
                    !seen[c as usize],
                    "vertex {v}: rotation revisits corner {c}"
                );
                seen[c as usize] = true;
                ensure!(
                    self.c(c).vertex == v,
                    "vertex {v}: rotation reaches corner {c} of another vertex"
                );
                n += 1;
                c = self.rot(c);
                if c == start {
                    break;
                }
                ensure!(
                    n < vx.count,
                    "vertex {v}: rotation does not return to its start"
                );
            }
            ensure!(
                n == vx.count,
                "vertex {v} is not a 2-manifold point: its rotation covers {n} of its {} corners",
                vx.count
            );
        }
        Ok(())
    }
}
