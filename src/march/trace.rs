//! Branch tracing with stop rules: domain boundary, return to the start, singular point, budget.
//!
//! [`trace_branch`] refines the start point, marches forward along `c = N^P × N^Q` and, unless the
//! forward march closed a loop, backward along `−c`, and joins both halves into one
//! [`Branch`] ordered along the curve.
//!
//! Stop rules:
//! - **Boundary**: a Newton point outside either domain is replaced by the point where the curve
//!   leaves the domain, found by Newton with that boundary parameter held fixed (exactly on it),
//!   between the last point and the outside one (on a short arc crossing a side at a small angle
//!   the bracket is halved along the curve first, see `land_on_boundary`). A start that refines
//!   to a point just outside is moved onto the boundary where the curve crosses it.
//! - **Closed loop**: the start point is taken as the next point (the last step is shortened or
//!   stretched to land exactly on it) only when all of these hold: it is within 1.5 predicted steps,
//!   it lies ahead (the chord to it is within 60° of the tangent), the tangent agrees with the
//!   start tangent (within 60°), and the accumulated turning of the tangent in P's or in Q's
//!   parameter domain is within `rotation_tolerance` of `2πk`, `k ≠ 0` (the rotation index of a
//!   loop; either domain suffices, so a degenerate parametrisation of one surface does no harm). A pass near
//!   the start on another part of the curve (close branches, a branch point) fails the tangent or
//!   the turning test and does not stop the march. The parameters must also return (within twice
//!   the local parameter speed times the distance), so a loop in model space that is open in a
//!   parameter domain (a periodic surface cut at a seam) is not closed. When the forward half
//!   from an interior start stops short with a Newton failure (as on a tiny loop of nearly
//!   tangent surfaces, where the corrections sit at the noise floor), the backward half closes
//!   the loop by the same test at the forward half's last point, instead of going round again.
//! - **Singular point**: `|N^P × N^Q| < singular_sine |N^P||N^Q|`. Below `watch_sine` the step is
//!   limited (while the sine decreases) to half the distance at which the sine would vanish at its
//!   current rate, so the marcher approaches a singular point geometrically instead of stepping
//!   across it. A step that still crosses one (the orientation of `N^P × N^Q` relative to the
//!   direction of travel flips, which on a regular arc never happens) is replaced by the singular
//!   point itself, located by Gauss–Newton. With `cross_singular` the march continues straight
//!   through the node's unused exit (each arc once), and the closing test then accepts rotation
//!   index 0.
//! - **Another curve**: a Newton point where the direction of travel runs against
//!   `N^P × N^Q` while no singular point lies between it and the last point is on another curve
//!   (on nearly tangent surfaces, the other arm of a curve that turns round); the step is
//!   halved as after a Newton failure.
//! - **Own path**: a point back on the half's own earlier path, away from its start, with the
//!   same direction (`closing::on_own_path`: a loop of another curve reached after a jump, or a loop
//!   whose closing test failed) ends the half before it goes round again.
//! - **Point limit** and **Newton failure** end the half with that reason, except that Newton
//!   failing within a step of a singular point ahead (normals nearly parallel; beside a branch
//!   point the curve's sheets are closer than the Newton tolerance resolves) stops on that point.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::surface::pair_bounds as bounds;
use crate::geometry::{ParametricSurface, Vec3};
use crate::march::boundary::{
    boundary_surface_of, enters, leaves_domains, onto_boundary, touching,
};
use crate::march::branch::{Branch, BranchStatus, CurvePoint, EndReason, Event, EventKind};
use crate::march::circle_step::circular_step;
use crate::march::closing::{add_turn, closing_turning, on_own_path, turn, OWN_PATH_GAP};
use crate::march::crossing::{cross_node, singular_ahead, singular_between};
use crate::march::dqoc_step::dqoc_step;
use crate::march::node::{inside, node_at, Node};
use crate::march::options::{MarchOptions, StepMethod};
use crate::march::step_limit::{
    model_size, on_pole, step_limit, StepLimit, POLE_NEWTON, POLE_REACHED,
};
use crate::march::tangent_step::tangent_step;
use crate::march::StepPrediction;
use crate::pair::branch_point::SingularNode;
use crate::pair::newton::{refine, Constraint};
use crate::pair::tangent::{curve_frame, parameter_direction};

/// Counts describing one traced branch.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MarchStats {
    /// Points of the branch.
    pub points: usize,
    /// `newton_histogram[k]` = number of points that needed `k` Newton corrections
    /// (`k = 0` for the start and for points landed on exactly, e.g. the closing point).
    pub newton_histogram: Vec<usize>,
    /// Steps that were retried with a halved step after a Newton failure.
    pub retried_steps: usize,
}

/// A traced branch with per-point Newton data.
#[derive(Debug, Clone, PartialEq)]
pub struct TracedBranch {
    /// The branch (id 0; the caller renumbers). For a closed loop the last point repeats the first.
    pub branch: Branch,
    /// Newton corrections per point of `branch.points`.
    pub newton_iterations: Vec<usize>,
    /// Unit model-space tangents per point, oriented along the branch.
    pub tangents: Vec<[f64; 3]>,
    /// Events found (singular points, boundary ends).
    pub events: Vec<Event>,
    /// Total signed turning (radians) of the tangent in P's parameter domain along the branch.
    pub turning: f64,
    /// The same in Q's parameter domain.
    pub turning_q: f64,
    /// Counts.
    pub stats: MarchStats,
}

struct Half {
    nodes: Vec<Node>,
    end: EndReason,
    events: Vec<Event>,
    /// Turning in P's and in Q's parameter domain.
    turning: [f64; 2],
    retried: usize,
}

fn bad(field: &str, problem: InputProblem) -> Error {
    Error::input(field, problem)
}

fn make_event(kind: EventKind, n: &Node) -> Event {
    Event {
        kind,
        p: [n.x[0], n.x[1]],
        q: [n.x[2], n.x[3]],
        xyz: [n.frame.xyz.x, n.frame.xyz.y, n.frame.xyz.z],
    }
}

/// Parameter guesses for the model-space target: on each surface, the target is inverted by
/// three Gauss–Newton steps `[S_u S_v] Δ = target − S` from the current parameters (a foot-point
/// projection, so the guesses keep the second-order accuracy of a circular prediction instead of
/// adding the O(h²) error of a single linearisation).
fn predict_parameters<S1, S2>(p: &S1, q: &S2, x: &[f64; 4], target: &Vec3) -> [f64; 4]
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let invert = |s: &dyn Fn(f64, f64) -> crate::geometry::SurfaceDerivs, mut a: [f64; 2]| {
        for _ in 0..3 {
            let d = s(a[0], a[1]);
            let delta = parameter_direction(&d, &(target - d.p));
            a = [a[0] + delta[0], a[1] + delta[1]];
        }
        a
    };
    let a = invert(&|u, v| p.derivs(u, v), [x[0], x[1]]);
    let b = invert(&|u, v| q.derivs(u, v), [x[2], x[3]]);
    if a.iter().chain(&b).all(|c| c.is_finite()) {
        [a[0], a[1], b[0], b[1]]
    } else {
        *x
    }
}

/// Below this chord (relative to the size of the coordinates, `max(|x|, 1)`) the circle through
/// the last two points is dominated by f64 noise (`ε|x|` on a chord of `√ε|x|`-ish), and the
/// radius of curvature from second derivatives replaces it.
const TINY_CHORD: f64 = 1e-5;

/// The predicted next point. The step `L` is an angle on tight curves: a circular step's arc is
/// `L` times the radius of the circle through the last two points (when below 1), so the marcher
/// follows a loop of any size. Where that circle cannot be trusted the radius of curvature
/// `R = 1/κ` estimated at the current point from second derivatives gives the step: the first
/// step of a half (no circle yet) is at most `L·R` long, and on chords shorter than
/// [`TINY_CHORD`] (a loop of radius 1e-6 at unit coordinates) a tangent step of `L·min(R, 1)`
/// replaces the circular one — except while `approaching` a singular point (the sine of the
/// normals' angle falling fast), where the curvature estimate diverges and the geometric
/// approach (`step`) rules.
fn predict(
    prev: Option<&Node>,
    cur: &Node,
    opts: &MarchOptions,
    step: f64,
    approaching: bool,
) -> StepPrediction {
    let (xyz, t) = (&cur.frame.xyz, &cur.frame.tangent);
    // Infinite on straight stretches (no cap), 0 never (κ is finite or infinite).
    let radius = 1.0 / cur.curvature;
    match (prev, opts.method) {
        (_, StepMethod::Tangent) => tangent_step(xyz, t, step),
        (None, _) => {
            let first = step * opts.first_step_fraction;
            tangent_step(
                xyz,
                t,
                if radius > 0.0 {
                    first.min(step * radius)
                } else {
                    first
                },
            )
        }
        (Some(pv), _)
            if !approaching
                && radius > 0.0
                && (xyz - pv.frame.xyz).norm() < TINY_CHORD * xyz.norm().max(1.0) =>
        {
            tangent_step(xyz, t, step * radius.min(1.0))
        }
        (Some(pv), StepMethod::Circular) => circular_step(
            &pv.frame.xyz,
            &pv.frame.tangent,
            xyz,
            t,
            step,
            opts.parallel_tolerance,
        ),
        (Some(pv), StepMethod::Dqoc) => dqoc_step(
            &pv.frame.xyz,
            &pv.frame.tangent,
            xyz,
            t,
            step,
            opts.parallel_tolerance,
        ),
    }
}

/// [`predict`] with the step's arc capped at `limit.cap` (the arc is proportional to `L`).
fn predict_capped(
    prev: Option<&Node>,
    cur: &Node,
    opts: &MarchOptions,
    limit: StepLimit,
) -> StepPrediction {
    let pred = predict(prev, cur, opts, limit.step, limit.approaching);
    if pred.arc > limit.cap && pred.arc.is_finite() {
        let step = limit.step * limit.cap / pred.arc;
        predict(prev, cur, opts, step, limit.approaching)
    } else {
        pred
    }
}

/// Corrects the prediction `first` (made within `limit`) onto the curve by Newton in the
/// plane through the predicted point, halving the step up to three times if Newton fails,
/// jumps too far or lands on another curve ([`settle`]). Returns the Newton point and its
/// settled node, if any, and the number of retries.
fn correct<S1, S2>(
    p: &S1,
    q: &S2,
    opts: &MarchOptions,
    prev: Option<&Node>,
    cur: &Node,
    first: StepPrediction,
    mut limit: StepLimit,
) -> (Option<([f64; 4], Node)>, usize)
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let mut attempt = first;
    let mut retried = 0;
    for tries in 0..4 {
        if tries > 0 {
            limit = limit.halved();
            attempt = predict_capped(prev, cur, opts, limit);
            retried += 1;
        }
        let guess = predict_parameters(p, q, &cur.x, &attempt.point);
        let dir = attempt.point - cur.frame.xyz;
        let len = dir.norm();
        if len == 0.0 || !len.is_finite() {
            break;
        }
        let constraint = Constraint::Plane {
            point: attempt.point,
            normal: dir / len,
        };
        if let Ok(r) = refine(
            p,
            q,
            guess,
            constraint,
            opts.newton_tolerance,
            opts.max_newton_iterations,
        ) {
            // Reject a jump that went backwards or much farther than predicted, or onto another
            // curve.
            let chord = p.point(r.x[0], r.x[1]) - cur.frame.xyz;
            if chord.norm() <= 3.0 * len + opts.newton_tolerance {
                let (node, jumped) = settle(p, q, cur, &r.x, r.iterations, chord, opts);
                if !jumped {
                    return (Some((r.x, node)), retried);
                }
            }
        }
    }
    (None, retried)
}

/// The node of the curve point `x` reached from `cur` by the step `chord`, oriented along it.
/// Where the direction of travel against `N^P × N^Q` turned over (on a regular arc it never
/// does) above `singular_sine`, the step crossed a singular point: that point instead, or,
/// with none between, the node and `true`: the step landed on another curve. On
/// nearly tangent surfaces a curve that turns round (normals 1e-7 apart at the turn) runs back
/// beside itself, its two arms about the sine over the normals' relative curvature apart; a
/// step out of the turn can land on the other arm, which runs the other way along the curve,
/// and the march would trace that arm again.
fn settle<S1, S2>(
    p: &S1,
    q: &S2,
    cur: &Node,
    x: &[f64; 4],
    iterations: usize,
    chord: Vec3,
    opts: &MarchOptions,
) -> (Node, bool)
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let node = node_at(p, q, *x, iterations, Some(chord));
    if node.flipped == cur.flipped || node.frame.sine < opts.singular_sine {
        return (node, false);
    }
    match singular_between(p, q, cur, &node, opts) {
        Some(at) => (at, false),
        None => (node, true),
    }
}

/// Marches from `start` (tangent oriented along the direction of travel) until a stop rule fires.
/// `closure`: the point where the march closes a loop, with the turning already accumulated
/// from it to `start` — `start` itself (no turning) for a forward half from an interior start;
/// the forward half's last point, for the backward half when the forward half stopped short of
/// closing (it then closes the loop from the other side instead of going round again).
///
/// Each step: the step limit near singular points ([`step_limit`]), the prediction, the closing
/// test ([`closing_turning`]), the Newton correction ([`correct`]), then the boundary
/// ([`leaves_domains`]) and singular-point rules.
fn march_half<S1, S2>(
    p: &S1,
    q: &S2,
    start: &Node,
    opts: &MarchOptions,
    budget: usize,
    closure: Option<(&Node, [f64; 2])>,
) -> Half
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let poles = [p.poles(), q.poles()];
    let size = model_size(p, q);
    let mut half = Half {
        nodes: Vec::new(),
        end: EndReason::PointLimit,
        events: Vec::new(),
        turning: [0.0, 0.0],
        retried: 0,
    };
    let mut prev: Option<Node> = None;
    let mut cur = *start;
    let mut crossings = 0;
    // Nodes crossed in this half, with the exits used (each arc once).
    let mut visited: Vec<(SingularNode, Vec<bool>)> = Vec::new();
    loop {
        if half.nodes.len() >= budget {
            half.end = EndReason::PointLimit;
            return half;
        }
        if let Some(surface) = on_pole(&poles, &cur, POLE_REACHED * size).filter(|_| prev.is_some())
        {
            half.end = EndReason::Boundary { surface };
            return half;
        }
        let limit = step_limit(prev.as_ref(), &cur, opts, &poles);
        let pred = predict_capped(prev.as_ref(), &cur, opts, limit);

        if let Some((target, prior)) = closure.filter(|_| half.nodes.len() >= 2) {
            let closed = closing_turning(
                target,
                prev.as_ref(),
                &cur,
                [prior[0] + half.turning[0], prior[1] + half.turning[1]],
                pred.arc,
                opts,
                !visited.is_empty(),
            );
            if let Some(total) = closed {
                half.turning = [total[0] - prior[0], total[1] - prior[1]];
                let mut closing = *target;
                closing.iterations = 0;
                half.nodes.push(closing);
                half.end = EndReason::ClosedLoop;
                return half;
            }
        }

        let (refined, retried) = correct(p, q, opts, prev.as_ref(), &cur, pred, limit);
        half.retried += retried;
        // Newton failing right next to a singular point stops on that point instead.
        let ahead = || {
            singular_ahead(p, q, &cur, opts).map(|x| {
                let chord = p.point(x[0], x[1]) - cur.frame.xyz;
                (x, settle(p, q, &cur, &x, 0, chord, opts).0)
            })
        };
        let Some((x, node)) = refined.or_else(ahead) else {
            half.end = match on_pole(&poles, &cur, POLE_NEWTON * size) {
                Some(surface) => EndReason::Boundary { surface },
                None => EndReason::NewtonFailed,
            };
            return half;
        };

        if let Some(landing) = leaves_domains(p, q, &cur, &x, pred.arc, opts) {
            match landing {
                Some((node, surface)) => {
                    add_turn(&mut half.turning, turn(&cur.frame, &node.frame));
                    half.events.push(make_event(EventKind::BoundaryEnd, &node));
                    half.nodes.push(node);
                    half.end = EndReason::Boundary { surface };
                }
                None => half.end = EndReason::NewtonFailed,
            }
            return half;
        }

        add_turn(&mut half.turning, turn(&cur.frame, &node.frame));
        half.nodes.push(node);
        if node.frame.sine < opts.singular_sine {
            half.events.push(make_event(EventKind::Singular, &node));
            let crossed = (crossings < opts.cross_singular)
                .then(|| cross_node(p, q, start, &half.nodes, &mut visited, opts))
                .flatten();
            match crossed {
                Some((at, beyond)) => {
                    crossings += 1;
                    // The tangent at the reached point (normals parallel) is noise: replace the
                    // turning to it by the turning from the last regular point to the exit.
                    let noise = turn(&cur.frame, &node.frame);
                    add_turn(&mut half.turning, [-noise[0], -noise[1]]);
                    add_turn(&mut half.turning, turn(&cur.frame, &beyond.frame));
                    half.nodes.pop();
                    half.nodes.push(at);
                    half.nodes.push(beyond);
                    prev = None;
                    cur = beyond;
                    continue;
                }
                None => {
                    half.end = EndReason::Singular;
                    return half;
                }
            }
        }
        if let Some(k) = on_own_path(&half.nodes, pred.arc, opts.watch_sine) {
            // Back on its first few points after going round: its own loop, whose closing test
            // missed the start (steps long against the loop). It closes at the start now, one
            // lap and those few points marched (the straying check flags the extra length).
            match closure.filter(|_| k < OWN_PATH_GAP) {
                Some((target, _)) => {
                    add_turn(&mut half.turning, turn(&node.frame, &target.frame));
                    let mut closing = *target;
                    closing.iterations = 0;
                    half.nodes.push(closing);
                    half.end = EndReason::ClosedLoop;
                }
                None => half.end = EndReason::OwnPath,
            }
            return half;
        }
        prev = Some(cur);
        cur = node;
    }
}

fn check_options(opts: &MarchOptions) -> Result<()> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(opts.step) {
        return Err(bad("step", InputProblem::NonFinite));
    }
    if !positive(opts.newton_tolerance) {
        return Err(bad("newton_tolerance", InputProblem::NonFinite));
    }
    if !positive(opts.first_step_fraction) || !positive(opts.watch_sine) {
        return Err(bad(
            "first_step_fraction/watch_sine",
            InputProblem::NonFinite,
        ));
    }
    if opts.max_points < 2 {
        return Err(bad(
            "max_points",
            InputProblem::WrongCount {
                expected: 2,
                found: opts.max_points,
            },
        ));
    }
    Ok(())
}

/// Refines a start guess onto the curve: a parameter already on a domain boundary is held there,
/// otherwise the point moves orthogonally to the (approximate) tangent.
pub(crate) fn refine_start<S1, S2>(
    p: &S1,
    q: &S2,
    guess: [f64; 4],
    opts: &MarchOptions,
) -> Result<Node>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let edge_tol = 1e-7 * dp.size().max(dq.size()).max(1.0);
    // The bounds the guess lies within `edge_tol` of, nearest first: a start the search found on
    // one face's edge lies exactly on it, and may also lie near an edge of the other face that
    // the curve runs along rather than crosses (a section along a knot line), where fixing that
    // edge's parameter has no isolated root.
    let mut near_edges: Vec<(f64, usize, f64)> = (0..4)
        .flat_map(|i| {
            let [lo, hi] = bounds(&dp, &dq, i);
            [(i, lo), (i, hi)]
        })
        .map(|(i, b)| ((guess[i] - b).abs(), i, b))
        .filter(|&(d, _, _)| d <= edge_tol)
        .collect();
    near_edges.sort_by(|a, b| a.0.total_cmp(&b.0));
    let frame = curve_frame(p, q, guess);
    let mut constraints: Vec<Constraint> = near_edges
        .iter()
        .map(|&(_, index, value)| Constraint::Fixed { index, value })
        .collect();
    if frame.tangent != Vec3::zeros() {
        constraints.push(Constraint::Plane {
            point: p.point(guess[0], guess[1]),
            normal: frame.tangent,
        });
    } else if constraints.is_empty() {
        constraints.push(Constraint::Fixed {
            index: 0,
            value: guess[0],
        });
    }
    let mut tried = constraints.into_iter().map(|constraint| {
        refine(
            p,
            q,
            guess,
            constraint,
            opts.newton_tolerance,
            opts.max_newton_iterations,
        )
    });
    let first = tried.next().expect("at least one constraint");
    let r = match first {
        Ok(r) => r,
        Err(e) => tried.find_map(|r| r.ok()).ok_or(e)?,
    };
    // A guess next to the boundary can refine to a point just outside (a short arc dipping into
    // the domain): the start is then the nearby point where the curve crosses the boundary.
    let x = if inside(&r.x, &dp, &dq, opts.domain_tolerance) {
        r.x
    } else {
        onto_boundary(p, q, r.x, opts).unwrap_or(r.x)
    };
    Ok(node_at(p, q, x, 0, None))
}

fn to_curve_point(n: &Node) -> CurvePoint {
    CurvePoint {
        p: [n.x[0], n.x[1]],
        q: [n.x[2], n.x[3]],
        xyz: [n.frame.xyz.x, n.frame.xyz.y, n.frame.xyz.z],
    }
}

/// Traces the arc leaving the singular point `node` through its exit point `exit` (a curve point
/// near it, see [`analyse_node`](crate::pair::branch_point::analyse_node)): the march starts at the exit,
/// heading away from the node, and runs until a stop rule fires (no loop closure: an arc from a
/// node ends at a node, a boundary, or the budget). The branch starts with the node itself, then
/// the exit. Errors: invalid options or a non-finite point ([`Error::InvalidInput`]).
pub fn trace_from_node<S1, S2>(
    p: &S1,
    q: &S2,
    node: [f64; 4],
    exit: [f64; 4],
    opts: &MarchOptions,
) -> Result<TracedBranch>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    check_options(opts)?;
    if let Some(i) = node.iter().chain(&exit).position(|c| !c.is_finite()) {
        return Err(bad(&format!("node/exit[{i}]"), InputProblem::NonFinite));
    }
    let n0 = node_at(p, q, node, 0, None);
    let away = p.point(exit[0], exit[1]) - n0.frame.xyz;
    let st = node_at(p, q, exit, 0, Some(away));
    let opts_arc = MarchOptions {
        cross_singular: 0,
        ..*opts
    };
    let half = march_half(
        p,
        q,
        &st,
        &opts_arc,
        opts.max_points.saturating_sub(2),
        None,
    );
    let mut nodes = vec![n0, st];
    nodes.extend(half.nodes.iter().copied());
    let mut events = half.events.clone();
    events.insert(0, make_event(EventKind::Singular, &n0));
    Ok(assemble(
        nodes,
        [EndReason::Singular, half.end],
        events,
        half.turning,
        half.retried,
    ))
}

/// Traces the branch of `P ∩ Q` through `start = (σ, t, u, v)` (a guess close to the curve).
///
/// The start is refined by Newton first; if it lies on a domain boundary it stays there and the
/// march goes one way only (into the domains), that end being `Boundary`. Otherwise the march goes
/// forward along `N^P × N^Q`, and backward too unless the forward march closed a loop.
///
/// Guarantees: every point satisfies `|P − Q| ≤ opts.newton_tolerance` (except points of a
/// closed loop's closing copy, which is the start itself); both ends carry their [`EndReason`];
/// singular and boundary ends are also reported as [`Event`]s. Errors: invalid options or a non-finite start
/// ([`Error::InvalidInput`]); a start Newton cannot refine ([`Error::NewtonFailed`]).
pub fn trace_branch<S1, S2>(
    p: &S1,
    q: &S2,
    start: [f64; 4],
    opts: &MarchOptions,
) -> Result<TracedBranch>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    check_options(opts)?;
    if let Some(i) = start.iter().position(|c| !c.is_finite()) {
        return Err(bad(&format!("start[{i}]"), InputProblem::NonFinite));
    }
    let s = refine_start(p, q, start, opts)?;
    let mut events = Vec::new();

    let (back, fwd, first_end) = if s.frame.sine < opts.singular_sine {
        events.push(make_event(EventKind::Singular, &s));
        (None, None, EndReason::Singular)
    } else {
        let on_edge = boundary_surface_of(p, q, &s, opts);
        // Where the curve only touches a face, the start is no end: from inside it lies within
        // a branch (a closed loop may pass through it), traced as an interior start with
        // closing allowed; from outside it is all the domain holds of the curve (one point).
        let touch = on_edge.and_then(|_| touching(p, q, &s, opts));
        let on_edge = on_edge.filter(|_| touch != Some(true));
        let (fwd_ok, back_ok) = (enters(p, q, &s, 1.0), enters(p, q, &s, -1.0));
        let budget = opts.max_points - 1;
        match on_edge {
            Some(surface) if touch == Some(false) => {
                events.push(make_event(EventKind::BoundaryEnd, &s));
                (None, None, EndReason::Boundary { surface })
            }
            Some(surface) if fwd_ok != back_ok => {
                // One way only; orient the start so that forward is inward.
                let st = if fwd_ok {
                    s
                } else {
                    node_at(p, q, s.x, 0, Some(-s.frame.tangent))
                };
                events.push(make_event(EventKind::BoundaryEnd, &st));
                let f = march_half(p, q, &st, opts, budget, None);
                (None, Some((st, f)), EndReason::Boundary { surface })
            }
            _ => {
                let interior = on_edge.is_none();
                let f = march_half(p, q, &s, opts, budget, interior.then_some((&s, [0.0; 2])));
                if f.end == EndReason::ClosedLoop {
                    (None, Some((s, f)), EndReason::ClosedLoop)
                } else {
                    let rev = s.frame.tangent;
                    let sb = node_at(p, q, s.x, 0, Some(-rev));
                    let left = budget.saturating_sub(f.nodes.len());
                    // Where the forward half stopped short (Newton failed, as on a tiny loop of
                    // nearly tangent surfaces), the backward half may come round to that point.
                    let stopped = matches!(f.end, EndReason::NewtonFailed);
                    let last = f.nodes.last().map(|n| Node {
                        frame: n.frame.reversed(),
                        ..*n
                    });
                    let target = last
                        .as_ref()
                        .filter(|_| interior && stopped)
                        .map(|n| (n, [-f.turning[0], -f.turning[1]]));
                    let b = march_half(p, q, &sb, opts, left, target);
                    let end = b.end;
                    (Some(b), Some((s, f)), end)
                }
            }
        }
    };

    // Join: reversed backward half, start, forward half.
    let mut nodes: Vec<Node> = Vec::new();
    let mut turning = [0.0, 0.0];
    let mut retried = 0;
    if let Some(b) = &back {
        for n in b.nodes.iter().rev() {
            nodes.push(Node {
                frame: n.frame.reversed(),
                ..*n
            });
        }
        turning = [turning[0] - b.turning[0], turning[1] - b.turning[1]];
        retried += b.retried;
        events.extend(b.events.iter().copied());
    }
    let last_end = match &fwd {
        // The backward half closed the loop at the forward half's last point.
        Some((st, f)) if first_end == EndReason::ClosedLoop && back.is_some() => {
            nodes.push(*st);
            nodes.extend(f.nodes.iter().copied());
            add_turn(&mut turning, f.turning);
            retried += f.retried;
            events.extend(f.events.iter().copied());
            EndReason::ClosedLoop
        }
        Some((st, f)) => {
            nodes.push(*st);
            nodes.extend(f.nodes.iter().copied());
            add_turn(&mut turning, f.turning);
            retried += f.retried;
            events.extend(f.events.iter().copied());
            f.end
        }
        None => {
            nodes.push(s);
            first_end
        }
    };
    Ok(assemble(
        nodes,
        [first_end, last_end],
        events,
        turning,
        retried,
    ))
}

/// The traced branch from its points, ends, events, turning (in P's and Q's domains) and retry
/// count: closed when the last end closes a loop, open when both ends are regular (boundary or
/// singular point), incomplete otherwise; with the Newton-iteration histogram.
fn assemble(
    nodes: Vec<Node>,
    ends: [EndReason; 2],
    events: Vec<Event>,
    turning: [f64; 2],
    retried: usize,
) -> TracedBranch {
    let status = BranchStatus::of_ends(&ends);
    let mut histogram = Vec::new();
    for n in &nodes {
        if histogram.len() <= n.iterations {
            histogram.resize(n.iterations + 1, 0);
        }
        histogram[n.iterations] += 1;
    }
    TracedBranch {
        branch: Branch {
            id: 0,
            status,
            ends,
            points: nodes.iter().map(to_curve_point).collect(),
        },
        newton_iterations: nodes.iter().map(|n| n.iterations).collect(),
        tangents: nodes
            .iter()
            .map(|n| [n.frame.tangent.x, n.frame.tangent.y, n.frame.tangent.z])
            .collect(),
        events,
        turning: turning[0],
        turning_q: turning[1],
        stats: MarchStats {
            points: nodes.len(),
            newton_histogram: histogram,
            retried_steps: retried,
        },
    }
}
