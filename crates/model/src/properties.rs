//! Seeded property test of issue 18's operators: random sequences of
//! extrusions, stellations, cuts, truncations and tools on small meshes
//! (closed, open, of genus 1, with faces of different sizes). After every
//! call the mesh validates and either the counts changed exactly as the
//! operator's documented formula says (worked out here from the
//! definitions, before the call) with genus and components unchanged, or
//! the call was refused and the mesh is bit-for-bit what it was.

use std::collections::HashSet;

use crate::test_util::{State, prim, state};
use holey_dlfl::{FaceId, Mesh, VertexId};
use holey_testkit::Rng;

use crate::cut::{self, CutError};
use crate::extrude::{self, ExtrudeError, ExtrudeParams, MultiExtrudeParams, RegionDirection};
use crate::{hull, tools, truncate, wireframe};

fn plus(s: State, d: (i64, i64, i64)) -> State {
    (s.0 + d.0, s.1 + d.1, s.2 + d.2, s.3, s.4)
}

fn surface_faces(m: &Mesh) -> Vec<FaceId> {
    m.surface_faces().collect()
}

fn any_face(m: &Mesh, rng: &mut Rng) -> Option<FaceId> {
    let fs = surface_faces(m);
    (!fs.is_empty()).then(|| *rng.pick(&fs))
}

/// Either the expected counts, or a refusal that changed nothing.
fn outcome<E: std::fmt::Display>(
    m: &Mesh,
    before: &Mesh,
    result: Result<(i64, i64, i64), E>,
    what: &str,
) {
    m.validate().unwrap_or_else(|e| panic!("{what}: {e}"));
    match result {
        Ok(delta) => assert_eq!(state(m), plus(state(before), delta), "{what}"),
        Err(e) => assert_eq!(
            m.to_raw(),
            before.to_raw(),
            "{what} refused ({e}) but changed the mesh"
        ),
    }
}

/// The cut formula of [`crate::cut`] for a region with vertices `s`.
fn cut_delta(m: &Mesh, s: &HashSet<VertexId>) -> (i64, i64, i64) {
    let (mut inner, mut spokes) = (0i64, 0i64);
    for e in m.edges() {
        let [a, b] = m.edge_vertices(e).unwrap();
        match (s.contains(&a), s.contains(&b)) {
            (true, true) => inner += 1,
            (true, false) | (false, true) => spokes += 1,
            _ => {}
        }
    }
    let full = m
        .faces()
        .filter(|&f| m.face_vertices(f).unwrap().iter().all(|v| s.contains(v)))
        .count() as i64;
    // Two spokes in two faces: one edge instead of a two-gon face.
    let partial = m
        .faces()
        .filter(|&f| {
            let vs = m.face_vertices(f).unwrap();
            vs.iter().any(|v| s.contains(v)) && !vs.iter().all(|v| s.contains(v))
        })
        .count();
    if spokes == 2 && partial == 2 {
        return (2 - s.len() as i64, 1 - inner, -full);
    }
    (spokes - s.len() as i64, spokes - inner, 1 - full)
}

fn extrusion_step(m: &mut Mesh, rng: &mut Rng) {
    let Some(f) = any_face(m, rng) else { return };
    let d = m.face_len(f).unwrap() as i64;
    let before = m.clone();
    let h = rng.range(0.2, 1.2);
    let (what, result): (&str, Result<(i64, i64, i64), ExtrudeError>) = match rng.below(9) {
        0 => {
            let k = 1 + rng.below(3);
            let p = ExtrudeParams {
                distance: rng.range(-0.5, 1.0),
                rotation_deg: rng.range(-40.0, 40.0),
                scale: rng.range(0.3, 1.2),
                count: k,
            };
            let k = k as i64;
            (
                "plain",
                extrude::extrude_face(m, f, &p).map(|_| (k * d, 2 * k * d, k * d)),
            )
        }
        1 => {
            let k = 1 + rng.below(2);
            let p = extrude::DooSabinParams {
                distance: h,
                twist: rng.range(0.0, 0.5),
                scale: 1.0,
                count: k,
            };
            let k = k as i64;
            (
                "doo-sabin",
                extrude::extrude_face_doo_sabin(m, f, &p).map(|_| (k * d, 2 * k * d, k * d)),
            )
        }
        2 => (
            "octahedral",
            extrude::extrude_face_octahedral(m, f, h).map(|_| (d, 3 * d, 2 * d)),
        ),
        3 => (
            "dodecahedral",
            extrude::extrude_face_dodecahedral(m, f, h).map(|_| (3 * d, 5 * d, 2 * d)),
        ),
        4 => (
            "icosahedral",
            extrude::extrude_face_icosahedral(m, f, h).map(|_| (3 * d, 9 * d, 6 * d)),
        ),
        5 => (
            "stellate",
            extrude::stellate_face(m, f, h - 0.7).map(|_| (1, d, d - 1)),
        ),
        6 => (
            "double stellate",
            extrude::double_stellate_face(m, f, h).map(|_| (d + 1, 4 * d, 3 * d - 1)),
        ),
        7 => {
            let k = 1 + rng.below(3);
            let p = extrude::DomeParams {
                height_factor: h,
                rings: k,
            };
            let k = k as i64;
            (
                "dome",
                extrude::extrude_face_dome(m, f, &p)
                    .map(|_| (k * d + 1, 2 * k * d + d, k * d + d - 1)),
            )
        }
        _ => {
            let faces = surface_faces(m);
            let mut sel: Vec<FaceId> = faces.iter().copied().filter(|_| rng.chance(0.25)).collect();
            sel.push(f);
            let set: HashSet<FaceId> = sel.iter().copied().collect();
            let b = m
                .edges()
                .filter(|&e| {
                    let [x, y] = m.edge_faces(e).unwrap();
                    set.contains(&x) != set.contains(&y)
                })
                .count() as i64;
            let p = MultiExtrudeParams {
                distance: rng.range(-0.3, 0.6),
                direction: if rng.chance(0.5) {
                    RegionDirection::Average
                } else {
                    RegionDirection::VertexNormals
                },
                count: 1 + rng.below(2),
            };
            let k = p.count as i64;
            (
                "multi",
                extrude::extrude_faces(m, &sel, &p).map(|_| (k * b, 2 * k * b, k * b)),
            )
        }
    };
    outcome(m, &before, result, what);
}

fn cut_step(m: &mut Mesh, rng: &mut Rng) {
    let before = m.clone();
    let x = if rng.chance(0.1) {
        *rng.pick(&[0.0, -0.1, f64::NAN, 1e9])
    } else {
        rng.range(0.01, 0.4)
    };
    let (what, result): (&str, Result<(i64, i64, i64), CutError>) = match rng.below(4) {
        0 => {
            let vs: Vec<VertexId> = m.vertices().collect();
            let v = *rng.pick(&vs);
            let delta = cut_delta(m, &HashSet::from([v]));
            ("cut vertex", cut::cut_vertex(m, v, x).map(|_| delta))
        }
        1 => {
            let es: Vec<_> = m.edges().collect();
            if es.is_empty() {
                return;
            }
            let e = *rng.pick(&es);
            let delta = cut_delta(m, &m.edge_vertices(e).unwrap().into_iter().collect());
            ("cut edge", cut::cut_edge(m, e, x).map(|_| delta))
        }
        2 => {
            let Some(f) = any_face(m, rng) else { return };
            let delta = cut_delta(m, &m.face_vertices(f).unwrap().into_iter().collect());
            ("cut face", cut::cut_face(m, f, x).map(|_| delta))
        }
        _ => {
            let vs: Vec<VertexId> = m.vertices().filter(|_| rng.chance(0.3)).collect();
            let t = rng.range(0.05, 0.45);
            let mut delta = (0, 0, 0);
            for &v in &vs {
                let d = cut_delta(m, &HashSet::from([v]));
                delta = (delta.0 + d.0, delta.1 + d.1, delta.2 + d.2);
            }
            (
                "truncate",
                truncate::truncate_vertices(m, &vs, t).map(|_| delta),
            )
        }
    };
    outcome(m, &before, result, what);
}

fn tool_step(m: &mut Mesh, rng: &mut Rng) {
    let before = m.clone();
    match rng.below(5) {
        0 => {
            let p = tools::PlanarizeParams {
                max_iterations: 5,
                tolerance: 1e-6,
            };
            let r = tools::planarize_faces(m, &[], &p).map(|_| (0, 0, 0));
            outcome(m, &before, r, "planarize");
        }
        1 => {
            let r = tools::make_spherical(m, &[]).map(|_| (0, 0, 0));
            outcome(m, &before, r, "spherical");
        }
        2 => {
            let n = tools::cleanup_two_gons(m) as i64;
            outcome(m, &before, Ok::<_, CutError>((0, -n, -n)), "two-gons");
        }
        3 => {
            let r = tools::remove_valence_two_vertices(m).map(|n| (-(n as i64), -(n as i64), 0));
            outcome(m, &before, r, "remove valence 2");
        }
        _ => {
            let r = tools::split_valence_two_vertices(m, rng.range(0.01, 0.2))
                .map(|n| (n as i64, n as i64, 0));
            outcome(m, &before, r, "split valence 2");
        }
    }
}

/// Wireframe and columns of the current mesh: genus E − V + C; the
/// wireframe's counts from E and the valences (`4E`, `10E − 2(V₁ + V₂)`,
/// `4E + 2V₃`, point-spheres copied) and no face under three sides.
fn frame_check(m: &Mesh, rng: &mut Rng) {
    let rank =
        m.edge_count() as i64 - m.vertex_count() as i64 + m.topology().component_count() as i64;
    let wire = rng.chance(0.5);
    let made = if wire {
        wireframe::wireframe(m, 0.002)
    } else {
        let p = wireframe::ColumnParams {
            sides: 3 + rng.below(3),
            radius: 0.001,
        };
        wireframe::columns(m, &p)
    };
    if let Ok(w) = made {
        w.validate().unwrap();
        assert_eq!(w.genus(), rank);
        if wire {
            let k: Vec<usize> = m.vertices().map(|v| m.valence(v).unwrap()).collect();
            let (e, spheres) = (m.edge_count(), k.iter().filter(|&&x| x == 0).count());
            let low = k.iter().filter(|&&x| x == 1 || x == 2).count();
            let high = k.iter().filter(|&&x| x >= 3).count();
            let expected = (
                4 * e + spheres,
                10 * e - 2 * low,
                4 * e + 2 * high + spheres,
            );
            let got = (w.vertex_count(), w.edge_count(), w.face_count());
            assert_eq!(got, expected, "wireframe counts");
            for f in w.faces() {
                let n = w.face_len(f).unwrap();
                assert!(n >= 3 || w.edge_count() == 0 || n == 1, "a {n}-gon");
            }
        }
    }
}

/// The convex hull and the dual convex hull of the current mesh: convex
/// polyhedra (genus 0, one piece, no holes), the dual with one face per
/// corner of the hull; or refused (flat meshes) with the input unchanged.
fn hull_check(m: &Mesh) {
    let before = m.to_raw();
    match (hull::convex_hull(m), hull::dual_convex_hull(m)) {
        (Ok(h), Ok(d)) => {
            for x in [&h, &d] {
                x.validate().unwrap();
                let t = x.topology();
                assert_eq!((t.genus(), t.component_count(), x.hole_count()), (0, 1, 0));
            }
            assert_eq!(d.face_count(), h.vertex_count());
        }
        (Err(a), Err(b)) => assert_eq!(a, b),
        (a, b) => panic!("one hull refused and not the other: {a:?} {b:?}"),
    }
    assert_eq!(m.to_raw(), before);
}

#[test]
fn random_sequences_of_issue_18_operators() {
    let specs = [
        "@cube",
        "@tetrahedron",
        "@octahedron",
        "@torus:4:3",
        "@plane:2:2",
        "@cylinder:5",
        "@cone:4",
        "@dodecahedron",
    ];
    let mut successes = 0;
    for seed in 0..40u64 {
        let mut rng = Rng::new(seed);
        let spec: &&str = rng.pick(&specs);
        let mut m = prim(spec);
        for step in 0..25 {
            let count = m.vertex_count();
            match rng.below(10) {
                0..=4 => extrusion_step(&mut m, &mut rng),
                5..=7 => cut_step(&mut m, &mut rng),
                _ => tool_step(&mut m, &mut rng),
            }
            if m.vertex_count() != count {
                successes += 1;
            }
            if step % 10 == 9 && m.corner_count() < 1500 {
                frame_check(&m, &mut rng);
                hull_check(&m);
            }
            if m.corner_count() > 4000 {
                break;
            }
        }
    }
    // Most steps must actually do something, or the test proves little.
    assert!(successes > 400, "only {successes} steps changed the mesh");
}
