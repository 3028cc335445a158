//! A frame that never leaves the surface worse than it found it: the
//! engine's result is checked, and where the motion cannot be resolved
//! cleanly the vertices that make the trouble are held still.
//!
//! Parity-based topology change (§3) is proven for solids (Theorem 5.1);
//! on the meshes people have — open sheets whose rims cross, scans folding
//! at a crease, surfaces already crossing themselves — the discrete
//! parity field can ask for a cut no clean surface follows (the paper's
//! §7: rims sweeping through a sheet, intersecting parts starting to
//! move). A sculpting frame must still end on a surface that is no worse
//! than the one it started from:
//!
//! - no new boundary loop (a closed surface stays closed), no new
//!   non-manifold curve, no new pinched vertex;
//! - no new degenerate (zero-area) triangle;
//! - no more intersecting triangle pairs than before: every intersection
//!   the motion makes is resolved;
//! - no piece cut loose and left hidden inside the surface, and no
//!   speck, a piece hardly wider than the edges the surface had there
//!   are long ([`crate::hidden`]). With [`Options::take_out_debris`]
//!   (an inflate), a speck the cut closed off, with its own points and
//!   whole within the frame's region, is debris below the surface's
//!   resolution: it is taken out of the result before the audit
//!   ([`crate::hidden::debris`]) rather than holding the frame;
//! - for an inflate ([`Options::outward`]), no new piece at all;
//! - no crumple: two or more new intersection curves within one piece,
//!   each smaller than the shortest edge there and within one such edge
//!   of each other, along which the cut would glue tunnels nobody can
//!   see ([`crate::hidden`]).
//!
//! [`topology_change_guarded`] runs the frame on the region the motion
//! reaches ([`crate::local`]) and audits that region and the ring of
//! triangles around it ([`crate::audit`]) before and after. When that
//! region's result does not splice back exactly, a wider region (the
//! motion's box grown by twice its size on every side, against half for
//! the first) is tried before the whole mesh. When the
//! result is worse, the motion that made it does not happen: every moving
//! vertex keeps its start position (it is *held*, as collision response
//! holds the parts of a cloth it cannot resolve), the surface is exactly
//! as it was, and the report says which vertices were held. A stroke
//! passes them on to its next frames
//! ([`topology_change_guarded_holding`]), so that a contact no frame can
//! resolve is not tried again at every frame; sculpting also eases the
//! rest of its brush off them, so that they do not stand out of the
//! surface it moves on (`holey-sculpt`'s `ease`).
//!
//! Holding only the vertices at the new contacts and letting the rest of
//! the brush move (impact zones) was tried: at a contact no frame could
//! resolve, the brush went on lifting everything around the held zone,
//! remeshing split the stretched triangles between them without end, and
//! a 40-frame dwell on the Stanford bunny's underside took 19 s instead
//! of 2.7 s.

use glam::DVec3;
use holey_geom::Aabb;
use holey_mesh::tri::SlotChanges;
use rustc_hash::{FxHashMap, FxHashSet};

use crate::audit::SurfaceAudit;
use crate::containment::{Surroundings, by_containment};
use crate::drag_path::{DragPath, Numbering};
use crate::engine::{
    Freedom, Geometry, Options, Outcome, Path, TopoError, check, finish, freedom, geometry,
    topology_change,
};
use crate::far_field::FarField;
use crate::hidden::{
    PieceCount, debris, hidden_pieces, median_edge_near, piece_count_welded, pieces_welded,
    shortest_edge_near, specks, tiny_new_curves, vertex_components,
};
use crate::intersect::{crossing_pairs_within, pair_count_at, pairs_intersect_at};
use crate::local::{
    Bounds, LocalReport, Plan, Region, RegionSplice, first_copies, from_whole, swept_box_in,
    with_margin, with_wide_margin,
};
use crate::mesh::TriMesh;
use crate::union_find::UnionFind;
use crate::window::{Window, corners_meet_box, outcodes};

/// What [`topology_change_guarded`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GuardedReport {
    /// The engine's report of the attempt that was kept.
    pub local: LocalReport,
    /// Engine runs (1 when the first result was clean).
    pub attempts: usize,
    /// Vertices that kept their start positions because moving them made
    /// the surface worse.
    pub held_vertices: usize,
    /// Every moving vertex was held: the frame changed nothing.
    pub held_all: bool,
    /// Where the held vertices are (they did not move): a stroke finds
    /// them again by position in its next frame, whatever the
    /// renumbering of topology change and remeshing did.
    pub held_positions: Vec<DVec3>,
    /// What the first attempt would have made worse, in words (empty when
    /// it was clean).
    pub refused: Vec<String>,
    /// How the kept attempt changed the Euler characteristic V − E + F of
    /// the surface (counted on the region and the triangles around it,
    /// before and after, welded at rims as the audit counts; the rest of
    /// the surface is the same on both sides): negative where the frame
    /// joined the surface to itself (a handle, −2 each) or two pieces
    /// into one (−2 each), positive where it cut one loose or opened a
    /// handle; 0 when it only moved the surface or was held.
    pub euler_change: i64,
    /// For a frame in a window ([`topology_change_guarded_holding_in`]):
    /// whether the window still lists what it must of the result (it was
    /// told every slot the splice wrote). False when the frame's result
    /// was built whole: the caller builds a new window.
    pub window_kept: bool,
}

/// [`crate::topology_change_local`] that keeps the surface's invariants
/// (see the module documentation): on success `mesh` is the result, which
/// is never worse than the input in any of the audited respects; on error
/// `mesh` is left as it was.
pub fn topology_change_guarded(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
) -> Result<GuardedReport, TopoError> {
    topology_change_guarded_holding(mesh, end, options, &[], None)
}

/// [`topology_change_guarded`] with the vertices `already` flags held
/// from the first attempt (a stroke passes on those its earlier frames had
/// to hold, so that a contact no frame can resolve is not tried again at
/// every frame). An empty `already` holds nothing to begin with. With
/// `far`, a stroke's kept far field ([`FarField`]), a frame resolved by
/// containment number reads the surface around its region from it; the
/// caller then reports each change it makes to the surface to it,
/// this frame's included ([`LocalReport::changed`]).
pub fn topology_change_guarded_holding(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
    already: &[bool],
    far: Option<&FarField>,
) -> Result<GuardedReport, TopoError> {
    guarded(mesh, end, options, already, false, far, None).map(|r| r.unwrap_or_default())
}

/// [`topology_change_guarded_holding`] that finds what the motion reaches
/// in `window` ([`Window`]) instead of passes over the whole mesh, where
/// that is exact: the same result, at a cost that follows the window.
/// The caller promises that `end` moves only vertices the window lists,
/// and that `mesh` passed its checks before (a stroke's, at an earlier
/// frame): only `end` at the listed vertices is checked here. The window
/// is told what the frame wrote; [`GuardedReport::window_kept`] says
/// whether it still holds for the result.
pub fn topology_change_guarded_holding_in(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
    already: &[bool],
    far: Option<&FarField>,
    window: &mut Window,
) -> Result<GuardedReport, TopoError> {
    guarded(mesh, end, options, already, false, far, Some(window)).map(|r| r.unwrap_or_default())
}

/// [`topology_change_guarded_holding`] for a motion that is to be taken
/// as one frame only where that is sure: it collides with nothing and
/// crosses nothing, or the change it makes is resolved by containment
/// number and the motion's collision parity agrees with it vertex for
/// vertex, crumples aside ([`run_if_sure`]), and the result is clean. Otherwise (it
/// would need the parity's correction, or would be held) `mesh` is left
/// as it was and the answer is `None`, so that the caller can take the
/// motion in shorter frames instead. A sculpting frame whose dabs
/// together move farther than its edges are long is tried this way
/// first: the collision parity of so long a linear motion through
/// folding surface is the error-prone case (§3.1: the parity samples
/// only the straight paths).
pub fn topology_change_guarded_if_sure(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
    already: &[bool],
    far: Option<&FarField>,
) -> Result<Option<GuardedReport>, TopoError> {
    guarded(mesh, end, options, already, true, far, None)
}

/// [`topology_change_guarded_if_sure`] in a `window`, as
/// [`topology_change_guarded_holding_in`] is.
pub fn topology_change_guarded_if_sure_in(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
    already: &[bool],
    far: Option<&FarField>,
    window: &mut Window,
) -> Result<Option<GuardedReport>, TopoError> {
    guarded(mesh, end, options, already, true, far, Some(window))
}

/// [`topology_change_guarded_holding`]; with `sure_only`, `None` (and
/// `mesh` untouched) instead of a run that is not sure or is held.
fn guarded(
    mesh: &mut TriMesh,
    end: &[DVec3],
    options: &Options,
    already: &[bool],
    sure_only: bool,
    far: Option<&FarField>,
    window_mut: Option<&mut Window>,
) -> Result<Option<GuardedReport>, TopoError> {
    // A window of another mesh is not read, nor told anything.
    let window_mut = window_mut.filter(|w| w.fits(mesh));
    let window = window_mut.as_deref();
    let checked_in_window = window.is_some_and(|w| {
        end.len() == mesh.positions.len()
            && w.vertices()
                .iter()
                .all(|&v| end.get(v as usize).is_some_and(|p| p.is_finite()))
    });
    if !checked_in_window {
        check(mesh, end)?;
    }
    let n = mesh.positions.len();
    let held_from_start = |v: usize| already.get(v).copied().unwrap_or(false);
    // `end`, with the vertices held from the start where they are; no
    // copy of a million positions when none is.
    let target: std::borrow::Cow<'_, [DVec3]> = if already.iter().take(n).any(|&a| a) {
        let mut target = end.to_vec();
        for (v, _) in already.iter().take(n).enumerate().filter(|(_, a)| **a) {
            target[v] = mesh.positions[v];
        }
        std::borrow::Cow::Owned(target)
    } else {
        std::borrow::Cow::Borrowed(end)
    };
    let first = if sure_only {
        // Whether the motion is sure as one frame is all that is asked:
        // the engine's correction does not run on a motion the caller
        // will take in shorter frames anyway.
        match run_if_sure(mesh, &target, options, far, window)? {
            Some(run) if run.worse.is_empty() => run,
            _ => return Ok(None),
        }
    } else {
        run_once(mesh, &target, options, &Motion::Frame, far, window)?
    };
    let mut report = GuardedReport {
        attempts: 1,
        ..GuardedReport::default()
    };
    // The kept run, who is held, the run's end positions, and whether
    // they are the motion's (not the start's, held whole).
    let (run, held, run_end, moves): (Run, Vec<bool>, std::borrow::Cow<'_, [DVec3]>, bool) =
        if first.worse.is_empty() {
            (first, (0..n).map(held_from_start).collect(), target, true)
        } else {
            // Hold everything that moves: the frame becomes a no-op.
            report.refused = first.worse;
            report.held_all = true;
            report.attempts += 1;
            let still = mesh.positions.clone();
            let run = run_once(mesh, &still, options, &Motion::Frame, far, window)?;
            (run, vec![true; n], std::borrow::Cow::Owned(still), false)
        };
    report.held_positions = (0..n)
        .filter(|&v| held[v] && mesh.positions[v] != end[v])
        .map(|v| mesh.positions[v])
        .collect();
    report.held_vertices = report.held_positions.len();
    report.local = run.report;
    report.euler_change = run.euler_change;
    let moved_only = matches!(run.made, Made::Moved);
    if moved_only {
        // Only moved (or held): as whole as it was.
        report.local.one_piece = options.one_piece;
    }
    report.window_kept = window_mut.is_some() && !matches!(run.made, Made::Whole(_));
    let written = run.made.write_into(mesh, &run_end);
    if moved_only && moves {
        // Only moved: in a window, only its vertices can have.
        match window {
            Some(w) => {
                for &v in w.vertices() {
                    mesh.positions[v as usize] = run_end[v as usize];
                }
            }
            None => mesh.positions = run_end.into_owned(),
        }
    }
    if let (Some(w), Some((triangles, vertices))) = (window_mut, written) {
        w.written(mesh, &triangles, &vertices);
    }
    Ok(Some(report))
}

/// One run of the frame and its audit.
pub(crate) struct Run {
    /// The result.
    pub made: Made,
    pub report: LocalReport,
    /// What got worse (empty: the result is clean).
    pub worse: Vec<String>,
    /// The change of the Euler characteristic ([`GuardedReport::euler_change`]).
    pub euler_change: i64,
}

/// The result of a [`Run`] of `mesh` moving to `end`.
pub(crate) enum Made {
    /// Only positions changed: the mesh's own triangles at the end
    /// positions (a frame on a million triangles does not copy them to
    /// say so).
    Moved,
    /// A result built whole.
    Whole(TriMesh),
    /// A region's result, to be spliced into the mesh in place.
    Splice(RegionSplice),
    /// A region's result spliced into a copy of the mesh (the audit read
    /// it), and what the splice changed.
    Spliced(TriMesh, SlotChanges),
}

impl Made {
    /// Writes the result into `mesh` (the run's input; `end` its end
    /// positions), except for [`Made::Moved`], whose positions the caller
    /// writes as it sees fit. Returns the triangle and vertex slots
    /// written ([`Window::written`]) where the result was spliced, and
    /// `None` where it was built whole or only moved.
    pub fn write_into(self, mesh: &mut TriMesh, end: &[DVec3]) -> Option<(Vec<u32>, Vec<u32>)> {
        let changes = match self {
            Made::Moved => return None,
            Made::Whole(result) => {
                *mesh = result;
                return None;
            }
            Made::Splice(splice) => splice.apply(mesh, end),
            Made::Spliced(result, changes) => {
                *mesh = result;
                changes
            }
        };
        let vertices = changes.written_vertices(mesh.positions.len());
        Some((changes.written_triangles, vertices))
    }

    /// The result as a mesh of its own, `mesh` (the run's input, `end`
    /// its end positions) left as it is.
    pub fn into_mesh(self, mesh: &TriMesh, end: &[DVec3]) -> TriMesh {
        match self {
            Made::Moved => TriMesh {
                positions: end.to_vec(),
                triangles: mesh.triangles.clone(),
            },
            Made::Whole(result) | Made::Spliced(result, _) => result,
            Made::Splice(splice) => splice.into_mesh(mesh, end),
        }
    }
}

/// Where the collision parity of a motion comes from, when the motion is
/// not resolved by containment number.
pub(crate) enum Motion<'a> {
    /// One linear frame: collision detection runs on the region.
    Frame,
    /// A drag: the parity accumulated over its frames (per vertex of the
    /// mesh), with its collision count, tests and seconds, and the number
    /// of frames.
    Drag {
        raw: &'a [bool],
        collisions: (usize, u64, f64),
        frames: u64,
        /// Its keyframes, if kept (`crate::drag_path`).
        path: Option<&'a DragPath>,
    },
}

/// Whether a run may resolve its frame by containment number where the
/// region is a piece of a solid, and the stroke's kept far field for it
/// ([`FarField`]).
#[derive(Clone, Copy)]
struct Containment<'a> {
    allowed: bool,
    far: Option<&'a FarField>,
}

/// The frame of `mesh` moving to `end` on the region the motion reaches,
/// spliced back, and audited: by containment number where the region is
/// a piece of a solid, by parity where it is not or where containment's
/// result is worse.
pub(crate) fn run_once(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
    motion: &Motion<'_>,
    far: Option<&FarField>,
    window: Option<&Window>,
) -> Result<Run, TopoError> {
    let first = run_with(
        mesh,
        end,
        options,
        motion,
        Containment { allowed: true, far },
        window,
    )?;
    if first.worse.is_empty() || !first.report.report.cut.solid_relabelled {
        return Ok(first);
    }
    let second = run_with(
        mesh,
        end,
        options,
        motion,
        Containment {
            allowed: false,
            far,
        },
        window,
    )?;
    Ok(if second.worse.len() < first.worse.len() {
        second
    } else {
        first
    })
}

fn run_with(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
    motion: &Motion<'_>,
    containment: Containment<'_>,
    window: Option<&Window>,
) -> Result<Run, TopoError> {
    let n = mesh.positions.len();
    let Some(bx) = swept_box_in(&mesh.triangles, &mesh.positions, end, window) else {
        return Ok(Run {
            made: Made::Moved,
            report: LocalReport::no_motion(n),
            worse: Vec::new(),
            euler_change: 0,
        });
    };
    // Most frames collide with nothing and cross nothing: that is settled
    // on the triangles the motion's box meets, every one a moving
    // triangle can touch, before the wider region the correction needs
    // as context (the box grown by half its size: four times the
    // triangles on a surface) is gathered at all.
    if matches!(motion, Motion::Frame)
        && let Some((tight, freedom)) = Tight::of(mesh, end, options, bx, window)
    {
        match freedom {
            Freedom::Free => return Ok(free_run(mesh, end, &tight)),
            // The containment number needs no context around what
            // moved (every curve the motion makes lies among the
            // triangles the motion's box meets, and the rest of the
            // surface enters through its winding number), so a piece
            // of a solid is resolved on the tight region, with the
            // intersections just found. Parity's correction does
            // need the context: anything else goes on below.
            Freedom::Changes { geometry, .. } if containment.allowed && options.solid_guard => {
                if let Some(run) =
                    contained(mesh, end, &tight, *geometry, None, options, containment.far)?
                {
                    return Ok(run);
                }
            }
            _ => {}
        }
    }
    // The region around the box, then a wider one when the first
    // region's result cannot be spliced exactly: a cut or a deletion that
    // reaches past the first region's interface (a rim dwell's lip folding
    // through itself ends up there) is mostly contained a little farther
    // out, at a fraction of the whole mesh's cost (on the Stanford bunny,
    // 26k of its 70k triangles and about half the time).
    let mut tried = 0;
    for grown in [with_margin(bx), with_wide_margin(bx)] {
        let region = Region::select_in(&mesh.triangles, &mesh.positions, end, grown, window);
        if !region.worth_it() || region.count <= tried {
            break;
        }
        tried = region.count;
        let sub = region.submesh(&mesh.positions);
        let mut out = resolve_frame(mesh, end, &region, &sub, options, motion, containment)?;
        take_out_debris(mesh, &region, &mut out, options);
        if let Some(mut run) = spliced_and_audited(mesh, end, &region, &sub, &out, options)? {
            run.worse.extend(unreached_deleted(&sub, &out, bx));
            return Ok(run);
        }
    }
    // The whole mesh, as one region (so numbers work as above).
    let everything = Region::select(
        &mesh.triangles,
        &mesh.positions,
        end,
        (DVec3::NEG_INFINITY, DVec3::INFINITY),
    );
    let sub = everything.submesh(&mesh.positions);
    let mut out = resolve_frame(mesh, end, &everything, &sub, options, motion, containment)?;
    take_out_debris(mesh, &everything, &mut out, options);
    let (result, mut report) = from_whole(&sub, out.clone());
    report.raw_odd = everything.scatter(&report.raw_odd, n, false);
    report.corrected_odd = everything.scatter(&report.corrected_odd, n, false);
    let (mut worse, euler_change) =
        audit_region(mesh, end, &everything, &sub, &out, &report, options)?;
    if !report.positions_only {
        worse.extend(piece_growth(mesh, &result, &|_| true, &|_| true, options));
        worse.extend(unreached_deleted(&sub, &out, bx));
    }
    // Only moved: as whole as it was.
    report.one_piece = options.one_piece && report.positions_only;
    report.changed = Some((DVec3::NEG_INFINITY, DVec3::INFINITY));
    Ok(Run {
        made: Made::Whole(result),
        report,
        worse,
        euler_change,
    })
}

/// The triangles a motion's box meets, every one a moving triangle can
/// touch (`region`; `sub` at the start, `moved` at the end).
struct Tight {
    region: Region,
    sub: TriMesh,
    moved: TriMesh,
}

impl Tight {
    /// The motion of `mesh` to `end` within its box `bx`, and whether it
    /// collides or crosses there ([`freedom`]); `None` when the box meets
    /// too much of the mesh for a region to pay.
    fn of(
        mesh: &TriMesh,
        end: &[DVec3],
        options: &Options,
        bx: Bounds,
        window: Option<&Window>,
    ) -> Option<(Tight, Freedom)> {
        let region = Region::select_in(&mesh.triangles, &mesh.positions, end, bx, window);
        if !region.worth_it() {
            return None;
        }
        let sub = region.submesh(&mesh.positions);
        let moved = region.submesh(end);
        let freedom = freedom(&sub, &moved.positions, options);
        Some((Tight { region, sub, moved }, freedom))
    }
}

/// A frame that only moves the surface: the triangles its box meets
/// neither collide nor cross at the end. Worse only if it flattens a
/// triangle.
fn free_run(mesh: &TriMesh, end: &[DVec3], tight: &Tight) -> Run {
    Run {
        made: Made::Moved,
        report: LocalReport {
            region_triangles: tight.region.count,
            changed: tight.region.bounds(&mesh.positions, end),
            ..LocalReport::no_motion(mesh.positions.len())
        },
        worse: flat_growth(&tight.sub, &tight.moved).into_iter().collect(),
        euler_change: 0,
    }
}

/// The frame of `mesh` to `end` resolved by containment number on the
/// triangles its box meets (`tight`, whose intersections at the end are
/// `geometry`), its debris taken out, spliced back and audited: the run
/// when that is clean, else `None`. With `parity` (the motion's
/// collision parity per vertex of `tight`, where it reads anything:
/// [`parity_across_sheets`]), only when containment deletes exactly the
/// vertices of odd parity among those.
fn contained(
    mesh: &TriMesh,
    end: &[DVec3],
    tight: &Tight,
    geometry: Geometry,
    parity: Option<&[Option<bool>]>,
    options: &Options,
    far: Option<&FarField>,
) -> Result<Option<Run>, TopoError> {
    let far = far.and_then(|f| Some((f, tight.region.bounds(&mesh.positions, end)?)));
    let surroundings = Surroundings::new(mesh, &tight.region.mask, end, far);
    let Some(mut out) = by_containment(
        &tight.sub,
        &tight.moved.positions,
        options,
        &surroundings,
        Some(geometry),
    )?
    else {
        return Ok(None);
    };
    let disagrees = |parity: &[Option<bool>]| {
        parity
            .iter()
            .zip(&out.corrected_odd)
            .any(|(odd, &deleted)| odd.is_some_and(|odd| odd != deleted))
    };
    if parity.is_some_and(disagrees) {
        return Ok(None);
    }
    take_out_debris(mesh, &tight.region, &mut out, options);
    Ok(
        spliced_and_audited(mesh, end, &tight.region, &tight.sub, &out, options)?
            .filter(|run| run.worse.is_empty()),
    )
}

/// [`run_once`] of a frame that may only be taken whole, when that is
/// sure: the triangles its motion's box meets neither collide nor cross
/// at the end; or they do, the change is resolved by containment number
/// on them (a piece of a solid), clean, and containment deletes exactly
/// the vertices the motion's collision parity finds odd, where that
/// parity reads a passage through a sheet ([`parity_across_sheets`]: a
/// triangle folded over its own hinge is not one). Else `None`
/// (also when its box meets too much of the mesh to tell cheaply),
/// without running the engine further.
///
/// Why the agreement: the parity of a long linear motion through
/// folding surface is the error-prone case (§3.1: it samples only the
/// straight paths), and the containment number reads only the end, so
/// it misses a part carried through a sheet and out again within the
/// motion. The two are independent readings of which vertices end up
/// inside; where they agree, the shorter frames the caller would take
/// instead have nothing to add.
fn run_if_sure(
    mesh: &TriMesh,
    end: &[DVec3],
    options: &Options,
    far: Option<&FarField>,
    window: Option<&Window>,
) -> Result<Option<Run>, TopoError> {
    let n = mesh.positions.len();
    let Some(bx) = swept_box_in(&mesh.triangles, &mesh.positions, end, window) else {
        return Ok(Some(Run {
            made: Made::Moved,
            report: LocalReport::no_motion(n),
            worse: Vec::new(),
            euler_change: 0,
        }));
    };
    Ok(match Tight::of(mesh, end, options, bx, window) {
        Some((tight, Freedom::Free)) => Some(free_run(mesh, end, &tight)),
        Some((
            tight,
            Freedom::Changes {
                geometry,
                odd_pairs,
            },
        )) if options.solid_guard => {
            let odd = parity_across_sheets(&tight.sub, &odd_pairs);
            contained(mesh, end, &tight, *geometry, Some(&odd), options, far)?
        }
        _ => None,
    })
}

/// Per vertex of `sub`, what the collision parity of a motion says of
/// it, for [`run_if_sure`] to compare with the containment number: the
/// parity of its collisions (`odd_pairs`, the (vertex, triangle) pairs
/// that collide an odd number of times) with triangles other than those
/// across an edge of its own link; `None` for a vertex whose collisions
/// are all with those.
///
/// A vertex `v` that passes through the triangle `(a, b, w)` across the
/// edge `ab` of its own triangle `(v, a, b)` folds that triangle over its
/// hinge `ab` (the dihedral angle there goes through zero): a crumple of
/// the surface (§3.1), not a
/// passage into the solid through another sheet. What is kept of a
/// crumple is settled by the containment number alone in the shorter
/// frames a long motion would be taken in instead, as in the long one;
/// so such a collision says nothing about whether the long motion
/// carried a part through a sheet and out again, which is what the
/// comparison is there to catch. On the Stanford bunny's recorded haunch
/// strokes, each long frame whose two readings disagreed (7 of 18
/// frames that changed topology) did so only at one to three vertices
/// folded that way, and was then taken again in shorter frames.
fn parity_across_sheets(sub: &TriMesh, odd_pairs: &[(u32, u32)]) -> Vec<Option<bool>> {
    // A colliding vertex is unread until a passage through a sheet is
    // found; every other vertex reads even.
    let mut parity = vec![Some(false); sub.positions.len()];
    for &(v, _) in odd_pairs {
        parity[v as usize] = None;
    }
    let edge = |a: u32, b: u32| (a.min(b), a.max(b));
    // The link edges of the colliding vertices: (v, a, b) gives v the
    // edge ab.
    let mut link: FxHashSet<(u32, (u32, u32))> = FxHashSet::default();
    for &[a, b, c] in &sub.triangles {
        for (v, x, y) in [(a, b, c), (b, c, a), (c, a, b)] {
            if parity[v as usize].is_none() {
                link.insert((v, edge(x, y)));
            }
        }
    }
    for &(v, t) in odd_pairs {
        let [a, b, c] = sub.triangles[t as usize];
        let folds = [(a, b), (b, c), (c, a)]
            .iter()
            .any(|&(x, y)| link.contains(&(v, edge(x, y))));
        if !folds {
            let read = &mut parity[v as usize];
            *read = Some(!read.unwrap_or(false));
        }
    }
    parity
}

/// How many triangles of `sub` the motion never reached (they do not meet
/// the box `bx` its triangles swept, so none of their corners moved and
/// nothing that moved touched them) are not among `out`'s, in words; `None`
/// when all are kept.
///
/// Such a triangle collided with nothing, so its parity is even and
/// topology change keeps it (§3; by containment, Lemma 8.1: its two sides'
/// containment numbers did not change). A result that deletes it was
/// labelled wrongly: a containment number sampled where the frame folded
/// the surface decided a piece that reaches far beyond the fold, and a
/// frame of several deflate dabs on the Stanford bunny deleted the whole
/// surface that way, which no other audit counts as worse (no boundary,
/// piece or crossing is added by deleting everything).
fn unreached_deleted(sub: &TriMesh, out: &Outcome, bx: Bounds) -> Option<String> {
    let bx = Aabb::new(bx.0, bx.1);
    let code = outcodes(&bx, &sub.positions);
    let far: Vec<[u32; 3]> = sub
        .triangles
        .iter()
        .filter(|t| !corners_meet_box(&code, t))
        .copied()
        .collect();
    if far.is_empty() {
        return None;
    }
    let sorted = |mut t: [u32; 3]| {
        t.sort_unstable();
        t
    };
    let kept: rustc_hash::FxHashSet<[u32; 3]> = out
        .mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let o = t.map(|v| {
                out.vertex_origin
                    .get(v as usize)
                    .copied()
                    .unwrap_or(u32::MAX)
            });
            (!o.contains(&u32::MAX)).then(|| sorted(o))
        })
        .collect();
    let lost = far.iter().filter(|&&t| !kept.contains(&sorted(t))).count();
    (lost > 0).then(|| format!("triangles the motion never reached deleted: {lost}"))
}

/// The engine's result `out` for `region` of `mesh` (submesh `sub`)
/// spliced into the whole and audited; `None` when the splice is not
/// exact (the caller runs the whole mesh instead).
fn spliced_and_audited(
    mesh: &TriMesh,
    end: &[DVec3],
    region: &Region,
    sub: &TriMesh,
    out: &Outcome,
    options: &Options,
) -> Result<Option<Run>, TopoError> {
    let (mut report, plan) = region.plan(mesh, out, options.solid_guard);
    report.changed = region.bounds(&mesh.positions, end);
    // The spliced result keeps every input vertex's number; new ones
    // follow.
    let n = mesh.positions.len();
    let near = |v: u32| region.local.get(v as usize).is_none_or(|&l| l != u32::MAX);
    let near_after = |v: u32| v as usize >= n || near(v);
    let map = match plan {
        Plan::PositionsOnly => None,
        Plan::NotExact => return Ok(None),
        Plan::Splice => match region.splice_map(mesh, n, &out.mesh, &out.vertex_origin) {
            Some(map) => Some(map),
            None => return Ok(None),
        },
    };
    // A mesh of one piece whose region's result provably keeps it one
    // needs no count; one that only moved keeps its triangles.
    let one_piece = options.one_piece
        && (map.is_none() || stays_one_piece(mesh, region, &out.mesh, &out.vertex_origin));
    report.one_piece = one_piece;
    // The audit works on the region; the count of the result's pieces is
    // a pass over the whole mesh, which reads the spliced triangles
    // without building the spliced mesh, so the two go side by side. The
    // splice itself is written in place once the frame is kept
    // ([`Made::Splice`]): a frame that is refused or run again costs no
    // copy of the mesh.
    let (audited, pieces) = rayon::join(
        || audit_region(mesh, end, region, sub, out, &report, options),
        || {
            map.as_ref().filter(|_| !one_piece).map(|map| {
                piece_count_welded(
                    n + map.added.len(),
                    &|v| map.position(end, v),
                    &|f| region.for_each_spliced_triangle(mesh, &out.mesh, map, f),
                    &near_after,
                )
            })
        },
    );
    let (mut worse, euler_change) = audited?;
    // A count of one by shared vertices alone tells the next frame that
    // it starts on one piece, where this one could not show it.
    report.one_piece |= pieces.is_some_and(PieceCount::one_piece);
    let made = match map {
        None => Made::Moved,
        Some(map) => {
            let splice = region.splice_of(mesh, &out.mesh, map);
            if pieces.is_some_and(|p| p.count >= 2) {
                // One piece cannot have grown in pieces: the rules that
                // compare pieces run only on a result of more than one,
                // and read it whole.
                let mut result = mesh.clone();
                let changes = splice.apply(&mut result, end);
                // The splice numbers its result its own way: the
                // region's vertices and the points the frame made are
                // found through it.
                let moved_from: FxHashMap<u32, u32> =
                    changes.moved.iter().map(|&(f, t)| (t, f)).collect();
                let near_result = |v: u32| {
                    v as usize >= changes.first_added
                        || near(moved_from.get(&v).copied().unwrap_or(v))
                };
                worse.extend(piece_growth(mesh, &result, &near, &near_result, options));
                Made::Spliced(result, changes)
            } else {
                Made::Splice(splice)
            }
        }
    };
    Ok(Some(Run {
        made,
        report,
        worse,
        euler_change,
    }))
}

/// Whether splicing `out`, the engine's result for `region` of `mesh`
/// (`origin` as for [`Region::splice`]), into a mesh of one piece leaves
/// one piece, shown from the region alone: every vertex of the region's
/// interface (those on the triangles around it) is in the result, all of
/// them in one of its connected components, and every component of the
/// result holds one of them.
///
/// Why that suffices: each connected part of the rest of the mesh
/// touches the region at an interface vertex (else it would have been a
/// piece of its own before), every interface vertex lies in the one
/// component, and nothing of the result is apart from it. Where an
/// input vertex was split into copies, the first keeps its number in the
/// splice ([`Region::output_map`]) and is the one the rest of the mesh
/// meets. Not shown (false) is not "more pieces": a region whose two
/// sheets the frame left apart joins them through the rest of the mesh.
fn stays_one_piece(mesh: &TriMesh, region: &Region, out: &TriMesh, origin: &[u32]) -> bool {
    let mut uf = UnionFind::new(out.positions.len());
    for t in &out.triangles {
        uf.union(t[0], t[1]);
        uf.union(t[0], t[2]);
    }
    let first = first_copies(origin, region.global.len());
    let mut component = None;
    for (l, _) in region
        .interface_vertices(&mesh.triangles)
        .iter()
        .enumerate()
        .filter(|(_, on)| **on)
    {
        if first[l] == u32::MAX {
            return false;
        }
        let root = uf.find(first[l]);
        if *component.get_or_insert(root) != root {
            return false;
        }
    }
    component.is_some_and(|c| out.triangles.iter().all(|t| uf.find(t[0]) == c))
}

/// With [`Options::take_out_debris`], `out`, the engine's result for
/// `region` of `mesh`, without its debris ([`crate::hidden::debris`]):
/// pieces the cut closed off (with a point of the cut or a copy of a
/// split vertex), whole within the region, smaller than [`SPECK_EDGES`]
/// of the median edge at the region's vertices (the specks
/// [`piece_growth`] would count). Their triangles go and the output's
/// vertices are renumbered in order (the engine's new points stay last);
/// [`crate::cut::CutReport::specks_removed`] counts the pieces. A result
/// in one piece costs one pass over its triangles.
fn take_out_debris(mesh: &TriMesh, region: &Region, out: &mut Outcome, options: &Options) {
    if !options.take_out_debris {
        return;
    }
    let (root, count) = pieces_welded(&out.mesh, &|_| true);
    if count < 2 {
        return;
    }
    let on_interface = region.interface_vertices(&mesh.triangles);
    // An input vertex the engine split at a pinch has several outputs;
    // only the first keeps its number in the splice (`Region::splice`),
    // so only it can join the rest of the surface, and the others are
    // new vertices as much as the cut's points are.
    let origin = &out.vertex_origin;
    let first = first_copies(origin, region.global.len());
    let keeps_its_number = |v: u32| {
        let o = origin[v as usize];
        o != u32::MAX && first[o as usize] == v
    };
    let made = |v: u32| !keeps_its_number(v);
    let interface = |v: u32| keeps_its_number(v) && on_interface[origin[v as usize] as usize];
    // The scale `piece_growth` measures specks by: the median edge of the
    // surface's triangles at the region's vertices.
    let near = |v: u32| region.local.get(v as usize).is_some_and(|&l| l != u32::MAX);
    let scale = SPECK_EDGES * median_edge_near(mesh, &near);
    let Some((gone, count)) = debris(&out.mesh, (&root, count), &made, &interface, scale) else {
        return;
    };
    let kept: Vec<[u32; 3]> = out
        .mesh
        .triangles
        .iter()
        .zip(&gone)
        .filter(|(_, g)| !**g)
        .map(|(t, _)| *t)
        .collect();
    let (compact, used) = TriMesh::of_used(&out.mesh.positions, kept);
    out.vertex_origin = used
        .iter()
        .map(|&v| out.vertex_origin[v as usize])
        .collect();
    out.mesh = compact;
    out.report.cut.specks_removed += count;
}

/// How many of the surface's edges (their median near the change) a new
/// piece must span not to be a speck. The smallest closed piece, four
/// triangles with sides of the surface's own length, spans about 1.2 of
/// them; a piece within two has no room for any shape a brush could give
/// it at that resolution (deflates over the Stanford bunny's fused haunch
/// cut off such tetrahedra, 1.4 mm across among edges of 1.4 mm).
const SPECK_EDGES: f64 = 2.0;

/// What `after` has worse than `before` in its pieces, in words: more
/// pieces hidden inside the surface or more specks (pieces within
/// [`SPECK_EDGES`] of the median edge the surface had there; both
/// [`crate::hidden`])
/// among the components near what changed (`near_before`, `near_after`
/// flag their vertices), and, for a motion that only pushes outward
/// ([`Options::outward`]), more pieces at all. The whole surface is
/// counted once (a union-find over its triangles); `before` only when
/// `after` has more than one piece.
fn piece_growth(
    before: &TriMesh,
    after: &TriMesh,
    near_before: &dyn Fn(u32) -> bool,
    near_after: &dyn Fn(u32) -> bool,
    options: &Options,
) -> Vec<String> {
    let (root_after, count_after) = pieces_welded(after, near_after);
    if count_after < 2 {
        return Vec::new();
    }
    // `before` is counted only when something needs it.
    let mut counted: Option<(Vec<u32>, usize)> = None;
    let mut worse = Vec::new();
    if options.outward {
        let count_before = counted
            .get_or_insert_with(|| pieces_welded(before, near_before))
            .1;
        if count_after > count_before {
            worse.push(format!("pieces cut loose: {count_before} -> {count_after}"));
        }
    }
    let scale = SPECK_EDGES * median_edge_near(before, near_before);
    let a = specks(after, (&root_after, count_after), near_after, scale);
    if a > 0 {
        let (root_before, count_before) =
            counted.get_or_insert_with(|| pieces_welded(before, near_before));
        let b = specks(before, (root_before, *count_before), near_before, scale);
        if a > b {
            worse.push(format!("specks cut off: {b} -> {a}"));
        }
    }
    let a = hidden_pieces(after, (&root_after, count_after), near_after);
    if a > 0 {
        let (root_before, count_before) =
            counted.get_or_insert_with(|| pieces_welded(before, near_before));
        let b = hidden_pieces(before, (root_before, *count_before), near_before);
        if a > b {
            worse.push(format!("pieces hidden inside the surface: {b} -> {a}"));
        }
    }
    worse
}

/// The engine's result for `region` of `mesh` (submesh `sub`) moving to
/// `end`: by containment number where the region is a piece of a solid
/// ([`crate::containment`]) and `containment` allows, by collision parity
/// (§3) elsewhere.
fn resolve_frame(
    mesh: &TriMesh,
    end: &[DVec3],
    region: &Region,
    sub: &TriMesh,
    options: &Options,
    motion: &Motion<'_>,
    containment: Containment<'_>,
) -> Result<Outcome, TopoError> {
    let local_end = region.gather(end);
    if containment.allowed && options.solid_guard {
        let far = containment
            .far
            .and_then(|f| Some((f, region.bounds(&mesh.positions, end)?)));
        let surroundings = Surroundings::new(mesh, &region.mask, end, far);
        if let Some(out) = by_containment(sub, &local_end, options, &surroundings, None)? {
            return Ok(out);
        }
    }
    match motion {
        Motion::Frame => topology_change(sub, &local_end, options),
        Motion::Drag {
            raw,
            collisions,
            frames,
            path,
        } => finish(
            sub,
            &sub.positions,
            &local_end,
            region.gather(raw),
            *collisions,
            options,
            std::time::Instant::now(),
            geometry(sub, &local_end, options)?,
            Path::of_drag(
                *frames,
                *path,
                Numbering {
                    global: &region.global,
                    local: &region.local,
                },
            ),
        ),
    }
}

/// Audits the region `region` of `mesh` (submesh `sub` at the start) and
/// the engine's output `out` for it, each with the ring of outside
/// triangles around the region (so that every region vertex has its whole
/// fan and every region edge all its triangles), and returns what got
/// worse, and the change of the Euler characteristic: that of the region
/// and its ring is the whole surface's, since everything else is the same
/// before and after.
fn audit_region(
    mesh: &TriMesh,
    end: &[DVec3],
    region: &Region,
    sub: &TriMesh,
    out: &Outcome,
    report: &LocalReport,
    options: &Options,
) -> Result<(Vec<String>, i64), TopoError> {
    // New contacts: the end's intersecting pairs that did not intersect at
    // the start.
    let pairs = &out.intersections.pairs;
    let was = pairs_intersect_at(sub, &sub.positions, pairs)?;
    let new_pairs: Vec<(u32, u32)> = pairs
        .iter()
        .zip(&was)
        .filter(|(_, w)| !**w)
        .map(|(p, _)| *p)
        .collect();
    let worse = if report.positions_only {
        // Same triangles: only intersections (and, in principle, a
        // triangle squashed flat) can be new.
        let mut worse = Vec::new();
        if !new_pairs.is_empty() {
            // Pairs the motion made; a curve the surface had may also
            // have slid off some: only a growing count is worse.
            let before = pair_count_at(sub, &sub.positions, usize::MAX)?;
            if pairs.len() > before {
                worse.push(format!(
                    "intersecting triangle pairs: {before} -> {}",
                    pairs.len()
                ));
            }
        }
        worse.extend(flat_growth(sub, &region.submesh(end)));
        (worse, 0)
    } else {
        let (before, after) = neighbourhoods(mesh, end, region, out);
        // Crossings: a triangle the cut made lies inside a triangle of a
        // crossing pair at the end; every other output triangle is one of
        // the region's, which crosses nothing at the end but what the
        // pairs hold. So every pair the result can have lies in the box
        // of the pairs' triangles at the end, and counting there, before
        // and after, catches every growth of the whole count (a moved
        // triangle's crossings at the start outside the box only make
        // the start's count smaller). The start is counted only when the
        // result has any; most frames that change topology leave none.
        let mut a = SurfaceAudit::topology(&after);
        let mut b = SurfaceAudit::topology(&before);
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &(s, t) in pairs {
            for v in sub.triangles[s as usize]
                .iter()
                .chain(&sub.triangles[t as usize])
            {
                let p = end[region.global[*v as usize] as usize];
                (lo, hi) = (lo.min(p), hi.max(p));
            }
        }
        a.intersecting_pairs = crossing_pairs_within(&after, (lo, hi));
        if a.intersecting_pairs > 0 {
            b.intersecting_pairs = crossing_pairs_within(&before, (lo, hi));
        }
        if options.nonmanifold_joins {
            a.nonmanifold_curves = a.nonmanifold_curves.min(b.nonmanifold_curves);
            a.pinched_vertices = a.pinched_vertices.min(b.pinched_vertices);
        }
        let mut worse = b.regressions(&a);
        worse.extend(crumple(mesh, end, region, sub, out, &was));
        (worse, a.euler() - b.euler())
    };
    Ok(worse)
}

/// The crumple rule ([`crate::hidden`]): two or more new intersection
/// curves within one piece of `mesh`, smaller than the shortest edge of
/// the region (`sub`, at the start) and within one such edge of each
/// other are handles too small to see, in words. `was` says which of the
/// pairs of `out`'s intersections (at `end`) intersected at the start.
fn crumple(
    mesh: &TriMesh,
    end: &[DVec3],
    region: &Region,
    sub: &TriMesh,
    out: &Outcome,
    was: &[bool],
) -> Option<String> {
    let x = &out.intersections;
    if x.curve_count < 2 {
        return None;
    }
    let at = |v: u32| end[region.global[v as usize] as usize];
    let scale = shortest_edge_near(sub, &|_| true);
    if tiny_new_curves(sub, &at, x, was, scale, &|_, _| true) < 2 {
        return None;
    }
    // Which curves join pieces is asked only now: the pieces of the
    // whole surface are one pass over it.
    let piece = vertex_components(mesh);
    let piece_of = |t: u32| piece[region.global[sub.triangles[t as usize][0] as usize] as usize];
    let tiny = tiny_new_curves(sub, &at, x, was, scale, &|s, t| piece_of(s) == piece_of(t));
    (tiny >= 2).then(|| format!("tiny handles: 0 -> {tiny}"))
}

/// Whether the triangles of `start` squashed flat (exactly zero area) are
/// more in `moved`, the same triangles at other positions, in words.
fn flat_growth(start: &TriMesh, moved: &TriMesh) -> Option<String> {
    let flat = |m: &TriMesh| {
        m.triangles
            .iter()
            .filter(|t| crate::audit::is_degenerate(m, **t))
            .count()
    };
    let (before, after) = (flat(start), flat(moved));
    (after > before).then(|| format!("degenerate triangles: {before} -> {after}"))
}

/// The region with its ring of outside triangles, before (at the start)
/// and after (the engine's output `out` in place of the region, at `end`
/// elsewhere), each compacted to its own vertices.
fn neighbourhoods(
    mesh: &TriMesh,
    end: &[DVec3],
    region: &Region,
    out: &Outcome,
) -> (TriMesh, TriMesh) {
    let ring: Vec<[u32; 3]> = region
        .ring(&mesh.triangles)
        .iter()
        .chain(&ring_by_position(mesh, region))
        .map(|&t| mesh.triangles[t as usize])
        .collect();
    let before = compact_of(
        region.global_triangles().chain(ring.iter().copied()),
        &|v| mesh.positions[v as usize],
    );
    // The output's vertices: region vertices by their global number, new
    // ones after every global number.
    let n = mesh.positions.len();
    let map = region.output_map(n, &out.mesh, &out.vertex_origin);
    let after = compact_of(
        out.mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| map.vertex[v as usize]))
            .chain(ring.iter().copied()),
        &|v| map.position(end, v),
    );
    (before, after)
}

/// The triangles outside `region` and its ring that have a corner at the
/// exact position of a region vertex on a rim: across an unwelded seam,
/// or a soup's neighbours. The audit joins such copies on a rim
/// ([`SurfaceAudit::topology`]), so the neighbourhood needs them to count
/// what the region's rim becomes (a seam the cut tore open, a fin at a
/// soup's corner). A region with no rim vertex (most frames on a closed
/// surface) has none, and the mesh is not scanned; else only triangles
/// with a corner in the box of the rim's vertices are hashed.
fn ring_by_position(mesh: &TriMesh, region: &Region) -> Vec<u32> {
    let ring = region.ring(&mesh.triangles);
    // The region's rim vertices: a side at them with one triangle among
    // the region's and its ring's, which hold every triangle at them.
    let mut sides: Vec<(u32, u32)> = Vec::new();
    let in_region = |v: u32| region.local[v as usize] != u32::MAX;
    for t in region
        .global_triangles()
        .chain(ring.iter().map(|&t| mesh.triangles[t as usize]))
    {
        for k in 0..3 {
            if in_region(t[k]) {
                sides.push((t[k], t[(k + 1) % 3]));
                sides.push((t[k], t[(k + 2) % 3]));
            }
        }
    }
    sides.sort_unstable();
    let mut at: rustc_hash::FxHashSet<[u64; 3]> = rustc_hash::FxHashSet::default();
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for run in sides.chunk_by(|x, y| x == y).filter(|run| run.len() == 1) {
        let p = mesh.positions[run[0].0 as usize];
        at.insert(holey_geom::position_key(p));
        (lo, hi) = (lo.min(p), hi.max(p));
    }
    if at.is_empty() {
        return Vec::new();
    }
    let in_box = |p: DVec3| p.cmpge(lo).all() && p.cmple(hi).all();
    (0..mesh.triangles.len() as u32)
        .filter(|&t| {
            !region.mask[t as usize]
                && mesh.triangles[t as usize].iter().any(|&v| {
                    let p = mesh.positions[v as usize];
                    in_box(p) && at.contains(&holey_geom::position_key(p))
                })
                && ring.binary_search(&t).is_err()
        })
        .collect()
}

/// A mesh of `triangles` (any vertex numbers) with only their vertices,
/// numbered in order of first use.
fn compact_of(
    triangles: impl Iterator<Item = [u32; 3]>,
    position: &dyn Fn(u32) -> DVec3,
) -> TriMesh {
    let mut index: rustc_hash::FxHashMap<u32, u32> = rustc_hash::FxHashMap::default();
    let mut m = TriMesh::default();
    for t in triangles {
        let local = t.map(|v| {
            *index.entry(v).or_insert_with(|| {
                m.positions.push(position(v));
                (m.positions.len() - 1) as u32
            })
        });
        m.triangles.push(local);
    }
    m
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Two triangles, one where the motion swept and one far from it, and
    /// an outcome that keeps `keep` of them (by input vertex, the way the
    /// engine's `vertex_origin` names them), the far one turned over when
    /// `flip`.
    fn outcome(keep: &[usize], flip: bool) -> (TriMesh, Outcome) {
        let sub = TriMesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                DVec3::new(10.0, 0.0, 0.0),
                DVec3::new(11.0, 0.0, 0.0),
                DVec3::new(10.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [3, 4, 5]],
        };
        let mut triangles: Vec<[u32; 3]> = keep.iter().map(|&t| sub.triangles[t]).collect();
        if flip {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        let n = sub.positions.len();
        let out = Outcome {
            mesh: TriMesh {
                positions: sub.positions.clone(),
                triangles,
            },
            report: crate::engine::Report::default(),
            raw_odd: vec![false; n],
            corrected_odd: vec![false; n],
            intersections: crate::intersect::Intersections::default(),
            vertex_origin: (0..n as u32).collect(),
        };
        (sub, out)
    }

    /// A grid of unit squares (edges 1 and √2: median 1) over [0, n]².
    fn grid(n: u32) -> TriMesh {
        TriMesh {
            positions: (0..=n)
                .flat_map(|j| (0..=n).map(move |i| DVec3::new(f64::from(i), f64::from(j), 0.0)))
                .collect(),
            triangles: holey_testkit::meshes::grid_triangles(n, n),
        }
    }

    /// [`grid`] of 6 and, over its middle at height 1, a closed
    /// tetrahedron of side `side`, numbered after the grid.
    fn grid_with_tetrahedron(side: f64) -> TriMesh {
        let mut m = grid(6);
        let n = m.positions.len() as u32;
        // The testkit's tetrahedron has sides 2√2.
        let (corners, faces) = holey_testkit::meshes::tetrahedron();
        let c = DVec3::new(3.0, 3.0, 1.0);
        let k = side / 8f64.sqrt();
        m.positions
            .extend(corners.map(|p| c + DVec3::from_array(p) * k));
        m.triangles.extend(faces.map(|t| t.map(|v| v + n)));
        m
    }

    /// A closed tetrahedron of side about `side` above the grid joins it
    /// as a piece of its own: one whose sides are the grid's edge length
    /// (about 1.2 edges across) is a speck, one three times that is not.
    #[test]
    fn a_tetrahedron_at_the_surfaces_edge_length_is_a_speck() {
        let before = grid(6);
        for (side, speck) in [(1.0, true), (3.0, false)] {
            let after = grid_with_tetrahedron(side);
            let worse = piece_growth(&before, &after, &|_| true, &|_| true, &Options::default());
            assert_eq!(
                worse.contains(&"specks cut off: 0 -> 1".to_owned()),
                speck,
                "side {side}: {worse:?}"
            );
        }
    }

    /// Where an output tetrahedron's vertices come from.
    #[derive(Clone, Copy, Debug)]
    enum Corners {
        /// Points the cut made.
        Made,
        /// Second copies of input vertices 0 to 3 (a pinch split).
        Copies,
        /// Input vertices of their own: the tetrahedron was there before.
        Input,
    }

    /// The grid and, over its middle at height 1, a closed tetrahedron of
    /// side `side`, as the engine's output for a region of the whole
    /// input, with the input it came from.
    fn grid_and_tetrahedron(side: f64, corners: Corners) -> (TriMesh, Outcome) {
        let with_tetrahedron = grid_with_tetrahedron(side);
        let n = grid(6).positions.len() as u32;
        let (_, mut out) = outcome(&[], false);
        out.mesh = with_tetrahedron.clone();
        out.vertex_origin = (0..n).collect();
        out.vertex_origin.extend((0..4).map(|i| match corners {
            Corners::Made => u32::MAX,
            Corners::Copies => i,
            Corners::Input => n + i,
        }));
        let input = match corners {
            Corners::Input => with_tetrahedron,
            Corners::Made | Corners::Copies => grid(6),
        };
        (input, out)
    }

    /// A speck the cut closed off (with its points or with copies of
    /// split vertices) is taken out of the result, its triangles and
    /// vertices, and the report counts it; one three times the grid's
    /// edge across stays, and so does a speck that was there before.
    #[test]
    fn debris_the_cut_closed_off_is_taken_out() {
        for (side, corners, goes) in [
            (1.0, Corners::Made, true),
            (1.0, Corners::Copies, true),
            (3.0, Corners::Made, false),
            (1.0, Corners::Input, false),
        ] {
            let (input, mut out) = grid_and_tetrahedron(side, corners);
            let everything = Region::select(
                &input.triangles,
                &input.positions,
                &input.positions,
                (DVec3::NEG_INFINITY, DVec3::INFINITY),
            );
            let debris_on = Options {
                take_out_debris: true,
                ..Options::default()
            };
            take_out_debris(&input, &everything, &mut out, &debris_on);
            // Off, the same output is left alone.
            let (_, mut untouched) = grid_and_tetrahedron(side, corners);
            let before = untouched.mesh.clone();
            take_out_debris(&input, &everything, &mut untouched, &Options::default());
            assert_eq!(untouched.mesh, before);
            let grid_triangles = grid(6).triangles.len();
            let left = if goes { 0 } else { 4 };
            let what = format!("side {side}, {corners:?}");
            assert_eq!(
                out.mesh.triangles.len(),
                grid_triangles + 4 - 4 * usize::from(goes),
                "{what}"
            );
            assert_eq!(
                out.mesh.positions.len(),
                grid(6).positions.len() + left,
                "{what}"
            );
            assert_eq!(out.vertex_origin.len(), out.mesh.positions.len(), "{what}");
            assert_eq!(out.report.cut.specks_removed, usize::from(goes), "{what}");
            out.mesh.check().unwrap();
        }
    }

    /// A triangle outside the swept box collided with nothing: deleting it
    /// is worse, keeping it (either way round) is not, and deleting the
    /// one the motion reached is for the other audits to judge.
    #[test]
    fn deleting_a_triangle_the_motion_never_reached_is_worse() {
        let swept = (DVec3::splat(-0.5), DVec3::splat(1.5));
        let (sub, out) = outcome(&[0], false);
        let said = unreached_deleted(&sub, &out, swept).unwrap();
        assert!(said.ends_with(": 1"), "{said}");
        assert_eq!(
            crate::audit::in_plain_words(&said),
            "delete surface far from where the brush moved it"
        );
        let (sub, out) = outcome(&[], false);
        assert!(unreached_deleted(&sub, &out, swept).is_some());
        for (keep, flip) in [(&[0, 1][..], false), (&[1], false), (&[0, 1], true)] {
            let (sub, out) = outcome(keep, flip);
            assert_eq!(unreached_deleted(&sub, &out, swept), None, "{keep:?}");
        }
        // A box that reaches both: nothing is far.
        let (sub, out) = outcome(&[], false);
        let everywhere = (DVec3::splat(-1.0), DVec3::splat(12.0));
        assert_eq!(unreached_deleted(&sub, &out, everywhere), None);
    }

    /// Spheres of 16 × 10 as one mesh, `(centre, radius)` each, with three
    /// more far off (so that the two a motion moves are under half the
    /// mesh, the share a region must stay below).
    fn spheres_and_far_ones(spheres: &[([f64; 3], f64)]) -> TriMesh {
        let mut all = spheres.to_vec();
        all.extend((0..3).map(|k| ([40.0 + 5.0 * f64::from(k), 0.0, 0.0], 1.0)));
        let (p, triangles) = holey_testkit::uv_spheres(16, 10, &all);
        TriMesh {
            positions: p.into_iter().map(DVec3::from_array).collect(),
            triangles,
        }
    }

    /// The winding number of the triangles `tris` of `positions` at `p`:
    /// their solid angles (Van Oosterom and Strackee's formula) over 4π.
    fn winding_at(positions: &[DVec3], tris: &[[u32; 3]], p: DVec3) -> f64 {
        let sum: f64 = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| positions[v as usize] - p);
                let (la, lb, lc) = (a.length(), b.length(), c.length());
                let num = a.dot(b.cross(c));
                let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
                2.0 * num.atan2(den)
            })
            .sum();
        sum / (4.0 * std::f64::consts::PI)
    }

    /// A sphere pushed deep into another in one motion longer than their
    /// edges (as a sculpting frame of several dabs is) is taken whole: the
    /// motion's collision parity and the containment number at its end
    /// agree on every vertex. The result is the union: closed, with no
    /// edge of more than two triangles, the two spheres one piece (the
    /// Euler characteristic 2 less), and
    /// its winding number at points of a grid 1 inside the union of the
    /// two moved spheres (by their own winding numbers, computed here)
    /// and 0 outside.
    #[test]
    fn a_long_fuse_where_parity_and_containment_agree_is_taken_whole() {
        let mut mesh = spheres_and_far_ones(&[([0.0, 0.0, 0.0], 1.0), ([2.6, 0.0, 0.0], 0.8)]);
        let second = 130..260u32;
        let shift = DVec3::new(-1.3, 0.05, 0.03);
        let end: Vec<DVec3> = (0..mesh.positions.len() as u32)
            .map(|v| {
                mesh.positions[v as usize]
                    + if second.contains(&v) {
                        shift
                    } else {
                        DVec3::ZERO
                    }
            })
            .collect();
        let input = mesh.clone();
        let report =
            topology_change_guarded_if_sure(&mut mesh, &end, &Options::default(), &[], None)
                .unwrap()
                .expect("a fuse both readings agree on is sure");
        assert!(!report.local.positions_only && report.local.new_vertices > 0);
        // Two spheres (χ = 2 each) became one: χ 4 -> 2.
        assert_eq!(report.euler_change, -2);
        let degrees = holey_testkit::edge_degrees(&mesh.triangles);
        assert!(degrees.values().all(|&d| d == 2), "closed and manifold");
        assert_eq!(holey_testkit::components(&mesh.triangles), 4);
        let (mut inside, mut outside) = (0, 0);
        for i in 0..24 {
            for j in 0..12 {
                for k in 0..12 {
                    let p = DVec3::new(-1.2, -1.2, -1.2)
                        + DVec3::new(f64::from(i), f64::from(j), f64::from(k)) * 0.11;
                    let expected = winding_at(&end, &input.triangles, p);
                    if (expected - expected.round()).abs() > 0.05 {
                        continue;
                    }
                    let expected = if expected > 0.5 { 1.0 } else { 0.0 };
                    let got = winding_at(&mesh.positions, &mesh.triangles, p);
                    assert!(
                        (got - expected).abs() < 0.05,
                        "at {p}: {got}, not {expected}"
                    );
                    if expected > 0.5 {
                        inside += 1;
                    } else {
                        outside += 1;
                    }
                }
            }
        }
        assert!(
            inside > 300 && outside > 300,
            "{inside} inside, {outside} outside"
        );
    }

    /// The fuse above in a window over the two spheres: the same result
    /// as without one, and the window, told what the splice wrote, lists
    /// what it must of the result. A window of another mesh is not read:
    /// the same result again, and the window is not kept.
    #[test]
    fn a_fuse_in_a_window_is_the_fuse_without_one() {
        let mesh = spheres_and_far_ones(&[([0.0, 0.0, 0.0], 1.0), ([2.6, 0.0, 0.0], 0.8)]);
        let second = 130..260u32;
        let shift = DVec3::new(-1.3, 0.05, 0.03);
        let end: Vec<DVec3> = (0..mesh.positions.len() as u32)
            .map(|v| {
                let p = mesh.positions[v as usize];
                if second.contains(&v) { p + shift } else { p }
            })
            .collect();
        let options = Options::default();
        let mut whole = mesh.clone();
        let want = topology_change_guarded_holding(&mut whole, &end, &options, &[], None).unwrap();
        assert!(!want.local.positions_only);
        let mut windowed = mesh.clone();
        let mut w = Window::build(&mesh, DVec3::splat(-1.5), DVec3::new(3.5, 1.5, 1.5));
        assert!(w.triangles().len() < mesh.triangles.len());
        let got =
            topology_change_guarded_holding_in(&mut windowed, &end, &options, &[], None, &mut w)
                .unwrap();
        assert!(windowed == whole, "the windowed fuse differs");
        assert_eq!(got.euler_change, want.euler_change);
        assert!(got.window_kept);
        assert!(w.fits(&windowed));
        assert_eq!(w.misses(&windowed), None);
        // A window of a smaller mesh.
        let other = spheres_and_far_ones(&[([0.0, 0.0, 0.0], 1.0)]);
        let mut stranger = Window::build(&other, DVec3::splat(-1.5), DVec3::splat(1.5));
        assert!(!stranger.fits(&mesh));
        let mut again = mesh.clone();
        let r = topology_change_guarded_holding_in(
            &mut again,
            &end,
            &options,
            &[],
            None,
            &mut stranger,
        )
        .unwrap();
        assert!(
            again == whole,
            "a window of another mesh changed the result"
        );
        assert!(!r.window_kept);
    }

    /// A triangle folded over its hinge and a vertex pushed through a
    /// sheet of its own: the motion's exact collision parity (the engine's
    /// CCD) finds both vertices odd, and the parity across sheets reads
    /// only the second. The flap `(v, a, b)` turns about `ab` until `v` has
    /// passed through the triangle `(a, w, b)` on the other side of the
    /// hinge (at t = 3/4 of the motion, at (0.5, −0.2, 0)); `u` goes
    /// straight down through the triangle `(p, q, r)` far from it.
    #[test]
    fn a_triangle_folded_over_its_hinge_is_not_read_as_a_passage() {
        let [a, b, w, v] = [0, 1, 2, 3];
        let [p, q, r, u] = [4, 5, 6, 7];
        let start = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, -1.0, 0.0),
            DVec3::new(0.5, 1.0, 0.3),
            DVec3::new(4.0, -1.0, 0.0),
            DVec3::new(6.0, -1.0, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
            DVec3::new(5.0, 0.0, 1.0),
            DVec3::new(5.2, 0.5, 2.0),
            DVec3::new(4.8, 0.5, 2.0),
        ];
        let mut end = start.clone();
        end[v as usize] = DVec3::new(0.5, -0.6, -0.1);
        end[u as usize] = DVec3::new(5.0, 0.0, -1.0);
        let sub = TriMesh {
            positions: start.clone(),
            triangles: vec![[v, a, b], [a, w, b], [p, q, r], [u, 8, 9]],
        };
        let ccd = holey_geom::ccd::vertex_parities(
            &start,
            &end,
            &sub.triangles,
            &crate::engine::ccd_options(&Options::default(), 0),
        )
        .unwrap();
        assert!(ccd.odd[v as usize] && ccd.odd[u as usize], "{:?}", ccd.odd);
        let parity = parity_across_sheets(&sub, &ccd.odd_pairs);
        let expected: Vec<Option<bool>> = (0..start.len() as u32)
            .map(|x| if x == v { None } else { Some(x == u) })
            .collect();
        assert_eq!(parity, expected);
    }

    /// A small sphere carried whole into a larger one in one motion crosses
    /// nothing at the end, so the containment number deletes nothing, but
    /// every vertex of it passed the larger one's surface once (odd
    /// parity): the readings disagree, the motion is not sure as one frame,
    /// and the mesh is left as it was for the caller to step.
    #[test]
    fn a_part_carried_whole_into_a_solid_is_not_taken_whole() {
        let mut mesh = spheres_and_far_ones(&[([0.0, 0.0, 0.0], 1.0), ([2.6, 0.05, 0.03], 0.3)]);
        let second = 130..260u32;
        let end: Vec<DVec3> = (0..mesh.positions.len() as u32)
            .map(|v| {
                let p = mesh.positions[v as usize];
                if second.contains(&v) {
                    p - DVec3::new(2.5, 0.0, 0.0)
                } else {
                    p
                }
            })
            .collect();
        let input = mesh.clone();
        let sure = topology_change_guarded_if_sure(&mut mesh, &end, &Options::default(), &[], None)
            .unwrap();
        assert!(sure.is_none());
        assert_eq!(mesh, input);
    }
}
