//! TopMod's remeshing schemes (issue 18): the `performRemeshing` switch of
//! TopMod (Akleman, Srinivasan et al.), every scheme a function of a
//! [`Mesh`] into a new one.
//!
//! ```
//! use holey_dlfl::convert::{ImportOptions, to_dlfl};
//! use holey_subdiv::{RemeshParams, RemeshScheme, remesh};
//!
//! let cube = to_dlfl(&holey_shapes::cube(1)?, ImportOptions::default())?.mesh;
//! let scheme: RemeshScheme = "vertex-truncation".parse()?;
//! let cut = remesh(&cube, scheme, &RemeshParams::default(), 1)?;
//! assert_eq!((cut.vertex_count(), cut.edge_count(), cut.face_count()), (24, 36, 14));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Counts
//!
//! Each [`RemeshScheme`] variant states what one level does to the counts.
//! `V`, `E`, `F` are the input's vertices, edges and faces, `C = Σ n_f`
//! the corners (the sum of the face sizes, `2E` on a closed mesh) and
//! `n_f`, `d_v` the size of a face and the valence of a vertex. Formulas
//! are for closed meshes without point-spheres; a point-sphere (one vertex,
//! one face, no edge) is copied unchanged by every scheme, so it adds one
//! vertex and one face to every count. Every scheme keeps, component by
//! component, the genus and the number of boundary loops; most are defined
//! on any DLFL (self-loops, two-gons, monogons, multiple edges and faces
//! visiting a vertex twice included, since every construction is written
//! per corner on the combinatorial map).
//!
//! # Boundaries
//!
//! Hole faces (boundary loops) are never filled. Schemes that build new
//! faces inside the old ones leave a hole's corners where they are (its
//! edges are divided like the others, so a hole of `k` corners becomes one
//! of `2k`, `3k` or `4k`); schemes that build faces around old vertices or
//! across old edges treat a hole like a face in the connectivity and keep
//! its new points on the old boundary polygon. The dual is not defined on
//! an open surface (a boundary loop would become a vertex with an open
//! ring), so [`RemeshScheme::Dual`] and every scheme TopMod builds from it
//! refuse meshes with holes with [`SubdivError::Boundary`], before
//! anything is computed.
//!
//! # Cost and size cap
//!
//! Every step runs on the flat arrays of [`crate::subdivide`] in a few
//! linear passes, with index arithmetic for the connectivity: O(output)
//! time and memory. The exact size of each step's output is computed from
//! its input before anything of it is allocated; more than the cap
//! ([`MAX_FACES`] unless [`remesh_capped`] is given another) is
//! [`SubdivError::RemeshTooLarge`]. The input mesh is never modified.

mod build;
mod checkerboard;
mod corner_cut;
mod doo_sabin_bc_new;
mod dual;
mod extrude;
mod honeycomb;
mod loop_split;
mod map;
mod omnitruncate;
mod pentagonal;
mod quad_split;
mod root4;
mod sqrt3;
mod stellate;
mod truncation;

#[cfg(test)]
mod tests;

use std::fmt;
use std::str::FromStr;

use holey_dlfl::{Mesh, RawMesh};

use crate::flat::{Flat, Kind};
use crate::{MAX_FACES, SubdivError};
use build::Budget;

/// The most levels one call may ask for. Every scheme that grows the mesh
/// reaches the face cap in far fewer; the dual and the triangulation do
/// not grow it, and this bound keeps a huge level count from running for
/// ever.
pub const MAX_LEVELS: usize = 64;

macro_rules! schemes {
    ($($(#[$doc:meta])* $variant:ident = $name:literal,)*) => {
        /// A remeshing scheme of TopMod's `performRemeshing` switch.
        ///
        /// The kebab-case [`name`](RemeshScheme::name) is what
        /// [`FromStr`] parses and [`fmt::Display`] prints.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum RemeshScheme {
            $($(#[$doc])* $variant,)*
        }

        impl RemeshScheme {
            /// Every scheme, in TopMod's menu order.
            pub const ALL: &'static [RemeshScheme] = &[$(RemeshScheme::$variant,)*];

            /// The scheme's kebab-case name.
            pub fn name(self) -> &'static str {
                match self {
                    $(RemeshScheme::$variant => $name,)*
                }
            }
        }
    };
}

schemes! {
    /// **Dual** (TopMod `createDual`): a vertex at each face's centroid, a
    /// face around each vertex, an edge across each edge.
    /// `V' = F, E' = E, F' = V`; face `f` becomes a vertex of valence
    /// `n_f`, vertex `v` a `d_v`-gon. Closed meshes only.
    Dual = "dual",
    /// **√3** (Kobbelt, "√3-subdivision", SIGGRAPH 2000; TopMod's "Root-3"
    /// entry builds the same connectivity as dual ∘ honeycomb ∘ dual): a
    /// vertex at each face's centroid joined to its corners, then every old
    /// edge between two faces flipped to join their centroids.
    /// `V' = V + F, E' = E + C, F' = C` (triangles; `3F` from triangles).
    /// Kobbelt's smoothing: an old vertex of valence `n` moves to
    /// `(1 − αₙ)p + αₙ·avg(neighbours)`, `αₙ = (4 − 2 cos(2π/n))/9`. On a
    /// boundary the edges next to a hole are not flipped (each keeps one
    /// triangle) and boundary vertices stay fixed; Kobbelt's alternating
    /// boundary trisection is not done.
    Sqrt3 = "sqrt3",
    /// **Triangulate** (TopMod `triangulateAllFaces`): every face that is
    /// not a triangle gets a vertex at its centroid joined to its corners;
    /// triangles and holes are kept.
    /// `V' = V + F≠3, E' = E + C≠3, F' = F₃ + C≠3` (`F≠3`, `C≠3` the
    /// non-triangles and their corners).
    Triangulate = "triangulate",
    /// **Dual vertex truncation** (TopMod's menu entry, whose code is
    /// `sqrt3Subdivide`): the connectivity of [`RemeshScheme::Sqrt3`], the
    /// dual of vertex truncation, without smoothing: old vertices stay,
    /// new ones are the face centroids. `V' = V + F, E' = E + C, F' = C`.
    DualVertexTruncation = "dual-vertex-truncation",
    /// **Stellate** (TopMod `subdivideAllFaces`, triangles): every face gets
    /// a vertex at its centroid joined to its corners.
    /// `V' = V + F, E' = E + C, F' = C` (an `n`-gon becomes `n` triangles).
    Stellate = "stellate",
    /// **Double stellate** (TopMod `starSubdivide`): [`Stellate`] twice,
    /// then each first-level centre moved by
    /// [`RemeshParams::double_stellate_offset`] along its face's unit
    /// normal. `V' = V + F + C, E' = E + 4C, F' = 3C`.
    ///
    /// [`Stellate`]: RemeshScheme::Stellate
    DoubleStellate = "double-stellate",
    /// **12.6.4** (TopMod `subdivide1264`): dual, [`Dual12_6_4`], dual:
    /// combinatorially the barycentric subdivision.
    /// `V' = V + E + F, E' = 3C, F' = 2C` (triangles). Positions: the
    /// centroids of the dual 12.6.4 faces. Closed meshes only.
    ///
    /// [`Dual12_6_4`]: RemeshScheme::Dual12_6_4
    TwelveSixFour = "12.6.4",
    /// **Honeycomb** (TopMod `honeycombSubdivide`): every face shrinks to
    /// a copy with one vertex per edge, the copies are joined by one edge
    /// across each old edge, and each old vertex becomes a `2d_v`-gon.
    /// `V' = C, E' = E + C, F' = F + V`. The copy's vertex `i` is TopMod's
    /// mask of the edge midpoints `mⱼ`: `α mᵢ + (1−α)/(3n−5) Σⱼ≠ᵢ (3 +
    /// 2 cos(2π(i−j)/n)) mⱼ`, `α = 1/√2 − 1/4 + 5/(4n)`. A hole's copy
    /// is its edge midpoints (and stays a hole).
    Honeycomb = "honeycomb",
    /// **Vertex truncation** (TopMod `vertexCuttingSubdivide`): every corner
    /// cut off by an edge between points at [`vertex_truncation_offset`] of
    /// its two edges' lengths from the vertex; the old vertices go.
    /// `V' = 2E, E' = E + C, F' = F + V`: an `n`-gon becomes a `2n`-gon,
    /// a vertex a `d_v`-gon. An offset of ½ is [`Simplest`] (the two points
    /// of an edge coincide), as in TopMod.
    ///
    /// [`vertex_truncation_offset`]: RemeshParams::vertex_truncation_offset
    /// [`Simplest`]: RemeshScheme::Simplest
    VertexTruncation = "vertex-truncation",
    /// **Dual 12.6.4** (TopMod `dual1264Subdivide`, Bei & Cansin): every
    /// face becomes a `2n`-gon through the points at thirds of its edges,
    /// scaled about their centroid by [`omnitruncation_scale`]; each edge
    /// becomes a quad and each vertex a `2d_v`-gon (the 4.6.12 tiling from
    /// a triangle mesh of valence 6: the omnitruncation).
    /// `V' = 2C, E' = 2E + 2C, F' = F + E + V`. Holes keep their points
    /// on the boundary, unscaled.
    ///
    /// [`omnitruncation_scale`]: RemeshParams::omnitruncation_scale
    Dual12_6_4 = "dual-12.6.4",
    /// **Linear vertex insertion** (TopMod `subdivideAllFaces`, quads): the
    /// Catmull–Clark connectivity with linear positions: old vertices
    /// stay, edge midpoints, face centroids.
    /// `V' = V + E + F, E' = 2E + C, F' = C` (an `n`-gon becomes `n` quads).
    LinearVertexInsertion = "linear-vertex-insertion",
    /// **Catmull–Clark**, delegated to [`crate::catmull_clark`].
    /// `V' = V + E + F, E' = 2E + C, F' = C`.
    CatmullClark = "catmull-clark",
    /// **Stellate with edge removal** (TopMod `stellateSubdivide`, Eric):
    /// [`Stellate`], then every old edge between two faces deleted, so each
    /// becomes the quad of its two ends and the two centroids.
    /// `V' = V + F, E' = C, F' = E` (all quads). An edge next to a hole is
    /// kept, with one triangle.
    ///
    /// [`Stellate`]: RemeshScheme::Stellate
    StellateEdgeRemoval = "stellate-edge-removal",
    /// **Doo–Sabin**, delegated to [`crate::doo_sabin`].
    /// `V' = C, E' = 2C, F' = F + E + V`.
    DooSabin = "doo-sabin",
    /// **Corner cutting** (TopMod `cornerCuttingSubdivide`): the Doo–Sabin
    /// connectivity (`V' = C, E' = 2C, F' = F + E + V`) with the tension
    /// mask: corner point `i` of an `n`-gon is
    /// `α vᵢ + (1−α)/(3n−5) Σⱼ≠ᵢ (3 + 2 cos(2π(i−j)/n)) vⱼ`,
    /// `α` = [`RemeshParams::corner_cutting_alpha`] (9/16 gives Doo–Sabin's
    /// quad weights). A monogon's point is its vertex; boundaries are
    /// refined by Chaikin's rule as in [`crate::doo_sabin`].
    CornerCutting = "corner-cutting",
    /// **Modified corner cutting** (TopMod
    /// `modifiedCornerCuttingSubdivide`): the Doo–Sabin connectivity with
    /// each face inset so that its new edges are parallel to the old ones
    /// at distance [`modified_corner_cutting_thickness`]`/2`: corner `v`
    /// with unit edge directions `u₁`, `u₂` moves to
    /// `v + t/√(1 − (u₁·u₂)²) (u₁ + u₂)`. A straight or degenerate corner
    /// moves by `t` towards the face's centroid. No corner moves more than
    /// a third of either edge at it, so faces narrower than the inset are
    /// inset less instead of turning over.
    /// `V' = C, E' = 2C, F' = F + E + V`.
    ///
    /// [`modified_corner_cutting_thickness`]: RemeshParams::modified_corner_cutting_thickness
    ModifiedCornerCutting = "modified-corner-cutting",
    /// **Simplest** (Peters & Reif, "The simplest subdivision scheme for
    /// smoothing polyhedra", 1997; TopMod `simplestSubdivide`): a vertex at
    /// each edge midpoint; each face becomes the polygon of its midpoints
    /// and each vertex a `d_v`-gon. `V' = E, E' = C, F' = F + V`.
    Simplest = "simplest",
    /// **Pentagonalization** (TopMod `pentagonalSubdivide`): every edge cut
    /// in thirds, a vertex at each face's centroid joined to the first
    /// third point of each of its edges; an `n`-gon becomes `n` pentagons.
    /// `V' = V + 2E + F, E' = 3E + C, F' = C`. The joined points move
    /// towards the centroid by [`pentagonal_offset`] of the way.
    ///
    /// [`pentagonal_offset`]: RemeshParams::pentagonal_offset
    Pentagonalization = "pentagonalization",
    /// **Cubic pentagonalization** (TopMod: pentagonalization, dual, dual):
    /// the counts of [`Pentagonalization`] with positions averaged twice
    /// (centroids of centroids). Closed meshes only.
    ///
    /// [`Pentagonalization`]: RemeshScheme::Pentagonalization
    CubicPentagonalization = "cubic-pentagonalization",
    /// **Dual pentagonalization** (TopMod: dual, pentagonalization, dual):
    /// every vertex of valence 5 (from a cube, the snub cube's
    /// connectivity). `V' = C, E' = 3E + C, F' = V + 2E + F`. Positions: the
    /// centroids of the pentagons of the pentagonalized dual. Closed meshes
    /// only.
    DualPentagonalization = "dual-pentagonalization",
    /// **Loop** (Loop 1987; TopMod `loopSubdivide`): every edge split at its
    /// edge point, every corner cut off by an edge between the points of
    /// its two edges. `V' = V + E, E' = 2E + C, F' = F + C`; from a
    /// triangle mesh `V + E, 2E + 3F, 4F`. Edge point
    /// `3/8 (p₀ + p₁) + 1/16 Σ` (on each side, the corner before the edge
    /// and the one two after its start: the opposite vertex, twice, in a
    /// triangle, so Loop's `1/8`); vertex `(1 − nβ)p + β Σ neighbours`,
    /// `β = (5/8 − (3/8 + cos(2π/n)/4)²)/n`. Boundary edges get their
    /// midpoint, a boundary vertex `(u + 6p + w)/8` (Hoppe et al. 1994),
    /// a corner or pinched boundary vertex stays.
    Loop = "loop",
    /// **Loop-style remeshing** (TopMod `loopStyleSubdivide`, Bei): the
    /// connectivity of [`Loop`] with the edge midpoints, each interior old
    /// vertex moved to `ℓ p + (1 − ℓ) avg(midpoints of its edges)`,
    /// `ℓ` = [`loop_style_length`]. `V' = V + E, E' = 2E + C, F' = F + C`.
    ///
    /// [`Loop`]: RemeshScheme::Loop
    /// [`loop_style_length`]: RemeshParams::loop_style_length
    LoopStyle = "loop-style",
    /// **Root-4** (TopMod `root4Subdivide`): every face shrinks to a copy
    /// joined to it corner by corner, then the old edges are deleted, so
    /// each old edge becomes a hexagon. `V' = V + C, E' = 2C, F' = F + E`
    /// (a hexagonal mesh stays hexagonal with 4× the faces). The copy is
    /// [`Honeycomb`]'s mask of the points at [`root4_twist`] along each
    /// edge; each interior old vertex moves by [`root4_weight`] towards the
    /// average of the copies' corners at it. An edge next to a hole is
    /// kept (its side becomes a quad).
    ///
    /// [`Honeycomb`]: RemeshScheme::Honeycomb
    /// [`root4_twist`]: RemeshParams::root4_twist
    /// [`root4_weight`]: RemeshParams::root4_weight
    Root4 = "root4",
    /// **Dual Loop** (TopMod: dual, Loop, dual): `V' = V + C, E' = 2C,
    /// F' = F + E` (the counts of [`Root4`]). Positions: the centroids of
    /// the faces of Loop applied to the dual. Closed meshes only.
    ///
    /// [`Root4`]: RemeshScheme::Root4
    DualLoop = "dual-loop",
    /// **Global extrude** (TopMod lists "Global Extrude" but never
    /// implemented it; this is its face extrusion applied to every face):
    /// every face is replaced by a copy moved [`extrude_length`]` · √A`
    /// along its unit normal (`A` the face's area, so the length is
    /// relative to each face's own size: at 1 a square becomes a cube, on
    /// any mesh's scale or density), scaled about its centroid by
    /// [`extrude_scale`], and joined to the old boundary by one quad per
    /// edge; the old edges stay.
    /// `V' = V + C, E' = E + 2C, F' = F + C` (quads stay quads).
    ///
    /// [`extrude_length`]: RemeshParams::extrude_length
    /// [`extrude_scale`]: RemeshParams::extrude_scale
    GlobalExtrude = "global-extrude",
    /// **Checkerboard** (TopMod `checkerBoardRemeshing`): every edge cut at
    /// [`checkerboard_thickness`] of its length from both ends, every face
    /// inset by the same fraction (corner `v` to `(1 − 2t)v + t(u + w)`,
    /// `u`, `w` its neighbours) and joined to the cut points: a quad
    /// becomes a 3×3 grid. `V' = V + 2E + C, E' = 3E + 3C, F' = F + 2C`.
    ///
    /// [`checkerboard_thickness`]: RemeshParams::checkerboard_thickness
    Checkerboard = "checkerboard",
    /// **Dual global extrude** (TopMod lists it, unimplemented): dual,
    /// [`GlobalExtrude`], dual. `V' = V + C, E' = E + 2C, F' = F + C`: each
    /// old vertex gets a new vertex per corner around it, the new vertices
    /// are the centroids of the extruded dual's faces. Closed meshes only.
    ///
    /// [`GlobalExtrude`]: RemeshScheme::GlobalExtrude
    DualGlobalExtrude = "dual-global-extrude",
    /// **Dual checkerboard** (TopMod: dual, checkerboard, dual):
    /// `V' = V + 2C, E' = 3E + 3C, F' = F + 2E + C`. Positions: the
    /// centroids of the faces of the checkerboarded dual. Closed meshes
    /// only.
    DualCheckerboard = "dual-checkerboard",
    /// **Pentagon preserving** (TopMod `pentagonalSubdivide2`): every edge
    /// split at its midpoint, a copy of each face through its midpoints
    /// scaled about their centroid by [`pentagon_preserving_scale`], joined
    /// to them; an `n`-gon becomes an `n`-gon and `n` pentagons.
    /// `V' = V + E + C, E' = 2E + 2C, F' = F + C`.
    ///
    /// [`pentagon_preserving_scale`]: RemeshParams::pentagon_preserving_scale
    PentagonPreserving = "pentagon-preserving",
    /// **Dual pentagon preserving** (TopMod: dual, pentagon preserving,
    /// dual): `V' = V + C, E' = 2E + 2C, F' = F + E + C`. Positions: the
    /// centroids of the faces of the remeshed dual. Closed meshes only.
    DualPentagonPreserving = "dual-pentagon-preserving",
    /// **Hexagon preserving** (TopMod's menu entry runs `root4Subdivide`):
    /// the same operator as [`Root4`]. `V' = V + C, E' = 2C, F' = F + E`.
    ///
    /// [`Root4`]: RemeshScheme::Root4
    HexagonPreserving = "hexagon-preserving",
    /// **Dual hexagon preserving** (TopMod: dual, root-4, dual):
    /// `V' = V + E, E' = 2C, F' = F + C` (triangles stay triangles).
    /// Positions: the centroids of the faces of root-4 applied to the dual.
    /// Closed meshes only.
    DualHexagonPreserving = "dual-hexagon-preserving",
    /// **Fractal** (TopMod `fractalSubdivide`, Doug): [`Loop`]'s
    /// connectivity with the midpoint face stellated: every edge split at
    /// its midpoint, every corner cut off, and the middle polygon fanned
    /// from a vertex above the face's centroid.
    /// `V' = V + E + F, E' = 2E + 2C, F' = 2C` (all triangles). The apex is
    /// raised along the unit normal by [`fractal_offset`]` · √(max(0,
    /// |m₀m₁|² − (|m₀x|/2)²))`, `m₀`, `m₁` the midpoints of the face's
    /// first two edges and `x` the point of the face's midpoint-refined
    /// walk `n` steps after `m₀` (TopMod's rule).
    ///
    /// [`Loop`]: RemeshScheme::Loop
    /// [`fractal_offset`]: RemeshParams::fractal_offset
    Fractal = "fractal",
    /// **Modified double stellate** (TopMod `twostellateSubdivide`, Eric):
    /// [`Stellate`] with centres raised by [`stellate_height`] along the
    /// face normal, then [`StellateEdgeRemoval`] of the result with centres
    /// raised by [`stellate_curve`]. `V' = V + F + C, E' = 2E + 2C,
    /// F' = E + C` (all quads).
    ///
    /// [`Stellate`]: RemeshScheme::Stellate
    /// [`StellateEdgeRemoval`]: RemeshScheme::StellateEdgeRemoval
    /// [`stellate_height`]: RemeshParams::stellate_height
    /// [`stellate_curve`]: RemeshParams::stellate_curve
    ModifiedDoubleStellate = "modified-double-stellate",
    /// **Doo–Sabin BC** (TopMod `dooSabinSubdivideBC`, Bei & Cansin): every
    /// edge split at its midpoint, then Doo–Sabin with TopMod's
    /// multiple-edge check, which joins the two edge faces at each
    /// midpoint by one edge instead of a two-gon.
    /// `V' = 2C, E' = 4C − E, F' = V + 2E + F`.
    DooSabinBc = "doo-sabin-bc",
    /// **Doo–Sabin BC New** (TopMod `dooSabinSubdivideBCNew`, Bei &
    /// Cansin): every edge split at its midpoint; every face replaced by a
    /// copy of its `2n`-gon through Doo–Sabin's points of it (TopMod's
    /// Doo–Sabin extrusion at distance 0: corner `i` of the `2n`-gon goes
    /// to `Σⱼ wᵢⱼ pⱼ`, `wᵢᵢ = 1/4 + 5/(8n)`, `wᵢⱼ = (3 + 2cos(π(i−j)/n))/(8n)`),
    /// scaled about its centroid by [`doo_sabin_bc_new_scale`]; the old
    /// edges deleted; at each midpoint its two edges replaced by one edge
    /// between its neighbours. Each old vertex stays, joined to its copy
    /// points, and moves to `ℓ p + (1 − ℓ) avg(its copy points)`,
    /// `ℓ` = [`doo_sabin_bc_new_length`]. Each old edge becomes two
    /// pentagons. `V' = V + 2C, E' = 4C − E, F' = F + 2E` (an `n`-gon
    /// becomes a `2n`-gon). An edge next to a hole is kept and gets one
    /// pentagon; the hole keeps its corners and boundary vertices stay.
    ///
    /// [`doo_sabin_bc_new_scale`]: RemeshParams::doo_sabin_bc_new_scale
    /// [`doo_sabin_bc_new_length`]: RemeshParams::doo_sabin_bc_new_length
    DooSabinBcNew = "doo-sabin-bc-new",
    /// **Dome** (TopMod `domeSubdivide`, Bei & Cansin): every edge cut in
    /// quarters, then every face extruded seven times by TopMod's
    /// Doo–Sabin extrusion (each ring the Doo–Sabin corner points of the
    /// previous one, moved along the face normal by `(0, 0.3, 0.18, 0.1,
    /// 0.05, 0.025, 0.01)·`[`dome_length`]`·√A` and scaled about its
    /// centroid by `(1.6, 1.7, 1.6, 1.4, 1.2, 1.1, 0.01)·`[`dome_scale`]).
    /// `A` is the face's area: TopMod's lengths are absolute, which on a
    /// fine triangle mesh raises spikes many faces tall; here a dome is
    /// `0.665 · `[`dome_length`] times its face's size high on any mesh.
    /// `V' = V + 3E + 28C, E' = 4E + 56C, F' = F + 28C`.
    ///
    /// [`dome_length`]: RemeshParams::dome_length
    /// [`dome_scale`]: RemeshParams::dome_scale
    Dome = "dome",
    /// **Subdivide face** (TopMod's "Subdivide Face" tool applied to every
    /// face): [`LinearVertexInsertion`] when
    /// [`RemeshParams::subdivide_face_quads`] (TopMod's default), otherwise
    /// [`Stellate`].
    ///
    /// [`LinearVertexInsertion`]: RemeshScheme::LinearVertexInsertion
    /// [`Stellate`]: RemeshScheme::Stellate
    SubdivideFace = "subdivide-face",
}

impl fmt::Display for RemeshScheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for RemeshScheme {
    type Err = SubdivError;

    /// Parses a kebab-case name (ASCII case and `_` for `-` tolerated).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase().replace('_', "-");
        RemeshScheme::ALL
            .iter()
            .copied()
            .find(|scheme| scheme.name() == wanted)
            .ok_or_else(|| SubdivError::UnknownScheme {
                name: s.to_string(),
            })
    }
}

impl RemeshScheme {
    /// True for the schemes TopMod builds from the dual, which need a
    /// closed surface: they return [`SubdivError::Boundary`] on a mesh with
    /// hole faces.
    pub fn needs_closed_surface(self) -> bool {
        use RemeshScheme::*;
        matches!(
            self,
            Dual | TwelveSixFour
                | CubicPentagonalization
                | DualPentagonalization
                | DualLoop
                | DualGlobalExtrude
                | DualCheckerboard
                | DualPentagonPreserving
                | DualHexagonPreserving
        )
    }
}

/// The schemes' parameters, with TopMod's defaults (`MainWindow.cc`).
/// Each is read only by the schemes its documentation names.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RemeshParams {
    /// Corner cutting's tension α, the weight of a corner's own vertex
    /// (TopMod: 9/16; any finite value, TopMod's dialog allows 0.333 to
    /// 0.999).
    pub corner_cutting_alpha: f64,
    /// Modified corner cutting's thickness: twice the distance of the new
    /// edges from the old ones (TopMod: 0.25).
    pub modified_corner_cutting_thickness: f64,
    /// Vertex truncation's offset, the fraction of each edge cut off at
    /// both ends, in `(0, ½]` (TopMod: 0.25).
    pub vertex_truncation_offset: f64,
    /// Pentagonalization's offset: how far the joined third points move
    /// towards the face centroid, as a fraction of the way (TopMod: 0).
    pub pentagonal_offset: f64,
    /// Pentagon preserving's scale of the inner face (TopMod: 0.75).
    pub pentagon_preserving_scale: f64,
    /// Checkerboard's thickness, the fraction of each edge cut off at both
    /// ends, in `[0, ½]` (TopMod: 0.33).
    pub checkerboard_thickness: f64,
    /// Root-4's weight: how far each old vertex moves towards its new
    /// neighbours (TopMod: 0).
    pub root4_weight: f64,
    /// Root-4's twist: where along each edge the points the mask averages
    /// lie, 0 at the edge's start (TopMod: 0).
    pub root4_twist: f64,
    /// Double stellate's offset of the first centres along the face normal
    /// (TopMod: 0).
    pub double_stellate_offset: f64,
    /// Modified double stellate's height of the first centres (TopMod: 0).
    pub stellate_height: f64,
    /// Modified double stellate's height of the second centres (TopMod: 0).
    pub stellate_curve: f64,
    /// Fractal's multiplier of the apex height (TopMod: 1).
    pub fractal_offset: f64,
    /// Dome's length factor, in units of each face's size `√(area)`: the
    /// domes rise `0.665 ×` this times their face's size (1; TopMod's
    /// lengths were absolute).
    pub dome_length: f64,
    /// Dome's scale factor (TopMod: 1).
    pub dome_scale: f64,
    /// Dual 12.6.4's scale of the new faces about their centroids (TopMod:
    /// 0.7; 0 and ±1 leave them unscaled, as in TopMod).
    pub omnitruncation_scale: f64,
    /// Loop-style's length factor: 1 keeps the old vertices (TopMod: 1).
    pub loop_style_length: f64,
    /// Global extrude's distance along the face normals, in units of each
    /// face's size `√(area)`, so 1 turns a square into a cube on a mesh of
    /// any scale (1; TopMod has no global extrude, and its face
    /// extrusion's absolute default of 2 raised spikes on fine meshes).
    pub extrude_length: f64,
    /// Global extrude's scale of the moved faces (TopMod's extrusion
    /// default, 1).
    pub extrude_scale: f64,
    /// Doo–Sabin BC New's scale of each face's copy about its centroid
    /// (TopMod's `sf`, default 1; `|sf|` is used and 0 leaves the copies
    /// unscaled, as in TopMod).
    pub doo_sabin_bc_new_scale: f64,
    /// Doo–Sabin BC New's length factor, the weight of each old vertex's
    /// own position: 1 keeps it (TopMod's `length`, default 1).
    pub doo_sabin_bc_new_length: f64,
    /// Subdivide face: quads (true, TopMod's default) or triangles.
    pub subdivide_face_quads: bool,
}

impl Default for RemeshParams {
    fn default() -> Self {
        RemeshParams {
            corner_cutting_alpha: 9.0 / 16.0,
            modified_corner_cutting_thickness: 0.25,
            vertex_truncation_offset: 0.25,
            pentagonal_offset: 0.0,
            pentagon_preserving_scale: 0.75,
            checkerboard_thickness: 0.33,
            root4_weight: 0.0,
            root4_twist: 0.0,
            double_stellate_offset: 0.0,
            stellate_height: 0.0,
            stellate_curve: 0.0,
            fractal_offset: 1.0,
            dome_length: 1.0,
            dome_scale: 1.0,
            omnitruncation_scale: 0.7,
            loop_style_length: 1.0,
            extrude_length: 1.0,
            extrude_scale: 1.0,
            doo_sabin_bc_new_scale: 1.0,
            doo_sabin_bc_new_length: 1.0,
            subdivide_face_quads: true,
        }
    }
}

/// What a parameter must be.
#[derive(Clone, Copy, Debug)]
enum Range {
    /// Any finite number (the rules are affine, or a distance).
    Finite,
    /// `(0, ½]`: a fraction cut off at both ends of an edge, not nothing.
    UpToHalf,
    /// `[0, ½]`.
    ZeroToHalf,
}

impl Range {
    fn contains(self, x: f64) -> bool {
        x.is_finite()
            && match self {
                Range::Finite => true,
                Range::UpToHalf => x > 0.0 && x <= 0.5,
                Range::ZeroToHalf => (0.0..=0.5).contains(&x),
            }
    }

    fn text(self) -> &'static str {
        match self {
            Range::Finite => "a finite number",
            Range::UpToHalf => "a number in (0, 0.5]",
            Range::ZeroToHalf => "a number in [0, 0.5]",
        }
    }
}

/// One option of a scheme: the short name that `holey remesh`, Python's
/// `Mesh.remesh` and the modeler's Remesh panel use, the field of
/// [`RemeshParams`] it sets ([`RemeshParams::set`] takes either), and
/// what it means, in one line with its unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RemeshOption {
    /// The short name, e.g. `alpha`, `thickness`, `offset`.
    pub name: &'static str,
    /// The field of [`RemeshParams`], e.g. `corner_cutting_alpha`.
    pub field: &'static str,
    /// What the value means and in what unit, e.g. "height of each
    /// face's extrusion, in units of the face's size √(area)".
    pub meaning: &'static str,
}

const fn opt(name: &'static str, field: &'static str, meaning: &'static str) -> RemeshOption {
    RemeshOption {
        name,
        field,
        meaning,
    }
}

const ALPHA: &[RemeshOption] = &[opt(
    "alpha",
    "corner_cutting_alpha",
    "tension: the weight of each corner's own vertex in its new point",
)];
const INSET: &[RemeshOption] = &[opt(
    "thickness",
    "modified_corner_cutting_thickness",
    "twice the distance of the new edges inside the old ones (a length)",
)];
const TRUNCATION: &[RemeshOption] = &[opt(
    "offset",
    "vertex_truncation_offset",
    "fraction of each edge cut off at both ends, in (0, 0.5]",
)];
const PENTAGONAL: &[RemeshOption] = &[opt(
    "offset",
    "pentagonal_offset",
    "fraction of the way the joined third points move towards the face centroid",
)];
const PENTAGON_PRESERVING: &[RemeshOption] = &[opt(
    "scale",
    "pentagon_preserving_scale",
    "scale of each inner face about its centroid",
)];
const CHECKERBOARD: &[RemeshOption] = &[opt(
    "thickness",
    "checkerboard_thickness",
    "fraction of each edge cut off at both ends, in [0, 0.5]",
)];
const ROOT4: &[RemeshOption] = &[
    opt(
        "weight",
        "root4_weight",
        "fraction of the way each old vertex moves towards its new neighbours",
    ),
    opt(
        "twist",
        "root4_twist",
        "where along each edge the averaged points lie, as a fraction from its start",
    ),
];
const DOUBLE_STELLATE: &[RemeshOption] = &[opt(
    "offset",
    "double_stellate_offset",
    "lift of the first centres along the face normal (a length)",
)];
const MODIFIED_STELLATE: &[RemeshOption] = &[
    opt(
        "height",
        "stellate_height",
        "lift of the first centres along the face normal (a length)",
    ),
    opt(
        "curve",
        "stellate_curve",
        "lift of the second centres along the face normal (a length)",
    ),
];
const FRACTAL: &[RemeshOption] = &[opt(
    "offset",
    "fractal_offset",
    "multiplier of the apex height TopMod's rule gives",
)];
const DOME: &[RemeshOption] = &[
    opt(
        "length",
        "dome_length",
        "height factor, in units of each face's size √(area): a dome rises 0.665 × this × its face's size",
    ),
    opt(
        "scale",
        "dome_scale",
        "multiplier of the rings' scales about their centroids",
    ),
];
const OMNITRUNCATION: &[RemeshOption] = &[opt(
    "scale",
    "omnitruncation_scale",
    "scale of each new face about its centroid (0 and ±1: unscaled)",
)];
const LOOP_STYLE: &[RemeshOption] = &[opt(
    "length",
    "loop_style_length",
    "weight of each old vertex's own position (1 keeps it)",
)];
const EXTRUDE: &[RemeshOption] = &[
    opt(
        "length",
        "extrude_length",
        "height of each face's extrusion, in units of the face's size √(area) (1 turns a square into a cube)",
    ),
    opt(
        "scale",
        "extrude_scale",
        "scale of each moved face about its centroid",
    ),
];
const DOO_SABIN_BC_NEW: &[RemeshOption] = &[
    opt(
        "scale",
        "doo_sabin_bc_new_scale",
        "scale of each face's copy about its centroid (TopMod's sf; 0 and ±1: unscaled)",
    ),
    opt(
        "length",
        "doo_sabin_bc_new_length",
        "weight of each old vertex's own position (1 keeps it)",
    ),
];

impl RemeshScheme {
    /// The numeric options this scheme reads, in the order it lists them
    /// (empty for most; `subdivide_face_quads`, a flag, is set directly).
    /// The one table that the CLI, Python and the modeler share.
    pub fn options(self) -> &'static [RemeshOption] {
        use RemeshScheme::*;
        match self {
            CornerCutting => ALPHA,
            ModifiedCornerCutting => INSET,
            VertexTruncation => TRUNCATION,
            Pentagonalization | CubicPentagonalization | DualPentagonalization => PENTAGONAL,
            PentagonPreserving | DualPentagonPreserving => PENTAGON_PRESERVING,
            Checkerboard | DualCheckerboard => CHECKERBOARD,
            Root4 | HexagonPreserving | DualHexagonPreserving => ROOT4,
            DoubleStellate => DOUBLE_STELLATE,
            ModifiedDoubleStellate => MODIFIED_STELLATE,
            Fractal => FRACTAL,
            Dome => DOME,
            Dual12_6_4 | TwelveSixFour => OMNITRUNCATION,
            LoopStyle => LOOP_STYLE,
            GlobalExtrude | DualGlobalExtrude => EXTRUDE,
            DooSabinBcNew => DOO_SABIN_BC_NEW,
            _ => &[],
        }
    }

    /// The short names of [`options`](RemeshScheme::options).
    pub fn reads(self) -> impl Iterator<Item = &'static str> {
        self.options().iter().map(|o| o.name)
    }
}

impl RemeshParams {
    /// The field a numeric parameter lives in, and its range.
    fn slot(&mut self, field: &str) -> Option<(&mut f64, Range)> {
        use Range::*;
        let p = self;
        Some(match field {
            "corner_cutting_alpha" => (&mut p.corner_cutting_alpha, Finite),
            "modified_corner_cutting_thickness" => {
                (&mut p.modified_corner_cutting_thickness, Finite)
            }
            "vertex_truncation_offset" => (&mut p.vertex_truncation_offset, UpToHalf),
            "pentagonal_offset" => (&mut p.pentagonal_offset, Finite),
            "pentagon_preserving_scale" => (&mut p.pentagon_preserving_scale, Finite),
            "checkerboard_thickness" => (&mut p.checkerboard_thickness, ZeroToHalf),
            "root4_weight" => (&mut p.root4_weight, Finite),
            "root4_twist" => (&mut p.root4_twist, Finite),
            "double_stellate_offset" => (&mut p.double_stellate_offset, Finite),
            "stellate_height" => (&mut p.stellate_height, Finite),
            "stellate_curve" => (&mut p.stellate_curve, Finite),
            "fractal_offset" => (&mut p.fractal_offset, Finite),
            "dome_length" => (&mut p.dome_length, Finite),
            "dome_scale" => (&mut p.dome_scale, Finite),
            "omnitruncation_scale" => (&mut p.omnitruncation_scale, Finite),
            "loop_style_length" => (&mut p.loop_style_length, Finite),
            "extrude_length" => (&mut p.extrude_length, Finite),
            "extrude_scale" => (&mut p.extrude_scale, Finite),
            "doo_sabin_bc_new_scale" => (&mut p.doo_sabin_bc_new_scale, Finite),
            "doo_sabin_bc_new_length" => (&mut p.doo_sabin_bc_new_length, Finite),
            _ => return None,
        })
    }

    /// Sets the option `name` of `scheme` — its short name (`alpha`,
    /// `thickness`, `offset`, `scale`, `length`, `weight`, `twist`,
    /// `height`, `curve`; [`RemeshScheme::options`] lists a scheme's) or
    /// its field name (`corner_cutting_alpha`) — to `value`.
    ///
    /// Refused, leaving `self` unchanged: an option the scheme does not
    /// read ([`SubdivError::UnknownOption`]), and a value out of the
    /// option's range ([`SubdivError::InvalidParameter`], as [`remesh`]
    /// would refuse it).
    pub fn set(&mut self, scheme: RemeshScheme, name: &str, value: f64) -> Result<(), SubdivError> {
        let option = scheme
            .options()
            .iter()
            .find(|o| o.name == name || o.field == name)
            .ok_or_else(|| SubdivError::UnknownOption {
                scheme,
                name: name.to_string(),
            })?;
        let (slot, range) = self
            .slot(option.field)
            .ok_or_else(|| SubdivError::UnknownOption {
                scheme,
                name: name.to_string(),
            })?;
        if !range.contains(value) {
            return Err(SubdivError::InvalidParameter {
                scheme,
                name: option.field,
                value,
                expected: range.text(),
            });
        }
        *slot = value;
        Ok(())
    }

    /// The value of the option `name` (short or field name) of `scheme`,
    /// or `None` when the scheme does not read it.
    pub fn get(&self, scheme: RemeshScheme, name: &str) -> Option<f64> {
        let option = scheme
            .options()
            .iter()
            .find(|o| o.name == name || o.field == name)?;
        let mut copy = *self;
        copy.slot(option.field).map(|(x, _)| *x)
    }

    /// The parameters `scheme` reads: field name, value, range.
    fn read_by(&self, scheme: RemeshScheme) -> Vec<(&'static str, f64, Range)> {
        let mut copy = *self;
        scheme
            .options()
            .iter()
            .filter_map(|o| copy.slot(o.field).map(|(x, r)| (o.field, *x, r)))
            .collect()
    }

    /// Refuses a parameter `scheme` reads that is not finite or out of its
    /// range; the others are not looked at.
    fn check(&self, scheme: RemeshScheme) -> Result<(), SubdivError> {
        for (name, value, range) in self.read_by(scheme) {
            if !range.contains(value) {
                return Err(SubdivError::InvalidParameter {
                    scheme,
                    name,
                    value,
                    expected: range.text(),
                });
            }
        }
        Ok(())
    }
}

/// The two numbers both extrusion steps read: the copy moves
/// `length × √A` along the face's unit normal (`A` the face's area) and is
/// scaled by `scale` about its centroid (the dome applies both per ring,
/// times its own constants).
#[derive(Clone, Copy, Debug)]
struct Extrusion {
    pub length: f64,
    pub scale: f64,
}

/// Root-4's two numbers: how far each interior old vertex moves towards
/// the copy vertices joined to it (`weight`), and where along each edge
/// the points the copy's mask averages lie (`twist`, 0 at its start).
#[derive(Clone, Copy, Debug)]
struct Root4Params {
    pub weight: f64,
    pub twist: f64,
}

/// Doo–Sabin BC New's two numbers: the scale of each face's copy about
/// its centroid (TopMod's `sf`) and the weight of each old vertex's own
/// position when it moves (`length`).
#[derive(Clone, Copy, Debug)]
struct DooSabinBcNewParams {
    pub scale: f64,
    pub length: f64,
}

/// One primitive step on the flat map; a scheme's level is a sequence of
/// them ([`plan`]).
#[derive(Clone, Copy, Debug)]
enum Op {
    Dual,
    Stellate { height: f64, skip_triangles: bool },
    StellateEdgeRemoval { height: f64 },
    DoubleStellate { offset: f64 },
    Sqrt3 { smooth: bool },
    Loop,
    LoopStyle { length: f64 },
    Fractal { offset: f64 },
    QuadSplit,
    VertexTruncation { offset: f64 },
    Simplest,
    CornerCutting { alpha: f64 },
    InsetCornerCutting { thickness: f64 },
    DooSabinBc,
    DooSabinBcNew(DooSabinBcNewParams),
    Honeycomb,
    Root4(Root4Params),
    Pentagonal { offset: f64 },
    PentagonPreserving { scale: f64 },
    Checkerboard { thickness: f64 },
    GlobalExtrude(Extrusion),
    Dome(Extrusion),
    Omnitruncate { scale: f64 },
    CatmullClark,
    DooSabin,
}

/// The steps of one level of `scheme`.
fn plan(scheme: RemeshScheme, p: &RemeshParams) -> Vec<Op> {
    use RemeshScheme as S;
    let root4 = Op::Root4(Root4Params {
        weight: p.root4_weight,
        twist: p.root4_twist,
    });
    let global_extrude = Op::GlobalExtrude(Extrusion {
        length: p.extrude_length,
        scale: p.extrude_scale,
    });
    let dual_of = |op: Op| vec![Op::Dual, op, Op::Dual];
    match scheme {
        S::Dual => vec![Op::Dual],
        S::Sqrt3 => vec![Op::Sqrt3 { smooth: true }],
        S::DualVertexTruncation => vec![Op::Sqrt3 { smooth: false }],
        S::Triangulate => vec![Op::Stellate {
            height: 0.0,
            skip_triangles: true,
        }],
        S::Stellate => vec![Op::Stellate {
            height: 0.0,
            skip_triangles: false,
        }],
        S::DoubleStellate => vec![Op::DoubleStellate {
            offset: p.double_stellate_offset,
        }],
        S::TwelveSixFour => dual_of(Op::Omnitruncate {
            scale: p.omnitruncation_scale,
        }),
        S::Dual12_6_4 => vec![Op::Omnitruncate {
            scale: p.omnitruncation_scale,
        }],
        S::Honeycomb => vec![Op::Honeycomb],
        S::VertexTruncation if p.vertex_truncation_offset == 0.5 => vec![Op::Simplest],
        S::VertexTruncation => vec![Op::VertexTruncation {
            offset: p.vertex_truncation_offset,
        }],
        S::LinearVertexInsertion => vec![Op::QuadSplit],
        S::CatmullClark => vec![Op::CatmullClark],
        S::StellateEdgeRemoval => vec![Op::StellateEdgeRemoval { height: 0.0 }],
        S::DooSabin => vec![Op::DooSabin],
        S::CornerCutting => vec![Op::CornerCutting {
            alpha: p.corner_cutting_alpha,
        }],
        S::ModifiedCornerCutting => vec![Op::InsetCornerCutting {
            thickness: p.modified_corner_cutting_thickness,
        }],
        S::Simplest => vec![Op::Simplest],
        S::Pentagonalization => vec![Op::Pentagonal {
            offset: p.pentagonal_offset,
        }],
        S::CubicPentagonalization => vec![
            Op::Pentagonal {
                offset: p.pentagonal_offset,
            },
            Op::Dual,
            Op::Dual,
        ],
        S::DualPentagonalization => dual_of(Op::Pentagonal {
            offset: p.pentagonal_offset,
        }),
        S::Loop => vec![Op::Loop],
        S::LoopStyle => vec![Op::LoopStyle {
            length: p.loop_style_length,
        }],
        S::Root4 | S::HexagonPreserving => vec![root4],
        S::DualLoop => dual_of(Op::Loop),
        S::GlobalExtrude => vec![global_extrude],
        S::DualGlobalExtrude => dual_of(global_extrude),
        S::Checkerboard => vec![Op::Checkerboard {
            thickness: p.checkerboard_thickness,
        }],
        S::DualCheckerboard => dual_of(Op::Checkerboard {
            thickness: p.checkerboard_thickness,
        }),
        S::PentagonPreserving => vec![Op::PentagonPreserving {
            scale: p.pentagon_preserving_scale,
        }],
        S::DualPentagonPreserving => dual_of(Op::PentagonPreserving {
            scale: p.pentagon_preserving_scale,
        }),
        S::DualHexagonPreserving => dual_of(root4),
        S::Fractal => vec![Op::Fractal {
            offset: p.fractal_offset,
        }],
        S::ModifiedDoubleStellate => vec![
            Op::Stellate {
                height: p.stellate_height,
                skip_triangles: false,
            },
            Op::StellateEdgeRemoval {
                height: p.stellate_curve,
            },
        ],
        S::DooSabinBc => vec![Op::DooSabinBc],
        S::DooSabinBcNew => vec![Op::DooSabinBcNew(DooSabinBcNewParams {
            scale: p.doo_sabin_bc_new_scale,
            length: p.doo_sabin_bc_new_length,
        })],
        S::Dome => vec![Op::Dome(Extrusion {
            length: p.dome_length,
            scale: p.dome_scale,
        })],
        S::SubdivideFace if p.subdivide_face_quads => vec![Op::QuadSplit],
        S::SubdivideFace => vec![Op::Stellate {
            height: 0.0,
            skip_triangles: false,
        }],
    }
}

impl Op {
    /// Runs the step on `src`, refusing before allocating when its output
    /// would pass the cap.
    fn run(self, src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
        match self {
            Op::Dual => dual::step(src, budget),
            Op::Stellate {
                height,
                skip_triangles,
            } => stellate::stellate(src, budget, height, skip_triangles),
            Op::StellateEdgeRemoval { height } => stellate::edge_removal(src, budget, height),
            Op::DoubleStellate { offset } => stellate::double(src, budget, offset),
            Op::Sqrt3 { smooth } => sqrt3::step(src, budget, smooth),
            Op::Loop => loop_split::step(src, budget, loop_split::Rule::Loop),
            Op::LoopStyle { length } => {
                loop_split::step(src, budget, loop_split::Rule::Style(length))
            }
            Op::Fractal { offset } => loop_split::fractal(src, budget, offset),
            Op::QuadSplit => quad_split::step(src, budget),
            Op::VertexTruncation { offset } => truncation::truncate(src, budget, offset),
            Op::Simplest => truncation::simplest(src, budget),
            Op::CornerCutting { alpha } => {
                corner_cut::step(src, budget, corner_cut::Rule::Tension(alpha))
            }
            Op::InsetCornerCutting { thickness } => {
                corner_cut::step(src, budget, corner_cut::Rule::Inset(thickness))
            }
            Op::DooSabinBc => corner_cut::doo_sabin_bc(src, budget),
            Op::DooSabinBcNew(params) => doo_sabin_bc_new::step(src, budget, params),
            Op::Honeycomb => honeycomb::step(src, budget),
            Op::Root4(params) => root4::step(src, budget, params),
            Op::Pentagonal { offset } => pentagonal::pentagonalize(src, budget, offset),
            Op::PentagonPreserving { scale } => pentagonal::preserve(src, budget, scale),
            Op::Checkerboard { thickness } => checkerboard::step(src, budget, thickness),
            Op::GlobalExtrude(lift) => extrude::global(src, budget, lift),
            Op::Dome(lift) => extrude::dome(src, budget, lift),
            Op::Omnitruncate { scale } => omnitruncate::step(src, budget, scale),
            Op::CatmullClark => corner_cut::catmull_clark(src, budget),
            Op::DooSabin => corner_cut::doo_sabin(src, budget),
        }
    }
}

/// `levels` levels of `scheme` on `mesh`, as a new mesh (zero levels
/// return a copy), capped at [`MAX_FACES`] faces.
///
/// The refusals, each before any output is built, leaving `mesh` as it
/// was: [`SubdivError::Boundary`] for a scheme that
/// [needs a closed surface](RemeshScheme::needs_closed_surface) on a mesh
/// with holes, [`SubdivError::InvalidParameter`] for a parameter the
/// scheme reads that is not finite or out of its range,
/// [`SubdivError::TooManyLevels`] past [`MAX_LEVELS`],
/// [`SubdivError::RemeshTooLarge`] when a level would pass the cap,
/// [`SubdivError::NonFinite`] for a non-finite input position and
/// [`SubdivError::RemeshOverflow`] when an output position is not finite.
///
/// Vertices are renumbered in the order the faces first use them, as
/// [`crate::subdivide`] does; [`remesh_to_raw`] keeps each step's own
/// numbering.
pub fn remesh(
    mesh: &Mesh,
    scheme: RemeshScheme,
    params: &RemeshParams,
    levels: usize,
) -> Result<Mesh, SubdivError> {
    remesh_capped(mesh, scheme, params, levels, MAX_FACES)
}

/// [`remesh`] with another cap on the number of faces of every step.
pub fn remesh_capped(
    mesh: &Mesh,
    scheme: RemeshScheme,
    params: &RemeshParams,
    levels: usize,
    max_faces: usize,
) -> Result<Mesh, SubdivError> {
    let flat = run(mesh, scheme, params, levels, max_faces)?;
    if levels == 0 {
        return Ok(mesh.clone());
    }
    flat.into_mesh(|vertex| SubdivError::RemeshOverflow { scheme, vertex })
}

/// [`remesh`] as flat arrays, without building the kernel mesh. The
/// numbering is each step's own: most schemes keep the input's vertices
/// first (in slot order) and number new vertices by the input entity they
/// come from (edge, face or corner, in slot order).
pub fn remesh_to_raw(
    mesh: &Mesh,
    scheme: RemeshScheme,
    params: &RemeshParams,
    levels: usize,
) -> Result<RawMesh, SubdivError> {
    Ok(run(mesh, scheme, params, levels, MAX_FACES)?.into_raw())
}

/// Checks the request, then runs the levels on flat arrays.
fn run(
    mesh: &Mesh,
    scheme: RemeshScheme,
    params: &RemeshParams,
    levels: usize,
    max_faces: usize,
) -> Result<Flat, SubdivError> {
    params.check(scheme)?;
    if levels > MAX_LEVELS {
        return Err(SubdivError::TooManyLevels {
            scheme,
            levels,
            max: MAX_LEVELS,
        });
    }
    let mut src = Flat::from_mesh(mesh)?;
    if scheme.needs_closed_surface() {
        let holes = (0..src.face_count())
            .filter(|&f| src.kind(f) == Kind::Hole)
            .count();
        if holes > 0 {
            return Err(SubdivError::Boundary { scheme, holes });
        }
    }
    let ops = plan(scheme, params);
    for level in 1..=levels {
        if src.edges.is_empty() {
            break; // point-spheres only: every scheme copies them
        }
        let budget = Budget {
            scheme,
            levels,
            level,
            max_faces,
        };
        for op in &ops {
            src = op.run(&src, &budget)?;
        }
    }
    if let Some(vertex) = src.pos.iter().position(|p| !p.is_finite()) {
        return Err(SubdivError::RemeshOverflow { scheme, vertex });
    }
    Ok(src)
}
