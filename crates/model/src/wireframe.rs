//! # Wireframe and column modeling (TopMod, issue 18)
//!
//! Both turn every edge of a mesh into a tube and every vertex into a
//! joint, so the result is the surface of a thickened edge graph: a
//! closed 2-manifold whose genus, per connected component of the graph,
//! is its cycle rank `E − V + 1`; for the whole mesh
//!
//! ```text
//! genus = E − V + C      (C = components of the edge graph)
//! ```
//!
//! For a closed genus-`g` surface (one component) that is `F − 1 + 2g`:
//! every face becomes a window. Hole faces count as faces (the boundary
//! loop becomes a window like any other) and point-spheres are copied.
//! Both build a new mesh from the input's connectivity in one pass and
//! leave the input untouched; the result is validated by the kernel.
//!
//! ## Wireframe ([`wireframe`])
//! TopMod's wireframe, the "rind-like" construction: every face is
//! shrunk into a smaller copy of itself (each corner moved into the face
//! along its bisector so that the copy's edges lie `thickness` inside the
//! face's), and the gaps between neighbouring copies become the tubes'
//! walls; the copies become windows lined by *jambs* down to an inner
//! layer `thickness` below (a hole face's copy is grown instead, so the
//! tubes along a boundary straddle it). Each corner `c` of the input gives an outer
//! vertex `o_c` and an inner `i_c`; faces:
//! - per edge, an outer strip `(o_(next a), o_a, o_(next b), o_b)` and
//!   the inner strip below it (`a`, `b` the edge's two corners);
//! - per corner, a jamb `(o_c, o_(next c), i_(next c), i_c)`;
//! - per vertex of valence `k ≥ 3`, an outer and an inner `k`-gon joint.
//!
//! A vertex of valence 2 (a grid's corner, a polygon's vertex on a
//! straight run) would make two-gon joints, flat between the same two
//! points: there the two strips share one edge instead, outer and inner.
//! At valence 1 (the tip of a dangling edge) the joint would be a
//! monogon closed by a loop: the edge's strips are triangles there. So
//! every face of the result has at least three sides and no edge is a
//! loop.
//!
//! Each corner's copy is the point `thickness` inside both of its edges
//! as seen in its face's plane (so a corner bending out of a non-planar
//! face is offset by its in-plane angle), but moves at most a third of
//! either edge at it, and the inner layer is lowered (to an eighth of
//! the vertex's shortest edge) where it would turn over at a crease: in
//! slivers and at short edges the tubes thin out instead of folding. A
//! thickness that no corner has room for is refused.
//!
//! Counts, with `C = 2E` corners, `V₁` and `V₂` the vertices of valence
//! 1 and 2 and `V₃` those of valence 3 or more: `V' = 2C = 4E`,
//! `E' = 5C − 2V₁ − 2V₂ = 10E − 2V₁ − 2V₂`, `F' = 4E + 2V₃` (plus any
//! point-spheres, copied: one vertex and one face each). So
//! `χ' = V' − E' + F' = 2(V₁ + V₂ + V₃) − 2E`, twice the edge graph's,
//! which is the genus above. Tubes have four sides.
//!
//! ## Columns ([`columns`])
//! An `n`-sided column (a prism of `n` quads) along every edge, ending at
//! `n`-gon *ports* near the vertices; a vertex of valence `k ≥ 3` joins
//! its ports with `k` side faces (between rotation-neighbouring ports,
//! each made of half of each port's rim) and two `k`-gon caps (top and
//! bottom); valence 2 needs only the two side faces and valence 1 closes
//! its port with one `n`-gon. Counts: `V' = 2nE`,
//! `E' = 3nE + Σ_(k≥3) 2k + 2·#(k = 2)`,
//! `F' = nE + Σ_(k≥3) (k + 2) + 2·#(k = 2) + #(k = 1)`.

use std::collections::HashMap;

use holey_dlfl::{BuildError, CornerId, DVec3, EdgeId, FaceId, Mesh, RawMesh, VertexId};

use crate::polygon;

/// Why a wireframe or column mesh was refused. The input is unchanged
/// (these functions never change it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WireframeError {
    /// The thickness (or radius) is NaN, infinite, zero or negative.
    #[error("the thickness must be positive and finite, got {0}")]
    InvalidThickness(f64),
    /// A column needs at least three sides.
    #[error("a column needs at least 3 sides, got {0}")]
    TooFewSides(usize),
    /// A face has zero area, so the wireframe cannot tell which way is
    /// inside it.
    #[error("face {0} has zero area, so its corners cannot be moved into it")]
    DegenerateFace(FaceId),
    /// Two consecutive corners of a face coincide, or a corner's edges
    /// fold back on each other, so the corner has no inward direction.
    #[error(
        "corner {corner} of face {face} has no inward direction (its edges coincide or fold back)"
    )]
    DegenerateCorner {
        /// The face.
        face: FaceId,
        /// The corner.
        corner: CornerId,
    },
    /// The shrunk copy of a face turns over: the thickness is too large
    /// for the face.
    #[error(
        "at thickness {thickness} the shrunk copy of face {face} turns over; use a smaller thickness"
    )]
    ThicknessTooLarge {
        /// The face.
        face: FaceId,
        /// The thickness asked for.
        thickness: f64,
    },
    /// The columns' joints at the two ends of an edge would overlap.
    #[error(
        "at radius {radius} the joints at the ends of edge {edge} overlap (the edge is too short)"
    )]
    EdgeTooShort {
        /// The edge.
        edge: EdgeId,
        /// The radius asked for.
        radius: f64,
    },
    /// Two edges at a vertex point (nearly) the same way, so their
    /// columns cannot be separated.
    #[error("two edges at vertex {0} point the same way; their columns would coincide")]
    CoincidentEdges(VertexId),
    /// A vertex's surrounding faces have no common normal, so the inner
    /// layer has no direction.
    #[error("vertex {0} has no normal: the normals of its faces cancel out")]
    NoNormal(VertexId),
    /// The result would need more entities than the kernel's indices hold.
    #[error("the result would have about {0} corners, too many for the kernel")]
    TooLarge(u64),
    /// The kernel refused the built arrays; a bug in this module.
    #[error("internal error building the result (please report): {0}")]
    Build(#[from] BuildError),
    /// A kernel accessor failed on the input (a bug: ids come from the mesh).
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// The input's corners with dense numbers and the links both builders use.
struct Corners {
    ids: Vec<CornerId>,
    dense: HashMap<CornerId, u32>,
    next: Vec<u32>,
    prev: Vec<u32>,
    /// Rotation successor around the vertex.
    rot: Vec<u32>,
    /// The other corner of the edge leaving this one (`u32::MAX`: none).
    partner: Vec<u32>,
    vertex: Vec<VertexId>,
    face: Vec<FaceId>,
}

impl Corners {
    fn new(mesh: &Mesh) -> Result<Corners, WireframeError> {
        let ids: Vec<CornerId> = mesh.corners().collect();
        let dense: HashMap<CornerId, u32> = ids
            .iter()
            .enumerate()
            .map(|(i, &c)| (c, i as u32))
            .collect();
        let n = ids.len();
        let mut out = Corners {
            next: Vec::with_capacity(n),
            prev: Vec::with_capacity(n),
            rot: Vec::with_capacity(n),
            partner: Vec::with_capacity(n),
            vertex: Vec::with_capacity(n),
            face: Vec::with_capacity(n),
            ids,
            dense,
        };
        for k in 0..n {
            let c = out.ids[k];
            let d = |x: CornerId| out.dense.get(&x).copied().unwrap_or(u32::MAX);
            out.next.push(d(mesh.corner_next(c)?));
            out.prev.push(d(mesh.corner_prev(c)?));
            out.rot.push(d(mesh.corner_rotation_next(c)?));
            let partner = match mesh.corner_edge(c)? {
                Some(e) => {
                    let [a, b] = mesh.edge_corners(e)?;
                    d(if a == c { b } else { a })
                }
                None => u32::MAX,
            };
            out.partner.push(partner);
            out.vertex.push(mesh.corner_vertex(c)?);
            out.face.push(mesh.corner_face(c)?);
        }
        Ok(out)
    }

    fn len(&self) -> usize {
        self.ids.len()
    }
}

/// Faces whose corners each name the edge they start by a key; corners
/// with equal keys become the two sides of one edge.
#[derive(Default)]
struct Builder {
    raw: RawMesh,
    keys: Vec<u64>,
}

impl Builder {
    fn vertex(&mut self, p: DVec3) -> u32 {
        self.raw.positions.push(p);
        (self.raw.positions.len() - 1) as u32
    }

    /// Adds a face: corner `k` at `vertices[k]`, starting edge `keys[k]`
    /// (`u64::MAX` for the edgeless corner of a point-sphere).
    fn face(&mut self, corners: &[(u32, u64)]) {
        if self.raw.face_offsets.is_empty() {
            self.raw.face_offsets.push(0);
        }
        for &(v, key) in corners {
            self.raw.face_vertices.push(v);
            self.keys.push(key);
        }
        self.raw
            .face_offsets
            .push(self.raw.face_vertices.len() as u32);
    }

    /// Adds a face without the corners that start a loop (an edge from a
    /// vertex back to itself, listed as two equal consecutive vertices).
    fn face_without_loops(&mut self, corners: &[(u32, u64)]) {
        let kept: Vec<(u32, u64)> = (0..corners.len())
            .filter(|&j| corners[j].0 != corners[(j + 1) % corners.len()].0)
            .map(|j| corners[j])
            .collect();
        self.face(&kept);
    }

    fn finish(mut self) -> Result<Mesh, WireframeError> {
        let mut first: HashMap<u64, u32> = HashMap::with_capacity(self.keys.len() / 2);
        for (corner, &key) in self.keys.iter().enumerate() {
            if key == u64::MAX {
                continue;
            }
            match first.remove(&key) {
                Some(other) => self.raw.edges.push([other, corner as u32]),
                None => {
                    first.insert(key, corner as u32);
                }
            }
        }
        if let Some(key) = first.keys().next() {
            return Err(WireframeError::Kernel(holey_dlfl::Error::Invalid(format!(
                "internal: edge key {key:#x} has one side only"
            ))));
        }
        Ok(Mesh::from_raw(&self.raw)?)
    }
}

/// An edge key: a kind and a number below 2^56.
fn key(kind: u8, n: u64) -> u64 {
    (u64::from(kind) << 56) | n
}

/// The unit sum of the unit normals of the surface (non-hole) faces
/// around `v`; `None` when they cancel or there are none.
fn vertex_normal(mesh: &Mesh, v: VertexId) -> Result<Option<DVec3>, WireframeError> {
    let mut sum = DVec3::ZERO;
    for c in mesh.vertex_corners(v)? {
        let f = mesh.corner_face(c)?;
        if mesh.is_hole(f)? {
            continue;
        }
        if let Some(fr) = polygon::frame(&mesh.face_positions(f)?) {
            sum += fr.normal;
        }
    }
    let len = sum.length();
    Ok((len > 1e-9 && len.is_finite()).then(|| sum / len))
}

fn check_size(corners: u64) -> Result<(), WireframeError> {
    if corners >= u64::from(u32::MAX) / 2 {
        Err(WireframeError::TooLarge(corners))
    } else {
        Ok(())
    }
}

/// The wireframe of `mesh` with tubes `thickness` wide (see the module
/// documentation): genus `E − V + C`. The input is not changed.
pub fn wireframe(mesh: &Mesh, thickness: f64) -> Result<Mesh, WireframeError> {
    if !(thickness.is_finite() && thickness > 0.0) {
        return Err(WireframeError::InvalidThickness(thickness));
    }
    let cs = Corners::new(mesh)?;
    check_size(cs.len() as u64 * 12)?;
    let (outer, inner) = wireframe_points(mesh, &cs, thickness)?;
    let mut b = Builder::default();
    let n = cs.len();
    let mut o = vec![u32::MAX; n];
    let mut i = vec![u32::MAX; n];
    for c in 0..n {
        if cs.partner[c] == u32::MAX {
            // A point-sphere: copied as it is.
            let v = b.vertex(outer[c]);
            b.face(&[(v, u64::MAX)]);
            continue;
        }
        o[c] = b.vertex(outer[c]);
        i[c] = b.vertex(inner[c]);
    }
    let rings = joint_rings(&cs);
    // The joint edge from corner c to its rotation successor is keyed by
    // `joint[c]`; around a vertex of valence 2 both of its corners name
    // one edge, so the two strips there meet at that edge instead of
    // across a two-gon joint.
    let mut joint: Vec<u64> = (0..n as u64).collect();
    for ring in &rings {
        if let [x, y] = ring[..] {
            joint[y] = joint[x];
        }
    }
    let (ko, ki, kv, kjo, kji) = (0u8, 1u8, 2u8, 3u8, 4u8);
    let k = |kind: u8, c: usize| key(kind, c as u64);
    let kj = |kind: u8, c: usize| key(kind, joint[c]);
    for c in 0..n {
        if cs.partner[c] == u32::MAX {
            continue;
        }
        let a = cs.partner[c] as usize;
        let nc = cs.next[c] as usize;
        // The jamb under the shrunk copy's edge from corner c.
        b.face(&[
            (o[c], k(ko, c)),
            (o[nc], k(kv, nc)),
            (i[nc], k(ki, c)),
            (i[c], k(kv, c)),
        ]);
        // The strips of the edge leaving c, made once, from its first side.
        // At a vertex of valence 1 (the tip of a dangling edge) the joint
        // edge would be a loop closing a monogon: the strip is a triangle.
        if c < a {
            let na = cs.next[a] as usize;
            b.face_without_loops(&[
                (o[nc], k(ko, c)),
                (o[c], kj(kjo, c)),
                (o[na], k(ko, a)),
                (o[a], kj(kjo, a)),
            ]);
            b.face_without_loops(&[
                (i[c], k(ki, c)),
                (i[nc], kj(kji, a)),
                (i[a], k(ki, a)),
                (i[na], kj(kji, c)),
            ]);
        }
    }
    // The joints of valence 3 and more: outer against the rotation
    // (counter-clockwise seen from outside), inner along it.
    for ring in rings.iter().filter(|r| r.len() >= 3) {
        let outer_joint: Vec<(u32, u64)> = (0..ring.len())
            .rev()
            .map(|j| {
                let prev = ring[(j + ring.len() - 1) % ring.len()];
                (o[ring[j]], k(kjo, prev))
            })
            .collect();
        // The corner at o_(c_j) starts the edge to o_(c_(j−1)), keyed by
        // c_(j−1); listed in reverse rotation order.
        b.face(&outer_joint);
        let inner_joint: Vec<(u32, u64)> = ring.iter().map(|&c| (i[c], k(kji, c))).collect();
        b.face(&inner_joint);
    }
    b.finish()
}

/// The corners around every vertex with edges, in rotation order.
fn joint_rings(cs: &Corners) -> Vec<Vec<usize>> {
    let n = cs.len();
    let mut rings = Vec::new();
    let mut done = vec![false; n];
    for start in 0..n {
        if done[start] || cs.partner[start] == u32::MAX {
            continue;
        }
        let mut ring = Vec::new();
        let mut c = start;
        loop {
            done[c] = true;
            ring.push(c);
            c = cs.rot[c] as usize;
            if c == start || ring.len() > n {
                break;
            }
        }
        rings.push(ring);
    }
    rings
}

/// Outer and inner positions of every corner (point-spheres: the vertex).
fn wireframe_points(
    mesh: &Mesh,
    cs: &Corners,
    w: f64,
) -> Result<(Vec<DVec3>, Vec<DVec3>), WireframeError> {
    let n = cs.len();
    let mut normals: HashMap<FaceId, DVec3> = HashMap::new();
    let mut vnormals: HashMap<VertexId, DVec3> = HashMap::new();
    let mut holes = std::collections::HashSet::new();
    for f in mesh.faces() {
        if mesh.is_hole(f)? {
            holes.insert(f);
        }
    }
    let pos = |c: usize| mesh.position(cs.vertex[c]);
    let mut outer = Vec::with_capacity(n);
    // The vertex normal at every corner, and whether the corner's copy was
    // held back from the full thickness.
    let mut down = Vec::with_capacity(n);
    let mut held = Vec::with_capacity(n);
    for c in 0..n {
        let p = pos(c)?;
        let mut was_held = false;
        if cs.partner[c] == u32::MAX {
            outer.push(p);
            down.push(DVec3::ZERO);
            held.push(false);
            continue;
        }
        let f = cs.face[c];
        let nf = match normals.get(&f) {
            Some(&x) => x,
            None => {
                let fr = polygon::frame(&mesh.face_positions(f)?)
                    .ok_or(WireframeError::DegenerateFace(f))?;
                normals.insert(f, fr.normal);
                fr.normal
            }
        };
        let degenerate = WireframeError::DegenerateCorner {
            face: f,
            corner: cs.ids[c],
        };
        let (pn, pp) = (pos(cs.next[c] as usize)?, pos(cs.prev[c] as usize)?);
        let e1 = (pn - p).normalize_or_zero();
        let e2 = (pp - p).normalize_or_zero();
        if e1 == DVec3::ZERO || e2 == DVec3::ZERO {
            return Err(degenerate);
        }
        let o = if cs.vertex[cs.next[c] as usize] == cs.vertex[cs.prev[c] as usize] || pn == pp {
            // The tip of a dangling edge: the face wraps around it, so the
            // copy goes round the tip, beyond it.
            p - e1 * w
        } else {
            // Where the face is narrower than the tubes (a sliver, a
            // short edge beside a sharp corner) the copy's corner moves
            // at most a third of either edge at it, so the copy of every
            // edge keeps at least a third of its length and never turns
            // over: the tubes thin out there instead.
            let q = miter(nf, e1, e2, w).ok_or(degenerate)?;
            let reach = p.distance(pn).min(p.distance(pp)) / 3.0;
            let len = q.length();
            was_held = len > reach;
            p + if was_held { q * (reach / len) } else { q }
        };
        // A hole face is the boundary loop seen from outside the surface:
        // its copy grows instead of shrinking, so the tubes along the
        // boundary straddle it rather than fold back over the surface.
        let o = if holes.contains(&f) { p * 2.0 - o } else { o };
        let v = cs.vertex[c];
        let nv = match vnormals.get(&v) {
            Some(&x) => x,
            None => {
                let x = vertex_normal(mesh, v)?.unwrap_or(nf);
                vnormals.insert(v, x);
                x
            }
        };
        outer.push(o);
        down.push(nv);
        held.push(was_held);
    }
    let inner = inner_layer(mesh, cs, w, &outer, &down, &mut held)?;
    // Held back everywhere: no corner of the mesh has room for the
    // thickness asked for, so the result would not have it anywhere.
    if let Some(c) = (0..n).find(|&c| cs.partner[c] != u32::MAX)
        && (0..n).all(|c| cs.partner[c] == u32::MAX || held[c])
    {
        return Err(WireframeError::ThicknessTooLarge {
            face: cs.face[c],
            thickness: w,
        });
    }
    // The shrunk copy of every face (grown, for a hole) keeps the
    // direction of its edges by construction; the inner layer, `thickness`
    // below it along the vertex normals, must keep them too (a thickness
    // past the surface's curvature turns it over).
    for c in 0..n {
        if cs.partner[c] == u32::MAX {
            continue;
        }
        let nc = cs.next[c] as usize;
        let along = pos(nc)? - pos(c)?;
        let dot = (outer[nc] - outer[c]).dot(along);
        let dot_inner = (inner[nc] - inner[c]).dot(along);
        if !(dot > 0.0 && dot_inner > 0.0 && outer[c].is_finite() && inner[c].is_finite()) {
            return Err(WireframeError::ThicknessTooLarge {
                face: cs.face[c],
                thickness: w,
            });
        }
    }
    Ok((outer, inner))
}

/// The inner layer: every corner's copy moved down its vertex normal
/// (`down`) by the thickness `w`, except at vertices where that would
/// turn an edge of the inner layer over against the outer one (short
/// edges at a crease whose normals part). There the depth is lowered to
/// `min(w, ℓ/8)`, `ℓ` the vertex's shortest edge, at both ends of each
/// such edge until none is left: with both ends lowered an edge's inner
/// copy keeps at least a quarter of its outer copy's length along it
/// (the outer copy keeps a third of the edge, the two depths take at
/// most a quarter), so this ends after lowering each vertex at most once.
/// The corners of lowered vertices are marked in `held`.
fn inner_layer(
    mesh: &Mesh,
    cs: &Corners,
    w: f64,
    outer: &[DVec3],
    down: &[DVec3],
    held: &mut [bool],
) -> Result<Vec<DVec3>, WireframeError> {
    let n = cs.len();
    let pos = |c: usize| mesh.position(cs.vertex[c]);
    let mut depth: HashMap<VertexId, f64> = HashMap::new();
    let inner_at = |depth: &HashMap<VertexId, f64>, c: usize| {
        outer[c] - down[c] * depth.get(&cs.vertex[c]).copied().unwrap_or(w)
    };
    let mut work: Vec<usize> = (0..n).filter(|&c| cs.partner[c] != u32::MAX).collect();
    while let Some(c) = work.pop() {
        let nc = cs.next[c] as usize;
        let along = pos(nc)? - pos(c)?;
        let outer_along = (outer[nc] - outer[c]).dot(along);
        let inner_along = (inner_at(&depth, nc) - inner_at(&depth, c)).dot(along);
        if inner_along >= outer_along / 4.0 || !inner_along.is_finite() {
            continue;
        }
        for end in [c, nc] {
            let v = cs.vertex[end];
            if depth.contains_key(&v) {
                continue;
            }
            // The corners around v: lower v and look again at both edges
            // of each of them in its face.
            let mut ring = Vec::new();
            let mut x = end;
            loop {
                ring.push(x);
                x = cs.rot[x] as usize;
                if x == end || ring.len() > n {
                    break;
                }
            }
            let mut shortest = f64::INFINITY;
            for &x in &ring {
                shortest = shortest.min(pos(cs.next[x] as usize)?.distance(pos(x)?));
            }
            depth.insert(v, w.min(shortest / 8.0));
            for &x in &ring {
                held[x] = true;
                work.push(x);
                work.push(cs.prev[x] as usize);
            }
        }
    }
    Ok((0..n).map(|c| inner_at(&depth, c)).collect())
}

/// Where the copy of a corner goes, relative to the corner: the point
/// `w` inside both of its edges, within the face's plane (unit normal
/// `n`). `e1` and `e2` are the unit directions from the corner to the
/// next and to the previous corner. Both edges are measured in that
/// plane, each by its own inward normal, so a corner that bends out of
/// a non-planar face is offset by its angle as seen in the face: the
/// miter `w (d1 + d2) / (1 + d1·d2)` has length `w / sin(θ/2)` for the
/// corner's in-plane angle `θ` (`w` at a straight corner, reflex
/// corners included) and grows without bound only as the corner closes
/// into a spike. `None` when an edge runs along the normal (no in-plane
/// direction) or the two edges fold back onto each other.
fn miter(n: DVec3, e1: DVec3, e2: DVec3, w: f64) -> Option<DVec3> {
    let d1 = n.cross(e1).try_normalize()?;
    let d2 = e2.cross(n).try_normalize()?;
    let denom = 1.0 + d1.dot(d2);
    let q = (d1 + d2) * (w / denom);
    (denom > 0.0 && q.is_finite()).then_some(q)
}

/// The parameters of [`columns`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColumnParams {
    /// Sides of every column, at least 3.
    pub sides: usize,
    /// Radius of every column (distance of its corners from the edge).
    pub radius: f64,
}

/// `n`-sided columns of radius `radius` along every edge of `mesh`, joined
/// at the vertices (see the module documentation): genus `E − V + C`.
/// The input is not changed.
///
/// Each column ends at a port centred on its edge, `a_v = r / sin(θ/2)`
/// from the vertex (`θ` the smallest angle between two edges at the
/// vertex, so neighbouring ports do not meet; `a_v = r` at valence 1);
/// refused when the two ports of an edge would overlap
/// (`a_u + a_w ≥ |e|`), or two edges at a vertex coincide.
pub fn columns(mesh: &Mesh, params: &ColumnParams) -> Result<Mesh, WireframeError> {
    let (n, r) = (params.sides, params.radius);
    if n < 3 {
        return Err(WireframeError::TooFewSides(n));
    }
    if !(r.is_finite() && r > 0.0) {
        return Err(WireframeError::InvalidThickness(r));
    }
    let cs = Corners::new(mesh)?;
    check_size((cs.len() as u64).saturating_mul(n as u64).saturating_mul(4))?;
    let ports = port_points(mesh, &cs, n, r)?;
    let mut b = Builder::default();
    // Port vertices: corner c's port is q(c, m) = base[c] + m.
    let mut base = vec![u32::MAX; cs.len()];
    for c in 0..cs.len() {
        if cs.partner[c] == u32::MAX {
            let v = b.vertex(ports[c][0]);
            b.face(&[(v, u64::MAX)]);
            continue;
        }
        base[c] = b.vertex(ports[c][0]);
        for &p in &ports[c][1..] {
            b.vertex(p);
        }
    }
    let nn = n as u64;
    let q = |c: usize, m: usize| base[c] + (m % n) as u32;
    // Port edge m of corner c joins q(c, m) and q(c, m + 1).
    let pe = |c: usize, m: usize| key(0, c as u64 * nn + (m % n) as u64);
    // Column edge m of the tube from corner c joins q(c, m) to the far port.
    let tl = |c: usize, m: usize| key(1, c as u64 * nn + (m % n) as u64);
    for c in 0..cs.len() {
        let far = cs.partner[c] as usize;
        if cs.partner[c] == u32::MAX || c > far {
            continue;
        }
        for m in 0..n {
            let back = |j: usize| (n - j % n) % n;
            b.face(&[
                (q(c, m), pe(c, m)),
                (q(c, m + 1), tl(c, m + 1)),
                (q(far, back(m + 1)), pe(far, back(m + 1))),
                (q(far, back(m)), tl(c, m)),
            ]);
        }
    }
    joints(&mut b, &cs, n, &q, &pe);
    b.finish()
}

/// The joint faces at every vertex with edges.
fn joints(
    b: &mut Builder,
    cs: &Corners,
    n: usize,
    q: &dyn Fn(usize, usize) -> u32,
    pe: &dyn Fn(usize, usize) -> u64,
) {
    let bottom = n / 2;
    for ring in joint_rings(cs) {
        let k = ring.len();
        if k == 1 {
            // Close the port: q(n−1) → … → q(0), each corner starting the
            // port edge below it.
            let cap: Vec<(u32, u64)> = (0..n)
                .rev()
                .map(|m| (q(ring[0], m), pe(ring[0], m + n - 1)))
                .collect();
            b.face(&cap);
            continue;
        }
        let top = |j: usize| key(2, if k == 2 { ring[0] } else { ring[j] } as u64);
        let low = |j: usize| key(3, if k == 2 { ring[0] } else { ring[j] } as u64);
        for j in 0..k {
            let (x, y) = (ring[j], ring[(j + 1) % k]);
            let mut side: Vec<(u32, u64)> = Vec::with_capacity(n + 2);
            // Down port x's rim facing y, from its bottom to its top…
            for m in (1..=bottom).rev() {
                side.push((q(x, m), pe(x, m - 1)));
            }
            side.push((q(x, 0), top(j)));
            // …then port y's rim facing x, from its top to its bottom.
            for m in (bottom + 1..=n).rev() {
                side.push((q(y, m), pe(y, m - 1)));
            }
            side.push((q(y, bottom), low(j)));
            b.face(&side);
        }
        if k >= 3 {
            let cap: Vec<(u32, u64)> = (0..k)
                .rev()
                .map(|j| (q(ring[(j + 1) % k], 0), top(j)))
                .collect();
            b.face(&cap);
            let floor: Vec<(u32, u64)> = (0..k).map(|j| (q(ring[j], bottom), low(j))).collect();
            b.face(&floor);
        }
    }
}

/// The `n` port points of every corner (point-spheres: the vertex).
fn port_points(
    mesh: &Mesh,
    cs: &Corners,
    n: usize,
    r: f64,
) -> Result<Vec<Vec<DVec3>>, WireframeError> {
    let len = cs.len();
    let mut dir = vec![DVec3::ZERO; len];
    let mut at: HashMap<VertexId, Vec<usize>> = HashMap::new();
    for (c, d) in dir.iter_mut().enumerate() {
        if cs.partner[c] == u32::MAX {
            continue;
        }
        let p = mesh.position(cs.vertex[c])?;
        let far = mesh.position(cs.vertex[cs.next[c] as usize])?;
        *d = (far - p).normalize_or_zero();
        if *d == DVec3::ZERO {
            return Err(WireframeError::CoincidentEdges(cs.vertex[c]));
        }
        at.entry(cs.vertex[c]).or_default().push(c);
    }
    // How far each vertex's ports sit from it.
    let mut offset: HashMap<VertexId, f64> = HashMap::new();
    for (&v, list) in &at {
        let mut a = r;
        for (i, &x) in list.iter().enumerate() {
            for &y in &list[i + 1..] {
                let angle = dir[x].angle_between(dir[y]);
                if angle.is_nan() || angle <= 1e-6 {
                    return Err(WireframeError::CoincidentEdges(v));
                }
                a = a.max(r / (angle / 2.0).sin());
            }
        }
        offset.insert(v, a);
    }
    let mut ports = Vec::with_capacity(len);
    let mut normals: HashMap<VertexId, Option<DVec3>> = HashMap::new();
    for (c, &d) in dir.iter().enumerate() {
        let v = cs.vertex[c];
        let p = mesh.position(v)?;
        if cs.partner[c] == u32::MAX {
            ports.push(vec![p]);
            continue;
        }
        let a = offset.get(&v).copied().unwrap_or(r);
        let far = cs.partner[c] as usize;
        let a_far = offset.get(&cs.vertex[far]).copied().unwrap_or(r);
        let length = mesh.position(cs.vertex[cs.next[c] as usize])?.distance(p);
        if a + a_far >= length {
            let edge = mesh
                .corner_edge(cs.ids[c])?
                .ok_or(WireframeError::CoincidentEdges(v))?;
            return Err(WireframeError::EdgeTooShort { edge, radius: r });
        }
        let nv = match normals.get(&v) {
            Some(&x) => x,
            None => {
                let x = vertex_normal(mesh, v)?;
                normals.insert(v, x);
                x
            }
        };
        let up = nv
            .map(|x| x - d * x.dot(d))
            .and_then(|x| x.try_normalize())
            .unwrap_or_else(|| d.any_orthonormal_vector());
        // Towards the next port in rotation order (clockwise seen from
        // outside), so rim 0 … n/2 faces it.
        let side = d.cross(up);
        let centre = p + d * a;
        let rim: Vec<DVec3> = (0..n)
            .map(|m| {
                let phi = std::f64::consts::TAU * m as f64 / n as f64;
                centre + (up * phi.cos() + side * phi.sin()) * r
            })
            .collect();
        ports.push(rim);
    }
    Ok(ports)
}

#[cfg(test)]
mod tests;
