//! Orientation predicates: exact in sign, and with simulation of simplicity.
//!
//! # Exact orientation
//!
//! [`orient3d`]`(a, b, c, d)` is the sign of
//!
//! ```text
//!              | ax ay az 1 |
//!   D(a,b,c,d) = | bx by bz 1 | = det[a−d; b−d; c−d]
//!              | cx cy cz 1 |
//!              | dx dy dz 1 |
//! ```
//!
//! positive when `d` lies on the side of plane `abc` *opposite* to the
//! normal `(b−a)×(c−a)` (Shewchuk's convention: "`d` below the plane, `a, b,
//! c` counter-clockwise seen from above"). [`orient2d`]`(a, b, c)` is the
//! sign of `det[[ax ay 1][bx by 1][cx cy 1]]`, positive when `a, b, c` turn
//! counter-clockwise. Both use Shewchuk's adaptive filters (`robust`
//! crate): exact for finite inputs barring overflow/underflow of the
//! intermediate products (coordinates within about 10^±90).
//!
//! # Simulation of simplicity: the term sequence, derived
//!
//! With the perturbation of [`crate::sos`] (identity rank `r`, axis `j ∈
//! {x=0, y=1, z=2}` gets `ε_{3r+j}`, more significant for smaller `3r+j`),
//! sort the four rows by identity into `P0 < P1 < P2 < P3` (a row swap
//! flips `D`'s sign, so the answer is multiplied by the parity of the
//! sorting permutation). `D` is multilinear in its rows, so the coefficient
//! of `Π_{(r,j)∈S} ε_{3r+j}` for a set `S` of (row, column) pairs is the
//! determinant of the matrix whose rows `r ∈ S` are replaced by the unit
//! vector `e_j`; it is zero unless `S` uses each row and each column at most
//! once, and otherwise it is ± the complementary minor. Listing the valid
//! `S` by increasing `Σ_{(r,j)∈S} 2^{3r+j}` (which is the monomial order for
//! multilinear polynomials) gives, with `Oᵃᵇ(P,Q,R)` the 2-D orientation of
//! the projection on axes `a, b` and `xᵢ, yᵢ, zᵢ` the coordinates of `Pᵢ`:
//!
//! | # | S (bits)            | coefficient                         |
//! |---|---------------------|-------------------------------------|
//! | 0 | ∅                   | `D(P0,P1,P2,P3)`                     |
//! | 1 | {P0x} (1)           | `+Oʸᶻ(P1,P2,P3)`                     |
//! | 2 | {P0y} (2)           | `−Oˣᶻ(P1,P2,P3)`                     |
//! | 3 | {P0z} (4)           | `+Oˣʸ(P1,P2,P3)`                     |
//! | 4 | {P1x} (8)           | `−Oʸᶻ(P0,P2,P3)`                     |
//! | 5 | {P0y,P1x} (10)      | `−(z2 − z3)`                         |
//! | 6 | {P0z,P1x} (12)      | `+(y2 − y3)`                         |
//! | 7 | {P1y} (16)          | `+Oˣᶻ(P0,P2,P3)`                     |
//! | – | {P0x,P1y} (17)      | `+(z2 − z3)`: zero if #5 was          |
//! | 8 | {P0z,P1y} (20)      | `−(x2 − x3)`                         |
//! | 9 | {P1z} (32)          | `−Oˣʸ(P0,P2,P3)`                     |
//! | – | {P0x,P1z}, {P0y,P1z}| `∓(y2−y3)`, `±(x2−x3)`: already zero |
//! |10 | {P2x} (64)          | `+Oʸᶻ(P0,P1,P3)`                     |
//! |11 | {P0y,P2x} (66)      | `+(z1 − z3)`                         |
//! |12 | {P0z,P2x} (68)      | `−(y1 − y3)`                         |
//! |13 | {P1y,P2x} (80)      | `−(z0 − z3)`                         |
//! |14 | {P0z,P1y,P2x} (84)  | `−1`                                 |
//!
//! (Skipped sets reuse a row or a column.) Term 14 is a nonzero constant,
//! so with four distinct identities the perturbed sign is never zero: 14
//! terms after the determinant, the count Edelsbrunner & Mücke give for
//! their (differently ordered) scheme. The table is checked in the tests
//! against a brute-force expansion of the perturbed 4×4 determinant in
//! big-integer arithmetic with a symbolic ε.
//!
//! For [`orient2d_sos`] (rows `P0 < P1 < P2`, variables `ε_{2r+j}`, `j ∈
//! {x, y}`) the same derivation gives: `D`, then `+(y1 − y2)` ({P0x}),
//! `−(x1 − x2)` ({P0y}), `−(y0 − y2)` ({P1x}), and `−1` ({P0y, P1x}).
//!
//! Every coefficient is an exact 2-D orientation or the sign of a
//! difference of two doubles (exact: `fl(a − b)` has the sign of `a − b`).

use crate::sos::{SosSign, SymPoint};
use glam::{DVec2, DVec3};
use robust::{Coord, Coord3D};

/// The sign of an exact (unperturbed) predicate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// The exact value is below zero.
    Negative,
    /// The exact value is zero: the points are degenerate for the predicate
    /// (coplanar for [`orient3d`], collinear for [`orient2d`]).
    Zero,
    /// The exact value is above zero.
    Positive,
}

impl Sign {
    /// The sign of a double (NaN counts as zero).
    pub fn of(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
}

#[inline]
fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

#[inline]
fn c2(x: f64, y: f64) -> Coord<f64> {
    Coord { x, y }
}

/// The raw adaptive-exact determinant `det[a−d; b−d; c−d]` (its sign is
/// exact; its magnitude is an approximation).
#[inline]
pub fn orient3d_value(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// Exact sign of `det[a−d; b−d; c−d]` (see the module docs).
#[inline]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    Sign::of(orient3d_value(a, b, c, d))
}

/// Exact sign of `det[[ax ay 1][bx by 1][cx cy 1]]`.
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    Sign::of(robust::orient2d(c2(a.x, a.y), c2(b.x, b.y), c2(c.x, c.y)))
}

/// A 2-D point with a symbolic identity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymPoint2 {
    /// Its unperturbed coordinates.
    pub pos: DVec2,
    /// Its symbolic identity: equal ids are one point, and a smaller id is
    /// perturbed more ([`crate::sos`]).
    pub id: u32,
}

impl SymPoint2 {
    /// The point at `pos` with identity `id`.
    pub fn new(pos: DVec2, id: u32) -> Self {
        SymPoint2 { pos, id }
    }
}

/// Sorts `ids` ascending in place (insertion sort, at most 4 items) and
/// returns the parity of the permutation applied (`true` = odd).
#[inline]
fn sort_with_parity<T: Copy>(v: &mut [T], key: impl Fn(&T) -> u32) -> bool {
    let mut odd = false;
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 && key(&v[j - 1]) > key(&v[j]) {
            v.swap(j - 1, j);
            odd = !odd;
            j -= 1;
        }
    }
    odd
}

#[inline]
fn o2(p: DVec3, q: DVec3, r: DVec3, a: usize, b: usize) -> f64 {
    robust::orient2d(c2(p[a], p[b]), c2(q[a], q[b]), c2(r[a], r[b]))
}

#[inline]
fn sgn(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// The first nonzero term of the table in the module docs, for rows already
/// sorted by identity (all distinct). Never zero.
fn orient3d_perturbed_sorted(p: [DVec3; 4]) -> i8 {
    let [p0, p1, p2, p3] = p;
    let (x, y, z) = (0, 1, 2);
    let terms: [&dyn Fn() -> i8; 13] = [
        &|| sgn(o2(p1, p2, p3, y, z)),
        &|| -sgn(o2(p1, p2, p3, x, z)),
        &|| sgn(o2(p1, p2, p3, x, y)),
        &|| -sgn(o2(p0, p2, p3, y, z)),
        &|| -sgn(p2.z - p3.z),
        &|| sgn(p2.y - p3.y),
        &|| sgn(o2(p0, p2, p3, x, z)),
        &|| -sgn(p2.x - p3.x),
        &|| -sgn(o2(p0, p2, p3, x, y)),
        &|| sgn(o2(p0, p1, p3, y, z)),
        &|| sgn(p1.z - p3.z),
        &|| -sgn(p1.y - p3.y),
        &|| -sgn(p0.z - p3.z),
    ];
    for t in terms {
        let s = t();
        if s != 0 {
            return s;
        }
    }
    -1
}

/// `orient3d` in the perturbed world of [`crate::sos`]: never
/// `Degenerate` unless two of the four points share an identity (then it is
/// always `Degenerate`: the same symbolic point twice makes the perturbed
/// determinant identically zero).
pub fn orient3d_sos(a: SymPoint, b: SymPoint, c: SymPoint, d: SymPoint) -> SosSign {
    if a.id == b.id || a.id == c.id || a.id == d.id || b.id == c.id || b.id == d.id || c.id == d.id
    {
        return SosSign::Degenerate;
    }
    let s = orient3d_value(a.pos, b.pos, c.pos, d.pos);
    if s > 0.0 {
        return SosSign::Positive;
    }
    if s < 0.0 {
        return SosSign::Negative;
    }
    let mut v = [a, b, c, d];
    let odd = sort_with_parity(&mut v, |p| p.id);
    let t = orient3d_perturbed_sorted([v[0].pos, v[1].pos, v[2].pos, v[3].pos]);
    SosSign::from_i8(if odd { -t } else { t })
}

/// `orient2d` in the perturbed world (2-D analogue of [`orient3d_sos`]).
pub fn orient2d_sos(a: SymPoint2, b: SymPoint2, c: SymPoint2) -> SosSign {
    if a.id == b.id || a.id == c.id || b.id == c.id {
        return SosSign::Degenerate;
    }
    let s = robust::orient2d(
        c2(a.pos.x, a.pos.y),
        c2(b.pos.x, b.pos.y),
        c2(c.pos.x, c.pos.y),
    );
    if s != 0.0 {
        return SosSign::from_i8(sgn(s));
    }
    let mut v = [a, b, c];
    let odd = sort_with_parity(&mut v, |p| p.id);
    let (p0, p1, p2) = (v[0].pos, v[1].pos, v[2].pos);
    let mut t = sgn(p1.y - p2.y);
    if t == 0 {
        t = -sgn(p1.x - p2.x);
    }
    if t == 0 {
        t = -sgn(p0.y - p2.y);
    }
    if t == 0 {
        t = -1;
    }
    SosSign::from_i8(if odd { -t } else { t })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ring::{Ring, V3, orient3};
    use crate::sos::{Poly, sos_sign};
    use holey_testkit::Rng;
    use holey_testkit::exact::{BigInt, EpsPolyRef};

    const SCALE: i32 = 1100;

    /// Brute force: the perturbed 4×4 determinant with a ones column, by
    /// the Leibniz formula, over polynomials in ε with big-integer
    /// coefficients. Coordinate j of the point with identity rank r gets
    /// `+ε^(2^(3r+j))`. Coordinates are scaled by 2^SCALE to integers
    /// (a positive factor: signs of all coefficients are unchanged).
    fn reference_orient3d_sos(p: &[SymPoint; 4]) -> i8 {
        let mut ids: Vec<u32> = p.iter().map(|q| q.id).collect();
        ids.sort();
        let m: Vec<Vec<EpsPolyRef>> = p
            .iter()
            .map(|q| {
                let r = ids.iter().position(|&i| i == q.id).unwrap_or(0) as u32;
                let c = [q.pos.x, q.pos.y, q.pos.z];
                let mut row: Vec<EpsPolyRef> = (0..3)
                    .map(|j| {
                        EpsPolyRef::constant(BigInt::from_f64_scaled(c[j], SCALE))
                            .add(&EpsPolyRef::monomial(1u128 << (3 * r + j as u32)))
                    })
                    .collect();
                row.push(EpsPolyRef::constant(BigInt::from_i64(1)));
                row
            })
            .collect();
        let mut det = EpsPolyRef::constant(BigInt::zero());
        let perms = permutations4();
        for (perm, odd) in perms {
            let mut t = EpsPolyRef::constant(BigInt::from_i64(1));
            for (r, &c) in perm.iter().enumerate() {
                t = t.mul(&m[r][c]);
            }
            det = if odd { det.sub(&t) } else { det.add(&t) };
        }
        det.sign()
    }

    fn permutations4() -> Vec<([usize; 4], bool)> {
        let mut out = Vec::new();
        for a in 0..4 {
            for b in 0..4 {
                for c in 0..4 {
                    for d in 0..4 {
                        let p = [a, b, c, d];
                        let mut s = p;
                        s.sort();
                        if s != [0, 1, 2, 3] {
                            continue;
                        }
                        let mut inv = 0;
                        for i in 0..4 {
                            for j in i + 1..4 {
                                if p[i] > p[j] {
                                    inv += 1;
                                }
                            }
                        }
                        out.push((p, inv % 2 == 1));
                    }
                }
            }
        }
        out
    }

    struct O3;
    impl Poly for O3 {
        fn eval<T: Ring>(&self, p: &[V3<T>]) -> T {
            orient3(&p[0], &p[1], &p[2], &p[3])
        }
    }

    fn grid_point(rng: &mut Rng, n: usize) -> DVec3 {
        DVec3::new(
            rng.below(n) as f64,
            rng.below(n) as f64,
            rng.below(n) as f64,
        )
    }

    /// Degenerate configurations: tiny grids (coplanar, collinear and
    /// coincident quadruples are common), explicit coplanar and collinear
    /// constructions, all with random distinct identities.
    fn degenerate_quadruples(seed: u64, count: usize) -> Vec<[SymPoint; 4]> {
        let mut rng = Rng::new(seed);
        let mut out = Vec::new();
        for k in 0..count {
            let mut ids: Vec<u32> = Vec::new();
            while ids.len() < 4 {
                let i = rng.below(1000) as u32;
                if !ids.contains(&i) {
                    ids.push(i);
                }
            }
            let pts: [DVec3; 4] = match k % 4 {
                0 => std::array::from_fn(|_| grid_point(&mut rng, 2)),
                1 => std::array::from_fn(|_| grid_point(&mut rng, 3)),
                2 => {
                    // Coplanar on z = c, with collinear/coincident cases.
                    let z = rng.below(3) as f64;
                    std::array::from_fn(|_| DVec3::new(rng.below(3) as f64, rng.below(2) as f64, z))
                }
                _ => {
                    // On a line through a random direction.
                    let d = grid_point(&mut rng, 3) - DVec3::ONE;
                    let o = grid_point(&mut rng, 3);
                    std::array::from_fn(|_| o + d * (rng.below(3) as f64 - 1.0))
                }
            };
            out.push(std::array::from_fn(|i| SymPoint::new(pts[i], ids[i])));
        }
        out
    }

    #[test]
    fn sos_table_matches_brute_force_perturbed_determinant() {
        for q in degenerate_quadruples(11, 4000) {
            let got = orient3d_sos(q[0], q[1], q[2], q[3]).as_i8();
            let want = reference_orient3d_sos(&q);
            assert_eq!(got, want, "{q:?}");
            assert_ne!(got, 0);
        }
    }

    #[test]
    fn generic_driver_agrees_with_the_table() {
        for q in degenerate_quadruples(12, 4000) {
            assert_eq!(orient3d_sos(q[0], q[1], q[2], q[3]), sos_sign(&O3, &q));
        }
    }

    #[test]
    fn sos_agrees_with_exact_sign_when_nonzero_and_flips_under_swaps() {
        let mut rng = Rng::new(5);
        let mut nonzero = 0;
        for q in degenerate_quadruples(13, 4000) {
            let s = orient3d_sos(q[0], q[1], q[2], q[3]);
            match orient3d(q[0].pos, q[1].pos, q[2].pos, q[3].pos) {
                Sign::Positive => {
                    nonzero += 1;
                    assert_eq!(s, SosSign::Positive)
                }
                Sign::Negative => {
                    nonzero += 1;
                    assert_eq!(s, SosSign::Negative)
                }
                Sign::Zero => {}
            }
            // Every transposition flips; even permutations keep the sign.
            for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                let mut r = q;
                r.swap(i, j);
                assert_eq!(orient3d_sos(r[0], r[1], r[2], r[3]), s.flip());
            }
            let cyc = [q[1], q[2], q[3], q[0]]; // 4-cycle: odd
            assert_eq!(orient3d_sos(cyc[0], cyc[1], cyc[2], cyc[3]), s.flip());
            let c3 = [q[1], q[2], q[0], q[3]]; // 3-cycle: even
            assert_eq!(orient3d_sos(c3[0], c3[1], c3[2], c3[3]), s);
            // Relabelling identities monotonically changes nothing.
            let shift = rng.below(1000) as u32;
            let m: Vec<SymPoint> = q
                .iter()
                .map(|p| SymPoint::new(p.pos, p.id * 3 + shift))
                .collect();
            assert_eq!(orient3d_sos(m[0], m[1], m[2], m[3]), s);
        }
        assert!(nonzero > 100 && nonzero < 3900, "{nonzero}");
    }

    #[test]
    fn shared_identity_is_the_only_degenerate_outcome() {
        let p = DVec3::new(1.0, 1.0, 1.0);
        let a = SymPoint::new(p, 1);
        let b = SymPoint::new(p, 2);
        let c = SymPoint::new(p, 3);
        let d = SymPoint::new(p, 4);
        assert_ne!(orient3d_sos(a, b, c, d), SosSign::Degenerate);
        assert_eq!(orient3d_sos(a, b, c, a), SosSign::Degenerate);
        let b1 = SymPoint::new(DVec3::new(7.0, 0.0, 0.0), 1);
        assert_eq!(orient3d_sos(a, b1, c, d), SosSign::Degenerate);
    }

    #[test]
    fn orient2d_sos_matches_brute_force() {
        let mut rng = Rng::new(21);
        for _ in 0..4000 {
            let mut ids: Vec<u32> = Vec::new();
            while ids.len() < 3 {
                let i = rng.below(50) as u32;
                if !ids.contains(&i) {
                    ids.push(i);
                }
            }
            let n = 2 + rng.below(2);
            let p: Vec<SymPoint2> = (0..3)
                .map(|i| {
                    SymPoint2::new(DVec2::new(rng.below(n) as f64, rng.below(n) as f64), ids[i])
                })
                .collect();
            let mut sorted = ids.clone();
            sorted.sort();
            let m: Vec<Vec<EpsPolyRef>> = p
                .iter()
                .map(|q| {
                    let r = sorted.iter().position(|&i| i == q.id).unwrap_or(0) as u32;
                    let c = [q.pos.x, q.pos.y];
                    let mut row: Vec<EpsPolyRef> = (0..2)
                        .map(|j| {
                            EpsPolyRef::constant(BigInt::from_f64_scaled(c[j], 0))
                                .add(&EpsPolyRef::monomial(1u128 << (2 * r + j as u32)))
                        })
                        .collect();
                    row.push(EpsPolyRef::constant(BigInt::from_i64(1)));
                    row
                })
                .collect();
            let t = |a: usize, b: usize, c: usize| m[0][a].mul(&m[1][b]).mul(&m[2][c]);
            let det = t(0, 1, 2)
                .add(&t(1, 2, 0))
                .add(&t(2, 0, 1))
                .sub(&t(2, 1, 0))
                .sub(&t(0, 2, 1))
                .sub(&t(1, 0, 2));
            let got = orient2d_sos(p[0], p[1], p[2]);
            assert_eq!(got.as_i8(), det.sign(), "{p:?}");
            assert_eq!(orient2d_sos(p[1], p[0], p[2]), got.flip());
            assert_eq!(orient2d_sos(p[1], p[2], p[0]), got);
        }
    }

    #[test]
    fn large_tiny_and_offset_coordinates() {
        // A fixed degenerate pattern (coplanar grid points) under scaling by
        // powers of ten and offsets: the exact sign stays zero where it must
        // and the perturbed sign follows the same table.
        for q in degenerate_quadruples(14, 120) {
            let base = orient3d_sos(q[0], q[1], q[2], q[3]);
            for &s in &[1e-30, 1e30, 0.1, 3.0] {
                for &off in &[0.0, 4096.0, 1e6, 1e12] {
                    let t: Vec<SymPoint> = q
                        .iter()
                        .map(|p| SymPoint::new(p.pos * s + DVec3::splat(off), p.id))
                        .collect();
                    // The transformed points are the rounded images; compare
                    // with the brute-force reference on those exact values.
                    let arr = [t[0], t[1], t[2], t[3]];
                    let got = orient3d_sos(t[0], t[1], t[2], t[3]);
                    assert_eq!(got.as_i8(), reference_orient3d_sos(&arr));
                    assert_eq!(got, sos_sign(&O3, &arr));
                    if off == 0.0 && s == 3.0 {
                        // Scaling small integers by 3 is exact: same answer.
                        assert_eq!(got, base);
                    }
                }
            }
        }
    }
}
