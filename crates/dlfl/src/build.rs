//! Building a mesh from raw parts in one pass, and taking it apart again.
//!
//! This is the symbolic phase of loading a file: the caller has already
//! decided which corners pair up into edges, and the builder lays the
//! arrays out directly (no operator calls), then validates.

use glam::DVec3;
use holey_mesh::NonFinite;

use crate::arena::Arena;
use crate::mesh::{Corner, Edge, Face, Mesh, NONE, Vertex};
use crate::validate::ValidationError;

/// A DLFL as flat arrays, the form files store.
///
/// Corner `k` of face `f` has the global corner index
/// `face_offsets[f] + k`. Each entry of `edges` names the two corners at
/// which an edge originates; the edge of corner `c` runs from its vertex to
/// the vertex of the next corner of its face.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawMesh {
    /// Vertex positions, indexed by vertex number.
    pub positions: Vec<DVec3>,
    /// `faces + 1` offsets into `face_vertices`, starting at 0.
    pub face_offsets: Vec<u32>,
    /// The vertex index (into `positions`) of every corner, face after face
    /// in walk order; its positions are the global corner indices.
    pub face_vertices: Vec<u32>,
    /// One flag per face; an empty vector means no face is a hole.
    pub holes: Vec<bool>,
    /// One entry per edge: the global indices of the two corners at which
    /// it originates, one on each of its sides.
    pub edges: Vec<[u32; 2]>,
}

impl RawMesh {
    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_offsets.len().saturating_sub(1)
    }
    /// The vertex indices of face `f`.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_vertices[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }
    /// True if face `f` is a hole.
    pub fn is_hole(&self, f: usize) -> bool {
        self.holes.get(f).copied().unwrap_or(false)
    }

    /// Appends `other` as further components: its vertices, faces, hole
    /// flags and edges after this mesh's, renumbered (as
    /// `PolyMesh::append` does for soups). Refused, with this mesh
    /// unchanged, when the vertices or corners together would not fit the
    /// 32-bit indices; nothing else is checked here
    /// ([`crate::Mesh::from_raw`] checks the result).
    pub fn append(&mut self, other: &RawMesh) -> Result<(), BuildError> {
        for total in [
            self.positions.len() + other.positions.len(),
            self.face_vertices.len() + other.face_vertices.len(),
        ] {
            if total > u32::MAX as usize {
                return Err(BuildError::TooLarge(total));
            }
        }
        // Both totals fit in u32, so the shifts only saturate on indices
        // that were out of range already (and stay so for from_raw).
        let nv = self.positions.len() as u32;
        let nc = self.face_vertices.len() as u32;
        if !self.holes.is_empty() || !other.holes.is_empty() {
            let (mine, theirs) = (self.face_count(), other.face_count());
            self.holes.resize(mine, false);
            self.holes.extend((0..theirs).map(|f| other.is_hole(f)));
        }
        if self.face_offsets.is_empty() {
            self.face_offsets.push(0);
        }
        self.positions.extend_from_slice(&other.positions);
        self.face_vertices
            .extend(other.face_vertices.iter().map(|v| v.saturating_add(nv)));
        self.face_offsets.extend(
            other
                .face_offsets
                .iter()
                .skip(1)
                .map(|o| o.saturating_add(nc)),
        );
        self.edges
            .extend(other.edges.iter().map(|e| e.map(|c| c.saturating_add(nc))));
        Ok(())
    }
}

/// Why raw parts do not form a valid DLFL.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// `face_offsets` is malformed: it does not start at 0, does not end at
    /// the number of corners, or decreases; the text says which.
    #[error("face offsets are malformed: {0}")]
    Offsets(String),
    /// There are this many vertices, corners or edges, too many for the
    /// kernel's 32-bit slot indices.
    #[error("{0} entities exceed the kernel's 32-bit indices")]
    TooLarge(usize),
    /// `holes` is neither empty nor one flag per face.
    #[error("hole flags: {flags} given for {faces} faces")]
    HoleCount {
        /// Number of hole flags given (length of `holes`).
        flags: usize,
        /// Number of faces, as `face_offsets` defines them.
        faces: usize,
    },
    /// A face has no corners (two equal consecutive offsets).
    #[error("face {face} has no corners")]
    EmptyFace {
        /// Index of the empty face.
        face: usize,
    },
    /// A face refers to a vertex index past the end of `positions`.
    #[error("face {face} refers to vertex {vertex}, but there are only {count} vertices")]
    VertexOutOfRange {
        /// Index of the face holding the bad reference.
        face: usize,
        /// The out-of-range vertex index it refers to.
        vertex: u32,
        /// Number of vertices (length of `positions`).
        count: usize,
    },
    /// A vertex position has a NaN or infinite coordinate (the first such
    /// vertex, by its index in `positions`).
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// A vertex is not referred to by any face's corners.
    #[error("vertex {vertex} is not used by any face")]
    UnusedVertex {
        /// Index of the unused vertex (the first one found).
        vertex: usize,
    },
    /// An edge names a global corner index past the last corner.
    #[error("edge {edge} names corner {corner}, but there are only {count} corners")]
    CornerOutOfRange {
        /// Index of the edge in `edges`.
        edge: usize,
        /// The out-of-range global corner index it names.
        corner: u32,
        /// Number of corners (length of `face_vertices`).
        count: usize,
    },
    /// A corner is named by two edges, or twice by one edge; each corner
    /// starts at most one edge.
    #[error(
        "corner {corner} (face {face}, corner {k}) starts more than one edge (edges {first} and {second})"
    )]
    CornerTwice {
        /// Global index of the corner named more than once.
        corner: usize,
        /// Index of the face the corner belongs to.
        face: usize,
        /// Position of the corner within that face, from 0.
        k: usize,
        /// Index of the edge that named the corner first.
        first: usize,
        /// Index of the edge that named it again (equal to `first` when one
        /// edge names the same corner for both its sides).
        second: usize,
    },
    /// A corner of a face with more than one corner starts no edge; only the
    /// single corner of a point-sphere may be edgeless.
    #[error(
        "corner {corner} (face {face}, corner {k}) starts no edge, but only a point-sphere's corner may"
    )]
    CornerWithoutEdge {
        /// Global index of the edgeless corner.
        corner: usize,
        /// Index of the face the corner belongs to.
        face: usize,
        /// Position of the corner within that face, from 0.
        k: usize,
    },
    /// An edge's two corners are not opposite sides of one edge: the vertex
    /// after one of them in its face is not the other corner's vertex.
    #[error("edge {edge}: its sides do not run oppositely between the same two vertices")]
    Mismatched {
        /// Index of the edge in `edges`.
        edge: usize,
    },
    /// The arrays are well formed but the result fails
    /// [`Mesh::validate`] (a vertex's rotation is not one cycle, say).
    #[error("not a valid 2-manifold: {0}")]
    Invalid(#[from] ValidationError),
}

fn to_u32(n: usize) -> Result<u32, BuildError> {
    u32::try_from(n)
        .ok()
        .filter(|&k| k < NONE)
        .ok_or(BuildError::TooLarge(n))
}

impl Mesh {
    /// Builds a mesh from raw parts, then [`validate`](Mesh::validate)s it.
    ///
    /// Slot indices equal input indices: vertex `i` of `raw.positions` is
    /// [`Mesh::vertex_at`]`(i)`, face `f` is [`Mesh::face_at`]`(f)` and
    /// global corner `k` is [`Mesh::corner_at`]`(k)`, with each face's walk
    /// starting at its first corner.
    pub fn from_raw(raw: &RawMesh) -> Result<Mesh, BuildError> {
        let mesh = Mesh::from_raw_trusted(raw)?;
        mesh.validate()?;
        Ok(mesh)
    }

    /// Like [`Mesh::from_raw`], for generators whose output is a 2-manifold
    /// by construction (subdivision of a valid mesh, say): every per-element
    /// check runs — index ranges, finite positions, face offsets, each corner
    /// starting exactly one edge whose sides run oppositely — but the global
    /// pass that checks each vertex's rotation is one cycle runs only in
    /// debug builds (as an error, not an assertion). Input read from files
    /// must go through [`Mesh::from_raw`].
    pub fn from_raw_trusted(raw: &RawMesh) -> Result<Mesh, BuildError> {
        let mesh = Mesh::build_unvalidated(raw)?;
        #[cfg(debug_assertions)]
        mesh.validate()?;
        Ok(mesh)
    }

    fn build_unvalidated(raw: &RawMesh) -> Result<Mesh, BuildError> {
        let nf = raw.face_count();
        let nv = raw.positions.len();
        let nc = raw.face_vertices.len();
        to_u32(nv)?;
        to_u32(nc)?;
        to_u32(raw.edges.len())?;
        if raw.face_offsets.first().is_some_and(|&o| o != 0) {
            return Err(BuildError::Offsets("the first offset is not 0".into()));
        }
        if raw
            .face_offsets
            .last()
            .map_or(nc != 0, |&o| o as usize != nc)
        {
            return Err(BuildError::Offsets(format!(
                "the last offset is not the number of corners ({nc})"
            )));
        }
        if !raw.holes.is_empty() && raw.holes.len() != nf {
            return Err(BuildError::HoleCount {
                flags: raw.holes.len(),
                faces: nf,
            });
        }
        for f in 0..nf {
            let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
            if hi < lo {
                return Err(BuildError::Offsets(format!("offsets decrease at face {f}")));
            }
            if hi == lo {
                return Err(BuildError::EmptyFace { face: f });
            }
        }

        let mut vertices = Vec::with_capacity(nv);
        NonFinite::check("vertex", &raw.positions)?;
        for p in &raw.positions {
            vertices.push(Vertex {
                position: *p,
                corner: NONE,
                count: 0,
            });
        }
        let mut faces = Vec::with_capacity(nf);
        let mut corners = Vec::with_capacity(nc);
        for f in 0..nf {
            let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
            faces.push(Face {
                corner: lo,
                len: hi - lo,
                hole: raw.is_hole(f),
            });
            for k in lo..hi {
                let v = raw.face_vertices[k as usize];
                if v as usize >= nv {
                    return Err(BuildError::VertexOutOfRange {
                        face: f,
                        vertex: v,
                        count: nv,
                    });
                }
                vertices[v as usize].count += 1;
                corners.push(Corner {
                    vertex: v,
                    face: f as u32,
                    next: if k + 1 == hi { lo } else { k + 1 },
                    prev: if k == lo { hi - 1 } else { k - 1 },
                    edge: NONE,
                    vnext: NONE,
                    vprev: NONE,
                });
            }
        }
        // Vertex rings: chain each vertex's corners in index order. The
        // last corner seen per vertex is kept in `vertex.corner` while
        // linking, then the ring is closed.
        for k in 0..nc as u32 {
            let v = corners[k as usize].vertex as usize;
            let last = vertices[v].corner;
            if last == NONE {
                corners[k as usize].vprev = k;
                corners[k as usize].vnext = k;
            } else {
                let first = corners[last as usize].vnext;
                corners[last as usize].vnext = k;
                corners[k as usize].vprev = last;
                corners[k as usize].vnext = first;
                corners[first as usize].vprev = k;
            }
            vertices[v].corner = k;
        }
        let mut mesh = Mesh {
            vertices: Arena::from_values(vertices),
            faces: Arena::from_values(faces),
            corners: Arena::from_values(corners),
            edges: Arena::default(),
        };
        if let Some(v) = (0..nv).find(|&v| mesh.v(v as u32).count == 0) {
            return Err(BuildError::UnusedVertex { vertex: v });
        }
        let locate = |c: u32| -> (usize, usize) {
            let f = raw.face_offsets.partition_point(|&o| o <= c) - 1;
            (f, (c - raw.face_offsets[f]) as usize)
        };
        let mut edges = Vec::with_capacity(raw.edges.len());
        for (ei, &[a, b]) in raw.edges.iter().enumerate() {
            for c in [a, b] {
                if c as usize >= nc {
                    return Err(BuildError::CornerOutOfRange {
                        edge: ei,
                        corner: c,
                        count: nc,
                    });
                }
                let prev = mesh.c(c).edge;
                if prev != NONE {
                    let (face, k) = locate(c);
                    return Err(BuildError::CornerTwice {
                        corner: c as usize,
                        face,
                        k,
                        first: prev as usize,
                        second: ei,
                    });
                }
                mesh.c_mut(c).edge = ei as u32;
            }
            if a == b {
                let (face, k) = locate(a);
                return Err(BuildError::CornerTwice {
                    corner: a as usize,
                    face,
                    k,
                    first: ei,
                    second: ei,
                });
            }
            let (ca, cb) = (*mesh.c(a), *mesh.c(b));
            if mesh.c(ca.next).vertex != cb.vertex || mesh.c(cb.next).vertex != ca.vertex {
                return Err(BuildError::Mismatched { edge: ei });
            }
            edges.push(Edge { corners: [a, b] });
        }
        mesh.edges = Arena::from_values(edges);
        for f in 0..nf {
            let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
            for k in lo..hi {
                if mesh.c(k).edge == NONE && hi - lo > 1 {
                    return Err(BuildError::CornerWithoutEdge {
                        corner: k as usize,
                        face: f,
                        k: (k - lo) as usize,
                    });
                }
            }
        }
        Ok(mesh)
    }

    /// Flattens the mesh: live vertices in slot order, live faces in slot
    /// order (holes flagged), each face's corners from
    /// [`Mesh::face_corner`], and every edge as its two corner indices.
    pub fn to_raw(&self) -> RawMesh {
        let mut vmap = vec![NONE; self.vertices.capacity_slots()];
        let mut positions = Vec::with_capacity(self.vertex_count());
        for v in self.vertices.live_indices() {
            vmap[v as usize] = positions.len() as u32;
            positions.push(self.v(v).position);
        }
        let mut cmap = vec![NONE; self.corners.capacity_slots()];
        let mut face_offsets = Vec::with_capacity(self.face_count() + 1);
        let mut face_vertices = Vec::with_capacity(self.corner_count());
        let mut holes = Vec::with_capacity(self.face_count());
        face_offsets.push(0);
        for f in self.faces.live_indices() {
            for c in self.face_corner_slots(f) {
                cmap[c as usize] = face_vertices.len() as u32;
                face_vertices.push(vmap[self.c(c).vertex as usize]);
            }
            face_offsets.push(face_vertices.len() as u32);
            holes.push(self.f(f).hole);
        }
        let edges = self
            .edges
            .live_indices()
            .map(|e| {
                let [a, b] = self.e(e).corners;
                [cmap[a as usize], cmap[b as usize]]
            })
            .collect();
        if !holes.iter().any(|&h| h) {
            holes.clear();
        }
        RawMesh {
            positions,
            face_offsets,
            face_vertices,
            holes,
            edges,
        }
    }
}
