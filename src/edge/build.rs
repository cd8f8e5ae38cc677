//! Building an edge from its parts: spans, the 3D curve, the p-curves and the bounds.

use super::poly::{self, eval_mid, Poly, DEGREE};
use super::span::{bezier, bounds, box_diameter, model_box, model_deviation, model_jet};
use super::{BSpline, Edge, EdgeBounds, EdgeError, PCurve, Part, Seg};
use crate::geometry::RationalBezierPatch;

/// One span of the edge: a piece of one link, re-expanded on `u ∈ [0, 1]`.
struct Span {
    part: usize,
    tube: usize,
    y: Poly<4>,
    /// Its length in the edge's parameter `s` (nominal: a chord length).
    ds: f64,
}

/// Longest chain of halvings of one link.
const MAX_DEPTH: usize = 6;

fn chord_length(p: &RationalBezierPatch, y: &Poly<4>) -> f64 {
    let pt = |u: f64| {
        let x = eval_mid(y, u);
        p.point_f64(x[0], x[1])
    };
    let mut len = 0.0;
    let mut a = pt(0.0);
    for k in 1..=8 {
        let b = pt(k as f64 / 8.0);
        len += ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
        a = b;
    }
    len
}

/// The quintic Hermite Bézier control points between two model jets (value, d/ds, d²/ds²)
/// over a span of length `ds`.
fn hermite(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3], ds: f64) -> [[f64; 3]; 6] {
    let f = |k: usize| -> [f64; 3] {
        std::array::from_fn(|r| match k {
            0 => a[0][r],
            1 => a[0][r] + ds / 5.0 * a[1][r],
            2 => a[0][r] + 2.0 * ds / 5.0 * a[1][r] + ds * ds / 20.0 * a[2][r],
            3 => b[0][r] - 2.0 * ds / 5.0 * b[1][r] + ds * ds / 20.0 * b[2][r],
            4 => b[0][r] - ds / 5.0 * b[1][r],
            _ => b[0][r],
        })
    };
    std::array::from_fn(f)
}

/// A model jet in `u` as one in `s` (`ds = ds/du`).
fn jet_in_s(j: [[f64; 3]; 3], ds: f64) -> [[f64; 3]; 3] {
    let d = if ds > 0.0 { ds } else { 1.0 };
    [j[0], j[1].map(|v| v / d), j[2].map(|v| v / (d * d))]
}

/// The spans of one piece of a link, halved while its own Hermite fit is above `target`.
fn split_seg(part: usize, pt: &Part, s: &Seg, target: Option<f64>, out: &mut Vec<Span>) {
    let t = &pt.cert.tubes[s.tube];
    let mut stack = vec![(s.ta, s.tb, 0usize)];
    while let Some((ta, tb, depth)) = stack.pop() {
        let y = poly::reparametrised(&t.coeffs, ta, tb);
        let ds = chord_length(pt.p, &y);
        if let Some(target) = target.filter(|_| depth < MAX_DEPTH && ta != tb) {
            let a = jet_in_s(model_jet(pt.p, &y, 0.0), ds);
            let b = jet_in_s(model_jet(pt.p, &y, 1.0), ds);
            if model_deviation(pt.p, &y, &hermite(&a, &b, ds)) > target {
                let tm = ta + 0.5 * (tb - ta);
                // Pushed second half first: popped in order.
                stack.push((tm, tb, depth + 1));
                stack.push((ta, tm, depth + 1));
                continue;
            }
        }
        out.push(Span {
            part,
            tube: s.tube,
            y,
            ds,
        });
    }
}

/// The 3D curve over the spans: per span the Hermite interpolant of its own jets (so it
/// follows the span's own parametrisation), the values shared at the knots. Also each span's
/// control points.
fn curve_3d(
    parts: &[Part],
    spans: &[Span],
    knots_s: &[f64],
    closed: bool,
) -> (BSpline<3>, Vec<[[f64; 3]; 6]>) {
    let n = spans.len();
    let own = |i: usize, u: f64| {
        let sp = &spans[i];
        jet_in_s(model_jet(parts[sp.part].p, &sp.y, u), sp.ds)
    };
    let mut values: Vec<[f64; 3]> = (0..n).map(|i| own(i, 0.0)[0]).collect();
    values.push(if closed {
        values[0]
    } else {
        own(n - 1, 1.0)[0]
    });
    let mut points: Vec<[f64; 3]> = Vec::with_capacity(5 * n + 1);
    let mut hs = Vec::with_capacity(n);
    for (i, sp) in spans.iter().enumerate() {
        let (mut a, mut b) = (own(i, 0.0), own(i, 1.0));
        a[0] = values[i];
        b[0] = values[i + 1];
        let h = hermite(&a, &b, sp.ds);
        if i == 0 {
            points.push(h[0]);
        }
        points.extend_from_slice(&h[1..]);
        hs.push(h);
    }
    let curve = BSpline {
        degree: DEGREE,
        knots: knot_vector(knots_s),
        points,
    };
    (curve, hs)
}

/// The p-curves of part `k` over its spans `range`, adding their bounds to `b`; returns the
/// largest distance of the span curves from the reported curve's image (for the cuts).
#[allow(clippy::too_many_arguments)]
fn part_pcurves(
    k: usize,
    pt: &Part,
    spans: &[Span],
    hs: &[[[f64; 3]; 6]],
    range: std::ops::Range<usize>,
    knots_s: &[f64],
    closes: bool,
    b: &mut EdgeBounds,
    out: &mut Vec<PCurve>,
) -> f64 {
    debug_assert!(spans[range.clone()].iter().all(|s| s.part == k));
    let (start, end) = (range.start, range.end);
    let beziers: Vec<Poly<4>> = spans[range.clone()].iter().map(|s| bezier(&s.y)).collect();
    let mut values: Vec<[f64; 4]> = beziers.iter().map(|z| z[0].map(|x| x.mid())).collect();
    values.push(if closes {
        values[0]
    } else {
        beziers[beziers.len() - 1][DEGREE].map(|x| x.mid())
    });
    let mut pts = Vec::new();
    let (mut prm, mut img, mut off) = ([0.0f64; 2], [0.0f64; 2], 0.0f64);
    for (m, i) in range.enumerate() {
        let r: [[f64; 4]; 6] = std::array::from_fn(|c| match c {
            0 => values[m],
            DEGREE => values[m + 1],
            c => beziers[m][c].map(|x| x.mid()),
        });
        if m == 0 {
            pts.push(r[0]);
        }
        pts.extend_from_slice(&r[1..]);
        let t = &pt.cert.tubes[spans[i].tube];
        let sb = bounds(
            pt.p,
            pt.q,
            &spans[i].y,
            &r,
            &hs[i],
            t.radius_param,
            t.radius_xyz,
        );
        prm = [prm[0].max(sb.delta_p), prm[1].max(sb.delta_q)];
        img = [img[0].max(sb.image_p), img[1].max(sb.image_q)];
        b.curve_3d = b.curve_3d.max(sb.curve);
        b.model_fit = b.model_fit.max(sb.model);
        b.same_parameter = b.same_parameter.max(sb.same_parameter);
        off = off.max(sb.off_reported);
    }
    b.pcurve_p_param = b.pcurve_p_param.max(prm[0]);
    b.pcurve_q_param = b.pcurve_q_param.max(prm[1]);
    b.pcurve_p_image = b.pcurve_p_image.max(img[0]);
    b.pcurve_q_image = b.pcurve_q_image.max(img[1]);
    let knots = knot_vector(&knots_s[start..=end]);
    for surface in 0..2 {
        out.push(PCurve {
            surface,
            face: pt.faces[surface],
            piece: pt.pieces[surface],
            branch: pt.branch,
            curve: BSpline {
                degree: DEGREE,
                knots: knots.clone(),
                points: pts
                    .iter()
                    .map(|x| [x[2 * surface], x[2 * surface + 1]])
                    .collect(),
            },
            param_tolerance: prm[surface],
            image_tolerance: img[surface],
        });
    }
    off
}

/// The edge of the parts in order (each part's segments in the edge's direction). `closed`:
/// the edge's last point is its first; `pcurve_closed`: so are the p-curves' (one part, closed
/// by its own certificate rather than across a seam).
///
/// First one span per link; when the 3D curve's bound is then the largest, the links whose
/// fit exceeds the other bounds (the certificate's tolerance and the p-curves' images, which
/// the 3D curve cannot improve on) are halved and the edge is built again.
pub(crate) fn assemble(
    parts: &[Part],
    closed: bool,
    pcurve_closed: bool,
) -> Result<Edge, EdgeError> {
    let first = assemble_with(parts, closed, pcurve_closed, None)?;
    let b = &first.bounds;
    let floor = b
        .certified_tolerance
        .max(b.pcurve_p_image)
        .max(b.pcurve_q_image)
        .max(1e-13);
    if b.curve_3d <= floor {
        return Ok(first);
    }
    assemble_with(parts, closed, pcurve_closed, Some(floor))
}

/// [`assemble`] with links halved while their own fit exceeds `target` (`None`: not halved).
fn assemble_with(
    parts: &[Part],
    closed: bool,
    pcurve_closed: bool,
    target: Option<f64>,
) -> Result<Edge, EdgeError> {
    let cert_tol = parts
        .iter()
        .map(|p| p.cert.certified_tolerance)
        .fold(0.0, f64::max);
    let mut spans = Vec::new();
    for (k, pt) in parts.iter().enumerate() {
        for s in &pt.segs {
            split_seg(k, pt, s, target, &mut spans);
        }
    }
    if spans.is_empty() {
        return Err(EdgeError::NotGapFree {
            branch: parts.first().map(|p| p.branch).unwrap_or(0),
            reason: "nothing left after cutting".into(),
        });
    }
    let mut knots_s = vec![0.0];
    for sp in &spans {
        let last: f64 = *knots_s.last().unwrap_or(&0.0);
        // Strictly increasing knots, also over a span of (nearly) zero length.
        let floor = 4.0 * f64::EPSILON * last.abs().max(1.0);
        knots_s.push(last + sp.ds.max(floor));
    }
    let (curve, hs) = curve_3d(parts, &spans, &knots_s, closed);
    let mut b = EdgeBounds {
        curve_3d: 0.0,
        model_fit: 0.0,
        same_parameter: 0.0,
        pcurve_p_image: 0.0,
        pcurve_q_image: 0.0,
        pcurve_p_param: 0.0,
        pcurve_q_param: 0.0,
        cuts: 0.0,
        certified_tolerance: cert_tol,
    };
    let mut pcurves = Vec::new();
    let (mut start, mut off) = (0, 0.0f64);
    for (k, pt) in parts.iter().enumerate() {
        let end = start + spans[start..].iter().take_while(|s| s.part == k).count();
        if end > start {
            let closes = pcurve_closed && parts.len() == 1;
            let o = part_pcurves(
                k,
                pt,
                &spans,
                &hs,
                start..end,
                &knots_s,
                closes,
                &mut b,
                &mut pcurves,
            );
            off = off.max(o);
        }
        start = end;
    }
    for pt in parts {
        for c in &pt.cuts {
            let t = &pt.cert.tubes[c.tube];
            let mut m = model_box(pt.p, &t.coeffs, c.gap);
            let mut r = t.radius_xyz;
            if let Some((tube, range)) = c.next {
                // The cut's range goes on into the next link: its reported points there too.
                let n = &pt.cert.tubes[tube];
                let mn = model_box(pt.p, &n.coeffs, range);
                m = std::array::from_fn(|i| m[i].convex_hull(mn[i]));
                r = r.max(n.radius_xyz);
            }
            // A true point of the cut's arc is within `r` of the reported curve there, that
            // within the diameter of the reported points over the cut's range of the reported
            // point at the cut, and that within `off` of each of the edge's three curves at its
            // end.
            let cut = poly::add_up(poly::add_up(r, box_diameter(&m)), off);
            b.cuts = b.cuts.max(cut);
        }
    }
    let edge_tolerance = [
        b.curve_3d,
        b.pcurve_p_image,
        b.pcurve_q_image,
        b.cuts,
        b.certified_tolerance,
    ]
    .into_iter()
    .fold(0.0, f64::max);
    let all = [
        edge_tolerance,
        b.same_parameter,
        b.pcurve_p_param,
        b.pcurve_q_param,
    ];
    if all.iter().any(|v| !v.is_finite()) {
        return Err(EdgeError::Unbounded {
            branch: parts[0].branch,
        });
    }
    Ok(Edge {
        curve,
        pcurves,
        closed,
        edge_tolerance,
        bounds: b,
        branches: parts.iter().map(|p| p.branch).collect(),
        links: parts.iter().map(|p| p.segs.len()).sum(),
    })
}

/// The clamped knot vector of degree-5 Bézier spans with ends `s` (interior knots of
/// multiplicity 5).
fn knot_vector(s: &[f64]) -> Vec<f64> {
    let mut k = Vec::with_capacity(5 * s.len() + 2);
    for (i, &v) in s.iter().enumerate() {
        let m = if i == 0 || i + 1 == s.len() {
            DEGREE + 1
        } else {
            DEGREE
        };
        k.extend(std::iter::repeat_n(v, m));
    }
    k
}
