//! Crossings parity left whole: a curve edge with all four sides kept.
//!
//! Two sheets that cross along a curve are glued there (§3.5), and parity
//! deletes one half of each. Where the motion swept no vertex on either
//! side, every half is kept and the glued curve is an X: four
//! sub-triangles on one edge, a non-manifold curve. It happens where an
//! open sheet's rim passes through another sheet near that sheet's own
//! rim (an inflate dwelling on a scan's hole): the curve is an arc from
//! one rim to the other, it bounds no region on either sheet, and no
//! parity can delete anything there. The paper leaves the X; the guard
//! then holds the frame, and a dwelling brush stalls for the rest of its
//! stroke.
//!
//! The X is reconnected instead. Around the edge the four halves
//! alternate, sheet A, sheet B, A, B, so joining each half of A to a
//! half of B pairs cyclic neighbours, and the result is embedded: the
//! sheets fuse at the crossing instead of passing through each other.
//! Of the two such pairings, orientation picks one: each half of A runs
//! the edge one way, so it joins the half of B that runs it the other
//! way, and the fused surface stays consistently oriented. For two
//! closed solids crossing, this pairing joins their outsides into the
//! union's surface and their insides into the intersection's: what a
//! union keeps and what it deletes (the guard refuses that inner piece
//! as hidden, as it refused the X).
//!
//! The curve's points then belong to two fans, one per pairing, and are
//! split into two vertices at one position; a point where the curve ends
//! on a rim stays one vertex, the rim passing through it.

use rustc_hash::FxHashMap as HashMap;

use glam::DVec3;

use super::junctions::runs_forward;
use super::{AroundCurve, Sources};
use crate::union_find::UnionFind;

/// Reconnects every curve edge whose four kept sub-triangles (of those
/// `around` it) are two sheets crossing (module docs): `tris` are renamed
/// in place and the split points' copies appended to `positions`.
/// Returns the number of edges reconnected.
pub(super) fn reconnect(
    tris: &mut Vec<[u32; 3]>,
    keep: &mut Vec<bool>,
    source: &mut Sources,
    around: &AroundCurve,
    positions: &mut Vec<DVec3>,
) -> usize {
    // Each crossing edge with its two pairs of sub-triangles to join.
    let mut crossing: HashMap<(u32, u32), [(usize, usize); 2]> = HashMap::default();
    for (&(a, b), subs) in around {
        let kept: Vec<usize> = subs.iter().copied().filter(|&s| keep[s]).collect();
        if let Some(pairs) = pairing(tris, source, &kept, a, b) {
            crossing.insert((a, b), pairs);
        }
    }
    if crossing.is_empty() {
        return 0;
    }
    split_lone_edges(tris, keep, source, positions, &mut crossing);
    // The kept sub-triangles around every point of a crossing edge.
    let mut points: Vec<u32> = crossing.keys().flat_map(|&(a, b)| [a, b]).collect();
    points.sort_unstable();
    points.dedup();
    let mut corners: Vec<(u32, usize, usize)> = Vec::new();
    for (s, t) in tris.iter().enumerate() {
        if !keep[s] {
            continue;
        }
        for (k, &v) in t.iter().enumerate() {
            if points.binary_search(&v).is_ok() {
                corners.push((v, s, k));
            }
        }
    }
    corners.sort_unstable();
    // Fans around each point, joined across its edges: an ordinary edge
    // joins every kept sub-triangle on it, a crossing edge only its pairs.
    // Renames are collected first so that every point sees the names the
    // cut gave.
    let mut renames: Vec<(usize, usize, u32)> = Vec::new();
    let mut sets = UnionFind::default();
    let mut by_neighbour: Vec<(u32, usize)> = Vec::new();
    for group in corners.chunk_by(|x, y| x.0 == y.0) {
        let v = group[0].0;
        sets.reset(group.len());
        by_neighbour.clear();
        for (j, &(_, s, k)) in group.iter().enumerate() {
            let t = tris[s];
            by_neighbour.push((t[(k + 1) % 3], j));
            by_neighbour.push((t[(k + 2) % 3], j));
        }
        by_neighbour.sort_unstable();
        for run in by_neighbour.chunk_by(|x, y| x.0 == y.0) {
            let u = run[0].0;
            match crossing.get(&(v.min(u), v.max(u))) {
                Some(pairs) => {
                    let slot = |s: usize| group.iter().position(|c| c.1 == s);
                    for &(p, q) in pairs {
                        if let (Some(i), Some(j)) = (slot(p), slot(q)) {
                            sets.union(i as u32, j as u32);
                        }
                    }
                }
                None => {
                    for w in run.windows(2) {
                        sets.union(w[0].1 as u32, w[1].1 as u32);
                    }
                }
            }
        }
        // The fan of the first corner keeps the point; each other fan
        // gets a copy.
        let mut name: Vec<Option<u32>> = vec![None; group.len()];
        let first = sets.find(0) as usize;
        name[first] = Some(v);
        for (j, &(_, s, k)) in group.iter().enumerate() {
            let r = sets.find(j as u32) as usize;
            let to = *name[r].get_or_insert_with(|| {
                positions.push(positions[v as usize]);
                (positions.len() - 1) as u32
            });
            if to != v {
                renames.push((s, k, to));
            }
        }
    }
    for (s, k, to) in renames {
        tris[s][k] = to;
    }
    crossing.len()
}

/// Splits at its midpoint every crossing edge that no other crossing
/// edge touches: a curve of one edge from one rim to the other. Both its
/// points are rim points, each one fan, so the joined pairs would share
/// both and stay one edge; the midpoint is the curve point they split at.
/// Each sub-triangle on the edge becomes two, of the same source.
fn split_lone_edges(
    tris: &mut Vec<[u32; 3]>,
    keep: &mut Vec<bool>,
    source: &mut Sources,
    positions: &mut Vec<DVec3>,
    crossing: &mut HashMap<(u32, u32), [(usize, usize); 2]>,
) {
    let mut touching: HashMap<u32, u32> = HashMap::default();
    for &(a, b) in crossing.keys() {
        *touching.entry(a).or_default() += 1;
        *touching.entry(b).or_default() += 1;
    }
    let mut lone: Vec<(u32, u32)> = crossing
        .keys()
        .copied()
        .filter(|(a, b)| touching[a] == 1 && touching[b] == 1)
        .collect();
    // Deterministic numbering of the new points and triangles.
    lone.sort_unstable();
    for (a, b) in lone {
        let Some(pairs) = crossing.remove(&(a, b)) else {
            continue;
        };
        let m = positions.len() as u32;
        positions.push((positions[a as usize] + positions[b as usize]) * 0.5);
        // Sub-triangle s keeps the half at a (b renamed m); its copy, the
        // half at b (a renamed m), is appended.
        let mut half_at_b = |s: usize| {
            let t = tris[s];
            tris[s] = t.map(|v| if v == b { m } else { v });
            tris.push(t.map(|v| if v == a { m } else { v }));
            keep.push(true);
            source.sub.push(source.get(s));
            tris.len() - 1
        };
        let mut second = [(0, 0); 2];
        for (k, &(p, q)) in pairs.iter().enumerate() {
            second[k] = (half_at_b(p), half_at_b(q));
        }
        crossing.insert((a.min(m), a.max(m)), pairs);
        crossing.insert((m.min(b), m.max(b)), second);
    }
}

/// The two pairs to join at curve edge `(a, b)` when its kept
/// sub-triangles `subs` are two sheets crossing: two source triangles,
/// each with one sub-triangle running the edge from `a` to `b` and one
/// from `b` to `a`. Each joins the other sheet's sub-triangle that runs
/// the edge the other way.
fn pairing(
    tris: &[[u32; 3]],
    source: &Sources,
    subs: &[usize],
    a: u32,
    b: u32,
) -> Option<[(usize, usize); 2]> {
    let &[first, ..] = subs else {
        return None;
    };
    let (sheet_a, sheet_b): (Vec<usize>, Vec<usize>) = subs
        .iter()
        .partition(|&&s| source.triangle(s) == source.triangle(first));
    let (&[a1, a2], &[b1, b2]) = (sheet_a.as_slice(), sheet_b.as_slice()) else {
        return None;
    };
    if source.triangle(b1) != source.triangle(b2) {
        return None;
    }
    // A sheet's two halves, the one running the edge from a to b first.
    let halves =
        |x: usize, y: usize| match (runs_forward(tris[x], a, b), runs_forward(tris[y], a, b)) {
            (true, false) => Some((x, y)),
            (false, true) => Some((y, x)),
            _ => None,
        };
    let (a_forward, a_backward) = halves(a1, a2)?;
    let (b_forward, b_backward) = halves(b1, b2)?;
    Some([(a_forward, b_backward), (a_backward, b_forward)])
}
