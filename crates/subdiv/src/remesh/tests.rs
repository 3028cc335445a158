//! Tests of the remeshing schemes: counts worked out from each scheme's
//! definition (and checked against Euler's formula), topology kept on a
//! torus, a genus-3 Sierpinski polyhedron, open grids and several
//! components, closed-form positions of the linear schemes, the typed
//! refusals, and seeded random sequences of schemes.

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{CornerId, DVec3, Mesh, RawMesh};
use holey_mesh::PolyMesh;
use holey_testkit::Rng;

use super::{RemeshParams, RemeshScheme, remesh, remesh_capped, remesh_to_raw};
use crate::SubdivError;
use crate::tests::{
    add_random_vertex, counts, join_random_corners, prim, random_self_loop, signature,
};

use RemeshScheme as S;

// ---------------------------------------------------------------- helpers

/// Counts of a closed mesh without point-spheres that the formulas use:
/// V, E, F, C (corners) and the triangles among the faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct K {
    v: i64,
    e: i64,
    f: i64,
    c: i64,
    f3: i64,
}

impl K {
    fn of(m: &Mesh) -> K {
        let sizes: Vec<usize> = m.faces().map(|f| m.face_len(f).unwrap()).collect();
        K {
            v: m.vertex_count() as i64,
            e: m.edge_count() as i64,
            f: m.face_count() as i64,
            c: sizes.iter().sum::<usize>() as i64,
            f3: sizes.iter().filter(|&&n| n == 3).count() as i64,
        }
    }
}

/// (V', E', F') after one level of `s` on a closed mesh without
/// point-spheres, from the definitions in each scheme's documentation.
/// Every line is checked against Euler's formula by
/// [`formulas_keep_the_euler_characteristic`].
fn expected(s: RemeshScheme, k: K, quads: bool) -> (i64, i64, i64) {
    let K { v, e, f, c, f3 } = k;
    match s {
        S::Dual => (f, e, v),
        S::Sqrt3 | S::DualVertexTruncation | S::Stellate => (v + f, e + c, c),
        S::SubdivideFace if !quads => (v + f, e + c, c),
        S::Triangulate => (v + f - f3, e + c - 3 * f3, f3 + c - 3 * f3),
        S::DoubleStellate => (v + f + c, e + 4 * c, 3 * c),
        S::TwelveSixFour => (v + e + f, 3 * c, 2 * c),
        S::Honeycomb => (c, e + c, f + v),
        S::VertexTruncation => (2 * e, e + c, f + v),
        S::Dual12_6_4 => (2 * c, 2 * e + 2 * c, f + e + v),
        S::LinearVertexInsertion | S::CatmullClark | S::SubdivideFace => (v + e + f, 2 * e + c, c),
        S::StellateEdgeRemoval => (v + f, c, e),
        S::DooSabin | S::CornerCutting | S::ModifiedCornerCutting => (c, 2 * c, f + e + v),
        S::Simplest => (e, c, f + v),
        S::Pentagonalization | S::CubicPentagonalization => (v + 2 * e + f, 3 * e + c, c),
        S::DualPentagonalization => (c, 3 * e + c, v + 2 * e + f),
        S::Loop | S::LoopStyle => (v + e, 2 * e + c, f + c),
        S::Root4 | S::HexagonPreserving | S::DualLoop => (v + c, 2 * c, f + e),
        S::GlobalExtrude | S::DualGlobalExtrude => (v + c, e + 2 * c, f + c),
        S::Checkerboard => (v + 2 * e + c, 3 * e + 3 * c, f + 2 * c),
        S::DualCheckerboard => (v + 2 * c, 3 * e + 3 * c, f + 2 * e + c),
        S::PentagonPreserving => (v + e + c, 2 * e + 2 * c, f + c),
        S::DualPentagonPreserving => (v + c, 2 * e + 2 * c, f + e + c),
        S::DualHexagonPreserving => (v + e, 2 * c, f + c),
        S::Fractal => (v + e + f, 2 * e + 2 * c, 2 * c),
        S::ModifiedDoubleStellate => (v + f + c, 2 * e + 2 * c, e + c),
        S::DooSabinBc => (2 * c, 4 * c - e, v + 2 * e + f),
        S::DooSabinBcNew => (v + 2 * c, 4 * c - e, f + 2 * e),
        S::Dome => (v + 3 * e + 28 * c, 4 * e + 56 * c, f + 28 * c),
    }
}

fn params() -> RemeshParams {
    RemeshParams::default()
}

/// Remeshes, validates, checks the topology is kept, and returns the
/// output.
fn checked(m: &Mesh, s: RemeshScheme, p: &RemeshParams, levels: usize) -> Mesh {
    let before = m.to_raw();
    let out = remesh(m, s, p, levels).unwrap_or_else(|e| panic!("{s}: {e}"));
    out.validate()
        .unwrap_or_else(|e| panic!("{s} x{levels}: invalid output: {e}"));
    assert_eq!(
        signature(&out),
        signature(m),
        "{s} x{levels} kept the topology"
    );
    assert_eq!(out.hole_count(), m.hole_count(), "{s}: boundary loops");
    assert_eq!(m.to_raw(), before, "{s}: the input is unchanged");
    out
}

/// Two meshes side by side as one mesh (two components).
fn disjoint(a: &Mesh, b: &Mesh) -> Mesh {
    let (ra, rb) = (a.to_raw(), b.to_raw());
    let (nv, nc) = (ra.positions.len() as u32, ra.face_vertices.len() as u32);
    let holes = |r: &RawMesh| {
        if r.holes.is_empty() {
            vec![false; r.face_count()]
        } else {
            r.holes.clone()
        }
    };
    let mut hole_flags = holes(&ra);
    hole_flags.extend(holes(&rb));
    let raw = RawMesh {
        positions: ra
            .positions
            .iter()
            .copied()
            .chain(rb.positions.iter().map(|p| *p + DVec3::new(5.0, 0.0, 0.0)))
            .collect(),
        face_offsets: ra
            .face_offsets
            .iter()
            .copied()
            .chain(rb.face_offsets.iter().skip(1).map(|o| o + nc))
            .collect(),
        face_vertices: ra
            .face_vertices
            .iter()
            .copied()
            .chain(rb.face_vertices.iter().map(|v| v + nv))
            .collect(),
        holes: hole_flags,
        edges: ra
            .edges
            .iter()
            .copied()
            .chain(rb.edges.iter().map(|&[x, y]| [x + nc, y + nc]))
            .collect(),
    };
    Mesh::from_raw(&raw).expect("a valid union")
}

/// A genus-3 Sierpinski polyhedron (one iteration of §VI.5 on a
/// tetrahedron, by holey-model): 10 vertices, 30 edges of which 6 are
/// self-loops, 16 faces.
fn sierpinski_tetrahedron() -> Mesh {
    let mut m = prim("@tetrahedron");
    holey_model::sierpinski::sierpinski(&mut m, 1).expect("Sierpinski iterates");
    assert_eq!((counts(&m), m.genus()), ((10, 30, 16), 3));
    m
}

fn raw_pos(r: &RawMesh, i: usize) -> DVec3 {
    r.positions[i]
}

fn close(a: DVec3, b: DVec3, what: &str) {
    assert!((a - b).length() < 1e-12, "{what}: {a} != {b}");
}

// ------------------------------------------------------------ the tests

#[test]
fn names_parse_back_and_cover_the_issue() {
    for &s in RemeshScheme::ALL {
        assert_eq!(s.name().parse::<RemeshScheme>().unwrap(), s);
        assert_eq!(s.to_string(), s.name());
    }
    let mut names: Vec<&str> = RemeshScheme::ALL.iter().map(|s| s.name()).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), RemeshScheme::ALL.len(), "names are unique");
    for wanted in [
        "dual",
        "triangulate",
        "sqrt3",
        "loop",
        "dual-loop",
        "root4",
        "linear-vertex-insertion",
        "subdivide-face",
        "vertex-truncation",
        "dual-vertex-truncation",
        "stellate",
        "double-stellate",
        "stellate-edge-removal",
        "corner-cutting",
        "modified-corner-cutting",
        "simplest",
        "honeycomb",
        "12.6.4",
        "dual-12.6.4",
        "pentagonalization",
        "cubic-pentagonalization",
        "dual-pentagonalization",
        "pentagon-preserving",
        "dual-pentagon-preserving",
        "hexagon-preserving",
        "dual-hexagon-preserving",
        "checkerboard",
        "dual-checkerboard",
        "global-extrude",
        "dual-global-extrude",
        "dome",
        "fractal",
        "doo-sabin-bc",
        "doo-sabin-bc-new",
    ] {
        assert!(names.contains(&wanted), "{wanted}");
    }
    assert_eq!(
        "Corner_Cutting".parse::<RemeshScheme>().unwrap(),
        S::CornerCutting
    );
    let err = "loopy".parse::<RemeshScheme>().unwrap_err();
    assert!(matches!(err, SubdivError::UnknownScheme { .. }));
    assert!(err.to_string().contains("pentagon-preserving"), "{err}");
}

#[test]
fn formulas_keep_the_euler_characteristic() {
    // χ = V − E + F must come out unchanged from every formula for any
    // closed counts (C = 2E), so each line of `expected` is at least
    // consistent with the scheme keeping the genus.
    for k in [
        K {
            v: 8,
            e: 12,
            f: 6,
            c: 24,
            f3: 0,
        },
        K {
            v: 4,
            e: 6,
            f: 4,
            c: 12,
            f3: 4,
        },
        K {
            v: 10,
            e: 30,
            f: 16,
            c: 60,
            f3: 4,
        },
        K {
            v: 7,
            e: 20,
            f: 9,
            c: 40,
            f3: 2,
        },
    ] {
        for &s in RemeshScheme::ALL {
            let (v, e, f) = expected(s, k, true);
            assert_eq!(v - e + f, k.v - k.e + k.f, "{s} on {k:?}");
        }
    }
}

#[test]
fn the_examples_of_the_issue() {
    let p = params();
    let cube = prim("@cube");
    let tet = prim("@tetrahedron");
    assert_eq!(counts(&checked(&cube, S::Dual, &p, 1)), (6, 12, 8));
    assert_eq!(counts(&checked(&tet, S::Sqrt3, &p, 1)), (8, 18, 12));
    assert_eq!(
        counts(&checked(&cube, S::VertexTruncation, &p, 1)),
        (24, 36, 14)
    );
    assert_eq!(counts(&checked(&cube, S::Stellate, &p, 1)), (14, 36, 24));
    assert_eq!(
        counts(&checked(&cube, S::CornerCutting, &p, 1)),
        (24, 48, 26)
    );
    // Loop on triangles: V + E, 2E + 3F, 4F, twice.
    let ico = prim("@icosahedron");
    let (v, e, f) = (12, 30, 20);
    let one = checked(&ico, S::Loop, &p, 1);
    assert_eq!(counts(&one), (v + e, 2 * e + 3 * f, 4 * f));
    let (v1, e1, f1) = (v + e, 2 * e + 3 * f, 4 * f);
    let two = checked(&ico, S::Loop, &p, 2);
    assert_eq!(counts(&two), (v1 + e1, 2 * e1 + 3 * f1, 4 * f1));
    assert!(two.faces().all(|face| two.face_len(face).unwrap() == 3));
}

#[test]
fn every_scheme_gives_the_counts_of_its_definition_on_polyhedra() {
    let p = params();
    for spec in [
        "@tetrahedron",
        "@cube",
        "@octahedron",
        "@dodecahedron",
        "@cylinder:5",
    ] {
        let m = prim(spec);
        let k = K::of(&m);
        for &s in RemeshScheme::ALL {
            let out = checked(&m, s, &p, 1);
            let (v, e, f) = expected(s, k, p.subdivide_face_quads);
            assert_eq!(
                counts(&out),
                (v as usize, e as usize, f as usize),
                "{s} on {spec}"
            );
        }
    }
}

#[test]
fn two_levels_follow_the_formulas_twice() {
    let p = params();
    let m = prim("@cube");
    for &s in RemeshScheme::ALL {
        if s == S::Triangulate || s == S::Dome {
            continue; // needs the triangle count after a level / too large
        }
        let k = K::of(&m);
        let (v, e, f) = expected(s, k, true);
        // Closed: every edge has two sides, so C = 2E after a level.
        let k1 = K {
            v,
            e,
            f,
            c: 2 * e,
            f3: 0,
        };
        let (v2, e2, f2) = expected(s, k1, true);
        let out = checked(&m, s, &p, 2);
        assert_eq!(counts(&out), (v2 as usize, e2 as usize, f2 as usize), "{s}");
    }
    // Triangulating twice is triangulating once.
    let t = checked(&m, S::Triangulate, &p, 2);
    assert_eq!(counts(&t), (14, 36, 24));
}

#[test]
fn torus_and_sierpinski_keep_genus_components_and_counts() {
    let p = params();
    for m in [prim("@torus:6:4"), sierpinski_tetrahedron()] {
        let k = K::of(&m);
        let genus = m.genus();
        for &s in RemeshScheme::ALL {
            let out = checked(&m, s, &p, 1);
            assert_eq!(out.genus(), genus, "{s}");
            assert_eq!(out.topology().component_count(), 1, "{s}");
            let (v, e, f) = expected(s, k, true);
            assert_eq!(counts(&out), (v as usize, e as usize, f as usize), "{s}");
        }
    }
}

#[test]
fn open_grids_keep_their_boundary_or_are_refused() {
    let p = params();
    for spec in ["@plane:3:2", "@tri-plane:2:2"] {
        let m = prim(spec);
        assert_eq!(m.hole_count(), 1);
        let before = m.to_raw();
        for &s in RemeshScheme::ALL {
            if s.needs_closed_surface() {
                match remesh(&m, s, &p, 1) {
                    Err(SubdivError::Boundary { scheme, holes }) => {
                        assert_eq!((scheme, holes), (s, 1));
                        let text = SubdivError::Boundary { scheme, holes }.to_string();
                        assert!(
                            text.contains(s.name()) && text.contains("boundary"),
                            "{text}"
                        );
                    }
                    other => panic!("{s} on {spec}: expected Boundary, got {other:?}"),
                }
                assert_eq!(m.to_raw(), before);
            } else {
                for levels in 1..=2 {
                    let out = checked(&m, s, &p, levels);
                    assert_eq!(out.genus(), 0, "{s}");
                    assert_eq!(out.topology().component_count(), 1, "{s}");
                }
            }
        }
    }
}

#[test]
fn several_components_and_point_spheres_are_kept() {
    let p = params();
    let mut m = disjoint(&prim("@cube"), &prim("@torus:5:3"));
    m.create_vertex(DVec3::new(-4.0, 2.0, 1.0)).unwrap();
    let sig = signature(&m);
    assert_eq!(sig.len(), 3);
    for &s in RemeshScheme::ALL {
        let out = checked(&m, s, &p, 1);
        assert_eq!(signature(&out), sig, "{s}");
        let ps = out
            .faces()
            .find(|&f| out.is_point_sphere(f).unwrap())
            .expect("the point-sphere survives");
        assert_eq!(
            out.face_positions(ps).unwrap(),
            vec![DVec3::new(-4.0, 2.0, 1.0)]
        );
    }
    // An open grid beside a closed cube: the dual family refuses it all.
    let open = disjoint(&prim("@cube"), &prim("@plane:2:2"));
    for &s in RemeshScheme::ALL {
        if s.needs_closed_surface() {
            assert!(matches!(
                remesh(&open, s, &p, 1),
                Err(SubdivError::Boundary { .. })
            ));
        } else {
            checked(&open, s, &p, 1);
        }
    }
}

#[test]
fn the_dual_of_the_dual_has_the_counts_back_and_centroid_positions() {
    let p = params();
    let cube = prim("@cube");
    let r = remesh_to_raw(&cube, S::Dual, &p, 1).unwrap();
    // Output vertex f is the centroid of face f: on [-1,1]³, a unit axis.
    for (f, q) in r.positions.iter().enumerate() {
        let face = cube.face_at(f).unwrap();
        let c: DVec3 = cube.face_positions(face).unwrap().iter().sum::<DVec3>() / 4.0;
        close(*q, c, "dual vertex");
        assert!((q.length() - 1.0).abs() < 1e-15);
    }
    let twice = checked(&cube, S::Dual, &p, 2);
    assert_eq!(counts(&twice), counts(&cube));
    // The octahedron's face centroids are the cube's corners over 3.
    for v in twice.vertices() {
        let q = twice.position(v).unwrap();
        assert!((q.abs() - DVec3::splat(1.0 / 3.0)).length() < 1e-15, "{q}");
    }
}

#[test]
fn linear_schemes_put_points_at_centroids_midpoints_and_fractions() {
    let p = params();
    let m = prim("@cube:2");
    let (nv, ne) = (m.vertex_count(), m.edge_count());
    let pos = |i: usize| m.position(m.vertex_at(i).unwrap()).unwrap();
    let mid = |e: usize| {
        let [a, b] = m.edge_vertices(m.edge_at(e).unwrap()).unwrap();
        (m.position(a).unwrap() + m.position(b).unwrap()) / 2.0
    };
    let centroid = |f: usize| {
        let ps = m.face_positions(m.face_at(f).unwrap()).unwrap();
        ps.iter().sum::<DVec3>() / ps.len() as f64
    };
    // Subdivide face (quads) = linear vertex insertion: old vertices stay,
    // then the midpoints, then the centroids.
    for s in [S::SubdivideFace, S::LinearVertexInsertion] {
        let r = remesh_to_raw(&m, s, &p, 1).unwrap();
        for i in 0..nv {
            assert_eq!(raw_pos(&r, i), pos(i));
        }
        for e in 0..ne {
            close(raw_pos(&r, nv + e), mid(e), "midpoint");
        }
        for f in 0..m.face_count() {
            close(raw_pos(&r, nv + ne + f), centroid(f), "centroid");
        }
    }
    // Stellate and subdivide face with triangles: centroids after the
    // vertices.
    let tri = RemeshParams {
        subdivide_face_quads: false,
        ..p
    };
    for (s, q) in [(S::Stellate, p), (S::SubdivideFace, tri)] {
        let r = remesh_to_raw(&m, s, &q, 1).unwrap();
        for f in 0..m.face_count() {
            close(raw_pos(&r, nv + f), centroid(f), "stellation centre");
        }
    }
    // Vertex truncation at t: vertex 2e + k is t of the way along edge e
    // from the end of its corner k (the edge's first vertex for k = 0).
    for t in [0.25, 0.1, 0.4] {
        let q = RemeshParams {
            vertex_truncation_offset: t,
            ..p
        };
        let r = remesh_to_raw(&m, S::VertexTruncation, &q, 1).unwrap();
        for e in 0..ne {
            let [a, b] = m.edge_vertices(m.edge_at(e).unwrap()).unwrap();
            let (pa, pb) = (m.position(a).unwrap(), m.position(b).unwrap());
            close(raw_pos(&r, 2 * e), pa + t * (pb - pa), "cut near a");
            close(raw_pos(&r, 2 * e + 1), pb + t * (pa - pb), "cut near b");
        }
    }
    // Simplest, and vertex truncation at ½, are the midpoints.
    let half = RemeshParams {
        vertex_truncation_offset: 0.5,
        ..p
    };
    for (s, q) in [(S::Simplest, p), (S::VertexTruncation, half)] {
        let r = remesh_to_raw(&m, s, &q, 1).unwrap();
        assert_eq!(r.positions.len(), ne);
        for e in 0..ne {
            close(raw_pos(&r, e), mid(e), "simplest");
        }
    }
    // Pentagonalization: thirds, and with an offset the joined third
    // point moves that fraction of the way to the centroid.
    let r = remesh_to_raw(&m, S::Pentagonalization, &p, 1).unwrap();
    for e in 0..ne {
        let [a, b] = m.edge_vertices(m.edge_at(e).unwrap()).unwrap();
        let (pa, pb) = (m.position(a).unwrap(), m.position(b).unwrap());
        close(raw_pos(&r, nv + 2 * e), (2.0 * pa + pb) / 3.0, "third");
        close(raw_pos(&r, nv + 2 * e + 1), (pa + 2.0 * pb) / 3.0, "third");
    }
    let off = RemeshParams {
        pentagonal_offset: 0.5,
        ..p
    };
    let moved = remesh_to_raw(&m, S::Pentagonalization, &off, 1).unwrap();
    let mut n_moved = 0;
    for i in nv..nv + 2 * ne {
        let (before, after) = (raw_pos(&r, i), raw_pos(&moved, i));
        if before != after {
            // Halfway to some face centroid, the new vertex it joins.
            let z = 2.0 * after - before;
            assert!(
                (0..m.face_count()).any(|f| (centroid(f) - z).length() < 1e-12),
                "third point {i}"
            );
            n_moved += 1;
        }
    }
    assert_eq!(n_moved, 2 * ne, "every third point is joined to one centre");
}

#[test]
fn checkerboard_cuts_a_flat_grid_into_a_finer_grid() {
    // On a flat unit-spaced grid the cut points and inset corners lie on
    // the lines at t and 1 − t of every cell.
    let m = prim("@plane:2:2");
    let t = 0.25;
    let p = RemeshParams {
        checkerboard_thickness: t,
        ..params()
    };
    let out = checked(&m, S::Checkerboard, &p, 1);
    assert_eq!(
        out.face_count(),
        4 * 9 + 1,
        "nine quads per quad and the hole"
    );
    // Cells are 1 wide on [-1,1]²: every coordinate is a multiple of ¼.
    for v in out.vertices() {
        let q = out.position(v).unwrap();
        for x in [q.x, q.y] {
            let k = (x + 1.0) / t;
            assert!((k - k.round()).abs() < 1e-12, "{q}");
        }
        assert_eq!(q.z, 0.0);
    }
    // And each output quad is an axis-aligned rectangle.
    for f in out.faces().filter(|&f| !out.is_hole(f).unwrap()) {
        let ps = out.face_positions(f).unwrap();
        assert_eq!(ps.len(), 4);
        for i in 0..4 {
            let d = ps[(i + 1) % 4] - ps[i];
            assert!(d.x.abs() < 1e-12 || d.y.abs() < 1e-12, "{ps:?}");
        }
    }
}

#[test]
fn corner_cutting_at_nine_sixteenths_is_doo_sabin_on_quads() {
    let m = prim("@cube:2");
    let a = remesh(&m, S::CornerCutting, &params(), 1).unwrap();
    let b = remesh(&m, S::DooSabin, &params(), 1).unwrap();
    assert_eq!(counts(&a), counts(&b));
    for (va, vb) in a.vertices().zip(b.vertices()) {
        close(
            a.position(va).unwrap(),
            b.position(vb).unwrap(),
            "corner point",
        );
    }
    // Another tension: the point of a square corner is α v + the rest.
    let alpha = 0.75;
    let q = RemeshParams {
        corner_cutting_alpha: alpha,
        ..params()
    };
    let r = remesh_to_raw(&prim("@plane:1:1"), S::CornerCutting, &q, 1).unwrap();
    // Face 0 is (-1,-1), (1,-1), (1,1), (-1,1); its first corner point:
    // neighbours weigh (1−α)·3/7 each, the opposite (1−α)·1/7.
    let w = (1.0 - alpha) / 7.0;
    let expect = alpha * DVec3::new(-1.0, -1.0, 0.0)
        + 3.0 * w * (DVec3::new(1.0, -1.0, 0.0) + DVec3::new(-1.0, 1.0, 0.0))
        + w * DVec3::new(1.0, 1.0, 0.0);
    close(raw_pos(&r, 0), expect, "tension corner");
}

#[test]
fn modified_corner_cutting_insets_at_half_the_thickness() {
    // A square of side 2: every new corner is at t/2 from both of its
    // edges, so t/2 inside the square along both axes.
    let t = 0.5;
    let p = RemeshParams {
        modified_corner_cutting_thickness: t,
        ..params()
    };
    let r = remesh_to_raw(&prim("@plane:1:1"), S::ModifiedCornerCutting, &p, 1).unwrap();
    let h = t / 2.0;
    close(raw_pos(&r, 0), DVec3::new(-1.0 + h, -1.0 + h, 0.0), "inset");
    close(raw_pos(&r, 1), DVec3::new(1.0 - h, -1.0 + h, 0.0), "inset");
    close(raw_pos(&r, 2), DVec3::new(1.0 - h, 1.0 - h, 0.0), "inset");
}

#[test]
fn sqrt3_and_loop_use_their_masks() {
    let p = params();
    // Octahedron: a vertex of valence 4 has α₄ = 4/9 and its neighbours
    // average to the origin, so it moves to 5/9 of itself (Kobbelt).
    let oct = prim("@octahedron");
    let r = remesh_to_raw(&oct, S::Sqrt3, &p, 1).unwrap();
    for i in 0..6 {
        let q = oct.position(oct.vertex_at(i).unwrap()).unwrap();
        close(raw_pos(&r, i), q * 5.0 / 9.0, "Kobbelt vertex");
    }
    // Without smoothing (dual vertex truncation) vertices stay.
    let r = remesh_to_raw(&oct, S::DualVertexTruncation, &p, 1).unwrap();
    for i in 0..6 {
        assert_eq!(
            raw_pos(&r, i),
            oct.position(oct.vertex_at(i).unwrap()).unwrap()
        );
    }
    // Loop on the octahedron: β₄ = (5/8 − (3/8)²)/4 = 31/256; the
    // neighbours' sum is 0, so a vertex moves to 1 − 4β = 132/256 of
    // itself. An edge point is 3/8 of its ends plus 1/8 of the two
    // opposite vertices.
    let r = remesh_to_raw(&oct, S::Loop, &p, 1).unwrap();
    for i in 0..6 {
        let q = oct.position(oct.vertex_at(i).unwrap()).unwrap();
        close(raw_pos(&r, i), q * (132.0 / 256.0), "Loop vertex");
    }
    for (k, e) in oct.edges().enumerate() {
        let [a, b] = oct.edge_vertices(e).unwrap();
        let [fa, fb] = oct.edge_faces(e).unwrap();
        let opposite = |f| {
            oct.face_vertices(f)
                .unwrap()
                .into_iter()
                .find(|&v| v != a && v != b)
                .unwrap()
        };
        let at = |v| oct.position(v).unwrap();
        let expect = 0.375 * (at(a) + at(b)) + 0.125 * (at(opposite(fa)) + at(opposite(fb)));
        close(raw_pos(&r, 6 + k), expect, "Loop edge point");
    }
    // Boundary: an edge of the open grid's border gets its midpoint.
    let grid = prim("@tri-plane:2:2");
    let r = remesh_to_raw(&grid, S::Loop, &p, 1).unwrap();
    let nv = grid.vertex_count();
    let border = grid
        .edges()
        .position(|e| {
            let [fa, fb] = grid.edge_faces(e).unwrap();
            grid.is_hole(fa).unwrap() || grid.is_hole(fb).unwrap()
        })
        .unwrap();
    let [a, b] = grid.edge_vertices(grid.edge_at(border).unwrap()).unwrap();
    let m = (grid.position(a).unwrap() + grid.position(b).unwrap()) / 2.0;
    close(raw_pos(&r, nv + border), m, "Loop boundary edge");
}

#[test]
fn extrusions_and_stellations_move_along_the_face_normal() {
    let cube = prim("@cube");
    let nv = cube.vertex_count();
    // Global extrude with scale 1: the moved face is the face plus
    // length × √area × its outward normal; the cube's faces are squares
    // of side 2 (√A = 2), so at length 0.5 every new vertex is a cube
    // corner pushed out by 1 along one axis.
    let p = RemeshParams {
        extrude_length: 0.5,
        ..params()
    };
    let r = remesh_to_raw(&cube, S::GlobalExtrude, &p, 1).unwrap();
    for q in &r.positions[nv..] {
        let mut a: Vec<f64> = q.to_array().iter().map(|x| x.abs()).collect();
        a.sort_by(f64::total_cmp);
        assert_eq!(a, vec![1.0, 1.0, 1.0 + 0.5 * 2.0], "{q}");
    }
    // Double stellate: the first centres move by offset along the normal.
    let p = RemeshParams {
        double_stellate_offset: 0.25,
        ..params()
    };
    let r = remesh_to_raw(&cube, S::DoubleStellate, &p, 1).unwrap();
    for f in 0..6 {
        let q = raw_pos(&r, nv + f);
        assert!((q.length() - 1.25).abs() < 1e-12, "{q}");
        assert_eq!(q.abs().max_element(), q.length());
    }
    // Fractal on a square of side 2: |m₀m₁|² = 2 and the opposite
    // midpoint is 2 away, so the apex rises √(2 − 1) = 1 (times offset).
    let r = remesh_to_raw(&cube, S::Fractal, &params(), 1).unwrap();
    let ne = cube.edge_count();
    for f in 0..6 {
        let q = raw_pos(&r, nv + ne + f);
        assert!((q.length() - 2.0).abs() < 1e-12, "{q}");
    }
}

#[test]
fn extrusion_lengths_are_relative_to_each_face() {
    // A triangle of legs 1 (area ½) and a square of side 3 (area 9), apart
    // (the square at x = 5 to 8): global extrude lifts each new vertex by
    // length × √area along its face's normal (+z), dome's cap rises
    // 0.665 × length × √area.
    let polygon = |corners: Vec<DVec3>| {
        let face: Vec<u32> = (0..corners.len() as u32).collect();
        let soup = PolyMesh::from_faces(corners, [face]);
        to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
    };
    let triangle = polygon(vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
    let square = polygon(vec![
        DVec3::ZERO,
        3.0 * DVec3::X,
        DVec3::new(3.0, 3.0, 0.0),
        3.0 * DVec3::Y,
    ]);
    let m = disjoint(&triangle, &square);
    let sizes = [0.5f64.sqrt(), 3.0];
    let p = RemeshParams {
        extrude_length: 0.7,
        dome_length: 0.3,
        ..params()
    };
    let out = checked(&m, S::GlobalExtrude, &p, 1);
    for v in out.vertices() {
        let q = out.position(v).unwrap();
        let size = if q.x < 3.0 { sizes[0] } else { sizes[1] };
        assert!(q.z == 0.0 || (q.z - 0.7 * size).abs() < 1e-12, "{q}");
    }
    let out = checked(&m, S::Dome, &p, 1);
    let mut tops = [0.0f64; 2];
    for v in out.vertices() {
        let q = out.position(v).unwrap();
        let k = usize::from(q.x >= 3.0);
        tops[k] = tops[k].max(q.z);
    }
    for k in 0..2 {
        assert!((tops[k] - 0.665 * 0.3 * sizes[k]).abs() < 1e-12, "{tops:?}");
    }
    // So a mesh scaled by s is extruded into the same shape scaled by s.
    let sphere = prim("@sphere:1");
    let small = scaled(&sphere, 0.01);
    for s in [S::GlobalExtrude, S::Dome] {
        let a = positions(&remesh(&sphere, s, &params(), 1).unwrap());
        let b = positions(&remesh(&small, s, &params(), 1).unwrap());
        for (x, y) in a.iter().zip(&b) {
            assert!((*x * 0.01 - *y).length() < 1e-12, "{s}: {x} {y}");
        }
    }
}

#[test]
fn twelve_six_four_points_are_at_thirds_when_unscaled() {
    let cube = prim("@cube");
    let p = RemeshParams {
        omnitruncation_scale: 1.0,
        ..params()
    };
    let r = remesh_to_raw(&cube, S::Dual12_6_4, &p, 1).unwrap();
    // Face f's corner k owns vertices 2(4f + k) and 2(4f + k) + 1.
    for f in 0..6 {
        let ps = cube.face_positions(cube.face_at(f).unwrap()).unwrap();
        for k in 0..4 {
            let (a, b) = (ps[k], ps[(k + 1) % 4]);
            close(raw_pos(&r, 2 * (4 * f + k)), (2.0 * a + b) / 3.0, "T1");
            close(raw_pos(&r, 2 * (4 * f + k) + 1), (a + 2.0 * b) / 3.0, "T2");
        }
    }
    // Scaled by 0.7 about the face centroid.
    let r = remesh_to_raw(&cube, S::Dual12_6_4, &params(), 1).unwrap();
    let ps = cube.face_positions(cube.face_at(0).unwrap()).unwrap();
    let c = ps.iter().sum::<DVec3>() / 4.0;
    close(
        raw_pos(&r, 0),
        c + 0.7 * ((2.0 * ps[0] + ps[1]) / 3.0 - c),
        "scaled T1",
    );
}

#[test]
fn inner_copies_loop_style_and_dome_rings_are_where_defined() {
    let p = params();
    // One square facing +z; face 0 walks (-1,-1), (1,-1), (1,1), (-1,1).
    let sq = prim("@plane:1:1");
    let face0 = sq.face_at(0).unwrap();
    assert!(!sq.is_hole(face0).unwrap());
    let walk = sq.face_positions(face0).unwrap();
    let corner = |k: usize| walk[k];
    // Pentagon preserving: the copy is the midpoints scaled by 0.75 about
    // the centroid (the origin): output vertices 4 + 4 edges, then copies.
    let r = remesh_to_raw(&sq, S::PentagonPreserving, &p, 1).unwrap();
    for k in 0..4 {
        let m = (corner(k) + corner((k + 1) % 4)) / 2.0;
        close(raw_pos(&r, 8 + k), 0.75 * m, "pentagon-preserving copy");
    }
    // Root-4 with twist 0: corner k of the copy is the mask of the
    // corners, α = 1/√2 − 1/4 + 5/16, the others (1 − α)(3 + 2 cos)/7.
    let r = remesh_to_raw(&sq, S::Root4, &p, 1).unwrap();
    let alpha = std::f64::consts::FRAC_1_SQRT_2 - 0.25 + 5.0 / 16.0;
    let w = (1.0 - alpha) / 7.0;
    for k in 0..4 {
        let expect = alpha * corner(k)
            + 3.0 * w * (corner((k + 1) % 4) + corner((k + 3) % 4))
            + w * corner((k + 2) % 4);
        close(raw_pos(&r, 4 + k), expect, "root-4 copy");
    }
    // Root-4's weight moves an interior vertex towards the average of the
    // copy corners joined to it; on the cube by symmetry along its
    // diagonal, to (1 − w)p + w·avg.
    let cube = prim("@cube");
    let q = RemeshParams {
        root4_weight: 0.5,
        ..p
    };
    let still = remesh_to_raw(&cube, S::Root4, &p, 1).unwrap();
    let moved = remesh_to_raw(&cube, S::Root4, &q, 1).unwrap();
    for i in 0..8 {
        let v = cube.vertex_at(i).unwrap();
        let copies: Vec<DVec3> = still.positions[8..]
            .iter()
            .copied()
            .filter(|c| (*c - cube.position(v).unwrap()).length() < 1.0)
            .collect();
        assert_eq!(copies.len(), 3, "the copy corners nearest corner {i}");
        let avg = copies.iter().sum::<DVec3>() / 3.0;
        close(
            raw_pos(&moved, i),
            0.5 * (raw_pos(&still, i) + avg),
            "root-4 weight",
        );
    }
    // Loop-style with ℓ = 0: each cube corner goes to the average of its
    // three edge midpoints, 2/3 of the way out.
    let q = RemeshParams {
        loop_style_length: 0.0,
        ..p
    };
    let r = remesh_to_raw(&cube, S::LoopStyle, &q, 1).unwrap();
    for i in 0..8 {
        let v = cube.position(cube.vertex_at(i).unwrap()).unwrap();
        close(raw_pos(&r, i), v * (2.0 / 3.0), "loop-style vertex");
    }
    // Modified double stellate: the first centres rise by the height.
    let q = RemeshParams {
        stellate_height: 0.5,
        ..p
    };
    let r = remesh_to_raw(&cube, S::ModifiedDoubleStellate, &q, 1).unwrap();
    for f in 0..6 {
        assert!((raw_pos(&r, 8 + f).length() - 1.5).abs() < 1e-12);
    }
    // Dome: ring centroids stay over the face centroid (the Doo–Sabin
    // mask and the scaling keep it), raised by the sum of the lengths
    // (0.665) times the face's size (a square of side 2: √A = 2); the
    // last ring is scaled by 0.01 to a small cap.
    let out = checked(&sq, S::Dome, &p, 1);
    let cap = out
        .faces()
        .filter(|&f| !out.is_hole(f).unwrap())
        .max_by_key(|&f| out.face_len(f).unwrap())
        .unwrap();
    let ps = out.face_positions(cap).unwrap();
    assert_eq!(ps.len(), 16, "the quartered square's cap");
    let c = ps.iter().sum::<DVec3>() / 16.0;
    let top = 0.665 * 2.0;
    close(c, DVec3::new(0.0, 0.0, top), "dome top");
    assert!(
        ps.iter()
            .all(|q| (*q - c).length() < 0.05 && (q.z - top).abs() < 1e-12)
    );
    // Global extrude's scale shrinks the moved face about its centroid;
    // length 1 lifts it by its size, the side 2.
    let q = RemeshParams {
        extrude_length: 1.0,
        extrude_scale: 0.5,
        ..p
    };
    let r = remesh_to_raw(&sq, S::GlobalExtrude, &q, 1).unwrap();
    for k in 0..4 {
        close(
            raw_pos(&r, 4 + k),
            0.5 * corner(k) + 2.0 * DVec3::Z,
            "extruded corner",
        );
    }
}

#[test]
fn closed_only_schemes_name_themselves_and_refuse_before_work() {
    let m = prim("@plane:4:4");
    for &s in RemeshScheme::ALL
        .iter()
        .filter(|s| s.needs_closed_surface())
    {
        // Even with a level count far past the cap: the boundary is the
        // first thing checked after the parameters.
        let err = remesh(&m, s, &params(), 40).unwrap_err();
        assert_eq!(
            err,
            SubdivError::Boundary {
                scheme: s,
                holes: 1
            }
        );
    }
}

#[test]
fn the_cap_is_checked_before_a_level_is_built() {
    let cube = prim("@cube");
    // Loop: 30 faces and 96 corners after one level, 30 + 96 = 126 after
    // two: a cap of 100 refuses level 2.
    match remesh_capped(&cube, S::Loop, &params(), 2, 100) {
        Err(SubdivError::RemeshTooLarge {
            scheme,
            level,
            faces,
            levels,
            cap,
            ..
        }) => assert_eq!(
            (scheme, level, faces, levels, cap),
            (S::Loop, 2, 126, 2, 100)
        ),
        other => panic!("expected RemeshTooLarge, got {other:?}"),
    }
    assert!(remesh_capped(&cube, S::Loop, &params(), 1, 100).is_ok());
    // Every growing scheme reaches a cap within the level limit, refused
    // by the count alone (a small cap keeps the levels before it cheap).
    for &s in RemeshScheme::ALL {
        if matches!(s, S::Dual | S::Triangulate) {
            continue;
        }
        let err = remesh_capped(&cube, s, &params(), super::MAX_LEVELS, 20_000).unwrap_err();
        assert!(
            matches!(err, SubdivError::RemeshTooLarge { faces, cap: 20_000, .. } if faces > 20_000),
            "{s}: {err}"
        );
    }
    assert!(matches!(
        remesh(&cube, S::Dual, &params(), super::MAX_LEVELS + 1),
        Err(SubdivError::TooManyLevels { .. })
    ));
    // The dual does not grow: all the allowed levels run.
    let d = remesh(&cube, S::Dual, &params(), super::MAX_LEVELS).unwrap();
    assert_eq!(counts(&d), counts(&cube));
}

#[test]
fn parameters_out_of_range_are_refused() {
    let cube = prim("@cube");
    let bad = [
        (
            S::VertexTruncation,
            RemeshParams {
                vertex_truncation_offset: 0.0,
                ..params()
            },
        ),
        (
            S::VertexTruncation,
            RemeshParams {
                vertex_truncation_offset: 0.6,
                ..params()
            },
        ),
        (
            S::Checkerboard,
            RemeshParams {
                checkerboard_thickness: -0.1,
                ..params()
            },
        ),
        (
            S::CornerCutting,
            RemeshParams {
                corner_cutting_alpha: f64::NAN,
                ..params()
            },
        ),
        (
            S::GlobalExtrude,
            RemeshParams {
                extrude_length: f64::INFINITY,
                ..params()
            },
        ),
    ];
    for (s, q) in bad {
        let err = remesh(&cube, s, &q, 1).unwrap_err();
        assert!(
            matches!(err, SubdivError::InvalidParameter { scheme, .. } if scheme == s),
            "{err}"
        );
    }
    // A parameter a scheme does not read is not checked.
    let q = RemeshParams {
        corner_cutting_alpha: f64::NAN,
        ..params()
    };
    checked(&cube, S::Loop, &q, 1);
}

#[test]
fn zero_levels_empty_meshes_and_overflow() {
    let cube = prim("@cube");
    for &s in RemeshScheme::ALL {
        let same = remesh(&cube, s, &params(), 0).unwrap();
        assert_eq!(same.to_raw(), cube.to_raw());
        assert!(remesh(&Mesh::new(), s, &params(), 2).unwrap().is_empty());
        let mut ps = Mesh::new();
        ps.create_vertex(DVec3::ONE).unwrap();
        assert_eq!(counts(&remesh(&ps, s, &params(), 3).unwrap()), (1, 0, 1));
    }
    // Coordinates near f64::MAX: centroids overflow.
    let mut big = prim("@cube");
    let vs: Vec<_> = big.vertices().collect();
    for v in vs {
        let q = big.position(v).unwrap();
        big.set_position(v, q * 1.5e308).unwrap();
    }
    for s in [S::Stellate, S::Loop, S::Dual, S::Honeycomb] {
        let err = remesh(&big, s, &params(), 1).unwrap_err();
        assert!(
            matches!(err, SubdivError::RemeshOverflow { scheme, .. } if scheme == s),
            "{err}"
        );
    }
}

#[test]
fn doo_sabin_bc_joins_the_edge_faces_at_each_midpoint() {
    let cube = prim("@cube");
    let out = checked(&cube, S::DooSabinBc, &params(), 1);
    // 2C = 48 corner points, 4C − E = 84 edges, V + 2E + F = 38 faces:
    // 6 octagons, 24 quads (two per edge), 8 triangles, no two-gons.
    assert_eq!(counts(&out), (48, 84, 38));
    let mut sizes: Vec<usize> = out.faces().map(|f| out.face_len(f).unwrap()).collect();
    sizes.sort_unstable();
    assert_eq!(sizes, [vec![3; 8], vec![4; 24], vec![8; 6]].concat());
}

#[test]
fn doo_sabin_bc_new_counts_from_its_steps() {
    // TopMod's steps on a closed mesh: splitting the edges gives V + E
    // vertices, 2E edges and 2C corners. Each face's zero-length Doo–Sabin
    // extrusion adds its 2n copy points, 2n copy edges and 2n joining
    // edges, and 2n quads in place of the face: V + E + 2C, 2E + 4C,
    // F + 2C. Deleting the 2E split edges merges quads in pairs:
    // 4C edges, F + 2C − 2E faces. At each of the E midpoints one edge is
    // inserted and two deleted and the midpoint goes: V + 2C, 4C − E,
    // F + 2C − 2E = F + 2E (C = 2E): each face's 2n-gon copy and two
    // pentagons per edge.
    let p = params();
    for (spec, v, e, f) in [
        ("@cube", 8, 12, 6),
        ("@tetrahedron", 4, 6, 4),
        ("@torus:6:4", 24, 48, 24),
    ] {
        let m = prim(spec);
        assert_eq!(counts(&m), (v, e, f), "{spec}");
        let c = 2 * e;
        let out = checked(&m, S::DooSabinBcNew, &p, 1);
        assert_eq!(counts(&out), (v + 2 * c, 4 * c - e, f + 2 * e), "{spec}");
        assert_eq!(out.genus(), m.genus(), "{spec}");
        let mut sizes: Vec<usize> = out.faces().map(|x| out.face_len(x).unwrap()).collect();
        sizes.sort_unstable();
        let n = m.face_len(m.faces().next().unwrap()).unwrap();
        assert!(m.faces().all(|x| m.face_len(x).unwrap() == n), "{spec}");
        assert_eq!(sizes, [vec![5; 2 * e], vec![2 * n; f]].concat(), "{spec}");
        // Old vertices keep their valence (one spoke per corner), the
        // copy points have three edges each.
        let mut valences: Vec<usize> = out.vertices().map(|x| out.valence(x).unwrap()).collect();
        valences.sort_unstable();
        let old: Vec<usize> = m.vertices().map(|x| m.valence(x).unwrap()).collect();
        let mut want = [old, vec![3; 2 * c]].concat();
        want.sort_unstable();
        assert_eq!(valences, want, "{spec}");
    }
    // The cube: 56 vertices, 84 edges, 30 faces.
    assert_eq!(
        counts(&checked(&prim("@cube"), S::DooSabinBcNew, &p, 1)),
        (56, 84, 30)
    );
}

#[test]
fn doo_sabin_bc_new_keeps_a_grid_boundary() {
    // A 2×2 grid: V = 9, E = 12 (4 between two quads, 8 on the boundary),
    // 4 quads (C = 16) and a hole of 8 corners. Every quad's corner gets
    // two copy points, 3 edges per normal corner plus the old edges, two
    // pentagons per inner edge, one per boundary edge, the hole kept:
    // V' = 9 + 32, E' = 48 + 12, F' = 4 + 8 + 8 + 1.
    let m = prim("@plane:2:2");
    assert_eq!((counts(&m), m.hole_count()), ((9, 12, 5), 1));
    let p = RemeshParams {
        doo_sabin_bc_new_length: 0.0,
        ..params()
    };
    for levels in 1..=2 {
        let out = checked(&m, S::DooSabinBcNew, &p, levels);
        assert_eq!(out.genus(), 0);
        if levels == 1 {
            assert_eq!(counts(&out), (41, 60, 21));
        }
    }
    let out = checked(&m, S::DooSabinBcNew, &p, 1);
    // The hole has its 8 corners where they were, even at length 0.
    let hole = |x: &Mesh| {
        let h = x.faces().find(|&f| x.is_hole(f).unwrap()).unwrap();
        let mut ps: Vec<[i64; 3]> = x
            .face_positions(h)
            .unwrap()
            .iter()
            .map(|q| [q.x, q.y, q.z].map(|t| (t * 1e9).round() as i64))
            .collect();
        ps.sort_unstable();
        ps
    };
    assert_eq!(hole(&out), hole(&m));
    assert_eq!(
        out.face_len(out.faces().find(|&f| out.is_hole(f).unwrap()).unwrap())
            .unwrap(),
        8
    );
}

#[test]
fn doo_sabin_bc_new_places_doo_sabin_points_and_moves_old_vertices() {
    let cube = prim("@cube");
    let input = cube.to_raw();
    let nv = input.positions.len();
    // Doo–Sabin's mask of the split 2n-gon, from the weights of Doo &
    // Sabin (1978): own 1/4 + 5/(4N), others (3 + 2cos(2π(i−j)/N))/(4N).
    let ds = |poly: &[DVec3], i: usize| {
        let n = poly.len() as f64;
        let mut q = DVec3::ZERO;
        for (j, x) in poly.iter().enumerate() {
            let w = if i == j {
                0.25 + 5.0 / (4.0 * n)
            } else {
                let t = std::f64::consts::TAU * (i as f64 - j as f64) / n;
                (3.0 + 2.0 * t.cos()) / (4.0 * n)
            };
            q += w * *x;
        }
        q
    };
    for (scale, length) in [(1.0, 1.0), (0.5, 0.0), (-1.5, 0.25)] {
        let p = RemeshParams {
            doo_sabin_bc_new_scale: scale,
            doo_sabin_bc_new_length: length,
            ..params()
        };
        let r = remesh_to_raw(&cube, S::DooSabinBcNew, &p, 1).unwrap();
        // Copy points follow the old vertices, face by face, two per
        // corner (the vertex's, then its edge midpoint's).
        let mut o = nv;
        let mut copies = vec![Vec::new(); nv];
        for f in 0..input.face_count() {
            let (lo, hi) = (
                input.face_offsets[f] as usize,
                input.face_offsets[f + 1] as usize,
            );
            let vs = &input.face_vertices[lo..hi];
            let at = |i: usize| input.positions[vs[i % vs.len()] as usize];
            let poly: Vec<DVec3> = (0..vs.len())
                .flat_map(|i| [at(i), (at(i) + at(i + 1)) / 2.0])
                .collect();
            let pts: Vec<DVec3> = (0..poly.len()).map(|i| ds(&poly, i)).collect();
            let z = pts.iter().sum::<DVec3>() / pts.len() as f64;
            for (i, q) in pts.iter().enumerate() {
                let want = z + scale.abs() * (*q - z);
                close(raw_pos(&r, o + i), want, "copy point");
                if i % 2 == 0 {
                    copies[vs[i / 2] as usize].push(want);
                }
            }
            o += poly.len();
        }
        assert_eq!(o, r.positions.len());
        for (i, mine) in copies.iter().enumerate() {
            assert_eq!(mine.len(), 3, "a cube vertex is in three faces");
            let avg = mine.iter().sum::<DVec3>() / 3.0;
            let want = length * input.positions[i] + (1.0 - length) * avg;
            close(raw_pos(&r, i), want, "old vertex");
        }
    }
}

// ------------------------------------------------- random sequences

/// A small random DLFL: a primitive (open or closed) changed by random
/// fundamental operators, sometimes with a face flagged as a hole.
fn random_mesh(rng: &mut Rng) -> Mesh {
    let specs = [
        "@tetrahedron",
        "@cube",
        "@octahedron",
        "@torus:4:3",
        "@plane:2:2",
        "@cone:4",
    ];
    let mut m = prim(specs[rng.below(specs.len())]);
    for _ in 0..rng.below(8) {
        let corners: Vec<CornerId> = m.corners().collect();
        match rng.below(5) {
            0 | 1 => join_random_corners(&mut m, rng, &corners),
            2 => {
                let edges: Vec<_> = m.edges().collect();
                m.subdivide_edge(*rng.pick(&edges)).unwrap();
            }
            3 => {
                let q = DVec3::new(rng.unit(), rng.unit(), rng.unit());
                add_random_vertex(&mut m, rng, &corners, q, 0.8);
            }
            _ => random_self_loop(&mut m, rng, &corners),
        }
    }
    if rng.chance(0.2) {
        let faces: Vec<_> = m.faces().collect();
        m.set_hole(*rng.pick(&faces), true).unwrap();
    }
    m.validate().unwrap();
    m
}

fn random_params(rng: &mut Rng) -> RemeshParams {
    RemeshParams {
        corner_cutting_alpha: rng.range(0.34, 0.99),
        modified_corner_cutting_thickness: rng.range(0.0, 0.5),
        vertex_truncation_offset: rng.range(0.05, 0.5),
        pentagonal_offset: rng.range(0.0, 0.5),
        pentagon_preserving_scale: rng.range(0.2, 1.0),
        checkerboard_thickness: rng.range(0.0, 0.5),
        root4_weight: rng.range(0.0, 1.0),
        root4_twist: rng.range(0.0, 1.0),
        double_stellate_offset: rng.range(-0.5, 0.5),
        stellate_height: rng.range(-0.5, 0.5),
        stellate_curve: rng.range(-0.5, 0.5),
        fractal_offset: rng.range(0.0, 2.0),
        dome_length: rng.range(0.0, 2.0),
        dome_scale: rng.range(0.0, 2.0),
        omnitruncation_scale: rng.range(0.0, 1.0),
        loop_style_length: rng.range(0.0, 1.0),
        extrude_length: rng.range(-1.0, 2.0),
        extrude_scale: rng.range(0.2, 1.5),
        doo_sabin_bc_new_scale: rng.range(0.0, 2.0),
        doo_sabin_bc_new_length: rng.range(0.0, 1.0),
        subdivide_face_quads: rng.chance(0.5),
    }
}

#[test]
fn random_sequences_of_schemes_keep_every_component_and_stay_valid() {
    let mut rng = Rng::new(0x7e5e_5eed);
    let (mut runs, mut refused_open, mut capped) = (0, 0, 0);
    let mut used = vec![false; RemeshScheme::ALL.len()];
    for _ in 0..160 {
        let mut m = random_mesh(&mut rng);
        let sig = signature(&m);
        for _ in 0..1 + rng.below(3) {
            let k = rng.below(RemeshScheme::ALL.len());
            let s = RemeshScheme::ALL[k];
            let p = random_params(&mut rng);
            match remesh_capped(&m, s, &p, 1, 4_000) {
                Ok(out) => {
                    out.validate()
                        .unwrap_or_else(|e| panic!("{s} after {sig:?}: {e}"));
                    assert_eq!(signature(&out), sig, "{s}");
                    assert_eq!(out.hole_count(), m.hole_count(), "{s}");
                    used[k] = true;
                    runs += 1;
                    m = out;
                }
                Err(SubdivError::Boundary { scheme, holes }) => {
                    assert!(scheme.needs_closed_surface() && holes == m.hole_count());
                    refused_open += 1;
                }
                Err(SubdivError::RemeshTooLarge { .. }) => {
                    capped += 1;
                    break;
                }
                Err(e) => panic!("{s}: {e}"),
            }
        }
    }
    assert!(
        runs > 150 && refused_open > 3 && capped > 3,
        "{runs} {refused_open} {capped}"
    );
    assert!(used.iter().all(|&u| u), "every scheme was exercised");
}

// ------------------------------------------------------- the option table

fn positions(m: &Mesh) -> Vec<DVec3> {
    m.vertices().map(|v| m.position(v).unwrap()).collect()
}

/// `m` scaled by `s` about the origin.
fn scaled(m: &Mesh, s: f64) -> Mesh {
    let mut out = m.clone();
    for v in m.vertices() {
        out.set_position(v, m.position(v).unwrap() * s).unwrap();
    }
    out
}

#[test]
fn every_option_in_the_table_is_read_by_its_scheme() {
    // The table is the schemes' own: changing an option it lists moves
    // the output of that scheme (on a cube, or a triangulated cube where
    // the scheme wants triangles), by either of its names.
    let cube = prim("@cube");
    let mut listed = 0;
    for &s in S::ALL {
        for o in s.options() {
            for name in [o.name, o.field] {
                let base = RemeshParams::default();
                let before = base.get(s, name).unwrap();
                let mut p = base;
                // Inside every range: the (0, ½] and [0, ½] fractions and
                // any finite number.
                let value = if before > 0.3 { 0.2 } else { before + 0.1 };
                p.set(s, name, value).unwrap();
                assert_eq!(p.get(s, o.name), Some(value), "{s} {name}");
                assert_ne!(p, base, "{s} {name}");
                let a = positions(&remesh(&cube, s, &base, 1).unwrap());
                let b = positions(&remesh(&cube, s, &p, 1).unwrap());
                assert_ne!(a, b, "{s}: option {name} changes nothing");
                listed += 1;
            }
        }
        assert_eq!(s.reads().count(), s.options().len());
    }
    // 20 fields, some shared by several schemes, each under two names.
    assert!(listed >= 2 * 20, "{listed}");
}

#[test]
fn setting_an_option_a_scheme_does_not_read_or_out_of_range_is_refused() {
    let mut p = RemeshParams::default();
    let before = p;
    assert!(matches!(
        p.set(S::Dual, "alpha", 0.5),
        Err(SubdivError::UnknownOption { .. })
    ));
    assert!(matches!(
        p.set(S::CornerCutting, "thickness", 0.5),
        Err(SubdivError::UnknownOption { .. })
    ));
    assert!(matches!(
        p.set(S::CornerCutting, "checkerboard_thickness", 0.5),
        Err(SubdivError::UnknownOption { .. })
    ));
    for (s, name, x) in [
        (S::CornerCutting, "alpha", f64::NAN),
        (S::VertexTruncation, "offset", 0.0),
        (S::VertexTruncation, "offset", 0.6),
        (S::Checkerboard, "thickness", -0.1),
        (S::Dome, "scale", f64::INFINITY),
    ] {
        assert!(
            matches!(p.set(s, name, x), Err(SubdivError::InvalidParameter { .. })),
            "{s} {name} {x}"
        );
    }
    assert_eq!(p, before);
    // The message names what the scheme reads.
    let e = p.set(S::Dome, "alpha", 1.0).unwrap_err().to_string();
    assert!(e.contains("length, scale"), "{e}");
    let e = p.set(S::Loop, "alpha", 1.0).unwrap_err().to_string();
    assert!(e.contains("no options"), "{e}");
}
