//! Binary mesh frames: what the browser draws, in the layout
//! `web/PROTOCOL.md` specifies (little-endian, 4-byte aligned sections).
//!
//! A frame carries display indices. For a DLFL the server keeps the
//! handles behind them ([`ModelIndex`]) so that a click on face 12 of the
//! picture names the same face when the request comes back.

use glam::DVec3;
use holey_dlfl::{EdgeId, FaceId, Mesh, VertexId};
use holey_mesh::slots::fill_holes;
use holey_mesh::tri::sides_by_edge;
use holey_topo::TriMesh;
use rustc_hash::FxHashMap;

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
/// Frame flag: a connectivity patch of the previous frame (see
/// [`encode_patch`]): the vertices, triangles and edges whose slots changed.
pub const FLAG_PATCH: u32 = 32;

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
    /// Whether this triangle display shows `mesh` exactly: its vertices
    /// at the mesh's positions and its triangles the mesh's, slot for
    /// slot. A stroke whose frames kept a display so (patches, whole
    /// frames) ends with one that shows the mesh it commits.
    pub fn shows(&self, mesh: &TriMesh) -> bool {
        self.faces == mesh.triangles.len()
            && self.positions == mesh.positions
            && self.triangles == mesh.triangles
    }

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
    for f in mesh.surface_faces() {
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
    // Every side by its edge's key (smaller end, larger end), in key
    // order: a counting sort and parallel sorts of each vertex's few
    // sides, where one sort of all 3n sides took a quarter of a second
    // on a million triangles, at every stroke frame that sent the whole
    // mesh.
    let mut edges: Vec<[u32; 2]> = sides_by_edge(&mesh.triangles)
        .into_iter()
        .map(|(key, _)| [(key >> 32) as u32, key as u32])
        .collect();
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

/// A frame that commits what the tabs already show as `version`:
/// positions only, sparse, with no vertex moved, and not a preview
/// (`web/PROTOCOL.md`, "A commit frame"). A stroke whose frames left every
/// tab showing the document's display slot for slot
/// ([`crate::doc::Document::commit_shown`]) ends with it instead of the
/// whole mesh, which on a million triangles is 38 MB every tab holds
/// already. It clears a vanish mask, as any frame without one does; a tab
/// whose counts differ cannot apply it and asks for the whole mesh.
pub fn encode_commit(display: &Display, version: u64) -> Vec<u8> {
    let mut out = Vec::with_capacity(36);
    header(
        &mut out,
        FLAG_POSITIONS_ONLY | FLAG_SPARSE,
        version,
        display.counts(display.positions.len()),
        None,
    );
    put(&mut out, 0);
    out
}

/// The slots of a triangle mesh's display that changed from one frame to
/// the next: what a patch frame carries (each list ascending).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Patch {
    /// The counts the patch starts from: vertices, triangles, edges.
    pub before: [usize; 3],
    /// Vertices whose position changed, and every new one.
    pub vertices: Vec<u32>,
    /// Triangle slots whose corners changed, and every new one.
    pub triangles: Vec<u32>,
    /// Edge slots whose endpoints changed, and every new one.
    pub edges: Vec<u32>,
}

/// The edges of a triangle display by endpoints (smaller first): their
/// slot in [`Display::edges`] and how many triangles have them. Kept
/// across a stroke's frames, so an edge keeps its slot while it lives.
#[derive(Clone, Debug, Default)]
pub struct EdgeBook {
    edges: FxHashMap<[u32; 2], (u32, u32)>,
}

fn edge_key(a: u32, b: u32) -> [u32; 2] {
    if a < b { [a, b] } else { [b, a] }
}

fn triangle_edges([a, b, c]: [u32; 3]) -> [[u32; 2]; 3] {
    [edge_key(a, b), edge_key(b, c), edge_key(c, a)]
}

impl EdgeBook {
    /// The book of a triangle display (its edges those of its triangles,
    /// as [`display_triangles`] makes them, in any order); `None` when the
    /// edge list is not that.
    pub fn of(display: &Display) -> Option<EdgeBook> {
        let mut edges: FxHashMap<[u32; 2], (u32, u32)> =
            FxHashMap::with_capacity_and_hasher(display.edges.len(), Default::default());
        for (slot, e) in display.edges.iter().enumerate() {
            if edges
                .insert(edge_key(e[0], e[1]), (slot as u32, 0))
                .is_some()
            {
                return None;
            }
        }
        for &t in &display.triangles {
            for e in triangle_edges(t) {
                edges.get_mut(&e)?.1 += 1;
            }
        }
        edges
            .values()
            .all(|&(_, n)| n > 0)
            .then_some(EdgeBook { edges })
    }
}

/// Turns `display` (a triangle display, as [`display_triangles`] makes
/// it, whose edge slots `book` records) into the display of `mesh`,
/// keeping every slot whose content survived: triangles and vertices
/// stay where the mesh has them, an edge keeps its slot while it lives,
/// new edges take the slots of removed ones, and the last edges move
/// into the slots left over. Returns the slots that changed, or `None`
/// (leaving both unchanged) when more than `max_share` of the mesh's
/// vertices or triangles changed: a whole frame is then the better deal.
pub fn patch_triangles(
    display: &mut Display,
    book: &mut EdgeBook,
    mesh: &TriMesh,
    max_share: f64,
) -> Option<Patch> {
    let changed = changed_slots(display, mesh, max_share)?;
    patch_changed(display, book, mesh, changed)
}

/// The vertex and triangle slots of `display` whose content `mesh`
/// changes, and every new one; `None` when more than `max_share` of the
/// mesh's vertices or triangles changed ([`patch_triangles`]'s first
/// step). It needs no [`EdgeBook`]: a caller without one learns here,
/// before building it (a hash of every edge, a sixth of a second on a
/// million triangles), whether a patch can be made at all.
pub fn changed_slots(display: &Display, mesh: &TriMesh, max_share: f64) -> Option<ChangedSlots> {
    let (nv0, nv1) = (display.positions.len(), mesh.positions.len());
    let (nt0, nt1) = (display.triangles.len(), mesh.triangles.len());
    let vertices: Vec<u32> = (0..nv1)
        .filter(|&i| i >= nv0 || display.positions[i] != mesh.positions[i])
        .map(|i| i as u32)
        .collect();
    let triangles: Vec<u32> = (0..nt1)
        .filter(|&i| i >= nt0 || display.triangles[i] != mesh.triangles[i])
        .map(|i| i as u32)
        .collect();
    let too_many = |n: usize, of: usize| n as f64 > max_share * of.max(1) as f64;
    if too_many(vertices.len(), nv1) || too_many(triangles.len() + nt0.saturating_sub(nt1), nt1) {
        return None;
    }
    Some(ChangedSlots {
        vertices,
        triangles,
    })
}

/// What [`changed_slots`] found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChangedSlots {
    vertices: Vec<u32>,
    triangles: Vec<u32>,
}

/// [`patch_triangles`] once its slots are known.
pub fn patch_changed(
    display: &mut Display,
    book: &mut EdgeBook,
    mesh: &TriMesh,
    changed: ChangedSlots,
) -> Option<Patch> {
    let ChangedSlots {
        vertices,
        triangles,
    } = changed;
    let (nv0, nt0, nt1) = (
        display.positions.len(),
        display.triangles.len(),
        mesh.triangles.len(),
    );
    let before = [nv0, nt0, display.edges.len()];
    // Edge counts: the old triangles of the changed slots (and of the
    // slots dropped) out, the new ones in.
    let mut delta: FxHashMap<[u32; 2], i64> = FxHashMap::default();
    let old = triangles
        .iter()
        .map(|&i| i as usize)
        .filter(|&i| i < nt0)
        .chain(nt1..nt0);
    for i in old {
        for e in triangle_edges(display.triangles[i]) {
            *delta.entry(e).or_default() -= 1;
        }
    }
    for &i in &triangles {
        for e in triangle_edges(mesh.triangles[i as usize]) {
            *delta.entry(e).or_default() += 1;
        }
    }
    let mut freed = Vec::new();
    let mut added = Vec::new();
    for (e, d) in delta {
        if d == 0 {
            continue;
        }
        match book.edges.get_mut(&e) {
            Some((slot, n)) => {
                let left = i64::from(*n) + d;
                if left <= 0 {
                    freed.push(*slot);
                    book.edges.remove(&e);
                } else {
                    *n = left as u32;
                }
            }
            None if d > 0 => added.push((e, d as u32)),
            // An edge no triangle had cannot lose one; the book is wrong.
            None => return None,
        }
    }
    freed.sort_unstable();
    added.sort_unstable();
    let mut edges = Vec::with_capacity(freed.len().max(added.len()));
    let mut free = freed.into_iter();
    for (e, n) in added {
        let slot = match free.next() {
            Some(slot) => {
                display.edges[slot as usize] = e;
                slot
            }
            None => {
                display.edges.push(e);
                (display.edges.len() - 1) as u32
            }
        };
        book.edges.insert(e, (slot, n));
        edges.push(slot);
    }
    // Slots still free: the last edges move into them.
    let holes: Vec<u32> = free.collect();
    let mut moves = Vec::new();
    fill_holes(&mut display.edges, &holes, |_, to| moves.push(to as u32));
    for h in moves {
        if let Some(entry) = book.edges.get_mut(&display.edges[h as usize]) {
            entry.0 = h;
        }
        edges.push(h);
    }
    let len = display.edges.len();
    edges.retain(|&s| (s as usize) < len);
    edges.sort_unstable();
    edges.dedup();
    display.positions.clone_from(&mesh.positions);
    display.triangles.clone_from(&mesh.triangles);
    display.triangle_face = (0..nt1 as u32).collect();
    display.faces = nt1;
    Some(Patch {
        before,
        vertices,
        triangles,
        edges,
    })
}

/// A patch frame ([`FLAG_PATCH`]): the header's counts are the new
/// display's; then the counts it applies to (vertices, triangles,
/// edges), the changed vertices (count, indices, positions), triangle
/// slots (count, indices, corners, faces) and edge slots (count,
/// indices, endpoints), and with `masked` (the sculpt mask of the listed
/// vertices, in their order; none when none is masked) a byte per
/// listed vertex.
pub fn encode_patch(
    display: &Display,
    patch: &Patch,
    flags: u32,
    version: u64,
    masked: Option<&[bool]>,
) -> Vec<u8> {
    let nv = display.positions.len();
    let (k, m, q) = (
        patch.vertices.len(),
        patch.triangles.len(),
        patch.edges.len(),
    );
    let flags = (flags
        | FLAG_PATCH
        | if masked.is_some() {
            FLAG_SCULPT_MASK
        } else {
            0
        })
        & !(FLAG_POSITIONS_ONLY | FLAG_SPARSE);
    let mut out = Vec::with_capacity(60 + 16 * k + 20 * m + 12 * q + k + 4);
    header(&mut out, flags, version, display.counts(nv), None);
    for c in patch.before {
        put(&mut out, c as u32);
    }
    put(&mut out, k as u32);
    for &v in &patch.vertices {
        put(&mut out, v);
    }
    for &v in &patch.vertices {
        let p = display.positions[v as usize];
        for c in [p.x, p.y, p.z] {
            out.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    put(&mut out, m as u32);
    for &t in &patch.triangles {
        put(&mut out, t);
    }
    for &t in &patch.triangles {
        for v in display.triangles[t as usize] {
            put(&mut out, v);
        }
    }
    for &t in &patch.triangles {
        put(&mut out, display.triangle_face[t as usize]);
    }
    put(&mut out, q as u32);
    for &e in &patch.edges {
        put(&mut out, e);
    }
    for &e in &patch.edges {
        let [a, b] = display.edges[e as usize];
        put(&mut out, a);
        put(&mut out, b);
    }
    vanish_mask(&mut out, masked, k);
    out
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

    /// One section of a patch frame starting at word `*at`, as PROTOCOL.md
    /// lays out all three (positions, triangles, edges): a count `n`, the
    /// `n` slots it rewrites, then `words_per_slot · n` words of data.
    /// Gives the slots and the word where their data starts, and moves
    /// `*at` past the section, so the oracle reads the layout in one place.
    fn patch_section(b: &[u8], at: &mut usize, words_per_slot: usize) -> (Vec<usize>, usize) {
        let n = word(b, *at) as usize;
        let slots = (0..n).map(|j| word(b, *at + 1 + j) as usize).collect();
        let data = *at + 1 + n;
        *at = data + words_per_slot * n;
        (slots, data)
    }

    /// Applies a patch frame to what a page holds (`old`): an oracle
    /// written from the layout in PROTOCOL.md, apart from the encoder.
    /// Slots the patch must fill start as `u32::MAX`/NaN, so a new slot it
    /// forgot shows.
    fn apply_patch(old: &Display, b: &[u8]) -> Display {
        let flags = word(b, 2);
        assert_eq!(flags & FLAG_PATCH, FLAG_PATCH);
        assert_eq!(flags & (FLAG_POSITIONS_ONLY | FLAG_SPARSE | FLAG_VANISH), 0);
        let [nv, nt, ne, nf] = [4, 5, 6, 7].map(|i| word(b, i) as usize);
        assert_eq!(
            [word(b, 8), word(b, 9), word(b, 10)].map(|n| n as usize),
            [old.positions.len(), old.triangles.len(), old.edges.len()],
            "the counts the patch applies to"
        );
        let f32_at = |i: usize| f32::from_le_bytes(b[4 * i..4 * i + 4].try_into().unwrap());
        let mut d = old.clone();
        d.positions.resize(nv, DVec3::NAN);
        d.triangles.resize(nt, [u32::MAX; 3]);
        d.triangle_face.resize(nt, u32::MAX);
        d.edges.resize(ne, [u32::MAX; 2]);
        d.faces = nf;
        let mut at = 11;
        let (moved, data) = patch_section(b, &mut at, 3);
        for (j, &v) in moved.iter().enumerate() {
            let p = data + 3 * j;
            d.positions[v] = DVec3::new(
                f64::from(f32_at(p)),
                f64::from(f32_at(p + 1)),
                f64::from(f32_at(p + 2)),
            );
        }
        let (triangles, data) = patch_section(b, &mut at, 4);
        let faces_at = data + 3 * triangles.len();
        for (j, &t) in triangles.iter().enumerate() {
            let c = data + 3 * j;
            d.triangles[t] = [word(b, c), word(b, c + 1), word(b, c + 2)];
            d.triangle_face[t] = word(b, faces_at + j);
        }
        let (edges, data) = patch_section(b, &mut at, 2);
        for (j, &e) in edges.iter().enumerate() {
            let c = data + 2 * j;
            d.edges[e] = [word(b, c), word(b, c + 1)];
        }
        let mask_bytes = if flags & FLAG_SCULPT_MASK != 0 {
            moved.len().div_ceil(4) * 4
        } else {
            0
        };
        assert_eq!(b.len(), 4 * at + mask_bytes, "nothing after the sections");
        d
    }

    /// `d` shows `mesh` (positions to f32, every edge of a triangle once).
    fn shows(d: &Display, mesh: &TriMesh) {
        let f = |p: &DVec3| p.to_array().map(|c| c as f32);
        assert_eq!(
            d.positions.iter().map(f).collect::<Vec<_>>(),
            mesh.positions.iter().map(f).collect::<Vec<_>>()
        );
        assert_eq!(d.triangles, mesh.triangles);
        assert_eq!(
            d.triangle_face,
            (0..mesh.triangles.len() as u32).collect::<Vec<_>>()
        );
        assert_eq!(d.faces, mesh.triangles.len());
        let mut edges = d.edges.clone();
        edges.sort_unstable();
        assert_eq!(edges, display_triangles(mesh).edges, "the edge set");
    }

    fn f32_display(d: &Display) -> Display {
        let mut d = d.clone();
        for p in &mut d.positions {
            *p = p.as_vec3().as_dvec3();
        }
        d
    }

    #[test]
    fn remeshing_frames_travel_as_patches_a_page_can_apply() {
        use holey_sculpt::{Remesh, RemeshOptions, default_range, remesh_in_place};
        let mut mesh = holey_shapes::parse_primitive("@sphere:3")
            .unwrap()
            .triangulated();
        let base = default_range(&mesh).unwrap();
        let mut server = display_triangles(&mesh);
        let mut book = EdgeBook::of(&server).unwrap();
        // What the page holds: the whole frame's f32 positions.
        let mut page = f32_display(&server);
        let mut patches = 0;
        let (mut splits, mut collapses) = (0, 0);
        for frame in 0..12 {
            // A bump pushed out and back with edges kept short (splits)
            // then long (collapses) around the top, as a remeshing stroke.
            let centre = DVec3::new(0.3 * (frame as f64 * 0.5).sin(), 0.0, 1.0);
            let active: Vec<bool> = mesh
                .positions
                .iter()
                .map(|p| p.distance(centre) < 0.4)
                .collect();
            for (p, &a) in mesh.positions.iter_mut().zip(&active) {
                if a {
                    *p *= 1.0 + 0.03 * if frame < 6 { 1.0 } else { -1.0 };
                }
            }
            // Edges a little short of what the sphere has, then long.
            let scale = if frame < 6 { 0.6 } else { 2.0 };
            let (lo, hi) = (scale * base.min_edge, scale * base.max_edge);
            let r = remesh_in_place(
                &mut mesh,
                &active,
                &RemeshOptions::new(Remesh {
                    min_edge: lo,
                    max_edge: hi,
                }),
            )
            .unwrap();
            splits += r.splits;
            collapses += r.collapses;
            let Some(patch) = patch_triangles(&mut server, &mut book, &mesh, 0.25) else {
                // Too much changed: a whole frame, and a new book.
                server = display_triangles(&mesh);
                book = EdgeBook::of(&server).unwrap();
                page = f32_display(&server);
                continue;
            };
            patches += 1;
            shows(&server, &mesh);
            let bytes = encode_patch(&server, &patch, FLAG_PREVIEW, 9, None);
            assert_eq!(word(&bytes, 2), FLAG_PREVIEW | FLAG_PATCH);
            page = apply_patch(&page, &bytes);
            assert_eq!(
                page,
                f32_display(&server),
                "frame {frame}: the page holds the server's display"
            );
            shows(&page, &mesh);
            // Every list ascending, and small next to the mesh.
            for list in [&patch.vertices, &patch.triangles, &patch.edges] {
                assert!(list.windows(2).all(|w| w[0] < w[1]));
            }
            assert!(patch.triangles.len() * 4 <= mesh.triangles.len());
        }
        assert!(patches >= 6, "{patches} patches");
        assert!(
            splits > 0 && collapses > 0,
            "{splits} splits, {collapses} collapses"
        );
    }

    #[test]
    fn a_patch_lists_edge_slots_freed_refilled_and_moved() {
        // Two triangles, then one removed and one added elsewhere, then
        // the count shrinking: the edge book keeps what lives in place.
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE, DVec3::Z];
        let a = TriMesh {
            positions: p.clone(),
            triangles: vec![[0, 1, 2], [2, 1, 3], [0, 2, 4], [1, 0, 4]],
        };
        let mut server = display_triangles(&a);
        let mut book = EdgeBook::of(&server).unwrap();
        let mut page = server.clone();
        let steps = [
            TriMesh {
                positions: p.clone(),
                triangles: vec![[0, 1, 2], [2, 1, 3], [0, 2, 4], [3, 1, 4]],
            },
            TriMesh {
                positions: p[..4].to_vec(),
                triangles: vec![[0, 1, 2], [2, 1, 3]],
            },
            TriMesh {
                positions: [&p[..4], &[DVec3::NEG_ONE, DVec3::NEG_X]].concat(),
                triangles: vec![[0, 1, 2], [2, 1, 3], [0, 4, 5], [5, 4, 1], [2, 3, 5]],
            },
        ];
        for next in &steps {
            let patch = patch_triangles(&mut server, &mut book, next, 1.0).unwrap();
            shows(&server, next);
            page = apply_patch(&page, &encode_patch(&server, &patch, 0, 1, None));
            assert_eq!(page, server);
        }
        // The mask section: a byte per listed vertex, padded.
        let last = steps[2].clone();
        let mut with = TriMesh {
            positions: last.positions.clone(),
            triangles: last.triangles.clone(),
        };
        with.positions[4].x += 1.0;
        let patch = patch_triangles(&mut server, &mut book, &with, 1.0).unwrap();
        assert_eq!(
            (patch.vertices.clone(), patch.triangles.len()),
            (vec![4], 0)
        );
        let b = encode_patch(&server, &patch, 0, 1, Some(&[true]));
        assert_eq!(word(&b, 2), FLAG_PATCH | FLAG_SCULPT_MASK);
        assert_eq!(&b[b.len() - 4..], &[1, 0, 0, 0]);
        assert_eq!(apply_patch(&page, &b), f32_display(&server));
    }

    #[test]
    fn wholesale_renumbering_is_no_patch() {
        let m = holey_shapes::parse_primitive("@sphere:2")
            .unwrap()
            .triangulated();
        let mut server = display_triangles(&m);
        let mut book = EdgeBook::of(&server).unwrap();
        let mut reversed = m.clone();
        reversed.triangles.reverse();
        let before = server.clone();
        assert!(patch_triangles(&mut server, &mut book, &reversed, 0.25).is_none());
        assert_eq!(server, before, "left as it was");
        // Known without a book.
        assert!(changed_slots(&server, &reversed, 0.25).is_none());
        assert!(changed_slots(&server, &m, 0.25).is_some());
        // A model display (polygon edges, no fan diagonals) has no book.
        let cube = holey_dlfl::convert::to_dlfl(
            &holey_shapes::parse_primitive("@cube").unwrap(),
            Default::default(),
        )
        .unwrap()
        .mesh;
        assert!(EdgeBook::of(&display_model(&cube).0).is_none());
    }

    /// The display's edges are every triangle side's edge, once, in
    /// order of (smaller end, larger end): an independent sort of the
    /// sides, on a fan-triangulated sphere with degenerate triangles
    /// (a repeated corner) and an unused vertex.
    #[test]
    fn display_edges_are_the_sorted_distinct_sides() {
        let mut m = holey_shapes::parse_primitive("@sphere:3")
            .unwrap()
            .triangulated();
        m.triangles.push([5, 5, 9]);
        m.triangles.push([7, 3, 7]);
        m.positions.push(DVec3::splat(9.0));
        let mut sides: Vec<[u32; 2]> = m
            .triangles
            .iter()
            .flat_map(|&[a, b, c]| [[a, b], [b, c], [c, a]])
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        sides.sort();
        sides.dedup();
        assert_eq!(display_triangles(&m).edges, sides);
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
