//! Sampling a certified B-spline edge and measuring distances to it, for the tests that check
//! an edge against a closed-form curve both ways.

use ssitrace::edge::BSpline;

/// The Euclidean distance between two points.
pub(crate) fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The distance from `x` to the segment `[a, b]` (to `a` when the segment is a point).
pub(crate) fn to_segment(x: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
    let w: [f64; 3] = std::array::from_fn(|k| x[k] - a[k]);
    let dd = d.iter().map(|v| v * v).sum::<f64>();
    let s = if dd > 0.0 {
        (w.iter().zip(&d).map(|(p, q)| p * q).sum::<f64>() / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let y: [f64; 3] = std::array::from_fn(|k| a[k] + s * d[k]);
    dist3(x, &y)
}

/// The distance from `x` to the polyline through `pts` (to its point when it has one).
pub(crate) fn to_polyline(pts: &[[f64; 3]], x: &[f64; 3]) -> f64 {
    if pts.len() == 1 {
        return dist3(&pts[0], x);
    }
    pts.windows(2)
        .map(|w| to_segment(x, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Dense parameters over a spline's range: `per_span` in every knot span.
pub(crate) fn samples<const D: usize>(b: &BSpline<D>, per_span: usize) -> Vec<f64> {
    let mut ks: Vec<f64> = b.knots.clone();
    ks.dedup();
    let mut out = Vec::new();
    for w in ks.windows(2) {
        out.extend((0..per_span).map(|m| w[0] + (w[1] - w[0]) * m as f64 / per_span as f64));
    }
    out.push(*ks.last().unwrap());
    out
}

/// The distance from `x` to the spline: the nearest local minima of the distance over the dense
/// samples `pts` (at the parameters `ss`), each refined by golden-section search between its
/// neighbours and between those and the next ones (a knot span of almost no length gives
/// neighbours with almost no room between them); where that leaves more than 1e-8, a fine scan
/// of the samples round those minima.
pub(crate) fn dist_to_spline(b: &BSpline<3>, ss: &[f64], pts: &[[f64; 3]], x: &[f64; 3]) -> f64 {
    // The four nearest local minima of the sampled distance (on a closed curve the first and
    // last samples are one point, and near the seam or a C0 join the nearest sample can lie on
    // the wrong side of the nearest point).
    let d: Vec<f64> = pts.iter().map(|p| dist3(p, x)).collect();
    let n = d.len();
    let mut order: Vec<(usize, f64)> = (0..n)
        .filter(|&k| (k == 0 || d[k] <= d[k - 1]) && (k + 1 == n || d[k] <= d[k + 1]))
        .map(|k| (k, d[k]))
        .collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    let best = order.first().map_or(f64::INFINITY, |o| o.1);
    let f = |s: f64| dist3(&b.eval(s), x);
    let at = |i: usize| ss[i.min(ss.len() - 1)];
    let mut found = best;
    for &(k, _) in order.iter().take(4) {
        let brackets = [
            (at(k.saturating_sub(1)), at(k + 1)),
            (at(k.saturating_sub(2)), at(k.saturating_sub(1))),
            (at(k + 1), at(k + 2)),
        ];
        for (lo, hi) in brackets {
            found = found.min(f(golden(&f, lo, hi)));
        }
    }
    if found > 1e-8 {
        // Still far: golden-section search can stop at the kink of a C0 join (seen at a cube
        // edge, 7.7e-5 where the curve passes within 6e-11). Scan the two sample intervals on
        // each side of the nearest minima finely and refine the best scanned point.
        for &(k, _) in order.iter().take(4) {
            let (lo, hi) = (at(k.saturating_sub(2)), at(k + 2));
            let n = 4000;
            let t = |i: usize| lo + (hi - lo) * i as f64 / n as f64;
            let best = (0..=n).min_by(|&a, &c| f(t(a)).total_cmp(&f(t(c))));
            if let Some(i) = best {
                let s = golden(&f, t(i.saturating_sub(1)), t((i + 1).min(n)));
                found = found.min(f(t(i))).min(f(s));
            }
        }
    }
    if found > 1e-8 {
        // Still far (a cube edge's C0 join: 7.7e-5 found where the curve passes within 4e-12,
        // its nearest point 3e-4 past the join in s): scan the whole curve, then finely round
        // the best scanned point.
        let (lo, hi) = (at(0), at(n - 1));
        let m = 100_000;
        let t = |i: usize| lo + (hi - lo) * i as f64 / m as f64;
        if let Some(i) = (0..=m).min_by(|&a, &c| f(t(a)).total_cmp(&f(t(c)))) {
            let (a, c) = (t(i.saturating_sub(2)), t((i + 2).min(m)));
            let k = 20_000;
            let u = |j: usize| a + (c - a) * j as f64 / k as f64;
            if let Some(j) = (0..=k).min_by(|&x, &y| f(u(x)).total_cmp(&f(u(y)))) {
                let s = golden(&f, u(j.saturating_sub(1)), u((j + 1).min(k)));
                found = found.min(f(u(j))).min(f(s));
            }
        }
    }
    found
}

/// The point of `[lo, hi]` where `f` is least, by 100 steps of golden-section search (a local
/// minimum where `f` is not unimodal there).
fn golden(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (a, c) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(a) < f(c) {
            hi = c;
        } else {
            lo = a;
        }
    }
    0.5 * (lo + hi)
}

/// The range of the angle `atan2(z, y)` that the sampled points `pts` of an edge on a circle
/// round the `x` axis span (the whole turn when the edge is `closed`): where the circle must
/// lie within the edge's tolerance of the curve.
pub(crate) fn yz_angle_range(pts: &[[f64; 3]], closed: bool) -> (f64, f64) {
    let angle = |x: &[f64; 3]| x[2].atan2(x[1]);
    match (closed, pts.first(), pts.last()) {
        (false, Some(a), Some(b)) => {
            let (a, b) = (angle(a), angle(b));
            (a.min(b), a.max(b))
        }
        _ => (0.0, 2.0 * std::f64::consts::PI),
    }
}
