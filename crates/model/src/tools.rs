//! # Mesh tools (TopMod's object menu, issue 18)
//!
//! - [`planarize_faces`]: iterative projection of every vertex onto the
//!   least-squares planes of its faces, until the faces are flat;
//! - [`make_spherical`]: projection onto the least-squares sphere;
//! - [`cleanup_two_gons`]: each two-gon's two edges merged into one;
//! - [`remove_valence_two_vertices`]: each vertex on exactly two edges
//!   removed, its edges merged into one;
//! - [`split_valence_two_vertices`]: each such vertex split into two.
//!
//! The first two move vertices only; the others change counts as each
//! function says. All check their parameters first and leave the mesh
//! unchanged when they refuse.

use std::collections::{BTreeSet, HashMap};

use holey_dlfl::{DVec3, EdgeId, FaceId, Mesh, VertexId};

use crate::polygon;

/// Why a tool refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ToolError {
    /// A parameter is NaN, infinite or outside its range.
    #[error("parameter '{name}' is {value}; it must be {expected}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The accepted range in words.
        expected: &'static str,
    },
    /// A hole face was given to a tool that works on surface faces.
    #[error("face {0} is a hole (a boundary loop), not surface")]
    HoleFace(FaceId),
    /// The vertices do not determine a sphere (fewer than four, or all on
    /// one plane or circle).
    #[error("the {0} vertices do not determine a sphere (they are too few or lie on one plane)")]
    NoSphere(usize),
    /// A vertex sits at the centre of the fitted sphere, so it has no
    /// direction to be projected along.
    #[error("vertex {0} is at the centre of the fitted sphere; it cannot be projected onto it")]
    AtCentre(VertexId),
    /// The split distance reaches the middle of an edge.
    #[error("a split distance of {distance} reaches the middle of edge {edge} (length {length})")]
    DistanceTooLarge {
        /// The edge.
        edge: EdgeId,
        /// Its length.
        length: f64,
        /// The distance asked for.
        distance: f64,
    },
    /// A kernel call failed: an id not in the mesh, or (after the checks) a bug.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// The parameters of [`planarize_faces`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarizeParams {
    /// Most iterations to run (0 only measures).
    pub max_iterations: usize,
    /// Stop once every corner is within this fraction of the mean edge
    /// length of its face's best-fit plane (finite and positive).
    pub tolerance: f64,
}

impl Default for PlanarizeParams {
    /// 1000 iterations, tolerance 10⁻⁹ of the mean edge length.
    fn default() -> Self {
        PlanarizeParams {
            max_iterations: 1000,
            tolerance: 1e-9,
        }
    }
}

/// What [`planarize_faces`] did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarizeReport {
    /// Iterations run (each moves every vertex of the faces once).
    pub iterations: usize,
    /// Faces considered (of four or more corners; triangles are flat).
    pub faces: usize,
    /// The largest distance of a corner from its face's best-fit plane,
    /// relative to the mean edge length, before and after.
    pub before: f64,
    /// As `before`, after the last iteration.
    pub after: f64,
    /// Whether `after` is within the tolerance.
    pub converged: bool,
}

fn check_param(
    name: &'static str,
    value: f64,
    expected: &'static str,
    ok: bool,
) -> Result<(), ToolError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ToolError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}

/// Planarizes `faces` (all surface faces when empty) by iterative
/// projection: each iteration fits the least-squares plane of every face
/// (through its centroid, normal the direction of least variance) and
/// moves every vertex to the average of its projections onto the planes
/// of its faces. Stops when every corner is within `tolerance` (relative
/// to the mean edge length) of its plane, or after `max_iterations`;
/// the report counts the iterations. Counts and connectivity are
/// unchanged; triangles are flat already and are not considered.
pub fn planarize_faces(
    mesh: &mut Mesh,
    faces: &[FaceId],
    params: &PlanarizeParams,
) -> Result<PlanarizeReport, ToolError> {
    check_param(
        "tolerance",
        params.tolerance,
        "finite and greater than 0",
        params.tolerance > 0.0,
    )?;
    let chosen: Vec<FaceId> = if faces.is_empty() {
        let mut all = Vec::new();
        for f in mesh.faces() {
            if !mesh.is_hole(f)? {
                all.push(f);
            }
        }
        all
    } else {
        for &f in faces {
            if mesh.is_hole(f)? {
                return Err(ToolError::HoleFace(f));
            }
        }
        faces.to_vec()
    };
    let mut work = Vec::new();
    for f in chosen.into_iter().collect::<BTreeSet<_>>() {
        if mesh.face_len(f)? >= 4 {
            work.push((f, mesh.face_vertices(f)?));
        }
    }
    let scale = {
        let mut total = 0.0;
        for (f, _) in &work {
            total += polygon::mean_edge(&mesh.face_positions(*f)?);
        }
        if work.is_empty() {
            1.0
        } else {
            total / work.len() as f64
        }
    };
    let before = deviation(mesh, &work)? / scale;
    let mut after = before;
    let mut iterations = 0;
    while iterations < params.max_iterations && after > params.tolerance {
        let mut sum: HashMap<VertexId, (DVec3, f64)> = HashMap::new();
        for (f, vs) in &work {
            let pts = mesh.face_positions(*f)?;
            let Some((c, n)) = polygon::best_fit_plane(&pts) else {
                continue;
            };
            for (&v, &p) in vs.iter().zip(&pts) {
                let e = sum.entry(v).or_insert((DVec3::ZERO, 0.0));
                e.0 += p - n * (p - c).dot(n);
                e.1 += 1.0;
            }
        }
        for (v, (s, k)) in sum {
            mesh.set_position(v, s / k)?;
        }
        iterations += 1;
        after = deviation(mesh, &work)? / scale;
    }
    Ok(PlanarizeReport {
        iterations,
        faces: work.len(),
        before,
        after,
        converged: after <= params.tolerance,
    })
}

/// The largest distance of a corner from its face's best-fit plane.
fn deviation(mesh: &Mesh, work: &[(FaceId, Vec<VertexId>)]) -> Result<f64, ToolError> {
    let mut worst = 0.0f64;
    for (f, _) in work {
        let pts = mesh.face_positions(*f)?;
        if let Some((c, n)) = polygon::best_fit_plane(&pts) {
            for p in &pts {
                worst = worst.max((*p - c).dot(n).abs());
            }
        }
    }
    Ok(worst)
}

/// The sphere [`make_spherical`] projected onto.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereFit {
    /// Its centre.
    pub centre: DVec3,
    /// Its radius.
    pub radius: f64,
}

/// Projects `vertices` (all vertices when empty) onto their least-squares
/// sphere (the algebraic fit `|p|² = 2c·p + k`, `r² = k + |c|²`): each
/// moves along the ray from the centre. Counts unchanged. Refused when
/// the points determine no sphere or one sits at its centre.
pub fn make_spherical(mesh: &mut Mesh, vertices: &[VertexId]) -> Result<SphereFit, ToolError> {
    let chosen: Vec<VertexId> = if vertices.is_empty() {
        mesh.vertices().collect()
    } else {
        vertices
            .iter()
            .copied()
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect()
    };
    let mut points = Vec::with_capacity(chosen.len());
    for &v in &chosen {
        points.push(mesh.position(v)?);
    }
    let (centre, radius) =
        polygon::best_fit_sphere(&points).ok_or(ToolError::NoSphere(points.len()))?;
    let mut moved = Vec::with_capacity(chosen.len());
    for (&v, &p) in chosen.iter().zip(&points) {
        let d = p - centre;
        let len = d.length();
        if len.is_nan() || len <= 1e-12 * radius {
            return Err(ToolError::AtCentre(v));
        }
        moved.push((v, centre + d * (radius / len)));
    }
    for (v, p) in moved {
        mesh.set_position(v, p)?;
    }
    Ok(SphereFit { centre, radius })
}

/// Merges the two edges of every two-gon into one (TopMod's "cleanup
/// 2-gons"): one edge is deleted, which merges the two-gon into the face
/// across it, so the two faces beside the two-gon now meet along the
/// other. Repeats until none is left. Hole two-gons, and a two-gon
/// bordered only by itself (a lone edge), are kept. Each removal: −1
/// edge, −1 face. Returns the number removed.
pub fn cleanup_two_gons(mesh: &mut Mesh) -> usize {
    mesh.remove_two_gons()
}

/// Removes every vertex of valence 2 whose two edges are distinct and
/// lead to corners that can be joined (TopMod's "remove valence-2
/// vertices"): an edge is inserted between its two neighbours beside it
/// and its two edges are deleted, so its neighbours become joined by one
/// edge and the vertex disappears. Each removal: −1 vertex, −1 edge,
/// faces unchanged. Returns how many were removed; vertices on a
/// self-loop or inside a two-gon with its neighbour are left.
pub fn remove_valence_two_vertices(mesh: &mut Mesh) -> Result<usize, ToolError> {
    let mut candidates = Vec::new();
    for v in mesh.vertices() {
        if mesh.valence(v)? == 2 {
            candidates.push(v);
        }
    }
    let mut removed = 0;
    for v in candidates {
        if !mesh.contains_vertex(v) || mesh.valence(v)? != 2 {
            continue;
        }
        let Some(c) = mesh.vertex_corners(v)?.next() else {
            continue;
        };
        let (before, after) = (mesh.corner_prev(c)?, mesh.corner_next(c)?);
        let edges: Vec<EdgeId> = mesh
            .vertex_corners(v)?
            .filter_map(|k| mesh.corner_edge(k).ok().flatten())
            .collect();
        let distinct = edges.len() == 2 && edges[0] != edges[1];
        let loops = edges.iter().any(|&e| mesh.is_self_loop(e).unwrap_or(true));
        if !distinct || loops || before == after {
            continue;
        }
        // The new edge cuts the triangle (before, v, after) off v's face;
        // deleting v's edges then merges that triangle across them.
        mesh.insert_edge(after, before)?;
        for e in edges {
            mesh.delete_edge_with_cleanup(e)?;
        }
        removed += 1;
    }
    Ok(removed)
}

/// Splits every vertex of valence 2 (not on a self-loop) into two,
/// `distance` apart along its edges (TopMod's "split valence-2
/// vertices", meant for meshes made from valence-1 vertices): a new
/// vertex is inserted on one of its edges `distance` from it, and the
/// vertex itself moves `distance` along the other. Each split: +1 vertex,
/// +1 edge. Vertices of valence 2 made by the splits are not split
/// again. `distance` must be positive, finite and less than half of each
/// edge at such a vertex. Returns the number split.
pub fn split_valence_two_vertices(mesh: &mut Mesh, distance: f64) -> Result<usize, ToolError> {
    check_param(
        "distance",
        distance,
        "finite and greater than 0",
        distance > 0.0,
    )?;
    // Plan from the mesh as it is: each vertex, the edge it splits with
    // that edge's far end, and the two new positions.
    let mut plan = Vec::new();
    for v in mesh.vertices() {
        if mesh.valence(v)? != 2 {
            continue;
        }
        let mut edges = Vec::with_capacity(2);
        for c in mesh.vertex_corners(v)? {
            if let Some(e) = mesh.corner_edge(c)? {
                edges.push(e);
            }
        }
        if edges.len() != 2 || edges[0] == edges[1] || mesh.is_self_loop(edges[0])? {
            continue;
        }
        let p = mesh.position(v)?;
        let mut ends = Vec::with_capacity(2);
        for &e in &edges {
            let [a, b] = mesh.edge_vertices(e)?;
            let far = if a == v { b } else { a };
            let length = mesh.position(far)?.distance(p);
            if length.is_nan() || distance >= length / 2.0 {
                return Err(ToolError::DistanceTooLarge {
                    edge: e,
                    length,
                    distance,
                });
            }
            ends.push((far, p + (mesh.position(far)? - p) * (distance / length)));
        }
        plan.push((v, edges[0], ends[0].0, ends[0].1, ends[1].1));
    }
    // The piece of an original edge that touches one of its original ends
    // (an edge split from both ends is split twice).
    let mut piece: HashMap<(EdgeId, VertexId), EdgeId> = HashMap::new();
    for &(v, split, far_end, q, r) in &plan {
        let e = piece.get(&(split, v)).copied().unwrap_or(split);
        let [a, b] = mesh.edge_vertices(e)?;
        let made = mesh.subdivide_edge_at(e, 0.5)?;
        mesh.set_position(made.vertex, q)?;
        mesh.set_position(v, r)?;
        // edges[0] runs from a to the new vertex, edges[1] on to b.
        let (at_v, at_far, far) = if a == v {
            (made.edges[0], made.edges[1], b)
        } else {
            (made.edges[1], made.edges[0], a)
        };
        piece.insert((split, v), at_v);
        if far == far_end {
            piece.insert((split, far_end), at_far);
        }
    }
    Ok(plan.len())
}

#[cfg(test)]
mod tests;
