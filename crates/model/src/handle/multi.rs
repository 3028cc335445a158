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
//! 1. `p_i` are the selected faces' centroids and `h` the hub's centre:
//!    a point strictly in front of every selected face and strictly
//!    inside the convex hull of the centroids, chosen by a linear program
//!    and checked exactly ([`super::hub`]; the centroids' average `c`
//!    when it is good enough). `d_i = (p_i − h)/|p_i − h|` are the
//!    directions from `h` to the faces; being inside the centroids' hull
//!    makes them span space positively, so the hub below is bounded.
//! 2. The hub is the dual convex hull ([`crate::hull::dual_convex_hull`])
//!    of the points `h + r·d_i`, `r = hub_scale · min_i |p_i − h|`: the
//!    points lie on one sphere, so each is a corner of their hull and the
//!    dual has exactly one face per selected face, touching the sphere at
//!    `h + r·d_i` and facing along (nearly) `d_i`. Each hub face is paired
//!    with the direction its unit normal is closest to; the pairing must be
//!    one-to-one.
//! 3. The hub is added to the mesh as a new component, then handle `i`
//!    runs from the first corner of selected face `i` to the hub corner
//!    that lines up best with it (the corners' choice sets the twist).
//! 4. The faces made or changed are checked for crossings with the whole
//!    surface and with each other, exactly, as `holey selfint` counts them
//!    ([`super::crossing`]); any crossing refuses the handle.
//!
//! So the result never passes through itself where the input did not.
//! Faces all around one body, each looking outward (TopMod's hub then
//! sits inside the solid and every handle runs through the surface), are
//! refused with [`MultiHandleError::NoCommonView`], naming at most four
//! faces that have no common point in front of them; faces that all look
//! one way (the top of a slab) with [`MultiHandleError::OneSided`]; a face
//! whose straight view of the hub is blocked with
//! [`MultiHandleError::Blocked`]; and handles that would still cross
//! (faces too large for the gap between them, weights too large) with
//! [`MultiHandleError::Crosses`]. The construction is for faces that look
//! at a common point from outside: one face of each of several bodies
//! arranged around a gap, faces lining the inside of a ring, or the
//! faces around a saddle of one body (a cow's horn, ears, neck and back
//! around a point above its head).

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
//! faces with no common point in front or all to one side of every such
//! point, a blocked view of the hub, a centroid at `h`, two faces in one
//! direction from `h`, directions on one plane (their hull is flat), a
//! hub scale that is not finite and positive, a hub whose faces do not
//! pair one-to-one with the directions, whatever the two-face handle
//! refuses, and a result whose new faces cross anything.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use holey_dlfl::{BuildError, CornerId, FaceId, Mesh, RawMesh, VertexId};

use super::crossing::crossings;
use super::geometry::{centroid, vector_area};
use super::hub::{Selection, hub_centre};
use super::multi_error::MultiHandleError;
use super::{HandleError, HandleParams, HandleReport, create_handle};
use crate::hull::dual_convex_hull;

/// The parameters of a multi-face handle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultiHandleParams {
    /// The parameters of each handle from a selected face to the hub
    /// (segments, weights, curve).
    pub handle: HandleParams,
    /// The hub's size: it touches the sphere about its centre `h` of
    /// radius `hub_scale · min_i |p_i − h|`.
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
    /// The hub's centre `h`.
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
    let (joined, report, untouched) = assemble(mesh, faces, params)?;
    check_crossings(&joined, &untouched, faces, &report.handles)?;
    *mesh = joined;
    Ok(report)
}

/// The input's faces (in the rebuilt mesh) with their vertices before the
/// handles ran. A face keeps its id when a pipe reshapes it (the selected
/// face becomes one of the pipe's quadrilaterals) or a subdivision adds a
/// corner, so only the same vertices in the same order count as untouched.
type Untouched = HashMap<FaceId, Vec<VertexId>>;

/// Steps 1–3 of the module docs on a copy of `mesh`: the mesh with the hub
/// and handles, the report, and the input's faces as they were.
fn assemble(
    mesh: &Mesh,
    faces: &[FaceId],
    params: &MultiHandleParams,
) -> Result<(Mesh, MultiHandleReport, Untouched), MultiHandleError> {
    check_selection(mesh, faces, params)?;
    let k = faces.len();
    let mut centroids = Vec::with_capacity(k);
    for &f in faces {
        let pts = mesh.face_positions(f).map_err(HandleError::from)?;
        if vector_area(&pts).length() == 0.0 {
            return Err(HandleError::DegenerateFace(f).into());
        }
        centroids.push(centroid(&pts));
    }
    let selection = Selection {
        faces,
        centroids: &centroids,
    };
    let centre = hub_centre(mesh, &selection)?;
    let directions = directions(faces, &centroids, centre)?;
    let nearest = centroids
        .iter()
        .map(|p| p.distance(centre))
        .fold(f64::INFINITY, f64::min);
    let (hub, pairing) = build_hub(centre, &directions, params.hub_scale * nearest)?;
    let hub_counts = (hub.vertex_count(), hub.edge_count(), hub.face_count());
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
    // Every face of the input as it was, to tell the faces the handles
    // made or changed (subdivided neighbours) from the untouched ones.
    let untouched: Untouched = joined
        .faces()
        .take(before)
        .filter_map(|f| joined.face_vertices(f).ok().map(|v| (f, v)))
        .collect();
    let mut hub_faces = Vec::with_capacity(k);
    let mut ends = Vec::with_capacity(k);
    for (i, (&s, &j)) in slot.iter().zip(&pairing).enumerate() {
        let (Some(f), Some(h)) = (joined.face_at(s), joined.face_at(before + j)) else {
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
    let report = MultiHandleReport {
        centre,
        hub_counts,
        hub_faces,
        handles,
    };
    Ok((joined, report, untouched))
}

/// The refusals that need no geometry: too few faces, duplicates, holes,
/// point-spheres, a bad hub scale.
fn check_selection(
    mesh: &Mesh,
    faces: &[FaceId],
    params: &MultiHandleParams,
) -> Result<(), MultiHandleError> {
    if faces.len() < 4 {
        return Err(MultiHandleError::TooFewFaces(faces.len()));
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
    Ok(())
}

/// The unit directions from `centre` to the centroids, refusing a centroid
/// at the centre and two faces in one direction.
fn directions(
    faces: &[FaceId],
    centroids: &[DVec3],
    centre: DVec3,
) -> Result<Vec<DVec3>, MultiHandleError> {
    let scale = centroids
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max);
    let mut directions = Vec::with_capacity(faces.len());
    for (&f, &p) in faces.iter().zip(centroids) {
        let d = p - centre;
        if d.length() <= 1e-12 * scale {
            return Err(MultiHandleError::AtCentre(f));
        }
        directions.push(d.normalize());
    }
    for i in 0..faces.len() {
        for j in 0..i {
            if directions[i].dot(directions[j]) >= 1.0 - 1e-12 {
                return Err(MultiHandleError::SameDirection(faces[j], faces[i]));
            }
        }
    }
    Ok(directions)
}

/// The hub touching the sphere of `radius` about `centre` in each of
/// `directions` (module docs, step 2), and the hub face paired with each
/// direction (the one whose normal is closest to it, one-to-one).
fn build_hub(
    centre: DVec3,
    directions: &[DVec3],
    radius: f64,
) -> Result<(Mesh, Vec<usize>), MultiHandleError> {
    let k = directions.len();
    let mut seeds = Mesh::new();
    for d in directions {
        seeds
            .create_vertex(centre + *d * radius)
            .map_err(HandleError::from)?;
    }
    let hub = dual_convex_hull(&seeds)?;
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
    let pairing = pairing.into_iter().collect::<Option<Vec<usize>>>();
    Ok((hub, pairing.ok_or(mismatch)?))
}

/// Refuses the result when a face the handles made or changed crosses
/// anything (exactly, as `holey selfint` counts), naming the selected
/// faces whose handles are involved (a handle owns the faces along its
/// pipes' edges; a crossing of the hub alone names every face).
fn check_crossings(
    joined: &Mesh,
    untouched: &Untouched,
    faces: &[FaceId],
    handles: &[HandleReport],
) -> Result<(), MultiHandleError> {
    let made: HashSet<FaceId> = joined
        .faces()
        .filter(|f| untouched.get(f) != joined.face_vertices(*f).ok().as_ref())
        .collect();
    let pairs = crossings(joined, &made)?;
    if pairs.is_empty() {
        return Ok(());
    }
    let mut owner = HashMap::new();
    for (i, h) in handles.iter().enumerate() {
        for e in h.pipes.iter().flatten() {
            for f in joined.edge_faces(*e).into_iter().flatten() {
                owner.entry(f).or_insert(i);
            }
        }
    }
    let mut named: Vec<usize> = pairs
        .iter()
        .flat_map(|(a, b)| [owner.get(a), owner.get(b)])
        .flatten()
        .copied()
        .collect();
    named.sort_unstable();
    named.dedup();
    if named.is_empty() {
        named = (0..faces.len()).collect();
    }
    Err(MultiHandleError::Crosses {
        faces: named.into_iter().map(|i| faces[i]).collect(),
        pairs: pairs.len(),
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
    use crate::hull::HullError;
    use holey_dlfl::convert::{ImportOptions, to_dlfl};
    use holey_mesh::PolyMesh;

    /// Copies of the primitive `spec` centred at `centres`, one component each.
    fn copies(spec: &str, centres: &[DVec3]) -> Mesh {
        let one = holey_shapes::parse_primitive(spec).unwrap();
        let mid = centroid(&one.positions);
        let mut soup = PolyMesh::new();
        for &c in centres {
            soup.append(&one.transformed(|p| p - mid + c));
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

    /// The six unit axis directions.
    fn axes() -> [DVec3; 6] {
        holey_testkit::AXES.map(DVec3::from_array)
    }

    #[test]
    fn six_cubes_around_a_hub_become_one_sphere() {
        // Six cubes (side 2) on the axes at distance 4, each face turned to the
        // origin selected. The directions are the octahedron's, so the hub
        // is its dual, a cube 8 / 12 / 6, with one quad facing each
        // selected quad: no subdivision. Each handle of s segments between
        // quads adds 4(s − 1) / 4(2s − 1) / 4s − 2. Seven components (six
        // cubes and the hub) joined by six handles: one sphere, genus 0.
        let centres: Vec<DVec3> = axes().iter().map(|&a| a * 4.0).collect();
        let m0 = cubes(&centres);
        assert_eq!(m0.topology().component_count(), 6);
        let faces: Vec<FaceId> = axes()
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
        let mut m = cubes(&axes().map(|a| a * 4.0));
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
        let faces: Vec<FaceId> = axes()
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
    fn quads_against_a_triangular_hub_cross_and_are_refused() {
        // Four cubes instead: quads against the tetrahedral hub's
        // triangles. Every hub triangle is brought to four corners before
        // its handle (by its own subdivision or by a neighbour's, which
        // splits a shared edge), so each handle has N = 4 and the result
        // is one valid sphere with V − E + F = 2. But the hub's triangles
        // are large beside the cubes' faces and meet at sharp edges, and
        // the handles leaving neighbouring hub faces run into each other:
        // the topology engine counts crossing pairs in what is built (this
        // was accepted silently before the crossing check), so the handle
        // is refused and the mesh left as it was.
        let (m0, faces) = tetrahedral("@cube");
        let p = MultiHandleParams::new(HandleParams::new(3, 0.5, 0.5), 0.5);
        let (built, r, _) = assemble(&m0, &faces, &p).unwrap();
        built.validate().unwrap();
        assert_eq!(r.hub_counts, (4, 6, 4));
        for h in &r.handles {
            assert_eq!(h.plan.corners, 4);
        }
        assert_eq!((built.topology().component_count(), built.genus()), (1, 0));
        assert_eq!(built.euler_characteristic(), 2);
        let tri = holey_dlfl::convert::to_poly(&built).poly.triangulated();
        let engine = holey_topo::self_intersections(&tri).unwrap().pairs.len();
        assert!(engine > 0);
        let mut m = m0.clone();
        let err = create_multi_face_handle(&mut m, &faces, &p).unwrap_err();
        assert_eq!(m.to_raw(), m0.to_raw());
        assert!(
            matches!(&err, MultiHandleError::Crosses { pairs, .. } if *pairs == engine),
            "{err}; the engine counts {engine}"
        );
    }

    #[test]
    fn bad_selections_are_refused_and_leave_the_mesh_unchanged() {
        let m0 = cubes(&axes().map(|a| a * 4.0));
        let faces: Vec<FaceId> = axes()
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
        // Four copies of one cube, the same face of each: every centroid
        // at one point, so no direction from any hub centre.
        let stacked = cubes(&[DVec3::ZERO; 4]);
        let same: Vec<FaceId> = (0..4).map(|i| stacked.face_at(6 * i).unwrap()).collect();
        let mut m = stacked.clone();
        let err = create_multi_face_handle(&mut m, &same, &ok).unwrap_err();
        assert_eq!(err, MultiHandleError::AtCentre(same[0]));
        assert_eq!(m.to_raw(), stacked.to_raw());
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
