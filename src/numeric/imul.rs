//! Interval multiplication without branching on the operands' signs.
//!
//! `inari`'s product classifies both operands by sign (nine cases and the zero and empty ones)
//! and jumps to the case's formula; in the Taylor-series products of the certifier (the
//! coefficients' signs vary from one product to the next) the mispredicted jumps made that
//! product the largest single cost of a certified run (about half of all samples on the
//! cylinders scene). [`mul`] forms all eight directed corner products in one AVX-512 multiply
//! with the rounding embedded in the instruction (upward; a lower bound is the negated upward
//! product of a negated operand), and takes the largest of each four:
//!
//! ```text
//! sup = ▲max(ac, ad, bc, bd),   inf = −▲max((−a)c, (−a)d, (−b)c, (−b)d)
//! ```
//!
//! Upward rounding is monotone, so `▲max zᵢ = max ▲zᵢ`: the result is the interval `inari`
//! returns, bound for bound (the test below compares them on random data, signed zeros aside).
//! Empty, unbounded or otherwise non-finite operands take `inari`'s product; so does every
//! operand on a machine without AVX-512.

use inari::Interval;

/// The product `x·y`, the same enclosure as `inari`'s `x * y`.
#[inline]
pub fn mul(x: Interval, y: Interval) -> Interval {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
    {
        let (a, b, c, d) = (x.inf(), x.sup(), y.inf(), y.sup());
        // NaN and infinite bounds (and a sum that overflows, which only sends finite operands
        // to the general path) fail this test.
        if (a + b + c + d).is_finite() {
            let [lo, hi] = corners_up(a, b, c, d);
            if let Ok(r) = Interval::try_from((lo, hi)) {
                return r;
            }
        }
    }
    x * y
}

/// `[▼min, ▲max]` of the four corner products of `[a, b]·[c, d]` (finite bounds).
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
#[inline]
fn corners_up(a: f64, b: f64, c: f64, d: f64) -> [f64; 2] {
    use std::arch::x86_64::{
        _mm512_mul_round_pd, _mm512_set_pd, _mm512_storeu_pd, _MM_FROUND_NO_EXC,
        _MM_FROUND_TO_POS_INF,
    };
    let mut z = [0.0f64; 8];
    // SAFETY: the target feature is enabled at compile time (cfg above); the store writes the
    // eight lanes into an array of eight f64.
    unsafe {
        // Lanes 0..3: a·c, a·d, b·c, b·d; lanes 4..7: the same with a, b negated.
        let xs = _mm512_set_pd(-b, -b, -a, -a, b, b, a, a);
        let ys = _mm512_set_pd(d, c, d, c, d, c, d, c);
        let p = _mm512_mul_round_pd::<{ _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC }>(xs, ys);
        _mm512_storeu_pd(z.as_mut_ptr(), p);
    }
    let hi = z[0].max(z[1]).max(z[2].max(z[3]));
    let neg_lo = z[4].max(z[5]).max(z[6].max(z[7]));
    [-neg_lo, hi]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::rounding::xorshift;

    fn random_bound(state: &mut u64) -> f64 {
        let r = xorshift(state);
        let mant = (r >> 11) as f64 / (1u64 << 53) as f64;
        let exp = ((r >> 3) % 40) as i32 - 20;
        let sign = if r & 1 == 0 { 1.0 } else { -1.0 };
        match r % 17 {
            0 => 0.0,
            1 => 1.0,
            _ => sign * mant * 2f64.powi(exp),
        }
    }

    #[test]
    fn products_are_inaris_bound_for_bound() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            let mut iv = || {
                let (p, q) = (random_bound(&mut state), random_bound(&mut state));
                Interval::try_from((p.min(q), p.max(q))).unwrap()
            };
            let (x, y) = (iv(), iv());
            let (ours, theirs) = (mul(x, y), x * y);
            assert_eq!(ours.inf(), theirs.inf(), "{x:?}·{y:?}");
            assert_eq!(ours.sup(), theirs.sup(), "{x:?}·{y:?}");
        }
    }

    #[test]
    fn unbounded_and_empty_operands_follow_inari() {
        let one = Interval::try_from((1.0, 2.0)).unwrap();
        let zero = Interval::try_from((0.0, 0.0)).unwrap();
        for x in [Interval::ENTIRE, Interval::EMPTY, zero, one] {
            for y in [Interval::ENTIRE, Interval::EMPTY, zero, one] {
                let (ours, theirs) = (mul(x, y), x * y);
                assert_eq!(ours.is_empty(), theirs.is_empty());
                if !ours.is_empty() {
                    assert_eq!((ours.inf(), ours.sup()), (theirs.inf(), theirs.sup()));
                }
            }
        }
    }
}
