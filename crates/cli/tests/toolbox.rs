//! TopMod's toolbox on the command line (issue 18): `holey remesh`,
//! `extrude`, `wireframe`, `cut` and `truncate`. Every expected count is
//! worked out here from the input's own counts (read back with `holey
//! info --json`), the operator's definition and Euler's formula; never
//! read from an output.

mod common;

use std::path::{Path, PathBuf};

use common::{ok, refused};
use holey_subdiv::RemeshScheme;
use serde_json::Value;

/// V, E, F, genus, components, boundary loops of a mesh argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Counts {
    v: i64,
    e: i64,
    f: i64,
    genus: i64,
    components: i64,
    loops: i64,
}

fn info(mesh: &str) -> Value {
    serde_json::from_str(&ok(&["info", mesh, "--json"])).expect("info --json is JSON")
}

fn counts(mesh: &str) -> Counts {
    let j = info(mesh);
    let n = |k: &str| {
        j[k].as_i64()
            .unwrap_or_else(|| panic!("info {mesh}: no integer {k}: {j}"))
    };
    Counts {
        v: n("vertices"),
        e: n("edges"),
        f: n("faces"),
        genus: n("genus"),
        components: n("components"),
        loops: n("boundary_loops"),
    }
}

fn vef(c: Counts) -> (i64, i64, i64) {
    (c.v, c.e, c.f)
}

/// A command's refusals on `@cube`: for each case, `holey CMD @cube OUT
/// ARGS…` is refused with a message containing every one of `needles`,
/// and writes nothing to OUT.
fn refused_on_the_cube(cmd: &str, cases: &[(&[&str], &[&str])]) {
    let d = Dir::new();
    let out = d.path("x.obj");
    for &(args, needles) in cases {
        let mut line = vec![cmd, "@cube", &out];
        line.extend_from_slice(args);
        let err = refused(&line);
        for needle in needles {
            assert!(err.contains(needle), "{line:?}: no {needle:?} in {err}");
        }
        assert!(!Path::new(&out).exists(), "a refused {line:?} wrote {out}");
    }
}

struct Dir(tempfile::TempDir);

impl Dir {
    fn new() -> Dir {
        Dir(tempfile::tempdir().expect("a temporary folder"))
    }
    fn path(&self, name: &str) -> String {
        let p: PathBuf = self.0.path().join(name);
        p.to_str().expect("utf-8 path").to_owned()
    }
}

/// Runs `holey ARGS EXTRA…`, which must succeed, and gives the counts of
/// the mesh it wrote to `out`: the tool tests' one way of running a
/// command with the options a case adds.
fn ok_then_counts(args: &[&str], extra: &[&str], out: &str) -> Counts {
    ok(&[args, extra].concat());
    counts(out)
}

/// `holey remesh IN OUT --scheme S [extra]` and the output's counts.
fn remesh(dir: &Dir, input: &str, scheme: &str, extra: &[&str]) -> Counts {
    let out = dir.path(&format!("{}.dlfl", scheme.replace('.', "_")));
    ok_then_counts(&["remesh", input, &out, "--scheme", scheme], extra, &out)
}

// ---------------------------------------------------------------- remesh

#[test]
fn dual_of_a_cube_is_an_octahedron() {
    let d = Dir::new();
    let cube = counts("@cube");
    let dual = remesh(&d, "@cube", "dual", &[]);
    // V' = F, E' = E, F' = V.
    assert_eq!(vef(dual), (cube.f, cube.e, cube.v));
    assert_eq!(vef(dual), (6, 12, 8));
    assert_eq!(info(&d.path("dual.dlfl"))["face_sizes"]["3"], 8);
}

#[test]
fn sqrt3_of_a_tetrahedron() {
    let d = Dir::new();
    let t = counts("@tetrahedron");
    let c = 2 * t.e; // corners of a closed mesh
    let s = remesh(&d, "@tetrahedron", "sqrt3", &[]);
    assert_eq!(vef(s), (t.v + t.f, t.e + c, c));
    assert_eq!(vef(s), (8, 18, 12));
    // Two levels: apply the rule twice.
    let s2 = remesh(&d, "@tetrahedron", "sqrt3", &["-n", "2"]);
    assert_eq!(vef(s2), (s.v + s.f, s.e + 2 * s.e, 2 * s.e));
    // TopMod's spellings are accepted too.
    assert_eq!(vef(remesh(&d, "@tetrahedron", "root-3", &[])), vef(s));
}

#[test]
fn loop_of_a_triangle_mesh() {
    let d = Dir::new();
    let ico = counts("@icosahedron");
    let l = remesh(&d, "@icosahedron", "loop", &[]);
    // Loop: V + E, 2E + 3F, 4F.
    assert_eq!(vef(l), (ico.v + ico.e, 2 * ico.e + 3 * ico.f, 4 * ico.f));
}

#[test]
fn truncation_stellation_and_corner_cutting_of_a_cube() {
    let d = Dir::new();
    let k = counts("@cube");
    let c = 2 * k.e;
    for (scheme, args, formula, cube) in [
        // Vertex truncation: 2E, E + C, F + V.
        (
            "vertex-truncation",
            &[][..],
            (2 * k.e, k.e + c, k.f + k.v),
            (24, 36, 14),
        ),
        // Stellate: V + F, E + C, C.
        ("stellate", &[], (k.v + k.f, k.e + c, c), (14, 36, 24)),
        // Corner cutting (Doo–Sabin connectivity): C, 2C, F + E + V.
        (
            "corner-cutting",
            &["--alpha", "0.7"],
            (c, 2 * c, k.f + k.e + k.v),
            (24, 48, 26),
        ),
    ] {
        let out = remesh(&d, "@cube", scheme, args);
        assert_eq!(vef(out), formula, "{scheme}");
        assert_eq!(vef(out), cube, "{scheme}");
    }
}

#[test]
fn scheme_options_reach_their_parameters() {
    let d = Dir::new();
    let k = counts("@cube");
    // Vertex truncation at ½ of every edge is the simplest scheme (the two
    // cut points of an edge coincide): E, C, F + V instead of 2E, E + C, F + V.
    let half = remesh(&d, "@cube", "vertex-truncation", &["--offset", "0.5"]);
    assert_eq!(vef(half), (k.e, 2 * k.e, k.f + k.v));
    // Corner cutting with α = 1 puts every corner point on its vertex, so
    // the result encloses the whole cube (volume 8); TopMod's α = 9/16
    // cuts the corners and edges away.
    let volume = |scheme_args: &[&str]| {
        let out = d.path("cc.obj");
        let mut args = vec!["remesh", "@cube", &out, "--scheme", "corner-cutting"];
        args.extend_from_slice(scheme_args);
        ok(&args);
        info(&out)["volume"]
            .as_f64()
            .expect("a closed mesh has a volume")
    };
    assert!((volume(&["--alpha", "1"]) - 8.0).abs() < 1e-12);
    assert!(volume(&[]) < 7.9);
    // subdivide-face makes quads, or triangles with --triangles.
    let tri = remesh(&d, "@cube", "subdivide-face", &["--triangles"]);
    assert_eq!(vef(tri), (k.v + k.f, 3 * k.e, 2 * k.e));
}

#[test]
fn twelve_six_four_names_are_accepted() {
    let d = Dir::new();
    let k = counts("@cube");
    let c = 2 * k.e;
    // 12.6.4: barycentric subdivision, V + E + F, 3C, 2C.
    let b = remesh(&d, "@cube", "12.6.4", &[]);
    assert_eq!(vef(b), (k.v + k.e + k.f, 3 * c, 2 * c));
    // dual 12.6.4: the omnitruncation, 2C, 2E + 2C, F + E + V; a cube
    // gives the truncated cuboctahedron: 48 vertices, 12 squares,
    // 8 hexagons, 6 octagons.
    let o = remesh(&d, "@cube", "dual-12.6.4", &["--scale", "0.5"]);
    assert_eq!(vef(o), (2 * c, 2 * k.e + 2 * c, k.f + k.e + k.v));
    let sizes = &info(&d.path("dual-12_6_4.dlfl"))["face_sizes"];
    assert_eq!(
        (&sizes["4"], &sizes["6"], &sizes["8"]),
        (&12.into(), &8.into(), &6.into())
    );
}

/// Every scheme the library has, by the name the command line takes
/// (the library's own tests check these are the names the issue lists).
fn schemes() -> impl Iterator<Item = &'static str> {
    RemeshScheme::ALL.iter().map(|scheme| scheme.name())
}

/// The schemes built from the dual, which need a closed surface.
const CLOSED_ONLY: &[&str] = &[
    "dual",
    "12.6.4",
    "cubic-pentagonalization",
    "dual-pentagonalization",
    "dual-loop",
    "dual-global-extrude",
    "dual-checkerboard",
    "dual-pentagon-preserving",
    "dual-hexagon-preserving",
];

#[test]
fn every_scheme_keeps_the_topology_of_a_torus_and_a_grid() {
    let d = Dir::new();
    let torus = counts("@torus:8:4");
    assert_eq!((torus.genus, torus.components, torus.loops), (1, 1, 0));
    let grid = counts("@plane:3:3");
    assert_eq!((grid.genus, grid.components, grid.loops), (0, 1, 1));
    for scheme in schemes() {
        let r = remesh(&d, "@torus:8:4", scheme, &[]);
        assert_eq!(
            (r.genus, r.components, r.loops),
            (1, 1, 0),
            "{scheme} on a torus"
        );
        // Euler's formula for a genus-1 closed surface.
        assert_eq!(r.v - r.e + r.f, 0, "{scheme}: χ of a torus");
        let out = d.path("grid.dlfl");
        let args = ["remesh", "@plane:3:3", &out, "--scheme", scheme];
        if CLOSED_ONLY.contains(&scheme) {
            let err = refused(&args);
            assert!(err.contains("boundary"), "{scheme} on a grid: {err}");
        } else {
            ok(&args);
            let g = counts(&out);
            assert_eq!(
                (g.genus, g.components, g.loops),
                (0, 1, 1),
                "{scheme} on an open grid"
            );
        }
    }
}

/// One level's counts from each scheme's definition, for a closed mesh
/// of quads (no triangles): `(V, E, F, C)` to `(V', E', F')`.
type Rule = fn(i64, i64, i64, i64) -> (i64, i64, i64);

const RULES: &[(&str, Rule)] = &[
    ("dual", |v, e, f, _| (f, e, v)),
    ("triangulate", |v, e, f, c| (v + f, e + c, c)),
    ("sqrt3", |v, e, f, c| (v + f, e + c, c)),
    ("dual-vertex-truncation", |v, e, f, c| (v + f, e + c, c)),
    ("stellate", |v, e, f, c| (v + f, e + c, c)),
    ("double-stellate", |v, e, f, c| {
        (v + f + c, e + 4 * c, 3 * c)
    }),
    ("stellate-edge-removal", |v, e, f, c| (v + f, c, e)),
    ("modified-double-stellate", |v, e, f, c| {
        (v + f + c, 2 * e + 2 * c, e + c)
    }),
    ("loop", |v, e, f, c| (v + e, 2 * e + c, f + c)),
    ("loop-style", |v, e, f, c| (v + e, 2 * e + c, f + c)),
    ("dual-loop", |v, e, f, c| (v + c, 2 * c, f + e)),
    ("root4", |v, e, f, c| (v + c, 2 * c, f + e)),
    ("hexagon-preserving", |v, e, f, c| (v + c, 2 * c, f + e)),
    ("dual-hexagon-preserving", |v, e, f, c| {
        (v + e, 2 * c, f + c)
    }),
    ("linear-vertex-insertion", |v, e, f, c| {
        (v + e + f, 2 * e + c, c)
    }),
    ("subdivide-face", |v, e, f, c| (v + e + f, 2 * e + c, c)),
    ("catmull-clark", |v, e, f, c| (v + e + f, 2 * e + c, c)),
    ("vertex-truncation", |v, e, f, c| (2 * e, e + c, f + v)),
    ("simplest", |v, e, f, c| (e, c, f + v)),
    ("corner-cutting", |v, e, f, c| (c, 2 * c, f + e + v)),
    ("modified-corner-cutting", |v, e, f, c| {
        (c, 2 * c, f + e + v)
    }),
    ("doo-sabin", |v, e, f, c| (c, 2 * c, f + e + v)),
    ("doo-sabin-bc", |v, e, f, c| {
        (2 * c, 4 * c - e, v + 2 * e + f)
    }),
    ("doo-sabin-bc-new", |v, e, f, c| {
        (v + 2 * c, 4 * c - e, f + 2 * e)
    }),
    ("honeycomb", |v, e, f, c| (c, e + c, f + v)),
    ("12.6.4", |v, e, f, c| (v + e + f, 3 * c, 2 * c)),
    ("dual-12.6.4", |v, e, f, c| {
        (2 * c, 2 * e + 2 * c, f + e + v)
    }),
    ("pentagonalization", |v, e, f, c| {
        (v + 2 * e + f, 3 * e + c, c)
    }),
    ("cubic-pentagonalization", |v, e, f, c| {
        (v + 2 * e + f, 3 * e + c, c)
    }),
    ("dual-pentagonalization", |v, e, f, c| {
        (c, 3 * e + c, v + 2 * e + f)
    }),
    ("pentagon-preserving", |v, e, f, c| {
        (v + e + c, 2 * e + 2 * c, f + c)
    }),
    ("dual-pentagon-preserving", |v, e, f, c| {
        (v + c, 2 * e + 2 * c, f + e + c)
    }),
    ("checkerboard", |v, e, f, c| {
        (v + 2 * e + c, 3 * e + 3 * c, f + 2 * c)
    }),
    ("dual-checkerboard", |v, e, f, c| {
        (v + 2 * c, 3 * e + 3 * c, f + 2 * e + c)
    }),
    ("global-extrude", |v, e, f, c| (v + c, e + 2 * c, f + c)),
    ("dual-global-extrude", |v, e, f, c| {
        (v + c, e + 2 * c, f + c)
    }),
    ("dome", |v, e, f, c| {
        (v + 3 * e + 28 * c, 4 * e + 56 * c, f + 28 * c)
    }),
    ("fractal", |v, e, f, c| (v + e + f, 2 * e + 2 * c, 2 * c)),
];

#[test]
fn every_scheme_gives_its_counts() {
    let d = Dir::new();
    assert_eq!(RULES.len(), schemes().count(), "a rule for every scheme");
    for mesh in ["@cube", "@torus:8:4"] {
        let m = counts(mesh);
        let c = 2 * m.e; // closed, so every edge has two corners
        for (scheme, rule) in RULES {
            assert!(schemes().any(|s| s == *scheme), "{scheme}");
            let got = remesh(&d, mesh, scheme, &[]);
            assert_eq!(vef(got), rule(m.v, m.e, m.f, c), "{scheme} of {mesh}");
            // Euler's formula: the genus is kept.
            assert_eq!(got.v - got.e + got.f, m.v - m.e + m.f, "{scheme} of {mesh}");
        }
    }
}

#[test]
fn the_help_lists_every_scheme() {
    let help = ok(&["remesh", "--help"]);
    for scheme in schemes() {
        assert!(
            help.contains(&format!("  {scheme} ")),
            "remesh --help does not list {scheme}"
        );
    }
    assert!(help.contains("Examples:"));
}

#[test]
fn remesh_refusals() {
    refused_on_the_cube(
        "remesh",
        &[
            (
                &["--scheme", "no-such-scheme"],
                &["no-such-scheme", "12.6.4"],
            ),
            (
                &["--scheme", "corner-cutting", "--alpha", "NaN"],
                &["NaN", "@cube"],
            ),
            (
                &["--scheme", "dual", "--alpha", "0.6"],
                &["--alpha", "dual"],
            ),
            (
                &["--scheme", "vertex-truncation", "--offset", "0.75"],
                &["0.75"],
            ),
        ],
    );
}

// ---------------------------------------------------------------- extrude

/// `holey extrude @cube OUT --faces 0 [extra]`: the change in V, E, F.
fn extrude_cube(d: &Dir, extra: &[&str]) -> (i64, i64, i64) {
    let before = counts("@cube");
    let out = d.path("extruded.dlfl");
    let after = ok_then_counts(&["extrude", "@cube", &out, "--faces", "0"], extra, &out);
    assert_eq!(
        (after.genus, after.components, after.loops),
        (0, 1, 0),
        "{extra:?}"
    );
    (after.v - before.v, after.e - before.e, after.f - before.f)
}

#[test]
fn extrusion_counts_of_a_quad() {
    let d = Dir::new();
    let q = 4; // the cube's face 0 is a quad
    // Plain, once: one ring of d quads: +d, +2d, +d.
    assert_eq!(extrude_cube(&d, &[]), (q, 2 * q, q));
    assert_eq!((q, 2 * q, q), (4, 8, 4));
    // k times: +kd, +2kd, +kd, with turn and scale.
    let k = 3;
    assert_eq!(
        extrude_cube(&d, &["--count", "3", "--scale", "0.8", "--rotation", "15"]),
        (k * q, 2 * k * q, k * q)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "cubical", "--count", "2"]),
        (2 * q, 4 * q, 2 * q)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "doo-sabin", "--twist", "0.1"]),
        (q, 2 * q, q)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "octahedral"]),
        (q, 3 * q, 2 * q)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "dodecahedral"]),
        (3 * q, 5 * q, 2 * q)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "icosahedral"]),
        (3 * q, 9 * q, 6 * q)
    );
    // Stellate: a cone of d triangles in place of the face.
    assert_eq!(
        extrude_cube(&d, &["--kind", "stellate", "--distance", "1"]),
        (1, q, q - 1)
    );
    assert_eq!(
        extrude_cube(&d, &["--kind", "double-stellate"]),
        (q + 1, 4 * q, 3 * q - 1)
    );
    // A dome of k rings: +kd + 1, +2kd + d, +kd + d − 1.
    let k = 2;
    assert_eq!(
        extrude_cube(&d, &["--kind", "dome", "--count", "2"]),
        (k * q + 1, 2 * k * q + q, k * q + q - 1)
    );
}

#[test]
fn stellating_every_face_of_a_cube() {
    let d = Dir::new();
    let k = counts("@cube");
    let out = d.path("spiky.obj");
    ok(&[
        "extrude",
        "@cube",
        &out,
        "--faces",
        "0,1,2,3,4,5",
        "--kind",
        "stellate",
        "--distance",
        "1",
    ]);
    // Each of the F quads: +1, +4, +3.
    let s = counts(&out);
    assert_eq!(vef(s), (k.v + k.f, k.e + 4 * k.f, k.f + 3 * k.f));
    assert_eq!(vef(s), (14, 36, 24));
    assert_eq!(info(&out)["face_sizes"]["3"], 24);
}

#[test]
fn extruding_faces_together() {
    let d = Dir::new();
    // A 4×4 grid of quads, faces row by row: 5, 6, 9, 10 are the middle
    // 2×2 block, whose boundary has b = 8 sides: +b, +2b, +b.
    let g = counts("@plane:4:4");
    assert_eq!(vef(g), (25, 40, 16));
    let out = d.path("block.obj");
    ok(&[
        "extrude",
        "@plane:4:4",
        &out,
        "--faces",
        "5,6,9,10",
        "--together",
        "--distance",
        "0.5",
    ]);
    let b = 8;
    let t = counts(&out);
    assert_eq!(vef(t), (g.v + b, g.e + 2 * b, g.f + b));
    // One by one, each quad gets its own four walls: 4 × (4, 8, 4).
    ok(&["extrude", "@plane:4:4", &out, "--faces", "5,6,9,10"]);
    let s = counts(&out);
    assert_eq!(vef(s), (g.v + 16, g.e + 32, g.f + 16));
}

/// NaN and infinite parameters are refused by the library's typed checks
/// (no hand check in the CLI) and named with the face in file order; so
/// is a finite distance whose repetitions overflow. Nothing is written.
#[test]
fn extrude_refuses_non_finite_parameters() {
    let d = Dir::new();
    let out = d.path("x.obj");
    let cases = [
        ("plain", "--distance", "distance"),
        ("plain", "--scale", "scale"),
        ("plain", "--rotation", "rotation_deg"),
        ("doo-sabin", "--twist", "twist"),
        ("doo-sabin", "--scale", "scale"),
        ("cubical", "--height", "height_factor"),
        ("dome", "--height", "height_factor"),
        ("dodecahedral", "--height", "height_factor"),
        ("icosahedral", "--height", "height_factor"),
        ("octahedral", "--height", "height_factor"),
        ("stellate", "--distance", "height"),
        ("double-stellate", "--distance", "height"),
    ];
    for (kind, flag, name) in cases {
        for (value, shown) in [("nan", "NaN"), ("inf", "inf"), ("-inf", "-inf")] {
            let args = [
                "extrude", "@cube", &out, "--faces", "1", "--kind", kind, flag, value,
            ];
            let err = refused(&args);
            assert!(
                err.contains(&format!("face 1: parameter '{name}' is {shown}")),
                "{args:?}: {err}"
            );
            assert!(!Path::new(&out).exists(), "{args:?} wrote {out}");
        }
    }
    let err = refused(&[
        "extrude",
        "@plane:4:4",
        &out,
        "--faces",
        "5,6",
        "--together",
        "--distance",
        "inf",
    ]);
    assert!(err.contains("parameter 'distance' is inf"), "{err}");
    // Finite, but three steps of 1e308 leave the doubles behind.
    let err = refused(&[
        "extrude",
        "@cube",
        &out,
        "--faces",
        "2",
        "--distance",
        "1e308",
        "--count",
        "3",
    ]);
    assert!(
        err.contains("face 2: a new vertex of face 2 would have non-finite coordinates"),
        "{err}"
    );
    // Which point: the second ring's first (points 4..8 of the quad).
    assert!(
        err.contains("(new point 4 has a non-finite coordinate ("),
        "{err}"
    );
    assert!(!Path::new(&out).exists());
    // Together: the first step reaches 1e308, the second is refused about
    // faces the first made, which the message names by what they are
    // (never by a kernel id such as `f20v1`).
    let err = refused(&[
        "extrude",
        "@plane:4:4",
        &out,
        "--faces",
        "5",
        "--together",
        "--distance",
        "1e308",
        "--count",
        "5",
    ]);
    assert!(
        err.contains("repetition 2 of 5 was refused, so none was made")
            && err.contains("non-finite coordinates")
            && !err.contains("v1"),
        "{err}"
    );
    assert!(!Path::new(&out).exists());
}

#[test]
fn extrude_refusals() {
    refused_on_the_cube(
        "extrude",
        &[
            // A bad face id.
            (&["--faces", "6"], &["face 6", "6 faces"]),
            (
                &["--faces", "0", "--distance", "nan"],
                &["distance", "NaN", "face 0"],
            ),
            (&["--faces", "0", "--scale", "-1"], &["scale"]),
            (
                &["--faces", "0", "--kind", "octahedral", "--rotation", "10"],
                &["--rotation", "octahedral"],
            ),
            (&["--faces", "0,x"], &["\"x\""]),
            (&["--faces", "0", "--kind", "pyramid"], &[]),
        ],
    );
}

// ---------------------------------------------------------------- wireframe

#[test]
fn wireframe_genus_is_the_cycle_rank() {
    let d = Dir::new();
    // Each mesh with its vertices of valence 2 or less (the 2×2 grid's
    // four corners).
    for (mesh, low) in [
        ("@cube", 0),
        ("@dodecahedron", 0),
        ("@plane:2:2", 4),
        ("@torus:6:4", 0),
    ] {
        let m = counts(mesh);
        let out = d.path("frame.dlfl");
        ok(&["wireframe", mesh, &out, "--thickness", "0.05"]);
        let w = counts(&out);
        // The graph of a mesh: V vertices, E edges, one component.
        assert_eq!(w.genus, m.e - m.v + 1, "{mesh}");
        assert_eq!((w.components, w.loops), (1, 0), "{mesh}");
        // Four-sided tubes, with no joint at a vertex of valence 2 or
        // less (3dea74f): V' = 4E, E' = 10E - 2(V1 + V2), F' = 4E + 2V3.
        assert_eq!(
            vef(w),
            (4 * m.e, 10 * m.e - 2 * low, 4 * m.e + 2 * (m.v - low)),
            "{mesh}"
        );
    }
    // An open 2×2 grid (9 vertices, 12 edges) gives genus 4: its boundary
    // loop is a window like the faces.
    let out = d.path("grid.obj");
    ok(&["wireframe", "@plane:2:2", &out, "--thickness", "0.05"]);
    assert_eq!(counts(&out).genus, 4);
}

#[test]
fn columns_along_every_edge() {
    let d = Dir::new();
    let m = counts("@cube"); // every vertex of valence 3
    let n = 6;
    let out = d.path("columns.obj");
    ok(&[
        "wireframe",
        "@cube",
        &out,
        "--thickness",
        "0.1",
        "--columns",
        "6",
    ]);
    let c = counts(&out);
    // V' = 2nE; E' = 3nE + Σ 2k; F' = nE + Σ (k + 2), over valence-3 vertices.
    assert_eq!(
        vef(c),
        (2 * n * m.e, 3 * n * m.e + 2 * 3 * m.v, n * m.e + 5 * m.v)
    );
    assert_eq!(c.genus, m.e - m.v + 1);
}

#[test]
fn wireframe_refusals() {
    refused_on_the_cube(
        "wireframe",
        &[
            (&["--thickness", "NaN"], &["thickness", "NaN"]),
            (&["--thickness", "5"], &["face 0", "turns over"]),
            (&["--thickness", "0.1", "--columns", "2"], &["3 sides"]),
        ],
    );
}

// ---------------------------------------------------------------- cut, truncate

#[test]
fn truncating_every_vertex() {
    let d = Dir::new();
    let out = d.path("t.obj");
    for (mesh, fraction) in [("@cube", "0.25"), ("@icosahedron", "0.3333333333333333")] {
        let m = counts(mesh);
        ok(&["truncate", mesh, &out, "--all", "--fraction", fraction]);
        let t = counts(&out);
        // 2E, 3E, F + V.
        assert_eq!(vef(t), (2 * m.e, 3 * m.e, m.f + m.v), "{mesh}");
    }
    // The last one is the soccer ball: 60/90/32, 12 pentagons, 20 hexagons,
    // as the built-in @soccerball.
    let ball = counts(&out);
    assert_eq!(vef(ball), (60, 90, 32));
    assert_eq!(vef(counts("@soccerball")), vef(ball));
    let sizes = &info(&out)["face_sizes"];
    assert_eq!((&sizes["5"], &sizes["6"]), (&12.into(), &20.into()));
}

#[test]
fn cutting_a_vertex_an_edge_and_a_face() {
    let d = Dir::new();
    let k = counts("@cube"); // valence 3 everywhere
    let out = d.path("c.obj");
    // A vertex of valence 3: +(k − 1), +k, +1.
    ok(&["cut", "@cube", &out, "--vertex", "0", "--offset", "0.5"]);
    assert_eq!(vef(counts(&out)), (k.v + 2, k.e + 3, k.f + 1));
    // An edge between valences 3 and 3: +(a + b − 4), +(a + b − 3), +1;
    // named by its vertices or by a corner.
    ok(&["cut", "@cube", &out, "--edge", "0-1", "--fraction", "0.25"]);
    assert_eq!(vef(counts(&out)), (k.v + 2, k.e + 3, k.f + 1));
    ok(&["cut", "@cube", &out, "--edge", "0:0"]);
    assert_eq!(vef(counts(&out)), (k.v + 2, k.e + 3, k.f + 1));
    // A face with 4 spokes and 4 sides: +0, +0, +0.
    ok(&["cut", "@cube", &out, "--face", "0"]);
    assert_eq!(vef(counts(&out)), vef(k));
    // Two vertices at once.
    ok(&["cut", "@cube", &out, "--vertex", "0,7"]);
    assert_eq!(vef(counts(&out)), (k.v + 4, k.e + 6, k.f + 2));
    // Truncating one edge: +(a + b − 4), +(a + b − 3), +1.
    ok(&["truncate", "@cube", &out, "--edge", "0-1"]);
    assert_eq!(vef(counts(&out)), (k.v + 2, k.e + 3, k.f + 1));
}

/// TopMod's cut by edge-vertex with an offset for each: edge 0-1 of the
/// cube (side 2) at 0.3 and the far corner 7 at 0.7. Each cut alone adds
/// 2 / 3 / 1; every new point lies on a cube edge at its own target's
/// offset from the corner it replaced (read back from the written file).
#[test]
fn an_edge_and_a_vertex_cut_at_offsets_of_their_own() {
    let d = Dir::new();
    let k = counts("@cube");
    let out = d.path("ev.obj");
    // Edge 0-1 at 0.3 and vertex 7 at `vertex_offset`.
    let ev_cut = |vertex_offset| {
        [
            "cut",
            "@cube",
            out.as_str(),
            "--edge",
            "0-1",
            "--vertex",
            "7",
            "--offset",
            "0.3",
            "--vertex-offset",
            vertex_offset,
        ]
    };
    ok(&ev_cut("0.7"));
    assert_eq!(vef(counts(&out)), (k.v + 4, k.e + 6, k.f + 2));
    let text = std::fs::read_to_string(&out).expect("the cut was written");
    let corner = |p: [f64; 3]| {
        let mut best = f64::INFINITY;
        for i in 0..8 {
            let c = [0, 1, 2].map(|a| if i >> a & 1 == 1 { 1.0 } else { -1.0 });
            let d2: f64 = (0..3).map(|a| (p[a] - c[a]) * (p[a] - c[a])).sum();
            best = best.min(d2.sqrt());
        }
        best
    };
    let mut dist: Vec<f64> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l
                .split_whitespace()
                .map(|t| t.parse().expect("a number"))
                .collect();
            corner([x[0], x[1], x[2]])
        })
        .collect();
    dist.sort_by(f64::total_cmp);
    let want = [0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.3, 0.3, 0.7, 0.7, 0.7];
    assert_eq!(dist.len(), want.len());
    for (got, want) in dist.iter().zip(want) {
        assert!((got - want).abs() < 1e-9, "{dist:?}");
    }
    // The vertices' offset is checked on their own spokes (length 2).
    let err = refused(&ev_cut("1.0"));
    assert!(err.contains("reaches the middle"), "{err}");
}

#[test]
fn cut_and_truncate_refusals() {
    refused_on_the_cube(
        "cut",
        &[
            (&["--vertex", "8"], &["vertex 8", "8 vertices"]),
            (&["--face", "6"], &["face 6"]),
            // The edge is named by its vertices.
            (
                &["--vertex", "0", "--offset", "5"],
                &["reaches the middle", "edge 0-"],
            ),
            (&["--vertex", "0", "--offset", "NaN"], &["NaN"]),
            (&["--edge", "0-7"], &["not joined"]),
            (&["--edge", "0-1", "--vertex", "1"], &["share vertex 1"]),
            (&[], &[]),
        ],
    );
    refused_on_the_cube("truncate", &[(&["--all", "--fraction", "0.5"], &["0.5"])]);
}

// ---------------------------------------------------------------- hull

#[test]
fn hull_of_a_torus_and_dual_hull_of_a_cube() {
    let d = Dir::new();
    // A cube is its own hull; its dual convex hull is the octahedron
    // (F, E, V of the cube). Both genus 0, one piece, closed.
    let h = d.path("h.obj");
    ok(&["hull", "@cube", &h]);
    let cube = counts("@cube");
    assert_eq!(vef(counts(&h)), vef(cube));
    let o = d.path("o.obj");
    ok(&["hull", "@cube", &o, "--dual"]);
    let oct = counts(&o);
    assert_eq!(vef(oct), (cube.f, cube.e, cube.v));
    // A torus's hull drops its inner ring: genus 0, one piece, no
    // boundary, Euler's formula, fewer vertices than the torus.
    let t = d.path("t.dlfl");
    ok(&["hull", "@torus", &t]);
    let (torus, hull) = (counts("@torus"), counts(&t));
    assert_eq!((hull.genus, hull.components, hull.loops), (0, 1, 0));
    assert_eq!(hull.v - hull.e + hull.f, 2);
    assert!(hull.v < torus.v);
    // The dual has one face per corner of the hull.
    let td = d.path("td.dlfl");
    ok(&["hull", "@torus", &td, "--dual"]);
    let dual = counts(&td);
    assert_eq!(dual.f, hull.v);
    assert_eq!((dual.genus, dual.components, dual.loops), (0, 1, 0));
}

#[test]
fn hull_of_a_flat_mesh_is_refused_and_writes_nothing() {
    let d = Dir::new();
    for dual in [false, true] {
        let out = d.path("flat.obj");
        let mut args = vec!["hull", "@plane:3:3", &out];
        if dual {
            args.push("--dual");
        }
        let err = refused(&args);
        assert!(err.contains("one plane"), "{err}");
        assert!(!Path::new(&out).exists());
    }
}

// ---------------------------------------------------------------- shared

#[test]
fn every_new_command_has_examples() {
    for command in ["remesh", "extrude", "wireframe", "cut", "truncate", "hull"] {
        let help = ok(&[command, "--help"]);
        assert!(
            help.contains("Examples:\n  holey "),
            "{command} --help: {help}"
        );
    }
}

#[test]
fn batch_remesh_wireframe_and_truncate() {
    let d = Dir::new();
    let a = d.path("a.obj");
    let b = d.path("b.obj");
    ok(&["primitive", "@cube", &a]);
    ok(&["primitive", "@tetrahedron", &b]);
    let out = d.path("out");
    ok(&["batch", "remesh", "--scheme", "dual", &a, &b, "--out", &out]);
    assert_eq!(vef(counts(&format!("{out}/a.obj"))), (6, 12, 8));
    assert_eq!(vef(counts(&format!("{out}/b.obj"))), (4, 6, 4));
    let frames = d.path("frames");
    ok(&[
        "batch",
        "wireframe",
        "--thickness",
        "0.05",
        &a,
        "--out",
        &frames,
    ]);
    assert_eq!(counts(&format!("{frames}/a.obj")).genus, 12 - 8 + 1);
    let cut = d.path("cut");
    ok(&["batch", "truncate", "--all", &a, &b, "--out", &cut]);
    assert_eq!(vef(counts(&format!("{cut}/b.obj"))), (12, 18, 8));
}
