//! Oracles on triangle index lists, written from the definitions and
//! independent of the library's own tables and union-find, for tests to
//! check the library against.

use std::collections::{HashMap, HashSet};

/// Disjoint sets over `u32` keys met so far (a map, so the keys need not
/// be dense): join them, then count the groups.
#[derive(Clone, Debug, Default)]
pub struct Groups {
    parent: HashMap<u32, u32>,
}

impl Groups {
    /// No keys yet.
    pub fn new() -> Self {
        Groups::default()
    }

    /// Adds `x` as a group of its own if it is new.
    pub fn add(&mut self, x: u32) {
        self.parent.entry(x).or_insert(x);
    }

    /// The representative of `x`'s group (`x` is added if new).
    pub fn find(&mut self, x: u32) -> u32 {
        let mut r = x;
        while let Some(&q) = self.parent.get(&r) {
            if q == r {
                break;
            }
            r = q;
        }
        self.parent.insert(x, r);
        r
    }

    /// Puts `a` and `b` (added if new) in one group.
    pub fn join(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent.insert(ra.max(rb), ra.min(rb));
        }
    }

    /// The number of groups among the keys added.
    pub fn count(&mut self) -> usize {
        let keys: Vec<u32> = self.parent.keys().copied().collect();
        keys.into_iter()
            .map(|k| self.find(k))
            .collect::<HashSet<_>>()
            .len()
    }
}

/// Every undirected edge `(min, max)` of the triangles with the number of
/// triangle sides on it.
pub fn edge_degrees(triangles: &[[u32; 3]]) -> HashMap<(u32, u32), usize> {
    let mut degree = HashMap::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *degree.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    degree
}

/// The pieces of the graph of `edges`, joined through shared vertices.
pub fn pieces(edges: &[(u32, u32)]) -> usize {
    let mut g = Groups::new();
    for &(a, b) in edges {
        g.join(a, b);
    }
    g.count()
}

/// The connected pieces of the triangles, joined through shared vertices.
pub fn components(triangles: &[[u32; 3]]) -> usize {
    let mut g = Groups::new();
    for t in triangles {
        g.join(t[0], t[1]);
        g.join(t[0], t[2]);
    }
    g.count()
}

/// The edges with one triangle side, and the boundary loops they make
/// (the pieces of their graph).
pub fn boundary(triangles: &[[u32; 3]]) -> (usize, usize) {
    let edges: Vec<(u32, u32)> = edge_degrees(triangles)
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect();
    (edges.len(), pieces(&edges))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_open_strips_have_two_loops_and_one_piece_each() {
        // A quad (two triangles), and a lone triangle apart from it.
        let t = [[0, 1, 2], [0, 2, 3], [10, 11, 12]];
        assert_eq!(boundary(&t), (7, 2));
        assert_eq!(edge_degrees(&t)[&(0, 2)], 2);
        assert_eq!(pieces(&[(0, 1), (1, 2), (5, 6)]), 2);
        assert_eq!(components(&t), 2);
        let mut g = Groups::new();
        g.add(7);
        g.join(1, 2);
        g.join(3, 2);
        assert_eq!(g.count(), 2);
        assert_eq!(g.find(3), g.find(1));
        // A closed octahedron has no boundary.
        assert_eq!(boundary(&crate::octahedron().1), (0, 0));
    }
}
