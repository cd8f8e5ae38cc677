//! Checking a marched polyline against the certified curve of its branch: straying points,
//! looping, points strayed onto another branch, and how much of the certified chain the marcher
//! covered.
//!
//! # The test, in parameter space `(σ, t, u, v)`
//!
//! A certified branch proves that its true curve lies, at every arc length of a tube piece,
//! within `radius_param` (max norm) of the piece's reported polynomial, and inside the piece's
//! enclosure box. A marched point `y` carries Newton's guarantee `|P(σ,t) − Q(u,v)| ≤ tol`
//! (`MarchOptions::newton_tolerance`, model units). To first order such a point lies within
//! `slack = tol / s₃` of the curve in parameters, `s₃` being the smallest singular value of the
//! 3×4 Jacobian `[P_σ P_t −Q_u −Q_v]` at `y` (a floating-point estimate: it only sets the
//! threshold, it is not part of any bound).
//!
//! A point is **straying** from a branch when it is *proven* farther than `slack` from the
//! branch's certified curve: for every piece, a rigorous lower bound (interval arithmetic) of
//! its max-norm distance to the piece's box, or to the piece's reported polynomial minus
//! `radius_param`, exceeds `slack`. So a reported straying distance is a true lower bound on the
//! distance to the certified part of the true curve; a point that is merely hard to decide is
//! never reported. A straying point has **strayed onto** branch `j` when it is proven within
//! `radius_param + slack` of branch `j`'s reported curve (an interval upper bound at the closest
//! parameter of the polynomial), i.e. within `2·radius_param + slack` of `j`'s true curve.
//!
//! Only the certified part of the curve is compared: a run of straying points at an end of the
//! marched polyline, next to a certified end that does not cover the rest (`unproven`,
//! `singular`, `close_branches`), is **unchecked**, not straying. `boundary` and `closed_loop`
//! ends cover the branch to its end, so every point beyond them strays.
//!
//! The model-space point `xyz` of a marched point is not compared (the marcher computes it from
//! the parameters); a branch whose chain is empty counts as not certified.
//!
//! **Looping**: the marcher passed over the certified chain (of arc length `L`) more than once:
//! the arc length it passed over — the summed changes of the closest tube parameter between
//! consecutive points that lie on the reported curve (within twice the widest tube radius),
//! leaving out jumps more than twice the chord plus two certified steps long (the closest point
//! switching between the ends of a chain that does not close) — exceeds `L` by more than
//! `1% · L` plus two certified steps, where the tubes are at most `L/100` wide (else passages
//! cannot be told apart and this is not decided). This holds on any chain,
//! whether or not its closure was proven: a marcher going round a tiny loop whose certificate
//! ends `singular` on both sides is caught. On a proven closed loop also the marcher's progress
//! along the loop (unwrapped modulo `L`; not used when consecutive points are more than `L/4`
//! apart, as the direction is then unclear), or the summed chords between consecutive
//! non-straying points (never longer than the arcs they span), exceeding `L` by as much is
//! looping.
//! **Covered fraction**: the part of the certified arc length spanned by consecutive
//! non-straying marched points, so a marcher that stopped early shows a fraction below 1.

use inari::Interval;
use nalgebra::{Matrix3, Matrix3x4};

use crate::certify::curve::{CertifiedBranch, CertifiedEnd, TubePiece};
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, CurvePoint, EndReason};
use crate::numeric::scalar::point;
use crate::numeric::vec3::dist3;
use tube_distance::{closest, eval_interval, tube_lower_bound};

mod tube_distance;

/// One marched point proven off its branch's certified curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrayingPoint {
    /// Index of the point in the marched branch.
    pub index: usize,
    /// Proven lower bound of its max-norm parameter distance from the certified curve.
    pub distance: f64,
    /// Floating-point estimate of that distance (to the reported tube polynomials).
    pub estimate: f64,
    /// The slack it was compared with (`tol / s₃`, see the module docs).
    pub slack: f64,
    /// The id of another certified branch the point is proven to lie on, if any.
    pub onto: Option<usize>,
}

/// What the straying check found on one marched branch.
#[derive(Debug, Clone, PartialEq)]
pub struct StrayReport {
    /// The id of the marched branch.
    pub branch: usize,
    /// Points proven off the certified curve where the certificate covers them, in order.
    pub straying: Vec<StrayingPoint>,
    /// Indices of points not compared: beyond a certified end that does not cover the rest of
    /// the branch, or every point when the branch has no certificate.
    pub unchecked: Vec<usize>,
    /// The marcher went over the certified curve more than once (round a loop, proven closed or
    /// not, more than once).
    pub looping: bool,
    /// Fraction (0..=1) of the certified arc length spanned by consecutive non-straying marched
    /// points; 0 without a certificate.
    pub covered_fraction: f64,
    /// Length of the marched polyline in model space.
    pub marched_length: f64,
    /// Arc length of the certified chain (`s_max − s_min`); 0 without a certificate.
    pub certified_length: f64,
}

impl StrayReport {
    /// The report for a branch without a certificate: every point unchecked.
    pub fn uncertified(marched: &Branch) -> Self {
        StrayReport {
            branch: marched.id,
            straying: Vec::new(),
            unchecked: (0..marched.points.len()).collect(),
            looping: false,
            covered_fraction: 0.0,
            marched_length: marched.length(),
            certified_length: 0.0,
        }
    }

    /// Whether any point strays or the marcher looped.
    pub fn has_problems(&self) -> bool {
        !self.straying.is_empty() || self.looping
    }
}

/// Checks every marched branch against its own certificate (`certificates[k]` belongs to
/// `branches[k]`; `None` = not certified) and the others (for strays onto another branch).
/// `newton_tolerance` is the marcher's Newton tolerance (model units).
pub fn check_branches(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    branches: &[Branch],
    certificates: &[Option<&CertifiedBranch>],
    newton_tolerance: f64,
) -> Vec<StrayReport> {
    branches
        .iter()
        .enumerate()
        .map(|(k, b)| match certificates.get(k).copied().flatten() {
            Some(own) => {
                let others: Vec<(usize, &CertifiedBranch)> = branches
                    .iter()
                    .zip(certificates)
                    .enumerate()
                    .filter(|(j, _)| *j != k)
                    .filter_map(|(_, (ob, oc))| oc.map(|c| (ob.id, c)))
                    .collect();
                check_branch(p, q, b, own, &others, newton_tolerance)
            }
            None => StrayReport::uncertified(b),
        })
        .collect()
}

/// Checks one marched branch against its certificate `own` (see the module docs for the
/// test; a certificate without boxes gives [`StrayReport::uncertified`]); `others` are the
/// certified branches a straying point may have strayed onto, with their ids.
/// `newton_tolerance` is the marcher's Newton tolerance (model units).
pub fn check_branch(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    marched: &Branch,
    own: &CertifiedBranch,
    others: &[(usize, &CertifiedBranch)],
    newton_tolerance: f64,
) -> StrayReport {
    if own.boxes.is_empty() || own.boxes.len() != own.tubes.len() {
        return StrayReport::uncertified(marched);
    }
    let pts = &marched.points;
    let n = pts.len();
    let marched_length = marched.length();
    let [s_min, s_max] = certified_span(p, q, own);
    let chain = Chain {
        span: [s_min, s_max],
        length: if s_max > s_min { s_max - s_min } else { 0.0 },
        max_h: own.tubes.iter().map(|t| t.h).fold(0.0, f64::max),
        max_radius: own.tubes.iter().map(|t| t.radius_param).fold(0.0, f64::max),
        proven_loop: own.ends == [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop],
    };

    // Per point: proven far (with bounds), or near with its arc length on the certified chain.
    let slacks: Vec<f64> = pts
        .iter()
        .map(|c| slack(p, q, c, newton_tolerance))
        .collect();
    let verdicts: Vec<Verdict> = pts
        .iter()
        .zip(&slacks)
        .map(|(c, &sl)| locate(own, &params(c), sl))
        .collect();
    // The marched polyline of a closed loop repeats its first point at the end: cyclic.
    let cyclic = n > 2
        && marched.ends == [EndReason::ClosedLoop; 2]
        && pts[0].p == pts[n - 1].p
        && pts[0].q == pts[n - 1].q;
    let located = Located {
        pts,
        slacks,
        verdicts,
        cyclic,
    };

    let (straying, unchecked) = located.straying(own, &chain, others);
    let (covered_fraction, looping) = located.progress(&chain, &unchecked);
    StrayReport {
        branch: marched.id,
        straying,
        unchecked,
        looping,
        covered_fraction,
        marched_length,
        certified_length: chain.length,
    }
}

/// The certified chain as the check sees it.
struct Chain {
    /// Its arc-length range `[s_min, s_max]` ([`certified_span`]).
    span: [f64; 2],
    /// `s_max − s_min` (0 if empty).
    length: f64,
    /// The longest step.
    max_h: f64,
    /// The widest tube radius (parameters, max norm).
    max_radius: f64,
    /// Both ends are a proven closed loop.
    proven_loop: bool,
}

/// The marched points located on the chain, with their slacks.
struct Located<'a> {
    pts: &'a [CurvePoint],
    slacks: Vec<f64>,
    verdicts: Vec<Verdict>,
    /// The last point repeats the first (a marched closed loop).
    cyclic: bool,
}

impl Located<'_> {
    /// Whether point `i` lies on the chain's reported curve to within twice the widest tube
    /// radius (plus 1e-9 for the marched point's own accuracy): not merely unproven far, as a
    /// point across a tiny loop from the chain can be when the slack exceeds the loop.
    fn on_chain(&self, i: usize, chain: &Chain) -> bool {
        matches!(self.verdicts[i], Verdict::Near { estimate, .. } if estimate <= 2.0 * chain.max_radius + 1e-9)
    }

    /// The arc length of point `i` on the chain, unless it is proven far.
    fn near_s(&self, i: usize) -> Option<f64> {
        match self.verdicts[i] {
            Verdict::Near { s, .. } => Some(s),
            Verdict::Far { .. } => None,
        }
    }

    /// The straying points (in order, each with the branch it strayed onto, if any) and the
    /// unchecked ones (sorted): runs of far points, cyclic on a marched loop, are unchecked when
    /// they continue the march past a certified end that does not cover the rest.
    fn straying(
        &self,
        own: &CertifiedBranch,
        chain: &Chain,
        others: &[(usize, &CertifiedBranch)],
    ) -> (Vec<StrayingPoint>, Vec<usize>) {
        let (pts, slacks, verdicts) = (self.pts, &self.slacks, &self.verdicts);
        let n = pts.len();
        let [s_min, s_max] = chain.span;
        let m = if self.cyclic { n - 1 } else { n };
        let mut straying = Vec::new();
        let mut unchecked = Vec::new();
        let is_far = |i: usize| matches!(verdicts[i], Verdict::Far { .. });
        // Runs of far points (cyclic when the marched branch is a loop).
        for run in far_runs(m, self.cyclic, &is_far) {
            let neighbours = [run.before, run.after];
            let at_uncovered_end = |nb: Option<usize>, inner: usize| -> bool {
                let Some(i) = nb else { return true };
                let Some(s) = self.near_s(i) else {
                    return false;
                };
                let chord = dist3(&pts[i].xyz, &pts[inner].xyz);
                let reach = chord + chain.max_h + slacks[i];
                let end0 = !own.ends[0].reaches_true_end() && (s - s_min).abs() <= reach;
                let end1 = !own.ends[1].reaches_true_end() && (s_max - s).abs() <= reach;
                end0 || end1
            };
            let first = run.indices[0];
            let last = *run.indices.last().unwrap_or(&first);
            let whole = neighbours == [None, None];
            let tail =
                !whole && at_uncovered_end(run.before, first) && at_uncovered_end(run.after, last);
            for &i in &run.indices {
                if tail {
                    unchecked.push(i);
                    continue;
                }
                if let Verdict::Far {
                    distance, estimate, ..
                } = verdicts[i]
                {
                    let y = params(&pts[i]);
                    let onto = others
                        .iter()
                        .find(|(_, c)| on_curve(c, &y, slacks[i]))
                        .map(|(id, _)| *id);
                    straying.push(StrayingPoint {
                        index: i,
                        distance,
                        estimate,
                        slack: slacks[i],
                        onto,
                    });
                }
            }
        }
        straying.sort_by_key(|s| s.index);
        if self.cyclic && straying.iter().any(|s| s.index == 0) && n > 0 {
            // The repeated last point is the first point again.
            if let Some(first) = straying.iter().find(|s| s.index == 0).copied() {
                straying.push(StrayingPoint {
                    index: n - 1,
                    ..first
                });
            }
        }
        if self.cyclic && unchecked.contains(&0) {
            unchecked.push(n - 1);
        }
        unchecked.sort_unstable();
        (straying, unchecked)
    }

    /// Progress along the chain between consecutive near points: the covered fraction of the
    /// certified arc length, and whether the marcher went over the certified curve more than once.
    /// `unchecked` (sorted) are the points beyond uncovered certified ends.
    fn progress(&self, chain: &Chain, unchecked: &[usize]) -> (f64, bool) {
        let pts = self.pts;
        let n = pts.len();
        let [s_min, s_max] = chain.span;
        let (certified_length, proven_loop) = (chain.length, chain.proven_loop);
        let mut spans: Vec<[f64; 2]> = Vec::new();
        let mut progress = 0.0;
        let mut jumps = false;
        let mut near_chords = 0.0;
        let mut variation = 0.0;
        for i in 0..n.saturating_sub(1) {
            let (a, b) = match (self.near_s(i), self.near_s(i + 1)) {
                (Some(a), Some(b)) => (a, b),
                // The march leaves the certified arc through an end that does not cover the
                // rest: it covers the arc up to that end.
                (Some(a), None) if unchecked.binary_search(&(i + 1)).is_ok() => {
                    spans.push(nearest_end(a, s_min, s_max));
                    continue;
                }
                (None, Some(b)) if unchecked.binary_search(&i).is_ok() => {
                    spans.push(nearest_end(b, s_min, s_max));
                    continue;
                }
                _ => continue,
            };
            let mut d = b - a;
            if proven_loop && certified_length > 0.0 {
                d -= certified_length * (d / certified_length).round();
                // A jump of more than a quarter of the loop has no clear direction.
                jumps |= d.abs() > 0.25 * certified_length;
            }
            progress += d;
            let chord = dist3(&pts[i].xyz, &pts[i + 1].xyz);
            near_chords += chord;
            // Arc length passed over; a jump much longer than the chord is no passage (the
            // closest chain point switching ends beside an uncovered gap, or across a loop's
            // unproven closure).
            if d.abs() <= 2.0 * chord + 2.0 * chain.max_h
                && self.on_chain(i, chain)
                && self.on_chain(i + 1, chain)
            {
                variation += d.abs();
            }
            let (lo, hi) = if d >= 0.0 { (a, a + d) } else { (a + d, a) };
            if proven_loop {
                push_wrapped(&mut spans, lo, hi, s_min, certified_length);
            } else {
                spans.push([lo.max(s_min), hi.min(s_max)]);
            }
        }
        let covered_fraction = if certified_length > 0.0 {
            (union_length(&mut spans) / certified_length).min(1.0)
        } else {
            0.0
        };
        let margin = 0.01 * certified_length + 2.0 * chain.max_h;
        // Passages are told apart only where the tubes are much thinner than the chain is long.
        let fine = chain.max_radius <= 0.01 * certified_length;
        let looping = certified_length > 0.0
            && ((proven_loop
                && ((!jumps && progress.abs() > certified_length + margin)
                    || near_chords > certified_length + margin))
                || (fine && variation > certified_length + margin));
        (covered_fraction, looping)
    }
}

/// The arc-length range of the certified chain, `[s_min, s_max]`. At a `boundary` end the last
/// box straddles the boundary, so the range is cut where the reported tube polynomial leaves the
/// domains; on a closed loop the last step crosses the start, so the range ends at the reported
/// point closest to the start (floating-point estimates, to compare with the marcher).
fn certified_span(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    c: &CertifiedBranch,
) -> [f64; 2] {
    let lo = c.boxes.iter().map(|b| b.s[0]).fold(f64::INFINITY, f64::min);
    let hi = c
        .boxes
        .iter()
        .map(|b| b.s[1])
        .fold(f64::NEG_INFINITY, f64::max);
    let (dp, dq) = (p.domain(), q.domain());
    let inside = |y: [f64; 4]| dp.contains(y[0], y[1], 0.0) && dq.contains(y[2], y[3], 0.0);
    // The arc length where the piece's reported curve leaves the domains, by bisection between
    // its inner end (τ = 0, towards the start point) and its outer end.
    let exit = |t: &TubePiece| -> Option<f64> {
        if !inside(t.eval(0.0)) || inside(t.eval(t.h)) {
            return None;
        }
        let (mut a, mut b) = (0.0, t.h);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if inside(t.eval(m)) {
                a = m;
            } else {
                b = m;
            }
        }
        Some(t.arc_length_at(a))
    };
    let mut span = [lo, hi];
    if c.ends[1] == CertifiedEnd::ClosedLoop {
        // The last step crosses the start: the loop ends at the closest reported point to it.
        let start = c.start.map(|x| x.mid());
        let k = c.tubes.len().saturating_sub(3);
        let end = c.tubes[k..]
            .iter()
            .map(|t| {
                let (tau, d) = closest(t, &start);
                (d, t.arc_length_at(tau))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, s)) = end {
            span[1] = s.min(hi);
        }
        return span;
    }
    if let (CertifiedEnd::Boundary { .. }, Some(t)) = (&c.ends[0], c.tubes.first()) {
        if let Some(s) = exit(t) {
            span[0] = s.max(lo);
        }
    }
    if let (CertifiedEnd::Boundary { .. }, Some(t)) = (&c.ends[1], c.tubes.last()) {
        if let Some(s) = exit(t) {
            span[1] = s.min(hi);
        }
    }
    span
}

/// The arc-length span from `s` to the nearer end of `[s_min, s_max]`.
fn nearest_end(s: f64, s_min: f64, s_max: f64) -> [f64; 2] {
    if s - s_min <= s_max - s {
        [s_min, s.max(s_min)]
    } else {
        [s.min(s_max), s_max]
    }
}

/// Where a marched point is relative to a certified chain.
#[derive(Debug, Clone, Copy)]
enum Verdict {
    /// Proven farther than the slack: `distance` is the proven lower bound.
    Far { distance: f64, estimate: f64 },
    /// Not proven far; `s` is the arc length of the closest reported tube point and `estimate`
    /// the distance to it (estimates).
    Near { s: f64, estimate: f64 },
}

fn params(c: &CurvePoint) -> [f64; 4] {
    [c.p[0], c.p[1], c.q[0], c.q[1]]
}

/// `tol / s₃`: the parameter distance from the curve, to first order, of a point with
/// `|P − Q| ≤ tol` (`s₃` the smallest singular value of `[P_σ P_t −Q_u −Q_v]`). Infinite where
/// the Jacobian is (nearly) rank deficient: such a point is never called straying.
fn slack(p: &RationalBezierPatch, q: &RationalBezierPatch, c: &CurvePoint, tol: f64) -> f64 {
    let (a, b) = (p.derivs_f64(c.p[0], c.p[1]), q.derivs_f64(c.q[0], c.q[1]));
    let j = Matrix3x4::from_fn(|r, col| match col {
        0 => a.su[r],
        1 => a.sv[r],
        2 => -b.su[r],
        _ => -b.sv[r],
    });
    let jjt: Matrix3<f64> = j * j.transpose();
    let smallest = jjt
        .symmetric_eigenvalues()
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let s3 = smallest.max(0.0).sqrt();
    let out = tol / s3;
    if out.is_finite() && s3 > 0.0 {
        out
    } else {
        f64::INFINITY
    }
}

/// Rigorous lower bound of the max-norm distance from `y` to the box `b`.
fn box_distance(b: &[Interval; 4], y: &[f64; 4]) -> f64 {
    (0..4)
        .map(|i| (point(y[i]) - b[i]).mig())
        .fold(0.0, f64::max)
}

/// Locates `y` on the chain: proven farther than `slack` from every piece, or near.
///
/// The proof aims at half the estimated distance (so the reported lower bound is close to the
/// truth), and falls back to `slack` itself.
fn locate(c: &CertifiedBranch, y: &[f64; 4], slack: f64) -> Verdict {
    let pieces: Vec<(f64, &TubePiece)> = c
        .boxes
        .iter()
        .zip(&c.tubes)
        .map(|(bx, t)| (box_distance(&bx.params(), y), t))
        .collect();
    // The closest reported point among the pieces whose boxes come within the slack.
    let mut best: Option<(f64, f64)> = None; // (estimate, arc length)
    let mut provable = true;
    for (d_box, t) in &pieces {
        if *d_box > slack {
            continue;
        }
        let (tau, est) = closest(t, y);
        if best.is_none_or(|(e, _)| est < e) {
            best = Some((est, t.arc_length_at(tau)));
        }
        // The estimate bounds the distance from above (up to rounding): no proof beyond it.
        provable &= est - t.radius_param > slack;
    }
    let Some((estimate, s)) = best else {
        // Outside every box by more than the slack: the boxes alone prove it.
        let (distance, nearest) = pieces
            .iter()
            .fold((f64::INFINITY, None), |(d, n), (db, t)| {
                if *db < d {
                    (*db, Some(*t))
                } else {
                    (d, n)
                }
            });
        let estimate = nearest.map_or(f64::INFINITY, |t| closest(t, y).1);
        return Verdict::Far { distance, estimate };
    };
    if !provable {
        return Verdict::Near { s, estimate };
    }
    let prove = |target: f64| -> f64 {
        pieces
            .iter()
            .map(|(d_box, t)| {
                if *d_box > target {
                    return *d_box;
                }
                let (tau, _) = closest(t, y);
                d_box.max(tube_lower_bound(t, y, tau, target))
            })
            .fold(f64::INFINITY, f64::min)
    };
    let aim = 0.5 * estimate;
    let mut distance = if aim > slack { prove(aim) } else { 0.0 };
    if distance <= slack {
        distance = prove(slack);
    }
    if distance > slack {
        Verdict::Far { distance, estimate }
    } else {
        Verdict::Near { s, estimate }
    }
}

/// Whether `y` is proven within `radius_param + slack` of some piece's reported polynomial.
fn on_curve(c: &CertifiedBranch, y: &[f64; 4], slack: f64) -> bool {
    c.boxes.iter().zip(&c.tubes).any(|(bx, tube)| {
        if box_distance(&bx.params(), y) > slack {
            return false;
        }
        let (tau, _) = closest(tube, y);
        let g = eval_interval(tube, point(tau));
        let upper = (0..4)
            .map(|i| (g[i] - point(y[i])).mag())
            .fold(0.0, f64::max);
        upper <= tube.radius_param + slack
    })
}

/// A maximal run of consecutive far points, with the near points just before and after it.
struct FarRun {
    indices: Vec<usize>,
    before: Option<usize>,
    after: Option<usize>,
}

/// The maximal runs of far points among `0..m` (cyclic: the runs wrap around).
fn far_runs(m: usize, cyclic: bool, is_far: &dyn Fn(usize) -> bool) -> Vec<FarRun> {
    let mut runs = Vec::new();
    if m == 0 {
        return runs;
    }
    if (0..m).all(is_far) {
        runs.push(FarRun {
            indices: (0..m).collect(),
            before: None,
            after: None,
        });
        return runs;
    }
    // Start the scan just after a near point, so that a cyclic run is never split.
    let start = if cyclic {
        (0..m).find(|&i| !is_far(i)).map_or(0, |i| i + 1)
    } else {
        0
    };
    let mut current: Option<FarRun> = None;
    for k in 0..m {
        let i = (start + k) % m;
        if is_far(i) {
            let run = current.get_or_insert_with(|| FarRun {
                indices: Vec::new(),
                before: if cyclic || i > 0 {
                    Some((i + m - 1) % m)
                } else {
                    None
                },
                after: None,
            });
            run.indices.push(i);
        } else if let Some(mut run) = current.take() {
            run.after = Some(i);
            runs.push(run);
        }
    }
    // A cyclic scan ends on the near point it started after, so only an open scan can end
    // inside a run.
    if let Some(run) = current.take() {
        runs.push(run);
    }
    runs
}

/// Adds `[lo, hi]` (arc length on a loop of length `len` starting at `s0`) to `spans`, split
/// where it wraps.
fn push_wrapped(spans: &mut Vec<[f64; 2]>, lo: f64, hi: f64, s0: f64, len: f64) {
    if hi - lo >= len {
        spans.push([s0, s0 + len]);
        return;
    }
    let shift = ((lo - s0) / len).floor() * len;
    let (a, b) = (lo - shift, hi - shift);
    let end = s0 + len;
    if b <= end {
        spans.push([a, b]);
    } else {
        spans.push([a, end]);
        spans.push([s0, s0 + (b - end)]);
    }
}

/// Total length of the union of the spans (sorted in place).
fn union_length(spans: &mut [[f64; 2]]) -> f64 {
    spans.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let mut total = 0.0;
    let mut cur: Option<[f64; 2]> = None;
    for s in spans.iter().filter(|s| s[1] > s[0]) {
        match &mut cur {
            Some(c) if s[0] <= c[1] => c[1] = c[1].max(s[1]),
            _ => {
                if let Some(c) = cur {
                    total += c[1] - c[0];
                }
                cur = Some(*s);
            }
        }
    }
    if let Some(c) = cur {
        total += c[1] - c[0];
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_of_spans_merges_overlaps() {
        let mut s = vec![[0.0, 1.0], [0.5, 2.0], [3.0, 4.0]];
        assert_eq!(union_length(&mut s), 3.0);
    }

    #[test]
    fn wrapped_span_is_split_at_the_loop_end() {
        let mut s = Vec::new();
        push_wrapped(&mut s, 9.0, 11.0, 0.0, 10.0);
        assert_eq!(s, vec![[9.0, 10.0], [0.0, 1.0]]);
    }

    #[test]
    fn cyclic_runs_wrap_around() {
        let far = [true, false, false, true, true];
        let runs = far_runs(5, true, &|i| far[i]);
        assert_eq!(runs.len(), 1);
        assert_eq!(runs[0].indices, vec![3, 4, 0]);
        assert_eq!((runs[0].before, runs[0].after), (Some(2), Some(1)));
        let open = far_runs(5, false, &|i| far[i]);
        assert_eq!(open.len(), 2);
        assert_eq!((open[0].before, open[0].after), (None, Some(1)));
        assert_eq!((open[1].before, open[1].after), (Some(2), None));
    }
}
