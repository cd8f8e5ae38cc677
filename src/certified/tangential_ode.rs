//! The tangential intersection ODE as an [`OdeSystem`] for the validated engine.
//!
//! Along a curve where P and Q touch (N^P ∥ N^Q) the transversal field is undefined. The curve
//! still has a direction: the double root of the contact quadratic
//! `b11 σ'² + 2 b12 σ' t' + b22 t'² = 0` ([`super::tangential`]), i.e. `(σ', t') ∝ (−b12, b11)`
//! or `∝ (b22, −b12)`, normalised to unit model-space speed `|P_σ σ' + P_t t'| = 1`, and
//! `(u', v')` from `P_σ σ' + P_t t' = Q_u u' + Q_v v'` in the common tangent plane.
//!
//! **What the field is.** Off a tangential curve the same formulas still define a smooth field
//! (wherever `|N^P|`, `det(Q_u, Q_v, N)` and the chosen root vector are non-zero): the validated
//! engine integrates *that* field. Its solution through a point of a tangential contact curve is
//! the contact curve (the curve's unit tangent satisfies both defining equations there), but
//! interval arithmetic cannot prove that a point lies on such a curve (`P − Q` only *contains*
//! zero), so a tube of this field is "the solution from the start box", not a proof of
//! intersection. [`super::contact`] adds what can be proven.

use super::field::ScalarSurface;
use super::tangential::{contact_quadratic, tangential_velocity, TangentialFormula};
use crate::validated::OdeSystem;
use crate::Scalar;

/// The tangential intersection ODE `y' = f(y)`, `y = (σ, t, u, v)`, by model-space arc length.
///
/// The root formula is fixed per system (the field must be a straight-line program); a tracer
/// switches systems when the better-conditioned formula changes. `orientation` = ±1 is the sign
/// applied to the chosen root vector. Undefined (the engine reports a domain error) where
/// `|N^P|`, `det(Q_u, Q_v, N)` or the root vector may vanish on the box.
#[derive(Debug, Clone, Copy)]
pub struct TangentialOde<'a, P: ?Sized, Q: ?Sized> {
    /// The first surface.
    pub p: &'a P,
    /// The second surface.
    pub q: &'a Q,
    /// Which expression of the double root is used.
    pub formula: TangentialFormula,
    /// +1 along the root vector, −1 against it.
    pub orientation: f64,
}

impl<P: ScalarSurface + ?Sized, Q: ScalarSurface + ?Sized> TangentialOde<'_, P, Q> {
    /// The velocity `(σ', t', u', v')` at `y`, in any scalar (an enclosure when `T` is rigorous).
    pub fn velocity<T: Scalar>(&self, y: &[T; 4]) -> [T; 4] {
        let c = contact_quadratic(self.p, self.q, y);
        tangential_velocity(&c, self.formula, self.orientation)
    }
}

impl<P: ScalarSurface + ?Sized, Q: ScalarSurface + ?Sized> OdeSystem for TangentialOde<'_, P, Q> {
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        self.velocity(&[y[0], y[1], y[2], y[3]]).to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certified::fixtures::Bowl;
    use crate::scalar::{interval, point};
    use crate::validated::{Integrator, IntegratorOptions};

    /// z = (u − v)² against z = 0: contact along the diagonal u = v, so the unit-speed solution
    /// from the origin is (s, s, s, s)/√2 (in P's and Q's parameters alike).
    struct Valley;
    impl ScalarSurface for Valley {
        fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
            let [p, a, b, ..] = self.second_order(u, v);
            [p, a, b]
        }
        fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
            let (o, z, two) = (T::one(), T::zero(), T::from_f64(2.0));
            let d = u - v;
            [
                [u, v, d.sqr()],
                [o, z, two * d],
                [z, o, -(two * d)],
                [z, z, two],
                [z, z, -two],
                [z, z, two],
            ]
        }
    }

    #[test]
    fn validated_tube_follows_a_diagonal_contact_line() {
        let plane = Bowl::new(0.0, 0.0);
        let y0 = [0.1; 4];
        let c = contact_quadratic(&Valley, &plane, &y0);
        let ode = TangentialOde {
            p: &Valley,
            q: &plane,
            formula: TangentialFormula::choose(&c),
            orientation: 1.0,
        };
        let v = ode.velocity(&y0);
        let sign = v[0].signum();
        let ode = TangentialOde {
            orientation: sign,
            ..ode
        };
        let mut integ = Integrator::new(
            &ode,
            IntegratorOptions {
                order: 12,
                tolerance: 1e-14,
                ..Default::default()
            },
        )
        .unwrap();
        let traj = integ.integrate(&[point(0.1); 4], 0.0, 0.5).unwrap();
        let r = 0.1 + 0.5 * std::f64::consts::FRAC_1_SQRT_2;
        for x in &traj.end {
            assert!(x.contains(r) && x.wid() < 1e-10, "{x:?} vs {r}");
        }
        // The interval field over a box around the line is an enclosure of the f64 field.
        let b = [interval(0.09, 0.11).unwrap(); 4];
        let vi = ode.velocity(&b);
        let vf = ode.velocity(&[0.1, 0.1, 0.1, 0.1]);
        assert!((0..4).all(|i| vi[i].contains(vf[i])));
    }
}
