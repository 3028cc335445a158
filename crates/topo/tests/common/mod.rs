//! Shared helpers of the scenario tests: meshes generated in code and
//! independent checks of the results.
#![allow(dead_code, clippy::unwrap_used)]

use std::collections::HashMap;

use glam::DVec3;
use holey_testkit::Rng;
use holey_topo::{Accumulator, Options, Outcome, TriMesh, self_intersections, topology_change};

/// The motion of `mesh` to `end` as a drag of §4: `frames` equal linear
/// steps accumulated (default options), not yet released.
pub fn dragged(mesh: &TriMesh, end: &[DVec3], frames: u32) -> Accumulator {
    let mut drag = Accumulator::new(mesh.clone(), Options::default()).unwrap();
    for f in 1..=frames {
        let t = f64::from(f) / f64::from(frames);
        let at: Vec<DVec3> = mesh
            .positions
            .iter()
            .zip(end)
            .map(|(p, q)| p.lerp(*q, t))
            .collect();
        drag.advance(&at).unwrap();
    }
    drag
}

/// A primitive as a triangle mesh (polygons fan-triangulated).
pub fn primitive(spec: &str) -> TriMesh {
    let p = holey_shapes::parse_primitive(spec).unwrap();
    p.triangulated()
}

/// One triangle with the given corners, as a mesh of its own.
pub fn triangle(corners: [DVec3; 3]) -> TriMesh {
    TriMesh {
        positions: corners.to_vec(),
        triangles: vec![[0, 1, 2]],
    }
}

/// An axis-aligned box from `lo` to `hi`, outward, 12 triangles.
pub fn cuboid(lo: DVec3, hi: DVec3) -> TriMesh {
    let positions = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    let triangles = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    TriMesh {
        positions,
        triangles,
    }
}

pub fn translate(m: &TriMesh, d: DVec3) -> TriMesh {
    TriMesh {
        positions: m.positions.iter().map(|p| *p + d).collect(),
        triangles: m.triangles.clone(),
    }
}

pub fn join(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let mut m = a.clone();
    m.append(b);
    m
}

/// One frame in which `still` stays where it is and `moving` goes from
/// its positions moved by `from` to its positions moved by `to`: the
/// joined start mesh (`still`'s vertices first) and the end positions.
pub fn still_and_moving(
    still: &TriMesh,
    moving: &TriMesh,
    from: DVec3,
    to: DVec3,
) -> (TriMesh, Vec<DVec3>) {
    let start = join(still, &translate(moving, from));
    let end = still
        .positions
        .iter()
        .copied()
        .chain(moving.positions.iter().map(|&p| p + to))
        .collect();
    (start, end)
}

pub fn volume(m: &TriMesh) -> f64 {
    let c = m.positions.first().copied().unwrap_or(DVec3::ZERO);
    m.triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| m.positions[v as usize] - c);
            p[0].dot(p[1].cross(p[2])) / 6.0
        })
        .sum()
}

/// Directed edge counts.
fn directed(m: &TriMesh) -> HashMap<(u32, u32), usize> {
    let mut d = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            *d.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    d
}

/// Closed and consistently oriented: every directed edge once, its
/// reverse once.
pub fn closed_oriented(m: &TriMesh) -> bool {
    let d = directed(m);
    d.iter()
        .all(|(&(a, b), &n)| n == 1 && d.get(&(b, a)) == Some(&1))
}

/// Edges with one triangle side, and the number of boundary loops
/// (connected components of the boundary-edge graph).
pub fn boundary(m: &TriMesh) -> (usize, usize) {
    holey_testkit::boundary(&m.triangles)
}

/// Connected components through shared vertices.
pub fn components(m: &TriMesh) -> usize {
    split_components(m).len()
}

/// Genus of a closed oriented mesh (all components): Σ (2 − χᵢ)/2.
pub fn genus(m: &TriMesh) -> i64 {
    let v = {
        let mut used = vec![false; m.positions.len()];
        for t in &m.triangles {
            for &x in t {
                used[x as usize] = true;
            }
        }
        used.iter().filter(|&&u| u).count() as i64
    };
    let e = directed(m).len() as i64 / 2;
    let f = m.triangles.len() as i64;
    (2 * components(m) as i64 - (v - e + f)) / 2
}

/// Is point `p` inside the closed mesh? Ray-crossing parity along a
/// slightly irrational direction, in floating point (an oracle independent
/// of the engine's exact predicates).
pub fn inside(m: &TriMesh, p: DVec3) -> bool {
    let dir = DVec3::new(0.5773, 0.5917, 0.5627).normalize();
    let mut crossings = 0;
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| m.positions[v as usize]);
        let (e1, e2) = (b - a, c - a);
        let h = dir.cross(e2);
        let det = e1.dot(h);
        if det.abs() < 1e-300 {
            continue;
        }
        let s = p - a;
        let u = s.dot(h) / det;
        let q = s.cross(e1);
        let v = dir.dot(q) / det;
        let t = e2.dot(q) / det;
        if u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 {
            crossings += 1;
        }
    }
    crossings % 2 == 1
}

/// Volume of the region inside `a` or inside `b` by Monte Carlo sampling.
pub fn union_volume_sampled(a: &TriMesh, b: &TriMesh, samples: usize, seed: u64) -> f64 {
    let bb = |m: &TriMesh| {
        m.positions
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
                (l.min(*p), h.max(*p))
            })
    };
    let (la, ha) = bb(a);
    let (lb, hb) = bb(b);
    let (lo, hi) = (la.min(lb), ha.max(hb));
    let mut rng = Rng::new(seed);
    let hits = (0..samples)
        .filter(|_| {
            let p = DVec3::from_array(rng.in_box(lo.to_array(), hi.to_array()));
            inside(a, p) || inside(b, p)
        })
        .count();
    let d = hi - lo;
    d.x * d.y * d.z * hits as f64 / samples as f64
}

/// Runs the engine and checks that the output is well formed: indices in
/// range, finite positions, no degenerate (repeated-vertex) triangle.
pub fn run(mesh: &TriMesh, end: &[DVec3], options: &Options) -> Outcome {
    let out = topology_change(mesh, end, options).unwrap();
    well_formed(&out.mesh);
    out
}

pub fn well_formed(m: &TriMesh) {
    for t in &m.triangles {
        for &v in t {
            assert!((v as usize) < m.positions.len(), "index out of range");
        }
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "degenerate triangle {t:?}"
        );
    }
    assert!(
        m.positions.iter().all(|p| p.is_finite()),
        "non-finite position"
    );
}

/// Number of intersecting triangle pairs.
pub fn self_intersecting_pairs(m: &TriMesh) -> usize {
    self_intersections(m).unwrap().pairs.len()
}

// ---------------------------------------------------------------------
// Helpers of the figure and robustness scenarios.
// ---------------------------------------------------------------------

/// `m` with every position mapped by `f`.
pub fn map_positions(m: &TriMesh, f: impl Fn(DVec3) -> DVec3) -> TriMesh {
    TriMesh {
        positions: m.positions.iter().map(|&p| f(p)).collect(),
        triangles: m.triangles.clone(),
    }
}

/// `m` scaled about the origin.
pub fn scale(m: &TriMesh, s: f64) -> TriMesh {
    map_positions(m, |p| p * s)
}

/// A triangle soup: every triangle gets its own three vertices.
pub fn soup(m: &TriMesh) -> TriMesh {
    m.unwelded()
}

/// Euler characteristic V − E + F over the vertices used by triangles.
pub fn euler(m: &TriMesh) -> i64 {
    let mut used = vec![false; m.positions.len()];
    let mut edges = std::collections::HashSet::new();
    for t in &m.triangles {
        for k in 0..3 {
            used[t[k] as usize] = true;
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.insert((a.min(b), a.max(b)));
        }
    }
    used.iter().filter(|&&u| u).count() as i64 - edges.len() as i64 + m.triangles.len() as i64
}

/// The largest number of triangles on one undirected edge (2 for a
/// manifold surface, 1 on a boundary).
pub fn max_edge_degree(m: &TriMesh) -> usize {
    holey_testkit::edge_degrees(&m.triangles)
        .into_values()
        .max()
        .unwrap_or(0)
}

/// Triangles split into connected components (through shared vertices):
/// one sub-mesh per component, all sharing the positions of `m`.
pub fn split_components(m: &TriMesh) -> Vec<TriMesh> {
    let mut parent: Vec<u32> = (0..m.positions.len() as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for t in &m.triangles {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut groups: HashMap<u32, Vec<[u32; 3]>> = HashMap::new();
    for t in &m.triangles {
        let r = find(&mut parent, t[0]);
        groups.entry(r).or_default().push(*t);
    }
    let mut keys: Vec<u32> = groups.keys().copied().collect();
    keys.sort_unstable();
    keys.into_iter()
        .map(|k| TriMesh {
            positions: m.positions.clone(),
            triangles: groups.remove(&k).unwrap(),
        })
        .collect()
}

/// Bounding box of the vertices used by triangles.
pub fn used_bounds(m: &TriMesh) -> (DVec3, DVec3) {
    m.triangles
        .iter()
        .flatten()
        .map(|&v| m.positions[v as usize])
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
            (l.min(p), h.max(p))
        })
}

/// Triangles by the bit patterns of their corner positions, rotated to
/// start at the smallest corner (orientation kept), sorted: compares two
/// meshes independently of vertex numbering.
pub fn oriented_triangle_keys(m: &TriMesh) -> Vec<[[u64; 3]; 3]> {
    let mut keys: Vec<[[u64; 3]; 3]> = m
        .triangles
        .iter()
        .map(|t| {
            let c = t.map(|v| {
                let p = m.positions[v as usize];
                [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
            });
            let k = (0..3).min_by_key(|&k| c[k]).unwrap();
            [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
        })
        .collect();
    keys.sort_unstable();
    keys
}

/// As [`oriented_triangle_keys`], orientation ignored.
pub fn unoriented_triangle_keys(m: &TriMesh) -> Vec<[[u64; 3]; 3]> {
    let mut keys: Vec<[[u64; 3]; 3]> = oriented_triangle_keys(m)
        .into_iter()
        .map(|mut k| {
            k.sort_unstable();
            k
        })
        .collect();
    keys.sort_unstable();
    keys
}

/// A closed tube of circular cross-section (`segments` around, first
/// vertex at angle `phase`) swept along `centre`; `up` is perpendicular to
/// every tangent. The ends are closed by fans to the end points.
pub fn tube(centre: &[DVec3], radius: f64, segments: u32, phase: f64, up: DVec3) -> TriMesh {
    let n = centre.len();
    let mut positions = Vec::new();
    for i in 0..n {
        let tangent = (centre[(i + 1).min(n - 1)] - centre[i.saturating_sub(1)]).normalize();
        let side = tangent.cross(up).normalize();
        let up = side.cross(tangent);
        for j in 0..segments {
            let a = phase + std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            positions.push(centre[i] + radius * (a.cos() * side + a.sin() * up));
        }
    }
    let first_cap = positions.len() as u32;
    positions.push(centre[0]);
    positions.push(centre[n - 1]);
    let s = segments;
    let mut triangles = Vec::new();
    for i in 0..n as u32 - 1 {
        for j in 0..s {
            let (a, b) = (i * s + j, i * s + (j + 1) % s);
            let (c, d) = (a + s, b + s);
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    let last = (n as u32 - 1) * s;
    for j in 0..s {
        triangles.push([first_cap, (j + 1) % s, j]);
        triangles.push([first_cap + 1, last + j, last + (j + 1) % s]);
    }
    let mut m = TriMesh {
        positions,
        triangles,
    };
    if volume(&m) < 0.0 {
        for t in &mut m.triangles {
            t.swap(1, 2);
        }
    }
    m
}

/// Reads a mesh of the shared data folder as triangles (faces fanned).
pub fn read_shared(dir: &std::path::Path, name: &str) -> TriMesh {
    let Ok(holey_io::MeshFile::Poly(p)) = holey_io::read_path(&dir.join(name)) else {
        panic!("cannot read {name}")
    };
    p.triangulated()
}

/// Why a mesh is not closed and oriented: (boundary edges, edges with more
/// than two triangles, manifold edges traversed twice the same way).
pub fn closedness_defects(m: &TriMesh) -> (usize, usize, usize) {
    let mut d: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = d.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                e.0 += 1;
            } else {
                e.1 += 1;
            }
        }
    }
    let boundary = d.values().filter(|(f, r)| f + r == 1).count();
    let nonmanifold = d.values().filter(|(f, r)| f + r > 2).count();
    let misoriented = d.values().filter(|(f, r)| f + r == 2 && *f != 1).count();
    (boundary, nonmanifold, misoriented)
}

/// Edges whose two triangles face opposite ways (normals at more than
/// 90°): creases where a deformation folded the surface over itself
/// locally, which no smooth immersion produces at this resolution.
pub fn folds(m: &TriMesh) -> usize {
    let normals: Vec<DVec3> = m
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| m.positions[v as usize]);
            (b - a).cross(c - a).normalize_or_zero()
        })
        .collect();
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (i, t) in m.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            by_edge.entry((a.min(b), a.max(b))).or_default().push(i);
        }
    }
    by_edge
        .values()
        .filter(|v| v.len() == 2 && normals[v[0]].dot(normals[v[1]]) < 0.0)
        .count()
}

/// Vertices whose triangles form more than one fan (joined through shared
/// edges around the vertex): pinch points where sheets touch at a point.
pub fn pinch_vertices(m: &TriMesh) -> usize {
    let mut around: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, t) in m.triangles.iter().enumerate() {
        for &v in t {
            around.entry(v).or_default().push(i);
        }
    }
    let mut pinched = 0;
    for (v, ts) in around {
        // Union the triangles around v that share an edge through v.
        let mut parent: Vec<usize> = (0..ts.len()).collect();
        fn root(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for i in 0..ts.len() {
            for j in i + 1..ts.len() {
                let (a, b) = (m.triangles[ts[i]], m.triangles[ts[j]]);
                let shared = a.iter().filter(|&&u| u != v && b.contains(&u)).count();
                if shared > 0 {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri] = rj;
                }
            }
        }
        let fans = (0..ts.len()).filter(|&i| root(&mut parent, i) == i).count();
        if fans > 1 {
            pinched += 1;
        }
    }
    pinched
}

/// The winding number of `m` at `p`: the sum of its triangles' signed
/// solid angles over 4π (Van Oosterom and Strackee's formula for the
/// solid angle of a triangle), in floating point: an oracle independent
/// of the engine's exact rays.
pub fn winding(m: &TriMesh, p: DVec3) -> f64 {
    let mut sum = 0.0;
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| m.positions[v as usize] - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let numerator = a.dot(b.cross(c));
        let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        sum += 2.0 * numerator.atan2(denominator);
    }
    sum / (4.0 * std::f64::consts::PI)
}

/// Asserts that `out` classifies `samples` random points of the inputs'
/// box (padded by a tenth) as the Boolean `op` of the inputs does by the
/// winding-number rule: its winding number ([`winding`]) is 1 where the
/// rule says inside and 0 elsewhere. A point within rounding of a surface
/// is not a fair question and is skipped; nine in ten must be decided.
pub fn assert_classifies_by_rule(
    inputs: &[&TriMesh],
    op: holey_topo::Operation,
    out: &TriMesh,
    samples: usize,
    seed: u64,
    what: &str,
) {
    let all = inputs
        .iter()
        .fold(TriMesh::default(), |acc, m| join(&acc, m));
    let (lo, hi) = used_bounds(&all);
    let pad = (hi - lo) * 0.1;
    let (lo, hi) = ((lo - pad).to_array(), (hi + pad).to_array());
    let mut rng = Rng::new(seed);
    let mut decided = 0;
    for _ in 0..samples {
        let p = DVec3::from_array(rng.in_box(lo, hi));
        let w: Vec<f64> = inputs.iter().map(|m| winding(m, p)).collect();
        let wo = winding(out, p);
        let unsure = |w: f64| (w - w.round()).abs() > 1e-6;
        if w.iter().any(|&w| unsure(w)) || unsure(wo) {
            continue;
        }
        decided += 1;
        let inside: Vec<bool> = w.iter().map(|w| w.round() >= 1.0).collect();
        assert_eq!(
            wo.round(),
            f64::from(u8::from(op.contains(&inside))),
            "{what}: output winding number {wo} at {p:?} (inputs {w:?})"
        );
    }
    assert!(
        decided * 10 >= samples * 9,
        "{what}: {decided} of {samples} decided"
    );
}
