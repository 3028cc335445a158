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
use std::hash::Hash;

use holey_dlfl::{EdgeId, FaceId, Mesh, VertexId};
use holey_model::cut::{CutOffset, CutTarget, cut};
use holey_model::extrude::{
    ExtrudeError, ExtrudeKind, ExtrudeOption, ExtrudeOptions, RegionDirection, extrude_selection,
};
use serde_json::json;

use super::request::{Direction, ExtrudeRequest, Targets};
use super::{Reply, Shared};
use crate::ServeError;
use crate::doc::{Content, Document};
use crate::frame::ModelIndex;

/// The most repetitions an extrusion request may ask for.
pub(super) const MAX_COUNT: usize = 64;

/// The request's name for the plain kind lifting the faces as one region
/// ([`ExtrudeOptions::together`]).
const TOGETHER: &str = "together";

impl Shared {
    /// `extrude`: the selected faces, each by itself (or all together,
    /// kind `together`); the reply names the new top faces.
    pub(super) fn extrude(&self, doc: &mut Document, req: &ExtrudeRequest) -> Reply {
        let mut mesh = self.model_for_edit(doc, req.version, "extrude")?;
        let faces = faces_of(doc, req.faces.as_deref())?;
        if faces.is_empty() {
            return Err(ServeError::Refused(
                "select the faces to extrude first".into(),
            ));
        }
        let ext = extrusion_of(req)?;
        let before = counts(&mesh);
        // The library puts back what it did on a refusal, and the copy is
        // only committed on success: a refusal leaves the document as it was.
        let tops = extrude_selection(&mut mesh, &faces, ext.kind, &ext.options)
            .map_err(|e| ServeError::Refused(format!("extrude: {}", refusal(&e, doc.index()))))?;
        self.check_size(&mesh)?;
        let message = format!("{} extrusion: {}", ext.name, delta(before, &mesh));
        doc.commit(Content::Model(mesh));
        let selected = display_faces(doc.index(), &tops);
        self.publish(doc);
        Ok(json!({"message": message, "faces": selected, "version": doc.version()}))
    }

    /// `cut` (by a distance in model units) or `truncate` (by a fraction
    /// of each edge), `op` as the request named it: the selected vertices,
    /// edges and faces cut off at once, each by one new face.
    pub(super) fn cut_or_truncate(
        &self,
        doc: &mut Document,
        op: &str,
        version: Option<u64>,
        selected: &Targets<'_>,
        offset: CutOffset,
    ) -> Reply {
        let mesh = self.model_for_edit(doc, version, op)?;
        let mut targets: Vec<CutTarget> = Vec::new();
        targets.extend(
            vertices_of(doc, selected.vertices)?
                .into_iter()
                .map(CutTarget::Vertex),
        );
        targets.extend(
            edges_of(doc, selected.edges)?
                .into_iter()
                .map(CutTarget::Edge),
        );
        targets.extend(
            faces_of(doc, selected.faces)?
                .into_iter()
                .map(CutTarget::Face),
        );
        if targets.is_empty() {
            return Err(ServeError::Refused(format!(
                "select the vertices (corners), edges or faces to {op} first"
            )));
        }
        self.cut_targets(doc, op, mesh, &targets, offset)
    }

    /// `truncate` with `all`: every vertex that has an edge.
    pub(super) fn truncate_all(
        &self,
        doc: &mut Document,
        version: Option<u64>,
        offset: CutOffset,
    ) -> Reply {
        let mesh = self.model_for_edit(doc, version, "truncate")?;
        let mut targets: Vec<CutTarget> = Vec::new();
        for v in mesh.vertices() {
            if mesh.valence(v).map_err(kernel)? > 0 {
                targets.push(CutTarget::Vertex(v));
            }
        }
        self.cut_targets(doc, "truncate", mesh, &targets, offset)
    }

    /// Cuts `targets` off a copy of the model and commits it.
    fn cut_targets(
        &self,
        doc: &mut Document,
        op: &str,
        mut mesh: Mesh,
        targets: &[CutTarget],
        offset: CutOffset,
    ) -> Reply {
        let before = counts(&mesh);
        let made = cut(&mut mesh, targets, offset)
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
    fn model_for_edit(
        &self,
        doc: &Document,
        version: Option<u64>,
        what: &str,
    ) -> Result<Mesh, ServeError> {
        doc.check_version(version)?;
        doc.check_no_rind()?;
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

/// What an `extrude` request asks for: the kind as it named it
/// (`together` too), and the library's kind and options.
struct Extrusion<'a> {
    name: &'a str,
    kind: ExtrudeKind,
    options: ExtrudeOptions,
}

/// Reads an `extrude` request's kind and options. A field that is absent
/// or null is not given (the library's default applies); whether the kind
/// reads the options given is the library's to say, except `direction`,
/// which only `together` reads.
fn extrusion_of(req: &ExtrudeRequest) -> Result<Extrusion<'_>, ServeError> {
    let refused = |why: String| ServeError::Refused(format!("extrude: {why}"));
    let name = req.kind.as_deref().unwrap_or(ExtrudeKind::Plain.name());
    let together = name == TOGETHER;
    let kind = if together {
        ExtrudeKind::Plain
    } else {
        name.parse::<ExtrudeKind>().map_err(|_| {
            let names: Vec<String> = ExtrudeKind::ALL
                .iter()
                .map(|k| k.name().to_owned())
                .chain(std::iter::once(TOGETHER.to_owned()))
                .collect();
            refused(format!(
                "unknown kind {name:?} (one of {})",
                and_list(&names)
            ))
        })?
    };
    if let Some(n) = req.count
        && !(1..=MAX_COUNT).contains(&n)
    {
        return Err(refused(format!(
            "\"count\" must be an integer from 1 to {MAX_COUNT}"
        )));
    }
    let direction = req.direction.map(|d| match d {
        Direction::Average => RegionDirection::Average,
        Direction::Normals => RegionDirection::VertexNormals,
    });
    if direction.is_some() && !together {
        return Err(refused(format!(
            "\"direction\" does not apply to the {name} extrusion (only to {TOGETHER})"
        )));
    }
    let options = ExtrudeOptions {
        distance: req.distance,
        scale: req.scale,
        rotation_deg: req.rotation,
        twist: req.twist,
        height: req.height,
        count: req.count,
        together: together.then(|| direction.unwrap_or(RegionDirection::Average)),
    };
    Ok(Extrusion {
        name,
        kind,
        options,
    })
}

/// "a", "a and b", "a, b and c".
fn and_list(items: &[String]) -> String {
    match items.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
    }
}

/// A refused extrusion in the request's words (its field names, the kind
/// `together`) with faces named by their display indices.
fn refusal(e: &ExtrudeError, index: &ModelIndex) -> String {
    let field = |o: &ExtrudeOption| format!("\"{o}\"");
    let text = match e {
        ExtrudeError::Unread { option, kind } => {
            let reads: Vec<String> = ExtrudeOption::ALL
                .iter()
                .filter(|&&o| kind.reads(o))
                .map(field)
                .collect();
            format!(
                "{} does not apply to the {kind} extrusion (it reads {})",
                field(option),
                and_list(&reads)
            )
        }
        ExtrudeError::UnreadTogether { option } => format!(
            "{} does not apply to the {TOGETHER} extrusion (it reads \"distance\", \"count\" and \"direction\")",
            field(option)
        ),
        // A bad value is about every face alike; a refusal that names
        // its face already needs no prefix.
        ExtrudeError::Face { cause, .. }
            if matches!(**cause, ExtrudeError::InvalidParameter { .. }) =>
        {
            cause.to_string()
        }
        ExtrudeError::Face { face, cause } => {
            let why = cause.to_string();
            if why.contains(&face.to_string()) {
                why
            } else {
                format!("face {face}: {why}")
            }
        }
        other => other.to_string(),
    };
    plain_ids(&text, index)
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

/// The entries of `table` at the display indices `shown` (absent: none),
/// repeats dropped; an index past the table is refused, naming it.
fn lookup<T: Copy + PartialEq>(
    table: &[T],
    shown: Option<&[usize]>,
    what: &str,
) -> Result<Vec<T>, ServeError> {
    let mut out: Vec<T> = Vec::new();
    for &i in shown.unwrap_or_default() {
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
pub(super) fn faces_of(doc: &Document, shown: Option<&[usize]>) -> Result<Vec<FaceId>, ServeError> {
    lookup(&doc.index().faces, shown, "face")
}

/// The edges a request names by display index, repeats dropped.
pub(super) fn edges_of(doc: &Document, shown: Option<&[usize]>) -> Result<Vec<EdgeId>, ServeError> {
    lookup(&doc.index().edges, shown, "edge")
}

/// The vertices a request names by display index, repeats dropped.
pub(super) fn vertices_of(
    doc: &Document,
    shown: Option<&[usize]>,
) -> Result<Vec<VertexId>, ServeError> {
    lookup(&doc.index().vertices, shown, "vertex")
}

/// The display indices of `faces` (faces not displayed, holes, left out).
pub(super) fn display_faces(index: &ModelIndex, faces: &[FaceId]) -> Vec<usize> {
    display_indices(&index.faces, faces)
}

/// The display indices of `edges`.
pub(super) fn display_edges(index: &ModelIndex, edges: &[EdgeId]) -> Vec<usize> {
    display_indices(&index.edges, edges)
}

/// Where each of `ids` stands in `shown`, the display order of one kind
/// of element; ids not shown are left out. Faces and edges are mapped
/// back to the indices the user sees the same way.
fn display_indices<T: Copy + Eq + Hash>(shown: &[T], ids: &[T]) -> Vec<usize> {
    let at: HashMap<T, usize> = shown.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    ids.iter().filter_map(|id| at.get(id).copied()).collect()
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
    use serde_json::Value;

    use crate::doc::primitive_mesh as mesh;

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

    /// Extrudes face `f` of `m` as an `extrude` request with `fields`
    /// asks, read as the server reads it; a refusal in the words the user
    /// is shown.
    fn extrude_req(m: &mut Mesh, faces: &[FaceId], fields: &Value) -> Result<Vec<FaceId>, String> {
        let (_, index) = display_model(m);
        let mut message = fields.clone();
        message["op"] = json!("extrude");
        let req = match super::super::request::parse(&message).map_err(|e| e.to_string())? {
            super::super::request::Request::Extrude(req) => req,
            other => panic!("{other:?}"),
        };
        let ext = extrusion_of(&req).map_err(|e| e.to_string())?;
        extrude_selection(m, faces, ext.kind, &ext.options).map_err(|e| refusal(&e, &index))
    }

    fn positions(m: &Mesh) -> Vec<[u64; 3]> {
        m.vertices()
            .map(|v| m.position(v).unwrap().to_array().map(f64::to_bits))
            .collect()
    }

    /// Each kind on one quad (d = 4) of a cube, against the counts its
    /// definition implies (V − E + F stays 2 for every one):
    /// - plain, Doo–Sabin, cubical and together, k repetitions: each adds
    ///   a ring of d corners, d rising edges and d ring edges, and d side
    ///   quads (the face moves up): +d, +2d, +d per repetition;
    /// - octahedral: a turned d-gon (+d corners, d edges), each new corner
    ///   joined to the two old ones below it (2d edges), 2d triangles;
    /// - dodecahedral: two rings of pentagons, +3d corners, +5d edges, +2d;
    /// - icosahedral: +3d, +9d, +6d (triangles and pentagon fans);
    /// - stellate: an apex (+1), d spokes, d triangles in place of the
    ///   face: +1, +d, +d − 1;
    /// - double stellate: stellate, then each of its d triangles
    ///   stellated (+1, +3, +2 each): +d + 1, +4d, +3d − 1;
    /// - dome of k rings: k rings of d corners and an apex (kd + 1), each
    ///   ring d rising and d ring edges plus d spokes (2kd + d), kd quads
    ///   and d triangles in place of the face (kd + d − 1).
    #[test]
    fn every_kind_extrudes_with_the_counts_of_its_definition() {
        let d = 4;
        for (fields, dv, de, df) in [
            (json!({}), d, 2 * d, d),
            (json!({"kind": "plain", "count": 2}), 2 * d, 4 * d, 2 * d),
            (json!({"kind": "together"}), d, 2 * d, d),
            (
                json!({"kind": "together", "count": 3, "direction": "normals"}),
                3 * d,
                6 * d,
                3 * d,
            ),
            (json!({"kind": "doo-sabin", "twist": 0.1}), d, 2 * d, d),
            (json!({"kind": "cubical", "count": 3}), 3 * d, 6 * d, 3 * d),
            (json!({"kind": "octahedral"}), d, 3 * d, 2 * d),
            (json!({"kind": "dodecahedral"}), 3 * d, 5 * d, 2 * d),
            (
                json!({"kind": "icosahedral", "height": 0.5}),
                3 * d,
                9 * d,
                6 * d,
            ),
            (json!({"kind": "stellate", "distance": 0.5}), 1, d, d - 1),
            (json!({"kind": "double-stellate"}), d + 1, 4 * d, 3 * d - 1),
            (
                json!({"kind": "dome", "count": 3}),
                3 * d + 1,
                2 * 3 * d + d,
                3 * d + d - 1,
            ),
            // A dome's rings default to the library's.
            (
                json!({"kind": "dome"}),
                5 * d + 1,
                2 * 5 * d + d,
                5 * d + d - 1,
            ),
        ] {
            let mut m = mesh("@cube");
            let f = m.faces().next().unwrap();
            let tops = extrude_req(&mut m, &[f], &fields).unwrap();
            assert_eq!(tops.len(), 1, "{fields}");
            m.validate().unwrap();
            assert_eq!(
                counts(&m),
                [8 + dv as i64, 12 + de as i64, 6 + df as i64],
                "{fields}"
            );
            assert_eq!(m.genus(), 0, "{fields}");
        }
    }

    /// Every kind refuses each option it does not read, naming the option
    /// and what the kind reads, and the mesh is left as it was.
    #[test]
    fn an_option_a_kind_does_not_read_is_refused() {
        let fields = ["distance", "scale", "rotation", "twist", "height", "count"];
        let cube = mesh("@cube");
        let f = cube.faces().next().unwrap();
        let before = positions(&cube);
        let mut refused = 0;
        for kind in ExtrudeKind::ALL {
            for (option, field) in ExtrudeOption::ALL.into_iter().zip(fields) {
                assert_eq!(option.name(), field);
                let req = json!({"kind": kind.name(), field: 2});
                let mut m = cube.clone();
                let r = extrude_req(&mut m, &[f], &req);
                if kind.reads(option) {
                    continue;
                }
                let e = r.unwrap_err();
                assert!(
                    e.starts_with(&format!(
                        "\"{field}\" does not apply to the {kind} extrusion"
                    )),
                    "{req}: {e}"
                );
                assert_eq!(positions(&m), before, "{req}");
                refused += 1;
            }
        }
        assert!(refused > 30);
        for (req, says) in [
            (
                json!({"kind": "together", "scale": 2}),
                "\"scale\" does not apply to the together extrusion",
            ),
            (
                json!({"kind": "stellate", "direction": "normals"}),
                "\"direction\" does not apply to the stellate",
            ),
            (
                json!({"direction": "average"}),
                "\"direction\" does not apply to the plain",
            ),
        ] {
            let mut m = cube.clone();
            let e = extrude_req(&mut m, &[f], &req).unwrap_err();
            assert!(e.contains(says), "{req}: {e}");
            assert_eq!(positions(&m), before, "{req}");
        }
    }

    /// Without a distance, a stellation lifts its apex as the library's
    /// default does (0: the apex is the face's centroid, in its plane).
    #[test]
    fn stellate_default_distance_is_the_library_default() {
        for kind in [ExtrudeKind::Stellate, ExtrudeKind::DoubleStellate] {
            let mut served = mesh("@cube");
            let f = served.faces().next().unwrap();
            extrude_req(&mut served, &[f], &json!({"kind": kind.name()})).unwrap();
            let mut library = mesh("@cube");
            let g = library.faces().next().unwrap();
            extrude_selection(&mut library, &[g], kind, &ExtrudeOptions::default()).unwrap();
            assert_eq!(positions(&served), positions(&library), "{kind}");
            // Nothing is lifted off the cube (corners at ±1): every corner stays in it.
            for v in served.vertices() {
                let p = served.position(v).unwrap();
                assert!(p.abs().max_element() <= 1.0 + 1e-12, "{kind}: {p}");
            }
        }
    }

    #[test]
    fn bad_extrusions_are_refused() {
        let mut m = mesh("@cube");
        let f = m.faces().next().unwrap();
        for (fields, says) in [
            (
                json!({"kind": "nope"}),
                "unknown kind \"nope\" (one of plain, cubical",
            ),
            (json!({"count": 0}), "count"),
            (json!({"count": 65}), "count"),
            (json!({"scale": -1}), "scale"),
            (json!({"distance": "x"}), "distance"),
            (json!({"kind": "together", "direction": "up"}), "direction"),
        ] {
            let e = extrude_req(&mut m, &[f], &fields).unwrap_err();
            assert!(e.contains(says), "{fields}: {e:?}");
        }
    }
}
