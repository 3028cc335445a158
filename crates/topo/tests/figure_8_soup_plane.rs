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
    let (start, end) = still_and_moving(plane, &s, CENTRE + DVec3::new(0.0, 0.0, 1.5), CENTRE);
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
    let a = plane.area();
    (a, m.area() - a)
}

#[test]
fn soup_and_welded_plane_agree() {
    // Radius of the hole: the sphere's section at z = 0.
    let rc = (R * R - CENTRE.z * CENTRE.z).sqrt();
    let hole = std::f64::consts::PI * rc * rc;
    let cap = std::f64::consts::TAU * R * (R + CENTRE.z);
    let welded_in = welded();
    let (w, _) = push_sphere(&welded_in);
    let mut results = vec![("welded", w, welded_in.area())];
    for seed in [1, 2] {
        let s = jittered_soup(seed);
        let plane_area = s.area();
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

/// Figure 8 at other sizes: soup planes of 20×20, 40×40 and 80×80 squares
/// on [-2, 2]², jittered by 1%, 2% and 3% of a square's side, with the sphere
/// pushed halfway in and a closed cylinder (Figure 4's) plunged through
/// the plane. Whatever the size, the part of each solid that went under
/// the plane is gone (no triangle lies wholly under the jitter's slab),
/// the plane keeps everything outside the solid's section, and a disk of
/// the section's area is cut out of it (within 5%). (At 4% one case of
/// the twelve, the sphere through 40×40, keeps two triangles under the
/// plane: a vertex slipped between soup triangles without colliding and
/// its edges to the vertices above slip through the same gaps, so no
/// curve separates it from them and correction cannot tell it apart.)
#[test]
fn soups_of_many_sizes_and_jitters() {
    for n in [20u32, 40, 80] {
        for share in [0.01, 0.02, 0.03] {
            let cell = 4.0 / f64::from(n);
            let jitter = share * cell;
            let mut rng = Rng::new(u64::from(n) * 1000 + (share * 100.0) as u64);
            let mut plane = soup(&scale(&primitive(&format!("@tri-plane:{n}:{n}")), 2.0));
            for p in &mut plane.positions {
                *p += DVec3::new(
                    rng.range(-jitter, jitter),
                    rng.range(-jitter, jitter),
                    rng.range(-jitter, jitter),
                );
            }
            let plane_area = plane.area();
            // The solids: a sphere of radius R whose centre ends 0.1 over
            // the plane, and a cylinder of radius 0.5 and height 1.2 whose
            // bottom ends 0.6 under it.
            let sphere = scale(&primitive("@sphere:3"), R);
            let cyl = primitive("@cylinder:32:4");
            let (lo, hi) = bounds(&cyl);
            let fit = |p: DVec3| {
                let q = (p - (lo + hi) * 0.5) / (hi - lo);
                DVec3::new(q.x, q.y, q.z * 1.2 + 0.5)
            };
            let cylinder = TriMesh {
                positions: cyl.positions.iter().map(|&p| fit(p)).collect(),
                triangles: cyl.triangles.clone(),
            };
            for (what, solid, end_shift, section) in [
                ("sphere", &sphere, CENTRE, {
                    let rc = (R * R - CENTRE.z * CENTRE.z).sqrt();
                    std::f64::consts::PI * rc * rc
                }),
                (
                    "cylinder",
                    &cylinder,
                    DVec3::new(0.013, -0.021, -0.6),
                    std::f64::consts::PI * 0.25,
                ),
            ] {
                let (start, end) = still_and_moving(
                    &plane,
                    solid,
                    end_shift + DVec3::new(0.0, 0.0, 1.6),
                    end_shift,
                );
                let m = run(&start, &end, &Options::default()).mesh;
                let tag = format!("{what} through a {n}×{n} soup jittered {share}");
                let below: Vec<&[u32; 3]> = m
                    .triangles
                    .iter()
                    .filter(|t| {
                        t.iter()
                            .all(|&v| m.positions[v as usize].z < -jitter - 1e-12)
                    })
                    .collect();
                assert!(
                    below.is_empty(),
                    "{tag}: {} triangles left under the plane",
                    below.len()
                );
                let kept_plane: f64 = (0..m.triangles.len())
                    .filter(|&t| m.corners(t).iter().all(|p| p.z.abs() <= jitter + 1e-12))
                    .map(|t| m.triangle_area(t))
                    .sum();
                let hole = plane_area - kept_plane;
                assert!(
                    (hole - section).abs() < 0.05 * section + 4.0 * cell * cell,
                    "{tag}: cut out {hole} vs the section {section}"
                );
            }
        }
    }
}

fn bounds(m: &TriMesh) -> (DVec3, DVec3) {
    m.positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        })
}
