//! The true Menger sponge on a parallelepiped (beyond the thesis; see the
//! module documentation of [`super`]).
//!
//! The level-`n` sponge is the union of the cells of a `3^n` grid whose
//! coordinates, written in base 3, never have a 1 in the same digit
//! position of two coordinates. Its surface is the set of cell faces
//! between a kept cell and a removed (or outside) one; every such face
//! becomes one quadrilateral, oriented away from its kept cell, and each
//! grid edge on the surface is shared by exactly two of them (checked by
//! construction, and by the kernel's validation of the result).

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use holey_dlfl::{DVec3, Mesh, RawMesh, VertexId};
use holey_geom::identity::MulHasher;

use super::MengerError;

/// The true sponge built by exact mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExactSponge {
    /// The sponge's level `n`: the number of subdivisions into `3×3×3` cells.
    pub level: usize,
    /// Vertices of the built mesh.
    pub vertices: usize,
    /// Edges of the built mesh (twice the faces).
    pub edges: usize,
    /// Faces of the built mesh, all quadrilaterals: `2·20^n + 4·8^n`.
    pub faces: usize,
    /// Genus of the surface, from the closed form `(21·20^n + 38·8^n − 59)/133`.
    pub genus: u128,
}

/// The closed-form counts of the level-`n` true sponge (module docs):
/// `(V, E, F, genus)`, or `None` if they overflow.
pub fn exact_counts(level: usize) -> Option<(u128, u128, u128, u128)> {
    let n = u32::try_from(level).ok()?;
    let p20 = 20u128.checked_pow(n)?;
    let p8 = 8u128.checked_pow(n)?;
    let faces = p20.checked_mul(2)?.checked_add(p8.checked_mul(4)?)?;
    let genus = p20
        .checked_mul(21)?
        .checked_add(p8.checked_mul(38)?)?
        .checked_sub(59)?
        / 133;
    let edges = faces.checked_mul(2)?;
    let vertices = faces.checked_add(2)?.checked_sub(genus.checked_mul(2)?)?;
    Some((vertices, edges, faces, genus))
}

/// A parallelepiped: `origin + i·a + j·b + k·c` for `i, j, k ∈ [0, 1]`.
struct Frame {
    origin: DVec3,
    axes: [DVec3; 3],
    /// True when the output must list its faces clockwise in the frame's
    /// coordinates to match the input's orientation.
    flip: bool,
}

/// Recognises a parallelepiped and its orientation.
fn frame(mesh: &Mesh) -> Result<Frame, MengerError> {
    let refuse = |reason: String| MengerError::NotAParallelepiped { reason };
    let (nv, ne, nf) = (mesh.vertex_count(), mesh.edge_count(), mesh.face_count());
    if (nv, ne, nf) != (8, 12, 6) || mesh.hole_count() > 0 {
        return Err(refuse(format!(
            "it has {nv} vertices, {ne} edges and {nf} faces ({} holes); a closed hexahedron has 8, 12 and 6",
            mesh.hole_count()
        )));
    }
    for f in mesh.faces() {
        if mesh.face_len(f)? != 4 {
            return Err(refuse(format!("face {f} is not a quadrilateral")));
        }
    }
    let vertices: Vec<VertexId> = mesh.vertices().collect();
    let o = vertices[0];
    let origin = mesh.position(o)?;
    let mut axes = Vec::with_capacity(3);
    for c in mesh.vertex_rotation(o)? {
        if let Some(e) = mesh.corner_edge(c)? {
            let [x, y] = mesh.edge_vertices(e)?;
            let other = if x == o { y } else { x };
            axes.push(mesh.position(other)? - origin);
        }
    }
    let [a, b, c] = <[DVec3; 3]>::try_from(axes)
        .map_err(|v| refuse(format!("a corner has {} edges instead of 3", v.len())))?;
    let det = a.dot(b.cross(c));
    let scale = a.length() * b.length() * c.length();
    if det.abs() <= 1e-9 * scale {
        return Err(refuse("its edges from one corner are coplanar".into()));
    }
    // Frame coordinates of every vertex must be a corner of the unit cube,
    // all eight different, and every edge must change exactly one of them.
    let inverse = [b.cross(c) / det, c.cross(a) / det, a.cross(b) / det];
    let tol = 1e-9;
    let mut seen = [false; 8];
    let mut slot_code = std::collections::BTreeMap::new();
    for &v in &vertices {
        let r = mesh.position(v)? - origin;
        let mut bits = 0;
        for (k, row) in inverse.iter().enumerate() {
            let s = row.dot(r);
            if s.abs() <= tol {
            } else if (s - 1.0).abs() <= tol {
                bits |= 1 << k;
            } else {
                return Err(refuse(format!(
                    "vertex {v} is not a corner of the parallelepiped spanned at vertex {o}"
                )));
            }
        }
        if seen[bits] {
            return Err(refuse("two vertices sit at the same corner".into()));
        }
        seen[bits] = true;
        slot_code.insert(v, bits);
    }
    for e in mesh.edges() {
        let [x, y] = mesh.edge_vertices(e)?;
        let diff = slot_code[&x] ^ slot_code[&y];
        if diff.count_ones() != 1 {
            return Err(refuse(format!(
                "edge {e} is not an edge of the parallelepiped"
            )));
        }
    }
    let volume = signed_volume(mesh)?;
    Ok(Frame {
        origin,
        axes: [a, b, c],
        flip: (det < 0.0) != (volume < 0.0),
    })
}

/// Signed volume enclosed by a closed mesh (positive when its faces turn
/// counter-clockwise seen from outside).
fn signed_volume(mesh: &Mesh) -> Result<f64, MengerError> {
    let mut v = 0.0;
    for f in mesh.faces() {
        let p = mesh.face_positions(f)?;
        for k in 1..p.len() - 1 {
            v += p[0].dot(p[k].cross(p[k + 1])) / 6.0;
        }
    }
    Ok(v)
}

/// Builds the level-`level` true sponge on the parallelepiped `mesh`.
pub(crate) fn build(
    mesh: &Mesh,
    level: usize,
    max_faces: usize,
) -> Result<(Mesh, ExactSponge), MengerError> {
    let frame = frame(mesh)?;
    let too_many = |bound: u128| MengerError::TooManyFaces {
        level,
        bound,
        cap: max_faces,
    };
    let (_, _, faces, genus) = exact_counts(level).ok_or(too_many(u128::MAX))?;
    if faces > max_faces as u128 {
        return Err(too_many(faces));
    }
    // Here 20^level ≤ 10^7, so level ≤ 5 and 3^level fits easily.
    let n = 3usize.pow(level as u32);
    // Digit positions holding a 1, per coordinate.
    let ones: Vec<u32> = (0..n)
        .map(|mut x| {
            let mut mask = 0;
            for k in 0..level {
                if x % 3 == 1 {
                    mask |= 1 << k;
                }
                x /= 3;
            }
            mask
        })
        .collect();
    let kept = |x: usize, y: usize, z: usize| -> bool {
        let (a, b, c) = (ones[x], ones[y], ones[z]);
        (a & b) | (b & c) | (a & c) == 0
    };
    let side = n + 1;
    let point = |x: usize, y: usize, z: usize| (x * side + y) * side + z;
    let mut vertex_of = vec![u32::MAX; side * side * side];
    let mut raw = RawMesh {
        face_offsets: Vec::with_capacity(faces as usize + 1),
        face_vertices: Vec::with_capacity(4 * faces as usize),
        edges: Vec::with_capacity(2 * faces as usize),
        ..RawMesh::default()
    };
    raw.face_offsets.push(0);
    let mut open: HashMap<u64, u32, BuildHasherDefault<MulHasher>> = HashMap::default();
    let inv = 1.0 / n as f64;
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                if !kept(x, y, z) {
                    continue;
                }
                let cell = [x, y, z];
                for axis in 0..3 {
                    for positive in [false, true] {
                        let mut nb = cell;
                        let outside = if positive {
                            nb[axis] += 1;
                            nb[axis] == n
                        } else if nb[axis] == 0 {
                            true
                        } else {
                            nb[axis] -= 1;
                            false
                        };
                        if !outside && kept(nb[0], nb[1], nb[2]) {
                            continue;
                        }
                        // The face's corners: in the plane of `axis`, walk
                        // the other two axes (cyclic order) counter-
                        // clockwise about the outward normal.
                        let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
                        let mut base = cell;
                        if positive {
                            base[axis] += 1;
                        }
                        let mut square = [(0, 0), (1, 0), (1, 1), (0, 1)];
                        if positive == frame.flip {
                            square.reverse();
                        }
                        let corner0 = raw.face_vertices.len() as u32;
                        let mut ids = [0usize; 4];
                        for (k, &(du, dw)) in square.iter().enumerate() {
                            let mut g = base;
                            g[u] += du;
                            g[w] += dw;
                            let id = point(g[0], g[1], g[2]);
                            ids[k] = id;
                            if vertex_of[id] == u32::MAX {
                                vertex_of[id] = raw.positions.len() as u32;
                                let [a, b, c] = frame.axes;
                                raw.positions.push(
                                    frame.origin
                                        + a * (g[0] as f64 * inv)
                                        + b * (g[1] as f64 * inv)
                                        + c * (g[2] as f64 * inv),
                                );
                            }
                            raw.face_vertices.push(vertex_of[id]);
                        }
                        raw.face_offsets.push(raw.face_vertices.len() as u32);
                        // Pair each side with the other side of its grid edge.
                        for k in 0..4 {
                            let (p, q) = (ids[k], ids[(k + 1) % 4]);
                            let (lo, hi) = if p < q { (p, q) } else { (q, p) };
                            let axis_of_edge = match hi - lo {
                                d if d == side * side => 0,
                                d if d == side => 1,
                                _ => 2,
                            };
                            let key = (lo as u64) * 3 + axis_of_edge;
                            let c = corner0 + k as u32;
                            match open.remove(&key) {
                                Some(first) => raw.edges.push([first, c]),
                                None => {
                                    open.insert(key, c);
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    if !open.is_empty() {
        return Err(MengerError::Kernel(holey_dlfl::Error::Invalid(format!(
            "{} sponge edges have a single side",
            open.len()
        ))));
    }
    let built = Mesh::from_raw_trusted(&raw)
        .map_err(|e| MengerError::Kernel(holey_dlfl::Error::Invalid(e.to_string())))?;
    let sponge = ExactSponge {
        level,
        vertices: built.vertex_count(),
        edges: built.edge_count(),
        faces: built.face_count(),
        genus,
    };
    Ok((built, sponge))
}
