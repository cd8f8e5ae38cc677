//! The fast marching pre-pass: Newton refinement, circular / DQOC / tangent steps, branch tracing.
//!
//! [`trace_branch`] marches from a start point both ways along the intersection curve of two
//! [`ParametricSurface`](crate::geometry::ParametricSurface)s, predicting each next point with a
//! circular ([`circle_step`]), dual-quaternion ([`dqoc_step`]) or tangent ([`tangent_step`]) step
//! and correcting it with Newton ([`crate::pair::newton`]); it stops exactly on domain boundaries, closes loops
//! exactly once and stops at singular points.

mod boundary;
pub mod branch;
pub mod circle_step;
mod closing;
pub(crate) mod covers;
mod crossing;
pub mod dqoc_step;
mod node;
pub mod options;
mod step_limit;
pub mod tangent_step;
pub mod trace;

pub use options::{MarchOptions, StepMethod};
pub use trace::{trace_branch, trace_from_node, MarchStats, TracedBranch};

use crate::geometry::Vec3;

/// A predicted next point of the curve, before Newton refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepPrediction {
    /// Predicted model-space point.
    pub point: Vec3,
    /// Predicted unit tangent there.
    pub tangent: Vec3,
    /// Predicted arc length from the current point.
    pub arc: f64,
}
