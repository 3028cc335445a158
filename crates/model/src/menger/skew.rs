//! Splitting strongly non-planar faces before a level (§VII.5.1).
//!
//! The thesis: a non-planar face has no simple remeshing face, slight skew
//! still gives acceptable results, and "non-planar faces can always be
//! triangulated to make them planar". So faces off their mean plane by at
//! most [`SKEW_SPLIT_REL`] of their size are left as they are, and more
//! skewed faces are cut along diagonals into planar pieces first (towards
//! triangles, but stopping as soon as each piece is planar).
//!
//! Such faces appear in the algorithm's own output: from level 3 on a cube,
//! the offset face around a vertex where three re-entrant edges meet is a
//! hexagon folded over the inside corner of a box, which this cuts into
//! its two planar quadrilaterals.

use holey_dlfl::{CornerId, DVec3, Mesh};

use super::MengerError;
use super::plan::AREA_REL;

/// Largest distance from the mean plane, as a fraction of the face's
/// longest edge, that a face may have and be kept whole.
pub(crate) const SKEW_SPLIT_REL: f64 = 0.01;

/// Faces above this many corners are not searched for diagonals (the
/// search is cubic in the size); planning reports them if they misbehave.
const MAX_SPLIT_LEN: usize = 64;

/// The distance from the mean plane over the longest edge, and the
/// Newell vector (twice the area vector) of a polygon.
fn skew(p: &[DVec3]) -> (f64, DVec3) {
    let n = p.len();
    let c = p.iter().copied().sum::<DVec3>() / n as f64;
    let newell: DVec3 = (0..n).map(|j| (p[j] - c).cross(p[(j + 1) % n] - c)).sum();
    let size = (0..n)
        .map(|j| p[j].distance(p[(j + 1) % n]))
        .fold(0.0, f64::max);
    if newell.length_squared() == 0.0 || size == 0.0 {
        return (f64::INFINITY, newell);
    }
    let normal = newell.normalize();
    let dev = p
        .iter()
        .map(|q| (*q - c).dot(normal).abs())
        .fold(0.0, f64::max);
    (dev / size, newell)
}

/// Cuts every face skewed beyond [`SKEW_SPLIT_REL`] into planar pieces.
/// Each cut is an `InsertEdge` inside the face (F+1, topology unchanged).
/// Returns the number of cuts.
pub(crate) fn split_skewed_faces(mesh: &mut Mesh) -> Result<usize, MengerError> {
    let mut work: Vec<CornerId> = Vec::new();
    for f in mesh.faces() {
        let len = mesh.face_len(f)?;
        if !(4..=MAX_SPLIT_LEN).contains(&len) || mesh.is_hole(f)? {
            continue;
        }
        let p = mesh.face_positions(f)?;
        if skew(&p).0 > SKEW_SPLIT_REL {
            work.push(mesh.face_corner(f)?);
        }
    }
    let mut cuts = 0;
    while let Some(c0) = work.pop() {
        let corners: Vec<CornerId> = mesh.face_corners_from(c0)?.collect();
        let n = corners.len();
        if n < 4 {
            continue;
        }
        let mut p = Vec::with_capacity(n);
        for &c in &corners {
            p.push(mesh.position(mesh.corner_vertex(c)?)?);
        }
        let (dev, whole) = skew(&p);
        if dev <= SKEW_SPLIT_REL {
            continue;
        }
        // The diagonal whose two pieces are flattest, among those whose
        // pieces both keep an area facing the same way as the face.
        let mut best: Option<(f64, usize, usize)> = None;
        for i in 0..n {
            for j in i + 2..n {
                if i == 0 && j == n - 1 {
                    continue;
                }
                let a: Vec<DVec3> = (i..=j).map(|k| p[k]).collect();
                let b: Vec<DVec3> = (j..n).chain(0..=i).map(|k| p[k]).collect();
                let (da, na) = skew(&a);
                let (db, nb) = skew(&b);
                let floor = AREA_REL * whole.length_squared();
                if na.dot(whole) <= floor || nb.dot(whole) <= floor {
                    continue;
                }
                let score = da.max(db);
                if best.is_none_or(|(s, _, _)| score < s) {
                    best = Some((score, i, j));
                }
            }
        }
        let Some((_, i, j)) = best else {
            // No diagonal keeps both pieces facing outwards: leave the face
            // to the planning checks.
            continue;
        };
        mesh.insert_edge(corners[i], corners[j])?;
        cuts += 1;
        work.push(corners[i]);
        work.push(corners[j]);
    }
    Ok(cuts)
}
