//! The topological half of one level of §VII.3: the kernel operators, in
//! the thesis's order, driven by a [`Plan`].
//!
//! Half-edges are held as the corners that start them. The kernel keeps
//! every existing corner handle valid through `InsertEdge`, `ConnectEdges`,
//! `SubDivideEdge` and `CollapseEdge` (a corner keeps its outgoing edge;
//! only the corners at which a deleted or collapsed edge starts go), so a
//! corner recorded early still names the same half-edge later, though its
//! face may change.

use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, VertexId};

use super::MengerError;
use super::MengerLevel;
use super::plan::{ANGLE_ULPS, Decision, LEN_REL, Plan};

/// The corners of a fresh face manifold, in point order, in its front
/// face and in its back face.
struct Manifold {
    front: Vec<CornerId>,
    back: Vec<CornerId>,
    vertices: Vec<VertexId>,
}

fn face_manifold(mesh: &mut Mesh, points: &[holey_dlfl::DVec3]) -> Result<Manifold, MengerError> {
    let fm = mesh.create_face_manifold(points)?;
    let n = points.len();
    let corner_in = |mesh: &Mesh, f: FaceId| -> Result<CornerId, MengerError> {
        for c in mesh.vertex_corners(fm.vertices[0])? {
            if mesh.corner_face(c)? == f {
                return Ok(c);
            }
        }
        Err(MengerError::Kernel(holey_dlfl::Error::Invalid(
            "face manifold without a corner at its first point".into(),
        )))
    };
    // The front face lists the points in order, the back face reversed.
    let front: Vec<CornerId> = mesh
        .face_corners_from(corner_in(mesh, fm.front)?)?
        .collect();
    let mut back = vec![front[0]; n];
    for (i, c) in mesh
        .face_corners_from(corner_in(mesh, fm.back)?)?
        .enumerate()
    {
        back[(n - i) % n] = c;
    }
    Ok(Manifold {
        front,
        back,
        vertices: fm.vertices,
    })
}

/// The corner of vertex `v` that lies in face `f`.
fn corner_at(mesh: &Mesh, v: VertexId, f: FaceId) -> Result<CornerId, MengerError> {
    for c in mesh.vertex_corners(v)? {
        if mesh.corner_face(c)? == f {
            return Ok(c);
        }
    }
    Err(MengerError::Kernel(holey_dlfl::Error::Invalid(format!(
        "vertex {v} has no corner in face {f}"
    ))))
}

/// Runs one planned level on `mesh`.
pub(crate) fn apply(mesh: &mut Mesh, plan: &Plan) -> Result<MengerLevel, MengerError> {
    let total = plan.corners.len();
    let nf = plan.faces.len();
    // Step 1: remeshing face pairs. For global corner g (corner j of face
    // i), the back remeshing face's matching half-edge runs p′j+1 → p′j and
    // starts at the back corner of p′j+1.
    let mut remesh_back = Vec::with_capacity(total);
    let mut remesh_front0 = Vec::with_capacity(nf);
    for face in &plan.faces {
        let m = face_manifold(mesh, &plan.remesh[face.start..face.start + face.len])?;
        for j in 0..face.len {
            remesh_back.push(m.back[(j + 1) % face.len]);
        }
        remesh_front0.push(m.front[0]);
    }
    // Step 2: offset face pairs. The front offset face's half-edge j runs
    // p″j → p″j+1, like the original edge in its face.
    let mut offset_front = Vec::with_capacity(total);
    let mut offset_vertex = Vec::with_capacity(total);
    let mut offset_back0 = Vec::with_capacity(nf);
    for face in &plan.faces {
        let m = face_manifold(mesh, &plan.offset[face.start..face.start + face.len])?;
        offset_front.extend_from_slice(&m.front);
        offset_vertex.extend_from_slice(&m.vertices);
        offset_back0.push(m.back[0]);
    }

    // Step 3a: ConnectEdges between the outward offset faces. The first
    // inserted edge joins the two offset corners at u, the second those at v.
    //
    // The strip walks u″1 → v″1 → v″2 → u″2, so the *vertex face* (the
    // remnant of the offset front faces around an original vertex) walks
    // the first connecting edge from u″1 and the second from v″2. Those
    // corners are recorded: they stay valid unless their edge is collapsed.
    let mut connecting: Vec<[EdgeId; 2]> = Vec::with_capacity(plan.edges.len());
    let mut vertex_face: Vec<[CornerId; 2]> = Vec::with_capacity(plan.edges.len());
    for ep in &plan.edges {
        let (_, pair) = mesh.connect_edges(offset_front[ep.a], offset_front[ep.b])?;
        let side_at = |mesh: &Mesh, e: EdgeId, v: VertexId| -> Result<CornerId, MengerError> {
            let [x, y] = mesh.edge_corners(e)?;
            Ok(if mesh.corner_vertex(x)? == v { x } else { y })
        };
        vertex_face.push([
            side_at(mesh, pair[0], offset_vertex[ep.a])?,
            side_at(mesh, pair[1], offset_vertex[ep.b])?,
        ]);
        connecting.push(pair);
    }
    // Figure 61 for cases 5 and 6: a vertex on each connecting edge, and an
    // edge between them across the strip. The strip is the face on the
    // offset side of the first half-edge.
    let mut bent = 0;
    for (ep, pair) in plan.edges.iter().zip(&connecting) {
        if ep.decision != Decision::Bend {
            continue;
        }
        let strip = mesh.corner_face(offset_front[ep.a])?;
        let mut ends = [offset_front[ep.a]; 2];
        for k in 0..2 {
            let s = mesh.subdivide_edge(pair[k])?;
            mesh.set_position(s.vertex, ep.bend[k])?;
            ends[k] = corner_at(mesh, s.vertex, strip)?;
        }
        mesh.insert_edge(ends[0], ends[1])?;
        bent += 1;
    }
    // Step 3b: collapses. A connecting edge that became a self-loop is
    // removed instead (§VII.3 3b), unless both its sides are one face, where
    // deleting it would change the topology.
    let mut collapsed = 0;
    let mut loops_removed = 0;
    for (ep, pair) in plan.edges.iter().zip(&connecting) {
        if ep.decision != Decision::Collapse {
            continue;
        }
        collapsed += 1;
        for &e in pair {
            if mesh.is_self_loop(e)? {
                loops_removed += remove_loop(mesh, e)?;
            } else {
                mesh.collapse_edge(e)?;
            }
        }
    }
    // Kept connecting edges whose ends merged through other collapses.
    for (ep, pair) in plan.edges.iter().zip(&connecting) {
        if ep.decision == Decision::Keep {
            for &e in pair {
                if mesh.is_self_loop(e)? {
                    loops_removed += remove_loop(mesh, e)?;
                }
            }
        }
    }
    // Merged offset corners go to their group's centroid.
    for (g, pos) in plan.merged.iter().enumerate() {
        if let Some(p) = pos
            && mesh.contains_vertex(offset_vertex[g])
        {
            mesh.set_position(offset_vertex[g], *p)?;
        }
    }

    // Vertex faces whose corners coincide (distinct vertices at one point,
    // as where a bend meets collapsed neighbours) are zipped shut.
    let mut zipped = 0;
    // Indexed by the original vertex's slot.
    let mut slots = 0;
    for &c in &plan.corners {
        slots = slots.max(mesh.corner_vertex(c)?.index() + 1);
    }
    let mut done = vec![false; slots];
    let tol_base = LEN_REL * plan.thickness;
    for ((ep, pair), vf) in plan.edges.iter().zip(&connecting).zip(&vertex_face) {
        if ep.decision == Decision::Collapse {
            continue;
        }
        for k in 0..2 {
            let original = if k == 0 { ep.a } else { ep.b };
            let slot = mesh.corner_vertex(plan.corners[original])?.index();
            if done[slot] || !mesh.contains_edge(pair[k]) || !mesh.contains_corner(vf[k]) {
                continue;
            }
            done[slot] = true;
            zipped += zip_face(mesh, vf[k], tol_base)?;
        }
    }

    // Step 4a: trisect the original edges, end segments of length D. The
    // kernel splits from the edge's first end, which is the planned u.
    for ep in &plan.edges {
        let ([x, y], _) = mesh.trisect_edge(ep.id)?;
        mesh.set_position(x, ep.trisect[0])?;
        mesh.set_position(y, ep.trisect[1])?;
    }
    // The middle segment's half-edge in face i starts at the corner after
    // the original corner (which still starts the first end segment).
    let mut middle = Vec::with_capacity(total);
    for &c in &plan.corners {
        middle.push(mesh.corner_next(c)?);
    }
    // Step 4b: ConnectEdges from each middle segment to the inward remeshing
    // face.
    for g in 0..total {
        mesh.connect_edges(middle[g], remesh_back[g])?;
    }

    // Step 5: a pipe from each outward remeshing face to its inward offset
    // face. CreatePipe reads the first face forwards and the second
    // backwards, so p′0 meets p″0, p′1 meets p″1, and so on.
    for i in 0..nf {
        mesh.create_pipe(remesh_front0[i], offset_back0[i])?;
    }

    let two_gons_removed = mesh.remove_two_gons();
    Ok(MengerLevel {
        thickness: plan.thickness,
        angle_cases: plan.angle_cases,
        collapsed_edges: collapsed,
        bent_edges: bent,
        nonconvex_corners: plan.nonconvex_corners,
        winged_corners: plan.winged_corners,
        nonplanar_faces: plan.nonplanar_faces,
        skew_cuts: 0,
        loops_removed,
        zipped_vertices: zipped,
        two_gons_removed,
        vertices: mesh.vertex_count(),
        edges: mesh.edge_count(),
        faces: mesh.face_count(),
    })
}

/// Deletes a zero-length self-loop when its two sides are different faces
/// (the one-cornered remnant of a vertex face and a strip), merging them.
fn remove_loop(mesh: &mut Mesh, e: EdgeId) -> Result<usize, MengerError> {
    let [f1, f2] = mesh.edge_faces(e)?;
    if f1 == f2 {
        return Ok(0);
    }
    mesh.delete_edge(e)?;
    Ok(1)
}

/// Zips the face of corner `start` shut where two of its corners are
/// distinct vertices at the same point: consecutive ones by collapsing the
/// zero-length edge between them, others by inserting an edge between them
/// (splitting the face) and collapsing it. Each step merges two vertices
/// and keeps χ; the slivers left are two-gons, which the level's final
/// cleanup removes. Returns the number of merges.
///
/// Coincidence is tested against `tol_base` (a small fraction of the
/// thickness) plus the rounding error of the coordinates involved.
fn zip_face(mesh: &mut Mesh, start: CornerId, tol_base: f64) -> Result<usize, MengerError> {
    let mut merges = 0;
    let mut work = vec![start];
    while let Some(c0) = work.pop() {
        if !mesh.contains_corner(c0) {
            continue;
        }
        let corners: Vec<CornerId> = mesh.face_corners_from(c0)?.collect();
        let m = corners.len();
        if m < 3 {
            continue;
        }
        let mut pos = Vec::with_capacity(m);
        let mut verts = Vec::with_capacity(m);
        for &c in &corners {
            let v = mesh.corner_vertex(c)?;
            verts.push(v);
            pos.push(mesh.position(v)?);
        }
        let scale = pos
            .iter()
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let tol = tol_base + ANGLE_ULPS * f64::EPSILON * scale;
        let mut found = None;
        'search: for i in 0..m {
            for j in i + 1..m {
                if verts[i] != verts[j] && pos[i].distance(pos[j]) <= tol {
                    found = Some((i, j));
                    break 'search;
                }
            }
        }
        let Some((i, j)) = found else {
            continue;
        };
        if j == i + 1 || (i == 0 && j == m - 1) {
            // Consecutive: the edge between them has no length.
            let from = if j == i + 1 { corners[i] } else { corners[j] };
            let e = mesh.corner_edge(from)?.ok_or_else(|| {
                MengerError::Kernel(holey_dlfl::Error::Invalid("corner without edge".into()))
            })?;
            let keep = mesh.corner_next(from)?;
            mesh.collapse_edge(e)?;
            work.push(keep);
        } else {
            let e = mesh.insert_edge(corners[i], corners[j])?;
            mesh.collapse_edge(e)?;
            work.push(corners[i]);
            work.push(corners[j]);
        }
        merges += 1;
    }
    Ok(merges)
}
