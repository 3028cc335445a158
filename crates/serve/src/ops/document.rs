//! Requests on the document as a whole: a new primitive, switching
//! workspaces, undo and redo, repairs (weld, make manifold) and the
//! remeshing setting.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use serde_json::json;

use super::{Reply, Shared, keep_workspace};
use crate::ServeError;
use crate::doc::{Content, Document};

impl Shared {
    /// `primitive`: the document becomes a built-in primitive (model workspace).
    pub(super) fn create_primitive(&self, doc: &mut Document, spec: &str) -> Reply {
        let soup = holey_shapes::parse_primitive(spec)
            .map_err(|e| ServeError::Refused(format!("{spec}: {e}")))?;
        if soup.face_count() > self.config.max_faces {
            return Err(ServeError::Refused(format!(
                "{spec} has {} faces; the modeler's limit is {}",
                soup.face_count(),
                self.config.max_faces
            )));
        }
        let mesh = to_dlfl(&soup, ImportOptions::default())
            .map_err(|e| ServeError::Refused(format!("{spec}: {e}")))?
            .mesh;
        let content = keep_workspace(doc, Content::Model(mesh))?;
        doc.rind = None;
        // A new mesh starts unmasked (undo brings the mask back too).
        doc.commit_unmasked(content);
        self.publish(doc);
        Ok(json!({"message": format!("created {spec}")}))
    }

    /// `workspace`: the document converted to the model or sculpt workspace.
    pub(super) fn switch_workspace(&self, doc: &mut Document, to: &str) -> Reply {
        if doc.content().workspace() == to {
            return Ok(json!({}));
        }
        doc.rind = None;
        let content = doc.content().clone();
        let next = match to {
            "model" => content.into_model()?,
            "sculpt" => content.into_sculpt()?,
            _ => {
                return Err(ServeError::BadRequest(format!(
                    "unknown workspace {to:?} (model or sculpt)"
                )));
            }
        };
        doc.commit(next);
        self.publish(doc);
        Ok(json!({}))
    }

    /// `undo` or `redo` (`op`).
    pub(super) fn undo_redo(&self, doc: &mut Document, op: &str) -> Reply {
        doc.check_no_rind()?;
        let done = if op == "undo" { doc.undo() } else { doc.redo() };
        if !done {
            return Err(ServeError::Refused(format!("nothing to {op}")));
        }
        self.publish(doc);
        Ok(json!({}))
    }

    /// `weld` (by a distance, a share of the mesh size) or, without one,
    /// `make_manifold`.
    pub(super) fn repair(&self, doc: &mut Document, weld: Option<f64>) -> Reply {
        doc.check_no_rind()?;
        let (content, message) = if let Some(distance) = weld {
            doc.content().welded(distance)?
        } else {
            (
                doc.content().made_manifold()?,
                "split the non-manifold edges and vertices".to_owned(),
            )
        };
        doc.commit(content);
        self.publish(doc);
        Ok(json!({"message": message}))
    }

    /// `set_remesh`: the dynamic remeshing detail in [0, 1] (0 is off).
    pub(super) fn set_remesh(&self, doc: &mut Document, detail: f64) -> Reply {
        doc.remesh_detail = detail.clamp(0.0, 1.0);
        self.publish_state(doc);
        Ok(json!({}))
    }
}
