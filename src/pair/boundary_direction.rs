//! Boundary points of `P ∩ Q`: does the curve enter the domain there, leave it, or only touch it?
//!
//! A point `y = (σ, t, u, v)` of the intersection lies on a face `y_k = bound` of the parameter
//! box (a boundary of P's or of Q's domain). Along the curve, oriented by `c = N^P × N^Q`, the
//! parameter velocity is (see [`crate::pair::field`])
//!
//! ```text
//! σ' = −(N^Q·P_t)/|c|   t' = (N^Q·P_σ)/|c|   u' = (N^P·Q_v)/|c|   v' = −(N^P·Q_u)/|c|
//! ```
//!
//! The numerator of `y_k'` is, up to sign, the determinant of Grandine's 3×3 system (Oh, Hur &
//! Kim, eq. 4: the derivative of `P − Q` along the boundary parameter, against the three other
//! parameters' columns; its solution is [`BoundaryClassification::face_derivatives`]). The
//! paper's eq. 1 (garbled in the OCR) is a sign test on those derivatives: the point starts a
//! branch when the curve heads into the domain along the chosen orientation. Here: at a `Min`
//! face the curve **enters** where `y_k' > 0` and **leaves** where `y_k' < 0` (reversed at `Max`);
//! [`BoundaryClassification::along`] restates the answer for any direction of travel.
//!
//! - **Regular case** (`c ≠ 0`, `y_k' ≠ 0`): the sign is proven when the Krawczyk test certifies a
//!   box around the point with `y_k` held exactly at the bound ([`certify_point`]) and the
//!   interval numerator over that box excludes 0. Otherwise the `f64` sign is returned as an
//!   estimate.
//! - **Tangent to the face** (`c ≠ 0`, `y_k' ≈ 0`): the sign of `y_k''` (from second derivatives)
//!   says whether the curve touches the face from inside or from outside: neither a start nor an
//!   end of a branch. Never proven (tangency is a codimension-one condition).
//! - **Critical case** (`c = 0`: the surfaces are tangent there, the 3×3 system is singular;
//!   the `critical` submodule): the contact quadratic of Ye & Maekawa separates isolated
//!   contacts and branch points; for a curve of tangency (or when all second-order terms vanish, contact of
//!   order ≥ 2 as in the paper's example) the direction is the paper's perturbation limit
//!   `dy/ds(0) = lim_{ε→0} dy/ds(ε)`, evaluated numerically on Q translated by `ε·n` (`n` the
//!   unit normal: the paper's own perturbation) for `|ε|` = 10⁻²…10⁻¹⁰ of the model size, both
//!   signs; the perturbed problems are regular, and their directions must agree over the three
//!   smallest levels. The numerical limit is used rather than the analytic one because the
//!   analytic limit needs the lowest non-vanishing order of the contact (third order in the
//!   paper's example), i.e. derivatives the surface traits do not provide, while the perturbed
//!   problems need only first derivatives and work for any contact order. The answer refers to
//!   the perturbed curves' common orientation `N^P × N^Q` when they share one; a curve of
//!   tangency of order one has none (its perturbed curves come in oppositely oriented pairs)
//!   and is oriented into the domain; oppositely oriented pairs at a higher-order contact are
//!   left undecided, because an isolated contact of higher order looks the same from the face.
//!   Never proven.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::surface::{pair_bounds, pair_widths};
use crate::geometry::{ParametricSurface, SurfaceDerivs, Vec3};
use crate::numeric::vec3::cross;
use crate::pair::contact_quadratic::ContactCase;
use crate::pair::field::{velocity_numerators, ScalarSurface};
use crate::pair::krawczyk::certify_point;
use crate::pair::newton::{refine, Constraint};
use inari::Interval;

mod critical;
use critical::classify_critical;

/// Which end of a parameter range a boundary face is at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// The lower end (`σ = σ0`, …).
    Min,
    /// The upper end.
    Max,
}

/// A face of the parameter box of a surface pair: coordinate `coordinate` of `(σ, t, u, v)`
/// (0, 1 on P; 2, 3 on Q) at its `bound`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BoundarySide {
    /// 0 = σ, 1 = t (P's parameters), 2 = u, 3 = v (Q's).
    pub coordinate: usize,
    /// Which end of the range.
    pub bound: Bound,
}

impl BoundarySide {
    /// The face `coordinate = bound`.
    pub const fn new(coordinate: usize, bound: Bound) -> Self {
        BoundarySide { coordinate, bound }
    }

    /// The surface the face belongs to: 0 for P, 1 for Q.
    pub fn surface(&self) -> usize {
        self.coordinate / 2
    }

    /// +1 when increasing the coordinate goes into the domain (a `Min` face), −1 at `Max`.
    pub fn inward_sign(&self) -> f64 {
        match self.bound {
            Bound::Min => 1.0,
            Bound::Max => -1.0,
        }
    }
}

/// The faces a point lies on: every coordinate within `tol` times its range's width of a bound.
pub fn boundary_sides<P, Q>(p: &P, q: &Q, y: &[f64; 4], tol: f64) -> Vec<BoundarySide>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let (dp, dq) = (p.domain(), q.domain());
    let mut out = Vec::new();
    for (k, &yk) in y.iter().enumerate() {
        let b = pair_bounds(&dp, &dq, k);
        let w = b[1] - b[0];
        if (yk - b[0]).abs() <= tol * w {
            out.push(BoundarySide::new(k, Bound::Min));
        } else if (yk - b[1]).abs() <= tol * w {
            out.push(BoundarySide::new(k, Bound::Max));
        }
    }
    out
}

/// What the intersection curve does at a boundary point, along the classification's orientation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundaryDirection {
    /// The curve comes into the domain here: a branch starts.
    Enters,
    /// The curve goes out of the domain here: a branch ends.
    Leaves,
    /// The curve is tangent to the face and stays on one side of it (`inside`: in the domain,
    /// the point is inside a branch; otherwise the point is all the curve has in the domain).
    Touches {
        /// Whether the curve near the point lies in the domain.
        inside: bool,
    },
    /// The surfaces touch at this point only (no curve through it).
    Isolated,
    /// Not decided (a branch point on the boundary, a critical case whose perturbation limit
    /// did not settle, or a touching of higher order).
    Undecided,
}

impl BoundaryDirection {
    /// The answer for the opposite orientation (`Enters` ↔ `Leaves`, the rest unchanged).
    pub fn reversed(self) -> Self {
        match self {
            BoundaryDirection::Enters => BoundaryDirection::Leaves,
            BoundaryDirection::Leaves => BoundaryDirection::Enters,
            other => other,
        }
    }
}

/// Which argument decided a [`BoundaryClassification`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DecidedBy {
    /// The sign of the boundary coordinate's velocity (Grandine's test).
    FirstOrder,
    /// The sign of its second derivative (the curve is tangent to the face).
    SecondOrder,
    /// The contact quadratic at a tangential point (isolated contact or branch point).
    ContactQuadratic,
    /// The limit of the perturbed problems' directions.
    PerturbationLimit,
    /// Nothing decided.
    Nothing,
}

/// One perturbed problem of the critical case: Q translated by `epsilon · n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerturbedDirection {
    /// The translation along the unit normal `n` of P at the point (model units).
    pub epsilon: f64,
    /// The perturbed problem's point on the same face.
    pub point: [f64; 4],
    /// Its parameter velocity at unit model speed along its `N^P × N^Q`.
    pub tangent: [f64; 4],
}

/// The answer of [`classify_boundary_point`].
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryClassification {
    /// What the curve does, travelling along `orientation`.
    pub direction: BoundaryDirection,
    /// The surfaces are tangent at the point (Grandine's 3×3 system is singular).
    pub critical: bool,
    /// `direction` is proven by interval arithmetic (only `Enters`/`Leaves` in the regular case
    /// ever are): the curve point on the face inside a Krawczyk-certified box crosses the face
    /// that way.
    pub proven: bool,
    /// Parameter velocity `(σ', t', u', v')` at unit model speed along `orientation` (zero when
    /// undecided): for `Enters` it points into the domain, for `Leaves` out of it.
    pub tangent: [f64; 4],
    /// The unit model-space tangent the answer refers to: `N^P × N^Q` normalised in the regular
    /// case; in the critical case the limit of the perturbed problems' `N^P × N^Q` when they
    /// agree, otherwise the direction into the domain.
    pub orientation: [f64; 3],
    /// The point used: the input with the face coordinate set exactly to its bound (and, in the
    /// regular case, refined onto the curve by Newton with that coordinate held).
    pub point: [f64; 4],
    /// What decided it.
    pub decided_by: DecidedBy,
    /// The perturbed problems examined (critical case only), largest `|ε|` first.
    pub perturbed: Vec<PerturbedDirection>,
    /// The shape of the contact (critical case only; estimated in `f64`).
    pub contact: Option<ContactCase>,
}

impl BoundaryClassification {
    /// The answer for a traveller moving along model-space direction `travel` (flipped when
    /// `travel` points against `orientation`).
    pub fn along(&self, travel: [f64; 3]) -> BoundaryDirection {
        let d: f64 = (0..3).map(|i| travel[i] * self.orientation[i]).sum();
        if d < 0.0 {
            self.direction.reversed()
        } else {
            self.direction
        }
    }

    /// The paper's derivatives along the face's parameter, `dy/dy_k` (entry `k` is 1): e.g. at
    /// Q's `u = 0` face `(dσ/du, dt/du, 1, dv/du)`. `None` when the tangent has no component
    /// across the face.
    pub fn face_derivatives(&self, side: BoundarySide) -> Option<[f64; 4]> {
        let k = side.coordinate.min(3);
        let tk = self.tangent[k];
        (tk != 0.0).then(|| self.tangent.map(|x| x / tk))
    }
}

/// Tolerances of [`classify_boundary_point`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryOptions {
    /// The residual admission: the point must satisfy `|P − Q| ≤ residual_admission` (model
    /// units).
    pub residual_admission: f64,
    /// It must be within `boundary_tolerance` times the range's width of the face.
    pub boundary_tolerance: f64,
    /// The surfaces count as tangent (critical case) where the sine of the normals' angle is
    /// below this.
    pub critical_sine: f64,
    /// The curve counts as tangent to the face where the face coordinate's velocity, relative
    /// to the largest one (each divided by its range's width), is below this.
    pub touch_ratio: f64,
    /// Box radii (times the largest range width) tried for the Krawczyk proof, smallest first.
    pub proof_radii: [f64; 3],
}

impl Default for BoundaryOptions {
    fn default() -> Self {
        BoundaryOptions {
            residual_admission: 1e-8,
            boundary_tolerance: 1e-9,
            critical_sine: 1e-8,
            touch_ratio: 1e-7,
            proof_radii: [1e-10, 1e-8, 1e-6],
        }
    }
}

/// Classifies the boundary point `y` of `P ∩ Q` on face `side`, with an interval proof where it
/// succeeds (see the module documentation for the cases).
///
/// Errors ([`Error::InvalidInput`]): a non-finite `y[i]` or option, a face coordinate above 3;
/// [`Error::NotOnBoundary`] when `y` is not on the face within `boundary_tolerance`;
/// [`Error::NotOnIntersection`] when `|P − Q| > tolerance` at `y`.
pub fn classify_boundary_point<P, Q>(
    p: &P,
    q: &Q,
    y: [f64; 4],
    side: BoundarySide,
    opts: &BoundaryOptions,
) -> Result<BoundaryClassification>
where
    P: ParametricSurface + ScalarSurface + ?Sized,
    Q: ParametricSurface + ScalarSurface + ?Sized,
{
    let prove = |x: &[f64; 4], k: usize, radius: f64| prove_sign(p, q, x, k, radius);
    classify(p, q, y, side, opts, Some(&prove))
}

/// [`classify_boundary_point`] on every face `y` lies on (within `opts.boundary_tolerance`;
/// two at a corner); an empty list for a point inside both domains. Same errors.
pub fn classify_on_faces<P, Q>(
    p: &P,
    q: &Q,
    y: [f64; 4],
    opts: &BoundaryOptions,
) -> Result<Vec<(BoundarySide, BoundaryClassification)>>
where
    P: ParametricSurface + ScalarSurface + ?Sized,
    Q: ParametricSurface + ScalarSurface + ?Sized,
{
    if let Some(i) = y.iter().position(|c| !c.is_finite()) {
        return Err(Error::input(format!("y[{i}]"), InputProblem::NonFinite));
    }
    boundary_sides(p, q, &y, opts.boundary_tolerance)
        .into_iter()
        .map(|side| Ok((side, classify_boundary_point(p, q, y, side, opts)?)))
        .collect()
}

/// [`classify_boundary_point`] for surfaces with only an `f64` evaluation: the same answer
/// without the interval proof (`proven` is always false).
pub fn classify_boundary_point_unproven<P, Q>(
    p: &P,
    q: &Q,
    y: [f64; 4],
    side: BoundarySide,
    opts: &BoundaryOptions,
) -> Result<BoundaryClassification>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    classify(p, q, y, side, opts, None)
}

/// Proves the sign of the face coordinate's velocity numerator at the curve point on the face
/// `y_k = x_k` near `x`: `Some(±1)` when a certified box exists and the numerator's interval
/// over it excludes 0.
fn prove_sign<P, Q>(p: &P, q: &Q, x: &[f64; 4], k: usize, radius: f64) -> Option<f64>
where
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let b = certify_point(p, q, *x, k, radius)?;
    let (ap, bp, gp) = p.scaled_first_order(b[0], b[1]);
    let (aq, bq, gq) = q.scaled_first_order(b[2], b[3]);
    // Positive scale factors g do not change signs: use the scaled partials directly (the box
    // may reach slightly outside a domain, so g > 0 is checked rather than assumed).
    if !(gp.inf() > 0.0 && gq.inf() > 0.0) {
        return None;
    }
    let num = numerator_of::<Interval>(&ap, &bp, &aq, &bq, k);
    if num.inf() > 0.0 {
        Some(1.0)
    } else if num.sup() < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// The numerator of `y_k'` (times `|c|`) from the four partials, in any scalar type.
fn numerator_of<T: crate::Scalar>(
    ps: &[T; 3],
    pt: &[T; 3],
    qu: &[T; 3],
    qv: &[T; 3],
    k: usize,
) -> T {
    velocity_numerators(ps, pt, qu, qv, &cross(ps, pt), &cross(qu, qv))[k.min(3)]
}

type Prover<'a> = &'a dyn Fn(&[f64; 4], usize, f64) -> Option<f64>;

fn arr(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn check_input<P, Q>(
    p: &P,
    q: &Q,
    y: &[f64; 4],
    side: BoundarySide,
    opts: &BoundaryOptions,
) -> Result<[f64; 4]>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    if let Some(i) = y.iter().position(|c| !c.is_finite()) {
        return Err(Error::input(format!("y[{i}]"), InputProblem::NonFinite));
    }
    let k = side.coordinate;
    if k > 3 {
        return Err(Error::input(
            "side.coordinate",
            InputProblem::WrongShape(format!("coordinate {k} (0..=3 expected)")),
        ));
    }
    let finite_pos = |x: f64| x.is_finite() && x > 0.0;
    let o = opts;
    if !(finite_pos(o.residual_admission)
        && finite_pos(o.boundary_tolerance)
        && finite_pos(o.critical_sine)
        && finite_pos(o.touch_ratio)
        && o.proof_radii.iter().all(|&r| finite_pos(r)))
    {
        return Err(Error::input(
            "options",
            InputProblem::WrongShape("tolerances must be finite and positive".into()),
        ));
    }
    let b = pair_bounds(&p.domain(), &q.domain(), k);
    let bound = match side.bound {
        Bound::Min => b[0],
        Bound::Max => b[1],
    };
    let distance = (y[k] - bound).abs();
    if distance > opts.boundary_tolerance * (b[1] - b[0]) {
        return Err(Error::NotOnBoundary {
            coordinate: k,
            bound,
            distance,
            near: *y,
        });
    }
    let mut x = *y;
    x[k] = bound;
    let residual = (p.point(x[0], x[1]) - q.point(x[2], x[3])).norm();
    if residual.is_nan() || residual > opts.residual_admission {
        return Err(Error::NotOnIntersection { residual, near: *y });
    }
    Ok(x)
}

/// Unit `c`, unnormalised velocity numerators and the sine of the normals' angle.
struct FirstOrder {
    c: Vec3,
    /// `(σ', t', u', v')` at unit model speed along `c` (zero when `c = 0`).
    velocity: [f64; 4],
    sine: f64,
}

fn first_order(dp: &SurfaceDerivs, dq: &SurfaceDerivs) -> FirstOrder {
    let (np, nq) = (dp.normal(), dq.normal());
    let m = np.cross(&nq);
    let mn = m.norm();
    let scale = np.norm() * nq.norm();
    let sine = if scale > 0.0 { mn / scale } else { 0.0 };
    if mn == 0.0 || !mn.is_finite() {
        return FirstOrder {
            c: Vec3::zeros(),
            velocity: [0.0; 4],
            sine,
        };
    }
    let a = |v: &Vec3| [v.x, v.y, v.z];
    let (ps, pt, qu, qv) = (a(&dp.su), a(&dp.sv), a(&dq.su), a(&dq.sv));
    let velocity =
        velocity_numerators(&ps, &pt, &qu, &qv, &cross(&ps, &pt), &cross(&qu, &qv)).map(|x| x / mn);
    FirstOrder {
        c: m / mn,
        velocity,
        sine,
    }
}

/// Derivative of the numerator of `y_k'` along the parameter direction `d`.
fn numerator_rate(dp: &SurfaceDerivs, dq: &SurfaceDerivs, d: &[f64; 4], k: usize) -> f64 {
    let ps1 = dp.suu * d[0] + dp.suv * d[1];
    let pt1 = dp.suv * d[0] + dp.svv * d[1];
    let qu1 = dq.suu * d[2] + dq.suv * d[3];
    let qv1 = dq.suv * d[2] + dq.svv * d[3];
    let (np, nq) = (dp.normal(), dq.normal());
    let np1 = ps1.cross(&dp.sv) + dp.su.cross(&pt1);
    let nq1 = qu1.cross(&dq.sv) + dq.su.cross(&qv1);
    match k {
        0 => -(nq1.dot(&dp.sv) + nq.dot(&pt1)),
        1 => nq1.dot(&dp.su) + nq.dot(&ps1),
        2 => np1.dot(&dq.sv) + np.dot(&qv1),
        _ => -(np1.dot(&dq.su) + np.dot(&qu1)),
    }
}

fn classify<P, Q>(
    p: &P,
    q: &Q,
    y: [f64; 4],
    side: BoundarySide,
    opts: &BoundaryOptions,
    prover: Option<Prover<'_>>,
) -> Result<BoundaryClassification>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let mut x = check_input(p, q, &y, side, opts)?;
    let k = side.coordinate;
    let widths = pair_widths(&p.domain(), &q.domain());
    let fo = first_order(&p.derivs(x[0], x[1]), &q.derivs(x[2], x[3]));
    if fo.sine < opts.critical_sine {
        return Ok(classify_critical(p, q, x, side, &widths));
    }
    // Regular: refine onto the curve with the face coordinate held exactly.
    if let Ok(r) = refine(
        p,
        q,
        x,
        Constraint::Fixed {
            index: k,
            value: x[k],
        },
        opts.residual_admission.min(1e-13),
        20,
    ) {
        if (0..4).all(|i| (r.x[i] - x[i]).abs() <= 1e-3 * widths[i]) {
            let bound = x[k];
            x = r.x;
            x[k] = bound; // exactly on the face, whatever Newton's rounding did
        }
    }
    let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
    let fo = first_order(&dp, &dq);
    let inward = side.inward_sign();
    let mut out = BoundaryClassification {
        direction: BoundaryDirection::Undecided,
        critical: false,
        proven: false,
        tangent: fo.velocity,
        orientation: arr(&fo.c),
        point: x,
        decided_by: DecidedBy::Nothing,
        perturbed: Vec::new(),
        contact: None,
    };
    let by_sign = |s: f64| {
        if s * inward > 0.0 {
            BoundaryDirection::Enters
        } else {
            BoundaryDirection::Leaves
        }
    };
    if let Some(prove) = prover {
        let wmax = widths.iter().copied().fold(0.0, f64::max);
        for r in opts.proof_radii {
            if let Some(s) = prove(&x, k, r * wmax) {
                out.direction = by_sign(s);
                out.proven = true;
                out.decided_by = DecidedBy::FirstOrder;
                return Ok(out);
            }
        }
    }
    let rel: [f64; 4] = std::array::from_fn(|i| fo.velocity[i] / widths[i]);
    let largest = rel.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    if rel[k].abs() > opts.touch_ratio * largest {
        out.direction = by_sign(rel[k]);
        out.decided_by = DecidedBy::FirstOrder;
        return Ok(out);
    }
    // Tangent to the face: the sign of y_k'' (the numerator's rate; the numerator is ~0).
    let rate = numerator_rate(&dp, &dq, &fo.velocity, k);
    let size = second_order_scale(&dp, &dq, &fo.velocity);
    if rate.abs() > 1e-6 * size {
        out.direction = BoundaryDirection::Touches {
            inside: rate * inward > 0.0,
        };
        out.decided_by = DecidedBy::SecondOrder;
    }
    Ok(out)
}

/// A magnitude the numerator rate is compared with: the same products with absolute values.
fn second_order_scale(dp: &SurfaceDerivs, dq: &SurfaceDerivs, d: &[f64; 4]) -> f64 {
    let f = |s: &SurfaceDerivs, a: f64, b: f64| {
        let first = s.su.norm() + s.sv.norm();
        let second = (s.suu.norm() + 2.0 * s.suv.norm() + s.svv.norm()) * (a.abs() + b.abs());
        (first, second)
    };
    let (p1, p2) = f(dp, d[0], d[1]);
    let (q1, q2) = f(dq, d[2], d[3]);
    p1 * p1 * q2 + p1 * p2 * q1 + q1 * q1 * p2 + q1 * q2 * p1 + f64::MIN_POSITIVE
}

/// Unit `c`, velocity and sine at `x` (see `first_order`).
fn velocity_at<P, Q>(p: &P, q: &Q, x: &[f64; 4]) -> (Vec3, [f64; 4], f64)
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    let fo = first_order(&p.derivs(x[0], x[1]), &q.derivs(x[2], x[3]));
    (fo.c, fo.velocity, fo.sine)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, PowerSurface, RationalBezierPatch};

    fn graph(d: Domain, z: Vec<(u32, u32, f64)>) -> RationalBezierPatch {
        PowerSurface::graph(d, z).to_bezier().unwrap()
    }

    #[test]
    fn velocity_maps_to_the_unit_tangent_on_both_surfaces() {
        let p = graph(Domain::UNIT, vec![(2, 0, 1.0), (1, 1, 0.3), (0, 2, -0.5)]);
        let q = graph(
            Domain::new(-1.0, 2.0, -1.0, 2.0),
            vec![(0, 0, 0.1), (1, 0, 0.4), (0, 1, -0.2)],
        );
        let x = [0.3, 0.6, 0.3, 0.6];
        let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
        let fo = first_order(&dp, &dq);
        let tp = dp.su * fo.velocity[0] + dp.sv * fo.velocity[1];
        let tq = dq.su * fo.velocity[2] + dq.sv * fo.velocity[3];
        assert!((tp - fo.c).norm() < 1e-14 && (tq - fo.c).norm() < 1e-14);
        assert!((fo.c.norm() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn numerator_rate_matches_a_finite_difference() {
        let p = graph(Domain::UNIT, vec![(2, 0, 1.0), (1, 1, 0.3), (0, 2, -0.5)]);
        let q = graph(
            Domain::new(-1.0, 2.0, -1.0, 2.0),
            vec![(0, 0, 0.1), (2, 0, 0.4), (1, 1, -0.2), (0, 2, 0.7)],
        );
        let x = [0.3, 0.6, 0.35, 0.5];
        let d = [0.2, -0.7, 0.4, 0.9];
        let num = |x: &[f64; 4], k: usize| {
            let (dp, dq) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
            let a = |v: &Vec3| [v.x, v.y, v.z];
            numerator_of(&a(&dp.su), &a(&dp.sv), &a(&dq.su), &a(&dq.sv), k)
        };
        let h = 1e-6;
        for k in 0..4 {
            let xp: [f64; 4] = std::array::from_fn(|i| x[i] + h * d[i]);
            let xm: [f64; 4] = std::array::from_fn(|i| x[i] - h * d[i]);
            let fd = (num(&xp, k) - num(&xm, k)) / (2.0 * h);
            let an = numerator_rate(&p.derivs(x[0], x[1]), &q.derivs(x[2], x[3]), &d, k);
            assert!(
                (fd - an).abs() < 1e-7 * (1.0 + an.abs()),
                "k {k}: {fd} vs {an}"
            );
        }
    }
}
