//! # Selection (TopMod's selection menu, issue 18)
//!
//! Functions that compute sets of faces, edges or vertices from a seed
//! or a current selection, without changing the mesh:
//! - [`face_loop`]: the strip of quadrilaterals crossed by walking
//!   straight across opposite edges;
//! - [`edge_loop`]: the edges continued straight through vertices of
//!   valence 4; [`edge_ring`]: the opposite edges of consecutive quads;
//! - [`grow_faces`], [`shrink_faces`], [`invert_faces`] and their vertex
//!   versions;
//! - [`similar_faces`] (same number of corners), [`similar_vertices`]
//!   (same valence);
//! - [`checkerboard`]: a 2-colouring of the faces, or the face where none
//!   exists.
//!
//! Hole faces are never selected, and stop loops and rings. Results are
//! sorted by slot (loops and rings are in walking order) and free of
//! repeats.

use std::collections::{BTreeSet, HashMap, HashSet, VecDeque};

use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, VertexId};

/// Why a selection could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SelectError {
    /// The face given to start a face loop is not a quadrilateral (or is
    /// a hole), so it has no opposite edge.
    #[error("face {0} is not a quadrilateral, so a face loop cannot pass through it")]
    NotAQuad(FaceId),
    /// The edge given to a face loop is not an edge of the face.
    #[error("edge {edge} is not an edge of face {face}")]
    NotOnFace {
        /// The face.
        face: FaceId,
        /// The edge.
        edge: EdgeId,
    },
    /// No 2-colouring of the faces exists: the two faces beside this edge
    /// would need the same colour (an odd cycle of faces passes through it).
    #[error(
        "the faces cannot be 2-coloured: faces {face} and {other} beside edge {edge} would both need one colour"
    )]
    NotBipartite {
        /// A face on the odd cycle.
        face: FaceId,
        /// The face across `edge` (equal to `face` when the edge has it on both sides).
        other: FaceId,
        /// The edge whose two sides conflict.
        edge: EdgeId,
    },
    /// A kernel accessor failed: an id not in the mesh.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// The corner of `face` at which `edge` starts, if the edge borders it.
fn corner_on(mesh: &Mesh, face: FaceId, edge: EdgeId) -> Result<Option<CornerId>, SelectError> {
    for c in mesh.edge_corners(edge)? {
        if mesh.corner_face(c)? == face {
            return Ok(Some(c));
        }
    }
    Ok(None)
}

/// The other side of the edge leaving corner `c`.
fn across(mesh: &Mesh, c: CornerId) -> Result<Option<CornerId>, SelectError> {
    let Some(e) = mesh.corner_edge(c)? else {
        return Ok(None);
    };
    let [a, b] = mesh.edge_corners(e)?;
    Ok(Some(if a == c { b } else { a }))
}

fn is_quad(mesh: &Mesh, f: FaceId) -> Result<bool, SelectError> {
    Ok(mesh.face_len(f)? == 4 && !mesh.is_hole(f)?)
}

/// The face loop through quad `face` across its edge `edge`: from `face`
/// walk across `edge` and, in every quad reached, on across the edge
/// opposite the one entered by; then the same from `face` across the
/// edge opposite `edge`. The walk stops at a face that is not a quad, a
/// hole, or one already in the loop (a closed loop). Returns the quads in
/// walking order, from one end to the other.
pub fn face_loop(mesh: &Mesh, face: FaceId, edge: EdgeId) -> Result<Vec<FaceId>, SelectError> {
    if !is_quad(mesh, face)? {
        return Err(SelectError::NotAQuad(face));
    }
    let start = corner_on(mesh, face, edge)?.ok_or(SelectError::NotOnFace { face, edge })?;
    let opposite = mesh.corner_next(mesh.corner_next(start)?)?;
    both_ways(mesh, face, [start, opposite], strip_step)
}

/// A face loop's step: across the edge leaving `c` into a quad, then on
/// from the corner that starts the quad's opposite edge.
fn strip_step(mesh: &Mesh, c: CornerId) -> Result<Option<(FaceId, CornerId)>, SelectError> {
    let Some(entry) = across(mesh, c)? else {
        return Ok(None);
    };
    let f = mesh.corner_face(entry)?;
    if !is_quad(mesh, f)? {
        return Ok(None);
    }
    Ok(Some((f, mesh.corner_next(mesh.corner_next(entry)?)?)))
}

/// The edge ring through `edge`: on each side of it, while the face is a
/// quad, the edge opposite in that quad, then on across that edge. Stops
/// at non-quads and holes, and when the ring closes. In walking order.
pub fn edge_ring(mesh: &Mesh, edge: EdgeId) -> Result<Vec<EdgeId>, SelectError> {
    let [a, b] = mesh.edge_corners(edge)?;
    both_ways(mesh, edge, [a, b], ring_step)
}

/// One step of a walk from corner `c`: the next face or edge and the
/// corner to go on from, or `None` where the walk stops.
type Step<T> = fn(&Mesh, CornerId) -> Result<Option<(T, CornerId)>, SelectError>;

/// Walks from corner `c` by `step`, taking each face or edge at most once
/// (`seen`): face loops, edge rings and edge loops differ only in their
/// step, and all stop where the walk meets what it has taken.
fn walk<T: Copy + Eq + std::hash::Hash>(
    mesh: &Mesh,
    mut c: CornerId,
    seen: &mut HashSet<T>,
    step: Step<T>,
) -> Result<Vec<T>, SelectError> {
    let mut out = Vec::new();
    while let Some((item, next)) = step(mesh, c)? {
        if !seen.insert(item) {
            break;
        }
        out.push(item);
        c = next;
    }
    Ok(out)
}

/// The walks by `step` from the corners `[ahead, behind]` of `seed` (an
/// edge of a ring or loop, the face of a face loop), joined through it in
/// walking order: the walk from `behind` reversed, `seed`, then the walk
/// from `ahead`. Each item is taken once, so a closed loop stops where it
/// began.
fn both_ways<T: Copy + Eq + std::hash::Hash>(
    mesh: &Mesh,
    seed: T,
    [ahead, behind]: [CornerId; 2],
    step: Step<T>,
) -> Result<Vec<T>, SelectError> {
    let mut seen = HashSet::from([seed]);
    let one = walk(mesh, ahead, &mut seen, step)?;
    let two = walk(mesh, behind, &mut seen, step)?;
    let mut out: Vec<T> = two.into_iter().rev().collect();
    out.push(seed);
    out.extend(one);
    Ok(out)
}

/// An edge ring's step: in the quad of `c`, the edge opposite the one
/// `c` starts, then on from its other side.
fn ring_step(mesh: &Mesh, c: CornerId) -> Result<Option<(EdgeId, CornerId)>, SelectError> {
    if !is_quad(mesh, mesh.corner_face(c)?)? {
        return Ok(None);
    }
    let opposite = mesh.corner_next(mesh.corner_next(c)?)?;
    let Some(e) = mesh.corner_edge(opposite)? else {
        return Ok(None);
    };
    Ok(across(mesh, opposite)?.map(|next| (e, next)))
}

/// The edge loop through `edge`: from each end of valence 4, on along
/// the edge opposite in the vertex's rotation (two steps round), until a
/// vertex of another valence, a self-loop, or the start again. In walking
/// order.
pub fn edge_loop(mesh: &Mesh, edge: EdgeId) -> Result<Vec<EdgeId>, SelectError> {
    let [a, b] = mesh.edge_corners(edge)?;
    // Corner a starts the edge at its first end; the walk beyond the
    // second end starts from b, the corner where the edge leaves that end.
    both_ways(mesh, edge, [b, a], loop_step)
}

/// An edge loop's step: `c` is the corner at which the current edge
/// leaves the vertex to walk through (going back along the edge); through
/// a vertex of valence 4, the edge straight on (not a self-loop).
fn loop_step(mesh: &Mesh, c: CornerId) -> Result<Option<(EdgeId, CornerId)>, SelectError> {
    if mesh.valence(mesh.corner_vertex(c)?)? != 4 {
        return Ok(None);
    }
    let straight = mesh.corner_rotation_next(mesh.corner_rotation_next(c)?)?;
    let Some(e) = mesh.corner_edge(straight)? else {
        return Ok(None);
    };
    if mesh.is_self_loop(e)? {
        return Ok(None);
    }
    // Beyond e: the corner where e leaves its far end, back towards the
    // vertex walked through.
    Ok(across(mesh, straight)?.map(|back| (e, back)))
}

/// The selection with every surface face that shares a vertex with it.
pub fn grow_faces(mesh: &Mesh, faces: &[FaceId]) -> Result<Vec<FaceId>, SelectError> {
    let mut out: BTreeSet<FaceId> = BTreeSet::new();
    for &f in faces {
        for v in mesh.face_vertices(f)? {
            for c in mesh.vertex_corners(v)? {
                let g = mesh.corner_face(c)?;
                if !mesh.is_hole(g)? {
                    out.insert(g);
                }
            }
        }
        if !mesh.is_hole(f)? {
            out.insert(f);
        }
    }
    Ok(out.into_iter().collect())
}

/// The selection without the faces on its border: those with a vertex
/// that also touches an unselected face (or a hole).
pub fn shrink_faces(mesh: &Mesh, faces: &[FaceId]) -> Result<Vec<FaceId>, SelectError> {
    let mut out = Vec::new();
    for f in inner(faces, |f| {
        let mut around = Vec::new();
        for v in mesh.face_vertices(f)? {
            for c in mesh.vertex_corners(v)? {
                around.push(mesh.corner_face(c)?);
            }
        }
        Ok(around)
    })? {
        if !mesh.is_hole(f)? {
            out.push(f);
        }
    }
    Ok(out)
}

/// Every surface face not in the selection.
pub fn invert_faces(mesh: &Mesh, faces: &[FaceId]) -> Result<Vec<FaceId>, SelectError> {
    let selected: HashSet<FaceId> = faces.iter().copied().collect();
    Ok(mesh
        .surface_faces()
        .filter(|f| !selected.contains(f))
        .collect())
}

/// The selection with every vertex joined to it by an edge.
pub fn grow_vertices(mesh: &Mesh, vertices: &[VertexId]) -> Result<Vec<VertexId>, SelectError> {
    let mut out: BTreeSet<VertexId> = vertices.iter().copied().collect();
    for &v in vertices {
        for c in mesh.vertex_corners(v)? {
            out.insert(mesh.corner_vertex(mesh.corner_next(c)?)?);
        }
    }
    Ok(out.into_iter().collect())
}

/// The selection without the vertices joined by an edge to an
/// unselected vertex.
pub fn shrink_vertices(mesh: &Mesh, vertices: &[VertexId]) -> Result<Vec<VertexId>, SelectError> {
    inner(vertices, |v| {
        let mut around = Vec::new();
        for c in mesh.vertex_corners(v)? {
            around.push(mesh.corner_vertex(mesh.corner_next(c)?)?);
        }
        Ok(around)
    })
}

/// The items of `selection`, sorted and without repeats, whose neighbours
/// (`around`) are all selected too: shrinking faces and vertices differ
/// only in what counts as a neighbour.
fn inner<T: Copy + Eq + std::hash::Hash + Ord>(
    selection: &[T],
    around: impl Fn(T) -> Result<Vec<T>, SelectError>,
) -> Result<Vec<T>, SelectError> {
    let selected: HashSet<T> = selection.iter().copied().collect();
    let mut out = BTreeSet::new();
    for &x in &selected {
        if around(x)?.iter().all(|n| selected.contains(n)) {
            out.insert(x);
        }
    }
    Ok(out.into_iter().collect())
}

/// Every vertex not in the selection.
pub fn invert_vertices(mesh: &Mesh, vertices: &[VertexId]) -> Vec<VertexId> {
    let selected: HashSet<VertexId> = vertices.iter().copied().collect();
    mesh.vertices().filter(|v| !selected.contains(v)).collect()
}

/// Every edge not in the selection.
pub fn invert_edges(mesh: &Mesh, edges: &[EdgeId]) -> Vec<EdgeId> {
    let selected: HashSet<EdgeId> = edges.iter().copied().collect();
    mesh.edges().filter(|e| !selected.contains(e)).collect()
}

/// Every surface face with as many corners as some face of the selection.
pub fn similar_faces(mesh: &Mesh, faces: &[FaceId]) -> Result<Vec<FaceId>, SelectError> {
    similar(faces, mesh.surface_faces(), |f| Ok(mesh.face_len(f)?))
}

/// Every vertex with the valence of some vertex of the selection.
pub fn similar_vertices(mesh: &Mesh, vertices: &[VertexId]) -> Result<Vec<VertexId>, SelectError> {
    similar(vertices, mesh.vertices(), |v| Ok(mesh.valence(v)?))
}

/// The `candidates`, in their order, whose `measure` (a face's size, a
/// vertex's valence) some item of `selection` also has: the similar-face
/// and similar-vertex selections differ only in what they measure.
fn similar<T: Copy, K: Eq + std::hash::Hash>(
    selection: &[T],
    candidates: impl Iterator<Item = T>,
    measure: impl Fn(T) -> Result<K, SelectError>,
) -> Result<Vec<T>, SelectError> {
    let mut wanted = HashSet::new();
    for &x in selection {
        wanted.insert(measure(x)?);
    }
    let mut out = Vec::new();
    for x in candidates {
        if wanted.contains(&measure(x)?) {
            out.push(x);
        }
    }
    Ok(out)
}

/// A 2-colouring of the faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Checkerboard {
    /// The faces of the first colour (each component's first face in slot
    /// order is of this colour), in slot order.
    pub first: Vec<FaceId>,
    /// The faces of the second colour, in slot order.
    pub second: Vec<FaceId>,
}

/// Colours the surface faces with two colours so that faces sharing an
/// edge differ (edges to holes do not count), if that is possible: it is
/// exactly when every cycle of faces around the surface is even (a cube:
/// no, three faces meet at each corner; an even quad torus or grid: yes).
/// Otherwise names the edge where the breadth-first colouring first
/// meets a conflict, and a face beside it.
pub fn checkerboard(mesh: &Mesh) -> Result<Checkerboard, SelectError> {
    let faces: Vec<FaceId> = mesh.surface_faces().collect();
    let mut colour: HashMap<FaceId, bool> = HashMap::with_capacity(faces.len());
    for &seed in &faces {
        if colour.contains_key(&seed) {
            continue;
        }
        colour.insert(seed, false);
        let mut queue = VecDeque::from([seed]);
        while let Some(f) = queue.pop_front() {
            let mine = colour.get(&f).copied().unwrap_or(false);
            for c in mesh.face_corners(f)? {
                let Some(e) = mesh.corner_edge(c)? else {
                    continue;
                };
                let Some(o) = across(mesh, c)? else {
                    continue;
                };
                let g = mesh.corner_face(o)?;
                if mesh.is_hole(g)? {
                    continue;
                }
                match colour.get(&g) {
                    Some(&theirs) if theirs == mine => {
                        return Err(SelectError::NotBipartite {
                            face: f,
                            other: g,
                            edge: e,
                        });
                    }
                    Some(_) => {}
                    None => {
                        colour.insert(g, !mine);
                        queue.push_back(g);
                    }
                }
            }
        }
    }
    let (mut first, mut second) = (Vec::new(), Vec::new());
    for f in faces {
        if colour.get(&f).copied().unwrap_or(false) {
            second.push(f);
        } else {
            first.push(f);
        }
    }
    Ok(Checkerboard { first, second })
}

#[cfg(test)]
mod tests;
