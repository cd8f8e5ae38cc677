//! A published reference problem for the engine: the planar circular restricted three-body
//! problem (PCR3BP) run that CAPD documents, shared by the tests, the example and the benchmark.

use crate::numeric::scalar::{interval, point};
use crate::validated::OdeSystem;
use crate::Scalar;
use inari::Interval;

/// An enclosure of a decimal literal: Rust parses it to the nearest `f64`, so one ulp on each
/// side holds the exact decimal value. Non-numbers give the whole line.
pub fn decimal(s: &str) -> Interval {
    s.parse::<f64>()
        .ok()
        .and_then(|x| interval(x.next_down(), x.next_up()))
        .unwrap_or(Interval::ENTIRE)
}

/// The PCR3BP in the rotating frame, state `(x, y, p, q)`:
/// `x' = p, y' = q, p' = x − (x+μ)A − (x−1+μ)B + 2q, q' = y(1 − A − B) − 2p`,
/// `A = (1−μ)((x+μ)² + y²)^(−3/2)`, `B = μ((x−1+μ)² + y²)^(−3/2)`.
#[derive(Debug, Clone, Copy)]
pub struct Pcr3bp {
    /// The mass ratio μ (an interval, so a decimal μ is enclosed exactly).
    pub mu: Interval,
}

/// The end time of the CAPD reference run.
pub const PCR3BP_T_END: f64 = 3.082119126376508;

/// CAPD's final widths of the reference run (order 30, doubleton sets), for comparison.
pub const PCR3BP_CAPD_WIDTHS: [f64; 4] = [6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12];

impl Pcr3bp {
    /// The reference problem: μ = 0.0009537.
    pub fn reference() -> Self {
        Pcr3bp {
            mu: decimal("0.0009537"),
        }
    }

    /// The reference initial state: `x0 = 0.9208034913207400196`, `y = p = 0`, and `q0` from the
    /// Jacobi constant 3.03, all evaluated in intervals.
    pub fn initial_state(&self) -> [Interval; 4] {
        let mu = self.mu;
        let x0 = decimal("0.9208034913207400196");
        let one = point(1.0);
        let q0 = (x0.sqr()
            + point(2.0) * ((one - mu) / (x0 + mu).abs() + mu / (x0 - one + mu).abs())
            + mu * (one - mu)
            - decimal("3.03"))
        .sqrt();
        [x0, point(0.0), point(0.0), q0]
    }

    /// The Jacobi integral `x² + y² + 2((1−μ)/r1 + μ/r2) + μ(1−μ) − (p² + q²)` over a box
    /// (constant along solutions: 3.03 on the reference run).
    pub fn jacobi(&self, s: &[Interval]) -> Interval {
        let (mu, one) = (self.mu, point(1.0));
        let r1 = ((s[0] + mu).sqr() + s[1].sqr()).sqrt();
        let r2 = ((s[0] - one + mu).sqr() + s[1].sqr()).sqrt();
        s[0].sqr() + s[1].sqr() + point(2.0) * ((one - mu) / r1 + mu / r2) + mu * (one - mu)
            - (s[2].sqr() + s[3].sqr())
    }
}

impl OdeSystem for Pcr3bp {
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, s: &[S]) -> Vec<S> {
        let (x, y, p, q) = (s[0], s[1], s[2], s[3]);
        let mu = S::from_interval(self.mu);
        let one = S::one();
        let y2 = y.sqr();
        let d1 = x + mu;
        let d2 = x - one + mu;
        let r1 = d1.sqr() + y2;
        let r2 = d2.sqr() + y2;
        let a = (one - mu) / (r1 * r1.sqrt());
        let b = mu / (r2 * r2.sqrt());
        let two = S::from_f64(2.0);
        vec![
            p,
            q,
            x - d1 * a - d2 * b + two * q,
            y * (one - a - b) - two * p,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_state_has_the_jacobi_constant() {
        let sys = Pcr3bp::reference();
        let y0 = sys.initial_state();
        assert!(sys.jacobi(&y0).contains(3.03));
        assert!(decimal("0.1").contains(0.1) && decimal("0.1").wid() > 0.0);
        assert!(decimal("not a number").is_entire());
    }
}
