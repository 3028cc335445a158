//! Reads the real meshes of the shared data folder (`../shared/data/meshes`,
//! made by others; see its README). Skipped, visibly, when the folder is
//! absent. Checks each file's face count and referenced-vertex count
//! against the README's table, then converts it to every other format
//! (glTF and 3MF included) and back and checks that the faces survive.

// Test helpers may unwrap: a panic is a failed test.
#![allow(clippy::unwrap_used)]

use std::collections::HashMap;
use std::path::Path;

use holey_io::{MeshFile, PolyMesh, RawMesh, WriteOptions, read_path, write_dlfl, write_poly};
use holey_mesh::DVec3;

/// (file stem, referenced vertices, faces) from the README of the shared
/// folder.
const TABLE: &[(&str, usize, usize)] = &[
    ("beetle", 1148, 2053),
    ("bigguyhalf", 739, 711),
    ("bunny_oded", 3301, 6598),
    ("fertility_poly", 3730, 2048),
    ("menger_sponge_level3", 7983, 21598),
    ("openscad-nonmanifold-crash", 717, 1442),
    ("self_intersectA", 8582, 17160),
    ("self_intersectB", 8582, 17160),
    ("spot_control_mesh", 188, 180),
    ("spot_quadrangulated", 2930, 2928),
    ("spot_triangulated", 2930, 5856),
    ("stanford-bunny", 34834, 69451),
    ("suzanne", 507, 500),
    ("teapot", 3644, 6320),
    ("thingi10k_65004_arduino_case_soup", 4398, 1466),
    ("thingi10k_88566_garden_fence", 2624, 5344),
];

/// stanford-bunny.obj also stores 1113 vertices no face uses.
const UNREFERENCED: &[(&str, usize)] = &[("stanford-bunny", 1113)];

fn referenced(m: &PolyMesh) -> usize {
    let mut used = vec![false; m.positions.len()];
    for &i in &m.face_indices {
        used[i as usize] = true;
    }
    used.iter().filter(|&&u| u).count()
}

fn poly(file: MeshFile) -> PolyMesh {
    match file {
        MeshFile::Poly(m) => m,
        MeshFile::Dlfl(_) => panic!("expected a polygon mesh"),
    }
}

/// Writes `m` to `path` (as text or binary, in the format its extension
/// names) and reads it back.
fn round_trip(m: &PolyMesh, path: &Path, ascii: bool) -> PolyMesh {
    let options = WriteOptions {
        ascii,
        ..Default::default()
    };
    write_poly(path, m, &options).unwrap();
    poly(read_path(path).unwrap())
}

fn bits(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

/// Faces as lists of corner positions (bitwise), independent of vertex
/// numbering.
fn corner_positions(m: &PolyMesh, round: impl Fn(f64) -> f64) -> Vec<Vec<[u64; 3]>> {
    m.faces()
        .map(|f| {
            f.iter()
                .map(|&i| bits(m.positions[i as usize].to_array().map(&round).into()))
                .collect()
        })
        .collect()
}

/// The soup as a `.dlfl` without `e` lines: referenced vertices only, in
/// order of first use.
fn to_raw(m: &PolyMesh) -> RawMesh {
    let mut map = vec![u32::MAX; m.positions.len()];
    let mut raw = RawMesh {
        face_offsets: m.face_offsets.clone(),
        ..RawMesh::default()
    };
    for &i in &m.face_indices {
        if map[i as usize] == u32::MAX {
            map[i as usize] = raw.positions.len() as u32;
            raw.positions.push(m.positions[i as usize]);
        }
        raw.face_vertices.push(map[i as usize]);
    }
    raw
}

fn check_conversions(name: &str, m: &PolyMesh, tmp: &Path) {
    let exact = corner_positions(m, |x| x);
    let triangles = |p: &PolyMesh| -> Vec<Vec<[u64; 3]>> {
        let (tris, _) = p.fan_triangles();
        tris.iter()
            .map(|t| t.iter().map(|&i| bits(p.positions[i as usize])).collect())
            .collect()
    };
    // Lossless formats give back the very same mesh.
    for (ext, ascii) in [
        ("obj", false),
        ("off", false),
        ("ply", false),
        ("ply", true),
    ] {
        let path = tmp.join(format!("{name}.{ext}"));
        let back = round_trip(m, &path, ascii);
        assert!(
            back == *m,
            "{name} via {ext} (ascii {ascii}) changed the mesh"
        );
    }
    // STL triangulates and welds bit-identical positions: the fan
    // triangles' corner positions survive (as f32 in binary).
    for ascii in [false, true] {
        let path = tmp.join(format!("{name}.stl"));
        let back = round_trip(m, &path, ascii);
        let mut want = triangles(m);
        if !ascii {
            let f32_tris: Vec<Vec<[u64; 3]>> = want
                .iter()
                .map(|t| {
                    t.iter()
                        .map(|b| b.map(|x| f64::from(f64::from_bits(x) as f32).to_bits()))
                        .collect()
                })
                .collect();
            want = f32_tris;
        }
        assert!(
            corner_positions(&back, |x| x) == want,
            "{name} via STL (ascii {ascii})"
        );
    }
    // glTF and 3MF hold triangles over all the stored vertices: the fan
    // triangles come back with the same vertex numbers, and the positions
    // bit for bit (3MF's decimals) or rounded to f32 (glTF).
    let (tris, _) = m.fan_triangles();
    let fan: Vec<Vec<u32>> = tris.iter().map(|t| t.to_vec()).collect();
    for ext in ["3mf", "glb", "gltf"] {
        let path = tmp.join(format!("{name}.{ext}"));
        write_poly(&path, m, &WriteOptions::default()).unwrap();
        let back = poly(read_path(&path).unwrap());
        let faces: Vec<Vec<u32>> = back.faces().map(<[u32]>::to_vec).collect();
        assert!(faces == fan, "{name} via {ext}: faces differ");
        let want: Vec<[u64; 3]> = m
            .positions
            .iter()
            .map(|p| match ext {
                "3mf" => bits(*p),
                _ => bits(p.to_array().map(|x| f64::from(x as f32)).into()),
            })
            .collect();
        let got: Vec<[u64; 3]> = back.positions.iter().map(|&p| bits(p)).collect();
        assert!(got == want, "{name} via {ext}: positions differ");
    }
    // .dlfl without edge lines keeps faces and positions exactly.
    let path = tmp.join(format!("{name}.dlfl"));
    let raw = to_raw(m);
    write_dlfl(&path, &raw).unwrap();
    let MeshFile::Dlfl(back) = read_path(&path).unwrap() else {
        panic!("{name}: .dlfl did not read as a DLFL");
    };
    assert!(back == raw, "{name} via .dlfl");
    let back_faces: Vec<Vec<[u64; 3]>> = (0..back.face_count())
        .map(|f| {
            back.face(f)
                .iter()
                .map(|&i| bits(back.positions[i as usize]))
                .collect()
        })
        .collect();
    assert!(back_faces == exact, "{name} via .dlfl: faces differ");
}

#[test]
fn shared_meshes_read_with_the_documented_counts_and_convert() {
    let dir = holey_testkit::shared_meshes_or_return!(
        "shared_meshes_read_with_the_documented_counts_and_convert"
    );
    let table: HashMap<&str, (usize, usize)> = TABLE.iter().map(|&(n, v, f)| (n, (v, f))).collect();
    let tmp = tempfile::tempdir().unwrap();
    let mut seen = Vec::new();
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    entries.sort();
    for path in entries {
        let stem = path.file_stem().unwrap().to_str().unwrap().to_owned();
        let m = poly(read_path(&path).unwrap_or_else(|e| panic!("{e}")));
        m.check().unwrap();
        if let Some(&(v, f)) = table.get(stem.as_str()) {
            assert_eq!(m.face_count(), f, "{stem}: faces");
            assert_eq!(referenced(&m), v, "{stem}: referenced vertices");
            let extra = UNREFERENCED
                .iter()
                .find(|(n, _)| *n == stem)
                .map_or(0, |&(_, k)| k);
            assert_eq!(m.positions.len(), v + extra, "{stem}: stored vertices");
            seen.push(stem.clone());
        } else {
            eprintln!("note: {stem}.obj is not in the README table; read but not counted");
        }
        check_conversions(&stem, &m, tmp.path());
    }
    let missing: Vec<_> = TABLE
        .iter()
        .filter(|(n, _, _)| !seen.iter().any(|s| s == n))
        .collect();
    assert!(missing.is_empty(), "missing shared meshes: {missing:?}");
}
