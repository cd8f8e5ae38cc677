//! The [`OdeSystem`] trait: an autonomous right-hand side `y' = f(y)` written once, generically.

use crate::Scalar;

/// An autonomous ODE `y' = f(y)` in `ℝⁿ` whose right-hand side is written once over [`Scalar`].
///
/// The same code is evaluated in `f64` (fast, non-rigorous), in `inari::Interval` (rigorous) and
/// on a recording scalar (`tape::Var`) from which the validated engine derives
/// Taylor coefficients and Jacobians. `eval` must therefore be a straight-line program of
/// [`Scalar`] operations: the trait offers no comparisons, so it cannot branch on values.
pub trait OdeSystem {
    /// The dimension `n` of the state.
    fn dim(&self) -> usize;
    /// The vector field `f(y)`; `y.len() == self.dim()`, and the result must have that length too
    /// (the engine reports a typed error otherwise).
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S>;
    /// The same field written around a centre `c` (`c.len() == self.dim()`): it must equal
    /// [`eval`](Self::eval) for every `c` (only its rounding and interval widths may differ).
    /// The engine passes the midpoint of every box it expands over, as a value that is constant
    /// in time, so a system can use a local (e.g. shifted power-basis) form whose interval Taylor
    /// coefficients are far tighter than a global form's. The default ignores `c`.
    fn eval_centred<S: Scalar>(&self, y: &[S], c: &[S]) -> Vec<S> {
        let _ = c;
        self.eval(y)
    }
    /// Whether [`eval_centred`](Self::eval_centred) uses its centre (default `false`).
    fn uses_centre(&self) -> bool {
        false
    }
}
