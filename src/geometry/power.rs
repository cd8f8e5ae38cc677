//! Surfaces given in the power basis, converted exactly (with interval rounding) to rational
//! Bézier form.
//!
//! A [`PowerSurface`] is `(x/w, y/w, z/w)` where each of `x, y, z, w` is a sum of terms
//! `c·uⁱ·vʲ` over the declared domain `[u0,u1] × [v0,v1]`. Conversion substitutes
//! `u = u0 + (u1 − u0)·s`, `v = v0 + (v1 − v0)·r`, expands in intervals and changes basis with
//! `sᵏ = Σ_{i≥k} C(i,k)/C(m,k) · Bᵢᵐ(s)`, all in [`Interval`] arithmetic, so the resulting
//! Bézier net encloses the exact Bernstein coefficients.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::{check_domain, RationalBezierPatch};
use crate::geometry::surface::Domain;
use crate::scalar::{point, Scalar};
use inari::Interval;

/// Largest exponent accepted in a power-basis term (keeps the dense expansion small).
pub const MAX_POWER_DEGREE: u32 = 64;

/// One power-basis term `(i, j, c)`: `c·uⁱ·vʲ`.
pub type PowerTerm = (u32, u32, f64);

/// A rational surface `(x/w, y/w, z/w)` with polynomial components in the power basis.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerSurface {
    /// The declared parameter domain.
    pub domain: Domain,
    /// Terms of the x numerator.
    pub x: Vec<PowerTerm>,
    /// Terms of the y numerator.
    pub y: Vec<PowerTerm>,
    /// Terms of the z numerator.
    pub z: Vec<PowerTerm>,
    /// Terms of the common denominator (`None`: w = 1).
    pub w: Option<Vec<PowerTerm>>,
}

/// Binomial coefficients `C(i, k)` for `i, k ≤ n`, as rigorous intervals (Pascal's rule).
fn binomials(n: usize) -> Vec<Vec<Interval>> {
    let mut c = vec![vec![point(0.0); n + 1]; n + 1];
    for i in 0..=n {
        c[i][0] = point(1.0);
        for k in 1..=i {
            c[i][k] = c[i - 1][k - 1] + c[i - 1][k];
        }
    }
    c
}

/// Change the power-basis polynomial `Σ a_i xⁱ` (x the declared parameter) first to the
/// normalised variable `t`, `x = x0 + h·t`, then to the Bernstein basis of degree `deg`.
fn power_to_bernstein_1d(a: &[Interval], x0: Interval, h: Interval, c: &[Vec<Interval>]) -> Vec<Interval> {
    let deg = a.len() - 1;
    // b_k = Σ_{i≥k} a_i C(i,k) x0^{i−k} h^k.
    let b: Vec<Interval> = (0..=deg)
        .map(|k| {
            let hk = h.powi(k as i32);
            (k..=deg).fold(point(0.0), |acc, i| {
                acc + a[i] * c[i][k] * x0.powi((i - k) as i32) * hk
            })
        })
        .collect();
    // Bernstein coefficient e_i = Σ_{k≤i} C(i,k)/C(deg,k) b_k.
    (0..=deg)
        .map(|i| (0..=i).fold(point(0.0), |acc, k| acc + c[i][k] / c[deg][k] * b[k]))
        .collect()
}

impl PowerSurface {
    /// The degree `[m, n]` the Bézier form will have: the largest exponent of `u` and of `v`
    /// over all components, at least 1.
    pub fn degree(&self) -> [usize; 2] {
        let all = self.x.iter().chain(&self.y).chain(&self.z).chain(self.w.iter().flatten());
        let (mut m, mut n) = (1, 1);
        for &(i, j, _) in all {
            m = m.max(i as usize);
            n = n.max(j as usize);
        }
        [m, n]
    }

    /// Check one component's terms: finite coefficients, exponents at most
    /// [`MAX_POWER_DEGREE`]. Fields are named `name[k]` (term k).
    fn check_terms(name: &str, terms: &[PowerTerm]) -> Result<()> {
        for (k, &(i, j, c)) in terms.iter().enumerate() {
            if !c.is_finite() {
                return Err(Error::input(format!("{name}[{k}][2]"), InputProblem::NonFinite));
            }
            for (e, idx) in [(i, 0), (j, 1)] {
                if e > MAX_POWER_DEGREE {
                    return Err(Error::input(
                        format!("{name}[{k}][{idx}]"),
                        InputProblem::WrongShape(format!(
                            "exponent {e} above the maximum {MAX_POWER_DEGREE}"
                        )),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Bernstein coefficients (degree `[m, n]`, index `i*(n+1)+j`) of one component.
    fn bernstein(&self, terms: &[PowerTerm], [m, n]: [usize; 2], c: &[Vec<Interval>]) -> Vec<Interval> {
        let d = &self.domain;
        let (u0, hu) = (point(d.u[0]), point(d.u[1]) - point(d.u[0]));
        let (v0, hv) = (point(d.v[0]), point(d.v[1]) - point(d.v[0]));
        let mut a = vec![vec![point(0.0); n + 1]; m + 1];
        for &(i, j, coef) in terms {
            a[i as usize][j as usize] = a[i as usize][j as usize] + point(coef);
        }
        // Convert each u-column (fixed power of v), then each row.
        let mut cols = vec![vec![point(0.0); n + 1]; m + 1];
        for j in 0..=n {
            let col: Vec<Interval> = (0..=m).map(|i| a[i][j]).collect();
            for (i, e) in power_to_bernstein_1d(&col, u0, hu, c).into_iter().enumerate() {
                cols[i][j] = e;
            }
        }
        let mut out = Vec::with_capacity((m + 1) * (n + 1));
        for row in &cols {
            out.extend(power_to_bernstein_1d(row, v0, hv, c));
        }
        out
    }

    /// The enclosing rational Bézier patch on the same declared domain.
    ///
    /// Errors: non-finite coefficients (`x[k][2]`…), exponents above [`MAX_POWER_DEGREE`], a bad
    /// `domain[k]`, a denominator `w` not provably positive on the domain (some Bernstein
    /// coefficient not > 0: `w`, [`InputProblem::NonPositiveWeight`]), or a constant surface.
    pub fn to_bezier(&self) -> Result<RationalBezierPatch> {
        for (name, terms) in [("x", &self.x), ("y", &self.y), ("z", &self.z)] {
            Self::check_terms(name, terms)?;
        }
        if let Some(w) = &self.w {
            Self::check_terms("w", w)?;
        }
        check_domain(&self.domain)?;
        let degree = self.degree();
        let c = binomials(degree[0].max(degree[1]));
        let xs = self.bernstein(&self.x, degree, &c);
        let ys = self.bernstein(&self.y, degree, &c);
        let zs = self.bernstein(&self.z, degree, &c);
        let ws = match &self.w {
            Some(w) => self.bernstein(w, degree, &c),
            None => vec![point(1.0); xs.len()],
        };
        if ws.iter().any(|w| !(w.inf() > 0.0)) {
            return Err(Error::input("w", InputProblem::NonPositiveWeight));
        }
        let net = (0..xs.len()).map(|k| [xs[k], ys[k], zs[k], ws[k]]).collect();
        RationalBezierPatch::from_homogeneous(degree, net, self.domain)
    }

    /// Evaluate the surface at `(u, v)` directly from its power form, in any [`Scalar`]
    /// (intervals: a rigorous enclosure, independent of the Bézier conversion).
    pub fn eval<S: Scalar>(&self, u: S, v: S) -> [S; 3] {
        let poly = |terms: &[PowerTerm]| {
            terms.iter().fold(S::zero(), |acc, &(i, j, c)| {
                acc + S::from_f64(c) * u.powi(i as i32) * v.powi(j as i32)
            })
        };
        let w = match &self.w {
            Some(w) => poly(w),
            None => S::one(),
        };
        [poly(&self.x) / w, poly(&self.y) / w, poly(&self.z) / w]
    }
}
