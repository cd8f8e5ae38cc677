//! A `Copy` truncated power series with interval coefficients, implementing [`Scalar`].
//!
//! [`Series`] stores up to [`MAX_TERMS`] coefficients inline (`[Interval; 32]` plus a length), so it
//! is `Copy` as [`Scalar`] requires and needs no allocation; a constant has length 1 and is
//! broadcast against longer operands. Every operation returns an enclosure of the truncated series
//! of the exact result for all values in the coefficient intervals. Where the result is undefined
//! (a divisor whose constant term may be zero, a square root whose argument's constant term may be
//! ≤ 0) every coefficient is the whole line, which the integrator rejects.
//!
//! Use: evaluating any generic [`Scalar`] code along a Taylor series (e.g. a patch along a curve),
//! and [`naive_expand`], the textbook way to get the solution's Taylor coefficients: evaluate `f`
//! on the series of `y` known to order `i` to get order `i + 1`. That costs `O(k)` evaluations of
//! `O(k²)` each; the engine instead uses the tape-based recurrences of [`crate::validated::ad`]
//! (`O(k²)` in total), and the `validated` benchmark measures the difference.

use crate::numeric::imul;
use crate::numeric::scalar::point;
use crate::validated::system::OdeSystem;
use crate::Scalar;
use inari::{const_interval, Interval};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Largest number of coefficients a [`Series`] holds (orders up to 31).
pub const MAX_TERMS: usize = 32;

const ZERO: Interval = const_interval!(0.0, 0.0);

/// A truncated power series `Σ_{i<len} cᵢ tⁱ` with interval coefficients: [`SeriesN`] with
/// room for [`MAX_TERMS`] of them.
pub type Series = SeriesN<MAX_TERMS>;

/// A truncated power series `Σ_{i<len} cᵢ tⁱ` with interval coefficients, at most `N` of them
/// (a small `N` makes copies cheaper).
#[derive(Clone, Copy, Debug)]
pub struct SeriesN<const N: usize> {
    c: [Interval; N],
    len: usize,
}

impl<const N: usize> SeriesN<N> {
    /// The series with the given coefficients (at most `N`; extra ones are dropped).
    pub fn new(coeffs: &[Interval]) -> Self {
        let mut c = [ZERO; N];
        let len = coeffs.len().clamp(1, N);
        c[..coeffs.len().min(N)].copy_from_slice(&coeffs[..coeffs.len().min(N)]);
        SeriesN { c, len }
    }
    /// The constant `x` (length 1).
    pub fn constant(x: Interval) -> Self {
        Self::new(&[x])
    }
    /// The coefficients.
    pub fn coeffs(&self) -> &[Interval] {
        &self.c[..self.len]
    }
    /// Coefficient `i` (zero beyond the length).
    pub fn coeff(&self, i: usize) -> Interval {
        if i < self.len {
            self.c[i]
        } else {
            ZERO
        }
    }
    fn undefined(len: usize) -> Self {
        let mut s = Self::new(&[Interval::ENTIRE]);
        s.c[..len].fill(Interval::ENTIRE);
        s.len = len;
        s
    }
    /// One past the last coefficient that is not exactly zero (at least 1).
    fn support(&self) -> usize {
        let mut l = self.len;
        while l > 1 && self.c[l - 1].inf() == 0.0 && self.c[l - 1].sup() == 0.0 {
            l -= 1;
        }
        l
    }
    fn len2(a: &Self, b: &Self) -> usize {
        a.len.max(b.len)
    }
}

impl<const N: usize> Add for SeriesN<N> {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        // The longer operand's coefficients beyond the shorter's length stay as they are
        // (adding an exact zero to an interval is exact).
        let (mut r, short) = if self.len >= rhs.len {
            (self, rhs)
        } else {
            (rhs, self)
        };
        for i in 0..short.len {
            r.c[i] += short.c[i];
        }
        r
    }
}
impl<const N: usize> Sub for SeriesN<N> {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        self + (-rhs)
    }
}
impl<const N: usize> Neg for SeriesN<N> {
    type Output = Self;
    fn neg(self) -> Self {
        let mut r = self;
        for v in &mut r.c[..self.len] {
            *v = -*v;
        }
        r
    }
}
impl<const N: usize> Mul for SeriesN<N> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        let n = Self::len2(&self, &rhs);
        let (la, lb) = (self.len, rhs.len);
        let mut r = Self::constant(ZERO);
        if la == 1 || lb == 1 {
            // A constant times a series: one product per coefficient, no sums.
            let (k, s) = if la == 1 {
                (self.c[0], &rhs)
            } else {
                (rhs.c[0], &self)
            };
            for i in 0..n {
                r.c[i] = imul::mul(k, s.c[i]);
            }
        } else {
            // Trailing coefficients that are exactly zero contribute nothing.
            let (la, lb) = (self.support(), rhs.support());
            for i in 0..n {
                // Terms m with m < la and i − m < lb.
                let (from, to) = ((i + 1).saturating_sub(lb), i.min(la - 1));
                if from > to {
                    continue;
                }
                let mut acc = ZERO;
                for m in from..=to {
                    acc += imul::mul(self.c[m], rhs.c[i - m]);
                }
                r.c[i] = acc;
            }
        }
        r.len = n;
        r
    }
}
impl<const N: usize> Div for SeriesN<N> {
    type Output = Self;
    fn div(self, rhs: Self) -> Self {
        let n = Self::len2(&self, &rhs);
        let b0 = rhs.c[0];
        if b0.contains(0.0) || b0.is_empty() {
            return Self::undefined(n);
        }
        // One division: each coefficient is multiplied by an enclosure of `1/b0` (a superset of
        // the quotient, one rounding wider, and several times cheaper than a division).
        let inv0 = point(1.0) / b0;
        let mut r = Self::constant(ZERO);
        for i in 0..n {
            let mut acc = self.coeff(i);
            for m in 1..=i.min(rhs.len - 1) {
                acc -= imul::mul(rhs.c[m], r.c[i - m]);
            }
            r.c[i] = imul::mul(acc, inv0);
        }
        r.len = n;
        r
    }
}

impl<const N: usize> Scalar for SeriesN<N> {
    fn terms(&self) -> usize {
        self.support()
    }
    fn from_f64(x: f64) -> Self {
        Self::constant(point(x))
    }
    fn from_interval(x: Interval) -> Self {
        Self::constant(x)
    }
    fn sqr(self) -> Self {
        let n = self.len;
        let mut r = Self::constant(ZERO);
        for i in 0..n {
            let mut acc = ZERO;
            for m in 0..i.div_ceil(2) {
                acc += imul::mul(self.c[m], self.c[i - m]);
            }
            acc = acc + acc;
            if i % 2 == 0 {
                acc += self.c[i / 2].sqr();
            }
            r.c[i] = acc;
        }
        r.len = n;
        r
    }
    fn sqrt(self) -> Self {
        let n = self.len;
        let a0 = self.c[0];
        if a0.is_empty() || a0.inf() <= 0.0 {
            return Self::undefined(n);
        }
        let mut r = Self::constant(a0.sqrt());
        let two_c0 = r.c[0] + r.c[0];
        for i in 1..n {
            let mut acc = ZERO;
            for m in 1..i.div_ceil(2) {
                acc += imul::mul(r.c[m], r.c[i - m]);
            }
            acc = acc + acc;
            if i % 2 == 0 {
                acc += r.c[i / 2].sqr();
            }
            r.c[i] = (self.c[i] - acc) / two_c0;
        }
        r.len = n;
        r
    }
    fn powi(self, n: i32) -> Self {
        if n == 0 {
            return Self::one();
        }
        let mut e = n.unsigned_abs();
        let mut base = self;
        let mut acc = Self::one();
        while e > 0 {
            if e & 1 == 1 {
                acc = acc * base;
            }
            e >>= 1;
            if e > 0 {
                base = base.sqr();
            }
        }
        if n < 0 {
            Self::one() / acc
        } else {
            acc
        }
    }
}

/// The normalised Taylor coefficients `y₀ … y_order` of the solution of `y' = f(y)` through every
/// point of the box `y0`, by the naive scheme (`order + 1 ≤ MAX_TERMS`): `coeffs[i][j]`.
/// Returns `None` if the field is undefined on the way or `order` is too large.
pub fn naive_expand<F: OdeSystem>(
    system: &F,
    y0: &[Interval],
    order: usize,
) -> Option<Vec<Vec<Interval>>> {
    if order + 1 > MAX_TERMS || y0.len() != system.dim() {
        return None;
    }
    let mut ys: Vec<Series> = y0.iter().map(|v| Series::constant(*v)).collect();
    for i in 0..order {
        let f = system.eval(&ys);
        if f.len() != ys.len() {
            return None;
        }
        let div = point((i + 1) as f64);
        for (y, fj) in ys.iter_mut().zip(&f) {
            let next = fj.coeff(i) / div;
            if !next.is_common_interval() {
                return None;
            }
            y.c[i + 1] = next;
            y.len = i + 2;
        }
    }
    Some(
        (0..=order)
            .map(|i| ys.iter().map(|y| y.coeff(i)).collect())
            .collect(),
    )
}
