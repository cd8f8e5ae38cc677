//! Wu–Andrade circular step on the approximate osculating circle.
//!
//! From the previous point `P` with unit tangent `u` and the current point `Q` with unit tangent
//! `v`, the centre `C` is the intersection of three planes: through `P` orthogonal to `u`, through
//! `Q` orthogonal to `v`, and through `Q` orthogonal to `u × v`. The radius is `R = |CQ|`. The next
//! point is `Q` rotated about the axis through `C` along `CP × CQ` by the central angle `L` when
//! `R ≤ 1`, and `L / R` otherwise (so the arc is `L·R` for tight circles and `L` for wide ones).
//! Nearly parallel tangents give a tangent step instead.

use crate::geometry::Vec3;
use crate::march::tangent_step::tangent_step;
use crate::march::StepPrediction;
use nalgebra::Matrix3;

/// An approximate osculating circle and the sense of travel on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApproxCircle {
    /// The centre `C`.
    pub centre: Vec3,
    /// The radius `|CQ|`.
    pub radius: f64,
    /// Unit axis `CP × CQ / |CP × CQ|`: a positive rotation about it moves from `P` towards `Q`.
    pub axis: Vec3,
}

/// The approximate osculating circle at `current` from `previous`, or `None` when the tangents
/// are parallel within `parallel_tolerance` (`|u·v| > 1 − tol`) or the three planes or the axis
/// are degenerate.
pub fn approximate_circle(
    previous: &Vec3,
    previous_tangent: &Vec3,
    current: &Vec3,
    current_tangent: &Vec3,
    parallel_tolerance: f64,
) -> Option<ApproxCircle> {
    let (u, v) = (previous_tangent, current_tangent);
    if u.dot(v).abs() > 1.0 - parallel_tolerance {
        return None;
    }
    let n = u.cross(v);
    let m = Matrix3::from_rows(&[u.transpose(), v.transpose(), n.transpose()]);
    let rhs = Vec3::new(u.dot(previous), v.dot(current), n.dot(current));
    let centre = m.lu().solve(&rhs)?;
    let (cp, cq) = (previous - centre, current - centre);
    let radius = cq.norm();
    let axis = cp.cross(&cq);
    let an = axis.norm();
    if an.is_nan() || an <= 1e-14 * cp.norm() * radius || !radius.is_finite() {
        return None;
    }
    Some(ApproxCircle {
        centre,
        radius,
        axis: axis / an,
    })
}

/// The central angle of one circular step: `L` if `R ≤ 1`, else `L / R`.
pub fn step_angle(radius: f64, step: f64) -> f64 {
    if radius <= 1.0 {
        step
    } else {
        step / radius
    }
}

/// Rotates `w` by `angle` about the unit `axis` (Rodrigues' formula).
pub fn rotate(w: &Vec3, axis: &Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    w * c + axis.cross(w) * s + axis * (axis.dot(w) * (1.0 - c))
}

/// The circular step: the predicted next point and tangent (falls back to a tangent step of
/// length `step` when no circle exists). `arc` is the predicted arc length.
pub fn circular_step(
    previous: &Vec3,
    previous_tangent: &Vec3,
    current: &Vec3,
    current_tangent: &Vec3,
    step: f64,
    parallel_tolerance: f64,
) -> StepPrediction {
    match approximate_circle(
        previous,
        previous_tangent,
        current,
        current_tangent,
        parallel_tolerance,
    ) {
        None => tangent_step(current, current_tangent, step),
        Some(circle) => {
            let angle = step_angle(circle.radius, step);
            let point = circle.centre + rotate(&(current - circle.centre), &circle.axis, angle);
            StepPrediction {
                point,
                tangent: rotate(current_tangent, &circle.axis, angle),
                arc: angle * circle.radius,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_an_exact_circle() {
        // A circle of radius 0.8 in a tilted plane: the circle through two of its points with
        // their tangents is the circle itself, and the step lands on it at angle L.
        let (e1, e2) = (
            Vec3::new(1.0, 0.0, 1.0).normalize(),
            Vec3::new(0.0, 1.0, 0.0),
        );
        let c0 = Vec3::new(0.3, -0.2, 0.5);
        let r = 0.8;
        let at = |a: f64| c0 + (e1 * a.cos() + e2 * a.sin()) * r;
        let tan = |a: f64| -e1 * a.sin() + e2 * a.cos();
        let circle = approximate_circle(&at(0.1), &tan(0.1), &at(0.2), &tan(0.2), 1e-12).unwrap();
        assert!((circle.centre - c0).norm() < 1e-12);
        assert!((circle.radius - r).abs() < 1e-12);
        let s = circular_step(&at(0.1), &tan(0.1), &at(0.2), &tan(0.2), 0.05, 1e-12);
        assert!((s.point - at(0.25)).norm() < 1e-12);
        assert!((s.tangent - tan(0.25)).norm() < 1e-12);
        assert!((s.arc - 0.05 * r).abs() < 1e-12);
    }

    #[test]
    fn parallel_tangents_give_a_tangent_step() {
        let t = Vec3::new(0.0, 0.0, 1.0);
        let s = circular_step(&Vec3::zeros(), &t, &Vec3::new(0.0, 0.0, 0.1), &t, 0.2, 1e-9);
        assert!((s.point - Vec3::new(0.0, 0.0, 0.3)).norm() < 1e-15);
    }
}
