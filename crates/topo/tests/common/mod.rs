//! Shared helpers of the scenario tests: meshes generated in code and
//! independent checks of the results.
#![allow(dead_code, clippy::unwrap_used)]

use std::collections::HashMap;

use glam::DVec3;
use holey_testkit::Rng;
use holey_topo::{Options, Outcome, TriMesh, self_intersections, topology_change};

/// A primitive as a triangle mesh (polygons fan-triangulated).
pub fn primitive(spec: &str) -> TriMesh {
    let p = holey_shapes::parse_primitive(spec).unwrap();
    let (triangles, _) = p.fan_triangles();
    TriMesh { positions: p.positions, triangles }
}

pub fn translate(m: &TriMesh, d: DVec3) -> TriMesh {
    TriMesh { positions: m.positions.iter().map(|p| *p + d).collect(), triangles: m.triangles.clone() }
}

pub fn join(a: &TriMesh, b: &TriMesh) -> TriMesh {
    let mut m = a.clone();
    let n = m.positions.len() as u32;
    m.positions.extend_from_slice(&b.positions);
    m.triangles.extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    m
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

pub fn area(m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| m.positions[v as usize]);
            0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
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
    d.iter().all(|(&(a, b), &n)| n == 1 && d.get(&(b, a)) == Some(&1))
}

/// Edges with one triangle side, and the number of boundary loops
/// (connected components of the boundary-edge graph).
pub fn boundary(m: &TriMesh) -> (usize, usize) {
    let mut undirected: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *undirected.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let bedges: Vec<(u32, u32)> = undirected.into_iter().filter(|&(_, n)| n == 1).map(|(e, _)| e).collect();
    let mut parent: HashMap<u32, u32> = HashMap::new();
    fn find(p: &mut HashMap<u32, u32>, x: u32) -> u32 {
        let mut r = x;
        while let Some(&q) = p.get(&r) {
            if q == r {
                break;
            }
            r = q;
        }
        p.insert(x, r);
        r
    }
    for &(a, b) in &bedges {
        parent.entry(a).or_insert(a);
        parent.entry(b).or_insert(b);
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        if ra != rb {
            parent.insert(ra, rb);
        }
    }
    let verts: Vec<u32> = parent.keys().copied().collect();
    let mut roots: Vec<u32> = verts.iter().map(|&v| find(&mut parent, v)).collect();
    roots.sort_unstable();
    roots.dedup();
    (bedges.len(), roots.len())
}

/// Connected components through shared vertices.
pub fn components(m: &TriMesh) -> usize {
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
    let mut used = vec![false; m.positions.len()];
    for t in &m.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let mut roots: Vec<u32> = (0..m.positions.len() as u32).filter(|&v| used[v as usize]).map(|v| find(&mut parent, v)).collect();
    roots.sort_unstable();
    roots.dedup();
    roots.len()
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
    let bb = |m: &TriMesh| m.positions.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| (l.min(*p), h.max(*p)));
    let (la, ha) = bb(a);
    let (lb, hb) = bb(b);
    let (lo, hi) = (la.min(lb), ha.max(hb));
    let mut rng = Rng::new(seed);
    let hits = (0..samples)
        .filter(|_| {
            let p = DVec3::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y), rng.range(lo.z, hi.z));
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
        assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "degenerate triangle {t:?}");
    }
    assert!(m.positions.iter().all(|p| p.is_finite()), "non-finite position");
}

/// Number of intersecting triangle pairs.
pub fn self_intersecting_pairs(m: &TriMesh) -> usize {
    self_intersections(m).unwrap().pairs.len()
}
