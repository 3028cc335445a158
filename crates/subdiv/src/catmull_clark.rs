//! One level of Catmull–Clark subdivision on a [`Flat`] map; the
//! rules, and what they do with the DLFL's special cases and with
//! boundaries, are documented on [`crate::catmull_clark`].

use glam::DVec3;

use crate::SubdivError;
use crate::flat::{Flat, Kind, NONE};

/// Buffers reused from level to level.
#[derive(Default)]
pub(crate) struct Scratch {
    kind: Vec<Kind>,
    /// First output corner of each input face.
    obase: Vec<u32>,
    /// First output face of each input face.
    ofbase: Vec<u32>,
    /// Vertex index of the face point (ordinary faces only).
    fp: Vec<u32>,
    /// Per vertex: corners in ordinary faces, corners in holes.
    n: Vec<u32>,
    nh: Vec<u32>,
    /// Per vertex: sum of the neighbours along the holes.
    bsum: Vec<DVec3>,
}

/// Subdivides `src` once into `dst` (which must be empty).
///
/// Output numbering: vertex `i < V` is the vertex point of input vertex
/// `i`; then come the edge points in edge order and the face points in
/// face order. Output faces follow input face order: an ordinary face's
/// quads in corner order, a hole's refined hole, a point-sphere's copy.
///
/// With `links` false (the last level), the per-corner face and edge
/// indices that only the next level needs are not made: `dst.cf` and
/// `dst.cedge` are left empty.
pub(crate) fn step(
    src: &Flat,
    dst: &mut Flat,
    s: &mut Scratch,
    links: bool,
) -> Result<(), SubdivError> {
    // Pass 1, faces: kinds and where each face's output goes.
    let sizes = plan_faces(src, s);
    crate::check_index(sizes.out_v)?;
    crate::check_index(sizes.oc)?;
    crate::check_index(sizes.out_e)?;

    // Pass 2, face points (centroids).
    face_points(src, &mut dst.pos, s, sizes.out_v);

    // Pass 3, vertex points: accumulate over corners, then apply the rule.
    vertex_points(src, &mut dst.pos, s);

    // Pass 4, edge points.
    edge_points(src, &mut dst.pos, s);

    // Pass 5, connectivity.
    connectivity(src, dst, s, links, &sizes)
}

/// The sizes of one level's output, from pass 1.
struct Sizes {
    /// Output corners.
    oc: usize,
    /// Output faces.
    of: usize,
    /// Output vertices: vertex points, edge points, face points.
    out_v: usize,
    /// Output edges.
    out_e: usize,
}

/// Pass 1: records each face's kind, first output corner, first output
/// face and face point in `s`, and returns the output's sizes.
fn plan_faces(src: &Flat, s: &mut Scratch) -> Sizes {
    let nv = src.pos.len();
    let ne = src.edges.len();
    let nf = src.face_count();
    s.kind.clear();
    s.obase.clear();
    s.ofbase.clear();
    s.fp.clear();
    let (mut oc, mut of, mut ncn, mut nfp) = (0usize, 0usize, 0usize, 0usize);
    for f in 0..nf {
        let k = (src.off[f + 1] - src.off[f]) as usize;
        let kind = src.kind(f);
        s.kind.push(kind);
        s.obase.push(oc as u32);
        s.ofbase.push(of as u32);
        match kind {
            Kind::Normal => {
                s.fp.push((nv + ne + nfp) as u32);
                nfp += 1;
                oc += 4 * k;
                of += k;
                ncn += k;
            }
            Kind::Hole => {
                s.fp.push(NONE);
                oc += 2 * k;
                of += 1;
            }
            Kind::PointSphere => {
                s.fp.push(NONE);
                oc += 1;
                of += 1;
            }
        }
    }
    Sizes {
        oc,
        of,
        out_v: nv + ne + nfp,
        out_e: 2 * ne + ncn,
    }
}

/// Pass 2: sizes `out` to `out_v` zeroed positions and writes each
/// ordinary face's point, the centroid of its corners.
fn face_points(src: &Flat, out: &mut Vec<DVec3>, s: &Scratch, out_v: usize) {
    let pos = &src.pos;
    out.clear();
    out.resize(out_v, DVec3::ZERO);
    for f in 0..src.face_count() {
        if s.kind[f] != Kind::Normal {
            continue;
        }
        let (lo, hi) = (src.off[f] as usize, src.off[f + 1] as usize);
        let sum: DVec3 = src.cv[lo..hi].iter().map(|&v| pos[v as usize]).sum();
        out[s.fp[f] as usize] = sum / (hi - lo) as f64;
    }
}

/// Pass 3: the vertex points, written to the first `V` entries of `out`
/// (whose face points pass 2 has written), accumulating each vertex's
/// neighbourhood over the corners before applying the rule.
fn vertex_points(src: &Flat, out: &mut [DVec3], s: &mut Scratch) {
    let nv = src.pos.len();
    let ne = src.edges.len();
    let pos = &src.pos;
    s.n.clear();
    s.n.resize(nv, 0);
    s.nh.clear();
    s.nh.resize(nv, 0);
    let has_holes = s.kind.contains(&Kind::Hole);
    if has_holes {
        s.bsum.clear();
        s.bsum.resize(nv, DVec3::ZERO);
    }
    let (vpts, rest) = out.split_at_mut(nv);
    let fpts = &rest[ne..];
    for f in 0..src.face_count() {
        let (lo, hi) = (src.off[f] as usize, src.off[f + 1] as usize);
        match s.kind[f] {
            Kind::Normal => {
                let fpos = fpts[(s.fp[f] as usize) - nv - ne];
                for c in lo..hi {
                    let v = src.cv[c] as usize;
                    let w = src.cv[if c + 1 == hi { lo } else { c + 1 }] as usize;
                    vpts[v] += fpos + pos[w];
                    s.n[v] += 1;
                }
            }
            Kind::Hole => {
                for c in lo..hi {
                    let v = src.cv[c] as usize;
                    let w = src.cv[if c + 1 == hi { lo } else { c + 1 }] as usize;
                    let u = src.cv[if c == lo { hi - 1 } else { c - 1 }] as usize;
                    s.bsum[v] += pos[u] + pos[w];
                    s.nh[v] += 1;
                }
            }
            Kind::PointSphere => {}
        }
    }
    for v in 0..nv {
        let (n, nh) = (s.n[v], s.nh[v]);
        let p = pos[v];
        vpts[v] = if nh == 0 && n >= 2 {
            let nf64 = f64::from(n);
            vpts[v] / (nf64 * nf64) + p * ((nf64 - 2.0) / nf64)
        } else if nh == 1 && n + nh >= 3 {
            (s.bsum[v] + 6.0 * p) / 8.0
        } else {
            p
        };
    }
}

/// Pass 4: the edge points, written to `out` after the vertex points
/// (reading the face points pass 2 wrote there).
fn edge_points(src: &Flat, out: &mut [DVec3], s: &Scratch) {
    let nv = src.pos.len();
    let pos = &src.pos;
    for (e, &[a, b]) in src.edges.iter().enumerate() {
        let (a, b) = (a as usize, b as usize);
        let (fa, fb) = (src.cf[a] as usize, src.cf[b] as usize);
        let (p0, p1) = (pos[src.cv[a] as usize], pos[src.cv[b] as usize]);
        out[nv + e] = if s.kind[fa] == Kind::Normal && s.kind[fb] == Kind::Normal {
            (p0 + p1 + out[s.fp[fa] as usize] + out[s.fp[fb] as usize]) * 0.25
        } else {
            (p0 + p1) * 0.5
        };
    }
}

/// `first(c)`: the output corner from v(c) to the point of c's edge.
#[inline]
fn first_corner(src: &Flat, s: &Scratch, c: usize) -> u32 {
    let f = src.cf[c] as usize;
    let j = (c - src.off[f] as usize) as u32;
    match s.kind[f] {
        Kind::Hole => s.obase[f] + 2 * j,
        _ => s.obase[f] + 4 * j,
    }
}

/// `second(c)`: the output corner from the point of c's edge on to
/// v(next c).
#[inline]
fn second_corner(src: &Flat, s: &Scratch, c: usize) -> u32 {
    let f = src.cf[c] as usize;
    let lo = src.off[f] as usize;
    let k = src.off[f + 1] as usize - lo;
    let j = c - lo;
    match s.kind[f] {
        Kind::Hole => s.obase[f] + 2 * j as u32 + 1,
        _ => s.obase[f] + 4 * ((j + 1) % k) as u32 + 3,
    }
}

/// Empties `dst`'s connectivity and reserves room for `sizes`; with
/// `links`, `dst.cedge` is sized to every output corner, unset.
fn reset_connectivity(dst: &mut Flat, sizes: &Sizes, links: bool) {
    let (oc, of) = (sizes.oc, sizes.of);
    dst.off.clear();
    dst.cv.clear();
    dst.cf.clear();
    dst.hole.clear();
    dst.off.reserve(of + 1);
    dst.cv.reserve(oc);
    if links {
        dst.cf.reserve(oc);
    }
    dst.hole.reserve(of);
    dst.edges.clear();
    dst.edges.reserve(sizes.out_e);
    dst.cedge.clear();
    if links {
        dst.cedge.resize(oc, NONE);
    }
}

/// Pass 5: the output faces and edges. `first(c)` is the output corner
/// from v(c) to the point of c's edge, `second(c)` the one from that
/// point on to v(next c); the two halves of an edge (a, b) pair first(a)
/// with second(b) and second(a) with first(b).
fn connectivity(
    src: &Flat,
    dst: &mut Flat,
    s: &Scratch,
    links: bool,
    sizes: &Sizes,
) -> Result<(), SubdivError> {
    let nv = src.pos.len();
    let first = |c: usize| first_corner(src, s, c);
    let second = |c: usize| second_corner(src, s, c);
    reset_connectivity(dst, sizes, links);
    // Edges are numbered in the order of their first corner, as each
    // output corner is written: what is near on the surface then stays
    // near in memory (edge points of the next level included), which
    // makes every later pass, and building the kernel mesh, faster.
    let edges = &mut dst.edges;
    let cedge = &mut dst.cedge;
    let mut pair = |x: u32, t: u32| {
        if t > x {
            let id = edges.len() as u32;
            edges.push([x, t]);
            if links {
                cedge[x as usize] = id;
                cedge[t as usize] = id;
            }
        }
    };
    let ep = |e: u32| nv as u32 + e;
    for f in 0..src.face_count() {
        let (lo, hi) = (src.off[f] as usize, src.off[f + 1] as usize);
        let k = hi - lo;
        let ob = s.obase[f];
        let ofb = s.ofbase[f];
        match s.kind[f] {
            Kind::Normal => {
                let fp = s.fp[f];
                for j in 0..k {
                    let c = lo + j;
                    let pc = if j == 0 { hi - 1 } else { c - 1 };
                    let q = ob + 4 * j as u32;
                    dst.off.push(q);
                    dst.cv
                        .extend_from_slice(&[src.cv[c], ep(src.cedge[c]), fp, ep(src.cedge[pc])]);
                    let face = ofb + j as u32;
                    if links {
                        dst.cf.extend_from_slice(&[face; 4]);
                    }
                    dst.hole.push(false);
                    // Corner 0 is first(c), corner 3 is second(prev c);
                    // corner 1 (edge point → face point) meets the next
                    // quad's corner 2.
                    let qn = ob + 4 * ((j + 1) % k) as u32;
                    let qp = ob + 4 * ((j + k - 1) % k) as u32;
                    pair(q, second(src.twin(c)));
                    pair(q + 1, qn + 2);
                    pair(q + 2, qp + 1);
                    pair(q + 3, first(src.twin(pc)));
                }
            }
            Kind::Hole => {
                dst.off.push(ob);
                for c in lo..hi {
                    dst.cv.push(src.cv[c]);
                    dst.cv.push(ep(src.cedge[c]));
                    let x = ob + 2 * (c - lo) as u32;
                    let t = src.twin(c);
                    pair(x, second(t));
                    pair(x + 1, first(t));
                }
                if links {
                    dst.cf.extend(std::iter::repeat_n(ofb, 2 * k));
                }
                dst.hole.push(true);
            }
            Kind::PointSphere => {
                dst.off.push(ob);
                dst.cv.push(src.cv[lo]);
                if links {
                    dst.cf.push(ofb);
                }
                dst.hole.push(src.hole[f]);
            }
        }
    }
    dst.off.push(sizes.oc as u32);
    if dst.edges.len() != sizes.out_e {
        return Err(SubdivError::Internal(format!(
            "{} edges made, {} expected",
            dst.edges.len(),
            sizes.out_e
        )));
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use holey_dlfl::{DVec3, Mesh, VertexId};
    use holey_testkit::Rng;

    use crate::Scheme;
    use crate::tests::{checked, counts, cube_levels, dlfl, prim, structured};

    const CC: Scheme = Scheme::CatmullClark;

    /// Signed volume of a closed mesh, faces fanned from their first corner.
    pub(crate) fn volume(m: &Mesh) -> f64 {
        m.faces()
            .map(|f| {
                let p = m.face_positions(f).unwrap();
                (1..p.len().saturating_sub(1))
                    .map(|i| p[0].dot(p[i].cross(p[i + 1])) / 6.0)
                    .sum::<f64>()
            })
            .sum()
    }

    /// The two neighbours of a boundary vertex along its hole.
    fn along_hole(m: &Mesh, v: VertexId) -> (DVec3, DVec3) {
        let c = m
            .vertex_corners(v)
            .unwrap()
            .find(|&c| m.is_hole(m.corner_face(c).unwrap()).unwrap())
            .expect("a boundary vertex");
        let at = |c| m.position(m.corner_vertex(c).unwrap()).unwrap();
        (at(m.corner_prev(c).unwrap()), at(m.corner_next(c).unwrap()))
    }

    /// An `n × n` open grid with random heights.
    fn bumpy_grid(n: u32, seed: u64) -> Mesh {
        let mut poly = holey_shapes::plane(n, n).unwrap();
        let mut rng = Rng::new(seed);
        for p in &mut poly.positions {
            p.z = rng.range(-0.3, 0.3);
        }
        dlfl(&poly)
    }

    /// The output vertex index of the edge point of the edge between input
    /// vertices `u` and `w` (edges are numbered in slot order).
    fn edge_point(m: &Mesh, u: usize, w: usize) -> usize {
        let rank = m
            .edges()
            .position(|e| {
                let [a, b] = m.edge_vertices(e).unwrap();
                (a.index(), b.index()) == (u, w) || (a.index(), b.index()) == (w, u)
            })
            .expect("an edge");
        m.vertex_count() + rank
    }

    #[test]
    fn cube_counts_and_two_levels() {
        // Two levels by formula: V' = V + E + F, E' = 2E + (corners),
        // F' = corners, and every face is a quad after one level.
        let two_levels = (26 + 48 + 24, 2 * 48 + 4 * 24, 4 * 24);
        let (_, two) = cube_levels(CC, (26, 48, 24), two_levels);
        assert_eq!(two.genus(), 0);
        // Triangles: the tetrahedron's 12 corners make 12 quads.
        let t = checked(&prim("@tetrahedron"), CC, 2);
        assert_eq!(counts(&t), (14 + 24 + 12, 2 * 24 + 48, 48));
    }

    #[test]
    fn torus_stays_genus_one() {
        let m = prim("@torus:8:6");
        assert_eq!(counts(&m), (48, 96, 48));
        let out = checked(&m, CC, 2);
        assert_eq!(counts(&out), (768, 1536, 768));
        assert_eq!(out.genus(), 1);
    }

    #[test]
    fn cube_points_are_the_textbook_ones() {
        // [-1,1]³: a corner has n = 3, Q = (1,1,1)/3, R = (2,2,2)/3, so it
        // moves to (Q + 2R)/3 = 5/9 (1,1,1); the edge from (1,1,1) to
        // (1,1,−1) gets (v₀ + v₁ + (1,0,0) + (0,1,0))/4 = (3/4, 3/4, 0).
        let m = prim("@cube");
        let out = structured(&m, CC, 1);
        for v in m.vertices() {
            let p = m.position(v).unwrap();
            let q = out.position(out.vertex_at(v.index()).unwrap()).unwrap();
            assert!((q - p * (5.0 / 9.0)).length() < 1e-15, "{q}");
        }
        let mut edge_pts = 0;
        let mut face_pts = 0;
        for v in out.vertices().skip(8) {
            let q = out.position(v).unwrap();
            let mut a: Vec<f64> = q.to_array().iter().map(|x| x.abs()).collect();
            a.sort_by(f64::total_cmp);
            if a == [0.0, 0.75, 0.75] {
                edge_pts += 1;
            } else if a == [0.0, 0.0, 1.0] {
                face_pts += 1;
            }
        }
        assert_eq!((edge_pts, face_pts), (12, 6));
    }

    #[test]
    fn regular_grid_interior_follows_the_bicubic_b_spline_masks() {
        // On a regular quad grid Catmull–Clark is uniform bicubic B-spline
        // refinement: vertex points are the tensor mask (1,6,1)/8 ⊗
        // (1,6,1)/8, edge points (1,1)/2 ⊗ (1,6,1)/8.
        let n = 6;
        let m = bumpy_grid(n, 7);
        let out = structured(&m, CC, 1);
        let id = |i: u32, j: u32| (j * (n + 1) + i) as usize;
        let p = |i: u32, j: u32| m.position(m.vertex_at(id(i, j)).unwrap()).unwrap();
        let q = |k: usize| out.position(out.vertex_at(k).unwrap()).unwrap();
        let w = [1.0 / 8.0, 6.0 / 8.0, 1.0 / 8.0];
        let mut checked_points = 0;
        for j in 1..n {
            for i in 1..n {
                let mut expect = DVec3::ZERO;
                for (a, wa) in w.iter().enumerate() {
                    for (b, wb) in w.iter().enumerate() {
                        expect += wa * wb * p(i + a as u32 - 1, j + b as u32 - 1);
                    }
                }
                assert!((q(id(i, j)) - expect).length() < 1e-14);
                // The edge to the right, (1,1)/2 across, (1,6,1)/8 along y.
                if i + 1 < n {
                    let mut e = DVec3::ZERO;
                    for (b, wb) in w.iter().enumerate() {
                        let jj = j + b as u32 - 1;
                        e += wb * 0.5 * (p(i, jj) + p(i + 1, jj));
                    }
                    let k = edge_point(&m, id(i, j), id(i + 1, j));
                    assert!((q(k) - e).length() < 1e-14);
                }
                checked_points += 1;
            }
        }
        assert_eq!(checked_points, 25);
    }

    #[test]
    fn boundary_curves_are_cubic_b_splines() {
        // The limit of a cubic B-spline at control point i is
        // (P₋ + 4P + P₊)/6, at the middle of span (i, i+1) it is
        // (P_{i−1} + 23P_i + 23P_{i+1} + P_{i+2})/48. Both must hold for
        // the boundary after three levels, evaluated with the limit mask
        // from the level-3 boundary, away from the fixed grid corners.
        let n = 8;
        let m = bumpy_grid(n, 11);
        let nv = m.vertex_count();
        let out = structured(&m, CC, 3);
        let p = |i: u32| m.position(m.vertex_at(i as usize).unwrap()).unwrap(); // row j = 0
        let limit = |k: usize| {
            let v = out.vertex_at(k).unwrap();
            let (a, b) = along_hole(&out, v);
            (a + 4.0 * out.position(v).unwrap() + b) / 6.0
        };
        for i in 2..=n - 2 {
            let expect = (p(i - 1) + 4.0 * p(i) + p(i + 1)) / 6.0;
            assert!((limit(i as usize) - expect).length() < 1e-13, "vertex {i}");
        }
        for i in 2..=n - 3 {
            let expect = (p(i - 1) + 23.0 * p(i) + 23.0 * p(i + 1) + p(i + 2)) / 48.0;
            let k = edge_point(&m, i as usize, i as usize + 1);
            assert!(k >= nv);
            assert!((limit(k) - expect).length() < 1e-13, "span {i}");
        }
        // Corners (valence 2) stay where they were, at every level.
        for corner in [
            0,
            n as usize,
            (n * (n + 1)) as usize,
            ((n + 1) * (n + 1) - 1) as usize,
        ] {
            let v = m.vertex_at(corner).unwrap();
            assert_eq!(
                out.position(out.vertex_at(corner).unwrap()).unwrap(),
                m.position(v).unwrap()
            );
        }
    }

    #[test]
    fn cube_volume_decreases_and_converges() {
        // The limit surface is inside every control mesh, so the volumes
        // decrease, geometrically (each level's change about a quarter of
        // the last), and stay above the ball through the limit of the face
        // centres: from level 1, a face centre is a regular vertex with
        // limit (16 S + 4 Σ edge neighbours + Σ diagonal neighbours)/36 =
        // (16 + 4·4·3/4 + 4·5/9)/36 = 68/81 from the centre.
        let m = prim("@cube");
        let r = 68.0 / 81.0;
        let ball = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
        let mut vols = vec![volume(&m)];
        for level in 1..=5 {
            vols.push(volume(&structured(&m, CC, level)));
        }
        assert!((vols[0] - 8.0).abs() < 1e-12);
        for w in vols.windows(2) {
            assert!(w[1] < w[0], "{vols:?}");
        }
        for w in vols.windows(3).skip(1) {
            let ratio = (w[2] - w[1]) / (w[1] - w[0]);
            assert!(ratio > 0.2 && ratio < 0.3, "{ratio} in {vols:?}");
        }
        assert!(vols[5] > ball, "{vols:?} vs ball {ball}");
        // The face centre itself converges to 68/81 (a +x face's centre is
        // output vertex 8 + 12 + k for the face k centred on +x).
        let face = m
            .faces()
            .position(|f| {
                let c: DVec3 = m.face_positions(f).unwrap().iter().sum::<DVec3>() / 4.0;
                c.x > 0.99
            })
            .unwrap();
        let k = 8 + 12 + face;
        let mut errs = Vec::new();
        for level in [3, 5, 7] {
            let out = structured(&m, CC, level);
            let x = out.position(out.vertex_at(k).unwrap()).unwrap();
            assert!(x.y.abs() < 1e-15 && x.z.abs() < 1e-15);
            errs.push((x.x - r).abs());
        }
        assert!(
            errs[1] < errs[0] / 8.0 && errs[2] < errs[1] / 8.0,
            "{errs:?}"
        );
        assert!(errs[2] < 1e-3, "{errs:?}");
    }
}
