use std::arch::asm;

macro_rules! impl_op_round {
    ($t:ty, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, rd) => {
        impl_op_round!($t, $f ($x $(,$y)*), $inst, "16256"); // _MM_ROUND_DOWN | _MM_MASK_MASK
    };

    ($t:ty, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, ru) => {
        impl_op_round!($t, $f ($x $(,$y)*), $inst, "24448"); // _MM_ROUND_UP | _MM_MASK_MASK
    };

    ($t:ty, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, $mxcsr:literal) => {
        pub(crate) fn $f(mut $x: $t, $($y: $t,)*) -> $t {
            unsafe {
                asm!(
                    "push {rax}", // Same as "sub rsp, 8", but does not modify flags.
                    "vstmxcsr [rsp]",
                    concat!("mov dword ptr [rsp + 4], ", $mxcsr),
                    "vldmxcsr [rsp + 4]",
                    $inst,
                    "vldmxcsr [rsp]",
                    "pop {rax}", // Same as "add rsp, 8", but does not modify flags.
                    $x = inout(xmm_reg) $x,
                    $($y = in(xmm_reg) $y,)*
                    rax = out(reg) _, // Any 64-bit general-purpose register.
                    options(pure, nomem, preserves_flags)
                );
            }
            $x
        }
    };
}

impl_op_round!(f64, sqrt1_rd(x), "vsqrtsd {x}, {x}, {x}", rd);
impl_op_round!(f64, sqrt1_ru(x), "vsqrtsd {x}, {x}, {x}", ru);
impl_op_round!(f64, sub1_ru(x, y), "vsubsd {x}, {x}, {y}", ru);
impl_op_round!(super::F64X2, add_ru_csr(x, y), "vaddpd {x}, {x}, {y}", ru);
impl_op_round!(super::F64X2, sub_ru_csr(x, y), "vsubpd {x}, {x}, {y}", ru);
impl_op_round!(super::F64X2, mul_ru_csr(x, y), "vmulpd {x}, {x}, {y}", ru);
impl_op_round!(super::F64X2, div_ru_csr(x, y), "vdivpd {x}, {x}, {y}", ru);
impl_op_round!(
    super::F64X2,
    mul_add_ru(x, y, z),
    "vfmadd213pd {x}, {y}, {z}",
    ru
);

// ssitrace's change (see PATCHED.md): `add_ru`, `sub_ru`, `mul_ru` and `div_ru` no longer
// switch the rounding mode. Each lane is computed rounded to nearest together with its exact
// error (Knuth's two-sum for `+` and `−`, a fused multiply-add for `×` and for the remainder of
// `/`), and the result is moved one float up where the error is positive: that is the
// upward-rounded result, bit for bit. Where the error might not be exact (a non-finite lane; a
// product below 2⁻⁹⁶⁰ without a zero operand; a quotient whose operands or result leave
// [2⁻⁴⁰⁰, 2⁴⁰⁰]) the original rounding-mode form `*_csr` runs instead.

use std::arch::x86_64::*;

/// `s` rounded upward, given that the exact value is `s + e`: one float up where `e > 0` (then
/// `s ≠ 0`, and one step of the bit pattern is +1 for `s > 0`, −1 for `s < 0`).
#[inline(always)]
unsafe fn up_from(s: __m128d, e: __m128d) -> __m128d {
    let zero = _mm_setzero_pd();
    let neg = _mm_castpd_si128(_mm_cmplt_pd(s, zero));
    let step = _mm_or_si128(neg, _mm_set1_epi64x(1));
    let above = _mm_castpd_si128(_mm_cmpgt_pd(e, zero));
    _mm_castsi128_pd(_mm_add_epi64(_mm_castpd_si128(s), _mm_and_si128(step, above)))
}

/// Whether `|v| ≤ MAX` in both lanes (false for infinities and NaN).
#[inline(always)]
unsafe fn both_finite(v: __m128d) -> bool {
    let m = _mm_andnot_pd(_mm_set1_pd(-0.0), v);
    _mm_movemask_pd(_mm_cmple_pd(m, _mm_set1_pd(f64::MAX))) == 3
}

/// `x + y` rounded upward, lane by lane, from the to-nearest sum and its exact error.
#[inline(always)]
unsafe fn sum_ru(x: __m128d, y: __m128d) -> Option<__m128d> {
    let s = _mm_add_pd(x, y);
    let v = _mm_sub_pd(s, x);
    let e = _mm_add_pd(_mm_sub_pd(x, _mm_sub_pd(s, v)), _mm_sub_pd(y, v));
    // A non-finite operand or an overflow anywhere leaves `s` or `e` non-finite.
    (both_finite(s) && both_finite(e)).then(|| up_from(s, e))
}

#[inline]
pub(crate) fn add_ru(x: super::F64X2, y: super::F64X2) -> super::F64X2 {
    unsafe { sum_ru(x, y) }.unwrap_or_else(|| add_ru_csr(x, y))
}

#[inline]
pub(crate) fn sub_ru(x: super::F64X2, y: super::F64X2) -> super::F64X2 {
    unsafe { sum_ru(x, _mm_xor_pd(y, _mm_set1_pd(-0.0))) }.unwrap_or_else(|| sub_ru_csr(x, y))
}

/// `x / y` rounded upward, lane by lane: `q = ○(x/y)` and the remainder `r = x − q·y` by a fused
/// multiply-add, exact when `|x|`, `|y|`, `|q|` lie in `[2⁻⁴⁰⁰, 2⁴⁰⁰]` (or `x = 0`, `q = ±0`);
/// the exact quotient is `q + r/y`, above `q` where `r·y > 0`.
#[inline]
pub(crate) fn div_ru(x: super::F64X2, y: super::F64X2) -> super::F64X2 {
    unsafe {
        let q = _mm_div_pd(x, y);
        let r = _mm_fnmadd_pd(q, y, x);
        let sign = _mm_set1_pd(-0.0);
        let within = |v: __m128d| {
            let m = _mm_andnot_pd(sign, v);
            _mm_and_pd(
                _mm_cmpge_pd(m, _mm_set1_pd(f64::from_bits((1023 - 400) << 52))),
                _mm_cmple_pd(m, _mm_set1_pd(f64::from_bits((1023 + 400) << 52))),
            )
        };
        let numerator = _mm_or_pd(
            _mm_and_pd(within(x), within(q)),
            _mm_cmpeq_pd(x, _mm_setzero_pd()),
        );
        if _mm_movemask_pd(_mm_and_pd(within(y), numerator)) != 3 {
            return div_ru_csr(x, y);
        }
        // r·sign(y): the sign of the quotient's error.
        up_from(q, _mm_xor_pd(r, _mm_and_pd(y, sign)))
    }
}

#[inline]
pub(crate) fn mul_ru(x: super::F64X2, y: super::F64X2) -> super::F64X2 {
    unsafe {
        let p = _mm_mul_pd(x, y);
        let e = _mm_fmsub_pd(x, y, p);
        let zero = _mm_setzero_pd();
        let m = _mm_andnot_pd(_mm_set1_pd(-0.0), p);
        // |p| ≥ 2⁻⁹⁶⁰: the exponents' sum is far above the least at which the error is a float.
        let in_range = _mm_and_pd(
            _mm_cmpge_pd(m, _mm_set1_pd(f64::from_bits((1023 - 960) << 52))),
            _mm_cmple_pd(m, _mm_set1_pd(f64::MAX)),
        );
        // A zero operand and a finite other: p = ±0 exactly, e = 0.
        let zero_operand = _mm_and_pd(
            _mm_cmpord_pd(p, p),
            _mm_or_pd(_mm_cmpeq_pd(x, zero), _mm_cmpeq_pd(y, zero)),
        );
        if _mm_movemask_pd(_mm_or_pd(in_range, zero_operand)) != 3 {
            return mul_ru_csr(x, y);
        }
        up_from(p, e)
    }
}

/// The interval product `[−a; b]·[−c; d]` as `[−lo; hi]` for finite bounds, without branching
/// on the operands' signs (inari's case analysis mispredicts in series products whose
/// coefficients change sign from one product to the next): the four corner products `ac`,
/// `bd`, `ad`, `bc` in one multiply, each rounded up and down from its exact error as in
/// [`mul_ru`], then `hi` the largest rounded-up one and `lo` the least rounded-down one. Each
/// corner is rounded as inari's own case would round it, so the result is the same interval.
/// `None` where a corner is not finite, or below 2⁻⁹⁶⁰ without a zero operand.
#[cfg(target_feature = "avx2")]
#[inline]
pub(crate) fn mul_corners(x: super::F64X2, y: super::F64X2) -> Option<super::F64X2> {
    unsafe {
        // xs = [−a, b, −a, b], ys = [−c, d, −d, c]: the products are ac, bd, ad, bc.
        let xs = _mm256_set_m128d(x, x);
        let swapped = _mm_shuffle_pd::<0b01>(y, y); // [d; −c]
        let ys = _mm256_xor_pd(
            _mm256_set_m128d(swapped, y), // [−c, d, d, −c]
            _mm256_set_pd(-0.0, -0.0, 0.0, 0.0),
        );
        let p = _mm256_mul_pd(xs, ys);
        let e = _mm256_fmsub_pd(xs, ys, p);
        let zero = _mm256_setzero_pd();
        let m = _mm256_andnot_pd(_mm256_set1_pd(-0.0), p);
        let in_range = _mm256_and_pd(
            _mm256_cmp_pd::<_CMP_GE_OQ>(m, _mm256_set1_pd(f64::from_bits((1023 - 960) << 52))),
            _mm256_cmp_pd::<_CMP_LE_OQ>(m, _mm256_set1_pd(f64::MAX)),
        );
        let zero_operand = _mm256_and_pd(
            _mm256_cmp_pd::<_CMP_ORD_Q>(p, p),
            _mm256_or_pd(
                _mm256_cmp_pd::<_CMP_EQ_OQ>(xs, zero),
                _mm256_cmp_pd::<_CMP_EQ_OQ>(ys, zero),
            ),
        );
        if _mm256_movemask_pd(_mm256_or_pd(in_range, zero_operand)) != 0b1111 {
            return None;
        }
        // One step of the bit pattern: up is +1 for p > 0 and −1 for p < 0, down the opposite.
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
        Some(_mm_max_pd(_mm_unpacklo_pd(d2, u2), _mm_unpackhi_pd(d2, u2)))
    }
}
