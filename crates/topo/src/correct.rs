//! Error correction of the raw parity field (§3.4 and appendix B).
//!
//! The raw parity can be corrupted by holes and boundaries of the surface
//! and by numerical error. Two schemes turn it into a corrected field:
//!
//! - **Graph partitioning** (the paper's choice, [`Scheme::Partition`]), in
//!   two stages per connected component of the vertex–edge graph:
//!   1. minimise the quadratic energy (3.2)
//!      `Σ_{E_o} w_ij (x_i − x_j)² + Σ_{E_c, r_i≠r_j} w_ij (x_i − x_j − (r_i − r_j))² + γ Σ (x_i − r_i)²`
//!      where `E_c` are the edges cut by an intersection curve (their
//!      coupling is dropped, or replaced by the "pry apart" term when the
//!      raw parities differ) and `E_o` the others; `r = +1` for even, `−1`
//!      for odd. It is the linear system of appendix B, solved by a sparse
//!      Cholesky factorisation (faer);
//!   2. round `x` by a sweep cut: the threshold minimising (3.3),
//!      `2π · (area whose label disagrees with r) + (wrong boundary length)²`,
//!      where wrong boundary is new boundary on uncut edges plus unused
//!      intersection edges (cut edges whose two ends got one label).
//! - **Majority voting** ([`Scheme::Majority`]), the paper's first scheme:
//!   an area-weighted vote of the raw parity within each region bounded by
//!   intersection curves.
//!
//! Two exact shortcuts keep the cost local: a component whose raw parity
//! changes only across cut edges has energy 0 at `x = r`, so `r` is the
//! minimiser and is kept without solving; and a component with a constant
//! raw parity and no cut edge is left as it is.
//!
//! **Scale.** The authors' code sets γ = 10⁻²/(total area). Taken literally,
//! the balance between the length-weighted smoothness terms and γ would
//! change with the mesh's scale, and the system becomes ill-conditioned
//! for large coordinates. We therefore measure lengths in units of
//! √(total area) — which makes the total area 1 and γ = 10⁻² exactly the
//! authors' value — so the result does not depend on the mesh's scale.

use faer::Side;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};

use crate::union_find::UnionFind;

/// Which error-correction scheme to run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scheme {
    /// Two-stage graph partitioning (§3.4, the paper's choice).
    #[default]
    Partition,
    /// Area-weighted majority vote per intersection-bounded region.
    Majority,
}

/// The graph the correction runs on.
pub struct Graph<'a> {
    /// Number of vertices.
    pub vertices: usize,
    /// Edge end points.
    pub ends: &'a [[u32; 2]],
    /// Dual edge lengths ([`crate::weights::Weights::edge`]).
    pub edge_weight: &'a [f64],
    /// Dual vertex areas ([`crate::weights::Weights::vertex`]).
    pub vertex_weight: &'a [f64],
    /// Edges crossed by an intersection curve.
    pub cut: &'a [bool],
    /// Total area, the unit of the energy.
    pub total_area: f64,
}

/// What the correction did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Correction {
    /// Corrected parity: `true` = odd (to be deleted).
    pub odd: Vec<bool>,
    /// The continuous field of stage 1 (`r` where no solve was needed).
    pub field: Vec<f64>,
    /// Components whose linear system was solved.
    pub solved_components: usize,
    /// Unknowns in the solved systems.
    pub solved_unknowns: usize,
    /// Components whose factorisation failed; their raw parity was kept.
    pub failed_components: usize,
}

/// The authors' regulariser, in units where the total area is 1.
pub const GAMMA: f64 = 1e-2;

/// Labels connected components; `skip_cut` leaves cut edges out.
fn components(g: &Graph, skip_cut: bool) -> (Vec<u32>, usize) {
    let mut sets = UnionFind::new(g.vertices);
    for (e, &[a, b]) in g.ends.iter().enumerate() {
        if !(skip_cut && g.cut[e]) {
            sets.union(a, b);
        }
    }
    sets.labels()
}

/// Corrects the raw parity `raw_odd` (`true` = odd) on graph `g`.
pub fn correct(g: &Graph, raw_odd: &[bool], scheme: Scheme) -> Correction {
    match scheme {
        Scheme::Partition => partition(g, raw_odd),
        Scheme::Majority => majority(g, raw_odd),
    }
}

fn sign(odd: bool) -> f64 {
    if odd { -1.0 } else { 1.0 }
}

/// Majority voting per region bounded by intersection curves.
fn majority(g: &Graph, raw_odd: &[bool]) -> Correction {
    let (label, n) = components(g, true);
    let mut vote = vec![0.0f64; n];
    for v in 0..g.vertices {
        vote[label[v] as usize] += sign(raw_odd[v]) * g.vertex_weight[v];
    }
    // Ties (including weightless regions) keep each vertex's own parity.
    let odd: Vec<bool> = (0..g.vertices)
        .map(|v| {
            let s = vote[label[v] as usize];
            if s == 0.0 { raw_odd[v] } else { s < 0.0 }
        })
        .collect();
    let field = odd.iter().map(|&o| sign(o)).collect();
    Correction {
        odd,
        field,
        ..Correction::default()
    }
}

/// Per-vertex adjacency in compressed rows: (neighbour, edge).
fn adjacency(g: &Graph) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut start = vec![0u32; g.vertices + 1];
    for &[a, b] in g.ends {
        start[a as usize + 1] += 1;
        start[b as usize + 1] += 1;
    }
    for i in 0..g.vertices {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut adj = vec![(0u32, 0u32); start[g.vertices] as usize];
    for (e, &[a, b]) in g.ends.iter().enumerate() {
        adj[fill[a as usize] as usize] = (b, e as u32);
        fill[a as usize] += 1;
        adj[fill[b as usize] as usize] = (a, e as u32);
        fill[b as usize] += 1;
    }
    (start, adj)
}

fn partition(g: &Graph, raw_odd: &[bool]) -> Correction {
    let (label, n) = components(g, false);
    let r: Vec<f64> = raw_odd.iter().map(|&o| sign(o)).collect();
    let mut field = r.clone();
    let mut odd = raw_odd.to_vec();
    let mut out = Correction::default();

    // Which components have a defect: an uncut edge across a parity change.
    let mut defect = vec![false; n];
    for (e, &[a, b]) in g.ends.iter().enumerate() {
        if !g.cut[e] && raw_odd[a as usize] != raw_odd[b as usize] {
            defect[label[a as usize] as usize] = true;
        }
    }
    if !defect.iter().any(|&d| d) {
        out.odd = odd;
        out.field = field;
        return out;
    }
    let length_unit = g.total_area.sqrt();
    let area_unit = g.total_area;
    let (start, adj) = adjacency(g);
    // Members of each defective component, in vertex order.
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); n];
    for v in 0..g.vertices {
        if defect[label[v] as usize] {
            members[label[v] as usize].push(v as u32);
        }
    }
    let mut local = vec![u32::MAX; g.vertices];
    for comp in members.iter().filter(|m| !m.is_empty()) {
        for (i, &v) in comp.iter().enumerate() {
            local[v as usize] = i as u32;
        }
        let m = comp.len();
        let mut triplets = Vec::with_capacity(m * 7);
        let mut rhs = vec![0.0; m];
        for (i, &v) in comp.iter().enumerate() {
            let mut diag = GAMMA;
            rhs[i] = GAMMA * r[v as usize];
            for &(u, e) in &adj[start[v as usize] as usize..start[v as usize + 1] as usize] {
                let w = g.edge_weight[e as usize] / length_unit;
                let pry = g.cut[e as usize];
                if pry && raw_odd[u as usize] == raw_odd[v as usize] {
                    continue; // a cut edge with equal raw parity: no coupling
                }
                if pry {
                    rhs[i] += w * (r[v as usize] - r[u as usize]);
                }
                if u != v {
                    triplets.push(Triplet::new(i, local[u as usize] as usize, -w));
                    diag += w;
                }
            }
            triplets.push(Triplet::new(i, i, diag));
        }
        let solved = SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &triplets)
            .ok()
            .and_then(|a| a.sp_cholesky(Side::Lower).ok())
            .map(|llt| llt.solve(faer::Mat::from_fn(m, 1, |i, _| rhs[i])));
        let Some(x) = solved else {
            out.failed_components += 1;
            continue;
        };
        out.solved_components += 1;
        out.solved_unknowns += m;
        for (i, &v) in comp.iter().enumerate() {
            let xi = x[(i, 0)];
            field[v as usize] = if xi.is_finite() { xi } else { r[v as usize] };
        }
        // Stage 2: sweep cut over the component's vertices sorted by x.
        let mut order: Vec<u32> = comp.clone();
        order.sort_by(|&a, &b| field[a as usize].total_cmp(&field[b as usize]));
        let mut label_odd = vec![false; m]; // start: all even
        let mut disagree: f64 = comp
            .iter()
            .filter(|&&v| raw_odd[v as usize])
            .map(|&v| g.vertex_weight[v as usize] / area_unit)
            .sum();
        let mut boundary: f64 = 0.0;
        for &v in comp {
            for &(u, e) in &adj[start[v as usize] as usize..start[v as usize + 1] as usize] {
                if g.cut[e as usize] && v < u {
                    boundary += g.edge_weight[e as usize] / length_unit;
                }
            }
        }
        let energy = |d: f64, b: f64| 2.0 * std::f64::consts::PI * d + b * b;
        let mut best = (energy(disagree, boundary), 0usize);
        let mut k = 0;
        while k < m {
            // Flip every vertex with this value of x together.
            let value = field[order[k] as usize];
            while k < m && field[order[k] as usize] == value {
                let v = order[k] as usize;
                let lv = local[v] as usize;
                let w = g.vertex_weight[v] / area_unit;
                disagree += if raw_odd[v] { -w } else { w };
                for &(u, e) in &adj[start[v] as usize..start[v + 1] as usize] {
                    if u as usize == v {
                        continue;
                    }
                    let lu = local[u as usize] as usize;
                    let w = g.edge_weight[e as usize] / length_unit;
                    let same_before = !label_odd[lu]; // v was even
                    let counted_before = if g.cut[e as usize] {
                        same_before
                    } else {
                        !same_before
                    };
                    boundary += if counted_before { -w } else { w };
                }
                label_odd[lv] = true;
                k += 1;
            }
            let en = energy(disagree, boundary.max(0.0));
            if en < best.0 {
                best = (en, k);
            }
        }
        for (pos, &v) in order.iter().enumerate() {
            odd[v as usize] = pos < best.1;
        }
    }
    out.odd = odd;
    out.field = field;
    out
}

#[cfg(test)]
mod tests;
