//! divan benchmarks of holey-geom: `cargo bench -p holey-geom`.
//!
//! Meshes are generated here: UV spheres of 262,144 triangles (512
//! meridians × 258 parallels) for the 524k-triangle two-sphere scenes.

use divan::Bencher;
use glam::DVec3;
use holey_geom::bvh::{Aabb, Bvh};
use holey_geom::ccd::{CcdOptions, vertex_parities};
use holey_geom::{SymPoint, orient3d, orient3d_sos};

fn main() {
    divan::main();
}

struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// UV sphere: `2·nu·(nv−2)` triangles.
fn uv_sphere(nu: usize, nv: usize, c: DVec3, r: f64, base: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = vec![c + DVec3::Z * r];
    for j in 1..nv - 1 {
        let th = std::f64::consts::PI * j as f64 / (nv - 1) as f64;
        for i in 0..nu {
            let ph = 2.0 * std::f64::consts::PI * i as f64 / nu as f64;
            pos.push(c + DVec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()) * r);
        }
    }
    pos.push(c - DVec3::Z * r);
    let south = base + (pos.len() - 1) as u32;
    let ring = |j: usize, i: usize| base + (1 + (j - 1) * nu + (i % nu)) as u32;
    let mut tris = Vec::new();
    for i in 0..nu {
        tris.push([base, ring(1, i), ring(1, i + 1)]);
    }
    for j in 1..nv - 2 {
        for i in 0..nu {
            let (a, b, c2, d) = (
                ring(j, i),
                ring(j + 1, i),
                ring(j + 1, i + 1),
                ring(j, i + 1),
            );
            tris.push([a, b, c2]);
            tris.push([a, c2, d]);
        }
    }
    for i in 0..nu {
        tris.push([ring(nv - 2, i), south, ring(nv - 2, i + 1)]);
    }
    (pos, tris)
}

/// Two overlapping spheres of 262,144 triangles each.
fn two_spheres() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut p, mut t) = uv_sphere(512, 258, DVec3::ZERO, 1.0, 0);
    let (p2, t2) = uv_sphere(512, 258, DVec3::new(1.2, 0.1, 0.05), 1.0, p.len() as u32);
    p.extend(p2);
    t.extend(t2);
    (p, t)
}

fn random_boxes(n: usize) -> Vec<Aabb> {
    let mut r = Lcg(7);
    (0..n)
        .map(|_| {
            let c = DVec3::new(r.unit(), r.unit(), r.unit());
            let e = DVec3::new(r.unit(), r.unit(), r.unit()) * 0.002;
            Aabb::new(c - e, c + e)
        })
        .collect()
}

#[divan::bench(sample_count = 10)]
fn bvh_build_1m(b: Bencher) {
    let boxes = random_boxes(1_000_000);
    b.bench(|| Bvh::build(&boxes).map(|t| t.node_count()));
}

#[divan::bench(sample_count = 10)]
fn bvh_stream_1m_queries(b: Bencher) {
    let boxes = random_boxes(1_000_000);
    let bvh = Bvh::build(&boxes).expect("finite");
    b.bench(|| bvh.overlap_pairs(&boxes).len());
}

#[divan::bench(sample_count = 10)]
fn self_overlaps_two_spheres_524k(b: Bencher) {
    let (p, t) = two_spheres();
    let boxes: Vec<Aabb> = t
        .iter()
        .map(|x| Aabb::from_points(&[p[x[0] as usize], p[x[1] as usize], p[x[2] as usize]]))
        .collect();
    b.bench(|| {
        let bvh = Bvh::build(&boxes).expect("finite");
        bvh.self_overlaps().len()
    });
}

#[divan::bench(sample_count = 5)]
fn ccd_union_524k(b: Bencher) {
    // Sphere B (at x = 2.5) sweeps into sphere A (at the origin).
    let (mut p, mut t) = uv_sphere(512, 258, DVec3::ZERO, 1.0, 0);
    let (p2, t2) = uv_sphere(512, 258, DVec3::new(2.5, 0.1, 0.05), 1.0, p.len() as u32);
    let na = p.len();
    p.extend(p2);
    t.extend(t2);
    let end: Vec<DVec3> = p
        .iter()
        .enumerate()
        .map(|(i, &x)| if i >= na { x - DVec3::X * 1.3 } else { x })
        .collect();
    b.bench(|| vertex_parities(&p, &end, &t, &CcdOptions::default()).map(|r| r.odd_pairs.len()));
}

#[divan::bench]
fn orient3d_random(b: Bencher) {
    let mut r = Lcg(1);
    let pts: Vec<DVec3> = (0..4096)
        .map(|_| DVec3::new(r.unit(), r.unit(), r.unit()))
        .collect();
    b.counter(divan::counter::ItemsCount::new(4093usize))
        .bench(|| {
            let mut s = 0i32;
            for w in pts.windows(4) {
                s += orient3d(w[0], w[1], w[2], w[3]) as i32;
            }
            s
        });
}

#[divan::bench]
fn orient3d_sos_grid(b: Bencher) {
    let mut r = Lcg(2);
    let pts: Vec<SymPoint> = (0..4096u32)
        .map(|i| {
            let g = |r: &mut Lcg| (r.unit() * 3.0).floor();
            SymPoint::new(DVec3::new(g(&mut r), g(&mut r), g(&mut r)), i)
        })
        .collect();
    b.counter(divan::counter::ItemsCount::new(4093usize))
        .bench(|| {
            let mut s = 0i32;
            for w in pts.windows(4) {
                s += orient3d_sos(w[0], w[1], w[2], w[3]).as_i8() as i32;
            }
            s
        });
}
