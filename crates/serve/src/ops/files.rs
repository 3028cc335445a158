//! Uploads and downloads.

use holey_dlfl::Mesh;
use holey_dlfl::convert::{ImportOptions, infer_edges, to_dlfl};
use holey_io::{Format, MeshFile};

use super::Shared;
use crate::ServeError;
use crate::doc::{Content, poly_to_tri};

impl Shared {
    /// Replaces the document with an uploaded file (one undo step).
    pub fn import(&self, name: &str, bytes: &[u8]) -> Result<String, ServeError> {
        let format = std::path::Path::new(name)
            .extension()
            .and_then(|e| e.to_str())
            .and_then(Format::from_extension)
            .ok_or_else(|| {
                ServeError::Refused(format!(
                    "{name}: unknown format (known: {})",
                    Format::known_extensions()
                ))
            })?;
        let file =
            holey_io::parse(format, bytes, name).map_err(|e| ServeError::Refused(e.to_string()))?;
        let faces = match &file {
            MeshFile::Dlfl(raw) => raw.face_count(),
            MeshFile::Poly(poly) => poly.face_count(),
        };
        if faces == 0 {
            return Err(ServeError::Refused(format!(
                "{name} has no faces: nothing to model"
            )));
        }
        let (content, note) = match file {
            MeshFile::Dlfl(mut raw) => {
                if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
                    infer_edges(&mut raw)
                        .map_err(|e| ServeError::Refused(format!("{name}: {e}")))?;
                }
                let mesh = Mesh::from_raw(&raw)
                    .map_err(|e| ServeError::Refused(format!("{name}: {e}")))?;
                (Content::Model(mesh), String::new())
            }
            MeshFile::Poly(poly) => {
                if poly.face_count() > self.config.max_faces {
                    return Err(ServeError::Refused(format!(
                        "{name} has {} faces; the modeler's limit is {}",
                        poly.face_count(),
                        self.config.max_faces
                    )));
                }
                match to_dlfl(&poly, ImportOptions::default()) {
                    Ok(imported) => (Content::Model(imported.mesh), String::new()),
                    // Any soup can be sculpted; the thesis's tools need a
                    // 2-manifold.
                    Err(e) => (
                        Content::Sculpt(poly_to_tri(&poly)?),
                        format!(" (not a 2-manifold, {e}: opened for sculpting)"),
                    ),
                }
            }
        };
        let mut doc = self.doc();
        if let Some((_, what)) = &doc.busy {
            return Err(ServeError::Refused(format!("busy: {what} is running")));
        }
        if doc.stroke.is_some() {
            return Err(ServeError::Refused("busy: a stroke is in progress".into()));
        }
        let content = match (&content, doc.content()) {
            (Content::Model(_), Content::Sculpt(_)) => content.into_sculpt()?,
            _ => content,
        };
        doc.rind = None;
        doc.commit_unmasked(content);
        self.publish(&doc);
        Ok(format!("imported {name}{note}"))
    }

    /// The document as a file: bytes and a file name. `format` is an
    /// extension without the dot: obj, ply, off, stl, glb, gltf, 3mf or
    /// dlfl (GLB, glTF and STL store `f32` positions; the rest are exact).
    pub fn export(&self, format: &str) -> Result<(Vec<u8>, String), ServeError> {
        let content = self.doc().content().clone();
        let mut bytes = Vec::new();
        let io = |e| ServeError::io("export", e);
        // The encoders say why a mesh does not fit their format (a
        // coordinate beyond f32 in glTF): the user's to hear.
        let refused = |m: String| ServeError::Refused(format!("cannot export as {format}: {m}"));
        match format {
            "obj" => holey_io::obj::write(&mut bytes, &content.to_poly()).map_err(io)?,
            "ply" => {
                holey_io::ply::write(&mut bytes, &content.to_poly(), false, None).map_err(io)?
            }
            "off" => holey_io::off::write(&mut bytes, &content.to_poly()).map_err(io)?,
            "stl" => holey_io::stl::write(&mut bytes, &content.to_poly(), false).map_err(io)?,
            "glb" => bytes = holey_io::gltf::encode_glb(&content.to_poly()).map_err(refused)?,
            "gltf" => bytes = holey_io::gltf::encode_gltf(&content.to_poly()).map_err(refused)?,
            "3mf" => bytes = holey_io::threemf::encode(&content.to_poly()).map_err(refused)?,
            "dlfl" => {
                let Content::Model(mesh) = content.into_model()? else {
                    return Err(ServeError::Refused("no DLFL to export".into()));
                };
                holey_io::dlfl::write(&mut bytes, &mesh.to_raw()).map_err(io)?;
            }
            other => {
                return Err(ServeError::BadRequest(format!(
                    "unknown export format {other:?} (obj, ply, off, stl, glb, gltf, 3mf, dlfl)"
                )));
            }
        }
        Ok((bytes, format!("holey.{format}")))
    }
}
