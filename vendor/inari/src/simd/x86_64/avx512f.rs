// ssitrace: upstream puts the 128-bit lane pairs below in the `zmm_reg` class (zmm0–zmm31) and
// names the 512-bit register with the `:z` modifier. With rustc 1.95 LLVM then sometimes
// allocates one of the EVEX-only registers 16–31 and prints it under an invalid name
// (`vaddpd R20BH, R20BH, zmm1, {ru-sae}`), and the crate fails to assemble depending on how
// callers inline (ssitrace's lib-test build, after an unrelated change). The `xmm_reg` class
// (xmm0–xmm15) keeps the same instructions on registers whose 512-bit names print correctly.
// (Intrinsics with an embedded rounding mode, or 512-bit operands, also assemble, but measured
// 5–7 % slower on a certified chain.)
use std::arch::asm;

macro_rules! impl_op_round {
    ($t:ty, $reg:ident, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, rd) => {
        impl_op_round!($t, $reg, $f ($x $(,$y)*), $inst, "{{rd-sae}}");
    };

    ($t:ty, $reg:ident, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, ru) => {
        impl_op_round!($t, $reg, $f ($x $(,$y)*), $inst, "{{ru-sae}}");
    };

    ($t:ty, $reg:ident, $f:ident ($x:ident $(,$y:ident)*), $inst:literal, $er:literal) => {
        pub(crate) fn $f(mut $x: $t, $($y: $t,)*) -> $t {
            unsafe {
                asm!(
                    concat!($inst, ", ", $er),
                    $x = inout($reg) $x,
                    $($y = in($reg) $y,)*
                    options(pure, nomem, nostack, preserves_flags)
                );
                $x
            }
        }
    };
}

impl_op_round!(f64, xmm_reg, sqrt1_rd(x), "vsqrtsd {x}, {x}, {x}", rd);
impl_op_round!(f64, xmm_reg, sqrt1_ru(x), "vsqrtsd {x}, {x}, {x}", ru);
impl_op_round!(f64, xmm_reg, sub1_ru(x, y), "vsubsd {x}, {x}, {y}", ru);
impl_op_round!(
    super::F64X2,
    xmm_reg,
    add_ru(x, y),
    "vaddpd {x:z}, {x:z}, {y:z}",
    ru
);
impl_op_round!(
    super::F64X2,
    xmm_reg,
    sub_ru(x, y),
    "vsubpd {x:z}, {x:z}, {y:z}",
    ru
);
impl_op_round!(
    super::F64X2,
    xmm_reg,
    mul_ru(x, y),
    "vmulpd {x:z}, {x:z}, {y:z}",
    ru
);
impl_op_round!(
    super::F64X2,
    xmm_reg,
    div_ru(x, y),
    "vdivpd {x:z}, {x:z}, {y:z}",
    ru
);
impl_op_round!(
    super::F64X2,
    xmm_reg,
    mul_add_ru(x, y, z),
    "vfmadd213pd {x:z}, {y:z}, {z:z}",
    ru
);

/// ssitrace (PATCHED.md): the interval product `[−a; b]·[−c; d]` as `[−lo; hi]` for finite
/// operands without branching on their signs: all eight directed corner products in one
/// multiply rounded upward (a lower bound is the negated upward product of a negated operand),
/// the largest of each four. Upward rounding is monotone, so this is inari's interval bound for
/// bound. `None` when an operand is not finite (empty or unbounded).
#[inline]
pub(crate) fn mul_corners(x: super::F64X2, y: super::F64X2) -> Option<super::F64X2> {
    use std::arch::x86_64::*;
    // SAFETY: AVX-512F is enabled at compile time (this module's cfg).
    unsafe {
        // v − v is 0 for finite v and NaN for an infinite or NaN one.
        let t = _mm_add_pd(_mm_sub_pd(x, x), _mm_sub_pd(y, y));
        if _mm_movemask_pd(_mm_cmpunord_pd(t, t)) != 0 {
            return None;
        }
        // xs = [−a, b, −a, b, −a, b, −a, b]; ys = [−c, d, −d, c, c, −c, d, −d]: products 0..3
        // are ac, bd, ad, bc (the upper bound's candidates), 4..7 are −ac, −bc, −ad, −bd.
        let xs = _mm512_broadcast_f64x2(x);
        let y8 = _mm512_castpd128_pd512(y);
        let perm = _mm512_permutexvar_pd(_mm512_set_epi64(1, 1, 0, 0, 0, 1, 1, 0), y8);
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
        let z = _mm512_max_pd(z, _mm512_permute_pd::<0b0101_0101>(z));
        let z = _mm512_max_pd(z, _mm512_shuffle_f64x2::<0b1011_0001>(z, z));
        // Lane 4 holds −lo, lane 0 holds hi.
        let out = _mm512_permutexvar_pd(_mm512_set_epi64(0, 0, 0, 0, 0, 0, 0, 4), z);
        Some(_mm512_castpd512_pd128(out))
    }
}
