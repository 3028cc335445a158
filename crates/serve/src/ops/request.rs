//! The WebSocket requests as types (`web/PROTOCOL.md`, "Requests"): one
//! variant per `op`, its fields typed, read by serde from the message
//! `{"id": N, "op": "<name>", ...}`. A field that is absent or `null` is
//! `None` where the protocol gives it a default; the handlers check the
//! values (ranges, names the library owns, indices of the picture), the
//! types are checked here, before anything runs.
//!
//! serde's own messages name a missing field but not an ill-typed one,
//! and neither names the op; [`parse`] says both.

use glam::DVec3;
use holey_sculpt::{About, Brush, Falloff, PressureDrives};
use serde::Deserialize;
use serde_json::{Map, Value};

use crate::ServeError;

/// One request, by its `op`.
#[derive(Debug, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case")]
pub(crate) enum Request {
    Hello,
    Primitives,
    RemeshSchemes,
    Cancel,
    Primitive {
        spec: String,
    },
    Workspace {
        workspace: String,
    },
    Undo,
    Redo,
    InsertEdge {
        version: Option<u64>,
        /// `[[face, vertex], [face, vertex]]`: two corners of one face.
        corners: [[usize; 2]; 2],
    },
    DeleteEdge {
        version: Option<u64>,
        edge: usize,
    },
    Handle(HandleRequest),
    RindBegin {
        thickness: f64,
    },
    RindPunch {
        version: Option<u64>,
        face: usize,
        peel: Option<bool>,
    },
    RindEnd {
        commit: Option<bool>,
    },
    Sierpinski {
        level: usize,
    },
    Menger {
        level: usize,
        exact: Option<bool>,
    },
    Subdivide {
        scheme: Option<String>,
        levels: usize,
    },
    Remesh(RemeshRequest),
    Wireframe {
        thickness: f64,
        columns: Option<usize>,
    },
    Tool(ToolRequest),
    Hull {
        dual: Option<bool>,
    },
    Extrude(ExtrudeRequest),
    Cut(CutRequest),
    Truncate(TruncateRequest),
    Select(SelectRequest),
    StrokeBegin(StrokeBegin),
    StrokeFrame(StrokeFrame),
    StrokeEnd,
    MaskPaint(MaskPaint),
    MaskClear,
    MaskInvert,
    SetRemesh {
        detail: f64,
    },
    Weld {
        distance: f64,
    },
    MakeManifold,
}

/// Every `op` a request may name, in the order of `web/PROTOCOL.md`'s table.
pub(crate) const OPS: &[&str] = &[
    "hello",
    "primitives",
    "primitive",
    "workspace",
    "undo",
    "redo",
    "cancel",
    "insert_edge",
    "delete_edge",
    "handle",
    "rind_begin",
    "rind_punch",
    "rind_end",
    "sierpinski",
    "menger",
    "subdivide",
    "remesh_schemes",
    "remesh",
    "extrude",
    "wireframe",
    "cut",
    "truncate",
    "hull",
    "tool",
    "select",
    "stroke_begin",
    "stroke_frame",
    "stroke_end",
    "mask_paint",
    "mask_clear",
    "mask_invert",
    "set_remesh",
    "weld",
    "make_manifold",
];

/// `handle`: two faces joined by a curved handle, or four or more joined
/// through a hub (a multi-face handle).
#[derive(Debug, Deserialize)]
pub(crate) struct HandleRequest {
    pub version: Option<u64>,
    pub faces: Vec<usize>,
    /// A vertex of each of two faces, choosing the twist; the first
    /// corners when absent.
    pub corners: Option<[usize; 2]>,
    /// `"hermite"` (the default) or `"bezier"`, as the library names them.
    pub curve: Option<String>,
    /// The hub's size (multi-face handles).
    pub hub_scale: Option<f64>,
    pub segments: Option<usize>,
    pub w1: Option<f64>,
    pub w2: Option<f64>,
    pub preview: Option<bool>,
}

/// `remesh`: a scheme of TopMod's menu by name.
#[derive(Debug, Deserialize)]
pub(crate) struct RemeshRequest {
    pub scheme: String,
    pub levels: Option<usize>,
    /// The scheme's own parameters by name. Which names there are and
    /// whether each is a number or a flag depends on the scheme (subdiv's
    /// option table), so they are read against that table, not here.
    pub params: Option<Map<String, Value>>,
}

/// `tool`: a clean-up tool by name and what it acts on.
#[derive(Debug, Deserialize)]
pub(crate) struct ToolRequest {
    pub version: Option<u64>,
    pub tool: String,
    pub faces: Option<Vec<usize>>,
    pub vertices: Option<Vec<usize>>,
    pub distance: Option<f64>,
}

/// `extrude`: the selected faces, a kind and its options. An option that
/// is absent or `null` takes the library's default; one the kind does not
/// read is refused by the library.
#[derive(Debug, Default, Deserialize)]
pub(crate) struct ExtrudeRequest {
    pub version: Option<u64>,
    pub faces: Option<Vec<usize>>,
    pub kind: Option<String>,
    pub distance: Option<f64>,
    pub scale: Option<f64>,
    pub rotation: Option<f64>,
    pub twist: Option<f64>,
    pub height: Option<f64>,
    pub count: Option<usize>,
    pub direction: Option<Direction>,
}

/// `extrude`'s `direction` (kind `together`).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Direction {
    Average,
    Normals,
}

/// `cut`: the selected vertices, edges and faces cut off by a distance.
/// (Not a flattened `Targets`: serde reads flattened fields after looking
/// for missing ones, which would hide which field is ill-typed.)
#[derive(Debug, Deserialize)]
pub(crate) struct CutRequest {
    pub version: Option<u64>,
    pub vertices: Option<Vec<usize>>,
    pub edges: Option<Vec<usize>>,
    pub faces: Option<Vec<usize>>,
    pub distance: f64,
}

/// `truncate`: as `cut` by a fraction of each edge, or every vertex (`all`).
#[derive(Debug, Deserialize)]
pub(crate) struct TruncateRequest {
    pub version: Option<u64>,
    pub vertices: Option<Vec<usize>>,
    pub edges: Option<Vec<usize>>,
    pub faces: Option<Vec<usize>>,
    pub fraction: f64,
    pub all: Option<bool>,
}

/// What `cut` and `truncate` act on: display indices of the selection.
pub(crate) struct Targets<'a> {
    pub vertices: Option<&'a [usize]>,
    pub edges: Option<&'a [usize]>,
    pub faces: Option<&'a [usize]>,
}

impl<'a> Targets<'a> {
    fn of([vertices, edges, faces]: [&'a Option<Vec<usize>>; 3]) -> Targets<'a> {
        Targets {
            vertices: vertices.as_deref(),
            edges: edges.as_deref(),
            faces: faces.as_deref(),
        }
    }
}

impl CutRequest {
    pub fn targets(&self) -> Targets<'_> {
        Targets::of([&self.vertices, &self.edges, &self.faces])
    }
}

impl TruncateRequest {
    pub fn targets(&self) -> Targets<'_> {
        Targets::of([&self.vertices, &self.edges, &self.faces])
    }
}

/// `select`: a query on the selection.
#[derive(Debug, Deserialize)]
pub(crate) struct SelectRequest {
    pub version: Option<u64>,
    pub query: String,
    pub faces: Option<Vec<usize>>,
    pub edges: Option<Vec<usize>>,
}

/// `stroke_begin`: the brush (sculpt's own `Deserialize`, so its names are
/// the stroke files' names) and its settings.
#[derive(Debug, Deserialize)]
pub(crate) struct StrokeBegin {
    pub brush: Brush,
    pub radius: f64,
    /// Required by every brush but `move`, which ignores it.
    pub strength: Option<f64>,
    pub point: [f64; 3],
    pub falloff: Option<Falloff>,
    pub symmetry: Option<String>,
    pub symmetry_about: Option<About>,
    pub pressure_drives: Option<PressureDrives>,
    pub pressure: Option<f64>,
}

impl StrokeBegin {
    /// The first frame, which the beginning carries.
    pub fn first_frame(&self) -> StrokeFrame {
        StrokeFrame {
            point: self.point,
            pressure: self.pressure,
            points: None,
            pressures: None,
        }
    }
}

/// `stroke_frame`: where the pointer is, and the pen's pressure if any;
/// `points` (with `pressures`, one each) are further dabs after it, which
/// a page sends together when they piled up while it waited for an answer.
#[derive(Debug, Deserialize)]
pub(crate) struct StrokeFrame {
    pub point: [f64; 3],
    pub pressure: Option<f64>,
    pub points: Option<Vec<[f64; 3]>>,
    pub pressures: Option<Vec<f64>>,
}

/// The most dabs one `stroke_frame` may carry (`point` and `points`).
pub const MAX_STROKE_POINTS: usize = 64;

impl StrokeFrame {
    /// Every dab of the request in order, with its pen pressure (1 when
    /// none was given); refused when `pressures` does not match `points`
    /// or there are more than [`MAX_STROKE_POINTS`].
    pub fn dabs(&self) -> Result<Vec<(DVec3, f64)>, ServeError> {
        let more = self.points.as_deref().unwrap_or_default();
        if more.len() + 1 > MAX_STROKE_POINTS {
            return Err(ServeError::BadRequest(format!(
                "a stroke_frame carries at most {MAX_STROKE_POINTS} points; got {}",
                more.len() + 1
            )));
        }
        if let Some(p) = &self.pressures
            && p.len() != more.len()
        {
            return Err(ServeError::BadRequest(format!(
                "stroke_frame: {} pressures for {} points",
                p.len(),
                more.len()
            )));
        }
        let first = (DVec3::from_array(self.point), self.pressure.unwrap_or(1.0));
        let rest = more.iter().enumerate().map(|(i, &q)| {
            let p = self.pressures.as_ref().map_or(1.0, |p| p[i]);
            (DVec3::from_array(q), p)
        });
        Ok(std::iter::once(first).chain(rest).collect())
    }
}

/// `mask_paint`: dab centres (`points`, or one `point`) and a radius.
#[derive(Debug, Deserialize)]
pub(crate) struct MaskPaint {
    pub radius: f64,
    pub points: Option<Vec<[f64; 3]>>,
    pub point: Option<[f64; 3]>,
    pub erase: Option<bool>,
}

/// The error for a field that the protocol requires only in some cases
/// (a brush's strength, a tool's distance), worded as [`parse`] words a
/// missing field.
pub(crate) fn missing(op: &str, field: &str) -> ServeError {
    ServeError::BadRequest(format!("{op:?} request: missing field \"{field}\""))
}

/// Reads a request message. The error names the op and, when a field is
/// at fault, the field.
pub(crate) fn parse(message: &Value) -> Result<Request, ServeError> {
    let Some(object) = message.as_object() else {
        return Err(ServeError::BadRequest(
            "a request is a JSON object with an \"op\"".into(),
        ));
    };
    let op = match object.get("op") {
        None | Some(Value::Null) => {
            return Err(ServeError::BadRequest("the request has no \"op\"".into()));
        }
        Some(Value::String(op)) => op.as_str(),
        Some(other) => {
            return Err(ServeError::BadRequest(format!(
                "\"op\" must be a string, got {other}"
            )));
        }
    };
    if !OPS.contains(&op) {
        return Err(ServeError::BadRequest(format!(
            "unknown op {op:?} (one of {})",
            OPS.join(", ")
        )));
    }
    Request::deserialize(message).map_err(|e| {
        let text = e.to_string();
        ServeError::BadRequest(match culprit(object, op, &text) {
            Some(field) => format!("{op:?} request, field {field:?}: {}", reword(&text, &field)),
            None => format!("{op:?} request: {}", reword(&text, "")),
        })
    })
}

/// The field an error is about, unless serde's message names it (a
/// missing field). It is a field whose value alone, with the op, fails on something other
/// than a missing field: serde reads a field's value where it meets it and
/// looks for missing fields only at the end, so a well-typed value alone
/// fails only for the fields it is missing. This runs only on a refused
/// request, of a handful of fields.
fn culprit(object: &Map<String, Value>, op: &str, error: &str) -> Option<String> {
    if error.starts_with("missing field") {
        // It names the field itself.
        return None;
    }
    object
        .iter()
        .filter(|(key, _)| !matches!(key.as_str(), "op" | "id"))
        .find(|(key, value)| {
            let mut alone = Map::new();
            alone.insert("op".into(), Value::String(op.into()));
            alone.insert((*key).clone(), (*value).clone());
            Request::deserialize(&Value::Object(alone))
                .is_err_and(|e| !e.to_string().starts_with("missing field"))
        })
        .map(|(key, _)| key.clone())
}

/// serde's message in the protocol's words: quotes for its backticks, and
/// a name's field for its "variant" (`unknown brush "paint"`).
fn reword(error: &str, field: &str) -> String {
    let text = error.replace('`', "\"");
    match text.strip_prefix("unknown variant ") {
        Some(rest) if !field.is_empty() => format!("unknown {field} {rest}"),
        _ => text,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use serde_json::json;

    use super::*;

    fn error(message: Value) -> String {
        parse(&message).unwrap_err().to_string()
    }

    /// Every op the protocol's table lists is a variant, and every variant
    /// is listed there: the table read from `web/PROTOCOL.md` itself.
    #[test]
    fn the_ops_are_the_protocols() {
        let doc = include_str!("../../../../web/PROTOCOL.md");
        let table = doc.split("### Requests").nth(1).unwrap();
        let mut listed: Vec<&str> = Vec::new();
        for line in table.lines().filter(|l| l.starts_with("| `")) {
            let cell = line.split('|').nth(1).unwrap();
            listed.extend(cell.split('`').skip(1).step_by(2));
        }
        let mut ours = OPS.to_vec();
        ours.sort_unstable();
        listed.sort_unstable();
        assert_eq!(ours, listed);
        for op in OPS {
            // An op that is a variant fails, if at all, on a field.
            let e = parse(&json!({"op": op}));
            if let Err(e) = e {
                let e = e.to_string();
                assert!(e.contains("missing field"), "{op}: {e}");
                assert!(!e.contains("unknown"), "{op}: {e}");
            }
        }
    }

    #[test]
    fn requests_read_as_the_client_sends_them() {
        let r = parse(
            &json!({"id": 3, "op": "handle", "version": 2, "faces": [1, 4],
            "segments": 6, "w1": null, "w2": 1.5, "preview": true}),
        )
        .unwrap();
        let Request::Handle(h) = r else {
            panic!("{r:?}")
        };
        assert_eq!(h.faces, [1, 4]);
        assert_eq!((h.curve, h.hub_scale), (None, None));
        assert_eq!((h.segments, h.w1, h.w2), (Some(6), None, Some(1.5)));
        assert_eq!(
            (h.version, h.corners, h.preview),
            (Some(2), None, Some(true))
        );
        let r = parse(&json!({"op": "truncate", "all": true, "fraction": 0.3})).unwrap();
        let Request::Truncate(t) = r else {
            panic!("{r:?}")
        };
        assert_eq!((t.fraction, t.all), (0.3, Some(true)));
        assert!(t.targets().faces.is_none() && t.targets().vertices.is_none());
        let r = parse(&json!({"op": "cut", "faces": [2], "edges": null, "distance": 1})).unwrap();
        let Request::Cut(c) = r else { panic!("{r:?}") };
        assert_eq!(
            (c.targets().faces, c.targets().edges),
            (Some(&[2][..]), None)
        );
        let r = parse(
            &json!({"op": "stroke_begin", "brush": "snake_hook", "radius": 0.2,
            "point": [0, 1, 2], "falloff": {"custom": [1, 1, 0.5, 0, 0]}}),
        )
        .unwrap();
        let Request::StrokeBegin(s) = r else {
            panic!("{r:?}")
        };
        assert_eq!(s.brush, Brush::SnakeHook);
        assert_eq!(
            s.first_frame().dabs().unwrap(),
            vec![(DVec3::new(0.0, 1.0, 2.0), 1.0)]
        );
        // Every brush by the name it gives itself.
        for b in holey_sculpt::brush::ALL_BRUSHES {
            let r = parse(
                &json!({"op": "stroke_begin", "brush": b.name(), "radius": 1,
                "point": [0, 0, 0]}),
            );
            assert!(
                matches!(r, Ok(Request::StrokeBegin(ref s)) if s.brush == b),
                "{b}"
            );
        }
    }

    #[test]
    fn errors_name_the_op_and_the_field() {
        for (message, says) in [
            (json!({"op": "nope"}), vec!["unknown op \"nope\"", "hello"]),
            (json!({}), vec!["no \"op\""]),
            (json!({"op": 7}), vec!["\"op\" must be a string"]),
            (json!([1]), vec!["JSON object"]),
            (
                json!({"op": "primitive"}),
                vec!["\"primitive\" request", "missing field \"spec\""],
            ),
            (
                json!({"op": "handle", "faces": [0, 1], "segments": "four"}),
                vec!["\"handle\" request", "field \"segments\"", "invalid type"],
            ),
            (
                json!({"op": "handle", "faces": 2}),
                vec!["field \"faces\"", "sequence"],
            ),
            (
                json!({"op": "insert_edge", "corners": [[0, 7], [0]]}),
                vec!["\"insert_edge\" request", "field \"corners\""],
            ),
            (
                json!({"op": "stroke_begin", "brush": "paint", "radius": 1, "point": [0, 0, 0]}),
                vec!["field \"brush\"", "unknown brush \"paint\"", "snake_hook"],
            ),
            (
                json!({"op": "stroke_frame", "point": [0, 0]}),
                vec!["\"stroke_frame\" request, field \"point\""],
            ),
            (
                json!({"op": "delete_edge", "edge": -1}),
                vec!["field \"edge\"", "-1"],
            ),
            (
                json!({"op": "extrude", "faces": "all"}),
                vec!["\"extrude\" request, field \"faces\"", "sequence"],
            ),
            (
                json!({"op": "extrude", "faces": [0], "direction": "up"}),
                vec!["field \"direction\"", "unknown direction \"up\""],
            ),
            (
                json!({"op": "truncate", "faces": [0], "fraction": "half"}),
                vec!["\"truncate\" request, field \"fraction\""],
            ),
            (
                json!({"op": "cut", "faces": ["a"], "distance": 1}),
                vec!["\"cut\" request, field \"faces\""],
            ),
            (
                json!({"op": "mask_paint", "radius": 1, "points": [[0, 0]]}),
                vec!["field \"points\""],
            ),
            (
                json!({"op": "menger", "level": 2, "exact": "yes"}),
                vec!["field \"exact\""],
            ),
            // Two bad fields: the one serde met first is named.
            (
                json!({"op": "weld", "distance": "far", "id": "x"}),
                vec!["\"weld\" request, field \"distance\""],
            ),
        ] {
            let e = error(message.clone());
            assert!(e.starts_with("bad request: "), "{message}: {e}");
            for s in says {
                assert!(e.contains(s), "{message}: {e:?} does not say {s:?}");
            }
        }
    }
}
