//! A byte cursor for the line-oriented text formats, and number parsing.
//!
//! Everything works on the raw bytes of the file: no line is copied into a
//! `String`, tokens are sub-slices, and only the final number conversion
//! looks at text (floats go through the standard library's exact,
//! correctly rounded parser so coordinates read back bit for bit).

/// Position in a text buffer with the current 1-based line number.
pub(crate) struct Cursor<'a> {
    b: &'a [u8],
    pos: usize,
    line: usize,
    /// `\` at the end of a line joins it with the next (OBJ).
    continuation: bool,
    /// `#` starts a comment running to the end of the line.
    comments: bool,
}

/// Horizontal whitespace, and the other control characters that can only
/// separate tokens. `\n` is not among them: it ends a line.
#[inline]
fn is_blank(c: u8) -> bool {
    c <= b' ' && c != b'\n'
}

impl<'a> Cursor<'a> {
    pub(crate) fn new(b: &'a [u8], continuation: bool, comments: bool) -> Self {
        Cursor {
            b,
            pos: 0,
            line: 1,
            continuation,
            comments,
        }
    }

    /// Starts at byte `pos`, which is on line `line`.
    pub(crate) fn at(b: &'a [u8], pos: usize, line: usize, comments: bool) -> Self {
        Cursor {
            b,
            pos: pos.min(b.len()),
            line,
            continuation: false,
            comments,
        }
    }

    /// The current line number (1-based).
    #[inline]
    pub(crate) fn line(&self) -> usize {
        self.line
    }

    /// The byte offset of the cursor.
    #[inline]
    pub(crate) fn pos(&self) -> usize {
        self.pos
    }

    #[inline]
    pub(crate) fn eof(&self) -> bool {
        self.pos >= self.b.len()
    }

    /// If the cursor is on a `\` that ends its line, the length of that
    /// backslash plus line break.
    #[inline]
    fn continuation_len(&self, at: usize) -> Option<usize> {
        match self.b.get(at + 1..) {
            Some([b'\n', ..]) => Some(2),
            Some([b'\r', b'\n', ..]) => Some(3),
            _ => None,
        }
    }

    /// Skips blanks (and line continuations) within the current line.
    #[inline]
    pub(crate) fn skip_blanks(&mut self) {
        while let Some(&c) = self.b.get(self.pos) {
            if is_blank(c) {
                self.pos += 1;
            } else if c == b'\\' && self.continuation {
                match self.continuation_len(self.pos) {
                    Some(n) => {
                        self.pos += n;
                        self.line += 1;
                    }
                    None => return,
                }
            } else {
                return;
            }
        }
    }

    /// After [`skip_blanks`](Self::skip_blanks): true at the end of the
    /// line's content (a line break, a comment or the end of the file).
    #[inline]
    pub(crate) fn at_eol(&self) -> bool {
        match self.b.get(self.pos) {
            None | Some(b'\n') => true,
            Some(b'#') => self.comments,
            Some(_) => false,
        }
    }

    /// Moves to the start of the next line, skipping whatever is left of
    /// this one (honouring continuations outside comments).
    pub(crate) fn next_line(&mut self) {
        let mut in_comment = false;
        while let Some(&c) = self.b.get(self.pos) {
            self.pos += 1;
            match c {
                b'\n' => {
                    self.line += 1;
                    return;
                }
                b'#' if self.comments => in_comment = true,
                b'\\' if self.continuation && !in_comment => {
                    if let Some(n) = self.continuation_len(self.pos - 1) {
                        self.pos += n - 1;
                        self.line += 1;
                    }
                }
                _ => {}
            }
        }
    }

    /// The next token on the current line, or `None` at the end of the
    /// line. A token runs to the next blank, line break, comment or line
    /// continuation.
    #[inline]
    pub(crate) fn token(&mut self) -> Option<&'a [u8]> {
        self.skip_blanks();
        if self.at_eol() {
            return None;
        }
        let start = self.pos;
        while let Some(&c) = self.b.get(self.pos) {
            // Fast path: digits, letters and `+-./` all sort above `#`.
            if c > b'#' && c != b'\\' {
                self.pos += 1;
                continue;
            }
            if self.ends_token(self.pos) {
                break;
            }
            self.pos += 1;
        }
        Some(&self.b[start..self.pos])
    }

    /// True if a token cannot go on at byte `at`.
    #[inline]
    fn ends_token(&self, at: usize) -> bool {
        match self.b.get(at) {
            None => true,
            Some(&c) => {
                c <= b' '
                    || (c == b'#' && self.comments)
                    || (c == b'\\' && self.continuation && self.continuation_len(at).is_some())
            }
        }
    }

    /// The next token read as a finite float: `None` at the end of the
    /// line, `Some(Err(message))` if it is not one (see [`parse_finite`]).
    /// Plain short decimals are converted while scanning (one pass over the
    /// bytes); anything else goes through the general parser.
    #[inline]
    pub(crate) fn float(&mut self) -> Option<Result<f64, String>> {
        self.skip_blanks();
        if self.at_eol() {
            return None;
        }
        if let Some((x, end)) = scan_short_decimal(self.b, self.pos)
            && self.ends_token(end)
        {
            self.pos = end;
            return Some(Ok(x));
        }
        let tok = self.token()?;
        Some(parse_finite(tok))
    }

    /// The next three tokens as a point's finite coordinates (each read by
    /// [`Cursor::float`]); the error names how many there were when the
    /// line ends early, or what is wrong with the first bad one.
    pub(crate) fn point(&mut self) -> Result<holey_mesh::DVec3, String> {
        let mut xyz = [0.0; 3];
        for (k, slot) in xyz.iter_mut().enumerate() {
            *slot = self
                .float()
                .ok_or_else(|| format!("vertex has {k} coordinate(s), but 3 are needed"))??;
        }
        Ok(holey_mesh::DVec3::from_array(xyz))
    }

    /// The next token read as an OBJ face corner (`v`, `v/vt`, `v//vn`,
    /// `v/vt/vn`): the optionally signed integer before the first `/`,
    /// converted while scanning; the texture and normal parts are skipped
    /// unread. `None` at the end of the line, `Some(Err(token))` if the
    /// vertex part is not an integer or overflows.
    #[inline]
    pub(crate) fn corner_index(&mut self) -> Option<Result<i64, &'a [u8]>> {
        self.skip_blanks();
        if self.at_eol() {
            return None;
        }
        let start = self.pos;
        let b = self.b;
        let mut i = start;
        let neg = b[i] == b'-';
        if neg || b[i] == b'+' {
            i += 1;
        }
        let first = i;
        let mut v: i64 = 0;
        while let Some(&c) = b.get(i) {
            let d = c.wrapping_sub(b'0');
            if d > 9 {
                break;
            }
            // 18 digits cannot overflow an i64; more are rejected below.
            v = v.wrapping_mul(10).wrapping_add(i64::from(d));
            i += 1;
        }
        if i - first > 18 {
            return Some(Err(self.token().unwrap_or(&b[start..i])));
        }
        let digits = i > first;
        if digits && self.ends_token(i) {
            self.pos = i;
            return Some(Ok(if neg { -v } else { v }));
        }
        if digits && b[i] == b'/' {
            self.pos = i;
            self.token(); // the rest of the corner, unread
            return Some(Ok(if neg { -v } else { v }));
        }
        Some(Err(self.token().unwrap_or(&b[start..i])))
    }

    /// The rest of the current line (without its line break), for free
    /// text such as an STL solid's name. Moves to the next line.
    pub(crate) fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        let end = self.b[start..]
            .iter()
            .position(|&c| c == b'\n')
            .map_or(self.b.len(), |k| start + k);
        self.pos = end;
        self.next_line();
        &self.b[start..end]
    }

    /// Skips blank lines and comment lines; stops at the first byte of the
    /// next line with content, or at the end of the file.
    pub(crate) fn skip_empty_lines(&mut self) {
        loop {
            self.skip_blanks();
            if self.eof() || !self.at_eol() {
                return;
            }
            self.next_line();
        }
    }

    /// Moves to the next line with content and reads its first token (the
    /// statement's keyword), with that line's number; `None` at the end of
    /// the file. The line-by-line readers (`.dlfl`, ASCII STL) start each
    /// statement this way, so blank and comment lines are skipped alike.
    pub(crate) fn next_statement(&mut self) -> Option<(usize, &'a [u8])> {
        self.skip_empty_lines();
        if self.eof() {
            return None;
        }
        let line = self.line();
        self.token().map(|keyword| (line, keyword))
    }
}

/// Ends the face whose corners were just pushed to `indices` by pushing its
/// end offset, or says why not: the polygon readers (OBJ, OFF, PLY) keep
/// 32-bit offsets and refuse corners that outgrow them in the same words.
pub(crate) fn push_face_end(offsets: &mut Vec<u32>, indices: &[u32]) -> Result<(), &'static str> {
    let end =
        u32::try_from(indices.len()).map_err(|_| "too many face corners for 32-bit indices")?;
    offsets.push(end);
    Ok(())
}

/// Parses a decimal float (the standard library's syntax: `1`, `-2.5`,
/// `.5`, `1e-3`, and also `inf` and `nan`, which callers reject).
#[inline]
pub(crate) fn parse_f64(tok: &[u8]) -> Option<f64> {
    if let Some(x) = parse_short_decimal(tok) {
        return Some(x);
    }
    std::str::from_utf8(tok).ok()?.parse().ok()
}

/// Exact powers of ten up to 10^15.
const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

/// The fast path for the plain decimals most files hold (`-0.123456`):
/// with at most 15 digits and no exponent, the digits form an integer
/// `m < 2^53` and the value is `m / 10^k` with `k <= 15`; both operands are
/// exact in `f64`, so the one correctly rounded division gives exactly the
/// correctly rounded value of the decimal (Clinger's fast path). Anything
/// else returns `None` and goes to the general parser.
#[inline]
fn parse_short_decimal(tok: &[u8]) -> Option<f64> {
    scan_short_decimal(tok, 0).and_then(|(x, end)| (end == tok.len()).then_some(x))
}

/// Scans a plain decimal (`[+-]digits[.digits]`, at most 15 digits) from
/// `b[start..]` and returns its value and where it stopped; see
/// [`parse_short_decimal`] for why the value is exact.
#[inline]
fn scan_short_decimal(b: &[u8], start: usize) -> Option<(f64, usize)> {
    let (neg, mut i) = match b.get(start) {
        Some(b'-') => (true, start + 1),
        Some(b'+') => (false, start + 1),
        _ => (false, start),
    };
    let mut m: u64 = 0;
    let mut digits = 0usize;
    let mut frac: Option<usize> = None;
    while let Some(&c) = b.get(i) {
        let d = c.wrapping_sub(b'0');
        if d <= 9 {
            if digits == 15 {
                return None;
            }
            m = m * 10 + u64::from(d);
            digits += 1;
        } else if c == b'.' && frac.is_none() {
            frac = Some(digits);
        } else {
            break;
        }
        i += 1;
    }
    if digits == 0 {
        return None;
    }
    let k = frac.map_or(0, |at| digits - at);
    let x = m as f64 / POW10[k];
    Some((if neg { -x } else { x }, i))
}

/// Parses a finite decimal float; the error says what was wrong with it.
#[inline]
pub(crate) fn parse_finite(tok: &[u8]) -> Result<f64, String> {
    match parse_f64(tok) {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(format!(
            "coordinate \"{}\" is not a finite number",
            crate::error::show(tok)
        )),
        None => Err(format!("bad number \"{}\"", crate::error::show(tok))),
    }
}

/// Parses an optionally signed decimal integer. `None` if it is not one
/// or does not fit in an `i64`.
#[inline]
pub(crate) fn parse_i64(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, tok),
    };
    let magnitude = parse_digits(digits)?;
    if neg {
        // Subtracting the magnitude from 0 reaches i64::MIN too.
        0i64.checked_sub_unsigned(magnitude)
    } else {
        i64::try_from(magnitude).ok()
    }
}

/// Parses an unsigned decimal integer (an optional `+` allowed).
#[inline]
pub(crate) fn parse_u64(tok: &[u8]) -> Option<u64> {
    parse_digits(tok.strip_prefix(b"+").unwrap_or(tok))
}

/// Parses one or more decimal digits and nothing else, for both integer
/// parsers. `None` if any byte is not a digit, there is none, or the
/// value does not fit in a `u64`.
#[inline]
fn parse_digits(digits: &[u8]) -> Option<u64> {
    if digits.is_empty() {
        return None;
    }
    let mut v: u64 = 0;
    for &c in digits {
        let d = c.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        v = v.checked_mul(10)?.checked_add(u64::from(d))?;
    }
    Some(v)
}

/// The one writer loop of the text formats: lines built in one buffer
/// and handed to the writer a chunk ([`crate::CHUNK`]) at a time.
pub(crate) struct Lines<W: std::io::Write> {
    out: W,
    buf: Vec<u8>,
}

impl<W: std::io::Write> Lines<W> {
    /// Starts with the file's `head` (its first lines, newlines included).
    pub(crate) fn new(out: W, head: &[u8]) -> Self {
        let mut buf = Vec::with_capacity(crate::CHUNK + 256);
        buf.extend_from_slice(head);
        Lines { out, buf }
    }

    /// One line: `fill` appends its text, the newline follows.
    pub(crate) fn line(&mut self, fill: impl FnOnce(&mut Vec<u8>)) -> std::io::Result<()> {
        fill(&mut self.buf);
        self.buf.push(b'\n');
        crate::flush_full(&mut self.out, &mut self.buf)
    }

    /// One line per position: `prefix` (OBJ's and .dlfl's `v `, nothing
    /// in OFF), then its coordinates.
    pub(crate) fn points(
        &mut self,
        prefix: &[u8],
        positions: &[holey_mesh::DVec3],
    ) -> std::io::Result<()> {
        for &p in positions {
            self.line(|b| {
                b.extend_from_slice(prefix);
                push_point(b, p);
            })?;
        }
        Ok(())
    }

    /// One line per face: `lead` writes what precedes the vertex indices
    /// (given the face's number and its indices: OBJ's `f`, OFF's count,
    /// .dlfl's `f` or `h`), then the indices plus `base`.
    pub(crate) fn faces<'f>(
        &mut self,
        faces: impl IntoIterator<Item = &'f [u32]>,
        base: u64,
        mut lead: impl FnMut(&mut Vec<u8>, usize, &[u32]),
    ) -> std::io::Result<()> {
        for (i, face) in faces.into_iter().enumerate() {
            self.line(|b| {
                lead(b, i, face);
                push_indices(b, face, base);
            })?;
        }
        Ok(())
    }

    /// Writes what is left and flushes.
    pub(crate) fn finish(mut self) -> std::io::Result<()> {
        self.out.write_all(&self.buf)?;
        self.out.flush()
    }
}

/// Appends the three coordinates of `p`, each as [`push_f64`] writes it,
/// separated by spaces.
fn push_point(out: &mut Vec<u8>, p: holey_mesh::DVec3) {
    push_f64(out, p.x);
    out.push(b' ');
    push_f64(out, p.y);
    out.push(b' ');
    push_f64(out, p.z);
}

/// Appends `x` as the shortest decimal that reads back to the same `f64`,
/// with no trailing `.0` on integers (`1`, `-0.5`, `1e-7`, `1.5e300`).
pub(crate) fn push_f64(out: &mut Vec<u8>, x: f64) {
    use std::io::Write;
    // `{:?}` is the shortest round-trip form and switches to exponent
    // notation for very large and very small magnitudes, where `{}` would
    // print hundreds of digits. Writing to a Vec cannot fail.
    let start = out.len();
    let _ = write!(out, "{x:?}");
    if out[start..].ends_with(b".0") {
        out.truncate(out.len() - 2);
    }
}

/// Appends ` i` for every vertex index `i` of `face`, plus `base` (1 for
/// OBJ's numbering from one).
fn push_indices(out: &mut Vec<u8>, face: &[u32], base: u64) {
    for &i in face {
        out.push(b' ');
        push_u64(out, u64::from(i) + base);
    }
}

/// Appends a decimal unsigned integer.
#[inline]
pub(crate) fn push_u64(out: &mut Vec<u8>, mut n: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&buf[i..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_lines_and_continuations() {
        let text = b"v 1 2\\\n 3 # c\r\nf 1/2 -3\\\r\n  4\n\n# x\nlast";
        let mut c = Cursor::new(text, true, true);
        assert_eq!(c.token(), Some(&b"v"[..]));
        assert_eq!(c.token(), Some(&b"1"[..]));
        assert_eq!(c.token(), Some(&b"2"[..]));
        assert_eq!(c.token(), Some(&b"3"[..]));
        assert_eq!(c.line(), 2);
        assert_eq!(c.token(), None);
        c.next_line();
        assert_eq!(c.line(), 3);
        assert_eq!(c.token(), Some(&b"f"[..]));
        assert_eq!(c.token(), Some(&b"1/2"[..]));
        assert_eq!(c.token(), Some(&b"-3"[..]));
        assert_eq!(c.token(), Some(&b"4"[..]));
        assert_eq!(c.token(), None);
        c.next_line();
        c.skip_empty_lines();
        assert_eq!(c.line(), 7);
        assert_eq!(c.token(), Some(&b"last"[..]));
        assert_eq!(c.token(), None);
        c.next_line();
        assert!(c.eof());
    }

    #[test]
    fn points_take_three_finite_coordinates() {
        let mut c = Cursor::new(b"1 -2.5 3e2 # c\n0.5 1\n1 nan 0\n1 x 0\n", false, true);
        assert_eq!(c.point(), Ok(holey_mesh::DVec3::new(1.0, -2.5, 300.0)));
        assert_eq!(c.token(), None);
        c.next_line();
        assert_eq!(
            c.point(),
            Err("vertex has 2 coordinate(s), but 3 are needed".to_string())
        );
        c.next_line();
        assert_eq!(
            c.point(),
            Err("coordinate \"nan\" is not a finite number".to_string())
        );
        c.next_line();
        assert_eq!(c.point(), Err("bad number \"x\"".to_string()));
    }

    #[test]
    fn integers() {
        assert_eq!(parse_i64(b"-12"), Some(-12));
        assert_eq!(parse_i64(b"+7"), Some(7));
        assert_eq!(parse_i64(b"-9223372036854775808"), Some(i64::MIN));
        assert_eq!(parse_i64(b"9223372036854775808"), None);
        assert_eq!(parse_i64(b"-9223372036854775809"), None);
        assert_eq!(parse_i64(b"-+5"), None);
        assert_eq!(parse_i64(b"-"), None);
        assert_eq!(parse_i64(b"1.5"), None);
        assert_eq!(parse_u64(b"18446744073709551615"), Some(u64::MAX));
        assert_eq!(parse_u64(b"18446744073709551616"), None);
        assert_eq!(parse_u64(b"-1"), None);
    }

    #[test]
    fn short_decimals_match_the_standard_parser() {
        let mut rng = holey_testkit::Rng::new(7);
        let mut cases: Vec<String> = [
            "0",
            "-0",
            "-0.0",
            "+1.5",
            ".5",
            "5.",
            "123456789012345",
            "0.000000000000001",
            "999999999999999",
            "1234567890123456",
            "0.1",
            "0.3",
            "-2.675",
            "1.",
            "00012.50",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        for _ in 0..20000 {
            let digits = 1 + rng.below(15);
            let mut s: String = (0..digits)
                .map(|_| char::from(b'0' + rng.below(10) as u8))
                .collect();
            s.insert(rng.below(digits + 1), '.');
            if rng.chance(0.5) {
                s.insert(0, '-');
            }
            cases.push(s);
        }
        for s in cases {
            let std: f64 = s.parse().unwrap();
            let ours = parse_f64(s.as_bytes()).unwrap();
            assert_eq!(ours.to_bits(), std.to_bits(), "{s}");
        }
        for bad in ["", ".", "-", "1..2", "1-2", "--1", "1e", "x"] {
            assert_eq!(parse_short_decimal(bad.as_bytes()), None, "{bad}");
            assert_eq!(parse_f64(bad.as_bytes()), None, "{bad}");
        }
    }

    #[test]
    fn floats_print_shortest_and_read_back() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -2.0,
            0.1,
            1.0 / 3.0,
            1e-300,
            1.5e300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            123456789.0,
        ] {
            let mut out = Vec::new();
            push_f64(&mut out, x);
            let back = parse_f64(&out).unwrap();
            assert_eq!(
                back.to_bits(),
                x.to_bits(),
                "{}",
                String::from_utf8_lossy(&out)
            );
        }
        let mut out = Vec::new();
        push_f64(&mut out, 1.0);
        assert_eq!(out, b"1");
        let mut out = Vec::new();
        push_u64(&mut out, 0);
        push_u64(&mut out, 1234567);
        assert_eq!(out, b"01234567");
    }
}
