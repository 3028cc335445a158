//! The workspace's one disjoint-set forest, over `u32` ids: components of
//! meshes, curves, regions and graphs all use it.

/// Disjoint sets over `0..n`. Roots are always the smallest id of their
/// set, which keeps every result independent of the order of unions.
#[derive(Clone, Debug, Default)]
pub struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
        }
    }

    /// Makes `0..n` singletons again, reusing the allocation.
    pub fn reset(&mut self, n: usize) {
        self.parent.clear();
        self.parent.extend(0..n as u32);
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.parent.len()
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.parent.is_empty()
    }

    /// The root of `x`'s set, its smallest id (path halving keeps later
    /// finds short).
    pub fn find(&mut self, mut x: u32) -> u32 {
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
    /// Returns whether they were apart.
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let ra = self.find(a);
        let rb = self.find(b);
        if ra < rb {
            self.parent[rb as usize] = ra;
        } else if rb < ra {
            self.parent[ra as usize] = rb;
        }
        ra != rb
    }

    /// Whether `x` is the root of its set.
    pub fn is_root(&mut self, x: u32) -> bool {
        self.find(x) == x
    }

    /// Per element, the number of its set, sets numbered from 0 in the
    /// order of their smallest element; and the number of sets.
    pub fn labels(&mut self) -> (Vec<u32>, usize) {
        let n = self.parent.len();
        let mut label = vec![u32::MAX; n];
        let mut next = 0u32;
        let labels = (0..n as u32)
            .map(|x| {
                let r = self.find(x) as usize;
                if label[r] == u32::MAX {
                    label[r] = next;
                    next += 1;
                }
                label[r]
            })
            .collect();
        (labels, next as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::UnionFind;

    #[test]
    fn smallest_id_is_root_and_labels_follow_it() {
        let mut uf = UnionFind::new(6);
        assert!(uf.union(4, 5));
        assert!(uf.union(5, 2));
        assert!(uf.union(0, 1));
        assert!(!uf.union(2, 4));
        assert_eq!(uf.find(4), 2);
        assert_eq!(uf.find(5), 2);
        assert_eq!(uf.find(1), 0);
        assert!(uf.is_root(3));
        assert!(!uf.is_root(4));
        assert_eq!(uf.labels(), (vec![0, 0, 1, 2, 1, 1], 3));
        uf.reset(2);
        assert_eq!((uf.len(), uf.find(1)), (2, 1));
        assert!(UnionFind::default().is_empty());
    }
}
