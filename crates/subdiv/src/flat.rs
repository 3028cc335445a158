//! The compact, corner-based form the schemes work on between levels.
//!
//! A [`Flat`] is a DLFL laid out as arrays, the same shape as
//! [`RawMesh`] plus two per-corner indices the schemes need in their inner
//! loops: the face of each corner (`cf`) and the edge that starts at it
//! (`cedge`). Corner `c` of face `f` is global corner `off[f] + k`; its
//! face successor is `c + 1`, wrapping to `off[f]` at the end of the face.
//!
//! This is a *combinatorial map*: the corners are half-edges, faces are the
//! cycles of `next`, and vertices are the cycles of the rotation
//! `rot(c) = next(twin(c))`, where `twin(c)` is the other corner of `c`'s
//! edge. The schemes are written entirely in these terms, so self-loops
//! (an edge whose two corners name one vertex), multiple edges, two-gons,
//! monogons, faces that visit a vertex twice and edges with the same face
//! on both sides need no special cases. Only point-spheres (a one-corner
//! face with no edge) are outside the map, and the schemes copy them.

use glam::DVec3;
use holey_dlfl::{BuildError, Mesh, NonFinite, RawMesh};

use crate::SubdivError;

/// Marks a point-sphere corner's missing edge.
pub(crate) const NONE: u32 = u32::MAX;

/// What a face is, for the schemes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// An ordinary face: subdivided.
    Normal,
    /// A hole face (a boundary loop): refined along its boundary only.
    Hole,
    /// A point-sphere (one corner, no edge): copied.
    PointSphere,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct Flat {
    pub(crate) pos: Vec<DVec3>,
    /// `faces + 1` offsets into the corner arrays, starting at 0.
    pub(crate) off: Vec<u32>,
    /// The vertex of each corner.
    pub(crate) cv: Vec<u32>,
    /// The face of each corner.
    pub(crate) cf: Vec<u32>,
    /// The edge that starts at each corner ([`NONE`] for a point-sphere).
    pub(crate) cedge: Vec<u32>,
    /// Each edge's two corners.
    pub(crate) edges: Vec<[u32; 2]>,
    /// One flag per face.
    pub(crate) hole: Vec<bool>,
}

impl Flat {
    pub(crate) fn face_count(&self) -> usize {
        self.off.len().saturating_sub(1)
    }

    pub(crate) fn corner_count(&self) -> usize {
        self.cv.len()
    }

    /// The kind of face `f`.
    #[inline]
    pub(crate) fn kind(&self, f: usize) -> Kind {
        let lo = self.off[f] as usize;
        if self.off[f + 1] as usize - lo == 1 && self.cedge[lo] == NONE {
            Kind::PointSphere
        } else if self.hole[f] {
            Kind::Hole
        } else {
            Kind::Normal
        }
    }

    /// The face successor of corner `c`.
    #[inline]
    pub(crate) fn next(&self, c: usize) -> usize {
        let f = self.cf[c] as usize;
        if c + 1 == self.off[f + 1] as usize {
            self.off[f] as usize
        } else {
            c + 1
        }
    }

    /// The face predecessor of corner `c`.
    #[inline]
    pub(crate) fn prev(&self, c: usize) -> usize {
        let f = self.cf[c] as usize;
        if c == self.off[f] as usize {
            self.off[f + 1] as usize - 1
        } else {
            c - 1
        }
    }

    /// The other corner of `c`'s edge (`c` must not be a point-sphere's).
    #[inline]
    pub(crate) fn twin(&self, c: usize) -> usize {
        let [a, b] = self.edges[self.cedge[c] as usize];
        if a as usize == c {
            b as usize
        } else {
            a as usize
        }
    }

    /// Lays a mesh out flat (live entities in slot order, as
    /// [`Mesh::to_raw`] does) and checks the positions.
    ///
    /// The kernel keeps its meshes valid, so the structural checks here
    /// can only fail on a kernel bug; they are made anyway (cheaply)
    /// because the schemes index arrays with these numbers and must never
    /// panic.
    pub(crate) fn from_mesh(mesh: &Mesh) -> Result<Flat, SubdivError> {
        let raw = mesh.to_raw();
        NonFinite::check("vertex", &raw.positions)?;
        let nf = raw.face_count();
        let nc = raw.face_vertices.len();
        let nv = raw.positions.len();
        let internal = |what: &str| Err(SubdivError::Internal(what.to_string()));
        if raw.face_offsets.first().copied().unwrap_or(0) != 0
            || raw.face_offsets.last().copied().unwrap_or(0) as usize != nc
        {
            return internal("face offsets do not cover the corners");
        }
        let mut cf = vec![0u32; nc];
        for f in 0..nf {
            let (lo, hi) = (
                raw.face_offsets[f] as usize,
                raw.face_offsets[f + 1] as usize,
            );
            if hi <= lo || hi > nc {
                return internal("face offsets decrease or leave a face empty");
            }
            cf[lo..hi].fill(f as u32);
        }
        if raw.face_vertices.iter().any(|&v| v as usize >= nv) {
            return internal("a corner names a vertex out of range");
        }
        let mut cedge = vec![NONE; nc];
        for (e, &[a, b]) in raw.edges.iter().enumerate() {
            for c in [a, b] {
                if c as usize >= nc || cedge[c as usize] != NONE {
                    return internal("an edge names a corner out of range or already used");
                }
                cedge[c as usize] = e as u32;
            }
        }
        let hole = if raw.holes.len() == nf {
            raw.holes
        } else {
            vec![false; nf]
        };
        let flat = Flat {
            pos: raw.positions,
            off: raw.face_offsets,
            cv: raw.face_vertices,
            cf,
            cedge,
            edges: raw.edges,
            hole,
        };
        for f in 0..nf {
            let (lo, hi) = (flat.off[f] as usize, flat.off[f + 1] as usize);
            if hi - lo > 1 && flat.cedge[lo..hi].contains(&NONE) {
                return internal("a corner of a face with several corners starts no edge");
            }
        }
        Ok(flat)
    }

    /// The kernel mesh of a step's output, its vertices first renumbered
    /// in the order the faces use them ([`Flat::localize_vertices`]): a
    /// non-finite position is an overflow, `overflow(vertex)`, and anything
    /// else the builder refuses a bug.
    pub(crate) fn into_mesh(
        mut self,
        overflow: impl FnOnce(usize) -> SubdivError,
    ) -> Result<Mesh, SubdivError> {
        self.localize_vertices();
        Mesh::from_raw_trusted(&self.into_raw()).map_err(|e| match e {
            BuildError::NonFinite(e) => overflow(e.index.unwrap_or_default()),
            other => SubdivError::Internal(format!("the output is not a valid DLFL: {other}")),
        })
    }

    /// The flat arrays as the kernel's [`RawMesh`], moving them.
    pub(crate) fn into_raw(self) -> RawMesh {
        let holes = if self.hole.iter().any(|&h| h) {
            self.hole
        } else {
            Vec::new()
        };
        RawMesh {
            positions: self.pos,
            face_offsets: self.off,
            face_vertices: self.cv,
            holes,
            edges: self.edges,
        }
    }

    /// Renumbers vertices in the order the faces first use them, keeping
    /// faces and corners as they are. Neighbours on the surface then sit
    /// close together in every array, which makes building and validating
    /// the kernel mesh markedly faster (its vertex rings and rotations are
    /// walked through these numbers). Linear time.
    pub(crate) fn localize_vertices(&mut self) {
        let nv = self.pos.len();
        let mut map = vec![NONE; nv];
        let mut pos = Vec::with_capacity(nv);
        for v in &mut self.cv {
            let m = &mut map[*v as usize];
            if *m == NONE {
                *m = pos.len() as u32;
                pos.push(self.pos[*v as usize]);
            }
            *v = *m;
        }
        // Every vertex is used by some face, so every vertex was met.
        self.pos = pos;
    }

    /// Empties every array, keeping the allocations for the next level.
    pub(crate) fn clear(&mut self) {
        self.pos.clear();
        self.off.clear();
        self.cv.clear();
        self.cf.clear();
        self.cedge.clear();
        self.edges.clear();
        self.hole.clear();
    }

    /// The sizes that decide how large the output of each level is.
    pub(crate) fn counts(&self) -> Counts {
        let mut k = Counts {
            vertices: self.pos.len() as u128,
            edges: self.edges.len() as u128,
            ..Counts::default()
        };
        for f in 0..self.face_count() {
            let len = (self.off[f + 1] - self.off[f]) as u128;
            match self.kind(f) {
                Kind::Normal => {
                    k.normal_faces += 1;
                    k.normal_corners += len;
                }
                Kind::Hole => {
                    k.hole_faces += 1;
                    k.hole_corners += len;
                }
                Kind::PointSphere => k.point_spheres += 1,
            }
        }
        k
    }
}

/// Entity counts of a mesh, by kind of face. Wide integers so that
/// predicting many levels ahead cannot overflow before the cap check.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// All vertices, point-sphere vertices included.
    pub vertices: u128,
    /// All edges, those bordering holes included.
    pub edges: u128,
    /// Faces that are neither holes nor point-spheres.
    pub normal_faces: u128,
    /// Hole faces (boundary loops).
    pub hole_faces: u128,
    /// Point-spheres (each is one vertex and one face).
    pub point_spheres: u128,
    /// Corners of the normal faces.
    pub normal_corners: u128,
    /// Corners of the hole faces.
    pub hole_corners: u128,
}

impl Counts {
    /// All faces: normal, holes and point-spheres.
    pub fn faces(&self) -> u128 {
        self.normal_faces + self.hole_faces + self.point_spheres
    }

    /// All corners.
    pub fn corners(&self) -> u128 {
        self.normal_corners + self.hole_corners + self.point_spheres
    }
}
