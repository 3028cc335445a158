//! STL, binary and ascii.
//!
//! Read: a file is binary when its size is exactly `84 + 50·n` for the
//! triangle count `n` in its header, even if it starts with `solid` (many
//! binary writers put that word in the header). Otherwise it is ascii if it
//! starts with `solid` and its first kilobyte is text, and binary (with an
//! error for its wrong size) if not. Binary trailing bytes after the
//! declared triangles are an error too.
//!
//! Ascii: `solid [name]`, then facets `facet normal nx ny nz` / `outer
//! loop` / `vertex x y z` (three or more) / `endloop` / `endfacet`, and
//! `endsolid [name]`; keywords in any case, any whitespace, several solids
//! in one file. Normals are ignored (they are recomputed on writing).
//!
//! Vertices are welded only where their coordinates are bit-identical (for
//! binary files, the `f32` values), so a triangle soup stays a soup and a
//! welded solid stays welded. Faces keep file order, and vertices are
//! numbered in order of first appearance.
//!
//! Write: binary (the default; `f32` coordinates, so precision beyond
//! `f32` is lost) or ascii (`f64` shortest round-trip decimals, exact).
//! Polygons are fan-triangulated from their first corner, faces of fewer
//! than three corners are left out, and each triangle gets its unit normal
//! (zero for a degenerate triangle).

use std::collections::HashMap;
use std::io::{self, Write};

use holey_mesh::{DVec3, PolyMesh};

use crate::IoError;
use crate::error::show;
use crate::text::{Cursor, push_f64};

/// True if the bytes are a binary STL by the rule in the module docs.
pub fn is_binary(bytes: &[u8]) -> bool {
    if let Some(n) = bytes.get(80..84) {
        let n = u32::from_le_bytes([n[0], n[1], n[2], n[3]]);
        if 84 + 50 * u64::from(n) == bytes.len() as u64 {
            return true;
        }
    }
    let start = bytes
        .iter()
        .position(|c| !c.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let starts_solid = bytes
        .get(start..start + 5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    let head = &bytes[..bytes.len().min(1024)];
    let text = head.iter().all(|&c| {
        c == b'\t'
            || c == b'\n'
            || c == b'\r'
            || c == 0x0c
            || (0x20..0x7f).contains(&c)
            || c >= 0x80
    });
    !(starts_solid && text)
}

/// Parses an STL file, binary or ascii (see the module docs). `source`
/// names the file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    if is_binary(bytes) {
        parse_binary(bytes, source)
    } else {
        parse_ascii(bytes, source)
    }
}

/// Collects faces, welding bit-identical positions.
struct Welder {
    mesh: PolyMesh,
    index: HashMap<[u64; 3], u32>,
}

impl Welder {
    fn new(triangles: usize) -> Self {
        let mut mesh = PolyMesh::new();
        mesh.positions.reserve(triangles / 2);
        mesh.face_offsets.reserve(triangles + 1);
        mesh.face_indices.reserve(triangles * 3);
        Welder {
            mesh,
            index: HashMap::with_capacity(triangles / 2),
        }
    }

    fn vertex(&mut self, p: DVec3) -> Result<u32, String> {
        let key = p.to_array().map(f64::to_bits);
        let next = self.mesh.positions.len();
        match self.index.get(&key) {
            Some(&i) => Ok(i),
            None => {
                let i = u32::try_from(next)
                    .ok()
                    .filter(|&i| i < u32::MAX)
                    .ok_or("too many vertices for 32-bit indices")?;
                self.index.insert(key, i);
                self.mesh.positions.push(p);
                Ok(i)
            }
        }
    }

    fn close_face(&mut self) -> Result<(), String> {
        let end = u32::try_from(self.mesh.face_indices.len())
            .map_err(|_| "too many corners for 32-bit indices")?;
        self.mesh.face_offsets.push(end);
        Ok(())
    }
}

/// Parses binary STL.
pub fn parse_binary(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    let Some(n) = bytes.get(80..84) else {
        return Err(IoError::byte(
            source,
            bytes.len(),
            format!(
                "file ends inside the 84-byte binary STL header ({} bytes)",
                bytes.len()
            ),
        ));
    };
    let n = u32::from_le_bytes([n[0], n[1], n[2], n[3]]) as usize;
    let available = (bytes.len() - 84) / 50;
    let mut w = Welder::new(n.min(available));
    for t in 0..n {
        let start = 84 + 50 * t;
        let Some(rec) = bytes.get(start..start + 50) else {
            return Err(IoError::byte(
                source,
                start,
                format!("file ends inside triangle {} of {n}", t + 1),
            ));
        };
        for k in 0..3 {
            let mut xyz = [0.0f64; 3];
            for (a, slot) in xyz.iter_mut().enumerate() {
                let o = 12 + 12 * k + 4 * a;
                let v = f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]);
                if !v.is_finite() {
                    return Err(IoError::byte(
                        source,
                        start + o,
                        format!(
                            "triangle {} of {n}: coordinate {v} is not a finite number",
                            t + 1
                        ),
                    ));
                }
                *slot = f64::from(v);
            }
            let i = w
                .vertex(DVec3::from_array(xyz))
                .map_err(|m| IoError::byte(source, start, m))?;
            w.mesh.face_indices.push(i);
        }
        w.close_face()
            .map_err(|m| IoError::byte(source, start, m))?;
    }
    let end = 84 + 50 * n;
    if bytes.len() > end {
        return Err(IoError::byte(
            source,
            end,
            format!(
                "{} bytes follow the {n} triangles the header declares",
                bytes.len() - end
            ),
        ));
    }
    Ok(w.mesh)
}

/// Parses ascii STL.
pub fn parse_ascii(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    #[derive(PartialEq)]
    enum State {
        Outside,
        InSolid,
        InFacet,
        InLoop,
        LoopDone,
    }
    let mut c = Cursor::new(bytes, false, false);
    // Ascii text takes at least ~100 bytes per triangle.
    let mut w = Welder::new(bytes.len() / 100);
    let mut state = State::Outside;
    let mut facet_line = 0;
    while let Some((line, tok)) = c.next_statement() {
        let is = |word: &[u8]| tok.eq_ignore_ascii_case(word);
        let unexpected = |expected: &str| {
            Err(IoError::line(
                source,
                line,
                format!("expected {expected}, found \"{}\"", show(tok)),
            ))
        };
        match state {
            State::Outside if is(b"solid") => {
                c.rest_of_line();
                state = State::InSolid;
                continue;
            }
            State::Outside => return unexpected("\"solid\""),
            State::InSolid if is(b"endsolid") => {
                c.rest_of_line();
                state = State::Outside;
                continue;
            }
            State::InSolid if is(b"facet") => {
                // The normal is ignored; whatever follows on the line goes.
                c.rest_of_line();
                facet_line = line;
                state = State::InFacet;
                continue;
            }
            State::InSolid => return unexpected("\"facet\" or \"endsolid\""),
            State::InFacet if is(b"outer") => {
                match c.token() {
                    Some(t) if t.eq_ignore_ascii_case(b"loop") => {}
                    _ => return Err(IoError::line(source, line, "expected \"outer loop\"")),
                }
                state = State::InLoop;
            }
            State::InFacet => return unexpected("\"outer loop\""),
            State::InLoop if is(b"vertex") => {
                let p = c.point().map_err(|m| IoError::line(source, line, m))?;
                let i = w.vertex(p).map_err(|m| IoError::line(source, line, m))?;
                w.mesh.face_indices.push(i);
            }
            State::InLoop if is(b"endloop") => {
                let start = w.mesh.face_offsets.last().copied().unwrap_or(0) as usize;
                let corners = w.mesh.face_indices.len() - start;
                if corners < 3 {
                    return Err(IoError::line(
                        source,
                        line,
                        format!("facet has {corners} vertices, but at least 3 are needed"),
                    ));
                }
                state = State::LoopDone;
            }
            State::InLoop => return unexpected("\"vertex\" or \"endloop\""),
            State::LoopDone if is(b"endfacet") => {
                w.close_face().map_err(|m| IoError::line(source, line, m))?;
                state = State::InSolid;
            }
            State::LoopDone => return unexpected("\"endfacet\""),
        }
        if let Some(extra) = c.token() {
            return Err(IoError::line(
                source,
                line,
                format!("unexpected \"{}\" at the end of the line", show(extra)),
            ));
        }
        c.next_line();
    }
    match state {
        // A missing final `endsolid` is common and harmless.
        State::Outside | State::InSolid => Ok(w.mesh),
        _ => Err(IoError::line(
            source,
            c.line(),
            format!("file ends inside the facet that starts on line {facet_line}"),
        )),
    }
}

/// Unit normal of a triangle, or zero if it is degenerate.
fn normal(a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let n = (b - a).cross(c - a);
    let len = n.length();
    if len > 0.0 && len.is_finite() {
        n / len
    } else {
        DVec3::ZERO
    }
}

/// The fan triangles of the mesh's faces, in order.
fn triangles(mesh: &PolyMesh) -> impl Iterator<Item = [DVec3; 3]> + '_ {
    mesh.faces().flat_map(move |f| {
        (1..f.len().saturating_sub(1))
            .map(move |k| [f[0], f[k], f[k + 1]].map(|i| mesh.positions[i as usize]))
    })
}

/// Writes `mesh` as STL, binary or (if `ascii`) ascii; see the module
/// docs. Fails with [`io::ErrorKind::InvalidInput`] if the mesh is
/// malformed or has more than 2³² − 1 triangles (binary).
pub fn write<W: Write>(mut w: W, mesh: &PolyMesh, ascii: bool) -> io::Result<()> {
    let invalid = crate::invalid_input;
    crate::check_poly(mesh).map_err(invalid)?;
    let mut buf = Vec::with_capacity(crate::CHUNK + 512);
    if ascii {
        buf.extend_from_slice(b"solid holey\n");
        for t in triangles(mesh) {
            let n = normal(t[0], t[1], t[2]);
            buf.extend_from_slice(b"  facet normal ");
            push_vec(&mut buf, n);
            buf.extend_from_slice(b"\n    outer loop\n");
            for p in t {
                buf.extend_from_slice(b"      vertex ");
                push_vec(&mut buf, p);
                buf.push(b'\n');
            }
            buf.extend_from_slice(b"    endloop\n  endfacet\n");
            crate::flush_full(&mut w, &mut buf)?;
        }
        buf.extend_from_slice(b"endsolid holey\n");
    } else {
        let count: usize = mesh.faces().map(|f| f.len().saturating_sub(2)).sum();
        let count = u32::try_from(count)
            .map_err(|_| invalid(format!("{count} triangles are too many for binary STL")))?;
        let mut header = [b' '; 80];
        let title = b"binary STL written by holey";
        header[..title.len()].copy_from_slice(title);
        buf.extend_from_slice(&header);
        buf.extend_from_slice(&count.to_le_bytes());
        for t in triangles(mesh) {
            let n = normal(t[0], t[1], t[2]);
            for p in [n, t[0], t[1], t[2]] {
                for v in p.to_array() {
                    buf.extend_from_slice(&(v as f32).to_le_bytes());
                }
            }
            buf.extend_from_slice(&[0, 0]);
            crate::flush_full(&mut w, &mut buf)?;
        }
    }
    w.write_all(&buf)?;
    w.flush()
}

fn push_vec(buf: &mut Vec<u8>, p: DVec3) {
    push_f64(buf, p.x);
    buf.push(b' ');
    push_f64(buf, p.y);
    buf.push(b' ');
    push_f64(buf, p.z);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(bytes: &[u8]) -> String {
        parse(bytes, "m.stl").unwrap_err().to_string()
    }

    fn quad_and_tri() -> PolyMesh {
        PolyMesh::from_faces(
            vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(0.5, 0.5, 1.0),
            ],
            [&[0u32, 1, 2, 3][..], &[0, 1, 4]],
        )
    }

    #[test]
    fn binary_round_trip_welds_and_triangulates() {
        let m = quad_and_tri();
        let mut out = Vec::new();
        write(&mut out, &m, false).unwrap();
        assert_eq!(out.len(), 84 + 50 * 3);
        assert!(is_binary(&out));
        let back = parse(&out, "b.stl").unwrap();
        assert_eq!(back.positions, m.positions);
        let faces: Vec<&[u32]> = back.faces().collect();
        assert_eq!(faces, vec![&[0u32, 1, 2][..], &[0, 2, 3], &[0, 1, 4]]);
        // Normal of the first triangle is +z.
        let nz = f32::from_le_bytes(out[84 + 8..84 + 12].try_into().unwrap());
        assert_eq!(nz, 1.0);
    }

    #[test]
    fn binary_even_if_it_starts_with_solid() {
        let m = quad_and_tri();
        let mut out = Vec::new();
        write(&mut out, &m, false).unwrap();
        out[..12].copy_from_slice(b"solid thing ");
        assert!(is_binary(&out));
        assert_eq!(parse(&out, "b.stl").unwrap().face_count(), 3);
    }

    #[test]
    fn ascii_round_trip_is_exact() {
        let mut m = quad_and_tri();
        m.positions[4] = DVec3::new(0.1, 1.0 / 3.0, 1e-300);
        let mut out = Vec::new();
        write(&mut out, &m, true).unwrap();
        assert!(!is_binary(&out));
        let back = parse(&out, "a.stl").unwrap();
        crate::assert_positions_bit_exact(&back.positions, &m.positions);
        assert_eq!(back.face_count(), 3);
    }

    #[test]
    fn soups_stay_soups_and_ascii_is_tolerant() {
        let text = "  SOLID  my part \r\n\
          Facet Normal 0 0 1\r\n  OUTER   LOOP\r\n\tVertex 0 0 0\r\n VERTEX 1 0 0\n vertex 0 1 0\n endloop\n endfacet\n\
          facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n vertex -0 1 0\n endloop\n endfacet\n\
          endsolid my part\nsolid second\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
        let m = parse(text.as_bytes(), "s.stl").unwrap();
        // -0 differs from 0 bitwise, so it is a fourth vertex.
        assert_eq!(m.positions.len(), 4);
        let faces: Vec<&[u32]> = m.faces().collect();
        assert_eq!(faces, vec![&[0u32, 1, 2][..], &[0, 1, 3], &[0, 1, 2]]);
        // A soup: no position repeats, so nothing is welded.
        let soup = "solid s\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                    facet normal 0 0 0\nouter loop\nvertex 0 0 1e-9\nvertex 1 0 1e-9\nvertex 0 1 1e-9\nendloop\nendfacet\nendsolid\n";
        assert_eq!(parse(soup.as_bytes(), "s.stl").unwrap().positions.len(), 6);
    }

    #[test]
    fn errors_name_line_or_byte() {
        let m = quad_and_tri();
        let mut out = Vec::new();
        write(&mut out, &m, false).unwrap();
        // 3 triangles; cut inside the second.
        assert_eq!(
            err(&out[..84 + 50 + 20]),
            "m.stl: byte 134: file ends inside triangle 2 of 3"
        );
        assert_eq!(
            err(&out[..40]),
            "m.stl: byte 40: file ends inside the 84-byte binary STL header (40 bytes)"
        );
        let mut extra = out.clone();
        extra.extend_from_slice(&[0; 7]);
        assert_eq!(
            err(&extra),
            "m.stl: byte 234: 7 bytes follow the 3 triangles the header declares"
        );
        let mut nan = out.clone();
        nan[84 + 50 + 16..84 + 50 + 20].copy_from_slice(&f32::NAN.to_le_bytes());
        assert_eq!(
            err(&nan),
            "m.stl: byte 150: triangle 2 of 3: coordinate NaN is not a finite number"
        );

        for (text, want) in [
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n",
                "m.stl:5: bad number \"zero\"",
            ),
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n",
                "m.stl:6: facet has 2 vertices, but at least 3 are needed",
            ),
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 0 inf\nendloop\n",
                "m.stl:6: coordinate \"inf\" is not a finite number",
            ),
            (
                "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 0 1\nendloop\n",
                "m.stl:8: file ends inside the facet that starts on line 2",
            ),
            (
                "solid x\nfacet normal 0 0 1\nvertex 0 0 0\n",
                "m.stl:3: expected \"outer loop\", found \"vertex\"",
            ),
        ] {
            assert_eq!(err(text.as_bytes()), want, "{text:?}");
        }
    }
}
