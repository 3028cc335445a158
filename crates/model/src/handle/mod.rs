//! # Multi-segment curved handles (thesis chapter IV)
//!
//! [`create_handle`] joins two faces of a mesh with a handle made of `k`
//! straight segments that follow a Hermite curve (§IV.2, eq. 4.1), or, with
//! [`HandleCurve::Bezier`], TopMod's cubic Bézier variant of it
//! ([`BezierCurve`]). Between
//! faces of one component the genus rises by one; between two components
//! they join and the genus sum is unchanged. With `k = 1` it is exactly
//! the kernel's `CreatePipe` (§III.3).
//!
//! [`create_multi_face_handle`] joins four or more faces at once through
//! a common polyhedral hub, one such handle per face (TopMod's multi-face
//! handle; see its module documentation).
//!
//! ## Algorithm (§IV.4)
//! Given corners `c1 = (v1, f1)`, `c2 = (v2, f2)`, weights `w1`, `w2` and
//! `k` segments:
//!
//! 0. **Preprocessing** (§IV, after §III.3): if the faces have different
//!    numbers of corners, edges of the smaller one are subdivided — the
//!    longest first, never one bordering either face — until both have
//!    `N` corners. This is planned before anything else, so every section
//!    has `N` corners.
//! 1. Read `f1` forwards from `c1` and `f2` *backwards* from `c2` ("reverse
//!    face f2"): vertex `j` of one matches vertex `j` of the other.
//! 2. The curve `H(t) = p1·h1 + p2·h2 + w1·n1·h3 − w2·n2·h4` runs from
//!    the centroid `p1` of `f1` (leaving along its unit normal `n1`) to
//!    the centroid `p2` of `f2` (arriving along `−n2`). The Bézier variant
//!    replaces it by `B(t) = (1−t)³·p1 + 3t(1−t)²·(p1 + w1·n1) +
//!    3t²(1−t)·(p2 + w2·n2) + t³·p2`, which leaves and arrives the same
//!    ways; everything after this step is the same for both curves.
//! 3. Both faces are rotated about their centroids onto the reference
//!    plane whose normal is along `p2 − p1`, flattened, and resolved into
//!    polar coordinates `(r, θ)` ([`geometry::polar`]).
//! 4. For `i = 1 … k−1`, `t = i/k`: interpolate `(r, θ)` linearly in `t`
//!    (eq. 4.4, with the thesis's typo corrected), rotate the polygon so
//!    its normal follows the curve's tangent at `t`, centre it on `H(t)`,
//!    and make it a two-faced sphere with `CreateFaceManifold`.
//! 5. `CreatePipe` between consecutive facing faces: `f1` → back of
//!    section 1, front of section 1 → back of section 2, …, front of
//!    section `k−1` → `f2`, each starting at the corners of the vertices
//!    that correspond to `v1` and `v2`. Choosing other corners twists the
//!    handle.
//!
//! The mesh is a valid 2-manifold after every fundamental step: sections
//! are separate spheres until piped, and each pipe is a sequence of
//! `InsertEdge`s. [`create_handle_observed`] reports each step.
//!
//! ## Counts
//! A handle of `s` segments between two `d`-gons adds `d(s−1)` vertices,
//! `d(2s−1)` edges and `ds − 2` faces: `s − 1` sections of `d` vertices,
//! `d` edges and 2 faces each, and `s` pipes of `d` edges that replace 2
//! faces by `d` quadrilaterals each. Preprocessing adds one vertex and one
//! edge per missing corner before that.
//!
//! ## Choices where the thesis is silent
//! - **Which way sections face.** The thesis turns each section's normal
//!   along the curve's tangent. That is right when the curve leaves `f1`
//!   along `+n1` and enters `f2` along `−n2` (positive weights: a handle
//!   outside the surface). When it leaves against the normal (negative
//!   weights: a tunnel through the solid), sections turned that way would
//!   be mirror images of the end faces and every segment would be a bow
//!   tie. So the sections face along `σ·tangent`, where `σ = ±1` is the
//!   sign of `T(0)·n1 − T(1)·n2` (`T` the unit tangent): `+1` for handles,
//!   `−1` for holes. The reference plane's normal is `σ·(p2 − p1)/|p2 − p1|`.
//!   With weights of opposite signs no orientation fits both ends and the
//!   handle necessarily passes through itself.
//! - **Degenerate rotations.** When a normal is exactly opposite to the
//!   direction it must be turned to (`n·n_R = −1`, ignored by the thesis),
//!   a half turn about the reference X axis is used (for `f1`, about the
//!   direction of its last edge's midpoint, which becomes that X axis).
//! - **Coincident centroids.** The reference normal falls back to `n1`.
//! - **Cusps.** Where `H′(t) = 0` the tangent is the chord between the
//!   neighbouring samples; sections never get NaN coordinates.
//! - **Refused input** (mesh unchanged): `k = 0`, non-finite weights, both
//!   corners in one face, point-sphere faces, **hole faces** (a handle
//!   attaches to surface; clear the hole flag first to join boundary
//!   loops), faces whose corner counts cannot be matched, and for `k ≥ 2`
//!   faces of zero area (no normal) or weights so large that positions
//!   overflow.

mod crossing;
pub mod geometry;
mod hub;
mod matching;
mod multi;
mod multi_error;
mod simplex;

use glam::DVec3;
use holey_dlfl::{CornerId, EdgeId, FaceId, Mesh, NonFinite, VertexId};

pub use crossing::CrossingError;
pub use geometry::{BezierCurve, HandlePath, HermiteCurve};
use geometry::{Morph, centroid, rotation_between, vector_area};
use matching::{Matching, plan_matching};
pub use multi::{MultiHandleParams, MultiHandleReport, create_multi_face_handle};
pub use multi_error::MultiHandleError;

/// Why a handle was refused. The mesh is unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HandleError {
    /// [`HandleParams::segments`] was 0; a handle has at least one segment.
    #[error("a handle needs at least one segment (got 0)")]
    NoSegments,
    /// A weight of eq. 4.1 is NaN or infinite.
    #[error("weight {name} is {value}; the weights must be finite")]
    NonFiniteWeight {
        /// Which weight is bad: `"w1"` or `"w2"`.
        name: &'static str,
        /// The offending value (NaN or ±∞).
        value: f64,
    },
    /// Both corners belong to this one face; a handle needs two different faces.
    #[error("both corners lie in face {0}; a handle joins two different faces")]
    SameFace(FaceId),
    /// This end face is a point-sphere (one corner, no edge), so no pipe
    /// can start from it.
    #[error("face {0} is a point-sphere: it has no edges for a handle to start from")]
    PointSphere(FaceId),
    /// This end face is flagged as a hole (a boundary loop), not surface.
    #[error(
        "face {0} is a hole (a boundary loop), not surface; clear its hole flag first to attach a handle to it"
    )]
    HoleFace(FaceId),
    /// The faces have different corner counts and the preprocessing cannot
    /// even them: every edge of the smaller face borders one of the two end
    /// faces, and such edges are never subdivided.
    #[error(
        "cannot match the corner counts of faces {small} and {large}: every edge of the smaller face borders one of the two faces, so none can be subdivided"
    )]
    Unmatchable {
        /// The end face with fewer corners, the one that needed subdividing.
        small: FaceId,
        /// The end face with more corners.
        large: FaceId,
    },
    /// This end face has zero area and so no normal for the curve to leave
    /// or enter along (only refused for two or more segments).
    #[error(
        "face {0} has zero area, so it has no normal for the handle's curve to leave along; use one segment (a plain pipe) or another face"
    )]
    DegenerateFace(FaceId),
    /// An intermediate section came out with a NaN or infinite coordinate,
    /// because the weights are too large for the mesh's scale: the failing
    /// section's number, from 1 (nearest `f1`) to `k − 1`, and its first
    /// non-finite point.
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// The handle would add more corners than the kernel's 32-bit ids can
    /// number.
    #[error(
        "a handle of {segments} segments between {corners}-corner faces needs more entities than the kernel's 32-bit indices hold"
    )]
    TooLarge {
        /// The requested number of segments `k`.
        segments: usize,
        /// Corners per face after matching (`N`), i.e. per section.
        corners: usize,
    },
    /// A kernel call failed: a corner or face id not in the mesh, or (once
    /// planning has passed) a kernel bug.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// Which curve a handle's sections follow.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum HandleCurve {
    /// The thesis's Hermite curve (§IV.2, eq. 4.1, [`HermiteCurve`]): the
    /// weights are the curve's speeds at its ends.
    #[default]
    Hermite,
    /// TopMod's cubic Bézier variant ([`BezierCurve`]): the weights are
    /// the distances of the inner control points above the faces. Equal
    /// to the Hermite curve with the weights tripled.
    Bezier,
}

impl HandleCurve {
    /// Every curve, in the order front ends list them.
    pub const ALL: [HandleCurve; 2] = [HandleCurve::Hermite, HandleCurve::Bezier];

    /// The curve's name as front ends spell it: `"hermite"` or `"bezier"`.
    pub fn name(self) -> &'static str {
        match self {
            HandleCurve::Hermite => "hermite",
            HandleCurve::Bezier => "bezier",
        }
    }
}

impl std::fmt::Display for HandleCurve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a [`HandleCurve`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown handle curve {0:?}; expected \"hermite\" or \"bezier\"")]
pub struct UnknownHandleCurve(pub String);

impl std::str::FromStr for HandleCurve {
    type Err = UnknownHandleCurve;

    /// `"hermite"` or `"bezier"` (also `"bézier"`), any case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_lowercase().as_str() {
            "hermite" => Ok(HandleCurve::Hermite),
            "bezier" | "bézier" => Ok(HandleCurve::Bezier),
            _ => Err(UnknownHandleCurve(s.to_string())),
        }
    }
}

/// The user's parameters of a handle (§IV.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandleParams {
    /// Number of segments `k ≥ 1`; `1` is a plain `CreatePipe`.
    pub segments: usize,
    /// Weight of the first face's normal in eq. 4.1 (in model units: the
    /// curve's speed as it leaves `f1`; for [`HandleCurve::Bezier`] the
    /// height of the first inner control point above `f1`). Negative
    /// makes a tunnel.
    pub w1: f64,
    /// Weight of the second face's normal.
    pub w2: f64,
    /// The curve the sections follow; [`HandleCurve::Hermite`] by default.
    pub curve: HandleCurve,
}

impl HandleParams {
    /// `k` segments with weights `w1`, `w2` along the Hermite curve.
    pub fn new(segments: usize, w1: f64, w2: f64) -> Self {
        HandleParams {
            segments,
            w1,
            w2,
            curve: HandleCurve::Hermite,
        }
    }

    /// These parameters with the sections following `curve` instead.
    pub fn with_curve(self, curve: HandleCurve) -> Self {
        HandleParams { curve, ..self }
    }

    fn check(&self) -> Result<(), HandleError> {
        if self.segments == 0 {
            return Err(HandleError::NoSegments);
        }
        for (name, value) in [("w1", self.w1), ("w2", self.w2)] {
            if !value.is_finite() {
                return Err(HandleError::NonFiniteWeight { name, value });
            }
        }
        Ok(())
    }
}

/// Which way the sections face relative to the curve (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// Section normals along the tangent: a handle outside the surface.
    AlongTangent,
    /// Section normals against the tangent: a tunnel (negative weights).
    AgainstTangent,
}

impl Orientation {
    /// `+1` or `−1`.
    pub fn sign(self) -> f64 {
        match self {
            Orientation::AlongTangent => 1.0,
            Orientation::AgainstTangent => -1.0,
        }
    }
}

/// One intermediate cross-section of a handle.
#[derive(Clone, Debug, PartialEq)]
pub struct HandleSection {
    /// Curve parameter `i/k`.
    pub t: f64,
    /// `H(t)`: the vertex average of `points`.
    pub centroid: DVec3,
    /// The unit normal of the section's front face: `σ` times the unit tangent at `t`.
    pub normal: DVec3,
    /// The vertices, vertex `j` matching vertex `j` of `f1` read from `c1`.
    pub points: Vec<DVec3>,
}

/// The geometry of a handle, computed without touching the mesh (for
/// previews; [`create_handle`] computes the same plan and applies it).
#[derive(Clone, Debug, PartialEq)]
pub struct HandlePlan {
    /// The two faces joined.
    pub faces: [FaceId; 2],
    /// Corners per face once matched (`N`).
    pub corners: usize,
    /// Vertices the preprocessing inserts, and into which face.
    pub subdivisions: usize,
    /// The face that preprocessing subdivides (the one with fewer corners),
    /// or `None` when both faces already have `N` corners.
    pub subdivided_face: Option<FaceId>,
    /// The curve (eq. 4.1 or its Bézier variant, as
    /// [`HandleParams::curve`] chose); `None` for one segment, which needs
    /// no geometry.
    pub curve: Option<HandlePath>,
    /// Unit normals `n1`, `n2` of the faces (zero for one segment).
    pub normals: [DVec3; 2],
    /// Which way sections face.
    pub orientation: Orientation,
    /// The unit normal of the reference plane the faces are resolved in
    /// (`σ·(p2 − p1)/|p2 − p1|`).
    pub reference_normal: DVec3,
    /// The `k − 1` intermediate sections, in order from `f1`.
    pub sections: Vec<HandleSection>,
    corner_ids: [CornerId; 2],
    matching: Option<Matching>,
}

/// A step of [`create_handle_observed`]; the mesh is a valid 2-manifold after each.
#[derive(Clone, Debug, PartialEq)]
pub enum HandleStep {
    /// Preprocessing inserted this vertex into an edge of the smaller face.
    Subdivided {
        /// The new vertex, placed where the plan put it on the split edge.
        vertex: VertexId,
    },
    /// Section `index` (from 1) was made by `CreateFaceManifold`.
    Section {
        /// The section's number along the handle, from 1 (next to `f1`) to `k − 1`.
        index: usize,
        /// The section's front face (normal `σ` times the curve's unit tangent);
        /// the pipe towards `f2` starts from it.
        front: FaceId,
        /// The section's back face, where the pipe from `f1`'s side ends.
        back: FaceId,
    },
    /// Pipe `index` (from 0: `f1` to section 1) was made by `CreatePipe`.
    Pipe {
        /// The pipe's number, from 0 (`f1` to section 1) to `k − 1` (last section to `f2`).
        index: usize,
    },
}

/// What [`create_handle`] built.
#[derive(Clone, Debug, PartialEq)]
pub struct HandleReport {
    /// The geometry that was applied.
    pub plan: HandlePlan,
    /// The vertices of each intermediate section, vertex `j` matching
    /// vertex `j` of `f1` read from `c1`.
    pub sections: Vec<Vec<VertexId>>,
    /// The edges of each of the `k` pipes, from `f1`'s end; the first edge
    /// of each lies on the line of corners through `v1` and `v2`.
    pub pipes: Vec<Vec<EdgeId>>,
}

/// The faces of `c1` and `c2`, checked.
fn end_faces(mesh: &Mesh, c1: CornerId, c2: CornerId) -> Result<[FaceId; 2], HandleError> {
    let f1 = mesh.corner_face(c1)?;
    let f2 = mesh.corner_face(c2)?;
    if f1 == f2 {
        return Err(HandleError::SameFace(f1));
    }
    for f in [f1, f2] {
        if mesh.is_point_sphere(f)? {
            return Err(HandleError::PointSphere(f));
        }
        if mesh.is_hole(f)? {
            return Err(HandleError::HoleFace(f));
        }
    }
    Ok([f1, f2])
}

/// Positions of the face of `c` read forwards from `c`.
fn forwards(mesh: &Mesh, c: CornerId) -> Result<Vec<DVec3>, HandleError> {
    let mut out = Vec::new();
    for k in mesh.face_corners_from(c)? {
        out.push(mesh.position(mesh.corner_vertex(k)?)?);
    }
    Ok(out)
}

/// `p` read backwards from its first point: `p0, p(n−1), …, p1`.
fn backwards(p: &[DVec3]) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(p.len());
    if let Some(&first) = p.first() {
        out.push(first);
        out.extend(p[1..].iter().rev());
    }
    out
}

/// Computes the handle between the faces of `c1` and `c2` without
/// touching the mesh: the preprocessing, the curve and every section.
/// Fails exactly when [`create_handle`] would.
pub fn plan_handle(
    mesh: &Mesh,
    c1: CornerId,
    c2: CornerId,
    params: &HandleParams,
) -> Result<HandlePlan, HandleError> {
    params.check()?;
    let [f1, f2] = end_faces(mesh, c1, c2)?;
    let (l1, l2) = (mesh.face_len(f1)?, mesh.face_len(f2)?);
    let n = l1.max(l2);
    // `a`: f1 forwards from c1; `b`: f2 backwards from c2 (§IV.4 step 2a).
    let (a, b, matching, subdivided_face) = if l1 < l2 {
        let m = plan_matching(mesh, c1, f2, n)?;
        let a = m.polygon.clone();
        (a, backwards(&forwards(mesh, c2)?), Some(m), Some(f1))
    } else if l2 < l1 {
        let m = plan_matching(mesh, c2, f1, n)?;
        let b = backwards(&m.polygon);
        (forwards(mesh, c1)?, b, Some(m), Some(f2))
    } else {
        (
            forwards(mesh, c1)?,
            backwards(&forwards(mesh, c2)?),
            None,
            None,
        )
    };
    let k = params.segments;
    // Entities added: 2N corners per section and 2N per pipe, plus splits.
    let added = 4u128 * n as u128 * k as u128 + 2 * (n - l1.min(l2)) as u128;
    if mesh.corner_count() as u128 + added >= u128::from(u32::MAX / 2) {
        return Err(HandleError::TooLarge {
            segments: k,
            corners: n,
        });
    }
    let mut plan = HandlePlan {
        faces: [f1, f2],
        corners: n,
        subdivisions: n - l1.min(l2),
        subdivided_face,
        curve: None,
        normals: [DVec3::ZERO; 2],
        orientation: Orientation::AlongTangent,
        reference_normal: DVec3::ZERO,
        sections: Vec::new(),
        corner_ids: [c1, c2],
        matching,
    };
    if k == 1 {
        return Ok(plan);
    }

    let (p1, p2) = (centroid(&a), centroid(&b));
    let radius = a
        .iter()
        .map(|p| p.distance(p1))
        .chain(b.iter().map(|p| p.distance(p2)))
        .fold(0.0, f64::max);
    let unit_normal = |poly: &[DVec3], f: FaceId| {
        let v = vector_area(poly);
        if radius > 0.0 && v.length() > 1e-12 * radius * radius {
            Ok(v.normalize())
        } else {
            Err(HandleError::DegenerateFace(f))
        }
    };
    let n1 = unit_normal(&a, f1)?;
    // `b` is f2 reversed, so its normal is −n2.
    let n2 = -unit_normal(&b, f2)?;
    let curve = match params.curve {
        HandleCurve::Hermite => {
            HandlePath::Hermite(HermiteCurve::new(p1, n1, params.w1, p2, n2, params.w2))
        }
        HandleCurve::Bezier => {
            HandlePath::Bezier(BezierCurve::new(p1, n1, params.w1, p2, n2, params.w2))
        }
    };
    let chord = p2 - p1;
    let n_r = if chord.length() > 1e-12 * radius.max(chord.length()) {
        chord.normalize()
    } else {
        n1
    };
    let step = 1.0 / k as f64;
    let t0 = curve.unit_tangent(0.0, step, n_r);
    let t1 = curve.unit_tangent(1.0, step, n_r);
    let orientation = if t0.dot(n1) - t1.dot(n2) < 0.0 {
        Orientation::AgainstTangent
    } else {
        Orientation::AlongTangent
    };
    let sigma = orientation.sign();
    let u = n_r * sigma;
    let morph = Morph::new(&a, n1, &b, -n2, u);
    let mut sections = Vec::with_capacity(k - 1);
    for i in 1..k {
        let t = i as f64 / k as f64;
        let normal = curve.unit_tangent(t, step, n_r) * sigma;
        let turn = rotation_between(morph.u, normal, morph.x);
        let centre = curve.point(t);
        let points: Vec<DVec3> = morph.at(t).into_iter().map(|q| centre + turn * q).collect();
        if let Some(&bad) = std::iter::once(&centre)
            .chain(&points)
            .find(|p| !p.is_finite())
        {
            return Err(NonFinite::new("handle section", i, bad)
                .with_hint("the weights are too large for the mesh's scale")
                .into());
        }
        sections.push(HandleSection {
            t,
            centroid: centre,
            normal,
            points,
        });
    }
    plan.curve = Some(curve);
    plan.normals = [n1, n2];
    plan.orientation = orientation;
    plan.reference_normal = u;
    plan.sections = sections;
    Ok(plan)
}

/// Creates a handle of `params.segments` segments between the faces of
/// `c1` and `c2` (§IV.4). See the module documentation. On error the mesh
/// is unchanged.
pub fn create_handle(
    mesh: &mut Mesh,
    c1: CornerId,
    c2: CornerId,
    params: &HandleParams,
) -> Result<HandleReport, HandleError> {
    create_handle_observed(mesh, c1, c2, params, |_, _| {})
}

/// [`create_handle`], calling `observe` after every step (each
/// subdivision, each section, each pipe) with the mesh as it stands.
pub fn create_handle_observed(
    mesh: &mut Mesh,
    c1: CornerId,
    c2: CornerId,
    params: &HandleParams,
    observe: impl FnMut(&Mesh, HandleStep),
) -> Result<HandleReport, HandleError> {
    let plan = plan_handle(mesh, c1, c2, params)?;
    apply(mesh, plan, params.segments, observe)
}

/// Applies a plan made for the mesh as it is. Every refusal happened in
/// the planning, so the kernel calls here succeed; an error would mean a
/// kernel bug.
fn apply(
    mesh: &mut Mesh,
    plan: HandlePlan,
    k: usize,
    mut observe: impl FnMut(&Mesh, HandleStep),
) -> Result<HandleReport, HandleError> {
    if let Some(m) = &plan.matching {
        for split in &m.splits {
            let mut edge = split.edge;
            for &p in &split.points {
                // Split the remaining far part; then put the vertex exactly
                // where the plan (and so the sections) expects it.
                let sub = mesh.subdivide_edge_at(edge, 0.5)?;
                mesh.set_position(sub.vertex, p)?;
                observe(mesh, HandleStep::Subdivided { vertex: sub.vertex });
                edge = sub.edges[1];
            }
        }
    }
    let mut sections = Vec::with_capacity(plan.sections.len());
    let mut facing = Vec::with_capacity(plan.sections.len());
    for (i, s) in plan.sections.iter().enumerate() {
        let fm = mesh.create_face_manifold(&s.points)?;
        let v0 = fm.vertices[0];
        let (mut front, mut back) = (None, None);
        for c in mesh.vertex_corners(v0)? {
            let f = mesh.corner_face(c)?;
            if f == fm.front {
                front = Some(c);
            } else if f == fm.back {
                back = Some(c);
            }
        }
        let (Some(front), Some(back)) = (front, back) else {
            return Err(HandleError::Kernel(holey_dlfl::Error::Invalid(format!(
                "internal: section {} lacks a front or back corner at its first vertex",
                i + 1
            ))));
        };
        observe(
            mesh,
            HandleStep::Section {
                index: i + 1,
                front: fm.front,
                back: fm.back,
            },
        );
        sections.push(fm.vertices);
        facing.push((front, back));
    }
    let [c1, c2] = plan.corner_ids;
    let mut pipes = Vec::with_capacity(k);
    let mut from = c1;
    for (i, &(front, back)) in facing.iter().enumerate() {
        pipes.push(mesh.create_pipe(from, back)?);
        observe(mesh, HandleStep::Pipe { index: i });
        from = front;
    }
    pipes.push(mesh.create_pipe(from, c2)?);
    observe(mesh, HandleStep::Pipe { index: k - 1 });
    Ok(HandleReport {
        plan,
        sections,
        pipes,
    })
}

#[cfg(test)]
mod tests;
