//! Checking and normalizing the mesh; face and corner normals.

use glam::{DVec3, Vec3};
use holey_mesh::PolyMesh;

use crate::{RenderError, unit};

/// A mesh ready to draw, in normalized coordinates: the drawable vertices
/// lie in the unit ball around the origin.
#[derive(Clone, Debug)]
pub struct Prepared<'a> {
    /// Normalized positions (meaningless where `ok` is false).
    pub q: Vec<DVec3>,
    /// Whether each vertex has finite coordinates.
    pub ok: Vec<bool>,
    /// Whether each vertex belongs to a drawable face.
    pub used: Vec<bool>,
    /// Start of each face's corners in `corners`, plus a final entry
    /// (the mesh's own offsets, checked).
    pub offsets: &'a [u32],
    /// The mesh's face index list.
    pub corners: &'a [u32],
    /// The faces to draw: at least 3 corners, all vertices finite.
    pub drawable: Vec<u32>,
    /// Unit Newell normal per face (zero for degenerate or skipped faces).
    pub normal: Vec<DVec3>,
    /// With smooth shading: a unit normal per corner (indexed like
    /// `corners`), else empty.
    pub corner_normal: Vec<Vec3>,
    center: DVec3,
    /// Half-extent used for the first scaling step.
    half: f64,
    /// Radius after the first step (in [1, √3]).
    radius: f64,
}

impl<'a> Prepared<'a> {
    /// Checks the mesh structure and prepares it. `smooth` also computes
    /// corner normals, sharp across dihedral angles above `crease`
    /// degrees.
    pub fn new(mesh: &'a PolyMesh, smooth: bool, crease: f64) -> Result<Prepared<'a>, RenderError> {
        let (offsets, corners) = check(mesh)?;
        let n = mesh.positions.len();
        let ok: Vec<bool> = mesh.positions.iter().map(|p| p.is_finite()).collect();
        let mut drawable = Vec::new();
        let mut used = vec![false; n];
        for f in 0..offsets.len() - 1 {
            let face = &corners[offsets[f] as usize..offsets[f + 1] as usize];
            if face.len() >= 3 && face.iter().all(|&v| ok[v as usize]) {
                drawable.push(f as u32);
                for &v in face {
                    used[v as usize] = true;
                }
            }
        }
        // Bounding box of the drawable vertices; halves avoid overflow for
        // coordinates near f64::MAX.
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for (p, &u) in mesh.positions.iter().zip(&used) {
            if u {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
        }
        let (center, half) = if lo.x <= hi.x {
            let c = lo * 0.5 + hi * 0.5;
            let h = (hi * 0.5 - c * 0.5).max_element();
            (c, if h > 0.0 { h } else { 1.0 })
        } else {
            (DVec3::ZERO, 1.0)
        };
        let mut prep = Prepared {
            q: Vec::with_capacity(n),
            ok,
            used,
            offsets,
            corners,
            drawable,
            normal: Vec::new(),
            corner_normal: Vec::new(),
            center,
            half,
            radius: 1.0,
        };
        // First into [-1, 1]³ by the half-extent, then into the unit ball.
        let first = |p: DVec3| (p * 0.5 - center * 0.5) / half;
        let radius = mesh
            .positions
            .iter()
            .zip(&prep.used)
            .filter(|(_, u)| **u)
            .map(|(&p, _)| first(p).length())
            .fold(0.0f64, f64::max);
        prep.radius = if radius > 0.0 && radius.is_finite() {
            radius
        } else {
            1.0
        };
        prep.q = mesh
            .positions
            .iter()
            .map(|&p| first(p) / prep.radius)
            .collect();
        prep.face_normals();
        if smooth {
            prep.corner_normals(crease);
        }
        Ok(prep)
    }

    /// The corners of face `f`.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.corners[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// World → normalized coordinates.
    pub fn to_normalized(&self, p: DVec3) -> DVec3 {
        (p * 0.5 - self.center * 0.5) / self.half / self.radius
    }

    /// Normalized → world coordinates.
    pub fn to_world(&self, q: DVec3) -> DVec3 {
        self.center + q * (self.radius * self.half * 2.0)
    }

    /// Newell's normal: N = Σᵢ (pᵢ × pᵢ₊₁), twice the vector area of the
    /// polygon, made unit. Zero when the polygon has no area.
    fn face_normals(&mut self) {
        let mut normal = vec![DVec3::ZERO; self.offsets.len() - 1];
        for &f in &self.drawable {
            let face = self.face(f as usize);
            let mut sum = DVec3::ZERO;
            let mut prev = self.q[face[face.len() - 1] as usize];
            for &v in face {
                let p = self.q[v as usize];
                sum += prev.cross(p);
                prev = p;
            }
            normal[f as usize] = unit(sum).unwrap_or(DVec3::ZERO);
        }
        self.normal = normal;
    }

    /// Angle-weighted vertex normals with creases (Thürmer & Wüthrich
    /// 1998): the normal at corner c of face f at vertex v is
    /// Σ θ_g N_g over the faces g around v whose normal is within the
    /// crease angle of N_f, θ_g being g's interior angle at v. At vertices
    /// with more than [`MAX_CREASE_VALENCE`] corners the quadratic
    /// per-corner test is replaced by one vertex normal, used where it is
    /// within the crease angle of N_f and N_f elsewhere.
    fn corner_normals(&mut self, crease: f64) {
        let n = self.q.len();
        let cos_crease = crease.to_radians().cos();
        // Interior angle of every corner of every drawable face.
        let mut angle = vec![0.0f64; self.corners.len()];
        for &f in &self.drawable {
            let (s, e) = (
                self.offsets[f as usize] as usize,
                self.offsets[f as usize + 1] as usize,
            );
            let k = e - s;
            for i in 0..k {
                let p = self.q[self.corners[s + i] as usize];
                let a = self.q[self.corners[s + (i + k - 1) % k] as usize] - p;
                let b = self.q[self.corners[s + (i + 1) % k] as usize] - p;
                angle[s + i] = angle_between(a.cross(b).length(), a.dot(b));
            }
        }
        // Corners around each vertex (compressed rows).
        let mut start = vec![0usize; n + 1];
        for &f in &self.drawable {
            for &v in self.face(f as usize) {
                start[v as usize + 1] += 1;
            }
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut ring = vec![(0u32, 0usize); start[n]];
        for &f in &self.drawable {
            let s = self.offsets[f as usize] as usize;
            for (i, &v) in self.face(f as usize).iter().enumerate() {
                ring[fill[v as usize]] = (f, s + i);
                fill[v as usize] += 1;
            }
        }
        let mut vertex_normal = vec![DVec3::ZERO; n];
        for (v, vn) in vertex_normal.iter_mut().enumerate() {
            *vn = ring[start[v]..start[v + 1]]
                .iter()
                .map(|&(g, c)| self.normal[g as usize] * angle[c])
                .sum();
        }
        // A vertex is smooth when every face normal around it is within
        // half the crease angle of the mean direction u: then any two are
        // within the crease angle of each other, so every corner there
        // sums all faces and gets the vertex normal.
        let cos_half = (crease / 2.0).to_radians().cos();
        let smooth: Vec<bool> = (0..n)
            .map(|v| match unit(vertex_normal[v]) {
                Some(u) => ring[start[v]..start[v + 1]]
                    .iter()
                    .all(|&(g, _)| self.normal[g as usize].dot(u) >= cos_half),
                None => false,
            })
            .collect();
        let mut out = vec![Vec3::ZERO; self.corners.len()];
        for &f in &self.drawable {
            let nf = self.normal[f as usize];
            let s = self.offsets[f as usize] as usize;
            for (i, &v) in self.face(f as usize).iter().enumerate() {
                let around = &ring[start[v as usize]..start[v as usize + 1]];
                let sum = if cos_crease <= -1.0 + 1e-12 || smooth[v as usize] {
                    vertex_normal[v as usize]
                } else if around.len() > MAX_CREASE_VALENCE {
                    let vn = vertex_normal[v as usize];
                    match unit(vn) {
                        Some(u) if u.dot(nf) >= cos_crease => vn,
                        _ => nf,
                    }
                } else {
                    around
                        .iter()
                        .filter(|&&(g, _)| self.normal[g as usize].dot(nf) >= cos_crease)
                        .map(|&(g, c)| self.normal[g as usize] * angle[c])
                        .sum()
                };
                out[s + i] = unit(sum).unwrap_or(nf).as_vec3();
            }
        }
        self.corner_normal = out;
    }
}

/// The angle atan2(y, x) ∈ [0, π] for y ≥ 0, from a degree-9 odd
/// polynomial for atan on [0, 1] (Abramowitz & Stegun 4.4.49, error below
/// 1e-5 rad): plenty for weights, and several times faster than libm.
/// Non-finite or zero input gives 0.
pub fn angle_between(y: f64, x: f64) -> f64 {
    let ax = x.abs();
    let (num, den) = if y <= ax { (y, ax) } else { (ax, y) };
    if !(den > 0.0 && den.is_finite() && num.is_finite()) {
        return 0.0;
    }
    let z = num / den;
    let z2 = z * z;
    let mut a = z
        * (0.999_866
            + z2 * (-0.330_299_5 + z2 * (0.180_141 + z2 * (-0.085_133 + z2 * 0.020_835_1))));
    if y > ax {
        a = std::f64::consts::FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = std::f64::consts::PI - a;
    }
    a
}

/// Above this many corners at a vertex, smooth normals use one vertex
/// normal instead of a per-corner crease test (keeps the cost linear).
pub const MAX_CREASE_VALENCE: usize = 64;

/// Checks offsets and indices without trusting either; returns the
/// offsets (a lone 0 for a mesh without any) and the index list.
fn check(mesh: &PolyMesh) -> Result<(&[u32], &[u32]), RenderError> {
    static NO_FACES: [u32; 1] = [0];
    let m = &mesh.face_offsets;
    if m.is_empty() {
        if mesh.face_indices.is_empty() {
            return Ok((&NO_FACES, &[]));
        }
        return Err(RenderError::Mesh(
            "face indices are given but no face offsets".into(),
        ));
    }
    if m[0] != 0 {
        return Err(RenderError::Mesh(format!(
            "the first face offset is {}, not 0",
            m[0]
        )));
    }
    if let Some(i) = m.windows(2).position(|w| w[1] < w[0]) {
        return Err(RenderError::Mesh(format!(
            "face offsets decrease at face {i}"
        )));
    }
    let last = m[m.len() - 1] as usize;
    if last != mesh.face_indices.len() {
        return Err(RenderError::Mesh(format!(
            "the last face offset is {last} but there are {} face indices",
            mesh.face_indices.len()
        )));
    }
    let n = mesh.positions.len();
    if let Some(pos) = mesh.face_indices.iter().position(|&v| v as usize >= n) {
        let face = m.partition_point(|&o| (o as usize) <= pos) - 1;
        return Err(RenderError::Mesh(format!(
            "face {face} refers to vertex {}, but there are only {n} vertices",
            mesh.face_indices[pos]
        )));
    }
    Ok((m, &mesh.face_indices))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_angle_matches_atan2() {
        let mut rng = holey_testkit::Rng::new(7);
        for _ in 0..10_000 {
            let (y, x) = (rng.range(0.0, 3.0), rng.range(-3.0, 3.0));
            assert!((angle_between(y, x) - y.atan2(x)).abs() < 2e-5, "{y} {x}");
        }
        assert_eq!(angle_between(0.0, 0.0), 0.0);
        assert_eq!(angle_between(f64::NAN, 1.0), 0.0);
        assert!((angle_between(1.0, 0.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-5);
        assert!((angle_between(0.0, -1.0) - std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn malformed_meshes_are_errors() {
        let mut m = PolyMesh::from_faces(vec![DVec3::ZERO; 3], [[0u32, 1, 2]]);
        m.face_indices[1] = 7;
        let e = Prepared::new(&m, false, 60.0).unwrap_err();
        assert!(e.to_string().contains("face 0 refers to vertex 7"), "{e}");
        let mut m = PolyMesh::from_faces(vec![DVec3::ZERO; 3], [[0u32, 1, 2]]);
        m.face_offsets = vec![0, 5];
        assert!(Prepared::new(&m, false, 60.0).is_err());
        m.face_offsets = vec![1, 3];
        assert!(Prepared::new(&m, false, 60.0).is_err());
        m.face_offsets = vec![0, 3, 2, 3];
        assert!(Prepared::new(&m, false, 60.0).is_err());
        m.face_offsets = vec![];
        assert!(Prepared::new(&m, false, 60.0).is_err());
        // A default (all-empty) mesh is fine and empty.
        let empty = PolyMesh::default();
        let p = Prepared::new(&empty, false, 60.0).unwrap();
        assert!(p.drawable.is_empty());
    }

    #[test]
    fn normalization_fits_the_unit_ball_and_round_trips() {
        let m = holey_shapes::parse_primitive("@cube").unwrap();
        let p = Prepared::new(&m, false, 60.0).unwrap();
        // Cube [-1,1]³: centre 0, radius √3 → corners at distance 1.
        for q in &p.q {
            assert!((q.length() - 1.0).abs() < 1e-12);
        }
        let w = p.to_world(p.q[3]);
        assert!((w - m.positions[3]).length() < 1e-12);
        assert!((p.to_normalized(m.positions[5]) - p.q[5]).length() < 1e-15);
        // Face normals of the cube are the axes, pointing outward.
        for &f in &p.drawable {
            let n = p.normal[f as usize];
            let c: DVec3 = p.face(f as usize).iter().map(|&v| p.q[v as usize]).sum();
            assert!((n.abs().max_element() - 1.0).abs() < 1e-12);
            assert!(n.dot(c) > 0.0);
        }
    }

    #[test]
    fn huge_coordinates_do_not_overflow() {
        let big = 1.5e308;
        let m = PolyMesh::from_faces(
            vec![
                DVec3::new(-big, -big, 0.0),
                DVec3::new(big, -big, 0.0),
                DVec3::new(big, big, 0.0),
            ],
            [[0u32, 1, 2]],
        );
        let p = Prepared::new(&m, false, 60.0).unwrap();
        assert!(
            p.q.iter()
                .all(|q| q.is_finite() && q.length() <= 1.0 + 1e-12)
        );
        assert!((p.normal[0] - DVec3::Z).length() < 1e-12);
    }

    #[test]
    fn non_finite_vertices_skip_their_faces() {
        let m = PolyMesh::from_faces(
            vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                DVec3::new(f64::NAN, 0.0, 0.0),
                DVec3::new(0.0, f64::INFINITY, 0.0),
            ],
            vec![vec![0u32, 1, 2], vec![0, 1, 3], vec![1, 2, 4], vec![0, 1]],
        );
        let p = Prepared::new(&m, true, 60.0).unwrap();
        assert_eq!(p.drawable, vec![0]);
        assert_eq!(p.used, vec![true, true, true, false, false]);
    }

    /// Smooth normals of an icosphere approximate the radial direction;
    /// a cube keeps its faces' normals (every dihedral angle is 90° > 60°)
    /// unless the crease is 180°, where corners get the diagonal.
    #[test]
    fn corner_normals() {
        let s = holey_shapes::parse_primitive("@sphere:3").unwrap();
        let p = Prepared::new(&s, true, 60.0).unwrap();
        for (c, &v) in p.corners.iter().enumerate() {
            let radial = p.q[v as usize].normalize().as_vec3();
            assert!(p.corner_normal[c].dot(radial) > 0.9995);
        }
        let cube = holey_shapes::parse_primitive("@cube").unwrap();
        let p = Prepared::new(&cube, true, 60.0).unwrap();
        for &f in &p.drawable {
            let s = p.offsets[f as usize] as usize;
            for i in 0..4 {
                let n = p.corner_normal[s + i].as_dvec3();
                assert!((n - p.normal[f as usize]).length() < 1e-6);
            }
        }
        let p = Prepared::new(&cube, true, 180.0).unwrap();
        for (c, &v) in p.corners.iter().enumerate() {
            let diag = p.q[v as usize].normalize().as_vec3();
            assert!(p.corner_normal[c].dot(diag) > 0.99999);
        }
    }
}
