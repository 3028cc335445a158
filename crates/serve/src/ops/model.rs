//! The thesis's edits on the model workspace.

use holey_dlfl::Mesh;
use holey_model::handle::{HandleParams, create_handle};
use serde_json::json;

use super::request::HandleRequest;
use super::{Out, Reply, Shared};
use crate::doc::{Content, Document};
use crate::frame::{FLAG_PREVIEW, display_model, encode};
use crate::{ConnId, ServeError};

impl Shared {
    /// An edit of the model (`op` names it in messages): the version
    /// checked, `edit` run on a copy, committed; with `preview` the result
    /// is sent to this tab only and not committed.
    pub(super) fn model_edit(
        &self,
        conn: ConnId,
        doc: &mut Document,
        op: &str,
        version: Option<u64>,
        preview: bool,
        edit: impl FnOnce(&Document, &mut Mesh) -> Result<String, ServeError>,
    ) -> Reply {
        doc.check_version(version)?;
        if doc.rind.is_some() {
            return Err(ServeError::Refused(
                "finish or cancel the rind first".into(),
            ));
        }
        let mut mesh = doc.model(op)?.clone();
        let message = edit(doc, &mut mesh)?;
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

/// `insert_edge`: between two corners (`[face, vertex]`) of one face.
pub(super) fn insert_edge(
    doc: &Document,
    mesh: &mut Mesh,
    corners: [[usize; 2]; 2],
) -> Result<String, ServeError> {
    let [[fa, va], [fb, vb]] = corners;
    let corners = [doc.corner(mesh, fa, va)?, doc.corner(mesh, fb, vb)?];
    let before = mesh.genus();
    mesh.insert_edge(corners[0], corners[1])
        .map_err(|e| ServeError::Refused(format!("insert edge: {e}")))?;
    Ok(format!(
        "edge inserted (genus {} → {})",
        before,
        mesh.genus()
    ))
}

/// `delete_edge`: the edge of that display index.
pub(super) fn delete_edge(doc: &Document, mesh: &mut Mesh, e: usize) -> Result<String, ServeError> {
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

/// `handle`: a curved handle between two faces.
pub(super) fn handle(
    doc: &Document,
    mesh: &mut Mesh,
    req: &HandleRequest,
) -> Result<String, ServeError> {
    let [fa, fb] = req.faces;
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
    let vs = match req.corners {
        Some([a, b]) => [Some(a), Some(b)],
        None => [None, None],
    };
    let a = corner(fa, vs[0])?;
    let b = corner(fb, vs[1])?;
    let segments = req.segments.unwrap_or(4);
    if !(1..=64).contains(&segments) {
        return Err(ServeError::BadRequest("segments must be 1 to 64".into()));
    }
    let params = HandleParams::new(segments, req.w1.unwrap_or(1.0), req.w2.unwrap_or(1.0));
    let before = mesh.genus();
    create_handle(mesh, a, b, &params).map_err(|e| ServeError::Refused(format!("handle: {e}")))?;
    Ok(format!("handle (genus {} → {})", before, mesh.genus()))
}
