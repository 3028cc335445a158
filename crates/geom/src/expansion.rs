//! Exact arithmetic on floating-point expansions (Shewchuk 1997).
//!
//! A real number is represented exactly as an *expansion*: a sum
//! `x = e_0 + e_1 + … + e_{m-1}` of doubles that are *nonoverlapping* (the
//! lowest set bit of each component is above the highest set bit of the
//! previous one) and sorted by increasing magnitude, with zeros removed.
//! Because the components do not overlap, the largest one dominates the sum
//! of all the others, so **the sign of the expansion is the sign of its last
//! component** and the expansion is zero exactly when it has no component.
//!
//! The two error-free transformations everything is built on:
//! - `two_sum(a, b) = (x, y)` with `x = fl(a + b)` and `x + y = a + b`
//!   exactly (Knuth's branch-free six-operation form);
//! - `two_prod(a, b) = (x, y)` with `x = fl(a·b)` and `x + y = a·b` exactly,
//!   the low part recovered with one fused multiply-add.
//!
//! Sums merge the two component lists by magnitude and run one `two_sum`
//! chain over them (Shewchuk's Fast-Expansion-Sum with the safer `two_sum`
//! in every step); products scale one operand by each component of the
//! other (Scale-Expansion) and add the partial products. Both keep the
//! nonoverlapping property (Shewchuk 1997, Theorems 13 and 19, which assume
//! IEEE round-to-nearest-even as Rust guarantees).
//!
//! Exactness needs the absence of overflow and of underflow below the
//! subnormal range; the predicate drivers in [`crate::sos`] rescale their
//! inputs by a power of two (an exact operation) so that the largest
//! coordinate is about 1, which keeps every intermediate in range for the
//! polynomial degrees used in this crate unless a single predicate mixes
//! coordinates more than about 10^±40 apart.

use smallvec::{SmallVec, smallvec};

/// The components of an expansion: up to [`INLINE`] kept in place, more
/// on the heap. The perturbed stage of [`crate::sos`] builds polynomials
/// whose coefficients are mostly one or two components, and allocating each
/// of them (and freeing it) was a fifth of `holey selfint` on the coplanar
/// overlaps of an OpenSCAD export.
pub(crate) type Components = SmallVec<[f64; INLINE]>;

/// Components an [`Expansion`] holds without allocating.
pub(crate) const INLINE: usize = 4;

/// `(fl(a + b), err)` with `fl(a + b) + err == a + b` exactly.
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    let br = b - bv;
    let ar = a - av;
    (x, ar + br)
}

/// `(fl(a·b), err)` with `fl(a·b) + err == a·b` exactly (barring underflow).
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    (x, a.mul_add(b, -x))
}

/// Appends `x` to the components `h` unless it is zero: every operation
/// here keeps an expansion free of zero components (zero elimination), so
/// its length stays the number of components that carry value.
#[inline]
fn push_nonzero(h: &mut Components, x: f64) {
    if x != 0.0 {
        h.push(x);
    }
}

/// The components of `e + sign·f` (`sign` is ±1, so `sign·f` is exact)
/// into `out`, which is cleared first: the two lists merged by magnitude
/// (`e`'s first on a tie) feeding one `two_sum` chain, without a merged
/// copy; either operand empty gives the other.
fn sum_into(e: &[f64], f: &[f64], sign: f64, out: &mut Components) {
    out.clear();
    if e.is_empty() {
        out.extend(f.iter().map(|x| sign * x));
        return;
    }
    if f.is_empty() {
        out.extend_from_slice(e);
        return;
    }
    out.reserve(e.len() + f.len());
    let (mut i, mut j) = (0, 0);
    let mut next = || {
        if i < e.len() && (j >= f.len() || e[i].abs() <= f[j].abs()) {
            i += 1;
            e[i - 1]
        } else {
            j += 1;
            sign * f[j - 1]
        }
    };
    let mut q = next();
    for _ in 1..e.len() + f.len() {
        let (s, err) = two_sum(q, next());
        push_nonzero(out, err);
        q = s;
    }
    push_nonzero(out, q);
}

/// The components of `c · b` into `out`, which is cleared first
/// (Scale-Expansion with zero elimination).
fn scale_into(c: &[f64], b: f64, out: &mut Components) {
    out.clear();
    if b == 0.0 || c.is_empty() {
        return;
    }
    out.reserve(2 * c.len());
    let (mut q, lo) = two_prod(c[0], b);
    push_nonzero(out, lo);
    for &e in &c[1..] {
        let (p1, p0) = two_prod(e, b);
        let (s, err) = two_sum(q, p0);
        push_nonzero(out, err);
        let (s2, err2) = two_sum(p1, s);
        push_nonzero(out, err2);
        q = s2;
    }
    push_nonzero(out, q);
}

/// An exact real number as a nonoverlapping expansion (see module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Expansion {
    /// Nonzero, nonoverlapping components by increasing magnitude.
    c: Components,
}

impl Expansion {
    /// Zero.
    pub fn zero() -> Self {
        Expansion {
            c: Components::new(),
        }
    }

    /// The exact value of one double.
    pub fn from_f64(x: f64) -> Self {
        if x == 0.0 {
            Self::zero()
        } else {
            Expansion { c: smallvec![x] }
        }
    }

    /// The components (increasing magnitude, none zero).
    pub fn components(&self) -> &[f64] {
        &self.c
    }

    /// Sign of the exact value: -1, 0 or 1 (0 also for a NaN component,
    /// which only non-finite input can produce).
    pub fn sign(&self) -> i8 {
        match self.c.last() {
            Some(&x) if x > 0.0 => 1,
            Some(&x) if x < 0.0 => -1,
            _ => 0,
        }
    }

    /// True when the value is exactly zero.
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    /// A double close to the value: the components summed from the smallest
    /// up. Its relative error is below about 2·2⁻⁵³ for a nonoverlapping
    /// expansion; [`crate::construct`] turns it into a faithful rounding.
    pub fn estimate(&self) -> f64 {
        self.c.iter().sum()
    }

    /// Exact sum.
    pub fn add(&self, o: &Expansion) -> Expansion {
        let mut h = Components::new();
        sum_into(&self.c, &o.c, 1.0, &mut h);
        Expansion { c: h }
    }

    /// `self += o` exactly, through `scratch` (any contents; it is left
    /// holding this expansion's old buffer, for the next call to reuse).
    pub(crate) fn add_assign_with(&mut self, o: &Expansion, scratch: &mut Components) {
        sum_into(&self.c, &o.c, 1.0, scratch);
        std::mem::swap(&mut self.c, scratch);
    }

    /// Exact negation.
    pub fn neg(&self) -> Expansion {
        Expansion {
            c: self.c.iter().map(|x| -x).collect(),
        }
    }

    /// Exact difference.
    pub fn sub(&self, o: &Expansion) -> Expansion {
        let mut h = Components::new();
        sum_into(&self.c, &o.c, -1.0, &mut h);
        Expansion { c: h }
    }

    /// Exact product with one double (Scale-Expansion with zero elimination).
    pub fn scale(&self, b: f64) -> Expansion {
        let mut h = Components::new();
        scale_into(&self.c, b, &mut h);
        Expansion { c: h }
    }

    /// Exact product.
    pub fn mul(&self, o: &Expansion) -> Expansion {
        let (small, big) = if self.c.len() <= o.c.len() {
            (self, o)
        } else {
            (o, self)
        };
        // The partial products and the running sum reuse three buffers;
        // the first partial product is the sum so far.
        let Some((&first, rest)) = small.c.split_first() else {
            return Expansion::zero();
        };
        let (mut acc, mut part, mut next) =
            (Components::new(), Components::new(), Components::new());
        scale_into(&big.c, first, &mut acc);
        for &b in rest {
            scale_into(&big.c, b, &mut part);
            sum_into(&acc, &part, 1.0, &mut next);
            std::mem::swap(&mut acc, &mut next);
        }
        Expansion { c: acc }
    }

    /// Exact `a - b` of two doubles.
    pub fn diff(a: f64, b: f64) -> Expansion {
        let (x, y) = two_sum(a, -b);
        let mut c = Components::new();
        push_nonzero(&mut c, y);
        push_nonzero(&mut c, x);
        Expansion { c }
    }

    /// Multiply by `2^k` (exact barring over/underflow).
    pub fn ldexp(&self, k: i32) -> Expansion {
        let f = pow2(k);
        Expansion {
            c: self.c.iter().map(|x| x * f).collect(),
        }
    }
}

/// `2^k` as a double for `k` in the normal range (clamped).
pub(crate) fn pow2(k: i32) -> f64 {
    let k = k.clamp(-1022, 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The exponent `e` with `2^e <= |x| < 2^(e+1)` for a normal nonzero `x`
/// (0 for zero or non-finite values).
pub fn exponent_of(x: f64) -> i32 {
    if x == 0.0 || !x.is_finite() {
        return 0;
    }
    let bits = x.abs().to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32;
    if e == 0 {
        // Subnormal.
        -1023 - (bits.leading_zeros() as i32 - 12)
    } else {
        e - 1023
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use holey_testkit::Rng;
    use holey_testkit::exact::BigInt;

    fn big(e: &Expansion) -> BigInt {
        let mut acc = BigInt::zero();
        for &x in e.components() {
            acc = acc.add(&BigInt::from_f64_scaled(x, 1100));
        }
        acc
    }

    #[test]
    fn two_sum_and_two_prod_are_exact() {
        let mut rng = Rng::new(1);
        for _ in 0..10_000 {
            let a = rng.range(-1.0, 1.0) * pow2(rng.below(80) as i32 - 40);
            let b = rng.range(-1.0, 1.0) * pow2(rng.below(80) as i32 - 40);
            let (x, y) = two_sum(a, b);
            let lhs = BigInt::from_f64_scaled(x, 1100).add(&BigInt::from_f64_scaled(y, 1100));
            let rhs = BigInt::from_f64_scaled(a, 1100).add(&BigInt::from_f64_scaled(b, 1100));
            assert_eq!(lhs, rhs);
            let (x, y) = two_prod(a, b);
            let lhs = BigInt::from_f64_scaled(x, 1100).add(&BigInt::from_f64_scaled(y, 1100));
            let rhs = BigInt::from_f64_scaled(a, 550).mul(&BigInt::from_f64_scaled(b, 550));
            assert_eq!(lhs, rhs);
        }
    }

    #[test]
    fn random_polynomials_match_big_integers() {
        let mut rng = Rng::new(7);
        for _ in 0..2_000 {
            // (a + b)(c - d) - e f with wildly different magnitudes, plus a
            // cancelling term so that zero and tiny results occur.
            let mut v = [0.0; 6];
            for x in v.iter_mut() {
                *x = rng.range(-1.0, 1.0) * pow2(rng.below(60) as i32 - 30);
                if rng.chance(0.2) {
                    *x = (rng.below(7) as f64) - 3.0;
                }
            }
            let e = |x: f64| Expansion::from_f64(x);
            let r = e(v[0])
                .add(&e(v[1]))
                .mul(&Expansion::diff(v[2], v[3]))
                .sub(&e(v[4]).mul(&e(v[5])));
            let s = 300;
            let b = |x: f64| BigInt::from_f64_scaled(x, s);
            let rb = b(v[0])
                .add(&b(v[1]))
                .mul(&b(v[2]).sub(&b(v[3])))
                .sub(&b(v[4]).mul(&b(v[5])));
            assert_eq!(r.sign(), rb.sign());
            // Value check at a common scale (2^600 for products).
            assert_eq!(
                big(&r),
                rb.mul(&BigInt::from_f64_scaled(1.0, 1100 - 600)),
                "{v:?}"
            );
            // Nonoverlapping and increasing: each component exceeds the sum
            // of the smaller ones in magnitude.
            let c = r.components();
            for w in c.windows(2) {
                assert!(w[0].abs() < w[1].abs());
            }
        }
    }

    #[test]
    fn exponent_and_pow2() {
        assert_eq!(exponent_of(1.0), 0);
        assert_eq!(exponent_of(1.5), 0);
        assert_eq!(exponent_of(2.0), 1);
        assert_eq!(exponent_of(-0.25), -2);
        assert_eq!(exponent_of(1e-310), exponent_of(1e-310 * 2.0) - 1);
        assert_eq!(pow2(10), 1024.0);
        assert_eq!(pow2(-3), 0.125);
    }
}
