//! The scenes the benchmarks (`benches/geom.rs`) and the figures of
//! `examples/measure.rs` run on, shared so both measure the same meshes.

use glam::DVec3;
use holey_geom::bvh::Aabb;
use holey_testkit::uv_spheres;

/// Two UV spheres of 262,144 triangles each (512 meridians × 258
/// parallels, radius 1), at the origin and at `b`, as one mesh.
pub fn two_spheres_at(b: [f64; 3]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (p, t) = uv_spheres(512, 258, &[([0.0; 3], 1.0), (b, 1.0)]);
    (p.into_iter().map(DVec3::from_array).collect(), t)
}

/// Two overlapping spheres (B at x = 1.2).
pub fn two_spheres() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    two_spheres_at([1.2, 0.1, 0.05])
}

/// The boxes of the triangles.
pub fn triangle_boxes(p: &[DVec3], t: &[[u32; 3]]) -> Vec<Aabb> {
    t.iter()
        .map(|x| Aabb::from_points(&[p[x[0] as usize], p[x[1] as usize], p[x[2] as usize]]))
        .collect()
}

/// The CCD union scene: sphere B (at x = 2.5) sweeps 1.3 along −x into
/// sphere A (at the origin). Start and end positions, and the triangles.
pub fn sphere_sweep() -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
    let (p, t) = two_spheres_at([2.5, 0.1, 0.05]);
    let na = p.len() / 2;
    let end = p
        .iter()
        .enumerate()
        .map(|(i, &x)| if i >= na { x - DVec3::X * 1.3 } else { x })
        .collect();
    (p, end, t)
}
