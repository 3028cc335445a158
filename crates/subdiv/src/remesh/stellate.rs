//! Stellation and what TopMod builds from it: stellate (TopMod's
//! `subdivideAllFaces` with triangles), triangulate (`triangulateAllFaces`:
//! stellate the faces that are not triangles), stellate with edge removal
//! (`stellateSubdivide`), double stellate (`starSubdivide`) and the
//! modified double stellate (`twostellateSubdivide`, a stellation followed
//! by a stellation with edge removal).
//!
//! Stellating face `f` with corners `c₀ … c_{n−1}` adds its centre `z` and
//! one spoke per corner; spoke `j` runs `v(cⱼ) → z` on side 0 and back on
//! side 1, so triangle `j` is `[v(cⱼ), v(cⱼ₊₁), z]` with labels
//! `(old edge of cⱼ, spoke j+1 side 0, spoke j side 1)`. A monogon gives
//! one triangle that holds both sides of its spoke.

use glam::DVec3;

use super::build::{Budget, Builder, Sizes};
use super::map::{Map, lab};
use crate::SubdivError;
use crate::flat::{Flat, Kind};

/// The centre of a stellated face: its centroid, raised `height` along its
/// unit normal.
fn centre(m: &Map, face: usize, height: f64) -> DVec3 {
    let c = m.centroid(face);
    if height == 0.0 {
        c
    } else {
        c + height * m.normal(face)
    }
}

/// Stellates every normal face (only the non-triangles with
/// `skip_triangles`). Output vertices: the input's, then the centres in
/// face order; spokes are numbered after the old edges, corner by corner.
pub(super) fn stellate(
    src: &Flat,
    budget: &Budget,
    height: f64,
    skip_triangles: bool,
) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let (sf, sc) = if skip_triangles {
        (st.nt_faces, st.nt_corners)
    } else {
        (st.nf, st.nc)
    };
    let all_f = st.nf + st.hf + st.ps;
    let all_c = st.nc + st.hc + st.ps;
    let sizes = Sizes {
        v: st.v + sf,
        e: st.e + sc,
        f: all_f - sf + sc,
        c: all_c + 2 * sc,
    };
    budget.check(sizes)?;
    let stellated = |face: usize| {
        let (lo, hi) = m.range(face);
        m.kind[face] == Kind::Normal && !(skip_triangles && hi - lo == 3)
    };
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(
        (0..src.face_count())
            .filter(|&face| stellated(face))
            .map(|face| centre(&m, face, height)),
    );
    let mut b = Builder::new(pos, sizes);
    let mut z = st.v as u32;
    let mut spoke = st.e;
    for face in 0..src.face_count() {
        let (lo, hi) = m.range(face);
        if m.kind[face] == Kind::PointSphere {
            b.point_sphere(src.cv[lo], src.hole[face]);
        } else if stellated(face) {
            let n = hi - lo;
            for j in 0..n {
                let (c, d) = (lo + j, lo + (j + 1) % n);
                b.face(&[
                    (src.cv[c], m.own(c)),
                    (src.cv[d], lab(spoke + (j + 1) % n, 0)),
                    (z, lab(spoke + j, 1)),
                ]);
            }
            z += 1;
            spoke += n;
        } else {
            b.walk(src.hole[face], lo..hi, |c, w| w.push((src.cv[c], m.own(c))));
        }
    }
    b.finish()
}

/// The faces a stellation keeps around the holes once its interior old
/// edges are gone (√3 flips them, the edge removal makes quads of them):
/// point-spheres, holes with their corners' old edges labelled by `old`,
/// and in each normal face the triangle `[v(c), v(next c), z]` on every
/// side `c` next to a hole, `z = centre(c)` the centre of `c`'s face and
/// `spoke(c, side)` the label of the spoke from `v(c)` to it.
pub(super) fn hole_side_triangles(
    b: &mut Builder,
    m: &Map,
    old: impl Fn(usize) -> usize,
    centre: impl Fn(usize) -> u32,
    spoke: impl Fn(usize, u32) -> usize,
) {
    let src = m.f;
    b.kept_faces(
        m,
        |c, hole| hole.push((src.cv[c], old(c))),
        |b, _, lo, hi| {
            for (c, d) in m.boundary_corners(lo, hi) {
                b.face(&[
                    (src.cv[c], old(c)),
                    (src.cv[d], spoke(d, 0)),
                    (centre(c), spoke(c, 1)),
                ]);
            }
        },
    );
}

/// Stellates every normal face with centres raised `height`, then deletes
/// every old edge with normal faces on both sides: edge `(a, b)` between
/// faces `f ∋ a` and `g ∋ b` becomes the quad `[v(a), z_g, v(b), z_f]`.
/// An edge next to a hole (or between two holes) is kept; the side in a
/// normal face keeps its triangle.
///
/// Output vertices: the input's, then the centres in normal-face order.
/// Edges: the kept old edges in order, then the spokes by normal corner.
/// Faces: holes, point-spheres and boundary triangles in face order, then
/// the quads in edge order.
pub(super) fn edge_removal(src: &Flat, budget: &Budget, height: f64) -> Result<Flat, SubdivError> {
    let m = Map::new(src);
    let st = m.st;
    let sizes = Sizes {
        v: st.v + st.nf,
        e: st.kept_edge_count() + st.nc,
        f: st.e_nn + st.b_sides + st.hf + st.ps,
        c: 4 * st.e_nn + 3 * st.b_sides + st.hc + st.ps,
    };
    budget.check(sizes)?;
    // Kept old edges are renumbered densely; interior ones get no number.
    let kept = m.kept_edges();
    let mut pos = m.kept_positions(sizes.v);
    pos.extend(m.normal_faces().map(|face| centre(&m, face, height)));
    let zc = |c: usize| st.v as u32 + m.nrank[src.cf[c] as usize];
    let spoke = |c: usize, side: u32| lab(st.kept_edge_count() + m.nidx(c), side);
    let old = |c: usize| lab(kept[m.edge(c)] as usize, m.side(c));
    let mut b = Builder::new(pos, sizes);
    hole_side_triangles(&mut b, &m, old, zc, spoke);
    for (_, a, bb, na, nb) in m.interior_edges() {
        b.face(&[
            (src.cv[a], spoke(nb, 0)),
            (zc(bb), spoke(bb, 1)),
            (src.cv[bb], spoke(na, 0)),
            (zc(a), spoke(a, 1)),
        ]);
    }
    b.finish()
}

/// Stellates twice (centres at the centroids), then moves each first-level
/// centre `offset` along the unit normal of the face it stellated, as
/// TopMod's `starSubdivide` does after both stellations. Stellation keeps
/// the input's vertices first and numbers centres in face order, so the
/// first-level centres are output vertices `V … V + F − 1`.
pub(super) fn double(src: &Flat, budget: &Budget, offset: f64) -> Result<Flat, SubdivError> {
    let once = stellate(src, budget, 0.0, false)?;
    let mut twice = stellate(&once, budget, 0.0, false)?;
    if offset != 0.0 {
        let m = Map::new(src);
        for (z, face) in (src.pos.len()..).zip(m.normal_faces()) {
            twice.pos[z] += offset * m.normal(face);
        }
    }
    Ok(twice)
}
