//! The tangential intersection ODE as an [`OdeSystem`] for the validated engine.
//!
//! Along a curve where P and Q touch (N^P ∥ N^Q) the transversal field is undefined. The curve
//! still has a direction: the double root of the contact quadratic
//! `b11 σ'² + 2 b12 σ' t' + b22 t'² = 0` ([`crate::pair::contact_quadratic`]), i.e. `(σ', t') ∝ (−b12, b11)`
//! or `∝ (b22, −b12)`, normalised to unit model-space speed `|P_σ σ' + P_t t'| = 1`, and
//! `(u', v')` from `P_σ σ' + P_t t' = Q_u u' + Q_v v'` in the common tangent plane.
//!
//! **What the field is.** Off a tangential curve the same formulas still define a smooth field
//! (wherever `|N^P|`, `det(Q_u, Q_v, N)` and the chosen root vector are non-zero): the validated
//! engine integrates *that* field. Its solution through a point of a tangential contact curve is
//! the contact curve (the curve's unit tangent satisfies both defining equations there), but
//! interval arithmetic cannot prove that a point lies on such a curve (`P − Q` only *contains*
//! zero), so a tube of this field is "the solution from the start box", not a proof of
//! intersection. [`crate::certify::contact`] adds what can be proven.

use crate::numeric::scalar::point;
use crate::numeric::vec3::{cross, norm_sqr};
use crate::pair::centred_second_order::CentredSecondOrder;
#[cfg(doc)]
use crate::pair::contact_quadratic::{contact_quadratic, tangential_velocity};
use crate::pair::contact_quadratic::{
    quadratic_coefficients, second_forms, tangent_map_numerators, TangentialFormula,
};
use crate::validated::OdeSystem;
use crate::Scalar;
use inari::Interval;

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

impl<P: CentredSecondOrder + ?Sized, Q: CentredSecondOrder + ?Sized> TangentialOde<'_, P, Q> {
    /// The velocity `(σ', t', u', v')` at `y`, in any scalar (an enclosure when `T` is rigorous).
    ///
    /// Evaluated in a division-free scaled form: with the unnormalised normal `n = P_σ × P_t`,
    /// `D = det(Q_u, Q_v, n)` and `A_ij = D·a_ij` (the numerators of the parameter map), the
    /// coefficients `b̃ = |n|·D²·b` are polynomials in the partials (`b̃11 = L̃^Q A11² +
    /// 2 M̃^Q A11 A21 + Ñ^Q A21² − L̃^P D²`, with `L̃ = S_uu·n` etc.), and the positive factor
    /// `|n| D²` changes no root direction. Only the unit-speed normalisation and `(u', v') =
    /// A·(σ', t')/D` divide. It equals [`tangential_velocity`] of [`contact_quadratic`] (tested),
    /// with far less interval dependency.
    pub fn velocity<T: Scalar>(&self, y: &[T; 4]) -> [T; 4] {
        let p = self.p.second_order(y[0], y[1]);
        let q = self.q.second_order(y[2], y[3]);
        Self::velocity_from(p, q, self.formula, self.orientation)
    }

    /// [`velocity`](Self::velocity) with both surfaces written around the centre `c` (the same
    /// function; tighter in intervals near `c`).
    pub fn velocity_centred<T: Scalar>(&self, y: &[T; 4], c: &[T; 4]) -> [T; 4] {
        let p = self.p.second_order_centred(y[0], y[1], c[0], c[1]);
        let q = self.q.second_order_centred(y[2], y[3], c[2], c[3]);
        Self::velocity_from(p, q, self.formula, self.orientation)
    }

    fn velocity_from<T: Scalar>(
        p: [[T; 3]; 6],
        q: [[T; 3]; 6],
        formula: TangentialFormula,
        orientation: f64,
    ) -> [T; 4] {
        let c = ScaledContact::new(&p, &q);
        let (ds, dt) = formula.double_root(c.b11, c.b12, c.b22);
        let (ps, pt) = (p[1], p[2]);
        let [[a11, a12], [a21, a22]] = c.a;
        let d = c.d;
        // |P_σ σ' + P_t t'|² = E σ'² + 2F σ' t' + G t'².
        let speed = [0, 1, 2].map(|i| ps[i] * ds + pt[i] * dt);
        let k = T::from_f64(orientation) / norm_sqr(&speed).sqrt();
        let (s1, t1) = (ds * k, dt * k);
        [s1, t1, (a11 * s1 + a12 * t1) / d, (a21 * s1 + a22 * t1) / d]
    }
}

impl<P: CentredSecondOrder + ?Sized, Q: CentredSecondOrder + ?Sized> OdeSystem
    for TangentialOde<'_, P, Q>
{
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        self.velocity(&[y[0], y[1], y[2], y[3]]).to_vec()
    }
    fn eval_centred<S: Scalar>(&self, y: &[S], c: &[S]) -> Vec<S> {
        self.velocity_centred(&[y[0], y[1], y[2], y[3]], &[c[0], c[1], c[2], c[3]])
            .to_vec()
    }
    fn uses_centre(&self) -> bool {
        true
    }
}

/// The same tangential field as [`TangentialOde`], written in **ratio form** for the validated
/// engine: `(σ', t') ∝ (1, −b̃12/b̃22)` for [`TangentialFormula::FromB22`] (`∝ (−b̃12/b̃11, 1)`
/// for `FromB11`), normalised to unit speed, times `orientation · pivot_sign`.
///
/// **Why.** The root vector `(b̃22, −b̃12)` of the scaled form carries the factor `|N^P|·D²`,
/// whose size changes fast along a contact curve while the direction changes slowly. Interval
/// Taylor coefficients cannot see that the unit-speed normalisation cancels the change of size:
/// the radial sensitivity is counted twice instead of cancelling, and the widths of the
/// coefficients over a box grow several times faster per order than the coefficients themselves
/// (measured on the cubic × quadratic contact: the root-test radius of the 16th coefficient over a
/// box of width 10⁻² along the curve is 0.060 in the scaled form, 0.085 in the ratio form; the
/// point solution's is ≈ 0.65). The ratio `b̃12/b̃22` has no size: its direction vector has
/// first component 1, so the validated steps may be longer for the same term target.
///
/// **Same field.** `(b̃22, −b̃12) = b̃22·(1, −b̃12/b̃22)`, so wherever the pivot (`b̃22`, or `b̃11`
/// for `FromB11`) has the sign `pivot_sign`, this field equals the [`TangentialOde`] with the same
/// formula and orientation. The engine evaluates the field only on boxes where the pivot is proven
/// non-zero (a quotient by an interval that may vanish is a domain error), each a-priori box of a
/// trace holds the start of its step, and consecutive boxes share solution points: the pivot keeps
/// one sign along every proven trace, the sign on its start set. [`pivot_sign`] proves that sign
/// on a box; with it, everything the engine proves about this field holds for the
/// [`TangentialOde`].
#[derive(Debug, Clone, Copy)]
pub struct RatioTangentialOde<'a, P: ?Sized, Q: ?Sized> {
    /// The field in scaled form (surfaces, root formula, orientation).
    pub field: TangentialOde<'a, P, Q>,
    /// The sign (±1) of the pivot on the traced region.
    pub pivot_sign: f64,
}

impl<P: CentredSecondOrder + ?Sized, Q: CentredSecondOrder + ?Sized> RatioTangentialOde<'_, P, Q> {
    /// The velocity `(σ', t', u', v')` in ratio form at `y`, both surfaces written around the
    /// centre `c`.
    pub fn velocity_centred<T: Scalar>(&self, y: &[T; 4], c: &[T; 4]) -> [T; 4] {
        let f = &self.field;
        let p = f.p.second_order_centred(y[0], y[1], c[0], c[1]);
        let q = f.q.second_order_centred(y[2], y[3], c[2], c[3]);
        let k = ScaledContact::new(&p, &q);
        let (ds, dt) = match f.formula {
            TangentialFormula::FromB22 => (T::one(), -(k.b12 / k.b22)),
            TangentialFormula::FromB11 => (-(k.b12 / k.b11), T::one()),
        };
        let (ps, pt) = (p[1], p[2]);
        let speed = [0, 1, 2].map(|i| ps[i] * ds + pt[i] * dt);
        let sign = T::from_f64(f.orientation * self.pivot_sign);
        let scale = sign / norm_sqr(&speed).sqrt();
        let (s1, t1) = (ds * scale, dt * scale);
        let [[a11, a12], [a21, a22]] = k.a;
        [
            s1,
            t1,
            (a11 * s1 + a12 * t1) / k.d,
            (a21 * s1 + a22 * t1) / k.d,
        ]
    }
}

impl<P: CentredSecondOrder + ?Sized, Q: CentredSecondOrder + ?Sized> OdeSystem
    for RatioTangentialOde<'_, P, Q>
{
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        let y = [y[0], y[1], y[2], y[3]];
        self.velocity_centred(&y, &y).to_vec()
    }
    fn eval_centred<S: Scalar>(&self, y: &[S], c: &[S]) -> Vec<S> {
        self.velocity_centred(&[y[0], y[1], y[2], y[3]], &[c[0], c[1], c[2], c[3]])
            .to_vec()
    }
    fn uses_centre(&self) -> bool {
        true
    }
}

/// The sign of the pivot of `formula` (`b̃22` for `FromB22`, `b̃11` for `FromB11`) on the box
/// `y`, if the interval evaluation (scaled form, both surfaces written around the box centre)
/// proves it non-zero there; `None` otherwise.
pub fn pivot_sign<P, Q>(p: &P, q: &Q, formula: TangentialFormula, y: &[Interval; 4]) -> Option<f64>
where
    P: CentredSecondOrder + ?Sized,
    Q: CentredSecondOrder + ?Sized,
{
    let c = y.map(|x| point(x.mid()));
    let sp = p.second_order_centred(y[0], y[1], c[0], c[1]);
    let sq = q.second_order_centred(y[2], y[3], c[2], c[3]);
    let k = ScaledContact::new(&sp, &sq);
    let pivot = match formula {
        TangentialFormula::FromB22 => k.b22,
        TangentialFormula::FromB11 => k.b11,
    };
    if pivot.is_empty() {
        None
    } else if pivot.inf() > 0.0 {
        Some(1.0)
    } else if pivot.sup() < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// The contact quadratic in the division-free scaled form of [`TangentialOde::velocity`], from
/// the second-order data `[S, S_u, S_v, S_uu, S_uv, S_vv]` of both surfaces.
///
/// `b̃ = |N^P|·D²·b` and `Δ̃ = b̃12² − b̃11 b̃22 = (|N^P| D²)² Δ` have the signs (and zero sets)
/// of the true `b` and `Δ` wherever `D ≠ 0`, so they classify a box like
/// [`crate::pair::contact_quadratic::classify`] with less interval dependency.
#[derive(Debug, Clone, Copy)]
pub struct ScaledContact<T> {
    /// `A = D·a`: numerators of the parameter map `(u', v') = A·(σ', t')/D`.
    pub a: [[T; 2]; 2],
    /// `D = det(Q_u, Q_v, P_σ × P_t)`.
    pub d: T,
    /// `b̃11`.
    pub b11: T,
    /// `b̃12`.
    pub b12: T,
    /// `b̃22`.
    pub b22: T,
    /// `Δ̃ = b̃12² − b̃11 b̃22`.
    pub discriminant: T,
    /// `|N^P × N^Q|²` (unnormalised normals): zero exactly where the surfaces are tangent.
    pub cross_norm_sqr: T,
}

impl<T: Scalar> ScaledContact<T> {
    /// The scaled quantities from both surfaces' second-order data.
    pub fn new(p: &[[T; 3]; 6], q: &[[T; 3]; 6]) -> Self {
        let [_, ps, pt, ..] = *p;
        let [_, qu, qv, ..] = *q;
        let n = cross(&ps, &pt);
        let (d, a) = tangent_map_numerators(&ps, &pt, &qu, &qv, &n);
        let d2 = d.sqr();
        let (p_form, q_form) = second_forms(p, q, &n);
        let [b11, b12, b22] = quadratic_coefficients(&a, p_form.map(|x| x * d2), q_form);
        ScaledContact {
            a,
            d,
            b11,
            b12,
            b22,
            discriminant: b12.sqr() - b11 * b22,
            cross_norm_sqr: norm_sqr(&cross(&n, &cross(&qu, &qv))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::{interval, point};
    use crate::pair::contact_quadratic::{contact_quadratic, tangential_velocity};
    use crate::pair::field::ScalarSurface;
    use crate::pair::fixtures::Bowl;
    use crate::validated::{Integrator, IntegratorOptions};

    /// z = (u − v)² against z = 0: contact along the diagonal u = v, so the unit-speed solution
    /// from the origin is (s, s, s, s)/√2 (in P's and Q's parameters alike).
    struct Valley;
    impl CentredSecondOrder for Valley {}
    impl CentredSecondOrder for Bowl {}
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
                term_target: 1e-14,
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

    #[test]
    fn scaled_form_equals_the_contact_quadratic_direction() {
        // Off any contact (where the formulas still define a field) and for both root formulas.
        let p = Bowl {
            a: 0.7,
            b: -0.4,
            d: 0.1,
        };
        let q = Bowl {
            a: -0.3,
            b: 0.9,
            d: 0.0,
        };
        for k in 0..40 {
            let x = -0.8 + 0.04 * k as f64;
            let y = [x, 0.3 - 0.5 * x, 0.2 + 0.3 * x, -0.1 * x];
            let c = contact_quadratic(&p, &q, &y);
            for formula in [TangentialFormula::FromB11, TangentialFormula::FromB22] {
                for orientation in [1.0, -1.0] {
                    let want = tangential_velocity(&c, formula, orientation);
                    let ode = TangentialOde {
                        p: &p,
                        q: &q,
                        formula,
                        orientation,
                    };
                    let got = ode.velocity(&y);
                    for i in 0..4 {
                        assert!((got[i] - want[i]).abs() < 1e-12, "{i}: {got:?} vs {want:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn ratio_form_is_the_scaled_field_where_the_pivot_has_its_sign() {
        let p = Bowl {
            a: 0.7,
            b: -0.4,
            d: 0.1,
        };
        let q = Bowl {
            a: -0.3,
            b: 0.9,
            d: 0.0,
        };
        let mut seen = [false; 2];
        // Swapping the surfaces flips the signs of b.
        for (p, q) in [(&p, &q), (&q, &p)] {
            for k in 0..40 {
                let x = -0.8 + 0.04 * k as f64;
                let y = [x, 0.3 - 0.5 * x, 0.2 + 0.3 * x, -0.1 * x];
                for formula in [TangentialFormula::FromB11, TangentialFormula::FromB22] {
                    let Some(sign) = pivot_sign(p, q, formula, &y.map(point)) else {
                        continue;
                    };
                    seen[usize::from(sign > 0.0)] = true;
                    for orientation in [1.0, -1.0] {
                        let field = TangentialOde {
                            p,
                            q,
                            formula,
                            orientation,
                        };
                        let want = field.velocity(&y);
                        let ratio = RatioTangentialOde {
                            field,
                            pivot_sign: sign,
                        };
                        let got = ratio.velocity_centred(&y, &[0.1, -0.2, 0.3, 0.0]);
                        for i in 0..4 {
                            assert!((got[i] - want[i]).abs() < 1e-12, "{i}: {got:?} vs {want:?}");
                        }
                        // In intervals over a small box it encloses the point value.
                        let b = y.map(|c| interval(c - 1e-3, c + 1e-3).unwrap());
                        let vi = ratio.velocity_centred(&b, &y.map(point));
                        assert!(
                            (0..4).all(|i| vi[i].contains(want[i])),
                            "{vi:?} vs {want:?}"
                        );
                    }
                }
            }
        }
        assert_eq!(seen, [true, true], "both pivot signs occur");
    }
}
