//! Bulut's DQOC step: the circular step as one unit dual quaternion.
//!
//! The advance on the approximate osculating circle is a rotation by the central angle about the
//! circle's axis line (through the centre `C`, along the unit axis `n`, in any direction of 3D
//! space). As a unit dual quaternion that is `T(C) · R(n, θ) · T(−C)`; applying it to the current
//! point gives the predicted point.

use crate::geometry::Vec3;
use crate::march::circle_step::{approximate_circle, step_angle};
use crate::march::tangent_step::tangent_step;
use crate::march::StepPrediction;

/// A quaternion `w + v` (scalar `w`, vector part `v`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quat {
    /// Scalar part.
    pub w: f64,
    /// Vector part.
    pub v: Vec3,
}

impl Quat {
    /// The Hamilton product `self · b`.
    pub fn mul(&self, b: &Quat) -> Quat {
        Quat {
            w: self.w * b.w - self.v.dot(&b.v),
            v: b.v * self.w + self.v * b.w + self.v.cross(&b.v),
        }
    }
    /// The conjugate `w − v`.
    pub fn conj(&self) -> Quat {
        Quat {
            w: self.w,
            v: -self.v,
        }
    }
    fn add(&self, b: &Quat) -> Quat {
        Quat {
            w: self.w + b.w,
            v: self.v + b.v,
        }
    }
}

/// A dual quaternion `real + ε dual` with `ε² = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DualQuat {
    /// Real part (the rotation for a unit dual quaternion).
    pub real: Quat,
    /// Dual part (`t · real / 2` for a translation `t` after the rotation).
    pub dual: Quat,
}

impl DualQuat {
    /// The rotation by `angle` about the unit vector `axis` through the origin.
    pub fn rotation(axis: &Vec3, angle: f64) -> Self {
        let (s, c) = (0.5 * angle).sin_cos();
        DualQuat {
            real: Quat { w: c, v: axis * s },
            dual: Quat {
                w: 0.0,
                v: Vec3::zeros(),
            },
        }
    }

    /// The translation by `t`.
    pub fn translation(t: &Vec3) -> Self {
        DualQuat {
            real: Quat {
                w: 1.0,
                v: Vec3::zeros(),
            },
            dual: Quat { w: 0.0, v: t * 0.5 },
        }
    }

    /// The product `self · b` (apply `b` first, then `self`).
    pub fn mul(&self, b: &DualQuat) -> DualQuat {
        DualQuat {
            real: self.real.mul(&b.real),
            dual: self.real.mul(&b.dual).add(&self.dual.mul(&b.real)),
        }
    }

    /// The rotation by `angle` about the line through `point` along the unit vector `axis`:
    /// `T(point) · R(axis, angle) · T(−point)`.
    pub fn rotation_about_line(point: &Vec3, axis: &Vec3, angle: f64) -> Self {
        DualQuat::translation(point)
            .mul(&DualQuat::rotation(axis, angle))
            .mul(&DualQuat::translation(&-point))
    }

    /// The image of the point `x`: the vector part of the dual part of `Q (1 + εx) Q̄`, with
    /// `Q̄ = real* − ε dual*` (both conjugations). Exact for unit dual quaternions.
    pub fn transform_point(&self, x: &Vec3) -> Vec3 {
        let xq = DualQuat {
            real: Quat {
                w: 1.0,
                v: Vec3::zeros(),
            },
            dual: Quat { w: 0.0, v: *x },
        };
        let conj = DualQuat {
            real: self.real.conj(),
            dual: Quat {
                w: -self.dual.w,
                v: self.dual.v,
            },
        };
        self.mul(&xq).mul(&conj).dual.v
    }

    /// The image of the free vector `w` (rotation only).
    pub fn transform_vector(&self, w: &Vec3) -> Vec3 {
        let wq = Quat { w: 0.0, v: *w };
        self.real.mul(&wq).mul(&self.real.conj()).v
    }
}

/// The DQOC step: the same prediction as
/// [`circular_step`](crate::march::circle_step::circular_step), computed by one unit dual quaternion.
pub fn dqoc_step(
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
            let motion = DualQuat::rotation_about_line(&circle.centre, &circle.axis, angle);
            StepPrediction {
                point: motion.transform_point(current),
                tangent: motion.transform_vector(current_tangent),
                arc: angle * circle.radius,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::march::circle_step::rotate;

    #[test]
    fn dual_quaternion_rotation_about_a_line_matches_rodrigues() {
        let c = Vec3::new(1.0, -2.0, 0.5);
        let n = Vec3::new(0.3, 0.4, -0.5).normalize();
        let x = Vec3::new(-0.7, 0.2, 2.0);
        for &a in &[0.0, 0.1, 1.0, -2.5, 3.0] {
            let dq = DualQuat::rotation_about_line(&c, &n, a);
            let exact = c + rotate(&(x - c), &n, a);
            assert!((dq.transform_point(&x) - exact).norm() < 1e-14, "angle {a}");
        }
        // A pure translation moves points and leaves vectors alone.
        let t = DualQuat::translation(&Vec3::new(1.0, 2.0, 3.0));
        assert!((t.transform_point(&x) - (x + Vec3::new(1.0, 2.0, 3.0))).norm() < 1e-15);
        assert!((t.transform_vector(&x) - x).norm() < 1e-15);
    }
}
