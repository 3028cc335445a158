//! Autosave and restore. After every change the document is written to
//! the state directory by a background thread (only the newest version
//! waits to be written, so a fast run of strokes costs one write), through
//! atomic writes: a crash leaves the previous save or the new one, never
//! half of one.
//!
//! Files: `session.json` (`{"workspace", "version", "mesh"}`) names the
//! mesh file, `session.dlfl` for the model workspace or `session.ply` for
//! the sculpt workspace. The mesh is written first, so the JSON never
//! names a file that is not complete.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex};

use holey_dlfl::Mesh;
use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_io::{MeshFile, WriteOptions};
use serde_json::{Value, json};

use crate::ServeError;
use crate::doc::{Content, Document, poly_to_tri};

type Pending = Arc<(Mutex<Option<(u64, Content)>>, Condvar)>;

/// The background writer.
pub struct Saver {
    pending: Pending,
}

impl Saver {
    pub fn start(dir: PathBuf) -> Saver {
        let pending: Pending = Arc::new((Mutex::new(None), Condvar::new()));
        let shared = Arc::clone(&pending);
        std::thread::spawn(move || {
            loop {
                let (version, content) = {
                    let (lock, ready) = &*shared;
                    let mut slot = lock.lock().unwrap_or_else(|p| p.into_inner());
                    loop {
                        if let Some(job) = slot.take() {
                            break job;
                        }
                        slot = ready.wait(slot).unwrap_or_else(|p| p.into_inner());
                    }
                };
                if let Err(e) = save(&dir, version, &content) {
                    eprintln!("holey serve: autosave failed: {e}");
                }
            }
        });
        Saver { pending }
    }

    /// Queues `content` for writing, replacing an older version that has
    /// not been written yet.
    pub fn save(&self, version: u64, content: Content) {
        let (lock, ready) = &*self.pending;
        *lock.lock().unwrap_or_else(|p| p.into_inner()) = Some((version, content));
        ready.notify_one();
    }
}

/// Writes the session now.
pub fn save(dir: &Path, version: u64, content: &Content) -> Result<(), ServeError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| ServeError::io(format!("cannot create {}", dir.display()), e))?;
    let refused = |e: holey_io::IoError| ServeError::Refused(e.to_string());
    let file = match content {
        Content::Model(m) => {
            holey_io::write_dlfl(&dir.join("session.dlfl"), &m.to_raw()).map_err(refused)?;
            "session.dlfl"
        }
        Content::Sculpt(_) => {
            holey_io::write_poly(
                &dir.join("session.ply"),
                &content.to_poly(),
                &WriteOptions::default(),
            )
            .map_err(refused)?;
            "session.ply"
        }
    };
    let meta = json!({"workspace": content.workspace(), "version": version, "mesh": file});
    holey_io::write_bytes_atomic(&dir.join("session.json"), meta.to_string().as_bytes())
        .map_err(refused)
}

/// The document saved in `dir`, or a new one (a cube) when there is none.
/// A save that cannot be read is left on disk untouched and reported.
pub fn restore(dir: &Path) -> Result<(Document, String), ServeError> {
    let meta_path = dir.join("session.json");
    if !meta_path.exists() {
        return Ok((Document::new(fresh()?, 1), "new session".into()));
    }
    match load(dir, &meta_path) {
        Ok((content, version)) => Ok((
            Document::new(content, version + 1),
            format!("restored the session saved in {}", dir.display()),
        )),
        Err(e) => Ok((
            Document::new(fresh()?, 1),
            format!(
                "could not restore the session in {} ({e}); it is left as it was, and a new one started",
                dir.display()
            ),
        )),
    }
}

fn load(dir: &Path, meta_path: &Path) -> Result<(Content, u64), ServeError> {
    let text = std::fs::read_to_string(meta_path)
        .map_err(|e| ServeError::io(meta_path.display().to_string(), e))?;
    let meta: Value = serde_json::from_str(&text)
        .map_err(|e| ServeError::Refused(format!("{}: {e}", meta_path.display())))?;
    let version = meta.get("version").and_then(Value::as_u64).unwrap_or(0);
    let file = match meta.get("mesh").and_then(Value::as_str) {
        Some(f @ ("session.dlfl" | "session.ply")) => f,
        _ => return Err(ServeError::Refused("session.json names no mesh".into())),
    };
    let read =
        holey_io::read_path(&dir.join(file)).map_err(|e| ServeError::Refused(e.to_string()))?;
    let content = match (read, meta.get("workspace").and_then(Value::as_str)) {
        (MeshFile::Dlfl(raw), _) => {
            Content::Model(Mesh::from_raw(&raw).map_err(|e| ServeError::Refused(e.to_string()))?)
        }
        (MeshFile::Poly(poly), Some("sculpt")) => Content::Sculpt(poly_to_tri(&poly)?),
        (MeshFile::Poly(_), _) => {
            return Err(ServeError::Refused(
                "session.json and the mesh disagree".into(),
            ));
        }
    };
    Ok((content, version))
}

fn fresh() -> Result<Content, ServeError> {
    let soup =
        holey_shapes::parse_primitive("@cube").map_err(|e| ServeError::Refused(e.to_string()))?;
    let mesh = to_dlfl(&soup, ImportOptions::default())
        .map_err(|e| ServeError::Refused(e.to_string()))?
        .mesh;
    Ok(Content::Model(mesh))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn save_and_restore_both_workspaces() {
        let dir = tempfile::tempdir().unwrap();
        let (doc, note) = restore(dir.path()).unwrap();
        assert_eq!(note, "new session");
        let torus = {
            let soup = holey_shapes::parse_primitive("@torus").unwrap();
            Content::Model(to_dlfl(&soup, ImportOptions::default()).unwrap().mesh)
        };
        save(dir.path(), 5, &torus).unwrap();
        let (back, note) = restore(dir.path()).unwrap();
        assert!(note.starts_with("restored"), "{note}");
        assert_eq!(back.state_json()["stats"]["genus"], 1);
        assert_eq!(back.version(), 6);
        let sculpt = torus.into_sculpt().unwrap();
        save(dir.path(), 9, &sculpt).unwrap();
        let (back, _) = restore(dir.path()).unwrap();
        assert_eq!(back.state_json()["workspace"], "sculpt");
        assert_eq!(back.state_json()["stats"]["genus"], 1);
        drop(doc);
        // A broken save is reported and left alone.
        std::fs::write(dir.path().join("session.ply"), b"garbage").unwrap();
        let (fresh, note) = restore(dir.path()).unwrap();
        assert!(note.contains("could not restore"), "{note}");
        assert_eq!(fresh.state_json()["stats"]["genus"], 0);
        assert_eq!(
            std::fs::read(dir.path().join("session.ply")).unwrap(),
            b"garbage"
        );
    }
}
