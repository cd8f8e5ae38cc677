//! How a half of a cover chain meets a singular point: links towards a singular end of the
//! march, the conditioning that holds links up near one, and the proven singular box a half
//! ends with.

use super::limit::LinkLimit;
use super::walker::{scaled_dist, Node, Walker};
use super::*;
use crate::certify::exact_residual::onto_curve;
use crate::geometry::pole::pole_scaled_normal;
use crate::geometry::{ParametricSurface, RationalBezierPatch, Vec3};
use crate::pair::branch_point::locate_singular_point_within;
use crate::pair::tangent::normals_sine_sqr;

/// Below this sine of the angle between the normals a link too wide is proven again on exact
/// residuals ([`Walker::precise_at`]): the interval residual's rounding (tens of ulps of the
/// model's size, 2e-14 on a cone of size 3) over the sine then reaches a fifth of a tight
/// tolerance.
/// Not above it: the exact residual is taken at the link's start, and the Taylor form centred
/// there ranges the residual over the link less tightly than one centred in its middle (torus
/// pieces at a sine of 4e-4 went from 2e-9 to 1.5e-7 with a threshold of 1e-3).
const PRECISE_SINE: f64 = 1e-4;

impl Walker<'_> {
    /// Whether a link from `x` wider than the aim is proven again on exact residuals: the
    /// surfaces are nearly tangent there ([`PRECISE_SINE`]), so the rounding of the residual
    /// over the sine can set the tube; the nodes there are moved onto the curve by an exact
    /// Newton step ([`Self::precise_node`]).
    pub(super) fn precise_at(&self, x: &[f64; 4]) -> bool {
        normals_sine_sqr(self.p, self.q, x) < PRECISE_SINE * PRECISE_SINE
    }

    /// `n` moved onto the curve by a Newton step on the exact residual with `x_j` held, for a
    /// precise link's predictor: an `f64` Newton point is off the curve by the residual's
    /// rounding over the sine (2e-9 on a cone 1e-8 from tangency), and the predictor through it
    /// would be too. `None` where no such step applies (interval patches, or a step longer than
    /// 1e-6 of the domains: not a correction of rounding).
    pub(super) fn precise_node(&self, n: &Node, j: usize) -> Option<Node> {
        let x = onto_curve(self.p, self.q, &n.x, j)?;
        (scaled_dist(&x, &n.x, &self.scales) <= 1e-6).then_some(Node { x, t: n.t })
    }

    /// How long a link from `node` can be when the march ended at a singular point: a link
    /// towards it fails to contract once it reaches much more than half way (the cylinders'
    /// node ends: links of 0.5 and 0.75 of the distance to the marched end held, of 0.95 all
    /// but one failed, and each failure halved the link), so [`SINGULAR_REACH`] of that
    /// distance. `None` otherwise.
    pub(super) fn singular_reach(&self, node: &Node) -> Option<f64> {
        self.toward_singular
            .map(|t| SINGULAR_REACH * scaled_dist(&node.x, &t, &self.scales))
    }

    /// Whether a proven link of scaled length `len` and model width `width` shows the walk
    /// held up by the conditioning, not by the predictor: wider than the aim (half the
    /// tolerance) although the link before it was at least as long and less than 3/4 as wide.
    /// Near a singular point the width grows like the inverse of the distance to it whatever
    /// the length, and the walk would only creep on with links as wide (the cylinders: about
    /// ten more attempts per end, to gain 1e-6); the caller ends the half there when a
    /// singular point is near ([`Self::conditioning_end`]; nearly tangent surfaces are not
    /// enough: on Fig. 7 the normals' cross product over boxes 1e-4 round ordinary links
    /// contains zero).
    pub(super) fn conditioning_limited(&self, len: f64, width: f64) -> bool {
        width > 0.5 * self.opts.required_tolerance
            && self
                .prev
                .is_some_and(|(l, w)| l >= len && w <= 0.75 * width)
    }

    /// The end of a half after a kept link from `a` to `b` of scaled length `len` that was
    /// [`Self::conditioning_limited`]: singular, when the link is shorter than [`FLOOR_LINK`],
    /// a singular point is found near `b` and a singular box within four lengths.
    pub(super) fn conditioning_end(
        &self,
        limited: bool,
        len: f64,
        a: &[f64; 4],
        b: &[f64; 4],
    ) -> Option<CertifiedEnd> {
        if !(limited && len < FLOOR_LINK && self.singular_point_near(b, 4.0 * len)) {
            return None;
        }
        let near = self.singular_box(a, b, 4.0 * len)?;
        Some(CertifiedEnd::Singular { near })
    }

    /// Whether Gauss–Newton finds a point of `P = Q` with parallel normals (sine below 1e-6)
    /// within the scaled distance `reach` of `x`: a singular point the walk is approaching, not
    /// merely nearly tangent surfaces (on a torus 1e-6 from tangency the conditioning also
    /// holds links up, but the curve goes on to the boundary). Guidance only: the end reported
    /// is the proven singular box.
    pub(super) fn singular_point_near(&self, x: &[f64; 4], reach: f64) -> bool {
        let scale = self.scales.iter().copied().fold(0.0, f64::max);
        let tol = self.opts.required_tolerance.max(1e-12);
        locate_singular_point_within(self.p, self.q, *x, tol, 1e-6, reach * scale, 50).is_some()
    }

    /// Whether a link from `a` to `b`, which halving did not narrow, is held up by the
    /// conditioning alone, so that keeping it is better than stopping: no box around the link
    /// (widened by up to 1e-4 of the domains) has normals whose cross product contains zero;
    /// or there is one (nearly tangent surfaces: on a torus 1e-8 from tangency a loop of radius
    /// 1e-4 lies wholly inside it) but Gauss–Newton finds no point of `P = Q` with parallel
    /// normals within that reach. Guidance only; the link's own proof is what is claimed, and
    /// the certificate says why its tolerance is wider ([`Self::limit_at`]).
    pub(super) fn conditioning_only(&self, a: &[f64; 4], b: &[f64; 4]) -> bool {
        self.singular_box(a, b, 1e-4).is_none() || !self.singular_point_near(b, 1e-4)
    }

    /// The pole of `surface` (0 for P, 1 for Q) nearest the point of `x` on it, and its
    /// distance relative to the patch's model size; `None` if the patch has no pole.
    fn nearest_pole(&self, surface: usize, x: &[f64; 4]) -> Option<(Vec3, f64)> {
        let s = [self.p, self.q][surface];
        let at = s.point(x[2 * surface], x[2 * surface + 1]);
        let size = s.model_width().max(f64::MIN_POSITIVE);
        s.poles()
            .into_iter()
            .map(|p| (p, (at - p).norm() / size))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// If the marched point `x` lies at a pole of `surface` (0 for P, 1 for Q; within 1e-11 of
    /// the model's size, where the march stops on one): why a half that ran into it ends
    /// unproven.
    pub(super) fn pole_at(&self, surface: usize, x: &[f64; 4]) -> Option<String> {
        let (pole, _) = self.nearest_pole(surface, x).filter(|&(_, d)| d <= 1e-11)?;
        Some(format!(
            "the curve runs into the pole ({:.6}, {:.6}, {:.6}) of {}, where a side of the patch \
             collapses to one point and its parameters degenerate: no link reaches it (in a \
             shell, a join through the pole can be proven on a cap round it)",
            pole.x + 0.0,
            pole.y + 0.0,
            pole.z + 0.0,
            ["P", "Q"][surface]
        ))
    }

    /// Why a link at `x` was kept although wider than the aim: the rounding of the
    /// coordinates, or the angle between the surfaces' normals (its sine at `x`, an `f64`
    /// estimate for the report).
    pub(super) fn limit_at(&self, x: &[f64; 4], rounding: bool) -> LinkLimit {
        if rounding {
            return LinkLimit::Rounding;
        }
        // Within 1e-6 of a model's size from a pole, the pole is what limits the link; within
        // 1e-3 too, unless the surfaces are nearly tangent (their crossing is then the cause).
        let sine = normals_sine_sqr(self.p, self.q, x).sqrt();
        let reach = if sine >= 1e-2 { 1e-3 } else { 1e-6 };
        for surface in 0..2 {
            if let Some((_, d)) = self.nearest_pole(surface, x).filter(|&(_, d)| d < reach) {
                let size = [self.p, self.q][surface].model_width();
                return LinkLimit::Pole {
                    surface,
                    distance: d * size,
                };
            }
        }
        LinkLimit::Conditioning { sine }
    }

    /// Why no link could be proven between `a` and `b`: a singular box if the normals'
    /// cross product cannot be bounded away from zero on a box around them (widened by up to
    /// 1e-4 of the domains: a link fails some way before a singular point, where the proven
    /// tube outgrows the tolerance), else close branches.
    pub(super) fn classify(&self, a: &Node, b: &Node) -> CertifiedEnd {
        let h = scaled_dist(&a.x, &b.x, &self.scales);
        match self.singular_box(&a.x, &b.x, 1e-4) {
            Some(near) => CertifiedEnd::Singular { near },
            None => CertifiedEnd::CloseBranches {
                h,
                near: std::array::from_fn(|i| hull(a.x[i], b.x[i])),
            },
        }
    }

    /// The end of a half stopped at `last` before the marched point `x` where the velocity
    /// vanishes: a singular box if one is found near them, else unproven.
    pub(super) fn singular_end(&self, last: &Node, x: &[f64; 4]) -> CertifiedEnd {
        let h = scaled_dist(&last.x, x, &self.scales);
        match self.singular_box(&last.x, x, (4.0 * h).max(1e-4)) {
            Some(near) => CertifiedEnd::Singular { near },
            None => CertifiedEnd::Unproven {
                reason: "the marched branch ends at a point without a velocity".into(),
                near: std::array::from_fn(|i| hull(last.x[i], x[i])),
            },
        }
    }

    /// The smallest of the boxes around `hull(a, b)`, widened by up to `reach` (scaled), on
    /// which every component of `N^P × N^Q` contains zero.
    pub(super) fn singular_box(
        &self,
        a: &[f64; 4],
        b: &[f64; 4],
        reach: f64,
    ) -> Option<[Interval; 4]> {
        let mut pad = 0.0;
        loop {
            let near: [Interval; 4] = std::array::from_fn(|i| {
                let w = pad * self.scales[i];
                hull(a[i].min(b[i]) - w, a[i].max(b[i]) + w)
            });
            // Near a pole the normal itself vanishes; a positive multiple of it does not.
            let normal = |s: &RationalBezierPatch, u: Interval, v: Interval| {
                pole_scaled_normal(s, u, v).unwrap_or_else(|| {
                    let [_, su, sv] = s.first_derivs(u, v);
                    cross(&su, &sv)
                })
            };
            let m = cross(
                &normal(self.p, near[0], near[1]),
                &normal(self.q, near[2], near[3]),
            );
            if m.iter().all(|c| c.contains(0.0)) {
                return Some(near);
            }
            if pad >= reach {
                return None;
            }
            pad = if pad == 0.0 {
                reach * 1e-6
            } else {
                (pad * 4.0).min(reach)
            };
        }
    }
}
