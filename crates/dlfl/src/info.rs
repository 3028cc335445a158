//! [`MeshInfo`] of a DLFL mesh, counted on the structure itself.

use std::collections::BTreeMap;

use crate::Mesh;
use glam::DVec3;

use holey_mesh::analysis::MeshInfo;

/// Measures a DLFL mesh as `holey info` reports a `.dlfl` file: every edge
/// record counts (self-loops and multiple edges included); faces are the
/// non-hole faces; each hole face is a boundary loop and each edge beside
/// a hole a boundary edge. A DLFL is an orientable 2-manifold by
/// construction, so the non-manifold and misoriented counts are zero and
/// the genus is always given. Area and volume fan-triangulate each face
/// from its first corner (zero-length self-loops add nothing); the volume
/// is given when the mesh has no holes.
pub fn dlfl_info(mesh: &Mesh) -> MeshInfo {
    let topo = mesh.topology();
    let mut face_sizes = BTreeMap::new();
    let (mut two_gons, mut point_spheres, mut faces) = (0, 0, 0);
    let (mut area, mut volume) = (0.0, 0.0);
    let origin = mesh
        .vertices()
        .next()
        .and_then(|v| mesh.position(v).ok())
        .unwrap_or(DVec3::ZERO);
    let mut boundary_edges = 0;
    for e in mesh.edges() {
        let holes = mesh
            .edge_faces(e)
            .map(|fs| {
                fs.iter()
                    .filter(|&&f| mesh.is_hole(f).unwrap_or(false))
                    .count()
            })
            .unwrap_or(0);
        if holes > 0 {
            boundary_edges += 1;
        }
    }
    for f in mesh.surface_faces() {
        faces += 1;
        let ps = mesh.face_positions(f).unwrap_or_default();
        *face_sizes.entry(ps.len()).or_insert(0) += 1;
        if mesh.is_point_sphere(f).unwrap_or(false) {
            point_spheres += 1;
        } else if ps.len() == 2 {
            two_gons += 1;
        }
        for k in 1..ps.len().saturating_sub(1) {
            let (a, b, c) = (ps[0] - origin, ps[k] - origin, ps[k + 1] - origin);
            area += 0.5 * (b - a).cross(c - a).length();
            volume += a.dot(b.cross(c)) / 6.0;
        }
    }
    let bbox = mesh
        .vertices()
        .filter_map(|v| mesh.position(v).ok())
        .fold(None::<(DVec3, DVec3)>, |acc, p| {
            Some(acc.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
        })
        .map(|(lo, hi)| [lo.to_array(), hi.to_array()]);
    let self_loops = mesh
        .edges()
        .filter(|&e| mesh.is_self_loop(e).unwrap_or(false))
        .count();
    let holes = topo.holes();
    MeshInfo {
        vertices: mesh.vertex_count(),
        unreferenced_vertices: 0,
        edges: mesh.edge_count(),
        faces,
        invalid_faces: 0,
        components: topo.component_count(),
        boundary_edges,
        boundary_loops: holes,
        nonmanifold_edges: 0,
        nonmanifold_vertices: 0,
        misoriented_edges: 0,
        degenerate_faces: 0,
        nonfinite_vertices: 0,
        closed: holes == 0,
        manifold: true,
        oriented: true,
        euler: topo.euler(),
        genus: Some(topo.genus()),
        self_loops,
        two_gons,
        point_spheres,
        face_sizes,
        bbox,
        volume: (holes == 0).then_some(volume),
        area,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::convert::{ImportOptions, to_dlfl};
    use holey_mesh::{PolyMesh, analysis::analyze};

    fn cube() -> PolyMesh {
        let p = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        PolyMesh::from_faces(
            p,
            [
                [0u32, 2, 3, 1],
                [4, 5, 7, 6],
                [0, 1, 5, 4],
                [2, 6, 7, 3],
                [1, 3, 7, 5],
                [0, 4, 6, 2],
            ],
        )
    }

    #[test]
    fn agrees_with_the_soup_analysis_on_manifold_meshes() {
        let soup = cube();
        let mesh = to_dlfl(&soup, ImportOptions::default()).unwrap().mesh;
        let mut a = analyze(&soup);
        let mut d = dlfl_info(&mesh);
        // The two sum fan volumes about different origins.
        assert!((a.volume.unwrap() - 1.0).abs() < 1e-12);
        assert!((d.volume.unwrap() - 1.0).abs() < 1e-12);
        a.volume = None;
        d.volume = None;
        assert_eq!(a, d);
    }

    #[test]
    fn counts_self_loops_two_gons_point_spheres_and_holes() {
        let mut mesh = to_dlfl(&cube(), ImportOptions::default()).unwrap().mesh;
        let v = mesh.vertices().next().unwrap();
        let cs: Vec<_> = mesh.vertex_corners(v).unwrap().collect();
        mesh.insert_edge(cs[0], cs[1]).unwrap();
        let f = mesh
            .faces()
            .find(|&f| mesh.face_len(f).unwrap() == 4)
            .unwrap();
        let fc: Vec<_> = mesh.face_corners(f).unwrap().collect();
        mesh.insert_edge(fc[0], fc[1]).unwrap();
        mesh.create_vertex(DVec3::splat(3.0)).unwrap();
        let some = mesh
            .faces()
            .find(|&f| mesh.face_len(f).unwrap() == 4)
            .unwrap();
        mesh.set_hole(some, true).unwrap();
        let d = dlfl_info(&mesh);
        assert_eq!(
            (
                d.vertices,
                d.edges,
                d.self_loops,
                d.two_gons,
                d.point_spheres
            ),
            (9, 14, 1, 1, 1)
        );
        assert_eq!((d.boundary_loops, d.closed, d.components), (1, false, 2));
        assert_eq!(d.volume, None);
        assert_eq!(d.genus, Some(1));
        assert_eq!(d.faces + d.boundary_loops, mesh.face_count());
    }
}
