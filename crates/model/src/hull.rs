//! # Convex hulls (TopMod's conical tools, issue 18)
//!
//! [`convex_hull`] replaces a mesh by the convex hull of its vertices, and
//! [`dual_convex_hull`] by TopMod's *dual convex hull*: the solid bounded
//! by the tangent planes at the hull's vertices.
//!
//! ## Convex hull
//! Quickhull over the vertex positions (point-spheres included), every
//! decision exact and without a tolerance: a point lies outside a
//! triangle when Shewchuk's exact `orient3d` ([`holey_geom::orient3d`])
//! of the triangle and the point is negative, and two neighbouring
//! triangles are one face when the far corner of one gives `orient3d`
//! exactly zero on the other. A point 10⁻¹⁷ outside a face is a corner of
//! the hull, at any offset; a point exactly on a face or on a straight
//! edge is not. Coplanar triangles are merged into one convex polygon and
//! points in the middle of a face or of a straight edge are dropped, so
//! every vertex of the result is a corner of at least three faces: a
//! convex polyhedron of genus 0, `V − E + F = 2`, with `F = 2V − 4` when
//! every face is a triangle (points in general position). The hull of a
//! cube's vertices is the cube, `8/12/6`.
//!
//! The predicates see the points scaled by one power of two, chosen so the
//! largest coordinate magnitude lies in `[1, 2)`: scaling by a power of two
//! is exact, and it keeps the determinants' products from overflowing, so
//! any finite coordinates have a hull. `orient3d` is exact as long as its
//! products do not underflow, which holds when every nonzero coordinate
//! (after that scaling) is above about `10⁻⁹⁰`; a set mixing coordinates
//! below that with ones near 1 could be misjudged, and what the
//! construction then finds inconsistent is refused with
//! [`HullError::Numerical`] rather than returned. Only the farthest-point
//! choice of quickhull uses floating point, which changes the order of
//! the work and never the result.
//!
//! ## Dual convex hull
//! TopMod's `createDualConvexHull` cuts the points' bounding box by the
//! plane through each hull vertex perpendicular to its normal, which
//! leaves the box untouched where the planes only graze it (a cube came
//! back a cube). Here the box is gone: the result is the intersection of
//! the half-spaces `n̂_v · (x − p_v) ≤ 0` over the hull's vertices `v`,
//! where `n_v = ∫ n dA` over the normal cone of `v`: the spherical polygon
//! spanned by the unit normals of the hull's faces at `v`, in order around
//! it.
//!
//! That `n_v` lies strictly inside the cone of normals at `v`, so each
//! plane touches the hull at `p_v` only and bounds one face of the
//! result; and the normal cones of a convex polyhedron's corners tile the
//! sphere, so `Σ_v n_v = ∫_(S²) n dA = 0` with every `n_v` nonzero and the
//! half-spaces bound a polytope. The cone does not change when a flat
//! face is cut into triangles and moves continuously with the faces, so
//! a face that is planar only to rounding (a dodecahedron's pentagons in
//! `f64`), which the exact hull keeps as several triangles, gives the
//! same planes to within rounding. (The earlier `Σ_f A_f n̂_f / k_f`
//! depended on how such a face was split.) Where rounding leaves that
//! integral outside the cone (faces meeting within rounding of flat), so
//! that a neighbour of `v` would lie in front of the plane, the sum of
//! the faces' unit normals is used instead. The result is the polar dual
//! of the hull seen from its vertex centroid: one face per hull vertex,
//! `F* = V`, and where three planes meet at each vertex (points in
//! general position) `V* = 2F* − 4`, `E* = 3F* − 6`. On a regular
//! polyhedron the normals point at its vertices and the result is its
//! dual: a cube gives an octahedron `6/12/8`, a dodecahedron an
//! icosahedron `12/30/20`. It contains the hull, touching it at the
//! hull's vertices.
//!
//! **Constructions and decisions.** The dual needs new points: the
//! normals `n_v`, each plane's polar point `n̂_v / (n̂_v · (p_v − c))`
//! about the centroid `c`, and each result vertex (the plane of a facet
//! of the polar points' hull). These are computed in floating point. The
//! rule is that a constructed point is rounded once and then only ever
//! decided on exactly, as an input: the polar points' hull is the exact
//! hull of the rounded polar points, and the result's faces, edges and
//! orientation are read off its combinatorics (the facets around each
//! polar corner, turned to face outward by the hull's own orientation,
//! with no sign test on constructed coordinates). So rounding can move a
//! vertex of the result (its faces are then planar only to rounding), or
//! make a plane that only just touches the others bound no face (a hull
//! corner whose planes meet within rounding), but it cannot make the
//! result invalid: it is always the dual of an exact convex polytope, a
//! closed genus-0 2-manifold. Constructions are done on the scaled points
//! and scaled back, so only a result whose corners lie beyond the range of
//! `f64` is refused ([`HullError::Overflow`]).
//!
//! Both run in `O(n log n)` expected time for `n` points and never change
//! their input. Fewer than four points off one plane are refused with
//! [`HullError::Flat`], decided exactly.

use std::collections::HashMap;

use holey_dlfl::{BuildError, DVec3, Mesh, RawMesh};
use holey_geom::{Sign, orient2d, orient3d};

/// Why a hull was refused. The input is unchanged (these functions never
/// change it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HullError {
    /// The points do not span space: all on one plane, a line or a point
    /// (or there are fewer than four), decided exactly.
    #[error(
        "the {points} vertex position(s) lie on one plane, so they bound no solid; a hull needs four points off one plane"
    )]
    Flat {
        /// How many points there were.
        points: usize,
    },
    /// The dual convex hull's corners lie beyond the range of `f64` (the
    /// number is the largest coordinate magnitude of the input).
    #[error(
        "the coordinates are too large for the dual convex hull: its corners lie beyond the range of floating point (the largest input coordinate is {0})"
    )]
    Overflow(f64),
    /// The construction found its own faces inconsistent. The decisions are
    /// exact, so this needs coordinates whose products underflow (nonzero
    /// coordinates below about 10⁻⁹⁰ of the largest), or a dual whose
    /// rounded planes do not close.
    #[error("the hull could not be built consistently: {0} (coordinates too small beside others?)")]
    Numerical(&'static str),
    /// The kernel refused the built polygons; a bug in this module.
    #[error("internal error building the hull (please report): {0}")]
    Build(#[from] BuildError),
}

/// The convex hull of `mesh`'s vertices as a new mesh (see the module
/// documentation): a convex polyhedron whose faces are the hull's planar
/// facets and whose vertices are its corners.
pub fn convex_hull(mesh: &Mesh) -> Result<Mesh, HullError> {
    let points = positions(mesh)?;
    let faces = hull_polygons(&points)?;
    build(points, &faces)
}

/// TopMod's dual convex hull of `mesh`'s vertices as a new mesh (see the
/// module documentation): one face per vertex of the convex hull, on the
/// plane through it perpendicular to its normal.
pub fn dual_convex_hull(mesh: &Mesh) -> Result<Mesh, HullError> {
    let input = positions(mesh)?;
    // Every construction on the points scaled by 2^-k (exact), the
    // result's corners scaled back.
    let (points, k) = scaled(&input);
    let hull = hull_polygons(&points)?;
    // Each hull corner's normal: the integral of the unit normal over its
    // normal cone, the spherical polygon of the unit normals of its faces
    // in order around it.
    let units: Vec<DVec3> = hull
        .iter()
        .map(|face| {
            let ps: Vec<DVec3> = face.iter().map(|&i| points[i as usize]).collect();
            newell(&ps).normalize_or_zero()
        })
        .collect();
    let mut corners = Vec::new();
    let mut normal = Vec::new();
    for (v, around) in around_vertices(&hull, points.len())? {
        let cone: Vec<DVec3> = around.iter().map(|&f| units[f as usize]).collect();
        // The plane must touch the hull at p_v only: every neighbour of v
        // behind it. A cone too thin for the integral to round to a
        // direction inside it (faces meeting within rounding of flat)
        // takes the sum of its unit normals, also inside it.
        let p = points[v as usize];
        let neighbours: Vec<DVec3> = around
            .iter()
            .filter_map(|&f| {
                let face = &hull[f as usize];
                let k = face.iter().position(|&x| x == v)?;
                Some(points[face[(k + 1) % face.len()] as usize])
            })
            .collect();
        let touches_once = |n: DVec3| {
            n.normalize_or_zero() != DVec3::ZERO && neighbours.iter().all(|&w| n.dot(w - p) < 0.0)
        };
        let n = cone_normal(&cone);
        let n = if touches_once(n) {
            n
        } else {
            cone.iter().sum()
        };
        corners.push(v);
        normal.push(n);
    }
    let centre = corners.iter().map(|&i| points[i as usize]).sum::<DVec3>() / corners.len() as f64;
    // Each plane n̂·(x − p) ≤ 0 as the polar point n̂ / (n̂·(p − centre)),
    // seen from the centre; the planes' intersection is the polar of the
    // polar points' hull.
    let mut polar = Vec::with_capacity(corners.len());
    for (&i, n) in corners.iter().zip(&normal) {
        let n = n.normalize_or_zero();
        let d = n.dot(points[i as usize] - centre);
        let q = n / d;
        if n == DVec3::ZERO
            || d.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || !q.is_finite()
        {
            return Err(HullError::Numerical("a hull vertex has no outward normal"));
        }
        polar.push(q);
    }
    let facets = hull_polygons(&polar)?;
    // A vertex of the result per facet of the polar hull: its plane
    // a·y = 1 is the point centre + a.
    let mut vertices = Vec::with_capacity(facets.len());
    for facet in &facets {
        let ps: Vec<DVec3> = facet.iter().map(|&i| polar[i as usize]).collect();
        let n = newell(&ps);
        let mid = ps.iter().sum::<DVec3>() / ps.len() as f64;
        let a = n / n.dot(mid);
        if !a.is_finite() {
            return Err(HullError::Numerical(
                "a facet of the polar hull has no plane",
            ));
        }
        let corner = times_pow2(centre + a, k);
        if !corner.is_finite() {
            return Err(HullError::Overflow(largest(&input)));
        }
        vertices.push(corner);
    }
    let faces: Vec<Vec<u32>> = around_vertices(&facets, polar.len())?
        .into_iter()
        .map(|(_, face)| face)
        .collect();
    build(vertices, &faces)
}

/// The mesh's vertex positions in slot order (finite: the kernel refuses
/// any other).
fn positions(mesh: &Mesh) -> Result<Vec<DVec3>, HullError> {
    mesh.vertices()
        .map(|v| mesh.position(v))
        .collect::<Result<_, _>>()
        .map_err(|_| HullError::Numerical("a vertex the mesh lists is stale"))
}

/// `∫ n dA` over the spherical polygon with corners `cone` (unit vectors,
/// counter-clockwise seen from outside the sphere): half the sum over its
/// arcs of the arc's angle times the unit normal of its great circle
/// (`½ ∮ x × dx`). Repeated corners (coplanar faces) add nothing, so it
/// does not depend on how a flat face is cut into triangles, and it moves
/// continuously with the faces' normals.
fn cone_normal(cone: &[DVec3]) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for (k, &u) in cone.iter().enumerate() {
        let w = cone[(k + 1) % cone.len()];
        let m = u.cross(w);
        let angle = m.length().atan2(u.dot(w));
        sum += m.normalize_or_zero() * angle;
    }
    sum / 2.0
}

/// Twice the area vector of a polygon (Newell's method), about its first
/// corner (so a polygon far from the origin loses no digits to it).
fn newell(ps: &[DVec3]) -> DVec3 {
    let Some(&o) = ps.first() else {
        return DVec3::ZERO;
    };
    let mut n = DVec3::ZERO;
    for (k, p) in ps.iter().enumerate() {
        n += (*p - o).cross(ps[(k + 1) % ps.len()] - o);
    }
    n
}

/// The facets around each point that is a corner of `facets` (a convex
/// polyhedron's faces, counter-clockwise seen from outside), in order
/// counter-clockwise seen from outside. For the polar hull each facet
/// stands for the result's vertex of the same number, and the lists are
/// the result's faces. The walk below goes clockwise seen from outside (the facets are
/// counter-clockwise), so each face is reversed to face outward: read off
/// the combinatorics, never from the constructed coordinates.
fn around_vertices(facets: &[Vec<u32>], points: usize) -> Result<Vec<(u32, Vec<u32>)>, HullError> {
    let open = HullError::Numerical("the polar hull is open");
    // The facets' corners in one flat list: corner c holds point
    // `point[c]`, lies in facet `facet[c]` and is followed by `next[c]`.
    let corners: usize = facets.iter().map(Vec::len).sum();
    if corners >= u32::MAX as usize {
        return Err(HullError::Build(BuildError::TooLarge(corners)));
    }
    let mut point = Vec::with_capacity(corners);
    let mut facet = Vec::with_capacity(corners);
    let mut next = Vec::with_capacity(corners);
    for (f, corners_of) in facets.iter().enumerate() {
        let start = point.len() as u32;
        let n = corners_of.len() as u32;
        for (k, &a) in corners_of.iter().enumerate() {
            point.push(a);
            facet.push(f as u32);
            next.push(start + (k as u32 + 1) % n);
        }
    }
    // The corner starting the reverse of each corner's edge: one sort by
    // the undirected edge puts the two sides of each edge side by side,
    // instead of a search per step of the walks below (which cost a
    // quarter of the dual hull's time on 100,000 points).
    let mut sides: Vec<(u64, u32)> = (0..corners as u32)
        .map(|c| {
            let (a, b) = (point[c as usize], point[next[c as usize] as usize]);
            ((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), c)
        })
        .collect();
    sides.sort_unstable();
    let mut twin = vec![u32::MAX; corners];
    for pair in sides.chunks(2) {
        let [(k1, c1), (k2, c2)] = *pair else {
            return Err(open);
        };
        // Each edge once each way: two convex facets meet along it.
        if k1 != k2 || point[c1 as usize] == point[c2 as usize] {
            return Err(open);
        }
        twin[c1 as usize] = c2;
        twin[c2 as usize] = c1;
    }
    let mut first = vec![u32::MAX; points];
    for (c, &a) in point.iter().enumerate() {
        if first[a as usize] == u32::MAX {
            first[a as usize] = c as u32;
        }
    }
    let mut faces = Vec::with_capacity(points);
    for (v, &c0) in first.iter().enumerate() {
        // A polar point that is no corner of the polar hull (its plane
        // only touches the others where they meet, after rounding) bounds
        // no face.
        if c0 == u32::MAX {
            continue;
        }
        let mut face = Vec::new();
        let mut c = c0;
        loop {
            face.push(facet[c as usize]);
            // Across edge v → b lies the facet holding b → v; its corner
            // after that edge's start is v again, starting the next edge.
            c = next[twin[c as usize] as usize];
            if c == c0 {
                break;
            }
            if point[c as usize] != v as u32 || face.len() > facets.len() {
                return Err(HullError::Numerical("the polar hull is inconsistent"));
            }
        }
        face.reverse();
        faces.push((v as u32, face));
    }
    Ok(faces)
}

/// The kernel mesh of `faces` over `points` (unused points left out):
/// each corner's edge is the corner starting the reverse edge.
fn build(points: Vec<DVec3>, faces: &[Vec<u32>]) -> Result<Mesh, HullError> {
    let mut raw = RawMesh::default();
    let mut number = vec![u32::MAX; points.len()];
    raw.face_offsets.push(0);
    for face in faces {
        for &i in face {
            if number[i as usize] == u32::MAX {
                number[i as usize] = raw.positions.len() as u32;
                raw.positions.push(points[i as usize]);
            }
            raw.face_vertices.push(number[i as usize]);
        }
        raw.face_offsets.push(raw.face_vertices.len() as u32);
    }
    // Directed edges (from, to) with their corners, sorted, so the reverse
    // of each is found by binary search.
    let mut directed: Vec<(u64, u32)> = Vec::with_capacity(raw.face_vertices.len());
    for f in 0..raw.face_count() {
        let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
        for c in lo..hi {
            let d = if c + 1 == hi { lo } else { c + 1 };
            let (a, b) = (raw.face_vertices[c as usize], raw.face_vertices[d as usize]);
            directed.push(((u64::from(a) << 32) | u64::from(b), c));
        }
    }
    directed.sort_unstable();
    for &(key, c) in &directed {
        let (a, b) = (key >> 32, key & 0xffff_ffff);
        if a < b {
            let reverse = (b << 32) | a;
            let k = directed
                .binary_search_by_key(&reverse, |&(x, _)| x)
                .map_err(|_| HullError::Numerical("an edge of the hull has one side"))?;
            raw.edges.push([c, directed[k].1]);
        }
    }
    Ok(Mesh::from_raw(&raw)?)
}

/// The largest coordinate magnitude of `points` (0 for none).
fn largest(points: &[DVec3]) -> f64 {
    points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max)
}

/// `p · 2^k`, exact unless the result overflows or falls into the
/// subnormal range (done in steps so that no factor overflows).
fn times_pow2(mut p: DVec3, mut k: i32) -> DVec3 {
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        p *= 2f64.powi(step);
        k -= step;
    }
    p
}

/// `points` scaled by `2^-k`, with `k` chosen so the largest coordinate
/// magnitude lies in `[1, 2)` (all points zero: unscaled), and `k`.
/// Scaling by a power of two changes no exact decision (barring
/// underflow) and keeps the predicates' products in range.
fn scaled(points: &[DVec3]) -> (Vec<DVec3>, i32) {
    let m = largest(points);
    if m == 0.0 || !m.is_finite() {
        return (points.to_vec(), 0);
    }
    // The binary exponent of m, subnormals included: log2 rounds, so
    // it is corrected by exact scalings.
    let mut k = m.log2().floor() as i32;
    let at = |k: i32| times_pow2(DVec3::splat(m), -k).x;
    while at(k) >= 2.0 {
        k += 1;
    }
    while at(k) < 1.0 {
        k -= 1;
    }
    let out = points.iter().map(|&p| times_pow2(p, -k)).collect();
    (out, k)
}

/// The convex hull of `points` as convex polygons (point numbers,
/// counter-clockwise seen from outside), coplanar triangles merged and
/// only the corners kept. Decided exactly on the points scaled by a power
/// of two.
fn hull_polygons(points: &[DVec3]) -> Result<Vec<Vec<u32>>, HullError> {
    let (p, _) = scaled(points);
    let mut hull = Quickhull::start(&p)?;
    hull.run()?;
    hull.polygons()
}

/// Whether `a`, `b` and `c` lie on one line, exactly (all three
/// coordinate projections collinear).
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let xy = |p: DVec3| glam::DVec2::new(p.x, p.y);
    let yz = |p: DVec3| glam::DVec2::new(p.y, p.z);
    let zx = |p: DVec3| glam::DVec2::new(p.z, p.x);
    [xy, yz, zx]
        .iter()
        .all(|f| orient2d(f(a), f(b), f(c)) == Sign::Zero)
}

/// One triangle of the hull: corners counter-clockwise seen from outside,
/// `next[i]` the triangle across the edge from corner `i` to corner
/// `i + 1`, a floating-point normal (only to choose the farthest point),
/// and the points outside it that no earlier triangle took.
struct Tri {
    v: [u32; 3],
    next: [u32; 3],
    normal: DVec3,
    outside: Vec<u32>,
    alive: bool,
}

struct Quickhull<'a> {
    p: &'a [DVec3],
    tris: Vec<Tri>,
}

impl<'a> Quickhull<'a> {
    /// A tetrahedron of four points off one plane (extreme ones where the
    /// floating-point guess is right, checked exactly), every other point
    /// given to the first of its faces it lies outside of.
    fn start(p: &'a [DVec3]) -> Result<Quickhull<'a>, HullError> {
        let flat = || HullError::Flat { points: p.len() };
        if p.len() < 4 {
            return Err(flat());
        }
        // The farthest pair among the extremes along the axes.
        let mut ext = Vec::with_capacity(6);
        for axis in 0..3 {
            let key = |i: &usize| p[*i][axis];
            let by = |a: &usize, b: &usize| key(a).total_cmp(&key(b));
            ext.extend((0..p.len()).min_by(by));
            ext.extend((0..p.len()).max_by(by));
        }
        let mut pair = (0, 0, -1.0);
        for &a in &ext {
            for &b in &ext {
                let d = p[a].distance(p[b]);
                if d > pair.2 {
                    pair = (a, b, d);
                }
            }
        }
        let a = pair.0;
        // Any point other than p[a] (the extremes differ unless all
        // points are one).
        let b = if p[pair.1] != p[a] {
            pair.1
        } else {
            (0..p.len()).find(|&i| p[i] != p[a]).ok_or_else(flat)?
        };
        let line = (p[b] - p[a]).normalize_or_zero();
        let off_line = |i: usize| {
            let d = p[i] - p[a];
            (d - line * d.dot(line)).length()
        };
        let guess = (0..p.len())
            .max_by(|&x, &y| off_line(x).total_cmp(&off_line(y)))
            .ok_or_else(flat)?;
        let c = if !collinear(p[a], p[b], p[guess]) {
            guess
        } else {
            (0..p.len())
                .find(|&i| !collinear(p[a], p[b], p[i]))
                .ok_or_else(flat)?
        };
        let n = (p[b] - p[a]).cross(p[c] - p[a]);
        let off_plane = |i: usize| n.dot(p[i] - p[a]).abs();
        let guess = (0..p.len())
            .max_by(|&x, &y| off_plane(x).total_cmp(&off_plane(y)))
            .ok_or_else(flat)?;
        let side = |i: usize| orient3d(p[a], p[b], p[c], p[i]);
        let d = if side(guess) != Sign::Zero {
            guess
        } else {
            (0..p.len())
                .find(|&i| side(i) != Sign::Zero)
                .ok_or_else(flat)?
        };
        // Orient a, b, c counter-clockwise seen from outside (d behind,
        // orient3d positive).
        let (b, c) = if side(d) == Sign::Negative {
            (c, b)
        } else {
            (b, c)
        };
        let [a, b, c, d] = [a as u32, b as u32, c as u32, d as u32];
        let mut hull = Quickhull {
            p,
            tris: Vec::new(),
        };
        // Faces 0..4 and their neighbours across each edge.
        hull.push([a, b, c], [1, 2, 3]);
        hull.push([a, d, b], [3, 2, 0]);
        hull.push([b, d, c], [1, 3, 0]);
        hull.push([c, d, a], [2, 1, 0]);
        let taken = [a, b, c, d];
        for i in 0..p.len() as u32 {
            if !taken.contains(&i) {
                hull.give(i, 0..4);
            }
        }
        Ok(hull)
    }

    /// Adds a triangle with its floating-point normal.
    fn push(&mut self, v: [u32; 3], next: [u32; 3]) -> u32 {
        let [a, b, c] = v.map(|i| self.p[i as usize]);
        self.tris.push(Tri {
            v,
            next,
            normal: (b - a).cross(c - a),
            outside: Vec::new(),
            alive: true,
        });
        (self.tris.len() - 1) as u32
    }

    /// Exactly where point `i` lies from triangle `t`'s plane: `Negative`
    /// outside (in front of its counter-clockwise side), `Zero` on it.
    fn side(&self, t: usize, i: u32) -> Sign {
        let [a, b, c] = self.tris[t].v.map(|k| self.p[k as usize]);
        orient3d(a, b, c, self.p[i as usize])
    }

    /// Whether point `i` lies strictly outside triangle `t`, exactly.
    fn outside(&self, t: usize, i: u32) -> bool {
        self.side(t, i) == Sign::Negative
    }

    /// About how far point `i` lies outside triangle `t` (in units of the
    /// triangle's doubled area; only to pick the farthest point).
    fn height(&self, t: usize, i: u32) -> f64 {
        let a = self.p[self.tris[t].v[0] as usize];
        self.tris[t].normal.dot(self.p[i as usize] - a)
    }

    /// Gives point `i` to the first triangle of `among` it lies outside
    /// of; a point outside none is inside the hull or on it, and dropped.
    fn give(&mut self, i: u32, among: std::ops::Range<usize>) {
        if let Some(t) = among.into_iter().find(|&t| self.outside(t, i)) {
            self.tris[t].outside.push(i);
        }
    }

    /// Adds the farthest outside point of some triangle until none is left.
    fn run(&mut self) -> Result<(), HullError> {
        let mut work: Vec<usize> = (0..4).collect();
        let limit = 8 * self.p.len() + 64;
        let mut steps = 0;
        while let Some(t) = work.pop() {
            if !self.tris[t].alive || self.tris[t].outside.is_empty() {
                continue;
            }
            steps += 1;
            if steps > limit {
                return Err(HullError::Numerical("quickhull does not end"));
            }
            let apex = self.tris[t]
                .outside
                .iter()
                .copied()
                .max_by(|&x, &y| self.height(t, x).total_cmp(&self.height(t, y)))
                .ok_or(HullError::Numerical("an empty outside set"))?;
            let first_new = self.tris.len();
            self.add(t, apex)?;
            work.extend(first_new..self.tris.len());
        }
        Ok(())
    }

    /// Replaces the triangles `apex` sees (starting from `t`) by a cone
    /// of triangles from `apex` to their horizon.
    fn add(&mut self, t: usize, apex: u32) -> Result<(), HullError> {
        // The visible triangles, and the horizon: the edges a → b of
        // visible triangles whose neighbour `g` is not visible.
        let mut visible = vec![t];
        let mut seen: HashMap<usize, bool> = HashMap::from([(t, true)]);
        let mut horizon: Vec<(u32, u32, usize)> = Vec::new();
        let mut k = 0;
        while k < visible.len() {
            let u = visible[k];
            k += 1;
            for e in 0..3 {
                let g = self.tris[u].next[e] as usize;
                let sees = match seen.get(&g) {
                    Some(&s) => s,
                    None => {
                        let s = self.outside(g, apex);
                        seen.insert(g, s);
                        if s {
                            visible.push(g);
                        }
                        s
                    }
                };
                if !sees {
                    let v = self.tris[u].v;
                    horizon.push((v[e], v[(e + 1) % 3], g));
                }
            }
        }
        // The cone: triangle (a, b, apex) for each horizon edge a → b.
        let base = self.tris.len();
        let mut by_start: HashMap<u32, u32> = HashMap::with_capacity(horizon.len());
        for (j, &(a, _, _)) in horizon.iter().enumerate() {
            if by_start.insert(a, (base + j) as u32).is_some() {
                return Err(HullError::Numerical("the horizon is not one loop"));
            }
        }
        let broken = HullError::Numerical("the horizon is not one loop");
        for &(a, b, g) in &horizon {
            let after = *by_start.get(&b).ok_or(broken.clone())?;
            // Across b → apex lies the cone triangle starting at b; across
            // apex → a the one ending at a, linked below.
            let me = self.push([a, b, apex], [g as u32, after, u32::MAX]);
            let gt = &mut self.tris[g];
            let e = (0..3)
                .find(|&e| gt.v[e] == b && gt.v[(e + 1) % 3] == a)
                .ok_or(broken.clone())?;
            gt.next[e] = me;
        }
        for j in 0..horizon.len() {
            let b_tri = self.tris[base + j].next[1] as usize;
            self.tris[b_tri].next[2] = (base + j) as u32;
        }
        // The visible triangles go; their points move to the cone.
        let mut orphans = Vec::new();
        for &u in &visible {
            self.tris[u].alive = false;
            orphans.append(&mut self.tris[u].outside);
        }
        let end = self.tris.len();
        for i in orphans {
            if i != apex {
                self.give(i, base..end);
            }
        }
        Ok(())
    }

    /// The live triangles merged into convex polygons: triangles whose
    /// neighbour's far corner lies exactly on their plane are one face; each face is the loop of its boundary edges, without
    /// the points that are corners of fewer than three faces (in the
    /// middle of a straight edge).
    fn polygons(&self) -> Result<Vec<Vec<u32>>, HullError> {
        let group = self.coplanar_groups()?;
        let n = self.tris.len();
        let crossing = |t: usize, e: usize| group[self.tris[t].next[e] as usize] != group[t];
        // Every face's boundary passes once through each of its corners,
        // so the faces at a point are the boundary edges leaving it.
        let mut faces_at = vec![0u32; self.p.len()];
        for t in (0..n).filter(|&t| self.tris[t].alive) {
            for e in (0..3).filter(|&e| crossing(t, e)) {
                faces_at[self.tris[t].v[e] as usize] += 1;
            }
        }
        let mut done = vec![false; 3 * n];
        let mut walked = vec![false; n];
        let mut out = Vec::new();
        for t0 in (0..n).filter(|&t| self.tris[t].alive) {
            for e0 in 0..3 {
                if done[3 * t0 + e0] || !crossing(t0, e0) {
                    continue;
                }
                // A second loop for one face: it is not a disk.
                if std::mem::replace(&mut walked[group[t0]], true) {
                    return Err(HullError::Numerical("a merged face is not a disk"));
                }
                let mut face = Vec::new();
                let (mut t, mut e) = (t0, e0);
                loop {
                    done[3 * t + e] = true;
                    let a = self.tris[t].v[e];
                    if faces_at[a as usize] >= 3 {
                        face.push(a);
                    }
                    (t, e) = self.next_boundary_edge(t, e, &group)?;
                    if (t, e) == (t0, e0) {
                        break;
                    }
                    if done[3 * t + e] {
                        return Err(HullError::Numerical("a face's boundary is not a loop"));
                    }
                }
                if face.len() < 3 {
                    return Err(HullError::Numerical(
                        "a merged face has fewer than 3 corners",
                    ));
                }
                out.push(face);
            }
        }
        Ok(out)
    }

    /// The coplanar groups of the live triangles, as one triangle number
    /// per group (by union-find over the edges).
    fn coplanar_groups(&self) -> Result<Vec<usize>, HullError> {
        let n = self.tris.len();
        let mut group: Vec<usize> = (0..n).collect();
        fn find(group: &mut [usize], mut x: usize) -> usize {
            while group[x] != x {
                group[x] = group[group[x]];
                x = group[x];
            }
            x
        }
        for t in (0..n).filter(|&t| self.tris[t].alive) {
            for e in 0..3 {
                let g = self.tris[t].next[e] as usize;
                let (a, b) = (self.tris[t].v[e], self.tris[t].v[(e + 1) % 3]);
                let Some(&far) = self.tris[g].v.iter().find(|&&x| x != a && x != b) else {
                    return Err(HullError::Numerical("two triangles share three corners"));
                };
                if self.side(t, far) == Sign::Zero {
                    let (x, y) = (find(&mut group, t), find(&mut group, g));
                    group[x] = y;
                }
            }
        }
        for t in 0..n {
            group[t] = find(&mut group, t);
        }
        Ok(group)
    }

    /// The boundary edge of `t`'s group after edge `e` of triangle `t`
    /// (from `a` to `b`): the first edge leaving `b` that crosses into
    /// another group, turning about `b` inside the group.
    fn next_boundary_edge(
        &self,
        t: usize,
        e: usize,
        group: &[usize],
    ) -> Result<(usize, usize), HullError> {
        let (mut t, mut e) = (t, (e + 1) % 3);
        for _ in 0..self.tris.len() {
            let g = self.tris[t].next[e] as usize;
            if group[g] != group[t] {
                return Ok((t, e));
            }
            // Inside the group: g holds the reverse edge, ending at b;
            // its edge leaving b is the one after.
            let b = self.tris[t].v[e];
            let k = (0..3)
                .find(|&k| {
                    self.tris[g].v[(k + 1) % 3] == b
                        && self.tris[g].v[k] == self.tris[t].v[(e + 1) % 3]
                })
                .ok_or(HullError::Numerical("neighbouring triangles disagree"))?;
            (t, e) = (g, (k + 1) % 3);
        }
        Err(HullError::Numerical("a face's boundary is not a loop"))
    }
}

#[cfg(test)]
mod tests;
