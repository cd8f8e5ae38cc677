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
}

/// The contact quadratic at `y = (σ, t, u, v)`, evaluated in `T`.
pub fn contact_quadratic<T, P, Q>(p: &P, q: &Q, y: &[T; 4]) -> ContactQuadratic<T>
where
    T: Scalar,
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let [_, ps, pt, pss, pst, ptt] = p.second_order(y[0], y[1]);
    let [_, qu, qv, quu, quv, qvv] = q.second_order(y[2], y[3]);
    let np = cross(&ps, &pt);
    let inv = T::one() / norm_sqr(&np).sqrt();
    let n = np.map(|c| c * inv);
    let d = det(&qu, &qv, &n);
    let a11 = det(&ps, &qv, &n) / d;
    let a12 = det(&pt, &qv, &n) / d;
    let a21 = det(&qu, &ps, &n) / d;
    let a22 = det(&qu, &pt, &n) / d;
    let (lp, mp, np2) = (dot(&pss, &n), dot(&pst, &n), dot(&ptt, &n));
    let (lq, mq, nq) = (dot(&quu, &n), dot(&quv, &n), dot(&qvv, &n));
    let two = T::from_f64(2.0);
    let b11 = lq * a11.sqr() + two * mq * a11 * a21 + nq * a21.sqr() - lp;
    let b12 = lq * a11 * a12 + mq * (a11 * a22 + a12 * a21) + nq * a21 * a22 - mp;
    let b22 = lq * a12.sqr() + two * mq * a12 * a22 + nq * a22.sqr() - np2;
    ContactQuadratic {
        a: [[a11, a12], [a21, a22]],
        b11,
        b12,
        b22,
        discriminant: b12.sqr() - b11 * b22,
        first_form: [dot(&ps, &ps), dot(&ps, &pt), dot(&pt, &pt)],
    }
}

/// The four interval cases of a tangential point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactCase {
    /// Δ < 0 proven: the surfaces touch at an isolated point.
    IsolatedPoint,
    /// Δ > 0 proven: two branches cross here.
    BranchPoint,
    /// Δ ∋ 0 but some b is bounded away from 0: a tangential curve with one defined direction.
    TangentialCurve,
    /// Every b contains 0: contact of higher order, undecidable from second-order data.
    HigherOrder,
}

/// Classifies an interval contact quadratic into the four cases.
pub fn classify(c: &ContactQuadratic<Interval>) -> ContactCase {
    let zero_free = |x: Interval| !x.contains(0.0);
    if c.discriminant.sup() < 0.0 {
        ContactCase::IsolatedPoint
    } else if c.discriminant.inf() > 0.0 {
        ContactCase::BranchPoint
    } else if zero_free(c.b11) || zero_free(c.b12) || zero_free(c.b22) {
        ContactCase::TangentialCurve
    } else {
        ContactCase::HigherOrder
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
    let (ds, dt) = match formula {
        TangentialFormula::FromB11 => (-c.b12, c.b11),
        TangentialFormula::FromB22 => (c.b22, -c.b12),
    };
    let [e, f, g] = c.first_form;
    let len2 = e * ds.sqr() + T::from_f64(2.0) * f * ds * dt + g * dt.sqr();
    let k = T::from_f64(orientation) / len2.sqrt();
    let (ds, dt) = (ds * k, dt * k);
    [
        ds,
        dt,
        c.a[0][0] * ds + c.a[0][1] * dt,
        c.a[1][0] * ds + c.a[1][1] * dt,
    ]
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
        assert_eq!(classify(&c), ContactCase::IsolatedPoint);
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
        assert_eq!(classify(&c), ContactCase::BranchPoint);
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
        assert_eq!(classify(&c), ContactCase::TangentialCurve);
        let cf = contact_quadratic(&Trough, &Bowl::new(0.0, 0.0), &[0.0, 0.25, 0.0, 0.25]);
        let vel = tangential_velocity(&cf, TangentialFormula::choose(&cf), 1.0);
        // Along the line u = 0: (σ', t') = (0, ±1) and (u', v') the same.
        assert!(vel[0].abs() < 1e-15 && (vel[1].abs() - 1.0).abs() < 1e-15);
        assert!((vel[2] - vel[0]).abs() < 1e-15 && (vel[3] - vel[1]).abs() < 1e-15);
    }

    #[test]
    fn flat_contact_is_higher_order() {
        let c = contact_quadratic(&Bowl::new(0.0, 0.0), &Bowl::new(0.0, 0.0), &at_origin());
        assert_eq!(classify(&c), ContactCase::HigherOrder);
    }
}
