//! # Multi-face handles (TopMod; not in the thesis)
//!
//! [`create_multi_face_handle`] joins `k ≥ 4` faces at once through a
//! common hub: a convex polyhedron with one face turned towards each
//! selected face, each joined to its face by a curved handle
//! ([`super::create_handle`], Hermite or Bézier as the parameters say).
//! The thesis defines only two-face handles; TopMod's multi-face handle
//! builds its hub from the convex hull of the selected faces, and this is
//! that natural reading:
//!
//! 1. `p_i` are the selected faces' centroids, `c` their average, and
//!    `d_i = (p_i − c)/|p_i − c|` the directions from `c` to them.
//! 2. The hub is the dual convex hull ([`crate::hull::dual_convex_hull`])
//!    of the points `c + r·d_i`, `r = hub_scale · min_i |p_i − c|`: the
//!    points lie on one sphere, so each is a corner of their hull and the
//!    dual has exactly one face per selected face, touching the sphere at
//!    `c + r·d_i` and facing along (nearly) `d_i`. Each hub face is paired
//!    with the direction its unit normal is closest to; the pairing must be
//!    one-to-one.
//! 3. The hub is added to the mesh as a new component, then handle `i`
//!    runs from the first corner of selected face `i` to the first corner
//!    of its hub face (the corners' choice sets the twist).
//!
//! The hub's faces face away from `c`, so the construction is meant for
//! faces turned towards a common point outside the surface (say, one face
//! of each of several bodies arranged around a gap, or faces lining the
//! inside of a ring). Where `c` lies inside the solid (faces all around
//! one convex body) the counts and the genus below still hold, and
//! `validate()` stays true, but the hub lies inside the solid and the
//! handles pass through the surface: no weights make that an embedding.
//!
//! ## Counts
//! With a hub of `V_h / E_h / k` (for points in general position
//! `V_h = 2k − 4`, `E_h = 3k − 6`), handle `i` of `s` segments with `N_i`
//! corners per section (the larger of its two faces' sizes when it runs)
//! and `S` vertices inserted by the handles' preprocessing in all:
//! `V' = V + V_h + S + Σ N_i(s − 1)`,
//! `E' = E + E_h + S + Σ N_i(2s − 1)`,
//! `F' = F + k + Σ (N_i s − 2)`.
//! When every selected face has as many corners as its hub face, `S = 0`
//! and `N_i` is that size. Otherwise `S` depends on the order: the
//! handles run in the order of the selection, and a subdivision of a hub
//! edge also adds a corner to the hub face on its other side.
//! The hub joins every component holding a selected face into one; if
//! those are `m` components the genus rises by `k − m` (the first handle
//! into each component joins it, every other one adds a handle).
//!
//! ## Ids
//! Adding the hub rebuilds the mesh from its raw parts, so every id held
//! from before is renumbered (old ones read as stale or as other
//! entities). The report names the hub's faces as they were before their
//! handles consumed them, and each handle's report.
//!
//! ## Refused input (mesh unchanged)
//! Fewer than four faces, a face given twice, hole or point-sphere faces,
//! a centroid at `c`, two faces in one direction from `c`, directions on
//! one plane (their hull is flat), a hub scale that is not finite and
//! positive, a hub whose faces do not pair one-to-one with the
//! directions, and whatever the two-face handle refuses.

use std::collections::HashMap;

use glam::DVec3;
use holey_dlfl::{BuildError, CornerId, FaceId, Mesh, RawMesh};

use super::geometry::{centroid, vector_area};
use super::{HandleError, HandleParams, HandleReport, create_handle};
use crate::hull::{HullError, dual_convex_hull};

/// Why a multi-face handle was refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MultiHandleError {
    /// Fewer than four faces were selected; a hub needs four directions
    /// that span space.
    #[error(
        "a multi-face handle needs at least four faces (got {0}); join two faces with a plain handle"
    )]
    TooFewFaces(usize),
    /// This face was selected twice.
    #[error("face {0} is selected twice")]
    DuplicateFace(FaceId),
    /// A selected face is unusable as a handle's end (a hole, a
    /// point-sphere, a stale id, …).
    #[error(transparent)]
    Face(#[from] HandleError),
    /// [`MultiHandleParams::hub_scale`] is not finite and positive.
    #[error("the hub scale is {0}; it must be finite and positive")]
    BadHubScale(f64),
    /// This face's centroid is the centre of all the centroids, so it has
    /// no direction from the hub.
    #[error(
        "face {0} has its centroid at the centre of the selected faces, so no direction from the hub"
    )]
    AtCentre(FaceId),
    /// Two faces lie in the same direction from the centre; one hub face
    /// cannot serve both.
    #[error("faces {0} and {1} lie in the same direction from the centre of the selected faces")]
    SameDirection(FaceId, FaceId),
    /// The hub could not be built: the directions lie on one plane
    /// ([`HullError::Flat`]) or a numerical failure.
    #[error("the hub could not be built: {0}")]
    Hub(#[from] HullError),
    /// The hub's faces do not pair one-to-one with the directions (a
    /// direction whose plane only grazes the others).
    #[error(
        "the hub has {hub_faces} faces for {faces} selected faces, or they do not pair one-to-one"
    )]
    HubMismatch {
        /// Faces of the hub.
        hub_faces: usize,
        /// Faces selected.
        faces: usize,
    },
    /// Adding the hub to the mesh failed (a kernel bug).
    #[error("internal error adding the hub (please report): {0}")]
    Build(#[from] BuildError),
    /// The two-face handle to the hub failed for selected face `index`.
    #[error("the handle from selected face {index} to the hub failed: {source}")]
    Handle {
        /// Position of the face in the selection.
        index: usize,
        /// Why.
        source: HandleError,
    },
}

/// The parameters of a multi-face handle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiHandleParams {
    /// The parameters of each handle from a selected face to the hub
    /// (segments, weights, curve).
    pub handle: HandleParams,
    /// The hub's size: it touches the sphere about the centre `c` of
    /// radius `hub_scale · min_i |p_i − c|`.
    pub hub_scale: f64,
}

impl MultiHandleParams {
    /// Handles as `handle`, a hub of scale `hub_scale`.
    pub fn new(handle: HandleParams, hub_scale: f64) -> Self {
        MultiHandleParams { handle, hub_scale }
    }
}

/// What [`create_multi_face_handle`] built.
#[derive(Clone, Debug, PartialEq)]
pub struct MultiHandleReport {
    /// The hub's centre `c`.
    pub centre: DVec3,
    /// The hub's vertex, edge and face counts before the handles.
    pub hub_counts: (usize, usize, usize),
    /// Hub face paired with each selected face (ids in the rebuilt mesh,
    /// consumed by the handles).
    pub hub_faces: Vec<FaceId>,
    /// Each handle, in the order of the selection.
    pub handles: Vec<HandleReport>,
}

/// Joins `faces` through a common hub (see the module documentation). On
/// error the mesh is unchanged; on success every earlier id is renumbered.
pub fn create_multi_face_handle(
    mesh: &mut Mesh,
    faces: &[FaceId],
    params: &MultiHandleParams,
) -> Result<MultiHandleReport, MultiHandleError> {
    let k = faces.len();
    if k < 4 {
        return Err(MultiHandleError::TooFewFaces(k));
    }
    for (i, &f) in faces.iter().enumerate() {
        if faces[..i].contains(&f) {
            return Err(MultiHandleError::DuplicateFace(f));
        }
        if mesh.is_point_sphere(f).map_err(HandleError::from)? {
            return Err(HandleError::PointSphere(f).into());
        }
        if mesh.is_hole(f).map_err(HandleError::from)? {
            return Err(HandleError::HoleFace(f).into());
        }
    }
    if !(params.hub_scale.is_finite() && params.hub_scale > 0.0) {
        return Err(MultiHandleError::BadHubScale(params.hub_scale));
    }
    let mut centroids = Vec::with_capacity(k);
    for &f in faces {
        let pts = mesh.face_positions(f).map_err(HandleError::from)?;
        if vector_area(&pts).length() == 0.0 {
            return Err(HandleError::DegenerateFace(f).into());
        }
        centroids.push(centroid(&pts));
    }
    let centre = centroid(&centroids);
    let scale = centroids
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max);
    let mut directions = Vec::with_capacity(k);
    let mut nearest = f64::INFINITY;
    for (&f, &p) in faces.iter().zip(&centroids) {
        let d = p - centre;
        if d.length() <= 1e-12 * scale {
            return Err(MultiHandleError::AtCentre(f));
        }
        nearest = nearest.min(d.length());
        directions.push(d.normalize());
    }
    for i in 0..k {
        for j in 0..i {
            if directions[i].dot(directions[j]) >= 1.0 - 1e-12 {
                return Err(MultiHandleError::SameDirection(faces[j], faces[i]));
            }
        }
    }
    let radius = params.hub_scale * nearest;
    let mut seeds = Mesh::new();
    for d in &directions {
        seeds
            .create_vertex(centre + *d * radius)
            .map_err(HandleError::from)?;
    }
    let hub = dual_convex_hull(&seeds)?;
    let hub_counts = (hub.vertex_count(), hub.edge_count(), hub.face_count());
    // Pair each hub face with the direction its normal is closest to.
    let mismatch = MultiHandleError::HubMismatch {
        hub_faces: hub.face_count(),
        faces: k,
    };
    if hub.face_count() != k {
        return Err(mismatch);
    }
    let mut pairing: Vec<Option<usize>> = vec![None; k];
    for (j, hf) in hub.faces().enumerate() {
        let n = vector_area(&hub.face_positions(hf).map_err(HandleError::from)?);
        let best = directions
            .iter()
            .enumerate()
            .map(|(i, d)| (i, d.dot(n)))
            .fold(None, |acc: Option<(usize, f64)>, (i, x)| match acc {
                Some((_, y)) if y >= x => acc,
                _ => Some((i, x)),
            });
        match best {
            Some((i, _)) if pairing[i].is_none() => pairing[i] = Some(j),
            _ => return Err(mismatch),
        }
    }
    // The selected faces' and hub faces' positions in the rebuilt mesh.
    let slot: Vec<usize> = {
        let order: HashMap<FaceId, usize> = mesh.faces().enumerate().map(|(i, f)| (f, i)).collect();
        faces
            .iter()
            .map(|f| order.get(f).copied().unwrap_or(usize::MAX))
            .collect()
    };
    let before = mesh.face_count();
    let mut joined = Mesh::from_raw(&disjoint_union(&mesh.to_raw(), &hub.to_raw())?)?;
    let mut hub_faces = Vec::with_capacity(k);
    let mut ends = Vec::with_capacity(k);
    for (i, (&s, j)) in slot.iter().zip(&pairing).enumerate() {
        let (Some(f), Some(h)) = (
            joined.face_at(s),
            j.and_then(|j| joined.face_at(before + j)),
        ) else {
            return Err(MultiHandleError::Handle {
                index: i,
                source: HandleError::Kernel(holey_dlfl::Error::Invalid(
                    "internal: a face was lost adding the hub".into(),
                )),
            });
        };
        hub_faces.push(h);
        ends.push((f, h));
    }
    let mut handles = Vec::with_capacity(k);
    for (index, (f, h)) in ends.into_iter().enumerate() {
        let handle = (|| {
            let c1 = joined.face_corner(f)?;
            let c2 = least_twisted(&joined, c1, h)?;
            create_handle(&mut joined, c1, c2, &params.handle)
        })()
        .map_err(|source| MultiHandleError::Handle { index, source })?;
        handles.push(handle);
    }
    *mesh = joined;
    Ok(MultiHandleReport {
        centre,
        hub_counts,
        hub_faces,
        handles,
    })
}

/// The corner of hub face `h` to pair with corner `c1` of a selected
/// face so that the handle turns least: the handle reads the selected
/// face forwards from `c1` and the hub face backwards from the corner
/// chosen (module docs), and the corner chosen is the one whose pairing
/// best lines up the corners' directions from their faces' centroids
/// (largest sum of dot products of the unit offsets). Faces of different
/// sizes keep the hub face's first corner (their corners are matched by
/// the handle's own rule).
fn least_twisted(mesh: &Mesh, c1: CornerId, h: FaceId) -> Result<CornerId, HandleError> {
    let f = mesh.corner_face(c1)?;
    let offsets = |corners: Vec<CornerId>| -> Result<Vec<DVec3>, HandleError> {
        let points = corners
            .iter()
            .map(|&c| mesh.position(mesh.corner_vertex(c)?))
            .collect::<Result<Vec<_>, _>>()?;
        let centroid = points.iter().copied().sum::<DVec3>() / points.len().max(1) as f64;
        Ok(points
            .iter()
            .map(|p| (*p - centroid).normalize_or_zero())
            .collect())
    };
    let selected: Vec<CornerId> = mesh.face_corners_from(c1)?.collect();
    let hub: Vec<CornerId> = mesh.face_corners(h)?.collect();
    let first = mesh.face_corner(h)?;
    if selected.len() != hub.len() || mesh.face_corners(f)?.count() != selected.len() {
        return Ok(first);
    }
    let (p, q) = (offsets(selected)?, offsets(hub.clone())?);
    let d = q.len();
    let score = |r: usize| -> f64 {
        // Selected corner i meets hub corner r − i (backwards from r).
        (0..d).map(|i| p[i].dot(q[(r + d - i) % d])).sum()
    };
    Ok((0..d)
        .max_by(|&a, &b| score(a).total_cmp(&score(b)))
        .map_or(first, |r| hub[r]))
}

/// `a` and `b` side by side: `b`'s vertices, faces, corners and edges
/// numbered after `a`'s.
fn disjoint_union(a: &RawMesh, b: &RawMesh) -> Result<RawMesh, BuildError> {
    let corners = a.face_vertices.len() + b.face_vertices.len();
    let vertices = a.positions.len() + b.positions.len();
    let too_large = |n: usize| (n >= u32::MAX as usize).then_some(BuildError::TooLarge(n));
    if let Some(e) = too_large(corners).or_else(|| too_large(vertices)) {
        return Err(e);
    }
    // Both below u32::MAX, checked above.
    let nv = a.positions.len() as u32;
    let nc = a.face_vertices.len() as u32;
    let mut out = a.clone();
    out.positions.extend_from_slice(&b.positions);
    out.face_offsets
        .extend(b.face_offsets.iter().skip(1).map(|&o| o + nc));
    out.face_vertices
        .extend(b.face_vertices.iter().map(|&v| v + nv));
    if !(a.holes.is_empty() && b.holes.is_empty()) {
        out.holes = (0..a.face_count())
            .map(|f| a.is_hole(f))
            .chain((0..b.face_count()).map(|f| b.is_hole(f)))
            .collect();
    }
    out.edges
        .extend(b.edges.iter().map(|&[x, y]| [x + nc, y + nc]));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::handle::HandleCurve;
    use holey_dlfl::convert::{ImportOptions, to_dlfl};

    /// Copies of the primitive `spec` centred at `centres`, one component each.
    fn copies(spec: &str, centres: &[DVec3]) -> Mesh {
        let one = holey_shapes::parse_primitive(spec).unwrap();
        let mid = centroid(&one.positions);
        let mut soup = one.clone();
        soup.positions.clear();
        soup.face_offsets.truncate(1);
        soup.face_indices.clear();
        for &c in centres {
            let base = soup.positions.len() as u32;
            let shift = soup.face_indices.len() as u32;
            soup.positions
                .extend(one.positions.iter().map(|&p| p - mid + c));
            soup.face_offsets
                .extend(one.face_offsets.iter().skip(1).map(|&o| o + shift));
            soup.face_indices
                .extend(one.face_indices.iter().map(|&i| i + base));
        }
        to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
    }

    /// `@cube`s (side 2) centred at `centres`: one component each, 8 / 12 / 6.
    fn cubes(centres: &[DVec3]) -> Mesh {
        copies("@cube", centres)
    }

    /// The face of `m` whose outward normal is `n` and whose centroid is
    /// within 1 of `near`.
    fn face_towards(m: &Mesh, n: DVec3, near: DVec3) -> FaceId {
        m.faces()
            .find(|&f| {
                let pts = m.face_positions(f).unwrap();
                vector_area(&pts).normalize().dot(n) > 0.999 && centroid(&pts).distance(near) < 1.0
            })
            .unwrap()
    }

    const AXES: [DVec3; 6] = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];

    #[test]
    fn six_cubes_around_a_hub_become_one_sphere() {
        // Six cubes (side 2) on the axes at distance 4, each face turned to the
        // origin selected. The directions are the octahedron's, so the hub
        // is its dual, a cube 8 / 12 / 6, with one quad facing each
        // selected quad: no subdivision. Each handle of s segments between
        // quads adds 4(s − 1) / 4(2s − 1) / 4s − 2. Seven components (six
        // cubes and the hub) joined by six handles: one sphere, genus 0.
        let centres: Vec<DVec3> = AXES.iter().map(|&a| a * 4.0).collect();
        let m0 = cubes(&centres);
        assert_eq!(m0.topology().component_count(), 6);
        let faces: Vec<FaceId> = AXES
            .iter()
            .map(|&a| face_towards(&m0, -a, a * 3.0))
            .collect();
        for curve in HandleCurve::ALL {
            let s = 3;
            let mut m = m0.clone();
            let p = MultiHandleParams::new(HandleParams::new(s, 0.5, 0.5).with_curve(curve), 0.5);
            let r = create_multi_face_handle(&mut m, &faces, &p).unwrap();
            m.validate().unwrap();
            assert_eq!(r.hub_counts, (8, 12, 6));
            assert!(r.centre.length() < 1e-12);
            let k = 6;
            assert_eq!(
                (m.vertex_count(), m.edge_count(), m.face_count()),
                (
                    48 + 8 + k * 4 * (s - 1),
                    72 + 12 + k * 4 * (2 * s - 1),
                    36 + 6 + k * (4 * s - 2)
                ),
                "{curve}"
            );
            assert_eq!(m.topology().component_count(), 1);
            assert_eq!(m.genus(), 0);
            assert_eq!(r.handles.len(), k);
            // Untwisted: the hub's squares face the cubes' squares corner
            // to corner along straight axes, so every quad the handles
            // make is planar (a handle turned by a quarter would skew its
            // sections' sides into twisted quads).
            for f in m.faces() {
                let p = m.face_positions(f).unwrap();
                let n = (p[1] - p[0]).cross(p[2] - p[0]);
                let off = (p[3] - p[0]).dot(n.normalize()).abs();
                assert!(off < 1e-9, "{curve}: a quad {off} off its plane");
            }
        }
    }

    #[test]
    fn six_cubes_already_joined_gain_five_handles() {
        // The six cubes first chained into one sphere by five plain pipes
        // between side faces that are not selected (each pipe between
        // quads: + 0 / + 4 / + 2, joining two components). Then the
        // multi-face handle: the hub (8 / 12 / 6) and six handles between
        // quads; the first joins the hub, each of the other five adds a
        // handle: genus 0 + 6 − 1 = 5.
        let mut m = cubes(&AXES.map(|a| a * 4.0));
        let (x, nx, y, ny, z, nz) = (
            DVec3::X * 4.0,
            DVec3::NEG_X * 4.0,
            DVec3::Y * 4.0,
            DVec3::NEG_Y * 4.0,
            DVec3::Z * 4.0,
            DVec3::NEG_Z * 4.0,
        );
        let pipes = [
            ((DVec3::Y, x), (DVec3::X, y)),
            ((DVec3::NEG_X, y), (DVec3::Y, nx)),
            ((DVec3::NEG_Y, nx), (DVec3::NEG_X, ny)),
            ((DVec3::Z, x), (DVec3::X, z)),
            ((DVec3::NEG_Z, x), (DVec3::X, nz)),
        ];
        for ((n1, at1), (n2, at2)) in pipes {
            let a = face_towards(&m, n1, at1 + n1);
            let b = face_towards(&m, n2, at2 + n2);
            let (ca, cb) = (m.face_corner(a).unwrap(), m.face_corner(b).unwrap());
            create_handle(&mut m, ca, cb, &HandleParams::new(1, 1.0, 1.0)).unwrap();
        }
        m.validate().unwrap();
        let (v, e, f) = (m.vertex_count(), m.edge_count(), m.face_count());
        assert_eq!((v, e, f), (48, 72 + 5 * 4, 36 + 5 * 2));
        assert_eq!((m.topology().component_count(), m.genus()), (1, 0));
        let faces: Vec<FaceId> = AXES
            .iter()
            .map(|&a| face_towards(&m, -a, a * 3.0))
            .collect();
        let (s, k) = (4, 6);
        let p = MultiHandleParams::new(
            HandleParams::new(s, 1.0, 0.5).with_curve(HandleCurve::Bezier),
            0.5,
        );
        let r = create_multi_face_handle(&mut m, &faces, &p).unwrap();
        m.validate().unwrap();
        assert_eq!(r.hub_counts, (8, 12, 6));
        assert_eq!(
            (m.vertex_count(), m.edge_count(), m.face_count()),
            (
                v + 8 + k * 4 * (s - 1),
                e + 12 + k * 4 * (2 * s - 1),
                f + 6 + k * (4 * s - 2)
            )
        );
        assert_eq!((m.topology().component_count(), m.genus()), (1, 5));
        // Each handle's middle ring lies between its cube's face (distance
        // 3 from the centre) and the hub (which touches the sphere of
        // radius ½ · 3 about the centre).
        for h in &r.handles {
            let ring: Vec<DVec3> = h.sections[1]
                .iter()
                .map(|&v| m.position(v).unwrap())
                .collect();
            let d = centroid(&ring).length();
            assert!(d > 1.5 && d < 3.0, "{d}");
        }
    }

    /// Four copies of `spec` towards the corners of a tetrahedron (distance
    /// 4 from the origin), and from each the face whose normal points most
    /// nearly at the origin.
    fn tetrahedral(spec: &str) -> (Mesh, Vec<FaceId>) {
        let corners = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ]
        .map(|d| d.normalize() * 4.0);
        let m = copies(spec, &corners);
        let faces = corners
            .iter()
            .map(|&c| {
                let towards = |f: FaceId| {
                    let pts = m.face_positions(f).unwrap();
                    vector_area(&pts).normalize().dot(-c.normalize())
                };
                m.faces()
                    .filter(|&f| centroid(&m.face_positions(f).unwrap()).distance(c) < 2.0)
                    .fold(None, |best: Option<FaceId>, f| match best {
                        Some(b) if towards(b) >= towards(f) => Some(b),
                        _ => Some(f),
                    })
                    .unwrap()
            })
            .collect();
        (m, faces)
    }

    #[test]
    fn four_octahedra_meet_at_a_tetrahedral_hub() {
        // Four octahedra (6 / 12 / 8) towards the corners of a
        // tetrahedron, from each the triangle facing the origin. Four
        // directions in general position: the hub is a tetrahedron
        // 4 / 6 / 4, whose triangles meet the selected triangles without
        // subdivision; each handle of s segments adds 3(s − 1) / 3(2s − 1)
        // / 3s − 2. Five components, four handles: one sphere, genus 0.
        let (m0, faces) = tetrahedral("@octahedron");
        assert_eq!(
            (m0.vertex_count(), m0.edge_count(), m0.face_count()),
            (24, 48, 32)
        );
        for &f in &faces {
            assert_eq!(m0.face_len(f).unwrap(), 3);
        }
        let (s, k) = (3, 4);
        let mut m = m0.clone();
        let p = MultiHandleParams::new(HandleParams::new(s, 0.5, 0.5), 0.5);
        let r = create_multi_face_handle(&mut m, &faces, &p).unwrap();
        m.validate().unwrap();
        assert_eq!(r.hub_counts, (4, 6, 4));
        assert_eq!(
            (m.vertex_count(), m.edge_count(), m.face_count()),
            (
                24 + 4 + k * 3 * (s - 1),
                48 + 6 + k * 3 * (2 * s - 1),
                32 + 4 + k * (3 * s - 2)
            )
        );
        assert_eq!((m.topology().component_count(), m.genus()), (1, 0));
    }

    #[test]
    fn a_triangular_hub_is_subdivided_to_meet_quads() {
        // Four cubes instead: quads against the tetrahedral hub's
        // triangles. Every hub triangle is brought to four corners before
        // its handle (by its own subdivision or by a neighbour's, which
        // splits a shared edge), so each handle has N = 4; the sum of the
        // subdivisions depends on the order, and whatever it is, the
        // result is one valid sphere with V − E + F = 2.
        let (m0, faces) = tetrahedral("@cube");
        let mut m = m0.clone();
        let p = MultiHandleParams::new(HandleParams::new(3, 0.5, 0.5), 0.5);
        let r = create_multi_face_handle(&mut m, &faces, &p).unwrap();
        m.validate().unwrap();
        assert_eq!(r.hub_counts, (4, 6, 4));
        for h in &r.handles {
            assert_eq!(h.plan.corners, 4);
        }
        assert_eq!((m.topology().component_count(), m.genus()), (1, 0));
        assert_eq!(m.euler_characteristic(), 2);
    }

    #[test]
    fn bad_selections_are_refused_and_leave_the_mesh_unchanged() {
        let m0 = cubes(&AXES.map(|a| a * 4.0));
        let faces: Vec<FaceId> = AXES
            .iter()
            .map(|&a| face_towards(&m0, -a, a * 3.0))
            .collect();
        let ok = MultiHandleParams::new(HandleParams::new(2, 0.5, 0.5), 0.5);
        let refuse = |sel: &[FaceId], p: &MultiHandleParams| {
            let mut m = m0.clone();
            let err = create_multi_face_handle(&mut m, sel, p).unwrap_err();
            assert_eq!(m.to_raw(), m0.to_raw(), "{err}");
            err
        };
        assert_eq!(refuse(&faces[..3], &ok), MultiHandleError::TooFewFaces(3));
        let twice = [faces[0], faces[1], faces[2], faces[0]];
        assert_eq!(
            refuse(&twice, &ok),
            MultiHandleError::DuplicateFace(faces[0])
        );
        // ±x and ±y: four directions in one plane, a flat hull.
        assert!(matches!(
            refuse(&faces[..4], &ok),
            MultiHandleError::Hub(HullError::Flat { .. })
        ));
        for bad in [0.0, -1.0, f64::NAN] {
            assert!(matches!(
                refuse(&faces, &MultiHandleParams::new(ok.handle, bad)),
                MultiHandleError::BadHubScale(_)
            ));
        }
        let zero = MultiHandleParams::new(HandleParams::new(0, 1.0, 1.0), 0.5);
        assert!(matches!(
            refuse(&faces, &zero),
            MultiHandleError::Handle {
                index: 0,
                source: HandleError::NoSegments
            }
        ));
    }
}
