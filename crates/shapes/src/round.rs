//! Round primitives: icosphere, UV sphere, torus, cylinder and cone.

use std::cmp::Ordering;
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

use holey_mesh::tri::rows_by_smaller_end;
use holey_mesh::{DVec3, PolyMesh};

use crate::ShapeError;
use crate::grid::{unit_coord, with_capacity};
use crate::solids::{ICOSAHEDRON_FACES, icosahedron_vertices};
use crate::spec::{CONE, CYLINDER, SPHERE, TORUS, UV_SPHERE, validate};

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

/// The unit icosphere: the icosahedron scaled to radius 1 and subdivided
/// `level` times (`0 ≤ level ≤ 9`), each triangle into four, new vertices
/// projected onto the unit sphere. V = 10·4^L + 2, E = 30·4^L,
/// F = 20·4^L.
///
/// Level 0 is [`crate::icosahedron`] scaled to radius 1, in the same
/// order. Each subdivision replaces face `t = (a,b,c)` by faces
/// `4t .. 4t+3` = `(a,ab,ca), (ab,b,bc), (ca,bc,c), (ab,bc,ca)`, where
/// `ab` is the new vertex on edge a–b. Old vertices keep their numbers;
/// new ones follow in order of first use, visiting faces in order and
/// each face's edges a–b, b–c, c–a. So the base-4 digits of a face number
/// below its icosahedron face spell its path: corner 0, 1, 2 or middle 3.
pub fn icosphere(level: u32) -> Result<PolyMesh, ShapeError> {
    validate(&SPHERE, &[f64::from(level)])?;
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
    Ok(m)
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

/// The unit sphere of latitude–longitude quads with triangle fans around
/// the poles: `segments` meridians (`≥ 3`) and `rings` bands from pole to
/// pole (`≥ 2`), evenly spaced in angle. V = segments·(rings−1) + 2,
/// E = segments·(2·rings−1), F = segments·rings.
///
/// Vertex 0 is the south pole (0,0,−1); then come the rings from south to
/// north, each of `segments` vertices starting at angle 0 (towards +x)
/// and running counter-clockwise seen from +z; the last vertex is the
/// north pole. Faces are the south fan, the bands of quads from south to
/// north, then the north fan, each in the same angular order:
/// `(pole, (1,i+1), (1,i))`, `((k,i), (k,i+1), (k+1,i+1), (k+1,i))`,
/// `((last,i), (last,i+1), pole)`, where `(k,i)` is vertex `i` of ring `k`
/// (rings numbered from 1) and indices wrap around.
pub fn uv_sphere(segments: u32, rings: u32) -> Result<PolyMesh, ShapeError> {
    validate(&UV_SPHERE, &[f64::from(segments), f64::from(rings)])?;
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
    Ok(m)
}

/// A quad torus of genus 1 about the z axis: a circle of radius
/// `minor_radius` (r) swept around the circle of radius `major_radius`
/// (R) in the xy plane, with `major ≥ 3` segments around z and
/// `minor ≥ 3` around the tube; `0 < r < R`. V = major·minor,
/// E = 2·major·minor, F = major·minor. The volume tends to 2π²Rr².
///
/// Vertex `i·minor + j` is at angle `2πi/major` around z (from +x,
/// counter-clockwise seen from +z) and `2πj/minor` around the tube (from
/// the outer equator, upwards first). Face `i·minor + j` is
/// `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`, indices wrapping around.
pub fn torus(
    major: u32,
    minor: u32,
    major_radius: f64,
    minor_radius: f64,
) -> Result<PolyMesh, ShapeError> {
    validate(
        &TORUS,
        &[
            f64::from(major),
            f64::from(minor),
            major_radius,
            minor_radius,
        ],
    )?;
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
    Ok(m)
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

/// A closed cylinder of radius 1 along z from −1 to 1, with `segments ≥ 3`
/// around z and `rings ≥ 1` rows of side quads; each cap is a single
/// polygon. V = segments·(rings+1), E = segments·(2·rings+1),
/// F = segments·rings + 2. The volume tends to 2π.
///
/// Vertex `k·segments + i` is on ring `k` (from z = −1 to z = 1) at angle
/// `2πi/segments` (from +x, counter-clockwise seen from +z). Face 0 is the
/// bottom cap, starting at vertex 0 and running clockwise seen from +z;
/// face 1 is the top cap, starting at its vertex at angle 0; face
/// `2 + k·segments + i` is the side quad `(k,i), (k,i+1), (k+1,i+1),
/// (k+1,i)`.
pub fn cylinder(segments: u32, rings: u32) -> Result<PolyMesh, ShapeError> {
    validate(&CYLINDER, &[f64::from(segments), f64::from(rings)])?;
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
    Ok(m)
}

/// A closed cone: a base polygon of radius 1 at z = −1 with `segments ≥ 3`
/// sides, and the apex (0,0,1). V = segments + 1, E = 2·segments,
/// F = segments + 1. The volume tends to 2π/3.
///
/// Vertex `i < segments` is on the base at angle `2πi/segments` (from +x,
/// counter-clockwise seen from +z); the last vertex is the apex. Face 0 is
/// the base, starting at vertex 0 and running clockwise seen from +z;
/// face `1 + i` is the triangle `(i, i+1, apex)`.
pub fn cone(segments: u32) -> Result<PolyMesh, ShapeError> {
    validate(&CONE, &[f64::from(segments)])?;
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
    Ok(m)
}
