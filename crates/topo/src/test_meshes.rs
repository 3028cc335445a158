//! Meshes the unit tests of several modules build on.

use glam::DVec3;

use crate::mesh::TriMesh;

/// A UV sphere of radius `r` about `centre`: `rings` rings of latitude
/// between the poles (`rings − 1` circles of `segs` vertices), outward.
/// Vertices: the north pole, the south pole, then the circles from north
/// to south, `segs` each, so vertex `2 + (i − 1)·segs + j` is number `j`
/// of circle `i`.
pub(crate) fn uv_sphere(centre: DVec3, r: f64, rings: u32, segs: u32) -> TriMesh {
    let mut positions = vec![centre + DVec3::Z * r, centre - DVec3::Z * r];
    for i in 1..rings {
        let th = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segs {
            let ph = std::f64::consts::TAU * j as f64 / segs as f64;
            positions
                .push(centre + r * DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()));
        }
    }
    let at = |i: u32, j: u32| 2 + (i - 1) * segs + (j % segs);
    let mut triangles = Vec::new();
    for j in 0..segs {
        triangles.push([0, at(1, j), at(1, j + 1)]);
        triangles.push([1, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segs {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    TriMesh {
        positions,
        triangles,
    }
}

/// The axis-aligned box `[lo, hi]` as 12 outward triangles (testkit's
/// unit cube stretched over it).
pub(crate) fn cuboid(lo: DVec3, hi: DVec3) -> TriMesh {
    let (corners, quads) = holey_testkit::unit_cube();
    TriMesh {
        positions: corners
            .iter()
            .map(|&c| lo + (hi - lo) * DVec3::from_array(c))
            .collect(),
        triangles: quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect(),
    }
}
