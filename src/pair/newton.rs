//! Newton refinement of a guess `(σ, t, u, v)` onto the intersection `P(σ,t) = Q(u,v)`.
//!
//! The three equations `P − Q = 0` get one more, the step constraint, to make a square 4×4 system:
//! either the point of P lies on a plane (the plane through the predicted point orthogonal to the
//! step direction), or one of the four parameters is held fixed (landing on a domain boundary).

use crate::error::{Error, Result};
use crate::geometry::{ParametricSurface, Vec3};
use nalgebra::{Matrix3x4, Matrix4, Vector3, Vector4};

/// The fourth equation of the Newton system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Constraint {
    /// `normal · (P(σ,t) − point) = 0`: the new point lies on this plane.
    Plane {
        /// A point of the plane.
        point: Vec3,
        /// Its normal (need not be unit; it scales the residual).
        normal: Vec3,
    },
    /// Parameter `index` (0 = σ, 1 = t, 2 = u, 3 = v) stays at `value`.
    Fixed {
        /// Which parameter.
        index: usize,
        /// Its value.
        value: f64,
    },
}

/// A converged Newton solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Refined {
    /// `(σ, t, u, v)` on the intersection.
    pub x: [f64; 4],
    /// Corrections applied, the last one being at most `tol` long (so at least 1).
    pub iterations: usize,
    /// `|P(σ,t) − Q(u,v)|` at the end.
    pub residual: f64,
}

/// Refines `guess` onto `P = Q` under `constraint`.
///
/// Iterations count corrections until one moves the point by at most `tol` (model units; or by
/// at most the f64 position noise `4ε·max(|P|, 1) / sin∠(N^P, N^Q)` where that is larger, so
/// near-tangent surfaces, e.g. a loop of radius 1e-6, converge) and leaves `|P − Q| ≤ tol` (the usual "correction below tolerance" rule: a prediction already
/// within `tol` takes one iteration, the confirming one).
///
/// Guarantees on `Ok`: `|P − Q| ≤ tol` and the constraint residual `≤ tol` at the returned point,
/// reached within `max_iter` corrections. Fails with [`Error::NewtonFailed`] (never panics) when the
/// Jacobian is singular, a value is not finite, or the iteration does not converge.
pub fn refine<S1, S2>(
    p: &S1,
    q: &S2,
    guess: [f64; 4],
    constraint: Constraint,
    tol: f64,
    max_iter: usize,
) -> Result<Refined>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let mut x = Vector4::from(guess);
    if let Constraint::Fixed { index, value } = constraint {
        if index < 4 {
            x[index] = value;
        }
    }
    let fail = |iterations: usize, residual: f64, x: &Vector4<f64>| Error::NewtonFailed {
        iterations,
        residual,
        near: [x[0], x[1], x[2], x[3]],
    };
    let mut residual = f64::INFINITY;
    for it in 1..=max_iter {
        let dp = p.derivs(x[0], x[1]);
        let dq = q.derivs(x[2], x[3]);
        let gap = dp.p - dq.p;
        residual = gap.norm();
        let (c_val, c_row) = match constraint {
            Constraint::Plane { point, normal } => (
                normal.dot(&(dp.p - point)),
                [normal.dot(&dp.su), normal.dot(&dp.sv), 0.0, 0.0],
            ),
            Constraint::Fixed { index, value } => {
                if index >= 4 {
                    return Err(fail(it - 1, residual, &x));
                }
                let mut row = [0.0; 4];
                row[index] = 1.0;
                (x[index] - value, row)
            }
        };
        let jac = Matrix4::new(
            dp.su.x, dp.sv.x, -dq.su.x, -dq.sv.x, //
            dp.su.y, dp.sv.y, -dq.su.y, -dq.sv.y, //
            dp.su.z, dp.sv.z, -dq.su.z, -dq.sv.z, //
            c_row[0], c_row[1], c_row[2], c_row[3],
        );
        let rhs = Vector4::new(-gap.x, -gap.y, -gap.z, -c_val);
        let Some(dx) = jac.lu().solve(&rhs) else {
            return Err(fail(it - 1, residual, &x));
        };
        x += dx;
        if !x.iter().all(|c| c.is_finite()) {
            return Err(fail(it, f64::NAN, &x));
        }
        // Check the corrected point: converged when the correction itself was at most `tol`
        // in model space and the corrected point satisfies the equations within `tol`.
        let pp = p.point(x[0], x[1]);
        let qq = q.point(x[2], x[3]);
        let moved = (pp - dp.p).norm().max((qq - dq.p).norm());
        residual = (pp - qq).norm();
        let c_res = match constraint {
            Constraint::Plane { point, normal } => normal.dot(&(pp - point)).abs(),
            Constraint::Fixed { index, value } => (x[index] - value).abs(),
        };
        // The correction cannot fall below the position noise of f64: evaluation errors of
        // about ε|P| in P − Q move the solution by that over the sine of the normals' angle
        // (5e-11 for a loop of radius 1e-6 at z ≈ 1). A correction at that floor counts as
        // converged; the residual tests below are unchanged, so `|P − Q| ≤ tol` still holds.
        let (np, nq) = (dp.normal(), dq.normal());
        let sine = np.cross(&nq).norm() / (np.norm() * nq.norm());
        let noise = 4.0 * f64::EPSILON * pp.norm().max(qq.norm()).max(1.0) / sine;
        let step_ok = moved <= tol || (noise.is_finite() && moved <= noise);
        if step_ok && residual <= tol && c_res <= tol.max(1e-15) {
            return Ok(Refined {
                x: [x[0], x[1], x[2], x[3]],
                iterations: it,
                residual,
            });
        }
    }
    Err(fail(max_iter, residual, &x))
}

/// Gauss–Newton (minimum-norm steps) from `x` onto `P(σ,t) = Q(u,v)`; `None` if it does not
/// converge to a residual below `tol`.
pub fn project_onto_intersection<P, Q>(p: &P, q: &Q, mut x: [f64; 4], tol: f64) -> Option<[f64; 4]>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    for _ in 0..40 {
        let a = p.derivs(x[0], x[1]);
        let b = q.derivs(x[2], x[3]);
        let f: Vector3<f64> = a.p - b.p;
        let j = Matrix3x4::from_columns(&[a.su, a.sv, -b.su, -b.sv]);
        let jjt = j * j.transpose();
        let y = jjt.lu().solve(&f)?;
        let step = j.transpose() * y;
        for (xi, si) in x.iter_mut().zip(step.iter()) {
            *xi -= si;
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if f.norm() <= tol && step.norm() <= 1e-10 {
            return Some(x);
        }
        if step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max)) {
            let r = (p.point(x[0], x[1]) - q.point(x[2], x[3])).norm();
            return (r <= tol).then_some(x);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::analytic::{AnalyticSurface, Jet2};
    use crate::geometry::Domain;

    #[test]
    fn sphere_and_plane_converge_to_the_circle() {
        let d = Domain::new(-4.0, 4.0, -4.0, 4.0);
        // Unit sphere (longitude u, latitude v) against the plane z = 0.5.
        let sphere = AnalyticSurface::new(d, |u: Jet2, v: Jet2| {
            [u.cos() * v.cos(), u.sin() * v.cos(), v.sin()]
        });
        let plane = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(0.5)]);
        let r = refine(
            &sphere,
            &plane,
            [0.3, 0.6, 0.8, 0.2],
            Constraint::Fixed {
                index: 0,
                value: 0.3,
            },
            1e-13,
            20,
        )
        .expect("converges");
        // Exact: v = π/6, (u, v) of the plane = (cos 0.3, sin 0.3)·cos(π/6).
        let c = (std::f64::consts::PI / 6.0).cos();
        assert!((r.x[1] - std::f64::consts::PI / 6.0).abs() < 1e-12);
        assert!((r.x[2] - 0.3f64.cos() * c).abs() < 1e-12);
        assert!((r.x[3] - 0.3f64.sin() * c).abs() < 1e-12);
        assert!(r.iterations >= 1);
    }

    #[test]
    fn parallel_planes_fail_with_a_typed_error() {
        let d = Domain::UNIT;
        let a = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(0.0)]);
        let b = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(1.0)]);
        let r = refine(
            &a,
            &b,
            [0.5; 4],
            Constraint::Fixed {
                index: 0,
                value: 0.5,
            },
            1e-12,
            10,
        );
        assert!(matches!(r, Err(Error::NewtonFailed { .. })));
    }
}
