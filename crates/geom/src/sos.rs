//! Simulation of simplicity (Edelsbrunner & Mücke 1990): symbolic points
//! and the generic exact-and-perturbed sign driver.
//!
//! # The perturbed world
//!
//! Every input point carries an identity `id: u32` ([`SymPoint`]). The
//! perturbed position of the point with identity `k` is
//!
//! ```text
//!   p_k(ε) = p_k + (ε_{3k}, ε_{3k+1}, ε_{3k+2}),   ε_i = ε^(B^i),  ε → 0⁺,
//! ```
//!
//! with `B` larger than the degree of any predicate polynomial in a single
//! variable. So each coordinate of each symbolic point gets its own
//! infinitesimal, points with a smaller identity are perturbed *more*, and
//! within a point x more than y more than z. Points with equal identities
//! are the same symbolic point (they get the same perturbation).
//!
//! A predicate is the sign of a polynomial `P` in the coordinates. In the
//! perturbed world `P(p(ε))` is a polynomial in the variables `ε_i`; the
//! monomial `Π ε_i^{d_i}` equals `ε^{Σ d_i B^i}`, and because every digit
//! `d_i < B` the exponents of distinct monomials are distinct base-`B`
//! numbers. As ε → 0⁺ the sign of `P` is therefore the sign of the
//! coefficient of the **smallest monomial in reverse-lexicographic order**
//! (compare the digit of the highest variable first). That coefficient is
//! `∂^d P / d! ` at the unperturbed point, an exact polynomial in the input.
//! `P(p(ε))` is the zero polynomial only if `P` vanishes identically on the
//! perturbed configuration space, e.g. when two arguments share an identity
//! in a way that makes the predicate degenerate: then, and only then, the
//! driver reports [`SosSign::Degenerate`].
//!
//! Only the *order* of the identities inside one predicate matters (the
//! comparison of base-`B` numbers looks at the highest differing digit), so
//! the driver renames the identities of one call to their ranks `0, 1, …`.
//! Because the rule is global — a fixed perturbation per identity — the
//! answers of different predicates are answers about one and the same
//! perturbed configuration, which is what makes combinatorial algorithms on
//! top of them consistent.
//!
//! # The driver
//!
//! [`sos_sign`] evaluates a [`Poly`] (a polynomial written once, generically
//! over [`Ring`]) in three stages:
//!
//! 1. interval arithmetic (a filter; most calls end here);
//! 2. exact [`Expansion`] arithmetic;
//! 3. if the exact value is zero, the exact polynomial in the perturbation
//!    variables, restricted to the first `L` variables for `L = 1, 3, 6, …`
//!    ([`EpsPoly`], `levels`). Restricting is exact for the monomials
//!    kept: every monomial involving a variable `≥ L` is larger (in the
//!    order above) than every monomial in variables `< L`, so the first
//!    nonzero restricted polynomial's smallest monomial is the global
//!    answer.
//!
//! Inputs are first scaled by a power of two (exact) so that the largest
//! coordinate has magnitude in `[1, 2)`: every polynomial used here is
//! homogeneous, so signs do not change, and the scaling keeps intervals and
//! expansions far from overflow and underflow for any input magnitude.
//! Stage 3 costs grow quickly with `L` and with the polynomial's degree,
//! which is why the predicates of [`crate::intersect`] are written as short
//! sums of products of orientations. Measured (release): a degree-12
//! comparison of coinciding segment crossings takes ~0.6 ms in stage 3; the
//! CCD broad phase on 524k triangles never reaches it once its exact early
//! rejects run. Hand-derived sequences ([`crate::orient`]) are used for the
//! hot orientation predicates instead.

use crate::expansion::{Expansion, exponent_of, pow2};
use crate::ring::{Interval, Ring, V3};
use glam::DVec3;
use std::cmp::Ordering;

/// A point together with its symbolic identity (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymPoint {
    /// Its unperturbed coordinates.
    pub pos: DVec3,
    /// Its symbolic identity: equal ids are one point, and a smaller id is
    /// perturbed more.
    pub id: u32,
}

impl SymPoint {
    /// The point at `pos` with identity `id`.
    pub fn new(pos: DVec3, id: u32) -> Self {
        SymPoint { pos, id }
    }
}

/// The sign of a predicate in the perturbed world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SosSign {
    /// The perturbed polynomial is negative as ε → 0⁺.
    Negative,
    /// The perturbed polynomial is positive as ε → 0⁺.
    Positive,
    /// The perturbed polynomial is identically zero: only possible when
    /// arguments share identities (the same symbolic point occurs twice in a
    /// way that makes the predicate degenerate).
    Degenerate,
}

impl SosSign {
    pub(crate) fn from_i8(s: i8) -> SosSign {
        match s {
            1 => SosSign::Positive,
            -1 => SosSign::Negative,
            _ => SosSign::Degenerate,
        }
    }

    /// `1`, `-1` or `0`.
    pub fn as_i8(self) -> i8 {
        match self {
            SosSign::Positive => 1,
            SosSign::Negative => -1,
            SosSign::Degenerate => 0,
        }
    }

    /// The opposite sign (Degenerate stays Degenerate).
    pub fn flip(self) -> SosSign {
        SosSign::from_i8(-self.as_i8())
    }
}

/// A monomial `Π ε_i^{d_i}` over at most 64 variables: 4-bit digits,
/// variable `i` in word `i / 16`. Ordered by comparing the highest variable
/// first (see the module docs). Digits never exceed 15 because no predicate
/// here has degree above 15 in one variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Mono([u64; 4]);

impl Mono {
    /// Above every monomial a predicate makes: the cap of a polynomial
    /// that keeps all its terms.
    const TOP: Mono = Mono([u64::MAX; 4]);

    fn var(i: usize) -> Mono {
        let mut m = [0u64; 4];
        m[i / 16] = 1u64 << (4 * (i % 16));
        Mono(m)
    }
    pub(crate) fn mul(self, o: Mono) -> Mono {
        Mono([
            self.0[0] + o.0[0],
            self.0[1] + o.0[1],
            self.0[2] + o.0[2],
            self.0[3] + o.0[3],
        ])
    }
}

impl Ord for Mono {
    fn cmp(&self, o: &Self) -> Ordering {
        for w in (0..4).rev() {
            // Digits are nibbles, so comparing whole words compares the
            // highest differing digit first.
            match self.0[w].cmp(&o.0[w]) {
                Ordering::Equal => continue,
                c => return c,
            }
        }
        Ordering::Equal
    }
}

impl PartialOrd for Mono {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// An exact polynomial in the perturbation variables, terms sorted by
/// [`Mono`] with nonzero [`Expansion`] coefficients, kept only up to a
/// cap.
///
/// **The cap.** A caller that needs only the terms at or below a monomial
/// `C` (a limit needs the coefficient of the denominator's lowest
/// monomial, and whether the numerator has a lower one) gives its
/// coordinates cap `C`, and every sum and product drops the terms above
/// it. That is exact for every term at or below `C`: the order is a term
/// order (the empty monomial is least, and `a < b` gives `a·c < b·c`,
/// digits adding without carries), so a term above `C` only makes terms
/// above `C`, in a product as in a sum. A result's cap is the least of
/// its operands' caps; `Mono::TOP` keeps everything.
#[derive(Clone, Debug)]
pub struct EpsPoly {
    terms: Vec<(Mono, Expansion)>,
    cap: Mono,
}

impl Default for EpsPoly {
    fn default() -> Self {
        EpsPoly {
            terms: Vec::new(),
            cap: Mono::TOP,
        }
    }
}

impl EpsPoly {
    /// `self + o`, or `self − o` when `negate`: the two term lists merged
    /// by monomial, equal monomials' coefficients added (or subtracted)
    /// exactly, zero results dropped; no negated copy of `o` is made.
    fn add_signed(&self, o: &Self, negate: bool) -> Self {
        let cap = self.cap.min(o.cap);
        let mut t = Vec::with_capacity(self.terms.len() + o.terms.len());
        let other = |(m, c): &(Mono, Expansion)| (*m, if negate { c.neg() } else { c.clone() });
        let (mut i, mut j) = (0, 0);
        while i < self.terms.len() && j < o.terms.len() {
            match self.terms[i].0.cmp(&o.terms[j].0) {
                Ordering::Less => {
                    t.push(self.terms[i].clone());
                    i += 1;
                }
                Ordering::Greater => {
                    t.push(other(&o.terms[j]));
                    j += 1;
                }
                Ordering::Equal => {
                    let (a, b) = (&self.terms[i].1, &o.terms[j].1);
                    let c = if negate { a.sub(b) } else { a.add(b) };
                    if !c.is_zero() {
                        t.push((self.terms[i].0, c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        t.extend_from_slice(&self.terms[i..]);
        t.extend(o.terms[j..].iter().map(other));
        // Both lists are sorted: what is above the cap is a tail.
        t.truncate(t.partition_point(|(m, _)| *m <= cap));
        EpsPoly { terms: t, cap }
    }

    fn from_terms(mut t: Vec<(Mono, Expansion)>, cap: Mono) -> EpsPoly {
        t.sort_by_key(|a| a.0);
        let mut out: Vec<(Mono, Expansion)> = Vec::with_capacity(t.len());
        let mut scratch = crate::expansion::Components::new();
        for (m, c) in t {
            if let Some(last) = out.last_mut()
                && last.0 == m
            {
                last.1.add_assign_with(&c, &mut scratch);
                continue;
            }
            out.push((m, c));
        }
        out.retain(|x| !x.1.is_zero());
        EpsPoly { terms: out, cap }
    }

    /// `c + ε_i`.
    fn perturbed(c: f64, var: usize) -> EpsPoly {
        let mut t = Vec::with_capacity(2);
        if c != 0.0 {
            t.push((Mono::default(), Expansion::from_f64(c)));
        }
        t.push((Mono::var(var), Expansion::from_f64(1.0)));
        EpsPoly {
            terms: t,
            cap: Mono::TOP,
        }
    }

    /// The coordinate value `c` perturbed by `ε_var` if `var < level`
    /// (variables at or above the level are not perturbed yet).
    pub(crate) fn coordinate(c: f64, var: usize, level: usize) -> EpsPoly {
        if var < level {
            EpsPoly::perturbed(c, var)
        } else {
            EpsPoly::cst(c)
        }
    }

    /// This polynomial with its terms above `cap` dropped, and `cap` (or
    /// its own, if lower) passed on to everything computed from it.
    pub(crate) fn capped(mut self, cap: Mono) -> EpsPoly {
        self.cap = self.cap.min(cap);
        let keep = self.terms.partition_point(|(m, _)| *m <= self.cap);
        self.terms.truncate(keep);
        self
    }

    /// The smallest monomial and its coefficient (None for zero).
    pub(crate) fn lowest(&self) -> Option<(Mono, &Expansion)> {
        self.terms.first().map(|(m, c)| (*m, c))
    }

    /// The coefficient of monomial `m` (zero if absent).
    pub(crate) fn coefficient(&self, m: Mono) -> Expansion {
        self.terms
            .binary_search_by(|t| t.0.cmp(&m))
            .map_or_else(|_| Expansion::zero(), |i| self.terms[i].1.clone())
    }

    /// Sign as ε → 0⁺: the sign of the smallest monomial's coefficient.
    pub fn sign(&self) -> i8 {
        self.terms.first().map_or(0, |t| t.1.sign())
    }

    /// Number of terms (for tests and statistics).
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether it has no terms: the zero polynomial.
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }
}

impl Ring for EpsPoly {
    fn cst(x: f64) -> Self {
        if x == 0.0 {
            EpsPoly::default()
        } else {
            EpsPoly {
                terms: vec![(Mono::default(), Expansion::from_f64(x))],
                cap: Mono::TOP,
            }
        }
    }
    fn add(&self, o: &Self) -> Self {
        self.add_signed(o, false)
    }
    fn sub(&self, o: &Self) -> Self {
        self.add_signed(o, true)
    }
    fn mul(&self, o: &Self) -> Self {
        let cap = self.cap.min(o.cap);
        let mut t = Vec::with_capacity(self.terms.len() * o.terms.len());
        for (m1, c1) in &self.terms {
            for (m2, c2) in &o.terms {
                let m = m1.mul(*m2);
                if m > cap {
                    // `o`'s later terms are larger, and so their products.
                    break;
                }
                t.push((m, c1.mul(c2)));
            }
        }
        EpsPoly::from_terms(t, cap)
    }
    fn neg(&self) -> Self {
        EpsPoly {
            terms: self.terms.iter().map(|(m, c)| (*m, c.neg())).collect(),
            cap: self.cap,
        }
    }
}

/// A predicate polynomial, written once over any [`Ring`]. It must be
/// homogeneous in the coordinates (translation-invariant polynomials built
/// from differences are), so that scaling all inputs by a positive power of
/// two does not change its sign.
pub trait Poly {
    /// Evaluates the polynomial at the given points (same order as given to
    /// [`sos_sign`]).
    fn eval<T: Ring>(&self, p: &[V3<T>]) -> T;
}

/// Most points a predicate may take (21 points = 63 perturbation
/// variables fit [`Mono`]).
pub const MAX_POINTS: usize = 21;

/// Statistics hooks: how many calls reached each stage (for benchmarks and
/// reports; relaxed atomics, negligible cost).
pub mod stats {
    use std::sync::atomic::{AtomicU64, Ordering};
    /// Calls of [`sos_sign`](super::sos_sign) with at most
    /// [`MAX_POINTS`](super::MAX_POINTS) points.
    pub static CALLS: AtomicU64 = AtomicU64::new(0);
    /// Calls the interval filter left undecided, which went on to exact
    /// arithmetic.
    pub static EXACT: AtomicU64 = AtomicU64::new(0);
    /// Calls whose exact value was zero, which went on to the perturbed stage.
    pub static PERTURBED: AtomicU64 = AtomicU64::new(0);

    /// `(calls, exact-stage calls, perturbed-stage calls)` of the generic
    /// driver since the last reset.
    pub fn read() -> (u64, u64, u64) {
        (
            CALLS.load(Ordering::Relaxed),
            EXACT.load(Ordering::Relaxed),
            PERTURBED.load(Ordering::Relaxed),
        )
    }

    /// Sets the three counters back to zero.
    pub fn reset() {
        CALLS.store(0, Ordering::Relaxed);
        EXACT.store(0, Ordering::Relaxed);
        PERTURBED.store(0, Ordering::Relaxed);
    }
}

/// The power of two `2^-e` that brings the largest coordinate into `[1, 2)`.
pub(crate) fn scale_exponent<'a>(pts: impl Iterator<Item = &'a DVec3>) -> i32 {
    let m = pts.fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    exponent_of(m)
}

/// The positions of `pts` times `s` (a power of two, so exact) as exact
/// expansions: the coordinates the exact stages evaluate their
/// polynomials at.
pub(crate) fn scaled_by(pts: &[SymPoint], s: f64) -> Vec<V3<Expansion>> {
    pts.iter()
        .map(|p| {
            let q = p.pos * s;
            [
                Expansion::from_f64(q.x),
                Expansion::from_f64(q.y),
                Expansion::from_f64(q.z),
            ]
        })
        .collect()
}

/// Sign of `poly` at the perturbed `pts` (see the module docs).
/// More than [`MAX_POINTS`] points gives `Degenerate`.
pub fn sos_sign<P: Poly>(poly: &P, pts: &[SymPoint]) -> SosSign {
    use std::sync::atomic::Ordering::Relaxed;
    let n = pts.len();
    if n > MAX_POINTS {
        return SosSign::Degenerate;
    }
    stats::CALLS.fetch_add(1, Relaxed);
    let k = scale_exponent(pts.iter().map(|p| &p.pos));
    let s = pow2(-k);
    let mut buf = [[Interval::cst(0.0); 3]; MAX_POINTS];
    for (b, p) in buf.iter_mut().zip(pts) {
        let q = p.pos * s;
        *b = [Interval::cst(q.x), Interval::cst(q.y), Interval::cst(q.z)];
    }
    if let Some(sg) = poly.eval(&buf[..n]).sign() {
        return SosSign::from_i8(sg);
    }
    stats::EXACT.fetch_add(1, Relaxed);
    let ex = scaled_by(pts, s);
    let sg = poly.eval(&ex).sign();
    if sg != 0 {
        return SosSign::from_i8(sg);
    }
    stats::PERTURBED.fetch_add(1, Relaxed);
    perturbed_sign(poly, pts, s)
}

/// The levels `L` (the first `L` perturbation variables) at which the
/// perturbed stage evaluates a polynomial in `nvars` variables: 1, then
/// every whole point (3, 6, 9, …, `nvars`).
///
/// Any level at or above the least level `L*` where the restricted
/// polynomial is nonzero gives the same lowest monomial, with the same
/// coefficient: the monomials a higher level adds each hold a variable
/// `≥ L*`, so each is larger than every monomial in the variables below
/// `L*` (the order compares the highest variable first). Searching every
/// level one by one is therefore not needed, only one at or above `L*`.
/// Levels within one point cost about as much as the whole point, so the
/// search steps a point at a time after the one-variable level (where most
/// degenerate constructions end). On the coplanar overlaps of an OpenSCAD
/// export, the triple points' signs ended at levels 1 to 10 and their
/// limits at levels up to 9, each level evaluated in full.
pub(crate) fn levels(nvars: usize) -> impl Iterator<Item = usize> {
    std::iter::once(1)
        .chain((3..=nvars).step_by(3))
        .filter(move |&l| l <= nvars)
}

/// The variables of one call of the perturbed stage: each point's rank
/// among the distinct identities of the call's points (only their order
/// matters, see the module docs), and how many variables there are, three
/// per identity.
pub(crate) struct Ranks {
    rank: Vec<usize>,
    /// The number of perturbation variables.
    pub(crate) nvars: usize,
}

impl Ranks {
    /// The ranks of the identities of `pts`.
    pub(crate) fn of(pts: &[SymPoint]) -> Ranks {
        let mut ids: Vec<u32> = pts.iter().map(|p| p.id).collect();
        ids.sort_unstable();
        ids.dedup();
        let rank = pts
            .iter()
            .map(|p| ids.binary_search(&p.id).unwrap_or(0))
            .collect();
        Ranks {
            rank,
            nvars: 3 * ids.len(),
        }
    }

    /// The points `pts` (those ranked) scaled by `s`, coordinate `j` of
    /// the point of rank `r` perturbed by variable `3r + j` if that is
    /// below `level`.
    pub(crate) fn at_level(&self, pts: &[SymPoint], s: f64, level: usize) -> Vec<V3<EpsPoly>> {
        pts.iter()
            .zip(&self.rank)
            .map(|(p, &r)| {
                let c = (p.pos * s).to_array();
                std::array::from_fn(|j| EpsPoly::coordinate(c[j], 3 * r + j, level))
            })
            .collect()
    }
}

/// Stage 3 of [`sos_sign`], public within the crate for tests.
pub(crate) fn perturbed_sign<P: Poly>(poly: &P, pts: &[SymPoint], s: f64) -> SosSign {
    let ranks = Ranks::of(pts);
    for level in levels(ranks.nvars) {
        let sg = poly.eval(&ranks.at_level(pts, s, level)).sign();
        if sg != 0 {
            return SosSign::from_i8(sg);
        }
    }
    SosSign::Degenerate
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ring::orient3;

    struct O3;
    impl Poly for O3 {
        fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
            orient3(&p[0], &p[1], &p[2], &p[3])
        }
    }

    #[test]
    fn mono_order_compares_highest_variable_first() {
        let a = Mono::var(0).mul(Mono::var(0)).mul(Mono::var(1));
        let b = Mono::var(2);
        assert!(a < b);
        assert!(Mono::var(15) < Mono::var(16));
        assert!(Mono::var(16).mul(Mono::var(0)) > Mono::var(16));
        assert!(Mono::var(63) > Mono::var(62).mul(Mono::var(62)));
    }

    #[test]
    fn coincident_distinct_points_are_never_degenerate() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        let pts: Vec<SymPoint> = (0..4).map(|i| SymPoint::new(p, i)).collect();
        assert_ne!(sos_sign(&O3, &pts), SosSign::Degenerate);
        let mut shared = pts.clone();
        shared[3].id = 0;
        assert_eq!(sos_sign(&O3, &shared), SosSign::Degenerate);
    }

    /// `O(p0,p1,p2,p3)·O(p4,p5,p6,p7) − O(p0,p1,p2,p7)·O(p4,p5,p6,p3)`: a
    /// degree-6 sum of products of orientations, the shape of the triple
    /// points' tests.
    struct Cross;
    impl Poly for Cross {
        fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
            let a = orient3(&p[0], &p[1], &p[2], &p[3]).mul(&orient3(&p[4], &p[5], &p[6], &p[7]));
            let b = orient3(&p[0], &p[1], &p[2], &p[7]).mul(&orient3(&p[4], &p[5], &p[6], &p[3]));
            a.sub(&b)
        }
    }

    /// The sign the perturbed stage gave before [`levels`]: every level
    /// `1, 2, …` evaluated in turn, the first nonzero one answering.
    fn sign_level_by_level<P: Poly>(poly: &P, pts: &[SymPoint]) -> SosSign {
        let ranks = Ranks::of(pts);
        for level in 1..=ranks.nvars {
            let sg = poly.eval(&ranks.at_level(pts, 1.0, level)).sign();
            if sg != 0 {
                return SosSign::from_i8(sg);
            }
        }
        SosSign::Degenerate
    }

    #[test]
    fn levels_step_a_point_at_a_time_and_end_at_every_variable() {
        assert_eq!(levels(0).count(), 0);
        assert_eq!(levels(3).collect::<Vec<_>>(), [1, 3]);
        assert_eq!(levels(12).collect::<Vec<_>>(), [1, 3, 6, 9, 12]);
    }

    /// Points on a coarse lattice, so that most configurations are
    /// degenerate (coplanar, collinear, coincident) and some share an
    /// identity: the stepped search gives the sign the level-by-level
    /// search gives, for orientations and for degree-6 cross terms.
    #[test]
    fn stepped_levels_give_the_level_by_level_sign() {
        let mut rng = holey_testkit::Rng::new(61);
        let mut perturbed = 0;
        for _ in 0..3_000 {
            let pts: Vec<SymPoint> = (0..8)
                .map(|_| {
                    let c = [0; 3].map(|_: i32| rng.below(3) as f64);
                    SymPoint::new(DVec3::from_array(c), rng.below(10) as u32)
                })
                .collect();
            let s = 1.0;
            for (got, want) in [
                (
                    perturbed_sign(&O3, &pts[..4], s),
                    sign_level_by_level(&O3, &pts[..4]),
                ),
                (
                    perturbed_sign(&Cross, &pts, s),
                    sign_level_by_level(&Cross, &pts),
                ),
            ] {
                assert_eq!(got, want, "{pts:?}");
                perturbed += usize::from(want != SosSign::Degenerate);
            }
        }
        // Most draws are degenerate and need the perturbation to answer.
        assert!(perturbed > 3_000, "{perturbed}");
    }
}
