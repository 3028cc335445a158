//! Meshes for holey's benchmarks, generated in code so that every run
//! measures the same input.

use holey_dlfl::Mesh;
use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_mesh::PolyMesh;
use holey_topo::TriMesh;

/// An n×m quad torus soup (n·m faces), welded and oriented.
pub fn torus_soup(n: u32, m: u32) -> PolyMesh {
    let mut positions = Vec::with_capacity((n * m) as usize);
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        for j in 0..m {
            let b = std::f64::consts::TAU * f64::from(j) / f64::from(m);
            let r = 1.0 + 0.4 * b.cos();
            positions.push(holey_mesh::DVec3::new(
                r * a.cos(),
                r * a.sin(),
                0.4 * b.sin(),
            ));
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut soup = PolyMesh {
        positions,
        ..PolyMesh::new()
    };
    for i in 0..n {
        for j in 0..m {
            soup.push_face(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    soup
}

/// The same torus in the kernel.
pub fn torus_mesh(n: u32, m: u32) -> Mesh {
    match to_dlfl(&torus_soup(n, m), ImportOptions::default()) {
        Ok(imported) => imported.mesh,
        Err(e) => panic!("benchmark torus does not import: {e}"),
    }
}

/// The torus as OBJ text.
pub fn torus_obj(n: u32, m: u32) -> Vec<u8> {
    use std::fmt::Write;
    let soup = torus_soup(n, m);
    let mut s = String::with_capacity(soup.face_count() * 40);
    for p in &soup.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for f in soup.faces() {
        let _ = writeln!(s, "f {} {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1, f[3] + 1);
    }
    s.into_bytes()
}

/// `@sphere:level` (20·4^level triangles) as a triangle mesh.
pub fn icosphere(level: u32) -> TriMesh {
    let soup = holey_shapes::parse_primitive(&format!("@sphere:{level}"))
        .unwrap_or_else(|e| panic!("sphere {level}: {e}"));
    tri_mesh(soup)
}

/// `@tri-plane:n:n` on [-1, 1]² (2n² triangles) as a triangle mesh.
pub fn tri_grid(n: u32) -> TriMesh {
    let soup = holey_shapes::parse_primitive(&format!("@tri-plane:{n}:{n}"))
        .unwrap_or_else(|e| panic!("grid {n}: {e}"));
    tri_mesh(soup)
}

fn tri_mesh(soup: PolyMesh) -> TriMesh {
    soup.triangulated()
}
