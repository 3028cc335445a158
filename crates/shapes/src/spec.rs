//! The table of primitives, spec parsing and the help text.

use std::fmt;
use std::sync::OnceLock;

use holey_mesh::PolyMesh;

use crate::{MAX_FACES, ShapeError};

/// The type, default and range of one primitive parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamKind {
    /// A decimal integer in `min..=max`. `capped` says that `max` comes
    /// from [`MAX_FACES`] rather than from geometry.
    Int {
        /// The value used when the parameter is left out or empty.
        default: u32,
        /// The smallest accepted value.
        min: u32,
        /// The largest accepted value.
        max: u32,
        /// Whether `max` is set by the face limit; out-of-range messages
        /// then say so.
        capped: bool,
    },
    /// A finite decimal number greater than 0 and at most `max`.
    Real {
        /// The value used when the parameter is left out or empty.
        default: f64,
        /// The largest accepted value.
        max: f64,
    },
}

impl ParamKind {
    /// The default as the number passed to the generator.
    pub fn default_value(&self) -> f64 {
        match *self {
            ParamKind::Int { default, .. } => f64::from(default),
            ParamKind::Real { default, .. } => default,
        }
    }

    /// The range in words, e.g. "an integer from 0 to 9".
    pub fn range_text(&self) -> String {
        match *self {
            ParamKind::Int { min, max, .. } => format!("an integer from {min} to {max}"),
            ParamKind::Real { max, .. } => format!("a number greater than 0 and at most {max}"),
        }
    }

    fn contains(&self, value: f64) -> bool {
        match *self {
            ParamKind::Int { min, max, .. } => {
                value.fract() == 0.0 && value >= f64::from(min) && value <= f64::from(max)
            }
            ParamKind::Real { max, .. } => value.is_finite() && value > 0.0 && value <= max,
        }
    }
}

/// One positional parameter of a primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// Short name used in usage lines and error messages.
    pub name: &'static str,
    /// Its type, default and accepted range.
    pub kind: ParamKind,
    /// What the parameter means.
    pub doc: &'static str,
}

/// One built-in primitive: its names, parameters and documentation, and
/// its generator.
#[derive(Clone, Copy, Debug)]
pub struct Primitive {
    /// The canonical name, written after the `@`.
    pub name: &'static str,
    /// One line for lists.
    pub summary: &'static str,
    /// Other accepted names.
    pub aliases: &'static [&'static str],
    /// Positional parameters, all optional.
    pub params: &'static [Param],
    /// Shape, size and position.
    pub description: &'static str,
    /// Vertex, edge and face counts as formulas in the parameters.
    pub counts: &'static str,
    /// The order of vertices and faces and where each face starts.
    pub order: &'static str,
    face_count: fn(&[f64]) -> u128,
    /// A constraint between parameters: the reason they do not fit.
    conflict: fn(&[f64]) -> Option<String>,
    build: fn(&[f64]) -> Result<PolyMesh, ShapeError>,
}

impl Primitive {
    /// The usage line, e.g. `@torus[:major[:minor[:R[:r]]]]`.
    pub fn usage(&self) -> String {
        let mut s = format!("@{}", self.name);
        for p in self.params {
            s.push_str("[:");
            s.push_str(p.name);
        }
        s.push_str(&"]".repeat(self.params.len()));
        s
    }

    /// The default value of every parameter.
    pub fn defaults(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.kind.default_value()).collect()
    }

    /// Whether `name` (case-insensitive, ignoring `-` and `_`) names this
    /// primitive.
    pub fn is_called(&self, name: &str) -> bool {
        let n = normalize(name);
        std::iter::once(&self.name)
            .chain(self.aliases)
            .any(|a| normalize(a) == n)
    }
}

/// A parsed, validated primitive spec: the primitive and the value of
/// every parameter (integers as exact `f64`s). Its `Display` is the
/// canonical spec with all parameters, e.g. `@torus:24:12:1:0.4`.
#[derive(Clone, Debug)]
pub struct PrimitiveSpec {
    primitive: &'static Primitive,
    args: Vec<f64>,
}

impl PrimitiveSpec {
    /// The primitive.
    pub fn primitive(&self) -> &'static Primitive {
        self.primitive
    }

    /// The value of every parameter, defaults filled in.
    pub fn args(&self) -> &[f64] {
        &self.args
    }

    /// Generates the mesh.
    pub fn build(&self) -> Result<PolyMesh, ShapeError> {
        (self.primitive.build)(&self.args)
    }

    /// The number of faces [`PrimitiveSpec::build`] will produce.
    pub fn face_count(&self) -> u128 {
        (self.primitive.face_count)(&self.args)
    }
}

impl PartialEq for PrimitiveSpec {
    fn eq(&self, other: &Self) -> bool {
        self.primitive.name == other.primitive.name && self.args == other.args
    }
}

impl fmt::Display for PrimitiveSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&spec_string(self.primitive, &self.args))
    }
}

/// Whether a command-line argument names a primitive rather than a file
/// (it starts with `@`).
pub fn is_primitive_spec(arg: &str) -> bool {
    arg.starts_with('@')
}

/// Builds the mesh for a spec such as `@cube`, `@sphere:4` or
/// `@torus:48:24:1:0.25`; see the crate documentation for the grammar.
/// Never panics; every problem is a [`ShapeError`] with a message for
/// users.
pub fn parse_primitive(spec: &str) -> Result<PolyMesh, ShapeError> {
    parse_spec(spec)?.build()
}

/// Parses and validates a spec without generating the mesh.
pub fn parse_spec(spec: &str) -> Result<PrimitiveSpec, ShapeError> {
    let Some(rest) = spec.strip_prefix('@') else {
        return Err(ShapeError::MissingAt {
            spec: spec.to_owned(),
        });
    };
    let mut fields = rest.split(':');
    let name = fields.next().unwrap_or_default();
    if name.is_empty() {
        return Err(ShapeError::MissingName);
    }
    let primitive = find_primitive(name).ok_or_else(|| ShapeError::UnknownName {
        name: name.to_owned(),
    })?;
    let texts: Vec<&str> = fields.collect();
    if texts.len() > primitive.params.len() {
        return Err(ShapeError::TooManyParameters {
            primitive: primitive.name,
            usage: primitive.usage(),
            max: primitive.params.len(),
            given: texts.len(),
        });
    }
    let mut args = primitive.defaults();
    for ((param, text), arg) in primitive.params.iter().zip(&texts).zip(&mut args) {
        if !text.is_empty() {
            *arg = parse_param(primitive, param, text)?;
        }
    }
    validate(primitive, &args)?;
    Ok(PrimitiveSpec { primitive, args })
}

/// The primitive called `name` (without the `@`; case-insensitive, `-`
/// and `_` ignored), if any.
pub fn find_primitive(name: &str) -> Option<&'static Primitive> {
    PRIMITIVES.iter().find(|p| p.is_called(name))
}

fn normalize(name: &str) -> String {
    name.chars()
        .filter(|&c| c != '-' && c != '_')
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

fn parse_param(
    primitive: &Primitive,
    param: &'static Param,
    text: &str,
) -> Result<f64, ShapeError> {
    let value = match param.kind {
        ParamKind::Int { .. } => match text.parse::<i64>() {
            // Integers this large are out of range anyway, so rounding
            // them to f64 does not matter.
            Ok(v) => v as f64,
            Err(_) => {
                let digits = text.strip_prefix(['+', '-']).unwrap_or(text);
                if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
                    return Err(out_of_range(primitive, param, text.to_owned()));
                }
                return Err(ShapeError::NotAnInteger {
                    primitive: primitive.name,
                    param: param.name,
                    value: text.to_owned(),
                });
            }
        },
        ParamKind::Real { .. } => {
            // Rust also parses "inf" and "NaN"; only accept digits,
            // signs, '.', and exponents.
            let plain = text
                .bytes()
                .all(|b| b.is_ascii_digit() || b"+-.eE".contains(&b));
            match text.parse::<f64>() {
                Ok(v) if plain && v.is_finite() => v,
                _ => {
                    return Err(ShapeError::NotANumber {
                        primitive: primitive.name,
                        param: param.name,
                        value: text.to_owned(),
                    });
                }
            }
        }
    };
    if param.kind.contains(value) {
        Ok(value)
    } else {
        Err(out_of_range(primitive, param, text.to_owned()))
    }
}

fn out_of_range(primitive: &Primitive, param: &Param, value: String) -> ShapeError {
    let note = match param.kind {
        ParamKind::Int {
            capped: true, max, ..
        } => format!(
            " ({} or more would give over {MAX_FACES} faces)",
            u64::from(max) + 1
        ),
        _ => String::new(),
    };
    ShapeError::OutOfRange {
        primitive: primitive.name,
        param: param.name,
        range: param.kind.range_text(),
        value,
        note,
    }
}

/// Checks every parameter's range and the face limit. Generators call
/// this first, so they also validate when called directly.
pub(crate) fn validate(primitive: &Primitive, args: &[f64]) -> Result<(), ShapeError> {
    if args.len() != primitive.params.len() {
        return Err(ShapeError::TooManyParameters {
            primitive: primitive.name,
            usage: primitive.usage(),
            max: primitive.params.len(),
            given: args.len(),
        });
    }
    for (param, &value) in primitive.params.iter().zip(args) {
        if !param.kind.contains(value) {
            return Err(out_of_range(primitive, param, value.to_string()));
        }
    }
    if let Some(message) = (primitive.conflict)(args) {
        return Err(ShapeError::Invalid {
            primitive: primitive.name,
            message,
        });
    }
    let faces = (primitive.face_count)(args);
    if faces > u128::from(MAX_FACES) {
        return Err(ShapeError::TooManyFaces {
            spec: spec_string(primitive, args),
            faces,
            limit: MAX_FACES,
        });
    }
    Ok(())
}

/// Checks `args` ([`validate`]) and builds the mesh: the public
/// generators are this with their own arguments.
pub(crate) fn generate(primitive: &Primitive, args: &[f64]) -> Result<PolyMesh, ShapeError> {
    validate(primitive, args)?;
    (primitive.build)(args)
}

fn spec_string(primitive: &Primitive, args: &[f64]) -> String {
    let mut s = format!("@{}", primitive.name);
    for a in args {
        s.push(':');
        s.push_str(&a.to_string());
    }
    s
}

/// The `k`th argument (validated, so in range) as an integer.
fn int(args: &[f64], k: usize) -> u32 {
    args.get(k).map_or(0, |&v| v as u32)
}

/// The `k`th argument as a wide integer, for face counts.
fn wide(args: &[f64], k: usize) -> u128 {
    u128::from(int(args, k))
}

fn real(args: &[f64], k: usize) -> f64 {
    args.get(k).copied().unwrap_or(f64::NAN)
}

/// "; known primitives: ..." for error messages.
pub(crate) fn known_list() -> String {
    PRIMITIVES
        .iter()
        .map(|p| format!("@{}", p.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// " (did you mean @x?)" when an unknown name is close to a known one.
pub(crate) fn suggestion(name: &str) -> String {
    let n = normalize(name);
    let mut best: Option<(usize, &str)> = None;
    for p in PRIMITIVES {
        for alias in std::iter::once(&p.name).chain(p.aliases) {
            let a = normalize(alias);
            let d = if a.starts_with(&n) && n.chars().count() >= 3 {
                0
            } else {
                edit_distance(&n, &a)
            };
            let limit = if n.chars().count() >= 5 { 2 } else { 1 };
            if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, p.name));
            }
        }
    }
    best.map(|(_, p)| format!(" (did you mean @{p}?)"))
        .unwrap_or_default()
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// The help text for all primitives (usage, parameters with defaults and
/// ranges, sizes, counts, vertex and face order), for `--help`.
pub fn primitive_help() -> &'static str {
    static HELP: OnceLock<String> = OnceLock::new();
    HELP.get_or_init(make_help)
}

/// One line per primitive (usage and summary), for short help.
pub fn primitive_summary() -> &'static str {
    static SUMMARY: OnceLock<String> = OnceLock::new();
    SUMMARY.get_or_init(|| {
        let mut out = String::new();
        for p in PRIMITIVES {
            let usage = format!("{:<32}", p.usage());
            wrap_hanging(&mut out, &usage, &" ".repeat(32), p.summary);
        }
        out
    })
}

const WIDTH: usize = 79;

fn make_help() -> String {
    let mut out = String::new();
    wrap(
        &mut out,
        "",
        &format!(
            "Built-in primitives can be used wherever an input mesh is expected: \
             @name or @name:p1:p2..., e.g. @cube, @sphere:4, @torus:48:24, \
             @torus::16. Parameters are positional and optional; a missing or \
             empty one takes its default. Names are case-insensitive and '-' \
             or '_' in them may be left out. Every primitive is welded and \
             consistently oriented, faces counter-clockwise seen from outside \
             (the planes are open and face +z), with at most {MAX_FACES} faces."
        ),
    );
    out.push('\n');
    wrap(
        &mut out,
        "",
        "The platonic solids are inscribed in the sphere of radius sqrt(3) \
         around the cube [-1,1]^3; round primitives have radius 1 and heights \
         and planes span [-1,1].",
    );
    for p in PRIMITIVES {
        out.push('\n');
        out.push_str(&p.usage());
        if !p.aliases.is_empty() {
            let aliases: Vec<String> = p.aliases.iter().map(|a| format!("@{a}")).collect();
            out.push_str(&format!("  (also {})", aliases.join(", ")));
        }
        out.push('\n');
        wrap(&mut out, "    ", p.description);
        for param in p.params {
            let range = match param.kind {
                ParamKind::Int {
                    default, min, max, ..
                } => {
                    format!("integer {min}..{max}, default {default}")
                }
                ParamKind::Real { default, max } => {
                    format!("number in (0, {max}], default {default}")
                }
            };
            let first = format!("    {:<10}", param.name);
            let text = format!("{}; {range}", param.doc);
            wrap_hanging(&mut out, &first, "              ", &text);
        }
        wrap(&mut out, "    ", &format!("Counts: {}", p.counts));
        wrap(&mut out, "    ", &format!("Order: {}", p.order));
    }
    out
}

fn wrap(out: &mut String, indent: &str, text: &str) {
    wrap_hanging(out, indent, indent, text);
}

/// Greedy word wrap at [`WIDTH`], `first` before the first line and
/// `rest` before the others.
fn wrap_hanging(out: &mut String, first: &str, rest: &str, text: &str) {
    let mut line = first.to_owned();
    let mut empty = true;
    for word in text.split_whitespace() {
        if !empty && line.chars().count() + 1 + word.chars().count() > WIDTH {
            out.push_str(line.trim_end());
            out.push('\n');
            line = rest.to_owned();
            empty = true;
        }
        if !empty {
            line.push(' ');
        }
        line.push_str(word);
        empty = false;
    }
    out.push_str(line.trim_end());
    out.push('\n');
}

// ---------------------------------------------------------------------
// The table.

/// Face-order rule shared by the platonic solids.
macro_rules! solid_order {
    () => {
        "Vertices in order of increasing z, then y, then x; faces in order of \
         their centres by the same rule (face 0 is the lowest). Each face runs \
         counter-clockwise seen from outside, starting at its lowest-numbered \
         vertex."
    };
}

/// An integer parameter whose maximum is set by [`MAX_FACES`].
const fn capped_param(
    name: &'static str,
    doc: &'static str,
    default: u32,
    min: u32,
    max: u32,
) -> Param {
    Param {
        name,
        kind: ParamKind::Int {
            default,
            min,
            max,
            capped: true,
        },
        doc,
    }
}

/// Largest and smallest allowed radius.
const MAX_RADIUS: f64 = 1e9;

/// Upper bound for `n` in 6·n² faces.
const CUBE_MAX_N: u32 = 1290;
/// Upper bound for the icosphere level: 20·4⁹ = 5 242 880 faces.
const SPHERE_MAX_LEVEL: u32 = 9;

pub(crate) const TETRAHEDRON: Primitive = Primitive {
    name: "tetrahedron",
    summary: "regular, corners alternate cube corners",
    aliases: &["tetra"],
    params: &[],
    description: "Regular tetrahedron inscribed in the sphere of radius sqrt(3): its corners \
                  are the alternate corners (1,-1,-1), (-1,1,-1), (-1,-1,1), (1,1,1) of the \
                  cube [-1,1]^3 (in this vertex order); edge 2*sqrt(2), volume 8/3.",
    counts: "V 4, E 6, F 4 triangles.",
    order: concat!(solid_order!(), " Face i is opposite vertex 3 - i."),
    face_count: |_| 4,
    conflict: |_| None,
    build: |_| Ok(crate::tetrahedron()),
};

pub(crate) const CUBE: Primitive = Primitive {
    name: "cube",
    summary: "[-1,1]^3, n x n quads per side",
    aliases: &["hexahedron"],
    params: &[capped_param(
        "n",
        "quads along each edge of each side",
        1,
        1,
        CUBE_MAX_N,
    )],
    description: "The cube [-1,1]^3 (edge 2, volume 8, circumradius sqrt(3)); for n > 1 \
                  each side is an n x n grid of quads.",
    counts: "V = 6n^2+2, E = 12n^2, F = 6n^2 quads (n = 1: 8, 12, 6).",
    order: "Vertices are the grid points of the surface in order of z, then y, then x, so \
            for n = 1 vertex i is at (2(i&1)-1, 2((i>>1)&1)-1, 2(i>>2)-1). Faces are \
            grouped by side in the order -z, -y, -x, +x, +y, +z (side s is faces \
            s*n^2 .. (s+1)*n^2-1); within a side, quads in order of their centres by \
            z, then y, then x. Each quad runs counter-clockwise seen from outside, \
            starting at its corner with the smallest coordinates (its lowest-numbered \
            vertex).",
    face_count: |a| 6 * wide(a, 0) * wide(a, 0),
    conflict: |_| None,
    build: |a| Ok(crate::grid::cube(int(a, 0))),
};

pub(crate) const OCTAHEDRON: Primitive = Primitive {
    name: "octahedron",
    summary: "regular, corners on the axes at sqrt(3)",
    aliases: &["octa"],
    params: &[],
    description: "Regular octahedron with corners (0,0,+-sqrt(3)), (0,+-sqrt(3),0), \
                  (+-sqrt(3),0,0) on the axes; circumradius sqrt(3), volume 4*sqrt(3).",
    counts: "V 6, E 12, F 8 triangles.",
    order: concat!(
        solid_order!(),
        " Vertex 0 is the bottom corner and 5 the top; face i lies in the octant of the \
         cube corner i of @cube."
    ),
    face_count: |_| 8,
    conflict: |_| None,
    build: |_| Ok(crate::octahedron()),
};

pub(crate) const DODECAHEDRON: Primitive = Primitive {
    name: "dodecahedron",
    summary: "regular, pentagons, circumradius sqrt(3)",
    aliases: &["dodeca"],
    params: &[],
    description: "Regular dodecahedron of pentagons, circumradius sqrt(3): the corners \
                  (+-1,+-1,+-1) of the cube [-1,1]^3 and the cyclic permutations of \
                  (0,+-1/phi,+-phi), phi = (1+sqrt(5))/2; edge 2/phi.",
    counts: "V 20, E 30, F 12 pentagons.",
    order: concat!(
        solid_order!(),
        " Faces 0 and 1 meet at the bottom edge 0-1 and faces 10 and 11 at the top edge \
         18-19, both parallel to y."
    ),
    face_count: |_| 12,
    conflict: |_| None,
    build: |_| Ok(crate::dodecahedron()),
};

pub(crate) const ICOSAHEDRON: Primitive = Primitive {
    name: "icosahedron",
    summary: "regular, circumradius sqrt(3)",
    aliases: &["icosa", "ico"],
    params: &[],
    description: "Regular icosahedron, circumradius sqrt(3): the cyclic permutations of \
                  (0,+-1,+-phi), phi = (1+sqrt(5))/2, scaled by sqrt(3)/sqrt(phi+2); \
                  edge 2*sqrt(3)/sqrt(phi+2) ~ 1.821.",
    counts: "V 12, E 30, F 20 triangles.",
    order: concat!(
        solid_order!(),
        " Vertices 0 and 1 form the bottom edge, parallel to y."
    ),
    face_count: |_| 20,
    conflict: |_| None,
    build: |_| Ok(crate::icosahedron()),
};

pub(crate) const SPHERE: Primitive = Primitive {
    name: "sphere",
    summary: "unit icosphere, 20*4^level triangles",
    aliases: &["icosphere"],
    params: &[capped_param(
        "level",
        "subdivision level",
        3,
        0,
        SPHERE_MAX_LEVEL,
    )],
    description: "Unit icosphere: the icosahedron scaled to radius 1 and subdivided level \
                  times, each triangle into four, new vertices projected onto the unit \
                  sphere.",
    counts: "V = 10*4^level+2, E = 30*4^level, F = 20*4^level triangles (level 3: 642, \
             1920, 1280).",
    order: "Level 0 is @icosahedron scaled to radius 1, in the same order. Each \
            subdivision replaces face t = (a,b,c) by faces 4t .. 4t+3 = (a,ab,ca), \
            (ab,b,bc), (ca,bc,c), (ab,bc,ca), where ab is the new vertex on edge a-b. Old \
            vertices keep their numbers; new ones follow in order of first use, visiting \
            faces in order and each face's edges a-b, b-c, c-a. So the base-4 digits of a \
            face number below its icosahedron face spell its path: corner 0, 1, 2 or \
            middle 3.",
    face_count: |a| 4u128.saturating_pow(int(a, 0)).saturating_mul(20),
    conflict: |_| None,
    build: |a| Ok(crate::round::icosphere(int(a, 0))),
};

pub(crate) const UV_SPHERE: Primitive = Primitive {
    name: "uv-sphere",
    summary: "unit sphere of quads and two polar fans",
    aliases: &[],
    params: &[
        capped_param(
            "segments",
            "segments around the z axis (meridians)",
            24,
            3,
            5_000_000,
        ),
        capped_param("rings", "bands from pole to pole", 12, 2, 3_333_333),
    ],
    description: "Unit sphere of latitude-longitude quads with triangle fans around the \
                  poles (0,0,-1) and (0,0,1); rings are evenly spaced in latitude.",
    counts: "V = segments*(rings-1)+2, E = segments*(2*rings-1), F = segments*rings \
             (2*segments triangles, the rest quads).",
    order: "Vertex 0 is the south pole; then come the rings from south to north, each of \
            segments vertices starting at angle 0 (towards +x) and running \
            counter-clockwise seen from +z; the last vertex is the north pole. Faces are \
            the south fan, the bands of quads from south to north, then the north fan, \
            each in the same angular order: (pole, (1,i+1), (1,i)); ((k,i), (k,i+1), \
            (k+1,i+1), (k+1,i)); ((last,i), (last,i+1), pole), where (k,i) is vertex i of \
            ring k and indices wrap around.",
    face_count: |a| wide(a, 0) * wide(a, 1),
    conflict: |_| None,
    build: |a| Ok(crate::round::uv_sphere(int(a, 0), int(a, 1))),
};

pub(crate) const QUAD_SPHERE: Primitive = Primitive {
    name: "quad-sphere",
    summary: "unit sphere of quads, 6n^2 faces",
    aliases: &["cube-sphere"],
    params: &[capped_param(
        "n",
        "quads along each edge of each cube side",
        8,
        1,
        CUBE_MAX_N,
    )],
    description: "Unit sphere of quads: @cube:n projected from the centre onto the sphere, \
                  with the grid spaced evenly in angle so quads are close to equal in size.",
    counts: "V = 6n^2+2, E = 12n^2, F = 6n^2 quads.",
    order: "As @cube:n (sides -z, -y, -x, +x, +y, +z).",
    face_count: |a| 6 * wide(a, 0) * wide(a, 0),
    conflict: |_| None,
    build: |a| Ok(crate::grid::quad_sphere(int(a, 0))),
};

fn torus_conflict(args: &[f64]) -> Option<String> {
    let (big_r, small_r) = (real(args, 2), real(args, 3));
    (small_r >= big_r).then(|| {
        format!(
            "the tube radius r must be less than R, or the torus would meet itself at the z \
             axis; got R = {big_r}, r = {small_r}"
        )
    })
}

pub(crate) const TORUS: Primitive = Primitive {
    name: "torus",
    summary: "quad torus about the z axis, genus 1",
    aliases: &["donut"],
    params: &[
        capped_param("major", "segments around the z axis", 24, 3, 3_333_333),
        capped_param("minor", "segments around the tube", 12, 3, 3_333_333),
        Param {
            name: "R",
            kind: ParamKind::Real {
                default: 1.0,
                max: MAX_RADIUS,
            },
            doc: "distance from the z axis to the centre of the tube",
        },
        Param {
            name: "r",
            kind: ParamKind::Real {
                default: 0.4,
                max: MAX_RADIUS,
            },
            doc: "radius of the tube, less than R",
        },
    ],
    description: "Quad torus of genus 1 about the z axis, centred at the origin: a circle \
                  of radius r swept around the circle of radius R in the xy plane; volume \
                  2*pi^2*R*r^2 in the limit.",
    counts: "V = major*minor, E = 2*major*minor, F = major*minor quads.",
    order: "Vertex i*minor+j is at angle 360*i/major degrees around z (from +x, \
            counter-clockwise seen from +z) and 360*j/minor around the tube (from the \
            outer equator, upwards first). Face i*minor+j is (i,j), (i+1,j), (i+1,j+1), \
            (i,j+1), indices wrapping around.",
    face_count: |a| wide(a, 0) * wide(a, 1),
    conflict: torus_conflict,
    build: |a| {
        Ok(crate::round::torus(
            int(a, 0),
            int(a, 1),
            real(a, 2),
            real(a, 3),
        ))
    },
};

pub(crate) const CYLINDER: Primitive = Primitive {
    name: "cylinder",
    summary: "closed, radius 1, z in [-1,1], polygon caps",
    aliases: &[],
    params: &[
        capped_param("segments", "segments around the z axis", 16, 3, 9_999_998),
        capped_param("rings", "rows of side quads", 1, 1, 3_333_332),
    ],
    description: "Closed cylinder of radius 1 along z from -1 to 1; each cap is a single \
                  polygon. Volume 2*pi in the limit.",
    counts: "V = segments*(rings+1), E = segments*(2*rings+1), F = segments*rings+2.",
    order: "Vertex k*segments+i is on ring k (from z = -1 to z = 1) at angle \
            360*i/segments degrees (from +x, counter-clockwise seen from +z). Face 0 is \
            the bottom cap, starting at vertex 0 and running clockwise seen from +z; face \
            1 is the top cap, starting at its vertex at angle 0; face 2+k*segments+i is \
            the side quad (k,i), (k,i+1), (k+1,i+1), (k+1,i).",
    face_count: |a| wide(a, 0) * wide(a, 1) + 2,
    conflict: |_| None,
    build: |a| Ok(crate::round::cylinder(int(a, 0), int(a, 1))),
};

pub(crate) const CONE: Primitive = Primitive {
    name: "cone",
    summary: "closed, base radius 1 at z = -1, apex (0,0,1)",
    aliases: &[],
    params: &[capped_param(
        "segments",
        "segments around the z axis",
        16,
        3,
        9_999_999,
    )],
    description: "Closed cone: a base polygon of radius 1 at z = -1 and the apex (0,0,1). \
                  Volume 2*pi/3 in the limit.",
    counts: "V = segments+1, E = 2*segments, F = segments+1.",
    order: "Vertex i < segments is on the base at angle 360*i/segments degrees (from +x, \
            counter-clockwise seen from +z); the last vertex is the apex. Face 0 is the \
            base, starting at vertex 0 and running clockwise seen from +z; face 1+i is the \
            triangle (i, i+1, apex).",
    face_count: |a| wide(a, 0) + 1,
    conflict: |_| None,
    build: |a| Ok(crate::round::cone(int(a, 0))),
};

pub(crate) const PLANE: Primitive = Primitive {
    name: "plane",
    summary: "open quad grid on [-1,1]^2 facing +z",
    aliases: &["grid"],
    params: &[
        capped_param("nx", "quads along x", 10, 1, 10_000_000),
        capped_param("ny", "quads along y", 10, 1, 10_000_000),
    ],
    description: "Open grid of nx x ny quads covering [-1,1]^2 in the plane z = 0, facing \
                  +z, with one boundary loop.",
    counts: "V = (nx+1)(ny+1), E = nx(ny+1)+ny(nx+1), F = nx*ny quads.",
    order: "Vertex j*(nx+1)+i is at x = -1+2i/nx, y = -1+2j/ny. Face j*nx+i is (i,j), \
            (i+1,j), (i+1,j+1), (i,j+1): counter-clockwise seen from +z, starting at its \
            lowest-numbered corner.",
    face_count: |a| wide(a, 0) * wide(a, 1),
    conflict: |_| None,
    build: |a| Ok(crate::grid::plane(int(a, 0), int(a, 1))),
};

pub(crate) const TRI_PLANE: Primitive = Primitive {
    name: "tri-plane",
    summary: "open triangle grid on [-1,1]^2 facing +z",
    aliases: &["tri-grid", "triangle-plane"],
    params: &[
        capped_param("nx", "squares along x", 10, 1, 5_000_000),
        capped_param("ny", "squares along y", 10, 1, 5_000_000),
    ],
    description: "@plane:nx:ny with each square split into two triangles along its \
                  diagonal from (i,j) to (i+1,j+1): a regular triangle grid (inner vertices \
                  of valence 6) for sculpting.",
    counts: "V = (nx+1)(ny+1), E = nx(ny+1)+ny(nx+1)+nx*ny, F = 2*nx*ny triangles.",
    order: "Vertices as @plane. Faces 2(j*nx+i) and 2(j*nx+i)+1 are (i,j), (i+1,j), \
            (i+1,j+1) and (i,j), (i+1,j+1), (i,j+1).",
    face_count: |a| 2 * wide(a, 0) * wide(a, 1),
    conflict: |_| None,
    build: |a| Ok(crate::grid::tri_plane(int(a, 0), int(a, 1))),
};

pub(crate) const SOCCER_BALL: Primitive = Primitive {
    name: "soccerball",
    summary: "truncated icosahedron: 12 pentagons, 20 hexagons",
    aliases: &["truncated-icosahedron", "buckyball"],
    params: &[],
    description: "The soccer ball (truncated icosahedron): @icosahedron with every vertex \
                  cut off a third of the way along its edges, leaving 12 regular pentagons \
                  and 20 regular hexagons with all edges equal; circumradius sqrt(3).",
    counts: "V 60, E 90, F 32 (12 pentagons, 20 hexagons).",
    order: "Vertex 5a+j lies a third of the way from icosahedron vertex a to its j-th \
            neighbour (neighbours counter-clockwise seen from outside, starting at the \
            lowest-numbered), moved out to radius sqrt(3). Faces 0 to 11 are the \
            pentagons, face a = (5a, ..., 5a+4) around icosahedron vertex a; face 12+t is \
            the hexagon of icosahedron face t = (a,b,c): (ab, ba, bc, cb, ca, ac), where xy \
            is the vertex near x on the edge towards y.",
    face_count: |_| 32,
    conflict: |_| None,
    // No parameter to check: the soccer ball always builds.
    build: |_| Ok(crate::soccer_ball()),
};

/// Upper bound for the geodesic frequency: 20·707² = 9 996 980 faces.
const GEODESIC_MAX: u32 = 707;

pub(crate) const GEODESIC: Primitive = Primitive {
    name: "geodesic",
    summary: "unit geodesic sphere, 20*n^2 triangles",
    aliases: &["geosphere", "geodesic-sphere"],
    params: &[capped_param(
        "n",
        "frequency: each icosahedron edge is cut into n",
        4,
        1,
        GEODESIC_MAX,
    )],
    description: "Unit geodesic sphere of frequency n (class I): each face of the \
                  icosahedron cut into n^2 triangles by a triangular grid, the grid points \
                  projected from the centre onto the unit sphere. This is the triangulated \
                  sphere, not its dual of pentagons and hexagons; n = 1 is the unit \
                  icosahedron.",
    counts: "V = 10n^2+2, E = 30n^2, F = 20n^2 triangles (n = 4: 162, 480, 320).",
    order: "The 12 icosahedron vertices first (as @icosahedron), then the n-1 inner points \
            of each icosahedron edge (edges in order of first use, visiting faces in order \
            and each face's edges a-b, b-c, c-a; points from the lower-numbered end), then \
            the inner points of each face. Faces t*n^2 .. (t+1)*n^2-1 cover icosahedron \
            face t = (a,b,c): with grid point (u,v) at a + u(b-a)/n + v(c-a)/n, row by row \
            (v from 0, u from 0), the triangle ((u,v), (u+1,v), (u,v+1)) followed, where \
            it exists, by ((u+1,v), (u+1,v+1), (u,v+1)).",
    face_count: |a| 20 * wide(a, 0) * wide(a, 0),
    conflict: |_| None,
    build: |a| Ok(crate::geodesic::geodesic(int(a, 0))),
};

/// Every built-in primitive, in the order the help lists them.
pub static PRIMITIVES: &[Primitive] = &[
    TETRAHEDRON,
    CUBE,
    OCTAHEDRON,
    DODECAHEDRON,
    ICOSAHEDRON,
    SPHERE,
    UV_SPHERE,
    QUAD_SPHERE,
    TORUS,
    CYLINDER,
    CONE,
    PLANE,
    TRI_PLANE,
    SOCCER_BALL,
    GEODESIC,
];
