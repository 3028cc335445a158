//! # holey-shapes: built-in primitive meshes
//!
//! Every holey command accepts a primitive in place of an input file,
//! written `@name` or `@name:p1:p2...` (`holey info @torus`,
//! `holey sierpinski @tetrahedron out.obj`, `holey info @sphere:5`).
//! [`parse_primitive`] turns such a spec into a [`PolyMesh`];
//! [`primitive_help`] is the full text for `--help` (parameters,
//! defaults, ranges, sizes, counts and vertex and face order) and
//! [`primitive_summary`] a one-line-per-primitive list, both generated
//! from the [`PRIMITIVES`] table. The generators are also available as
//! plain functions ([`cube`], [`torus`], ...) that validate their
//! parameters the same way.
//!
//! ```
//! let torus = holey_shapes::parse_primitive("@torus:32:16").unwrap();
//! assert_eq!(torus.face_count(), 32 * 16);
//! let err = holey_shapes::parse_primitive("@sphere:99").unwrap_err();
//! assert!(err.to_string().contains("10000000 faces"));
//! ```
//!
//! ## Spec grammar
//!
//! ```text
//! spec   = "@" name { ":" param }
//! name   = one of the names or aliases in PRIMITIVES
//! param  = "" | integer | number
//! ```
//!
//! - The leading `@` is required.
//! - Names are **case-insensitive**, and `-` and `_` in them are ignored:
//!   `@uv-sphere`, `@uvsphere`, `@UV_Sphere` are the same primitive.
//! - Parameters are positional and all optional; missing trailing ones and
//!   empty ones take their defaults (`@torus::16` is 24 × 16 segments).
//!   Integer parameters are decimal integers; real parameters are finite
//!   decimal numbers (`0.25`, `1e-2`). Nothing else (no spaces) is allowed.
//! - No primitive may have more than [`MAX_FACES`] (10 million) faces;
//!   `@sphere:99` and `@torus:5000:5000` are errors that say so.
//!
//! ## What every primitive guarantees
//!
//! - Welded: corners of neighbouring faces share vertex indices; no two
//!   vertices have the same position and every vertex is used.
//! - An oriented 2-manifold: every edge is shared by exactly two faces
//!   that traverse it in opposite directions (the planes have one boundary
//!   loop instead), every vertex has a single fan of faces.
//! - Faces run **counter-clockwise seen from outside** (outward normals,
//!   positive signed volume); the planes face `+z`.
//! - No degenerate faces. Faces of the platonic solids, cubes, cylinders,
//!   cones, tori, UV spheres and planes are planar.
//! - Vertex and face order are deterministic and documented per primitive,
//!   so faces can be addressed by index in file order.
//!
//! ## Sizes
//!
//! The platonic solids are all inscribed in the sphere of radius √3, the
//! circumsphere of the cube `[-1, 1]³`; the tetrahedron's corners are
//! alternate corners of that cube and the dodecahedron contains all eight.
//! Round primitives have unit radius (spheres, torus major radius,
//! cylinder and cone), and heights and planes span `[-1, 1]`. The soccer
//! ball (`@soccerball`, the truncated icosahedron) is inscribed in the
//! platonic solids' sphere of radius √3; the geodesic spheres
//! (`@geodesic:n`, the icosahedron's faces cut into `n²` triangles and
//! projected) have unit radius.
//!
//! ## Face order of the platonic solids and cubes
//!
//! Vertices are listed in order of increasing `z`, then `y`, then `x`;
//! faces in order of their centres by the same rule, so face 0 is the
//! lowest. Each face starts at its lowest-numbered vertex.

#![warn(missing_docs)]

mod error;
mod geodesic;
mod grid;
mod round;
mod solids;
mod spec;

#[cfg(test)]
mod tests;

pub use error::ShapeError;
pub use geodesic::soccer_ball;
pub use holey_mesh::PolyMesh;
pub use solids::{dodecahedron, icosahedron, octahedron, tetrahedron};
pub use spec::{
    PRIMITIVES, Param, ParamKind, Primitive, PrimitiveSpec, find_primitive, is_primitive_spec,
    parse_primitive, parse_spec, primitive_help, primitive_summary,
};

/// The most faces a primitive may have: about ten million, which keeps
/// memory use in the hundreds of megabytes.
pub const MAX_FACES: u64 = 10_000_000;

// The generators with parameters, checked against their entries in the
// spec table (`spec`) before they build: the table calls the unchecked
// builders with parameters its parser checked, so the builders need not
// know the table.

/// The cube `[-1, 1]³` with each side an `n × n` grid of quads (`n = 1`:
/// the plain cube; `1 ≤ n ≤ 1290`).
///
/// Vertices are the grid points of the surface in order of z, then y,
/// then x (for `n = 1`, vertex `i` is at `(2(i&1)−1, 2((i>>1)&1)−1,
/// 2(i>>2)−1)`). Faces are grouped by side in the order −z, −y, −x, +x,
/// +y, +z, `n²` per side; within a side, quads are in order of their
/// centres by z, then y, then x. Each quad runs counter-clockwise seen
/// from outside, starting at its corner with the smallest coordinates
/// (its lowest-numbered vertex). V = 6n²+2, E = 12n², F = 6n².
pub fn cube(n: u32) -> Result<PolyMesh, ShapeError> {
    spec::generate(&spec::CUBE, &[f64::from(n)])
}

/// The unit sphere as `n × n` quads on each of six cube sides: `@cube:n`
/// projected from the centre, with the grid spaced evenly in angle
/// (coordinate `tan(π/4 · t)` for evenly spaced `t` in `[-1, 1]`) so the
/// quads are close to equal in size. Same order and counts as
/// [`cube`]; `1 ≤ n ≤ 1290`.
pub fn quad_sphere(n: u32) -> Result<PolyMesh, ShapeError> {
    spec::generate(&spec::QUAD_SPHERE, &[f64::from(n)])
}

/// An open grid of `nx × ny` quads covering `[-1, 1]²` in the plane
/// z = 0, facing +z, with one boundary loop (`1 ≤ nx, ny`, `nx·ny` at
/// most [`crate::MAX_FACES`]).
///
/// Vertex `j(nx+1) + i` is at `x = −1 + 2i/nx`, `y = −1 + 2j/ny`. Face
/// `j·nx + i` is `(i,j), (i+1,j), (i+1,j+1), (i,j+1)`: counter-clockwise
/// seen from +z, starting at its lowest-numbered corner.
/// V = (nx+1)(ny+1), E = nx(ny+1) + ny(nx+1), F = nx·ny.
pub fn plane(nx: u32, ny: u32) -> Result<PolyMesh, ShapeError> {
    spec::generate(&spec::PLANE, &[f64::from(nx), f64::from(ny)])
}

/// [`plane`] with each square split into two triangles along its
/// diagonal from `(i,j)` to `(i+1,j+1)`: a regular triangle grid whose
/// inner vertices all have valence 6, for sculpting.
///
/// Vertices as [`plane`]. Faces `2(j·nx+i)` and `2(j·nx+i)+1` are
/// `(i,j), (i+1,j), (i+1,j+1)` and `(i,j), (i+1,j+1), (i,j+1)`.
/// V = (nx+1)(ny+1), E = nx(ny+1) + ny(nx+1) + nx·ny, F = 2·nx·ny.
pub fn tri_plane(nx: u32, ny: u32) -> Result<PolyMesh, ShapeError> {
    spec::generate(&spec::TRI_PLANE, &[f64::from(nx), f64::from(ny)])
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
    spec::generate(&spec::SPHERE, &[f64::from(level)])
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
    spec::generate(&spec::UV_SPHERE, &[f64::from(segments), f64::from(rings)])
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
    spec::generate(
        &spec::TORUS,
        &[
            f64::from(major),
            f64::from(minor),
            major_radius,
            minor_radius,
        ],
    )
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
    spec::generate(&spec::CYLINDER, &[f64::from(segments), f64::from(rings)])
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
    spec::generate(&spec::CONE, &[f64::from(segments)])
}

/// The geodesic sphere of frequency `n` (`1 ≤ n ≤ 707`): every face of
/// the icosahedron cut into `n²` triangles by a triangular grid (a
/// class I geodesic subdivision, not its dual), the grid points projected
/// from the centre onto the unit sphere. V = 10n² + 2, E = 30n²,
/// F = 20n² triangles; frequency 1 is the unit icosahedron and
/// frequency `2^L` has the counts of `@sphere:L`.
///
/// Vertices: the 12 icosahedron vertices (in [`crate::icosahedron`]
/// order), then the `n − 1` inner points of each icosahedron edge (edges
/// in order of first use, visiting faces in order and each face's edges
/// `a–b`, `b–c`, `c–a`; points from the lower-numbered end), then the
/// inner points of each face. Faces `t·n² … (t+1)·n² − 1` cover
/// icosahedron face `t = (a, b, c)`: with grid point `(u, v)` at
/// `a + u(b − a)/n + v(c − a)/n`, row by row (`v` from 0), the triangle
/// `((u,v), (u+1,v), (u,v+1))` followed, where it exists, by
/// `((u+1,v), (u+1,v+1), (u,v+1))`.
pub fn geodesic(n: u32) -> Result<PolyMesh, ShapeError> {
    spec::generate(&spec::GEODESIC, &[f64::from(n)])
}
