//! 3MF, the 3D Manufacturing Format: a ZIP package of XML parts.
//!
//! 3MF is what slicers and CAD tools exchange for printing; unlike STL it
//! keeps shared vertices, and its coordinates are decimal text, so a mesh
//! can go through it without losing a bit. The package is read and
//! written with the `zip` crate and the XML with `quick-xml`; the one 3MF
//! crate there is reads every `.model` part of an archive without
//! following the package's relationships and says nothing about where a
//! file is wrong, so holey does the little 3MF needs here itself.
//!
//! Read: the start part named by the package relationships (`_rels/.rels`,
//! the relationship of type `…/3dmanufacturing/2013/01/3dmodel`; without
//! that file, `3D/3dmodel.model`). Every build item contributes its object:
//! the object's mesh, and the meshes of its components, recursively (also
//! in other model parts, as the production extension's `p:path` names
//! them), each with the product of the transforms from the item down
//! (3MF's `m00 … m32` row-vector affine matrices) applied in `f64`, and
//! with triangles turned over where that product mirrors. Everything
//! makes one polygon mesh of triangles, objects' vertices kept as stored
//! (nothing is welded) and in build order. Elements of other namespaces
//! (materials, colours, beam lattices, slices, vendors' metadata) are
//! skipped; the `unit` is not applied (coordinates are taken as numbers,
//! as every other format here holds them). Errors name the part and the
//! line: bad XML, a missing attribute, a bad number, a triangle naming a
//! vertex the mesh does not have, an item or component naming an object
//! that does not exist, components that contain themselves.
//!
//! Write: one object holding the mesh, one build item, unit millimetre.
//! Coordinates are written as shortest round-trip decimals (Rust's
//! formatting of `f64`, in exponent form only for very large or small
//! magnitudes, which 3MF's number syntax allows), so write then read gives
//! back the same bits. Faces are fan-triangulated from their first corner
//! (3MF holds triangles only); faces of fewer than three corners are left
//! out; every vertex is written, so vertex numbers survive. The model part
//! is deflated.

use std::borrow::Cow;
use std::collections::HashMap;
use std::io::{self, Cursor, Read, Write};

use glam::{DMat3, DMat4, DVec3};
use holey_mesh::{NonFinite, PolyMesh};
use quick_xml::NsReader;
use quick_xml::events::{BytesStart, Event};
use quick_xml::name::{Namespace, ResolveResult};
use zip::ZipArchive;
use zip::write::SimpleFileOptions;

use crate::IoError;
use crate::error::show;
use crate::text::{parse_finite, parse_u64, push_f64, push_u64};

/// The namespace of 3MF's core elements.
const CORE_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
/// The namespace of the production extension's `p:path`.
const PRODUCTION_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
/// The relationship type that names a package's 3D model part.
const MODEL_RELATIONSHIP: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
/// Where the model part usually is, and where holey writes it.
const DEFAULT_PART: &str = "3D/3dmodel.model";
/// Components nested deeper than this are refused (real files nest a few
/// levels; a long chain would only exhaust the stack).
const MAX_DEPTH: usize = 256;

/// Parses a 3MF file's bytes (see the module docs). `source` names the
/// file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    let zip = ZipArchive::new(Cursor::new(bytes)).map_err(|e| {
        IoError::content(
            source,
            format!("not a 3MF file: not a readable ZIP archive ({e})"),
        )
    })?;
    let mut reader = Package {
        zip,
        source,
        parts: HashMap::new(),
        mesh: PolyMesh::new(),
    };
    let start = reader.start_part()?;
    reader.load(&start)?;
    let build = reader
        .parts
        .get(&start)
        .map(|m| m.build.clone())
        .unwrap_or_default();
    for item in build {
        let part = item.part.clone().unwrap_or_else(|| start.clone());
        let mut stack = Vec::new();
        reader.place(&part, &item, item.transform, &mut stack)?;
    }
    Ok(reader.mesh)
}

/// An object's mesh as stored.
#[derive(Default)]
struct ObjectMesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

/// A reference to an object: a build item or a component.
#[derive(Clone)]
struct Ref {
    /// The object's id.
    object: u64,
    /// The model part holding it (`p:path`), when not the referring one.
    part: Option<String>,
    /// The referring element's transform.
    transform: DMat4,
    /// The referring element's line, for messages.
    line: usize,
}

#[derive(Default)]
struct Object {
    mesh: Option<ObjectMesh>,
    components: Vec<Ref>,
}

/// One model part: its objects by id and its build items.
#[derive(Default)]
struct Model {
    objects: HashMap<u64, Object>,
    build: Vec<Ref>,
}

struct Package<'a> {
    zip: ZipArchive<Cursor<&'a [u8]>>,
    source: &'a str,
    parts: HashMap<String, Model>,
    mesh: PolyMesh,
}

/// A part name as stored in the archive: without the leading '/'.
fn part_name(target: &str) -> String {
    target.trim_start_matches('/').to_owned()
}

/// The 1-based line of byte `pos` of `text`.
fn line_at(text: &[u8], pos: u64) -> usize {
    let end = (pos as usize).min(text.len());
    1 + text[..end].iter().filter(|&&c| c == b'\n').count()
}

impl Package<'_> {
    fn bad(&self, m: impl std::fmt::Display) -> IoError {
        IoError::content(self.source, m)
    }

    /// The bytes of a part, or `None` if the archive has no such part.
    fn read_part(&mut self, name: &str) -> Result<Option<Vec<u8>>, IoError> {
        let index = self.zip.index_for_name(name).or_else(|| {
            // Part names are case-insensitive in the package format.
            (0..self.zip.len()).find(|&i| {
                self.zip
                    .name_for_index(i)
                    .and_then(Result::ok)
                    .is_some_and(|n| n.eq_ignore_ascii_case(name))
            })
        });
        let Some(index) = index else { return Ok(None) };
        let source = self.source;
        let corrupt = |e: &dyn std::fmt::Display| {
            IoError::content(
                source,
                format!("part {name} cannot be read from the ZIP archive: {e}"),
            )
        };
        let file = self.zip.by_index(index).map_err(|e| corrupt(&e))?;
        let declared = file.size();
        // Deflate expands at most about 1032 times: a larger declared size
        // is a lie, and must not size an allocation.
        let most = file
            .compressed_size()
            .saturating_mul(1032)
            .saturating_add(1 << 10);
        if declared > most {
            return Err(corrupt(&format!(
                "it declares {declared} bytes uncompressed, more than its {} compressed bytes can hold",
                file.compressed_size()
            )));
        }
        let mut out = Vec::with_capacity(declared.min(1 << 24) as usize);
        file.take(declared.saturating_add(1))
            .read_to_end(&mut out)
            .map_err(|e| corrupt(&e))?;
        if out.len() as u64 != declared {
            return Err(corrupt(&format!(
                "it holds {} bytes, not the {declared} its header declares",
                out.len()
            )));
        }
        Ok(Some(out))
    }

    /// The model part the package relationships name.
    fn start_part(&mut self) -> Result<String, IoError> {
        let Some(rels) = self.read_part("_rels/.rels")? else {
            return Ok(DEFAULT_PART.to_owned());
        };
        let source = self.source;
        let at = |r: &NsReader<&[u8]>, m: String| {
            IoError::content(
                source,
                format!("_rels/.rels:{}: {m}", line_at(&rels, r.buffer_position())),
            )
        };
        let mut r = NsReader::from_reader(&rels[..]);
        loop {
            match r.read_event() {
                Err(e) => return Err(at(&r, format!("bad XML: {e}"))),
                Ok(Event::Eof) => break,
                Ok(Event::Start(e) | Event::Empty(e))
                    if e.local_name().as_ref() == "Relationship" =>
                {
                    let kind = attribute(&e, "Type").map_err(|m| at(&r, m))?;
                    if kind.as_deref() == Some(MODEL_RELATIONSHIP) {
                        let target =
                            attribute(&e, "Target")
                                .map_err(|m| at(&r, m))?
                                .ok_or_else(|| {
                                    at(&r, "the 3D model relationship has no Target".into())
                                })?;
                        return Ok(part_name(&target));
                    }
                }
                Ok(_) => {}
            }
        }
        Err(self.bad("_rels/.rels names no 3D model part (a relationship of type …/3dmanufacturing/2013/01/3dmodel)"))
    }

    /// Reads and parses a model part, once.
    fn load(&mut self, part: &str) -> Result<(), IoError> {
        if self.parts.contains_key(part) {
            return Ok(());
        }
        let Some(xml) = self.read_part(part)? else {
            let names: Vec<String> = self
                .zip
                .file_names()
                .filter_map(Result::ok)
                .map(|n| n.into_owned())
                .take(8)
                .collect();
            return Err(self.bad(format!(
                "the ZIP archive has no model part {part} (it holds: {})",
                if names.is_empty() {
                    "nothing".to_owned()
                } else {
                    names.join(", ")
                }
            )));
        };
        let model = parse_model(&xml, part, self.source)?;
        self.parts.insert(part.to_owned(), model);
        Ok(())
    }

    /// Appends object `r.object` of `part` and its components, placed by
    /// `world`. `stack` holds the objects being placed, to catch cycles.
    fn place(
        &mut self,
        part: &str,
        r: &Ref,
        world: DMat4,
        stack: &mut Vec<(String, u64)>,
    ) -> Result<(), IoError> {
        self.load(part)?;
        let key = (part.to_owned(), r.object);
        if stack.contains(&key) {
            return Err(self.bad(format!(
                "{part}:{}: object {} contains itself through its components",
                r.line, r.object
            )));
        }
        if stack.len() >= MAX_DEPTH {
            return Err(self.bad(format!(
                "{part}:{}: components nest more than {MAX_DEPTH} levels deep",
                r.line
            )));
        }
        let Some(object) = self.parts.get(part).and_then(|m| m.objects.get(&r.object)) else {
            return Err(self.bad(format!(
                "{part}:{}: object {} does not exist",
                r.line, r.object
            )));
        };
        if let Some(mesh) = &object.mesh {
            let out = &mut self.mesh;
            if out.positions.len()
                + out.face_indices.len()
                + mesh.positions.len()
                + 3 * mesh.triangles.len()
                > crate::MAX_ELEMENTS
            {
                return Err(IoError::content(
                    self.source,
                    format!(
                        "{part}:{}: the build's objects, placed by its items and components, hold more than {} vertices and corners",
                        r.line,
                        crate::MAX_ELEMENTS
                    ),
                ));
            }
            // Below MAX_ELEMENTS, so u32 holds it.
            let base = out.positions.len() as u32;
            if world == DMat4::IDENTITY {
                out.positions.extend_from_slice(&mesh.positions);
            } else {
                out.positions
                    .extend(mesh.positions.iter().map(|&p| world.transform_point3(p)));
                if let Some(v) = out.positions[base as usize..]
                    .iter()
                    .position(|p| !p.is_finite())
                {
                    return Err(IoError::content(
                        self.source,
                        format!(
                            "{part}:{}: vertex {v} of object {} is not finite once transformed",
                            r.line, r.object
                        ),
                    ));
                }
            }
            let mirror = DMat3::from_mat4(world).determinant() < 0.0;
            for t in &mesh.triangles {
                let t = if mirror { [t[0], t[2], t[1]] } else { *t };
                out.face_indices.extend(t.map(|i| base + i));
                out.face_offsets.push(out.face_indices.len() as u32);
            }
        }
        let components = object.components.clone();
        stack.push(key);
        for c in &components {
            let target = c.part.clone().unwrap_or_else(|| part.to_owned());
            self.place(&target, c, world * c.transform, stack)?;
        }
        stack.pop();
        Ok(())
    }
}

/// The value of the unprefixed attribute `name`, unescaped.
fn attribute<'e>(e: &'e BytesStart<'_>, name: &str) -> Result<Option<Cow<'e, str>>, String> {
    for a in e.attributes() {
        let a = a.map_err(|e| format!("bad attribute: {e}"))?;
        if a.key.as_ref() == name {
            return a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map(Some)
                .map_err(|e| format!("bad value of {name}: {e}"));
        }
    }
    Ok(None)
}

fn required<'e>(e: &'e BytesStart<'_>, name: &str, what: &str) -> Result<Cow<'e, str>, String> {
    attribute(e, name)?.ok_or_else(|| format!("<{what}> has no {name} attribute"))
}

fn number(e: &BytesStart<'_>, name: &str, what: &str) -> Result<f64, String> {
    let v = required(e, name, what)?;
    parse_finite(v.as_bytes()).map_err(|m| format!("<{what}> {name}: {m}"))
}

fn id(e: &BytesStart<'_>, name: &str, what: &str) -> Result<u64, String> {
    let v = required(e, name, what)?;
    parse_u64(v.as_bytes()).ok_or_else(|| {
        format!(
            "<{what}> {name}=\"{}\" is not a non-negative integer",
            show(v.as_bytes())
        )
    })
}

/// A `transform` attribute: twelve numbers, the columns of glam's affine
/// matrix in order (3MF multiplies row vectors from the left).
fn transform(e: &BytesStart<'_>, what: &str) -> Result<DMat4, String> {
    let Some(v) = attribute(e, "transform")? else {
        return Ok(DMat4::IDENTITY);
    };
    let mut m = [0.0; 12];
    let mut n = 0;
    for tok in v.split_ascii_whitespace() {
        let slot = m
            .get_mut(n)
            .ok_or_else(|| format!("<{what}> transform has more than 12 numbers"))?;
        *slot = parse_finite(tok.as_bytes()).map_err(|e| format!("<{what}> transform: {e}"))?;
        n += 1;
    }
    if n != 12 {
        return Err(format!("<{what}> transform has {n} numbers, not 12"));
    }
    Ok(DMat4::from_cols(
        glam::DVec4::new(m[0], m[1], m[2], 0.0),
        glam::DVec4::new(m[3], m[4], m[5], 0.0),
        glam::DVec4::new(m[6], m[7], m[8], 0.0),
        glam::DVec4::new(m[9], m[10], m[11], 1.0),
    ))
}

/// Where the parser is in a model part.
#[derive(Clone, Copy, PartialEq)]
enum Ctx {
    Model,
    Resources,
    Object,
    Mesh,
    Vertices,
    Triangles,
    Components,
    Build,
    /// Inside an element holey does not read.
    Skip,
}

/// Parses one model part's XML.
fn parse_model(xml: &[u8], part: &str, source: &str) -> Result<Model, IoError> {
    let xml = xml.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(xml);
    let mut r = NsReader::from_reader(xml);
    let mut model = Model::default();
    let mut stack: Vec<Ctx> = Vec::new();
    let mut current: Option<u64> = None;
    let mut seen_root = false;
    // The line of byte `line_pos`, advanced as the reader goes (counting
    // from the start for every element would be quadratic).
    let (mut line, mut line_pos) = (1, 0);
    loop {
        let start = r.buffer_position();
        let at = |pos: u64, m: &dyn std::fmt::Display| {
            IoError::content(source, format!("{part}:{}: {m}", line_at(xml, pos)))
        };
        let (ns, event) = match r.read_resolved_event() {
            Ok(x) => x,
            Err(e) => return Err(at(r.error_position(), &format!("bad XML: {e}"))),
        };
        let core = match ns {
            ResolveResult::Unbound => true,
            ResolveResult::Bound(Namespace(n)) => n == CORE_NS,
            ResolveResult::Unknown(_) => false,
        };
        let (e, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                if let Some(Ctx::Object) = stack.pop() {
                    current = None;
                }
                continue;
            }
            Event::Eof => {
                if !stack.is_empty() {
                    return Err(at(start, &"the XML ends before its elements are closed"));
                }
                if !seen_root {
                    return Err(at(start, &"no <model> element"));
                }
                return Ok(model);
            }
            _ => continue,
        };
        let here = (start as usize).min(xml.len());
        line += xml[line_pos.min(here)..here]
            .iter()
            .filter(|&&c| c == b'\n')
            .count();
        line_pos = here;
        let fail = |m: String| IoError::content(source, format!("{part}:{line}: {m}"));
        let name = e.local_name();
        let name = if core { name.as_ref() } else { "" };
        let parent = stack.last().copied();
        let next = match (parent, name) {
            (None, "model") if !seen_root => {
                seen_root = true;
                Ctx::Model
            }
            (None, _) => {
                return Err(fail(format!(
                    "the root element is <{}>, not a 3MF <model>",
                    show(e.name().as_ref().as_bytes())
                )));
            }
            (Some(Ctx::Model), "resources") => Ctx::Resources,
            (Some(Ctx::Model), "build") => Ctx::Build,
            (Some(Ctx::Resources), "object") => {
                let oid = id(&e, "id", "object").map_err(fail)?;
                if model.objects.insert(oid, Object::default()).is_some() {
                    return Err(fail(format!("object id {oid} is defined twice")));
                }
                current = Some(oid);
                Ctx::Object
            }
            (Some(Ctx::Object), "mesh") => {
                if let Some(o) = current.and_then(|c| model.objects.get_mut(&c)) {
                    o.mesh = Some(ObjectMesh::default());
                }
                Ctx::Mesh
            }
            (Some(Ctx::Object), "components") => Ctx::Components,
            (Some(Ctx::Mesh), "vertices") => Ctx::Vertices,
            (Some(Ctx::Mesh), "triangles") => Ctx::Triangles,
            (Some(Ctx::Vertices), "vertex") => {
                let p = DVec3::new(
                    number(&e, "x", "vertex").map_err(fail)?,
                    number(&e, "y", "vertex").map_err(fail)?,
                    number(&e, "z", "vertex").map_err(fail)?,
                );
                if let Some(m) = current
                    .and_then(|c| model.objects.get_mut(&c))
                    .and_then(|o| o.mesh.as_mut())
                {
                    m.positions.push(p);
                }
                Ctx::Skip
            }
            (Some(Ctx::Triangles), "triangle") => {
                let mut t = [0u32; 3];
                let mesh = current
                    .and_then(|c| model.objects.get_mut(&c))
                    .and_then(|o| o.mesh.as_mut());
                let count = mesh.as_ref().map_or(0, |m| m.positions.len());
                for (slot, key) in t.iter_mut().zip(["v1", "v2", "v3"]) {
                    let v = id(&e, key, "triangle").map_err(fail)?;
                    if v >= count as u64 {
                        return Err(fail(format!(
                            "<triangle> {key}=\"{v}\" refers to a vertex the mesh does not have (it has {count})"
                        )));
                    }
                    // Below `count`, a Vec length of u32-sized... checked below.
                    *slot =
                        u32::try_from(v).map_err(|_| fail("vertex index beyond 32 bits".into()))?;
                }
                if let Some(m) = mesh {
                    m.triangles.push(t);
                }
                Ctx::Skip
            }
            (Some(Ctx::Components), "component") | (Some(Ctx::Build), "item") => {
                let what = if parent == Some(Ctx::Build) {
                    "item"
                } else {
                    "component"
                };
                let mut path = None;
                for a in e.attributes() {
                    let a = a.map_err(|err| fail(format!("bad attribute: {err}")))?;
                    let (ans, local) = r.resolver().resolve_attribute(a.key);
                    if local.as_ref() == "path"
                        && matches!(ans, ResolveResult::Bound(Namespace(n)) if n == PRODUCTION_NS)
                    {
                        let v = a
                            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                            .map_err(|err| fail(format!("bad p:path: {err}")))?;
                        path = Some(part_name(&v));
                    }
                }
                let reference = Ref {
                    object: id(&e, "objectid", what).map_err(fail)?,
                    part: path,
                    transform: transform(&e, what).map_err(fail)?,
                    line,
                };
                if what == "item" {
                    model.build.push(reference);
                } else if let Some(o) = current.and_then(|c| model.objects.get_mut(&c)) {
                    o.components.push(reference);
                }
                Ctx::Skip
            }
            _ => Ctx::Skip,
        };
        if !empty {
            stack.push(next);
        } else if next == Ctx::Object {
            current = None;
        }
    }
}

// ---- writing ----------------------------------------------------------------

const CONTENT_TYPES: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"#;

const RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"#;

/// The model part's XML for a mesh.
fn model_xml(mesh: &PolyMesh) -> Result<Vec<u8>, String> {
    let (tris, _) = mesh.fan_triangles();
    let mut x = Vec::with_capacity(64 * mesh.positions.len() + 48 * tris.len() + 512);
    x.extend_from_slice(
        b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
          <model unit=\"millimeter\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n\
          <metadata name=\"Application\">holey</metadata>\n\
          <resources>\n<object id=\"1\" type=\"model\">\n<mesh>\n<vertices>\n",
    );
    NonFinite::check("vertex", &mesh.positions).map_err(|e| e.to_string())?;
    for p in &mesh.positions {
        for (k, c) in [b"<vertex x=\"" as &[u8], b"\" y=\"", b"\" z=\""]
            .iter()
            .zip(p.to_array())
        {
            x.extend_from_slice(k);
            push_f64(&mut x, c);
        }
        x.extend_from_slice(b"\"/>\n");
    }
    x.extend_from_slice(b"</vertices>\n<triangles>\n");
    for t in &tris {
        for (k, i) in [b"<triangle v1=\"" as &[u8], b"\" v2=\"", b"\" v3=\""]
            .iter()
            .zip(t)
        {
            x.extend_from_slice(k);
            push_u64(&mut x, u64::from(*i));
        }
        x.extend_from_slice(b"\"/>\n");
    }
    x.extend_from_slice(
        b"</triangles>\n</mesh>\n</object>\n</resources>\n\
          <build>\n<item objectid=\"1\"/>\n</build>\n</model>\n",
    );
    Ok(x)
}

/// The mesh as a 3MF package. The error says why the mesh cannot be
/// written.
pub fn encode(mesh: &PolyMesh) -> Result<Vec<u8>, String> {
    let xml = model_xml(mesh)?;
    let zip_err = |e: zip::result::ZipError| format!("cannot build the ZIP package: {e}");
    let io_err = |e: io::Error| format!("cannot build the ZIP package: {e}");
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::with_capacity(xml.len() / 4 + 1024)));
    let opts = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("[Content_Types].xml", opts)
        .map_err(zip_err)?;
    zip.write_all(CONTENT_TYPES.as_bytes()).map_err(io_err)?;
    zip.start_file("_rels/.rels", opts).map_err(zip_err)?;
    zip.write_all(RELS.as_bytes()).map_err(io_err)?;
    zip.start_file(
        DEFAULT_PART,
        opts.large_file(xml.len() as u64 >= u64::from(u32::MAX)),
    )
    .map_err(zip_err)?;
    zip.write_all(&xml).map_err(io_err)?;
    Ok(zip.finish().map_err(zip_err)?.into_inner())
}

/// Writes the mesh as 3MF (see the module docs). A mesh that cannot be
/// written is an [`io::ErrorKind::InvalidInput`] error.
pub fn write<W: Write>(w: W, mesh: &PolyMesh) -> io::Result<()> {
    crate::write_encoded(w, encode(mesh))
}

#[cfg(test)]
mod tests {
    // Test helpers may unwrap: a panic is a failed test.
    #![allow(clippy::unwrap_used)]

    use std::fs;

    use super::*;
    use crate::{MeshFile, WriteOptions, face_lists, read_path, write_poly};

    fn bits(m: &PolyMesh) -> Vec<[u64; 3]> {
        m.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    }

    /// A ZIP of the given parts, as a 3MF producer would make it.
    fn package(parts: &[(&str, &str)]) -> Vec<u8> {
        let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
        for (name, text) in parts {
            zip.start_file(*name, SimpleFileOptions::default()).unwrap();
            zip.write_all(text.as_bytes()).unwrap();
        }
        zip.finish().unwrap().into_inner()
    }

    /// A model part with `resources` and `build` inside <model>.
    fn model(resources: &str, build: &str) -> String {
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
             <model unit=\"millimeter\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" \
             xmlns:p=\"http://schemas.microsoft.com/3dmanufacturing/production/2015/06\">\n\
             <resources>\n{resources}\n</resources>\n<build>\n{build}\n</build>\n</model>\n"
        )
    }

    /// Object `id`: the unit tetrahedron's corners and two triangles.
    fn tetra_object(id: u32) -> String {
        format!(
            "<object id=\"{id}\" type=\"model\"><mesh><vertices>\n\
             <vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" y=\"0\" z=\"0\"/>\n\
             <vertex x=\"0\" y=\"1\" z=\"0\"/><vertex x=\"0\" y=\"0\" z=\"1\"/>\n\
             </vertices><triangles>\n\
             <triangle v1=\"0\" v2=\"1\" v3=\"2\"/><triangle v1=\"0\" v2=\"2\" v3=\"3\"/>\n\
             </triangles></mesh></object>"
        )
    }

    fn one_part(resources: &str, build: &str) -> Vec<u8> {
        package(&[
            ("_rels/.rels", RELS),
            (DEFAULT_PART, &model(resources, build)),
        ])
    }

    fn err(bytes: &[u8]) -> String {
        parse(bytes, "t.3mf").unwrap_err().to_string()
    }

    #[test]
    fn round_trip_is_exact_in_f64() {
        let positions = vec![
            DVec3::new(0.1 + 0.2, 1.0 / 3.0, -0.0),
            DVec3::new(f64::MAX, -f64::MIN_POSITIVE, 5e-324),
            DVec3::new(123_456_789.123_456_79, -2.5e-17, 1e300),
            DVec3::new(std::f64::consts::PI, 0.0, -7.0),
            DVec3::new(42.0, 42.0, 42.0),
        ];
        let m = PolyMesh::from_faces(positions, [&[0u32, 1, 2][..], &[0, 2, 3, 1]]);
        let back = parse(&encode(&m).unwrap(), "t.3mf").unwrap();
        assert_eq!(bits(&back), bits(&m), "every bit of every coordinate");
        assert_eq!(
            face_lists(&back),
            vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 1]]
        );
        // Through files; the package holds the parts a 3MF consumer looks for.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.3mf");
        write_poly(&path, &m, &WriteOptions::default()).unwrap();
        let MeshFile::Poly(again) = read_path(&path).unwrap() else {
            panic!("not a polygon mesh");
        };
        assert_eq!(again, back);
        let mut zip = ZipArchive::new(Cursor::new(fs::read(&path).unwrap())).unwrap();
        let mut names: Vec<_> = zip.file_names().map(|n| n.unwrap().into_owned()).collect();
        names.sort();
        assert_eq!(
            names,
            ["3D/3dmodel.model", "[Content_Types].xml", "_rels/.rels"]
        );
        let part = zip.by_name(DEFAULT_PART).unwrap();
        assert_eq!(part.compression(), zip::CompressionMethod::Deflated);
        // An empty mesh too.
        let empty = parse(&encode(&PolyMesh::new()).unwrap(), "e.3mf").unwrap();
        assert_eq!((empty.positions.len(), empty.face_count()), (0, 0));
    }

    #[test]
    fn build_items_and_components_are_placed() {
        // Object 1 is the tetrahedron; object 2 holds it twice, lifted by 5
        // and by 6; the build places object 1 scaled by 2 and moved by 10
        // along x, object 2 as it is, and object 1 mirrored in x. Object 3
        // is not built. Elements of other namespaces are skipped, even
        // where their names are core names.
        let resources = format!(
            "<m:basematerials xmlns:m=\"http://schemas.microsoft.com/3dmanufacturing/material/2015/02\" id=\"9\">\
             <m:base name=\"red\" displaycolor=\"#FF0000\"/></m:basematerials>\n\
             <s:slicestack xmlns:s=\"http://schemas.microsoft.com/3dmanufacturing/slice/2015/07\" id=\"8\">\
             <s:slice ztop=\"1\"><s:vertices><s:vertex x=\"5\" y=\"5\"/></s:vertices></s:slice></s:slicestack>\n\
             {}\n\
             <object id=\"2\" type=\"model\"><components>\
             <component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0 5\"/>\
             <component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0 6\"/>\
             </components></object>\n{}",
            tetra_object(1),
            tetra_object(3)
        );
        let build = "<item objectid=\"1\" transform=\"2 0 0 0 2 0 0 0 2 10 0 0\"/>\n\
                     <item objectid=\"2\"/>\n\
                     <item objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 0 0 0\"/>";
        let m = parse(&one_part(&resources, build), "t.3mf").unwrap();
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let mut want: Vec<DVec3> = corners.iter().map(|&p| 2.0 * p + 10.0 * DVec3::X).collect();
        want.extend(corners.iter().map(|&p| p + 5.0 * DVec3::Z));
        want.extend(corners.iter().map(|&p| p + 6.0 * DVec3::Z));
        want.extend(corners.iter().map(|&p| DVec3::new(-p.x, p.y, p.z)));
        assert_eq!(m.positions, want);
        let f = face_lists(&m);
        assert_eq!(f.len(), 8);
        assert_eq!(f[2..4], [vec![4, 5, 6], vec![4, 6, 7]]);
        // The mirrored copy is turned over, so it still faces outwards.
        assert_eq!(f[6..8], [vec![12, 14, 13], vec![12, 15, 14]]);
        // A rotation composes with its component's translation: the
        // component is moved first, then the item rotates (x → y).
        let resources = format!(
            "{}<object id=\"2\"><components><component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 3 0 0\"/></components></object>",
            tetra_object(1)
        );
        let m = parse(
            &one_part(
                &resources,
                "<item objectid=\"2\" transform=\"0 1 0 -1 0 0 0 0 1 0 0 0\"/>",
            ),
            "t.3mf",
        )
        .unwrap();
        assert_eq!(m.positions[0], DVec3::new(0.0, 3.0, 0.0));
        assert_eq!(m.positions[1], DVec3::new(0.0, 4.0, 0.0));
        assert_eq!(m.positions[2], DVec3::new(-1.0, 3.0, 0.0));
    }

    #[test]
    fn other_parts_and_packages_without_relationships() {
        // The production extension: the build's object is in another part.
        let root = model(
            "<object id=\"5\"><components><component objectid=\"1\" p:path=\"/3D/Objects/tetra.model\" transform=\"1 0 0 0 1 0 0 0 1 0 7 0\"/></components></object>",
            "<item objectid=\"5\"/>",
        );
        let other = model(&tetra_object(1), "");
        let rels = RELS.replace("/3D/3dmodel.model", "/3D/main.model");
        let bytes = package(&[
            ("_rels/.rels", &rels),
            ("3D/main.model", &root),
            ("3D/Objects/tetra.model", &other),
        ]);
        let m = parse(&bytes, "t.3mf").unwrap();
        assert_eq!(m.positions[2], DVec3::new(0.0, 8.0, 0.0));
        assert_eq!(m.face_count(), 2);
        // Without _rels/.rels, the usual part name.
        let bytes = package(&[(
            DEFAULT_PART,
            &model(&tetra_object(1), "<item objectid=\"1\"/>"),
        )]);
        assert_eq!(parse(&bytes, "t.3mf").unwrap().face_count(), 2);
    }

    #[test]
    fn malformed_packages_are_clear_errors() {
        let good = one_part(&tetra_object(1), "<item objectid=\"1\"/>");
        assert!(parse(&good, "t.3mf").is_ok());
        for len in 0..good.len() {
            assert!(parse(&good[..len], "t.3mf").is_err(), "{len}");
        }
        // Damage inside the compressed model part: an error, not a panic.
        let mut damaged = encode(&PolyMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            [[0u32, 1, 2]],
        ))
        .unwrap();
        let at = damaged
            .windows(16)
            .position(|w| w.starts_with(b"3D/3dmodel.model"))
            .unwrap()
            + 30;
        for b in &mut damaged[at..at + 40] {
            *b ^= 0x5a;
        }
        let e = err(&damaged);
        assert!(
            e.starts_with("t.3mf: part 3D/3dmodel.model cannot be read"),
            "{e}"
        );
        assert!(
            err(b"PK\x03\x04 not really")
                .starts_with("t.3mf: not a 3MF file: not a readable ZIP archive")
        );
        assert!(err(b"solid x\nendsolid x\n").contains("not a readable ZIP archive"));
        let e = err(&package(&[
            ("[Content_Types].xml", CONTENT_TYPES),
            ("docs/readme.txt", "hi"),
        ]));
        assert_eq!(
            e,
            "t.3mf: the ZIP archive has no model part 3D/3dmodel.model (it holds: [Content_Types].xml, docs/readme.txt)"
        );
        let e = err(&package(&[(
            "_rels/.rels",
            "<Relationships><Relationship Type=\"other\" Target=\"/x\"/></Relationships>",
        )]));
        assert!(e.contains("_rels/.rels names no 3D model part"), "{e}");
        // The model's XML and content, each error naming the part and line.
        let cases: &[(String, &str)] = &[
            (
                model(&tetra_object(1), "<item objectid=\"1\">").replace("</build>", "</built>"),
                "3D/3dmodel.model:13: bad XML: ill-formed document: expected `</item>`, but `</built>` was found",
            ),
            (
                "<?xml version=\"1.0\"?>\n<modle/>".into(),
                "3D/3dmodel.model:2: the root element is <modle>, not a 3MF <model>",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>")
                    .replace("<vertex x=\"1\" y=\"0\"", "<vertex x=\"1\""),
                "3D/3dmodel.model:5: <vertex> has no y attribute",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>").replace("x=\"1\"", "x=\"1,5\""),
                "3D/3dmodel.model:5: <vertex> x: bad number \"1,5\"",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>").replace("x=\"1\"", "x=\"NaN\""),
                "3D/3dmodel.model:5: <vertex> x: coordinate \"NaN\" is not a finite number",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>").replace("v3=\"3\"", "v3=\"4\""),
                "3D/3dmodel.model:8: <triangle> v3=\"4\" refers to a vertex the mesh does not have (it has 4)",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>")
                    .replace("v1=\"0\" v2=\"1\"", "v1=\"-1\" v2=\"1\""),
                "3D/3dmodel.model:8: <triangle> v1=\"-1\" is not a non-negative integer",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"9\"/>"),
                "3D/3dmodel.model:12: object 9 does not exist",
            ),
            (
                model(&format!("{}{}", tetra_object(1), tetra_object(1)), ""),
                "3D/3dmodel.model:9: object id 1 is defined twice",
            ),
            (
                model(
                    &tetra_object(1),
                    "<item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0\"/>",
                ),
                "3D/3dmodel.model:12: <item> transform has 11 numbers, not 12",
            ),
            (
                model(
                    "<object id=\"1\"><components><component objectid=\"2\"/></components></object>\n\
                     <object id=\"2\"><components><component objectid=\"1\"/></components></object>",
                    "<item objectid=\"1\"/>",
                ),
                "3D/3dmodel.model:5: object 1 contains itself through its components",
            ),
            (
                model(&tetra_object(1), "<item objectid=\"1\"/>").replace("</model>\n", ""),
                "3D/3dmodel.model:14: the XML ends before its elements are closed",
            ),
            (
                model(
                    "<object id=\"1\"><components><component objectid=\"1\" p:path=\"/3D/missing.model\"/></components></object>",
                    "<item objectid=\"1\"/>",
                ),
                "the ZIP archive has no model part 3D/missing.model",
            ),
        ];
        for (xml, want) in cases {
            let e = parse(&package(&[(DEFAULT_PART, xml)]), "t.3mf").unwrap_err();
            assert!(e.is_bad_input());
            assert!(
                e.to_string().starts_with(&format!("t.3mf: {want}")),
                "want {want:?}\n got {e}"
            );
        }
    }

    /// The ZIP's checksums stop damaged bytes before they reach the XML,
    /// so the model parser is fed mutated XML directly: errors, never a
    /// panic, and some mutations still parse.
    #[test]
    fn mutated_model_xml_never_panics() {
        let resources = format!(
            "{}<object id=\"2\"><components><component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0 5\"/></components></object>",
            tetra_object(1)
        );
        let seed = model(&resources, "<item objectid=\"2\"/><item objectid=\"1\"/>").into_bytes();
        let tokens: &[&[u8]] = &[
            b"<",
            b">",
            b"/>",
            b"\"",
            b"&amp;",
            b"&bogus;",
            b"<![CDATA[x]]>",
            b"<!--",
            b"-1",
            b"4294967296",
            b"1e999",
            b"nan",
            b"<vertex x=\"1\" y=\"2\" z=\"3\"/>",
            b"<triangle v1=\"0\" v2=\"0\" v3=\"9\"/>",
            b"<object id=\"1\">",
            b"</mesh>",
            b"xmlns:q=\"urn:x\"",
            b"\xff\xfe",
            b"\0",
        ];
        let mut rng = holey_testkit::Rng::new(0x3_3f);
        let mut outcomes = [0usize; 2];
        for _ in 0..3000 {
            let mut b = seed.clone();
            for _ in 0..=rng.below(3) {
                let n = b.len();
                match rng.below(4) {
                    0 if n > 0 => {
                        let i = rng.below(n);
                        b[i] = rng.below(256) as u8;
                    }
                    1 => {
                        let i = rng.below(n + 1);
                        b.splice(i..i, rng.pick(tokens).iter().copied());
                    }
                    2 if n > 0 => {
                        let i = rng.below(n);
                        let len = rng.below(n - i).min(40) + 1;
                        b.drain(i..i + len);
                    }
                    _ => b.truncate(rng.below(n + 1)),
                }
            }
            let r = parse_model(&b, DEFAULT_PART, "fuzz");
            outcomes[usize::from(r.is_ok())] += 1;
            if let Err(e) = r {
                assert!(e.to_string().starts_with("fuzz: 3D/3dmodel.model:"), "{e}");
            }
        }
        assert!(outcomes[0] > 100 && outcomes[1] > 100, "{outcomes:?}");
    }

    #[test]
    fn a_refused_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.3mf");
        let mut m = PolyMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], [[0u32, 1, 2]]);
        m.positions[1].y = f64::INFINITY;
        let e = write_poly(&path, &m, &WriteOptions::default()).unwrap_err();
        assert!(e.is_bad_input());
        assert!(
            e.to_string()
                .contains("vertex 1 has a non-finite coordinate"),
            "{e}"
        );
        assert_eq!(
            encode(&m).unwrap_err(),
            "vertex 1 has a non-finite coordinate (1, inf, 0)"
        );
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
