//! The test ODEs with closed-form solutions, and an integrator of a given order.

use inari::Interval;
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem};
use ssitrace::Scalar;

/// The rotation `x' = −y, y' = x`: solutions turn at unit angular speed.
pub(crate) struct Rotation;

impl OdeSystem for Rotation {
    fn dim(&self) -> usize {
        2
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        vec![-y[1], y[0]]
    }
}

impl Rotation {
    /// An enclosure of the solution from `p` at time `t`:
    /// `x(t) = x0 cos t − y0 sin t`, `y(t) = x0 sin t + y0 cos t`. cos/sin in f64 (≤ 1 ulp each
    /// for |t| ≤ 63), two products and a sum: error ≤ 4·2⁻⁵²·(|x0| + |y0|) ≈ 1e-15·(|x0|+|y0|).
    /// Margin 1e-13·(|x0|+|y0|): 100× that, and 1e-10 of a box width 2e-3.
    pub(crate) fn exact(p: &[f64], t: f64) -> Vec<Interval> {
        let m = 1e-13 * (p[0].abs() + p[1].abs());
        let (s, c) = t.sin_cos();
        let widened = |x: f64| interval(x - m, x + m).expect("finite");
        vec![widened(p[0] * c - p[1] * s), widened(p[0] * s + p[1] * c)]
    }
}

/// `y' = y²`: solution `y₀/(1 − y₀t)`, which blows up at `t = 1/y₀`; Taylor coefficients
/// `y₀^{i+1}`.
pub(crate) struct Square;

impl OdeSystem for Square {
    fn dim(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        vec![y[0].sqr()]
    }
}

impl Square {
    /// The solution `y0/(1 − y0 t)` from `p` at time `t`, evaluated in intervals: rigorous, no
    /// margin.
    pub(crate) fn exact(p: &[f64], t: f64) -> Vec<Interval> {
        vec![point(p[0]) / (point(1.0) - point(p[0]) * point(t))]
    }
}

/// An integrator of `system` at Taylor order `order`, other options at their defaults.
pub(crate) fn integrator_of_order<F: OdeSystem>(system: &F, order: usize) -> Integrator {
    Integrator::new(
        system,
        IntegratorOptions {
            order,
            ..Default::default()
        },
    )
    .unwrap()
}
