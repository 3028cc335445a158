//! Double-double numbers with a running error bound: a certified fast
//! path for the constructions of [`crate::construct`].
//!
//! A [`Dd`] is an unevaluated sum `hi + lo` (about 106 bits) and a bound
//! `err` on its distance to the exact value of the polynomial it stands
//! for. Every operation adds its own rounding error to the propagated
//! bounds, inflated generously so that the bound's own floating-point
//! evaluation cannot make it too small.
//!
//! [`certified_div`] returns the correctly rounded quotient of two such
//! values when the error bounds prove which double that is (the exact
//! quotient lies strictly inside the rounding interval of the candidate),
//! and `None` otherwise. A `Some` is therefore bit-identical to what the
//! exact expansions give ([`crate::construct::div_round`]); a `None` sends
//! the caller to the exact path. With 106 bits against the 53 of the
//! result, `None` happens only near exact ties or near-degenerate inputs,
//! so the exact expansions, whose size grows with the degree of the
//! polynomial, are left for the cases that need them.
//!
//! Error-free transformations: Knuth's two-sum and Dekker's product with
//! Veltkamp splitting (no fused multiply-add needed). Splitting is exact
//! below about 2^996; inputs are scaled to `[1, 2)` first, and any overflow
//! shows as a non-finite value, which is never certified.

use crate::ring::Ring;

const U: f64 = f64::EPSILON * 0.5; // unit roundoff, 2^-53
/// Inflation of every error bound, covering the rounding of the bound's
/// own arithmetic (a handful of operations per step).
const INFLATE: f64 = 1.0 + 32.0 * U;
/// Added to every bound: covers underflow in products of small errors.
const TINY: f64 = f64::MIN_POSITIVE;

/// A double-double with an absolute error bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dd {
    /// The leading double: `hi + lo` rounded to nearest.
    pub hi: f64,
    /// The trailing double: what `hi` leaves of the sum (at most half an ulp of
    /// `hi`).
    pub lo: f64,
    /// Bound on the absolute error: `|hi + lo − exact|` is at most `err`.
    pub err: f64,
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl Dd {
    fn magnitude(&self) -> f64 {
        self.hi.abs() + self.lo.abs()
    }

    /// Whether the value is certainly not zero.
    pub fn certainly_nonzero(&self) -> bool {
        self.hi.is_finite() && self.err.is_finite() && self.magnitude() > self.err * INFLATE
    }

    /// Whether the value is exactly zero (no error, zero value).
    pub fn exactly_zero(&self) -> bool {
        self.err == 0.0 && self.hi == 0.0 && self.lo == 0.0
    }
}

impl Ring for Dd {
    fn cst(x: f64) -> Dd {
        Dd {
            hi: x,
            lo: 0.0,
            err: 0.0,
        }
    }

    fn add(&self, o: &Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let t = self.lo + o.lo;
        let e2 = e + t;
        let (hi, lo) = two_sum(s, e2);
        // Rounding of t and of e + t; the two-sums are exact.
        let own = U * (t.abs() + e2.abs());
        Dd {
            hi,
            lo,
            err: (self.err + o.err + own) * INFLATE + TINY,
        }
    }

    fn sub(&self, o: &Dd) -> Dd {
        self.add(&Dd {
            hi: -o.hi,
            lo: -o.lo,
            err: o.err,
        })
    }

    fn mul(&self, o: &Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        let cross1 = self.hi * o.lo;
        let cross2 = self.lo * o.hi;
        let e2 = e + (cross1 + cross2);
        let (hi, lo) = two_sum(p, e2);
        // Dropped lo·lo, and the roundings of the cross terms and sums.
        let own = (self.lo * o.lo).abs() + 4.0 * U * (cross1.abs() + cross2.abs() + e2.abs());
        let prop = self.magnitude() * o.err + o.magnitude() * self.err + self.err * o.err;
        Dd {
            hi,
            lo,
            err: (prop + own) * INFLATE + TINY,
        }
    }
}

/// The correctly rounded `n / d` when the bounds prove it, else `None`.
/// An exactly zero numerator gives 0 (as the exact path does).
pub fn certified_div(n: &Dd, d: &Dd) -> Option<f64> {
    if !d.certainly_nonzero() {
        return None;
    }
    if n.exactly_zero() {
        return Some(0.0);
    }
    if !n.certainly_nonzero() {
        return None;
    }
    // Relative error of the operands, then of the double-double quotient.
    let r = n.err / n.magnitude() + d.err / d.magnitude();
    // Written so that a NaN bound is refused too.
    let small = r < 1e-20;
    if !small {
        return None;
    }
    let q1 = n.hi / d.hi;
    if !q1.is_finite() || q1.abs() < 1e-290 || q1.abs() > 1e290 {
        return None;
    }
    // Remainder n − q1·d, to double-double accuracy.
    let (p, pe) = two_prod(q1, d.hi);
    let rem = ((n.hi - p) - pe) + (n.lo - q1 * d.lo);
    let q2 = rem / d.hi;
    let (qh, ql) = two_sum(q1, q2);
    // Bound on |exact − (qh + ql)|, relative to |qh|: the operands' error
    // (r, with second-order slack) and the quotient's own (≤ 2^-100).
    let bound = qh.abs() * (r * (1.0 + 4.0 * r) + 1e-30) * INFLATE;
    let a = qh.abs();
    let half_gap = (a.next_up() - a).min(a - a.next_down()) * 0.5;
    (ql.abs() + bound < half_gap).then_some(qh)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::expansion::Expansion;

    fn both(x: f64) -> (Dd, Expansion) {
        (Dd::cst(x), Expansion::from_f64(x))
    }

    /// Random polynomials evaluated both ways: whenever the fast path
    /// certifies a quotient it equals the exactly rounded one.
    #[test]
    fn certified_quotients_equal_the_exact_ones() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut certified = 0;
        let trials = 20_000;
        for trial in 0..trials {
            let xs: Vec<f64> = (0..8).map(|_| next()).collect();
            let v: Vec<(Dd, Expansion)> = xs.iter().map(|&x| both(x)).collect();
            // n = x0·x1·x2 − x3·x4 + x5, d = x6·x7 + x0·x3 (near-cancelling
            // every so often).
            let mut n = (
                v[0].0.mul(&v[1].0).mul(&v[2].0).sub(&v[3].0.mul(&v[4].0)),
                v[0].1.mul(&v[1].1).mul(&v[2].1).sub(&v[3].1.mul(&v[4].1)),
            );
            if trial % 5 == 0 {
                // x5 chosen to cancel n almost exactly.
                let c = both(-(n.0.hi));
                n = (n.0.add(&c.0), n.1.add(&c.1));
            } else {
                n = (n.0.add(&v[5].0), n.1.add(&v[5].1));
            }
            let d = (
                v[6].0.mul(&v[7].0).add(&v[0].0.mul(&v[3].0)),
                v[6].1.mul(&v[7].1).add(&v[0].1.mul(&v[3].1)),
            );
            if d.1.is_zero() {
                continue;
            }
            if let Some(q) = certified_div(&n.0, &d.0) {
                certified += 1;
                let exact = crate::construct::div_round(&n.1, &d.1);
                assert_eq!(q.to_bits(), exact.to_bits(), "trial {trial}");
            }
        }
        assert!(certified > trials * 3 / 4, "{certified} of {trials}");
    }

    #[test]
    fn ties_and_zero_are_not_certified_wrongly() {
        // 1 + 2^-53 is a tie between 1 and 1 + 2^-52: never certified.
        let n = Dd::cst(1.0).add(&Dd::cst(f64::EPSILON * 0.5));
        assert_eq!(certified_div(&n, &Dd::cst(1.0)), None);
        assert_eq!(certified_div(&Dd::cst(0.0), &Dd::cst(3.0)), Some(0.0));
        assert_eq!(certified_div(&Dd::cst(1.0), &Dd::cst(0.0)), None);
        assert_eq!(certified_div(&Dd::cst(1.0), &Dd::cst(3.0)), Some(1.0 / 3.0));
        let inf = Dd::cst(f64::INFINITY);
        assert_eq!(certified_div(&inf, &Dd::cst(3.0)), None);
    }
}
