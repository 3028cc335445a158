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
pub use geodesic::{geodesic, soccer_ball};
pub use grid::{cube, plane, quad_sphere, tri_plane};
pub use holey_mesh::PolyMesh;
pub use round::{cone, cylinder, icosphere, torus, uv_sphere};
pub use solids::{dodecahedron, icosahedron, octahedron, tetrahedron};
pub use spec::{
    PRIMITIVES, Param, ParamKind, Primitive, PrimitiveSpec, find_primitive, is_primitive_spec,
    parse_primitive, parse_spec, primitive_help, primitive_summary,
};

/// The most faces a primitive may have: about ten million, which keeps
/// memory use in the hundreds of megabytes.
pub const MAX_FACES: u64 = 10_000_000;
