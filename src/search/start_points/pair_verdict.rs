//! One pair of pieces of the interior search, tested on its own (pure, so a level's pairs are
//! tested in parallel): disjoint, loop-free, undecided at the smallest size, or split.

use super::critical_cover::{prove_by_cover, MAX_CELLS};
use super::{diameter, Ctx};
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::piece::Piece;
use crate::geometry::ParametricSurface;
use crate::geometry::RationalBezierPatch;
use crate::search::loop_exclusion::loop_test;

/// What the tests say of one pair of pieces.
pub(super) enum PairVerdict {
    /// Their rigorous boxes are disjoint.
    Disjoint,
    /// The loop test proved the pair loop-free (its faces are searched next).
    LoopFree,
    /// Both pieces at the smallest size and still neither: undecided.
    Undecided,
    /// Split one piece: the two new pairs.
    Split(Vec<(Piece, Piece)>),
}

/// Tests one pair of pieces (pure: no report, no budget).
pub(super) fn classify_pair(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    a: &Piece,
    b: &Piece,
) -> PairVerdict {
    let (ea, eb) = (a.bounds(), b.bounds());
    if boxes_disjoint(&ea, &eb) || separated_across(a, b) {
        return PairVerdict::Disjoint;
    }
    let test = loop_test(p, a, q, b);
    if test.proof.is_some() {
        return PairVerdict::LoopFree;
    }
    let (wa, wb) = (diameter(&ea), diameter(&eb));
    if cover_settles(ctx, p, q, a, b, wa, wb) {
        return PairVerdict::LoopFree;
    }
    if wa <= ctx.min_pair && wb <= ctx.min_pair {
        return PairVerdict::Undecided;
    }
    // Split the piece whose size times normal spread is larger (the one that keeps the test
    // from succeeding): a flat piece is never split for the loop test's sake.
    let [sa, sb] = test.spread;
    let (ka, kb) = (wa * sa.min(1e300), wb * sb.min(1e300));
    let split_a = if ka == kb || !(ka.is_finite() && kb.is_finite()) {
        wa >= wb
    } else {
        ka > kb
    };
    let split_a = if wa <= ctx.min_pair {
        false
    } else if wb <= ctx.min_pair {
        true
    } else {
        split_a
    };
    let halves = if split_a {
        a.split(a.split_direction())
            .into_iter()
            .map(|half| (half, b.clone()))
            .collect()
    } else {
        b.split(b.split_direction())
            .into_iter()
            .map(|half| (a.clone(), half))
            .collect()
    };
    PairVerdict::Split(halves)
}

/// Whether the critical set of the height difference over the smaller piece is covered
/// ([`prove_by_cover`]; then every component in the pair reaches the boundary of that piece,
/// and the pair counts as loop-free): tried only on pairs with one piece at most
/// [`COVER_BELOW`] of the model size and nearly parallel normals at their centres (elsewhere
/// the loop test settles pairs soon enough), and never over a piece at a pole.
fn cover_settles(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    a: &Piece,
    b: &Piece,
    wa: f64,
    wb: f64,
) -> bool {
    let size = ctx.leaf * 64.0;
    let w = wa.min(wb);
    if w > COVER_BELOW * size || w < COVER_ABOVE * size {
        return false;
    }
    let (dp, dq) = (p.domain(), q.domain());
    let (bp, bq) = (a.declared(&dp, 0.0), b.declared(&dq, 0.0));
    let (np, nq) = (
        p.derivs(bp[0].mid(), bp[1].mid()).normal(),
        q.derivs(bq[0].mid(), bq[1].mid()).normal(),
    );
    let parallel = np.cross(&nq).norm() <= 0.5 * np.norm() * nq.norm();
    // The graph over the smaller piece (the larger one holds its image more easily).
    // Not over a piece on a side its surface collapses to a pole: the normal vanishes along it,
    // so the cells there all hold critical points and must be signed, which fails wherever
    // the other surface passes near the pole (the pole cap's business). On 1 000 polar pairs
    // 68 of 128 tries failed at the full cell budget; skipping them all took the pairs from
    // 22–24 s to 6.5 s in all (worst 1.5–3.4 s to 0.05 s), and no search was left incomplete.
    let at_pole = |s: &RationalBezierPatch, x: &Piece| {
        let c = s.collapsed_sides();
        x.touches().iter().zip(&c).any(|(t, c)| *t && c.is_some())
    };
    if !parallel || (wa <= wb && at_pole(p, a)) || (wa > wb && at_pole(q, b)) {
        false
    } else if wa <= wb {
        prove_by_cover(p, a, q, b, MAX_CELLS)
    } else {
        prove_by_cover(q, b, p, a, MAX_CELLS)
    }
}

/// Pairs are tried by [`cover_settles`] once one piece is at most this fraction of the model
/// size, and no longer below [`COVER_ABOVE`] (a few levels: each failed try costs up to
/// [`MAX_CELLS`] cells, and near-tangent pairs without a covered critical set, as Fig. 7's
/// loops, fail at every level).
const COVER_BELOW: f64 = 1.0 / 16.0;

/// See [`COVER_BELOW`].
const COVER_ABOVE: f64 = 1.0 / 64.0;

/// Whether the pieces' control hulls are proven apart along the normal of one of them (a flat
/// face, as a plane far larger than its partner, is never split, and its axis-aligned box holds
/// everything near it; along its normal a piece of the other surface that does not reach it is
/// separated at once).
pub(super) fn separated_across(a: &Piece, b: &Piece) -> bool {
    [a.corner_normal(), b.corner_normal()]
        .into_iter()
        .flatten()
        .any(|d| match (a.range_along(&d), b.range_along(&d)) {
            (Some(x), Some(y)) => x.disjoint(y),
            _ => false,
        })
}
