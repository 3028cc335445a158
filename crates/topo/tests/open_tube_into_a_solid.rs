//! An open tube pushed end first into a closed solid: the teapot's spout
//! pushed into its body, in miniature (issue 15, item 3: "pushing a tip
//! into a body fuses it").
//!
//! The tube's vertices that crossed the sphere are odd and its part inside
//! is deleted. The sphere's cap inside the tube's loop is crossed by
//! nothing (the tube has no lid), so every vertex of it is even: parity
//! alone keeps both halves of the sphere and leaves the tube's cut end
//! standing on it, a T at every curve edge. The one manifold reading pairs
//! the tube's kept wall with the half of the sphere whose orientation
//! continues it, the outside of the loop; the cap, enclosed by the loop,
//! goes, and the tube opens into the sphere.
//!
//! Expected, from the shapes: one piece; one boundary loop (the tube's
//! far end); every edge on at most two triangles; χ = V − E + F = 1 (a
//! disk: the sphere less its cap, with an annulus glued along the loop);
//! no crossing pair; the sphere's area less that of the cap inside the
//! tube, 2πRh with h = R − √(R² − r²), within the facets' error.

mod common;

use common::*;
use glam::DVec3;
use holey_topo::{Options, TriMesh};

/// The tube of `tube()` without its two end fans: open at both ends.
fn open_tube(centre: &[DVec3], radius: f64, segments: u32) -> TriMesh {
    let closed = tube(centre, radius, segments, 0.1, DVec3::X);
    let caps = (centre.len() as u32) * segments;
    TriMesh {
        positions: closed.positions,
        triangles: closed
            .triangles
            .into_iter()
            .filter(|t| t.iter().all(|&v| v < caps))
            .collect(),
    }
}

#[test]
fn open_tube_pushed_into_a_sphere_opens_into_it() {
    let sphere = primitive("@sphere:4");
    let big_r = sphere
        .positions
        .iter()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    let r = 0.3 * big_r;
    // The tube: z from 1.25 R to 2.25 R over the sphere's top, rows 0.05 R
    // apart, moved down by R: its end ends at 0.25 R, inside the sphere.
    let rows: Vec<DVec3> = (0..=20)
        .map(|i| {
            DVec3::new(
                0.013 * big_r,
                -0.007 * big_r,
                big_r * (1.25 + 0.05 * f64::from(i)),
            )
        })
        .collect();
    let pipe = open_tube(&rows, r, 24);
    assert_eq!(boundary(&pipe).1, 2, "the tube is open at both ends");
    let start = join(&sphere, &pipe);
    let mut end = start.positions.clone();
    for p in &mut end[sphere.positions.len()..] {
        p.z -= big_r;
    }
    let out = run(&start, &end, &Options::default());
    let m = &out.mesh;
    assert_eq!(
        max_edge_degree(m),
        2,
        "an edge on three sheets: {:?}",
        out.report
    );
    assert_eq!(components(m), 1, "one piece");
    assert_eq!(boundary(m).1, 1, "one boundary loop, the tube's far end");
    assert_eq!(euler(m), 1, "a disk");
    assert_eq!(self_intersecting_pairs(m), 0);
    // Area: the sphere loses its cap, 2πRh, and the tube (length R) keeps
    // what stands above the loop at height R − h.
    let h = big_r - (big_r * big_r - r * r).sqrt();
    let cap = std::f64::consts::TAU * big_r * h;
    let tube_left = pipe.area() * (1.25 * big_r - (big_r - h)) / big_r;
    let missing = sphere.area() + tube_left - m.area();
    assert!(
        (missing - cap).abs() < 0.25 * cap,
        "area missing {missing}, the cap's {cap}"
    );
}
