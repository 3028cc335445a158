//! # holey-subdiv: smoothing subdivision of DLFL meshes
//!
//! [Catmull–Clark](catmull_clark) (Catmull & Clark 1978) and
//! [Doo–Sabin](doo_sabin) (Doo & Sabin 1978, original weights) for any mesh
//! the [`holey_dlfl`] kernel holds: self-loops, two-gons, monogons,
//! multiple edges, valence-1 and valence-2 vertices, point-spheres, several
//! components and open surfaces (hole faces). The thesis smooths its
//! Sierpinski polyhedra with these schemes (Srinivasan 2004, §VI.6,
//! figures 43 and 44) and shows what two-gons do to them (§V.2.3,
//! figure 28). Each scheme's module documentation gives its rules and what
//! it does with every special case and with boundaries.
//!
//! Both schemes keep, component by component, the genus, the number of
//! boundary loops (each hole face becomes one hole face) and the
//! components themselves (point-spheres are copied unchanged). The input
//! mesh is never modified.
//!
//! TopMod's remeshing schemes (dual, √3, Loop, root-4, truncations,
//! stellations, corner cutting, honeycomb, pentagonal, checkerboard,
//! extrusions, …) are in [`mod@remesh`], one entry point [`remesh()`] over a
//! [`RemeshScheme`].
//!
//! ```
//! use holey_dlfl::convert::{ImportOptions, to_dlfl};
//!
//! let cube = to_dlfl(&holey_shapes::cube(1)?, ImportOptions::default())?.mesh;
//! let smooth = holey_subdiv::catmull_clark(&cube, 2)?;
//! assert_eq!((smooth.vertex_count(), smooth.edge_count(), smooth.face_count()), (98, 192, 96));
//! let cut = holey_subdiv::doo_sabin(&cube, 1)?;
//! assert_eq!((cut.vertex_count(), cut.edge_count(), cut.face_count()), (24, 48, 26));
//! assert_eq!(cut.genus(), 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Cost
//!
//! Each level runs on compact flat arrays (corner → vertex, face, edge;
//! edge → its two corners) in a handful of linear passes, with index
//! arithmetic for the new connectivity: O(output) time and memory, no
//! search, no hashing and no per-face work that grows faster than the face
//! (TopMod's Doo–Sabin is O(F²)). The kernel mesh is built once, at the
//! end, by [`Mesh::from_raw_trusted`]: subdivision of a valid 2-manifold
//! is one by construction, so the per-element checks run but the global
//! rotation pass only in debug builds (the tests validate every output).
//! [`subdivide_to_raw`] stops before the build, for callers that only
//! write the result out.
//!
//! ## Size cap
//!
//! The output size of every level is computed from the input's counts
//! before anything is allocated; more than [`MAX_FACES`] faces (or more
//! entities than the kernel's 32-bit indices hold) is a
//! [`SubdivError::TooLarge`] error. [`subdivide_capped`] takes another cap.

#![warn(missing_docs)]

mod catmull_clark;
mod doo_sabin;
mod flat;
pub mod remesh;

#[cfg(test)]
mod tests;

use std::fmt;

use holey_dlfl::{Mesh, NonFinite, RawMesh};

pub use flat::Counts;
use flat::Flat;
pub use remesh::{
    MAX_LEVELS, RemeshOption, RemeshParams, RemeshScheme, remesh, remesh_capped, remesh_to_raw,
};

/// The most faces a subdivision may produce by default: fifty million,
/// about 10 GB as a kernel mesh.
pub const MAX_FACES: usize = 50_000_000;

/// A smoothing subdivision scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// Catmull–Clark: quads, approximating bicubic B-splines.
    CatmullClark,
    /// Doo–Sabin: corner cutting, approximating biquadratic B-splines.
    DooSabin,
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Scheme::CatmullClark => "Catmull-Clark",
            Scheme::DooSabin => "Doo-Sabin",
        })
    }
}

/// Why a mesh could not be subdivided. The input is never changed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SubdivError {
    /// The predicted output of some level has more faces than the cap, or
    /// more vertices, edges or corners than the kernel's 32-bit indices
    /// hold; found from the counts before anything is allocated.
    #[error(
        "{levels} level(s) of {scheme} subdivision would make {faces} faces and {corners} corners \
         at level {level}, over the cap of {cap} faces (and the kernel's 32-bit indices)"
    )]
    TooLarge {
        /// The scheme that was asked for.
        scheme: Scheme,
        /// The number of levels that was asked for.
        levels: usize,
        /// The first level that is too large.
        level: usize,
        /// Predicted number of faces at `level`, holes and point-spheres
        /// included.
        faces: u128,
        /// Predicted number of corners at `level`.
        corners: u128,
        /// The cap on output faces in force ([`MAX_FACES`] unless a
        /// `_capped` function was given another).
        cap: usize,
    },
    /// An input vertex has a NaN or infinite coordinate: the first such
    /// vertex, by its index among the input's live vertices in slot order
    /// (the numbering of [`Mesh::to_raw`]).
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// The input was finite but an output position is not: with coordinates
    /// this large, the sums taken while averaging overflowed `f64`.
    #[error(
        "{scheme} subdivision overflowed: output vertex {vertex} is not finite (coordinates too large)"
    )]
    Overflow {
        /// The scheme that was run.
        scheme: Scheme,
        /// Index of the first non-finite output vertex, in the output's
        /// vertex numbering.
        vertex: usize,
    },
    /// A consistency check inside a scheme failed; a bug, described by the
    /// text, not a property of the input.
    #[error("internal error in subdivision (please report): {0}")]
    Internal(String),
    /// The remeshing scheme needs a closed surface (it is built from the
    /// dual, see [`RemeshScheme::needs_closed_surface`]) and the mesh has
    /// hole faces.
    #[error(
        "remeshing scheme {scheme} is not defined on meshes with boundary: the mesh has \
         {holes} hole face(s); close the boundary first"
    )]
    Boundary {
        /// The scheme that was asked for.
        scheme: RemeshScheme,
        /// How many hole faces (boundary loops) the mesh has.
        holes: usize,
    },
    /// A step of the remeshing would have more faces than the cap, or more
    /// vertices, edges or corners than the kernel's 32-bit indices hold;
    /// found from the step's input before its output is allocated.
    #[error(
        "{levels} level(s) of {scheme} remeshing would make {faces} faces and {corners} corners \
         at level {level}, over the cap of {cap} faces (and the kernel's 32-bit indices)"
    )]
    RemeshTooLarge {
        /// The scheme that was asked for.
        scheme: RemeshScheme,
        /// The number of levels that was asked for.
        levels: usize,
        /// The first level that is too large.
        level: usize,
        /// Faces of the refused step, holes and point-spheres included.
        faces: u128,
        /// Corners of the refused step.
        corners: u128,
        /// The cap on faces in force ([`MAX_FACES`] unless
        /// [`remesh_capped`] was given another).
        cap: usize,
    },
    /// More levels than [`MAX_LEVELS`] were asked for.
    #[error("{levels} levels of {scheme} remeshing asked for; at most {max} are allowed")]
    TooManyLevels {
        /// The scheme that was asked for.
        scheme: RemeshScheme,
        /// The number of levels that was asked for.
        levels: usize,
        /// [`MAX_LEVELS`].
        max: usize,
    },
    /// The input was finite but an output position of the remeshing is
    /// not: the coordinates (or the parameters) are too large.
    #[error(
        "{scheme} remeshing overflowed: output vertex {vertex} is not finite (coordinates or \
         parameters too large)"
    )]
    RemeshOverflow {
        /// The scheme that was run.
        scheme: RemeshScheme,
        /// Index of the first non-finite output vertex.
        vertex: usize,
    },
    /// A parameter the scheme reads is not finite or out of its range.
    #[error("{scheme} remeshing: parameter {name} is {value}, it must be {expected}")]
    InvalidParameter {
        /// The scheme that was asked for.
        scheme: RemeshScheme,
        /// The field of [`RemeshParams`].
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// An option the scheme does not read ([`RemeshScheme::options`]).
    #[error(
        "{scheme} remeshing does not read the option {name:?}; it reads {}",
        list_options(*scheme)
    )]
    UnknownOption {
        /// The scheme that was asked for.
        scheme: RemeshScheme,
        /// The name given.
        name: String,
    },
    /// A name that is no [`RemeshScheme`]'s.
    #[error(
        "unknown remeshing scheme {name:?}; the schemes are: {}",
        RemeshScheme::ALL.iter().map(|s| s.name()).collect::<Vec<_>>().join(", ")
    )]
    UnknownScheme {
        /// The name given.
        name: String,
    },
}

fn list_options(scheme: RemeshScheme) -> String {
    let names: Vec<&str> = scheme.options().iter().map(|o| o.name).collect();
    if names.is_empty() {
        "no options".to_string()
    } else {
        names.join(", ")
    }
}

/// `levels` levels of Catmull–Clark subdivision of `mesh`, as a new mesh
/// (zero levels return a copy).
///
/// # Rules (Catmull & Clark 1978)
///
/// For every ordinary face `f` a **face point** `F(f)`, the centroid of its
/// corners. For every edge `e` an **edge point**: the average of its two
/// end points and the face points on its two sides,
/// `(P₀ + P₁ + F(f_a) + F(f_b)) / 4`. For every vertex a **vertex point**
/// `(Q + 2R + (n − 3)S) / n`, where `S` is the old position, `n` the number
/// of corners at the vertex (its valence: one per edge end, a self-loop
/// counting twice), `Q` the average of the face points of its corners'
/// faces and `R` the average of the midpoints of the edges that start at
/// its corners. With `R = (S + avg(neighbours))/2` this is
/// `Σ(F(f_c) + P(next c)) / n² + (n − 2)S / n`, which the code evaluates in
/// one pass over the corners.
///
/// Every corner `c` of an ordinary face becomes the quad
/// `[v(c), E(edge(c)), F(face(c)), E(edge(prev c))]`, which keeps the
/// orientation. Each edge splits in two at its edge point and each corner
/// adds the edge from its outgoing edge's point to the face point.
///
/// # What the rules do with the DLFL's special cases
///
/// The construction is per corner, so it is defined for every
/// combinatorial map and keeps genus, components and boundary loops:
/// - a **self-loop** at `v` gets an edge point `(2v + F_a + F_b)/4` and
///   becomes two edges from `v` to it (a multi-edge); its zero length
///   counts in `R` as two midpoints at `v`. So the Sierpinski polyhedra
///   of §VI.5, whose small tetrahedra are joined only through self-loops,
///   smooth into one connected surface of the same genus (§VI.6 names
///   both schemes; figures 43–44 show Doo–Sabin);
/// - a **two-gon** gives two quads and a face point of valence 2. Textbook
///   rules keep the tangent discontinuity the thesis shows in figure 28B;
///   call [`holey_dlfl::Mesh::remove_two_gons`] first to avoid it;
/// - a **monogon** (one corner and a self-loop) gives one quad that visits
///   the loop's edge point twice, with a dangling edge to its face point;
/// - a **point-sphere** has no edge and nothing to subdivide: it is kept,
///   vertex, face and position unchanged, so components are preserved;
/// - a vertex with a single corner and no hole (the tip of a dangling
///   edge) is kept fixed: the rule's `(n − 3)/n` weight would be −2.
///
/// # Boundaries (hole faces)
///
/// A hole face is a boundary loop, not a face: it gets no face point and
/// no quads. Its `k` corners become a hole of `2k` corners (each old
/// vertex, then the point of the edge leaving it), so holes correspond one
/// to one. Boundary curves refine as cubic B-splines:
/// - the point of an edge with a hole on either side is its midpoint;
/// - a vertex with exactly one hole corner and at least three corners
///   moves to `(prev + 6v + next)/8`, its neighbours along the hole;
/// - a **corner** vertex (one hole corner and one face, valence 2) stays
///   fixed, as does any vertex the boundary touches more than once (two
///   or more hole corners: the boundary pinches there, so no single curve
///   passes through it).
///
/// Interior vertices and the edges between ordinary faces use the
/// textbook rules even next to the boundary.
pub fn catmull_clark(mesh: &Mesh, levels: usize) -> Result<Mesh, SubdivError> {
    subdivide(mesh, Scheme::CatmullClark, levels)
}

/// `levels` levels of Doo–Sabin subdivision of `mesh`, as a new mesh (zero
/// levels return a copy).
///
/// # Rules (Doo & Sabin 1978), original weights
///
/// Every corner `c` of an ordinary face with `n` corners `v₀ … v_{n−1}`
/// (`v₀` the corner's own vertex) gets a new **corner point**
/// `Σ αᵢ vᵢ` with
///
/// ```text
/// α₀ = 1/4 + 5/(4n),   αᵢ = (3 + 2 cos(2πi/n)) / (4n)   (i > 0).
/// ```
///
/// These are Doo and Sabin's own weights (quads get the biquadratic
/// B-spline's 9/16, 3/16, 1/16, 3/16), not the simpler "average of vertex,
/// edge midpoints and centroid" variant. They sum to 1 for every `n ≥ 2`;
/// a monogon's single corner point is its vertex. Since
/// `Σᵢ cos(2πi/n) v_{j+i} = cos θⱼ·C + sin θⱼ·S` with
/// `C = Σₘ cos θₘ vₘ`, `S = Σₘ sin θₘ vₘ`, `θₘ = 2πm/n`, a face's corner
/// points cost O(n), not O(n²), however large the face.
///
/// The new faces, all built from corner points:
/// - an **F-face** per face: its corner points in order;
/// - an **E-face** per edge: the quad of the four corner points at the
///   edge's ends, two on each side;
/// - a **V-face** per vertex: the corner points of its corners in rotation
///   order, so a vertex of valence `n` gives an `n`-gon.
///
/// Written per corner on the combinatorial map, with the rotation
/// `rot(c) = next(twin(c))` walked backwards for the V-faces, the
/// construction keeps the surface's genus and components for any DLFL
/// (V' = C, E' = 2C, F' = F + E + V with C = 2E corners, so χ is
/// unchanged, and the faces around an old vertex, edge or face stay
/// joined through its new face):
/// - a **self-loop** at `v` gives an E-face between the two sectors it
///   separates at `v`, and both of its ends add a corner to `v`'s V-face;
///   a Sierpinski polyhedron (§VI.5) therefore smooths into one connected
///   surface of the same genus, as in figures 43 and 44;
/// - a **two-gon** gives a two-gon F-face (corner points at 7/8 and 1/8 of
///   its two vertices) and a vertex of valence 2 gives a two-gon V-face.
///   They are kept, since removing them is a topological choice;
///   [`holey_dlfl::Mesh::remove_two_gons`] removes them (figure 29);
/// - a **monogon** gives a monogon F-face; a vertex of valence 1 gives a
///   monogon V-face;
/// - a **point-sphere** is kept as it is (vertex, face and position), so
///   components are preserved; it has no edge to make faces from.
///
/// # Boundaries (hole faces)
///
/// The boundary polygon is refined by **Chaikin's corner cutting**, so
/// every boundary loop converges to the uniform quadratic B-spline of its
/// control polygon (the curve analogue of Doo–Sabin). Each hole corner `c`
/// at `v`, between its neighbours `u` (before) and `w` (after) along the
/// hole, gets two points instead of one: `3/4 v + 1/4 u` and
/// `3/4 v + 1/4 w`. The hole's `k` corners thus become a hole of `2k`
/// corners, the Chaikin polygon; the boundary edge's E-face is the quad
/// between its two Chaikin points and the two corner points inside, and a
/// boundary vertex's V-face gains one corner, closing it along the chord
/// of the cut corner. Topologically this is Doo–Sabin of the closed DLFL
/// with each hole corner point split into an edge, so genus, components
/// and boundary loops are preserved. Corner points of ordinary faces use
/// the weights above even next to the boundary.
///
/// Boundary corners are rounded (cut) like every other boundary vertex:
/// the quadratic B-spline does not interpolate its control points. An
/// edge with a hole on both sides (a "wire") becomes a flat, zero-area
/// quad E-face, which keeps the two sides joined.
pub fn doo_sabin(mesh: &Mesh, levels: usize) -> Result<Mesh, SubdivError> {
    subdivide(mesh, Scheme::DooSabin, levels)
}

/// `levels` levels of `scheme`, capped at [`MAX_FACES`] output faces.
///
/// Faces, corners and edges come in the order [`subdivide_to_raw`]
/// describes, but the vertices are renumbered in the order the faces
/// first use them: neighbours on the surface are then neighbours in
/// memory, which makes building and validating the kernel mesh about a
/// quarter faster than with the structured vertex numbering. Use
/// [`subdivide_to_raw`] and [`Mesh::from_raw`] to keep that numbering.
pub fn subdivide(mesh: &Mesh, scheme: Scheme, levels: usize) -> Result<Mesh, SubdivError> {
    subdivide_capped(mesh, scheme, levels, MAX_FACES)
}

/// [`subdivide`] with another cap on the number of output faces.
pub fn subdivide_capped(
    mesh: &Mesh,
    scheme: Scheme,
    levels: usize,
    max_faces: usize,
) -> Result<Mesh, SubdivError> {
    if levels == 0 {
        return Ok(mesh.clone());
    }
    run(mesh, scheme, levels, max_faces)?
        .into_mesh(|vertex| SubdivError::Overflow { scheme, vertex })
}

/// The subdivided mesh as flat arrays, ready for [`Mesh::from_raw`] or a
/// file writer, without building the kernel mesh.
///
/// Numbering (input entities counted in slot order):
/// - Catmull–Clark: output vertex `i < V` is the vertex point of input
///   vertex `i`; then come the edge points in input edge order and the
///   face points in input face order. Faces follow input face order: an
///   ordinary face's quads in corner order (the quad of its `j`-th corner
///   starts at that corner's vertex point), a hole's refined hole, a
///   point-sphere's copy.
/// - Doo–Sabin: the vertices are the corner points in input corner order
///   (two per hole corner, a point-sphere's vertex for its corner). Output
///   face `f < F` is input face `f`'s F-face (holes and point-spheres
///   included), then come the E-faces in input edge order and the V-faces
///   in input vertex order (point-sphere vertices have none).
/// - Edges are numbered in the order of their first corner (Catmull–Clark)
///   or by the input edge and hole corner they come from (Doo–Sabin).
pub fn subdivide_to_raw(
    mesh: &Mesh,
    scheme: Scheme,
    levels: usize,
) -> Result<RawMesh, SubdivError> {
    subdivide_to_raw_capped(mesh, scheme, levels, MAX_FACES)
}

/// [`subdivide_to_raw`] with another cap on the number of output faces.
pub fn subdivide_to_raw_capped(
    mesh: &Mesh,
    scheme: Scheme,
    levels: usize,
    max_faces: usize,
) -> Result<RawMesh, SubdivError> {
    Ok(run(mesh, scheme, levels, max_faces)?.into_raw())
}

/// Runs the levels on flat arrays.
fn run(mesh: &Mesh, scheme: Scheme, levels: usize, max_faces: usize) -> Result<Flat, SubdivError> {
    let mut src = Flat::from_mesh(mesh)?;
    check_size(src.counts(), scheme, levels, max_faces)?;
    let mut dst = Flat::default();
    match scheme {
        Scheme::CatmullClark => {
            let mut scratch = catmull_clark::Scratch::default();
            for level in 1..=levels {
                if src.edges.is_empty() {
                    break; // point-spheres only: a fixed point
                }
                dst.clear();
                catmull_clark::step(&src, &mut dst, &mut scratch, level < levels)?;
                std::mem::swap(&mut src, &mut dst);
            }
        }
        Scheme::DooSabin => {
            let mut scratch = doo_sabin::Scratch::default();
            for _ in 0..levels {
                if src.edges.is_empty() {
                    break; // point-spheres only: a fixed point
                }
                dst.clear();
                doo_sabin::step(&src, &mut dst, &mut scratch)?;
                std::mem::swap(&mut src, &mut dst);
            }
        }
    }
    if let Some(vertex) = src.pos.iter().position(|p| !p.is_finite()) {
        return Err(SubdivError::Overflow { scheme, vertex });
    }
    Ok(src)
}

/// The counts [`subdivide`] would produce, computed from `mesh`'s counts
/// without subdividing; the same [`SubdivError::TooLarge`] when the output
/// would be over [`MAX_FACES`].
pub fn predict(mesh: &Mesh, scheme: Scheme, levels: usize) -> Result<Counts, SubdivError> {
    check_size(Flat::from_mesh(mesh)?.counts(), scheme, levels, MAX_FACES)
}

/// The counts after one level of `scheme`.
fn next_counts(k: Counts, scheme: Scheme) -> Counts {
    match scheme {
        Scheme::CatmullClark => Counts {
            vertices: k.vertices + k.edges + k.normal_faces,
            edges: 2 * k.edges + k.normal_corners,
            normal_faces: k.normal_corners,
            hole_faces: k.hole_faces,
            point_spheres: k.point_spheres,
            normal_corners: 4 * k.normal_corners,
            hole_corners: 2 * k.hole_corners,
        },
        Scheme::DooSabin => Counts {
            vertices: k.normal_corners + 2 * k.hole_corners + k.point_spheres,
            edges: 4 * k.edges + k.hole_corners,
            normal_faces: k.normal_faces + k.edges + (k.vertices - k.point_spheres),
            hole_faces: k.hole_faces,
            point_spheres: k.point_spheres,
            normal_corners: 2 * k.normal_corners + 2 * k.hole_corners + 4 * k.edges,
            hole_corners: 2 * k.hole_corners,
        },
    }
}

/// Predicts every level's counts and refuses the first that is too large.
/// A mesh with corners grows by at least a factor of 2 per level, so this
/// fails within about 32 levels; a mesh of point-spheres only (no edge) is
/// a fixed point and stops at once.
fn check_size(
    mut k: Counts,
    scheme: Scheme,
    levels: usize,
    max_faces: usize,
) -> Result<Counts, SubdivError> {
    let limit = u128::from(u32::MAX - 1);
    for level in 1..=levels {
        let next = next_counts(k, scheme);
        if next == k {
            break;
        }
        k = next;
        let too_big = k.faces() > max_faces as u128
            || k.corners() > limit
            || k.vertices > limit
            || k.edges > limit;
        if too_big {
            return Err(SubdivError::TooLarge {
                scheme,
                levels,
                level,
                faces: k.faces(),
                corners: k.corners(),
                cap: max_faces,
            });
        }
    }
    Ok(k)
}

/// Refuses an entity count the kernel's 32-bit indices cannot hold (the
/// size check makes this unreachable; it guards the index arithmetic).
pub(crate) fn check_index(n: usize) -> Result<(), SubdivError> {
    if n >= u32::MAX as usize {
        Err(SubdivError::Internal(format!(
            "{n} entities exceed 32-bit indices"
        )))
    } else {
        Ok(())
    }
}
