//! What [`intersect`](super::intersect) does: the method, the marching step, the certified budgets
//! and the tuning of the search, the boundary test and the contact cover.

use crate::certify::contact::ContactOptions;
use crate::certify::contact_cover::CoverOptions;
use crate::error::{Error, Result};
use crate::geometry::RationalBezierPatch;
use crate::pair::boundary_direction::BoundaryOptions;
use crate::search::start_points::SearchOptions;
use std::time::Duration;

/// How the branches are traced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Floating-point marching only: fast, nothing proven (`"march"`).
    March,
    /// March to find the branches, then certify each and check the marched points against the
    /// certificates (`"validated"`).
    Validated,
    /// As `Validated`; the result reports the marched and certified curves side by side
    /// (`"both"`).
    Both,
}

impl Method {
    /// The name used in scene files, on the command line and in the result JSON.
    pub fn name(self) -> &'static str {
        match self {
            Method::March => "march",
            Method::Validated => "validated",
            Method::Both => "both",
        }
    }

    /// Whether the method certifies the marched branches.
    pub fn certifies(self) -> bool {
        self != Method::March
    }
}

/// How a transversal branch is certified.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Engine {
    /// A cover chain ([`crate::certify::chain`]): Krawczyk-proven tubes around septic predictors
    /// between the marched points, joined without gaps. Fast; its certificate's tube pieces are
    /// parametrised by a parameter of the curve, its arc lengths are nominal (`"chain"`).
    #[default]
    Chain,
    /// The validated Taylor ODE solver by arc length ([`crate::certify::trace`]): proven arc
    /// lengths, one to three orders of magnitude slower (`"taylor"`).
    Taylor,
}

impl Engine {
    /// The name used on the command line and in the result JSON.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Chain => "chain",
            Engine::Taylor => "taylor",
        }
    }
}

/// Default certified step budget per half branch.
pub const DEFAULT_MAX_STEPS: usize = 20_000;

/// Default arc-length budget of a certified half branch, as a multiple of the marched length.
pub const LENGTH_BUDGET_FACTOR: f64 = 1.5;

/// Default leaf size of the contact cover, as a fraction of each domain width (coarser than the
/// cover's own default: still sound, at a fraction of the cost).
pub const COVER_LEAF: f64 = 1.0 / 64.0;

/// Default enclosure budget of the contact cover (when spent, the cover stays sound but coarse).
pub const COVER_EVALUATIONS: usize = 50_000;

/// Everything [`intersect`](super::intersect) can be told. [`Options::default`] is what the
/// command line runs for a scene without options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// The tracing method (default [`Method::Both`]).
    pub method: Method,
    /// The certification engine of transversal branches (default [`Engine::Chain`]).
    pub engine: Engine,
    /// The marching step `L` (> 0, finite; default 0.05), see
    /// [`MarchOptions::step`](crate::march::MarchOptions::step): in model units for patches up
    /// to 50 units across; for larger ones (the smaller patch's bounding box wider than that) it
    /// is multiplied by that width over 50, so a part 1 000 units across (millimetres) is marched
    /// with as many points as the same part 50 units across ([`Options::marching_step`]).
    pub step: f64,
    /// The model-space tolerance a certified branch should meet (> 0, finite; default 1e-9).
    /// Reported per branch ([`BranchCertificate::meets`](super::BranchCertificate::meets)), not
    /// enforced.
    pub required_tolerance: f64,
    /// Certified step budget per half branch (≥ 1; default [`DEFAULT_MAX_STEPS`]).
    pub max_steps: usize,
    /// Arc-length budget of a certified half branch, as a multiple of the marched branch's
    /// length (default [`LENGTH_BUDGET_FACTOR`]).
    pub length_budget: f64,
    /// The start-point search.
    pub search: SearchOptions,
    /// Grandine's test of the branches' boundary ends.
    pub boundary: BoundaryOptions,
    /// The certification of tangential contacts, with its cover (default: the contact defaults
    /// with a cover of leaf [`COVER_LEAF`] and budget [`COVER_EVALUATIONS`]).
    pub contact: ContactOptions,
    /// Wall-clock limit of the certification, counted from the call (none by default). When it
    /// expires, each certified half and contact still running ends unproven ("time limit")
    /// with everything proven up to there; the search and the march are not limited.
    pub time_limit: Option<Duration>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Both,
            engine: Engine::default(),
            step: 0.05,
            required_tolerance: 1e-9,
            max_steps: DEFAULT_MAX_STEPS,
            length_budget: LENGTH_BUDGET_FACTOR,
            search: SearchOptions::default(),
            boundary: BoundaryOptions::default(),
            contact: ContactOptions {
                cover: CoverOptions {
                    leaf_fraction: COVER_LEAF,
                    max_evaluations: COVER_EVALUATIONS,
                },
                ..ContactOptions::default()
            },
            time_limit: None,
        }
    }
}

/// Patches up to this wide (the larger side of the smaller patch's bounding box) are marched with
/// [`Options::step`] as it is; larger ones with the step scaled by their width over this.
const STEP_SCALE_SIZE: f64 = 50.0;

impl Options {
    /// The marching step in model units for the patches `p` and `q` (see [`Options::step`]).
    pub fn marching_step(&self, p: &RationalBezierPatch, q: &RationalBezierPatch) -> f64 {
        let size = p.model_width().min(q.model_width());
        if size.is_finite() && size > STEP_SCALE_SIZE {
            self.step * (size / STEP_SCALE_SIZE)
        } else {
            self.step
        }
    }

    /// Checks the numbers a run depends on.
    ///
    /// Errors ([`Error::Scene`], as for a scene's options): a step or tolerance that is not a
    /// positive finite number; a zero step budget; a length budget that is not positive.
    pub fn check(&self) -> Result<()> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(Error::Scene(format!(
                "the step must be a positive number, not {}",
                self.step
            )));
        }
        if !(self.required_tolerance.is_finite() && self.required_tolerance > 0.0) {
            return Err(Error::Scene(format!(
                "the tolerance must be a positive number, not {}",
                self.required_tolerance
            )));
        }
        if self.max_steps == 0 {
            return Err(Error::Scene("the step budget must be at least 1".into()));
        }
        if self.length_budget.is_nan() || self.length_budget <= 0.0 {
            return Err(Error::Scene(format!(
                "the length budget must be a positive number, not {}",
                self.length_budget
            )));
        }
        Ok(())
    }
}
