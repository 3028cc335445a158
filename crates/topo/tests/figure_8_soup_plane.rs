//! Figure 8: the ground plane as a triangle soup — every triangle its own
//! three vertices, each jittered by up to ±0.02 — behaves like the welded
//! plane when a sphere is pushed halfway into it: the same disk is cut out
//! of the plane and the same cap of the sphere stays above it.

#![allow(clippy::unwrap_used)]

mod common;

use common::*;
use glam::DVec3;
use holey_testkit::Rng;
use holey_topo::{Options, TriMesh};

const R: f64 = 0.7;
const CENTRE: DVec3 = DVec3::new(0.031, -0.017, 0.1);
const JITTER: f64 = 0.02;

/// 20×20 squares on [-2,2]² at z = 0.
fn welded() -> TriMesh {
    scale(&primitive("@tri-plane:20:20"), 2.0)
}

fn jittered_soup(seed: u64) -> TriMesh {
    let mut rng = Rng::new(seed);
    let mut m = soup(&welded());
    for p in &mut m.positions {
        *p += DVec3::new(
            rng.range(-JITTER, JITTER),
            rng.range(-JITTER, JITTER),
            rng.range(-JITTER, JITTER),
        );
    }
    m
}

/// The sphere comes down from z = 1.5 + 0.1 to centre 0.1: its bottom
/// goes 0.6 under the plane.
fn push_sphere(plane: &TriMesh) -> (TriMesh, usize) {
    let s = scale(&primitive("@sphere:3"), R);
    let start = join(plane, &translate(&s, CENTRE + DVec3::new(0.0, 0.0, 1.5)));
    let end: Vec<DVec3> = plane
        .positions
        .iter()
        .copied()
        .chain(s.positions.iter().map(|&p| p + CENTRE))
        .collect();
    (
        run(&start, &end, &Options::default()).mesh,
        plane.positions.len(),
    )
}

/// Output triangles of the plane: every corner within the jitter slab.
fn in_slab(m: &TriMesh, t: &[u32; 3]) -> bool {
    t.iter()
        .all(|&v| m.positions[v as usize].z.abs() <= JITTER + 1e-12)
}

/// Is (x, y) within `tol` of a plane triangle of `m` (in projection)?
fn covered(m: &TriMesh, x: f64, y: f64, tol: f64) -> bool {
    let q = glam::DVec2::new(x, y);
    m.triangles.iter().filter(|t| in_slab(m, t)).any(|t| {
        let [a, b, c] = t.map(|v| m.positions[v as usize].truncate());
        let s = |p: glam::DVec2, r: glam::DVec2| (r - p).perp_dot(q - p);
        let (s1, s2, s3) = (s(a, b), s(b, c), s(c, a));
        if (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0) {
            return true;
        }
        let seg = |p: glam::DVec2, r: glam::DVec2| {
            let t = ((q - p).dot(r - p) / (r - p).length_squared()).clamp(0.0, 1.0);
            (p + (r - p) * t - q).length()
        };
        seg(a, b).min(seg(b, c)).min(seg(c, a)) <= tol
    })
}

fn plane_and_cap_areas(m: &TriMesh) -> (f64, f64) {
    let plane = TriMesh {
        positions: m.positions.clone(),
        triangles: m
            .triangles
            .iter()
            .filter(|t| in_slab(m, t))
            .copied()
            .collect(),
    };
    let a = area(&plane);
    (a, area(m) - a)
}

#[test]
fn soup_and_welded_plane_agree() {
    // Radius of the hole: the sphere's section at z = 0.
    let rc = (R * R - CENTRE.z * CENTRE.z).sqrt();
    let hole = std::f64::consts::PI * rc * rc;
    let cap = std::f64::consts::TAU * R * (R + CENTRE.z);
    let welded_in = welded();
    let (w, _) = push_sphere(&welded_in);
    let mut results = vec![("welded", w, area(&welded_in))];
    for seed in [1, 2] {
        let s = jittered_soup(seed);
        let plane_area = area(&s);
        results.push(("soup", push_sphere(&s).0, plane_area));
    }
    let mut rng = Rng::new(99);
    for (what, m, plane_area) in &results {
        well_formed(m);
        let (p, c) = plane_and_cap_areas(m);
        // The deleted disk, the kept cap (polyhedral sphere: within 3%).
        assert!(
            ((plane_area - p) - hole).abs() < 0.05 * hole,
            "{what}: deleted {} vs disk {hole}",
            plane_area - p
        );
        assert!(
            (c - cap).abs() < 0.03 * cap,
            "{what}: cap area {c} vs {cap}"
        );
        // The same region is deleted: points well inside the section are
        // bare, points well outside are covered (within the soup's gaps).
        for _ in 0..400 {
            let (x, y) = (rng.range(-1.9, 1.9), rng.range(-1.9, 1.9));
            let rho = ((x - CENTRE.x).powi(2) + (y - CENTRE.y).powi(2)).sqrt();
            if (rho - rc).abs() < 0.1 {
                continue;
            }
            assert_eq!(
                covered(m, x, y, 0.03),
                rho > rc,
                "{what}: ({x}, {y}) at distance {rho} from the axis"
            );
        }
    }
    // Welded: no self-intersection at all. Soup: the jittered plane
    // triangles may overlap each other, but nothing crosses the sphere.
    assert_eq!(
        self_intersecting_pairs(&results[0].1),
        0,
        "welded result intersects itself"
    );
    for (what, m, _) in &results[1..] {
        let x = holey_topo::self_intersections(m).unwrap();
        for &(a, b) in &x.pairs {
            let (ta, tb) = (m.triangles[a as usize], m.triangles[b as usize]);
            assert!(
                in_slab(m, &ta) && in_slab(m, &tb),
                "{what}: triangles {ta:?} and {tb:?} intersect off the plane"
            );
        }
    }
}
