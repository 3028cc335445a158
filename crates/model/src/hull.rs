//! # Convex hulls (TopMod's conical tools, issue 18)
//!
//! [`convex_hull`] replaces a mesh by the convex hull of its vertices, and
//! [`dual_convex_hull`] by TopMod's *dual convex hull*: the solid bounded
//! by the tangent planes at the hull's vertices.
//!
//! ## Convex hull
//! Quickhull over the vertex positions (point-spheres included), with a
//! tolerance of `10⁻¹¹` of the points' bounding-box diagonal: a point
//! that close to a face is on it. Coplanar triangles are merged into one
//! convex polygon and points in the middle of a face or of a straight
//! edge are dropped, so every vertex of the result is a corner of at
//! least three faces: a convex polyhedron of genus 0, `V − E + F = 2`,
//! with `F = 2V − 4` when every face is a triangle (points in general
//! position). The hull of a cube's vertices is the cube, `8/12/6`.
//!
//! ## Dual convex hull
//! TopMod's `createDualConvexHull` cuts the points' bounding box by the
//! plane through each hull vertex perpendicular to its normal, which
//! leaves the box untouched where the planes only graze it (a cube came
//! back a cube). Here the box is gone: the result is the intersection of
//! the half-spaces `n̂_v · (x − p_v) ≤ 0` over the hull's vertices `v`,
//! `n_v = Σ_(f ∋ v) A_f n̂_f / k_f` (`A_f`, `n̂_f` and `k_f` the area,
//! unit normal and number of corners of each hull face at `v`).
//!
//! That `n_v` lies strictly inside the cone of normals at `v`, so each
//! plane touches the hull at `p_v` only and bounds one face of the
//! result; and `Σ_v n_v = Σ_f A_f n̂_f = 0` with every weight positive,
//! so the half-spaces bound a polytope. The result is the polar dual of
//! the hull seen from its vertex centroid: one face per hull vertex,
//! `F* = V`, and where three planes meet at each vertex (points in
//! general position) `V* = 2F* − 4`, `E* = 3F* − 6`. On a regular
//! polyhedron the normals point at its vertices and the result is its
//! dual: a cube gives an octahedron `6/12/8`, a dodecahedron an
//! icosahedron `12/30/20`. It contains the hull, touching it at the
//! hull's vertices.
//!
//! Both run in `O(n log n)` expected time for `n` points and never change
//! their input. Fewer than four points off one plane are refused with
//! [`HullError::Flat`].

use std::collections::HashMap;

use holey_dlfl::{BuildError, DVec3, Mesh, RawMesh};

/// Why a hull was refused. The input is unchanged (these functions never
/// change it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HullError {
    /// The points do not span space: all on one plane, a line or a point
    /// (or there are fewer than four).
    #[error(
        "the {points} vertex position(s) lie on one plane, so they bound no solid; a hull needs four points off one plane"
    )]
    Flat {
        /// How many points there were.
        points: usize,
    },
    /// The coordinates are so large that the hull's planes overflow.
    #[error(
        "the coordinates are too large to compute a hull with (the box of the points is {0} across)"
    )]
    Overflow(f64),
    /// Rounding made the hull's faces inconsistent (points within the
    /// tolerance of each other in ways the construction cannot order).
    #[error("the hull could not be built consistently: {0} (points too close to each other?)")]
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
    let points = positions(mesh)?;
    let hull = hull_polygons(&points)?;
    // The hull's vertices and their normals n_v = Σ A_f n̂_f / k_f.
    let mut normal: HashMap<u32, DVec3> = HashMap::new();
    for face in &hull {
        let ps: Vec<DVec3> = face.iter().map(|&i| points[i as usize]).collect();
        let share = newell(&ps) / (2.0 * face.len() as f64);
        for &i in face {
            *normal.entry(i).or_insert(DVec3::ZERO) += share;
        }
    }
    let mut corners: Vec<u32> = normal.keys().copied().collect();
    corners.sort_unstable();
    let centre = corners.iter().map(|&i| points[i as usize]).sum::<DVec3>() / corners.len() as f64;
    // Each plane n̂·(x − p) ≤ 0 as the polar point n̂ / (n̂·(p − centre)),
    // seen from the centre; the planes' intersection is the polar of the
    // polar points' hull.
    let mut polar = Vec::with_capacity(corners.len());
    let mut units = Vec::with_capacity(corners.len());
    for &i in &corners {
        let n = normal[&i].normalize_or_zero();
        let d = n.dot(points[i as usize] - centre);
        if n == DVec3::ZERO || d.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(HullError::Numerical("a hull vertex has no outward normal"));
        }
        polar.push(n / d);
        units.push(n);
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
        vertices.push(centre + a);
    }
    let faces = around_vertices(&facets, polar.len(), &vertices, &units)?;
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

/// Twice the area vector of a polygon (Newell's method).
fn newell(ps: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (k, p) in ps.iter().enumerate() {
        n += p.cross(ps[(k + 1) % ps.len()]);
    }
    n
}

/// The faces around each polar point: the facets of the polar hull
/// containing it, in order, each facet standing for the result's vertex
/// of the same number. Faces are turned to face along `units`.
fn around_vertices(
    facets: &[Vec<u32>],
    points: usize,
    vertices: &[DVec3],
    units: &[DVec3],
) -> Result<Vec<Vec<u32>>, HullError> {
    // The facet holding each directed edge a → b, sorted by (a, b).
    let mut holding: Vec<(u64, u32)> = Vec::new();
    let mut first: Vec<Option<(u32, u32)>> = vec![None; points];
    for (f, facet) in facets.iter().enumerate() {
        for (k, &a) in facet.iter().enumerate() {
            let b = facet[(k + 1) % facet.len()];
            holding.push(((u64::from(a) << 32) | u64::from(b), f as u32));
            first[a as usize].get_or_insert((f as u32, b));
        }
    }
    holding.sort_unstable();
    let holder = |a: u32, b: u32| {
        let key = (u64::from(a) << 32) | u64::from(b);
        holding
            .binary_search_by_key(&key, |&(x, _)| x)
            .map(|k| holding[k].1)
            .map_err(|_| HullError::Numerical("the polar hull is open"))
    };
    let mut faces = Vec::with_capacity(points);
    for (v, start) in first.iter().enumerate() {
        // A polar point that is no corner of the polar hull (its plane
        // only grazes the others within the tolerance) bounds no face.
        let Some(&(f0, b0)) = start.as_ref() else {
            continue;
        };
        let v = v as u32;
        let mut face = Vec::new();
        let (mut f, mut b) = (f0, b0);
        loop {
            face.push(f);
            // Across edge v → b lies the facet holding b → v; its edge
            // leaving v comes next.
            let g = holder(b, v)?;
            let facet = &facets[g as usize];
            let k = facet
                .iter()
                .position(|&x| x == v)
                .ok_or(HullError::Numerical("the polar hull is inconsistent"))?;
            f = g;
            b = facet[(k + 1) % facet.len()];
            if f == f0 || face.len() > facets.len() {
                break;
            }
        }
        let ps: Vec<DVec3> = face.iter().map(|&i| vertices[i as usize]).collect();
        if newell(&ps).dot(units[v as usize]) < 0.0 {
            face.reverse();
        }
        faces.push(face);
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

/// The tolerance of a point set: a point this close to a plane is on it.
/// Refused when the products of coordinates a plane needs overflow.
fn tolerance(points: &[DVec3]) -> Result<f64, HullError> {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let diagonal = (hi - lo).length();
    if points.len() >= 4 && !(diagonal * diagonal).is_finite() {
        return Err(HullError::Overflow(diagonal));
    }
    Ok(1e-11 * diagonal)
}

/// The convex hull of `points` as convex polygons (point numbers,
/// counter-clockwise seen from outside), coplanar triangles merged and
/// only the corners kept.
fn hull_polygons(points: &[DVec3]) -> Result<Vec<Vec<u32>>, HullError> {
    let eps = tolerance(points)?;
    let mut hull = Quickhull::start(points, eps)?;
    hull.run()?;
    hull.polygons()
}

/// One triangle of the hull: corners counter-clockwise seen from outside,
/// `next[i]` the triangle across the edge from corner `i` to corner
/// `i + 1`, the plane `normal · x = offset`, and the points outside it
/// that no earlier triangle took.
struct Tri {
    v: [u32; 3],
    next: [u32; 3],
    normal: DVec3,
    offset: f64,
    outside: Vec<u32>,
    alive: bool,
}

struct Quickhull<'a> {
    p: &'a [DVec3],
    eps: f64,
    tris: Vec<Tri>,
}

impl<'a> Quickhull<'a> {
    /// A tetrahedron of four extreme points, every other point given to
    /// the first of its faces it lies outside of.
    fn start(p: &'a [DVec3], eps: f64) -> Result<Quickhull<'a>, HullError> {
        let flat = HullError::Flat { points: p.len() };
        if p.len() < 4 || eps.is_nan() {
            return Err(flat);
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
        let (a, b) = (pair.0, pair.1);
        let line = (p[b] - p[a]).normalize_or_zero();
        let off_line = |i: usize| {
            let d = p[i] - p[a];
            (d - line * d.dot(line)).length()
        };
        let c = (0..p.len())
            .max_by(|&x, &y| off_line(x).total_cmp(&off_line(y)))
            .ok_or(HullError::Flat { points: p.len() })?;
        if pair.2 <= eps || off_line(c) <= eps {
            return Err(flat);
        }
        let n = (p[b] - p[a]).cross(p[c] - p[a]).normalize_or_zero();
        let off_plane = |i: usize| n.dot(p[i] - p[a]);
        let d = (0..p.len())
            .max_by(|&x, &y| off_plane(x).abs().total_cmp(&off_plane(y).abs()))
            .ok_or(HullError::Flat { points: p.len() })?;
        if off_plane(d).abs() <= eps {
            return Err(flat);
        }
        // Orient a, b, c counter-clockwise seen from outside (d behind).
        let (b, c) = if off_plane(d) > 0.0 { (c, b) } else { (b, c) };
        let [a, b, c, d] = [a as u32, b as u32, c as u32, d as u32];
        let mut hull = Quickhull {
            p,
            eps,
            tris: Vec::new(),
        };
        // Faces 0..4 and their neighbours across each edge.
        hull.push([a, b, c], [1, 2, 3]);
        hull.push([a, d, b], [3, 2, 0]);
        hull.push([b, d, c], [1, 3, 0]);
        hull.push([c, d, a], [2, 1, 0]);
        for t in 0..4 {
            let [x, y, z] = hull.tris[t].v;
            for (k, w) in [(0, [x, y]), (1, [y, z]), (2, [z, x])] {
                let g = hull.tris[t].next[k] as usize;
                if !hull.tris[g].v.contains(&w[0]) || !hull.tris[g].v.contains(&w[1]) {
                    return Err(HullError::Numerical(
                        "the first tetrahedron is inconsistent",
                    ));
                }
            }
        }
        let taken = [a, b, c, d];
        for i in 0..p.len() as u32 {
            if !taken.contains(&i) {
                hull.give(i, 0..4);
            }
        }
        Ok(hull)
    }

    /// Adds a triangle with its plane.
    fn push(&mut self, v: [u32; 3], next: [u32; 3]) -> u32 {
        let [a, b, c] = v.map(|i| self.p[i as usize]);
        let normal = (b - a).cross(c - a).normalize_or_zero();
        self.tris.push(Tri {
            v,
            next,
            normal,
            offset: normal.dot(a),
            outside: Vec::new(),
            alive: true,
        });
        (self.tris.len() - 1) as u32
    }

    /// How far point `i` lies outside triangle `t`.
    fn height(&self, t: usize, i: u32) -> f64 {
        self.tris[t].normal.dot(self.p[i as usize]) - self.tris[t].offset
    }

    /// Gives point `i` to the first triangle of `among` it lies outside
    /// of; a point outside none is inside the hull and dropped.
    fn give(&mut self, i: u32, among: std::ops::Range<usize>) {
        if let Some(t) = among.into_iter().find(|&t| self.height(t, i) > self.eps) {
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
                        let s = self.height(g, apex) > self.eps;
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
    /// neighbour's far corner lies on their plane (within the tolerance)
    /// are one face; each face is the loop of its boundary edges, without
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
                if self.height(t, far).abs() <= self.eps {
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
