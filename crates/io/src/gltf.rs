//! glTF 2.0: `.gltf` (JSON) and `.glb` (the binary container).
//!
//! glTF is how meshes travel between today's 3D tools and the web, so
//! holey reads what those tools write and writes what they read. The JSON
//! schema is gltf-json's; the GLB container, buffers and accessors are
//! read here, with every offset and count checked against the bytes that
//! are really there, so a malformed file is an error naming the file and
//! the part at fault, never a panic.
//!
//! Read: the meshes of the default scene (`scene`, else the first scene;
//! a file without scenes gives every mesh once, untransformed). Every node
//! reached from the scene's root nodes that has a mesh contributes each of
//! its primitives, with the node's world transform (its `matrix`, or its
//! translation, rotation and scale, after its parents') applied in `f64`,
//! and with its triangles turned over where that transform mirrors (a
//! negative determinant, as the glTF spec asks). All of them make one
//! polygon mesh: vertices in the order met, each primitive's own vertices
//! kept as stored (nothing is welded; `holey info --weld` and
//! `holey convert --weld 0` merge equal positions). Primitives of mode
//! `TRIANGLES` are read, and `TRIANGLE_STRIP` and `TRIANGLE_FAN` as the
//! triangles they stand for; points and lines have no faces and are left
//! out. Positions must be `f32` `VEC3` accessors; indices may be unsigned
//! bytes, shorts or ints (or absent: vertices taken in order). Skins,
//! morph targets, normals, colours, materials and textures are ignored.
//!
//! Buffers: a GLB's first buffer may be its BIN chunk; any buffer may be a
//! base64 `data:` URI; other URIs name files relative to the `.gltf`,
//! which only [`parse_with_files`] (and so [`crate::read_path`]) reads:
//! [`parse`] is given bytes alone (an upload, say) and refuses such a
//! buffer instead of opening files on its behalf. Not supported, each with
//! an error saying so: sparse accessors, accessors without a buffer view,
//! Draco (`KHR_draco_mesh_compression`), meshopt compression, quantized
//! positions (`KHR_mesh_quantization`), GPU instancing, any other required
//! extension that could change geometry, URLs, and glTF 1.0.
//!
//! Write: one mesh in one node of one scene; positions as `f32` (glTF has
//! no `f64` positions, so precision beyond `f32` is lost, and a coordinate
//! beyond `f32`'s range is refused), faces fan-triangulated from their
//! first corner as `u32` indices (faces of fewer than three corners are
//! left out), all vertices kept so vertex numbers survive a round trip.
//! [`PolyMesh`] has no normals, so none are written. A mesh without
//! triangles but with vertices is written as a `POINTS` primitive (which
//! holey reads back as an empty mesh); an empty mesh as a scene whose one
//! node has no mesh.
//! `.glb` holds the data in its BIN chunk; `.gltf` holds it as a base64
//! data URI, so the one file is self-contained.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::{self, Write};
use std::path::Path;

use base64::Engine as _;
use glam::{DMat3, DMat4, DQuat, DVec3};
use gltf_json::accessor::{ComponentType, GenericComponentType, Type};
use gltf_json::mesh::{Mode, Semantic};
use gltf_json::validation::{Checked, USize64};
use gltf_json::{Index, Root};
use holey_mesh::PolyMesh;

use crate::IoError;
use crate::error::show;

/// The first four bytes of every GLB file.
const GLB_MAGIC: &[u8; 4] = b"glTF";
/// The chunk type of a GLB's JSON chunk (`JSON` in ASCII, little-endian).
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// The chunk type of a GLB's binary chunk (`BIN\0`).
const CHUNK_BIN: u32 = 0x004E_4942;

/// Parses a `.gltf` file's bytes: glTF JSON, or a GLB (recognised by its
/// magic). Buffers must be embedded (data URIs or the GLB's BIN chunk): a
/// buffer in a separate file is refused, since there is no directory to
/// find it in. `source` names the file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    read(bytes, source, None, false)
}

/// Parses a `.glb` file's bytes, which must start with the GLB magic;
/// otherwise as [`parse`].
pub fn parse_glb(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    read(bytes, source, None, true)
}

/// As [`parse`] (or [`parse_glb`] when `glb`), and buffers that name files
/// are read from `dir`, the directory of the glTF file.
pub fn parse_with_files(
    bytes: &[u8],
    source: &str,
    dir: &Path,
    glb: bool,
) -> Result<PolyMesh, IoError> {
    read(bytes, source, Some(dir), glb)
}

fn read(bytes: &[u8], source: &str, dir: Option<&Path>, glb: bool) -> Result<PolyMesh, IoError> {
    let is_glb = bytes.starts_with(GLB_MAGIC);
    if glb && !is_glb {
        return Err(IoError::byte(
            source,
            0,
            format!(
                "not a GLB file: it starts with \"{}\", not the magic \"glTF\"",
                show(&bytes[..bytes.len().min(4)])
            ),
        ));
    }
    let (json, bin) = if is_glb {
        split_glb(bytes, source)?
    } else {
        (bytes, None)
    };
    let root = parse_json(json, source, is_glb)?;
    check_required_extensions(&root, source)?;
    let mut reader = Reader {
        root: &root,
        source,
        buffers: Buffers {
            bin,
            dir,
            loaded: vec![None; root.buffers.len()],
        },
        mesh: PolyMesh::new(),
    };
    for (mesh, world) in instances(&root, source)? {
        reader.instance(mesh, &world)?;
    }
    Ok(reader.mesh)
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at + 4)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a GLB into its JSON chunk and its BIN chunk (if any), checking
/// the header and every chunk's length against the file.
fn split_glb<'a>(bytes: &'a [u8], source: &str) -> Result<(&'a [u8], Option<&'a [u8]>), IoError> {
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(IoError::byte(
            source,
            bytes.len(),
            format!(
                "file ends inside the 12-byte GLB header ({} bytes)",
                bytes.len()
            ),
        ));
    };
    if version != 2 {
        return Err(IoError::byte(
            source,
            4,
            format!("GLB version {version} is not supported (holey reads glTF 2.0)"),
        ));
    }
    let length = length as usize;
    if length > bytes.len() {
        return Err(IoError::byte(
            source,
            bytes.len(),
            format!(
                "file is truncated: the GLB header declares {length} bytes, the file has {}",
                bytes.len()
            ),
        ));
    }
    if length < bytes.len() {
        return Err(IoError::byte(
            source,
            length,
            format!(
                "{} bytes follow the {length} bytes the GLB header declares",
                bytes.len() - length
            ),
        ));
    }
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    let mut index = 0;
    while at < length {
        let (Some(chunk_len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(IoError::byte(
                source,
                at,
                format!("file ends inside the header of chunk {index}"),
            ));
        };
        let start = at + 8;
        let end = start
            .checked_add(chunk_len as usize)
            .filter(|&e| e <= length)
            .ok_or_else(|| {
                IoError::byte(
                    source,
                    at,
                    format!(
                        "chunk {index} declares {chunk_len} bytes, but only {} follow",
                        length - start
                    ),
                )
            })?;
        let data = &bytes[start..end];
        match (index, kind) {
            (0, CHUNK_JSON) => json = Some(data),
            (0, _) => {
                return Err(IoError::byte(
                    source,
                    at + 4,
                    format!(
                        "the first chunk must be JSON, but its type is 0x{kind:08x} (\"{}\")",
                        show(&kind.to_le_bytes())
                    ),
                ));
            }
            (1, CHUNK_BIN) => bin = Some(data),
            // Chunks of unknown types are skipped, as the spec asks.
            _ => {}
        }
        index += 1;
        at = end;
    }
    let json = json.ok_or_else(|| IoError::byte(source, 12, "the GLB has no JSON chunk"))?;
    Ok((json, bin))
}

fn parse_json(json: &[u8], source: &str, glb: bool) -> Result<Root, IoError> {
    let what = if glb {
        "the JSON chunk is not valid glTF"
    } else {
        "not valid glTF JSON"
    };
    Root::from_slice(json).map_err(|e| {
        // glTF 1.0 has another schema: say so rather than which field of
        // 2.0 it lacks.
        let version = gltf_json::deserialize::from_slice::<gltf_json::Value>(json)
            .ok()
            .and_then(|v| v.get("asset")?.get("version")?.as_str().map(str::to_owned));
        match version {
            Some(v) if !v.starts_with("2.") => IoError::content(
                source,
                format!("glTF version {v} is not supported (holey reads glTF 2.0)"),
            ),
            _ => IoError::content(source, format!("{what}: {e}")),
        }
    })
}

/// True for required extensions that only affect appearance (materials,
/// textures, lights), which a reader of geometry may ignore.
fn harmless_extension(name: &str) -> bool {
    [
        "KHR_materials_",
        "KHR_texture_",
        "EXT_texture_",
        "KHR_lights_",
        "EXT_lights_",
    ]
    .iter()
    .any(|p| name.starts_with(p))
}

fn check_required_extensions(root: &Root, source: &str) -> Result<(), IoError> {
    match root
        .extensions_required
        .iter()
        .find(|e| !harmless_extension(e))
    {
        Some(e) => Err(IoError::content(
            source,
            format!(
                "the file requires the glTF extension {e}, which holey does not read{}",
                match e.as_str() {
                    "KHR_draco_mesh_compression" => " (Draco-compressed meshes)",
                    "EXT_meshopt_compression" | "KHR_meshopt_compression" =>
                        " (meshopt-compressed buffers)",
                    "KHR_mesh_quantization" => " (quantized positions; holey reads f32 positions)",
                    "EXT_mesh_gpu_instancing" => " (instanced meshes)",
                    _ => "",
                }
            ),
        )),
        None => Ok(()),
    }
}

/// The local transform of a node: its matrix, or translation · rotation ·
/// scale.
fn local_transform(node: &gltf_json::Node, n: usize, source: &str) -> Result<DMat4, IoError> {
    if let Some(m) = node.matrix {
        return Ok(DMat4::from_cols_array(&m.map(f64::from)));
    }
    let t = node.translation.unwrap_or([0.0; 3]).map(f64::from);
    let s = node.scale.unwrap_or([1.0; 3]).map(f64::from);
    let q = node
        .rotation
        .as_ref()
        .map_or([0.0, 0.0, 0.0, 1.0], |r| r.0)
        .map(f64::from);
    let q = DQuat::from_array(q);
    let len = q.length();
    if !(len.is_finite() && len > 0.0) {
        return Err(IoError::content(
            source,
            format!(
                "node {n}'s rotation {:?} is not a unit quaternion",
                q.to_array()
            ),
        ));
    }
    // Stored in f32, a unit quaternion is unit only to f32 precision.
    Ok(DMat4::from_scale_rotation_translation(
        DVec3::from_array(s),
        q / len,
        DVec3::from_array(t),
    ))
}

/// Every (mesh, world transform) of the default scene, in depth-first
/// order of the scene's nodes and their children.
fn instances(root: &Root, source: &str) -> Result<Vec<(usize, DMat4)>, IoError> {
    let scene = match root.scene {
        Some(s) => Some(root.scenes.get(s.value()).ok_or_else(|| {
            IoError::content(
                source,
                format!(
                    "the default scene is scene {}, but there are {} scenes",
                    s.value(),
                    root.scenes.len()
                ),
            )
        })?),
        None => root.scenes.first(),
    };
    let Some(scene) = scene else {
        return Ok((0..root.meshes.len())
            .map(|m| (m, DMat4::IDENTITY))
            .collect());
    };
    let node_count = root.nodes.len();
    let missing = |n: usize, whose: &str| {
        IoError::content(
            source,
            format!("{whose} refers to node {n}, but there are {node_count} nodes"),
        )
    };
    let mut out = Vec::new();
    let mut seen = vec![false; node_count];
    let mut stack: Vec<(usize, DMat4)> = Vec::new();
    for n in scene.nodes.iter().rev() {
        stack.push((n.value(), DMat4::IDENTITY));
    }
    while let Some((n, parent)) = stack.pop() {
        let node = root.nodes.get(n).ok_or_else(|| missing(n, "the scene"))?;
        // Nodes form trees: a node met twice is a cycle or a shared child,
        // either of which would make the traversal loop or repeat.
        if std::mem::replace(&mut seen[n], true) {
            return Err(IoError::content(
                source,
                format!("node {n} is reached twice: the node hierarchy must be a tree"),
            ));
        }
        let world = parent * local_transform(node, n, source)?;
        if let Some(m) = node.mesh {
            out.push((m.value(), world));
        }
        for c in node.children.iter().flatten().rev() {
            if c.value() >= node_count {
                return Err(missing(c.value(), &format!("node {n}")));
            }
            stack.push((c.value(), world));
        }
    }
    Ok(out)
}

/// The buffers of the file, loaded when an accessor first needs them.
struct Buffers<'a> {
    bin: Option<&'a [u8]>,
    dir: Option<&'a Path>,
    loaded: Vec<Option<Cow<'a, [u8]>>>,
}

/// A decoder for the base64 of data URIs, accepting them with or without
/// padding.
const BASE64: base64::engine::GeneralPurpose = base64::engine::GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    base64::engine::GeneralPurposeConfig::new()
        .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent),
);

/// Decodes `%XX` escapes of a relative URI into a file name.
fn percent_decode(uri: &str) -> Option<String> {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

impl<'a> Buffers<'a> {
    /// The bytes of buffer `b`, at least its declared `byteLength` long.
    fn get(&mut self, root: &Root, b: usize, source: &str) -> Result<&[u8], IoError> {
        let bad = |m: String| IoError::content(source, m);
        let buffer = root.buffers.get(b).ok_or_else(|| {
            bad(format!(
                "buffer {b} does not exist ({} buffers)",
                root.buffers.len()
            ))
        })?;
        if self.loaded[b].is_none() {
            let data: Cow<'a, [u8]> = match buffer.uri.as_deref() {
                None if b == 0 => Cow::Borrowed(self.bin.ok_or_else(|| {
                    bad("buffer 0 has no uri and the file has no GLB BIN chunk to hold it".into())
                })?),
                None => return Err(bad(format!("buffer {b} has no uri"))),
                Some(uri) if uri.starts_with("data:") => {
                    let (head, data) = uri.split_once(',').ok_or_else(|| {
                        bad(format!("buffer {b}'s data URI has no ',' before its data"))
                    })?;
                    if !head.ends_with(";base64") {
                        return Err(bad(format!(
                            "buffer {b}'s data URI is not base64 (\"{}\")",
                            show(head.as_bytes())
                        )));
                    }
                    Cow::Owned(BASE64.decode(data.trim_end()).map_err(|e| {
                        bad(format!("buffer {b}'s data URI is not valid base64: {e}"))
                    })?)
                }
                Some(uri) => Cow::Owned(self.file(uri, b, source)?),
            };
            self.loaded[b] = Some(data);
        }
        let data = self.loaded[b].as_deref().unwrap_or_default();
        if (data.len() as u64) < buffer.byte_length.0 {
            return Err(bad(format!(
                "buffer {b} holds {} bytes, fewer than its byteLength {}",
                data.len(),
                buffer.byte_length.0
            )));
        }
        Ok(data)
    }

    /// Reads a buffer stored in a file beside the glTF.
    fn file(&self, uri: &str, b: usize, source: &str) -> Result<Vec<u8>, IoError> {
        let bad = |m: String| IoError::content(source, m);
        // A scheme (`http:`, `file:`, a drive letter) comes before any '/'.
        let scheme = uri.find(':').is_some_and(|c| !uri[..c].contains('/'));
        if scheme || uri.starts_with('/') || uri.starts_with('\\') {
            return Err(bad(format!(
                "buffer {b}'s uri \"{}\" is not a relative file name; holey reads data URIs and files beside the glTF",
                show(uri.as_bytes())
            )));
        }
        let name = percent_decode(uri).ok_or_else(|| {
            bad(format!(
                "buffer {b}'s uri \"{}\" has a bad %-escape",
                show(uri.as_bytes())
            ))
        })?;
        let Some(dir) = self.dir else {
            return Err(bad(format!(
                "buffer {b} is in a separate file \"{}\", which is not read here: read the glTF from disk, or embed its buffers (a .glb, or data URIs)",
                show(name.as_bytes())
            )));
        };
        let path = dir.join(&name);
        std::fs::read(&path).map_err(|e| {
            IoError::io(
                &path.display().to_string(),
                "cannot read this buffer file named by the glTF",
                e,
            )
        })
    }
}

/// Where an accessor's elements lie: `count` elements of `size` bytes,
/// `stride` apart, from `start` in `data`.
struct Layout<'d> {
    data: &'d [u8],
    start: usize,
    stride: usize,
    count: usize,
}

impl Layout<'_> {
    fn element(&self, i: usize, size: usize) -> &[u8] {
        let at = self.start + i * self.stride;
        &self.data[at..at + size]
    }
}

struct Reader<'a> {
    root: &'a Root,
    source: &'a str,
    buffers: Buffers<'a>,
    mesh: PolyMesh,
}

fn component_name(c: ComponentType) -> &'static str {
    match c {
        ComponentType::I8 => "signed byte",
        ComponentType::U8 => "unsigned byte",
        ComponentType::I16 => "signed short",
        ComponentType::U16 => "unsigned short",
        ComponentType::U32 => "unsigned int",
        ComponentType::F32 => "float",
    }
}

impl Reader<'_> {
    fn bad(&self, m: impl std::fmt::Display) -> IoError {
        IoError::content(self.source, m)
    }

    /// Checks accessor `a` (for `what`, e.g. "POSITION of mesh 0
    /// primitive 1") and finds its bytes: every element must lie inside
    /// its buffer view, and the view inside its buffer.
    fn layout(
        &mut self,
        a: Index<gltf_json::Accessor>,
        what: &str,
        ty: Type,
        components: &[ComponentType],
    ) -> Result<(Layout<'_>, ComponentType), IoError> {
        let root = self.root;
        let n = a.value();
        let acc = root.accessors.get(n).ok_or_else(|| {
            self.bad(format!(
                "{what} refers to accessor {n}, but there are {} accessors",
                root.accessors.len()
            ))
        })?;
        if acc.sparse.is_some() {
            return Err(self.bad(format!(
                "accessor {n} ({what}) is sparse, which holey does not read"
            )));
        }
        let (Checked::Valid(GenericComponentType(component)), Checked::Valid(acc_ty)) =
            (acc.component_type, acc.type_)
        else {
            return Err(self.bad(format!(
                "accessor {n} ({what}) has an invalid componentType or type"
            )));
        };
        if acc_ty != ty || !components.contains(&component) {
            let want: Vec<_> = components.iter().map(|&c| component_name(c)).collect();
            return Err(self.bad(format!(
                "accessor {n} ({what}) holds {:?} of {}, but holey reads {ty:?} of {}",
                acc_ty,
                component_name(component),
                want.join(" or ")
            )));
        }
        let Some(v) = acc.buffer_view else {
            return Err(self.bad(format!(
                "accessor {n} ({what}) has no bufferView: its data would come from an extension such as Draco, which holey does not read"
            )));
        };
        let view = root.buffer_views.get(v.value()).ok_or_else(|| {
            self.bad(format!(
                "accessor {n} refers to buffer view {}, but there are {} buffer views",
                v.value(),
                root.buffer_views.len()
            ))
        })?;
        if let Some(ext) = view
            .extensions
            .as_ref()
            .and_then(|e| e.others.keys().next())
        {
            return Err(self.bad(format!(
                "buffer view {} is encoded with the extension {ext}, which holey does not read",
                v.value()
            )));
        }
        let size = component_size(component) * type_len(ty);
        let stride = view.byte_stride.map_or(size as u64, |s| s.0 as u64);
        if stride < size as u64 {
            return Err(self.bad(format!(
                "buffer view {}'s byteStride {stride} is less than accessor {n}'s element size {size}",
                v.value()
            )));
        }
        let count = acc.count.0;
        let acc_offset = acc.byte_offset.map_or(0, |o| o.0);
        let view_offset = view.byte_offset.map_or(0, |o| o.0);
        let view_len = view.byte_length.0;
        // The bytes the elements span, from the view's start.
        let span_end = count
            .checked_sub(1)
            .map(|last| {
                last.checked_mul(stride)
                    .and_then(|x| x.checked_add(size as u64))
                    .and_then(|x| x.checked_add(acc_offset))
            })
            .unwrap_or(Some(acc_offset));
        if span_end.is_none_or(|e| e > view_len) {
            return Err(self.bad(format!(
                "accessor {n} ({what}) is out of bounds: {count} elements of {size} bytes, {stride} apart, from byte {acc_offset} do not fit in buffer view {}'s {view_len} bytes",
                v.value()
            )));
        }
        let b = view.buffer.value();
        let buffer_len = root.buffers.get(b).map_or(0, |buf| buf.byte_length.0);
        if view_offset
            .checked_add(view_len)
            .is_none_or(|e| e > buffer_len)
        {
            return Err(self.bad(format!(
                "buffer view {} is out of bounds: {view_len} bytes from byte {view_offset} do not fit in buffer {b}'s byteLength {buffer_len}",
                v.value()
            )));
        }
        let source = self.source;
        let data = self.buffers.get(root, b, source)?;
        // Everything is now known to lie within `data`, so these fit usize.
        Ok((
            Layout {
                data,
                start: (view_offset + acc_offset) as usize,
                stride: stride as usize,
                count: count as usize,
            },
            component,
        ))
    }

    /// Appends the primitives of mesh `m` placed by `world`.
    fn instance(&mut self, m: usize, world: &DMat4) -> Result<(), IoError> {
        let root = self.root;
        let mesh = root.meshes.get(m).ok_or_else(|| {
            self.bad(format!(
                "a node refers to mesh {m}, but there are {} meshes",
                root.meshes.len()
            ))
        })?;
        let identity = *world == DMat4::IDENTITY;
        let mirror = DMat3::from_mat4(*world).determinant() < 0.0;
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let what = format!("mesh {m} primitive {p}");
            if let Some(ext) = prim.extensions.as_ref().and_then(|e| {
                e.others
                    .keys()
                    .find(|k| k.as_str() == "KHR_draco_mesh_compression")
            }) {
                return Err(self.bad(format!(
                    "{what} is compressed with {ext} (Draco), which holey does not read"
                )));
            }
            let mode = match prim.mode {
                Checked::Valid(mode) => mode,
                Checked::Invalid => return Err(self.bad(format!("{what} has an invalid mode"))),
            };
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                continue;
            }
            let Some(&pos) = prim.attributes.get(&Checked::Valid(Semantic::Positions)) else {
                return Err(self.bad(format!("{what} has no POSITION attribute")));
            };
            let base = self.mesh.positions.len();
            let count = self.positions(pos, &what, world, identity)?;
            let indices = match prim.indices {
                Some(i) => self.indices(i, &what)?,
                None => (0..count as u32).collect(),
            };
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= count) {
                return Err(self.bad(format!(
                    "{what}: index {bad} is out of range (its POSITION accessor has {count} vertices)"
                )));
            }
            self.triangles(&indices, mode, base, mirror, &what)?;
        }
        Ok(())
    }

    /// Appends the positions of accessor `a`, transformed; returns how
    /// many.
    fn positions(
        &mut self,
        a: Index<gltf_json::Accessor>,
        what: &str,
        world: &DMat4,
        identity: bool,
    ) -> Result<usize, IoError> {
        let what = format!("POSITION of {what}");
        let source = self.source;
        let held = self.mesh.positions.len() + self.mesh.face_indices.len();
        let (layout, _) = self.layout(a, &what, Type::Vec3, &[ComponentType::F32])?;
        if held + layout.count > crate::MAX_ELEMENTS {
            return Err(IoError::content(
                source,
                format!(
                    "{what}: the scene's meshes, placed by its nodes, hold more than {} vertices and corners",
                    crate::MAX_ELEMENTS
                ),
            ));
        }
        let mut out = Vec::with_capacity(layout.count);
        for i in 0..layout.count {
            let e = layout.element(i, 12);
            let f = |k: usize| f32::from_le_bytes([e[k], e[k + 1], e[k + 2], e[k + 3]]);
            let p = DVec3::new(f64::from(f(0)), f64::from(f(4)), f64::from(f(8)));
            let p = if identity {
                p
            } else {
                world.transform_point3(p)
            };
            if !p.is_finite() {
                return Err(IoError::content(
                    source,
                    format!(
                        "{what}: vertex {i} is not finite ({} {} {}) after its node's transform",
                        p.x, p.y, p.z
                    ),
                ));
            }
            out.push(p);
        }
        let count = out.len();
        self.mesh.positions.extend(out);
        Ok(count)
    }

    /// The indices of accessor `a`, as u32.
    fn indices(&mut self, a: Index<gltf_json::Accessor>, what: &str) -> Result<Vec<u32>, IoError> {
        let what = format!("indices of {what}");
        let (layout, component) = self.layout(
            a,
            &what,
            Type::Scalar,
            &[ComponentType::U8, ComponentType::U16, ComponentType::U32],
        )?;
        let size = component_size(component);
        Ok((0..layout.count)
            .map(|i| {
                let e = layout.element(i, size);
                match component {
                    ComponentType::U8 => u32::from(e[0]),
                    ComponentType::U16 => u32::from(u16::from_le_bytes([e[0], e[1]])),
                    _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
                }
            })
            .collect())
    }

    /// Appends the triangles `indices` make in `mode`, offset by `base`.
    fn triangles(
        &mut self,
        indices: &[u32],
        mode: Mode,
        base: usize,
        mirror: bool,
        what: &str,
    ) -> Result<(), IoError> {
        let n = indices.len();
        let mut tris: Vec<[u32; 3]> = match mode {
            Mode::Triangles => {
                if !n.is_multiple_of(3) {
                    return Err(
                        self.bad(format!("{what}: {n} indices do not make whole triangles"))
                    );
                }
                indices
                    .chunks_exact(3)
                    .map(|t| [t[0], t[1], t[2]])
                    .collect()
            }
            // Every other triangle of a strip is turned to keep the winding.
            Mode::TriangleStrip => (2..n)
                .map(|k| {
                    let (a, b, c) = (indices[k - 2], indices[k - 1], indices[k]);
                    if k % 2 == 0 { [a, b, c] } else { [b, a, c] }
                })
                .collect(),
            Mode::TriangleFan => (2..n)
                .map(|k| [indices[0], indices[k - 1], indices[k]])
                .collect(),
            _ => Vec::new(),
        };
        if mirror {
            for t in &mut tris {
                t.swap(1, 2);
            }
        }
        if self.mesh.positions.len() + self.mesh.face_indices.len() + 3 * tris.len()
            > crate::MAX_ELEMENTS
        {
            return Err(self.bad(format!(
                "{what}: the scene's meshes, placed by its nodes, hold more than {} vertices and corners",
                crate::MAX_ELEMENTS
            )));
        }
        // Both below MAX_ELEMENTS, so u32 holds them.
        let base = base as u32;
        let out = &mut self.mesh;
        out.face_indices.reserve(3 * tris.len());
        out.face_offsets.reserve(tris.len());
        for t in tris {
            out.face_indices.extend(t.map(|i| base + i));
            out.face_offsets.push(out.face_indices.len() as u32);
        }
        Ok(())
    }
}

fn component_size(c: ComponentType) -> usize {
    match c {
        ComponentType::I8 | ComponentType::U8 => 1,
        ComponentType::I16 | ComponentType::U16 => 2,
        ComponentType::U32 | ComponentType::F32 => 4,
    }
}

fn type_len(t: Type) -> usize {
    match t {
        Type::Scalar => 1,
        Type::Vec2 => 2,
        Type::Vec3 => 3,
        Type::Vec4 | Type::Mat2 => 4,
        Type::Mat3 => 9,
        Type::Mat4 => 16,
    }
}

// ---- writing ----------------------------------------------------------------

/// The glTF document for a mesh and its binary buffer (positions, then
/// indices). `uri` is the buffer's URI (`None` for a GLB's BIN chunk).
fn document(mesh: &PolyMesh, embed: bool) -> Result<(Root, Vec<u8>), String> {
    let (tris, _) = mesh.fan_triangles();
    let nv = mesh.positions.len();
    let mut bin = Vec::with_capacity(12 * nv + 12 * tris.len());
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for (v, p) in mesh.positions.iter().enumerate() {
        for (k, &x) in p.to_array().iter().enumerate() {
            // `as` rounds to the nearest f32; out of range it gives ±inf.
            let f = x as f32;
            if !f.is_finite() {
                return Err(format!(
                    "vertex {v}'s coordinate {x} is beyond the range of f32, which glTF positions are"
                ));
            }
            min[k] = min[k].min(f);
            max[k] = max[k].max(f);
            bin.extend_from_slice(&f.to_le_bytes());
        }
    }
    let positions_len = bin.len();
    for t in &tris {
        for i in t {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let mut root = Root {
        asset: gltf_json::Asset {
            generator: Some("holey".into()),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut scene = gltf_json::Scene {
        extensions: None,
        extras: Default::default(),
        name: None,
        nodes: Vec::new(),
    };
    // A scene lists at least one node (and gltf-json reads no scene
    // without), so an empty mesh is a node without a mesh.
    let mut node = gltf_json::Node::default();
    if nv > 0 {
        let uri = embed.then(|| {
            format!(
                "data:application/octet-stream;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&bin)
            )
        });
        let buffer = root.push(gltf_json::Buffer {
            byte_length: USize64::from(bin.len()),
            name: None,
            uri,
            extensions: None,
            extras: Default::default(),
        });
        let view = |offset: usize, len: usize, target| gltf_json::buffer::View {
            buffer,
            byte_length: USize64::from(len),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Checked::Valid(target)),
            extensions: None,
            extras: Default::default(),
        };
        let accessor =
            |view, count: usize, component, type_, bounds: Option<([f32; 3], [f32; 3])>| {
                gltf_json::Accessor {
                    buffer_view: Some(view),
                    byte_offset: None,
                    count: USize64::from(count),
                    component_type: Checked::Valid(GenericComponentType(component)),
                    extensions: None,
                    extras: Default::default(),
                    type_: Checked::Valid(type_),
                    min: bounds.map(|b| gltf_json::Value::from(b.0.to_vec())),
                    max: bounds.map(|b| gltf_json::Value::from(b.1.to_vec())),
                    name: None,
                    normalized: false,
                    sparse: None,
                }
            };
        let pv = root.push(view(
            0,
            positions_len,
            gltf_json::buffer::Target::ArrayBuffer,
        ));
        let pa = root.push(accessor(
            pv,
            nv,
            ComponentType::F32,
            Type::Vec3,
            Some((min, max)),
        ));
        let indices = if tris.is_empty() {
            None
        } else {
            let iv = root.push(view(
                positions_len,
                bin.len() - positions_len,
                gltf_json::buffer::Target::ElementArrayBuffer,
            ));
            Some(root.push(accessor(
                iv,
                3 * tris.len(),
                ComponentType::U32,
                Type::Scalar,
                None,
            )))
        };
        let primitive = gltf_json::mesh::Primitive {
            attributes: BTreeMap::from([(Checked::Valid(Semantic::Positions), pa)]),
            extensions: None,
            extras: Default::default(),
            indices,
            material: None,
            mode: Checked::Valid(if tris.is_empty() {
                Mode::Points
            } else {
                Mode::Triangles
            }),
            targets: None,
        };
        let m = root.push(gltf_json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: None,
            primitives: vec![primitive],
            weights: None,
        });
        node.mesh = Some(m);
    }
    scene.nodes.push(root.push(node));
    let scene = root.push(scene);
    root.scene = Some(scene);
    Ok((root, if embed { Vec::new() } else { bin }))
}

/// The mesh as a `.gltf` file (JSON with its buffer as a base64 data URI).
/// The error says why the mesh cannot be written.
pub fn encode_gltf(mesh: &PolyMesh) -> Result<Vec<u8>, String> {
    let (root, _) = document(mesh, true)?;
    let mut out = root
        .to_vec_pretty()
        .map_err(|e| format!("cannot encode the glTF JSON: {e}"))?;
    out.push(b'\n');
    Ok(out)
}

/// The mesh as a `.glb` file: header, JSON chunk, BIN chunk. The error
/// says why the mesh cannot be written.
pub fn encode_glb(mesh: &PolyMesh) -> Result<Vec<u8>, String> {
    let (root, mut bin) = document(mesh, false)?;
    let mut json = root
        .to_vec()
        .map_err(|e| format!("cannot encode the glTF JSON: {e}"))?;
    // Chunks are 4-byte aligned: JSON padded with spaces, BIN with zeros.
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = 12 + 8 + json.len() + bin_chunk;
    let total32 = u32::try_from(total)
        .map_err(|_| format!("{total} bytes exceed the 4 GiB a GLB file can hold"))?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(GLB_MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    // Both lengths are below `total`, which fits u32.
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(&bin);
    }
    Ok(out)
}

/// Writes the mesh as `.glb` (see the module docs). A mesh glTF cannot
/// hold is an [`io::ErrorKind::InvalidInput`] error.
pub fn write_glb<W: Write>(w: W, mesh: &PolyMesh) -> io::Result<()> {
    crate::write_encoded(w, encode_glb(mesh))
}

/// Writes the mesh as a self-contained `.gltf` (see the module docs). A
/// mesh glTF cannot hold is an [`io::ErrorKind::InvalidInput`] error.
pub fn write_gltf<W: Write>(w: W, mesh: &PolyMesh) -> io::Result<()> {
    crate::write_encoded(w, encode_gltf(mesh))
}

#[cfg(test)]
mod tests {
    // Test helpers may unwrap: a panic is a failed test.
    #![allow(clippy::unwrap_used)]

    use std::fs;

    use super::*;
    use crate::{MeshFile, WriteOptions, face_lists, read_path, write_poly};

    /// Triangles, a quad (fanned on writing) and an unused vertex, at
    /// coordinates f32 does not hold exactly.
    fn sample() -> PolyMesh {
        let positions = vec![
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.0 / 3.0, -2.7e10, 1e-30),
            DVec3::new(-1.5, 2.25, 7.0),
            DVec3::new(0.7, 0.0, -0.0),
            DVec3::new(9.0, 9.0, 9.0),
            DVec3::new(3.0, 1.0, 4.0),
        ];
        PolyMesh::from_faces(positions, [&[0u32, 1, 2][..], &[0, 2, 3, 5], &[5, 3, 1]])
    }

    fn assert_round_trip(back: &PolyMesh, m: &PolyMesh) {
        let rounded: Vec<DVec3> = m
            .positions
            .iter()
            .map(|p| p.to_array().map(|x| f64::from(x as f32)).into())
            .collect();
        assert_eq!(back.positions, rounded);
        let (tris, _) = m.fan_triangles();
        let want: Vec<Vec<u32>> = tris.iter().map(|t| t.to_vec()).collect();
        assert_eq!(face_lists(back), want);
    }

    /// A GLB of a JSON document and a BIN chunk.
    fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
        let mut j = json.as_bytes().to_vec();
        while !j.len().is_multiple_of(4) {
            j.push(b' ');
        }
        let mut b = bin.to_vec();
        while !b.len().is_multiple_of(4) {
            b.push(0);
        }
        let total = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
        let mut out = b"glTF".to_vec();
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(j.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&j);
        if !b.is_empty() {
            out.extend_from_slice(&(b.len() as u32).to_le_bytes());
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&b);
        }
        out
    }

    /// `points` as a buffer holds VEC3 float positions (little-endian
    /// f32), each followed by `padding` (the bytes a `byteStride` beyond
    /// 12 skips): the start of the test buffers built by hand.
    fn f32_points(points: &[[f32; 3]], padding: &[u8]) -> Vec<u8> {
        let mut b = Vec::new();
        for p in points {
            for x in p {
                b.extend_from_slice(&x.to_le_bytes());
            }
            b.extend_from_slice(padding);
        }
        b
    }

    /// Four f32 positions (the unit tetrahedron's corners), then u16
    /// indices of two triangles: 48 + 12 bytes.
    fn tetra_bin() -> Vec<u8> {
        let mut b = f32_points(
            &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            &[],
        );
        for i in [0u16, 1, 2, 0, 2, 3] {
            b.extend_from_slice(&i.to_le_bytes());
        }
        b
    }

    /// A document over `tetra_bin` with the given nodes, scenes and
    /// primitive; `{extra}` goes at the top level.
    fn doc(nodes: &str, primitive: &str, extra: &str) -> String {
        format!(
            r#"{{"asset":{{"version":"2.0"}},{extra}
            "buffers":[{{"byteLength":60}}],
            "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":12}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}},
                         {{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}}],
            "meshes":[{{"primitives":[{primitive}]}}],
            "nodes":{nodes}}}"#
        )
    }

    const PRIMITIVE: &str = r#"{"attributes":{"POSITION":0},"indices":1}"#;

    fn err(bytes: &[u8]) -> String {
        parse(bytes, "t.glb").unwrap_err().to_string()
    }

    #[test]
    fn glb_and_gltf_round_trip() {
        let m = sample();
        let back = parse_glb(&encode_glb(&m).unwrap(), "t.glb").unwrap();
        assert_round_trip(&back, &m);
        let text = encode_gltf(&m).unwrap();
        let json = std::str::from_utf8(&text).unwrap();
        assert!(json.contains("\"uri\": \"data:application/octet-stream;base64,"));
        // POSITION accessors must carry their bounds.
        let v: gltf_json::Value = gltf_json::deserialize::from_slice(&text).unwrap();
        assert_eq!(
            v["accessors"][0]["min"][1].as_f64(),
            Some(f64::from(-2.7e10f32))
        );
        assert_eq!(v["accessors"][0]["max"][0].as_f64(), Some(9.0));
        assert_eq!(v["accessors"][1]["componentType"], 5125, "u32 indices");
        assert!(
            v["meshes"][0]["primitives"][0]["attributes"]
                .get("NORMAL")
                .is_none()
        );
        assert_round_trip(&parse(&text, "t.gltf").unwrap(), &m);
        // Through files, as every command reads and writes them.
        let dir = tempfile::tempdir().unwrap();
        for ext in ["glb", "gltf"] {
            let path = dir.path().join(format!("t.{ext}"));
            write_poly(&path, &m, &WriteOptions::default()).unwrap();
            let MeshFile::Poly(back) = read_path(&path).unwrap() else {
                panic!("not a polygon mesh");
            };
            assert_round_trip(&back, &m);
        }
        assert!(
            fs::read(dir.path().join("t.glb"))
                .unwrap()
                .starts_with(b"glTF")
        );
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            2,
            "one file each"
        );
    }

    #[test]
    fn empty_and_faceless_meshes_are_written() {
        let empty = PolyMesh::new();
        for bytes in [encode_glb(&empty).unwrap(), encode_gltf(&empty).unwrap()] {
            let back = parse(&bytes, "e").unwrap();
            assert_eq!((back.positions.len(), back.face_count()), (0, 0));
        }
        // Points only: written as a POINTS primitive, which has no faces.
        let points = PolyMesh::from_faces(vec![DVec3::X, DVec3::Y], [[0u32; 0]; 0]);
        let bytes = encode_glb(&points).unwrap();
        let v: gltf_json::Value = gltf_json::deserialize::from_slice(
            &bytes[20..20 + u32_at(&bytes, 12).unwrap() as usize],
        )
        .unwrap();
        assert_eq!(v["meshes"][0]["primitives"][0]["mode"], 0);
        assert_eq!(parse_glb(&bytes, "p").unwrap().face_count(), 0);
    }

    #[test]
    fn node_transforms_are_applied() {
        // Scene 1 is the default: node 0 translates its child node 1, which
        // scales; node 2 translates by a matrix; node 3 mirrors x. Scene 0
        // would place the mesh untransformed.
        let nodes = r#"[{"translation":[10,0,0],"children":[1]},
                        {"scale":[2,2,2],"mesh":0},
                        {"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1],"mesh":0},
                        {"scale":[-1,1,1],"mesh":0},
                        {"mesh":0}]"#;
        let json = doc(
            nodes,
            PRIMITIVE,
            r#""scene":1,"scenes":[{"nodes":[4]},{"nodes":[0,2,3]}],"#,
        );
        let m = parse_glb(&glb(&json, &tetra_bin()), "t.glb").unwrap();
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut want: Vec<DVec3> = corners
            .iter()
            .map(|&p| 2.0 * p + DVec3::new(10.0, 0.0, 0.0))
            .collect();
        want.extend(corners.iter().map(|&p| p + DVec3::new(0.0, 0.0, 5.0)));
        want.extend(corners.iter().map(|&p| DVec3::new(-p.x, p.y, p.z)));
        assert_eq!(m.positions, want);
        // The mirrored copy has its triangles turned over.
        assert_eq!(
            face_lists(&m),
            vec![
                vec![0, 1, 2],
                vec![0, 2, 3],
                vec![4, 5, 6],
                vec![4, 6, 7],
                vec![8, 10, 9],
                vec![8, 11, 10],
            ]
        );
        // A rotation (90° about z, as a quaternion) turns x into y.
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let nodes = format!(r#"[{{"rotation":[0,0,{h},{h}],"mesh":0}}]"#);
        let json = doc(&nodes, PRIMITIVE, r#""scenes":[{"nodes":[0]}],"#);
        let m = parse_glb(&glb(&json, &tetra_bin()), "t.glb").unwrap();
        assert!(
            (m.positions[1] - DVec3::Y).length() < 1e-15,
            "{}",
            m.positions[1]
        );
        // Without scenes, every mesh once, untransformed.
        let json = doc(r#"[{"translation":[1,1,1],"mesh":0}]"#, PRIMITIVE, "");
        let m = parse_glb(&glb(&json, &tetra_bin()), "t.glb").unwrap();
        assert_eq!(m.positions, corners);
    }

    #[test]
    fn index_types_strides_and_modes() {
        // Positions interleaved with padding (stride 16), u8 indices, no
        // indices, strips, fans; points and lines contribute nothing.
        let mut bin = f32_points(
            &[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.]],
            &[0xAB; 4],
        );
        bin.extend_from_slice(&[0u8, 1, 2, 3]);
        let json = r#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
            "buffers":[{"byteLength":68}],
            "bufferViews":[{"buffer":0,"byteLength":64,"byteStride":16},{"buffer":0,"byteOffset":64,"byteLength":4}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                         {"bufferView":1,"componentType":5121,"count":3,"type":"SCALAR"},
                         {"bufferView":1,"componentType":5121,"count":4,"type":"SCALAR"}],
            "meshes":[{"primitives":[
                {"attributes":{"POSITION":0},"indices":1},
                {"attributes":{"POSITION":0},"mode":5,"indices":2},
                {"attributes":{"POSITION":0},"mode":6},
                {"attributes":{"POSITION":0},"mode":0},
                {"attributes":{"POSITION":0},"mode":1}]}]}"#;
        let m = parse_glb(&glb(json, &bin), "t.glb").unwrap();
        assert_eq!(
            m.positions.len(),
            12,
            "three triangle primitives of 4 vertices"
        );
        assert_eq!(m.positions[3], DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(
            face_lists(&m),
            vec![
                vec![0, 1, 2],
                // The strip 0 1 2 3: (0 1 2), then (2 1 3) keeping the winding.
                vec![4, 5, 6],
                vec![6, 5, 7],
                // The fan 0 1 2 3: (0 1 2), (0 2 3).
                vec![8, 9, 10],
                vec![8, 10, 11],
            ]
        );
    }

    #[test]
    fn external_buffers_are_read_beside_the_file_and_only_there() {
        let dir = tempfile::tempdir().unwrap();
        let json = doc("[{\"mesh\":0}]", PRIMITIVE, r#""scenes":[{"nodes":[0]}],"#).replace(
            r#"{"byteLength":60}"#,
            r#"{"byteLength":60,"uri":"data%20file.bin"}"#,
        );
        fs::write(dir.path().join("data file.bin"), tetra_bin()).unwrap();
        let path = dir.path().join("t.gltf");
        fs::write(&path, &json).unwrap();
        let MeshFile::Poly(m) = read_path(&path).unwrap() else {
            panic!("not a polygon mesh")
        };
        assert_eq!(m.positions[3], DVec3::Z);
        assert_eq!(m.face_count(), 2);
        // From bytes alone nothing else is opened.
        let e = crate::parse(crate::Format::Gltf, json.as_bytes(), "up.gltf").unwrap_err();
        assert!(e.is_bad_input());
        assert!(
            e.to_string()
                .starts_with("up.gltf: buffer 0 is in a separate file \"data file.bin\""),
            "{e}"
        );
        // A missing buffer file is a failure to read a file, naming it.
        fs::remove_file(dir.path().join("data file.bin")).unwrap();
        let e = read_path(&path).unwrap_err();
        assert!(!e.is_bad_input());
        assert!(e.to_string().contains("data file.bin"), "{e}");
        // URLs and absolute paths are not followed.
        for uri in ["https://example.invalid/a.bin", "/etc/a.bin", "file:a.bin"] {
            let j = json.replace("data%20file.bin", uri);
            fs::write(&path, &j).unwrap();
            let e = read_path(&path).unwrap_err().to_string();
            assert!(e.contains("is not a relative file name"), "{e}");
        }
    }

    #[test]
    fn malformed_files_are_clear_errors() {
        let scene = r#""scenes":[{"nodes":[0]}],"#;
        let good = glb(&doc("[{\"mesh\":0}]", PRIMITIVE, scene), &tetra_bin());
        assert!(parse_glb(&good, "t.glb").is_ok());
        // Every truncation is an error, never a panic.
        for len in 0..good.len() {
            assert!(parse_glb(&good[..len], "t.glb").is_err(), "{len}");
        }
        assert_eq!(
            err(&good[..good.len() - 8]),
            format!(
                "t.glb: byte {}: file is truncated: the GLB header declares {} bytes, the file has {}",
                good.len() - 8,
                good.len(),
                good.len() - 8
            )
        );
        assert!(err(&good[..7]).contains("inside the 12-byte GLB header"));
        let mut long = good.clone();
        long.extend_from_slice(b"junk");
        assert!(err(&long).contains("4 bytes follow the"));
        // Magic, version, chunk types and lengths.
        let e = parse_glb(b"GLTF\x02\0\0\0\x0c\0\0\0", "t.glb").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.glb: byte 0: not a GLB file: it starts with \"GLTF\", not the magic \"glTF\""
        );
        let mut v1 = good.clone();
        v1[4] = 1;
        assert!(err(&v1).contains("GLB version 1 is not supported"));
        let mut bad_type = good.clone();
        bad_type[16..20].copy_from_slice(b"BIN\0");
        assert!(err(&bad_type).contains("the first chunk must be JSON"));
        let mut bad_len = good.clone();
        bad_len[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(err(&bad_len).contains("chunk 0 declares 4294967295 bytes"));
        // The JSON.
        let e = err(&glb(
            "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ oops",
            &[],
        ));
        assert!(
            e.starts_with("t.glb: the JSON chunk is not valid glTF: "),
            "{e}"
        );
        assert!(e.contains("line 1 column"), "{e}");
        let e = parse(b"{\"asset\":{\"version\":\"2.0\"},\n\"nodes\":7}", "t.gltf").unwrap_err();
        assert!(
            e.to_string().starts_with("t.gltf: not valid glTF JSON: "),
            "{e}"
        );
        let e = parse(
            b"{\"asset\":{\"version\":\"1.0\"},\"meshes\":{}}",
            "old.gltf",
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "old.gltf: glTF version 1.0 is not supported (holey reads glTF 2.0)"
        );
        // What the document says about its data.
        let bin = tetra_bin();
        let cases: &[(String, &str)] = &[
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace("\"count\":4", "\"count\":5"),
                "accessor 0 (POSITION of mesh 0 primitive 0) is out of bounds: 5 elements of 12 bytes",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace("\"byteOffset\":48,", "\"byteOffset\":50,"),
                "buffer view 1 is out of bounds: 12 bytes from byte 50 do not fit in buffer 0's byteLength 60",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace("{\"byteLength\":60}", "{\"byteLength\":64}"),
                "buffer 0 holds 60 bytes, fewer than its byteLength 64",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace("\"count\":6", "\"count\":4"),
                "mesh 0 primitive 0: 4 indices do not make whole triangles",
            ),
            (
                doc("[{\"mesh\":0}]", r#"{"attributes":{"POSITION":0},"indices":9}"#, scene),
                "indices of mesh 0 primitive 0 refers to accessor 9, but there are 2 accessors",
            ),
            (
                doc("[{\"mesh\":0}]", r#"{"attributes":{"NORMAL":0}}"#, scene),
                "mesh 0 primitive 0 has no POSITION attribute",
            ),
            (
                doc("[{\"mesh\":0}]", r#"{"attributes":{"POSITION":1}}"#, scene),
                "accessor 1 (POSITION of mesh 0 primitive 0) holds Scalar of unsigned short, but holey reads Vec3 of float",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace(
                    "\"count\":4,\"type\":\"VEC3\"}",
                    "\"count\":4,\"type\":\"VEC3\",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123},\"values\":{\"bufferView\":0}}}",
                ),
                "accessor 0 (POSITION of mesh 0 primitive 0) is sparse, which holey does not read",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace("\"byteLength\":48}", "\"byteLength\":48,\"byteStride\":8}"),
                "buffer view 0's byteStride 8 is less than accessor 0's element size 12",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, r#""extensionsRequired":["KHR_materials_unlit","KHR_draco_mesh_compression"],"#),
                "the file requires the glTF extension KHR_draco_mesh_compression, which holey does not read (Draco-compressed meshes)",
            ),
            (
                doc(
                    "[{\"mesh\":0}]",
                    r#"{"attributes":{"POSITION":0},"indices":1,"extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":0}}}}"#,
                    scene,
                ),
                "mesh 0 primitive 0 is compressed with KHR_draco_mesh_compression (Draco), which holey does not read",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace(
                    "{\"bufferView\":0,\"componentType\":5126",
                    "{\"componentType\":5126",
                ),
                "accessor 0 (POSITION of mesh 0 primitive 0) has no bufferView",
            ),
            (
                doc("[{\"children\":[1]},{\"children\":[0],\"mesh\":0}]", PRIMITIVE, scene),
                "node 0 is reached twice: the node hierarchy must be a tree",
            ),
            (
                doc("[{\"children\":[5]}]", PRIMITIVE, scene),
                "node 0 refers to node 5, but there are 1 nodes",
            ),
            (
                doc("[{\"mesh\":3}]", PRIMITIVE, scene),
                "a node refers to mesh 3, but there are 1 meshes",
            ),
            (
                doc("[{\"mesh\":0}]", PRIMITIVE, r#""scene":2,"scenes":[{"nodes":[0]}],"#),
                "the default scene is scene 2, but there are 1 scenes",
            ),
            (
                doc("[{\"mesh\":0,\"rotation\":[0,0,0,0]}]", PRIMITIVE, scene),
                "node 0's rotation [0.0, 0.0, 0.0, 0.0] is not a unit quaternion",
            ),
            (
                doc("[{\"mesh\":0,\"scale\":[1e30,1e30,1e30]},{\"mesh\":0,\"scale\":[1e30,1,1]}]", PRIMITIVE, r#""scenes":[{"nodes":[1,0]}],"#),
                "",
            ),
        ];
        for (json, want) in cases {
            let r = parse_glb(&glb(json, &bin), "t.glb");
            if want.is_empty() {
                // Large but finite transforms are fine.
                assert!(r.is_ok(), "{r:?}");
                continue;
            }
            let e = r.unwrap_err();
            assert!(e.is_bad_input());
            assert!(
                e.to_string().starts_with(&format!("t.glb: {want}")),
                "want {want:?}\n got {e}"
            );
        }
        // An index past the vertices: patch the last u16 index to 7.
        let mut bad_index = bin.clone();
        bad_index[58..60].copy_from_slice(&7u16.to_le_bytes());
        let e = err(&glb(&doc("[{\"mesh\":0}]", PRIMITIVE, scene), &bad_index));
        assert_eq!(
            e,
            "t.glb: mesh 0 primitive 0: index 7 is out of range (its POSITION accessor has 4 vertices)"
        );
        // Non-finite positions, stored or after a transform (1e39 is
        // infinite in f32).
        let mut nan = bin.clone();
        nan[16..20].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = err(&glb(&doc("[{\"mesh\":0}]", PRIMITIVE, scene), &nan));
        assert!(e.contains("vertex 1 is not finite"), "{e}");
        let e = err(&glb(
            &doc("[{\"mesh\":0,\"scale\":[1e39,1,1]}]", PRIMITIVE, scene),
            &bin,
        ));
        assert!(e.contains("vertex 0 is not finite"), "{e}");
        // Buffers: no BIN chunk, bad data URIs.
        let e = err(&glb(&doc("[{\"mesh\":0}]", PRIMITIVE, scene), &[]));
        assert!(
            e.contains("buffer 0 has no uri and the file has no GLB BIN chunk"),
            "{e}"
        );
        let with_uri = |uri: &str| {
            doc("[{\"mesh\":0}]", PRIMITIVE, scene).replace(
                "{\"byteLength\":60}",
                &format!("{{\"byteLength\":60,\"uri\":\"{uri}\"}}"),
            )
        };
        let e = parse(
            with_uri("data:application/octet-stream;base64,@@@@").as_bytes(),
            "t.gltf",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("buffer 0's data URI is not valid base64"), "{e}");
        let e = parse(with_uri("data:text/plain,abc").as_bytes(), "t.gltf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not base64"), "{e}");
    }

    #[test]
    fn writes_refuse_what_gltf_cannot_hold_and_leave_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let mut m = sample();
        m.positions[2].y = 1e39;
        for ext in ["glb", "gltf"] {
            let path = dir.path().join(format!("t.{ext}"));
            let e = write_poly(&path, &m, &WriteOptions::default()).unwrap_err();
            assert!(e.is_bad_input());
            assert_eq!(
                e.to_string(),
                format!(
                    "{}: cannot write this mesh: vertex 2's coordinate 1000000000000000000000000000000000000000 is beyond the range of f32, which glTF positions are",
                    path.display()
                )
            );
        }
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            0,
            "nothing written"
        );
        // An existing file stays as it was.
        let keep = dir.path().join("keep.glb");
        fs::write(&keep, b"precious").unwrap();
        write_poly(&keep, &m, &WriteOptions::default()).unwrap_err();
        assert_eq!(fs::read(&keep).unwrap(), b"precious");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
