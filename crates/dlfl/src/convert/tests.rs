use crate::Mesh;
use glam::DVec3;
use holey_testkit::Rng;

use super::*;

/// Imports `soup` splitting what is not manifold, and validates the mesh.
fn split(soup: &PolyMesh) -> Imported {
    let imp = to_dlfl(
        soup,
        ImportOptions {
            split_nonmanifold: true,
        },
    )
    .unwrap();
    imp.mesh.validate().unwrap();
    imp
}

fn cube_soup() -> PolyMesh {
    let (p, quads) = holey_testkit::unit_cube();
    PolyMesh::from_faces(p.map(DVec3::from_array).to_vec(), quads)
}

/// An n×n quad grid in the plane, with the quads for which `skip` is true left out.
fn grid(n: u32, mut skip: impl FnMut(u32, u32) -> bool) -> PolyMesh {
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if !skip(i, j) {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    PolyMesh::from_faces(pos, faces)
}

fn summary(m: &Mesh) -> (usize, usize, usize, usize, usize, i64) {
    let t = m.topology();
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count() - m.hole_count(),
        m.hole_count(),
        t.component_count(),
        t.genus(),
    )
}

#[test]
fn closed_cube_imports_with_file_order_faces() {
    let soup = cube_soup();
    let imp = to_dlfl(&soup, ImportOptions::default()).unwrap();
    imp.mesh.validate().unwrap();
    assert_eq!(summary(&imp.mesh), (8, 12, 6, 0, 1, 0));
    for (i, f) in imp.faces.iter().enumerate() {
        let f = f.unwrap();
        assert_eq!(imp.mesh.face_at(i), Some(f));
        let vs: Vec<u32> = imp
            .mesh
            .face_vertices(f)
            .unwrap()
            .iter()
            .map(|v| v.index() as u32)
            .collect();
        assert_eq!(vs, soup.face(i));
    }
    let back = to_poly(&imp.mesh);
    assert_eq!(back.poly, soup);
}

#[test]
fn open_grid_gets_one_hole_and_exports_unchanged() {
    let soup = grid(4, |_, _| false);
    let imp = to_dlfl(&soup, ImportOptions::default()).unwrap();
    imp.mesh.validate().unwrap();
    assert_eq!(summary(&imp.mesh), (25, 40, 16, 1, 1, 0));
    assert_eq!(imp.report.holes, 1);
    let hole = imp
        .mesh
        .faces()
        .find(|&f| imp.mesh.is_hole(f).unwrap())
        .unwrap();
    assert_eq!(imp.mesh.face_len(hole).unwrap(), 16);
    assert_eq!(to_poly(&imp.mesh).poly, soup);
}

#[test]
fn disk_with_two_holes() {
    let soup = grid(5, |i, j| (i, j) == (1, 1) || (i, j) == (3, 3));
    let imp = to_dlfl(&soup, ImportOptions::default()).unwrap();
    imp.mesh.validate().unwrap();
    let (_, _, f, holes, comps, genus) = summary(&imp.mesh);
    assert_eq!((f, holes, comps, genus), (23, 3, 1, 0));
    assert_eq!(to_poly(&imp.mesh).poly, soup);
}

#[test]
fn holes_touching_at_a_vertex_make_a_non_manifold_vertex() {
    // Removing two diagonal quads leaves their shared corner with two fans.
    let soup = grid(4, |i, j| (i, j) == (1, 1) || (i, j) == (2, 2));
    match to_dlfl(&soup, ImportOptions::default()) {
        Err(ImportError::NonManifoldVertex { vertex, fans, .. }) => {
            assert_eq!(vertex, 2 * 5 + 2);
            assert_eq!(fans, 2);
        }
        other => panic!("expected a non-manifold vertex, got {other:?}"),
    }
    let imp = split(&soup);
    assert_eq!(imp.report.split_vertices, 1);
    assert_eq!(imp.mesh.vertex_count(), 26);
}

#[test]
fn bowtie_is_refused_or_split_into_two_components() {
    let pos = vec![
        DVec3::ZERO,
        DVec3::new(1., 0., 0.),
        DVec3::new(0., 1., 0.),
        DVec3::new(-1., 0., 0.),
        DVec3::new(0., -1., 0.),
    ];
    let soup = PolyMesh::from_faces(pos, [[0u32, 1, 2], [0, 3, 4]]);
    let err = to_dlfl(&soup, ImportOptions::default()).unwrap_err();
    assert!(err.to_string().contains("non-manifold vertex 0"), "{err}");
    let imp = split(&soup);
    assert_eq!(summary(&imp.mesh), (6, 6, 2, 2, 2, 0));
}

#[test]
fn three_faces_on_one_edge() {
    let pos = vec![
        DVec3::ZERO,
        DVec3::new(1., 0., 0.),
        DVec3::new(0., 1., 0.),
        DVec3::new(0., -1., 0.),
        DVec3::new(0., 0., 1.),
    ];
    let soup = PolyMesh::from_faces(pos, [[0u32, 1, 2], [1, 0, 3], [0, 1, 4]]);
    match to_dlfl(&soup, ImportOptions::default()) {
        Err(ImportError::NonManifoldEdge { u, v, count, faces }) => {
            assert_eq!((u, v, count), (0, 1, 3));
            assert_eq!(faces, vec![0, 1, 2]);
        }
        other => panic!("expected a non-manifold edge, got {other:?}"),
    }
    let imp = split(&soup);
    assert_eq!(imp.report.cut_edges, 1);
    // Cut apart, the three triangles share only vertices 0 and 1, each of
    // which is split into one copy per triangle.
    assert_eq!(imp.mesh.topology().component_count(), 3);
}

#[test]
fn a_flipped_face_is_misoriented() {
    let mut soup = cube_soup();
    let f0: Vec<u32> = soup.face(0).iter().rev().copied().collect();
    let rest: Vec<Vec<u32>> = (1..6).map(|f| soup.face(f).to_vec()).collect();
    soup = PolyMesh::from_faces(soup.positions.clone(), std::iter::once(f0).chain(rest));
    let err = to_dlfl(&soup, ImportOptions::default()).unwrap_err();
    assert!(matches!(err, ImportError::Misoriented { .. }), "{err}");
    assert!(err.to_string().contains("same direction"));
    let imp = split(&soup);
    assert_eq!(imp.report.cut_edges, 4);
}

#[test]
fn degenerate_and_short_faces() {
    let pos = (0..4)
        .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
        .collect::<Vec<_>>();
    let soup = PolyMesh::from_faces(pos.clone(), [vec![0u32, 1, 1, 2]]);
    assert_eq!(
        to_dlfl(&soup, ImportOptions::default()).unwrap_err(),
        ImportError::DegenerateFace { face: 0, vertex: 1 }
    );
    let fixed = split(&soup);
    assert_eq!(summary(&fixed.mesh), (3, 3, 1, 1, 1, 0));
    let short = PolyMesh::from_faces(pos, [vec![0u32]]);
    assert_eq!(
        to_dlfl(&short, ImportOptions::default()).unwrap_err(),
        ImportError::ShortFace { face: 0, len: 1 }
    );
    let dropped = split(&short);
    assert_eq!(dropped.report.dropped_faces, 1);
    assert_eq!(dropped.faces, vec![None]);
}

#[test]
fn bad_soups_are_errors() {
    let soup = PolyMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], [[0u32, 1, 7]]);
    assert!(matches!(
        to_dlfl(&soup, ImportOptions::default()),
        Err(ImportError::Soup(_))
    ));
    let nan = PolyMesh::from_faces(
        vec![DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0., 0.)],
        [[0u32, 1, 2]],
    );
    let err = to_dlfl(&nan, ImportOptions::default()).unwrap_err();
    assert!(err.to_string().contains("vertex 2"), "{err}");
}

#[test]
fn unreferenced_vertices_are_dropped_and_mapped() {
    let mut soup = cube_soup();
    soup.positions.insert(0, DVec3::splat(9.0));
    for i in &mut soup.face_indices {
        *i += 1;
    }
    let imp = to_dlfl(&soup, ImportOptions::default()).unwrap();
    assert_eq!(imp.report.unreferenced_vertices, 1);
    assert_eq!(imp.vertices[0], None);
    assert_eq!(
        imp.mesh.position(imp.vertices[1].unwrap()).unwrap(),
        DVec3::ZERO
    );
}

#[test]
fn export_drops_self_loops_and_short_faces() {
    let mut m = to_dlfl(&cube_soup(), ImportOptions::default())
        .unwrap()
        .mesh;
    let v = m.vertices().next().unwrap();
    let cs: Vec<_> = m.vertex_corners(v).unwrap().collect();
    let lp = m.insert_edge(cs[0], cs[1]).unwrap();
    assert!(m.is_self_loop(lp).unwrap());
    let out = to_poly(&m);
    assert_eq!(out.dropped_self_loops, 2);
    assert_eq!(out.poly.face_count(), 5);
    assert!(out.poly.faces().any(|f| f.len() == 8));
    // A point-sphere is omitted.
    m.create_vertex(DVec3::splat(4.0)).unwrap();
    let out2 = to_poly(&m);
    assert_eq!(out2.dropped_faces, 1);
    assert_eq!(out2.poly.positions.len(), 8);
}

#[test]
fn infer_edges_for_dlfl_files_without_edge_lines() {
    let imp = to_dlfl(&grid(3, |_, _| false), ImportOptions::default()).unwrap();
    let mut raw = imp.mesh.to_raw();
    let expected = raw.edges.len();
    raw.edges.clear();
    infer_edges(&mut raw).unwrap();
    assert_eq!(raw.edges.len(), expected);
    Mesh::from_raw(&raw).unwrap().validate().unwrap();
    // An open face list has unpaired half-edges.
    let mut open = raw.clone();
    open.face_offsets.pop();
    let n = *open.face_offsets.last().unwrap() as usize;
    open.face_vertices.truncate(n);
    open.holes.pop();
    assert!(matches!(
        infer_edges(&mut open),
        Err(ImportError::Unpaired { .. })
    ));
}

#[test]
fn random_patches_never_panic_and_split_always_imports() {
    let mut rng = Rng::new(0x5eed);
    for round in 0..300 {
        let n = 2 + rng.below(5) as u32;
        let p = rng.range(0.2, 0.9);
        let flips = rng.chance(0.3);
        let mut soup = grid(n, |_, _| rng.unit() > p);
        if flips && soup.face_count() > 0 {
            let k = rng.below(soup.face_count());
            let mut faces: Vec<Vec<u32>> = soup.faces().map(|f| f.to_vec()).collect();
            faces[k].reverse();
            soup = PolyMesh::from_faces(soup.positions.clone(), faces);
        }
        if let Ok(imp) = to_dlfl(&soup, ImportOptions::default()) {
            imp.mesh.validate().unwrap();
            assert_eq!(
                to_poly(&imp.mesh).poly.faces().count(),
                soup.face_count(),
                "round {round}"
            );
        }
        let imp = split(&soup);
        let faces = imp.mesh.face_count() - imp.mesh.hole_count();
        assert_eq!(faces, soup.face_count(), "round {round}");
    }
}
