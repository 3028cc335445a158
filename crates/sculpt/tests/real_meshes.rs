//! Issue 15's scenarios on the real meshes of `../shared/data/meshes`
//! (read through `holey_testkit::shared_meshes`; every test prints a SKIP
//! line and passes vacuously when that folder is absent): strokes dragged
//! across scans, open surfaces, non-manifold models, self-intersecting
//! solids and a triangle soup, checked stroke by stroke against what a
//! stroke may change (issue 15, item 1):
//!
//! - a closed input stays closed, and no boundary loop appears;
//! - no non-manifold edge (in connected curves, so that remeshing's splits
//!   of an existing one do not count) and no pinched vertex appears;
//! - no degenerate (exactly zero-area) triangle appears;
//! - the exact count of intersecting triangle pairs never grows;
//! - where a scenario has a topology (a tunnel, a join), its genus and
//!   components;
//! - with remeshing, the triangles a stroke adds are bounded by the area
//!   it made over (√3/4)·min_edge² (item 2: the remesher never blows up).
//!
//! The oracle is written here, apart from the crate: edges and fans by
//! hash maps, components by a union-find, degeneracy by exact orientation
//! (holey-geom's predicates), intersections by the engine's exact static
//! intersection pass (`holey_topo::self_intersections`, which the sculpting
//! pipeline does not call).
#![allow(clippy::unwrap_used)]

use std::collections::{HashMap, HashSet};

use glam::{DVec2, DVec3};
use holey_geom::{Sign, orient2d};
use holey_sculpt::brush::closest_point;
use holey_sculpt::{Brush, Session, Stroke, StrokeReport};
use holey_testkit::{Groups, Rng, components, edge_degrees, pieces, shared_meshes_or_skip};
use holey_topo::{TriMesh, self_intersections};

/// A shared mesh's polygons as stored, or `None` (with a SKIP line) when
/// the shared folder is absent.
fn load_polygons(test: &str, file: &str) -> Option<holey_mesh::PolyMesh> {
    let dir = shared_meshes_or_skip(test)?;
    let holey_io::MeshFile::Poly(p) = holey_io::read_path(&dir.join(file)).unwrap() else {
        panic!("{file}: not a polygon mesh");
    };
    Some(p)
}

/// A shared mesh as triangles (polygons fan-triangulated), or `None`
/// (with a SKIP line) when the shared folder is absent.
fn load(test: &str, file: &str) -> Option<TriMesh> {
    Some(load_polygons(test, file)?.triangulated())
}

/// What the tests measure of a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Shape {
    triangles: usize,
    components: usize,
    boundary_loops: usize,
    nonmanifold_curves: usize,
    /// Edges of two triangles that run along them the same way: the
    /// surface's sides meet back to front there.
    misoriented: usize,
    pinched: usize,
    degenerate: usize,
    intersecting_pairs: usize,
    euler: i64,
}

fn measure(m: &TriMesh) -> Shape {
    let degree = edge_degrees(&m.triangles);
    let boundary: Vec<(u32, u32)> = degree
        .iter()
        .filter(|(_, c)| **c == 1)
        .map(|(e, _)| *e)
        .collect();
    let nonmanifold: Vec<(u32, u32)> = degree
        .iter()
        .filter(|(_, c)| **c > 2)
        .map(|(e, _)| *e)
        .collect();
    // Directed sides: an edge of two triangles is misoriented when both
    // run it from the same end.
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    let misoriented = degree
        .iter()
        .filter(|&(&(a, b), &c)| {
            let (ab, ba) = (directed.get(&(a, b)), directed.get(&(b, a)));
            c == 2 && a != b && (ab == Some(&2) || ba == Some(&2))
        })
        .count();
    let components = components(&m.triangles);
    let used: HashSet<u32> = m.triangles.iter().flatten().copied().collect();
    // Fans: the triangles at a vertex joined through edges at it.
    let mut at: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, t) in m.triangles.iter().enumerate() {
        for &v in t {
            at.entry(v).or_default().push(i);
        }
    }
    let pinched = at
        .iter()
        .filter(|(v, tris)| {
            let mut fan = Groups::new();
            for &i in tris.iter() {
                fan.add(i as u32);
            }
            let mut by_edge: HashMap<u32, Vec<u32>> = HashMap::new();
            for &i in tris.iter() {
                for &w in &m.triangles[i] {
                    if w != **v {
                        by_edge.entry(w).or_default().push(i as u32);
                    }
                }
            }
            for group in by_edge.values() {
                for pair in group.windows(2) {
                    fan.join(pair[0], pair[1]);
                }
            }
            fan.count() > 1
        })
        .count();
    let planes: [fn(DVec3) -> DVec2; 3] = [
        |p| DVec2::new(p.x, p.y),
        |p| DVec2::new(p.y, p.z),
        |p| DVec2::new(p.z, p.x),
    ];
    let degenerate = m
        .triangles
        .iter()
        .filter(|t| {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return true;
            }
            let [a, b, c] = t.map(|v| m.positions[v as usize]);
            planes
                .iter()
                .all(|f| orient2d(f(a), f(b), f(c)) == Sign::Zero)
        })
        .count();
    Shape {
        triangles: m.triangles.len(),
        components,
        boundary_loops: pieces(&boundary),
        nonmanifold_curves: pieces(&nonmanifold),
        misoriented,
        pinched,
        degenerate,
        intersecting_pairs: self_intersections(m).unwrap().pairs.len(),
        euler: used.len() as i64 - degree.len() as i64 + m.triangles.len() as i64,
    }
}

/// Genus of a closed, manifold surface: (2C − χ) / 2.
fn genus(s: &Shape) -> i64 {
    (2 * s.components as i64 - s.euler - s.boundary_loops as i64) / 2
}

/// The bunny scan after strokes meant to keep it whole: still one piece,
/// with the five holes of its base as they were.
fn bunny_one_piece_with_its_five_holes(end: &Shape) {
    assert_eq!(end.components, 1);
    assert_eq!(end.boundary_loops, 5);
}

/// [`bunny_one_piece_with_its_five_holes`], and of genus `expected` (0 as
/// scanned, 1 where a stroke made a tunnel, a handle or a slit), `why`
/// saying which. With one piece and five loops fixed, the genus follows
/// from the Euler characteristic alone ([`genus`]).
fn bunny_whole_of_genus(end: &Shape, expected: i64, why: &str) {
    bunny_one_piece_with_its_five_holes(end);
    assert_eq!(genus(end), expected, "{why}");
}

/// Asserts that `after` is no worse than `before` (issue 15, item 1).
fn no_worse(what: &str, before: &Shape, after: &Shape) {
    if before.boundary_loops == 0 {
        assert_eq!(after.boundary_loops, 0, "{what}: a closed input opened");
    }
    // Each measure of a defect may shrink but not grow.
    for (defect, was, now) in [
        (
            "boundary loops",
            before.boundary_loops,
            after.boundary_loops,
        ),
        (
            "non-manifold curves",
            before.nonmanifold_curves,
            after.nonmanifold_curves,
        ),
        ("misoriented edges", before.misoriented, after.misoriented),
        ("pinched vertices", before.pinched, after.pinched),
        ("degenerate triangles", before.degenerate, after.degenerate),
        (
            "intersecting pairs",
            before.intersecting_pairs,
            after.intersecting_pairs,
        ),
    ] {
        assert!(now <= was, "{what}: {defect} {was} -> {now}");
    }
}

/// The vertices on `m`'s boundary (ends of edges one triangle uses),
/// each once, in increasing order.
fn boundary_vertices(m: &TriMesh) -> Vec<u32> {
    let mut rim: Vec<u32> = edge_degrees(&m.triangles)
        .into_iter()
        .filter(|(_, d)| *d == 1)
        .flat_map(|((a, b), _)| [a, b])
        .collect();
    rim.sort_unstable();
    rim.dedup();
    rim
}

/// Bounding box of the used vertices.
/// The positions of the vertices some triangle uses (with repeats).
fn used_positions(m: &TriMesh) -> impl Iterator<Item = DVec3> + '_ {
    m.triangles
        .iter()
        .flatten()
        .map(|&v| m.positions[v as usize])
}

fn bounds(m: &TriMesh) -> (DVec3, DVec3) {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    for t in &m.triangles {
        for &v in t {
            lo = lo.min(m.positions[v as usize]);
            hi = hi.max(m.positions[v as usize]);
        }
    }
    (lo, hi)
}

/// `n` brush centres on the surface along the straight line between the
/// surface points nearest to `from` and `to` (each a point of the
/// bounding box in its own units: 0 is the box's minimum, 1 its maximum).
fn walk(m: &TriMesh, from: [f64; 3], to: [f64; 3], n: usize) -> Vec<DVec3> {
    let (lo, hi) = bounds(m);
    let at = |r: [f64; 3]| lo + (hi - lo) * DVec3::from_array(r);
    let (a, b) = (
        closest_point(m, at(from)).unwrap().1,
        closest_point(m, at(to)).unwrap().1,
    );
    (0..n)
        .map(|i| {
            let t = i as f64 / (n.max(2) - 1) as f64;
            closest_point(m, a + (b - a) * t).unwrap().1
        })
        .collect()
}

/// The brush radius `share` of the bounding-box diagonal, and the
/// modeler's inflate strength for a slider value `s` (the displacement
/// per frame is `s` × 5% of the radius, as `web/src/main.js` sends it).
fn radius_and_strength(m: &TriMesh, share: f64, s: f64) -> (f64, f64) {
    let (lo, hi) = bounds(m);
    let r = share * lo.distance(hi);
    (r, s * 0.05 * r)
}

/// Applies `strokes` one by one, checking every stroke against the
/// surface before it; returns the reports and the final shape.
fn sculpt(
    what: &str,
    mesh: TriMesh,
    strokes: &[Stroke],
    remesh: bool,
) -> (Session, Vec<StrokeReport>, Shape) {
    let mut s = Session::new(mesh).unwrap();
    s.set_remeshing(remesh);
    let mut before = measure(s.mesh());
    let mut reports = Vec::new();
    for (i, st) in strokes.iter().enumerate() {
        let start = s.mesh().clone();
        let r = s
            .apply_stroke(st)
            .unwrap_or_else(|e| panic!("{what}: stroke {i}: {e}"));
        if let Some(range) = s.remesh() {
            growth_bounded_by_area(
                &format!("{what}, stroke {i}"),
                &start,
                s.mesh(),
                range.min_edge,
            );
        }
        let after = measure(s.mesh());
        eprintln!(
            "{what}, stroke {i} ({}): {} frames, {} topology changes, {} guarded frames, \
             {} held, {} sub-frames, {} -> {} triangles, {} -> {} pairs, {:.2} s",
            st.brush,
            r.frames,
            r.changes,
            r.guarded_frames,
            r.held_frames,
            r.subframes,
            before.triangles,
            after.triangles,
            before.intersecting_pairs,
            after.intersecting_pairs,
            r.seconds
        );
        no_worse(
            &format!("{what}, stroke {i} ({})", st.brush),
            &before,
            &after,
        );
        reports.push(r);
        before = after;
    }
    (s, reports, before)
}

/// Issue 15, item 2: remeshing never blows up. The triangles a stroke
/// added are at most the area of the triangles it made (those not in the
/// surface before, bit for bit) over the area of an equilateral triangle
/// of the remesher's shortest edge, (√3/4)·min_edge²: the count a tiling
/// of that area by the smallest triangles remeshing aims for would have.
fn growth_bounded_by_area(what: &str, before: &TriMesh, after: &TriMesh, min_edge: f64) {
    let key = |m: &TriMesh, t: &[u32; 3]| {
        let mut k = t.map(|v| m.positions[v as usize].to_array().map(f64::to_bits));
        k.sort_unstable();
        k
    };
    let old: HashSet<[[u64; 3]; 3]> = before.triangles.iter().map(|t| key(before, t)).collect();
    let made_area: f64 = (0..after.triangles.len())
        .filter(|&t| !old.contains(&key(after, &after.triangles[t])))
        .map(|t| after.triangle_area(t))
        .sum();
    let bound = made_area / (3f64.sqrt() / 4.0 * min_edge * min_edge);
    let grew = after.triangles.len() as f64 - before.triangles.len() as f64;
    eprintln!("{what}: {grew} triangles added, area bound {bound:.0}");
    assert!(
        grew <= bound.ceil(),
        "{what}: remeshing added {grew} triangles over a made area allowing {bound:.1}"
    );
}

fn paint(brush: Brush, radius: f64, strength: f64, path: Vec<DVec3>) -> Stroke {
    Stroke {
        brush,
        radius,
        strength,
        path,
        ..Stroke::default()
    }
}

/// The haunch strokes of the first report: inflate across the
/// bunny's haunch in 40 small steps at radius 5%, and deflate back, at
/// slider 0.5 and then 1.
fn haunch_strokes(bunny: &TriMesh) -> Vec<Stroke> {
    let across = walk(bunny, [0.55, 0.35, 1.0], [0.75, 0.45, 1.0], 40);
    let back: Vec<DVec3> = across.iter().rev().copied().collect();
    let mut strokes = Vec::new();
    for s in [0.5, 1.0] {
        let (r, k) = radius_and_strength(bunny, 0.05, s);
        strokes.push(paint(Brush::Inflate, r, k, across.clone()));
        strokes.push(paint(Brush::Inflate, r, -k, back.clone()));
    }
    strokes
}

/// The first report: inflate dragged across the bunny's haunch in
/// 40 small steps at radius 5% (slider 0.5, then 1), and deflate back,
/// with and without remeshing. It tore the scan into 54 pieces with
/// 128,600 non-manifold edges; now every stroke leaves it one piece, its
/// five holes as they were, nothing crossing.
#[test]
fn stanford_bunny_inflate_and_deflate_across_the_haunch() {
    let Some(bunny) = load("stanford_bunny_inflate", "stanford-bunny.obj") else {
        return;
    };
    for remesh in [true, false] {
        let strokes = haunch_strokes(&bunny);
        let (_, _, end) = sculpt(
            &format!("bunny haunch (remesh {remesh})"),
            bunny.clone(),
            &strokes,
            remesh,
        );
        bunny_one_piece_with_its_five_holes(&end);
    }
}

/// The haunch strokes as the modeler sends them when its frames take
/// longer than the pointer's steps: the dabs in frames of one to three
/// (`"frames"` in a stroke file), each frame's dabs painted in turn and
/// their motion resolved at once (`LiveStroke::frame_together`), with and
/// without remeshing. Every stroke leaves the scan no worse, one piece,
/// its five holes as they were.
#[test]
fn stanford_bunny_haunch_strokes_in_frames_of_several_dabs() {
    let Some(bunny) = load("stanford_bunny_haunch_frames", "stanford-bunny.obj") else {
        return;
    };
    for remesh in [true, false] {
        let mut strokes = haunch_strokes(&bunny);
        // 40 dabs in frames of 1, 2, 3, 1, 2, 3, ... (the last one short).
        let mut frames = Vec::new();
        let mut left = strokes[0].path.len();
        for k in [1, 2, 3].into_iter().cycle() {
            if left == 0 {
                break;
            }
            frames.push(k.min(left));
            left -= k.min(left);
        }
        for s in &mut strokes {
            s.frames.clone_from(&frames);
        }
        let (_, reports, end) = sculpt(
            &format!("bunny haunch in frames of several dabs (remesh {remesh})"),
            bunny.clone(),
            &strokes,
            remesh,
        );
        for r in &reports {
            assert_eq!(r.frames, frames.len(), "one frame per group of dabs");
        }
        bunny_one_piece_with_its_five_holes(&end);
    }
}

/// Dwell: inflate held on one spot of the bunny's flank at radius 8%,
/// full strength, thirty frames; then smooth it.
#[test]
fn stanford_bunny_dwell_inflate_and_smooth() {
    let Some(bunny) = load("stanford_bunny_dwell", "stanford-bunny.obj") else {
        return;
    };
    let spot = walk(&bunny, [0.6, 0.4, 1.0], [0.6, 0.4, 1.0], 1)[0];
    let (r, k) = radius_and_strength(&bunny, 0.08, 1.0);
    let strokes = [
        paint(Brush::Inflate, r, k, vec![spot; 30]),
        paint(Brush::Smooth, r, 0.5, vec![spot; 10]),
    ];
    let (_, _, end) = sculpt("bunny dwell", bunny, &strokes, true);
    assert_eq!(end.components, 1);
}

/// The path of a grab from the highest point of the bunny's back on the
/// vertical through (0.03, ·, −0.015), clear of the ears and of the
/// holes underneath, straight down to 0.043 under its lowest point: 25
/// points.
fn back_through_belly(bunny: &TriMesh) -> Vec<DVec3> {
    let (lo, _) = bounds(bunny);
    let top = used_positions(bunny)
        .filter(|p| (p.x - 0.03).abs() < 0.002 && (p.z + 0.015).abs() < 0.002)
        .max_by(|a, b| a.y.total_cmp(&b.y))
        .unwrap();
    let below = DVec3::new(top.x, lo.y - 0.043, top.z);
    (0..25)
        .map(|i| top + (below - top) * (i as f64 / 24.0))
        .collect()
}

/// Dragging the top of the bunny's back down through its belly (away
/// from the holes underneath) makes a tunnel: genus 0 to 1, one piece,
/// the five holes as they were.
#[test]
fn stanford_bunny_back_through_belly_makes_a_tunnel() {
    let Some(bunny) = load("stanford_bunny_tunnel", "stanford-bunny.obj") else {
        return;
    };
    let path = back_through_belly(&bunny);
    let (_, reports, end) = sculpt(
        "bunny tunnel",
        bunny,
        &[paint(Brush::Grab, 0.015, 1.0, path)],
        true,
    );
    assert!(reports[0].refused.is_empty(), "{:?}", reports[0].refused);
    bunny_whole_of_genus(&end, 1, "a tunnel through the body");
}

/// The grab of the back through the belly with the live preview on
/// (issue 15, item 3: "the preview shows exactly what release will
/// do"): the pointer comes to rest at the end of the path, as a hand
/// does before letting go, and the vertices the preview marks as
/// vanishing there are the ones the release deletes, vertex for vertex.
/// The release is the guarded run the preview made for the same frames,
/// not a second computation that could differ. (A release that comes
/// with a last step the preview never saw, such as a path whose last
/// point is also its release, can delete more: 232 against 218 here.)
#[test]
fn stanford_bunny_tunnel_preview_is_what_the_release_does() {
    let Some(bunny) = load("stanford_bunny_tunnel_preview", "stanford-bunny.obj") else {
        return;
    };
    let mut path = back_through_belly(&bunny);
    path.extend(path.last().copied());
    let mut s = Session::new(bunny).unwrap();
    s.set_remeshing(false);
    s.set_preview(true);
    let mut last: Option<Vec<bool>> = None;
    s.apply_stroke_observed(&paint(Brush::Grab, 0.015, 1.0, path), &mut |f| {
        if let Some(odd) = f.corrected_odd {
            last = Some(odd.to_vec());
        }
        Ok(())
    })
    .unwrap();
    let previewed = last.expect("the drag showed a preview");
    let released = &s.diagnostics().corrected_odd;
    let count = |v: &[bool]| v.iter().filter(|&&o| o).count();
    assert_eq!(previewed.len(), released.len());
    let differ = previewed
        .iter()
        .zip(released)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differ,
        0,
        "{} vertices previewed as vanishing, {} deleted",
        count(&previewed),
        count(released)
    );
}

/// The bunny's back ear snake-hooked into its head (issue 15, item 3): the
/// ear tip is pulled forward over the head and pressed into its crown.
/// The tip fuses with the head, which makes a handle (genus 0 → 1): one
/// piece, its five holes as they were, nothing crossing, no non-manifold
/// edge. (A grab folds over a pull of many radii and the engine deletes
/// the inverted spike; the snake hook's short steps cannot fold.)
#[test]
fn stanford_bunny_ear_snake_hooked_into_the_head_makes_a_handle() {
    let Some(bunny) = load("stanford_bunny_ear_into_head", "stanford-bunny.obj") else {
        return;
    };
    let used = || used_positions(&bunny);
    // The back ear's tip is the bunny's highest point.
    let tip = used().max_by(|a, b| a.y.total_cmp(&b.y)).unwrap();
    // The crown of the head: the highest point on the vertical through
    // (−0.065, ·, 0.02), in front of the other ear's root.
    let crown = used()
        .filter(|p| (p.x + 0.065).abs() < 0.002 && (p.z - 0.02).abs() < 0.002)
        .max_by(|a, b| a.y.total_cmp(&b.y))
        .unwrap();
    let corners = [
        tip,
        DVec3::new(-0.04, tip.y + 0.013, 0.02),
        crown + DVec3::new(0.0, 0.025, 0.005),
        crown - DVec3::new(0.0, 0.02, 0.0),
    ];
    let mut path = Vec::new();
    for w in corners.windows(2) {
        for i in 0..10 {
            path.push(w[0] + (w[1] - w[0]) * (f64::from(i) / 10.0));
        }
    }
    path.push(corners[3]);
    let (_, reports, end) = sculpt(
        "bunny ear into head",
        bunny.clone(),
        &[paint(Brush::SnakeHook, 0.012, 1.0, path)],
        true,
    );
    assert!(reports[0].changes >= 1, "the tip met the head");
    bunny_whole_of_genus(&end, 1, "the ear fused to the head: a handle");
}

/// Issue 19's brushes on the scan, each dragged across the haunch as
/// the inflate test does (radius 5%): draw, clay, crease, flatten,
/// pinch, scrape, local scale and layer, with symmetry in z on one stroke (the
/// mirror image lands on the other flank) and a falloff other than the
/// default on another. Every stroke keeps what item 1 asks (the oracle
/// of this file), and the bunny stays one piece of genus 0 with its five
/// holes.
#[test]
fn stanford_bunny_sculptor_brushes_across_the_haunch() {
    let Some(bunny) = load("stanford_bunny_brushes", "stanford-bunny.obj") else {
        return;
    };
    let (r, k) = radius_and_strength(&bunny, 0.05, 1.0);
    let across = walk(&bunny, [0.55, 0.35, 1.0], [0.75, 0.45, 1.0], 20);
    let mut strokes: Vec<Stroke> = [
        (Brush::Draw, k),
        (Brush::Clay, k),
        (Brush::Crease, 0.5 * k),
        (Brush::Flatten, 0.5),
        (Brush::Pinch, 0.3),
        (Brush::Scrape, 0.5),
        (Brush::Scale, 0.05),
        (Brush::Layer, 4.0 * k),
    ]
    .into_iter()
    .map(|(brush, strength)| paint(brush, r, strength, across.clone()))
    .collect();
    strokes[0].symmetry = [false, false, true];
    strokes[1].falloff = holey_sculpt::Falloff::Sphere;
    let (_, reports, end) = sculpt("bunny brushes", bunny, &strokes, true);
    assert!(reports.iter().all(|r| r.refused.is_empty()));
    bunny_whole_of_genus(&end, 0, "the scan's genus, kept");
}

/// Issue 19: a crease held on the back ear's flat middle cuts through the
/// thin ear and opens a slit: genus 0 → 1, one piece, the five holes
/// underneath as they were.
#[test]
fn stanford_bunny_crease_through_the_ear_opens_a_slit() {
    let Some(bunny) = load("stanford_bunny_crease_ear", "stanford-bunny.obj") else {
        return;
    };
    // The middle of the ear: the mean of the used vertices above y = 0.165
    // with x > −0.04 (the back ear), then the used vertex nearest it.
    let used: Vec<DVec3> = used_positions(&bunny).collect();
    let ear: Vec<DVec3> = used
        .iter()
        .copied()
        .filter(|p| p.y > 0.165 && p.x > -0.04)
        .collect();
    let mean = ear.iter().copied().sum::<DVec3>() / ear.len() as f64;
    let spot = used
        .iter()
        .copied()
        .min_by(|a, b| a.distance(mean).total_cmp(&b.distance(mean)))
        .unwrap();
    let (_, reports, end) = sculpt(
        "bunny crease",
        bunny,
        &[paint(Brush::Crease, 0.01, 0.0008, vec![spot; 30])],
        true,
    );
    assert!(reports[0].changes >= 1, "the groove met the far side");
    bunny_whole_of_genus(&end, 1, "a slit through the ear");
}

/// The teapot's spout tip (the used vertex farthest along +x) and a point
/// inside the body, 70% of the way across and below the tip, where the
/// spout tests push it.
fn spout_tip_and_body(teapot: &TriMesh) -> (DVec3, DVec3) {
    let (lo, hi) = bounds(teapot);
    let tip = used_positions(teapot)
        .max_by(|a, b| a.x.total_cmp(&b.x))
        .unwrap();
    let into = DVec3::new(
        lo.x + 0.7 * (hi.x - lo.x),
        tip.y - 0.2 * (hi.y - lo.y),
        tip.z,
    );
    (tip, into)
}

/// The teapot: patches stored unwelded, non-manifold vertices, 156 pairs
/// crossing. Inflate along the spout and body, smooth, and grab the
/// spout's tip into the body: nothing gets worse, and nothing far from
/// the brushes changes (the handle and the lid rim stay bit for bit).
#[test]
fn teapot_inflate_smooth_and_spout_into_body() {
    let Some(teapot) = load("teapot", "teapot.obj") else {
        return;
    };
    let (r, k) = radius_and_strength(&teapot, 0.05, 1.0);
    let along = walk(&teapot, [0.85, 0.5, 0.6], [0.6, 0.5, 0.4], 30);
    let (tip, into) = spout_tip_and_body(&teapot);
    let grab: Vec<DVec3> = (0..20)
        .map(|i| tip + (into - tip) * (i as f64 / 19.0))
        .collect();
    let strokes = [
        paint(Brush::Inflate, r, k, along.clone()),
        paint(Brush::Smooth, r, 0.5, along),
        paint(Brush::Grab, r, 1.0, grab.clone()),
    ];
    let (s, _, _) = sculpt("teapot", teapot.clone(), &strokes, true);
    // Far from every brush (two radii beyond the strokes' reach), the
    // surface is as it was.
    let reach = |p: DVec3| {
        strokes
            .iter()
            .flat_map(|st| st.path.iter())
            .chain(grab.iter())
            .map(|q| q.distance(p))
            .fold(f64::INFINITY, f64::min)
    };
    let key = |p: DVec3| p.to_array().map(f64::to_bits);
    let now: HashSet<[u64; 3]> = s.mesh().positions.iter().map(|&p| key(p)).collect();
    let far: Vec<DVec3> = used_positions(&teapot)
        .filter(|&p| reach(p) > 3.0 * r + (into - tip).length())
        .collect();
    assert!(!far.is_empty());
    assert!(
        far.iter().all(|&p| now.contains(&key(p))),
        "a vertex far from the brushes moved or vanished"
    );
}

/// The teapot welded where its patches share positions, the path of 60
/// points from its spout's tip into its body, and a brush radius of 12%
/// of its diagonal; `None` (with a SKIP line) without the shared meshes.
fn welded_teapot_spout_into_body(test: &str) -> Option<(TriMesh, Vec<DVec3>, f64)> {
    let p = load_polygons(test, "teapot.obj")?;
    let teapot = holey_mesh::analysis::weld_exact(&p).triangulated();
    let (tip, into) = spout_tip_and_body(&teapot);
    let (lo, hi) = bounds(&teapot);
    let path: Vec<DVec3> = (0..60)
        .map(|i| tip + (into - tip) * (f64::from(i) / 59.0))
        .collect();
    let radius = 0.12 * (hi - lo).length();
    Some((teapot, path, radius))
}

/// The teapot welded where its patches share positions (three pieces:
/// body with spout and handle, lid, knob; 156 crossing pairs, the spout's
/// and the handle's roots crossing the body): the snake hook takes the
/// spout's open end back into the body (radius 12%, 60 dabs). The end
/// fuses: the spout's lip goes inside and is deleted, and the spout joins
/// the body, so one piece and one boundary loop fewer (issue 15, item 3:
/// "pushing a tip into a body fuses it"), and nothing else gets worse.
#[test]
fn teapot_spout_snake_hooked_into_the_body_fuses() {
    let Some((teapot, path, radius)) =
        welded_teapot_spout_into_body("teapot_spout_snake_hooked_into_the_body_fuses")
    else {
        return;
    };
    let start = measure(&teapot);
    let (_, reports, end) = sculpt(
        "teapot spout into body",
        teapot.clone(),
        &[paint(Brush::SnakeHook, radius, 1.0, path)],
        true,
    );
    assert!(reports[0].changes >= 1, "the spout met the body");
    assert_eq!(
        (end.components, end.boundary_loops),
        (start.components - 1, start.boundary_loops - 1),
        "the spout's end fused into the body"
    );
}

/// What [`dwell_on_a_base_hole_rim`] ran and left.
struct RimDwell {
    bunny: TriMesh,
    /// The rim vertex dwelt on.
    at: DVec3,
    radius: f64,
    strength: f64,
    session: Session,
    report: StrokeReport,
    end: Shape,
}

/// A dwell inflate of 40 frames (radius 5% of the diagonal, the
/// modeler's strength for slider 1) on the rim vertex of the bunny's base
/// holes with the smallest index, with or without remeshing. `None` (a
/// visible skip) without the shared meshes.
fn dwell_on_a_base_hole_rim(test: &str, remesh: bool) -> Option<RimDwell> {
    let bunny = load(test, "stanford-bunny.obj")?;
    let rim = boundary_vertices(&bunny)[0];
    let (radius, strength) = radius_and_strength(&bunny, 0.05, 1.0);
    let at = bunny.positions[rim as usize];
    let (session, reports, end) = sculpt(
        test,
        bunny.clone(),
        &[paint(Brush::Inflate, radius, strength, vec![at; 40])],
        remesh,
    );
    let report = reports.into_iter().next().unwrap();
    Some(RimDwell {
        bunny,
        at,
        radius,
        strength,
        session,
        report,
        end,
    })
}

/// A dwell inflate on a rim vertex of one of the bunny's base holes
/// (radius 5%, 40 frames, remeshing) bulges the rim out and holds no
/// frame: no triangle at the ragged rim turns over, because a rim
/// vertex moves along the normal of its two-ring (see the brush's
/// `rim_normals`). With the rim vertices' own one-sided normals, 29 of
/// the 40 frames were held from frame 11 on, and the rim stayed where
/// it was. The surface near the rim vertex ends more than 0.3 of the
/// brush's whole travel (40 × strength) from the bunny as it was (0.38
/// measured; the 11 frames before the old hold moved it 0.28 at most).
#[test]
fn stanford_bunny_dwell_on_a_base_hole_rim_bulges_it() {
    let Some(d) = dwell_on_a_base_hole_rim("stanford_bunny_dwell_on_a_base_hole_rim", true) else {
        return;
    };
    assert_eq!(d.report.guarded_frames, 0, "{:?}", d.report);
    assert!(d.report.held_because.is_empty());
    bunny_one_piece_with_its_five_holes(&d.end);
    let bulge = used_positions(d.session.mesh())
        .filter(|p| p.distance(d.at) < d.radius)
        .map(|p| closest_point(&d.bunny, p).unwrap().2)
        .fold(0.0, f64::max);
    let travel = 40.0 * d.strength;
    assert!(
        bulge > 0.3 * travel,
        "the rim moved out by {bulge}, the brush's travel is {travel}"
    );
}

/// The same dwell without remeshing still holds frames (its triangles
/// are stretched to many times their size and cross): the report says
/// why, in the audit's words, each reason once, and only when frames
/// were held. (Should a change stop these holds, this test needs
/// another stroke that holds.)
#[test]
fn stanford_bunny_dwell_on_a_base_hole_rim_unremeshed_holds_and_says_why() {
    let Some(d) =
        dwell_on_a_base_hole_rim("stanford_bunny_dwell_on_a_base_hole_rim_unremeshed", false)
    else {
        return;
    };
    let report = &d.report;
    assert!(report.guarded_frames > 0, "the rim crosses: {report:?}");
    assert!(!report.held_because.is_empty());
    for why in &report.held_because {
        assert_ne!(
            holey_topo::audit::in_plain_words(why),
            why.as_str(),
            "a reason the audit gives: {why}"
        );
        assert_eq!(report.held_because.iter().filter(|w| *w == why).count(), 1);
    }
    bunny_one_piece_with_its_five_holes(&d.end);
}

/// The six rim dwells ([`rim_dwells`]) replayed one after another on the
/// shared mesh `file`, checked stroke by stroke as [`sculpt`] does, with
/// remeshing: the reports and the final shape, or `None` when the shared
/// meshes are absent.
fn sculpt_rim_dwells(test: &str, file: &str) -> Option<(Vec<StrokeReport>, Shape)> {
    let m = load(test, file)?;
    let (_, reports, end) = sculpt(test, m.clone(), &rim_dwells(&m), true);
    Some((reports, end))
}

/// The six rim dwells of `bench/sculpt/rim_dwells.py` on `m`: inflates of
/// 40 frames at one point each (radius 5% of the diagonal), at rim
/// vertices spread along the rims by index.
fn rim_dwells(m: &TriMesh) -> Vec<Stroke> {
    let rim = boundary_vertices(m);
    let step = (rim.len() / 6).max(1);
    let (radius, strength) = radius_and_strength(m, 0.05, 1.0);
    (0..6)
        .map(|k| {
            let at = m.positions[rim[k * step] as usize];
            paint(Brush::Inflate, radius, strength, vec![at; 40])
        })
        .collect()
}

/// Two dwell inflates (40 frames each, radius 5%, slider 1, remeshing) on
/// the bunny's base-hole rims, at the fifth and sixth of six rim vertices
/// spread along the rims by index, as `bench/sculpt/rim_dwells.py` picks
/// them. At the second dwell's fifth frame its rim passes through the
/// sheet the first raised: the curve runs from one rim to the other,
/// bounds nothing, and parity deletes neither side, so the paper's glued
/// curve is an X of four triangles, a non-manifold edge. The guard held
/// that frame, and with it the rest of the stroke (no topology change in
/// 40 frames). The crossing now fuses the sheets (`cut/crossings.rs` in
/// holey-topo): the frame goes through as a topology change, and the
/// surface stays one manifold piece with its five holes.
#[test]
fn stanford_bunny_rim_dwell_through_a_raised_sheet_fuses_it() {
    let test = "stanford_bunny_rim_dwell_through_a_raised_sheet_fuses_it";
    let Some(bunny) = load(test, "stanford-bunny.obj") else {
        return;
    };
    let dwells = rim_dwells(&bunny);
    let (_, reports, end) = sculpt(test, bunny.clone(), &dwells[4..], true);
    assert_eq!(reports[0].guarded_frames, 0, "{:?}", reports[0]);
    assert!(
        reports[1].changes >= 1,
        "the rims' crossing went through: {:?}",
        reports[1]
    );
    assert_eq!(
        (end.components, end.boundary_loops, end.nonmanifold_curves),
        (1, 5, 0)
    );
}

/// The six rim dwells of `bench/sculpt/rim_dwells.py`, one after another
/// on the scan. In the last, the lip the five before raised folds
/// through the sheet beside it, and the cut of two of its frames reaches
/// past the region the motion's box gives (its result changes that
/// region's interface with the rest). The wider region around it holds
/// the cut, so no frame is recomputed on the whole scan (each such frame
/// took 130–160 ms against 50–70 ms on the wider region), and the scan
/// stays one piece with its five holes and no non-manifold curve.
#[test]
fn stanford_bunny_six_rim_dwells_stay_within_the_brushs_region() {
    let test = "stanford_bunny_six_rim_dwells_stay_within_the_brushs_region";
    let Some((reports, end)) = sculpt_rim_dwells(test, "stanford-bunny.obj") else {
        return;
    };
    assert!(
        reports[5].changes >= 1,
        "the last dwell folds its lip through: {:?}",
        reports[5]
    );
    for r in &reports {
        assert_eq!(r.whole_mesh_frames, 0, "{r:?}");
    }
    assert_eq!(
        (end.components, end.boundary_loops, end.nonmanifold_curves),
        (1, 5, 0)
    );
}

/// The six rim dwells of `bench/sculpt/rim_dwells.py` on `bigguyhalf.obj`
/// (an open mask). In the fifth, the rim's fold pokes its tip through the
/// sheet beside it and the cut closes off tetrahedra of the tip, each
/// below the mask's resolution and inside it: the guard takes them out
/// of the frame's result (`specks_removed`) instead of holding the frame,
/// and the dwell changes topology four times where it changed it twice
/// and then stalled. Every stroke keeps item 1's properties (the oracle
/// of this file) and the mask stays one piece without a non-manifold
/// curve.
#[test]
fn bigguyhalf_rim_dwell_takes_out_the_debris_of_its_fold() {
    let test = "bigguyhalf_rim_dwell_takes_out_the_debris_of_its_fold";
    let Some((reports, end)) = sculpt_rim_dwells(test, "bigguyhalf.obj") else {
        return;
    };
    assert!(reports[4].specks_removed >= 1, "{:?}", reports[4]);
    assert!(reports[4].changes >= 4, "{:?}", reports[4]);
    assert_eq!((end.components, end.nonmanifold_curves), (1, 0));
}

/// How many connected pieces of `m` lie inside the rest of it: the
/// generalized winding number of every other piece, summed here from
/// the solid angles of their triangles (Van Oosterom and Strackee), is at
/// least ½ in magnitude at the centroid of the piece's largest triangle.
fn hidden_pieces(m: &TriMesh) -> usize {
    let mut g = Groups::new();
    for t in &m.triangles {
        g.join(t[0], t[1]);
        g.join(t[0], t[2]);
    }
    let piece: Vec<u32> = m.triangles.iter().map(|t| g.find(t[0])).collect();
    let at = |v: u32| m.positions[v as usize];
    let mut largest: HashMap<u32, (f64, usize)> = HashMap::new();
    for (i, t) in m.triangles.iter().enumerate() {
        let area = (at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0])).length();
        let e = largest.entry(piece[i]).or_insert((area, i));
        if area > e.0 {
            *e = (area, i);
        }
    }
    largest
        .iter()
        .filter(|&(&p, &(_, i))| {
            let q = m.triangles[i].iter().map(|&v| at(v)).sum::<DVec3>() / 3.0;
            let omega: f64 = m
                .triangles
                .iter()
                .zip(&piece)
                .filter(|(_, r)| **r != p)
                .map(|(t, _)| {
                    let [a, b, c] = t.map(|v| at(v) - q);
                    let (la, lb, lc) = (a.length(), b.length(), c.length());
                    let num = a.dot(b.cross(c));
                    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
                    2.0 * num.atan2(den)
                })
                .sum();
            (omega / (4.0 * std::f64::consts::PI)).abs() >= 0.5
        })
        .count()
}

/// Issue 15's teapot grab, the spout's tip dragged into the body (the
/// snake hook's path above, as a grab at radius 12%): the grab's frozen
/// weights fold the stretched spout over itself, the folded strand goes
/// as swept, and the tip, through the wall, was left inside the body as
/// a piece of its own that nobody sees. No stroke may leave a piece
/// hidden inside the surface that was not there before (counted here
/// from winding numbers); this drag is undone instead.
#[test]
fn teapot_spout_grabbed_into_the_body_hides_nothing_inside() {
    let Some((teapot, path, radius)) =
        welded_teapot_spout_into_body("teapot_spout_grabbed_into_the_body")
    else {
        return;
    };
    let before = hidden_pieces(&teapot);
    let (session, _, _) = sculpt(
        "teapot spout grabbed into the body",
        teapot.clone(),
        &[paint(Brush::Grab, radius, 1.0, path)],
        true,
    );
    assert_eq!(hidden_pieces(session.mesh()), before);
}

/// The beetle (open, 47 non-manifold edges, two pieces, crossing itself):
/// one inflate stroke on the hood took it from 2 to 27 pieces with torn
/// slits. Now it keeps its pieces and gets no worse.
#[test]
fn beetle_inflate_on_the_hood() {
    let Some(beetle) = load("beetle", "beetle.obj") else {
        return;
    };
    let (r, k) = radius_and_strength(&beetle, 0.05, 1.0);
    let hood = walk(&beetle, [0.2, 0.5, 0.8], [0.4, 0.5, 0.9], 30);
    let back: Vec<DVec3> = hood.iter().rev().copied().collect();
    let strokes = [
        paint(Brush::Inflate, r, k, hood),
        paint(Brush::Inflate, r, -k, back),
    ];
    for remesh in [true, false] {
        let (_, _, end) = sculpt("beetle", beetle.clone(), &strokes, remesh);
        assert_eq!(end.components, 2, "remesh {remesh}");
    }
}

/// Open and self-intersecting surfaces, inflate and deflate at radius 5%
/// and 8%: bigguyhalf (an open mask), suzanne (open, eyes apart, 90
/// pairs), fertility (closed, genus 4, 104 pairs after fan triangulation)
/// and spot (closed genus 0).
#[test]
fn open_and_self_intersecting_models() {
    for (file, genus_kept) in [
        ("bigguyhalf.obj", None),
        ("suzanne.obj", None),
        ("fertility_poly.obj", Some(4)),
        ("spot_triangulated.obj", Some(0)),
    ] {
        let Some(mesh) = load("open_and_self_intersecting_models", file) else {
            return;
        };
        for (share, slider) in [(0.05, 1.0), (0.08, 0.5)] {
            let (r, k) = radius_and_strength(&mesh, share, slider);
            let path = walk(&mesh, [0.3, 0.4, 1.0], [0.7, 0.6, 1.0], 30);
            let back: Vec<DVec3> = path.iter().rev().copied().collect();
            let strokes = [
                paint(Brush::Inflate, r, k, path),
                paint(Brush::Inflate, r, -k, back),
            ];
            let (_, _, end) = sculpt(file, mesh.clone(), &strokes, true);
            if let Some(g) = genus_kept {
                assert_eq!(end.components, 1, "{file}");
                assert_eq!(genus(&end), g, "{file}");
            }
        }
    }
}

/// Issue 15, item 5: a closed solid that crosses itself
/// (`self_intersectA.obj`, 338 intersecting pairs), inflated at 0.5% of
/// its diagonal a frame: 20 frames dragged across its middle at radius
/// 5%, then 10 frames of a dwell at radius 8%. Once, the surface opened
/// after 4 such frames, fell into 47 pieces after 6 and grew from 5.8k
/// to 138k triangles at the 7th. Now every stroke leaves it closed, in
/// one piece, with no non-manifold edge and no more crossing pairs than
/// it had (checked stroke by stroke).
#[test]
fn self_intersect_a_inflated_stays_closed_and_whole() {
    let Some(mesh) = load("self_intersect_a_inflated", "self_intersectA.obj") else {
        return;
    };
    let (lo, hi) = bounds(&mesh);
    let step = 0.005 * lo.distance(hi);
    let (r, _) = radius_and_strength(&mesh, 0.05, 1.0);
    let (dwell_r, _) = radius_and_strength(&mesh, 0.08, 1.0);
    let path = walk(&mesh, [0.3, 0.4, 0.5], [0.7, 0.6, 0.5], 20);
    let strokes = [
        paint(Brush::Inflate, r, step, path.clone()),
        paint(Brush::Inflate, dwell_r, step, vec![path[10]; 10]),
    ];
    let (_, _, end) = sculpt("self_intersectA inflate", mesh, &strokes, true);
    assert_eq!(end.boundary_loops, 0, "still closed");
    assert_eq!(end.components, 1, "still one piece");
    assert_eq!(end.nonmanifold_curves, 0);
}

/// The Arduino case as a triangle soup (1466 triangles, no shared vertex
/// index; welded it is a closed genus-2 solid): brushes treat its copies
/// of a corner as one point, so inflate and smooth keep it together.
#[test]
fn arduino_soup_inflate_and_smooth() {
    let Some(soup) = load("arduino_soup", "thingi10k_65004_arduino_case_soup.obj") else {
        return;
    };
    let (r, k) = radius_and_strength(&soup, 0.05, 1.0);
    let path = walk(&soup, [0.3, 0.5, 1.0], [0.6, 0.5, 1.0], 20);
    let strokes = [
        paint(Brush::Inflate, r, k, path.clone()),
        paint(Brush::Smooth, r, 0.5, path),
    ];
    sculpt("arduino soup", soup, &strokes, true);
}

/// The edges of `m` taken by exact position (a soup's copies of a corner
/// as one point): how many have one triangle, and how many more than two.
fn welded_rim_and_fins(m: &TriMesh) -> (usize, usize) {
    let mut class: HashMap<[u64; 3], u32> = HashMap::new();
    let id: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let key = [p.x, p.y, p.z].map(|c| if c == 0.0 { 0 } else { c.to_bits() });
            let next = class.len() as u32;
            *class.entry(key).or_insert(next)
        })
        .collect();
    let welded: Vec<[u32; 3]> = m
        .triangles
        .iter()
        .map(|t| t.map(|v| id[v as usize]))
        .collect();
    let degree = edge_degrees(&welded);
    (
        degree.values().filter(|&&d| d == 1).count(),
        degree.values().filter(|&&d| d > 2).count(),
    )
}

/// A dwell inflate at a corner of the Arduino case soup (12 frames at
/// one of its vertices, radius 4.92 and 0.111 a frame: the fourth stroke
/// of `bench/sculpt/fuzz_strokes.py`, seed 1303). Welded by position the
/// soup is closed, and the inflate pushes the corner's walls into each
/// other, so frames cut soup triangles. The guard counted pieces by
/// vertex number, where a soup is a piece per triangle and every cut
/// triangle's kept part a speck: it took 50 of them out as debris,
/// leaving 74 edges of holes in the welded surface. Pieces are counted
/// with a rim's copies joined by position now: nothing is taken out, and
/// the welded surface stays closed, without a fin.
#[test]
fn arduino_soup_dwell_at_a_corner_keeps_its_welded_surface_closed() {
    let test = "arduino_soup_dwell_at_a_corner_keeps_its_welded_surface_closed";
    let Some(soup) = load(test, "thingi10k_65004_arduino_case_soup.obj") else {
        return;
    };
    assert_eq!(welded_rim_and_fins(&soup), (0, 0), "the soup welds closed");
    let corner = DVec3::new(-36.80595016479492, -25.0, 19.34903907775879);
    let dwell = paint(
        Brush::Inflate,
        4.924809611945693,
        0.11085714840578006,
        vec![corner; 12],
    );
    let (session, reports, _) = sculpt(test, soup, &[dwell], true);
    assert_eq!(reports[0].specks_removed, 0, "{:?}", reports[0]);
    assert_eq!(welded_rim_and_fins(session.mesh()), (0, 0));
}

/// Move: a copy of the watertight bunny moved into it merges with it into
/// one closed piece of genus 0.
#[test]
fn bunny_oded_move_into_a_copy() {
    let Some(bunny) = load("bunny_oded_move", "bunny_oded.obj") else {
        return;
    };
    let (lo, hi) = bounds(&bunny);
    let shift = DVec3::new(1.2 * (hi.x - lo.x), 0.0, 0.0);
    let mut two = bunny.clone();
    two.append(&bunny.translated(shift));
    let centre = (lo + hi) * 0.5 + shift;
    let pick = closest_point(&two, centre + DVec3::new(0.0, hi.y - lo.y, 0.0))
        .unwrap()
        .1;
    let to = pick - DVec3::new(0.8 * (hi.x - lo.x), 0.0, 0.0);
    let path: Vec<DVec3> = (0..10)
        .map(|i| pick + (to - pick) * (i as f64 / 9.0))
        .collect();
    let (_, _, end) = sculpt(
        "bunny move",
        two,
        &[paint(Brush::Move, 0.0, 1.0, path)],
        true,
    );
    assert_eq!(end.components, 1, "the copies merged");
    assert_eq!(end.boundary_loops, 0);
    assert_eq!(genus(&end), 0);
}

/// Move, an open scan onto a solid: the Stanford bunny (five holes in its
/// base) moved whole down into a ball under it. A rim of one of its holes
/// pierces the ball, so the intersection curve there ends on the rim and
/// encloses nothing: vertex parity leaves a T-junction where it ends,
/// which only the drag's own path can resolve (`holey_topo`'s kept
/// keyframes; before them the release was undone). The bunny and the
/// ball fuse into one piece of genus 0 (χ and loops counted here); the
/// piercing rim's stretch outside the ball is still open (its vertices,
/// found from the ball's equation, are boundary vertices of the result),
/// and holes whose rims sank whole into the ball no longer bound it.
#[test]
fn stanford_bunny_moved_whole_onto_a_ball_fuses() {
    let test = "stanford_bunny_moved_whole_onto_a_ball_fuses";
    let Some(bunny) = load(test, "stanford-bunny.obj") else {
        return;
    };
    let (lo, hi) = bounds(&bunny);
    let radius = 0.15;
    let centre = DVec3::new(
        (lo.x + hi.x) / 2.0,
        lo.y - 0.01 - radius,
        (lo.z + hi.z) / 2.0,
    );
    let ball = holey_shapes::icosphere(5).unwrap().triangulated();
    let mut scene = bunny.clone();
    scene.append(&TriMesh {
        positions: ball
            .positions
            .iter()
            .map(|&p| centre + p * radius)
            .collect(),
        triangles: ball.triangles.clone(),
    });
    let drop = DVec3::new(0.0, -0.04, 0.0);
    let pick = closest_point(&scene, DVec3::new(centre.x, hi.y, centre.z))
        .unwrap()
        .1;
    let path: Vec<DVec3> = (0..11)
        .map(|i| pick + drop * (f64::from(i) / 10.0))
        .collect();
    // The rim vertices of the bunny's holes, where the drop takes them,
    // and whether the ball holds them.
    let rim_ends: Vec<(DVec3, bool)> = boundary_vertices(&bunny)
        .into_iter()
        .map(|v| {
            let p = bunny.positions[v as usize] + drop;
            (p, (p - centre).length() < radius)
        })
        .collect();
    let outside: Vec<DVec3> = rim_ends.iter().filter(|e| !e.1).map(|e| e.0).collect();
    assert!(!outside.is_empty() && outside.len() < rim_ends.len());
    let (session, reports, end) = sculpt(
        "bunny onto a ball",
        scene,
        &[paint(Brush::Move, 0.0, 1.0, path)],
        false,
    );
    assert_eq!(reports[0].changes, 1, "the release changed the topology");
    assert_eq!(end.components, 1, "the bunny and the ball fused");
    assert_eq!(genus(&end), 0);
    assert!(end.boundary_loops < 5, "holes sank into the ball: {end:?}");
    let out = session.mesh();
    let boundary: Vec<DVec3> = boundary_vertices(out)
        .into_iter()
        .map(|v| out.positions[v as usize])
        .collect();
    // The move adds its steps one frame at a time: the same point to
    // within rounding, a billionth of the bunny's size.
    let tolerance = 1e-9 * (hi - lo).length();
    for p in outside {
        assert!(
            boundary.iter().any(|q| (*q - p).length() < tolerance),
            "rim vertex {p} outside the ball is no longer on the boundary"
        );
    }
}

/// A seeded fuzz loop of random strokes on the real meshes (inflate,
/// deflate, dwell, smooth, grab; random radius 3–8% and strength): no
/// panic, no refusal, every stroke no worse than the surface before it.
#[test]
fn fuzz_random_strokes_on_real_meshes() {
    let files = [
        "stanford-bunny.obj",
        "teapot.obj",
        "beetle.obj",
        "suzanne.obj",
        "spot_triangulated.obj",
    ];
    let mut rng = Rng::new(15);
    for file in files {
        let Some(mesh) = load("fuzz_random_strokes_on_real_meshes", file) else {
            return;
        };
        let mut strokes = Vec::new();
        for _ in 0..4 {
            let share = rng.range(0.03, 0.08);
            let slider = rng.range(0.2, 1.0);
            let (r, k) = radius_and_strength(&mesh, share, slider);
            let a = [rng.unit(), rng.unit(), rng.unit()];
            let b = [rng.unit(), rng.unit(), rng.unit()];
            let path = walk(&mesh, a, b, 12);
            strokes.push(match rng.below(5) {
                0 => paint(Brush::Inflate, r, k, path),
                1 => paint(Brush::Inflate, r, -k, path),
                2 => paint(Brush::Inflate, r, k, vec![path[0]; 12]),
                3 => paint(Brush::Smooth, r, slider, path),
                _ => {
                    let (lo, hi) = bounds(&mesh);
                    let to = path[0] + (hi - lo) * rng.range(-0.3, 0.3);
                    let drag = (0..8)
                        .map(|i| path[0] + (to - path[0]) * (i as f64 / 7.0))
                        .collect();
                    paint(Brush::Grab, r, 1.0, drag)
                }
            });
        }
        sculpt(&format!("fuzz {file}"), mesh, &strokes, true);
    }
}

/// The strokes one run of the browser scenario sent with the mouse
/// (inflate across the haunch, then deflate back; `tests/data`), replayed
/// frame by frame as the modeler's server replays them: a live stroke per
/// stroke, remeshing at the range derived from the mesh it starts on. At
/// the deflate's frame 40 the guard held 88 vertices earlier frames had
/// had to hold; held still while the deflate moved their neighbours, they
/// stood out as a crease whose neck the frame pinched off, a closed bubble
/// of 12 triangles outside the surface that no rule refused. A frame that
/// holds vertices may now cut no piece loose: the bunny stays one piece,
/// and nothing else gets worse.
#[test]
fn stanford_bunny_deflate_back_over_held_vertices_cuts_no_bubble() {
    use holey_sculpt::{BrushSettings, LiveStroke, RemeshOptions, default_range, parse_strokes};
    let test = "stanford_bunny_deflate_back_over_held_vertices_cuts_no_bubble";
    let Some(mut mesh) = load(test, "stanford-bunny.obj") else {
        return;
    };
    let file = parse_strokes(include_str!("data/bunny_haunch_there_and_back.json")).unwrap();
    let before = measure(&mesh);
    for stroke in &file.strokes {
        let settings = BrushSettings {
            falloff: stroke.falloff,
            ..BrushSettings::new(stroke.brush, stroke.radius, stroke.strength)
        };
        let first = stroke.path[0];
        let options = holey_topo::Options::default();
        let mut live = LiveStroke::begin(&mesh, settings, first, options).unwrap();
        live.set_remesh(default_range(&mesh).map(RemeshOptions::new));
        for &point in &stroke.path {
            live.frame(point).unwrap();
        }
        mesh = live.finish().unwrap().mesh;
    }
    let after = measure(&mesh);
    no_worse(test, &before, &after);
    assert_eq!(after.components, 1, "a piece was cut off");
}

/// The recorded haunch strokes (`tests/data`: inflate across the haunch
/// and deflate back, three recordings), replayed frame by frame with the
/// frames the modeler sent: wherever a frame says the stroke knows the
/// bunny is still one piece (`LiveFrame::one_piece`, which spares the
/// guard a count of pieces over the whole mesh), an independent count of
/// the surface's pieces (`holey_testkit::components`) finds one; and the
/// shortcut is taken, on frames that change topology too.
#[test]
fn stanford_bunny_haunch_strokes_know_they_stay_one_piece() {
    use holey_sculpt::{BrushSettings, LiveStroke, RemeshOptions, default_range, parse_strokes};
    let test = "stanford_bunny_haunch_strokes_know_they_stay_one_piece";
    let Some(bunny) = load(test, "stanford-bunny.obj") else {
        return;
    };
    let (mut known, mut known_changing) = (0, 0);
    for strokes in [
        include_str!("data/bunny_haunch_deflate_in_frames_of_seven.json"),
        include_str!("data/bunny_haunch_browser_reinflate_folds_flat.json"),
        include_str!("data/bunny_haunch_there_and_back.json"),
    ] {
        let file = parse_strokes(strokes).unwrap();
        let mut mesh = bunny.clone();
        for stroke in &file.strokes {
            let settings = BrushSettings {
                falloff: stroke.falloff,
                ..BrushSettings::new(stroke.brush, stroke.radius, stroke.strength)
            };
            let options = holey_topo::Options::default();
            let mut live = LiveStroke::begin(&mesh, settings, stroke.path[0], options).unwrap();
            let range = stroke.remesh_or(|| file.remesh.or_else(|| default_range(&mesh)));
            live.set_remesh(range.map(RemeshOptions::new));
            for dabs in stroke.frame_groups() {
                let f = live.frame_together(&dabs).unwrap();
                if f.one_piece {
                    assert_eq!(components(&f.mesh.triangles), 1, "frame {}", f.index);
                    known += 1;
                    known_changing += usize::from(f.topology_changed);
                }
            }
            mesh = live.finish().unwrap().mesh;
        }
    }
    println!(
        "{test}: known one piece at {known} frames, {known_changing} of them changing topology"
    );
    assert!(
        known > 100 && known_changing > 5,
        "{known} {known_changing}"
    );
}

/// The Stanford bunny and a recorded stroke file (`tests/data`) replayed
/// on it through a `Session`: the bunny as it was, the session and the
/// strokes' reports. `None` (a visible skip) without the shared meshes.
fn replay_on_the_bunny(test: &str, strokes: &str) -> Option<(TriMesh, Session, Vec<StrokeReport>)> {
    let bunny = load(test, "stanford-bunny.obj")?;
    let file = holey_sculpt::parse_strokes(strokes).unwrap();
    let mut session = Session::new(bunny.clone()).unwrap();
    let reports = session.replay(&file, &mut |_, _| Ok(())).unwrap();
    Some((bunny, session, reports))
}

/// The strokes of a browser run that failed (inflate across the haunch,
/// then deflate back; `tests/data`), recorded as the modeler sent them:
/// the dabs that queued while a frame was computed in one frame (up to
/// eight), and each stroke's remeshing range as the server derived it.
/// Together the deflate's dabs of one frame moved the surface several
/// edge lengths in one straight motion over the fold the inflate had
/// fused, and its collision parity cut off six closed flakes, the largest
/// of ten triangles, outside the surface (7 pieces). Such a frame now
/// moves in one motion only where nothing collides; where something does
/// its dabs go in runs that each move the surface at most one frame's
/// step.
#[test]
fn stanford_bunny_deflate_in_frames_of_seven_dabs_cuts_no_flakes() {
    let strokes = include_str!("data/bunny_haunch_deflate_in_frames_of_seven.json");
    let file = holey_sculpt::parse_strokes(strokes).unwrap();
    assert!(
        file.strokes[1].frames.iter().any(|&k| k >= 7),
        "the recording's long frames"
    );
    let test = "stanford_bunny_deflate_in_frames_of_seven_dabs_cuts_no_flakes";
    let Some((bunny, session, _)) = replay_on_the_bunny(test, strokes) else {
        return;
    };
    let before = measure(&bunny);
    let after = measure(session.mesh());
    no_worse(test, &before, &after);
    assert_eq!(after.components, 1, "pieces were cut off");
}

/// A browser run of scenario 10 (inflate across the haunch, deflate
/// back, inflate again; `tests/data`, as the modeler sent it). In the
/// third stroke two neighbouring triangles fold flat onto each other
/// across their shared edge, and the cut's patches of the two, glued at
/// points that round alike, are one triangle twice, facing opposite ways:
/// a pillow of no volume hung on an edge where the sheets go on through
/// (four triangles on one edge). The guard held that frame and two more
/// (non-manifold curves 0 -> 1). Such pairs now cancel
/// (`cut/coincident.rs` in holey-topo): no frame is held, and the surface
/// stays one manifold piece with its five holes.
#[test]
fn stanford_bunny_reinflate_over_a_flat_fold_holds_no_frame() {
    let test = "stanford_bunny_reinflate_over_a_flat_fold_holds_no_frame";
    let strokes = include_str!("data/bunny_haunch_browser_reinflate_folds_flat.json");
    let Some((bunny, session, reports)) = replay_on_the_bunny(test, strokes) else {
        return;
    };
    let before = measure(&bunny);
    let after = measure(session.mesh());
    no_worse(test, &before, &after);
    assert_eq!(reports[2].guarded_frames, 0, "{:?}", reports[2]);
    assert_eq!(
        (
            after.components,
            after.boundary_loops,
            after.nonmanifold_curves
        ),
        (1, 5, 0)
    );
}

/// A browser run of scenarios 10 and 11 (three inflates across the
/// haunch, then the snake hook pulling the long ear's tip up, over and
/// down into the crown with the mouse; `tests/data`, as the modeler sent
/// it, which ended at genus 0). On the way over, one long step of the
/// hook crumpled the tentacle's tip through itself and the engine trimmed
/// it: a cut that made points within the hook's reach, so the hook let go
/// above the head, short of the crown. A cut that leaves the Euler
/// characteristic as it was meets nothing: the hook now holds on until
/// the tip fuses into the crown, a handle.
#[test]
fn stanford_bunny_ear_hooked_with_the_mouse_holds_on_past_a_trimmed_tip() {
    let test = "stanford_bunny_ear_hooked_with_the_mouse_holds_on_past_a_trimmed_tip";
    let strokes = include_str!("data/bunny_haunch_then_ear_snake_hook_browser.json");
    let Some((bunny, session, reports)) = replay_on_the_bunny(test, strokes) else {
        return;
    };
    let before = measure(&bunny);
    let after = measure(session.mesh());
    no_worse(test, &before, &after);
    assert!(reports[3].changes >= 2, "{:?}", reports[3]);
    bunny_whole_of_genus(&after, 1, "the ear fused to the crown: a handle");
}

/// How far the vertex that stands out most stands out of its ring: over
/// the vertices with a closed ring of three or more neighbours (a rim
/// vertex's ring is open), the distance from the centroid of its
/// neighbours over their mean distance from it. A smooth surface keeps
/// it well under 1; a vertex left behind while its ring moved on is a
/// spike or a pit of one edge, near or above 1.
fn sharpest_vertex(m: &TriMesh) -> f64 {
    let mut ring: HashMap<u32, HashSet<u32>> = HashMap::new();
    let degree = edge_degrees(&m.triangles);
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            ring.entry(a).or_default().insert(b);
            ring.entry(b).or_default().insert(a);
        }
    }
    let on_rim: HashSet<u32> = degree
        .iter()
        .filter(|(_, d)| **d == 1)
        .flat_map(|((a, b), _)| [*a, *b])
        .collect();
    let at = |v: u32| m.positions[v as usize];
    ring.iter()
        .filter(|(v, r)| r.len() >= 3 && !on_rim.contains(v))
        .map(|(&v, r)| {
            let centroid = r.iter().map(|&u| at(u)).sum::<DVec3>() / r.len() as f64;
            let mean = r.iter().map(|&u| at(u).distance(at(v))).sum::<f64>() / r.len() as f64;
            at(v).distance(centroid) / mean
        })
        .fold(0.0, f64::max)
}

/// The same recording with its frames regrouped at random
/// (`bench/sculpt/regroup_strokes.py`'s regrouping with seed 18: frames
/// of 1 to 2 dabs in both strokes; `tests/data`): where the guard
/// held vertices the deflate could not move (a contact over the fold the
/// inflate fused), the rest of the brush eases off them (`ease.rs`), so
/// the groove's rim is a shoulder, not spikes. Measured on the recording
/// as sent, when its deflate still held: the scan's sharpest vertex
/// stands 0.71 of its mean edge out of its ring; with the held vertices
/// left standing while their rings deflated, 0.97 (15 vertices over
/// 0.8); eased, 0.71 (the scan's own). Since long frames whose readings
/// differ only at a crumple are taken whole, that recording's inflate
/// fuses a fold its deflate no longer presses against, and holds
/// nothing. Which grouping holds depends on every vertex number the
/// frames leave (the remesher visits edges in their order): seed 8's
/// held until the cut's splice kept slots (stop 52) and holds nothing
/// since. This grouping's deflate holds 4,139 vertex-frames; eased, its
/// sharpest vertex is 0.71; with the held vertices left standing (the
/// easing turned off), 0.97. Of the 17 groupings among seeds 0 to 29
/// whose deflate holds, most end with a vertex 0.86 to 1.00 out of its
/// ring, with the cut's old splice as with the new; in the one traced
/// (seed 3, stop 50) it appears at a frame that fuses the groove's two
/// walls, before anything is held: the tip of a notch where the walls
/// meet, not a held vertex left standing, which this measure cannot tell
/// apart.
/// Asserted: the deflate held vertices, and nothing is sharper than the
/// scan's own sharpest vertex and a tenth.
#[test]
fn stanford_bunny_deflate_regrouped_leaves_no_spikes_where_it_holds() {
    let test = "stanford_bunny_deflate_regrouped_leaves_no_spikes_where_it_holds";
    let strokes = include_str!("data/bunny_haunch_deflate_regrouped_holds.json");
    let Some((bunny, session, reports)) = replay_on_the_bunny(test, strokes) else {
        return;
    };
    let scan = sharpest_vertex(&bunny);
    assert!(
        reports[1].held_vertices > 0,
        "the deflate held vertices: {:?}",
        reports[1]
    );
    let sculpted = sharpest_vertex(session.mesh());
    println!(
        "{test}: {} vertex-frames held; sharpest vertex {sculpted:.2} of its mean edge out of its ring (the scan's: {scan:.2})",
        reports[1].held_vertices
    );
    assert!(
        sculpted <= 1.1 * scan,
        "a vertex stands {sculpted:.2} of its mean edge out of its ring (the scan's sharpest: {scan:.2})"
    );
}
