//! Curves that turn round more tightly than the marcher resolves: two marched branches ending at
//! the same two-armed "singular point" are joined and certified as one branch, and the join is
//! kept only where the chain proves the curve through that point.
//!
//! On nearly tangent surfaces a curve can turn round within 1e-8 (its radius there is about the
//! sine of the normals' angle over their relative curvature). Below a sine of 1e-7 an `f64`
//! march cannot tell such a turn from a singular point ([`MarchOptions::singular_sine`]): it
//! stops on both arms there, and the curve comes back as two branches ending at a "node" with
//! two exits. The cover chain proves its links on the exact residual at such sines, so it can
//! often go round the turn. A proven link through the point shows the curve is regular there
//! (at a singular point no tube through it contracts), so a join whose certificate reaches past
//! the turn on both sides replaces the two arms, and the node and its event are dropped.
//! Otherwise both arms stay as they were and are certified one by one.
//!
//! [`MarchOptions::singular_sine`]: crate::march::MarchOptions::singular_sine

use inari::Interval;

use super::result::BranchCertificate;
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::surface::pair_widths;
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, BranchStatus, CurvePoint, EndReason, Event, EventKind};
use crate::pair::branch_point::SingularNode;

/// Two branch ends meeting at a two-armed node: `(branch, end)` twice, and the node's index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Turn {
    pub(super) arms: [(usize, usize); 2],
    pub(super) node: usize,
}

fn params(c: &CurvePoint) -> [f64; 4] {
    [c.p[0], c.p[1], c.q[0], c.q[1]]
}

fn end_point(b: &Branch, end: usize) -> Option<&CurvePoint> {
    if end == 0 {
        b.points.first()
    } else {
        b.points.last()
    }
}

/// The first node not `tried` with at most two exits at which exactly two singular ends of two
/// different branches lie (the end point is the node's point, as the marcher attaches it), if
/// any.
pub(super) fn find_turn(
    branches: &[Branch],
    nodes: &[SingularNode],
    tried: &[bool],
) -> Option<Turn> {
    nodes.iter().enumerate().find_map(|(k, node)| {
        if tried[k] || node.exits.len() > 2 {
            return None;
        }
        let ends: Vec<(usize, usize)> = branches
            .iter()
            .enumerate()
            .flat_map(|(i, _)| (0..2).map(move |e| (i, e)))
            .filter(|&(i, e)| {
                let b = &branches[i];
                b.ends[e] == EndReason::Singular
                    && end_point(b, e).is_some_and(|c| params(c) == node.x)
            })
            .collect();
        match ends[..] {
            [a, b] if a.0 != b.0 => Some(Turn {
                arms: [a, b],
                node: k,
            }),
            _ => None,
        }
    })
}

/// `first` run up to the turn, then `second` from it (the turn's point once): the joined
/// branch, with `first`'s id.
pub(super) fn joined(
    first: &Branch,
    first_end: usize,
    second: &Branch,
    second_end: usize,
) -> Branch {
    let mut points = first.points.clone();
    let mut start = first.ends[0];
    if first_end == 0 {
        points.reverse();
        start = first.ends[1];
    }
    let mut rest = second.points.clone();
    let mut end = second.ends[1];
    if second_end == 1 {
        rest.reverse();
        end = second.ends[0];
    }
    points.extend(rest.into_iter().skip(1));
    Branch {
        id: first.id,
        status: BranchStatus::of_ends(&[start, end]),
        ends: [start, end],
        points,
    }
}

/// Whether the certificate of a joined branch reaches past the turn at `x` on both sides:
/// every end that stopped short of a proof of what follows (a singular box, close branches, an
/// unproven stop) lies nearer, in scaled parameters, to one of the branch's own end points than
/// to the turn.
pub(super) fn passes_turn(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    joined: &Branch,
    cert: &CertifiedBranch,
    x: &[f64; 4],
) -> bool {
    let scales = pair_widths(&p.domain(), &q.domain());
    let dist = |b: &[Interval; 4], y: &[f64; 4]| {
        (0..4)
            .map(|k| {
                let off = (b[k].inf() - y[k]).max(y[k] - b[k].sup()).max(0.0);
                off / scales[k]
            })
            .fold(0.0, f64::max)
    };
    let outer: Vec<[f64; 4]> = [0, 1]
        .iter()
        .filter_map(|&e| end_point(joined, e).map(params))
        .collect();
    cert.ends.iter().all(|e| {
        let near = match e {
            CertifiedEnd::Boundary { .. } | CertifiedEnd::ClosedLoop => return true,
            CertifiedEnd::Singular { near }
            | CertifiedEnd::CloseBranches { near, .. }
            | CertifiedEnd::Unproven { near, .. } => near,
        };
        let to_turn = dist(near, x);
        outer.iter().any(|y| dist(near, y) < to_turn)
    })
}

/// Joins the arms of every turn the chain proves the curve through (see the module doc):
/// `certify` certifies one branch. Returns the certificates of the joined branches, index for
/// index with the branches (`None` for the others); drops the turns' nodes and their singular
/// events, and keeps the per-branch data beside the branches (the boundary-end checks) in
/// step, the joined branch's made by `check`.
pub(super) fn join_turns<C>(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    (branches, checked): (&mut Vec<Branch>, &mut Vec<C>),
    (nodes, events): (&mut Vec<SingularNode>, &mut Vec<Event>),
    certify: &dyn Fn(&Branch) -> BranchCertificate,
    check: &dyn Fn(&Branch) -> C,
) -> Vec<Option<BranchCertificate>> {
    let mut certs: Vec<Option<BranchCertificate>> = branches.iter().map(|_| None).collect();
    let mut tried = vec![false; nodes.len()];
    let mut through = vec![false; nodes.len()];
    while let Some(turn) = find_turn(branches, nodes, &tried) {
        tried[turn.node] = true;
        let x = nodes[turn.node].x;
        let [(a, ea), (b, eb)] = turn.arms;
        let j = joined(&branches[a], ea, &branches[b], eb);
        let cert = certify(&j);
        if !cert
            .certified()
            .is_some_and(|c| passes_turn(p, q, &j, c, &x))
        {
            continue;
        }
        through[turn.node] = true;
        events
            .retain(|e| !(e.kind == EventKind::Singular && [e.p[0], e.p[1], e.q[0], e.q[1]] == x));
        checked[a] = check(&j);
        branches[a] = j;
        certs[a] = Some(cert);
        branches.remove(b);
        checked.remove(b);
        certs.remove(b);
    }
    let mut k = 0;
    nodes.retain(|_| {
        k += 1;
        !through[k - 1]
    });
    certs
}
