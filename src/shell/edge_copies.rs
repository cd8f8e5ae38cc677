//! Branches traced twice because they run *along* an edge two pieces share.
//!
//! A plane through the axis of a NURBS cylinder or sphere at a knot angle (the commonest section
//! of a body of revolution) cuts it along a knot line: the curve lies on a side of two
//! neighbouring pieces at once, and each piece pair traces it. So does a curve along a periodic
//! seam, or along an edge two faces share. [`drop_edge_copies`] keeps one copy.
//!
//! Two branches are copies when every marched point of each lies on a side of its piece of the
//! same surface (its coordinate within [`SIDE_TOLERANCE`] of the side's value, relative to the
//! pieces' size), the two sides are the two sides of one shared edge ([`shared_edges`]), the
//! other surface's piece is the same, and their end points coincide in model space (either way
//! round, within [`MARCH_JOIN_TOLERANCE`](super::sites::MARCH_JOIN_TOLERANCE)). Of the two,
//! the copy whose certificate reaches both true ends is kept, then the one in the face listed
//! first (along an edge two faces share), then the one on the lower side of its piece (so the
//! copies kept along one line all lie on the same side of it, whatever each face's
//! parametrisation, and join each other across knot lines rather than across corners), then
//! the tighter certificate, then the one traced first. Dropping claims nothing: the kept copy's certificate covers the
//! same curve; the test is in `f64` because it only decides what is reported twice.

use std::cmp::Reverse;

use super::edges::{shared_edges, side_coordinate, PieceSide};
use super::sites::{marched_gap, patches, SIDE_TOLERANCE};
use super::{Face, PieceIntersection};
use crate::certify::CertifiedEnd;
use crate::march::branch::CurvePoint;
use crate::solve::TracedBranch;

/// A branch lying along a side of its piece of surface `surface` (0 for A, 1 for B).
#[derive(Debug, Clone, Copy)]
struct Along {
    pair: usize,
    branch: usize,
    surface: usize,
    side: PieceSide,
}

/// Removes from `pairs` every branch that is a copy of another along a shared edge (see the
/// module documentation); returns how many were removed.
pub(super) fn drop_edge_copies(a: &[Face], b: &[Face], pairs: &mut [PieceIntersection]) -> usize {
    let links = [shared_edges(a), shared_edges(b)];
    if links.iter().all(Vec::is_empty) {
        return 0;
    }
    let along = branches_along_sides(a, b, pairs);
    let mut dropped: Vec<(usize, usize)> = Vec::new();
    for (x, first) in along.iter().enumerate() {
        for second in &along[x + 1..] {
            let (s, o) = (first.surface, 1 - first.surface);
            let (p1, p2) = (&pairs[first.pair], &pairs[second.pair]);
            let same_other = second.surface == s
                && first.pair != second.pair
                && p1.faces[o] == p2.faces[o]
                && p1.pieces[o] == p2.pieces[o];
            let linked = links[s]
                .iter()
                .any(|l| l.from == first.side && l.to == second.side);
            if !same_other || !linked {
                continue;
            }
            let keys = [(first.pair, first.branch), (second.pair, second.branch)];
            if keys.iter().any(|k| dropped.contains(k)) {
                continue;
            }
            let (b1, b2) = (
                &p1.result.branches[first.branch],
                &p2.result.branches[second.branch],
            );
            if !same_ends(&b1.marched.points, &b2.marched.points) {
                continue;
            }
            let (r1, r2) = (rank(b1, first.side), rank(b2, second.side));
            dropped.push(if r2 > r1 { keys[0] } else { keys[1] });
        }
    }
    let count = dropped.len();
    dropped.sort_unstable_by(|x, y| y.cmp(x));
    for (pair, branch) in dropped {
        pairs[pair].result.branches.remove(branch);
    }
    count
}

/// The branches whose marched points all lie on one side of their piece of one surface.
fn branches_along_sides(a: &[Face], b: &[Face], pairs: &[PieceIntersection]) -> Vec<Along> {
    let mut along = Vec::new();
    for (k, pi) in pairs.iter().enumerate() {
        let pieces = patches(a, b, pi);
        let size = pieces[0].domain().size().max(pieces[1].domain().size());
        for (i, traced) in pi.result.branches.iter().enumerate() {
            let points = &traced.marched.points;
            if points.len() < 2 {
                continue;
            }
            for (surface, piece) in pieces.iter().enumerate() {
                let d = piece.domain();
                let on = |side: usize| {
                    let (c, value) = side_coordinate(&d, side);
                    points.iter().all(|pt| {
                        let x = if surface == 0 { pt.p } else { pt.q };
                        (x[c] - value).abs() <= SIDE_TOLERANCE * size
                    })
                };
                along.extend((0..4).filter(|&side| on(side)).map(|side| Along {
                    pair: k,
                    branch: i,
                    surface,
                    side: PieceSide {
                        face: pi.faces[surface],
                        piece: pi.pieces[surface],
                        side,
                    },
                }));
            }
        }
    }
    along
}

/// Whether the two point sequences start and end at the same model points, either way round.
fn same_ends(p1: &[CurvePoint], p2: &[CurvePoint]) -> bool {
    let (Some(a0), Some(a1), Some(b0), Some(b1)) = (p1.first(), p1.last(), p2.first(), p2.last())
    else {
        return false;
    };
    let at = |x: &CurvePoint, y: &CurvePoint| marched_gap(x, y).is_some();
    (at(a0, b0) && at(a1, b1)) || (at(a0, b1) && at(a1, b0))
}

/// How good a copy is (greater is better): its certificate reaches both true ends, it is
/// certified, then it lies in the face listed first, then on the lower side of its piece
/// (`u = u0` or `v = v0`). So all the copies kept along one line lie in the pieces on the same
/// side of it (across a face edge by the faces' order, which does not depend on which way
/// each face's parameters run), and the kept branches join across the knot lines that cross
/// the line, not across corners. Then the lower certified tolerance.
fn rank(t: &TracedBranch, side: PieceSide) -> (bool, bool, Reverse<usize>, bool, f64) {
    let c = t.certified();
    (
        c.is_some_and(|c| c.ends.iter().all(CertifiedEnd::reaches_true_end)),
        c.is_some(),
        Reverse(side.face),
        side.side.is_multiple_of(2),
        -t.certified_tolerance().unwrap_or(f64::INFINITY),
    )
}
