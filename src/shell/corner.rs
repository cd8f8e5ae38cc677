//! Joins across a corner of the piece pair: a curve that crosses a shared edge of one surface
//! (a knot line, a seam, or the edge of two faces) exactly where it crosses one of the other
//! (both pieces change at once).
//!
//! The two branches that meet there belong to diagonally neighbouring pairs `(a₁, b₁)` and
//! `(a₂, b₂)`; the two pairs beside the corner, `(a₁, b₂)` and `(a₂, b₁)`, hold at most a sliver
//! of the curve (usually the corner point alone, which the marcher reports as a branch of one
//! point). Neither branch's end lies on an edge its neighbour shares, so the proof
//! of the join module does not apply. Instead:
//!
//! 1. **A chart round the corner.** Each surface's two pieces are written in the parameters of
//!    the first, the second through an affine map across the shared side (`ChartMap`: the
//!    edge's normalised parameter kept, reversed when the edge runs the other way, and the
//!    chart continued past the side onto the second piece). On the union of the two domains
//!    the stitched map is the surface itself: continuous (the pieces are the same curve on the
//!    edge at the same normalised parameter), and continuously differentiable on each piece.
//! 2. **The corner box.** For each branch, walking its chain of enclosure boxes inwards from its
//!    certified end at the corner, the boxes up to the first one strictly inside both of its
//!    pieces' domains hold the chain's curve from there on, so the point where the branch's
//!    part of the true curve ends. The hull of both branches' boxes (in the chart), widened
//!    a little, is the corner box `K`; it must lie in the union of the domains.
//! 3. **One arc.** The parametric Krawczyk test on `K` with the stitched surfaces (their
//!    enclosures hulled over the pieces a box meets: the mean-value inclusion holds for such a
//!    map) proves, for some coordinate held over its whole range in `K`, exactly one curve point
//!    in `K` for each of its values: the curve in `K` is one arc, the graph of a continuous
//!    function. Both branches' exit points lie on it, so the curve between them stays in `K`.
//!
//! The branches of the two side pairs whose marched points all lie in `K` are pieces of that
//! arc: the join absorbs them ([`CornerJoin::absorbed`]).

use std::collections::HashMap;

use inari::Interval;

use super::chart::{chart_map, ChartMap};
use super::edges::{side_coordinate, EdgeKind, EdgeLink};
use super::sites::{marched_gap, patches, EndSite, Zero};
use super::{Face, PieceIntersection};
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;
use crate::march::branch::CurvePoint;
use crate::numeric::scalar::point;
use crate::pair::krawczyk::{krawczyk, BoxSurface, KrawczykResult, ParamBox};

/// What a join across a corner of the piece pair, a proven join through a pole, a proven join
/// across a near edge, or a proven join on a shared edge that absorbed slivers at a vertex of
/// faces adds to [`super::Join`].
#[derive(Debug, Clone, PartialEq)]
pub struct CornerJoin {
    /// The edge crossed on the second surface (the join's `edge` is the first surface's;
    /// [`EdgeKind::Pole`] through a pole; [`EdgeKind::NearEdge`] across a near edge; the
    /// join's own `edge` at a vertex).
    pub second_edge: EdgeKind,
    /// Every point of the true curve between the two parts' ends lies in this model-space box
    /// (the corner box's image, or the pole proof's box, see `shell/pole_cap.rs`; at a vertex,
    /// the hull of the join's proven end boxes and of the slivers' covers, see
    /// `shell/slivers.rs`; across a near edge, the hull of the two proven end boxes, see
    /// `shell/near.rs`; empty when the join is not proven).
    pub xyz: [Interval; 3],
    /// Branches of the other piece pairs at the corner or pole whose marched points all lie in
    /// the corner box or the pole's cap (slivers of the same arc), or at a vertex whose piece
    /// pair's curve there lies in `xyz`: covered by the join and in no curve's parts.
    pub absorbed: Vec<usize>,
}

/// Two neighbouring pieces of one surface written in the first one's parameters (the chart):
/// the second through its [`ChartMap`].
pub(super) struct Stitched<'a> {
    first: &'a RationalBezierPatch,
    /// The other pieces (one across an edge; three round a corner of the first piece, whose
    /// domains and the first's tile a rectangle) with their maps.
    others: Vec<(&'a RationalBezierPatch, ChartMap)>,
}

impl Stitched<'_> {
    /// The domain of piece `k` (0 the first) in the chart.
    fn chart_domain(&self, k: usize) -> Option<[Interval; 2]> {
        if k == 0 {
            let d = self.first.domain();
            Some([
                Interval::try_from((d.u[0], d.u[1])).ok()?,
                Interval::try_from((d.v[0], d.v[1])).ok()?,
            ])
        } else {
            self.others.get(k - 1)?.1.chart_domain()
        }
    }

    /// Whether the chart box `x` lies in the union of the pieces' domains (which is a
    /// rectangle: the pieces tile it).
    fn covers(&self, x: [Interval; 2]) -> bool {
        let mut hull: Option<[Interval; 2]> = None;
        for k in 0..=self.others.len() {
            let Some(d) = self.chart_domain(k) else {
                return false;
            };
            hull = Some(hull.map_or(d, |h| [h[0].convex_hull(d[0]), h[1].convex_hull(d[1])]));
        }
        hull.is_some_and(|h| (0..2).all(|i| x[i].subset(h[i])))
    }
}

impl BoxSurface for Stitched<'_> {
    /// The hull of the pieces' enclosures over the parts of `u × v` in their domains (the whole
    /// line if the box meets neither).
    fn box_first_order(&self, u: Interval, v: Interval) -> [[Interval; 3]; 3] {
        let mut out: Option<[[Interval; 3]; 3]> = None;
        for k in 0..=self.others.len() {
            let Some(d) = self.chart_domain(k) else {
                continue;
            };
            let (cu, cv) = (u.intersection(d[0]), v.intersection(d[1]));
            if cu.is_empty() || cv.is_empty() {
                continue;
            }
            let e = if k == 0 {
                self.first.first_derivs(cu, cv)
            } else {
                // In the piece's parameters, clipped to its domain (the map is enclosed; the
                // domain is exact); the partials by the chart's coordinates by the chain rule.
                let (p, map) = self.others[k - 1];
                let pd = p.domain();
                let (Ok(du), Ok(dv)) = (
                    Interval::try_from((pd.u[0], pd.u[1])),
                    Interval::try_from((pd.v[0], pd.v[1])),
                ) else {
                    continue;
                };
                let [pu, pv] = map.forward([cu, cv]);
                let (pu, pv) = (pu.intersection(du), pv.intersection(dv));
                if pu.is_empty() || pv.is_empty() {
                    continue;
                }
                let [s, su, sv] = p.first_derivs(pu, pv);
                let mut e = [s, s, s];
                for (i, d) in [su, sv].into_iter().enumerate() {
                    let (src, f) = map.chain_factor(i);
                    e[1 + src] = d.map(|c| c * f);
                }
                e
            };
            out = Some(match out {
                None => e,
                Some(o) => {
                    std::array::from_fn(|r| std::array::from_fn(|c| o[r][c].convex_hull(e[r][c])))
                }
            });
        }
        out.unwrap_or([[Interval::ENTIRE; 3]; 3])
    }
}

/// The parameter box of `y` (in a pair's own parameters) in the chart of the corner, each
/// surface's parameters mapped back through its [`ChartMap`].
fn to_chart(y: &ParamBox, maps: [ChartMap; 2]) -> ParamBox {
    let [a, b] = [maps[0].back([y[0], y[1]]), maps[1].back([y[2], y[3]])];
    [a[0], a[1], b[0], b[1]]
}

/// Whether the box `y` lies strictly inside both domains.
fn strictly_inside(y: &ParamBox, doms: [&Domain; 2]) -> bool {
    (0..4).all(|i| {
        let d = doms[i / 2];
        let r = if i % 2 == 0 { d.u } else { d.v };
        y[i].inf() > r[0] && y[i].sup() < r[1]
    })
}

/// The hull of the certified branch `c`'s enclosure boxes at its end nearest `near` (a
/// boundary end), from its outermost box inwards up to the first box strictly inside the
/// pair's domains: the branch's curve from there to the chain's end lies in it, so wherever
/// the branch's part of the true curve ends (leaving the domains, or at the chain's end) is
/// in it.
pub(super) fn exit_boxes(
    c: &CertifiedBranch,
    near: [f64; 4],
    doms: [&Domain; 2],
) -> Option<ParamBox> {
    let distance = |y: &ParamBox| {
        (0..4)
            .map(|i| (y[i].inf() - near[i]).max(near[i] - y[i].sup()).max(0.0))
            .fold(0.0, f64::max)
    };
    let (first, last) = (c.boxes.first()?, c.boxes.last()?);
    let end = usize::from(distance(&last.params()) < distance(&first.params()));
    if !matches!(c.ends[end], CertifiedEnd::Boundary { .. }) {
        return None;
    }
    let walk: Box<dyn Iterator<Item = _>> = if end == 0 {
        Box::new(c.boxes.iter())
    } else {
        Box::new(c.boxes.iter().rev())
    };
    let mut hull: Option<ParamBox> = None;
    for bx in walk {
        let y = bx.params();
        if strictly_inside(&y, doms) {
            return hull;
        }
        hull = Some(match hull {
            None => y,
            Some(h) => std::array::from_fn(|i| h[i].convex_hull(y[i])),
        });
    }
    None
}

/// The two pairs' pieces at a corner and both branches' exit boxes.
type CornerStart<'a> = ([[&'a RationalBezierPatch; 2]; 2], (ParamBox, ParamBox));

/// What both corner proofs start from ([`prove_pair`], and the one round a corner of one
/// surface's own pieces): the two pairs' pieces and the proven exit boxes of both branches
/// ([`both_exits`]); why not, if the method does not certify or an exit is not proven.
pub(super) fn corner_start<'a>(
    a: &'a [Face],
    b: &'a [Face],
    p: [&PieceIntersection; 2],
    s: [&EndSite; 2],
) -> Result<CornerStart<'a>, &'static str> {
    if !p[0].result.options.method.certifies() {
        return Err("the method does not certify");
    }
    let q = [patches(a, b, p[0]), patches(a, b, p[1])];
    Ok((q, both_exits(s, q)?))
}

/// The exit boxes ([`exit_boxes`]) of the two sites `s` at a corner, each in its pair's own
/// parameters (`q`: the pairs' pieces), or why there are none.
fn both_exits(
    s: [&EndSite; 2],
    q: [[&RationalBezierPatch; 2]; 2],
) -> Result<(ParamBox, ParamBox), &'static str> {
    let (Some(c1), Some(c2)) = (s[0].certificate, s[1].certificate) else {
        return Err("an end at the corner is not certified");
    };
    let near = |pt: &CurvePoint| [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
    let (d1, d2) = (
        [q[0][0].domain(), q[0][1].domain()],
        [q[1][0].domain(), q[1][1].domain()],
    );
    match (
        exit_boxes(c1, near(&s[0].point), [&d1[0], &d1[1]]),
        exit_boxes(c2, near(&s[1].point), [&d2[0], &d2[1]]),
    ) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => Err("a certified end does not leave its pieces at the corner"),
    }
}

/// The proof of a corner join (see the module documentation): `x` and `y` are the two
/// branches' exit boxes, `x` in the chart (the first pair's parameters), `y` in the second
/// pair's own; `maps` take the chart to the second pair's parameters; `a`, `b` are the
/// stitched surfaces; `sides` are the coordinate (of `(σ, t, u, v)`) and chart value of the
/// side crossed on each surface. Returns the box holding the curve between the two branches'
/// parts, and its model-space image.
pub(super) fn prove(
    a: &Stitched<'_>,
    b: &Stitched<'_>,
    x: &ParamBox,
    y: &ParamBox,
    maps: [ChartMap; 2],
    sides: [(usize, f64); 2],
) -> Result<(ParamBox, [Interval; 3]), &'static str> {
    let y = to_chart(y, maps);
    let hull: ParamBox = std::array::from_fn(|i| x[i].convex_hull(y[i]));
    // One arc in K0: a graph over coordinate j, proven slice by slice. K0 is the hull widened
    // across j only (along j the exit boxes already reach past both crossings; widened there,
    // the curve would leave K0 through its other faces).
    // Along the curve the exit boxes are long and across it thin: try the coordinates in
    // order of their extent (relative to the pieces' domains), the two longest only.
    let extent = |i: usize| {
        let s = if i < 2 { a } else { b };
        let d = s.first.domain();
        let size = if i.is_multiple_of(2) {
            d.u[1] - d.u[0]
        } else {
            d.v[1] - d.v[0]
        };
        hull[i].wid() / size
    };
    let mut order = [0, 1, 2, 3];
    order.sort_by(|&p, &q| extent(q).total_cmp(&extent(p)));
    let mut arc = None;
    for j in order.into_iter().take(2) {
        let mut k0 = hull;
        for (i, r) in k0.iter_mut().enumerate() {
            pad_one(r, if i == j { 0.0 } else { 0.125 })?;
        }
        if !a.covers([k0[0], k0[1]]) || !b.covers([k0[2], k0[3]]) {
            return Err("the corner box reaches past the two pieces of a surface");
        }
        if let Some(slices) = one_arc(a, b, &k0, j) {
            arc = Some((j, k0, slices));
            break;
        }
    }
    let (j, k0, slices) = arc.ok_or("the curve in the corner box is not proven to be one arc")?;
    // Where the arc crosses each side (once each in K0).
    let mut crossing = Vec::new();
    for (c, value) in sides {
        crossing.push(unique_crossing(a, b, &k0, c, value)?[j]);
    }
    // Between the crossings (the stretch in neither branch's pair): the arc over their range
    // of j, enclosed on the slices it meets.
    let mut range = crossing[0].convex_hull(crossing[1]);
    pad_one(&mut range, 0.125)?;
    let mut k2: Option<ParamBox> = None;
    for sl in &slices {
        let r = sl[j].intersection(range);
        if r.is_empty() {
            continue;
        }
        let mut bx = *sl;
        bx[j] = r;
        let KrawczykResult::Proven { enclosure, .. } = krawczyk(a, b, bx, j, 30) else {
            return Err("the arc between the crossings is not enclosed");
        };
        k2 = Some(match k2 {
            None => enclosure,
            Some(h) => std::array::from_fn(|i| h[i].convex_hull(enclosure[i])),
        });
    }
    let k2 = k2.ok_or("the crossings lie outside the corner box")?;
    let [pa, ..] = a.box_first_order(k2[0], k2[1]);
    let [qb, ..] = b.box_first_order(k2[2], k2[3]);
    let mut xyz = pa;
    for i in 0..3 {
        let both = pa[i].intersection(qb[i]);
        if both.is_empty() {
            return Err("the corner box's images are disjoint");
        }
        xyz[i] = both;
    }
    Ok((k2, xyz))
}

/// Slices of `k` across coordinate `j` (each the whole of `k` in the others) on each of which
/// the parametric Krawczyk test with `j` held over the slice is proven: then for every value of
/// `j` in `k` there is exactly one curve point in `k`. `None` when some slice is not proven at
/// 16 or at 128 slices.
fn one_arc(a: &Stitched<'_>, b: &Stitched<'_>, k: &ParamBox, j: usize) -> Option<Vec<ParamBox>> {
    'count: for n in [16usize, 128] {
        let (lo, hi) = (k[j].inf(), k[j].sup());
        let mut out = Vec::with_capacity(n);
        for m in 0..n {
            // Cut points in f64; consecutive slices share them, so the slices cover k[j].
            let at = |i: usize| {
                if i == 0 {
                    lo
                } else if i == n {
                    hi
                } else {
                    lo + (hi - lo) * i as f64 / n as f64
                }
            };
            let mut s = *k;
            s[j] = Interval::try_from((at(m), at(m + 1))).ok()?;
            // (Contracting iterations keep every curve point of the slice: a proof on a
            // contracted box is one for the whole slice.)
            if !matches!(krawczyk(a, b, s, j, 30), KrawczykResult::Proven { .. }) {
                continue 'count;
            }
            out.push(s);
        }
        return Some(out);
    }
    None
}

/// Most boxes [`unique_crossing`] looks at.
const MOST_CROSSING_BOXES: usize = 512;

/// The enclosure of the only curve point of `k` with coordinate `c` at `value` ([`Zero`]: the
/// images are the stitched surfaces' enclosures, boxes are cut along the free coordinate
/// widest relative to `k`).
fn unique_crossing(
    a: &Stitched<'_>,
    b: &Stitched<'_>,
    k: &ParamBox,
    c: usize,
    value: f64,
) -> Result<ParamBox, &'static str> {
    let mut start = *k;
    start[c] = point(value);
    let zero = Zero {
        fixed: c,
        most: MOST_CROSSING_BOXES,
        images: |y: &ParamBox| {
            let [pa, ..] = a.box_first_order(y[0], y[1]);
            let [qb, ..] = b.box_first_order(y[2], y[3]);
            (pa, qb)
        },
        cut: |y: &ParamBox| {
            let w = |i: usize| y[i].wid() / k[i].wid().max(f64::MIN_POSITIVE);
            (0..4)
                .filter(|&i| i != c)
                .max_by(|&p, &q| w(p).total_cmp(&w(q)))
                .unwrap_or((c + 1) % 4)
        },
    };
    zero.unique(a, b, start)
        .map_err(|_| "a side's crossing in the corner box is not proven unique")
}

/// Widens `r` by `fraction` of its width and `1e-12·(1 + |r|)`.
fn pad_one(r: &mut Interval, fraction: f64) -> Result<(), &'static str> {
    let w = (point(fraction * r.wid()) + point(1e-12 * (1.0 + r.mag()))).sup();
    *r += Interval::try_from((-w, w)).map_err(|_| "a corner box is not finite")?;
    Ok(())
}

/// Whether every point of `points` (a pair's own parameters) lies in the chart box `k` once
/// mapped back through `maps`.
pub(super) fn all_inside(points: &[[f64; 4]], k: &ParamBox, maps: [ChartMap; 2]) -> bool {
    points.iter().all(|p| {
        let y: ParamBox = std::array::from_fn(|i| point(p[i]));
        let c = to_chart(&y, maps);
        (0..4).all(|i| c[i].subset(k[i]))
    })
}

/// The two stitched surfaces of a corner: surface `s`'s pieces `first` and `second`, the
/// second through `map`.
pub(super) fn stitched<'a>(
    first: &'a RationalBezierPatch,
    second: &'a RationalBezierPatch,
    map: ChartMap,
) -> Stitched<'a> {
    Stitched {
        first,
        others: vec![(second, map)],
    }
}

/// A surface's piece `first` with the pieces `others` round it through their maps (none: the
/// piece alone).
pub(super) fn stitched_round<'a>(
    first: &'a RationalBezierPatch,
    others: Vec<(&'a RationalBezierPatch, ChartMap)>,
) -> Stitched<'a> {
    Stitched { first, others }
}

/// A candidate join across a corner, before matching.
pub(super) struct CornerCandidate {
    /// The two end sites (indices into the site list), the first below the second.
    pub(super) sites: [usize; 2],
    /// The marched end points' model-space distance.
    pub(super) gap: f64,
    /// Proven, or why not (the join's status where the method certifies).
    pub(super) status: Result<(), &'static str>,
    /// The edges crossed on the first and the second surface.
    pub(super) edges: [EdgeKind; 2],
    /// When proven: the corner box (in the first site's pair's parameters), its image, and the
    /// pieces of the first and second site's pairs (`[[a₁, b₁], [a₂, b₂]]`, face and piece).
    pub(super) proof: Option<CornerProof>,
}

/// A proven corner box and where it lies.
pub(super) struct CornerProof {
    pub(super) k: ParamBox,
    pub(super) xyz: [Interval; 3],
    /// The pairs beside the corner, whose branches lying in the box are slivers of its arc:
    /// `[[face, piece] of A, [face, piece] of B]`, and per surface the map from the chart to
    /// that pair's piece.
    pub(super) beside: Vec<([[usize; 2]; 2], [ChartMap; 2])>,
}

/// Every candidate join across a corner: an end site on a side of both of its pieces, and one
/// of the pair diagonally across both sides at the same corner, whose marched points agree to
/// [`MARCH_JOIN_TOLERANCE`]; proven as the module documentation says when both are certified.
pub(super) fn candidates(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    sites: &[EndSite],
    links: &[Vec<EdgeLink>; 2],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
) -> Vec<CornerCandidate> {
    let mut out = Vec::new();
    let mut at_pair: HashMap<usize, Vec<usize>> = HashMap::new();
    for (y, s) in sites.iter().enumerate() {
        if s.corner.is_some() {
            at_pair.entry(s.pair).or_default().push(y);
        }
    }
    // An end at a corner has a site on each side: one candidate per pair of branch ends.
    let mut seen = std::collections::HashSet::new();
    for (x, s1) in sites.iter().enumerate() {
        let Some(sides1) = s1.sides() else { continue };
        let from = |k: usize| {
            let l = &links[k];
            let first = l.partition_point(|e| e.from < sides1[k]);
            l[first..].iter().take_while(move |e| e.from == sides1[k])
        };
        for la in from(0) {
            for lb in from(1) {
                let p1 = &pairs[s1.pair];
                let faces = [la.to.face, lb.to.face];
                let pieces = [la.to.piece, lb.to.piece];
                let Some(&k2) = by_pair.get(&(faces, pieces)) else {
                    continue;
                };
                for &y in at_pair.get(&k2).into_iter().flatten() {
                    let s2 = &sites[y];
                    if y <= x || s2.sides() != Some([la.to, lb.to]) || !seen.insert((s1.at, s2.at))
                    {
                        continue;
                    }
                    let Some(gap) = marched_gap(&s1.point, &s2.point) else {
                        continue;
                    };
                    let (status, proof) = prove_pair(a, b, [p1, &pairs[k2]], [s1, s2], [la, lb]);
                    out.push(CornerCandidate {
                        sites: [x, y],
                        gap,
                        status,
                        edges: [la.kind, lb.kind],
                        proof,
                    });
                }
            }
        }
    }
    out
}

/// The status of the corner join of sites `s` of pairs `p` across the links `l` (of A's side,
/// then B's), and its proof.
fn prove_pair(
    a: &[Face],
    b: &[Face],
    p: [&PieceIntersection; 2],
    s: [&EndSite; 2],
    l: [&EdgeLink; 2],
) -> (Result<(), &'static str>, Option<CornerProof>) {
    let unproven = |reason| (Err(reason), None);
    let ([q1, q2], (x, y)) = match corner_start(a, b, p, s) {
        Ok(start) => start,
        Err(reason) => return unproven(reason),
    };
    let (Some(sa), Some(sb)) = (chart_map(l[0], q1[0], q2[0]), chart_map(l[1], q1[1], q2[1]))
    else {
        return unproven("a side at the corner is degenerate");
    };
    let d1 = [q1[0].domain(), q1[1].domain()];
    let sta = stitched(q1[0], q2[0], sa);
    let stb = stitched(q1[1], q2[1], sb);
    let (ka, va) = side_coordinate(&d1[0], l[0].from.side);
    let (kb, vb) = side_coordinate(&d1[1], l[1].from.side);
    match prove(&sta, &stb, &x, &y, [sa, sb], [(ka, va), (2 + kb, vb)]) {
        Ok((k, xyz)) => (
            Ok(()),
            Some({
                // (a₁, b₂): B mapped; (a₂, b₁): A mapped.
                let same = ChartMap::identity();
                let (a1, b1) = (
                    [p[0].faces[0], p[0].pieces[0]],
                    [p[0].faces[1], p[0].pieces[1]],
                );
                let (a2, b2) = (
                    [p[1].faces[0], p[1].pieces[0]],
                    [p[1].faces[1], p[1].pieces[1]],
                );
                CornerProof {
                    k,
                    xyz,
                    beside: vec![([a1, b2], [same, sb]), ([a2, b1], [sa, same])],
                }
            }),
        ),
        Err(reason) => unproven(reason),
    }
}

/// The branches (shell-wide, numbered as the joins number them) of the two side pairs of a proven
/// corner whose marched points all lie in its box.
pub(super) fn absorbed(
    proof: &CornerProof,
    pairs: &[PieceIntersection],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
    first_branch: &[usize],
) -> Vec<usize> {
    let mut out = Vec::new();
    for &([pa, pb], maps) in &proof.beside {
        let Some(&k) = by_pair.get(&([pa[0], pb[0]], [pa[1], pb[1]])) else {
            continue;
        };
        for (i, br) in pairs[k].result.branches.iter().enumerate() {
            let pts: Vec<[f64; 4]> = br
                .marched
                .points
                .iter()
                .map(|c| [c.p[0], c.p[1], c.q[0], c.q[1]])
                .collect();
            if !pts.is_empty() && all_inside(&pts, &proof.k, maps) {
                out.push(first_branch[k] + i);
            }
        }
    }
    out
}

/// The Euclidean diameter of a model-space box, rounded up (infinite for an empty or unbounded
/// box).
pub(crate) fn diameter(x: &[Interval; 3]) -> f64 {
    let s = x
        .iter()
        .map(|c| {
            let w = point(c.sup()) - point(c.inf());
            w * w
        })
        .fold(point(0.0), |a, b| a + b);
    s.sqrt().sup()
}
