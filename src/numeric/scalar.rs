//! The crate-local scalar trait.
//!
//! Geometry and ODE right-hand sides are written once, generically over [`Scalar`], and evaluated
//! in plain `f64` (fast, non-rigorous), in [`inari::Interval`] (rigorous enclosures, every rounding
//! outward) and in truncated Taylor series with interval coefficients (the validated ODE engine).

use inari::Interval;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Arithmetic needed by patch evaluation and by the intersection ODE.
///
/// Implementations for rigorous types (intervals, interval Taylor series) must return enclosures
/// of the exact results; `f64` is the plain floating-point evaluation and claims nothing.
pub trait Scalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The value `x`, represented exactly (every finite `f64` is exactly representable).
    fn from_f64(x: f64) -> Self;
    /// A coefficient known only as an interval: rigorous types enclose all of `x`; `f64` takes the
    /// midpoint (and so is not rigorous).
    fn from_interval(x: Interval) -> Self;
    /// The square `self²` (tighter than `self * self` for intervals containing zero).
    fn sqr(self) -> Self;
    /// The square root (for intervals: of the non-negative part).
    fn sqrt(self) -> Self;
    /// Integer power `selfⁿ` (negative `n` allowed).
    fn powi(self, n: i32) -> Self;
    /// Zero.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// One.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// How many stored terms a product with this value runs over: 1 for a number; for a
    /// truncated series, its coefficients up to the last one that is not exactly zero (an
    /// affine series costs 2 per coefficient of a product, a full one up to its length).
    /// Evaluation orders may use it; values never depend on it.
    fn terms(&self) -> usize {
        1
    }
}

impl Scalar for f64 {
    fn from_f64(x: f64) -> Self {
        x
    }
    fn from_interval(x: Interval) -> Self {
        x.mid()
    }
    fn sqr(self) -> Self {
        self * self
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn powi(self, n: i32) -> Self {
        f64::powi(self, n)
    }
}

impl Scalar for Interval {
    fn from_f64(x: f64) -> Self {
        Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
    }
    fn from_interval(x: Interval) -> Self {
        x
    }
    fn sqr(self) -> Self {
        Interval::sqr(self)
    }
    fn sqrt(self) -> Self {
        Interval::sqrt(self)
    }
    fn powi(self, n: i32) -> Self {
        interval_powi(self, n)
    }
}

/// `xⁿ` for an interval, tight (monotone on each sign) and rigorous.
fn interval_powi(x: Interval, n: i32) -> Interval {
    if x.is_empty() {
        return x;
    }
    if n == 0 {
        return point(1.0);
    }
    if n < 0 {
        return point(1.0) / interval_powi(x, -n);
    }
    // Enclosure of aⁿ for a single number a, by repeated squaring in intervals.
    let pow_point = |a: f64| {
        let (mut base, mut e, mut acc) = (point(a), n as u32, point(1.0));
        while e > 0 {
            if e & 1 == 1 {
                acc *= base;
            }
            base = Interval::sqr(base);
            e >>= 1;
        }
        acc
    };
    if n % 2 == 1 {
        interval(pow_point(x.inf()).inf(), pow_point(x.sup()).sup()).unwrap_or(Interval::ENTIRE)
    } else {
        interval(pow_point(x.mig()).inf(), pow_point(x.mag()).sup()).unwrap_or(Interval::ENTIRE)
    }
}

/// The interval `[lo, hi]`; `None` if `lo > hi` or either bound is NaN.
pub fn interval(lo: f64, hi: f64) -> Option<Interval> {
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    Interval::try_from((lo, hi)).ok()
}

/// Two enclosures of the same value combined: their intersection, or `a` where rounding left
/// them disjoint (never empty; each encloses the value alone).
pub fn meet(a: Interval, b: Interval) -> Interval {
    let both = a.intersection(b);
    if both.is_empty() {
        a
    } else {
        both
    }
}

/// The point interval `[x, x]` (an exact enclosure of `x`). Non-finite `x` gives the whole line.
pub fn point(x: f64) -> Interval {
    <Interval as Scalar>::from_f64(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly<S: Scalar>(x: S) -> S {
        x.sqr() * S::from_f64(3.0) - x / S::from_f64(7.0) + x.powi(3) - S::one()
    }

    #[test]
    fn interval_evaluation_encloses_f64_evaluation() {
        for k in 0..200 {
            let x = -2.0 + 0.02 * k as f64;
            let i = poly(point(x));
            let f = poly(x);
            assert!(
                i.inf() <= f && f <= i.sup(),
                "{x}: {f} not in [{}, {}]",
                i.inf(),
                i.sup()
            );
            assert!(i.wid() < 1e-13);
        }
    }

    #[test]
    fn interval_constructor_rejects_inverted_bounds() {
        assert!(interval(1.0, 0.0).is_none());
        assert!(interval(f64::NAN, 0.0).is_none());
        assert_eq!(interval(0.0, 1.0).unwrap().wid(), 1.0);
    }

    #[test]
    fn interval_powers_are_tight_and_enclosing() {
        let x = interval(-1.0, 2.0).unwrap();
        let c = x.powi(3);
        assert!(
            c.inf() <= -1.0 && c.inf() > -1.0 - 1e-15 && c.sup() >= 8.0 && c.sup() < 8.0 + 1e-14
        );
        let e = x.powi(4);
        assert!(e.inf() == 0.0 && e.sup() >= 16.0 && e.sup() < 16.0 + 1e-13);
        let r = point(3.0).powi(-2);
        assert!(r.inf() <= 1.0 / 9.0 && 1.0 / 9.0 <= r.sup());
    }

    #[test]
    fn sqrt_of_interval_encloses_root() {
        let r = point(2.0).sqrt();
        assert!(r.inf() <= std::f64::consts::SQRT_2 && std::f64::consts::SQRT_2 <= r.sup());
    }
}
