//! End-to-end tests of `holey batch`: the real binary over folders,
//! patterns and lists of files written by the tests themselves.

#![allow(clippy::unwrap_used)] // test helpers: a failed unwrap is a failed test

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

mod common;
use common::{holey, ok, refused};

fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).expect("utf-8 output")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn info(mesh: &Path) -> Value {
    serde_json::from_str(&ok(&["info", "--json", s(mesh)])).expect("info prints JSON")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().expect("a temporary directory")
}

/// Writes a built-in primitive to `folder/name`.
fn primitive(folder: &Path, primitive: &str, name: &str) -> PathBuf {
    let path = folder.join(name);
    ok(&["primitive", primitive, s(&path)]);
    path
}

/// A folder `models` in `dir` with the given primitives written into it,
/// as (primitive, file name).
fn models_folder(dir: &Path, files: &[(&str, &str)]) -> PathBuf {
    let models = dir.join("models");
    std::fs::create_dir(&models).unwrap();
    for (name, file) in files {
        primitive(&models, name, file);
    }
    models
}

/// An OBJ whose third face names a vertex that does not exist.
fn malformed(folder: &Path, name: &str) -> PathBuf {
    let path = folder.join(name);
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n").unwrap();
    path
}

/// Two unit cubes overlapping by half, as one OBJ: a surface crossing
/// itself, which a union of one input repairs.
fn overlapping_cubes(folder: &Path, name: &str) -> PathBuf {
    let (corners, quads) = holey_testkit::unit_cube();
    let mut text = String::new();
    for offset in [0.0, 0.5] {
        for [x, y, z] in corners {
            text += &format!("v {} {} {}\n", x + offset, y + offset, z + offset);
        }
    }
    for base in [0, 8] {
        for quad in quads {
            let [a, b, c, d] = quad.map(|k| k + base + 1);
            text += &format!("f {a} {b} {c} {d}\n");
        }
    }
    let path = folder.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The file names in a folder, sorted.
fn listing(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The JSON lines of a reporting run.
fn lines(text: &str) -> Vec<Value> {
    text.lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{l:?} is not JSON: {e}")))
        .collect()
}

/// The "file" field of each line, as the file's name.
fn files_of(lines: &[Value]) -> Vec<String> {
    lines
        .iter()
        .map(|l| {
            let file = l["file"].as_str().expect("every line names its file");
            Path::new(file)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect()
}

#[test]
fn a_malformed_file_fails_alone() {
    let dir = tmp();
    let models = models_folder(
        dir.path(),
        &[
            ("@cube", "cube.obj"),
            ("@torus:12:8", "torus.off"),
            ("@tetrahedron", "tet.ply"),
        ],
    );
    malformed(&models, "bad.obj");
    // Not a mesh file: a folder gives only files with mesh extensions.
    std::fs::write(models.join("notes.txt"), "not a mesh").unwrap();
    let out_dir = dir.path().join("out");
    let out = holey(&[
        "batch",
        "convert",
        s(&models),
        "--format",
        "stl",
        "--out",
        s(&out_dir),
        "--jobs",
        "2",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(out.stdout.is_empty(), "convert prints nothing on stdout");
    assert_eq!(listing(&out_dir), ["cube.stl", "tet.stl", "torus.stl"]);
    // STL holds triangles: every face split, the shape kept.
    let cube = info(&out_dir.join("cube.stl"));
    assert_eq!(
        (cube["vertices"].as_u64(), cube["faces"].as_u64()),
        (Some(8), Some(12))
    );
    let torus = info(&out_dir.join("torus.stl"));
    assert_eq!(
        (torus["faces"].as_u64(), torus["genus"].as_u64()),
        (Some(192), Some(1))
    );
    assert_eq!(info(&out_dir.join("tet.stl"))["faces"], 4);
    let err = stderr(&out);
    assert!(
        err.lines()
            .any(|l| l.contains("bad.obj") && l.contains("vertex 9")),
        "the failure names its file and its fault: {err}"
    );
    assert!(
        err.contains("batch convert: 3 done, 1 failed, of 4 files"),
        "{err}"
    );
}

#[test]
fn a_report_gives_the_failed_file_a_line_with_its_error() {
    let dir = tmp();
    primitive(dir.path(), "@cube", "a.obj");
    malformed(dir.path(), "b.obj");
    primitive(dir.path(), "@tetrahedron", "c.obj");
    let out = holey(&["batch", "info", s(dir.path())]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let report = lines(&stdout(&out));
    assert_eq!(files_of(&report), ["a.obj", "b.obj", "c.obj"]);
    assert_eq!(report[0]["vertices"], 8);
    assert!(
        report[1]["error"]
            .as_str()
            .is_some_and(|e| e.contains("vertex 9")),
        "{}",
        report[1]
    );
    assert!(report[1].get("vertices").is_none());
    assert_eq!(report[2]["vertices"], 4);
    assert!(stderr(&out).contains("2 done, 1 failed, of 3 files"));
}

#[test]
fn info_over_a_folder_matches_info_on_each_file() {
    let dir = tmp();
    let meshes = [
        ("@cube", "a_cube.obj", 8),
        ("@torus:12:8", "b_torus.off", 96),
        ("@tetrahedron", "c_tet.ply", 4),
        ("@plane:4:3", "d_plane.obj", 20),
        ("@sphere:1", "e_sphere.stl", 42),
        ("@cube", "f_cube.dlfl", 8),
    ];
    for (p, name, _) in meshes {
        primitive(dir.path(), p, name);
    }
    for jobs in ["1", "2"] {
        let out = ok(&["batch", "info", "--json", s(dir.path()), "--jobs", jobs]);
        let report = lines(&out);
        // Input order: the folder's files by name, whatever finished first.
        let names: Vec<&str> = meshes.iter().map(|m| m.1).collect();
        assert_eq!(files_of(&report), names);
        for ((_, name, vertices), mut line) in meshes.iter().zip(report) {
            assert_eq!(line["vertices"], *vertices, "{name}");
            let single = info(&dir.path().join(name));
            let fields = line.as_object_mut().unwrap();
            assert!(fields.remove("file").is_some());
            assert_eq!(Value::Object(fields.clone()), single, "{name}");
        }
    }
}

#[test]
fn patterns_folders_and_recursion_pick_the_right_files() {
    let dir = tmp();
    let root = dir.path();
    std::fs::create_dir(root.join("sub")).unwrap();
    for name in ["a.obj", "b.obj", "c.off", "sub/d.obj"] {
        primitive(root, "@cube", name);
    }
    let run = |args: &[&str]| -> Vec<String> {
        let mut all = vec!["batch", "info"];
        all.extend_from_slice(args);
        files_of(&lines(&ok(&all)))
    };
    // Given as one argument, as a quoted pattern is: holey expands it.
    let obj = format!("{}/*.obj", s(root));
    assert_eq!(run(&[&obj]), ["a.obj", "b.obj"]);
    let deep = format!("{}/**/*.obj", s(root));
    assert_eq!(run(&[&deep]), ["a.obj", "b.obj", "d.obj"]);
    assert_eq!(run(&[s(root)]), ["a.obj", "b.obj", "c.off"]);
    assert_eq!(
        run(&[s(root), "--recursive"]),
        ["a.obj", "b.obj", "c.off", "d.obj"]
    );
    // A file reached twice runs once; lists keep their order.
    let c = root.join("c.off");
    assert_eq!(
        run(&[s(&c), &obj, s(&root.join("a.obj"))]),
        ["c.off", "a.obj", "b.obj"]
    );
    // A pattern or folder with no mesh files is a mistake, said before work.
    let none = format!("{}/*.stl", s(root));
    assert!(refused(&["batch", "info", &obj, &none]).contains("no mesh files"));
    assert!(refused(&["batch", "info", s(&root.join("missing.obj"))]).contains("no such file"));
}

#[test]
fn one_job_and_two_jobs_give_identical_outputs() {
    let dir = tmp();
    let models = models_folder(
        dir.path(),
        &[
            ("@cube:2", "cube.obj"),
            ("@torus:16:8", "torus.obj"),
            ("@tetrahedron", "tet.ply"),
            ("@sphere:2", "sphere.off"),
        ],
    );
    overlapping_cubes(&models, "crossing.obj");
    let mut runs = Vec::new();
    for jobs in ["1", "2"] {
        let smooth = dir.path().join(format!("smooth{jobs}"));
        let solid = dir.path().join(format!("solid{jobs}"));
        ok(&[
            "batch",
            "subdivide",
            "--scheme",
            "catmull-clark",
            "-n",
            "2",
            s(&models),
            "--out",
            s(&smooth),
            "--jobs",
            jobs,
        ]);
        ok(&["batch", "union", s(&models), "--out", s(&solid), "-j", jobs]);
        let report = ok(&["batch", "info", s(&models), "-j", jobs]);
        runs.push((smooth, solid, report));
    }
    let [(smooth1, solid1, info1), (smooth2, solid2, info2)] = &runs[..] else {
        unreachable!()
    };
    assert_eq!(info1, info2);
    for (a, b) in [(smooth1, smooth2), (solid1, solid2)] {
        let names = listing(a);
        assert_eq!(names.len(), 5);
        assert_eq!(names, listing(b));
        for name in names {
            let (x, y) = (
                std::fs::read(a.join(&name)).unwrap(),
                std::fs::read(b.join(&name)).unwrap(),
            );
            assert!(!x.is_empty());
            assert!(x == y, "{name} differs between --jobs 1 and --jobs 2");
        }
    }
    // The union of one input repaired the crossing cubes: a closed
    // surface of volume 1 + 1 - 1/8.
    let solid = info(&solid1.join("crossing.obj"));
    assert_eq!(solid["closed"], true);
    let volume = solid["volume"].as_f64().unwrap();
    assert!((volume - 1.875).abs() < 1e-9, "volume {volume}");
    let before = info(&models.join("crossing.obj"))["volume"]
        .as_f64()
        .unwrap();
    assert!(
        (before - 2.0).abs() < 1e-9,
        "the input counts the overlap twice: {before}"
    );
}

#[test]
fn every_command_runs_with_its_own_options() {
    let dir = tmp();
    let cube = primitive(dir.path(), "@cube", "cube.obj");
    let out = |name: &str| dir.path().join(name);
    let counts = |v: &Value| {
        (
            v["vertices"].as_u64().unwrap(),
            v["edges"].as_u64().unwrap(),
            v["faces"].as_u64().unwrap(),
        )
    };
    // Options may come after the inputs and --out.
    ok(&[
        "batch",
        "subdivide",
        s(&cube),
        "--out",
        s(&out("cc")),
        "--scheme",
        "catmull-clark",
        "-n",
        "2",
    ]);
    assert_eq!(counts(&info(&out("cc").join("cube.obj"))), (98, 192, 96));
    ok(&[
        "batch",
        "subdivide",
        "--scheme",
        "doo-sabin",
        s(&cube),
        "--out",
        s(&out("ds")),
    ]);
    assert_eq!(counts(&info(&out("ds").join("cube.obj"))), (24, 48, 26));
    ok(&[
        "batch",
        "convert",
        "--ascii",
        s(&cube),
        "--out",
        s(&out("ply")),
        "--format",
        ".PLY",
    ]);
    let ply = std::fs::read(out("ply").join("cube.ply")).unwrap();
    assert!(
        ply.starts_with(b"ply\nformat ascii"),
        "--ascii reached convert"
    );
    ok(&[
        "batch",
        "sierpinski",
        "-n",
        "1",
        s(&cube),
        "--out",
        s(&out("s")),
        "--format",
        "dlfl",
    ]);
    // One iteration joins a small cube per corner along the 12 edges:
    // genus E - V + 1 = 5.
    assert_eq!(info(&out("s").join("cube.dlfl"))["genus"], 5);
    ok(&[
        "batch",
        "menger",
        "--exact",
        s(&cube),
        "--out",
        s(&out("m")),
    ]);
    assert_eq!(info(&out("m").join("cube.obj"))["genus"], 5);
    ok(&["batch", "resolve", s(&cube), "--out", s(&out("r"))]);
    assert_eq!(info(&out("r").join("cube.obj"))["faces"], 12);
    ok(&["batch", "union", s(&cube), "--out", s(&out("u"))]);
    assert_eq!(info(&out("u").join("cube.obj"))["volume"], 8.0);
    let report = lines(&ok(&["batch", "selfint", "--pairs", s(&cube)]));
    assert_eq!(report.len(), 1);
    assert_eq!(report[0]["triangles"], 12);
    assert_eq!(report[0]["intersecting_pairs"], 0);
    assert_eq!(report[0]["pairs"], Value::Array(vec![]));
    let crossing = overlapping_cubes(dir.path(), "crossing.obj");
    let report = lines(&ok(&["batch", "selfint", s(&crossing)]));
    assert!(report[0]["intersecting_pairs"].as_u64().unwrap() > 0);
    let help = ok(&["batch", "--help"]);
    assert!(help.contains("Examples:") && help.contains("JSON Lines"));
}

#[test]
fn an_output_collision_is_refused_before_any_work() {
    let dir = tmp();
    for folder in ["a", "b"] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
    }
    let first = primitive(dir.path(), "@cube", "a/x.obj");
    let second = primitive(dir.path(), "@tetrahedron", "b/x.obj");
    let out_dir = dir.path().join("out");
    let err = refused(&[
        "batch",
        "convert",
        s(&first),
        s(&second),
        "--out",
        s(&out_dir),
    ]);
    assert!(err.contains(s(&first)) && err.contains(s(&second)), "{err}");
    assert!(!out_dir.exists(), "nothing was done, not even the folder");
    // Different extensions write different files, until --format makes
    // them one.
    let ply = primitive(dir.path(), "@torus", "a/x.ply");
    ok(&["batch", "convert", s(&first), s(&ply), "--out", s(&out_dir)]);
    assert_eq!(listing(&out_dir), ["x.obj", "x.ply"]);
    let stl_dir = dir.path().join("stl");
    refused(&[
        "batch",
        "convert",
        s(&first),
        s(&ply),
        "--out",
        s(&stl_dir),
        "--format",
        "stl",
    ]);
    assert!(!stl_dir.exists());
}

#[test]
fn an_out_folder_that_is_a_file_is_refused() {
    let dir = tmp();
    let cube = primitive(dir.path(), "@cube", "cube.obj");
    let file = dir.path().join("results");
    std::fs::write(&file, "precious").unwrap();
    let err = refused(&[
        "batch",
        "convert",
        s(&cube),
        "--out",
        s(&file),
        "--format",
        "ply",
    ]);
    assert!(err.contains("not a folder"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "precious");
}

#[test]
fn a_result_never_replaces_its_input() {
    let dir = tmp();
    let cube = primitive(dir.path(), "@cube", "cube.obj");
    let before = std::fs::read(&cube).unwrap();
    let err = refused(&[
        "batch",
        "subdivide",
        "--scheme",
        "catmull-clark",
        s(dir.path()),
        "--out",
        s(dir.path()),
    ]);
    assert!(err.contains("would replace it"), "{err}");
    assert_eq!(std::fs::read(&cube).unwrap(), before);
}

#[test]
fn options_that_name_one_file_are_refused() {
    let dir = tmp();
    let cube = primitive(dir.path(), "@cube", "cube.obj");
    let report = dir.path().join("r.json");
    let out_dir = dir.path().join("out");
    let err = refused(&[
        "batch",
        "union",
        s(&cube),
        "--out",
        s(&out_dir),
        "--report",
        s(&report),
    ]);
    assert!(err.contains("--report"), "{err}");
    assert!(!report.exists() && !out_dir.exists());
    let curves = dir.path().join("c.obj");
    refused(&["batch", "selfint", s(&cube), "--curves", s(&curves)]);
    assert!(!curves.exists());
    // Reports write no files, so they take no --out.
    let out = holey(&["batch", "info", s(&cube), "--out", s(&out_dir)]);
    assert_eq!(out.status.code(), Some(2));
}
