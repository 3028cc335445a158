//! Whole-pipeline tests: framing, depth, edges, shading sides, robustness
//! and determinism, checked on pixels against analytic expectations.

use glam::{DVec2, DVec3};
use holey_mesh::PolyMesh;

use crate::*;

fn prim(spec: &str) -> PolyMesh {
    holey_shapes::parse_primitive(spec).unwrap()
}

/// Light (high luma, unlike edges) and unlike any grey or tint.
const BG: Rgba = [120, 220, 250, 255];

/// Small pictures on a solid, unmistakable background.
fn opts(width: u32, height: u32) -> RenderOptions {
    RenderOptions {
        width,
        height,
        background: Background::Solid(BG),
        ..RenderOptions::default()
    }
}

/// One polygon in the plane y = 0 through `corners`, given as (x, z) in
/// order: the flat test pieces `View::Front` sees head-on.
fn front_polygon(corners: impl IntoIterator<Item = (f64, f64)>) -> PolyMesh {
    let positions: Vec<DVec3> = corners
        .into_iter()
        .map(|(x, z)| DVec3::new(x, 0.0, z))
        .collect();
    let face: Vec<u32> = (0..positions.len() as u32).collect();
    PolyMesh::from_faces(positions, [face])
}

fn pixels(img: &Image) -> impl Iterator<Item = (u32, u32, Rgba)> + '_ {
    (0..img.height()).flat_map(move |y| {
        (0..img.width()).map(move |x| (x, y, img.pixel(x, y).unwrap_or_default()))
    })
}

fn differing(a: &Image, b: &Image) -> usize {
    assert_eq!((a.width(), a.height()), (b.width(), b.height()));
    a.pixels()
        .chunks(4)
        .zip(b.pixels().chunks(4))
        .filter(|(p, q)| p != q)
        .count()
}

fn luma(p: Rgba) -> u32 {
    (u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10
}

/// The pixel under a world point, with the camera `render` uses.
fn pixel_of(mesh: &PolyMesh, o: &RenderOptions, p: DVec3) -> (u32, u32) {
    let cam = frame(mesh, o).unwrap();
    let q = cam.project(p, o.width, o.height).unwrap();
    (q.x as u32, q.y as u32)
}

/// The pixels covered by the model (different from the background) and
/// their centroid.
fn coverage(img: &Image) -> (usize, DVec2) {
    let mut count = 0;
    let mut sum = DVec2::ZERO;
    for (x, y, p) in pixels(img) {
        if p != BG {
            count += 1;
            sum += DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
        }
    }
    (count, sum / count.max(1) as f64)
}

/// A unit sphere's silhouette is a centred disc whose diameter is FILL of
/// the shorter side, for both framings and for a wide and a tall picture.
#[test]
fn sphere_silhouette_is_centred_and_fills_85_percent() {
    let sphere = prim("@sphere:4");
    for framing in [Framing::Sphere, Framing::Fit] {
        for (w, h) in [(240, 160), (150, 210)] {
            let o = RenderOptions {
                framing,
                ..opts(w, h)
            };
            let img = render(&sphere, &o).unwrap();
            let (count, centroid) = coverage(&img);
            let short = f64::from(w.min(h));
            let expected = std::f64::consts::PI * (FILL * short / 2.0).powi(2);
            let ratio = count as f64 / expected;
            assert!((ratio - 1.0).abs() < 0.03, "{framing:?} {w}x{h}: {ratio}");
            let centre = DVec2::new(f64::from(w), f64::from(h)) / 2.0;
            assert!(
                (centroid - centre).length() < 0.6,
                "{framing:?} {w}x{h}: {centroid} vs {centre}"
            );
        }
    }
}

/// Fit framing fills FILL of the limiting side with the projected model:
/// a long box seen from the front spans 85 % of the width.
#[test]
fn fit_framing_uses_the_projected_extent() {
    let mut bar = prim("@cube");
    for p in &mut bar.positions {
        p.x *= 4.0;
    }
    let o = RenderOptions {
        view: View::Front,
        ..opts(200, 200)
    };
    let img = render(&bar, &o).unwrap();
    let (mut xmin, mut xmax) = (u32::MAX, 0);
    for (x, _, p) in pixels(&img) {
        if p != BG {
            xmin = xmin.min(x);
            xmax = xmax.max(x);
        }
    }
    let span = f64::from(xmax - xmin + 1);
    assert!((span - 170.0).abs() <= 2.0, "{span}");
    assert!((f64::from(xmin + xmax + 1) / 2.0 - 100.0).abs() <= 1.0);
}

/// Two cubes, each with its own colour: the small one in front hides the
/// big one, whichever comes first in the mesh.
#[test]
fn nearer_faces_hide_farther_ones() {
    let big = prim("@cube");
    let mut small = prim("@cube");
    for p in &mut small.positions {
        *p = *p * 0.3 + DVec3::new(0.0, -2.0, 0.0);
    }
    let green: Rgb = [0, 255, 0];
    let red: Rgb = [255, 0, 0];
    for small_first in [false, true] {
        let (first, second) = if small_first {
            (&small, &big)
        } else {
            (&big, &small)
        };
        let mut mesh = first.clone();
        let n = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&second.positions);
        for f in second.faces() {
            let shifted: Vec<u32> = f.iter().map(|&v| v + n).collect();
            mesh.push_face(&shifted);
        }
        let colors: Vec<Rgb> = (0..12)
            .map(|f| {
                let is_small = (f < 6) == small_first;
                if is_small { green } else { red }
            })
            .collect();
        let o = RenderOptions {
            view: View::Front,
            ..opts(120, 120)
        };
        let img = render_with_colors(&mesh, Colors::PerFace(&colors), &o).unwrap();
        let centre = img.pixel(60, 60).unwrap();
        assert!(
            centre[1] > 100 && centre[0] < 30,
            "small_first={small_first}: {centre:?}"
        );
        // Beside the small cube the big one shows.
        let (x, y) = pixel_of(&mesh, &o, DVec3::new(0.7, -1.0, 0.7));
        let side = img.pixel(x, y).unwrap();
        assert!(side[0] > 100 && side[1] < 30, "{side:?}");
    }
}

/// From the front a cube is a square (the front face); with edges, its
/// outline is dark and nothing inside changes (the back face's edges are
/// hidden); without edges, the outline is not dark.
#[test]
fn edges_show_only_where_visible() {
    let cube = prim("@cube");
    let plain = opts(200, 200);
    let o = RenderOptions {
        view: View::Front,
        ..plain.clone()
    };
    let lined = RenderOptions {
        edges: true,
        ..o.clone()
    };
    let without = render(&cube, &o).unwrap();
    let with = render(&cube, &lined).unwrap();
    // The front square spans [15, 185] (85 % of 200, centred); the
    // 1.5-pixel line straddles the boundary, covering 2/3 of the pixels
    // on either side, which makes them clearly darker than the face and
    // background (both of luma about 193 here).
    let darkest =
        |img: &Image, xs: std::ops::RangeInclusive<u32>, ys: std::ops::RangeInclusive<u32>| {
            xs.flat_map(|x| ys.clone().map(move |y| (x, y)))
                .map(|(x, y)| luma(img.pixel(x, y).unwrap()))
                .min()
                .unwrap()
        };
    for t in [40, 100, 160] {
        for (xs, ys) in [
            (t..=t, 14..=16),
            (t..=t, 184..=186),
            (14..=16, t..=t),
            (184..=186, t..=t),
        ] {
            assert!(
                darkest(&with, xs.clone(), ys.clone()) < 140,
                "edge at {xs:?},{ys:?}"
            );
            assert!(
                darkest(&without, xs.clone(), ys.clone()) > 170,
                "no edge at {xs:?},{ys:?}"
            );
        }
    }
    for (x, y, p) in pixels(&with) {
        let inside = (19..=180).contains(&x) && (19..=180).contains(&y);
        if inside {
            assert_eq!(Some(p), without.pixel(x, y), "hidden edge drawn at {x},{y}");
        }
    }
    // In the iso view, the midpoints of the 9 visible edges are dark and
    // the hidden corner (−1, 1, −1) is not.
    let iso = RenderOptions {
        edges: true,
        edge_width: 2.0,
        ..plain
    };
    let img = render(&cube, &iso).unwrap();
    let hidden = DVec3::new(-1.0, 1.0, -1.0);
    let (hx, hy) = pixel_of(&cube, &iso, hidden);
    assert!(luma(img.pixel(hx, hy).unwrap()) > 140);
    let mut dark = 0;
    for f in cube.faces() {
        for k in 0..4 {
            let (a, b) = (
                cube.positions[f[k] as usize],
                cube.positions[f[(k + 1) % 4] as usize],
            );
            if a == hidden || b == hidden {
                continue;
            }
            let (x, y) = pixel_of(&cube, &iso, (a + b) / 2.0);
            assert!(
                darkest(&img, x - 1..=x + 1, y - 1..=y + 1) < 100,
                "edge {a}–{b}"
            );
            dark += 1;
        }
    }
    assert_eq!(dark, 18); // 9 edges, each seen from both faces
}

/// Fan diagonals are not edges: a square and a hexagon seen head-on have
/// light centres with edges on.
#[test]
fn edges_follow_polygon_boundaries_not_fans() {
    let square = front_polygon([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]);
    let hexagon = front_polygon((0..6).map(|k| {
        let a = f64::from(k) * std::f64::consts::PI / 3.0;
        (a.cos(), a.sin())
    }));
    let o = RenderOptions {
        view: View::Front,
        edges: true,
        ..opts(101, 101)
    };
    for mesh in [square, hexagon] {
        let img = render(&mesh, &o).unwrap();
        for (x, y) in [(50, 50), (35, 35), (65, 65), (35, 65), (65, 35), (30, 50)] {
            assert!(luma(img.pixel(x, y).unwrap()) > 150, "{x},{y}");
        }
        assert!(pixels(&img).filter(|p| luma(p.2) < 140).count() > 200);
    }
}

/// Edges shorter than a pixel fade out completely: a dense sphere in a
/// tiny picture looks the same with and without edges.
#[test]
fn sub_pixel_edges_are_not_drawn() {
    let sphere = prim("@sphere:5");
    let o = opts(40, 40);
    let plain = render(&sphere, &o).unwrap();
    let lined = render(&sphere, &RenderOptions { edges: true, ..o }).unwrap();
    assert_eq!(differing(&plain, &lined), 0);
}

#[test]
fn renders_are_byte_identical() {
    let torus = prim("@torus");
    for o in [
        RenderOptions {
            edges: true,
            ..opts(160, 120)
        },
        RenderOptions {
            smooth: true,
            edges: true,
            background: Background::DEFAULT,
            ..opts(130, 170)
        },
    ] {
        let a = render(&torus, &o).unwrap().encode_png().unwrap();
        let b = render(&torus, &o).unwrap().encode_png().unwrap();
        assert_eq!(a, b);
    }
}

#[test]
fn sizes_are_checked() {
    assert_eq!(parse_size("800x600").unwrap(), (800, 600));
    assert_eq!(parse_size(" 64 X 48 ").unwrap(), (64, 48));
    assert_eq!(parse_size("16384x1").unwrap(), (16384, 1));
    for bad in [
        "", "800", "800x", "x600", "8x6x4", "-8x6", "8.5x6", "0x10", "10x0",
    ] {
        assert!(parse_size(bad).is_err(), "{bad:?}");
    }
    let e = parse_size("99999999999x2").unwrap_err();
    assert!(e.to_string().contains("far too large"), "{e}");
    assert!(matches!(
        parse_size("16385x10"),
        Err(RenderError::TooLarge { .. })
    ));
    assert!(matches!(
        parse_size("16384x16384"),
        Err(RenderError::TooLarge { .. })
    ));
    let cube = prim("@cube");
    let zero = render(&cube, &opts(0, 10)).unwrap_err();
    assert!(matches!(zero, RenderError::ZeroSize { .. }), "{zero}");
    let huge = render(&cube, &opts(20_000, 10)).unwrap_err();
    assert!(huge.to_string().contains("too large"), "{huge}");
    assert!(render(&cube, &opts(10_000, 10_000)).is_err());
    // Big pictures get fewer samples per pixel instead of huge buffers.
    assert_eq!(opts(8192, 8192).validate().unwrap(), 1);
    assert_eq!(opts(4096, 4096).validate().unwrap(), 2);
    assert_eq!(opts(1024, 768).validate().unwrap(), 3);
}

#[test]
fn options_are_checked() {
    let cube = prim("@cube");
    let bad = [
        RenderOptions {
            edge_width: 0.0,
            ..opts(10, 10)
        },
        RenderOptions {
            edge_width: f64::NAN,
            ..opts(10, 10)
        },
        RenderOptions {
            crease_angle: 200.0,
            ..opts(10, 10)
        },
        RenderOptions {
            fov: 0.0,
            ..opts(10, 10)
        },
        RenderOptions {
            supersample: 0,
            ..opts(10, 10)
        },
        RenderOptions {
            view: View::Direction(DVec3::ZERO),
            ..opts(10, 10)
        },
    ];
    for o in bad {
        assert!(render(&cube, &o).is_err(), "{o:?}");
    }
    let few = [[1u8, 2, 3]; 5];
    let e = render_with_colors(&cube, Colors::PerFace(&few), &opts(10, 10)).unwrap_err();
    assert!(
        matches!(
            e,
            RenderError::ColorCount {
                expected: 6,
                got: 5,
                ..
            }
        ),
        "{e}"
    );
    assert!(render_with_colors(&cube, Colors::PerVertex(&few), &opts(10, 10)).is_err());
}

/// Faces touching a non-finite vertex are skipped and do not disturb the
/// framing: the picture equals that of the mesh without them.
#[test]
fn non_finite_positions_are_skipped() {
    let cube = prim("@cube");
    let mut bad = cube.clone();
    let nan = bad.positions.len() as u32;
    bad.positions.push(DVec3::new(f64::NAN, 0.0, 1.0));
    bad.positions.push(DVec3::new(0.0, f64::INFINITY, 1.0));
    bad.push_face(&[0, 1, nan]);
    bad.push_face(&[nan + 1, 2, 3, 4]);
    let o = RenderOptions {
        edges: true,
        smooth: true,
        ..opts(90, 70)
    };
    let a = render(&cube, &o).unwrap();
    let b = render(&bad, &o).unwrap();
    assert_eq!(a, b);
    // Nothing drawable at all: the background.
    let only_nan = PolyMesh::from_faces(vec![DVec3::NAN; 3], [[0u32, 1, 2]]);
    let blank = render(&PolyMesh::new(), &o).unwrap();
    assert!(pixels(&blank).all(|p| p.2 == BG));
    assert_eq!(render(&only_nan, &o).unwrap(), blank);
    assert_eq!(render(&PolyMesh::default(), &o).unwrap(), blank);
    // Faces with fewer than three corners are skipped too.
    let slivers = PolyMesh::from_faces(
        vec![DVec3::ZERO, DVec3::X],
        vec![vec![0u32, 1], vec![1], vec![]],
    );
    assert_eq!(render(&slivers, &o).unwrap(), blank);
    // Degenerate faces (all corners on a line) draw nothing and do not panic.
    let line = PolyMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0], [[0u32, 1, 2]]);
    assert!(render(&line, &o).is_ok());
}

#[test]
fn malformed_meshes_are_errors() {
    let mut m = prim("@cube");
    m.face_indices[3] = 99;
    let e = render(&m, &opts(10, 10)).unwrap_err();
    assert!(matches!(e, RenderError::Mesh(_)), "{e}");
    let mut m = prim("@cube");
    m.face_offsets.pop();
    assert!(render(&m, &opts(10, 10)).is_err());
}

/// Size does not matter: a cube scaled by 1e300 and moved far away gives
/// the same picture as the unit cube.
#[test]
fn framing_is_scale_and_translation_invariant() {
    let cube = prim("@cube");
    let mut huge = cube.clone();
    for p in &mut huge.positions {
        *p *= 1e300;
    }
    let o = RenderOptions {
        edges: true,
        ..opts(80, 60)
    };
    assert_eq!(render(&cube, &o).unwrap(), render(&huge, &o).unwrap());
    let mut moved = cube.clone();
    for p in &mut moved.positions {
        *p += DVec3::new(1024.0, -512.0, 64.0);
    }
    assert_eq!(render(&cube, &o).unwrap(), render(&moved, &o).unwrap());
}

fn warm(p: Rgba) -> bool {
    i32::from(p[0]) - i32::from(p[2]) > 40
}

/// An open plane (facing +z) seen from below shows the back tint; from
/// above the neutral front material.
#[test]
fn back_faces_have_their_own_tint() {
    let plane = prim("@plane");
    let above = render(&plane, &opts(60, 60)).unwrap();
    let below_opts = RenderOptions {
        view: View::parse("1,-0.8,-1.2").unwrap(),
        ..opts(60, 60)
    };
    let below = render(&plane, &below_opts).unwrap();
    let (a, b) = (above.pixel(30, 30).unwrap(), below.pixel(30, 30).unwrap());
    assert!(
        !warm(a) && (i32::from(a[0]) - i32::from(a[2])).abs() < 15,
        "{a:?}"
    );
    assert!(warm(b), "{b:?}");
    let green = RenderOptions {
        back_color: [0, 200, 0],
        ..below_opts
    };
    let g = render(&plane, &green).unwrap().pixel(30, 30).unwrap();
    assert!(g[1] > 60 && g[0] < 10 && g[2] < 10, "{g:?}");
    // Inside-out: the reversed cube is all back faces.
    let mut inverted = prim("@cube");
    let faces: Vec<Vec<u32>> = inverted
        .faces()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    inverted.face_offsets = vec![0];
    inverted.face_indices.clear();
    for f in &faces {
        inverted.push_face(f);
    }
    let img = render(&inverted, &opts(60, 60)).unwrap();
    assert!(warm(img.pixel(30, 30).unwrap()));
}

/// Smooth shading hides facets: neighbouring pixels inside a coarse
/// sphere differ much less than with flat shading.
#[test]
fn smooth_shading_hides_facets() {
    let sphere = prim("@sphere:2");
    let jump = |smooth: bool| {
        let o = RenderOptions {
            smooth,
            ..opts(120, 120)
        };
        let img = render(&sphere, &o).unwrap();
        let mut worst = 0;
        for y in 30..90 {
            for x in 30..89 {
                let (p, q) = (img.pixel(x, y).unwrap(), img.pixel(x + 1, y).unwrap());
                worst = worst.max(luma(p).abs_diff(luma(q)));
            }
        }
        worst
    };
    let (flat, smooth) = (jump(false), jump(true));
    assert!(flat >= 8, "{flat}");
    assert!(smooth <= 3, "{smooth}");
}

/// A cube stays faceted under smooth shading (its dihedral angles exceed
/// the crease angle): the image equals the flat one up to rounding.
#[test]
fn creases_stay_sharp() {
    let cube = prim("@cube");
    let flat = render(&cube, &opts(80, 80)).unwrap();
    let smooth = render(
        &cube,
        &RenderOptions {
            smooth: true,
            ..opts(80, 80)
        },
    )
    .unwrap();
    let worst = flat
        .pixels()
        .iter()
        .zip(smooth.pixels())
        .map(|(a, b)| a.abs_diff(*b))
        .max();
    assert!(worst <= Some(1), "{worst:?}");
}

/// Per-vertex colours are interpolated across the face.
#[test]
fn vertex_colours_blend() {
    let tri = front_polygon([(-1.0, -1.0), (1.0, -1.0), (0.0, 1.0)]);
    let colors = [[255, 0, 0], [0, 255, 0], [0, 0, 255]];
    let o = RenderOptions {
        view: View::Front,
        ..opts(100, 100)
    };
    let img = render_with_colors(&tri, Colors::PerVertex(&colors), &o).unwrap();
    let near = |p: DVec3| {
        let (x, y) = pixel_of(&tri, &o, p);
        img.pixel(x, y).unwrap()
    };
    let r = near(DVec3::new(-0.8, 0.0, -0.9));
    let g = near(DVec3::new(0.8, 0.0, -0.9));
    let b = near(DVec3::new(0.0, 0.0, 0.8));
    assert!(r[0] > r[1] + 50 && r[0] > r[2] + 50, "{r:?}");
    assert!(g[1] > g[0] + 50 && g[1] > g[2] + 50, "{g:?}");
    assert!(b[2] > b[0] + 50 && b[2] > b[1] + 50, "{b:?}");
    let mid = near(DVec3::new(0.0, 0.0, -0.4));
    assert!(mid.iter().take(3).all(|&c| c > 40), "{mid:?}");
}

/// The camera `frame` reports, fixed, reproduces the picture.
#[test]
fn a_fixed_camera_reproduces_the_framed_picture() {
    let torus = prim("@torus");
    let o = RenderOptions {
        edges: true,
        ..opts(120, 90)
    };
    let cam = frame(&torus, &o).unwrap();
    let fixed = RenderOptions {
        framing: Framing::Fixed(cam),
        ..o.clone()
    };
    let a = render(&torus, &o).unwrap();
    let b = render(&torus, &fixed).unwrap();
    assert!(differing(&a, &b) <= 20, "{}", differing(&a, &b));
    // The target is the bounding box centre, the eye along the iso view.
    assert!(cam.target.length() < 1e-9);
    let d = (cam.eye - cam.target).normalize();
    assert!((d - View::Iso.direction(Up::Z).unwrap()).length() < 1e-9);
}

/// Cameras inside or behind the model are clipped, never panic.
#[test]
fn near_plane_clipping() {
    let plane = prim("@plane:8");
    let low = Camera {
        eye: DVec3::new(0.0, -0.9, 0.05),
        target: DVec3::new(0.0, 1.0, 0.0),
        up: DVec3::Z,
        fov: 90.0,
        shift: DVec2::ZERO,
    };
    let o = RenderOptions {
        framing: Framing::Fixed(low),
        edges: true,
        ..opts(80, 60)
    };
    let img = render(&plane, &o).unwrap();
    // The plane fills the lower half up to the horizon.
    assert_ne!(img.pixel(40, 58).unwrap(), BG);
    assert_eq!(img.pixel(40, 2).unwrap(), BG);
    let behind = Camera {
        eye: DVec3::new(0.0, -3.0, 0.05),
        target: DVec3::new(0.0, -5.0, 0.0),
        ..low
    };
    let img = render(
        &plane,
        &RenderOptions {
            framing: Framing::Fixed(behind),
            ..o.clone()
        },
    )
    .unwrap();
    assert!(pixels(&img).all(|p| p.2 == BG));
    let degenerate = Camera {
        target: low.eye,
        ..low
    };
    assert!(matches!(
        render(
            &plane,
            &RenderOptions {
                framing: Framing::Fixed(degenerate),
                ..o.clone()
            }
        ),
        Err(RenderError::Camera(_))
    ));
    let parallel = Camera {
        up: DVec3::Y,
        target: DVec3::new(0.0, 1.0, 0.05),
        ..low
    };
    assert!(
        render(
            &plane,
            &RenderOptions {
                framing: Framing::Fixed(parallel),
                ..o
            }
        )
        .is_err()
    );
}

/// A y-up model with `Up::Y` looks like the same model stood up in z-up.
#[test]
fn y_up_models_look_like_z_up_ones() {
    let torus = prim("@torus");
    let mut y_up = torus.clone();
    for p in &mut y_up.positions {
        *p = Up::Y.from_z_up(*p);
    }
    for view in [View::Iso, View::Front, View::Top, View::Left] {
        let o = RenderOptions {
            view,
            ..opts(90, 70)
        };
        let a = render(&torus, &o).unwrap();
        let b = render(
            &y_up,
            &RenderOptions {
                up: Up::Y,
                ..o.clone()
            },
        )
        .unwrap();
        assert!(differing(&a, &b) <= 10, "{view:?}: {}", differing(&a, &b));
    }
}

#[test]
fn transparent_background() {
    let o = RenderOptions {
        background: Background::TRANSPARENT,
        ..opts(40, 40)
    };
    let img = render(&prim("@sphere:2"), &o).unwrap();
    assert_eq!(img.pixel(0, 0).unwrap()[3], 0);
    assert_eq!(img.pixel(20, 20).unwrap()[3], 255);
    // Anti-aliased silhouette pixels are partly transparent.
    assert!(pixels(&img).any(|p| p.2[3] > 0 && p.2[3] < 255));
    assert!(!img.is_opaque());
}

/// The default gradient background is lighter at the top and the model
/// stands out from it.
#[test]
fn default_background_gradient() {
    let o = RenderOptions {
        width: 50,
        height: 50,
        ..RenderOptions::default()
    };
    let img = render(&PolyMesh::new(), &o).unwrap();
    let (top, bottom) = (img.pixel(3, 0).unwrap(), img.pixel(3, 49).unwrap());
    assert!(luma(top) > luma(bottom) + 20);
    assert!(img.is_opaque());
}
