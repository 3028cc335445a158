//! Primitives built on square grids: the (subdivided) cube, the quad
//! sphere and the planes.

use std::f64::consts::FRAC_PI_4;

use holey_mesh::{DVec3, PolyMesh};

/// An empty mesh with room for `vertices` positions, `faces` faces and
/// `corners` face corners.
pub(crate) fn with_capacity(vertices: usize, faces: usize, corners: usize) -> PolyMesh {
    let mut m = PolyMesh::new();
    m.positions.reserve(vertices);
    m.face_offsets.reserve(faces);
    m.face_indices.reserve(corners);
    m
}

/// The grid points on the surface of the lattice cube `[0, n]³`, numbered
/// in order of z, then y, then x.
struct CubeLattice {
    n: u32,
}

impl CubeLattice {
    /// The points in index order.
    fn points(&self) -> Vec<[u32; 3]> {
        let n = self.n;
        let mut out = Vec::with_capacity(6 * n as usize * n as usize + 2);
        for z in 0..=n {
            for y in 0..=n {
                if z == 0 || z == n || y == 0 || y == n {
                    out.extend((0..=n).map(|x| [x, y, z]));
                } else {
                    // Only the ends of inner rows are on the surface.
                    out.extend([[0, y, z], [n, y, z]]);
                }
            }
        }
        out
    }

    /// The index of surface point `p` in [`CubeLattice::points`]: the
    /// bottom and top layers are full `(n+1)²` grids, the layers between
    /// them rings of `4n` points.
    fn index(&self, [x, y, z]: [u32; 3]) -> u32 {
        let n = self.n;
        let row = n + 1;
        let full = row * row;
        if z == 0 {
            y * row + x
        } else if z == n {
            full + (n - 1) * 4 * n + y * row + x
        } else {
            let in_ring = if y == 0 {
                x
            } else if y == n {
                row + 2 * (n - 1) + x
            } else {
                row + 2 * (y - 1) + u32::from(x == n)
            };
            full + (z - 1) * 4 * n + in_ring
        }
    }
}

/// The six sides in face order: fixed axis, whether at the high end, and
/// the axes `a`, `b` along a quad's first and last edge, with `a × b`
/// pointing out.
const SIDES: [(usize, bool, usize, usize); 6] = [
    (2, false, 1, 0), // -z: y × x = -z
    (1, false, 0, 2), // -y: x × z = -y
    (0, false, 2, 1), // -x: z × y = -x
    (0, true, 1, 2),  // +x: y × z = +x
    (1, true, 2, 0),  // +y: z × x = +y
    (2, true, 0, 1),  // +z: x × y = +z
];

/// The cube lattice `[0, n]³` as a quad mesh, with `coord` mapping a
/// lattice coordinate to a position coordinate.
fn cube_mesh(n: u32, coord: impl Fn(u32) -> f64) -> PolyMesh {
    let lattice = CubeLattice { n };
    let points = lattice.points();
    let faces = 6 * n as usize * n as usize;
    let mut m = with_capacity(points.len(), faces, 4 * faces);
    m.positions.extend(
        points
            .iter()
            .map(|p| DVec3::new(coord(p[0]), coord(p[1]), coord(p[2]))),
    );
    for (fixed, high, a, b) in SIDES {
        let (outer, inner) = (a.max(b), a.min(b));
        for o in 0..n {
            for i in 0..n {
                let mut c = [0; 3];
                c[fixed] = if high { n } else { 0 };
                c[outer] = o;
                c[inner] = i;
                let corner = |da: u32, db: u32| {
                    let mut p = c;
                    p[a] += da;
                    p[b] += db;
                    lattice.index(p)
                };
                m.push_face(&[corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)]);
            }
        }
    }
    m
}

/// `(2c − n) / n`: lattice coordinate `c` of `0..=n` mapped to `[-1, 1]`,
/// exactly symmetric about 0.
pub(crate) fn unit_coord(c: u32, n: u32) -> f64 {
    (2.0 * f64::from(c) - f64::from(n)) / f64::from(n)
}

/// [`crate::cube`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn cube(n: u32) -> PolyMesh {
    cube_mesh(n, |c| unit_coord(c, n))
}

/// [`crate::quad_sphere`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn quad_sphere(n: u32) -> PolyMesh {
    let mut m = cube_mesh(n, |c| {
        let t = unit_coord(c, n);
        if t.abs() == 1.0 || t == 0.0 {
            t
        } else {
            (FRAC_PI_4 * t.abs()).tan().copysign(t)
        }
    });
    for p in &mut m.positions {
        *p = p.normalize();
    }
    m
}

/// The grid points of `[-1, 1]²` in the plane z = 0, row by row.
fn grid_points(nx: u32, ny: u32) -> impl Iterator<Item = DVec3> {
    (0..=ny).flat_map(move |j| {
        (0..=nx).map(move |i| DVec3::new(unit_coord(i, nx), unit_coord(j, ny), 0.0))
    })
}

/// [`crate::plane`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn plane(nx: u32, ny: u32) -> PolyMesh {
    let faces = nx as usize * ny as usize;
    let mut m = with_capacity((nx as usize + 1) * (ny as usize + 1), faces, 4 * faces);
    m.positions.extend(grid_points(nx, ny));
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            m.push_face(&[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    m
}

/// [`crate::tri_plane`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn tri_plane(nx: u32, ny: u32) -> PolyMesh {
    let faces = 2 * nx as usize * ny as usize;
    let mut m = with_capacity((nx as usize + 1) * (ny as usize + 1), faces, 3 * faces);
    m.positions.extend(grid_points(nx, ny));
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..ny {
        for i in 0..nx {
            m.push_face(&[v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            m.push_face(&[v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::CubeLattice;

    #[test]
    fn lattice_index_matches_point_order() {
        for n in 1..9 {
            let lattice = CubeLattice { n };
            let points = lattice.points();
            assert_eq!(points.len(), 6 * (n * n) as usize + 2);
            for (i, &p) in points.iter().enumerate() {
                assert_eq!(lattice.index(p) as usize, i, "n = {n}, point {p:?}");
            }
        }
    }
}
