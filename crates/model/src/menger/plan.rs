//! The geometric half of one level of §VII.3: every position, decision and
//! check, computed from the mesh before anything changes.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use holey_dlfl::{CornerId, DVec3, EdgeId, FaceId, Mesh};
use holey_mesh::UnionFind;

use super::{MengerError, Thickness};

/// Angle tolerance in units of the machine epsilon; see [`angle_tol`].
pub(crate) const ANGLE_ULPS: f64 = 256.0;
/// Areas (and dot products of edge vectors) below this fraction of the
/// face's squared size count as zero or negative.
pub(crate) const AREA_REL: f64 = 1e-12;
/// A length below this fraction of its reference length counts as zero.
pub(crate) const LEN_REL: f64 = 1e-9;
/// A face off its mean plane by more than this fraction of its size is
/// reported as non-planar.
const PLANAR_REL: f64 = 1e-9;

/// The tolerance for an angle between directions of length `length`
/// computed from positions of magnitude up to `scale`: rounding a position
/// by `ε·scale` turns a direction by about `ε·scale/length` radians.
pub(crate) fn angle_tol(scale: f64, length: f64) -> f64 {
    ANGLE_ULPS * f64::EPSILON * (1.0 + scale / length)
}

/// What happens to the two connecting edges of an original edge (§VII.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Decision {
    Collapse,
    Keep,
    /// Keep, and insert the figure-61 vertices (cases 5 and 6).
    Bend,
}

pub(crate) struct FacePlan {
    pub id: FaceId,
    /// First global corner index of the face.
    pub start: usize,
    pub len: usize,
}

pub(crate) struct EdgePlan {
    pub id: EdgeId,
    /// Global corner of the first side (`edge_corners[0]`), which starts the
    /// edge u → v in its face.
    pub a: usize,
    /// Global corner of the second side, which starts v → u.
    pub b: usize,
    pub decision: Decision,
    /// Figure-61 vertices at the u and v ends (for [`Decision::Bend`]).
    pub bend: [DVec3; 2],
    /// The trisection points, at distance D from u and from v.
    pub trisect: [DVec3; 2],
}

/// Everything one level needs. A *global corner* is a position in the
/// concatenation of all faces' corner lists (face order = slot order).
pub(crate) struct Plan {
    pub thickness: f64,
    pub faces: Vec<FacePlan>,
    /// Original corner per global corner: corner j of its face, which starts
    /// the edge p_j → p_j+1.
    pub corners: Vec<CornerId>,
    pub face_of: Vec<u32>,
    /// Remeshing face points p′ per global corner.
    pub remesh: Vec<DVec3>,
    /// Offset face points p″ per global corner, before merging.
    pub offset: Vec<DVec3>,
    /// Final offset position per global corner after collapses (the
    /// centroid of its merge group), and whether it was merged at all.
    pub merged: Vec<Option<DVec3>>,
    pub edges: Vec<EdgePlan>,
    pub angle_cases: [usize; 6],
    pub nonconvex_corners: usize,
    pub winged_corners: usize,
    pub nonplanar_faces: usize,
}

impl Plan {
    /// The global corner after `g` in its face.
    pub fn next(&self, g: usize) -> usize {
        let f = &self.faces[self.face_of[g] as usize];
        f.start + (g - f.start + 1) % f.len
    }

    /// Plans one level on `mesh`, or explains why it cannot run.
    pub fn new(
        mesh: &Mesh,
        thickness: Thickness,
        collapse_below: f64,
        level: usize,
    ) -> Result<Plan, MengerError> {
        mesh.require_closed()
            .map_err(|holes| MengerError::OpenSurface { holes })?;
        if mesh.face_count() == 0 {
            return Err(MengerError::Empty);
        }
        let d = match thickness {
            Thickness::Absolute(d) => d,
            Thickness::RatioOfMeanEdge(r) => r * mean_edge_length(mesh)?,
        };
        if !(d.is_finite() && d > 0.0) {
            return Err(MengerError::InvalidThickness { value: d });
        }
        let mut plan = Plan {
            thickness: d,
            faces: Vec::with_capacity(mesh.face_count()),
            corners: Vec::with_capacity(mesh.corner_count()),
            face_of: Vec::with_capacity(mesh.corner_count()),
            remesh: Vec::with_capacity(mesh.corner_count()),
            offset: Vec::with_capacity(mesh.corner_count()),
            merged: Vec::new(),
            edges: Vec::with_capacity(mesh.edge_count()),
            angle_cases: [0; 6],
            nonconvex_corners: 0,
            winged_corners: 0,
            nonplanar_faces: 0,
        };
        let mut positions: Vec<DVec3> = Vec::with_capacity(mesh.corner_count());
        let mut normals: Vec<DVec3> = Vec::with_capacity(mesh.face_count());
        for f in mesh.faces() {
            let len = mesh.face_len(f)?;
            if len < 3 {
                return Err(MengerError::ShortFace { face: f, len });
            }
            let start = plan.corners.len();
            for c in mesh.face_corners(f)? {
                match mesh.corner_edge(c)? {
                    Some(e) if mesh.is_self_loop(e)? => {
                        return Err(MengerError::SelfLoop { edge: e });
                    }
                    Some(_) => {}
                    None => return Err(MengerError::ShortFace { face: f, len }),
                }
                plan.corners.push(c);
                plan.face_of.push(plan.faces.len() as u32);
                positions.push(mesh.position(mesh.corner_vertex(c)?)?);
            }
            let normal = plan.face_geometry(f, &positions[start..], d, level)?;
            normals.push(normal);
            plan.faces.push(FacePlan { id: f, start, len });
        }
        // Dense map from corner slot to global corner.
        let slots = plan
            .corners
            .iter()
            .map(|c| c.index() + 1)
            .max()
            .unwrap_or(0);
        let mut global = vec![u32::MAX; slots];
        for (g, c) in plan.corners.iter().enumerate() {
            global[c.index()] = g as u32;
        }
        let find = |c: CornerId| -> Result<usize, MengerError> {
            match global.get(c.index()) {
                Some(&g) if g != u32::MAX => Ok(g as usize),
                _ => Err(MengerError::Kernel(holey_dlfl::Error::Invalid(format!(
                    "corner {c} of an edge is in no face"
                )))),
            }
        };
        // Edges: sides, dihedral angle, decision, trisection.
        let mut sets = UnionFind::new(plan.corners.len());
        for e in mesh.edges() {
            let [ca, cb] = mesh.edge_corners(e)?;
            let (a, b) = (find(ca)?, find(cb)?);
            let (fa, fb) = (plan.face_of[a] as usize, plan.face_of[b] as usize);
            if fa == fb {
                return Err(MengerError::SameFaceBothSides {
                    edge: e,
                    face: plan.faces[fa].id,
                });
            }
            let (u, v) = (positions[a], positions[b]);
            let length = u.distance(v);
            if length <= 0.0 {
                return Err(MengerError::DegenerateEdge {
                    edge: e,
                    reason: "its ends coincide".into(),
                });
            }
            let t = (v - u) / length;
            let (n1, n2) = (normals[fa], normals[fb]);
            let phi = interior_angle(t, n1, n2);
            let tol = angle_tol(u.abs().max_element().max(v.abs().max_element()), length);
            let (case, decision) = classify(phi, tol, collapse_below);
            plan.angle_cases[case - 1] += 1;
            if decision == Decision::Collapse {
                // The connecting edge at u joins f1's corner at u (a) and
                // f2's corner at u (the one after b); at v, next(a) and b.
                sets.union(a as u32, plan.next(b) as u32);
                sets.union(plan.next(a) as u32, b as u32);
            }
            plan.edges.push(EdgePlan {
                id: e,
                a,
                b,
                decision,
                bend: [DVec3::ZERO; 2],
                trisect: [u + d * t, v - d * t],
            });
        }
        plan.merge_groups(&mut sets);
        plan.check_offsets(&positions, level)?;
        // Figure-61 vertices, now that the merged offset corners are known.
        for k in 0..plan.edges.len() {
            if plan.edges[k].decision != Decision::Bend {
                continue;
            }
            let ep = &plan.edges[k];
            let (a, b) = (ep.a, ep.b);
            let (fa, fb) = (plan.face_of[a] as usize, plan.face_of[b] as usize);
            let (n1, n2) = (normals[fa], normals[fb]);
            let denom = 1.0 + n1.dot(n2);
            if denom <= LEN_REL {
                return Err(MengerError::DegenerateEdge {
                    edge: ep.id,
                    reason: "its two faces fold back onto each other".into(),
                });
            }
            let (u, v) = (positions[a], positions[b]);
            let t = (v - u).normalize();
            let ends = [
                (u, plan.final_offset(a), plan.final_offset(plan.next(b))),
                (v, plan.final_offset(plan.next(a)), plan.final_offset(b)),
            ];
            let mut bend = [DVec3::ZERO; 2];
            for (slot, (p, q1, q2)) in bend.iter_mut().zip(ends) {
                // At distance D behind both face planes through p...
                let x0 = p - d * (n1 + n2) / denom;
                // ...slid along the edge to the middle of the strip's end.
                let mid = (q1 + q2) * 0.5;
                *slot = x0 + t * (mid - x0).dot(t);
            }
            plan.edges[k].bend = bend;
        }
        Ok(plan)
    }

    /// The offset position of a global corner after merging.
    pub fn final_offset(&self, g: usize) -> DVec3 {
        self.merged[g].unwrap_or(self.offset[g])
    }

    /// Normal, corner classification, remeshing and offset points of one
    /// face, and the per-face thickness checks. Returns the unit normal.
    fn face_geometry(
        &mut self,
        f: FaceId,
        p: &[DVec3],
        d: f64,
        level: usize,
    ) -> Result<DVec3, MengerError> {
        let n = p.len();
        let centroid = p.iter().copied().sum::<DVec3>() / n as f64;
        let newell: DVec3 = (0..n)
            .map(|j| (p[j] - centroid).cross(p[(j + 1) % n] - centroid))
            .sum();
        let lengths: Vec<f64> = (0..n).map(|j| p[j].distance(p[(j + 1) % n])).collect();
        let size = lengths.iter().copied().fold(0.0, f64::max);
        let scale = p.iter().map(|q| q.abs().max_element()).fold(0.0, f64::max);
        if let Some(j) = lengths.iter().position(|&l| l <= LEN_REL * size) {
            return Err(MengerError::DegenerateFace {
                face: f,
                reason: format!("its edge {j} has zero length"),
            });
        }
        if newell.length() <= 2.0 * AREA_REL * size * size {
            return Err(MengerError::DegenerateFace {
                face: f,
                reason: "it has no area, so no normal".into(),
            });
        }
        let normal = newell.normalize();
        if p.iter()
            .any(|q| (*q - centroid).dot(normal).abs() > PLANAR_REL * size)
        {
            self.nonplanar_faces += 1;
        }
        let too_large = |reason: String| MengerError::ThicknessTooLarge {
            face: f,
            level,
            thickness: d,
            reason,
        };
        for (j, &l) in lengths.iter().enumerate() {
            if l - 2.0 * d <= LEN_REL * l {
                return Err(too_large(format!(
                    "its edge {j} is {l} long, not more than twice the thickness"
                )));
            }
        }
        // Unit vectors towards the next (e1) and previous (e2) corner.
        let e1: Vec<DVec3> = (0..n)
            .map(|j| (p[(j + 1) % n] - p[j]) / lengths[j])
            .collect();
        let e2 = |j: usize| -e1[(j + n - 1) % n];
        let mut remesh = Vec::with_capacity(n);
        for j in 0..n {
            let (a, b) = (e1[j], e2(j));
            let theta = {
                let t = a.cross(b).dot(normal).atan2(a.dot(b));
                if t < 0.0 { t + TAU } else { t }
            };
            let tol = angle_tol(scale, lengths[j].min(lengths[(j + n - 1) % n]));
            if theta <= tol || theta >= TAU - tol {
                return Err(MengerError::DegenerateFace {
                    face: f,
                    reason: format!("its corner {j} folds back on itself (a 0° or 360° angle)"),
                });
            }
            let q = if (theta - PI).abs() <= tol {
                // Winged corner (§VII.5.3): e1 + e2 vanishes; n × e1 points
                // into the face.
                self.winged_corners += 1;
                p[j] + d * normal.cross(a)
            } else if theta > PI {
                // Non-convex corner (§VII.5.2): e1 + e2 points out of the face.
                self.nonconvex_corners += 1;
                p[j] - d * (a + b)
            } else {
                p[j] + d * (a + b)
            };
            remesh.push(q);
        }
        // The remeshed face: corner quads (Y_j−1, p_j, X_j, p′_j), edge quads
        // (X_j, Y_j, p′_j+1, p′_j) and the remeshing face must all keep a
        // positive area, and the remeshing edges their direction.
        let area_min = AREA_REL * size * size;
        for j in 0..n {
            let k = (j + 1) % n;
            let x_j = p[j] + d * e1[j];
            let y_j = p[k] - d * e1[j];
            let y_prev = p[j] + d * e2(j);
            if (remesh[k] - remesh[j]).dot(p[k] - p[j]) <= AREA_REL * lengths[j] * lengths[j] {
                return Err(too_large(format!(
                    "its remeshing face's edge {j} would be reversed or vanish"
                )));
            }
            if signed_area(&[y_prev, p[j], x_j, remesh[j]], normal) <= area_min {
                return Err(too_large(format!(
                    "its corner quadrilateral {j} would invert"
                )));
            }
            if signed_area(&[x_j, y_j, remesh[k], remesh[j]], normal) <= area_min {
                return Err(too_large(format!(
                    "its edge quadrilateral {j} would invert"
                )));
            }
        }
        if signed_area(&remesh, normal) <= area_min {
            return Err(too_large("its remeshing face would invert".into()));
        }
        for q in &remesh {
            self.remesh.push(*q);
            self.offset.push(*q - d * normal);
        }
        Ok(normal)
    }

    /// Centroids of the merge groups of offset corners.
    fn merge_groups(&mut self, sets: &mut UnionFind) {
        let total = sets.len();
        let mut sum = vec![DVec3::ZERO; total];
        let mut count = vec![0u32; total];
        for g in 0..total {
            let r = sets.find(g as u32) as usize;
            sum[r] += self.offset[g];
            count[r] += 1;
        }
        self.merged = (0..total)
            .map(|g| {
                let r = sets.find(g as u32) as usize;
                (count[r] > 1).then(|| sum[r] / f64::from(count[r]))
            })
            .collect();
    }

    /// Every offset face, with its merged corners, must keep the direction
    /// of each edge and a positive area: otherwise the inner surface turns
    /// inside out there.
    fn check_offsets(&self, positions: &[DVec3], level: usize) -> Result<(), MengerError> {
        for face in &self.faces {
            let g0 = face.start;
            let n = face.len;
            let q: Vec<DVec3> = (g0..g0 + n).map(|g| self.final_offset(g)).collect();
            let p = &positions[g0..g0 + n];
            let size = (0..n)
                .map(|j| p[j].distance(p[(j + 1) % n]))
                .fold(0.0, f64::max);
            let normal = {
                let c = p.iter().copied().sum::<DVec3>() / n as f64;
                (0..n)
                    .map(|j| (p[j] - c).cross(p[(j + 1) % n] - c))
                    .sum::<DVec3>()
                    .normalize()
            };
            let too_large = |reason: String| MengerError::ThicknessTooLarge {
                face: face.id,
                level,
                thickness: self.thickness,
                reason,
            };
            for j in 0..n {
                let k = (j + 1) % n;
                let l2 = p[j].distance_squared(p[k]);
                if (q[k] - q[j]).dot(p[k] - p[j]) <= AREA_REL * l2 {
                    return Err(too_large(format!(
                        "its offset face's edge {j} would be reversed or vanish once the offset corners merge"
                    )));
                }
            }
            if signed_area(&q, normal) <= AREA_REL * size * size {
                return Err(too_large("its offset face would invert".into()));
            }
        }
        Ok(())
    }
}

/// Mean length of the mesh's edges.
fn mean_edge_length(mesh: &Mesh) -> Result<f64, MengerError> {
    let mut sum = 0.0;
    let mut count = 0usize;
    for e in mesh.edges() {
        let [u, v] = mesh.edge_vertices(e)?;
        sum += mesh.position(u)?.distance(mesh.position(v)?);
        count += 1;
    }
    if count == 0 {
        return Err(MengerError::Empty);
    }
    Ok(sum / count as f64)
}

/// The interior dihedral angle φ ∈ [0, 2π) of an edge with direction `t`
/// (as its first face walks it) between faces with outward normals `n1`
/// (first face) and `n2`. The normals are first projected perpendicular to
/// the edge, which makes the angle exact for planar faces and a fair
/// average for skewed ones.
pub(crate) fn interior_angle(t: DVec3, n1: DVec3, n2: DVec3) -> f64 {
    let project = |n: DVec3| {
        let m = n - t * n.dot(t);
        if m.length_squared() > 1e-12 {
            m.normalize()
        } else {
            n
        }
    };
    let (m1, m2) = (project(n1), project(n2));
    // ψ is the signed turn of the normal from the first face to the second,
    // positive when the surface bends away from its outside (convex).
    let psi = t.dot(m1.cross(m2)).atan2(m1.dot(m2));
    PI - psi
}

/// The case of §VII.4 (1–6) and the decision for an interior angle `phi`.
pub(crate) fn classify(phi: f64, tol: f64, collapse_below: f64) -> (usize, Decision) {
    let (right, straight, three_right) = (FRAC_PI_2, PI, 3.0 * FRAC_PI_2);
    if phi < right - tol {
        (1, Decision::Collapse)
    } else if phi <= right + tol {
        (2, Decision::Collapse)
    } else if phi < straight - tol {
        if phi < collapse_below {
            (3, Decision::Collapse)
        } else {
            (3, Decision::Keep)
        }
    } else if phi <= straight + tol {
        (4, Decision::Keep)
    } else if phi < three_right - tol {
        (5, Decision::Bend)
    } else {
        (6, Decision::Bend)
    }
}

/// The area of a polygon projected along the unit `normal`, positive when it
/// turns counter-clockwise about it.
pub(crate) fn signed_area(q: &[DVec3], normal: DVec3) -> f64 {
    let n = q.len();
    let mut s = DVec3::ZERO;
    for j in 1..n.saturating_sub(1) {
        s += (q[j] - q[0]).cross(q[j + 1] - q[0]);
    }
    0.5 * s.dot(normal)
}
