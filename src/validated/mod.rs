//! The validated Taylor ODE engine.
//!
//! For an autonomous system `y' = f(y)` ([`OdeSystem`], written once over [`crate::Scalar`]) and
//! an initial box, [`Integrator`] produces proven steps ([`StepRecord`]): the step size `h`, an
//! a-priori box `[ỹ_j]` over the whole step, a tight end box `[y_{j+1}]`, and the interval Taylor
//! coefficients with their remainder, so callers can enclose the solution on any sub-interval of a
//! step far tighter than `[ỹ_j]` ([`StepRecord::enclose_on`]). Every claimed bound is computed in
//! `inari` interval arithmetic (or with an a-posteriori rounding-error bound finished in `inari`,
//! [`dot`](crate::numeric::dot)). A step that cannot be proven ends the integration with
//! [`crate::Error::StepFailed`], carrying the time and the enclosure reached; nothing panics.
//!
//! ```
//! use ssitrace::numeric::scalar::interval;
//! use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem};
//! use ssitrace::Scalar;
//!
//! /// y' = y², solution y0 / (1 − y0·t).
//! struct Square;
//! impl OdeSystem for Square {
//!     fn dim(&self) -> usize { 1 }
//!     fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> { vec![y[0].sqr()] }
//! }
//!
//! let mut integ = Integrator::new(&Square, IntegratorOptions { order: 20, ..Default::default() })?;
//! let traj = integ.integrate(&[interval(0.5, 0.5).unwrap()], 0.0, 1.0)?;
//! assert!(traj.end[0].contains(1.0)); // 0.5 / (1 − 0.5) = 1
//! let step = &traj.steps[0];
//! let tube = step.enclose_on(0.0, step.h / 2.0)?; // the first half of the first step
//! assert!(tube[0].subset(step.apriori[0]));
//! # Ok::<(), ssitrace::Error>(())
//! ```
//!
//! # Design choices (measured with `cargo bench --bench validated`)
//! * **Taylor coefficients by recurrences on a tape** ([`tape`], [`ad`]): the field is recorded
//!   once as a straight-line program and the solution's coefficients are computed order by order,
//!   `O(k²)` per operation. The textbook alternative, evaluating `f` on [`Series`] of growing
//!   length ([`series::naive_expand`], `O(k³)`), takes ≈ 1.0 ms at order 30 on the PCR3BP field
//!   against ≈ 0.09 ms (11×). [`Series`] remains available as a `Copy` [`crate::Scalar`] for
//!   evaluating generic code along a series.
//! * **Jacobians `∂yᵢ/∂y₀` by forward-mode differentiation of the same recurrences** ([`ad`]),
//!   `n` derivative series per tape operation, in the same pass over the tape.
//! * **Convolutions with an a-posteriori error bound** ([`dot`](crate::numeric::dot)) instead of switching the rounding
//!   mode per operation: ≈ 3× faster expansions on sign-straddling data and ≈ 2.5× faster
//!   integration of the PCR3BP run; the expansion at the set's centre, whose rounding widths feed
//!   the set directly, keeps operation-by-operation rounding for its first orders (all-fast widened the PCR3BP result
//!   from 4.1e-12 to 6.6e-12).
//! * **Phase I** ([`enclosure`]): the high-order test of Corliss & Rihm, falling back to the
//!   first-order test; `h` shrinks on failure down to `h_min`. Work counters
//!   ([`Integrator::work`], [`TaylorAd::work`]) say where the expansions go.
//! * **Phase II** ([`integrator`], [`lohner`]): mean-value form with Lohner's QR set
//!   `x̂ + A·[r]`, `A⁻¹` enclosed by a verified inverse.
//! * **Tape simplification** ([`tape::Tape::simplified`]): dead operations are dropped and repeated
//!   ones merged when recording. (The sphere/plane intersection field: 1074 operations at first;
//!   390 with this pass, first-order patch evaluation and the cancellation-free field; 797 in the
//!   centred form below, of which only 310 vary in time.)
//! * **Centred fields** ([`OdeSystem::eval_centred`], [`tape::Op::Centre`]): a system may write its
//!   field around a centre that the engine sets to the midpoint of every box it expands over, as a
//!   value constant in time (its coefficients above order 0 vanish and it has no derivatives with
//!   respect to the initial value; operations built only from it and constants cost `O(1)` per
//!   expansion). Interval Taylor coefficients over a box grow with the dependency of the formula;
//!   the intersection ODE's rational Bézier patches in shifted power form around the centre cut
//!   the order-20 coefficient width over a box of radius 1e-3 from ≈ 1e37 to ≈ 4e6 and made the
//!   certified steps ≈ 20× longer.
//! * **Jacobians to a lower order** ([`integrator`]): only up to the order `p` above which the
//!   coefficients' ranges over the initial box may enter the set as a box (their width times `hⁱ`
//!   is below a tenth of the remainder target): 2× cheaper certified steps, same PCR3BP widths.
//! * **Remainder over pieces of the step** (opt-in, [`Integrator::set_remainder_pieces`]): the
//!   Lagrange remainder re-enclosed over sub-boxes of the a-priori box (longer steps, more
//!   expansions; off by default because it did not pay in total time on the certified scenes).
//! * **Cutting a step instead of re-running phase I**: when the validated remainder misses its
//!   target, the a-priori box and remainder coefficient already proven over `[0, h]` hold over any
//!   shorter step, whose remainder bound is `|y_k([ỹ])|·h'ᵏ`: the step is cut to meet the target
//!   without another order-`k` expansion (on the certified intersection ODE ≈ 0.5 phase-I
//!   expansions per step saved; the PCR3BP reference run is unchanged).
//! * **Opt-in for callers that restart every step from a thin box** (the certified tracer):
//!   [`Integrator::set_mean_value`]`(false)` drops phase II's Jacobians (direct Taylor form
//!   only), and [`Integrator::set_adaptive_guess`] starts phase I from a remainder guess learnt
//!   from the last step (one expansion per phase I instead of ≈ 2 on the intersection ODE). Both
//!   widen long runs of a plain integration, so both are off by default.
//! * **Step size**: from the last two Taylor terms (the midpoints of their ranges over the set,
//!   which estimate the values at its centre), then reduced until the validated
//!   remainder `hᵏ·y_k([ỹ])` meets the tolerance (the interval remainder over the a-priori box is
//!   often many orders of magnitude above the point estimate).
//!
//! Pieces, one per file: [`system`] (the trait), [`tape`] (recording the field once), [`ad`]
//! (Taylor-mode AD over intervals with Jacobians), [`series`] (a `Copy` truncated-series scalar, the naive alternative), [`enclosure`] (phase I),
//! [`lohner`] (the QR set representation), [`record`] (step output), [`integrator`] (driver and
//! step control).

pub mod ad;
pub mod enclosure;
pub mod integrator;
pub mod lohner;
pub mod midrad;
pub mod record;
pub mod reference;
pub mod series;
pub mod system;
pub mod tape;

pub use ad::{AdWork, DomainError, Expansion, TaylorAd};
pub use enclosure::EnclosureMethod;
pub use integrator::{
    Integrator, IntegratorOptions, IntegratorState, IntegratorWork, StepFailure, Trajectory,
};
pub use midrad::MidRadSeries;
pub use record::StepRecord;
pub use series::{Series, SeriesN};
pub use system::OdeSystem;
