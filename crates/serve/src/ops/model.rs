//! The thesis's edits on the model workspace.

use holey_dlfl::Mesh;
use holey_model::handle::{HandleParams, create_handle};
use serde_json::{Value, json};

use super::fields::{index_field, num_field, pair};
use super::{Out, Reply, Shared};
use crate::doc::{Content, Document};
use crate::frame::{FLAG_PREVIEW, display_model, encode};
use crate::{ConnId, ServeError};

impl Shared {
    /// `insert_edge`, `delete_edge` or `handle` (`op`) on the model; a handle with `preview` is sent to this tab only and not committed.
    pub(super) fn model_edit(
        &self,
        conn: ConnId,
        doc: &mut Document,
        op: &str,
        req: &Value,
    ) -> Reply {
        doc.check_version(req)?;
        if doc.rind.is_some() {
            return Err(ServeError::Refused(
                "finish or cancel the rind first".into(),
            ));
        }
        let mut mesh = doc.model(op)?.clone();
        let preview = op == "handle" && req.get("preview").and_then(Value::as_bool) == Some(true);
        let message = match op {
            "insert_edge" => insert_edge(doc, &mut mesh, req)?,
            "delete_edge" => delete_edge(doc, &mut mesh, req)?,
            _ => handle(doc, &mut mesh, req)?,
        };
        if preview {
            let (display, _) = display_model(&mesh);
            self.hub.send(
                conn,
                Out::Binary(encode(&display, FLAG_PREVIEW, doc.version(), None)),
            );
            return Ok(json!({"message": message, "preview": true}));
        }
        doc.commit(Content::Model(mesh));
        self.publish(doc);
        Ok(json!({"message": message}))
    }
}

pub(super) fn insert_edge(
    doc: &Document,
    mesh: &mut Mesh,
    req: &Value,
) -> Result<String, ServeError> {
    let bad =
        || ServeError::BadRequest("\"corners\" must be [[face, vertex], [face, vertex]]".into());
    let cs = req
        .get("corners")
        .and_then(Value::as_array)
        .ok_or_else(bad)?;
    if cs.len() != 2 {
        return Err(bad());
    }
    let mut pairs = Vec::with_capacity(2);
    for c in cs {
        pairs.push(pair(&json!({"c": c}), "c").map_err(|_| bad())?);
    }
    let mut corners = Vec::with_capacity(2);
    for [f, v] in pairs {
        corners.push(doc.corner(mesh, f, v)?);
    }
    let before = mesh.genus();
    mesh.insert_edge(corners[0], corners[1])
        .map_err(|e| ServeError::Refused(format!("insert edge: {e}")))?;
    Ok(format!(
        "edge inserted (genus {} → {})",
        before,
        mesh.genus()
    ))
}

pub(super) fn delete_edge(
    doc: &Document,
    mesh: &mut Mesh,
    req: &Value,
) -> Result<String, ServeError> {
    let e = index_field(req, "edge")?;
    let edge = *doc
        .index()
        .edges
        .get(e)
        .ok_or_else(|| ServeError::Refused(format!("edge {e} does not exist")))?;
    let before = mesh.genus();
    mesh.delete_edge(edge)
        .map_err(|e| ServeError::Refused(format!("delete edge: {e}")))?;
    Ok(format!(
        "edge deleted (genus {} → {})",
        before,
        mesh.genus()
    ))
}

pub(super) fn handle(doc: &Document, mesh: &mut Mesh, req: &Value) -> Result<String, ServeError> {
    let [fa, fb] = pair(req, "faces")?;
    let corner = |face: usize, vertex: Option<usize>| -> Result<_, ServeError> {
        match vertex {
            Some(v) => doc.corner(mesh, face, v),
            None => {
                let f =
                    *doc.index().faces.get(face).ok_or_else(|| {
                        ServeError::Refused(format!("face {face} does not exist"))
                    })?;
                mesh.face_corners(f)
                    .map_err(|e| ServeError::Refused(e.to_string()))?
                    .next()
                    .ok_or_else(|| ServeError::Refused(format!("face {face} has no corners")))
            }
        }
    };
    let vs = if req.get("corners").is_some_and(|c| !c.is_null()) {
        let [a, b] = pair(req, "corners")?;
        [Some(a), Some(b)]
    } else {
        [None, None]
    };
    let a = corner(fa, vs[0])?;
    let b = corner(fb, vs[1])?;
    let segments = req.get("segments").and_then(Value::as_u64).unwrap_or(4) as usize;
    if !(1..=64).contains(&segments) {
        return Err(ServeError::BadRequest("segments must be 1 to 64".into()));
    }
    let w = |name: &str| match req.get(name) {
        None | Some(Value::Null) => Ok(1.0),
        Some(_) => num_field(req, name),
    };
    let params = HandleParams::new(segments, w("w1")?, w("w2")?);
    let before = mesh.genus();
    create_handle(mesh, a, b, &params).map_err(|e| ServeError::Refused(format!("handle: {e}")))?;
    Ok(format!("handle (genus {} → {})", before, mesh.genus()))
}
