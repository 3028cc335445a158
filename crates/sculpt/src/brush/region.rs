//! What a centred brush sees of the surface in one frame: the vertices
//! of the patch under it, their falloff weights and normals, and the
//! plane the plane-based brushes (clay, flatten, scrape, pinch, crease)
//! work against.
//!
//! The patch is the connected piece of the surface within the radius
//! that holds the surface point nearest the centre
//! ([`super::snake_hook::hooked_patch`]), not every vertex in the ball:
//! on a thin wall the ball also holds the far side, whose normals would
//! cancel the near side's in the brush plane, and which a brush must not
//! drag along, or a crease pressed through the wall would push the far
//! side ahead of it instead of meeting it and opening a hole.

use glam::DVec3;
use holey_topo::TriMesh;

use super::falloff::Falloff;
use super::normals_of;
use super::snake_hook::hooked_patch;

/// The brushed region around a centre.
#[derive(Clone, Debug)]
pub struct Region {
    /// The vertices of the patch under the brush, increasing.
    pub vertices: Vec<u32>,
    /// Each vertex's falloff weight, in `vertices` order.
    pub weights: Vec<f64>,
    /// Each vertex's area-weighted normal, in `vertices` order.
    pub normals: Vec<DVec3>,
    /// The brush's normal: the weighted sum of the vertex normals,
    /// normalised (zero when they cancel).
    pub normal: DVec3,
    /// The brush plane's point: the weighted mean of the positions (the
    /// centre itself when every weight is 0).
    pub origin: DVec3,
}

impl Region {
    /// The region of a brush of `radius` at `centre` with `falloff`.
    pub fn gather(mesh: &TriMesh, centre: DVec3, radius: f64, falloff: Falloff) -> Region {
        let vertices = hooked_patch(mesh, centre, radius);
        let normals = normals_of(mesh, &vertices);
        let weights: Vec<f64> = vertices
            .iter()
            .map(|&v| falloff.weight(mesh.positions[v as usize].distance(centre), radius))
            .collect();
        let (mut sum_n, mut sum_p, mut sum_w) = (DVec3::ZERO, DVec3::ZERO, 0.0);
        for ((&v, n), &w) in vertices.iter().zip(&normals).zip(&weights) {
            sum_n += w * *n;
            sum_p += w * mesh.positions[v as usize];
            sum_w += w;
        }
        let origin = if sum_w > 0.0 { sum_p / sum_w } else { centre };
        Region {
            vertices,
            weights,
            normals,
            normal: sum_n.normalize_or_zero(),
            origin,
        }
    }

    /// Signed height of `p` above the brush plane, along its normal.
    pub fn height(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }

    /// The part of `v` across the brush normal (in the brush plane).
    pub fn across(&self, v: DVec3) -> DVec3 {
        v - v.dot(self.normal) * self.normal
    }

    /// The positions of `mesh` with each region vertex moved by
    /// `displacement(position, weight, vertex normal)`.
    pub fn displaced(
        &self,
        mesh: &TriMesh,
        displacement: impl Fn(DVec3, f64, DVec3) -> DVec3,
    ) -> Vec<DVec3> {
        let mut out = mesh.positions.clone();
        for ((&v, &w), &n) in self.vertices.iter().zip(&self.weights).zip(&self.normals) {
            if w == 0.0 {
                continue;
            }
            let p = mesh.positions[v as usize];
            out[v as usize] = p + displacement(p, w, n);
        }
        out
    }
}
