//! # holey-sculpt: sculpting with incidental topology change
//!
//! The modeler of Bernstein & Wojtan, *Putting Holes in Holey Geometry*
//! (SIGGRAPH 2013), §4: four ordinary brushes (inflate/deflate, smooth,
//! grab, move) whose collisions change the topology of the surface as a
//! side effect, through the engine of `holey-topo` (§3).
//!
//! - [`brush`]: the brushes as pure functions of positions (no topology).
//! - [`session`]: a [`Session`] owns the mesh, applies strokes with the
//!   topology change (every frame for inflate and smooth, once at release
//!   for grab and move), undo and redo of whole strokes, diagnostics.
//! - [`strokes`]: the JSON stroke files `holey sculpt` replays.
//! - [`remesh`]: dynamic remeshing (split, collapse, flip) of the region
//!   around given vertices, never changing topology.
//!
//! Not implemented yet (issue 5): remeshing between the frames of a
//! session (the `remesh` range of a stroke file is parsed and stored, and
//! [`remesh()`] exists, but the session does not call it yet), and
//! locality of the topology change (every frame runs the engine on the
//! whole mesh, so the per-frame cost grows with the mesh, not with the
//! brushed region).
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

pub mod brush;
pub mod live;
pub mod remesh;
pub mod session;
pub mod strokes;

pub use brush::{Brush, falloff};
pub use live::{BrushSettings, FinishedStroke, LiveFrame, LiveStroke};
pub use remesh::{RemeshError, RemeshOptions, RemeshReport, remesh, remesh_in_place, remesh_with};
pub use session::{Diagnostics, Frame, ObserverError, SculptError, Session, StrokeReport};
pub use strokes::{Remesh, Stroke, StrokeFile, StrokeFileError, parse_strokes};
