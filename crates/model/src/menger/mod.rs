//! Generalized Menger sponges (Srinivasan 2004, chapter VII), and the true
//! Menger sponge (beyond the thesis: its future-work item 4).
//!
//! # The thesis's algorithm (§VII.3), one level
//!
//! With a thickness `D`, for every face `fi` with corners `p0 … pN−1` and
//! average unit normal `ni`:
//!
//! 1. **Remeshing face pair** `(f′i,f, f′i,b) = CreateFaceManifold(p′0 …)`
//!    with `p′j = pj + D·vo,j`, `vo,j = e1 + e2` (the unit vectors from `pj`
//!    towards its two neighbours). §VII.5.2: at a *non-convex* corner
//!    (interior angle over 180°) `p′j = pj − D·vo,j`. §VII.5.3: at a
//!    *winged* corner (exactly 180°) `vo,j = ni × e1`, which points into
//!    the face.
//! 2. **Offset face pair** `(f″i,f, f″i,b)` on `p″j = p′j − D·ni`.
//! 3. For every original edge, `ConnectEdges` between the matching edges of
//!    the two *outward* offset faces (f″1,f and f″2,f); this sews the
//!    offset faces into one inward-facing surface with a strip per edge and
//!    a face per vertex. Then collapse the two inserted edges where §VII.4
//!    says so (below).
//! 4. Trisect every original edge so that its end segments have length
//!    `D`, and `ConnectEdges` each middle segment (in `fi`) with the
//!    matching edge of the *inward* remeshing face `f′i,b`. Each face of `k`
//!    corners becomes `2k` quadrilaterals and the remeshing face `f′i,f`.
//! 5. `CreatePipe` from each `f′i,f` to its `f″i,b`, at matching corners.
//!
//! Between levels the two-gons left by collapsed strips are removed
//! ([`Mesh::remove_two_gons`]), so the next level sees plain faces.
//!
//! ## The collapse decision (§VII.4)
//!
//! `φ` is the interior (solid-side) dihedral angle of the original edge,
//! computed from the two faces' normals projected perpendicular to the
//! edge: `φ = 180° − atan2(t·(n1 × n2), n1·n2)`, with `t` the edge
//! direction as its first face walks it.
//!
//! | case | φ | the thesis | here |
//! |---|---|---|---|
//! | 1 | < 90° | collapse (offset faces intersect) | collapse |
//! | 2 | = 90° | collapse (the strip has no width) | collapse |
//! | 3 | 90°–180° | user's choice | collapse iff `φ < collapse_angle_deg` |
//! | 4 | = 180° | keep | keep |
//! | 5 | 180°–270° | keep; a fix is described but not implemented | keep, and bend |
//! | 6 | ≥ 270° | keep; same | keep, and bend |
//!
//! **Bend** (cases 5 and 6) is the fix of §VII.5.4 / figure 61 that the
//! thesis left out: at each end of the strip a new vertex is inserted on
//! the connecting edge, at the point `X = p − D·(n1 + n2)/(1 + n1·n2)`
//! (moved along the edge to the middle of the strip's end), which is at
//! distance `D` behind *both* face planes, and an edge joins the two new
//! vertices across the strip. The strip becomes two quadrilaterals that
//! keep the thickness `D` instead of cutting towards (case 5) or through
//! (case 6) the original edge. Topology is unchanged (V+2, E+3, F+1).
//!
//! When a connecting edge is collapsed, its two ends merge. All offset
//! corners merged together are placed at their centroid, which does not
//! depend on the order of the collapses (the kernel's `CollapseEdge` puts
//! each merge at a midpoint). A connecting edge that has become a self-loop
//! is removed, as the thesis says; so is a kept one whose two ends were
//! merged through other collapses (it would be a zero-length loop around a
//! one-cornered face).
//!
//! **Zipping.** Where bends meet collapses, a vertex face can have two
//! distinct corners at one point (on a cube's level 2, at each tunnel's
//! rim corner the bend vertex of the tunnel's re-entrant edge lands on the
//! offset corner of the neighbouring flat face), which leaves a face of
//! zero area. Each vertex face is therefore zipped shut where its corners
//! coincide: an edge between the two corners (or the zero-length edge
//! already there) is collapsed, and the slivers left are two-gons, removed
//! at the end of the level. χ is unchanged.
//!
//! ## Tolerances
//!
//! Equality of angles (φ = 90°, 180°, 270°, and a winged corner's 180°) is
//! tested with a tolerance relative to the *conditioning* of the angle: a
//! position known to within `ε·s` (`s` the largest coordinate magnitude
//! involved) moves an angle over a length `h` by about `ε·s/h`, so the
//! tolerance is `ANGLE_ULPS · ε · (1 + s/h)` radians, `ε` the f64 machine
//! epsilon and `ANGLE_ULPS = 256`. Nothing compares against an absolute
//! epsilon: scaling or translating the mesh scales the tolerance with it.
//! Areas are compared against `AREA_REL` times the face's squared size.
//!
//! ## Special cases
//!
//! - **Non-planar faces** (§VII.5.1): the thesis notes the problem has no
//!   simple solution, that slight skew still gives acceptable results, and
//!   that non-planar faces can always be triangulated. So: a face off its
//!   mean plane by at most 1% of its longest edge is used as it is, with
//!   its Newell (average) normal (those off by more than `1e-9` are
//!   counted in [`MengerLevel::nonplanar_faces`]); a more skewed face is
//!   first cut along diagonals into planar pieces (counted in
//!   [`MengerLevel::skew_cuts`]). The algorithm makes such faces itself:
//!   from level 3 on a cube, around a vertex where three re-entrant edges
//!   meet, a hexagon folded over a box's inside corner, cut into its two
//!   planar quadrilaterals.
//! - **Thickness too large**: checked per face before anything changes.
//!   Every original edge must be longer than `2D`; every remeshing edge
//!   must keep its direction; every corner quad, edge quad and remeshing
//!   face must keep a positive area along the face normal; and every
//!   offset face, with its merged corners, must keep the direction of every
//!   edge (a point reflection through the centre, as a too-deep offset of a
//!   tetrahedron gives, reverses them). The error names the face. Global
//!   self-intersection (offsets of opposite sides of a thin part crossing)
//!   is not detected.
//! - Open surfaces (hole faces), faces of fewer than 3 corners, self-loops
//!   (a Sierpinski polyhedron's, say) and an edge with one face on both
//!   sides are refused. A DLFL mesh is a 2-manifold by construction;
//!   non-manifold soups are refused (or split) when they are imported.
//!
//! ## Counts
//!
//! A closed genus-`g` component with `V`, `E`, `F` (after any skew cuts)
//! gives one component of genus `2g + F − 1`: before any collapse it has
//! `V + 6E` vertices, `15E` edges and `7E + V` faces (χ = 2V − 2E), and
//! collapses, loop removals, bends, zipping and two-gon removals all keep
//! χ. A cube with `D` a third of its edge gives 64/144/72, genus 5:
//! exactly the level-1 Menger sponge. A second level (D a third of the new
//! edges) gives 800/1920/960, genus 81: with the bends and zipping it
//! encloses exactly the true level-2 sponge (same volume and area; 960
//! faces instead of 1056 because coplanar strips keep their width 2D).
//! The thesis saw interior differences at level 2 (§VII.6) without the
//! figure-61 fix. From level 3 on the surfaces differ for good: the
//! algorithm drills each face of the previous level once, so the faces of
//! width 2D get one tunnel where the true sponge has two (level 3: genus
//! 2·81 + 960 − 1 = 1121, the true sponge 1409).
//!
//! ## Cost
//!
//! Planning is one pass over faces and edges; every kernel operation
//! after it is local (O(1), or linear in the small faces it touches), so a
//! level is linear in its output. Measured (release, this shared 2-core
//! machine; ±30% with load):
//! a cube's levels 1–4 (186 144 faces) in 0.22 s, a fifth level (2.6 M
//! faces) in 3.1 s; one level on `@cube:100` (0.9 M faces) in 0.57 s.
//! Exact mode: level 4 (336 384 faces) in 0.28 s, level 5 (6.5 M) in 6.9 s,
//! 40% of it in the kernel's `from_raw` validation.
//!
//! # The true Menger sponge (`exact: true`)
//!
//! The thesis's future-work item 4 asks for an exact replica. With `exact`
//! set, the input must be a parallelepiped (a cube up to an affine map: 8
//! vertices, 12 edges, 6 quadrilaterals, every edge along one of three
//! edge vectors from a corner), and the output is the boundary of the
//! union of the `20^n` sub-cells that survive `n` levels of the
//! construction, mapped affinely onto the input: the sub-cell with
//! base-3 digit triples `(x_k, y_k, z_k)` survives when no digit position
//! has two or more 1s. Every exposed cell face is one quadrilateral, with
//! the input's orientation. Counts: F from the surface area
//! (`2(20/9)^n + 4(8/9)^n` of a unit cube's side², in cells of side
//! `3^−n`); E = 2F as every face is a quadrilateral and every edge has two
//! sides; and a closed form for the genus, `a·20^n + b·8^n + c` fitted to
//! levels 0–2 and checked against independent brute-force cell counts
//! (levels 1–3 in the unit tests, level 4 once by a separate script: 5,
//! 81, 1409, 26433; 1409 is also the shared level-3 mesh's genus):
//!
//! ```text
//! F = 2·20^n + 4·8^n,   E = 2F,   genus = (21·20^n + 38·8^n − 59)/133,
//! V = F + 2 − 2·genus
//! ```
//!
//! Level 1: 64/144/72 (genus 5), 2: 896/2112/1056 (81), 3: 15232/36096/18048
//! (1409). `thickness` and `collapse_angle_deg` are validated but unused:
//! the true sponge's thickness is fixed at a third. Any other input is
//! refused with [`MengerError::NotAParallelepiped`]; the thesis's algorithm
//! is the generalization to other shapes.

mod apply;
mod exact;
mod plan;
mod skew;

use holey_dlfl::{EdgeId, FaceId, Mesh};

pub use exact::{ExactSponge, exact_counts};

/// The default cap on the faces one level may produce (about 4 corners of
/// ~30 bytes each per face in the kernel: a few gigabytes at the cap).
pub const MAX_FACES: usize = 20_000_000;

/// How thick the sponge's walls are: the thesis's `D`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Thickness {
    /// `D` itself, in model units, at every level.
    Absolute(f64),
    /// `D = R ×` the mean edge length, recomputed at every level (R = 1/3 on
    /// a cube reproduces figure 62).
    RatioOfMeanEdge(f64),
}

/// Parameters of [`menger`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MengerParams {
    /// Number of levels.
    pub iterations: usize,
    /// The wall thickness `D` (§VII.3), in model units or relative to the
    /// mean edge length.
    pub thickness: Thickness,
    /// Case 3 of §VII.4 (90° < φ < 180°): the connecting edges of an
    /// original edge are collapsed when its interior angle φ is below this
    /// many degrees. Must lie in [90, 180]; 90 never collapses case 3.
    pub collapse_angle_deg: f64,
    /// Build the true Menger sponge instead (input: a parallelepiped).
    pub exact: bool,
}

impl Default for MengerParams {
    fn default() -> Self {
        MengerParams {
            iterations: 1,
            thickness: Thickness::RatioOfMeanEdge(1.0 / 3.0),
            collapse_angle_deg: 90.0,
            exact: false,
        }
    }
}

/// Why [`menger`] refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MengerError {
    /// The thickness is not a finite positive number, either as given or
    /// once a ratio is multiplied by the mean edge length.
    #[error("thickness must be a finite number greater than 0, got {value}")]
    InvalidThickness {
        /// The rejected value: the given `D` or ratio, or the computed `D`.
        value: f64,
    },
    /// [`MengerParams::collapse_angle_deg`] is outside [90, 180] (or NaN).
    #[error("the collapse angle must be a number of degrees in [90, 180], got {value}")]
    InvalidCollapseAngle {
        /// The rejected angle, in degrees.
        value: f64,
    },
    /// The mesh has no faces (or no edges to take a mean length from).
    #[error("the mesh has no faces")]
    Empty,
    /// The mesh has hole faces, so it is not a closed surface.
    #[error(
        "the mesh has {holes} hole face(s); the Menger sponge algorithm needs a closed surface"
    )]
    OpenSurface {
        /// How many hole faces the mesh has.
        holes: usize,
    },
    /// A face has fewer than 3 corners.
    #[error("face {face} has {len} corner(s); the Menger sponge algorithm needs at least 3")]
    ShortFace {
        /// The face refused.
        face: FaceId,
        /// Its number of corners.
        len: usize,
    },
    /// An edge joins a vertex to itself.
    #[error("edge {edge} is a self-loop; the Menger sponge algorithm needs plain edges")]
    SelfLoop {
        /// The self-loop edge.
        edge: EdgeId,
    },
    /// An edge has the same face on both of its sides, so it has no
    /// dihedral angle (§VII.4).
    #[error("edge {edge} has face {face} on both sides; its dihedral angle is undefined")]
    SameFaceBothSides {
        /// The edge refused.
        edge: EdgeId,
        /// The face lying on both of its sides.
        face: FaceId,
    },
    /// A face has no usable geometry: a zero-length edge, no area, or a
    /// corner folded back to 0° or 360°.
    #[error("face {face} is degenerate: {reason}")]
    DegenerateFace {
        /// The degenerate face.
        face: FaceId,
        /// What is wrong with it, in words.
        reason: String,
    },
    /// An edge has no usable geometry: its ends coincide, or its two faces
    /// fold back onto each other where a bend is needed.
    #[error("edge {edge} is degenerate: {reason}")]
    DegenerateEdge {
        /// The degenerate edge.
        edge: EdgeId,
        /// What is wrong with it, in words.
        reason: String,
    },
    /// The thickness `D` does not fit in a face: an edge not longer than
    /// `2D`, or a remeshing or offset polygon that would reverse or vanish.
    #[error("thickness {thickness} is too large for face {face} at level {level}: {reason}")]
    ThicknessTooLarge {
        /// The face the thickness does not fit.
        face: FaceId,
        /// The level being planned, from 1.
        level: usize,
        /// The thickness `D` used at that level, in model units.
        thickness: f64,
        /// Which check failed, in words.
        reason: String,
    },
    /// A level could produce more faces than the cap ([`MAX_FACES`] or the
    /// one given to [`menger_capped`]).
    #[error("level {level} could produce up to {bound} faces, above the cap of {cap}")]
    TooManyFaces {
        /// The level refused, from 1 (in exact mode, the level asked for).
        level: usize,
        /// The upper bound on its faces: `8E + V` of the mesh before the level,
        /// or in exact mode the sponge's face count (`u128::MAX` on overflow).
        bound: u128,
        /// The cap that `bound` exceeds.
        cap: usize,
    },
    /// Exact mode was asked for but the mesh is not a parallelepiped.
    #[error("exact mode needs a parallelepiped (a cube up to an affine map): {reason}")]
    NotAParallelepiped {
        /// Why the mesh is not one, in words.
        reason: String,
    },
    /// A kernel operation failed on handles this module made itself: a bug.
    #[error("internal error in the Menger sponge algorithm (please report): {0}")]
    Kernel(#[from] holey_dlfl::Error),
}

/// What one level of the thesis's algorithm did, and the mesh after it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MengerLevel {
    /// The thickness `D` used.
    pub thickness: f64,
    /// Original edges in each case of §VII.4 (index 0 is case 1).
    pub angle_cases: [usize; 6],
    /// Original edges whose connecting edges were collapsed.
    pub collapsed_edges: usize,
    /// Original edges whose strip was bent (cases 5 and 6).
    pub bent_edges: usize,
    /// Corners with an interior angle over 180° (§VII.5.2).
    pub nonconvex_corners: usize,
    /// Corners of exactly 180° (§VII.5.3).
    pub winged_corners: usize,
    /// Faces kept whole though off their mean plane by more than 1e-9 of
    /// their size (§VII.5.1).
    pub nonplanar_faces: usize,
    /// Diagonals inserted first to cut faces skewed by more than 1% into
    /// planar pieces (§VII.5.1).
    pub skew_cuts: usize,
    /// Zero-length self-loops removed after the collapses.
    pub loops_removed: usize,
    /// Vertex-face corners merged because they coincided (see [`menger`]).
    pub zipped_vertices: usize,
    /// Edges deleted by the two-gon cleanup.
    pub two_gons_removed: usize,
    /// Vertices of the mesh after this level.
    pub vertices: usize,
    /// Edges of the mesh after this level.
    pub edges: usize,
    /// Faces of the mesh after this level.
    pub faces: usize,
}

/// What [`menger`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MengerReport {
    /// One entry per level of the thesis's algorithm (empty in exact mode).
    pub levels: Vec<MengerLevel>,
    /// The true sponge built in exact mode.
    pub exact: Option<ExactSponge>,
}

/// Applies the generalized Menger sponge algorithm (§VII.3–VII.5), or in
/// exact mode builds the true Menger sponge, with the face cap
/// [`MAX_FACES`]. See the module documentation.
pub fn menger(mesh: &mut Mesh, params: &MengerParams) -> Result<MengerReport, MengerError> {
    menger_capped(mesh, params, MAX_FACES)
}

/// [`menger`] with an explicit cap on the faces of any level. In the
/// thesis's mode each level is checked against the bound `8E + V` (the
/// faces before any collapse, plus one per possible bend) before it runs.
///
/// All work happens on a copy of the mesh, which replaces it only when
/// every level succeeded, so on any error the mesh is unchanged.
pub fn menger_capped(
    mesh: &mut Mesh,
    params: &MengerParams,
    max_faces: usize,
) -> Result<MengerReport, MengerError> {
    match params.thickness {
        Thickness::Absolute(v) | Thickness::RatioOfMeanEdge(v) => {
            if !(v.is_finite() && v > 0.0) {
                return Err(MengerError::InvalidThickness { value: v });
            }
        }
    }
    let angle = params.collapse_angle_deg;
    if !(90.0..=180.0).contains(&angle) {
        return Err(MengerError::InvalidCollapseAngle { value: angle });
    }
    let mut report = MengerReport::default();
    if params.iterations == 0 {
        return Ok(report);
    }
    if params.exact {
        let (built, sponge) = exact::build(mesh, params.iterations, max_faces)?;
        *mesh = built;
        report.exact = Some(sponge);
        return Ok(report);
    }
    let mut work = mesh.clone();
    for level in 1..=params.iterations {
        let skew_cuts = skew::split_skewed_faces(&mut work)?;
        let bound = 8 * work.edge_count() as u128 + work.vertex_count() as u128;
        if bound > max_faces as u128 {
            return Err(MengerError::TooManyFaces {
                level,
                bound,
                cap: max_faces,
            });
        }
        let plan = plan::Plan::new(&work, params.thickness, angle.to_radians(), level)?;
        let mut done = apply::apply(&mut work, &plan)?;
        done.skew_cuts = skew_cuts;
        report.levels.push(done);
    }
    *mesh = work;
    Ok(report)
}

#[cfg(test)]
mod tests;
