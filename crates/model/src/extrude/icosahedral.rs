//! Icosahedral extrusion (TopMod's `extrudeFaceIcosa`): a dual extrusion,
//! a plain extrusion of its top, deletion of the dual top's edges (which
//! leaves a ring of pentagons) and a stellation of each pentagon, so the
//! walls are triangles only: a regular triangle grows a regular
//! icosahedron.

use holey_dlfl::{DVec3, FaceId, Mesh};

use super::dodecahedral::{GoldenBase, PHI, face_edges};
use super::octahedral::dual_extrude_at;
use super::plain::extrude_to;
use super::stellate::stellate_at;
use super::{ExtrudeError, Extruded, check_rings};

/// Icosahedral extrusion of `face`.
///
/// For a `d`-gon with centroid `c`, unit normal `n`, corners `p_i` and
/// mean circumradius `R`, with `h = height_factor·R` and `m_i` the
/// midpoint direction of edge `i` scaled to the circumradius: the dual
/// ring at `c + φ·m_i + h·n`, the pentagon apexes at
/// `c + φ(p_(i+1) − c) + φh·n`, the top at `c + m_i + φ²h·n`. For a
/// regular triangle and `height_factor = 1` these are the vertices of the
/// regular icosahedron on that face (layers, along a 3-fold axis, at
/// heights `0, R, φR, φ²R` with radii `R, φR, φR, R`).
///
/// Counts: a `d`-gon adds `3d` vertices, `9d` edges and `6d` faces (`d`
/// triangles on the old edges, `5d` around the apexes; the top `d`-gon
/// replaces the base). A triangle of an icosahedron: 12/30/20 → 21/57/38.
pub fn extrude_face_icosahedral(
    mesh: &mut Mesh,
    face: FaceId,
    height_factor: f64,
) -> Result<Extruded, ExtrudeError> {
    let base = GoldenBase::new(mesh, face, height_factor)?;
    let (c, n, h) = (base.centre, base.normal, base.h);
    let points = &base.points;
    let d = points.len();
    let mids = base.turned(PHI, h);
    let apexes: Vec<DVec3> = (0..d)
        .map(|i| c + (points[(i + 1) % d] - c) * PHI + n * (PHI * h))
        .collect();
    let ring = base.top();
    check_rings(face, &[&mids, &apexes, &ring])?;
    let dual = dual_extrude_at(mesh, base.corners[0], &mids)?;
    let dual_top = face_edges(mesh, dual.top)?;
    let last = extrude_to(mesh, dual.top, dual.top_start, &ring)?;
    // Each dual-top edge lies between a corner triangle and a quad of the
    // new ring: deleting it leaves the pentagon
    // (m_i, p_(i+1), m_(i+1), t_(i+1), t_i).
    for e in dual_top {
        mesh.delete_edge(e)?;
    }
    // The pentagon over top edge i (t_i → t_(i+1)) gets the apex i.
    let mut pentagons = Vec::with_capacity(d);
    for corner in mesh.face_corners_from(last.top_start)? {
        let Some(e) = mesh.corner_edge(corner)? else {
            continue;
        };
        let [x, y] = mesh.edge_faces(e)?;
        pentagons.push(if x == last.top { y } else { x });
    }
    let mut vertices = dual.vertices;
    vertices.extend(last.vertices);
    for (&pentagon, &apex) in pentagons.iter().zip(&apexes) {
        let start = mesh.face_corner(pentagon)?;
        vertices.extend(stellate_at(mesh, pentagon, start, apex)?.vertices);
    }
    Extruded::around(mesh, last.top, last.top_start, vertices)
}
