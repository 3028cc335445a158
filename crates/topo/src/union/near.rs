//! Where a Boolean looks for the pairs across its two solids, and the
//! frame each solid's self-crossing check measures its boxes in.
//!
//! Why: on turned CAD parts the frame boxes are measured in decides how
//! many candidate pairs a tree finds ([`holey_geom::frame`]), and a tree
//! of 68k triangles costs about as much to build as testing 130k
//! candidate pairs. Left to itself, a Boolean with the self-crossing
//! check would build three trees of its bigger solid: the check's, in
//! that solid's own frame; an axis-aligned one for the containment rays;
//! and one in the joint frame of both near sets for the pairs across. So
//! each solid keeps one tree, which the rays and the pairs across reuse,
//! and where the joint frame serves the check about as well as the
//! solid's own, the check builds it there (EMBER
//! 1063852 − 72214: the joint frame is 72214's, in which 1063852's check
//! finds as many candidates as in its own, while 72214's slivers turned
//! in 1063852's frame give 181,166 candidate pairs across instead of
//! 36,238).

use holey_geom::{Aabb, BoxFrame, Bvh};
use rayon::prelude::*;

use super::{Parts, UnionError};
use crate::engine::TopoError;
use crate::intersect::{Candidates, Primitives};
use crate::mesh::TriMesh;

/// The triangles of each solid whose boxes meet the other solid's box
/// (only they can meet the other solid), and the frame of them all.
pub(super) struct NearSets {
    /// A's near triangles, numbered in A, then B's, numbered in B; each
    /// increasing.
    near: [Vec<u32>; 2],
    /// [`BoxFrame::of_triangles`] of both near sets together: the frame
    /// the pairs across are best found in, measured on the EMBER pairs
    /// (either solid's own frame can leave the other's slivers turned).
    joint: BoxFrame,
}

/// The box of every triangle of `m` together (indices checked already).
fn bounds(m: &TriMesh) -> Aabb {
    (0..m.triangles.len())
        .into_par_iter()
        .map(|t| Aabb::from_points(&m.corners(t)))
        .reduce(|| Aabb::EMPTY, |x, y| x.union(&y))
}

/// The triangles of `m` whose boxes meet `other`, in increasing order: a
/// pass over the corners, cheaper than a tree built for it.
fn meeting(m: &TriMesh, other: &Aabb) -> Vec<u32> {
    (0..m.triangles.len() as u32)
        .into_par_iter()
        .filter(|&t| Aabb::from_points(&m.corners(t as usize)).overlaps(other))
        .collect()
}

/// The triangles of `m` listed in `near`.
fn gathered(m: &TriMesh, near: &[u32]) -> Vec<[u32; 3]> {
    near.iter().map(|&t| m.triangles[t as usize]).collect()
}

/// Whether `near` triangles are most of a solid's `all`: then a tree of
/// all its triangles serves the pairs across about as well as one of the
/// near ones.
fn most(near: usize, all: usize) -> bool {
    2 * near >= all
}

impl NearSets {
    /// The near sets of `a` and `b` (both checked) and their joint frame.
    pub(super) fn of(a: &TriMesh, b: &TriMesh) -> NearSets {
        let near = near_triangles(a, b);
        let joint = joint_frame(a, b, &near);
        NearSets { near, joint }
    }

    /// [`NearSets::of`], and the frame each solid's self-crossing check
    /// should build its tree in: the joint frame where most of the solid
    /// is near the other (its tree then serves the pairs across, and one
    /// tree build of its near triangles is saved) and the check's
    /// estimated candidate pairs there exceed those in its own frame by
    /// less than that build costs; otherwise `None`, its own frame (which
    /// the check finds beside its other whole-mesh passes).
    pub(super) fn with_check_frames(a: &TriMesh, b: &TriMesh) -> (NearSets, [Option<BoxFrame>; 2]) {
        let near = near_triangles(a, b);
        let joint = joint_frame(a, b, &near);
        let choose = |m: &TriMesh, near: usize| -> Option<BoxFrame> {
            if !most(near, m.triangles.len()) {
                return None;
            }
            let sample = Spread::of(m.triangles.len());
            // The own frame of the 4,096 triangles counted against: close
            // enough to the whole mesh's for an estimate, at a sixteenth
            // of the cost on 68k triangles.
            let tris: Vec<[u32; 3]> = sample.against.iter().map(|&t| m.triangles[t]).collect();
            let own = BoxFrame::of_triangles(&[(&m.positions, &tris)]);
            if own == joint {
                return Some(joint);
            }
            let (in_own, in_joint) = rayon::join(
                || sample.overlaps_per_triangle(m, &own),
                || sample.overlaps_per_triangle(m, &joint),
            );
            let n = m.triangles.len() as f64;
            (in_joint * n <= in_own * n + BUILD_PER_TRIANGLE * near as f64).then_some(joint)
        };
        let (fa, fb) = rayon::join(|| choose(a, near[0].len()), || choose(b, near[1].len()));
        (NearSets { near, joint }, [fa, fb])
    }
}

/// The triangles of `a` whose boxes meet the box of `b`, and those of
/// `b` meeting the box of `a`.
fn near_triangles(a: &TriMesh, b: &TriMesh) -> [Vec<u32>; 2] {
    let (box_a, box_b) = rayon::join(|| bounds(a), || bounds(b));
    let (near_a, near_b) = rayon::join(|| meeting(a, &box_b), || meeting(b, &box_a));
    [near_a, near_b]
}

/// [`BoxFrame::of_triangles`] of both near sets together.
fn joint_frame(a: &TriMesh, b: &TriMesh, [near_a, near_b]: &[Vec<u32>; 2]) -> BoxFrame {
    BoxFrame::of_triangles(&[
        (&a.positions, &gathered(a, near_a)),
        (&b.positions, &gathered(b, near_b)),
    ])
}

/// Triangles of a solid whose boxes are counted in [`Spread`].
const SELF_SAMPLE: usize = 256;
/// Triangles of a solid they are counted against.
const SELF_AGAINST: usize = 4096;

/// Triangles spread over a mesh of `n` for an estimate of its
/// self-crossing check's candidate pairs: [`SELF_SAMPLE`] counted
/// against [`SELF_AGAINST`] others.
struct Spread {
    n: usize,
    against: Vec<usize>,
    counted: Vec<usize>,
}

impl Spread {
    fn of(n: usize) -> Spread {
        let against = (0..n).step_by(n.div_ceil(SELF_AGAINST).max(1)).collect();
        let step = n.div_ceil(SELF_SAMPLE).max(1);
        let counted = (step / 2..n).step_by(step).collect();
        Spread {
            n,
            against,
            counted,
        }
    }

    /// An estimate of how many other triangles' boxes each triangle's box
    /// meets in `frame`: the check's candidate pairs there, per triangle.
    /// The counted triangles' boxes are tested against a tree of the
    /// others', and the count is scaled to the whole mesh (about 150 pairs
    /// are found on a smooth part, so the estimate is good to a tenth).
    /// Infinite where no tree can be built (a non-finite box), so that
    /// the other frame is taken.
    fn overlaps_per_triangle(&self, m: &TriMesh, frame: &BoxFrame) -> f64 {
        if self.n < 2 {
            return 0.0;
        }
        let box_of = |t: usize| frame.triangle_box(m.corners(t));
        let boxes: Vec<Aabb> = self.against.iter().map(|&t| box_of(t)).collect();
        let Ok(tree) = Bvh::build(&boxes) else {
            return f64::INFINITY;
        };
        let mut found = 0usize;
        for &s in &self.counted {
            tree.for_each_overlap(&box_of(s), |k| {
                if self.against[k as usize] != s {
                    found += 1;
                }
            });
        }
        found as f64 / self.counted.len().max(1) as f64 * self.n as f64 / self.against.len() as f64
    }
}

/// The trees the pairs across A and B are found in: only the triangles
/// whose boxes meet the other solid's box can meet it (a small part
/// placed on a big one needs a few of the big one's triangles), and
/// boxes are measured in the [`BoxFrame`] of those triangles (turned CAD
/// parts' flat faces then have flat boxes: EMBER pairs 1.14M candidate
/// pairs → 0.21M), or in the frame of a solid's own tree where that is
/// cheaper.
pub(super) struct Near<'p> {
    /// A's tree and B's.
    pub(super) trees: [NearTree<'p>; 2],
}

/// One solid's tree of [`Near`].
pub(super) enum NearTree<'p> {
    /// A tree of the listed triangles (numbered in the joined mesh).
    Listed(Vec<u32>, Bvh),
    /// The solid's own tree of every triangle ([`Parts::tree`]), whose
    /// triangles start at `offset` in the joined mesh.
    Whole(&'p Bvh, u32),
}

impl NearTree<'_> {
    fn tree_and_triangles(&self) -> (&Bvh, Primitives<'_>) {
        match self {
            NearTree::Listed(list, tree) => (tree, Primitives::Listed(list)),
            NearTree::Whole(tree, offset) => (tree, Primitives::From(*offset)),
        }
    }
}

/// Triangles of each near set sampled to cost a frame.
const FRAME_SAMPLE: usize = 256;

/// A tree build's cost per triangle (its box and its share of the
/// build), in candidate pairs tested: measured, a 68k-triangle tree took
/// about as long as 130k candidate pairs.
const BUILD_PER_TRIANGLE: f64 = 2.0;

/// Sampled triangles' corners, and how many triangles each stands for.
type Sample = (Vec<[glam::DVec3; 3]>, f64);

/// The corners of every k-th of the triangles of `m` listed in `near`,
/// at most [`FRAME_SAMPLE`] of them, and how many triangles each stands
/// for.
fn sample(m: &TriMesh, near: &[u32]) -> Sample {
    let step = near.len().div_ceil(FRAME_SAMPLE).max(1);
    let corners: Vec<[glam::DVec3; 3]> = near
        .iter()
        .step_by(step)
        .map(|&t| m.corners(t as usize))
        .collect();
    let weight = near.len() as f64 / corners.len().max(1) as f64;
    (corners, weight)
}

/// The cost of finding the pairs across two near sets in `frame`, in
/// candidate pairs: the pairs of the samples' boxes that overlap, scaled
/// up to the whole sets, plus building trees of `to_build` triangles.
fn frame_cost(frame: &BoxFrame, ((a, wa), (b, wb)): &(Sample, Sample), to_build: usize) -> f64 {
    let boxes_b: Vec<Aabb> = b.iter().map(|&p| frame.triangle_box(p)).collect();
    let overlapping: usize = a
        .iter()
        .map(|&p| {
            let x = frame.triangle_box(p);
            boxes_b.iter().filter(|y| x.overlaps(y)).count()
        })
        .sum();
    overlapping as f64 * wa * wb + BUILD_PER_TRIANGLE * to_build as f64
}

impl<'p> Near<'p> {
    /// The trees for the pairs across `a` and `b` (B's triangles
    /// numbered after A's), from their near sets.
    ///
    /// The frame the pairs are found in is the joint one, or the frame of
    /// a solid's own tree of all its triangles (the world's axes, or the
    /// one its self-crossing check chose): where most of that solid is
    /// near the other, its tree is reused, and only the other's near
    /// triangles need a tree measured in that very frame. Neither is
    /// always best: a small part turned otherwise than a big one can hold
    /// most of the joint area, and the big one's slivers are then turned
    /// in the joint frame (EMBER 79741 − 65004: 210,232 pairs of boxes
    /// there, 25,302 in 79741's own frame), or it is the one whose
    /// slivers turn (1063852 − 72214: 36,238 against 181,166). So each is
    /// costed from a sample of both near sets, trees to build included.
    pub(super) fn of(
        a: &TriMesh,
        pa: &'p Parts,
        b: &TriMesh,
        pb: &'p Parts,
        sets: &NearSets,
    ) -> Result<Near<'p>, UnionError> {
        let [near_a, near_b] = &sets.near;
        let reach = [
            most(near_a.len(), a.triangles.len()),
            most(near_b.len(), b.triangles.len()),
        ];
        let samples = (sample(a, near_a), sample(b, near_b));
        let whole = [&pa.tree, &pb.tree];
        // Which solids' own trees serve in `frame`.
        let reused = |frame: &BoxFrame| -> [bool; 2] {
            [0, 1].map(|k| reach[k] && whole[k].frame == *frame)
        };
        let cost = |frame: &BoxFrame| -> f64 {
            let r = reused(frame);
            let to_build = (0..2).filter(|&k| !r[k]).map(|k| sets.near[k].len()).sum();
            frame_cost(frame, &samples, to_build)
        };
        let mut frames = vec![sets.joint, pa.tree.frame, pb.tree.frame];
        frames.dedup();
        let frame = frames
            .iter()
            .map(|f| (*f, cost(f)))
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .map_or(sets.joint, |(f, _)| f);
        let r = reused(&frame);
        let split = a.triangles.len() as u32;
        let tree_of = |k: usize| -> Result<NearTree<'p>, UnionError> {
            let (m, offset) = if k == 0 { (a, 0) } else { (b, split) };
            if r[k] {
                return Ok(NearTree::Whole(&whole[k].tree, offset));
            }
            let boxes: Vec<Aabb> = sets.near[k]
                .par_iter()
                .map(|&t| frame.triangle_box(m.corners(t as usize)))
                .collect();
            let listed = sets.near[k].iter().map(|&t| t + offset).collect();
            Ok(NearTree::Listed(
                listed,
                Bvh::build(&boxes).map_err(TopoError::from)?,
            ))
        };
        let (ta, tb) = rayon::join(|| tree_of(0), || tree_of(1));
        Ok(Near { trees: [ta?, tb?] })
    }

    pub(super) fn candidates(&self) -> Candidates<'_> {
        let [ta, tb] = &self.trees;
        let (first, first_triangles) = ta.tree_and_triangles();
        let (second, second_triangles) = tb.tree_and_triangles();
        Candidates::Across {
            first,
            first_triangles,
            second,
            second_triangles,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::intersect::tests::{ellipse, fan_prism, turn};
    use glam::DVec3;

    /// Turned about another axis than [`turn`].
    fn turn_otherwise(q: DVec3) -> DVec3 {
        let axis = DVec3::new(3.0, -1.0, 2.0).normalize();
        let (s, c) = 1.1f64.sin_cos();
        q * c + axis.cross(q) * s + axis * axis.dot(q) * (1.0 - c)
    }

    /// Pairs of overlapping boxes among all of `m`'s triangles in `frame`,
    /// counted through a tree of them all.
    fn pairs_in(m: &TriMesh, frame: &BoxFrame) -> usize {
        let boxes: Vec<Aabb> = m
            .triangles
            .iter()
            .map(|t| frame.triangle_box(t.map(|v| m.positions[v as usize])))
            .collect();
        Bvh::build(&boxes).unwrap().self_overlaps().len()
    }

    /// A thin slivered part inside a big block turned another way: the
    /// block holds most of the joint area, so the joint frame is the
    /// block's, where the part's slivers turn and their boxes meet more
    /// (counted whole here); the part's check keeps its own frame.
    /// Turned the same way as the block, the part is checked in the joint
    /// frame, whose tree then serves the pairs across.
    #[test]
    fn a_check_takes_the_joint_frame_only_where_its_slivers_stay_thin() {
        let part = |t: fn(DVec3) -> DVec3| fan_prism(&ellipse(300, 1.0, 0.5), 0.05, t, DVec3::ZERO);
        let block = fan_prism(
            &ellipse(8, 3.0, 3.0),
            2.0,
            turn,
            turn(DVec3::new(0.0, 0.0, -1.0)),
        );
        for (t, same) in [(turn_otherwise as fn(DVec3) -> DVec3, false), (turn, true)] {
            let a = part(t);
            let (sets, [fa, _]) = NearSets::with_check_frames(&a, &block);
            assert_eq!(
                sets.near[0].len(),
                a.triangles.len(),
                "the part is inside the block"
            );
            let own = BoxFrame::of_triangles(&[(&a.positions, &a.triangles)]);
            let (in_own, in_joint) = (pairs_in(&a, &own), pairs_in(&a, &sets.joint));
            if same {
                assert_eq!(fa, Some(sets.joint));
                assert!(
                    in_joint as f64 <= 1.05 * in_own as f64,
                    "{in_joint} against {in_own}"
                );
            } else {
                assert_eq!(fa, None);
                assert!(
                    in_joint as f64 > 1.2 * in_own as f64,
                    "{in_joint} against {in_own}"
                );
            }
        }
    }

    /// The estimate counts what a tree of every triangle finds: on a
    /// mesh small enough to be counted whole, exactly.
    #[test]
    fn the_estimate_is_the_count_where_every_triangle_is_counted() {
        let m = fan_prism(&ellipse(60, 1.0, 0.5), 0.2, turn, DVec3::ZERO);
        let n = m.triangles.len();
        assert!(n <= SELF_SAMPLE);
        let frame = BoxFrame::IDENTITY;
        let boxes: Vec<Aabb> = m
            .triangles
            .iter()
            .map(|t| frame.triangle_box(t.map(|v| m.positions[v as usize])))
            .collect();
        let mut pairs = 0usize;
        for i in 0..n {
            for j in 0..n {
                pairs += usize::from(i != j && boxes[i].overlaps(&boxes[j]));
            }
        }
        let estimate = Spread::of(n).overlaps_per_triangle(&m, &frame);
        assert!(
            (estimate - pairs as f64 / n as f64).abs() < 1e-9,
            "{estimate}"
        );
    }
}
