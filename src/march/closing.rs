//! The turning of the tangent along a march, the test that closes a loop at its start, and the
//! test that stops a march that came back onto its own path elsewhere.
//!
//! The march accumulates the signed turning of the parameter tangents in P's and in Q's domain;
//! [`closing_turning`] accepts the start as the next point only when it is near, ahead, with an
//! agreeing tangent, reached in the parameters too, and after a full turn (see the module docs of
//! [`crate::march::trace`]).

use crate::march::node::Node;
use crate::march::options::MarchOptions;
use crate::pair::tangent::CurveFrame;
use std::f64::consts::PI;

/// Signed angle from 2D vector `a` to `b` in `(−π, π]` (0 if either is zero).
fn signed_angle(a: [f64; 2], b: [f64; 2]) -> f64 {
    let cross = a[0] * b[1] - a[1] * b[0];
    let dot = a[0] * b[0] + a[1] * b[1];
    if cross == 0.0 && dot == 0.0 {
        0.0
    } else {
        cross.atan2(dot)
    }
}

/// Euclidean distance of two parameter 4-tuples.
fn param_distance(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Turning of the parameter tangents from frame `a` to frame `b`, in P's and Q's domains.
pub(crate) fn turn(a: &CurveFrame, b: &CurveFrame) -> [f64; 2] {
    [
        signed_angle(a.tangent_p, b.tangent_p),
        signed_angle(a.tangent_q, b.tangent_q),
    ]
}

/// Adds the turning `t` to `acc`.
pub(crate) fn add_turn(acc: &mut [f64; 2], t: [f64; 2]) {
    acc[0] += t[0];
    acc[1] += t[1];
}

/// Whether `turning` is within `tol` of `2πk` for an integer `k`, `k ≠ 0` unless `zero_ok` (a
/// curve through crossings may have rotation index 0, e.g. a figure eight).
fn is_full_turn(turning: f64, tol: f64, zero_ok: bool) -> bool {
    let k = (turning / (2.0 * PI)).round();
    (k != 0.0 || zero_ok) && (turning - 2.0 * PI * k).abs() < tol
}

/// The closing test of a forward half at `cur` (after `prev`), whose tangent turned by
/// `turning` since `start`: the total turning including the last turn to `start` when `start`
/// is to be the next point, `None` otherwise. `arc` is the predicted step; `crossed` says the
/// half went through a singular point (then rotation index 0 closes too).
pub(crate) fn closing_turning(
    start: &Node,
    prev: Option<&Node>,
    cur: &Node,
    turning: [f64; 2],
    arc: f64,
    opts: &MarchOptions,
    crossed: bool,
) -> Option<[f64; 2]> {
    let to_start = start.frame.xyz - cur.frame.xyz;
    let dist = to_start.norm();
    let turn_to_start = turn(&cur.frame, &start.frame);
    let total = [turning[0] + turn_to_start[0], turning[1] + turn_to_start[1]];
    // The parameters must come back too (not only the model point): the start's
    // parameters are at most twice as far as the local parameter speed allows.
    let param_speed = prev.map_or(f64::INFINITY, |pv| {
        param_distance(&pv.x, &cur.x) / (pv.frame.xyz - cur.frame.xyz).norm()
    });
    (dist <= 1.5 * arc
        && param_distance(&start.x, &cur.x) <= 2.0 * param_speed * dist + 1e-9
        && to_start.dot(&cur.frame.tangent) > 0.5 * dist
        && cur.frame.tangent.dot(&start.frame.tangent) > 0.5
        && (is_full_turn(total[0], opts.rotation_tolerance, crossed)
            || is_full_turn(total[1], opts.rotation_tolerance, crossed)))
    .then_some(total)
}

/// Earlier points closer than this many points behind the last one are never taken for a
/// return onto the march's own path; a return onto one of the first this many points of a
/// half that should close at its start closes it there.
pub(crate) const OWN_PATH_GAP: usize = 4;

/// Whether the last of `nodes` lies on the march's own earlier path, not at its start: within
/// half the predicted step `arc` of an earlier point (in model space, and in the parameters within
/// twice the local parameter speed times that distance), with a tangent within about 25° of that
/// point's, after at least four times `arc` of marched length and [`OWN_PATH_GAP`] points since
/// it. A curve that is not closed never comes back to its own point, and a closed loop traced
/// from its start closes at the start first ([`closing_turning`] accepts it from 1.5 steps away);
/// so this is a loop of another curve reached after a jump, or a loop whose closing test failed,
/// and the march would go round it again. Points near a singular point (sine of the normals'
/// angle below `watch_sine`) are never taken: a curve through a tacnode passes it twice with
/// the same tangent. Returns the earliest such point's index.
pub(crate) fn on_own_path(nodes: &[Node], arc: f64, watch_sine: f64) -> Option<usize> {
    let n = nodes.len();
    if n < OWN_PATH_GAP + 2 || arc.is_nan() || arc <= 0.0 {
        return None;
    }
    let (cur, prev) = (&nodes[n - 1], &nodes[n - 2]);
    if cur.frame.sine < watch_sine {
        return None;
    }
    let step = (prev.frame.xyz - cur.frame.xyz).norm();
    if step == 0.0 {
        return None;
    }
    let param_speed = param_distance(&prev.x, &cur.x) / step;
    let reach = 0.5 * arc;
    // The earliest point near the last one, tested from the start (squared distance first: this
    // runs after every marching step). The marched length back to it is summed only for that
    // point: it is the longest of all candidates', so if it is too short, all are.
    let k = nodes[..n - OWN_PATH_GAP].iter().position(|e| {
        let off = e.frame.xyz - cur.frame.xyz;
        off.norm_squared() <= reach * reach && {
            let d = off.norm();
            e.frame.sine >= watch_sine
                && param_distance(&e.x, &cur.x) <= 2.0 * param_speed * d + 1e-9
                && e.frame.tangent.dot(&cur.frame.tangent) > 0.9
        }
    })?;
    let behind: f64 = nodes[k..]
        .windows(2)
        .map(|w| (w[1].frame.xyz - w[0].frame.xyz).norm())
        .sum();
    (behind >= 4.0 * arc).then_some(k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Vec3;

    /// A node on the unit circle of the plane `z = 0` at angle `a` (parameters: the point's
    /// own coordinates on both surfaces), moving anticlockwise, with normals at sine `sine`.
    fn on_circle(a: f64, sine: f64) -> Node {
        let (c, s) = (a.cos(), a.sin());
        Node {
            x: [c, s, c, s],
            frame: CurveFrame {
                xyz: Vec3::new(c, s, 0.0),
                tangent: Vec3::new(-s, c, 0.0),
                tangent_p: [-s, c],
                tangent_q: [-s, c],
                sine,
            },
            iterations: 0,
            curvature: 1.0,
            flipped: false,
        }
    }

    fn march(angles: impl Iterator<Item = f64>, sine: f64) -> Vec<Node> {
        angles.map(|a| on_circle(a, sine)).collect()
    }

    #[test]
    fn a_second_lap_is_the_own_path_and_the_first_is_not() {
        let step = 2.0 * PI / 20.0;
        // Nineteen steps: not yet back.
        let lap = march((0..20).map(|k| 0.3 + k as f64 * step), 1.0);
        assert_eq!(on_own_path(&lap, step, 0.05), None);
        // Twenty-one steps: a point (almost) on the second point's place, the same direction.
        let more = march((0..22).map(|k| 0.3 + k as f64 * step + 1e-3), 1.0);
        assert_eq!(on_own_path(&more, step, 0.05), Some(1));
    }

    #[test]
    fn passing_back_the_other_way_or_near_a_singular_point_is_not_the_own_path() {
        let step = 2.0 * PI / 20.0;
        // Back along the same circle in the opposite direction: tangents disagree.
        let mut there_and_back = march((0..10).map(|k| k as f64 * step), 1.0);
        there_and_back.extend(march((0..10).rev().map(|k| k as f64 * step + 1e-3), 1.0));
        for n in &mut there_and_back[10..] {
            n.frame.tangent = -n.frame.tangent;
        }
        assert_eq!(on_own_path(&there_and_back, step, 0.05), None);
        // A second lap through points whose normals are nearly parallel (a tacnode).
        let tacnode = march((0..22).map(|k| 0.3 + k as f64 * step), 0.01);
        assert_eq!(on_own_path(&tacnode, step, 0.05), None);
    }
}
