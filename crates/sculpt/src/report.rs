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
    #[error("the mesh: {0}")]
    Mesh(MeshError),
    #[error("{brush}: nothing to pick, the mesh has no triangles")]
    NoSurface { brush: Brush },
    #[error(
        "{brush}: the first path point {point} is {distance:.6} from the surface, farther than {limit:.6} ({why})"
    )]
    PickTooFar {
        brush: Brush,
        point: DVec3,
        distance: f64,
        limit: f64,
        why: &'static str,
    },
    #[error("frame {frame}: topology change failed: {source}")]
    Topo { frame: usize, source: TopoError },
    #[error("frame {frame}: {source}")]
    Observer { frame: usize, source: ObserverError },
    #[error("frame {frame}: {source}")]
    Remesh {
        frame: usize,
        source: crate::remesh::RemeshError,
    },
    /// An error of a stroke of a replayed file; `index` counts from 0.
    #[error("stroke {index} ({brush}): {source}")]
    Stroke {
        index: usize,
        brush: Brush,
        source: Box<SculptError>,
    },
}

/// What one stroke did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StrokeReport {
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
    pub corrected_odd_vertices: usize,
    pub triangles_before: usize,
    pub triangles_after: usize,
    /// Splits, collapses and flips of dynamic remeshing.
    pub remesh_operations: usize,
    /// Frames whose first result would have left the surface worse (a
    /// new hole, non-manifold curve, pinch, degenerate triangle or
    /// intersection) and that held some vertices still instead
    /// ([`holey_topo::guard`]).
    pub guarded_frames: usize,
    /// Vertex-frames held still by the guard, over the stroke.
    pub held_vertices: usize,
    /// Frames held entirely (nothing moved): by the guard, or a frame
    /// still too crumpled after the most sub-frames.
    pub held_frames: usize,
    /// For a drag the guard refused at release (the drag was undone): what
    /// the change would have made worse, in words.
    pub refused: Vec<String>,
    /// Frames split in two because the engine found the motion crumpled
    /// the surface too much for one frame (each split counts once).
    pub subframes: usize,
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
