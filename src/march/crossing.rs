//! Crossing singular points during a single trace: stopping exactly on one the march stepped
//! across, and continuing straight through a node along an unused exit (each arc once).

use crate::geometry::{ParametricSurface, Vec3};
use crate::march::node::{inside, node_at, Node};
use crate::march::options::MarchOptions;
use crate::pair::branch_point::{analyse_node, locate_singular_point, SingularNode};
use crate::pair::tangent::curve_frame;

/// The singular point between `a` and `b` (consecutive points whose `N^P × N^Q` orientations
/// differ): located by Gauss–Newton from the point of least normal sine on the parameter segment.
pub(crate) fn singular_between<S1, S2>(
    p: &S1,
    q: &S2,
    a: &Node,
    b: &Node,
    opts: &MarchOptions,
) -> Option<Node>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let at = |s: f64| -> [f64; 4] { std::array::from_fn(|i| a.x[i] + s * (b.x[i] - a.x[i])) };
    let best = (1..16).map(|k| at(k as f64 / 16.0)).min_by(|x, y| {
        curve_frame(p, q, *x)
            .sine
            .total_cmp(&curve_frame(p, q, *y).sine)
    })?;
    let scale = 1.0 + a.frame.xyz.norm();
    let tol = (100.0 * opts.newton_tolerance).max(1e-9 * scale);
    let x = locate_singular_point(p, q, best, tol, opts.singular_sine)?;
    if !inside(&x, &p.domain(), &q.domain(), opts.domain_tolerance) {
        return None;
    }
    let chord = b.frame.xyz - a.frame.xyz;
    let mut n = node_at(p, q, x, 0, Some(chord));
    n.flipped = a.flipped;
    Some(n)
}

/// The singular point just ahead of `cur` when Newton cannot step on: within a few microns of a
/// branch point the two sheets of the curve are closer together than the Newton tolerance can
/// tell apart, so the corrector fails before the sine drops below `singular_sine`. While the
/// normals are nearly parallel (sine below `watch_sine`), the point is located by Gauss–Newton
/// from `cur`; it is accepted when it lies inside both domains, within one step of `cur` and
/// ahead of it (within 60° of the tangent; a contact point beside the curve, as inside a tiny
/// loop, is not where the march ends). Returns its parameters.
pub(crate) fn singular_ahead<S1, S2>(
    p: &S1,
    q: &S2,
    cur: &Node,
    opts: &MarchOptions,
) -> Option<[f64; 4]>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    if cur.frame.sine >= opts.watch_sine {
        return None;
    }
    let scale = 1.0 + cur.frame.xyz.norm();
    let tol = (100.0 * opts.newton_tolerance).max(1e-9 * scale);
    let x = locate_singular_point(p, q, cur.x, tol, opts.singular_sine)?;
    if !inside(&x, &p.domain(), &q.domain(), opts.domain_tolerance) {
        return None;
    }
    let to = p.point(x[0], x[1]) - cur.frame.xyz;
    let dist = to.norm();
    (dist <= opts.step && (to.dot(&cur.frame.tangent) >= 0.5 * dist || dist <= tol)).then_some(x)
}

/// Crosses the singular point reached as the last of `path` (marched from `start`) straight
/// through: the node is located and analysed (or found among `visited`), the exit the march
/// arrived through is marked used, and the march continues through the unused exit nearest to
/// the straight continuation (the arrival point at distance `r` mirrored across the normal line
/// of the arriving branch, whose tangent at the node is extrapolated from the chords at `r` and
/// `r/2`, so the right branch is kept at a tacnode). `None` (stop here) when the node has no
/// exits, the arrival exit was already used (the arc was traced before) or no exit is left.
/// Returns the node point and the exit point.
pub(crate) fn cross_node<S1, S2>(
    p: &S1,
    q: &S2,
    start: &Node,
    path: &[Node],
    visited: &mut Vec<(SingularNode, Vec<bool>)>,
    opts: &MarchOptions,
) -> Option<(Node, Node)>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let reached = path.last()?;
    let scale = 1.0 + reached.frame.xyz.norm();
    let tol = (100.0 * opts.newton_tolerance).max(1e-9 * scale);
    let located = locate_singular_point(p, q, reached.x, tol, opts.singular_sine);
    let x = located.unwrap_or(reached.x);
    let centre = p.point(x[0], x[1]);
    let r = opts.node_radius * opts.step;
    let idx = match visited
        .iter()
        .position(|(n, _)| (Vec3::from(n.xyz) - centre).norm() < 0.25 * r)
    {
        Some(i) => i,
        None => {
            let n = analyse_node(
                p,
                q,
                x,
                located.is_some(),
                r,
                opts.newton_tolerance,
                opts.max_newton_iterations,
            );
            let k = n.exits.len();
            visited.push((n, vec![false; k]));
            visited.len() - 1
        }
    };
    let (node, used) = &mut visited[idx];
    let centre = Vec3::from(node.xyz);
    // The arriving polyline, from the node outwards.
    let outward: Vec<Vec3> = path[..path.len() - 1]
        .iter()
        .rev()
        .map(|n| n.frame.xyz)
        .chain(std::iter::once(start.frame.xyz))
        .collect();
    let at_distance = |d: f64| -> Option<Vec3> {
        let mut last = centre;
        for pt in &outward {
            let (da, db) = ((last - centre).norm(), (pt - centre).norm());
            if db >= d {
                let s = if db > da {
                    ((d - da) / (db - da)).clamp(0.0, 1.0)
                } else {
                    1.0
                };
                return Some(last + (pt - last) * s);
            }
            last = *pt;
        }
        None
    };
    let c_in = at_distance(r)?;
    let c_half = at_distance(0.5 * r)?;
    let nearest = |target: &Vec3, skip: Option<usize>, used: &[bool], any: bool| {
        node.exit_xyz
            .iter()
            .enumerate()
            .filter(|(k, _)| Some(*k) != skip && (any || !used[*k]))
            .map(|(k, e)| (k, (Vec3::from(*e) - target).norm()))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)
    };
    let arrival = nearest(&c_in, None, used, true)?;
    if used[arrival] {
        return None;
    }
    used[arrival] = true;
    let u_in = (centre - c_in).normalize();
    let u_half = (centre - c_half).normalize();
    let tangent = (u_half * 2.0 - u_in).normalize();
    let tangent = if tangent.iter().all(|c| c.is_finite()) {
        tangent
    } else {
        u_in
    };
    let d = c_in - centre;
    let target = centre + d - tangent * (2.0 * d.dot(&tangent));
    let leave = nearest(&target, Some(arrival), used, false)?;
    used[leave] = true;
    let exit = node.exits[leave];
    let at = node_at(p, q, node.x, 0, None);
    let away = p.point(exit[0], exit[1]) - centre;
    let mut beyond = node_at(p, q, exit, 0, Some(away));
    beyond.iterations = 0;
    Some((at, beyond))
}
