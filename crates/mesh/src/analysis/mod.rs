//! Measures of an arbitrary polygon soup (what `holey info` prints).
//!
//! [`analyze`] takes any [`PolyMesh`], however broken, and never panics.
//! The definitions below reproduce the measured-properties table of the
//! shared test meshes (`shared/data/meshes/README.md`) on all 16 files.
//!
//! # Definitions
//!
//! **Valid faces.** A face is analysed only if its offsets are well formed,
//! it has at least one corner, and all its indices are below
//! `positions.len()` (and below `u32::MAX`). Other faces are counted in
//! [`MeshInfo::invalid_faces`] and otherwise ignored. "Faces" below means
//! valid faces.
//!
//! **Vertices.** A vertex is *referenced* if a face uses it; only
//! referenced vertices count as V. Vertices are identified by index, never
//! by position (see [`weld_exact`] for welding equal positions).
//!
//! **Sides and edges.** A face `(v0, v1, …, v(n−1))` with n ≥ 2 has the n
//! *sides* `vi → v(i+1 mod n)`. A 2-gon `(a, b)` thus has the sides `a → b`
//! and `b → a`, both on the edge {a, b}. A 1-gon (point sphere, as in DLFL)
//! has a corner but no side and no edge. An *edge* is an unordered pair
//! {u, v} used by at least one side; `u = v` is allowed (a *self-loop*,
//! coming from consecutive repeats such as `(a, a, b)`). E counts edges.
//!
//! **Edge classes.** By the number k of sides on an edge:
//! * k = 1: *boundary edge*. The mesh is *closed* when there is none.
//! * k = 2: an interior edge. It is *misoriented* when both sides run the
//!   same way (`u → v` twice). A self-loop has no direction, so it is never
//!   misoriented.
//! * k ≥ 3: *non-manifold edge*. (Sides, not faces, are counted, so an edge
//!   used twice by one face and once by another is non-manifold too.)
//!
//! **Fans.** A *corner* is one occurrence of a vertex in a face. Two corners
//! at the same vertex v are in the same *fan* when they are joined by a
//! chain of corners at v in which consecutive corners have a side on a
//! common edge at v (any edge, including non-manifold edges and
//! self-loops). Equivalently: the fans of v are the connected components of
//! v's link, the graph whose nodes are the edges at v and which has one arc
//! per corner at v, between the corner's incoming and outgoing edges. A
//! 1-gon's corner is a fan on its own. A *non-manifold vertex* has more than
//! one fan: two surfaces meeting at a single vertex (bowtie), or a 1-gon
//! sitting on a surface vertex. A vertex on a non-manifold edge is *not* by
//! that alone a non-manifold vertex, since the edge joins its corners into
//! one fan. (This matches the README: beetle.obj has 47 non-manifold edges
//! and no non-manifold vertex; teapot.obj has 38 non-manifold vertices.)
//!
//! **Boundary loops** are the connected pieces of the graph formed by the
//! boundary edges: two boundary edges are in the same loop when a chain of
//! boundary edges, each sharing a vertex with the next, joins them. On a
//! manifold mesh a boundary vertex has exactly two boundary edges (the
//! ends of its one open fan), so the pieces are the usual boundary cycles. Where boundaries touch at a
//! non-manifold vertex they count as one loop (a bowtie of two triangles
//! has 1 loop). That is what the shared README counts: teapot.obj has 10
//! loops; keeping the boundaries of different fans apart would give 25.
//!
//! **Degenerate faces** repeat a vertex, anywhere in the face (`(a, b, a, c)`
//! as well as `(a, a, b)`).
//!
//! **Manifold** means no non-manifold edge, no non-manifold vertex and no
//! degenerate face. **Oriented** means no misoriented edge; orientation is
//! not judged on non-manifold edges.
//!
//! **Components** are the classes of vertices joined through faces (two
//! faces sharing just a vertex are one component). Components are numbered
//! by their smallest vertex index; every edge, face, fan and loop belongs to
//! the component of its vertices.
//!
//! **Euler characteristic** χ = V − E + F, over the referenced vertices, all
//! edges (self-loops included) and all valid faces.
//!
//! **Genus** of a component with χᵢ and bᵢ boundary loops is
//! (2 − χᵢ − bᵢ)/2. The mesh's genus is the sum over components, given only
//! when the mesh is manifold and oriented.
//!
//! **Geometry.** Polygons are fan-triangulated from their first corner
//! (`(v0, vk, vk+1)`); 1-gons and 2-gons have no area. The bounding box is
//! over referenced vertices with finite coordinates; area sums the fan
//! triangles whose corners are all finite. The volume is the signed volume
//! Σ p0·(p1 × p2)/6 over fan triangles (positive for outward-facing
//! counter-clockwise faces), given only when the mesh is closed, manifold
//! and oriented and all its referenced positions are finite.

mod geometry;
mod soup;
mod topology;
mod weld;

#[cfg(test)]
mod tests;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::PolyMesh;
pub use topology::{Counts, Surface};
pub use weld::{WeldError, Welded, weld_by_distance, weld_exact};

/// Measures of a whole mesh. See the [module documentation](self) for the
/// exact definitions. The fields are meaningful for any polygon mesh, so
/// the same struct can be filled from a DLFL mesh (where self-loops,
/// 2-gons and point spheres are legal and manifold).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshInfo {
    /// Referenced vertices (V).
    pub vertices: usize,
    /// Vertex slots that no valid face refers to.
    pub unreferenced_vertices: usize,
    /// Distinct undirected edges {u, v}, self-loops {u, u} included (E).
    pub edges: usize,
    /// Valid faces (F), of every size.
    pub faces: usize,
    /// Faces left out of the analysis: malformed offsets, no corner, or an
    /// index out of range.
    pub invalid_faces: usize,
    /// Connected components (vertices joined through faces).
    pub components: usize,
    /// Edges with exactly one side.
    pub boundary_edges: usize,
    /// Connected pieces of the boundary-edge graph.
    pub boundary_loops: usize,
    /// Edges with three or more sides.
    pub nonmanifold_edges: usize,
    /// Vertices with more than one fan.
    pub nonmanifold_vertices: usize,
    /// Two-sided edges whose two sides run the same way.
    pub misoriented_edges: usize,
    /// Faces that use some vertex more than once.
    pub degenerate_faces: usize,
    /// Referenced vertices with a NaN or infinite coordinate.
    pub nonfinite_vertices: usize,
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
    /// Edges whose two ends are the same vertex.
    pub self_loops: usize,
    /// Faces with exactly 2 corners.
    pub two_gons: usize,
    /// Faces with exactly 1 corner.
    pub point_spheres: usize,
    /// Face size → number of faces. Serialized with string keys
    /// (`{"3": 6598}`), as JSON object keys are strings.
    pub face_sizes: BTreeMap<usize, usize>,
    /// `[min, max]` over referenced vertices with finite coordinates.
    pub bbox: Option<[[f64; 3]; 2]>,
    /// Signed volume of the fan triangles; `None` unless closed, manifold,
    /// oriented and finite.
    pub volume: Option<f64>,
    /// Total area of the fan triangles with finite corners.
    pub area: f64,
}

/// Measures of one connected component, with the same definitions as
/// [`MeshInfo`] restricted to it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComponentInfo {
    /// This component's counts (its V, E, F, b, ...), serialized as fields
    /// of the component.
    #[serde(flatten)]
    pub counts: Counts,
    /// What the counts say of this component (its genus is
    /// (2 − χ − b)/2), serialized as fields of the component.
    #[serde(flatten)]
    pub surface: Surface,
    /// Signed volume; `None` unless this component is closed, manifold,
    /// oriented and finite.
    pub volume: Option<f64>,
    /// Total area of this component's fan triangles with finite corners.
    pub area: f64,
}

/// Analyses a soup. Linear in its size apart from sorting each vertex's
/// few edges; never panics.
pub fn analyze(mesh: &PolyMesh) -> MeshInfo {
    measure(mesh, false).0
}

/// The combinatorial part of [`analyze`] alone: the whole mesh's
/// [`Counts`], what they say of its [`Surface`], and how many components
/// it has, the same as [`analyze`] gives them; no areas, volumes or boxes
/// (a pass over every corner's position fewer: the modeller counts its
/// sculpture after every stroke).
pub fn analyze_topology(mesh: &PolyMesh) -> (Counts, Surface, usize) {
    counted(&soup::Soup::new(mesh), mesh.positions.len())
}

/// The whole soup's counts over `vertex_slots` vertices, its surface and
/// its number of components.
fn counted(soup: &soup::Soup, vertex_slots: usize) -> (Counts, Surface, usize) {
    let topo = topology::topology(soup, vertex_slots, false);
    let surface = topo.total.surface(topo.component_count);
    (topo.total, surface, topo.component_count)
}

/// [`analyze_topology`] of a triangle mesh's triangles over its
/// positions, the same as of `PolyMesh::from(mesh)` but without that copy
/// of the mesh, its corner table filled in parallel runs
/// (`soup::Soup::of_triangles`): the modeller counts its sculpture, a
/// million triangles, after every stroke.
pub fn analyze_triangle_topology(mesh: &crate::tri::TriMesh) -> (Counts, Surface, usize) {
    let n = mesh.positions.len();
    counted(&soup::Soup::of_triangles(n, &mesh.triangles), n)
}

/// Per-component measures, components numbered by smallest vertex index.
pub fn analyze_components(mesh: &PolyMesh) -> Vec<ComponentInfo> {
    measure(mesh, true).1
}

/// The genus of every component (`None` where it is not manifold and
/// oriented), components numbered by smallest vertex index.
pub fn component_genera(mesh: &PolyMesh) -> Vec<Option<i64>> {
    analyze_components(mesh)
        .iter()
        .map(|c| c.surface.genus)
        .collect()
}

/// [`analyze`] and [`analyze_components`] in one pass.
pub fn analyze_with_components(mesh: &PolyMesh) -> (MeshInfo, Vec<ComponentInfo>) {
    measure(mesh, true)
}

/// The analysis, with the per-component breakdown only if asked for (it
/// costs memory per component, and a soup has a component per face).
fn measure(mesh: &PolyMesh, per_component: bool) -> (MeshInfo, Vec<ComponentInfo>) {
    let soup = soup::Soup::new(mesh);
    let topo = topology::topology(&soup, mesh.positions.len(), per_component);
    let bins = per_component.then_some(topo.component_count);
    let geo = geometry::geometry(&soup, &mesh.positions, &topo.component, bins);

    let components: Vec<ComponentInfo> = topo
        .components
        .iter()
        .zip(geo.area.iter().zip(&geo.volume))
        .map(|(c, (&area, &volume))| {
            let surface = c.surface(1);
            ComponentInfo {
                counts: c.clone(),
                surface,
                volume: volume.filter(|_| surface.bounds_volume()),
                area,
            }
        })
        .collect();

    let t = &topo.total;
    let surface = t.surface(topo.component_count);
    let volume = geo.total_volume.filter(|_| surface.bounds_volume());
    let info = MeshInfo {
        vertices: t.vertices,
        unreferenced_vertices: mesh.positions.len() - t.vertices,
        edges: t.edges,
        faces: t.faces,
        invalid_faces: soup.invalid_faces,
        components: topo.component_count,
        boundary_edges: t.boundary_edges,
        boundary_loops: t.boundary_loops,
        nonmanifold_edges: t.nonmanifold_edges,
        nonmanifold_vertices: t.nonmanifold_vertices,
        misoriented_edges: t.misoriented_edges,
        degenerate_faces: t.degenerate_faces,
        nonfinite_vertices: geo.nonfinite_vertices,
        closed: surface.closed,
        manifold: surface.manifold,
        oriented: surface.oriented,
        euler: surface.euler,
        genus: surface.genus,
        self_loops: t.self_loops,
        two_gons: topo.two_gons,
        point_spheres: topo.point_spheres,
        face_sizes: topo.face_sizes,
        bbox: geo.bbox.map(|(lo, hi)| [lo.to_array(), hi.to_array()]),
        volume,
        area: geo.total_area,
    };
    (info, components)
}
