//! The intersection tangent `c = N^P × N^Q / |N^P × N^Q|` and its images in both parameter domains.

use crate::geometry::{ParametricSurface, SurfaceDerivs, Vec3};

/// Local first-order data of the intersection curve at a point `(σ, t, u, v)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveFrame {
    /// Model-space point (midpoint of `P(σ,t)` and `Q(u,v)`).
    pub xyz: Vec3,
    /// Unit model-space tangent (zero when the normals are parallel).
    pub tangent: Vec3,
    /// `(σ', t')` with `P_σ σ' + P_t t' = tangent` (least squares; exact on the curve).
    pub tangent_p: [f64; 2],
    /// `(u', v')` with `Q_u u' + Q_v v' = tangent`.
    pub tangent_q: [f64; 2],
    /// `|N^P × N^Q| / (|N^P| |N^Q|)`: the sine of the angle between the normals (0 = tangency).
    pub sine: f64,
}

/// Solves `[su sv] (a, b)ᵀ = w` in the least-squares sense (normal equations, 2×2).
/// Returns zeros when `su`, `sv` are parallel.
pub fn parameter_direction(d: &SurfaceDerivs, w: &Vec3) -> [f64; 2] {
    let (e, f, g) = (d.su.dot(&d.su), d.su.dot(&d.sv), d.sv.dot(&d.sv));
    let det = e * g - f * f;
    if det.abs() <= f64::EPSILON * e * g || det == 0.0 {
        return [0.0, 0.0];
    }
    let (r1, r2) = (d.su.dot(w), d.sv.dot(w));
    [(g * r1 - f * r2) / det, (e * r2 - f * r1) / det]
}

/// The frame at `x = (σ, t, u, v)`.
///
/// The tangent's sign is that of `N^P × N^Q`; callers orient it along their direction of travel.
pub fn curve_frame<S1, S2>(p: &S1, q: &S2, x: [f64; 4]) -> CurveFrame
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let dp = p.derivs(x[0], x[1]);
    let dq = q.derivs(x[2], x[3]);
    frame_from_derivs(&dp, &dq)
}

/// [`curve_frame`] from already evaluated derivatives.
pub fn frame_from_derivs(dp: &SurfaceDerivs, dq: &SurfaceDerivs) -> CurveFrame {
    let (np, nq) = (dp.normal(), dq.normal());
    let c = np.cross(&nq);
    let scale = np.norm() * nq.norm();
    let cn = c.norm();
    let sine = if scale > 0.0 { cn / scale } else { 0.0 };
    let tangent = if cn > 0.0 { c / cn } else { Vec3::zeros() };
    CurveFrame {
        xyz: (dp.p + dq.p) * 0.5,
        tangent,
        tangent_p: parameter_direction(dp, &tangent),
        tangent_q: parameter_direction(dq, &tangent),
        sine,
    }
}

/// Curvature `κ ≥ 0` of the intersection curve at a point, from second derivatives.
///
/// The curvature vector `k ⟂ t` has normal components `k·n̂ᴾ = IIᴾ(t, t)` and `k·n̂^Q = II^Q(t, t)`
/// (the normal curvatures of both surfaces along the unit tangent `t`), so with `c = n̂ᴾ·n̂^Q`,
/// `κ² = (κᴾ² + κ^Q² − 2c κᴾκ^Q) / (1 − c²)`. An estimate in f64 (not a bound); infinite where
/// the normals are parallel or a surface is degenerate.
pub fn curvature(dp: &SurfaceDerivs, dq: &SurfaceDerivs, frame: &CurveFrame) -> f64 {
    let (np, nq) = (dp.normal(), dq.normal());
    let (lp, lq) = (np.norm(), nq.norm());
    if lp == 0.0 || lq == 0.0 || frame.tangent == Vec3::zeros() {
        return f64::INFINITY;
    }
    let (np, nq) = (np / lp, nq / lq);
    let normal_curvature = |d: &SurfaceDerivs, n: &Vec3, [a, b]: [f64; 2]| {
        n.dot(&(d.suu * (a * a) + d.suv * (2.0 * a * b) + d.svv * (b * b)))
    };
    let kp = normal_curvature(dp, &np, frame.tangent_p);
    let kq = normal_curvature(dq, &nq, frame.tangent_q);
    let c = np.dot(&nq);
    let sin2 = np.cross(&nq).norm_squared();
    let k2 = (kp * kp + kq * kq - 2.0 * c * kp * kq).max(0.0) / sin2;
    if k2.is_finite() {
        k2.sqrt()
    } else {
        f64::INFINITY
    }
}

impl CurveFrame {
    /// The same frame with the tangent (and parameter tangents) reversed.
    pub fn reversed(mut self) -> Self {
        self.tangent = -self.tangent;
        self.tangent_p = [-self.tangent_p[0], -self.tangent_p[1]];
        self.tangent_q = [-self.tangent_q[0], -self.tangent_q[1]];
        self
    }
}

/// `sin²` of the angle between the normals of `p` at `(σ, t)` and of `q` at `(u, v)`, for
/// `y = (σ, t, u, v)`: 1 for perpendicular surfaces, 0 at tangency or where a normal vanishes.
/// A floating-point estimate, for choices and reports only (no bound is claimed from it).
pub fn normals_sine_sqr<S1, S2>(p: &S1, q: &S2, y: &[f64; 4]) -> f64
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (np, nq) = (p.derivs(y[0], y[1]).normal(), q.derivs(y[2], y[3]).normal());
    let s = np.cross(&nq).norm_squared() / (np.norm_squared() * nq.norm_squared());
    if s.is_finite() {
        s
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::analytic::{AnalyticSurface, Jet2};
    use crate::geometry::Domain;

    #[test]
    fn cylinder_and_plane_tangent_is_the_circle_tangent() {
        let d = Domain::new(-4.0, 4.0, -4.0, 4.0);
        let cyl = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u.cos(), u.sin(), v]);
        let plane = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(0.0)]);
        let a: f64 = 0.7;
        let f = curve_frame(&cyl, &plane, [a, 0.0, a.cos(), a.sin()]);
        let exact = Vec3::new(-a.sin(), a.cos(), 0.0);
        assert!((f.tangent.dot(&exact).abs() - 1.0).abs() < 1e-14);
        assert!((f.sine - 1.0).abs() < 1e-14);
        // σ' = ±1, t' = 0 on the cylinder; (u', v') = ±(−sin a, cos a) on the plane.
        let s = f.tangent.dot(&exact).signum();
        assert!((f.tangent_p[0] - s).abs() < 1e-14 && f.tangent_p[1].abs() < 1e-14);
        assert!((f.tangent_q[0] + s * a.sin()).abs() < 1e-14);
        // The unit circle: curvature 1.
        let (dp, dq) = (cyl.derivs(a, 0.0), plane.derivs(a.cos(), a.sin()));
        assert!((curvature(&dp, &dq, &f) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn sphere_and_plane_curvature_is_one_over_the_circle_radius() {
        // Sphere of radius 2 (longitude u, latitude v) against z = 1.9: a circle of radius
        // √(4 − 1.9²), met at the latitude v = asin(0.95), where the normals are far from parallel.
        let d = Domain::new(-4.0, 4.0, -4.0, 4.0);
        let sphere = AnalyticSurface::new(d, |u: Jet2, v: Jet2| {
            [
                u.cos() * v.cos() * 2.0,
                u.sin() * v.cos() * 2.0,
                v.sin() * 2.0,
            ]
        });
        let plane = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(1.9)]);
        let (u, v) = (0.4f64, 0.95f64.asin());
        let r = 2.0 * v.cos();
        let x = [u, v, r * u.cos(), r * u.sin()];
        let f = curve_frame(&sphere, &plane, x);
        let (dp, dq) = (sphere.derivs(x[0], x[1]), plane.derivs(x[2], x[3]));
        let k = curvature(&dp, &dq, &f);
        assert!((k * r - 1.0).abs() < 1e-12, "κ = {k}, 1/r = {}", 1.0 / r);
    }
}
