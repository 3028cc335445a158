//! The DLFL entities, their accessors, and the four fundamental operators.

use glam::DVec3;
use holey_mesh::NonFinite;

use crate::arena::Arena;
use crate::error::{Error, Result};
use crate::ids::{CornerId, EdgeId, EntityKind, FaceId, VertexId};

/// Marks an absent link (a point-sphere's corner has no edge).
pub(crate) const NONE: u32 = u32::MAX;

/// A corner: one step of a face's boundary walk (§II.5).
///
/// Links are raw slot indices: the kernel keeps them consistent, and only
/// handles given out to callers carry generations.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corner {
    pub(crate) vertex: u32,
    pub(crate) face: u32,
    /// Next corner in the face's cyclic order.
    pub(crate) next: u32,
    /// Previous corner in the face's cyclic order.
    pub(crate) prev: u32,
    /// The edge that starts here, running from this corner's vertex to the
    /// next corner's vertex; [`NONE`] only for a point-sphere's lone corner.
    pub(crate) edge: u32,
    /// Next and previous corner in the vertex's (unordered) corner ring.
    pub(crate) vnext: u32,
    pub(crate) vprev: u32,
}

/// An edge: the corners at which it originates on its two sides.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Edge {
    pub(crate) corners: [u32; 2],
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    /// Any corner of the face; the walk starts here.
    pub(crate) corner: u32,
    /// Number of corners.
    pub(crate) len: u32,
    /// True for a face that closes a boundary loop of an open surface.
    pub(crate) hole: bool,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Vertex {
    pub(crate) position: DVec3,
    /// Any corner of the vertex; its corner ring starts here.
    pub(crate) corner: u32,
    /// Number of corners in the ring.
    pub(crate) count: u32,
}

/// An orientable 2-manifold polygon mesh in the Doubly Linked Face List
/// representation. See the crate documentation.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub(crate) vertices: Arena<Vertex>,
    pub(crate) edges: Arena<Edge>,
    pub(crate) faces: Arena<Face>,
    pub(crate) corners: Arena<Corner>,
}

/// The accessors every entity kind has, alike but for names: the handle of
/// slot `i` (`$id`), the slot of a handle after checking it (`$check`),
/// and slot `i`'s record (`$get`, and `$get_mut` where the kernel changes
/// records of that kind in place).
macro_rules! entity_accessors {
    ($arena:ident: $Record:ident, $Id:ident, $id:ident, $check:ident, $get:ident $(, $get_mut:ident)?) => {
        #[inline]
        pub(crate) fn $id(&self, i: u32) -> $Id {
            $Id {
                index: i,
                generation: self.$arena.generation(i),
            }
        }
        #[inline]
        pub(crate) fn $check(&self, handle: $Id) -> Result<u32> {
            self.$arena
                .check(EntityKind::$Record, handle.index, handle.generation)
        }
        #[inline]
        pub(crate) fn $get(&self, i: u32) -> &$Record {
            self.$arena.get(i)
        }
        $(
            #[inline]
            pub(crate) fn $get_mut(&mut self, i: u32) -> &mut $Record {
                self.$arena.get_mut(i)
            }
        )?
    };
}

/// The public lookups every entity kind has, alike but for names: the
/// handle in slot `index` (`$at`) and whether a handle is live
/// (`$contains`).
macro_rules! entity_lookups {
    ($arena:ident, $Id:ident, $id:ident, $check:ident, $at:ident, $contains:ident, $noun:literal) => {
        #[doc = concat!("The handle currently living in ", $noun, " slot `index`, if any.")]
        pub fn $at(&self, index: usize) -> Option<$Id> {
            let i = u32::try_from(index).ok()?;
            self.$arena.is_live(i).then(|| self.$id(i))
        }
        /// True if the handle names a live entity of this mesh.
        pub fn $contains(&self, handle: $Id) -> bool {
            self.$check(handle).is_ok()
        }
    };
}

/// Handle constructors and checks, and raw slot access.
impl Mesh {
    entity_accessors!(vertices: Vertex, VertexId, vid, check_vertex, v, v_mut);
    entity_accessors!(edges: Edge, EdgeId, eid, check_edge, e);
    entity_accessors!(faces: Face, FaceId, fid, check_face, f, f_mut);
    entity_accessors!(corners: Corner, CornerId, cid, check_corner, c, c_mut);

    /// The rotation successor of corner `i` around its vertex: the corner
    /// of the same vertex in the face on the other side of the edge that
    /// starts at `i`. For a point-sphere corner it is the corner itself.
    #[inline]
    pub(crate) fn rot(&self, i: u32) -> u32 {
        let e = self.c(i).edge;
        if e == NONE {
            return i;
        }
        self.c(self.mate(i, e)).next
    }

    /// The other corner of edge `e`, one of whose two corners is `i`: the
    /// corner that starts `e` on its other side.
    #[inline]
    pub(crate) fn mate(&self, i: u32, e: u32) -> u32 {
        let [a, b] = self.e(e).corners;
        if a == i { b } else { a }
    }
}

/// Counts and iteration.
impl Mesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }
    /// Number of edges (self-loops and multiple edges each count once).
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }
    /// Number of faces, hole faces included.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }
    /// Number of corners, i.e. the sum of all face sizes.
    pub fn corner_count(&self) -> usize {
        self.corners.len()
    }
    /// Number of faces flagged as holes (boundary loops).
    pub fn hole_count(&self) -> usize {
        self.faces
            .live_indices()
            .filter(|&f| self.f(f).hole)
            .count()
    }
    /// `Ok` on a closed surface, else `Err` with the number of hole faces:
    /// the refusal of the operators defined only on closed surfaces.
    pub fn require_closed(&self) -> std::result::Result<(), usize> {
        match self.hole_count() {
            0 => Ok(()),
            holes => Err(holes),
        }
    }
    /// True when the mesh has no vertices.
    pub fn is_empty(&self) -> bool {
        self.vertices.len() == 0
    }

    /// Live vertices in slot order.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        self.vertices.live_indices().map(|i| self.vid(i))
    }
    /// Live edges in slot order.
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> + '_ {
        self.edges.live_indices().map(|i| self.eid(i))
    }
    /// Live faces (holes included) in slot order. For a mesh freshly built
    /// from a file this is file order.
    pub fn faces(&self) -> impl Iterator<Item = FaceId> + '_ {
        self.faces.live_indices().map(|i| self.fid(i))
    }
    /// Live faces that are not holes (the surface's own faces), in slot
    /// order: the faces exporters, displays and selections walk, without
    /// each asking [`Mesh::is_hole`] of every face.
    pub fn surface_faces(&self) -> impl Iterator<Item = FaceId> + '_ {
        self.faces
            .live_indices()
            .filter(|&i| !self.f(i).hole)
            .map(|i| self.fid(i))
    }
    /// Live corners in slot order.
    pub fn corners(&self) -> impl Iterator<Item = CornerId> + '_ {
        self.corners.live_indices().map(|i| self.cid(i))
    }

    /// Approximate heap bytes held by the mesh.
    pub fn heap_bytes(&self) -> usize {
        self.vertices.heap_bytes()
            + self.edges.heap_bytes()
            + self.faces.heap_bytes()
            + self.corners.heap_bytes()
    }

    entity_lookups!(
        vertices,
        VertexId,
        vid,
        check_vertex,
        vertex_at,
        contains_vertex,
        "vertex"
    );
    entity_lookups!(
        edges,
        EdgeId,
        eid,
        check_edge,
        edge_at,
        contains_edge,
        "edge"
    );
    entity_lookups!(
        faces,
        FaceId,
        fid,
        check_face,
        face_at,
        contains_face,
        "face"
    );
    entity_lookups!(
        corners,
        CornerId,
        cid,
        check_corner,
        corner_at,
        contains_corner,
        "corner"
    );
}

/// Accessors. Each checks its handle and fails with [`Error::Stale`].
impl Mesh {
    /// The position of a vertex.
    pub fn position(&self, v: VertexId) -> Result<DVec3> {
        Ok(self.v(self.check_vertex(v)?).position)
    }

    /// Moves a vertex. Non-finite coordinates are refused.
    pub fn set_position(&mut self, v: VertexId, p: DVec3) -> Result<()> {
        let i = self.check_vertex(v)?;
        check_finite(p)?;
        self.v_mut(i).position = p;
        Ok(())
    }

    /// Number of corners at a vertex (its number of face incidences).
    pub fn vertex_corner_count(&self, v: VertexId) -> Result<usize> {
        Ok(self.v(self.check_vertex(v)?).count as usize)
    }

    /// Valence: the number of edge ends at the vertex (a self-loop counts twice).
    pub fn valence(&self, v: VertexId) -> Result<usize> {
        let i = self.check_vertex(v)?;
        let vx = self.v(i);
        if vx.count == 1 && self.c(vx.corner).edge == NONE {
            return Ok(0);
        }
        // Each corner at v is the start of exactly one edge end at v
        // (its outgoing edge), so valence = number of corners.
        Ok(vx.count as usize)
    }

    /// The corners of a vertex, in ring order (not rotation order).
    pub fn vertex_corners(&self, v: VertexId) -> Result<VertexCorners<'_>> {
        Ok(VertexCorners {
            walk: self.vertex_walk(v)?,
        })
    }

    /// The corners of a vertex in rotation order (the cyclic order around
    /// the vertex, taken through the faces), starting at any corner.
    pub fn vertex_rotation(&self, v: VertexId) -> Result<VertexRotation<'_>> {
        let walk = self.vertex_walk(v)?;
        Ok(VertexRotation {
            start: walk.next,
            walk,
        })
    }

    /// A walk of as many corners as vertex `v` has, from its first.
    fn vertex_walk(&self, v: VertexId) -> Result<Countdown<'_>> {
        let vx = self.v(self.check_vertex(v)?);
        Ok(Countdown {
            mesh: self,
            next: vx.corner,
            left: vx.count,
        })
    }

    /// The rotation successor of a corner around its vertex.
    pub fn corner_rotation_next(&self, c: CornerId) -> Result<CornerId> {
        let i = self.check_corner(c)?;
        Ok(self.cid(self.rot(i)))
    }

    /// The vertex a corner refers to.
    pub fn corner_vertex(&self, c: CornerId) -> Result<VertexId> {
        Ok(self.vid(self.c(self.check_corner(c)?).vertex))
    }
    /// The face a corner belongs to.
    pub fn corner_face(&self, c: CornerId) -> Result<FaceId> {
        Ok(self.fid(self.c(self.check_corner(c)?).face))
    }
    /// The next corner of the same face.
    pub fn corner_next(&self, c: CornerId) -> Result<CornerId> {
        Ok(self.cid(self.c(self.check_corner(c)?).next))
    }
    /// The previous corner of the same face.
    pub fn corner_prev(&self, c: CornerId) -> Result<CornerId> {
        Ok(self.cid(self.c(self.check_corner(c)?).prev))
    }
    /// The edge that starts at this corner, or `None` for a point-sphere.
    pub fn corner_edge(&self, c: CornerId) -> Result<Option<EdgeId>> {
        let e = self.c(self.check_corner(c)?).edge;
        Ok((e != NONE).then(|| self.eid(e)))
    }

    /// The two corners at which an edge originates. The edge runs from
    /// `corners[k]`'s vertex to the vertex of the corner after it.
    pub fn edge_corners(&self, e: EdgeId) -> Result<[CornerId; 2]> {
        let [a, b] = self.e(self.check_edge(e)?).corners;
        Ok([self.cid(a), self.cid(b)])
    }
    /// The end vertices of an edge, as seen from its first side.
    pub fn edge_vertices(&self, e: EdgeId) -> Result<[VertexId; 2]> {
        let [a, b] = self.e(self.check_edge(e)?).corners;
        Ok([self.vid(self.c(a).vertex), self.vid(self.c(b).vertex)])
    }
    /// The faces on the two sides of an edge (equal when both sides lie in one face).
    pub fn edge_faces(&self, e: EdgeId) -> Result<[FaceId; 2]> {
        let [a, b] = self.e(self.check_edge(e)?).corners;
        Ok([self.fid(self.c(a).face), self.fid(self.c(b).face)])
    }
    /// True when both ends of the edge are the same vertex.
    pub fn is_self_loop(&self, e: EdgeId) -> Result<bool> {
        let [a, b] = self.e(self.check_edge(e)?).corners;
        Ok(self.c(a).vertex == self.c(b).vertex)
    }

    /// Number of corners of a face.
    pub fn face_len(&self, f: FaceId) -> Result<usize> {
        Ok(self.f(self.check_face(f)?).len as usize)
    }
    /// True if the face closes a boundary loop.
    pub fn is_hole(&self, f: FaceId) -> Result<bool> {
        Ok(self.f(self.check_face(f)?).hole)
    }
    /// Flags or unflags a face as a hole.
    pub fn set_hole(&mut self, f: FaceId, hole: bool) -> Result<()> {
        let i = self.check_face(f)?;
        self.f_mut(i).hole = hole;
        Ok(())
    }
    /// True if the face is a point-sphere: one corner and no edge.
    pub fn is_point_sphere(&self, f: FaceId) -> Result<bool> {
        let fx = self.f(self.check_face(f)?);
        Ok(fx.len == 1 && self.c(fx.corner).edge == NONE)
    }
    /// The first corner of a face's walk.
    pub fn face_corner(&self, f: FaceId) -> Result<CornerId> {
        Ok(self.cid(self.f(self.check_face(f)?).corner))
    }
    /// The corners of a face in cyclic order, starting at [`Mesh::face_corner`].
    pub fn face_corners(&self, f: FaceId) -> Result<FaceCorners<'_>> {
        let fx = *self.f(self.check_face(f)?);
        Ok(FaceCorners {
            walk: Countdown {
                mesh: self,
                next: fx.corner,
                left: fx.len,
            },
        })
    }
    /// The corners of a face in cyclic order, starting at `c`.
    pub fn face_corners_from(&self, c: CornerId) -> Result<FaceCorners<'_>> {
        let i = self.check_corner(c)?;
        Ok(FaceCorners {
            walk: Countdown {
                mesh: self,
                next: i,
                left: self.f(self.c(i).face).len,
            },
        })
    }
    /// The vertices of a face in cyclic order.
    pub fn face_vertices(&self, f: FaceId) -> Result<Vec<VertexId>> {
        Ok(self
            .face_corners(f)?
            .map(|c| self.vid(self.c(c.index).vertex))
            .collect())
    }
    /// The positions of a face's corners in cyclic order.
    pub fn face_positions(&self, f: FaceId) -> Result<Vec<DVec3>> {
        Ok(self
            .face_corners(f)?
            .map(|c| self.v(self.c(c.index).vertex).position)
            .collect())
    }
    /// The corner of face `f` at vertex `v`, the first in walk order if the
    /// face visits `v` more than once.
    pub fn corner_of(&self, f: FaceId, v: VertexId) -> Result<Option<CornerId>> {
        let vi = self.check_vertex(v)?;
        Ok(self.face_corners(f)?.find(|c| self.c(c.index).vertex == vi))
    }
}

/// Corners of a face in cyclic order.
pub type FaceCorners<'a> = CornerCycle<'a, false>;

/// Corners of a vertex in ring order.
pub type VertexCorners<'a> = CornerCycle<'a, true>;

/// The corners met by following one link from corner to corner as many
/// times as the cycle is long: the face links (`next`) for
/// [`FaceCorners`], the vertex ring links (`vnext`) when `RING`, for
/// [`VertexCorners`]. Both cycles know their length, so neither walk has
/// to look for its start.
pub struct CornerCycle<'a, const RING: bool> {
    walk: Countdown<'a>,
}

impl<const RING: bool> Iterator for CornerCycle<'_, RING> {
    type Item = CornerId;
    #[inline]
    fn next(&mut self) -> Option<CornerId> {
        let c = self.walk.step(|mesh, c| {
            let corner = mesh.c(c);
            if RING { corner.vnext } else { corner.next }
        })?;
        Some(self.walk.mesh.cid(c))
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.walk.left as usize;
        (left, Some(left))
    }
}

impl<const RING: bool> ExactSizeIterator for CornerCycle<'_, RING> {}

/// Corners of a vertex in rotation order.
pub struct VertexRotation<'a> {
    walk: Countdown<'a>,
    start: u32,
}

impl Iterator for VertexRotation<'_> {
    type Item = CornerId;
    #[inline]
    fn next(&mut self) -> Option<CornerId> {
        let c = self.walk.step(Mesh::rot)?;
        // Back at the start early: the rotation is a shorter cycle than
        // the vertex's corners (a vertex that is not a 2-manifold point).
        if self.walk.next == self.start {
            self.walk.left = 0;
        }
        Some(self.walk.mesh.cid(c))
    }
}

/// The state of a walk from corner to corner that stops after `left`
/// corners, which the corner iterators share.
struct Countdown<'a> {
    mesh: &'a Mesh,
    next: u32,
    left: u32,
}

impl Countdown<'_> {
    /// The walk's next corner, the walk moved on to `link(mesh, corner)`;
    /// `None` once `left` corners have been met.
    #[inline]
    fn step(&mut self, link: impl FnOnce(&Mesh, u32) -> u32) -> Option<u32> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let c = self.next;
        self.next = link(self.mesh, c);
        Some(c)
    }
}

pub(crate) fn check_finite(p: DVec3) -> Result<()> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite(NonFinite::position(p)))
    }
}

/// Low-level linking shared by the operators.
impl Mesh {
    /// Adds corner `c` to the ring of vertex `v`.
    #[inline]
    pub(crate) fn ring_insert(&mut self, v: u32, c: u32) {
        let vx = *self.v(v);
        if vx.count == 0 {
            let cc = self.c_mut(c);
            cc.vnext = c;
            cc.vprev = c;
            let vm = self.v_mut(v);
            vm.corner = c;
            vm.count = 1;
            return;
        }
        let head = vx.corner;
        let tail = self.c(head).vprev;
        {
            let cc = self.c_mut(c);
            cc.vnext = head;
            cc.vprev = tail;
        }
        self.c_mut(tail).vnext = c;
        self.c_mut(head).vprev = c;
        self.v_mut(v).count += 1;
    }

    /// Removes corner `c` from the ring of its vertex.
    #[inline]
    pub(crate) fn ring_remove(&mut self, c: u32) {
        let cc = *self.c(c);
        let v = cc.vertex;
        let vm = self.v_mut(v);
        vm.count -= 1;
        if vm.count == 0 {
            vm.corner = NONE;
            return;
        }
        if vm.corner == c {
            vm.corner = cc.vnext;
        }
        self.c_mut(cc.vprev).vnext = cc.vnext;
        self.c_mut(cc.vnext).vprev = cc.vprev;
    }

    /// Makes `a -> b` consecutive in their face.
    #[inline]
    pub(crate) fn link(&mut self, a: u32, b: u32) {
        self.c_mut(a).next = b;
        self.c_mut(b).prev = a;
    }

    /// A new corner at `vertex` in `face`, added to the vertex ring; its
    /// face links are left for the caller.
    #[inline]
    pub(crate) fn new_corner(&mut self, vertex: u32, face: u32) -> u32 {
        let (c, _) = self.corners.insert(Corner {
            vertex,
            face,
            next: NONE,
            prev: NONE,
            edge: NONE,
            vnext: NONE,
            vprev: NONE,
        });
        self.ring_insert(vertex, c);
        c
    }

    pub(crate) fn new_face(&mut self, corner: u32, len: u32, hole: bool) -> u32 {
        self.faces.insert(Face { corner, len, hole }).0
    }

    /// The corner slots of face slot `f` in walk order, from its first
    /// corner: [`Mesh::face_corners`] without the ids, for the kernel's own
    /// walks.
    #[inline]
    pub(crate) fn face_corner_slots(&self, f: u32) -> impl Iterator<Item = u32> + '_ {
        let fx = *self.f(f);
        std::iter::successors(Some(fx.corner), move |&c| Some(self.c(c).next)).take(fx.len as usize)
    }

    /// Sets the face of every corner of the cycle through `start` to `face`
    /// and returns the cycle's length.
    pub(crate) fn assign_cycle(&mut self, start: u32, face: u32) -> u32 {
        let mut c = start;
        let mut n = 0;
        loop {
            self.c_mut(c).face = face;
            n += 1;
            c = self.c(c).next;
            if c == start {
                return n;
            }
        }
    }

    /// Walks the cycles through `x` and `y` in lockstep and returns which
    /// one closes first and its length: `(true, n)` for `x`'s cycle. Cost is
    /// proportional to the shorter cycle (the two must be distinct cycles).
    pub(crate) fn shorter_cycle(&self, x: u32, y: u32) -> (bool, u32) {
        let (mut a, mut b) = (x, y);
        let mut n = 0;
        loop {
            a = self.c(a).next;
            b = self.c(b).next;
            n += 1;
            if a == x {
                return (true, n);
            }
            if b == y {
                return (false, n);
            }
        }
    }

    /// After a face's corner cycle was cut in two, gives the shorter cycle a
    /// new face (copying the hole flag) and fixes both lengths. `x` and `y`
    /// are corners of the two cycles; `total` is the sum of their lengths.
    pub(crate) fn split_face_cycles(&mut self, face: u32, x: u32, y: u32, total: u32) -> u32 {
        let (x_shorter, n) = self.shorter_cycle(x, y);
        let (short, long) = if x_shorter { (x, y) } else { (y, x) };
        let hole = self.f(face).hole;
        let nf = self.new_face(short, n, hole);
        self.assign_cycle(short, nf);
        let fm = self.f_mut(face);
        fm.corner = long;
        fm.len = total - n;
        nf
    }
}

/// The four fundamental operators (§II.5).
impl Mesh {
    /// `CreateVertex(p)`: adds a point-sphere, a new component made of one
    /// vertex and one face with a single corner and no edge (Euler MVFS).
    /// Returns the vertex, the face and the face's corner.
    pub fn create_vertex(&mut self, p: DVec3) -> Result<(VertexId, FaceId, CornerId)> {
        check_finite(p)?;
        let (v, _) = self.vertices.insert(Vertex {
            position: p,
            corner: NONE,
            count: 0,
        });
        let f = self.new_face(NONE, 1, false);
        let c = self.new_corner(v, f);
        self.link(c, c);
        self.f_mut(f).corner = c;
        Ok((self.vid(v), self.fid(f), self.cid(c)))
    }

    /// `DeleteVertex(v)`: removes a point-sphere (Euler KVFS). Any other
    /// vertex is refused with [`Error::NotPointSphere`] and nothing changes.
    pub fn delete_vertex(&mut self, v: VertexId) -> Result<()> {
        let vi = self.check_vertex(v)?;
        let vx = *self.v(vi);
        if vx.count != 1 || self.c(vx.corner).edge != NONE {
            return Err(Error::NotPointSphere(v));
        }
        let c = vx.corner;
        let f = self.c(c).face;
        self.corners.remove(c);
        self.faces.remove(f);
        self.vertices.remove(vi);
        Ok(())
    }

    /// `InsertEdge(c1, c2)`: inserts an edge between the vertices of two
    /// corners, inside the angular sectors the corners stand for.
    ///
    /// - Corners of one face: the face is split in two; topology is unchanged.
    /// - Corners of two faces (point-spheres included): the faces merge into
    ///   one, which adds a handle when they were in one component and joins
    ///   the components otherwise.
    ///
    /// Each corner's sector is split in two: `c1` keeps its outgoing edge and
    /// a new corner at `c1`'s vertex takes the incoming side and starts the
    /// new edge towards `c2` (a point-sphere corner is reused instead). So
    /// after the call the face walk reads `prev(c1) → c1' → c2 …` and
    /// `prev(c2) → c2' → c1 …`, and `c1`, `c2` stay valid with their old
    /// outgoing edges.
    pub fn insert_edge(&mut self, c1: CornerId, c2: CornerId) -> Result<EdgeId> {
        let p = self.check_corner(c1)?;
        let q = self.check_corner(c2)?;
        if p == q {
            return Err(Error::SameCorner(c1));
        }
        let e = self.insert_edge_raw(p, q);
        Ok(self.eid(e))
    }

    pub(crate) fn insert_edge_raw(&mut self, p: u32, q: u32) -> u32 {
        let cp = *self.c(p);
        let cq = *self.c(q);
        let (fp, fq) = (cp.face, cq.face);
        let p_sphere = cp.edge == NONE;
        let q_sphere = cq.edge == NONE;
        let (pp, pq) = (cp.prev, cq.prev);

        let a = if p_sphere {
            p
        } else {
            self.new_corner(cp.vertex, fp)
        };
        let b = if q_sphere {
            q
        } else {
            self.new_corner(cq.vertex, fq)
        };
        if !p_sphere {
            self.link(pp, a);
        }
        self.link(a, q);
        if !q_sphere {
            self.link(pq, b);
        }
        self.link(b, p);

        let (e, _) = self.edges.insert(Edge { corners: [a, b] });
        self.c_mut(a).edge = e;
        self.c_mut(b).edge = e;

        if fp == fq {
            // Split: the cycle through p (ends with b) and through q (ends with a).
            let total = self.f(fp).len + 2;
            self.c_mut(a).face = fp;
            self.c_mut(b).face = fp;
            self.split_face_cycles(fp, p, q, total);
        } else {
            // Merge: keep the longer face, relabel the shorter one's corners.
            let (lp, lq) = (self.f(fp).len, self.f(fq).len);
            let added = u32::from(!p_sphere) + u32::from(!q_sphere);
            let (keep, drop, drop_start) = if lp >= lq { (fp, fq, q) } else { (fq, fp, p) };
            let hole = self.f(fp).hole && self.f(fq).hole;
            self.c_mut(a).face = keep;
            self.c_mut(b).face = keep;
            let mut c = drop_start;
            while self.c(c).face == drop {
                self.c_mut(c).face = keep;
                c = self.c(c).next;
            }
            self.faces.remove(drop);
            let fm = self.f_mut(keep);
            fm.len = lp + lq + added;
            fm.hole = hole;
            fm.corner = p;
        }
        e
    }

    /// `DeleteEdge(e)`: the exact inverse of [`Mesh::insert_edge`].
    ///
    /// - Two different faces beside `e`: they merge into one.
    /// - The same face on both sides: it splits in two, which removes a
    ///   handle or separates a component. An end vertex left with no other
    ///   edge becomes a point-sphere.
    pub fn delete_edge(&mut self, e: EdgeId) -> Result<()> {
        let ei = self.check_edge(e)?;
        self.delete_edge_raw(ei);
        Ok(())
    }

    /// Deletes edge `e`; returns the vertices that became point-spheres.
    pub(crate) fn delete_edge_raw(&mut self, e: u32) -> [u32; 2] {
        let [a0, b0] = self.e(e).corners;
        let ca = *self.c(a0);
        let cb = *self.c(b0);
        let (fa, fb) = (ca.face, cb.face);
        let (a1, b1, pa, pb) = (ca.next, cb.next, ca.prev, cb.prev);
        let removed = |c: u32| c == a0 || c == b0;
        // Removing the edge's two origin corners merges angular sectors:
        // a0's with next(b0) and b0's with next(a0). A corner whose face
        // successor is removed continues at the removed corner's partner,
        // skipping through chains of removed corners (monogons, dangling ends).
        let skip = |mut c: u32| -> Option<u32> {
            for _ in 0..4 {
                if !removed(c) {
                    return Some(c);
                }
                c = if c == a0 { b1 } else { a1 };
            }
            None
        };
        if !removed(pa)
            && let Some(t) = skip(a0)
        {
            self.link(pa, t);
        }
        if !removed(pb)
            && let Some(t) = skip(b0)
        {
            self.link(pb, t);
        }
        self.ring_remove(a0);
        self.ring_remove(b0);
        self.edges.remove(e);

        // Face bookkeeping for the surviving corners.
        if fa != fb {
            let (la, lb) = (self.f(fa).len, self.f(fb).len);
            let n = la + lb - 2;
            if n == 0 {
                self.faces.remove(fa);
                self.faces.remove(fb);
            } else {
                let (keep, drop, drop_run) = if la >= lb {
                    (fa, fb, (b1 != b0).then_some(b1))
                } else {
                    (fb, fa, (a1 != a0).then_some(a1))
                };
                let hole = self.f(fa).hole && self.f(fb).hole;
                if let Some(mut c) = drop_run {
                    while self.c(c).face == drop {
                        self.c_mut(c).face = keep;
                        c = self.c(c).next;
                    }
                }
                self.faces.remove(drop);
                let start = [a1, b1, pa, pb]
                    .into_iter()
                    .find(|&c| !removed(c))
                    .unwrap_or(NONE);
                let fm = self.f_mut(keep);
                fm.len = n;
                fm.corner = start;
                fm.hole = hole;
            }
        } else {
            let total = self.f(fa).len - 2;
            let x = (a1 != b0).then_some(a1);
            let y = (b1 != a0).then_some(b1);
            match (x, y) {
                (Some(x), Some(y)) => {
                    self.split_face_cycles(fa, x, y, total);
                }
                (Some(r), None) | (None, Some(r)) => {
                    let fm = self.f_mut(fa);
                    fm.len = total;
                    fm.corner = r;
                }
                (None, None) => self.faces.remove(fa),
            }
        }

        // Revive the removed corners as point-spheres where their vertex
        // has no corner left; free them otherwise.
        let mut spheres = [NONE, NONE];
        for (k, c) in [a0, b0].into_iter().enumerate() {
            let v = self.c(c).vertex;
            if self.v(v).count == 0 {
                let f = self.new_face(c, 1, false);
                let cm = self.c_mut(c);
                cm.face = f;
                cm.edge = NONE;
                cm.next = c;
                cm.prev = c;
                self.ring_insert(v, c);
                spheres[k] = v;
            } else {
                self.corners.remove(c);
            }
        }
        spheres
    }
}

#[cfg(test)]
mod tests;
