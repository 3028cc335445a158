//! Combinatorial measures: edges, boundary, fans, loops and components.
//!
//! Everything here is linear in the number of corners plus vertex slots,
//! apart from sorting each vertex's few link entries: corners are bucketed
//! by vertex with a counting sort and each vertex is then handled on its
//! own, so no hash map is involved.

use std::collections::BTreeMap;

use serde::Serialize;

use super::soup::Soup;
use crate::union_find::UnionFind;

/// Marks an unreferenced vertex in a component labelling.
pub(crate) const NONE: u32 = u32::MAX;

/// Stands for the missing neighbours of a 1-gon's corner. Never a vertex:
/// [`Soup`] treats index `u32::MAX` as out of range.
const POINT: u32 = u32::MAX;

/// Combinatorial counts of one connected component (or of a whole mesh),
/// with the definitions of the [module documentation](super).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Counts {
    /// Referenced vertices (V).
    pub vertices: usize,
    /// Distinct undirected edges, self-loops included (E).
    pub edges: usize,
    /// Valid faces, of every size (F).
    pub faces: usize,
    /// Edges with exactly one side.
    pub boundary_edges: usize,
    /// Connected pieces of the boundary-edge graph (b).
    pub boundary_loops: usize,
    /// Edges with three or more sides.
    pub nonmanifold_edges: usize,
    /// Vertices with more than one fan.
    pub nonmanifold_vertices: usize,
    /// Two-sided edges whose two sides run the same way.
    pub misoriented_edges: usize,
    /// Faces that use some vertex more than once.
    pub degenerate_faces: usize,
    /// Edges whose two ends are the same vertex.
    pub self_loops: usize,
}

impl Counts {
    fn add(&mut self, o: &Counts) {
        self.vertices += o.vertices;
        self.edges += o.edges;
        self.faces += o.faces;
        self.boundary_edges += o.boundary_edges;
        self.boundary_loops += o.boundary_loops;
        self.nonmanifold_edges += o.nonmanifold_edges;
        self.nonmanifold_vertices += o.nonmanifold_vertices;
        self.misoriented_edges += o.misoriented_edges;
        self.degenerate_faces += o.degenerate_faces;
        self.self_loops += o.self_loops;
    }

    pub(crate) fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }

    pub(crate) fn manifold(&self) -> bool {
        self.nonmanifold_edges == 0 && self.nonmanifold_vertices == 0 && self.degenerate_faces == 0
    }

    pub(crate) fn oriented(&self) -> bool {
        self.misoriented_edges == 0
    }

    /// Σ (2 − χᵢ − bᵢ)/2 over `components` components that these counts
    /// add up; `None` unless manifold and oriented. Each (2 − χᵢ − bᵢ) is
    /// then twice a genus, so the sum can be taken at once; an odd total
    /// (impossible for such surfaces) also gives `None`, so that nonsense
    /// is never printed.
    pub(crate) fn genus(&self, components: usize) -> Option<i64> {
        let twice = 2 * components as i64 - self.euler() - self.boundary_loops as i64;
        (self.manifold() && self.oriented() && twice % 2 == 0).then_some(twice / 2)
    }

    /// The surface these counts describe, made of `components` components.
    pub(crate) fn surface(&self, components: usize) -> Surface {
        Surface {
            closed: self.boundary_edges == 0,
            manifold: self.manifold(),
            oriented: self.oriented(),
            euler: self.euler(),
            genus: self.genus(components),
        }
    }
}

/// What a mesh's (or a component's) [`Counts`] say about its surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Surface {
    /// No boundary edge.
    pub closed: bool,
    /// No non-manifold edge or vertex and no degenerate face.
    pub manifold: bool,
    /// No misoriented edge.
    pub oriented: bool,
    /// χ = V − E + F.
    pub euler: i64,
    /// Σ over components of (2 − χᵢ − bᵢ)/2; `None` unless manifold and
    /// oriented.
    pub genus: Option<i64>,
}

impl Surface {
    /// Closed, manifold and oriented: a surface whose signed volume means
    /// something.
    pub fn bounds_volume(&self) -> bool {
        self.closed && self.manifold && self.oriented
    }
}

/// The combinatorial analysis of a [`Soup`].
pub(crate) struct Topology {
    /// Component of every vertex slot, [`NONE`] where unreferenced.
    /// Components are numbered by their smallest vertex index.
    pub component: Vec<u32>,
    pub component_count: usize,
    /// Per component in that order if asked for, else empty.
    pub components: Vec<Counts>,
    /// Sums over all components.
    pub total: Counts,
    pub two_gons: usize,
    pub point_spheres: usize,
    pub face_sizes: BTreeMap<usize, usize>,
}

/// Counts everything, per component if `per_component` (a soup can have a
/// component per face, so the breakdown is only made when wanted).
pub(crate) fn topology(soup: &Soup, vertex_slots: usize, per_component: bool) -> Topology {
    let nv = vertex_slots;
    let (vert, next, prev) = (&soup.vert, &soup.next, &soup.prev);

    // One pass over the faces: components (vertices joined through faces),
    // corners per vertex, face sizes, and faces that repeat a vertex.
    let mut vuf = UnionFind::new(nv);
    let mut corner_start = vec![0u32; nv + 1];
    let mut small_sizes = [0usize; 32];
    let mut face_sizes = BTreeMap::new();
    let mut degenerate: Vec<u32> = Vec::new();
    let mut stamp: Vec<u32> = Vec::new();
    for (f, face) in soup.faces().enumerate() {
        let first = face[0];
        for &v in face {
            corner_start[v as usize + 1] += 1;
            vuf.union(first, v);
        }
        match small_sizes.get_mut(face.len()) {
            Some(n) => *n += 1,
            None => *face_sizes.entry(face.len()).or_insert(0) += 1,
        }
        if repeats_vertex(face, f as u32, &mut stamp, nv) {
            degenerate.push(first);
        }
    }
    drop(stamp);
    for (size, &n) in small_sizes.iter().enumerate() {
        if n > 0 {
            face_sizes.insert(size, n);
        }
    }

    // Roots are the smallest member, so scanning upwards meets every
    // component's root before its other vertices.
    let mut component = vec![NONE; nv];
    let mut component_count = 0u32;
    for v in 0..nv {
        if corner_start[v + 1] == 0 {
            continue;
        }
        let r = vuf.find(v as u32) as usize;
        if r == v {
            component[v] = component_count;
            component_count += 1;
        } else {
            component[v] = component[r];
        }
    }
    drop(vuf);
    // Counts go to one bin per component, or all to a single bin.
    let bin_count = if per_component {
        component_count as usize
    } else {
        1
    };
    let mut bins = vec![Counts::default(); bin_count];
    let bin = |v: u32| match per_component {
        true => component[v as usize] as usize,
        false => 0,
    };
    for v in 0..nv as u32 {
        if component[v as usize] != NONE {
            bins[bin(v)].vertices += 1;
        }
    }
    for face in soup.faces() {
        bins[bin(face[0])].faces += 1;
    }
    for &v in &degenerate {
        bins[bin(v)].degenerate_faces += 1;
    }

    // For the corners at each vertex, bucketed by a counting sort: the
    // vertices after and before it in its face ([`POINT`] for a 1-gon's
    // corner, which has no side). Copying them here, rather than corner
    // ids, lets the pass below read each vertex's corners contiguously.
    for v in 0..nv {
        corner_start[v + 1] += corner_start[v];
    }
    let mut vertex_corners = vec![[0u32; 2]; soup.corner_count()];
    {
        let mut fill = corner_start.clone();
        for (c, &v) in vert.iter().enumerate() {
            let (n, p) = (next[c] as usize, prev[c] as usize);
            let slot = &mut fill[v as usize];
            vertex_corners[*slot as usize] = if n == c {
                [POINT; 2]
            } else {
                [vert[n], vert[p]]
            };
            *slot += 1;
        }
    }

    // Every vertex on its own: the sides at v are the outgoing side of each
    // corner at v and the incoming side of each corner at v, so all sides of
    // every edge {v, w} are seen here, together with the corners that join
    // into fans. Each edge is classified at its smaller end. Without the
    // per-component breakdown the vertices go in parallel runs, each with
    // its own sums (the server counts a million-triangle sculpture after
    // every stroke).
    let corners_at =
        |v: usize| &vertex_corners[corner_start[v] as usize..corner_start[v + 1] as usize];
    let mut boundary: Vec<(u32, u32)> = Vec::new();
    if per_component {
        let mut scratch = VertexScratch::default();
        for v in 0..nv as u32 {
            let corners = corners_at(v as usize);
            if !corners.is_empty() {
                scratch.count(v, corners, &mut bins[bin(v)], &mut boundary);
            }
        }
    } else {
        use rayon::prelude::*;
        let runs: Vec<(Counts, Vec<(u32, u32)>)> = (0..nv as u32)
            .into_par_iter()
            .with_min_len(crate::PARALLEL_RUN)
            .fold(
                || (VertexScratch::default(), Counts::default(), Vec::new()),
                |(mut scratch, mut counts, mut boundary), v| {
                    scratch.count(v, corners_at(v as usize), &mut counts, &mut boundary);
                    (scratch, counts, boundary)
                },
            )
            .map(|(_, counts, boundary)| (counts, boundary))
            .collect();
        for (counts, b) in runs {
            bins[0].add(&counts);
            boundary.extend(b);
        }
    }
    drop(vertex_corners);
    drop(corner_start);

    // Boundary loops: the connected pieces of the graph of boundary edges,
    // each counted once, at its root.
    if !boundary.is_empty() {
        let mut buf = UnionFind::new(nv);
        for &(v, w) in &boundary {
            buf.union(v, w);
        }
        let mut counted = vec![false; nv];
        for &(v, _) in &boundary {
            let r = buf.find(v);
            if !std::mem::replace(&mut counted[r as usize], true) {
                bins[bin(r)].boundary_loops += 1;
            }
        }
    }

    let mut total = Counts::default();
    for c in &bins {
        total.add(c);
    }
    Topology {
        component,
        component_count: component_count as usize,
        components: if per_component { bins } else { Vec::new() },
        total,
        two_gons: face_sizes.get(&2).copied().unwrap_or(0),
        point_spheres: face_sizes.get(&1).copied().unwrap_or(0),
        face_sizes,
    }
}

/// The buffers of [`VertexScratch::count`], reused from vertex to vertex.
#[derive(Default)]
struct VertexScratch {
    link: Vec<u64>,
    local: UnionFind,
}

impl VertexScratch {
    /// Adds to `counts` what vertex `v` (whose corners give, each, the
    /// vertices after and before it in its face) says: the edges at
    /// their smaller end, with their sides (boundary ones also to
    /// `boundary`), and whether the corners at `v` make more than one
    /// fan.
    fn count(
        &mut self,
        v: u32,
        corners: &[[u32; 2]],
        counts: &mut Counts,
        boundary: &mut Vec<(u32, u32)>,
    ) {
        if corners.is_empty() {
            return;
        }
        let (link, local) = (&mut self.link, &mut self.local);
        // Entries (w << 32 | k << 1 | out) for the corner numbered k here.
        link.clear();
        for (k, &[after, before]) in corners.iter().enumerate() {
            if after != POINT {
                let k = (k as u64) << 1;
                link.push((after as u64) << 32 | k | 1);
                link.push((before as u64) << 32 | k);
            }
        }
        link.sort_unstable();
        local.reset(corners.len());
        for group in link.chunk_by(|a, b| a >> 32 == b >> 32) {
            let corner = |e: u64| e as u32 >> 1;
            let k0 = corner(group[0]);
            for &e in &group[1..] {
                local.union(k0, corner(e));
            }
            let w = (group[0] >> 32) as u32;
            let outgoing = group.iter().filter(|&&e| e & 1 == 1).count();
            let sides = match w.cmp(&v) {
                // Counted at w.
                std::cmp::Ordering::Less => continue,
                // A self-loop's every side is seen twice here, once leaving
                // and once arriving.
                std::cmp::Ordering::Equal => {
                    counts.self_loops += 1;
                    outgoing
                }
                std::cmp::Ordering::Greater => group.len(),
            };
            counts.edges += 1;
            match sides {
                1 => {
                    counts.boundary_edges += 1;
                    boundary.push((v, w));
                }
                2 => {
                    if w != v && outgoing != 1 {
                        counts.misoriented_edges += 1;
                    }
                }
                _ => counts.nonmanifold_edges += 1,
            }
        }
        // Fans are the classes of corners here.
        let fans = (0..corners.len() as u32)
            .filter(|&k| local.is_root(k))
            .count();
        if fans > 1 {
            counts.nonmanifold_vertices += 1;
        }
    }
}

/// Whether `face` (number `f`) uses some vertex twice. Small faces are
/// compared pairwise; larger ones mark vertices in `stamp` (made on first
/// need, `nv` long) with their face number, which keeps this linear.
fn repeats_vertex(face: &[u32], f: u32, stamp: &mut Vec<u32>, nv: usize) -> bool {
    if face.len() <= 8 {
        return (1..face.len()).any(|i| face[..i].contains(&face[i]));
    }
    if stamp.is_empty() {
        stamp.resize(nv, u32::MAX);
    }
    face.iter()
        .any(|&v| std::mem::replace(&mut stamp[v as usize], f) == f)
}
