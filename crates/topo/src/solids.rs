//! Booleans of solids behind one entry point, [`solid_boolean`], with the
//! policy that picks how each is computed (issue 16: the policy lives in
//! the engine; the CLI, the demo, the bindings and the benchmarks only
//! call it):
//!
//! - **Containment** ([`crate::union()`], Theorem 5.2 of Bernstein & Wojtan
//!   2013 without the motion): two closed, consistently oriented
//!   2-manifolds, neither crossing itself, no piece nested in another.
//!   Where its exact result is not clean, or may be wrong at exact
//!   coordinates though clean (its cut merged points, or the solids cross
//!   nowhere and may only touch), the exact winding-number arrangement
//!   answers first and is kept when clean; then the scale-relative nudges
//!   of [`crate::union::NUDGES`], unless `exact`. Solids that share a
//!   triangle (exact coplanar contact, where the cut merges points) go to
//!   the arrangement before the containment, unless `exact`.
//! - **Winding** ([`crate::winding_boolean`]): anything else (open input,
//!   an edge of more than two triangles, self-crossing or nested shells,
//!   one input or more than two), by the winding-number rule; nudged per
//!   piece unless `exact`.
//! - **Motion** (Theorem 5.2 itself): B arrives from far away along a
//!   direction in one frame and the whole pipeline (collisions,
//!   intersections, correction, cut) deletes what ends up inside; only
//!   for the union of two inputs, and the fallback of a union the
//!   containment path cannot take when the check was skipped.
//!
//! The choice is exact: [`crate::needs_arrangement`] checks closedness,
//! orientation, self-crossings and nesting (about one self-intersection
//! pass over each input); `check: false` skips it for inputs known to be
//! clean solids.

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use crate::clean_solids::needs_arrangement;
use crate::engine::{Options, Outcome, TopoError, topology_change};
use crate::mesh::TriMesh;
use crate::union::{NUDGES, Operation, PreparedPair, UnionError, boolean, boolean_robust, nudge};
use crate::winding_boolean::{
    WindingError, WindingOutcome, boolean_by_winding, boolean_by_winding_first_try,
    boolean_by_winding_robust,
};

/// The default direction B arrives from in the motion: generic, so that
/// B's vertices travel along lines that pass through none of the
/// vertices and edges of a mesh built on an axis-aligned lattice (a union
/// of two copies of one mesh shifted along an axis is the common case,
/// and an axis-aligned approach would make every collision degenerate).
pub const DEFAULT_DIRECTION: [f64; 3] = [1.0, 0.3127, 0.1731];

/// How a Boolean of solids is computed (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Each vertex's containment parity in the other solid, without the motion
    /// ([`crate::union()`]).
    Containment,
    /// The winding-number rule on the arrangement of all the inputs
    /// ([`crate::winding_boolean`]).
    Winding,
    /// B moved in from far away in one frame, through the whole pipeline
    /// (Theorem 5.2).
    Motion,
}

impl Method {
    /// The name reports use: `containment`, `winding`, `motion`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Containment => "containment",
            Method::Winding => "winding",
            Method::Motion => "motion",
        }
    }
}

/// What [`solid_boolean`] may do.
#[derive(Clone, Copy, Debug)]
pub struct BooleanOptions {
    /// The engine's options (the correction scheme, the solid guard, …).
    pub engine: Options,
    /// Keep the first attempt: no nudges where coplanar faces overlap.
    pub exact: bool,
    /// Check exactly whether two inputs are clean solids before choosing
    /// the containment path; `false` trusts them (a solid that does cross
    /// itself then keeps its crossings, or a union falls back to the
    /// motion).
    pub check: bool,
    /// A method to use instead of the choice; [`Method::Motion`] only
    /// unites two inputs.
    pub method: Option<Method>,
    /// The direction B arrives from in the motion (any length but zero);
    /// `None`: [`DEFAULT_DIRECTION`].
    pub direction: Option<DVec3>,
}

impl Default for BooleanOptions {
    fn default() -> Self {
        BooleanOptions {
            engine: Options::default(),
            exact: false,
            check: true,
            method: None,
            direction: None,
        }
    }
}

/// The result of one of the two engines behind [`solid_boolean`].
#[derive(Clone, Debug)]
pub enum Computed {
    /// Containment or motion: the engine's outcome, with its report,
    /// parities and intersections.
    Parity(Outcome),
    /// The winding-number arrangement's outcome and report.
    Winding(WindingOutcome),
}

/// What [`solid_boolean`] made, and how.
#[derive(Clone, Debug)]
pub struct BooleanOutcome {
    /// The method that made the result.
    pub method: Method,
    /// The result of the engine that computed it: the surface and its report.
    pub computed: Computed,
    /// Wall-clock seconds, the choice included.
    pub seconds: f64,
    /// The motion's inputs at its end (built by the motion anyway); see
    /// [`BooleanOutcome::at_end`].
    motion_end: Option<TriMesh>,
}

impl BooleanOutcome {
    /// The resulting surface.
    pub fn mesh(&self) -> &TriMesh {
        match &self.computed {
            Computed::Parity(o) => &o.mesh,
            Computed::Winding(o) => &o.mesh,
        }
    }

    /// The resulting surface, taken.
    pub fn into_mesh(self) -> TriMesh {
        match self.computed {
            Computed::Parity(o) => o.mesh,
            Computed::Winding(o) => o.mesh,
        }
    }

    /// For containment and motion: the inputs as one mesh where the parity
    /// was computed (B nudged, or at the motion's end), whose vertices the
    /// outcome's parities number: what a picture of the parity shows.
    /// `inputs` are those given to [`solid_boolean`]. Made only when asked
    /// for: it copies both inputs.
    pub fn at_end(&self, inputs: &[&TriMesh]) -> Option<TriMesh> {
        match (&self.computed, inputs) {
            (Computed::Parity(_), _) if self.motion_end.is_some() => self.motion_end.clone(),
            (Computed::Parity(o), [a, b]) => {
                Some(joined(a, b, nudge(a, b, o.report.perturbation_retries)))
            }
            _ => None,
        }
    }

    /// Nudges of B (or of pieces) before the result came out clean.
    pub fn perturbation_retries(&self) -> usize {
        match &self.computed {
            Computed::Parity(o) => o.report.perturbation_retries,
            Computed::Winding(o) => o.report.perturbation_retries,
        }
    }
}

/// Why [`solid_boolean`] could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BooleanError {
    /// No input mesh was given.
    #[error("a Boolean needs at least one input")]
    NoInput,
    /// An input has no vertices; the field is the index of the first such input
    /// in the list (from 0).
    #[error("input {0} has no vertices")]
    Empty(usize),
    /// The inputs hold too many vertices for 32-bit indices (at least
    /// `u32::MAX / 2`); the field is their total.
    #[error("the inputs together have too many vertices ({0})")]
    TooManyVertices(usize),
    /// The motion moves B into A: it unites exactly two solids.
    #[error("the motion unites exactly two solids (given {inputs} inputs for a {op})")]
    MotionNeedsTwo {
        /// Number of inputs given.
        inputs: usize,
        /// Name of the operation asked for ([`Operation::name`]).
        op: &'static str,
    },
    /// The direction B arrives from is zero or not finite.
    #[error("the direction B arrives from must be finite and not zero")]
    BadDirection,
    /// B's start position, far along the direction, is not finite.
    #[error("B's start position overflows: the coordinates are too large")]
    Overflow,
    /// The containment path refused its input ([`UnionError`] says why).
    #[error(transparent)]
    Union(#[from] UnionError),
    /// The winding-number path refused its input ([`WindingError`] says why).
    #[error(transparent)]
    Winding(#[from] WindingError),
    /// The engine failed on the motion's frame ([`TopoError`] says why).
    #[error(transparent)]
    Topo(#[from] TopoError),
}

/// The operation `op` on the solids `inputs` encloses (module
/// documentation): the method chosen (or forced), the result, and for
/// the parity methods the inputs where the parity was computed.
///
/// ```
/// use holey_topo::{Operation, TriMesh};
/// use holey_topo::solids::{BooleanOptions, Method, solid_boolean};
/// use glam::DVec3;
///
/// // Two unit cubes, the second shifted by (0.5, 0.25, 0.125).
/// let cube = |o: DVec3| TriMesh {
///     positions: (0..8)
///         .map(|i| o + DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
///         .collect(),
///     triangles: vec![
///         [0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
///         [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5],
///     ],
/// };
/// let (a, b) = (cube(DVec3::ZERO), cube(DVec3::new(0.5, 0.25, 0.125)));
/// let out = solid_boolean(&[&a, &b], Operation::Difference, &BooleanOptions::default())?;
/// assert_eq!(out.method, Method::Containment);
/// let volume: f64 = out.mesh().triangles.iter().map(|t| {
///     let [p, q, r] = t.map(|v| out.mesh().positions[v as usize]);
///     p.dot(q.cross(r)) / 6.0
/// }).sum();
/// assert!((volume - (1.0 - 0.5 * 0.75 * 0.875)).abs() < 1e-12);
/// # Ok::<(), holey_topo::solids::BooleanError>(())
/// ```
pub fn solid_boolean(
    inputs: &[&TriMesh],
    op: Operation,
    options: &BooleanOptions,
) -> Result<BooleanOutcome, BooleanError> {
    let started = Instant::now();
    if inputs.is_empty() {
        return Err(BooleanError::NoInput);
    }
    if let Some(i) = inputs.iter().position(|m| m.positions.is_empty()) {
        return Err(BooleanError::Empty(i));
    }
    let total: usize = inputs.iter().map(|m| m.positions.len()).sum();
    if total >= u32::MAX as usize / 2 {
        return Err(BooleanError::TooManyVertices(total));
    }
    let finish = |method, computed, motion_end| BooleanOutcome {
        method,
        computed,
        seconds: started.elapsed().as_secs_f64(),
        motion_end,
    };
    if options.method == Some(Method::Motion) {
        let ([a, b], Operation::Union) = (inputs, op) else {
            return Err(BooleanError::MotionNeedsTwo {
                inputs: inputs.len(),
                op: op.name(),
            });
        };
        let (out, at_end) = by_motion(a, b, options)?;
        return Ok(finish(Method::Motion, Computed::Parity(out), Some(at_end)));
    }
    // The containment method's edge tables and trees, built beside the
    // check: it reads both surfaces' closedness from them, and the method
    // uses them.
    let mut prepared = None;
    let winding = match (inputs, options.method) {
        (_, Some(Method::Winding)) => true,
        ([a, b], None) if options.check => match PreparedPair::with_checks(a, b, op) {
            Ok(pair) => {
                prepared = pair;
                prepared.is_none()
            }
            // A mesh the method refuses: the check says why.
            Err(_) => needs_arrangement(a, b)?,
        },
        ([_, _], _) => false,
        _ => true,
    };
    let by_winding = || {
        let out = if options.exact {
            boolean_by_winding(inputs, op, &options.engine)?
        } else {
            boolean_by_winding_robust(inputs, op, &options.engine)?
        };
        Ok::<_, BooleanError>(finish(Method::Winding, Computed::Winding(out), None))
    };
    if winding {
        return by_winding();
    }
    let &[a, b] = inputs else {
        unreachable!("two inputs take the containment path")
    };
    // Solids that share a triangle (a solid and its copy, a part against
    // its mirror image face for face) touch in exact coplanar contact:
    // the containment's cut merges points there, so its result is
    // suspect and the arrangement answers anyway, and its pairs go to
    // exact arithmetic (1.4 s of a sponge minus itself, whose arrangement
    // takes 0.14 s). The arrangement is tried first, kept when clean.
    let shared = prepared.is_some() && !options.exact && shares_a_triangle(a, b);
    if shared && let Some(mut w) = exact_winding_if_clean(inputs, op, options, shared)? {
        w.report.seconds.total = started.elapsed().as_secs_f64();
        return Ok(finish(Method::Winding, Computed::Winding(w), None));
    }
    let direct = match (prepared, options.exact) {
        (Some(pair), true) => pair.exact(&options.engine),
        // Where the exact containment is not clean (coplanar contact),
        // the exact winding-number arrangement before any nudge: where
        // its answer is clean it is exact, where a nudge moves the answer
        // (lattice solids, boxes on a lattice, a part against its own
        // quarter turn).
        (Some(pair), false) => match pair.exact(&options.engine) {
            Ok(mut out) => {
                let mut best = None;
                // A cut that merged points put together what the perturbed
                // world kept apart: there even a closed 2-manifold can be
                // the wrong solid (two boxes on a lattice came out empty
                // for their intersection). Solids that meet without a
                // crossing in the perturbed world may touch at exact
                // coordinates (a box resting on another kept as two boxes
                // and a wall). In both, the arrangement answers first,
                // unless the merges are points where no face lies on a
                // face and no sliver of the cut crosses anything (a solid
                // against its mirror image): then the result stands.
                let suspect = pair.suspect(&out);
                let stands = if suspect {
                    out.mesh.is_closed_manifold() && pair.clean_despite_merges(&mut out)
                } else {
                    pair.first_is_clean(&mut out, &mut best)
                };
                if stands {
                    // The check of the result is part of the Boolean.
                    out.report.timings.total = started.elapsed().as_secs_f64();
                    Ok(out)
                } else if let Some(mut w) = (pair.both_oriented() && !shared)
                    .then(|| exact_winding_if_clean(inputs, op, options, shared))
                    .transpose()?
                    .flatten()
                {
                    w.report.seconds.total = started.elapsed().as_secs_f64();
                    return Ok(finish(Method::Winding, Computed::Winding(w), None));
                } else if suspect && pair.first_is_clean(&mut out, &mut best) {
                    Ok(out)
                } else {
                    pair.nudged(&options.engine, out, best)
                }
            }
            Err(e) => Err(e),
        },
        (None, true) => boolean(a, b, op, &options.engine),
        (None, false) => boolean_robust(a, b, op, &options.engine),
    };
    match direct {
        Ok(out) => Ok(finish(Method::Containment, Computed::Parity(out), None)),
        // A solid crossing itself where it meets the other would crack
        // under containment: it is what the winding number is for. The
        // check can pass such a solid where its crossings are slivers a
        // hair wide that only the containment's perturbation (vertices
        // told apart by number, not position) makes cross (a snapped
        // sponge turned: the union went to the motion for 148 s and came
        // out in 234 open pieces).
        Err(UnionError::SelfIntersecting(_)) if options.method.is_none() => by_winding(),
        // Containment means nothing for a surface with boundary (the
        // check, when skipped, did not send it to the winding number);
        // the motion takes it, and unites.
        Err(UnionError::NotClosed(_)) if op == Operation::Union && options.method.is_none() => {
            let (out, at_end) = by_motion(a, b, options)?;
            Ok(finish(Method::Motion, Computed::Parity(out), Some(at_end)))
        }
        Err(e) => Err(e.into()),
    }
}

/// Whether some triangle of `b` has the three positions of one of `a`'s
/// (bit for bit, in any order).
///
/// Positions are named first ([`crate::coplanar::position_index`]: one
/// vertex of `a` for each position of `a`), and `b`'s positions by the
/// vertex of `a` at the same position, if any. A triangle is then its
/// three names, sorted (12 bytes, not the 72 of its coordinates), and
/// only the triangles of `b` whose corners all lie on `a` are looked up.
/// Solids that merely cross (two spheres) share few positions, and the
/// test costs a pass over each vertex array: on two 262k-triangle
/// spheres, 90 ms of coordinate hashing became about 20.
fn shares_a_triangle(a: &TriMesh, b: &TriMesh) -> bool {
    let index = crate::coplanar::position_index(&a.positions);
    let name = |positions: &[DVec3]| -> Vec<u32> {
        (positions.par_iter())
            .map(|&p| (index.get(&holey_geom::position_key(p)).copied()).unwrap_or(u32::MAX))
            .collect()
    };
    let (of_a, of_b) = (name(&a.positions), name(&b.positions));
    let key = |names: &[u32], t: &[u32; 3]| {
        let mut k = t.map(|v| names.get(v as usize).copied().unwrap_or(u32::MAX));
        k.sort_unstable();
        (k[2] != u32::MAX).then_some(k)
    };
    let wanted: rustc_hash::FxHashSet<[u32; 3]> =
        b.triangles.iter().filter_map(|t| key(&of_b, t)).collect();
    !wanted.is_empty()
        && a.triangles
            .iter()
            .any(|t| key(&of_a, t).is_some_and(|k| wanted.contains(&k)))
}

/// The exact winding-number Boolean of `inputs`
/// ([`boolean_by_winding_first_try`]) when its result is clean: closed, a
/// 2-manifold at edges and vertices, and crossing itself nowhere
/// (checked exactly; the report says 0), or when snap rounding makes it
/// so ([`crate::snap_round`]). `None` otherwise.
///
/// Called only once [`PreparedPair::with_checks`] found each solid
/// crossing itself nowhere, so the arrangement tests the pairs across the
/// two, not the neighbours within each; except for solids that `share` a
/// triangle (a solid and its copy), where the whole-mesh search, which
/// tests one copy of each repeated triangle, does less.
fn exact_winding_if_clean(
    inputs: &[&TriMesh],
    op: Operation,
    options: &BooleanOptions,
    share: bool,
) -> Result<Option<WindingOutcome>, BooleanError> {
    let mut out = boolean_by_winding_first_try(inputs, op, &options.engine, !share)?;
    // Only a result crossing itself nowhere is kept: the search stops at
    // its first crossing pair (`TooManyPairs` past a limit of none), and
    // builds no points or curves.
    let clean = out.report.shape_defects() == 0
        && match crate::intersect::intersecting_pair_count(&out.mesh, 0) {
            Ok(n) => n == 0,
            Err(crate::intersect::IntersectError::TooManyPairs { .. }) => false,
            Err(e) => return Err(TopoError::from(e).into()),
        };
    if clean {
        out.report.output_intersecting_pairs = Some(0);
        return Ok(Some(out));
    }
    // Rounded points that cross, or walls the overlay left: snapped to
    // a fine grid and resolved ([`crate::snap_round`]), when that is clean.
    Ok(crate::winding_boolean::snap_rounded(&out, &options.engine)?)
}

/// The start positions of `a` joined with `b` moved away along `d` (a
/// unit vector) far enough that they are apart, and the end positions:
/// both where they are. One frame of this motion is Theorem 5.2's union.
pub fn synthesize(a: &TriMesh, b: &TriMesh, d: DVec3) -> (TriMesh, Vec<DVec3>) {
    let shadow = |m: &TriMesh| {
        m.positions
            .iter()
            .map(|p| p.dot(d))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let (alo, ahi) = shadow(a);
    let (blo, bhi) = shadow(b);
    let (alen, blen) = ((ahi - alo).max(0.0), (bhi - blo).max(0.0));
    let s = (ahi - blo).max(0.0) + 0.1 * (alen + blen) + f64::MIN_POSITIVE;
    let start = joined(a, b, d * s);
    let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
    (start, end)
}

/// `a` and `b` as one mesh, `b` moved by `offset` (A's vertices first).
pub fn joined(a: &TriMesh, b: &TriMesh, offset: DVec3) -> TriMesh {
    let mut both = a.clone();
    both.append(&b.translated(offset));
    both
}

/// The synthesized motion through the whole pipeline, B nudged as
/// [`NUDGES`] says from the first nonzero nudge on, while A and B are
/// closed 2-manifolds and the result is not; with `exact`, B unmoved
/// only. The motion starts nudged, unlike the direct union: on
/// lattice-aligned copies its vertex parity misses overlaps whose
/// vertices all lie on the other's faces (§3.5 drops a curve between even
/// vertices), leaving both solids whole, which is closed and so would not
/// be retried. Returns the outcome and the inputs at the motion's end.
fn by_motion(
    a: &TriMesh,
    b: &TriMesh,
    options: &BooleanOptions,
) -> Result<(Outcome, TriMesh), BooleanError> {
    let d = options
        .direction
        .unwrap_or(DVec3::from_array(DEFAULT_DIRECTION));
    let len = d.length();
    if !(len.is_finite() && len > 0.0) {
        return Err(BooleanError::BadDirection);
    }
    let d = d / len;
    let both_closed = a.is_closed_manifold() && b.is_closed_manifold();
    let attempts = if options.exact { 0..1 } else { 1..NUDGES.len() };
    let mut last = None;
    for k in attempts {
        let b = b.translated(nudge(a, b, k));
        let (start, end) = synthesize(a, &b, d);
        if start.positions.iter().any(|p| !p.is_finite()) {
            return Err(BooleanError::Overflow);
        }
        let mut out = topology_change(&start, &end, &options.engine)?;
        out.report.perturbation_retries = k;
        let good = !both_closed || out.mesh.is_closed_manifold();
        let at_end = TriMesh {
            positions: end,
            triangles: start.triangles,
        };
        last = Some((out, at_end));
        if good {
            break;
        }
    }
    last.ok_or(BooleanError::Overflow)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cube `[o, o + s]³`, from the built-in primitive (`[−1, 1]³`).
    fn cube(o: DVec3, s: f64) -> TriMesh {
        holey_shapes::parse_primitive("@cube")
            .unwrap()
            .triangulated()
            .transformed(|p| o + s * 0.5 * (p + DVec3::ONE))
    }

    fn volume(m: &TriMesh) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [p, q, r] = t.map(|v| m.positions[v as usize]);
                p.dot(q.cross(r)) / 6.0
            })
            .sum()
    }

    /// The policy, case by case: clean solids take containment; a nested
    /// piece, three inputs or one take the winding number; `check: false`
    /// trusts; a forced motion unites and refuses anything else; an open
    /// union without the check falls back to the motion; empty input and
    /// a zero direction are errors, not panics. Every result's volume is
    /// the closed form.
    #[test]
    fn the_policy_picks_the_method_and_every_method_gives_the_closed_form() {
        let a = cube(DVec3::ZERO, 1.0);
        let b = cube(DVec3::new(0.5, 0.25, 0.125), 1.0);
        let overlap = 0.5 * 0.75 * 0.875;
        let union = 2.0 - overlap;
        let run = |inputs: &[&TriMesh], op, options: &BooleanOptions| {
            solid_boolean(inputs, op, options).unwrap()
        };
        let default = BooleanOptions::default();
        let out = run(&[&a, &b], Operation::Union, &default);
        assert_eq!(out.method, Method::Containment);
        assert!((volume(out.mesh()) - union).abs() < 1e-12);
        assert_eq!(out.at_end(&[&a, &b]).map(|m| m.positions.len()), Some(16));

        // A box inside A, facing the same way: nested, w = 2 inside it.
        let mut nested = a.clone();
        nested.append(&cube(DVec3::splat(0.25), 0.5));
        let far = cube(DVec3::splat(5.0), 1.0);
        let out = run(&[&nested, &far], Operation::Union, &default);
        assert_eq!(out.method, Method::Winding);
        assert!((volume(out.mesh()) - 2.0).abs() < 1e-12);

        let c = cube(DVec3::new(-0.5, 0.5, 0.0), 1.0);
        let out = run(&[&a, &b, &c], Operation::Intersection, &default);
        assert_eq!(out.method, Method::Winding);
        assert!((volume(out.mesh()) - 0.0).abs() < 1e-12);
        let out = run(&[&a], Operation::Union, &default);
        assert_eq!(out.method, Method::Winding);
        assert!((volume(out.mesh()) - 1.0).abs() < 1e-12);

        let forced = BooleanOptions {
            method: Some(Method::Motion),
            ..default
        };
        let out = run(&[&a, &b], Operation::Union, &forced);
        assert_eq!(out.method, Method::Motion);
        assert!(out.mesh().is_closed_manifold());
        // Nudged by 2⁻³⁰ of the diagonal first: the volume moves by about
        // that times the area it shifts.
        let off = (volume(out.mesh()) - union).abs();
        assert!(off < 1e-7, "{off}");
        assert!(matches!(
            solid_boolean(&[&a, &b], Operation::Difference, &forced),
            Err(BooleanError::MotionNeedsTwo { .. })
        ));
        assert!(matches!(
            solid_boolean(&[&a], Operation::Union, &forced),
            Err(BooleanError::MotionNeedsTwo { .. })
        ));

        // An open A (one face gone) without the check: the union falls
        // back to the motion; the difference is refused by name.
        let mut open = a.clone();
        open.triangles.pop();
        let trusting = BooleanOptions {
            check: false,
            ..default
        };
        let out = run(&[&open, &b], Operation::Union, &trusting);
        assert_eq!(out.method, Method::Motion);
        assert!(matches!(
            solid_boolean(&[&open, &b], Operation::Difference, &trusting),
            Err(BooleanError::Union(UnionError::NotClosed(_)))
        ));
        // With the check, the open input takes the winding number.
        assert_eq!(
            run(&[&open, &b], Operation::Union, &default).method,
            Method::Winding
        );

        assert_eq!(
            solid_boolean(&[], Operation::Union, &default).unwrap_err(),
            BooleanError::NoInput
        );
        let empty = TriMesh::default();
        assert_eq!(
            solid_boolean(&[&a, &empty], Operation::Union, &default).unwrap_err(),
            BooleanError::Empty(1)
        );
        let zero = BooleanOptions {
            direction: Some(DVec3::ZERO),
            ..forced
        };
        assert_eq!(
            solid_boolean(&[&a, &b], Operation::Union, &zero).unwrap_err(),
            BooleanError::BadDirection
        );
    }

    /// A solid that crosses itself where it meets the other, passed
    /// unchecked as a clean one: containment would crack there and
    /// refuses it (the union went to the motion, the others failed), so
    /// the policy takes the winding number, and every operation gives the
    /// winding rule's closed-form volume. A is two cubes in one mesh,
    /// [0,1]³ and [0.5,1.5] × [0.1,1.1] × [0.2,1.2] (inside: their union,
    /// 2 − 0.5·0.9·0.8); B, the slab x ∈ [0.3, 0.7] through both, meets
    /// the walls of one cube where they cross the other's.
    #[test]
    fn a_solid_crossing_itself_where_it_meets_the_other_takes_the_winding_number() {
        let mut a = cube(DVec3::ZERO, 1.0);
        a.append(&cube(DVec3::new(0.5, 0.1, 0.2), 1.0));
        let b = cube(DVec3::new(0.3, -0.5, -0.5), 2.0)
            .transformed(|p| DVec3::new(0.3 + (p.x - 0.3) * 0.2, p.y, p.z));
        let (va, vb) = (2.0 - 0.5 * 0.9 * 0.8, 0.4 * 2.0 * 2.0);
        // Cross sections of A at x: [0,1]² before 0.5, then the union of
        // the two squares.
        let both = 0.2 * 1.0 + 0.2 * (2.0 - 0.9 * 0.8);
        let trusting = BooleanOptions {
            check: false,
            ..BooleanOptions::default()
        };
        for (op, want) in [
            (Operation::Union, va + vb - both),
            (Operation::Intersection, both),
            (Operation::Difference, va - both),
        ] {
            let direct = boolean_robust(&a, &b, op, &trusting.engine);
            assert!(
                matches!(
                    direct,
                    Err(UnionError::SelfIntersecting(crate::union::Solid::A))
                ),
                "{}: {direct:?}",
                op.name()
            );
            let out = solid_boolean(&[&a, &b], op, &trusting).unwrap();
            assert_eq!(out.method, Method::Winding, "{}", op.name());
            let v = volume(out.mesh());
            assert!((v - want).abs() < 1e-12, "{}: {v}, want {want}", op.name());
        }
    }

    /// Two solids share a triangle when one of `b`'s has the positions
    /// of one of `a`'s, whatever their vertex numbers, their corners'
    /// order or the sign of a zero coordinate; a copy moved by an ulp
    /// shares none.
    #[test]
    fn solids_share_a_triangle_by_its_positions() {
        let a = cube(DVec3::ZERO, 1.0);
        let mut b = cube(DVec3::ZERO, 1.0);
        b.positions.reverse();
        let last = b.positions.len() as u32 - 1;
        for t in &mut b.triangles {
            *t = [last - t[1], last - t[0], last - t[2]];
        }
        for p in &mut b.positions {
            if p.x == 0.0 {
                p.x = -0.0;
            }
        }
        assert!(b.positions.iter().any(|p| p.x.is_sign_negative()));
        assert!(shares_a_triangle(&a, &b));
        let moved = a.translated(DVec3::new(0.0, 0.0, f64::EPSILON));
        assert!(!shares_a_triangle(&a, &moved));
        // Sharing a face's plane and a corner is not sharing a triangle.
        let over = a.translated(DVec3::new(0.5, 0.5, 0.0));
        assert!(!shares_a_triangle(&a, &over));
        // Every position shared, no triangle: a square split along its
        // other diagonal; then along the same one, as a triangle of `b`
        // in another corner order.
        let square = |triangles: Vec<[u32; 3]>| TriMesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            triangles,
        };
        let split = square(vec![[0, 1, 2], [0, 2, 3]]);
        assert!(!shares_a_triangle(
            &split,
            &square(vec![[0, 1, 3], [1, 2, 3]])
        ));
        assert!(shares_a_triangle(
            &split,
            &square(vec![[1, 2, 3], [2, 0, 1]])
        ));
    }
}
