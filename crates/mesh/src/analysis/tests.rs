//! Unit tests on soups generated in code.

use super::*;
use crate::DVec3;

fn p(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The unit cube [0, 1]³ as 6 outward counter-clockwise quads.
fn cube() -> PolyMesh {
    let positions = (0..8)
        .map(|i| p((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64))
        .collect();
    let faces = [
        [0, 2, 3, 1], // z = 0
        [4, 5, 7, 6], // z = 1
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 1
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 1
    ];
    PolyMesh::from_faces(positions, faces)
}

/// An n × m grid of quads in the plane z = 0, optionally glued into a
/// torus (then embedded as a real torus so the volume is meaningful).
fn grid(n: u32, m: u32, torus: bool) -> PolyMesh {
    let (rows, cols) = if torus { (n, m) } else { (n + 1, m + 1) };
    let mut positions = Vec::new();
    for i in 0..rows {
        for j in 0..cols {
            if torus {
                let u = i as f64 / n as f64 * std::f64::consts::TAU;
                let v = j as f64 / m as f64 * std::f64::consts::TAU;
                positions.push(p(
                    (2.0 + v.cos()) * u.cos(),
                    (2.0 + v.cos()) * u.sin(),
                    v.sin(),
                ));
            } else {
                positions.push(p(i as f64, j as f64, 0.0));
            }
        }
    }
    let id = |i: u32, j: u32| (i % rows) * cols + j % cols;
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    PolyMesh::from_faces(positions, faces)
}

fn tri_positions(n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|i| p(i as f64, (i * i % 7) as f64, (i % 3) as f64))
        .collect()
}

#[test]
fn cube_is_a_closed_genus_0_solid() {
    let i = analyze(&cube());
    assert_eq!((i.vertices, i.edges, i.faces), (8, 12, 6));
    assert_eq!(i.euler, 2);
    assert!(i.closed && i.manifold && i.oriented);
    assert_eq!(
        (i.boundary_edges, i.boundary_loops, i.components),
        (0, 0, 1)
    );
    assert_eq!(i.genus, Some(0));
    assert_eq!(i.volume, Some(1.0));
    assert_eq!(i.area, 6.0);
    assert_eq!(i.bbox, Some([[0.0; 3], [1.0; 3]]));
    assert_eq!(i.face_sizes, BTreeMap::from([(4, 6)]));
    assert_eq!(i.unreferenced_vertices, 0);
}

#[test]
fn reversed_cube_has_negative_volume() {
    let c = cube();
    let faces: Vec<Vec<u32>> = c
        .faces()
        .map(|f| f.iter().rev().copied().collect())
        .collect();
    let i = analyze(&PolyMesh::from_faces(c.positions.clone(), faces));
    assert_eq!(i.volume, Some(-1.0));
    assert!(i.oriented);
}

#[test]
fn volume_is_translation_invariant_far_from_origin() {
    let mut c = cube();
    for q in &mut c.positions {
        *q += p(1e6, -3e6, 2e6);
    }
    let i = analyze(&c);
    assert_eq!(i.volume, Some(1.0));
}

#[test]
fn quad_torus_has_genus_1() {
    let i = analyze(&grid(12, 8, true));
    assert_eq!((i.vertices, i.edges, i.faces), (96, 192, 96));
    assert_eq!(i.euler, 0);
    assert!(i.closed && i.manifold && i.oriented);
    assert_eq!(i.genus, Some(1));
    // A 12 × 8 polygonal torus with R = 2, r = 1 is a bit smaller than the
    // smooth one, 2π²Rr² ≈ 39.48.
    let v = i.volume.expect("closed torus has a volume");
    assert!(v > 30.0 && v < 39.48, "{v}");
}

#[test]
fn open_grid_is_a_disk() {
    let i = analyze(&grid(4, 3, false));
    assert_eq!((i.vertices, i.faces), (20, 12));
    assert!(!i.closed && i.manifold && i.oriented);
    assert_eq!(i.boundary_edges, 14);
    assert_eq!(i.boundary_loops, 1);
    assert_eq!(i.euler, 1);
    assert_eq!(i.genus, Some(0));
    assert_eq!(i.volume, None);
    assert_eq!(i.area, 12.0);
}

/// A 5 × 5 grid without the quads at (1, 1) and (3, 3).
fn grid_with_two_holes() -> PolyMesh {
    let g = grid(5, 5, false);
    let faces: Vec<&[u32]> = g
        .faces()
        .enumerate()
        .filter(|&(f, _)| f != 6 && f != 18)
        .map(|(_, q)| q)
        .collect();
    PolyMesh::from_faces(g.positions.clone(), faces)
}

#[test]
fn disk_with_two_holes() {
    let i = analyze(&grid_with_two_holes());
    assert_eq!(i.faces, 23);
    assert_eq!(i.boundary_loops, 3);
    assert_eq!(i.boundary_edges, 20 + 4 + 4);
    assert_eq!(i.euler, -1);
    assert_eq!(i.genus, Some(0));
    assert!(i.manifold && i.oriented && !i.closed);
}

/// A grid of 300 × 300 quads with 3,600 holes (a quad taken out wherever
/// both its row and column are 2 mod 5: no two holes and no hole and the
/// rim share a vertex), large enough that its vertices are counted in
/// many parallel runs: V = 301², E = 2 · 300 · 301, F = 300² − k, so
/// χ = 1 − k, with 4 · 300 + 4k boundary edges in 1 + k loops, genus 0.
#[test]
fn a_large_grid_with_many_holes_is_counted_in_parallel_runs_as_a_disk_with_holes() {
    let n = 300u32;
    let g = grid(n, n, false);
    let hole = |f: usize| {
        let (i, j) = (f as u32 / n, f as u32 % n);
        i % 5 == 2 && j % 5 == 2
    };
    let faces: Vec<&[u32]> = g
        .faces()
        .enumerate()
        .filter(|&(f, _)| !hole(f))
        .map(|(_, q)| q)
        .collect();
    let k = (n * n) as usize - faces.len();
    assert_eq!(k, 60 * 60);
    assert!(g.positions.len() > 4 * crate::PARALLEL_RUN);
    let i = analyze(&PolyMesh::from_faces(g.positions.clone(), faces));
    let side = n as usize;
    assert_eq!(i.vertices, (side + 1) * (side + 1));
    assert_eq!(i.edges, 2 * side * (side + 1));
    assert_eq!(i.faces, side * side - k);
    assert_eq!(i.euler, 1 - k as i64);
    assert_eq!(i.boundary_edges, 4 * side + 4 * k);
    assert_eq!(i.boundary_loops, 1 + k);
    assert_eq!(
        (i.components, i.nonmanifold_edges, i.nonmanifold_vertices),
        (1, 0, 0)
    );
    assert_eq!(i.genus, Some(0));
}

/// [`analyze_topology`] gives what [`analyze`] gives of the same
/// counts, on closed, open, holed, non-manifold, misoriented and soup
/// meshes.
#[test]
fn the_topology_alone_is_what_the_whole_analysis_counts() {
    let meshes = [
        cube(),
        grid(12, 8, true),
        grid(4, 3, false),
        grid_with_two_holes(),
        PolyMesh::from_faces(tri_positions(5), [[0, 1, 2], [0, 3, 4]]),
        PolyMesh::from_faces(tri_positions(6), [[0, 1, 2], [1, 0, 3], [0, 1, 4]]),
        PolyMesh::from_faces(tri_positions(4), [[0, 1, 2], [0, 1, 3]]),
        PolyMesh::from_faces(tri_positions(9), [[0, 1, 2], [3, 4, 5], [6, 7, 8]]),
    ];
    for (k, m) in meshes.iter().enumerate() {
        let i = analyze(m);
        let (c, s, components) = analyze_topology(m);
        assert_eq!(
            (c.vertices, c.edges, c.faces, components),
            (i.vertices, i.edges, i.faces, i.components),
            "mesh {k}"
        );
        assert_eq!(
            (c.boundary_edges, c.boundary_loops, c.nonmanifold_edges),
            (i.boundary_edges, i.boundary_loops, i.nonmanifold_edges),
            "mesh {k}"
        );
        assert_eq!(
            (c.nonmanifold_vertices, c.misoriented_edges),
            (i.nonmanifold_vertices, i.misoriented_edges),
            "mesh {k}"
        );
        assert_eq!(
            (s.closed, s.manifold, s.oriented, s.euler, s.genus),
            (i.closed, i.manifold, i.oriented, i.euler, i.genus),
            "mesh {k}"
        );
    }
}

/// A triangle mesh's topology counted from its triangles
/// (`analyze_triangle_topology`, a corner table filled in parallel runs)
/// is the polygon path's (`analyze_topology` of `PolyMesh::from`): a
/// torus grid large enough for parallel runs (2 × 200 × 100 triangles)
/// with cells taken out, a second piece, an unused vertex, a bow tie; and
/// the same with a triangle that names a vertex out of range, which both
/// leave out.
#[test]
fn the_triangles_topology_is_the_polygon_paths() {
    let (w, h) = (200u32, 100u32);
    let at = |i: u32, j: u32| (i % w) + w * (j % h);
    let mut positions: Vec<DVec3> = (0..w * h)
        .map(|k| p(f64::from(k % w), f64::from(k / w), 0.0))
        .collect();
    let mut triangles = Vec::new();
    for j in 0..h {
        for i in 0..w {
            // Holes: every cell with i and j both multiples of 7.
            if i % 7 == 0 && j % 7 == 0 {
                continue;
            }
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    // A separate bow tie (two triangles sharing a vertex) and an unused
    // vertex.
    let n = positions.len() as u32;
    positions.extend((0..6).map(|k| p(f64::from(k), -5.0, 1.0)));
    triangles.push([n, n + 1, n + 2]);
    triangles.push([n + 2, n + 3, n + 4]);
    let mut mesh = crate::tri::TriMesh {
        positions,
        triangles,
    };
    assert!(mesh.triangles.len() > 2 * crate::PARALLEL_RUN);
    let polygon = |m: &crate::tri::TriMesh| analyze_topology(&PolyMesh::from(m));
    let (c, s, k) = analyze_triangle_topology(&mesh);
    assert_eq!((c.clone(), s, k), polygon(&mesh));
    assert_eq!(k, 2);
    assert_eq!(c.nonmanifold_vertices, 1);
    assert_eq!(c.vertices, (w * h) as usize + 5);
    // A triangle past the last vertex: left out by both.
    mesh.triangles
        .insert(17, [0, 1, mesh.positions.len() as u32]);
    let (c2, s2, k2) = analyze_triangle_topology(&mesh);
    assert_eq!((c2.clone(), s2, k2), polygon(&mesh));
    assert_eq!(c2, c, "the triangle out of range is left out");
}

#[test]
fn bowtie_has_one_nonmanifold_vertex() {
    let i = analyze(&PolyMesh::from_faces(
        tri_positions(5),
        [[0, 1, 2], [0, 3, 4]],
    ));
    assert_eq!(i.nonmanifold_vertices, 1);
    assert_eq!(i.nonmanifold_edges, 0);
    assert!(!i.manifold && i.oriented);
    assert_eq!(i.components, 1);
    // The two triangles' boundaries touch at vertex 0: one piece.
    assert_eq!(i.boundary_loops, 1);
    assert_eq!(i.genus, None);
}

#[test]
fn three_triangles_on_one_edge() {
    let i = analyze(&PolyMesh::from_faces(
        tri_positions(5),
        [[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    ));
    assert_eq!(i.nonmanifold_edges, 1);
    // The edge joins the corners at 0 and at 1 into one fan each.
    assert_eq!(i.nonmanifold_vertices, 0);
    assert_eq!(i.boundary_edges, 6);
    assert_eq!(i.misoriented_edges, 0);
    assert!(!i.manifold);
    assert_eq!(i.genus, None);
}

#[test]
fn flipped_face_misorients_its_edges() {
    let mut c = cube();
    let n = c.face_indices.len();
    c.face_indices[n - 4..].reverse();
    let i = analyze(&c);
    assert_eq!(i.misoriented_edges, 4);
    assert!(i.closed && i.manifold && !i.oriented);
    assert_eq!(i.genus, None);
    assert_eq!(i.volume, None);
    assert_eq!(i.euler, 2);
}

#[test]
fn triangle_soup_is_one_component_per_triangle() {
    let n = 7;
    let faces: Vec<[u32; 3]> = (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let i = analyze(&PolyMesh::from_faces(tri_positions(3 * n as usize), faces));
    let n = n as usize;
    assert_eq!(
        (i.vertices, i.edges, i.faces, i.components),
        (3 * n, 3 * n, n, n)
    );
    assert_eq!((i.boundary_edges, i.boundary_loops), (3 * n, n));
    assert_eq!(i.euler, n as i64);
    assert_eq!(i.genus, Some(0));
    let comps = analyze_components(&PolyMesh::from_faces(
        tri_positions(3 * n),
        (0..n as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]),
    ));
    assert_eq!(comps.len(), n);
    assert!(comps.iter().all(|c| c.surface.euler == 1
        && c.counts.boundary_loops == 1
        && c.surface.genus == Some(0)));
}

#[test]
fn repeated_vertex_is_degenerate() {
    // (0, 1, 0, 2) repeats 0 without a self-loop.
    let i = analyze(&PolyMesh::from_faces(tri_positions(3), [[0u32, 1, 0, 2]]));
    assert_eq!(i.degenerate_faces, 1);
    assert_eq!(i.self_loops, 0);
    assert!(!i.manifold);
    assert_eq!(i.genus, None);
    // Sides 0→1, 1→0, 0→2, 2→0: two edges, each used twice, oppositely.
    assert_eq!((i.edges, i.boundary_edges, i.misoriented_edges), (2, 0, 0));
    // (0, 0, 1): consecutive repeat, so a self-loop edge {0, 0} with one
    // side, and the edge {0, 1} with the opposite sides 0→1 and 1→0.
    let i = analyze(&PolyMesh::from_faces(tri_positions(2), [[0u32, 0, 1]]));
    assert_eq!(i.degenerate_faces, 1);
    assert_eq!(i.self_loops, 1);
    assert_eq!((i.edges, i.boundary_edges, i.boundary_loops), (2, 1, 1));
    assert_eq!(i.euler, 1);
    assert_eq!(i.area, 0.0);
}

#[test]
fn large_face_repeating_a_vertex() {
    // Longer than the pairwise-comparison limit.
    let face: Vec<u32> = (0..20).chain([5]).chain(20..30).collect();
    let i = analyze(&PolyMesh::from_faces(tri_positions(30), [face]));
    assert_eq!(i.degenerate_faces, 1);
    let face: Vec<u32> = (0..30).collect();
    let i = analyze(&PolyMesh::from_faces(tri_positions(30), [face]));
    assert_eq!(i.degenerate_faces, 0);
    assert_eq!(i.face_sizes, BTreeMap::from([(30, 1)]));
    assert_eq!((i.boundary_loops, i.genus), (1, Some(0)));
}

#[test]
fn two_gon_is_a_sphere() {
    let i = analyze(&PolyMesh::from_faces(tri_positions(2), [[0u32, 1]]));
    assert_eq!((i.vertices, i.edges, i.faces, i.two_gons), (2, 1, 1, 1));
    assert!(i.closed && i.manifold && i.oriented);
    assert_eq!(i.euler, 2);
    assert_eq!(i.genus, Some(0));
    assert_eq!(i.volume, Some(0.0));
    assert_eq!(i.area, 0.0);
    // Two 2-gons on the same pair put four sides on one edge.
    let i = analyze(&PolyMesh::from_faces(tri_positions(2), [[0u32, 1], [1, 0]]));
    assert_eq!((i.edges, i.nonmanifold_edges, i.two_gons), (1, 1, 2));
    // (0, 0): two sides on the self-loop {0, 0}, never misoriented.
    let i = analyze(&PolyMesh::from_faces(tri_positions(1), [[0u32, 0]]));
    assert_eq!(
        (i.edges, i.self_loops, i.boundary_edges, i.misoriented_edges),
        (1, 1, 0, 0)
    );
    assert_eq!(i.degenerate_faces, 1);
}

#[test]
fn one_gon_is_a_point_sphere() {
    let i = analyze(&PolyMesh::from_faces(tri_positions(1), [[0u32]]));
    assert_eq!(
        (i.vertices, i.edges, i.faces, i.point_spheres),
        (1, 0, 1, 1)
    );
    assert!(i.closed && i.manifold && i.oriented);
    assert_eq!(i.euler, 2);
    assert_eq!(i.genus, Some(0));
    assert_eq!(i.face_sizes, BTreeMap::from([(1, 1)]));
    // A point sphere at a surface vertex is a second fan there.
    let i = analyze(&PolyMesh::from_faces(
        tri_positions(3),
        [&[0u32, 1, 2][..], &[1]],
    ));
    assert_eq!(i.nonmanifold_vertices, 1);
    assert_eq!(i.components, 1);
    assert_eq!(i.genus, None);
}

#[test]
fn empty_meshes() {
    for m in [PolyMesh::new(), PolyMesh::default()] {
        let i = analyze(&m);
        assert_eq!((i.vertices, i.edges, i.faces, i.components), (0, 0, 0, 0));
        assert_eq!(i.euler, 0);
        assert!(i.closed && i.manifold && i.oriented);
        assert_eq!(i.genus, Some(0));
        assert_eq!(i.volume, Some(0.0));
        assert_eq!(i.bbox, None);
        assert_eq!(i.area, 0.0);
        assert!(i.face_sizes.is_empty());
    }
    let mut m = PolyMesh::new();
    m.positions = tri_positions(4);
    let i = analyze(&m);
    assert_eq!((i.vertices, i.unreferenced_vertices), (0, 4));
    assert_eq!(i.bbox, None);
}

#[test]
fn nan_positions_are_reported_not_propagated() {
    let mut c = cube();
    c.positions[7] = p(f64::NAN, 1.0, 1.0);
    let i = analyze(&c);
    assert_eq!(i.nonfinite_vertices, 1);
    // Topology does not look at positions.
    assert!(i.closed && i.manifold && i.oriented);
    assert_eq!(i.genus, Some(0));
    assert_eq!(i.volume, None);
    assert_eq!(i.bbox, Some([[0.0; 3], [1.0; 3]]));
    // Vertex 7 is the third corner of its three quads, so both fan
    // triangles of each touch it and only the other three quads count.
    assert_eq!(i.area, 3.0);
    let comps = analyze_components(&c);
    assert_eq!(comps[0].volume, None);

    let mut c = cube();
    c.positions
        .iter_mut()
        .for_each(|q| *q = p(f64::INFINITY, f64::NAN, 0.0));
    let i = analyze(&c);
    assert_eq!(
        (i.nonfinite_vertices, i.bbox, i.volume, i.area),
        (8, None, None, 0.0)
    );
}

#[test]
fn invalid_faces_are_skipped_and_counted() {
    let mut m = PolyMesh::from_faces(tri_positions(3), [[0u32, 1, 2]]);
    m.push_face(&[0, 1, 7]); // out of range
    m.push_face(&[]); // no corner
    m.push_face(&[0, u32::MAX, 1]);
    let i = analyze(&m);
    assert_eq!((i.faces, i.invalid_faces), (1, 3));
    assert_eq!((i.vertices, i.edges, i.boundary_loops), (3, 3, 1));

    // Malformed offsets: decreasing, past the end, not starting at 0.
    let m = PolyMesh {
        positions: tri_positions(4),
        face_offsets: vec![1, 4, 2, 99, 3],
        face_indices: vec![0, 1, 2, 3],
    };
    let i = analyze(&m);
    assert_eq!((i.faces, i.invalid_faces), (1, 3));
    assert_eq!(i.face_sizes, BTreeMap::from([(3, 1)]));
    let m = PolyMesh {
        positions: Vec::new(),
        face_offsets: vec![0],
        face_indices: vec![0, 1],
    };
    assert_eq!(analyze(&m).faces, 0);
}

#[test]
fn components_and_their_genera() {
    // A torus (vertices 0..96) next to an open grid and a cube.
    let t = grid(6, 4, true);
    let g = grid(2, 2, false);
    let c = cube();
    let mut positions = t.positions.clone();
    let mut faces: Vec<Vec<u32>> = t.faces().map(<[u32]>::to_vec).collect();
    for m in [&g, &c] {
        let base = positions.len() as u32;
        positions.extend(&m.positions);
        faces.extend(m.faces().map(|f| f.iter().map(|&v| v + base).collect()));
    }
    let m = PolyMesh::from_faces(positions, faces);
    let (info, comps) = analyze_with_components(&m);
    assert_eq!(info.components, 3);
    assert_eq!(component_genera(&m), vec![Some(1), Some(0), Some(0)]);
    assert_eq!(info.genus, Some(1));
    assert!(!info.closed);
    assert_eq!(info.volume, None);
    assert_eq!(comps[2].volume, Some(1.0));
    assert_eq!(comps[1].volume, None);
    assert_eq!(comps[1].counts.boundary_loops, 1);
    assert_eq!(
        comps.iter().map(|c| c.counts.faces).sum::<usize>(),
        info.faces
    );
    assert_eq!(
        comps.iter().map(|c| c.surface.euler).sum::<i64>(),
        info.euler
    );
    assert_eq!(comps.iter().map(|c| c.area).sum::<f64>(), info.area);
}

#[test]
fn component_genus_is_per_component() {
    // A bowtie next to a cube: the mesh has no genus, the cube has.
    let c = cube();
    let mut positions = c.positions.clone();
    positions.extend(tri_positions(5));
    let mut faces: Vec<Vec<u32>> = c.faces().map(<[u32]>::to_vec).collect();
    faces.extend([vec![8, 9, 10], vec![8, 11, 12]]);
    let m = PolyMesh::from_faces(positions, faces);
    assert_eq!(analyze(&m).genus, None);
    assert_eq!(component_genera(&m), vec![Some(0), None]);
}

#[test]
fn weld_merges_equal_positions_first_wins() {
    // Two triangles of a square, stored unwelded, plus an unreferenced
    // duplicate and a signed zero.
    let positions = vec![
        p(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.0),
        p(1.0, 1.0, 0.0),
        p(-0.0, 0.0, 0.0),
        p(1.0, 1.0, 0.0),
        p(0.0, 1.0, 0.0),
        p(1.0, 0.0, 0.0),
    ];
    let m = PolyMesh::from_faces(positions, [[0u32, 1, 2], [3, 4, 5]]);
    let before = analyze(&m);
    assert_eq!(
        (
            before.components,
            before.boundary_loops,
            before.unreferenced_vertices
        ),
        (2, 2, 1)
    );
    let w = weld_exact(&m);
    assert_eq!(
        w.positions,
        vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(1.0, 1.0, 0.0),
            p(0.0, 1.0, 0.0)
        ]
    );
    assert_eq!(w.face_indices, vec![0, 1, 2, 0, 2, 3]);
    assert_eq!(w.face_offsets, m.face_offsets);
    let after = analyze(&w);
    assert_eq!(
        (
            after.vertices,
            after.components,
            after.boundary_loops,
            after.euler
        ),
        (4, 1, 1, 1)
    );
    assert_eq!(after.genus, Some(0));
}

#[test]
fn weld_keeps_bad_indices_bad_and_nans_apart() {
    let nan = p(f64::NAN, 0.0, 0.0);
    let m = PolyMesh {
        positions: vec![nan, nan, p(1.0, 2.0, 3.0), p(1.0, 2.0, 3.0)],
        face_offsets: vec![0, 3, 1],
        face_indices: vec![0, 3, 5, 2],
    };
    let w = weld_exact(&m);
    // The same NaN bits merge; the repeated point merges.
    assert_eq!(w.positions.len(), 2);
    assert_eq!(w.face_indices, vec![0, 1, 3, 1]);
    assert_eq!(w.face_offsets, m.face_offsets);
    assert_eq!(analyze(&w).invalid_faces, 2);
    assert_eq!(weld_exact(&PolyMesh::default()), PolyMesh::default());
}
