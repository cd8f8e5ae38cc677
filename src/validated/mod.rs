//! The validated Taylor ODE engine.
//!
//! For an autonomous system `y' = f(y)` ([`OdeSystem`], written once over [`crate::Scalar`]) and
//! an initial box, [`Integrator`] produces proven steps ([`StepRecord`]): the step size `h`, an
//! a-priori box over the whole step, a tight end box, and the interval Taylor coefficients with
//! their remainder so callers can enclose the solution on any sub-interval
//! ([`StepRecord::enclose_on`]).
//!
//! Pieces, one per file: [`tape`] (recording the field once), [`ad`] (Taylor-mode AD over
//! intervals with Jacobians), [`series`] (a `Copy` truncated-series scalar, the naive alternative),
//! [`enclosure`] (phase I), [`lohner`] (the QR set representation), [`record`] (step output),
//! [`integrator`] (driver and step control).

pub mod ad;
pub mod dot;
pub mod enclosure;
pub mod integrator;
pub mod lohner;
pub mod record;
pub mod series;
pub mod system;
pub mod tape;

pub use ad::{DomainError, Expansion, TaylorAd};
pub use enclosure::EnclosureMethod;
pub use integrator::{Integrator, IntegratorOptions, IntegratorState, StepFailure, Trajectory};
pub use record::StepRecord;
pub use series::Series;
pub use system::OdeSystem;
