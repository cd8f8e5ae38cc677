//! Joins through a pole, proven on a cap round it.
//!
//! A curve through the pole `X` of a shell (a side of some of its pieces that the patch maps to
//! `X`: a sphere's pole, the end of any surface of revolution meeting its axis) comes back as
//! two branches, one in each piece it arrives and leaves by, each ending unproven a little short
//! of the pole: a chain cannot reach it, because every point of the collapsed side is a
//! parameter of `X` and the parameters degenerate there. [`prove`] proves that the two branches
//! are one curve through (or past) the pole, and encloses the arc between their chains' ends.
//!
//! **The cap.** `F` is the part of the shell within a normalised width `w` of the collapsed
//! sides of all its pieces at `X`, in every face that has one there (each piece's *strip*; a
//! sphere split into faces along meridians has its poles on every face): strips of
//! neighbouring pieces meet on their shared knot line, seam or face edge, so `F` is a disc
//! round `X` on the surface, whose rim is made of the strips' inner sides and of those strip
//! ends that are not glued to another strip (a piece of a surface of revolution of less than a
//! full turn, or an edge that maps neither strip's sides exactly onto the other's). `V` covers every part of the
//! other surface's piece whose image meets `F`'s bounding box (quadtree leaves, all strictly
//! inside that piece).
//!
//! 1. **No loop, each arc monotone.** With `d = n₀ × m₀` (`n₀` the face's normal at `X`, `m₀`
//!    the other surface's near it), `⟨Ñ × N_Q, d⟩` excludes zero on every strip piece and leaf
//!    whose images meet, `Ñ` the positive multiple of the face's normal that has a limit at the
//!    pole (`geometry::pole`). So along every arc of the curve in `F` (off `X`) the tangent
//!    never turns orthogonal to `d`: `⟨x, d⟩` is strictly monotone on it and there is no closed
//!    loop. Every component of the curve in `F` is then an arc with two ends on the rim, or
//!    with one end on the rim and one at `X`.
//! 2. **Two crossings.** On each piece of the rim, with that coordinate held, the crossings with
//!    the other surface over `V` are cut into boxes proven empty or proven to hold one zero
//!    ([`Zero`]): exactly two in all, one on the inner side of each branch's strip, neither
//!    at a corner of the rim. So the curve in `F` is one arc, possibly through `X`, between
//!    those two points.
//! 3. **The branches cross there.** Each branch's chain starts outside its strip and ends
//!    inside it (its unproven end at the pole), and its boxes from that end out to the first
//!    one wholly outside lie within its piece's side range: its curve crosses the inner side of
//!    its own strip, so at the crossing found there. Both chains' curves are parts of the one
//!    arc, and the true arc between their ends lies in `F`.
//! 4. **Where the arc lies.** The strip pieces' control points bound `⟨x, n₀⟩` over `F`, the
//!    leaves' bound `⟨x, m₀⟩` (two thin slabs: the surfaces are nearly their tangent planes on
//!    so small a cap), and by (1) `⟨x, d⟩` on the arc between the ends lies between its values
//!    on the two end boxes; the three bounds, solved for `x` in interval arithmetic, give the
//!    model box [`PoleProof::xyz`] holding the arc.
//!
//! Branches of the pairs of the strips' pieces whose marched points all lie in a strip are
//! slivers of the same arc: the join absorbs them ([`absorbed`]).

mod rim;

use std::collections::HashMap;

use inari::Interval;

use super::corner::stitched;
use super::edges::{side_coordinate, EdgeLink};
use super::sites::{patches, EndSite};
use super::{Face, PieceIntersection};
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::piece::Piece;
use crate::geometry::pole::collapsed_normal;
use crate::numeric::scalar::{meet, point};
use crate::numeric::vec3::{cross, dot};
use crate::pair::krawczyk::{BoxSurface, ParamBox};
use rim::{crossing, rim};

/// Strip widths tried, smallest first (normalised, exact powers of two).
const WIDTHS: [f64; 3] = [1.0 / 65536.0, 1.0 / 4096.0, 1.0 / 256.0];
/// Pieces of a strip along its side, for the normals and the slab bounds.
const ALONG: usize = 16;
/// Widest piece of a strip across its side (normalised).
const ACROSS: f64 = 1.0 / 32.0;
/// Widest strip tried to settle the search's undecided regions round a pole (normalised).
const SETTLE_MOST: f64 = 0.5;
/// Deepest level of the other surface's quadtree.
const MAX_LEVEL: usize = 48;
/// Most leaves kept.
const MAX_LEAVES: usize = 512;

/// A proven join through a pole.
pub(super) struct PoleProof {
    /// Every point of the true curve between the two branches' ends lies in this model box.
    pub(super) xyz: [Interval; 3],
    /// The pole's surface (0 or 1) and strips (face, piece, collapsed side).
    surface: usize,
    strips: Vec<(usize, usize, usize)>,
    /// The other surface's face and piece.
    other: [usize; 2],
    /// The strips' normalised width (the widest proven: the box may come from a narrower
    /// cap, which lies in this one).
    width: f64,
}

/// One piece of a face at the pole: the strip along its collapsed side `side`.
struct Strip<'a> {
    face: usize,
    piece: usize,
    patch: &'a RationalBezierPatch,
    side: usize,
}

impl Strip<'_> {
    /// The parameter index (0: u, 1: v) across the side.
    fn across(&self) -> usize {
        self.side / 2
    }

    /// The declared value of the strip's inner side at normalised width `w`.
    fn inner(&self, w: f64) -> f64 {
        let d = self.patch.domain();
        let r = if self.across() == 0 { d.u } else { d.v };
        if self.side.is_multiple_of(2) {
            r[0] + w * (r[1] - r[0])
        } else {
            r[1] - w * (r[1] - r[0])
        }
    }

    /// Whether the interval `x` of the across coordinate lies strictly between the side and
    /// the inner value `at` (`inside`), or strictly beyond `at` (`!inside`).
    fn holds(&self, x: Interval, at: f64, inside: bool) -> bool {
        let lower = self.side.is_multiple_of(2);
        match (lower, inside) {
            (true, true) => x.sup() < at,
            (true, false) => x.inf() > at,
            (false, true) => x.inf() > at,
            (false, false) => x.sup() < at,
        }
    }

    /// The strip's pieces, covering it to a little past its inner side (`w·(1 + 2⁻¹⁰)`, so
    /// whatever the rounding of the inner value), with enclosures of positive multiples of the
    /// normal: [`ALONG`] pieces along the side, and across it one piece touching the side (the
    /// pole-scaled normal, `geometry::pole`) and pieces at most [`ACROSS`] wide beyond (the
    /// normal itself, away from the pole).
    fn pieces(&self, w: f64, x: [f64; 3]) -> Option<Vec<(Piece, [Interval; 3])>> {
        let cover = (w + w / 1024.0).min(1.0);
        let touch = cover.min(ACROSS);
        let beyond = ((cover - touch) / ACROSS).ceil() as usize;
        let mut cuts = vec![0.0, touch];
        cuts.extend((1..=beyond).map(|k| touch + (cover - touch) * k as f64 / beyond as f64));
        let dom = self.patch.domain();
        let mut out = Vec::with_capacity(ALONG * cuts.len());
        for k in 0..ALONG {
            let along = [k as f64 / ALONG as f64, (k + 1) as f64 / ALONG as f64];
            for (c, span) in cuts.windows(2).enumerate() {
                let across = if self.side.is_multiple_of(2) {
                    [span[0], span[1]]
                } else {
                    [1.0 - span[1], 1.0 - span[0]]
                };
                let (s, r) = if self.across() == 0 {
                    (across, along)
                } else {
                    (along, across)
                };
                let piece = Piece::over(self.patch, s, r)?;
                let n = if c == 0 {
                    collapsed_normal(&piece, self.side, x)?
                } else {
                    let origin = piece.bounds().map(|c| c.mid());
                    let [Some(su), Some(sv)] = piece.partials(&dom, None, &origin, 0.0)? else {
                        return None;
                    };
                    cross(&su, &sv)
                };
                out.push((piece, n));
            }
        }
        Some(out)
    }
}

/// The hull of the declared parameter boxes of the parts of `other` (the leaves, cut in four
/// until no wider than `target`) whose images meet `target`; `None` if none does (no point of
/// `other` lies in `target`).
fn near_parameters(
    other: &RationalBezierPatch,
    leaves: &[Leaf],
    target: &[Interval; 3],
) -> Option<[Interval; 2]> {
    let size = crate::shell::corner::diameter(target);
    let dom = other.domain();
    let mut todo: Vec<([f64; 2], [f64; 2], usize)> =
        leaves.iter().map(|l| (l.piece.s, l.piece.r, 0)).collect();
    let mut hull: Option<[Interval; 2]> = None;
    while let Some((s, r, level)) = todo.pop() {
        let piece = Piece::over(other, s, r)?;
        if boxes_disjoint(&piece.bounds(), target) {
            continue;
        }
        if level >= 24 || crate::shell::corner::diameter(&piece.bounds()) <= size {
            let d = piece.declared(&dom, 0.0);
            hull = Some(hull.map_or(d, |h| [h[0].convex_hull(d[0]), h[1].convex_hull(d[1])]));
            continue;
        }
        for (ss, rr) in quarters(s, r) {
            todo.push((ss, rr, level + 1));
        }
    }
    hull
}

/// The piece of `patch` over the declared box `y` (either range may be a point): over the
/// normalised box round it, widened by a part in 2³⁰ of its width and at least 2⁻⁶⁰ or an ulp
/// (its control points' hull holds the patch over `y`). `None` if the box leaves the domain.
fn thin_piece(patch: &RationalBezierPatch, y: [Interval; 2]) -> Option<Piece> {
    let d = patch.domain();
    let norm = |x: Interval, r: [f64; 2]| -> Option<[f64; 2]> {
        let t = (x - point(r[0])) / (point(r[1]) - point(r[0]));
        let pad = (t.wid() / 1073741824.0).max(1.0 / 1152921504606846976.0);
        // At least an ulp each way: next to 1 a pad of 2⁻⁶⁰ is lost to the rounding, and a
        // point range would give no piece.
        let lo = (t.inf() - pad).min(t.inf().next_down()).max(0.0);
        let hi = (t.sup() + pad).max(t.sup().next_up()).min(1.0);
        (lo < hi).then_some([lo, hi])
    };
    Piece::over(patch, norm(y[0], d.u)?, norm(y[1], d.v)?)
}

/// A leaf of the other surface's quadtree: its piece, declared box and normal enclosure.
struct Leaf {
    piece: Piece,
    declared: [Interval; 2],
    normal: [Interval; 3],
}

/// The leaves of `other` whose images meet `cap`, each strictly inside `other`'s domain.
fn leaves(other: &RationalBezierPatch, cap: &[Interval; 3]) -> Result<Vec<Leaf>, &'static str> {
    let size = crate::shell::corner::diameter(cap);
    let dom = other.domain();
    let mut todo = vec![([0.0, 1.0], [0.0, 1.0], 0usize)];
    let mut out = Vec::new();
    while let Some((s, r, level)) = todo.pop() {
        let piece = Piece::over(other, s, r).ok_or("a quadtree box of the other piece")?;
        if boxes_disjoint(&piece.bounds(), cap) {
            continue;
        }
        let touches = s[0] == 0.0 || s[1] == 1.0 || r[0] == 0.0 || r[1] == 1.0;
        let small = crate::shell::corner::diameter(&piece.bounds()) <= 4.0 * size;
        if (small && !touches) || level >= MAX_LEVEL {
            if touches {
                return Err("the other surface's piece ends within the pole's cap");
            }
            let declared = piece.declared(&dom, 0.0);
            let origin = piece.bounds().map(|c| c.mid());
            let [Some(su), Some(sv)] = piece
                .partials(&dom, None, &origin, 0.0)
                .ok_or("the other piece's weights are not positive")?
            else {
                return Err("the other piece is degenerate");
            };
            out.push(Leaf {
                normal: cross(&su, &sv),
                piece,
                declared,
            });
            if out.len() > MAX_LEAVES {
                return Err("the other surface meets the pole's cap in too many places");
            }
            continue;
        }
        for (ss, rr) in quarters(s, r) {
            todo.push((ss, rr, level + 1));
        }
    }
    if out.is_empty() {
        return Err("the other surface does not come near the pole");
    }
    Ok(out)
}

/// The four quarters of the normalised box `s × r` (halved exactly: dyadic ends stay dyadic).
fn quarters(s: [f64; 2], r: [f64; 2]) -> [([f64; 2], [f64; 2]); 4] {
    let (sm, rm) = (0.5 * (s[0] + s[1]), 0.5 * (r[0] + r[1]));
    [
        ([s[0], sm], [r[0], rm]),
        ([sm, s[1]], [r[0], rm]),
        ([s[0], sm], [rm, r[1]]),
        ([sm, s[1]], [rm, r[1]]),
    ]
}

/// The unit vector along `x` (`None` if it is zero or not finite).
fn unit(x: [f64; 3]) -> Option<[f64; 3]> {
    let n = x.iter().map(|c| c * c).sum::<f64>().sqrt();
    (n > 0.0 && n.is_finite()).then(|| x.map(|c| c / n))
}

/// How far (relative to the side's range) a chain's boxes may reach past a glued end of its
/// strip: the rounding of a chain along the knot line or seam there.
const ALONG_SLACK: f64 = 1e-9;

/// The certified end of `c` at the marched end point of `site`, when it is unproven at a pole:
/// its box, and whether it is the chain's first end.
fn pole_end(site: &EndSite<'_>, c: &CertifiedBranch) -> Option<([Interval; 4], bool)> {
    let target = [
        site.point.p[0],
        site.point.p[1],
        site.point.q[0],
        site.point.q[1],
    ];
    let distance = |y: &[Interval; 4]| {
        (0..4)
            .map(|i| {
                (y[i].inf() - target[i])
                    .max(target[i] - y[i].sup())
                    .max(0.0)
            })
            .fold(0.0, f64::max)
    };
    let ends: Vec<(usize, [Interval; 4])> = c
        .ends
        .iter()
        .enumerate()
        .filter_map(|(k, e)| match e {
            CertifiedEnd::Unproven { reason, near } if reason.contains("pole") => Some((k, *near)),
            _ => None,
        })
        .collect();
    let (k, near) = ends
        .into_iter()
        .min_by(|a, b| distance(&a.1).total_cmp(&distance(&b.1)))?;
    Some((near, k == 0))
}

/// Checks step 3 of the module documentation for one branch: its chain ends inside its strip
/// (at `near`) and crosses the strip's inner side within the piece's side range (past an end
/// `glued` to the next strip, where a rim piece runs on round the corner, by rounding only: a
/// chain along the knot line there). Returns the model box of its end.
fn chain_crosses(
    site: &EndSite<'_>,
    st: &Strip<'_>,
    w: f64,
    glued: [bool; 2],
    surface: usize,
    pair: [&RationalBezierPatch; 2],
) -> Result<[Interval; 3], &'static str> {
    let c = site
        .certificate
        .ok_or("a branch at the pole is not certified")?;
    let (near, first) = pole_end(site, c).ok_or("a branch does not end unproven at the pole")?;
    let at = st.inner(w);
    let (across, along) = (2 * surface + st.across(), 2 * surface + 1 - st.across());
    if !st.holds(near[across], at, true) {
        return Err("a branch's chain ends outside the pole's cap");
    }
    let d = st.patch.domain();
    let mut along_range = if st.across() == 0 { d.v } else { d.u };
    let slack = ALONG_SLACK * (along_range[1] - along_range[0]);
    if glued[0] {
        along_range[0] -= slack;
    }
    if glued[1] {
        along_range[1] += slack;
    }
    let walk: Box<dyn Iterator<Item = _>> = if first {
        Box::new(c.boxes.iter())
    } else {
        Box::new(c.boxes.iter().rev())
    };
    let mut outside = false;
    for bx in walk {
        let y = bx.params();
        if st.holds(y[across], at, false) {
            outside = true;
            break;
        }
        if !(y[along].inf() >= along_range[0] && y[along].sup() <= along_range[1]) {
            return Err("a branch's chain leaves its piece within the pole's cap");
        }
    }
    if !outside {
        return Err("a branch's chain lies wholly within the pole's cap");
    }
    let xp = pair[0].enclose(near[0], near[1]);
    let xq = pair[1].enclose(near[2], near[3]);
    Ok(std::array::from_fn(|i| meet(xp[i], xq[i])))
}

/// Proves the join of `s1` and `s2` (two ends on sides of one shell collapsed to the same pole,
/// against the same piece of the other surface) through the pole; see the module
/// documentation. `links` are the shared edges of the pole's shell.
pub(super) fn prove(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    s1: &EndSite<'_>,
    s2: &EndSite<'_>,
    links: &[EdgeLink],
) -> Result<PoleProof, &'static str> {
    let surface = s1.surface;
    let pair = patches(a, b, &pairs[s1.pair]);
    let x = pair[surface].collapsed_sides()[s1.side.side].ok_or("no pole on the side")?;
    // Every piece of every face of the shell with a side collapsed to the pole.
    let strips: Vec<Strip<'_>> = [a, b][surface]
        .iter()
        .enumerate()
        .flat_map(|(f, face)| {
            face.pieces().iter().enumerate().flat_map(move |(k, p)| {
                (0..4)
                    .filter(move |&sd| p.collapsed_sides()[sd] == Some(x))
                    .map(move |side| Strip {
                        face: f,
                        piece: k,
                        patch: p,
                        side,
                    })
            })
        })
        .collect();
    let index = |s: &EndSite<'_>| {
        strips.iter().position(|st| {
            st.face == s.side.face && st.piece == s.side.piece && st.side == s.side.side
        })
    };
    let (Some(k1), Some(k2)) = (index(s1), index(s2)) else {
        return Err("an end is not on a side at the pole");
    };
    if k1 == k2 {
        return Err("both branches are in one piece at the pole");
    }
    let mut last = "no cap round the pole";
    for w in WIDTHS {
        match prove_at(a, b, pairs, [s1, s2], [k1, k2], &strips, x, w, links) {
            Ok(xyz) => {
                let other_pair = &pairs[s1.pair];
                let mut proof = PoleProof {
                    xyz,
                    surface,
                    strips: strips.iter().map(|s| (s.face, s.piece, s.side)).collect(),
                    other: [
                        other_pair.faces[1 - surface],
                        other_pair.pieces[1 - surface],
                    ],
                    width: w,
                };
                // A wider cap, when the search left regions round the pole that this one
                // does not hold: the proof at that width covers them (its box is not kept).
                // Just wider than they reach, else the next widths tried that reach as far.
                let wanted = undecided_reach(&proof, &strips, pairs);
                let wider = (wanted * 1.125).min(SETTLE_MOST);
                let tries = (wider > wanted)
                    .then_some(wider)
                    .into_iter()
                    .chain(WIDTHS.into_iter().filter(|&c| c > wanted));
                if wanted >= w {
                    for c in tries {
                        if prove_at(a, b, pairs, [s1, s2], [k1, k2], &strips, x, c, links).is_ok() {
                            proof.width = c;
                            break;
                        }
                    }
                }
                return Ok(proof);
            }
            Err(e) => last = e,
        }
    }
    Err(last)
}

/// [`prove`] with strips of normalised width `w`: the model box of the arc between the ends.
#[allow(clippy::too_many_arguments)]
fn prove_at(
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    sites: [&EndSite<'_>; 2],
    at: [usize; 2],
    strips: &[Strip<'_>],
    x: [f64; 3],
    w: f64,
    links: &[EdgeLink],
) -> Result<[Interval; 3], &'static str> {
    let surface = sites[0].surface;
    let other_surface = 1 - surface;
    let other = patches(a, b, &pairs[sites[0].pair])[other_surface];
    // The strips' pieces and the cap's bounding box.
    let mut cap: Option<[Interval; 3]> = None;
    let mut pieces = Vec::new();
    for st in strips {
        let ps = st
            .pieces(w, x)
            .ok_or("a strip's normal cannot be enclosed")?;
        for (p, _) in &ps {
            let bd = p.bounds();
            cap = Some(cap.map_or(bd, |c| std::array::from_fn(|i| c[i].convex_hull(bd[i]))));
        }
        pieces.push(ps);
    }
    let cap = cap.ok_or("no strips")?;
    let leaves = leaves(other, &cap)?;
    // 1. A direction along which the curve is monotone in the cap.
    let n0 = unit(pieces[at[0]][0].1.map(|c| c.mid())).ok_or("no normal at the pole")?;
    let m0 = unit(leaves[0].normal.map(|c| c.mid())).ok_or("no normal of the other surface")?;
    let d = unit(cross(&n0, &m0)).ok_or("the surfaces touch at the pole")?;
    let dp = d.map(point);
    for (piece, n) in pieces.iter().flatten() {
        for leaf in &leaves {
            if boxes_disjoint(&piece.bounds(), &leaf.piece.bounds()) {
                continue;
            }
            if dot(&cross(n, &leaf.normal), &dp).contains(0.0) {
                return Err("the curve is not monotone in the pole's cap");
            }
        }
    }
    // 2. Exactly two crossings of the rim, on the branches' strips' inner sides.
    let hull = leaves.iter().fold(leaves[0].declared, |h, l| {
        [
            h[0].convex_hull(l.declared[0]),
            h[1].convex_hull(l.declared[1]),
        ]
    });
    let rims = rim(strips, surface, w, links)?;
    let found = rim_crossings(strips, &rims, surface, other, &leaves, hull, &m0)?;
    let on = |c: &Vec<usize>, k: usize| c.contains(&at[k]);
    let matched = found.len() == 2
        && ((on(&found[0], 0) && on(&found[1], 1)) || (on(&found[0], 1) && on(&found[1], 0)));
    if !matched {
        return Err("the curve does not cross the pole's cap exactly where the branches enter");
    }
    // 3. Each branch crosses its strip's inner side.
    let mut ends = Vec::with_capacity(2);
    for (site, &k) in sites.iter().zip(&at) {
        // An end of the strip with no rim piece on it is glued to the next strip.
        let glued = [0, 1].map(|e| {
            let end =
                side_coordinate(&strips[k].patch.domain(), 2 * (1 - strips[k].across()) + e).1;
            !rims
                .iter()
                .any(|r| r.strip == k && r.inner_of.is_empty() && r.value == end)
        });
        ends.push(chain_crosses(
            site,
            &strips[k],
            w,
            glued,
            surface,
            patches(a, b, &pairs[site.pair]),
        )?);
    }
    // 4. The slabs and the range along d.
    let along_n = hull_all(pieces.iter().flatten().map(|(p, _)| p.range_along(&n0)))
        .ok_or("a strip's weights are not positive")?;
    let along_m = hull_all(leaves.iter().map(|l| l.piece.range_along(&m0)))
        .ok_or("a leaf's weights are not positive")?;
    let along_d = ends
        .iter()
        .fold(Interval::EMPTY, |h, e| h.convex_hull(dot(e, &dp)));
    let xyz = solve_frame([n0, m0, d], [along_n, along_m, along_d]);
    Ok(std::array::from_fn(|i| meet(xyz[i], cap[i])))
}

/// The hull of the intervals, `None` if one is missing.
fn hull_all(xs: impl Iterator<Item = Option<Interval>>) -> Option<Interval> {
    let mut xs = xs;
    xs.try_fold(Interval::EMPTY, |h, x| Some(h.convex_hull(x?)))
}

/// Step 2 of the module documentation: the crossings of the curve with the pieces of the rim
/// `rims` (the other surface `other`, its leaves and their hull `hull`, `m0` its normal near
/// the pole); per crossing, the strips whose inner side it lies on.
fn rim_crossings(
    strips: &[Strip<'_>],
    rims: &[rim::Rim],
    surface: usize,
    other: &RationalBezierPatch,
    leaves: &[Leaf],
    hull: [Interval; 2],
    m0: &[f64; 3],
) -> Result<Vec<Vec<usize>>, &'static str> {
    let other_surface = 1 - surface;
    let mut found: Vec<Vec<usize>> = Vec::new();
    for r in rims {
        let st = &strips[r.strip];
        let stitched = r
            .across
            .map(|(next, map)| stitched(st.patch, strips[next].patch, map));
        let own: &dyn BoxSurface = match &stitched {
            Some(s) => s,
            None => st.patch,
        };
        let mut pair: [&dyn BoxSurface; 2] = [own, other];
        if surface == 1 {
            pair.swap(0, 1);
        }
        // Along the other surface's normal near the pole, the two images of a box (hulls of
        // their pieces' control points: a plain evaluation next to the pole is as wide as the
        // net, and the axis-aligned boxes of a tilted surface overlap far from it).
        let apart = |y: &ParamBox| -> bool {
            if r.across.is_some() {
                return false;
            }
            let o = 2 * other_surface;
            let mine = 2 * surface;
            let (Some(pp), Some(po)) = (
                thin_piece(st.patch, [y[mine], y[mine + 1]]),
                thin_piece(other, [y[o], y[o + 1]]),
            ) else {
                return false;
            };
            match (pp.range_along(m0), po.range_along(m0)) {
                (Some(x), Some(z)) => x.disjoint(z),
                _ => false,
            }
        };
        // The other surface's parameters near this piece of the rim (all of the leaves' hull
        // round a corner).
        let near = if r.across.is_some() {
            Some(hull)
        } else {
            let mut y = [Interval::ENTIRE; 4];
            y[r.fixed] = point(r.value);
            y[r.free] = Interval::try_from((r.range[0], r.range[1])).map_err(|_| "a rim range")?;
            let mine = 2 * surface;
            match thin_piece(st.patch, [y[mine], y[mine + 1]]) {
                Some(piece) => near_parameters(other, leaves, &piece.bounds()),
                None => Some(hull),
            }
        };
        let Some(near) = near else {
            continue;
        };
        if crossing(pair, r, other_surface, near, &apart)?.is_some() {
            found.push(r.inner_of.clone());
        }
    }
    Ok(found)
}

/// Every `x` with `⟨x, rows[i]⟩ ∈ values[i]` (three independent rows), enclosed: by Cramer's
/// rule in interval arithmetic.
fn solve_frame(rows: [[f64; 3]; 3], values: [Interval; 3]) -> [Interval; 3] {
    let r = rows.map(|row| row.map(point));
    let det = dot(&r[0], &cross(&r[1], &r[2]));
    let cols = [
        cross(&r[1], &r[2]),
        cross(&r[2], &r[0]),
        cross(&r[0], &r[1]),
    ];
    std::array::from_fn(|i| (0..3).fold(point(0.0), |acc, k| acc + values[k] * cols[k][i]) / det)
}

/// The pairs of the proof's strips' pieces against its other piece, each with the strip.
fn strip_pairs<'a>(
    proof: &PoleProof,
    a: &'a [Face],
    b: &'a [Face],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
) -> Vec<(usize, Strip<'a>)> {
    let s = proof.surface;
    let mut out = Vec::new();
    for &(face, piece, side) in &proof.strips {
        let (mut faces, mut pcs) = ([0; 2], [0; 2]);
        faces[s] = face;
        pcs[s] = piece;
        faces[1 - s] = proof.other[0];
        pcs[1 - s] = proof.other[1];
        if let Some(&k) = by_pair.get(&(faces, pcs)) {
            let patch = &[a, b][s][face].pieces()[piece];
            out.push((
                k,
                Strip {
                    face,
                    piece,
                    patch,
                    side,
                },
            ));
        }
    }
    out
}

/// The largest normalised distance from the pole's side reached by an undecided search region
/// of the pairs of the proof's strips' pieces against its other piece.
fn undecided_reach(proof: &PoleProof, strips: &[Strip<'_>], pairs: &[PieceIntersection]) -> f64 {
    let s = proof.surface;
    let mut most = 0.0f64;
    for pi in pairs {
        let theirs = [pi.faces[1 - s], pi.pieces[1 - s]] == proof.other;
        let Some(st) = strips
            .iter()
            .find(|st| theirs && st.face == pi.faces[s] && st.piece == pi.pieces[s])
        else {
            continue;
        };
        let d = st.patch.domain();
        let r = if st.across() == 0 { d.u } else { d.v };
        for reg in pi.result.undecided_regions() {
            let x = (if s == 0 { reg.p } else { reg.q })[st.across()];
            let reach = if st.side.is_multiple_of(2) {
                (x[1] - r[0]) / (r[1] - r[0])
            } else {
                (r[1] - x[0]) / (r[1] - r[0])
            };
            most = most.max(reach);
        }
    }
    most
}

/// The undecided search regions (`(pair, index in its list)`) of the pairs of the proof's
/// strips' pieces against its other piece whose box on the pole's surface lies strictly
/// inside the strip (across the side: between the side and the inner value). Every curve
/// point with parameters there lies in the cap, where the proof shows the curve to be the
/// one arc the join covers: the region hides nothing. (The boundary search cannot settle a
/// collapsed side whose pole lies on the other surface: the side maps to a curve point.)
pub(super) fn settled(
    proof: &PoleProof,
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
) -> Vec<(usize, usize)> {
    let s = proof.surface;
    let mut out = Vec::new();
    for (k, st) in strip_pairs(proof, a, b, by_pair) {
        let at = st.inner(proof.width);
        for (i, r) in pairs[k].result.undecided_regions().iter().enumerate() {
            let bx = if s == 0 { r.p } else { r.q };
            let x = bx[st.across()];
            let Ok(x) = Interval::try_from((x[0], x[1])) else {
                continue;
            };
            if st.holds(x, at, true) {
                out.push((k, i));
            }
        }
    }
    out
}

/// The branches of the pairs of the proof's strips' pieces (against its other piece) whose
/// marched points all lie strictly inside a strip, except `keep`: slivers of the arc the join
/// proves. Shell-wide branch numbers.
pub(super) fn absorbed(
    proof: &PoleProof,
    a: &[Face],
    b: &[Face],
    pairs: &[PieceIntersection],
    by_pair: &HashMap<([usize; 2], [usize; 2]), usize>,
    first_branch: &[usize],
    keep: [usize; 2],
) -> Vec<usize> {
    let s = proof.surface;
    let mut out = Vec::new();
    for (k, st) in strip_pairs(proof, a, b, by_pair) {
        let at = st.inner(proof.width);
        for (i, br) in pairs[k].result.branches.iter().enumerate() {
            let g = first_branch[k] + i;
            let pts = &br.marched.points;
            let inside = pts.iter().all(|c| {
                let y = if s == 0 { c.p } else { c.q };
                st.holds(point(y[st.across()]), at, true)
            });
            if !keep.contains(&g) && !pts.is_empty() && inside {
                out.push(g);
            }
        }
    }
    out
}
