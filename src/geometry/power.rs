//! Surfaces given in the power basis, converted exactly (with interval rounding) to rational
//! Bézier form.
//!
//! A [`PowerSurface`] is `(x/w, y/w, z/w)` where each of `x, y, z, w` is a sum of terms
//! `c·uⁱ·vʲ` over the declared domain `[u0,u1] × [v0,v1]`. Conversion is exact up to outward
//! rounding: each monomial `uⁱ` (after the substitution `u = u0 + (u1 − u0)·s`) has the
//! Bernstein coefficients given by its blossom at the domain ends (see `monomial_bernstein`),
//! summed per term in [`Interval`] arithmetic, so the resulting Bézier net encloses the exact
//! Bernstein coefficients. (Expanding `(u0 + h·s)ⁱ` in powers of `s` first would cancel badly.)

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

/// Bernstein coefficients of the monomials `xⁱ` (`i ≤ deg`) on `[lo, hi]` in degree `deg`:
/// `table[i][k]`, as rigorous intervals.
///
/// They are values of the blossom of `xⁱ` written in degree `deg`, the symmetric mean of the
/// products of `i` of its `deg` arguments, at `deg − k` copies of `lo` and `k` copies of `hi`:
/// `Σ_j C(k, j)·C(deg − k, i − j)·hiʲ·loⁱ⁻ʲ / C(deg, i)`. Every term has the sign of
/// `hiʲ·loⁱ⁻ʲ`, so nothing cancels (unlike expanding `(lo + (hi − lo)·t)ⁱ` in powers of `t`).
fn monomial_bernstein(deg: usize, lo: f64, hi: f64, c: &[Vec<Interval>]) -> Vec<Vec<Interval>> {
    let (lo, hi) = (point(lo), point(hi));
    (0..=deg)
        .map(|i| {
            (0..=deg)
                .map(|k| {
                    let sum =
                        (0..=i.min(k))
                            .filter(|&j| i - j <= deg - k)
                            .fold(point(0.0), |acc, j| {
                                acc + c[k][j]
                                    * c[deg - k][i - j]
                                    * hi.powi(j as i32)
                                    * lo.powi((i - j) as i32)
                            });
                    sum / c[deg][i]
                })
                .collect()
        })
        .collect()
}

impl PowerSurface {
    /// The height field `(u, v, z(u, v))` over `domain`, `z` a sum of terms `c·uⁱ·vʲ`.
    ///
    /// ```
    /// use ssitrace::geometry::{Domain, PowerSurface};
    /// let bowl = PowerSurface::graph(Domain::new(-1.0, 1.0, -1.0, 1.0), vec![(2, 0, 1.0), (0, 2, 1.0)]);
    /// let patch = bowl.to_bezier()?;
    /// assert_eq!(patch.degree(), [2, 2]);
    /// # Ok::<(), ssitrace::Error>(())
    /// ```
    pub fn graph(domain: Domain, z: Vec<PowerTerm>) -> Self {
        PowerSurface {
            domain,
            x: vec![(1, 0, 1.0)],
            y: vec![(0, 1, 1.0)],
            z,
            w: None,
        }
    }

    /// The degree `[m, n]` the Bézier form will have: the largest exponent of `u` and of `v`
    /// over all components, at least 1.
    pub fn degree(&self) -> [usize; 2] {
        let all = self
            .x
            .iter()
            .chain(&self.y)
            .chain(&self.z)
            .chain(self.w.iter().flatten());
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
                return Err(Error::input(
                    format!("{name}[{k}][2]"),
                    InputProblem::NonFinite,
                ));
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

    /// Bernstein coefficients (degree `[m, n]`, index `i*(n+1)+j`) of one component, from the
    /// monomial tables `eu` (in u) and `ev` (in v).
    fn bernstein(
        terms: &[PowerTerm],
        [m, n]: [usize; 2],
        eu: &[Vec<Interval>],
        ev: &[Vec<Interval>],
    ) -> Vec<Interval> {
        let mut out = vec![point(0.0); (m + 1) * (n + 1)];
        for &(i, j, coef) in terms {
            let (ru, rv) = (&eu[i as usize], &ev[j as usize]);
            let coef = point(coef);
            for k in 0..=m {
                let ck = coef * ru[k];
                for l in 0..=n {
                    out[k * (n + 1) + l] += ck * rv[l];
                }
            }
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
        let d = &self.domain;
        let eu = monomial_bernstein(degree[0], d.u[0], d.u[1], &c);
        let ev = monomial_bernstein(degree[1], d.v[0], d.v[1], &c);
        let xs = Self::bernstein(&self.x, degree, &eu, &ev);
        let ys = Self::bernstein(&self.y, degree, &eu, &ev);
        let zs = Self::bernstein(&self.z, degree, &eu, &ev);
        let ws = match &self.w {
            Some(w) => Self::bernstein(w, degree, &eu, &ev),
            None => vec![point(1.0); xs.len()],
        };
        if ws.iter().any(|w| w.is_empty() || w.inf() <= 0.0) {
            return Err(Error::input("w", InputProblem::NonPositiveWeight));
        }
        let net = (0..xs.len())
            .map(|k| [xs[k], ys[k], zs[k], ws[k]])
            .collect();
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
