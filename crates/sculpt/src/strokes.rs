//! Stroke files: the JSON that `holey sculpt` replays (issue 5).
//!
//! ```json
//! {
//!   "remesh": {"min_edge": 0.02, "max_edge": 0.06},
//!   "strokes": [
//!     {"brush": "inflate", "radius": 0.3, "strength": 0.02, "path": [[0,0,1], [0.1,0,1]]},
//!     {"brush": "smooth",  "radius": 0.3, "strength": 0.5,  "path": [[0,0,1]]},
//!     {"brush": "grab",    "radius": 0.4, "path": [[0,0,1], [0,0,0.5], [0,0,-1.5]]},
//!     {"brush": "move",    "path": [[2,0,0], [1.5,0,0], [1,0,0]]},
//!     {"brush": "snake_hook", "radius": 0.3, "path": [[0,0,1], [0,0,1.5]]}
//!   ]
//! }
//! ```
//!
//! Parsing is strict: an unknown field or brush, a missing field, an empty
//! path, a non-positive radius or a non-finite number is an error naming
//! the stroke (numbered from 0, like faces). Each path point is one dab,
//! and one frame unless `frames` groups them. `grab` takes an optional
//! `strength` (default 1) that scales the drag; `move` takes a path and an
//! optional `radius`: without one (or 0) it moves the whole piece it picks,
//! with one the part of it within the radius, held rigidly in the inner
//! half and blended out to the rim. `snake_hook` hooks the surface at the
//! first point (within the radius) and pulls it along the rest, with an
//! optional `strength` (default 1, the hooked point follows the path).
//!
//! `frames` (optional, every brush) groups the path into frames: how many
//! consecutive points each frame takes, all of them together
//! ([`crate::LiveStroke::frame_together`]), summing to the path's length.
//! The modeler sends the dabs that queued while a frame was computed as
//! one frame, and a stroke recorded from it keeps those groups, so that
//! a replay computes what the modeler did. Without it each point is one
//! frame.
//!
//! `remesh` is the target edge-length range of dynamic remeshing; without
//! it the session derives one from the mesh's mean edge length
//! ([`crate::remesh::default_range`]). A stroke may carry its own
//! (`"remesh": {"min_edge": …, "max_edge": …}`, or `"remesh": "off"`),
//! which wins over the file's for that stroke: the modeler derives a range
//! from the mesh as each stroke begins and from its detail slider, so a
//! stroke it recorded keeps the range it was remeshed to.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::brush::{Brush, Falloff, PressureDrives};
use crate::symmetry::About;

/// One stroke: a brush, its parameters and its path (one point per frame).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stroke {
    /// The brush the stroke uses.
    pub brush: Brush,
    /// World-space radius of the brush (move: 0 moves the whole piece).
    pub radius: f64,
    /// Inflate: displacement per frame at the centre (negative deflates).
    /// Smooth: fraction of a Laplacian step, in `[0, 1]`. Grab: scale of
    /// the drag (1 follows the pointer). Move: unused. Snake hook: scale of
    /// the pull (1 follows the path).
    pub strength: f64,
    /// The brush positions in world space, one per frame (never empty in a
    /// parsed file): inflate and smooth centre the brush there; grab, move
    /// and snake hook pick at the first point and then follow the later
    /// ones.
    pub path: Vec<DVec3>,
    /// The falloff curve (`"falloff"`, default smooth).
    pub falloff: Falloff,
    /// Mirror the stroke across the planes normal to x, y, z
    /// (`"symmetry": "xz"`).
    pub symmetry: [bool; 3],
    /// Where the mirror planes pass (`"symmetry_about"`: `origin`, the
    /// default, or `centre`).
    pub symmetry_about: About,
    /// Vertices the stroke may not move (`"mask"`).
    pub mask: Option<Mask>,
    /// Pen pressure per path point, in `[0, 1]` (`"pressure"`; empty: 1
    /// throughout).
    pub pressure: Vec<f64>,
    /// What the pressure scales (`"pressure_drives"`: `strength`, the
    /// default, or `radius`).
    pub pressure_drives: PressureDrives,
    /// How many consecutive path points each frame takes (`"frames"`;
    /// every count positive, summing to the path's length); empty: one
    /// point a frame.
    pub frames: Vec<usize>,
    /// This stroke's own remeshing (`"remesh"`); `None`: the file's or
    /// the session's.
    pub remesh: Option<StrokeRemesh>,
}

/// A stroke's own dynamic remeshing, which wins over the file's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StrokeRemesh {
    /// Remesh to this range (`{"min_edge": …, "max_edge": …}`).
    Range(Remesh),
    /// Do not remesh (`"off"`).
    Off,
}

impl Stroke {
    /// The range this stroke remeshes to: its own (`"remesh"`), else
    /// `fallback` (the file's, or one derived from the mesh); `None` when
    /// it says `"off"` or there is none.
    pub fn remesh_or(&self, fallback: impl FnOnce() -> Option<Remesh>) -> Option<Remesh> {
        match self.remesh {
            Some(StrokeRemesh::Range(r)) => Some(r),
            Some(StrokeRemesh::Off) => None,
            None => fallback(),
        }
    }

    /// The path's points, with their pressures, grouped into the frames
    /// [`Stroke::frames`] gives (one point a frame without it, or when its
    /// counts do not cover the path exactly, as a parsed file's do).
    pub fn frame_groups(&self) -> Vec<Vec<(DVec3, f64)>> {
        let dab = |i: usize| (self.path[i], self.pressure.get(i).copied().unwrap_or(1.0));
        if !covers(&self.frames, self.path.len()) {
            return (0..self.path.len()).map(|i| vec![dab(i)]).collect();
        }
        let mut next = 0;
        self.frames
            .iter()
            .map(|&k| {
                let group = (next..next + k).map(dab).collect();
                next += k;
                group
            })
            .collect()
    }
}

/// The vertices a stroke may not move.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Mask {
    /// These vertices of the mesh the stroke starts on (`{"vertices":
    /// [0, 5, 9]}`).
    Vertices(Vec<u32>),
    /// The vertices within a ball (`{"sphere": {"centre": [0, 0, 1],
    /// "radius": 0.3}}`).
    Sphere {
        /// The ball's centre.
        centre: [f64; 3],
        /// Its radius (non-negative).
        radius: f64,
    },
}

impl Mask {
    /// The exact positions of the masked vertices of `positions`, as
    /// [`holey_geom::position_key`] gives them; indices out of range
    /// mask nothing.
    pub fn positions(&self, positions: &[DVec3]) -> std::collections::HashSet<[u64; 3]> {
        let key = holey_geom::position_key;
        match self {
            Mask::Vertices(vs) => vs
                .iter()
                .filter_map(|&v| positions.get(v as usize))
                .map(|&p| key(p))
                .collect(),
            Mask::Sphere { centre, radius } => {
                let c = DVec3::from_array(*centre);
                positions
                    .iter()
                    .filter(|p| p.distance(c) <= *radius)
                    .map(|&p| key(p))
                    .collect()
            }
        }
    }
}

/// Why a remeshing range is not one: it must be finite with
/// 0 < `min_edge` < `max_edge`.
fn check_range(r: &Remesh) -> Result<(), String> {
    if r.min_edge.is_finite()
        && r.max_edge.is_finite()
        && 0.0 < r.min_edge
        && r.min_edge < r.max_edge
    {
        return Ok(());
    }
    Err(format!(
        "need 0 < min_edge < max_edge, got min_edge {} and max_edge {}",
        r.min_edge, r.max_edge
    ))
}

/// A stroke's `"remesh"`: a range object or `"off"`.
fn stroke_remesh(value: serde_json::Value) -> Result<StrokeRemesh, String> {
    if value.as_str() == Some("off") {
        return Ok(StrokeRemesh::Off);
    }
    let range: Remesh = serde_json::from_value(value).map_err(|e| {
        format!("remesh must be {{\"min_edge\": …, \"max_edge\": …}} or \"off\": {e}")
    })?;
    check_range(&range).map_err(|e| format!("remesh: {e}"))?;
    Ok(StrokeRemesh::Range(range))
}

/// Whether `frames` groups `points` path points: positive counts that sum
/// to it (an empty list groups none).
fn covers(frames: &[usize], points: usize) -> bool {
    !frames.is_empty()
        && !frames.contains(&0)
        && frames.iter().try_fold(0usize, |a, &k| a.checked_add(k)) == Some(points)
}

/// The keys every brush accepts besides its own.
#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct Common {
    #[serde(default)]
    falloff: Falloff,
    #[serde(default)]
    symmetry: String,
    #[serde(default)]
    symmetry_about: About,
    #[serde(default)]
    mask: Option<Mask>,
    #[serde(default)]
    pressure: Vec<f64>,
    #[serde(default)]
    pressure_drives: PressureDrives,
    #[serde(default)]
    frames: Vec<usize>,
    #[serde(default)]
    remesh: Option<serde_json::Value>,
}

const COMMON_KEYS: [&str; 8] = [
    "falloff",
    "symmetry",
    "symmetry_about",
    "mask",
    "pressure",
    "pressure_drives",
    "frames",
    "remesh",
];

/// The keys of the centred brushes that have no variant of their own.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PaintSpec {
    radius: f64,
    strength: f64,
    path: Vec<[f64; 3]>,
}

/// The optional target edge-length range of dynamic remeshing.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
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
#[serde(tag = "brush", rename_all = "snake_case", deny_unknown_fields)]
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
    SnakeHook {
        radius: f64,
        #[serde(default)]
        strength: Option<f64>,
        path: Vec<[f64; 3]>,
    },
}

/// Parses and checks a stroke file.
pub fn parse_strokes(text: &str) -> Result<StrokeFile, StrokeFileError> {
    let spec: FileSpec = serde_json::from_str(text).map_err(StrokeFileError::Json)?;
    if let Some(r) = &spec.remesh {
        check_range(r).map_err(StrokeFileError::Remesh)?;
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
    let serde_json::Value::Object(mut fields) = value else {
        return Err("a stroke must be a JSON object".into());
    };
    let mut common = serde_json::Map::new();
    for key in COMMON_KEYS {
        if let Some(v) = fields.remove(key) {
            common.insert(key.into(), v);
        }
    }
    let common: Common =
        serde_json::from_value(serde_json::Value::Object(common)).map_err(|e| e.to_string())?;
    // The sculptor's brushes beyond §4's share one shape of keys.
    let named = fields
        .get("brush")
        .and_then(|b| b.as_str())
        .and_then(Brush::from_name)
        .filter(|b| {
            !matches!(
                b,
                Brush::Inflate | Brush::Smooth | Brush::Grab | Brush::Move | Brush::SnakeHook
            )
        });
    let mut out = match named {
        Some(brush) => {
            fields.remove("brush");
            let spec: PaintSpec = serde_json::from_value(serde_json::Value::Object(fields))
                .map_err(|e| format!("{brush}: {e}"))?;
            (brush, spec.radius, spec.strength, spec.path)
        }
        None => classic(fields)?,
    };
    let brush = out.0;
    if brush.strength_is_a_share() && brush != Brush::Smooth {
        let (lo, hi) = brush.share_range();
        if !(lo..=hi).contains(&out.2) {
            return Err(format!(
                "{brush}: strength is a share of the way per frame and must be in [{lo}, {hi}], got {}",
                out.2
            ));
        }
    }
    if !common.pressure.is_empty() && common.pressure.len() != out.3.len() {
        return Err(format!(
            "{brush}: {} pressure values for {} path points",
            common.pressure.len(),
            out.3.len()
        ));
    }
    if !common.frames.is_empty() && !covers(&common.frames, out.3.len()) {
        return Err(format!(
            "{brush}: frames must be positive counts of path points summing to the path's {}, got {:?}",
            out.3.len(),
            common.frames
        ));
    }
    if let Some(k) = common
        .pressure
        .iter()
        .position(|p| !(0.0..=1.0).contains(p))
    {
        return Err(format!("{brush}: pressure {k} must be in [0, 1]"));
    }
    if let Some(Mask::Sphere { centre, radius }) = &common.mask
        && !(centre.iter().all(|c| c.is_finite()) && radius.is_finite() && *radius >= 0.0)
    {
        return Err(format!(
            "{brush}: a mask sphere needs a finite centre and a non-negative radius"
        ));
    }
    let symmetry = crate::symmetry::Symmetry::parse(&common.symmetry, DVec3::ZERO)
        .ok_or_else(|| {
            format!(
                "{brush}: symmetry names axes among x, y and z, got {:?}",
                common.symmetry
            )
        })?
        .axes;
    let path = std::mem::take(&mut out.3);
    let mut s = checked(brush, out.1, out.2, path)?;
    s.falloff = common.falloff;
    s.symmetry = symmetry;
    s.symmetry_about = common.symmetry_about;
    s.mask = common.mask;
    s.pressure = common.pressure;
    s.pressure_drives = common.pressure_drives;
    s.frames = common.frames;
    s.remesh = common
        .remesh
        .map(stroke_remesh)
        .transpose()
        .map_err(|e| format!("{brush}: {e}"))?;
    Ok(s)
}

type Parts = (Brush, f64, f64, Vec<[f64; 3]>);

/// A stroke of §4's brushes and the snake hook, by their own keys.
fn classic(fields: serde_json::Map<String, serde_json::Value>) -> Result<Parts, String> {
    let spec: StrokeSpec =
        serde_json::from_value(serde_json::Value::Object(fields)).map_err(|e| e.to_string())?;
    Ok(match spec {
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
        StrokeSpec::SnakeHook {
            radius,
            strength,
            path,
        } => (Brush::SnakeHook, radius, strength.unwrap_or(1.0), path),
    })
}

/// The checks every stroke passes, and the stroke they make.
fn checked(
    brush: Brush,
    radius: f64,
    strength: f64,
    path: Vec<[f64; 3]>,
) -> Result<Stroke, String> {
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
        ..Stroke::default()
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

    #[test]
    fn frames_group_the_path_and_must_cover_it() {
        let f = parse_strokes(
            r#"{"strokes": [{"brush": "inflate", "radius": 1, "strength": 0.1,
                "path": [[0,0,0], [1,0,0], [2,0,0], [3,0,0]], "pressure": [1, 0.5, 0.25, 1],
                "frames": [1, 3]}]}"#,
        )
        .unwrap();
        let groups = f.strokes[0].frame_groups();
        assert_eq!(groups.len(), 2);
        assert_eq!(groups[0], [(DVec3::ZERO, 1.0)]);
        assert_eq!(
            groups[1],
            [
                (DVec3::X, 0.5),
                (DVec3::new(2.0, 0.0, 0.0), 0.25),
                (DVec3::new(3.0, 0.0, 0.0), 1.0)
            ]
        );
        // Without `frames`, a point a frame.
        let one = parse_strokes(EXAMPLE).unwrap().strokes[0].frame_groups();
        assert_eq!(one.len(), 2);
        assert!(one.iter().all(|g| g.len() == 1));
        for bad in ["[1, 2]", "[2, 0, 2]", "[5]", "[]"] {
            let text = format!(
                r#"{{"strokes": [{{"brush": "smooth", "radius": 1, "strength": 0.5,
                    "path": [[0,0,0], [1,0,0], [2,0,0], [3,0,0]], "frames": {bad}}}]}}"#
            );
            if bad == "[]" {
                // An empty list groups nothing: a point a frame.
                assert_eq!(
                    parse_strokes(&text).unwrap().strokes[0]
                        .frame_groups()
                        .len(),
                    4
                );
                continue;
            }
            let (i, reason) = stroke_error(&text);
            assert_eq!(i, 0);
            assert!(reason.contains("frames"), "{bad}: {reason}");
        }
        // A stroke built in code whose counts do not cover its path: a
        // point a frame, not a panic.
        let odd = Stroke {
            path: vec![DVec3::ZERO; 3],
            frames: vec![2, 5],
            ..Stroke::default()
        };
        assert_eq!(odd.frame_groups().len(), 3);
    }

    #[test]
    fn a_stroke_may_carry_its_own_remeshing() {
        let f = parse_strokes(
            r#"{"remesh": {"min_edge": 0.02, "max_edge": 0.06}, "strokes": [
                {"brush": "inflate", "radius": 1, "strength": 0.1, "path": [[0,0,0]],
                 "remesh": {"min_edge": 0.5, "max_edge": 1.5}},
                {"brush": "snake_hook", "radius": 1, "path": [[0,0,0]], "remesh": "off"},
                {"brush": "pinch", "radius": 1, "strength": 0.5, "path": [[0,0,0]]}]}"#,
        )
        .unwrap();
        let got: Vec<Option<StrokeRemesh>> = f.strokes.iter().map(|s| s.remesh).collect();
        assert_eq!(
            got,
            [
                Some(StrokeRemesh::Range(Remesh {
                    min_edge: 0.5,
                    max_edge: 1.5
                })),
                Some(StrokeRemesh::Off),
                None
            ]
        );
        for bad in [
            r#""on""#,
            r#"{"min_edge": 2, "max_edge": 1}"#,
            r#"{"min_edge": 0, "max_edge": 1}"#,
            r#"{"min_edge": 1}"#,
            "3",
        ] {
            let (i, reason) = stroke_error(&format!(
                r#"{{"strokes": [{{"brush": "clay", "radius": 1, "strength": 0.1, "path": [[0,0,0]], "remesh": {bad}}}]}}"#
            ));
            assert_eq!(i, 0);
            assert!(reason.starts_with("clay: remesh"), "{bad}: {reason}");
        }
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
