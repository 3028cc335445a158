//! The writing half of every remeshing scheme: the sizes one step will
//! produce ([`Sizes`]), checked against the cap before anything is
//! allocated ([`Budget`]), and a writer that pairs output corners into
//! edges by explicit labels ([`Builder`], see [`super::map`] for the
//! labels), with the face loops the schemes share:
//!
//! - [`Builder::walk`]: one face through a run of input corners, each
//!   corner adding its (vertex, label) pairs;
//! - [`Builder::kept_faces`]: the loop of the schemes that keep the input's
//!   vertices: point-spheres copied, holes refined corner by corner, normal
//!   faces by the scheme;
//! - [`Builder::walked_faces`]: the loop of the schemes written on the
//!   closed map, where holes are treated as faces: every face walked the
//!   same way, its kind kept;
//! - [`Builder::vertex_faces`]: one face per vertex, around its rotation.

use glam::DVec3;

use super::map::Map;
use crate::SubdivError;
use crate::flat::{Flat, Kind, NONE};

/// A face under construction: its (vertex, label) corners in walk order.
pub(super) type Walk = Vec<(u32, usize)>;

/// The exact size of one step's output.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Sizes {
    pub v: usize,
    pub e: usize,
    pub f: usize,
    pub c: usize,
}

/// The cap in force and what to name in the error when a step would pass
/// it.
pub(super) struct Budget {
    pub scheme: super::RemeshScheme,
    pub levels: usize,
    pub level: usize,
    pub max_faces: usize,
}

impl Budget {
    /// Refuses `s` when it has more faces than the cap or more entities
    /// than the kernel's 32-bit indices hold.
    pub fn check(&self, s: Sizes) -> Result<(), SubdivError> {
        let limit = (u32::MAX - 2) as usize;
        if s.f > self.max_faces || s.c > limit || s.v > limit || s.e > limit {
            return Err(SubdivError::RemeshTooLarge {
                scheme: self.scheme,
                levels: self.levels,
                level: self.level,
                faces: s.f as u128,
                corners: s.c as u128,
                cap: self.max_faces,
            });
        }
        Ok(())
    }
}

/// Writes one step's output: faces as (vertex, label) corners, pairing
/// corners into edges by label (see [`super::map`]).
pub(super) struct Builder {
    out: Flat,
    sizes: Sizes,
    /// The first inconsistency met, reported by [`Builder::finish`]; the
    /// writing methods stay infallible so the schemes read as geometry.
    bad: Option<String>,
    /// The face [`Builder::walk`] is gathering, kept for its capacity.
    walk: Walk,
}

impl Builder {
    /// A writer for an output of exactly `sizes`, whose vertex positions
    /// are `pos`. The caller has checked `sizes` against the [`Budget`].
    pub fn new(pos: Vec<DVec3>, sizes: Sizes) -> Builder {
        let bad = (pos.len() != sizes.v)
            .then(|| format!("{} positions for {} vertices", pos.len(), sizes.v));
        let mut out = Flat {
            pos,
            ..Flat::default()
        };
        out.off.reserve(sizes.f + 1);
        out.cv.reserve(sizes.c);
        out.cf.reserve(sizes.c);
        out.cedge.reserve(sizes.c);
        out.hole.reserve(sizes.f);
        out.edges.resize(sizes.e, [NONE, NONE]);
        Builder {
            out,
            sizes,
            bad,
            walk: Vec::new(),
        }
    }

    /// Appends a face of the surface (not a hole) of the given corners
    /// (vertex, label), in walk order: the faces the schemes write one by
    /// one are never holes.
    pub fn face(&mut self, corners: &[(u32, usize)]) {
        self.add_face(false, corners);
    }

    /// Appends a face, a hole if `hole`, of the given corners (vertex,
    /// label), in walk order.
    fn add_face(&mut self, hole: bool, corners: &[(u32, usize)]) {
        let face = self.out.hole.len() as u32;
        self.out.off.push(self.out.cv.len() as u32);
        self.out.hole.push(hole);
        for &(v, label) in corners {
            let x = self.out.cv.len() as u32;
            let (e, s) = (label >> 1, label & 1);
            self.out.cv.push(v);
            self.out.cf.push(face);
            self.out.cedge.push(e as u32);
            match self.out.edges.get_mut(e) {
                Some(slot) if slot[s] == NONE => slot[s] = x,
                _ => {
                    if self.bad.is_none() {
                        self.bad =
                            Some(format!("edge label {label} is out of range or used twice"));
                    }
                }
            }
        }
    }

    /// Appends a point-sphere at vertex `v` (one corner, no edge).
    pub fn point_sphere(&mut self, v: u32, hole: bool) {
        let face = self.out.hole.len() as u32;
        self.out.off.push(self.out.cv.len() as u32);
        self.out.hole.push(hole);
        self.out.cv.push(v);
        self.out.cf.push(face);
        self.out.cedge.push(NONE);
    }

    /// Appends the face that `each(c, walk)` writes for the corners `c` of
    /// `corners` in turn, each pushing its (vertex, label) pairs.
    pub fn walk(
        &mut self,
        hole: bool,
        corners: impl IntoIterator<Item = usize>,
        mut each: impl FnMut(usize, &mut Walk),
    ) {
        let mut walk = std::mem::take(&mut self.walk);
        walk.clear();
        for c in corners {
            each(c, &mut walk);
        }
        self.add_face(hole, &walk);
        self.walk = walk;
    }

    /// The face loop of the schemes that keep the input's vertices (and so
    /// its point-spheres' vertices): in face order, a point-sphere is
    /// copied, a hole becomes the face `hole_corner(c, walk)` writes
    /// corner by corner, and `normal(b, face, lo, hi)` writes whatever a
    /// normal face with corners `lo..hi` becomes.
    pub fn kept_faces(
        &mut self,
        m: &Map,
        mut hole_corner: impl FnMut(usize, &mut Walk),
        mut normal: impl FnMut(&mut Builder, usize, usize, usize),
    ) {
        let src = m.f;
        for face in 0..src.face_count() {
            let (lo, hi) = m.range(face);
            match m.kind[face] {
                Kind::PointSphere => self.point_sphere(src.cv[lo], src.hole[face]),
                Kind::Hole => self.walk(true, lo..hi, &mut hole_corner),
                Kind::Normal => normal(self, face, lo, hi),
            }
        }
    }

    /// The face loop of the schemes written on the closed map, holes
    /// treated as faces: in face order, every normal face and hole becomes
    /// the face of the same kind that `corner(c, walk)` writes corner by
    /// corner, and every point-sphere a point-sphere at vertex
    /// `sphere(face)`.
    pub fn walked_faces(
        &mut self,
        m: &Map,
        mut sphere: impl FnMut(usize) -> u32,
        mut corner: impl FnMut(usize, &mut Walk),
    ) {
        let src = m.f;
        for face in 0..src.face_count() {
            let (lo, hi) = m.range(face);
            match m.kind[face] {
                Kind::PointSphere => self.point_sphere(sphere(face), src.hole[face]),
                kind => self.walk(kind == Kind::Hole, lo..hi, &mut corner),
            }
        }
    }

    /// One normal face per vertex (point-spheres' aside), in vertex order:
    /// the face `corner(c, walk)` writes for the corners of its rotation
    /// (see [`Map::for_each_ring`]).
    pub fn vertex_faces(
        &mut self,
        m: &Map,
        mut corner: impl FnMut(usize, &mut Walk),
    ) -> Result<(), SubdivError> {
        m.for_each_ring(|_, ring| self.walk(false, ring.iter().copied(), &mut corner))
    }

    /// The finished map; an error when an edge was left unpaired, a label
    /// was used twice, or the output does not have the sizes predicted.
    pub fn finish(mut self) -> Result<Flat, SubdivError> {
        self.out.off.push(self.out.cv.len() as u32);
        if let Some(what) = self.bad {
            return Err(SubdivError::Internal(what));
        }
        if let Some(e) = self.out.edges.iter().position(|s| s.contains(&NONE)) {
            return Err(SubdivError::Internal(format!(
                "output edge {e} was left unpaired"
            )));
        }
        let got = Sizes {
            v: self.out.pos.len(),
            e: self.out.edges.len(),
            f: self.out.hole.len(),
            c: self.out.cv.len(),
        };
        if got != self.sizes {
            return Err(SubdivError::Internal(format!(
                "made {got:?}, predicted {:?}",
                self.sizes
            )));
        }
        Ok(self.out)
    }
}
