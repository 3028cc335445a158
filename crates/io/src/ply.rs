//! Stanford PLY, ascii and binary (little- and big-endian).
//!
//! Read: the header (`ply`, `format`, `comment`, `obj_info`, `element`,
//! `property`, `end_header`) and then every element in order. From the
//! `vertex` element the scalar properties `x`, `y`, `z` are read, whatever
//! their type (`char uchar short ushort int uint float double`, or the
//! names `int8 uint8 int16 uint16 int32 uint32 float32 float64`); other
//! vertex properties are skipped. From the `face` element the list
//! property `vertex_indices` (or `vertex_index`) is read, with any count
//! and index types; other properties, lists included, are skipped. Any
//! other element is skipped. In ascii files every element instance is one
//! line. Faces need at least 3 corners. Data after the last element is
//! ignored. Errors name the header or data line (ascii) or the byte
//! offset from the start of the file (binary).
//!
//! Write: binary little-endian (or ascii), `double` coordinates so a round
//! trip is exact, optional `uchar red green blue` per vertex, and faces as
//! `list uchar int vertex_indices` (`uint` counts for faces of more than
//! 255 corners, `uint` indices past 2³¹ vertices).

use std::io::{self, Write};

use holey_mesh::{DVec3, PolyMesh};

use crate::IoError;
use crate::error::show;
use crate::text::{Cursor, parse_f64, parse_i64, push_f64, push_face_end, push_u64};

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    /// Header line of the `element` statement, for messages.
    line: usize,
    props: Vec<Property>,
}

impl Element {
    /// Bytes per instance in binary, if every property is a scalar.
    fn fixed_size(&self) -> Option<usize> {
        self.props.iter().try_fold(0usize, |acc, p| match p.kind {
            Kind::Scalar(s) => Some(acc + s.size()),
            Kind::List { .. } => None,
        })
    }

    /// The fewest bytes an instance can take in binary.
    fn min_size(&self) -> usize {
        self.props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(s) => s.size(),
                Kind::List { count, .. } => count.size(),
            })
            .sum()
    }

    /// Singular noun for messages ("vertex 3 of 8").
    fn noun(&self) -> String {
        match self.name.as_str() {
            "vertex" | "face" => self.name.clone(),
            other => format!("element \"{other}\""),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the first data byte.
    data_start: usize,
    /// Line number of the first data line (ascii).
    data_line: usize,
}

fn parse_header(bytes: &[u8], source: &str) -> Result<Header, IoError> {
    let mut c = Cursor::new(bytes, false, false);
    if c.token() != Some(b"ply") || c.token().is_some() {
        return Err(IoError::line(
            source,
            1,
            "not a PLY file (the first line must be \"ply\")",
        ));
    }
    c.next_line();
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if c.eof() {
            return Err(IoError::line(
                source,
                c.line(),
                "the header has no end_header line",
            ));
        }
        let line = c.line();
        let bad = |m: String| Err(IoError::line(source, line, m));
        let Some(keyword) = c.token() else {
            c.next_line();
            continue;
        };
        match keyword {
            b"comment" | b"obj_info" => {}
            b"format" => {
                let e = match c.token() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::LittleEndian,
                    Some(b"binary_big_endian") => Encoding::BigEndian,
                    other => {
                        return bad(format!("unknown format \"{}\"", show(other.unwrap_or(b""))));
                    }
                };
                match c.token() {
                    Some(b"1.0") | Some(b"1") => {}
                    other => {
                        return bad(format!(
                            "unsupported PLY version \"{}\"",
                            show(other.unwrap_or(b""))
                        ));
                    }
                }
                if encoding.is_some() {
                    return bad("a second format line".into());
                }
                encoding = Some(e);
            }
            b"element" => {
                let (Some(name), Some(count)) = (c.token(), c.token()) else {
                    return bad("an element line needs a name and a count".into());
                };
                let Some(count) = crate::text::parse_u64(count) else {
                    return bad(format!("bad element count \"{}\"", show(count)));
                };
                elements.push(Element {
                    name: String::from_utf8_lossy(name).into_owned(),
                    count,
                    props: Vec::new(),
                    line,
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return bad("a property line before any element line".into());
                };
                let scalar = |tok: Option<&[u8]>| -> Result<Scalar, IoError> {
                    let tok = tok.unwrap_or(b"");
                    Scalar::from_name(tok).ok_or_else(|| {
                        IoError::line(
                            source,
                            line,
                            format!("unknown property type \"{}\"", show(tok)),
                        )
                    })
                };
                let first = c.token();
                let kind = if first == Some(b"list") {
                    let count = scalar(c.token())?;
                    if count.is_float() {
                        return bad("a list count must have an integer type".into());
                    }
                    Kind::List {
                        count,
                        item: scalar(c.token())?,
                    }
                } else {
                    Kind::Scalar(scalar(first)?)
                };
                let Some(name) = c.token() else {
                    return bad("a property line needs a name".into());
                };
                element.props.push(Property {
                    name: String::from_utf8_lossy(name).into_owned(),
                    kind,
                });
            }
            b"end_header" => {
                c.next_line();
                let Some(encoding) = encoding else {
                    return bad("the header has no format line".into());
                };
                return Ok(Header {
                    encoding,
                    elements,
                    data_start: c.pos(),
                    data_line: c.line(),
                });
            }
            other => return bad(format!("unknown header line \"{}\"", show(other))),
        }
        c.next_line();
    }
}

/// Where the data of the elements this reader keeps sits.
struct Layout {
    vertex: Option<usize>,
    xyz: [usize; 3],
    face: Option<usize>,
    indices: usize,
    vertex_count: u32,
}

fn layout(h: &Header, source: &str) -> Result<Layout, IoError> {
    let header_err = |line: usize, m: String| IoError::line(source, line, m);
    let vertex = h.elements.iter().position(|e| e.name == "vertex");
    let mut xyz = [0; 3];
    let mut vertex_count = 0;
    if let Some(v) = vertex {
        let e = &h.elements[v];
        for (slot, axis) in xyz.iter_mut().zip(["x", "y", "z"]) {
            *slot = e
                .props
                .iter()
                .position(|p| p.name == axis && matches!(p.kind, Kind::Scalar(_)))
                .ok_or_else(|| {
                    header_err(
                        e.line,
                        format!("the vertex element has no scalar property \"{axis}\""),
                    )
                })?;
        }
        vertex_count = u32::try_from(e.count)
            .ok()
            .filter(|&n| n < u32::MAX)
            .ok_or_else(|| {
                header_err(
                    e.line,
                    format!("{} vertices exceed 32-bit indices", e.count),
                )
            })?;
    }
    let face = h.elements.iter().position(|e| e.name == "face");
    let mut indices = 0;
    if let Some(f) = face {
        let e = &h.elements[f];
        indices = e
            .props
            .iter()
            .position(|p| {
                (p.name == "vertex_indices" || p.name == "vertex_index")
                    && matches!(p.kind, Kind::List { .. })
            })
            .ok_or_else(|| {
                header_err(
                    e.line,
                    "the face element has no list property \"vertex_indices\"".into(),
                )
            })?;
        if e.count > 0 && vertex.is_none() {
            return Err(header_err(e.line, "faces but no vertex element".into()));
        }
    }
    Ok(Layout {
        vertex,
        xyz,
        face,
        indices,
        vertex_count,
    })
}

/// Parses a PLY file (any of the three encodings). `source` names the file
/// in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    let h = parse_header(bytes, source)?;
    let l = layout(&h, source)?;
    let mut out = Out {
        positions: Vec::new(),
        offsets: vec![0],
        indices: Vec::new(),
    };
    let rest = bytes.len() - h.data_start;
    if let Some(v) = l.vertex {
        // Capped by what the file could hold, never by the declared count.
        let cap = (l.vertex_count as usize).min(rest / h.elements[v].min_size().max(2));
        out.positions.reserve(cap);
    }
    if let Some(f) = l.face {
        let cap = (h.elements[f].count.min(u64::from(u32::MAX)) as usize)
            .min(rest / h.elements[f].min_size().max(2));
        out.offsets.reserve(cap);
        out.indices.reserve(cap.saturating_mul(3));
    }
    match h.encoding {
        Encoding::Ascii => read_ascii(bytes, &h, &l, source, &mut out)?,
        Encoding::LittleEndian => read_binary(bytes, &h, &l, false, source, &mut out)?,
        Encoding::BigEndian => read_binary(bytes, &h, &l, true, source, &mut out)?,
    }
    Ok(PolyMesh {
        positions: out.positions,
        face_offsets: out.offsets,
        face_indices: out.indices,
    })
}

struct Out {
    positions: Vec<DVec3>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
}

impl Out {
    /// Closes the face whose corners were just pushed; `None` if it is too
    /// short or the corner count overflows 32 bits.
    fn close_face(&mut self, start: usize) -> Result<(), String> {
        let corners = self.indices.len() - start;
        if corners < 3 {
            return Err(format!(
                "has {corners} corner(s), but at least 3 are needed"
            ));
        }
        push_face_end(&mut self.offsets, &self.indices).map_err(String::from)
    }
}

/// Checks a vertex index read as a float (every PLY scalar fits exactly).
fn vertex_index(x: f64, vertex_count: u32) -> Result<u32, String> {
    if x >= 0.0 && x < f64::from(vertex_count) && x.fract() == 0.0 {
        Ok(x as u32)
    } else if x.fract() == 0.0 || !x.is_finite() {
        Err(format!(
            "refers to vertex {x}, but only {vertex_count} vertices are defined"
        ))
    } else {
        Err(format!("has a non-integer vertex index {x}"))
    }
}

fn read_ascii(
    bytes: &[u8],
    h: &Header,
    l: &Layout,
    source: &str,
    out: &mut Out,
) -> Result<(), IoError> {
    let mut c = Cursor::at(bytes, h.data_start, h.data_line, false);
    for (ei, e) in h.elements.iter().enumerate() {
        if e.props.is_empty() {
            // Instances with no properties have no text; do not loop over
            // a count that may be astronomically large.
            continue;
        }
        let keep_vertex = l.vertex == Some(ei);
        let keep_face = l.face == Some(ei);
        let noun = e.noun();
        for i in 0..e.count {
            c.skip_empty_lines();
            let line = c.line();
            let at = |m: String| {
                IoError::line(
                    source,
                    line,
                    format!("{noun} {} of {}: {m}", i + 1, e.count),
                )
            };
            if c.eof() {
                return Err(IoError::line(
                    source,
                    line,
                    format!(
                        "file ends after {i} of {} {noun} lines (the header declares more)",
                        e.count
                    ),
                ));
            }
            let mut xyz = [0.0; 3];
            let face_start = out.indices.len();
            for (pi, p) in e.props.iter().enumerate() {
                let mut value = |s: Scalar| -> Result<f64, IoError> {
                    let Some(tok) = c.token() else {
                        return Err(at(
                            "the line has fewer values than the header declares".into()
                        ));
                    };
                    let v = if s.is_float() {
                        parse_f64(tok)
                    } else {
                        parse_i64(tok).map(|i| i as f64)
                    };
                    v.ok_or_else(|| at(format!("bad number \"{}\"", show(tok))))
                };
                match p.kind {
                    Kind::Scalar(s) => {
                        let v = value(s)?;
                        if keep_vertex && let Some(axis) = l.xyz.iter().position(|&k| k == pi) {
                            if !v.is_finite() {
                                return Err(at(format!("coordinate {v} is not a finite number")));
                            }
                            xyz[axis] = v;
                        }
                    }
                    Kind::List { count, item } => {
                        let n = value(count)?;
                        if n < 0.0 {
                            return Err(at(format!("negative list length {n}")));
                        }
                        let keep = keep_face && pi == l.indices;
                        // Each item is a token of this line, so a huge
                        // declared length stops at the end of the line.
                        let mut k = 0.0;
                        while k < n {
                            let v = value(item)?;
                            if keep {
                                out.indices
                                    .push(vertex_index(v, l.vertex_count).map_err(at)?);
                            }
                            k += 1.0;
                        }
                    }
                }
            }
            if c.token().is_some() {
                return Err(at(
                    "the line has more values than the header declares".into()
                ));
            }
            if keep_vertex {
                out.positions.push(DVec3::from_array(xyz));
            }
            if keep_face {
                out.close_face(face_start).map_err(at)?;
            }
            c.next_line();
        }
    }
    Ok(())
}

/// Reads scalars from binary data, tracking the byte offset.
struct Bin<'a> {
    b: &'a [u8],
    pos: usize,
    big: bool,
}

impl Bin<'_> {
    #[inline]
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let end = self.pos.checked_add(N)?;
        let bytes: [u8; N] = self.b.get(self.pos..end)?.try_into().ok()?;
        self.pos = end;
        Some(if self.big {
            let mut r = bytes;
            r.reverse();
            r
        } else {
            bytes
        })
    }

    /// Reads one scalar as a float; every PLY scalar type converts exactly.
    #[inline]
    fn read(&mut self, s: Scalar) -> Option<f64> {
        Some(match s {
            Scalar::I8 => f64::from(i8::from_le_bytes(self.take::<1>()?)),
            Scalar::U8 => f64::from(u8::from_le_bytes(self.take::<1>()?)),
            Scalar::I16 => f64::from(i16::from_le_bytes(self.take::<2>()?)),
            Scalar::U16 => f64::from(u16::from_le_bytes(self.take::<2>()?)),
            Scalar::I32 => f64::from(i32::from_le_bytes(self.take::<4>()?)),
            Scalar::U32 => f64::from(u32::from_le_bytes(self.take::<4>()?)),
            Scalar::F32 => f64::from(f32::from_le_bytes(self.take::<4>()?)),
            Scalar::F64 => f64::from_le_bytes(self.take::<8>()?),
        })
    }

    fn skip(&mut self, n: usize) -> Option<()> {
        let end = self.pos.checked_add(n).filter(|&e| e <= self.b.len())?;
        self.pos = end;
        Some(())
    }
}

fn read_binary(
    bytes: &[u8],
    h: &Header,
    l: &Layout,
    big: bool,
    source: &str,
    out: &mut Out,
) -> Result<(), IoError> {
    let mut r = Bin {
        b: bytes,
        pos: h.data_start,
        big,
    };
    for (ei, e) in h.elements.iter().enumerate() {
        let keep_vertex = l.vertex == Some(ei);
        let keep_face = l.face == Some(ei);
        let noun = e.noun();
        let ends = |start: usize, i: u64| {
            IoError::byte(
                source,
                start,
                format!(
                    "file ends inside {noun} {} of {} (the header declares more data)",
                    i + 1,
                    e.count
                ),
            )
        };
        if !keep_vertex
            && !keep_face
            && let Some(size) = e.fixed_size()
        {
            // Skip the whole block at once.
            let rest = bytes.len() - r.pos;
            let need = u64::try_from(size)
                .ok()
                .and_then(|s| s.checked_mul(e.count));
            match need {
                Some(need) if need <= rest as u64 => r.pos += need as usize,
                _ => {
                    let whole = (rest / size.max(1)) as u64;
                    return Err(ends(r.pos + whole as usize * size, whole));
                }
            }
            continue;
        }
        for i in 0..e.count {
            let start = r.pos;
            let at = |pos: usize, m: String| {
                IoError::byte(source, pos, format!("{noun} {} of {}: {m}", i + 1, e.count))
            };
            let mut xyz = [0.0; 3];
            let face_start = out.indices.len();
            for (pi, p) in e.props.iter().enumerate() {
                match p.kind {
                    Kind::Scalar(s) => {
                        let value_at = r.pos;
                        let v = r.read(s).ok_or_else(|| ends(start, i))?;
                        if keep_vertex && let Some(axis) = l.xyz.iter().position(|&k| k == pi) {
                            if !v.is_finite() {
                                return Err(at(
                                    value_at,
                                    format!("coordinate {v} is not a finite number"),
                                ));
                            }
                            xyz[axis] = v;
                        }
                    }
                    Kind::List { count, item } => {
                        let n_at = r.pos;
                        let n = r.read(count).ok_or_else(|| ends(start, i))?;
                        if n < 0.0 {
                            return Err(at(n_at, format!("negative list length {n}")));
                        }
                        let n = n as u64; // integral: counts have integer types
                        if keep_face && pi == l.indices {
                            for _ in 0..n {
                                let value_at = r.pos;
                                let v = r.read(item).ok_or_else(|| ends(start, i))?;
                                out.indices.push(
                                    vertex_index(v, l.vertex_count).map_err(|m| at(value_at, m))?,
                                );
                            }
                        } else {
                            let len = n
                                .checked_mul(item.size() as u64)
                                .and_then(|x| usize::try_from(x).ok());
                            len.and_then(|len| r.skip(len))
                                .ok_or_else(|| ends(start, i))?;
                        }
                    }
                }
            }
            if keep_vertex {
                out.positions.push(DVec3::from_array(xyz));
            }
            if keep_face {
                out.close_face(face_start).map_err(|m| at(start, m))?;
            }
            if r.pos == start {
                // Zero-size instances (an element without properties): the
                // rest are the same nothing, and the count may be huge.
                break;
            }
        }
    }
    Ok(())
}

/// Writes `mesh` as PLY: binary little-endian, or ascii if `ascii`, with
/// `double` coordinates and, if given, one `uchar` RGB colour per vertex.
/// Faces are written as given, whatever their size. Fails with
/// [`io::ErrorKind::InvalidInput`] if the mesh is malformed or the colours
/// do not match the vertices.
pub fn write<W: Write>(
    mut w: W,
    mesh: &PolyMesh,
    ascii: bool,
    colors: Option<&[[u8; 3]]>,
) -> io::Result<()> {
    let invalid = crate::invalid_input;
    crate::check_poly(mesh).map_err(invalid)?;
    if let Some(colors) = colors
        && colors.len() != mesh.positions.len()
    {
        return Err(invalid(format!(
            "{} vertex colours for {} vertices",
            colors.len(),
            mesh.positions.len()
        )));
    }
    let wide_counts = mesh.faces().any(|f| f.len() > usize::from(u8::MAX));
    let wide_indices = mesh.positions.len() > i32::MAX as usize;
    let mut buf = Vec::with_capacity(crate::CHUNK + 256);
    buf.extend_from_slice(b"ply\nformat ");
    buf.extend_from_slice(if ascii {
        b"ascii"
    } else {
        b"binary_little_endian"
    });
    buf.extend_from_slice(b" 1.0\ncomment written by holey\nelement vertex ");
    push_u64(&mut buf, mesh.positions.len() as u64);
    buf.extend_from_slice(b"\nproperty double x\nproperty double y\nproperty double z\n");
    if colors.is_some() {
        buf.extend_from_slice(b"property uchar red\nproperty uchar green\nproperty uchar blue\n");
    }
    buf.extend_from_slice(b"element face ");
    push_u64(&mut buf, mesh.face_count() as u64);
    buf.extend_from_slice(b"\nproperty list ");
    buf.extend_from_slice(if wide_counts { b"uint " } else { b"uchar " });
    buf.extend_from_slice(if wide_indices { b"uint" } else { b"int" });
    buf.extend_from_slice(b" vertex_indices\nend_header\n");
    for (i, p) in mesh.positions.iter().enumerate() {
        let rgb = colors.map(|c| c[i]);
        if ascii {
            push_f64(&mut buf, p.x);
            buf.push(b' ');
            push_f64(&mut buf, p.y);
            buf.push(b' ');
            push_f64(&mut buf, p.z);
            if let Some(rgb) = rgb {
                for v in rgb {
                    buf.push(b' ');
                    push_u64(&mut buf, u64::from(v));
                }
            }
            buf.push(b'\n');
        } else {
            for v in p.to_array() {
                buf.extend_from_slice(&v.to_le_bytes());
            }
            if let Some(rgb) = rgb {
                buf.extend_from_slice(&rgb);
            }
        }
        crate::flush_full(&mut w, &mut buf)?;
    }
    for face in mesh.faces() {
        if ascii {
            push_u64(&mut buf, face.len() as u64);
            for &i in face {
                buf.push(b' ');
                push_u64(&mut buf, u64::from(i));
            }
            buf.push(b'\n');
        } else {
            if wide_counts {
                buf.extend_from_slice(&(face.len() as u32).to_le_bytes());
            } else {
                buf.push(face.len() as u8);
            }
            for &i in face {
                buf.extend_from_slice(&i.to_le_bytes());
            }
        }
        crate::flush_full(&mut w, &mut buf)?;
    }
    w.write_all(&buf)?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> PolyMesh {
        let positions = vec![
            DVec3::new(0.1, -0.0, 1.0 / 3.0),
            DVec3::new(1e-300, 1.5e300, -7.0),
            DVec3::new(2.0, 3.0, 4.0),
            DVec3::new(0.3, 0.2, 0.1),
        ];
        PolyMesh::from_faces(positions, [&[0u32, 1, 2][..], &[0, 2, 3, 1], &[3, 2, 1]])
    }

    fn err(bytes: &[u8]) -> String {
        parse(bytes, "m.ply").unwrap_err().to_string()
    }

    #[test]
    fn round_trips_ascii_and_binary_with_and_without_colours() {
        let m = sample();
        let colors = [[255u8, 0, 0], [0, 255, 0], [0, 0, 255], [1, 2, 3]];
        for ascii in [false, true] {
            for c in [None, Some(&colors[..])] {
                let mut out = Vec::new();
                write(&mut out, &m, ascii, c).unwrap();
                crate::assert_same_poly(&parse(&out, "rt.ply").unwrap(), &m);
            }
        }
        let mut out = Vec::new();
        write(&mut out, &m, true, Some(&colors)).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("property uchar red\n"), "{text}");
        assert!(text.contains("\n2 3 4 0 0 255\n"), "{text}");
        let mut out = Vec::new();
        let e = write(&mut out, &m, true, Some(&colors[..2])).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
    }

    #[test]
    fn wide_faces_use_uint_counts() {
        let n = 300u32;
        let positions = (0..n).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
        let m = PolyMesh::from_faces(positions, [(0..n).collect::<Vec<_>>()]);
        let mut out = Vec::new();
        write(&mut out, &m, false, None).unwrap();
        crate::assert_same_poly(&parse(&out, "w.ply").unwrap(), &m);
    }

    /// A hand-made big-endian file with other elements, other properties
    /// (lists too) and assorted scalar types.
    fn big_endian_file() -> Vec<u8> {
        let mut b = b"ply\r\nformat binary_big_endian 1.0\ncomment made by hand\nobj_info x\n\
element material 2\nproperty uchar r\nproperty float shine\n\
element vertex 4\nproperty int16 id\nproperty float x\nproperty double y\nproperty list uint8 int tags\nproperty int z\nproperty uchar alpha\n\
element face 2\nproperty list uchar uint vertex_indices\nproperty list ushort float texcoord\nproperty short flags\n\
element extra 1\nproperty list int uchar stuff\nend_header\n"
            .to_vec();
        for (r, s) in [(1u8, 0.5f32), (2, 1.5)] {
            b.push(r);
            b.extend_from_slice(&s.to_be_bytes());
        }
        let verts = [
            (0.0f32, 0.0f64, 0i32),
            (1.5, 0.0, 0),
            (0.0, -2.25, 0),
            (0.0, 0.0, 7),
        ];
        for (i, (x, y, z)) in verts.iter().enumerate() {
            b.extend_from_slice(&(i as i16).to_be_bytes());
            b.extend_from_slice(&x.to_be_bytes());
            b.extend_from_slice(&y.to_be_bytes());
            b.push(2);
            b.extend_from_slice(&9i32.to_be_bytes());
            b.extend_from_slice(&8i32.to_be_bytes());
            b.extend_from_slice(&z.to_be_bytes());
            b.push(200);
        }
        for face in [&[0u32, 2, 1][..], &[0, 1, 2, 3]] {
            b.push(face.len() as u8);
            for &i in face {
                b.extend_from_slice(&i.to_be_bytes());
            }
            b.extend_from_slice(&2u16.to_be_bytes());
            b.extend_from_slice(&0.25f32.to_be_bytes());
            b.extend_from_slice(&0.75f32.to_be_bytes());
            b.extend_from_slice(&(-1i16).to_be_bytes());
        }
        b.extend_from_slice(&3i32.to_be_bytes());
        b.extend_from_slice(&[1, 2, 3]);
        b
    }

    #[test]
    fn reads_big_endian_and_skips_what_it_does_not_need() {
        let m = parse(&big_endian_file(), "be.ply").unwrap();
        assert_eq!(
            m.positions,
            vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.5, 0.0, 0.0),
                DVec3::new(0.0, -2.25, 0.0),
                DVec3::new(0.0, 0.0, 7.0)
            ]
        );
        assert_eq!(m.face(0), &[0, 2, 1]);
        assert_eq!(m.face(1), &[0, 1, 2, 3]);
    }

    #[test]
    fn reads_ascii_with_other_elements() {
        let text = "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float32 x\nproperty float32 y\nproperty float32 z\nproperty uchar red\n\
                    element face 1\nproperty list uchar int vertex_index\nproperty list uchar float uv\n\
                    element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n\
                    0 0 0 1\n1 0 0 2\n\n0 1.5 0 3\n3 0 1 2 2 0.5 0.5\n0 1\n";
        let m = parse(text.as_bytes(), "a.ply").unwrap();
        assert_eq!(m.positions[2], DVec3::new(0.0, 1.5, 0.0));
        assert_eq!(m.face(0), &[0, 1, 2]);
    }

    #[test]
    fn header_errors() {
        assert_eq!(
            err(b"plx\n"),
            "m.ply:1: not a PLY file (the first line must be \"ply\")"
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nelement vertex 1\n"),
            "m.ply:4: the header has no end_header line"
        );
        assert_eq!(
            err(b"ply\nformat bcd 1.0\n"),
            "m.ply:2: unknown format \"bcd\""
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
            "m.ply:3: a property line before any element line"
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
            "m.ply:4: unknown property type \"quad\""
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nelement vertex x\nend_header\n"),
            "m.ply:3: bad element count \"x\""
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n"),
            "m.ply:3: the vertex element has no scalar property \"z\""
        );
        assert_eq!(
            err(b"ply\nelement vertex 0\nend_header\n"),
            "m.ply:3: the header has no format line"
        );
        assert_eq!(
            err(b"ply\nformat ascii 1.0\nfoo\nend_header\n"),
            "m.ply:3: unknown header line \"foo\""
        );
    }

    fn tri_header(format: &str, nv: usize, nf: usize) -> Vec<u8> {
        format!(
            "ply\nformat {format} 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n\
             element face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes()
    }

    #[test]
    fn ascii_data_errors_name_the_line() {
        let h = String::from_utf8(tri_header("ascii", 3, 1)).unwrap(); // 9 header lines
        let e = |data: &str| err(format!("{h}{data}").as_bytes());
        assert_eq!(
            e("0 0 0\n1 0 0\n0 x 0\n3 0 1 2\n"),
            "m.ply:12: vertex 3 of 3: bad number \"x\""
        );
        assert_eq!(
            e("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            "m.ply:13: face 1 of 1: refers to vertex 3, but only 3 vertices are defined"
        );
        assert_eq!(
            e("0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            "m.ply:13: face 1 of 1: has 2 corner(s), but at least 3 are needed"
        );
        assert_eq!(
            e("0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"),
            "m.ply:12: vertex 3 of 3: coordinate NaN is not a finite number"
        );
        // The header lies: it declares more vertices than the file has.
        let lying = String::from_utf8(tri_header("ascii", 4, 1)).unwrap();
        assert_eq!(
            err(format!("{lying}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").as_bytes()),
            "m.ply:13: vertex 4 of 4: the line has more values than the header declares"
        );
        assert_eq!(
            err(format!("{lying}0 0 0\n1 0 0\n0 1 0\n").as_bytes()),
            "m.ply:13: file ends after 3 of 4 vertex lines (the header declares more)"
        );
        assert_eq!(
            e("0 0 0 9\n"),
            "m.ply:10: vertex 1 of 3: the line has more values than the header declares"
        );
    }

    #[test]
    fn binary_data_errors_name_the_byte() {
        let m = PolyMesh::from_faces(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            [&[0u32, 1, 2][..], &[0, 1, 3]],
        );
        let mut good = Vec::new();
        write(&mut good, &m, false, None).unwrap();
        let header_len = good.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        // Truncated inside face 2 (vertices are 24 bytes each, faces 13).
        let cut = header_len + 4 * 24 + 13 + 5;
        assert_eq!(
            err(&good[..cut]),
            format!(
                "m.ply: byte {}: file ends inside face 2 of 2 (the header declares more data)",
                header_len + 4 * 24 + 13
            )
        );
        // Truncated inside vertex 3.
        assert_eq!(
            err(&good[..header_len + 2 * 24 + 3]),
            format!(
                "m.ply: byte {}: file ends inside vertex 3 of 4 (the header declares more data)",
                header_len + 2 * 24
            )
        );
        // The header lies about the face count.
        let text = String::from_utf8_lossy(&good).replace("element face 2", "element face 3");
        let lying: Vec<u8> = {
            let mut v = text.as_bytes()[..header_len].to_vec();
            v.extend_from_slice(&good[header_len..]);
            v
        };
        assert_eq!(
            err(&lying),
            format!(
                "m.ply: byte {}: file ends inside face 3 of 3 (the header declares more data)",
                header_len + 4 * 24 + 26
            )
        );
        // Out-of-range index and NaN.
        let mut bad = good.clone();
        let at = header_len + 4 * 24 + 13 + 1 + 8;
        bad[at..at + 4].copy_from_slice(&9i32.to_le_bytes());
        assert_eq!(
            err(&bad),
            format!(
                "m.ply: byte {at}: face 2 of 2: refers to vertex 9, but only 4 vertices are defined"
            )
        );
        let mut bad = good.clone();
        let at = header_len + 24 + 8;
        bad[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert_eq!(
            err(&bad),
            format!("m.ply: byte {at}: vertex 2 of 4: coordinate NaN is not a finite number")
        );
    }

    #[test]
    fn huge_counts_do_not_allocate_or_hang() {
        let mut b = b"ply\nformat binary_little_endian 1.0\nelement nothing 18446744073709551615\n\
element blob 18446744073709551615\nproperty double v\n\
element vertex 4294967294\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
            .to_vec();
        b.extend_from_slice(&[0; 64]);
        let e = err(&b);
        assert!(
            e.contains("file ends inside element \"blob\" 9 of 18446744073709551615"),
            "{e}"
        );
        let b = b"ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        assert_eq!(err(b), "m.ply:3: 4294967295 vertices exceed 32-bit indices");
        let mut b = tri_header("binary_little_endian", 0, 1);
        b.push(255);
        b.extend_from_slice(&[0; 8]);
        assert!(err(&b).contains("face 1 of 1"));
        let b = format!(
            "{}3 0 1 2\n",
            String::from_utf8(tri_header("ascii", 0, 4_000_000_000)).unwrap()
        );
        let e = err(b.as_bytes());
        assert!(e.contains("refers to vertex 0, but only 0 vertices"), "{e}");
    }
}
