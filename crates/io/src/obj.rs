//! Wavefront OBJ: positions and polygon faces.
//!
//! Read: `v x y z [w]` (values past the third, such as vertex colours, are
//! ignored) and `f` with corners written `v`, `v/vt`, `v//vn` or
//! `v/vt/vn`, 1-based or negative (relative to the last vertex defined so
//! far). Every other statement (`o`, `g`, `s`, `usemtl`, `mtllib`, `vt`,
//! `vn`, `vp`, `l`, `p`, and anything unknown) is ignored, as are comments
//! (`#` to the end of the line). A `\` at the end of a line continues the
//! statement on the next line; CRLF line endings are accepted. Faces may
//! name vertices defined further down the file; indices are checked once
//! the whole file is read. Vertices are kept exactly as stored: nothing is
//! welded and unreferenced vertices stay in `positions`.
//!
//! What is not an OBJ file is refused rather than read as an empty mesh:
//! binary data (a NUL or another control byte than tab, line feed,
//! vertical tab, form feed and carriage return), and text of which no
//! statement is one of OBJ's (a file of only comments and blank lines is
//! an empty OBJ). Each error names the first bad line.
//!
//! Write: a `# written by holey` comment, one `v` line per position in
//! shortest round-trip decimals (so reading gives back the same `f64`
//! bits) and one `f` line per face, 1-based.

use std::io::{self, Write};

use holey_mesh::{DVec3, PolyMesh};

use crate::IoError;
use crate::text::{Cursor, Lines, push_face_end};

/// The statements of the OBJ format (Wavefront's Appendix B1): geometry,
/// free-form curves and surfaces, grouping, display and rendering. Only
/// `v` and `f` are read; the rest are skipped, but they make a file an
/// OBJ file.
const STATEMENTS: [&[u8]; 41] = [
    b"v",
    b"vt",
    b"vn",
    b"vp",
    b"f",
    b"fo",
    b"l",
    b"p",
    b"g",
    b"o",
    b"s",
    b"mg",
    b"usemtl",
    b"mtllib",
    b"usemap",
    b"maplib",
    b"cstype",
    b"deg",
    b"bmat",
    b"step",
    b"curv",
    b"curv2",
    b"surf",
    b"parm",
    b"trim",
    b"hole",
    b"scrv",
    b"sp",
    b"end",
    b"con",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"lod",
    b"shadow_obj",
    b"trace_obj",
    b"ctech",
    b"stech",
    b"call",
    b"csh",
    b"res",
];

/// The 1-based line of the first byte no text file has, with the byte.
fn binary_byte(bytes: &[u8]) -> Option<(usize, u8)> {
    let at = bytes.iter().position(|&b| {
        (b < 0x20 && !matches!(b, b'\t' | b'\n' | 0x0b | 0x0c | b'\r')) || b == 0x7f
    })?;
    let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
    Some((line, bytes[at]))
}

/// Parses OBJ text. `source` names the file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    if let Some((line, byte)) = binary_byte(bytes) {
        return Err(IoError::line(
            source,
            line,
            format!("not an OBJ file: binary data (byte 0x{byte:02x})"),
        ));
    }
    // Whether any statement was OBJ's, and the first that was not.
    let mut recognised = false;
    let mut first_unknown: Option<(usize, String)> = None;
    let mut c = Cursor::new(bytes, true, true);
    let mut positions: Vec<DVec3> = Vec::new();
    let mut offsets: Vec<u32> = vec![0];
    let mut indices: Vec<u32> = Vec::new();
    // Faces naming a vertex that is not defined yet, as (line, largest
    // 1-based index). Usually empty; settled once all vertices are known.
    let mut forward: Vec<(usize, u64)> = Vec::new();
    loop {
        let Some(keyword) = c.token() else {
            if c.eof() {
                break;
            }
            c.next_line();
            continue;
        };
        let line = c.line();
        if STATEMENTS.contains(&keyword) {
            recognised = true;
        } else if first_unknown.is_none() {
            first_unknown = Some((line, crate::error::show(keyword)));
        }
        match keyword {
            b"v" => {
                let p = c.point().map_err(|m| IoError::line(source, c.line(), m))?;
                positions.push(p);
            }
            b"f" => {
                let start = indices.len();
                let defined = positions.len() as u64;
                let mut largest_forward = 0u64;
                while let Some(read) = c.corner_index() {
                    let i = read.map_err(|tok| {
                        IoError::line(
                            source,
                            c.line(),
                            format!("bad vertex index \"{}\"", crate::error::show(tok)),
                        )
                    })?;
                    let index = match i {
                        0 => {
                            return Err(IoError::line(
                                source,
                                c.line(),
                                "vertex index 0 is not allowed (OBJ indices start at 1)",
                            ));
                        }
                        1.. => i.unsigned_abs() - 1,
                        _ => match defined.checked_sub(i.unsigned_abs()) {
                            Some(index) => index,
                            None => {
                                return Err(IoError::line(
                                    source,
                                    c.line(),
                                    format!(
                                        "relative vertex index {i} reaches before the first vertex \
                                         (only {defined} vertices are defined so far)"
                                    ),
                                ));
                            }
                        },
                    };
                    if index >= u64::from(u32::MAX) {
                        return Err(IoError::line(
                            source,
                            c.line(),
                            format!("vertex index {i} is too large"),
                        ));
                    }
                    if index >= defined {
                        largest_forward = largest_forward.max(index + 1);
                    }
                    indices.push(index as u32);
                }
                let corners = indices.len() - start;
                if corners < 3 {
                    return Err(IoError::line(
                        source,
                        line,
                        format!("face has {corners} corner(s), but at least 3 are needed"),
                    ));
                }
                if largest_forward > 0 {
                    forward.push((line, largest_forward));
                }
                push_face_end(&mut offsets, &indices)
                    .map_err(|m| IoError::line(source, line, m))?;
            }
            _ => {}
        }
        c.next_line();
    }
    if let (false, Some((line, token))) = (recognised, first_unknown) {
        return Err(IoError::line(
            source,
            line,
            format!("not an OBJ file: \"{token}\" is no OBJ statement, and no line has one"),
        ));
    }
    let n = positions.len() as u64;
    if n >= u64::from(u32::MAX) {
        return Err(IoError::content(
            source,
            format!("{n} vertices exceed 32-bit indices"),
        ));
    }
    if let Some(&(line, index)) = forward.iter().find(|&&(_, largest)| largest > n) {
        return Err(IoError::line(
            source,
            line,
            format!("face refers to vertex {index}, but only {n} vertices are defined"),
        ));
    }
    Ok(PolyMesh {
        positions,
        face_offsets: offsets,
        face_indices: indices,
    })
}

/// Writes `mesh` as OBJ. Faces are written as given, whatever their size.
/// Fails with [`io::ErrorKind::InvalidInput`] if the mesh is malformed
/// (see [`crate::check_poly`]).
pub fn write<W: Write>(w: W, mesh: &PolyMesh) -> io::Result<()> {
    crate::check_poly(mesh).map_err(crate::invalid_input)?;
    let mut out = Lines::new(w, b"# written by holey\n");
    out.points(b"v ", &mesh.positions)?;
    out.faces(mesh.faces(), 1, |b, _, _| b.push(b'f'))?;
    out.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse(text.as_bytes(), "m.obj").unwrap_err().to_string()
    }

    /// Issue 14's garbage files: 5,000 random bytes named `.obj` were read
    /// as an empty mesh (exit 0 from `info`, `convert`, `subdivide`). Binary
    /// data and text with no OBJ statement are refused, naming the first
    /// bad line; comments and blank lines alone are an empty OBJ, and
    /// unknown statements beside OBJ's are skipped as before.
    #[test]
    fn what_is_not_an_obj_file_is_refused_by_line() {
        let mut rng = 0x9e37_79b9_7f4a_7c15u64;
        let random: Vec<u8> = (0..5000)
            .map(|_| {
                rng ^= rng << 13;
                rng ^= rng >> 7;
                rng ^= rng << 17;
                (rng >> 24) as u8
            })
            .collect();
        let e = parse(&random, "r.obj").unwrap_err().to_string();
        assert!(e.contains("not an OBJ file: binary data"), "{e}");
        let e = err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\0\n");
        assert!(e.starts_with("m.obj:4:") && e.contains("byte 0x00"), "{e}");
        let e = err("# notes\n\nhello world\nthis is not obj\n");
        assert!(
            e.starts_with("m.obj:3:") && e.contains("\"hello\" is no OBJ statement"),
            "{e}"
        );
        let empty = parse(b"# only a comment\n\n  \r\n", "m.obj").unwrap();
        assert!(empty.positions.is_empty() && empty.face_count() == 0);
        let m = parse(b"hello\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj").unwrap();
        assert_eq!(m.face_count(), 1);
    }

    #[test]
    fn reads_all_corner_forms_and_ignores_the_rest() {
        let text = "# comment\r\nmtllib a.mtl\no thing\ng group\ns off\nusemtl red\n\
                    v 0 0 0\nv 1 0 0 1\nv 0 1 0 0.5 0.5 0.5\nv 0 0 1\nvt 0 0\nvn 0 0 1\nvp 0.5\n\
                    f 1 2 3\nf 1/1 2/1 4/1\nf 1//1 3//1 4//1\nf 2/1/1 3/1/1 4/1/1 # trailing\n\
                    f -4 -3 -1\nl 1 2\np 3\nfrobnicate 1 2 3\nf 1 \\\n 2 \\\r\n 3\n";
        let m = parse(text.as_bytes(), "t.obj").unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.positions[1], DVec3::new(1.0, 0.0, 0.0));
        let faces: Vec<&[u32]> = m.faces().collect();
        assert_eq!(
            faces,
            vec![
                &[0, 1, 2][..],
                &[0, 1, 3],
                &[0, 2, 3],
                &[1, 2, 3],
                &[0, 1, 3],
                &[0, 1, 2]
            ]
        );
        m.check().unwrap();
    }

    #[test]
    fn keeps_unreferenced_vertices_and_allows_forward_references() {
        let m = parse(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\n", "t.obj").unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.face(0), &[0, 1, 2]);
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let positions = vec![
            DVec3::new(0.1, -0.0, 1.0 / 3.0),
            DVec3::new(1e-300, 1.5e300, -7.0),
            DVec3::new(f64::MIN_POSITIVE, 5e-324, 123456789.125),
            DVec3::new(2.0, 3.0, 4.0),
            DVec3::new(0.0, 0.0, 0.0),
        ];
        let m = PolyMesh::from_faces(positions, [&[0u32, 1, 2][..], &[2, 3, 4, 1], &[4, 3, 0]]);
        let mut out = Vec::new();
        write(&mut out, &m).unwrap();
        let text = String::from_utf8(out.clone()).unwrap();
        assert!(text.starts_with("# written by holey\n"));
        assert!(text.contains("v 2 3 4\n"), "{text}");
        let back = parse(&out, "rt.obj").unwrap();
        crate::assert_same_poly(&back, &m);
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(err("v 0 0 0\nv 1 x 0\n"), "m.obj:2: bad number \"x\"");
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 0 2\n"),
            "m.obj:5: vertex index 0 is not allowed (OBJ indices start at 1)"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\nv 0 0 1\nf 1 2 9\n"),
            "m.obj:6: face refers to vertex 9, but only 4 vertices are defined"
        );
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nf 1 2\n"),
            "m.obj:3: face has 2 corner(s), but at least 3 are needed"
        );
        assert_eq!(
            err("v 0 nan 0\n"),
            "m.obj:1: coordinate \"nan\" is not a finite number"
        );
        assert_eq!(
            err("# x\nv 0 0 inf\n"),
            "m.obj:2: coordinate \"inf\" is not a finite number"
        );
        assert_eq!(
            err("v 0 0 1e999\n"),
            "m.obj:1: coordinate \"1e999\" is not a finite number"
        );
        assert_eq!(
            err("v 0 0\n"),
            "m.obj:1: vertex has 2 coordinate(s), but 3 are needed"
        );
        assert_eq!(
            err("v 0 0 0\nf 1 -2 1\n"),
            "m.obj:2: relative vertex index -2 reaches before the first vertex (only 1 vertices are defined so far)"
        );
        assert_eq!(
            err("v 0 0 0\nf 1 a/2 1\n"),
            "m.obj:2: bad vertex index \"a/2\""
        );
        assert_eq!(
            err("v 0 0 0\nf 1 1 99999999999\n"),
            "m.obj:2: vertex index 99999999999 is too large"
        );
        // A continued face is reported at the line where it starts.
        assert_eq!(
            err("v 0 0 0\nf 1 \\\n 1 \\\n 7\n"),
            "m.obj:2: face refers to vertex 7, but only 1 vertices are defined"
        );
        let e = parse(b"v 0 0 0\nv 1 x 0\n", "m.obj").unwrap_err();
        assert!(e.is_bad_input());
    }

    #[test]
    fn empty_input_is_an_empty_mesh() {
        let m = parse(b"", "e.obj").unwrap();
        assert_eq!(m.face_count(), 0);
        assert!(m.positions.is_empty());
    }
}
