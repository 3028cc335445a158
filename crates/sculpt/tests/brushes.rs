//! Issue 19's brushes and controls, replayed through a [`Session`] on
//! meshes generated in code and checked against oracles written here:
//!
//! - each centred brush moves every vertex as its displacement field says
//!   (the field evaluated in the test from its own normals, weights and
//!   brush plane);
//! - symmetry: a mirrored stroke on a mirror-symmetric sphere leaves a
//!   mirror-symmetric surface;
//! - a mask keeps its vertices bit for bit;
//! - pressure scales the strength;
//! - the snake hook pulled through a sphere's far side makes genus 1; a
//!   crease pressed through a thin slab opens a hole.
#![allow(clippy::unwrap_used)]

use std::collections::HashSet;

use glam::DVec3;
use holey_sculpt::{Brush, Falloff, Mask, Session, Stroke};
use holey_topo::TriMesh;

fn sphere() -> TriMesh {
    holey_shapes::parse_primitive("@sphere:3")
        .unwrap()
        .triangulated()
}

/// Area-weighted vertex normals, summed here from the triangles.
fn normals(m: &TriMesh) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; m.positions.len()];
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| m.positions[v as usize]);
        let w = (b - a).cross(c - a);
        for &v in t {
            n[v as usize] += w;
        }
    }
    n.into_iter().map(|x| x.normalize_or_zero()).collect()
}

/// The brush-plane oracle: weights `(1 − t²)²`, the weighted normal and
/// the weighted mean position of the vertices within `r` of `c`.
struct Plane {
    weights: Vec<f64>,
    normal: DVec3,
    origin: DVec3,
}

fn plane(m: &TriMesh, c: DVec3, r: f64) -> Plane {
    let vn = normals(m);
    let weights: Vec<f64> = m
        .positions
        .iter()
        .map(|p| {
            let t = p.distance(c) / r;
            if t < 1.0 { (1.0 - t * t).powi(2) } else { 0.0 }
        })
        .collect();
    let (mut n, mut o, mut sw) = (DVec3::ZERO, DVec3::ZERO, 0.0);
    for ((w, p), vnorm) in weights.iter().zip(&m.positions).zip(&vn) {
        n += *w * *vnorm;
        o += *w * *p;
        sw += w;
    }
    Plane {
        weights,
        normal: n.normalize(),
        origin: o / sw,
    }
}

/// `m` after `stroke`, applied with remeshing off: the vertices keep
/// their indices, so the oracles can compare them one by one.
fn brushed(m: &TriMesh, stroke: &Stroke) -> TriMesh {
    let mut session = Session::new(m.clone()).unwrap();
    session.set_remeshing(false);
    session.apply_stroke(stroke).unwrap();
    session.into_mesh()
}

fn one_frame(m: &TriMesh, brush: Brush, c: DVec3, r: f64, s: f64) -> TriMesh {
    let stroke = Stroke {
        brush,
        radius: r,
        strength: s,
        path: vec![c],
        ..Stroke::default()
    };
    brushed(m, &stroke)
}

/// The highest vertex of `m`.
fn highest_vertex(m: &TriMesh) -> DVec3 {
    *m.positions
        .iter()
        .max_by(|a, b| a.z.total_cmp(&b.z))
        .unwrap()
}

/// Each centred brush on an icosphere, one frame at the vertex nearest
/// the top, against its displacement field (the doc comment of its file
/// in `crates/sculpt/src/brush/`), vertex by vertex.
#[test]
fn each_brush_moves_vertices_as_its_displacement_field_says() {
    let m = sphere();
    let top = highest_vertex(&m);
    // A centre a little off the vertex, so that pinch and crease have a
    // direction at every vertex.
    let c = top + DVec3::new(0.013, -0.007, 0.0);
    let r = 0.6;
    let pl = plane(&m, c, r);
    let n = pl.normal;
    let across = |v: DVec3| v - v.dot(n) * n;
    let height = |p: DVec3| (p - pl.origin).dot(n);
    let vn = normals(&m);
    type Field<'a> = Box<dyn Fn(usize, DVec3, f64) -> DVec3 + 'a>;
    let cases: Vec<(Brush, f64, Field)> = vec![
        (Brush::Inflate, 0.01, Box::new(|v, _, w| 0.01 * w * vn[v])),
        (Brush::Draw, 0.01, Box::new(|_, _, w| 0.01 * w * n)),
        (Brush::Draw, -0.01, Box::new(|_, _, w| -0.01 * w * n)),
        (
            Brush::Clay,
            0.01,
            Box::new(|_, p, w| w * (0.01 - height(p)).clamp(0.0, 0.01) * n),
        ),
        (
            Brush::Flatten,
            0.5,
            Box::new(|_, p, w| -0.5 * w * height(p) * n),
        ),
        (
            Brush::Scrape,
            0.5,
            Box::new(|_, p, w| 0.5 * w * (-height(p)).min(0.0) * n),
        ),
        (
            Brush::Pinch,
            0.3,
            Box::new(|_, p, w| 0.3 * w * across(c - p)),
        ),
        (
            Brush::Crease,
            0.01,
            Box::new(|_, p, w| -0.01 * w * w * n + (0.01 / r) * w * across(c - p)),
        ),
        (Brush::Scale, 0.1, Box::new(|_, p, w| 0.1 * w * (p - c))),
        (Brush::Scale, -0.1, Box::new(|_, p, w| -0.1 * w * (p - c))),
    ];
    for (brush, s, field) in cases {
        let out = one_frame(&m, brush, c, r, s);
        assert_eq!(
            out.triangles, m.triangles,
            "{brush} {s}: no topology change"
        );
        let mut moved = 0;
        for (v, (p, q)) in m.positions.iter().zip(&out.positions).enumerate() {
            let w = pl.weights[v];
            let want = *p
                + if w > 0.0 {
                    field(v, *p, w)
                } else {
                    DVec3::ZERO
                };
            assert!(
                want.distance(*q) < 1e-12,
                "{brush} {s}: vertex {v} at {q}, the field says {want}"
            );
            moved += usize::from(p != q);
        }
        assert!(moved > 10, "{brush} {s}: only {moved} vertices moved");
    }
}

/// Issue 19: an inflate with symmetry X on a sphere centred at the origin
/// leaves a surface that is its own mirror image: every vertex has its
/// mirror within 1e-9 of the diagonal. Also for crease and pinch, whose
/// fields point across the brush, and for a grab.
#[test]
fn a_stroke_with_symmetry_x_leaves_a_mirror_image() {
    let m = sphere();
    // The icosphere is mirror-symmetric in x: check the oracle first.
    let diag = 2.0 * 3f64.sqrt();
    let mirror_of = |mesh: &TriMesh| -> f64 {
        mesh.positions
            .iter()
            .map(|p| {
                let q = DVec3::new(-p.x, p.y, p.z);
                mesh.positions
                    .iter()
                    .map(|x| x.distance(q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    assert!(mirror_of(&m) < 1e-12 * diag);
    let on_one_side = [
        DVec3::new(0.6, 0.3, 0.74),
        DVec3::new(0.62, 0.25, 0.74),
        DVec3::new(0.64, 0.2, 0.74),
    ];
    for (brush, strength) in [
        (Brush::Inflate, 0.02),
        (Brush::Crease, 0.01),
        (Brush::Pinch, 0.3),
        (Brush::Grab, 1.0),
    ] {
        let path = if brush == Brush::Grab {
            let start = on_one_side[0].normalize();
            vec![start, start * 1.15]
        } else {
            on_one_side.to_vec()
        };
        let stroke = Stroke {
            brush,
            radius: 0.4,
            strength,
            path,
            symmetry: [true, false, false],
            ..Stroke::default()
        };
        let out = &brushed(&m, &stroke);
        let moved = |x_sign: f64| {
            m.positions
                .iter()
                .zip(&out.positions)
                .filter(|(p, q)| p != q && p.x * x_sign > 0.0)
                .count()
        };
        assert!(
            moved(1.0) > 5 && moved(-1.0) > 5,
            "{brush}: both sides move"
        );
        let off = mirror_of(out);
        assert!(off < 1e-9 * diag, "{brush}: {off} from its mirror image");
    }
}

/// Masked vertices keep their positions bit for bit, whatever the brush;
/// the rest of the brushed region moves.
#[test]
fn masked_vertices_do_not_move() {
    let m = sphere();
    let c = DVec3::new(0.0, 0.0, 1.0);
    let ball = Mask::Sphere {
        centre: [0.0, 0.0, 1.0],
        radius: 0.2,
    };
    let masked: HashSet<usize> = m
        .positions
        .iter()
        .enumerate()
        .filter(|(_, p)| p.distance(c) <= 0.2)
        .map(|(v, _)| v)
        .collect();
    assert!(masked.len() > 3);
    for (brush, strength) in [
        (Brush::Inflate, 0.03),
        (Brush::Draw, 0.03),
        (Brush::Smooth, 0.5),
        (Brush::Scale, 0.2),
        (Brush::Grab, 1.0),
    ] {
        let path = if brush == Brush::Grab {
            vec![c, c + DVec3::new(0.1, 0.0, 0.2)]
        } else {
            vec![c]
        };
        let stroke = Stroke {
            brush,
            radius: 0.6,
            strength,
            path,
            mask: Some(ball.clone()),
            ..Stroke::default()
        };
        let out = brushed(&m, &stroke);
        for &v in &masked {
            assert_eq!(
                out.positions[v].to_array().map(f64::to_bits),
                m.positions[v].to_array().map(f64::to_bits),
                "{brush}: masked vertex {v} moved"
            );
        }
        let others = (0..m.positions.len())
            .filter(|v| !masked.contains(v) && m.positions[*v] != out.positions[*v])
            .count();
        assert!(others > 5, "{brush}: the unmasked part moves");
    }
    // Mask by vertex index: the same vertices.
    let by_index = Mask::Vertices(masked.iter().map(|&v| v as u32).collect());
    assert_eq!(
        by_index.positions(&m.positions),
        ball.positions(&m.positions)
    );
}

/// Pen pressure scales the strength: a draw at pressure ½ moves every
/// vertex half as far as at full pressure (a linear field).
#[test]
fn pressure_scales_the_strength() {
    let m = sphere();
    let c = DVec3::new(0.05, 0.0, 1.0);
    let run = |pressure: Vec<f64>| {
        let stroke = Stroke {
            brush: Brush::Draw,
            radius: 0.5,
            strength: 0.02,
            path: vec![c],
            pressure,
            ..Stroke::default()
        };
        brushed(&m, &stroke)
    };
    let full = run(vec![]);
    let half = run(vec![0.5]);
    for ((p, f), h) in m.positions.iter().zip(&full.positions).zip(&half.positions) {
        let (df, dh) = (*f - *p, *h - *p);
        assert!((df * 0.5 - dh).length() < 1e-15, "{df} vs {dh}");
    }
}

/// A falloff curve changes the weights: a constant falloff moves every
/// vertex in the radius by the full strength.
#[test]
fn constant_falloff_moves_the_whole_disk_alike() {
    let m = sphere();
    let c = DVec3::new(0.0, 0.0, 1.0);
    let stroke = Stroke {
        brush: Brush::Draw,
        radius: 0.5,
        strength: 0.02,
        path: vec![c],
        falloff: Falloff::Constant,
        ..Stroke::default()
    };
    for (p, q) in m.positions.iter().zip(&brushed(&m, &stroke).positions) {
        let d = q.distance(*p);
        if p.distance(c) < 0.5 {
            assert!((d - 0.02).abs() < 1e-15, "{d}");
        } else {
            assert_eq!(d, 0.0);
        }
    }
}

fn genus_and_closed(m: &TriMesh) -> (i64, bool) {
    let degrees = holey_testkit::edge_degrees(&m.triangles);
    let v = m.triangles.iter().flatten().collect::<HashSet<_>>().len() as i64;
    let chi = v - degrees.len() as i64 + m.triangles.len() as i64;
    ((2 - chi) / 2, degrees.values().all(|&d| d == 2))
}

/// Issue 19: the snake hook, hooked on a sphere's near side and pulled
/// in through the inside and out of the far side, makes genus 1: the
/// dent it pulls meets the far side, which opens into a tunnel.
#[test]
fn snake_hook_pulled_through_the_far_side_makes_genus_1() {
    let mut s = Session::new(sphere()).unwrap();
    let path: Vec<DVec3> = (0..=20)
        .map(|i| DVec3::new(0.0, 0.0, 1.0 - 2.4 * f64::from(i) / 20.0))
        .collect();
    let r = s
        .apply_stroke(&Stroke {
            brush: Brush::SnakeHook,
            radius: 0.45,
            strength: 1.0,
            path,
            ..Stroke::default()
        })
        .unwrap();
    assert!(r.changes >= 1);
    let m = s.mesh();
    assert_eq!(holey_testkit::components(&m.triangles), 1);
    assert_eq!(genus_and_closed(m), (1, true), "a closed torus");
    assert!(holey_topo::self_intersections(m).unwrap().pieces.is_empty());
}

/// A thin closed slab, `@cube:12` stretched to 4 × 4 × 0.2 (doubled in
/// x and y, a tenth in z), finely divided so a groove has vertices.
fn thin_slab() -> TriMesh {
    let slab = holey_shapes::parse_primitive("@cube:12")
        .unwrap()
        .triangulated();
    TriMesh {
        positions: slab
            .positions
            .iter()
            .map(|p| DVec3::new(p.x * 2.0, p.y * 2.0, p.z * 0.1))
            .collect(),
        triangles: slab.triangles,
    }
}

/// A crease of `radius` pressed into the [`thin_slab`] at `(x, 0)` on its
/// top, with `symmetry`, frame after frame for three times the slab's
/// thickness: it cuts through (a topology change), and the slab stays
/// one closed piece, now of genus `holes`. Returns the result and the
/// bottom of the slab before.
fn crease_through_slab(x: f64, radius: f64, symmetry: [bool; 3], holes: i64) -> (TriMesh, f64) {
    let slab = thin_slab();
    let hi = slab
        .positions
        .iter()
        .fold(f64::NEG_INFINITY, |z, p| z.max(p.z));
    let lo = slab.positions.iter().fold(f64::INFINITY, |z, p| z.min(p.z));
    let at = DVec3::new(x, 0.0, hi);
    let mut s = Session::new(slab).unwrap();
    let r = s
        .apply_stroke(&Stroke {
            brush: Brush::Crease,
            radius,
            strength: 0.02,
            path: vec![at; (3.0 * (hi - lo) / 0.02) as usize],
            symmetry,
            ..Stroke::default()
        })
        .unwrap();
    assert!(r.changes >= 1, "no groove reached the far side");
    let m = s.mesh();
    assert_eq!(holey_testkit::components(&m.triangles), 1);
    assert_eq!(
        genus_and_closed(m),
        (holes, true),
        "a slab with {holes} hole(s)"
    );
    (m.clone(), lo)
}

/// Issue 19: a crease pressed into a thin closed slab, frame after
/// frame at one spot, cuts through to the far side and opens a hole:
/// the slab becomes a closed surface of genus 1.
#[test]
fn crease_through_a_thin_slab_opens_a_hole() {
    crease_through_slab(0.0, 0.5, [false; 3], 1);
}

/// Issue 19: symmetry holds across a topology change. The crease of the
/// slab test, pressed at x = 0.5 with symmetry X about the origin, cuts
/// through at x = ±0.5: a closed surface of genus 2 with a hole at each
/// image of the brush. (The slab's triangulation is not itself
/// mirror-symmetric, so positions are not compared vertex for vertex.)
#[test]
fn a_mirrored_crease_through_a_slab_opens_two_holes() {
    let (m, lo) = crease_through_slab(0.5, 0.45, [true, false, false], 2);
    // One hole at each image of the brush: on each side of x = 0 the
    // groove's tip went through the bottom face (z = lo).
    let deepest = |sign: f64| {
        m.positions
            .iter()
            .filter(|p| p.x * sign > 0.0)
            .map(|p| p.z)
            .fold(f64::INFINITY, f64::min)
    };
    assert!(
        deepest(1.0) < lo && deepest(-1.0) < lo,
        "both sides cut through"
    );
}

/// The layer brush lays a plateau: dwelling at the top of a sphere, the
/// vertex under the centre rises by the layer's height and no further,
/// however long the brush stays (10 frames and 20 frames give the same
/// surface), and no vertex rises further than the layer's height.
#[test]
fn layer_rises_to_its_height_and_stops() {
    let m = sphere();
    let top = highest_vertex(&m);
    let h = 0.03;
    let run = |frames: usize| {
        let stroke = Stroke {
            brush: Brush::Layer,
            radius: 0.5,
            strength: h,
            path: vec![top; frames],
            ..Stroke::default()
        };
        brushed(&m, &stroke)
    };
    let (ten, twenty) = (run(10), run(20));
    assert_eq!(
        ten.positions, twenty.positions,
        "the plateau is reached and kept"
    );
    let v = m.positions.iter().position(|&p| p == top).unwrap();
    let rise = ten.positions[v].distance(top);
    // Along the brush normal of each frame, which tilts a little as the
    // patch rises: within 1% of the height.
    assert!(
        (rise - h).abs() < 1e-2 * h,
        "the centre rose {rise}, the layer is {h}"
    );
    // Nothing rises past the plateau, and nothing outside the brush moves.
    for (p, q) in m.positions.iter().zip(&ten.positions) {
        assert!(q.distance(*p) <= h * (1.0 + 1e-12));
        if p.distance(top) >= 0.5 {
            assert_eq!(p, q);
        }
    }
}
