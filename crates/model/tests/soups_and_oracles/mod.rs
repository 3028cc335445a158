//! Helpers shared by the figure tests (chapters IV–VII: handles, rinds,
//! Sierpinski and Menger): primitives as kernel meshes, unions of soups,
//! counts, and oracles written from the definitions (independent of the
//! code under test).
#![allow(dead_code, clippy::unwrap_used)]

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{CornerId, DVec3, EdgeId, FaceId, Mesh};
use holey_mesh::PolyMesh;

pub fn poly(spec: &str) -> PolyMesh {
    holey_shapes::parse_primitive(spec).unwrap()
}

pub fn mesh(soup: &PolyMesh) -> Mesh {
    to_dlfl(soup, ImportOptions::default()).unwrap().mesh
}

pub fn prim(spec: &str) -> Mesh {
    mesh(&poly(spec))
}

/// The soup `a` followed by `b` moved by `offset`: faces of `a` keep
/// their indices, faces of `b` follow.
pub fn union(a: &PolyMesh, b: &PolyMesh, offset: DVec3) -> PolyMesh {
    let mut out = a.clone();
    out.append(&b.translated(offset));
    out
}

pub fn counts(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

pub fn corner(m: &Mesh, face: usize) -> CornerId {
    m.face_corner(m.face_at(face).unwrap()).unwrap()
}

/// The edge of face `a` that has face `b` on its other side (the two
/// faces must be neighbours).
pub fn shared_edge(m: &Mesh, a: FaceId, b: FaceId) -> EdgeId {
    m.face_corners(a)
        .unwrap()
        .filter_map(|c| m.corner_edge(c).unwrap())
        .find(|&e| m.edge_faces(e).unwrap().contains(&b))
        .unwrap()
}

/// The `k`-th corner of face `face` from its first corner.
pub fn nth_corner(m: &Mesh, face: usize, k: usize) -> CornerId {
    m.face_corners(m.face_at(face).unwrap())
        .unwrap()
        .nth(k)
        .unwrap()
}

pub fn vertex_average(points: &[DVec3]) -> DVec3 {
    points.iter().copied().sum::<DVec3>() / points.len() as f64
}

/// Twice the vector area by the shoelace sum Σ pᵢ × pᵢ₊₁.
pub fn shoelace(points: &[DVec3]) -> DVec3 {
    let n = points.len();
    (0..n).map(|i| points[i].cross(points[(i + 1) % n])).sum()
}

pub fn unit_normal(m: &Mesh, f: FaceId) -> DVec3 {
    shoelace(&m.face_positions(f).unwrap()).normalize()
}

/// Eq. 4.1 written out: H(t) = p1·h1 + p2·h2 + w1·n1·h3 − w2·n2·h4.
pub fn hermite(p1: DVec3, n1: DVec3, w1: f64, p2: DVec3, n2: DVec3, w2: f64, t: f64) -> DVec3 {
    let h1 = 2.0 * t.powi(3) - 3.0 * t * t + 1.0;
    let h2 = -2.0 * t.powi(3) + 3.0 * t * t;
    let h3 = t.powi(3) - 2.0 * t * t + t;
    let h4 = t.powi(3) - t * t;
    p1 * h1 + p2 * h2 + n1 * (w1 * h3) - n2 * (w2 * h4)
}

/// dH/dt by differentiating the basis by hand.
pub fn hermite_velocity(
    p1: DVec3,
    n1: DVec3,
    w1: f64,
    p2: DVec3,
    n2: DVec3,
    w2: f64,
    t: f64,
) -> DVec3 {
    let d1 = 6.0 * t * t - 6.0 * t;
    let d2 = -6.0 * t * t + 6.0 * t;
    let d3 = 3.0 * t * t - 4.0 * t + 1.0;
    let d4 = 3.0 * t * t - 2.0 * t;
    p1 * d1 + p2 * d2 + n1 * (w1 * d3) - n2 * (w2 * d4)
}

/// Undirected edges of a soup, each with the faces on its sides.
pub fn soup_edges(soup: &PolyMesh) -> std::collections::BTreeMap<(u32, u32), Vec<usize>> {
    let mut map = std::collections::BTreeMap::new();
    for (f, face) in soup.faces().enumerate() {
        for i in 0..face.len() {
            let (a, b) = (face[i], face[(i + 1) % face.len()]);
            map.entry((a.min(b), a.max(b)))
                .or_insert_with(Vec::new)
                .push(f);
        }
    }
    map
}

/// For a set of faces `region` of a closed soup: (interior edges — both
/// sides in the region —, interior vertices — every face around them in
/// the region).
pub fn region_interior(soup: &PolyMesh, region: &[usize]) -> (usize, usize) {
    let inside = |f: &usize| region.contains(f);
    let walls = soup_edges(soup)
        .values()
        .filter(|fs| fs.len() == 2 && fs.iter().all(inside))
        .count();
    let mut around: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (f, face) in soup.faces().enumerate() {
        for &v in face {
            around.entry(v).or_default().push(f);
        }
    }
    let vertices = around.values().filter(|fs| fs.iter().all(inside)).count();
    (walls, vertices)
}
