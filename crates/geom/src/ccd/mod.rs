//! Continuous collision detection for the parity field (§3.2, appendix A).
//!
//! Every vertex moves linearly from its start to its end position over the
//! frame; the raw parity of a vertex is the parity of the number of times it
//! hits the moving surface. Narrow phase, two ways:
//!
//! - [`cubic`]: the paper's floating-point test (coplanarity cubic, interval
//!   search, barycentric containment);
//! - [`parity`]: the exact parity by the root-parity method of Brochu,
//!   Edwards & Bridson 2012, with simulation of simplicity for every
//!   degenerate case.
//!
//! Broad phase ([`vertex_parities`]): a [`Bvh`] over the swept segments of
//! the vertices (the box of start and end), each triangle's swept box (the
//! box of its six keyframe corners) streamed over it in parallel; a triangle
//! skips the vertices it contains *by index*. When the motion is a few
//! rigid translations (a solid sliding into another, Theorem 5.2), a
//! specialised broad phase (`groups`) streams each vertex's needle over
//! the shadows of the other parts' triangles instead. Pairs with exactly
//! equal displacements have no relative motion and are not tested. Output
//! is deterministic: the odd (vertex, triangle) pairs sorted, and per
//! vertex the XOR of its pairs.
//!
//! # Identities and frames
//!
//! The exact test perturbs each keyframe position as its own symbolic
//! point. [`frame_ids`] numbers them so that consecutive frames agree: in
//! frame `k` (keyframes `k → k+1`) vertex `v` has start identity `2v + (k
//! mod 2)` and end identity `2v + ((k+1) mod 2)`, so the end of frame `k`
//! and the start of frame `k+1` are the same symbolic point and parities
//! accumulate across frames exactly (see [`parity`]).
//!
//! **Coincident-but-unwelded vertices.** With [`Identities::ByIndex`], two
//! vertices at the same position are different symbolic points, separated
//! infinitesimally: a vertex lying exactly on a triangle's corner (e.g. the
//! duplicate of that corner in an unwelded soup) and moving with it gets a
//! parity decided by the perturbation — arbitrary but deterministic, the
//! kind of isolated error the error-correction stage removes. With
//! [`Identities::ByPosition`] the identities are `2·class + parity`, with
//! `class` the position class ([`crate::identity::position_classes`]) at
//! that keyframe: such a vertex then shares an identity with the corner, the
//! pair is degenerate and skipped (counted in
//! [`CcdReport::degenerate_pairs`]), exactly as if the soup were welded
//! there.

pub mod cubic;
mod filter;
mod groups;
pub mod parity;

pub use cubic::{FloatCollisions, collisions_float, coplanarity_cubic};
pub use parity::{CcdParity, MovingPoint, vertex_triangle_parity};

use crate::bvh::{Aabb, Bvh};
use crate::error::{GeomError, NonFinite};
use crate::identity::position_classes;
use crate::sos::SymPoint;
use glam::DVec3;
use groups::Groups;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Which narrow phase to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Narrow {
    /// Exact parity ([`vertex_triangle_parity`]).
    Exact,
    /// The paper's floating-point cubic ([`collisions_float`]); the pair
    /// parity is the collision count mod 2.
    Float,
}

/// How keyframe positions get their symbolic identities (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Identities {
    /// Each vertex's keyframe positions get identities from its index
    /// ([`frame_ids`]): coincident vertices stay distinct symbolic points.
    ByIndex,
    /// Identities `2·class + parity` from each keyframe's position classes:
    /// vertices coincident there are one symbolic point, as if welded.
    ByPosition,
}

/// Options of [`vertex_parities`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CcdOptions {
    /// The narrow-phase test run on each candidate vertex–triangle pair.
    pub narrow: Narrow,
    /// How keyframe positions get their symbolic identities.
    pub identities: Identities,
    /// Index `k` of the frame (keyframes `k → k+1`): only its parity matters.
    pub frame: u64,
}

impl Default for CcdOptions {
    fn default() -> Self {
        CcdOptions {
            narrow: Narrow::Exact,
            identities: Identities::ByIndex,
            frame: 0,
        }
    }
}

/// Result of [`vertex_parities`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CcdReport {
    /// Per vertex: odd number of collisions during the frame.
    pub odd: Vec<bool>,
    /// The (vertex, triangle) pairs with an odd number of collisions,
    /// sorted.
    pub odd_pairs: Vec<(u32, u32)>,
    /// Narrow-phase tests run (broad-phase candidates minus skipped ones).
    pub candidates: u64,
    /// Pairs skipped because the vertex shares a keyframe identity with a
    /// corner of the triangle (only with [`Identities::ByPosition`]).
    pub degenerate_pairs: u64,
}

/// Start and end identities of `n` vertices in frame `frame`, by index:
/// `2v + (frame mod 2)` and `2v + ((frame + 1) mod 2)`.
pub fn frame_ids(n: usize, frame: u64) -> Result<(Vec<u32>, Vec<u32>), GeomError> {
    if n >= (1usize << 31) {
        return Err(GeomError::TooMany(n));
    }
    let (s, e) = ((frame & 1) as u32, ((frame + 1) & 1) as u32);
    Ok((
        (0..n as u32).map(|v| 2 * v + s).collect(),
        (0..n as u32).map(|v| 2 * v + e).collect(),
    ))
}

fn check_input(start: &[DVec3], end: &[DVec3], tris: &[[u32; 3]]) -> Result<(), GeomError> {
    let n = start.len();
    if end.len() != n {
        return Err(GeomError::LengthMismatch {
            what: "end positions",
            got: end.len(),
            expected: n,
        });
    }
    if n >= (1usize << 31) || tris.len() >= (1usize << 31) {
        return Err(GeomError::TooMany(n.max(tris.len())));
    }
    NonFinite::check("vertex", start).map_err(|e| e.in_input("start positions"))?;
    NonFinite::check("vertex", end).map_err(|e| e.in_input("end positions"))?;
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            if v as usize >= n {
                return Err(GeomError::VertexOutOfRange {
                    triangle: t,
                    vertex: v,
                    count: n,
                });
            }
        }
    }
    Ok(())
}

/// Per chunk of work: odd pairs, narrow tests run, degenerate pairs skipped.
type Part = (Vec<(u32, u32)>, u64, u64);

/// Raw collision parity of every vertex of a triangle soup moving linearly
/// from `start` to `end` (module docs). Parallel, deterministic.
pub fn vertex_parities(
    start: &[DVec3],
    end: &[DVec3],
    tris: &[[u32; 3]],
    opts: &CcdOptions,
) -> Result<CcdReport, GeomError> {
    vertex_parities_cancellable(start, end, tris, opts, &AtomicBool::new(false))
}

/// [`vertex_parities`] that gives up with [`GeomError::Cancelled`] once
/// `cancel` is raised (checked between chunks of work), so a caller
/// running it beside another stage can stop it when that stage fails.
pub fn vertex_parities_cancellable(
    start: &[DVec3],
    end: &[DVec3],
    tris: &[[u32; 3]],
    opts: &CcdOptions,
    cancel: &AtomicBool,
) -> Result<CcdReport, GeomError> {
    check_input(start, end, tris)?;
    let n = start.len();
    let (sid, eid) = match opts.identities {
        Identities::ByIndex => frame_ids(n, opts.frame)?,
        Identities::ByPosition => {
            let (s, e) = ((opts.frame & 1) as u32, ((opts.frame + 1) & 1) as u32);
            let cs = position_classes(start)?;
            let ce = position_classes(end)?;
            (
                cs.iter().map(|c| 2 * c + s).collect(),
                ce.iter().map(|c| 2 * c + e).collect(),
            )
        }
    };
    let mp = |v: u32| MovingPoint {
        start: SymPoint::new(start[v as usize], sid[v as usize]),
        end: SymPoint::new(end[v as usize], eid[v as usize]),
    };
    let disp = |v: u32| end[v as usize] - start[v as usize];
    // One narrow-phase test. A vertex and a triangle displaced by exactly
    // the same vector (a static part against itself, a rigid part against
    // itself) have no relative motion and cannot collide, whatever the
    // perturbation says of a vertex lying exactly on the triangle.
    let test = |v: u32, t: u32, part: &mut Part| {
        let tri = tris[t as usize];
        if tri.contains(&v) {
            return;
        }
        let d = disp(v);
        if tri.iter().all(|&c| disp(c) == d) {
            return;
        }
        // A vertex at one of the triangle's corners at both ends of the
        // motion is that corner (the copies of an unwelded soup's shared
        // corner move together): a triangle does not collide with its own
        // corner, whatever the perturbation of two identities says (as
        // with identities by motion class, `crate::motion_classes`).
        let (p0, p1) = (start[v as usize], end[v as usize]);
        if tri
            .iter()
            .any(|&c| start[c as usize] == p0 && end[c as usize] == p1)
        {
            part.2 += 1;
            return;
        }
        let is_odd = match opts.narrow {
            Narrow::Exact => {
                let corners = tri.map(|c| [start[c as usize], end[c as usize]]);
                if let Some(odd) =
                    filter::rigid_filter([start[v as usize], end[v as usize]], corners)
                {
                    part.1 += 1;
                    if odd {
                        part.0.push((v, t));
                    }
                    return;
                }
                let [a, b, c] = tri.map(mp);
                match vertex_triangle_parity(mp(v), a, b, c) {
                    CcdParity::Odd => true,
                    CcdParity::Even => false,
                    CcdParity::Degenerate => {
                        part.2 += 1;
                        return;
                    }
                }
            }
            Narrow::Float => {
                let corners = tri.map(|c| [start[c as usize], end[c as usize]]);
                let p = [start[v as usize], end[v as usize]];
                collisions_float(p, corners[0], corners[1], corners[2]).count % 2 == 1
            }
        };
        part.1 += 1;
        if is_odd {
            part.0.push((v, t));
        }
    };
    const CHUNK: usize = 256;
    let parts: Vec<Part> = if let Some(groups) = Groups::detect(start, end, tris) {
        let prepared = groups.prepare(start, end, tris)?;
        prepared
            .pairs
            .iter()
            .flat_map(|set| {
                set.verts
                    .par_chunks(CHUNK)
                    .map(|chunk| {
                        let mut part: Part = Default::default();
                        if cancel.load(Ordering::Relaxed) {
                            return part;
                        }
                        for &v in chunk {
                            set.candidates(v, start, end, |t| test(v, t, &mut part));
                        }
                        part
                    })
                    .collect::<Vec<Part>>()
            })
            .collect()
    } else {
        let swept: Vec<Aabb> = start
            .par_iter()
            .zip(end.par_iter())
            .map(|(&a, &b)| Aabb::new(a.min(b), a.max(b)))
            .collect();
        let bvh = Bvh::build(&swept)?;
        tris.par_chunks(CHUNK)
            .enumerate()
            .map(|(ci, chunk)| {
                let mut part: Part = Default::default();
                if cancel.load(Ordering::Relaxed) {
                    return part;
                }
                for (k, tri) in chunk.iter().enumerate() {
                    let t = (ci * CHUNK + k) as u32;
                    let bb = Aabb::from_points(&[
                        start[tri[0] as usize],
                        end[tri[0] as usize],
                        start[tri[1] as usize],
                        end[tri[1] as usize],
                        start[tri[2] as usize],
                        end[tri[2] as usize],
                    ]);
                    bvh.for_each_overlap(&bb, |v| test(v, t, &mut part));
                }
                part
            })
            .collect()
    };
    if cancel.load(Ordering::Relaxed) {
        return Err(GeomError::Cancelled);
    }
    let mut report = CcdReport {
        odd: vec![false; n],
        ..Default::default()
    };
    for (odd, cand, degen) in parts {
        report.candidates += cand;
        report.degenerate_pairs += degen;
        report.odd_pairs.extend(odd);
    }
    report.odd_pairs.sort_unstable();
    for &(v, _) in &report.odd_pairs {
        report.odd[v as usize] ^= true;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::uv_sphere;

    fn grid(n: usize, lo: f64, z: f64, base: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let idx = |i: usize, j: usize| base + (i * (n + 1) + j) as u32;
        let mut pos = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                pos.push(DVec3::new(lo + i as f64, lo + j as f64, z));
            }
        }
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                tris.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
                tris.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
            }
        }
        (pos, tris)
    }

    /// The paper's hard case through the broad phase: a grid sheet falls
    /// through an aligned, larger static grid sheet. Every moving vertex
    /// crosses once; static vertices strictly inside the moving sheet's
    /// footprint are swept once, those strictly outside never.
    #[test]
    fn aligned_grid_sheets() {
        let n = 10;
        let (sa, ta) = grid(n, 0.0, 0.0, 0);
        let na = sa.len() as u32;
        let (sb, tb) = grid(n - 4, 2.0, 1.0, na);
        let mut start = sa.clone();
        start.extend(&sb);
        let mut end = sa.clone();
        end.extend(sb.iter().map(|p| DVec3::new(p.x, p.y, -1.0)));
        let tris: Vec<[u32; 3]> = ta.iter().chain(tb.iter()).copied().collect();
        for identities in [Identities::ByIndex, Identities::ByPosition] {
            for frame in [0, 1] {
                let opts = CcdOptions {
                    identities,
                    frame,
                    ..Default::default()
                };
                let r = vertex_parities(&start, &end, &tris, &opts).expect("valid");
                for (v, p) in start.iter().enumerate() {
                    if v as u32 >= na {
                        assert!(r.odd[v], "moving vertex {v}");
                    } else {
                        let strictly_in =
                            p.x > 2.0 && p.x < (n - 2) as f64 && p.y > 2.0 && p.y < (n - 2) as f64;
                        let strictly_out =
                            p.x < 2.0 || p.x > (n - 2) as f64 || p.y < 2.0 || p.y > (n - 2) as f64;
                        if strictly_in {
                            assert!(r.odd[v], "static vertex {v} at {p}");
                        }
                        if strictly_out {
                            assert!(!r.odd[v], "static vertex {v} at {p}");
                        }
                    }
                }
            }
        }
        // The float narrow phase on the same input: count its errors on the
        // moving vertices (reported, not asserted).
        let opts = CcdOptions {
            narrow: Narrow::Float,
            ..Default::default()
        };
        let r = vertex_parities(&start, &end, &tris, &opts).expect("valid");
        let wrong = (na as usize..start.len()).filter(|&v| !r.odd[v]).count();
        eprintln!(
            "aligned grids: float cubic wrong on {wrong}/{} moving vertices",
            start.len() - na as usize
        );
    }

    /// Two UV spheres, one moving into the other (the union scenario):
    /// away from the surfaces, a vertex is odd iff it ends inside the other
    /// sphere (it started outside). Checked against the analytic spheres
    /// with a margin for the polyhedral approximation.
    #[test]
    fn sphere_moves_into_sphere() {
        let (pa, ta) = uv_sphere(48, 26, [0.0, 0.0, 0.0], 1.0);
        let (pb, tb) = uv_sphere(40, 22, [3.0, 0.2, 0.1], 0.8);
        let na = pa.len() as u32;
        let d = DVec3::new(-2.2, 0.1, -0.05);
        let mut start: Vec<DVec3> = pa.iter().map(|p| DVec3::from_array(*p)).collect();
        let mut end = start.clone();
        start.extend(pb.iter().map(|p| DVec3::from_array(*p)));
        end.extend(pb.iter().map(|p| DVec3::from_array(*p) + d));
        let mut tris = ta.clone();
        tris.extend(tb.iter().map(|t| t.map(|v| v + na)));
        let ca = DVec3::ZERO;
        let cb0 = DVec3::new(3.0, 0.2, 0.1);
        let cb1 = cb0 + d;
        let exact = vertex_parities(&start, &end, &tris, &CcdOptions::default()).expect("valid");
        let mut checked = 0;
        let mut odd_count = 0;
        for v in 0..start.len() {
            let want = if (v as u32) < na {
                let dist = (start[v] - cb1).length();
                if (dist - 0.8).abs() < 0.05 {
                    continue;
                }
                dist < 0.8
            } else {
                let dist = (end[v] - ca).length();
                if (dist - 1.0).abs() < 0.05 {
                    continue;
                }
                dist < 1.0
            };
            assert_eq!(exact.odd[v], want, "vertex {v}");
            checked += 1;
            odd_count += want as u32;
        }
        assert!(checked > 1500 && odd_count > 100, "{checked} {odd_count}");
        // Determinism (parallel run twice).
        let again = vertex_parities(&start, &end, &tris, &CcdOptions::default()).expect("valid");
        assert_eq!(exact, again);
    }

    /// The rigid-group broad phase finds exactly the odd pairs an
    /// all-pairs loop over the same narrow phase finds: three spheres
    /// translated by different vectors, one of them with displacements
    /// rounded per vertex as `p + d` computes them.
    #[test]
    fn rigid_groups_agree_with_all_pairs() {
        let (pa, ta) = uv_sphere(16, 9, [0.0, 0.0, 0.0], 1.0);
        let mut start = Vec::new();
        let mut end = Vec::new();
        let mut tris = Vec::new();
        let moves = [
            (DVec3::new(0.0, 0.0, 0.0), DVec3::ZERO),
            (DVec3::new(7.3, 0.31, -0.2), DVec3::new(-6.1, 0.05, 0.1)),
            (DVec3::new(0.4, -5.0, 0.13), DVec3::new(0.2, 4.4, -0.3)),
        ];
        for (offset, d) in moves {
            let base = start.len() as u32;
            for p in &pa {
                let p0 = DVec3::from_array(*p) + offset;
                start.push(p0);
                end.push(p0 + d);
            }
            tris.extend(ta.iter().map(|t| t.map(|v| v + base)));
        }
        assert!(groups::Groups::detect(&start, &end, &tris).is_some());
        let r = vertex_parities(&start, &end, &tris, &CcdOptions::default()).expect("valid");
        let (sid, eid) = frame_ids(start.len(), 0).expect("small");
        let mp = |v: u32| MovingPoint {
            start: SymPoint::new(start[v as usize], sid[v as usize]),
            end: SymPoint::new(end[v as usize], eid[v as usize]),
        };
        let mut want = Vec::new();
        for v in 0..start.len() as u32 {
            for (t, tri) in tris.iter().enumerate() {
                if tri.contains(&v) {
                    continue;
                }
                let [a, b, c] = tri.map(mp);
                if vertex_triangle_parity(mp(v), a, b, c) == CcdParity::Odd {
                    want.push((v, t as u32));
                }
            }
        }
        assert!(!want.is_empty());
        assert_eq!(r.odd_pairs, want);
    }

    #[test]
    fn input_errors() {
        let p = vec![DVec3::ZERO; 3];
        let t = vec![[0u32, 1, 3]];
        assert!(matches!(
            vertex_parities(&p, &p, &t, &CcdOptions::default()),
            Err(GeomError::VertexOutOfRange { .. })
        ));
        assert!(matches!(
            vertex_parities(&p, &p[..2], &[], &CcdOptions::default()),
            Err(GeomError::LengthMismatch { .. })
        ));
        let mut q = p.clone();
        q[1].y = f64::NAN;
        assert!(matches!(
            vertex_parities(&q, &p, &[], &CcdOptions::default()),
            Err(GeomError::NonFinite(e)) if e.index == Some(1) && e.input == "start positions"
        ));
        assert_eq!(frame_ids(2, 0), Ok((vec![0, 2], vec![1, 3])));
        assert_eq!(frame_ids(2, 1), Ok((vec![1, 3], vec![0, 2])));
    }
}
