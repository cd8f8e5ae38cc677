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

impl CurveFrame {
    /// The same frame with the tangent (and parameter tangents) reversed.
    pub fn reversed(mut self) -> Self {
        self.tangent = -self.tangent;
        self.tangent_p = [-self.tangent_p[0], -self.tangent_p[1]];
        self.tangent_q = [-self.tangent_q[0], -self.tangent_q[1]];
        self
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
    }
}
