//! Slivers at a vertex: branches that hold no more of a curve than a point where it passes a
//! vertex of the shell.
//!
//! Where a curve passes within rounding of a vertex at which three or more faces meet (a plane
//! through the corner of a box), the face it does not really cross there may still meet it in
//! a sliver a few ulps long: whether it does depends on the last bit of the input. Its branch
//! is certified like any other, so it is a true piece of the intersection, but as a curve of
//! its own it is noise: an edge shorter than any tolerance, and its ends take the join slots
//! that belong to the faces the curve really passes between.
//!
//! Two rules handle it:
//!
//! 1. **Ranking** ([`small`]): a join candidate with a branch whose marched points span no
//!    more than the requested tolerance ranks after every other candidate of the same status,
//!    so the faces on either side of the vertex are joined to each other first (guidance: the
//!    candidates' own proofs are unchanged).
//! 2. **Absorbing** ([`absorb`]): a certified branch that is left in no join, and whose
//!    enclosure boxes together with the proven end boxes of a proven join on a shared edge fit
//!    in a model box of diameter at most the requested tolerance, is absorbed by that join. The
//!    join then carries that box (`CornerJoin`): it holds the join's end point and every
//!    point of the sliver's true curve (which lies in the sliver's boxes), so each lies within
//!    the box's diameter of a point of the joined curve, and the curve's certified tolerance
//!    counts that diameter as it does a corner's.

use inari::Interval;

use super::corner::diameter;
use super::sites::patches;
use super::{Face, PieceIntersection};
use crate::certify::contact_cover::{contact_cover, CoverBox, CoverOptions};
use crate::geometry::surface::{pair_bounds, pair_widths};
use crate::geometry::RationalBezierPatch;
use crate::march::branch::CurvePoint;
use crate::numeric::scalar::interval;

/// Per shell-wide branch (`index`: its pair and its place there): whether its marched points
/// span no more than the requested tolerance in model space.
pub(super) fn small(pairs: &[PieceIntersection], index: &[(usize, usize)]) -> Vec<bool> {
    index
        .iter()
        .map(|&(k, i)| {
            let points = &pairs[k].result.branches[i].marched.points;
            let tolerance = pairs[k].result.options.required_tolerance;
            let span = (0..3)
                .map(|c| {
                    let (lo, hi) = points
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |m, p| {
                            (m.0.min(p.xyz[c]), m.1.max(p.xyz[c]))
                        });
                    (hi - lo).powi(2)
                })
                .sum::<f64>()
                .sqrt();
            !points.is_empty() && span <= tolerance
        })
        .collect()
}

/// The hull of two model boxes.
pub(super) fn hull(x: &[Interval; 3], y: &[Interval; 3]) -> [Interval; 3] {
    std::array::from_fn(|c| x[c].convex_hull(y[c]))
}

/// The farthest a sliver's cover reaches round its marched points, relative to each
/// parameter's range.
const MARGIN: f64 = 1.0 / 1_048_576.0;

/// The smallest leaf of a sliver's cover, relative to each parameter's range.
const LEAF_LEAST: f64 = 1.0 / 281_474_976_710_656.0;

/// The evaluation budget of a sliver's cover (a sliver at a box's corner took 400 to 7 000,
/// and 14 400 where the curve runs within a degree of an edge).
const BUDGET: usize = 20_000;

/// A model box holding every intersection point of the pieces `pq` near the marched points
/// `points`, proven to be all of the curve there: a cover of the parameter box round them
/// (widened by 1 024 leaves, at most [`MARGIN`] of each range, clipped to the domains) whose
/// kept boxes all lie
/// strictly inside every side of it that is not a side of a domain, so no curve leaves the
/// box except across the pieces' sides. `None` when that cannot be shown, or nothing is kept.
fn enclosed(
    pq: [&RationalBezierPatch; 2],
    points: &[CurvePoint],
    tolerance: f64,
) -> Option<[Interval; 3]> {
    let (dp, dq) = (pq[0].domain(), pq[1].domain());
    let widths = pair_widths(&dp, &dq);
    let coords = |c: &CurvePoint| [c.p[0], c.p[1], c.q[0], c.q[1]];
    // Leaves of a sixty-fourth of the tolerance in model space (nominally: a piece's size over
    // its domain), so that the leaves a sliver keeps fit in the tolerance even where the curve
    // runs close to an edge, and a region 16 times the tolerance round its points.
    let size = pq[0].model_width().max(pq[1].model_width());
    let leaf = (tolerance / (64.0 * size)).clamp(LEAF_LEAST, MARGIN / 1024.0);
    let margin = 1024.0 * leaf;
    let mut region = [Interval::EMPTY; 4];
    for (i, r) in region.iter_mut().enumerate() {
        let (lo, hi) = points
            .iter()
            .map(|c| coords(c)[i])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |m, x| {
                (m.0.min(x), m.1.max(x))
            });
        let m = margin * widths[i];
        *r = interval(lo - m, hi + m)?;
    }
    let opts = CoverOptions {
        leaf_fraction: leaf,
        max_evaluations: BUDGET,
    };
    let cover = contact_cover(pq[0], pq[1], &[region], &opts);
    if !cover.resolved {
        return None;
    }
    // Per parameter: the region's bounds that lie inside the domain (sides a curve could
    // leave the region by without leaving the pieces).
    let open: [[Option<f64>; 2]; 4] = std::array::from_fn(|i| {
        let [lo, hi] = pair_bounds(&dp, &dq, i);
        let r = region[i];
        [
            (r.inf() > lo).then_some(r.inf()),
            (r.sup() < hi).then_some(r.sup()),
        ]
    });
    let params = |b: &CoverBox| [b.p[0], b.p[1], b.q[0], b.q[1]];
    let inside = cover.boxes.iter().all(|b| {
        params(b).iter().zip(&open).all(|(x, [lo, hi])| {
            lo.is_none_or(|lo| x.inf() > lo) && hi.is_none_or(|hi| x.sup() < hi)
        })
    });
    if !inside {
        return None;
    }
    cover
        .boxes
        .iter()
        .map(|b| b.xyz)
        .reduce(|h, x| hull(&h, &x))
}

/// The slivers (see the module documentation) among the branches `free` marks (small, in no
/// join, not absorbed), and the proven joins on shared edges that absorb them: per join of
/// `on_edges` (the hull of its two proven end boxes), `None`, or its new box and the branches
/// it absorbs.
pub(super) fn absorb(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    index: &[(usize, usize)],
    on_edges: &[[Interval; 3]],
    free: &[bool],
) -> Vec<Option<([Interval; 3], Vec<usize>)>> {
    let mut taken: Vec<Option<([Interval; 3], Vec<usize>)>> = vec![None; on_edges.len()];
    for (g, &(k, i)) in index.iter().enumerate() {
        if !free[g] {
            continue;
        }
        let pieces = patches(a, b, &pairs[k]);
        let tolerance = pairs[k].result.options.required_tolerance;
        let points = &pairs[k].result.branches[i].marched.points;
        // Only next to such a join is a cover worth its cost (guidance: the marched points).
        let marched = points.iter().fold([Interval::EMPTY; 3], |h, p| {
            hull(
                &h,
                &p.xyz.map(|x| interval(x, x).unwrap_or(Interval::ENTIRE)),
            )
        });
        if !on_edges
            .iter()
            .any(|x| diameter(&hull(x, &marched)) <= tolerance)
        {
            continue;
        }
        let Some(own) = enclosed(pieces, points, tolerance) else {
            continue;
        };
        let best = on_edges
            .iter()
            .enumerate()
            .filter_map(|(n, xyz)| {
                let so_far = taken[n].as_ref().map_or(xyz, |t| &t.0);
                let both = hull(so_far, &own);
                let d = diameter(&both);
                (d <= tolerance).then_some((d, n, both))
            })
            .min_by(|p, q| p.0.total_cmp(&q.0));
        if let Some((_, n, both)) = best {
            let entry = taken[n].get_or_insert_with(|| (both, Vec::new()));
            entry.0 = both;
            entry.1.push(g);
        }
    }
    taken
}
