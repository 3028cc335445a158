//! The keyframes of a drag (§4), kept so that a point sampled at release
//! follows the surface's true path.
//!
//! A drag's raw parity is accumulated frame by frame, each vertex moving
//! straight between consecutive keyframes. At release the cut samples the
//! parity of points that are not vertices: regions a curve cuts off with
//! no vertex inside (Figure 13, §7's refinement) and the two sides of a
//! T-junction where a curve ends at a sheet's boundary (Figure 7;
//! `cut/junctions.rs`). Such a point's parity is the number of times its
//! path crosses the moving surface, mod 2, and on an open surface that
//! depends on the path: a point the drag carried around a sheet's edge
//! and one carried through the sheet end in the same place. Sampled along
//! the straight line from the drag's start to its end, the parity beside
//! a curve can be wrong, so without the keyframes those junctions are
//! left to orientation alone. With them, a sample moves as the vertices
//! did, frame by frame, and its parity is exact (the same root-parity
//! test and the same chained identities as the vertices'; module docs of
//! `holey_geom::ccd`).
//!
//! Only what moved in each frame is kept, within [`MAX_ENTRIES`]; past
//! that the drag forgets its keyframes and samples go straight. One
//! frame is sampled by the same [`PathSampler`], as a single straight step.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::OnceLock;

use glam::DVec3;
use holey_geom::ccd::{CcdParity, MovingPoint, vertex_triangle_parity};
use holey_geom::{Aabb, Bvh, SymPoint};
use rustc_hash::FxHashMap as HashMap;

/// Most (vertex, frame) positions a drag keeps: 4M, about 110 MB. Moving
/// a 36k-vertex scan whole keeps over a hundred frames; a local grab of a
/// few thousand vertices, over a thousand.
pub const MAX_ENTRIES: usize = 1 << 22;

/// The vertices that moved in each frame of a drag and where each frame
/// left them.
#[derive(Clone, Debug, Default)]
pub(crate) struct DragPath {
    /// Per frame: the vertices that moved (increasing) and their
    /// positions at its end.
    frames: Vec<(Vec<u32>, Vec<DVec3>)>,
    entries: usize,
}

impl DragPath {
    /// Records a frame from `from` to `to` (same length), looking only at
    /// the vertices `among` (increasing; every vertex of a triangle that
    /// moved) or, with `None`, at all. Returns `false` when the drag has
    /// moved more than [`MAX_ENTRIES`] positions: the path is then
    /// incomplete and must be dropped.
    pub fn record(&mut self, from: &[DVec3], to: &[DVec3], among: Option<&[u32]>) -> bool {
        let moved_to = |v: u32| {
            let (a, b) = (from.get(v as usize)?, to.get(v as usize)?);
            (a != b).then_some((v, *b))
        };
        let (moved, ends): (Vec<u32>, Vec<DVec3>) = match among {
            Some(vs) => vs.iter().filter_map(|&v| moved_to(v)).unzip(),
            None => (0..from.len() as u32).filter_map(moved_to).unzip(),
        };
        self.entries += moved.len();
        self.frames.push((moved, ends));
        self.entries <= MAX_ENTRIES
    }

    /// Where global vertex `g` is at the end of frame `f`, if it moved in
    /// that frame.
    fn moved_to(&self, f: usize, g: u32) -> Option<DVec3> {
        let (moved, ends) = &self.frames[f];
        moved.binary_search(&g).ok().map(|i| ends[i])
    }
}

/// How a region's vertices are numbered in the whole mesh (the path
/// records global numbers).
#[derive(Clone, Copy)]
pub(crate) struct Numbering<'a> {
    /// Local vertex → global vertex; empty when local numbers are global.
    pub global: &'a [u32],
    /// Global vertex → local vertex (`u32::MAX` outside); empty likewise.
    pub local: &'a [u32],
}

impl Numbering<'_> {
    /// Local numbers are the global ones.
    pub const WHOLE: Numbering<'static> = Numbering {
        global: &[],
        local: &[],
    };

    fn global(&self, v: u32) -> u32 {
        self.global.get(v as usize).copied().unwrap_or(v)
    }

    fn local(&self, g: u32) -> Option<u32> {
        if self.local.is_empty() {
            Some(g)
        } else {
            self.local
                .get(g as usize)
                .copied()
                .filter(|&l| l != u32::MAX)
        }
    }
}

/// How the vertices of a sampled mesh move.
#[derive(Clone, Copy)]
pub(crate) enum Keyframes<'a> {
    /// One straight frame from the sampler's start to these positions.
    Straight(&'a [DVec3]),
    /// A drag's recorded frames, the mesh numbered as `Numbering` says.
    Recorded(&'a DragPath, Numbering<'a>),
}

/// The parity of a point of a triangle, moving with the surface along its
/// keyframes: the number of times it hits the moving surface, mod 2, by
/// the exact test (module docs). One straight frame is the path of one
/// keyframe step. Built per cut; the tree over the triangles' boxes over
/// every keyframe and the vertices' keyframes are made on the first
/// sample.
pub(crate) struct PathSampler<'a> {
    /// The triangles (local numbers) and their positions at the start
    /// (local).
    tris: &'a [[u32; 3]],
    start: &'a [DVec3],
    keyframes: Keyframes<'a>,
    bvh: OnceLock<Option<Bvh>>,
    /// Keyframe positions per local vertex, filled as samples need them.
    cache: RefCell<HashMap<u32, Rc<[DVec3]>>>,
}

impl<'a> PathSampler<'a> {
    pub fn new(tris: &'a [[u32; 3]], start: &'a [DVec3], keyframes: Keyframes<'a>) -> Self {
        PathSampler {
            tris,
            start,
            keyframes,
            bvh: OnceLock::new(),
            cache: RefCell::new(HashMap::default()),
        }
    }

    /// Keyframe steps (frames).
    fn frames(&self) -> usize {
        match self.keyframes {
            Keyframes::Straight(_) => 1,
            Keyframes::Recorded(path, _) => path.frames.len(),
        }
    }

    /// Keyframes `0..=F` of local vertex `v`.
    fn keyframes_of(&self, v: u32) -> Option<Rc<[DVec3]>> {
        if let Some(k) = self.cache.borrow().get(&v) {
            return Some(k.clone());
        }
        let mut at = *self.start.get(v as usize)?;
        let out: Rc<[DVec3]> = match self.keyframes {
            Keyframes::Straight(end) => [at, *end.get(v as usize)?].into(),
            Keyframes::Recorded(path, numbering) => {
                let g = numbering.global(v);
                let mut out = Vec::with_capacity(path.frames.len() + 1);
                out.push(at);
                for f in 0..path.frames.len() {
                    if let Some(p) = path.moved_to(f, g) {
                        at = p;
                    }
                    out.push(at);
                }
                out.into()
            }
        };
        self.cache.borrow_mut().insert(v, out.clone());
        Some(out)
    }

    /// The tree over each triangle's box over every keyframe.
    fn tree(&self) -> Option<&Bvh> {
        self.bvh
            .get_or_init(|| {
                let mut lo = self.start.to_vec();
                let mut hi = self.start.to_vec();
                let mut grow = |l: usize, p: DVec3| {
                    if let Some(x) = lo.get_mut(l) {
                        *x = x.min(p);
                        hi[l] = hi[l].max(p);
                    }
                };
                match self.keyframes {
                    Keyframes::Straight(end) => {
                        for (l, &p) in end.iter().enumerate() {
                            grow(l, p);
                        }
                    }
                    Keyframes::Recorded(path, numbering) => {
                        for (moved, ends) in &path.frames {
                            for (&g, &p) in moved.iter().zip(ends) {
                                if let Some(l) = numbering.local(g) {
                                    grow(l as usize, p);
                                }
                            }
                        }
                    }
                }
                let boxes: Vec<Aabb> = self
                    .tris
                    .iter()
                    .map(|t| {
                        let [a, b, c] = t.map(|v| v as usize);
                        Aabb::new(lo[a].min(lo[b]).min(lo[c]), hi[a].max(hi[b]).max(hi[c]))
                    })
                    .collect();
                Bvh::build(&boxes).ok()
            })
            .as_ref()
    }

    /// The parity of the point with barycentric weights `w` in triangle
    /// `t`, sampled with call number `k` (its symbolic identities come
    /// after every vertex's).
    pub fn parity(&self, k: u32, t: u32, w: [f64; 3]) -> Option<bool> {
        let n = self.start.len();
        let corners = *self.tris.get(t as usize)?;
        let [a, b, c] = corners.map(|c| self.keyframes_of(c));
        let own = [a?, b?, c?];
        let frames = self.frames();
        let point: Vec<DVec3> = (0..=frames)
            .map(|f| own[0][f] * w[0] + own[1][f] * w[1] + own[2][f] * w[2])
            .collect();
        let span = point
            .iter()
            .fold(Aabb::new(point[0], point[0]), |b, &p| b.grow(p));
        let base = u32::try_from(2 * n + 2 * k as usize).ok()?;
        base.checked_add(1)?;
        let tree = self.tree()?;
        let mut candidates = Vec::new();
        tree.for_each_overlap(&span, |u| {
            if u != t {
                candidates.push(u);
            }
        });
        let mut odd = false;
        for u in candidates {
            let tri = self.tris[u as usize];
            let [a, b, c] = tri.map(|c| self.keyframes_of(c));
            let ks = [a?, b?, c?];
            for f in 0..frames {
                let still = |k: &[DVec3]| k[f] == k[f + 1];
                if still(&point) && ks.iter().all(|k| still(k)) {
                    // No relative motion: nothing can be crossed.
                    continue;
                }
                let segment = Aabb::new(point[f].min(point[f + 1]), point[f].max(point[f + 1]));
                let swept = ks.iter().fold(Aabb::new(ks[0][f], ks[0][f]), |b, k| {
                    b.grow(k[f]).grow(k[f + 1])
                });
                if !segment.overlaps(&swept) {
                    continue;
                }
                // Chained identities (holey_geom::ccd::frame_ids): the end
                // of frame f and the start of frame f + 1 are one point.
                let (s, e) = ((f & 1) as u32, ((f + 1) & 1) as u32);
                let x = MovingPoint {
                    start: SymPoint::new(point[f], base + s),
                    end: SymPoint::new(point[f + 1], base + e),
                };
                let mp = |i: usize| MovingPoint {
                    start: SymPoint::new(ks[i][f], 2 * tri[i] + s),
                    end: SymPoint::new(ks[i][f + 1], 2 * tri[i] + e),
                };
                if vertex_triangle_parity(x, mp(0), mp(1), mp(2)) == CcdParity::Odd {
                    odd = !odd;
                }
            }
        }
        Some(odd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small triangle around the origin in z = 0 and a big one above
    /// it in z = 1, both facing +z.
    fn still_and_mover() -> [[DVec3; 3]; 2] {
        [
            [
                DVec3::new(-0.1, -0.1, 0.0),
                DVec3::new(0.2, -0.1, 0.0),
                DVec3::new(-0.1, 0.2, 0.0),
            ],
            [
                DVec3::new(-2.0, -2.0, 1.0),
                DVec3::new(3.0, -2.0, 1.0),
                DVec3::new(-2.0, 3.0, 1.0),
            ],
        ]
    }

    /// A fixed point at the origin (the middle of a small still triangle)
    /// and a big triangle above it that, over four frames, drops through
    /// it, slides far aside, rises and slides back: it ends where it
    /// began, having crossed the point exactly once. The straight path
    /// from the drag's start to its end does not move at all (even); the
    /// keyframes give the true parity (odd). Then the same loop without
    /// the drop through the point (down beside it): even.
    #[test]
    fn a_loop_that_crosses_a_point_once_is_odd() {
        let [small, big] = still_and_mover();
        let tris = [[0, 1, 2], [3, 4, 5]];
        let third = [1.0 / 3.0; 3];
        for (through, expected) in [(true, true), (false, false)] {
            let aside = DVec3::new(10.0, 0.0, 0.0);
            let steps = if through {
                [
                    DVec3::new(0.0, 0.0, -2.0),
                    aside,
                    DVec3::new(0.0, 0.0, 2.0),
                    -aside,
                ]
            } else {
                [
                    aside,
                    DVec3::new(0.0, 0.0, -2.0),
                    DVec3::new(0.0, 0.0, 2.0),
                    -aside,
                ]
            };
            let start: Vec<DVec3> = small.iter().chain(&big).copied().collect();
            let mut path = DragPath::default();
            let mut at = start.clone();
            for step in steps {
                let next: Vec<DVec3> = at
                    .iter()
                    .enumerate()
                    .map(|(v, &p)| if v >= 3 { p + step } else { p })
                    .collect();
                assert!(path.record(&at, &next, None));
                at = next;
            }
            assert_eq!(at, start, "the loop comes back");
            let sampler =
                PathSampler::new(&tris, &start, Keyframes::Recorded(&path, Numbering::WHOLE));
            assert_eq!(
                sampler.parity(0, 0, third),
                Some(expected),
                "through {through}"
            );
            // A point of the moving triangle, far from the still one: it
            // never meets it.
            assert_eq!(sampler.parity(1, 1, third), Some(false));
        }
    }

    /// A region's numbering: the path records global vertices, the
    /// sampler reads local ones.
    #[test]
    fn a_region_reads_the_path_by_global_number() {
        // Global vertices 0..6; the region holds 3, 4, 5 (the mover) and
        // 0, 1, 2 (the still triangle) as local 3, 4, 5 and 0, 1, 2 of a
        // numbering that swaps them: local v is global (v + 3) % 6.
        let [still, mover] = still_and_mover();
        let global_start: Vec<DVec3> = still.iter().chain(&mover).copied().collect();
        let global_end: Vec<DVec3> = still
            .iter()
            .copied()
            .chain(mover.iter().map(|p| *p - DVec3::new(0.0, 0.0, 2.0)))
            .collect();
        let mut path = DragPath::default();
        assert!(path.record(&global_start, &global_end, Some(&[3, 4, 5])));
        let global: Vec<u32> = (0..6).map(|v| (v + 3) % 6).collect();
        let mut local = vec![0; 6];
        for (l, &g) in global.iter().enumerate() {
            local[g as usize] = l as u32;
        }
        let start: Vec<DVec3> = global.iter().map(|&g| global_start[g as usize]).collect();
        // Local triangle 0 is the mover (local 0, 1, 2 = global 3, 4, 5).
        let tris = [[0, 1, 2], [3, 4, 5]];
        let numbering = Numbering {
            global: &global,
            local: &local,
        };
        let sampler = PathSampler::new(&tris, &start, Keyframes::Recorded(&path, numbering));
        assert_eq!(sampler.parity(0, 1, [1.0 / 3.0; 3]), Some(true));
    }
}
