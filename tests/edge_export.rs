//! Edge export (`ssitrace::edge`): certified curves as a 3D B-spline, two p-curves and one
//! proven tolerance, checked against curves known in closed form (sampled densely both ways),
//! against the certified boxes, on a joined NURBS shell curve, and the typed errors.
//!
//! Truth is evaluated in f64; its error is a few ulps, far below the tolerances checked.

mod common;

use common::scenes::{scene, scene_path};
use common::spline::{dist3, dist_to_spline, samples, yz_angle_range};
use ssitrace::edge::{edge_from_branch, edge_from_certified, edges_of_shells, Edge, EdgeError};
use ssitrace::io::edge_json::{edges_document, EDGE_FORMAT};
use ssitrace::io::scene::{Scene, ShellScene};
use ssitrace::pipeline::RunOptions;
use ssitrace::shell::intersect_shells;
use ssitrace::{intersect, Method, Options, RationalBezierPatch, SurfaceIntersection};

/// Rounding slack of evaluating the splines and the truth in f64.
const SLACK: f64 = 1e-13;

fn run(s: &Scene, method: Method) -> SurfaceIntersection {
    let [p, q] = &s.surfaces;
    let opts = Options {
        method,
        ..RunOptions::from_scene(s).options()
    };
    intersect(p, q, &opts).expect("runs")
}

/// Distance from `x` to the circle `x = 1.375`, `y² + z² = 141/256`.
fn off_sphere_circle(x: &[f64; 3]) -> f64 {
    let r = (141.0f64 / 256.0).sqrt();
    let rho = (x[1] * x[1] + x[2] * x[2]).sqrt();
    ((x[0] - 1.375).powi(2) + (rho - r).powi(2)).sqrt()
}

fn the_edge(s: &Scene, r: &SurfaceIntersection) -> Edge {
    assert_eq!(r.branches.len(), 1);
    let [p, q] = &s.surfaces;
    edge_from_branch(p, q, &r.branches[0]).expect("an edge")
}

fn report(name: &str, e: &Edge) {
    eprintln!(
        "{name}: {} control points, {} p-curves, {} links, closed {}, edge_tolerance {:.3e} \
         (certified {:.3e}, 3D {:.3e}, fit {:.3e}, P image {:.3e}, Q image {:.3e}, cuts {:.3e})",
        e.curve.points.len(),
        e.pcurves.len(),
        e.links,
        e.closed,
        e.edge_tolerance,
        e.bounds.certified_tolerance,
        e.bounds.curve_3d,
        e.bounds.model_fit,
        e.bounds.pcurve_p_image,
        e.bounds.pcurve_q_image,
        e.bounds.cuts
    );
}

/// Every image point of a p-curve on its surface, sampled, within `tol` of the curve `off`.
fn pcurve_images(e: &Edge, surf: [&RationalBezierPatch; 2], off: &dyn Fn(&[f64; 3]) -> f64) {
    for c in &e.pcurves {
        assert!(c.image_tolerance <= e.edge_tolerance);
        for s in samples(&c.curve, 64) {
            let [a, b] = c.curve.eval(s);
            let x = surf[c.surface].point_f64(a, b);
            let d = off(&x);
            assert!(
                d <= c.image_tolerance + SLACK,
                "p-curve on surface {} at s = {s}: {d:e} > {:e}",
                c.surface,
                c.image_tolerance
            );
        }
    }
}

#[test]
fn the_sphere_plane_circle_is_within_the_edge_tolerance_both_ways() {
    let s = scene("sphere_patch_plane.json");
    let r = run(&s, Method::Validated);
    let e = the_edge(&s, &r);
    report("sphere_patch_plane", &e);
    let cert = r.branches[0].certified().unwrap();
    let tol = e.edge_tolerance;
    assert!(tol >= cert.certified_tolerance);
    assert!(tol <= 1e-8, "{tol:e}");
    assert_eq!(e.curve.degree, 8);
    assert_eq!(e.curve.knots.len(), e.curve.points.len() + 9);
    assert_eq!(e.pcurves.len(), 2);
    // Spline to circle.
    let ss = samples(&e.curve, 200);
    let pts: Vec<[f64; 3]> = ss.iter().map(|&x| e.curve.eval(x)).collect();
    let worst = pts.iter().map(off_sphere_circle).fold(0.0, f64::max);
    eprintln!("sphere_patch_plane: largest sampled distance spline → circle {worst:.3e}");
    assert!(worst <= tol + SLACK, "{worst:e} > {tol:e}");
    // Circle to spline: the arc the spline spans (all of it when closed).
    let (a0, a1) = yz_angle_range(&pts, e.closed);
    let r0 = (141.0f64 / 256.0).sqrt();
    let mut back = 0.0f64;
    for m in 0..=2000 {
        let a = a0 + (a1 - a0) * m as f64 / 2000.0;
        let x = [1.375, r0 * a.cos(), r0 * a.sin()];
        back = back.max(dist_to_spline(&e.curve, &ss, &pts, &x));
    }
    eprintln!("sphere_patch_plane: largest sampled distance circle → spline {back:.3e}");
    assert!(back <= tol + SLACK, "{back:e} > {tol:e}");
    // The p-curves through P and Q.
    let [p, q] = &s.surfaces;
    pcurve_images(&e, [p, q], &off_sphere_circle);
    // The closed edge ends where it starts.
    if e.closed {
        assert_eq!(e.curve.points.first(), e.curve.points.last());
    }
    // The document: one edge, numbered by its branch, the numbers as computed.
    let doc = edges_document(Some("sphere"), "branch", &[(0, Ok(e.clone()))]);
    let v = &doc["edges"][0];
    assert_eq!(v["branch"], 0);
    assert_eq!(v["edge_tolerance"].as_f64(), Some(tol));
    assert_eq!(v["curve"]["degree"], 8);
    assert_eq!(
        v["curve"]["control_points"].as_array().unwrap().len(),
        e.curve.points.len()
    );
    assert_eq!(v["pcurves"][0]["surface"], "P");
    assert_eq!(v["pcurves"][1]["surface"], "Q");
    assert!(doc["skipped"].as_array().unwrap().is_empty());
}

#[test]
fn the_bicubic_edge_stays_within_the_certified_boxes() {
    let s = scene("bicubic_transversal.json");
    let r = run(&s, Method::Validated);
    let [p, q] = &s.surfaces;
    let mut edges = 0;
    for b in &r.branches {
        let Some(cert) = b.certified() else { continue };
        let e = edge_from_branch(p, q, b).expect("an edge");
        report("bicubic_transversal", &e);
        edges += 1;
        assert!(e.edge_tolerance >= cert.certified_tolerance);
        let tol = e.edge_tolerance;
        let to_box = |x: &[f64; 3], bx: &[inari::Interval; 3]| {
            (0..3)
                .map(|i| {
                    (bx[i].inf() - x[i])
                        .max(x[i] - bx[i].sup())
                        .max(0.0)
                        .powi(2)
                })
                .sum::<f64>()
                .sqrt()
        };
        let near_boxes = |x: &[f64; 3]| {
            cert.boxes
                .iter()
                .map(|bx| to_box(x, &bx.xyz))
                .fold(f64::INFINITY, f64::min)
        };
        let ss = samples(&e.curve, 50);
        let pts: Vec<[f64; 3]> = ss.iter().map(|&x| e.curve.eval(x)).collect();
        for (x, sv) in pts.iter().zip(&ss) {
            let d = near_boxes(x);
            assert!(
                d <= tol + SLACK,
                "3D curve at s = {sv}: {d:e} from the boxes"
            );
        }
        for c in &e.pcurves {
            let surf = if c.surface == 0 { p } else { q };
            for sv in samples(&c.curve, 20) {
                let [a, bb] = c.curve.eval(sv);
                let d = near_boxes(&surf.point_f64(a, bb));
                assert!(d <= c.image_tolerance + SLACK, "p-curve image: {d:e}");
            }
        }
        // A boundary end is cut at the side: the p-curve of that surface ends on it.
        for (k, end) in cert.ends.iter().enumerate() {
            if let ssitrace::certify::CertifiedEnd::Boundary { surface } = end {
                let c = &e.pcurves[*surface];
                let x = if k == 0 {
                    c.curve.points[0]
                } else {
                    *c.curve.points.last().unwrap()
                };
                let d = [p, q][*surface].domain();
                let off = (0..2)
                    .map(|i| {
                        let r = if i == 0 { d.u } else { d.v };
                        (x[i] - r[0]).abs().min((x[i] - r[1]).abs())
                    })
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    off <= c.param_tolerance + SLACK,
                    "end {k}: {off:e} off the side"
                );
            }
        }
        // Each box holds true points, so meets the tolerance's neighbourhood of the spline:
        // the box's nearest sample is within the tolerance plus the sampling step.
        let step = pts
            .windows(2)
            .map(|w| dist3(&w[0], &w[1]))
            .fold(0.0, f64::max);
        for bx in &cert.boxes {
            let d = pts
                .iter()
                .map(|x| to_box(x, &bx.xyz))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= tol + step, "box at {:?}: {d:e}", bx.s);
        }
    }
    assert!(edges >= 1);
}

#[test]
fn the_nurbs_sphere_shell_gives_one_closed_edge() {
    let s = ShellScene::from_path(&scene_path("nurbs_sphere_plane.json")).unwrap();
    let opts = RunOptions::from_scene_options(&s.options).options();
    let r = intersect_shells(&s.shells[0], &s.shells[1], &opts).unwrap();
    assert_eq!(r.curves.len(), 1);
    let out = edges_of_shells(&s.shells[0], &s.shells[1], &r);
    assert_eq!(out.len(), 1);
    let e = out[0].1.as_ref().expect("an edge");
    report("nurbs_sphere_plane", e);
    assert!(e.closed);
    assert_eq!(e.branches.len(), 4);
    assert_eq!(e.curve.points.first(), e.curve.points.last());
    assert_eq!(e.pcurves.len(), 8, "one per part and surface");
    let tol = e.edge_tolerance;
    assert!(tol >= r.curves[0].certified_tolerance.unwrap());
    assert!(tol <= 1e-8, "{tol:e}");
    // The unit sphere against z = 0.3: the circle x² + y² = 0.91, z = 0.3.
    let off = |x: &[f64; 3]| {
        let rho = (x[0] * x[0] + x[1] * x[1]).sqrt();
        ((x[2] - 0.3).powi(2) + (rho - 0.91f64.sqrt()).powi(2)).sqrt()
    };
    let ss = samples(&e.curve, 100);
    let pts: Vec<[f64; 3]> = ss.iter().map(|&x| e.curve.eval(x)).collect();
    let worst = pts.iter().map(off).fold(0.0, f64::max);
    assert!(worst <= tol + SLACK, "{worst:e} > {tol:e}");
    let r0 = 0.91f64.sqrt();
    let mut back = 0.0f64;
    for m in 0..1000 {
        let a = 2.0 * std::f64::consts::PI * m as f64 / 1000.0;
        let x = [r0 * a.cos(), r0 * a.sin(), 0.3];
        back = back.max(dist_to_spline(&e.curve, &ss, &pts, &x));
    }
    eprintln!("nurbs_sphere_plane: spline → circle {worst:.3e}, circle → spline {back:.3e}");
    assert!(back <= tol + SLACK, "{back:e} > {tol:e}");
    // P-curves on the pieces they name.
    let mut seen = [0.0f64; 2];
    for c in &e.pcurves {
        let shell = &s.shells[c.surface];
        let patch = &shell[c.face].pieces()[c.piece];
        for sv in samples(&c.curve, 32) {
            let [a, b] = c.curve.eval(sv);
            let d = off(&patch.point_f64(a, b));
            seen[c.surface] = seen[c.surface].max(d);
            assert!(d <= c.image_tolerance + SLACK, "{d:e}");
        }
    }
    eprintln!("nurbs_sphere_plane: p-curve images off the circle by at most {seen:?} (sampled)");
    let doc = edges_document(Some("nurbs_sphere_plane"), "curve", &out);
    assert_eq!(doc["format"], EDGE_FORMAT);
    assert_eq!(doc["edges"][0]["closed"], true);
    assert_eq!(doc["edges"][0]["pcurves"].as_array().unwrap().len(), 8);
    // The joined curve's number does not hide the 3D curve.
    assert_eq!(doc["edges"][0]["curve_index"], 0);
    assert_eq!(
        doc["edges"][0]["curve"]["control_points"]
            .as_array()
            .unwrap()
            .len(),
        e.curve.points.len()
    );
    // Marched only: the joins rest on marched points, and no edge is made.
    let march = Options {
        method: Method::March,
        ..opts
    };
    let m = intersect_shells(&s.shells[0], &s.shells[1], &march).unwrap();
    let out = edges_of_shells(&s.shells[0], &s.shells[1], &m);
    assert!(
        matches!(out[0].1, Err(EdgeError::UnprovenJoin { .. })),
        "{:?}",
        out[0].1
    );
}

#[test]
fn an_uncertified_branch_is_a_typed_error() {
    let s = scene("sphere_patch_plane.json");
    let [p, q] = &s.surfaces;
    let marched = run(&s, Method::March);
    match edge_from_branch(p, q, &marched.branches[0]) {
        Err(EdgeError::NotCertified { branch, .. }) => assert_eq!(branch, marched.branches[0].id()),
        other => panic!("expected NotCertified, got {other:?}"),
    }
    // A chain with a link taken out has a gap.
    let r = run(&s, Method::Validated);
    let mut cert = r.branches[0].certified().unwrap().clone();
    assert!(cert.boxes.len() >= 3);
    let mid = cert.boxes.len() / 2;
    cert.boxes.remove(mid);
    cert.tubes.remove(mid);
    match edge_from_certified(p, q, &cert, 7) {
        Err(EdgeError::NotGapFree { branch: 7, .. }) => {}
        other => panic!("expected NotGapFree, got {other:?}"),
    }
    // A certificate without along-parameter pieces (the Taylor engine's form).
    let mut taylor = r.branches[0].certified().unwrap().clone();
    taylor.tubes[0].along = None;
    assert!(matches!(
        edge_from_certified(p, q, &taylor, 0),
        Err(EdgeError::NotCoverChain { branch: 0 })
    ));
}
