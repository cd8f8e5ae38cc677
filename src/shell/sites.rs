//! Branch ends on the sides of their pieces, and their proven exits: what the joins
//! matches (and the corner joins at corners of the piece pair).

use std::collections::HashMap;

use inari::Interval;

use super::edges::{side_coordinate, side_of, side_of_where, EdgeLink, PieceSide};
use super::{Face, PieceIntersection};
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;
use crate::march::branch::{CurvePoint, EndReason};
use crate::numeric::scalar::point;
use crate::pair::krawczyk::{krawczyk, BoxSurface, KrawczykResult, ParamBox};
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

/// A boundary end of a branch, placed on a side of its piece.
#[derive(Clone)]
pub(super) struct EndSite<'a> {
    pub(super) at: BranchEnd,
    /// The pair the branch belongs to.
    pub(super) pair: usize,
    /// The surface (0 or 1) whose piece boundary the end is on.
    pub(super) surface: usize,
    pub(super) side: PieceSide,
    /// The side of the other surface's piece the end point is also on (a corner of the pair).
    pub(super) corner: Option<PieceSide>,
    /// The other side of the same piece the end point is also on (a corner of the piece, where
    /// four pieces of one face meet), when it is on no side of the other surface's piece.
    pub(super) own_corner: Option<PieceSide>,
    /// The marched end point.
    pub(super) point: CurvePoint,
    /// The certified exit, when the branch is certified and its exit could be proven.
    pub(super) exit: Option<Exit>,
    /// The branch's certified tolerance, when it is certified.
    pub(super) tolerance: Option<f64>,
    /// The branch's certificate, when it is certified.
    pub(super) certificate: Option<&'a CertifiedBranch>,
}

impl EndSite<'_> {
    /// At a corner of the pair: its sides on surface 0 and on surface 1.
    pub(super) fn sides(&self) -> Option<[PieceSide; 2]> {
        let c = self.corner?;
        Some(if self.surface == 0 {
            [self.side, c]
        } else {
            [c, self.side]
        })
    }
}

/// A proven end of a certified branch on a side: the exact end point lies in `exit`, and it is
/// the only curve point of the piece pair on the side inside `region`.
#[derive(Clone)]
pub(super) struct Exit {
    pub(super) exit: ParamBox,
    pub(super) region: ParamBox,
    pub(super) xyz: [Interval; 3],
}

/// The pieces of the pair: `[piece of A, piece of B]`.
pub(super) fn patches<'a>(
    a: &'a [Face],
    b: &'a [Face],
    pi: &PieceIntersection,
) -> [&'a RationalBezierPatch; 2] {
    [
        &a[pi.faces[0]].pieces()[pi.pieces[0]],
        &b[pi.faces[1]].pieces()[pi.pieces[1]],
    ]
}

/// The [`EndSite`] of `at` when the marcher ended it on a piece boundary that is a side of the
/// piece.
pub(super) fn end_site<'a>(
    a: &[Face],
    b: &[Face],
    pi: &PieceIntersection,
    pair: usize,
    traced: &'a TracedBranch,
    at: BranchEnd,
) -> Option<EndSite<'a>> {
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
    // Not a side the whole branch runs along (a section along a knot line or seam ends where
    // it crosses another side, perhaps at a corner with the side it runs along).
    let along = |sd: usize| along_side(&m.points, surface, &dom, sd, SIDE_TOLERANCE * size);
    let tol = SIDE_TOLERANCE * size;
    let side = side_of_where(&dom, x, tol, |sd| !along(sd)).or_else(|| side_of(&dom, x, tol))?;
    let side = PieceSide {
        face: pi.faces[surface],
        piece: pi.pieces[surface],
        side,
    };
    let exit = traced
        .certified()
        .and_then(|c| certified_exit(pieces, surface, side.side, &point, c));
    let other = 1 - surface;
    let y = if other == 0 { point.p } else { point.q };
    let corner = side_of(&pieces[other].domain(), y, SIDE_TOLERANCE * size).map(|s| PieceSide {
        face: pi.faces[other],
        piece: pi.pieces[other],
        side: s,
    });
    // The perpendicular sides of the same piece.
    let across = if side.side < 2 { [2, 3] } else { [0, 1] };
    let own_corner = across
        .into_iter()
        .filter(|&sd| corner.is_none() && !along(sd))
        .find_map(|sd| {
            let (k, value) = side_coordinate(&dom, sd);
            ((x[k] - value).abs() <= SIDE_TOLERANCE * size).then_some(PieceSide {
                face: pi.faces[surface],
                piece: pi.pieces[surface],
                side: sd,
            })
        });
    Some(EndSite {
        at,
        pair,
        surface,
        side,
        corner,
        own_corner,
        point,
        exit,
        tolerance: traced.certified_tolerance(),
        certificate: traced.certified(),
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
pub(super) fn certified_exit(
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
    // A boundary end, of either surface: near a corner the certifier names one side and the
    // chain also leaves by the other; what follows proves the exit through `side` on its own.
    if !matches!(c.ends[end], CertifiedEnd::Boundary { .. }) {
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
    let zero = Zero {
        fixed,
        most: MAX_ZERO_BOXES,
        images: |y: &ParamBox| (pieces[0].enclose(y[0], y[1]), pieces[1].enclose(y[2], y[3])),
        cut: |y: &ParamBox| widest(pieces, y, fixed),
    };
    zero.unique(pieces[0], pieces[1], region).ok()
}

/// How [`Zero::unique`] looks for the only zero of `P − Q` in a region with one coordinate
/// held: `images` encloses both surfaces' model-space images of a box, `cut` names the
/// coordinate to bisect a box along, and at most `most` boxes are looked at.
pub(super) struct Zero<I, C> {
    pub(super) fixed: usize,
    pub(super) most: usize,
    pub(super) images: I,
    pub(super) cut: C,
}

impl<I, C> Zero<I, C>
where
    I: Fn(&ParamBox) -> ([Interval; 3], [Interval; 3]),
    C: Fn(&ParamBox) -> usize,
{
    /// The enclosure of the only zero in `region` (coordinate `fixed` a point there): `region`
    /// is cut into boxes until each is proven empty (disjoint images, or a Krawczyk image
    /// disjoint from it) or proven to hold exactly one zero; exactly one box must hold one.
    pub(super) fn unique<P, Q>(
        &self,
        p: &P,
        q: &Q,
        region: ParamBox,
    ) -> Result<ParamBox, &'static str>
    where
        P: BoxSurface + ?Sized,
        Q: BoxSurface + ?Sized,
    {
        let mut todo = vec![region];
        let mut found: Option<ParamBox> = None;
        let mut looked = 0;
        while let Some(y) = todo.pop() {
            looked += 1;
            if looked > self.most {
                return Err("the search for the zero looked at too many boxes");
            }
            let (xp, xq) = (self.images)(&y);
            // Bounded enclosures: both weight functions are nonzero on the box, so every
            // interval evaluation below is of a well-defined function. Otherwise give up.
            if xp.iter().chain(&xq).any(|x| !x.is_common_interval()) {
                return Err("an image is unbounded");
            }
            if xp.iter().zip(&xq).any(|(a, b)| a.disjoint(*b)) {
                continue;
            }
            match krawczyk(p, q, y, self.fixed, 30) {
                KrawczykResult::Proven { enclosure, .. } => {
                    if found.replace(enclosure).is_some() {
                        return Err("two zeros");
                    }
                }
                KrawczykResult::NotProven(reason) if reason.contains("disjoint") => {}
                KrawczykResult::NotProven(_) => {
                    let [a, b] =
                        cut_box(&y, (self.cut)(&y), 0.5).ok_or("a box too small to cut")?;
                    todo.push(a);
                    todo.push(b);
                }
            }
        }
        found.ok_or("no zero")
    }
}

/// The box `y` cut across coordinate `k` at the fraction `at` of its width: `None` if the cut
/// would not fall strictly inside (a box too small to cut) or is not finite.
pub(super) fn cut_box(y: &ParamBox, k: usize, at: f64) -> Option<[ParamBox; 2]> {
    let (lo, hi) = (y[k].inf(), y[k].sup());
    let m = lo + at * (hi - lo);
    if !(lo < m && m < hi) {
        return None;
    }
    let (mut a, mut b) = (*y, *y);
    a[k] = Interval::try_from((lo, m)).ok()?;
    b[k] = Interval::try_from((m, hi)).ok()?;
    Some([a, b])
}

/// Whether every point of `points` lies on `side` of the domain `d` of surface `surface` (0 for
/// P, 1 for Q), within `tol`: the branch runs along that side (two points at least).
pub(super) fn along_side(
    points: &[CurvePoint],
    surface: usize,
    d: &Domain,
    side: usize,
    tol: f64,
) -> bool {
    let (c, value) = side_coordinate(d, side);
    points.len() >= 2
        && points.iter().all(|pt| {
            let x = if surface == 0 { pt.p } else { pt.q };
            (x[c] - value).abs() <= tol
        })
}

/// The model-space distance of two marched end points, when within [`MARCH_JOIN_TOLERANCE`]
/// (relative to `1 + |x|∞` of the points).
pub(super) fn marched_gap(p1: &CurvePoint, p2: &CurvePoint) -> Option<f64> {
    let scale = 1.0
        + p1.xyz
            .iter()
            .chain(&p2.xyz)
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = (0..3)
        .map(|i| (p1.xyz[i] - p2.xyz[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    (gap <= MARCH_JOIN_TOLERANCE * scale).then_some(gap)
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

/// Euclidean distance between two boxes (0 when they overlap).
pub(super) fn box_gap(x: &[Interval], y: &[Interval]) -> f64 {
    x.iter()
        .zip(y)
        .map(|(a, b)| (a.inf() - b.sup()).max(b.inf() - a.sup()).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Sites on the two sides of a link, and where to find them: the sites on a side of a piece
/// pair, by `(pair, surface, side)`, and the pairs by their faces and pieces.
pub(super) struct SiteIndex<'s> {
    pub(super) at_side: &'s HashMap<(usize, usize, PieceSide), Vec<usize>>,
    pub(super) by_pair: &'s HashMap<([usize; 2], [usize; 2]), usize>,
}

impl SiteIndex<'_> {
    /// Every `(x, y, link)`: site `x` on `link.from` (of `links`, sorted by `from`, for the
    /// site's surface), site `y > x` on `link.to` in the piece pair that differs from `x`'s by
    /// that side's piece only. `edge` gives a link's [`EdgeLink`].
    pub(super) fn across<'l, L>(
        &self,
        pairs: &[PieceIntersection],
        sites: &[EndSite<'_>],
        links: &'l [Vec<L>; 2],
        edge: impl Fn(&L) -> &EdgeLink,
    ) -> Vec<(usize, usize, &'l L)> {
        let mut out = Vec::new();
        for (x, s1) in sites.iter().enumerate() {
            let from = &links[s1.surface];
            let first = from.partition_point(|l| edge(l).from < s1.side);
            for l in from[first..].iter().take_while(|l| edge(l).from == s1.side) {
                let to = edge(l).to;
                let p1 = &pairs[s1.pair];
                let (mut faces, mut pieces) = (p1.faces, p1.pieces);
                faces[s1.surface] = to.face;
                pieces[s1.surface] = to.piece;
                let Some(&k2) = self.by_pair.get(&(faces, pieces)) else {
                    continue;
                };
                let Some(others) = self.at_side.get(&(k2, s1.surface, to)) else {
                    continue;
                };
                out.extend(others.iter().filter(|&&y| y > x).map(|&y| (x, y, l)));
            }
        }
        out
    }
}
