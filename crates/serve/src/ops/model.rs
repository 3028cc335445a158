//! The thesis's edits on the model workspace.

use holey_dlfl::Mesh;
use holey_model::handle::{
    HandleCurve, HandleParams, MultiHandleParams, UnknownHandleCurve, create_handle,
    create_multi_face_handle,
};
use serde_json::json;

use super::request::HandleRequest;
use super::toolbox::plain_ids;
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
        doc.check_no_rind()?;
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

/// The hub scale of a multi-face handle when the request gives none (the
/// CLI's `--hub-scale` default).
pub(super) const DEFAULT_HUB_SCALE: f64 = 0.5;

/// `handle`: a curved handle between two faces, or with four or more
/// faces a multi-face handle joining them through a hub.
pub(super) fn handle(
    doc: &Document,
    mesh: &mut Mesh,
    req: &HandleRequest,
) -> Result<String, ServeError> {
    let segments = req.segments.unwrap_or(4);
    if !(1..=64).contains(&segments) {
        return Err(ServeError::BadRequest("segments must be 1 to 64".into()));
    }
    let curve: HandleCurve = match &req.curve {
        Some(name) => name
            .parse()
            .map_err(|e: UnknownHandleCurve| ServeError::BadRequest(e.to_string()))?,
        None => HandleCurve::default(),
    };
    let params =
        HandleParams::new(segments, req.w1.unwrap_or(1.0), req.w2.unwrap_or(1.0)).with_curve(curve);
    match req.faces.as_slice() {
        &[fa, fb] => {
            if req.hub_scale.is_some() {
                return Err(ServeError::BadRequest(
                    "\"hub_scale\" is for a handle of four or more faces".into(),
                ));
            }
            pair_handle(doc, mesh, [fa, fb], req.corners, &params)
        }
        faces if faces.len() >= 4 => {
            if req.corners.is_some() {
                return Err(ServeError::BadRequest(
                    "\"corners\" choose the twist of a two-face handle; a multi-face handle starts at each face's first corner".into(),
                ));
            }
            let hub_scale = req.hub_scale.unwrap_or(DEFAULT_HUB_SCALE);
            multi_handle(doc, mesh, faces, MultiHandleParams::new(params, hub_scale))
        }
        faces => Err(ServeError::Refused(format!(
            "a handle joins two faces, or four or more through a hub; {} selected",
            faces.len()
        ))),
    }
}

/// A handle between two faces, from the corners given (a vertex of each
/// face) or the faces' first corners.
fn pair_handle(
    doc: &Document,
    mesh: &mut Mesh,
    [fa, fb]: [usize; 2],
    corners: Option<[usize; 2]>,
    params: &HandleParams,
) -> Result<String, ServeError> {
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
    let vs = match corners {
        Some([a, b]) => [Some(a), Some(b)],
        None => [None, None],
    };
    let a = corner(fa, vs[0])?;
    let b = corner(fb, vs[1])?;
    let before = mesh.genus();
    create_handle(mesh, a, b, params).map_err(|e| ServeError::Refused(format!("handle: {e}")))?;
    Ok(format!(
        "{} handle (genus {} → {})",
        curve_title(params.curve),
        before,
        mesh.genus()
    ))
}

/// A multi-face handle: the faces (display indices) joined through a hub.
/// The library leaves the mesh unchanged on a refusal, whose faces are
/// named back by their display indices.
fn multi_handle(
    doc: &Document,
    mesh: &mut Mesh,
    shown: &[usize],
    params: MultiHandleParams,
) -> Result<String, ServeError> {
    let index = doc.index();
    let faces = shown
        .iter()
        .map(|&i| {
            index.faces.get(i).copied().ok_or_else(|| {
                ServeError::Refused(format!(
                    "face {i} does not exist ({} faces)",
                    index.faces.len()
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let before = mesh.genus();
    create_multi_face_handle(mesh, &faces, &params)
        .map_err(|e| ServeError::Refused(format!("multi-face handle: {}", plain_ids(&e, index))))?;
    Ok(format!(
        "multi-face {} handle of {} faces (genus {} → {})",
        curve_title(params.handle.curve),
        faces.len(),
        before,
        mesh.genus()
    ))
}

/// The curve as the modeler's menu names it.
fn curve_title(curve: HandleCurve) -> &'static str {
    match curve {
        HandleCurve::Hermite => "Hermite",
        HandleCurve::Bezier => "Bézier",
    }
}
