//! Topology change restricted to the region a motion can reach, so that a
//! sculpting frame costs what the brush touches, not what the mesh holds
//! (the locality §4's interactive rates need).
//!
//! **Why a region suffices.** Every collision of a frame involves a moving
//! vertex or a moving triangle, and every new intersection involves a
//! moving triangle. Let B be the bounding box of the swept volumes of the
//! moving triangles. A triangle that can collide with or cross a moving
//! triangle overlaps B, and so does every triangle containing a point of
//! such a contact. The engine run on the triangles overlapping B (grown
//! by a margin, which gives the error correction of §3.4 context around
//! the odd region) therefore sees every collision and every intersection
//! curve the frame makes, and the result is spliced back into the rest of
//! the mesh, which is left exactly as it was.
//!
//! **The guard.** The splice is exact only if the region's interface with
//! the rest (its edges shared with outside triangles, with their
//! directions) comes back unchanged: no cut crossing it, nothing deleted
//! or reoriented along it. That holds for a surface free of intersections
//! away from the brush, which is what sculpting keeps; when it fails (an
//! intersection the input already had that touches the interface, say),
//! the frame is recomputed on the whole mesh (a guarded frame,
//! `crate::guard`, tries a wider region first). Correctness never depends
//! on the region; only speed does.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec3;
use holey_geom::Aabb;
use holey_mesh::PARALLEL_RUN;
use holey_mesh::tri::SlotChanges;
use rayon::prelude::*;

use crate::engine::{Options, Outcome, Report, TopoError, check, topology_change};
use crate::intersect::intersecting_pair_count;
use crate::mesh::TriMesh;
use crate::window::Window;

/// What [`topology_change_local`] and
/// [`Accumulator::release_local`](crate::Accumulator::release_local) did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LocalReport {
    /// The engine's report of its run on the region, or on the whole mesh after
    /// a fallback.
    pub report: Report,
    /// Raw and corrected parity per input vertex (`true` = odd); vertices
    /// outside the region are even.
    pub raw_odd: Vec<bool>,
    /// Corrected parity per input vertex (`true` = odd, §3.4); vertices outside
    /// the region are even.
    pub corrected_odd: Vec<bool>,
    /// Intersection curves the frame found.
    pub intersection_curves: usize,
    /// Triangles the engine ran on (the whole mesh after a fallback).
    pub region_triangles: usize,
    /// Whether the frame was recomputed on the whole mesh.
    pub whole_mesh: bool,
    /// Whether only positions changed (same triangles, same vertices).
    pub positions_only: bool,
    /// Vertices the frame made (intersection points, split vertices,
    /// copies at pinches): the result's last `new_vertices` vertices.
    pub new_vertices: usize,
    /// A guarded frame's result is one piece ([`crate::is_one_piece`]):
    /// with [`crate::Options::one_piece`], as the guard showed from the
    /// region alone (or the frame only moved the surface); with or
    /// without, as its count of the result's pieces found (by shared
    /// vertices alone). False where neither showed it, which is not "in
    /// pieces": the caller must count them to know.
    pub one_piece: bool,
    /// A box that every triangle the frame added, removed or moved meets
    /// (at its positions before or after): what a stroke's kept far field
    /// is told ([`crate::FarField::changed_within`]). Set by the guarded
    /// frames; `None` when nothing changed; the infinite box when the
    /// frame ran on the whole mesh.
    pub changed: Option<(DVec3, DVec3)>,
}

impl LocalReport {
    /// Nothing a triangle uses moved: no collision, no crossing.
    pub(crate) fn no_motion(n: usize) -> LocalReport {
        LocalReport {
            raw_odd: vec![false; n],
            corrected_odd: vec![false; n],
            positions_only: true,
            ..LocalReport::default()
        }
    }
}

/// What the engine's output for a region means for the whole mesh.
pub(crate) enum Spliced {
    /// The region came back as it went in: only positions changed.
    PositionsOnly,
    /// The mesh with the region replaced.
    Mesh(TriMesh),
    /// The splice would not be exact: run on the whole mesh.
    NotExact,
}

/// What [`Region::plan`] decided the engine's output means, before the
/// splice is made.
pub(crate) enum Plan {
    /// The region came back as it went in.
    PositionsOnly,
    /// Splice the output in ([`Region::carry_out`]).
    Splice,
    /// The splice would not be exact.
    NotExact,
}

/// Whether `out` (with `origin`, per output vertex the input vertex it
/// is) is the input `triangles` over `n` vertices, unchanged.
fn is_identity(triangles: &[[u32; 3]], n: usize, out: &TriMesh, origin: &[u32]) -> bool {
    out.triangles == triangles
        && origin.len() == n
        && origin.iter().enumerate().all(|(i, &o)| o == i as u32)
}

/// The share of the mesh above which the region is not worth extracting.
const WHOLE_MESH_SHARE: f64 = 0.5;

/// An axis-aligned box, closed.
pub(crate) type Bounds = (DVec3, DVec3);

pub(crate) fn union(a: Option<Bounds>, b: Option<Bounds>) -> Option<Bounds> {
    match (a, b) {
        (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
        (a, None) => a,
        (None, b) => b,
    }
}

/// [`swept_box`] read from a `window` ([`Window`]) of a motion that moves
/// only vertices the window lists (the caller's promise): the moving
/// triangles are all listed.
pub(crate) fn swept_box_in(
    tris: &[[u32; 3]],
    start: &[DVec3],
    end: &[DVec3],
    window: Option<&Window>,
) -> Option<Bounds> {
    let Some(w) = window else {
        return swept_box(tris, start, end);
    };
    debug_assert!(
        (0..start.len() as u32)
            .filter(|&v| start[v as usize] != end[v as usize])
            .all(|v| w.vertices().binary_search(&v).is_ok()),
        "a vertex the window does not list moved"
    );
    let moved = |v: u32| start[v as usize] != end[v as usize];
    box_of_moving(
        w.triangles()
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .map(|&t| tris[t as usize])
            .filter(|t| t.iter().any(|&v| moved(v))),
        start,
        end,
    )
}

/// The box of the triangles `moving` over their positions at `start` and
/// at `end`; the box is a min and a max, the same in any order.
fn box_of_moving(
    moving: impl ParallelIterator<Item = [u32; 3]>,
    start: &[DVec3],
    end: &[DVec3],
) -> Option<Bounds> {
    moving
        .fold(
            || None,
            |b, t| {
                let corners = t.iter().flat_map(|&v| [start[v as usize], end[v as usize]]);
                let (lo, hi) = corners
                    .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p), hi.max(p))
                    });
                union(b, Some((lo, hi)))
            },
        )
        .reduce(|| None, union)
}

/// The box of the triangles that move from `start` to `end` (those with a
/// vertex whose position changes), over both positions; `None` when no
/// triangle moves.
pub(crate) fn swept_box(tris: &[[u32; 3]], start: &[DVec3], end: &[DVec3]) -> Option<Bounds> {
    // Flags first: the triangle scan then reads a byte per corner, and
    // positions only around what moved. Both passes run in parallel runs
    // (a frame on a million triangles spends milliseconds in each); the
    // box is a min and a max, the same in any order.
    let moved: Vec<bool> = start
        .par_iter()
        .zip(end)
        .with_min_len(PARALLEL_RUN)
        .map(|(p, q)| p != q)
        .collect();
    if !moved.contains(&true) {
        return None;
    }
    box_of_moving(
        tris.par_iter()
            .with_min_len(PARALLEL_RUN)
            .copied()
            .filter(|t| t.iter().any(|&v| moved[v as usize])),
        start,
        end,
    )
}

/// `b` grown by half its largest side on every side: context for the
/// error correction around what moved.
pub(crate) fn with_margin(b: Bounds) -> Bounds {
    grown(b, 0.5)
}

/// `b` grown by twice its largest side on every side: the second region a
/// guarded frame tries when the result on [`with_margin`]'s cannot be
/// spliced exactly, before the whole mesh (`crate::guard`).
pub(crate) fn with_wide_margin(b: Bounds) -> Bounds {
    grown(b, 2.0)
}

/// `b` grown on every side by `share` of its largest side.
fn grown(b: Bounds, share: f64) -> Bounds {
    let m = DVec3::splat(share * (b.1 - b.0).max_element());
    (b.0 - m, b.1 + m)
}

/// Triangles of a mesh and their vertices, renumbered in increasing
/// global order. Keeping the order keeps every tie the exact predicates
/// break by vertex identity (simulation of simplicity) broken the same way
/// as on the whole mesh.
pub(crate) struct Region {
    /// Per triangle of the mesh: inside.
    pub mask: Vec<bool>,
    pub count: usize,
    /// The region's triangle slots in the mesh, increasing.
    pub slots: Vec<u32>,
    /// Local vertex → global vertex, increasing.
    pub global: Vec<u32>,
    /// Global vertex → local vertex, or `u32::MAX`.
    pub local: Vec<u32>,
    /// The region's triangles in local numbers.
    pub triangles: Vec<[u32; 3]>,
    /// The ring ([`Region::ring`]), found on first use: a frame that
    /// only moves the surface never needs it.
    ring: std::sync::OnceLock<Vec<u32>>,
}

impl Region {
    /// [`Region::select`] read from a `window` ([`Window`]) that holds
    /// `bx`, of a motion `a` → `b` that moves only vertices the window
    /// lists: a triangle it does not list stays where it was, outside the
    /// window's box, so outside `bx`. Otherwise (no window, or `bx`
    /// reaching past it) the whole mesh is read. The region is the same.
    pub fn select_in(
        tris: &[[u32; 3]],
        a: &[DVec3],
        b: &[DVec3],
        bx: Bounds,
        window: Option<&Window>,
    ) -> Region {
        let Some(w) = window.filter(|w| w.holds_box(bx.0, bx.1)) else {
            return Region::select(tris, a, b, bx);
        };
        let region = Aabb::new(bx.0, bx.1);
        let code = |v: u32| region.outcode(a[v as usize]) & region.outcode(b[v as usize]);
        let inside: Vec<usize> = w
            .triangles()
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .map(|&t| t as usize)
            .filter(|&t| tris[t].iter().fold(0x3f, |c, &v| c & code(v)) == 0)
            .collect();
        let mut mask = vec![false; tris.len()];
        for &t in &inside {
            mask[t] = true;
        }
        Region::of_inside(tris, a.len(), mask, &inside)
    }

    /// The triangles whose box over `a` and `b` meets `bx`.
    ///
    /// A box misses `bx` exactly when all its points lie beyond one face
    /// of `bx`; with a 6-bit outcode per point (below/above on each axis)
    /// that is a nonzero AND of the codes of the triangle's six points.
    /// The codes are computed per vertex first, so the triangle scan
    /// reads a byte per corner; both passes run in parallel runs.
    pub fn select(tris: &[[u32; 3]], a: &[DVec3], b: &[DVec3], bx: Bounds) -> Region {
        let bx = Aabb::new(bx.0, bx.1);
        let code: Vec<u8> = a
            .par_iter()
            .zip(b)
            .with_min_len(PARALLEL_RUN)
            .map(|(&p, &q)| bx.outcode(p) & bx.outcode(q))
            .collect();
        let mask: Vec<bool> = tris
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .map(|t| code[t[0] as usize] & code[t[1] as usize] & code[t[2] as usize] == 0)
            .collect();
        // The region's triangles, and its vertices in increasing order:
        // those of a region much smaller than the mesh (a frame's, on a
        // million triangles) sorted, a larger one's by a pass over every
        // vertex.
        let inside: Vec<usize> = mask
            .par_iter()
            .with_min_len(PARALLEL_RUN)
            .enumerate()
            .filter(|(_, m)| **m)
            .map(|(t, _)| t)
            .collect();
        Region::of_inside(tris, a.len(), mask, &inside)
    }

    /// The region of the triangles `inside` (flagged in `mask`) of a mesh
    /// of `n` vertices.
    fn of_inside(tris: &[[u32; 3]], n: usize, mask: Vec<bool>, inside: &[usize]) -> Region {
        let mut local = vec![u32::MAX; n];
        let mut global = Vec::new();
        for &t in inside {
            for v in tris[t] {
                if local[v as usize] == u32::MAX {
                    local[v as usize] = 0;
                    global.push(v);
                }
            }
        }
        if global.len().saturating_mul(16) < n {
            global.sort_unstable();
        } else {
            global = (0..n as u32).filter(|&v| local[v as usize] == 0).collect();
        }
        for (l, &v) in global.iter().enumerate() {
            local[v as usize] = l as u32;
        }
        let triangles: Vec<[u32; 3]> = inside
            .iter()
            .map(|&t| tris[t].map(|v| local[v as usize]))
            .collect();
        Region {
            count: triangles.len(),
            slots: inside.iter().map(|&t| t as u32).collect(),
            mask,
            global,
            local,
            triangles,
            ring: std::sync::OnceLock::new(),
        }
    }

    /// The ring: the triangles of `tris` (the mesh the region was
    /// selected from) outside the region with a vertex in it, in mesh
    /// order. They are the only outside triangles the region's output can
    /// share an edge or a vertex with, so the splice and the audit of a
    /// frame need only them, not the whole mesh.
    pub fn ring(&self, tris: &[[u32; 3]]) -> &[u32] {
        self.ring.get_or_init(|| {
            tris.par_iter()
                .zip(&self.mask)
                .with_min_len(PARALLEL_RUN)
                .enumerate()
                .filter(|(_, (t, inside))| {
                    !**inside && t.iter().any(|&v| self.local[v as usize] != u32::MAX)
                })
                .map(|(i, _)| i as u32)
                .collect()
        })
    }

    /// Per region vertex (the region's numbering): whether a triangle of
    /// the ring uses it, that is, whether the region shares it with the
    /// rest of the mesh (its interface).
    pub(crate) fn interface_vertices(&self, tris: &[[u32; 3]]) -> Vec<bool> {
        let mut interface = vec![false; self.global.len()];
        for &t in self.ring(tris) {
            for v in tris[t as usize] {
                if let Some(&l) = self.local.get(v as usize).filter(|&&l| l != u32::MAX) {
                    interface[l as usize] = true;
                }
            }
        }
        interface
    }

    /// The box of the region's vertices at `start` and at `end` (global
    /// positions): every triangle of the region, before and after the
    /// frame, and every point a cut of it makes lies in it. `None` for an
    /// empty region.
    pub fn bounds(&self, start: &[DVec3], end: &[DVec3]) -> Option<Bounds> {
        self.global
            .iter()
            .flat_map(|&v| [start[v as usize], end[v as usize]])
            .fold(None, |b, p| union(b, Some((p, p))))
    }

    /// The region's triangles in the mesh's vertex numbers, in mesh order.
    pub fn global_triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.triangles
            .iter()
            .map(|t| t.map(|v| self.global[v as usize]))
    }

    /// Whether the region is small enough to be worth it.
    pub fn worth_it(&self) -> bool {
        (self.count as f64) <= WHOLE_MESH_SHARE * self.mask.len() as f64
    }

    /// Per-vertex values of the region's vertices.
    pub fn gather<T: Copy>(&self, values: &[T]) -> Vec<T> {
        self.global.iter().map(|&v| values[v as usize]).collect()
    }

    /// Per-vertex values of the whole mesh: the region's, `outside` elsewhere.
    pub fn scatter<T: Copy>(&self, values: &[T], n: usize, outside: T) -> Vec<T> {
        let mut all = vec![outside; n];
        for (&g, &v) in self.global.iter().zip(values) {
            all[g as usize] = v;
        }
        all
    }

    /// The region's submesh at `positions` (global).
    pub fn submesh(&self, positions: &[DVec3]) -> TriMesh {
        TriMesh {
            positions: self.gather(positions),
            triangles: self.triangles.clone(),
        }
    }

    /// The report of the engine's run `out` on the region of `mesh`, and
    /// what its output means for the whole mesh (at `end` outside the
    /// region). With `solid_guard` (the engine option), an output that
    /// opens a hole in a closed, consistently oriented mesh is not spliced:
    /// the region is only a patch of the solid, so the guard
    /// ([`crate::solid`]) can only run on the whole mesh.
    pub fn resolve(
        &self,
        mesh: &TriMesh,
        end: &[DVec3],
        out: &Outcome,
        solid_guard: bool,
    ) -> (LocalReport, Spliced) {
        let (report, plan) = self.plan(mesh, out, solid_guard);
        (report, self.carry_out(plan, mesh, end, out))
    }

    /// [`Region::resolve`] in two steps: what the output means (cheap,
    /// on the region), then [`Region::carry_out`] (the splice, a pass
    /// over the whole mesh), so that a caller can audit the region while
    /// the splice runs.
    pub fn plan(&self, mesh: &TriMesh, out: &Outcome, solid_guard: bool) -> (LocalReport, Plan) {
        let n = mesh.positions.len();
        let mut report = LocalReport {
            new_vertices: new_vertex_count(&out.vertex_origin),
            report: out.report.clone(),
            raw_odd: self.scatter(&out.raw_odd, n, false),
            corrected_odd: self.scatter(&out.corrected_odd, n, false),
            intersection_curves: out.intersections.curve_count,
            region_triangles: self.count,
            ..LocalReport::default()
        };
        // What would make the whole-mesh run's solid guard step in:
        // checked first, since a fold can leave a crossing that parity
        // does not resolve while changing nothing (positions only).
        // The region must start free of intersections too, or the whole
        // mesh does not either and its guard would not apply: a closed
        // mesh that already crossed itself would otherwise go to the
        // whole mesh at every frame near its old curves.
        let cut = &out.report.cut;
        let plan = if solid_guard
            && (cut.curves_dropped > 0
                || cut.false_vertices > 0
                || self.opens(&out.mesh, &out.vertex_origin))
            && mesh.is_closed_manifold()
            && intersecting_pair_count(&self.submesh(&mesh.positions), 0) == Ok(0)
        {
            Plan::NotExact
        } else if is_identity(
            &self.triangles,
            self.global.len(),
            &out.mesh,
            &out.vertex_origin,
        ) {
            report.positions_only = true;
            Plan::PositionsOnly
        } else {
            Plan::Splice
        };
        (report, plan)
    }

    /// The [`Plan`] carried out: for [`Plan::Splice`], the mesh with the
    /// region replaced by `out`, at `end` outside, or
    /// [`Spliced::NotExact`] when the splice would not be exact.
    pub fn carry_out(&self, plan: Plan, mesh: &TriMesh, end: &[DVec3], out: &Outcome) -> Spliced {
        match plan {
            Plan::PositionsOnly => Spliced::PositionsOnly,
            Plan::NotExact => Spliced::NotExact,
            Plan::Splice => match self.splice(mesh, end, &out.mesh, &out.vertex_origin) {
                Some(m) => Spliced::Mesh(m),
                None => Spliced::NotExact,
            },
        }
    }

    /// Whether the engine's output `out` (`origin` as for
    /// [`Region::splice`]) has a boundary edge that is not one of the
    /// region's own: an edge at a new point, or between region vertices
    /// that the region's triangles do not leave open.
    fn opens(&self, out: &TriMesh, origin: &[u32]) -> bool {
        let boundary = |tris: &mut dyn Iterator<Item = [u32; 3]>| {
            let mut count: HashMap<(u32, u32), u32> = HashMap::default();
            for t in tris {
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    *count.entry((a.min(b), a.max(b))).or_default() += 1;
                }
            }
            count
                .into_iter()
                .filter(|&(_, c)| c == 1)
                .map(|(e, _)| e)
                .collect::<Vec<_>>()
        };
        let own: HashSet<(u32, u32)> = boundary(&mut self.triangles.iter().copied())
            .into_iter()
            .collect();
        boundary(&mut out.triangles.iter().copied())
            .into_iter()
            .any(|(a, b)| {
                let (a, b) = (origin[a as usize], origin[b as usize]);
                a == u32::MAX || b == u32::MAX || !own.contains(&(a.min(b), a.max(b)))
            })
    }

    /// The mesh with the region replaced by the engine's output `out`
    /// (`origin`: per output vertex, the region vertex it is, or
    /// `u32::MAX`), at `end` outside. `None` when the output does not keep
    /// the region's interface with the rest of the mesh (see the module
    /// documentation): the caller must then run on the whole mesh.
    fn splice(
        &self,
        mesh: &TriMesh,
        end: &[DVec3],
        out: &TriMesh,
        origin: &[u32],
    ) -> Option<TriMesh> {
        let map = self.splice_map(mesh, end.len(), out, origin)?;
        // A mesh given to the engine may have unused vertices, which
        // this splice drops everywhere (the stroke's in-place splice
        // keeps those outside the region).
        let extra = map.triangles(out);
        let spliced = holey_mesh::tri::splice_keeping_slots(
            end,
            &map.added,
            &mesh.triangles,
            &self.mask,
            &extra,
        );
        Some(spliced.mesh)
    }

    /// Where each vertex of the engine's output `out` goes in the spliced
    /// mesh before its unused vertices are dropped (see
    /// [`Region::splice`]): an input vertex keeps its number (the first
    /// of its copies, where the engine split it), the others follow the
    /// mesh's `n` vertices in order. `None` when
    /// the output does not keep the region's interface.
    pub(crate) fn splice_map(
        &self,
        mesh: &TriMesh,
        n: usize,
        out: &TriMesh,
        origin: &[u32],
    ) -> Option<SpliceMap> {
        let mut interface: HashSet<(u32, u32)> = HashSet::default();
        for t in self
            .ring(&mesh.triangles)
            .iter()
            .map(|&t| mesh.triangles[t as usize])
        {
            for k in 0..3 {
                let (a, b) = (
                    self.local[t[k] as usize],
                    self.local[t[(k + 1) % 3] as usize],
                );
                if a != u32::MAX && b != u32::MAX {
                    interface.insert((a.min(b), a.max(b)));
                }
            }
        }
        let mut produced: HashSet<(u32, u32)> = HashSet::default();
        for t in &out.triangles {
            for k in 0..3 {
                let (a, b) = (origin[t[k] as usize], origin[t[(k + 1) % 3] as usize]);
                if a != u32::MAX && b != u32::MAX {
                    produced.insert((a, b));
                }
            }
        }
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if interface.contains(&(a.min(b), a.max(b))) && !produced.contains(&(a, b)) {
                    return None;
                }
            }
        }
        Some(self.output_map(n, out, origin))
    }

    /// [`Region::splice_map`] without the check of the interface: where
    /// each vertex of the output `out` (`origin` as for
    /// [`Region::splice`]) goes among the `n` vertices of the mesh and the
    /// new ones after them. The splice and the guard's audit number the
    /// output so.
    pub(crate) fn output_map(&self, n: usize, out: &TriMesh, origin: &[u32]) -> SpliceMap {
        // An input vertex the engine split (one copy per fan where the
        // surface was pinched) has several outputs: the first keeps its
        // number, the others are new vertices.
        let mut taken = vec![false; self.global.len()];
        let mut added = Vec::new();
        let vertex: Vec<u32> = origin
            .iter()
            .zip(&out.positions)
            .map(|(&o, &p)| {
                if o == u32::MAX || std::mem::replace(&mut taken[o as usize], true) {
                    added.push(p);
                    (n + added.len() - 1) as u32
                } else {
                    self.global[o as usize]
                }
            })
            .collect();
        SpliceMap { vertex, added }
    }

    /// What splicing `out` (the engine's output for the region, placed
    /// by `map` from [`Region::splice_map`]) into `mesh` writes, ready to
    /// be written in place ([`RegionSplice::apply`]) once the frame is
    /// kept: no pass over the mesh. The vertices that go are the
    /// region's that neither the ring ([`Region::ring`], found by the
    /// splice map) nor the output uses; every other vertex of a mesh
    /// without unused vertices is used outside the region.
    pub(crate) fn splice_of(&self, mesh: &TriMesh, out: &TriMesh, map: SpliceMap) -> RegionSplice {
        let extra = map.triangles(out);
        let mut used = self.interface_vertices(&mesh.triangles);
        for &v in extra.iter().flatten() {
            if let Some(&l) = self.local.get(v as usize).filter(|&&l| l != u32::MAX) {
                used[l as usize] = true;
            }
        }
        let dropped = self
            .global
            .iter()
            .zip(&used)
            .filter(|(_, used)| !**used)
            .map(|(&v, _)| v)
            .collect();
        RegionSplice {
            vertices: self.global.clone(),
            skipped: self.slots.clone(),
            dropped,
            added: map.added,
            extra,
        }
    }

    /// Every triangle of the spliced mesh of `map` before its unused
    /// vertices are dropped (the outside triangles of `mesh`, then
    /// `out`'s), in no particular order, without building it.
    pub(crate) fn for_each_spliced_triangle(
        &self,
        mesh: &TriMesh,
        out: &TriMesh,
        map: &SpliceMap,
        f: &mut dyn FnMut([u32; 3]),
    ) {
        for (t, _) in mesh
            .triangles
            .iter()
            .zip(&self.mask)
            .filter(|(_, inside)| !**inside)
        {
            f(*t);
        }
        for t in &out.triangles {
            f(t.map(|v| map.vertex[v as usize]));
        }
    }
}

/// Per region vertex (`count` of them): the first vertex of an engine's
/// output that comes from it (`origin` as for [`Region::splice`]), or
/// `u32::MAX` where none does. Where the engine split a vertex into
/// copies, that first one keeps its number in the splice
/// ([`Region::output_map`]) and is the one the rest of the mesh meets.
pub(crate) fn first_copies(origin: &[u32], count: usize) -> Vec<u32> {
    let mut first = vec![u32::MAX; count];
    for (v, &o) in origin.iter().enumerate() {
        if let Some(f) = first.get_mut(o as usize).filter(|f| **f == u32::MAX) {
            *f = v as u32;
        }
    }
    first
}

/// Where a region's output goes in the mesh it is spliced into
/// ([`Region::splice_map`]).
pub(crate) struct SpliceMap {
    /// Per output vertex, its number in the spliced mesh before
    /// the splice drops its unused vertices.
    pub vertex: Vec<u32>,
    /// The positions of the vertices numbered after the mesh's own.
    pub added: Vec<DVec3>,
}

impl SpliceMap {
    /// The triangles of `out` (the output the map was made for) in the
    /// spliced mesh's numbers before the splice drops its unused vertices.
    pub fn triangles(&self, out: &TriMesh) -> Vec<[u32; 3]> {
        out.triangles
            .iter()
            .map(|t| t.map(|v| self.vertex[v as usize]))
            .collect()
    }

    /// The position of vertex `v` of the spliced mesh before the splice
    /// drops its unused vertices: the mesh's own at `end`, then the added
    /// ones.
    pub fn position(&self, end: &[DVec3], v: u32) -> DVec3 {
        match (v as usize).checked_sub(end.len()) {
            None => end[v as usize],
            Some(k) => self.added[k],
        }
    }
}

/// A region's output placed in the mesh it goes into
/// ([`Region::splice_of`]), not yet written.
#[derive(Clone, Debug)]
pub(crate) struct RegionSplice {
    /// The region's vertices: they take their end positions (no other
    /// vertex moves in a frame).
    vertices: Vec<u32>,
    /// The region's triangle slots, increasing.
    skipped: Vec<u32>,
    /// The region's vertices nothing uses after the splice, increasing.
    dropped: Vec<u32>,
    /// The positions of the vertices numbered after the mesh's own.
    added: Vec<DVec3>,
    /// The output's triangles in the mesh's numbers before the splice.
    extra: Vec<[u32; 3]>,
}

impl RegionSplice {
    /// Writes the splice into `mesh` (the mesh it was made for, at its
    /// start positions; `end` its end positions): the region's vertices
    /// move to `end`, and [`holey_mesh::tri::splice_in_place`] does the
    /// rest, so the result is the copying splice's
    /// ([`holey_mesh::tri::splice_keeping_slots`]) number for number.
    pub fn apply(&self, mesh: &mut TriMesh, end: &[DVec3]) -> SlotChanges {
        for &v in &self.vertices {
            mesh.positions[v as usize] = end[v as usize];
        }
        holey_mesh::tri::splice_in_place(
            mesh,
            &self.added,
            &self.skipped,
            &self.dropped,
            &self.extra,
        )
    }

    /// The spliced mesh as a mesh of its own, `mesh` left as it is.
    pub fn into_mesh(self, mesh: &TriMesh, end: &[DVec3]) -> TriMesh {
        let mut result = mesh.clone();
        self.apply(&mut result, end);
        result
    }
}

/// [`topology_change`] of `mesh` moving to `end`,
/// run only on the triangles the motion can reach, written into `mesh`
/// (left as it was on error). Same contract; see the module documentation
/// for why the result matches.
pub fn topology_change_local(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
) -> Result<LocalReport, TopoError> {
    check(mesh, end)?;
    let Some(bx) = swept_box(&mesh.triangles, &mesh.positions, end) else {
        mesh.positions.copy_from_slice(end);
        return Ok(LocalReport::no_motion(mesh.positions.len()));
    };
    let region = Region::select(&mesh.triangles, &mesh.positions, end, with_margin(bx));
    if !region.worth_it() {
        return whole(mesh, end, options);
    }
    let sub = region.submesh(&mesh.positions);
    let out = topology_change(&sub, &region.gather(end), options)?;
    let (report, spliced) = region.resolve(mesh, end, &out, options.solid_guard);
    match spliced {
        Spliced::PositionsOnly => mesh.positions.copy_from_slice(end),
        Spliced::Mesh(m) => *mesh = m,
        Spliced::NotExact => return whole(mesh, end, options),
    }
    Ok(report)
}

fn whole(mesh: &mut TriMesh, end: &[DVec3], options: &Options) -> Result<LocalReport, TopoError> {
    let out = topology_change(mesh, end, options)?;
    let (m, report) = from_whole(mesh, out);
    *mesh = m;
    Ok(report)
}

/// How many of an output's vertices are new (`origin` per output vertex:
/// its input vertex, `u32::MAX` for a new point; a repeated input vertex
/// is a copy made at a pinch). Both kinds are numbered after the
/// surviving input vertices.
pub(crate) fn new_vertex_count(origin: &[u32]) -> usize {
    let mut seen = rustc_hash::FxHashSet::default();
    origin
        .iter()
        .filter(|&&o| o == u32::MAX || !seen.insert(o))
        .count()
}

/// A whole-mesh outcome as a mesh and a [`LocalReport`].
pub(crate) fn from_whole(mesh: &TriMesh, out: Outcome) -> (TriMesh, LocalReport) {
    let positions_only = is_identity(
        &mesh.triangles,
        mesh.positions.len(),
        &out.mesh,
        &out.vertex_origin,
    );
    let report = LocalReport {
        new_vertices: new_vertex_count(&out.vertex_origin),
        intersection_curves: out.intersections.curve_count,
        region_triangles: mesh.triangles.len(),
        whole_mesh: true,
        positions_only,
        report: out.report,
        raw_odd: out.raw_odd,
        corrected_odd: out.corrected_odd,
        one_piece: false,
        changed: Some((DVec3::NEG_INFINITY, DVec3::INFINITY)),
    };
    (out.mesh, report)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::test_meshes::uv_sphere;

    /// A window's reads find what the whole mesh's passes find: the
    /// swept box and the regions of boxes inside the window, the same
    /// field by field, for a motion of vertices inside it; a box reaching
    /// past the window reads the whole mesh, the same again.
    #[test]
    fn window_reads_are_the_whole_mesh_reads() {
        let mesh = uv_sphere(DVec3::ZERO, 1.0, 48, 96);
        let (lo, hi) = (DVec3::new(0.2, -0.5, -0.5), DVec3::new(1.2, 0.5, 0.5));
        let w = Window::build(&mesh, lo, hi);
        assert!(w.triangles().len() < mesh.triangles.len() / 4);
        // Push the vertices near (1, 0, 0) outward.
        let end: Vec<DVec3> = mesh
            .positions
            .iter()
            .map(|&p| {
                let d = p.distance(DVec3::X);
                if d < 0.3 {
                    p * (1.0 + 0.2 * (0.3 - d))
                } else {
                    p
                }
            })
            .collect();
        let whole = swept_box(&mesh.triangles, &mesh.positions, &end);
        assert!(whole.is_some());
        assert_eq!(
            swept_box_in(&mesh.triangles, &mesh.positions, &end, Some(&w)),
            whole
        );
        let Some(bx) = whole else { return };
        for b in [bx, with_margin(bx), with_wide_margin(bx)] {
            let a = Region::select(&mesh.triangles, &mesh.positions, &end, b);
            let c = Region::select_in(&mesh.triangles, &mesh.positions, &end, b, Some(&w));
            assert!(a.count > 0);
            assert_eq!(a.mask, c.mask);
            assert_eq!(a.count, c.count);
            assert_eq!(a.global, c.global);
            assert_eq!(a.local, c.local);
            assert_eq!(a.triangles, c.triangles);
        }
        // The widest box reaches past the window (and is read whole).
        let wide = with_wide_margin(bx);
        assert!(!w.holds_box(wide.0, wide.1));
        assert!(w.holds_box(bx.0, bx.1));
        // Nothing moves: no box either way.
        assert_eq!(
            swept_box_in(&mesh.triangles, &mesh.positions, &mesh.positions, Some(&w)),
            None
        );
    }

    fn components(m: &TriMesh) -> usize {
        let mut parent: Vec<usize> = (0..m.positions.len()).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for t in &m.triangles {
            let a = find(&mut parent, t[0] as usize);
            for &v in &t[1..] {
                let b = find(&mut parent, v as usize);
                parent[b] = a;
            }
        }
        (0..m.positions.len())
            .filter(|&v| find(&mut parent, v) == v)
            .count()
    }

    /// A far-away second sphere keeps the region small.
    fn scene() -> TriMesh {
        let mut a = uv_sphere(DVec3::ZERO, 1.0, 16, 24);
        let b = uv_sphere(DVec3::new(2.5, 0.0, 0.0), 1.0, 16, 24);
        let off = a.positions.len() as u32;
        a.positions.extend(b.positions);
        a.triangles
            .extend(b.triangles.iter().map(|t| t.map(|v| v + off)));
        // A third, far away, that only adds work for a global run.
        let c = uv_sphere(DVec3::new(0.0, 40.0, 0.0), 1.0, 40, 60);
        let off = a.positions.len() as u32;
        a.positions.extend(c.positions);
        a.triangles
            .extend(c.triangles.iter().map(|t| t.map(|v| v + off)));
        a
    }

    #[test]
    fn a_motion_without_contact_moves_positions_only() {
        let m = scene();
        let mut end = m.positions.clone();
        end[0] += DVec3::Z * 0.05;
        let mut moved = m.clone();
        let out = topology_change_local(&mut moved, &end, &Options::default()).unwrap();
        assert!(out.positions_only && !out.whole_mesh);
        assert!(out.region_triangles < m.triangles.len() / 4);
        assert_eq!(moved.positions, end);
        assert_eq!(moved.triangles, m.triangles);
    }

    /// The end positions of [`scene`] with the first sphere's +x cap
    /// pushed into the second sphere.
    fn cap_pushed_in(m: &TriMesh) -> Vec<DVec3> {
        m.positions
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                if i < 2 + 15 * 24 && p.x > 0.6 {
                    p + DVec3::X * 1.2
                } else {
                    p
                }
            })
            .collect()
    }

    #[test]
    fn matches_the_whole_mesh_engine_on_a_union() {
        let m = scene();
        let end = cap_pushed_in(&m);
        let mut local_mesh = m.clone();
        let local = topology_change_local(&mut local_mesh, &end, &Options::default()).unwrap();
        let global = topology_change(&m, &end, &Options::default()).unwrap();
        assert!(!local.whole_mesh);
        assert!(!local.positions_only);
        assert!(local.report.cut.triangles_deleted > 0);
        local_mesh.check().unwrap();
        assert_eq!(local_mesh.triangles.len(), global.mesh.triangles.len());
        assert_eq!(local_mesh.positions.len(), global.mesh.positions.len());
        assert_eq!(components(&local_mesh), 2, "the two spheres joined");
        assert_eq!(components(&global.mesh), 2);
        assert!(local_mesh.is_closed_manifold());
        // Same surface: the same multiset of rounded triangle centroids.
        let key = |m: &TriMesh| {
            let mut c: Vec<[i64; 3]> = m
                .triangles
                .iter()
                .map(|t| {
                    let p = t.iter().map(|&v| m.positions[v as usize]).sum::<DVec3>() / 3.0;
                    [p.x, p.y, p.z].map(|x| (x * 1e9).round() as i64)
                })
                .collect();
            c.sort_unstable();
            c
        };
        assert_eq!(key(&local_mesh), key(&global.mesh));
    }

    /// A frame's region spliced in place ([`Region::splice_of`], which
    /// finds the vertices that go from the region's ring alone) is the
    /// copying splice's mesh number for number, on a mesh that uses
    /// every vertex: the first sphere's cap pushed into the second,
    /// which deletes vertices inside it and makes points on the curve.
    #[test]
    fn a_region_spliced_in_place_is_the_copying_splice() {
        let m = scene();
        let end = cap_pushed_in(&m);
        let bx = swept_box(&m.triangles, &m.positions, &end).unwrap();
        let region = Region::select(&m.triangles, &m.positions, &end, with_margin(bx));
        assert!(region.worth_it());
        let sub = region.submesh(&m.positions);
        let out = topology_change(&sub, &region.gather(&end), &Options::default()).unwrap();
        let copied = region
            .splice(&m, &end, &out.mesh, &out.vertex_origin)
            .unwrap();
        let map = region
            .splice_map(&m, m.positions.len(), &out.mesh, &out.vertex_origin)
            .unwrap();
        let splice = region.splice_of(&m, &out.mesh, map);
        assert!(!splice.dropped.is_empty() && !splice.added.is_empty());
        let mut in_place = m.clone();
        let changes = splice.apply(&mut in_place, &end);
        assert!(!changes.moved.is_empty());
        assert_eq!(in_place, copied);
        in_place.check().unwrap();
        assert_eq!(components(&in_place), 2, "the two spheres joined");
    }

    #[test]
    fn a_local_drag_matches_the_whole_mesh_release() {
        let m = scene();
        let cap = |t: f64| -> Vec<DVec3> {
            m.positions
                .iter()
                .enumerate()
                .map(|(i, &p)| {
                    if i < 2 + 15 * 24 && p.x > 0.6 {
                        p + DVec3::X * t
                    } else {
                        p
                    }
                })
                .collect()
        };
        let mut acc = crate::Accumulator::new(m.clone(), Options::default()).unwrap();
        for t in [0.4, 0.8, 1.2] {
            acc.advance(&cap(t)).unwrap();
        }
        let preview = acc.corrected_parity().unwrap();
        assert!(
            preview.iter().any(|&o| o),
            "the preview shows what vanishes"
        );
        let global = acc.clone().release().unwrap();
        assert_eq!(preview, global.corrected_odd);
        let (local_mesh, local) = acc.release_local().unwrap();
        assert!(!local.whole_mesh);
        assert!(local.region_triangles < m.triangles.len() / 2);
        assert_eq!(local.raw_odd, global.raw_odd);
        assert_eq!(local_mesh.triangles.len(), global.mesh.triangles.len());
        assert!(local_mesh.is_closed_manifold());
        assert_eq!(components(&local_mesh), 2);
    }

    #[test]
    fn bad_input_is_an_error() {
        let m = scene();
        let mut same = m.clone();
        let short = m.positions[1..].to_vec();
        assert!(topology_change_local(&mut same, &short, &Options::default()).is_err());
        let mut end = m.positions.clone();
        end[3] = DVec3::NAN;
        assert!(topology_change_local(&mut same, &end, &Options::default()).is_err());
        assert_eq!(same, m, "an error leaves the mesh as it was");
        let mut bad = m.clone();
        bad.triangles.push([0, 1, u32::MAX]);
        assert!(topology_change_local(&mut bad, &m.positions, &Options::default()).is_err());
    }
}
