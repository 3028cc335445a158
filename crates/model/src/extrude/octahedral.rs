//! Octahedral ("dual") extrusion (TopMod's `extrudeDualFace`): the new
//! face stands on the midpoints of the old face's edges, joined to it by
//! a band of triangles — one on each old edge and one at each old corner —
//! so a triangle extruded this way grows an octahedron.

use holey_dlfl::{CornerId, DVec3, FaceId, Mesh};

use super::{ExtrudeError, Extruded, check_points, solid_base, turned_ring};

/// Octahedral extrusion of `face`: new vertex `m_i` over the midpoint of
/// edge `i` (from corner `i` to `i + 1`), at the position of a regular
/// octahedron's opposite face when `face` is a regular triangle: the
/// base turned by half a step about its normal (circumradius kept) and
/// lifted by `height_factor · √2 · R`, with `R` the base's mean
/// circumradius (`height_factor` finite and positive; 1 is regular).
///
/// Counts: a `d`-gon adds `d` vertices, `3d` edges and `2d` faces (`2d`
/// triangles; the top `d`-gon replaces the base). A triangle on a
/// tetrahedron: 4/6/4 → 7/15/10.
pub fn extrude_face_octahedral(
    mesh: &mut Mesh,
    face: FaceId,
    height_factor: f64,
) -> Result<Extruded, ExtrudeError> {
    let (corners, points, frame) = solid_base(mesh, face, height_factor)?;
    let lift = height_factor * std::f64::consts::SQRT_2 * frame.radius;
    let mids = turned_ring(&points, frame.centroid, frame.normal, 1.0, lift);
    check_points(face, 0, &mids)?;
    dual_extrude_at(mesh, corners[0], &mids)
}

/// Dual extrusion of a face that passed [`super::base_face`]: `mids[i]`
/// is the new vertex for the edge leaving the `i`-th corner from `start`.
/// `top_start` is the top's corner at `mids[0]`'s vertex.
pub(crate) fn dual_extrude_at(
    mesh: &mut Mesh,
    start: CornerId,
    mids: &[DVec3],
) -> Result<Extruded, ExtrudeError> {
    let ring: Vec<CornerId> = mesh.face_corners_from(start)?.collect();
    let d = ring.len();
    // 1. Hang m_i inside the face on an edge to corner i; the walk reads
    //    … a_i(v_i) → σ_i(m_i) → c_i(v_i) → a_(i+1)(v_(i+1)) …
    let mut vertices = Vec::with_capacity(d);
    let mut sigma = Vec::with_capacity(d);
    let mut before = Vec::with_capacity(d);
    for (i, &c) in ring.iter().enumerate() {
        let (v, _, s) = mesh.create_vertex(mids[i])?;
        mesh.insert_edge(c, s)?;
        vertices.push(v);
        sigma.push(s);
        before.push(mesh.corner_prev(s)?);
    }
    // 2. Cut the triangle (v_i, v_(i+1), m_i) on every old edge; m_i's
    //    corner in what remains is the one just before a_(i+1).
    let mut rest = Vec::with_capacity(d);
    for i in 0..d {
        let next = before[(i + 1) % d];
        mesh.insert_edge(next, sigma[i])?;
        rest.push(mesh.corner_prev(next)?);
    }
    // 3. What remains alternates v_i and m_i: cut the triangle
    //    (v_(i+1), m_(i+1), m_i) at every old corner; the m's are left.
    close_ring(mesh, &mut rest)?;
    let top = mesh.corner_face(rest[0])?;
    Extruded::around(mesh, top, rest[0], vertices)
}

/// Given corners `r_0 … r_(n−1)` of one face in walk order, with one
/// corner between consecutive ones, cuts each in-between corner off with
/// an edge `r_i – r_(i+1)`, leaving the face `r_0 … r_(n−1)`. `r` is
/// updated to the corners of that face.
pub(crate) fn close_ring(mesh: &mut Mesh, r: &mut [CornerId]) -> Result<(), ExtrudeError> {
    let n = r.len();
    for i in 0..n {
        let j = (i + 1) % n;
        mesh.insert_edge(r[j], r[i])?;
        r[i] = mesh.corner_prev(r[j])?;
    }
    Ok(())
}
