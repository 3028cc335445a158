//! Autosave and restore. After every change the document is written to
//! the state directory by a background thread (only the newest version
//! waits to be written, so a fast run of strokes costs one write), through
//! atomic writes: a crash leaves the previous save or the new one, never
//! half of one.
//!
//! Files: `session.json` (`{"workspace", "version", "mesh", "mask"}`)
//! names the mesh file, `session.dlfl` for the model workspace or
//! `session.ply` for the sculpt workspace, and lists the sculpt mask as
//! the numbers of the masked vertices in that file (the mask is kept by
//! exact position; the numbers give it back whatever the file's precision).
//! The mesh is written first, so the JSON never names a file that is not
//! complete.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex};

use holey_dlfl::Mesh;
use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_io::{MeshFile, WriteOptions};
use serde_json::{Value, json};

use crate::ServeError;
use crate::doc::{Content, Document, Mask, mask_flags, poly_to_tri};

/// A save waiting to be written: the version, the content and its mask.
type Job = (u64, Content, Arc<Mask>);
type Pending = Arc<(Mutex<Option<Job>>, Condvar)>;

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
                let (version, content, mask) = {
                    let (lock, ready) = &*shared;
                    let mut slot = lock.lock().unwrap_or_else(|p| p.into_inner());
                    loop {
                        if let Some(job) = slot.take() {
                            break job;
                        }
                        slot = ready.wait(slot).unwrap_or_else(|p| p.into_inner());
                    }
                };
                if let Err(e) = save(&dir, version, &content, &mask) {
                    eprintln!("holey serve: autosave failed: {e}");
                }
            }
        });
        Saver { pending }
    }

    /// Queues `content` and its mask for writing, replacing an older
    /// version that has not been written yet.
    pub fn save(&self, version: u64, content: Content, mask: Arc<Mask>) {
        let (lock, ready) = &*self.pending;
        *lock.lock().unwrap_or_else(|p| p.into_inner()) = Some((version, content, mask));
        ready.notify_one();
    }
}

/// Writes the session now.
pub fn save(dir: &Path, version: u64, content: &Content, mask: &Mask) -> Result<(), ServeError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| ServeError::io(format!("cannot create {}", dir.display()), e))?;
    let refused = |e: holey_io::IoError| ServeError::Refused(e.to_string());
    let mut masked = Vec::new();
    let file = match content {
        Content::Model(m) => {
            holey_io::write_dlfl(&dir.join("session.dlfl"), &m.to_raw()).map_err(refused)?;
            "session.dlfl"
        }
        Content::Sculpt(_) => {
            let poly = content.to_poly();
            if let Some(flags) = mask_flags(mask, &poly.positions) {
                masked.extend((0..flags.len()).filter(|&i| flags[i]));
            }
            holey_io::write_poly(&dir.join("session.ply"), &poly, &WriteOptions::default())
                .map_err(refused)?;
            "session.ply"
        }
    };
    let meta = json!({
        "workspace": content.workspace(),
        "version": version,
        "mesh": file,
        "mask": masked,
    });
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
        Ok((content, version, mask)) => Ok((
            Document::new(content, version + 1).with_mask(mask),
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

fn load(dir: &Path, meta_path: &Path) -> Result<(Content, u64, Mask), ServeError> {
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
    let mask = match &content {
        Content::Sculpt(t) => saved_mask(&meta, &t.positions)?,
        Content::Model(_) => Mask::new(),
    };
    Ok((content, version, mask))
}

/// The mask `session.json` lists (vertex numbers of the saved mesh) as
/// the exact positions of those vertices; none when it lists none (a save
/// from before masks were saved). A number past the mesh is an error.
fn saved_mask(meta: &Value, positions: &[glam::DVec3]) -> Result<Mask, ServeError> {
    let Some(list) = meta.get("mask") else {
        return Ok(Mask::new());
    };
    let bad = || ServeError::Refused("session.json: \"mask\" must list vertex numbers".into());
    list.as_array()
        .ok_or_else(bad)?
        .iter()
        .map(|i| {
            let i = i.as_u64().ok_or_else(bad)?;
            usize::try_from(i)
                .ok()
                .and_then(|i| positions.get(i))
                .map(|&p| holey_geom::position_key(p))
                .ok_or_else(|| {
                    ServeError::Refused(format!(
                        "session.json masks vertex {i}, and the mesh has {}",
                        positions.len()
                    ))
                })
        })
        .collect()
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
        save(dir.path(), 5, &torus, &Mask::new()).unwrap();
        let (back, note) = restore(dir.path()).unwrap();
        assert!(note.starts_with("restored"), "{note}");
        assert_eq!(back.state_json()["stats"]["genus"], 1);
        assert_eq!(back.version(), 6);
        let sculpt = torus.into_sculpt().unwrap();
        save(dir.path(), 9, &sculpt, &Mask::new()).unwrap();
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

    /// The sculpt mask comes back with the session, on the same vertices
    /// (by exact position), and a save without one restores unmasked.
    #[test]
    fn the_mask_is_saved_with_the_sculpt_session() {
        let dir = tempfile::tempdir().unwrap();
        let soup = holey_shapes::parse_primitive("@sphere:2").unwrap();
        let sphere = Content::Model(to_dlfl(&soup, ImportOptions::default()).unwrap().mesh)
            .into_sculpt()
            .unwrap();
        let Content::Sculpt(t) = &sphere else {
            panic!("not sculpt")
        };
        // The upper cap is masked.
        let mask: Mask = t
            .positions
            .iter()
            .filter(|p| p.z > 0.3)
            .map(|&p| holey_geom::position_key(p))
            .collect();
        assert!(!mask.is_empty() && mask.len() < t.positions.len());
        save(dir.path(), 3, &sphere, &mask).unwrap();
        let (back, _) = restore(dir.path()).unwrap();
        assert_eq!(**back.mask(), mask);
        let flags = back.mask_flags().unwrap();
        assert_eq!(flags.iter().filter(|&&b| b).count(), mask.len());
        // Undo does not reach before the restored session.
        assert!(!back.can_undo());
        // Keys of vertices no longer in the mesh are not saved.
        let mut stale = mask.clone();
        stale.insert(holey_geom::position_key(glam::DVec3::splat(7.0)));
        save(dir.path(), 4, &sphere, &stale).unwrap();
        let (back, _) = restore(dir.path()).unwrap();
        assert_eq!(**back.mask(), mask);
        // A save from before masks were saved restores unmasked; a number
        // past the mesh is refused (and the session left on disk).
        let meta = dir.path().join("session.json");
        let text = std::fs::read_to_string(&meta).unwrap();
        let mut v: Value = serde_json::from_str(&text).unwrap();
        v.as_object_mut().unwrap().remove("mask");
        std::fs::write(&meta, v.to_string()).unwrap();
        let (back, note) = restore(dir.path()).unwrap();
        assert!(note.starts_with("restored"), "{note}");
        assert!(back.mask().is_empty());
        v["mask"] = json!([0, 100_000_000]);
        std::fs::write(&meta, v.to_string()).unwrap();
        let (_, note) = restore(dir.path()).unwrap();
        assert!(note.contains("masks vertex 100000000"), "{note}");
    }
}
