//! The automatic step of rind modeling (§V.3.1): the offset surface.
//!
//! The input is flattened ([`holey_dlfl::Mesh::to_raw`]), and a second copy of every
//! vertex and face is appended to the same arrays: faces reversed, edges
//! mapped corner by corner, vertices moved along their averaged unit
//! normals. [`holey_dlfl::Mesh::from_raw`] then builds both shells in one pass. This
//! is linear in the size of the mesh.

use glam::DVec3;
use holey_dlfl::{NonFinite, RawMesh};

use super::RindError;
use crate::handle::geometry::vector_area;

/// Relative tolerance below which an offset face's area along its outer
/// face's normal counts as collapsed or flipped.
const FLIP_TOLERANCE: f64 = 1e-9;

/// The two shells as raw arrays: outer faces `0..F`, their inner copies
/// `F..2F`; the inner copy of face `f` starts at the copy of `f`'s first
/// vertex, so corner `offsets[f]` (outer) matches corner
/// `C + offsets[f]` (inner), `C` the number of outer corners.
pub(crate) struct Shells {
    pub(crate) raw: RawMesh,
    /// Outer corners `C`.
    pub(crate) corners: u32,
}

/// What is wrong with an offset face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Defect {
    /// Turned over: an edge reversed, or the face's normal flipped.
    Inverted,
    /// Shrunk to nothing: an edge or the whole face.
    Collapsed,
}

/// Compares an offset face `inner` (read in the outer face's order) with
/// its original `outer`:
/// - each edge must keep its direction: an offset past the local centre
///   of curvature reverses edges (a sphere offset by more than its radius
///   is its own point reflection, which keeps every face normal);
/// - the face must keep facing the same way: a fold can turn a face over
///   while each edge stays within 90° of its direction.
///
/// Both are measured relative to the original (10⁻⁹ of the edge length
/// or of the area), so uniformly scaled meshes behave alike.
pub(crate) fn face_offset_defect(outer: &[DVec3], inner: &[DVec3]) -> Option<Defect> {
    let n = outer.len();
    for i in 0..n {
        let d = outer[(i + 1) % n] - outer[i];
        let d_in = inner[(i + 1) % n] - inner[i];
        let len2 = d.length_squared();
        if len2 > 0.0 && d_in.dot(d) <= FLIP_TOLERANCE * len2 {
            return Some(
                if d_in.length_squared() <= FLIP_TOLERANCE * FLIP_TOLERANCE * len2 {
                    Defect::Collapsed
                } else {
                    Defect::Inverted
                },
            );
        }
    }
    let a = vector_area(outer);
    let area = a.length();
    if area == 0.0 {
        return None;
    }
    let b = vector_area(inner);
    if b.dot(a) / area <= FLIP_TOLERANCE * area {
        return Some(if b.length() <= FLIP_TOLERANCE * area {
            Defect::Collapsed
        } else {
            Defect::Inverted
        });
    }
    None
}

/// Unit normal of each face (zero for faces of zero area and for holes).
fn face_normals(raw: &RawMesh) -> Vec<DVec3> {
    (0..raw.face_count())
        .map(|f| {
            if raw.is_hole(f) {
                return DVec3::ZERO;
            }
            let pts: Vec<DVec3> = raw
                .face(f)
                .iter()
                .map(|&v| raw.positions[v as usize])
                .collect();
            vector_area(&pts).normalize_or_zero()
        })
        .collect()
}

/// Builds the offset shells of `raw`, whose vertex `i` and face `f` are
/// the input's vertex slot `vertex_slot[i]` and face slot `face_slot[f]`
/// (for error messages).
///
/// Each vertex's offset direction is the average of the unit normals of
/// its non-hole faces (§V.3.1 step 1), normalised; the inner copy sits at
/// `p − thickness·n`, so a positive thickness goes inside an outward-
/// facing surface. Refused: a vertex whose normals cancel (no direction),
/// non-finite results, and any face whose offset copy is turned over or
/// collapsed: an edge whose copy runs the other way or shrinks to nothing
/// (its component along the original is ≤ 10⁻⁹ of its length), or a face
/// whose copy, read in the outer face's order, no longer faces the same
/// way (its area along the outer normal is ≤ 10⁻⁹ of the outer area). The
/// thickness is then too large for the local feature size there.
pub(crate) fn build_shells(
    raw: &RawMesh,
    thickness: f64,
    vertex_slot: &[usize],
    face_slot: &[usize],
) -> Result<Shells, RindError> {
    let nv = raw.positions.len();
    let nf = raw.face_count();
    let nc = raw.face_vertices.len();
    let normals = face_normals(raw);
    let mut sum = vec![DVec3::ZERO; nv];
    let mut some_face = vec![usize::MAX; nv];
    for (f, &normal) in normals.iter().enumerate() {
        for &v in raw.face(f) {
            sum[v as usize] += normal;
            if some_face[v as usize] == usize::MAX || raw.is_hole(some_face[v as usize]) {
                some_face[v as usize] = f;
            }
        }
    }
    let mut positions = Vec::with_capacity(2 * nv);
    positions.extend_from_slice(&raw.positions);
    for v in 0..nv {
        let n = sum[v];
        // The sum of k unit vectors; a length this small means they cancel.
        if n.length().is_nan() || n.length() <= 1e-9 {
            return Err(RindError::NoVertexNormal {
                vertex: vertex_slot[v],
                face: face_slot.get(some_face[v]).copied().unwrap_or(usize::MAX),
            });
        }
        let p = raw.positions[v] - n.normalize() * thickness;
        if !p.is_finite() {
            return Err(
                NonFinite::new("the offset copy of vertex", vertex_slot[v], p)
                    .with_hint("the thickness is too large for the model's coordinates")
                    .into(),
            );
        }
        positions.push(p);
    }
    for (f, &slot) in face_slot.iter().enumerate().take(nf) {
        if raw.is_hole(f) {
            continue;
        }
        let face = raw.face(f);
        let outer: Vec<DVec3> = face.iter().map(|&v| raw.positions[v as usize]).collect();
        let inner: Vec<DVec3> = face.iter().map(|&v| positions[nv + v as usize]).collect();
        match face_offset_defect(&outer, &inner) {
            None => {}
            Some(Defect::Collapsed) => {
                return Err(RindError::Collapsed {
                    face: slot,
                    thickness,
                });
            }
            Some(Defect::Inverted) => {
                return Err(RindError::Inverted {
                    face: slot,
                    thickness,
                });
            }
        }
    }

    let nv32 = nv as u32;
    let nc32 = nc as u32;
    let mut face_offsets = Vec::with_capacity(2 * nf + 1);
    face_offsets.extend_from_slice(&raw.face_offsets);
    face_offsets.extend(raw.face_offsets[1..].iter().map(|o| o + nc32));
    let mut face_vertices = Vec::with_capacity(2 * nc);
    face_vertices.extend_from_slice(&raw.face_vertices);
    let mut corner_face = vec![0u32; nc];
    for f in 0..nf {
        let face = raw.face(f);
        // Reversed, starting at the same vertex: v0, v(n−1), …, v1.
        face_vertices.push(face[0] + nv32);
        face_vertices.extend(face[1..].iter().rev().map(|v| v + nv32));
        let (lo, hi) = (
            raw.face_offsets[f] as usize,
            raw.face_offsets[f + 1] as usize,
        );
        corner_face[lo..hi].fill(f as u32);
    }
    let holes = if raw.holes.is_empty() {
        Vec::new()
    } else {
        let mut h = raw.holes.clone();
        h.extend_from_slice(&raw.holes);
        h
    };
    // Outer corner k of a face of n corners starts the half-edge
    // v_k → v_(k+1); in the reversed copy the half-edge v_(k+1) → v_k
    // starts at local corner n − 1 − k.
    let inner_corner = |c: u32| {
        let f = corner_face[c as usize] as usize;
        let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
        let k = c - lo;
        nc32 + lo + (hi - lo - 1 - k)
    };
    let mut edges = Vec::with_capacity(2 * raw.edges.len());
    edges.extend_from_slice(&raw.edges);
    edges.extend(
        raw.edges
            .iter()
            .map(|&[a, b]| [inner_corner(a), inner_corner(b)]),
    );
    Ok(Shells {
        raw: RawMesh {
            positions,
            face_offsets,
            face_vertices,
            holes,
            edges,
        },
        corners: nc32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_face_turned_over_with_its_edges_kept_is_caught() {
        // The apex crosses the base: both slanted edges stay within 90°.
        let outer = [
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::X,
            DVec3::new(0.0, 0.1, 0.0),
        ];
        let inner = [
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::X,
            DVec3::new(0.0, -0.1, 0.0),
        ];
        for i in 0..3 {
            let d = outer[(i + 1) % 3] - outer[i];
            let e = inner[(i + 1) % 3] - inner[i];
            assert!(d.dot(e) > 0.0);
        }
        assert_eq!(face_offset_defect(&outer, &inner), Some(Defect::Inverted));
        // Moved and shrunk but not turned: fine.
        let ok = outer.map(|p| p * 0.5 + DVec3::Z);
        assert_eq!(face_offset_defect(&outer, &ok), None);
        // Point-reflected: same normal, every edge reversed.
        let refl = outer.map(|p| -p * 0.5);
        assert_eq!(face_offset_defect(&outer, &refl), Some(Defect::Inverted));
        // Collapsed to a point.
        let pt = [DVec3::ONE; 3];
        assert_eq!(face_offset_defect(&outer, &pt), Some(Defect::Collapsed));
        // Collapsed onto a segment without reversing an edge.
        let flat = [DVec3::new(-1.0, 0.0, 0.0), DVec3::X, DVec3::ZERO];
        assert_eq!(face_offset_defect(&outer, &flat), Some(Defect::Collapsed));
    }
}
