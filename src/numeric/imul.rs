//! Interval multiplication without branching on the operands' signs.
//!
//! `inari`'s product classified both operands by sign (nine cases and the zero and empty ones)
//! and jumped to the case's formula; in the Taylor-series products of the certifier (the
//! coefficients' signs vary from one product to the next) the mispredicted jumps made that
//! product the largest single cost of a certified run (about half of all samples on the
//! cylinders scene). The vendored `inari` (`vendor/inari/PATCHED.md`) now forms the corner
//! products without branches for finite operands on every supported machine: with AVX-512 all
//! eight directed corners in one multiply with the rounding embedded in the instruction
//! (upward; a lower bound is the negated upward product of a negated operand), the largest of
//! each four,
//!
//! ```text
//! sup = ▲max(ac, ad, bc, bd),   inf = −▲max((−a)c, (−a)d, (−b)c, (−b)d);
//! ```
//!
//! with AVX2 and FMA the four corners each rounded from its exact error. Upward rounding is
//! monotone, so `▲max zᵢ = max ▲zᵢ`: the interval of inari's case analysis, bound for bound
//! (`numeric::rounding`'s tests compare the product with the corners computed under a rounding
//! mode set directly). Empty, unbounded or tiny operands take the case analysis.
//!
//! [`mul`] is that product under the name the series code uses; it once held the AVX-512 form
//! itself, before `inari`'s own product did.

use inari::Interval;

/// The product `x·y`: `inari`'s `x * y`.
#[inline]
pub fn mul(x: Interval, y: Interval) -> Interval {
    x * y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::interval;

    #[test]
    fn unbounded_empty_and_zero_operands_give_the_standard_products() {
        // IEEE 1788: the empty set absorbs, {0} times anything nonempty is {0} (also times the
        // whole line), a bounded nonzero interval times the whole line is the whole line.
        let one_two = interval(1.0, 2.0).unwrap();
        let zero = interval(0.0, 0.0).unwrap();
        for x in [Interval::ENTIRE, Interval::EMPTY, zero, one_two] {
            assert!(mul(Interval::EMPTY, x).is_empty() && mul(x, Interval::EMPTY).is_empty());
            if !x.is_empty() {
                assert_eq!(mul(zero, x), zero);
                assert_eq!(mul(x, zero), zero);
            }
        }
        assert!(mul(Interval::ENTIRE, one_two).is_entire());
        assert!(mul(Interval::ENTIRE, Interval::ENTIRE).is_entire());
        let half_line = interval(1.0, f64::INFINITY).unwrap();
        let p = mul(half_line, interval(-2.0, -1.0).unwrap());
        assert_eq!((p.inf(), p.sup()), (f64::NEG_INFINITY, -1.0));
        let q = mul(one_two, one_two);
        assert_eq!((q.inf(), q.sup()), (1.0, 4.0));
    }
}
