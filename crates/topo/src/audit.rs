//! What a surface is, measured exactly: the properties a topology change
//! must keep (issue 15's "what a stroke changes") and the tests check.
//!
//! [`SurfaceAudit::of`] counts, for any triangle list, its components,
//! boundary, non-manifold and misoriented edges, pinched vertices, exactly degenerate
//! triangles and exactly intersecting triangle pairs. [`SurfaceAudit::regressions`]
//! says in words what got worse from one audit to the next.
//!
//! Every count is exact: degeneracy is exact collinearity (all three
//! coordinate projections of the corners have orientation zero), and
//! intersections are the engine's own exact static intersections
//! ([`crate::intersect`]), which ignore the contact of triangles that
//! share a vertex or an edge.

use glam::DVec3;
use holey_geom::{Sign, orient2d};
use rayon::prelude::*;

use crate::intersect::{COORDINATE_PLANES, IntersectError, intersecting_pair_count};
use crate::mesh::{Edges, TriMesh, coincident_pairs, repeats_a_corner};
use crate::union_find::UnionFind;

/// The exact properties of a triangle mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceAudit {
    /// Triangles in the list, degenerate ones included.
    pub triangles: usize,
    /// Vertices some triangle uses.
    pub vertices: usize,
    /// Distinct edges: unordered pairs of vertex indices that a triangle side
    /// joins.
    pub edges: usize,
    /// Components joined through shared vertices.
    pub components: usize,
    /// Edges with exactly one triangle.
    pub boundary_edges: usize,
    /// Connected pieces of the boundary (joined through shared vertices):
    /// the boundary loops of a manifold. Unlike the edge count, it does
    /// not change when remeshing splits or collapses a boundary edge.
    pub boundary_loops: usize,
    /// Edges with more than two triangles.
    pub nonmanifold_edges: usize,
    /// Connected pieces of the non-manifold edges (joined through shared
    /// vertices): the non-manifold curves, however finely split.
    pub nonmanifold_curves: usize,
    /// Edges with two triangles that run along them the same way: the
    /// surface's two sides meet there back to front, and no choice of
    /// orientation makes it consistent if the count does not drop to zero
    /// by flipping whole components (a one-sided surface).
    pub misoriented_edges: usize,
    /// Vertices whose triangles form more than one fan (joined through
    /// edges at the vertex): the surface is pinched there.
    pub pinched_vertices: usize,
    /// Triangles with a repeated vertex or three collinear corners.
    pub degenerate_triangles: usize,
    /// Triangle pairs that intersect other than along a shared vertex or
    /// edge (exact).
    pub intersecting_pairs: usize,
}

impl SurfaceAudit {
    /// Audits `mesh` (its indices must be in range: [`TriMesh::check`]).
    pub fn of(mesh: &TriMesh) -> Result<SurfaceAudit, IntersectError> {
        let mut audit = SurfaceAudit::topology(mesh);
        audit.intersecting_pairs = intersecting_pair_count(mesh, usize::MAX)?;
        Ok(audit)
    }

    /// Everything but the intersections (linear time).
    ///
    /// Vertices on a rim (an edge at them has one triangle) that lie at
    /// one exact position are counted as one: a soup's copies of a corner
    /// and the two sides of an unwelded seam are one point of the surface,
    /// as the brushes and the engine's identities by position take them.
    /// So a soup that welds closed is closed here, and a frame that opens
    /// a hole in it is seen to (counted by vertex numbers, a soup is all
    /// rim, a loop per triangle, and no hole can be told from its seams).
    /// Copies with whole fans (a split pinch, sheets fused at a crossing)
    /// stay apart. A mesh without such copies costs one pass over its rim.
    pub fn topology(mesh: &TriMesh) -> SurfaceAudit {
        let edges = Edges::new(mesh);
        match welded_rims(mesh, &edges) {
            Some(welded) => SurfaceAudit::by_number(&welded, &Edges::new(&welded)),
            None => SurfaceAudit::by_number(mesh, &edges),
        }
    }

    /// [`SurfaceAudit::topology`] of `mesh` by vertex number, with its
    /// `edges`.
    fn by_number(mesh: &TriMesh, edges: &Edges) -> SurfaceAudit {
        let degree = |e: usize| edges.triangles(e).len();
        let mut used = vec![false; mesh.positions.len()];
        let mut sets = UnionFind::new(mesh.positions.len());
        for t in &mesh.triangles {
            for &v in t {
                used[v as usize] = true;
            }
            sets.union(t[0], t[1]);
            sets.union(t[0], t[2]);
        }
        let vertices = used.iter().filter(|&&u| u).count();
        let pieces = |pick: &dyn Fn(usize) -> bool| {
            let mut sets = UnionFind::new(mesh.positions.len());
            let mut on = vec![false; mesh.positions.len()];
            for e in (0..edges.len()).filter(|&e| pick(e)) {
                let [a, b] = edges.ends[e];
                on[a as usize] = true;
                on[b as usize] = true;
                sets.union(a, b);
            }
            (0..mesh.positions.len() as u32)
                .filter(|&v| on[v as usize] && sets.find(v) == v)
                .count()
        };
        let components = (0..mesh.positions.len() as u32)
            .filter(|&v| used[v as usize] && sets.find(v) == v)
            .count();
        SurfaceAudit {
            triangles: mesh.triangles.len(),
            vertices,
            edges: edges.len(),
            components,
            boundary_edges: (0..edges.len()).filter(|&e| degree(e) == 1).count(),
            boundary_loops: pieces(&|e| degree(e) == 1),
            nonmanifold_edges: (0..edges.len()).filter(|&e| degree(e) > 2).count(),
            nonmanifold_curves: pieces(&|e| degree(e) > 2),
            misoriented_edges: (0..edges.len())
                .filter(|&e| match *edges.triangles(e) {
                    [t, u] => {
                        let way = |t| edges.runs_forward(&mesh.triangles, t, e);
                        matches!((way(t), way(u)), (Some(a), Some(b)) if a == b)
                    }
                    _ => false,
                })
                .count(),
            pinched_vertices: mesh.pinched_vertices().iter().filter(|&&p| p).count(),
            degenerate_triangles: mesh
                .triangles
                .par_iter()
                .filter(|t| is_degenerate(mesh, **t))
                .count(),
            intersecting_pairs: 0,
        }
    }

    /// Euler characteristic V − E + F of the used vertices.
    pub fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.triangles as i64
    }

    /// What is worse in `after` than in `self`, in words: more boundary
    /// loops, non-manifold curves, misoriented edges, pinches, degenerate
    /// triangles or intersecting pairs. Empty when nothing is. Edge counts are not
    /// compared: remeshing splits and collapses boundary and non-manifold
    /// edges without changing what the surface is.
    pub fn regressions(&self, after: &SurfaceAudit) -> Vec<String> {
        let checks = [
            ("boundary loops", self.boundary_loops, after.boundary_loops),
            (
                "non-manifold curves",
                self.nonmanifold_curves,
                after.nonmanifold_curves,
            ),
            (
                "misoriented edges",
                self.misoriented_edges,
                after.misoriented_edges,
            ),
            (
                "pinched vertices",
                self.pinched_vertices,
                after.pinched_vertices,
            ),
            (
                "degenerate triangles",
                self.degenerate_triangles,
                after.degenerate_triangles,
            ),
            (
                "intersecting triangle pairs",
                self.intersecting_pairs,
                after.intersecting_pairs,
            ),
        ];
        checks
            .iter()
            .filter(|(_, before, now)| now > before)
            .map(|(what, before, now)| format!("{what}: {before} -> {now}"))
            .collect()
    }
}

/// `mesh` with its rim vertices at one exact position renamed to one of
/// them ([`SurfaceAudit::topology`]), or `None` when no two rim vertices
/// share a position.
fn welded_rims(mesh: &TriMesh, edges: &Edges) -> Option<TriMesh> {
    let mut on_rim = vec![false; mesh.positions.len()];
    for e in (0..edges.len()).filter(|&e| edges.triangles(e).len() == 1) {
        for v in edges.ends[e] {
            on_rim[v as usize] = true;
        }
    }
    let rim = (0..mesh.positions.len() as u32).filter(|&v| on_rim[v as usize]);
    let pairs = coincident_pairs(&|v| mesh.positions[v as usize], rim);
    if pairs.is_empty() {
        return None;
    }
    let mut to: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    for (v, at) in pairs {
        to[v as usize] = at;
    }
    Some(TriMesh {
        positions: mesh.positions.clone(),
        triangles: mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| to[v as usize]))
            .collect(),
    })
}

/// What a regression of [`SurfaceAudit::regressions`] means to someone
/// sculpting, in plain words ("open a hole", "pinch the surface at a
/// point"); the regression itself when it is not one of those.
pub fn in_plain_words(regression: &str) -> &str {
    const WORDS: [(&str, &str); 11] = [
        ("boundary loops", "open a hole"),
        (
            "non-manifold curves",
            "join surfaces along an edge shared by more than two faces",
        ),
        (
            "misoriented edges",
            "join the surface to itself back to front, outside to inside",
        ),
        ("pinched vertices", "pinch the surface at a point"),
        ("degenerate triangles", "leave a flat sliver triangle"),
        (
            "intersecting triangle pairs",
            "leave the surface passing through itself",
        ),
        (
            "pieces hidden inside the surface",
            "leave a piece cut loose inside the surface, out of sight",
        ),
        ("pieces cut loose", "cut a piece loose from the surface"),
        (
            "specks cut off",
            "leave specks of surface too small to see where it crosses itself",
        ),
        (
            "tiny handles",
            "crumple the surface into tunnels too small to see",
        ),
        (
            "triangles the motion never reached",
            "delete surface far from where the brush moved it",
        ),
    ];
    WORDS
        .iter()
        .find(|(key, _)| regression.starts_with(key))
        .map_or(regression, |(_, plain)| plain)
}

impl std::fmt::Display for SurfaceAudit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} triangles, {} components, {} boundary edges in {} loops, \
             {} non-manifold edges in {} curves, {} misoriented edges, \
             {} pinched vertices, {} degenerate triangles, {} intersecting \
             pairs, euler {}",
            self.triangles,
            self.components,
            self.boundary_edges,
            self.boundary_loops,
            self.nonmanifold_edges,
            self.nonmanifold_curves,
            self.misoriented_edges,
            self.pinched_vertices,
            self.degenerate_triangles,
            self.intersecting_pairs,
            self.euler()
        )
    }
}

/// Whether triangle `t` of `mesh` repeats a vertex or has three exactly
/// collinear corners (zero area). Three points in space are collinear
/// exactly when their projections onto the three coordinate planes all
/// are.
pub fn is_degenerate(mesh: &TriMesh, t: [u32; 3]) -> bool {
    if repeats_a_corner(&t) {
        return true;
    }
    is_flat(t.map(|v| mesh.positions[v as usize]))
}

/// The three points are exactly collinear (or coincide): the triangle
/// they make has zero area. Exact: a triangle is flat exactly when its
/// projections onto the three coordinate planes all are.
pub fn is_flat([a, b, c]: [DVec3; 3]) -> bool {
    COORDINATE_PLANES
        .iter()
        .all(|proj| orient2d(proj(a), proj(b), proj(c)) == Sign::Zero)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn tetra() -> TriMesh {
        let (positions, triangles) = holey_testkit::tetrahedron();
        TriMesh::from_arrays(&positions, &triangles)
    }

    #[test]
    fn a_tetrahedron_is_clean() {
        let a = SurfaceAudit::of(&tetra()).unwrap();
        assert_eq!(
            a,
            SurfaceAudit {
                triangles: 4,
                vertices: 4,
                edges: 6,
                components: 1,
                ..SurfaceAudit::default()
            }
        );
        assert_eq!(a.euler(), 2);
        assert!(a.regressions(&a).is_empty());
    }

    #[test]
    fn counts_what_is_wrong() {
        let mut m = tetra();
        // Open it, add a second tetrahedron through the first, a fin on an
        // edge (non-manifold) and a collinear triangle.
        m.triangles.pop();
        let n = m.positions.len() as u32;
        m.positions
            .extend(tetra().positions.iter().map(|p| *p * 0.8 + DVec3::X * 0.9));
        m.triangles
            .extend(tetra().triangles.iter().map(|t| t.map(|v| v + n)));
        m.positions.push(DVec3::new(0.0, 5.0, 5.0));
        m.triangles.push([0, 1, 8]);
        m.positions.push(DVec3::new(2.0, 2.0, 2.0)); // on the line of vertex 0
        m.triangles.push([9, 0, 9 - 1]);
        m.positions.push(DVec3::new(3.0, 3.0, 3.0));
        m.triangles.push([9, 0, 10]);
        let a = SurfaceAudit::of(&m).unwrap();
        assert_eq!(a.components, 2);
        assert_eq!(a.degenerate_triangles, 1);
        assert!(a.nonmanifold_edges >= 1);
        assert!(a.boundary_edges > 0);
        assert!(a.intersecting_pairs > 0);
        let clean = SurfaceAudit::of(&tetra()).unwrap();
        let worse = clean.regressions(&a);
        assert!(worse.iter().any(|w| w.starts_with("boundary loops")));
        assert!(worse.iter().any(|w| w.starts_with("non-manifold curves")));
        assert!(worse.iter().any(|w| w.starts_with("degenerate")));
        assert!(worse.iter().any(|w| w.starts_with("intersecting")));
    }

    #[test]
    fn a_bow_tie_is_pinched() {
        let m = TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y],
            triangles: vec![[0, 1, 2], [0, 3, 4]],
        };
        let a = SurfaceAudit::topology(&m);
        assert_eq!(a.pinched_vertices, 1);
        assert_eq!(a.components, 1);
        assert_eq!(a.boundary_edges, 6);
        assert_eq!(a.boundary_loops, 1);
    }

    /// A tetrahedron as a soup (every triangle its own three corners)
    /// audits as the closed tetrahedron it welds to; without one triangle
    /// it has one hole. Copies with whole fans (two tetrahedra touching
    /// at a corner, each its own vertex there) are not joined.
    #[test]
    fn a_soup_audits_as_the_surface_it_welds_to() {
        let t = tetra();
        let soup = t.unwelded();
        let a = SurfaceAudit::topology(&soup);
        let b = SurfaceAudit::topology(&t);
        assert_eq!(
            (
                a.components,
                a.boundary_edges,
                a.boundary_loops,
                a.nonmanifold_edges,
                a.pinched_vertices,
                a.euler()
            ),
            (b.components, 0, 0, 0, 0, 2)
        );
        let mut holed = soup.clone();
        holed.triangles.pop();
        let h = SurfaceAudit::topology(&holed);
        assert_eq!((h.boundary_edges, h.boundary_loops), (3, 1));
        assert_eq!(a.regressions(&h), ["boundary loops: 0 -> 1"]);
        // Two tetrahedra, the second's corner 0 a vertex of its own at the
        // first's corner 0: two pieces, one touching the other.
        let mut two = t.clone();
        let n = two.positions.len() as u32;
        two.positions
            .extend(t.positions.iter().map(|p| 2.0 * t.positions[0] - *p));
        two.triangles
            .extend(t.triangles.iter().map(|f| f.map(|v| v + n)));
        assert_eq!(SurfaceAudit::topology(&two).components, 2);
    }

    /// Two triangles on an edge: misoriented when both run it the same
    /// way; flipping one makes it consistent, and a regression names it.
    #[test]
    fn an_edge_run_the_same_way_twice_is_misoriented() {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, -DVec3::Y];
        let same = TriMesh {
            positions: positions.clone(),
            triangles: vec![[0, 1, 2], [0, 1, 3]],
        };
        let opposite = TriMesh {
            positions,
            triangles: vec![[0, 1, 2], [1, 0, 3]],
        };
        let (a, b) = (
            SurfaceAudit::topology(&same),
            SurfaceAudit::topology(&opposite),
        );
        assert_eq!((a.misoriented_edges, b.misoriented_edges), (1, 0));
        assert_eq!(b.regressions(&a), ["misoriented edges: 0 -> 1"]);
        assert!(a.regressions(&b).is_empty());
        assert_eq!(SurfaceAudit::topology(&tetra()).misoriented_edges, 0);
    }
}
