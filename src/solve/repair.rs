//! Stretches of curve that a marcher jump left without a certificate, traced again with a finer
//! step.
//!
//! At a near-crossing of two curves (two arms of a hyperbola-like pair, closer together than the
//! march step can tell apart) the marcher can step from one curve onto the other and go on as if
//! nothing happened: its branch ends cleanly on boundaries, but the cover chain of that branch
//! cannot follow the jump and stops there (`singular box`, `close branches` or `unproven`). The
//! arm the marcher walked on the far side of the jump from the chain's start is then certified by
//! no branch, and the arm it skipped may be traced by nobody (a torus's saddle side against a
//! nearly tangent plane, in the quadric oracle).
//!
//! **The rule.** A branch is *suspect* when the marcher ended it cleanly (on boundaries, closed,
//! or back on its own path: a loop of another curve reached after a jump) but its certificate stops short at some end as if at a singular point or at
//! branches too close to resolve (a budget, a time limit or an unproven end is not a jump), or
//! when the marched points at one of its ends lie in no tube of its own certificate (the chain left the
//! marched points and proved where its own curve leaves the domain). A run of at least two of
//! its marched points that lie in no tube piece of any certified branch (the same test as for
//! duplicates) is *uncovered*; the middle point of each uncovered run is a start for a new trace
//! with the step divided by 8 (then by 64 in a second round, if uncovered runs remain), and so
//! is the point where its chain stopped (the end of its tube nearest the stop box): the chain
//! was still on its own curve there, and the arm the marcher skipped goes on from it with no
//! marched point on it. The new branches are certified like the others; the duplicate rule
//! ([`super::duplicates`]) then drops the suspects whose marched points are all certified by
//! other branches. Nothing here claims anything: it only decides
//! what to trace again, so it is in `f64`.

use crate::certify::{CertifiedBranch, CertifiedEnd, TubePiece};
use crate::geometry::surface::pair_widths;
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, BranchStatus, CurvePoint, EndReason};
use inari::Interval;

/// Uncovered runs shorter than this many marched points are not traced again (the last point of
/// an arc ending at a node lies at the node, beyond the chain's proven approach to it).
const MIN_UNCOVERED_RUN: usize = 2;

/// Starts for tracing again: the middle point of every uncovered run of every suspect branch
/// (see the module documentation).
pub(crate) fn uncovered_starts(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    marched: &[Branch],
    certified: &[Option<&CertifiedBranch>],
    slack: f64,
) -> Vec<[f64; 4]> {
    let scales = pair_widths(&p.domain(), &q.domain());
    let tubes: Vec<&TubePiece> = certified.iter().flatten().flat_map(|c| &c.tubes).collect();
    let mut starts = Vec::new();
    for (i, (b, c)) in marched.iter().zip(certified).enumerate() {
        if !suspect(b, *c, &scales, slack) {
            continue;
        }
        // Where the chain stopped, it was still on its own curve: the arm the marcher skipped
        // goes on from there, and no marched point lies on it. Unless a complete certificate
        // of another branch already holds that point (traced again in an earlier round): a
        // partial one that holds it is a second jumping branch over the same curve (two
        // branches that each passed a near self-crossing once and jumped at the second pass:
        // together they cover the curve, each stretch between the passes twice), so the point
        // is traced again all the same.
        let others: Vec<&TubePiece> = certified
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .filter_map(|(_, c)| *c)
            .filter(|c| c.ends.iter().all(CertifiedEnd::reaches_true_end))
            .flat_map(|c| &c.tubes)
            .collect();
        for (c, near) in c
            .iter()
            .flat_map(|c| c.ends.iter().filter_map(jump_box).map(move |n| (*c, n)))
        {
            let x = stop_point(c, near, &scales);
            if !others.iter().any(|t| t.holds(&x, &scales, slack)) {
                starts.push(x);
            }
        }
        let covered: Vec<bool> = b
            .points
            .iter()
            .map(|pt| {
                let x = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
                tubes.iter().any(|t| t.holds(&x, &scales, slack))
            })
            .collect();
        let mut k = 0;
        while k < covered.len() {
            if covered[k] {
                k += 1;
                continue;
            }
            let run = k..covered[k..]
                .iter()
                .position(|c| *c)
                .map_or(covered.len(), |n| k + n);
            if run.len() >= MIN_UNCOVERED_RUN {
                let pt = &b.points[(run.start + run.end) / 2];
                starts.push([pt.p[0], pt.p[1], pt.q[0], pt.q[1]]);
            }
            k = run.end;
        }
    }
    starts
}

/// The point of `c`'s chain where it stopped at the box `near`: the end of a tube piece nearest
/// the box's centre (on the chain's curve, to within its proven radius; the centre itself can
/// lie between two close curves, where Newton finds neither).
fn stop_point(c: &CertifiedBranch, near: &[Interval; 4], scales: &[f64; 4]) -> [f64; 4] {
    let centre: [f64; 4] = std::array::from_fn(|k| near[k].mid());
    let dist = |x: &[f64; 4]| {
        (0..4)
            .map(|k| (x[k] - centre[k]).abs() / scales[k])
            .fold(0.0, f64::max)
    };
    c.tubes
        .iter()
        .flat_map(|t| [t.eval(0.0), t.eval(t.h)])
        .min_by(|a, b| dist(a).total_cmp(&dist(b)))
        .unwrap_or(centre)
}

/// Whether the marcher ended the branch cleanly but its certificate stops short as at a jump,
/// or follows another curve than the march to one of its ends (the last [`MIN_UNCOVERED_RUN`]
/// marched points at an end held by no tube of its own certificate: the chain left the marched
/// points and proved where its own curve leaves the domain, `certify/chain/leave.rs`; a single
/// end point can lie just beyond a certificate that stops on the boundary). Only cover chains
/// follow the marched points; the Taylor engine's steps and tubes need not reach them. (A
/// chain that stops short of an end for a budget says so in its end instead.)
fn suspect(b: &Branch, c: Option<&CertifiedBranch>, scales: &[f64; 4], slack: f64) -> bool {
    let clean = b.status == BranchStatus::Closed
        || b.ends.iter().all(|e| {
            matches!(
                e,
                EndReason::Boundary { .. } | EndReason::ClosedLoop | EndReason::OwnPath
            )
        });
    let Some(c) = c.filter(|_| clean) else {
        return false;
    };
    let held = |pt: &CurvePoint| {
        let x = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
        c.tubes.iter().any(|t| t.holds(&x, scales, slack))
    };
    let n = b.points.len();
    let k = MIN_UNCOVERED_RUN.min(n);
    c.ends.iter().any(|e| jump_box(e).is_some())
        || (!c.arc_length_proven()
            && c.ends.iter().all(CertifiedEnd::reaches_true_end)
            && n > k
            && [&b.points[..k], &b.points[n - k..]]
                .iter()
                .any(|end| end.iter().all(|pt| !held(pt))))
}

/// The box where a chain stopped as at a marcher jump: a singular box, or two branches too
/// close to resolve. An `unproven` end is a budget or a time limit, or a failure that a finer
/// step does not mend.
fn jump_box(e: &CertifiedEnd) -> Option<&[Interval; 4]> {
    match e {
        CertifiedEnd::Singular { near } | CertifiedEnd::CloseBranches { near, .. } => Some(near),
        _ => None,
    }
}

/// Whether a branch traced again certifies something new: its certificate reaches a true end
/// at both ends (a closed loop, or boundaries: the duplicate rule then prefers it to a copy
/// that stops short), or one of its marched points is held by a tube of its own certificate
/// and by none of `before` (the certified branches so far). A branch whose certification
/// failed is kept if one of its points is held by none of `before` (it may be an arm no other
/// branch reached).
pub(crate) fn adds_cover(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &Branch,
    own: Option<&CertifiedBranch>,
    before: &[&TubePiece],
    slack: f64,
) -> bool {
    if own.is_some_and(|c| c.ends.iter().all(CertifiedEnd::reaches_true_end)) {
        return true;
    }
    let scales = pair_widths(&p.domain(), &q.domain());
    b.points.iter().any(|pt| {
        let x = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
        own.is_none_or(|own| own.tubes.iter().any(|t| t.holds(&x, &scales, slack)))
            && !before.iter().any(|t| t.holds(&x, &scales, slack))
    })
}
