//! Exact crossings between the faces an operation made and the rest of
//! the surface, counted as `holey selfint` counts them: every non-hole
//! face fanned into triangles from its first corner, vertices with equal
//! positions one point, and two triangles crossing when
//! [`holey_geom::triangle_triangle_segment`] finds a segment between them
//! in the perturbed world of simulation of simplicity (triangles that
//! share an edge or only a vertex do not cross).

use std::collections::HashSet;

use glam::DVec3;
use holey_dlfl::{FaceId, Mesh, VertexId};
use holey_geom::{Aabb, Bvh, GeomError, SymPoint, position_classes, triangle_triangle_segment};

/// A mesh's non-hole faces as fans of triangles over its vertices.
pub(super) struct Surface {
    /// Vertex positions, densely numbered.
    pub positions: Vec<DVec3>,
    /// Each triangle's three vertex numbers.
    pub triangles: Vec<[u32; 3]>,
    /// The face each triangle comes from.
    pub owner: Vec<FaceId>,
}

impl Surface {
    /// The fans of every non-hole face of `mesh` (point-spheres give none).
    pub fn of(mesh: &Mesh) -> Result<Surface, holey_dlfl::Error> {
        let mut number = std::collections::HashMap::<VertexId, u32>::new();
        let mut positions = Vec::with_capacity(mesh.vertex_count());
        for v in mesh.vertices() {
            number.insert(v, positions.len() as u32);
            positions.push(mesh.position(v)?);
        }
        let mut triangles = Vec::new();
        let mut owner = Vec::new();
        for f in mesh.faces() {
            if mesh.is_hole(f)? {
                continue;
            }
            let vs: Vec<u32> = mesh
                .face_vertices(f)?
                .iter()
                .filter_map(|v| number.get(v).copied())
                .collect();
            for j in 1..vs.len().saturating_sub(1) {
                triangles.push([vs[0], vs[j], vs[j + 1]]);
                owner.push(f);
            }
        }
        Ok(Surface {
            positions,
            triangles,
            owner,
        })
    }

    /// The three corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        self.triangles[t].map(|v| self.positions[v as usize])
    }

    fn bounds(&self, t: usize) -> Aabb {
        Aabb::from_points(&self.corners(t))
    }
}

/// The pairs of faces (a new face first) whose fan triangles cross, one
/// entry per crossing triangle pair, for the faces in `new` against every
/// face of `mesh` (themselves included). `O(n)` for the old surface plus
/// a tree over the new triangles.
pub(super) fn crossings(
    mesh: &Mesh,
    new: &HashSet<FaceId>,
) -> Result<Vec<(FaceId, FaceId)>, CrossingError> {
    let s = Surface::of(mesh)?;
    let ids = position_classes(&s.positions)?;
    let sym =
        |t: usize| s.triangles[t].map(|v| SymPoint::new(s.positions[v as usize], ids[v as usize]));
    let fresh: Vec<usize> = (0..s.triangles.len())
        .filter(|&t| new.contains(&s.owner[t]))
        .collect();
    let boxes: Vec<Aabb> = fresh.iter().map(|&t| s.bounds(t)).collect();
    let tree = Bvh::build(&boxes)?;
    let reach = tree.bounds();
    let mut pairs = Vec::new();
    for t in 0..s.triangles.len() {
        let bb = s.bounds(t);
        if fresh.is_empty() || !bb.overlaps(&reach) {
            continue;
        }
        let t_new = new.contains(&s.owner[t]);
        tree.for_each_overlap(&bb, |i| {
            let u = fresh[i as usize];
            // Each pair of new triangles once, and never a triangle with
            // itself.
            if t_new && t >= u {
                return;
            }
            // Triangles sharing an edge (two identities) meet along it and
            // are neighbours, never a crossing, as the engine counts.
            let (iu, it) = (
                s.triangles[u].map(|v| ids[v as usize]),
                s.triangles[t].map(|v| ids[v as usize]),
            );
            if iu.iter().filter(|i| it.contains(i)).count() >= 2 {
                return;
            }
            if triangle_triangle_segment(sym(u), sym(t)).is_some() {
                pairs.push((s.owner[u], s.owner[t]));
            }
        });
    }
    Ok(pairs)
}

/// Why the crossings could not be counted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CrossingError {
    /// The kernel refused a query (a bug: the mesh was just built).
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
    /// A position is not finite, or the mesh is too large to number.
    #[error(transparent)]
    Geom(#[from] GeomError),
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_dlfl::convert::{ImportOptions, to_dlfl, to_poly};

    /// The topology engine's exact count for the written mesh.
    fn engine_pairs(mesh: &Mesh) -> usize {
        let tri = to_poly(mesh).poly.triangulated();
        holey_topo::self_intersections(&tri).unwrap().pairs.len()
    }

    #[test]
    fn every_face_new_counts_what_selfint_counts() {
        // The coarse cow's non-planar quads, fanned, cross each other in
        // places (26 pairs by the engine); with every face counted as new
        // each crossing pair is found once. Two cubes overlapping at a
        // corner cross too; one cube does not.
        let dir =
            holey_testkit::shared_meshes_or_return!("every_face_new_counts_what_selfint_counts");
        let holey_io::MeshFile::Poly(soup) =
            holey_io::read_path(&dir.join("spot_control_mesh.obj")).unwrap()
        else {
            panic!("not polygons");
        };
        let spot = to_dlfl(&soup, ImportOptions::default()).unwrap().mesh;
        let cube = holey_shapes::parse_primitive("@cube").unwrap();
        let mut two = cube.clone();
        two.append(&cube.translated(DVec3::splat(1.5)));
        let two = to_dlfl(&two, ImportOptions::default()).unwrap().mesh;
        let one = to_dlfl(&cube, ImportOptions::default()).unwrap().mesh;
        for m in [spot, two, one] {
            let all: HashSet<FaceId> = m.faces().collect();
            assert_eq!(crossings(&m, &all).unwrap().len(), engine_pairs(&m));
            assert!(crossings(&m, &HashSet::new()).unwrap().is_empty());
        }
    }
}
