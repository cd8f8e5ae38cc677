//! The critical case of [`super`]: the surfaces are tangent at the boundary point.
//!
//! First the contact quadratic (second-order terms) separates an isolated contact and a branch
//! point from a curve of tangency; for a curve (or when all second-order terms vanish) the
//! direction is the limit of the perturbed problems' directions, Q translated by `ε·n`.

use super::{
    arr, pair_bounds, velocity_at, BoundaryClassification, BoundaryDirection, BoundarySide,
    DecidedBy, PerturbedDirection,
};
use crate::geometry::{ParametricSurface, SurfaceDerivs, Vec3};
use crate::pair::contact_quadratic::{
    contact_from_derivs, ContactCase, Relative, TangentialFormula,
};
use nalgebra::{Matrix3, Vector3};

/// The shape of the contact at a tangential point from its second-order terms (Ye & Maekawa's
/// quadratic `b11 σ'² + 2 b12 σ' t' + b22 t'² = 0`), with `f64` thresholds relative to the size
/// of the terms that cancel in the `b`s; for a curve of tangency also its direction.
fn contact_shape(
    dp: &SurfaceDerivs,
    dq: &SurfaceDerivs,
    n: &Vec3,
    ell: f64,
) -> (ContactCase, Option<[f64; 4]>) {
    let c = contact_from_derivs(dp, dq, n);
    if c.d == 0.0 || !c.d.is_finite() {
        return (ContactCase::HigherOrder, None);
    }
    let [[a11, a12], [a21, a22]] = c.a;
    // Magnitude of the terms that cancel in the b's, and of a curvature 1/ell.
    let a2 = a11 * a11 + a12 * a12 + a21 * a21 + a22 * a22;
    let scale = (dp.su.norm_squared() + dp.sv.norm_squared()) / ell
        + dp.suu.norm()
        + 2.0 * dp.suv.norm()
        + dp.svv.norm()
        + (dq.suu.norm() + 2.0 * dq.suv.norm() + dq.svv.norm()) * a2;
    let case = c.case(&Relative {
        floor: 1e-7 * scale,
        rel: 1e-6,
    });
    // The double root of the quadratic: the curve's direction (σ', t'), and (u', v') = a·(σ', t').
    let direction = (case == ContactCase::TangentialCurve).then(|| {
        let (ds, dt) = c.double_root(TangentialFormula::choose(&c));
        c.lift(ds, dt)
    });
    (case, direction)
}

/// `|ε|` of the perturbed problems, relative to the model size: 10⁻², …, 10⁻¹⁰.
const PERTURBATION_LEVELS: i32 = 9;

/// The perturbed problems' points on face `k` near `x`: Q translated by `ε n`, for decreasing
/// `|ε|` of both signs, each solved by Newton from several starts around `x` (the tangential
/// point itself is a singular start) and from the previous level's points.
fn perturbed_points<P, Q>(
    p: &P,
    q: &Q,
    x: [f64; 4],
    k: usize,
    n: &Vec3,
    ell: f64,
    widths: &[f64; 4],
) -> Vec<PerturbedDirection>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let free: Vec<usize> = (0..4).filter(|&i| i != k).collect();
    let mut dirs: Vec<[f64; 3]> = Vec::new();
    for a in 0..3 {
        for s in [1.0, -1.0] {
            let mut d = [0.0; 3];
            d[a] = s;
            dirs.push(d);
        }
    }
    let r3 = 1.0 / 3f64.sqrt();
    for m in 0..8 {
        dirs.push(std::array::from_fn(
            |a| if m >> a & 1 == 1 { -r3 } else { r3 },
        ));
    }
    let max_step: [f64; 4] = widths.map(|w| 0.25 * w);
    let magnitude = 1.0 + p.point(x[0], x[1]).norm();
    let scaled_dist = |a: &[f64; 4], b: &[f64; 4]| {
        (0..4)
            .map(|i| ((a[i] - b[i]) / widths[i]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mut out = Vec::new();
    for sign in [1.0, -1.0] {
        let mut prev: Vec<[f64; 4]> = Vec::new();
        for j in 0..PERTURBATION_LEVELS {
            let r = 10f64.powi(-(2 + j));
            let eps = sign * r * ell;
            let e = n * eps;
            let ftol = (1e-4 * eps.abs()).max(4.0 * f64::EPSILON * magnitude);
            let reach = (3.0 * r.powf(0.25)).min(0.5);
            let mut starts = prev.clone();
            for rho in [r.sqrt(), r.cbrt(), r.powf(0.25)] {
                for d in &dirs {
                    let mut s = x;
                    for (a, &i) in free.iter().enumerate() {
                        s[i] += rho * d[a] * widths[i];
                    }
                    starts.push(s);
                }
            }
            let mut found: Vec<[f64; 4]> = Vec::new();
            for s in starts {
                let Some(z) = newton_on_face(p, q, s, k, &e, ftol, &max_step) else {
                    continue;
                };
                let inside = (0..4).all(|i| {
                    let b = pair_bounds(&dp, &dq, i);
                    let slack = 1e-9 * widths[i];
                    z[i] >= b[0] - slack && z[i] <= b[1] + slack
                });
                let dist = scaled_dist(&z, &x);
                if !inside || dist > reach || dist == 0.0 {
                    continue;
                }
                if found.iter().all(|f| scaled_dist(f, &z) > 1e-9) {
                    found.push(z);
                }
            }
            for z in &found {
                let (_, v, sine) = velocity_at(p, q, z);
                if sine > 1e-13 {
                    out.push(PerturbedDirection {
                        epsilon: eps,
                        point: *z,
                        tangent: v,
                    });
                }
            }
            prev = found;
        }
    }
    out.sort_by(|a, b| b.epsilon.abs().total_cmp(&a.epsilon.abs()));
    out
}

/// The limit line of the perturbed directions (unit, in width-scaled parameters) and, when all
/// perturbed curves of the last three levels are oriented the same way along it, that sign.
/// `None` unless the last three levels with points agree within 0.02 rad and the last one is
/// at most `10⁻⁶ ell` (the limit must actually be approached).
fn perturbation_limit(
    list: &[PerturbedDirection],
    widths: &[f64; 4],
    ell: f64,
) -> Option<(usize, Option<f64>)> {
    let scaled = |t: &[f64; 4]| {
        let s: [f64; 4] = std::array::from_fn(|i| t[i] / widths[i]);
        let len = s.iter().map(|x| x * x).sum::<f64>().sqrt();
        (len > 0.0).then(|| s.map(|x| x / len))
    };
    let mut mags: Vec<f64> = list.iter().map(|d| d.epsilon.abs()).collect();
    mags.dedup();
    if mags.len() < 3 || mags[mags.len() - 1] > 1e-6 * ell {
        return None;
    }
    let last = mags[mags.len() - 3];
    let tail: Vec<usize> = (0..list.len())
        .filter(|&i| list[i].epsilon.abs() <= last)
        .collect();
    let reference = *tail.last()?;
    let l = scaled(&list[reference].tangent)?;
    let mut signs = Vec::new();
    for &i in &tail {
        let d = scaled(&list[i].tangent)?;
        let c: f64 = (0..4).map(|a| d[a] * l[a]).sum();
        if c.abs() < 1.0 - 2e-4 {
            return None;
        }
        signs.push(c.signum());
    }
    let consistent = signs.iter().all(|&s| s == signs[0]).then_some(signs[0]);
    Some((reference, consistent))
}

/// The mean of the perturbed directions at the smallest `|ε|` (both signs, each turned to agree
/// with `reference`), at unit model speed on P at the face point. The leading error terms of
/// perturbations of opposite sign, or of the two curves of a pair, have opposite signs (in the
/// seed example's family they are odd in `∛ε`), so the mean converges an order faster.
fn smallest_level_mean(
    list: &[PerturbedDirection],
    reference: usize,
    widths: &[f64; 4],
    dp: &SurfaceDerivs,
) -> [f64; 4] {
    let r = &list[reference];
    let agree = |t: &[f64; 4]| {
        (0..4)
            .map(|i| t[i] * r.tangent[i] / widths[i].powi(2))
            .sum::<f64>()
    };
    let mut sum = [0.0; 4];
    for pd in list.iter().filter(|d| d.epsilon.abs() == r.epsilon.abs()) {
        let sign = agree(&pd.tangent).signum();
        for (acc, t) in sum.iter_mut().zip(&pd.tangent) {
            *acc += sign * t;
        }
    }
    let speed = (dp.su * sum[0] + dp.sv * sum[1]).norm();
    if speed > 0.0 && speed.is_finite() {
        sum.map(|x| x / speed)
    } else {
        r.tangent
    }
}

/// `|cos|` of the angle between the lines of `a` and `b` in width-scaled parameters (0 when
/// either is zero).
fn line_cosine(a: &[f64; 4], b: &[f64; 4], widths: &[f64; 4]) -> f64 {
    let dot =
        |x: &[f64; 4], y: &[f64; 4]| (0..4).map(|i| x[i] * y[i] / widths[i].powi(2)).sum::<f64>();
    let n = (dot(a, a) * dot(b, b)).sqrt();
    if n > 0.0 {
        (dot(a, b) / n).abs()
    } else {
        0.0
    }
}

/// The critical case (the surfaces tangent at `x`): contact quadratic, then perturbation limit.
pub(crate) fn classify_critical<P, Q>(
    p: &P,
    q: &Q,
    x: [f64; 4],
    side: BoundarySide,
    widths: &[f64; 4],
) -> BoundaryClassification
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let k = side.coordinate;
    let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
    let mut out = BoundaryClassification {
        direction: BoundaryDirection::Undecided,
        critical: true,
        proven: false,
        tangent: [0.0; 4],
        orientation: [0.0; 3],
        point: x,
        decided_by: DecidedBy::Nothing,
        perturbed: Vec::new(),
        contact: None,
    };
    let np = dp.normal();
    if np.norm() == 0.0 || !np.norm().is_finite() || dq.normal().norm() == 0.0 {
        return out; // a singular surface point: nothing to say
    }
    let n = np / np.norm();
    let ell = dp.su.norm() * widths[0] + dp.sv.norm() * widths[1];
    let ell = if ell > 0.0 && ell.is_finite() {
        ell
    } else {
        1.0
    };
    let (shape, quadratic_direction) = contact_shape(&dp, &dq, &n, ell);
    out.contact = Some(shape);
    match shape {
        ContactCase::IsolatedPoint => {
            out.direction = BoundaryDirection::Isolated;
            out.decided_by = DecidedBy::ContactQuadratic;
            return out;
        }
        ContactCase::BranchPoint => {
            out.decided_by = DecidedBy::ContactQuadratic;
            return out;
        }
        _ => {}
    }
    out.perturbed = perturbed_points(p, q, x, k, &n, ell, widths);
    let Some((reference, consistent)) = perturbation_limit(&out.perturbed, widths, ell) else {
        return out;
    };
    let mut tangent = smallest_level_mean(&out.perturbed, reference, widths, &dp);
    if let Some(qd) = quadratic_direction {
        // Order one: the contact quadratic gives the direction directly; a perturbation limit
        // that disagrees with it (beyond 0.05 rad) is not trusted.
        if line_cosine(&qd, &tangent, widths) < (0.05f64).cos() {
            return out;
        }
    }
    let rel: [f64; 4] = std::array::from_fn(|i| tangent[i] / widths[i]);
    let largest = rel.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    let across = rel[k] / largest;
    if across.is_nan() || across.abs() < 0.05 {
        // The limit runs along the face: not decided at this accuracy.
        return out;
    }
    let inward = side.inward_sign();
    let orientation = match consistent {
        Some(_) => velocity_at(p, q, &out.perturbed[reference].point).0,
        None if shape == ContactCase::TangentialCurve => {
            // A tangential curve of order one: its perturbed curves come in oppositely oriented
            // pairs, so there is no orientation from the normals; orient it into the domain.
            if across * inward < 0.0 {
                tangent = tangent.map(|t| -t);
            }
            let t = dp.su * tangent[0] + dp.sv * tangent[1];
            t / t.norm()
        }
        // Oppositely oriented pairs at a higher-order contact: an isolated contact point looks
        // the same from the face, so nothing is decided.
        None => return out,
    };
    out.direction = if tangent[k] * inward > 0.0 {
        BoundaryDirection::Enters
    } else {
        BoundaryDirection::Leaves
    };
    out.tangent = tangent;
    out.orientation = arr(&orientation);
    out.decided_by = DecidedBy::PerturbationLimit;
    out
}

/// The 3×3 Newton solve of `P − Q − e = 0` on the three coordinates other than `k`, started at
/// `x0`, each correction capped at `max_step`; `Some` when it converges to `|P − Q − e| ≤ ftol`.
fn newton_on_face<P, Q>(
    p: &P,
    q: &Q,
    x0: [f64; 4],
    k: usize,
    e: &Vec3,
    ftol: f64,
    max_step: &[f64; 4],
) -> Option<[f64; 4]>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let free: Vec<usize> = (0..4).filter(|&i| i != k).collect();
    let mut x = x0;
    let mut converged = 0;
    for _ in 0..60 {
        let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
        let f = dp.p - dq.p - e;
        if !f.iter().all(|c| c.is_finite()) {
            return None;
        }
        if f.norm() <= ftol {
            converged += 1;
            if converged >= 2 {
                return Some(x);
            }
        }
        let cols = [dp.su, dp.sv, -dq.su, -dq.sv];
        let j = Matrix3::from_columns(&[cols[free[0]], cols[free[1]], cols[free[2]]]);
        let step = j.lu().solve(&Vector3::new(-f.x, -f.y, -f.z))?;
        if !step.iter().all(|c| c.is_finite()) {
            return None;
        }
        let ratio = (0..3)
            .map(|r| step[r].abs() / max_step[free[r]])
            .fold(0.0, f64::max);
        let s = if ratio > 1.0 { 1.0 / ratio } else { 1.0 };
        for r in 0..3 {
            x[free[r]] += s * step[r];
        }
    }
    let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
    ((dp.p - dq.p - e).norm() <= ftol).then_some(x)
}
