//! TopMod's remeshing schemes in the modeler: the list the Remesh panel
//! shows (`remesh_schemes`), and a `remesh` request read into a scheme,
//! its parameters and a number of levels (run as a long operation, see
//! `long`).

use holey_subdiv::{RemeshParams, RemeshScheme};
use serde_json::{Map, Value, json};

use super::request::RemeshRequest;
use crate::ServeError;

/// The most levels the modeler runs in one request (each level of most
/// schemes multiplies the faces by 3 or 4; the face cap stops it sooner).
pub(super) const MAX_REMESH_LEVELS: usize = 8;

/// A parameter of [`RemeshParams`] as the panel shows it.
pub(super) struct Param {
    /// The field of [`RemeshParams`], which is also its name in requests.
    pub name: &'static str,
    /// What the panel calls it.
    pub label: &'static str,
    /// `true` for the one boolean field (`subdivide_face_quads`).
    pub boolean: bool,
    /// The range the library accepts, shown as the input's bounds.
    pub min: Option<f64>,
    pub max: Option<f64>,
}

/// What the panel calls a field, and the range it shows (the library's
/// checks decide; these only guide the input).
fn label_and_range(field: &str) -> (&'static str, Option<f64>, Option<f64>) {
    match field {
        "corner_cutting_alpha" => ("tension α", None, None),
        "vertex_truncation_offset" => ("offset", Some(0.001), Some(0.5)),
        "checkerboard_thickness" => ("thickness", Some(0.0), Some(0.5)),
        "modified_corner_cutting_thickness" => ("thickness", None, None),
        f if f.ends_with("offset") => ("offset", None, None),
        f if f.ends_with("scale") => ("scale", None, None),
        f if f.ends_with("length") => ("length", None, None),
        f if f.ends_with("weight") => ("weight", None, None),
        f if f.ends_with("twist") => ("twist", None, None),
        f if f.ends_with("height") => ("height", None, None),
        f if f.ends_with("curve") => ("curve", None, None),
        _ => ("value", None, None),
    }
}

/// The parameters each scheme reads: the library's option table
/// ([`RemeshScheme::options`]), named by their [`RemeshParams`] fields,
/// and subdivide-face's flag.
pub(super) fn params_of(scheme: RemeshScheme) -> Vec<Param> {
    let mut out: Vec<Param> = scheme
        .options()
        .iter()
        .map(|o| {
            let (label, min, max) = label_and_range(o.field);
            Param {
                name: o.field,
                label,
                boolean: false,
                min,
                max,
            }
        })
        .collect();
    if scheme == RemeshScheme::SubdivideFace {
        out.push(Param {
            name: "subdivide_face_quads",
            label: "quads",
            boolean: true,
            min: None,
            max: None,
        });
    }
    out
}

/// A title for the panel: the kebab name in words.
fn title(scheme: RemeshScheme) -> String {
    let name = scheme.name().replace('-', " ");
    let mut chars = name.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect(),
        None => name,
    }
}

/// `remesh_schemes`: every scheme with its parameters and their defaults,
/// in TopMod's menu order.
pub(super) fn schemes_json() -> Value {
    let defaults = RemeshParams::default();
    let list: Vec<Value> = RemeshScheme::ALL
        .iter()
        .map(|&s| {
            let params: Vec<Value> = params_of(s)
                .into_iter()
                .map(|p| {
                    let default = if p.boolean {
                        json!(defaults.subdivide_face_quads)
                    } else {
                        json!(defaults.get(s, p.name))
                    };
                    json!({"name": p.name, "label": p.label, "type": if p.boolean { "bool" } else { "number" },
                           "default": default, "min": p.min, "max": p.max})
                })
                .collect();
            json!({"name": s.name(), "title": title(s), "closed_only": s.needs_closed_surface(),
                   "params": params})
        })
        .collect();
    json!({"schemes": list, "max_levels": MAX_REMESH_LEVELS})
}

/// A `remesh` request: `scheme`, optional `levels` (1) and `params` (an
/// object of the scheme's parameters; the others are refused, so that a
/// typo does not pass silently).
pub(super) fn read_request(
    req: &RemeshRequest,
) -> Result<(RemeshScheme, RemeshParams, usize), ServeError> {
    let scheme: RemeshScheme = req
        .scheme
        .parse()
        .map_err(|e: holey_subdiv::SubdivError| ServeError::BadRequest(e.to_string()))?;
    let levels = req.levels.unwrap_or(1);
    if !(1..=MAX_REMESH_LEVELS).contains(&levels) {
        return Err(ServeError::BadRequest(format!(
            "\"levels\" must be an integer from 1 to {MAX_REMESH_LEVELS}"
        )));
    }
    let mut params = RemeshParams::default();
    let empty = Map::new();
    let given = req.params.as_ref().unwrap_or(&empty);
    let reads = params_of(scheme);
    for (key, value) in given {
        let Some(p) = reads.iter().find(|p| p.name == key) else {
            let names: Vec<&str> = reads.iter().map(|p| p.name).collect();
            return Err(ServeError::BadRequest(format!(
                "{scheme} has no parameter {key:?} ({})",
                if names.is_empty() {
                    "it has none".to_owned()
                } else {
                    format!("it reads {}", names.join(", "))
                }
            )));
        };
        if p.boolean {
            params.subdivide_face_quads = value.as_bool().ok_or_else(|| {
                ServeError::BadRequest(format!("{scheme}: {key} must be true or false"))
            })?;
        } else {
            let v = value.as_f64().filter(|v| v.is_finite()).ok_or_else(|| {
                ServeError::BadRequest(format!("{scheme}: {key} must be a finite number"))
            })?;
            params
                .set(scheme, key, v)
                .map_err(|e| ServeError::BadRequest(format!("{scheme}: {e}")))?;
        }
    }
    Ok((scheme, params, levels))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn every_scheme_is_listed_with_its_defaults() {
        let v = schemes_json();
        let list = v["schemes"].as_array().unwrap();
        assert_eq!(list.len(), RemeshScheme::ALL.len());
        let cc = list.iter().find(|s| s["name"] == "corner-cutting").unwrap();
        assert_eq!(cc["params"][0]["name"], "corner_cutting_alpha");
        assert_eq!(cc["params"][0]["default"], 9.0 / 16.0);
        let dual = list.iter().find(|s| s["name"] == "dual").unwrap();
        assert_eq!(dual["closed_only"], true);
        assert_eq!(dual["title"], "Dual");
        let sf = list.iter().find(|s| s["name"] == "subdivide-face").unwrap();
        assert_eq!(sf["params"][0]["type"], "bool");
        assert_eq!(sf["params"][0]["default"], true);
    }

    /// A `remesh` message read as the server reads it: the request's
    /// types first, then the scheme's table.
    fn read(message: Value) -> Result<(RemeshScheme, RemeshParams, usize), ServeError> {
        let mut message = message;
        message["op"] = json!("remesh");
        match super::super::request::parse(&message)? {
            super::super::request::Request::Remesh(r) => read_request(&r),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn requests_are_read_and_bad_ones_refused() {
        let (s, p, n) = read(json!({"scheme": "corner-cutting", "levels": 2,
            "params": {"corner_cutting_alpha": 0.6}}))
        .unwrap();
        assert_eq!((s, n), (RemeshScheme::CornerCutting, 2));
        assert_eq!(p.corner_cutting_alpha, 0.6);
        let (_, p, _) =
            read(json!({"scheme": "subdivide-face", "params": {"subdivide_face_quads": false}}))
                .unwrap();
        assert!(!p.subdivide_face_quads);
        for (req, says) in [
            (json!({}), "\"scheme\""),
            (json!({"scheme": "nope"}), "unknown remeshing scheme"),
            (json!({"scheme": "dual", "levels": 0}), "levels"),
            (json!({"scheme": "dual", "levels": 99}), "levels"),
            (json!({"scheme": "dual", "params": {"x": 1}}), "has none"),
            (
                json!({"scheme": "loop", "params": {"corner_cutting_alpha": 1}}),
                "no parameter",
            ),
            (
                json!({"scheme": "corner-cutting", "params": {"corner_cutting_alpha": "a"}}),
                "finite number",
            ),
            (
                json!({"scheme": "subdivide-face", "params": {"subdivide_face_quads": 1}}),
                "true or false",
            ),
            (json!({"scheme": "dual", "params": [1]}), "field \"params\""),
        ] {
            let e = read(req.clone()).unwrap_err().to_string();
            assert!(e.contains(says), "{req}: {e:?} does not say {says:?}");
        }
    }
}
