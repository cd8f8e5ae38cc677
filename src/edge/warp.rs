//! The parameter map of one fine span: which point of the link's reported curve the coarse
//! curves are compared with at each edge parameter.
//!
//! A link's reported polynomial `y(u)` (`u ∈ [0, 1]` over the link's piece) moves its along
//! coordinate at a constant rate, and the along coordinate changes from link to link, so the
//! edge parameter `s` cannot be affine in `u` on every link and smooth at once. Each fine span
//! has a warp `w`: the span's own `r ∈ [0, 1]` (affine in `s`) is compared at `u = w(r)`. The warp
//! is a polynomial of degree [`WARP_DEGREE`] in Bernstein form with `f64` coefficients, the
//! first exactly 0, the last exactly 1 and all in `[0, 1]`; as a real polynomial it is then exact,
//! `w(0) = 0`, `w(1) = 1` and `w([0, 1]) ⊂ [0, 1]` (convex hull). So it maps the span onto the
//! link's piece (every `u` is `w(r)` for some `r`, by continuity) and never outside it: the
//! bounds compared at `(r, w(r))` hold both ways. It is chosen (in `f64`, guidance only) to make
//! `r` proportional to the arc length of `P(y(u))`, so that the edge parameter is a nominal arc
//! length, smooth across the links.

use super::poly::{eval_mid, taylor_shift, Poly, PolyN};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use crate::validated::SeriesN;
use inari::Interval;
use nalgebra::{DMatrix, DVector};

/// The degree of a warp.
pub(crate) const WARP_DEGREE: usize = 5;

/// A warp's power-basis coefficients, enclosed.
pub(crate) type WarpPoly = PolyN<{ WARP_DEGREE + 1 }, 1>;

/// The map `r ↦ u` of one fine span: Bernstein coefficients on `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Warp {
    bern: [f64; WARP_DEGREE + 1],
}

/// Gauss–Legendre nodes on `[-1, 1]` (positive half) and weights, 8 points.
const GL_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GL_W: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_26,
];

impl Warp {
    /// `r ↦ r` (up to the rounding of the coefficients `i / n`, which is harmless: the warp is
    /// whatever exact polynomial its coefficients define).
    pub(crate) fn identity() -> Self {
        Warp {
            bern: std::array::from_fn(|i| i as f64 / WARP_DEGREE as f64),
        }
    }

    /// The warp with Bernstein coefficients `b` (the ends set to exactly 0 and 1), or `None`
    /// when one is not finite or outside `[0, 1]`.
    fn from_bernstein(mut b: [f64; WARP_DEGREE + 1]) -> Option<Self> {
        b[0] = 0.0;
        b[WARP_DEGREE] = 1.0;
        b.iter()
            .all(|v| (0.0..=1.0).contains(v))
            .then_some(Warp { bern: b })
    }

    /// `w(r)` in `f64` (de Casteljau; guidance only).
    pub(crate) fn at(&self, r: f64) -> f64 {
        let mut b = self.bern;
        for k in 1..=WARP_DEGREE {
            for i in 0..=WARP_DEGREE - k {
                b[i] = (1.0 - r) * b[i] + r * b[i + 1];
            }
        }
        b[0]
    }

    /// The power-basis coefficients, enclosed.
    pub(crate) fn power(&self) -> WarpPoly {
        let b: WarpPoly = std::array::from_fn(|i| [point(self.bern[i])]);
        super::poly::power_from_bezier(&b)
    }
}

/// The model-space speed `|d/du P(y(u))|` (`f64`).
fn speed(p: &RationalBezierPatch, y: &Poly<4>, u: f64) -> f64 {
    let x = eval_mid(y, u);
    let d: [f64; 4] = std::array::from_fn(|k| {
        y.iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(0.0, |acc, (m, row)| acc * u + m as f64 * row[k].mid())
    });
    let [_, ds, dt] = p.first_derivs(x[0], x[1]);
    let v: [f64; 3] = std::array::from_fn(|c| ds[c] * d[0] + dt[c] * d[1]);
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The arc length of `P(y(u))` over `[a, b]` (8-point Gauss–Legendre, `f64`).
fn arc(p: &RationalBezierPatch, y: &Poly<4>, a: f64, b: f64) -> f64 {
    let (m, h) = (0.5 * (a + b), 0.5 * (b - a));
    let mut s = 0.0;
    for (x, w) in GL_X.iter().zip(GL_W) {
        s += w * (speed(p, y, m - h * x) + speed(p, y, m + h * x));
    }
    s * h
}

/// The warp of the span with reported curve `y` that makes `r` proportional to the arc length
/// of `P(y(u))`, and that arc length. Interpolates the inverse arc length at the Chebyshev–
/// Lobatto points; the identity (and the chord-free arc length) where that fails.
pub(crate) fn arc_length_warp(p: &RationalBezierPatch, y: &Poly<4>) -> (Warp, f64) {
    let n = WARP_DEGREE;
    let u: Vec<f64> = (0..=n)
        .map(|k| match k {
            0 => 0.0,
            k if k == n => 1.0,
            k => 0.5 * (1.0 - (std::f64::consts::PI * k as f64 / n as f64).cos()),
        })
        .collect();
    let mut a = vec![0.0f64; n + 1];
    for k in 1..=n {
        a[k] = a[k - 1] + arc(p, y, u[k - 1], u[k]);
    }
    let len = a[n];
    if !(len > 0.0 && len.is_finite()) {
        return (Warp::identity(), len.max(0.0));
    }
    // Interior coefficients b_1..b_{n-1}: Σ b_i B_i(r_k) = u_k − B_n(r_k) at the interior r_k.
    let bern = |i: usize, r: f64| {
        super::poly::binom(n, i) * r.powi(i as i32) * (1.0 - r).powi((n - i) as i32)
    };
    let m = n - 1;
    let mut mat = DMatrix::<f64>::zeros(m, m);
    let mut rhs = DVector::<f64>::zeros(m);
    for k in 1..n {
        let r = a[k] / len;
        for i in 1..n {
            mat[(k - 1, i - 1)] = bern(i, r);
        }
        rhs[k - 1] = u[k] - bern(n, r);
    }
    let Some(sol) = mat.lu().solve(&rhs) else {
        return (Warp::identity(), len);
    };
    let mut b = [0.0; WARP_DEGREE + 1];
    for i in 1..n {
        b[i] = sol[i - 1];
    }
    b[n] = 1.0;
    let w = Warp::from_bernstein(b).unwrap_or_else(Warp::identity);
    (w, len)
}

/// The Taylor coefficients (`len` of them) of `y(w(r))` at every point `r` of `at`, for the
/// reported curve `y` and the warp's enclosed power form `w`.
pub(crate) fn composite<const L: usize>(
    y: &Poly<4>,
    w: &WarpPoly,
    at: Interval,
) -> [SeriesN<L>; 4] {
    let sw = taylor_shift(w, at);
    // All L coefficients (a product of series keeps the longer operand's length).
    let c: [Interval; L] = std::array::from_fn(|m| sw.get(m).map_or(point(0.0), |row| row[0]));
    let ws = SeriesN::<L>::new(&c);
    std::array::from_fn(|d| {
        y.iter()
            .rev()
            .skip(1)
            .fold(SeriesN::<L>::constant(y[y.len() - 1][d]), |acc, row| {
                acc * ws + SeriesN::constant(row[d])
            })
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::edge::poly::{eval, reparametrised};

    use crate::pair::fixtures::quarter_cylinder as cylinder;

    #[test]
    fn the_warp_makes_the_parameter_an_arc_length() {
        let p = cylinder();
        let coeffs = [[0.0, 0.1, 0.0, 0.0], [1.0, 0.4, 0.0, 0.0]];
        let y = reparametrised(&coeffs, 0.0, 1.0);
        let (w, len) = arc_length_warp(&p, &y);
        assert_eq!(w.at(0.0), 0.0);
        assert_eq!(w.at(1.0), 1.0);
        // The length of the curve by 200 000 chords (the rational quarter circle has a
        // non-uniform speed in σ).
        let pt = |u: f64| {
            let x = eval_mid(&y, u);
            p.point_f64(x[0], x[1])
        };
        let chords = 200_000;
        let exact: f64 = (0..chords)
            .map(|k| {
                let (a, b) = (
                    pt(k as f64 / chords as f64),
                    pt((k + 1) as f64 / chords as f64),
                );
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
            })
            .sum();
        assert!((len - exact).abs() < 1e-9, "{len} vs {exact}");
        // The arc length to w(r) is r·len, to within the interpolation's error.
        for k in 1..10 {
            let r = k as f64 / 10.0;
            let s = arc(&p, &y, 0.0, w.at(r));
            assert!((s - r * len).abs() < 1e-4 * len, "{r}: {s} vs {}", r * len);
        }
    }

    /// A warp far from the identity.
    pub(crate) fn a_warp() -> Warp {
        Warp::from_bernstein([0.0, 0.1, 0.3, 0.55, 0.9, 1.0]).unwrap()
    }

    #[test]
    fn the_composite_series_encloses_the_composition() {
        let coeffs = [
            [0.2, 0.1, 0.3, 0.0],
            [0.9, 0.4, -0.2, 1.0],
            [-0.3, 0.2, 0.1, 0.0],
            [0.05, 0.0, 0.0, 0.0],
        ];
        let y = reparametrised(&coeffs, 0.1, 0.7);
        let w = a_warp();
        let wp = w.power();
        let at = inari::interval!(0.25, 0.5).unwrap();
        let s = composite::<32>(&y, &wp, point(0.3));
        let over = composite::<10>(&y, &wp, at);
        for k in 0..=20 {
            let r = 0.25 + 0.25 * k as f64 / 20.0;
            let u = w.at(r);
            for d in 0..4 {
                let exact = eval(&y, point(u), d);
                assert!(over[d].coeff(0).inf() <= exact.sup() + 1e-14);
                assert!(exact.inf() - 1e-14 <= over[d].coeff(0).sup());
                // The series at 0.3 summed at r − 0.3.
                let th = r - 0.3;
                let v: f64 = (0..32)
                    .map(|m| s[d].coeff(m).mid() * th.powi(m as i32))
                    .sum();
                assert!((v - exact.mid()).abs() < 1e-12, "{d} {r}: {v} vs {exact:?}");
            }
        }
    }
}
