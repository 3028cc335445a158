//! TopMod's remeshing schemes in the modeler: the list the Remesh panel
//! shows (`remesh_schemes`), and a `remesh` request read into a scheme,
//! its parameters and a number of levels (run as a long operation, see
//! `long`).

use holey_subdiv::{RemeshParams, RemeshScheme};
use serde_json::{Map, Value, json};

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

const fn number(name: &'static str, label: &'static str) -> Param {
    Param {
        name,
        label,
        boolean: false,
        min: None,
        max: None,
    }
}

/// The parameters each scheme reads (the library's documentation of
/// every [`RemeshScheme`] variant names them; a test below checks this
/// table against what `remesh` refuses).
pub(super) fn params_of(scheme: RemeshScheme) -> Vec<Param> {
    use RemeshScheme as S;
    let half = |name, label, min_open: bool| Param {
        name,
        label,
        boolean: false,
        min: Some(if min_open { 0.001 } else { 0.0 }),
        max: Some(0.5),
    };
    match scheme {
        S::CornerCutting => vec![number("corner_cutting_alpha", "tension α")],
        S::ModifiedCornerCutting => {
            vec![number("modified_corner_cutting_thickness", "thickness")]
        }
        S::VertexTruncation => vec![half("vertex_truncation_offset", "offset", true)],
        S::Pentagonalization | S::CubicPentagonalization | S::DualPentagonalization => {
            vec![number("pentagonal_offset", "offset")]
        }
        S::PentagonPreserving | S::DualPentagonPreserving => {
            vec![number("pentagon_preserving_scale", "scale")]
        }
        S::Checkerboard | S::DualCheckerboard => {
            vec![half("checkerboard_thickness", "thickness", false)]
        }
        S::Root4 | S::HexagonPreserving | S::DualHexagonPreserving => vec![
            number("root4_weight", "weight"),
            number("root4_twist", "twist"),
        ],
        S::DoubleStellate => vec![number("double_stellate_offset", "offset")],
        S::ModifiedDoubleStellate => vec![
            number("stellate_height", "height"),
            number("stellate_curve", "curve"),
        ],
        S::Fractal => vec![number("fractal_offset", "offset")],
        S::Dome => vec![
            number("dome_length", "length"),
            number("dome_scale", "scale"),
        ],
        S::Dual12_6_4 | S::TwelveSixFour => vec![number("omnitruncation_scale", "scale")],
        S::LoopStyle => vec![number("loop_style_length", "length")],
        S::GlobalExtrude | S::DualGlobalExtrude => vec![
            number("extrude_length", "length"),
            number("extrude_scale", "scale"),
        ],
        S::SubdivideFace => vec![Param {
            name: "subdivide_face_quads",
            label: "quads",
            boolean: true,
            min: None,
            max: None,
        }],
        _ => Vec::new(),
    }
}

/// The value of a numeric field of `p` by name.
fn get(p: &RemeshParams, name: &str) -> Option<f64> {
    Some(match name {
        "corner_cutting_alpha" => p.corner_cutting_alpha,
        "modified_corner_cutting_thickness" => p.modified_corner_cutting_thickness,
        "vertex_truncation_offset" => p.vertex_truncation_offset,
        "pentagonal_offset" => p.pentagonal_offset,
        "pentagon_preserving_scale" => p.pentagon_preserving_scale,
        "checkerboard_thickness" => p.checkerboard_thickness,
        "root4_weight" => p.root4_weight,
        "root4_twist" => p.root4_twist,
        "double_stellate_offset" => p.double_stellate_offset,
        "stellate_height" => p.stellate_height,
        "stellate_curve" => p.stellate_curve,
        "fractal_offset" => p.fractal_offset,
        "dome_length" => p.dome_length,
        "dome_scale" => p.dome_scale,
        "omnitruncation_scale" => p.omnitruncation_scale,
        "loop_style_length" => p.loop_style_length,
        "extrude_length" => p.extrude_length,
        "extrude_scale" => p.extrude_scale,
        _ => return None,
    })
}

/// Sets a numeric field of `p` by name; `false` if there is none.
fn set(p: &mut RemeshParams, name: &str, v: f64) -> bool {
    let field = match name {
        "corner_cutting_alpha" => &mut p.corner_cutting_alpha,
        "modified_corner_cutting_thickness" => &mut p.modified_corner_cutting_thickness,
        "vertex_truncation_offset" => &mut p.vertex_truncation_offset,
        "pentagonal_offset" => &mut p.pentagonal_offset,
        "pentagon_preserving_scale" => &mut p.pentagon_preserving_scale,
        "checkerboard_thickness" => &mut p.checkerboard_thickness,
        "root4_weight" => &mut p.root4_weight,
        "root4_twist" => &mut p.root4_twist,
        "double_stellate_offset" => &mut p.double_stellate_offset,
        "stellate_height" => &mut p.stellate_height,
        "stellate_curve" => &mut p.stellate_curve,
        "fractal_offset" => &mut p.fractal_offset,
        "dome_length" => &mut p.dome_length,
        "dome_scale" => &mut p.dome_scale,
        "omnitruncation_scale" => &mut p.omnitruncation_scale,
        "loop_style_length" => &mut p.loop_style_length,
        "extrude_length" => &mut p.extrude_length,
        "extrude_scale" => &mut p.extrude_scale,
        _ => return false,
    };
    *field = v;
    true
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
                        json!(get(&defaults, p.name))
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
pub(super) fn read_request(req: &Value) -> Result<(RemeshScheme, RemeshParams, usize), ServeError> {
    let name = req
        .get("scheme")
        .and_then(Value::as_str)
        .ok_or_else(|| ServeError::BadRequest("\"scheme\" must be a string".into()))?;
    let scheme: RemeshScheme = name
        .parse()
        .map_err(|e: holey_subdiv::SubdivError| ServeError::BadRequest(e.to_string()))?;
    let levels = match req.get("levels") {
        None | Some(Value::Null) => 1,
        Some(v) => v
            .as_u64()
            .and_then(|n| usize::try_from(n).ok())
            .filter(|n| (1..=MAX_REMESH_LEVELS).contains(n))
            .ok_or_else(|| {
                ServeError::BadRequest(format!(
                    "\"levels\" must be an integer from 1 to {MAX_REMESH_LEVELS}"
                ))
            })?,
    };
    let mut params = RemeshParams::default();
    let empty = Map::new();
    let given = match req.get("params") {
        None | Some(Value::Null) => &empty,
        Some(Value::Object(m)) => m,
        Some(_) => {
            return Err(ServeError::BadRequest(
                "\"params\" must be an object of parameter names and values".into(),
            ));
        }
    };
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
            set(&mut params, key, v);
        }
    }
    Ok((scheme, params, levels))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use holey_dlfl::convert::{ImportOptions, to_dlfl};
    use holey_subdiv::{SubdivError, remesh};

    fn cube() -> holey_dlfl::Mesh {
        let soup = holey_shapes::parse_primitive("@cube").unwrap();
        to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
    }

    const ALL_FIELDS: &[&str] = &[
        "corner_cutting_alpha",
        "modified_corner_cutting_thickness",
        "vertex_truncation_offset",
        "pentagonal_offset",
        "pentagon_preserving_scale",
        "checkerboard_thickness",
        "root4_weight",
        "root4_twist",
        "double_stellate_offset",
        "stellate_height",
        "stellate_curve",
        "fractal_offset",
        "dome_length",
        "dome_scale",
        "omnitruncation_scale",
        "loop_style_length",
        "extrude_length",
        "extrude_scale",
    ];

    /// The table agrees with the library: a NaN in a field the table
    /// lists for a scheme is refused naming that field; a NaN anywhere
    /// else is not looked at.
    #[test]
    fn the_parameter_table_is_what_each_scheme_reads() {
        let cube = cube();
        for &scheme in RemeshScheme::ALL {
            let listed: Vec<&str> = params_of(scheme).iter().map(|p| p.name).collect();
            for &field in ALL_FIELDS {
                let mut p = RemeshParams::default();
                assert!(set(&mut p, field, f64::NAN));
                let got = remesh(&cube, scheme, &p, 1);
                if listed.contains(&field) {
                    match got {
                        Err(SubdivError::InvalidParameter { name, .. }) => {
                            assert_eq!(name, field, "{scheme}")
                        }
                        other => panic!("{scheme} ignored NaN in {field}: {other:?}"),
                    }
                } else {
                    assert!(
                        !matches!(got, Err(SubdivError::InvalidParameter { .. })),
                        "{scheme} reads {field}, which the table does not list"
                    );
                }
            }
        }
    }

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

    #[test]
    fn requests_are_read_and_bad_ones_refused() {
        let (s, p, n) = read_request(&json!({"scheme": "corner-cutting", "levels": 2,
            "params": {"corner_cutting_alpha": 0.6}}))
        .unwrap();
        assert_eq!((s, n), (RemeshScheme::CornerCutting, 2));
        assert_eq!(p.corner_cutting_alpha, 0.6);
        let (_, p, _) = read_request(
            &json!({"scheme": "subdivide-face", "params": {"subdivide_face_quads": false}}),
        )
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
            (json!({"scheme": "dual", "params": [1]}), "object"),
        ] {
            let e = read_request(&req).unwrap_err().to_string();
            assert!(e.contains(says), "{req}: {e:?} does not say {says:?}");
        }
    }
}
