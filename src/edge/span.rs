//! The proven bounds of one fine span of an edge: the coarse curves' distance from the
//! reported curve compared through the span's warp ([`super::warp`]): the p-curves against
//! `z(r) = y(w(r))`, the 3D curve against `P(z(r))`, each by an interval Taylor form with a
//! Lagrange remainder on sub-intervals of the span (the reported side's Taylor coefficients do
//! not depend on the fit and are computed once per span), and the images of the p-curves on P
//! and Q.

use super::poly::{add_up, norm_sup, taylor_shift, Poly, SPoly, SPLINE_DEGREE};
use super::warp::{composite, Warp};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::{meet, point};
use crate::validated::SeriesN;
use inari::Interval;

/// Order of the Taylor forms (the remainder uses the next coefficient); at least the coarse
/// curves' degree, whose coefficients enter the forms exactly.
const ORDER: usize = 8;
/// Sub-intervals of `r ∈ [0, 1]` the Taylor forms are evaluated on.
const SUBS: usize = 4;

const _: () = assert!(SPLINE_DEGREE <= ORDER);

type Long = SeriesN<{ ORDER + 2 }>;

/// The sub-interval `k` of [`SUBS`] equal parts of `[0, 1]` (exact ends).
fn sub(k: usize) -> Interval {
    inari::interval!(k as f64 / SUBS as f64, (k + 1) as f64 / SUBS as f64).unwrap()
}

/// The Taylor form of a function `g` (`D` components) on one sub-interval: its coefficients at
/// the centre up to [`ORDER`], and the next one enclosed over the whole sub-interval.
#[derive(Debug, Clone, Copy)]
struct Form<const D: usize> {
    centre: [[Interval; D]; ORDER + 1],
    next: [Interval; D],
    /// The largest distance of the sub-interval's points from its centre.
    theta: f64,
}

impl<const D: usize> Form<D> {
    fn of(at: &[Long; D], over: &[Long; D], theta: f64) -> Self {
        Form {
            centre: std::array::from_fn(|m| std::array::from_fn(|d| at[d].coeff(m))),
            next: std::array::from_fn(|d| over[d].coeff(ORDER + 1)),
            theta,
        }
    }

    /// Per component, an upper bound of `|h(r) − g(r)|` over the sub-interval centred at `c`
    /// (`h` in the power basis, or 0).
    fn gap(&self, h: Option<&SPoly<D>>, c: f64) -> [f64; D] {
        let hc = h.map(|h| taylor_shift(h, point(c)));
        std::array::from_fn(|d| {
            let mut acc = point(0.0);
            let mut pow = point(1.0);
            for m in 0..=ORDER + 1 {
                let g = if m == ORDER + 1 {
                    self.next[d]
                } else {
                    self.centre[m][d]
                };
                let e = match &hc {
                    Some(hc) if m <= SPLINE_DEGREE => hc[m][d] - g,
                    _ => -g,
                };
                acc += point(e.mag()) * pow;
                pow *= point(self.theta);
            }
            let v = acc.sup();
            if v.is_nan() {
                f64::INFINITY
            } else {
                v
            }
        })
    }
}

/// What one span proves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpanBounds {
    /// `|pcurve_P − (σ, t)(w(r))|` max norm, plus the tube's parameter radius.
    pub(crate) delta_p: f64,
    /// The same for `(u, v)`.
    pub(crate) delta_q: f64,
    /// `|H − P(z)|`.
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
    /// `Q(pcurve_Q)`) from the image `P(σ, t)` of the reported curve at the warped parameter,
    /// point by point.
    pub(crate) off_reported: f64,
}

/// `|∂S/∂a·e_a + ∂S/∂b·e_b|` for `e_a ∈ [−r_a, r_a]`, `e_b ∈ [−r_b, r_b]`, the derivatives
/// over `(a, b) ∈ bx`. Each parameter keeps its own radius: on a patch whose two parameters
/// are scaled unlike each other (a domain of sides 50 and 0.03), a max-norm radius taken
/// in both directions multiplies the long side's error by the short side's derivative.
fn image_of(s: &RationalBezierPatch, bx: [Interval; 2], r: [f64; 2]) -> f64 {
    let [ea, eb] = r.map(symmetric);
    let [_, da, db] = s.first_derivs(bx[0], bx[1]);
    let v: Vec<Interval> = (0..3).map(|k| da[k] * ea + db[k] * eb).collect();
    norm_sup(&v)
}

/// What a fine span's bounds need that does not depend on the fitted curves.
#[derive(Debug, Clone)]
pub(crate) struct SpanFixed {
    /// The enclosure of the reported curve over the span.
    pub(crate) bx: [Interval; 4],
    /// An upper bound of its residual `|P(σ, t) − Q(u, v)|`.
    pub(crate) residual: f64,
    /// The Taylor forms of `P(z)` per sub-interval.
    model: [Form<3>; SUBS],
    /// The Taylor forms of `z`.
    params: [Form<4>; SUBS],
}

impl SpanFixed {
    /// The fixed data of the span whose reported curve is `y`, compared at `u = w(r)`.
    pub(crate) fn of(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        y: &Poly<4>,
        warp: &Warp,
    ) -> Self {
        let w = warp.power();
        let mut bx = [Interval::EMPTY; 4];
        let mut residual = 0.0f64;
        let forms: [(Form<3>, Form<4>); SUBS] = std::array::from_fn(|k| {
            let u = sub(k);
            let c = u.mid();
            let theta = (u - point(c)).mag();
            let zc = composite::<{ ORDER + 2 }>(y, &w, point(c));
            let zu = composite::<{ ORDER + 2 }>(y, &w, u);
            for d in 0..4 {
                bx[d] = bx[d].convex_hull(zu[d].coeff(0));
            }
            let (pc, pu) = (p.eval(zc[0], zc[1]), p.eval(zu[0], zu[1]));
            let (qc, qu) = (q.eval(zc[2], zc[3]), q.eval(zu[2], zu[3]));
            let rc: [Long; 3] = std::array::from_fn(|r| pc[r] - qc[r]);
            let ru: [Long; 3] = std::array::from_fn(|r| pu[r] - qu[r]);
            let g = Form::of(&rc, &ru, theta).gap(None, c);
            residual = residual.max(norm_sup(&g.map(symmetric)));
            (Form::of(&pc, &pu, theta), Form::of(&zc, &zu, theta))
        });
        SpanFixed {
            bx,
            residual,
            model: forms.map(|f| f.0),
            params: forms.map(|f| f.1),
        }
    }
}

/// `[−v, v]`.
fn symmetric(v: f64) -> Interval {
    inari::interval!(-v, v).unwrap_or(Interval::ENTIRE)
}

/// The bounds of one fine span with fixed data `fixed`, the coarse p-curves' polynomial `c4`
/// (all four coordinates) and the coarse 3D curve's `c3` on the same span (enclosed, in the
/// span's `r`), over a tube piece with radii `radius_param`, `radius_xyz`. Only the
/// derivatives of `p` and `q` are used: either may be its patch moved by any vector
/// (`RationalBezierPatch::translated`, tighter next to a pole).
#[allow(clippy::too_many_arguments)]
pub(crate) fn bounds(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    fixed: &SpanFixed,
    c4: &SPoly<4>,
    c3: &SPoly<3>,
    radius_param: f64,
    radius_xyz: f64,
) -> SpanBounds {
    // Per parameter (σ, t, u, v): the fit's distance from the reported curve.
    let mut delta = [0.0f64; 4];
    let mut model = 0.0f64;
    for k in 0..SUBS {
        let c = sub(k).mid();
        let g = fixed.params[k].gap(Some(c4), c);
        for d in 0..4 {
            delta[d] = delta[d].max(g[d]);
        }
        let m = fixed.model[k].gap(Some(c3), c);
        model = model.max(norm_sup(&m.map(symmetric)));
    }
    let bx = fixed.bx;
    let widen = |d: usize, w: [f64; 4]| bx[d] + symmetric(w[d]);
    let on = |s: &RationalBezierPatch, i: usize, w: [f64; 4]| {
        image_of(s, [widen(i, w), widen(i + 1, w)], [w[i], w[i + 1]])
    };
    let dp = on(p, 0, delta);
    let with_tube = delta.map(|d| add_up(radius_param, d));
    // Q(pcurve_Q) − true = Q(pcurve_Q) − Q(z_Q) + Q(z_Q) − true: the fit through DQ, and
    // radius_xyz (a cover-chain link's radius bounds the reported curve's image on Q too, not
    // only on P); or directly through DQ and radius_param.
    let dq = on(q, 2, delta);
    let image_q = on(q, 2, with_tube).min(add_up(dq, radius_xyz));
    // Q(pcurve_Q) against the reported image on P: the fit and the reported residual.
    let q_off = add_up(dq, fixed.residual);
    let (delta_p, delta_q) = (delta[0].max(delta[1]), delta[2].max(delta[3]));
    SpanBounds {
        delta_p: add_up(radius_param, delta_p),
        delta_q: add_up(radius_param, delta_q),
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
        meet(naive[k], mv)
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
    fn a_warped_curve_the_spline_reproduces_has_a_small_bound() {
        // Plane P(σ, t) = (σ, t, 0) and a straight reported curve: through a quintic warp the
        // compared curve is a quintic in r, which a degree-8 span holds exactly. With the
        // identity the bound is at the rounding level; with a strongly bent warp the Lagrange
        // remainder (enclosed over sub-intervals) adds a little, less on a short link.
        let net = [
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        let p = RationalBezierPatch::from_f64_points([1, 1], &net, None, Domain::UNIT).unwrap();
        let coeffs = [[0.1, 0.2, 0.3, 0.4], [1.0, 0.5, -0.5, 0.25]];
        let cases = [
            (Warp::identity(), 0.5, 1e-13),
            (crate::edge::warp::tests::a_warp(), 0.01, 1e-10),
        ];
        for (w, h, slack) in cases {
            let y = super::super::poly::reparametrised(&coeffs, 0.0, h);
            let z = composite::<{ SPLINE_DEGREE + 1 }>(&y, &w.power(), point(0.0));
            let c4: SPoly<4> =
                std::array::from_fn(|m| std::array::from_fn(|d| point(z[d].coeff(m).mid())));
            for shift in [0.0, 1e-6] {
                let c3: SPoly<3> = std::array::from_fn(|m| {
                    std::array::from_fn(|d| match d {
                        2 if m == 0 => point(shift),
                        2 => point(0.0),
                        _ => c4[m][d],
                    })
                });
                let f = SpanFixed::of(&p, &p, &y, &w);
                let b = bounds(&p, &p, &f, &c4, &c3, 0.0, 0.0);
                assert!(b.delta_p < 1e-13 && b.delta_q < 1e-13, "{b:?}");
                assert!(b.model >= shift && b.model < shift + slack, "{h}: {b:?}");
                assert!(b.same_parameter >= shift);
            }
        }
    }

    #[test]
    fn the_model_box_encloses_the_image_and_is_first_order_tight() {
        // A quarter of the unit cylinder (rational, degree 2 × 1) and a curve on it.
        let p = crate::pair::fixtures::quarter_cylinder();
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
