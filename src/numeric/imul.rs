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
//! non-finite operands take `inari`'s product. Without AVX-512, an AVX2 + FMA form (below)
//! rounds each corner from its exact error instead, without touching the rounding mode.

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
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma",
        not(target_feature = "avx512f")
    ))]
    {
        if let Some(r) = fma::mul_finite(x, y) {
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

/// The AVX2 + FMA product, for machines without AVX-512, in the rounding mode the program
/// runs in (to nearest): no write to the MXCSR register, which `inari` changes twice per
/// operation and which stalls the pipeline on some processors (AMD Zen 3: half of a certified
/// run's samples were in `inari`'s product, most of them at `ldmxcsr`).
///
/// The four corner products `p = ○(x·y)` are formed in one multiply and their exact errors
/// `e = x·y − p` by one fused multiply-add (exact whenever the product neither overflows nor
/// comes near the subnormal range, which is checked: `|p|` in `[2⁻⁹⁶⁰, MAX]`, or an operand
/// exactly zero). Then the upward-rounded product is `p` where `e ≤ 0` and the next float up
/// where `e > 0`, the downward one likewise; the next float is one step of the bit pattern
/// (`p ≠ 0` there: a zero `p` has `e = 0` once underflow is excluded). So each corner is rounded
/// exactly as `inari` rounds it in directed mode, and the result is `inari`'s, bound for bound.
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma",
    not(target_feature = "avx512f")
))]
mod fma {
    use inari::Interval;
    use std::arch::x86_64::*;

    const _: () = assert!(std::mem::size_of::<Interval>() == std::mem::size_of::<__m128d>());

    /// `2⁻⁹⁶⁰`: above it a product's rounding error is a float (and far from subnormal).
    const TINY: f64 = f64::from_bits((1023 - 960) << 52);

    /// `x·y` when both have finite bounds and no corner product is near underflow or
    /// overflow (`None` otherwise).
    #[inline]
    pub(super) fn mul_finite(x: Interval, y: Interval) -> Option<Interval> {
        // SAFETY: the target features are enabled at compile time (cfg on the module);
        // `Interval` and `__m128d` have the same size (asserted above) and every bit pattern
        // is a valid `__m128d`. The register built at the end is `[−lo; hi]` with finite
        // `lo ≤ hi` (the checks exclude non-finite corners; `lo` is a rounded-down and `hi` a
        // rounded-up corner product), a valid `inari` interval.
        unsafe {
            let xr: __m128d = std::mem::transmute::<Interval, __m128d>(x); // [−a; b]
            let yr: __m128d = std::mem::transmute::<Interval, __m128d>(y); // [−c; d]
                                                                           // v − v is 0 for finite v and NaN for an infinite or NaN one.
            let t = _mm_add_pd(_mm_sub_pd(xr, xr), _mm_sub_pd(yr, yr));
            if _mm_movemask_pd(_mm_cmpunord_pd(t, t)) != 0 {
                return None;
            }
            // xs = [−a, b, −a, b], ys = [−c, d, −d, c]: the products are ac, bd, ad, bc.
            let xs = _mm256_set_m128d(xr, xr);
            let swapped = _mm_shuffle_pd::<0b01>(yr, yr); // [d; −c]
            let ys = _mm256_xor_pd(
                _mm256_set_m128d(swapped, yr), // [−c, d, d, −c]
                _mm256_set_pd(-0.0, -0.0, 0.0, 0.0),
            );
            let p = _mm256_mul_pd(xs, ys);
            let e = _mm256_fmsub_pd(xs, ys, p);
            // |p| in [2⁻⁹⁶⁰, MAX] (false for NaN), or an operand exactly zero (then p = ±0
            // exactly, the other operand being finite).
            let zero = _mm256_setzero_pd();
            let m = _mm256_andnot_pd(_mm256_set1_pd(-0.0), p);
            let in_range = _mm256_and_pd(
                _mm256_cmp_pd::<_CMP_GE_OQ>(m, _mm256_set1_pd(TINY)),
                _mm256_cmp_pd::<_CMP_LE_OQ>(m, _mm256_set1_pd(f64::MAX)),
            );
            let zero_operand = _mm256_or_pd(
                _mm256_cmp_pd::<_CMP_EQ_OQ>(xs, zero),
                _mm256_cmp_pd::<_CMP_EQ_OQ>(ys, zero),
            );
            if _mm256_movemask_pd(_mm256_or_pd(in_range, zero_operand)) != 0b1111 {
                return None;
            }
            // One step of the bit pattern away from zero is +1, towards it −1: the step up is
            // +1 for p > 0 and −1 for p < 0 (`neg | 1`), the step down its negation.
            let neg = _mm256_castpd_si256(_mm256_cmp_pd::<_CMP_LT_OQ>(p, zero));
            let step = _mm256_or_si256(neg, _mm256_set1_epi64x(1));
            let above = _mm256_castpd_si256(_mm256_cmp_pd::<_CMP_GT_OQ>(e, zero));
            let below = _mm256_castpd_si256(_mm256_cmp_pd::<_CMP_LT_OQ>(e, zero));
            let bits = _mm256_castpd_si256(p);
            let up = _mm256_castsi256_pd(_mm256_add_epi64(bits, _mm256_and_si256(step, above)));
            let down = _mm256_castsi256_pd(_mm256_sub_epi64(bits, _mm256_and_si256(step, below)));
            // hi = max(up), −lo = max(−down).
            let neg_down = _mm256_xor_pd(down, _mm256_set1_pd(-0.0));
            let u2 = _mm_max_pd(_mm256_castpd256_pd128(up), _mm256_extractf128_pd::<1>(up));
            let d2 = _mm_max_pd(
                _mm256_castpd256_pd128(neg_down),
                _mm256_extractf128_pd::<1>(neg_down),
            );
            let out = _mm_max_pd(_mm_unpacklo_pd(d2, u2), _mm_unpackhi_pd(d2, u2));
            Some(std::mem::transmute::<__m128d, Interval>(out))
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
