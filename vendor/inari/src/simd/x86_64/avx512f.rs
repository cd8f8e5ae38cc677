// ssitrace: upstream writes these operations as inline assembly with the rounding mode
// embedded in the instruction ("vaddpd {x:z}, {x:z}, {y:z}, {ru-sae}" on a zmm register class
// holding a 128-bit value). rustc 1.95's LLVM can allocate that operand to a register it then
// prints as an invalid name ("R20BH"), and the crate fails to assemble depending on how the
// callers inline (seen in ssitrace's lib-test build). The same instructions through the
// AVX-512 intrinsics with an embedded rounding mode: the 128-bit operands widened to 512 bits
// (upper lanes zero, exceptions suppressed), the low 128 bits of the result returned.
use std::arch::x86_64::*;

use super::F64X2;

const RD: i32 = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
const RU: i32 = _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC;

#[inline]
fn wide(x: F64X2) -> __m512d {
    // SAFETY: AVX-512F is enabled at compile time (this module's cfg).
    unsafe { _mm512_zextpd128_pd512(x) }
}

#[inline]
fn narrow(x: __m512d) -> F64X2 {
    // SAFETY: as above.
    unsafe { _mm512_castpd512_pd128(x) }
}

pub(crate) fn sqrt1_rd(x: f64) -> f64 {
    // SAFETY: as above.
    unsafe {
        let a = _mm_set_sd(x);
        _mm_cvtsd_f64(_mm_sqrt_round_sd::<RD>(a, a))
    }
}

pub(crate) fn sqrt1_ru(x: f64) -> f64 {
    // SAFETY: as above.
    unsafe {
        let a = _mm_set_sd(x);
        _mm_cvtsd_f64(_mm_sqrt_round_sd::<RU>(a, a))
    }
}

pub(crate) fn sub1_ru(x: f64, y: f64) -> f64 {
    // SAFETY: as above.
    unsafe { _mm_cvtsd_f64(_mm_sub_round_sd::<RU>(_mm_set_sd(x), _mm_set_sd(y))) }
}

pub(crate) fn add_ru(x: F64X2, y: F64X2) -> F64X2 {
    // SAFETY: as above.
    narrow(unsafe { _mm512_add_round_pd::<RU>(wide(x), wide(y)) })
}

pub(crate) fn sub_ru(x: F64X2, y: F64X2) -> F64X2 {
    // SAFETY: as above.
    narrow(unsafe { _mm512_sub_round_pd::<RU>(wide(x), wide(y)) })
}

pub(crate) fn mul_ru(x: F64X2, y: F64X2) -> F64X2 {
    // SAFETY: as above.
    narrow(unsafe { _mm512_mul_round_pd::<RU>(wide(x), wide(y)) })
}

pub(crate) fn div_ru(x: F64X2, y: F64X2) -> F64X2 {
    // SAFETY: as above.
    narrow(unsafe { _mm512_div_round_pd::<RU>(wide(x), wide(y)) })
}

/// `x·y + z` rounded upward once.
pub(crate) fn mul_add_ru(x: F64X2, y: F64X2, z: F64X2) -> F64X2 {
    // SAFETY: as above.
    narrow(unsafe { _mm512_fmadd_round_pd::<RU>(wide(x), wide(y), wide(z)) })
}
