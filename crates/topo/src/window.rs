//! A working window for a sequence of local frames (a sculpting
//! stroke's): a superset of the triangles and vertices of
//! the surface near the brush, kept from frame to frame, so that the
//! passes a frame makes to find what its dabs touch read a few thousand
//! slots instead of every triangle of a million-triangle mesh.
//!
//! The window is a box and two sorted lists of mesh slots. Its invariant:
//! **every triangle whose corners' box meets the window's box, and every
//! vertex inside the box, is listed** (the lists may hold more). A pass
//! that looks for triangles with a vertex inside the box (or a box inside
//! it) therefore finds in the lists exactly what it finds in the whole
//! mesh, in the same order; a pass whose answer might reach past the box
//! checks that it did not ([`Window::holds_all`]) and otherwise goes over
//! the whole mesh.
//!
//! Why the invariant survives a stroke's frames:
//! - a brush moves only vertices its dabs reach, and a window is used
//!   only for frames whose reach lies inside its box. A triangle with a
//!   vertex that moves therefore met the box before the move and is
//!   listed; no unlisted triangle or vertex moves;
//! - remeshing tells the window every slot it writes
//!   ([`Window::written`]): the triangles it rewrote, made or moved into
//!   freed slots, the vertices it made or moved. Every other slot holds
//!   what it held;
//! - a frame that changes topology keeps every slot its splice does not
//!   write, and the splice reports those it does
//!   (`holey_mesh::tri::SlotChanges::written_triangles`, and the vertices
//!   it moved or made); the guard tells the window. A frame whose result
//!   was built whole renumbers everything: the stroke drops its window
//!   and builds a new one at its next frame.

use crate::TriMesh;
use glam::DVec3;
use holey_geom::Aabb;
use holey_mesh::PARALLEL_RUN;
use rayon::prelude::*;

/// See the module documentation.
#[derive(Clone, Debug)]
pub struct Window {
    lo: DVec3,
    hi: DVec3,
    /// Sorted slots of the mesh's triangles; every triangle whose box
    /// meets `[lo, hi]` is among them.
    triangles: Vec<u32>,
    /// Sorted slots of the mesh's vertices; every vertex in `[lo, hi]` is
    /// among them.
    vertices: Vec<u32>,
    /// The numbers of triangles and vertices of the mesh the lists are
    /// of ([`Window::fits`]).
    sizes: (usize, usize),
}

impl Window {
    /// The window of `mesh` over the box `[lo, hi]`: one pass over its
    /// vertices and one over its triangles, in parallel runs. A triangle's
    /// box misses the window's exactly when its three corners lie beyond
    /// one face of it ([`Aabb::outcode`]).
    pub fn build(mesh: &TriMesh, lo: DVec3, hi: DVec3) -> Window {
        let code = outcodes(&Aabb::new(lo, hi), &mesh.positions);
        let vertices = code
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .enumerate()
            .filter(|(_, c)| **c == 0)
            .map(|(v, _)| v as u32)
            .collect();
        let triangles = mesh
            .triangles
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .enumerate()
            .filter(|(_, t)| {
                // Indices the mesh does not have are the engine's to
                // report; the window lists such a triangle, never panics.
                corners_meet_box(&code, t)
            })
            .map(|(t, _)| t as u32)
            .collect();
        Window {
            lo,
            hi,
            triangles,
            vertices,
            sizes: (mesh.triangles.len(), mesh.positions.len()),
        }
    }

    /// Whether `mesh` has as many triangles and vertices as the mesh the
    /// window was built for and last told of: every listed slot is then
    /// one of `mesh`'s. A window of some other mesh is not read (the
    /// engine reads the whole mesh instead), so a wrong window cannot
    /// index past a mesh's end.
    pub fn fits(&self, mesh: &TriMesh) -> bool {
        self.sizes == (mesh.triangles.len(), mesh.positions.len())
    }

    /// Whether the box `[lo, hi]` lies inside the window's.
    pub fn holds_box(&self, lo: DVec3, hi: DVec3) -> bool {
        lo.cmpge(self.lo).all() && hi.cmple(self.hi).all()
    }

    /// Whether `p` lies inside the window's box.
    pub fn holds(&self, p: DVec3) -> bool {
        p.cmpge(self.lo).all() && p.cmple(self.hi).all()
    }

    /// Whether every vertex `vertices` names lies inside the window's box:
    /// then every triangle at one of them is listed.
    pub fn holds_all(&self, mesh: &TriMesh, vertices: impl IntoIterator<Item = u32>) -> bool {
        vertices.into_iter().all(|v| {
            mesh.positions
                .get(v as usize)
                .is_some_and(|&p| self.holds(p))
        })
    }

    /// The listed vertices `pick` takes, in mesh order.
    pub fn vertices_where(&self, pick: impl Fn(u32) -> bool + Sync) -> Vec<u32> {
        self.vertices
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .copied()
            .filter(|&v| pick(v))
            .collect()
    }

    /// The listed triangles' slots, in mesh order.
    pub fn triangles(&self) -> &[u32] {
        &self.triangles
    }

    /// The listed vertices' slots, in mesh order.
    pub fn vertices(&self) -> &[u32] {
        &self.vertices
    }

    /// The listed triangles with a vertex `pick` takes, in mesh order: what
    /// [`holey_mesh::tri::triangles_with_vertex`] finds in the whole mesh
    /// when every vertex `pick` takes lies in the window's box.
    pub fn triangles_with_vertex(
        &self,
        triangles: &[[u32; 3]],
        pick: impl Fn(u32) -> bool + Sync,
    ) -> Vec<usize> {
        self.triangles
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .filter(|&&t| triangles[t as usize].iter().any(|&v| pick(v)))
            .map(|&t| t as usize)
            .collect()
    }

    /// Takes in the slots a remeshing run wrote into `mesh` (already
    /// written): `triangles` it rewrote, filled or appended, `vertices` it
    /// made or moved. Slots past the mesh's end (removed) leave the lists.
    pub fn written(&mut self, mesh: &TriMesh, triangles: &[u32], vertices: &[u32]) {
        merge_into(&mut self.triangles, triangles, mesh.triangles.len());
        merge_into(&mut self.vertices, vertices, mesh.positions.len());
        self.sizes = (mesh.triangles.len(), mesh.positions.len());
    }

    /// The first triangle or vertex of `mesh` the invariant misses (a
    /// triangle meeting the box, or a vertex in it, that is not listed):
    /// `None` when it holds. A whole-mesh check, for tests.
    pub fn misses(&self, mesh: &TriMesh) -> Option<String> {
        let full = Window::build(mesh, self.lo, self.hi);
        if let Some(t) = full
            .triangles
            .iter()
            .find(|t| self.triangles.binary_search(t).is_err())
        {
            return Some(format!("triangle {t}"));
        }
        full.vertices
            .iter()
            .find(|v| self.vertices.binary_search(v).is_err())
            .map(|v| format!("vertex {v}"))
    }
}

/// Each point's [`Aabb::outcode`] against `region`, in parallel runs: a
/// whole-mesh scan then reads a byte per triangle corner.
pub fn outcodes(region: &Aabb, points: &[DVec3]) -> Vec<u8> {
    points
        .par_iter()
        .with_min_len(PARALLEL_RUN)
        .map(|&p| region.outcode(p))
        .collect()
}

/// Whether the box of the triangle `tri` meets the box whose
/// [`outcodes`] `code` holds for its corners: it misses exactly when all
/// three corners lie beyond one face (their codes share a bit). A corner
/// `code` does not have counts as inside, so a bad index is listed, not
/// a panic.
pub fn corners_meet_box(code: &[u8], tri: &[u32; 3]) -> bool {
    tri.iter()
        .map(|&v| code.get(v as usize).copied().unwrap_or(0))
        .fold(0x3f, |a, c| a & c)
        == 0
}

/// Merges the slots of `more` below `len` into the sorted `list`, and
/// drops `list`'s slots at or past `len`.
fn merge_into(list: &mut Vec<u32>, more: &[u32], len: usize) {
    list.retain(|&s| (s as usize) < len);
    if more.is_empty() {
        return;
    }
    list.extend(more.iter().copied().filter(|&s| (s as usize) < len));
    list.sort_unstable();
    list.dedup();
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn grid(n: u32) -> TriMesh {
        let mut positions = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        let mut triangles = Vec::new();
        let at = |i: u32, j: u32| j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        TriMesh {
            positions,
            triangles,
        }
    }

    /// Against the definition, triangle by triangle: a triangle is listed
    /// exactly when its corners' box meets the window's (a long sliver
    /// whose corners all lie outside still counts), a vertex when it lies
    /// inside.
    #[test]
    fn a_window_lists_what_meets_its_box() {
        let mut mesh = grid(10);
        // A sliver from far left to far right across the window.
        mesh.positions.push(DVec3::new(-50.0, 4.5, 0.0));
        mesh.positions.push(DVec3::new(50.0, 4.6, 0.0));
        mesh.positions.push(DVec3::new(50.0, 4.7, 0.0));
        let n = mesh.positions.len() as u32;
        mesh.triangles.push([n - 3, n - 2, n - 1]);
        let (lo, hi) = (DVec3::new(3.5, 3.5, -1.0), DVec3::new(6.0, 5.0, 1.0));
        let w = Window::build(&mesh, lo, hi);
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let p = tri.map(|v| mesh.positions[v as usize]);
            let (a, b) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
            let meets = a.cmple(hi).all() && b.cmpge(lo).all();
            assert_eq!(w.triangles().contains(&(t as u32)), meets, "triangle {t}");
        }
        for (v, &p) in mesh.positions.iter().enumerate() {
            assert_eq!(w.vertices().contains(&(v as u32)), w.holds(p), "vertex {v}");
        }
        assert!(w.triangles().contains(&(mesh.triangles.len() as u32 - 1)));
        assert!(w.misses(&mesh).is_none());
        // A triangle outside the box, moved in without being written, is
        // what the invariant forbids, and `misses` finds it.
        mesh.positions[0] = DVec3::new(4.0, 4.0, 0.0);
        assert!(w.misses(&mesh).is_some());
    }

    /// Slots a run wrote come in; slots past the new end leave.
    #[test]
    fn written_slots_join_and_removed_ones_leave() {
        let mesh = grid(4);
        let mut w = Window::build(&mesh, DVec3::splat(-0.5), DVec3::new(1.5, 1.5, 0.5));
        let before = w.triangles().to_vec();
        let mut shorter = mesh.clone();
        shorter.triangles.truncate(mesh.triangles.len() - 2);
        let last = shorter.triangles.len() as u32 - 1;
        w.written(&shorter, &[last, last + 1, 0], &[]);
        let mut want: Vec<u32> = before.iter().copied().chain([last]).collect();
        want.sort_unstable();
        want.dedup();
        assert_eq!(w.triangles(), &want[..]);
        assert!(w.triangles().windows(2).all(|p| p[0] < p[1]));
    }
}
