//! Domain boundaries during a march: landing exactly on the boundary where the curve leaves a
//! domain, and how a start on a boundary relates to it (which way enters, whether the curve only
//! touches the face, which surface's boundary it is).

use crate::geometry::surface::{pair_bounds as bounds, pair_widths};
use crate::geometry::{Domain, ParametricSurface};
use crate::march::node::{inside, node_at, Node};
use crate::march::options::MarchOptions;
use crate::pair::boundary_direction::{
    boundary_sides, classify_boundary_point_unproven, BoundaryDirection, BoundaryOptions,
};
use crate::pair::newton::{refine, Constraint};

/// The first parameter (index, bound, fraction along `a → b`) where the segment leaves a domain
/// by more than `tol`.
fn first_exit(
    a: &[f64; 4],
    b: &[f64; 4],
    dp: &Domain,
    dq: &Domain,
    tol: f64,
) -> Option<(usize, f64, f64)> {
    let mut best: Option<(usize, f64, f64)> = None;
    for i in 0..4 {
        let [lo, hi] = bounds(dp, dq, i);
        // Out by no more than the domain tolerance is not out (a curve running along the side,
        // a rounding error beyond it): held fixed there, Newton would have no isolated root.
        let bound = if b[i] < lo - tol {
            lo
        } else if b[i] > hi + tol {
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

/// Halvings of the bracket along the curve before [`land_on_boundary`] gives up.
const BRACKET_HALVINGS: usize = 10;

/// Lands on the boundary between `cur` (inside) and `out` (outside): Newton with the exit
/// parameter fixed at its bound. Returns the landed node and the surface whose boundary it is.
///
/// The guess for that Newton is interpolated linearly in the parameters between the two points,
/// which is good while the curve crosses the boundary steeply within the bracket. A short arc
/// that dips into the domain and leaves again through the same side (its two boundary points a
/// step or less apart) crosses it at a small angle: the interpolated guess then sits near where
/// the curve is tangent to the side, between its two boundary points, and Newton along the side
/// diverges or finds the crossing behind the march. So a landing must lie between the two points
/// ([`chord_position`]); otherwise the bracket is halved along the curve (a curve point on the
/// plane through the chord's midpoint, kept on the side of the bracket where the curve is still
/// outside) and the landing tried again from the shorter bracket. A landing on `cur` itself is
/// kept only when no landing ahead of it is found: from a start on the boundary whose first step
/// overshot the whole arc, the interpolated guess is the start, and the exit lies ahead.
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
    let tol = opts.newton_tolerance;
    let (mut inner, mut outer) = (cur.x, out);
    let mut at_cur = None;
    for _ in 0..=BRACKET_HALVINGS {
        match land_between(p, q, &inner, &outer, opts) {
            Some(landed) if chord_position(p, &cur.x, &outer, &landed.0) > tol => {
                at_cur = Some(landed);
                break;
            }
            Some(landed) => {
                at_cur.get_or_insert(landed);
            }
            None => {}
        }
        let Some(mid) = midpoint_on_curve(p, q, &inner, &outer, opts) else {
            break;
        };
        if inside(&mid, &dp, &dq, 0.0) {
            inner = mid;
        } else {
            outer = mid;
        }
    }
    at_cur.map(|(x, iterations, i)| {
        let node = node_at(p, q, x, iterations, Some(cur.frame.tangent));
        (node, usize::from(i >= 2))
    })
}

/// One landing attempt from the bracket `inner` (inside) → `outer` (outside): the landed
/// parameters, Newton's corrections and the index of the fixed parameter.
fn land_between<S1, S2>(
    p: &S1,
    q: &S2,
    inner: &[f64; 4],
    outer: &[f64; 4],
    opts: &MarchOptions,
) -> Option<([f64; 4], usize, usize)>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let mut target = *outer;
    for _ in 0..4 {
        let (i, bound, s) = first_exit(inner, &target, &dp, &dq, opts.domain_tolerance)?;
        let guess: [f64; 4] = std::array::from_fn(|k| inner[k] + s * (target[k] - inner[k]));
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
        if !between(p, inner, outer, &r.x, opts.newton_tolerance) {
            return None;
        }
        if inside(&r.x, &dp, &dq, opts.domain_tolerance) {
            return Some((r.x, r.iterations, i));
        }
        // Left through another side first: aim again at the landed point.
        target = r.x;
    }
    None
}

/// Where P at `x` projects onto the chord from P at `a` to P at `b` (0 at `a`, the chord's length
/// at `b`; 0 for a degenerate chord).
fn chord_position<S>(p: &S, a: &[f64; 4], b: &[f64; 4], x: &[f64; 4]) -> f64
where
    S: ParametricSurface + ?Sized,
{
    let (pa, pb, px) = (
        p.point(a[0], a[1]),
        p.point(b[0], b[1]),
        p.point(x[0], x[1]),
    );
    let chord = pb - pa;
    let len = chord.norm();
    if len > 0.0 && len.is_finite() {
        (px - pa).dot(&chord) / len
    } else {
        0.0
    }
}

/// Whether the curve point `x` lies in the slab between the planes through P at `a` and at `b`
/// orthogonal to the chord (with `tol` and a thousandth of the chord to spare). The arc from `a`
/// to `b` turns by less than a half turn, so its points lie in that slab (exactly so on a
/// circle); a landing from the bracket `a → b` outside it is a crossing behind the march (on a
/// short arc, the boundary point where the march came in) or beyond its step.
fn between<S>(p: &S, a: &[f64; 4], b: &[f64; 4], x: &[f64; 4], tol: f64) -> bool
where
    S: ParametricSurface + ?Sized,
{
    let len = (p.point(b[0], b[1]) - p.point(a[0], a[1])).norm();
    let along = chord_position(p, a, b, x);
    let spare = 1e-3 * len + tol;
    !(along < -spare || along > len + spare)
}

/// The curve point on the plane through the midpoint of P at `a` and at `b`, orthogonal to the
/// chord (Newton from the parameters' midpoint), if Newton finds one within the chord.
fn midpoint_on_curve<S1, S2>(
    p: &S1,
    q: &S2,
    a: &[f64; 4],
    b: &[f64; 4],
    opts: &MarchOptions,
) -> Option<[f64; 4]>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (pa, pb) = (p.point(a[0], a[1]), p.point(b[0], b[1]));
    let chord = pb - pa;
    let len = chord.norm();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let guess: [f64; 4] = std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
    let r = refine(
        p,
        q,
        guess,
        Constraint::Plane {
            point: pa + 0.5 * chord,
            normal: chord / len,
        },
        opts.newton_tolerance,
        opts.max_newton_iterations,
    )
    .ok()?;
    between(p, a, b, &r.x, opts.newton_tolerance).then_some(r.x)
}

/// The curve point on the boundary next to `x`, a curve point just outside the domains: Newton
/// with the most violated parameter held at its bound, from `x` moved onto it. `None` when
/// Newton fails or lands outside again.
pub(crate) fn onto_boundary<S1, S2>(
    p: &S1,
    q: &S2,
    x: [f64; 4],
    opts: &MarchOptions,
) -> Option<[f64; 4]>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let (index, value, _) = (0..4)
        .filter_map(|i| {
            let [lo, hi] = bounds(&dp, &dq, i);
            let excess = (lo - x[i]).max(x[i] - hi) / (hi - lo);
            (excess > 0.0).then(|| (i, if x[i] < lo { lo } else { hi }, excess))
        })
        .max_by(|a, b| a.2.total_cmp(&b.2))?;
    let r = refine(
        p,
        q,
        x,
        Constraint::Fixed { index, value },
        opts.newton_tolerance,
        opts.max_newton_iterations,
    )
    .ok()?;
    inside(&r.x, &dp, &dq, opts.domain_tolerance).then_some(r.x)
}

/// Whether moving along `sign · tangent` from the start enters both domains (false when the start
/// sits on a boundary and that direction leaves it).
pub(crate) fn enters<S1, S2>(p: &S1, q: &S2, n: &Node, sign: f64) -> bool
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let d = parameter_tangent(n);
    let edge_tol = 1e-7 * dp.size().max(dq.size()).max(1.0);
    let speed = parameter_speed(&dp, &dq, &d);
    (0..4).all(|i| {
        let [lo, hi] = bounds(&dp, &dq, i);
        // A tangent component across the side at rounding level is none: the curve runs along
        // the side (a section along a knot line) rather than out through it.
        let di = sign * d[i];
        let di = if di.abs() <= ALONG * speed * (hi - lo) {
            0.0
        } else {
            di
        };
        !((n.x[i] - lo).abs() <= edge_tol && di < 0.0
            || (hi - n.x[i]).abs() <= edge_tol && di > 0.0)
    })
}

/// The node's parameter tangent `(σ', t', u', v')`.
fn parameter_tangent(n: &Node) -> [f64; 4] {
    let (tp, tq) = (n.frame.tangent_p, n.frame.tangent_q);
    [tp[0], tp[1], tq[0], tq[1]]
}

/// A parameter tangent component below this fraction of the fastest one (each relative to its
/// domain width) runs along a side rather than across it.
const ALONG: f64 = 1e-9;

/// The largest `|dₖ| / widthₖ` of the parameter tangent `d` (`(σ', t', u', v')`).
fn parameter_speed(dp: &Domain, dq: &Domain, d: &[f64; 4]) -> f64 {
    (0..4).fold(0.0, |m: f64, k| {
        let [lo, hi] = bounds(dp, dq, k);
        m.max(d[k].abs() / (hi - lo))
    })
}

/// Whether the curve through the node `n` runs *along* the side of coordinate `coordinate`
/// (0..4) that `n` lies on (a section along a knot line, or along a patch's boundary curve):
/// its parameter tangent has no component across the side (below [`ALONG`] of the fastest),
/// and the curve points a short way along it both ways (a thousandth of the fastest
/// coordinate's domain width; Newton on the normal planes) still lie on the side, to [`ALONG`]
/// of its coordinate's width. A curve that only touches the side moves off it by its curvature
/// times the step squared, a millionth of the width. Not a proof: it decides how the marcher
/// starts.
pub(crate) fn runs_along<S1, S2>(
    p: &S1,
    q: &S2,
    n: &Node,
    coordinate: usize,
    opts: &MarchOptions,
) -> bool
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let d = parameter_tangent(n);
    let [lo, hi] = bounds(&dp, &dq, coordinate);
    let value = if (n.x[coordinate] - lo).abs() <= (hi - n.x[coordinate]).abs() {
        lo
    } else {
        hi
    };
    let speed = parameter_speed(&dp, &dq, &d);
    if !(speed > 0.0 && speed.is_finite()) || d[coordinate].abs() > ALONG * speed * (hi - lo) {
        return false;
    }
    let h = 1e-3 / speed;
    [1.0, -1.0].into_iter().all(|sign| {
        let y: [f64; 4] = std::array::from_fn(|k| n.x[k] + sign * h * d[k]);
        let constraint = Constraint::Plane {
            point: p.point(y[0], y[1]),
            normal: n.frame.tangent,
        };
        refine(
            p,
            q,
            y,
            constraint,
            opts.newton_tolerance,
            opts.max_newton_iterations,
        )
        .is_ok_and(|r| (r.x[coordinate] - value).abs() <= ALONG * (hi - lo))
    })
}

/// Whether the curve through the boundary node `n` only touches the faces `n` lies on
/// (Grandine's test to second order, see [`classify_boundary_point_unproven`]): `Some(true)`
/// when it is tangent to every such face and stays inside the domains, `Some(false)` when it
/// touches a face from outside (or the surfaces touch at this point only), `None` otherwise.
pub(crate) fn touching<S1, S2>(p: &S1, q: &S2, n: &Node, march: &MarchOptions) -> Option<bool>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let opts = BoundaryOptions::default();
    // Sides the curve runs along are neither touched nor crossed.
    let sides: Vec<_> = boundary_sides(p, q, &n.x, 1e-7)
        .into_iter()
        .filter(|side| !runs_along(p, q, n, side.coordinate, march))
        .collect();
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

/// The surface (0 for P, 1 for Q) on whose domain boundary the node `n` lies, if any, not
/// counting sides the curve runs along ([`runs_along`]).
pub(crate) fn boundary_surface_of<S1, S2>(
    p: &S1,
    q: &S2,
    n: &Node,
    opts: &MarchOptions,
) -> Option<usize>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let edge_tol = 1e-7 * dp.size().max(dq.size()).max(1.0);
    let d = parameter_tangent(n);
    // Of the sides the node lies on, the one the curve crosses most steeply (relative to the
    // domain's width that way): a curve running along one surface's edge (a section along a
    // knot line) and leaving the other's domain ends on the other's boundary.
    (0..4)
        .filter(|&i| {
            let [lo, hi] = bounds(&dp, &dq, i);
            ((n.x[i] - lo).abs() <= edge_tol || (hi - n.x[i]).abs() <= edge_tol)
                && !runs_along(p, q, n, i, opts)
        })
        .map(|i| {
            let [lo, hi] = bounds(&dp, &dq, i);
            (i, d[i].abs() / (hi - lo).max(f64::MIN_POSITIVE))
        })
        .reduce(|a, b| if b.1 > a.1 { b } else { a })
        .map(|(i, _)| usize::from(i >= 2))
}

/// Whether the half leaves a domain on the step from `cur` to its Newton point `x`: `None` if
/// not; else the landing on the boundary between (`None` inside if none is found). `x` outside
/// a domain leaves it; `x` inside may too, past an exit it stepped over ([`exit_before`]).
pub(crate) fn leaves_domains<S1, S2>(
    p: &S1,
    q: &S2,
    cur: &Node,
    x: &[f64; 4],
    arc: f64,
    opts: &MarchOptions,
) -> Option<Option<(Node, usize)>>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    if !inside(x, &p.domain(), &q.domain(), opts.domain_tolerance) {
        return Some(land_on_boundary(p, q, cur, *x, opts));
    }
    exit_before(p, q, cur, arc, opts).map(Some)
}

/// Where the curve leaves a domain between `cur` and the step's Newton point, which is inside
/// (the caller checks): the step's first-order guess (`arc` along the parameter tangent) leaves a
/// domain, by a short step (a tenth of each domain; next to a pole the angular parameter's rate
/// is no guide), and a landing on the boundary between lies ahead of `cur`. Beside a side, a
/// curve's exit can lie 1e-5 from its own entering arc, and Newton from past the exit lands on
/// that arc: the march jumped.
fn exit_before<S1, S2>(
    p: &S1,
    q: &S2,
    cur: &Node,
    arc: f64,
    opts: &MarchOptions,
) -> Option<(Node, usize)>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let (tp, tq) = (cur.frame.tangent_p, cur.frame.tangent_q);
    let step = [tp[0], tp[1], tq[0], tq[1]].map(|d| arc * d);
    let guess: [f64; 4] = std::array::from_fn(|i| cur.x[i] + step[i]);
    let widths = pair_widths(&dp, &dq);
    let short = (0..4).all(|i| step[i].abs() <= 0.1 * widths[i]);
    let jumped = short && !inside(&guess, &dp, &dq, opts.domain_tolerance);
    jumped
        .then(|| land_on_boundary(p, q, cur, guess, opts))
        .flatten()
}
