//! The intersection ODE as an [`OdeSystem`] for the validated engine.

use crate::pair::field::{transversal_velocity, transversal_velocity_centred, ScalarSurface};
use crate::validated::OdeSystem;
use crate::Scalar;

/// The transversal intersection ODE `y' = f(y)`, `y = (σ, t, u, v)`, by arc length along
/// `orientation · (N^P × N^Q)/|N^P × N^Q|` (`orientation` = ±1).
///
/// Undefined (the engine reports a domain error) where `N^P × N^Q` may vanish on the box.
#[derive(Debug, Clone, Copy)]
pub struct TransversalOde<'a, P: ?Sized, Q: ?Sized> {
    /// The first surface.
    pub p: &'a P,
    /// The second surface.
    pub q: &'a Q,
    /// +1 along `N^P × N^Q`, −1 against it.
    pub orientation: f64,
}

impl<P: ScalarSurface + ?Sized, Q: ScalarSurface + ?Sized> OdeSystem for TransversalOde<'_, P, Q> {
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        let y4 = [y[0], y[1], y[2], y[3]];
        transversal_velocity(self.p, self.q, &y4, self.orientation).to_vec()
    }
    fn eval_centred<S: Scalar>(&self, y: &[S], c: &[S]) -> Vec<S> {
        let y4 = [y[0], y[1], y[2], y[3]];
        let c4 = [c[0], c[1], c[2], c[3]];
        transversal_velocity_centred(self.p, self.q, &y4, &c4, self.orientation).to_vec()
    }
    fn uses_centre(&self) -> bool {
        true
    }
}
