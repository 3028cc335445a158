//! Dodecahedral extrusion (TopMod's `extrudeFaceDodeca`): a plain
//! extrusion, a dual extrusion of its top and a plain extrusion of that,
//! after which the edges of the two intermediate tops are deleted, so the
//! walls are two rings of pentagons: a regular pentagon grows a regular
//! dodecahedron.

use holey_dlfl::{CornerId, DVec3, EdgeId, FaceId, Mesh};

use super::octahedral::dual_extrude_at;
use super::plain::extrude_to;
use super::{ExtrudeError, Extruded, check_rings, solid_base, turned_ring};

/// The golden ratio.
pub(crate) const PHI: f64 = 1.618_033_988_749_895;

/// The base face of a golden extrusion (dodecahedral or icosahedral) and
/// what both place their rings by: the layers of either solid stand at
/// heights `0, h, φh, φ²h` over the base (`h = height_factor·R`, `R` the
/// base's mean circumradius) and both end in the same top, the base
/// turned half a step at height `φ²h`.
pub(crate) struct GoldenBase {
    /// The base's corners from [`Mesh::face_corner`].
    pub corners: Vec<CornerId>,
    /// Their positions.
    pub points: Vec<DVec3>,
    /// The base's centroid.
    pub centre: DVec3,
    /// The base's unit normal.
    pub normal: DVec3,
    /// The height step `h`.
    pub h: f64,
}

impl GoldenBase {
    /// The checked base `face` for `height_factor` (see [`solid_base`]).
    pub fn new(mesh: &Mesh, face: FaceId, height_factor: f64) -> Result<Self, ExtrudeError> {
        let (corners, points, frame) = solid_base(mesh, face, height_factor)?;
        Ok(GoldenBase {
            corners,
            points,
            centre: frame.centroid,
            normal: frame.normal,
            h: height_factor * frame.radius,
        })
    }

    /// The base turned half a step, scaled by `scale` about the centre and
    /// lifted by `height` (see [`turned_ring`]).
    pub fn turned(&self, scale: f64, height: f64) -> Vec<DVec3> {
        turned_ring(&self.points, self.centre, self.normal, scale, height)
    }

    /// The top both solids end in: the base turned half a step, at `φ²h`.
    pub fn top(&self) -> Vec<DVec3> {
        self.turned(1.0, PHI * PHI * self.h)
    }
}

/// Dodecahedral extrusion of `face`.
///
/// For a `d`-gon with centroid `c`, unit normal `n`, corners `p_i` and
/// mean circumradius `R`, with `h = height_factor·R`: ring 1 at
/// `c + φ(p_i − c) + h·n`; ring 2 over the edge midpoints at
/// `c + φ·m_i + φh·n`; the top at `c + m_i + φ²h·n`, where `m_i` is the
/// midpoint direction of edge `i` scaled to the circumradius (the corner
/// of the base turned half a step). For a regular pentagon and
/// `height_factor = 1` these are the vertices of the regular dodecahedron
/// on that face (its layers, seen along a 5-fold axis, lie at heights
/// `0, R, φR, φ²R` with radii `R, φR, φR, R`).
///
/// Counts: a `d`-gon adds `3d` vertices, `5d` edges and `2d` faces (two
/// rings of `d` pentagons; the top `d`-gon replaces the base). A pentagon
/// of a dodecahedron: 20/30/12 → 35/55/22.
pub fn extrude_face_dodecahedral(
    mesh: &mut Mesh,
    face: FaceId,
    height_factor: f64,
) -> Result<Extruded, ExtrudeError> {
    let base = GoldenBase::new(mesh, face, height_factor)?;
    let (c, n, h) = (base.centre, base.normal, base.h);
    let ring1: Vec<DVec3> = base
        .points
        .iter()
        .map(|&p| c + (p - c) * PHI + n * h)
        .collect();
    let mids = base.turned(PHI, PHI * h);
    let ring3 = base.top();
    check_rings(face, &[&ring1, &mids, &ring3])?;
    let first = extrude_to(mesh, face, base.corners[0], &ring1)?;
    let first_top = face_edges(mesh, first.top)?;
    let second = dual_extrude_at(mesh, first.top_start, &mids)?;
    // Each old top edge lies between a quad of ring 1 and the triangle on
    // that edge: deleting it makes the lower pentagons.
    for e in first_top {
        mesh.delete_edge(e)?;
    }
    let second_top = face_edges(mesh, second.top)?;
    let third = extrude_to(mesh, second.top, second.top_start, &ring3)?;
    // Each edge of the dual top lies between a corner triangle and a quad
    // of the last ring: deleting it makes the upper pentagons.
    for e in second_top {
        mesh.delete_edge(e)?;
    }
    let mut vertices = first.vertices;
    vertices.extend(second.vertices);
    vertices.extend(third.vertices);
    Extruded::around(mesh, third.top, third.top_start, vertices)
}

/// The edges of a face in walk order.
pub(crate) fn face_edges(mesh: &Mesh, face: FaceId) -> Result<Vec<EdgeId>, ExtrudeError> {
    let mut edges = Vec::new();
    for c in mesh.face_corners(face)? {
        if let Some(e) = mesh.corner_edge(c)? {
            edges.push(e);
        }
    }
    Ok(edges)
}
