//! Reference arithmetic for exact predicates, written independently of
//! holey-geom's floating-point expansions so that its tests check them
//! against something else: arbitrary-precision integers (sign and
//! magnitude in base 2³²) and polynomials in a symbolic ε with big-integer
//! coefficients (the oracle for simulation of simplicity). Test use only:
//! it asserts on misuse.

use std::cmp::Ordering;

/// A signed arbitrary-precision integer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BigInt {
    neg: bool,
    mag: Vec<u32>, // little-endian, no trailing zeros
}

fn trim(v: &mut Vec<u32>) {
    while v.last() == Some(&0) {
        v.pop();
    }
}

fn cmp_mag(a: &[u32], b: &[u32]) -> Ordering {
    if a.len() != b.len() {
        return a.len().cmp(&b.len());
    }
    for i in (0..a.len()).rev() {
        if a[i] != b[i] {
            return a[i].cmp(&b[i]);
        }
    }
    Ordering::Equal
}

fn add_mag(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut r = Vec::with_capacity(a.len().max(b.len()) + 1);
    let mut carry = 0u64;
    for i in 0..a.len().max(b.len()) {
        let s = carry + *a.get(i).unwrap_or(&0) as u64 + *b.get(i).unwrap_or(&0) as u64;
        r.push(s as u32);
        carry = s >> 32;
    }
    if carry > 0 {
        r.push(carry as u32);
    }
    r
}

/// a - b with |a| >= |b|.
fn sub_mag(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut r = Vec::with_capacity(a.len());
    let mut borrow = 0i64;
    for (i, &ai) in a.iter().enumerate() {
        let mut d = ai as i64 - *b.get(i).unwrap_or(&0) as i64 - borrow;
        if d < 0 {
            d += 1 << 32;
            borrow = 1;
        } else {
            borrow = 0;
        }
        r.push(d as u32);
    }
    trim(&mut r);
    r
}

impl BigInt {
    pub fn zero() -> Self {
        BigInt {
            neg: false,
            mag: Vec::new(),
        }
    }

    pub fn from_i64(x: i64) -> Self {
        let u = x.unsigned_abs();
        let mut mag = vec![u as u32, (u >> 32) as u32];
        trim(&mut mag);
        BigInt { neg: x < 0, mag }
    }

    /// `x · 2^s`, which must be an integer.
    pub fn from_f64_scaled(x: f64, s: i32) -> Self {
        assert!(x.is_finite());
        if x == 0.0 {
            return Self::zero();
        }
        let bits = x.to_bits();
        let neg = x < 0.0;
        let exp = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp - 1075)
        };
        // x = m · 2^e; want m · 2^(e + s).
        let sh = e + s;
        let mut r = BigInt::from_i64(m as i64);
        if sh >= 0 {
            r = r.shl(sh as u32);
        } else {
            let k = (-sh) as u32;
            assert!(m.trailing_zeros() >= k, "not an integer after scaling");
            r = BigInt::from_i64((m >> k) as i64);
        }
        r.neg = neg;
        r
    }

    pub fn shl(&self, k: u32) -> Self {
        if self.mag.is_empty() {
            return self.clone();
        }
        let words = (k / 32) as usize;
        let bits = k % 32;
        let mut mag = vec![0u32; words];
        let mut carry = 0u32;
        for &w in &self.mag {
            if bits == 0 {
                mag.push(w);
            } else {
                mag.push((w << bits) | carry);
                carry = w >> (32 - bits);
            }
        }
        if carry != 0 {
            mag.push(carry);
        }
        BigInt { neg: self.neg, mag }
    }

    pub fn sign(&self) -> i8 {
        if self.mag.is_empty() {
            0
        } else if self.neg {
            -1
        } else {
            1
        }
    }

    pub fn neg(&self) -> Self {
        let mut r = self.clone();
        if !r.mag.is_empty() {
            r.neg = !r.neg;
        }
        r
    }

    pub fn add(&self, o: &BigInt) -> BigInt {
        if self.neg == o.neg {
            let mut r = BigInt {
                neg: self.neg,
                mag: add_mag(&self.mag, &o.mag),
            };
            if r.mag.is_empty() {
                r.neg = false;
            }
            return r;
        }
        match cmp_mag(&self.mag, &o.mag) {
            Ordering::Equal => BigInt::zero(),
            Ordering::Greater => BigInt {
                neg: self.neg,
                mag: sub_mag(&self.mag, &o.mag),
            },
            Ordering::Less => BigInt {
                neg: o.neg,
                mag: sub_mag(&o.mag, &self.mag),
            },
        }
    }

    pub fn sub(&self, o: &BigInt) -> BigInt {
        self.add(&o.neg())
    }

    pub fn mul(&self, o: &BigInt) -> BigInt {
        if self.mag.is_empty() || o.mag.is_empty() {
            return BigInt::zero();
        }
        let mut r = vec![0u32; self.mag.len() + o.mag.len()];
        for (i, &a) in self.mag.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &b) in o.mag.iter().enumerate() {
                let t = r[i + j] as u64 + a as u64 * b as u64 + carry;
                r[i + j] = t as u32;
                carry = t >> 32;
            }
            let mut k = i + o.mag.len();
            while carry > 0 {
                let t = r[k] as u64 + carry;
                r[k] = t as u32;
                carry = t >> 32;
                k += 1;
            }
        }
        trim(&mut r);
        BigInt {
            neg: self.neg != o.neg,
            mag: r,
        }
    }

    /// Approximate value `self · 2^-s` as a double.
    pub fn to_f64_scaled(&self, s: i32) -> f64 {
        // Top three limbs carry all the precision a double can hold.
        let n = self.mag.len();
        let mut v = 0.0f64;
        for &w in self.mag.iter().rev().take(3) {
            v = v * 4294967296.0 + w as f64;
        }
        let low_limbs = n.saturating_sub(3) as i32;
        let v = v * 2f64.powi(32 * low_limbs - s);
        if self.neg { -v } else { v }
    }
}

impl Ord for BigInt {
    fn cmp(&self, o: &BigInt) -> Ordering {
        match self.sub(o).sign() {
            -1 => Ordering::Less,
            0 => Ordering::Equal,
            _ => Ordering::Greater,
        }
    }
}

impl PartialOrd for BigInt {
    fn partial_cmp(&self, o: &BigInt) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// A polynomial in one symbolic infinitesimal ε: sparse `(exponent,
/// coefficient)` terms. The reference for simulation of simplicity: with ε
/// → 0⁺ its sign is the sign of the coefficient of the smallest exponent.
#[derive(Clone, Debug)]
pub struct EpsPolyRef {
    pub terms: Vec<(u128, BigInt)>,
}

impl EpsPolyRef {
    pub fn constant(c: BigInt) -> Self {
        EpsPolyRef {
            terms: vec![(0, c)],
        }
        .norm()
    }

    pub fn monomial(e: u128) -> Self {
        EpsPolyRef {
            terms: vec![(e, BigInt::from_i64(1))],
        }
    }

    fn norm(mut self) -> Self {
        self.terms.sort_by_key(|t| t.0);
        let mut out: Vec<(u128, BigInt)> = Vec::new();
        for (e, c) in self.terms {
            if let Some(last) = out.last_mut()
                && last.0 == e
            {
                last.1 = last.1.add(&c);
                continue;
            }
            out.push((e, c));
        }
        out.retain(|t| t.1.sign() != 0);
        EpsPolyRef { terms: out }
    }

    pub fn add(&self, o: &Self) -> Self {
        let mut t = self.terms.clone();
        t.extend(o.terms.iter().cloned());
        EpsPolyRef { terms: t }.norm()
    }

    pub fn sub(&self, o: &Self) -> Self {
        let mut t = self.terms.clone();
        t.extend(o.terms.iter().map(|(e, c)| (*e, c.neg())));
        EpsPolyRef { terms: t }.norm()
    }

    pub fn mul(&self, o: &Self) -> Self {
        let mut t = Vec::new();
        for (e1, c1) in &self.terms {
            for (e2, c2) in &o.terms {
                t.push((e1 + e2, c1.mul(c2)));
            }
        }
        EpsPolyRef { terms: t }.norm()
    }

    /// Sign as ε → 0⁺.
    pub fn sign(&self) -> i8 {
        self.terms.first().map_or(0, |t| t.1.sign())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rng;

    /// `i128` is exact for sums and products of two `i64`: the oracle.
    fn value(b: &BigInt) -> i128 {
        let mut v: i128 = 0;
        for &w in b.mag.iter().rev() {
            v = (v << 32) | i128::from(w);
        }
        if b.neg { -v } else { v }
    }

    #[test]
    fn big_integers_agree_with_i128() {
        let mut rng = Rng::new(16);
        let mut pick = || {
            let r = rng.next_u64() as i64;
            // Small values and edges too, where carries and signs turn.
            match rng.below(4) {
                0 => r >> 40,
                1 => [0, 1, -1, i64::MIN, i64::MAX][rng.below(5)],
                _ => r,
            }
        };
        for _ in 0..2000 {
            let (a, b) = (pick(), pick());
            let (x, y) = (BigInt::from_i64(a), BigInt::from_i64(b));
            let (a, b) = (i128::from(a), i128::from(b));
            assert_eq!(value(&x.add(&y)), a + b, "{a} + {b}");
            assert_eq!(value(&x.sub(&y)), a - b, "{a} - {b}");
            assert_eq!(value(&x.mul(&y)), a * b, "{a} · {b}");
            assert_eq!(x.cmp(&y), a.cmp(&b));
            assert_eq!(i128::from(x.sign()), a.signum());
            assert_eq!(value(&x.shl(7)), a * 128);
        }
        // 0.75 · 2⁴ = 12; −2⁻¹⁰⁷⁴ · 2¹⁰⁷⁴ = −1.
        assert_eq!(value(&BigInt::from_f64_scaled(0.75, 4)), 12);
        assert_eq!(
            value(&BigInt::from_f64_scaled(-f64::from_bits(1), 1074)),
            -1
        );
        assert_eq!(BigInt::from_i64(3).shl(100).to_f64_scaled(100), 3.0);
    }

    #[test]
    fn the_sign_in_epsilon_is_the_lowest_terms() {
        let one = || BigInt::from_i64(1);
        // (2 − ε)(−1 + ε²) = −2 + ε + 2ε² − ε³: sign of −2.
        let p = EpsPolyRef::constant(BigInt::from_i64(2)).sub(&EpsPolyRef::monomial(1));
        let q = EpsPolyRef::constant(one().neg()).add(&EpsPolyRef::monomial(2));
        assert_eq!(p.mul(&q).sign(), -1);
        // ε − ε = 0, and ε² − ε is negative for small ε.
        let e = EpsPolyRef::monomial(1);
        assert_eq!(e.sub(&e).sign(), 0);
        assert_eq!(EpsPolyRef::monomial(2).sub(&e).sign(), -1);
    }
}
