//! What the bounds of a face tell the reader: how far the face reaches along given directions
//! (for the parameter box of a plane, cylinder or cone) and whether its boundary is only the
//! surface's own seams (then the face is its whole surface and not trimmed).
//!
//! The reach is taken from the boundary's vertices, the full extent of its circles and ellipses,
//! and the control points of its B-spline curves and polylines (a B-spline curve lies in the
//! hull of its control points); it is computed in `f64` and only chooses the box: the
//! intersection is certified on the box's surface patch, whatever the box is.

use super::entities::{step_error, Entities};
use super::surfaces::{cartesian_point, mid, placement};
use crate::error::Result;

/// A piece of a face's boundary, as far as its reach is concerned.
#[derive(Debug, Clone, Copy)]
enum Reach {
    /// A point.
    Point([f64; 3]),
    /// An ellipse: centre, first and second semi-axis vectors.
    Ellipse([f64; 3], [f64; 3], [f64; 3]),
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The bounds of a face, gathered.
#[derive(Debug, Default)]
pub(super) struct Boundary {
    reach: Vec<Reach>,
    /// Whether every bound is a vertex loop or a loop of seam edges (or of circles about
    /// `axis`, when the surface has one).
    pub(super) natural: bool,
    /// The first edge curve of a type whose reach is not known (`#n` and its entity name); such
    /// an edge is not natural, and its reach is missing from [`Boundary::range`].
    pub(super) unknown: Option<(u64, String)>,
}

impl Boundary {
    /// `[min, max]` of `(x − origin)·d` over the boundary, or `None` without any boundary.
    pub(super) fn range(&self, origin: [f64; 3], d: [f64; 3]) -> Option<[f64; 2]> {
        let mut out: Option<[f64; 2]> = None;
        for r in &self.reach {
            let (c, h) = match r {
                Reach::Point(p) => (*p, 0.0),
                Reach::Ellipse(c, a, b) => (*c, dot(a, &d).hypot(dot(b, &d))),
            };
            let s = dot(&[c[0] - origin[0], c[1] - origin[1], c[2] - origin[2]], &d);
            let [lo, hi] = out.get_or_insert([s - h, s + h]);
            *lo = lo.min(s - h);
            *hi = hi.max(s + h);
        }
        out
    }
}

/// The bounds of face `face` (its `FACE_BOUND`s `bounds`); `axis` is the surface's axis,
/// whose circles count as natural edges (the ends of a cylinder or cone face).
pub(super) fn boundary(
    e: &Entities<'_>,
    bounds: &[u64],
    axis: Option<[f64; 3]>,
) -> Result<Boundary> {
    let mut b = Boundary {
        natural: true,
        ..Boundary::default()
    };
    for &fb in bounds {
        let bound = e.record(fb, &["FACE_OUTER_BOUND", "FACE_BOUND"])?;
        let lp = bound.reference(1)?;
        let inst = e.get(lp)?;
        if let Some(r) = inst.record("VERTEX_LOOP") {
            let v = super::entities::Args { id: lp, record: r }.reference(1)?;
            b.reach.push(Reach::Point(vertex(e, v)?));
        } else if let Some(r) = inst.record("POLY_LOOP") {
            b.natural = false;
            for p in (super::entities::Args { id: lp, record: r }).refs(1)? {
                b.reach.push(Reach::Point(cartesian_point(e, p)?));
            }
        } else {
            let edges = e.record(lp, &["EDGE_LOOP"])?.refs(1)?;
            for oe in edges {
                let edge = e.record(oe, &["ORIENTED_EDGE", "EDGE_CURVE"])?;
                let ec = if edge.name() == "ORIENTED_EDGE" {
                    edge.reference(3)?
                } else {
                    oe
                };
                let ec = e.record(ec, &["EDGE_CURVE"])?;
                b.reach.push(Reach::Point(vertex(e, ec.reference(1)?)?));
                b.reach.push(Reach::Point(vertex(e, ec.reference(2)?)?));
                let natural = curve(e, ec.reference(3)?, axis, &mut b, 0)?;
                b.natural &= natural;
            }
        }
    }
    Ok(b)
}

fn vertex(e: &Entities<'_>, id: u64) -> Result<[f64; 3]> {
    let v = e.record(id, &["VERTEX_POINT"])?;
    cartesian_point(e, v.reference(1)?)
}

/// Adds the reach of curve `id`; whether it is a natural edge (a seam, or a circle about
/// `axis`).
fn curve(
    e: &Entities<'_>,
    id: u64,
    axis: Option<[f64; 3]>,
    b: &mut Boundary,
    depth: usize,
) -> Result<bool> {
    let reach = &mut b.reach;
    if depth > 4 {
        return Err(step_error(id, "curves nested too deeply"));
    }
    let inst = e.get(id)?;
    let name = inst.name();
    if let Some(r) = inst.record("B_SPLINE_CURVE") {
        // A complex (rational) B-spline curve: the control points are parameter 1.
        for p in (super::entities::Args { id, record: r }).refs(1)? {
            reach.push(Reach::Point(cartesian_point(e, p)?));
        }
        return Ok(false);
    }
    let found = e.record(
        id,
        &[
            "LINE",
            "CIRCLE",
            "ELLIPSE",
            "B_SPLINE_CURVE_WITH_KNOTS",
            "POLYLINE",
            "SEAM_CURVE",
            "SURFACE_CURVE",
            "INTERSECTION_CURVE",
            "TRIMMED_CURVE",
        ],
    );
    let Ok(a) = found else {
        b.unknown.get_or_insert((id, name));
        return Ok(false);
    };
    match a.name() {
        // A line edge is the segment between its vertices, which are already counted.
        "LINE" => Ok(false),
        "CIRCLE" | "ELLIPSE" => {
            let f = placement(e, a.reference(1)?)?;
            let r1 = a.real(2)?;
            let r2 = if a.name() == "CIRCLE" { r1 } else { a.real(3)? };
            let (x, y, z) = (mid(&f.x), mid(&f.y), mid(&f.z));
            let c = mid(&f.origin);
            reach.push(Reach::Ellipse(c, x.map(|t| t * r1), y.map(|t| t * r2)));
            Ok(a.name() == "CIRCLE" && axis.is_some_and(|ax| dot(&ax, &z).abs() > 1.0 - 1e-12))
        }
        "B_SPLINE_CURVE_WITH_KNOTS" | "POLYLINE" => {
            let k = if a.name() == "POLYLINE" { 1 } else { 2 };
            for p in a.refs(k)? {
                reach.push(Reach::Point(cartesian_point(e, p)?));
            }
            Ok(false)
        }
        "SEAM_CURVE" => {
            curve(e, a.reference(1)?, axis, b, depth + 1)?;
            Ok(true)
        }
        // SURFACE_CURVE, INTERSECTION_CURVE (the 3D curve), TRIMMED_CURVE (its basis curve).
        _ => curve(e, a.reference(1)?, axis, b, depth + 1),
    }
}
