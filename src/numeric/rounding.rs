//! Directed rounding without switching the FPU mode: error-free transforms in round-to-nearest.
//!
//! `inari` sets the rounding mode around every operation, which dominates the cost of long
//! loops of simple interval operations (de Casteljau splits of Bernstein nets, rotations of
//! enclosures). Here each bound is computed in ordinary round-to-nearest and its rounding error
//! recovered exactly (TwoSum for sums, a fused multiply-add for products); the bound is stepped
//! one ulp outward only when it lies on the wrong side of the exact value, so in the normal range
//! the results are the same intervals `inari` gives (tested on random data below).
//!
//! With AVX-512, inari 2 rounds in the instruction instead; for bounded operands [`average`] and
//! [`dot_point`] then take inari's sums and [`imul`]'s branch-free product (the same
//! intervals, faster), and the error-free transforms serve the other cases.
//!
//! The a-posteriori accumulator for long sums of interval products is [`DotAcc`](super::dot::DotAcc).

use super::imul;
use inari::{const_interval, Interval};

const ENTIRE: Interval = Interval::ENTIRE;
const HALF: Interval = const_interval!(0.5, 0.5);

/// `a + b` rounded down / up (`up` false / true), exactly as directed rounding would: the
/// rounding error of the nearest sum is recovered exactly by TwoSum, and the sum stepped one ulp
/// when it lies on the wrong side. An overflowing or infinite sum is returned as is (an
/// infinite bound is only ever on the safe side or makes the caller's interval invalid).
#[inline]
pub fn add_dir(a: f64, b: f64, up: bool) -> f64 {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    if up && e > 0.0 {
        s.next_up()
    } else if !up && e < 0.0 {
        s.next_down()
    } else {
        s
    }
}

/// `a · b` rounded down / up: the error of the nearest product is exact by a fused
/// multiply-add, except near the subnormal range, where the product is stepped outward
/// unconditionally.
#[inline]
pub fn mul_dir(a: f64, b: f64, up: bool) -> f64 {
    let p = a * b;
    if p.is_nan() || p.abs() < 1e-280 {
        return if up { p.next_up() } else { p.next_down() };
    }
    let e = a.mul_add(b, -p);
    if up && e > 0.0 {
        p.next_up()
    } else if !up && e < 0.0 {
        p.next_down()
    } else {
        p
    }
}

/// `x / 2` rounded down / up: exact unless the result is subnormal (detected by doubling back).
#[inline]
pub fn half_dir(x: f64, up: bool) -> f64 {
    let h = 0.5 * x;
    if 2.0 * h == x {
        h
    } else if up {
        h.next_up()
    } else {
        h.next_down()
    }
}

/// `(a + b) / 2`, rounded outward.
#[inline]
pub fn average(a: Interval, b: Interval) -> Interval {
    // inari's sum, then each bound halved: exact where both are zero or at least 2⁻¹⁰²¹ in
    // magnitude and finite (the halves are normal numbers), the interval `(a + b)·½` rounded
    // outward would give. This is de Casteljau's inner step: one sum, no product.
    let sum = a + b;
    let (lo, hi) = (sum.inf(), sum.sup());
    let halves_exactly =
        |x: f64| x == 0.0 || (x.abs() >= 2.0 * f64::MIN_POSITIVE && x.abs() <= f64::MAX);
    if halves_exactly(lo) && halves_exactly(hi) {
        if let Ok(h) = Interval::try_from((0.5 * lo, 0.5 * hi)) {
            return h;
        }
    }
    if a.is_common_interval() && b.is_common_interval() {
        // Bounded operands: inari's sum and the branch-free product, the same interval.
        return imul::mul(sum, HALF);
    }
    let lo = half_dir(add_dir(a.inf(), b.inf(), false), false);
    let hi = half_dir(add_dir(a.sup(), b.sup(), true), true);
    Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
}

/// `b − a`, rounded outward.
#[inline]
pub fn sub(b: Interval, a: Interval) -> Interval {
    let lo = add_dir(b.inf(), -a.sup(), false);
    let hi = add_dir(b.sup(), -a.inf(), true);
    Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
}

/// `r · x` for an exact row `r` and an interval vector `x`, rounded outward (every product and
/// partial sum rounded in its bound's direction). `ENTIRE` if a bound is not a number (e.g.
/// `0 · ∞`).
pub fn dot_point(r: &[f64; 3], x: &[Interval; 3]) -> Interval {
    if r.iter().all(|v| v.is_finite()) && x.iter().all(|v| v.is_common_interval()) {
        // Bounded operands: the same interval as the loop below gives, from inari's sums and
        // the branch-free product.
        let term = |k: usize| imul::mul(Interval::try_from((r[k], r[k])).unwrap_or(ENTIRE), x[k]);
        return term(0) + term(1) + term(2);
    }
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    for (&rk, xk) in r.iter().zip(x) {
        let (a, b) = if rk >= 0.0 {
            (xk.inf(), xk.sup())
        } else {
            (xk.sup(), xk.inf())
        };
        lo = add_dir(lo, mul_dir(rk, a, false), false);
        hi = add_dir(hi, mul_dir(rk, b, true), true);
    }
    Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
}

/// One step of the xorshift64 generator: the pseudo-random test data of the numeric modules.
#[cfg(test)]
pub(crate) fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// A pseudo-random number in `[−1, 1)` from [`xorshift`] (test data).
#[cfg(test)]
pub(crate) fn uniform_pm1(state: &mut u64) -> f64 {
    (xorshift(state) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// A pseudo-random bound from [`xorshift`] (test data): zeros, ones, and signed numbers over
/// `2^±20`, with one in seventeen over `2^±1000`, whose products overflow or fall into the
/// subnormal range.
#[cfg(test)]
pub(crate) fn wide_bound(state: &mut u64) -> f64 {
    let r = xorshift(state);
    let mant = (r >> 11) as f64 / (1u64 << 53) as f64;
    let exp = ((r >> 3) % 40) as i32 - 20;
    let sign = if r & 1 == 0 { 1.0 } else { -1.0 };
    match r % 17 {
        0 => 0.0,
        1 => 1.0,
        2 => sign * mant * 2f64.powi(exp * 50),
        _ => sign * mant * 2f64.powi(exp),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::{interval, point};

    /// `x ∘ y` for `∘` in `+ − × /`, computed with the processor's rounding mode set to upward
    /// for that one instruction (inline assembly, so that the compiler cannot move the
    /// operation out of the mode): the reference for what every interval bound must be.
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    fn upward(op: char, x: f64, y: f64) -> f64 {
        let mut v = x;
        // Round up, all exceptions masked.
        let mode: u32 = 0x5f80;
        let mut saved: u32 = 0;
        // SAFETY: the block saves MXCSR, sets it, does one scalar operation on registers and
        // restores it; it touches no other memory than the two u32 named.
        unsafe {
            macro_rules! with_mode {
                ($inst:literal) => {
                    std::arch::asm!(
                        "vstmxcsr [{saved}]",
                        "vldmxcsr [{mode}]",
                        $inst,
                        "vldmxcsr [{saved}]",
                        saved = in(reg) &mut saved,
                        mode = in(reg) &mode,
                        v = inout(xmm_reg) v,
                        y = in(xmm_reg) y,
                        options(nostack),
                    )
                };
            }
            match op {
                '+' => with_mode!("vaddsd {v}, {v}, {y}"),
                '-' => with_mode!("vsubsd {v}, {v}, {y}"),
                '/' => with_mode!("vdivsd {v}, {v}, {y}"),
                _ => with_mode!("vmulsd {v}, {v}, {y}"),
            }
        }
        v
    }

    /// The lower bound `a` of the first operand at −∞ in the `k`-th of every `every` draws, the
    /// upper bound `d` of the second at +∞ in the next, both as drawn otherwise.
    fn unbounded_now_and_then(k: usize, every: usize, a: f64, d: f64) -> (f64, f64) {
        match k % every {
            0 => (f64::NEG_INFINITY, d),
            1 => (a, f64::INFINITY),
            _ => (a, d),
        }
    }

    #[test]
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    fn inari_sums_and_products_round_as_the_mode_does() {
        // inari's sums, differences, products and quotients (vendor/inari, patched to round
        // from exact errors instead of switching the mode on machines without AVX-512) must be
        // the directed-rounded corner values, bound for bound: the lower bound −▲(−…), the
        // upper one ▲(…).
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let (mut checked, mut divided) = (0, 0);
        for k in 0..300_000 {
            let mut iv = || {
                let (p, q) = (wide_bound(&mut state), wide_bound(&mut state));
                (p.min(q), p.max(q))
            };
            let ((a, b), (c, d)) = (iv(), iv());
            // Now and then an unbounded side (sums only: 0·∞ is a special case of products).
            let (a, d) = unbounded_now_and_then(k, 23, a, d);
            let (x, y) = (interval(a, b).unwrap(), interval(c, d).unwrap());
            let lo = |op, u: f64, v: f64| -upward(op, -u, v);
            let s = x + y;
            assert_eq!(
                (s.inf(), s.sup()),
                (-upward('+', -a, -c), upward('+', b, d))
            );
            let s = x - y;
            assert_eq!(
                (s.inf(), s.sup()),
                (-upward('-', -a, -d), upward('-', b, c))
            );
            if a.is_finite() && d.is_finite() {
                let corners = [(a, c), (a, d), (b, c), (b, d)];
                // The directed-rounded range of `op` over the corners.
                let range = |op| {
                    corners
                        .iter()
                        .fold((f64::MAX, f64::MIN), |(l, h), &(u, v)| {
                            (l.min(lo(op, u, v)), h.max(upward(op, u, v)))
                        })
                };
                let m = x * y;
                assert_eq!((m.inf(), m.sup()), range('*'), "{a} {b} · {c} {d}");
                checked += 1;
                if c > 0.0 || d < 0.0 {
                    let q = x / y;
                    assert_eq!((q.inf(), q.sup()), range('/'), "{a} {b} / {c} {d}");
                    divided += 1;
                }
            }
        }
        assert!(
            checked > 250_000 && divided > 100_000,
            "{checked} {divided}"
        );
    }

    /// `√x` rounded down (`up == false`) or up, with the mode set for the one instruction.
    fn directed_sqrt(x: f64, up: bool) -> f64 {
        let mut v = x;
        let mode: u32 = if up { 0x5f80 } else { 0x3f80 };
        let mut saved: u32 = 0;
        // SAFETY: as in `upward`: save MXCSR, set it, one scalar square root, restore it.
        unsafe {
            std::arch::asm!(
                "vstmxcsr [{saved}]",
                "vldmxcsr [{mode}]",
                "vsqrtsd {v}, {v}, {v}",
                "vldmxcsr [{saved}]",
                saved = in(reg) &mut saved,
                mode = in(reg) &mode,
                v = inout(xmm_reg) v,
                options(nostack),
            )
        }
        v
    }

    #[test]
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    fn inari_square_roots_round_as_the_mode_does() {
        // The bounds of inari's interval square root (its AVX-512 form embeds the rounding in
        // the instruction, vendor/inari) are the directed square roots of the bounds.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..100_000 {
            let (p, q) = (wide_bound(&mut state).abs(), wide_bound(&mut state).abs());
            let (a, b) = (p.min(q), p.max(q));
            let r = interval(a, b).unwrap().sqrt();
            assert_eq!(
                (r.inf(), r.sup()),
                (directed_sqrt(a, false), directed_sqrt(b, true)),
                "√[{a}, {b}]"
            );
        }
    }

    #[test]
    fn float_directed_helpers_match_inari() {
        // The helpers round each bound in its direction exactly as inari does (normal range):
        // the results are the same intervals, and at the subnormal edge still enclose.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            let s = xorshift(&mut seed);
            let m = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            m * 10f64.powi((s % 13) as i32 - 6)
        };
        for _ in 0..2000 {
            let (a0, a1, b0, b1) = (next(), next(), next(), next());
            let a = interval(a0.min(a1), a0.max(a1)).unwrap();
            let b = interval(b0.min(b1), b0.max(b1)).unwrap();
            assert_eq!(sub(b, a), b - a);
            assert_eq!(average(a, b), (a + b) * point(0.5));
            let r = [next(), next(), next()];
            let x = [a, b, a - b];
            let expect = point(r[0]) * x[0] + point(r[1]) * x[1] + point(r[2]) * x[2];
            assert_eq!(dot_point(&r, &x), expect);
        }
        let tiny = interval(f64::MIN_POSITIVE / 3.0, f64::MIN_POSITIVE / 3.0).unwrap();
        let exact = (tiny + tiny) * point(0.5);
        assert!(exact.subset(average(tiny, tiny)));
        let d = dot_point(&[1e-300, 0.0, 0.0], &[interval(3e-20, 3e-20).unwrap(); 3]);
        assert!((point(1e-300) * point(3e-20)).subset(d));
        // 0 · ∞ is not a number: the whole line.
        let e = dot_point(
            &[0.0, 1.0, 1.0],
            &[Interval::ENTIRE, point(1.0), point(2.0)],
        );
        assert!(e.is_entire());
    }

    #[test]
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    fn averages_are_the_directed_half_sums() {
        // The average (each bound halved exactly where it can be) against the sums under a
        // rounding mode set directly, over magnitudes from 2⁻¹⁰⁷⁴ to 2¹⁰⁰⁰
        // (subnormal halves included) and unbounded sides.
        let mut state = 0x853c_49e6_748f_ea9b_u64;
        // Bounds whose halves (or sums' halves) are subnormal or round.
        let tiny = [
            5e-324,
            1e-310,
            2.2250738585072014e-308,
            4.450147717014403e-308,
            3e-308,
        ];
        for k in 0..200_000 {
            let mut iv = || {
                let mut bound = || match xorshift(&mut state) % 5 {
                    0 => {
                        let t = tiny[(xorshift(&mut state) % 5) as usize];
                        if xorshift(&mut state).is_multiple_of(2) {
                            t
                        } else {
                            -t
                        }
                    }
                    _ => wide_bound(&mut state),
                };
                let (p, q) = (bound(), bound());
                (p.min(q), p.max(q))
            };
            let ((a, b), (c, d)) = (iv(), iv());
            let (a, d) = unbounded_now_and_then(k, 19, a, d);
            let h = average(interval(a, b).unwrap(), interval(c, d).unwrap());
            // The sums rounded down and up with the mode set: twice each bound must lie
            // beyond them (doubling is exact), and equal them where halving them is exact.
            let (s_lo, s_hi) = (-upward('+', -a, -c), upward('+', b, d));
            let (lo, hi) = (h.inf(), h.sup());
            assert!(
                lo + lo <= s_lo && hi + hi >= s_hi,
                "[{a}, {b}] ⊕ [{c}, {d}]: {h:?}"
            );
            if 2.0 * (0.5 * s_lo) == s_lo {
                assert_eq!(lo, 0.5 * s_lo, "[{a}, {b}] ⊕ [{c}, {d}]");
            }
            if 2.0 * (0.5 * s_hi) == s_hi {
                assert_eq!(hi, 0.5 * s_hi, "[{a}, {b}] ⊕ [{c}, {d}]");
            }
        }
    }

    #[test]
    fn halving_is_exact_or_outward() {
        // An average with a zero is a halving: exact in the normal range, outward below it.
        let x = interval(-3.0, 1e-310).unwrap();
        let h = average(x, point(0.0));
        assert!(h.inf() <= -1.5 && h.sup() >= 0.5e-310);
        assert_eq!(
            average(interval(2.0, 6.0).unwrap(), point(0.0)),
            interval(1.0, 3.0).unwrap()
        );
    }
}
