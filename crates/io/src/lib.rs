//! # holey-io: mesh files
//!
//! Readers and writers for OBJ ([`obj`]), OFF ([`off`]), PLY ([`ply`],
//! ascii and binary), STL ([`stl`], ascii and binary), glTF 2.0
//! ([`gltf`], `.gltf` and `.glb`), 3MF ([`threemf`]) and holey's native
//! `.dlfl` ([`dlfl`]). Each module documents exactly what it accepts.
//!
//! - The polygon formats read into a [`PolyMesh`] holding the file's
//!   vertices and faces as stored (STL: welded only where positions are
//!   bit-identical; glTF and 3MF: the meshes of the scene or build, each
//!   placed by its transforms); `.dlfl` reads into a [`RawMesh`] for
//!   [`holey_dlfl::Mesh::from_raw`].
//! - Readers never panic on any input and never allocate by a declared
//!   count beyond what the file's size can hold. Every error says what is
//!   wrong and where: `file:line:` for text, `file: byte N:` for binary
//!   data.
//! - Writers write atomically: to a temporary file beside the destination,
//!   flushed and synced, then renamed over it. On any error the
//!   destination is left as it was.
//!
//! ```no_run
//! use std::path::Path;
//! use holey_io::{MeshFile, WriteOptions};
//!
//! let MeshFile::Poly(mesh) = holey_io::read_path(Path::new("bunny.obj"))? else {
//!     unreachable!("OBJ files read as polygon meshes")
//! };
//! holey_io::write_poly(Path::new("bunny.ply"), &mesh, &WriteOptions::default())?;
//! # Ok::<(), holey_io::IoError>(())
//! ```

#![warn(missing_docs)]

pub mod dlfl;
mod error;
pub mod gltf;
pub mod obj;
pub mod off;
pub mod ply;
pub mod stl;
mod text;
pub mod threemf;

use std::fmt;
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use holey_mesh::NonFinite;

pub use error::IoError;
pub use holey_dlfl::RawMesh;
pub use holey_mesh::PolyMesh;

/// Writers hand their output to the destination in pieces of about this
/// many bytes.
pub(crate) const CHUNK: usize = 1 << 16;

/// The most vertices plus face corners a glTF or 3MF reader builds. Both
/// formats place one stored mesh any number of times (glTF nodes, 3MF
/// build items and components), so a file of a few kilobytes could ask
/// for more copies than memory holds; past this the reader stops with an
/// error instead. It is far above any mesh holey can work on.
pub(crate) const MAX_ELEMENTS: usize = 1 << 28;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (`.obj`), text: positions and polygon faces.
    Obj,
    /// Object File Format (`.off`), text form only.
    Off,
    /// Stanford PLY (`.ply`), ascii or binary of either byte order.
    Ply,
    /// STL (`.stl`), ascii or binary: separate facets, welded on reading
    /// only where positions are bit-identical.
    Stl,
    /// glTF 2.0 as JSON (`.gltf`); holey writes its buffer as a base64 data
    /// URI so the one file is self-contained. Positions are `f32`.
    Gltf,
    /// glTF 2.0 in its binary container (`.glb`). Positions are `f32`.
    Glb,
    /// 3MF (`.3mf`): a ZIP package of XML; decimal coordinates, exact.
    ThreeMf,
    /// holey's native DLFL text format (`.dlfl`): faces, hole faces and edges.
    Dlfl,
}

impl Format {
    /// Every format, in a fixed order.
    pub const ALL: [Format; 8] = [
        Format::Obj,
        Format::Off,
        Format::Ply,
        Format::Stl,
        Format::Gltf,
        Format::Glb,
        Format::ThreeMf,
        Format::Dlfl,
    ];

    /// The known extensions for messages: `.obj, .off, …, .dlfl`.
    pub fn known_extensions() -> String {
        Format::ALL
            .iter()
            .map(|f| format!(".{}", f.extension()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The format named by a path's extension (`.obj`, `.off`, `.ply`,
    /// `.stl`, `.gltf`, `.glb`, `.3mf`, `.dlfl`, in any case).
    pub fn from_path(path: &Path) -> Result<Format, IoError> {
        let ext = path.extension().and_then(|e| e.to_str());
        ext.and_then(Format::from_extension)
            .ok_or_else(|| IoError::UnknownFormat {
                file: path.display().to_string(),
                message: match path.extension() {
                    Some(e) => format!(
                        "unknown mesh file extension \".{}\" (known: {})",
                        e.to_string_lossy(),
                        Format::known_extensions()
                    ),
                    None => format!(
                        "no file extension to tell the mesh format (known: {})",
                        Format::known_extensions()
                    ),
                },
            })
    }

    /// The format with this extension (without the dot, any case).
    pub fn from_extension(ext: &str) -> Option<Format> {
        Format::ALL
            .into_iter()
            .find(|f| f.extension().eq_ignore_ascii_case(ext))
    }

    /// The format's name for messages: `OBJ`, `OFF`, `PLY`, `STL`, `glTF`,
    /// `GLB`, `3MF`, `DLFL`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::Off => "OFF",
            Format::Ply => "PLY",
            Format::Stl => "STL",
            Format::Gltf => "glTF",
            Format::Glb => "GLB",
            Format::ThreeMf => "3MF",
            Format::Dlfl => "DLFL",
        }
    }

    /// The usual file extension, lower case without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Off => "off",
            Format::Ply => "ply",
            Format::Stl => "stl",
            Format::Gltf => "gltf",
            Format::Glb => "glb",
            Format::ThreeMf => "3mf",
            Format::Dlfl => "dlfl",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What a file holds: a polygon mesh (OBJ, OFF, PLY, STL, glTF, 3MF) or a
/// DLFL in raw form (`.dlfl`).
#[derive(Clone, Debug, PartialEq)]
pub enum MeshFile {
    /// The vertices and faces of an OBJ, OFF, PLY, STL, glTF or 3MF file,
    /// as stored (glTF and 3MF: placed by their transforms).
    Poly(PolyMesh),
    /// The contents of a `.dlfl` file, ready for [`holey_dlfl::Mesh::from_raw`].
    Dlfl(RawMesh),
}

/// Reads a mesh file, choosing the format by the extension. Errors name the
/// path as given. A `.gltf` may keep its buffers in files beside it; they
/// are read relative to its directory.
pub fn read_path(path: &Path) -> Result<MeshFile, IoError> {
    let format = Format::from_path(path)?;
    let name = path.display().to_string();
    let bytes = fs::read(path).map_err(|e| IoError::io(&name, "cannot read the file", e))?;
    if let Format::Gltf | Format::Glb = format {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let glb = format == Format::Glb;
        return Ok(MeshFile::Poly(gltf::parse_with_files(
            &bytes, &name, dir, glb,
        )?));
    }
    parse(format, &bytes, &name)
}

/// Parses the bytes of a file in `format`; `source` is the file name used in
/// error messages. Nothing but `bytes` is read: a glTF whose buffers are in
/// separate files is refused (use [`read_path`]).
pub fn parse(format: Format, bytes: &[u8], source: &str) -> Result<MeshFile, IoError> {
    Ok(match format {
        Format::Obj => MeshFile::Poly(obj::parse(bytes, source)?),
        Format::Off => MeshFile::Poly(off::parse(bytes, source)?),
        Format::Ply => MeshFile::Poly(ply::parse(bytes, source)?),
        Format::Stl => MeshFile::Poly(stl::parse(bytes, source)?),
        Format::Gltf => MeshFile::Poly(gltf::parse(bytes, source)?),
        Format::Glb => MeshFile::Poly(gltf::parse_glb(bytes, source)?),
        Format::ThreeMf => MeshFile::Poly(threemf::parse(bytes, source)?),
        Format::Dlfl => MeshFile::Dlfl(dlfl::parse(bytes, source)?),
    })
}

/// How [`write_poly`] writes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WriteOptions {
    /// PLY and STL: write ascii instead of binary.
    pub ascii: bool,
    /// PLY only: one RGB colour per vertex (ignored by other formats).
    pub vertex_colors: Option<Vec<[u8; 3]>>,
}

/// Checks that a polygon mesh can be written: offsets well formed, no face
/// without corners, indices in range, positions finite. A mesh with empty
/// `face_offsets` (as from `PolyMesh::default()`) has no faces.
pub fn check_poly(mesh: &PolyMesh) -> Result<(), String> {
    if mesh.face_offsets.is_empty() {
        if !mesh.face_indices.is_empty() {
            return Err("face offsets are missing".into());
        }
        if mesh.positions.len() >= u32::MAX as usize {
            return Err(format!(
                "{} vertices exceed 32-bit indices",
                mesh.positions.len()
            ));
        }
        return NonFinite::check("vertex", &mesh.positions).map_err(|e| e.to_string());
    }
    mesh.check().map_err(|e| e.to_string())?;
    if let Some(f) = mesh.face_offsets.windows(2).position(|w| w[1] == w[0]) {
        return Err(format!("face {f} has no corners"));
    }
    Ok(())
}

/// Writes a polygon mesh as OBJ, OFF, PLY, STL, glTF (`.gltf`, `.glb`) or
/// 3MF, chosen by the extension, atomically (see the crate docs). `.dlfl`
/// is refused: it stores a DLFL, so convert the mesh and use
/// [`write_dlfl`]. glTF and 3MF are encoded in memory first, so a mesh they
/// cannot hold (a coordinate beyond `f32` for glTF) is refused before
/// anything is written.
pub fn write_poly(path: &Path, mesh: &PolyMesh, opts: &WriteOptions) -> Result<(), IoError> {
    let format = Format::from_path(path)?;
    let name = path.display().to_string();
    check_poly(mesh).map_err(|m| IoError::invalid_mesh(&name, m))?;
    let colors = opts.vertex_colors.as_deref();
    if format == Format::Ply
        && let Some(c) = colors
        && c.len() != mesh.positions.len()
    {
        return Err(IoError::invalid_mesh(
            &name,
            format!(
                "{} vertex colours for {} vertices",
                c.len(),
                mesh.positions.len()
            ),
        ));
    }
    match format {
        Format::Obj => write_atomic(path, |w| obj::write(w, mesh)),
        Format::Off => write_atomic(path, |w| off::write(w, mesh)),
        Format::Ply => write_atomic(path, |w| ply::write(w, mesh, opts.ascii, colors)),
        Format::Stl => write_atomic(path, |w| stl::write(w, mesh, opts.ascii)),
        Format::Gltf | Format::Glb | Format::ThreeMf => {
            let bytes = match format {
                Format::Gltf => gltf::encode_gltf(mesh),
                Format::Glb => gltf::encode_glb(mesh),
                _ => threemf::encode(mesh),
            }
            .map_err(|m| IoError::invalid_mesh(&name, m))?;
            write_atomic(path, |w| w.write_all(&bytes))
        }
        Format::Dlfl => Err(IoError::invalid_mesh(
            &name,
            "a .dlfl file stores a DLFL mesh, not a polygon soup; convert the mesh first and write it with write_dlfl",
        )),
    }
}

/// Writes a raw DLFL as `.dlfl`, atomically. The path must end in `.dlfl`.
pub fn write_dlfl(path: &Path, raw: &RawMesh) -> Result<(), IoError> {
    let name = path.display().to_string();
    if Format::from_path(path)? != Format::Dlfl {
        return Err(IoError::invalid_mesh(
            &name,
            "write_dlfl writes .dlfl files; give the path a .dlfl extension",
        ));
    }
    dlfl::check_raw(raw).map_err(|m| IoError::invalid_mesh(&name, m))?;
    write_atomic(path, |w| dlfl::write(w, raw))
}

/// Writes `bytes` to `path` atomically (for pictures, reports and other
/// non-mesh outputs): nothing is left at `path` unless the whole write
/// succeeded, and an existing file there is replaced only then.
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    write_atomic(path, |w| w.write_all(bytes))
}

/// A mesh a writer's format cannot hold (malformed, or past the format's
/// limits), as the error every writer returns for it.
pub(crate) fn invalid_input(why: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, why)
}

/// Hands `buf` to `w` and empties it once it holds a chunk ([`CHUNK`]) or
/// more: the writers build their output in one buffer and call this after
/// every record.
pub(crate) fn flush_full<W: Write>(w: &mut W, buf: &mut Vec<u8>) -> io::Result<()> {
    if buf.len() >= CHUNK {
        w.write_all(buf)?;
        buf.clear();
    }
    Ok(())
}

/// Writes the bytes a binary encoder (glTF, GLB, 3MF) made of a mesh; its
/// refusal is an [`io::ErrorKind::InvalidInput`] error.
pub(crate) fn write_encoded<W: Write>(
    mut w: W,
    encoded: Result<Vec<u8>, String>,
) -> io::Result<()> {
    w.write_all(&encoded.map_err(invalid_input)?)
}

/// A mesh's faces as lists of vertex indices, for tests to compare.
#[cfg(test)]
pub(crate) fn face_lists(m: &PolyMesh) -> Vec<Vec<u32>> {
    m.faces().map(<[u32]>::to_vec).collect()
}

/// Asserts that two position lists are equal to the bit (so `-0.0` and
/// `0.0` differ): what the round-trip tests of every format demand, since
/// the writers print each coordinate as the shortest text that reads back
/// to the same `f64`.
#[cfg(test)]
pub(crate) fn assert_positions_bit_exact(a: &[holey_mesh::DVec3], b: &[holey_mesh::DVec3]) {
    assert_eq!(a.len(), b.len(), "position counts differ");
    for (p, q) in a.iter().zip(b) {
        assert_eq!(
            p.to_array().map(f64::to_bits),
            q.to_array().map(f64::to_bits)
        );
    }
}

/// Asserts that two polygon meshes are the same: the same faces in the
/// same order and bit-identical positions.
#[cfg(test)]
pub(crate) fn assert_same_poly(a: &PolyMesh, b: &PolyMesh) {
    assert_eq!(a.face_offsets, b.face_offsets);
    assert_eq!(a.face_indices, b.face_indices);
    assert_positions_bit_exact(&a.positions, &b.positions);
}

/// Runs `body` on a temporary file in the destination's directory, then
/// flushes, syncs and renames it over `path`. On any failure the temporary
/// file is removed and `path` is untouched.
pub(crate) fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut BufWriter<&mut fs::File>) -> io::Result<()>,
) -> Result<(), IoError> {
    let name = path.display().to_string();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".holey-").suffix(".tmp");
    #[cfg(unix)]
    {
        // The default 0600 of temporary files would stick to the result;
        // ask for 0666 so the umask decides, as for any new file.
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder
        .tempfile_in(dir)
        .map_err(|e| IoError::io(&name, "cannot create a temporary file beside it", e))?;
    {
        let mut w = BufWriter::with_capacity(CHUNK, tmp.as_file_mut());
        body(&mut w).map_err(|e| IoError::io(&name, "cannot write", e))?;
        w.flush()
            .map_err(|e| IoError::io(&name, "cannot write", e))?;
    }
    if let Ok(meta) = fs::metadata(path) {
        // Replacing a file keeps its permissions; failing to copy them is
        // not worth failing the write.
        let _ = tmp.as_file().set_permissions(meta.permissions());
    }
    tmp.as_file()
        .sync_all()
        .map_err(|e| IoError::io(&name, "cannot sync to disk", e))?;
    tmp.persist(path)
        .map_err(|e| IoError::io(&name, "cannot move the written file into place", e.error))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use holey_mesh::DVec3;

    use super::*;

    fn tetra() -> PolyMesh {
        PolyMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            [[0u32, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
    }

    #[test]
    fn formats_by_extension() {
        assert_eq!(
            Format::from_path(Path::new("a/b.OBJ")).unwrap(),
            Format::Obj
        );
        assert_eq!(Format::from_path(Path::new("x.Ply")).unwrap(), Format::Ply);
        assert_eq!(
            Format::from_path(Path::new("x.dlfl")).unwrap(),
            Format::Dlfl
        );
        let e = Format::from_path(Path::new("dir/mesh.3ds")).unwrap_err();
        assert!(e.is_bad_input());
        assert_eq!(
            e.to_string(),
            "dir/mesh.3ds: unknown mesh file extension \".3ds\" (known: .obj, .off, .ply, .stl, .gltf, .glb, .3mf, .dlfl)"
        );
        assert_eq!(Format::from_path(Path::new("a.GLB")).unwrap(), Format::Glb);
        assert_eq!(
            Format::from_path(Path::new("a.gltf")).unwrap(),
            Format::Gltf
        );
        assert_eq!(
            Format::from_path(Path::new("a.3MF")).unwrap(),
            Format::ThreeMf
        );
        let e = Format::from_path(Path::new("README")).unwrap_err();
        assert!(e.to_string().starts_with("README: no file extension"));
        for f in Format::ALL {
            assert_eq!(Format::from_extension(f.extension()), Some(f));
            assert_eq!(f.to_string(), f.name());
        }
        let e = read_path(Path::new("nowhere/x.foo")).unwrap_err();
        assert!(e.is_bad_input());
    }

    #[test]
    fn every_format_round_trips_through_files() {
        let dir = tempfile::tempdir().unwrap();
        let m = tetra();
        // The tetrahedron is triangles at coordinates f32 holds exactly, so
        // glTF and 3MF give it back unchanged too.
        for ext in ["obj", "off", "ply", "stl", "gltf", "glb", "3mf"] {
            for ascii in [false, true] {
                let path = dir.path().join(format!("t.{ext}"));
                write_poly(
                    &path,
                    &m,
                    &WriteOptions {
                        ascii,
                        ..Default::default()
                    },
                )
                .unwrap();
                let MeshFile::Poly(back) = read_path(&path).unwrap() else {
                    panic!("{ext}: not a polygon mesh");
                };
                // STL numbers vertices by first appearance; compare faces by
                // their corner positions.
                let corners = |p: &PolyMesh| -> Vec<Vec<DVec3>> {
                    p.faces()
                        .map(|f| f.iter().map(|&i| p.positions[i as usize]).collect())
                        .collect()
                };
                assert_eq!(corners(&back), corners(&m), "{ext}");
                if ext != "stl" {
                    assert_eq!(back, m, "{ext}");
                }
            }
        }
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names.len(), 7, "no temporary files left behind: {names:?}");
    }

    #[test]
    fn write_poly_refuses_what_it_cannot_write() {
        let dir = tempfile::tempdir().unwrap();
        let m = tetra();
        let e = write_poly(&dir.path().join("t.dlfl"), &m, &WriteOptions::default()).unwrap_err();
        assert!(e.is_bad_input());
        let e = write_poly(&dir.path().join("t.xyz"), &m, &WriteOptions::default()).unwrap_err();
        assert!(e.is_bad_input());
        let mut bad = m.clone();
        bad.face_indices[2] = 9;
        let e = write_poly(&dir.path().join("t.obj"), &bad, &WriteOptions::default()).unwrap_err();
        assert!(e.is_bad_input());
        assert!(e.to_string().contains("refers to vertex 9"), "{e}");
        let opts = WriteOptions {
            vertex_colors: Some(vec![[0, 0, 0]; 3]),
            ..Default::default()
        };
        let e = write_poly(&dir.path().join("t.ply"), &m, &opts).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}: cannot write this mesh: 3 vertex colours for 4 vertices",
                dir.path().join("t.ply").display()
            )
        );
        let e = write_dlfl(&dir.path().join("t.obj"), &RawMesh::default()).unwrap_err();
        assert!(e.is_bad_input());
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            0,
            "nothing was written"
        );
        let mut empty = PolyMesh::default();
        assert!(check_poly(&empty).is_ok());
        empty.face_indices.push(0);
        assert!(check_poly(&empty).is_err());
        let mut with_empty_face = tetra();
        with_empty_face.push_face(&[]);
        assert_eq!(
            check_poly(&with_empty_face).unwrap_err(),
            "face 4 has no corners"
        );
    }

    #[test]
    fn writing_into_a_missing_directory_fails_and_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing/sub/t.obj");
        let e = write_poly(&path, &tetra(), &WriteOptions::default()).unwrap_err();
        assert!(!e.is_bad_input(), "a system failure: {e}");
        assert!(e.to_string().contains("missing/sub/t.obj"), "{e}");
        assert!(!dir.path().join("missing").exists());
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_failed_write_leaves_the_destination_unchanged() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.obj");
        fs::write(&path, b"precious").unwrap();
        let e = write_atomic(&path, |w| {
            w.write_all(&[b'x'; 3 * CHUNK])?;
            Err(io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert!(!e.is_bad_input());
        assert!(e.to_string().ends_with("cannot write: disk on fire"), "{e}");
        assert_eq!(fs::read(&path).unwrap(), b"precious");
        // An invalid mesh is refused before anything is written.
        let mut bad = tetra();
        bad.positions[0].x = f64::NAN;
        write_poly(&path, &bad, &WriteOptions::default()).unwrap_err();
        assert_eq!(fs::read(&path).unwrap(), b"precious");
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary file left"
        );
        // A successful write replaces it.
        write_poly(&path, &tetra(), &WriteOptions::default()).unwrap();
        assert!(fs::read(&path).unwrap().starts_with(b"# written by holey"));
    }

    #[cfg(unix)]
    #[test]
    fn written_files_get_ordinary_permissions_and_replacements_keep_theirs() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let plain = dir.path().join("plain");
        fs::write(&plain, b"").unwrap();
        let ordinary = fs::metadata(&plain).unwrap().permissions().mode() & 0o777;
        let path = dir.path().join("t.off");
        write_poly(&path, &tetra(), &WriteOptions::default()).unwrap();
        let mode = fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(
            mode, ordinary,
            "as for any new file under the umask: {mode:o}"
        );
        fs::set_permissions(&path, fs::Permissions::from_mode(0o640)).unwrap();
        write_poly(&path, &tetra(), &WriteOptions::default()).unwrap();
        assert_eq!(
            fs::metadata(&path).unwrap().permissions().mode() & 0o777,
            0o640
        );
    }

    #[test]
    fn reading_a_missing_file_is_a_system_error_naming_it() {
        let e = read_path(Path::new("/nonexistent/dir/x.obj")).unwrap_err();
        assert!(!e.is_bad_input());
        assert!(
            e.to_string()
                .starts_with("/nonexistent/dir/x.obj: cannot read the file: "),
            "{e}"
        );
    }
}
