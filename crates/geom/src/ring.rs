//! The number types a predicate polynomial is evaluated in, behind one
//! trait, so each predicate is written once as a generic polynomial and then
//! evaluated three ways (see [`crate::sos`]):
//!
//! 1. [`Interval`]: a filter. Every operation rounds to nearest and then
//!    widens the result by one ulp on each side (`next_down`/`next_up`), so
//!    the interval always contains the exact value; if it excludes zero the
//!    sign is decided.
//! 2. [`Expansion`]: the exact value.
//! 3. [`crate::sos::EpsPoly`]: the exact polynomial in the symbolic
//!    perturbation variables of simulation of simplicity.
//!
//! Only ring operations (+, −, ×) occur: no division, so every predicate is
//! the sign of a polynomial in the input coordinates.

use crate::expansion::Expansion;

/// A commutative ring with the operations predicates need.
pub trait Ring: Clone {
    /// The exact value of a double.
    fn cst(x: f64) -> Self;
    /// The sum `self + o`: exact, except for [`Interval`] (an enclosure)
    /// and [`Dd`](crate::dd::Dd) (with a bounded error).
    fn add(&self, o: &Self) -> Self;
    /// The difference `self − o`: exact, except for [`Interval`] (an enclosure)
    /// and [`Dd`](crate::dd::Dd) (with a bounded error).
    fn sub(&self, o: &Self) -> Self;
    /// The product `self × o`: exact, except for [`Interval`] (an enclosure)
    /// and [`Dd`](crate::dd::Dd) (with a bounded error).
    fn mul(&self, o: &Self) -> Self;
    /// The negation `−self`; by default `0 − self`.
    fn neg(&self) -> Self {
        Self::cst(0.0).sub(self)
    }
}

/// A closed interval `[lo, hi]` known to contain an exact real.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Lower bound: at most the exact value.
    pub lo: f64,
    /// Upper bound: at least the exact value.
    pub hi: f64,
}

impl Interval {
    /// Sign if decided: `Some(1)`, `Some(-1)`, or `None` when the interval
    /// contains zero (or is NaN).
    pub fn sign(&self) -> Option<i8> {
        if self.lo > 0.0 {
            Some(1)
        } else if self.hi < 0.0 {
            Some(-1)
        } else {
            None
        }
    }
}

impl Ring for Interval {
    #[inline]
    fn cst(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Interval {
            lo: (self.lo + o.lo).next_down(),
            hi: (self.hi + o.hi).next_up(),
        }
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Interval {
            lo: (self.lo - o.hi).next_down(),
            hi: (self.hi - o.lo).next_up(),
        }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let a = self.lo * o.lo;
        let b = self.lo * o.hi;
        let c = self.hi * o.lo;
        let d = self.hi * o.hi;
        if a.is_nan() || b.is_nan() || c.is_nan() || d.is_nan() {
            return Interval {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
            };
        }
        Interval {
            lo: a.min(b).min(c.min(d)).next_down(),
            hi: a.max(b).max(c.max(d)).next_up(),
        }
    }
    #[inline]
    fn neg(&self) -> Self {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

impl Ring for Expansion {
    fn cst(x: f64) -> Self {
        Expansion::from_f64(x)
    }
    fn add(&self, o: &Self) -> Self {
        Expansion::add(self, o)
    }
    fn sub(&self, o: &Self) -> Self {
        Expansion::sub(self, o)
    }
    fn mul(&self, o: &Self) -> Self {
        Expansion::mul(self, o)
    }
    fn neg(&self) -> Self {
        Expansion::neg(self)
    }
}

/// A point with ring coordinates.
pub type V3<T> = [T; 3];

/// The componentwise difference `a − b`.
#[inline]
pub fn sub3<T: Ring>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

/// The componentwise sum `a + b`.
#[inline]
pub fn add3<T: Ring>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [a[0].add(&b[0]), a[1].add(&b[1]), a[2].add(&b[2])]
}

/// The vector `a` scaled by `s`.
#[inline]
pub fn scale3<T: Ring>(s: &T, a: &V3<T>) -> V3<T> {
    [s.mul(&a[0]), s.mul(&a[1]), s.mul(&a[2])]
}

/// The dot product `a · b`.
#[inline]
pub fn dot<T: Ring>(a: &V3<T>, b: &V3<T>) -> T {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// The cross product `a × b`.
#[inline]
pub fn cross<T: Ring>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// `det[a; b; c]` (rows).
#[inline]
pub fn det3<T: Ring>(a: &V3<T>, b: &V3<T>, c: &V3<T>) -> T {
    dot(a, &cross(b, c))
}

/// `orient3d(a, b, c, d) = det[a−d; b−d; c−d]`: positive when `d` lies
/// below the plane through `a, b, c`, i.e. when `a, b, c` turn
/// counter-clockwise seen from `d`'s opposite side… equivalently, positive
/// when `(b−a)×(c−a)` points away from `d`. Same convention as Shewchuk's
/// `orient3d`.
#[inline]
pub fn orient3<T: Ring>(a: &V3<T>, b: &V3<T>, c: &V3<T>, d: &V3<T>) -> T {
    det3(&sub3(a, d), &sub3(b, d), &sub3(c, d))
}

/// `n = (b−a)×(c−a)`, twice the area vector of triangle `abc`.
#[inline]
pub fn normal<T: Ring>(a: &V3<T>, b: &V3<T>, c: &V3<T>) -> V3<T> {
    cross(&sub3(b, a), &sub3(c, a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::Rng;

    #[test]
    fn intervals_contain_the_exact_value() {
        let mut rng = Rng::new(3);
        for _ in 0..5_000 {
            let v: Vec<f64> = (0..4).map(|_| rng.range(-10.0, 10.0)).collect();
            let i = |x: f64| Interval::cst(x);
            let r = i(v[0]).mul(&i(v[1])).sub(&i(v[2]).mul(&i(v[3])));
            let e = |x: f64| Expansion::from_f64(x);
            let x = e(v[0]).mul(&e(v[1])).sub(&e(v[2]).mul(&e(v[3])));
            let est = x.estimate();
            assert!(r.lo <= est && est <= r.hi);
            if let Some(s) = r.sign() {
                assert_eq!(s, x.sign());
            }
        }
    }
}
