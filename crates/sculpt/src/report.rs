//! What a stroke did and why one was refused, shared by [`crate::live`]
//! and [`crate::session`].

use glam::DVec3;
use holey_topo::TopoError;
use holey_topo::mesh::MeshError;

use crate::brush::Brush;

/// An error an observer of frames may return (writing a picture, say).
pub type ObserverError = Box<dyn std::error::Error + Send + Sync>;

/// Why a stroke was refused. The session is left as it was.
#[derive(Debug, thiserror::Error)]
pub enum SculptError {
    /// The mesh a session was started on failed its checks (an index out of
    /// range, a non-finite position, too many vertices).
    #[error("the mesh: {0}")]
    Mesh(MeshError),
    /// A grab or move had nothing to pick: the mesh has no triangles.
    #[error("{brush}: nothing to pick, the mesh has no triangles")]
    NoSurface {
        /// The stroke's brush (grab or move).
        brush: Brush,
    },
    /// The first path point of a grab or move lies too far from the surface
    /// to pick it.
    #[error(
        "{brush}: the first path point {point} is {distance:.6} from the surface, farther than {limit:.6} ({why})"
    )]
    PickTooFar {
        /// The stroke's brush (grab or move).
        brush: Brush,
        /// The first path point, where the pick was tried.
        point: DVec3,
        /// Its distance to the closest point of the surface, in world units.
        distance: f64,
        /// The largest distance allowed: the brush radius for a grab,
        /// [`MOVE_PICK_FRACTION`](crate::live::MOVE_PICK_FRACTION) of the
        /// bounding-box diagonal for a move.
        limit: f64,
        /// Which of those two limits applied, in words (for the message).
        why: &'static str,
    },
    /// The topology-change engine (§3) failed on a frame.
    #[error("frame {frame}: topology change failed: {source}")]
    Topo {
        /// The frame within its stroke, from 0 (0 also when the drag's collision
        /// tally could not start; a drag's release counts as its last frame).
        frame: usize,
        /// The engine's error.
        source: TopoError,
    },
    /// The observer returned an error for a frame it was shown.
    #[error("frame {frame}: {source}")]
    Observer {
        /// The frame within its stroke, from 0, that the observer was shown.
        frame: usize,
        /// The observer's error.
        source: ObserverError,
    },
    /// Dynamic remeshing (§4) refused the mesh after a frame.
    #[error("frame {frame}: {source}")]
    Remesh {
        /// The frame within its stroke, from 0 (a grab's release counts as its
        /// last frame).
        frame: usize,
        /// Why remeshing refused.
        source: crate::remesh::RemeshError,
    },
    /// An error of a stroke of a replayed file; `index` counts from 0.
    #[error("stroke {index} ({brush}): {source}")]
    Stroke {
        /// Position of the failing stroke in the file's `strokes`.
        index: usize,
        /// That stroke's brush.
        brush: Brush,
        /// The error that stroke met.
        source: Box<SculptError>,
    },
}

/// What one stroke did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrokeReport {
    /// The stroke's brush; `None` only in a report no stroke filled in (the
    /// default).
    pub brush: Option<Brush>,
    /// Path points replayed.
    pub frames: usize,
    /// Runs of the topology-change engine (frames that moved something,
    /// or the release of a drag).
    pub engine_runs: usize,
    /// Engine runs that cut the surface (some intersection curve was
    /// inserted or some triangle deleted).
    pub changes: usize,
    /// Odd vertices over all engine runs, before and after correction.
    pub raw_odd_vertices: usize,
    /// Vertices left odd by error correction (§3.4), summed over all engine
    /// runs.
    pub corrected_odd_vertices: usize,
    /// Triangles of the mesh the stroke started from.
    pub triangles_before: usize,
    /// Triangles of the mesh the stroke ended with, after any remeshing.
    pub triangles_after: usize,
    /// Splits, collapses and flips of dynamic remeshing.
    pub remesh_operations: usize,
    /// Frames whose first result would have left the surface worse (a
    /// new hole, non-manifold curve, pinch, degenerate triangle or
    /// intersection) and that held some vertices still instead
    /// ([`holey_topo::topology_change_guarded`]).
    pub guarded_frames: usize,
    /// Vertex-frames held still by the guard, over the stroke.
    pub held_vertices: usize,
    /// Frames held entirely (nothing moved): by the guard, or a frame
    /// still too crumpled after the most sub-frames.
    pub held_frames: usize,
    /// For a drag the guard refused at release (the drag was undone): what
    /// the change would have made worse, in words.
    pub refused: Vec<String>,
    /// What the frames the guard held would have made worse, in words,
    /// each once, in the order first met (`guarded_frames` says how often).
    pub held_because: Vec<String>,
    /// Frames split in two because the engine found the motion crumpled
    /// the surface too much for one frame (each split counts once).
    pub subframes: usize,
    /// Frames the engine had to recompute on the whole mesh: neither the
    /// region the motion reaches nor the wider one around it gave a
    /// result that splices back exactly (`holey_topo::guard`). Such a
    /// frame costs what the mesh holds, not what the brush touches.
    pub whole_mesh_frames: usize,
    /// Debris the guard took out of frames' results: pieces the cut
    /// closed off, below the surface's resolution
    /// (`holey_topo::CutReport::specks_removed`).
    pub specks_removed: usize,
    /// Wall-clock seconds from the start of the stroke to its finish, any
    /// pauses between frames included.
    pub seconds: f64,
}

/// The diagnostics of the last topology change (§4's parity display).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagnostics {
    /// Raw parity per vertex of the mesh the change started from.
    pub raw_odd: Vec<bool>,
    /// Corrected parity per vertex of the same mesh.
    pub corrected_odd: Vec<bool>,
    /// Intersection curves at the end positions of that change.
    pub intersection_curves: usize,
}
