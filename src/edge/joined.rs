//! The edge of a joined shell curve ([`JoinedCurve`]): its parts' chains, each cut where it
//! crosses the piece side of a join, end to end.
//!
//! A branch of one piece pair is certified a little past the side of its piece (the chain's
//! last link proves a curve point outside), on the piece's polynomial extended beyond its
//! domain, which is not the shell's surface there. So at each join (and at a boundary end of
//! the curve) the part is cut: on the link
//! where the reported curve crosses the side coordinate's value, at the crossing `τ_c`; a range
//! `T` of `τ` around it is proven to hold every `τ` where the true curve can meet the side
//! (the reported side coordinate, widened by `radius_param`, is strictly inside the piece
//! before `T` on that link and strictly outside after it, on that link and every later one).
//! When the crossing lies at the junction of two links (the marched branch, and so the chain,
//! ends exactly on the side: the next link starts on the side to within an ulp, and cannot be
//! proven outside at its start), `T` straddles the junction: the end of the cut link from
//! `τ_c − w` on, and the next link's start up to where it is proven outside. The side
//! coordinate is enclosed by its Taylor form at the centre of each checked range, on ranges
//! growing geometrically away from the crossing, so `T` can be as narrow as the radius allows.
//! The true arc over `T` is the cut's share of the tolerance (see [`super`]). Every join must be
//! [`JoinStatus::Proven`]: the two parts' true end points are then one point on the side. At a
//! join across a corner of the piece pair (both pieces change, or two sides of one surface's
//! piece at a corner of its own pieces) each part is cut where it first leaves its pieces'
//! domains (the side whose proven crossing range starts first: before it the chain is inside
//! both), and the true arc between the two parts lies in the join's corner box, whose diameter
//! adds to the cut's share.

use super::poly::{eval, eval_mid, reparametrised, taylor_shift, Poly};
use super::{assemble, chain_segs, check_chain, Cut, Edge, EdgeError, Part, Seg};
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use crate::pair::krawczyk::{krawczyk, KrawczykResult};
use crate::shell::corner::diameter;
use crate::shell::edges::EdgeKind;
use crate::shell::{Face, JoinStatus, JoinedCurve, ShellIntersection};
use inari::Interval;

/// Samples of a link's reported curve when looking for the crossing.
const SAMPLES: usize = 32;
/// Sub-intervals of the interval checks before and after the crossing.
const CHECKS: usize = 16;

/// The edge of the joined curve `curve` of the shell intersection `shell` of shells `a`, `b`.
///
/// Errors: [`EdgeError::NotCertified`] for a part without a certificate,
/// [`EdgeError::UnprovenJoin`] for a join that is not proven, [`EdgeError::Trim`] where a part
/// cannot be cut at its side, and as [`super::edge_from_certified`].
pub fn edge_from_joined(
    a: &[Face],
    b: &[Face],
    shell: &ShellIntersection,
    curve: &JoinedCurve,
) -> Result<Edge, EdgeError> {
    for (k, j) in curve.joins.iter().enumerate() {
        match &j.status {
            JoinStatus::Proven => {}
            JoinStatus::Unproven { reason } => {
                return Err(EdgeError::UnprovenJoin {
                    join: k,
                    reason: (*reason).into(),
                })
            }
            JoinStatus::Marched => {
                return Err(EdgeError::UnprovenJoin {
                    join: k,
                    reason: "joined on marched points only".into(),
                })
            }
        }
    }
    let n = curve.parts.len();
    let cyclic = curve.closed && !curve.joins.is_empty();
    let mut parts = Vec::with_capacity(n);
    for (k, part) in curve.parts.iter().enumerate() {
        let g = part.branch;
        let (pi, traced) = shell.branch(g).ok_or_else(|| EdgeError::NotCertified {
            branch: g,
            reason: "no such branch".into(),
        })?;
        let cert = match &traced.certificate {
            Some(c) => c.result.as_ref().map_err(|e| EdgeError::NotCertified {
                branch: g,
                reason: e.to_string(),
            })?,
            None => {
                return Err(EdgeError::NotCertified {
                    branch: g,
                    reason: "the method does not certify".into(),
                })
            }
        };
        check_chain(cert, g)?;
        let p = &a[pi.faces[0]].pieces()[pi.pieces[0]];
        let q = &b[pi.faces[1]].pieces()[pi.pieces[1]];
        let mut segs = chain_segs(cert, part.reversed);
        // The certified ends in the edge's direction.
        let ends = if part.reversed {
            [&cert.ends[1], &cert.ends[0]]
        } else {
            [&cert.ends[0], &cert.ends[1]]
        };
        // The joins before and after this part, and whether each is across a corner or
        // through a pole.
        let join_at = |i: Option<usize>| -> Option<MustCut> {
            let j = &curve.joins[i?];
            Some(match (&j.corner, j.edge) {
                (None, _) => MustCut::Side,
                (Some(c), EdgeKind::Pole) => MustCut::Pole(diameter(&c.xyz)),
                (Some(c), _) => MustCut::Corner(diameter(&c.xyz)),
            })
        };
        let before = if k > 0 {
            Some(k - 1)
        } else if cyclic {
            Some(curve.joins.len() - 1)
        } else {
            None
        };
        let after = (k + 1 < n || cyclic).then_some(k);
        let cuts = cut_ends(
            cert,
            &mut segs,
            ends,
            [p, q],
            g,
            [join_at(before), join_at(after)],
        )?;
        if !cyclic && curve.closed {
            // One closed branch, no joins: closed by its own certificate.
            let tol = Some(shell.options.required_tolerance);
            return super::edge_from_certified_within(p, q, cert, g, tol).map(|mut e| {
                e.pcurves.iter_mut().for_each(|c| {
                    c.face = pi.faces[c.surface];
                    c.piece = pi.pieces[c.surface];
                });
                e
            });
        }
        parts.push(Part {
            p,
            q,
            cert,
            branch: g,
            faces: pi.faces,
            pieces: pi.pieces,
            segs,
            cuts,
        });
    }
    assemble(
        &parts,
        curve.closed,
        false,
        Some(shell.options.required_tolerance),
    )
}

/// How an end of a part must be cut at a join (an end without a join is cut only if it is a
/// boundary end).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum MustCut {
    /// At the piece side the join is on.
    Side,
    /// Across a corner of the piece pair: where the chain first leaves its pieces; the corner
    /// box's diameter is the cut's extra share.
    Corner(f64),
    /// Through a pole: at the chain's end (unproven at the pole); the diameter of the box
    /// holding the arc through the pole is the cut's extra share.
    Pole(f64),
}

/// Cuts the chain `segs` (in the edge's direction, its certified ends `ends` in that order)
/// at the piece side of each end that must be cut (`must`: a join) or is a boundary end. At a
/// join across a corner the chain is cut where it first leaves its pieces' domains: at the side
/// of either surface whose proven crossing range starts first ([`cut_at_corner`]).
pub(super) fn cut_ends(
    cert: &CertifiedBranch,
    segs: &mut Vec<Seg>,
    ends: [&CertifiedEnd; 2],
    pq: [&RationalBezierPatch; 2],
    branch: usize,
    must: [Option<MustCut>; 2],
) -> Result<Vec<Cut>, EdgeError> {
    let mut cuts = Vec::new();
    let boundary = |e: &CertifiedEnd| matches!(e, CertifiedEnd::Boundary { .. });
    let cut = |segs: &mut Vec<Seg>, end: &CertifiedEnd, m: Option<MustCut>| match m {
        Some(MustCut::Corner(corner)) => cut_at_corner(cert, segs, end, pq, branch, corner),
        Some(MustCut::Pole(share)) => cut_at_pole(segs, end, branch, share),
        _ => cut_at_side(cert, segs, end, pq, branch, None).map(|(c, _)| c),
    };
    if must[0].is_some() || boundary(ends[0]) {
        flip(segs);
        let c = cut(segs, ends[0], must[0]);
        flip(segs);
        cuts.push(c?);
    }
    if must[1].is_some() || boundary(ends[1]) {
        cuts.push(cut(segs, ends[1], must[1])?);
    }
    Ok(cuts)
}

/// [`cut_at_side`] at a join across a corner: the chain's end (a boundary end, of either
/// surface) is cut at every side it lies beyond (on copies: the side of P and of Q across a
/// corner of the piece pair, two sides of one surface across a corner of its own pieces), and
/// the cut whose proven range starts first along the chain is kept. Before that start the chain is
/// strictly inside both domains (each cut proves its own side), so the part is the true curve
/// up to its cut; the corner box's diameter `corner` is the cut's extra share.
fn cut_at_corner(
    cert: &CertifiedBranch,
    segs: &mut Vec<Seg>,
    end: &CertifiedEnd,
    pq: [&RationalBezierPatch; 2],
    branch: usize,
    corner: f64,
) -> Result<Cut, EdgeError> {
    if !matches!(end, CertifiedEnd::Boundary { .. }) {
        return Err(EdgeError::Trim {
            branch,
            reason: "the part's end at the corner is not a proven boundary end".into(),
        });
    }
    // Every side the chain's end lies beyond must be cut (one of each surface across a corner
    // of the piece pair, two of one surface across a corner of its own pieces): the earliest
    // cut's claim (inside the domains before it) rests on the other cuts proving the chain
    // inside up to their own ranges.
    let mut cuts = Vec::with_capacity(2);
    for surface in 0..2 {
        for coord in 0..2 {
            if !ends_beyond(cert, segs, pq, surface, coord) {
                continue;
            }
            let mut mine = segs.clone();
            let boundary = CertifiedEnd::Boundary { surface };
            let (c, at) = cut_at_side(cert, &mut mine, &boundary, pq, branch, Some(coord))?;
            cuts.push((mine, c, at));
        }
    }
    let first = (0..cuts.len())
        .min_by(|&i, &j| {
            let (a, b) = (cuts[i].2, cuts[j].2);
            (a.0, a.1)
                .partial_cmp(&(b.0, b.1))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .ok_or_else(|| EdgeError::Trim {
            branch,
            reason: "the part's end at the corner lies inside both pieces".into(),
        })?;
    let (mine, c, _) = cuts.swap_remove(first);
    *segs = mine;
    Ok(Cut { corner, ..c })
}

/// At a join through a pole: the chain is not cut (its end, unproven at the pole, is inside
/// the pieces); the last link's end is the cut, and `share`, the diameter of the join's box
/// holding the true arc from there through the pole to the next part, its extra share.
fn cut_at_pole(
    segs: &mut [Seg],
    end: &CertifiedEnd,
    branch: usize,
    share: f64,
) -> Result<Cut, EdgeError> {
    let fail = |reason: &str| EdgeError::Trim {
        branch,
        reason: reason.into(),
    };
    if !matches!(end, CertifiedEnd::Unproven { .. }) {
        return Err(fail(
            "the part's end at the pole is not where its chain stops",
        ));
    }
    let last = segs.last().ok_or_else(|| fail("no links"))?;
    Ok(Cut {
        tube: last.tube,
        gap: point(last.tb),
        next: None,
        corner: share,
    })
}

/// Whether the reported end of the chain `segs` lies beyond a side of coordinate `coord` (0
/// for `u`, 1 for `v`) of `surface`'s piece (guidance: which sides to cut at).
fn ends_beyond(
    cert: &CertifiedBranch,
    segs: &[Seg],
    pq: [&RationalBezierPatch; 2],
    surface: usize,
    coord: usize,
) -> bool {
    let Some(last) = segs.last() else {
        return false;
    };
    let end = eval_mid(
        &reparametrised(&cert.tubes[last.tube].coeffs, last.ta, last.tb),
        1.0,
    );
    let d = pq[surface].domain();
    let (lo, hi) = if coord == 0 {
        (d.u[0], d.u[1])
    } else {
        (d.v[0], d.v[1])
    };
    let x = end[2 * surface + coord];
    x < lo || x > hi
}

/// The segments run the other way.
fn flip(segs: &mut [Seg]) {
    segs.reverse();
    for s in segs.iter_mut() {
        std::mem::swap(&mut s.ta, &mut s.tb);
    }
}

/// Whether the sample point `x` is inside the domains of the coordinates `coords`.
fn inside(x: &[f64; 4], coords: [usize; 2], lo: [f64; 2], hi: [f64; 2]) -> bool {
    (0..2).all(|i| x[coords[i]] >= lo[i] && x[coords[i]] <= hi[i])
}

/// Cuts the last segments of `segs` at the side of the piece that the chain's end `end` (a
/// boundary end) leaves through; the cut's `τ` range, and where along the chain its proven
/// range starts (the cut link's index and fraction).
fn cut_at_side(
    cert: &CertifiedBranch,
    segs: &mut Vec<Seg>,
    end: &CertifiedEnd,
    pq: [&RationalBezierPatch; 2],
    branch: usize,
    only: Option<usize>,
) -> Result<(Cut, (usize, f64)), EdgeError> {
    let fail = |reason: &str| EdgeError::Trim {
        branch,
        reason: reason.into(),
    };
    let CertifiedEnd::Boundary { surface } = *end else {
        return Err(fail(
            "the part's end at the join is not a proven boundary end",
        ));
    };
    let d = &pq[surface].domain();
    let coords = if surface == 0 { [0, 1] } else { [2, 3] };
    let (lo, hi) = ([d.u[0], d.v[0]], [d.u[1], d.v[1]]);
    let poly_of = |s: &Seg| reparametrised(&cert.tubes[s.tube].coeffs, s.ta, s.tb);
    let last = segs.last().ok_or_else(|| fail("no links"))?;
    let end_pt = eval_mid(&poly_of(last), 1.0);
    // The side: the coordinate (and bound) the chain's end lies beyond (`only` that one).
    let (c, bound, out_sign) = (0..2)
        .filter(|&i| only.is_none_or(|o| o == i))
        .find_map(|i| {
            let x = end_pt[coords[i]];
            if x < lo[i] {
                Some((i, lo[i], -1.0))
            } else if x > hi[i] {
                Some((i, hi[i], 1.0))
            } else {
                None
            }
        })
        .ok_or_else(|| fail("the chain ends inside the piece"))?;
    let b = coords[c];
    // The last segment with a sample inside the piece.
    let (k, u_in) = segs
        .iter()
        .enumerate()
        .rev()
        .find_map(|(k, s)| {
            let y = poly_of(s);
            (0..=SAMPLES)
                .rev()
                .map(|m| m as f64 / SAMPLES as f64)
                .find(|&u| inside(&eval_mid(&y, u), coords, lo, hi))
                .map(|u| (k, u))
        })
        .ok_or_else(|| fail("no link reaches inside the piece"))?;
    let seg = segs[k];
    let y = poly_of(&seg);
    let side = Side {
        cert,
        b,
        bound,
        out_sign,
    };
    let strictly = |s: &Seg, y: &Poly<4>, u0: f64, u1: f64, outside: bool, first: f64| {
        side.strictly(s, y, [u0, u1], outside, first)
    };
    let all_outside = |from: usize| {
        segs[from.min(segs.len())..]
            .iter()
            .all(|s| strictly(s, &poly_of(s), 0.0, 1.0, true, 1.0))
    };
    // The reported crossing on the cut link (its end when the reported curve crosses only
    // at the junction with the next link).
    let uc = match side.reported_crossing(&y, u_in) {
        Some(uc) => uc,
        None if k + 1 < segs.len() => 1.0,
        None => return Err(fail("the cut link does not cross the side")),
    };
    let later_outside = all_outside(k + 1);
    // The next link, and the `e` from which on it is proven outside (`[0, e]` is where the
    // crossing may lie past the cut link), when the links after it are outside.
    let mut beyond: Option<Option<(Seg, f64)>> = None;
    let mut straddle = || {
        *beyond.get_or_insert_with(|| {
            let ns = *segs.get(k + 1)?;
            if !all_outside(k + 2) {
                return None;
            }
            let ny = poly_of(&ns);
            let mut e = 1e-12;
            loop {
                if strictly(&ns, &ny, e, 1.0, true, e) {
                    break Some((ns, e));
                }
                if e >= 0.25 {
                    break None;
                }
                e *= 4.0;
            }
        })
    };
    // The range `[u0, u1]` of the cut link around the crossing, and how far into the next
    // link the crossing may lie (`None`: not past the cut link).
    let mut attempt = |w: f64| {
        let (u0, u1) = ((uc - w).max(0.0), (uc + w).min(1.0));
        if !strictly(&seg, &y, 0.0, u0, false, w) {
            return None;
        }
        if u1 < 1.0 && later_outside && strictly(&seg, &y, u1, 1.0, true, w) {
            return Some((u0, u1, None));
        }
        // The range straddles the junction: the rest of the cut link, and the start of the
        // next one up to where that is proven outside.
        straddle().map(|n| (u0, 1.0, Some(n)))
    };
    let proven = smallest(&mut attempt);
    let Some((u0, u1, beyond)) = proven else {
        return Err(fail(if later_outside || straddle().is_some() {
            "the crossing could not be isolated"
        } else {
            "a later link is not proven outside the piece"
        }));
    };
    let at = if uc >= 1.0 {
        seg.tb
    } else {
        seg.ta + (seg.tb - seg.ta) * uc
    };
    let next_range = beyond.map(|(ns, e)| (ns.tube, tau_range(&ns, 0.0, e)));
    let next = beyond.map(|(ns, e)| (ns, poly_of(&ns), e));
    let (gap, at, next_range) = narrowed_cut(
        &side,
        pq,
        (&seg, &y, [u0, u1]),
        next.as_ref(),
        (tau_range(&seg, u0, u1), at, next_range),
    );
    let gap = gap.convex_hull(point(at));
    segs.truncate(k + 1);
    if let Some(s) = segs.last_mut() {
        s.tb = at;
    }
    let cut = Cut {
        tube: seg.tube,
        gap,
        next: next_range,
        corner: 0.0,
    };
    Ok((cut, (k, u0)))
}

/// The cut's `τ` range on the cut link, the cut point and the next link's range, narrowed to
/// the proven crossing where [`Side::crossing_slice`] holds (else `was` unchanged): the cut
/// is at the crossing's middle, not at the reported curve's crossing (which lies up to the
/// tube's width off it), or at the junction when the crossing may lie on the next link.
#[allow(clippy::type_complexity)]
fn narrowed_cut(
    side: &Side,
    pq: [&RationalBezierPatch; 2],
    cut: (&Seg, &Poly<4>, [f64; 2]),
    next: Option<&(Seg, Poly<4>, f64)>,
    was: (Interval, f64, Option<(usize, Interval)>),
) -> (Interval, f64, Option<(usize, Interval)>) {
    let (gap, _, next_range) = was;
    let seg = cut.0;
    let Some(c) = side.crossing_slice(pq, cut, next, gap) else {
        return was;
    };
    let (gap, at) = if c.on_cut.is_empty() {
        (point(seg.tb), seg.tb)
    } else if c.on_next.is_some() {
        (c.on_cut, seg.tb)
    } else {
        (c.on_cut, c.on_cut.mid())
    };
    let next_range = next_range.zip(c.on_next).map(|((t, _), r)| (t, r));
    (gap, at, next_range)
}

/// Where the true curve's crossing of a side lies ([`Side::crossing_slice`]): the `τ` range on
/// the cut link (empty when it lies wholly on the next), and on the next link if it may lie
/// there.
struct Crossing {
    on_cut: Interval,
    on_next: Option<Interval>,
}

/// The `τ` range of the piece `s` over `u ∈ [a, z]` (`τ = ta + (tb − ta)·u`), enclosed.
fn tau_range(s: &Seg, a: f64, z: f64) -> Interval {
    let len = point(s.tb) - point(s.ta);
    point(s.ta) + len * inari::interval!(a, z).unwrap_or(Interval::ENTIRE)
}

/// The side a chain is cut at: coordinate `b` of the four parameters at the value `bound`,
/// outside where `out_sign·(x_b − bound) > 0`.
struct Side<'a> {
    cert: &'a CertifiedBranch,
    b: usize,
    bound: f64,
    out_sign: f64,
}

impl Side<'_> {
    /// Signed side distance of the true curve over `u` on the piece `s` (its polynomial `y`):
    /// `out_sign·(y_b(u) − bound)` ± the tube's radius (none in the along coordinate, which
    /// the tube holds exactly). The polynomial is enclosed by its Taylor form at the centre of
    /// `u` (excess quadratic in the width, so that ranges next to the crossing can be proven).
    fn distance(&self, s: &Seg, y: &Poly<4>, u: Interval) -> Interval {
        let t = &self.cert.tubes[s.tube];
        let along = t.along.map(|a| a.index).unwrap_or(0);
        let rp = if self.b == along { 0.0 } else { t.radius_param };
        let m = u.mid();
        let centred = eval(&taylor_shift(y, point(m)), u - point(m), self.b);
        point(self.out_sign) * (centred - point(self.bound))
            + inari::interval!(-rp, rp).unwrap_or(Interval::ENTIRE)
    }

    /// The `τ` range of the cut link `s` (its reported curve `y`) that holds the true curve's
    /// first crossing of the side, narrowed from `gap` (`τ` over `u ∈ [u0, u1]`, proven to
    /// hold it, or to hold it unless it lies on the next link's `[0, e]`, `next`). The tubes
    /// over those ranges are hulled into a box `B` holding every true curve point there (one
    /// arc); Krawczyk's test on `B` with `x_b` held at the bound proves exactly one point of
    /// the arc on the side, a transversal crossing (so the arc is outside after it), and
    /// encloses it. Its along coordinate maps back to `τ` (exactly affine); with a next link
    /// (graphed over the same coordinate, the same way) the range must lie within `gap` to be
    /// on the cut link. `None` when any of this fails (then the tube's own range stands).
    /// Near-transversal crossings of a wide link: the range is then the crossing's rounding,
    /// not the tube's width over the crossing's slope (the cube's faces: a cut share of 1.1e-9
    /// from a link of 1.5e-10).
    fn crossing_slice(
        &self,
        pq: [&RationalBezierPatch; 2],
        (s, y, [u0, u1]): (&Seg, &Poly<4>, [f64; 2]),
        next: Option<&(Seg, Poly<4>, f64)>,
        gap: Interval,
    ) -> Option<Crossing> {
        let t = &self.cert.tubes[s.tube];
        let along = t.along?.index;
        if along == self.b {
            return None;
        }
        // τ = dir·(x_j − from), `from` and `dir` (±1) exact as in `TubePiece`.
        let from = t.coeffs.first()?[along];
        let dir = t.coeffs.get(1)?[along];
        if dir.abs() != 1.0 {
            return None;
        }
        let tube_box = |piece: &crate::certify::TubePiece, y: &Poly<4>, a: f64, z: f64| {
            let u = inari::interval!(a, z).ok()?;
            let m = u.mid();
            let shifted = taylor_shift(y, point(m));
            let rp = inari::interval!(-piece.radius_param, piece.radius_param).ok()?;
            Some(std::array::from_fn::<Interval, 4, _>(|i| {
                let c = eval(&shifted, u - point(m), i);
                if i == along {
                    c
                } else {
                    c + rp
                }
            }))
        };
        let mut bx = tube_box(t, y, u0, u1)?;
        if let Some((ns, ny, e)) = next {
            let nt = &self.cert.tubes[ns.tube];
            if nt.along.map(|a| a.index) != Some(along) || nt.coeffs.get(1)?[along] != dir {
                return None;
            }
            let nb = tube_box(nt, ny, 0.0, *e)?;
            bx = std::array::from_fn(|i| bx[i].convex_hull(nb[i]));
        }
        bx[self.b] = point(self.bound);
        let KrawczykResult::Proven { enclosure, .. } = krawczyk(pq[0], pq[1], bx, self.b, 8) else {
            return None;
        };
        let tau = (enclosure[along] - point(from)) * point(dir);
        let on_cut = tau.intersection(gap);
        let on_next = match next {
            Some((ns, _, e)) => {
                let nt = &self.cert.tubes[ns.tube];
                let from = nt.coeffs.first()?[along];
                let whole = tau_range(ns, 0.0, *e);
                let r = ((enclosure[along] - point(from)) * point(dir)).intersection(whole);
                (!r.is_empty()).then_some(r)
            }
            None => None,
        };
        if on_cut.is_empty() && on_next.is_none() {
            return None;
        }
        let narrower = on_cut.is_empty() || on_cut.wid() < gap.wid();
        narrower.then_some(Crossing { on_cut, on_next })
    }

    /// Whether the true curve over `u ∈ [u0, u1]` of the piece `s` is proven strictly inside
    /// (`outside` false) or strictly outside the side. The crossing is near `u1` when inside,
    /// near `u0` when outside: the sub-ranges start at the width `first` there and double away
    /// from it, up to a [`CHECKS`]-th of the range.
    fn strictly(
        &self,
        s: &Seg,
        y: &Poly<4>,
        [u0, u1]: [f64; 2],
        outside: bool,
        first: f64,
    ) -> bool {
        if u1 <= u0 {
            return true;
        }
        let cap = (u1 - u0) / CHECKS as f64;
        let mut width = first.min(cap);
        let mut done = 0.0;
        while done < u1 - u0 {
            let next = (done + width).min(u1 - u0);
            let (a, z) = if outside {
                (u0 + done, if next >= u1 - u0 { u1 } else { u0 + next })
            } else {
                (if next >= u1 - u0 { u0 } else { u1 - next }, u1 - done)
            };
            let u = inari::interval!(a.min(z), z.max(a)).unwrap_or(Interval::ENTIRE);
            let v = self.distance(s, y, u);
            if !(if outside {
                v.inf() > 0.0
            } else {
                v.sup() < 0.0
            }) {
                return false;
            }
            done = next;
            width = (2.0 * width).min(cap);
        }
        true
    }

    /// Where the reported curve `y` (midpoints, guidance only) crosses the side after `u_in`
    /// (a sample inside), by bisection; `None` when its end is not outside.
    fn reported_crossing(&self, y: &Poly<4>, u_in: f64) -> Option<f64> {
        let f = |u: f64| self.out_sign * (eval_mid(y, u)[self.b] - self.bound);
        if f(1.0) <= 0.0 {
            return None;
        }
        let (mut a0, mut a1) = (u_in, 1.0);
        for _ in 0..80 {
            let m = 0.5 * (a0 + a1);
            if f(m) > 0.0 {
                a1 = m;
            } else {
                a0 = m;
            }
        }
        Some(0.5 * (a0 + a1))
    }
}

/// The result of `attempt` at the smallest half-width found: on a ladder of factors of 4 from
/// 1e-12 to 1/4, then narrowed by bisection (geometric) between the last failure and the first
/// success.
fn smallest<T>(attempt: &mut impl FnMut(f64) -> Option<T>) -> Option<T> {
    let (mut w, mut bad) = (1e-12, 0.0);
    let mut proven = None;
    while w <= 0.25 {
        if let Some(r) = attempt(w) {
            proven = Some(r);
            break;
        }
        bad = w;
        w *= 4.0;
    }
    if proven.is_some() && bad > 0.0 {
        for _ in 0..6 {
            let m = (bad * w).sqrt();
            match attempt(m) {
                Some(r) => {
                    proven = Some(r);
                    w = m;
                }
                None => bad = m,
            }
        }
    }
    proven
}

#[cfg(test)]
mod tests;
