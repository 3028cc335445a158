//! TopMod's toolbox on the selection (issue 18): extrusions of the
//! selected faces, conical cuts and truncation of the selected vertices,
//! edges and faces. Each is one undo step. The whole-mesh tools
//! (remeshing, wireframe and columns, the convex hull and dual convex
//! hull, planarize and the other clean-ups) build on a worker as long
//! operations (`long`); the selection queries are in `select`.
//!
//! Requests name display indices; this file turns them into the kernel's
//! handles, and the handles in the library's error messages back into
//! display indices, so that a refusal names what the user sees.

use std::collections::HashMap;

use holey_dlfl::{EdgeId, FaceId, Mesh, VertexId};
use holey_model::cut::{CutOffset, CutTarget, cut};
use holey_model::extrude::{
    DomeParams, DooSabinParams, ExtrudeParams, MultiExtrudeParams, RegionDirection,
    double_stellate_face, extrude_face, extrude_face_cubical, extrude_face_dodecahedral,
    extrude_face_dome, extrude_face_doo_sabin, extrude_face_icosahedral, extrude_face_octahedral,
    extrude_faces, stellate_face,
};
use serde_json::{Value, json};

use super::fields::num_field;
use super::{Reply, Shared};
use crate::ServeError;
use crate::doc::{Content, Document};
use crate::frame::ModelIndex;

/// The most repetitions an extrusion request may ask for.
pub(super) const MAX_COUNT: usize = 64;

/// The extrusion kinds, as requests name them.
pub(super) const EXTRUDE_KINDS: &[&str] = &[
    "plain",
    "together",
    "doo-sabin",
    "cubical",
    "dodecahedral",
    "icosahedral",
    "octahedral",
    "stellate",
    "double-stellate",
    "dome",
];

impl Shared {
    /// `extrude`: the selected faces, each by itself (or all together,
    /// kind `together`); the reply names the new top faces.
    pub(super) fn extrude(&self, doc: &mut Document, req: &Value) -> Reply {
        let mut mesh = self.model_for_edit(doc, req, "extrude")?;
        let faces = faces_of(doc, req, "faces")?;
        if faces.is_empty() {
            return Err(ServeError::Refused(
                "select the faces to extrude first".into(),
            ));
        }
        let kind = match req.get("kind") {
            None | Some(Value::Null) => "plain",
            Some(v) => v
                .as_str()
                .ok_or_else(|| ServeError::BadRequest("\"kind\" must be a string".into()))?,
        };
        let before = counts(&mesh);
        let tops = extrude_with(&mut mesh, &faces, kind, req)
            .map_err(|e| ServeError::Refused(format!("extrude: {}", plain_ids(&e, doc.index()))))?;
        self.check_size(&mesh)?;
        let message = format!("{kind} extrusion: {}", delta(before, &mesh));
        doc.commit(Content::Model(mesh));
        let selected = display_faces(doc.index(), &tops);
        self.publish(doc);
        Ok(json!({"message": message, "faces": selected, "version": doc.version()}))
    }

    /// `cut` (by a distance in model units) or `truncate` (by a fraction
    /// of each edge, or every vertex with `all`): the selected vertices,
    /// edges and faces cut off at once, each by one new face.
    pub(super) fn cut_or_truncate(&self, doc: &mut Document, op: &str, req: &Value) -> Reply {
        let mut mesh = self.model_for_edit(doc, req, op)?;
        let truncate = op == "truncate";
        let mut targets: Vec<CutTarget> = Vec::new();
        if truncate && req.get("all").and_then(Value::as_bool) == Some(true) {
            for v in mesh.vertices() {
                if mesh.valence(v).map_err(kernel)? > 0 {
                    targets.push(CutTarget::Vertex(v));
                }
            }
        } else {
            targets.extend(
                vertices_of(doc, req, "vertices")?
                    .into_iter()
                    .map(CutTarget::Vertex),
            );
            targets.extend(
                edges_of(doc, req, "edges")?
                    .into_iter()
                    .map(CutTarget::Edge),
            );
            targets.extend(
                faces_of(doc, req, "faces")?
                    .into_iter()
                    .map(CutTarget::Face),
            );
        }
        if targets.is_empty() {
            return Err(ServeError::Refused(format!(
                "select the vertices (corners), edges or faces to {op} first"
            )));
        }
        let offset = if truncate {
            CutOffset::Fraction(num_field(req, "fraction")?)
        } else {
            CutOffset::Distance(num_field(req, "distance")?)
        };
        let before = counts(&mesh);
        let made = cut(&mut mesh, &targets, offset)
            .map_err(|e| ServeError::Refused(format!("{op}: {}", plain_ids(&e, doc.index()))))?;
        let message = format!(
            "{op}: {} new face{}, {}",
            made.len(),
            if made.len() == 1 { "" } else { "s" },
            delta(before, &mesh)
        );
        doc.commit(Content::Model(mesh));
        let selected = display_faces(doc.index(), &made);
        self.publish(doc);
        Ok(json!({"message": message, "faces": selected, "version": doc.version()}))
    }

    /// A copy of the model to edit, after the checks every selection edit
    /// makes: the picture's version, no rind being punched.
    fn model_for_edit(&self, doc: &Document, req: &Value, what: &str) -> Result<Mesh, ServeError> {
        doc.check_version(req)?;
        if doc.rind.is_some() {
            return Err(ServeError::Refused(
                "finish or cancel the rind first".into(),
            ));
        }
        Ok(doc.model(what)?.clone())
    }

    fn check_size(&self, mesh: &Mesh) -> Result<(), ServeError> {
        let faces = mesh.face_count();
        if faces > self.config.max_faces {
            return Err(ServeError::Refused(format!(
                "that would make {faces} faces; the modeler's limit is {}",
                self.config.max_faces
            )));
        }
        Ok(())
    }
}

/// Extrudes `faces` by `kind`; returns the top faces made.
fn extrude_with(
    mesh: &mut Mesh,
    faces: &[FaceId],
    kind: &str,
    req: &Value,
) -> Result<Vec<FaceId>, String> {
    let opt = |name: &str, default: f64| -> Result<f64, String> {
        match req.get(name) {
            None | Some(Value::Null) => Ok(default),
            Some(_) => num_field(req, name).map_err(|e| e.to_string()),
        }
    };
    let count = match req.get("count") {
        None | Some(Value::Null) => 1,
        Some(v) => v
            .as_u64()
            .and_then(|n| usize::try_from(n).ok())
            .filter(|n| (1..=MAX_COUNT).contains(n))
            .ok_or_else(|| format!("\"count\" must be an integer from 1 to {MAX_COUNT}"))?,
    };
    let distance = opt("distance", 1.0)?;
    let height = opt("height", 1.0)?;
    if kind == "together" {
        let direction = match req.get("direction").and_then(Value::as_str) {
            None | Some("average") => RegionDirection::Average,
            Some("normals") => RegionDirection::VertexNormals,
            Some(other) => {
                return Err(format!("unknown direction {other:?} (average or normals)"));
            }
        };
        let params = MultiExtrudeParams {
            distance,
            direction,
            count,
        };
        return extrude_faces(mesh, faces, &params)
            .map(|m| m.tops)
            .map_err(|e| e.to_string());
    }
    if !EXTRUDE_KINDS.contains(&kind) {
        return Err(format!(
            "unknown kind {kind:?} (one of {})",
            EXTRUDE_KINDS.join(", ")
        ));
    }
    let plain = ExtrudeParams {
        distance,
        rotation_deg: opt("rotation", 0.0)?,
        scale: opt("scale", 1.0)?,
        count,
    };
    let doo_sabin = DooSabinParams {
        distance,
        twist: opt("twist", 0.0)?,
        scale: opt("scale", 1.0)?,
        count,
    };
    let dome = DomeParams {
        height_factor: height,
        rings: match req.get("count") {
            None | Some(Value::Null) => DomeParams::default().rings,
            _ => count,
        },
    };
    // Every face not consumed keeps its handle through the others'
    // extrusions, so the list stays good; the first refusal leaves a
    // partly edited copy, which the caller drops.
    let mut tops = Vec::with_capacity(faces.len());
    for &f in faces {
        let made = match kind {
            "plain" => extrude_face(mesh, f, &plain),
            "doo-sabin" => extrude_face_doo_sabin(mesh, f, &doo_sabin),
            "cubical" => extrude_face_cubical(mesh, f, height, count),
            "dodecahedral" => extrude_face_dodecahedral(mesh, f, height),
            "icosahedral" => extrude_face_icosahedral(mesh, f, height),
            "octahedral" => extrude_face_octahedral(mesh, f, height),
            "stellate" => stellate_face(mesh, f, distance),
            "double-stellate" => double_stellate_face(mesh, f, distance),
            _ => extrude_face_dome(mesh, f, &dome),
        }
        .map_err(|e| e.to_string())?;
        tops.push(made.top);
    }
    Ok(tops)
}

fn kernel(e: holey_dlfl::Error) -> ServeError {
    ServeError::Refused(e.to_string())
}

/// V, E and F (holes not counted) of a mesh.
pub(super) fn counts(mesh: &Mesh) -> [i64; 3] {
    [
        mesh.vertex_count() as i64,
        mesh.edge_count() as i64,
        (mesh.face_count() - mesh.hole_count()) as i64,
    ]
}

/// "V 8 → 12, E 12 → 20, F 6 → 10".
pub(super) fn delta(before: [i64; 3], mesh: &Mesh) -> String {
    let after = counts(mesh);
    format!(
        "V {} → {}, E {} → {}, F {} → {}",
        before[0], after[0], before[1], after[1], before[2], after[2]
    )
}

/// A list of display indices (`name`, absent or null: none).
fn indices(req: &Value, name: &str) -> Result<Vec<usize>, ServeError> {
    let bad = || {
        ServeError::BadRequest(format!(
            "\"{name}\" must be a list of non-negative integers"
        ))
    };
    match req.get(name) {
        None | Some(Value::Null) => Ok(Vec::new()),
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_u64()
                    .and_then(|n| usize::try_from(n).ok())
                    .ok_or_else(bad)
            })
            .collect(),
        Some(_) => Err(bad()),
    }
}

fn lookup<T: Copy + PartialEq>(
    table: &[T],
    req: &Value,
    name: &str,
    what: &str,
) -> Result<Vec<T>, ServeError> {
    let mut out: Vec<T> = Vec::new();
    for i in indices(req, name)? {
        let id = *table.get(i).ok_or_else(|| {
            ServeError::Refused(format!(
                "{what} {i} does not exist ({} {what}s)",
                table.len()
            ))
        })?;
        if !out.contains(&id) {
            out.push(id);
        }
    }
    Ok(out)
}

/// The faces a request names by display index, repeats dropped.
pub(super) fn faces_of(doc: &Document, req: &Value, name: &str) -> Result<Vec<FaceId>, ServeError> {
    lookup(&doc.index().faces, req, name, "face")
}

/// The edges a request names by display index, repeats dropped.
pub(super) fn edges_of(doc: &Document, req: &Value, name: &str) -> Result<Vec<EdgeId>, ServeError> {
    lookup(&doc.index().edges, req, name, "edge")
}

/// The vertices a request names by display index, repeats dropped.
pub(super) fn vertices_of(
    doc: &Document,
    req: &Value,
    name: &str,
) -> Result<Vec<VertexId>, ServeError> {
    lookup(&doc.index().vertices, req, name, "vertex")
}

/// The display indices of `faces` (faces not displayed, holes, left out).
pub(super) fn display_faces(index: &ModelIndex, faces: &[FaceId]) -> Vec<usize> {
    let at: HashMap<FaceId, usize> = index
        .faces
        .iter()
        .enumerate()
        .map(|(i, &f)| (f, i))
        .collect();
    faces.iter().filter_map(|f| at.get(f).copied()).collect()
}

/// The display indices of `edges`.
pub(super) fn display_edges(index: &ModelIndex, edges: &[EdgeId]) -> Vec<usize> {
    let at: HashMap<EdgeId, usize> = index
        .edges
        .iter()
        .enumerate()
        .map(|(i, &e)| (e, i))
        .collect();
    edges.iter().filter_map(|e| at.get(e).copied()).collect()
}

/// A library message with its kernel handles (`f12v3`, `e7v1`, `v4v1`)
/// replaced by the display indices the user sees; a handle with none (a
/// hole face) is left as it is.
pub(super) fn plain_ids(message: &impl ToString, index: &ModelIndex) -> String {
    let text = message.to_string();
    let mut out = String::with_capacity(text.len());
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if let Some((len, shown)) = handle_at(&text, i, index) {
            out.push_str(&shown);
            i += len;
            continue;
        }
        // Copy one whole character.
        let ch_len = text[i..].chars().next().map_or(1, char::len_utf8);
        out.push_str(&text[i..i + ch_len]);
        i += ch_len;
    }
    out
}

/// The handle starting at byte `i` of `text`, if one does and the
/// display has it: its length and the display index as text.
fn handle_at(text: &str, i: usize, index: &ModelIndex) -> Option<(usize, String)> {
    let bytes = text.as_bytes();
    if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_') {
        return None;
    }
    let kind = bytes[i];
    if !matches!(kind, b'f' | b'e' | b'v') {
        return None;
    }
    let digits = |from: usize| {
        let n = bytes[from..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        (n > 0).then_some(n)
    };
    let n1 = digits(i + 1)?;
    let v_at = i + 1 + n1;
    if bytes.get(v_at) != Some(&b'v') {
        return None;
    }
    let n2 = digits(v_at + 1)?;
    let end = v_at + 1 + n2;
    if bytes
        .get(end)
        .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
    {
        return None;
    }
    let slot: usize = text[i + 1..v_at].parse().ok()?;
    let generation: u32 = text[v_at + 1..end].parse().ok()?;
    let same = |s: usize, g: u32| s == slot && g == generation;
    let shown = match kind {
        b'f' => index
            .faces
            .iter()
            .position(|f| same(f.index(), f.generation())),
        b'e' => index
            .edges
            .iter()
            .position(|e| same(e.index(), e.generation())),
        _ => index
            .vertices
            .iter()
            .position(|v| same(v.index(), v.generation())),
    }?;
    Some((end - i, shown.to_string()))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::frame::display_model;
    use holey_dlfl::convert::{ImportOptions, to_dlfl};

    fn mesh(spec: &str) -> Mesh {
        let soup = holey_shapes::parse_primitive(spec).unwrap();
        to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
    }

    #[test]
    fn handles_in_messages_become_display_indices() {
        let m = mesh("@cube");
        let (_, index) = display_model(&m);
        let f = index.faces[3];
        let e = index.edges[5];
        let text = format!(
            "face {f} and edge {e}; xf{}v{} stays",
            f.index(),
            f.generation()
        );
        let shown = plain_ids(&text, &index);
        assert_eq!(
            shown,
            format!(
                "face 3 and edge 5; xf{}v{} stays",
                f.index(),
                f.generation()
            )
        );
        // A handle the display does not have is left alone.
        assert_eq!(plain_ids(&"face f999v1", &index), "face f999v1");
        assert_eq!(plain_ids(&"ünïcode f", &index), "ünïcode f");
    }

    /// Each kind on one face of a cube, counted against the library's
    /// documented deltas for a 4-gon (extrude/mod.rs's table, d = 4).
    #[test]
    fn every_kind_extrudes_with_its_documented_counts() {
        let d = 4;
        for (kind, fields, dv, de, df) in [
            ("plain", json!({"count": 2}), 2 * d, 4 * d, 2 * d),
            ("together", json!({}), d, 2 * d, d),
            ("doo-sabin", json!({}), d, 2 * d, d),
            ("cubical", json!({"count": 3}), 3 * d, 6 * d, 3 * d),
            ("octahedral", json!({}), d, 3 * d, 2 * d),
            ("dodecahedral", json!({}), 3 * d, 5 * d, 2 * d),
            ("icosahedral", json!({}), 3 * d, 9 * d, 6 * d),
            ("stellate", json!({"distance": 0.5}), 1, d, d - 1),
            ("double-stellate", json!({}), d + 1, 4 * d, 3 * d - 1),
            (
                "dome",
                json!({"count": 5}),
                5 * d + 1,
                2 * 5 * d + d,
                5 * d + d - 1,
            ),
        ] {
            let mut m = mesh("@cube");
            let f = m.faces().next().unwrap();
            let tops = extrude_with(&mut m, &[f], kind, &fields).unwrap();
            assert_eq!(tops.len(), 1, "{kind}");
            m.validate().unwrap();
            assert_eq!(
                counts(&m),
                [8 + dv as i64, 12 + de as i64, 6 + df as i64],
                "{kind}"
            );
            assert_eq!(m.genus(), 0, "{kind}");
        }
    }

    #[test]
    fn bad_extrusions_are_refused() {
        let mut m = mesh("@cube");
        let f = m.faces().next().unwrap();
        for (kind, fields, says) in [
            ("nope", json!({}), "unknown kind"),
            ("plain", json!({"count": 0}), "count"),
            ("plain", json!({"scale": -1}), "scale"),
            ("plain", json!({"distance": "x"}), "distance"),
            ("together", json!({"direction": "up"}), "direction"),
        ] {
            let e = extrude_with(&mut m, &[f], kind, &fields).unwrap_err();
            assert!(e.contains(says), "{kind} {fields}: {e:?}");
        }
    }
}
