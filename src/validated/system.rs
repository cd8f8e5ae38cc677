//! The [`OdeSystem`] trait: an autonomous right-hand side `y' = f(y)` written once, generically.

use crate::Scalar;

/// An autonomous ODE `y' = f(y)` in `ℝⁿ` whose right-hand side is written once over [`Scalar`].
///
/// The same code is evaluated in `f64` (fast, non-rigorous), in `inari::Interval` (rigorous) and
/// on a recording scalar ([`crate::validated::tape::Var`]) from which the validated engine derives
/// Taylor coefficients and Jacobians. `eval` must therefore be a straight-line program of
/// [`Scalar`] operations: the trait offers no comparisons, so it cannot branch on values.
pub trait OdeSystem {
    /// The dimension `n` of the state.
    fn dim(&self) -> usize;
    /// The vector field `f(y)`; `y.len() == self.dim()`, and the result must have that length too
    /// (the engine reports a typed error otherwise).
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S>;
}
