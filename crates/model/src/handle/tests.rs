use super::*;
use crate::test_util::prim;
use holey_dlfl::RawMesh;
use holey_dlfl::convert::{ImportOptions, to_dlfl};

fn corner(m: &Mesh, face: usize) -> CornerId {
    m.face_corner(m.face_at(face).unwrap()).unwrap()
}

/// Runs `create_handle` expecting `want`, and checks the mesh is untouched.
fn refused(m: &mut Mesh, c1: CornerId, c2: CornerId, p: HandleParams) -> HandleError {
    let before: RawMesh = m.to_raw();
    let err = create_handle(m, c1, c2, &p).unwrap_err();
    assert_eq!(m.to_raw(), before, "the mesh changed on {err}");
    assert_eq!(
        plan_handle(m, c1, c2, &p).unwrap_err().to_string(),
        err.to_string()
    );
    err
}

#[test]
fn bad_parameters_are_refused_and_leave_the_mesh_unchanged() {
    let mut m = prim("@cube");
    let (c0, c5) = (corner(&m, 0), corner(&m, 5));
    assert_eq!(
        refused(&mut m, c0, c5, HandleParams::new(0, 1.0, 1.0)),
        HandleError::NoSegments
    );
    assert!(matches!(
        refused(&mut m, c0, c5, HandleParams::new(3, f64::NAN, 1.0)),
        HandleError::NonFiniteWeight { name: "w1", .. }
    ));
    assert!(matches!(
        refused(&mut m, c0, c5, HandleParams::new(3, 1.0, f64::INFINITY)),
        HandleError::NonFiniteWeight { name: "w2", .. }
    ));
    let other = m.corner_next(c0).unwrap();
    assert_eq!(
        refused(&mut m, c0, other, HandleParams::new(3, 1.0, 1.0)),
        HandleError::SameFace(m.face_at(0).unwrap())
    );
    assert!(matches!(
        refused(&mut m, c0, c5, HandleParams::new(usize::MAX, 1.0, 1.0)),
        HandleError::TooLarge { .. }
    ));
    // A stale corner: one removed by an edge deletion.
    let e = m.corner_edge(c0).unwrap().unwrap();
    let mut n = m.clone();
    n.delete_edge(e).unwrap();
    assert!(matches!(
        refused(&mut n, c0, c5, HandleParams::new(2, 1.0, 1.0)),
        HandleError::Kernel(holey_dlfl::Error::Stale { .. })
    ));
}

#[test]
fn point_spheres_holes_and_arealess_faces_are_refused() {
    let mut m = prim("@cube");
    let (_, sphere, c) = m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
    let c0 = corner(&m, 0);
    assert_eq!(
        refused(&mut m, c0, c, HandleParams::new(2, 1.0, 1.0)),
        HandleError::PointSphere(sphere)
    );
    // A plane has one hole face after its quads.
    let mut p = prim("@plane:2:2");
    let hole = p.faces().find(|&f| p.is_hole(f).unwrap()).unwrap();
    let (a, h) = (corner(&p, 0), p.face_corner(hole).unwrap());
    assert_eq!(
        refused(&mut p, a, h, HandleParams::new(2, 1.0, 1.0)),
        HandleError::HoleFace(hole)
    );
    // Two-gons have no area: fine as a pipe, refused for a curved handle.
    let mut t = Mesh::new();
    let fm = t.create_face_manifold(&[DVec3::ZERO, DVec3::X]).unwrap();
    let (a, b) = (
        t.face_corner(fm.front).unwrap(),
        t.face_corner(fm.back).unwrap(),
    );
    assert_eq!(
        refused(&mut t, a, b, HandleParams::new(3, 1.0, 1.0)),
        HandleError::DegenerateFace(fm.front)
    );
    create_handle(&mut t, a, b, &HandleParams::new(1, 1.0, 1.0)).unwrap();
    t.validate().unwrap();
    assert_eq!(t.genus(), 1);
}

#[test]
fn faces_whose_counts_cannot_be_matched_are_refused() {
    // A triangle whose every edge borders one face G: the back of a
    // triangle sphere merged with the back of a quad sphere.
    let mut m = Mesh::new();
    let tri = m
        .create_face_manifold(&[DVec3::ZERO, DVec3::X, DVec3::Y])
        .unwrap();
    let quad = m
        .create_face_manifold(&[
            DVec3::new(0.0, 0.0, 3.0),
            DVec3::new(1.0, 0.0, 3.0),
            DVec3::new(1.0, 1.0, 3.0),
            DVec3::new(0.0, 1.0, 3.0),
        ])
        .unwrap();
    let (tb, qb) = (
        m.face_corner(tri.back).unwrap(),
        m.face_corner(quad.back).unwrap(),
    );
    m.insert_edge(tb, qb).unwrap();
    let g = m.corner_face(tb).unwrap();
    assert_eq!(m.face_len(g).unwrap(), 9);
    let t = m.face_corner(tri.front).unwrap();
    for k in [1, 3] {
        assert_eq!(
            refused(&mut m, t, tb, HandleParams::new(k, 1.0, 1.0)),
            HandleError::Unmatchable {
                small: tri.front,
                large: g
            }
        );
    }
}

#[test]
fn one_segment_is_exactly_create_pipe() {
    let m0 = prim("@cube");
    let (c0, c5) = (corner(&m0, 0), corner(&m0, 5));
    let mut a = m0.clone();
    let r = create_handle(&mut a, c0, c5, &HandleParams::new(1, 1.0, 1.0)).unwrap();
    let mut b = m0.clone();
    let edges = b.create_pipe(c0, c5).unwrap();
    assert_eq!(a.to_raw(), b.to_raw());
    assert_eq!(r.pipes, vec![edges]);
    assert!(r.sections.is_empty() && r.plan.curve.is_none());
}

#[test]
fn every_step_leaves_a_valid_manifold() {
    // Triangle (a cone's side) to the cone's square base, 4 segments:
    // one subdivision, 3 sections, 4 pipes.
    let mut m = prim("@cone:4");
    let (base, side) = (corner(&m, 0), corner(&m, 2));
    let mut steps = Vec::new();
    let r = create_handle_observed(
        &mut m,
        side,
        base,
        &HandleParams::new(4, 1.0, 1.0),
        |mesh, step| {
            mesh.validate().unwrap();
            steps.push(step);
        },
    )
    .unwrap();
    assert_eq!(steps.len(), 1 + 3 + 4);
    assert!(matches!(steps[0], HandleStep::Subdivided { .. }));
    assert!(matches!(steps[1], HandleStep::Section { index: 1, .. }));
    assert!(matches!(steps[7], HandleStep::Pipe { index: 3 }));
    assert_eq!(r.plan.subdivisions, 1);
    assert_eq!(r.plan.corners, 4);
    assert_eq!(m.genus(), 1);
}

#[test]
fn planning_does_not_touch_the_mesh_and_matches_the_result() {
    let m0 = prim("@cube:3");
    // Two faces of the +z side (faces 45..54), a U-shaped handle.
    let (c1, c2) = (corner(&m0, 45), corner(&m0, 53));
    let p = HandleParams::new(5, 2.0, 2.0);
    let plan = plan_handle(&m0, c1, c2, &p).unwrap();
    let mut m = m0.clone();
    let r = create_handle(&mut m, c1, c2, &p).unwrap();
    assert_eq!(r.plan, plan);
    for (vs, s) in r.sections.iter().zip(&plan.sections) {
        for (v, q) in vs.iter().zip(&s.points) {
            assert_eq!(m.position(*v).unwrap(), *q);
        }
    }
    assert_eq!(plan.orientation, Orientation::AlongTangent);
}

#[test]
fn a_hole_between_opposite_faces_is_straight_and_untwisted() {
    // Negative weights from the top of a cube to its bottom: a tunnel.
    // The reference plane needs no half turn (σ = −1), and each section is
    // the top face translated: vertex j lies straight below vertex j.
    let mut m = prim("@cube");
    let top = m.face_at(5).unwrap();
    let bottom = m.face_at(0).unwrap();
    let c1 = m.face_corner(top).unwrap();
    let v = m.corner_vertex(c1).unwrap();
    let p = m.position(v).unwrap();
    // The bottom corner straight below.
    let c2 = m
        .face_corners(bottom)
        .unwrap()
        .find(|&c| {
            let q = m.position(m.corner_vertex(c).unwrap()).unwrap();
            q.x == p.x && q.y == p.y
        })
        .unwrap();
    let top_pts = m.face_positions(top).unwrap();
    let r = create_handle(&mut m, c1, c2, &HandleParams::new(4, -1.0, -1.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1);
    assert_eq!(r.plan.orientation, Orientation::AgainstTangent);
    let first = m.corner_vertex(c1).unwrap();
    assert_eq!(first, v);
    for (i, s) in r.plan.sections.iter().enumerate() {
        assert!((s.normal - DVec3::Z).length() < 1e-12, "section {i}");
        let start = top_pts.iter().position(|&q| q == p).unwrap();
        for (j, q) in s.points.iter().enumerate() {
            let above = top_pts[(start + j) % 4];
            assert!((q.x - above.x).abs() < 1e-12 && (q.y - above.y).abs() < 1e-12);
        }
    }
}

#[test]
fn opposite_normals_do_not_produce_nan() {
    // Positive weights from the top to the bottom: n1·n_R = −1 at both
    // ends, and the symmetric curve runs along its own axis with cusps.
    for (w1, w2) in [(1.0, 1.0), (0.5, 2.0), (0.0, 0.0), (3.0, -3.0)] {
        let mut m = prim("@cube");
        let (c1, c2) = (corner(&m, 5), corner(&m, 0));
        let r = create_handle(&mut m, c1, c2, &HandleParams::new(6, w1, w2)).unwrap();
        m.validate().unwrap();
        assert_eq!(m.genus(), 1);
        for v in m.vertices() {
            assert!(m.position(v).unwrap().is_finite());
        }
        for s in &r.plan.sections {
            assert!((s.normal.length() - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn huge_weights_fail_cleanly_or_stay_finite() {
    let mut m = prim("@cube");
    let (c1, c2) = (corner(&m, 3), corner(&m, 2));
    let before = m.to_raw();
    match create_handle(&mut m, c1, c2, &HandleParams::new(4, f64::MAX, f64::MAX)) {
        Ok(_) => {
            m.validate().unwrap();
            assert!(m.vertices().all(|v| m.position(v).unwrap().is_finite()));
        }
        Err(HandleError::NonFinite(e)) => {
            assert_eq!((e.what, e.input), ("handle section", ""));
            assert!(e.to_string().contains("the weights are too large"), "{e}");
            assert_eq!(m.to_raw(), before);
        }
        Err(e) => panic!("unexpected {e}"),
    }
}

#[test]
fn faces_sharing_an_edge_or_a_vertex() {
    let m0 = prim("@octahedron");
    let faces: Vec<FaceId> = m0.faces().collect();
    let shared = |a: FaceId, b: FaceId| {
        let va = m0.face_vertices(a).unwrap();
        m0.face_vertices(b)
            .unwrap()
            .iter()
            .filter(|v| va.contains(v))
            .count()
    };
    for want in [2, 1] {
        let (a, b) = faces
            .iter()
            .flat_map(|&a| faces.iter().map(move |&b| (a, b)))
            .find(|&(a, b)| a != b && shared(a, b) == want)
            .unwrap();
        for s in [1usize, 2, 4] {
            let mut m = m0.clone();
            let (c1, c2) = (m.face_corner(a).unwrap(), m.face_corner(b).unwrap());
            create_handle_observed(
                &mut m,
                c1,
                c2,
                &HandleParams::new(s, 1.0, 1.0),
                |mesh, _| {
                    mesh.validate().unwrap();
                },
            )
            .unwrap();
            assert_eq!(
                vef(&m),
                vef_after_handle((6, 12, 8), 3, s),
                "shared {want}, s={s}"
            );
            assert_eq!(m.genus(), 1);
        }
    }
}

/// The centroid and outward unit normal of face `f`, from its positions.
fn centroid_and_normal(m: &Mesh, f: FaceId) -> (DVec3, DVec3) {
    let pts = m.face_positions(f).unwrap();
    (
        geometry::centroid(&pts),
        geometry::vector_area(&pts).normalize(),
    )
}

/// `B(½) = (P0 + 3·P1 + 3·P2 + P3) / 8` for the control points
/// `p1, p1 + w1·n1, p2 + w2·n2, p2`, worked out here from the two faces.
fn bezier_midpoint(m: &Mesh, f1: FaceId, f2: FaceId, w1: f64, w2: f64) -> DVec3 {
    let (p1, n1) = centroid_and_normal(m, f1);
    let (p2, n2) = centroid_and_normal(m, f2);
    (p1 + (p1 + n1 * w1) * 3.0 + (p2 + n2 * w2) * 3.0 + p2) / 8.0
}

#[test]
fn handle_curve_names_round_trip_and_hermite_is_the_default() {
    assert_eq!(HandleCurve::default(), HandleCurve::Hermite);
    assert_eq!(HandleParams::new(3, 1.0, 1.0).curve, HandleCurve::Hermite);
    for c in HandleCurve::ALL {
        assert_eq!(c.name().parse::<HandleCurve>(), Ok(c));
        assert_eq!(c.to_string(), c.name());
    }
    assert_eq!(" Bézier".parse::<HandleCurve>(), Ok(HandleCurve::Bezier));
    let err = "spline".parse::<HandleCurve>().unwrap_err();
    assert!(err.to_string().contains("\"spline\""), "{err}");
}

/// V, E and F of `m`.
fn vef(m: &Mesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

/// V, E and F after a handle of `s` segments between two `d`-gons of a
/// mesh with `(v, e, f)`: s − 1 sections (d vertices, d edges, 2 faces
/// each) and s pipes (each d new edges, 2 faces replaced by d quads).
fn vef_after_handle((v, e, f): (usize, usize, usize), d: usize, s: usize) -> (usize, usize, usize) {
    (
        v + d * (s - 1),
        e + d * (s - 1) + d * s,
        f + 2 * (s - 1) + (d - 2) * s,
    )
}

#[test]
fn bezier_handle_between_two_faces_of_a_cube() {
    // Two quads of one cube, s segments. A handle of s segments between
    // two d-gons makes s − 1 sections (d vertices, d edges, 2 faces each)
    // and s pipes (each d new edges, 2 faces replaced by d quads):
    //   V' = V + d(s − 1), E' = E + d(s − 1) + d·s, F' = F + 2(s − 1) + (d − 2)s,
    // and the faces are in one component, so the genus rises by one.
    let m0 = prim("@cube");
    assert_eq!((vef(&m0), m0.genus()), ((8, 12, 6), 0));
    let d = 4;
    // Faces 0 and 2 are adjacent (the bottom and a side): with positive
    // weights the handle arcs outside the cube. Faces 5 and 0 are the top
    // and the bottom: the curve runs along its own axis through the cube.
    for (a, b) in [(0, 2), (5, 0)] {
        for s in [2usize, 4, 6] {
            let mut m = m0.clone();
            let (f1, f2) = (m.face_at(a).unwrap(), m.face_at(b).unwrap());
            let (c1, c2) = (corner(&m, a), corner(&m, b));
            let (w1, w2) = (1.5, 0.75);
            let mid = bezier_midpoint(&m, f1, f2, w1, w2);
            let p = HandleParams::new(s, w1, w2).with_curve(HandleCurve::Bezier);
            let r = create_handle_observed(&mut m, c1, c2, &p, |mesh, _| {
                mesh.validate().unwrap();
            })
            .unwrap();
            m.validate().unwrap();
            assert_eq!(
                vef(&m),
                vef_after_handle(vef(&m0), d, s),
                "faces {a},{b}, s={s}"
            );
            assert_eq!(m.genus(), 1);
            assert!(matches!(r.plan.curve, Some(HandlePath::Bezier(_))));
            // The middle ring (section s/2, t = ½) is centred on B(½).
            let ring = &r.sections[s / 2 - 1];
            assert_eq!(r.plan.sections[s / 2 - 1].t, 0.5);
            let pts: Vec<DVec3> = ring.iter().map(|&v| m.position(v).unwrap()).collect();
            let c = geometry::centroid(&pts);
            assert!((c - mid).length() < 1e-12, "{c} vs {mid}");
        }
    }
}

#[test]
fn bezier_and_hermite_differ_and_agree_at_tripled_weights() {
    // Same faces and weights: the Bézier curve's inner control points sit
    // |w| above the faces, the Hermite curve leaves at speed w, so the
    // middle rings differ; with the Hermite weights tripled they coincide.
    let m0 = prim("@cube");
    let (c1, c2) = (corner(&m0, 0), corner(&m0, 2));
    let bez = plan_handle(
        &m0,
        c1,
        c2,
        &HandleParams::new(4, 1.0, 1.0).with_curve(HandleCurve::Bezier),
    )
    .unwrap();
    let her = plan_handle(&m0, c1, c2, &HandleParams::new(4, 1.0, 1.0)).unwrap();
    let her3 = plan_handle(&m0, c1, c2, &HandleParams::new(4, 3.0, 3.0)).unwrap();
    assert!(matches!(her.curve, Some(HandlePath::Hermite(_))));
    let mid = |p: &HandlePlan| p.sections[1].centroid;
    assert!((mid(&bez) - mid(&her)).length() > 0.1);
    for (a, b) in bez.sections.iter().zip(&her3.sections) {
        assert!((a.centroid - b.centroid).length() < 1e-12);
        for (p, q) in a.points.iter().zip(&b.points) {
            assert!((*p - *q).length() < 1e-12);
        }
    }
}

/// Two `@cube`s (side 2) side by side, the second shifted by `gap` along x: two
/// components, 16 / 24 / 12.
fn two_cubes(gap: f64) -> Mesh {
    let one = holey_shapes::parse_primitive("@cube").unwrap();
    let mut soup = one.clone();
    soup.append(&one.translated(DVec3::X * gap));
    to_dlfl(&soup, ImportOptions::default()).unwrap().mesh
}

#[test]
fn bezier_handle_between_two_components_joins_them() {
    // The +x face of the first cube to the −x face of the second, facing
    // each other across the gap. The counts are those of one component
    // (above), but the pipe chain joins the two spheres into one: the
    // genus sum stays 0 + 0 = 0 and V − E + F drops from 4 to 2.
    let m0 = two_cubes(3.0);
    assert_eq!(vef(&m0), (16, 24, 12));
    assert_eq!(m0.topology().component_count(), 2);
    let faces: Vec<FaceId> = m0.faces().collect();
    let pick = |want: DVec3, x_range: (f64, f64)| {
        *faces
            .iter()
            .find(|&&f| {
                let (c, n) = centroid_and_normal(&m0, f);
                n.dot(want) > 0.999 && c.x > x_range.0 && c.x < x_range.1
            })
            .unwrap()
    };
    let f1 = pick(DVec3::X, (-1.0, 1.5));
    let f2 = pick(DVec3::NEG_X, (1.5, 4.0));
    let (c1, c2) = (m0.face_corner(f1).unwrap(), m0.face_corner(f2).unwrap());
    let (s, d, w) = (4usize, 4usize, 0.8);
    let mid = bezier_midpoint(&m0, f1, f2, w, w);
    let mut m = m0.clone();
    let p = HandleParams::new(s, w, w).with_curve(HandleCurve::Bezier);
    let r = create_handle(&mut m, c1, c2, &p).unwrap();
    m.validate().unwrap();
    assert_eq!(vef(&m), vef_after_handle(vef(&m0), d, s));
    assert_eq!(m.topology().component_count(), 1);
    assert_eq!(m.genus(), 0);
    let ring: Vec<DVec3> = r.sections[1]
        .iter()
        .map(|&v| m.position(v).unwrap())
        .collect();
    assert!((geometry::centroid(&ring) - mid).length() < 1e-12);
    // Facing faces on one straight line: B(½) is the midpoint of the gap.
    let (p1, _) = centroid_and_normal(&m0, f1);
    let (p2, _) = centroid_and_normal(&m0, f2);
    assert!((mid - (p1 + p2) / 2.0).length() < 1e-12);
}
