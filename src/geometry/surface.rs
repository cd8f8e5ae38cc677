//! The floating-point surface trait the marcher works on.

use nalgebra::Vector3;

/// A 3-vector of `f64`.
pub type Vec3 = Vector3<f64>;

/// A rectangular parameter domain `[u0, u1] × [v0, v1]` with `u0 < u1`, `v0 < v1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// `[u0, u1]`.
    pub u: [f64; 2],
    /// `[v0, v1]`.
    pub v: [f64; 2],
}

impl Domain {
    /// The unit square `[0,1]²`.
    pub const UNIT: Domain = Domain {
        u: [0.0, 1.0],
        v: [0.0, 1.0],
    };

    /// The domain `[u0,u1] × [v0,v1]` (not checked; see the scene parser for validation).
    pub const fn new(u0: f64, u1: f64, v0: f64, v1: f64) -> Self {
        Domain {
            u: [u0, u1],
            v: [v0, v1],
        }
    }

    /// Whether `(u, v)` lies in the closed domain, allowing `tol` outside.
    pub fn contains(&self, u: f64, v: f64, tol: f64) -> bool {
        u >= self.u[0] - tol && u <= self.u[1] + tol && v >= self.v[0] - tol && v <= self.v[1] + tol
    }

    /// Width of the larger side.
    pub fn size(&self) -> f64 {
        (self.u[1] - self.u[0]).max(self.v[1] - self.v[0])
    }
}

/// A surface point with its first and second partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceDerivs {
    /// The point S(u, v).
    pub p: Vec3,
    /// ∂S/∂u.
    pub su: Vec3,
    /// ∂S/∂v.
    pub sv: Vec3,
    /// ∂²S/∂u².
    pub suu: Vec3,
    /// ∂²S/∂u∂v.
    pub suv: Vec3,
    /// ∂²S/∂v².
    pub svv: Vec3,
}

impl SurfaceDerivs {
    /// The (unnormalised) normal `S_u × S_v`.
    pub fn normal(&self) -> Vec3 {
        self.su.cross(&self.sv)
    }
}

/// A parametric surface evaluated in `f64`, with derivatives up to second order.
///
/// The marcher runs on anything implementing this: rational Bézier patches (through their
/// midpoint control net) and analytic surfaces in tests.
pub trait ParametricSurface {
    /// The parameter domain.
    fn domain(&self) -> Domain;
    /// Point and partial derivatives at `(u, v)`; `(u, v)` may lie slightly outside the domain.
    fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs;
    /// The point S(u, v).
    fn point(&self, u: f64, v: f64) -> Vec3 {
        self.derivs(u, v).p
    }
    /// The points whole sides of the domain map to (poles, where `S_u × S_v` vanishes along
    /// the side), each once; none by default.
    fn poles(&self) -> Vec<Vec3> {
        Vec::new()
    }
}

impl<T: ParametricSurface + ?Sized> ParametricSurface for &T {
    fn domain(&self) -> Domain {
        (**self).domain()
    }
    fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        (**self).derivs(u, v)
    }
    fn point(&self, u: f64, v: f64) -> Vec3 {
        (**self).point(u, v)
    }
    fn poles(&self) -> Vec<Vec3> {
        (**self).poles()
    }
}

/// The range of parameter `i` of a surface pair's `(σ, t, u, v)`: `dp` is P's domain, `dq` Q's.
pub fn pair_bounds(dp: &Domain, dq: &Domain, i: usize) -> [f64; 2] {
    match i {
        0 => dp.u,
        1 => dp.v,
        2 => dq.u,
        _ => dq.v,
    }
}

/// The widths of the four parameter ranges of a surface pair's `(σ, t, u, v)`.
pub fn pair_widths(dp: &Domain, dq: &Domain) -> [f64; 4] {
    std::array::from_fn(|i| {
        let b = pair_bounds(dp, dq, i);
        b[1] - b[0]
    })
}
