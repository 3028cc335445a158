//! The drag of §4: raw collision parity accumulated over the frames of a
//! stroke, the corrected parity on demand for the live preview, and one
//! topology change at release, each on the region the motion reached
//! (see [`crate::topology_change_local`]).

use std::time::Instant;

use glam::DVec3;
use holey_geom::ccd::vertex_parities;

use crate::drag_path::{DragPath, Numbering};
use crate::engine::{
    Options, Outcome, Path, TopoError, ccd_options, check, finish, geometry, static_stage,
};
use crate::guard::{Motion, run_once};
use crate::local::{
    Bounds, LocalReport, Region, Spliced, from_whole, swept_box, union, with_margin,
};
use crate::mesh::TriMesh;

/// Accumulates raw collision parity over the frames of a drag (§4): while
/// the mouse is held, each frame runs collision detection only; the
/// corrected parity can be computed every frame for preview; the topology
/// change runs once, at release, with the accumulated parity. Dragging
/// back to where the drag began accumulates an even number of collisions
/// everywhere, which cancels the change.
#[derive(Clone, Debug)]
pub struct Accumulator {
    mesh: TriMesh,
    current: Vec<DVec3>,
    raw: Vec<bool>,
    frame: u64,
    collisions: usize,
    tests: u64,
    seconds: f64,
    options: Options,
    /// The box of everything that moved so far: collisions, and so odd
    /// vertices and new intersections, lie inside it.
    swept: Option<Bounds>,
    /// What moved in each frame, so that points sampled at release follow
    /// the drag's true path (`crate::drag_path`); `None` once the drag
    /// moved more than that keeps.
    path: Option<DragPath>,
    /// The guarded release computed for the last preview, at frame
    /// `.0`: the release reuses it when nothing moved since.
    last_release: Option<(u64, std::sync::Arc<Release>)>,
}

/// What releasing a drag does (see [`Accumulator::release_guarded`]).
#[derive(Clone, Debug)]
pub struct Release {
    /// The surface after the release.
    pub mesh: TriMesh,
    /// The engine's report (of the attempt kept).
    pub report: LocalReport,
    /// Per vertex of the drag's mesh: it vanishes at release.
    pub vanishing: Vec<bool>,
    /// Empty when the release is clean; otherwise what the change would
    /// have made worse, in words, and the release undoes the drag.
    pub refused: Vec<String>,
}

impl Accumulator {
    /// Starts a drag of `mesh` at its positions.
    pub fn new(mesh: TriMesh, options: Options) -> Result<Accumulator, TopoError> {
        mesh.check()?;
        let n = mesh.positions.len();
        Ok(Accumulator {
            current: mesh.positions.clone(),
            mesh,
            raw: vec![false; n],
            frame: 0,
            collisions: 0,
            tests: 0,
            seconds: 0.0,
            options,
            swept: None,
            path: Some(DragPath::default()),
            last_release: None,
        })
    }

    /// Moves every vertex linearly from its current position to `next`,
    /// accumulating collision parity. Only the triangles the motion can
    /// reach are tested (see [`crate::topology_change_local`]), so a frame costs what
    /// moves, plus a linear scan.
    pub fn advance(&mut self, next: &[DVec3]) -> Result<(), TopoError> {
        check(&self.mesh, next)?;
        let t = Instant::now();
        let tris = &self.mesh.triangles;
        let moved = swept_box(tris, &self.current, next);
        if let Some(bx) = moved {
            let region = Region::select(tris, &self.current, next, bx);
            // Every vertex that moved is one of the region's.
            let among = region.worth_it().then_some(region.global.as_slice());
            if let Some(path) = &mut self.path
                && !path.record(&self.current, next, among)
            {
                self.path = None;
            }
            let opts = ccd_options(&self.options, self.frame);
            let (odd, pairs, tests) = if region.worth_it() {
                let ccd = vertex_parities(
                    &region.gather(&self.current),
                    &region.gather(next),
                    &region.triangles,
                    &opts,
                )?;
                let n = self.raw.len();
                (
                    region.scatter(&ccd.odd, n, false),
                    ccd.odd_pairs.len(),
                    ccd.candidates,
                )
            } else {
                let ccd = vertex_parities(&self.current, next, tris, &opts)?;
                (ccd.odd, ccd.odd_pairs.len(), ccd.candidates)
            };
            for (r, o) in self.raw.iter_mut().zip(&odd) {
                *r ^= o;
            }
            self.collisions += pairs;
            self.tests += tests;
            self.swept = union(self.swept, moved);
        }

        self.seconds += t.elapsed().as_secs_f64();
        self.current = next.to_vec();
        self.frame += 1;
        Ok(())
    }

    /// Frames accumulated so far.
    pub fn frames(&self) -> u64 {
        self.frame
    }

    /// The accumulated raw parity (`true` = odd).
    pub fn raw_parity(&self) -> &[bool] {
        &self.raw
    }

    /// The current positions.
    pub fn positions(&self) -> &[DVec3] {
        &self.current
    }

    /// The corrected parity at the current positions, for live preview.
    /// Computed on the region everything moved through, with a margin.
    pub fn corrected_parity(&self) -> Result<Vec<bool>, TopoError> {
        let n = self.raw.len();
        let Some(bx) = self.swept else {
            return Ok(vec![false; n]);
        };
        let region = Region::select(
            &self.mesh.triangles,
            &self.mesh.positions,
            &self.current,
            with_margin(bx),
        );
        if !region.worth_it() {
            return Ok(
                static_stage(&self.mesh, &self.current, &self.raw, &self.options)?.corrected,
            );
        }
        let sub = region.submesh(&self.mesh.positions);
        let s = static_stage(
            &sub,
            &region.gather(&self.current),
            &region.gather(&self.raw),
            &self.options,
        )?;
        Ok(region.scatter(&s.corrected, n, false))
    }

    /// What releasing the drag now would do, computed as the release
    /// computes it (so the preview of §4 shows exactly that): by
    /// containment number where the dragged region is a piece of a solid,
    /// by the accumulated parity elsewhere, guarded like a sculpting frame
    /// ([`crate::topology_change_guarded`]). A release that would leave the surface worse
    /// is refused: the drag is undone and nothing vanishes.
    pub fn preview(&mut self) -> Result<std::sync::Arc<Release>, TopoError> {
        if let Some((frame, r)) = &self.last_release
            && *frame == self.frame
        {
            return Ok(r.clone());
        }
        let run = run_once(
            &self.mesh,
            &self.current,
            &self.options,
            &Motion::Drag {
                raw: &self.raw,
                collisions: (self.collisions, self.tests, self.seconds),
                frames: self.frame,
                path: self.path.as_ref(),
            },
            None,
            None,
        )?;
        let release = if run.worse.is_empty() {
            Release {
                vanishing: run.report.corrected_odd.clone(),
                mesh: run.made.into_mesh(&self.mesh, &self.current),
                report: run.report,
                refused: Vec::new(),
            }
        } else {
            Release {
                vanishing: vec![false; self.mesh.positions.len()],
                mesh: self.mesh.clone(),
                report: LocalReport::no_motion(self.mesh.positions.len()),
                refused: run.worse,
            }
        };
        let release = std::sync::Arc::new(release);
        self.last_release = Some((self.frame, release.clone()));
        Ok(release)
    }

    /// Ends the drag: the surface after the guarded topology change (see
    /// [`Accumulator::preview`], whose result it reuses when nothing moved
    /// since). A drag that came back to its start gives the start surface.
    pub fn release_guarded(mut self) -> Result<Release, TopoError> {
        let r = self.preview()?;
        self.last_release = None;
        Ok(std::sync::Arc::try_unwrap(r).unwrap_or_else(|shared| (*shared).clone()))
    }

    /// [`Accumulator::release`] run on the region everything moved
    /// through (with a margin) and spliced into the rest of the mesh; the
    /// whole mesh when the region is large or the splice would not be
    /// exact (see [`crate::topology_change_local`]).
    pub fn release_local(self) -> Result<(TriMesh, LocalReport), TopoError> {
        let started = Instant::now();
        let n = self.raw.len();
        let Some(bx) = self.swept else {
            let mesh = TriMesh {
                positions: self.current,
                triangles: self.mesh.triangles,
            };
            return Ok((mesh, LocalReport::no_motion(n)));
        };
        let region = Region::select(
            &self.mesh.triangles,
            &self.mesh.positions,
            &self.current,
            with_margin(bx),
        );
        if region.worth_it() {
            let sub = region.submesh(&self.mesh.positions);
            let end = region.gather(&self.current);
            let out = finish(
                &sub,
                &sub.positions,
                &end,
                region.gather(&self.raw),
                (self.collisions, self.tests, self.seconds),
                &self.options,
                started,
                geometry(&sub, &end, &self.options)?,
                Path::of_drag(
                    self.frame,
                    self.path.as_ref(),
                    Numbering {
                        global: &region.global,
                        local: &region.local,
                    },
                ),
            )?;
            match region.resolve(&self.mesh, &self.current, &out, self.options.solid_guard) {
                (report, Spliced::PositionsOnly) => {
                    let mesh = TriMesh {
                        positions: self.current,
                        triangles: self.mesh.triangles,
                    };
                    return Ok((mesh, report));
                }
                (report, Spliced::Mesh(m)) => return Ok((m, report)),
                (_, Spliced::NotExact) => {}
            }
        }
        let mesh = self.mesh.clone();
        Ok(from_whole(&mesh, self.release()?))
    }

    /// Applies the topology change with the accumulated parity.
    pub fn release(self) -> Result<Outcome, TopoError> {
        let started = Instant::now();
        let geometry = geometry(&self.mesh, &self.current, &self.options)?;
        finish(
            &self.mesh,
            &self.mesh.positions,
            &self.current,
            self.raw,
            (self.collisions, self.tests, self.seconds),
            &self.options,
            started,
            geometry,
            Path::of_drag(self.frame, self.path.as_ref(), Numbering::WHOLE),
        )
    }
}
