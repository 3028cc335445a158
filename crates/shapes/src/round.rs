//! Round primitives: icosphere, UV sphere, torus, cylinder and cone.

use std::cmp::Ordering;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

use holey_mesh::tri::rows_by_smaller_end;
use holey_mesh::{DVec3, PolyMesh};

use crate::grid::{unit_coord, with_capacity};
use crate::solids::{ICOSAHEDRON_FACES, icosahedron_vertices};

/// `(cos, sin)` of the angle `2π·i/n`, computed within the first octant
/// and extended by symmetry: exact at quarter turns (no `6e-17` or `-0`
/// coordinates), and mirror-image angles give exactly mirrored values.
pub(crate) fn turn(i: u32, n: u32) -> (f64, f64) {
    if n == 0 {
        return (1.0, 0.0);
    }
    let n = u64::from(n);
    let four = 4 * (u64::from(i) % n);
    // The angle is (quadrant + r/n) quarter turns.
    let (quadrant, r) = (four / n, four % n);
    let (c, s) = match (2 * r).cmp(&n) {
        Ordering::Less => {
            let (s, c) = (FRAC_PI_2 * r as f64 / n as f64).sin_cos();
            (c, s)
        }
        Ordering::Equal => (FRAC_1_SQRT_2, FRAC_1_SQRT_2),
        Ordering::Greater => {
            let (s, c) = (FRAC_PI_2 * (n - r) as f64 / n as f64).sin_cos();
            (s, c)
        }
    };
    // Adding 0.0 turns -0.0 into 0.0.
    let (c, s) = match quadrant {
        0 => (c, s),
        1 => (-s, c),
        2 => (-c, -s),
        _ => (s, -c),
    };
    (c + 0.0, s + 0.0)
}

/// [`crate::icosphere`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn icosphere(level: u32) -> PolyMesh {
    let mut positions = icosahedron_vertices(1.0);
    let mut tris = ICOSAHEDRON_FACES.to_vec();
    for _ in 0..level {
        tris = subdivide(&mut positions, &tris);
    }
    let mut m = with_capacity(0, tris.len(), 3 * tris.len());
    m.positions = positions;
    for t in &tris {
        m.push_face(t);
    }
    m
}

/// One level of icosphere subdivision of the closed triangle mesh `tris`,
/// appending the new vertices to `positions`.
fn subdivide(positions: &mut Vec<DVec3>, tris: &[[u32; 3]]) -> Vec<[u32; 3]> {
    // The midpoint of edge lo–hi (lo < hi) is stored in row `lo` of a
    // compressed table, as (hi, midpoint). Rows get room for every edge
    // that names their vertex as its lower end, counted per face corner.
    let v = positions.len();
    let start: Vec<usize> = rows_by_smaller_end(tris, v)
        .into_iter()
        .map(|s| s as usize)
        .collect();
    let mut end = start.clone();
    let mut slots = vec![(0u32, 0u32); start[v]];
    positions.reserve(tris.len() * 3 / 2);
    let mut out = Vec::with_capacity(4 * tris.len());
    for &[a, b, c] in tris {
        let mut mid = |p: u32, q: u32| {
            let (lo, hi) = (p.min(q) as usize, p.max(q));
            if let Some(&(_, m)) = slots[start[lo]..end[lo]].iter().find(|s| s.0 == hi) {
                return m;
            }
            let m = positions.len() as u32;
            positions.push((positions[p as usize] + positions[q as usize]).normalize());
            slots[end[lo]] = (hi, m);
            end[lo] += 1;
            m
        };
        let ab = mid(a, b);
        let bc = mid(b, c);
        let ca = mid(c, a);
        out.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    out
}

/// [`crate::uv_sphere`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn uv_sphere(segments: u32, rings: u32) -> PolyMesh {
    let (s, r) = (segments, rings);
    let vertices = s as usize * (r as usize - 1) + 2;
    let faces = s as usize * r as usize;
    let mut m = with_capacity(vertices, faces, 4 * faces);
    m.positions.push(DVec3::NEG_Z);
    for k in 1..r {
        // Polar angle πk/r from the south pole.
        let (c, rho) = turn(k, 2 * r);
        for i in 0..s {
            let (cu, su) = turn(i, s);
            m.positions.push(DVec3::new(rho * cu, rho * su, 0.0 - c));
        }
    }
    m.positions.push(DVec3::Z);
    let ring = |k: u32, i: u32| 1 + (k - 1) * s + i % s;
    let north = 1 + (r - 1) * s;
    for i in 0..s {
        m.push_face(&[0, ring(1, i + 1), ring(1, i)]);
    }
    for k in 1..r - 1 {
        for i in 0..s {
            m.push_face(&[
                ring(k, i),
                ring(k, i + 1),
                ring(k + 1, i + 1),
                ring(k + 1, i),
            ]);
        }
    }
    for i in 0..s {
        m.push_face(&[ring(r - 1, i), ring(r - 1, i + 1), north]);
    }
    m
}

/// [`crate::torus`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn torus(major: u32, minor: u32, major_radius: f64, minor_radius: f64) -> PolyMesh {
    let (big_r, small_r) = (major_radius, minor_radius);
    let faces = major as usize * minor as usize;
    let mut m = with_capacity(faces, faces, 4 * faces);
    for i in 0..major {
        let (cu, su) = turn(i, major);
        for j in 0..minor {
            let (cv, sv) = turn(j, minor);
            let rho = big_r + small_r * cv;
            m.positions
                .push(DVec3::new(rho * cu, rho * su, small_r * sv));
        }
    }
    let v = |i: u32, j: u32| (i % major) * minor + j % minor;
    for i in 0..major {
        for j in 0..minor {
            m.push_face(&[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    m
}

/// Pushes a cap polygon over `ring` (a ring of `n` vertices counter-
/// clockwise seen from +z starting at `first`), facing down (−z) when
/// `down`, else up. Both start at the ring's first vertex.
fn push_cap(m: &mut PolyMesh, first: u32, n: u32, down: bool) {
    let cap: Vec<u32> = if down {
        std::iter::once(first)
            .chain((1..n).rev().map(|i| first + i))
            .collect()
    } else {
        (0..n).map(|i| first + i).collect()
    };
    m.push_face(&cap);
}

/// [`crate::cylinder`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn cylinder(segments: u32, rings: u32) -> PolyMesh {
    let (s, r) = (segments, rings);
    let vertices = s as usize * (r as usize + 1);
    let sides = s as usize * r as usize;
    let mut m = with_capacity(vertices, sides + 2, 4 * sides + 2 * s as usize);
    for k in 0..=r {
        let z = unit_coord(k, r);
        for i in 0..s {
            let (c, sn) = turn(i, s);
            m.positions.push(DVec3::new(c, sn, z));
        }
    }
    push_cap(&mut m, 0, s, true);
    push_cap(&mut m, r * s, s, false);
    let v = |k: u32, i: u32| k * s + i % s;
    for k in 0..r {
        for i in 0..s {
            m.push_face(&[v(k, i), v(k, i + 1), v(k + 1, i + 1), v(k + 1, i)]);
        }
    }
    m
}

/// [`crate::cone`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn cone(segments: u32) -> PolyMesh {
    let s = segments;
    let mut m = with_capacity(s as usize + 1, s as usize + 1, 4 * s as usize);
    for i in 0..s {
        let (c, sn) = turn(i, s);
        m.positions.push(DVec3::new(c, sn, -1.0));
    }
    m.positions.push(DVec3::Z);
    push_cap(&mut m, 0, s, true);
    for i in 0..s {
        m.push_face(&[i, (i + 1) % s, s]);
    }
    m
}
