//! Re-anchoring a certified step on the curve, with a proven arc-length error.
//!
//! After a validated step, the end box holds the flow's end point `e` but is spread along the
//! curve. [`reanchor`] replaces it by a thin box around the curve point `a` where the fastest
//! coordinate `x_k` takes the end box's midpoint value, bounds the arc length between `e` and
//! `a` (which becomes an error on the arc length carried from then on), and encloses the curve
//! around `a` far enough for the boxes to hold their published arc-length ranges despite it.
//! [`join_tolerance`] bounds the distance of the joining piece to the reported curve.

use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::{interval, point};
use crate::pair::field::transversal_field;
use crate::pair::krawczyk::{contract_box, krawczyk, KrawczykResult};
use inari::Interval;

/// A re-anchored start: the curve point where the along-curve coordinate takes a chosen value.
pub(crate) struct Anchor {
    /// Thin box around that point (coordinate `k` a point).
    pub(crate) start: [Interval; 4],
    /// Holds every curve point within `2·s_err` arc length of the anchor, and the flow's end.
    pub(crate) cover: [Interval; 4],
    /// Proven bound on the anchor's arc-length error (the previous error plus `bridge`).
    pub(crate) s_err: f64,
    /// Proven bound on the arc length between the flow's end point and the anchor.
    pub(crate) bridge: f64,
}

/// Re-anchors the step's end box `end` (which holds the flow's end point `e`) on the curve point
/// `a` with `x_k = c`, `c` the midpoint of `end`'s coordinate `k`.
///
/// Krawczyk with `x_k` held in an interval `X ∋ c` around `end[k]`, on `end` inflated in the
/// other coordinates, proves that the curve in that box is the graph of a function of `x_k ∈ X`
/// and encloses it (`cover`). Then, rigorously over `cover`: the arc length from `e` to `a` is
/// at most `|c − e_k| / min|x_k'|` (the field has unit model-space speed), and every curve point
/// within arc length `L` of `a` stays in `cover` when `L·max|x_k'|` is below the distance from
/// `c` to the ends of `X`. `X` is chosen so that this holds for `L = 2·s_err` (checked, not
/// assumed). `velocity` (an estimate of the field at `end`) sizes `X` and the inflation.
pub(crate) fn reanchor(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    end: &[Interval; 4],
    k: usize,
    velocity: &[f64; 4],
    s_err: f64,
    dir: f64,
) -> Option<Anchor> {
    let c = end[k].mid();
    let (ci, lo, hi) = (point(c), point(end[k].inf()), point(end[k].sup()));
    // Largest distance from c to a point of end[k].
    let d = (ci - lo).sup().max((hi - ci).sup());
    let v_est = velocity[k].abs();
    if !(v_est > 0.0 && d.is_finite()) {
        return None;
    }
    let mut half_width = d.max(4.0 * (s_err + 2.0 * d / v_est) * v_est) * 1.25
        + 4.0 * f64::EPSILON * c.abs().max(1e-300);
    // Smallest inflation of the other coordinates, relative to max(1, |x_i|): the Krawczyk image
    // of a box this thin is dominated by the rounding errors of the patch evaluations.
    let mut floor = 1e-13;
    for _attempt in 0..4 {
        let x = interval(c - half_width, c + half_width)?;
        if !end[k].subset(x) {
            half_width *= 2.0;
            continue;
        }
        let mut grown = *end;
        for (i, g) in grown.iter_mut().enumerate() {
            if i == k {
                *g = x;
            } else {
                // Room for the curve's motion over X in this coordinate (twice the estimate).
                let motion = 2.0 * half_width * (velocity[i] / velocity[k]).abs();
                let r = g.wid().max(floor * g.mag().max(1.0)).max(motion);
                *g = interval(g.inf() - r, g.sup() + r)?;
            }
        }
        let KrawczykResult::Proven {
            enclosure: cover, ..
        } = krawczyk(p, q, grown, k, 4)
        else {
            floor *= 16.0;
            continue;
        };
        let vk = transversal_field(p, q, &cover, dir).velocity[k];
        if vk.is_empty() || vk.contains(0.0) {
            return None;
        }
        let (m, big_m) = (point(vk.mig()), point(vk.mag()));
        let bridge = (point(d) / m).sup();
        let err = (point(s_err) + point(bridge)).sup();
        let room = (ci - point(x.inf())).inf().min((point(x.sup()) - ci).inf());
        if (point(2.0) * point(err) * big_m).sup() >= room {
            half_width *= 2.0;
            continue;
        }
        let mut thin = cover;
        thin[k] = ci;
        let start = contract_box(p, q, thin, k, 3)?;
        return Some(Anchor {
            start,
            cover,
            s_err: err,
            bridge,
        });
    }
    None
}

/// Distance bound for the true curve piece joining a step's end `e` to the next start `a`, of arc
/// length at most `bridge` (the field has unit speed): a point `b` on it has
/// `min(|b − e|, |b − a|) ≤ bridge/2`, `e` is within `r_before` of the reported curve and `a`
/// within `r_after`, so `b` is within `max(r_before, r_after) + bridge/2` of it. Without a next
/// tube (`r_after = None`), `r_before + bridge`.
pub(crate) fn join_tolerance(r_before: f64, bridge: f64, r_after: Option<f64>) -> f64 {
    match r_after {
        Some(r) => (point(r_before.max(r)) + point(bridge) / point(2.0)).sup(),
        None => (point(r_before) + point(bridge)).sup(),
    }
}
