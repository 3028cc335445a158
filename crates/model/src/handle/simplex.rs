//! A small dense linear program: `maximize c·x` subject to `A x ≤ b`,
//! `x ≥ 0`, by the simplex method on a tableau with Bland's rule (the
//! entering and leaving variables of smallest index, which cannot cycle).
//! An infeasible origin (some `b_i < 0`) is handled by the one-variable
//! first phase: maximize `−x₀` over `A x − x₀ ≤ b`, `x₀ ≥ 0`, starting by
//! pivoting `x₀` into the row of the most negative `b_i`, which makes
//! every right-hand side non-negative; the program is feasible exactly
//! when that phase ends with `x₀ = 0`.
//!
//! It serves the multi-face handle's choice of a hub centre (a handful of
//! faces, so tens of variables and constraints), in floating point with a
//! fixed tolerance on data scaled to about 1. Its answers are candidates
//! only: the caller decides everything that matters about them exactly.

/// Tolerance on tableau entries: data are scaled to about 1.
const EPS: f64 = 1e-10;

/// The outcome of [`maximize`].
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Lp {
    /// An optimal `x` and the objective's value there.
    Optimal(Vec<f64>, f64),
    /// No `x ≥ 0` satisfies `A x ≤ b` (to the tolerance).
    Infeasible,
    /// The objective grows without bound, or the iteration limit was hit.
    Unsolved,
}

/// A tableau in slack form: row `i` reads `x_basis[i] + Σ_j rows[i][j] x_j
/// = rows[i][w]` over the non-basic `x_j`; the objective row `o` reads
/// `z = −o[w] + Σ_j o[j] x_j`.
struct Tableau {
    rows: Vec<Vec<f64>>,
    o: Vec<f64>,
    basis: Vec<usize>,
    /// Columns that may not enter (the first phase's variable afterwards).
    barred: Vec<bool>,
}

impl Tableau {
    fn width(&self) -> usize {
        self.o.len() - 1
    }

    /// Makes column `j` basic in row `r`.
    fn pivot(&mut self, r: usize, j: usize) {
        let p = self.rows[r][j];
        for x in &mut self.rows[r] {
            *x /= p;
        }
        let pivot_row = self.rows[r].clone();
        for (i, row) in self.rows.iter_mut().enumerate() {
            let f = row[j];
            if i != r && f != 0.0 {
                for (x, y) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * y;
                }
            }
        }
        let f = self.o[j];
        if f != 0.0 {
            for (x, y) in self.o.iter_mut().zip(&pivot_row) {
                *x -= f * y;
            }
        }
        self.basis[r] = j;
    }

    /// Runs the simplex method from the current feasible basis; false if
    /// the objective is unbounded or the iteration limit is reached.
    fn run(&mut self) -> bool {
        let w = self.width();
        // Bland's rule terminates; the limit only guards against a loop
        // made by rounding.
        let limit = 50 * (w + self.rows.len() + 1);
        for _ in 0..limit {
            let Some(j) = (0..w).find(|&j| !self.barred[j] && self.o[j] > EPS) else {
                return true;
            };
            let mut best: Option<(f64, usize, usize)> = None;
            for (i, row) in self.rows.iter().enumerate() {
                if row[j] > EPS {
                    let ratio = row[w] / row[j];
                    let better = match best {
                        None => true,
                        Some((r, _, b)) => {
                            ratio < r - EPS || (ratio <= r + EPS && self.basis[i] < b)
                        }
                    };
                    if better {
                        best = Some((ratio, i, self.basis[i]));
                    }
                }
            }
            match best {
                Some((_, r, _)) => self.pivot(r, j),
                None => return false,
            }
        }
        false
    }

    /// The values of the first `n` variables.
    fn solution(&self, n: usize) -> Vec<f64> {
        let w = self.width();
        let mut x = vec![0.0; n];
        for (row, &b) in self.rows.iter().zip(&self.basis) {
            if b < n {
                x[b] = row[w].max(0.0);
            }
        }
        x
    }
}

/// Maximizes `c·x` over `a x ≤ b`, `x ≥ 0` (`a` has one row per entry
/// of `b`, each of `c.len()` entries).
pub(crate) fn maximize(c: &[f64], a: &[Vec<f64>], b: &[f64]) -> Lp {
    let (n, m) = (c.len(), b.len());
    // Columns: the n variables, m slacks, the first phase's x₀, then the
    // right-hand side.
    let w = n + m + 1;
    let aux = n + m;
    let rows: Vec<Vec<f64>> = (0..m)
        .map(|i| {
            let mut row = vec![0.0; w + 1];
            row[..n].copy_from_slice(&a[i][..n]);
            row[n + i] = 1.0;
            row[aux] = -1.0;
            row[w] = b[i];
            row
        })
        .collect();
    let mut t = Tableau {
        rows,
        o: vec![0.0; w + 1],
        basis: (n..n + m).collect(),
        barred: vec![false; w],
    };
    let worst = (0..m).min_by(|&i, &j| b[i].total_cmp(&b[j]));
    if let Some(r) = worst.filter(|&r| b[r] < 0.0) {
        t.o[aux] = -1.0;
        t.pivot(r, aux);
        if !t.run() || -t.o[w] < -EPS {
            return Lp::Infeasible;
        }
        if let Some(r) = t.basis.iter().position(|&v| v == aux) {
            // x₀ is basic at zero: swap it for any variable of its row.
            match (0..aux).find(|&j| t.rows[r][j].abs() > EPS) {
                Some(j) => t.pivot(r, j),
                None => return Lp::Unsolved,
            }
        }
    }
    t.barred[aux] = true;
    for row in &mut t.rows {
        row[aux] = 0.0;
    }
    // The real objective, expressed over the current non-basic variables.
    t.o = vec![0.0; w + 1];
    t.o[..n].copy_from_slice(c);
    for i in 0..m {
        let f = t.o[t.basis[i]];
        if f != 0.0 {
            for (x, y) in t.o.iter_mut().zip(&t.rows[i]) {
                *x -= f * y;
            }
        }
    }
    if !t.run() {
        return Lp::Unsolved;
    }
    let x = t.solution(n);
    let value = c.iter().zip(&x).map(|(c, x)| c * x).sum();
    Lp::Optimal(x, value)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn optimum(c: &[f64], a: &[Vec<f64>], b: &[f64]) -> (Vec<f64>, f64) {
        match maximize(c, a, b) {
            Lp::Optimal(x, v) => (x, v),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_textbook_program() {
        // max 3x + 2y, x + y ≤ 4, x + 3y ≤ 6, x ≤ 3: the optimum is at the
        // corner x = 3, y = 1 (the first and third constraints tight),
        // value 11.
        let (x, v) = optimum(
            &[3.0, 2.0],
            &[vec![1.0, 1.0], vec![1.0, 3.0], vec![1.0, 0.0]],
            &[4.0, 6.0, 3.0],
        );
        assert!((x[0] - 3.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9);
        assert!((v - 11.0).abs() < 1e-9);
    }

    #[test]
    fn an_infeasible_origin_needs_the_first_phase() {
        // max −x − y with x + y ≥ 2 (−x − y ≤ −2), x ≤ 5: the optimum
        // is −2 on the line x + y = 2.
        let (x, v) = optimum(
            &[-1.0, -1.0],
            &[vec![-1.0, -1.0], vec![1.0, 0.0]],
            &[-2.0, 5.0],
        );
        assert!((x[0] + x[1] - 2.0).abs() < 1e-9);
        assert!((v + 2.0).abs() < 1e-9);
        // x ≥ 3 and x ≤ 1 together: nothing.
        assert_eq!(
            maximize(&[1.0], &[vec![-1.0], vec![1.0]], &[-3.0, 1.0]),
            Lp::Infeasible
        );
        // max x with only x ≥ 1: unbounded.
        assert_eq!(maximize(&[1.0], &[vec![-1.0]], &[-1.0]), Lp::Unsolved);
    }

    #[test]
    fn a_degenerate_corner_does_not_cycle() {
        // Beale's example, which cycles under the largest-coefficient
        // rule: max 3/4 x1 − 150 x2 + 1/50 x3 − 6 x4 over three
        // constraints with a degenerate origin; the optimum is 1/20 at
        // x = (1/25, 0, 1, 0).
        let (x, v) = optimum(
            &[0.75, -150.0, 0.02, -6.0],
            &[
                vec![0.25, -60.0, -0.04, 9.0],
                vec![0.5, -90.0, -0.02, 3.0],
                vec![0.0, 0.0, 1.0, 0.0],
            ],
            &[0.0, 0.0, 1.0],
        );
        assert!((v - 0.05).abs() < 1e-9, "{v} at {x:?}");
    }
}
