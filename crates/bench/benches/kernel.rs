//! Kernel benchmarks (issue: foundation, performance targets).
//!
//! cargo bench -p holey-bench --bench kernel

use divan::{Bencher, black_box};
use holey_bench::{torus_mesh, torus_obj};
use holey_dlfl::{CornerId, Mesh};

fn main() {
    divan::main();
}

/// One insert_edge splitting a quad into two triangles, then the
/// delete_edge that undoes it, sweeping over the faces in order (the access
/// pattern of operators that walk a mesh); counted per operation.
#[divan::bench(args = [10_000u32, 1_000_000], sample_size = 20_000)]
fn insert_delete_edge_sweep(bencher: Bencher, faces: u32) {
    insert_delete(bencher, faces, 1);
}

/// The same at random faces of the mesh: bound by memory latency once the
/// mesh is larger than the caches.
#[divan::bench(args = [10_000u32, 1_000_000], sample_size = 20_000)]
fn insert_delete_edge_random(bencher: Bencher, faces: u32) {
    insert_delete(bencher, faces, 7919);
}

fn insert_delete(bencher: Bencher, faces: u32, stride: usize) {
    let side = (faces as f64).sqrt() as u32;
    let mut mesh = torus_mesh(side, side);
    let quads: Vec<(CornerId, CornerId)> = mesh
        .faces()
        .map(|f| {
            let cs: Vec<CornerId> = mesh
                .face_corners(f)
                .map(|c| c.collect())
                .unwrap_or_default();
            (cs[0], cs[2])
        })
        .collect();
    let mut k = 0usize;
    bencher
        .counter(divan::counter::ItemsCount::new(2usize))
        .bench_local(|| {
            let (a, b) = quads[k % quads.len()];
            k = k.wrapping_add(stride);
            if let Ok(e) = mesh.insert_edge(a, b) {
                let _ = black_box(mesh.delete_edge(e));
            }
        });
}

/// validate() on a mesh of about a million quads.
#[divan::bench(sample_count = 10)]
fn validate_1m_faces(bencher: Bencher) {
    let mesh = torus_mesh(1000, 1000);
    bencher.bench(|| black_box(mesh.validate()).is_ok());
}

/// Parsing a 1-million-face OBJ and importing it into the kernel.
#[divan::bench(sample_count = 5)]
fn load_1m_face_obj_into_kernel(bencher: Bencher) {
    let obj = torus_obj(1000, 1000);
    bencher.bench(|| {
        let parsed = holey_io::parse(holey_io::Format::Obj, &obj, "bench.obj");
        let Ok(holey_io::MeshFile::Poly(soup)) = parsed else {
            panic!("benchmark OBJ does not parse")
        };
        let imported = holey_dlfl::convert::to_dlfl(&soup, Default::default());
        black_box(imported.map(|i| i.mesh.face_count()).unwrap_or(0))
    });
}

/// Building the kernel from an already-parsed soup (the symbolic phase).
#[divan::bench(sample_count = 5)]
fn import_1m_face_soup(bencher: Bencher) {
    let soup = holey_bench::torus_soup(1000, 1000);
    bencher.bench(|| {
        let imported = holey_dlfl::convert::to_dlfl(&soup, Default::default());
        black_box(imported.map(|i| i.mesh.face_count()).unwrap_or(0))
    });
}

/// Bytes per corner of the kernel (printed once; not a timing).
#[divan::bench(sample_count = 1, sample_size = 1)]
fn memory_per_corner() -> f64 {
    let mesh: Mesh = torus_mesh(1000, 1000);
    let per = mesh.heap_bytes() as f64 / mesh.corner_count() as f64;
    eprintln!(
        "kernel memory: {per:.1} bytes per corner ({} corners)",
        mesh.corner_count()
    );
    per
}
