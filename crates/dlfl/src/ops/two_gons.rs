use crate::mesh::Mesh;

impl Mesh {
    /// Removes two-gons by deleting one of their edges, which merges the
    /// two-gon into the face across that edge (§V.2.3, figure 29). Two-gons
    /// carry no geometry but spoil smoothing (figure 28). Repeats until no
    /// removable two-gon is left; hole faces are never merged away, and a
    /// two-gon bordered only by itself (a lone edge) is kept. Returns the
    /// number of edges deleted.
    pub fn remove_two_gons(&mut self) -> usize {
        let mut work: Vec<u32> = self
            .faces
            .live_indices()
            .filter(|&f| self.f(f).len == 2)
            .collect();
        let mut removed = 0;
        while let Some(f) = work.pop() {
            if !self.faces.is_live(f) || self.f(f).len != 2 || self.f(f).hole {
                continue;
            }
            let x = self.f(f).corner;
            let y = self.c(x).next;
            for c in [x, y] {
                let e = self.c(c).edge;
                let far = self.mate(c, e);
                let g = self.c(far).face;
                if g == f || self.f(g).hole {
                    continue;
                }
                self.delete_edge_raw(e);
                removed += 1;
                // The merged face survives under one of the two ids.
                let merged = self.c(far).face;
                if self.f(merged).len == 2 {
                    work.push(merged);
                }
                break;
            }
        }
        removed
    }
}
