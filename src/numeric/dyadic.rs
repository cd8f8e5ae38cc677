//! Exact dyadic rationals `m·2ᵉ` (`m` a big integer): sums, differences and products of `f64`s
//! without rounding, and a rigorous enclosure of the result as an interval.
//!
//! A polynomial in `f64` data evaluated at an `f64` point is a dyadic rational, so this gives
//! a residual `P(σ, t) − Q(u, v)` at an exact point with no rounding but the last division
//! (the certifier's exact residual). Interval arithmetic loses tens of ulps of the model's
//! size there, and over nearly tangent surfaces that rounding, divided by the sine of the
//! angle between the normals, is what a link's tube cannot get below. Only `num-bigint`'s
//! integers are used: no crate offers exact dyadic numbers with outward conversion to `f64`
//! bounds, and the arithmetic needed (align, add, multiply, round outward) is short.

use inari::Interval;
use num_bigint::{BigInt, Sign};
use num_traits::{ToPrimitive, Zero};
use std::ops::{Add, Mul, Neg, Sub};

/// An exact dyadic rational `m·2ᵉ`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Dyadic {
    m: BigInt,
    e: i64,
}

impl Dyadic {
    /// Zero.
    pub(crate) fn zero() -> Self {
        Dyadic {
            m: BigInt::zero(),
            e: 0,
        }
    }

    /// The exact value of `x`; `None` if it is not finite.
    pub(crate) fn from_f64(x: f64) -> Option<Self> {
        if !x.is_finite() {
            return None;
        }
        if x == 0.0 {
            return Some(Self::zero());
        }
        let bits = x.to_bits();
        let field = ((bits >> 52) & 0x7ff) as i64;
        let frac = bits & ((1u64 << 52) - 1);
        // Normal: (2⁵² + f)·2^(E − 1075); subnormal: f·2^(−1074).
        let (mant, e) = if field == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), field - 1075)
        };
        let m = BigInt::from(mant);
        Some(Dyadic {
            m: if x < 0.0 { -m } else { m },
            e,
        })
    }

    /// An interval holding the value: its bounds are the nearest `f64`s at most one unit in the
    /// 53rd bit away on either side (exact when the value is an `f64`). `None` if the value is
    /// outside the normal range of `f64` (it would overflow or lose bits to underflow).
    pub(crate) fn enclosure(&self) -> Option<Interval> {
        if self.m.is_zero() {
            return Some(crate::numeric::scalar::point(0.0));
        }
        let negative = self.m.sign() == Sign::Minus;
        let mag = self.m.magnitude();
        let bits = mag.bits() as i64;
        // |m| = q·2^shift + r with 0 ≤ r < 2^shift and q < 2⁵³: |value| ∈ [q, q + 1]·2^(e+shift).
        let shift = (bits - 53).max(0);
        let q = (mag >> shift as u64).to_u64()?;
        let exact = shift == 0 || mag.trailing_zeros().is_some_and(|t| t as i64 >= shift);
        let scale = self.e + shift;
        // q and q + 1 are at most 2⁵³ (exact); scaling them by 2^scale, in two exact steps
        // of powers of two in the normal range, is exact when the result is a normal number.
        let top = bits.min(53) + scale; // |value| < 2^top
        let low = bits.min(53) - 1 + scale; // |value| ≥ 2^low
                                            // (Inexact, the upper bound (q + 1)·2^scale may reach 2^top itself.)
        let top = if exact { top - 1 } else { top };
        if top > 1023 || low < -1022 {
            return None;
        }
        let pow = |k: i64| f64::from_bits(((k + 1023) as u64) << 52);
        let (s1, s2) = (scale / 2, scale - scale / 2);
        let scaled = |x: f64| x * pow(s1) * pow(s2);
        let lo = scaled(q as f64);
        let hi = if exact { lo } else { scaled((q + 1) as f64) };
        let (lo, hi) = if negative { (-hi, -lo) } else { (lo, hi) };
        inari::interval!(lo, hi).ok()
    }
}

impl Add for &Dyadic {
    type Output = Dyadic;
    fn add(self, o: &Dyadic) -> Dyadic {
        if self.m.is_zero() {
            return o.clone();
        }
        if o.m.is_zero() {
            return self.clone();
        }
        let (lo, hi) = if self.e <= o.e { (self, o) } else { (o, self) };
        let shifted = &hi.m << ((hi.e - lo.e) as u64);
        Dyadic {
            m: &lo.m + shifted,
            e: lo.e,
        }
    }
}

impl Neg for &Dyadic {
    type Output = Dyadic;
    fn neg(self) -> Dyadic {
        Dyadic {
            m: -&self.m,
            e: self.e,
        }
    }
}

impl Sub for &Dyadic {
    type Output = Dyadic;
    fn sub(self, o: &Dyadic) -> Dyadic {
        self + &(-o)
    }
}

impl Mul for &Dyadic {
    type Output = Dyadic;
    fn mul(self, o: &Dyadic) -> Dyadic {
        if self.m.is_zero() || o.m.is_zero() {
            return Dyadic::zero();
        }
        Dyadic {
            m: &self.m * &o.m,
            e: self.e + o.e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(x: f64) -> Dyadic {
        Dyadic::from_f64(x).unwrap()
    }

    #[test]
    fn f64_values_round_trip_exactly() {
        for x in [
            0.0,
            1.0,
            -3.5,
            0.1,
            1e-300,
            5e-324,
            -f64::MAX,
            2.0f64.powi(-1022),
        ] {
            let e = d(x).enclosure();
            if x.abs() < 2.0f64.powi(-1022) && x != 0.0 {
                assert!(e.is_none(), "{x}: subnormal results are refused");
                continue;
            }
            let e = e.unwrap();
            assert_eq!((e.inf(), e.sup()), (x, x), "{x}");
        }
        assert!(Dyadic::from_f64(f64::NAN).is_none());
        assert!(Dyadic::from_f64(f64::INFINITY).is_none());
    }

    #[test]
    fn sums_that_cancel_are_exact() {
        // (1 + 2⁻⁶⁰) − 1 = 2⁻⁶⁰, lost in f64 arithmetic.
        let one = d(1.0);
        let tiny = d(2.0f64.powi(-60));
        let s = &(&one + &tiny) - &one;
        let e = s.enclosure().unwrap();
        assert_eq!((e.inf(), e.sup()), (2.0f64.powi(-60), 2.0f64.powi(-60)));
        // 0.1·0.1 − 0.01 (as f64s) is the product's rounding error: tiny and nonzero.
        let r = &(&d(0.1) * &d(0.1)) - &d(0.01);
        let e = r.enclosure().unwrap();
        let fma = 0.1f64.mul_add(0.1, -0.01);
        assert!(e.inf() <= fma && fma <= e.sup(), "{e:?} {fma}");
        assert!(e.wid() <= 1e-32, "{e:?}");
    }

    #[test]
    fn inexact_values_are_enclosed_by_neighbours() {
        // 1 + 2⁻⁸⁰ is not an f64: its enclosure is [1, 1 + 2⁻⁵²].
        let x = &d(1.0) + &d(2.0f64.powi(-80));
        let e = x.enclosure().unwrap();
        assert_eq!((e.inf(), e.sup()), (1.0, 1.0f64.next_up()));
        let e = (-&x).enclosure().unwrap();
        assert_eq!((e.inf(), e.sup()), (-1.0f64.next_up(), -1.0));
        // A product beyond f64's range is refused.
        assert!((&d(1e300) * &d(1e300)).enclosure().is_none());
        assert!((&d(1e-300) * &d(1e-300)).enclosure().is_none());
    }

    #[test]
    fn random_products_and_sums_are_enclosed() {
        // Against the exact value computed another way: an FMA's exact residual.
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 * 8.0 - 4.0
        };
        for _ in 0..2000 {
            let (a, b) = (next(), next());
            let p = a * b;
            let err = a.mul_add(b, -p); // a·b − p exactly (normal range)
            let exact = &(&d(a) * &d(b)) - &d(p);
            let e = exact.enclosure().unwrap();
            assert!(e.inf() <= err && err <= e.sup(), "{a} {b}: {e:?} {err}");
        }
    }
}
