//! Consistent orientation after a topology change (§3.5, last step).
//!
//! Across every manifold edge (exactly two triangle sides) two triangles
//! agree when they traverse the edge in opposite directions. Each
//! connected component (through manifold edges) is oriented by a
//! breadth-first walk; where the surface is non-orientable the walk meets
//! a contradiction, which is left as it is. Of the two possible
//! orientations of a component, the one that keeps the majority of its
//! triangles (by area) as they were is chosen, so a correctly oriented
//! input is never turned inside out.

use crate::mesh::{TriMesh, sides_by_edge};

/// Flips triangles so that orientations agree across manifold edges where
/// the surface allows; returns the number of triangles flipped.
pub fn orient_consistently(mesh: &mut TriMesh) -> usize {
    let nt = mesh.triangles.len();
    // Sides sorted by undirected edge: (min, max, triangle, forward).
    let sides: Vec<(u32, u32, u32, bool)> = sides_by_edge(&mesh.triangles)
        .into_iter()
        .filter_map(|(key, side)| {
            let t = side / 3;
            let tri = mesh.triangles[t as usize];
            let k = side as usize % 3;
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            (a != b).then_some(((key >> 32) as u32, key as u32, t, a < b))
        })
        .collect();
    // Already consistent (the usual case: a cut keeps each piece's
    // orientation): every component's walk would keep every triangle.
    let disagree = sides.windows(2).enumerate().any(|(i, w)| {
        let (a, b) = (w[0], w[1]);
        (a.0, a.1) == (b.0, b.1)
            && a.3 == b.3
            && a.2 != b.2
            // Exactly two sides on this edge (a manifold edge).
            && (i == 0 || (sides[i - 1].0, sides[i - 1].1) != (a.0, a.1))
            && sides.get(i + 2).is_none_or(|c| (c.0, c.1) != (a.0, a.1))
    });
    if !disagree {
        return 0;
    }
    // Neighbours across manifold edges: (other triangle, same direction?).
    let mut adj: Vec<Vec<(u32, bool)>> = vec![Vec::new(); nt];
    let mut i = 0;
    while i < sides.len() {
        let mut j = i;
        while j < sides.len() && (sides[j].0, sides[j].1) == (sides[i].0, sides[i].1) {
            j += 1;
        }
        if j - i == 2 && sides[i].2 != sides[i + 1].2 {
            let (a, b) = (sides[i], sides[i + 1]);
            let same = a.3 == b.3; // both traverse it the same way: disagree
            adj[a.2 as usize].push((b.2, same));
            adj[b.2 as usize].push((a.2, same));
        }
        i = j;
    }
    let area: Vec<f64> = mesh
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| mesh.positions[v as usize]);
            (p[1] - p[0]).cross(p[2] - p[0]).length()
        })
        .collect();
    let mut flip: Vec<Option<bool>> = vec![None; nt];
    let mut total = 0;
    let mut stack = Vec::new();
    let mut component = Vec::new();
    for root in 0..nt {
        if flip[root].is_some() {
            continue;
        }
        flip[root] = Some(false);
        stack.push(root);
        component.clear();
        while let Some(t) = stack.pop() {
            component.push(t);
            let ft = flip[t].unwrap_or(false);
            for &(u, same) in &adj[t] {
                if flip[u as usize].is_none() {
                    flip[u as usize] = Some(ft ^ same);
                    stack.push(u as usize);
                }
            }
        }
        let (mut kept, mut flipped) = (0.0, 0.0);
        for &t in &component {
            if flip[t] == Some(true) {
                flipped += area[t];
            } else {
                kept += area[t];
            }
        }
        let invert = flipped > kept;
        for &t in &component {
            if flip[t].unwrap_or(false) != invert {
                mesh.triangles[t].swap(1, 2);
                total += 1;
            }
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn strip() -> TriMesh {
        TriMesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::Y,
                DVec3::new(2.0, 0.5, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]],
        }
    }

    #[test]
    fn consistent_meshes_are_untouched() {
        let mut m = strip();
        assert_eq!(orient_consistently(&mut m), 0);
        assert_eq!(m, strip());
    }

    #[test]
    fn a_minority_flipped_triangle_is_fixed() {
        let mut m = strip();
        m.triangles[1] = [0, 3, 2];
        assert_eq!(orient_consistently(&mut m), 1);
        assert_eq!(m.triangles[1], [0, 2, 3]);
        // The first triangle flipped alone: still the minority that moves.
        let mut n = strip();
        n.triangles[0] = [0, 2, 1];
        assert_eq!(orient_consistently(&mut n), 1);
        assert_eq!(n.triangles[0], [0, 1, 2]);
    }

    #[test]
    fn a_mobius_band_does_not_loop() {
        // Four quads in a twisted ring: non-orientable.
        let p: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new((i % 4) as f64, (i / 4) as f64, 0.0))
            .collect();
        let mut m = TriMesh {
            positions: p,
            triangles: vec![
                [0, 1, 5],
                [0, 5, 4],
                [1, 2, 6],
                [1, 6, 5],
                [2, 3, 7],
                [2, 7, 6],
                [3, 4, 0],
                [3, 7, 4],
            ],
        };
        let _ = orient_consistently(&mut m);
        assert_eq!(m.triangles.len(), 8);
    }
}
