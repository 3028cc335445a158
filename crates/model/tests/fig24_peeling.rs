//! Figures 24 and 27 (§V.2.3, §V.3): rind modeling. Punching `k` holes
//! in a genus-`g` crust gives genus `2g + k − 1`; peeling removes the
//! infinitely thin walls between neighbouring holes and the two-gons they
//! leave, exactly as deleting the edges of figure 27 by hand does.
//!
//! Counts, from a closed mesh of `V, E, F` and a peeled region of `k`
//! faces of sizes `n_i` with `w` interior edges (walls) and `x` interior
//! vertices: `V' = 2V − 2x`, `E' = 2E + Σn_i − 4w`, `F' = 2F + Σ(n_i − 2) − 2w`.
#![allow(clippy::unwrap_used)]

mod soups_and_oracles;

use holey_dlfl::Mesh;
use holey_mesh::PolyMesh;
use holey_model::rind::{PunchOutcome, Rind};
use holey_testkit::Rng;
use soups_and_oracles::*;

fn no_two_gons(m: &Mesh) -> bool {
    m.faces().all(|f| m.face_len(f).unwrap() != 2)
}

/// Distinct random faces of a soup.
fn pick(rng: &mut Rng, faces: usize, k: usize) -> Vec<usize> {
    let mut all: Vec<usize> = (0..faces).collect();
    for i in 0..k {
        let j = i + rng.below(faces - i);
        all.swap(i, j);
    }
    all.truncate(k);
    all
}

/// Punches `faces` one by one and checks counts and genus after each.
fn punch_and_check(soup: &PolyMesh, genus: i64, thickness: f64, faces: &[usize]) {
    let m = mesh(soup);
    let (v, e, f) = counts(&m);
    let mut rind = Rind::new(m, thickness).unwrap();
    assert_eq!(counts(rind.mesh()), (2 * v, 2 * e, 2 * f));
    assert_eq!(rind.mesh().genus(), 2 * genus);
    let (mut de, mut df) = (0, 0);
    for (i, &face) in faces.iter().enumerate() {
        let n = soup.face(face).len();
        let out = rind.punch_index(face).unwrap();
        assert_eq!(out.report().unwrap().pipe_edges.len(), n);
        de += n;
        df += n - 2;
        let m = rind.mesh();
        assert_eq!(counts(m), (2 * v, 2 * e + de, 2 * f + df));
        let k = i as i64 + 1;
        assert_eq!(m.genus(), 2 * genus + k - 1, "after {k} punches");
        if faces.len() <= 30 || k % 20 == 0 {
            m.validate().unwrap();
        }
    }
    rind.mesh().validate().unwrap();
    assert_eq!(rind.mesh().topology().component_count(), 1);
}

#[test]
fn punching_k_holes_gives_genus_2g_plus_k_minus_1() {
    let mut rng = Rng::new(24);
    let cube = poly("@cube");
    for k in 1..=6 {
        punch_and_check(&cube, 0, 0.2, &pick(&mut rng, 6, k));
    }
    let sphere = poly("@sphere:2");
    assert_eq!(sphere.face_count(), 320);
    for k in [1, 2, 5, 20, 80] {
        punch_and_check(&sphere, 0, 0.05, &pick(&mut rng, 320, k));
    }
    let torus = poly("@torus:12:8:1:0.3");
    for k in [1, 3, 10, 40] {
        punch_and_check(&torus, 1, 0.05, &pick(&mut rng, 96, k));
    }
}

/// Peels `region` and checks the counts formula, the genus and the
/// number of components against what they should be.
fn peel_and_check(
    soup: &PolyMesh,
    thickness: f64,
    region: &[usize],
    genus: i64,
    components: usize,
) -> Rind {
    let m = mesh(soup);
    let (v, e, f) = counts(&m);
    let mut rind = Rind::new(m, thickness).unwrap();
    let mut walls = 0;
    for &face in region {
        let out = rind.peel_index(face).unwrap();
        let r = out.report().unwrap();
        assert_eq!(r.walls_skipped, 0);
        assert_eq!(r.two_gons_removed, 0, "the wall removal leaves no two-gon");
        walls += r.walls_removed;
        rind.mesh().validate().unwrap();
        assert!(no_two_gons(rind.mesh()));
    }
    let (w, x) = region_interior(soup, region);
    assert_eq!(walls, w);
    let sum_n: usize = region.iter().map(|&i| soup.face(i).len()).sum();
    let m = rind.mesh();
    assert_eq!(
        counts(m),
        (
            2 * v - 2 * x,
            2 * e + sum_n - 4 * w,
            2 * f + sum_n - 2 * region.len() - 2 * w
        )
    );
    assert_eq!(m.genus(), genus);
    assert_eq!(m.topology().component_count(), components);
    rind
}

/// A path of `k` faces, each sharing an edge with the previous one,
/// grown greedily from `start` (from the soup, independently of the rind).
fn strip(soup: &PolyMesh, start: usize, k: usize) -> Vec<usize> {
    let edges = soup_edges(soup);
    let mut path = vec![start];
    while path.len() < k {
        let last = *path.last().unwrap();
        let face = soup.face(last);
        let next = (0..face.len())
            .filter_map(|i| {
                let (a, b) = (face[i], face[(i + 1) % face.len()]);
                edges[&(a.min(b), a.max(b))]
                    .iter()
                    .copied()
                    .find(|&g| g != last)
            })
            // Share an edge with no earlier face, so the strip is a disc
            // with k − 1 interior edges (and no interior vertex, which
            // would need a closed fan).
            .find(|&g| {
                !path.contains(&g) && {
                    let gf = soup.face(g);
                    path[..path.len() - 1].iter().all(|&p| {
                        let pf = soup.face(p);
                        (0..gf.len()).all(|i| {
                            let (a, b) = (gf[i], gf[(i + 1) % gf.len()]);
                            !(pf.contains(&a) && pf.contains(&b))
                        })
                    })
                }
            })
            .unwrap();
        path.push(next);
    }
    path
}

#[test]
fn peeling_a_strip_leaves_one_opening_and_no_walls() {
    // A strip of a cube:3's top row, the whole top, a strip on an
    // icosphere and one along a torus's tube: each a disc, so the rind
    // keeps genus 2g with one component.
    let cube = poly("@cube:3");
    peel_and_check(&cube, 0.1, &[45, 46, 47], 0, 1);
    let top: Vec<usize> = (45..54).collect();
    peel_and_check(&cube, 0.1, &top, 0, 1);
    let sphere = poly("@sphere:2");
    let s = strip(&sphere, 0, 7);
    assert_eq!(region_interior(&sphere, &s), (6, 0));
    peel_and_check(&sphere, 0.05, &s, 0, 1);
    let torus = poly("@torus:12:8:1:0.3");
    // Face i·8 + j: j runs around the tube; i around the z axis.
    peel_and_check(&torus, 0.05, &[40, 48, 56, 64], 2, 1);
    peel_and_check(&torus, 0.05, &[40, 41, 42, 43], 2, 1);
}

#[test]
fn peeling_rings_cuts_the_rind_apart() {
    // The middle row of the four sides of a cube:3 (z = 0): the crust
    // falls into a top cap and a bottom cap, two spheres.
    let cube = poly("@cube:3");
    let ring: Vec<usize> = [12, 13, 14, 32, 31, 30, 41, 40, 39, 23, 22, 21]
        .into_iter()
        .collect();
    let (w, x) = region_interior(&cube, &ring);
    assert_eq!((w, x), (12, 0));
    peel_and_check(&cube, 0.1, &ring, 0, 2);
    // Around a torus's tube: the crust of an annulus, a torus (genus 1).
    let torus = poly("@torus:12:8:1:0.3");
    let meridian: Vec<usize> = (16..24).collect();
    peel_and_check(&torus, 0.05, &meridian, 1, 1);
    // Around the torus's hole (along the outer equator): an annulus again.
    let longitude: Vec<usize> = (0..12).map(|i| i * 8).collect();
    peel_and_check(&torus, 0.05, &longitude, 1, 1);
}

#[test]
fn peeling_every_face_leaves_nothing() {
    let cube = poly("@cube");
    let all: Vec<usize> = (0..6).collect();
    let rind = peel_and_check(&cube, 0.2, &all, 0, 0);
    assert!(rind.mesh().is_empty());
    assert_eq!(rind.mesh().face_count(), 0);
}

#[test]
fn figure_24_punching_neighbours_leaves_a_thin_wall_that_peeling_removes() {
    let cube = poly("@cube:2");
    let mut rind = Rind::new(mesh(&cube), 0.1).unwrap();
    // Faces 20 and 21 of the top share an edge.
    rind.punch_index(20).unwrap();
    let r = rind.punch_index(21).unwrap().report().unwrap().clone();
    assert_eq!(r.walls_removed, 0);
    let m = rind.mesh();
    m.validate().unwrap();
    assert_eq!(m.genus(), 1);
    // The wall: two distinct quadrilaterals on the same four points.
    let walls: Vec<_> = m
        .faces()
        .filter(|&f| m.face_len(f).unwrap() == 4)
        .map(|f| {
            let mut p = m.face_positions(f).unwrap();
            p.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
            (f, p)
        })
        .collect();
    let coincident = walls
        .iter()
        .enumerate()
        .flat_map(|(i, a)| walls[i + 1..].iter().map(move |b| (a, b)))
        .filter(|(a, b)| a.1 == b.1)
        .count();
    assert_eq!(coincident, 1);
    // Peeling 22 (beside 20, touching 21 at a vertex) removes the wall it
    // makes with 20; 23 then removes its walls with 21 and 22. The wall
    // between the two punched faces stays, but its end at the top's
    // centre lost every other attachment: it hangs from the rim as a
    // two-sided flap, which is no handle.
    let r = rind.peel_index(22).unwrap().report().unwrap().clone();
    assert_eq!(r.walls_removed, 1);
    rind.mesh().validate().unwrap();
    let r = rind.peel_index(23).unwrap().report().unwrap().clone();
    assert_eq!(r.walls_removed, 2);
    rind.mesh().validate().unwrap();
    assert!(no_two_gons(rind.mesh()));
    assert_eq!(rind.mesh().genus(), 0);
    let m = rind.mesh();
    let centre = m
        .vertices()
        .find(|&v| m.position(v).unwrap() == holey_dlfl::DVec3::Z)
        .unwrap();
    assert_eq!(m.valence(centre).unwrap(), 2, "the flap's free corner");
}

#[test]
fn figure_27_the_wall_is_a_handle_removed_by_four_edge_deletions() {
    // Punch two neighbours, then delete the wall's edges by hand as in
    // figure 27, and compare with peeling.
    let cube = poly("@cube");
    let mut rind = Rind::new(mesh(&cube), 0.2).unwrap();
    let a = rind.outer_face(0).unwrap();
    let b = rind.outer_face(1).unwrap();
    let ma = rind.matching(a).unwrap();
    let mb = rind.matching(b).unwrap();
    // The edge between outer faces 0 and 1, and its inner copy.
    let m = rind.mesh();
    let e1 = shared_edge(m, a, b);
    let e2 = shared_edge(m, ma.inner, mb.inner);
    rind.punch(a).unwrap();
    rind.punch(b).unwrap();
    let mut m = rind.into_mesh();
    let genus_punched = m.genus();
    assert_eq!(genus_punched, 1);
    let [q1, q2] = m.edge_faces(e1).unwrap();
    let mut beside_e2 = m.edge_faces(e2).unwrap();
    beside_e2.sort();
    let mut beside_e1 = [q1, q2];
    beside_e1.sort();
    assert_eq!(
        beside_e1, beside_e2,
        "the faces beside e1 are those beside e2"
    );
    assert_eq!((m.face_len(q1).unwrap(), m.face_len(q2).unwrap()), (4, 4));
    let others: Vec<_> = m
        .face_corners(q1)
        .unwrap()
        .map(|c| m.corner_edge(c).unwrap().unwrap())
        .filter(|&e| e != e1 && e != e2)
        .collect();
    assert_eq!(others.len(), 2);
    // e1: two quadrilaterals become one hexagon, still a handle.
    m.delete_edge(e1).unwrap();
    m.validate().unwrap();
    let hex = m.edge_faces(e2).unwrap();
    assert_eq!(hex[0], hex[1]);
    assert_eq!(m.face_len(hex[0]).unwrap(), 6);
    assert_eq!(m.genus(), 1);
    // e2: the hexagon falls into two two-gons; the handle is gone.
    m.delete_edge(e2).unwrap();
    m.validate().unwrap();
    assert_eq!(
        m.faces().filter(|&f| m.face_len(f).unwrap() == 2).count(),
        2
    );
    assert_eq!(m.genus(), 0);
    // e3, e4: each two-gon merges into the pipe face beyond it.
    for e in others {
        m.delete_edge(e).unwrap();
        m.validate().unwrap();
    }
    assert!(no_two_gons(&m));
    // Peeling the same two faces gives the same counts.
    let mut peeled = Rind::new(mesh(&cube), 0.2).unwrap();
    peeled.peel_index(0).unwrap();
    peeled.peel_index(1).unwrap();
    assert_eq!(counts(peeled.mesh()), counts(&m));
    assert_eq!(peeled.mesh().genus(), m.genus());
}

#[test]
fn a_punched_neighbour_also_counts_for_peeling() {
    let cube = poly("@cube:3");
    let mut rind = Rind::new(mesh(&cube), 0.1).unwrap();
    rind.punch_index(45).unwrap();
    let out = rind.peel_index(46).unwrap();
    assert_eq!(out.report().unwrap().walls_removed, 1);
    rind.mesh().validate().unwrap();
    assert_eq!(rind.mesh().genus(), 0);
    assert!(matches!(
        rind.peel_index(45).unwrap(),
        PunchOutcome::NotPunchable { .. }
    ));
}

#[test]
fn peeling_random_regions_in_random_order_follows_the_counts() {
    // Any set of faces, peeled in any order: every shared edge becomes a
    // removed wall and every vertex surrounded by peeled faces vanishes.
    let mut rng = Rng::new(27);
    for (spec, thickness) in [
        ("@sphere:1", 0.05),
        ("@torus:8:6:1:0.3", 0.05),
        ("@cube:3", 0.1),
    ] {
        let soup = poly(spec);
        let faces = soup.face_count();
        for _ in 0..6 {
            let k = 1 + rng.below(faces);
            let region = pick(&mut rng, faces, k);
            let (w, x) = region_interior(&soup, &region);
            let m = mesh(&soup);
            let (v, e, f) = counts(&m);
            let mut rind = Rind::new(m, thickness).unwrap();
            let mut walls = 0;
            for &face in &region {
                let r = rind.peel_index(face).unwrap().report().unwrap().clone();
                assert_eq!((r.walls_skipped, r.two_gons_removed), (0, 0));
                walls += r.walls_removed;
                rind.mesh().validate().unwrap();
            }
            assert_eq!(walls, w, "{spec}: {region:?}");
            let sum_n: usize = region.iter().map(|&i| soup.face(i).len()).sum();
            assert_eq!(
                counts(rind.mesh()),
                (
                    2 * v - 2 * x,
                    2 * e + sum_n - 4 * w,
                    2 * f + sum_n - 2 * k - 2 * w
                ),
                "{spec}: {region:?}"
            );
            assert!(no_two_gons(rind.mesh()));
        }
    }
}
