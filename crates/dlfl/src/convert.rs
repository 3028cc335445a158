//! Conversion between polygon soups and the DLFL kernel.
//!
//! **Import** ([`to_dlfl`]) pairs each half-edge u→v of the soup with the
//! single v→u. What stays unpaired is boundary: each boundary loop is
//! closed by a face flagged as a *hole*, so the DLFL stays a closed
//! 2-manifold and the opening is written back out on export. Anything that
//! is not an orientable 2-manifold with boundary is an error naming the
//! offending edge or vertex, unless [`ImportOptions::split_nonmanifold`]
//! asks to cut it apart:
//! - an edge used by more than two faces, or twice in the same direction,
//!   is cut: none of its half-edges is paired, so each side becomes boundary;
//! - a vertex whose faces form several separate fans gets one copy per fan.
//!
//! **Export** ([`to_poly`]) writes the non-hole faces. Self-loops are
//! dropped from face lists (a Sierpinski hexagon with three zero-length
//! loops is written as the triangle it looks like), and faces left with
//! fewer than three corners (two-gons, point-spheres) are omitted; the
//! `.dlfl` format keeps all of them.

use crate::{BuildError, FaceId, Mesh, RawMesh, VertexId};
use glam::DVec3;

use holey_mesh::{PolyMesh, PolyMeshError};

const NONE: u32 = u32::MAX;

/// How to import a soup that is not a 2-manifold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// Cut non-manifold and misoriented edges, split non-manifold vertices
    /// into one copy per fan, and drop degenerate faces, instead of failing.
    pub split_nonmanifold: bool,
}

/// Why a soup cannot be imported into the kernel.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImportError {
    /// The soup itself is malformed (an index out of range, say), as its own
    /// check reports.
    #[error(transparent)]
    Soup(#[from] PolyMeshError),
    /// A face has fewer than two corners.
    #[error("face {face} has {len} corner(s); the kernel imports faces of 2 or more corners")]
    ShortFace {
        /// Index of the face in the soup.
        face: usize,
        /// Its number of corners (0 or 1).
        len: usize,
    },
    /// A face names the same vertex at two consecutive corners (cyclically),
    /// which would make a zero-length edge.
    #[error("face {face} repeats vertex {vertex} at consecutive corners (a zero-length edge)")]
    DegenerateFace {
        /// Index of the face in the soup.
        face: usize,
        /// Soup index of the repeated vertex.
        vertex: u32,
    },
    /// An edge has more than two face sides (half-edges, in either
    /// direction), so no single pairing of its sides exists.
    #[error(
        "non-manifold edge between vertices {u} and {v}: it is used by {count} face sides (faces {faces:?}); \
         split it with --split-nonmanifold"
    )]
    NonManifoldEdge {
        /// One end of the edge: where its half-edge with the smallest corner
        /// index starts. In [`to_dlfl`] vertices are numbered among the
        /// referenced ones only, which is the soup index unless an unused
        /// vertex comes before it.
        u: u32,
        /// The other end of the edge, numbered as `u` is.
        v: u32,
        /// Number of half-edges along the edge, both directions counted.
        count: usize,
        /// The face of each of those half-edges, sorted (a face appears
        /// once per side it contributes).
        faces: Vec<usize>,
    },
    /// Two face sides run along an edge in the same direction, so the faces
    /// around it are not consistently oriented.
    #[error(
        "faces {faces:?} all use edge {u}→{v} in the same direction, so the surface is not consistently oriented; \
         split it with --split-nonmanifold"
    )]
    Misoriented {
        /// Start of the doubled half-edge u→v, numbered as the `u` of
        /// `NonManifoldEdge` is.
        u: u32,
        /// End of the doubled half-edge u→v, numbered like `u`.
        v: u32,
        /// The faces of the two half-edges, sorted.
        faces: Vec<usize>,
    },
    /// The faces around a vertex form several separate fans (they touch only
    /// at the vertex), so it has no single disk neighbourhood.
    #[error(
        "non-manifold vertex {vertex} at ({x}, {y}, {z}): its faces form {fans} separate fans; \
         split it with --split-nonmanifold"
    )]
    NonManifoldVertex {
        /// Soup index of the vertex.
        vertex: u32,
        /// Number of separate fans of faces around it (2 or more).
        fans: usize,
        /// x coordinate of the vertex.
        x: f64,
        /// y coordinate of the vertex.
        y: f64,
        /// z coordinate of the vertex.
        z: f64,
    },
    /// From [`infer_edges`]: a half-edge has no partner running the other
    /// way (`.dlfl` files make boundaries explicit with hole faces).
    #[error("corner {corner} of face {face} has no partner edge running the other way")]
    Unpaired {
        /// Index of the face holding the unpaired half-edge.
        face: usize,
        /// Position within that face, from 0, of the corner the half-edge
        /// starts at.
        corner: usize,
    },
    /// The paired arrays failed [`Mesh::from_raw`]; a bug in the importer
    /// rather than a property of the input.
    #[error("internal: the paired soup did not build a valid DLFL: {0}")]
    Build(#[from] BuildError),
}

/// What [`to_dlfl`] did besides building the mesh.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ImportReport {
    /// Boundary loops closed by hole faces.
    pub holes: usize,
    /// Edges cut because they were non-manifold or misoriented.
    pub cut_edges: usize,
    /// Extra vertex copies made to split non-manifold vertices.
    pub split_vertices: usize,
    /// Faces dropped because they were degenerate.
    pub dropped_faces: usize,
    /// Soup vertices no face refers to (not imported).
    pub unreferenced_vertices: usize,
}

/// A soup imported into the kernel.
#[derive(Clone, Debug)]
pub struct Imported {
    /// The imported mesh, boundary loops closed by hole faces.
    pub mesh: Mesh,
    /// The DLFL face of each soup face, in file order (`None` if dropped).
    pub faces: Vec<Option<FaceId>>,
    /// The DLFL vertex of each soup vertex (`None` if unreferenced). A
    /// split vertex maps to its first copy.
    pub vertices: Vec<Option<VertexId>>,
    /// Counts of what the import cut, split, closed or dropped.
    pub report: ImportReport,
}

/// Half-edge pairing of faces in compressed rows. Corner `c` (a position in
/// `indices`) starts the half-edge from `indices[c]` to the next corner's vertex.
struct Pairing {
    /// Partner corner of each corner's half-edge, or `NONE` if unpaired.
    twin: Vec<u32>,
    cut_edges: usize,
}

fn face_of_corner(offsets: &[u32], c: u32) -> usize {
    offsets.partition_point(|&o| o <= c) - 1
}

/// Successor of each corner within its face.
fn next_corners(offsets: &[u32]) -> Vec<u32> {
    let n = offsets.last().copied().unwrap_or(0) as usize;
    let mut next = vec![0u32; n];
    for w in offsets.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        for c in lo..hi {
            next[c as usize] = if c + 1 == hi { lo } else { c + 1 };
        }
    }
    next
}

/// Pairs half-edges u→v with v→u. An undirected edge with exactly one
/// half-edge each way is paired; one with a single half-edge is boundary;
/// anything else is an error, or cut (left unpaired) when `cut` is set.
fn pair_half_edges(
    offsets: &[u32],
    indices: &[u32],
    next: &[u32],
    nverts: usize,
    cut: bool,
) -> Result<Pairing, ImportError> {
    let nc = indices.len();
    // Half-edges grouped by origin vertex (compressed rows).
    let mut start = vec![0u32; nverts + 1];
    for &u in indices {
        start[u as usize + 1] += 1;
    }
    for i in 0..nverts {
        start[i + 1] += start[i];
    }
    // Each row holds (corner, target vertex) so that scanning a row reads
    // one contiguous run instead of chasing `next` per entry.
    let mut fill = start.clone();
    let mut out = vec![(0u32, 0u32); nc];
    for (c, &u) in indices.iter().enumerate() {
        out[fill[u as usize] as usize] = (c as u32, indices[next[c] as usize]);
        fill[u as usize] += 1;
    }
    let outgoing = |u: u32| &out[start[u as usize] as usize..start[u as usize + 1] as usize];

    let mut twin = vec![NONE; nc];
    let mut cut_edges = 0;
    let mut same = Vec::new();
    let mut back = Vec::new();
    // Visit corners row by row (by origin vertex) so the row of u is hot.
    for &(c, v) in &out {
        let u = indices[c as usize];
        same.clear();
        back.clear();
        same.extend(
            outgoing(u)
                .iter()
                .filter(|&&(_, t)| t == v)
                .map(|&(d, _)| d),
        );
        back.extend(
            outgoing(v)
                .iter()
                .filter(|&&(_, t)| t == u)
                .map(|&(d, _)| d),
        );
        // Decide each undirected edge once, from its smallest corner.
        if same.iter().chain(&back).any(|&d| d < c) {
            continue;
        }
        match (same.len(), back.len()) {
            (1, 1) => {
                twin[c as usize] = back[0];
                twin[back[0] as usize] = c;
            }
            (1, 0) => {}
            (s, b) => {
                if cut {
                    cut_edges += 1;
                    continue;
                }
                let mut faces: Vec<usize> = same
                    .iter()
                    .chain(&back)
                    .map(|&d| face_of_corner(offsets, d))
                    .collect();
                faces.sort_unstable();
                return Err(if s + b > 2 {
                    ImportError::NonManifoldEdge {
                        u,
                        v,
                        count: s + b,
                        faces,
                    }
                } else {
                    ImportError::Misoriented { u, v, faces }
                });
            }
        }
    }
    Ok(Pairing { twin, cut_edges })
}

impl Mesh {
    /// The kernel mesh of the polygons `faces` (vertex indices, any size,
    /// counter-clockwise seen from outside) over `positions`: boundary
    /// loops become hole faces, and input that is not an orientable
    /// 2-manifold is refused naming the face or edge ([`to_dlfl`] with
    /// default options).
    ///
    /// ```
    /// use holey_dlfl::{DVec3, Mesh};
    ///
    /// // A tetrahedron: V − E + F = 4 − 6 + 4 = 2, genus 0.
    /// let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    /// let m = Mesh::from_polygons(p.to_vec(), [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])?;
    /// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count(), m.genus()), (4, 6, 4, 0));
    /// // An edge used twice the same way is refused, not guessed.
    /// assert!(Mesh::from_polygons(p.to_vec(), [[0u32, 1, 2], [0, 1, 3]]).is_err());
    /// # Ok::<(), holey_dlfl::convert::ImportError>(())
    /// ```
    pub fn from_polygons<F: AsRef<[u32]>>(
        positions: Vec<DVec3>,
        faces: impl IntoIterator<Item = F>,
    ) -> Result<Mesh, ImportError> {
        let soup = PolyMesh::from_faces(positions, faces);
        to_dlfl(&soup, ImportOptions::default()).map(|imported| imported.mesh)
    }
}

/// Imports a soup into the kernel. See the module documentation.
///
/// Faces keep file order: soup face `i` becomes `imported.faces[i]`, which
/// is also [`Mesh::face_at`]`(i)` when no face was dropped; holes follow.
/// Each face's walk starts at its first corner.
pub fn to_dlfl(soup: &PolyMesh, options: ImportOptions) -> Result<Imported, ImportError> {
    soup.check()?;
    let split = options.split_nonmanifold;
    let mut report = ImportReport::default();

    // Faces to import: validate, or clean up in split mode.
    let FacesToImport {
        offsets,
        mut indices,
        kept,
    } = faces_to_import(soup, split, &mut report)?;

    // Compact referenced vertices, keeping index order.
    let (mut positions, mut original) = compact_vertices(soup, &mut indices, &mut report);

    let next = next_corners(&offsets);
    let nc = indices.len();
    let mut prev = vec![0u32; nc];
    for (c, &n) in next.iter().enumerate() {
        prev[n as usize] = c as u32;
    }
    let pairing = pair_half_edges(&offsets, &indices, &next, positions.len(), split)?;
    report.cut_edges = pairing.cut_edges;
    let twin = pairing.twin;

    // Fans, and one vertex per fan.
    let mut fans = find_fans(&indices, &next, &prev, &twin);
    split_fans(&mut fans, &mut positions, &mut original, split, &mut report)?;
    for (u, &fan) in indices.iter_mut().zip(&fans.fan) {
        *u = fans.target[fan as usize];
    }

    // Hole corners.
    let raw = close_holes(
        positions,
        offsets,
        indices,
        &twin,
        &prev,
        &fans,
        &mut report,
    );

    let mesh = Mesh::from_raw(&raw)?;
    Ok(imported(
        mesh,
        &kept,
        &original,
        soup.positions.len(),
        report,
    ))
}

/// The faces of a soup to import, in compressed rows.
struct FacesToImport {
    /// Where each face's corners start in `indices`, then their end.
    offsets: Vec<u32>,
    /// The soup vertex of each corner.
    indices: Vec<u32>,
    /// Whether each soup face was kept.
    kept: Vec<bool>,
}

/// The faces of `soup` to import: each face is validated, or with
/// `split` cleaned up (repeated vertices merged) or dropped (counted in
/// `report`).
fn faces_to_import(
    soup: &PolyMesh,
    split: bool,
    report: &mut ImportReport,
) -> Result<FacesToImport, ImportError> {
    let mut offsets = vec![0u32];
    let mut indices: Vec<u32> = Vec::with_capacity(soup.face_indices.len());
    let mut kept = Vec::with_capacity(soup.face_count());
    let mut scratch = Vec::new();
    for (f, face) in soup.faces().enumerate() {
        scratch.clear();
        scratch.extend_from_slice(face);
        let repeat = (0..scratch.len())
            .find(|&k| scratch.len() > 1 && scratch[k] == scratch[(k + 1) % scratch.len()]);
        if let Some(k) = repeat {
            if !split {
                return Err(ImportError::DegenerateFace {
                    face: f,
                    vertex: scratch[k],
                });
            }
            scratch.dedup();
            while scratch.len() > 1 && scratch.first() == scratch.last() {
                scratch.pop();
            }
        }
        if scratch.len() < 2 || (split && scratch.len() < 3) {
            if !split {
                return Err(ImportError::ShortFace {
                    face: f,
                    len: scratch.len(),
                });
            }
            report.dropped_faces += 1;
            kept.push(false);
            continue;
        }
        indices.extend_from_slice(&scratch);
        offsets.push(indices.len() as u32);
        kept.push(true);
    }
    Ok(FacesToImport {
        offsets,
        indices,
        kept,
    })
}

/// Renumbers `indices` to the soup vertices they refer to, keeping index
/// order; returns those vertices' positions and soup indices, and counts
/// the others in `report`.
fn compact_vertices(
    soup: &PolyMesh,
    indices: &mut [u32],
    report: &mut ImportReport,
) -> (Vec<DVec3>, Vec<u32>) {
    let nv_soup = soup.positions.len();
    let mut compact = vec![NONE; nv_soup];
    for &u in indices.iter() {
        compact[u as usize] = 0;
    }
    let mut positions = Vec::new();
    let mut original = Vec::new();
    for (u, slot) in compact.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = positions.len() as u32;
            positions.push(soup.positions[u]);
            original.push(u as u32);
        }
    }
    report.unreferenced_vertices = nv_soup - positions.len();
    for u in indices.iter_mut() {
        *u = compact[*u as usize];
    }
    (positions, original)
}

/// The fans of corners around the vertices, and the vertex each becomes.
struct Fans {
    /// The fan of each corner.
    fan: Vec<u32>,
    /// The vertex of each fan.
    vertex: Vec<u32>,
    /// (start, end) corners of each open fan, in fan order.
    end_of_start: Vec<(u32, u32)>,
    /// The output vertex of each fan (filled by [`split_fans`]).
    target: Vec<u32>,
}

/// Groups the corners into fans. rot(c) = next(twin(c)) is the rotation
/// successor of corner c around its vertex; it is undefined where c's
/// half-edge is boundary. A fan starts at a corner whose incoming
/// half-edge is boundary; the open fans come first, then the closed ones.
fn find_fans(indices: &[u32], next: &[u32], prev: &[u32], twin: &[u32]) -> Fans {
    let nc = indices.len();
    let mut fan = vec![NONE; nc];
    let mut fan_vertex: Vec<u32> = Vec::new(); // fan id -> vertex
    let mut fan_end_of_start: Vec<(u32, u32)> = Vec::new(); // (start, end) of open fans
    for s in 0..nc as u32 {
        if twin[prev[s as usize] as usize] != NONE {
            continue;
        }
        let id = fan_vertex.len() as u32;
        fan_vertex.push(indices[s as usize]);
        let mut c = s;
        loop {
            fan[c as usize] = id;
            let t = twin[c as usize];
            if t == NONE {
                break;
            }
            c = next[t as usize];
        }
        fan_end_of_start.push((s, c));
    }
    for s in 0..nc as u32 {
        if fan[s as usize] != NONE {
            continue;
        }
        let id = fan_vertex.len() as u32;
        fan_vertex.push(indices[s as usize]);
        let mut c = s;
        while fan[c as usize] == NONE {
            fan[c as usize] = id;
            c = next[twin[c as usize] as usize];
        }
    }
    Fans {
        fan,
        vertex: fan_vertex,
        end_of_start: fan_end_of_start,
        target: Vec::new(),
    }
}

/// One vertex per fan: the first fan of a vertex keeps it, later fans
/// are non-manifold and get copies (appended to `positions` and
/// `original`, counted in `report`) with `split`, or fail. Sets
/// `fans.target`.
fn split_fans(
    fans: &mut Fans,
    positions: &mut Vec<DVec3>,
    original: &mut Vec<u32>,
    split: bool,
    report: &mut ImportReport,
) -> Result<(), ImportError> {
    let fan_vertex = &fans.vertex;
    let mut fans_per_vertex = vec![0u32; positions.len()];
    let mut fan_target = vec![NONE; fan_vertex.len()];
    for (id, &v) in fan_vertex.iter().enumerate() {
        fans_per_vertex[v as usize] += 1;
        if fans_per_vertex[v as usize] == 1 {
            fan_target[id] = v;
        }
    }
    if !split && let Some(v) = fans_per_vertex.iter().position(|&n| n > 1) {
        let p = positions[v];
        return Err(ImportError::NonManifoldVertex {
            vertex: original[v],
            fans: fans_per_vertex[v] as usize,
            x: p.x,
            y: p.y,
            z: p.z,
        });
    }
    for (id, &v) in fan_vertex.iter().enumerate() {
        if fan_target[id] == NONE {
            fan_target[id] = positions.len() as u32;
            positions.push(positions[v as usize]);
            original.push(original[v as usize]);
            report.split_vertices += 1;
        }
    }
    fans.target = fan_target;
    Ok(())
}

/// The mesh to build: the faces, their paired edges, and a hole face
/// closing each boundary loop (counted in `report`).
///
/// Hole corners: one per open fan, at the fan's vertex, keyed by the
/// boundary corner that ends the fan. The hole runs u→w against the
/// boundary half-edge w→u that enters the fan's start s (from prev(s)),
/// pairs with it, and continues at the hole corner of prev(s)'s fan.
fn close_holes(
    positions: Vec<DVec3>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    twin: &[u32],
    prev: &[u32],
    fans: &Fans,
    report: &mut ImportReport,
) -> RawMesh {
    let nc = indices.len();
    let fan_end_of_start = &fans.end_of_start;
    let mut hole_of_end = vec![NONE; nc];
    for (k, &(_, end)) in fan_end_of_start.iter().enumerate() {
        hole_of_end[end as usize] = k as u32;
    }
    let nh = fan_end_of_start.len();
    let mut hole_next = vec![NONE; nh];
    let mut hole_partner = vec![NONE; nh];
    for (k, &(s, _)) in fan_end_of_start.iter().enumerate() {
        let p = prev[s as usize];
        hole_partner[k] = p;
        hole_next[k] = hole_of_end[p as usize];
    }
    let mut raw = RawMesh {
        positions,
        face_offsets: offsets,
        face_vertices: indices,
        holes: Vec::new(),
        edges: Vec::with_capacity(nc / 2 + nh),
    };
    for c in 0..nc as u32 {
        let t = twin[c as usize];
        if t != NONE && c < t {
            raw.edges.push([c, t]);
        }
    }
    let nfaces = raw.face_count();
    let mut placed = vec![NONE; nh];
    for k0 in 0..nh {
        if placed[k0] != NONE {
            continue;
        }
        let mut k = k0;
        while placed[k] == NONE {
            let corner = raw.face_vertices.len() as u32;
            placed[k] = corner;
            let end = fan_end_of_start[k].1;
            raw.face_vertices
                .push(fans.target[fans.fan[end as usize] as usize]);
            k = hole_next[k] as usize;
        }
        raw.face_offsets.push(raw.face_vertices.len() as u32);
        report.holes += 1;
    }
    for k in 0..nh {
        raw.edges.push([placed[k], hole_partner[k]]);
    }
    if report.holes > 0 {
        raw.holes = vec![false; raw.face_count()];
        raw.holes[nfaces..].fill(true);
    }
    raw
}

/// The import's result: `mesh`, with the DLFL face of each soup face
/// (`kept` says which were) and the DLFL vertex of each of the `nv_soup`
/// soup vertices (its first copy, from `original`).
fn imported(
    mesh: Mesh,
    kept: &[bool],
    original: &[u32],
    nv_soup: usize,
    report: ImportReport,
) -> Imported {
    let mut face_ids = Vec::with_capacity(kept.len());
    let mut next_face = 0usize;
    for &k in kept {
        if k {
            face_ids.push(mesh.face_at(next_face));
            next_face += 1;
        } else {
            face_ids.push(None);
        }
    }
    let mut vertices = vec![None; nv_soup];
    for (i, &o) in original.iter().enumerate() {
        if vertices[o as usize].is_none() {
            vertices[o as usize] = mesh.vertex_at(i);
        }
    }
    Imported {
        mesh,
        faces: face_ids,
        vertices,
        report,
    }
}

/// Fills in `raw.edges` by pairing half-edges, for a `.dlfl` file written
/// without `e` lines. Every half-edge must have exactly one partner
/// running the other way (holes are explicit in `.dlfl`), and the faces
/// must be free of multiple edges between the same two vertices.
pub fn infer_edges(raw: &mut RawMesh) -> Result<(), ImportError> {
    let nv = raw.positions.len();
    if let Some(&index) = raw.face_vertices.iter().find(|&&u| u as usize >= nv) {
        let face = face_of_corner(
            &raw.face_offsets,
            raw.face_vertices
                .iter()
                .position(|&u| u == index)
                .unwrap_or(0) as u32,
        );
        return Err(PolyMeshError::IndexOutOfRange {
            face,
            index,
            count: nv,
        }
        .into());
    }
    let next = next_corners(&raw.face_offsets);
    let pairing = pair_half_edges(&raw.face_offsets, &raw.face_vertices, &next, nv, false)?;
    raw.edges.clear();
    for (c, &t) in pairing.twin.iter().enumerate() {
        let c = c as u32;
        if t == NONE {
            let f = face_of_corner(&raw.face_offsets, c);
            if raw.face_offsets[f + 1] - raw.face_offsets[f] == 1 {
                continue; // a point-sphere's corner starts no edge
            }
            return Err(ImportError::Unpaired {
                face: f,
                corner: (c - raw.face_offsets[f]) as usize,
            });
        }
        if c < t {
            raw.edges.push([c, t]);
        }
    }
    Ok(())
}

/// What [`to_poly`] left out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Exported {
    /// The written soup: the non-hole faces with self-loops removed, over
    /// the vertices they use.
    pub poly: PolyMesh,
    /// The DLFL face each written face came from, in output order.
    pub faces: Vec<FaceId>,
    /// Self-loop corners dropped from face lists.
    pub dropped_self_loops: usize,
    /// Faces omitted because fewer than 3 corners were left (two-gons,
    /// point-spheres, faces made only of self-loops).
    pub dropped_faces: usize,
}

/// Exports the non-hole faces of a DLFL as a soup, in face slot order.
/// Self-loops are removed from face lists and faces with fewer than three
/// corners left are omitted (see the module documentation). Vertices are
/// numbered in slot order among those the written faces use.
pub fn to_poly(mesh: &Mesh) -> Exported {
    let mut out = Exported::default();
    let mut index = vec![NONE; mesh.vertices().last().map_or(0, |v| v.index() + 1)];
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(mesh.face_count());
    let mut face_ids = Vec::with_capacity(mesh.face_count());
    let mut list = Vec::new();
    for f in mesh.surface_faces() {
        list.clear();
        if let Ok(corners) = mesh.face_corners(f) {
            list.extend(corners.filter_map(|c| mesh.corner_vertex(c).ok()));
        }
        let before = list.len();
        list.dedup();
        while list.len() > 1 && list.first() == list.last() {
            list.pop();
        }
        let loops = before - list.len();
        if list.len() < 3 {
            out.dropped_faces += 1;
            continue;
        }
        out.dropped_self_loops += loops;
        faces.push(list.iter().map(|v| v.index() as u32).collect());
        face_ids.push(f);
    }
    for face in &faces {
        for &v in face {
            index[v as usize] = 0;
        }
    }
    let mut positions = Vec::new();
    for v in mesh.vertices() {
        if index[v.index()] == 0 {
            index[v.index()] = positions.len() as u32;
            positions.push(mesh.position(v).unwrap_or(DVec3::ZERO));
        }
    }
    for face in &mut faces {
        for v in face.iter_mut() {
            *v = index[*v as usize];
        }
    }
    out.poly = PolyMesh::from_faces(positions, faces);
    out.faces = face_ids;
    out
}

#[cfg(test)]
mod tests;
