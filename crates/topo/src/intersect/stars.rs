//! Vertex stars that provably lie flat: two of their triangles that share
//! only the star's centre meet nowhere else, so those pairs need no test.
//!
//! CAD triangulations are fans: a vertex on a flat cap or a cylinder's
//! end carries hundreds of long triangles, whose boxes all overlap. On
//! EMBER's turned 3D-print parts these pairs were most of the candidate
//! pairs of a self-intersection check (365,608 of 447,035 tested on
//! thingi10k 1063852), every one dismissed by the plane filter only
//! after its corners and planes were read.
//!
//! **The certificate.** Take the star of a vertex `v` (every triangle
//! with a corner whose identity is `v`'s) and the link edges `a → b`
//! opposite `v`, in each triangle's order `(v, a, b)`. Project along the
//! coordinate axis `k` where the star's summed normal is largest. The
//! star is certified when:
//! 1. the link edges form one permutation of the link's identities (each
//!    identity starts exactly one edge and ends exactly one edge), so
//!    they close into disjoint cycles;
//! 2. every projected triangle `(v, a, b)` turns the same way `σ`, exactly
//!    and strictly (`orient2d ≠ 0`);
//! 3. the projected link winds around `v` exactly once: counted as the
//!    steps that cross the ray from `v` along the first projected axis,
//!    every step turning by less than π in the sense `σ`, so each pass
//!    over the ray is one crossing and their number is the winding number.
//!
//! Then the projected triangles are sectors around `v` with disjoint
//! interiors that fill one turn, and two sectors that are not neighbours
//! in the cycle meet only at `v`. A triangle projects one to one (its
//! projection has area), so in space the two triangles share only `v`.
//! Every sign above is strict, and an infinitesimal perturbation keeps
//! strict signs and the integer winding number, so the same holds in the
//! perturbed world of simulation of simplicity. (A star that fails any
//! test is simply not certified, and its pairs are tested as before.)

use crate::mesh::repeats_a_corner;
use glam::{DVec2, DVec3};
use holey_geom::orient::{Sign, orient2d};
use rayon::prelude::*;

/// Whether the star of each identity (indexed by identity, as
/// `holey_geom::position_classes` numbers them: `ids[v]` for vertex
/// `v`) is certified flat ([module documentation](self)). Identities no
/// vertex has, and every star with a triangle that repeats an identity
/// (no area even in the perturbed world), are not.
pub(crate) fn flat_stars(tris: &[[u32; 3]], positions: &[DVec3], ids: &[u32]) -> Vec<bool> {
    let n = ids.len();
    // Each identity's link edges, gathered by a counting sort: `start[v]`
    // to `start[v + 1]` in `link`, as vertex indices `(a, b)`.
    let mut start = vec![0u32; n + 1];
    let mut repeats = vec![false; n];
    let tri_ids = |t: &[u32; 3]| t.map(|c| ids[c as usize]);
    for t in tris {
        let i = tri_ids(t);
        if repeats_a_corner(&i) {
            for c in i {
                repeats[c as usize] = true;
            }
            continue;
        }
        for c in i {
            start[c as usize + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut link = vec![[0u32; 2]; start[n] as usize];
    for t in tris {
        let i = tri_ids(t);
        if repeats_a_corner(&i) {
            continue;
        }
        for k in 0..3 {
            let at = &mut fill[i[k] as usize];
            link[*at as usize] = [t[(k + 1) % 3], t[(k + 2) % 3]];
            *at += 1;
        }
    }
    // Two scratch lists per worker, not two allocations per vertex.
    (0..n)
        .into_par_iter()
        .map_init(
            || (Vec::new(), Vec::new()),
            |scratch, v| {
                let edges = &link[start[v] as usize..start[v + 1] as usize];
                !repeats[v]
                    && ids[v] as usize == v
                    && star_is_flat(positions[v], edges, positions, ids, scratch)
            },
        )
        .collect()
}

/// The three tests of the [module documentation](self) for the star of a
/// vertex at `centre` whose link edges are `edges` (vertex indices);
/// `scratch` holds the link's sorted ends.
fn star_is_flat(
    centre: DVec3,
    edges: &[[u32; 2]],
    positions: &[DVec3],
    ids: &[u32],
    (from, to): &mut (Vec<u32>, Vec<u32>),
) -> bool {
    if edges.len() < 3 {
        return false;
    }
    // 1. The link edges are a permutation of the link's identities.
    from.clear();
    from.extend(edges.iter().map(|e| ids[e[0] as usize]));
    to.clear();
    to.extend(edges.iter().map(|e| ids[e[1] as usize]));
    from.sort_unstable();
    to.sort_unstable();
    if from != to || from.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    // The axis of the largest summed normal, and the plane across it with
    // its two coordinates in cyclic order, so that a projected triangle's
    // orientation has the sign of its normal's component along the axis.
    let normal: DVec3 = edges
        .iter()
        .map(|e| (positions[e[0] as usize] - centre).cross(positions[e[1] as usize] - centre))
        .sum();
    let m = normal.abs();
    let project: fn(DVec3) -> DVec2 = if m.x >= m.y && m.x >= m.z {
        |p| DVec2::new(p.y, p.z)
    } else if m.y >= m.z {
        |p| DVec2::new(p.z, p.x)
    } else {
        |p| DVec2::new(p.x, p.y)
    };
    let c = project(centre);
    // 2. Every projected triangle turns one way, strictly; 3. the link
    // winds once around the centre.
    let mut turn = Sign::Zero;
    let mut crossings = 0usize;
    for e in edges {
        let (a, b) = (
            project(positions[e[0] as usize]),
            project(positions[e[1] as usize]),
        );
        let s = orient2d(c, a, b);
        if s == Sign::Zero || (turn != Sign::Zero && s != turn) {
            return false;
        }
        turn = s;
        // Taken in the counter-clockwise sense, a step from below the ray's
        // line to on or above it passes over the ray itself.
        let (lo, hi) = if s == Sign::Positive { (a, b) } else { (b, a) };
        if lo.y < c.y && hi.y >= c.y {
            crossings += 1;
        }
    }
    crossings == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan of `k` triangles around the origin in the plane z = 0
    /// (a regular polygon), counter-clockwise seen from +z.
    fn fan(k: usize, turns: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut positions = vec![DVec3::ZERO];
        for i in 0..k {
            let a = std::f64::consts::TAU * (turns * i) as f64 / k as f64;
            positions.push(DVec3::new(a.cos(), a.sin(), 0.0));
        }
        let tris = (0..k as u32)
            .map(|i| [0, 1 + i, 1 + (i + 1) % k as u32])
            .collect();
        (positions, tris)
    }

    fn centre_is_flat(positions: &[DVec3], tris: &[[u32; 3]]) -> bool {
        let ids = holey_geom::position_classes(positions).unwrap();
        flat_stars(tris, positions, &ids)[0]
    }

    #[test]
    fn a_flat_fan_is_certified_in_either_orientation() {
        let (p, t) = fan(12, 1);
        assert!(centre_is_flat(&p, &t));
        let flipped: Vec<[u32; 3]> = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
        assert!(centre_is_flat(&p, &flipped));
    }

    /// A link that winds twice around the centre (a flat fan over a
    /// 7-point star polygon) overlaps itself: its non-neighbouring
    /// triangles cross, so it must not be certified.
    #[test]
    fn a_fan_winding_twice_is_not_certified() {
        let (p, t) = fan(7, 2);
        assert!(!centre_is_flat(&p, &t));
    }

    /// A cone of 6 triangles, tilted: still flat in projection along the
    /// axis of its summed normal.
    #[test]
    fn a_cone_is_certified_and_a_pleated_one_is_not() {
        let (mut p, t) = fan(6, 1);
        p[0].z = 0.4;
        assert!(centre_is_flat(&p, &t));
        // Fold one link vertex back across the centre: its two triangles
        // turn the other way in every projection.
        p[3] = DVec3::new(0.3, -0.1, -0.2);
        assert!(!centre_is_flat(&p, &t));
    }

    /// An open fan (a boundary vertex), a star with a repeated triangle and
    /// a vertex whose link closes into two separate cycles (two cones
    /// touching at their tips) are left to the exact tests.
    #[test]
    fn open_doubled_and_pinched_stars_are_not_certified() {
        let (p, t) = fan(8, 1);
        assert!(!centre_is_flat(&p, &t[..7]));
        let mut doubled = t.clone();
        doubled.push(t[0]);
        assert!(!centre_is_flat(&p, &doubled));
        // Two fans around the same centre, the second lifted off the plane.
        let (mut q, mut u) = fan(5, 1);
        let (r, w) = fan(5, 1);
        q.extend(r[1..].iter().map(|&x| x + DVec3::new(0.0, 0.0, 0.5)));
        u.extend(w.iter().map(|&[a, b, c]| [a, b + 5, c + 5]));
        assert!(!centre_is_flat(&q, &u));
    }

    /// A vertex in two places of the list (an unwelded soup) is one
    /// identity: its star is every triangle at that position.
    #[test]
    fn copies_of_a_vertex_share_one_star() {
        let (mut p, t) = fan(6, 1);
        p.push(DVec3::ZERO);
        let mut t = t;
        t[2][0] = 7;
        t[4][0] = 7;
        let ids = holey_geom::position_classes(&p).unwrap();
        let flat = flat_stars(&t, &p, &ids);
        assert!(flat[0]);
        assert!(!flat[7], "the copy is not an identity of its own");
    }
}
