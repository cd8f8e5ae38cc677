//! Joins across a corner of one surface's own pieces: a curve through a point where four
//! pieces of one surface meet (two knot lines crossing, a knot line and a periodic seam, or a
//! vertex of four faces of a shell), at a point inside the other surface's piece. The great
//! circle of a NURBS sphere in a plane through its centre and a knot-line crossing of the
//! equator does this.
//!
//! The two branches that meet there belong to the pairs of diagonally opposite pieces `a₁` and
//! `a₂` of that surface with the other surface's piece `b`; the pairs of the two pieces beside
//! the corner, `a_x` (across the first side) and `a_y` (across the second), hold at most a
//! sliver (the corner point). The proof is the one of [`super::corner`] with the chart made of
//! all four pieces round the corner: `a₁`'s parameters, `a_x` and `a_y` mapped across the edge
//! each shares with `a₁` ([`super::chart::chart_map`]), and `a₂` through both, checked to be
//! the same piece with its sides on the corner's lines either way round, so that the four tile
//! a rectangle of the chart and the stitched map is continuous across all four edges. The
//! other surface is its one piece.

use std::collections::{HashMap, HashSet};

use super::chart::{chart_map, ChartMap};
use super::corner::{corner_start, prove, stitched_round, CornerCandidate, CornerProof};
use super::edges::{side_coordinate, EdgeKind, EdgeLink, PieceSide};
use super::sites::{marched_gap, EndSite};
use super::{Face, PieceIntersection};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;

/// The links of `links` (sorted by their `from` side) from `side`.
fn from_side(links: &[EdgeLink], side: PieceSide) -> impl Iterator<Item = &EdgeLink> {
    let first = links.partition_point(|e| e.from < side);
    links[first..].iter().take_while(move |e| e.from == side)
}

/// The four pieces round a corner of piece `a₁` of one surface, with the maps from `a₁`'s
/// parameters (the chart) to theirs.
struct Round<'a> {
    /// `a_x`, `a_y` (across the site's first and second side) and `a₂` (diagonally across).
    pieces: [PieceSide; 3],
    maps: [ChartMap; 3],
    patches: [&'a RationalBezierPatch; 3],
    edges: [EdgeKind; 2],
}

/// The side of the piece with domain `d` at which its parameter `i` takes the value `v` (an
/// end of its range).
fn side_at(d: &Domain, i: usize, v: f64) -> Option<usize> {
    let r = if i == 0 { d.u } else { d.v };
    if v == r[0] {
        Some(2 * i)
    } else if v == r[1] {
        Some(2 * i + 1)
    } else {
        None
    }
}

/// The pieces round the corner of the site's piece `a₁` at its sides `sides`: `a_x` and
/// `a_y` across them, and `a₂` across the side of `a_x` that continues the second side and
/// across the side of `a_y` that continues the first (the same piece both ways). `a₂`'s map
/// takes each chart coordinate across the edge it crosses first and then along the next
/// ([`ChartMap::composed`]), and must put the corner's lines on `a₂`'s sides at the two edges
/// it shares with `a_x` and `a_y`: then the four pieces tile a rectangle of the chart and
/// the stitched map is continuous across all four edges.
fn round<'a>(faces: &'a [Face], links: &[EdgeLink], sides: [PieceSide; 2]) -> Vec<Round<'a>> {
    let piece = |ps: &PieceSide| &faces[ps.face].pieces()[ps.piece];
    let dom = |ps: &PieceSide| piece(ps).domain();
    let d1 = dom(&sides[0]);
    let (k1, v1) = side_coordinate(&d1, sides[0].side);
    let (k2, v2) = side_coordinate(&d1, sides[1].side);
    let mut out = Vec::new();
    for l1 in from_side(links, sides[0]) {
        for l3 in from_side(links, sides[1]) {
            let (ax, ay) = (l1.to, l3.to);
            let found = (|| {
                let m1 = chart_map(l1, piece(&sides[0]), piece(&ax))?;
                let m3 = chart_map(l3, piece(&sides[0]), piece(&ay))?;
                // The sides of a_x and a_y through the corner, continuing a₁'s other side.
                let (jx, wx) = m1.end_image(k2, v2)?;
                let (jy, wy) = m3.end_image(k1, v1)?;
                let ax_side = PieceSide {
                    side: side_at(&dom(&ax), jx, wx)?,
                    ..ax
                };
                let ay_side = PieceSide {
                    side: side_at(&dom(&ay), jy, wy)?,
                    ..ay
                };
                Some((m1, m3, jx, jy, ax_side, ay_side))
            })();
            let Some((m1, m3, jx, jy, ax_side, ay_side)) = found else {
                continue;
            };
            for l2 in from_side(links, ax_side) {
                for l4 in from_side(links, ay_side) {
                    let a2 = l2.to;
                    if (a2.face, a2.piece) != (l4.to.face, l4.to.piece) {
                        continue;
                    }
                    let d2 = dom(&a2);
                    let m2 = (|| {
                        let m2 = chart_map(l2, piece(&ax), piece(&a2))?;
                        let m4 = chart_map(l4, piece(&ay), piece(&a2))?;
                        // a_x's parameter along l₂ is the one across l₁ (1 − jx); the one of
                        // a₂ it becomes, along l₂, is fixed on l₄'s side. Likewise round a_y.
                        let (i2, _) = side_coordinate(&d2, l4.to.side);
                        let (i4, _) = side_coordinate(&d2, l2.to.side);
                        let map =
                            ChartMap::composed([(&m1, 1 - jx, &m2, i2), (&m3, 1 - jy, &m4, i4)])?;
                        // The corner's lines land on a₂'s sides at l₂ and l₄.
                        let at_l2 = map.end_image(k2, v2)? == side_coordinate(&d2, l2.to.side);
                        let at_l4 = map.end_image(k1, v1)? == side_coordinate(&d2, l4.to.side);
                        (at_l2 && at_l4).then_some(map)
                    })();
                    if let Some(m2) = m2 {
                        out.push(Round {
                            pieces: [ax, ay, a2],
                            maps: [m1, m3, m2],
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
    let ([q1, _], (x, y)) = match corner_start(a, b, p, s) {
        Ok(start) => start,
        Err(reason) => return unproven(reason),
    };
    let sf = s[0].surface;
    let maps = r.maps;
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
