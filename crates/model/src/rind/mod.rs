//! # Rind modeling, the improved algorithm (thesis chapter V, §V.3)
//!
//! A rind is a shell: the input surface (the *outer* shell) and an offset
//! copy inside it with reversed orientation (the *inner* shell), so that
//! the solid enclosed by the surface is the thin region between them.
//! Punching a hole joins an outer face to its inner copy with
//! `CreatePipe` (§III.3); peeling punches and then removes the infinitely
//! thin walls left between neighbouring holes, so adjacent holes merge
//! into one opening.
//!
//! ## The automatic step (§V.3.1): [`Rind::new`]
//! 1. Duplicate the mesh, reverse the copy's faces, and average the unit
//!    normals of the faces around each vertex.
//! 2. Record the correspondence table: each outer face ↔ its inner copy,
//!    and the corners at which the two are matched. Outer corner `c` of a
//!    face read forwards matches the inner copy read backwards, as
//!    `CreatePipe` wants.
//! 3. Move each inner vertex by the thickness along its averaged normal.
//!
//! **Sign convention:** the thickness must be positive and moves the copy
//! *against* the outward normals: inside a surface whose faces run
//! counter-clockwise seen from outside (as every primitive and most files
//! do). An input oriented the other way gets its rind outside.
//!
//! The offset is the thesis's ad hoc one: one vertex per vertex, so the
//! two shells have the same structure (which keeps the one-to-one table;
//! §V.3.1 explains why topology-changing offsets are not attempted). Too
//! large a thickness folds the inner shell; [`Rind::new`] refuses any
//! thickness that flips or collapses an inner face relative to its outer
//! face (the error names the face), or leaves a vertex without a normal.
//! Folds that do not flip a face, and intersections between distant parts
//! of the shells, are not detected: keep the thickness below the local
//! feature size.
//!
//! **Open input.** Hole faces (boundary loops) are not faces of the rind:
//! each is piped to its inner copy when the rind is made, which closes the
//! shell along the boundary (a plane becomes a slab). Hole faces are not
//! in the table. A surface of genus `h` with `b` boundary loops gives a
//! rind of genus `2h + b − 1`.
//!
//! ## The interactive step (§V.3.2): [`Rind::punch`], [`Rind::peel`]
//! Faces are chosen on the outer shell only: the table supplies the inner
//! face and both corners. A face the table does not hold — one made by an
//! earlier punch, an inner face, a face already punched — is ignored, and
//! the outcome says why ([`PunchOutcome::NotPunchable`]); it is not an
//! error, so a batch goes on.
//!
//! Peeling, after the pipe, visits each edge `e1` of the punched outer
//! face and its matching edge `e2` of the inner face. If the two faces
//! beside `e1` are the two faces beside `e2`, those two faces are
//! coincident quadrilaterals — an infinitely thin wall, which is really a
//! handle (figure 27) — and all the edges of one of them are deleted:
//! first `e1`, which merges the two quadrilaterals into a hexagon, then
//! `e2`, which cuts the hexagon into two two-gons, then the two other
//! edges, which merge each two-gon into the pipe face beyond it. Vertices
//! left with no edge (a vertex whose every surrounding face was peeled)
//! are deleted. No two-gons remain.
//!
//! Walls are only looked for beside the face being peeled, as in the
//! thesis: a wall between two faces that were merely punched stays. If
//! peeling later strips everything else from one of its ends, it remains
//! as a two-sided flap hanging from the rim (not a handle).
//!
//! ## Counts
//! From a closed mesh of `V, E, F` the rind has `2V, 2E, 2F` and genus
//! `2g` summed over two components per input component. Punching an
//! `n`-gon adds `n` edges and `n − 2` faces; the first punch in a
//! component joins its two shells, each further one adds a handle: `k`
//! punches in a genus-`g` crust give genus `2g + k − 1`. Each thin wall
//! removed deletes 4 edges and 2 faces (and a handle, or separates a
//! component), and each vertex freed by peeling deletes itself and its
//! inner copy.
//!
//! ## Addressing faces
//! Outer faces keep the identity of the input's faces: the input face in
//! slot `i` (for a mesh just read from a file or made from a primitive,
//! face `i` in file order) is [`Rind::outer_face`]`(i)`. Callers that
//! take face numbers (a CLI's `--punch 3,4`) use [`Rind::punch_indices`]
//! and [`Rind::peel_indices`].

mod offset;

use holey_dlfl::{BuildError, CornerId, EdgeId, FaceId, Mesh, NonFinite, VertexId};

/// Why a rind could not be made or an operation was refused. Nothing was changed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RindError {
    /// The thickness given (the value held) is zero, negative, NaN or infinite.
    #[error("the rind thickness must be positive and finite, got {0}")]
    InvalidThickness(f64),
    /// The input mesh has no faces.
    #[error("the mesh is empty; there is nothing to make a rind of")]
    Empty,
    /// A vertex has no offset direction: the unit normals of its faces
    /// cancel out, or are undefined because the faces have no area (§V.3.1 step 1).
    #[error(
        "vertex {vertex} (on face {face}) has no normal: the unit normals of its faces cancel out (or its faces have no area), so it has no offset direction"
    )]
    NoVertexNormal {
        /// The vertex's slot index in the input mesh.
        vertex: usize,
        /// The slot index in the input mesh of one face around that vertex
        /// (a non-hole one if there is any); `usize::MAX` if it has none.
        face: usize,
    },
    /// A face's inner copy is turned over: it faces the other way from the
    /// outer face, or one of its edges runs backwards.
    #[error(
        "face {face}: at thickness {thickness} its offset copy turns over (its normal flips relative to the outer face); the thickness is too large for the local feature size"
    )]
    Inverted {
        /// The face's slot index in the input mesh.
        face: usize,
        /// The thickness that was asked for, in model units.
        thickness: f64,
    },
    /// A face's inner copy shrinks to (nearly) zero area, or one of its
    /// edges to (nearly) zero length.
    #[error(
        "face {face}: at thickness {thickness} its offset copy collapses to zero area; the thickness is too large for the local feature size"
    )]
    Collapsed {
        /// The face's slot index in the input mesh.
        face: usize,
        /// The thickness that was asked for, in model units.
        thickness: f64,
    },
    /// A vertex's inner copy would have a NaN or infinite coordinate: the
    /// offset copy of the vertex with this slot index in the input mesh.
    #[error(transparent)]
    NonFinite(#[from] NonFinite),
    /// A face index given to [`Rind::punch_index`] and its kin names no live
    /// face of the input mesh.
    #[error("there is no face {index}: the input had {count} face slots")]
    NoSuchFace {
        /// The index asked for.
        index: usize,
        /// The number of face slots of the input mesh (one past its last live face).
        count: usize,
    },
    /// The kernel rejected the two shells' arrays when building the rind
    /// mesh; a bug in this module, not an input error.
    #[error("internal: the two shells do not form a valid mesh: {0}")]
    Build(#[from] BuildError),
    /// A kernel operation on the rind mesh failed (closing a rim, a pipe, or
    /// peeling); not expected on meshes this module built.
    #[error(transparent)]
    Kernel(#[from] holey_dlfl::Error),
}

/// One entry of the correspondence table (§V.3.1 step 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RindMatch {
    /// The input face's slot index (file order for a freshly read mesh).
    pub index: usize,
    /// The outer face and its inner copy.
    pub outer: FaceId,
    /// The inner copy of `outer` on the offset shell, with reversed orientation.
    pub inner: FaceId,
    /// Matching corners: the inner face read backwards from
    /// `inner_corner` visits the copies of the vertices that the outer
    /// face visits read forwards from `outer_corner` (the order
    /// `CreatePipe(outer_corner, inner_corner)` pairs them in).
    pub outer_corner: CornerId,
    /// The corner of `inner` at the copy of `outer_corner`'s vertex.
    pub inner_corner: CornerId,
}

/// Why a selected face was ignored (§V.3.2: "selecting a face which was
/// created by a previously punched hole does not have any effect").
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NotPunchable {
    /// The outer face made from this input face was already punched or peeled.
    #[error("face {index} has already been punched")]
    AlreadyPunched {
        /// The input face's slot index.
        index: usize,
    },
    /// This input face was a hole; the rind closed it with a rim instead of
    /// making an outer face of it.
    #[error("face {index} was a hole of the input (a boundary loop), closed by the rind's rim")]
    HoleFace {
        /// The input face's slot index.
        index: usize,
    },
    /// The face is in the mesh but not in the correspondence table: it was
    /// made by a punch, lies on the inner shell, or was already punched.
    #[error(
        "face {face} is not an unpunched outer face (it was made by an earlier punch, or is on the inner shell)"
    )]
    NotInTable {
        /// The face selected.
        face: FaceId,
    },
    /// The face id names no face of the current mesh (an earlier punch or
    /// peel deleted it).
    #[error("face {face} no longer exists")]
    Stale {
        /// The face id selected.
        face: FaceId,
    },
}

/// What one punch or peel did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PunchReport {
    /// The input index of the punched face.
    pub index: usize,
    /// The pipe's edges, outer vertex to inner vertex.
    pub pipe_edges: Vec<EdgeId>,
    /// Thin walls removed (peeling only), 4 edges each.
    pub walls_removed: usize,
    /// Coincident face pairs found but not removed because neither face
    /// was a quadrilateral bounded by the two matching edges (not expected
    /// from meshes the rind tool made).
    pub walls_skipped: usize,
    /// Edges deleted by peeling.
    pub edges_deleted: usize,
    /// Vertices deleted because peeling left them without edges.
    pub vertices_deleted: usize,
    /// Two-gons removed by a final local sweep, beyond those the wall
    /// removal itself merges away (not expected).
    pub two_gons_removed: usize,
}

/// The outcome of selecting a face.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PunchOutcome {
    /// The face was punched (and peeled, if asked); the report says what changed.
    Punched(PunchReport),
    /// Nothing changed.
    NotPunchable {
        /// Why the face was ignored.
        reason: NotPunchable,
    },
}

impl PunchOutcome {
    /// The report, if the face was punched.
    pub fn report(&self) -> Option<&PunchReport> {
        match self {
            PunchOutcome::Punched(r) => Some(r),
            PunchOutcome::NotPunchable { .. } => None,
        }
    }
}

/// A rind under construction. See the module documentation.
#[derive(Clone, Debug)]
pub struct Rind {
    mesh: Mesh,
    thickness: f64,
    /// By outer face slot: the table entry while the face is unpunched.
    table: Vec<Option<RindMatch>>,
    /// By input face slot: the outer face slot, `None` for dead slots.
    by_input: Vec<Option<u32>>,
    /// Input face slots that were holes.
    input_holes: Vec<bool>,
    rims: usize,
}

/// Whether a selected face is peeled or only punched.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Punch,
    Peel,
}

impl Rind {
    /// The automatic step (§V.3.1): the offset shell at `thickness`
    /// (positive: inside), the table, and rims closing any boundary loops.
    ///
    /// Takes the mesh by value because the rind replaces it; on error the
    /// mesh is dropped, so a caller that wants it back should use
    /// [`Rind::from_mesh`], which builds the rind from a borrowed mesh.
    pub fn new(mesh: Mesh, thickness: f64) -> Result<Rind, RindError> {
        Rind::from_mesh(&mesh, thickness)
    }

    /// [`Rind::new`] from a borrowed mesh, which stays as it was. The cost
    /// is the same: the rind is built from the mesh's flattened arrays.
    pub fn from_mesh(mesh: &Mesh, thickness: f64) -> Result<Rind, RindError> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(RindError::InvalidThickness(thickness));
        }
        if mesh.face_count() == 0 {
            return Err(RindError::Empty);
        }
        let vertex_slot: Vec<usize> = mesh.vertices().map(|v| v.index()).collect();
        let face_slot: Vec<usize> = mesh.faces().map(|f| f.index()).collect();
        let raw = mesh.to_raw();
        let shells = offset::build_shells(&raw, thickness, &vertex_slot, &face_slot)?;
        let mut out = Mesh::from_raw_trusted(&shells.raw)?;
        let nf = raw.face_count();
        let slots = face_slot.last().map_or(0, |&s| s + 1);
        let mut by_input = vec![None; slots];
        let mut input_holes = vec![false; slots];
        let mut table = Vec::with_capacity(nf);
        let mut rims = Vec::new();
        for (f, &slot) in face_slot.iter().enumerate() {
            let lo = raw.face_offsets[f] as usize;
            let face = |i: usize| out.face_at(i).ok_or_else(|| missing("face", i));
            let corner = |i: usize| out.corner_at(i).ok_or_else(|| missing("corner", i));
            let (oc, ic) = (corner(lo)?, corner(shells.corners as usize + lo)?);
            by_input[slot] = Some(f as u32);
            if raw.is_hole(f) {
                input_holes[slot] = true;
                table.push(None);
                rims.push((oc, ic));
                continue;
            }
            table.push(Some(RindMatch {
                index: slot,
                outer: face(f)?,
                inner: face(nf + f)?,
                outer_corner: oc,
                inner_corner: ic,
            }));
        }
        for &(oc, ic) in &rims {
            out.create_pipe(oc, ic)?;
        }
        Ok(Rind {
            mesh: out,
            thickness,
            table,
            by_input,
            input_holes,
            rims: rims.len(),
        })
    }

    /// The mesh of both shells with the holes punched so far.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Ends rind modeling and returns the mesh.
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }

    /// The thickness the rind was made with.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// Boundary loops of the input closed by rims.
    pub fn rims(&self) -> usize {
        self.rims
    }

    /// Number of face slots of the input (the valid range of indices).
    pub fn input_face_slots(&self) -> usize {
        self.by_input.len()
    }

    /// The outer face made from input face slot `index`, while it is unpunched.
    pub fn outer_face(&self, index: usize) -> Option<FaceId> {
        let slot = (*self.by_input.get(index)?)?;
        self.table
            .get(slot as usize)
            .copied()
            .flatten()
            .map(|m| m.outer)
    }

    /// The table entry of an unpunched outer face.
    pub fn matching(&self, outer: FaceId) -> Option<RindMatch> {
        self.table
            .get(outer.index())
            .copied()
            .flatten()
            .filter(|m| m.outer == outer && self.mesh.contains_face(outer))
    }

    /// The inner corner matching a corner of an unpunched outer face: the
    /// copy of the same vertex, where the edge reversing the outer corner's
    /// edge ends. O(face size).
    pub fn matching_corner(&self, outer_corner: CornerId) -> Option<CornerId> {
        let face = self.mesh.corner_face(outer_corner).ok()?;
        let m = self.matching(face)?;
        let k = self
            .mesh
            .face_corners_from(m.outer_corner)
            .ok()?
            .position(|c| c == outer_corner)?;
        let mut c = m.inner_corner;
        for _ in 0..k {
            c = self.mesh.corner_prev(c).ok()?;
        }
        Some(c)
    }

    /// The table entries of the faces not punched yet, by input index.
    pub fn unpunched(&self) -> impl Iterator<Item = RindMatch> + '_ {
        self.table.iter().filter_map(|m| *m)
    }

    /// `CreatePipe` from `outer` to its inner copy (§V.3.2, hole punching
    /// mode). A face the table does not hold is ignored.
    pub fn punch(&mut self, outer: FaceId) -> Result<PunchOutcome, RindError> {
        self.select(outer, Mode::Punch)
    }

    /// Punches `outer`, then removes the thin walls between it and
    /// neighbouring holes and the two-gons they leave (§V.3.2, peeling
    /// mode). A face the table does not hold is ignored.
    pub fn peel(&mut self, outer: FaceId) -> Result<PunchOutcome, RindError> {
        self.select(outer, Mode::Peel)
    }

    /// [`Rind::punch`] of the outer face made from input face `index`.
    pub fn punch_index(&mut self, index: usize) -> Result<PunchOutcome, RindError> {
        self.select_index(index, Mode::Punch)
    }

    /// [`Rind::peel`] of the outer face made from input face `index`.
    pub fn peel_index(&mut self, index: usize) -> Result<PunchOutcome, RindError> {
        self.select_index(index, Mode::Peel)
    }

    /// Punches the outer faces made from the input faces `indices`, in
    /// order. Indices are checked first: one out of range is an error and
    /// nothing is punched. Faces already punched (also earlier in the same
    /// list) are reported as not punchable.
    pub fn punch_indices(&mut self, indices: &[usize]) -> Result<Vec<PunchOutcome>, RindError> {
        self.select_indices(indices, Mode::Punch)
    }

    /// Peels the outer faces made from the input faces `indices`, in
    /// order, like [`Rind::punch_indices`].
    pub fn peel_indices(&mut self, indices: &[usize]) -> Result<Vec<PunchOutcome>, RindError> {
        self.select_indices(indices, Mode::Peel)
    }

    fn check_index(&self, index: usize) -> Result<u32, RindError> {
        self.by_input
            .get(index)
            .copied()
            .flatten()
            .ok_or(RindError::NoSuchFace {
                index,
                count: self.by_input.len(),
            })
    }

    fn select_indices(
        &mut self,
        indices: &[usize],
        mode: Mode,
    ) -> Result<Vec<PunchOutcome>, RindError> {
        for &i in indices {
            self.check_index(i)?;
        }
        indices
            .iter()
            .map(|&i| self.select_index(i, mode))
            .collect()
    }

    fn select_index(&mut self, index: usize, mode: Mode) -> Result<PunchOutcome, RindError> {
        let slot = self.check_index(index)?;
        if self.input_holes[index] {
            return Ok(PunchOutcome::NotPunchable {
                reason: NotPunchable::HoleFace { index },
            });
        }
        match self.table[slot as usize] {
            Some(m) => self.apply(m, mode).map(PunchOutcome::Punched),
            None => Ok(PunchOutcome::NotPunchable {
                reason: NotPunchable::AlreadyPunched { index },
            }),
        }
    }

    fn select(&mut self, outer: FaceId, mode: Mode) -> Result<PunchOutcome, RindError> {
        if !self.mesh.contains_face(outer) {
            return Ok(PunchOutcome::NotPunchable {
                reason: NotPunchable::Stale { face: outer },
            });
        }
        match self.matching(outer) {
            Some(m) => self.apply(m, mode).map(PunchOutcome::Punched),
            None => Ok(PunchOutcome::NotPunchable {
                reason: NotPunchable::NotInTable { face: outer },
            }),
        }
    }

    /// True if `f` is an unpunched outer face (the wall removal must not touch those).
    fn in_table(&self, f: FaceId) -> bool {
        self.matching(f).is_some()
    }

    fn apply(&mut self, m: RindMatch, mode: Mode) -> Result<PunchReport, RindError> {
        // §V.3.2 step 3: the matching edges, read before the pipe. Outer
        // edge i starts at outer corner i (v_i → v_(i+1)); its copy starts
        // at inner corner i+1 read backwards (v'_(i+1) → v'_i).
        let pairs = if mode == Mode::Peel {
            let outer: Vec<CornerId> = self.mesh.face_corners_from(m.outer_corner)?.collect();
            let n = outer.len();
            let mut inner = Vec::with_capacity(n);
            let mut c = m.inner_corner;
            for _ in 0..n {
                inner.push(c);
                c = self.mesh.corner_prev(c)?;
            }
            let mut pairs = Vec::with_capacity(n);
            for i in 0..n {
                let e1 = self.mesh.corner_edge(outer[i])?;
                let e2 = self.mesh.corner_edge(inner[(i + 1) % n])?;
                if let (Some(e1), Some(e2)) = (e1, e2) {
                    pairs.push((e1, e2));
                }
            }
            pairs
        } else {
            Vec::new()
        };
        let pipe_edges = self.mesh.create_pipe(m.outer_corner, m.inner_corner)?;
        self.table[m.outer.index()] = None;
        let mut report = PunchReport {
            index: m.index,
            pipe_edges,
            walls_removed: 0,
            walls_skipped: 0,
            edges_deleted: 0,
            vertices_deleted: 0,
            two_gons_removed: 0,
        };
        let mut touched = Vec::new();
        for (e1, e2) in pairs {
            self.remove_wall(e1, e2, &mut report, &mut touched)?;
        }
        self.sweep_two_gons(&touched, &mut report)?;
        Ok(report)
    }

    /// §V.3.2 step 4 and figure 27: if the faces beside `e1` are the faces
    /// beside `e2`, delete all edges of one of them — `e1`, `e2`, then its
    /// two other edges.
    fn remove_wall(
        &mut self,
        e1: EdgeId,
        e2: EdgeId,
        report: &mut PunchReport,
        touched: &mut Vec<VertexId>,
    ) -> Result<(), RindError> {
        let mesh = &self.mesh;
        if !mesh.contains_edge(e1) || !mesh.contains_edge(e2) {
            return Ok(());
        }
        let [a, b] = mesh.edge_faces(e1)?;
        let [c, d] = mesh.edge_faces(e2)?;
        if a == b || !((a == c && b == d) || (a == d && b == c)) {
            return Ok(());
        }
        if self.in_table(a) || self.in_table(b) {
            report.walls_skipped += 1;
            return Ok(());
        }
        let mut chosen = None;
        for q in [a, b] {
            if let Some(others) = self.wall_face_edges(q, e1, e2)? {
                chosen = Some(others);
                break;
            }
        }
        let Some([e3, e4]) = chosen else {
            report.walls_skipped += 1;
            return Ok(());
        };
        for e in [e1, e2, e3, e4] {
            touched.extend(self.mesh.edge_vertices(e)?);
        }
        for e in [e1, e2, e3, e4] {
            report.vertices_deleted += self.mesh.delete_edge_with_cleanup(e)?.len();
            report.edges_deleted += 1;
        }
        report.walls_removed += 1;
        Ok(())
    }

    /// If face `q` is a quadrilateral with `e1` and `e2` once each and two
    /// other distinct edges, those two edges.
    fn wall_face_edges(
        &self,
        q: FaceId,
        e1: EdgeId,
        e2: EdgeId,
    ) -> Result<Option<[EdgeId; 2]>, RindError> {
        if self.mesh.face_len(q)? != 4 {
            return Ok(None);
        }
        let mut others = Vec::with_capacity(2);
        let (mut n1, mut n2) = (0, 0);
        for c in self.mesh.face_corners(q)? {
            let Some(e) = self.mesh.corner_edge(c)? else {
                return Ok(None);
            };
            if e == e1 {
                n1 += 1;
            } else if e == e2 {
                n2 += 1;
            } else {
                others.push(e);
            }
        }
        Ok(match others[..] {
            [x, y] if n1 == 1 && n2 == 1 && x != y => Some([x, y]),
            _ => None,
        })
    }

    /// Removes two-gons at the vertices a wall removal touched by
    /// deleting one of their edges (figure 29), merging each into a
    /// neighbouring face that is not in the table. Local: only the faces
    /// around `touched` are looked at.
    fn sweep_two_gons(
        &mut self,
        touched: &[VertexId],
        report: &mut PunchReport,
    ) -> Result<(), RindError> {
        let mut faces = Vec::new();
        for &v in touched {
            if !self.mesh.contains_vertex(v) {
                continue;
            }
            for c in self.mesh.vertex_corners(v)? {
                faces.push(self.mesh.corner_face(c)?);
            }
        }
        while let Some(f) = faces.pop() {
            if !self.mesh.contains_face(f)
                || self.mesh.face_len(f)? != 2
                || self.mesh.is_hole(f)?
                || self.in_table(f)
            {
                continue;
            }
            let mut target = None;
            for c in self.mesh.face_corners(f)? {
                let Some(e) = self.mesh.corner_edge(c)? else {
                    continue;
                };
                let [x, y] = self.mesh.edge_faces(e)?;
                let g = if x == f { y } else { x };
                if g != f && !self.mesh.is_hole(g)? && !self.in_table(g) {
                    target = Some((e, g));
                    break;
                }
            }
            if let Some((e, g)) = target {
                report.vertices_deleted += self.mesh.delete_edge_with_cleanup(e)?.len();
                report.edges_deleted += 1;
                report.two_gons_removed += 1;
                // The merged face keeps one of the two ids; look again.
                faces.push(g);
                faces.push(f);
            }
        }
        Ok(())
    }
}

fn missing(what: &str, i: usize) -> RindError {
    RindError::Kernel(holey_dlfl::Error::Invalid(format!(
        "internal: {what} slot {i} of the freshly built rind is empty"
    )))
}

#[cfg(test)]
mod tests;
