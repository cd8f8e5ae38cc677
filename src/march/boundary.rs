//! Domain boundaries during a march: landing exactly on the boundary where the curve leaves a
//! domain, and how a start on a boundary relates to it (which way enters, whether the curve only
//! touches the face, which surface's boundary it is).

use crate::geometry::surface::pair_bounds as bounds;
use crate::geometry::{Domain, ParametricSurface};
use crate::march::node::{inside, node_at, Node};
use crate::march::options::MarchOptions;
use crate::pair::boundary_direction::{
    boundary_sides, classify_boundary_point_unproven, BoundaryDirection, BoundaryOptions,
};
use crate::pair::newton::{refine, Constraint};

/// The first parameter (index, bound, fraction along `a → b`) where the segment leaves a domain.
fn first_exit(a: &[f64; 4], b: &[f64; 4], dp: &Domain, dq: &Domain) -> Option<(usize, f64, f64)> {
    let mut best: Option<(usize, f64, f64)> = None;
    for i in 0..4 {
        let [lo, hi] = bounds(dp, dq, i);
        let bound = if b[i] < lo {
            lo
        } else if b[i] > hi {
            hi
        } else {
            continue;
        };
        let span = b[i] - a[i];
        let s = if span != 0.0 {
            ((bound - a[i]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        if best.is_none_or(|(_, _, sb)| s < sb) {
            best = Some((i, bound, s));
        }
    }
    best
}

/// Lands on the boundary between `cur` (inside) and `out` (outside): Newton with the exit
/// parameter fixed at its bound. Returns the landed node and the surface whose boundary it is.
pub(crate) fn land_on_boundary<S1, S2>(
    p: &S1,
    q: &S2,
    cur: &Node,
    out: [f64; 4],
    opts: &MarchOptions,
) -> Option<(Node, usize)>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let mut target = out;
    for _ in 0..4 {
        let (i, bound, s) = first_exit(&cur.x, &target, &dp, &dq)?;
        let guess: [f64; 4] = std::array::from_fn(|k| cur.x[k] + s * (target[k] - cur.x[k]));
        let r = refine(
            p,
            q,
            guess,
            Constraint::Fixed {
                index: i,
                value: bound,
            },
            opts.newton_tolerance,
            opts.max_newton_iterations,
        )
        .ok()?;
        if inside(&r.x, &dp, &dq, opts.domain_tolerance) {
            let node = node_at(p, q, r.x, r.iterations, Some(cur.frame.tangent));
            return Some((node, usize::from(i >= 2)));
        }
        // Left through another side first: aim again at the landed point.
        target = r.x;
    }
    None
}

/// Whether moving along `sign · tangent` from the start enters both domains (false when the start
/// sits on a boundary and that direction leaves it).
pub(crate) fn enters<S1, S2>(p: &S1, q: &S2, n: &Node, sign: f64) -> bool
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let d = [
        n.frame.tangent_p[0],
        n.frame.tangent_p[1],
        n.frame.tangent_q[0],
        n.frame.tangent_q[1],
    ];
    let edge_tol = 1e-7 * dp.size().max(dq.size()).max(1.0);
    (0..4).all(|i| {
        let [lo, hi] = bounds(&dp, &dq, i);
        let di = sign * d[i];
        !((n.x[i] - lo).abs() <= edge_tol && di < 0.0
            || (hi - n.x[i]).abs() <= edge_tol && di > 0.0)
    })
}

/// Whether the curve through the boundary node `n` only touches the faces `n` lies on
/// (Grandine's test to second order, see [`classify_boundary_point_unproven`]): `Some(true)`
/// when it is tangent to every such face and stays inside the domains, `Some(false)` when it
/// touches a face from outside (or the surfaces touch at this point only), `None` otherwise.
pub(crate) fn touching<S1, S2>(p: &S1, q: &S2, n: &Node) -> Option<bool>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let opts = BoundaryOptions::default();
    let sides = boundary_sides(p, q, &n.x, 1e-7);
    let mut inside = !sides.is_empty();
    for side in sides {
        match classify_boundary_point_unproven(p, q, n.x, side, &opts).map(|c| c.direction) {
            Ok(BoundaryDirection::Touches { inside: false } | BoundaryDirection::Isolated) => {
                return Some(false)
            }
            Ok(BoundaryDirection::Touches { inside: true }) => {}
            _ => inside = false,
        }
    }
    inside.then_some(true)
}

/// The surface (0 for P, 1 for Q) on whose domain boundary the node `n` lies, if any.
pub(crate) fn boundary_surface_of<S1, S2>(p: &S1, q: &S2, n: &Node) -> Option<usize>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let edge_tol = 1e-7 * dp.size().max(dq.size()).max(1.0);
    (0..4).find_map(|i| {
        let [lo, hi] = bounds(&dp, &dq, i);
        ((n.x[i] - lo).abs() <= edge_tol || (hi - n.x[i]).abs() <= edge_tol)
            .then_some(usize::from(i >= 2))
    })
}
