//! How far the marcher's next step may go: the step `L`, capped near a singular point (the
//! sine of the normals' angle falling fast) and near a pole of either surface (where the
//! parameters turn fast however smooth the curve is), and when a march has reached a pole.

use crate::geometry::{Domain, ParametricSurface, Vec3};
use crate::march::node::Node;
use crate::march::options::MarchOptions;

/// A march this close to a pole (relative to the model's size) has reached it.
pub(super) const POLE_REACHED: f64 = 1e-12;
/// A march whose Newton fails this close to a pole (relative) has reached it.
pub(super) const POLE_NEWTON: f64 = 1e-12;

/// The larger model extent of the two surfaces' domains (corner to corner), at least 1e-300.
pub(super) fn model_size<S1, S2>(p: &S1, q: &S2) -> f64
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let diag = |s: &dyn Fn(f64, f64) -> Vec3, d: Domain| {
        (s(d.u[1], d.v[1]) - s(d.u[0], d.v[0]))
            .norm()
            .max((s(d.u[1], d.v[0]) - s(d.u[0], d.v[1])).norm())
    };
    diag(&|u, v| p.point(u, v), p.domain())
        .max(diag(&|u, v| q.point(u, v), q.domain()))
        .max(1e-300)
}

/// The step for the next prediction: `L` (an angle on tight curves, see [`predict`]), a cap
/// on the predicted arc length, and whether the march is heading into a singular point.
#[derive(Clone, Copy)]
pub(super) struct StepLimit {
    pub(super) step: f64,
    pub(super) cap: f64,
    pub(super) approaching: bool,
}

impl StepLimit {
    pub(super) fn halved(self) -> Self {
        StepLimit {
            step: 0.5 * self.step,
            cap: 0.5 * self.cap,
            ..self
        }
    }
}

/// The step for the next prediction. Near a singular point (sine small and decreasing) the arc
/// is capped at half the distance to where the sine would vanish at its current rate of
/// decrease: a geometric approach. The cap is a length, applied to the predicted arc: on a tight
/// curve `L` is an angle (the arc is `L·R`), and taking the cap for `L` itself would shrink the
/// step twice over (on a tiny loop of nearly tangent surfaces, radius 1e-3 and a sine of 1e-4,
/// the march crawled at 1e-7 a step and stopped at the point limit a third of the way round).
pub(super) fn step_limit(
    prev: Option<&Node>,
    cur: &Node,
    opts: &MarchOptions,
    poles: &[Vec<Vec3>; 2],
) -> StepLimit {
    // Near a pole the parameters turn fast however smooth the curve is in space (a curve
    // passing at distance ρ from a sphere's pole sweeps half a turn of u within a few ρ): the
    // arc is capped at half the distance to the pole, a geometric approach that a pass
    // close by survives.
    let near_pole = poles
        .iter()
        .flatten()
        .map(|x| 0.5 * (cur.frame.xyz - x).norm())
        .fold(f64::INFINITY, f64::min);
    let mut limit = StepLimit {
        step: opts.step,
        cap: near_pole,
        approaching: false,
    };
    if let Some(pv) = prev {
        let chord = (cur.frame.xyz - pv.frame.xyz).norm();
        let rate = (pv.frame.sine - cur.frame.sine) / chord;
        if cur.frame.sine < opts.watch_sine && rate > 0.0 {
            limit.cap = limit.cap.min(0.5 * cur.frame.sine / rate);
            // At this rate the sine vanishes within a hundred chords: heading into a
            // singular point (on a tiny loop the sine is small but constant, its rate
            // rounding noise, and the predicted zero far away).
            limit.approaching = cur.frame.sine < 100.0 * rate * chord;
        }
    }
    limit
}

/// Which surface's pole (0 for P, 1 for Q; `poles`: each surface's) `node` lies within
/// `reach` of, if any: a curve through a pole reaches it in geometrically shrinking steps and
/// ends there, on that surface's boundary (the pole's side).
pub(super) fn on_pole(poles: &[Vec<Vec3>; 2], node: &Node, reach: f64) -> Option<usize> {
    (0..2).find(|&s| {
        poles[s]
            .iter()
            .any(|x| (node.frame.xyz - x).norm() <= reach)
    })
}
