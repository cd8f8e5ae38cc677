//! The chart of a corner: the parameters of one piece, continued across a shared edge onto
//! the piece beyond by an affine map of each parameter (kept along the edge, reversed when the
//! edge runs the other way, and continued past the side across it), evaluated in intervals.

use inari::Interval;

use super::edges::{along_range, side_coordinate, EdgeLink};
use crate::geometry::bezier::RationalBezierPatch;
use crate::numeric::scalar::point;

/// One parameter of a piece as an affine function of one chart coordinate: the chart segment
/// `[a, b]` onto the piece's `[c, e]` (`a ↦ c`, `b ↦ e`; `e < c` when the edge runs the other
/// way). The map is that exact real function; it is evaluated in intervals, so every image
/// encloses the exact one.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    /// The chart coordinate it follows (0 or 1).
    src: usize,
    a: f64,
    b: f64,
    c: f64,
    e: f64,
}

impl Segment {
    /// `c + (x − a)·(e − c)/(b − a)`, enclosed.
    fn forward(&self, x: Interval) -> Interval {
        point(self.c) + (x - point(self.a)) * self.factor()
    }

    /// `a + (y − c)·(b − a)/(e − c)`, enclosed.
    fn back(&self, y: Interval) -> Interval {
        let inverse = (point(self.b) - point(self.a)) / (point(self.e) - point(self.c));
        point(self.a) + (y - point(self.c)) * inverse
    }

    /// `(e − c)/(b − a)`: the derivative of the piece's parameter by the chart coordinate.
    fn factor(&self) -> Interval {
        (point(self.e) - point(self.c)) / (point(self.b) - point(self.a))
    }
}

/// The affine map from a corner's chart (the parameters of the piece on one side of a shared
/// edge) to the parameters of the piece across it: along the edge, the edge's normalised
/// parameter is the same on both sides (reversed when the link is); across it, the chart
/// continues past the side to a far bound `F`, and `[side, F]` maps onto the second piece's
/// range from its side inwards. On the edge the two pieces are the same rational Bézier curve
/// at the same normalised parameter ([`super::edges`]), so the stitched map is continuous, and
/// being affine the maps keep it continuously differentiable on each piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ChartMap {
    /// The second piece's `u` and `v`.
    coords: [Segment; 2],
}

impl ChartMap {
    /// The identity (no second piece to map: a pair whose pieces did not change).
    pub(super) fn identity() -> ChartMap {
        let seg = |src| Segment {
            src,
            a: 0.0,
            b: 1.0,
            c: 0.0,
            e: 1.0,
        };
        ChartMap {
            coords: [seg(0), seg(1)],
        }
    }

    /// The map to a piece two edges away, one coordinate through each of two maps: the
    /// second piece's parameter `i` is `second.coords[i]` applied to the first map's segment
    /// `via[i]` (its target range the source range of that segment, so that every end maps to
    /// an end exactly). `None` when the ranges do not meet so, or the two segments do not
    /// follow the chart's two coordinates.
    pub(super) fn composed(parts: [(&ChartMap, usize, &ChartMap, usize); 2]) -> Option<ChartMap> {
        let compose = |(m1, k1, m2, k2): (&ChartMap, usize, &ChartMap, usize)| {
            let (s1, s2) = (m1.coords.get(k1)?, m2.coords.get(k2)?);
            let end = |v: f64| {
                if v == s2.a {
                    Some(s2.c)
                } else if v == s2.b {
                    Some(s2.e)
                } else {
                    None
                }
            };
            (s2.src == k1).then_some(())?;
            Some(Segment {
                src: s1.src,
                a: s1.a,
                b: s1.b,
                c: end(s1.c)?,
                e: end(s1.e)?,
            })
        };
        let (c0, c1) = (compose(parts[0])?, compose(parts[1])?);
        let (i0, i1) = (parts[0].3, parts[1].3);
        if i0 == i1 || c0.src == c1.src {
            return None;
        }
        let mut coords = [c0, c1];
        if i0 == 1 {
            coords.swap(0, 1);
        }
        Some(ChartMap { coords })
    }

    /// Which of the second piece's parameters follows chart coordinate `src`, and the image
    /// of the chart value `v` there when `v` is an end of that segment's source range (then
    /// exactly an end of the piece's range).
    pub(super) fn end_image(&self, src: usize, v: f64) -> Option<(usize, f64)> {
        let (i, s) = self.coords.iter().enumerate().find(|(_, s)| s.src == src)?;
        if v == s.a {
            Some((i, s.c))
        } else if v == s.b {
            Some((i, s.e))
        } else {
            None
        }
    }

    /// The second piece's parameters of the chart box `x`.
    pub(super) fn forward(&self, x: [Interval; 2]) -> [Interval; 2] {
        self.coords.map(|s| s.forward(x[s.src]))
    }

    /// The chart box of the second piece's parameters `y`.
    pub(super) fn back(&self, y: [Interval; 2]) -> [Interval; 2] {
        let mut out = [Interval::ENTIRE; 2];
        for (k, s) in self.coords.iter().enumerate() {
            out[s.src] = s.back(y[k]);
        }
        out
    }

    /// The chart coordinate the second piece's parameter `i` follows, and the derivative of
    /// that parameter by it (the chain rule's factor, enclosed).
    pub(super) fn chain_factor(&self, i: usize) -> (usize, Interval) {
        let s = &self.coords[i];
        (s.src, s.factor())
    }

    /// The second piece's domain in the chart (exact: its ends are the segments' `a`, `b`).
    pub(super) fn chart_domain(&self) -> Option<[Interval; 2]> {
        let mut out = [Interval::ENTIRE; 2];
        for s in &self.coords {
            out[s.src] = Interval::try_from((s.a.min(s.b), s.a.max(s.b))).ok()?;
        }
        Some(out)
    }
}

/// The map taking the chart (the parameters of the piece `p_from` on `link.from`) to those of
/// the piece `p_to` on `link.to` across their shared edge ([`ChartMap`]): a knot line, a seam
/// (the same or the reverse way) or a face edge, between any two sides. The chart's far bound
/// across the edge is chosen (in `f64`: any bound on the right side would do, the map is
/// defined by it) so that the model moves about as fast per chart unit across the edge on both
/// sides, at the edge's middle: otherwise the stitched Jacobian, hulled over both pieces at the
/// edge, is as wide as their scales differ, and the Krawczyk tests there lose their contraction
/// (a face over `[0, 2] × [0, 4]` beside one over the unit square: corner boxes 1e-7 across
/// instead of 1e-12). `None` for a degenerate side.
pub(super) fn chart_map(
    link: &EdgeLink,
    p_from: &RationalBezierPatch,
    p_to: &RationalBezierPatch,
) -> Option<ChartMap> {
    let (from, to) = (&p_from.domain(), &p_to.domain());
    let (k1, v1) = side_coordinate(from, link.from.side);
    let (k2, v2) = side_coordinate(to, link.to.side);
    let [a0, a1] = along_range(from, link.from.side);
    let [b0, b1] = along_range(to, link.to.side);
    let (c, e) = if link.reversed { (b1, b0) } else { (b0, b1) };
    let along = Segment {
        src: 1 - k1,
        a: a0,
        b: a1,
        c,
        e,
    };
    // Across: from the side inwards on the second piece; past the side outwards in the chart.
    let inner = if link.to.side.is_multiple_of(2) {
        if k2 == 0 {
            to.u[1]
        } else {
            to.v[1]
        }
    } else if k2 == 0 {
        to.u[0]
    } else {
        to.v[0]
    };
    let width = (inner - v2).abs();
    let outwards = if link.from.side.is_multiple_of(2) {
        -1.0
    } else {
        1.0
    };
    // Model speed across the edge per parameter unit, at the edge's middle, on each piece.
    let speed = |p: &RationalBezierPatch, k: usize, value: f64, range: [f64; 2]| {
        let m = 0.5 * (range[0] + range[1]);
        let (u, v) = if k == 0 { (value, m) } else { (m, value) };
        let d = p.derivs_f64(u, v);
        let t = if k == 0 { d.su } else { d.sv };
        t.iter().map(|x| x * x).sum::<f64>().sqrt()
    };
    let (g1, g2) = (
        speed(p_from, k1, v1, [a0, a1]),
        speed(p_to, k2, v2, [b0, b1]),
    );
    let matched = width * g2 / g1;
    let reach = if matched.is_finite() && matched > 0.0 {
        matched
    } else {
        width
    };
    let far = v1 + outwards * reach;
    let across = Segment {
        src: k1,
        a: v1,
        b: far,
        c: v2,
        e: inner,
    };
    let ok = |s: &Segment| {
        s.a != s.b && s.c != s.e && [s.a, s.b, s.c, s.e].iter().all(|x| x.is_finite())
    };
    if !(ok(&along) && ok(&across)) {
        return None;
    }
    let mut coords = [along, across];
    if k2 == 0 {
        coords.swap(0, 1);
    }
    // `coords[i]` gives the second piece's parameter i: along is its 1 − k2, across its k2.
    Some(ChartMap { coords })
}
