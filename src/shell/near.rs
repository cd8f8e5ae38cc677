//! Joins across sides that agree only to within a distance
//! ([`EdgeKind::NearEdge`](super::edges::EdgeKind::NearEdge)).
//!
//! Faces whose corners were computed apart (each face's from its own origin and edge vectors,
//! or written by a kernel to its modelling tolerance) share no boundary row exactly, and a curve
//! crossing from one to the other came back as separate open pieces. Where two sides are
//! matched by [`near_edges`] (the same weights, control points within the required tolerance,
//! so the sides are within a proven `mismatch` of each other at corresponding parameters), the
//! two surfaces' curves do not meet: each ends on its own side, near the other's end. A join
//! there is proven when both ends are certified exits on their sides (each the only crossing of
//! its side in its uniqueness region) within the two tolerances and the mismatch of each other;
//! the hull of the two exit boxes holds both true end points, and the joined curve's tolerance
//! counts its diameter, as for a join across a corner. Candidates come from the same sites as
//! the exact joins; without certificates the marched ends must agree as for an exact edge.

use inari::Interval;

use super::edges::{near_edges, EdgeLink, NearLink};
use super::sites::{box_gap, marched_gap, EndSite, SiteIndex};
use super::{Face, PieceIntersection};

/// What a near join candidate's evidence is: `None` marched (the method does not certify),
/// `Ok` proven with the box holding both end points, `Err` unproven with the reason.
pub(super) type Verdict = Option<Result<[Interval; 3], &'static str>>;

/// A near join candidate: the gap, the two sites and the verdict.
pub(super) type NearCandidate = (f64, usize, usize, Verdict);

/// The near links of both shells (sides matched within the required tolerance of the pairs;
/// `exact`: each shell's exact links, [`shared_edges`](super::edges::shared_edges)).
pub(super) fn links(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    exact: &[Vec<EdgeLink>; 2],
) -> [Vec<NearLink>; 2] {
    let within = pairs
        .first()
        .map_or(0.0, |p| p.result.options.required_tolerance);
    [
        near_edges(a, &exact[0], within),
        near_edges(b, &exact[1], within),
    ]
}

/// The join candidates across near links (see the module documentation).
pub(super) fn candidates(
    pairs: &[PieceIntersection],
    sites: &[EndSite<'_>],
    links: &[Vec<NearLink>; 2],
    index: &SiteIndex<'_>,
) -> Vec<NearCandidate> {
    index
        .across(pairs, sites, links, |l| &l.link)
        .into_iter()
        .filter_map(|(x, y, near)| {
            let (gap, verdict) = candidate(pairs, &sites[x], &sites[y], near.mismatch)?;
            Some((gap, x, y, verdict))
        })
        .collect()
}

/// Whether `s1` and `s2`, on sides within `mismatch` of each other, may be joined: the gap, the
/// verdict. The ends are candidates when their certified exit
/// boxes are within the two tolerances and the mismatch of each other, or their marched points
/// within [`MARCH_JOIN_TOLERANCE`](super::sites::MARCH_JOIN_TOLERANCE) (a curve crossing the
/// edge at a small angle ends farther along it on one side than on the other); the join is
/// proven when both exits are.
fn candidate(
    pairs: &[PieceIntersection],
    s1: &EndSite,
    s2: &EndSite,
    mismatch: f64,
) -> Option<(f64, Verdict)> {
    let marched = marched_gap(&s1.point, &s2.point);
    if let (Some(x1), Some(x2), Some(t1), Some(t2)) =
        (&s1.exit, &s2.exit, s1.tolerance, s2.tolerance)
    {
        let gap = box_gap(&x1.xyz, &x2.xyz);
        if gap <= t1 + t2 + mismatch || marched.is_some() {
            let hull = std::array::from_fn(|k| x1.xyz[k].convex_hull(x2.xyz[k]));
            return Some((gap, Some(Ok(hull))));
        }
    }
    let gap = marched?;
    let certifies = pairs[s1.pair].result.options.method.certifies();
    let verdict = certifies.then_some(Err("an end is not certified on the nearly shared edge"));
    Some((gap, verdict))
}
