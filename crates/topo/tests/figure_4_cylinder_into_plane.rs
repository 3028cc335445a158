//! Figure 4: a closed cylinder plunged into an open ground plane. Parity
//! deletes the disk of the plane the cylinder's bottom swept and the part
//! of the cylinder that went under: the plane gets a hole glued to the
//! upper part of the cylinder — a "top hat", still a disk with one
//! boundary loop. Plunged from below to the same final position, the
//! mirror image is kept: the motion, not the final position, decides.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

const SEGMENTS: u32 = 16;

/// Ground plane: 20×20 squares on [-3,3]², z = 0.
fn plane() -> TriMesh {
    scale(&primitive("@tri-plane:20:20"), 3.0)
}

/// Cylinder of radius 1, z in [-1,1], 3 rings of side quads (no ring at
/// z = 0.1, where the plane will cut it), slightly off the grid lines.
fn cylinder() -> TriMesh {
    primitive(&format!("@cylinder:{SEGMENTS}:3"))
}

const OFFSET: DVec3 = DVec3::new(0.013, 0.021, 0.1);

fn plunge(from_z: f64) -> (TriMesh, TriMesh) {
    let (p, c) = (plane(), cylinder());
    let (start, end) = still_and_moving(&p, &c, OFFSET + DVec3::new(0.0, 0.0, from_z), OFFSET);
    let out = run(&start, &end, &Options::default()).mesh;
    (start, out)
}

/// Area of the regular 16-gon of circumradius 1 and its perimeter.
fn polygon() -> (f64, f64) {
    let n = f64::from(SEGMENTS);
    let a = std::f64::consts::TAU / n;
    (0.5 * n * a.sin(), n * 2.0 * (a / 2.0).sin())
}

fn check_top_hat(out: &TriMesh, above: bool) {
    assert_eq!(
        self_intersecting_pairs(out),
        0,
        "the result intersects itself"
    );
    assert_eq!(components(out), 1, "the cylinder is not glued to the plane");
    assert_eq!(max_edge_degree(out), 2, "non-manifold edges");
    // A disk: one boundary loop, the plane's outer square, and χ = 1.
    let (_, loops) = boundary(out);
    assert_eq!(loops, 1, "boundary loops");
    assert_eq!(euler(out), 1, "Euler characteristic of a disk");
    // Boundary vertices are on the outer square only: no gap around the hole.
    let mut undirected = std::collections::HashMap::new();
    for t in &out.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *undirected.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    for (&(a, b), &n) in &undirected {
        if n == 1 {
            for v in [a, b] {
                let p = out.positions[v as usize];
                assert!(
                    p.x.abs().max(p.y.abs()) > 3.0 - 1e-9,
                    "inner boundary vertex {p}"
                );
            }
        }
    }
    // Only the kept half of the cylinder is left off the plane.
    let sign = if above { 1.0 } else { -1.0 };
    for v in out.triangles.iter().flatten() {
        let p = out.positions[*v as usize];
        assert!(sign * p.z > -1e-9, "vertex {p} on the deleted side");
    }
    // Area: the plane minus the polygon, plus the kept side and one cap
    // (the cap of the polygon's area): exactly 36 + perimeter × height.
    let (_, perimeter) = polygon();
    let height = if above {
        1.0 + OFFSET.z
    } else {
        1.0 - OFFSET.z
    };
    let expected = 36.0 + perimeter * height;
    let a = out.area();
    assert!(
        (a - expected).abs() < 1e-6 * expected,
        "area {a} vs {expected}"
    );
}

#[test]
fn plunged_from_above_keeps_the_top_hat() {
    let (_, out) = plunge(3.0);
    check_top_hat(&out, true);
}

#[test]
fn plunged_from_below_keeps_the_bottom_part() {
    let (_, out) = plunge(-3.0);
    check_top_hat(&out, false);
}

#[test]
fn the_hole_is_the_cylinder_cross_section() {
    // Points of the plane inside the polygon (shrunk) are gone, points
    // outside it (grown) remain: sample a ring of points at z = 0 and
    // look for output triangles of the plane over them.
    let (_, out) = plunge(3.0);
    let covered = |x: f64, y: f64| {
        out.triangles.iter().any(|t| {
            let [a, b, c] = t.map(|v| out.positions[v as usize]);
            if a.z.abs() > 1e-9 || b.z.abs() > 1e-9 || c.z.abs() > 1e-9 {
                return false;
            }
            let s = |p: DVec3, q: DVec3| (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
            let (s1, s2, s3) = (s(a, b), s(b, c), s(c, a));
            (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
        })
    };
    for k in 0..40 {
        let a = std::f64::consts::TAU * f64::from(k) / 40.0 + 0.05;
        let (x0, y0) = (OFFSET.x, OFFSET.y);
        // The 16-gon's inradius is cos(π/16) ≈ 0.981.
        assert!(
            !covered(x0 + 0.9 * a.cos(), y0 + 0.9 * a.sin()),
            "hole covered at angle {a}"
        );
        assert!(
            covered(x0 + 1.1 * a.cos(), y0 + 1.1 * a.sin()),
            "plane missing at angle {a}"
        );
    }
}

/// Plunged all the way through, the cylinder's bottom and top caps both
/// sweep the disk: the plane is collided twice (even) and stays whole,
/// while every point of the cylinder crossed the plane once (odd): the
/// parity deletes the cylinder and leaves the plane untouched.
#[test]
fn plunged_through_leaves_the_plane_whole() {
    let (p, c) = (plane(), cylinder());
    let start = join(&p, &translate(&c, OFFSET + DVec3::new(0.0, 0.0, 3.0)));
    let end: Vec<DVec3> = p
        .positions
        .iter()
        .copied()
        .chain(
            c.positions
                .iter()
                .map(|&q| q + OFFSET - DVec3::new(0.0, 0.0, 3.0)),
        )
        .collect();
    let out = run(&start, &end, &Options::default());
    assert!(
        out.raw_odd[..p.positions.len()].iter().all(|&o| !o),
        "plane vertices collided an odd number of times"
    );
    assert!(
        out.raw_odd[p.positions.len()..].iter().all(|&o| o),
        "cylinder vertices with even parity"
    );
    assert_eq!(
        unoriented_triangle_keys(&out.mesh),
        unoriented_triangle_keys(&p)
    );
}
