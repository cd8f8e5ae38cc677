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
//! 4. The joins chain the branches into [`JoinedCurve`]s: ordered parts with orientations,
//!    closed when the chain comes back to its first part. Every branch is in exactly one curve
//!    (a branch that nothing joins is a curve of one part).

use std::collections::HashMap;

use inari::Interval;

use super::edges::PieceSide;
use super::edges::{along_range, shared_edges, side_coordinate, side_of, EdgeKind, EdgeLink};
use super::{Face, PieceIntersection};
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;
use crate::march::branch::{BranchStatus, CurvePoint, EndReason};
use crate::numeric::scalar::point;
use crate::pair::krawczyk::{krawczyk, KrawczykResult, ParamBox};
use crate::solve::TracedBranch;

/// Model-space tolerance for joining marched end points, relative to `1 + |x|∞` of the point:
/// a hundred times the marcher's parameter tolerance on domain boundaries (1e-9).
pub const MARCH_JOIN_TOLERANCE: f64 = 1e-7;

/// Parameter tolerance for "on a side of the piece" and "the parameters agree", relative to the
/// pieces' size (the marcher puts boundary ends within 1e-7 of the larger of the two).
pub const SIDE_TOLERANCE: f64 = 1e-6;

/// One end of one branch: the branch's index in the shell's branch sequence
/// ([`super::ShellIntersection::branch`]) and `0` for its first point, `1` for its last.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BranchEnd {
    /// The branch (shell-wide index, the `"id"` of the result document).
    pub branch: usize,
    /// 0: the first marched point; 1: the last.
    pub end: usize,
}

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
    /// The largest certified tolerance of the parts, when every part is certified and every join
    /// proven; `None` otherwise.
    pub certified_tolerance: Option<f64>,
}

/// A boundary end of a branch, placed on a side of its piece.
struct EndSite {
    at: BranchEnd,
    /// The pair the branch belongs to.
    pair: usize,
    /// The surface (0 or 1) whose piece boundary the end is on.
    surface: usize,
    side: PieceSide,
    /// The marched end point.
    point: CurvePoint,
    /// The certified exit, when the branch is certified and its exit could be proven.
    exit: Option<Exit>,
    /// The branch's certified tolerance, when it is certified.
    tolerance: Option<f64>,
}

/// A proven end of a certified branch on a side: the exact end point lies in `exit`, and it is
/// the only curve point of the piece pair on the side inside `region`.
struct Exit {
    exit: ParamBox,
    region: ParamBox,
    xyz: [Interval; 3],
}

/// The branch sequence of `pairs`: `(pair, index in the pair)` per shell-wide branch.
fn branch_index(pairs: &[PieceIntersection]) -> Vec<(usize, usize)> {
    pairs
        .iter()
        .enumerate()
        .flat_map(|(k, p)| (0..p.result.branches.len()).map(move |i| (k, i)))
        .collect()
}

/// The pieces of the pair: `[piece of A, piece of B]`.
fn patches<'a>(
    a: &'a [Face],
    b: &'a [Face],
    pi: &PieceIntersection,
) -> [&'a RationalBezierPatch; 2] {
    [
        &a[pi.faces[0]].pieces()[pi.pieces[0]],
        &b[pi.faces[1]].pieces()[pi.pieces[1]],
    ]
}

/// Join the branches of all piece pairs (see the module documentation). `a` and `b` are the
/// two shells the pairs were traced on.
pub fn join_branches(a: &[Face], b: &[Face], pairs: &[PieceIntersection]) -> Vec<JoinedCurve> {
    let index = branch_index(pairs);
    let links = [shared_edges(a), shared_edges(b)];
    let mut sites = Vec::new();
    for (g, &(k, i)) in index.iter().enumerate() {
        let pi = &pairs[k];
        let traced = &pi.result.branches[i];
        for end in 0..2 {
            if let Some(site) = end_site(a, b, pi, k, traced, BranchEnd { branch: g, end }) {
                sites.push(site);
            }
        }
    }
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
    let mut candidates = Vec::new();
    for (x, s1) in sites.iter().enumerate() {
        let from = &links[s1.surface];
        let first = from.partition_point(|l| l.from < s1.side);
        for link in from[first..].iter().take_while(|l| l.from == s1.side) {
            let p1 = &pairs[s1.pair];
            let (mut faces, mut pieces) = (p1.faces, p1.pieces);
            faces[s1.surface] = link.to.face;
            pieces[s1.surface] = link.to.piece;
            let Some(&k2) = by_pair.get(&(faces, pieces)) else {
                continue;
            };
            let Some(others) = at_side.get(&(k2, s1.surface, link.to)) else {
                continue;
            };
            for &y in others.iter().filter(|&&y| y > x) {
                if let Some(c) = candidate(a, b, pairs, s1, &sites[y], link) {
                    candidates.push((c.0, x, y, c.1, link.kind));
                }
            }
        }
    }
    // Proven joins first, then the nearest.
    candidates.sort_by(|p, q| {
        (!p.3.is_proven())
            .cmp(&!q.3.is_proven())
            .then(p.0.total_cmp(&q.0))
    });
    let mut used = vec![false; sites.len()];
    let mut joins: HashMap<BranchEnd, (BranchEnd, EdgeKind, JoinStatus, f64)> = HashMap::new();
    for (gap, x, y, status, kind) in candidates {
        if used[x] || used[y] {
            continue;
        }
        used[x] = true;
        used[y] = true;
        let (e1, e2) = (sites[x].at, sites[y].at);
        joins.insert(e1, (e2, kind, status.clone(), gap));
        joins.insert(e2, (e1, kind, status, gap));
    }
    let tolerance = |g: usize| {
        let (k, i) = index[g];
        pairs[k].result.branches[i].certified_tolerance()
    };
    let closed_branch = |g: usize| {
        let (k, i) = index[g];
        pairs[k].result.branches[i].marched.status == BranchStatus::Closed
    };
    chain(index.len(), &joins, &tolerance, &closed_branch)
}

/// The [`EndSite`] of `at` when the marcher ended it on a piece boundary that is a side of the
/// piece.
fn end_site(
    a: &[Face],
    b: &[Face],
    pi: &PieceIntersection,
    pair: usize,
    traced: &TracedBranch,
    at: BranchEnd,
) -> Option<EndSite> {
    let m = &traced.marched;
    let EndReason::Boundary { surface } = m.ends[at.end] else {
        return None;
    };
    let point = *if at.end == 0 {
        m.points.first()?
    } else {
        m.points.last()?
    };
    let pieces = patches(a, b, pi);
    let dom = pieces[surface].domain();
    let x = if surface == 0 { point.p } else { point.q };
    let size = dom.size().max(pieces[1 - surface].domain().size());
    let side = side_of(&dom, x, SIDE_TOLERANCE * size)?;
    let side = PieceSide {
        face: pi.faces[surface],
        piece: pi.pieces[surface],
        side,
    };
    let exit = traced
        .certified()
        .and_then(|c| certified_exit(pieces, surface, side.side, &point, c));
    Some(EndSite {
        at,
        pair,
        surface,
        side,
        point,
        exit,
        tolerance: traced.certified_tolerance(),
    })
}

/// The proven exit of the certified branch `c` through `side` of `surface`'s piece, at the
/// certified end nearest the marched end point `near`.
///
/// The end's last tube piece proves the true curve point at its outer end beyond the side (its
/// reported point, evaluated in interval arithmetic, is farther beyond than the piece's
/// parameter radius); walking the chain of enclosure boxes inwards from that end, the first box
/// wholly on the inner side proves a curve point inside. The curve is continuous along the
/// chain, so it meets the side in the boxes in between; their hull on the side, slightly
/// widened, is the region where the parametric Krawczyk test (the side's coordinate held at
/// its value) proves that the piece pair's curve meets the side exactly once.
fn certified_exit(
    pieces: [&RationalBezierPatch; 2],
    surface: usize,
    side: usize,
    near: &CurvePoint,
    c: &CertifiedBranch,
) -> Option<Exit> {
    let dom = pieces[surface].domain();
    let (k, value) = side_coordinate(&dom, side);
    let fixed = 2 * surface + k;
    let lower = side.is_multiple_of(2);
    let target = [near.p[0], near.p[1], near.q[0], near.q[1]];
    let distance = |y: &ParamBox| {
        (0..4)
            .map(|i| {
                let (lo, hi) = (y[i].inf(), y[i].sup());
                (lo - target[i]).max(target[i] - hi).max(0.0)
            })
            .fold(0.0, f64::max)
    };
    let (first, last) = (c.boxes.first()?, c.boxes.last()?);
    // The certified end at the marched end: 0 (smallest arc length) or 1.
    let end = usize::from(distance(&last.params()) < distance(&first.params()));
    if !matches!(c.ends[end], CertifiedEnd::Boundary { surface: s } if s == surface) {
        return None;
    }
    let tube = if end == 0 {
        c.tubes.first()?
    } else {
        c.tubes.last()?
    };
    // The outer end of the end piece is at τ = h on both halves.
    if (tube.direction < 0.0) != (end == 0) {
        return None;
    }
    let h = point(tube.h);
    let reported = tube
        .coeffs
        .iter()
        .rev()
        .fold(point(0.0), |acc, c| acc * h + point(c[fixed]));
    let radius = point(tube.radius_param);
    let beyond = if lower {
        (reported + radius).sup() < value
    } else {
        (reported - radius).inf() > value
    };
    if !beyond {
        return None;
    }
    let inner = |y: &ParamBox| {
        if lower {
            y[fixed].inf() > value
        } else {
            y[fixed].sup() < value
        }
    };
    let mut region: Option<ParamBox> = None;
    let mut reached_inside = false;
    let walk: Box<dyn Iterator<Item = _>> = if end == 0 {
        Box::new(c.boxes.iter())
    } else {
        Box::new(c.boxes.iter().rev())
    };
    for bx in walk {
        let y = bx.params();
        if inner(&y) {
            reached_inside = true;
            break;
        }
        region = Some(match region {
            None => y,
            Some(r) => std::array::from_fn(|i| r[i].convex_hull(y[i])),
        });
    }
    let mut region = region.filter(|_| reached_inside)?;
    for (i, r) in region.iter_mut().enumerate() {
        if i == fixed {
            *r = point(value);
        } else {
            let pad = (point(0.125 * r.wid()) + point(1e-12 * (1.0 + r.mag()))).sup();
            *r += Interval::try_from((-pad, pad)).ok()?;
        }
    }
    let enclosure = unique_zero(pieces, region, fixed)?;
    let xp = pieces[0].enclose(enclosure[0], enclosure[1]);
    let xq = pieces[1].enclose(enclosure[2], enclosure[3]);
    let mut xyz = xp;
    for i in 0..3 {
        let both = xp[i].intersection(xq[i]);
        if both.is_empty() {
            return None;
        }
        xyz[i] = both;
    }
    Some(Exit {
        exit: enclosure,
        region,
        xyz,
    })
}

/// Most boxes [`unique_zero`] looks at.
const MAX_ZERO_BOXES: usize = 256;

/// The enclosure of the only zero of `P − Q` in `region` with coordinate `fixed` held (a
/// point), proven: `region` is cut into boxes (bisecting the free coordinate that is longest in
/// model space) until each is proven empty (disjoint model-space enclosures, or a Krawczyk image
/// disjoint from it) or proven to hold exactly one zero (the Krawczyk test); the answer is that
/// zero's enclosure when exactly one box holds one. `None` when the cutting gives up, a box's
/// model-space enclosure is unbounded (a weight may vanish there), or there are several (or no)
/// such boxes.
fn unique_zero(
    pieces: [&RationalBezierPatch; 2],
    region: ParamBox,
    fixed: usize,
) -> Option<ParamBox> {
    let mut todo = vec![region];
    let mut found: Option<ParamBox> = None;
    let mut looked = 0;
    while let Some(y) = todo.pop() {
        looked += 1;
        if looked > MAX_ZERO_BOXES {
            return None;
        }
        let xp = pieces[0].enclose(y[0], y[1]);
        let xq = pieces[1].enclose(y[2], y[3]);
        // Bounded enclosures: both weight functions are nonzero on the box, so every interval
        // evaluation below is of a well-defined function. Otherwise give up.
        if xp.iter().chain(&xq).any(|x| !x.is_common_interval()) {
            return None;
        }
        if xp.iter().zip(&xq).any(|(a, b)| a.disjoint(*b)) {
            continue;
        }
        match krawczyk(pieces[0], pieces[1], y, fixed, 30) {
            KrawczykResult::Proven { enclosure, .. } => {
                if found.replace(enclosure).is_some() {
                    return None;
                }
            }
            KrawczykResult::NotProven(reason) if reason.contains("disjoint") => {}
            KrawczykResult::NotProven(_) => {
                let k = widest(pieces, &y, fixed);
                let m = y[k].mid();
                let (lo, hi) = (y[k].inf(), y[k].sup());
                if !(lo < m && m < hi) {
                    return None;
                }
                let (mut a, mut b) = (y, y);
                a[k] = Interval::try_from((lo, m)).ok()?;
                b[k] = Interval::try_from((m, hi)).ok()?;
                todo.push(a);
                todo.push(b);
            }
        }
    }
    found
}

/// The free coordinate of `y` (not `fixed`) whose width is largest in model space (times the
/// length of the surface's partial derivative at the box's midpoint).
fn widest(pieces: [&RationalBezierPatch; 2], y: &ParamBox, fixed: usize) -> usize {
    let mid = y.map(|c| c.mid());
    let speed = |k: usize| {
        let s = &pieces[k / 2];
        let d = s.derivs_f64(mid[2 * (k / 2)], mid[2 * (k / 2) + 1]);
        let col = if k.is_multiple_of(2) { d.su } else { d.sv };
        let n = col.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n.is_finite() {
            n.max(1e-300)
        } else {
            1.0
        }
    };
    (0..4)
        .filter(|&k| k != fixed)
        .max_by(|&a, &b| (y[a].wid() * speed(a)).total_cmp(&(y[b].wid() * speed(b))))
        .unwrap_or((fixed + 1) % 4)
}

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

/// Euclidean distance between two boxes (0 when they overlap).
fn box_gap(x: &[Interval], y: &[Interval]) -> f64 {
    x.iter()
        .zip(y)
        .map(|(a, b)| (a.inf() - b.sup()).max(b.inf() - a.sup()).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
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
    let scale = 1.0
        + p1.xyz
            .iter()
            .chain(&p2.xyz)
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = (0..3)
        .map(|i| (p1.xyz[i] - p2.xyz[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    if gap > MARCH_JOIN_TOLERANCE * scale {
        return None;
    }
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
    joins: &HashMap<BranchEnd, (BranchEnd, EdgeKind, JoinStatus, f64)>,
    tolerance: &dyn Fn(usize) -> Option<f64>,
    closed_branch: &dyn Fn(usize) -> bool,
) -> Vec<JoinedCurve> {
    let mut seen = vec![false; count];
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
            let Some((next, edge, status, gap)) = joins.get(&exit) else {
                break;
            };
            links.push(Join {
                ends: [exit, *next],
                edge: *edge,
                status: status.clone(),
                gap: *gap,
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
            parts
                .iter()
                .map(|p| tolerance(p.branch))
                .try_fold(0.0f64, |m, t| t.map(|t| m.max(t)))
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
