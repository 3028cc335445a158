//! Tests across both schemes: the shared spot oracle, Sierpinski-like
//! meshes with self-loops, two-gons and point-spheres, seeded random
//! topology, open meshes and the size cap. Scheme-specific analytic tests
//! are next to each scheme.

use std::collections::HashMap;

use holey_dlfl::convert::{ImportOptions, to_dlfl};
use holey_dlfl::{CornerId, DVec3, Mesh, VertexId};
use holey_mesh::PolyMesh;
use holey_testkit::Rng;

use crate::{Scheme, SubdivError, catmull_clark, doo_sabin, predict, subdivide, subdivide_capped};

// ---------------------------------------------------------------- helpers

/// A soup imported into the kernel (slot `i` = soup vertex `i`).
pub(crate) fn dlfl(poly: &PolyMesh) -> Mesh {
    let imported = to_dlfl(poly, ImportOptions::default()).expect("test soup imports");
    for (i, v) in imported.vertices.iter().enumerate() {
        assert_eq!(v.map(|v| v.index()), Some(i), "import keeps vertex order");
    }
    imported.mesh
}

pub(crate) fn prim(spec: &str) -> Mesh {
    dlfl(&holey_shapes::parse_primitive(spec).expect("primitive"))
}

/// Per component: (genus, boundary loops, is a point-sphere), sorted, so
/// two meshes compare equal when subdivision kept every component's
/// topology.
pub(crate) fn signature(m: &Mesh) -> Vec<(i64, usize, bool)> {
    let mut s: Vec<_> = m
        .topology()
        .components
        .iter()
        .map(|c| (c.genus(), c.holes, c.vertices == 1 && c.edges == 0))
        .collect();
    s.sort_unstable();
    s
}

/// The subdivided mesh with the structured numbering of
/// [`crate::subdivide_to_raw`] (vertex points first, and so on), which
/// [`subdivide`] trades for locality.
pub(crate) fn structured(m: &Mesh, scheme: Scheme, levels: usize) -> Mesh {
    let raw = crate::subdivide_to_raw(m, scheme, levels).expect("subdivides");
    Mesh::from_raw(&raw).expect("valid output")
}

pub(crate) fn counts(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

/// One and two levels of `scheme` on the cube, [`checked`], with the
/// counts `one` and `two` (V, E, F) and one sphere after one level.
pub(crate) fn cube_levels(
    scheme: Scheme,
    one: (usize, usize, usize),
    two: (usize, usize, usize),
) -> (Mesh, Mesh) {
    let m = prim("@cube");
    let first = checked(&m, scheme, 1);
    assert_eq!(counts(&first), one);
    assert_eq!(signature(&first), vec![(0, 0, false)]);
    let second = checked(&m, scheme, 2);
    assert_eq!(counts(&second), two);
    (first, second)
}

/// Subdivides with `scheme`, validates, and checks that the topology and
/// the predicted sizes hold. Returns the output.
pub(crate) fn checked(m: &Mesh, scheme: Scheme, levels: usize) -> Mesh {
    let before = signature(m);
    let out = subdivide(m, scheme, levels).expect("subdivides");
    out.validate().expect("valid output");
    assert_eq!(
        signature(&out),
        before,
        "{scheme} x{levels} kept the topology"
    );
    assert_eq!(out.hole_count(), m.hole_count());
    let k = predict(m, scheme, levels).expect("predicts");
    assert_eq!(
        (k.vertices, k.edges, k.faces(), k.corners()),
        (
            out.vertex_count() as u128,
            out.edge_count() as u128,
            out.face_count() as u128,
            out.corner_count() as u128,
        ),
        "{scheme} x{levels}: predicted counts"
    );
    out
}

/// One step of the thesis's Sierpinski subdivision (§VI.5), written with
/// the kernel's operators: midpoints on every edge that is not a
/// self-loop; at every old vertex, an edge across each corner cutting off
/// a triangle; at every midpoint, a self-loop between its two corners in
/// faces without an old vertex (the central faces), which merges the
/// central faces into the back faces. Processing corners one at a time,
/// each insertion sees the current face walk. On later levels a run of
/// corners joined by the previous level's (zero-length) self-loops is cut
/// off as one corner.
pub(crate) fn sierpinski_step(m: &mut Mesh) {
    let old: Vec<VertexId> = m.vertices().collect();
    let mut is_old = vec![false; old.iter().map(|v| v.index() + 1).max().unwrap_or(0)];
    for v in &old {
        is_old[v.index()] = true;
    }
    let edges: Vec<_> = m
        .edges()
        .filter(|&e| !m.is_self_loop(e).expect("live"))
        .collect();
    let mids: Vec<VertexId> = edges
        .into_iter()
        .map(|e| m.subdivide_edge(e).expect("subdivides").vertex)
        .collect();
    for &v in &old {
        let corners: Vec<CornerId> = m.vertex_corners(v).expect("live").collect();
        for c in corners {
            // A run of corners at v joined by self-loops is one geometric
            // corner: cut it off whole, from the corner its run starts at.
            let p = m.corner_prev(c).expect("live");
            if m.corner_vertex(p).expect("live") == v {
                continue;
            }
            let mut last = c;
            while m
                .corner_vertex(m.corner_next(last).expect("live"))
                .expect("live")
                == v
            {
                last = m.corner_next(last).expect("live");
            }
            let n = m.corner_next(last).expect("live");
            m.insert_edge(p, n).expect("cuts a corner");
        }
    }
    for &v in &mids {
        let central = |c: CornerId| {
            let f = m.corner_face(c).expect("live");
            m.face_vertices(f)
                .expect("live")
                .iter()
                .all(|w| w.index() >= is_old.len() || !is_old[w.index()])
        };
        let cs: Vec<CornerId> = m
            .vertex_corners(v)
            .expect("live")
            .filter(|&c| central(c))
            .collect();
        assert_eq!(cs.len(), 2, "a midpoint has two central corners");
        m.insert_edge(cs[0], cs[1]).expect("self-loop");
    }
    m.validate().expect("Sierpinski step keeps a valid DLFL");
}

fn self_loops(m: &Mesh) -> usize {
    m.edges().filter(|&e| m.is_self_loop(e).unwrap()).count()
}

fn two_gons(m: &Mesh) -> usize {
    m.faces().filter(|&f| m.face_len(f).unwrap() == 2).count()
}

// ------------------------------------------------------------------ tests

#[test]
fn sierpinski_polyhedra_smooth_into_one_surface_of_the_same_genus() {
    // A level-k Sierpinski polyhedron is many small tetrahedra joined at
    // midpoints by self-loops, so its genus is the cycle rank of the
    // "which tetrahedra touch" graph. Each step turns a tetrahedron into 4
    // joined at 6 midpoints: the tetrahedron gives 4^k tetrahedra and
    // genus 4^k − 1; the cube 8·4^(k−1) tetrahedra with 12 + 6·(8·4^(k−1)
    // − 8)/3 joins: genus 5, 29, 125. The thesis smooths the third levels
    // with Doo–Sabin in figures 43 (tetrahedron) and 44 (cube).
    for (spec, genera, loops) in [
        ("@tetrahedron", &[3i64, 15, 63][..], &[6usize, 30, 126][..]),
        ("@cube", &[5, 29, 125][..], &[12, 60, 252][..]),
        ("@octahedron", &[7][..], &[12][..]),
    ] {
        let mut m = prim(spec);
        for (level, (&genus, &nloops)) in genera.iter().zip(loops).enumerate() {
            sierpinski_step(&mut m);
            assert_eq!(m.genus(), genus, "{spec} level {}", level + 1);
            assert_eq!(m.topology().component_count(), 1);
            assert_eq!(self_loops(&m), nloops, "{spec}: one self-loop per join");
            for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
                for levels in 1..=2 {
                    let out = checked(&m, scheme, levels);
                    assert_eq!(out.genus(), genus);
                    assert_eq!(out.topology().component_count(), 1);
                }
            }
        }
    }
}

#[test]
fn two_gons_self_loops_point_spheres_and_dangling_edges() {
    let mut m = prim("@cube");
    let f0 = m.faces().next().unwrap();
    let c0 = m.face_corner(f0).unwrap();
    let c1 = m.corner_next(c0).unwrap();
    // An edge between adjacent corners: a two-gon beside an edge.
    m.insert_edge(c0, c1).unwrap();
    assert_eq!(two_gons(&m), 1);
    // A self-loop between two corners of one vertex in different faces:
    // merges them, adding a handle.
    let v = m.corner_vertex(c1).unwrap();
    let cs: Vec<_> = m.vertex_corners(v).unwrap().collect();
    let (a, b) = cs
        .iter()
        .flat_map(|&a| cs.iter().map(move |&b| (a, b)))
        .find(|&(a, b)| m.corner_face(a).unwrap() != m.corner_face(b).unwrap())
        .unwrap();
    let lp = m.insert_edge(a, b).unwrap();
    assert!(m.is_self_loop(lp).unwrap());
    assert_eq!(m.genus(), 1);
    // A point-sphere (its own component) and a dangling edge to another
    // (a valence-1 vertex inside a face).
    m.create_vertex(DVec3::new(5.0, 5.0, 5.0)).unwrap();
    let (_, _, tip) = m.create_vertex(DVec3::new(0.0, 0.0, 1.5)).unwrap();
    let f5 = m.faces().find(|&f| m.face_len(f).unwrap() == 4).unwrap();
    let host = m.face_corner(f5).unwrap();
    m.insert_edge(host, tip).unwrap();
    m.validate().unwrap();
    assert_eq!(signature(&m), vec![(0, 0, true), (1, 0, false)]);
    for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
        for levels in 1..=3 {
            let out = checked(&m, scheme, levels);
            // The point-sphere is copied exactly.
            let ps = out
                .faces()
                .find(|&f| out.is_point_sphere(f).unwrap())
                .unwrap();
            assert_eq!(out.face_positions(ps).unwrap(), vec![DVec3::splat(5.0)]);
        }
    }
    // Doo–Sabin keeps a two-gon as a two-gon F-face.
    let ds = doo_sabin(&m, 1).unwrap();
    assert!(two_gons(&ds) >= 1);
}

#[test]
fn monogon_and_a_face_visiting_a_vertex_twice() {
    // A dangling edge makes its face visit the base vertex twice; a
    // self-loop between those two corners cuts off the face (v, tip, v);
    // deleting the dangling edge then leaves that face a monogon (one
    // corner and its self-loop) and the tip a point-sphere.
    let mut m = prim("@tetrahedron");
    let (_, _, tip) = m.create_vertex(DVec3::new(0.1, 0.1, 0.1)).unwrap();
    let f = m.faces().next().unwrap();
    let base = m.face_corner(f).unwrap();
    let dangling = m.insert_edge(base, tip).unwrap();
    let bv = m.corner_vertex(base).unwrap();
    let twice: Vec<_> = m
        .vertex_corners(bv)
        .unwrap()
        .filter(|&c| m.corner_face(c).unwrap() == m.corner_face(base).unwrap())
        .collect();
    assert_eq!(twice.len(), 2, "the face visits the base twice");
    m.insert_edge(twice[0], twice[1]).unwrap();
    m.validate().unwrap();
    for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
        checked(&m, scheme, 2);
    }
    m.delete_edge(dangling).unwrap();
    m.validate().unwrap();
    assert!(
        m.faces()
            .any(|f| m.face_len(f).unwrap() == 1 && !m.is_point_sphere(f).unwrap()),
        "a monogon"
    );
    // And a two-gon beside a triangle's edge.
    let g = m.faces().find(|&f| m.face_len(f).unwrap() == 3).unwrap();
    let c = m.face_corner(g).unwrap();
    m.insert_edge(c, m.corner_next(c).unwrap()).unwrap();
    assert_eq!(two_gons(&m), 1);
    for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
        for levels in 1..=3 {
            checked(&m, scheme, levels);
        }
    }
}

/// Joins two random corners of `corners` by an edge, unless the same
/// corner is drawn twice.
pub(crate) fn join_random_corners(m: &mut Mesh, rng: &mut Rng, corners: &[CornerId]) {
    let a = *rng.pick(corners);
    let b = *rng.pick(corners);
    if a != b {
        m.insert_edge(a, b).unwrap();
    }
}

/// A self-loop between a random corner of `corners` and a random corner of
/// the same vertex, unless that is the same corner.
pub(crate) fn random_self_loop(m: &mut Mesh, rng: &mut Rng, corners: &[CornerId]) {
    let c = *rng.pick(corners);
    let v = m.corner_vertex(c).unwrap();
    let at: Vec<_> = m.vertex_corners(v).unwrap().collect();
    let d = *rng.pick(&at);
    if c != d {
        m.insert_edge(c, d).unwrap();
    }
}

/// A point-sphere at `p`, joined by an edge to a random corner of
/// `corners` with probability `joined`.
pub(crate) fn add_random_vertex(
    m: &mut Mesh,
    rng: &mut Rng,
    corners: &[CornerId],
    p: DVec3,
    joined: f64,
) {
    let (_, _, c) = m.create_vertex(p).unwrap();
    if rng.chance(joined) {
        m.insert_edge(*rng.pick(corners), c).unwrap();
    }
}

/// Applies random fundamental operators, then flags random faces as
/// holes: self-loops, multi-edges, two-gons, handles, merged and split
/// components, point-spheres, dangling edges, pinched boundaries, wires.
fn random_mesh(rng: &mut Rng) -> Mesh {
    let specs: [&str; 4] = ["@tetrahedron", "@cube", "@octahedron", "@torus:6:4"];
    let spec = specs[rng.below(specs.len())];
    let mut m = prim(spec);
    for _ in 0..rng.below(40) + 5 {
        let corners: Vec<CornerId> = m.corners().collect();
        match rng.below(10) {
            0..=4 => join_random_corners(&mut m, rng, &corners),
            5 => {
                let edges: Vec<_> = m.edges().collect();
                if !edges.is_empty() {
                    m.subdivide_edge(*rng.pick(&edges)).unwrap();
                }
            }
            6 => {
                let p = DVec3::from_array(rng.point(-2.0, 2.0));
                add_random_vertex(&mut m, rng, &corners, p, 0.7);
            }
            7 => {
                let edges: Vec<_> = m.edges().collect();
                if !edges.is_empty() && m.edge_count() > 8 {
                    m.delete_edge(*rng.pick(&edges)).unwrap();
                }
            }
            _ => random_self_loop(&mut m, rng, &corners),
        }
    }
    let faces: Vec<_> = m.faces().collect();
    for f in faces {
        if rng.chance(0.15) {
            m.set_hole(f, true).unwrap();
        }
    }
    m.validate().unwrap();
    m
}

#[test]
fn random_topology_is_preserved_by_both_schemes() {
    let mut rng = Rng::new(0x5eed_5b0d);
    let (mut loops, mut twos, mut holes, mut spheres) = (0, 0, 0, 0);
    for _ in 0..150 {
        let m = random_mesh(&mut rng);
        loops += self_loops(&m);
        twos += two_gons(&m);
        holes += m.hole_count();
        spheres += m.faces().filter(|&f| m.is_point_sphere(f).unwrap()).count();
        for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
            checked(&m, scheme, 1 + rng.below(2));
        }
    }
    // The generator did produce the special cases it is meant to.
    assert!(loops > 50 && twos > 20 && holes > 50 && spheres > 5);
}

#[test]
fn open_grids_keep_their_boundary_loop() {
    for spec in ["@plane:3:2", "@tri-plane:2:2", "@cylinder"] {
        let m = prim(spec);
        for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
            let out = checked(&m, scheme, 2);
            assert_eq!(out.hole_count(), m.hole_count(), "{spec}");
        }
    }
}

#[test]
fn zero_levels_copy_and_empty_meshes() {
    let m = prim("@cube");
    let same = catmull_clark(&m, 0).unwrap();
    assert_eq!(counts(&same), counts(&m));
    let empty = Mesh::new();
    for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
        let out = subdivide(&empty, scheme, 3).unwrap();
        assert!(out.is_empty());
        // Point-spheres only: a fixed point, even for absurd level counts.
        let mut ps = Mesh::new();
        ps.create_vertex(DVec3::ONE).unwrap();
        let out = subdivide(&ps, scheme, usize::MAX).unwrap();
        assert_eq!(counts(&out), (1, 0, 1));
    }
}

#[test]
fn the_face_cap_is_checked_before_allocating() {
    let m = prim("@cube");
    // 6·4^12 ≈ 100M quads > 50M: refused at once.
    match catmull_clark(&m, 12) {
        Err(SubdivError::TooLarge { level, faces, .. }) => {
            assert_eq!(level, 12);
            assert_eq!(faces, 6 * 4u128.pow(12));
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
    assert!(matches!(
        doo_sabin(&m, usize::MAX),
        Err(SubdivError::TooLarge { .. })
    ));
    // A small cap: 2 levels (96 faces) pass, 3 (384) do not.
    assert!(subdivide_capped(&m, Scheme::CatmullClark, 2, 100).is_ok());
    let err = subdivide_capped(&m, Scheme::CatmullClark, 3, 100).unwrap_err();
    assert!(err.to_string().contains("384 faces"), "{err}");
}

#[test]
fn overflowing_positions_are_an_error_and_the_input_is_kept() {
    // Coordinates near f64::MAX: the face points' sums overflow.
    let mut m = prim("@cube");
    let vs: Vec<_> = m.vertices().collect();
    for v in vs {
        let p = m.position(v).unwrap();
        m.set_position(v, p * 1.5e308).unwrap();
    }
    let before = m.to_raw();
    for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
        let err = subdivide(&m, scheme, 1).unwrap_err();
        assert!(matches!(err, SubdivError::Overflow { .. }), "{err}");
    }
    assert_eq!(m.to_raw(), before);
}

#[test]
fn the_kernel_mesh_and_the_raw_arrays_hold_the_same_surface() {
    // `subdivide` renumbers the vertices for locality but keeps the faces
    // and their walks: face by face, the corner positions are those of the
    // raw arrays.
    let faces = |m: &Mesh| -> Vec<(bool, Vec<[u64; 3]>)> {
        m.faces()
            .map(|f| {
                let ps = m.face_positions(f).unwrap();
                let bits = ps.iter().map(|p| p.to_array().map(f64::to_bits)).collect();
                (m.is_hole(f).unwrap(), bits)
            })
            .collect()
    };
    let mut rng = Rng::new(77);
    for _ in 0..20 {
        let m = random_mesh(&mut rng);
        for scheme in [Scheme::CatmullClark, Scheme::DooSabin] {
            let a = subdivide(&m, scheme, 2).unwrap();
            let b = structured(&m, scheme, 2);
            assert_eq!(counts(&a), counts(&b));
            assert_eq!(faces(&a), faces(&b));
        }
    }
}

// ------------------------------------------------------- the spot oracle

/// Nearest-neighbour matching of points through a uniform grid hash.
struct PointIndex {
    cell: f64,
    map: HashMap<[i64; 3], Vec<usize>>,
    points: Vec<DVec3>,
}

impl PointIndex {
    fn new(points: Vec<DVec3>, cell: f64) -> Self {
        let mut map: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (i, p) in points.iter().enumerate() {
            map.entry(Self::key(*p, cell)).or_default().push(i);
        }
        PointIndex { cell, map, points }
    }
    fn key(p: DVec3, cell: f64) -> [i64; 3] {
        let q = (p / cell).floor();
        [q.x as i64, q.y as i64, q.z as i64]
    }
    /// The nearest point within one cell of `p`, and its distance.
    fn nearest(&self, p: DVec3) -> Option<(usize, f64)> {
        let k = Self::key(p, self.cell);
        let mut best: Option<(usize, f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = self.map.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &i in list {
                        let d = self.points[i].distance(p);
                        if best.is_none_or(|(_, bd)| d < bd) {
                            best = Some((i, d));
                        }
                    }
                }
            }
        }
        best
    }
}

#[test]
fn two_catmull_clark_steps_of_spot_reproduce_spot_quadrangulated() {
    // Reads the shared real meshes (../shared/data/meshes): Keenan Crane's
    // spot control cage and its published two-level Catmull–Clark result.
    let dir = holey_testkit::shared_meshes_or_return!(
        "two_catmull_clark_steps_of_spot_reproduce_spot_quadrangulated"
    );
    let read = |name: &str| match holey_io::read_path(&dir.join(name)).expect("reads") {
        holey_io::MeshFile::Poly(p) => p,
        holey_io::MeshFile::Dlfl(_) => unreachable!("OBJ reads as a soup"),
    };
    let control = dlfl(&read("spot_control_mesh.obj"));
    let oracle = read("spot_quadrangulated.obj");
    let sizes: Vec<usize> = control
        .faces()
        .map(|f| control.face_len(f).unwrap())
        .collect();
    assert_eq!(
        (
            sizes.iter().filter(|&&k| k == 3).count(),
            sizes.iter().filter(|&&k| k == 4).count(),
            sizes.iter().filter(|&&k| k == 5).count()
        ),
        (4, 160, 16)
    );
    let out = checked(&control, Scheme::CatmullClark, 2);
    assert_eq!(out.vertex_count(), oracle.vertex_count());
    assert_eq!(out.face_count(), oracle.face_count());

    // Vertices: each output vertex within 1e-5 of a distinct oracle vertex.
    let index = PointIndex::new(oracle.positions.clone(), 1e-3);
    let mut to_oracle = vec![usize::MAX; out.vertex_count()];
    let mut taken = vec![false; oracle.vertex_count()];
    let mut worst = 0.0f64;
    for v in out.vertices() {
        let p = out.position(v).unwrap();
        let (i, d) = index.nearest(p).expect("an oracle vertex nearby");
        assert!(
            d <= 1e-5,
            "vertex {} at {p} is {d} from the oracle",
            v.index()
        );
        assert!(!taken[i], "two output vertices match oracle vertex {i}");
        taken[i] = true;
        to_oracle[v.index()] = i;
        worst = worst.max(d);
    }
    eprintln!("spot: worst vertex distance to the oracle {worst:.2e}");

    // Faces: the same quads, with the same orientation, as cyclic
    // sequences of matched vertices.
    let canonical = |face: &[usize]| -> Vec<usize> {
        let k = face.iter().enumerate().min_by_key(|(_, v)| **v).unwrap().0;
        face[k..].iter().chain(&face[..k]).copied().collect()
    };
    let mut expected: Vec<Vec<usize>> = oracle
        .faces()
        .map(|f| canonical(&f.iter().map(|&v| v as usize).collect::<Vec<_>>()))
        .collect();
    let mut got: Vec<Vec<usize>> = out
        .faces()
        .map(|f| {
            let vs: Vec<usize> = out
                .face_vertices(f)
                .unwrap()
                .iter()
                .map(|v| to_oracle[v.index()])
                .collect();
            canonical(&vs)
        })
        .collect();
    expected.sort_unstable();
    got.sort_unstable();
    assert_eq!(got, expected, "face connectivity and orientation match");
}
