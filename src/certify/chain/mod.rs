//! Cover-chain certification of a marched branch: proven segments (`certify/segment.rs`)
//! between the marched points, joined without gaps.
//!
//! 1. **Nodes.** Each marched point is refined by Newton onto `P = Q` (holding its
//!    fastest-moving parameter) and given its parameter velocity. The nodes only guide the
//!    proofs; nothing about them is claimed.
//! 2. **Links.** Between two nodes, a cubic Hermite predictor graphed over a coordinate that
//!    moves monotonically between them is proven by the segment test. A link that cannot be
//!    proven, or whose tube is wider than the requested tolerance allows, is split at a new
//!    node (Newton at the middle value of the along coordinate); below a smallest length the
//!    half stops, and the end says why.
//! 3. **Joins.** The box where a link ends (its last slice, enclosed) must lie inside the next
//!    link's tube: the curve point there is then the unique curve point of that tube's slice,
//!    so the two arcs are one curve and the chain has no gap. When the along coordinate
//!    changes, the next link starts a little before the node to take the box in.
//! 4. **Ends.** A closed loop is walked once round; its last link must hold the first link's
//!    start slice (the curve comes back to the start point: proven closed, traced once). An
//!    open branch is walked both ways from its start node. At a boundary end the chain goes on
//!    past the marched end point to a node outside the domain, and the end is proven when the
//!    last slice lies wholly outside. A half that stops elsewhere reports a singular box (the
//!    normals' cross product cannot be bounded away from zero near it), close branches, or an
//!    unproven end with the reason.
//!
//! What a chain reports, and how it differs from the Taylor engine's certificate: every tube
//! piece is parametrised by its along coordinate ([`TubePiece::along`]), so its guarantee is
//! stated in terms of that coordinate, and the boxes' arc lengths are those of the reported
//! curve, not proven ones (see [`CertifiedBranch::arc_length_proven`]).

use crate::certify::curve::{
    AlongParameter, CertifiedBranch, CertifiedEnd, EnclosureBox, TubePiece,
};
use crate::certify::segment::{
    hull, others, prove_segment, Jet, Predictor, SegmentProof, PREDICTOR_DEGREE,
};
use crate::error::{Error, Result};
use crate::geometry::surface::pair_widths;
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, BranchStatus, EndReason};
use crate::numeric::scalar::point;
use crate::numeric::vec3::cross;
use crate::pair::field::transversal_velocity;
use crate::pair::krawczyk::{krawczyk, KrawczykResult};
use crate::pair::newton::{refine, Constraint, Refined};
use inari::Interval;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

mod along;
mod leave;
mod limit;
mod output;
mod pole;
mod singular;
mod slice;
mod walker;

use output::assemble;
use slice::tight_slice;
use walker::{newton, point_box, scaled_dist, velocity, Walker};

/// Parameters of [`certify_chain`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainOptions {
    /// The model-space tolerance every link's tube must meet (a link wider than this is split).
    pub required_tolerance: f64,
    /// Most links per branch (both halves together); more ends the chain unproven.
    pub max_links: usize,
    /// Stop (unproven) once this instant has passed.
    pub deadline: Option<Instant>,
}

impl Default for ChainOptions {
    fn default() -> Self {
        ChainOptions {
            required_tolerance: 1e-9,
            max_links: 200_000,
            deadline: None,
        }
    }
}

/// Splits of one marched interval before a half gives up there.
const MAX_SPLITS: usize = 20_000;
/// A link whose tube halving did not narrow is kept although wider than the tolerance when its
/// width is at rounding level (any length: a tolerance below rounding was asked for), or when
/// it is shorter than this scaled length and no singular box lies within 1e-4 (the predictor's
/// error, of order `L⁸`, is negligible there, so the width is the conditioning): the certificate
/// then says the tolerance is not met. Near a singular box the half stops instead, within the
/// tolerance.
const FLOOR_LINK: f64 = 1e-4;
/// Splits in a row whose tube stayed wider than [`STALL_RATIO`] of the split link's before a half
/// near a singular box stops there (halving on would not narrow it: on the cylinders each end
/// at the tangency took 10–15 more links down to [`MIN_LINK`], all as wide).
const STALLED_SPLITS: usize = 3;
/// A split narrowed the tube when the shorter link's width is at most this part of the
/// longer's.
const STALL_RATIO: f64 = 0.9;
/// Shortest link tried, in scaled parameters (below it a half gives up there).
const MIN_LINK: f64 = 1e-10;
/// The longest link towards a singular end of the march, as a fraction of the scaled distance
/// to the marched end ([`walker::Walker`]'s `singular_reach`).
const SINGULAR_REACH: f64 = 0.8;

/// Refined guide points of the marched branch (each on `P = Q` to rounding level; a point that
/// does not refine is kept as marched).
fn guide_points(p: &RationalBezierPatch, q: &RationalBezierPatch, b: &Branch) -> Vec<[f64; 4]> {
    let scales = pair_widths(&p.domain(), &q.domain());
    let mut out: Vec<[f64; 4]> = Vec::with_capacity(b.points.len());
    for c in &b.points {
        let x = [c.p[0], c.p[1], c.q[0], c.q[1]];
        let v = velocity(p, q, &x);
        let j = (0..4)
            .max_by(|&a, &b| (v[a].abs() / scales[a]).total_cmp(&(v[b].abs() / scales[b])))
            .unwrap_or(0);
        let y = pole::refine_guide(p, q, x, j)
            .filter(|y| scaled_dist(y, &x, &scales) < 1e-6)
            .unwrap_or(x);
        if out.last().is_none_or(|l| scaled_dist(l, &y, &scales) > 0.0) {
            out.push(y);
        }
    }
    out
}

/// Certifies the marched branch `b` by a cover chain, starting at its point nearest `start`.
///
/// Errors: [`Error::Certification`] when not even the first link can be proven (the branch is
/// singular there or not near a curve). Everything returned is proven; ends that are not are
/// [`CertifiedEnd::Unproven`].
pub fn certify_chain(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &Branch,
    start: [f64; 4],
    opts: &ChainOptions,
) -> Result<CertifiedBranch> {
    let mut xs = guide_points(p, q, b);
    let scales = pair_widths(&p.domain(), &q.domain());
    let fail = |reason: &str, near: [f64; 4]| Error::Certification {
        reason: reason.into(),
        near,
    };
    let closed = b.status == BranchStatus::Closed
        || (b.ends[0] == EndReason::ClosedLoop && b.ends[1] == EndReason::ClosedLoop);
    if closed && xs.len() > 2 && scaled_dist(&xs[0], &xs[xs.len() - 1], &scales) < 1e-9 {
        xs.pop();
    }
    if xs.len() < 2 {
        let reason = if b.points.len() < 2 {
            "the marched branch has fewer than two points"
        } else {
            // Several marched points, one point of the curve: e.g. at a corner of the piece
            // pair, where the curve only passes through the corner (a proven corner join of
            // the shell absorbs the branch).
            "the marched branch is a single point of the curve (e.g. where the curve passes \
             through a corner of the piece pair): no arc to certify"
        };
        return Err(fail(reason, start));
    }
    if closed {
        if let Some(c) = closed_chain(p, q, &xs, opts) {
            return Ok(c);
        }
        // Not closed by proof: from the first point both ways round, each way until it stops;
        // from another point where no link from it holds (a near-tangent loop: a start where
        // the links must be far shorter than elsewhere).
        let n = xs.len();
        let mut tried = Vec::new();
        for k in [0, n / 2, n / 4, 3 * n / 4] {
            if tried.contains(&k) {
                continue;
            }
            tried.push(k);
            let mut ring = xs.clone();
            ring.rotate_left(k);
            if let Some(c) = ring_chain(p, q, &ring, opts) {
                return Ok(c);
            }
        }
        return Err(fail("no link of the loop could be proven", xs[0]));
    }
    if xs.len() == 2 {
        split_two(p, q, &mut xs);
    }
    let s = (0..xs.len())
        .min_by(|&a, &c| {
            scaled_dist(&xs[a], &start, &scales).total_cmp(&scaled_dist(&xs[c], &start, &scales))
        })
        .unwrap_or(0);
    let n = xs.len();
    // Not at an end of the marched points (when there is a point between): a half starting at
    // the last point has no link to walk and its end could not be proven even at a boundary.
    let s = if n > 2 { s.clamp(1, n - 2) } else { s };
    // Towards a singular end the marched points halve their distance to it, so a start chosen
    // by index or by the search lies close to it, where links must be short both ways: start
    // half way along the marched length instead (the cylinders' arcs: the half away from the
    // node began 1e-4 from it, four failed links and four doublings before its links were long).
    let s = if b.ends.contains(&EndReason::Singular) && n > 2 {
        middle_by_length(&xs, &scales).clamp(1, n - 2)
    } else {
        s
    };
    // Another start where no link from the chosen one can be proven (a start next to a
    // singular point).
    let mut tried = Vec::new();
    for k in [s, n / 2, n / 4, 3 * n / 4, n / 8, 7 * n / 8, 0, n - 1] {
        if tried.contains(&k) {
            continue;
        }
        tried.push(k);
        if let Some(c) = open_chain(p, q, &xs, k, b.ends, opts) {
            return Ok(c);
        }
    }
    Err(fail(
        "no link could be proven from any tried start point",
        xs[s],
    ))
}

/// The index of the point of `xs` nearest half way along the polyline's scaled length.
fn middle_by_length(xs: &[[f64; 4]], scales: &[f64; 4]) -> usize {
    let total: f64 = xs
        .windows(2)
        .map(|w| scaled_dist(&w[0], &w[1], scales))
        .sum();
    let mut run = 0.0;
    for (i, w) in xs.windows(2).enumerate() {
        let step = scaled_dist(&w[0], &w[1], scales);
        if run + step >= 0.5 * total {
            return if 0.5 * total - run <= run + step - 0.5 * total {
                i
            } else {
                i + 1
            };
        }
        run += step;
    }
    xs.len() / 2
}

/// A marched branch of two points (a short arc across a corner of a domain) gets a third, a
/// curve point between them (Newton from their middle, holding its fastest-moving parameter),
/// so the chain can start between its ends and walk out of the domain at both. Kept as it is if
/// Newton fails or lands nearer one end than a quarter of their distance.
fn split_two(p: &RationalBezierPatch, q: &RationalBezierPatch, xs: &mut Vec<[f64; 4]>) {
    let scales = pair_widths(&p.domain(), &q.domain());
    let (a, b) = (xs[0], xs[1]);
    let m: [f64; 4] = std::array::from_fn(|i| 0.5 * (a[i] + b[i]));
    let v = velocity(p, q, &m);
    let j = (0..4)
        .max_by(|&x, &y| (v[x].abs() / scales[x]).total_cmp(&(v[y].abs() / scales[y])))
        .unwrap_or(0);
    let h = scaled_dist(&a, &b, &scales);
    if let Some(r) = newton(p, q, m, j, m[j]) {
        if scaled_dist(&r.x, &a, &scales).min(scaled_dist(&r.x, &b, &scales)) > 0.25 * h {
            xs.insert(1, r.x);
        }
    }
}

/// A closed loop: links round from the first node back to it, the last one holding the first
/// link's start slice. `None` if any link fails.
fn closed_chain(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    xs: &[[f64; 4]],
    opts: &ChainOptions,
) -> Option<CertifiedBranch> {
    if let Some(c) = closed_chain_halves(p, q, xs, opts) {
        return Some(c);
    }
    let mut w = Walker::new(p, q, opts);
    w.wants_closure = true;
    let mut nodes = w.nodes(xs);
    if nodes.len() < xs.len() {
        return None;
    }
    w.advance(&nodes, None).ok()?;
    if w.closed {
        // The march went round more than once; the loop closed at the last link.
        return closed_loop(p, q, &w.links);
    }
    let start_slice = w.close_at?;
    let last = *nodes.last()?;
    let back = w.node(xs[0], &last.t)?;
    nodes.clear();
    nodes.extend([last, back]);
    w.advance(&nodes, Some(&start_slice)).ok()?;
    closed_loop(p, q, &w.links)
}

/// A closed loop marched once round, certified as two arcs at the same time (rayon): from the
/// first guide point to the middle one and from there back to the first, each arc's first link
/// holding a proven slice of the curve at its start ([`point_slice`]) and its last link the slice
/// where the other arc starts. `None` (the caller walks round in one piece) when the march may
/// have gone round more than once (a guide point in the middle of the list, or any before the
/// last few, nearest the first one), when a slice is not proven, or when an arc fails.
fn closed_chain_halves(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    xs: &[[f64; 4]],
    opts: &ChainOptions,
) -> Option<CertifiedBranch> {
    let n = xs.len();
    if n < 8 {
        return None;
    }
    let scales = pair_widths(&p.domain(), &q.domain());
    let from_start: Vec<f64> = xs.iter().map(|x| scaled_dist(&xs[0], x, &scales)).collect();
    let reach = from_start.iter().copied().fold(0.0, f64::max);
    let nearest = (n / 8..n).min_by(|&a, &b| from_start[a].total_cmp(&from_start[b]))?;
    let once_round = nearest + 3 >= n
        && from_start[n / 8..=7 * n / 8]
            .iter()
            .all(|&d| d >= 0.2 * reach);
    if !once_round {
        return None;
    }
    let m = n / 2;
    let (s0, sm) = (point_slice(p, q, &xs[0])?, point_slice(p, q, &xs[m])?);
    let spent = AtomicUsize::new(0);
    let arc = |ys: &[[f64; 4]], from: [Interval; 4], to: [Interval; 4]| {
        let mut w = Walker::new(p, q, opts);
        w.shared = Some(&spent);
        w.join = Some(from);
        let nodes = w.nodes(ys);
        if nodes.len() < ys.len() {
            return None;
        }
        w.advance(&nodes, Some(&to)).ok()?;
        Some(w.links)
    };
    let second: Vec<[f64; 4]> = xs[m..].iter().chain(&xs[..1]).copied().collect();
    let (a, b) = rayon::join(|| arc(&xs[..=m], s0, sm), || arc(&second, sm, s0));
    let mut links = a?;
    links.extend(b?);
    closed_loop(p, q, &links)
}

/// The certificate of a loop proven closed by `links`.
fn closed_loop(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    links: &[walker::Link],
) -> Option<CertifiedBranch> {
    let ends = [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop];
    assemble(p, q, &[], links, ends)
}

/// A marched loop whose closure could not be proven: walked from its first point forwards
/// round the loop and backwards round it, each way until it stops (both ends say why).
fn ring_chain(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    xs: &[[f64; 4]],
    opts: &ChainOptions,
) -> Option<CertifiedBranch> {
    let mut fwd_ring = xs.to_vec();
    fwd_ring.push(xs[0]);
    // x0, x_{n−1}, …, x1, x0.
    let bwd_ring: Vec<[f64; 4]> = std::iter::once(xs[0])
        .chain(xs.iter().rev().copied())
        .collect();
    let round = EndReason::NewtonFailed;
    let mut fwd = Walker::new(p, q, opts);
    fwd.wants_closure = true;
    let fwd_end = fwd.walk(&fwd_ring, round);
    if fwd.closed {
        return closed_loop(p, q, &fwd.links);
    }
    let mut bwd = Walker::new(p, q, opts);
    bwd.used = fwd.links.len();
    bwd.join = fwd
        .links
        .first()
        .map(|l| tight_slice(p, q, &l.proof, l.from));
    let bwd_end = bwd.walk(&bwd_ring, round);
    assemble(p, q, &bwd.links, &fwd.links, [bwd_end, fwd_end])
}

/// A proven slice of the curve at the guide point `x`: a box round it, its fastest-moving
/// parameter held at `x`'s value, where Krawczyk proves exactly one curve point. Two halves
/// whose first links both hold it are joined there (the curve point of the slice lies on both).
fn point_slice(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
) -> Option<[Interval; 4]> {
    let scales = pair_widths(&p.domain(), &q.domain());
    let v = velocity(p, q, x);
    let j =
        (0..4).max_by(|&a, &b| (v[a].abs() / scales[a]).total_cmp(&(v[b].abs() / scales[b])))?;
    let unit = crate::numeric::scalar::interval(-1.0, 1.0)?;
    [1e-12, 1e-10, 1e-8].into_iter().find_map(|pad| {
        let y: [Interval; 4] = std::array::from_fn(|i| {
            if i == j {
                point(x[i])
            } else {
                point(x[i]) + point(pad * scales[i]) * unit
            }
        });
        match krawczyk(p, q, y, j, 4) {
            KrawczykResult::Proven { enclosure, .. } => Some(enclosure),
            KrawczykResult::NotProven(_) => None,
        }
    })
}

/// An open branch through node `s`: the forward half over `xs[s..]`, the backward half over
/// `xs[..=s]` reversed, joined at the start. When both halves have marched points and a slice of
/// the curve at the start is proven ([`point_slice`]), the halves are walked at the same time
/// (rayon), each first link holding that slice; otherwise one after the other, the backward
/// half's first link holding the forward half's start slice.
fn open_chain(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    xs: &[[f64; 4]],
    s: usize,
    ends: [EndReason; 2],
    opts: &ChainOptions,
) -> Option<CertifiedBranch> {
    if s > 0 && s + 1 < xs.len() {
        if let Some(slice) = point_slice(p, q, &xs[s]) {
            let spent = AtomicUsize::new(0);
            let half = |ys: &[[f64; 4]], end: EndReason| {
                let mut w = Walker::new(p, q, opts);
                w.shared = Some(&spent);
                w.join = Some(slice);
                let reached = w.walk(ys, end);
                (w.links, reached)
            };
            let back: Vec<[f64; 4]> = xs[..=s].iter().rev().copied().collect();
            let ((fwd, fwd_end), (bwd, bwd_end)) =
                rayon::join(|| half(&xs[s..], ends[1]), || half(&back, ends[0]));
            return assemble(p, q, &bwd, &fwd, [bwd_end, fwd_end]);
        }
    }
    open_chain_in_turn(p, q, xs, s, ends, opts)
}

/// [`open_chain`] one half after the other.
fn open_chain_in_turn(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    xs: &[[f64; 4]],
    s: usize,
    ends: [EndReason; 2],
    opts: &ChainOptions,
) -> Option<CertifiedBranch> {
    let mut fwd = Walker::new(p, q, opts);
    let fwd_end = if s + 1 < xs.len() {
        fwd.walk(&xs[s..], ends[1])
    } else {
        CertifiedEnd::Unproven {
            reason: "start at the last marched point".into(),
            near: point_box(&xs[s]),
        }
    };
    let mut bwd = Walker::new(p, q, opts);
    bwd.used = fwd.links.len();
    // The backward half's first link must hold the forward half's start slice.
    bwd.join = fwd
        .links
        .first()
        .map(|l| tight_slice(p, q, &l.proof, l.from));
    let back: Vec<[f64; 4]> = xs[..=s].iter().rev().copied().collect();
    let bwd_end = if back.len() > 1 {
        bwd.walk(&back, ends[0])
    } else {
        CertifiedEnd::Unproven {
            reason: "start at the first marched point".into(),
            near: point_box(&xs[s]),
        }
    };
    assemble(p, q, &bwd.links, &fwd.links, [bwd_end, fwd_end])
}
