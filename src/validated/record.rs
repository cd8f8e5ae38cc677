//! What one validated step reports, and enclosures on sub-intervals of a step.

use super::enclosure::EnclosureMethod;
use super::lohner::{mat_mul, mat_vec};
use crate::error::{Error, InputProblem, Result};
use crate::scalar::interval;
use inari::Interval;

/// One proven step from `t0` to `t0 + h`.
///
/// Guarantees, for every solution starting (at `t0`) in the step's initial set: it exists and is
/// unique on `[t0, t0 + h]`, lies in [`apriori`](Self::apriori) there, lies in
/// [`end`](Self::end) at `t0 + h`, and at `t0 + τ` (`0 ≤ τ ≤ h`) its deviation from
/// `Σ_{i<k} coeffs[i]·τⁱ` lies in `remainder_coeff·τᵏ` (each coefficient an enclosure over the
/// whole initial set).
#[derive(Clone, Debug)]
pub struct StepRecord {
    /// Start time `s_j`.
    pub t0: f64,
    /// End time `s_j + h` (exact; the next step starts here).
    pub t1: f64,
    /// Step size: an upper bound of `t1 − t0`; everything below is proven for `τ ∈ [0, h]`.
    pub h: f64,
    /// Enclosure `[y_j]` of the initial set at `t0`.
    pub start: Vec<Interval>,
    /// The a-priori box `[ỹ_j]`: all solutions on the whole step `[t0, t0 + h]`.
    pub apriori: Vec<Interval>,
    /// The tight end box `[y_{j+1}]` at `t0 + h`.
    pub end: Vec<Interval>,
    /// Taylor coefficients `yᵢ` (`i < k`) at `t0`, enclosing them for the whole initial set.
    pub coeffs: Vec<Vec<Interval>>,
    /// The remainder coefficient `y_k([ỹ_j])`.
    pub remainder_coeff: Vec<Interval>,
    /// Which phase-I test proved the a-priori box.
    pub method: EnclosureMethod,
    /// Mean-value data: Taylor coefficients at the centre `x̂` of the initial set for `i < p`, and
    /// over the initial box for `p ≤ i < k` (`p` = the number of Jacobians).
    pub(crate) center_coeffs: Vec<Vec<Interval>>,
    /// Mean-value data: `Jᵢ` (`i < p`, `1 ≤ p ≤ k`) row-major over the initial box.
    pub(crate) jacobians: Vec<Vec<Interval>>,
    /// Mean-value data: the initial set is `x̂ + A·[r]`; this is `A` (interval copy of exact values).
    pub(crate) basis: Vec<Interval>,
    /// Mean-value data: `[r]`.
    pub(crate) r: Vec<Interval>,
}

impl StepRecord {
    /// The order `k` used for this step.
    pub fn order(&self) -> usize {
        self.coeffs.len()
    }

    /// Encloses every solution of the step's initial set at all times `t0 + τ`, `τ ∈ [a, b]`,
    /// `0 ≤ a ≤ b ≤ h`: the intersection of the direct Taylor form, the mean-value form (centre
    /// polynomial plus `(Σ Jᵢ τⁱ)·A·[r]`, which does not wrap) and the a-priori box. Errors on an
    /// invalid sub-interval.
    pub fn enclose_on(&self, a: f64, b: f64) -> Result<Vec<Interval>> {
        if !(a.is_finite() && b.is_finite()) {
            return Err(Error::input("enclose_on(a, b)", InputProblem::NonFinite));
        }
        if !(0.0 <= a && a <= b && b <= self.h) {
            return Err(Error::input(
                "enclose_on(a, b)",
                InputProblem::EmptyDomain { lo: a, hi: b },
            ));
        }
        let t = interval(a, b).unwrap_or(Interval::ENTIRE);
        let n = self.start.len();
        let horner = |cs: &[Vec<Interval>], top: &[Interval]| -> Vec<Interval> {
            let mut acc = top.to_vec();
            for c in cs.iter().rev() {
                for j in 0..n {
                    acc[j] = acc[j] * t + c[j];
                }
            }
            acc
        };
        let direct = horner(&self.coeffs, &self.remainder_coeff);
        let central = horner(&self.center_coeffs, &self.remainder_coeff);
        // S(τ) = Σ_{i<p} Jᵢ τⁱ, by Horner on matrices (orders p..k are ranges in `central`).
        let p = self.jacobians.len();
        let mut s = self.jacobians[p - 1].clone();
        for jac in self.jacobians[..p - 1].iter().rev() {
            for (sv, jv) in s.iter_mut().zip(jac) {
                *sv = *sv * t + *jv;
            }
        }
        let spread = mat_vec(&mat_mul(&s, &self.basis, n), &self.r, n);
        Ok((0..n)
            .map(|j| {
                let mv = central[j] + spread[j];
                let best = direct[j].intersection(mv).intersection(self.apriori[j]);
                if best.is_empty() {
                    // Cannot happen in exact arithmetic (all three enclose the solutions).
                    self.apriori[j]
                } else {
                    best
                }
            })
            .collect())
    }

    /// Largest width of the end box.
    pub fn end_width(&self) -> f64 {
        self.end.iter().map(|v| v.wid()).fold(0.0, f64::max)
    }
}
