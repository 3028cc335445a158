//! One level of Doo–Sabin subdivision on a [`Flat`] map; the
//! rules, and what they do with the DLFL's special cases and with
//! boundaries, are documented on [`crate::doo_sabin`].

use glam::DVec3;

use crate::SubdivError;
use crate::flat::{Flat, Kind, NONE};

/// Buffers reused from level to level.
#[derive(Default)]
pub(crate) struct Scratch {
    kind: Vec<Kind>,
    /// Per input corner: its point before (`B`) and after (`A`) the
    /// corner along the face walk. They differ only at hole corners.
    pb: Vec<u32>,
    pa: Vec<u32>,
    /// Per vertex: its corners (point-sphere corners excluded), its hole
    /// corners, and its first corner.
    count: Vec<u32>,
    nh: Vec<u32>,
    start: Vec<u32>,
    /// Angles' cosines and sines for large faces.
    trig: Vec<(f64, f64)>,
}

/// The corner points of an ordinary face with corners at `p` (in order),
/// written to `out`.
pub(crate) fn corner_points(p: &[DVec3], out: &mut [DVec3], trig: &mut Vec<(f64, f64)>) {
    let n = p.len();
    match n {
        0 => {}
        1 => out[0] = p[0],
        2 => {
            out[0] = (7.0 * p[0] + p[1]) / 8.0;
            out[1] = (7.0 * p[1] + p[0]) / 8.0;
        }
        3 => {
            for j in 0..3 {
                out[j] = (4.0 * p[j] + p[(j + 1) % 3] + p[(j + 2) % 3]) / 6.0;
            }
        }
        4 => {
            for j in 0..4 {
                out[j] =
                    (9.0 * p[j] + 3.0 * (p[(j + 1) % 4] + p[(j + 3) % 4]) + p[(j + 2) % 4]) / 16.0;
            }
        }
        _ => {
            let nf = n as f64;
            trig.clear();
            trig.extend((0..n).map(|m| (std::f64::consts::TAU * m as f64 / nf).sin_cos()));
            let mut centroid = DVec3::ZERO;
            let mut cs = DVec3::ZERO;
            let mut sn = DVec3::ZERO;
            for (q, &(s, c)) in p.iter().zip(trig.iter()) {
                centroid += *q;
                cs += c * *q;
                sn += s * *q;
            }
            let centroid = centroid / nf;
            for (j, &(s, c)) in trig.iter().enumerate() {
                out[j] = 0.25 * p[j] + 0.75 * centroid + (c * cs + s * sn) / (2.0 * nf);
            }
        }
    }
}

/// Subdivides `src` once into `dst` (which must be empty).
///
/// Output numbering: the new vertices are the corner points in input
/// corner order (two per hole corner, `B` then `A`; a point-sphere's
/// vertex for its corner). Output face `f < F` is input face `f`'s F-face
/// (holes and point-spheres included), then come the E-faces in edge order
/// and the V-faces in vertex order (point-sphere vertices have none). The
/// F-faces' corners are numbered like the vertices they stand at.
pub(crate) fn step(src: &Flat, dst: &mut Flat, s: &mut Scratch) -> Result<(), SubdivError> {
    let nc = src.corner_count();

    // Pass 1: kinds and each corner's points.
    let nvo = number_corner_points(src, s);

    // Per vertex: corner counts and a first corner.
    let sizes = count_vertex_corners(src, s, nvo);
    crate::check_index(sizes.out_c)?;
    crate::check_index(sizes.out_f)?;
    crate::check_index(sizes.out_e)?;
    crate::check_index(nc)?;

    // Pass 2: positions.
    positions(src, &mut dst.pos, s, nvo);

    // Pass 3: F-faces. Their corners are numbered like their vertices.
    f_faces(src, dst, s, &sizes);

    // Pass 4: E-faces, and the edges they share with the F-faces.
    e_faces(src, dst, s, &sizes);

    // Pass 5: V-faces.
    v_faces(src, dst, s, &sizes)?;

    link_corners(dst, sizes.out_c)
}

/// Where one level's output goes, and its sizes.
struct Sizes {
    /// First corner of the E-faces (after the F-faces').
    base_e: usize,
    /// First corner of the V-faces (after the E-faces').
    base_v: usize,
    /// Output corners.
    out_c: usize,
    /// Output faces.
    out_f: usize,
    /// Output edges.
    out_e: usize,
}

/// Pass 1: records each face's kind and each corner's points (`B` and
/// `A`) in `s`, and returns the number of output vertices.
fn number_corner_points(src: &Flat, s: &mut Scratch) -> usize {
    s.kind.clear();
    s.pb.clear();
    s.pa.clear();
    let mut nvo = 0u32;
    for f in 0..src.face_count() {
        let kind = src.kind(f);
        s.kind.push(kind);
        for _ in src.off[f]..src.off[f + 1] {
            s.pb.push(nvo);
            if kind == Kind::Hole {
                s.pa.push(nvo + 1);
                nvo += 2;
            } else {
                s.pa.push(nvo);
                nvo += 1;
            }
        }
    }
    nvo as usize
}

/// Counts each vertex's corners and hole corners and finds its first
/// corner (point-sphere corners excluded), in `s`; returns the output's
/// layout given its `nvo` vertices.
fn count_vertex_corners(src: &Flat, s: &mut Scratch, nvo: usize) -> Sizes {
    let nv = src.pos.len();
    let ne = src.edges.len();
    let nf = src.face_count();
    s.count.clear();
    s.count.resize(nv, 0);
    s.nh.clear();
    s.nh.resize(nv, 0);
    s.start.clear();
    s.start.resize(nv, NONE);
    for f in 0..nf {
        let kind = s.kind[f];
        if kind == Kind::PointSphere {
            continue;
        }
        for c in src.off[f] as usize..src.off[f + 1] as usize {
            let v = src.cv[c] as usize;
            s.count[v] += 1;
            if kind == Kind::Hole {
                s.nh[v] += 1;
            }
            if s.start[v] == NONE {
                s.start[v] = c as u32;
            }
        }
    }
    let vfaces = s.count.iter().filter(|&&n| n > 0).count();
    let vcorners: usize = s
        .count
        .iter()
        .zip(&s.nh)
        .map(|(&n, &h)| (n + h) as usize)
        .sum();
    let hole_corners: usize = s.nh.iter().map(|&h| h as usize).sum();
    let base_e = nvo;
    let base_v = base_e + 4 * ne;
    Sizes {
        base_e,
        base_v,
        out_c: base_v + vcorners,
        out_f: nf + ne + vfaces,
        out_e: 4 * ne + hole_corners,
    }
}

/// Pass 2: the `nvo` output positions, each face's corner points.
fn positions(src: &Flat, out: &mut Vec<DVec3>, s: &mut Scratch, nvo: usize) {
    out.clear();
    out.resize(nvo, DVec3::ZERO);
    let mut face_pos: Vec<DVec3> = Vec::new();
    for f in 0..src.face_count() {
        let (lo, hi) = (src.off[f] as usize, src.off[f + 1] as usize);
        let ob = s.pb[lo] as usize;
        match s.kind[f] {
            Kind::Normal => {
                face_pos.clear();
                face_pos.extend(src.cv[lo..hi].iter().map(|&v| src.pos[v as usize]));
                corner_points(&face_pos, &mut out[ob..ob + (hi - lo)], &mut s.trig);
            }
            Kind::Hole => {
                for c in lo..hi {
                    let v = src.pos[src.cv[c] as usize];
                    let u = src.pos[src.cv[if c == lo { hi - 1 } else { c - 1 }] as usize];
                    let w = src.pos[src.cv[if c + 1 == hi { lo } else { c + 1 }] as usize];
                    let o = ob + 2 * (c - lo);
                    out[o] = 0.75 * v + 0.25 * u;
                    out[o + 1] = 0.75 * v + 0.25 * w;
                }
            }
            Kind::PointSphere => out[ob] = src.pos[src.cv[lo] as usize],
        }
    }
}

/// Pass 3: empties `dst`'s faces, reserves room for the whole output,
/// and writes the F-faces, whose corners are numbered like their
/// vertices.
fn f_faces(src: &Flat, dst: &mut Flat, s: &Scratch, sizes: &Sizes) {
    dst.off.clear();
    dst.cv.clear();
    dst.cf.clear();
    dst.hole.clear();
    dst.off.reserve(sizes.out_f + 1);
    dst.cv.reserve(sizes.out_c);
    dst.cf.reserve(sizes.out_c);
    dst.hole.reserve(sizes.out_f);
    for f in 0..src.face_count() {
        let (lo, hi) = (src.off[f] as usize, src.off[f + 1] as usize);
        let (b, e) = (s.pb[lo], s.pa[hi - 1] + 1);
        dst.off.push(b);
        dst.cv.extend(b..e);
        dst.cf
            .extend(std::iter::repeat_n(f as u32, (e - b) as usize));
        dst.hole.push(src.hole[f]);
    }
}

/// Pass 4: E-faces [A(a), B(next b), A(b), B(next a)] for edge (a, b),
/// and the edges they share with the F-faces; sizes `dst.edges` to every
/// output edge, the V-face sides left unset.
fn e_faces(src: &Flat, dst: &mut Flat, s: &Scratch, sizes: &Sizes) {
    let nf = src.face_count();
    dst.edges.clear();
    dst.edges.resize(sizes.out_e, [NONE, NONE]);
    for (e, &[a, b]) in src.edges.iter().enumerate() {
        let (a, b) = (a as usize, b as usize);
        let (na, nb) = (src.next(a), src.next(b));
        let q = (sizes.base_e + 4 * e) as u32;
        dst.off.push(q);
        dst.cv
            .extend_from_slice(&[s.pa[a], s.pb[nb], s.pa[b], s.pb[na]]);
        dst.cf.extend_from_slice(&[(nf + e) as u32; 4]);
        dst.hole.push(false);
        // F-face corner A(a) runs A(a) → B(next a), against E-face corner 3.
        dst.edges[4 * e] = [s.pa[a], q + 3];
        dst.edges[4 * e + 1] = [s.pa[b], q + 1];
        // Corners 0 and 2 are paired with V-face corners in pass 5.
        dst.edges[4 * e + 2][0] = q;
        dst.edges[4 * e + 3][0] = q + 2;
    }
}

/// Pass 5: V-faces, walking each vertex's rotation backwards
/// (c → twin(prev c)) from its first corner. At corner c the V-face
/// reads A(c) (then B(c) at a hole corner) and goes on to the next
/// corner's A across the E-face of edge(prev c). Closes `dst.off`;
/// an error when a rotation does not match its vertex's corner count or
/// the totals do not match `sizes`.
fn v_faces(src: &Flat, dst: &mut Flat, s: &Scratch, sizes: &Sizes) -> Result<(), SubdivError> {
    let nv = src.pos.len();
    let ne = src.edges.len();
    let (out_c, out_e) = (sizes.out_c, sizes.out_e);
    let mut cur = sizes.base_v as u32;
    let mut hole_edge = 4 * ne;
    let mut face = (src.face_count() + ne) as u32;
    for v in 0..nv {
        let n = s.count[v];
        if n == 0 {
            continue;
        }
        dst.off.push(cur);
        dst.hole.push(false);
        let start = s.start[v] as usize;
        let mut c = start;
        let mut steps = 0u32;
        loop {
            let va = cur;
            dst.cv.push(s.pa[c]);
            dst.cf.push(face);
            cur += 1;
            let vend = if s.pa[c] != s.pb[c] {
                dst.cv.push(s.pb[c]);
                dst.cf.push(face);
                // The hole's corner B(c) → A(c) against V-face A(c) → B(c).
                dst.edges[hole_edge] = [s.pb[c], va];
                hole_edge += 1;
                cur += 1;
                cur - 1
            } else {
                va
            };
            let p = src.prev(c);
            let e = src.cedge[p] as usize;
            if src.edges[e][0] as usize == p {
                dst.edges[4 * e + 3][1] = vend;
            } else {
                dst.edges[4 * e + 2][1] = vend;
            }
            steps += 1;
            c = src.twin(p);
            if c == start {
                break;
            }
            if steps >= n {
                return Err(SubdivError::Internal(format!(
                    "the rotation at vertex {v} does not close after its {n} corners"
                )));
            }
        }
        if steps != n {
            return Err(SubdivError::Internal(format!(
                "the rotation at vertex {v} covers {steps} of its {n} corners"
            )));
        }
        face += 1;
    }
    dst.off.push(cur);
    if cur as usize != out_c || hole_edge != out_e {
        return Err(SubdivError::Internal(format!(
            "V-faces hold {cur} corners and {hole_edge} edges, {out_c} and {out_e} expected"
        )));
    }
    Ok(())
}

/// Sizes `dst.cedge` to the `out_c` output corners and sets each
/// corner's edge; an error for an edge pass 4 or 5 left unpaired.
fn link_corners(dst: &mut Flat, out_c: usize) -> Result<(), SubdivError> {
    dst.cedge.clear();
    dst.cedge.resize(out_c, NONE);
    for (i, &[x, y]) in dst.edges.iter().enumerate() {
        if x == NONE || y == NONE {
            return Err(SubdivError::Internal(format!(
                "output edge {i} was left unpaired"
            )));
        }
        dst.cedge[x as usize] = i as u32;
        dst.cedge[y as usize] = i as u32;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use holey_dlfl::DVec3;
    use holey_testkit::Rng;

    use super::corner_points;
    use crate::catmull_clark::tests::volume;
    use crate::tests::{checked, counts, cube_levels, dlfl, prim};
    use crate::{Scheme, doo_sabin};

    const DS: Scheme = Scheme::DooSabin;

    /// The corner point by the weights as written, O(n) per corner.
    fn direct(p: &[DVec3], j: usize) -> DVec3 {
        let n = p.len();
        let nf = n as f64;
        (0..n)
            .map(|i| {
                let a = if i == 0 {
                    0.25 + 5.0 / (4.0 * nf)
                } else {
                    (3.0 + 2.0 * (std::f64::consts::TAU * i as f64 / nf).cos()) / (4.0 * nf)
                };
                a * p[(j + i) % n]
            })
            .sum()
    }

    #[test]
    fn corner_points_use_the_original_weights() {
        let mut rng = Rng::new(3);
        let mut trig = Vec::new();
        for n in 2..=40 {
            let p: Vec<DVec3> = (0..n)
                .map(|_| DVec3::from_array(rng.point(-1.0, 1.0)))
                .collect();
            let mut out = vec![DVec3::ZERO; n];
            corner_points(&p, &mut out, &mut trig);
            for (j, q) in out.iter().enumerate() {
                assert!((*q - direct(&p, j)).length() < 1e-14, "n = {n}, corner {j}");
            }
            // Weights sum to one: a translated face gives translated points.
            let shifted: Vec<DVec3> = p.iter().map(|q| *q + DVec3::splat(10.0)).collect();
            let mut out2 = vec![DVec3::ZERO; n];
            corner_points(&shifted, &mut out2, &mut trig);
            for (a, b) in out.iter().zip(&out2) {
                assert!((*b - *a - DVec3::splat(10.0)).length() < 1e-12);
            }
        }
        // The quad's weights are the biquadratic B-spline's.
        let sq = [DVec3::X, DVec3::Y, DVec3::Z, DVec3::ONE];
        let mut out = [DVec3::ZERO; 4];
        corner_points(&sq, &mut out, &mut trig);
        let expect = (9.0 * DVec3::X + 3.0 * DVec3::Y + DVec3::Z + 3.0 * DVec3::ONE) / 16.0;
        assert_eq!(out[0], expect);
        // A monogon's point is its vertex.
        let mut one = [DVec3::ZERO];
        corner_points(&[DVec3::X], &mut one, &mut trig);
        assert_eq!(one[0], DVec3::X);
    }

    #[test]
    fn cube_counts_and_two_levels() {
        // V' = corners = 2E, E' = 4E, F' = F + E + V.
        let (one, _) = cube_levels(DS, (24, 48, 26), (2 * 48, 4 * 48, 26 + 48 + 24));
        // The cube's corner points sit at (±1/2, ±1/2, ±1) and permutations
        // (9/16·1 + 3/16·1 + 1/16·(−1) + 3/16·(−1) = 1/2 in-plane).
        for v in one.vertices() {
            let mut a: Vec<f64> = one
                .position(v)
                .unwrap()
                .to_array()
                .iter()
                .map(|x| x.abs())
                .collect();
            a.sort_by(f64::total_cmp);
            assert_eq!(a, [0.5, 0.5, 1.0]);
        }
        // Face sizes: 6 quads (F), 12 quads (E), 8 triangles (V).
        let mut sizes: Vec<usize> = one.faces().map(|f| one.face_len(f).unwrap()).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, [vec![3; 8], vec![4; 18]].concat());
    }

    #[test]
    fn torus_stays_genus_one() {
        let m = prim("@torus:8:6");
        let out = checked(&m, DS, 2);
        // Level 1: V = 192, E = 384, F = 48 + 96 + 48; level 2: V = 768.
        assert_eq!(counts(&out), (768, 1536, 192 + 384 + 192));
        assert_eq!(out.genus(), 1);
    }

    #[test]
    fn cube_volume_decreases() {
        // Corner cutting of a convex solid stays inside it.
        let m = prim("@cube");
        let mut last = volume(&m);
        for level in 1..=5 {
            let v = volume(&doo_sabin(&m, level).unwrap());
            assert!(v < last && v > 4.0, "level {level}: {v} after {last}");
            last = v;
        }
    }

    #[test]
    fn planar_meshes_stay_planar() {
        // A jittered open grid with triangles and pentagons mixed in, laid
        // in a tilted plane: every corner point and Chaikin point is an
        // affine combination of points of the plane.
        let mut rng = Rng::new(5);
        let mut poly = holey_shapes::tri_plane(5, 4).unwrap();
        let normal = DVec3::new(1.0, -2.0, 0.5).normalize();
        let u = normal.any_orthonormal_vector();
        let w = normal.cross(u);
        let origin = DVec3::new(0.3, 0.1, -2.0);
        for p in &mut poly.positions {
            let (x, y) = (p.x + rng.range(-0.1, 0.1), p.y + rng.range(-0.1, 0.1));
            *p = origin + x * u + y * w;
        }
        let mut m = dlfl(&poly);
        // Merge a few triangle pairs into quads by deleting diagonals.
        let diagonals: Vec<_> = m
            .edges()
            .filter(|&e| {
                let [a, b] = m.edge_faces(e).unwrap();
                !m.is_hole(a).unwrap() && !m.is_hole(b).unwrap()
            })
            .step_by(3)
            .collect();
        for e in diagonals {
            m.delete_edge(e).unwrap();
        }
        let out = checked(&m, DS, 3);
        let d = origin.dot(normal);
        for v in out.vertices() {
            let off = out.position(v).unwrap().dot(normal) - d;
            assert!(off.abs() < 1e-12, "{off}");
        }
    }

    #[test]
    fn boundary_loops_refine_by_chaikin_into_quadratic_b_splines() {
        // The quadratic B-spline of a closed polygon passes through each
        // edge's midpoint and, halfway between, through (P₋ + 6P + P₊)/8.
        // Chaikin refinement keeps both as midpoints of the refined
        // polygon's edges at every level; after three levels the hole is
        // the level-3 Chaikin polygon, 8 times as many corners.
        let mut poly = holey_shapes::plane(4, 3).unwrap();
        let mut rng = Rng::new(9);
        for p in &mut poly.positions {
            p.z = rng.range(-0.5, 0.5);
        }
        let m = dlfl(&poly);
        let hole = m.faces().find(|&f| m.is_hole(f).unwrap()).unwrap();
        let ring = m.face_positions(hole).unwrap();
        let k = ring.len();
        let out = checked(&m, DS, 3);
        let out_hole = out.faces().find(|&f| out.is_hole(f).unwrap()).unwrap();
        let refined = out.face_positions(out_hole).unwrap();
        assert_eq!(refined.len(), 8 * k);
        let mids: Vec<DVec3> = (0..refined.len())
            .map(|i| (refined[i] + refined[(i + 1) % refined.len()]) / 2.0)
            .collect();
        let on_curve = |p: DVec3| mids.iter().any(|q| (*q - p).length() < 1e-13);
        for i in 0..k {
            let (a, b, c) = (ring[(i + k - 1) % k], ring[i], ring[(i + 1) % k]);
            assert!(on_curve((b + c) / 2.0), "edge {i}");
            assert!(on_curve((a + 6.0 * b + c) / 8.0), "vertex {i}");
        }
        // The refined hole polygon is exactly Chaikin's: consecutive pairs
        // at 3/4 and 1/4 along each edge of the level-2 hole.
        let two = doo_sabin(&m, 2).unwrap();
        let h2 = two.faces().find(|&f| two.is_hole(f).unwrap()).unwrap();
        let r2 = two.face_positions(h2).unwrap();
        let n2 = r2.len();
        for i in 0..n2 {
            let (b, c) = (r2[i], r2[(i + 1) % n2]);
            for expect in [0.75 * b + 0.25 * c, 0.25 * b + 0.75 * c] {
                assert!(refined.iter().any(|q| (*q - expect).length() < 1e-14));
            }
        }
    }

    #[test]
    fn valence_two_vertices_and_two_gons_give_two_gon_faces() {
        // A subdivided cube edge has a valence-2 vertex: its V-face is a
        // two-gon. Both faces beside the edge gain a corner (pentagons).
        let mut m = prim("@cube");
        let e = m.edges().next().unwrap();
        m.subdivide_edge(e).unwrap();
        let out = checked(&m, DS, 1);
        let sizes: Vec<usize> = out.faces().map(|f| out.face_len(f).unwrap()).collect();
        assert_eq!(sizes.iter().filter(|&&k| k == 2).count(), 1);
        assert_eq!(sizes.iter().filter(|&&k| k == 5).count(), 2);
    }
}
