//! Seeded mutation testing: every reader must return `Ok` or `Err` on any
//! byte sequence, never panic (nor hang or allocate by a lying count).

// Test helpers may unwrap: a panic is a failed test.
#![allow(clippy::unwrap_used)]

use holey_io::{Format, PolyMesh, RawMesh, parse};
use holey_mesh::DVec3;
use holey_testkit::Rng;

/// A small closed mesh with a quad, so polygon paths are exercised too.
fn cube() -> PolyMesh {
    let positions = (0..8)
        .map(|i| {
            DVec3::new(
                f64::from(i & 1),
                f64::from((i >> 1) & 1) * 0.1,
                f64::from(i >> 2) / 3.0,
            )
        })
        .collect();
    PolyMesh::from_faces(
        positions,
        [
            &[0u32, 2, 3, 1][..],
            &[4, 5, 7, 6],
            &[0, 1, 5, 4],
            &[2, 6, 7, 3],
            &[0, 4, 6],
            &[0, 6, 2],
            &[1, 3, 7, 5],
        ],
    )
}

fn dlfl_sample() -> RawMesh {
    // A tetrahedron with explicit edges, and a point-sphere.
    let text = "dlfl 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\n\
                f 0 2 1\nf 0 1 3\nf 1 2 3\nh 0 3 2\nf 4\n\
                e 0:0 3:2\ne 0:1 2:0\ne 0:2 1:0\ne 1:1 2:2\ne 1:2 3:0\ne 2:1 3:1\n";
    holey_io::dlfl::parse(text.as_bytes(), "sample.dlfl").unwrap()
}

/// Valid files of every format and encoding.
fn seeds() -> Vec<(Format, Vec<u8>)> {
    let m = cube();
    let mut out = Vec::new();
    let mut buf = Vec::new();
    holey_io::obj::write(&mut buf, &m).unwrap();
    // Extra OBJ syntax: corner forms, relative indices, continuations.
    buf.extend_from_slice(b"vt 0 0\nvn 0 0 1\nf 1/1/1 2//1 -1/1\\\n 3\r\ng x\n");
    out.push((Format::Obj, buf));
    let mut buf = Vec::new();
    holey_io::off::write(&mut buf, &m).unwrap();
    out.push((Format::Off, buf));
    for ascii in [false, true] {
        let colors: Vec<[u8; 3]> = (0..8).map(|i| [i, 2 * i, 3 * i]).collect();
        let mut buf = Vec::new();
        holey_io::ply::write(&mut buf, &m, ascii, Some(&colors)).unwrap();
        out.push((Format::Ply, buf.clone()));
        if !ascii {
            out.push((Format::Ply, big_endian_ply(&m)));
        }
        let mut buf = Vec::new();
        holey_io::stl::write(&mut buf, &m, ascii).unwrap();
        out.push((Format::Stl, buf));
    }
    let mut buf = Vec::new();
    holey_io::dlfl::write(&mut buf, &dlfl_sample()).unwrap();
    out.push((Format::Dlfl, buf));
    out.push((Format::Glb, holey_io::gltf::encode_glb(&m).unwrap()));
    out.push((Format::Gltf, holey_io::gltf::encode_gltf(&m).unwrap()));
    out.push((Format::Gltf, gltf_with_nodes()));
    out.push((Format::ThreeMf, holey_io::threemf::encode(&m).unwrap()));
    out
}

/// A .gltf with a node hierarchy, transforms, u16 indices, a strip and a
/// strided view: the paths the writer's own output does not take.
fn gltf_with_nodes() -> Vec<u8> {
    let mut bin = Vec::new();
    for p in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]] {
        for x in p {
            bin.extend_from_slice(&x.to_le_bytes());
        }
        bin.extend_from_slice(&[0; 4]);
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let data: String = {
        use std::fmt::Write;
        // Hex is not base64: encode by hand with the standard alphabet.
        const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut s = String::new();
        for c in bin.chunks(3) {
            let n = (u32::from(c[0]) << 16)
                | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
                | u32::from(*c.get(2).unwrap_or(&0));
            for k in 0..=c.len() {
                let _ = s.write_char(char::from(A[(n >> (18 - 6 * k)) as usize & 63]));
            }
        }
        s
    };
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,2]}}],
        "nodes":[{{"translation":[1,2,3],"rotation":[0,0.6,0,0.8],"children":[1]}},{{"scale":[2,-1,2],"mesh":0}},
                 {{"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,5,5,5,1],"mesh":0}}],
        "buffers":[{{"byteLength":76,"uri":"data:application/octet-stream;base64,{data}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":64,"byteStride":16}},{{"buffer":0,"byteOffset":64,"byteLength":12}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"}},
                     {{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}},
                                  {{"attributes":{{"POSITION":0}},"indices":1,"mode":5}}]}}]}}"#
    )
    .into_bytes()
}

/// The mesh as big-endian PLY with float coordinates and ushort counts.
fn big_endian_ply(m: &PolyMesh) -> Vec<u8> {
    let mut b = format!(
        "ply\nformat binary_big_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {}\nproperty list ushort uint vertex_indices\nend_header\n",
        m.positions.len(),
        m.face_count()
    )
    .into_bytes();
    for p in &m.positions {
        for v in p.to_array() {
            b.extend_from_slice(&(v as f32).to_be_bytes());
        }
    }
    for f in m.faces() {
        b.extend_from_slice(&(f.len() as u16).to_be_bytes());
        for &i in f {
            b.extend_from_slice(&i.to_be_bytes());
        }
    }
    b
}

const INTERESTING: &[&[u8]] = &[
    b" ",
    b"\n",
    b"\r\n",
    b"\\\n",
    b"#",
    b"-",
    b"/",
    b":",
    b"0",
    b"-1",
    b"9",
    b"4294967295",
    b"18446744073709551616",
    b"99999999999999999999999",
    b"nan",
    b"inf",
    b"1e999",
    b"f",
    b"v",
    b"e",
    b"h",
    b"facet",
    b"endloop",
    b"element face 4294967295\n",
    b"property list uint uint vertex_indices\n",
    b"\xff\xff\xff\xff",
    b"\0",
    b"glTF",
    b"\"count\":4294967295",
    b"\"byteOffset\":999,",
    b"\"children\":[0],",
    b"<vertex x=\"1\" y=\"2\" z=\"3\"/>",
    b"<triangle v1=\"9\" v2=\"0\" v3=\"1\"/>",
];

fn mutate(rng: &mut Rng, bytes: &mut Vec<u8>) {
    let n = bytes.len();
    match rng.below(7) {
        0 if n > 0 => {
            let i = rng.below(n);
            bytes[i] = rng.below(256) as u8;
        }
        1 if n > 0 => {
            let i = rng.below(n);
            bytes[i] ^= 1 << rng.below(8);
        }
        2 => {
            let i = rng.below(n + 1);
            let s = rng.pick(INTERESTING);
            bytes.splice(i..i, s.iter().copied());
        }
        3 if n > 0 => {
            let i = rng.below(n);
            let len = rng.below(n - i).min(64) + 1;
            bytes.drain(i..i + len);
        }
        4 => bytes.truncate(rng.below(n + 1)),
        5 if n > 0 => {
            let i = rng.below(n);
            let len = rng.below(n - i).min(64) + 1;
            let chunk: Vec<u8> = bytes[i..i + len].to_vec();
            let at = rng.below(n + 1);
            bytes.splice(at..at, chunk);
        }
        _ => {
            // Overwrite a 4-byte word (binary counts and floats).
            if n >= 4 {
                let i = rng.below(n - 3);
                let word = *rng.pick(&[
                    0u32,
                    1,
                    2,
                    3,
                    255,
                    256,
                    65535,
                    u32::MAX,
                    0x7fc0_0000,
                    0x7f80_0000,
                ]);
                bytes[i..i + 4].copy_from_slice(&word.to_le_bytes());
            }
        }
    }
}

#[test]
fn seeds_are_valid() {
    for (format, bytes) in seeds() {
        if let Err(e) = parse(format, &bytes, "seed") {
            panic!("{format}: {e}");
        }
    }
}

#[test]
fn mutated_files_never_panic() {
    let mut rng = Rng::new(0x5eed_1e55);
    let mut outcomes = [0usize; 2];
    // HOLEY_FUZZ_ROUNDS=100000 runs a longer search by hand.
    let rounds: usize = std::env::var("HOLEY_FUZZ_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(400);
    for (si, (format, seed)) in seeds().into_iter().enumerate() {
        for round in 0..rounds {
            let mut bytes = seed.clone();
            for _ in 0..=rng.below(4) {
                mutate(&mut rng, &mut bytes);
            }
            // The intended reader, and one other to mix up formats.
            let other = *rng.pick(&Format::ALL);
            for f in [format, other] {
                let r = parse(f, &bytes, "fuzz");
                outcomes[usize::from(r.is_ok())] += 1;
                if let Err(e) = r {
                    assert!(e.is_bad_input(), "seed {si} round {round}: {e}");
                    assert!(e.to_string().starts_with("fuzz"), "{e}");
                }
            }
        }
    }
    // Both outcomes occur: the mutations are neither all harmless nor all fatal.
    assert!(outcomes[0] > 100 && outcomes[1] > 100, "{outcomes:?}");
}

#[test]
fn every_prefix_of_every_seed_is_handled() {
    for (format, seed) in seeds() {
        for len in 0..seed.len() {
            let _ = parse(format, &seed[..len], "prefix");
        }
    }
}
