//! # holey
//!
//! Changes the topology of meshes: it punches holes, joins parts, grows
//! handles and builds very high-genus shapes, on the meshes people really
//! have. This crate is the front door: it re-exports the workspace's
//! crates by what they are, and its [`prelude`] holds what most programs
//! use. Two papers stand behind it:
//!
//! - Srinivasan, *Modeling High-Genus Surfaces* (2004): the doubly linked
//!   face list ([`dlfl`]) with its corners and operators, and the tools
//!   built on it ([`model`]: handles, rinds, Sierpinski polyhedra, Menger
//!   sponges; [`subdiv`]: Catmull–Clark and Doo–Sabin);
//! - Bernstein & Wojtan, *Putting Holes in Holey Geometry* (2013): topology
//!   change for arbitrary triangle meshes during deformation ([`topo`]:
//!   collision parity, exact intersections, error correction, cut and
//!   glue; Booleans by containment and by the winding number) and a
//!   sculpting modeler whose brushes change topology ([`sculpt`]).
//!
//! Below them sit plain polygon meshes ([`mesh`]), files ([`io`]),
//! built-in primitives ([`shapes`]), exact geometry ([`geom`]) and a
//! picture renderer ([`render`]).
//!
//! ## The kernel: build from polygons, insert an edge
//!
//! A polygon soup becomes a DLFL; inserting an edge between two corners of
//! one face splits the face (the thesis's `InsertEdge`, §II.3):
//!
//! ```
//! use holey::prelude::*;
//!
//! // A cube: eight corners, six quads counter-clockwise seen from outside.
//! let corner = |i: u32| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64);
//! let quads = [[0u32, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
//! let mut m = Mesh::from_polygons((0..8).map(corner).collect(), quads)?;
//! let (v, e, f) = (m.vertex_count(), m.edge_count(), m.face_count());
//! assert_eq!((v, e, f), (8, 12, 6));
//! let face = m.faces().next().expect("a cube has faces");
//! let c1 = m.face_corner(face)?;
//! let c2 = m.corner_next(m.corner_next(c1)?)?;
//! m.insert_edge(c1, c2)?;
//! m.validate()?;
//! assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (v, e + 1, f + 1));
//! assert_eq!(m.genus(), 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Handles and rinds (thesis chapters IV and V)
//!
//! A curved handle between the top and the bottom face of a subdivided
//! cube, with negative weights, runs through the cube: a tunnel, genus 1.
//!
//! ```
//! use holey::prelude::*;
//! use holey::model::handle::{HandleParams, create_handle};
//!
//! let mut m = to_dlfl(&shapes::parse_primitive("@cube:3")?)?;
//! // The faces whose centres lie highest and lowest.
//! let height = |f| -> f64 {
//!     let ps = m.face_positions(f).unwrap_or_default();
//!     ps.iter().map(|p| p.z).sum::<f64>() / ps.len() as f64
//! };
//! let top = m.faces().max_by(|a, b| height(*a).total_cmp(&height(*b))).unwrap();
//! let bottom = m.faces().min_by(|a, b| height(*a).total_cmp(&height(*b))).unwrap();
//! let (c1, c2) = (m.face_corner(top)?, m.face_corner(bottom)?);
//! create_handle(&mut m, c1, c2, &HandleParams::new(6, -1.0, -1.0))?;
//! m.validate()?;
//! assert_eq!(m.genus(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A rind is a thick crust around a surface: two shells. Punching one
//! hole through it joins them into one piece; a second hole makes a
//! handle.
//!
//! ```
//! use holey::prelude::*;
//! use holey::model::rind::Rind;
//!
//! let mut rind = Rind::new(to_dlfl(&shapes::parse_primitive("@sphere:1")?)?, 0.1)?;
//! assert_eq!(rind.mesh().topology().component_count(), 2);
//! rind.punch_index(0)?;
//! assert_eq!((rind.mesh().topology().component_count(), rind.mesh().genus()), (1, 0));
//! rind.punch_index(7)?;
//! let m = rind.into_mesh();
//! m.validate()?;
//! assert_eq!(m.genus(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Sierpinski polyhedra and Menger sponges (chapters VI and VII)
//!
//! The thesis's counts for the Sierpinski tetrahedron (figure 39A), and
//! the closed form of the true Menger sponge:
//!
//! ```
//! use holey::prelude::*;
//! use holey::model::menger::{MengerParams, exact_counts, menger};
//! use holey::model::sierpinski::sierpinski;
//!
//! let mut t = to_dlfl(&shapes::parse_primitive("@tetrahedron")?)?;
//! sierpinski(&mut t, 2)?;
//! assert_eq!((t.vertex_count(), t.edge_count(), t.face_count()), (34, 126, 64));
//! assert_eq!(t.genus(), 15);
//!
//! let mut sponge = to_dlfl(&shapes::parse_primitive("@cube")?)?;
//! menger(&mut sponge, &MengerParams { iterations: 2, exact: true, ..MengerParams::default() })?;
//! let (v, e, f, g) = exact_counts(2).expect("level 2 fits");
//! assert_eq!(
//!     (sponge.vertex_count() as u128, sponge.edge_count() as u128, sponge.face_count() as u128),
//!     (v, e, f)
//! );
//! assert_eq!(sponge.genus() as u128, g);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Catmull–Clark
//!
//! One level on a cube: a vertex per old vertex, edge and face.
//!
//! ```
//! use holey::prelude::*;
//!
//! let cube = to_dlfl(&shapes::parse_primitive("@cube")?)?;
//! let smooth = subdiv::catmull_clark(&cube, 1)?;
//! assert_eq!((smooth.vertex_count(), smooth.edge_count(), smooth.face_count()), (26, 48, 24));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## The union of two spheres (Theorem 5.2)
//!
//! Two overlapping spheres united exactly: one closed piece, whose volume
//! lies between the larger sphere's and the sum of both.
//!
//! ```
//! use holey::prelude::*;
//!
//! let a = triangles(&shapes::parse_primitive("@sphere:3")?);
//! let b = a.translated(DVec3::new(1.0, 0.2, 0.1));
//! let out = topo::union(&a, &b, &topo::Options::default())?;
//! assert!(out.mesh.is_closed_manifold());
//! let volume = |m: &TriMesh| -> f64 {
//!     m.triangles.iter().map(|t| {
//!         let [p, q, r] = t.map(|v| m.positions[v as usize]);
//!         p.dot(q.cross(r)) / 6.0
//!     }).sum()
//! };
//! let (va, vu) = (volume(&a), volume(&out.mesh));
//! assert!(va < vu && vu < 2.0 * va);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## One frame of topology change (Bernstein & Wojtan §3)
//!
//! A cube moves, in one frame, from far away into another: the engine
//! finds the collisions and intersections, deletes what ended up inside
//! and glues the rest, leaving one closed surface.
//!
//! ```
//! use holey::prelude::*;
//!
//! let cube = triangles(&shapes::parse_primitive("@cube:2")?);
//! let mut start = cube.clone();
//! start.append(&cube.translated(DVec3::new(5.0, 0.3, 0.2)));
//! let end: Vec<DVec3> = cube
//!     .positions
//!     .iter()
//!     .copied()
//!     .chain(cube.positions.iter().map(|p| *p + DVec3::new(0.5, 0.3, 0.2)))
//!     .collect();
//! let out = topo::topology_change(&start, &end, &topo::Options::default())?;
//! assert!(out.mesh.is_closed_manifold());
//! assert!(out.report.intersecting_pairs > 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Files
//!
//! OBJ, OFF, PLY, STL, glTF (`.gltf`, `.glb`), 3MF and `.dlfl` by
//! extension; writes are atomic.
//!
//! ```
//! use holey::prelude::*;
//!
//! let torus = shapes::parse_primitive("@torus")?;
//! let path = std::env::temp_dir().join(format!("holey-doc-{}.obj", std::process::id()));
//! io::write_poly(&path, &torus, &io::WriteOptions::default())?;
//! let io::MeshFile::Poly(back) = io::read_path(&path)? else {
//!     unreachable!("an OBJ file reads as polygons")
//! };
//! std::fs::remove_file(&path)?;
//! assert_eq!(back.positions, torus.positions);
//! assert_eq!(back.face_count(), torus.face_count());
//! assert_eq!(to_dlfl(&back)?.genus(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub use holey_dlfl as dlfl;
pub use holey_geom as geom;
pub use holey_io as io;
pub use holey_mesh as mesh;
pub use holey_model as model;
pub use holey_render as render;
pub use holey_sculpt as sculpt;
pub use holey_shapes as shapes;
pub use holey_subdiv as subdiv;
pub use holey_topo as topo;

pub use glam::DVec3;

/// What most programs use: the kernel's mesh and handles, plain meshes,
/// the triangle mesh of the engine, and the conversions between them.
pub mod prelude {
    pub use crate::{io, shapes, subdiv, topo};
    pub use crate::{to_dlfl, triangles};
    pub use glam::DVec3;
    pub use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, VertexId};
    pub use holey_mesh::PolyMesh;
    pub use holey_topo::TriMesh;
}

/// The kernel's mesh of a polygon soup (boundaries become hole faces);
/// an error names the face or edge that does not fit a 2-manifold
/// ([`holey_dlfl::convert::to_dlfl`] with default options, which also
/// says how to split non-manifold input).
pub fn to_dlfl(
    soup: &holey_mesh::PolyMesh,
) -> Result<holey_dlfl::Mesh, holey_dlfl::convert::ImportError> {
    holey_dlfl::convert::to_dlfl(soup, holey_dlfl::convert::ImportOptions::default())
        .map(|imported| imported.mesh)
}

/// The triangle mesh of a polygon soup, every face fanned from its first
/// corner (the form the topology engine, Booleans and sculpting take).
pub fn triangles(soup: &holey_mesh::PolyMesh) -> holey_topo::TriMesh {
    soup.triangulated()
}
