//! Fast rigorous sums of interval products (the convolutions of Taylor-mode AD).
//!
//! `inari` switches the FPU rounding mode around every operation, which dominates the cost of the
//! `O(k²)` convolutions. [`DotAcc`] instead forms each product's bounds and the running sums in
//! ordinary round-to-nearest and adds one a-posteriori error bound at the end:
//!
//! for `N` terms `[a, b]·[c, d]`, let `lo`/`hi` be the round-to-nearest sums of the min/max of the
//! four rounded corner products and `A` the round-to-nearest sum of `max(|a|,|b|)·max(|c|,|d|)`.
//! Each corner product is off by at most `u·A_m + η` (`u = 2⁻⁵³`, `η = 2⁻¹⁰⁷⁵` for underflow), and a
//! recursive sum of `N` terms by at most `γ_{N−1}·Σ|terms|`; with the slack for `A` itself being
//! rounded, the exact sum of the exact products lies in
//! `[lo − B, hi + B]`, `B = (N + 4)·2⁻⁵²·A + (N + 1)·2⁻¹⁰⁷⁴` (a factor of about 2 to spare);
//! `B` is evaluated with one more unit in each term to absorb its own rounding, and the final
//! bounds are moved one ulp outward after rounding to nearest. Any non-finite bound gives the
//! whole line.

use crate::numeric::scalar::point;
use inari::Interval;

/// `2⁻¹⁰⁰⁰`, a normal number exceeding the underflow allowance `(n + 2)·2⁻¹⁰⁷⁴` of any sum.
const UNDERFLOW_PAD: f64 = 9.332636185032189e-302;

/// A rigorous accumulator of sums of interval products.
pub trait IntervalDot: Copy {
    /// An empty sum.
    fn start() -> Self;
    /// Adds the product `x·y`.
    fn add(&mut self, x: Interval, y: Interval);
    /// An interval enclosing the exact sum of the exact products.
    fn total(self) -> Interval;
}

/// The plain `inari` sum: one outward-rounded operation at a time (tightest, slower).
#[derive(Clone, Copy, Debug)]
pub struct InariDot(Interval);

impl IntervalDot for InariDot {
    #[inline]
    fn start() -> Self {
        InariDot(point(0.0))
    }
    #[inline]
    fn add(&mut self, x: Interval, y: Interval) {
        self.0 += crate::numeric::imul::mul(x, y);
    }
    #[inline]
    fn total(self) -> Interval {
        self.0
    }
}

impl IntervalDot for DotAcc {
    #[inline]
    fn start() -> Self {
        DotAcc::new()
    }
    #[inline]
    fn add(&mut self, x: Interval, y: Interval) {
        self.add_prod(x, y)
    }
    #[inline]
    fn total(self) -> Interval {
        self.finish()
    }
}

/// Accumulates `Σ xₘ·yₘ` for intervals; [`finish`](Self::finish) returns an enclosure.
#[derive(Clone, Copy, Debug, Default)]
pub struct DotAcc {
    lo: f64,
    hi: f64,
    mag: f64,
    check: f64,
    n: u32,
}

/// The smaller of `x` and `y` by one comparison (a single `minsd`; `f64::min`'s care for a NaN
/// operand costs a compare and a blend more). A NaN can only come from a non-finite operand,
/// which [`DotAcc::finish`] turns into the whole line anyway.
#[inline(always)]
fn min(x: f64, y: f64) -> f64 {
    if x < y {
        x
    } else {
        y
    }
}

/// The larger of `x` and `y` by one comparison (see [`min`]).
#[inline(always)]
fn max(x: f64, y: f64) -> f64 {
    if x > y {
        x
    } else {
        y
    }
}

impl DotAcc {
    /// An empty sum.
    #[inline]
    pub fn new() -> Self {
        DotAcc::default()
    }

    /// Adds the product `x·y`.
    #[inline]
    pub fn add_prod(&mut self, x: Interval, y: Interval) {
        let (a, b, c, d) = (x.inf(), x.sup(), y.inf(), y.sup());
        let (p1, p2, p3, p4) = (a * c, a * d, b * c, b * d);
        self.lo += min(min(p1, p2), min(p3, p4));
        self.hi += max(max(p1, p2), max(p3, p4));
        self.mag += max(a.abs(), b.abs()) * max(c.abs(), d.abs());
        // Any infinite or NaN bound (unbounded or empty operands) poisons this sum.
        self.check += a + b + c + d;
        self.n += 1;
    }

    /// An interval enclosing the exact sum of the exact products.
    #[inline]
    pub fn finish(self) -> Interval {
        if self.n == 0 {
            return point(0.0);
        }
        if !(self.lo.is_finite()
            && self.hi.is_finite()
            && self.mag.is_finite()
            && self.check.is_finite())
        {
            return Interval::ENTIRE;
        }
        let n = self.n as f64;
        // B = (n + 4)·2⁻⁵²·A + (n + 1)·2⁻¹⁰⁷⁴, evaluated in round-to-nearest with one extra unit in
        // the first factor: the two roundings of the product and the one of the sum (relative
        // 3·2⁻⁵³ of B) are covered by the extra 2⁻⁵²·A, an underflow of the product (absolute
        // 2⁻¹⁰⁷⁵) by the generous underflow pad.
        // The underflow part uses the normal number 2⁻¹⁰⁰⁰ ≥ (n + 2)·2⁻¹⁰⁷⁴ (n < 2⁷³): arithmetic on
        // subnormal numbers is very slow on x86.
        let bound = (n + 5.0) * f64::EPSILON * self.mag + UNDERFLOW_PAD;
        // One ulp outward of a round-to-nearest result is on the correct side of the exact value.
        let lo = (self.lo - bound).next_down();
        let hi = (self.hi + bound).next_up();
        crate::numeric::scalar::interval(lo, hi).unwrap_or(Interval::ENTIRE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::rounding::uniform_pm1;
    use crate::numeric::scalar::interval;

    #[test]
    fn dot_encloses_interval_products_and_is_tight() {
        let xs = [
            interval(-1.0, 2.0).unwrap(),
            point(0.1),
            interval(3.0, 3.5).unwrap(),
            point(-1e-300),
        ];
        let ys = [
            interval(0.5, 0.75).unwrap(),
            point(0.3),
            interval(-2.0, -1.0).unwrap(),
            point(1e-300),
        ];
        let mut acc = DotAcc::new();
        let mut reference = point(0.0);
        for (x, y) in xs.iter().zip(&ys) {
            acc.add_prod(*x, *y);
            reference += *x * *y;
        }
        let got = acc.finish();
        assert!(reference.subset(got), "{got:?} vs {reference:?}");
        // The a-posteriori bound is 2(N + 4)·u·Σ|x||y| ≈ 1.5e-14 per side here.
        assert!(got.wid() - reference.wid() < 4e-14, "{got:?}");
        // Unbounded operands give the whole line.
        let mut bad = DotAcc::new();
        bad.add_prod(Interval::ENTIRE, point(0.0));
        assert!(!bad.finish().is_common_interval());
        let mut empty = DotAcc::new();
        empty.add_prod(Interval::EMPTY, point(1.0));
        assert!(!empty.finish().is_common_interval());
    }

    #[test]
    fn dot_encloses_inari_sum_on_pseudo_random_data() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || uniform_pm1(&mut state);
        for trial in 0..2000 {
            let n = 1 + trial % 40;
            let scale = 10f64.powi((trial % 9) * 20 - 80);
            let mut acc = DotAcc::new();
            let mut reference = point(0.0);
            for _ in 0..n {
                let (a, w1, b, w2) = (
                    next() * scale,
                    next().abs() * scale * 0.1,
                    next(),
                    next().abs() * 1e-3,
                );
                let x = interval(a, a + w1).unwrap();
                let y = interval(b, b + w2).unwrap();
                acc.add_prod(x, y);
                reference += x * y;
            }
            let got = acc.finish();
            assert!(
                reference.subset(got),
                "trial {trial}: {got:?} vs {reference:?}"
            );
        }
    }

    #[test]
    fn underflow_pad_is_two_to_the_minus_1000() {
        assert_eq!(UNDERFLOW_PAD, 2f64.powi(-1000));
        const { assert!(UNDERFLOW_PAD >= f64::MIN_POSITIVE) };
    }
}
