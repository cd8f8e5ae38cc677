//! The validated steps of one certified half and their budget, shared by the branch tracer
//! ([`CertifyOptions`](crate::certify::CertifyOptions)) and the contact tracer
//! ([`ContactOptions`](crate::certify::ContactOptions)), each with its own defaults
//! ([`StepBudget::CERTIFY`], [`StepBudget::CONTACT`]).

use crate::geometry::RationalBezierPatch;
use crate::validated::IntegratorOptions;
use std::time::Instant;

/// How the validated steps of one half are taken and when the half stops for its budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepBudget {
    /// Taylor order of the validated steps.
    pub order: usize,
    /// Per-step size target of the last Taylor terms (the integrator's
    /// [`term_target`](IntegratorOptions::term_target)).
    pub term_target: f64,
    /// Smallest step before the half ends for want of a provable step.
    pub h_min: f64,
    /// Largest step (arc length). The tracers also cap it at 1/8 of the smaller patch's model
    /// size, so a step never reaches far outside the domains (where interval bounds of the patch
    /// extension are loose).
    pub h_max: f64,
    /// Step budget per half.
    pub max_steps: usize,
    /// Arc-length budget per half (e.g. 1.5 × the marcher's loop length).
    pub max_length: f64,
    /// Wall-clock deadline (none by default). Once it has passed, a half ends before its next
    /// step as unproven ("time limit"), keeping every step proven so far.
    pub deadline: Option<Instant>,
}

impl StepBudget {
    /// The default of the branch tracer. Order: measured with re-anchored thin boxes
    /// (`tests/certified_perf_profile.rs`, thread CPU time), orders 14–20 cost within ≈ 5–8% of
    /// each other on the sphere, bicubic, S31/S32 and Fig. 7 scenes (16–18 marginally fastest,
    /// 12 and 24 slower); 20 keeps the longest steps at that cost.
    pub const CERTIFY: StepBudget = StepBudget {
        order: 20,
        term_target: 1e-15,
        h_min: 1e-9,
        h_max: 0.25,
        max_steps: 200_000,
        max_length: f64::INFINITY,
        deadline: None,
    };

    /// The default of the contact tracer. Its steps are sized by the validated remainder over
    /// the a-priori box, not by the term target (halving the target shortens them by ≈ 3%), so
    /// a tight target costs little and keeps the tube thin; measured on the cubic × quadratic
    /// contact (ratio form): order 16 / 1e-14 took 242 steps (tube radius 2.1e-11), order 20 /
    /// 5e-15 201 steps (1.0e-11) in the same time.
    pub const CONTACT: StepBudget = StepBudget {
        order: 20,
        term_target: 5e-15,
        h_min: 1e-8,
        h_max: 0.125,
        max_steps: 1000,
        max_length: f64::INFINITY,
        deadline: None,
    };

    /// Whether a half that took `steps` steps over the arc length `length` has spent its budget.
    pub(crate) fn spent(&self, steps: usize, length: f64) -> bool {
        steps >= self.max_steps || length >= self.max_length
    }

    /// Whether the deadline has passed.
    pub(crate) fn out_of_time(&self) -> bool {
        self.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// The integrator's options for a half whose largest step is `h_max` (the budget's own
    /// capped by [`h_max_for`] the patches); the step count is left to this budget.
    pub(crate) fn integrator_options(&self, h_max: f64) -> IntegratorOptions {
        IntegratorOptions {
            order: self.order,
            term_target: self.term_target,
            h_min: self.h_min,
            h_max,
            qr: true,
            max_steps: usize::MAX,
        }
    }
}

/// The largest step: `h_max`, at most 1/8 of the smaller model-space diameter of the two
/// patches.
pub(crate) fn h_max_for(p: &RationalBezierPatch, q: &RationalBezierPatch, h_max: f64) -> f64 {
    let size = p.model_width().min(q.model_width());
    if size.is_finite() && size > 0.0 {
        h_max.min(0.125 * size)
    } else {
        h_max
    }
}
