//! holey's native `.dlfl` text format (specified in `docs/dlfl-format.md`).
//!
//! Read: `#` comments (whole lines or after a statement) and blank lines
//! anywhere; the header `dlfl 1` as the first statement; then `v x y z`,
//! `f i j …` and `h i j …` (faces and hole faces, numbered together in
//! file order, 0-based vertex numbers, at least one corner) and
//! `e F:K G:L` (an edge by the two corners at which it starts). The result
//! is a [`RawMesh`] whose `edges` is empty when the file has no `e` line
//! (the caller then infers them). Everything that can be pinned to a line
//! is checked here: numbers, vertex and corner references, unused
//! vertices, a corner starting two edges, an edge whose sides do not run
//! oppositely between the same two vertices, and (when there are `e`
//! lines) a corner starting no edge other than a point-sphere's. Whether
//! the whole is a valid 2-manifold is left to
//! [`holey_dlfl::Mesh::from_raw`].
//!
//! Write: a `# written by holey` comment, the header, `v` lines in shortest
//! round-trip decimals, `f`/`h` lines, and one `e` line per edge of the
//! [`RawMesh`] (none if it has no edges).

use std::io::{self, Write};

use holey_dlfl::RawMesh;
use holey_mesh::{DVec3, NonFinite};

use crate::IoError;
use crate::error::show;
use crate::text::{Cursor, Lines, parse_u64, push_u64};

const NONE: u32 = u32::MAX;

/// Parses a `.dlfl` file. `source` names the file in error messages.
pub fn parse(bytes: &[u8], source: &str) -> Result<RawMesh, IoError> {
    let mut c = Cursor::new(bytes, false, true);
    header(&mut c, source)?;
    let mut st = statements(&mut c, source)?;
    st.check_vertices_used(source)?;
    // Resolve edges to global corners, checking each against its line.
    let edge_of = resolve_edges(&mut st.raw, &st.edges, source)?;
    if !st.edges.is_empty() {
        st.check_corners_start_edges(&edge_of, source)?;
    }
    Ok(st.raw)
}

/// An `e` line as written: its two (face, corner) pairs and its line.
type WrittenEdge = ([u64; 2], [u64; 2], usize);

/// The statements of a `.dlfl` file after its header.
struct Statements {
    /// The vertices and faces (hole flags empty when there is no hole),
    /// edges not yet resolved.
    raw: RawMesh,
    /// The line of each vertex.
    vertex_lines: Vec<usize>,
    /// The line of each face.
    face_lines: Vec<usize>,
    /// Edges as written, (face, corner) pairs, with their lines; resolved
    /// once every face is known.
    edges: Vec<WrittenEdge>,
}

impl Statements {
    /// Checks that the vertices fit 32-bit indices, that every face refers
    /// to defined vertices only, and that every vertex is used by a face.
    fn check_vertices_used(&self, source: &str) -> Result<(), IoError> {
        let (raw, vertex_lines, face_lines) = (&self.raw, &self.vertex_lines, &self.face_lines);
        let err = |line: usize, m: String| IoError::line(source, line, m);
        let nv = raw.positions.len();
        if nv >= NONE as usize {
            return Err(IoError::content(
                source,
                format!("{nv} vertices exceed 32-bit indices"),
            ));
        }
        let mut used = vec![false; nv];
        for (f, &line) in face_lines.iter().enumerate() {
            for &v in raw.face(f) {
                match used.get_mut(v as usize) {
                    Some(u) => *u = true,
                    None => {
                        return Err(err(
                            line,
                            format!(
                                "face refers to vertex {v}, but only {nv} vertices are defined"
                            ),
                        ));
                    }
                }
            }
        }
        if let Some(v) = used.iter().position(|&u| !u) {
            return Err(err(
                vertex_lines[v],
                format!("vertex {v} is not used by any face"),
            ));
        }
        Ok(())
    }

    /// Checks that every corner starts an edge (`edge_of`, from
    /// [`resolve_edges`]), except a point-sphere's lone corner.
    fn check_corners_start_edges(&self, edge_of: &[u32], source: &str) -> Result<(), IoError> {
        let (raw, face_lines) = (&self.raw, &self.face_lines);
        let err = |line: usize, m: String| IoError::line(source, line, m);
        for (f, &line) in face_lines.iter().enumerate() {
            let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
            if hi - lo == 1 {
                continue; // a point-sphere's lone corner may start no edge
            }
            if let Some(g) = (lo..hi).find(|&g| edge_of[g as usize] == NONE) {
                return Err(err(
                    line,
                    format!(
                        "corner {f}:{} starts no edge (no \"e\" line names it)",
                        g - lo
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Reads the header `dlfl 1` (after any blank or comment lines) and moves
/// past its line.
fn header(c: &mut Cursor<'_>, source: &str) -> Result<(), IoError> {
    let err = |line: usize, m: String| IoError::line(source, line, m);
    c.skip_empty_lines();
    match (c.token(), c.token()) {
        (Some(b"dlfl"), Some(b"1")) => {}
        (Some(b"dlfl"), Some(v)) => {
            return Err(err(
                c.line(),
                format!(
                    "unsupported .dlfl version \"{}\" (this reader knows 1)",
                    show(v)
                ),
            ));
        }
        _ => return Err(err(c.line(), "expected the header \"dlfl 1\"".into())),
    }
    if let Some(t) = c.token() {
        return Err(err(
            c.line(),
            format!("unexpected \"{}\" after the header", show(t)),
        ));
    }
    c.next_line();
    Ok(())
}

/// Reads every statement up to the end of the file, checking each line
/// on its own.
fn statements(c: &mut Cursor<'_>, source: &str) -> Result<Statements, IoError> {
    let err = |line: usize, m: String| IoError::line(source, line, m);
    let mut raw = RawMesh {
        face_offsets: vec![0],
        ..RawMesh::default()
    };
    let mut any_hole = false;
    let mut vertex_lines: Vec<usize> = Vec::new();
    let mut face_lines: Vec<usize> = Vec::new();
    let mut edges: Vec<WrittenEdge> = Vec::new();
    while let Some((line, keyword)) = c.next_statement() {
        match keyword {
            b"v" => {
                raw.positions.push(vertex_statement(c, line, source)?);
                vertex_lines.push(line);
            }
            b"f" | b"h" => {
                face_statement(c, line, source, &mut raw)?;
                let hole = keyword == b"h";
                any_hole |= hole;
                raw.holes.push(hole);
                face_lines.push(line);
            }
            b"e" => {
                let ends = edge_statement(c, line, source)?;
                edges.push((ends[0], ends[1], line));
            }
            other => return Err(err(line, format!("unknown statement \"{}\"", show(other)))),
        }
        if let Some(t) = c.token() {
            return Err(err(
                line,
                format!("unexpected \"{}\" at the end of the line", show(t)),
            ));
        }
        c.next_line();
    }
    if !any_hole {
        raw.holes.clear();
    }
    Ok(Statements {
        raw,
        vertex_lines,
        face_lines,
        edges,
    })
}

/// The position of a `v` statement on line `line`, after its keyword.
fn vertex_statement(c: &mut Cursor<'_>, line: usize, source: &str) -> Result<DVec3, IoError> {
    c.point().map_err(|m| IoError::line(source, line, m))
}

/// Appends the corners of an `f` or `h` statement on line `line`, after
/// its keyword, to `raw` as a new face (its hole flag is the caller's).
fn face_statement(
    c: &mut Cursor<'_>,
    line: usize,
    source: &str,
    raw: &mut RawMesh,
) -> Result<(), IoError> {
    let err = |line: usize, m: String| IoError::line(source, line, m);
    let start = raw.face_vertices.len();
    while let Some(tok) = c.token() {
        match parse_u64(tok) {
            Some(i) if i < u64::from(NONE) => raw.face_vertices.push(i as u32),
            Some(i) => {
                return Err(err(line, format!("vertex number {i} is too large")));
            }
            None => {
                return Err(err(line, format!("bad vertex number \"{}\"", show(tok))));
            }
        }
    }
    if raw.face_vertices.len() == start {
        return Err(err(line, "a face needs at least one corner".into()));
    }
    let end = u32::try_from(raw.face_vertices.len())
        .ok()
        .filter(|&e| e < NONE)
        .ok_or_else(|| err(line, "too many corners for 32-bit indices".into()))?;
    raw.face_offsets.push(end);
    Ok(())
}

/// The two `face:corner` pairs of an `e` statement on line `line`, after
/// its keyword.
fn edge_statement(c: &mut Cursor<'_>, line: usize, source: &str) -> Result<[[u64; 2]; 2], IoError> {
    let err = |line: usize, m: String| IoError::line(source, line, m);
    let mut ends = [[0u64; 2]; 2];
    for end in &mut ends {
        let Some(tok) = c.token() else {
            return Err(err(
                line,
                "an edge needs two corners, written face:corner".into(),
            ));
        };
        let parsed = tok
            .iter()
            .position(|&b| b == b':')
            .and_then(|k| Some([parse_u64(&tok[..k])?, parse_u64(&tok[k + 1..])?]));
        *end = parsed.ok_or_else(|| {
            err(
                line,
                format!("bad corner \"{}\" (expected face:corner)", show(tok)),
            )
        })?;
    }
    Ok(ends)
}

/// Resolves the written `edges` to global corners in `raw.edges`,
/// checking each against its line; returns the edge each corner starts
/// (`NONE` for none; empty when there are no edges).
fn resolve_edges(
    raw: &mut RawMesh,
    edges: &[WrittenEdge],
    source: &str,
) -> Result<Vec<u32>, IoError> {
    let err = |line: usize, m: String| IoError::line(source, line, m);
    let nf = raw.face_count();
    let nc = raw.face_vertices.len();
    let mut edge_of = vec![NONE; if edges.is_empty() { 0 } else { nc }];
    let mut edge_lines = Vec::with_capacity(edges.len());
    for (ei, &(a, b, line)) in edges.iter().enumerate() {
        let mut corners = [0u32; 2];
        for (slot, [f, k]) in corners.iter_mut().zip([a, b]) {
            let Some(fi) = usize::try_from(f).ok().filter(|&f| f < nf) else {
                return Err(err(
                    line,
                    format!("edge names face {f}, but there are only {nf} faces"),
                ));
            };
            let len = raw.face(fi).len();
            if k >= len as u64 {
                return Err(err(
                    line,
                    format!("edge names corner {f}:{k}, but face {f} has only {len} corner(s)"),
                ));
            }
            let g = raw.face_offsets[fi] + k as u32;
            let previous = edge_of[g as usize];
            if previous != NONE {
                let first = edge_lines.get(previous as usize).copied().unwrap_or(line);
                return Err(err(
                    line,
                    format!("corner {f}:{k} starts a second edge (the first is on line {first})"),
                ));
            }
            edge_of[g as usize] = ei as u32;
            *slot = g;
        }
        let ((u0, v0), (u1, v1)) = (side(raw, corners[0]), side(raw, corners[1]));
        if u0 != v1 || v0 != u1 {
            return Err(err(
                line,
                format!(
                    "the edge's sides do not run oppositely between the same two vertices \
                     ({u0}→{v0} and {u1}→{v1})"
                ),
            ));
        }
        raw.edges.push(corners);
        edge_lines.push(line);
    }
    Ok(edge_of)
}

/// The side starting at global corner `g` of `raw`: from its corner's
/// vertex to the next corner's.
fn side(raw: &RawMesh, g: u32) -> (u32, u32) {
    let f = raw.face_offsets.partition_point(|&o| o <= g) - 1;
    let (lo, hi) = (raw.face_offsets[f], raw.face_offsets[f + 1]);
    let next = if g + 1 == hi { lo } else { g + 1 };
    (
        raw.face_vertices[g as usize],
        raw.face_vertices[next as usize],
    )
}

/// Checks that a [`RawMesh`] can be written: well-formed offsets, no empty
/// face, vertex numbers and edge corners in range, hole flags for every
/// face, finite positions.
pub fn check_raw(raw: &RawMesh) -> Result<(), String> {
    let nf = raw.face_count();
    let nc = raw.face_vertices.len();
    if raw.face_offsets.is_empty() {
        if nc != 0 {
            return Err("face offsets are missing".into());
        }
    } else if raw.face_offsets[0] != 0 || raw.face_offsets[nf] as usize != nc {
        return Err("face offsets must start at 0 and end at the number of corners".into());
    }
    if let Some(f) = raw.face_offsets.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!("face {f} has no corners (or the offsets decrease)"));
    }
    if !raw.holes.is_empty() && raw.holes.len() != nf {
        return Err(format!("{} hole flags for {nf} faces", raw.holes.len()));
    }
    let nv = raw.positions.len();
    NonFinite::check("vertex", &raw.positions).map_err(|e| e.to_string())?;
    if let Some(&v) = raw.face_vertices.iter().find(|&&v| v as usize >= nv) {
        return Err(format!(
            "a face refers to vertex {v}, but there are only {nv} vertices"
        ));
    }
    if let Some(e) = raw
        .edges
        .iter()
        .position(|e| e.iter().any(|&c| c as usize >= nc))
    {
        return Err(format!("edge {e} names a corner past the last of {nc}"));
    }
    Ok(())
}

/// Writes a [`RawMesh`] as `.dlfl`. Fails with
/// [`io::ErrorKind::InvalidInput`] if [`check_raw`] rejects it.
pub fn write<W: Write>(w: W, raw: &RawMesh) -> io::Result<()> {
    check_raw(raw).map_err(crate::invalid_input)?;
    let mut out = Lines::new(w, b"# written by holey\ndlfl 1\n");
    out.points(b"v ", &raw.positions)?;
    let faces = (0..raw.face_count()).map(|f| raw.face(f));
    out.faces(faces, 0, |b, f, _| {
        b.push(if raw.is_hole(f) { b'h' } else { b'f' });
    })?;
    for &[a, b] in &raw.edges {
        out.line(|buf| {
            buf.push(b'e');
            for g in [a, b] {
                // check_raw guarantees g is a corner, so some face holds it.
                let f = raw
                    .face_offsets
                    .partition_point(|&o| o <= g)
                    .saturating_sub(1);
                buf.push(b' ');
                push_u64(buf, f as u64);
                buf.push(b':');
                push_u64(buf, u64::from(g - raw.face_offsets[f]));
            }
        })?;
    }
    out.finish()
}

#[cfg(test)]
mod tests {
    use holey_dlfl::Mesh;

    use super::*;

    fn err(text: &str) -> String {
        parse(text.as_bytes(), "m.dlfl").unwrap_err().to_string()
    }

    /// Faces as vertex lists, corners as (face, k), built by hand:
    /// - a point-sphere (one corner, no edge);
    /// - a self-loop on a sphere: faces [a] and [a], edge 1:0–2:0;
    /// - a two-gon sphere with two edges between b and c (multi-edges):
    ///   faces [b, c] and [c, b], edges 3:0–4:0 and 3:1–4:1;
    /// - a triangle with a hole: faces [d, e, f] and hole [f, e, d].
    fn special() -> RawMesh {
        let positions = (0..7)
            .map(|i| DVec3::new(f64::from(i) * 0.1, 1.0 / 3.0, -f64::from(i)))
            .collect();
        let faces: [&[u32]; 7] = [&[0], &[1], &[1], &[2, 3], &[3, 2], &[4, 5, 6], &[6, 5, 4]];
        let mut face_offsets = vec![0u32];
        let mut face_vertices = Vec::new();
        for f in faces {
            face_vertices.extend_from_slice(f);
            face_offsets.push(face_vertices.len() as u32);
        }
        // Global corners: f0:0=0, f1:0=1, f2:0=2, f3=3,4, f4=5,6, f5=7,8,9, f6=10,11,12.
        let edges = vec![[1, 2], [3, 5], [4, 6], [7, 11], [8, 10], [9, 12]];
        RawMesh {
            positions,
            face_offsets,
            face_vertices,
            holes: vec![false, false, false, false, false, false, true],
            edges,
        }
    }

    #[test]
    fn special_mesh_round_trips_and_stays_valid() {
        let raw = special();
        Mesh::from_raw(&raw).unwrap();
        let mut out = Vec::new();
        write(&mut out, &raw).unwrap();
        let text = String::from_utf8(out.clone()).unwrap();
        assert!(text.starts_with("# written by holey\ndlfl 1\n"), "{text}");
        assert!(text.contains("\nh 6 5 4\n"), "{text}");
        assert!(text.contains("\ne 1:0 2:0\n"), "{text}");
        let back = parse(&out, "rt.dlfl").unwrap();
        assert_eq!(back.face_offsets, raw.face_offsets);
        assert_eq!(back.face_vertices, raw.face_vertices);
        assert_eq!(back.holes, raw.holes);
        assert_eq!(back.edges, raw.edges);
        crate::assert_positions_bit_exact(&back.positions, &raw.positions);
        Mesh::from_raw(&back).unwrap();
        // And through the kernel and back out.
        let again = Mesh::from_raw(&back).unwrap().to_raw();
        let mut out2 = Vec::new();
        write(&mut out2, &again).unwrap();
        Mesh::from_raw(&parse(&out2, "rt2.dlfl").unwrap()).unwrap();
    }

    #[test]
    fn reads_the_example_of_the_spec_style() {
        let text = "# a tetrahedron\n\ndlfl 1   # header\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
                    f 0 2 1\nf 0 1 3\nf 1 2 3\nf 0 3 2 # last\n";
        let raw = parse(text.as_bytes(), "t.dlfl").unwrap();
        assert!(raw.edges.is_empty());
        assert!(raw.holes.is_empty());
        assert_eq!(raw.face_count(), 4);
        let with_edges =
            format!("{text}e 0:0 3:2\ne 0:1 2:0\ne 0:2 1:0\ne 1:1 2:2\ne 1:2 3:0\ne 2:1 3:1\n");
        let raw = parse(with_edges.as_bytes(), "t.dlfl").unwrap();
        assert_eq!(raw.edges.len(), 6);
        Mesh::from_raw(&raw).unwrap();
    }

    #[test]
    fn errors_name_the_line() {
        let head = "dlfl 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let e = |body: &str| err(&format!("{head}{body}"));
        assert_eq!(
            err("dlfl 2\n"),
            "m.dlfl:1: unsupported .dlfl version \"2\" (this reader knows 1)"
        );
        assert_eq!(
            err("# c\nv 0 0 0\n"),
            "m.dlfl:2: expected the header \"dlfl 1\""
        );
        for (input, want) in [
            ("v 1 x 0\n", "m.dlfl:5: bad number \"x\""),
            (
                "v 1 0 nan\n",
                "m.dlfl:5: coordinate \"nan\" is not a finite number",
            ),
            (
                "f 0 1 2\nf 2 1 7\n",
                "m.dlfl:6: face refers to vertex 7, but only 3 vertices are defined",
            ),
            ("f 0 1\n", "m.dlfl:4: vertex 2 is not used by any face"),
            ("f\n", "m.dlfl:5: a face needs at least one corner"),
            ("f 0 1 2\nq 1\n", "m.dlfl:6: unknown statement \"q\""),
            ("f 0 1 2 x\n", "m.dlfl:5: bad vertex number \"x\""),
            (
                "v 1 2 3 4\n",
                "m.dlfl:5: unexpected \"4\" at the end of the line",
            ),
        ] {
            assert_eq!(e(input), want, "{input:?}");
        }
        let tri = "f 0 1 2\nf 2 1 0\n";
        for (input, want) in [
            (
                "e 0:0 1:1\ne 0-1 1:0\n",
                "m.dlfl:8: bad corner \"0-1\" (expected face:corner)",
            ),
            (
                "e 0:0 2:1\n",
                "m.dlfl:7: edge names face 2, but there are only 2 faces",
            ),
            (
                "e 0:0 1:3\n",
                "m.dlfl:7: edge names corner 1:3, but face 1 has only 3 corner(s)",
            ),
            (
                "e 0:0 1:1\ne 1:1 0:0\n",
                "m.dlfl:8: corner 1:1 starts a second edge (the first is on line 7)",
            ),
            (
                "e 0:0 1:0\n",
                "m.dlfl:7: the edge's sides do not run oppositely between the same two vertices (0→1 and 2→1)",
            ),
            (
                "e 0:0 1:1\ne 0:1 1:0\n",
                "m.dlfl:5: corner 0:2 starts no edge (no \"e\" line names it)",
            ),
        ] {
            assert_eq!(e(&format!("{tri}{input}")), want, "{input:?}");
        }
    }

    #[test]
    fn writer_rejects_malformed_raw_meshes() {
        let mut raw = special();
        raw.edges.push([0, 99]);
        assert!(check_raw(&raw).unwrap_err().contains("edge 6"));
        let mut raw = special();
        raw.holes.pop();
        assert!(check_raw(&raw).is_err());
        let mut raw = special();
        raw.face_offsets[1] = 0;
        assert!(check_raw(&raw).is_err());
        assert!(check_raw(&RawMesh::default()).is_ok());
        let mut out = Vec::new();
        write(&mut out, &RawMesh::default()).unwrap();
        let back = parse(&out, "e.dlfl").unwrap();
        assert_eq!(back.face_count(), 0);
    }
}
