//! Joins across a corner of one surface's own pieces: a curve through a point where four
//! pieces of one face meet (two knot lines crossing, or a knot line and a periodic seam), at a
//! point inside the other surface's piece. The great circle of a NURBS sphere in a plane
//! through its centre and a knot-line crossing of the equator does this.
//!
//! The two branches that meet there belong to the pairs of diagonally opposite pieces `a₁` and
//! `a₂` of that surface with the other surface's piece `b`; the pairs of the two pieces beside
//! the corner, `a_x` (across the first side) and `a_y` (across the second), hold at most a
//! sliver (the corner point). The proof is the one of [`super::corner`] with the chart made of
//! all four pieces of the face round the corner: the face's own parameters, the pieces across a
//! periodic seam shifted by the period (exactly, in `f64`). Only knot lines and seams the same
//! way round are taken (the four pieces are then one surface in one parametrisation, and the
//! piece diagonally across is reached with the same shift either way round the corner); the
//! other surface is its one piece.

use std::collections::{HashMap, HashSet};

use super::corner::{both_exits, prove, stitched_round, ChartMap, CornerCandidate, CornerProof};
use super::edges::{along_range, side_coordinate, EdgeKind, EdgeLink, PieceSide};
use super::sites::{marched_gap, patches, EndSite};
use super::{Face, PieceIntersection};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;

/// The exact shift taking the parameters of the piece on `link.from` (domain `from`) to those
/// of the piece on `link.to` (domain `to`): a knot line or a seam of one face between opposite
/// sides, the edge parameter running the same way over the same range. `None` otherwise.
fn exact_shift(link: &EdgeLink, from: &Domain, to: &Domain) -> Option<[f64; 2]> {
    if link.kind == EdgeKind::FaceEdge || link.reversed {
        return None;
    }
    let (k1, v1) = side_coordinate(from, link.from.side);
    let (k2, v2) = side_coordinate(to, link.to.side);
    let opposite = link.from.side / 2 == link.to.side / 2 && link.from.side != link.to.side;
    if k1 != k2 || !opposite || along_range(from, link.from.side) != along_range(to, link.to.side) {
        return None;
    }
    let d = v2 - v1;
    if v1 + d != v2 || v2 - d != v1 {
        return None;
    }
    let mut shift = [0.0; 2];
    shift[k1] = d;
    Some(shift)
}

/// The links of `links` (sorted by their `from` side) from `side`.
fn from_side(links: &[EdgeLink], side: PieceSide) -> impl Iterator<Item = &EdgeLink> {
    let first = links.partition_point(|e| e.from < side);
    links[first..].iter().take_while(move |e| e.from == side)
}

/// The four pieces round a corner of piece `a₁` of one surface, with their shifts from `a₁`'s
/// parameters.
struct Round<'a> {
    /// `a_x`, `a_y` (across the site's first and second side) and `a₂` (diagonally across).
    pieces: [PieceSide; 3],
    shifts: [[f64; 2]; 3],
    patches: [&'a RationalBezierPatch; 3],
    edges: [EdgeKind; 2],
}

/// The pieces round the corner of the site's piece at its sides `sides`, when each is reached
/// across a knot line or seam with an exact shift and the diagonal piece is the same both ways
/// round.
fn round<'a>(faces: &'a [Face], links: &[EdgeLink], sides: [PieceSide; 2]) -> Vec<Round<'a>> {
    let piece = |ps: &PieceSide| &faces[ps.face].pieces()[ps.piece];
    let dom = |ps: &PieceSide| piece(ps).domain();
    let mut out = Vec::new();
    for l1 in from_side(links, sides[0]) {
        for l3 in from_side(links, sides[1]) {
            let (ax, ay) = (l1.to, l3.to);
            let ax_side = PieceSide {
                side: sides[1].side,
                ..ax
            };
            let ay_side = PieceSide {
                side: sides[0].side,
                ..ay
            };
            for l2 in from_side(links, ax_side) {
                for l4 in from_side(links, ay_side) {
                    let a2 = l2.to;
                    if (a2.face, a2.piece) != (l4.to.face, l4.to.piece) {
                        continue;
                    }
                    let shifts = (|| {
                        let dx = exact_shift(l1, &dom(&sides[0]), &dom(&ax))?;
                        let dy = exact_shift(l3, &dom(&sides[1]), &dom(&ay))?;
                        let dxa = exact_shift(l2, &dom(&ax), &dom(&a2))?;
                        let dya = exact_shift(l4, &dom(&ay), &dom(&a2))?;
                        let d2: [f64; 2] = std::array::from_fn(|i| dx[i] + dxa[i]);
                        let same = (0..2).all(|i| {
                            d2[i] - dx[i] == dxa[i]
                                && d2[i] == dy[i] + dya[i]
                                && d2[i] - dy[i] == dya[i]
                        });
                        same.then_some([dx, dy, d2])
                    })();
                    if let Some(shifts) = shifts {
                        out.push(Round {
                            pieces: [ax, ay, a2],
                            shifts,
                            patches: [piece(&ax), piece(&ay), piece(&a2)],
                            edges: [l1.kind, l3.kind],
                        });
                    }
                }
            }
        }
    }
    out
}

/// Every candidate join across a corner of one surface's pieces: an end site on two sides of
/// its piece (and inside the other surface's), and one of the pair of the diagonal piece with
/// the same other piece, also at a corner of its piece, whose marched points agree; proven as
/// the module documentation says when both are certified.
pub(super) fn candidates(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    sites: &[EndSite],
    links: &[Vec<EdgeLink>; 2],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
) -> Vec<CornerCandidate> {
    let mut at_pair: HashMap<usize, Vec<usize>> = HashMap::new();
    for (y, s) in sites.iter().enumerate() {
        if s.own_corner.is_some() {
            at_pair.entry(s.pair).or_default().push(y);
        }
    }
    let mut out = Vec::new();
    let mut seen = HashSet::new();
    for (x, s1) in sites.iter().enumerate() {
        let Some(second) = s1.own_corner else {
            continue;
        };
        let sf = s1.surface;
        let faces = if sf == 0 { a } else { b };
        let p1 = &pairs[s1.pair];
        for r in round(faces, &links[sf], [s1.side, second]) {
            let (mut fc, mut pc) = (p1.faces, p1.pieces);
            fc[sf] = r.pieces[2].face;
            pc[sf] = r.pieces[2].piece;
            let Some(&k2) = by_pair.get(&(fc, pc)) else {
                continue;
            };
            for &y in at_pair.get(&k2).into_iter().flatten() {
                let s2 = &sites[y];
                let key = if s1.at < s2.at {
                    (s1.at, s2.at)
                } else {
                    (s2.at, s1.at)
                };
                if y == x || !seen.insert(key) {
                    continue;
                }
                let Some(gap) = marched_gap(&s1.point, &s2.point) else {
                    continue;
                };
                let (status, proof) =
                    prove_own(a, b, [p1, &pairs[k2]], [s1, s2], [s1.side, second], &r);
                out.push(CornerCandidate {
                    sites: [x, y],
                    gap,
                    status,
                    edges: r.edges,
                    proof,
                });
            }
        }
    }
    out
}

/// The status of the join of sites `s` (of pairs `p`, the first's piece at the corner with
/// `sides`) round the pieces `r`, and its proof.
fn prove_own(
    a: &[Face],
    b: &[Face],
    p: [&PieceIntersection; 2],
    s: [&EndSite; 2],
    sides: [PieceSide; 2],
    r: &Round<'_>,
) -> (Result<(), &'static str>, Option<CornerProof>) {
    let unproven = |reason| (Err(reason), None);
    if !p[0].result.options.method.certifies() {
        return unproven("the method does not certify");
    }
    let sf = s[0].surface;
    let (q1, q2) = (patches(a, b, p[0]), patches(a, b, p[1]));
    let maps: Vec<ChartMap> = (0..3)
        .filter_map(|i| ChartMap::shift(r.shifts[i], &r.patches[i].domain()))
        .collect();
    if maps.len() != 3 {
        return unproven("a piece round the corner is not shifted exactly");
    }
    let (x, y) = match both_exits(s, [q1, q2]) {
        Ok(b) => b,
        Err(reason) => return unproven(reason),
    };
    let d1 = [q1[0].domain(), q1[1].domain()];
    let round = stitched_round(q1[sf], (0..3).map(|i| (r.patches[i], maps[i])).collect());
    let alone = stitched_round(q1[1 - sf], Vec::new());
    let same = ChartMap::identity();
    let on = |m: ChartMap| if sf == 0 { [m, same] } else { [same, m] };
    let (ka, va) = side_coordinate(&d1[sf], sides[0].side);
    let (kb, vb) = side_coordinate(&d1[sf], sides[1].side);
    let crossed = [(2 * sf + ka, va), (2 * sf + kb, vb)];
    let (sa, sb) = if sf == 0 {
        (&round, &alone)
    } else {
        (&alone, &round)
    };
    let key = |piece: &PieceSide| {
        let other = [p[0].faces[1 - sf], p[0].pieces[1 - sf]];
        let mine = [piece.face, piece.piece];
        if sf == 0 {
            [mine, other]
        } else {
            [other, mine]
        }
    };
    match prove(sa, sb, &x, &y, on(maps[2]), crossed) {
        Ok((k, xyz)) => (
            Ok(()),
            Some(CornerProof {
                k,
                xyz,
                beside: vec![
                    (key(&r.pieces[0]), on(maps[0])),
                    (key(&r.pieces[1]), on(maps[1])),
                ],
            }),
        ),
        Err(reason) => unproven(reason),
    }
}
