//! The per-step Taylor term target of a certified half branch, sized from its error budgets.
//!
//! The validated engine sizes each step so that its last Taylor terms stay below a target `ε`
//! ([`crate::validated::IntegratorOptions::term_target`]). A fixed tiny `ε` (1e-15) makes the
//! steps independent of what the caller asked for. Two quantities of a certified branch grow
//! with `ε`, and bound how large it may be:
//!
//! * the step's model-space tube radius (it enters the branch's tolerance): kept below a
//!   fraction [`RADIUS_SHARE`] of the required tolerance;
//! * the re-anchoring's arc-length error: every step adds its `bridge` (about the end box's
//!   along-curve width over the speed, so about `ε`), and the sum is carried along the half.
//!   The covers of the re-anchoring grow with it, and the Krawczyk proofs on them fail once it
//!   reaches about 1e-9 on close loops (measured on `two_loops_s31_s32`). The half's total is
//!   kept below [`ARC_ERROR_BUDGET`], shared out over the arc length still to go.
//!
//! Both grow about linearly in `ε` above a floor set by rounding and the start box, so the
//! controller is multiplicative: after each re-anchored step `ε` is scaled by the smaller of
//! `budget / observed` for the two quantities, by at most [`MAX_GROWTH`] up and never below the
//! fixed floor ([`crate::certify::budget::StepBudget::term_target`], the former fixed value). A target only
//! sizes the steps: every bound stays proven whatever `ε` is; a bad guess costs steps or a
//! re-anchoring, never soundness.

/// Share of the required tolerance a step's tube radius may take.
pub(crate) const RADIUS_SHARE: f64 = 1.0 / 16.0;

/// Largest arc-length error the re-anchoring may accumulate over a half branch.
pub(crate) const ARC_ERROR_BUDGET: f64 = 1e-11;

/// Largest factor by which the target grows from one step to the next.
pub(crate) const MAX_GROWTH: f64 = 4.0;

/// Largest target, relative to the required tolerance. The response of the steps to the target
/// is steep and lagging: `h` grows like `ε^{1/k}`, the tube radius (the *width* of the Taylor
/// form, not the size of its terms) stays at its rounding floor until `h` nears the series'
/// radius of convergence and then jumps by orders of magnitude in one or two steps (measured on
/// `sphere_patch_plane`, order 20: 1e-14 up to ε ≈ 3e-4, then 6e-12 and 7e-10). The cap keeps the
/// controller far below that cliff.
pub(crate) const MAX_RELATIVE: f64 = 1e-3;

/// Arc length assumed for a half without a length budget, in units of the smaller patch's model
/// diameter.
const LENGTH_WITHOUT_BUDGET: f64 = 8.0;

/// The controller of one half branch.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TermTarget {
    current: f64,
    floor: f64,
    radius_budget: f64,
    cap: f64,
    length: f64,
}

impl TermTarget {
    /// Starts at `floor` (the first step measures the ratios); `tolerance` is the required
    /// model-space tolerance, `max_length` the half's arc-length budget (may be infinite) and
    /// `model_size` the smaller patch's model diameter.
    pub(crate) fn new(floor: f64, tolerance: f64, max_length: f64, model_size: f64) -> Self {
        let length = if max_length.is_finite() && max_length > 0.0 {
            max_length
        } else if model_size.is_finite() && model_size > 0.0 {
            LENGTH_WITHOUT_BUDGET * model_size
        } else {
            LENGTH_WITHOUT_BUDGET
        };
        let radius_budget = if tolerance.is_finite() && tolerance > 0.0 {
            RADIUS_SHARE * tolerance
        } else {
            0.0
        };
        TermTarget {
            current: floor,
            floor,
            radius_budget,
            cap: (MAX_RELATIVE * tolerance).max(floor),
            length,
        }
    }

    /// The target for the next step.
    pub(crate) fn current(&self) -> f64 {
        self.current
    }

    /// Learns from a step of length `h` ending at arc length `t` that was taken with the current
    /// target: its tube radius `radius`, the bridge `bridge` to the re-anchored start and the
    /// half's accumulated arc-length error `s_err` after it.
    pub(crate) fn observe(&mut self, h: f64, t: f64, radius: f64, bridge: f64, s_err: f64) {
        let to_go = (self.length - t).max(h).max(f64::MIN_POSITIVE);
        let bridge_budget = (ARC_ERROR_BUDGET - s_err).max(0.0) * (h / to_go).min(1.0);
        let factor = ratio(self.radius_budget, radius).min(ratio(bridge_budget, bridge));
        let next = self.current * factor.min(MAX_GROWTH);
        self.current = if next.is_finite() {
            next.min(self.cap).max(self.floor)
        } else {
            self.floor
        };
    }
}

/// `budget / used`, for a quantity that scales about linearly with the target (unbounded when
/// nothing is used yet).
fn ratio(budget: f64, used: f64) -> f64 {
    if used > 0.0 {
        budget / used
    } else if budget > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_towards_the_budgets_and_never_below_the_floor() {
        let mut t = TermTarget::new(1e-15, 1e-9, 4.0, 1.0);
        // Radius 6·ε, bridge 1.5·ε on steps of 0.05: both budgets far away, growth limited.
        t.observe(0.05, 0.05, 6e-15, 1.5e-15, 1.5e-15);
        assert_eq!(t.current(), 4e-15);
        let mut s_err = 1.5e-15;
        for j in 2..60 {
            let e = t.current();
            s_err += 1.5 * e;
            t.observe(0.05, 0.05 * j as f64, 6.0 * e, 1.5 * e, s_err);
            assert!(s_err < ARC_ERROR_BUDGET, "{j}: {s_err}");
        }
        // The bridge budget (1e-11 over 80 steps) binds below the cap (1e-12) and the radius
        // budget (6e-11 / 6).
        assert!(
            t.current() < 1e-12 && t.current() > 1e-14,
            "{}",
            t.current()
        );
        // Loose budgets: the cap binds.
        let mut loose = TermTarget::new(1e-15, 1e-9, 4.0, 1.0);
        for _ in 0..40 {
            loose.observe(0.05, 0.05, 1e-16, 0.0, 0.0);
        }
        assert_eq!(loose.current(), MAX_RELATIVE * 1e-9);
        // A radius far over its budget sends the target to the floor.
        t.observe(0.05, 1.0, 1.0, 0.0, 0.0);
        assert_eq!(t.current(), 1e-15);
    }
}
