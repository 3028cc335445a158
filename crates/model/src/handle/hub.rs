//! # Where a multi-face handle's hub goes
//!
//! A handle leaves face `i` along its normal `n̂_i` from its centroid
//! `p_i` and must reach the hub from outside the surface, so the hub's
//! centre `h` must lie **in front of every selected face** (`n̂_i · (h −
//! p_i) > 0`), and the hub, which has one face turned towards each
//! selected face, is bounded only if the directions `d_i = p_i − h`
//! positively span space: `h` **strictly inside the convex hull of the
//! centroids** (`h = Σ λ_i p_i`, every `λ_i > 0`, `Σ λ_i = 1`). Faces all
//! around one body, each looking outward, have no such point: their
//! average lies inside the body, and a hub there sends every handle
//! through the surface (TopMod builds it anyway).
//!
//! Both conditions are linear in `(λ, t)`, so the centre is chosen by a
//! linear program ([`super::simplex`]) on the centroids scaled to the
//! selection's radius `L = max_i |p_i − c|` about their average `c`:
//!
//! ```text
//!   maximize t  subject to  n̂_i · (Σ_j λ_j p_j − p_i) ≥ t L,
//!                           λ_i ≥ t / k,   Σ λ_j = 1,   0 ≤ t ≤ 1,
//! ```
//!
//! which asks for room in front of every face and for every face to pull
//! on the hub (at `c`, `λ_i = 1/k`, the second margin is 1). The average
//! `c` itself is kept when its margin is at least half the optimum: it is
//! the balanced centre, and the optimum of a linear program sits at a
//! corner of the feasible region, often lopsided.
//!
//! The program is floating point; what it proposes is then decided
//! exactly ([`holey_geom::orient3d`]): `h` must lie strictly in front of
//! every fan triangle of every selected face, and the straight segment
//! from each centroid to `h` must cross no other face
//! ([`holey_geom::segment_triangle_intersect`], in the perturbed world of
//! simulation of simplicity). After the handles are built the caller
//! counts exact crossings of the new faces as the final word.
//!
//! When no centre exists, the refusal names faces: by Helly's theorem a
//! set of half-spaces of `R³` with empty intersection has an empty
//! sub-family of at most four, found by dropping faces one at a time while
//! the rest still has no common point in front (looked for within four
//! selection radii of `c`, where a hub is of any use).

use glam::DVec3;
use holey_dlfl::{FaceId, Mesh};
use holey_geom::{Aabb, Sign, SymPoint, orient3d, position_classes, segment_triangle_intersect};

use super::crossing::{CrossingError, Surface};
use super::multi_error::MultiHandleError;
use super::simplex::{Lp, maximize};

/// Margins (in units of `L`) below this count as none: a hub that close
/// to a face's plane is useless, and the program's rounding is far below.
const TINY: f64 = 1e-6;

/// How far from `c`, in selection radii, a common point in front of the
/// faces is looked for when naming the faces that have none.
const REACH: f64 = 4.0;

/// The selected faces and their centroids.
pub(super) struct Selection<'a> {
    pub faces: &'a [FaceId],
    pub centroids: &'a [DVec3],
}

/// The plane of one fan triangle of selected face `face` (an index into
/// the selection), through `point` with unit normal `normal`. A face that
/// is not planar has several, and the hub must be in front of them all.
struct Plane {
    face: usize,
    normal: DVec3,
    point: DVec3,
}

impl Selection<'_> {
    fn len(&self) -> usize {
        self.faces.len()
    }

    /// The planes of the selected faces' fan triangles, scaled about `c`
    /// by `1/l` (triangles without area have no plane and are skipped).
    fn planes(&self, mesh: &Mesh, c: DVec3, l: f64) -> Result<Vec<Plane>, MultiHandleError> {
        let mut planes = Vec::new();
        for (face, &f) in self.faces.iter().enumerate() {
            let p = mesh
                .face_positions(f)
                .map_err(|e| MultiHandleError::Check(CrossingError::Kernel(e)))?;
            for j in 1..p.len().saturating_sub(1) {
                let n = (p[j] - p[0]).cross(p[j + 1] - p[0]);
                if n.length() > 0.0 {
                    planes.push(Plane {
                        face,
                        normal: n.normalize(),
                        point: (p[0] - c) / l,
                    });
                }
            }
        }
        Ok(planes)
    }

    /// The centroids' average `c` and radius `L` about it.
    fn frame(&self) -> (DVec3, f64) {
        let c = self.centroids.iter().copied().sum::<DVec3>() / self.len() as f64;
        let l = self
            .centroids
            .iter()
            .map(|p| p.distance(c))
            .fold(0.0, f64::max);
        (c, l)
    }
}

/// The hub's centre for `sel` (module docs), or the refusal naming the
/// faces that have no common point to look at.
pub(super) fn hub_centre(mesh: &Mesh, sel: &Selection<'_>) -> Result<DVec3, MultiHandleError> {
    let k = sel.len();
    let (c, l) = sel.frame();
    if !(l > 0.0 && l.is_finite()) {
        // Every centroid at one point: no face has a direction from it.
        return Err(MultiHandleError::AtCentre(sel.faces[0]));
    }
    let q: Vec<DVec3> = sel.centroids.iter().map(|&p| (p - c) / l).collect();
    let planes = sel.planes(mesh, c, l)?;
    let Some((h_lp, t_lp)) = surrounded_view(&planes, &q) else {
        let all: Vec<usize> = (0..k).collect();
        if !common_view(&planes, &all) {
            let named = minimal_blind_set(&planes, all);
            return Err(MultiHandleError::NoCommonView(
                named.iter().map(|&i| sel.faces[i]).collect(),
            ));
        }
        return Err(MultiHandleError::OneSided(sel.faces.to_vec()));
    };
    // At c (the origin of the scaled frame) every λ_i is 1/k.
    let t_c = planes
        .iter()
        .map(|p| -p.normal.dot(p.point))
        .fold(1.0, f64::min);
    let mut candidates = vec![c + h_lp * l];
    if t_c >= 0.5 * t_lp {
        candidates.insert(0, c);
    }
    let mut blind = Vec::new();
    for &h in &candidates {
        blind = blind_faces(mesh, sel.faces, h)?;
        if blind.is_empty() {
            sightlines(mesh, sel, h)?;
            return Ok(h);
        }
    }
    Err(MultiHandleError::Blind {
        faces: blind,
        hub: candidates[candidates.len() - 1],
    })
}

/// The best centre (scaled about `c`) with faces all around it and its
/// margin `t`, if positive.
fn surrounded_view(planes: &[Plane], q: &[DVec3]) -> Option<(DVec3, f64)> {
    let k = q.len();
    // Variables λ_0 … λ_{k−1}, t.
    let mut a = Vec::with_capacity(planes.len() + k + 3);
    let mut b = Vec::with_capacity(planes.len() + k + 3);
    for p in planes {
        // n̂ · (Σ λ_j q_j − point) ≥ t.
        let mut row: Vec<f64> = q.iter().map(|qj| -p.normal.dot(*qj)).collect();
        row.push(1.0);
        a.push(row);
        b.push(-p.normal.dot(p.point));
    }
    for i in 0..k {
        let mut row = vec![0.0; k + 1];
        row[i] = -1.0;
        row[k] = 1.0 / k as f64;
        a.push(row);
        b.push(0.0);
    }
    let mut sum = vec![1.0; k + 1];
    sum[k] = 0.0;
    a.push(sum.clone());
    b.push(1.0);
    a.push(sum.iter().map(|x| -x).collect());
    b.push(-1.0);
    let mut cap = vec![0.0; k + 1];
    cap[k] = 1.0;
    a.push(cap.clone());
    b.push(1.0);
    match maximize(&cap, &a, &b) {
        Lp::Optimal(x, t) if t > TINY => {
            let h = q.iter().zip(&x).map(|(qj, &lj)| *qj * lj).sum();
            Some((h, t))
        }
        _ => None,
    }
}

/// Whether some point within [`REACH`] of `c` lies in front of every face
/// in `subset` by more than [`TINY`].
fn common_view(planes: &[Plane], subset: &[usize]) -> bool {
    // Variables u = h + REACH·(1,1,1) ≥ 0 and t.
    let mut a = Vec::with_capacity(planes.len() + 4);
    let mut b = Vec::with_capacity(planes.len() + 4);
    for p in planes.iter().filter(|p| subset.contains(&p.face)) {
        let n = p.normal;
        // n̂ · (u − REACH·1 − point) ≥ t.
        a.push(vec![-n.x, -n.y, -n.z, 1.0]);
        b.push(-n.dot(p.point + DVec3::splat(REACH)));
    }
    for axis in 0..3 {
        let mut row = vec![0.0; 4];
        row[axis] = 1.0;
        a.push(row);
        b.push(2.0 * REACH);
    }
    a.push(vec![0.0, 0.0, 0.0, 1.0]);
    b.push(1.0);
    matches!(maximize(&[0.0, 0.0, 0.0, 1.0], &a, &b), Lp::Optimal(_, t) if t > TINY)
}

/// A smallest-by-inclusion subset of `set` with no common point in front
/// (Helly: at most four, up to rounding), by dropping faces one at a time.
fn minimal_blind_set(planes: &[Plane], mut set: Vec<usize>) -> Vec<usize> {
    let mut i = 0;
    while i < set.len() {
        let mut rest = set.clone();
        rest.remove(i);
        if !rest.is_empty() && !common_view(planes, &rest) {
            set = rest;
        } else {
            i += 1;
        }
    }
    set
}

/// The faces of `faces` that do not have `h` strictly in front of each of
/// their fan triangles (exact `orient3d`; a triangle whose corners are
/// collinear has no side and is skipped).
fn blind_faces(mesh: &Mesh, faces: &[FaceId], h: DVec3) -> Result<Vec<FaceId>, MultiHandleError> {
    let mut blind = Vec::new();
    for &f in faces {
        let p = mesh
            .face_positions(f)
            .map_err(|e| MultiHandleError::Check(CrossingError::Kernel(e)))?;
        let mut sides = (1..p.len().saturating_sub(1)).map(|j| orient3d(p[0], p[j], p[j + 1], h));
        // Shewchuk's sign: negative when h is on the side the
        // counter-clockwise normal points to.
        let seen = sides.clone().any(|s| s == Sign::Negative) && sides.all(|s| s != Sign::Positive);
        if !seen {
            blind.push(f);
        }
    }
    Ok(blind)
}

/// Refuses `h` when the straight segment from a selected face's centroid
/// to it crosses another face (exactly, with the mesh's equal positions
/// as one point and the centroids and `h` as points of their own).
fn sightlines(mesh: &Mesh, sel: &Selection<'_>, h: DVec3) -> Result<(), MultiHandleError> {
    let s = Surface::of(mesh).map_err(CrossingError::Kernel)?;
    let ids = position_classes(&s.positions).map_err(CrossingError::Geom)?;
    let base = s.positions.len() as u32;
    let hub = SymPoint::new(h, base + sel.len() as u32);
    for (i, (&f, &p)) in sel.faces.iter().zip(sel.centroids).enumerate() {
        let from = SymPoint::new(p, base + i as u32);
        let reach = Aabb::from_points(&[p, h]);
        for (t, tri) in s.triangles.iter().enumerate() {
            if s.owner[t] == f || !Aabb::from_points(&s.corners(t)).overlaps(&reach) {
                continue;
            }
            let [a, b, c] = tri.map(|v| SymPoint::new(s.positions[v as usize], ids[v as usize]));
            if segment_triangle_intersect(from, hub, a, b, c) {
                return Err(MultiHandleError::Blocked {
                    face: f,
                    by: s.owner[t],
                    hub: h,
                });
            }
        }
    }
    Ok(())
}
