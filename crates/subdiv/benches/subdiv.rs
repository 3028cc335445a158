//! Subdivision benchmarks (divan). The headline job is six Catmull–Clark
//! levels of the shared spot control mesh (about 750k quads), which reads
//! ../shared/data/meshes and is skipped when that folder is absent.
//!
//! `cargo bench -p holey-subdiv --bench subdiv`

use holey_dlfl::Mesh;
use holey_subdiv::{Scheme, subdivide, subdivide_to_raw};

fn main() {
    divan::main();
}

fn spot() -> Option<Mesh> {
    let dir = holey_testkit::shared_meshes_or_skip("bench spot")?;
    let holey_io::MeshFile::Poly(poly) =
        holey_io::read_path(&dir.join("spot_control_mesh.obj")).ok()?
    else {
        return None;
    };
    Some(
        holey_dlfl::convert::to_dlfl(&poly, Default::default())
            .ok()?
            .mesh,
    )
}

fn cube() -> Mesh {
    let poly = holey_shapes::parse_primitive("@cube:4").expect("primitive");
    holey_dlfl::convert::to_dlfl(&poly, Default::default())
        .expect("imports")
        .mesh
}

/// Six Catmull–Clark levels of spot, kernel mesh built and validated.
#[divan::bench(sample_count = 10)]
fn spot_catmull_clark_6(bencher: divan::Bencher) {
    let Some(mesh) = spot() else { return };
    bencher.bench(|| subdivide(&mesh, Scheme::CatmullClark, 6).expect("subdivides"));
}

/// The same without building the kernel mesh (flat arrays only).
#[divan::bench(sample_count = 10)]
fn spot_catmull_clark_6_raw(bencher: divan::Bencher) {
    let Some(mesh) = spot() else { return };
    bencher.bench(|| subdivide_to_raw(&mesh, Scheme::CatmullClark, 6).expect("subdivides"));
}

/// Five Doo–Sabin levels of spot (about 1.1M faces).
#[divan::bench(sample_count = 10)]
fn spot_doo_sabin_5(bencher: divan::Bencher) {
    let Some(mesh) = spot() else { return };
    bencher.bench(|| subdivide(&mesh, Scheme::DooSabin, 5).expect("subdivides"));
}

/// Small meshes: per-call overhead.
#[divan::bench(args = [Scheme::CatmullClark, Scheme::DooSabin])]
fn cube4_two_levels(bencher: divan::Bencher, scheme: Scheme) {
    let mesh = cube();
    bencher.bench(|| subdivide(&mesh, scheme, 2).expect("subdivides"));
}
