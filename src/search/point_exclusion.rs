//! A proof that a point lies off a patch: the boundary search's answer for a side that its
//! patch collapses to one point (a pole, see [`crate::geometry::pole`]).
//!
//! Such a side is a curve of zero length, so the curve/surface search on it has no regular
//! solution to prove and can only exclude it leaf by leaf, down to leaves of the other patch
//! as small as the pole's distance from it. Instead the other patch's domain is subdivided and
//! each box `B` is settled by one of two tests:
//! - its enclosure (the hull of its sub-net) does not contain the point `X`;
//! - the distance along the direction `n` from the surface point at the box's centre `c` to `X`
//!   stays away from zero over the box, by the mean-value form
//!   `n·(Q(B) − X) ⊂ n·(Q(c) − X) + Σ_k (n·∂_k Q(B))·(B_k − c_k)`. Near the foot of `X` on the
//!   patch `n·∂_k Q` is small (zero at the foot), so boxes of size about `√(d/κ)` settle a
//!   point at distance `d` where enclosures alone would need boxes of size `d`.
//!
//! If every box is settled, no point of the patch is `X`.

use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use inari::Interval;

/// Boxes examined before giving up.
const MAX_BOXES: usize = 4000;

/// Whether `x` is proven to lie off `q` (no parameter pair of `q`'s domain maps to it).
/// `false` means not proven (the point may lie on the patch, or the budget ran out).
pub(crate) fn point_off_patch(x: [f64; 3], q: &RationalBezierPatch) -> bool {
    let d = q.domain();
    let xp = x.map(point);
    let mut stack = vec![(d.u, d.v)];
    let mut examined = 0;
    while let Some((u, v)) = stack.pop() {
        examined += 1;
        if examined > MAX_BOXES {
            return false;
        }
        let (Ok(ui), Ok(vi)) = (
            Interval::try_from((u[0], u[1])),
            Interval::try_from((v[0], v[1])),
        ) else {
            return false;
        };
        if settled(x, xp, q, ui, vi, u, v) {
            continue;
        }
        let (um, vm) = (0.5 * (u[0] + u[1]), 0.5 * (v[0] + v[1]));
        if !(u[0] < um && um < u[1] && v[0] < vm && vm < v[1]) {
            return false;
        }
        stack.extend([
            ([u[0], um], [v[0], vm]),
            ([um, u[1]], [v[0], vm]),
            ([u[0], um], [vm, v[1]]),
            ([um, u[1]], [vm, v[1]]),
        ]);
    }
    true
}

/// Whether the box `u × v` (enclosed by `ui × vi`) is proven to hold no preimage of `x`.
fn settled(
    x: [f64; 3],
    xp: [Interval; 3],
    q: &RationalBezierPatch,
    ui: Interval,
    vi: Interval,
    u: [f64; 2],
    v: [f64; 2],
) -> bool {
    if let Some(b) = q.hull_bound(ui, vi) {
        if (0..3).any(|k| !b[k].contains(x[k])) {
            return true;
        }
    }
    let c = [0.5 * (u[0] + u[1]), 0.5 * (v[0] + v[1])];
    let at = q.point_f64(c[0], c[1]);
    let n: [f64; 3] = std::array::from_fn(|k| at[k] - x[k]);
    if n.iter().all(|&t| t == 0.0) || !n.iter().all(|t| t.is_finite()) {
        return false;
    }
    let n = n.map(point);
    let qc = q.eval(point(c[0]), point(c[1]));
    let [_, su, sv] = q.first_derivs(ui, vi);
    let dot = |a: &[Interval; 3]| n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
    let off: [Interval; 3] = std::array::from_fn(|k| qc[k] - xp[k]);
    let g = dot(&off) + dot(&su) * (ui - point(c[0])) + dot(&sv) * (vi - point(c[1]));
    !g.is_empty() && (g.inf() > 0.0 || g.sup() < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Domain;

    /// The paraboloid z = x² + y² over [−1, 1]² (biquadratic, exact net).
    fn paraboloid() -> RationalBezierPatch {
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                let (x, y) = (i as f64 - 1.0, j as f64 - 1.0);
                // Blossom of x² at (a, b) is a·b: the net heights are x_i x_i' terms.
                let z = [1.0, -1.0, 1.0][i] + [1.0, -1.0, 1.0][j];
                pts.push([x, y, z]);
            }
        }
        let dom = Domain {
            u: [-1.0, 1.0],
            v: [-1.0, 1.0],
        };
        RationalBezierPatch::from_f64_points([2, 2], &pts, None, dom).unwrap()
    }

    #[test]
    fn points_just_off_the_surface_are_proven_off_and_points_on_it_never() {
        let q = paraboloid();
        for &(x, y) in &[(0.0, 0.0), (0.3, -0.7), (1.0, 1.0), (-0.5, 0.25)] {
            let z = x * x + y * y;
            assert!(!point_off_patch([x, y, z], &q), "({x}, {y}) on the surface");
            for d in [1e-3, 1e-6, 1e-9] {
                assert!(point_off_patch([x, y, z - d], &q), "({x}, {y}) {d} below");
                assert!(point_off_patch([x, y, z + d], &q), "({x}, {y}) {d} above");
            }
        }
        // Beyond the domain's edge, in the surface's extension: off the patch.
        assert!(point_off_patch([1.1, 0.0, 1.21], &q));
    }
}
