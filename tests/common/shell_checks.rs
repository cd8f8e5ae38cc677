//! Shell scenes and their checks against curves known in closed form: NURBS cylinders and
//! planes as scene JSON; every curve closed and proven; each edge's 3D B-spline and p-curves
//! within its tolerance of the truth both ways.

use super::spline::{dist3, dist_to_spline, samples};
use super::surfaces::UNIT_CIRCLE_NET;
use serde_json::{json, Value};
use ssitrace::edge::{edges_of_shells, Edge};
use ssitrace::io::scene::ShellScene;
use ssitrace::pipeline::{run_shells, RunOptions, ShellRunReport};
use ssitrace::shell::Face;
use std::f64::consts::PI;

/// Rounding slack of evaluating the splines and the truth in f64.
pub(crate) const SLACK: f64 = 1e-12;

/// An interval `[lo, hi]` as the scene format writes it.
pub(crate) fn iv(lo: f64, hi: f64) -> Value {
    json!([lo, hi])
}

/// `√2/2` enclosed (the nearest `f64` widened by an ulp each way).
pub(crate) fn half_sqrt2() -> Value {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    iv(h.next_down(), h.next_up())
}

/// A full NURBS cylinder of radius `r` about the coordinate axis `axis`, the axis coordinate in
/// `[-len, len]`: the standard nine-point circle of four quarters (degree 2, weights 1 and
/// `√2/2`) times a line (degree 1). With `turn = [c, s]` (a rational rotation, `c² + s² = 1`),
/// the circle's control points are turned by that angle, so its joints (knot lines and seam)
/// move off the coordinate axes; the turned coordinates are intervals of width 2e-15 round
/// the `f64` products, which enclose the exact ones.
pub(crate) fn cylinder(axis: usize, r: f64, len: f64, turn: Option<[f64; 2]>) -> Value {
    let circle = UNIT_CIRCLE_NET;
    let coord = |v: f64| match turn {
        None => json!(r * v),
        Some(_) => iv(r * v - 1e-15, r * v + 1e-15),
    };
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (k, &(a, b)) in circle.iter().enumerate() {
        let (a, b) = match turn {
            None => (a, b),
            Some([c, s]) => (a * c - b * s, a * s + b * c),
        };
        for h in [-len, len] {
            let mut p = vec![json!(0.0); 3];
            p[axis] = json!(h);
            p[(axis + 1) % 3] = coord(a);
            p[(axis + 2) % 3] = coord(b);
            points.push(Value::Array(p));
            weights.push(if k % 2 == 1 { half_sqrt2() } else { json!(1.0) });
        }
    }
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    json!({"kind": "nurbs", "degree": [2, 1], "knots": [knots, [0.0, 0.0, 1.0, 1.0]],
           "points": points, "weights": weights})
}

/// The paraboloid `z = (x − 0.45)² + (y − 0.55)²` over `[0, 1]²` as a non-rational biquadratic
/// B-spline with interior knots 1/4, 1/2, 3/4 both ways (control points by blossoming: exact
/// in binary).
pub(crate) fn bspline_paraboloid() -> Value {
    let t = [0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0];
    let nodes = |f: &dyn Fn(f64, f64) -> f64| -> Vec<f64> {
        (0..t.len() - 3).map(|i| f(t[i + 1], t[i + 2])).collect()
    };
    let xs = nodes(&|a, b| 0.5 * (a + b));
    let gx = nodes(&|a, b| (a - 0.45) * (b - 0.45));
    let gy = nodes(&|a, b| (a - 0.55) * (b - 0.55));
    let mut points = Vec::new();
    for i in 0..xs.len() {
        for j in 0..xs.len() {
            points.push(json!([xs[i], xs[j], gx[i] + gy[j]]));
        }
    }
    json!({"kind": "nurbs", "degree": [2, 2], "knots": [t, t], "points": points})
}

/// Four faces, each a quarter of x² + y² = 1, z ∈ [−1, 1] (one rational Bézier span, the
/// quarter from angle kπ/2 to (k + 1)π/2), sharing their edges.
pub(crate) fn quarter_cylinders() -> Vec<Value> {
    let c = UNIT_CIRCLE_NET;
    let quarter = |k: usize| {
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for (m, &(a, b)) in c[2 * k..=2 * k + 2].iter().enumerate() {
            for z in [-1.0, 1.0] {
                points.push(json!([a, b, z]));
                weights.push(if m == 1 { half_sqrt2() } else { json!(1.0) });
            }
        }
        json!({"kind": "nurbs", "degree": [2, 1],
               "knots": [[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], [0.0, 0.0, 1.0, 1.0]],
               "points": points, "weights": weights})
    };
    (0..4).map(quarter).collect()
}

/// The bilinear patch spanned by `origin + a·e1 + b·e2`, `a, b ∈ [0, 1]`.
pub(crate) fn plane(origin: [f64; 3], e1: [f64; 3], e2: [f64; 3]) -> Value {
    let at = |a: f64, b: f64| -> Vec<f64> {
        (0..3).map(|k| origin[k] + a * e1[k] + b * e2[k]).collect()
    };
    json!({"kind": "bezier", "degree": [1, 1],
           "points": [at(0.0, 0.0), at(0.0, 1.0), at(1.0, 0.0), at(1.0, 1.0)]})
}

/// The NURBS sphere of `scenes/nurbs_sphere_plane.json`, its coordinates taken in the order
/// `axes` (`[0, 1, 2]` as written, poles on z; `[2, 0, 1]` puts the poles on x).
pub(crate) fn nurbs_sphere(axes: [usize; 3]) -> Value {
    let text = std::fs::read_to_string(super::scenes::scene_path("nurbs_sphere_plane.json"))
        .expect("scene");
    let mut s: Value = serde_json::from_str(&text).expect("json");
    let mut sphere = s["surfaces"][0].take();
    for p in sphere["points"].as_array_mut().expect("points") {
        let c = p.as_array().expect("point").clone();
        *p = json!([c[axes[0]], c[axes[1]], c[axes[2]]]);
    }
    sphere
}

/// The faces of a split [`nurbs_sphere`]`(axes)`: face `[u0, u1, v0, v1]` is the part over
/// the knot spans `u ∈ [u0, u1]` (quarter turns, 0 to 4) and `v ∈ [v0, v1]` (0 to 2, pole to
/// pole), with its own clamped knot vectors (the sphere's, cut exactly). With `flip[0]`
/// (`flip[1]`), the face's rows in u (in v) are listed the other way round: the same surface,
/// that parameter reversed.
pub(crate) fn split_sphere(axes: [usize; 3], faces: &[([usize; 4], [bool; 2])]) -> Vec<Value> {
    let sphere = nurbs_sphere(axes);
    let (points, weights) = (&sphere["points"], &sphere["weights"]);
    let nv = 5;
    let knots = |lo: usize, hi: usize| -> Vec<usize> {
        let mut k = vec![lo];
        k.extend((lo..=hi).flat_map(|x| [x, x]));
        k.push(hi);
        k
    };
    faces
        .iter()
        .map(|&([u0, u1, v0, v1], flip)| {
            let mut rows: Vec<usize> = (2 * u0..=2 * u1).collect();
            let mut cols: Vec<usize> = (2 * v0..=2 * v1).collect();
            if flip[0] {
                rows.reverse();
            }
            if flip[1] {
                cols.reverse();
            }
            let at = |i: usize, j: usize| i * nv + j;
            let cells = || {
                rows.iter()
                    .flat_map(|&i| cols.iter().map(move |&j| at(i, j)))
            };
            json!({"kind": "nurbs", "degree": [2, 2],
                   "knots": [knots(u0, u1), knots(v0, v1)],
                   "points": cells().map(|c| points[c].clone()).collect::<Vec<_>>(),
                   "weights": cells().map(|c| weights[c].clone()).collect::<Vec<_>>()})
        })
        .collect()
}

/// The plane `y = k·x + e` over `|x| ≤ 2`, `|z| ≤ 2` (exact corners for `k` any `f64` and `e`
/// a power of two), its coordinates permuted like [`nurbs_sphere`]'s.
pub(crate) fn axis_plane(k: f64, e: f64, axes: [usize; 3]) -> Value {
    let corner = |x: f64, z: f64| {
        let c = [x, k * x + e, z];
        json!([c[axes[0]], c[axes[1]], c[axes[2]]])
    };
    json!({"kind": "bezier", "degree": [1, 1],
           "points": [corner(-2.0, -2.0), corner(-2.0, 2.0), corner(2.0, -2.0), corner(2.0, 2.0)]})
}

/// The scene of [`nurbs_sphere`]`(axes)` and [`axis_plane`]`(k, 0, axes)` (a plane holding the
/// sphere's axis), the sphere first or second.
pub(crate) fn sphere_and_axis_plane(axes: [usize; 3], k: f64, sphere_first: bool) -> Value {
    let (s, p) = (nurbs_sphere(axes), axis_plane(k, 0.0, axes));
    if sphere_first {
        json!({ "surfaces": [s, p] })
    } else {
        json!({ "surfaces": [p, s] })
    }
}

pub(crate) fn run(scene: Value) -> (ShellScene, ShellRunReport) {
    let scene = ShellScene::from_json_value(&scene).expect("scene");
    let opts = RunOptions::from_scene_options(&scene.options);
    let report = run_shells(&scene, &opts).expect("runs");
    (scene, report)
}

/// Checks the edge `e` both ways against a closed-form curve: `off(x)` bounds the distance
/// from `x` to it, `truth` are dense points of the part of it the edge covers. Also its
/// p-curves' images on the faces of `shells`. Returns the worst distances (curve to truth,
/// truth to curve).
pub(crate) fn check_edge(
    what: &str,
    e: &Edge,
    shells: &[Vec<Face>; 2],
    off: &dyn Fn(&[f64; 3]) -> f64,
    truth: &[[f64; 3]],
) -> (f64, f64) {
    check_edge_with(what, e, shells, off, truth, 5)
}

/// [`check_edge`] with at most `per_link` control points per certified link (instead of five).
pub(crate) fn check_edge_with(
    what: &str,
    e: &Edge,
    shells: &[Vec<Face>; 2],
    off: &dyn Fn(&[f64; 3]) -> f64,
    truth: &[[f64; 3]],
    per_link: usize,
) -> (f64, f64) {
    check_edge_within(what, e, shells, off, truth, per_link, 1e-9)
}

/// [`check_edge_with`] for an edge whose tolerance may be up to `most` (above the request,
/// with a stated shortfall when it is).
pub(crate) fn check_edge_within(
    what: &str,
    e: &Edge,
    shells: &[Vec<Face>; 2],
    off: &dyn Fn(&[f64; 3]) -> f64,
    truth: &[[f64; 3]],
    per_link: usize,
    most: f64,
) -> (f64, f64) {
    let tol = e.edge_tolerance;
    // Within `most` (the requested tolerance, the default 1e-9, unless said), and fewer
    // control points than `per_link` per link (the link-by-link construction has five).
    assert!(tol <= most, "{what}: tolerance {tol:e} above {most:e}");
    assert!(
        tol <= 1e-9 || e.shortfall.is_some(),
        "{what}: tolerance {tol:e} above the request, and no reason given"
    );
    assert!(
        e.curve.points.len() < per_link * e.links,
        "{what}: {} control points for {} links",
        e.curve.points.len(),
        e.links
    );
    // Samples, without repeats (a span of nearly zero length gives many copies of one point,
    // which would hide the neighbours the foot-point search brackets with).
    let (mut ss, mut pts) = (Vec::new(), Vec::<[f64; 3]>::new());
    for s in samples(&e.curve, 64) {
        let x = e.curve.eval(s);
        if pts.last().is_none_or(|l| dist3(l, &x) > 1e-12) {
            ss.push(s);
            pts.push(x);
        }
    }
    let there = pts.iter().map(off).fold(0.0, f64::max);
    assert!(
        there <= tol + SLACK,
        "{what}: a curve point {there:e} off the truth (tolerance {tol:e})"
    );
    let back = truth
        .iter()
        .map(|x| dist_to_spline(&e.curve, &ss, &pts, x))
        .fold(0.0, f64::max);
    assert!(
        back <= tol + SLACK,
        "{what}: a true point {back:e} off the curve (tolerance {tol:e})"
    );
    for c in &e.pcurves {
        assert!(c.image_tolerance <= tol);
        let piece = &shells[c.surface][c.face].pieces()[c.piece];
        for s in samples(&c.curve, 32) {
            let [a, b] = c.curve.eval(s);
            let d = off(&piece.point_f64(a, b));
            assert!(
                d <= c.image_tolerance + SLACK,
                "{what}: p-curve on surface {} face {} at s = {s}: {d:e} > {:e}",
                c.surface,
                c.face,
                c.image_tolerance
            );
        }
    }
    eprintln!(
        "{what}: {} control points, {} p-curves ({} control points each on average), \
         {} links, tolerance {tol:.2e}; curve to truth {there:.2e}, truth to curve {back:.2e}",
        e.curve.points.len(),
        e.pcurves.len(),
        e.pcurves
            .iter()
            .map(|c| c.curve.points.len())
            .sum::<usize>()
            / e.pcurves.len().max(1),
        e.links
    );
    (there, back)
}

/// Every curve of the report has an edge; returns them.
pub(crate) fn edges(what: &str, scene: &ShellScene, report: &ShellRunReport) -> Vec<Edge> {
    let [a, b] = &scene.shells;
    edges_of_shells(a, b, &report.result)
        .into_iter()
        .map(|(k, e)| e.unwrap_or_else(|err| panic!("{what}: curve {k}: {err}")))
        .collect()
}

/// Every joined curve is closed, its joins proven and its tolerance at most 1e-9.
pub(crate) fn closed_and_proven(what: &str, report: &ShellRunReport) {
    let r = &report.result;
    assert!(r.is_complete(), "{what}: search incomplete");
    for c in &r.curves {
        assert!(c.closed, "{what}: an open curve {c:?}");
        let tol = c
            .certified_tolerance
            .unwrap_or_else(|| panic!("{what}: not certified as a whole: {c:?}"));
        assert!(tol <= 1e-9, "{what}: {tol:e}");
    }
}

/// 4 000 points of a closed curve `t ↦ c(t)`, `t ∈ [0, 2π)`, evenly in `t`: the true curve the
/// edges are checked against.
pub(crate) fn around(c: impl Fn(f64) -> [f64; 3]) -> Vec<[f64; 3]> {
    (0..4000).map(|m| c(2.0 * PI * m as f64 / 4000.0)).collect()
}
