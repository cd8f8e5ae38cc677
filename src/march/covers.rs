//! Whether a curve point lies on an already marched branch (so a start on it is not traced
//! again): within a chord's deviation bound in model space and within its parameter range.

use crate::geometry::ParametricSurface;
use crate::march::branch::Branch;
use crate::numeric::vec3::{dist3, dot, norm3};

/// Whether the curve point with parameters `x` lies on `branch`: within the deviation bound of
/// one of its chords in model space, with parameters inside that chord's parameter range widened
/// by 2 % of the domain sizes (so a point of another sheet over the same model point is not
/// covered).
///
/// A chord of length `c` spanning an arc that turns by `φ` stays within the sagitta `≈ c·φ/8` of
/// it. The turning is estimated from the curvature at the joints up to two chords away (angle
/// between the chords over their mean length, the largest, times `c`; `π/2` for a lone chord,
/// and at most `π/2`) and the bound taken four times over: `c·φ/2`, plus `floor` (the
/// accuracy of the points, e.g. a multiple of the Newton tolerance). So a separate curve closer
/// to the branch than its step (concentric loops 0.002 apart, step 0.05) is not covered, while a
/// point refined onto the traced curve is.
pub(crate) fn covers<P: ParametricSurface + ?Sized>(
    branch: &Branch,
    x: &[f64; 4],
    p: &P,
    floor: f64,
    scales: &[f64; 4],
) -> bool {
    let pt = p.point(x[0], x[1]);
    let c = [pt.x, pt.y, pt.z];
    let params = |k: usize| {
        let cp = &branch.points[k];
        [cp.p[0], cp.p[1], cp.q[0], cp.q[1]]
    };
    // Parameters within the chord's parameter range, widened by 2 % of the domains.
    let between = |a: &[f64; 4], b: &[f64; 4]| {
        (0..4).all(|i| {
            let slack = 0.02 * scales[i] + 1e-12;
            x[i] >= a[i].min(b[i]) - slack && x[i] <= a[i].max(b[i]) + slack
        })
    };
    let n = branch.points.len();
    let chord = |k: usize| -> [f64; 3] {
        let (a, b) = (&branch.points[k].xyz, &branch.points[k + 1].xyz);
        std::array::from_fn(|i| b[i] - a[i])
    };
    // Turning per unit length at the joint of chords k and k + 1: their angle over their mean
    // length (None if either is degenerate).
    let curvature = |k: usize| -> Option<f64> {
        let (a, b) = (chord(k), chord(k + 1));
        let (la, lb) = (norm3(&a), norm3(&b));
        if la == 0.0 || lb == 0.0 {
            return None;
        }
        let cos = dot(&a, &b) / (la * lb);
        Some(cos.clamp(-1.0, 1.0).acos() / (0.5 * (la + lb)))
    };
    if n == 1 {
        let a = &branch.points[0].xyz;
        return dist3(&c, a) <= floor && between(&params(0), &params(0));
    }
    (0..n - 1).any(|k| {
        let (a, b) = (&branch.points[k].xyz, &branch.points[k + 1].xyz);
        let length = dist3(a, b);
        // The turning over this chord, from the largest curvature at the two joints on either
        // side (the curvature can change fast: near a boundary end a long last chord, the step
        // clipped onto the boundary, may turn more than its neighbour did).
        let joints = k.saturating_sub(2)..(k + 2).min(n - 2);
        let turning = joints
            .filter_map(curvature)
            .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))))
            .map_or(std::f64::consts::FRAC_PI_2, |kappa| {
                (kappa * length).min(std::f64::consts::FRAC_PI_2)
            });
        let radius = 0.5 * length * turning + floor;
        segment_distance(&c, a, b) <= radius && between(&params(k), &params(k + 1))
    })
}

/// Distance from point `c` to the segment `[a, b]`.
fn segment_distance(c: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: [f64; 3] = std::array::from_fn(|i| b[i] - a[i]);
    let ac: [f64; 3] = std::array::from_fn(|i| c[i] - a[i]);
    let len2 = ab.iter().map(|x| x * x).sum::<f64>();
    let t = if len2 > 0.0 {
        (ab.iter().zip(&ac).map(|(x, y)| x * y).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let foot: [f64; 3] = std::array::from_fn(|i| a[i] + t * ab[i]);
    dist3(c, &foot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::analytic::{AnalyticSurface, Jet2};
    use crate::geometry::Domain;
    use crate::march::branch::{BranchStatus, CurvePoint, EndReason};

    /// An open branch through the given points of the plane z = 0 (parameters = x, y).
    fn branch_through(points: impl Iterator<Item = [f64; 2]>) -> Branch {
        Branch {
            id: 0,
            status: BranchStatus::Open,
            ends: [EndReason::PointLimit, EndReason::PointLimit],
            points: points
                .map(|[x, y]| CurvePoint {
                    p: [x, y],
                    q: [x, y],
                    xyz: [x, y, 0.0],
                })
                .collect(),
        }
    }

    #[test]
    fn covers_holds_the_curve_but_not_a_circle_0_002_away() {
        // The plane z = 0 as P (parameters = x, y); a traced circle of radius 0.3 with points
        // every 0.05 rad from 0 to 5 rad (chords 0.015, sagitta 0.3·(1 − cos 0.025) ≈ 9.4e-5).
        let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
        let plane = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(0.0)]);
        let at = |r: f64, a: f64| [r * a.cos(), r * a.sin()];
        let branch = branch_through((0..=100).map(|k| at(0.3, 0.05 * k as f64)));
        let scales = [2.0; 4];
        // Points of the circle itself between the traced points (worst: chord midpoints).
        for k in 0..100 {
            let [x, y] = at(0.3, 0.05 * k as f64 + 0.025);
            assert!(covers(&branch, &[x, y, x, y], &plane, 1e-8, &scales));
        }
        // The concentric circle 0.002 outside and inside, and a point of the circle beyond the traced arc (0 to 5 rad).
        for k in 0..100 {
            for r in [0.302, 0.298] {
                let [x, y] = at(r, 0.05 * k as f64 + 0.025);
                assert!(!covers(&branch, &[x, y, x, y], &plane, 1e-8, &scales));
            }
        }
        let [x, y] = at(0.3, 5.5);
        assert!(!covers(&branch, &[x, y, x, y], &plane, 1e-8, &scales));
    }

    #[test]
    fn covers_a_last_chord_past_an_inflection() {
        // The cubic y = x³ traced at x = −1.5, −1, −0.5, 0, 0.5: the two chords meeting at the
        // inflection x = 0 are parallel (no bend there), yet the last chord stays 0.048 off the
        // curve (at x = 1/√12). The curvature two joints back bounds it; a point 0.4 off the
        // chord is still not covered. (Seen at a torus's boundary end in the quadric oracle:
        // bends 0.025, 0.010, 0.0005 and then a longer, turning last step.)
        let d = Domain::new(-2.0, 2.0, -2.0, 2.0);
        let plane = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, Jet2::constant(0.0)]);
        let branch = branch_through(
            [-1.5f64, -1.0, -0.5, 0.0, 0.5]
                .iter()
                .map(|&x| [x, x * x * x]),
        );
        let scales = [4.0; 4];
        for k in 1..50 {
            let x = 0.5 * k as f64 / 50.0;
            let y = x * x * x;
            assert!(covers(&branch, &[x, y, x, y], &plane, 1e-8, &scales), "{x}");
        }
        let (x, y) = (0.29, 0.29 * 0.25 + 0.4);
        assert!(!covers(&branch, &[x, y, x, y], &plane, 1e-8, &scales));
    }

    #[test]
    fn segment_distance_matches_closed_form() {
        let (a, b) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        assert_eq!(segment_distance(&[1.0, 1.0, 0.0], &a, &b), 1.0);
        assert_eq!(segment_distance(&[3.0, 0.0, 0.0], &a, &b), 1.0);
        assert_eq!(segment_distance(&[-1.0, 0.0, 0.0], &a, &a), 1.0);
    }
}
