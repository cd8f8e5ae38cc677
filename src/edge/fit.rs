//! The coarse curves of an edge: a clamped B-spline of degree [`DEGREE`] (the poly module's
//! `SPLINE_DEGREE`) on a few of the fine
//! knots, fitted in `f64` by least squares (guidance only), and its polynomial on each fine
//! span enclosed in interval arithmetic (what the bounds are computed from).
//!
//! The enclosure: the spline's control points (exact `f64`) are refined by Boehm's knot
//! insertion, every interior knot up to multiplicity [`DEGREE`], with interval weights
//! (`α = (t − uᵢ)/(uᵢ₊ₚ − uᵢ)` and `1 − α = (uᵢ₊ₚ − t)/(uᵢ₊ₚ − uᵢ)`, each enclosed): the result
//! encloses the exact Bézier control points of every coarse span. On a fine span inside a
//! coarse span the polynomial is re-expanded in the fine span's own `u ∈ [0, 1]` (power basis,
//! a Taylor shift and a scaling by enclosed ratios of knot differences).

use super::poly::{power_from_bezier, taylor_shift, SPoly, SPLINE_DEGREE as DEGREE};
use crate::numeric::scalar::point;
use inari::Interval;

/// The clamped knot vector of degree [`DEGREE`] on the breakpoints `s` (strictly increasing),
/// the interior breakpoint `i` of multiplicity `mult(i)` (clamped to `1..=DEGREE`).
pub(crate) fn knots_on(s: &[f64], mult: impl Fn(usize) -> usize) -> Vec<f64> {
    let mut k = Vec::with_capacity(s.len() + 2 * DEGREE);
    for (i, &v) in s.iter().enumerate() {
        let m = if i == 0 || i + 1 == s.len() {
            DEGREE + 1
        } else {
            mult(i).clamp(1, DEGREE)
        };
        k.extend(std::iter::repeat_n(v, m));
    }
    k
}

/// The values of the `DEGREE + 1` basis functions that are not zero at `s`, and the index of
/// the first of them (Cox–de Boor, `f64`).
fn basis(knots: &[f64], n: usize, s: f64) -> (usize, [f64; DEGREE + 1]) {
    let p = DEGREE;
    let mut k = p;
    while k + 1 < n && knots[k + 1] <= s {
        k += 1;
    }
    let mut nb = [0.0; DEGREE + 1];
    let mut left = [0.0; DEGREE + 1];
    let mut right = [0.0; DEGREE + 1];
    nb[0] = 1.0;
    for j in 1..=p {
        left[j] = s - knots[k + 1 - j];
        right[j] = knots[k + j] - s;
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let tmp = if den == 0.0 { 0.0 } else { nb[r] / den };
            nb[r] = saved + right[r + 1] * tmp;
            saved = left[j - r] * tmp;
        }
        nb[j] = saved;
    }
    (k - p, nb)
}

/// Least-squares control points of the clamped spline on `knots` (degree [`DEGREE`]) through
/// the samples `(s, x)`, its first and last control points fixed to `ends` (`f64`; guidance
/// only: nothing proven rests on it).
pub(crate) fn least_squares<const D: usize>(
    knots: &[f64],
    samples: &[(f64, [f64; D])],
    ends: [[f64; D]; 2],
) -> Vec<[f64; D]> {
    weighted(knots, samples, |_| 1.0, ends)
}

/// [`least_squares`] per coordinate, the residual of coordinate `d` at sample `i` weighted by
/// `weights[i][d]` (positive): each coordinate is fitted on its own, so that where one
/// coordinate barely moves the curve's image (a sphere's longitude next to its pole) its
/// samples cannot pull the fit away from the others' (guidance only).
pub(crate) fn least_squares_weighted<const D: usize>(
    knots: &[f64],
    samples: &[(f64, [f64; D])],
    weights: &[[f64; D]],
    ends: [[f64; D]; 2],
) -> Vec<[f64; D]> {
    let mut out = vec![[0.0; D]; knots.len() - DEGREE - 1];
    for d in 0..D {
        let one: Vec<(f64, [f64; 1])> = samples.iter().map(|(s, x)| (*s, [x[d]])).collect();
        let fit = weighted(knots, &one, |i| weights[i][d], ends.map(|e| [e[d]]));
        for (o, f) in out.iter_mut().zip(fit) {
            o[d] = f[0];
        }
    }
    out
}

/// [`least_squares`] with the row of sample `i` scaled by `weight(i)`.
fn weighted<const D: usize>(
    knots: &[f64],
    samples: &[(f64, [f64; D])],
    weight: impl Fn(usize) -> f64,
    ends: [[f64; D]; 2],
) -> Vec<[f64; D]> {
    let n = knots.len() - DEGREE - 1;
    let free = n.saturating_sub(2);
    let mut out = vec![ends[0]; n];
    out[n - 1] = ends[1];
    if free == 0 {
        return out;
    }
    // Fitted about the first end (`Σ Nᵢ = 1`): the rotations' rounding is then relative to the
    // curve's variation, not to its distance from 0.
    let a = ends[0];
    let ends = ends.map(|e| std::array::from_fn::<f64, D, _>(|d| e[d] - a[d]));
    // Banded QR by Givens rotations: each sample's row has at most DEGREE + 1 consecutive
    // non-zeros, so R has DEGREE + 1 diagonals (r[i][k] is entry (i, i + k)).
    const W: usize = DEGREE + 1;
    let mut r = vec![[0.0f64; W]; free];
    let mut rb = vec![[0.0f64; D]; free];
    for (k, (s, x)) in samples.iter().enumerate() {
        let (first, nb) = basis(knots, n, *s);
        let mut rhs: [f64; D] = std::array::from_fn(|d| x[d] - a[d]);
        // The row over the free columns first - 1 .. first - 1 + DEGREE (column i is control
        // point i + 1); the fixed end points go to the right-hand side.
        let mut v = [0.0f64; W];
        let base = first as isize - 1;
        for (j, w) in nb.iter().enumerate() {
            let i = first + j;
            if i == 0 || i == n - 1 {
                let e = if i == 0 { ends[0] } else { ends[1] };
                for d in 0..D {
                    rhs[d] -= w * e[d];
                }
            } else {
                v[j] = *w;
            }
        }
        let wk = weight(k);
        if wk != 1.0 {
            v.iter_mut().for_each(|x| *x *= wk);
            rhs.iter_mut().for_each(|x| *x *= wk);
        }
        for j in 0..W {
            let col = base + j as isize;
            if v[j] == 0.0 || col < 0 || col as usize >= free {
                continue;
            }
            let c = col as usize;
            let rr = &mut r[c];
            if rr[0] == 0.0 {
                // An empty row of R: the rest of this row becomes it.
                rr[..W - j].copy_from_slice(&v[j..]);
                rb[c] = rhs;
                break;
            }
            let h = rr[0].hypot(v[j]);
            let (cs, sn) = (rr[0] / h, v[j] / h);
            for k in 0..W - j {
                let (a, b) = (rr[k], v[j + k]);
                rr[k] = cs * a + sn * b;
                v[j + k] = -sn * a + cs * b;
            }
            for d in 0..D {
                let (a, b) = (rb[c][d], rhs[d]);
                rb[c][d] = cs * a + sn * b;
                rhs[d] = -sn * a + cs * b;
            }
        }
    }
    let mut sol = vec![[0.0f64; D]; free];
    for i in (0..free).rev() {
        if r[i][0] == 0.0 || !r[i][0].is_finite() {
            // Not determined by the samples: the ends' chord for the guidance.
            return out;
        }
        let mut acc = rb[i];
        for k in 1..W.min(free - i) {
            for d in 0..D {
                acc[d] -= r[i][k] * sol[i + k][d];
            }
        }
        sol[i] = acc.map(|v| v / r[i][0]);
    }
    for (o, x) in out[1..=free].iter_mut().zip(&sol) {
        *o = std::array::from_fn(|d| x[d] + a[d]);
    }
    out
}

/// The enclosed Bézier control points of every span of the clamped spline (`knots`,
/// `points`, degree [`DEGREE`]), in order, by interval knot insertion.
fn bezier_spans<const D: usize>(knots: &[f64], points: Vec<[Interval; D]>) -> Vec<SPoly<D>> {
    let p = DEGREE;
    let mut u: Vec<f64> = knots.to_vec();
    let mut c = points;
    let mut k = p + 1;
    // Walk the interior knots; raise each one's multiplicity to p.
    while k < u.len() - p - 1 {
        let t = u[k];
        let mult = u[k..].iter().take_while(|&&x| x == t).count();
        for _ in mult..p {
            // t sits at span index `span` (u[span] <= t < u[span + 1]): the last copy of t.
            let span = k + u[k..].iter().take_while(|&&x| x == t).count() - 1;
            let s = u[k..=span].len();
            let mut q: Vec<[Interval; D]> = Vec::with_capacity(c.len() + 1);
            for i in 0..=c.len() {
                if i + p <= span {
                    q.push(c[i]);
                } else if i + s <= span {
                    let den = point(u[i + p]) - point(u[i]);
                    let al = (point(t) - point(u[i])) / den;
                    let be = (point(u[i + p]) - point(t)) / den;
                    q.push(std::array::from_fn(|d| al * c[i][d] + be * c[i - 1][d]));
                } else {
                    q.push(c[i - 1]);
                }
            }
            c = q;
            u.insert(span + 1, t);
        }
        k += p;
    }
    let spans = (c.len() - 1) / p;
    (0..spans)
        .map(|j| std::array::from_fn(|i| c[j * p + i]))
        .collect()
}

/// The polynomial of the spline (`knots`, `points`; breakpoints `coarse`, a subset of `fine`)
/// on every fine span `[fine[i], fine[i + 1]]`, in that span's `u ∈ [0, 1]` (power basis),
/// enclosed.
pub(crate) fn on_fine_spans<const D: usize>(
    knots: &[f64],
    points: &[[f64; D]],
    coarse: &[f64],
    fine: &[f64],
) -> Vec<SPoly<D>> {
    // Every enclosure below widens in proportion to the magnitude of what it encloses, and the
    // bounds multiply a p-curve's widths by the surface's derivative: a parameter far from 0
    // on a short side (v ∈ [2, 2.02], `|∂Q/∂v|` ~ 100) would carry rounding of 2 into every
    // bound. So the spline is enclosed about an anchor, the first control point (`Σ Nᵢ = 1`:
    // the spline is the anchor plus the spline of the control points less the anchor), and each
    // coarse span again about its first Bézier point before the basis change and the shifts;
    // the widths then scale with the curve's extent, not with its distance from 0.
    let origin = points.first().copied().unwrap_or([0.0; D]);
    let less: Vec<[Interval; D]> = points
        .iter()
        .map(|x| std::array::from_fn(|d| point(x[d]) - point(origin[d])))
        .collect();
    let spans = bezier_spans(knots, less);
    let anchors: Vec<[f64; D]> = spans.iter().map(|b| b[0].map(|x| x.mid())).collect();
    let power: Vec<SPoly<D>> = spans
        .iter()
        .zip(&anchors)
        .map(|(b, a)| {
            let less: SPoly<D> =
                std::array::from_fn(|i| std::array::from_fn(|d| b[i][d] - point(a[d])));
            power_from_bezier(&less)
        })
        .collect();
    let mut out = Vec::with_capacity(fine.len().saturating_sub(1));
    let mut c = 0;
    for w in fine.windows(2) {
        while c + 2 < coarse.len() && coarse[c + 1] <= w[0] {
            c += 1;
        }
        let (a, b) = (coarse[c], coarse[c + 1]);
        let len = point(b) - point(a);
        let w0 = (point(w[0]) - point(a)) / len;
        let dw = (point(w[1]) - point(w[0])) / len;
        let mut y = taylor_shift(&power[c], w0);
        let mut pow = point(1.0);
        for row in y.iter_mut() {
            for v in row.iter_mut() {
                *v *= pow;
            }
            pow *= dw;
        }
        for d in 0..D {
            y[0][d] = y[0][d] + point(anchors[c][d]) + point(origin[d]);
        }
        out.push(y);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edge::poly::eval;
    use crate::edge::BSpline;

    #[test]
    fn fine_span_polynomials_enclose_the_spline() {
        let coarse = [0.0, 0.7, 1.5, 2.0];
        let knots = knots_on(&coarse, |i| if i == 2 { DEGREE - 1 } else { 1 });
        let n = knots.len() - DEGREE - 1;
        let points: Vec<[f64; 2]> = (0..n)
            .map(|i| [(i as f64 * 0.37).sin(), (i as f64).powi(2) * 0.1])
            .collect();
        let spline = BSpline::<2> {
            degree: DEGREE,
            knots: knots.clone(),
            points: points.clone(),
        };
        let fine = [0.0, 0.3, 0.7, 1.1, 1.2, 1.5, 2.0];
        let polys = on_fine_spans(&knots, &points, &coarse, &fine);
        assert_eq!(polys.len(), fine.len() - 1);
        for (i, y) in polys.iter().enumerate() {
            for m in 0..=10 {
                let u = m as f64 / 10.0;
                let s = fine[i] + (fine[i + 1] - fine[i]) * u;
                let x = spline.eval(s);
                for (d, xd) in x.iter().enumerate() {
                    let v = eval(y, point(u), d);
                    assert!(
                        v.inf() - 1e-13 <= *xd && *xd <= v.sup() + 1e-13,
                        "span {i} u {u}: {v:?} vs {xd}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_weighted_fit_follows_the_heavy_samples() {
        // One coordinate is a cubic but for a jump of 1e-3 in its last few samples, weighted
        // 1e-9 there; the other is the cubic, weighted 1 (so it alone cannot tell): fitted
        // per coordinate, the first follows the cubic where its weight is 1, the second
        // everywhere.
        let coarse = [0.0, 1.0, 2.0];
        let knots = knots_on(&coarse, |_| 1);
        let f = |s: f64| s * s * s - s;
        let n = 200;
        let mut samples = Vec::new();
        let mut weights = Vec::new();
        for k in 0..=n {
            let s = 2.0 * k as f64 / n as f64;
            let far = k > n - 4;
            samples.push((s, [f(s) + if far { 1e-3 } else { 0.0 }, f(s)]));
            weights.push([if far { 1e-9 } else { 1.0 }, 1.0]);
        }
        let ends = [[f(0.0); 2], [f(2.0); 2]];
        let plain = least_squares(&knots, &samples, ends);
        let pts = least_squares_weighted(&knots, &samples, &weights, ends);
        let curve = |pts: Vec<[f64; 2]>| BSpline::<2> {
            degree: DEGREE,
            knots: knots.clone(),
            points: pts,
        };
        let (plain, fit) = (curve(plain), curve(pts));
        let mut worst_plain = 0.0f64;
        for k in 0..=150 {
            let s = k as f64 / 100.0;
            let x = fit.eval(s);
            assert!((x[0] - f(s)).abs() < 1e-9, "{s}: {x:?}");
            assert!((x[1] - f(s)).abs() < 1e-12, "{s}: {x:?}");
            worst_plain = worst_plain.max((plain.eval(s)[0] - f(s)).abs());
        }
        assert!(worst_plain > 1e-6, "{worst_plain}");
    }

    #[test]
    fn least_squares_reproduces_a_polynomial() {
        let coarse = [0.0, 1.0, 2.0];
        let knots = knots_on(&coarse, |i| if i == 2 { DEGREE - 1 } else { 1 });
        let f = |s: f64| [s * s * s - s, 0.5 * s];
        let samples: Vec<(f64, [f64; 2])> = (0..=40)
            .map(|k| {
                let s = k as f64 / 20.0;
                (s, f(s))
            })
            .collect();
        let pts = least_squares(&knots, &samples, [f(0.0), f(2.0)]);
        let spline = BSpline::<2> {
            degree: DEGREE,
            knots,
            points: pts,
        };
        for k in 0..=20 {
            let s = k as f64 / 10.0;
            let (x, y) = (spline.eval(s), f(s));
            assert!((x[0] - y[0]).abs() < 1e-12 && (x[1] - y[1]).abs() < 1e-12);
        }
    }
}
