//! Tangential intersections: the contact quadratic b11 σ'² + 2 b12 σ' t' + b22 t'² = 0.
//!
//! Where the surfaces are tangent (N^P ∥ N^Q) the transversal tangent c = N^P × N^Q vanishes and
//! the direction of the curve comes from equal normal curvatures (after Ye & Maekawa 1999). With
//! one unit normal N (here N^P/|N^P|) and D = det(Q_u, Q_v, N):
//!
//! ```text
//! u' = a11 σ' + a12 t',  v' = a21 σ' + a22 t'
//! a11 = det(P_σ, Q_v, N)/D   a12 = det(P_t, Q_v, N)/D
//! a21 = det(Q_u, P_σ, N)/D   a22 = det(Q_u, P_t, N)/D
//! b11 = L^Q a11² + 2 M^Q a11 a21 + N^Q a21² − L^P
//! b12 = L^Q a11 a12 + M^Q (a11 a22 + a12 a21) + N^Q a21 a22 − M^P
//! b22 = L^Q a12² + 2 M^Q a12 a22 + N^Q a22² − N^P
//! ```
//!
//! and Δ = b12² − b11·b22. Evaluated in intervals this gives the four cases of the seed paper:
//! Δ < 0 an isolated contact point; Δ > 0 a branch point with two directions; Δ ∋ 0 with some b
//! bounded away from zero a tangential curve with one direction; every b ∋ 0 higher-order contact
//! (undecidable at this order).
//!
//! This module is the one home of those formulas and of their classification: the interval
//! certifier, the `f64` node analysis of the marcher ([`crate::pair::branch_point`]) and the
//! boundary classification ([`crate::pair::boundary_direction`]) all build their quadratic
//! with [`contact_from_second_order`] (or its parts [`tangent_map_numerators`] and
//! [`quadratic_coefficients`]) and classify it with [`classify`]; they differ only in the
//! [`SignRule`] that decides the signs: [`Proven`] interval signs, or [`Relative`] `f64`
//! thresholds.

use crate::geometry::{SurfaceDerivs, Vec3};
use crate::numeric::vec3::{cross, det, dot, norm_sqr};
use crate::pair::field::ScalarSurface;
use crate::Scalar;
use inari::Interval;

/// The contact quadratic and the parameter map between the surfaces at a tangential point.
#[derive(Debug, Clone, Copy)]
pub struct ContactQuadratic<T> {
    /// `[[a11, a12], [a21, a22]]`: `(u', v') = a·(σ', t')`.
    pub a: [[T; 2]; 2],
    /// `b11`.
    pub b11: T,
    /// `b12`.
    pub b12: T,
    /// `b22`.
    pub b22: T,
    /// `Δ = b12² − b11·b22`.
    pub discriminant: T,
    /// First fundamental form `(E, F, G)` of P.
    pub first_form: [T; 3],
    /// `D = det(Q_u, Q_v, N)`, the denominator of `a` (zero where Q's partials are degenerate).
    pub d: T,
}

/// The contact quadratic at `y = (σ, t, u, v)`, evaluated in `T`.
pub fn contact_quadratic<T, P, Q>(p: &P, q: &Q, y: &[T; 4]) -> ContactQuadratic<T>
where
    T: Scalar,
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let sp = p.second_order(y[0], y[1]);
    let sq = q.second_order(y[2], y[3]);
    let np = cross(&sp[1], &sp[2]);
    let inv = T::one() / norm_sqr(&np).sqrt();
    let n = np.map(|c| c * inv);
    contact_from_second_order(&sp, &sq, &n)
}

/// The numerators of the parameter map `a = A/D` against the normal `n`: `(D, A)` with
/// `D = det(Q_u, Q_v, n)`, `A = [[det(P_σ, Q_v, n), det(P_t, Q_v, n)], [det(Q_u, P_σ, n),
/// det(Q_u, P_t, n)]]`. Any non-zero multiple of the unit normal gives the same `a`.
pub fn tangent_map_numerators<T: Scalar>(
    ps: &[T; 3],
    pt: &[T; 3],
    qu: &[T; 3],
    qv: &[T; 3],
    n: &[T; 3],
) -> (T, [[T; 2]; 2]) {
    let d = det(qu, qv, n);
    let a = [
        [det(ps, qv, n), det(pt, qv, n)],
        [det(qu, ps, n), det(qu, pt, n)],
    ];
    (d, a)
}

/// `[b11, b12, b22]` from the parameter map `a` and the second fundamental forms of P
/// (`[L^P, M^P, N^P]`) and Q (`[L^Q, M^Q, N^Q]`) against the common normal. A caller working
/// with `A = D·a` passes P's form times `D²` and gets `D²·b`.
pub fn quadratic_coefficients<T: Scalar>(
    a: &[[T; 2]; 2],
    p_form: [T; 3],
    q_form: [T; 3],
) -> [T; 3] {
    let [[a11, a12], [a21, a22]] = *a;
    let [lp, mp, np] = p_form;
    let [lq, mq, nq] = q_form;
    let two = T::from_f64(2.0);
    [
        lq * a11.sqr() + two * mq * a11 * a21 + nq * a21.sqr() - lp,
        lq * a11 * a12 + mq * (a11 * a22 + a12 * a21) + nq * a21 * a22 - mp,
        lq * a12.sqr() + two * mq * a12 * a22 + nq * a22.sqr() - np,
    ]
}

/// The second fundamental forms `([L^P, M^P, N^P], [L^Q, M^Q, N^Q])` against the normal `n`
/// (second derivatives dotted with `n`) from the second-order data `[S, S_u, S_v, S_uu, S_uv,
/// S_vv]` of both surfaces.
pub fn second_forms<T: Scalar>(p: &[[T; 3]; 6], q: &[[T; 3]; 6], n: &[T; 3]) -> ([T; 3], [T; 3]) {
    let form = |s: &[[T; 3]; 6]| [dot(&s[3], n), dot(&s[4], n), dot(&s[5], n)];
    (form(p), form(q))
}

/// The contact quadratic from both surfaces' second-order data `[S, S_u, S_v, S_uu, S_uv, S_vv]`
/// and the unit normal `n` (the caller's normalisation of `N^P`).
pub fn contact_from_second_order<T: Scalar>(
    p: &[[T; 3]; 6],
    q: &[[T; 3]; 6],
    n: &[T; 3],
) -> ContactQuadratic<T> {
    let [_, ps, pt, ..] = p;
    let [_, qu, qv, ..] = q;
    let (d, num) = tangent_map_numerators(ps, pt, qu, qv, n);
    let a = num.map(|row| row.map(|x| x / d));
    let (p_form, q_form) = second_forms(p, q, n);
    let [b11, b12, b22] = quadratic_coefficients(&a, p_form, q_form);
    ContactQuadratic {
        a,
        b11,
        b12,
        b22,
        discriminant: b12.sqr() - b11 * b22,
        first_form: [dot(ps, ps), dot(ps, pt), dot(pt, pt)],
        d,
    }
}

/// The contact quadratic in `f64` from evaluated derivatives of both surfaces and the unit
/// normal `n` ([`contact_from_second_order`]).
pub fn contact_from_derivs(
    dp: &SurfaceDerivs,
    dq: &SurfaceDerivs,
    n: &Vec3,
) -> ContactQuadratic<f64> {
    let second = |d: &SurfaceDerivs| [d.p, d.su, d.sv, d.suu, d.suv, d.svv].map(<[f64; 3]>::from);
    contact_from_second_order(&second(dp), &second(dq), &(*n).into())
}

/// The four cases of a tangential point (the one enum for them: certified, boundary and
/// marcher-side classifications alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactCase {
    /// Δ < 0: the surfaces touch at an isolated point.
    IsolatedPoint,
    /// Δ > 0: two branches cross here.
    BranchPoint,
    /// Δ ≈ 0 (not decided) but some b is not: a tangential curve with one defined direction.
    TangentialCurve,
    /// Every b is indistinguishable from 0: contact of higher order, undecidable from
    /// second-order data.
    HigherOrder,
}

/// How the signs of a contact quadratic are decided: proven interval signs ([`Proven`]) or
/// `f64` thresholds relative to the size of the coefficients ([`Relative`]).
pub trait SignRule<T> {
    /// Whether all of `b = [b11, b12, b22]` are indistinguishable from zero.
    fn vanish(&self, b: &[T; 3]) -> bool;
    /// Whether `Δ < 0` is decided.
    fn negative(&self, discriminant: T, b: &[T; 3]) -> bool;
    /// Whether `Δ > 0` is decided.
    fn positive(&self, discriminant: T, b: &[T; 3]) -> bool;
}

/// Interval signs: a sign counts only when the enclosure excludes zero (and is not empty: an
/// evaluation that divided by an exact zero proves nothing).
#[derive(Debug, Clone, Copy)]
pub struct Proven;

impl SignRule<Interval> for Proven {
    fn vanish(&self, b: &[Interval; 3]) -> bool {
        b.iter().all(|x| x.contains(0.0))
    }
    fn negative(&self, discriminant: Interval, _: &[Interval; 3]) -> bool {
        !discriminant.is_empty() && discriminant.sup() < 0.0
    }
    fn positive(&self, discriminant: Interval, _: &[Interval; 3]) -> bool {
        !discriminant.is_empty() && discriminant.inf() > 0.0
    }
}

/// `f64` estimates: with `|b| = max(|b11|, |b12|, |b22|)`, the `b` vanish where `|b| ≤ floor`
/// and `Δ` has a sign where `|Δ| > rel·|b|²`.
#[derive(Debug, Clone, Copy)]
pub struct Relative {
    /// Absolute size below which the `b` count as zero.
    pub floor: f64,
    /// Relative size of `Δ` (against `|b|²`) below which its sign is not decided.
    pub rel: f64,
}

impl Relative {
    fn size(b: &[f64; 3]) -> f64 {
        b[0].abs().max(b[1].abs()).max(b[2].abs())
    }
}

impl SignRule<f64> for Relative {
    fn vanish(&self, b: &[f64; 3]) -> bool {
        Relative::size(b) <= self.floor
    }
    fn negative(&self, discriminant: f64, b: &[f64; 3]) -> bool {
        let size = Relative::size(b);
        discriminant < -self.rel * size * size
    }
    fn positive(&self, discriminant: f64, b: &[f64; 3]) -> bool {
        let size = Relative::size(b);
        discriminant > self.rel * size * size
    }
}

/// The case of a contact quadratic with discriminant `discriminant` and coefficients
/// `b = [b11, b12, b22]`, its signs decided by `rule`.
pub fn classify<T: Copy, R: SignRule<T>>(discriminant: T, b: [T; 3], rule: &R) -> ContactCase {
    if rule.vanish(&b) {
        ContactCase::HigherOrder
    } else if rule.negative(discriminant, &b) {
        ContactCase::IsolatedPoint
    } else if rule.positive(discriminant, &b) {
        ContactCase::BranchPoint
    } else {
        ContactCase::TangentialCurve
    }
}

impl<T: Scalar> ContactQuadratic<T> {
    /// `[b11, b12, b22]`.
    pub fn b(&self) -> [T; 3] {
        [self.b11, self.b12, self.b22]
    }

    /// The case of this quadratic, its signs decided by `rule`.
    pub fn case<R: SignRule<T>>(&self, rule: &R) -> ContactCase {
        classify(self.discriminant, self.b(), rule)
    }

    /// The double root `(σ', t')` of the quadratic (unnormalised) by `formula`.
    pub fn double_root(&self, formula: TangentialFormula) -> (T, T) {
        formula.double_root(self.b11, self.b12, self.b22)
    }

    /// `(σ', t', u', v')` for the P velocity `(σ', t')`, with `(u', v') = a·(σ', t')`.
    pub fn lift(&self, ds: T, dt: T) -> [T; 4] {
        [
            ds,
            dt,
            self.a[0][0] * ds + self.a[0][1] * dt,
            self.a[1][0] * ds + self.a[1][1] * dt,
        ]
    }
}

/// Which of the two equivalent direction formulas to use along a tangential curve: decided once
/// per step from an `f64` evaluation (the formulas themselves contain no branches).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentialFormula {
    /// (σ', t') ∝ (−b12, b11): used when |b11| ≥ |b22|.
    FromB11,
    /// (σ', t') ∝ (b22, −b12): used otherwise.
    FromB22,
}

impl TangentialFormula {
    /// The double root `(σ', t')` (unnormalised) of the quadratic with coefficients `b11`,
    /// `b12`, `b22` (or any common positive multiple of them) by this formula.
    pub fn double_root<T: Scalar>(self, b11: T, b12: T, b22: T) -> (T, T) {
        match self {
            TangentialFormula::FromB11 => (-b12, b11),
            TangentialFormula::FromB22 => (b22, -b12),
        }
    }

    /// The better-conditioned formula for an `f64` quadratic.
    pub fn choose(c: &ContactQuadratic<f64>) -> Self {
        if c.b11.abs() >= c.b22.abs() {
            TangentialFormula::FromB11
        } else {
            TangentialFormula::FromB22
        }
    }
}

/// The unit-speed parameter velocity `(σ', t', u', v')` along a tangential curve (Δ = 0), with
/// direction sign `orientation` = ±1. Normalised by E σ'² + 2F σ' t' + G t'² = 1.
pub fn tangential_velocity<T: Scalar>(
    c: &ContactQuadratic<T>,
    formula: TangentialFormula,
    orientation: f64,
) -> [T; 4] {
    let (ds, dt) = c.double_root(formula);
    let [e, f, g] = c.first_form;
    let len2 = e * ds.sqr() + T::from_f64(2.0) * f * ds * dt + g * dt.sqr();
    let k = T::from_f64(orientation) / len2.sqrt();
    c.lift(ds * k, dt * k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::{interval, point};
    use crate::pair::fixtures::Bowl;

    fn at_origin() -> [Interval; 4] {
        [point(0.0); 4]
    }

    #[test]
    fn bowl_on_plane_is_an_isolated_contact() {
        let c = contact_quadratic(&Bowl::new(1.0, 0.0), &Bowl::new(0.0, 0.0), &at_origin());
        assert_eq!(c.case(&Proven), ContactCase::IsolatedPoint);
        // Δ = 0 − (−2)(−2) = −4 exactly.
        assert!(c.discriminant.contains(-4.0) && c.discriminant.wid() < 1e-14);
    }

    #[test]
    fn saddle_on_plane_is_a_branch_point() {
        // z = u·v against z = 0 at the origin: b12 = −1, b11 = b22 = 0, Δ = 1.
        let saddle = Bowl {
            a: 0.0,
            b: 1.0,
            d: 0.0,
        };
        let c = contact_quadratic(&saddle, &Bowl::new(0.0, 0.0), &at_origin());
        assert_eq!(c.case(&Proven), ContactCase::BranchPoint);
        assert!(c.discriminant.contains(1.0));
    }

    #[test]
    fn parallel_cylinder_like_contact_is_a_tangential_curve_with_its_direction() {
        // z = u² (a "cylinder" graph along v) on z = 0 touches along the line u = 0.
        struct Trough;
        impl ScalarSurface for Trough {
            fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
                let [p, a, b, ..] = self.second_order(u, v);
                [p, a, b]
            }
            fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
                let (o, z, two) = (T::one(), T::zero(), T::from_f64(2.0));
                [
                    [u, v, u.sqr()],
                    [o, z, two * u],
                    [z, o, z],
                    [z, z, two],
                    [z, z, z],
                    [z, z, z],
                ]
            }
        }
        let y = [
            point(0.0),
            interval(0.2, 0.3).unwrap(),
            point(0.0),
            interval(0.2, 0.3).unwrap(),
        ];
        let c = contact_quadratic(&Trough, &Bowl::new(0.0, 0.0), &y);
        assert_eq!(c.case(&Proven), ContactCase::TangentialCurve);
        let cf = contact_quadratic(&Trough, &Bowl::new(0.0, 0.0), &[0.0, 0.25, 0.0, 0.25]);
        let vel = tangential_velocity(&cf, TangentialFormula::choose(&cf), 1.0);
        // Along the line u = 0: (σ', t') = (0, ±1) and (u', v') the same.
        assert!(vel[0].abs() < 1e-15 && (vel[1].abs() - 1.0).abs() < 1e-15);
        assert!((vel[2] - vel[0]).abs() < 1e-15 && (vel[3] - vel[1]).abs() < 1e-15);
    }

    #[test]
    fn flat_contact_is_higher_order() {
        let c = contact_quadratic(&Bowl::new(0.0, 0.0), &Bowl::new(0.0, 0.0), &at_origin());
        assert_eq!(c.case(&Proven), ContactCase::HigherOrder);
    }
}
