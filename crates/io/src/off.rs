//! Object File Format (OFF), the text form.
//!
//! Read: an optional header keyword `OFF`, `COFF`, `NOFF`, `CNOFF` (any of
//! the prefixes `ST`, `C`, `N` in that order before `OFF`), the counts
//! `vertices faces [edges]` (on the header line or the next line with
//! content), one vertex per line (`x y z`, further values such as normals
//! or colours ignored) and one face per line (`n i1 … in`, 0-based, an
//! optional colour after the indices ignored). Blank lines and `#` comments
//! are skipped anywhere. Faces need at least 3 corners. Binary OFF and the
//! 4-D / n-D variants are rejected with an error.
//!
//! Write: `OFF`, a `# written by holey` comment, the counts (edge count 0,
//! as most writers do), positions in shortest round-trip decimals and the
//! faces.

use std::io::{self, Write};

use holey_mesh::PolyMesh;

use crate::IoError;
use crate::error::show;
use crate::text::{Cursor, Lines, parse_u64, push_face_end, push_u64};

/// True for a header keyword this reader handles.
fn is_off_keyword(word: &[u8]) -> bool {
    let w = word.strip_prefix(b"ST").unwrap_or(word);
    let w = w.strip_prefix(b"C").unwrap_or(w);
    let w = w.strip_prefix(b"N").unwrap_or(w);
    w == b"OFF"
}

/// Parses OFF text. `source` names the file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<PolyMesh, IoError> {
    let mut c = Cursor::new(bytes, false, true);
    c.skip_empty_lines();
    let header_line = c.line();
    let mut counts: Vec<(&[u8], usize)> = Vec::with_capacity(3);
    match c.token() {
        None => {
            return Err(IoError::content(
                source,
                "the file is empty (expected an OFF header)",
            ));
        }
        Some(word) if is_off_keyword(word) => {
            if let Some(next) = c.token() {
                if next.eq_ignore_ascii_case(b"BINARY") {
                    return Err(IoError::line(
                        source,
                        header_line,
                        "binary OFF is not supported",
                    ));
                }
                counts.push((next, header_line));
            }
        }
        Some(word) if word.ends_with(b"OFF") => {
            return Err(IoError::line(
                source,
                header_line,
                format!(
                    "unsupported OFF variant \"{}\" (only 3-D OFF is read)",
                    show(word)
                ),
            ));
        }
        // The keyword is optional in the original definition of the format.
        Some(word) if parse_u64(word).is_some() => counts.push((word, header_line)),
        Some(word) => {
            return Err(IoError::line(
                source,
                header_line,
                format!("expected the header \"OFF\", found \"{}\"", show(word)),
            ));
        }
    }
    // The counts: on the header line or the next line with content.
    loop {
        match c.token() {
            Some(tok) => {
                counts.push((tok, c.line()));
                if counts.len() == 3 {
                    break;
                }
            }
            None if counts.len() >= 2 => break,
            None => {
                c.next_line();
                c.skip_empty_lines();
                if c.eof() {
                    return Err(IoError::line(
                        source,
                        c.line(),
                        "file ends before the vertex and face counts",
                    ));
                }
            }
        }
    }
    let count = |(tok, line): (&[u8], usize), what: &str| -> Result<usize, IoError> {
        match parse_u64(tok) {
            Some(n) if n < u64::from(u32::MAX) => Ok(n as usize),
            Some(n) => Err(IoError::line(
                source,
                line,
                format!("{what} count {n} is too large"),
            )),
            None => Err(IoError::line(
                source,
                line,
                format!("bad {what} count \"{}\"", show(tok)),
            )),
        }
    };
    let nv = count(counts[0], "vertex")?;
    let nf = count(counts[1], "face")?;
    c.next_line();

    // Never trust declared counts for allocation: a vertex line takes at
    // least 6 bytes and a face line at least 8.
    let mut positions = Vec::with_capacity(nv.min(bytes.len() / 6));
    let mut offsets = Vec::with_capacity(nf.min(bytes.len() / 8) + 1);
    offsets.push(0u32);
    let mut indices: Vec<u32> = Vec::with_capacity((nf.min(bytes.len() / 8)) * 3);
    for i in 0..nv {
        c.skip_empty_lines();
        if c.eof() {
            return Err(IoError::line(
                source,
                c.line(),
                format!("file ends after {i} of {nv} vertices"),
            ));
        }
        let p = c.point().map_err(|m| IoError::line(source, c.line(), m))?;
        positions.push(p);
        c.next_line();
    }
    for f in 0..nf {
        c.skip_empty_lines();
        let line = c.line();
        let Some(tok) = c.token() else {
            return Err(IoError::line(
                source,
                line,
                format!("file ends after {f} of {nf} faces"),
            ));
        };
        let Some(n) = parse_u64(tok) else {
            return Err(IoError::line(
                source,
                line,
                format!("bad face corner count \"{}\"", show(tok)),
            ));
        };
        if n < 3 {
            return Err(IoError::line(
                source,
                line,
                format!("face has {n} corner(s), but at least 3 are needed"),
            ));
        }
        for k in 0..n {
            let Some(tok) = c.token() else {
                return Err(IoError::line(
                    source,
                    line,
                    format!("face declares {n} corners but lists {k}"),
                ));
            };
            let index = match parse_u64(tok) {
                Some(i) if i < nv as u64 => i as u32,
                Some(i) => {
                    return Err(IoError::line(
                        source,
                        line,
                        format!(
                            "face refers to vertex {i}, but only {nv} vertices are defined (OFF counts from 0)"
                        ),
                    ));
                }
                None => {
                    return Err(IoError::line(
                        source,
                        line,
                        format!("bad vertex index \"{}\"", show(tok)),
                    ));
                }
            };
            indices.push(index);
        }
        push_face_end(&mut offsets, &indices).map_err(|m| IoError::line(source, line, m))?;
        c.next_line();
    }
    Ok(PolyMesh {
        positions,
        face_offsets: offsets,
        face_indices: indices,
    })
}

/// Writes `mesh` as OFF. Faces are written as given, whatever their size.
/// Fails with [`io::ErrorKind::InvalidInput`] if the mesh is malformed.
pub fn write<W: Write>(w: W, mesh: &PolyMesh) -> io::Result<()> {
    crate::check_poly(mesh).map_err(crate::invalid_input)?;
    let mut out = Lines::new(w, b"OFF\n# written by holey\n");
    out.line(|b| {
        push_u64(b, mesh.positions.len() as u64);
        b.push(b' ');
        push_u64(b, mesh.face_count() as u64);
        b.extend_from_slice(b" 0");
    })?;
    out.points(b"", &mesh.positions)?;
    out.faces(mesh.faces(), 0, |b, _, face| push_u64(b, face.len() as u64))?;
    out.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_mesh::DVec3;

    fn err(text: &str) -> String {
        parse(text.as_bytes(), "m.off").unwrap_err().to_string()
    }

    #[test]
    fn reads_variants_comments_and_colours() {
        let text = "# lead comment\nCOFF 4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n\n# mid\n0 1 0 1 1 1 1\n0 0 1 1 1 1 1\n3 0 1 2 0.5 0.5 0.5\n4 0 1 3 2\n";
        let m = parse(text.as_bytes(), "t.off").unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.face(0), &[0, 1, 2]);
        assert_eq!(m.face(1), &[0, 1, 3, 2]);
        for head in ["OFF\n4 1\n", "NOFF\n\n4 1 6\n", "CNOFF 4 1 6\n", "4 1 0\n"] {
            let text = format!("{head}0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
            let m = parse(text.as_bytes(), "t.off").unwrap();
            assert_eq!(m.face(0), &[0, 1, 2], "{head}");
        }
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let positions = vec![
            DVec3::new(0.1, -0.0, 1.0 / 3.0),
            DVec3::new(1e-300, 1.5e300, -7.0),
            DVec3::new(2.0, 3.0, 4.0),
            DVec3::new(0.3, 0.2, 0.1),
        ];
        let m = PolyMesh::from_faces(positions, [&[0u32, 1, 2][..], &[0, 2, 3, 1]]);
        let mut out = Vec::new();
        write(&mut out, &m).unwrap();
        let back = parse(&out, "rt.off").unwrap();
        crate::assert_same_poly(&back, &m);
    }

    #[test]
    fn errors_name_the_line() {
        for (input, want) in [
            ("OFF\n2 0 0\n0 0 0\n0 x 0\n", "m.off:4: bad number \"x\""),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                "m.off:6: face refers to vertex 3, but only 3 vertices are defined (OFF counts from 0)",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                "m.off:6: face has 2 corner(s), but at least 3 are needed",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 NaN\n0 1 0\n3 0 1 2\n",
                "m.off:4: coordinate \"NaN\" is not a finite number",
            ),
            (
                "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                "m.off:7: file ends after 1 of 2 faces",
            ),
            (
                "OFF\n5 0 0\n0 0 0\n",
                "m.off:4: file ends after 1 of 5 vertices",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
                "m.off:6: face declares 4 corners but lists 3",
            ),
            ("OFF\n3 x 0\n", "m.off:2: bad face count \"x\""),
            ("OFF BINARY\n", "m.off:1: binary OFF is not supported"),
            (
                "4OFF\n",
                "m.off:1: unsupported OFF variant \"4OFF\" (only 3-D OFF is read)",
            ),
            (
                "PLY\n",
                "m.off:1: expected the header \"OFF\", found \"PLY\"",
            ),
            ("", "m.off: the file is empty (expected an OFF header)"),
            // Huge declared counts do not allocate; the file simply ends.
            (
                "OFF\n5000000000 1 0\n",
                "m.off:2: vertex count 5000000000 is too large",
            ),
            (
                "OFF\n400000000 1 0\n0 0 0\n",
                "m.off:4: file ends after 1 of 400000000 vertices",
            ),
        ] {
            assert_eq!(err(input), want, "{input:?}");
        }
    }
}
