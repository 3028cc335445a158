//! Binary mesh frames: what the browser draws, in the layout
//! `web/PROTOCOL.md` specifies (little-endian, 4-byte aligned sections).
//!
//! A frame carries display indices. For a DLFL the server keeps the
//! handles behind them ([`ModelIndex`]) so that a click on face 12 of the
//! picture names the same face when the request comes back.

use glam::DVec3;
use holey_dlfl::{EdgeId, FaceId, Mesh, VertexId};
use holey_topo::TriMesh;

/// Frame flag: a preview, not the committed document.
pub const FLAG_PREVIEW: u32 = 1;
/// Frame flag: a per-vertex vanish mask follows the arrays.
pub const FLAG_VANISH: u32 = 2;
/// Frame flag: positions only; connectivity as in the previous frame.
pub const FLAG_POSITIONS_ONLY: u32 = 4;
/// Frame flag (with [`FLAG_POSITIONS_ONLY`]): only the vertices that moved
/// since the previous frame, as a count, their indices and positions.
pub const FLAG_SPARSE: u32 = 8;
/// Frame flag (full frames only): the sculpt mask follows the vanish mask,
/// one byte per vertex, 1 where no brush moves the vertex.
pub const FLAG_SCULPT_MASK: u32 = 16;

const MAGIC: &[u8; 4] = b"HMSH";
const FORMAT_VERSION: u32 = 1;

/// A mesh as the browser draws it: fan-triangulated faces, the face of
/// every triangle, and the polygon edges for the wireframe.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Display {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    pub triangle_face: Vec<u32>,
    pub edges: Vec<[u32; 2]>,
    pub faces: usize,
}

impl Display {
    /// The header counts of a frame over this connectivity with `nv`
    /// vertices: vertices, triangles, edges, faces.
    fn counts(&self, nv: usize) -> [usize; 4] {
        [nv, self.triangles.len(), self.edges.len(), self.faces]
    }
}

/// The kernel handles behind a DLFL's display indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModelIndex {
    pub vertices: Vec<VertexId>,
    pub faces: Vec<FaceId>,
    pub edges: Vec<EdgeId>,
}

/// The display of a DLFL: vertices, non-hole faces and edges in slot order.
pub fn display_model(mesh: &Mesh) -> (Display, ModelIndex) {
    let vertices: Vec<VertexId> = mesh.vertices().collect();
    // Slot indices are dense enough to map through a table.
    let slots = vertices.iter().map(|v| v.index() + 1).max().unwrap_or(0);
    let mut display_of = vec![u32::MAX; slots];
    for (i, v) in vertices.iter().enumerate() {
        display_of[v.index()] = i as u32;
    }
    let at = |v: VertexId| display_of.get(v.index()).copied().unwrap_or(u32::MAX);
    let positions = vertices
        .iter()
        .map(|&v| mesh.position(v).unwrap_or_default())
        .collect();
    let mut faces = Vec::new();
    let mut triangles = Vec::new();
    let mut triangle_face = Vec::new();
    let mut ring = Vec::new();
    for f in mesh.faces() {
        if mesh.is_hole(f).unwrap_or(false) {
            continue;
        }
        ring.clear();
        if let Ok(vs) = mesh.face_vertices(f) {
            ring.extend(vs.into_iter().map(at));
        }
        let index = faces.len() as u32;
        faces.push(f);
        // A fan is exact for the convex faces the tools make; the
        // picture of a non-convex face may fold, its topology does not.
        for k in 1..ring.len().saturating_sub(1) {
            triangles.push([ring[0], ring[k], ring[k + 1]]);
            triangle_face.push(index);
        }
    }
    let mut edges = Vec::new();
    let mut edge_ids = Vec::new();
    for e in mesh.edges() {
        if let Ok([a, b]) = mesh.edge_vertices(e) {
            edges.push([at(a), at(b)]);
            edge_ids.push(e);
        }
    }
    let display = Display {
        positions,
        triangles,
        triangle_face,
        edges,
        faces: faces.len(),
    };
    let index = ModelIndex {
        vertices,
        faces,
        edges: edge_ids,
    };
    (display, index)
}

/// The display of a triangle mesh: every triangle is its own face.
pub fn display_triangles(mesh: &TriMesh) -> Display {
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
        .map(|[a, b]| if a < b { [a, b] } else { [b, a] })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    Display {
        positions: mesh.positions.clone(),
        triangles: mesh.triangles.clone(),
        triangle_face: (0..mesh.triangles.len() as u32).collect(),
        edges,
        faces: mesh.triangles.len(),
    }
}

fn put(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn header(
    out: &mut Vec<u8>,
    flags: u32,
    version: u64,
    counts: [usize; 4],
    vanish: Option<&[bool]>,
) -> u32 {
    let flags = flags | if vanish.is_some() { FLAG_VANISH } else { 0 };
    out.extend_from_slice(MAGIC);
    put(out, FORMAT_VERSION);
    put(out, flags);
    // The browser compares versions for equality only; wrapping is fine.
    put(out, version as u32);
    for c in counts {
        put(out, c as u32);
    }
    flags
}

fn positions(out: &mut Vec<u8>, ps: &[DVec3]) {
    for p in ps {
        for c in [p.x, p.y, p.z] {
            out.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
}

fn vanish_mask(out: &mut Vec<u8>, vanish: Option<&[bool]>, nv: usize) {
    if let Some(mask) = vanish {
        out.extend((0..nv).map(|i| u8::from(mask.get(i).copied().unwrap_or(false))));
        while !out.len().is_multiple_of(4) {
            out.push(0);
        }
    }
}

/// A whole frame.
pub fn encode(display: &Display, flags: u32, version: u64, vanish: Option<&[bool]>) -> Vec<u8> {
    encode_masked(display, flags, version, vanish, None)
}

/// A whole frame with the sculpt mask (`masked`, one flag per vertex; none
/// when no vertex is masked).
pub fn encode_masked(
    display: &Display,
    flags: u32,
    version: u64,
    vanish: Option<&[bool]>,
    masked: Option<&[bool]>,
) -> Vec<u8> {
    let nv = display.positions.len();
    let flags = flags
        | if masked.is_some() {
            FLAG_SCULPT_MASK
        } else {
            0
        };
    let nt = display.triangles.len();
    let ne = display.edges.len();
    let mut out = Vec::with_capacity(32 + 12 * nv + 16 * nt + 8 * ne + nv + 4);
    header(
        &mut out,
        flags & !FLAG_POSITIONS_ONLY,
        version,
        display.counts(nv),
        vanish,
    );
    positions(&mut out, &display.positions);
    for t in &display.triangles {
        for &v in t {
            put(&mut out, v);
        }
    }
    for &f in &display.triangle_face {
        put(&mut out, f);
    }
    for e in &display.edges {
        put(&mut out, e[0]);
        put(&mut out, e[1]);
    }
    vanish_mask(&mut out, vanish, nv);
    // The same layout as the vanish mask: a byte per vertex, padded.
    vanish_mask(&mut out, masked, nv);
    out
}

/// A positions-only frame over the connectivity of `display` (which the
/// browser already has).
pub fn encode_positions(
    display: &Display,
    moved: &[DVec3],
    flags: u32,
    version: u64,
    vanish: Option<&[bool]>,
) -> Vec<u8> {
    let nv = moved.len();
    let mut out = Vec::with_capacity(32 + 12 * nv + nv + 4);
    header(
        &mut out,
        flags | FLAG_POSITIONS_ONLY,
        version,
        display.counts(nv),
        vanish,
    );
    positions(&mut out, moved);
    vanish_mask(&mut out, vanish, nv);
    out
}

/// A positions-only frame carrying only the vertices whose position
/// differs from `sent` (what the browser has), or `None` when so many
/// moved that the dense frame is smaller.
pub fn encode_sparse(
    display: &Display,
    sent: &[DVec3],
    moved: &[DVec3],
    flags: u32,
    version: u64,
    vanish: Option<&[bool]>,
) -> Option<Vec<u8>> {
    if sent.len() != moved.len() {
        return None;
    }
    let changed: Vec<u32> = (0..moved.len() as u32)
        .filter(|&i| sent[i as usize] != moved[i as usize])
        .collect();
    // 16 bytes per sparse vertex against 12 per dense one.
    if 16 * changed.len() >= 12 * moved.len() {
        return None;
    }
    let nv = moved.len();
    let mut out = Vec::with_capacity(36 + 16 * changed.len() + nv + 4);
    header(
        &mut out,
        flags | FLAG_POSITIONS_ONLY | FLAG_SPARSE,
        version,
        display.counts(nv),
        vanish,
    );
    put(&mut out, changed.len() as u32);
    for &i in &changed {
        put(&mut out, i);
    }
    let ps: Vec<DVec3> = changed.iter().map(|&i| moved[i as usize]).collect();
    positions(&mut out, &ps);
    vanish_mask(&mut out, vanish, nv);
    Some(out)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn word(b: &[u8], i: usize) -> u32 {
        u32::from_le_bytes(b[4 * i..4 * i + 4].try_into().unwrap())
    }

    #[test]
    fn cube_frame_layout() {
        let soup = holey_shapes::parse_primitive("@cube").unwrap();
        let mesh = holey_dlfl::convert::to_dlfl(&soup, Default::default())
            .unwrap()
            .mesh;
        let (d, index) = display_model(&mesh);
        assert_eq!((d.positions.len(), d.faces, d.edges.len()), (8, 6, 12));
        assert_eq!(d.triangles.len(), 12);
        assert_eq!(index.faces.len(), 6);
        let bytes = encode(&d, 0, 7, None);
        assert_eq!(&bytes[..4], b"HMSH");
        assert_eq!(word(&bytes, 3), 7);
        assert_eq!(
            [
                word(&bytes, 4),
                word(&bytes, 5),
                word(&bytes, 6),
                word(&bytes, 7)
            ],
            [8, 12, 12, 6]
        );
        assert_eq!(bytes.len(), 32 + 12 * 8 + 12 * 12 + 4 * 12 + 8 * 12);
        // Every triangle's face is a face, every index a vertex.
        let tri_face = 8 + 3 * 8 + 3 * 12;
        for t in 0..12 {
            assert!(word(&bytes, tri_face + t) < 6);
        }
        let with_mask = encode_positions(&d, &d.positions, 0, 8, Some(&[true; 8]));
        assert_eq!(word(&with_mask, 2), FLAG_POSITIONS_ONLY | FLAG_VANISH);
        assert_eq!(with_mask.len(), 32 + 12 * 8 + 8);
        assert_eq!(with_mask[32 + 96], 1);
    }

    #[test]
    fn sparse_frames_carry_only_what_moved() {
        let soup = holey_shapes::parse_primitive("@sphere:2").unwrap();
        let m = soup.triangulated();
        let d = display_triangles(&m);
        let mut moved = m.positions.clone();
        moved[5].x += 0.25;
        moved[9].z -= 0.5;
        let b = encode_sparse(&d, &m.positions, &moved, 0, 3, None).unwrap();
        assert_eq!(word(&b, 2), FLAG_POSITIONS_ONLY | FLAG_SPARSE);
        assert_eq!(word(&b, 4) as usize, m.positions.len());
        assert_eq!(word(&b, 8), 2);
        assert_eq!([word(&b, 9), word(&b, 10)], [5, 9]);
        let x = f32::from_le_bytes(b[44..48].try_into().unwrap());
        assert_eq!(x, moved[5].x as f32);
        assert_eq!(b.len(), 36 + 2 * 16);
        // Everything moved: the dense frame is smaller.
        let all: Vec<DVec3> = m.positions.iter().map(|p| *p * 2.0).collect();
        assert!(encode_sparse(&d, &m.positions, &all, 0, 3, None).is_none());
    }

    #[test]
    fn sculpt_mask_follows_the_vanish_mask() {
        let m = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE, DVec3::Z],
            triangles: vec![[0, 1, 2], [2, 1, 3], [0, 2, 4]],
        };
        let d = display_triangles(&m);
        let vanish = [false, true, false, false, false];
        let masked = [true, false, false, true, true];
        let b = encode_masked(&d, 0, 2, Some(&vanish), Some(&masked));
        assert_eq!(word(&b, 2), FLAG_VANISH | FLAG_SCULPT_MASK);
        let arrays = 32 + 12 * 5 + 12 * 3 + 4 * 3 + 8 * d.edges.len();
        // Each mask takes 5 bytes padded to 8.
        assert_eq!(b.len(), arrays + 8 + 8);
        assert_eq!(&b[arrays..arrays + 5], &[0, 1, 0, 0, 0]);
        assert_eq!(&b[arrays + 8..arrays + 13], &[1, 0, 0, 1, 1]);
        // Without a mask the frame is the plain one.
        assert_eq!(encode_masked(&d, 0, 2, None, None), encode(&d, 0, 2, None));
    }

    #[test]
    fn triangle_display_shares_edges() {
        let m = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE],
            triangles: vec![[0, 1, 2], [2, 1, 3]],
        };
        let d = display_triangles(&m);
        assert_eq!(d.edges.len(), 5);
        assert_eq!(d.faces, 2);
        let b = encode(&d, FLAG_PREVIEW, 1, Some(&[false, true, false, false]));
        assert_eq!(b.len() % 4, 0);
        assert_eq!(word(&b, 2), FLAG_PREVIEW | FLAG_VANISH);
    }
}
