//! A point of a marched branch with its local frame, and the domain test the marcher uses.

use crate::geometry::{Domain, ParametricSurface, Vec3};
use crate::pair::tangent::{curvature, frame_from_derivs, CurveFrame};

/// A refined curve point during marching: parameters, local frame and curvature.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node {
    pub(crate) x: [f64; 4],
    pub(crate) frame: CurveFrame,
    pub(crate) iterations: usize,
    /// Curvature estimate `κ` of the curve here (see [`curvature`]); infinite at a singular point.
    pub(crate) curvature: f64,
    /// Whether the tangent is `−N^P × N^Q` (reversed to follow the direction of travel). Along a
    /// regular arc this never changes; a change between two points means the march stepped
    /// across a zero of `N^P × N^Q`: a singular point.
    pub(crate) flipped: bool,
}

/// The marching node at the curve point `x`, its tangent oriented along `along` if given.
pub(crate) fn node_at<S1, S2>(
    p: &S1,
    q: &S2,
    x: [f64; 4],
    iterations: usize,
    along: Option<Vec3>,
) -> Node
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
    let mut frame = frame_from_derivs(&dp, &dq);
    let kappa = curvature(&dp, &dq, &frame);
    let mut flipped = false;
    if let Some(dir) = along {
        if frame.tangent.dot(&dir) < 0.0 {
            frame = frame.reversed();
            flipped = true;
        }
    }
    Node {
        x,
        frame,
        iterations,
        curvature: kappa,
        flipped,
    }
}

/// Whether `x = (σ, t, u, v)` lies in both domains, within `tol`.
pub(crate) fn inside(x: &[f64; 4], dp: &Domain, dq: &Domain, tol: f64) -> bool {
    dp.contains(x[0], x[1], tol) && dq.contains(x[2], x[3], tol)
}
