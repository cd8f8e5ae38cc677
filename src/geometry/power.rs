//! Surfaces given in the power basis, converted exactly (with interval rounding) to rational
//! Bézier form.
//!
//! A [`PowerSurface`] is `(x/w, y/w, z/w)` where each of `x, y, z, w` is a sum of terms
//! `c·uⁱ·vʲ` over the declared domain `[u0,u1] × [v0,v1]`. Conversion is exact up to outward
//! rounding: each monomial `uⁱ` (after the substitution `u = u0 + (u1 − u0)·s`) has the
//! Bernstein coefficients given by its blossom at the domain ends (see `monomial_bernstein`),
//! summed per term in [`Interval`] arithmetic, so the resulting Bézier net encloses the exact
//! Bernstein coefficients. (Expanding `(u0 + h·s)ⁱ` in powers of `s` first would cancel badly.)
//! When the denominator's Bernstein coefficients are not all provably positive in the lowest
//! degree (a circle arc of 180° or more), the same tables are built in a higher degree until
//! they are (degree elevation, see [`PowerSurface::to_bezier`]).

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::{check_domain, RationalBezierPatch};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::{point, Scalar};
use inari::Interval;

/// Largest exponent accepted in a power-basis term (keeps the dense expansion small).
pub const MAX_POWER_DEGREE: u32 = 64;

/// Largest degree (per direction) [`PowerSurface::to_bezier`] elevates to while trying to
/// prove the weights positive.
pub const MAX_ELEVATED_DEGREE: usize = 64;

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

    /// The smallest degree `[m, n]` of the Bézier form: the largest exponent of `u` and of `v`
    /// over all components, at least 1. [`to_bezier`](Self::to_bezier) raises it in a direction
    /// the denominator depends on when the weights need it.
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

    /// The enclosing rational Bézier patch on the same declared domain, degree elevated (up
    /// to [`MAX_ELEVATED_DEGREE`] per direction) until the weights are provably positive.
    ///
    /// A denominator positive on the domain can still have Bernstein coefficients ≤ 0 in the
    /// lowest degree (e.g. `1 + u²` on `[−a, a]`, `a ≥ 1`: a circle arc of 180° or more).
    /// Its Bernstein coefficients in degree `N` tend to its values as `N` grows, so raising
    /// the degree in the directions `w` depends on makes them all positive. The control points
    /// of the raised degree are computed directly (not by repeated elevation), with the same
    /// outward rounding, so the patch encloses exactly the same surface.
    ///
    /// Errors: non-finite coefficients (`x[k][2]`…), exponents above [`MAX_POWER_DEGREE`], a bad
    /// `domain[k]`, a denominator `w` proven not positive somewhere on the domain (`w`,
    /// [`InputProblem::NonPositiveWeight`]), one not proven positive by
    /// [`MAX_ELEVATED_DEGREE`] (`w`, [`InputProblem::WeightNotProvenPositive`]), or a constant
    /// surface.
    pub fn to_bezier(&self) -> Result<RationalBezierPatch> {
        self.to_bezier_up_to(MAX_ELEVATED_DEGREE)
    }

    /// [`to_bezier`](Self::to_bezier) with the elevation limited to degree `max_degree` per
    /// direction (never below the surface's own [`degree`](Self::degree)).
    pub fn to_bezier_up_to(&self, max_degree: usize) -> Result<RationalBezierPatch> {
        for (name, terms) in [("x", &self.x), ("y", &self.y), ("z", &self.z)] {
            Self::check_terms(name, terms)?;
        }
        if let Some(w) = &self.w {
            Self::check_terms("w", w)?;
        }
        check_domain(&self.domain)?;
        let mut degree = self.degree();
        // Directions the denominator depends on: elevating the others cannot help.
        let (mut wu, mut wv) = (false, false);
        for &(i, j, _) in self.w.iter().flatten() {
            wu |= i > 0;
            wv |= j > 0;
        }
        let d = &self.domain;
        loop {
            let c = binomials(degree[0].max(degree[1]));
            let eu = monomial_bernstein(degree[0], d.u[0], d.u[1], &c);
            let ev = monomial_bernstein(degree[1], d.v[0], d.v[1], &c);
            let ws = match &self.w {
                Some(w) => Self::bernstein(w, degree, &eu, &ev),
                None => vec![point(1.0); (degree[0] + 1) * (degree[1] + 1)],
            };
            if ws.iter().all(|w| !w.is_empty() && w.inf() > 0.0) {
                let xs = Self::bernstein(&self.x, degree, &eu, &ev);
                let ys = Self::bernstein(&self.y, degree, &eu, &ev);
                let zs = Self::bernstein(&self.z, degree, &eu, &ev);
                let net = (0..xs.len())
                    .map(|k| [xs[k], ys[k], zs[k], ws[k]])
                    .collect();
                return RationalBezierPatch::from_homogeneous(degree, net, self.domain);
            }
            if self.weight_fails_on_grid(degree) {
                return Err(Error::input("w", InputProblem::NonPositiveWeight));
            }
            let up = |k: usize, dep: bool| dep && k < max_degree;
            let (grow_u, grow_v) = (up(degree[0], wu), up(degree[1], wv));
            if !grow_u && !grow_v {
                return Err(Error::input(
                    "w",
                    InputProblem::WeightNotProvenPositive {
                        max_degree: max_degree.max(degree[0]).max(degree[1]),
                    },
                ));
            }
            degree[0] += grow_u as usize;
            degree[1] += grow_v as usize;
        }
    }

    /// Whether `w` is proven ≤ 0 at some point of the uniform `(m + 1) × (n + 1)` grid over the
    /// domain (interval evaluation at f64 grid points inside the domain).
    fn weight_fails_on_grid(&self, [m, n]: [usize; 2]) -> bool {
        let Some(w) = &self.w else {
            return false;
        };
        let d = &self.domain;
        let at = |lo: f64, hi: f64, k: usize, of: usize| {
            (lo + (hi - lo) * k as f64 / of as f64).clamp(lo, hi)
        };
        (0..=m).any(|k| {
            let u = point(at(d.u[0], d.u[1], k, m));
            (0..=n).any(|l| {
                let v = point(at(d.v[0], d.v[1], l, n));
                let value = w.iter().fold(point(0.0), |acc, &(i, j, c)| {
                    acc + point(c) * u.powi(i as i32) * v.powi(j as i32)
                });
                !value.is_empty() && value.sup() <= 0.0
            })
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cylinder `x² + z² = 1` along y: `(x, z) = (1 − s², 2s)/(1 + s²)`, `y = t`, over
    /// `s ∈ [−a, a]` (an arc of `4·atan a` about the +x direction).
    fn cylinder(a: f64) -> PowerSurface {
        PowerSurface {
            domain: Domain::new(-a, a, -1.0, 1.0),
            x: vec![(0, 0, 1.0), (2, 0, -1.0)],
            y: vec![(0, 1, 1.0), (2, 1, 1.0)],
            z: vec![(1, 0, 2.0)],
            w: Some(vec![(0, 0, 1.0), (2, 0, 1.0)]),
        }
    }

    #[test]
    fn wide_circle_arcs_are_elevated_to_the_least_degree_with_positive_weights() {
        // In degree N the Bernstein coefficients of 1 + s² on [−a, a] are
        // 1 + a²·((N − 2k)² − N)/(N(N − 1)); the least is 1 − a²/(N − 1) (N even) or
        // 1 − a²(N − 1)/(N(N − 1)) = 1 − a²/N (N odd). Closed form of the least N that works:
        let least = |a: f64| {
            (2..200usize)
                .find(|&n| {
                    let min = if n % 2 == 0 {
                        1.0 - a * a / (n - 1) as f64
                    } else {
                        1.0 - a * a / n as f64
                    };
                    min > 1e-9
                })
                .unwrap()
        };
        for a in [0.5, 0.99, 1.3, 1.5, 2.0, 3.0, 5.0] {
            let s = cylinder(a);
            let patch = s.to_bezier().unwrap();
            let [m, n] = patch.degree();
            assert_eq!(m, least(a).max(2), "a = {a}");
            assert_eq!(n, 1, "the weight does not depend on t: no elevation in t");
            assert!(patch.homogeneous().iter().all(|h| h[3].inf() > 0.0));
            // The patch is the power form: compare on a dense grid, and check the circle.
            let mut worst = 0.0f64;
            for i in 0..=60 {
                for j in 0..=10 {
                    let u = -a + 2.0 * a * i as f64 / 60.0;
                    let v = -1.0 + 0.2 * j as f64;
                    let pb = patch.point_f64(u, v);
                    let pp = s.eval(u, v);
                    for c in 0..3 {
                        worst = worst.max((pb[c] - pp[c]).abs());
                    }
                    assert!((pb[0] * pb[0] + pb[2] * pb[2] - 1.0).abs() < 1e-12);
                    // The interval evaluation of the patch encloses the power form's value.
                    let e = patch.eval(point(u), point(v));
                    let q = s.eval(point(u), point(v));
                    for c in 0..3 {
                        assert!(!e[c].disjoint(q[c]), "a = {a}, ({u}, {v}), coordinate {c}");
                    }
                }
            }
            assert!(worst < 1e-12, "a = {a}: off the power form by {worst:e}");
        }
    }

    #[test]
    fn elevation_stops_at_the_limit_and_never_needs_to_rise_without_a_weight() {
        // a = 3: degree 10 is needed (1 − 9/9 = 0 at N = 10 even, so N = 11 odd: 1 − 9/11 > 0).
        let s = cylinder(3.0);
        let err = s.to_bezier_up_to(6).unwrap_err();
        assert!(matches!(
            err,
            Error::InvalidInput {
                problem: InputProblem::WeightNotProvenPositive { max_degree: 6 },
                ..
            }
        ));
        assert_eq!(s.to_bezier_up_to(11).unwrap().degree(), [11, 1]);
        // No weight: the minimal degree, whatever the domain.
        let g = PowerSurface::graph(Domain::new(-5.0, 5.0, -5.0, 5.0), vec![(3, 1, 1.0)]);
        assert_eq!(g.to_bezier().unwrap().degree(), [3, 1]);
    }

    #[test]
    fn weights_with_a_root_in_the_domain_are_rejected() {
        let problem = |w: Vec<PowerTerm>, max: usize| {
            let mut s = cylinder(1.0);
            s.w = Some(w);
            match s.to_bezier_up_to(max) {
                Err(Error::InvalidInput { field, problem, .. }) => {
                    assert_eq!(field, "w");
                    problem
                }
                other => panic!("expected an input error, got {other:?}"),
            }
        };
        // 0.25 − s²: negative at the ends of [−1, 1].
        assert_eq!(
            problem(vec![(0, 0, 0.25), (2, 0, -1.0)], 64),
            InputProblem::NonPositiveWeight
        );
        // (s − 0.3)² − 0.001: positive at the ends, negative on a short interval inside,
        // found by the grid once the degree (and so the grid) is fine enough.
        assert_eq!(
            problem(vec![(2, 0, 1.0), (1, 0, -0.6), (0, 0, 0.09 - 0.001)], 64),
            InputProblem::NonPositiveWeight
        );
        // (s − 1/3)² + 0: touches zero between grid points: not provable either way.
        let third = 1.0 / 3.0;
        assert_eq!(
            problem(
                vec![(2, 0, 1.0), (1, 0, -2.0 * third), (0, 0, third * third)],
                24
            ),
            InputProblem::WeightNotProvenPositive { max_degree: 24 }
        );
    }
}
