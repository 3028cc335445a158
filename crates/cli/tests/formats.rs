//! glTF and 3MF through the `holey` binary: `holey convert` from OBJ to
//! `.glb`, `.gltf` and `.3mf` and back, `holey info` on each, and the
//! errors for what cannot be read or written.

#![allow(clippy::unwrap_used)] // test helpers: a failed unwrap is a failed test

use std::path::Path;

use serde_json::Value;

mod common;
use common::{ok, refused};

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// The `v` positions and `f` faces (0-based) of an OBJ file holey wrote.
fn read_obj(path: &Path) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut v = Vec::new();
    let mut f = Vec::new();
    for line in text.lines() {
        let mut t = line.split_whitespace();
        match t.next() {
            Some("v") => {
                let x: Vec<f64> = t.map(|n| n.parse().unwrap()).collect();
                v.push([x[0], x[1], x[2]]);
            }
            Some("f") => f.push(t.map(|n| n.parse::<u32>().unwrap() - 1).collect()),
            _ => {}
        }
    }
    (v, f)
}

/// A cube of six quads whose corners f32 cannot hold exactly.
const CUBE: &str = "\
v 0.1 0.1 0.1\nv 1.1 0.1 0.1\nv 1.1 1.1 0.1\nv 0.1 1.1 0.1\n\
v 0.1 0.1 1.1\nv 1.1 0.1 1.1\nv 1.1 1.1 1.1\nv 0.1 1.1 1.1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

#[test]
fn convert_obj_to_gltf_and_3mf_and_back() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("cube.obj");
    std::fs::write(&obj, CUBE).unwrap();
    let (positions, quads) = read_obj(&obj);
    // Each quad comes back as the fan of two triangles from its first corner.
    let triangles: Vec<Vec<u32>> = quads
        .iter()
        .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
        .collect();
    for ext in ["glb", "gltf", "3mf"] {
        let file = dir.path().join(format!("cube.{ext}"));
        ok(&["convert", s(&obj), s(&file)]);
        let info: Value = serde_json::from_str(&ok(&["info", "--json", s(&file)])).unwrap();
        assert_eq!(info["vertices"], 8, "{ext}");
        assert_eq!(info["faces"], 12, "{ext}");
        assert_eq!(info["face_sizes"]["3"], 12, "{ext}");
        assert_eq!(info["genus"], 0, "{ext}");
        assert_eq!(info["closed"], true, "{ext}");
        assert_eq!(info["oriented"], true, "{ext}");
        let back = dir.path().join(format!("back-{ext}.obj"));
        ok(&["convert", s(&file), s(&back)]);
        let (v, f) = read_obj(&back);
        assert_eq!(f, triangles, "{ext}: faces");
        let want: Vec<[f64; 3]> = match ext {
            // 3MF's decimals are exact.
            "3mf" => positions.clone(),
            // glTF positions are f32.
            _ => positions
                .iter()
                .map(|p| p.map(|x| f64::from(x as f32)))
                .collect(),
        };
        assert_eq!(v, want, "{ext}: positions");
        if ext != "3mf" {
            assert_ne!(v, positions, "0.1 is not an f32: the test can tell");
        }
    }
    // The text report reads the binary file too.
    let text = ok(&["info", s(&dir.path().join("cube.glb"))]);
    assert!(text.contains("genus:         0"), "{text}");
    assert!(
        std::fs::read(dir.path().join("cube.glb"))
            .unwrap()
            .starts_with(b"glTF")
    );
    // A command other than convert takes glTF input and writes 3MF.
    let sub = dir.path().join("smooth.3mf");
    ok(&[
        "subdivide",
        s(&dir.path().join("cube.gltf")),
        s(&sub),
        "--scheme",
        "catmull-clark",
    ]);
    let info: Value = serde_json::from_str(&ok(&["info", "--json", s(&sub)])).unwrap();
    assert_eq!(info["genus"], 0);
    assert_eq!(info["closed"], true);
}

#[test]
fn malformed_or_unwritable_is_status_2_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let junk = dir.path().join("junk.glb");
    std::fs::write(&junk, b"solid not a glb\n").unwrap();
    let err = refused(&["info", s(&junk)]);
    assert!(
        err.contains(&format!(
            "{}: byte 0: not a GLB file: it starts with \"soli\"",
            junk.display()
        )),
        "{err}"
    );
    let zip = dir.path().join("empty.3mf");
    std::fs::write(&zip, b"PK\x05\x06\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0").unwrap();
    let err = refused(&["info", s(&zip)]);
    assert!(err.contains("has no model part 3D/3dmodel.model"), "{err}");
    // glTF cannot hold a coordinate beyond f32: refused, nothing written.
    let big = dir.path().join("big.obj");
    std::fs::write(&big, "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let out = dir.path().join("big.glb");
    let err = refused(&["convert", s(&big), s(&out)]);
    assert!(err.contains("beyond the range of f32"), "{err}");
    assert!(!out.exists());
    // 3MF holds it exactly.
    let out = dir.path().join("big.3mf");
    ok(&["convert", s(&big), s(&out)]);
    let info: Value = serde_json::from_str(&ok(&["info", "--json", s(&out)])).unwrap();
    assert_eq!(info["bbox"][1][0], 1e39);
}
