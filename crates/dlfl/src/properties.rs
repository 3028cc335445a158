//! Seeded property tests: random sequences of operators on random meshes
//! keep `validate()` true and the Euler bookkeeping exact.

use glam::DVec3;
use holey_testkit::Rng;

use crate::test_util::{canonical, check, cube, tetrahedron, torus};
use crate::{CornerId, EdgeId, Error, Mesh};

/// (V, E, F, components, genus).
fn state(m: &Mesh) -> (i64, i64, i64, i64, i64) {
    let t = m.topology();
    (
        m.vertex_count() as i64,
        m.edge_count() as i64,
        m.face_count() as i64,
        t.component_count() as i64,
        t.genus(),
    )
}

fn component_of_corner(m: &Mesh, c: CornerId) -> usize {
    let v = m.corner_vertex(c).unwrap();
    m.vertex_components()
        .into_iter()
        .find(|(w, _)| *w == v)
        .unwrap()
        .1
}

fn random_corner(m: &Mesh, rng: &mut Rng) -> Option<CornerId> {
    let cs: Vec<_> = m.corners().collect();
    (!cs.is_empty()).then(|| *rng.pick(&cs))
}

fn random_edge(m: &Mesh, rng: &mut Rng) -> Option<EdgeId> {
    let es: Vec<_> = m.edges().collect();
    (!es.is_empty()).then(|| *rng.pick(&es))
}

fn start_mesh(rng: &mut Rng) -> Mesh {
    match rng.below(5) {
        0 => cube(),
        1 => tetrahedron(),
        2 => torus(3 + rng.below(3) as u32, 3 + rng.below(2) as u32),
        3 => Mesh::new(),
        _ => {
            let mut m = Mesh::new();
            for _ in 0..3 {
                let p = DVec3::new(rng.unit(), rng.unit(), rng.unit());
                m.create_vertex(p).unwrap();
            }
            m
        }
    }
}

fn step(m: &mut Mesh, rng: &mut Rng) {
    let (v, e, f, c, g) = state(m);
    match rng.below(12) {
        0..=2 => {
            let (Some(c1), Some(c2)) = (random_corner(m, rng), random_corner(m, rng)) else {
                return;
            };
            if c1 == c2 {
                let before = canonical(m);
                assert_eq!(m.insert_edge(c1, c2), Err(Error::SameCorner(c1)));
                assert_eq!(canonical(m), before);
                return;
            }
            let same_face = m.corner_face(c1).unwrap() == m.corner_face(c2).unwrap();
            let same_comp = component_of_corner(m, c1) == component_of_corner(m, c2);
            m.insert_edge(c1, c2).unwrap();
            let expect = if same_face {
                (v, e + 1, f + 1, c, g)
            } else if same_comp {
                (v, e + 1, f - 1, c, g + 1)
            } else {
                (v, e + 1, f - 1, c - 1, g)
            };
            assert_eq!(
                state(m),
                expect,
                "insert_edge (same face {same_face}, same component {same_comp})"
            );
        }
        3 | 4 => {
            let Some(edge) = random_edge(m, rng) else {
                return;
            };
            let [fa, fb] = m.edge_faces(edge).unwrap();
            m.delete_edge(edge).unwrap();
            let s = state(m);
            if fa != fb {
                assert_eq!(s, (v, e - 1, f - 1, c, g), "delete_edge merging faces");
            } else {
                assert!(
                    s == (v, e - 1, f + 1, c, g - 1) || s == (v, e - 1, f + 1, c + 1, g),
                    "delete_edge splitting a face: {:?} -> {s:?}",
                    (v, e, f, c, g)
                );
            }
            assert!(matches!(m.edge_faces(edge), Err(Error::Stale { .. })));
        }
        5 => {
            m.create_vertex(DVec3::new(rng.unit(), rng.unit(), rng.unit()))
                .unwrap();
            assert_eq!(state(m), (v + 1, e, f + 1, c + 1, g));
        }
        6 => {
            let vs: Vec<_> = m.vertices().collect();
            if vs.is_empty() {
                return;
            }
            let x = *rng.pick(&vs);
            if m.valence(x).unwrap() == 0 {
                m.delete_vertex(x).unwrap();
                assert_eq!(state(m), (v - 1, e, f - 1, c - 1, g));
            } else {
                let before = canonical(m);
                assert_eq!(m.delete_vertex(x), Err(Error::NotPointSphere(x)));
                assert_eq!(canonical(m), before);
            }
        }
        7 => {
            let Some(edge) = random_edge(m, rng) else {
                return;
            };
            m.subdivide_edge(edge).unwrap();
            assert_eq!(state(m), (v + 1, e + 1, f, c, g));
        }
        8 => {
            let Some(edge) = random_edge(m, rng) else {
                return;
            };
            if m.is_self_loop(edge).unwrap() {
                assert_eq!(m.collapse_edge(edge), Err(Error::SelfLoop(edge)));
                return;
            }
            m.collapse_edge(edge).unwrap();
            // Also for a lone segment, which collapses to a point-sphere.
            assert_eq!(state(m), (v - 1, e - 1, f, c, g));
        }
        9 => {
            let (Some(c1), Some(c2)) = (random_corner(m, rng), random_corner(m, rng)) else {
                return;
            };
            let (f1, f2) = (m.corner_face(c1).unwrap(), m.corner_face(c2).unwrap());
            let same_comp = component_of_corner(m, c1) == component_of_corner(m, c2);
            let before = canonical(m);
            match m.create_pipe(c1, c2) {
                Ok(edges) => {
                    let n = edges.len() as i64;
                    let (v2, e2, f2_, c2_, g2) = state(m);
                    let added = v2 - v; // vertices from matching the corner counts
                    assert_eq!(e2, e + added + n);
                    assert_eq!(f2_, f - 2 + n);
                    if same_comp {
                        assert_eq!((c2_, g2), (c, g + 1));
                    } else {
                        assert_eq!((c2_, g2), (c - 1, g));
                    }
                }
                Err(err) => {
                    assert!(
                        f1 == f2 || matches!(err, Error::PointSphereFace(_) | Error::Invalid(_)),
                        "{err}"
                    );
                    assert_eq!(canonical(m), before);
                }
            }
        }
        10 => {
            let (Some(c1), Some(c2)) = (random_corner(m, rng), random_corner(m, rng)) else {
                return;
            };
            let same_face = m.corner_face(c1).unwrap() == m.corner_face(c2).unwrap();
            let same_comp = component_of_corner(m, c1) == component_of_corner(m, c2);
            let before = canonical(m);
            match m.connect_edges(c1, c2) {
                Ok(_) => {
                    let expect = if same_face {
                        (v, e + 2, f + 2, c, g)
                    } else if same_comp {
                        (v, e + 2, f, c, g + 1)
                    } else {
                        (v, e + 2, f, c - 1, g)
                    };
                    assert_eq!(state(m), expect);
                }
                Err(_) => assert_eq!(canonical(m), before),
            }
        }
        _ => match rng.below(3) {
            0 => {
                let removed = m.remove_two_gons() as i64;
                assert_eq!(state(m), (v, e - removed, f - removed, c, g));
            }
            1 => {
                let first = m.faces().next();
                if let Some(face) = first {
                    m.reverse_component(face).unwrap();
                    assert_eq!(state(m), (v, e, f, c, g));
                }
            }
            _ => {
                let Some(edge) = random_edge(m, rng) else {
                    return;
                };
                let gone = m.delete_edge_with_cleanup(edge).unwrap().len() as i64;
                let s = state(m);
                assert_eq!((s.0, s.1), (v - gone, e - 1));
            }
        },
    }
}

#[test]
fn random_operator_sequences_keep_the_mesh_valid() {
    for seed in 0..60u64 {
        let mut rng = Rng::new(seed);
        let mut m = start_mesh(&mut rng);
        for i in 0..150 {
            step(&mut m, &mut rng);
            check(&m);
            if i % 50 == 49 {
                // Raw parts round-trip exactly.
                let back = Mesh::from_raw(&m.to_raw()).unwrap();
                assert_eq!(canonical(&back), canonical(&m), "seed {seed}");
                assert_eq!(back.topology(), m.topology());
            }
            if m.corner_count() > 3000 {
                break;
            }
        }
    }
}

#[test]
fn stale_handles_of_every_kind_are_refused() {
    let mut rng = Rng::new(7);
    let mut m = torus(4, 4);
    let old_corners: Vec<_> = m.corners().collect();
    let old_edges: Vec<_> = m.edges().collect();
    let old_faces: Vec<_> = m.faces().collect();
    for _ in 0..20 {
        let e = random_edge(&m, &mut rng).unwrap();
        if !m.is_self_loop(e).unwrap() {
            m.collapse_edge(e).unwrap();
        }
    }
    for c in old_corners.iter().filter(|c| !m.contains_corner(**c)) {
        assert!(matches!(m.corner_next(*c), Err(Error::Stale { .. })));
    }
    let dead: Vec<_> = old_edges
        .into_iter()
        .filter(|e| !m.contains_edge(*e))
        .collect();
    assert!(!dead.is_empty());
    for e in dead {
        assert!(matches!(m.delete_edge(e), Err(Error::Stale { .. })));
    }
    for f in old_faces.iter().filter(|f| !m.contains_face(**f)) {
        assert!(matches!(m.face_len(*f), Err(Error::Stale { .. })));
    }
    check(&m);
}
