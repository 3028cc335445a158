//! Scenario tests of issue 5 (Bernstein & Wojtan 2013, §4, Figure 1 and
//! the applications of §6: pinch closing, part assembly (Figure 9) and
//! paper mâché (Figure 11)), on meshes generated in code, checked with
//! helpers independent of the crate: closedness, components, boundary
//! loops and genus by the Euler characteristic; and a seeded fuzz loop of
//! strokes and remeshing.
#![allow(clippy::unwrap_used)]

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use holey_sculpt::{
    Brush, Remesh, RemeshOptions, SculptError, Session, Stroke, parse_strokes, remesh_with,
};
use holey_topo::{Options, TriMesh, self_intersections};

fn sphere(centre: DVec3) -> TriMesh {
    let p = holey_shapes::parse_primitive("@sphere:3").unwrap();
    p.triangulated().translated(centre)
}

fn from_poly(p: holey_shapes::PolyMesh) -> TriMesh {
    p.triangulated()
}

fn transformed(m: &TriMesh, scale: f64, offset: DVec3) -> TriMesh {
    TriMesh {
        positions: m.positions.iter().map(|&p| p * scale + offset).collect(),
        triangles: m.triangles.clone(),
    }
}

fn join(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let mut m = a.clone();
    m.append(b);
    m
}

/// Undirected edges with the number of triangles on each.
fn edges(m: &TriMesh) -> HashMap<(u32, u32), usize> {
    holey_testkit::edge_degrees(&m.triangles)
}

/// Every edge has exactly two triangles.
fn closed(m: &TriMesh) -> bool {
    edges(m).values().all(|&c| c == 2)
}

fn components(m: &TriMesh) -> usize {
    holey_testkit::components(&m.triangles)
}

/// Genus of a closed, connected surface: χ = V − E + F = 2 − 2g.
fn genus(m: &TriMesh) -> i64 {
    let v = m.triangles.iter().flatten().collect::<HashSet<_>>().len() as i64;
    let e = edges(m).len() as i64;
    let f = m.triangles.len() as i64;
    let chi = v - e + f;
    assert_eq!(chi % 2, 0, "odd Euler characteristic {chi}");
    (2 - chi) / 2
}

/// Boundary loops: connected groups of edges with one triangle.
fn boundary_loops(m: &TriMesh) -> usize {
    holey_testkit::boundary(&m.triangles).1
}

/// Every triangle refers to existing vertices, every position is finite.
fn valid(m: &TriMesh) -> bool {
    m.check().is_ok()
}

fn no_self_intersections(m: &TriMesh) -> bool {
    self_intersections(m).unwrap().pieces.is_empty()
}

fn stroke(brush: Brush, radius: f64, strength: f64, path: &[[f64; 3]]) -> Stroke {
    Stroke {
        brush,
        radius,
        strength,
        path: path.iter().map(|&p| DVec3::from_array(p)).collect(),
        ..Stroke::default()
    }
}

/// A move of the whole piece picked at the path's first point (radius 0),
/// at full strength.
fn move_piece(path: &[[f64; 3]]) -> Stroke {
    stroke(Brush::Move, 0.0, 1.0, path)
}

/// After `stroke` moved an open part into the unit body: one topology
/// change, a valid mesh of one component with `loops` boundary loops left
/// and no self-intersection, and no vertex within 0.9 of the body's
/// centre (the part's end that went in is gone). `what` names the part.
fn assert_part_attached(s: &mut Session, stroke: &Stroke, loops: usize, what: &str) {
    let r = s.apply_stroke(stroke).unwrap();
    assert_eq!(r.changes, 1);
    let m = s.mesh();
    assert!(valid(m));
    assert_eq!(components(m), 1, "the {what} is attached");
    assert_eq!(boundary_loops(m), loops, "the {what}'s boundary loops");
    assert!(no_self_intersections(m));
    for p in &m.positions {
        assert!(
            p.length() > 0.9,
            "a vertex of the {what}'s end inside the body: {p}"
        );
    }
}

/// Figure 1: grab the top of a sphere and push it down through the
/// bottom; the poke-through opens a tunnel.
#[test]
fn figure_1_poke_through_makes_a_tunnel() {
    let mut s = Session::new(sphere(DVec3::ZERO)).unwrap();
    let g = stroke(
        Brush::Grab,
        0.7,
        1.0,
        &[[0., 0., 1.], [0., 0., 0.], [0., 0., -1.], [0., 0., -2.5]],
    );
    let r = s.apply_stroke(&g).unwrap();
    assert_eq!(r.engine_runs, 1, "a drag changes topology once, at release");
    assert_eq!(r.changes, 1);
    assert!(r.corrected_odd_vertices > 0);
    let m = s.mesh();
    assert!(closed(m), "the result is closed");
    assert_eq!(components(m), 1);
    assert_eq!(genus(m), 1, "a tunnel");
    assert!(no_self_intersections(m));
    assert!(s.diagnostics().corrected_odd.iter().any(|&o| o));
}

/// The snake hook pulls a tentacle out of a sphere's side, arcs it up
/// and over, and presses its tip into the top: the tip fuses with the
/// body, which makes a handle (genus 1), still one closed piece,
/// crossing nothing. The hook lets go at the fuse.
#[test]
fn snake_hook_tip_pressed_into_the_body_makes_a_handle() {
    let mut s = Session::new(sphere(DVec3::ZERO)).unwrap();
    // Out along +x, a quarter-circle arc up over the top, then down.
    let mut path = vec![DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.4, 0.0, 0.0)];
    let centre = DVec3::new(0.3, 0.0, 0.35);
    let start = DVec3::new(1.4, 0.0, 0.0) - centre;
    let (radius, a0) = (start.length(), start.z.atan2(start.x));
    for i in 1..=24 {
        let a = a0 + (std::f64::consts::FRAC_PI_2 - a0) * f64::from(i) / 24.0;
        path.push(centre + radius * DVec3::new(a.cos(), 0.0, a.sin()));
    }
    let top = *path.last().unwrap();
    for i in 1..=8 {
        let t = f64::from(i) / 8.0;
        path.push(DVec3::new(
            top.x * (1.0 - t),
            0.0,
            top.z + (0.5 - top.z) * t,
        ));
    }
    let hook = Stroke {
        brush: Brush::SnakeHook,
        radius: 0.5,
        strength: 1.0,
        path,
        ..Stroke::default()
    };
    let r = s.apply_stroke(&hook).unwrap();
    let m = s.mesh();
    assert!(r.changes >= 1, "the tip met the body");
    assert!(r.subframes > 0, "long pulls are cut into short steps");
    assert!(valid(m));
    assert!(closed(m), "the result is closed");
    assert_eq!(components(m), 1);
    assert_eq!(genus(m), 1, "a handle");
    assert!(no_self_intersections(m));
    // The tentacle reached out: some of the surface is still far outside
    // the unit sphere.
    assert!(m.positions.iter().any(|p| p.length() > 1.3));
}

/// §4: move one sphere into the other; they merge into one solid.
#[test]
fn union_by_move() {
    let two = join(&sphere(DVec3::ZERO), &sphere(DVec3::new(3.0, 0.0, 0.0)));
    let mut s = Session::new(two).unwrap();
    // The pick is just off the second sphere's surface, the drag 2 units.
    let mv = move_piece(&[[4.05, 0., 0.], [3.5, 0.1, 0.], [2.05, 0.1, 0.05]]);
    let r = s.apply_stroke(&mv).unwrap();
    assert_eq!(r.engine_runs, 1);
    let m = s.mesh();
    assert!(closed(m));
    assert_eq!(components(m), 1);
    assert_eq!(genus(m), 0);
    assert!(no_self_intersections(m));
}

/// §4: dragging back to where the drag began cancels the change, even
/// after poking through.
#[test]
fn cancelled_drag_changes_nothing() {
    let start = sphere(DVec3::ZERO);
    let mut s = Session::new(start.clone()).unwrap();
    s.set_preview(true);
    let mut previewed_odd = false;
    let g = stroke(
        Brush::Grab,
        0.7,
        1.0,
        &[
            [0., 0., 1.],
            [0., 0., -1.],
            [0., 0., -2.5],
            [0., 0., -0.5],
            [0., 0., 1.],
        ],
    );
    let r = s
        .apply_stroke_observed(&g, &mut |f| {
            if let Some(odd) = f.corrected_odd {
                assert_eq!(odd.len(), f.mesh.positions.len());
                previewed_odd |= odd.iter().any(|&o| o);
            }
            Ok(())
        })
        .unwrap();
    assert!(
        previewed_odd,
        "the preview showed the poke-through mid-drag"
    );
    assert_eq!(r.changes, 0);
    assert!(s.diagnostics().raw_odd.iter().all(|&o| !o));
    assert_eq!(s.mesh().triangles.len(), start.triangles.len());
    assert!(closed(s.mesh()));
    assert_eq!(genus(s.mesh()), 0);
    assert_eq!(s.mesh(), &start, "back at the start, bit for bit");
}

#[test]
fn undo_and_redo_restore_exact_meshes() {
    let start = sphere(DVec3::ZERO);
    let mut s = Session::new(start.clone()).unwrap();
    s.apply_stroke(&stroke(
        Brush::Inflate,
        0.5,
        0.05,
        &[[0., 0., 1.], [0.1, 0., 1.]],
    ))
    .unwrap();
    let inflated = s.mesh().clone();
    assert_ne!(inflated, start);
    s.apply_stroke(&stroke(Brush::Smooth, 0.5, 0.5, &[[0., 0., 1.]]))
        .unwrap();
    let smoothed = s.mesh().clone();
    assert_ne!(smoothed, inflated);
    assert!(s.undo());
    assert_eq!(s.mesh(), &inflated);
    assert!(s.undo());
    assert_eq!(s.mesh(), &start);
    assert!(!s.undo());
    assert!(s.redo());
    assert_eq!(s.mesh(), &inflated);
    assert!(s.redo());
    assert_eq!(s.mesh(), &smoothed);
    assert!(!s.redo());
    // A new stroke after an undo drops the redo branch.
    assert!(s.undo());
    s.apply_stroke(&stroke(Brush::Inflate, 0.5, -0.05, &[[1., 0., 0.]]))
        .unwrap();
    assert!(!s.can_redo());
}

/// Inflate with no collisions: topology is untouched and the surface
/// stays closed; the same strokes give the same mesh (determinism).
#[test]
fn inflate_without_collision_is_deterministic() {
    let run = || {
        let mut s = Session::new(sphere(DVec3::ZERO)).unwrap();
        let r = s
            .apply_stroke(&stroke(
                Brush::Inflate,
                0.6,
                0.1,
                &[[0., 0., 1.], [0.2, 0., 1.], [0.4, 0., 0.9]],
            ))
            .unwrap();
        assert_eq!(r.engine_runs, 3);
        assert_eq!(r.changes, 0);
        s.into_mesh()
    };
    let a = run();
    assert!(closed(&a));
    assert_eq!(genus(&a), 0);
    assert_eq!(a, run());
}

#[test]
fn bad_stroke_files_name_the_stroke() {
    let e = parse_strokes(
        r#"{"strokes": [{"brush": "move", "path": [[0,0,0]]}, {"brush": "twist", "path": [[0,0,0]]}]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("stroke 1:"), "{e}");
    let e = parse_strokes(
        r#"{"strokes": [{"brush": "smooth", "radius": 1, "strength": 0.5, "path": []}]}"#,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("stroke 0:"), "{e}");

    // A pick far from the surface fails at replay, naming the stroke, and
    // the session is left as it was.
    let start = sphere(DVec3::ZERO);
    let mut s = Session::new(start.clone()).unwrap();
    let file = parse_strokes(
        r#"{"remesh": {"min_edge": 0.05, "max_edge": 0.2}, "strokes": [
            {"brush": "inflate", "radius": 0.3, "strength": 0.02, "path": [[0,0,1]]},
            {"brush": "grab", "radius": 0.3, "path": [[0,0,3], [0,0,2]]}
        ]}"#,
    )
    .unwrap();
    let e = s.replay(&file, &mut |_, _| Ok(())).unwrap_err();
    assert!(
        matches!(&e, SculptError::Stroke { index: 1, brush: Brush::Grab, source }
            if matches!(**source, SculptError::PickTooFar { .. })),
        "{e}"
    );
    assert!(e.to_string().starts_with("stroke 1 (grab):"), "{e}");
    assert_eq!(s.mesh(), &start);
    assert!(!s.can_undo());
    assert_eq!(
        s.remesh(),
        holey_sculpt::default_range(&start),
        "the file's range was not kept"
    );

    let far_move =
        parse_strokes(r#"{"strokes": [{"brush": "move", "path": [[0,0,1.5], [0,0,2]]}]}"#).unwrap();
    let e = s.replay(&far_move, &mut |_, _| Ok(())).unwrap_err();
    assert!(e.to_string().contains("10%"), "{e}");
}

/// §6, pinch closing: inflate the inner ring of a torus with a small hole
/// until it collides with itself. The colliding walls delete each other,
/// the hole closes, and the result is a closed surface of genus 0.
///
/// The hole (radius 1 − 0.8 = 0.2) is squashed to 0.12 across y, so that
/// the walls across y meet first, two at a time, as a pinch does, rather
/// than the whole ring meeting at the axis in one frame. Dynamic
/// remeshing keeps the inner walls sampled finely enough for
/// vertex–triangle collisions to see them meet (with the coarse starting
/// mesh and no remeshing the walls first cross edge against edge, the
/// paper's blind spot, and the correction then leaves a hole).
#[test]
fn pinch_closing_fills_the_hole_of_a_torus() {
    let torus = from_poly(holey_shapes::torus(32, 16, 1.0, 0.8).unwrap());
    let torus = TriMesh {
        positions: torus
            .positions
            .iter()
            .map(|p| DVec3::new(p.x, 0.6 * p.y, p.z))
            .collect(),
        ..torus
    };
    assert_eq!(genus(&torus), 1);
    let mut s = Session::new(torus).unwrap();
    s.set_remesh(Some(Remesh {
        min_edge: 0.04,
        max_edge: 0.14,
    }));
    let centre = [0.011, 0.004, 0.003];
    let mut changes = 0;
    for frame in 0..30 {
        let r = s
            .apply_stroke(&stroke(Brush::Inflate, 0.45, 0.01, &[centre]))
            .unwrap();
        changes += r.changes;
        let m = s.mesh();
        assert!(valid(m) && closed(m), "frame {frame}: a closed, valid mesh");
        if genus(m) == 0 {
            break;
        }
    }
    assert!(changes > 0, "the inner ring collided with itself");
    let m = s.mesh();
    assert!(closed(m));
    assert_eq!(components(m), 1);
    assert_eq!(genus(m), 0, "the hole closed");
    assert!(no_self_intersections(m));
}

/// An open hemisphere of radius `r` whose dome points along +x, rim in
/// the plane x = 0, moved to `offset`.
fn hemisphere(r: f64, offset: DVec3) -> TriMesh {
    let s = from_poly(holey_shapes::uv_sphere(24, 12).unwrap());
    let cut = TriMesh {
        triangles: s
            .triangles
            .iter()
            .copied()
            .filter(|t| t.iter().all(|&v| s.positions[v as usize].x >= 0.0))
            .collect(),
        ..s
    }
    .compacted();
    transformed(&cut, r, offset)
}

/// The part-assembly move: pick the tip of the nose (the hemisphere of
/// radius 0.3 at x = 2, see the tests below), then push it in by 1.2: the
/// rim ends at x = 0.8 (inside the unit body), the tip at 1.1 (outside).
fn push_the_nose_in() -> Stroke {
    move_piece(&[
        [2.3, 0., 0.],
        [1.9, 0.004, 0.002],
        [1.5, 0.008, 0.004],
        [1.1, 0.013, 0.007],
    ])
}

/// §6, part assembly (Figure 9): move an open part (a nose: an open
/// hemisphere, rim first) into a closed body. The part's rim and the
/// portion inside the body cross the body once and are deleted, and the
/// rest is glued to the body along the intersection curve: one component,
/// no boundary left. As §7 warns, parity keeps the body's surface inside
/// the nose: the nose's open side led the way, so its surface never swept
/// over that cap, which stays as an occluded surface the user does not
/// see, meeting body and nose along edges of three triangles. That is
/// non-manifold, so it needs [`Options::nonmanifold_joins`]; by default
/// see `part_assembly_by_default_leaves_no_occluded_cap`.
#[test]
fn part_assembly_glues_an_open_part_onto_a_body() {
    let nose = hemisphere(0.3, DVec3::new(2.0, 0.0, 0.0));
    assert_eq!(boundary_loops(&nose), 1);
    let m = join(&sphere(DVec3::ZERO), &nose);
    let options = Options {
        nonmanifold_joins: true,
        solid_guard: false,
        ..Options::default()
    };
    let mut s = Session::with_options(m, options).unwrap();
    // The rim was inside and is gone.
    assert_part_attached(&mut s, &push_the_nose_in(), 0, "nose");
    let m = s.mesh();
    // The occluded cap: the body's pole, inside the nose, is still there,
    // and the glue curve is a T-junction (edges of three triangles).
    assert!(
        m.positions
            .iter()
            .any(|p| p.distance(DVec3::new(1.0, 0.0, 0.0)) < 0.05)
    );
    let degrees = edges(m);
    assert!(degrees.values().all(|&c| c == 2 || c == 3));
    assert!(degrees.values().any(|&c| c == 3));
}

/// Part assembly with an open tube pushed into a body by one end: the
/// end inside the body is deleted, the tube is glued on, and its outer
/// end stays open.
#[test]
fn part_assembly_with_an_open_tube_keeps_its_outer_end() {
    let cyl = from_poly(holey_shapes::cylinder(24, 6).unwrap());
    // The side only (no caps), radius 0.25, axis along x from 1.5 to 2.5.
    let side = TriMesh {
        positions: cyl
            .positions
            .iter()
            .map(|p| DVec3::new(2.0 + 0.5 * p.z, 0.25 * p.x, 0.25 * p.y))
            .collect(),
        triangles: cyl
            .triangles
            .iter()
            .copied()
            .filter(|t| {
                let n = (cyl.positions[t[1] as usize] - cyl.positions[t[0] as usize])
                    .cross(cyl.positions[t[2] as usize] - cyl.positions[t[0] as usize]);
                n.z.abs() < 1e-9
            })
            .collect(),
    }
    .compacted();
    assert_eq!(boundary_loops(&side), 2);
    let m = join(&sphere(DVec3::ZERO), &side);
    let mut s = Session::new(m).unwrap();
    let mv = move_piece(&[[2.5, 0.25, 0.], [2.0, 0.254, 0.002], [1.7, 0.259, 0.005]]);
    // The outer end stays open.
    assert_part_attached(&mut s, &mv, 1, "tube");
}

/// Part assembly with the default options: where the body is a solid the
/// move is resolved by containment number, so the body's cap inside the
/// nose goes too (it lies inside the union) and the join is a 2-manifold:
/// one closed component, every edge on two triangles, no vertex of the
/// body's cap or the nose's rim left inside.
#[test]
fn part_assembly_by_default_leaves_no_occluded_cap() {
    let nose = hemisphere(0.3, DVec3::new(2.0, 0.0, 0.0));
    let m = join(&sphere(DVec3::ZERO), &nose);
    let mut s = Session::new(m).unwrap();
    let r = s.apply_stroke(&push_the_nose_in()).unwrap();
    assert!(r.refused.is_empty(), "{:?}", r.refused);
    let m = s.mesh();
    assert!(valid(m));
    assert_eq!(components(m), 1, "the part is attached");
    assert!(closed(m), "a 2-manifold without boundary");
    assert!(no_self_intersections(m));
    for p in &m.positions {
        assert!(
            p.length() > 0.99 || p.x > 0.99,
            "a vertex inside the union: {p}"
        );
    }
    assert!(
        !m.positions
            .iter()
            .any(|p| p.distance(DVec3::new(1.0, 0.0, 0.0)) < 0.05),
        "the body's cap inside the nose is gone"
    );
}

/// §6, paper mâché (Figure 11): grab a sheet by its edge and drag the
/// edge into another surface. The part of the sheet that went through
/// is deleted and the sheet is glued to the surface: they connect, along
/// a curve of edges with three triangles (the sheet meets the ball from
/// one side), which needs [`Options::nonmanifold_joins`]: by default the
/// guard undoes such a drag.
#[test]
fn paper_mache_connects_a_sheet_to_another_surface() {
    let sheet = from_poly(holey_shapes::tri_plane(16, 16).unwrap());
    let sheet = transformed(&sheet, 0.5, DVec3::ZERO);
    let ball = transformed(&sphere(DVec3::ZERO), 0.6, DVec3::new(1.6, 0.0, 0.0));
    let m = join(&sheet, &ball);
    assert_eq!(components(&m), 2);
    let options = Options {
        nonmanifold_joins: true,
        ..Options::default()
    };
    let mut s = Session::with_options(m.clone(), options).unwrap();
    // Grab the middle of the sheet's right edge (x = 0.5) and pull it
    // 0.8 to the right and a little up, into the ball (x from 1 to 2.2).
    let g = stroke(
        Brush::Grab,
        0.5,
        1.0,
        &[
            [0.5, 0.0, 0.0],
            [0.8, 0.003, 0.01],
            [1.1, 0.006, 0.02],
            [1.3, 0.009, 0.03],
        ],
    );
    let r = s.apply_stroke(&g).unwrap();
    assert_eq!(r.changes, 1);
    let m = s.mesh();
    assert!(valid(m));
    assert_eq!(components(m), 1, "the sheet and the ball connect");
    assert!(no_self_intersections(m));
    // The grabbed edge went inside the ball and is gone.
    let centre = DVec3::new(1.6, 0.0, 0.0);
    assert!(
        m.positions.iter().all(|p| p.distance(centre) > 0.5),
        "nothing of the sheet is left deep inside the ball"
    );
}

/// Euler characteristic over distinct triangles and used vertices.
fn euler(m: &TriMesh) -> i64 {
    let v = m.triangles.iter().flatten().collect::<HashSet<_>>().len() as i64;
    let f = m
        .triangles
        .iter()
        .map(|t| {
            let mut k = *t;
            k.sort_unstable();
            k
        })
        .collect::<HashSet<_>>()
        .len() as i64;
    v - edges(m).len() as i64 + f
}

/// A random small mesh: spheres, tori, open grids, two close spheres, or
/// a soup of random triangles (then `true`).
fn random_mesh(rng: &mut holey_testkit::Rng) -> (TriMesh, bool) {
    let kind = rng.below(5);
    let m = match kind {
        0 => transformed(
            &from_poly(holey_shapes::icosphere(1 + rng.below(2) as u32).unwrap()),
            rng.range(0.5, 1.5),
            DVec3::ZERO,
        ),
        1 => from_poly(
            holey_shapes::torus(
                8 + rng.below(8) as u32,
                4 + rng.below(6) as u32,
                1.0,
                rng.range(0.2, 0.7),
            )
            .unwrap(),
        ),
        2 => from_poly(
            holey_shapes::tri_plane(3 + rng.below(6) as u32, 3 + rng.below(6) as u32).unwrap(),
        ),
        3 => {
            let a = from_poly(holey_shapes::icosphere(1).unwrap());
            let b = transformed(
                &a,
                1.0,
                DVec3::new(rng.range(1.6, 2.4), rng.range(-0.3, 0.3), 0.0),
            );
            join(&a, &b)
        }
        _ => {
            let n = 4 + rng.below(12);
            let positions: Vec<DVec3> = (0..3 * n)
                .map(|_| {
                    DVec3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                    )
                })
                .collect();
            let triangles = (0..n as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            TriMesh {
                positions,
                triangles,
            }
        }
    };
    (m, kind == 4)
}

fn random_point_near(rng: &mut holey_testkit::Rng, m: &TriMesh) -> DVec3 {
    if m.positions.is_empty() {
        return DVec3::ZERO;
    }
    let p = *rng.pick(&m.positions);
    p + DVec3::new(
        rng.range(-0.05, 0.05),
        rng.range(-0.05, 0.05),
        rng.range(-0.05, 0.05),
    )
}

fn mean_edge(m: &TriMesh) -> f64 {
    let e = edges(m);
    let total: f64 = e
        .keys()
        .map(|&(a, b)| m.positions[a as usize].distance(m.positions[b as usize]))
        .sum();
    total / e.len().max(1) as f64
}

#[derive(Default)]
struct FuzzTally {
    applied: usize,
    changes: usize,
    remeshed: usize,
}

/// Four random strokes on a random small mesh, each followed by a
/// remeshing around it: no panics, every mesh valid, a refused stroke
/// leaves the session unchanged, remeshing keeps the Euler characteristic
/// and the components.
fn fuzz_seed(seed: u64, remesh_soups: bool, tally: &mut FuzzTally) {
    let mut rng = holey_testkit::Rng::new(seed);
    let (mesh, soup) = random_mesh(&mut rng);
    let mut s = Session::new(mesh).unwrap();
    for _ in 0..4 {
        let m = s.mesh().clone();
        let brush = *rng.pick(&holey_sculpt::brush::ALL_BRUSHES);
        let start = random_point_near(&mut rng, &m);
        let frames = 1 + rng.below(3);
        let mut path = vec![start];
        for k in 1..frames {
            let drift = if brush.is_drag() || brush == Brush::SnakeHook {
                0.4
            } else {
                0.1
            };
            let step = DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            path.push(path[k - 1] + drift * step);
        }
        let st = Stroke {
            brush,
            radius: rng.range(0.2, 0.8),
            strength: match brush {
                Brush::Inflate | Brush::Draw | Brush::Clay | Brush::Crease | Brush::Layer => {
                    rng.range(-0.05, 0.05)
                }
                Brush::Smooth | Brush::Flatten | Brush::Scrape => rng.unit(),
                Brush::Pinch => rng.range(-1.0, 1.0),
                Brush::Scale => rng.range(-0.3, 0.3),
                _ => 1.0,
            },
            path,
            ..Stroke::default()
        };
        match s.apply_stroke(&st) {
            Ok(r) => {
                assert!(valid(s.mesh()), "seed {seed}: {st:?}");
                tally.applied += 1;
                tally.changes += r.changes;
            }
            Err(_) => assert_eq!(
                s.mesh(),
                &m,
                "seed {seed}: a refused stroke changed the mesh"
            ),
        }
        // Remesh around the stroke, as the session will between frames.
        let m = s.mesh().clone();
        let h = mean_edge(&m);
        if (soup && !remesh_soups) || h.is_nan() || h <= 0.0 {
            continue;
        }
        let lo = h * rng.range(0.3, 0.8);
        let opts = RemeshOptions::new(Remesh {
            min_edge: lo,
            max_edge: lo * rng.range(2.0, 3.5),
        });
        let reach = rng.range(0.2, 1.5);
        let active: Vec<bool> = m
            .positions
            .iter()
            .map(|p| p.distance(start) < reach)
            .collect();
        let (out, r) = remesh_with(&m, &active, &opts).unwrap();
        tally.remeshed += r.splits + r.collapses + r.flips;
        assert!(valid(&out), "seed {seed}");
        assert_eq!(euler(&out), euler(&m), "seed {seed}: remeshing changed χ");
        assert_eq!(components(&out), components(&m), "seed {seed}");
        s = Session::new(out).unwrap();
    }
}

/// The fuzz loop over 300 seeds (every brush among the picks). Soups are not remeshed here: remeshing
/// a heavily self-intersecting soup makes many nearly coplanar pieces, on
/// which the engine's static intersections can be very slow (see
/// `fuzz_remeshed_soups`).
#[test]
fn fuzz_strokes_and_remeshing() {
    let started = std::time::Instant::now();
    let mut tally = FuzzTally::default();
    for seed in 0..300u64 {
        fuzz_seed(seed, false, &mut tally);
    }
    let seconds = started.elapsed().as_secs_f64();
    eprintln!(
        "fuzz: {} strokes applied, {} topology changes, {} remeshing operations, {seconds:.1} s",
        tally.applied, tally.changes, tally.remeshed
    );
    // Most random strokes collide with nothing; the loop must still reach
    // some topology changes (9 with these seeds).
    assert!(tally.applied > 600 && tally.changes >= 5 && tally.remeshed > 2000);
}

/// Seeds the fuzz loop once found to run for minutes inside the engine's
/// exact predicates and constructions, not in remeshing:
/// - 76 with its soup remeshed: a move that only clicks starts a drag
///   accumulator on 246 self-intersecting pieces of 15 random triangles;
/// - 158: a torus sculpted and remeshed to 3,892 triangles, then a smooth
///   stroke.
///
/// With the local engine and the double-double constructions both run in
/// about 20 s; they stay here so that they keep passing validation.
#[test]
fn fuzz_slow_seeds() {
    let mut tally = FuzzTally::default();
    fuzz_seed(76, true, &mut tally);
    fuzz_seed(158, false, &mut tally);
}

/// §4's dynamic remeshing inside a session: inflating a bump with a
/// given range keeps every edge the brush reached within it (splits bring
/// stretched edges under `max_edge`; collapses may leave a few short
/// edges where the angle bounds forbid them), inverts no triangle, and
/// changes no topology; the triangles the brush never reached are the
/// same as before.
#[test]
fn remeshing_keeps_edges_in_range_during_strokes() {
    let start = sphere(DVec3::ZERO);
    let mut s = Session::new(start.clone()).unwrap();
    let range = holey_sculpt::Remesh {
        min_edge: 0.04,
        max_edge: 0.12,
    };
    s.set_remesh(Some(range));
    let centre = [0.0, 0.0, 1.0];
    let r = s
        .apply_stroke(&stroke(Brush::Inflate, 0.5, 0.03, &[centre; 12]))
        .unwrap();
    assert!(r.remesh_operations > 0, "the bump was remeshed");
    let m = s.mesh();
    assert!(valid(m) && closed(m));
    assert_eq!(genus(m), 0);
    assert_eq!(components(m), 1);
    assert!(no_self_intersections(m));
    let c = DVec3::from_array(centre);
    let (mut near, mut long, mut short) = (0, 0, 0);
    for t in &m.triangles {
        let [a, b, cc] = t.map(|v| m.positions[v as usize]);
        // The bump stays star-shaped about the origin: no triangle turns
        // its back to it.
        assert!(
            (b - a).cross(cc - a).dot(a + b + cc) > 0.0,
            "inverted triangle"
        );
        if [a, b, cc].iter().all(|p| p.distance(c) < 0.4) {
            for (p, q) in [(a, b), (b, cc), (cc, a)] {
                near += 1;
                let l = p.distance(q);
                long += usize::from(l > range.max_edge * 1.0001);
                short += usize::from(l < range.min_edge);
            }
        }
    }
    assert!(near > 100, "{near} edges near the brush");
    assert_eq!(long, 0, "edges longer than max_edge near the brush");
    assert!(
        short * 20 < near,
        "{short} of {near} edges shorter than min_edge"
    );
    // Far from the brush nothing moved.
    let far: Vec<[u32; 3]> = start
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&v| start.positions[v as usize].z < -0.2))
        .copied()
        .collect();
    let key =
        |m: &TriMesh, t: &[u32; 3]| t.map(|v| m.positions[v as usize].to_array().map(f64::to_bits));
    let now: std::collections::HashSet<_> = m.triangles.iter().map(|t| key(m, t)).collect();
    assert!(far.iter().all(|t| now.contains(&key(&start, t))));
}

/// The session needs no seed: nothing in it is random (exact predicates
/// with simulation of simplicity, brushes and remeshing in a fixed
/// order), so replaying the same strokes on the same mesh gives the same
/// mesh bit for bit, topology changes and remeshing included.
#[test]
fn replays_are_bit_identical_with_topology_change_and_remeshing() {
    let run = || {
        let mut s = Session::new(sphere(DVec3::ZERO)).unwrap();
        let strokes = [
            stroke(Brush::Inflate, 0.4, 0.03, &[[1., 0., 0.]; 4]),
            stroke(Brush::Smooth, 0.4, 0.5, &[[1.1, 0., 0.]]),
            stroke(
                Brush::Grab,
                0.7,
                1.0,
                &[[0., 0., 1.], [0., 0., 0.], [0., 0., -1.], [0., 0., -2.5]],
            ),
        ];
        for st in &strokes {
            s.apply_stroke(st).unwrap();
        }
        s.into_mesh()
    };
    let (a, b) = (run(), run());
    assert!(genus(&a) >= 1, "the grab changed topology");
    assert_eq!(a.triangles, b.triangles);
    let bits = |m: &TriMesh| -> Vec<[u64; 3]> {
        m.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
}

/// A strong inflate circling on a sphere, one frame per stroke (strength
/// 0.1 at radius 0.28: each frame lifts the bump by a third of the radius
/// while its neighbours tilt). Before step control the surface folded
/// over itself by the fourth frame and a frame was refused as too
/// crumpled by the seventh; now every frame is cut into sub-steps that
/// move no vertex farther than the edges around it are long, each with
/// its normals evaluated again, and all ten frames leave a solid: closed,
/// one piece, genus 0, no self-intersection.
#[test]
fn strong_circling_inflate_keeps_the_solid() {
    let p = holey_shapes::parse_primitive("@sphere:6").unwrap();
    let mut s = Session::new(from_poly(p)).unwrap();
    let mut subframes = 0;
    for t in 0..10 {
        let a = f64::from(t) / 3.0;
        let centre = [0.2 * a.cos(), 0.2 * a.sin(), 1.0];
        let r = s
            .apply_stroke(&stroke(Brush::Inflate, 0.28, 0.1, &[centre]))
            .unwrap();
        subframes += r.subframes;
        let m = s.mesh();
        assert!(closed(m), "frame {t}: not closed");
        assert_eq!(components(m), 1, "frame {t}");
        assert_eq!(genus(m), 0, "frame {t}");
        assert!(no_self_intersections(m), "frame {t}: self-intersecting");
    }
    assert!(subframes >= 10, "the frames were split: {subframes}");
}

/// The local move: with a radius, move drags the part of the picked
/// piece within it, every vertex by `move_falloff(d) × offset` (the whole
/// offset inside half the radius, blending to nothing at the rim) and
/// the rest not at all; without one it drags the whole piece.
#[test]
fn local_move_drags_the_part_within_its_radius() {
    let start = sphere(DVec3::ZERO);
    let mut s = Session::new(start.clone()).unwrap();
    s.set_remeshing(false);
    // The drag's offset as the stroke computes it: last point − first.
    let offset = DVec3::new(0.0, 0.0, 1.1) - DVec3::new(0.0, 0.0, 1.0);
    let mv = stroke(
        Brush::Move,
        0.6,
        1.0,
        &[[0., 0., 1.], [0., 0., 1.05], [0., 0., 1.1]],
    );
    let r = s.apply_stroke(&mv).unwrap();
    assert!(r.refused.is_empty());
    let m = s.mesh();
    assert_eq!(m.triangles, start.triangles, "nothing collided");
    let picked = DVec3::new(0.0, 0.0, 1.0);
    let mut rigid = 0;
    for (p0, p1) in start.positions.iter().zip(&m.positions) {
        let d = p0.distance(picked);
        let want = *p0 + offset * holey_sculpt::live::move_falloff(d, 0.6);
        assert!((*p1 - want).length() < 1e-12, "{p0}: {p1} vs {want}");
        if d < 0.3 {
            assert_eq!(*p1, *p0 + offset, "held rigidly");
            rigid += 1;
        }
        if d >= 0.6 {
            assert_eq!(p1, p0);
        }
    }
    assert!(rigid > 3, "some vertices inside half the radius");
    // Radius 0: the whole piece.
    let whole = move_piece(&[[0., 0., 1.], [0., 0., 1.1]]);
    let mut s = Session::new(start.clone()).unwrap();
    s.apply_stroke(&whole).unwrap();
    for (p0, p1) in start.positions.iter().zip(&s.mesh().positions) {
        assert!((*p1 - *p0 - offset).length() < 1e-12);
    }
}

/// Several dabs painted as one frame (`LiveStroke::frame_together`, what
/// the modeler sends when the pointer moved on during a frame): the brush
/// is applied at each dab on the positions the one before it left, so
/// when nothing collides the surface ends exactly where the brush alone,
/// applied dab after dab, takes it (computed here with
/// `holey_sculpt::brush::inflate`), in one frame and with the same
/// triangles.
#[test]
fn dabs_painted_together_move_the_surface_as_the_brush_dab_after_dab() {
    use holey_sculpt::{BrushSettings, LiveStroke, brush::inflate};
    let mesh = sphere(DVec3::ZERO);
    let (radius, strength) = (0.5, 0.01);
    let dabs = [
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(0.1, 0.0, 0.99),
        DVec3::new(0.2, 0.05, 0.97),
    ];
    let mut expected = mesh.clone();
    for &c in &dabs {
        expected.positions = inflate(&expected, c, radius, strength);
    }
    assert_ne!(
        expected.positions, mesh.positions,
        "the dabs move the surface"
    );
    let settings = BrushSettings::new(Brush::Inflate, radius, strength);
    let mut live = LiveStroke::begin(&mesh, settings, dabs[0], Options::default()).unwrap();
    let together: Vec<(DVec3, f64)> = dabs.iter().map(|&c| (c, 1.0)).collect();
    let frame = live.frame_together(&together).unwrap();
    assert!(!frame.connectivity_changed && !frame.topology_changed);
    assert_eq!(frame.mesh.triangles, mesh.triangles);
    assert_eq!(frame.mesh.positions, expected.positions);
    assert_eq!(live.frames(), 1);
}

/// A dab whose step is longer than one frame may (a vertex farther than
/// the edges around the moving vertices are long) is evaluated in the
/// sub-steps its own frame would take, within the frame of several dabs:
/// without remeshing or collisions, the frame ends exactly where the same
/// dabs sent one a frame end (each split into sub-frames there).
#[test]
fn long_dabs_painted_together_take_the_steps_their_own_frames_would() {
    use holey_sculpt::{BrushSettings, LiveStroke};
    let mesh = sphere(DVec3::ZERO);
    // Each dab moves the top about 1.4 edges' mean length (the sphere's
    // edges are all about as long): sub-frames.
    let lengths: Vec<f64> = mesh
        .triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| mesh.positions[a as usize].distance(mesh.positions[b as usize]))
        .collect();
    let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
    let (radius, strength) = (0.6, 1.4 * mean);
    let dabs = [
        (DVec3::new(0.0, 0.0, 1.0), 1.0),
        (DVec3::new(0.02, 0.0, 1.0), 1.0),
        (DVec3::new(0.04, 0.0, 1.0), 1.0),
    ];
    let settings = BrushSettings::new(Brush::Inflate, radius, strength);
    let mut together = LiveStroke::begin(&mesh, settings, dabs[0].0, Options::default()).unwrap();
    together.frame_together(&dabs).unwrap();
    let mut apart = LiveStroke::begin(&mesh, settings, dabs[0].0, Options::default()).unwrap();
    for &(c, p) in &dabs {
        apart.frame_pressed(c, p).unwrap();
    }
    assert_eq!(together.mesh(), apart.mesh());
    assert_eq!((together.frames(), apart.frames()), (1, 3));
    let split = apart.finish().unwrap().report.subframes;
    assert!(split > 0, "no dab needed sub-frames of its own");
}

/// A frame of several dabs computes its brush steps on the piece of the
/// surface they can read; on an open surface with an unwelded seam (the
/// upper half of a sphere, its two sides with their own copies of the
/// seam's vertices) and dabs on the rim, where the brushes read the rim's
/// two-ring and take coincident copies for one point, the frame still ends
/// exactly where inflate and smooth applied to the whole mesh, dab after
/// dab, take it. Two sets of dabs: a wide brush where the seam meets the
/// rim, and a brush moving only a rim vertex beside the seam, whose rim
/// normal reads the triangles at its seam neighbour's position on the
/// other side, which share no vertex number with anything it moves.
#[test]
fn dabs_painted_together_at_a_rim_and_a_seam_read_what_the_whole_mesh_gives() {
    let sphere = sphere(DVec3::ZERO);
    let upper: Vec<[u32; 3]> = sphere
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&v| sphere.positions[v as usize].z > -1e-9))
        .collect();
    // The side x < 0 gets its own copy of every vertex it uses.
    let mut mesh = TriMesh {
        positions: sphere.positions.clone(),
        triangles: Vec::new(),
    };
    let mut copy = HashMap::new();
    for t in &upper {
        let west = t
            .iter()
            .map(|&v| sphere.positions[v as usize].x)
            .sum::<f64>()
            < 0.0;
        mesh.triangles.push(if west {
            t.map(|v| {
                *copy.entry(v).or_insert_with(|| {
                    mesh.positions.push(sphere.positions[v as usize]);
                    (mesh.positions.len() - 1) as u32
                })
            })
        } else {
            *t
        });
    }
    // Sides by position, and a rim vertex east of the seam (x = 0) with a
    // neighbour on it.
    let key = |p: DVec3| p.to_array().map(f64::to_bits);
    let mut sides: HashMap<([u64; 3], [u64; 3]), usize> = HashMap::new();
    for t in &mesh.triangles {
        for k in 0..3 {
            let a = key(mesh.positions[t[k] as usize]);
            let b = key(mesh.positions[t[(k + 1) % 3] as usize]);
            *sides.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let point = |k: [u64; 3]| DVec3::from_array(k.map(f64::from_bits));
    let beside_the_seam = sides
        .iter()
        .filter(|(_, n)| **n == 1)
        .flat_map(|((a, b), _)| [(*a, *b), (*b, *a)])
        .find(|&(v, q)| point(v).x > 1e-9 && point(q).x.abs() < 1e-9)
        .map(|(v, _)| point(v))
        .expect("a rim vertex beside the seam");
    let wide = vec![
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.05, 0.99, 0.05),
        DVec3::new(-0.05, 0.99, 0.1),
    ];
    for (radius, dabs) in [(0.4, wide), (1e-3, vec![beside_the_seam; 3])] {
        brushes_together_as_on_the_whole_mesh(&mesh, radius, &dabs);
    }
}

/// Inflate and smooth at `dabs` as one frame end where the brush applied
/// to the whole `mesh`, dab after dab, takes it.
fn brushes_together_as_on_the_whole_mesh(mesh: &TriMesh, radius: f64, dabs: &[DVec3]) {
    use holey_sculpt::{BrushSettings, LiveStroke, brush};
    for (which, strength) in [(Brush::Inflate, 0.01), (Brush::Smooth, 0.5)] {
        let mut expected = mesh.clone();
        for &c in dabs {
            expected.positions = match which {
                Brush::Smooth => brush::smooth(&expected, c, radius, strength),
                _ => brush::inflate(&expected, c, radius, strength),
            };
        }
        assert_ne!(expected.positions, mesh.positions, "{which} moves it");
        let settings = BrushSettings::new(which, radius, strength);
        let mut live = LiveStroke::begin(mesh, settings, dabs[0], Options::default()).unwrap();
        let together: Vec<(DVec3, f64)> = dabs.iter().map(|&c| (c, 1.0)).collect();
        let frame = live.frame_together(&together).unwrap();
        assert!(!frame.topology_changed, "{which}");
        let differ = (frame.mesh.positions.iter())
            .zip(&expected.positions)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differ, 0,
            "{which} at radius {radius}: positions that differ"
        );
    }
}
