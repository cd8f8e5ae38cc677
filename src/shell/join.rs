//! Joining the branches of all piece pairs into one curve per connected intersection curve.
//!
//! Each piece pair is traced on its own, so a curve that crosses a knot line, a periodic seam
//! or an edge shared by two faces comes back as one branch per piece pair, each ending on a
//! piece boundary. [`join_branches`] glues them back together:
//!
//! 1. Every branch end that the marcher ended on the boundary of one surface is placed on a side
//!    of that surface's piece. When the branch is certified, its certified end there gets a
//!    proven *exit box* on the side: the end's last tube piece proves a true curve point beyond
//!    the side, the chain of enclosure boxes a curve point inside (the first box, walking
//!    inwards, that lies wholly on the inner side), so the curve meets the side in the boxes
//!    between; on their hull, slightly widened (the *uniqueness region*), the parametric
//!    Krawczyk test with the side's coordinate held at its value (after cutting the region
//!    into boxes proven empty or holding one zero) proves that the piece pair's curve meets the
//!    side there exactly once, and encloses that point tightly.
//! 2. Two ends are candidates for a join when their pieces share that side (see
//!    [`super::edges`]: a knot line of one face, a periodic seam, or an edge of two faces), the
//!    other surface's piece is the same, and the end points coincide: the two exit boxes (mapped
//!    across the edge) are within the sum of the branches' certified tolerances in model space,
//!    or, failing that, the marched end points are within [`MARCH_JOIN_TOLERANCE`] (relative to
//!    the model's size) in model space and their parameters along the edge and on the other
//!    surface agree to [`SIDE_TOLERANCE`] (relative to the piece's size). Candidates are accepted
//!    proven ones first, then nearest first, each end joined at most once.
//! 3. A join of two certified ends is [`JoinStatus::Proven`] when the two exit boxes overlap in
//!    model space and in all four parameters (the shared face's, mapped across the edge, and the
//!    other surface's), and one exit box lies inside the other end's uniqueness region: both
//!    true end points then lie in that region, where the curve meets the edge only once, so
//!    they are the same point. Otherwise the join is [`JoinStatus::Unproven`] with the reason;
//!    with the marching method it is [`JoinStatus::Marched`].
//!    A join through a pole (two ends on sides of one shell collapsed to the same point) is
//!    proven on a cap round the pole (`pole_cap.rs`), its arc held in a model box. Sides that
//!    agree only to within the requested tolerance (faces whose corners were computed apart)
//!    are joined with a gap, proven when both exits are, the hull of the exit boxes counted in
//!    the curve's tolerance (`near.rs`).
//! 4. The joins chain the branches into [`JoinedCurve`]s: ordered parts with orientations,
//!    closed when the chain comes back to its first part. Every branch is in exactly one curve
//!    (a branch that nothing joins is a curve of one part).

use std::collections::HashMap;

use inari::Interval;

use super::corner::{self, CornerJoin};
use super::edges::{along_range, shared_edges, side_coordinate, EdgeKind, EdgeLink, PieceSide};
use super::near;
use super::own_corner;
use super::pole_cap::{self, PoleProof};
use super::sites::{box_gap, certified_exit, end_site, marched_gap, patches, EndSite, SiteIndex};
pub use super::sites::{BranchEnd, MARCH_JOIN_TOLERANCE, SIDE_TOLERANCE};
use super::slivers;
use super::{Face, PieceIntersection};
use crate::geometry::surface::Domain;
use crate::march::branch::BranchStatus;
use crate::numeric::scalar::point;
use crate::pair::krawczyk::ParamBox;

/// Whether a join is proven.
#[derive(Debug, Clone, PartialEq)]
pub enum JoinStatus {
    /// Both ends certified, their exit boxes overlap in model space and in the parameters, and
    /// one lies in the other's uniqueness region: the two branches meet at one true point.
    Proven,
    /// The method certifies, but this join could not be proven; the branches are glued on the
    /// evidence of their end points only.
    Unproven {
        /// Why not.
        reason: &'static str,
    },
    /// The method does not certify: joined because the marched end points coincide.
    Marched,
}

impl JoinStatus {
    /// Whether the join is proven.
    pub fn is_proven(&self) -> bool {
        matches!(self, JoinStatus::Proven)
    }
}

/// Two branch ends glued across a shared edge.
#[derive(Debug, Clone, PartialEq)]
pub struct Join {
    /// The two ends, in the order of the curve (the end of one part, the start of the next).
    pub ends: [BranchEnd; 2],
    /// The kind of edge crossed.
    pub edge: EdgeKind,
    /// Whether the join is proven.
    pub status: JoinStatus,
    /// The model-space gap the ends were matched with (distance of the exit boxes, or of the
    /// marched points).
    pub gap: f64,
    /// For a join across a corner of the piece pair (both pieces change: `edge` is the first
    /// surface's edge) or of one surface's own pieces (four pieces of it meet there: `edge` and
    /// the corner's `second_edge` are both that surface's), what it crosses and covers
    /// ([`super::corner`]); for a proven join through a pole, the box holding the arc through
    /// it (`second_edge` [`EdgeKind::Pole`], see `shell/pole_cap.rs`); for a proven join
    /// across a near edge, the box holding both ends (`second_edge` [`EdgeKind::NearEdge`], see
    /// `shell/near.rs`); `None` otherwise.
    pub corner: Option<CornerJoin>,
}

/// One part of a joined curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CurvePart {
    /// The branch (shell-wide index).
    pub branch: usize,
    /// Whether the curve runs through the branch from its last point to its first.
    pub reversed: bool,
}

/// One connected intersection curve made of branches of several piece pairs.
#[derive(Debug, Clone, PartialEq)]
pub struct JoinedCurve {
    /// The parts in order along the curve.
    pub parts: Vec<CurvePart>,
    /// Whether the curve is closed (the last part joins the first, or one closed branch).
    pub closed: bool,
    /// The joins: `joins[k]` between `parts[k]` and `parts[k + 1]`, and for a closed curve of
    /// joined parts, last the one from the last part back to the first.
    pub joins: Vec<Join>,
    /// The largest certified tolerance of the parts, plus the largest diameter of a join's box
    /// (across a corner, through a pole, across a near edge, or at a vertex with slivers), when
    /// every part is
    /// certified and every join proven; `None` otherwise.
    pub certified_tolerance: Option<f64>,
}

/// The branch sequence of `pairs`: `(pair, index in the pair)` per shell-wide branch.
fn branch_index(pairs: &[PieceIntersection]) -> Vec<(usize, usize)> {
    pairs
        .iter()
        .enumerate()
        .flat_map(|(k, p)| (0..p.result.branches.len()).map(move |i| (k, i)))
        .collect()
}

/// Join the branches of all piece pairs (see the module documentation). `a` and `b` are the
/// two shells the pairs were traced on.
pub fn join_branches(a: &[Face], b: &[Face], pairs: &[PieceIntersection]) -> Vec<JoinedCurve> {
    join_and_settle(a, b, pairs).0
}

/// [`join_branches`], and the undecided search regions that its proven joins through poles
/// settle (`(pair, index of the region in the pair's list)`: every curve point there lies on
/// a proven arc through a pole, see [`pole_cap::settled`]).
pub(super) fn join_and_settle(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
) -> (Vec<JoinedCurve>, Vec<(usize, usize)>) {
    let index = branch_index(pairs);
    let links = [shared_edges(a), shared_edges(b)];
    let sites = end_sites(a, b, pairs, &index);
    let by_pair: HashMap<([usize; 2], [usize; 2]), usize> = pairs
        .iter()
        .enumerate()
        .map(|(k, p)| ((p.faces, p.pieces), k))
        .collect();
    let mut at_side: HashMap<(usize, usize, PieceSide), Vec<usize>> = HashMap::new();
    for (y, site) in sites.iter().enumerate() {
        at_side
            .entry((site.pair, site.surface, site.side))
            .or_default()
            .push(y);
    }
    let index_sites = SiteIndex {
        at_side: &at_side,
        by_pair: &by_pair,
    };
    let mut candidates = Vec::new();
    for (x, y, link) in index_sites.across(pairs, &sites, &links, |l| l) {
        if let Some(c) = candidate(a, b, pairs, &sites[x], &sites[y], link) {
            candidates.push((c.0, x, y, c.1, link.kind, Region::None));
        }
    }
    // Across sides that agree only to within the required tolerance (`near.rs`).
    let near_links = near::links(a, b, pairs, &links);
    let near = near::candidates(pairs, &sites, &near_links, &index_sites);
    let near_boxes = near_candidates(near, &mut candidates);
    let mut poles = Vec::new();
    candidates.extend(pole_candidates(a, b, pairs, &sites, &links, &mut poles));
    let mut corners = corner::candidates(a, b, pairs, &sites, &links, &by_pair);
    corners.extend(own_corner::candidates(
        a, b, pairs, &sites, &links, &by_pair,
    ));
    for (n, c) in corners.iter().enumerate() {
        let [x, y] = c.sites;
        let status = match c.status {
            _ if !pairs[sites[x].pair].result.options.method.certifies() => JoinStatus::Marched,
            Ok(()) => JoinStatus::Proven,
            Err(reason) => JoinStatus::Unproven { reason },
        };
        candidates.push((c.gap, x, y, status, c.edges[0], Region::Corner(n)));
    }
    // Proven joins first, then those without a sliver at a vertex (`slivers.rs`), then the
    // nearest.
    let small = slivers::small(pairs, &index);
    let sliver = |c: &Candidate| small[sites[c.1].at.branch] || small[sites[c.2].at.branch];
    candidates.sort_by(|p, q| {
        (!p.3.is_proven(), sliver(p))
            .cmp(&(!q.3.is_proven(), sliver(q)))
            .then(p.0.total_cmp(&q.0))
    });
    let first_branch: Vec<usize> = pairs
        .iter()
        .scan(0, |n, p| {
            let f = *n;
            *n += p.result.branches.len();
            Some(f)
        })
        .collect();
    // Per branch end: an end with a site on each side is joined once.
    let mut used: std::collections::HashSet<BranchEnd> = std::collections::HashSet::new();
    let mut absorbed = vec![false; index.len()];
    let mut joins: HashMap<BranchEnd, JoinValue> = HashMap::new();
    let mut settled = Vec::new();
    // Proven joins on a shared edge, with the hull of their two proven end boxes.
    let mut on_edges = Vec::new();
    for (gap, x, y, status, kind, region) in candidates {
        let (e1, e2) = (sites[x].at, sites[y].at);
        if used.contains(&e1) || used.contains(&e2) || absorbed[e1.branch] || absorbed[e2.branch] {
            continue;
        }
        used.insert(e1);
        used.insert(e2);
        let corner = match region {
            Region::None => {
                if let (true, Some(x1), Some(x2)) =
                    (status.is_proven(), &sites[x].exit, &sites[y].exit)
                {
                    on_edges.push(([e1, e2], slivers::hull(&x1.xyz, &x2.xyz)));
                }
                None
            }
            Region::Corner(n) => Some(corner_join(&corners[n], pairs, &by_pair, &first_branch)),
            Region::Near(n) => {
                // Its box holds both proven end boxes: a sliver at a vertex is absorbed by it
                // as by an exact edge's join.
                on_edges.push(([e1, e2], near_boxes[n]));
                Some(CornerJoin {
                    second_edge: EdgeKind::NearEdge,
                    xyz: near_boxes[n],
                    absorbed: Vec::new(),
                })
            }
            Region::Pole(n) => {
                let pr = &poles[n];
                settled.extend(pole_cap::settled(pr, a, b, pairs, &by_pair));
                let keep = [e1.branch, e2.branch];
                Some(CornerJoin {
                    second_edge: EdgeKind::Pole,
                    xyz: pr.xyz,
                    absorbed: pole_cap::absorbed(pr, a, b, pairs, &by_pair, &first_branch, keep),
                })
            }
        };
        for &g in corner.iter().flat_map(|c| &c.absorbed) {
            absorbed[g] = true;
        }
        joins.insert(e1, (e2, kind, status.clone(), gap, corner.clone()));
        joins.insert(e2, (e1, kind, status, gap, corner));
    }
    let shells = [a, b];
    absorb_slivers(
        shells,
        pairs,
        &index,
        &small,
        &on_edges,
        &mut joins,
        &mut absorbed,
    );
    let tolerance = |g: usize| {
        let (k, i) = index[g];
        pairs[k].result.branches[i].certified_tolerance()
    };
    let closed_branch = |g: usize| {
        let (k, i) = index[g];
        pairs[k].result.branches[i].marched.status == BranchStatus::Closed
    };
    let curves = chain(index.len(), &joins, &tolerance, &closed_branch, &absorbed);
    (curves, settled)
}

/// Slivers at a vertex of faces (`slivers.rs`): each small branch (`small`) in no join that a
/// proven join on a shared edge (`on_edges`: its two ends and the hull of their proven end boxes) absorbs is
/// marked in `absorbed`, and that join gains the box holding them.
fn absorb_slivers(
    [a, b]: [&[Face]; 2],
    pairs: &[PieceIntersection],
    index: &[(usize, usize)],
    small: &[bool],
    on_edges: &[([BranchEnd; 2], [Interval; 3])],
    joins: &mut HashMap<BranchEnd, JoinValue>,
    absorbed: &mut [bool],
) {
    // Small branches in no join.
    let free: Vec<bool> = (0..index.len())
        .map(|g| {
            small[g]
                && !absorbed[g]
                && (0..2).all(|end| !joins.contains_key(&BranchEnd { branch: g, end }))
        })
        .collect();
    let boxes: Vec<_> = on_edges.iter().map(|e| e.1).collect();
    let slivers = slivers::absorb(a, b, pairs, index, &boxes, &free);
    for ((ends, _), taken) in on_edges.iter().zip(slivers) {
        let Some((xyz, slivers)) = taken else {
            continue;
        };
        for &g in &slivers {
            absorbed[g] = true;
        }
        for e in ends {
            if let Some(v) = joins.get_mut(e) {
                v.4 = Some(CornerJoin {
                    second_edge: v.1,
                    xyz,
                    absorbed: slivers.clone(),
                });
            }
        }
    }
}

/// The sites of every branch end of `pairs` (`index`: shell-wide branch → pair and place)
/// that the marcher ended on a piece side: one per end, another on the other surface's side at
/// a corner of the pair, and another on the perpendicular side at a corner of its own piece.
fn end_sites<'a>(
    a: &[Face],
    b: &[Face],
    pairs: &'a [PieceIntersection],
    index: &[(usize, usize)],
) -> Vec<EndSite<'a>> {
    let mut sites = Vec::new();
    for (g, &(k, i)) in index.iter().enumerate() {
        let pi = &pairs[k];
        let traced = &pi.result.branches[i];
        for end in 0..2 {
            if let Some(site) = end_site(a, b, pi, k, traced, BranchEnd { branch: g, end }) {
                // An end on a side of both pieces (at or near a corner) is a site on each: the
                // marcher names one surface, and its neighbour across the corner may name the
                // other.
                let other = site.corner.map(|c| {
                    let pieces = patches(a, b, pi);
                    let surface = 1 - site.surface;
                    let exit = traced.certified().and_then(|cert| {
                        certified_exit(pieces, surface, c.side, &site.point, cert)
                    });
                    EndSite {
                        surface,
                        side: c,
                        corner: Some(site.side),
                        exit,
                        ..site.clone()
                    }
                });
                // An end at a corner of its own piece is a site on the perpendicular side too:
                // where three faces meet at a vertex (a box's corner), the face the curve
                // leaves into shares that side, not the one the marcher named.
                let own = site.own_corner.map(|c| {
                    let pieces = patches(a, b, pi);
                    let exit = traced.certified().and_then(|cert| {
                        certified_exit(pieces, site.surface, c.side, &site.point, cert)
                    });
                    EndSite {
                        side: c,
                        own_corner: None,
                        exit,
                        ..site.clone()
                    }
                });
                sites.push(site);
                sites.extend(other);
                sites.extend(own);
            }
        }
    }
    sites
}

/// What a corner candidate's join adds: the other edge, the corner box and the slivers it
/// covers.
fn corner_join(
    c: &corner::CornerCandidate,
    pairs: &[PieceIntersection],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
    first_branch: &[usize],
) -> CornerJoin {
    CornerJoin {
        second_edge: c.edges[1],
        xyz: c.proof.as_ref().map_or([Interval::EMPTY; 3], |pr| pr.xyz),
        absorbed: c.proof.as_ref().map_or(Vec::new(), |pr| {
            corner::absorbed(pr, pairs, by_pair, first_branch)
        }),
    }
}

/// Adds the near join candidates to `candidates`; returns the boxes of the proven ones (their
/// regions index it).
fn near_candidates(
    near: Vec<near::NearCandidate>,
    candidates: &mut Vec<Candidate>,
) -> Vec<[Interval; 3]> {
    let mut boxes = Vec::new();
    for (gap, x, y, verdict) in near {
        let (status, region) = match verdict {
            None => (JoinStatus::Marched, Region::None),
            Some(Ok(hull)) => {
                boxes.push(hull);
                (JoinStatus::Proven, Region::Near(boxes.len() - 1))
            }
            Some(Err(reason)) => (JoinStatus::Unproven { reason }, Region::None),
        };
        candidates.push((gap, x, y, status, EdgeKind::NearEdge, region));
    }
    boxes
}

/// A join candidate: the gap, the two sites, the status, the edge and its proof's region.
type Candidate = (f64, usize, usize, JoinStatus, EdgeKind, Region);

/// Where the proof of a join candidate holds the arc between its two ends.
#[derive(Clone, Copy)]
enum Region {
    /// Nowhere: the ends meet on a shared edge.
    None,
    /// In the corner box of this corner candidate.
    Corner(usize),
    /// In the box of this pole proof.
    Pole(usize),
    /// In this box holding both ends of a join across a near edge (`near.rs`).
    Near(usize),
}

/// How far from opposite (`1 + cos` of the angle between them) two branches may leave a pole
/// and still be joined there as one curve passing through it.
const STRAIGHT_THROUGH: f64 = 1e-3;

/// Joins through a pole: two ends that the marcher ended on sides of one shell (one face or
/// several faces sharing the pole) collapsed to the same pole, against the same piece of the other surface, leaving the pole in opposite
/// directions (to [`STRAIGHT_THROUGH`]): a curve through a sphere's pole arrives on one piece's
/// pole side and leaves from another's, straight on (and two lines crossing at a cone's apex
/// pair up by their lines). No chain reaches the pole (its parameters degenerate there): the
/// join is proven on a cap round the pole ([`pole_cap`]), whose proofs go to `proofs`.
fn pole_candidates(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    sites: &[EndSite<'_>],
    links: &[Vec<EdgeLink>; 2],
    proofs: &mut Vec<PoleProof>,
) -> Vec<Candidate> {
    let index = branch_index(pairs);
    let pole =
        |s: &EndSite<'_>| patches(a, b, &pairs[s.pair])[s.surface].collapsed_sides()[s.side.side];
    // The direction from the pole into the branch: from its end point to a point a little in.
    let outward = |s: &EndSite<'_>| {
        let (k, i) = index[s.at.branch];
        let pts = &pairs[k].result.branches[i].marched.points;
        let inner = if s.at.end == 0 {
            pts.get(pts.len().min(4).checked_sub(1)?)
        } else {
            pts.get(pts.len().saturating_sub(4))
        }?;
        let d: [f64; 3] = std::array::from_fn(|c| inner.xyz[c] - s.point.xyz[c]);
        let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        (n > 0.0).then(|| d.map(|x| x / n))
    };
    let mut out = Vec::new();
    for (x, s1) in sites.iter().enumerate() {
        let Some(p1) = pole(s1) else {
            continue;
        };
        let other = 1 - s1.surface;
        for (y, s2) in sites.iter().enumerate().skip(x + 1) {
            let (q1, q2) = (&pairs[s1.pair], &pairs[s2.pair]);
            let same = s2.surface == s1.surface
                && q1.faces[other] == q2.faces[other]
                && q1.pieces[other] == q2.pieces[other]
                && pole(s2) == Some(p1);
            let Some(gap) = marched_gap(&s1.point, &s2.point).filter(|_| same) else {
                continue;
            };
            let (Some(d1), Some(d2)) = (outward(s1), outward(s2)) else {
                continue;
            };
            if 1.0 + d1[0] * d2[0] + d1[1] * d2[1] + d1[2] * d2[2] > STRAIGHT_THROUGH {
                continue;
            }
            let (status, region) = if !q1.result.options.method.certifies() {
                (JoinStatus::Marched, Region::None)
            } else {
                match pole_cap::prove(a, b, pairs, s1, s2, &links[s1.surface]) {
                    Ok(proof) => {
                        proofs.push(proof);
                        (JoinStatus::Proven, Region::Pole(proofs.len() - 1))
                    }
                    Err(reason) => (JoinStatus::Unproven { reason }, Region::None),
                }
            };
            out.push((gap, x, y, status, EdgeKind::Pole, region));
        }
    }
    out
}

/// What [`chain`] knows of a join from one of its ends: the other end, the edge, the status, the
/// gap and, across a corner, the corner.
type JoinValue = (BranchEnd, EdgeKind, JoinStatus, f64, Option<CornerJoin>);

/// Map a parameter box of the pair of `from` (its `surface` coordinates on side `link.from`)
/// across the edge into the pair of `link.to`.
fn map_box(y: &ParamBox, surface: usize, link: &EdgeLink, doms: [&Domain; 2]) -> ParamBox {
    let (k_from, _) = side_coordinate(doms[0], link.from.side);
    let (k_to, value) = side_coordinate(doms[1], link.to.side);
    let along = y[2 * surface + 1 - k_from];
    let mut out = *y;
    out[2 * surface + k_to] = point(value);
    out[2 * surface + 1 - k_to] = link.map_along(along, doms[0], doms[1]);
    out
}

/// Whether every interval of `x` lies in the matching one of `y`.
fn inside(x: &ParamBox, y: &ParamBox) -> bool {
    x.iter().zip(y).all(|(a, b)| a.subset(*b))
}

/// Whether `s1` (on `link.from`) and `s2` (on `link.to`) may be joined: the gap and the status.
fn candidate(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    s1: &EndSite,
    s2: &EndSite,
    link: &EdgeLink,
) -> Option<(f64, JoinStatus)> {
    let s = s1.surface;
    let d1 = patches(a, b, &pairs[s1.pair])[s].domain();
    let d2 = patches(a, b, &pairs[s2.pair])[s].domain();
    let back = EdgeLink {
        from: link.to,
        to: link.from,
        reversed: link.reversed,
        kind: link.kind,
    };
    let certifies = pairs[s1.pair].result.options.method.certifies();
    // The certified evidence: exit boxes within the sum of the certified tolerances.
    if let (Some(x1), Some(x2), Some(t1), Some(t2)) =
        (&s1.exit, &s2.exit, s1.tolerance, s2.tolerance)
    {
        let gap = box_gap(&x1.xyz, &x2.xyz);
        if gap <= t1 + t2 {
            let y2 = map_box(&x2.exit, s, &back, [&d2, &d1]);
            let y1 = map_box(&x1.exit, s, link, [&d1, &d2]);
            let overlap = box_gap(&x1.exit, &y2) == 0.0 && gap == 0.0;
            let status = if !overlap {
                JoinStatus::Unproven {
                    reason: "the end boxes do not overlap",
                }
            } else if inside(&y2, &x1.region) || inside(&y1, &x2.region) {
                JoinStatus::Proven
            } else {
                JoinStatus::Unproven {
                    reason: "neither end box lies in the other's uniqueness region",
                }
            };
            return Some((gap, status));
        }
    }
    // The marched evidence.
    let (p1, p2) = (&s1.point, &s2.point);
    let gap = marched_gap(p1, p2)?;
    let x1 = if s == 0 { p1.p } else { p1.q };
    let x2 = if s == 0 { p2.p } else { p2.q };
    let (k1, _) = side_coordinate(&d1, link.from.side);
    let (k2, _) = side_coordinate(&d2, link.to.side);
    let mapped = link.map_along(point(x1[1 - k1]), &d1, &d2).mid();
    let [lo, hi] = along_range(&d2, link.to.side);
    if (mapped - x2[1 - k2]).abs() > SIDE_TOLERANCE * (hi - lo) {
        return None;
    }
    let (o1, o2) = if s == 0 { (p1.q, p2.q) } else { (p1.p, p2.p) };
    let other = patches(a, b, &pairs[s1.pair])[1 - s].domain();
    if (0..2).any(|i| (o1[i] - o2[i]).abs() > SIDE_TOLERANCE * other.size()) {
        return None;
    }
    let status = if !certifies {
        JoinStatus::Marched
    } else if s1.exit.is_none() || s2.exit.is_none() {
        JoinStatus::Unproven {
            reason: "an end is not certified on the shared edge",
        }
    } else {
        JoinStatus::Unproven {
            reason: "the certified end boxes are farther apart than the certified tolerances",
        }
    };
    Some((gap, status))
}

/// The joined curves of `count` branches under `joins` (see the module documentation).
fn chain(
    count: usize,
    joins: &HashMap<BranchEnd, JoinValue>,
    tolerance: &dyn Fn(usize) -> Option<f64>,
    closed_branch: &dyn Fn(usize) -> bool,
    absorbed: &[bool],
) -> Vec<JoinedCurve> {
    // Branches absorbed by a corner join are in no curve's parts.
    let mut seen = absorbed.to_vec();
    let mut curves = Vec::new();
    for g in 0..count {
        if seen[g] {
            continue;
        }
        // Walk back from g's first end to the start of its chain (or once round a cycle).
        let mut start = CurvePart {
            branch: g,
            reversed: false,
        };
        loop {
            let entry = BranchEnd {
                branch: start.branch,
                end: usize::from(start.reversed),
            };
            let Some((prev, ..)) = joins.get(&entry) else {
                break;
            };
            if prev.branch == g {
                // A cycle: start it at g, forwards.
                start = CurvePart {
                    branch: g,
                    reversed: false,
                };
                break;
            }
            start = CurvePart {
                branch: prev.branch,
                reversed: prev.end == 0,
            };
        }
        let mut parts = vec![start];
        let mut links = Vec::new();
        let mut closed = false;
        seen[start.branch] = true;
        let mut current = start;
        loop {
            let exit = BranchEnd {
                branch: current.branch,
                end: usize::from(!current.reversed),
            };
            let Some((next, edge, status, gap, corner)) = joins.get(&exit) else {
                break;
            };
            links.push(Join {
                ends: [exit, *next],
                edge: *edge,
                status: status.clone(),
                gap: *gap,
                corner: corner.clone(),
            });
            if next.branch == start.branch {
                closed = true;
                break;
            }
            current = CurvePart {
                branch: next.branch,
                reversed: next.end == 1,
            };
            seen[current.branch] = true;
            parts.push(current);
        }
        if parts.len() == 1 && links.is_empty() && closed_branch(start.branch) {
            closed = true;
        }
        let certified_tolerance = if links.iter().all(|j| j.status.is_proven()) {
            // A corner's arc between two parts (or a vertex's slivers) lies in its box, which
            // holds the parts' true end points: no farther from a true point of the curve than
            // the box's diameter, so from the reported curve than that plus the parts' tolerance.
            let corners = links
                .iter()
                .filter_map(|j| j.corner.as_ref())
                .map(|c| corner::diameter(&c.xyz))
                .fold(0.0f64, f64::max);
            parts
                .iter()
                .map(|p| tolerance(p.branch))
                .try_fold(0.0f64, |m, t| t.map(|t| m.max(t)))
                .map(|t| (point(t) + point(corners)).sup())
        } else {
            None
        };
        curves.push(JoinedCurve {
            parts,
            closed,
            joins: links,
            certified_tolerance,
        });
    }
    curves
}
