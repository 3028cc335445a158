//! Checks `analysis` against a deliberately naive reference (hash maps and
//! graph searches written straight from the definitions) on seeded random
//! soups, including broken ones, and checks invariance under renumbering.

use std::collections::hash_map::Entry;
use std::collections::{BTreeMap, HashMap, HashSet};

use holey_mesh::analysis::{MeshInfo, analyze, analyze_with_components, weld_exact};
use holey_mesh::{DVec3, PolyMesh};
use holey_testkit::Rng;

/// The counts the reference computes.
#[derive(Debug, PartialEq)]
struct Reference {
    vertices: usize,
    edges: usize,
    faces: usize,
    invalid_faces: usize,
    components: usize,
    boundary_edges: usize,
    boundary_loops: usize,
    nonmanifold_edges: usize,
    nonmanifold_vertices: usize,
    misoriented_edges: usize,
    degenerate_faces: usize,
    self_loops: usize,
    euler: i64,
    genus: Option<i64>,
    face_sizes: BTreeMap<usize, usize>,
}

/// Connected components of an undirected graph given as adjacency sets,
/// by breadth-first search; returns a label per node.
fn components_of(nodes: &[u32], adj: &HashMap<u32, Vec<u32>>) -> HashMap<u32, usize> {
    let mut label = HashMap::new();
    let mut count = 0;
    for &start in nodes {
        if label.contains_key(&start) {
            continue;
        }
        let mut queue = vec![start];
        label.insert(start, count);
        while let Some(x) = queue.pop() {
            for &y in adj.get(&x).into_iter().flatten() {
                if let Entry::Vacant(e) = label.entry(y) {
                    e.insert(count);
                    queue.push(y);
                }
            }
        }
        count += 1;
    }
    label
}

fn reference(m: &PolyMesh) -> Reference {
    let n = m.positions.len();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut invalid_faces = 0;
    for w in m.face_offsets.windows(2) {
        match m.face_indices.get(w[0] as usize..w[1] as usize) {
            Some(f) if !f.is_empty() && f.iter().all(|&i| (i as usize) < n && i != u32::MAX) => {
                faces.push(f.to_vec())
            }
            _ => invalid_faces += 1,
        }
    }
    let mut verts: Vec<u32> = faces
        .iter()
        .flatten()
        .copied()
        .collect::<HashSet<_>>()
        .into_iter()
        .collect();
    verts.sort();

    // Sides per undirected edge.
    let mut edges: HashMap<(u32, u32), Vec<(u32, u32)>> = HashMap::new();
    for f in faces.iter().filter(|f| f.len() >= 2) {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            edges.entry((a.min(b), a.max(b))).or_default().push((a, b));
        }
    }
    let boundary: Vec<(u32, u32)> = edges
        .iter()
        .filter(|(_, s)| s.len() == 1)
        .map(|(&k, _)| k)
        .collect();

    // Components through faces.
    let mut adj: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in &faces {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            adj.entry(a).or_default().push(b);
            adj.entry(b).or_default().push(a);
        }
    }
    let comp = components_of(&verts, &adj);
    let ncomp = comp.values().collect::<HashSet<_>>().len();

    // Boundary loops: pieces of the boundary-edge graph.
    let mut badj: HashMap<u32, Vec<u32>> = HashMap::new();
    for &(a, b) in &boundary {
        badj.entry(a).or_default().push(b);
        badj.entry(b).or_default().push(a);
    }
    let bverts: Vec<u32> = badj.keys().copied().collect();
    let bcomp = components_of(&bverts, &badj);
    let loop_reps: HashSet<(usize, u32)> = bverts.iter().map(|v| (bcomp[v], *v)).collect();
    let mut loops_per_comp = vec![0i64; ncomp];
    let mut seen = HashSet::new();
    for &(l, v) in &loop_reps {
        if seen.insert(l) {
            loops_per_comp[comp[&v]] += 1;
        }
    }

    // Fans: corners at v are nodes; a corner is linked to the edge keys
    // {v, next} and {v, prev}; corners sharing a key are in one fan.
    let mut corners_at: HashMap<u32, Vec<(usize, usize)>> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for (i, &v) in f.iter().enumerate() {
            corners_at.entry(v).or_default().push((fi, i));
        }
    }
    let mut nonmanifold_vertices = 0;
    let mut nmv_per_comp = vec![0usize; ncomp];
    for (&v, cs) in &corners_at {
        // Bipartite graph: corner nodes 0..k, edge-key nodes k + w.
        let k = cs.len() as u32;
        let mut g: HashMap<u32, Vec<u32>> = HashMap::new();
        let mut key_id: HashMap<u32, u32> = HashMap::new();
        for (ci, &(fi, i)) in cs.iter().enumerate() {
            let f = &faces[fi];
            if f.len() < 2 {
                continue;
            }
            for w in [f[(i + 1) % f.len()], f[(i + f.len() - 1) % f.len()]] {
                let next_id = k + key_id.len() as u32;
                let id = *key_id.entry(w).or_insert(next_id);
                g.entry(ci as u32).or_default().push(id);
                g.entry(id).or_default().push(ci as u32);
            }
        }
        let nodes: Vec<u32> = (0..k).collect();
        let fans = components_of(&nodes, &g);
        let count = (0..k).map(|c| fans[&c]).collect::<HashSet<_>>().len();
        if count > 1 {
            nonmanifold_vertices += 1;
            nmv_per_comp[comp[&v]] += 1;
        }
    }

    let degenerate: Vec<usize> = (0..faces.len())
        .filter(|&f| faces[f].iter().collect::<HashSet<_>>().len() < faces[f].len())
        .collect();
    let mut face_sizes = BTreeMap::new();
    for f in &faces {
        *face_sizes.entry(f.len()).or_insert(0) += 1;
    }
    let nonmanifold_edges = edges.values().filter(|s| s.len() > 2).count();
    let misoriented_edges = edges
        .iter()
        .filter(|((a, b), s)| a != b && s.len() == 2 && s[0] == s[1])
        .count();

    // Genus from per-component χ and loops.
    let mut chi = vec![0i64; ncomp];
    for v in &verts {
        chi[comp[v]] += 1;
    }
    for &(a, _) in edges.keys() {
        chi[comp[&a]] -= 1;
    }
    for f in &faces {
        chi[comp[&f[0]]] += 1;
    }
    let manifold = nonmanifold_edges == 0 && nonmanifold_vertices == 0 && degenerate.is_empty();
    let genus = (manifold && misoriented_edges == 0).then(|| {
        (0..ncomp)
            .map(|c| (2 - chi[c] - loops_per_comp[c]) / 2)
            .sum()
    });
    Reference {
        vertices: verts.len(),
        edges: edges.len(),
        faces: faces.len(),
        invalid_faces,
        components: ncomp,
        boundary_edges: boundary.len(),
        boundary_loops: loop_reps
            .iter()
            .map(|&(l, _)| l)
            .collect::<HashSet<_>>()
            .len(),
        nonmanifold_edges,
        nonmanifold_vertices,
        misoriented_edges,
        degenerate_faces: degenerate.len(),
        self_loops: edges.keys().filter(|(a, b)| a == b).count(),
        euler: verts.len() as i64 - edges.len() as i64 + faces.len() as i64,
        genus,
        face_sizes,
    }
}

fn counts(i: &MeshInfo) -> Reference {
    Reference {
        vertices: i.vertices,
        edges: i.edges,
        faces: i.faces,
        invalid_faces: i.invalid_faces,
        components: i.components,
        boundary_edges: i.boundary_edges,
        boundary_loops: i.boundary_loops,
        nonmanifold_edges: i.nonmanifold_edges,
        nonmanifold_vertices: i.nonmanifold_vertices,
        misoriented_edges: i.misoriented_edges,
        degenerate_faces: i.degenerate_faces,
        self_loops: i.self_loops,
        euler: i.euler,
        genus: i.genus,
        face_sizes: i.face_sizes.clone(),
    }
}

/// A random soup over few vertices (so that edges and vertices are shared
/// in every possible way), sometimes broken.
fn random_soup(rng: &mut Rng) -> PolyMesh {
    let nv = 1 + rng.below(12);
    let positions = (0..nv)
        .map(|_| {
            if rng.chance(0.05) {
                DVec3::new(f64::NAN, 0.0, f64::INFINITY)
            } else {
                DVec3::from_array(rng.point(-1.0, 1.0))
            }
        })
        .collect();
    let mut m = PolyMesh {
        positions,
        ..PolyMesh::new()
    };
    for _ in 0..rng.below(10) {
        let size = [1, 2, 3, 3, 3, 4, 4, 5, 7][rng.below(9)];
        let face: Vec<u32> = (0..size)
            .map(|_| {
                if rng.chance(0.01) {
                    [nv as u32, u32::MAX][rng.below(2)]
                } else {
                    rng.below(nv) as u32
                }
            })
            .collect();
        m.push_face(&face);
    }
    if rng.chance(0.05) {
        // Corrupt an offset.
        let k = rng.below(m.face_offsets.len());
        m.face_offsets[k] = rng.below(m.face_indices.len() + 3) as u32;
    }
    m
}

/// A random soup of triangles and quads drawn from a welded surface made of
/// a few grid patches, so that loops, genus and components are exercised
/// on meshes that are mostly manifold.
fn random_patches(rng: &mut Rng) -> PolyMesh {
    let mut m = PolyMesh::new();
    for _ in 0..1 + rng.below(3) {
        let (n, k) = (2 + rng.below(4) as u32, 2 + rng.below(4) as u32);
        let (wrap_i, wrap_j) = (rng.chance(0.5), rng.chance(0.5));
        let (rows, cols) = (
            if wrap_i { n } else { n + 1 },
            if wrap_j { k } else { k + 1 },
        );
        let base = m.positions.len() as u32;
        for _ in 0..rows * cols {
            m.positions
                .push(DVec3::new(rng.unit(), rng.unit(), rng.unit()));
        }
        let id = |i: u32, j: u32| base + (i % rows) * cols + j % cols;
        for i in 0..n {
            for j in 0..k {
                if rng.chance(0.1) {
                    continue;
                }
                let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                if rng.chance(0.5) {
                    m.push_face(&q);
                } else {
                    m.push_face(&[q[0], q[1], q[2]]);
                    m.push_face(&[q[0], q[2], q[3]]);
                }
            }
        }
    }
    m
}

#[test]
fn agrees_with_naive_reference_on_random_soups() {
    let mut rng = Rng::new(0x5eed_a7a1);
    for round in 0..3000 {
        let m = if round % 2 == 0 {
            random_soup(&mut rng)
        } else {
            random_patches(&mut rng)
        };
        let info = analyze(&m);
        assert_eq!(counts(&info), reference(&m), "round {round}: {m:?}");
        let (with, comps) = analyze_with_components(&m);
        assert_eq!(with, info);
        assert_eq!(comps.len(), info.components);
        assert_eq!(
            comps.iter().map(|c| c.counts.boundary_loops).sum::<usize>(),
            info.boundary_loops
        );
        // Welding never breaks the analysis either.
        let w = analyze(&weld_exact(&m));
        assert_eq!(w.faces, info.faces);
        assert!(w.vertices <= info.vertices);
    }
}

/// Renumbers vertices, reorders faces and, if asked, rotates each face's
/// corners (which changes the fan triangulation of non-planar faces, so
/// area and volume are only compared without it).
fn shuffled(m: &PolyMesh, rng: &mut Rng, rotate: bool) -> PolyMesh {
    let n = m.positions.len();
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for k in (1..n).rev() {
        perm.swap(k, rng.below(k + 1));
    }
    let mut positions = vec![DVec3::ZERO; n];
    for (old, &new) in perm.iter().enumerate() {
        positions[new as usize] = m.positions[old];
    }
    let mut faces: Vec<Vec<u32>> = m
        .faces()
        .map(|f| f.iter().map(|&v| perm[v as usize]).collect())
        .collect();
    for k in (1..faces.len()).rev() {
        faces.swap(k, rng.below(k + 1));
    }
    if rotate {
        for f in &mut faces {
            let r = rng.below(f.len());
            f.rotate_left(r);
        }
    }
    PolyMesh::from_faces(positions, faces)
}

#[test]
fn invariant_under_renumbering() {
    let mut rng = Rng::new(7);
    for _ in 0..300 {
        let m = random_patches(&mut rng);
        let a = analyze(&m);
        let rotated = analyze(&shuffled(&m, &mut rng, true));
        assert_eq!(counts(&a), counts(&rotated));
        let b = analyze(&shuffled(&m, &mut rng, false));
        assert_eq!(counts(&a), counts(&b));
        assert_eq!(a.bbox, b.bbox);
        assert!((a.area - b.area).abs() <= 1e-9 * (1.0 + a.area));
        match (a.volume, b.volume) {
            (Some(x), Some(y)) => assert!((x - y).abs() <= 1e-9 * (1.0 + x.abs())),
            (x, y) => assert_eq!(x, y),
        }
    }
}

#[test]
fn never_panics_on_garbage() {
    let mut rng = Rng::new(99);
    for _ in 0..2000 {
        let n = rng.below(6);
        let m = PolyMesh {
            positions: (0..n)
                .map(|_| DVec3::splat([0.0, -0.0, f64::NAN, 1.0][rng.below(4)]))
                .collect(),
            face_offsets: (0..rng.below(6)).map(|_| rng.below(12) as u32).collect(),
            face_indices: (0..rng.below(10))
                .map(|_| [0, 1, 5, u32::MAX][rng.below(4)].min(rng.below(8) as u32 + 1))
                .collect(),
        };
        let i = analyze(&m);
        assert_eq!(
            i.faces + i.invalid_faces,
            m.face_offsets.len().saturating_sub(1)
        );
        let w = weld_exact(&m);
        assert_eq!(w.face_offsets, m.face_offsets);
        analyze(&w);
    }
}
