//! Scenario tests of issue 5 (Bernstein & Wojtan 2013, §4 and Figure 1),
//! on meshes generated in code, checked with helpers independent of the
//! crate: closedness, components and genus by the Euler characteristic.
#![allow(clippy::unwrap_used)]

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use holey_sculpt::{Brush, SculptError, Session, Stroke, parse_strokes};
use holey_topo::{TriMesh, self_intersections};

fn sphere(centre: DVec3) -> TriMesh {
    let p = holey_shapes::parse_primitive("@sphere:3").unwrap();
    let (triangles, _) = p.fan_triangles();
    TriMesh {
        positions: p.positions.iter().map(|q| *q + centre).collect(),
        triangles,
    }
}

fn join(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let mut m = a.clone();
    let n = m.positions.len() as u32;
    m.positions.extend_from_slice(&b.positions);
    m.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    m
}

/// Undirected edges with the number of triangles on each.
fn edges(m: &TriMesh) -> HashMap<(u32, u32), usize> {
    let mut e = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *e.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    e
}

/// Every edge has exactly two triangles.
fn closed(m: &TriMesh) -> bool {
    edges(m).values().all(|&c| c == 2)
}

fn components(m: &TriMesh) -> usize {
    let n = m.positions.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for t in &m.triangles {
        for &v in &t[1..] {
            let (a, b) = (
                find(&mut parent, t[0] as usize),
                find(&mut parent, v as usize),
            );
            parent[a] = b;
        }
    }
    let used: HashSet<usize> = m.triangles.iter().flatten().map(|&v| v as usize).collect();
    used.into_iter()
        .map(|v| find(&mut parent, v))
        .collect::<HashSet<_>>()
        .len()
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

fn no_self_intersections(m: &TriMesh) -> bool {
    self_intersections(m).unwrap().pieces.is_empty()
}

fn stroke(brush: Brush, radius: f64, strength: f64, path: &[[f64; 3]]) -> Stroke {
    Stroke {
        brush,
        radius,
        strength,
        path: path.iter().map(|&p| DVec3::from_array(p)).collect(),
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

/// §4: move one sphere into the other; they merge into one solid.
#[test]
fn union_by_move() {
    let two = join(&sphere(DVec3::ZERO), &sphere(DVec3::new(3.0, 0.0, 0.0)));
    let mut s = Session::new(two).unwrap();
    // The pick is just off the second sphere's surface, the drag 2 units.
    let mv = stroke(
        Brush::Move,
        0.0,
        1.0,
        &[[4.05, 0., 0.], [3.5, 0.1, 0.], [2.05, 0.1, 0.05]],
    );
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
    assert!(s.remesh().is_none());

    let far_move =
        parse_strokes(r#"{"strokes": [{"brush": "move", "path": [[0,0,1.5], [0,0,2]]}]}"#).unwrap();
    let e = s.replay(&far_move, &mut |_, _| Ok(())).unwrap_err();
    assert!(e.to_string().contains("10%"), "{e}");
}
