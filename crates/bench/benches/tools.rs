//! The thesis's tools at about a million output faces (issue: high-genus
//! tools, performance), plus the renderer.
//!
//! cargo bench -p holey-bench --bench tools

use divan::{Bencher, black_box};
use holey_dlfl::convert::{ImportOptions, to_dlfl, to_poly};
use holey_dlfl::{FaceId, Mesh};
use holey_model::extrude::{ExtrudeParams, extrude_face, stellate_face};
use holey_model::handle::{HandleParams, create_handle};
use holey_model::hull::{convex_hull, dual_convex_hull};
use holey_model::menger::{MengerParams, Thickness, menger};
use holey_model::rind::Rind;
use holey_model::sierpinski::sierpinski;
use holey_model::truncate::truncate_all_vertices;
use holey_model::wireframe::{ColumnParams, columns, wireframe};
use holey_render::{RenderOptions, render};
use holey_subdiv::{catmull_clark, doo_sabin};

fn main() {
    divan::main();
}

fn primitive(spec: &str) -> Mesh {
    let soup = holey_shapes::parse_primitive(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
    to_dlfl(&soup, ImportOptions::default())
        .unwrap_or_else(|e| panic!("{spec}: {e}"))
        .mesh
}

/// Times `run` on a fresh copy of `base` per sample: the copy is made, and
/// what `run` returns is dropped, outside the timing.
fn on_copies<O>(bencher: Bencher, base: &Mesh, run: impl Fn(Mesh) -> O) {
    bencher.with_inputs(|| base.clone()).bench_local_values(run);
}

/// Times `edit` applied to every face of `base` (the faces it had before
/// the first edit), on a fresh copy per sample as [`on_copies`] makes;
/// each sample returns the copy's face count. For the per-face tools,
/// which run one face at a time and must not see the faces they add.
fn on_every_face<O>(bencher: Bencher, base: &Mesh, edit: impl Fn(&mut Mesh, FaceId) -> O) {
    let faces: Vec<FaceId> = base.faces().collect();
    on_copies(bencher, base, |mut m| {
        for &f in &faces {
            let _ = black_box(edit(&mut m, f));
        }
        m.face_count()
    });
}

/// Times `make`, a tool that builds a new mesh from `base`; each sample
/// returns the new mesh's face count.
fn on_new_meshes<E>(bencher: Bencher, base: &Mesh, make: impl Fn(&Mesh) -> Result<Mesh, E> + Sync) {
    bencher.bench(|| black_box(make(base)).map(|m| m.face_count()));
}

/// Times rendering the primitive `spec` at `width` × `height`.
fn render_primitive(bencher: Bencher, spec: &str, width: u32, height: u32) {
    let soup = holey_shapes::parse_primitive(spec).unwrap_or_else(|e| panic!("{e}"));
    let opts = RenderOptions {
        width,
        height,
        ..RenderOptions::default()
    };
    bencher.bench(|| black_box(render(&soup, &opts)).map(|i| i.width()));
}

/// Nine Sierpinski iterations of a tetrahedron: 1,048,576 faces.
#[divan::bench(sample_count = 5)]
fn sierpinski_tetrahedron_9(bencher: Bencher) {
    let base = primitive("@tetrahedron");
    on_copies(bencher, &base, |mut m| {
        let _ = black_box(sierpinski(&mut m, 9));
        m
    });
}

/// One Menger level on a finely divided cube: about 0.9M faces.
#[divan::bench(sample_count = 5)]
fn menger_one_level_on_cube_100(bencher: Bencher) {
    let base = primitive("@cube:100");
    let params = MengerParams::default();
    on_copies(bencher, &base, |mut m| {
        let _ = black_box(menger(&mut m, &params));
        m
    });
}

/// Menger levels 1–4 of a cube at a third of the mean edge (186k faces).
#[divan::bench(sample_count = 5)]
fn menger_cube_4_levels(bencher: Bencher) {
    let base = primitive("@cube");
    let params = MengerParams {
        iterations: 4,
        thickness: Thickness::RatioOfMeanEdge(1.0 / 3.0),
        ..MengerParams::default()
    };
    on_copies(bencher, &base, |mut m| {
        let _ = black_box(menger(&mut m, &params));
        m
    });
}

/// The true sponge, level 5: 6.5M faces (level 4: 336k).
#[divan::bench(args = [4usize, 5], sample_count = 3)]
fn menger_exact(bencher: Bencher, level: usize) {
    let base = primitive("@cube");
    let params = MengerParams {
        iterations: level,
        exact: true,
        ..MengerParams::default()
    };
    on_copies(bencher, &base, |mut m| {
        let _ = black_box(menger(&mut m, &params));
        m
    });
}

/// A 100-segment handle between the two caps of a 1000-gon cylinder (a
/// tunnel): about 100k vertices added.
#[divan::bench(sample_count = 10)]
fn handle_100_segments_1000_gons(bencher: Bencher) {
    let base = primitive("@cylinder:1000:1");
    on_copies(bencher, &base, |mut m| {
        let (a, b) = (m.face_at(0), m.face_at(1));
        if let (Some(a), Some(b)) = (a, b)
            && let (Ok(ca), Ok(cb)) = (m.face_corner(a), m.face_corner(b))
        {
            let _ = black_box(create_handle(
                &mut m,
                ca,
                cb,
                &HandleParams::new(100, -1.0, -1.0),
            ));
        }
        m
    });
}

/// A rind of a 100k-face cube, then every outer face punched.
#[divan::bench(sample_count = 5)]
fn rind_100k_faces_punch_all(bencher: Bencher) {
    let base = primitive("@cube:129");
    on_copies(bencher, &base, |m| {
        let faces = m.face_count();
        let Ok(mut rind) = Rind::new(m, 0.001) else {
            return 0;
        };
        for i in 0..faces {
            let _ = rind.punch_index(i);
        }
        rind.mesh().face_count()
    });
}

/// The 64 × 64 torus of quads (4,096 faces) both subdivision benches
/// start from: four levels take it to about a million faces.
fn torus_64() -> Mesh {
    primitive("@torus:64:64")
}

/// Subdivision to about a million faces from a 4k-face torus.
#[divan::bench(sample_count = 5)]
fn catmull_clark_to_1m(bencher: Bencher) {
    let base = torus_64();
    on_new_meshes(bencher, &base, |m| catmull_clark(m, 4));
}

#[divan::bench(sample_count = 5)]
fn doo_sabin_to_1m(bencher: Bencher) {
    let base = torus_64();
    on_new_meshes(bencher, &base, |m| doo_sabin(m, 4));
}

/// Issue 18's families at about a million output faces, on a
/// 128 × 128 torus of quads (16,384 faces, 32,768 edges).
fn torus_128() -> Mesh {
    primitive("@torus:128:128")
}

/// Every face extruded once, repeated 15 times (+4 faces each ring):
/// 16,384 × (1 + 4 · 15) ≈ 1.0M faces.
#[divan::bench(sample_count = 3)]
fn extrude_every_face_15_rings_to_1m(bencher: Bencher) {
    let base = torus_128();
    let params = ExtrudeParams::new(0.001, 15);
    on_every_face(bencher, &base, |m, f| extrude_face(m, f, &params));
}

/// Every face of a 256 × 256 torus stellated (each quad fans into 4
/// triangles): 65,536 × 4 = 262,144 faces, one face at a time.
#[divan::bench(sample_count = 3)]
fn stellate_every_face_of_a_256_torus(bencher: Bencher) {
    let base = primitive("@torus:256:256");
    on_every_face(bencher, &base, |m, f| stellate_face(m, f, 0.001));
}

/// The wireframe of a 320 × 320 torus: 4E + 2V = 10 · 320² ≈ 1.02M
/// faces.
#[divan::bench(sample_count = 3)]
fn wireframe_to_1m(bencher: Bencher) {
    let base = primitive("@torus:320:320");
    on_new_meshes(bencher, &base, |m| wireframe(m, 0.001));
}

/// Hexagonal columns on every edge of the 128 × 128 torus, with their
/// joints.
#[divan::bench(sample_count = 3)]
fn columns_6_on_every_edge(bencher: Bencher) {
    let base = torus_128();
    let params = ColumnParams {
        sides: 6,
        radius: 0.002,
    };
    on_new_meshes(bencher, &base, |m| columns(m, &params));
}

/// Every vertex of a 512 × 512 torus truncated: V + F = 524,288 faces.
#[divan::bench(sample_count = 3)]
fn truncate_every_vertex_of_a_512_torus(bencher: Bencher) {
    let base = primitive("@torus:512:512");
    on_copies(bencher, &base, |mut m| {
        let _ = black_box(truncate_all_vertices(&mut m, 1.0 / 3.0));
        m.face_count()
    });
}

/// A 1M-triangle icosphere at 1024×768 (flat shading, 3×3 supersampling).
#[divan::bench(sample_count = 5)]
fn render_1m_triangles(bencher: Bencher) {
    render_primitive(bencher, "@sphere:8", 1024, 768);
}

/// A 10k-face mesh at 640×480, as for a sculpting frame.
#[divan::bench(sample_count = 10)]
fn render_10k_triangles(bencher: Bencher) {
    render_primitive(bencher, "@sphere:5", 640, 480);
}

/// Writing a Sierpinski result as a soup (self-loops dropped).
#[divan::bench(sample_count = 5)]
fn export_1m_face_sierpinski_to_soup(bencher: Bencher) {
    let mut m = primitive("@tetrahedron");
    let _ = sierpinski(&mut m, 9);
    bencher.bench(|| black_box(to_poly(&m)).poly.face_count());
}

/// `n` points on the unit sphere, as point-spheres (a SplitMix64 stream,
/// so every run hulls the same points): every one a corner of the hull.
fn sphere_points(n: usize) -> Mesh {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut m = Mesh::new();
    while m.vertex_count() < n {
        let p = glam::DVec3::new(next(), next(), next());
        let r = p.length();
        if r > 0.1 && r <= 1.0 {
            m.create_vertex(p / r).expect("a finite point");
        }
    }
    m
}

/// The convex hull of 500,000 points on a sphere: 2n − 4 = 999,996
/// triangles, every decision exact.
#[divan::bench(sample_count = 3)]
fn convex_hull_of_500k_sphere_points(bencher: Bencher) {
    let base = sphere_points(500_000);
    on_new_meshes(bencher, &base, convex_hull);
}

/// The dual convex hull of 100,000 points on a sphere: 100,000 faces,
/// 2n − 4 = 199,996 vertices (two hulls and the constructions between).
#[divan::bench(sample_count = 3)]
fn dual_convex_hull_of_100k_sphere_points(bencher: Bencher) {
    let base = sphere_points(100_000);
    on_new_meshes(bencher, &base, dual_convex_hull);
}
