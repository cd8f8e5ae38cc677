//! Rigorous bounds of rational Bézier patches over parameter boxes.
//!
//! Two independent enclosures, both computed entirely in [`Interval`] arithmetic:
//!
//! * **convex hull of the sub-patch net**: the control net of the sub-patch over the box is
//!   obtained by blossoming (de Casteljau with a different parameter on each level) in homogeneous
//!   coordinates, with interval parameters enclosing the exact normalised box corners; because
//!   every weight is positive, each surface point is a convex combination of the projected
//!   control points, so the bounding box of the projected interval net encloses the sub-patch;
//! * **naive interval evaluation** of the rational form over the box.
//!
//! [`RationalBezierPatch::enclose`] returns their intersection.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::{PatchDerivs, RationalBezierPatch};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::point;
use inari::Interval;

/// Reusable buffers of [`restrict_curve`] (no allocation per call once they have grown).
#[derive(Debug, Default, Clone)]
pub(crate) struct RestrictBuffers {
    /// The de Casteljau triangle at `a`, level `l` at `l·(deg + 1)`.
    triangle: Vec<[Interval; 4]>,
    /// The points of one output's levels at `b`.
    pts: Vec<[Interval; 4]>,
}

/// Control points of the polynomial curve with control points `net` (homogeneous, degree
/// `net.len() − 1`) restricted to the normalised parameter range `[a, b]`, where `a`, `b` are
/// intervals enclosing the exact range ends. Rigorous: each output encloses the exact control
/// point `blossom(a, …, a, b, …, b)`. Written to `out[..net.len()]` (`out` at least that long).
#[inline]
pub(crate) fn restrict_curve(
    net: &[[Interval; 4]],
    a: Interval,
    b: Interval,
    buf: &mut RestrictBuffers,
    out: &mut [[Interval; 4]],
) {
    // One de Casteljau level at parameter t over the first `len` points: (1 − t)·Pᵢ + t·Pᵢ₊₁,
    // exact for t = 0 and t = 1, so restricting to the whole range reproduces the net without
    // rounding.
    let lerp = |pts: &mut [[Interval; 4]], len: usize, t: Interval| {
        let one_minus = point(1.0) - t;
        for i in 0..len - 1 {
            // The next point by reference (copied by value it costs a store-forwarding stall
            // per step, see `Piece::split`).
            let (here, next) = pts.split_at_mut(i + 1);
            for (x, y) in here[i].iter_mut().zip(&next[0]) {
                *x = one_minus * *x + t * *y;
            }
        }
    };
    let w = net.len();
    let deg = w - 1;
    let RestrictBuffers { triangle, pts } = buf;
    triangle.clear();
    triangle.extend_from_slice(net);
    for l in 1..=deg {
        // Level l: level l − 1 (deg − l + 2 points) with one de Casteljau step at a; it holds
        // the blossoms (a^l, ·) of the net.
        let from = (l - 1) * w;
        triangle.extend_from_within(from..from + w);
        lerp(&mut triangle[l * w..], deg - l + 2, a);
    }
    // Control point k is blossom(a^(deg−k), b^k): k further levels at b from level deg − k.
    for (k, o) in out.iter_mut().enumerate().take(w) {
        let len = k + 1;
        let from = (deg - k) * w;
        pts.clear();
        pts.extend_from_slice(&triangle[from..from + len]);
        for level in 0..k {
            lerp(pts, len - level, b);
        }
        *o = pts[0];
    }
}

/// The homogeneous net (degrees `[m, n]`, row-major in the first parameter) restricted to the
/// normalised box `[s₀, s₁] × [r₀, r₁]`, the ends given as intervals enclosing the exact ones:
/// every u-column, then every v-row ([`restrict_curve`]). Each output point encloses the exact
/// control point of the sub-patch over that box.
pub(crate) fn restrict_net(
    net: &[[Interval; 4]],
    [m, n]: [usize; 2],
    [sa, sb]: [Interval; 2],
    [ra, rb]: [Interval; 2],
) -> Vec<[Interval; 4]> {
    let z = [point(0.0); 4];
    let mut tmp = vec![z; net.len()];
    let mut buf = RestrictBuffers::default();
    let mut column = Vec::with_capacity(m + 1);
    let mut restricted = vec![z; m + 1];
    for j in 0..=n {
        column.clear();
        column.extend((0..=m).map(|i| net[i * (n + 1) + j]));
        restrict_curve(&column, sa, sb, &mut buf, &mut restricted);
        for (i, h) in restricted.iter().enumerate() {
            tmp[i * (n + 1) + j] = *h;
        }
    }
    let mut out = vec![z; net.len()];
    for i in 0..=m {
        let r = i * (n + 1)..(i + 1) * (n + 1);
        restrict_curve(&tmp[r.clone()], ra, rb, &mut buf, &mut out[r]);
    }
    out
}

/// The interval `(x − lo) / (hi − lo)` enclosing the normalised parameter of `x`.
fn normalised(x: f64, [lo, hi]: [f64; 2]) -> Interval {
    (point(x) - point(lo)) / (point(hi) - point(lo))
}

/// The bounding box of the projections `(w·x)/w` of a homogeneous net with positive weights;
/// `None` if some weight interval is not provably positive.
pub(crate) fn hull_of_net(net: &[[Interval; 4]]) -> Option<[Interval; 3]> {
    let mut out: Option<[Interval; 3]> = None;
    for h in net {
        if h[3].is_empty() || h[3].inf() <= 0.0 {
            return None;
        }
        // Polynomial pieces keep the weight exactly 1 under subdivision: no division needed.
        let p = if h[3].inf() == 1.0 && h[3].sup() == 1.0 {
            [h[0], h[1], h[2]]
        } else {
            [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
        };
        out = Some(match out {
            None => p,
            Some(o) => [
                o[0].convex_hull(p[0]),
                o[1].convex_hull(p[1]),
                o[2].convex_hull(p[2]),
            ],
        });
    }
    out
}

impl RationalBezierPatch {
    /// Homogeneous interval control net of the sub-patch over `[u.inf, u.sup] × [v.inf, v.sup]`
    /// (declared parameters), enclosing the exact sub-patch net of every patch in the interval net.
    /// Works for degenerate (point) ranges and for ranges outside the domain (extrapolation).
    pub fn subnet(&self, u: Interval, v: Interval) -> Vec<[Interval; 4]> {
        let [m, n] = self.degree();
        let d = self.domain();
        let (ua, ub) = (normalised(u.inf(), d.u), normalised(u.sup(), d.u));
        let (va, vb) = (normalised(v.inf(), d.v), normalised(v.sup(), d.v));
        restrict_net(self.homogeneous(), [m, n], [ua, ub], [va, vb])
    }

    /// The sub-patch over `[u.inf, u.sup] × [v.inf, v.sup]` (declared parameters, which become
    /// its declared domain). Its interval net provably encloses the exact sub-patch net.
    ///
    /// Errors: a range of zero width or non-finite (`domain[k]`), or an extrapolated net whose
    /// weights are not provably positive (`weights[k]`).
    pub fn subpatch(&self, u: Interval, v: Interval) -> Result<RationalBezierPatch> {
        if u.is_empty() || v.is_empty() {
            return Err(Error::input(
                "domain",
                InputProblem::WrongShape("empty parameter range".into()),
            ));
        }
        let domain = Domain::new(u.inf(), u.sup(), v.inf(), v.sup());
        crate::geometry::bezier::check_domain(&domain)?;
        RationalBezierPatch::from_homogeneous(self.degree(), self.subnet(u, v), domain)
    }

    /// Bounding box of the projected control net of the sub-patch over the box: rigorous when
    /// all its weights are provably positive (always inside the domain); `None` otherwise.
    pub fn hull_bound(&self, u: Interval, v: Interval) -> Option<[Interval; 3]> {
        if u.is_empty() || v.is_empty() {
            return None;
        }
        hull_of_net(&self.subnet(u, v))
    }

    /// Naive interval evaluation of the rational form over the box (rigorous). Where the
    /// denominator is exactly zero (possible only outside the domain) the result is the whole
    /// line rather than the empty set interval division would give.
    pub fn naive_bound(&self, u: Interval, v: Interval) -> [Interval; 3] {
        let p = self.eval::<Interval>(u, v);
        if u.is_empty() || v.is_empty() {
            return p;
        }
        p.map(|x| if x.is_empty() { Interval::ENTIRE } else { x })
    }

    /// A rigorous enclosure of `{S(u, v) : u ∈ u, v ∈ v}` for every patch of the interval net:
    /// the intersection of [`Self::hull_bound`] and [`Self::naive_bound`].
    pub fn enclose(&self, u: Interval, v: Interval) -> [Interval; 3] {
        let naive = self.naive_bound(u, v);
        match self.hull_bound(u, v) {
            Some(hull) => {
                let mut out = naive;
                for c in 0..3 {
                    let both = naive[c].intersection(hull[c]);
                    // Both are rigorous, so they overlap; keep the naive bound if rounding ever
                    // made them disjoint rather than return an empty set.
                    if !both.is_empty() {
                        out[c] = both;
                    }
                }
                out
            }
            None => naive,
        }
    }

    /// Bounding box of the whole patch over its domain (convex hull of the projected net).
    pub fn bounding_box(&self) -> [Interval; 3] {
        // Weights are checked positive on construction, so the hull always exists.
        hull_of_net(self.homogeneous()).unwrap_or([Interval::ENTIRE; 3])
    }

    /// The largest side of [`Self::bounding_box`]: the model size of the patch that steps,
    /// leaves and budgets are scaled by (nominal; infinite if the box is unbounded).
    pub fn model_width(&self) -> f64 {
        self.bounding_box()
            .iter()
            .map(|x| x.wid())
            .fold(0.0, f64::max)
    }

    /// Rigorous enclosures of the point and all first and second partials over the box (naive
    /// interval evaluation of the derivative formulas). Inside the domain the denominator is
    /// positive; outside it, a denominator enclosing zero gives unbounded (or, if exactly zero,
    /// empty) components, so callers should keep boxes inside the domain.
    pub fn enclose_derivs(&self, u: Interval, v: Interval) -> PatchDerivs<Interval> {
        self.eval_derivs::<Interval>(u, v)
    }
}

/// Whether two interval boxes are disjoint in some coordinate (a proof that they do not meet).
pub fn boxes_disjoint(a: &[Interval; 3], b: &[Interval; 3]) -> bool {
    a.iter().zip(b).any(|(x, y)| x.disjoint(*y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restricting_a_curve_to_its_own_range_is_the_identity() {
        let net: Vec<[Interval; 4]> = (0..4)
            .map(|i| {
                [
                    point(i as f64),
                    point((i * i) as f64),
                    point(1.0),
                    point(1.0),
                ]
            })
            .collect();
        let restrict = |a: f64, b: f64| {
            let mut out = vec![[point(0.0); 4]; net.len()];
            restrict_curve(
                &net,
                point(a),
                point(b),
                &mut RestrictBuffers::default(),
                &mut out,
            );
            out
        };
        let same = restrict(0.0, 1.0);
        // (1 − t)·P + t·Q is exact at t = 0 and t = 1.
        assert_eq!(same, net);
        // x = 3t restricted to [1/4, 3/4] has equally spaced controls 3/4, 5/4, 7/4, 9/4.
        let part = restrict(0.25, 0.75);
        for (k, h) in part.iter().enumerate() {
            let x = 0.75 + 0.5 * k as f64;
            assert!(h[0].contains(x) && h[0].wid() < 1e-14, "{k}: {h:?}");
        }
        // Restricting to [0.5, 0.5] collapses every control point onto the curve point there.
        let mid = restrict(0.5, 0.5);
        // Cubic with x-controls 0,1,2,3 is x = 3t; at t = 0.5, x = 1.5.
        assert!(mid.iter().all(|h| h[0].contains(1.5)));
    }
}
