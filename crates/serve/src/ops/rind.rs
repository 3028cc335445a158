//! Rind modeling in the modeler (thesis chapter V): begin with a
//! thickness, punch or peel faces, end by committing or cancelling.

use holey_model::rind::{PunchOutcome, Rind};
use serde_json::json;

use super::{Reply, Shared};
use crate::ServeError;
use crate::doc::{Content, Document, RindMode};

impl Shared {
    /// `rind_begin`: the model's rind of a thickness, shown until it ends.
    pub(super) fn rind_begin(&self, doc: &mut Document, thickness: f64) -> Reply {
        if doc.rind.is_some() {
            return Err(ServeError::Refused("already in rind mode".into()));
        }
        let rind = Rind::from_mesh(doc.model("rind")?, thickness)
            .map_err(|e| ServeError::Refused(format!("rind: {e}")))?;
        doc.rind = Some(RindMode { rind, thickness });
        doc.touch();
        self.publish(doc);
        Ok(json!({"message": "click faces to punch (shift: peel)"}))
    }

    /// `rind_punch`: a face of the rind punched (or, with `peel`, peeled).
    pub(super) fn rind_punch(
        &self,
        doc: &mut Document,
        version: Option<u64>,
        face: usize,
        peel: bool,
    ) -> Reply {
        doc.check_version(version)?;
        let f = *doc
            .index()
            .faces
            .get(face)
            .ok_or_else(|| ServeError::Refused(format!("face {face} does not exist")))?;
        let Some(mode) = doc.rind.as_mut() else {
            return Err(ServeError::Refused("not in rind mode".into()));
        };
        let outcome = if peel {
            mode.rind.peel(f)
        } else {
            mode.rind.punch(f)
        }
        .map_err(|e| ServeError::Refused(format!("rind: {e}")))?;
        if let PunchOutcome::NotPunchable { reason } = outcome {
            return Err(ServeError::Refused(format!(
                "that face cannot be {}: {reason}",
                if peel { "peeled" } else { "punched" }
            )));
        }
        doc.touch();
        self.publish(doc);
        Ok(json!({}))
    }

    /// `rind_end`: the rind committed (`commit: true`) or cancelled.
    pub(super) fn rind_end(&self, doc: &mut Document, commit: bool) -> Reply {
        let Some(mode) = doc.rind.take() else {
            return Err(ServeError::Refused("not in rind mode".into()));
        };
        if commit {
            let t = mode.thickness;
            doc.commit(Content::Model(mode.rind.into_mesh()));
            self.publish(doc);
            Ok(json!({"message": format!("rind of thickness {t} committed")}))
        } else {
            doc.touch();
            self.publish(doc);
            Ok(json!({"message": "rind cancelled"}))
        }
    }
}
