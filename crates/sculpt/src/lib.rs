//! # holey-sculpt: sculpting with incidental topology change
//!
//! The modeler of Bernstein & Wojtan, *Putting Holes in Holey Geometry*
//! (SIGGRAPH 2013), §4: four ordinary brushes (inflate/deflate, smooth,
//! grab, move) whose collisions change the topology of the surface as a
//! side effect, through the engine of `holey-topo` (§3); and the brushes
//! sculptors know from SculptGL and Blender (draw, clay, crease, flatten,
//! pinch, scrape, local scale, the snake hook), under the same rule.
//!
//! - [`brush`]: the brushes as pure functions of positions (no topology),
//!   one file each with its displacement field, and the falloff curves.
//! - [`symmetry`]: the mirror images a stroke is repeated across.
//! - [`session`]: a [`Session`] owns the mesh, applies strokes with the
//!   topology change (every frame for the painting brushes and the snake
//!   hook, once at release for grab and move), undo and redo of whole
//!   strokes, diagnostics.
//! - [`strokes`]: the JSON stroke files `holey sculpt` replays.
//! - [`remesh`](mod@remesh): dynamic remeshing (split, collapse, flip) of the region
//!   around given vertices, never changing topology; strokes run it after
//!   every inflate/smooth frame and after a grab's release, in a range
//!   given by the stroke file or derived from the mean edge length.
//! - [`live`]: [`LiveStroke`], a stroke fed one frame at a time (the
//!   interactive modeler drives it from mouse events).
//!
//! Every frame is local: the topology change runs on the region the
//! motion can reach ([`holey_topo::topology_change_local`]), the brushes
//! and remeshing touch only the brushed vertices, so beyond a few linear
//! scans a frame costs what the brush touches.
//!
//! ```
//! use holey_sculpt::{Session, parse_strokes};
//! use holey_topo::TriMesh;
//! use glam::DVec3;
//!
//! let mesh = TriMesh {
//!     positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
//!     triangles: vec![[0, 1, 2]],
//! };
//! let file = parse_strokes(
//!     r#"{"strokes": [{"brush": "grab", "radius": 2, "path": [[0,0,0], [0,0,1]]}]}"#,
//! )?;
//! let mut session = Session::new(mesh)?;
//! session.replay(&file, &mut |_, _| Ok(()))?;
//! assert_eq!(session.mesh().positions[0], DVec3::Z);
//! assert!(session.undo());
//! assert_eq!(session.mesh().positions[0], DVec3::ZERO);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

pub mod brush;
mod ease;
pub mod live;
pub mod remesh;
pub mod report;
pub mod session;
pub mod strokes;
pub mod symmetry;

pub use brush::{Brush, Falloff, PressureDrives, falloff};
pub use live::{BrushSettings, FinishedStroke, Handover, LiveFrame, LiveStroke};
pub use remesh::{
    RemeshError, RemeshOptions, RemeshReport, default_range, remesh, remesh_in_place, remesh_with,
};
pub use session::{Diagnostics, Frame, ObserverError, SculptError, Session, StrokeReport};
pub use strokes::{Mask, Remesh, Stroke, StrokeFile, StrokeFileError, StrokeRemesh, parse_strokes};
pub use symmetry::{About, Symmetry};
