//! Certified tangential contacts: the tangential ODE per step, its case per step, and a contact
//! cover that provably holds every intersection point around it.
//!
//! [`certify_contact`] starts from a point of a tangential contact (e.g. a marcher contact event)
//! and reports three things with different strengths:
//!
//! 1. **Tube** (a solution, not an intersection proof): the tangential field
//!    ([`TangentialOde`]) is integrated both ways on the validated engine, the halves on two
//!    threads (the engine sees the same field in ratio form, [`RatioTangentialOde`], on lean
//!    polynomial patches, [`ContactPatch`], for longer and cheaper steps). Each step proves that
//!    every solution from the start box exists and lies in the step's a-priori box and within
//!    the tube piece's radius of its polynomial. Exact tangency along a curve cannot be proven in
//!    interval arithmetic, so this is "the solution of the tangential direction field from the
//!    start", which is the contact curve when the start lies on it.
//! 2. **Case per step**: on each a-priori box (widened by
//!    [`ContactOptions::classify_radius`]) `|N^P × N^Q|²` is enclosed; if it is bounded away from
//!    zero the step is [`StepCase::Transversal`], else the contact quadratic is classified
//!    ([`crate::pair::contact_quadratic::classify`] with [`Proven`] signs, in a scaled form).
//!    The tracer stops, with the case as the reason, as soon as a step is not a
//!    [`StepCase::TangentialCurve`] (the contact opens into a crossing, splits into branches, or
//!    becomes a point or higher-order contact).
//! 3. **Cover** (proven): [`contact_cover`] over the tube's boxes widened by
//!    [`ContactOptions::cover_margin`]: every intersection point of that region lies in a kept
//!    box.

use crate::certify::budget::{h_max_for, StepBudget};
use crate::certify::contact_cover::{contact_cover, ContactCover, CoverOptions};
use crate::certify::contact_patch::ContactPatch;
use crate::certify::curve::TubePiece;
use crate::certify::tangential_ode::{
    pivot_sign, RatioTangentialOde, ScaledContact, TangentialOde,
};
use crate::certify::trace::tube_piece;
use crate::error::{Error, Result};
use crate::geometry::surface::{pair_bounds, pair_widths};
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Event, EventKind};
use crate::numeric::scalar::{interval, point};
use crate::pair::centred_second_order::CentredSecondOrder;
use crate::pair::contact_quadratic::{
    classify, contact_quadratic, tangential_velocity, ContactCase, Proven, TangentialFormula,
};
use crate::validated::{Integrator, IntegratorOptions, IntegratorState};
use inari::Interval;
use rayon::prelude::*;

/// What one parameter box is, decided in interval arithmetic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepCase {
    /// `|N^P × N^Q|² > 0` proven on the box: no tangency anywhere in it.
    Transversal,
    /// Normals may be parallel and Δ < 0 proven: an isolated contact point (if any).
    IsolatedPoint,
    /// Normals may be parallel and Δ > 0 proven: two branches cross (if they meet).
    BranchPoint,
    /// Normals may be parallel, Δ ∋ 0 and some b ≠ 0: a tangential curve with one direction.
    TangentialCurve,
    /// Normals may be parallel and every b ∋ 0: higher-order contact, undecidable here.
    HigherOrder,
    /// The quantities cannot be enclosed on the box (e.g. a degenerate normal).
    Undefined,
}

impl From<ContactCase> for StepCase {
    fn from(c: ContactCase) -> Self {
        match c {
            ContactCase::IsolatedPoint => StepCase::IsolatedPoint,
            ContactCase::BranchPoint => StepCase::BranchPoint,
            ContactCase::TangentialCurve => StepCase::TangentialCurve,
            ContactCase::HigherOrder => StepCase::HigherOrder,
        }
    }
}

/// The case of the box `y = ([σ], [t], [u], [v])`: [`StepCase::Transversal`] if
/// `|N^P × N^Q|² > 0` is proven on it, otherwise the interval class of its contact quadratic
/// (scaled form, [`ScaledContact`], with both surfaces written around the box centre). An
/// undecided box is bisected (at most [`CLASSIFY_LEAVES`] pieces); transversal pieces hold no
/// tangency and are ignored, and the remaining pieces must agree. Every verdict other than
/// `HigherOrder`/`Undefined` is proven for the whole box.
pub fn classify_box<P, Q>(p: &P, q: &Q, y: &[Interval; 4]) -> StepCase
where
    P: CentredSecondOrder + ?Sized,
    Q: CentredSecondOrder + ?Sized,
{
    let mut work = vec![*y];
    let mut leaves = 0;
    let mut found: Option<StepCase> = None;
    while let Some(b) = work.pop() {
        let case = classify_piece(p, q, &b);
        let undecided = matches!(case, StepCase::HigherOrder | StepCase::Undefined);
        if undecided && leaves + work.len() + 2 <= CLASSIFY_LEAVES {
            let k = (0..4)
                .max_by(|&i, &j| b[i].wid().total_cmp(&b[j].wid()))
                .unwrap_or(0);
            let m = b[k].mid();
            for half in [interval(b[k].inf(), m), interval(m, b[k].sup())]
                .into_iter()
                .flatten()
            {
                let mut c = b;
                c[k] = half;
                work.push(c);
            }
            continue;
        }
        leaves += 1;
        if case == StepCase::Transversal {
            continue;
        }
        match found {
            None => found = Some(case),
            Some(f) if f == case => {}
            Some(_) => return StepCase::HigherOrder,
        }
    }
    found.unwrap_or(StepCase::Transversal)
}

/// Most pieces [`classify_box`] splits an undecided box into.
pub const CLASSIFY_LEAVES: usize = 64;

/// One interval evaluation of the case on a box (no bisection).
fn classify_piece<P, Q>(p: &P, q: &Q, y: &[Interval; 4]) -> StepCase
where
    P: CentredSecondOrder + ?Sized,
    Q: CentredSecondOrder + ?Sized,
{
    let c: [Interval; 4] = y.map(|x| point(x.mid()));
    let sp = p.second_order_centred(y[0], y[1], c[0], c[1]);
    let sq = q.second_order_centred(y[2], y[3], c[2], c[3]);
    let k = ScaledContact::new(&sp, &sq);
    let m2 = k.cross_norm_sqr;
    if m2.is_empty() {
        return StepCase::Undefined;
    }
    if m2.inf() > 0.0 {
        return StepCase::Transversal;
    }
    let all = [k.discriminant, k.b11, k.b12, k.b22];
    if all.iter().any(|x| x.is_empty()) || k.d.contains(0.0) {
        return StepCase::Undefined;
    }
    classify(k.discriminant, [k.b11, k.b12, k.b22], &Proven).into()
}

/// Parameters of [`certify_contact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactOptions {
    /// The validated steps and the budget of each half (default [`StepBudget::CONTACT`]; below
    /// the smallest step a half ends as [`ContactEnd::StepFailed`]).
    pub steps: StepBudget,
    /// Half-width of the start box around the given start (parameter units; 0: a point).
    pub start_radius: f64,
    /// Each a-priori box is widened by this (parameter units) before it is classified, so a
    /// start a little off the contact curve (a marcher point) still sees its tangency.
    pub classify_radius: f64,
    /// The cover searches the tube's boxes widened by this fraction of each domain width.
    pub cover_margin: f64,
    /// Cover resolution and budget.
    pub cover: CoverOptions,
}

impl Default for ContactOptions {
    fn default() -> Self {
        ContactOptions {
            steps: StepBudget::CONTACT,
            start_radius: 0.0,
            classify_radius: 1e-7,
            cover_margin: 1.0 / 64.0,
            cover: CoverOptions::default(),
        }
    }
}

/// Why one half of a contact trace ends.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactEnd {
    /// The tube left the domain of surface `surface` (0 = P, 1 = Q): its end box lies wholly
    /// outside.
    Boundary {
        /// 0 for P, 1 for Q.
        surface: usize,
    },
    /// The last step's box is no longer a tangential curve (its case says what it is).
    CaseChanged {
        /// The case of the last step.
        case: StepCase,
        /// Its a-priori box.
        near: [Interval; 4],
    },
    /// A validated step could not be proven (e.g. the root vector vanishes).
    StepFailed {
        /// The engine's reason.
        reason: String,
        /// The enclosure reached.
        near: [Interval; 4],
    },
    /// The step or length budget is spent.
    Budget {
        /// Arc length reached.
        length: f64,
    },
    /// The start itself is not a tangential curve: nothing was traced.
    NotTraced,
}

/// One validated step of the tangential ODE.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactStep {
    /// Arc-length range from the start (negative backwards).
    pub s: [f64; 2],
    /// The a-priori box `([σ], [t], [u], [v])`: every solution from the start box over `s`.
    pub apriori: [Interval; 4],
    /// `P([σ],[t])`: the model-space image of the a-priori box on P.
    pub xyz: [Interval; 3],
    /// The case of the a-priori box (widened by the classify radius).
    pub case: StepCase,
}

/// What [`certify_contact`] reports; see the module documentation for the strength of each part.
#[derive(Debug, Clone, PartialEq)]
pub struct CertifiedContact {
    /// The start box.
    pub start: [Interval; 4],
    /// The case of the start box (widened by the classify radius).
    pub start_case: StepCase,
    /// The steps, backward half reversed then forward half: arc length increases.
    pub steps: Vec<ContactStep>,
    /// One tube piece per step (same order): the solution of the tangential field from the
    /// start box stays within `radius_xyz` of the piece's model curve.
    pub tubes: Vec<TubePiece>,
    /// Largest model-space tube radius.
    pub tube_radius: f64,
    /// Ends of the backward and forward halves.
    pub ends: [ContactEnd; 2],
    /// The proven cover of the region around the tube.
    pub cover: ContactCover,
    /// Diagnostic (plain f64, not a bound): largest model-space distance from a cover box's
    /// centre to the tube's sampled model curve (the start point if nothing was traced).
    pub cover_band: f64,
    /// What is proven, in words, with the figures of this result.
    pub proven_statement: String,
}

impl CertifiedContact {
    /// Number of steps of each case, in the order of first appearance.
    pub fn case_counts(&self) -> Vec<(StepCase, usize)> {
        let mut out: Vec<(StepCase, usize)> = Vec::new();
        for s in &self.steps {
            match out.iter_mut().find(|(c, _)| *c == s.case) {
                Some(e) => e.1 += 1,
                None => out.push((s.case, 1)),
            }
        }
        out
    }
}

fn widen4(y: &[Interval; 4], r: [f64; 4]) -> [Interval; 4] {
    std::array::from_fn(|i| {
        interval(y[i].inf() - r[i], y[i].sup() + r[i]).unwrap_or(Interval::ENTIRE)
    })
}

fn mids(y: &[Interval; 4]) -> [f64; 4] {
    y.map(|x| x.mid())
}

fn to4(v: &[Interval]) -> [Interval; 4] {
    [v[0], v[1], v[2], v[3]]
}

/// Certifies what can be certified about the tangential contact through `start ≈ (σ, t, u, v)`
/// (module documentation). If the start box is not a tangential curve, nothing is traced and the
/// cover searches the start box widened by the cover margin (e.g. around an isolated contact).
///
/// Errors: a non-finite start or bad options ([`Error::Certification`],
/// [`Error::BadIntegratorSetup`]).
pub fn certify_contact(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    start: [f64; 4],
    opts: &ContactOptions,
) -> Result<CertifiedContact> {
    let fail = |reason: &str| Error::Certification {
        reason: reason.to_string(),
        near: start,
    };
    if start.iter().any(|x| !x.is_finite()) {
        return Err(fail("non-finite start point"));
    }
    let radii_ok = [opts.start_radius, opts.classify_radius, opts.cover_margin]
        .iter()
        .all(|r| r.is_finite() && *r >= 0.0);
    if !radii_ok {
        return Err(Error::BadIntegratorSetup(
            "contact radii and margin must be finite and non-negative".into(),
        ));
    }
    let y0: [Interval; 4] = widen4(&start.map(point), [opts.start_radius; 4]);
    let start_case = classify_box(p, q, &widen4(&y0, [opts.classify_radius; 4]));
    let (mut steps, mut tubes) = (Vec::new(), Vec::new());
    let mut ends = [ContactEnd::NotTraced, ContactEnd::NotTraced];
    if start_case == StepCase::TangentialCurve {
        let c0 = contact_quadratic(p, q, &start);
        let v_ref = tangential_velocity(&c0, TangentialFormula::choose(&c0), 1.0);
        if v_ref.iter().any(|x| !x.is_finite()) {
            return Err(fail("the tangential direction is undefined at the start"));
        }
        let (lp, lq) = (ContactPatch::new(p), ContactPatch::new(q));
        let lean = (&lp, &lq);
        // The halves are independent: one thread each.
        let (backward, forward) = rayon::join(
            || trace_half(p, q, lean, &y0, v_ref.map(|x| -x), -1.0, opts),
            || trace_half(p, q, lean, &y0, v_ref, 1.0, opts),
        );
        let (backward, forward) = (backward?, forward?);
        steps.extend(backward.steps.into_iter().rev());
        tubes.extend(backward.tubes.into_iter().rev());
        steps.extend(forward.steps);
        tubes.extend(forward.tubes);
        ends = [backward.end, forward.end];
    }
    let widths = pair_widths(&p.domain(), &q.domain());
    let margin = widths.map(|w| opts.cover_margin * w);
    let region = if steps.is_empty() {
        vec![widen4(&y0, margin)]
    } else {
        grouped_region(&steps, &widths, margin)
    };
    let cover = contact_cover(p, q, &region, &opts.cover);
    // (Non-finite samples never lower a minimum: left out.)
    let mut samples = tube_samples(p, &tubes, start);
    samples.retain(|s| s.iter().all(|x| x.is_finite()));
    samples.sort_by(|a, b| a[0].total_cmp(&b[0]));
    // (On two threads; the maximum does not depend on the order.)
    let cover_band = cover
        .boxes
        .par_iter()
        .map(|b| nearest_sqr(&b.xyz.map(|x| x.mid()), &samples).sqrt())
        .reduce(|| 0.0, f64::max);
    let tube_radius = tubes.iter().map(|t| t.radius_xyz).fold(0.0, f64::max);
    let proven_statement = statement(&steps, tube_radius, &cover, opts);
    Ok(CertifiedContact {
        start: y0,
        start_case,
        steps,
        tubes,
        tube_radius,
        ends,
        cover,
        cover_band,
        proven_statement,
    })
}

/// [`certify_contact`] from a marcher's contact events: one result per [`EventKind::Singular`]
/// event whose parameters are not already inside the searched region of an earlier result.
///
/// Each result starts from the pending event nearest the centroid of all pending events (in
/// parameters), not from the first one: along a contact curve the marcher reports events all
/// the way, and a start in their middle gives two halves of similar length, which trace on two
/// threads (from an end, one half would carry the whole curve).
pub fn certify_contact_events(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    events: &[Event],
    opts: &ContactOptions,
) -> Result<Vec<CertifiedContact>> {
    let mut out: Vec<CertifiedContact> = Vec::new();
    let (dp, dq) = (p.domain(), q.domain());
    // A located contact point may sit a rounding-sized distance outside a domain: clamp it in,
    // so that it is recognised inside an earlier contact's (clipped) region.
    let mut pending: Vec<[f64; 4]> = events
        .iter()
        .filter(|e| e.kind == EventKind::Singular)
        .map(|e| {
            std::array::from_fn(|i| {
                let [lo, hi] = pair_bounds(&dp, &dq, i);
                [e.p[0], e.p[1], e.q[0], e.q[1]][i].clamp(lo, hi)
            })
        })
        .collect();
    loop {
        if let Some(last) = out.last() {
            pending.retain(|y| {
                !last
                    .cover
                    .region
                    .iter()
                    .any(|r| r.iter().zip(y).all(|(x, v)| x.contains(*v)))
            });
        }
        let Some(start) = central(&pending) else {
            return Ok(out);
        };
        let y = pending.remove(start);
        out.push(certify_contact(p, q, y, opts)?);
    }
}

/// The index of the point nearest the centroid of `points` (the first of equals); `None` if
/// there are none.
fn central(points: &[[f64; 4]]) -> Option<usize> {
    let n = points.len() as f64;
    let c: [f64; 4] = std::array::from_fn(|i| points.iter().map(|y| y[i]).sum::<f64>() / n);
    let dist = |y: &[f64; 4]| (0..4).map(|i| (y[i] - c[i]).powi(2)).sum::<f64>();
    (0..points.len()).min_by(|&a, &b| dist(&points[a]).total_cmp(&dist(&points[b])))
}

/// The searched region: runs of consecutive a-priori boxes whose hull spans at most two
/// margins (relative to the domain widths), each hull widened by the margin. (Longer runs save
/// duplicated work where region boxes overlap, but a hull of a diagonal run reaches far from
/// the curve and the cover then keeps more boxes.)
fn grouped_region(
    steps: &[ContactStep],
    widths: &[f64; 4],
    margin: [f64; 4],
) -> Vec<[Interval; 4]> {
    let span = 2.0
        * margin
            .iter()
            .zip(widths)
            .map(|(m, w)| m / w)
            .fold(0.0, f64::max);
    let mut out = Vec::new();
    let mut hull: Option<[Interval; 4]> = None;
    for s in steps {
        let joined = match hull {
            None => s.apriori,
            Some(h) => std::array::from_fn(|i| h[i].convex_hull(s.apriori[i])),
        };
        let too_long = (0..4).any(|i| joined[i].wid() > span * widths[i]);
        match hull {
            Some(h) if too_long => {
                out.push(widen4(&h, margin));
                hull = Some(s.apriori);
            }
            _ => hull = Some(joined),
        }
    }
    out.extend(hull.map(|h| widen4(&h, margin)));
    out
}

/// The smallest squared distance from `c` to the finite points `sorted` (sorted by their first
/// coordinate; `+∞` if there are none): outwards from `c`'s place in that order, each way until
/// the first coordinate alone is as far as the nearest point found. The same value as the
/// minimum over all of them (the same sums, compared), far fewer of them.
fn nearest_sqr(c: &[f64; 3], sorted: &[[f64; 3]]) -> f64 {
    let d = |s: &[f64; 3]| (c[0] - s[0]).powi(2) + (c[1] - s[1]).powi(2) + (c[2] - s[2]).powi(2);
    if !c.iter().all(|x| x.is_finite()) {
        return sorted.iter().map(d).fold(f64::INFINITY, f64::min);
    }
    let at = sorted.partition_point(|s| s[0] < c[0]);
    let mut best = f64::INFINITY;
    for s in &sorted[at..] {
        if (s[0] - c[0]).powi(2) >= best {
            break;
        }
        best = best.min(d(s));
    }
    for s in sorted[..at].iter().rev() {
        if (c[0] - s[0]).powi(2) >= best {
            break;
        }
        best = best.min(d(s));
    }
    best
}

/// Model-space points of the tube polynomials (f64), or the start point's image.
fn tube_samples(p: &RationalBezierPatch, tubes: &[TubePiece], start: [f64; 4]) -> Vec<[f64; 3]> {
    let mut out = vec![p.point_f64(start[0], start[1])];
    for t in tubes {
        for k in 0..=16 {
            let y = t.eval(t.h * k as f64 / 16.0);
            out.push(p.point_f64(y[0], y[1]));
        }
    }
    out
}

fn statement(
    steps: &[ContactStep],
    tube: f64,
    cover: &ContactCover,
    opts: &ContactOptions,
) -> String {
    let tangential = steps
        .iter()
        .filter(|s| s.case == StepCase::TangentialCurve)
        .count();
    let s = |k: usize| steps.get(k).map_or(0.0, |x| x.s[k.min(1)]);
    format!(
        "Tube: every solution of the tangential direction field (double root of the contact \
         quadratic, unit model speed) from the start box exists on arc length [{:.6}, {:.6}] and \
         stays within {:.3e} (model space) of the reported pieces; this solves the direction \
         field and does not prove that P and Q meet. Cases: {} of {} step boxes (widened by \
         {:e}) are a tangential curve in interval arithmetic. Cover: every (σ,t,u,v) in the {} \
         searched boxes with P(σ,t) = Q(u,v) lies in one of the {} kept boxes (model width ≤ \
         {:.3e}{}); no intersection point is proven to exist.",
        s(0),
        steps.last().map_or(0.0, |x| x.s[1]),
        tube,
        tangential,
        steps.len(),
        opts.classify_radius,
        cover.region.len(),
        cover.boxes.len(),
        cover.max_xyz_width,
        if cover.resolved {
            ""
        } else {
            ", budget spent before the leaf size"
        }
    )
}

/// The validated integrator of the tangential field of `p`, `q` with root formula `formula` and
/// orientation `orientation`, from the start set `start`: both patches in their lean centred
/// form ([`ContactPatch`]), the field in ratio form ([`RatioTangentialOde`], longer steps) when
/// the sign of its pivot is proven on `start`, else in the scaled form ([`TangentialOde`]). All
/// are the same field on every box the engine proves anything over.
fn tangential_integrator(
    p: &ContactPatch<'_>,
    q: &ContactPatch<'_>,
    formula: TangentialFormula,
    orientation: f64,
    start: &[Interval; 4],
    options: IntegratorOptions,
) -> Result<Integrator> {
    let field = TangentialOde {
        p,
        q,
        formula,
        orientation,
    };
    match pivot_sign(p, q, formula, start) {
        Some(pivot_sign) => Integrator::new(&RatioTangentialOde { field, pivot_sign }, options),
        None => Integrator::new(&field, options),
    }
}

struct HalfTrace {
    steps: Vec<ContactStep>,
    tubes: Vec<TubePiece>,
    end: ContactEnd,
}

/// The active integrator: its root formula, orientation and state.
struct Active {
    formula: TangentialFormula,
    orientation: f64,
    integ: Integrator,
    state: IntegratorState,
}

/// One half of the trace, along `dir` (+1 forward, −1 backward); `heading` is the f64 parameter
/// velocity the first step should agree with.
#[allow(clippy::too_many_arguments)]
fn trace_half(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    lean: (&ContactPatch<'_>, &ContactPatch<'_>),
    y0: &[Interval; 4],
    heading: [f64; 4],
    dir: f64,
    opts: &ContactOptions,
) -> Result<HalfTrace> {
    let (dp, dq) = (p.domain(), q.domain());
    let h_max = h_max_for(p, q, opts.steps.h_max);
    let mut half = HalfTrace {
        steps: Vec::new(),
        tubes: Vec::new(),
        end: ContactEnd::Budget { length: 0.0 },
    };
    let mut current = *y0;
    let mut t = 0.0;
    let mut heading = heading;
    let mut active: Option<Active> = None;
    loop {
        if opts.steps.spent(half.steps.len(), t) || opts.steps.out_of_time() {
            half.end = ContactEnd::Budget { length: t };
            return Ok(half);
        }
        // The better-conditioned root formula at the current centre; a new system when it
        // changes, oriented to continue the heading.
        let c = contact_quadratic(p, q, &mids(&current));
        let formula = TangentialFormula::choose(&c);
        if active.as_ref().is_none_or(|a| a.formula != formula) {
            let v = tangential_velocity(&c, formula, 1.0);
            let along: f64 = v.iter().zip(&heading).map(|(a, b)| a * b).sum();
            if !along.is_finite() {
                half.end = ContactEnd::StepFailed {
                    reason: "the tangential direction is undefined".into(),
                    near: current,
                };
                return Ok(half);
            }
            let orientation = if along >= 0.0 { 1.0 } else { -1.0 };
            let options = opts.steps.integrator_options(h_max);
            let (lp, lq) = lean;
            let mut integ = tangential_integrator(lp, lq, formula, orientation, &current, options)?;
            // Sound for any guess; the thin restarted sets of this tracer do not widen by it.
            integ.set_adaptive_guess(true);
            let state = integ.start(&current, t)?;
            active = Some(Active {
                formula,
                orientation,
                integ,
                state,
            });
        }
        let Some(a) = active.as_mut() else {
            continue;
        };
        let limit = a.state.t() + h_max;
        let rec = match a.integ.step(&mut a.state, limit) {
            Ok(r) => r,
            Err(Error::StepFailed { reason, .. }) => {
                half.end = ContactEnd::StepFailed {
                    reason: reason.to_string(),
                    near: current,
                };
                return Ok(half);
            }
            Err(e) => return Err(e),
        };
        let apriori = to4(&rec.apriori);
        let case = classify_box(p, q, &widen4(&apriori, [opts.classify_radius; 4]));
        let s = if dir > 0.0 {
            [rec.t0, rec.t1]
        } else {
            [-rec.t1, -rec.t0]
        };
        half.steps.push(ContactStep {
            s,
            apriori,
            xyz: p.enclose(apriori[0], apriori[1]),
            case,
        });
        // Not re-anchored: arc length counts exactly from the start (`s0_error` 0); the
        // model-space radius is always tightened with the centred partials.
        half.tubes.push(tube_piece(p, &rec, dir, 0.0, 0.0)?);
        current = to4(&rec.end);
        t = rec.t1;
        let ode = TangentialOde {
            p,
            q,
            formula: a.formula,
            orientation: a.orientation,
        };
        heading = ode.velocity(&mids(&current));
        if case != StepCase::TangentialCurve {
            half.end = ContactEnd::CaseChanged {
                case,
                near: apriori,
            };
            return Ok(half);
        }
        let outside = (0..4).find_map(|i| {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            (current[i].sup() < lo || current[i].inf() > hi).then_some(i / 2)
        });
        if let Some(surface) = outside {
            half.end = ContactEnd::Boundary { surface };
            return Ok(half);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::nearest_sqr;

    #[test]
    fn nearest_point_is_the_brute_force_minimum() {
        let mut h = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || crate::numeric::rounding::uniform_pm1(&mut h);
        for n in [0, 1, 2, 7, 300] {
            let mut pts: Vec<[f64; 3]> = (0..n).map(|_| [next(), next(), 0.1 * next()]).collect();
            pts.sort_by(|a, b| a[0].total_cmp(&b[0]));
            for _ in 0..200 {
                let c = [1.2 * next(), next(), next()];
                let brute = pts
                    .iter()
                    .map(|s| (c[0] - s[0]).powi(2) + (c[1] - s[1]).powi(2) + (c[2] - s[2]).powi(2))
                    .fold(f64::INFINITY, f64::min);
                assert_eq!(nearest_sqr(&c, &pts).to_bits(), brute.to_bits());
            }
        }
    }
}
