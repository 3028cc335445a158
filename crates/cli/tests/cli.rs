//! End-to-end tests of the `holey` binary: one test binary, each test
//! running the real command line.

#![allow(clippy::unwrap_used)] // test helpers: a failed unwrap is a failed test

use std::path::{Path, PathBuf};

use serde_json::Value;

mod common;
use common::{holey, ok, refused_output};

fn info(mesh: &str, extra: &[&str]) -> Value {
    let mut args = vec!["info", "--json", mesh];
    args.extend_from_slice(extra);
    serde_json::from_str(&ok(&args)).expect("info prints JSON")
}

fn bad(args: &[&str]) -> String {
    let out = refused_output(args);
    assert!(out.stdout.is_empty(), "holey {args:?} printed to stdout");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `holey ARGS --report DIR/report.json` and returns the report it
/// wrote (a report left by an earlier run is removed first).
fn reported(dir: &Path, args: &[&str]) -> Value {
    let r = dir.join("report.json");
    let _ = std::fs::remove_file(&r);
    let mut all = args.to_vec();
    all.extend(["--report", s(&r)]);
    ok(&all);
    serde_json::from_str(&std::fs::read_to_string(&r).unwrap()).unwrap()
}

/// A file `name` in `dir` holding `text`.
fn file_in(dir: &Path, name: impl AsRef<Path>, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary directory")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// `holey selfint --json` of the mesh at `path`.
fn selfint(path: &Path) -> Value {
    serde_json::from_str(&ok(&["selfint", "--json", s(path)])).unwrap()
}

/// Checks that `info` describes one closed 2-manifold solid of genus 0;
/// `what` names the case in a failure.
fn assert_one_closed_sphere(m: &Value, what: &str) {
    assert_eq!(m["closed"], true, "{what}");
    assert_eq!(m["manifold"], true, "{what}");
    assert_eq!(m["components"], 1, "{what}");
    assert_eq!(m["genus"], 0, "{what}");
}

#[test]
fn info_on_primitives() {
    let cube = info("@cube", &[]);
    assert_eq!(cube["vertices"], 8);
    assert_eq!(cube["edges"], 12);
    assert_eq!(cube["faces"], 6);
    assert_eq!(cube["genus"], 0);
    assert_eq!(cube["closed"], true);
    assert_eq!(cube["volume"], 8.0);
    assert_eq!(cube["face_sizes"]["4"], 6);
    let torus = info("@torus", &[]);
    assert_eq!(torus["genus"], 1);
    assert_eq!(torus["euler"], 0);
    let plane = info("@plane:4:3", &[]);
    assert_eq!(plane["boundary_loops"], 1);
    assert_eq!(plane["closed"], false);
    assert_eq!(plane["volume"], Value::Null);
    for field in [
        "vertices",
        "edges",
        "faces",
        "components",
        "boundary_edges",
        "boundary_loops",
        "nonmanifold_edges",
        "nonmanifold_vertices",
        "closed",
        "manifold",
        "oriented",
        "euler",
        "genus",
        "self_loops",
        "two_gons",
        "point_spheres",
        "face_sizes",
        "bbox",
        "volume",
    ] {
        assert!(plane.get(field).is_some(), "info --json lacks {field}");
    }
    let text = ok(&["info", "@torus"]);
    assert!(text.contains("genus:         1"), "{text}");
}

#[test]
fn help_has_examples_for_every_command() {
    for cmd in [
        "info",
        "convert",
        "primitive",
        "topo",
        "union",
        "intersection",
        "difference",
        "selfint",
        "resolve",
        "sculpt",
    ] {
        let help = ok(&[cmd, "--help"]);
        assert!(help.contains("Examples:"), "{cmd} --help has no examples");
    }
    let top = ok(&["--help"]);
    assert!(top.contains("@name") && top.contains("file order"));
    assert!(ok(&["primitives"]).contains("@torus"));
}

#[test]
fn convert_round_trips_through_every_format() {
    let dir = tmp();
    let base = info("@torus:12:8", &[]);
    for ext in ["obj", "off", "ply", "dlfl"] {
        let a = dir.path().join(format!("t.{ext}"));
        ok(&["convert", "@torus:12:8", s(&a)]);
        let back = dir.path().join(format!("back-{ext}.obj"));
        ok(&["convert", s(&a), s(&back)]);
        for v in [info(s(&a), &[]), info(s(&back), &[])] {
            for key in ["vertices", "edges", "faces", "genus", "components", "bbox"] {
                assert_eq!(v[key], base[key], "{ext}: {key}");
            }
        }
    }
    // STL holds triangles: the quads come back split in two.
    let stl = dir.path().join("t.stl");
    ok(&["convert", "@torus:12:8", s(&stl)]);
    let t = info(s(&stl), &[]);
    assert_eq!(t["faces"], 2 * 96);
    assert_eq!(t["genus"], 1);
    let ascii = dir.path().join("t-ascii.ply");
    ok(&["convert", "@cube", s(&ascii), "--ascii"]);
    assert!(
        std::fs::read_to_string(&ascii)
            .unwrap()
            .contains("format ascii")
    );
}

#[test]
fn primitive_command_writes_files() {
    let dir = tmp();
    let out = dir.path().join("ico.obj");
    ok(&["primitive", "icosahedron", s(&out)]);
    let v = info(s(&out), &[]);
    assert_eq!(
        (v["vertices"].as_u64(), v["faces"].as_u64()),
        (Some(12), Some(20))
    );
    let err = bad(&["primitive", "@sphere:99", s(&dir.path().join("x.obj"))]);
    assert!(err.contains("sphere"), "{err}");
    assert!(!dir.path().join("x.obj").exists());
}

#[test]
fn malformed_input_is_status_2_with_line_and_no_output() {
    let dir = tmp();
    let cases = [
        (
            "badnum.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 x\nf 1 2 3\n",
            "badnum.obj:3",
        ),
        (
            "range.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            "range.obj:4",
        ),
        ("short.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "short.obj:3"),
        (
            "nan.obj",
            "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n",
            "nan.obj:3",
        ),
        (
            "inf.off",
            "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n",
            "inf.off:5",
        ),
    ];
    for (name, text, expect) in cases {
        let input = file_in(dir.path(), name, text);
        let out = dir.path().join(format!("{name}.ply"));
        let err = bad(&["convert", s(&input), s(&out)]);
        assert!(err.contains(expect), "{name}: {err}");
        assert!(!out.exists(), "{name}: a partial output was written");
        assert_eq!(
            std::fs::read_to_string(&input).unwrap(),
            text,
            "input modified"
        );
        bad(&["info", s(&input)]);
    }
    // Truncated binary STL: a byte offset.
    let stl = dir.path().join("cut.stl");
    ok(&["convert", "@cube", s(&stl)]);
    let bytes = std::fs::read(&stl).unwrap();
    std::fs::write(&stl, &bytes[..bytes.len() - 7]).unwrap();
    let err = bad(&["info", s(&stl)]);
    assert!(err.contains("byte"), "{err}");
    // Unknown extension, missing file, unknown primitive.
    assert!(bad(&["info", "mesh.xyz"]).contains("mesh.xyz"));
    assert!(bad(&["info", s(&dir.path().join("missing.obj"))]).contains("missing.obj"));
    assert!(bad(&["info", "@nosuch"]).contains("@nosuch"));
}

#[test]
fn failed_write_leaves_an_existing_output_untouched() {
    let dir = tmp();
    let out = file_in(dir.path(), "keep.dlfl", "precious");
    // A non-manifold soup cannot become a DLFL without splitting.
    let bowtie = file_in(
        dir.path(),
        "bowtie.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n",
    );
    let err = bad(&["convert", s(&bowtie), s(&out)]);
    assert!(err.contains("non-manifold vertex 0"), "{err}");
    assert!(err.contains("--split-nonmanifold"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "precious");
    ok(&["convert", s(&bowtie), s(&out), "--split-nonmanifold"]);
    let v = info(s(&out), &[]);
    assert_eq!(
        (v["vertices"].as_u64(), v["components"].as_u64()),
        (Some(6), Some(2))
    );
}

#[test]
fn dlfl_files_keep_what_other_formats_cannot() {
    let dir = tmp();
    // A sphere made of a self-loop and two monogons, plus a two-gon sphere
    // and a point-sphere, written by hand.
    let text = "dlfl 1\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 0\nf 0\ne 0:0 1:0\nf 1 2\nf 2 1\ne 2:0 3:0\ne 2:1 3:1\nf 3\n";
    let path = file_in(dir.path(), "odd.dlfl", text);
    let v = info(s(&path), &[]);
    assert_eq!(v["vertices"], 4);
    assert_eq!(v["edges"], 3);
    assert_eq!(v["faces"], 5);
    assert_eq!(v["self_loops"], 1);
    assert_eq!(v["two_gons"], 2);
    assert_eq!(v["point_spheres"], 1);
    assert_eq!(v["components"], 3);
    assert_eq!(v["genus"], 0);
    let copy = dir.path().join("copy.dlfl");
    ok(&["convert", s(&path), s(&copy)]);
    assert_eq!(info(s(&copy), &[]), v);
    // A .dlfl whose edges contradict its faces is refused with its line.
    let broken = file_in(
        dir.path(),
        "broken.dlfl",
        "dlfl 1\nv 0 0 0\nv 1 0 0\nf 0 1\nf 0 1\ne 0:0 1:0\ne 0:1 1:1\n",
    );
    let err = bad(&["info", s(&broken)]);
    assert!(err.contains("broken.dlfl"), "{err}");
}

/// Values of one row of the shared README's table.
struct Row {
    file: String,
    cells: Vec<String>,
}

fn readme_rows(readme: &str) -> Vec<Row> {
    readme
        .lines()
        .filter(|l| l.starts_with("| ") && l.contains(".obj |"))
        .filter_map(|l| {
            let cells: Vec<String> = l
                .trim_matches('|')
                .split(" | ")
                .map(|c| c.trim().to_owned())
                .collect();
            // The measured-properties table has 15 columns.
            (cells.len() == 15).then(|| Row {
                file: cells[0].clone(),
                cells,
            })
        })
        .collect()
}

fn leading_int(s: &str) -> i64 {
    let t: String = s
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '-')
        .collect();
    t.parse().unwrap_or_else(|_| panic!("no integer in {s:?}"))
}

/// The shared README lists V, F, face sizes, closedness, boundary,
/// non-manifold counts, components, χ, genus and volume for every mesh, and
/// the same after welding. `holey info` must agree on every file. Reads
/// ../shared/data/meshes; skipped visibly when it is absent.
#[test]
fn info_agrees_with_the_shared_readme_table() {
    let dir = holey_testkit::shared_meshes_or_return!("info_agrees_with_the_shared_readme_table");
    let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
    let rows = readme_rows(&readme);
    assert_eq!(rows.len(), 16, "expected 16 meshes in the README table");
    for row in rows {
        let path: PathBuf = dir.join(&row.file);
        let v = info(s(&path), &[]);
        let c = &row.cells;
        let ctx = &row.file;
        // The counts one column holds each: (JSON key, column, label).
        for (key, column, label) in [
            ("vertices", 2, "V"),
            ("faces", 3, "F"),
            ("nonmanifold_edges", 6, "nm edges"),
            ("nonmanifold_vertices", 7, "nm verts"),
            ("misoriented_edges", 8, "misoriented"),
            ("components", 9, "comps"),
            ("euler", 10, "chi"),
        ] {
            assert_eq!(
                v[key].as_i64().unwrap(),
                leading_int(&c[column]),
                "{ctx} {label}"
            );
        }
        if let Some(extra) = c[2].split("(+").nth(1) {
            assert_eq!(
                v["unreferenced_vertices"].as_i64().unwrap(),
                leading_int(extra),
                "{ctx} unreferenced"
            );
        }
        for pair in c[4].split_whitespace() {
            let (k, n) = pair.split_once(':').unwrap();
            assert_eq!(
                v["face_sizes"][k].as_i64().unwrap(),
                n.parse::<i64>().unwrap(),
                "{ctx} {k}-gons"
            );
        }
        assert_eq!(
            v["closed"].as_bool().unwrap(),
            c[5].starts_with("yes"),
            "{ctx} closed"
        );
        let inner = c[5].split('(').nth(1).unwrap();
        let mut nums = inner.split(',').map(leading_int_trim);
        assert_eq!(
            v["boundary_edges"].as_i64().unwrap(),
            nums.next().unwrap(),
            "{ctx} be"
        );
        assert_eq!(
            v["boundary_loops"].as_i64().unwrap(),
            nums.next().unwrap(),
            "{ctx} loops"
        );
        if c[11] == "-" {
            assert_eq!(v["genus"], Value::Null, "{ctx} genus");
        } else {
            assert_eq!(
                v["genus"].as_i64().unwrap(),
                leading_int(&c[11]),
                "{ctx} genus"
            );
        }
        if c[12] == "-" {
            assert_eq!(v["volume"], Value::Null, "{ctx} volume");
        } else {
            let want: f64 = c[12].parse().unwrap();
            let got = v["volume"].as_f64().unwrap();
            // The README prints six significant digits.
            assert!(
                (got - want).abs() <= 5e-6 * want.abs().max(1.0),
                "{ctx} volume {got} vs {want}"
            );
        }
        if let Some(welded) = c[14].strip_prefix("welded: ") {
            let w = info(s(&path), &["--weld"]);
            for item in welded.split(", ") {
                let (key, val) = item.split_once('=').unwrap();
                let field = match key {
                    "V" => "vertices",
                    "closed" => "closed",
                    "nm-edges" => "nonmanifold_edges",
                    "nm-verts" => "nonmanifold_vertices",
                    "comps" => "components",
                    "chi" => "euler",
                    "genus" => "genus",
                    _ => continue, // si_pairs: self-intersections, a later issue
                };
                match field {
                    "closed" => {
                        assert_eq!(
                            w["closed"].as_bool().unwrap(),
                            val.starts_with("yes"),
                            "{ctx} welded closed"
                        );
                        let be = leading_int(val.split('(').nth(1).unwrap());
                        assert_eq!(w["boundary_edges"].as_i64().unwrap(), be, "{ctx} welded be");
                    }
                    "genus" if val == "-" => {
                        assert_eq!(w["genus"], Value::Null, "{ctx} welded genus")
                    }
                    _ => assert_eq!(
                        w[field].as_i64().unwrap(),
                        leading_int(val),
                        "{ctx} welded {key}"
                    ),
                }
            }
        }
    }
}

fn leading_int_trim(s: &str) -> i64 {
    leading_int(s.trim())
}

/// Every manifold mesh of the shared folder imports into the kernel and
/// its .dlfl measures the same as the soup; the non-manifold ones are
/// refused with the offending element named, and import with splitting.
/// Reads ../shared/data/meshes; skipped visibly when absent.
#[test]
fn shared_meshes_import_into_the_kernel() {
    let dir = holey_testkit::shared_meshes_or_return!("shared_meshes_import_into_the_kernel");
    let out = tmp();
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    names.sort();
    for path in names {
        let soup = info(s(&path), &[]);
        let target = out.path().join("k.dlfl");
        let result = holey(&["convert", s(&path), s(&target)]);
        let manifold = soup["manifold"].as_bool().unwrap() && soup["oriented"].as_bool().unwrap();
        if manifold {
            assert!(
                result.status.success(),
                "{path:?}: {}",
                String::from_utf8_lossy(&result.stderr)
            );
            let k = info(s(&target), &[]);
            for key in [
                "vertices",
                "edges",
                "faces",
                "components",
                "boundary_edges",
                "boundary_loops",
                "euler",
                "genus",
            ] {
                assert_eq!(k[key], soup[key], "{path:?}: {key}");
            }
        } else {
            assert_eq!(result.status.code(), Some(2), "{path:?}");
            let err = String::from_utf8_lossy(&result.stderr);
            assert!(
                err.contains("non-manifold") || err.contains("same direction"),
                "{path:?}: {err}"
            );
            ok(&["convert", s(&path), s(&target), "--split-nonmanifold"]);
            let k = info(s(&target), &[]);
            assert_eq!(k["faces"], soup["faces"], "{path:?}");
        }
    }
}

// ---- The high-genus tools (thesis chapters IV–VII) ----

fn vef(v: &Value) -> (i64, i64, i64, i64) {
    (
        v["vertices"].as_i64().unwrap(),
        v["edges"].as_i64().unwrap(),
        v["faces"].as_i64().unwrap(),
        v["genus"].as_i64().unwrap(),
    )
}

#[test]
fn sierpinski_tetrahedron_counts() {
    let dir = tmp();
    let expect = [
        (1, (10, 30, 16, 3), 6),
        (2, (34, 126, 64, 15), 30),
        (3, (130, 510, 256, 63), 126),
    ];
    for (n, counts, loops) in expect {
        let out = dir.path().join(format!("s{n}.dlfl"));
        ok(&["sierpinski", "@tetrahedron", s(&out), "-n", &n.to_string()]);
        let v = info(s(&out), &[]);
        assert_eq!(vef(&v), counts, "iteration {n}");
        assert_eq!(v["self_loops"], loops, "iteration {n}");
        assert_eq!(v["components"], 1);
        // OBJ drops the self-loops from face lists.
        let obj = dir.path().join(format!("s{n}.obj"));
        ok(&["convert", s(&out), s(&obj)]);
        let o = info(s(&obj), &[]);
        assert_eq!(o["self_loops"], 0);
        assert_eq!(o["faces"].as_i64().unwrap(), counts.2);
    }
    assert!(bad(&["sierpinski", "@plane", s(&dir.path().join("x.obj"))]).contains("@plane"));
}

#[test]
fn menger_sponges() {
    let dir = tmp();
    let one = dir.path().join("m1.obj");
    ok(&["menger", "@cube", s(&one)]);
    assert_eq!(vef(&info(s(&one), &[])), (64, 144, 72, 5));
    let two = dir.path().join("m2.dlfl");
    ok(&[
        "menger",
        "@cube",
        s(&two),
        "-n",
        "2",
        "--thickness-ratio",
        "0.3333333333333333",
    ]);
    assert_eq!(info(s(&two), &[])["genus"], 81);
    let exact = dir.path().join("m3.obj");
    ok(&["menger", "@cube", s(&exact), "-n", "3", "--exact"]);
    let e = info(s(&exact), &[]);
    assert_eq!(e["genus"], 1409);
    assert!((e["volume"].as_f64().unwrap() - 8.0 * (20.0f64 / 27.0).powi(3)).abs() < 1e-9);
    let absolute = dir.path().join("ma.obj");
    ok(&["menger", "@cube", s(&absolute), "--thickness", "0.5"]);
    assert_eq!(info(s(&absolute), &[])["genus"], 5);
    for bad_args in [
        ["--thickness", "-1"],
        ["--thickness", "5"],
        ["--collapse-angle", "200"],
    ] {
        let target = dir.path().join("no.obj");
        let mut args = vec!["menger", "@cube", s(&target)];
        args.extend_from_slice(&bad_args);
        bad(&args);
        assert!(!target.exists());
    }
}

/// A multi-face handle (`--faces`): six unit cubes on the axes, the face
/// of each that looks at the origin joined through a hub. The six
/// directions are the octahedron's, so the hub is a cube (8 / 12 / 6)
/// with a square facing each selected square; each handle of s segments
/// between squares adds 4(s − 1) / 4(2s − 1) / 4s − 2; seven pieces
/// joined by six handles are one sphere.
#[test]
fn multi_face_handle_joins_six_cubes_through_a_hub() {
    let dir = tmp();
    let input = dir.path().join("six.obj");
    let corners = [
        [0, 0, 0],
        [1, 0, 0],
        [1, 1, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 0, 1],
        [1, 1, 1],
        [0, 1, 1],
    ];
    // Outward quads and their normals.
    let quads: [([usize; 4], [i32; 3]); 6] = [
        ([0, 3, 2, 1], [0, 0, -1]),
        ([4, 5, 6, 7], [0, 0, 1]),
        ([0, 1, 5, 4], [0, -1, 0]),
        ([2, 3, 7, 6], [0, 1, 0]),
        ([1, 2, 6, 5], [1, 0, 0]),
        ([0, 4, 7, 3], [-1, 0, 0]),
    ];
    let (mut text, mut facing) = (String::new(), Vec::new());
    for k in 0..6 {
        let (axis, sign) = (k / 2, if k % 2 == 0 { -1 } else { 1 });
        for c in corners {
            let p: Vec<f64> = (0..3)
                .map(|i| c[i] as f64 - 0.5 + if i == axis { 3.0 * sign as f64 } else { 0.0 })
                .collect();
            text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        }
        for (j, (q, n)) in quads.into_iter().enumerate() {
            // Face 6k + j in file order; this one looks at the origin.
            if n[axis] == -sign {
                facing.push((6 * k + j).to_string());
            }
            let v: Vec<String> = q.iter().map(|i| (8 * k + i + 1).to_string()).collect();
            text += &format!("f {}\n", v.join(" "));
        }
    }
    std::fs::write(&input, text).unwrap();
    assert_eq!(facing.len(), 6);
    let out = dir.path().join("star.obj");
    let segments = 3usize;
    ok(&[
        "handle",
        s(&input),
        s(&out),
        "--faces",
        &facing.join(","),
        "--segments",
        &segments.to_string(),
    ]);
    let (k, sg) = (6, segments as i64);
    let want = (
        48 + 8 + k * 4 * (sg - 1),
        72 + 12 + k * 4 * (2 * sg - 1),
        36 + 6 + k * (4 * sg - 2),
        0,
    );
    assert_eq!(vef(&info(s(&out), &[])), want);
    assert_eq!(info(s(&out), &[])["components"], 1);
    // Refusals name the user's face numbers and write nothing.
    let missing = dir.path().join("x.obj");
    let twice = format!("{0},{0},{1},{2}", facing[0], facing[1], facing[2]);
    assert!(
        bad(&["handle", s(&input), s(&missing), "--faces", &twice])
            .contains(&format!("face {} is selected twice", facing[0]))
    );
    assert!(bad(&["handle", s(&input), s(&missing), "--faces", "0,1"]).contains("at least four"));
    assert!(!missing.exists());
}

/// The arguments of `holey handle @cube OUT --from FROM --to TO`, then
/// `extra`.
fn cube_handle<'a>(out: &'a Path, from: &'a str, to: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec!["handle", "@cube", s(out), "--from", from, "--to", to];
    args.extend_from_slice(extra);
    args
}

#[test]
fn curved_handles() {
    let dir = tmp();
    let out = dir.path().join("h.obj");
    // Faces 0 (−z) and 5 (+z) of the cube, 3 segments: +8 V, +20 E, +10 F.
    let weights = ["--segments", "3", "--w1", "1", "--w2", "1"];
    ok(&cube_handle(&out, "0:0", "5:0", &weights));
    assert_eq!(vef(&info(s(&out), &[])), (16, 32, 16, 1));
    let tunnel = dir.path().join("t.obj");
    let weights = ["--segments", "2", "--w1", "-1", "--w2", "-1"];
    ok(&cube_handle(&tunnel, "0:0", "5:2", &weights));
    assert_eq!(info(s(&tunnel), &[])["genus"], 1);
    // The same handle along TopMod's Bézier: the same counts, another
    // curve (the middle ring sits elsewhere, so the files differ).
    let bezier = dir.path().join("b.obj");
    let curve = ["--segments", "3", "--curve", "bezier"];
    ok(&cube_handle(&bezier, "0:0", "5:0", &curve));
    assert_eq!(vef(&info(s(&bezier), &[])), (16, 32, 16, 1));
    assert_ne!(
        std::fs::read(&out).unwrap(),
        std::fs::read(&bezier).unwrap()
    );
    // Refused, naming what is wrong where the message must (an empty
    // needle: any refusal), and nothing is written.
    let missing = dir.path().join("x.obj");
    let refusals: [(&str, &str, &[&str], &str); 6] = [
        ("0:0", "5:0", &["--curve", "spline"], "spline"),
        ("99:0", "5:0", &[], "face 99"),
        ("0:9", "5:0", &[], "corner 9"),
        ("0:0", "0:1", &[], ""),
        ("0:0", "5:0", &["--segments", "0"], ""),
        ("zero", "5:0", &[], ""),
    ];
    for (from, to, extra, needle) in refusals {
        let err = bad(&cube_handle(&missing, from, to, extra));
        assert!(
            err.contains(needle),
            "--from {from} --to {to} {extra:?}: {err}"
        );
        assert!(!missing.exists());
    }
}

/// The arguments of `holey rind SHAPE OUT --thickness THICKNESS`, then
/// `--punch` or `--peel` (`how`) with the face list `faces`.
fn rind<'a>(
    shape: &'a str,
    out: &'a Path,
    thickness: &'a str,
    how: &'a str,
    faces: &'a str,
) -> [&'a str; 7] {
    ["rind", shape, s(out), "--thickness", thickness, how, faces]
}

#[test]
fn rind_punch_and_peel() {
    let dir = tmp();
    // .dlfl keeps the thin walls between neighbouring punches exactly; as a
    // soup two coincident wall quads read as non-manifold.
    let out = dir.path().join("r.dlfl");
    // k holes in a genus-0 crust: genus k − 1.
    for (punch, genus) in [("0", 0), ("0,5", 1), ("0,1,2,5", 3)] {
        ok(&rind("@cube", &out, "0.2", "--punch", punch));
        let v = info(s(&out), &[]);
        assert_eq!(v["genus"], genus, "punch {punch}");
        assert_eq!(v["closed"], true);
    }
    let torus = dir.path().join("rt.dlfl");
    ok(&rind("@torus", &torus, "0.05", "--punch", "0,100"));
    assert_eq!(info(s(&torus), &[])["genus"], 3); // 2g + k − 1
    let peeled = dir.path().join("p.obj");
    ok(&rind("@cube", &peeled, "0.2", "--peel", "1,2"));
    assert_eq!(info(s(&peeled), &[])["two_gons"], 0);
    // Punching a face twice is a note, not an error.
    let twice = holey(&rind("@cube", &out, "0.2", "--punch", "3,3"));
    assert!(twice.status.success());
    assert!(String::from_utf8_lossy(&twice.stderr).contains("face 3"));
    let none = dir.path().join("none.obj");
    bad(&rind("@cube", &none, "5", "--punch", "0"));
    bad(&rind("@cube", &none, "0.2", "--punch", "42"));
    assert!(!none.exists());
}

#[test]
fn subdivision_counts() {
    let dir = tmp();
    let cc = dir.path().join("cc.obj");
    ok(&["subdivide", "@cube", s(&cc), "--scheme", "catmull-clark"]);
    assert_eq!(vef(&info(s(&cc), &[])), (26, 48, 24, 0));
    let ds = dir.path().join("ds.obj");
    ok(&["subdivide", "@cube", s(&ds), "--scheme", "doo-sabin"]);
    assert_eq!(vef(&info(s(&ds), &[])), (24, 48, 26, 0));
    let torus = dir.path().join("t.obj");
    ok(&[
        "subdivide",
        "@torus",
        s(&torus),
        "--scheme",
        "catmull-clark",
        "-n",
        "2",
    ]);
    assert_eq!(info(s(&torus), &[])["genus"], 1);
    bad(&["subdivide", "@cube", s(&cc), "--scheme", "loop"]);
}

#[test]
fn render_is_deterministic_and_checks_its_options() {
    let dir = tmp();
    let a = dir.path().join("a.png");
    let b = dir.path().join("b.png");
    ok(&["render", "@torus", s(&a), "--edges", "--size", "320x240"]);
    ok(&["render", "@torus", s(&b), "--edges", "--size", "320x240"]);
    let (pa, pb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert_eq!(&pa[1..4], b"PNG");
    assert_eq!(pa, pb, "the same input gave different pictures");
    bad(&[
        "render",
        "@torus",
        s(&dir.path().join("c.png")),
        "--size",
        "0x10",
    ]);
    bad(&[
        "render",
        "@torus",
        s(&dir.path().join("c.png")),
        "--view",
        "sideways",
    ]);
    bad(&["render", "@torus", s(&dir.path().join("c.jpg"))]);
}

#[test]
fn demo_writes_the_gallery() {
    let dir = tmp();
    let out = holey(&["demo", "--out", s(dir.path()), "--size", "240x180"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = String::from_utf8(out.stdout).unwrap();
    let index = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    for name in [
        "sierpinski-tetrahedron",
        "menger-2",
        "menger-3-exact",
        "rind-sphere",
        "handle-torus",
        "cup",
    ] {
        assert!(table.contains(name), "table lacks {name}");
        assert!(
            index.contains(&format!("{name}.png")),
            "gallery lacks {name}"
        );
        for ext in ["obj", "dlfl", "png"] {
            assert!(
                dir.path().join(format!("{name}.{ext}")).exists(),
                "{name}.{ext}"
            );
        }
    }
    // The table's genus column agrees with the files.
    let genus = |name: &str| {
        info(s(&dir.path().join(format!("{name}.dlfl"))), &[])["genus"]
            .as_i64()
            .unwrap()
    };
    assert_eq!(genus("sierpinski-tetrahedron"), 63);
    assert_eq!(genus("menger-3-exact"), 1409);
    assert_eq!(genus("cup"), 1);
}

/// Writes the OBJ file `from` to `to` with each vertex `p` moved to
/// `moved(p)`; every other line is kept as it is.
fn move_obj_vertices(from: &Path, to: &Path, moved: impl Fn([f64; 3]) -> [f64; 3]) {
    let text = std::fs::read_to_string(from).unwrap();
    let out: String = text
        .lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(rest) => {
                let c: Vec<f64> = rest
                    .split_whitespace()
                    .map(|t| t.parse().unwrap())
                    .collect();
                let [x, y, z] = moved([c[0], c[1], c[2]]);
                format!("v {x} {y} {z}\n")
            }
            None => format!("{l}\n"),
        })
        .collect();
    std::fs::write(to, out).unwrap();
}

/// Shifts the vertices of an OBJ file by (dx, dy, dz), in place.
fn shift_obj(path: &Path, [dx, dy, dz]: [f64; 3]) {
    move_obj_vertices(path, path, |[x, y, z]| [x + dx, y + dy, z + dz]);
}

/// The primitive `shape` written twice in `dir`, as `a.obj` and as `b.obj`
/// moved by `shift`: the two inputs of a Boolean.
fn shifted_pair(dir: &Path, shape: &str, shift: [f64; 3]) -> (PathBuf, PathBuf) {
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    ok(&["primitive", shape, s(&a)]);
    ok(&["primitive", shape, s(&b)]);
    shift_obj(&b, shift);
    (a, b)
}

/// Two cubes [-1,1]³, the second shifted by exactly 1 in x: coplanar
/// faces and coinciding vertices and edges wherever they touch. The union
/// is the box [-1,2]×[-1,1]², volume 12. The containment's exact result
/// is not a closed 2-manifold there (duplicate triangles), so `holey
/// union` takes the exact winding-number arrangement, which is: the
/// volume is exact and nothing is nudged.
#[test]
fn union_of_lattice_aligned_cubes() {
    let dir = tmp();
    let (a, b) = shifted_pair(dir.path(), "@cube:4", [1.0, 0.0, 0.0]);
    let u = dir.path().join("u.obj");
    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&u)]);
    let m = info(s(&u), &[]);
    assert_one_closed_sphere(&m, "union");
    assert_eq!(m["volume"].as_f64(), Some(12.0));
    assert_eq!(report["method"], "winding");
    assert_eq!(report["perturbation_retries"], 0);
    assert_eq!(report["output_intersecting_pairs"], 0);
    // --exact keeps the containment's first attempt, whatever it gives.
    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&u), "--exact"]);
    assert_eq!(report["method"], "containment");
    assert_eq!(report["perturbation_retries"], 0);
}

/// `holey intersection` and `holey difference` of two cubes [-1,1]³, the
/// second moved by (0.9, 0.7, 0.55) (general position: no faces in one
/// plane): the overlap is the box 1.1 × 1.3 × 1.45, so A ∩ B has that
/// volume and A − B the rest of 8; both are single closed solids of genus
/// 0 without self-intersections. An open B is refused by name, and
/// nothing is written.
#[test]
fn intersection_and_difference_of_two_cubes() {
    let dir = tmp();
    let (a, b) = shifted_pair(dir.path(), "@cube:4", [0.9, 0.7, 0.55]);
    let overlap = 1.1 * 1.3 * 1.45;
    for (cmd, want) in [("intersection", overlap), ("difference", 8.0 - overlap)] {
        let out = dir.path().join(format!("{cmd}.obj"));
        let report = reported(dir.path(), &[cmd, s(&a), s(&b), s(&out)]);
        let m = info(s(&out), &[]);
        assert_one_closed_sphere(&m, cmd);
        let v = m["volume"].as_f64().unwrap();
        assert!(
            (v - want).abs() < 1e-12,
            "{cmd}: volume {v}, expected {want}"
        );
        assert_eq!(selfint(&out)["intersecting_pairs"], 0, "{cmd}");
        assert!(
            report["intersection_curves"].as_u64().unwrap() >= 1,
            "{cmd}"
        );
    }
    // An open solid is classified by its generalized winding number (the
    // winding-number arrangement), and the report says which one was open.
    let open = dir.path().join("open.obj");
    let text = std::fs::read_to_string(&b).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    let last_face = lines.iter().rposition(|l| l.starts_with("f ")).unwrap();
    lines.remove(last_face);
    std::fs::write(&open, lines.join("\n")).unwrap();
    let out = dir.path().join("open.ply");
    let report = reported(dir.path(), &["difference", s(&a), s(&open), s(&out)]);
    assert_eq!(report["inputs_closed"], serde_json::json!([true, false]));
}

/// The OBJ files `parts` as one file: their vertices in order, face
/// indices offset.
fn concatenate_obj(parts: &[&Path], out: &Path) {
    let (mut verts, mut faces, mut base) = (String::new(), String::new(), 0usize);
    for p in parts {
        let text = std::fs::read_to_string(p).unwrap();
        let mut count = 0;
        for line in text.lines() {
            if let Some(rest) = line.strip_prefix("v ") {
                verts += &format!("v {rest}\n");
                count += 1;
            } else if let Some(rest) = line.strip_prefix("f ") {
                let ids: Vec<String> = rest
                    .split_whitespace()
                    .map(|i| (i.parse::<usize>().unwrap() + base).to_string())
                    .collect();
                faces += &format!("f {}\n", ids.join(" "));
            }
        }
        base += count;
    }
    std::fs::write(out, verts + &faces).unwrap();
}

/// The winding-number Booleans (issue 14) from the command line: one file
/// holding two crossing cubes unites into their union (one input: the
/// solid it encloses); three inputs unite; a difference whose first solid
/// crosses itself takes the arrangement too. Volumes by inclusion and
/// exclusion of boxes; the report says which method ran.
#[test]
fn crossing_and_many_solids_by_the_winding_number() {
    let dir = tmp();
    let (a, b, c) = (
        dir.path().join("a.obj"),
        dir.path().join("b.obj"),
        dir.path().join("c.obj"),
    );
    for p in [&a, &b, &c] {
        ok(&["primitive", "@cube", s(p)]);
    }
    shift_obj(&b, [0.9, 0.7, 0.55]);
    shift_obj(&c, [10.0, 0.0, 0.0]);
    let shells = dir.path().join("shells.obj");
    concatenate_obj(&[&a, &b], &shells);
    assert!(selfint(&shells)["intersecting_pairs"].as_u64().unwrap() > 0);
    let overlap = 1.1 * 1.3 * 1.45;
    let united = 16.0 - overlap;
    let check = |out: &Path, want: f64, what: &str| {
        let m = info(s(out), &[]);
        assert_eq!(m["closed"], true, "{what}");
        assert_eq!(m["manifold"], true, "{what}");
        let v = m["volume"].as_f64().unwrap();
        assert!(
            (v - want).abs() < 1e-12,
            "{what}: volume {v}, expected {want}"
        );
        assert_eq!(selfint(out)["intersecting_pairs"], 0, "{what}");
    };
    let out = dir.path().join("one.obj");
    let report = reported(dir.path(), &["union", s(&shells), s(&out)]);
    check(&out, united, "one input");
    assert_eq!(report["method"], "winding");
    assert_eq!(report["output_intersecting_pairs"], 0);
    assert!(report["cells"].as_u64().unwrap() >= 2);

    let out = dir.path().join("three.obj");
    ok(&["union", s(&a), s(&b), s(&c), s(&out)]);
    check(&out, united + 8.0, "three inputs");

    let out = dir.path().join("minus.obj");
    let report = reported(dir.path(), &["difference", s(&shells), s(&c), s(&out)]);
    check(&out, united, "crossing minus apart");
    assert_eq!(report["method"], "winding");

    // An open input counts by its generalized winding number, and the
    // report says it is open: a cube without its top, apart from the
    // others, is kept as it is (w ≥ ½ only inside it, near its hole less).
    let open = dir.path().join("open.obj");
    let text = std::fs::read_to_string(&c).unwrap();
    let kept: Vec<&str> = text.lines().filter(|l| !l.starts_with("f 5")).collect();
    std::fs::write(&open, kept.join("\n")).unwrap();
    let out = dir.path().join("open_union.obj");
    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&open), s(&out)]);
    assert_eq!(
        report["inputs_closed"],
        serde_json::json!([true, true, false])
    );
    // The same as the union with the closed cube, less its two top
    // triangles.
    let closed_c = info(s(&dir.path().join("three.obj")), &[])["faces"]
        .as_u64()
        .unwrap();
    assert_eq!(info(s(&out), &[])["faces"].as_u64().unwrap(), closed_c - 2);
}

/// `holey union` of two unit icospheres one unit apart along x: one
/// closed genus-0 solid whose volume is the two spheres' minus the
/// overlap. The overlap of the polyhedra is bounded by the lens of the
/// circumscribed spheres (radius 1), and the result is checked against
/// the exact lens formula within the polyhedral gap. The shifted sphere's
/// curve points meet the first's exactly in places (the icosphere is
/// symmetric about x = ½), so the containment's cut merges points. They
/// are points, not faces on faces, and no triangle of the cut crosses
/// anything: the policy keeps the containment's exact result, which the
/// arrangement (`--winding`), the containment's own first attempt
/// (`--exact`) and the synthesized motion match.
#[test]
fn union_of_two_spheres_is_one_closed_solid() {
    let dir = tmp();
    let (a, b) = shifted_pair(dir.path(), "@sphere:4", [1.0, 0.0, 0.0]);
    let u = dir.path().join("u.ply");
    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&u)]);
    let m = info(s(&u), &[]);
    assert_one_closed_sphere(&m, "union");
    let one = info(s(&a), &[])["volume"].as_f64().unwrap();
    let v = m["volume"].as_f64().unwrap();
    let pi = std::f64::consts::PI;
    let lens = pi * (4.0 + 1.0) * (2.0f64 - 1.0).powi(2) / 12.0;
    let ball = 4.0 / 3.0 * pi;
    // The icosphere's volume is a fraction of the ball's; so, roughly, is
    // the overlap's.
    let want = 2.0 * one - lens * one / ball;
    assert!(
        (v - want).abs() < 0.01 * want,
        "union volume {v}, expected about {want}"
    );
    assert_eq!(report["method"], "containment");
    assert!(report["merged_points"].as_u64().unwrap() > 0);
    assert_eq!(report["output_intersecting_pairs"], 0);
    assert_eq!(report["perturbation_retries"], 0);
    assert_eq!(report["intersection_curves"], 1);
    let uw = dir.path().join("uw.ply");
    let arranged = reported(dir.path(), &["union", s(&a), s(&b), s(&uw), "--winding"]);
    assert_eq!(arranged["method"], "winding");
    let vw = info(s(&uw), &[])["volume"].as_f64().unwrap();
    assert!((v - vw).abs() < 1e-12 * vw, "{v} vs the arrangement's {vw}");
    assert!(report["seconds"]["total"].as_f64().is_some());
    // No self-intersection is left.
    assert_eq!(selfint(&u)["intersecting_pairs"], 0);
    // The containment's own first attempt: the same solid, the parity
    // computed by containment rays, not by simulating the motion.
    let uc = dir.path().join("uc.ply");
    let exact = reported(dir.path(), &["union", s(&a), s(&b), s(&uc), "--exact"]);
    let mc = info(s(&uc), &[]);
    assert_eq!(exact["method"], "containment");
    assert_eq!(exact["collisions"], 0);
    assert!(exact["containment_rays"].as_u64().unwrap() >= 2);
    assert!(exact["merged_points"].as_u64().unwrap() > 0);
    assert_eq!(mc["faces"], m["faces"]);
    let v0 = mc["volume"].as_f64().unwrap();
    assert!((v - v0).abs() < 1e-12 * v0, "{v} vs {v0}");
    // The motion itself, through the whole pipeline, gives the same solid.
    let um = dir.path().join("um.ply");
    let motion = reported(
        dir.path(),
        &["union", s(&a), s(&b), s(&um), "--via-motion", "--exact"],
    );
    let mm = info(s(&um), &[]);
    assert_eq!(motion["method"], "motion");
    assert!(motion["collisions"].as_u64().unwrap() > 0);
    assert_eq!(motion["containment_rays"], 0);
    assert_eq!(mm["faces"], mc["faces"]);
    assert_eq!(mm["vertices"], mc["vertices"]);
    let vm = mm["volume"].as_f64().unwrap();
    assert!((vm - v0).abs() < 1e-12 * v0, "{vm} vs {v0}");
    assert_eq!(motion["raw_odd_vertices"], exact["raw_odd_vertices"]);
    // Nudged (the motion's default), the same solid to the nudge's size.
    ok(&["union", s(&a), s(&b), s(&um), "--via-motion"]);
    let vn = info(s(&um), &[])["volume"].as_f64().unwrap();
    assert!((vn - v0).abs() < 1e-7 * v0, "{vn} vs {v0}");
}

/// An open B (a sphere with one face removed) bounds no solid exactly:
/// `holey union` classifies it by its generalized winding number, which
/// keeps B's surface outside A and its hole as it is (the report says B is
/// open); `--via-motion` runs the synthesized motion through the whole
/// pipeline instead: collisions are found, no ray is cast.
#[test]
fn union_with_an_open_surface() {
    let dir = tmp();
    let (a, b) = shifted_pair(dir.path(), "@sphere:2", [1.0, 0.0, 0.0]);
    let u = dir.path().join("u.ply");
    let text = std::fs::read_to_string(&b).unwrap();
    let last_face = text.rfind("\nf ").unwrap();
    std::fs::write(&b, &text[..last_face + 1]).unwrap();
    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&u)]);
    assert_eq!(report["method"], "winding");
    assert_eq!(report["inputs_closed"], serde_json::json!([true, false]));
    assert_eq!(report["intersection_curves"], 1);
    // The removed face's three sides are the only boundary.
    assert_eq!(report["unpaired_edges"], 3);
    let m = info(s(&u), &[]);
    assert_eq!(m["boundary_edges"], 3);
    assert_eq!(m["components"], 1);

    let report = reported(dir.path(), &["union", s(&a), s(&b), s(&u), "--via-motion"]);
    assert!(report["collisions"].as_u64().unwrap() > 0);
    assert_eq!(report["containment_rays"], 0);
    assert_eq!(report["intersection_curves"], 1);
}

/// `holey topo` with zero motion returns the mesh unchanged (quads come
/// back fan-triangulated: twice the faces, same surface), and a
/// mismatched AFTER is a clear error with status 2.
#[test]
fn topo_checks_its_frames() {
    let dir = tmp();
    let a = dir.path().join("a.obj");
    let out = dir.path().join("out.obj");
    let parity = dir.path().join("p.ply");
    ok(&["primitive", "@torus", s(&a)]);
    ok(&["topo", s(&a), s(&a), s(&out), "--parity", s(&parity)]);
    let before = info(s(&a), &["--weld"]);
    let after = info(s(&out), &[]);
    for key in ["genus", "closed", "components", "vertices"] {
        assert_eq!(before[key], after[key], "{key}");
    }
    assert_eq!(
        after["faces"].as_u64(),
        before["faces"].as_u64().map(|f| 2 * f)
    );
    let (v0, v1) = (
        before["volume"].as_f64().unwrap(),
        after["volume"].as_f64().unwrap(),
    );
    assert!((v0 - v1).abs() < 1e-12 * v0, "volume {v0} -> {v1}");
    let p = info(s(&parity), &[]);
    assert_eq!(p["vertices"], before["vertices"]);
    let err = bad(&["topo", s(&a), "@sphere", s(&out.with_extension("x.obj"))]);
    assert!(err.contains("same mesh"), "{err}");
    let err = bad(&["union", "@cube", "@cube", s(&out), "--direction", "0,0,0"]);
    assert!(err.contains("non-zero"), "{err}");
}

/// `holey selfint` counts the crossing pairs of two triangles exactly, and
/// `holey resolve` cuts them so that nothing crosses.
#[test]
fn selfint_and_resolve_on_crossing_triangles() {
    let dir = tmp();
    let m = dir.path().join("x.obj");
    let r = dir.path().join("r.obj");
    std::fs::write(
        &m,
        "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0.5 0.5 -1\nv 0.5 0.5 1\nv 3 3 0\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let si: Value = serde_json::from_str(&ok(&["selfint", "--json", "--pairs", s(&m)])).unwrap();
    assert_eq!(si["intersecting_pairs"], 1);
    assert_eq!(si["intersection_curves"], 1);
    assert_eq!(si["pairs"][0], serde_json::json!([0, 1]));
    // The curve as geometry: the segment from where the second
    // triangle's edge pierces the first, (0.5, 0.5, 0), to where the
    // first's edge x + y = 2 crosses the second, (1, 1, 0).
    let c = dir.path().join("c.obj");
    ok(&["selfint", s(&m), "--curves", s(&c)]);
    let text = std::fs::read_to_string(&c).unwrap();
    let mut points: Vec<[f64; 3]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    points.sort_by(|a, b| a[0].total_cmp(&b[0]));
    assert_eq!(points, vec![[0.5, 0.5, 0.0], [1.0, 1.0, 0.0]]);
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
    assert_eq!(lines.len(), 1);
    assert_eq!(text.lines().filter(|l| l.starts_with("g curve")).count(), 1);
    let err = bad(&["selfint", s(&m), "--curves", "c.png"]);
    assert!(err.contains(".obj"), "{err}");
    ok(&["resolve", s(&m), s(&r)]);
    assert_eq!(selfint(&r)["intersecting_pairs"], 0);
    let out = info(s(&r), &[]);
    assert!(out["faces"].as_u64().unwrap() > 2);
    let err = bad(&["selfint", s(&dir.path().join("missing.obj"))]);
    assert!(err.contains("missing.obj"), "{err}");
}

/// `a` moved by a Gaussian bump: vertices near `centre` move by up to `d`.
fn bumped_obj(from: &Path, to: &Path, centre: [f64; 3], d: [f64; 3], sigma: f64) {
    move_obj_vertices(from, to, |p| {
        let r2: f64 = (0..3).map(|k| (p[k] - centre[k]).powi(2)).sum();
        let w = (-r2 / (sigma * sigma)).exp();
        [p[0] + w * d[0], p[1] + w * d[1], p[2] + w * d[2]]
    });
}

/// Vertex colours of a binary PLY written by holey (x, y, z as doubles,
/// then red, green, blue).
fn ply_colours(path: &Path) -> Vec<[u8; 3]> {
    let bytes = std::fs::read(path).unwrap();
    let end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    let header = String::from_utf8_lossy(&bytes[..end]).into_owned();
    assert!(header.contains("binary_little_endian"), "{header}");
    assert!(header.contains("property double x"), "{header}");
    let n: usize = header
        .lines()
        .find_map(|l| l.strip_prefix("element vertex "))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    (0..n)
        .map(|i| {
            let at = end + i * 27 + 24;
            [bytes[at], bytes[at + 1], bytes[at + 2]]
        })
        .collect()
}

/// `holey topo` on a real frame: a sphere's north pole pushed through its
/// south pole punches a tunnel (genus 1), with every scheme and the
/// paper's float collision test. The report counts what happened, and the
/// parity picture colours the input's vertices as the report counts them
/// (grey even, red odd, yellow odd only before correction, blue odd only
/// after).
#[test]
fn topo_punches_a_tunnel_and_reports_it() {
    let dir = tmp();
    let a = dir.path().join("a.obj");
    let b = dir.path().join("b.obj");
    let out = dir.path().join("out.obj");
    let p = dir.path().join("p.ply");
    ok(&["primitive", "@sphere:4", s(&a)]);
    bumped_obj(&a, &b, [0.013, 0.007, 1.0], [0.0, 0.0, -2.6], 0.35);
    for extra in [&[][..], &["--scheme", "majority"], &["--float-ccd"]] {
        let mut args = vec!["topo", s(&a), s(&b), s(&out), "--parity", s(&p)];
        args.extend_from_slice(extra);
        let report = reported(dir.path(), &args);
        let m = info(s(&out), &[]);
        assert_eq!(m["closed"], true, "{extra:?}");
        assert_eq!(m["manifold"], true, "{extra:?}");
        assert_eq!(m["genus"], 1, "{extra:?}: a tunnel");
        assert!(report["collisions"].as_u64().unwrap() > 0, "{extra:?}");
        assert!(
            report["intersection_curves"].as_u64().unwrap() >= 1,
            "{extra:?}"
        );
        assert!(
            report["triangles_deleted"].as_u64().unwrap() > 0,
            "{extra:?}"
        );
        for key in [
            "collisions",
            "intersection_points",
            "seconds",
            "perturbation_retries",
        ] {
            assert!(!report[key].is_null(), "{extra:?}: no {key}");
        }
        let colours = ply_colours(&p);
        assert_eq!(
            colours.len(),
            info(s(&a), &[])["vertices"].as_u64().unwrap() as usize
        );
        let count = |c: [u8; 3]| colours.iter().filter(|&&x| x == c).count() as u64;
        let (grey, red, yellow, blue) = (
            count([170, 170, 170]),
            count([220, 40, 40]),
            count([240, 200, 30]),
            count([40, 90, 230]),
        );
        assert_eq!(grey + red + yellow + blue, colours.len() as u64);
        assert_eq!(red + yellow, report["raw_odd_vertices"].as_u64().unwrap());
        assert_eq!(
            red + blue,
            report["corrected_odd_vertices"].as_u64().unwrap()
        );
        assert!(red > 0 && grey > 0, "{extra:?}");
    }
    // Same vertex count, different faces: refused before any work.
    let c = dir.path().join("c.obj");
    let text = std::fs::read_to_string(&a).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let first_face = lines.iter().position(|l| l.starts_with("f ")).unwrap();
    let f: Vec<&str> = lines[first_face].split_whitespace().collect();
    lines[first_face] = format!("f {} {} {}", f[1], f[3], f[2]);
    std::fs::write(&c, lines.join("\n") + "\n").unwrap();
    let err = bad(&["topo", s(&a), s(&c), s(&out)]);
    assert!(err.contains("faces") && err.contains("differ"), "{err}");
    // A parity picture that cannot be written is refused before the
    // result is: nothing is written.
    let never = dir.path().join("never.obj");
    let err = bad(&["topo", s(&a), s(&b), s(&never), "--parity", "p.png"]);
    assert!(err.contains(".ply"), "{err}");
    assert!(!never.exists());
}

/// Bad input to the topology commands gets a clear error naming the
/// problem and the place, exit status 2, never a panic: NaN and infinite
/// coordinates, an index out of range, for `topo`, `union`, `selfint` and
/// `resolve` alike.
#[test]
fn topology_commands_refuse_bad_input() {
    let dir = tmp();
    let good = dir.path().join("good.obj");
    let out = dir.path().join("out.obj");
    ok(&["primitive", "@tetrahedron", s(&good)]);
    let cases = [
        (
            "nan.obj",
            "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
            "nan.obj:3",
        ),
        (
            "inf.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 inf\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
            "inf.obj:4",
        ),
        (
            "index.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 9\nf 1 4 2\nf 2 4 3\n",
            "index.obj:6",
        ),
    ];
    for (name, text, place) in cases {
        let path = file_in(dir.path(), name, text);
        for args in [
            vec!["topo", s(&path), s(&path), s(&out)],
            vec!["topo", s(&good), s(&path), s(&out)],
            vec!["union", s(&good), s(&path), s(&out)],
            vec!["union", s(&path), s(&good), s(&out)],
            vec!["selfint", s(&path)],
            vec!["resolve", s(&path), s(&out)],
        ] {
            let err = bad(&args);
            assert!(err.contains(place), "{args:?}: {err}");
            assert!(!err.contains("panicked"), "{args:?}: {err}");
        }
    }
    assert!(!out.exists(), "nothing was written");
}

/// `--weld`: a square given as two triangles whose shared corners are
/// repeated, one of them off by 1e-6, welds into one piece at a distance
/// above the gap (absolute or as a share of the diagonal), stays two
/// pieces below it, and a weld distance that is not one is refused.
#[test]
fn convert_and_sculpt_weld_by_distance() {
    let dir = tmp();
    let soup = file_in(
        dir.path(),
        "soup.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1.000001 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n",
    );
    let out = dir.path().join("out.obj");
    let (soup, out) = (s(&soup), s(&out));
    ok(&["convert", soup, out, "--weld", "0"]);
    assert_eq!(info(out, &[])["vertices"], 5);
    ok(&["convert", soup, out, "--weld", "1e-5"]);
    assert_eq!(info(out, &[])["vertices"], 4);
    assert_eq!(info(out, &[])["components"], 1);
    ok(&["convert", soup, out, "--weld", "0.001%"]);
    assert_eq!(info(out, &[])["vertices"], 4);
    let e = bad(&["convert", soup, out, "--weld=-1"]);
    assert!(e.contains("weld distance"), "{e}");
    let strokes = file_in(
        dir.path(),
        "s.json",
        r#"{"strokes": [{"brush": "smooth", "radius": 0.5, "strength": 0.5, "path": [[0.5,0.5,0]]}]}"#,
    );
    ok(&["sculpt", soup, s(&strokes), out, "--weld", "1e-5"]);
    assert_eq!(info(out, &[])["vertices"], 4);
}

/// `holey sculpt --audit -v` judges a grab by its release: Figure 1's
/// poke-through (the top of a sphere grabbed down through its bottom)
/// passes through itself while dragged, and those frames are shown as
/// "dragging, before the release" without a verdict; the release, a
/// closed torus-like solid that crosses nothing, is not worse than the
/// sphere it came from (a stroke file written here).
#[test]
fn sculpt_audit_judges_a_grab_at_its_release() {
    let dir = tmp();
    let strokes = file_in(
        dir.path(),
        "grab.json",
        r#"{"strokes": [{"brush": "grab", "radius": 0.7, "strength": 1,
            "path": [[0,0,1], [0,0,0], [0,0,-1.5], [0,0,-2.5], [0,0,-2.5]]}]}"#,
    );
    let out = dir.path().join("out.obj");
    let run = holey(&["sculpt", "@sphere:3", s(&strokes), s(&out), "--audit", "-v"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    let dragging = err
        .lines()
        .filter(|l| l.contains("(dragging, before the release)"))
        .count();
    assert_eq!(dragging, 4, "{err}");
    assert!(
        err.lines()
            .any(|l| l.contains("dragging") && !l.contains(" 0 intersecting pairs")),
        "the dragged sphere passes through itself: {err}"
    );
    assert!(!err.contains("[worse"), "{err}");
    assert!(!err.contains("worse than the input"), "{err}");
    assert!(err.contains("stroke 0 frame 4: "), "{err}");
}

/// A reader that closes the pipe early (`holey … | head -1`) gets a
/// clear error from the commands that print, never a panic: stdout's
/// read end is closed before the command writes, for a report of each
/// kind (text, JSON, a help text).
#[test]
fn a_closed_stdout_is_an_error_not_a_panic() {
    use std::process::{Command, Stdio};
    for args in [
        &["selfint", "@sphere:3", "--pairs"][..],
        &["selfint", "--json", "@sphere:3"],
        &["info", "--json", "@sphere:3"],
        &["primitives"],
    ] {
        // The pipe's reading end is closed before the program starts: a
        // reader closed after the start races a short output into the
        // pipe's buffer, and the write then succeeds.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_holey"))
            .args(args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "holey {args:?}: {err}");
        assert!(
            err.contains("cannot write to stdout"),
            "holey {args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "holey {args:?}: {err}");
    }
}
