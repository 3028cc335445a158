//! A broad phase for meshes whose parts move rigidly by translations, such
//! as the union of Theorem 5.2, where one solid slides into another from
//! far away.
//!
//! The general broad phase boxes each vertex's swept segment and each
//! triangle's swept volume. When a part travels a long way, every triangle
//! of it sweeps a long slab that holds a large share of all vertices, and
//! the candidate count grows like `n^1.5`. Here the vertices are grouped
//! by displacement (equal up to the rounding of the caller's arithmetic),
//! and each (vertex group, triangle group) pair is handled in the frame of
//! the triangle group, where triangles are (nearly) static and the vertices
//! of the other group move along one common direction `r`:
//!
//! - `r = 0` (the same group): boxes of the short residual motions;
//! - otherwise: coordinates `(u, w, s)` with `s` along `r`. A vertex's
//!   motion is a segment parallel to the `s` axis, so its box is a needle
//!   and meets only the triangles whose shadow along `r` covers it: a few
//!   per vertex, as in ray casting.
//!
//! Only the broad phase changes: candidates still go to the same exact
//! narrow phase, so the parities are those of the general path. Boxes are
//! inflated by a scale-relative margin far above the rounding of the
//! frame change and of the grouping, so no colliding pair is missed.

use glam::DVec3;
use rayon::prelude::*;

use crate::bvh::{Aabb, Bvh};
use crate::error::GeomError;

/// At most this many groups; more falls back to the general broad phase.
const MAX_GROUPS: usize = 4;

/// Vertices whose displacements differ by at most this times the scene's
/// scale are one group: far above the rounding of `p + d` (a few units of
/// 2⁻⁵³ of the scale) and far below any real motion difference.
const GROUP_TOLERANCE: f64 = 1e-13;

/// Box inflation, times the scale: covers the grouping tolerance and the
/// rounding of the frame change many times over.
const MARGIN: f64 = 1e-11;

/// A partition of vertices and triangles into rigid groups.
pub(crate) struct Groups {
    /// Representative displacement of each group.
    displacement: Vec<DVec3>,
    vertex_group: Vec<u8>,
    triangle_group: Vec<u8>,
    /// Every vertex of the group has exactly the representative
    /// displacement: the group cannot collide with itself.
    exact: Vec<bool>,
    scale: f64,
}

impl Groups {
    /// Groups the motion, or `None` when it is not a few rigid
    /// translations (more than [`MAX_GROUPS`] displacements, or a triangle
    /// whose corners move differently), or when nothing moves far enough
    /// for grouping to pay.
    pub(crate) fn detect(start: &[DVec3], end: &[DVec3], tris: &[[u32; 3]]) -> Option<Groups> {
        let scale = start
            .iter()
            .chain(end)
            .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
        if scale == 0.0 {
            return None;
        }
        let tol = GROUP_TOLERANCE * scale;
        let mut displacement: Vec<DVec3> = Vec::new();
        let mut vertex_group = Vec::with_capacity(start.len());
        let mut exact: Vec<bool> = Vec::new();
        for (a, b) in start.iter().zip(end) {
            let d = *b - *a;
            let g = match displacement
                .iter()
                .position(|r| (d - *r).abs().max_element() <= tol)
            {
                Some(g) => {
                    exact[g] &= d == displacement[g];
                    g
                }
                None => {
                    if displacement.len() == MAX_GROUPS {
                        return None;
                    }
                    displacement.push(d);
                    exact.push(true);
                    displacement.len() - 1
                }
            };
            vertex_group.push(g as u8);
        }
        if displacement.len() < 2 {
            return None;
        }
        let mut triangle_group = Vec::with_capacity(tris.len());
        for t in tris {
            let g = vertex_group[t[0] as usize];
            if vertex_group[t[1] as usize] != g || vertex_group[t[2] as usize] != g {
                return None;
            }
            triangle_group.push(g);
        }
        Some(Groups {
            displacement,
            vertex_group,
            triangle_group,
            exact,
            scale,
        })
    }

    /// One [`PairSet`] per (triangle group, vertex group): a BVH over the
    /// triangle group's boxes in the frame along the relative motion.
    pub(crate) fn prepare(
        &self,
        start: &[DVec3],
        end: &[DVec3],
        tris: &[[u32; 3]],
    ) -> Result<Prepared, GeomError> {
        let k = self.displacement.len();
        let margin = MARGIN
            * (self.scale
                + self
                    .displacement
                    .iter()
                    .fold(0.0f64, |m, d| m.max(d.abs().max_element())));
        // Members of each group, gathered once.
        let mut verts_of: Vec<Vec<u32>> = vec![Vec::new(); k];
        for (v, &g) in self.vertex_group.iter().enumerate() {
            verts_of[g as usize].push(v as u32);
        }
        let mut tris_of: Vec<Vec<u32>> = vec![Vec::new(); k];
        for (t, &g) in self.triangle_group.iter().enumerate() {
            tris_of[g as usize].push(t as u32);
        }
        // The (triangle group, vertex group) pairs to stream, then their
        // hierarchies built side by side.
        let mut jobs: Vec<(usize, usize)> = Vec::new();
        for (gt, tri_ids) in tris_of.iter().enumerate() {
            for (gv, members) in verts_of.iter().enumerate() {
                // Equal displacements: every pair would be skipped.
                let rigid_self = gv == gt && self.exact[gt];
                if !rigid_self && !tri_ids.is_empty() && !members.is_empty() {
                    jobs.push((gt, gv));
                }
            }
        }
        let pairs = jobs
            .par_iter()
            .map(|&(gt, gv)| {
                let dt = self.displacement[gt];
                let tri_ids = &tris_of[gt];
                let r = self.displacement[gv] - dt;
                let frame = Frame::along(r);
                // Triangles in the frame of their group: the box of their
                // start corners and their end corners moved back by `dt`.
                let tri_boxes: Vec<Aabb> = tri_ids
                    .iter()
                    .map(|&t| {
                        let c = tris[t as usize];
                        let mut bb = Aabb::EMPTY;
                        for &v in &c {
                            bb = bb.grow(frame.map(start[v as usize]));
                            bb = bb.grow(frame.map(end[v as usize] - dt));
                        }
                        inflate(bb, margin)
                    })
                    .collect();
                let bvh = Bvh::build(&tri_boxes)?;
                Ok(PairSet {
                    frame,
                    dt,
                    verts: verts_of[gv].clone(),
                    tri_ids: tri_ids.clone(),
                    bvh,
                    margin,
                })
            })
            .collect::<Result<Vec<PairSet>, GeomError>>()?;
        Ok(Prepared { pairs })
    }
}

/// Everything needed to stream the vertices of one group over the
/// triangles of another.
pub(crate) struct PairSet {
    frame: Frame,
    dt: DVec3,
    pub(crate) verts: Vec<u32>,
    tri_ids: Vec<u32>,
    bvh: Bvh,
    margin: f64,
}

impl PairSet {
    /// Calls `f(triangle)` for each candidate triangle of vertex `v`.
    pub(crate) fn candidates(
        &self,
        v: u32,
        start: &[DVec3],
        end: &[DVec3],
        mut f: impl FnMut(u32),
    ) {
        let a = self.frame.map(start[v as usize]);
        let b = self.frame.map(end[v as usize] - self.dt);
        let bb = inflate(Aabb::new(a.min(b), a.max(b)), self.margin);
        self.bvh
            .for_each_overlap(&bb, |i| f(self.tri_ids[i as usize]));
    }
}

pub(crate) struct Prepared {
    pub(crate) pairs: Vec<PairSet>,
}

fn inflate(bb: Aabb, m: f64) -> Aabb {
    Aabb::new(bb.min - DVec3::splat(m), bb.max + DVec3::splat(m))
}

/// An orthonormal frame whose third axis is along `r` (any frame when `r`
/// is zero).
#[derive(Clone, Copy, Debug)]
struct Frame {
    axes: [DVec3; 3],
}

impl Frame {
    fn along(r: DVec3) -> Frame {
        let len = r.length();
        if len == 0.0 || !len.is_finite() {
            return Frame {
                axes: [DVec3::X, DVec3::Y, DVec3::Z],
            };
        }
        let s = r / len;
        let helper = if s.x.abs() < 0.6 { DVec3::X } else { DVec3::Y };
        let u = s.cross(helper).normalize();
        let w = s.cross(u);
        Frame { axes: [u, w, s] }
    }

    #[inline]
    fn map(&self, p: DVec3) -> DVec3 {
        DVec3::new(
            p.dot(self.axes[0]),
            p.dot(self.axes[1]),
            p.dot(self.axes[2]),
        )
    }
}
