//! Singular points of the intersection curve (normals parallel) and the arcs leaving them.
//!
//! Where `N^P ∥ N^Q` the transversal tangent vanishes. [`locate_singular_point`] pins the point
//! down (Gauss–Newton on `P = Q`, `N^P × N^Q = 0`), [`analyse_node`] classifies it by the contact
//! quadratic `b11 σ'² + 2 b12 σ' t' + b22 t'² = 0` (the formulas of
//! [`contact_quadratic`](crate::pair::contact_quadratic), here in `f64` on [`SurfaceDerivs`],
//! judged in model space, see `classify_in_model_space`) and finds the curve points where the arcs
//! leave it:
//!
//! - `Δ = b12² − b11 b22 > 0` (a branch point, two crossing branches): the two roots of the
//!   quadratic give four half-directions; each is refined onto the curve at distance `r`.
//! - `Δ ≈ 0` (a tacnode, a triple point, higher-order contact): the quadratic does not separate
//!   the branches, so the exits are found by sampling the circle of radius `r` round the point in
//!   the common tangent plane for sign changes of the height difference of the two surfaces.
//! - `Δ < 0`: an isolated contact point, no exits.
//!
//! All of this is `f64` estimation for the marcher; nothing here is a rigorous bound.

use crate::geometry::{ParametricSurface, SurfaceDerivs, Vec3};
use crate::pair::contact_quadratic::{
    contact_from_derivs, ContactCase, ContactQuadratic, TangentialFormula,
};
use crate::pair::newton::{refine, Constraint};
use crate::pair::tangent::parameter_direction;
use nalgebra::{Matrix6x4, Vector4, Vector6};
use std::f64::consts::PI;

/// A singular point of the intersection with the curve points where its arcs leave it.
#[derive(Debug, Clone, PartialEq)]
pub struct SingularNode {
    /// Parameters `(σ, t, u, v)` of the point.
    pub x: [f64; 4],
    /// Model-space point (midpoint of `P(σ,t)` and `Q(u,v)`).
    pub xyz: [f64; 3],
    /// Whether Gauss–Newton converged onto a point with parallel normals (otherwise `x` is the
    /// point where the marcher stopped).
    pub located: bool,
    /// Classification by the sign of `Δ` (relative to the size of the `b`s).
    pub case: ContactCase,
    /// `Δ = b12² − b11 b22` at the point.
    pub discriminant: f64,
    /// Unit model-space half-directions from the contact quadratic (four when `Δ > 0`).
    pub quadratic_directions: Vec<[f64; 3]>,
    /// Curve points at distance ≈ `radius` from the node, one per leaving arc.
    pub exits: Vec<[f64; 4]>,
    /// The same exits in model space.
    pub exit_xyz: Vec<[f64; 3]>,
    /// The distance of the exits from the node.
    pub radius: f64,
}

/// Pins down a point with parallel normals near `x0`: Gauss–Newton (least squares by SVD, since
/// the system is nearly rank deficient at tacnodes and triple points) on the six equations
/// `P − Q = 0`, `(N^P × N^Q)/(|N^P||N^Q|) = 0` in four unknowns. Returns `None` when it does not
/// converge to a point with `|P − Q| ≤ tol` and normal sine ≤ `sine_tol` within a parameter
/// distance 0.1 of `x0`.
pub fn locate_singular_point<S1, S2>(
    p: &S1,
    q: &S2,
    x0: [f64; 4],
    tol: f64,
    sine_tol: f64,
) -> Option<[f64; 4]>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    locate_singular_point_within(p, q, x0, tol, sine_tol, 0.1, 200)
}

/// [`locate_singular_point`], accepting a point up to the parameter distance `reach` from `x0`,
/// after at most `iterations` Gauss–Newton steps.
pub fn locate_singular_point_within<S1, S2>(
    p: &S1,
    q: &S2,
    x0: [f64; 4],
    tol: f64,
    sine_tol: f64,
    reach: f64,
    iterations: usize,
) -> Option<[f64; 4]>
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let mut x = Vector4::from(x0);
    for _ in 0..iterations {
        let dp = p.derivs(x[0], x[1]);
        let dq = q.derivs(x[2], x[3]);
        let (np, nq) = (dp.normal(), dq.normal());
        let scale = np.norm() * nq.norm();
        if scale == 0.0 || !scale.is_finite() {
            return None;
        }
        let gap = dp.p - dq.p;
        let c = np.cross(&nq) / scale;
        // Derivatives of the normals.
        let np_s = dp.suu.cross(&dp.sv) + dp.su.cross(&dp.suv);
        let np_t = dp.suv.cross(&dp.sv) + dp.su.cross(&dp.svv);
        let nq_u = dq.suu.cross(&dq.sv) + dq.su.cross(&dq.suv);
        let nq_v = dq.suv.cross(&dq.sv) + dq.su.cross(&dq.svv);
        let cols_gap = [dp.su, dp.sv, -dq.su, -dq.sv];
        let cols_c = [
            np_s.cross(&nq) / scale,
            np_t.cross(&nq) / scale,
            np.cross(&nq_u) / scale,
            np.cross(&nq_v) / scale,
        ];
        // Least squares J Δ = −F by SVD (not normal equations: at a tacnode J is nearly rank
        // deficient and squaring its condition number would stall the iteration).
        let mut jac = Matrix6x4::<f64>::zeros();
        let mut rhs = Vector6::<f64>::zeros();
        for k in 0..4 {
            for r in 0..3 {
                jac[(r, k)] = cols_gap[k][r];
                jac[(r + 3, k)] = cols_c[k][r];
            }
        }
        for r in 0..3 {
            rhs[r] = -gap[r];
            rhs[r + 3] = -c[r];
        }
        let delta = jac.svd(true, true).solve(&rhs, 1e-15).ok()?;
        x += delta;
        if !x.iter().all(|c| c.is_finite()) {
            return None;
        }
        if delta.norm() <= 1e-14 * (1.0 + x.norm()) {
            break;
        }
    }
    let dp = p.derivs(x[0], x[1]);
    let dq = q.derivs(x[2], x[3]);
    let (np, nq) = (dp.normal(), dq.normal());
    let sine = np.cross(&nq).norm() / (np.norm() * nq.norm());
    let moved = (x - Vector4::from(x0)).norm();
    let ok = (dp.p - dq.p).norm() <= tol && sine <= sine_tol && moved <= reach;
    ok.then_some([x[0], x[1], x[2], x[3]])
}

/// Whether P and Q stay tangent along the parameter direction `d = (σ', t')` from the singular
/// point `x`: at `x ± r·d` (model distance `r = radius / 2`) on P, the closest point of Q (two
/// Gauss–Newton iterations from the tangent map `a`, then more until converged) is within `tol`
/// and the normals are parallel there to within a sine of 1e-6. At a tacnode the two branches
/// share a tangent too, but the surfaces open up away from the point, so this fails there.
fn tangency_continues<S1, S2>(
    p: &S1,
    q: &S2,
    x: &[f64; 4],
    d: [f64; 2],
    a: [[f64; 2]; 2],
    radius: f64,
    tol: f64,
) -> bool
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let dp = p.derivs(x[0], x[1]);
    let speed = (dp.su * d[0] + dp.sv * d[1]).norm();
    if !(speed > 0.0 && speed.is_finite()) {
        return false;
    }
    let h = 0.5 * radius / speed;
    [1.0, -1.0].iter().all(|&sign| {
        let (s, t) = (x[0] + sign * h * d[0], x[1] + sign * h * d[1]);
        let target = p.point(s, t);
        let (mut u, mut v) = (
            x[2] + sign * h * (a[0][0] * d[0] + a[0][1] * d[1]),
            x[3] + sign * h * (a[1][0] * d[0] + a[1][1] * d[1]),
        );
        for _ in 0..20 {
            let dq = q.derivs(u, v);
            let r = target - dq.p;
            let (g11, g12, g22) = (dq.su.dot(&dq.su), dq.su.dot(&dq.sv), dq.sv.dot(&dq.sv));
            let (r1, r2) = (dq.su.dot(&r), dq.sv.dot(&r));
            let det = g11 * g22 - g12 * g12;
            if det == 0.0 || !det.is_finite() {
                return false;
            }
            let (du, dv) = ((g22 * r1 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det);
            u += du;
            v += dv;
            if du.abs().max(dv.abs()) <= 1e-15 * (1.0 + u.abs().max(v.abs())) {
                break;
            }
        }
        let (ep, eq) = (p.derivs(s, t), q.derivs(u, v));
        let (np, nq) = (ep.normal(), eq.normal());
        let sine = np.cross(&nq).norm() / (np.norm() * nq.norm());
        (ep.p - eq.p).norm() <= tol && sine <= 1e-6
    })
}

/// Classifies the node at `x` and finds its exits at distance `radius` (see the module docs).
/// `tol` and `max_newton` are the Newton settings used to refine the exits.
pub fn analyse_node<S1, S2>(
    p: &S1,
    q: &S2,
    x: [f64; 4],
    located: bool,
    radius: f64,
    tol: f64,
    max_newton: usize,
) -> SingularNode
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let dp = p.derivs(x[0], x[1]);
    let dq = q.derivs(x[2], x[3]);
    let centre = (dp.p + dq.p) * 0.5;
    let np = dp.normal();
    let quadratic = contact_from_derivs(&dp, &dq, &(np / np.norm()));
    let ContactQuadratic {
        a, b11, b12, b22, ..
    } = quadratic;
    let disc = quadratic.discriminant;
    let case = classify_in_model_space(&dp, [b11, b12, b22], 1e-9 * (1.0 + centre.norm()));
    let mut quadratic_directions = Vec::new();
    if case == ContactCase::BranchPoint {
        let sq = disc.sqrt();
        let roots = if b11.abs() >= b22.abs() {
            [(-b12 + sq, b11), (-b12 - sq, b11)]
        } else {
            [(b22, -b12 + sq), (b22, -b12 - sq)]
        };
        for (ds, dt) in roots {
            let d = dp.su * ds + dp.sv * dt;
            let n = d.norm();
            if n > 0.0 {
                for s in [1.0, -1.0] {
                    let u = d * (s / n);
                    quadratic_directions.push([u.x, u.y, u.z]);
                }
            }
        }
    }
    let node = Anchor { x, centre, dp };
    let mut exits = Vec::new();
    // Use the roots only when they are well apart (more than ~6°); nearly equal roots (a tacnode
    // seen slightly off its point) do not separate the branches.
    let apart = quadratic_directions.len() == 4 && {
        let (d0, d1) = (
            Vec3::from(quadratic_directions[0]),
            Vec3::from(quadratic_directions[2]),
        );
        d0.dot(&d1).abs() < 0.995
    };
    if case == ContactCase::BranchPoint && apart {
        for d in &quadratic_directions {
            let dir = Vec3::from(*d);
            if let Some(e) = node.exit_along(p, q, &dir, radius, tol, max_newton) {
                push_distinct(&mut exits, e, p, radius);
            }
        }
    }
    // A point of a curve of tangency (the surfaces stay tangent along the double root) is a
    // contact, not a node with arcs: no exits.
    let contact_curve = case == ContactCase::TangentialCurve && {
        let (ds, dt) = quadratic.double_root(TangentialFormula::choose(&quadratic));
        tangency_continues(p, q, &x, [ds, dt], a, radius, tol)
    };
    // Fall back on the circle when the quadratic does not give four distinct exits (and use it
    // for every degenerate case).
    if !contact_curve
        && case != ContactCase::IsolatedPoint
        && (case != ContactCase::BranchPoint || exits.len() != 4)
    {
        exits.clear();
        for e in node.exits_on_circle(p, q, radius, tol, max_newton) {
            push_distinct(&mut exits, e, p, radius);
        }
    }
    let exit_xyz = exits
        .iter()
        .map(|e| {
            let a = p.point(e[0], e[1]);
            [a.x, a.y, a.z]
        })
        .collect();
    SingularNode {
        x,
        xyz: [centre.x, centre.y, centre.z],
        located,
        case,
        discriminant: disc,
        quadratic_directions,
        exits,
        exit_xyz,
        radius,
    }
}

/// The contact case of the quadratic `b` (in P's parameters at `dp`), judged in model space so
/// that it does not depend on how P is parametrised: the eigenvalues `λ₁, λ₂` of `G⁻¹B` (`G` P's
/// first fundamental form, `B` the quadratic's matrix) are the quadratic's values on unit model
/// directions along its principal axes. Higher-order contact when `max |λ| ≤ floor`; otherwise a
/// branch point when `−λ₁λ₂ > 10⁻³ max λ²`, an isolated point when `λ₁λ₂ > 10⁻³ max λ²`, else
/// a (near) double root. (In raw parameters a domain ten times narrower in σ than in t scales
/// `b11` by 100 and would turn a branch point into a double root.)
fn classify_in_model_space(dp: &SurfaceDerivs, b: [f64; 3], floor: f64) -> ContactCase {
    let [b11, b12, b22] = b;
    let (g11, g12, g22) = (dp.su.dot(&dp.su), dp.su.dot(&dp.sv), dp.sv.dot(&dp.sv));
    let det_g = g11 * g22 - g12 * g12;
    if !(det_g > 0.0 && det_g.is_finite()) {
        return ContactCase::HigherOrder;
    }
    let prod = (b11 * b22 - b12 * b12) / det_g;
    let half_trace = 0.5 * (g22 * b11 - 2.0 * g12 * b12 + g11 * b22) / det_g;
    let size = half_trace.abs() + (half_trace * half_trace - prod).max(0.0).sqrt();
    let rel = 1e-3;
    if size.is_nan() || size <= floor {
        ContactCase::HigherOrder
    } else if -prod > rel * size * size {
        ContactCase::BranchPoint
    } else if prod > rel * size * size {
        ContactCase::IsolatedPoint
    } else {
        ContactCase::TangentialCurve
    }
}

fn push_distinct<S: ParametricSurface + ?Sized>(
    list: &mut Vec<[f64; 4]>,
    e: [f64; 4],
    p: &S,
    radius: f64,
) {
    let pe = p.point(e[0], e[1]);
    if list
        .iter()
        .all(|f| (p.point(f[0], f[1]) - pe).norm() > 1e-3 * radius)
    {
        list.push(e);
    }
}

/// The node's point and derivatives, for projecting nearby model points onto both surfaces.
struct Anchor {
    x: [f64; 4],
    centre: Vec3,
    dp: SurfaceDerivs,
}

impl Anchor {
    /// Foot points of `target` on P and on Q (Gauss–Newton from the node's parameters).
    fn feet<S1, S2>(&self, p: &S1, q: &S2, target: &Vec3) -> [f64; 4]
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let foot = |s: &dyn Fn(f64, f64) -> SurfaceDerivs, mut a: [f64; 2]| {
            for _ in 0..10 {
                let d = s(a[0], a[1]);
                let delta = parameter_direction(&d, &(target - d.p));
                a = [a[0] + delta[0], a[1] + delta[1]];
                if delta[0].abs() + delta[1].abs() < 1e-15 * (1.0 + a[0].abs() + a[1].abs()) {
                    break;
                }
            }
            a
        };
        let a = foot(&|u, v| p.derivs(u, v), [self.x[0], self.x[1]]);
        let b = foot(&|u, v| q.derivs(u, v), [self.x[2], self.x[3]]);
        [a[0], a[1], b[0], b[1]]
    }

    /// Refines the curve point on the plane through `centre + radius·dir` orthogonal to `dir`.
    fn exit_along<S1, S2>(
        &self,
        p: &S1,
        q: &S2,
        dir: &Vec3,
        radius: f64,
        tol: f64,
        max_newton: usize,
    ) -> Option<[f64; 4]>
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let target = self.centre + dir * radius;
        let guess = self.feet(p, q, &target);
        let r = refine(
            p,
            q,
            guess,
            Constraint::Plane {
                point: target,
                normal: *dir,
            },
            tol,
            max_newton,
        )
        .ok()?;
        let at = p.point(r.x[0], r.x[1]);
        let dist = (at - self.centre).norm();
        let inside =
            p.domain().contains(r.x[0], r.x[1], 1e-9) && q.domain().contains(r.x[2], r.x[3], 1e-9);
        (inside && dist > 0.5 * radius && dist < 2.0 * radius).then_some(r.x)
    }

    /// Exits found as sign changes of the height difference `(P − Q)·N` of the two surfaces over
    /// the circle of radius `radius` round the node in the common tangent plane.
    fn exits_on_circle<S1, S2>(
        &self,
        p: &S1,
        q: &S2,
        radius: f64,
        tol: f64,
        max_newton: usize,
    ) -> Vec<[f64; 4]>
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let n = self.dp.normal().normalize();
        let e1 = self.dp.su.normalize();
        let e2 = n.cross(&e1);
        let dir = |th: f64| e1 * th.cos() + e2 * th.sin();
        let height = |th: f64| {
            let f = self.feet(p, q, &(self.centre + dir(th) * radius));
            (p.point(f[0], f[1]) - q.point(f[2], f[3])).dot(&n)
        };
        const SAMPLES: usize = 720;
        let angles: Vec<f64> = (0..=SAMPLES)
            .map(|k| 2.0 * PI * k as f64 / SAMPLES as f64)
            .collect();
        let values: Vec<f64> = angles.iter().map(|&a| height(a)).collect();
        let mut found = Vec::new();
        for k in 0..SAMPLES {
            let (mut a, mut b) = (angles[k], angles[k + 1]);
            let (mut ga, gb) = (values[k], values[k + 1]);
            if ga == 0.0 && k > 0 {
                continue; // counted as the end of the previous interval
            }
            if ga * gb > 0.0 || (ga != 0.0 && gb == 0.0 && k + 1 == SAMPLES) {
                continue;
            }
            for _ in 0..40 {
                let m = 0.5 * (a + b);
                let gm = height(m);
                if gm == 0.0 {
                    (a, b) = (m, m);
                    break;
                }
                if gm * ga < 0.0 {
                    b = m;
                } else {
                    a = m;
                    ga = gm;
                }
            }
            let th = 0.5 * (a + b);
            if let Some(e) = self.exit_along(p, q, &dir(th), radius, tol, max_newton) {
                found.push(e);
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::analytic::{AnalyticSurface, Jet2};
    use crate::geometry::Domain;

    fn plane() -> AnalyticSurface<impl Fn(Jet2, Jet2) -> [Jet2; 3]> {
        AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |r: Jet2, s: Jet2| {
            [r, s, Jet2::constant(0.0)]
        })
    }

    #[test]
    fn saddle_node_has_four_exits_along_the_axes() {
        // z = u·v against z = 0: the branches are the axes.
        let saddle = AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |u: Jet2, v: Jet2| {
            [u, v, u * v]
        });
        let x = locate_singular_point(&saddle, &plane(), [0.01, -0.02, 0.01, -0.02], 1e-10, 1e-8)
            .expect("locates the saddle point");
        assert!(x.iter().all(|c| c.abs() < 1e-10), "{x:?}");
        let node = analyse_node(&saddle, &plane(), x, true, 0.1, 1e-12, 12);
        assert_eq!(node.case, ContactCase::BranchPoint);
        assert_eq!(node.exits.len(), 4);
        for e in &node.exits {
            // On an axis, at distance 0.1.
            assert!(
                e[0].abs().min(e[1].abs()) < 1e-10
                    && (e[0].abs().max(e[1].abs()) - 0.1).abs() < 1e-10
            );
        }
    }

    #[test]
    fn triple_point_has_six_exits_from_the_circle() {
        // z = v(3u² − v²) against z = 0: three lines through the origin at 60°.
        let monkey = AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |u: Jet2, v: Jet2| {
            [u, v, v * (3.0 * u * u - v * v)]
        });
        let node = analyse_node(&monkey, &plane(), [0.0; 4], true, 0.1, 1e-12, 12);
        assert_eq!(node.case, ContactCase::HigherOrder);
        assert_eq!(node.exits.len(), 6);
        for e in &node.exits {
            // Angles are multiples of 60°: v(3u² − v²) = 0.
            assert!((e[1] * (3.0 * e[0] * e[0] - e[1] * e[1])).abs() < 1e-12);
        }
    }

    #[test]
    fn tacnode_is_located_and_has_four_exits() {
        // z = (v − u²)(v − 2u²) against z = 0: two parabolas touching at the origin.
        let tac = AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |u: Jet2, v: Jet2| {
            [u, v, (v - u * u) * (v - 2.0 * u * u)]
        });
        let x0 = [1e-3, 1.5e-6, 1e-3, 1.5e-6];
        let x = locate_singular_point(&tac, &plane(), x0, 1e-10, 1e-6).expect("located");
        assert!(x.iter().all(|c| c.abs() < 1e-7), "{x:?}");
        let node = analyse_node(&tac, &plane(), x, true, 0.1, 1e-12, 12);
        assert_eq!(node.case, ContactCase::TangentialCurve);
        assert_eq!(node.exits.len(), 4);
    }

    #[test]
    fn isolated_contact_has_no_exits() {
        let bowl = AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |u: Jet2, v: Jet2| {
            [u, v, u * u + v * v]
        });
        let node = analyse_node(&bowl, &plane(), [0.0; 4], true, 0.1, 1e-12, 12);
        assert_eq!(node.case, ContactCase::IsolatedPoint);
        assert!(node.exits.is_empty());
    }
}
