//! The machinery behind [`super::extrude_face`] and
//! [`super::extrude_faces`]: lift a set of selected faces off the
//! surface and join them to it with a ring of quadrilateral walls along
//! the selection's boundary, with fundamental operators only.
//!
//! ## Fans
//! Around a vertex, the corners in rotation order are selected (their
//! face is selected) or not. A vertex whose corners are all selected is
//! *interior*: it just moves. Otherwise its selected corners form *fans*,
//! maximal runs `s_1 … s_m` in rotation order: the edge leaving `s_j`
//! lies between `face(s_j)` and `face(s_(j+1))`, so `s_1 … s_(m−1)` leave
//! along *interior* edges (selected on both sides) and `s_m` along a
//! *boundary* edge (selected on its side only). Each boundary side ends
//! exactly one fan, so walls = fans.
//!
//! ## Steps (each a valid mesh)
//! 1. For every fan at `v`: `CreateVertex(v′)` and `InsertEdge(s_1, σ)`
//!    hangs `v′` inside `face(s_1)` on a new edge `v–v′` (the future
//!    wall's side). Then every interior edge `i_j = v–x_j` of the fan is
//!    moved to `v′`: `InsertEdge(next(s_j), prev(s_j))` cuts the triangle
//!    `(v, x_j, v′)` off `face(s_j)` along a new edge `x_j–v′`, and
//!    `DeleteEdge(i_j)` merges that triangle into `face(s_(j+1))`, where
//!    `v′` now sits just before `s_(j+1)`. The new edge replaces `i_j`
//!    (an edge between two boundary vertices is moved twice, once from
//!    each end).
//! 2. For every fan, the boundary edge `v → w` leaving `s_m` now reads
//!    `v′ → v → w → w′` in its selected face: `InsertEdge` between the
//!    corners at `w′` and `v′` cuts off the wall quad `(v, w, w′, v′)`.
//! 3. Interior vertices move to their targets.
//!
//! Per fan: +1 vertex, +2 edges (`v–v′` and the wall's top), +1 face
//! (the wall); moving an interior edge adds one edge and deletes one.

use std::collections::{BTreeSet, HashMap, HashSet};

use holey_dlfl::{CornerId, DVec3, EdgeId, FaceId, Mesh, VertexId};

use super::{ExtrudeError, check_surface_face};

/// A boundary vertex's maximal run of selected corners.
#[derive(Clone, Debug)]
pub(super) struct Fan {
    pub vertex: VertexId,
    /// The fan's corners in rotation order, as planned.
    pub corners: Vec<CornerId>,
    /// The edges leaving all but the last corner (selected on both sides).
    interior: Vec<EdgeId>,
    /// The boundary edge leaving the last corner.
    last: EdgeId,
}

/// Everything an extrusion of a selection needs, checked before any change.
#[derive(Clone, Debug)]
pub(super) struct RegionPlan {
    pub fans: Vec<Fan>,
    /// Where each fan's new vertex goes, in fan order.
    pub fan_targets: Vec<DVec3>,
    /// Interior vertices, where they move, and their corners as planned.
    pub interior: Vec<(VertexId, DVec3, Vec<CornerId>)>,
}

/// What [`apply`] made.
#[derive(Clone, Debug)]
pub(super) struct RegionResult {
    /// The wall quads, one per fan, in fan order.
    pub walls: Vec<FaceId>,
    /// The lifted faces (every vertex moved or new), in slot order.
    pub tops: Vec<FaceId>,
    /// The new vertex of each fan, in fan order.
    pub fan_vertices: Vec<VertexId>,
    /// For every planned corner of a selected face, the vertex that now
    /// stands for it on the lifted side.
    pub lifted: HashMap<CornerId, VertexId>,
}

/// Where a fan's new vertex (or an interior vertex) goes, given the
/// vertex and the fan's corners (all its corners for an interior vertex).
pub(super) type TargetFn<'a> = dyn Fn(VertexId, &[CornerId]) -> Result<DVec3, ExtrudeError> + 'a;

/// Finds the fans and interior vertices of the selection `faces` (live,
/// non-hole faces with edges and no self-loops, else an error) without
/// positions; [`RegionPlan::fan_targets`] and the interior targets are
/// filled by `target(vertex, corners)`, given the fan's corners (or all
/// the corners of an interior vertex).
pub(super) fn plan(
    mesh: &Mesh,
    faces: &[FaceId],
    target: &TargetFn<'_>,
) -> Result<RegionPlan, ExtrudeError> {
    if faces.is_empty() {
        return Err(ExtrudeError::EmptySelection);
    }
    let selected: HashSet<FaceId> = faces.iter().copied().collect();
    let mut vertices = BTreeSet::new();
    for &f in faces {
        check_surface_face(mesh, f)?;
        for c in mesh.face_corners(f)? {
            vertices.insert(mesh.corner_vertex(c)?);
        }
    }
    let mut plan = RegionPlan {
        fans: Vec::new(),
        fan_targets: Vec::new(),
        interior: Vec::new(),
    };
    for v in vertices {
        let ring: Vec<CornerId> = mesh.vertex_rotation(v)?.collect();
        let mut chosen = Vec::with_capacity(ring.len());
        for &c in &ring {
            chosen.push(selected.contains(&mesh.corner_face(c)?));
        }
        let Some(start) = chosen.iter().position(|&s| !s) else {
            let p = target(v, &ring)?;
            plan.interior.push((v, p, ring));
            continue;
        };
        let n = ring.len();
        let mut run: Vec<CornerId> = Vec::new();
        for step in 1..=n {
            let k = (start + step) % n;
            if chosen[k] {
                run.push(ring[k]);
            } else if !run.is_empty() {
                let fan = make_fan(mesh, v, std::mem::take(&mut run))?;
                plan.fan_targets.push(target(v, &fan.corners)?);
                plan.fans.push(fan);
            }
        }
    }
    Ok(plan)
}

fn make_fan(mesh: &Mesh, vertex: VertexId, corners: Vec<CornerId>) -> Result<Fan, ExtrudeError> {
    let mut edges = Vec::with_capacity(corners.len());
    for &c in &corners {
        // Selected faces have edges, so every corner here starts one.
        let e = mesh
            .corner_edge(c)?
            .ok_or_else(|| internal("a fan corner without an edge"))?;
        edges.push(e);
    }
    let last = edges.pop().ok_or_else(|| internal("an empty fan"))?;
    Ok(Fan {
        vertex,
        corners,
        interior: edges,
        last,
    })
}

fn internal(what: &str) -> ExtrudeError {
    ExtrudeError::Kernel(holey_dlfl::Error::Invalid(format!(
        "internal error in extrusion (please report): {what}"
    )))
}

/// The corner at which edge `e` leaves `v` (edges here are never loops).
fn origin_at(mesh: &Mesh, e: EdgeId, v: VertexId) -> Result<CornerId, ExtrudeError> {
    let [a, b] = mesh.edge_corners(e)?;
    if mesh.corner_vertex(a)? == v {
        Ok(a)
    } else if mesh.corner_vertex(b)? == v {
        Ok(b)
    } else {
        Err(internal("an edge of a fan no longer touches its vertex"))
    }
}

/// Follows the chain of edges that replaced `e` when it was moved.
fn resolve(moved: &HashMap<EdgeId, EdgeId>, mut e: EdgeId) -> EdgeId {
    while let Some(&next) = moved.get(&e) {
        e = next;
    }
    e
}

/// Applies a plan made by [`plan`] on this same, unchanged mesh.
pub(super) fn apply(mesh: &mut Mesh, plan: &RegionPlan) -> Result<RegionResult, ExtrudeError> {
    let mut moved: HashMap<EdgeId, EdgeId> = HashMap::new();
    let mut fan_vertices = Vec::with_capacity(plan.fans.len());
    let mut lifted = HashMap::new();
    // Step 1: hang each fan's new vertex and move its interior edges to it.
    for (fan, &target) in plan.fans.iter().zip(&plan.fan_targets) {
        let (vp, _, sigma) = mesh.create_vertex(target)?;
        fan_vertices.push(vp);
        for &c in &fan.corners {
            lifted.insert(c, vp);
        }
        let first = resolve(&moved, *fan.interior.first().unwrap_or(&fan.last));
        mesh.insert_edge(origin_at(mesh, first, fan.vertex)?, sigma)?;
        for &i in &fan.interior {
            let cur = resolve(&moved, i);
            let s = origin_at(mesh, cur, fan.vertex)?;
            let before = mesh.corner_prev(s)?;
            if mesh.corner_vertex(before)? != vp {
                return Err(internal(
                    "the new vertex does not precede the fan's next corner",
                ));
            }
            let replacement = mesh.insert_edge(mesh.corner_next(s)?, before)?;
            mesh.delete_edge(cur)?;
            moved.insert(cur, replacement);
        }
    }
    // Step 2: cut one wall quad off each selected face per boundary side.
    let mut walls = Vec::with_capacity(plan.fans.len());
    for fan in &plan.fans {
        let s = origin_at(mesh, fan.last, fan.vertex)?;
        let at_v = mesh.corner_prev(s)?;
        let at_w = mesh.corner_next(mesh.corner_next(s)?)?;
        let top = mesh.insert_edge(at_w, at_v)?;
        walls.push(mesh.corner_face(mesh.edge_corners(top)?[0])?);
    }
    // Step 3: interior vertices follow.
    for (v, p, corners) in &plan.interior {
        mesh.set_position(*v, *p)?;
        for &c in corners {
            lifted.insert(c, *v);
        }
    }
    let tops = lifted_faces(mesh, &fan_vertices, &plan.interior)?;
    Ok(RegionResult {
        walls,
        tops,
        fan_vertices,
        lifted,
    })
}

/// The faces all of whose corners are at moved or new vertices: the
/// selected faces in their new place.
fn lifted_faces(
    mesh: &Mesh,
    fan_vertices: &[VertexId],
    interior: &[(VertexId, DVec3, Vec<CornerId>)],
) -> Result<Vec<FaceId>, ExtrudeError> {
    let up: HashSet<VertexId> = fan_vertices
        .iter()
        .copied()
        .chain(interior.iter().map(|(v, _, _)| *v))
        .collect();
    let mut tops = BTreeSet::new();
    for &v in &up {
        for c in mesh.vertex_corners(v)? {
            let f = mesh.corner_face(c)?;
            if tops.contains(&f) {
                continue;
            }
            let mut all = true;
            for w in mesh.face_vertices(f)? {
                all &= up.contains(&w);
            }
            if all {
                tops.insert(f);
            }
        }
    }
    Ok(tops.into_iter().collect())
}
