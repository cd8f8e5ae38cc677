//! What one validated step reports, and enclosures on sub-intervals of a step.

use crate::error::{Error, InputProblem, Result};
use crate::numeric::scalar::{interval, point};
use crate::validated::enclosure::EnclosureMethod;
use crate::validated::lohner::{mat_mul, mat_vec};
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
    /// Mean-value data: `Jᵢ` (`i < p`, `1 ≤ p ≤ k`) row-major over the initial box; empty for a
    /// step without the mean-value form (then `center_coeffs` are the ranges over the box).
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
        // S(τ)·A·[r], S(τ) = Σ_{i<p} Jᵢ τⁱ (orders p..k are ranges in `central`).
        let spread = self.spread(t);
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

    /// A polynomial close to the solution from the centre of the initial set: the midpoints of
    /// the coefficients at the centre (orders below the number of Jacobians) and over the initial
    /// box (the others), `k` coefficients of dimension `n`.
    pub fn centre_polynomial(&self) -> Vec<Vec<f64>> {
        self.center_coeffs
            .iter()
            .map(|c| c.iter().map(|x| x.mid()).collect())
            .collect()
    }

    /// For any polynomial `poly` (coefficients `poly[i][j]` of `τⁱ`, at most `k` of them, each of
    /// dimension `n`), a proven bound per component of `|y(t0 + τ) − Σ poly[i]·τⁱ|` over
    /// `τ ∈ [0, h]` and every solution from the initial set: the smaller of the direct Taylor form
    /// (coefficient ranges over the initial box) and the mean-value form (centre coefficients
    /// plus `(Σ Jᵢ τⁱ)·A·[r]`, which does not wrap the initial set). Errors on a wrong shape.
    pub fn deviation_bound(&self, poly: &[Vec<f64>]) -> Result<Vec<f64>> {
        let n = self.start.len();
        let k = self.coeffs.len();
        if poly.len() > k || poly.iter().any(|c| c.len() != n) {
            return Err(Error::input(
                "poly",
                InputProblem::WrongCount {
                    expected: k,
                    found: poly.len(),
                },
            ));
        }
        let t = interval(0.0, self.h).unwrap_or(Interval::ENTIRE);
        let zero = vec![0.0; n];
        let horner = |cs: &[Vec<Interval>]| -> Vec<Interval> {
            let mut acc = self.remainder_coeff.clone();
            for (i, c) in cs.iter().enumerate().rev() {
                let pc = poly.get(i).unwrap_or(&zero);
                for j in 0..n {
                    acc[j] = acc[j] * t + (c[j] - point(pc[j]));
                }
            }
            acc
        };
        let direct = horner(&self.coeffs);
        let central = horner(&self.center_coeffs);
        let spread = self.spread(t);
        Ok((0..n)
            .map(|j| direct[j].mag().min((central[j] + spread[j]).mag()))
            .collect())
    }

    /// `(Σ_{i<p} Jᵢ tⁱ)·A·[r]` for the times `t`: the mean-value part of the deviation of the
    /// solutions from the one through the centre.
    fn spread(&self, t: Interval) -> Vec<Interval> {
        let n = self.start.len();
        let p = self.jacobians.len();
        if p == 0 {
            // No mean-value data: the centre coefficients are the ranges over the initial box.
            return vec![point(0.0); n];
        }
        let mut s = self.jacobians[p - 1].clone();
        for jac in self.jacobians[..p - 1].iter().rev() {
            for (sv, jv) in s.iter_mut().zip(jac) {
                *sv = *sv * t + *jv;
            }
        }
        mat_vec(&mat_mul(&s, &self.basis, n), &self.r, n)
    }

    /// Largest width of the end box.
    pub fn end_width(&self) -> f64 {
        self.end.iter().map(|v| v.wid()).fold(0.0, f64::max)
    }
}
