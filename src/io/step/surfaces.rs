//! STEP surfaces as NURBS surfaces: B-spline surfaces as written, elementary surfaces by their
//! exact rational representations with interval control data.
//!
//! - A placement `AXIS2_PLACEMENT_3D` becomes an orthonormal frame in interval arithmetic
//!   (normalised axis, reference direction projected and normalised), so every control point
//!   below encloses the exact one for the numbers in the file.
//! - A full turn about the axis is four quarter arcs of the rational quadratic circle: knots
//!   `0,0,0,1,1,2,2,3,3,4,4,4`, corner weights `√2/2` (an interval). Its parameter is not the
//!   STEP angle: `u ∈ [0, 4]`, one unit per quarter turn, starting at the reference direction.
//! - `PLANE`: degree 1×1 over the box given (the STEP parameters: `P = O + u·X + v·Y`).
//! - `CYLINDRICAL_SURFACE`, `CONICAL_SURFACE`: a full turn × degree 1 in the STEP height `v`
//!   over the range given (`radius + v·tan(semi_angle)` for a cone; `tan` by interval Taylor
//!   series of sine and cosine with a proven remainder).
//! - `SPHERICAL_SURFACE`: a full turn × a half circle from the pole at `−axis` to `+axis`
//!   (knots `0,0,0,1,1,2,2,2`): the standard 9×5 net.
//! - `TOROIDAL_SURFACE`: a full turn × a full turn of the tube circle (starting on the outside,
//!   towards `+axis`).

use super::entities::{step_error, Args, Entities};
use crate::error::Result;
use crate::geometry::nurbs::NurbsSurface;
use crate::numeric::scalar::point;
use inari::Interval;

/// A vector with interval components.
pub(super) type IVec = [Interval; 3];

/// An orthonormal frame enclosing the exact one of a placement.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    pub(super) origin: IVec,
    pub(super) x: IVec,
    pub(super) y: IVec,
    pub(super) z: IVec,
}

fn dot(a: &IVec, b: &IVec) -> Interval {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &IVec, b: &IVec) -> IVec {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn ivec(p: [f64; 3]) -> IVec {
    p.map(point)
}

/// `a / |a|`, or `None` when `|a|` may be zero.
fn normalise(a: &IVec) -> Option<IVec> {
    let n = dot(a, a).sqrt();
    (n.inf() > 0.0 && n.sup().is_finite()).then(|| a.map(|c| c / n))
}

/// The midpoint of an interval vector.
pub(super) fn mid(a: &IVec) -> [f64; 3] {
    a.map(|c| c.mid())
}

/// `√2 / 2`, enclosed.
fn half_sqrt2() -> Interval {
    point(2.0).sqrt() / point(2.0)
}

/// sin and cos of `x` (|x| ≤ 4) by their Taylor series to 30 terms plus the Lagrange remainder.
fn sin_cos(x: Interval) -> Option<(Interval, Interval)> {
    if x.mag().is_nan() || x.mag() > 4.0 {
        return None;
    }
    let mut term = point(1.0); // x^k / k!
    let (mut s, mut c) = (point(0.0), point(0.0));
    let terms = 30;
    for k in 0..terms {
        match k % 4 {
            0 => c += term,
            1 => s += term,
            2 => c -= term,
            _ => s -= term,
        }
        term = term * x / point((k + 1) as f64);
    }
    // |remainder| ≤ |x|^terms / terms!, which `term` now encloses.
    let r = Interval::try_from((-term.mag(), term.mag())).ok()?;
    Some((s + r, c + r))
}

/// The points of a CARTESIAN_POINT with three coordinates.
pub(super) fn cartesian_point(e: &Entities<'_>, id: u64) -> Result<[f64; 3]> {
    let a = e.record(id, &["CARTESIAN_POINT"])?;
    let c = a.reals(1)?;
    <[f64; 3]>::try_from(c.as_slice())
        .map_err(|_| step_error(id, format!("{} coordinates where 3 are needed", c.len())))
}

fn direction(e: &Entities<'_>, id: u64) -> Result<[f64; 3]> {
    let a = e.record(id, &["DIRECTION"])?;
    let c = a.reals(1)?;
    <[f64; 3]>::try_from(c.as_slice())
        .map_err(|_| step_error(id, format!("{} ratios where 3 are needed", c.len())))
}

/// The frame of an AXIS2_PLACEMENT_3D (ISO 10303-42 `build_axes`: axis default `+z`, reference
/// direction default `+x`, or `+y` when the axis is along `x`).
pub(super) fn placement(e: &Entities<'_>, id: u64) -> Result<Frame> {
    let a = e.record(id, &["AXIS2_PLACEMENT_3D"])?;
    let origin = ivec(cartesian_point(e, a.reference(1)?)?);
    let axis = match a.opt_ref(2)? {
        Some(d) => direction(e, d)?,
        None => [0.0, 0.0, 1.0],
    };
    let z = normalise(&ivec(axis)).ok_or_else(|| step_error(id, "axis of zero length"))?;
    let r = match a.opt_ref(3)? {
        Some(d) => direction(e, d)?,
        None if axis[1] == 0.0 && axis[2] == 0.0 => [0.0, 1.0, 0.0],
        None => [1.0, 0.0, 0.0],
    };
    let r = ivec(r);
    let rz = dot(&r, &z);
    let proj = [r[0] - rz * z[0], r[1] - rz * z[1], r[2] - rz * z[2]];
    let x = normalise(&proj)
        .ok_or_else(|| step_error(id, "reference direction along the axis (or of zero length)"))?;
    let y = cross(&z, &x);
    Ok(Frame { origin, x, y, z })
}

/// `o + a·X + b·Y + c·Z`.
fn at(f: &Frame, a: Interval, b: Interval, c: Interval) -> IVec {
    [0, 1, 2].map(|k| f.origin[k] + a * f.x[k] + b * f.y[k] + c * f.z[k])
}

/// The rational quadratic full circle: `(cos-like, sin-like, weight)` of its nine control points.
fn circle() -> [(f64, f64, Interval); 9] {
    let (one, s) = (point(1.0), half_sqrt2());
    [
        (1.0, 0.0, one),
        (1.0, 1.0, s),
        (0.0, 1.0, one),
        (-1.0, 1.0, s),
        (-1.0, 0.0, one),
        (-1.0, -1.0, s),
        (0.0, -1.0, one),
        (1.0, -1.0, s),
        (1.0, 0.0, one),
    ]
}

const CIRCLE_KNOTS: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];

/// The surface swept by a profile `(ρ, z, weight)` (degree `vdeg`, knots `vknots`) turned once
/// about the frame's axis: `ρ` measured from the axis, `z` along it.
fn revolve(
    id: u64,
    f: &Frame,
    profile: &[(Interval, Interval, Interval)],
    vdeg: usize,
    vknots: Vec<f64>,
) -> Result<NurbsSurface> {
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (cx, cy, wu) in circle() {
        for &(rho, z, wv) in profile {
            points.push(at(f, rho * point(cx), rho * point(cy), z));
            weights.push(wu * wv);
        }
    }
    NurbsSurface::new(
        [2, vdeg],
        [CIRCLE_KNOTS.to_vec(), vknots],
        points,
        Some(weights),
    )
    .map_err(|e| step_error(id, format!("its NURBS form is not valid: {e}")))
}

/// A NURBS surface from a `PLANE`, given the box.
pub(super) fn plane(
    e: &Entities<'_>,
    a: Args<'_>,
    u: [f64; 2],
    v: [f64; 2],
) -> Result<NurbsSurface> {
    let f = placement(e, a.reference(1)?)?;
    let mut points = Vec::new();
    for su in u {
        for sv in v {
            points.push(at(&f, point(su), point(sv), point(0.0)));
        }
    }
    NurbsSurface::new(
        [1, 1],
        [vec![u[0], u[0], u[1], u[1]], vec![v[0], v[0], v[1], v[1]]],
        points,
        None,
    )
    .map_err(|err| step_error(a.id, format!("its NURBS form is not valid: {err}")))
}

fn positive(a: &Args<'_>, k: usize) -> Result<f64> {
    let r = a.real(k)?;
    if r > 0.0 {
        Ok(r)
    } else {
        Err(step_error(
            a.id,
            format!("{} parameter {k}: {r} is not positive", a.name()),
        ))
    }
}

/// A NURBS surface from a `CYLINDRICAL_SURFACE` or `CONICAL_SURFACE` over heights `v`.
/// `angle` converts the file's plane angles to radians.
pub(super) fn cylinder_or_cone(
    e: &Entities<'_>,
    a: Args<'_>,
    v: [f64; 2],
    angle: Interval,
) -> Result<NurbsSurface> {
    let f = placement(e, a.reference(1)?)?;
    let r = point(a.real(2)?);
    if r.inf() < 0.0 {
        return Err(step_error(a.id, "a negative radius"));
    }
    let slope = if a.name() == "CONICAL_SURFACE" {
        let (s, c) = sin_cos(point(a.real(3)?) * angle)
            .ok_or_else(|| step_error(a.id, "semi-angle out of range"))?;
        if c.inf().is_nan() || c.inf() <= 0.0 {
            return Err(step_error(a.id, "semi-angle not below a right angle"));
        }
        s / c
    } else {
        point(0.0)
    };
    let one = point(1.0);
    let profile = v.map(|h| (r + point(h) * slope, point(h), one));
    revolve(a.id, &f, &profile, 1, vec![v[0], v[0], v[1], v[1]])
}

/// A NURBS surface from a `SPHERICAL_SURFACE` (the whole sphere).
pub(super) fn sphere(e: &Entities<'_>, a: Args<'_>) -> Result<NurbsSurface> {
    let f = placement(e, a.reference(1)?)?;
    let r = point(positive(&a, 2)?);
    let (zero, one, s) = (point(0.0), point(1.0), half_sqrt2());
    let profile = [
        (zero, -r, one),
        (r, -r, s),
        (r, zero, one),
        (r, r, s),
        (zero, r, one),
    ];
    revolve(
        a.id,
        &f,
        &profile,
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
    )
}

/// A NURBS surface from a `TOROIDAL_SURFACE` (the whole torus).
pub(super) fn torus(e: &Entities<'_>, a: Args<'_>) -> Result<NurbsSurface> {
    let f = placement(e, a.reference(1)?)?;
    let big = point(positive(&a, 2)?);
    let small = point(positive(&a, 3)?);
    let profile: Vec<_> = circle()
        .iter()
        .map(|&(cx, cy, w)| (big + small * point(cx), small * point(cy), w))
        .collect();
    revolve(a.id, &f, &profile, 2, CIRCLE_KNOTS.to_vec())
}

/// The knot vector from distinct knots and multiplicities, for `count` control points of
/// degree `p` (checked before anything is allocated).
fn expand_knots(
    a: &Args<'_>,
    k: usize,
    mults: &[usize],
    knots: &[f64],
    count: usize,
    p: usize,
) -> Result<Vec<f64>> {
    if mults.len() != knots.len() {
        return Err(step_error(
            a.id,
            format!(
                "{} parameter {k}: {} multiplicities for {} knots",
                a.name(),
                mults.len(),
                knots.len()
            ),
        ));
    }
    let total: usize = mults.iter().sum();
    if total != count + p + 1 {
        return Err(step_error(
            a.id,
            format!(
                "{} parameter {k}: multiplicities add up to {total} where {count} control points of degree {p} need {}",
                a.name(),
                count + p + 1
            ),
        ));
    }
    Ok(knots
        .iter()
        .zip(mults)
        .flat_map(|(&t, &m)| std::iter::repeat_n(t, m))
        .collect())
}

/// The most Bézier control points a B-spline surface of a STEP file may split into.
pub const MAX_BEZIER_POINTS: usize = 1 << 24;

/// A NURBS surface from a `B_SPLINE_SURFACE_WITH_KNOTS`, simple or the complex instance with
/// `B_SPLINE_SURFACE`, `B_SPLINE_SURFACE_WITH_KNOTS` and possibly `RATIONAL_B_SPLINE_SURFACE`.
pub(super) fn bspline(e: &Entities<'_>, id: u64) -> Result<NurbsSurface> {
    let inst = e.get(id)?;
    // Attribute positions: (record, first index) of the B_SPLINE_SURFACE and WITH_KNOTS parts.
    let (base, b0, kn, k0) = match inst {
        super::part21::Instance::Simple(_) => {
            let a = e.record(id, &["B_SPLINE_SURFACE_WITH_KNOTS"])?;
            (a, 1, a, 8)
        }
        super::part21::Instance::Complex(_) => (
            e.record(id, &["B_SPLINE_SURFACE"])?,
            0,
            e.record(id, &["B_SPLINE_SURFACE_WITH_KNOTS"])?,
            0,
        ),
    };
    let p = base.int(b0, 1, 64)? as usize;
    let q = base.int(b0 + 1, 1, 64)? as usize;
    let rows = base.ref_rows(b0 + 2)?;
    let nu = rows.len();
    let nv = rows.first().map_or(0, |r| r.len());
    if nu == 0 || nv == 0 || rows.iter().any(|r| r.len() != nv) {
        return Err(step_error(
            id,
            "control points are not a non-empty rectangular array",
        ));
    }
    let um = kn.ints(k0, 1, 65)?;
    let vm = kn.ints(k0 + 1, 1, 65)?;
    let uk = kn.reals(k0 + 2)?;
    let vk = kn.reals(k0 + 3)?;
    let uknots = expand_knots(&kn, k0, &um, &uk, nu, p)?;
    let vknots = expand_knots(&kn, k0 + 1, &vm, &vk, nv, q)?;
    // The Bézier split makes one piece per pair of knot spans, each (p+1)(q+1) points: refuse
    // what would not fit in memory before splitting.
    let spans = |k: &[f64]| k.windows(2).filter(|w| w[0] < w[1]).count().max(1);
    let pieces = spans(&uknots) * spans(&vknots);
    if pieces.saturating_mul((p + 1) * (q + 1)) > MAX_BEZIER_POINTS {
        return Err(step_error(
            id,
            format!("{pieces} Bézier pieces of degree ({p}, {q}): too many to split"),
        ));
    }
    let mut points = Vec::with_capacity(nu * nv);
    for row in &rows {
        for &pt in row {
            points.push(ivec(cartesian_point(e, pt)?));
        }
    }
    let weights = match inst.record("RATIONAL_B_SPLINE_SURFACE") {
        Some(r) => {
            let w = Args { id, record: r }.real_rows(0)?;
            if w.len() != nu || w.iter().any(|r| r.len() != nv) {
                return Err(step_error(id, "weights do not match the control points"));
            }
            Some(w.into_iter().flatten().map(point).collect())
        }
        None => None,
    };
    NurbsSurface::new([p, q], [uknots, vknots], points, weights)
        .map_err(|err| step_error(id, format!("not a valid B-spline surface: {err}")))
}

/// Plane angles of a file in radians: the factor of a `CONVERSION_BASED_UNIT` plane angle unit
/// (its `PLANE_ANGLE_MEASURE_WITH_UNIT`'s value, as written), else 1.
pub(super) fn angle_factor(e: &Entities<'_>) -> Result<Interval> {
    for id in &e.file.order {
        let inst = e.get(*id)?;
        if inst.record("PLANE_ANGLE_UNIT").is_none() {
            continue;
        }
        if let Some(r) = inst.record("CONVERSION_BASED_UNIT") {
            let m = Args { id: *id, record: r }.reference(1)?;
            let factor = e.record(m, &["PLANE_ANGLE_MEASURE_WITH_UNIT", "MEASURE_WITH_UNIT"])?;
            let x = factor.real(0)?;
            if x <= 0.0 {
                return Err(step_error(m, "a plane angle unit that is not positive"));
            }
            return Ok(point(x));
        }
    }
    Ok(point(1.0))
}
