//! Branches the marcher traced twice: at a near-crossing of two curves (closer than its step
//! can tell apart) the marcher can jump from one curve to the other and go on along a curve
//! another branch already traced. The cover chain of such a branch stops at the jump, or follows
//! the true curve away from the marched points, and what it certified lies on other branches.
//!
//! A branch is dropped as a **duplicate** when every one of its marched points (but an end point
//! on a domain boundary, [`inner_points`]) lies in a tube piece of another kept branch's cover
//! chain (the piece's reported curve ± its proven parameter
//! radius, plus the marcher's Newton tolerance). Usually its certificate stops short at an end
//! (`close_branches` at the jump, `singular` where the close curves look like a singular point,
//! `unproven` where the chain left the marched points); after a stretch is traced again
//! (`solve/repair.rs`) it may also be a whole copy of a branch traced with the finer step. Then
//! its whole marched path, and with it everything its certificate covers, is
//! certified by other branches, so no component loses its only trace. Dropping claims nothing;
//! the test is in `f64` because it only decides what is reported twice. (Two distinct curves
//! within the certified tolerance of each other along a whole branch would be taken for one:
//! no certificate at that tolerance tells them apart.)

use crate::certify::{CertifiedBranch, CertifiedEnd, TubePiece};
use crate::geometry::surface::pair_widths;
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, CurvePoint, EndReason};
use crate::pair::tangent::normals_sine_sqr;

/// Which branches are duplicates (see the module documentation): a branch is tested against the
/// branches not dropped before it and all after it, those whose certificate stops short first.
pub(crate) fn duplicate_branches(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    marched: &[Branch],
    certified: &[Option<&CertifiedBranch>],
    newton_tolerance: f64,
) -> Vec<bool> {
    let scales = pair_widths(&p.domain(), &q.domain());
    let mut dropped = vec![false; marched.len()];
    // Branches whose certificate stops short are tested first (then the complete ones, each
    // against what is left), so a whole certified copy is kept in preference to a partial one.
    let complete =
        |i: usize| certified[i].is_some_and(|c| c.ends.iter().all(CertifiedEnd::reaches_true_end));
    let every_tube: Vec<&TubePiece> = certified.iter().flatten().flat_map(|c| &c.tubes).collect();
    let mut order: Vec<usize> = (0..marched.len()).collect();
    order.sort_by_key(|&i| complete(i));
    for i in order {
        let others: Vec<&TubePiece> = (0..marched.len())
            .filter(|&j| j != i && !dropped[j])
            .filter_map(|j| certified[j])
            .flat_map(|c| &c.tubes)
            .collect();
        let held = |pt: &CurvePoint, tubes: &[&TubePiece]| {
            let x = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
            let slack = newton_tolerance.max(rounding_offset(p, q, pt));
            tubes.iter().any(|t| t.holds(&x, &scales, slack))
        };
        let inner = inner_points(&marched[i]);
        let by_others: Vec<bool> = inner.iter().map(|pt| held(pt, &others)).collect();
        // The last points before a boundary end can lie beyond every certificate (a node just
        // outside the domain: each chain stops in a box round it); they are no reason to keep
        // a copy when another kept branch ends at the same point (its own marched points
        // there stand for that stretch), as long as the copy's other points are held.
        let tail = |end: usize| {
            let n = inner.len();
            let run = (0..n)
                .map(|k| if end == 0 { k } else { n - 1 - k })
                .take_while(|&k| !by_others[k])
                .count();
            let unheld = (0..run)
                .map(|k| if end == 0 { k } else { n - 1 - k })
                .all(|k| !held(&inner[k], &every_tube));
            let shared = shares_end(marched, &dropped, i, end, certified, newton_tolerance);
            (unheld && shared).then_some(run)
        };
        let (head, rest) = (tail(0).unwrap_or(0), tail(1).unwrap_or(0));
        dropped[i] = !others.is_empty()
            && head + rest < inner.len()
            && by_others[head..inner.len() - rest].iter().all(|b| *b);
    }
    dropped
}

/// Whether end `end` of branch `i` is a boundary end at the end point of another kept branch
/// with a certificate (within `tolerance` in every parameter, relative to the domains).
fn shares_end(
    marched: &[Branch],
    dropped: &[bool],
    i: usize,
    end: usize,
    certified: &[Option<&CertifiedBranch>],
    tolerance: f64,
) -> bool {
    let b = &marched[i];
    if !matches!(b.ends[end], EndReason::Boundary { .. }) {
        return false;
    }
    let at = |c: &CurvePoint| [c.p[0], c.p[1], c.q[0], c.q[1]];
    let x = at(if end == 0 {
        &b.points[0]
    } else {
        &b.points[b.points.len() - 1]
    });
    let near = |y: [f64; 4]| (0..4).all(|k| (x[k] - y[k]).abs() <= tolerance * (1.0 + x[k].abs()));
    (0..marched.len())
        .filter(|&j| j != i && !dropped[j] && certified[j].is_some())
        .any(|j| {
            let o = &marched[j];
            [&o.points[0], &o.points[o.points.len() - 1]]
                .iter()
                .any(|c| near(at(c)))
        })
}

/// Ulps of the model's coordinates that an `f64` evaluation of `P − Q` rounds by (a few per
/// operation of the patches' evaluation).
const RESIDUAL_ULPS: f64 = 16.0;

/// How far rounding alone can put the marched point `pt` off its curve, in parameters: the
/// residual's rounding over the sine of the normals' angle there (at most 1e-6). Next to the
/// tight turn of a curve on nearly tangent surfaces (normals 1.4e-7 apart) a march's points
/// were up to 7e-9 off, and a trace that stopped there was not seen as a copy of the branch
/// that went round the turn (an arc reported twice). Two distinct curves that close are about
/// a sine over the normals' relative curvature apart, far more at any sine the march resolves
/// (above 1e-7).
fn rounding_offset(p: &RationalBezierPatch, q: &RationalBezierPatch, pt: &CurvePoint) -> f64 {
    let x = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
    let size = 1.0 + pt.xyz.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let sine = normals_sine_sqr(p, q, &x).sqrt();
    (RESIDUAL_ULPS * f64::EPSILON * size / sine).min(1e-6)
}

/// The marched points a copy must hold: all but an end point on a domain boundary or at a
/// singular point, when two or more points are left. A boundary point is the exit itself; a
/// chain that proves the same exit stops with its last link across the boundary, but the
/// link's range in its along parameter can end just short of the point (in a parameter that
/// moves slowly there). A singular end point is where the marcher located a node; where the
/// surfaces are only nearly tangent (two curves passing close, like the two branches of a
/// hyperbola) it is the point of closest approach between them, on neither curve, and the
/// chain of the branch that goes on along the true curve passes beside it.
fn inner_points(b: &Branch) -> &[CurvePoint] {
    let n = b.points.len();
    if n <= 2 {
        return &b.points;
    }
    let lo = usize::from(b.ends[0].is_regular());
    let hi = n - usize::from(b.ends[1].is_regular());
    if hi < lo + 2 {
        // Too few would be left: keep the singular end's point.
        let boundary = |e: &EndReason| matches!(e, EndReason::Boundary { .. });
        let lo = usize::from(boundary(&b.ends[0]));
        let hi = n - usize::from(boundary(&b.ends[1]));
        return &b.points[lo..hi];
    }
    &b.points[lo..hi]
}
