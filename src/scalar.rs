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
        self.pown(n)
    }
}

/// The interval `[lo, hi]`; `None` if `lo > hi` or either bound is NaN.
pub fn interval(lo: f64, hi: f64) -> Option<Interval> {
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    Interval::try_from((lo, hi)).ok()
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
            assert!(i.inf() <= f && f <= i.sup(), "{x}: {f} not in [{}, {}]", i.inf(), i.sup());
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
    fn sqrt_of_interval_encloses_root() {
        let r = point(2.0).sqrt();
        assert!(r.inf() <= std::f64::consts::SQRT_2 && std::f64::consts::SQRT_2 <= r.sup());
    }
}
