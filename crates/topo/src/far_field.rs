//! The winding numbers of the surface around a sculpting frame, kept from
//! one frame of a stroke to the next.
//!
//! A frame resolved by containment number ([`crate::containment`]) needs
//! the winding number of the whole surface outside its region at its
//! pieces' samples, and the orientation of the whole surface. Up to
//! [`FEW_POINTS`] samples that is one pass over every triangle; beyond,
//! an octree built over them ([`crate::winding::WindingField`]), at every
//! such ask: on the 1.1M-triangle bunny 110–150 ms, twice in the slowest
//! frame of its recorded stroke (a whole try, then the stepped run on a
//! surface the first step changed). Between two frames of a stroke,
//! though, the surface changes only where the brush went.
//!
//! So a stroke keeps a snapshot of its surface with an octree over it
//! (whose cells also keep the box and signed volume of their triangles),
//! and a box `B` that every change since the snapshot lies in: every
//! triangle the surface gained, lost, or whose corners moved has its box
//! (at its positions before or after) meeting `B`. Then the triangles
//! whose box misses `B` are the same in the snapshot and in the surface
//! now, and
//!
//! ```text
//! w(p) = Σ_{t in the snapshot, box(t) ∩ B' = ∅} Ω_t(p) / 4π
//!      + Σ_{t in the surface now, box(t) ∩ B' ≠ ∅, t outside the region} Ω_t(p) / 4π
//! ```
//!
//! with `B' = B ∪` the box of the region's vertices at the frame's start
//! and end, so that every triangle of the region (and every triangle the
//! frame moves) falls in the second sum, where it is left out. The first
//! sum is the octree's, each cell whose box meets `B'` summed without the
//! triangles that meet it (found once per ask, [`Octree::residue`]) and
//! still taken by its dipole when far; the second is a pass that tests
//! each triangle's box and sums the few that meet it (20–28 ms on the
//! 1.1M bunny, where the octree took 110–150), or, past [`FEW_POINTS`]
//! points, builds a field over the ones that meet it. Both keep an ask's
//! cost per point independent of how many triangles `B'` holds: after
//! three strokes on the 1.1M bunny at the modeller's own remeshing
//! length, it held 90k, and a frame whose cut left 1,878 pieces asked
//! at as many points (10 s in one frame when every point opened every
//! cell meeting `B'` and summed every triangle in it; 30 ms now).
//! The signed volume splits the same way (cells keep theirs). The caller
//! reports what each frame changed ([`FarField::changed_within`]); the
//! snapshot is rebuilt when `B'` holds a quarter of it.
//!
//! The second sum's pass reads a code byte per corner, and corners only
//! of the triangles that meet `B'`, where one pass over the triangles
//! for a handful of samples reads every triangle's corners. So on a
//! surface of at least [`EVERY_ASK_FROM`] triangles the field answers
//! every ask: on the 1.1M-triangle bunny 6–15 ms against 18–28 ms for two
//! to six samples, on the 70k one 0.6–1.4 ms against 1.2–1.9 ms. A build
//! (140–300 ms on the 1.1M bunny, 12–16 ms on the 70k one) would be a
//! frame's longest wait, so the stroke starts it on a thread of its own
//! as its first frame begins ([`FarField::prepare`]), and again when an
//! ask finds the snapshot stale; the next ask takes it over, waiting for
//! it if need be, so the answers never depend on the build's timing. On
//! a smaller surface the pass is cheap: the field answers only asks of
//! more than [`FEW_POINTS`] samples, where the alternative is an octree
//! built for that ask alone, and is built at the first of them.
//!
//! A field may outlive its stroke: a session that hands it to the next
//! stroke on the surface the last one left (`holey_sculpt`'s session and
//! the modeller's document do) saves that stroke the build.

use std::sync::Mutex;

use glam::DVec3;
use holey_geom::Aabb;
use holey_mesh::PARALLEL_RUN;
use rayon::prelude::*;

use crate::local::Bounds;
use crate::mesh::TriMesh;
use crate::winding::{FEW_POINTS, Octree, Residue, WindingField, classified_sums};
use crate::window::{corners_meet_box, outcodes};

/// A snapshot is rebuilt when more than this share of its triangles lies
/// in the changed box: the pass over those costs as much as one over all.
const STALE_SHARE: f64 = 0.25;

/// From this many triangles a field answers asks at any number of points
/// (module documentation): the kept query then costs about half of one
/// pass over the triangles (measured on the 70k and the 1.1M bunny),
/// and a session's strokes share one build, made beside the frames.
pub const EVERY_ASK_FROM: usize = 1 << 15;

/// A stroke's far field: winding numbers and orientation of a surface
/// that changes a little at a time (module documentation). It answers
/// the frames that ask at more than [`FEW_POINTS`] points, for which a
/// frame built an octree over the whole surface at every ask (twice in
/// the slowest frame of the 1.1M bunny's recorded stroke: a whole try,
/// then the stepped run), and on a surface of at least
/// [`EVERY_ASK_FROM`] triangles every ask. It is built at the first ask
/// of more than [`FEW_POINTS`] points, or beside the frames from
/// [`FarField::prepare`] on a large surface, and again only when the
/// changes cover a quarter of it.
#[derive(Default)]
pub struct FarField {
    state: Mutex<State>,
}

#[derive(Default)]
struct State {
    snapshot: Option<Snapshot>,
    /// The box every change since the snapshot lies in.
    changed: Option<Bounds>,
    /// Snapshots built so far.
    builds: usize,
    /// Asks answered so far.
    answers: usize,
    /// A snapshot being built on a thread of its own ([`FarField::prepare`]).
    pending: Option<Pending>,
}

/// A snapshot being built beside the frames, and the box every change
/// since the surface it copies lies in.
struct Pending {
    build: std::thread::JoinHandle<Snapshot>,
    changed: Option<Bounds>,
}

impl Pending {
    /// Starts building the snapshot of `mesh` on a thread of its own,
    /// whose parallel passes run in a pool of one thread so that they
    /// take turns with the frames' rather than queueing before them.
    /// `None` when no thread can be started.
    fn start(mesh: &TriMesh) -> Option<Pending> {
        let (positions, triangles) = (mesh.positions.clone(), mesh.triangles.clone());
        let build = std::thread::Builder::new()
            .name("holey-far-field".into())
            .spawn(move || {
                let tree = |triangles: &[[u32; 3]], positions: &[DVec3]| {
                    Octree::with_boxes(triangles, &|v| positions[v as usize])
                };
                let tree = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
                    Ok(pool) => pool.install(|| tree(&triangles, &positions)),
                    Err(_) => tree(&triangles, &positions),
                };
                Snapshot {
                    positions,
                    triangles,
                    tree,
                }
            })
            .ok()?;
        Some(Pending {
            build,
            changed: None,
        })
    }
}

impl State {
    /// Takes over the snapshot being built, waiting for it: every ask
    /// after [`FarField::prepare`] reads it, so which asks the field
    /// answers does not depend on how long the build took.
    fn install_pending(&mut self) {
        if let Some(p) = self.pending.take() {
            // A build that panicked leaves no snapshot: the next ask of
            // many points builds one in place.
            self.snapshot = p.build.join().ok();
            self.changed = p.changed;
            self.builds += usize::from(self.snapshot.is_some());
        }
    }

    /// The changed box with the box `region` of a frame's region: every
    /// triangle that differs between the snapshot and the surface at the
    /// frame's end meets it.
    fn dirty(&self, region: Bounds) -> Aabb {
        let (lo, hi) = self
            .changed
            .map_or(region, |c| (c.0.min(region.0), c.1.max(region.1)));
        Aabb::new(lo, hi)
    }
}

/// The surface as it was, with its octree.
struct Snapshot {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    tree: Octree,
}

impl std::fmt::Debug for FarField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // Without waiting for a build in progress.
        let state = self.state.lock();
        let (built, building, builds) = state.as_ref().map_or((false, false, 0), |s| {
            (s.snapshot.is_some(), s.pending.is_some(), s.builds)
        });
        f.debug_struct("FarField")
            .field("built", &built)
            .field("building", &building)
            .field("builds", &builds)
            .finish()
    }
}

impl FarField {
    /// An empty field: nothing is built until a frame asks.
    pub fn new() -> FarField {
        FarField::default()
    }

    /// Notes that the surface changed within `b`: every triangle it
    /// gained, lost or moved has its box (at its positions before or
    /// after) meeting `b`. A caller that changes the surface and does not
    /// say so gets wrong winding numbers; one that cannot bound a change
    /// passes the infinite box, and the snapshot is rebuilt when next
    /// asked.
    pub fn changed_within(&self, b: (DVec3, DVec3)) {
        if let Ok(mut state) = self.state.lock() {
            if state.snapshot.is_some() {
                state.changed = crate::local::union(state.changed, Some(b));
            }
            if let Some(p) = state.pending.as_mut() {
                p.changed = crate::local::union(p.changed, Some(b));
            }
        }
    }

    /// On a surface of at least [`EVERY_ASK_FROM`] triangles with no
    /// snapshot kept or being built, starts building one of `mesh` (the
    /// surface as it is now) on a thread of its own, so that the
    /// frames' asks need not wait for a build of 140–300 ms (the 1.1M
    /// bunny) when they come; the next ask takes it over, waiting if it
    /// is not done. A stroke calls this as each frame begins; on a
    /// smaller surface it does nothing.
    pub fn prepare(&self, mesh: &TriMesh) {
        if mesh.triangles.len() < EVERY_ASK_FROM {
            return;
        }
        if let Ok(mut state) = self.state.lock()
            && state.snapshot.is_none()
            && state.pending.is_none()
        {
            state.pending = Pending::start(mesh);
        }
    }

    /// Whether a snapshot is kept (for tests and measurements).
    pub fn is_built(&self) -> bool {
        self.state.lock().is_ok_and(|mut s| {
            s.install_pending();
            s.snapshot.is_some()
        })
    }

    /// How many snapshots were built: the first, and one for each time
    /// the changes covered a quarter of the last (for tests and
    /// measurements).
    pub fn builds(&self) -> usize {
        self.state.lock().map_or(0, |mut s| {
            s.install_pending();
            s.builds
        })
    }

    /// How many asks the field answered (for tests and measurements).
    pub fn answers(&self) -> usize {
        self.state.lock().map_or(0, |s| s.answers)
    }

    /// What the frame asks ([`Ask`]).
    /// `None` for up to [`FEW_POINTS`] points, where one pass over the
    /// triangles serves and the caller sums them itself, unless the
    /// surface has at least [`EVERY_ASK_FROM`] triangles and a snapshot
    /// is kept or being built that the changes have not made stale (a
    /// stale one is then dropped and built again beside the frames).
    pub(crate) fn winding_numbers_and_volume_at(&self, ask: &Ask<'_>) -> Option<(Vec<f64>, f64)> {
        let Ask {
            mesh,
            region,
            points,
            ..
        } = *ask;
        let few = points.len() <= FEW_POINTS;
        if few && mesh.triangles.len() < EVERY_ASK_FROM {
            return None;
        }
        let mut state = self.state.lock().ok()?;
        state.install_pending();
        // How much of the snapshot the changes cover, the volume of the
        // rest, and the sums of the cells they meet without them, in one
        // walk down its octree.
        let split = |state: &State| {
            state.snapshot.as_ref().map(|s| {
                let residue = s.tree.residue(
                    &s.triangles,
                    &|v| s.positions[v as usize],
                    &state.dirty(region),
                );
                (
                    residue.meeting as f64 > STALE_SHARE * s.triangles.len() as f64,
                    residue,
                )
            })
        };
        let residue = match split(&state) {
            Some((false, residue)) => residue,
            // A few points never pay for a build: one pass serves them,
            // and a snapshot of the surface is built beside the frames
            // for the asks after (`prepare`).
            _ if few => {
                // (Nothing is pending here: the ask took it over above.)
                state.snapshot = None;
                state.changed = None;
                state.pending = Pending::start(mesh);
                return None;
            }
            _ => {
                // The snapshot at the frame's start: only the region differs
                // at its end, and the region is in the changed box.
                let tree = Octree::with_boxes(&mesh.triangles, &|v| mesh.positions[v as usize]);
                state.snapshot = Some(Snapshot {
                    positions: mesh.positions.clone(),
                    triangles: mesh.triangles.clone(),
                    tree,
                });
                state.changed = None;
                state.builds += 1;
                split(&state)?.1
            }
        };
        state.answers += 1;
        kept_query(&state, ask, &residue)
    }
}

/// What a frame asks of a [`FarField`]: the winding numbers at `points` of
/// the triangles of `mesh` that `inside` does not flag, at `end` (equal
/// to `mesh`'s positions outside the region), and the signed volume of
/// all of them at `end`; `region` bounds the region's vertices at the
/// start and at `end`.
#[derive(Clone, Copy)]
pub(crate) struct Ask<'a> {
    pub mesh: &'a TriMesh,
    pub inside: &'a [bool],
    pub end: &'a [DVec3],
    pub region: Bounds,
    pub points: &'a [DVec3],
}

/// [`FarField::winding_numbers_and_volume_at`] on a kept snapshot, whose
/// triangles `residue` splits by the changed box.
fn kept_query(state: &State, ask: &Ask<'_>, residue: &Residue) -> Option<(Vec<f64>, f64)> {
    let Ask {
        mesh,
        inside,
        end,
        region,
        points,
    } = *ask;
    let s = state.snapshot.as_ref()?;
    let b = state.dirty(region);
    let old = |v: u32| s.positions[v as usize];
    // The triangles of the surface now whose box meets the changed box:
    // outside the region they count in the winding numbers, all of them
    // in the volume. A triangle's box misses it exactly when its corners'
    // outcodes share a bit (`corners_meet`), so the pass reads a code
    // byte per corner and only the meeting triangles' corners.
    let code = outcodes(&b, end);
    let meets = |tri: &[u32; 3]| corners_meet_box(&code, tri);
    let (mut w, volume_now) = if points.len() <= FEW_POINTS {
        classified_sums(&mesh.triangles, &|v| end[v as usize], points, &|t, tri| {
            let meets = meets(tri);
            (meets && !inside[t], meets)
        })
    } else {
        // Many points: the meeting triangles outside the region count by
        // a field of their own, where a sum over all of them at every
        // point costs their number times the points' (a changed box of
        // 90k triangles after three strokes on the 1.1M bunny, 1,878
        // samples in a frame whose cut left that many pieces: seconds).
        let meeting: Vec<usize> = (0..mesh.triangles.len())
            .into_par_iter()
            .with_min_len(PARALLEL_RUN)
            .filter(|&t| meets(&mesh.triangles[t]))
            .collect();
        let corners = |t: usize| mesh.triangles[t].map(|v| end[v as usize]);
        let six: f64 = meeting
            .iter()
            .map(|&t| {
                let [a, bb, c] = corners(t);
                a.dot(bb.cross(c))
            })
            .sum();
        let kept: Vec<[u32; 3]> = meeting
            .iter()
            .filter(|&&t| !inside[t])
            .map(|&t| mesh.triangles[t])
            .collect();
        let at_end = |v: u32| end[v as usize];
        let field = WindingField::new(&kept, &at_end);
        let w = points.par_iter().map(|&p| field.at(p, None)).collect();
        (w, six / 6.0)
    };
    // The snapshot's triangles that the changes left as they were: the
    // cells meeting the changed box summed without the ones meeting it.
    w.par_iter_mut().zip(points).for_each(|(w, &p)| {
        *w += s.tree.sum_outside(&s.triangles, &old, p, &b, residue);
    });
    // The sums give the volume, the octree six times it.
    Some((w, volume_now + residue.six_kept / 6.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_meshes::uv_sphere;
    use crate::winding::{corners_meet, winding_numbers_and_volume_at};

    /// What `field` answers for `m` at `points`, with no region (the
    /// region's box: `m`'s first vertex).
    fn asked(field: &FarField, m: &TriMesh, points: &[DVec3]) -> (Vec<f64>, f64) {
        let nothing = vec![false; m.triangles.len()];
        let first = m.positions[0];
        field
            .winding_numbers_and_volume_at(&Ask {
                mesh: m,
                inside: &nothing,
                end: &m.positions,
                region: (first, first),
                points,
            })
            .expect("built")
    }

    /// On a surface past [`EVERY_ASK_FROM`] triangles a prepared field
    /// answers a few points, exactly as one pass does up to the
    /// octree's error; a change over the whole surface makes it stale,
    /// and the next few points go to the caller's pass while a new
    /// snapshot is built, which the ask after reads.
    #[test]
    fn a_prepared_field_answers_few_points_and_is_rebuilt_when_stale() {
        let m = uv_sphere(DVec3::ZERO, 1.0, 300, 500);
        assert!(m.triangles.len() >= EVERY_ASK_FROM);
        let points = [DVec3::new(0.1, 0.2, 0.3), DVec3::new(0.0, 0.0, 1.5)];
        let at = |v: u32| m.positions[v as usize];
        let (exact, exact_volume) =
            winding_numbers_and_volume_at(&m.triangles, &|_| true, &at, &points);
        let field = FarField::new();
        field.prepare(&m);
        let (w, volume) = asked(&field, &m, &points);
        for (w, e) in w.iter().zip(&exact) {
            assert!((w - e).abs() < 1e-2, "{w} against {e}");
        }
        assert!((volume - exact_volume).abs() < 1e-9 * exact_volume.abs());
        assert_eq!((field.builds(), field.answers()), (1, 1));
        // Preparing again keeps the snapshot.
        field.prepare(&m);
        let _ = asked(&field, &m, &points);
        assert_eq!((field.builds(), field.answers()), (1, 2));
        field.changed_within((DVec3::splat(-2.0), DVec3::splat(2.0)));
        let nothing = vec![false; m.triangles.len()];
        let first = m.positions[0];
        let stale = field.winding_numbers_and_volume_at(&Ask {
            mesh: &m,
            inside: &nothing,
            end: &m.positions,
            region: (first, first),
            points: &points,
        });
        assert!(
            stale.is_none(),
            "a stale field leaves a few points to the pass"
        );
        let (w, _) = asked(&field, &m, &points);
        assert_eq!((field.builds(), field.answers()), (2, 3));
        for (w, e) in w.iter().zip(&exact) {
            assert!((w - e).abs() < 1e-2, "{w} against {e}");
        }
    }

    /// Many points and a changed box holding a large part of the
    /// snapshot, below the share that makes it stale (a fifth of the
    /// triangles, where three strokes on the 1.1M bunny left 90k of them
    /// in it and a frame asked at 1,878 points): the cells meeting the
    /// box count without its triangles, by their dipoles when far, and
    /// the surface's triangles in the box by a field of their own. Points
    /// inside and outside, in the box and out, and between the cap where
    /// it was and where it moved, agree with the exact pass over the
    /// surface now.
    #[test]
    fn many_points_and_a_large_changed_box_agree_with_the_exact_pass() {
        let mut m = uv_sphere(DVec3::ZERO, 1.0, 60, 90);
        let field = FarField::new();
        let points: Vec<DVec3> = (0..40)
            .map(|i| {
                let (polar, around) = (0.05 + 0.075 * i as f64, 2.4 * i as f64);
                let dir = DVec3::new(
                    polar.sin() * around.cos(),
                    polar.sin() * around.sin(),
                    polar.cos(),
                );
                dir * [0.5, 0.97, 1.02, 1.5][i % 4]
            })
            .collect();
        let _ = asked(&field, &m, &points);
        assert!(field.is_built());
        // The cap z > 0.8 (around the first vertex, the region's box
        // here), pushed out by 5%.
        let lo = DVec3::new(-1.1, -1.1, 0.75);
        let hi = DVec3::new(1.1, 1.1, 1.1);
        for p in m.positions.iter_mut().filter(|p| p.z > 0.8) {
            *p *= 1.05;
        }
        field.changed_within((lo, hi));
        let b = Aabb::new(lo, hi);
        let meeting = m
            .triangles
            .iter()
            .filter(|t| corners_meet(&t.map(|v| m.positions[v as usize]), &b))
            .count();
        let share = meeting as f64 / m.triangles.len() as f64;
        assert!((0.1..STALE_SHARE).contains(&share), "{share}");
        let (kept, volume) = asked(&field, &m, &points);
        assert_eq!(field.builds(), 1, "not stale: the snapshot is kept");
        let at = |v: u32| m.positions[v as usize];
        let (exact, exact_volume) =
            winding_numbers_and_volume_at(&m.triangles, &|_| true, &at, &points);
        for ((k, e), p) in kept.iter().zip(&exact).zip(&points) {
            assert!((k - e).abs() < 2e-2, "{p}: {k} against {e}");
        }
        assert!((volume - exact_volume).abs() < 1e-9 * exact_volume.abs());
        // Some points lie between the cap where it was and where it is.
        assert!(
            points
                .iter()
                .zip(&exact)
                .any(|(p, e)| p.z > 0.8 && p.length() > 1.0 && (e - 1.0).abs() < 0.1)
        );
    }

    /// The exact pass over the surface now, beside the kept field, as a
    /// surface changes patch by patch and the changes are reported: the
    /// winding numbers agree within the octree's far-field error, the
    /// volumes to rounding.
    #[test]
    fn a_kept_field_follows_reported_changes() {
        let mut m = uv_sphere(DVec3::ZERO, 1.0, 40, 80);
        // A second sphere inside: points between them have w = 1, inside
        // both w = 2.
        let inner = uv_sphere(DVec3::new(0.2, 0.0, 0.0), 0.4, 12, 24);
        let base = m.positions.len() as u32;
        m.positions.extend(&inner.positions);
        m.triangles
            .extend(inner.triangles.iter().map(|t| t.map(|v| v + base)));
        let field = FarField::new();
        // More points than one pass serves: between the spheres, inside
        // both, outside, and along a line through all three.
        let mut points = vec![
            DVec3::new(0.0, 0.7, 0.0),
            DVec3::new(0.2, 0.0, 0.1),
            DVec3::new(2.0, 0.0, 0.0),
        ];
        points.extend((0..FEW_POINTS).map(|i| DVec3::new(-1.5 + 0.19 * i as f64, 0.05, -0.02)));
        let nothing = vec![false; m.triangles.len()];
        let first = |m: &TriMesh| m.positions[0];
        let region = (first(&m), first(&m));
        let few = field.winding_numbers_and_volume_at(&Ask {
            mesh: &m,
            inside: &nothing,
            end: &m.positions,
            region,
            points: &points[..3],
        });
        assert!(
            few.is_none() && !field.is_built(),
            "a few points are the caller's pass"
        );
        let _ = field.winding_numbers_and_volume_at(&Ask {
            mesh: &m,
            inside: &nothing,
            end: &m.positions,
            region,
            points: &points,
        });
        assert!(field.is_built());
        for step in 0..6 {
            // Move a cap of the outer sphere outward, a different one
            // each step, and remove one of its triangles (a hole).
            let dir = DVec3::new((step as f64).cos(), (step as f64).sin(), 0.3).normalize();
            let moved: Vec<u32> = (0..base)
                .filter(|&v| m.positions[v as usize].dot(dir) > 0.9)
                .collect();
            let before: Vec<DVec3> = moved.iter().map(|&v| m.positions[v as usize]).collect();
            for &v in &moved {
                m.positions[v as usize] *= 1.1;
            }
            let hole = m
                .triangles
                .iter()
                .position(|t| t.iter().all(|v| moved.contains(v)));
            let mut lost = None;
            if let Some(h) = hole {
                lost = Some(m.triangles.remove(h));
            }
            let bound = moved
                .iter()
                .map(|&v| m.positions[v as usize])
                .chain(before)
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
                    (l.min(p), h.max(p))
                });
            field.changed_within(bound);
            assert!(lost.is_some());
            let (kept, volume) = asked(&field, &m, &points);
            let at = |v: u32| m.positions[v as usize];
            let (exact, exact_volume) =
                winding_numbers_and_volume_at(&m.triangles, &|_| true, &at, &points);
            // The octree's cells count by their dipoles past three radii:
            // about 1% here, as a `WindingField` over the surface now.
            for (k, e) in kept.iter().zip(&exact) {
                assert!((k - e).abs() < 2e-2, "step {step}: {k} against {e}");
            }
            assert!(
                (volume - exact_volume).abs() < 1e-9 * exact_volume.abs(),
                "step {step}: volume {volume} against {exact_volume}"
            );
        }
        // A change not reported is not seen: the volume is the old one.
        let dir = DVec3::new(0.0, 0.0, -1.0);
        for v in 0..base as usize {
            if m.positions[v].dot(dir) > 0.8 {
                m.positions[v] *= 1.2;
            }
        }
        let (_, volume) = asked(&field, &m, &points);
        let at = |v: u32| m.positions[v as usize];
        let (_, exact_volume) = winding_numbers_and_volume_at(&m.triangles, &|_| true, &at, &[]);
        assert!(
            (volume - exact_volume).abs() > 1e-3,
            "{volume} {exact_volume}"
        );
    }
}
