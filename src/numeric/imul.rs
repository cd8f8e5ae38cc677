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
//! The operands are read and the result written in `inari`'s own register form, `[−a; b]`, so
//! that no bound is extracted or checked one at a time (a first version through `inf()`,
//! `sup()` and `Interval::try_from` saved half as much). Empty, unbounded or otherwise
//! non-finite operands take `inari`'s product; so does every operand on a machine without
//! AVX-512, where the vendored `inari` (`vendor/inari/PATCHED.md`) forms the same four corners
//! without branches itself, each rounded from its exact error.

use inari::Interval;

/// The product `x·y`, the same enclosure as `inari`'s `x * y`.
#[inline]
pub fn mul(x: Interval, y: Interval) -> Interval {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
    {
        if let Some(r) = raw::mul_finite(x, y) {
            return r;
        }
    }
    x * y
}

/// The AVX-512 product on `inari`'s own representation of an interval `[a, b]`: one SIMD
/// register holding `[−a; b]` (documented in inari 2.0's `interval.rs`; `Interval` is
/// `#[repr(C)]` around that one register, which the size assertion below and the
/// bound-for-bound test against `inari` check).
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod raw {
    use inari::Interval;
    use std::arch::x86_64::*;

    const _: () = assert!(std::mem::size_of::<Interval>() == std::mem::size_of::<__m128d>());

    /// `x·y` when both have finite bounds (`None` otherwise: empty, unbounded).
    #[inline]
    pub(super) fn mul_finite(x: Interval, y: Interval) -> Option<Interval> {
        // SAFETY: the target feature is enabled at compile time (cfg on the module);
        // `Interval` and `__m128d` have the same size (asserted above) and every bit pattern
        // is a valid `__m128d`. The register built at the end is `[−lo; hi]` with finite or
        // outward-infinite `lo ≤ hi` (an upward product of finite numbers is never NaN, and
        // `lo` is a rounded-down, `hi` a rounded-up corner product), a valid `inari` interval.
        unsafe {
            let xr: __m128d = std::mem::transmute::<Interval, __m128d>(x); // [−a; b]
            let yr: __m128d = std::mem::transmute::<Interval, __m128d>(y); // [−c; d]
                                                                           // v − v is 0 for finite v and NaN for an infinite or NaN one.
            let t = _mm_add_pd(_mm_sub_pd(xr, xr), _mm_sub_pd(yr, yr));
            if _mm_movemask_pd(_mm_cmpunord_pd(t, t)) != 0 {
                return None;
            }
            // xs = [−a, b, −a, b, −a, b, −a, b];
            // ys = [−c, d, −d, c, c, −c, d, −d] (lanes 0..7):
            // products 0..3 = ac, bd, ad, bc (the upper bound's candidates),
            // products 4..7 = −ac, −bc, −ad, −bd (the negated lower bound's).
            let xs = _mm512_broadcast_f64x2(xr);
            let y8 = _mm512_castpd128_pd512(yr);
            let idx = _mm512_set_epi64(1, 1, 0, 0, 0, 1, 1, 0);
            let perm = _mm512_permutexvar_pd(idx, y8); // [−c, d, d, −c, −c, −c, d, d]
                                                       // Negate lanes 2, 3, 4 and 7 (arguments from lane 7 down to lane 0).
            let sign = _mm512_castsi512_pd(_mm512_set_epi64(
                i64::MIN,
                0,
                0,
                i64::MIN,
                i64::MIN,
                i64::MIN,
                0,
                0,
            ));
            let ys = _mm512_xor_pd(perm, sign);
            let z = _mm512_mul_round_pd::<{ _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC }>(xs, ys);
            // Pairwise maxima, then across the two pairs of each half.
            let z = _mm512_max_pd(z, _mm512_permute_pd::<0b0101_0101>(z));
            let z = _mm512_max_pd(z, _mm512_shuffle_f64x2::<0b1011_0001>(z, z));
            // Lane 4 holds −lo, lane 0 holds hi.
            let out = _mm512_permutexvar_pd(_mm512_set_epi64(0, 0, 0, 0, 0, 0, 0, 4), z);
            Some(std::mem::transmute::<__m128d, Interval>(
                _mm512_castpd512_pd128(out),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::rounding::wide_bound;

    #[test]
    fn products_are_inaris_bound_for_bound() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            let mut iv = || {
                let (p, q) = (wide_bound(&mut state), wide_bound(&mut state));
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
