//! T-junctions left by vertex-sampled parity (Figure 7).
//!
//! Where a kept curve ends at a sheet's boundary, the even/odd boundary
//! parity draws on the *other* sheet runs along mesh edges (false edges,
//! §3.5) and rarely reaches the curve's end. The curve's last stretch then
//! crosses triangles of the swept sheet whose corners are all even, so
//! both halves of that sheet are kept, while the crossing sheet is cut
//! (one half kept, one deleted): three kept sub-triangles at one curve
//! edge, a non-manifold T.
//!
//! The motion decides which half of the swept sheet was crossed: a point
//! just beside the curve edge on each half is tested as if it were a
//! vertex ([`Sampler`], the refinement of §7). When exactly one half is
//! odd its sub-triangle at that edge is deleted, and the edge joins the
//! kept half of each sheet.
//!
//! When the motion says both halves are even, the parity field really has
//! a T there: an open sheet's end pushed into another sheet (a spout into
//! a teapot's body, a tube into a sphere: the tube has no lid, so nothing
//! sweeps the part of the other sheet inside its loop). Orientation then
//! decides. Of the uncut sheet's two halves, the one that runs the curve
//! edge the same way as the crossing sheet's kept half cannot pair with
//! it into a consistently oriented surface; its region (reached across
//! everything but curve edges) is deleted when curve edges enclose it on
//! every side, so the tube opens into the sheet it entered. A region that
//! reaches an open boundary is left: nothing encloses it, and deleting it
//! would remove surface far from the contact.

use rustc_hash::FxHashMap as HashMap;

use glam::DVec3;

use super::{AroundCurve, Sampler, Sources};
use crate::mesh::Edges;

/// Most junction edges examined per cut: each costs two to six
/// moving-point queries, and past a few thousand the surface is crumpled beyond what
/// local repair can mend.
pub const MAX_JUNCTION_EDGES: usize = 4096;

/// How far into a sub-triangle, from its curve edge toward the opposite
/// corner, a side's sample sits (a fraction of that corner's weight):
/// close to the curve, where the swept half is swept, yet off it. The
/// swept half narrows to nothing where the curve ends on a boundary (a
/// rim edge pierced the sheet), so when the two samples agree they are
/// taken again closer in; the last offset stays some ten orders of
/// magnitude above the rounding of the curve's points, so a sample never
/// lands on the wrong side of its edge.
const OFFSETS: [f64; 3] = [1.0 / 64.0, 1.0 / 4096.0, 1.0 / 262_144.0];

/// The sub-triangles and geometry one repair reads.
pub(super) struct Junctions<'a> {
    /// Sub-triangles (global vertex indices) and their source triangles.
    pub tris: &'a [[u32; 3]],
    pub source: &'a Sources,
    /// Positions of the global vertices (at the frame's end).
    pub positions: &'a [DVec3],
    /// The input's triangles and their end positions (the source frame).
    pub input_tris: &'a [[u32; 3]],
    pub input_positions: &'a [DVec3],
    /// Curve edges (sorted, deduplicated `(min, max)` pairs).
    pub curve: &'a [(u32, u32)],
    /// The sub-triangles on each curve edge ([`super::around_curve`]).
    pub around: &'a AroundCurve,
}

/// Barycentric weights of `q` in triangle `p` (least squares in its
/// plane); `None` for a degenerate triangle.
fn barycentric(p: [DVec3; 3], q: DVec3) -> Option<[f64; 3]> {
    let (e1, e2, d) = (p[1] - p[0], p[2] - p[0], q - p[0]);
    let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let det = a * c - b * b;
    // Scale-relative: the Gram determinant against its own terms (NaN
    // fails too).
    if det.partial_cmp(&(a * c * 1e-14)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let (r1, r2) = (d.dot(e1), d.dot(e2));
    let u = (c * r1 - b * r2) / det;
    let w = (a * r2 - b * r1) / det;
    Some([1.0 - u - w, u, w])
}

impl Junctions<'_> {
    /// The parity of the point beside edge `(a, b)` inside sub-triangle
    /// `s`, sampled with call number `k`.
    fn side_parity(
        &self,
        sample: &Sampler<'_>,
        k: u32,
        s: usize,
        (a, b): (u32, u32),
        offset: f64,
    ) -> Option<bool> {
        let t = self.tris[s];
        let c = *t.iter().find(|&&v| v != a && v != b)?;
        let at = |v: u32| self.positions.get(v as usize).copied();
        let q = (at(a)? + at(b)?) * (0.5 * (1.0 - offset)) + at(c)? * offset;
        let src = self.source.triangle(s);
        let corners = *self.input_tris.get(src as usize)?;
        let p = corners.map(|v| self.input_positions[v as usize]);
        let w = barycentric(p, q)?;
        sample(k, src, w)
    }

    /// Deletes the swept side of a source triangle: the kept sub-triangles
    /// of its source reachable from `swept` without crossing a curve edge.
    /// Deleting only `swept` would leave the side's other sub-triangles
    /// at the same curve point as a second fan there (a pinch vertex).
    fn delete_side(
        &self,
        keep: &mut [bool],
        swept: usize,
        by_source: &HashMap<u32, Vec<usize>>,
    ) -> usize {
        let Some(siblings) = by_source.get(&self.source.triangle(swept)) else {
            return 0;
        };
        let is_curve = |a: u32, b: u32| self.curve.binary_search(&(a.min(b), a.max(b))).is_ok();
        let shares_open_edge = |s: usize, r: usize| {
            let (t, u) = (self.tris[s], self.tris[r]);
            (0..3).any(|i| {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                !is_curve(a, b) && u.contains(&a) && u.contains(&b)
            })
        };
        keep[swept] = false;
        let mut deleted = 1;
        let mut stack = vec![swept];
        while let Some(s) = stack.pop() {
            for &r in siblings {
                if keep[r] && shares_open_edge(s, r) {
                    keep[r] = false;
                    deleted += 1;
                    stack.push(r);
                }
            }
        }
        deleted
    }

    /// Deletes (`keep[s] = false`) the swept half at every curve edge with
    /// three kept sub-triangles where the motion tells the halves apart
    /// (`sample`: one frame's straight motion), else the enclosed half
    /// against the crossing sheet's orientation (module docs). Returns the
    /// number of sub-triangles deleted. `first_call` numbers the samples
    /// after those the labelling made.
    pub fn repair(
        &self,
        keep: &mut [bool],
        sample: Option<&Sampler<'_>>,
        open_ends: bool,
        first_call: u32,
    ) -> usize {
        if self.curve.is_empty() {
            return 0;
        }
        let subs = self.source.first_sub()..self.tris.len();
        let mut junctions: Vec<((u32, u32), &[usize])> = self
            .around
            .iter()
            .filter(|(_, ss)| ss.iter().filter(|&&s| keep[s]).count() == 3)
            .map(|(&e, ss)| (e, ss.as_slice()))
            .collect();
        // Deterministic order (the map's is not).
        junctions.sort_unstable_by_key(|(e, _)| *e);
        // Sub-triangles of each source triangle touched by a junction.
        let mut by_source: HashMap<u32, Vec<usize>> = HashMap::default();
        for (_, ss) in &junctions {
            for &s in ss.iter() {
                by_source.entry(self.source.triangle(s)).or_default();
            }
        }
        for s in subs {
            if let Some(list) = by_source.get_mut(&self.source.triangle(s)) {
                list.push(s);
            }
        }
        let mut call = first_call;
        let mut deleted = 0;
        // Built once, only if orientation has to decide.
        let mut edges: Option<Edges> = None;
        for ((a, b), ss) in junctions.into_iter().take(MAX_JUNCTION_EDGES) {
            // Still a T after the repairs so far?
            if ss.iter().filter(|&&s| keep[s]).count() != 3 {
                continue;
            }
            // The sheet kept on both sides: two sub-triangles of one source
            // triangle, both kept.
            let Some((s0, s1)) = ss.iter().enumerate().find_map(|(i, &s)| {
                ss[i + 1..]
                    .iter()
                    .find(|&&r| {
                        keep[s] && keep[r] && self.source.triangle(r) == self.source.triangle(s)
                    })
                    .map(|&r| (s, r))
            }) else {
                continue;
            };
            let mut sides = (None, None);
            if let Some(sample) = sample {
                for offset in OFFSETS {
                    call += 2;
                    sides = (
                        self.side_parity(sample, call - 2, s0, (a, b), offset),
                        self.side_parity(sample, call - 1, s1, (a, b), offset),
                    );
                    if matches!(sides, (Some(x), Some(y)) if x != y) {
                        break;
                    }
                }
            }
            let (odd0, odd1) = sides;
            match (odd0, odd1) {
                (Some(true), Some(false)) => deleted += self.delete_side(keep, s0, &by_source),
                (Some(false), Some(true)) => deleted += self.delete_side(keep, s1, &by_source),
                _ if open_ends => {
                    let Some(&crossing) = ss.iter().find(|&&s| keep[s] && s != s0 && s != s1)
                    else {
                        continue;
                    };
                    let runs = |s: usize| runs_forward(self.tris[s], a, b);
                    let (against, with) = if runs(s0) == runs(crossing) {
                        (s0, s1)
                    } else {
                        (s1, s0)
                    };
                    let edges = edges.get_or_insert_with(|| Edges::of_triangles(self.tris));
                    deleted += self.delete_enclosed(keep, against, with, edges);
                }
                _ => {}
            }
        }
        deleted
    }

    /// Deletes the kept region of `from` (reached across kept triangles'
    /// shared edges that are not curve edges) when curve edges bound it on
    /// every side and part it from `other`, the far side of the curve
    /// edge; returns the number deleted (0 when it reaches an open
    /// boundary or `other`: a curve that does not enclose it, such as a
    /// sheet's edge pushed into a ball, Figure 11).
    fn delete_enclosed(
        &self,
        keep: &mut [bool],
        from: usize,
        other: usize,
        edges: &Edges,
    ) -> usize {
        let is_curve = |a: u32, b: u32| self.curve.binary_search(&(a.min(b), a.max(b))).is_ok();
        let mut region = vec![from];
        let mut seen: rustc_hash::FxHashSet<usize> = std::iter::once(from).collect();
        let mut at = 0;
        while let Some(&s) = region.get(at) {
            at += 1;
            let t = self.tris[s];
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                if is_curve(a, b) {
                    continue;
                }
                let mut alone = true;
                for &r in edges.triangles(edges.of_triangle[s][i] as usize) {
                    let r = r as usize;
                    if r != s && keep[r] {
                        alone = false;
                        if seen.insert(r) {
                            region.push(r);
                        }
                    }
                }
                if alone {
                    return 0;
                }
            }
            if seen.contains(&other) {
                return 0;
            }
        }
        for &s in &region {
            keep[s] = false;
        }
        region.len()
    }
}

/// Whether triangle `t` runs its edge from `a` to `b` (rather than from
/// `b` to `a`).
pub(super) fn runs_forward(t: [u32; 3], a: u32, b: u32) -> bool {
    (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A T where the swept half is thinner than the first sample's
    /// offset reaches, as where a rim edge pierced a sheet: sheet A (one
    /// source triangle in z = 0, corners 0, 1, 2) is crossed by a curve
    /// from its edge 0–2 to its edge 1–2 (points 6, 7), and the motion
    /// swept only a band 0.001 wide below the curve (the sampler here is
    /// that band). A's two halves and sheet B's kept part (source 1) meet
    /// at the curve edge. The first samples, 1/64 of the way to the far
    /// corners, both miss the band; the closer ones find it, and A's
    /// swept half is deleted.
    #[test]
    fn a_thin_swept_half_is_found_by_closer_samples() {
        let input_positions = vec![
            DVec3::new(-4.0, -4.0, 0.0),
            DVec3::new(4.0, -4.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
            DVec3::new(-3.0, 0.0, -1.0),
            DVec3::new(3.0, 0.0, -1.0),
            DVec3::new(0.0, 0.0, 2.0),
        ];
        let input_tris = vec![[0, 1, 2], [3, 4, 5]];
        let mut positions = input_positions.clone();
        positions.push(DVec3::new(-2.0, 0.0, 0.0));
        positions.push(DVec3::new(2.0, 0.0, 0.0));
        // A below the curve (two), A above it, B above A.
        let tris = vec![[0, 1, 7], [0, 7, 6], [6, 7, 2], [7, 6, 5]];
        let source = Sources {
            whole: Vec::new(),
            sub: vec![(0, [0.0; 2]), (0, [0.0; 2]), (0, [0.0; 2]), (1, [0.0; 2])],
        };
        let curve = [(6, 7)];
        let around = super::super::around_curve(&tris, source.first_sub(), &curve, positions.len());
        let junctions = Junctions {
            tris: &tris,
            source: &source,
            positions: &positions,
            input_tris: &input_tris,
            input_positions: &input_positions,
            curve: &curve,
            around: &around,
        };
        let band = |_: u32, t: u32, w: [f64; 3]| -> Option<bool> {
            let p = input_tris[t as usize]
                .iter()
                .zip(w)
                .map(|(&v, wi)| input_positions[v as usize] * wi)
                .sum::<DVec3>();
            Some(t == 0 && p.y < 0.0 && p.y > -0.001)
        };
        // The first offset alone cannot tell the halves apart.
        for s in [1, 2] {
            assert_eq!(
                junctions.side_parity(&band, 0, s, (6, 7), OFFSETS[0]),
                Some(false)
            );
        }
        let mut keep = vec![true; 4];
        let deleted = junctions.repair(&mut keep, Some(&band), true, 0);
        assert_eq!(deleted, 2);
        assert_eq!(keep, [false, false, true, true]);
    }

    #[test]
    fn barycentric_recovers_weights_and_refuses_degenerate() {
        let p = [
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(4.0, 2.5, 3.0),
            DVec3::new(1.5, 6.0, 2.0),
        ];
        let w = [0.2, 0.3, 0.5];
        let q = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
        let got = barycentric(p, q).expect("a proper triangle");
        for k in 0..3 {
            assert!((got[k] - w[k]).abs() < 1e-12, "{got:?}");
        }
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(barycentric(flat, DVec3::X), None);
    }
}
