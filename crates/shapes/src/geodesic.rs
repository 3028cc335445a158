//! Primitives made from the icosahedron (issue 18): the soccer ball
//! (truncated icosahedron) and the geodesic sphere of any frequency.

use holey_mesh::PolyMesh;

use crate::grid::with_capacity;
use crate::solids::{ICOSAHEDRON_FACES, icosahedron_vertices};

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// The neighbours of each icosahedron vertex, counter-clockwise seen from
/// outside, starting at the lowest-numbered one.
fn icosahedron_rings() -> [[u32; 5]; 12] {
    // In a counter-clockwise face (a, b, c) the neighbour after b around
    // a, counter-clockwise, is c.
    let mut after = [[u32::MAX; 12]; 12];
    for &[a, b, c] in &ICOSAHEDRON_FACES {
        after[a as usize][b as usize] = c;
        after[b as usize][c as usize] = a;
        after[c as usize][a as usize] = b;
    }
    let mut rings = [[0u32; 5]; 12];
    for (a, ring) in rings.iter_mut().enumerate() {
        let first = (0..12u32).find(|&b| after[a][b as usize] != u32::MAX);
        let mut b = first.unwrap_or(0);
        for slot in ring.iter_mut() {
            *slot = b;
            b = after[a][b as usize];
        }
    }
    rings
}

/// The soccer ball: the icosahedron truncated at a third of every edge,
/// 12 regular pentagons and 20 regular hexagons, circumradius √3.
/// V = 60, E = 90, F = 32.
///
/// Vertex `5a + j` is a third of the way from icosahedron vertex `a` (in
/// [`crate::icosahedron`] order) to its `j`-th neighbour, neighbours
/// counter-clockwise seen from outside starting at the lowest-numbered;
/// all are then scaled to radius √3. Faces 0–11 are the pentagons, face
/// `a` being `(5a, …, 5a + 4)` around icosahedron vertex `a`; face
/// `12 + t` is the hexagon of icosahedron face `t = (a, b, c)`, starting
/// at the point near `a` towards `b`: `(a→b, b→a, b→c, c→b, c→a, a→c)`.
pub fn soccer_ball() -> PolyMesh {
    let ico = icosahedron_vertices(SQRT3);
    let rings = icosahedron_rings();
    let mut m = with_capacity(60, 32, 60 + 120);
    for (a, ring) in rings.iter().enumerate() {
        for &b in ring {
            let p = ico[a] + (ico[b as usize] - ico[a]) / 3.0;
            m.positions.push(p.normalize() * SQRT3);
        }
    }
    let point = |a: u32, b: u32| -> u32 {
        let j = rings[a as usize].iter().position(|&x| x == b).unwrap_or(0);
        5 * a + j as u32
    };
    for a in 0..12u32 {
        let p: Vec<u32> = (0..5).map(|j| 5 * a + j).collect();
        m.push_face(&p);
    }
    for &[a, b, c] in &ICOSAHEDRON_FACES {
        m.push_face(&[
            point(a, b),
            point(b, a),
            point(b, c),
            point(c, b),
            point(c, a),
            point(a, c),
        ]);
    }
    m
}

/// [`crate::geodesic`] without the check of its parameters: the spec
/// table calls it with parameters its parser checked.
pub(crate) fn geodesic(n: u32) -> PolyMesh {
    let ico = icosahedron_vertices(1.0);
    let nn = n as usize;
    let vertices = 10 * nn * nn + 2;
    let faces = 20 * nn * nn;
    let mut m = with_capacity(vertices, faces, 3 * faces);
    m.positions.extend(ico.iter().copied());
    // Inner edge points: edge (lo, hi) → index of its first point.
    let mut edge_start = std::collections::HashMap::new();
    for &[a, b, c] in &ICOSAHEDRON_FACES {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            let key = (x.min(y), x.max(y));
            if edge_start.contains_key(&key) {
                continue;
            }
            edge_start.insert(key, m.positions.len() as u32);
            let (p, q) = (ico[key.0 as usize], ico[key.1 as usize]);
            for k in 1..n {
                let t = f64::from(k) / f64::from(n);
                m.positions.push(p.lerp(q, t).normalize());
            }
        }
    }
    // The point `k` steps from `from` along the edge to `to`.
    let on_edge = |from: u32, to: u32, k: u32| -> u32 {
        let key = (from.min(to), from.max(to));
        let start = edge_start.get(&key).copied().unwrap_or(0);
        if from == key.0 {
            start + k - 1
        } else {
            start + (n - k) - 1
        }
    };
    for &[a, b, c] in &ICOSAHEDRON_FACES {
        let inner_start = m.positions.len() as u32;
        let (pa, pb, pc) = (ico[a as usize], ico[b as usize], ico[c as usize]);
        let nf = f64::from(n);
        for v in 1..n {
            for u in 1..n - v {
                let p = pa + (pb - pa) * (f64::from(u) / nf) + (pc - pa) * (f64::from(v) / nf);
                m.positions.push(p.normalize());
            }
        }
        // Inner row v holds n − 1 − v points (u = 1 … n − v − 1).
        let row_start = |v: u32| -> u32 { (1..v).map(|r| n - 1 - r).sum::<u32>() + inner_start };
        let index = |u: u32, v: u32| -> u32 {
            match (u, v) {
                (0, 0) => a,
                (u, 0) if u == n => b,
                (0, v) if v == n => c,
                (u, 0) => on_edge(a, b, u),
                (0, v) => on_edge(a, c, v),
                (u, v) if u + v == n => on_edge(b, c, v),
                (u, v) => row_start(v) + u - 1,
            }
        };
        for v in 0..n {
            for u in 0..n - v {
                m.push_face(&[index(u, v), index(u + 1, v), index(u, v + 1)]);
                if u + v + 2 <= n {
                    m.push_face(&[index(u + 1, v), index(u + 1, v + 1), index(u, v + 1)]);
                }
            }
        }
    }
    m
}
