//! The proven bounds of one fine span of an edge: the coarse p-curves' distance from the
//! reported curve (the Bernstein coefficients of the difference, enclosed), the coarse 3D
//! curve's deviation from the image of the reported curve (a Taylor form with a Lagrange
//! remainder on sub-intervals), and the images of the p-curves on P and Q.

#[cfg(test)]
use super::poly::power_from_bezier;
use super::poly::{add_up, bezier_from_power, eval, norm_sup, taylor_shift, Poly, DEGREE};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use crate::validated::SeriesN;
use inari::Interval;

/// Order of the Taylor form of the 3D deviation (the remainder uses the next coefficient).
const ORDER: usize = 8;
/// Sub-intervals of `u ∈ [0, 1]` the Taylor form is evaluated on.
const SUBS: usize = 4;

type Long = SeriesN<{ ORDER + 2 }>;

/// The sub-interval `k` of [`SUBS`] equal parts of `[0, 1]` (exact ends).
fn sub(k: usize) -> Interval {
    inari::interval!(k as f64 / SUBS as f64, (k + 1) as f64 / SUBS as f64).unwrap()
}

/// The four coordinates of `y` as series in `θ` around every point of `at`, of length `len`.
fn series_pt(y: &Poly<4>, at: Interval, len: usize) -> [Long; 4] {
    let sh = taylor_shift(y, at);
    std::array::from_fn(|d| {
        let c: Vec<Interval> = (0..len)
            .map(|k| if k <= DEGREE { sh[k][d] } else { point(0.0) })
            .collect();
        Long::new(&c)
    })
}

/// The model-space jet `(value, d/du, d²/du²)` of `P(y(u))` at `u` (midpoints; guidance only,
/// it only shapes the reported 3D curve).
pub(crate) fn model_jet(p: &RationalBezierPatch, y: &Poly<4>, u: f64) -> [[f64; 3]; 3] {
    let [a, b, _, _] = series_pt(y, point(u), 3);
    let g = p.eval(a, b);
    std::array::from_fn(|k| {
        let f = if k == 2 { 2.0 } else { 1.0 };
        std::array::from_fn(|r| f * g[r].coeff(k).mid())
    })
}

/// An upper bound of `|h(u) − f(y(u))|` over `u ∈ [0, 1]` (`h` in the power basis, or 0): on
/// each sub-interval a Taylor form of order [`ORDER`] at its centre, the next coefficient
/// enclosed over the whole sub-interval (Lagrange remainder; `h` has degree 5 < [`ORDER`]).
fn taylor_bound(y: &Poly<4>, h: Option<&Poly<3>>, f: &dyn Fn(&[Long; 4]) -> [Long; 3]) -> f64 {
    let mut worst = 0.0f64;
    for k in 0..SUBS {
        let u = sub(k);
        let c = u.mid();
        let theta = (u - point(c)).mag();
        let gc = f(&series_pt(y, point(c), ORDER + 1));
        let gu = f(&series_pt(y, u, ORDER + 2));
        let hc = h.map(|h| taylor_shift(h, point(c)));
        let comp: Vec<Interval> = (0..3)
            .map(|r| {
                let mut acc = point(0.0);
                let mut pow = point(1.0);
                for m in 0..=ORDER + 1 {
                    let g = if m == ORDER + 1 {
                        gu[r].coeff(m)
                    } else {
                        gc[r].coeff(m)
                    };
                    let e = match &hc {
                        Some(hc) if m <= DEGREE => hc[m][r] - g,
                        _ => -g,
                    };
                    acc += point(e.mag()) * pow;
                    pow *= point(theta);
                }
                inari::interval!(-acc.sup(), acc.sup()).unwrap_or(Interval::ENTIRE)
            })
            .collect();
        worst = worst.max(norm_sup(&comp));
    }
    worst
}

/// An upper bound of `|H(u) − P(y(u))|` over `u ∈ [0, 1]` for the Bézier curve `h`.
#[cfg(test)]
pub(crate) fn model_deviation(p: &RationalBezierPatch, y: &Poly<4>, h: &[[f64; 3]; 6]) -> f64 {
    let hp = power_from_bezier(&h.map(|r| r.map(point)));
    taylor_bound(y, Some(&hp), &|s| p.eval(s[0], s[1]))
}

/// An upper bound of the residual `|P(σ(u), t(u)) − Q(u(u), v(u))|` of the reported curve.
fn residual(p: &RationalBezierPatch, q: &RationalBezierPatch, y: &Poly<4>) -> f64 {
    taylor_bound(y, None, &|s| {
        let a = p.eval(s[0], s[1]);
        let b = q.eval(s[2], s[3]);
        std::array::from_fn(|r| a[r] - b[r])
    })
}

/// What one span proves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpanBounds {
    /// `|pcurve_P − (σ, t)(τ)|` max norm: rounding of the control points and the join.
    pub(crate) delta_p: f64,
    /// The same for `(u, v)`.
    pub(crate) delta_q: f64,
    /// `|H − P(y)|`.
    pub(crate) model: f64,
    /// `|3D curve − true|`.
    pub(crate) curve: f64,
    /// `|P(pcurve_P) − true|`.
    pub(crate) image_p: f64,
    /// `|Q(pcurve_Q) − true|`.
    pub(crate) image_q: f64,
    /// `|3D curve − P(pcurve_P)|` at the same parameter.
    pub(crate) same_parameter: f64,
    /// The largest distance of the span's three curves (3D curve, `P(pcurve_P)`,
    /// `Q(pcurve_Q)`) from the image `P(σ(τ), t(τ))` of the reported curve, point by point.
    pub(crate) off_reported: f64,
}

/// The enclosure of `y` over `u ∈ [0, 1]` (hull of the sub-interval enclosures).
pub(crate) fn param_box(y: &Poly<4>) -> [Interval; 4] {
    std::array::from_fn(|d| {
        (0..SUBS)
            .map(|k| eval(y, sub(k), d))
            .reduce(|a, b| a.convex_hull(b))
            .unwrap_or(Interval::ENTIRE)
    })
}

/// An upper bound of `max |c_d(u) − y_d(u)|` over `u ∈ [0, 1]` and the coordinates `dims`:
/// the largest Bernstein coefficient of the difference (partition of unity).
fn poly_gap(c: &Poly<4>, y: &Poly<4>, dims: [usize; 2]) -> f64 {
    let diff: Poly<4> = std::array::from_fn(|k| std::array::from_fn(|d| c[k][d] - y[k][d]));
    let b = bezier_from_power(&diff);
    let mut m = 0.0f64;
    for row in &b {
        for d in dims {
            m = m.max(row[d].mag());
        }
    }
    if m.is_nan() {
        f64::INFINITY
    } else {
        m
    }
}

/// `|∂S/∂a·e + ∂S/∂b·e|` for `e ∈ [−r, r]`, the derivatives over `(a, b) ∈ bx`.
fn image_of(s: &RationalBezierPatch, bx: [Interval; 2], r: f64) -> f64 {
    let e = inari::interval!(-r, r).unwrap_or(Interval::ENTIRE);
    let [_, da, db] = s.first_derivs(bx[0], bx[1]);
    let v: Vec<Interval> = (0..3).map(|k| da[k] * e + db[k] * e).collect();
    norm_sup(&v)
}

/// What a fine span's bounds need that does not depend on the fitted curves.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpanFixed {
    /// The enclosure of the reported curve over the span.
    pub(crate) bx: [Interval; 4],
    /// An upper bound of its residual `|P(σ, t) − Q(u, v)|`.
    pub(crate) residual: f64,
}

impl SpanFixed {
    /// The fixed data of the span whose reported curve is `y`.
    pub(crate) fn of(p: &RationalBezierPatch, q: &RationalBezierPatch, y: &Poly<4>) -> Self {
        SpanFixed {
            bx: param_box(y),
            residual: residual(p, q, y),
        }
    }
}

/// The bounds of one fine span with reported curve `y` (enclosed polynomial in the span's
/// `u`), the coarse p-curves' polynomial `c4` (all four coordinates) and the coarse 3D curve's
/// `c3` on the same span (enclosed), over a tube piece with radii `radius_param`, `radius_xyz`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn bounds(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &Poly<4>,
    fixed: &SpanFixed,
    c4: &Poly<4>,
    c3: &Poly<3>,
    radius_param: f64,
    radius_xyz: f64,
) -> SpanBounds {
    let delta_p = poly_gap(c4, y, [0, 1]);
    let delta_q = poly_gap(c4, y, [2, 3]);
    let bx = fixed.bx;
    let widen = |x: Interval, w: f64| x + inari::interval!(-w, w).unwrap_or(Interval::ENTIRE);
    let dp = image_of(p, [widen(bx[0], delta_p), widen(bx[1], delta_p)], delta_p);
    let rq = add_up(radius_param, delta_q);
    // Q(pcurve_Q) − true = Q(pcurve_Q) − Q(y_Q) + Q(y_Q) − P(y_P) + P(y_P) − true: the
    // fit, the residual, and radius_xyz; or directly through DQ and radius_param.
    let dq = image_of(q, [widen(bx[2], delta_q), widen(bx[3], delta_q)], delta_q);
    let q_off = add_up(dq, fixed.residual);
    let image_q =
        image_of(q, [widen(bx[2], rq), widen(bx[3], rq)], rq).min(add_up(q_off, radius_xyz));
    let model = taylor_bound(y, Some(c3), &|s| p.eval(s[0], s[1]));
    SpanBounds {
        delta_p: add_up(radius_param, delta_p),
        delta_q: rq,
        model,
        curve: add_up(model, radius_xyz),
        image_p: add_up(radius_xyz, dp),
        image_q,
        same_parameter: add_up(model, dp),
        off_reported: model.max(dp).max(q_off),
    }
}

/// An enclosure of `P(y(τ))` for `τ ∈ tau`, the tube's coefficients in `τ`: the naive
/// interval evaluation intersected with the mean-value form `P(y(m)) + DP(y(tau))·y'(tau)·(tau
/// − m)` about the centre `m` (first order in the width of `tau`, where the naive form
/// over-estimates a rational patch by a factor).
pub(crate) fn model_box(
    p: &RationalBezierPatch,
    coeffs: &[[f64; 4]],
    tau: Interval,
) -> [Interval; 3] {
    let horner = |t: Interval, d: usize| {
        coeffs
            .iter()
            .rev()
            .fold(point(0.0), |acc, c| acc * t + point(c[d]))
    };
    let slope = |d: usize| {
        coeffs
            .iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(point(0.0), |acc, (k, c)| {
                acc * tau + point(k as f64) * point(c[d])
            })
    };
    let y: [Interval; 2] = std::array::from_fn(|d| horner(tau, d));
    let naive = p.eval(y[0], y[1]);
    let m = point(tau.mid());
    let ym: [Interval; 2] = std::array::from_fn(|d| horner(m, d));
    let at = p.eval(ym[0], ym[1]);
    let [_, da, db] = p.first_derivs(y[0], y[1]);
    let (s0, s1) = (slope(0), slope(1));
    let off = tau - m;
    std::array::from_fn(|k| {
        let mv = at[k] + (da[k] * s0 + db[k] * s1) * off;
        let both = naive[k].intersection(mv);
        if both.is_empty() {
            naive[k]
        } else {
            both
        }
    })
}

/// The diameter (upper bound) of a box: the largest difference of two of its points.
pub(crate) fn box_diameter(m: &[Interval; 3]) -> f64 {
    // The widths, rounded up.
    let w: Vec<Interval> = m.iter().map(|x| point(x.sup()) - point(x.inf())).collect();
    norm_sup(&w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Domain;

    #[test]
    fn a_curve_the_hermite_reproduces_has_a_rounding_level_bound() {
        // Plane P(σ, t) = (σ, t, 0): the model curve is (σ(u), t(u), 0).
        let net = [
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let p = RationalBezierPatch::from_f64_points([1, 1], &net, None, Domain::UNIT).unwrap();
        let coeffs = [
            [0.1, 0.2, 0.0, 0.0],
            [1.0, 0.5, 0.0, 0.0],
            [0.0, 0.3, 0.0, 0.0],
        ];
        let y = super::super::poly::reparametrised(&coeffs, 0.0, 0.5);
        let a = model_jet(&p, &y, 0.0);
        let b = model_jet(&p, &y, 1.0);
        let h: [[f64; 3]; 6] = std::array::from_fn(|k| match k {
            0 => a[0],
            1 => std::array::from_fn(|r| a[0][r] + a[1][r] / 5.0),
            2 => std::array::from_fn(|r| a[0][r] + 2.0 * a[1][r] / 5.0 + a[2][r] / 20.0),
            3 => std::array::from_fn(|r| b[0][r] - 2.0 * b[1][r] / 5.0 + b[2][r] / 20.0),
            4 => std::array::from_fn(|r| b[0][r] - b[1][r] / 5.0),
            _ => b[0],
        });
        let d = model_deviation(&p, &y, &h);
        assert!(d < 1e-12);
    }

    #[test]
    fn the_model_box_encloses_the_image_and_is_first_order_tight() {
        // A quarter of the unit cylinder (rational, degree 2 × 1) and a curve on it.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let net = [
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 1.0],
        ];
        let w = [1.0, 1.0, h, h, 1.0, 1.0];
        let p = RationalBezierPatch::from_f64_points([2, 1], &net, Some(&w), Domain::UNIT).unwrap();
        let coeffs = [
            [0.2, 0.1, 0.0, 0.0],
            [0.9, 0.4, 0.0, 0.0],
            [-0.3, 0.2, 0.0, 0.0],
        ];
        let tau = inari::interval!(0.3, 0.3001).unwrap();
        let b = model_box(&p, &coeffs, tau);
        for k in 0..=20 {
            let t = 0.3 + 0.0001 * k as f64 / 20.0;
            let y: [f64; 2] =
                std::array::from_fn(|d| coeffs.iter().rev().fold(0.0, |acc, c| acc * t + c[d]));
            let x = p.point_f64(y[0], y[1]);
            for c in 0..3 {
                assert!(b[c].inf() - 1e-14 <= x[c] && x[c] <= b[c].sup() + 1e-14);
            }
        }
        // The naive enclosure is wider; the box is within a few times the true image's size.
        let y: [Interval; 2] = std::array::from_fn(|d| {
            coeffs
                .iter()
                .rev()
                .fold(point(0.0), |acc, c| acc * tau + point(c[d]))
        });
        let naive = p.eval(y[0], y[1]);
        assert!(box_diameter(&b) <= box_diameter(&naive));
        assert!(box_diameter(&b) < 3.0 * 1e-4, "{}", box_diameter(&b));
    }
}
