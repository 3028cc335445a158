//! Small meshes the tests of several crates build on, as plain arrays
//! (positions as `[f64; 3]`, faces as vertex indices), so that this crate
//! depends on none of them: each test turns them into its own crate's
//! type.

/// The six unit axis directions, `+x`, `−x`, `+y`, `−y`, `+z`, `−z`: where
/// tests put the six neighbours of a hub or the six faces of a cube.
pub const AXES: [[f64; 3]; 6] = [
    [1., 0., 0.],
    [-1., 0., 0.],
    [0., 1., 0.],
    [0., -1., 0.],
    [0., 0., 1.],
    [0., 0., -1.],
];

/// The unit cube `[0, 1]³`: corners in the order `(0,0,0)`, `(1,0,0)`,
/// `(1,1,0)`, `(0,1,0)`, then the same at `z = 1`; six quads, outward.
pub fn unit_cube() -> ([[f64; 3]; 8], [[u32; 4]; 6]) {
    (
        [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
        ],
        [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [1, 2, 6, 5],
            [0, 4, 7, 3],
        ],
    )
}

/// The regular octahedron with corners on the axes, in the order +x, −x,
/// +y, −y, +z, −z (unit directions; scale and move them as needed), and
/// its eight triangles, outward.
pub fn octahedron() -> ([[f64; 3]; 6], [[u32; 3]; 8]) {
    (
        AXES,
        [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    )
}

/// The regular tetrahedron on alternate corners of `[−1, 1]³`, and its
/// four triangles, outward.
pub fn tetrahedron() -> ([[f64; 3]; 4], [[u32; 3]; 4]) {
    (
        [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]],
        [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
    )
}

/// An `n × m` quad torus (`n` around the axis `z`, `m` around the tube;
/// radii 2 and ½): vertex `i·m + j` is at angle `i` around the axis and
/// `j` around the tube; `n·m` quads, outward.
pub fn quad_torus(n: u32, m: u32) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
    let mut pos = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / m as f64,
            );
            let r = 2.0 + 0.5 * b.cos();
            pos.push([r * a.cos(), r * a.sin(), 0.5 * b.sin()]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let quads = (0..n)
        .flat_map(|i| (0..m).map(move |j| [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]))
        .collect();
    (pos, quads)
}

/// The triangles of a grid of `nu × nv` squares whose vertex `(i, j)`, for
/// `i` in `0..=nu` and `j` in `0..=nv`, has index `j·(nu + 1) + i` (rows of
/// `nu + 1`): square `(i, j)` as the triangles `(i, j) (i+1, j) (i+1, j+1)`
/// and `(i, j) (i+1, j+1) (i, j+1)`, square by square along each row.
/// Counter-clockwise when `i` runs along x and `j` along y.
pub fn grid_triangles(nu: u32, nv: u32) -> Vec<[u32; 3]> {
    let id = |i: u32, j: u32| j * (nu + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    triangles
}

/// A UV sphere of `2·nu·(nv−2)` triangles: `nu` meridians, `nv` parallels
/// (poles included), welded, outward-oriented, centre `c`, radius `r`.
/// Vertices: the north pole, the rings from north to south, the south
/// pole.
pub fn uv_sphere(nu: usize, nv: usize, c: [f64; 3], r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut pos = vec![[c[0], c[1], c[2] + r]];
    for j in 1..nv - 1 {
        let th = std::f64::consts::PI * j as f64 / (nv - 1) as f64;
        for i in 0..nu {
            let ph = 2.0 * std::f64::consts::PI * i as f64 / nu as f64;
            pos.push([
                c[0] + r * th.sin() * ph.cos(),
                c[1] + r * th.sin() * ph.sin(),
                c[2] + r * th.cos(),
            ]);
        }
    }
    pos.push([c[0], c[1], c[2] - r]);
    let south = (pos.len() - 1) as u32;
    let ring = |j: usize, i: usize| (1 + (j - 1) * nu + (i % nu)) as u32;
    let mut tris = Vec::new();
    for i in 0..nu {
        tris.push([0, ring(1, i), ring(1, i + 1)]);
    }
    for j in 1..nv - 2 {
        for i in 0..nu {
            let (a, b, c2, d) = (
                ring(j, i),
                ring(j + 1, i),
                ring(j + 1, i + 1),
                ring(j, i + 1),
            );
            tris.push([a, b, c2]);
            tris.push([a, c2, d]);
        }
    }
    for i in 0..nu {
        tris.push([ring(nv - 2, i), south, ring(nv - 2, i + 1)]);
    }
    (pos, tris)
}

/// Several [`uv_sphere`]s of `nu × nv` as one mesh, each `(centre,
/// radius)` in turn: the vertices of sphere `k` follow those of sphere
/// `k − 1`.
pub fn uv_spheres(
    nu: usize,
    nv: usize,
    spheres: &[([f64; 3], f64)],
) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let (mut pos, mut tris) = (Vec::new(), Vec::new());
    for &(c, r) in spheres {
        let (p, t) = uv_sphere(nu, nv, c, r);
        let base = pos.len() as u32;
        pos.extend(p);
        tris.extend(t.iter().map(|x| x.map(|v| v + base)));
    }
    (pos, tris)
}

/// The closed surface of a set of unit lattice cubes (cube `c` spans
/// `c .. c + 1` on each axis): every square face between a cube of the
/// set and a cell outside it, outward, as two triangles split along the
/// diagonal from its first corner, vertices welded by lattice point.
/// Where cubes of the set meet only along an edge or at a corner, the
/// surface is not a 2-manifold there (an edge of four faces, a vertex of
/// two fans), as the solid is not.
pub fn lattice_cubes(cells: &[[i32; 3]]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let set: std::collections::HashSet<[i32; 3]> = cells.iter().copied().collect();
    let mut index: std::collections::HashMap<[i32; 3], u32> = Default::default();
    let mut pos: Vec<[f64; 3]> = Vec::new();
    let mut tris = Vec::new();
    for c in cells {
        for axis in 0..3 {
            for dir in [-1, 1] {
                let mut n = *c;
                n[axis] += dir;
                if set.contains(&n) {
                    continue;
                }
                let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut base = *c;
                base[axis] += i32::from(dir > 0);
                let mut quad: Vec<[i32; 3]> = [(0, 0), (1, 0), (1, 1), (0, 1)]
                    .iter()
                    .map(|&(du, dw)| {
                        let mut q = base;
                        q[u] += du;
                        q[w] += dw;
                        q
                    })
                    .collect();
                if dir < 0 {
                    quad.reverse();
                }
                let q: Vec<u32> = quad
                    .iter()
                    .map(|q| {
                        *index.entry(*q).or_insert_with(|| {
                            pos.push(q.map(f64::from));
                            (pos.len() - 1) as u32
                        })
                    })
                    .collect();
                tris.push([q[0], q[1], q[2]]);
                tris.push([q[0], q[2], q[3]]);
            }
        }
    }
    (pos, tris)
}

/// The cubes of the Menger sponge of `level` on the lattice `0..3^level`:
/// those none of whose base-3 digit triples has two or more ones.
pub fn menger_cells(level: u32) -> Vec<[i32; 3]> {
    let n = 3i32.pow(level);
    let kept = |c: [i32; 3]| {
        let mut c = c;
        while c != [0, 0, 0] {
            if c.iter().filter(|&&x| x % 3 == 1).count() >= 2 {
                return false;
            }
            c = c.map(|x| x / 3);
        }
        true
    };
    let mut cells = Vec::new();
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                if kept([x, y, z]) {
                    cells.push([x, y, z]);
                }
            }
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every directed edge once and its reverse once: closed and oriented.
    fn closed_oriented<const N: usize>(faces: &[[u32; N]]) -> bool {
        let mut edges: Vec<(u32, u32)> = faces
            .iter()
            .flat_map(|f| (0..N).map(move |k| (f[k], f[(k + 1) % N])))
            .collect();
        edges.sort_unstable();
        let unique = edges.windows(2).all(|w| w[0] != w[1]);
        unique
            && edges
                .iter()
                .all(|&(a, b)| edges.binary_search(&(b, a)).is_ok())
    }

    /// Six times the signed volume a closed surface's faces bound, by the
    /// divergence theorem over a fan of each face: positive when outward.
    fn six_volume<const N: usize>(p: &[[f64; 3]], faces: &[[u32; N]]) -> f64 {
        let det = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        };
        faces
            .iter()
            .flat_map(|f| (1..N - 1).map(move |k| [f[0], f[k], f[k + 1]]))
            .map(|[a, b, c]| det(p[a as usize], p[b as usize], p[c as usize]))
            .sum()
    }

    #[test]
    fn the_meshes_are_closed_and_oriented() {
        assert!(closed_oriented(&unit_cube().1));
        assert!(closed_oriented(&octahedron().1));
        let (p, t) = tetrahedron();
        assert!(closed_oriented(&t));
        // Edge 2√2, volume (2√2)³/(6√2) = 8/3.
        assert!((six_volume(&p, &t) - 16.0).abs() < 1e-12);
        for (n, m) in [(3, 3), (4, 3), (8, 6)] {
            let (p, q) = quad_torus(n, m);
            assert_eq!((p.len(), q.len()), ((n * m) as usize, (n * m) as usize));
            assert!(closed_oriented(&q), "{n}×{m}");
            // Quads of a torus of revolution: the polyhedron's volume is
            // positive and below the smooth torus's 2π²·R·r² = π².
            let v = six_volume(&p, &q) / 6.0;
            assert!(v > 0.0 && v < std::f64::consts::PI.powi(2), "{n}×{m}: {v}");
        }
        // Two squares in a row: the row 0 1 2, then 3 4 5 beside it.
        assert_eq!(
            grid_triangles(2, 1),
            vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]]
        );
        let (p, t) = uv_sphere(12, 7, [1.0, 2.0, 3.0], 0.5);
        assert_eq!((p.len(), t.len()), (2 + 12 * 5, 2 * 12 * 5));
        assert!(closed_oriented(&t));
        let (p2, t2) = uv_spheres(12, 7, &[([0.0; 3], 1.0), ([1.0, 2.0, 3.0], 0.5)]);
        assert_eq!(&p2[p2.len() - p.len()..], &p[..]);
        assert_eq!(t2[t.len()], t[0].map(|v| v + p.len() as u32));
        for q in &p {
            let d = ((q[0] - 1.0).powi(2) + (q[1] - 2.0).powi(2) + (q[2] - 3.0).powi(2)).sqrt();
            assert!((d - 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn menger_cells_are_20_to_the_level_and_their_surface_is_closed() {
        assert_eq!(menger_cells(1).len(), 20);
        assert_eq!(menger_cells(2).len(), 400);
        let (pos, tris) = lattice_cubes(&menger_cells(1));
        // Every edge has two faces, one each way: closed, oriented.
        let mut net = std::collections::HashMap::new();
        for t in &tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *net.entry((a.min(b), a.max(b))).or_insert(0i32) += if a < b { 1 } else { -1 };
            }
        }
        assert!(net.values().all(|&n| n == 0));
        // The level-1 sponge of side 3 has area 72 = 9·(2·20/9 + 4·8/9):
        // 48 squares outside, 24 in its tunnels.
        assert_eq!(tris.len(), 2 * 72);
        assert_eq!(pos.len(), 64);
    }
}
