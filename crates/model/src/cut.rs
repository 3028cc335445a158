//! # Conical cuts (TopMod's "cut by vertex / edge / face", issue 18)
//!
//! A cut removes a small neighbourhood of a vertex, an edge or a face —
//! the *region* — and closes the wound with one new face. The region's
//! vertices `S` are those of the target (one vertex; the two ends of an
//! edge; the corners of a face); its *inner* edges `I` join two vertices
//! of `S`; its *spokes* are the edges with exactly one end in `S`. Each
//! spoke is cut at the offset from its `S` end (for a vertex of valence
//! `k` that is `k` points, the corners of a `k`-gon), consecutive points
//! around the region are joined across the faces they share, and `S`,
//! `I` and the spokes' inner halves are deleted. So
//!
//! ```text
//! ΔV = s − |S|,   ΔE = s − |I|,   ΔF = 1 − |Φ|
//! ```
//!
//! with `s` the number of spokes and `Φ` the faces lying wholly in the
//! region (the face itself for a face cut). Worked out:
//! - vertex of valence `k`: `+(k − 1)` vertices, `+k` edges, `+1` face (a
//!   `k`-gon); a cube corner: 8/12/6 → 10/15/7;
//! - edge between valences `k_u`, `k_w`: `+(k_u + k_w − 4)`,
//!   `+(k_u + k_w − 3)`, `+1` (a `(k_u + k_w − 2)`-gon); a cube edge:
//!   8/12/6 → 10/15/7;
//! - face with `s` spokes, `d` corners and `d` edges: `s − d`, `s − d`,
//!   `0`; a cube side: the cube gets shorter, 8/12/6.
//!
//! Geometry: each new point lies on its spoke at the given distance (or
//! fraction of the spoke's length) from the region. For a vertex of
//! valence 3, or a symmetric one, the new face is planar, a true plane
//! cut; otherwise it is the polygon through those points (planarize it
//! with [`crate::tools::planarize_faces`] if wanted).
//!
//! ## What is refused (the mesh is unchanged)
//! An offset that is zero, negative, NaN or infinite; an offset of half
//! a spoke's length or more (TopMod's issue #11: a cut point past the
//! middle of an edge meets the cut from its other end), named by the
//! edge and its length; self-loops in the region; two targets sharing
//! a vertex; a region that is not a disk (its faces and inner edges
//! enclose a handle or a hole of the surface: `|S| − |I| + |Φ| ≠ 1`, or
//! `S` is not connected by `I`); a region with no spokes (a whole
//! component); cutting a hole face, or a region that would swallow one.
//!
//! Regions on a boundary are cut like any other: the new face closes the
//! corner of the boundary loop that the cut removed.
//!
//! ## Two spokes: no new face
//! A region with two spokes in two different faces — a vertex of valence
//! 2 (a corner of a lone polygon, a vertex in the middle of a chain), an
//! edge whose ends have valence 2 — would leave a two-gon wound. Its two
//! sides are one edge instead: the corner becomes an edge of both faces,
//! as when a polygon's corner is cut off. So
//!
//! ```text
//! ΔV = 2 − |S|,   ΔE = 1 − |I|,   ΔF = −|Φ|
//! ```
//!
//! (a corner of a lone triangle: 3/3/2 → 4/4/2, a quad and its boundary
//! loop). On a boundary the edge is cut across the surface face and the
//! boundary loop follows it; the face returned is the one the region
//! opened into (the hole, on a boundary).

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, VertexId};

/// What a cut removes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CutTarget {
    /// A vertex and the corner around it.
    Vertex(VertexId),
    /// An edge, its two end vertices and the wedge around it.
    Edge(EdgeId),
    /// A face, its corners and edges, and the slab under it.
    Face(FaceId),
}

/// How far along each spoke the cut points lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CutOffset {
    /// A distance in model units from the region's end of the spoke.
    Distance(f64),
    /// A fraction of each spoke's length, from the region's end.
    Fraction(f64),
}

/// Why a cut was refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CutError {
    /// The offset is zero, negative, NaN or infinite.
    #[error("the cut offset must be positive and finite, got {0}")]
    InvalidOffset(f64),
    /// The offset reaches the middle of a spoke.
    #[error(
        "an offset of {offset} reaches the middle of edge {edge} (length {length}); it must be less than {limit}"
    )]
    OffsetTooLarge {
        /// The spoke.
        edge: EdgeId,
        /// Its length.
        length: f64,
        /// The offset along it, in model units.
        offset: f64,
        /// The largest allowed offset (exclusive), half the length.
        limit: f64,
    },
    /// An edge of the region starts and ends at one vertex.
    #[error("edge {0} is a self-loop; regions with self-loops are not cut")]
    SelfLoop(EdgeId),
    /// A hole face was given, or lies wholly inside a region.
    #[error("face {0} is a hole (a boundary loop); it cannot be cut or cut away")]
    HoleFace(FaceId),
    /// Two targets share this vertex; their cuts would overlap.
    #[error("two cut targets share vertex {0}; cut them one at a time")]
    Overlap(VertexId),
    /// The region is not a disk, so one face cannot replace it.
    #[error(
        "the region of {0:?} is not a disk (it wraps around a handle or a hole); it cannot be cut off by one face"
    )]
    NotADisk(CutTarget),
    /// The region has no spokes: it is a whole component.
    #[error("{0:?} has no edges leaving it (it is a whole component); there is nothing to cut")]
    NothingToCut(CutTarget),
    /// A kernel call failed: an id not in the mesh, or (after the checks) a bug.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// The plan of one region.
struct Region {
    /// `(first, last)` corner of every run of region corners in a face.
    runs: Vec<(CornerId, CornerId)>,
    vertices: Vec<VertexId>,
}

/// A spoke and the offsets (model units) to cut at, from each region end.
struct Spoke {
    edge: EdgeId,
    cuts: Vec<(VertexId, f64)>,
}

/// Cuts a vertex (see the module documentation): a valence-`k` vertex
/// becomes a `k`-gon, `+(k − 1)/+k/+1`. Returns the new face.
pub fn cut_vertex(mesh: &mut Mesh, v: VertexId, distance: f64) -> Result<FaceId, CutError> {
    cut_single(mesh, CutTarget::Vertex(v), distance)
}

/// Cuts an edge: a `(k_u + k_w − 2)`-gon replaces it and its ends.
pub fn cut_edge(mesh: &mut Mesh, e: EdgeId, distance: f64) -> Result<FaceId, CutError> {
    cut_single(mesh, CutTarget::Edge(e), distance)
}

/// Cuts a face off by (roughly) a parallel plane `distance` below it.
pub fn cut_face(mesh: &mut Mesh, f: FaceId, distance: f64) -> Result<FaceId, CutError> {
    cut_single(mesh, CutTarget::Face(f), distance)
}

/// Cuts several vertices at once (TopMod's global vertex cut when given
/// every vertex); each must be more than twice the offset from the next.
pub fn cut_vertices(
    mesh: &mut Mesh,
    vertices: &[VertexId],
    distance: f64,
) -> Result<Vec<FaceId>, CutError> {
    cut_all(
        mesh,
        vertices,
        CutTarget::Vertex,
        CutOffset::Distance(distance),
    )
}

/// Cuts several edges at once; edges sharing a vertex are refused
/// ([`CutError::Overlap`]).
pub fn cut_edges(
    mesh: &mut Mesh,
    edges: &[EdgeId],
    distance: f64,
) -> Result<Vec<FaceId>, CutError> {
    cut_all(mesh, edges, CutTarget::Edge, CutOffset::Distance(distance))
}

/// TopMod's "cut by edge-vertex": the given edges and vertices in one
/// cut (no two sharing a vertex), the edges' spokes cut at `edge_distance`
/// and the vertices' at `vertex_distance` (TopMod's "Offset (Edge)" and
/// "Offset (Vertex)"). The counts are those of each cut alone, summed.
pub fn cut_edges_and_vertices(
    mesh: &mut Mesh,
    edges: &[EdgeId],
    vertices: &[VertexId],
    edge_distance: f64,
    vertex_distance: f64,
) -> Result<Vec<FaceId>, CutError> {
    let mut targets: Vec<(CutTarget, CutOffset)> = edges
        .iter()
        .map(|&e| (CutTarget::Edge(e), CutOffset::Distance(edge_distance)))
        .collect();
    targets.extend(
        vertices
            .iter()
            .map(|&v| (CutTarget::Vertex(v), CutOffset::Distance(vertex_distance))),
    );
    cut_each(mesh, &targets)
}

/// Cuts the one `target` at `distance` and returns its new face: the
/// single-target cuts differ only in the element they name.
fn cut_single(mesh: &mut Mesh, target: CutTarget, distance: f64) -> Result<FaceId, CutError> {
    one(cut(mesh, &[target], CutOffset::Distance(distance))?)
}

/// Cuts every one of `ids`, made a target by `target`, at the same
/// `offset`: the several-target cuts and truncations
/// ([`crate::truncate`]) differ only in the kind of element and offset.
pub(crate) fn cut_all<T: Copy>(
    mesh: &mut Mesh,
    ids: &[T],
    target: fn(T) -> CutTarget,
    offset: CutOffset,
) -> Result<Vec<FaceId>, CutError> {
    let targets: Vec<CutTarget> = ids.iter().map(|&id| target(id)).collect();
    cut(mesh, &targets, offset)
}

fn one(faces: Vec<FaceId>) -> Result<FaceId, CutError> {
    faces
        .first()
        .copied()
        .ok_or_else(|| internal("a cut of one target made no face"))
}

fn internal(what: &str) -> CutError {
    CutError::Kernel(holey_dlfl::Error::Invalid(format!(
        "internal error in a cut (please report): {what}"
    )))
}

/// Cuts every target at once (duplicates ignored) and returns the new
/// face of each, in the order given. All checks come first.
pub fn cut(
    mesh: &mut Mesh,
    targets: &[CutTarget],
    offset: CutOffset,
) -> Result<Vec<FaceId>, CutError> {
    let each: Vec<(CutTarget, CutOffset)> = targets.iter().map(|&t| (t, offset)).collect();
    cut_each(mesh, &each)
}

/// The targets paired with their offsets for [`cut_each`]: each vertex
/// cut at `vertex`, each edge or face cut at `other`. This is how the
/// front ends (the command line, Python) take a cut's depth, as a vertex
/// cut may want another offset than the edges and faces cut with it.
pub fn offsets_by_kind(
    targets: impl IntoIterator<Item = CutTarget>,
    vertex: CutOffset,
    other: CutOffset,
) -> Vec<(CutTarget, CutOffset)> {
    targets
        .into_iter()
        .map(|t| match t {
            CutTarget::Vertex(_) => (t, vertex),
            _ => (t, other),
        })
        .collect()
}

/// [`cut`] with an offset of its own for each target (the first given
/// for a target named twice): a spoke between two regions is cut at each
/// end by its own region's offset, each below half the spoke.
pub fn cut_each(
    mesh: &mut Mesh,
    targets: &[(CutTarget, CutOffset)],
) -> Result<Vec<FaceId>, CutError> {
    for (_, offset) in targets {
        let amount = match *offset {
            CutOffset::Distance(x) | CutOffset::Fraction(x) => x,
        };
        if !(amount.is_finite() && amount > 0.0) {
            return Err(CutError::InvalidOffset(amount));
        }
    }
    let mut seen = HashSet::new();
    let unique: Vec<(CutTarget, CutOffset)> = targets
        .iter()
        .copied()
        .filter(|(t, _)| seen.insert(*t))
        .collect();
    let offsets: Vec<CutOffset> = unique.iter().map(|&(_, o)| o).collect();
    let mut owner: HashMap<VertexId, usize> = HashMap::new();
    let mut regions = Vec::with_capacity(unique.len());
    for (i, &(t, _)) in unique.iter().enumerate() {
        let region = plan_region(mesh, t)?;
        for &v in &region.vertices {
            if owner.insert(v, i).is_some() {
                return Err(CutError::Overlap(v));
            }
        }
        regions.push(region);
    }
    let spokes = plan_spokes(mesh, &regions, &owner, &offsets)?;
    apply(mesh, &regions, &spokes)
}

/// The region of one target, checked to be a disk.
fn plan_region(mesh: &Mesh, target: CutTarget) -> Result<Region, CutError> {
    let vertices: BTreeSet<VertexId> = match target {
        CutTarget::Vertex(v) => {
            mesh.valence(v)?;
            BTreeSet::from([v])
        }
        CutTarget::Edge(e) => {
            if mesh.is_self_loop(e)? {
                return Err(CutError::SelfLoop(e));
            }
            mesh.edge_vertices(e)?.into_iter().collect()
        }
        CutTarget::Face(f) => {
            if mesh.is_hole(f)? {
                return Err(CutError::HoleFace(f));
            }
            mesh.face_vertices(f)?.into_iter().collect()
        }
    };
    let mut inner = BTreeSet::new();
    let mut spokes = 0usize;
    let mut faces = BTreeSet::new();
    for &v in &vertices {
        for c in mesh.vertex_corners(v)? {
            faces.insert(mesh.corner_face(c)?);
            let Some(e) = mesh.corner_edge(c)? else {
                continue;
            };
            if mesh.is_self_loop(e)? {
                return Err(CutError::SelfLoop(e));
            }
            let [a, b] = mesh.edge_vertices(e)?;
            if vertices.contains(&a) && vertices.contains(&b) {
                inner.insert(e);
            } else {
                spokes += 1;
            }
        }
    }
    // Every edge leaving S starts at exactly one corner at its S end, so
    // each spoke was counted once.
    if spokes == 0 {
        return Err(CutError::NothingToCut(target));
    }
    let mut runs = Vec::new();
    let mut full = 0i64;
    for &f in &faces {
        let corners: Vec<CornerId> = mesh.face_corners(f)?.collect();
        let inside: Vec<bool> = corners
            .iter()
            .map(|&c| mesh.corner_vertex(c).map(|v| vertices.contains(&v)))
            .collect::<Result<_, _>>()?;
        if inside.iter().all(|&x| x) {
            if mesh.is_hole(f)? {
                return Err(CutError::HoleFace(f));
            }
            full += 1;
            continue;
        }
        let n = corners.len();
        for k in 0..n {
            if inside[k] && !inside[(k + n - 1) % n] {
                let mut last = k;
                while inside[(last + 1) % n] {
                    last = (last + 1) % n;
                }
                runs.push((corners[k], corners[last]));
            }
        }
    }
    // A disk: χ of the region's open cells is 1, and S is connected by I.
    let chi = vertices.len() as i64 - inner.len() as i64 + full;
    if chi != 1 || !connected(mesh, &vertices, &inner)? {
        return Err(CutError::NotADisk(target));
    }
    Ok(Region {
        runs,
        vertices: vertices.into_iter().collect(),
    })
}

fn connected(
    mesh: &Mesh,
    vertices: &BTreeSet<VertexId>,
    inner: &BTreeSet<EdgeId>,
) -> Result<bool, CutError> {
    let index: BTreeMap<VertexId, usize> =
        vertices.iter().enumerate().map(|(i, &v)| (v, i)).collect();
    let mut sets = holey_mesh::UnionFind::new(vertices.len());
    for &e in inner {
        let [a, b] = mesh.edge_vertices(e)?;
        if let (Some(&x), Some(&y)) = (index.get(&a), index.get(&b)) {
            sets.union(x as u32, y as u32);
        }
    }
    let root = sets.find(0);
    Ok((1..vertices.len()).all(|i| sets.find(i as u32) == root))
}

/// Every spoke with its cuts, checked against its length.
fn plan_spokes(
    mesh: &Mesh,
    regions: &[Region],
    owner: &HashMap<VertexId, usize>,
    offsets: &[CutOffset],
) -> Result<Vec<Spoke>, CutError> {
    let mut edges = BTreeSet::new();
    for r in regions {
        for &v in &r.vertices {
            for c in mesh.vertex_corners(v)? {
                // Every edge at v leaves from exactly one corner at v.
                if let Some(e) = mesh.corner_edge(c)? {
                    edges.insert(e);
                }
            }
        }
    }
    let mut spokes = Vec::new();
    for e in edges {
        let [a, b] = mesh.edge_vertices(e)?;
        let ends: Vec<VertexId> = [a, b]
            .into_iter()
            .filter(|v| owner.contains_key(v))
            .collect();
        let both = ends.len() == 2;
        if both && owner.get(&a) == owner.get(&b) {
            continue; // an inner edge
        }
        if ends.is_empty() {
            continue;
        }
        let length = mesh.position(a)?.distance(mesh.position(b)?);
        let mut cuts = Vec::with_capacity(2);
        for v in ends {
            let offset = owner.get(&v).and_then(|&i| offsets.get(i));
            let x = match offset {
                Some(CutOffset::Distance(x)) => *x,
                Some(CutOffset::Fraction(t)) => t * length,
                None => return Err(internal("a spoke's end has no region")),
            };
            // Half the spoke, whether or not its other end is cut now: a
            // point past the middle would leave the far end's own cut (now
            // or later) nowhere to go.
            let limit = length / 2.0;
            if x.is_nan() || x >= limit {
                return Err(CutError::OffsetTooLarge {
                    edge: e,
                    length,
                    offset: x,
                    limit,
                });
            }
            cuts.push((v, x));
        }
        spokes.push(Spoke { edge: e, cuts });
    }
    Ok(spokes)
}

/// Splits edge `e` at `distance` from its end `from`; returns the piece
/// still touching `from`'s far side (the one from the new vertex away
/// from `from`).
fn split_from(
    mesh: &mut Mesh,
    e: EdgeId,
    from: VertexId,
    distance: f64,
) -> Result<EdgeId, CutError> {
    let [a, b] = mesh.edge_vertices(e)?;
    let length = mesh.position(a)?.distance(mesh.position(b)?);
    let t = if a == from {
        distance / length
    } else {
        1.0 - distance / length
    };
    let s = mesh.subdivide_edge_at(e, t)?;
    // edges[0] runs from a to the new vertex, edges[1] on to b.
    Ok(if a == from { s.edges[1] } else { s.edges[0] })
}

/// For a region whose wound would be a two-gon (two runs, in two
/// different faces), the run to cut across: the first in a surface face.
fn two_gon_run(mesh: &Mesh, runs: &[(CornerId, CornerId)]) -> Result<Option<usize>, CutError> {
    let [(a, _), (b, _)] = runs else {
        return Ok(None);
    };
    let (fa, fb) = (mesh.corner_face(*a)?, mesh.corner_face(*b)?);
    if fa == fb {
        return Ok(None);
    }
    Ok(Some(if mesh.is_hole(fa)? && !mesh.is_hole(fb)? {
        1
    } else {
        0
    }))
}

fn apply(mesh: &mut Mesh, regions: &[Region], spokes: &[Spoke]) -> Result<Vec<FaceId>, CutError> {
    // 1. The cut points.
    for spoke in spokes {
        let mut rest = spoke.edge;
        for (k, &(v, x)) in spoke.cuts.iter().enumerate() {
            if k == 0 {
                rest = split_from(mesh, rest, v, x)?;
            } else {
                split_from(mesh, rest, v, x)?;
            }
        }
    }
    // 2. Across each face, join the points before and after each run of
    //    region corners: the run is cut off on its own face.
    let mut cut_edges = Vec::with_capacity(regions.len());
    for r in regions {
        let mut first_edge = None;
        let mut runs = r.runs.clone();
        let mut opens_into_hole = false;
        if let Some(keep) = two_gon_run(mesh, &runs)? {
            // Two spokes in two faces: the wound would be a two-gon, so its
            // two sides become one edge across one face (a surface face,
            // not the hole, when the region is on a boundary).
            opens_into_hole = mesh.is_hole(mesh.corner_face(runs[1 - keep].0)?)?;
            runs = vec![runs[keep]];
        }
        for &(first, last) in &runs {
            let before = mesh.corner_prev(first)?;
            let after = mesh.corner_next(last)?;
            let e = mesh.insert_edge(after, before)?;
            first_edge.get_or_insert(e);
        }
        cut_edges.push((
            first_edge.ok_or_else(|| internal("a region without runs"))?,
            opens_into_hole,
        ));
    }
    // 3. Delete the region's edges (inner ones first) and so its vertices.
    for r in regions {
        let mut edges: Vec<(bool, EdgeId)> = Vec::new();
        let inside: HashSet<VertexId> = r.vertices.iter().copied().collect();
        for &v in &r.vertices {
            for c in mesh.vertex_corners(v)? {
                if let Some(e) = mesh.corner_edge(c)? {
                    let [a, b] = mesh.edge_vertices(e)?;
                    edges.push((!(inside.contains(&a) && inside.contains(&b)), e));
                }
            }
        }
        edges.sort();
        edges.dedup();
        for (_, e) in edges {
            if mesh.contains_edge(e) {
                mesh.delete_edge_with_cleanup(e)?;
            }
        }
        for &v in &r.vertices {
            if mesh.contains_vertex(v) {
                return Err(internal("a region vertex survived its cut"));
            }
        }
    }
    // The first corner of a cut edge lies on the side that was cut off,
    // which is now the new face.
    let mut faces = Vec::with_capacity(regions.len());
    for &(e, hole) in &cut_edges {
        let f = mesh.corner_face(mesh.edge_corners(e)?[0])?;
        if hole {
            // The boundary loop took in the cut-off corner; merging kept
            // the surface face's flag.
            mesh.set_hole(f, true)?;
        }
        faces.push(f);
    }
    Ok(faces)
}

#[cfg(test)]
mod tests;
