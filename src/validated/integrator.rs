//! The driver: step-size control, phase I, phase II (mean-value form + Lohner QR), output.
//!
//! One step from `t` with initial set `x̂ + A·[r]` (interval hull `[y]`):
//! 1. expand over `B = hull([y], x̂)` (coefficients to order `k`);
//! 2. step size `h = min_{i ∈ {k−1, k}, i ≥ 2} (ε/‖mid yᵢ(B)‖∞)^{1/i}` (the midpoints estimate
//!    the coefficients at the centre), `ε = term_target·max(1, ‖x̂‖∞)`, then
//!    scaled by the ratio accepted at the previous step, capped by `h_max` and the time left;
//! 3. phase I ([`prove_apriori_with_guess`]) proves `[ỹ]` over `[t, t + h]`; on failure `h`
//!    shrinks by 0.7 until `h_min`, below which the integrator stops with [`Error::StepFailed`];
//!    if the validated remainder `hᵏ·‖y_k([ỹ])‖` exceeds ε (or 1e-9 of the set's width, if
//!    larger), the step is cut to `h' = h·(ε/rem)^{1/k}` keeping `[ỹ]` and `y_k([ỹ])` (valid over
//!    `[0, h'] ⊂ [0, h]`; `[ỹ]` is intersected with the Taylor form over `[0, h']`), or, when the
//!    cut cannot be represented, `h` shrinks and phase I runs again (at most 6 times);
//! 4. (with [`Integrator::set_mean_value`]`(false)`: the end box is the direct Taylor form
//!    `Σ_{i<k} yᵢ(B) hⁱ + hᵏ·y_k([ỹ])` ∩ `[ỹ]`, no Jacobians; otherwise:)
//!    phase II: `u = Σ_{i<p} yᵢ(x̂) hⁱ + Σ_{p≤i<k} yᵢ(B) hⁱ + hᵏ·y_k([ỹ])`, `S = Σ_{i<p} Jᵢ hⁱ`;
//!    then every solution at `t + h` lies in `u + S·A·[r]` (mean-value theorem over the convex box
//!    `B` for the orders below `p`, the range over `B` for the others, Taylor with the Lagrange
//!    remainder over `[ỹ]`), which the [`LohnerSet`] update re-encloses without wrapping; the end
//!    box is the hull of the new set intersected with `u + S·([y] − x̂)` and `[ỹ]`. `p ≤ k` is the
//!    smallest order for which the widths `Σ_{p≤i<k} w(yᵢ(B)) hⁱ` (the part that wraps) stay below
//!    a tenth of the remainder target; the Jacobians, `n` times the cost of the coefficients, are
//!    then computed to order `p` only (on thin sets `p` is a few units, not `k`), and so is the
//!    expansion at the centre `x̂`.

pub use crate::error::StepFailure;
use crate::error::{Error, Result};
use crate::numeric::scalar::{interval, point};
use crate::validated::ad::{Expansion, TaylorAd};
use crate::validated::enclosure::{
    prove_apriori_with_guess, refine_remainder, remainder_ratio, taylor_poly, Apriori,
    EnclosureMethod, DEFAULT_GUESS_FACTOR,
};
use crate::validated::lohner::{mat_mul, mat_vec, LohnerSet};
use crate::validated::record::StepRecord;
use crate::validated::system::OdeSystem;
use crate::validated::tape::Tape;
use crate::Scalar;
use inari::Interval;

/// How many times one step may shrink `h` because the validated remainder exceeds `ε`.
const MAX_REMAINDER_SHRINKS: usize = 6;

/// The remainder may be this fraction of the current set's width without shrinking the step.
const REMAINDER_FRACTION_OF_WIDTH: f64 = 1e-9;

/// Parameters of the validated integrator.
#[derive(Clone, Copy, Debug)]
pub struct IntegratorOptions {
    /// Taylor order `k` (1..=60; orders up to 30 are the intended range).
    pub order: usize,
    /// Target size of the last Taylor terms per step, `ε` in the module docs (absolute, scaled
    /// by `max(1, ‖x̂‖∞)`); it also sets the target of the validated remainder.
    pub term_target: f64,
    /// Smallest step size phase I may try before giving up.
    pub h_min: f64,
    /// Largest step size.
    pub h_max: f64,
    /// Keep the set in Lohner's QR form (`true`) or as a plain box (`false`, wraps).
    pub qr: bool,
    /// Maximum number of steps of one [`Integrator::integrate`] call.
    pub max_steps: usize,
}

impl Default for IntegratorOptions {
    fn default() -> Self {
        IntegratorOptions {
            order: 20,
            term_target: 1e-16,
            h_min: 1e-10,
            h_max: f64::INFINITY,
            qr: true,
            max_steps: 1_000_000,
        }
    }
}

/// The integrator's current state: time and the set `x̂ + A·[r]` with a tight box around it.
#[derive(Clone, Debug)]
pub struct IntegratorState {
    /// Current time (exact).
    pub(crate) t: f64,
    /// The Lohner set enclosing all solutions at `t`.
    pub(crate) set: LohnerSet,
    /// A box enclosing all solutions at `t` (not necessarily the whole Lohner set).
    pub(crate) boxed: Vec<Interval>,
    /// Step-size memory: the ratio of the last accepted step to its point-coefficient prediction
    /// (the validated remainder usually forces a smaller step than the prediction; starting from
    /// the last ratio saves repeated phase-I attempts). Starts at 1.
    pub(crate) step_ratio: f64,
    /// First remainder guess of phase I, relative to the initial box's own remainder term
    /// (learnt from the last proven step; see [`crate::validated::enclosure::prove_apriori_with_guess`]).
    pub(crate) guess_factor: f64,
}

impl IntegratorState {
    /// The current time.
    pub fn t(&self) -> f64 {
        self.t
    }
    /// A box enclosing every solution at [`t`](Self::t).
    pub fn enclosure(&self) -> &[Interval] {
        &self.boxed
    }
    /// The Lohner set `x̂ + A·[r]` enclosing every solution at [`t`](Self::t).
    pub fn set(&self) -> &LohnerSet {
        &self.set
    }
}

/// A validated integration from `t0` to `t_end`: every step's record.
#[derive(Clone, Debug)]
pub struct Trajectory {
    /// The steps, in order; `steps[j].t1 == steps[j + 1].t0`.
    pub steps: Vec<StepRecord>,
    /// Enclosure of all solutions at the final time.
    pub end: Vec<Interval>,
    /// The final time reached (equals the requested end time).
    pub t_end: f64,
}

impl Trajectory {
    /// Largest width of the final box.
    pub fn end_width(&self) -> f64 {
        self.end.iter().map(|v| v.wid()).fold(0.0, f64::max)
    }
}

/// Work done by an [`Integrator`] (for profiling): how many steps and phase-I attempts, and the
/// Taylor recurrence cost per phase in the units of [`crate::validated::AdWork`] (coefficients plus
/// Jacobians).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IntegratorWork {
    /// Steps proven.
    pub steps: usize,
    /// Calls of phase I (one per step size tried).
    pub phase1_attempts: usize,
    /// Phase-I calls that failed (the step size shrank by 0.7).
    pub phase1_failures: usize,
    /// Phase-I calls repeated because the validated remainder missed its target.
    pub remainder_shrinks: usize,
    /// Steps cut short, without a new phase I, because the validated remainder missed its target.
    pub remainder_cuts: usize,
    /// Cost of the expansions over the initial box (step-size prediction and coefficients).
    pub box_units: f64,
    /// Cost of the phase-I expansions (a-priori box and remainder).
    pub phase1_units: f64,
    /// Cost of the phase-II expansions (Jacobians and the centre).
    pub phase2_units: f64,
    /// What sized the steps, summed over them: the steps `h`.
    pub h_sum: f64,
    /// The root-test radius `min_{k/2 ≤ i ≤ k} ‖yᵢ‖^{−1/i}` of the coefficients over the (thin)
    /// initial box: about the point solution's radius of convergence. Summed over the steps.
    pub radius_point_sum: f64,
    /// `‖y_k([ỹ])‖^{−1/k}` of the remainder coefficient over the a-priori box: the radius the
    /// validated remainder behaves as if it had, `h ≈ radius · (ε/C)^{1/k}`. Summed over the
    /// steps. When it is well below [`radius_point_sum`](Self::radius_point_sum), the interval
    /// coefficients over the a-priori box (which spans the step in every coordinate) limit the
    /// step, not the solution's own series.
    pub radius_apriori_sum: f64,
}

impl std::ops::AddAssign for IntegratorWork {
    /// Adds another run's counts and costs to these.
    fn add_assign(&mut self, w: IntegratorWork) {
        self.steps += w.steps;
        self.phase1_attempts += w.phase1_attempts;
        self.phase1_failures += w.phase1_failures;
        self.remainder_shrinks += w.remainder_shrinks;
        self.remainder_cuts += w.remainder_cuts;
        self.box_units += w.box_units;
        self.phase1_units += w.phase1_units;
        self.phase2_units += w.phase2_units;
        self.h_sum += w.h_sum;
        self.radius_point_sum += w.radius_point_sum;
        self.radius_apriori_sum += w.radius_apriori_sum;
    }
}

/// A validated Taylor integrator for one [`OdeSystem`].
#[derive(Clone, Debug)]
pub struct Integrator {
    ad: TaylorAd,
    options: IntegratorOptions,
    exp_center: Expansion,
    exp_box: Expansion,
    exp_jac: Expansion,
    scratch: Expansion,
    remainder_pieces: usize,
    mean_value: bool,
    adaptive_guess: bool,
    work: IntegratorWork,
}

impl Integrator {
    /// Records the system's field and checks the options (typed error on bad ones).
    pub fn new<F: OdeSystem>(system: &F, options: IntegratorOptions) -> Result<Self> {
        let o = &options;
        if o.order == 0 || o.order > 60 {
            return Err(Error::BadIntegratorSetup(format!(
                "order {} is not in 1..=60",
                o.order
            )));
        }
        if !(o.term_target > 0.0 && o.term_target.is_finite()) {
            return Err(Error::BadIntegratorSetup(format!(
                "term target {} is not positive",
                o.term_target
            )));
        }
        if !(o.h_min > 0.0 && o.h_min.is_finite() && o.h_max >= o.h_min) {
            return Err(Error::BadIntegratorSetup(format!(
                "step bounds h_min = {}, h_max = {} are invalid",
                o.h_min, o.h_max
            )));
        }
        let tape = Tape::record(system)?;
        Ok(Integrator {
            ad: TaylorAd::new(tape),
            options,
            exp_center: Expansion::default(),
            exp_box: Expansion::default(),
            exp_jac: Expansion::default(),
            scratch: Expansion::default(),
            remainder_pieces: 1,
            mean_value: true,
            adaptive_guess: false,
            work: IntegratorWork::default(),
        })
    }

    /// Re-encloses a remainder that misses its target over `pieces` sub-intervals of the step
    /// before shrinking the step (1, the default, never does). Interval Taylor coefficients over
    /// a box grow much faster than linearly with its size, so this buys longer steps for `pieces`
    /// more expansions. Measured on the certified intersection ODE (order 20): 2 pieces make the
    /// steps ≈ 1.25× and 4 pieces ≈ 1.4× longer, at ≈ 1.2× and ≈ 1.6× the total time. `pieces`
    /// is clamped to `1..=64`.
    pub fn set_remainder_pieces(&mut self, pieces: usize) {
        self.remainder_pieces = pieces.clamp(1, 64);
    }

    /// The work done so far (counts and recurrence costs per phase).
    pub fn work(&self) -> IntegratorWork {
        self.work
    }

    /// Whether phase II uses the mean-value form with Lohner's set (`true`, the default) or only
    /// the direct Taylor form over the initial box (`false`: no Jacobians, about a tenth cheaper
    /// per step, but the set wraps: the end box grows with the initial box's width times the
    /// field's Lipschitz constant, so use it only when every step restarts from a thin box).
    pub fn set_mean_value(&mut self, on: bool) {
        self.mean_value = on;
    }

    /// Whether phase I starts from a remainder guess learnt from the last step (twice the ratio
    /// of its proven remainder to the initial box's own one) instead of the fixed factor
    /// [`DEFAULT_GUESS_FACTOR`]. Off by default. It saves the second phase-I expansion that a too
    /// small first guess costs (on the certified intersection ODE nearly every step: ≈ 25% of the
    /// work), but the larger a-priori box it proves feeds back into the next remainder, which
    /// widens long runs of the plain integrator (PCR3BP: 4.9e-12 → 2.9e-11); a caller that
    /// restarts from a thin box every step does not see that.
    pub fn set_adaptive_guess(&mut self, on: bool) {
        self.adaptive_guess = on;
    }

    /// Changes the per-step term target ([`IntegratorOptions::term_target`]) for the next steps,
    /// e.g. to size each step from what the caller's error budget allows (a value that is not
    /// positive and finite is ignored). Any target is sound: it sizes the steps, never a bound.
    pub fn set_term_target(&mut self, term_target: f64) {
        if term_target > 0.0 && term_target.is_finite() {
            self.options.term_target = term_target;
        }
    }

    /// The options in use.
    pub fn options(&self) -> &IntegratorOptions {
        &self.options
    }

    /// The Taylor-mode AD engine (to expand the field directly).
    pub fn ad(&mut self) -> &mut TaylorAd {
        &mut self.ad
    }

    /// The state for the initial box `y0` at time `t0`.
    pub fn start(&self, y0: &[Interval], t0: f64) -> Result<IntegratorState> {
        if y0.len() != self.ad.dim() {
            return Err(Error::input(
                "y0",
                crate::InputProblem::WrongCount {
                    expected: self.ad.dim(),
                    found: y0.len(),
                },
            ));
        }
        if !t0.is_finite() || y0.iter().any(|v| !v.is_common_interval()) {
            return Err(Error::input("y0", crate::InputProblem::NonFinite));
        }
        Ok(IntegratorState {
            t: t0,
            set: LohnerSet::from_box(y0),
            boxed: y0.to_vec(),
            step_ratio: 1.0,
            guess_factor: DEFAULT_GUESS_FACTOR,
        })
    }

    /// Integrates the box `y0` from `t0` to `t_end > t0`, proving every step.
    pub fn integrate(&mut self, y0: &[Interval], t0: f64, t_end: f64) -> Result<Trajectory> {
        if !(t_end.is_finite() && t_end > t0) {
            return Err(Error::BadIntegratorSetup(format!(
                "end time {t_end} is not after {t0}"
            )));
        }
        let mut state = self.start(y0, t0)?;
        let mut steps = Vec::new();
        while state.t < t_end {
            if steps.len() >= self.options.max_steps {
                return Err(Error::StepFailed {
                    time: state.t,
                    step: 0.0,
                    state: state.boxed.clone(),
                    reason: StepFailure::TooManySteps(self.options.max_steps),
                });
            }
            steps.push(self.step(&mut state, t_end)?);
        }
        Ok(Trajectory {
            end: state.boxed.clone(),
            t_end: state.t,
            steps,
        })
    }

    /// One proven step from `state.t` towards (never past) `t_limit`; advances `state`.
    ///
    /// The phases, each its own (private) method: the expansion over the initial box and the
    /// step-size prediction (`predict_step`), phase I with remainder control (`phase_one`),
    /// phase II (`phase_two`, or `direct_form` without the mean-value form), and the record with
    /// the state update (`advance_state`).
    pub fn step(&mut self, state: &mut IntegratorState, t_limit: f64) -> Result<StepRecord> {
        let n = self.ad.dim();
        if state.boxed.len() != n {
            return Err(Error::BadIntegratorSetup(format!(
                "a state of dimension {} for a system of dimension {n}",
                state.boxed.len()
            )));
        }
        if !(t_limit > state.t && t_limit.is_finite()) {
            return Err(Error::BadIntegratorSetup(format!(
                "step limit {t_limit} is not after the current time {}",
                state.t
            )));
        }
        let k = self.options.order;
        let center: Vec<Interval> = state.set.center.iter().map(|c| point(*c)).collect();
        let range: Vec<Interval> = state
            .boxed
            .iter()
            .zip(&center)
            .map(|(b, c)| b.convex_hull(*c))
            .collect();
        let u0 = work_units(&self.ad);
        self.ad
            .expand(&range, k, false, &mut self.exp_box)
            .map_err(|e| step_failed(state, 0.0, StepFailure::Domain(e)))?;
        let u1 = work_units(&self.ad);
        self.work.box_units += u1 - u0;

        // Step control: the predicted step, scaled by the ratio learnt at the last step.
        let scale = state.set.center.iter().fold(1.0f64, |m, c| m.max(c.abs()));
        let eps = self.options.term_target * scale;
        let h_predicted = self.predict_step(k, eps);
        let h = (h_predicted * (state.step_ratio * 1.05).min(1.0)).min(self.options.h_max);
        // The remainder target: ε, or a tiny fraction of the set's width when that is larger
        // (shrinking h cannot make a wide set tighter; it only multiplies the steps).
        let width = state.boxed.iter().fold(0.0f64, |m, v| m.max(v.wid()));
        let rem_target = eps.max(REMAINDER_FRACTION_OF_WIDTH * width);

        let proven = self.phase_one(state, &range, h, t_limit, rem_target)?;
        self.record_radii(k, &proven);
        let u2 = work_units(&self.ad);
        self.work.phase1_units += u2 - u1;

        let (record, next) = if self.mean_value {
            self.phase_two(state, proven, &center, &range, rem_target, u2)?
        } else {
            self.direct_form(state, proven)
        };
        self.advance_state(state, &record, next, h_predicted, t_limit);
        Ok(record)
    }

    /// Adds the step's size and the two radii of [`IntegratorWork`] (profiling only).
    fn record_radii(&mut self, k: usize, proven: &ProvenStep) {
        let mag = |c: &[Interval]| c.iter().fold(0.0f64, |m, x| m.max(x.mag()));
        let radius_point = (k / 2..=k)
            .map(|i| mag(self.exp_box.coeff(i)).powf(-1.0 / i as f64))
            .fold(f64::INFINITY, f64::min);
        let radius_apriori = mag(&proven.apriori.remainder_coeff).powf(-1.0 / k as f64);
        if radius_point.is_finite() && radius_apriori.is_finite() {
            self.work.h_sum += proven.h.sup();
            self.work.radius_point_sum += radius_point;
            self.work.radius_apriori_sum += radius_apriori;
        }
    }

    /// Step control: the step size predicted from the last two terms of the expansion over the
    /// initial box (their midpoints estimate the coefficients at the centre; the expansion at the
    /// centre itself is needed to order `p` only, in phase II), capped by `h_max`.
    fn predict_step(&self, k: usize, eps: f64) -> f64 {
        let mut h = self.options.h_max;
        // (The first-order term is skipped for k ≥ 2: (ε/‖y₁‖)¹ would force h ≈ ε.)
        for i in [k.saturating_sub(1).max(2).min(k), k] {
            let norm = self
                .exp_box
                .coeff(i)
                .iter()
                .fold(0.0f64, |m, c| m.max(c.mid().abs()));
            if norm > 0.0 {
                h = h.min((eps / norm).powf(1.0 / i as f64));
            }
        }
        h
    }

    /// Phase I from the step size `h`: proves an a-priori box over the step, shrinking `h` by 0.7
    /// on failure, and controls the validated remainder against `rem_target` (re-enclosed over
    /// pieces, then the step cut or phase I repeated with a shorter step).
    fn phase_one(
        &mut self,
        state: &mut IntegratorState,
        range: &[Interval],
        mut h: f64,
        t_limit: f64,
        rem_target: f64,
    ) -> Result<ProvenStep> {
        let k = self.options.order;
        let mut shrinks = 0;
        loop {
            let (t1, h_iv) = next_time(state.t, h, t_limit);
            let h_try = h_iv.sup();
            if h_try < self.options.h_min && h_try < t_limit - state.t {
                return Err(step_failed(
                    state,
                    h_try,
                    StepFailure::BelowMinimumStep {
                        h_min: self.options.h_min,
                    },
                ));
            }
            self.work.phase1_attempts += 1;
            match prove_apriori_with_guess(
                &mut self.ad,
                range,
                &self.exp_box,
                k,
                h_try,
                state.guess_factor,
                &mut self.scratch,
            ) {
                Ok(mut a) => {
                    // Remember what the first guess had to exceed (twice it, for the next step).
                    if self.adaptive_guess && a.method == EnclosureMethod::HighOrder {
                        if let Some(r) = remainder_ratio(&a, &self.exp_box, k) {
                            state.guess_factor = (2.0 * r).clamp(DEFAULT_GUESS_FACTOR, 1e200);
                        }
                    }
                    // Remainder control: the interval remainder over the a-priori box can be far
                    // larger than the point estimate used above; re-enclose it over pieces of the
                    // step if needed, then shrink until it meets ε.
                    let rem_of = |a: &Apriori| {
                        a.remainder_coeff.iter().fold(0.0f64, |m, c| m.max(c.mag()))
                            * h_try.powi(k as i32)
                    };
                    let mut rem = rem_of(&a);
                    if rem > rem_target && self.remainder_pieces > 1 {
                        a.remainder_coeff = refine_remainder(
                            &mut self.ad,
                            &self.exp_box,
                            k,
                            h_try,
                            &a,
                            self.remainder_pieces,
                            &mut self.scratch,
                        );
                        rem = rem_of(&a);
                    }
                    if rem <= rem_target
                        || shrinks >= MAX_REMAINDER_SHRINKS
                        || h_try <= self.options.h_min
                    {
                        return Ok(ProvenStep {
                            t1,
                            h: h_iv,
                            apriori: a,
                        });
                    }
                    // A shorter step needs no new phase I: the a-priori box and the remainder
                    // coefficient proven over [0, h_try] hold over every [0, h'] ⊂ [0, h_try],
                    // where the remainder bound is |y_k([ỹ])|·h'ᵏ. Cut the step to meet the
                    // target with them (re-running phase I over the smaller box would allow a
                    // slightly longer step, at the price of another order-k expansion).
                    let h_cut =
                        (h_try * (rem_target / rem).powf(1.0 / k as f64)).max(self.options.h_min);
                    let (t1c, h_ivc) = next_time(state.t, h_cut, t_limit);
                    if h_ivc.sup() < h_try && h_ivc.inf() > 0.0 {
                        self.work.remainder_cuts += 1;
                        let tc = interval(0.0, h_ivc.sup()).unwrap_or(Interval::ENTIRE);
                        let poly = taylor_poly(&self.exp_box, k, tc, Some(&a.remainder_coeff));
                        for (b, p) in a.boxed.iter_mut().zip(&poly) {
                            let c = b.intersection(*p);
                            if !c.is_empty() {
                                *b = c;
                            }
                        }
                        return Ok(ProvenStep {
                            t1: t1c,
                            h: h_ivc,
                            apriori: a,
                        });
                    }
                    shrinks += 1;
                    self.work.remainder_shrinks += 1;
                    h = h_try * (rem_target / rem).powf(1.0 / k as f64).clamp(0.3, 0.95);
                }
                Err(_) => {
                    self.work.phase1_failures += 1;
                    if h_try <= self.options.h_min {
                        return Err(step_failed(
                            state,
                            h_try,
                            StepFailure::BelowMinimumStep {
                                h_min: self.options.h_min,
                            },
                        ));
                    }
                    h = h_try * 0.7;
                }
            }
        }
    }

    /// The end of a step without the mean-value form: every solution at `t + h` lies in the
    /// direct Taylor form `Σ_{i<k} yᵢ([y]) hⁱ + hᵏ·y_k([ỹ])` (a box: it wraps, which a caller that
    /// restarts from a thin box every step does not mind). Returns the record and the next set.
    fn direct_form(
        &mut self,
        state: &IntegratorState,
        proven: ProvenStep,
    ) -> (StepRecord, LohnerSet) {
        let k = self.options.order;
        let ProvenStep { t1, h: hp, apriori } = proven;
        let direct = taylor_poly(&self.exp_box, k, hp, Some(&apriori.remainder_coeff));
        let end: Vec<Interval> = direct
            .iter()
            .zip(&apriori.boxed)
            .map(|(d, a)| {
                let e = d.intersection(*a);
                if e.is_empty() {
                    *d
                } else {
                    e
                }
            })
            .collect();
        self.work.steps += 1;
        let coeffs: Vec<Vec<Interval>> = (0..k).map(|i| self.exp_box.coeff(i).to_vec()).collect();
        let next = LohnerSet::from_box(&end);
        let record = StepRecord {
            t0: state.t,
            t1,
            h: hp.sup(),
            start: state.boxed.clone(),
            apriori: apriori.boxed,
            end,
            center_coeffs: coeffs.clone(),
            coeffs,
            remainder_coeff: apriori.remainder_coeff,
            method: apriori.method,
            jacobians: Vec::new(),
            basis: Vec::new(),
            r: Vec::new(),
        };
        (record, next)
    }

    /// Phase II: the mean-value form over the initial box for the orders below `p`
    /// ([`Self::jacobian_order`]), the range over it for the others, and the Lagrange remainder
    /// over the a-priori box; the Lohner set update re-encloses the result. `units_before` is
    /// the AD work count when phase II starts. Returns the record and the next set.
    fn phase_two(
        &mut self,
        state: &IntegratorState,
        proven: ProvenStep,
        center: &[Interval],
        range: &[Interval],
        rem_target: f64,
        units_before: f64,
    ) -> Result<(StepRecord, LohnerSet)> {
        let n = self.ad.dim();
        let k = self.options.order;
        let ProvenStep { t1, h: hp, apriori } = proven;
        let h = hp.sup();
        let hk = hp.powi(k as i32);
        // Mean-value form for the orders below p only: for i ≥ p the range yᵢ([y]) itself
        // enters u (a box, so it wraps, but its width times hⁱ is below a tenth of the
        // remainder target), which saves the Jacobians' O(n·k²) recurrences above order p.
        let p = self.jacobian_order(k, h, rem_target);
        self.ad
            .expand(range, p, true, &mut self.exp_jac)
            .map_err(|e| step_failed(state, h, StepFailure::Domain(e)))?;
        self.ad
            .expand_tight(center, p, false, &mut self.exp_center)
            .map_err(|e| step_failed(state, h, StepFailure::Domain(e)))?;
        self.work.phase2_units += work_units(&self.ad) - units_before;
        self.work.steps += 1;
        let low_high: Vec<&[Interval]> = (0..k)
            .map(|i| {
                if i < p {
                    self.exp_center.coeff(i)
                } else {
                    self.exp_box.coeff(i)
                }
            })
            .collect();
        let mut poly = low_high[k - 1].to_vec();
        for c in low_high[..k - 1].iter().rev() {
            for (pj, cj) in poly.iter_mut().zip(c.iter()) {
                *pj = *pj * hp + *cj;
            }
        }
        let u: Vec<Interval> = (0..n)
            .map(|j| apriori.remainder_coeff[j] * hk + poly[j])
            .collect();
        let mut s = self.exp_jac.jacobian(p - 1).to_vec();
        for i in (0..p - 1).rev() {
            for (sv, jv) in s.iter_mut().zip(self.exp_jac.jacobian(i)) {
                *sv = *sv * hp + *jv;
            }
        }
        let basis = state.set.basis_intervals();
        let m = mat_mul(&s, &basis, n);
        let next = state.set.advance(&u, &m, self.options.qr);
        let dev: Vec<Interval> = state
            .boxed
            .iter()
            .zip(center)
            .map(|(b, c)| *b - *c)
            .collect();
        let direct = mat_vec(&s, &dev, n);
        let hull = next.hull();
        let end: Vec<Interval> = (0..n)
            .map(|j| {
                let e = hull[j]
                    .intersection(u[j] + direct[j])
                    .intersection(apriori.boxed[j]);
                if e.is_empty() {
                    hull[j]
                } else {
                    e
                }
            })
            .collect();

        let record = StepRecord {
            t0: state.t,
            t1,
            h,
            start: state.boxed.clone(),
            apriori: apriori.boxed,
            end,
            coeffs: (0..k).map(|i| self.exp_box.coeff(i).to_vec()).collect(),
            remainder_coeff: apriori.remainder_coeff,
            method: apriori.method,
            center_coeffs: low_high.iter().map(|c| c.to_vec()).collect(),
            jacobians: (0..p).map(|i| self.exp_jac.jacobian(i).to_vec()).collect(),
            basis,
            r: state.set.r.clone(),
        };
        Ok((record, next))
    }

    /// Record: moves `state` to the end of the step `record` with the set `next`, and learns the
    /// ratio of the accepted step to the predicted one (unless the step was cut by `t_limit`).
    fn advance_state(
        &self,
        state: &mut IntegratorState,
        record: &StepRecord,
        next: LohnerSet,
        h_predicted: f64,
        t_limit: f64,
    ) {
        if record.t1 < t_limit && h_predicted.is_finite() && h_predicted > 0.0 {
            state.step_ratio = (record.h / h_predicted).clamp(1e-6, 1.0);
        }
        state.t = record.t1;
        state.set = next;
        state.boxed.clone_from(&record.end);
    }
}

/// What phase I proved for one step: its end time, an enclosure of its length `t1 − t`, and the
/// a-priori box with the remainder coefficient over it.
struct ProvenStep {
    t1: f64,
    h: Interval,
    apriori: Apriori,
}

/// The AD work so far in the units of the profile (coefficients plus Jacobians).
fn work_units(ad: &TaylorAd) -> f64 {
    let w = ad.work();
    w.coefficient_units + w.jacobian_units
}

/// The error of a step from `state` that failed at step size `h`.
fn step_failed(state: &IntegratorState, h: f64, reason: StepFailure) -> Error {
    Error::StepFailed {
        time: state.t,
        step: h,
        state: state.boxed.clone(),
        reason,
    }
}

impl Integrator {
    /// The smallest order `p ∈ 1..=k` such that the widths of the range coefficients above it,
    /// `Σ_{p ≤ i < k} w(yᵢ([y]))·hⁱ`, stay below a tenth of the remainder target.
    fn jacobian_order(&self, k: usize, h: f64, rem_target: f64) -> usize {
        let mut tail = 0.0;
        let mut p = k;
        while p > 1 {
            let w = self
                .exp_box
                .coeff(p - 1)
                .iter()
                .fold(0.0f64, |m, c| m.max(c.wid()));
            let next = tail + w * h.powi(p as i32 - 1);
            // (A NaN width fails the test and keeps the Jacobians.)
            if next.is_nan() || next > 0.1 * rem_target {
                break;
            }
            tail = next;
            p -= 1;
        }
        p
    }
}

/// The end time `t1 ≤ t_limit` of a step of about `h` from `t` (`t1 = t_limit` for the last step)
/// and an enclosure of the true step `t1 − t` (which need not be a double).
fn next_time(t: f64, h: f64, t_limit: f64) -> (f64, Interval) {
    let t1 = if h >= t_limit - t {
        t_limit
    } else {
        (t + h).min(t_limit)
    };
    (t1, point(t1) - point(t))
}
