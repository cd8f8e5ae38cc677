//! The rim of a pole's cap (see the parent module) and the curve's crossings with it: each
//! piece of the rim with one parameter held, its zeros cut into boxes proven empty or proven
//! to hold exactly one (the parametric Krawczyk test), on the pieces of the face or, round a
//! corner where two strips meet across a glued edge, on the two stitched through the chart
//! across it.

use inari::Interval;

use super::Strip;
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::surface::Domain;
use crate::numeric::scalar::point;
use crate::pair::krawczyk::{krawczyk, BoxSurface, KrawczykResult, ParamBox};
use crate::shell::chart::{chart_map, ChartMap};
use crate::shell::edges::{side_coordinate, EdgeLink, PieceSide};
use crate::shell::sites::cut_box;

/// Most boxes the crossing search looks at per rim piece.
const MAX_BOXES: usize = 6000;

/// A piece of the cap's rim: on the strip `strip`, parameter `fixed` (0..4) held at `value`,
/// `free` over `range`.
pub(super) struct Rim {
    pub(super) strip: usize,
    pub(super) fixed: usize,
    pub(super) value: f64,
    pub(super) free: usize,
    pub(super) range: [f64; 2],
    /// For a piece round the corner where this strip's inner side meets the next strip's
    /// across a glued edge: that strip and the chart map onto its piece (the rim piece is in
    /// this strip's parameters, continued across the edge).
    pub(super) across: Option<(usize, ChartMap)>,
    /// The strips whose inner side the piece is part of.
    pub(super) inner_of: Vec<usize>,
}

/// The share of an inner side's range, at each glued end, given to the rim piece round that
/// corner (a crossing on the glued edge itself, the curve running along a knot line or seam,
/// lies inside that piece, not at the end of two).
const CORNER_SHARE: f64 = 1.0 / 64.0;

/// The rim of the cap of strips `strips` at width `w`: each strip's inner side (short of its
/// glued ends), a piece round each corner where two strips' inner sides meet across a glued
/// edge (`links`: another strip's end at the same end of the edge), and each strip end that is
/// not glued.
pub(super) fn rim(
    strips: &[Strip<'_>],
    surface: usize,
    w: f64,
    links: &[EdgeLink],
) -> Result<Vec<Rim>, &'static str> {
    // The strip glued to the end `here` of strip `k`, which of its ends, and the chart onto it.
    let glued = |k: usize, here: PieceSide| {
        let mine = &strips[k];
        let dk = mine.patch.domain();
        links.iter().filter(|l| l.from == here).find_map(|l| {
            // Only where the edge maps this strip's collapsed side and inner side exactly onto
            // the other's (either way round, any parametrisation): the two inner sides then
            // meet exactly on the edge (else they could miss each other by a rounding).
            let onto = |a: f64, b: f64, dn: &Domain| {
                let m = l.map_along(point(a), &dk, dn);
                m.inf() == b && m.sup() == b
            };
            let next = strips.iter().position(|st| {
                let dn = st.patch.domain();
                st.face == l.to.face
                    && st.piece == l.to.piece
                    && st.side / 2 != l.to.side / 2
                    && onto(
                        side_coordinate(&dk, mine.side).1,
                        side_coordinate(&dn, st.side).1,
                        &dn,
                    )
                    && onto(mine.inner(w), st.inner(w), &dn)
            })?;
            let map = chart_map(l, mine.patch, strips[next].patch)?;
            Some((next, l.to.side % 2, map))
        })
    };
    let mut out = Vec::new();
    for (k, st) in strips.iter().enumerate() {
        let d = st.patch.domain();
        let (across, along) = (st.across(), 1 - st.across());
        let mut range = if along == 0 { d.u } else { d.v };
        let share = CORNER_SHARE * (range[1] - range[0]);
        let side_value = side_coordinate(&d, st.side).1;
        let inner = st.inner(w);
        for e in 0..2 {
            let here = PieceSide {
                face: st.face,
                piece: st.piece,
                side: 2 * along + e,
            };
            let at = side_coordinate(&d, here.side).1;
            let Some((next, next_end, map)) = glued(k, here) else {
                out.push(Rim {
                    strip: k,
                    fixed: 2 * surface + along,
                    value: at,
                    free: 2 * surface + across,
                    range: [side_value.min(inner), side_value.max(inner)],
                    across: None,
                    inner_of: Vec::new(),
                });
                continue;
            };
            // Short of the corner; the piece round it belongs to the first of the two ends.
            // A little more than the share of the next piece its inner side leaves out, so
            // that the two overlap whatever the rounding of the chart.
            let reach = map
                .chart_domain()
                .map(|cd| 1.001 * CORNER_SHARE * cd[along].wid())
                .filter(|r| r.is_finite() && *r > 0.0);
            if e == 0 {
                range[0] = at + share;
            } else {
                range[1] = at - share;
            }
            if (k, e) < (next, next_end) {
                let reach = reach.ok_or("a corner of the cap's rim has no chart")?;
                let corner = if e == 0 {
                    [at - reach, at + share]
                } else {
                    [at - share, at + reach]
                };
                out.push(Rim {
                    strip: k,
                    fixed: 2 * surface + across,
                    value: inner,
                    free: 2 * surface + along,
                    range: corner,
                    across: Some((next, map)),
                    inner_of: vec![k, next],
                });
            }
        }
        out.push(Rim {
            strip: k,
            fixed: 2 * surface + across,
            value: inner,
            free: 2 * surface + along,
            range,
            across: None,
            inner_of: vec![k],
        });
    }
    Ok(out)
}

/// The crossings of the curve with the rim piece `r` (of `surfaces`, in the order P, Q) over
/// the leaves' hull `v` (other surface's coordinates), `apart` a further proof that a box
/// holds no zero (the two surfaces' images separated along a direction): `Ok(Some(enclosure))`
/// for exactly one, strictly inside the piece's range, `Ok(None)` for none.
pub(super) fn crossing(
    surfaces: [&dyn BoxSurface; 2],
    r: &Rim,
    other: usize,
    v: [Interval; 2],
    apart: &dyn Fn(&ParamBox) -> bool,
) -> Result<Option<ParamBox>, &'static str> {
    let mut region = [Interval::ENTIRE; 4];
    region[r.fixed] = point(r.value);
    region[r.free] = Interval::try_from((r.range[0], r.range[1])).map_err(|_| "a rim range")?;
    region[2 * other] = v[0];
    region[2 * other + 1] = v[1];
    match zeros(surfaces, region, r.fixed, apart)?.as_slice() {
        [] => Ok(None),
        [e] => {
            let f = e[r.free];
            if f.inf() > r.range[0] && f.sup() < r.range[1] {
                Ok(Some(*e))
            } else {
                Err("the curve crosses the cap's rim at a corner")
            }
        }
        _ => Err("the curve crosses a piece of the cap's rim more than once"),
    }
}

/// Where boxes are cut, as a fraction of their width: off the middle, so that a zero at a
/// symmetric parameter (the middle of a knot span) is not on the cut.
const CUT: f64 = 0.4638671875;

/// The distinct zeros of `P − Q` in `region` (coordinate `fixed` a point there), each
/// enclosed: the region is cut into boxes proven empty (disjoint images, or a Krawczyk image
/// disjoint from the box) or proven to hold exactly one zero, and two such boxes hold the same
/// zero when one's enclosure lies in the other or the Krawczyk test proves one zero in their
/// hull (a zero on the cut between them).
fn zeros(
    surfaces: [&dyn BoxSurface; 2],
    region: ParamBox,
    fixed: usize,
    apart: &dyn Fn(&ParamBox) -> bool,
) -> Result<Vec<ParamBox>, &'static str> {
    let [p, q] = surfaces;
    let mut todo = vec![region];
    let mut found: Vec<(ParamBox, ParamBox)> = Vec::new();
    let mut looked = 0;
    while let Some(y) = todo.pop() {
        looked += 1;
        if looked > MAX_BOXES {
            return Err("the crossings of the cap's rim could not be settled (too many boxes)");
        }
        let (fp, fq) = (p.box_first_order(y[0], y[1]), q.box_first_order(y[2], y[3]));
        if fp
            .iter()
            .chain(&fq)
            .flatten()
            .any(|x| !x.is_common_interval())
        {
            return Err("an image on the cap's rim is unbounded");
        }
        if boxes_disjoint(&fp[0], &fq[0]) || apart(&y) {
            continue;
        }
        match krawczyk(p, q, y, fixed, 30) {
            KrawczykResult::Proven { enclosure, .. } => found.push((y, enclosure)),
            KrawczykResult::NotProven(reason) if reason.contains("disjoint") => {}
            KrawczykResult::NotProven(_) => {
                // The free coordinate widest in model space (its partial's length times its
                // width).
                let partial = |k: usize| {
                    let f = if k < 2 { &fp } else { &fq };
                    let c = f[1 + k % 2];
                    (c[0].sqr() + c[1].sqr() + c[2].sqr()).sqrt().sup()
                };
                let k = (0..4)
                    .filter(|&k| k != fixed)
                    .max_by(|&a, &b| {
                        (y[a].wid() * partial(a)).total_cmp(&(y[b].wid() * partial(b)))
                    })
                    .unwrap_or((fixed + 1) % 4);
                let [a, b] = cut_box(&y, k, CUT)
                    .ok_or("the crossings of the cap's rim could not be settled")?;
                todo.push(a);
                todo.push(b);
            }
        }
    }
    let inside = |e: &ParamBox, y: &ParamBox| e.iter().zip(y).all(|(a, b)| a.subset(*b));
    let mut distinct: Vec<(ParamBox, ParamBox)> = Vec::new();
    'next: for (y, e) in found {
        for (dy, de) in distinct.iter_mut() {
            if inside(&e, dy) || inside(de, &y) {
                continue 'next;
            }
            if e.iter().zip(de.iter()).all(|(a, b)| !a.disjoint(*b)) {
                let hull: ParamBox = std::array::from_fn(|i| y[i].convex_hull(dy[i]));
                match krawczyk(p, q, hull, fixed, 30) {
                    KrawczykResult::Proven { enclosure, .. } => {
                        (*dy, *de) = (hull, enclosure);
                        continue 'next;
                    }
                    _ => return Err("two crossings of the cap's rim could not be told apart"),
                }
            }
        }
        distinct.push((y, e));
    }
    Ok(distinct.into_iter().map(|(_, e)| e).collect())
}
