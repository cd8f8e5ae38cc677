//! A truncated power series in midpoint–radius form, for the link proofs' series arithmetic.
//!
//! [`MidRadSeries`] stores each coefficient as a midpoint `m` and a radius `r` (the coefficient
//! lies in `[m − r, m + r]`) and computes in plain round-to-nearest `f64`, with no rounding-mode
//! switch and no four-corner products: a product coefficient costs four fused multiply-adds
//! per term where an interval product costs eight directed products. Every rounding error is
//! bounded and added to the radius, so each operation still returns an enclosure of the exact
//! result for all values in its operands (the same contract as [`SeriesN`]); the radii are at
//! most 1.5 times those of interval arithmetic (the midpoint–radius product's overestimate),
//! and far less on the thin coefficients a link proof mostly handles.
//!
//! # Why the radii are upper bounds
//! Write `U = 2⁻⁵²` and `η = 2⁻¹⁰⁷⁴`. For any real `x` and its nearest double `fl(x)`,
//! `|fl(x) − x| ≤ U·|fl(x)| + η` (in the normal range the error is at most `2⁻⁵³|x|`, which is
//! at most `U·|fl(x)|`; below it, at most `η/2`). So `x ≤ (1 + U)·fl(x) + η` for `x ≥ 0`.
//!
//! A radius is a sum of non-negative terms evaluated in round-to-nearest by at most
//! `MAX_OPS` operations on non-negative operands; by the bound above the exact sum is at most
//! `(1 + U)^MAX_OPS · (s + MAX_OPS · η)` for the computed `s`, which is below
//! `(1 + 2⁻⁴⁴)·s + 2⁻¹⁰⁶⁶`. `inflate` returns `s·(1 + 2⁻⁴⁰)` rounded to nearest, which keeps
//! more than `(1 + 2⁻⁴¹)·s`, when `s ≥ 2⁻⁹⁰⁰` (then `2⁻¹⁰⁶⁶` is far below `2⁻⁴²·s`), and the
//! constant `2⁻⁹⁰⁰·(1 + 2⁻⁴⁰)` when `s` is smaller. No radius is ever below that constant
//! except an exact zero, so radii never feed subnormal operands into the products.
//!
//! The terms of each radius:
//! - **product** `Σⱼ aⱼ·b_{i−j}`: for `x ∈ aⱼ`, `y ∈ b_{i−j}`,
//!   `|x·y − mₐ·m_b| ≤ |mₐ|·r_b + rₐ·(|m_b| + r_b)`; the midpoint is a chain of `n` fused
//!   multiply-adds, each rounding once by at most `u = 2⁻⁵³` of its exact result (or `η/2`), so
//!   with `|sₖ| ≤ (1 + u)ᵏ·Σ_{l≤k}|mₐ·m_b|` for its partial sums its error is at most
//!   `n·u·(1 + u)ⁿ·Σⱼ|mₐ·m_b| + n·η`; the radius adds `n·u·Σⱼ|mₐ·m_b|` (the factor `(1 + u)ⁿ`
//!   and the `η`s are covered by `inflate`'s margin and least radius);
//! - **sum** `a + b`: `rₐ + r_b + U·|m|` for the rounded midpoint `m`;
//! - **from an interval** `[lo, hi]`: the midpoint `m` (finite for a bounded interval) and the
//!   larger of `hi − m` and `m − lo`; a point interval is exact (radius 0);
//! - a product or sum of exact operands that is itself exact (checked by the product's fused
//!   multiply-add residual away from underflow, and by TwoSum) keeps radius 0;
//! - **quotient** `a / b`: the recurrence `rᵢ = (aᵢ − Σ_{k≥1} b_k·r_{i−k})·(1/b₀)` with the
//!   products and sums above and `1/b₀` enclosed by an interval division.
//!
//! A non-finite midpoint or radius anywhere makes the coefficient the whole line when it is
//! read back ([`MidRadSeries::to_series`]); so does a divisor whose constant term may be zero.

use crate::numeric::scalar::point;
use crate::validated::SeriesN;
use crate::Scalar;
use inari::{interval, Interval};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// `2⁻⁵²`: bounds the relative rounding error of a nearest result, relative to that result.
const U: f64 = f64::EPSILON;
/// `2⁻⁵³`, the unit roundoff: bounds the relative rounding error of a nearest result, relative
/// to the exact value (normal range).
const HALF_U: f64 = f64::EPSILON / 2.0;
/// Most nearest-rounded operations in one radius's evaluation tree: a product of series of `N`
/// terms takes at most `3N + 2` (checked at compile time), a sum or a scalar product five.
const MAX_OPS: usize = 200;
/// `2⁻⁹⁰⁰`: below it [`inflate`] returns a constant, far above every absolute rounding term and
/// normal, so that radii never feed subnormal operands (each costs a microcode assist) into the
/// products.
const TINY: f64 = f64::from_bits(123 << 52);
/// `1 + 2⁻⁴⁰`, the relative margin of [`inflate`].
const GROW: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;

/// An upper bound of the exact value of a sum of non-negative terms computed as `s` in
/// round-to-nearest with at most [`MAX_OPS`] operations (module docs): `s·(1 + 2⁻⁴⁰)`, and at
/// least [`TINY`]`·(1 + 2⁻⁴⁰)`. A NaN stays NaN and `+∞` stays `+∞`.
#[inline]
fn inflate(s: f64) -> f64 {
    if s < TINY {
        TINY * GROW
    } else {
        s * GROW
    }
}

/// A truncated power series `Σ_{i<len} cᵢ tⁱ` with each coefficient `cᵢ ∈ [mᵢ − rᵢ, mᵢ + rᵢ]`,
/// at most `N` of them (module docs); implements [`Scalar`] with the same meaning as
/// [`SeriesN`].
#[derive(Clone, Copy, Debug)]
pub struct MidRadSeries<const N: usize> {
    m: [f64; N],
    r: [f64; N],
    len: usize,
}

impl<const N: usize> MidRadSeries<N> {
    fn zero_len(len: usize) -> Self {
        MidRadSeries {
            m: [0.0; N],
            r: [0.0; N],
            len,
        }
    }

    /// The series enclosing every series of `s` (its first `N` coefficients).
    pub fn from_series<const M: usize>(s: &SeriesN<M>) -> Self {
        let c = s.coeffs();
        let mut out = Self::zero_len(c.len().clamp(1, N));
        for (i, x) in c.iter().take(N).enumerate() {
            (out.m[i], out.r[i]) = mid_rad(*x);
        }
        out
    }

    /// The coefficients as intervals: `[m − r, m + r]` rounded outward, the whole line where
    /// the midpoint or radius is not finite.
    pub fn to_series<const M: usize>(&self) -> SeriesN<M> {
        let c: [Interval; M] = std::array::from_fn(|i| {
            let (m, r) = self.pair(i);
            if m.is_finite() && r.is_finite() {
                point(m) + interval!(-r, r).unwrap_or(Interval::ENTIRE)
            } else {
                Interval::ENTIRE
            }
        });
        SeriesN::new(&c[..self.len.min(M)])
    }

    /// Coefficient `i` as `(m, r)` (exact zero beyond the length).
    #[inline]
    fn pair(&self, i: usize) -> (f64, f64) {
        if i < self.len {
            (self.m[i], self.r[i])
        } else {
            (0.0, 0.0)
        }
    }

    /// One past the last coefficient that is not exactly zero (at least 1).
    fn support(&self) -> usize {
        let mut l = self.len;
        while l > 1 && self.m[l - 1] == 0.0 && self.r[l - 1] == 0.0 {
            l -= 1;
        }
        l
    }

    /// Every coefficient `k·cᵢ` for the scalar `k`.
    fn scale(&self, k: (f64, f64)) -> Self {
        let mut out = Self::zero_len(self.len);
        for i in 0..self.len {
            (out.m[i], out.r[i]) = mul1(k, (self.m[i], self.r[i]));
        }
        out
    }
}

/// `a·b` for one midpoint–radius pair each (module docs; exact products keep radius 0).
#[inline]
fn mul1((am, ar): (f64, f64), (bm, br): (f64, f64)) -> (f64, f64) {
    let m = am * bm;
    // Exact: a zero factor, or a product far from underflow whose error (exactly
    // representable there) is zero.
    let exact = am == 0.0 || bm == 0.0 || (m.abs() > 1e-290 && am.mul_add(bm, -m) == 0.0);
    if ar == 0.0 && br == 0.0 && exact {
        return (m, 0.0);
    }
    let r = am.abs().mul_add(br, ar * (bm.abs() + br)) + U * m.abs();
    (m, inflate(r))
}

/// `a + b` for one midpoint–radius pair each (module docs; exact sums keep radius 0).
#[inline]
fn add1((am, ar): (f64, f64), (bm, br): (f64, f64)) -> (f64, f64) {
    let m = am + bm;
    if ar == 0.0 && br == 0.0 {
        // TwoSum: the rounding error of `m`, exactly.
        let bb = m - am;
        if (am - (m - bb)) + (bm - bb) == 0.0 {
            return (m, 0.0);
        }
    }
    (m, inflate(ar + br + U * m.abs()))
}

/// Midpoint and radius of `x` (a radius of `+∞` for an unbounded or empty `x`).
fn mid_rad(x: Interval) -> (f64, f64) {
    if x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite() {
        return (0.0, f64::INFINITY);
    }
    let (lo, hi) = (x.inf(), x.sup());
    if lo == hi {
        return (lo, 0.0);
    }
    let m = x.mid();
    (m, inflate((hi - m).max(m - lo)))
}

impl<const N: usize> Add for MidRadSeries<N> {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        // Beyond the shorter operand's length the sum is the longer one's coefficient, exactly.
        let (mut out, short) = if self.len >= rhs.len {
            (self, rhs)
        } else {
            (rhs, self)
        };
        for i in 0..short.len {
            (out.m[i], out.r[i]) = add1(out.pair(i), short.pair(i));
        }
        out
    }
}

impl<const N: usize> Neg for MidRadSeries<N> {
    type Output = Self;
    fn neg(self) -> Self {
        let mut out = self;
        for v in &mut out.m[..self.len] {
            *v = -*v;
        }
        out
    }
}

impl<const N: usize> Sub for MidRadSeries<N> {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        self + (-rhs)
    }
}

impl<const N: usize> Mul for MidRadSeries<N> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        let n = self.len.max(rhs.len);
        if self.len == 1 {
            let mut out = rhs.scale(self.pair(0));
            out.len = n;
            return out;
        }
        if rhs.len == 1 {
            let mut out = self.scale(rhs.pair(0));
            out.len = n;
            return out;
        }
        const {
            assert!(
                3 * N + 2 <= MAX_OPS,
                "a product's radius takes 3N + 2 operations"
            )
        };
        let (la, lb) = (self.support(), rhs.support());
        // Per coefficient of `rhs`: its magnitude, and the factor of `rₐ`.
        let mut bm = [0.0; N];
        let mut of_ar = [0.0; N];
        for j in 0..lb {
            bm[j] = rhs.m[j].abs();
            of_ar[j] = bm[j] + rhs.r[j];
        }
        let am: [f64; N] = std::array::from_fn(|j| self.m[j].abs());
        let mut out = Self::zero_len(n);
        for i in 0..n.min(la + lb - 1) {
            let (from, to) = ((i + 1).saturating_sub(lb), i.min(la - 1));
            let (mut m, mut r, mut mag) = (0.0f64, 0.0f64, 0.0f64);
            for j in from..=to {
                m = self.m[j].mul_add(rhs.m[i - j], m);
                mag = am[j].mul_add(bm[i - j], mag);
                r = am[j].mul_add(rhs.r[i - j], r);
                r = self.r[j].mul_add(of_ar[i - j], r);
            }
            // The midpoint chain's rounding: at most `n·u·Σ|mₐ·m_b|` for its `n` terms.
            let chain = (to + 1 - from) as f64 * HALF_U;
            out.m[i] = m;
            out.r[i] = inflate(chain.mul_add(mag, r));
        }
        out
    }
}

impl<const N: usize> Div for MidRadSeries<N> {
    type Output = Self;
    /// `r = a / b` by `rᵢ = (aᵢ − Σ_{k≥1} b_k·r_{i−k}) · (1/b₀)`, with `1/b₀` enclosed by an
    /// interval division; every coefficient is the whole line when `b₀` may be zero.
    fn div(self, rhs: Self) -> Self {
        let n = self.len.max(rhs.len);
        let (b0m, b0r) = (rhs.m[0], rhs.r[0]);
        let b0 = if b0m.is_finite() && b0r.is_finite() {
            point(b0m) + interval!(-b0r, b0r).unwrap_or(Interval::ENTIRE)
        } else {
            Interval::ENTIRE
        };
        if b0.contains(0.0) || b0.is_empty() {
            let mut out = Self::zero_len(n);
            out.r[..n].fill(f64::INFINITY);
            return out;
        }
        let inv0 = mid_rad(point(1.0) / b0);
        let mut out = Self::zero_len(n);
        for i in 0..n {
            let mut acc = self.pair(i);
            for k in 1..=i.min(rhs.len - 1) {
                let t = mul1(rhs.pair(k), out.pair(i - k));
                acc = add1(acc, (-t.0, t.1));
            }
            (out.m[i], out.r[i]) = mul1(acc, inv0);
        }
        out
    }
}

impl<const N: usize> Scalar for MidRadSeries<N> {
    fn terms(&self) -> usize {
        self.support()
    }
    fn from_f64(x: f64) -> Self {
        let mut s = Self::zero_len(1);
        s.m[0] = x;
        if !x.is_finite() {
            s.r[0] = f64::INFINITY;
        }
        s
    }
    fn from_interval(x: Interval) -> Self {
        let mut s = Self::zero_len(1);
        (s.m[0], s.r[0]) = mid_rad(x);
        s
    }
    fn sqr(self) -> Self {
        self * self
    }
    fn sqrt(self) -> Self {
        // Rare here: through the interval series.
        let s: SeriesN<N> = self.to_series();
        Self::from_series(&s.sqrt())
    }
    fn powi(self, n: i32) -> Self {
        let s: SeriesN<N> = self.to_series();
        Self::from_series(&s.powi(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::rounding::{uniform_pm1, xorshift};

    const N: usize = 9;
    type M = MidRadSeries<N>;

    /// `a + b` as an unevaluated sum `(s, e)`, exactly.
    fn two_sum(a: f64, b: f64) -> (f64, f64) {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    }

    /// A double-double accumulator: sums of exact products, to about 2⁻¹⁰⁰ relative to the
    /// sum of their magnitudes.
    #[derive(Clone, Copy, Default)]
    struct Dd {
        hi: f64,
        lo: f64,
        mag: f64,
    }

    impl Dd {
        fn add_prod(&mut self, x: f64, y: f64) {
            let p = x * y;
            let e = x.mul_add(y, -p);
            let (s, t) = two_sum(self.hi, p);
            self.hi = s;
            self.lo += t + e;
            self.mag += (x * y).abs();
        }
        fn add(&mut self, x: f64) {
            self.add_prod(x, 1.0);
        }
        /// Whether the accumulated value lies within `r` of `m` (with the accumulator's own
        /// error as slack).
        fn within(&self, m: f64, r: f64) -> bool {
            let (d, e) = two_sum(self.hi, -m);
            let off = (d + (e + self.lo)).abs();
            off <= r + 1e-28 * self.mag + 4.0 * f64::MIN_POSITIVE
        }
    }

    /// A random interval series: midpoints over `scale`, radii zero, tiny or wide, trailing
    /// zeros sometimes.
    fn random_series(state: &mut u64, len: usize, scale: f64) -> Vec<Interval> {
        let zeros = if xorshift(state).is_multiple_of(4) {
            (xorshift(state) % len as u64) as usize
        } else {
            0
        };
        (0..len)
            .map(|i| {
                if i >= len - zeros && i > 0 {
                    return point(0.0);
                }
                let m = scale * uniform_pm1(state) * 2f64.powi((xorshift(state) % 20) as i32 - 10);
                let r = match xorshift(state) % 4 {
                    0 | 1 => 0.0,
                    2 => m.abs() * 1e-15 * uniform_pm1(state).abs(),
                    _ => m.abs() * 1e-3 * uniform_pm1(state).abs(),
                };
                interval!(m - r, m + r).unwrap()
            })
            .collect()
    }

    /// A point of each coefficient interval: an end, the midpoint or a random inner point.
    fn sample(state: &mut u64, c: &[Interval]) -> Vec<f64> {
        c.iter()
            .map(|x| match xorshift(state) % 4 {
                0 => x.inf(),
                1 => x.sup(),
                2 => x.mid(),
                _ => x.inf() + (x.sup() - x.inf()) * 0.5 * (1.0 + uniform_pm1(state)),
            })
            .zip(c)
            .map(|(v, x)| v.clamp(x.inf(), x.sup()))
            .collect()
    }

    fn of(c: &[Interval]) -> M {
        M::from_series(&SeriesN::<N>::new(c))
    }

    /// Every coefficient of `got` holds the exact value `want[i]` (and so does its interval).
    fn check(got: &M, want: &[Dd], what: &str) {
        let back: SeriesN<N> = got.to_series();
        for (i, w) in want.iter().enumerate() {
            let (m, r) = got.pair(i);
            assert!(w.within(m, r), "{what}: coefficient {i}: {m:e} ± {r:e}");
            let c = back.coeff(i);
            assert!(c.inf() <= m - r && m + r <= c.sup() || c == Interval::ENTIRE);
        }
    }

    #[test]
    fn products_sums_and_quotients_enclose_the_exact_series() {
        let mut state = 0x5eed_1234_abcd_0001u64;
        for round in 0..4000 {
            let (la, lb) = match round % 5 {
                0 => (1, N),
                1 => (N, 1),
                2 => (2, N),
                _ => (
                    1 + (xorshift(&mut state) % N as u64) as usize,
                    1 + (xorshift(&mut state) % N as u64) as usize,
                ),
            };
            let ca = random_series(&mut state, la, 1.0);
            let mut cb = random_series(&mut state, lb, 1.0);
            if cb[0].contains(0.0) {
                cb[0] = point(0.75);
            }
            let (a, b) = (of(&ca), of(&cb));
            let (prod, sum, diff, quot) = (a * b, a + b, a - b, a / b);
            let n = la.max(lb);
            for _ in 0..4 {
                let (x, y) = (sample(&mut state, &ca), sample(&mut state, &cb));
                let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(0.0);
                // The exact product, sum and difference of the sampled series.
                let mut want_p = vec![Dd::default(); n];
                let mut want_s = vec![Dd::default(); n];
                let mut want_d = vec![Dd::default(); n];
                for i in 0..n {
                    for j in 0..=i {
                        want_p[i].add_prod(at(&x, j), at(&y, i - j));
                    }
                    want_s[i].add(at(&x, i));
                    want_s[i].add(at(&y, i));
                    want_d[i].add(at(&x, i));
                    want_d[i].add(-at(&y, i));
                }
                check(&prod, &want_p, "product");
                check(&sum, &want_s, "sum");
                check(&diff, &want_d, "difference");
                // The quotient q of the samples satisfies b·q = a: q's coefficients to double-
                // double accuracy by the same recurrence, checked against the enclosure.
                let mut q = vec![(0.0f64, 0.0f64); n];
                let mut want_q = vec![Dd::default(); n];
                for i in 0..n {
                    let mut acc = Dd::default();
                    acc.add(at(&x, i));
                    for k in 1..=i {
                        acc.add_prod(-at(&y, k), q[i - k].0);
                        acc.add_prod(-at(&y, k), q[i - k].1);
                    }
                    let hi = (acc.hi + acc.lo) / y[0];
                    let lo = {
                        // Remainder of the division, exactly, then divided.
                        let r = (-hi).mul_add(y[0], acc.hi) + acc.lo;
                        r / y[0]
                    };
                    q[i] = (hi, lo);
                    want_q[i] = Dd {
                        hi,
                        lo,
                        mag: acc.mag / y[0].abs() + hi.abs(),
                    };
                }
                let (qm, qr) = quot.pair(0);
                assert!(want_q[0].within(qm, qr), "quotient 0");
                // Higher quotient coefficients: the recurrence's own error grows with the
                // terms, so those are checked with a slack of 1e-24 relative.
                for (i, w) in want_q.iter().enumerate().skip(1) {
                    let (m, r) = quot.pair(i);
                    let (d, e) = two_sum(w.hi, -m);
                    let off = (d + (e + w.lo)).abs();
                    assert!(off <= r + 1e-24 * (w.mag + 1.0), "quotient {i}");
                }
            }
        }
    }

    #[test]
    fn exact_operations_stay_exact_and_thin_ones_stay_thin() {
        let c = |v: &[f64]| of(&v.iter().map(|&x| point(x)).collect::<Vec<_>>());
        // Small integers: sums and products by a constant are exact (a series product keeps
        // its rounding allowance, N·U of the magnitudes, tested below).
        let (a, b) = (c(&[1.0, 2.0, -3.0]), c(&[0.5, 4.0, 1.0]));
        for s in [a + b, a - b, a * c(&[2.0])] {
            assert!((0..3).all(|i| s.pair(i).1 == 0.0));
        }
        assert_eq!((a * b).pair(1).0, 0.5 * 2.0 + 4.0);
        // Inexact products get radii at the level of the rounding, not wider: within 64 ulps
        // of the magnitudes (the allowance is N·U of them).
        let mut state = 99u64;
        for _ in 0..1000 {
            let x: Vec<f64> = (0..N).map(|_| uniform_pm1(&mut state)).collect();
            let y: Vec<f64> = (0..N).map(|_| uniform_pm1(&mut state)).collect();
            let p = c(&x) * c(&y);
            for i in 0..N {
                let mag: f64 = (0..=i).map(|j| (x[j] * y[i - j]).abs()).sum();
                assert!(p.pair(i).1 <= 64.0 * f64::EPSILON * mag + 1e-300);
            }
        }
    }

    #[test]
    fn unbounded_and_undefined_give_the_whole_line() {
        let wide = MidRadSeries::<4>::from_interval(Interval::ENTIRE);
        let one = MidRadSeries::<4>::from_f64(1.0);
        let back: SeriesN<4> = (wide * one + one).to_series();
        assert_eq!(back.coeff(0), Interval::ENTIRE);
        let zero_div = one / MidRadSeries::<4>::from_interval(interval!(-1.0, 1.0).unwrap());
        let back: SeriesN<4> = zero_div.to_series();
        assert_eq!(back.coeff(0), Interval::ENTIRE);
        let big = MidRadSeries::<4>::from_f64(1e300);
        let back: SeriesN<4> = (big * big).to_series();
        assert_eq!(back.coeff(0), Interval::ENTIRE);
    }
}
