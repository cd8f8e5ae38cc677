//! Surfaces given by closures, differentiated exactly with second-order jets.
//!
//! [`Jet2`] is a forward-mode jet in two variables: a value with its gradient and Hessian, carried
//! through `+ − × ÷`, `sin`, `cos`, `sqrt`, `powi`, `exp` and `ln` by the chain rule. Evaluating a
//! closure `|u, v| -> [Jet2; 3]` on the seed jets of `u` and `v` gives the point and all first and
//! second partial derivatives to rounding, with no finite differences. [`AnalyticSurface`] wraps such
//! a closure as a [`ParametricSurface`], so tests can use the papers' trigonometric and polynomial
//! surfaces.

use crate::geometry::surface::{Domain, ParametricSurface, SurfaceDerivs, Vec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value with its exact gradient and Hessian with respect to two variables `(x, y)`.
///
/// `hess` stores `[∂²/∂x², ∂²/∂x∂y, ∂²/∂y²]`. Every operation applies the chain rule exactly, so
/// the derivative parts are as accurate as the value part (up to floating-point rounding).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet2 {
    /// The value.
    pub val: f64,
    /// `[∂/∂x, ∂/∂y]`.
    pub grad: [f64; 2],
    /// `[∂²/∂x², ∂²/∂x∂y, ∂²/∂y²]`.
    pub hess: [f64; 3],
}

impl Jet2 {
    /// A constant (all derivatives zero).
    pub const fn constant(c: f64) -> Self {
        Jet2 {
            val: c,
            grad: [0.0, 0.0],
            hess: [0.0, 0.0, 0.0],
        }
    }

    /// The first variable `x` at the value `x` (gradient `(1, 0)`).
    pub const fn var_x(x: f64) -> Self {
        Jet2 {
            val: x,
            grad: [1.0, 0.0],
            hess: [0.0, 0.0, 0.0],
        }
    }

    /// The second variable `y` at the value `y` (gradient `(0, 1)`).
    pub const fn var_y(y: f64) -> Self {
        Jet2 {
            val: y,
            grad: [0.0, 1.0],
            hess: [0.0, 0.0, 0.0],
        }
    }

    /// `φ(self)` given `φ(a)`, `φ'(a)`, `φ''(a)` at `a = self.val` (the chain rule).
    fn compose(self, f0: f64, f1: f64, f2: f64) -> Self {
        let [gx, gy] = self.grad;
        let [hxx, hxy, hyy] = self.hess;
        Jet2 {
            val: f0,
            grad: [f1 * gx, f1 * gy],
            hess: [
                f1 * hxx + f2 * gx * gx,
                f1 * hxy + f2 * gx * gy,
                f1 * hyy + f2 * gy * gy,
            ],
        }
    }

    /// Sine.
    pub fn sin(self) -> Self {
        let (s, c) = self.val.sin_cos();
        self.compose(s, c, -s)
    }

    /// Cosine.
    pub fn cos(self) -> Self {
        let (s, c) = self.val.sin_cos();
        self.compose(c, -s, -c)
    }

    /// Square root (derivatives are infinite at 0).
    pub fn sqrt(self) -> Self {
        let r = self.val.sqrt();
        self.compose(r, 0.5 / r, -0.25 / (r * self.val))
    }

    /// Natural exponential.
    pub fn exp(self) -> Self {
        let e = self.val.exp();
        self.compose(e, e, e)
    }

    /// Natural logarithm.
    pub fn ln(self) -> Self {
        let a = self.val;
        self.compose(a.ln(), 1.0 / a, -1.0 / (a * a))
    }

    /// Integer power `selfⁿ` (negative `n` allowed).
    pub fn powi(self, n: i32) -> Self {
        let a = self.val;
        let nf = f64::from(n);
        let (f0, f1, f2) = match n {
            0 => (1.0, 0.0, 0.0),
            1 => (a, 1.0, 0.0),
            _ => (
                a.powi(n),
                nf * a.powi(n - 1),
                nf * (nf - 1.0) * a.powi(n - 2),
            ),
        };
        self.compose(f0, f1, f2)
    }

    /// The reciprocal `1 / self`.
    pub fn recip(self) -> Self {
        let a = self.val;
        let r = 1.0 / a;
        self.compose(r, -r * r, 2.0 * r * r * r)
    }
}

impl From<f64> for Jet2 {
    fn from(c: f64) -> Self {
        Jet2::constant(c)
    }
}

impl Add for Jet2 {
    type Output = Jet2;
    fn add(self, b: Jet2) -> Jet2 {
        Jet2 {
            val: self.val + b.val,
            grad: [self.grad[0] + b.grad[0], self.grad[1] + b.grad[1]],
            hess: [
                self.hess[0] + b.hess[0],
                self.hess[1] + b.hess[1],
                self.hess[2] + b.hess[2],
            ],
        }
    }
}

impl Neg for Jet2 {
    type Output = Jet2;
    fn neg(self) -> Jet2 {
        Jet2 {
            val: -self.val,
            grad: [-self.grad[0], -self.grad[1]],
            hess: [-self.hess[0], -self.hess[1], -self.hess[2]],
        }
    }
}

impl Sub for Jet2 {
    type Output = Jet2;
    fn sub(self, b: Jet2) -> Jet2 {
        self + (-b)
    }
}

impl Mul for Jet2 {
    type Output = Jet2;
    fn mul(self, b: Jet2) -> Jet2 {
        let (a0, b0) = (self.val, b.val);
        let [ax, ay] = self.grad;
        let [bx, by] = b.grad;
        Jet2 {
            val: a0 * b0,
            grad: [a0 * bx + b0 * ax, a0 * by + b0 * ay],
            hess: [
                a0 * b.hess[0] + b0 * self.hess[0] + 2.0 * ax * bx,
                a0 * b.hess[1] + b0 * self.hess[1] + ax * by + ay * bx,
                a0 * b.hess[2] + b0 * self.hess[2] + 2.0 * ay * by,
            ],
        }
    }
}

impl Div for Jet2 {
    type Output = Jet2;
    // Division is multiplication by the reciprocal; clippy's lint does not apply here.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, b: Jet2) -> Jet2 {
        self * b.recip()
    }
}

macro_rules! scalar_ops {
    ($($tr:ident $m:ident),*) => {$(
        impl $tr<f64> for Jet2 {
            type Output = Jet2;
            fn $m(self, b: f64) -> Jet2 { self.$m(Jet2::constant(b)) }
        }
        impl $tr<Jet2> for f64 {
            type Output = Jet2;
            fn $m(self, b: Jet2) -> Jet2 { Jet2::constant(self).$m(b) }
        }
    )*};
}
scalar_ops!(Add add, Sub sub, Mul mul, Div div);

/// A surface `S(u, v)` given by a closure on jets, with exact first and second derivatives.
///
/// The closure must compute with [`Jet2`] arithmetic only (constants enter through `f64`
/// operands or [`Jet2::constant`]); then [`ParametricSurface::derivs`] is exact up to rounding.
#[derive(Clone)]
pub struct AnalyticSurface<F> {
    domain: Domain,
    f: F,
}

impl<F> AnalyticSurface<F>
where
    F: Fn(Jet2, Jet2) -> [Jet2; 3],
{
    /// The surface `f` on `domain`.
    pub fn new(domain: Domain, f: F) -> Self {
        AnalyticSurface { domain, f }
    }
}

impl<F> std::fmt::Debug for AnalyticSurface<F> {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        out.debug_struct("AnalyticSurface")
            .field("domain", &self.domain)
            .finish_non_exhaustive()
    }
}

impl<F> ParametricSurface for AnalyticSurface<F>
where
    F: Fn(Jet2, Jet2) -> [Jet2; 3],
{
    fn domain(&self) -> Domain {
        self.domain
    }

    fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let xyz = (self.f)(Jet2::var_x(u), Jet2::var_y(v));
        let pick = |g: &dyn Fn(&Jet2) -> f64| Vec3::new(g(&xyz[0]), g(&xyz[1]), g(&xyz[2]));
        SurfaceDerivs {
            p: pick(&|j| j.val),
            su: pick(&|j| j.grad[0]),
            sv: pick(&|j| j.grad[1]),
            suu: pick(&|j| j.hess[0]),
            suv: pick(&|j| j.hess[1]),
            svv: pick(&|j| j.hess[2]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + b.abs())
    }

    #[test]
    fn jet_matches_closed_form_derivatives() {
        // f(x, y) = sin(x·y) + cos(x)/y + sqrt(x² + y²) + (x − y)³ + exp(x) ln(y)
        let (x0, y0) = (0.7, 1.3);
        let (x, y) = (Jet2::var_x(x0), Jet2::var_y(y0));
        let f = (x * y).sin()
            + x.cos() / y
            + (x * x + y * y).sqrt()
            + (x - y).powi(3)
            + x.exp() * y.ln();
        let r = (x0 * x0 + y0 * y0).sqrt();
        let fx = y0 * (x0 * y0).cos() - x0.sin() / y0
            + x0 / r
            + 3.0 * (x0 - y0).powi(2)
            + x0.exp() * y0.ln();
        let fy = x0 * (x0 * y0).cos() - x0.cos() / (y0 * y0) + y0 / r - 3.0 * (x0 - y0).powi(2)
            + x0.exp() / y0;
        let fxx = -y0 * y0 * (x0 * y0).sin() - x0.cos() / y0
            + y0 * y0 / r.powi(3)
            + 6.0 * (x0 - y0)
            + x0.exp() * y0.ln();
        let fxy = (x0 * y0).cos() - x0 * y0 * (x0 * y0).sin() + x0.sin() / (y0 * y0)
            - x0 * y0 / r.powi(3)
            - 6.0 * (x0 - y0)
            + x0.exp() / y0;
        let fyy = -x0 * x0 * (x0 * y0).sin()
            + 2.0 * x0.cos() / y0.powi(3)
            + x0 * x0 / r.powi(3)
            + 6.0 * (x0 - y0)
            - x0.exp() / (y0 * y0);
        assert!(close(f.grad[0], fx), "{} {}", f.grad[0], fx);
        assert!(close(f.grad[1], fy), "{} {}", f.grad[1], fy);
        assert!(close(f.hess[0], fxx), "{} {}", f.hess[0], fxx);
        assert!(close(f.hess[1], fxy), "{} {}", f.hess[1], fxy);
        assert!(close(f.hess[2], fyy), "{} {}", f.hess[2], fyy);
    }

    #[test]
    fn powi_handles_negative_and_small_exponents() {
        let x = Jet2::var_x(2.0);
        let r = x.powi(-2);
        assert!(close(r.val, 0.25) && close(r.grad[0], -0.25) && close(r.hess[0], 0.375));
        assert_eq!(x.powi(0).grad[0], 0.0);
        assert!(close(x.powi(1).grad[0], 1.0));
    }

    #[test]
    fn torus_derivatives_are_exact() {
        let torus = AnalyticSurface::new(Domain::new(-3.2, 3.2, -3.2, 3.2), |u: Jet2, v: Jet2| {
            [
                (3.0 + u.cos()) * v.sin(),
                (3.0 + u.cos()) * v.cos(),
                u.sin(),
            ]
        });
        let (u, v) = (0.4, -1.1);
        let d = torus.derivs(u, v);
        let suv = Vec3::new(-u.sin() * v.cos(), u.sin() * v.sin(), 0.0);
        let svv = Vec3::new(-(3.0 + u.cos()) * v.sin(), -(3.0 + u.cos()) * v.cos(), 0.0);
        let suu = Vec3::new(-u.cos() * v.sin(), -u.cos() * v.cos(), -u.sin());
        assert!((d.suv - suv).norm() < 1e-14);
        assert!((d.svv - svv).norm() < 1e-14);
        assert!((d.suu - suu).norm() < 1e-14);
    }
}
