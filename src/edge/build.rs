//! Building an edge from its parts: fine spans ([`FINE_PER_LINK`] per link, or
//! [`DENSE_FINE_PER_LINK`] in links that stalled above the request or needed knots of raised
//! multiplicity, each as long as its arc length, with its warp), coarse curves fitted over
//! them, and the proven bounds, refined ([`refine`]) until they meet the target tolerance.

use super::fit::{knots_on, least_squares, least_squares_weighted, on_fine_spans};
use super::poly::{self, eval_mid, Poly, SPLINE_DEGREE as DEGREE};
use super::span::{bounds, box_diameter, model_box, SpanBounds, SpanFixed};
use super::warp::{arc_length_warp, Warp};
use super::{BSpline, Edge, EdgeBounds, EdgeError, PCurve, Part, Seg, Shortfall};
use crate::geometry::pole::moved_to_pole;
use crate::geometry::RationalBezierPatch;
use refine::{coarsen, refine_all};

mod refine;

/// One fine span of the edge: a piece of one link, re-expanded on `u ∈ [0, 1]`, compared with
/// the coarse curves at `u = w(r)` (`r ∈ [0, 1]` affine in the edge parameter).
struct Span {
    tube: usize,
    y: Poly<4>,
    warp: Warp,
    fixed: SpanFixed,
    radius_param: f64,
    radius_xyz: f64,
}

/// Samples of each fine span the coarse curves are fitted to (more than a span of the coarse
/// curves has control points, so that the fit stays determined when every fine knot is one).
const SAMPLES: usize = DEGREE + 3;
/// Most rounds of fitting and refining the coarse knots.
const ROUNDS: usize = 16;
/// Most pieces a coarse span is cut into in one round.
const MOST_PIECES: usize = 8;
/// Fine spans per coarse span at the start.
const START_SPANS: usize = 32;
/// Fine spans per link (equal parts of its `τ` range): a coarse knot may then fall inside a
/// link. With one, a degree-8 piece per link could not follow a long link's polynomial through
/// its warp (the bicubic pair's 11 links stalled at 4.5e-9 against a request of 1e-9; with two
/// it reaches 4e-12).
pub(crate) const FINE_PER_LINK: usize = 2;

/// The tolerance the coarse curves aim at: the requested one when the fine construction's
/// floor (the certificates' tolerance and the cuts' fixed share) is under it, but never less
/// than [`LEAST_ROOM`] times the floor; else a quarter above the floor (the request cannot be
/// met; the last few per cent above the floor would cost several times the control points).
fn target(floor: f64, requested: Option<f64>) -> f64 {
    match requested {
        Some(r) if floor <= r => r.max(LEAST_ROOM * floor),
        Some(_) => 1.25 * floor,
        None => 2.0 * floor,
    }
    .max(1e-13)
}

/// The least room above the floor a request is aimed with. The coarse curves' bounds add to
/// the floor, so a request at the floor itself leaves them no room: every region stalls, and
/// the bounds they end at are far above what a little room reaches (sphere patch / plane, a
/// request equal to the certificate's 4.25e-10: 6.35e-10 with 200 control points when aimed
/// at, 4.50e-10 with 190 when aimed 2% above it).
const LEAST_ROOM: f64 = 1.02;

/// A refined region counts as improving while a round at least divides its worst ratio by
/// this (a cut coarse span of degree 8 gains far more where the fit, not a floor, limits it;
/// a raised knot gains little, but it gains).
const GAIN: f64 = 1.02;

/// One part's coarse curves and what they prove.
struct PartFit {
    /// Breakpoints: indices into the part's fine knots (first 0, last the part's span count).
    breaks: Vec<Break>,
    /// The clamped knot vector on the breakpoints' values.
    knots: Vec<f64>,
    /// The 3D control points.
    xyz: Vec<[f64; 3]>,
    /// The p-curves' control points (`σ, t, u, v`).
    params: Vec<[f64; 4]>,
    /// Per fine span of the part.
    bounds: Vec<SpanBounds>,
}

/// A part's fine spans and its fixed data.
struct PartData<'a> {
    pt: &'a Part<'a>,
    /// Its spans' range in the edge's spans.
    range: std::ops::Range<usize>,
    /// The 3D values at its start and end (shared with the neighbouring parts).
    ends_xyz: [[f64; 3]; 2],
    /// The p-curves' values at its start and end.
    ends_param: [[f64; 4]; 2],
    /// Per cut of the part: its tube and the share of its bound that the fit does not change.
    cuts: Vec<(usize, f64)>,
    /// Its patches moved so that a pole of theirs is the origin, when they have one
    /// (`geometry::pole::moved_to_pole`): only their derivatives are taken, and next to a
    /// pole those of the net as given are differences of terms near it, each as wide as the
    /// box they are taken over (a span passing 1e-12 from it had its image bound `|DP·δ|` at
    /// 2e-5); moved, they are as small as the distance to the pole.
    moved: [Option<RationalBezierPatch>; 2],
}

/// Fits the coarse curves of one part on the breakpoints `breaks` and bounds them.
fn fit_part(d: &PartData, spans: &[Span], knots_s: &[f64], breaks: Vec<Break>) -> PartFit {
    let (start, end) = (d.range.start, d.range.end);
    let fine = &knots_s[start..=end];
    let coarse: Vec<f64> = breaks.iter().map(|b| fine[b.0]).collect();
    let knots = knots_on(&coarse, |i| breaks[i].1);
    let mut s3 = Vec::with_capacity(SAMPLES * (end - start) + 1);
    let mut s4 = Vec::with_capacity(SAMPLES * (end - start) + 1);
    for (m, sp) in spans[start..end].iter().enumerate() {
        let last = m + 1 == end - start;
        let count = if last { SAMPLES + 1 } else { SAMPLES };
        for j in 0..count {
            let r = j as f64 / SAMPLES as f64;
            let s = fine[m] + (fine[m + 1] - fine[m]) * r;
            let x = eval_mid(&sp.y, sp.warp.at(r));
            s3.push((s, d.pt.p.point_f64(x[0], x[1])));
            s4.push((s, x));
        }
    }
    let xyz = least_squares(&knots, &s3, d.ends_xyz);
    let params = least_squares_weighted(&knots, &s4, &image_weights(d.pt, &s4), d.ends_param);
    let c3 = on_fine_spans(&knots, &xyz, &coarse, fine);
    let c4 = on_fine_spans(&knots, &params, &coarse, fine);
    let bounds = spans[start..end]
        .iter()
        .enumerate()
        .map(|(m, sp)| {
            bounds(
                d.moved[0].as_ref().unwrap_or(d.pt.p),
                d.moved[1].as_ref().unwrap_or(d.pt.q),
                &sp.fixed,
                &c4[m],
                &c3[m],
                sp.radius_param,
                sp.radius_xyz,
            )
        })
        .collect();
    PartFit {
        breaks,
        knots,
        xyz,
        params,
        bounds,
    }
}

/// Weights of the p-curves' samples `s4` (per sample, per parameter `σ, t, u, v`): the length
/// of the surface's derivative in that parameter there, so that the fit weighs each
/// parameter's error by what it moves the p-curve's image (the bounds are `|∂P/∂σ|·δ_σ +
/// |∂P/∂t|·δ_t`). Next to a sphere's pole the longitude moves the image by almost nothing and the
/// chain's longitude wanders (by 2e-6 on `y = −2.5·x`): fitted unweighted, the p-curve ringed by
/// 1e-8 in the longitude all along the meridian, where it counts. Each weight is at least
/// [`LEAST_WEIGHT`] times its parameter's largest (a collapsed side's zero derivative would
/// leave its control points undetermined).
fn image_weights(pt: &Part, s4: &[(f64, [f64; 4])]) -> Vec<[f64; 4]> {
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut w: Vec<[f64; 4]> = s4
        .iter()
        .map(|(_, x)| {
            let [_, ps, pt_] = pt.p.first_derivs(x[0], x[1]);
            let [_, qu, qv] = pt.q.first_derivs(x[2], x[3]);
            [len(ps), len(pt_), len(qu), len(qv)]
        })
        .collect();
    for d in 0..4 {
        let most = w
            .iter()
            .map(|x| x[d])
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max);
        let least = if most > 0.0 { LEAST_WEIGHT * most } else { 1.0 };
        for x in &mut w {
            x[d] = if x[d].is_finite() {
                x[d].max(least)
            } else {
                least
            };
        }
    }
    w
}

/// The least weight of a p-curve sample relative to its parameter's largest ([`image_weights`]).
const LEAST_WEIGHT: f64 = 1e-9;

/// The largest distance of a part's curves from the reported curve on the spans of `tube`
/// (on all its spans when none is on it).
fn off_on(d: &PartData, spans: &[Span], f: &PartFit, tube: usize) -> f64 {
    let on = |want: Option<usize>| {
        f.bounds
            .iter()
            .zip(&spans[d.range.clone()])
            .filter(|(_, sp)| want.is_none_or(|t| sp.tube == t))
            .map(|(b, _)| b.off_reported)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let o = on(Some(tube));
    if o.is_finite() {
        o
    } else {
        on(None).max(0.0)
    }
}

/// A coarse breakpoint: an index into the part's fine knots and the knot's multiplicity
/// (1: the curves are C7 there; up to [`DEGREE`]: C0).
type Break = (usize, usize);

/// How many times too large each fine span's fit-dependent bounds are for the target `t`
/// (cut bounds included: the spans of a cut's tube), and the largest bound that ratio is
/// about (what the span proves now).
fn ratios(d: &PartData, spans: &[Span], f: &PartFit, t: f64) -> Vec<(f64, f64)> {
    let mut r: Vec<(f64, f64)> = f
        .bounds
        .iter()
        .zip(&spans[d.range.clone()])
        .map(|(b, sp)| {
            let room = t - sp.radius_xyz;
            let need = b
                .model
                .max(b.image_p - sp.radius_xyz)
                .max(b.image_q - sp.radius_xyz);
            let level = b.curve.max(b.image_p).max(b.image_q);
            if level <= t || room <= 0.0 {
                (0.0, level)
            } else {
                (need / room, level)
            }
        })
        .collect();
    for &(tube, base) in &d.cuts {
        let off = off_on(d, spans, f, tube);
        let level = poly::add_up(base, off);
        let q = if level > t && base < t {
            off / (t - base)
        } else {
            0.0
        };
        for (m, sp) in spans[d.range.clone()].iter().enumerate() {
            if sp.tube == tube {
                r[m] = (r[m].0.max(q), r[m].1.max(level));
            }
        }
    }
    r
}

/// The edge of the parts in order (each part's segments in the edge's direction). `closed`:
/// the edge's last point is its first; `pcurve_closed`: so are the p-curves' (one part, closed
/// by its own certificate rather than across a seam); `requested`: the tolerance asked for.
///
/// [`FINE_PER_LINK`] fine spans per link; per part, coarse curves (3D and p-curves, one knot vector) on a
/// subset of the fine knots, fitted by least squares and bounded on every fine span; coarse
/// spans whose bounds exceed the target are cut at fine knots and the part fitted again.
pub(crate) fn assemble(
    parts: &[Part],
    closed: bool,
    pcurve_closed: bool,
    requested: Option<f64>,
) -> Result<Edge, EdgeError> {
    let missed = |e: &Edge| requested.is_some_and(|r| e.edge_tolerance > r);
    let build = |dense: &[(usize, usize)], least_room: bool| {
        assemble_with(parts, closed, pcurve_closed, requested, dense, least_room)
    };
    let first = build(&[], false)?;
    if !missed(&first.edge) {
        // Knots raised in multiplicity where every fine knot was already a break: more fine
        // spans there usually do with fewer control points (S31/S32's first loop at 1e-7: 153
        // control points, 13 knots of multiplicity 5 in a row).
        if !first.raised.is_empty() {
            let dense = build(&first.raised, false)?.edge;
            if !missed(&dense) && dense.curve.points.len() < first.edge.curve.points.len() {
                return Ok(dense);
            }
        }
        return Ok(first.edge);
    }
    let mut best = first.edge;
    // The stalled spans' links cut into more fine spans: the coarse knots can then fall
    // closer together there (Viviani's arcs asked for 1.05x their certificate stalled at
    // 1.07x in a long link's two fine spans; with four they meet the request).
    if matches!(best.shortfall, Some(Shortfall::FitStalled { .. })) && !first.stalled.is_empty() {
        let dense = build(&first.stalled, false)?.edge;
        if dense.edge_tolerance < best.edge_tolerance {
            best = dense;
        }
        if !missed(&best) {
            return Ok(best);
        }
    }
    // Still missed with more room than the least: the stalls depend on the aim (a region
    // stalls at a level that another aim passes), so aim at the least room too and keep the
    // closer edge. Last, since that aim costs control points: Fig. 7's third loop at 1e-9,
    // 426 where the dense spans would do.
    if first.least_room_differs {
        let least = build(&first.stalled, true)?.edge;
        if least.edge_tolerance < best.edge_tolerance {
            best = least;
        }
    }
    Ok(best)
}

/// An edge of [`assemble_with`], the links holding a span above the request (part, tube), the
/// links beside a raised knot, and whether the request left more room above the floor than [`LEAST_ROOM`] (and is not below
/// the floor), so that aiming at the least room is another aim.
struct Built {
    edge: Edge,
    stalled: Vec<(usize, usize)>,
    /// The links (part, tube) next to an interior coarse knot of raised multiplicity.
    raised: Vec<(usize, usize)>,
    least_room_differs: bool,
}

/// The fine spans of the parts (in order), their nominal arc lengths, and each part's range
/// of them: [`FINE_PER_LINK`] per link, [`DENSE_FINE_PER_LINK`] in the links `dense`.
#[allow(clippy::type_complexity)]
fn fine_spans(
    parts: &[Part],
    dense: &[(usize, usize)],
) -> (Vec<Span>, Vec<f64>, Vec<std::ops::Range<usize>>) {
    let mut spans = Vec::new();
    let mut ds = Vec::new();
    let mut ranges = Vec::with_capacity(parts.len());
    for (pi, pt) in parts.iter().enumerate() {
        let start = spans.len();
        let fine = |s: &Seg| {
            if dense.contains(&(pi, s.tube)) {
                DENSE_FINE_PER_LINK
            } else {
                FINE_PER_LINK
            }
        };
        for (s, k, fine) in pt.segs.iter().flat_map(|s| {
            let f = fine(s);
            (0..f).map(move |k| (s, k, f))
        }) {
            let t = &pt.cert.tubes[s.tube];
            // Piece k runs between the cut points k and k + 1, each computed once, so that
            // neighbouring pieces share their end exactly (no gap of an ulp between them).
            let cut = |i: usize| match i {
                0 => s.ta,
                i if i == fine => s.tb,
                i => s.ta + (s.tb - s.ta) * i as f64 / fine as f64,
            };
            let (ta, tb) = (cut(k), cut(k + 1));
            let y = poly::reparametrised(&t.coeffs, ta, tb);
            let (warp, len) = arc_length_warp(pt.p, &y);
            ds.push(len);
            spans.push(Span {
                tube: s.tube,
                fixed: SpanFixed::of(pt.p, pt.q, &y, &warp),
                warp,
                y,
                radius_param: t.radius_param,
                radius_xyz: t.radius_xyz,
            });
        }
        ranges.push(start..spans.len());
    }
    (spans, ds, ranges)
}

/// Fine spans per link in the links of [`assemble_with`]'s `dense`.
const DENSE_FINE_PER_LINK: usize = 2 * FINE_PER_LINK;

/// [`assemble`]'s one build: [`DENSE_FINE_PER_LINK`] fine spans in the links `dense` (part,
/// tube), aimed at the request (or above the floor, [`target`]) or, with `least_room`, at
/// [`LEAST_ROOM`] times the floor.
fn assemble_with(
    parts: &[Part],
    closed: bool,
    pcurve_closed: bool,
    requested: Option<f64>,
    dense: &[(usize, usize)],
    least_room: bool,
) -> Result<Built, EdgeError> {
    let cert_tol = parts
        .iter()
        .map(|p| p.cert.certified_tolerance)
        .fold(0.0, f64::max);
    let (spans, ds, ranges) = fine_spans(parts, dense);
    if spans.is_empty() || ranges.iter().any(|r| r.is_empty()) {
        return Err(EdgeError::NotGapFree {
            branch: parts.first().map(|p| p.branch).unwrap_or(0),
            reason: "nothing left after cutting".into(),
        });
    }
    let mut knots_s = vec![0.0];
    for &d in &ds {
        let last: f64 = *knots_s.last().unwrap_or(&0.0);
        // Strictly increasing knots, also over a span of (nearly) zero length.
        let floor = 4.0 * f64::EPSILON * last.abs().max(1.0);
        knots_s.push(last + d.max(floor));
    }
    let model_at = |i: usize, u: f64| {
        let x = eval_mid(&spans[i].y, u);
        (parts_p(parts, &ranges, i).point_f64(x[0], x[1]), x)
    };
    let n = parts.len();
    let mut data = Vec::with_capacity(n);
    let mut floor = cert_tol;
    for (k, pt) in parts.iter().enumerate() {
        let r = ranges[k].clone();
        let start3 = model_at(r.start, 0.0).0;
        let end3 = if k + 1 < n {
            model_at(ranges[k + 1].start, 0.0).0
        } else if closed {
            model_at(0, 0.0).0
        } else {
            model_at(r.end - 1, 1.0).0
        };
        let start4 = model_at(r.start, 0.0).1;
        let end4 = if pcurve_closed && n == 1 {
            start4
        } else {
            model_at(r.end - 1, 1.0).1
        };
        let cuts: Vec<(usize, f64)> = pt
            .cuts
            .iter()
            .map(|c| {
                let t = &pt.cert.tubes[c.tube];
                let mut m = model_box(pt.p, &t.coeffs, c.gap);
                let mut rad = t.radius_xyz;
                if let Some((tube, range)) = c.next {
                    // The cut's range goes on into the next link: its reported points too.
                    let nt = &pt.cert.tubes[tube];
                    let mn = model_box(pt.p, &nt.coeffs, range);
                    m = std::array::from_fn(|i| m[i].convex_hull(mn[i]));
                    rad = rad.max(nt.radius_xyz);
                }
                // (Across a corner, the true arc between the parts lies in the corner box, whose
                // diameter adds to the share.)
                let share = poly::add_up(rad, box_diameter(&m));
                (c.tube, poly::add_up(share, c.corner))
            })
            .collect();
        floor = cuts.iter().map(|c| c.1).fold(floor, f64::max);
        data.push(PartData {
            pt,
            range: r,
            ends_xyz: [start3, end3],
            ends_param: [start4, end4],
            cuts,
            moved: [moved_to_pole(pt.p), moved_to_pole(pt.q)],
        });
    }
    let build = |goal: f64| -> Result<(Edge, Vec<PartFit>, bool), EdgeError> {
        let mut fits: Vec<PartFit> = data
            .iter()
            .map(|d| {
                let m = d.range.len();
                let pieces = m.div_ceil(START_SPANS).max(1);
                let mut breaks: Vec<Break> = (0..=pieces).map(|k| (k * m / pieces, 1)).collect();
                breaks.dedup_by_key(|b| b.0);
                fit_part(d, &spans, &knots_s, breaks)
            })
            .collect();
        let out_of_rounds = refine_all(&data, &spans, &knots_s, &mut fits, goal);
        for (d, f) in data.iter().zip(fits.iter_mut()) {
            coarsen(d, &spans, &knots_s, f, goal);
        }
        let e = finish(&data, &spans, &fits, closed, cert_tol)?;
        Ok((e, fits, out_of_rounds))
    };
    let goal = target(floor, requested);
    let least = LEAST_ROOM * floor;
    let (mut e, fits, out_of_rounds) = build(if least_room { least } else { goal })?;
    e.requested = requested;
    e.shortfall = requested.filter(|&r| e.edge_tolerance > r).map(|r| {
        shortfall(
            &data,
            &spans,
            &fits,
            [floor, e.edge_tolerance],
            r,
            out_of_rounds,
        )
    });
    let mut stalled = Vec::new();
    if let Some(r) = requested {
        for (pi, (d, f)) in data.iter().zip(&fits).enumerate() {
            for (m, x) in ratios(d, &spans, f, r).iter().enumerate() {
                let key = (pi, spans[d.range.start + m].tube);
                if x.1 > r && !stalled.contains(&key) {
                    stalled.push(key);
                }
            }
        }
    }
    let mut raised = Vec::new();
    for (pi, (d, f)) in data.iter().zip(&fits).enumerate() {
        let last = d.range.len();
        for &(at, _) in f.breaks.iter().filter(|b| b.1 > 1 && b.0 > 0 && b.0 < last) {
            for m in [at - 1, at] {
                let key = (pi, spans[d.range.start + m].tube);
                if !raised.contains(&key) {
                    raised.push(key);
                }
            }
        }
    }
    Ok(Built {
        edge: e,
        stalled,
        raised,
        least_room_differs: requested.is_some_and(|r| floor <= r && goal > least),
    })
}

/// Why the final fits' tolerance is above the request `r`.
fn shortfall(
    data: &[PartData],
    spans: &[Span],
    fits: &[PartFit],
    [floor, reached]: [f64; 2],
    r: f64,
    out_of_rounds: bool,
) -> Shortfall {
    // The certificates explain a miss only when the edge came near their floor (its curves
    // aim a quarter above it); far above it, the fit is the cause (a p-curve that turns too
    // fast for it next to a pole).
    if floor > r && reached <= 2.0 * floor {
        return Shortfall::Certificate { floor };
    }
    if out_of_rounds {
        return Shortfall::Rounds { rounds: ROUNDS };
    }
    let above: Vec<f64> = data
        .iter()
        .zip(fits)
        .flat_map(|(d, f)| ratios(d, spans, f, r))
        .map(|x| x.1)
        .filter(|&l| l > r)
        .collect();
    Shortfall::FitStalled {
        spans: above.len(),
        level: above.iter().copied().fold(0.0, f64::max),
    }
}

/// The surface P of the part holding span `i`.
fn parts_p<'a>(
    parts: &'a [Part],
    ranges: &[std::ops::Range<usize>],
    i: usize,
) -> &'a RationalBezierPatch {
    let k = ranges.iter().position(|r| r.contains(&i)).unwrap_or(0);
    parts[k].p
}

/// The edge of the final fits: its curves and bounds.
fn finish(
    data: &[PartData],
    spans: &[Span],
    fits: &[PartFit],
    closed: bool,
    cert_tol: f64,
) -> Result<Edge, EdgeError> {
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
    let mut knots = Vec::new();
    let mut points = Vec::new();
    let mut pcurves = Vec::new();
    for (k, (d, f)) in data.iter().zip(fits).enumerate() {
        if k == 0 {
            knots.extend_from_slice(&f.knots[..f.knots.len() - 1]);
            points.extend_from_slice(&f.xyz);
        } else {
            knots.extend_from_slice(&f.knots[DEGREE + 1..f.knots.len() - 1]);
            points.extend_from_slice(&f.xyz[1..]);
        }
        let (mut prm, mut img) = ([0.0f64; 2], [0.0f64; 2]);
        for sb in &f.bounds {
            prm = [prm[0].max(sb.delta_p), prm[1].max(sb.delta_q)];
            img = [img[0].max(sb.image_p), img[1].max(sb.image_q)];
            b.curve_3d = b.curve_3d.max(sb.curve);
            b.model_fit = b.model_fit.max(sb.model);
            b.same_parameter = b.same_parameter.max(sb.same_parameter);
        }
        for &(tube, base) in &d.cuts {
            // A true point of the cut's arc is within `base` (the tube's radius and the
            // diameter of the reported points over the cut's range) of the reported point at
            // the cut, and that within `off` of each of the edge's three curves at its end.
            let cut = poly::add_up(base, off_on(d, spans, f, tube));
            b.cuts = b.cuts.max(cut);
        }
        b.pcurve_p_param = b.pcurve_p_param.max(prm[0]);
        b.pcurve_q_param = b.pcurve_q_param.max(prm[1]);
        b.pcurve_p_image = b.pcurve_p_image.max(img[0]);
        b.pcurve_q_image = b.pcurve_q_image.max(img[1]);
        for surface in 0..2 {
            pcurves.push(PCurve {
                surface,
                face: d.pt.faces[surface],
                piece: d.pt.pieces[surface],
                branch: d.pt.branch,
                curve: BSpline {
                    degree: DEGREE,
                    knots: f.knots.clone(),
                    points: f
                        .params
                        .iter()
                        .map(|x| [x[2 * surface], x[2 * surface + 1]])
                        .collect(),
                },
                param_tolerance: prm[surface],
                image_tolerance: img[surface],
            });
        }
    }
    if let Some(&last) = fits.last().and_then(|f| f.knots.last()) {
        knots.push(last);
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
            branch: data[0].pt.branch,
        });
    }
    Ok(Edge {
        curve: BSpline {
            degree: DEGREE,
            knots,
            points,
        },
        pcurves,
        closed,
        edge_tolerance,
        bounds: b,
        branches: data.iter().map(|d| d.pt.branch).collect(),
        links: data.iter().map(|d| d.pt.segs.len()).sum(),
        requested: None,
        shortfall: None,
    })
}
