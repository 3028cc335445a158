//! A flat disjoint-set forest over `u32` ids.

/// Disjoint sets over `0..n`. Roots are always the smallest id of their
/// set, which keeps every result independent of the order of unions.
pub(crate) struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    /// Makes `0..n` singletons again, reusing the allocation.
    pub(crate) fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n as u32);
    }

    /// The root of `x`'s set (path halving keeps later finds short).
    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        loop {
            let p = self.parent[x as usize];
            if p == x {
                return x;
            }
            let gp = self.parent[p as usize];
            self.parent[x as usize] = gp;
            x = gp;
        }
    }

    /// Merges the sets of `a` and `b`; the smaller root becomes the root.
    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let ra = self.find(a);
        let rb = self.find(b);
        if ra < rb {
            self.parent[rb as usize] = ra;
        } else if rb < ra {
            self.parent[ra as usize] = rb;
        }
    }

    /// Whether `x` is the root of its set.
    pub(crate) fn is_root(&mut self, x: u32) -> bool {
        self.find(x) == x
    }
}

#[cfg(test)]
mod tests {
    use super::UnionFind;

    #[test]
    fn smallest_id_is_root() {
        let mut uf = UnionFind::new(6);
        uf.union(4, 5);
        uf.union(5, 2);
        uf.union(0, 1);
        assert_eq!(uf.find(4), 2);
        assert_eq!(uf.find(5), 2);
        assert_eq!(uf.find(1), 0);
        assert!(uf.is_root(3));
        assert!(!uf.is_root(4));
    }
}
