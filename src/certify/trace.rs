//! Certified tracing of one branch on the validated engine.
//!
//! 1. **Start**: the marcher's point is turned into a proven box by the parametric Krawczyk test
//!    ([`crate::pair::krawczyk`]), holding the fastest-moving parameter fixed; the box of the proof is
//!    kept: for that parameter value the curve meets it in exactly one point.
//! 2. **Steps**: the transversal ODE ([`crate::certify::ode::TransversalOde`]) is integrated both ways by
//!    [`Integrator`]; each step gives an a-priori box (the link of the chain), a tight end box and
//!    Taylor coefficients with a remainder (the tube piece).
//! 3. **Re-anchoring** (the contraction, [`CertifyOptions::contract`]): Krawczyk with the
//!    fastest-moving parameter `x_k` held in an interval `X` around the end box's, on the end box
//!    inflated in the other three, proves that the curve there is a graph over `x_k` and encloses
//!    it (the *cover*); the next step starts from the curve point with `x_k = c = mid`, enclosed
//!    by Krawczyk with `x_k = c` (a thin box: the along-curve spread of the end box is dropped, so
//!    Taylor coefficients, tubes and the certified tolerance stay at rounding level instead of
//!    growing along the branch). That point's arc length is known up to a proven error, accumulated along the half:
//!    the joining piece has arc length ≤ `|c − e_k| / min|x_k'|` over the cover (unit speed).
//!    Boxes hold the covers too, so they hold the curve over their arc-length ranges despite the
//!    error ([`EnclosureBox`]); tubes carry it ([`TubePiece::s0_error`]); the certified tolerance
//!    counts the joining pieces. Re-anchored steps need no Jacobians (the direct Taylor form's wrapping
//!    does not accumulate) and learn phase I's remainder guess from the last step.
//! 4. **Ends**, each proven: the end box lies outside a domain (the last box straddles the
//!    boundary); the curve crosses the start parameter's value inside the start's uniqueness box
//!    (a closed loop: it is the start point, traced once); the field cannot be bounded because
//!    `0 ∈ |N^P × N^Q|` (singular or tangential point); the step fell below `h_min` with the
//!    normals separated (branches closer than can be resolved). A budget end is reported as
//!    [`CertifiedEnd::Unproven`].

use crate::certify::anchor::{join_tolerance, reanchor};
use crate::certify::budget::{h_max_for, StepBudget};
use crate::certify::closing::{closes, Closure, Crossing};
use crate::certify::contact_patch::ContactPatch;
use crate::certify::curve::{CertifiedBranch, CertifiedEnd, EnclosureBox, TubePiece};
use crate::certify::ode::TransversalOde;
use crate::certify::term_target::TermTarget;
use crate::error::{Error, Result};
use crate::geometry::surface::{pair_bounds as bounds, pair_widths};
use crate::geometry::{Domain, RationalBezierPatch};
use crate::numeric::scalar::{interval, point};
use crate::numeric::vec3::norm_sqr;
use crate::pair::field::{transversal_field, ScalarSurface};
use crate::pair::krawczyk::{best_fixed_coordinate, krawczyk, KrawczykResult};
use crate::pair::newton::{refine, Constraint};
use crate::validated::{Integrator, IntegratorWork, StepFailure, StepRecord};
use inari::Interval;
use std::time::Instant;

/// Parameters of [`certify_branch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CertifyOptions {
    /// The validated steps and the budget of each half (default [`StepBudget::CERTIFY`]; the
    /// smallest step is where the tracer reports branches closer than can be resolved).
    pub steps: StepBudget,
    /// Pull every end box back onto `P = Q` (Krawczyk) before the next step.
    pub contract: bool,
    /// The model-space tolerance the branch should meet (default 1e-9). It sizes the steps and
    /// is not a claim: each half starts at the budget's [`term_target`](StepBudget::term_target)
    /// and raises it while a step's tube radius stays near a sixteenth of this and the
    /// re-anchoring's arc-length error within its budget over [`StepBudget::max_length`]
    /// (`certify/term_target.rs`). 0 keeps every step at the budget's term target.
    pub required_tolerance: f64,
    /// Trace the backward half on another thread (`rayon::join`) while the forward half runs.
    /// The result is the same. Worth it for an open branch (the two halves are about equal); on a
    /// closed loop the forward half closes it alone and the backward work is thrown away, so
    /// set it only for branches known to be open (default `false`).
    pub parallel_halves: bool,
}

impl Default for CertifyOptions {
    fn default() -> Self {
        CertifyOptions {
            steps: StepBudget::CERTIFY,
            contract: true,
            required_tolerance: 1e-9,
            parallel_halves: false,
        }
    }
}

fn to4(v: &[Interval]) -> [Interval; 4] {
    [v[0], v[1], v[2], v[3]]
}

fn mids(v: &[Interval; 4]) -> [f64; 4] {
    v.map(|x| x.mid())
}

/// Largest width over the coordinates other than `along` (all four if unknown).
fn transversal_width(v: &[Interval; 4], along: Option<usize>) -> f64 {
    (0..4)
        .filter(|&i| Some(i) != along)
        .map(|i| v[i].wid())
        .fold(0.0, f64::max)
}

/// Where the time of [`certify_branch_profiled`] went (wall-clock seconds per part, and the
/// validated integrator's work summed over both halves).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TraceProfile {
    /// Validated steps (Taylor expansions, phase I and phase II).
    pub step_seconds: f64,
    /// Re-anchoring (Krawczyk on the end boxes, arc-length bounds).
    pub anchor_seconds: f64,
    /// Model-space boxes and tube radii.
    pub enclosure_seconds: f64,
    /// The loop-closing test.
    pub closing_seconds: f64,
    /// Counts and recurrence costs of the integrator.
    pub integrator: IntegratorWork,
}

impl TraceProfile {
    fn add_work(&mut self, w: IntegratorWork) {
        self.integrator += w;
    }

    fn add(&mut self, other: &TraceProfile) {
        self.step_seconds += other.step_seconds;
        self.anchor_seconds += other.anchor_seconds;
        self.enclosure_seconds += other.enclosure_seconds;
        self.closing_seconds += other.closing_seconds;
        self.integrator += other.integrator;
    }
}

/// Certifies the branch through `start ≈ (σ, t, u, v)` (a point on the curve from the marcher).
///
/// Errors: the start cannot be proven (singular, or not near the curve) or an internal check of
/// the certificate fails ([`Error::Certification`]); bad options ([`Error::BadIntegratorSetup`]).
/// Everything returned is proven; ends that are not are [`CertifiedEnd::Unproven`].
pub fn certify_branch(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    start: [f64; 4],
    opts: &CertifyOptions,
) -> Result<CertifiedBranch> {
    certify_branch_profiled(p, q, start, opts).map(|(b, _)| b)
}

/// [`certify_branch`], also reporting where the time went.
pub fn certify_branch_profiled(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    start: [f64; 4],
    opts: &CertifyOptions,
) -> Result<(CertifiedBranch, TraceProfile)> {
    let mut profile = TraceProfile::default();
    let (dp, dq) = (p.domain(), q.domain());
    let scales = pair_widths(&dp, &dq);
    let fail = |reason: &str| Error::Certification {
        reason: reason.to_string(),
        near: start,
    };
    if start.iter().any(|x| !x.is_finite()) {
        return Err(fail("non-finite start point"));
    }
    let v0 = transversal_field(p, q, &start, 1.0);
    if !v0.velocity.iter().all(|x| x.is_finite()) {
        return Err(fail(
            "the normals are parallel at the start point (singular start)",
        ));
    }
    let fixed = best_fixed_coordinate(&v0.velocity, &scales);
    let (y0, uniq) = prove_start(p, q, start, fixed, &scales).ok_or_else(|| {
        fail(
            "no Krawczyk proof of a unique curve point near the start (off the curve, or singular)",
        )
    })?;

    let closure = Some((fixed, start[fixed], &uniq, v0.velocity[fixed]));
    let (forward, backward) = if opts.parallel_halves {
        let half = |dir: f64, closure: Option<Closure>| {
            let mut pr = TraceProfile::default();
            let h = trace_half(p, q, &y0, dir, closure, opts, &mut pr);
            (h, pr)
        };
        let ((forward, pf), (backward, pb)) =
            rayon::join(|| half(1.0, closure), || half(-1.0, None));
        profile.add(&pf);
        profile.add(&pb);
        let forward = forward?;
        // A closed loop needs no backward half (the sequential trace never runs it).
        let backward = match forward.end {
            CertifiedEnd::ClosedLoop => None,
            _ => Some(backward?),
        };
        (forward, backward)
    } else {
        let forward = trace_half(p, q, &y0, 1.0, closure, opts, &mut profile)?;
        let backward = match forward.end {
            CertifiedEnd::ClosedLoop => None,
            _ => Some(trace_half(p, q, &y0, -1.0, None, opts, &mut profile)?),
        };
        (forward, backward)
    };
    let (mut boxes, mut tubes, mut widths) = (Vec::new(), Vec::new(), Vec::new());
    let mut certified_tolerance = forward.certified_tolerance;
    let first_end;
    if let Some(backward) = backward {
        first_end = backward.end;
        boxes.extend(backward.boxes.into_iter().rev());
        tubes.extend(backward.tubes.into_iter().rev());
        widths.extend(backward.widths.into_iter().rev());
        certified_tolerance = certified_tolerance.max(backward.certified_tolerance);
    } else {
        first_end = CertifiedEnd::ClosedLoop;
    }
    let joined = boxes.len();
    boxes.extend(forward.boxes);
    tubes.extend(forward.tubes);
    widths.extend(forward.widths);
    // Gap-free chain: consecutive boxes share the curve point at their common arc length. The
    // two halves meet at the start point, which both first boxes contain.
    for (j, pair) in boxes.windows(2).enumerate() {
        if !pair[0].overlaps(&pair[1]) {
            return Err(Error::Certification {
                reason: format!(
                    "boxes {j} and {} of the chain do not overlap (at the join: {})",
                    j + 1,
                    j + 1 == joined
                ),
                near: mids(&pair[1].params()),
            });
        }
    }
    let branch = CertifiedBranch {
        start: y0,
        fixed,
        start_uniqueness: uniq,
        boxes,
        tubes,
        certified_tolerance,
        ends: [first_end, forward.end],
        widths,
        tolerance_limit: None,
    };
    Ok((branch, profile))
}

/// The proven start box and the box of its uniqueness proof: the largest of a few radii for which
/// Krawczyk succeeds (a large uniqueness box makes the loop-closing proof easy).
fn prove_start(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    start: [f64; 4],
    fixed: usize,
    scales: &[f64; 4],
) -> Option<([Interval; 4], [Interval; 4])> {
    let mut rho = 1e-2;
    while rho >= 1e-10 {
        let mut y = [point(0.0); 4];
        for k in 0..4 {
            y[k] = if k == fixed {
                point(start[k])
            } else {
                interval(start[k] - rho * scales[k], start[k] + rho * scales[k])?
            };
        }
        if let KrawczykResult::Proven { enclosure, .. } = krawczyk(p, q, y, fixed, 30) {
            return Some((tighten_start(p, q, enclosure, &y, fixed, scales), y));
        }
        rho *= 0.125;
    }
    None
}

/// A tight box of the start point proven in the wide box `uniq`. Krawczyk on a wide box may stop
/// contracting while its enclosure is still about as wide as the box (its image shrinks by less
/// than 10 % per iteration there), and a trace started from such a box carries that width along
/// the whole branch. So the point is refined by f64 Newton (fixed coordinate kept) and proven
/// again in a box of rounding size around it; that box lies in `uniq`, whose curve point is
/// unique, so both proofs enclose the same point and their intersection is returned. If no tight
/// proof succeeds, the wide `enclosure` is returned unchanged (still proven).
fn tighten_start(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    enclosure: [Interval; 4],
    uniq: &[Interval; 4],
    fixed: usize,
    scales: &[f64; 4],
) -> [Interval; 4] {
    let wide = (0..4).any(|k| k != fixed && enclosure[k].wid() > 1e-12 * scales[k]);
    if !wide {
        return enclosure;
    }
    let guess = enclosure.map(|c| c.mid());
    let value = enclosure[fixed].mid();
    let Ok(refined) = refine(
        p,
        q,
        guess,
        Constraint::Fixed {
            index: fixed,
            value,
        },
        1e-13,
        12,
    ) else {
        return enclosure;
    };
    for rho in [1e-13, 1e-11, 1e-9] {
        let mut y = enclosure;
        for k in 0..4 {
            if k == fixed {
                continue;
            }
            let Some(c) = interval(
                refined.x[k] - rho * scales[k],
                refined.x[k] + rho * scales[k],
            ) else {
                return enclosure;
            };
            if !c.subset(uniq[k]) {
                return enclosure;
            }
            y[k] = c;
        }
        if let KrawczykResult::Proven {
            enclosure: tight, ..
        } = krawczyk(p, q, y, fixed, 30)
        {
            let both: [Interval; 4] = std::array::from_fn(|k| tight[k].intersection(enclosure[k]));
            if both.iter().all(|c| !c.is_empty()) {
                return both;
            }
        }
    }
    enclosure
}

struct Half {
    boxes: Vec<EnclosureBox>,
    tubes: Vec<TubePiece>,
    widths: Vec<f64>,
    /// Bound on the distance of the half's true curve to its reported curve (see
    /// [`join_tolerance`]); the last join is added by [`trace_half`].
    certified_tolerance: f64,
    /// The last step's model-space radius and the arc-length bound of the piece joining its end
    /// to the next start (no tube follows it yet).
    pending_join: Option<(f64, f64)>,
    end: CertifiedEnd,
}

impl Half {
    /// Enclosure phase, the box of one step: the link (the a-priori box, and the curve pieces
    /// within the arc-length errors `errs` of both starts, held by their `covers`, which also
    /// join the flow's end to the re-anchored start), its model-space box and its arc-length
    /// range. Returns the link.
    fn push_box(
        &mut self,
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        rec: &StepRecord,
        dir: f64,
        [cover, next_cover]: [&[Interval; 4]; 2],
        [s_err, next_err]: [f64; 2],
    ) -> Result<[Interval; 4]> {
        let apriori = to4(&rec.apriori);
        let link: [Interval; 4] =
            std::array::from_fn(|i| apriori[i].convex_hull(cover[i]).convex_hull(next_cover[i]));
        let xyz = model_box(p, q, &link).ok_or_else(|| Error::Certification {
            reason: "the model-space boxes of P and Q over the a-priori box are disjoint".into(),
            near: mids(&link),
        })?;
        // The arc-length range: the link holds the curve from (true) arc length t0 − s_err to
        // t1 + next_err (the covers hold the curve within 2·err of either start); publish the part
        // [t0 − s_err, t1 − next_err], so consecutive ranges touch. A last step that could not be
        // re-anchored holds it up to t1 − s_err (next_err = s_err then).
        let s = if dir > 0.0 {
            let s0 = rec.t0 - s_err;
            [s0, (rec.t1 - next_err).max(s0)]
        } else {
            let s1 = -rec.t0 + s_err;
            [(-rec.t1 + next_err).min(s1), s1]
        };
        self.boxes.push(EnclosureBox {
            s,
            p: [link[0], link[1]],
            q: [link[2], link[3]],
            xyz,
        });
        Ok(link)
    }

    /// Enclosure phase, the tube of one step and the half's certified tolerance: the tube's
    /// model-space radius, and the joins before and after the step (`bridge`: the arc-length
    /// bound of the piece joining its end to the re-anchored start, 0 if none).
    fn push_tube(
        &mut self,
        p: &RationalBezierPatch,
        rec: &StepRecord,
        dir: f64,
        s_err: f64,
        bridge: f64,
    ) -> Result<()> {
        // The radius enters the certified tolerance alone and in the joins before and after this step.
        let join = self.pending_join.map_or(0.0, |(_, b)| b).max(bridge);
        let tube = tube_piece(p, rec, dir, s_err, self.certified_tolerance - 0.5 * join)?;
        // Every true point of this step is within radius_xyz of the reported curve; the piece
        // joining the last step's end to this start is accounted for by join_tolerance.
        self.certified_tolerance = self.certified_tolerance.max(tube.radius_xyz);
        if let Some((r, b)) = self.pending_join.take() {
            self.certified_tolerance =
                self.certified_tolerance
                    .max(join_tolerance(r, b, Some(tube.radius_xyz)));
        }
        self.pending_join = (bridge > 0.0).then_some((tube.radius_xyz, bridge));
        self.tubes.push(tube);
        Ok(())
    }
}

fn trace_half(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y0: &[Interval; 4],
    dir: f64,
    closure: Option<Closure>,
    opts: &CertifyOptions,
    profile: &mut TraceProfile,
) -> Result<Half> {
    let mut integ = make_integrator(p, q, dir, opts)?;
    // Every step restarts from a thin re-anchored box: the direct Taylor form is enough (its
    // wrapping does not accumulate) and saves the Jacobians. Without re-anchoring the set must
    // not wrap: keep the mean-value form with Lohner's set.
    integ.set_mean_value(!opts.contract);
    integ.set_adaptive_guess(opts.contract);
    let half = trace_half_with(&mut integ, p, q, y0, dir, closure, opts, profile);
    profile.add_work(integ.work());
    half.map(|mut h| {
        if let Some((r, b)) = h.pending_join.take() {
            h.certified_tolerance = h.certified_tolerance.max(join_tolerance(r, b, None));
        }
        h
    })
}

fn make_integrator(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    dir: f64,
    opts: &CertifyOptions,
) -> Result<Integrator> {
    // The field is recorded once, on the lean centred form of polynomial patches (the same
    // function, far fewer recorded operations; rational patches keep their own form).
    let (lp, lq) = (ContactPatch::new(p), ContactPatch::new(q));
    let ode = TransversalOde {
        p: &lp,
        q: &lq,
        orientation: dir,
    };
    let h_max = h_max_for(p, q, opts.steps.h_max);
    Integrator::new(&ode, opts.steps.integrator_options(h_max))
}

/// The loop of [`trace_half`] on a given integrator.
#[allow(clippy::too_many_arguments)]
fn trace_half_with(
    integ: &mut Integrator,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y0: &[Interval; 4],
    dir: f64,
    closure: Option<Closure>,
    opts: &CertifyOptions,
    profile: &mut TraceProfile,
) -> Result<Half> {
    let (dp, dq) = (p.domain(), q.domain());
    let mut state = integ.start(y0, 0.0)?;
    let mut half = Half {
        boxes: Vec::new(),
        tubes: Vec::new(),
        widths: Vec::new(),
        certified_tolerance: 0.0,
        pending_join: None,
        end: CertifiedEnd::ClosedLoop,
    };
    let mut crossing = Crossing::default();
    let scales = pair_widths(&dp, &dq);
    let mut current = *y0;
    // The arc-length error of the current start (0 at the branch's start point) and a box holding
    // the curve within twice that arc length of it (and the piece joining it to the last step).
    let mut s_err = 0.0f64;
    let mut cover = *y0;
    // (h_max_for caps at 1/8 of the smaller patch's model size.)
    let model_size = 8.0 * h_max_for(p, q, f64::INFINITY);
    let mut target = TermTarget::new(
        opts.steps.term_target,
        opts.required_tolerance,
        opts.steps.max_length,
        model_size,
    );
    loop {
        let stop = if opts.steps.out_of_time() {
            Some("time limit reached")
        } else if opts.steps.spent(half.boxes.len(), state.t) {
            Some("budget spent")
        } else {
            None
        };
        if let Some(why) = stop {
            half.end = CertifiedEnd::Unproven {
                reason: format!("{why} ({} steps, arc length {})", half.boxes.len(), state.t),
                near: current,
            };
            return Ok(half);
        }
        let limit = state.t + integ.options().h_max;
        integ.set_term_target(target.current());
        let clock = Instant::now();
        let stepped = integ.step(&mut state, limit);
        profile.step_seconds += clock.elapsed().as_secs_f64();
        let rec = match stepped {
            Ok(r) => r,
            Err(Error::StepFailed { step, reason, .. }) => {
                half.end =
                    classify_failure(p, q, &current, step.max(opts.steps.h_min), reason, &dp, &dq);
                return Ok(half);
            }
            Err(e) => return Err(e),
        };
        let end = to4(&rec.end);
        // The fastest-moving parameter: held fixed by the re-anchoring, and the along-curve
        // direction when measuring the transversal width.
        let v = transversal_field(p, q, &mids(&end), dir).velocity;
        let along = v
            .iter()
            .all(|x| x.is_finite())
            .then(|| best_fixed_coordinate(&v, &scales));
        let clock = Instant::now();
        let anchor = match (opts.contract, along) {
            (true, Some(k)) => reanchor(p, q, &end, k, &v, s_err, dir),
            _ => None,
        };
        profile.anchor_seconds += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let (next_err, next_cover, bridge) = match &anchor {
            Some(a) => (a.s_err, a.cover, a.bridge),
            None => (s_err, end, 0.0),
        };
        let link = half.push_box(p, q, &rec, dir, [&cover, &next_cover], [s_err, next_err])?;
        half.push_tube(p, &rec, dir, s_err, bridge)?;
        if let Some(tube) = half.tubes.last() {
            target.observe(rec.h, rec.t1, tube.radius_xyz, bridge, next_err);
        }
        profile.enclosure_seconds += clock.elapsed().as_secs_f64();
        let previous_cover = cover;
        match anchor {
            Some(a) => {
                let (ratio, guess) = (state.step_ratio, state.guess_factor);
                state = integ.start(&a.start, rec.t1)?;
                state.step_ratio = ratio;
                state.guess_factor = guess;
                current = a.start;
                s_err = a.s_err;
                cover = a.cover;
            }
            None if s_err == 0.0 => {
                // Not re-anchored: the integrator's set goes on, the arc length stays exact.
                current = end;
                cover = end;
            }
            None => {
                half.end = unanchored_end(p, q, &end, rec.h.max(opts.steps.h_min), &dp, &dq);
                return Ok(half);
            }
        }
        half.widths.push(transversal_width(&current, along));
        if let Some(surface) = outside(&current, &dp, &dq) {
            half.end = CertifiedEnd::Boundary { surface };
            return Ok(half);
        }
        if let Some(c) = closure {
            let clock = Instant::now();
            let closed = closes(&rec, &link, &previous_cover, c, &mut crossing)?;
            profile.closing_seconds += clock.elapsed().as_secs_f64();
            if closed {
                half.end = CertifiedEnd::ClosedLoop;
                return Ok(half);
            }
        }
    }
}

/// The end of a half whose last end box `end` (step `h`) could not be re-anchored: a boundary
/// or singular end when proven, unproven otherwise.
fn unanchored_end(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    end: &[Interval; 4],
    h: f64,
    dp: &Domain,
    dq: &Domain,
) -> CertifiedEnd {
    match (outside(end, dp, dq), singular_near(p, q, end, h)) {
        (Some(surface), _) => CertifiedEnd::Boundary { surface },
        (None, Some(near)) => CertifiedEnd::Singular { near },
        (None, None) => CertifiedEnd::Unproven {
            reason: "the end box of a step could not be re-anchored on the curve".into(),
            near: *end,
        },
    }
}

/// The model-space box `P([σ],[t]) ∩ Q([u],[v])`; `None` if empty (impossible for a box that
/// holds curve points, so a sign of a broken certificate).
fn model_box(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
) -> Option<[Interval; 3]> {
    let a = p.enclose(y[0], y[1]);
    let b = q.enclose(y[2], y[3]);
    let out = [
        a[0].intersection(b[0]),
        a[1].intersection(b[1]),
        a[2].intersection(b[2]),
    ];
    (!out.iter().any(|x| x.is_empty())).then_some(out)
}

/// The surface whose domain the box lies wholly outside of, if any.
fn outside(y: &[Interval; 4], dp: &Domain, dq: &Domain) -> Option<usize> {
    (0..4).find_map(|i| {
        let b = bounds(dp, dq, i);
        (y[i].sup() < b[0] || y[i].inf() > b[1]).then_some(i / 2)
    })
}

/// Whether the box is not wholly inside both domains.
fn straddles(y: &[Interval; 4], dp: &Domain, dq: &Domain) -> Option<usize> {
    (0..4).find_map(|i| {
        let b = bounds(dp, dq, i);
        (y[i].inf() < b[0] || y[i].sup() > b[1]).then_some(i / 2)
    })
}

/// Why a step could not be proven, decided rigorously where possible.
fn classify_failure(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
    h: f64,
    reason: StepFailure,
    dp: &Domain,
    dq: &Domain,
) -> CertifiedEnd {
    if let Some(near) = singular_near(p, q, y, h) {
        return CertifiedEnd::Singular { near };
    }
    // A box reaching over a boundary does not prove that the curve leaves there (it may only
    // touch it): say so instead of claiming a boundary end.
    if let Some(surface) = straddles(y, dp, dq) {
        return CertifiedEnd::Unproven {
            reason: format!(
                "no step could be proven from a box reaching over the boundary of surface {surface} ({reason})"
            ),
            near: *y,
        };
    }
    match reason {
        StepFailure::BelowMinimumStep { .. } => CertifiedEnd::CloseBranches { h, near: *y },
        other => CertifiedEnd::Unproven {
            reason: other.to_string(),
            near: *y,
        },
    }
}

/// A box around `y` on which `|N^P × N^Q|` may vanish (a singular or tangential point may lie in
/// it), if one is found.
///
/// Near a singular point the Taylor coefficients blow up (their radius of convergence is the
/// distance to it), so the step collapses at a distance of many steps. Looks for `0 ∈ m2` in
/// boxes of radius 10ʲ·h·(1 + speed), j = 0..3, around `y`.
fn singular_near(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
    h: f64,
) -> Option<[Interval; 4]> {
    let speed = transversal_field(p, q, &mids(y), 1.0)
        .velocity
        .iter()
        .fold(
            1.0f64,
            |m, v| if v.is_finite() { m.max(v.abs()) } else { m },
        );
    for factor in [1.0, 10.0, 100.0, 1000.0] {
        let r = factor * h * (1.0 + speed);
        let near = y.map(|x| interval(x.inf() - r, x.sup() + r).unwrap_or(Interval::ENTIRE));
        let m2 = transversal_field(p, q, &near, 1.0).cross_norm_sqr;
        if m2.contains(0.0) || m2.is_empty() {
            return Some(near);
        }
    }
    None
}

/// One step's tube: the polynomial through the centre of the step's initial set and its proven
/// radii (the smaller of the direct and mean-value deviation bounds). The model-space radius is
/// tightened with the centred partials only if it would exceed `refine_above`.
pub(crate) fn tube_piece(
    p: &RationalBezierPatch,
    rec: &StepRecord,
    dir: f64,
    s0_error: f64,
    refine_above: f64,
) -> Result<TubePiece> {
    let poly = rec.centre_polynomial();
    let radii = rec.deviation_bound(&poly)?;
    let radius_param = radii.iter().cloned().fold(0.0f64, f64::max);
    let coeffs: Vec<[f64; 4]> = poly.iter().map(|c| [c[0], c[1], c[2], c[3]]).collect();
    // Model space: |P(σ, t) − P(σ', t')| ≤ sup‖P_σ‖·|σ − σ'| + sup‖P_t‖·|t − t'| over the a-priori
    // box grown by the radii (it holds both points and the path between them).
    let grow = |x: Interval, r: f64| interval(x.inf() - r, x.sup() + r).unwrap_or(Interval::ENTIRE);
    let (gs, gt) = (
        grow(rec.apriori[0], radii[0]),
        grow(rec.apriori[1], radii[1]),
    );
    let [_, ps, pt] = p.first_order(gs, gt);
    let (mut norm_s, mut norm_t) = (norm_sqr(&ps).sqrt(), norm_sqr(&pt).sqrt());
    // Where the Bernstein evaluation over the box is loose (well above the values at its centre,
    // typically on long steps of high-degree patches), intersect with the centred (shifted power)
    // form S_σ = a/g, S_t = b/g, g > 0: far tighter there, but costlier to evaluate.
    // Only when it matters: the branch's certified tolerance is the largest radius, so a radius
    // below `refine_above` (the largest so far) is published as it is (it is a valid bound).
    let [_, cs, ct] = p.first_order(gs.mid(), gt.mid());
    let at_centre = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let loose = (norm_s * point(radii[0]) + norm_t * point(radii[1])).sup();
    if loose > refine_above
        && (norm_s.sup() > 1.25 * at_centre(cs) || norm_t.sup() > 1.25 * at_centre(ct))
    {
        let (a, b, g) = p.scaled_first_order_centred(gs, gt, point(gs.mid()), point(gt.mid()));
        let centred = [norm_sqr(&a).sqrt() / g, norm_sqr(&b).sqrt() / g];
        for (n, c) in [&mut norm_s, &mut norm_t].into_iter().zip(centred) {
            let both = n.intersection(c);
            if !both.is_empty() {
                *n = both;
            }
        }
    }
    let radius_xyz = (norm_s * point(radii[0]) + norm_t * point(radii[1])).sup();
    if !(radius_param.is_finite() && radius_xyz.is_finite()) {
        return Err(Error::Certification {
            reason: "unbounded tube radius".into(),
            near: mids(&to4(&rec.apriori)),
        });
    }
    Ok(TubePiece {
        s0: dir * rec.t0,
        direction: dir,
        h: rec.h,
        coeffs,
        radius_param,
        radius_xyz,
        s0_error,
        along: None,
    })
}
