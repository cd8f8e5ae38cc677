//! The residual `P(σ, t) − Q(u, v)` at an `f64` point, enclosed to the last division's rounding
//! only, and one Newton step on it.
//!
//! Over nearly tangent surfaces a link's tube is the residual's width over the sine of the
//! angle between the normals ([`crate::certify::segment`]): interval evaluation leaves tens of
//! ulps of the model's size in it (2e-14 on a cone of size 3), which at a sine of 5e-7 is a tube
//! of 4e-8; and a node refined by Newton in `f64` is off the curve by as much. With exact
//! patches (control data given as `f64`s) the residual at an `f64` point is a dyadic rational
//! over a positive one, computed here exactly ([`crate::numeric::dyadic`]); only its final
//! quotient rounds, to about 1e-16 of the residual itself.

use crate::certify::jet::others;
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use inari::Interval;
use nalgebra::{Matrix3, Vector3};

/// An enclosure of `P(x₀, x₁) − Q(x₂, x₃)` as wide as the rounding of one quotient of exact
/// numbers; `None` if either patch has interval (not exact) control data, or the numbers leave
/// the normal range of `f64`, or a weight sum is not bounded away from zero there.
pub(crate) fn exact_residual(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
) -> Option<[Interval; 3]> {
    let hp = p.homogeneous_exact(x[0], x[1])?;
    let hq = q.homogeneous_exact(x[2], x[3])?;
    // P − Q = (Hp·wq − Hq·wp) / (wp·wq), both scaled by positive domain factors.
    let den = (&hp[3] * &hq[3]).enclosure()?;
    if den.inf() <= 0.0 && den.sup() >= 0.0 {
        return None;
    }
    let mut out = [point(0.0); 3];
    for r in 0..3 {
        let num = &(&hp[r] * &hq[3]) - &(&hq[r] * &hp[3]);
        out[r] = num.enclosure()? / den;
    }
    out.iter()
        .all(|v| v.inf().is_finite() && v.sup().is_finite())
        .then_some(out)
}

/// `x` moved onto the curve by one Newton step on the exact residual, with `x_j` held: the
/// other three coordinates minus `J⁻¹·F(x)` (`J` the `f64` Jacobian of `P − Q` in them, whose
/// error only scales the step's own small size). `None` if the residual is not exact (see
/// [`exact_residual`]) or the step is not finite. Guidance only: the point steers a link's
/// predictor, whose proof is what is claimed.
pub(crate) fn onto_curve(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
    j: usize,
) -> Option<[f64; 4]> {
    let f = exact_residual(p, q, x)?;
    let f = Vector3::from_fn(|r, _| f[r].mid());
    if f.iter().all(|v| *v == 0.0) {
        return Some(*x);
    }
    let [_, ps, pt] = p.first_derivs(x[0], x[1]);
    let [_, qu, qv] = q.first_derivs(x[2], x[3]);
    let cols = [ps, pt, qu.map(|v| -v), qv.map(|v| -v)];
    let free = others(j);
    let jac = Matrix3::from_fn(|r, c| cols[free[c]][r]);
    let step = jac.try_inverse()? * f;
    let mut out = *x;
    for (c, &i) in free.iter().enumerate() {
        out[i] -= step[c];
    }
    out.iter().all(|v| v.is_finite()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Domain;

    /// The plane at height `z` over `[−2, 2]²`.
    fn plane(z: f64) -> RationalBezierPatch {
        RationalBezierPatch::new(
            [1, 1],
            vec![
                [-2.0, -2.0, z],
                [-2.0, 2.0, z],
                [2.0, -2.0, z],
                [2.0, 2.0, z],
            ]
            .into_iter()
            .map(|p| p.map(point))
            .collect(),
            None,
            Domain::UNIT,
        )
        .unwrap()
    }

    /// The paraboloid `z = x² + y²` over `[−1, 1]²` (a polynomial Bézier patch, exact net).
    fn paraboloid() -> RationalBezierPatch {
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                let (x, y) = (i as f64 - 1.0, j as f64 - 1.0);
                // z = x² + y² has Bernstein coefficients 1, −1, 1 in each variable.
                let cz = |k: usize| if k == 1 { -1.0 } else { 1.0 };
                pts.push([x, y, cz(i) + cz(j)].map(point));
            }
        }
        RationalBezierPatch::new([2, 2], pts, None, Domain::UNIT).unwrap()
    }

    #[test]
    fn a_near_tangent_circle_is_reached_to_the_last_bits() {
        // z = δ cuts the paraboloid in the circle x² + y² = δ (radius 1e-4): the surfaces are
        // nearly tangent there (sine ~ 2e-4).
        let delta = 1e-8;
        let (p, q) = (paraboloid(), plane(delta));
        let r = delta.sqrt();
        for k in 0..16 {
            let a = k as f64 * 0.39;
            let (x, y) = (r * a.cos(), r * a.sin());
            // Parameters: P at ((x + 1)/2, (y + 1)/2), Q at ((x + 2)/4, (y + 2)/4); start 1e-9
            // off the circle radially.
            let off = 1.0 + 1e-9 / r;
            let guess = [
                (x * off + 1.0) / 2.0,
                (y * off + 1.0) / 2.0,
                (x * off + 2.0) / 4.0,
                (y * off + 2.0) / 4.0,
            ];
            // Held: the coordinate the circle moves along most there.
            let j = if a.sin().abs() > a.cos().abs() { 2 } else { 3 };
            let x1 = onto_curve(&p, &q, &guess, j).unwrap();
            let x2 = onto_curve(&p, &q, &x1, j).unwrap();
            assert_eq!(x1[j], guess[j]);
            // The height's residual is what the near tangency amplifies: on the curve to
            // the parameters' own quantisation (2r·ulp ≈ 4e-20; an f64 Newton leaves about
            // the rounding of the heights, 1e-16, so 5e-13 off radially).
            let f = exact_residual(&p, &q, &x2).unwrap();
            assert!(f[2].mag() < 1e-18, "{k}: {f:?}");
            assert!(f[0].mag() < 1e-15 && f[1].mag() < 1e-15, "{k}: {f:?}");
            // The residual of a point off the curve is enclosed, and tight.
            let f0 = exact_residual(&p, &q, &guess).unwrap();
            let e = p.eval(point(guess[0]), point(guess[1]));
            let g = q.eval(point(guess[2]), point(guess[3]));
            for c in 0..3 {
                assert!((e[c] - g[c]).contains(f0[c].mid()), "{c}");
                assert!(f0[c].wid() <= 1e-15 * f0[c].mag(), "{:?}", f0[c]);
            }
        }
    }
}
