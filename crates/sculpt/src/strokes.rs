//! Stroke files: the JSON that `holey sculpt` replays (issue 5).
//!
//! ```json
//! {
//!   "remesh": {"min_edge": 0.02, "max_edge": 0.06},
//!   "strokes": [
//!     {"brush": "inflate", "radius": 0.3, "strength": 0.02, "path": [[0,0,1], [0.1,0,1]]},
//!     {"brush": "smooth",  "radius": 0.3, "strength": 0.5,  "path": [[0,0,1]]},
//!     {"brush": "grab",    "radius": 0.4, "path": [[0,0,1], [0,0,0.5], [0,0,-1.5]]},
//!     {"brush": "move",    "path": [[2,0,0], [1.5,0,0], [1,0,0]]}
//!   ]
//! }
//! ```
//!
//! Parsing is strict: an unknown field or brush, a missing field, an empty
//! path, a non-positive radius or a non-finite number is an error naming
//! the stroke (numbered from 0, like faces). Each path point is one frame.
//! `grab` takes an optional `strength` (default 1) that scales the drag;
//! `move` takes a path and an optional `radius`: without one (or 0) it
//! moves the whole piece it picks, with one the part of it within the
//! radius, held rigidly in the inner half and blended out to the rim.
//!
//! `remesh` is the target edge-length range of dynamic remeshing; without
//! it the session derives one from the mesh's mean edge length
//! ([`crate::remesh::default_range`]).

use glam::DVec3;
use serde::Deserialize;

use crate::brush::Brush;

/// One stroke: a brush, its parameters and its path (one point per frame).
#[derive(Clone, Debug, PartialEq)]
pub struct Stroke {
    /// The brush the stroke uses.
    pub brush: Brush,
    /// World-space radius of the brush (move: 0 moves the whole piece).
    pub radius: f64,
    /// Inflate: displacement per frame at the centre (negative deflates).
    /// Smooth: fraction of a Laplacian step, in `[0, 1]`. Grab: scale of
    /// the drag (1 follows the pointer). Move: unused.
    pub strength: f64,
    /// The brush positions in world space, one per frame (never empty in a
    /// parsed file): inflate and smooth centre the brush there; grab and
    /// move pick at the first point and then follow the later ones.
    pub path: Vec<DVec3>,
}

/// The optional target edge-length range of dynamic remeshing.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Remesh {
    /// Edges shorter than this, in world units, are collapsed (positive).
    pub min_edge: f64,
    /// Edges longer than this, in world units, are split (above `min_edge`).
    pub max_edge: f64,
}

/// A parsed stroke file.
#[derive(Clone, Debug, PartialEq)]
pub struct StrokeFile {
    /// The file's `remesh` range; `None` lets the session derive one from
    /// the mesh ([`crate::remesh::default_range`]).
    pub remesh: Option<Remesh>,
    /// The strokes in file order; replaying makes each one undo step.
    pub strokes: Vec<Stroke>,
}

/// Why a stroke file was refused.
#[derive(Debug, thiserror::Error)]
pub enum StrokeFileError {
    /// Not JSON, or the top level is not `{"remesh"?, "strokes"}`.
    #[error("stroke file: {0}")]
    Json(#[source] serde_json::Error),
    /// The `remesh` range is not finite with 0 < `min_edge` < `max_edge`;
    /// the message gives the values found.
    #[error("stroke file: remesh: {0}")]
    Remesh(String),
    /// A stroke is malformed; `index` counts from 0.
    #[error("stroke {index}: {reason}")]
    Stroke {
        /// Position of the stroke in the file's `strokes` array.
        index: usize,
        /// What is wrong with it, in words: the JSON decoder's message or the
        /// check that failed.
        reason: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    #[serde(default)]
    remesh: Option<Remesh>,
    strokes: Vec<serde_json::Value>,
}

// Parsed one stroke at a time so that every error can name its stroke.
#[derive(Deserialize)]
#[serde(tag = "brush", rename_all = "lowercase", deny_unknown_fields)]
enum StrokeSpec {
    Inflate {
        radius: f64,
        strength: f64,
        path: Vec<[f64; 3]>,
    },
    Smooth {
        radius: f64,
        strength: f64,
        path: Vec<[f64; 3]>,
    },
    Grab {
        radius: f64,
        #[serde(default)]
        strength: Option<f64>,
        path: Vec<[f64; 3]>,
    },
    Move {
        #[serde(default)]
        radius: f64,
        path: Vec<[f64; 3]>,
    },
}

/// Parses and checks a stroke file.
pub fn parse_strokes(text: &str) -> Result<StrokeFile, StrokeFileError> {
    let spec: FileSpec = serde_json::from_str(text).map_err(StrokeFileError::Json)?;
    if let Some(r) = &spec.remesh
        && !(r.min_edge.is_finite()
            && r.max_edge.is_finite()
            && 0.0 < r.min_edge
            && r.min_edge < r.max_edge)
    {
        return Err(StrokeFileError::Remesh(format!(
            "need 0 < min_edge < max_edge, got min_edge {} and max_edge {}",
            r.min_edge, r.max_edge
        )));
    }
    let strokes = spec
        .strokes
        .into_iter()
        .enumerate()
        .map(|(index, value)| {
            stroke(value).map_err(|reason| StrokeFileError::Stroke { index, reason })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(StrokeFile {
        remesh: spec.remesh,
        strokes,
    })
}

fn stroke(value: serde_json::Value) -> Result<Stroke, String> {
    let spec: StrokeSpec = serde_json::from_value(value).map_err(|e| e.to_string())?;
    let (brush, radius, strength, path) = match spec {
        StrokeSpec::Inflate {
            radius,
            strength,
            path,
        } => (Brush::Inflate, radius, strength, path),
        StrokeSpec::Smooth {
            radius,
            strength,
            path,
        } => {
            // More than a full step overshoots the neighbour mean and
            // oscillates; a negative one sharpens without bound.
            if !(0.0..=1.0).contains(&strength) {
                return Err(format!(
                    "smooth: strength is the fraction of a Laplacian step and must be in [0, 1], got {strength}"
                ));
            }
            (Brush::Smooth, radius, strength, path)
        }
        StrokeSpec::Grab {
            radius,
            strength,
            path,
        } => (Brush::Grab, radius, strength.unwrap_or(1.0), path),
        StrokeSpec::Move { radius, path } => (Brush::Move, radius, 1.0, path),
    };
    if brush != Brush::Move && !(radius.is_finite() && radius > 0.0) {
        return Err(format!("{brush}: radius must be positive, got {radius}"));
    }
    if brush == Brush::Move && !(radius.is_finite() && radius >= 0.0) {
        return Err(format!(
            "move: radius must be 0 (the whole piece) or positive (a part of it), got {radius}"
        ));
    }
    if !strength.is_finite() {
        return Err(format!("{brush}: strength must be finite, got {strength}"));
    }
    if path.is_empty() {
        return Err(format!("{brush}: the path is empty"));
    }
    if let Some(k) = path.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(format!("{brush}: path point {k} is not finite"));
    }
    Ok(Stroke {
        brush,
        radius,
        strength,
        path: path.into_iter().map(DVec3::from_array).collect(),
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    const EXAMPLE: &str = r#"{
      "remesh": {"min_edge": 0.02, "max_edge": 0.06},
      "strokes": [
        {"brush": "inflate", "radius": 0.3, "strength": 0.02, "path": [[0,0,1], [0.1,0,1]]},
        {"brush": "smooth",  "radius": 0.3, "strength": 0.5,  "path": [[0,0,1]]},
        {"brush": "grab",    "radius": 0.4, "path": [[0,0,1], [0,0,0.5], [0,0,-1.5]]},
        {"brush": "move",    "path": [[2,0,0], [1.5,0,0], [1,0,0]]}
      ]
    }"#;

    #[test]
    fn the_issue_example_parses() {
        let f = parse_strokes(EXAMPLE).unwrap();
        assert_eq!(
            f.remesh,
            Some(Remesh {
                min_edge: 0.02,
                max_edge: 0.06
            })
        );
        let brushes: Vec<_> = f.strokes.iter().map(|s| s.brush).collect();
        assert_eq!(
            brushes,
            [Brush::Inflate, Brush::Smooth, Brush::Grab, Brush::Move]
        );
        assert_eq!(f.strokes[0].path, [DVec3::Z, DVec3::new(0.1, 0.0, 1.0)]);
        assert_eq!(f.strokes[2].strength, 1.0);
        assert_eq!(f.strokes[3].path.len(), 3);
        assert!(
            parse_strokes(r#"{"strokes": []}"#)
                .unwrap()
                .remesh
                .is_none()
        );
    }

    fn stroke_error(text: &str) -> (usize, String) {
        match parse_strokes(text) {
            Err(StrokeFileError::Stroke { index, reason }) => (index, reason),
            other => panic!("expected a stroke error, got {other:?}"),
        }
    }

    #[test]
    fn errors_name_the_stroke() {
        let ok = r#"{"brush": "move", "path": [[0,0,0]]}"#;
        let (i, r) = stroke_error(&format!(
            r#"{{"strokes": [{ok}, {{"brush": "pinch", "radius": 1, "path": [[0,0,0]]}}]}}"#
        ));
        assert_eq!(i, 1);
        assert!(r.contains("pinch"), "{r}");
        let (i, r) = stroke_error(&format!(
            r#"{{"strokes": [{ok}, {ok}, {{"brush": "inflate", "radius": 1, "strength": 1, "path": [[0,0,0]], "colour": 3}}]}}"#
        ));
        assert_eq!(i, 2);
        assert!(r.contains("colour"), "{r}");
        let (i, r) = stroke_error(r#"{"strokes": [{"brush": "grab", "radius": 1, "path": []}]}"#);
        assert_eq!(i, 0);
        assert!(r.contains("empty"), "{r}");
        let (_, r) = stroke_error(r#"{"strokes": [{"brush": "grab", "path": [[0,0,0]]}]}"#);
        assert!(r.contains("radius"), "{r}");
        let (_, r) = stroke_error(
            r#"{"strokes": [{"brush": "inflate", "radius": -1, "strength": 1, "path": [[0,0,0]]}]}"#,
        );
        assert!(r.contains("positive"), "{r}");
        let (_, r) = stroke_error(
            r#"{"strokes": [{"brush": "smooth", "radius": 1, "strength": 3, "path": [[0,0,0]]}]}"#,
        );
        assert!(r.contains("[0, 1]"), "{r}");
        let (_, r) = stroke_error(r#"{"strokes": [{"radius": 1, "path": [[0,0,0]]}]}"#);
        assert!(r.contains("brush"), "{r}");
        let (_, r) = stroke_error(r#"{"strokes": [{"brush": "move", "path": [[0,0]]}]}"#);
        assert!(!r.is_empty());
        let (_, r) =
            stroke_error(r#"{"strokes": [{"brush": "move", "radius": -1, "path": [[0,0,0]]}]}"#);
        assert!(r.contains("radius"), "{r}");
        let local =
            parse_strokes(r#"{"strokes": [{"brush": "move", "radius": 0.5, "path": [[0,0,0]]}]}"#)
                .unwrap();
        assert_eq!(local.strokes[0].radius, 0.5);
    }

    #[test]
    fn file_level_errors() {
        assert!(matches!(parse_strokes("{"), Err(StrokeFileError::Json(_))));
        assert!(matches!(
            parse_strokes(r#"{"strokes": [], "speed": 2}"#),
            Err(StrokeFileError::Json(_))
        ));
        assert!(matches!(
            parse_strokes(r#"{"remesh": {"min_edge": 0.1}, "strokes": []}"#),
            Err(StrokeFileError::Json(_))
        ));
        assert!(matches!(
            parse_strokes(r#"{"remesh": {"min_edge": 0.1, "max_edge": 0.05}, "strokes": []}"#),
            Err(StrokeFileError::Remesh(_))
        ));
        assert!(matches!(
            parse_strokes(
                r#"{"remesh": {"min_edge": 0.1, "max_edge": 0.5, "angle": 3}, "strokes": []}"#
            ),
            Err(StrokeFileError::Json(_))
        ));
    }
}
