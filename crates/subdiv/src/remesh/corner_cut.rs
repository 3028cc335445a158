//! The schemes with Doo–Sabin's connectivity: corner cutting (TopMod's
//! `cornerCuttingSubdivide`, a tension parameter α), modified corner
//! cutting (`modifiedCornerCuttingSubdivide`, a constant-distance inset)
//! and Doo–Sabin BC (`dooSabinSubdivideBC`: edge midpoints, then
//! Doo–Sabin); plus Catmull–Clark and Doo–Sabin themselves, delegated to
//! this crate's implementations so that every scheme of TopMod's switch
//! goes through [`super::remesh`].
//!
//! The connectivity (and the Chaikin refinement of boundaries) is
//! [`crate::doo_sabin()`]'s step; only the corner points of normal faces are
//! placed again. Its output numbers the corner points in input corner
//! order: one per normal or point-sphere corner, two per hole corner.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, tension_mask};
use crate::flat::{Flat, Kind, NONE};
use crate::{Scheme, SubdivError, next_counts};

/// Where a corner-cutting scheme puts the corner points of a face.
#[derive(Clone, Copy, Debug)]
pub(super) enum Rule {
    /// TopMod's tension mask with this α.
    Tension(f64),
    /// An inset at half this thickness from every edge.
    Inset(f64),
}

/// Refuses `scheme`'s next level of `src` when it passes the cap (the
/// counts of [`next_counts`], wide, so nothing is narrowed before the
/// comparison).
fn check_counts(src: &Flat, scheme: Scheme, budget: &Budget) -> Result<(), SubdivError> {
    let k = next_counts(src.counts(), scheme);
    let limit = u128::from(u32::MAX - 2);
    if k.faces() > budget.max_faces as u128
        || k.corners() > limit
        || k.vertices > limit
        || k.edges > limit
    {
        return Err(SubdivError::RemeshTooLarge {
            scheme: budget.scheme,
            levels: budget.levels,
            level: budget.level,
            faces: k.faces(),
            corners: k.corners(),
            cap: budget.max_faces,
        });
    }
    Ok(())
}

/// One level of Doo–Sabin's connectivity with `rule`'s corner points.
pub(super) fn step(src: &Flat, budget: &Budget, rule: Rule) -> Result<Flat, SubdivError> {
    check_counts(src, Scheme::DooSabin, budget)?;
    let mut dst = Flat::default();
    crate::doo_sabin::step(src, &mut dst, &mut crate::doo_sabin::Scratch::default())?;
    let m = Map::new(src);
    let mut ring = Vec::new();
    let mut out = Vec::new();
    let mut o = 0usize;
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        match m.kind[face] {
            Kind::Normal => {
                ring.clear();
                ring.extend((lo..hi).map(|c| m.p(c)));
                out.clear();
                out.resize(hi - lo, DVec3::ZERO);
                match rule {
                    Rule::Tension(alpha) => tension_mask(&ring, |_| alpha, &mut out),
                    Rule::Inset(thickness) => inset(&ring, 0.5 * thickness, &mut out),
                }
                dst.pos[o..o + out.len()].copy_from_slice(&out);
                o += hi - lo;
            }
            Kind::Hole => o += 2 * (hi - lo),
            Kind::PointSphere => o += 1,
        }
    }
    if o != dst.pos.len() {
        return Err(SubdivError::Internal(format!(
            "{o} corner points placed, {} made",
            dst.pos.len()
        )));
    }
    Ok(dst)
}

/// TopMod's modified corner cutting: corner `v` with unit directions `u₁`,
/// `u₂` towards its neighbours goes to `v + t/√(1 − (u₁·u₂)²) (u₁ + u₂)`,
/// the point at distance `t` from both edge lines inside the corner. When
/// the corner is straight or folded (`|u₁·u₂|` within 1e-9 of 1) or an
/// edge has no length, it moves by `t` towards the centroid instead (not
/// at all if it is the centroid). No corner moves more than a third of
/// either edge at it (the inset is held back in faces narrower than it).
fn inset(p: &[DVec3], t: f64, out: &mut [DVec3]) {
    let n = p.len();
    let centroid = p.iter().sum::<DVec3>() / n as f64;
    for i in 0..n {
        let v = p[i];
        let u1 = (p[(i + n - 1) % n] - v).normalize_or_zero();
        let u2 = (p[(i + 1) % n] - v).normalize_or_zero();
        let cos = u1.dot(u2);
        let sin2 = 1.0 - cos * cos;
        let step = if u1 == DVec3::ZERO || u2 == DVec3::ZERO || sin2 < 1e-9 {
            t * (centroid - v).normalize_or_zero()
        } else {
            (t / sin2.sqrt()) * (u1 + u2)
        };
        // A face narrower than the inset (a sliver, or a thickness larger
        // than the model's faces) would turn over and throw its corners
        // far outside: each corner moves at most a third of either edge
        // at it, so every inset edge keeps a third of its length.
        let reach = p[(i + n - 1) % n]
            .distance(v)
            .min(p[(i + 1) % n].distance(v))
            / 3.0;
        let len = step.length();
        out[i] = v + if len > reach {
            step * (reach / len)
        } else {
            step
        };
    }
}

/// Catmull–Clark through [`crate::catmull_clark`]'s step.
pub(super) fn catmull_clark(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    check_counts(src, Scheme::CatmullClark, budget)?;
    let mut dst = Flat::default();
    crate::catmull_clark::step(
        src,
        &mut dst,
        &mut crate::catmull_clark::Scratch::default(),
        true,
    )?;
    Ok(dst)
}

/// Doo–Sabin through [`crate::doo_sabin`]'s step.
pub(super) fn doo_sabin(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    check_counts(src, Scheme::DooSabin, budget)?;
    let mut dst = Flat::default();
    crate::doo_sabin::step(src, &mut dst, &mut crate::doo_sabin::Scratch::default())?;
    Ok(dst)
}

/// Doo–Sabin BC: every edge split at its midpoint (a midpoint has two
/// corners), then Doo–Sabin, then the two-gon V-face of every midpoint
/// between two normal faces replaced by one edge, as TopMod's
/// multiple-edge check in `connectEdges` leaves it.
pub(super) fn doo_sabin_bc(src: &Flat, budget: &Budget) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let split = midpoint_split(&m, budget)?;
    let ds = doo_sabin(&split, budget)?;
    // Doo–Sabin's faces: the F-faces of the split mesh's faces, its
    // E-faces by edge, then a V-face per vertex with corners in order,
    // which is every vertex but the point-spheres'; the midpoints are the
    // split mesh's last vertices, in edge order.
    let first_mid = split.face_count() + split.edges.len() + st.v - st.ps;
    let two_gons: Vec<usize> = (0..st.e)
        .filter(|&e| m.interior(e))
        .map(|e| first_mid + e)
        .collect();
    collapse_two_gons(ds, &two_gons)
}

/// Every edge split at its midpoint: vertices `V + e`, halves `2e`, `2e + 1`.
fn midpoint_split(m: &Map, budget: &Budget) -> Result<Flat, SubdivError> {
    let src = m.f;
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.e,
        e: 2 * st.e,
        f: st.nf + st.hf + st.ps,
        c: 2 * (st.nc + st.hc) + st.ps,
    };
    budget.check(sizes)?;
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(m.midpoints());
    let mut b = Builder::new(pos, sizes);
    b.walked_faces(
        m,
        |face| src.cv[m.range(face).0],
        |c, w| m.push_halves(c, st.v, w),
    );
    b.finish()
}

/// Removes the given two-gon faces, each `[x, y]` replaced by one edge
/// joining the corners across its two edges (their other corners `x'`,
/// `y'` run oppositely between the same two vertices, so `[x', y']` is an
/// edge). Faces, corners and edges keep their order otherwise.
fn collapse_two_gons(mut f: Flat, faces: &[usize]) -> Result<Flat, SubdivError> {
    let nf = f.face_count();
    let nc = f.corner_count();
    let mut gone_face = vec![false; nf];
    let mut gone_edge = vec![false; f.edges.len()];
    for &g in faces {
        let (lo, hi) = (f.off[g] as usize, f.off[g + 1] as usize);
        let (x, y) = (lo, lo + 1);
        let (ex, ey) = (f.cedge[x] as usize, f.cedge[y] as usize);
        if hi - lo != 2 || ex == ey || gone_face[g] {
            return Err(SubdivError::Internal(format!(
                "face {g} is not a two-gon between two edges"
            )));
        }
        let (tx, ty) = (f.twin(x), f.twin(y));
        if gone_face[f.cf[tx] as usize] || gone_face[f.cf[ty] as usize] {
            return Err(SubdivError::Internal(format!(
                "two-gon {g} borders another removed two-gon"
            )));
        }
        f.edges[ex] = [tx as u32, ty as u32];
        gone_edge[ey] = true;
        gone_face[g] = true;
    }
    let mut cmap = vec![NONE; nc];
    let mut next = 0u32;
    for (face, &gone) in gone_face.iter().enumerate() {
        if gone {
            continue;
        }
        for c in f.off[face]..f.off[face + 1] {
            cmap[c as usize] = next;
            next += 1;
        }
    }
    let mut out = Flat {
        pos: std::mem::take(&mut f.pos),
        ..Flat::default()
    };
    for (face, &gone) in gone_face.iter().enumerate() {
        if gone {
            continue;
        }
        let new_face = out.hole.len() as u32;
        out.off.push(out.cv.len() as u32);
        out.hole.push(f.hole[face]);
        for c in f.off[face] as usize..f.off[face + 1] as usize {
            out.cv.push(f.cv[c]);
            out.cf.push(new_face);
        }
    }
    out.off.push(out.cv.len() as u32);
    out.cedge = vec![NONE; out.cv.len()];
    for (e, &[a, b]) in f.edges.iter().enumerate() {
        if gone_edge[e] {
            continue;
        }
        let (a, b) = (cmap[a as usize], cmap[b as usize]);
        if a == NONE || b == NONE {
            return Err(SubdivError::Internal(format!(
                "edge {e} keeps a corner of a removed two-gon"
            )));
        }
        let id = out.edges.len() as u32;
        out.edges.push([a, b]);
        out.cedge[a as usize] = id;
        out.cedge[b as usize] = id;
    }
    Ok(out)
}
