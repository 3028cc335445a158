//! Generalized Sierpinski polyhedra (Srinivasan 2004, chapter VI).
//!
//! # The scheme (§VI.5)
//!
//! One iteration on a closed manifold mesh with vertex set `V`:
//!
//! 1. Subdivide every edge that is not a self-loop at its midpoint; call the
//!    new vertices `Vm`.
//! 2. For every vertex `vi` of `V` and every corner `{a, vi, b}` at it, insert
//!    an edge between the corners `{c, a, vi}` and `{vi, b, d}`. Every face of
//!    `k` visible corners is split into `k` corner pieces and one *central
//!    face* on the `k` midpoints.
//! 3. For every midpoint of `Vm`, insert an edge between its two corners that
//!    lie in central faces. These edges are self-loops; the central faces
//!    disappear ("holes in their place") and the faces that close the
//!    pyramids from behind appear, one at every vertex of `V` (figure 36).
//!
//! Self-loops are skipped by step 1, which makes the scheme recursive: the
//! loops of one iteration are the zero-length "hinges" (figure 38) of the
//! next.
//!
//! ## Corners joined by self-loops
//!
//! From the second iteration on, a face visits a vertex that carries a
//! self-loop twice in a row: `… m → v ⟲ v → m′ …` (figure 37: a "triangle"
//! is a hexagon with three loops). The thesis counts such a run as *one*
//! corner ("self-loops are ignored"). This module does the same: a *chain*
//! is a maximal run of corners of one face joined by self-loops (all at the
//! same vertex of `V`), and step 2 inserts one edge per chain, from the
//! corner before the chain to the corner after it. Cutting corner by corner
//! instead would split the hexagon between the two ends of a loop and give
//! a different, non-Sierpinski mesh; the chain rule is what reproduces the
//! thesis's counts (tetrahedron: 16, 64, 256 faces).
//!
//! # Counts
//!
//! Let a closed mesh have `V` vertices, `E` edges of which `L` are
//! self-loops, `n = E − L`, and let every vertex's loops separate its
//! rotation into `1 + loops(v)` fans (true of every mesh this scheme makes
//! from a loop-free mesh). Step 1 adds `n` vertices and `n` edges; step 2
//! adds `2n` edges and `2n` faces (each non-loop edge has two sides, each
//! side ends one chain); step 3 adds `n` loops and leaves one face per fan,
//! `V + L` in all, in place of the central faces. So
//!
//! ```text
//! V' = V + n,   E' = E + 4n,   F' = 2n + V + L,   L' = L + n,   n' = 4n
//! χ' = 2V − 2n   ⇒   genus' = 1 + n − V   (one component)
//! ```
//!
//! For a loop-free genus-`g` input this is `genus' = 2g + F − 1`; afterwards
//! `genus' = genus + n/2`, so the genus grows by about ×4 per iteration, as
//! §VI.4 says. Tetrahedron: 10/30/16 (genus 3, 6 loops), 34/126/64 (15, 30),
//! 130/510/256 (63, 126). Cube: 20/60/32 (5, 12), 68/252/128 (29, 60),
//! 260/1020/512 (125, 252).
//!
//! # Cost
//!
//! Every step is a loop over the current edges or corners doing O(1)
//! kernel work (`insert_edge` walks only the shorter face it makes), so an
//! iteration is linear in the size of its output. Measured (release, this
//! shared 2-core machine; ±30% with load): a tetrahedron's 9th iteration (262 144 → 1 048 576
//! faces) takes 0.54 s, all nine 0.69 s; a cube's 8th (→ 524 288 faces)
//! 0.30 s and 9th (→ 2 097 152) 1.4 s.
//!
//! # Scope
//!
//! Any closed DLFL mesh: polyhedra of any genus, several components (each
//! stays one connected component), faces with self-loops (from earlier
//! iterations), point-spheres (left alone). Open meshes (hole faces) are
//! refused: the scheme is defined for closed polyhedra, and a hole's
//! corners would be cut like a face's.

use holey_dlfl::{CornerId, Mesh, VertexId};

/// The default cap on the number of faces an application may produce. A
/// Sierpinski iteration multiplies the face count by about 4 and the kernel
/// stores about 4 corners per face (~30 bytes each), so 20 million faces is
/// a few gigabytes.
pub const MAX_FACES: usize = 20_000_000;

/// Why [`sierpinski`] refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SierpinskiError {
    /// The mesh has hole faces; the scheme of §VI.5 needs a closed surface.
    #[error(
        "the mesh has {holes} hole face(s); Sierpinski subdivision (§VI.5) is defined for closed polyhedra, close the boundary first"
    )]
    OpenSurface {
        /// How many hole faces the mesh has.
        holes: usize,
    },
    /// The requested iterations could make more faces than the cap
    /// ([`MAX_FACES`] or the one given to [`sierpinski_capped`]).
    #[error(
        "{iterations} Sierpinski iteration(s) could produce up to {bound} faces, above the cap of {cap}"
    )]
    TooManyFaces {
        /// The number of iterations asked for.
        iterations: usize,
        /// An upper bound on the face count after them (computed only until
        /// it first passes the cap, so possibly lower than the final bound).
        bound: u128,
        /// The cap that `bound` exceeds.
        cap: usize,
    },
    /// A kernel operation failed on handles this module made itself: a bug.
    #[error("internal error in Sierpinski subdivision (please report): {0}")]
    Kernel(#[from] holey_dlfl::Error),
}

/// What one iteration did, and the mesh size after it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SierpinskiStep {
    /// Edges subdivided in step 1 (the non-loop edges).
    pub subdivided: usize,
    /// Edges inserted in step 2 (one per chain of corners).
    pub corner_cuts: usize,
    /// Self-loops inserted in step 3.
    pub loops: usize,
    /// Vertices of the mesh after this iteration.
    pub vertices: usize,
    /// Edges of the mesh after this iteration, self-loops included.
    pub edges: usize,
    /// Faces of the mesh after this iteration.
    pub faces: usize,
}

/// The steps of a [`sierpinski`] call, one per iteration.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SierpinskiReport {
    /// What each iteration did, in order; empty for zero iterations.
    pub steps: Vec<SierpinskiStep>,
}

/// Applies `iterations` Sierpinski iterations (§VI.5) to a closed mesh,
/// with the default face cap [`MAX_FACES`]. See the module documentation.
pub fn sierpinski(mesh: &mut Mesh, iterations: usize) -> Result<SierpinskiReport, SierpinskiError> {
    sierpinski_capped(mesh, iterations, MAX_FACES)
}

/// [`sierpinski`] with an explicit cap on the number of output faces.
///
/// The cap is checked before anything changes, against an upper bound on
/// the face count: with `n` non-loop edges and `h` of their sides in faces,
/// an iteration adds at most `h` faces in step 2 and `n` in step 3 and makes
/// at most `2n + h ≤ 4n` non-loop edges.
pub fn sierpinski_capped(
    mesh: &mut Mesh,
    iterations: usize,
    max_faces: usize,
) -> Result<SierpinskiReport, SierpinskiError> {
    mesh.require_closed()
        .map_err(|holes| SierpinskiError::OpenSurface { holes })?;
    let bound = face_bound(mesh, iterations, max_faces)?;
    if bound > max_faces as u128 {
        return Err(SierpinskiError::TooManyFaces {
            iterations,
            bound,
            cap: max_faces,
        });
    }
    let mut report = SierpinskiReport::default();
    for _ in 0..iterations {
        report.steps.push(iterate(mesh)?);
    }
    Ok(report)
}

/// An upper bound on the faces after `iterations` iterations; stops early
/// once the bound passes `cap`.
fn face_bound(mesh: &Mesh, iterations: usize, cap: usize) -> Result<u128, SierpinskiError> {
    let mut n: u128 = 0;
    for e in mesh.edges() {
        if !mesh.is_self_loop(e)? {
            n += 1;
        }
    }
    // Closed mesh: every non-loop edge has two sides in (non-hole) faces.
    let mut sides = 2 * n;
    let mut faces = mesh.face_count() as u128;
    for _ in 0..iterations {
        faces += sides + n;
        n = 2 * n + sides;
        sides = 2 * n;
        if faces > cap as u128 {
            break;
        }
    }
    Ok(faces)
}

/// Index of a vertex slot in a dense per-vertex table.
fn slot(v: VertexId) -> usize {
    v.index()
}

/// One iteration of §VI.5.
fn iterate(mesh: &mut Mesh) -> Result<SierpinskiStep, SierpinskiError> {
    let (original_corners, midpoints) = subdivide_step(mesh)?;
    let (central, corner_cuts) = cut_step(mesh, original_corners, &midpoints)?;
    let loops = loop_step(mesh, &central)?;
    Ok(SierpinskiStep {
        subdivided: midpoints.len(),
        corner_cuts,
        loops,
        vertices: mesh.vertex_count(),
        edges: mesh.edge_count(),
        faces: mesh.face_count(),
    })
}

/// Step 1: subdivides the non-loop edges at their midpoints. Returns the
/// corners that existed before (the corners of the original vertices:
/// subdivision keeps every corner handle valid, and later steps only add
/// corners) and the midpoints.
fn subdivide_step(mesh: &mut Mesh) -> Result<(Vec<CornerId>, Vec<VertexId>), SierpinskiError> {
    let original_corners: Vec<CornerId> = mesh.corners().collect();
    let edges: Vec<_> = mesh.edges().collect();
    let mut midpoints: Vec<VertexId> = Vec::with_capacity(edges.len());
    for e in edges {
        if !mesh.is_self_loop(e)? {
            midpoints.push(mesh.subdivide_edge(e)?.vertex);
        }
    }
    Ok((original_corners, midpoints))
}

/// The two central-face corners of each midpoint, filled by [`cut_step`].
type CentralCorners = Vec<[Option<CornerId>; 2]>;

/// Step 2: cuts every chain of original corners off its face.
///
/// A corner of an original vertex starts a chain when the corner before it
/// is at a midpoint (otherwise it continues a chain across a self-loop).
/// The chain runs on while its corners start self-loops; `next` of its last
/// corner is again at a midpoint, since step 1 left no non-loop edge
/// between two original vertices.
///
/// `insert_edge(p, q)`, with p before and q after the chain, makes the
/// walks `prev(p) → p′ → q …` (the central face goes on) and
/// `t → q′ → p → s …` (the corner piece). So p′ = prev(q) is the central
/// face's corner at p's midpoint. It starts the new edge and keeps it
/// through every later cut (a later cut can only use it as its `q`, which
/// stays in the central face), so it is the corner step 3 needs.
fn cut_step(
    mesh: &mut Mesh,
    original_corners: Vec<CornerId>,
    midpoints: &[VertexId],
) -> Result<(CentralCorners, usize), SierpinskiError> {
    // Dense table: vertex slot -> midpoint number (u32::MAX for others).
    let slots = midpoints.iter().map(|&m| slot(m) + 1).max().unwrap_or(0);
    let mut mid_of = vec![u32::MAX; slots];
    for (k, &m) in midpoints.iter().enumerate() {
        mid_of[slot(m)] = k as u32;
    }
    let midpoint_number = |v: VertexId| -> Option<usize> {
        mid_of
            .get(slot(v))
            .copied()
            .filter(|&k| k != u32::MAX)
            .map(|k| k as usize)
    };
    let mut central: CentralCorners = vec![[None, None]; midpoints.len()];
    let mut cuts = 0;
    for s in original_corners {
        let p = mesh.corner_prev(s)?;
        let Some(k) = midpoint_number(mesh.corner_vertex(p)?) else {
            continue;
        };
        let mut t = s;
        let len = mesh.face_len(mesh.corner_face(s)?)?;
        let mut steps = 0;
        while let Some(e) = mesh.corner_edge(t)? {
            if !mesh.is_self_loop(e)? || steps >= len {
                break;
            }
            t = mesh.corner_next(t)?;
            steps += 1;
        }
        let q = mesh.corner_next(t)?;
        mesh.insert_edge(p, q)?;
        cuts += 1;
        let p_central = mesh.corner_prev(q)?;
        let entry = &mut central[k];
        if entry[0].is_none() {
            entry[0] = Some(p_central);
        } else {
            entry[1] = Some(p_central);
        }
    }
    Ok((central, cuts))
}

/// Step 3: one self-loop per midpoint, between its two central corners.
/// Each insertion merges two faces or splits one; the final faces are fixed
/// by where the loops sit, whatever the order.
fn loop_step(mesh: &mut Mesh, central: &CentralCorners) -> Result<usize, SierpinskiError> {
    let mut loops = 0;
    for pair in central {
        if let [Some(a), Some(b)] = *pair {
            mesh.insert_edge(a, b)?;
            loops += 1;
        }
    }
    Ok(loops)
}

#[cfg(test)]
mod tests;
