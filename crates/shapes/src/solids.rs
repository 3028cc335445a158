//! The regular polyhedra other than the cube (see [`crate::cube`]).
//!
//! All are inscribed in the sphere of radius √3 around the cube
//! `[-1, 1]³`. Vertices are listed in order of increasing z, then y, then
//! x; faces in order of their centres by the same rule; each face runs
//! counter-clockwise seen from outside, starting at its lowest-numbered
//! vertex. The tables below follow these rules (the tests check them).

use holey_mesh::{DVec3, PolyMesh};

/// The golden ratio.
const PHI: f64 = 1.618_033_988_749_895;
/// 1 / φ = φ − 1.
const INV_PHI: f64 = PHI - 1.0;
const SQRT3: f64 = 1.732_050_807_568_877_2;

fn solid<const N: usize>(positions: &[[f64; 3]], faces: &[[u32; N]]) -> PolyMesh {
    PolyMesh::from_faces(positions.iter().map(|&p| DVec3::from(p)).collect(), faces)
}

/// Regular tetrahedron: the alternate corners (1,−1,−1), (−1,1,−1),
/// (−1,−1,1), (1,1,1) of the cube `[-1, 1]³` in this order; edge 2√2,
/// circumradius √3, volume 8/3. Face `i` is opposite vertex `3 − i`:
/// `(0,2,1), (0,1,3), (0,3,2), (1,2,3)`.
pub fn tetrahedron() -> PolyMesh {
    solid(
        &[
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
        ],
        &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

/// Regular octahedron with corners on the axes at distance √3, in the
/// order −z, −y, −x, +x, +y, +z; volume 4√3. Face `i` lies in the octant
/// of corner `i` of the unit cube (`@cube` vertex order):
/// `(0,1,2), (0,3,1), (0,2,4), (0,4,3), (1,5,2), (1,3,5), (2,5,4), (3,4,5)`.
pub fn octahedron() -> PolyMesh {
    let s = SQRT3;
    solid(
        &[
            [0.0, 0.0, -s],
            [0.0, -s, 0.0],
            [-s, 0.0, 0.0],
            [s, 0.0, 0.0],
            [0.0, s, 0.0],
            [0.0, 0.0, s],
        ],
        &[
            [0, 1, 2],
            [0, 3, 1],
            [0, 2, 4],
            [0, 4, 3],
            [1, 5, 2],
            [1, 3, 5],
            [2, 5, 4],
            [3, 4, 5],
        ],
    )
}

/// Regular dodecahedron of 12 pentagons: the corners (±1,±1,±1) of the
/// cube and the cyclic permutations of (0, ±1/φ, ±φ); edge 2/φ,
/// circumradius √3. The bottom edge 0–1 and top edge 18–19 are parallel
/// to y; faces 0 and 1 meet at the bottom, 10 and 11 at the top.
pub fn dodecahedron() -> PolyMesh {
    let (a, b) = (INV_PHI, PHI);
    solid(
        &[
            [0.0, -a, -b],
            [0.0, a, -b],
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [1.0, 1.0, -1.0],
            [-b, 0.0, -a],
            [b, 0.0, -a],
            [-a, -b, 0.0],
            [a, -b, 0.0],
            [-a, b, 0.0],
            [a, b, 0.0],
            [-b, 0.0, a],
            [b, 0.0, a],
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, -a, b],
            [0.0, a, b],
        ],
        &[
            [0, 2, 6, 4, 1],
            [0, 1, 5, 7, 3],
            [0, 3, 9, 8, 2],
            [1, 4, 10, 11, 5],
            [2, 8, 14, 12, 6],
            [3, 7, 13, 15, 9],
            [4, 6, 12, 16, 10],
            [5, 11, 17, 13, 7],
            [8, 9, 15, 18, 14],
            [10, 16, 19, 17, 11],
            [12, 14, 18, 19, 16],
            [13, 17, 19, 18, 15],
        ],
    )
}

/// The icosahedron's vertices before scaling: cyclic permutations of
/// (0, ±1, ±φ), circumradius √(φ + 2).
const ICOSAHEDRON_VERTICES: [[f64; 3]; 12] = [
    [0.0, -1.0, -PHI],
    [0.0, 1.0, -PHI],
    [-PHI, 0.0, -1.0],
    [PHI, 0.0, -1.0],
    [-1.0, -PHI, 0.0],
    [1.0, -PHI, 0.0],
    [-1.0, PHI, 0.0],
    [1.0, PHI, 0.0],
    [-PHI, 0.0, 1.0],
    [PHI, 0.0, 1.0],
    [0.0, -1.0, PHI],
    [0.0, 1.0, PHI],
];

pub(crate) const ICOSAHEDRON_FACES: [[u32; 3]; 20] = [
    [0, 2, 1],
    [0, 1, 3],
    [0, 4, 2],
    [0, 3, 5],
    [1, 2, 6],
    [1, 7, 3],
    [0, 5, 4],
    [1, 6, 7],
    [2, 4, 8],
    [3, 9, 5],
    [2, 8, 6],
    [3, 7, 9],
    [4, 5, 10],
    [6, 11, 7],
    [4, 10, 8],
    [5, 9, 10],
    [6, 8, 11],
    [7, 11, 9],
    [8, 10, 11],
    [9, 11, 10],
];

/// The icosahedron's vertices scaled to circumradius `radius`.
pub(crate) fn icosahedron_vertices(radius: f64) -> Vec<DVec3> {
    ICOSAHEDRON_VERTICES
        .iter()
        .map(|&p| DVec3::from(p).normalize() * radius)
        .collect()
}

/// Regular icosahedron: the cyclic permutations of (0, ±1, ±φ) scaled to
/// circumradius √3. The bottom edge 0–1 and top edge 10–11 are parallel
/// to y.
pub fn icosahedron() -> PolyMesh {
    PolyMesh::from_faces(icosahedron_vertices(SQRT3), ICOSAHEDRON_FACES)
}
