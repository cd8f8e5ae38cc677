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
//! **The rule.** A branch is *suspect* when the marcher ended it cleanly (on boundaries, or closed)
//! but its certificate stops short at some end as if at a singular point, at branches too close
//! to resolve, or where the chain lost its marched path (a budget, a time limit or another
//! unproven end is not a jump). A run of at least two of its marched points that
//! lie in no tube piece of any certified branch (the same test as for duplicates) is *uncovered*;
//! the middle point of each uncovered run is a start for a new trace with the step divided by 8
//! (then by 64 in a second round, if uncovered runs remain), and so is the centre of the box where
//! its chain stopped: the chain was still on its own curve there, and the arm the marcher skipped
//! goes on from it with no marched point on it. The new branches are certified like
//! the others; the duplicate rule ([`super::duplicates`]) then drops the suspects whose marched
//! points are all certified by other branches. Nothing here claims anything: it only decides
//! what to trace again, so it is in `f64`.

use crate::certify::{CertifiedBranch, CertifiedEnd, TubePiece, LEFT_THE_MARCH};
use crate::geometry::surface::pair_widths;
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, BranchStatus, EndReason};
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
        if !suspect(b, *c) {
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
        for near in c.iter().flat_map(|c| &c.ends).filter_map(jump_box) {
            let x: [f64; 4] = std::array::from_fn(|k| near[k].mid());
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

/// Whether the marcher ended the branch cleanly but its certificate stops short as at a jump.
fn suspect(b: &Branch, c: Option<&CertifiedBranch>) -> bool {
    let clean = b.status == BranchStatus::Closed
        || b.ends
            .iter()
            .all(|e| matches!(e, EndReason::Boundary { .. } | EndReason::ClosedLoop));
    clean && c.is_some_and(|c| c.ends.iter().any(|e| jump_box(e).is_some()))
}

/// The box where a chain stopped as at a marcher jump: a singular box, two branches too close
/// to resolve, or a chain that lost its marched path. Another `unproven` end is a budget or a
/// time limit, or a failure that a finer step does not mend.
fn jump_box(e: &CertifiedEnd) -> Option<&[Interval; 4]> {
    match e {
        CertifiedEnd::Singular { near } | CertifiedEnd::CloseBranches { near, .. } => Some(near),
        CertifiedEnd::Unproven { reason, near } if reason == LEFT_THE_MARCH => Some(near),
        _ => None,
    }
}
