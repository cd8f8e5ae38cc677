//! Certified edges on surfaces whose parameter domains are scaled unlike each other (issue 11):
//! the rational sphere patch of `scenes/sphere_patch_plane.json` over a domain of sides 50 and
//! 0.02 (so `|∂Q/∂v|` is 2500 times `|∂Q/∂u|`) against the plane `x = 1.375`. The intersection
//! is the circle `x = 1.375`, `y² + z² = 141/256`, whatever the parametrisation; the edge's
//! proven tolerance must meet the requested one, and the curve and the p-curves' images are
//! checked against the circle, sampled densely.
//!
//! Before the p-curve image bounds kept each parameter's fit error apart, the fit error in the
//! long parameter was multiplied by the short parameter's derivative, and the p-curve on the
//! rescaled surface stayed above the request however the knots were refined.

mod common;

use common::spline::{dist_to_spline, samples, yz_angle_range};
use ssitrace::edge::{edge_from_branch_within, Edge};
use ssitrace::geometry::Domain;
use ssitrace::{intersect, Method, Options, RationalBezierPatch};

/// Rounding slack of evaluating the splines and the truth in f64.
const SLACK: f64 = 1e-13;
/// The requested tolerance.
const TOL: f64 = 1e-9;

/// Distance from `x` to the circle `x = 1.375`, `y² + z² = 141/256`.
fn off_circle(x: &[f64; 3]) -> f64 {
    let r = (141.0f64 / 256.0).sqrt();
    let rho = (x[1] * x[1] + x[2] * x[2]).sqrt();
    ((x[0] - 1.375).powi(2) + (rho - r).powi(2)).sqrt()
}

/// The rational sphere patch (degree 2 × 2, radius 1.5625 about the origin) over `domain`.
fn sphere(domain: Domain) -> RationalBezierPatch {
    let net = [
        [1.0, -0.75, -0.9375],
        [1.5625, -1.171875, 0.0],
        [1.0, -0.75, 0.9375],
        [1.5625, 0.0, -0.9375],
        [2.44140625, 0.0, 0.0],
        [1.5625, 0.0, 0.9375],
        [1.0, 0.75, -0.9375],
        [1.5625, 1.171875, 0.0],
        [1.0, 0.75, 0.9375],
    ];
    let w = [25.0, 20.0, 25.0, 20.0, 16.0, 20.0, 25.0, 20.0, 25.0];
    RationalBezierPatch::from_f64_points([2, 2], &net, Some(&w), domain).unwrap()
}

/// The plane `x = 1.375` over `domain`.
fn plane(domain: Domain) -> RationalBezierPatch {
    let net = [
        [1.375, -1.0, -1.0],
        [1.375, -1.0, 1.0],
        [1.375, 1.0, -1.0],
        [1.375, 1.0, 1.0],
    ];
    RationalBezierPatch::from_f64_points([1, 1], &net, None, domain).unwrap()
}

/// The edge of the single certified branch of `P ∩ Q`, aiming at [`TOL`].
fn the_edge(p: &RationalBezierPatch, q: &RationalBezierPatch) -> Edge {
    let opts = Options {
        method: Method::Validated,
        step: 0.02,
        required_tolerance: TOL,
        ..Options::default()
    };
    let r = intersect(p, q, &opts).expect("runs");
    assert_eq!(r.branches.len(), 1);
    edge_from_branch_within(p, q, &r.branches[0], Some(TOL)).expect("an edge")
}

/// The edge's tolerance meets the request, and the curve and the p-curves' images are within
/// their proven tolerances of the circle (and the circle within the edge's of the curve).
fn check(what: &str, e: &Edge, surf: [&RationalBezierPatch; 2], unit_points: usize) {
    eprintln!(
        "{what}: {} control points, {} links, tolerance {:.3e} (P image {:.3e}, Q image \
         {:.3e}, P param {:.3e}, Q param {:.3e})",
        e.curve.points.len(),
        e.links,
        e.edge_tolerance,
        e.bounds.pcurve_p_image,
        e.bounds.pcurve_q_image,
        e.bounds.pcurve_p_param,
        e.bounds.pcurve_q_param
    );
    assert!(e.edge_tolerance <= TOL, "{what}: {:e}", e.edge_tolerance);
    // Few control points: the rescaled domain costs at most half as many again as the same
    // circle on the unit domain.
    assert!(
        2 * e.curve.points.len() <= 3 * unit_points,
        "{what}: {} control points against {unit_points} on the unit domain",
        e.curve.points.len()
    );
    let ss = samples(&e.curve, 64);
    let pts: Vec<[f64; 3]> = ss.iter().map(|&s| e.curve.eval(s)).collect();
    for x in &pts {
        assert!(off_circle(x) <= e.edge_tolerance + SLACK, "{what}: {x:?}");
    }
    // The circle to the curve, over the arc the curve spans.
    let (a0, a1) = yz_angle_range(&pts, e.closed);
    let r0 = (141.0f64 / 256.0).sqrt();
    for m in 0..=1000 {
        let a = a0 + (a1 - a0) * m as f64 / 1000.0;
        let x = [1.375, r0 * a.cos(), r0 * a.sin()];
        let d = dist_to_spline(&e.curve, &ss, &pts, &x);
        assert!(
            d <= e.edge_tolerance + SLACK,
            "{what}: circle at {a}: {d:e}"
        );
    }
    for c in &e.pcurves {
        assert!(c.image_tolerance <= e.edge_tolerance);
        for s in samples(&c.curve, 64) {
            let [a, b] = c.curve.eval(s);
            let d = off_circle(&surf[c.surface].point_f64(a, b));
            assert!(
                d <= c.image_tolerance + SLACK,
                "{what}: p-curve on {} at {s}: {d:e}",
                c.surface
            );
        }
    }
}

#[test]
fn an_edge_on_a_rescaled_surface_meets_the_request() {
    let long_short = Domain {
        u: [-3.0, 47.0],
        v: [2.0, 2.02],
    };
    let (p, q) = (plane(Domain::UNIT), sphere(Domain::UNIT));
    let unit = the_edge(&p, &q);
    eprintln!("unit domains: {} control points", unit.curve.points.len());
    let n = unit.curve.points.len();
    // The rescaled sphere as Q, then as P.
    let (p, q) = (plane(Domain::UNIT), sphere(long_short));
    check("rescaled Q", &the_edge(&p, &q), [&p, &q], n);
    let (p, q) = (sphere(long_short), plane(Domain::UNIT));
    check("rescaled P", &the_edge(&p, &q), [&p, &q], n);
}
