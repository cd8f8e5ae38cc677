//! Issue 11's "must show" cases on shells of NURBS faces, against curves known in closed form:
//!
//! - two full NURBS cylinders of different radii at right angles: two closed curves;
//! - two of equal radii: the two singular points and four arcs between them, each once;
//! - a paraboloid with interior knots in both directions (a non-rational B-spline made by
//!   blossoming) against a plane: one closed curve across four knot lines;
//! - a shell of four quarter-cylinder faces against an oblique plane: one closed ellipse.
//!
//! For every curve with an edge (`ssitrace::edge`), the 3D B-spline is checked both ways
//! against the closed form, sampled densely: every curve point within the edge tolerance of
//! the true curve, every true point within it of the curve; and every p-curve's image on its
//! face within its image tolerance of the true curve. The distances to the closed forms are
//! upper bounds (the distance to one particular point of the other curve), so the checks are
//! conservative. Control-point counts are printed.

mod common;

use common::scenes::scene_path;
use common::shell_checks::{
    around, bspline_paraboloid, check_edge, closed_and_proven, cylinder, edges, plane,
    quarter_cylinders, run,
};
use common::spline::dist3;
use serde_json::{json, Value};
use ssitrace::io::scene::ShellScene;
use ssitrace::march::branch::EndReason;
use ssitrace::pipeline::ShellRunReport;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The edges of two unit cylinders about z and x: open, from near one node to near the other,
/// within their tolerance of the ellipses (cos φ, sin φ, ±cos φ) both ways (the truth sampled
/// away from the nodes, where the chains stop short).
fn check_ellipse_arcs(what: &str, scene: &ShellScene, report: &ShellRunReport) {
    let arc_point = |phi: f64, s: f64| [phi.cos(), phi.sin(), s * phi.cos()];
    for (k, e) in edges(what, scene, report).iter().enumerate() {
        assert!(!e.closed);
        let mid = e
            .curve
            .eval(0.5 * (e.curve.range()[0] + e.curve.range()[1]));
        let (xs, zs) = (mid[0].signum(), (mid[0] * mid[2]).signum());
        let off = |p: &[f64; 3]| dist3(p, &arc_point(p[1].atan2(p[0]), zs));
        let truth: Vec<[f64; 3]> = (0..=2000)
            .map(|m| {
                let phi = -0.5 * PI + 1e-3 + (PI - 2e-3) * m as f64 / 2000.0;
                if xs > 0.0 {
                    phi
                } else {
                    phi + PI
                }
            })
            .map(|phi| arc_point(phi, zs))
            .collect();
        check_edge(&format!("{what}: arc {k}"), e, &scene.shells, &off, &truth);
    }
}

#[test]
fn nurbs_cylinders_of_different_radii_meet_in_two_closed_curves() {
    // x² + y² = 1 about z and y² + z² = 1/4 about x: the loops x = ±√(1 − y²), (y, z) on the
    // circle of radius 1/2. Both curves cross seams and knot lines of both cylinders. The
    // second cylinder is turned by atan(12/5) so that no crossing of one cylinder's knot line
    // is also one of the other's (a curve through a corner of the piece pair, on a knot line
    // of both surfaces at once, is the next test's case).
    let scene = json!({"surfaces": [cylinder(2, 1.0, 2.0, None),
                                    cylinder(0, 0.5, 2.0, Some([5.0 / 13.0, 12.0 / 13.0]))],
                       "options": {"method": "both"}});
    let (scene, report) = run(scene);
    closed_and_proven("cylinders 1, 1/2", &report);
    assert_eq!(report.result.curves.len(), 2, "{:?}", report.result.curves);
    let loop_point = |phi: f64, sign: f64| {
        let (y, z) = (0.5 * phi.cos(), 0.5 * phi.sin());
        [sign * (1.0 - y * y).sqrt(), y, z]
    };
    let mut signs = Vec::new();
    for (k, e) in edges("cylinders 1, 1/2", &scene, &report)
        .iter()
        .enumerate()
    {
        assert!(e.closed);
        let sign = e.curve.points[0][0].signum();
        signs.push(sign);
        let off = |p: &[f64; 3]| dist3(p, &loop_point(p[2].atan2(p[1]), sign));
        let truth = around(|t| loop_point(t, sign));
        check_edge(
            &format!("cylinders 1, 1/2: loop {k}"),
            e,
            &scene.shells,
            &off,
            &truth,
        );
    }
    signs.sort_by(f64::total_cmp);
    assert_eq!(signs, [-1.0, 1.0], "one loop on each side");
}

/// The same cylinders with both circles unturned. Each loop then crosses the first cylinder's
/// seam (y = 0) exactly where it crosses a knot line of the second (z = ±1/2): a branch ends in
/// a corner of its piece pair, and the next branch is in the diagonally neighbouring pair (both
/// pieces change). The two pairs beside the corner each report a branch of one point (the
/// corner). The join across the corner is proven (`ssitrace::shell::corner`): its box holds
/// the exact corner point, the one-point branches are absorbed, and each loop is one closed
/// curve of four certified arcs, with its edge (each part cut where it first leaves its pieces)
/// checked against the closed form.
#[test]
fn unturned_nurbs_cylinders_cross_seam_and_knot_line_at_once() {
    let scene = json!({"surfaces": [cylinder(2, 1.0, 2.0, None), cylinder(0, 0.5, 2.0, None)],
                       "options": {"method": "both"}});
    let (scene, report) = run(scene);
    closed_and_proven("unturned cylinders 1, 1/2", &report);
    let r = &report.result;
    assert_eq!(r.curves.len(), 2);
    // The edges, across the corners too, against the closed form both ways.
    let loop_point = |phi: f64, sign: f64| {
        let (y, z) = (0.5 * phi.cos(), 0.5 * phi.sin());
        [sign * (1.0 - y * y).sqrt(), y, z]
    };
    for (k, e) in edges("unturned cylinders", &scene, &report)
        .iter()
        .enumerate()
    {
        assert!(e.closed);
        let sign = e.curve.points[0][0].signum();
        let off = |p: &[f64; 3]| dist3(p, &loop_point(p[2].atan2(p[1]), sign));
        let truth = around(|t| loop_point(t, sign));
        check_edge(
            &format!("unturned cylinders: loop {k}"),
            e,
            &scene.shells,
            &off,
            &truth,
        );
    }
    // The four corners (±1, 0, ±1/2), each in one corner join's box; every branch is a part of
    // a curve or absorbed by a corner.
    let corners: Vec<_> = r
        .curves
        .iter()
        .flat_map(|c| &c.joins)
        .filter_map(|j| j.corner.as_ref())
        .collect();
    assert_eq!(corners.len(), 4, "{corners:?}");
    for (x, z) in [(1.0, 0.5), (1.0, -0.5), (-1.0, 0.5), (-1.0, -0.5)] {
        let at = [x, 0.0, z];
        let holding = corners
            .iter()
            .filter(|c| (0..3).all(|i| c.xyz[i].contains(at[i])))
            .count();
        assert_eq!(holding, 1, "corner {at:?}");
    }
    for c in &corners {
        let diameter = c.xyz.iter().map(|x| x.wid()).fold(0.0, f64::max);
        assert!(diameter < 1e-9, "{diameter:e}");
        assert!(!c.absorbed.is_empty());
    }
    let mut covered: Vec<usize> = r
        .curves
        .iter()
        .flat_map(|c| c.parts.iter().map(|p| p.branch))
        .chain(corners.iter().flat_map(|c| c.absorbed.iter().copied()))
        .collect();
    covered.sort_unstable();
    assert_eq!(covered, (0..r.branch_count()).collect::<Vec<_>>());
}

/// The unturned cylinders with the second moved by `δ` along y: each loop now crosses the first
/// cylinder's seam (y = 0) and the second's knot line (y = δ) apart, by about δ along the curve,
/// so the stretch between the crossings is a short branch of a pair beside the corner. Its ends
/// lie on sides of both of their pieces, and the marcher names one surface where the neighbour
/// names the other: each such end is a site on both sides, so every loop is one closed curve,
/// every join proven (at δ = 1e-9 the short branch leaves through the seam at its marched end:
/// its chain goes on past the side, so that exit is proven too).
#[test]
fn nearly_corner_crossings_are_joined_into_closed_curves() {
    for delta in [1e-6, 1e-9] {
        let mut moved = cylinder(0, 0.5, 2.0, None);
        for p in moved["points"].as_array_mut().unwrap() {
            let y = p[1].as_f64().unwrap();
            p[1] = json!(y + delta);
        }
        let scene = json!({"surfaces": [cylinder(2, 1.0, 2.0, None), moved],
                           "options": {"method": "both"}});
        let (_, report) = run(scene);
        let what = format!("cylinders 1, 1/2 moved by {delta:e}");
        let r = &report.result;
        assert_eq!(r.curves.len(), 2, "{what}: {:?}", r.curves);
        for c in &r.curves {
            assert!(c.closed, "{what}: an open curve {c:?}");
            let unproven: Vec<_> = c.joins.iter().filter(|j| !j.status.is_proven()).collect();
            assert!(unproven.is_empty(), "{what}: {unproven:?}");
            let tol = c.certified_tolerance.expect("certified, joins proven");
            assert!(tol <= 1e-9, "{what}: {tol:e}");
        }
    }
}

/// Two equal cylinders, unturned: the ellipses (cos φ, sin φ, ±cos φ) cross the first's seam
/// exactly where they cross knot lines of the second, at (±1, 0, ±1), and the singular points
/// (0, ±1, 0) lie on knot lines of both. Each of the four arcs between the nodes is made of two
/// branches joined across a corner of their piece pairs, and proven.
#[test]
fn unturned_equal_cylinders_give_four_arcs_each_joined_across_a_corner() {
    let scene = json!({"surfaces": [cylinder(2, 1.0, 2.0, None), cylinder(0, 1.0, 2.0, None)],
                       "options": {"method": "both"}});
    let (scene, report) = run(scene);
    let r = &report.result;
    assert_eq!(r.curves.len(), 4, "{:?}", r.curves);
    let mut met = Vec::new();
    for c in &r.curves {
        assert!(!c.closed);
        let tol = c.certified_tolerance.expect("certified, joins proven");
        assert!(tol <= 1e-9, "{tol:e}");
        let corners: Vec<_> = c.joins.iter().filter_map(|j| j.corner.as_ref()).collect();
        assert_eq!(corners.len(), 1, "{c:?}");
        let at = [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .into_iter()
            .position(|(x, z)| {
                let p = [x, 0.0, z];
                (0..3).all(|i| corners[0].xyz[i].contains(p[i]))
            })
            .expect("the corner box holds a crossing (±1, 0, ±1)");
        met.push(at);
    }
    met.sort_unstable();
    assert_eq!(met, [0, 1, 2, 3], "one arc through each crossing");
    // The edges across the corners, against the closed form.
    check_ellipse_arcs("unturned cylinders 1, 1", &scene, &report);
}

#[test]
fn nurbs_cylinders_of_equal_radii_meet_in_four_arcs_between_two_nodes() {
    // x² + y² = 1 about z and y² + z² = 1 about x: the ellipses (cos φ, sin φ, ±cos φ), which
    // cross at the singular points (0, ±1, 0): four arcs between them. Both circles are
    // turned (by atan(4/3) and atan(12/5)) so that the singular points lie inside knot spans
    // and no knot line of one is crossed where one of the other is.
    let scene = json!({"surfaces": [cylinder(2, 1.0, 2.0, Some([0.6, 0.8])),
                                    cylinder(0, 1.0, 2.0, Some([5.0 / 13.0, 12.0 / 13.0]))],
                       "options": {"method": "both"}});
    let (scene, report) = run(scene);
    let r = &report.result;
    assert_eq!(r.curves.len(), 4, "four arcs: {:?}", r.curves);
    let nodes = [[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]];
    let mut arcs = Vec::new();
    let mut met = [false; 2];
    for c in &r.curves {
        assert!(!c.closed);
        let tol = c.certified_tolerance.expect("certified, joins proven");
        assert!(tol <= 1e-9, "{tol:e}");
        // Both ends are singular, at the nodes (one at each).
        let (p0, pn) = (c.parts[0], c.parts[c.parts.len() - 1]);
        let first = &r.branch(p0.branch).unwrap().1.marched;
        let last = &r.branch(pn.branch).unwrap().1.marched;
        let start = if p0.reversed {
            (first.points.last().unwrap(), first.ends[1])
        } else {
            (first.points.first().unwrap(), first.ends[0])
        };
        let stop = if pn.reversed {
            (last.points.first().unwrap(), last.ends[0])
        } else {
            (last.points.last().unwrap(), last.ends[1])
        };
        let mut at = Vec::new();
        for (pt, why) in [start, stop] {
            assert_eq!(why, EndReason::Singular, "{c:?}");
            let k = (0..2)
                .find(|&k| dist3(&pt.xyz, &nodes[k]) < 1e-3)
                .unwrap_or_else(|| panic!("an end at {:?}, not at a node", pt.xyz));
            met[k] = true;
            at.push(k);
        }
        assert_ne!(at[0], at[1], "an arc from one node to the other");
        // Which of the four arcs: the signs of x and of x·z at its marched points.
        let mut label = None;
        for part in &c.parts {
            for pt in &r.branch(part.branch).unwrap().1.marched.points {
                let x = pt.xyz;
                assert!(
                    (x[0].abs() - x[2].abs()).abs() < 1e-6,
                    "{x:?} is off x = ±z"
                );
                if x[0].abs() > 1e-2 {
                    let l = (x[0] > 0.0, x[0] * x[2] > 0.0);
                    assert!(*label.get_or_insert(l) == l, "a curve on two arcs");
                }
            }
        }
        arcs.push(label.expect("a point away from the nodes"));
    }
    assert!(met.iter().all(|&m| m), "both nodes");
    arcs.sort();
    arcs.dedup();
    assert_eq!(arcs.len(), 4, "each arc once");
    check_ellipse_arcs("cylinders 1, 1", &scene, &report);
}

#[test]
fn a_paraboloid_with_interior_knots_against_a_plane_is_one_closed_curve() {
    // z = (x − 0.45)² + (y − 0.55)² over [0, 1]², biquadratic with knots 1/4, 1/2, 3/4 in both
    // directions (control points by blossoming: exact in binary), against z = 0.0784: the
    // circle of radius 0.28 about (0.45, 0.55), crossing x = 1/4, 1/2 and y = 1/2, 3/4.
    let h = 0.0784;
    let scene = json!({"surfaces": [
        bspline_paraboloid(),
        plane([-1.0, -1.0, h], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0])],
        "options": {"method": "both"}});
    let (scene, report) = run(scene);
    closed_and_proven("paraboloid", &report);
    let r = &report.result;
    assert_eq!(r.curves.len(), 1, "one curve: {:?}", r.curves);
    assert!(r.curves[0].parts.len() >= 4, "it crosses four knot lines");
    let rad = 0.28;
    let circle = |phi: f64| [0.45 + rad * phi.cos(), 0.55 + rad * phi.sin(), h];
    let off = |p: &[f64; 3]| dist3(p, &circle((p[1] - 0.55).atan2(p[0] - 0.45)));
    let truth = around(circle);
    let e = edges("paraboloid", &scene, &report);
    assert_eq!(e.len(), 1);
    assert!(e[0].closed);
    check_edge("paraboloid", &e[0], &scene.shells, &off, &truth);
}

#[test]
fn four_quarter_cylinders_against_an_oblique_plane_are_one_closed_ellipse() {
    // Four faces, each a quarter of x² + y² = 1, z ∈ [−1, 1] (one rational Bézier span), sharing
    // their edges; the plane z = 0.3·x + 0.2·y + 0.1 cuts the ellipse
    // (cos θ, sin θ, 0.3·cos θ + 0.2·sin θ + 0.1): one closed curve of four parts, not four.
    let z = |x: f64, y: f64| 0.3 * x + 0.2 * y + 0.1;
    let oblique = plane(
        [-2.0, -2.0, z(-2.0, -2.0)],
        [4.0, 0.0, 1.2],
        [0.0, 4.0, 0.8],
    );
    let scene = json!({"surfaces": [quarter_cylinders(), oblique],
                       "options": {"method": "both"}});
    let (scene, report) = run(scene);
    closed_and_proven("quarter cylinders", &report);
    let r = &report.result;
    assert_eq!(
        r.curves.len(),
        1,
        "one ellipse, not four pieces: {:?}",
        r.curves
    );
    assert_eq!(r.curves[0].parts.len(), 4);
    let ellipse = |t: f64| [t.cos(), t.sin(), z(t.cos(), t.sin())];
    let off = |p: &[f64; 3]| dist3(p, &ellipse(p[1].atan2(p[0])));
    let truth = around(ellipse);
    let e = edges("quarter cylinders", &scene, &report);
    assert_eq!(e.len(), 1);
    assert!(e[0].closed);
    check_edge("quarter cylinders", &e[0], &scene.shells, &off, &truth);
}

/// The one curve of `report` has one corner join at each point of `exact`, whose box holds
/// that point and is below 1e-9 across, and every branch is a part of it or absorbed by a
/// corner.
fn check_corners(what: &str, report: &ShellRunReport, exact: &[[f64; 3]]) {
    let r = &report.result;
    let corners: Vec<_> = r.curves[0]
        .joins
        .iter()
        .filter_map(|j| j.corner.as_ref())
        .collect();
    assert_eq!(corners.len(), exact.len(), "{what}: {corners:?}");
    for at in exact {
        let holding = corners
            .iter()
            .filter(|c| (0..3).all(|i| c.xyz[i].contains(at[i])))
            .count();
        assert_eq!(holding, 1, "{what}: corner {at:?}");
    }
    for c in &corners {
        let diameter = c.xyz.iter().map(|x| x.wid()).fold(0.0, f64::max);
        assert!(diameter < 1e-9, "{what}: {diameter:e}");
    }
    let used: std::collections::HashSet<usize> = r.curves[0]
        .parts
        .iter()
        .map(|p| p.branch)
        .chain(corners.iter().flat_map(|c| c.absorbed.iter().copied()))
        .collect();
    assert_eq!(used.len(), r.branch_count(), "{what}");
}

/// The quarter cylinders against an oblique plane made of two faces that share the line
/// `x = 0`: the ellipse crosses the plane's face edge exactly where it crosses the cylinder's
/// face edges, at `(0, ±1)`. There each branch ends at a corner of its piece pair and the next
/// one lies in the diagonally neighbouring pair (both faces change at once); the pairs beside
/// the corner hold a branch of one point. The join across such a corner is proven on a chart
/// that maps one face's parameters onto its neighbour's across the shared edge. Three ways of
/// writing the plane's second face: the same way as the first, its shared edge running the
/// other way, and over another parameter domain (a NURBS face on `[0, 2] × [0, 4]`). Each
/// time: one closed curve of four parts, both corners proven (each box holding the exact
/// corner point), the one-point branches absorbed, the edge within its tolerance of the
/// ellipse both ways. (The corner proof used to accept only knot lines and seams the same way
/// round: here both joins stayed unproven and the slivers were a curve of their own.)
#[test]
fn a_corner_across_face_edges_of_both_shells_is_joined_and_proven() {
    // Dyadic coefficients: every control point is exact.
    let z = |x: f64, y: f64| 0.25 * x + 0.125 * y + 0.0625;
    let at = |x: f64, y: f64| json!([x, y, z(x, y)]);
    let left = json!({"kind": "bezier", "degree": [1, 1],
                      "points": [at(-2.0, -2.0), at(-2.0, 2.0), at(0.0, -2.0), at(0.0, 2.0)]});
    let right_same = json!({"kind": "bezier", "degree": [1, 1],
                            "points": [at(0.0, -2.0), at(0.0, 2.0), at(2.0, -2.0), at(2.0, 2.0)]});
    let right_reversed = json!({"kind": "bezier", "degree": [1, 1],
                                "points": [at(0.0, 2.0), at(0.0, -2.0), at(2.0, 2.0), at(2.0, -2.0)]});
    let right_rescaled = json!({"kind": "nurbs", "degree": [1, 1],
                                "knots": [[0.0, 0.0, 2.0, 2.0], [0.0, 0.0, 4.0, 4.0]],
                                "points": [at(0.0, -2.0), at(0.0, 2.0), at(2.0, -2.0), at(2.0, 2.0)]});
    let ellipse = |t: f64| [t.cos(), t.sin(), z(t.cos(), t.sin())];
    for (what, right) in [
        ("same way", right_same),
        ("reversed", right_reversed),
        ("rescaled", right_rescaled),
    ] {
        let scene = json!({"surfaces": [quarter_cylinders(), [left.clone(), right]],
                           "options": {"method": "both"}});
        let (scene, report) = run(scene);
        closed_and_proven(what, &report);
        let r = &report.result;
        assert_eq!(r.curves.len(), 1, "{what}: one ellipse: {:?}", r.curves);
        assert_eq!(r.curves[0].parts.len(), 4, "{what}");
        let exact = [1.0, -1.0].map(|y| [0.0, y, z(0.0, y)]);
        check_corners(what, &report, &exact);
        let off = |p: &[f64; 3]| dist3(p, &ellipse(p[1].atan2(p[0])));
        let e = edges(what, &scene, &report);
        assert_eq!(e.len(), 1, "{what}");
        assert!(e[0].closed, "{what}");
        check_edge(what, &e[0], &scene.shells, &off, &around(ellipse));
    }
}

/// The standard NURBS sphere (degree 2×2, the 9×5 net of `scenes/nurbs_sphere_plane.json`:
/// knot lines on the meridians at 90°, 180° and 270°, the seam at 0°, and the equator) against
/// planes through its centre that meet the equator where a meridian knot line or the seam
/// crosses it: `y = z` through `(±1, 0, 0)` (the seam's and the 180° meridian's crossings) and
/// `x = z` through `(0, ±1, 0)`. There the curve passes through a point where four pieces of
/// the sphere meet, inside the plane's one piece: the branches on either side lie in pairs of
/// diagonally opposite pieces, and the pairs beside the corner hold a one-point branch. The
/// join across such a corner is proven on a chart of the four pieces round it (the face's own
/// parameters, shifted by the period across the seam). Each time: one closed great circle of
/// four parts, both corners proven (each box holding the exact corner point), every branch a
/// part or absorbed, the edge within its tolerance of the circle both ways. (Before: two open
/// curves with unproven joins.)
#[test]
fn a_great_circle_through_knot_line_crossings_of_a_nurbs_sphere_is_one_closed_curve() {
    let text = std::fs::read_to_string(scene_path("nurbs_sphere_plane.json")).expect("scene");
    let scene: Value = serde_json::from_str(&text).expect("json");
    let sphere = scene["surfaces"][0].clone();
    // The plane's name, control points, the circle and the two corners it passes through.
    type Case = (
        &'static str,
        [[f64; 3]; 4],
        fn(f64) -> [f64; 3],
        [[f64; 3]; 2],
    );
    let cases: [Case; 2] = [
        (
            "y = z",
            [
                [-2.0, -2.0, -2.0],
                [-2.0, 2.0, 2.0],
                [2.0, -2.0, -2.0],
                [2.0, 2.0, 2.0],
            ],
            |t| [t.cos(), t.sin() * FRAC_1_SQRT_2, t.sin() * FRAC_1_SQRT_2],
            [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]],
        ),
        (
            "x = z",
            [
                [-2.0, -2.0, -2.0],
                [-2.0, 2.0, -2.0],
                [2.0, -2.0, 2.0],
                [2.0, 2.0, 2.0],
            ],
            |t| [t.sin() * FRAC_1_SQRT_2, t.cos(), t.sin() * FRAC_1_SQRT_2],
            [[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]],
        ),
    ];
    for (what, points, circle, corners_at) in cases {
        let plane = json!({"kind": "bezier", "degree": [1, 1], "points": points});
        let (scene, report) = run(json!({"surfaces": [sphere.clone(), plane],
                                         "options": {"method": "both"}}));
        closed_and_proven(what, &report);
        let res = &report.result;
        assert_eq!(res.curves.len(), 1, "{what}: one circle: {:?}", res.curves);
        assert_eq!(res.curves[0].parts.len(), 4, "{what}");
        check_corners(what, &report, &corners_at);
        // An upper bound on the distance to the unit circle in the plane: the distance to the
        // plane `a` and to the unit sphere `r` give at most `√(a² + (r + a)²) ≤ 2a + r`.
        let normal = {
            let [a, b, c] = [circle(0.0), circle(1.0), circle(2.0)];
            let (u, v) = (
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            n.map(|x| x / l)
        };
        let off = |p: &[f64; 3]| {
            let along = p[0] * normal[0] + p[1] * normal[1] + p[2] * normal[2];
            let radial = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0;
            2.0 * along.abs() + radial.abs()
        };
        let e = edges(what, &scene, &report);
        assert_eq!(e.len(), 1, "{what}");
        assert!(e[0].closed, "{what}");
        check_edge(what, &e[0], &scene.shells, &off, &around(circle));
    }
}

/// A plane of four quadrant faces meeting at the origin, each written another way (the
/// standard parametrisation, its axes swapped, both reversed, and a NURBS face over
/// `[0, 2] × [0, 4]`), against the paraboloid `z = (x − cx)² + (y − cy)² − (cx² + cy²)`
/// (a biquadratic Bézier patch over `[−1, 1]²`, every control point exact): the circle round
/// `(cx, cy)` through the origin crosses there from one face to the diagonally opposite one, a
/// point where four faces meet across face edges. The join across it is proven on a chart of
/// the four faces (each mapped affinely across the edge it shares, and the diagonal face
/// reached both ways round with the same map). Two circles, one through each pair of
/// opposite faces: one closed curve each, the corner proven (its box holds the origin), the
/// one-point branches absorbed, the edge within its tolerance of the circle both ways.
#[test]
fn a_curve_through_a_vertex_where_four_faces_meet_is_one_closed_curve() {
    let p = |x: f64, y: f64| json!([x, y, 0.0]);
    let bilinear = |c: [Value; 4]| json!({"kind": "bezier", "degree": [1, 1], "points": c});
    let quadrants = vec![
        bilinear([p(0.0, 0.0), p(0.0, 1.0), p(1.0, 0.0), p(1.0, 1.0)]),
        bilinear([p(0.0, 0.0), p(-1.0, 0.0), p(0.0, 1.0), p(-1.0, 1.0)]),
        bilinear([p(0.0, 0.0), p(0.0, -1.0), p(-1.0, 0.0), p(-1.0, -1.0)]),
        json!({"kind": "nurbs", "degree": [1, 1], "knots": [[0.0, 0.0, 2.0, 2.0], [0.0, 0.0, 4.0, 4.0]],
               "points": [p(0.0, -1.0), p(0.0, 0.0), p(1.0, -1.0), p(1.0, 0.0)]}),
    ];
    for (cx, cy) in [(0.25, 0.125), (-0.25, 0.125)] {
        let what = format!("circle round ({cx}, {cy})");
        // (x − c)² over x = −1 + 2s in Bernstein form: (1 + c)², c² − 1, (1 − c)².
        let bern = |c: f64| [(1.0 + c) * (1.0 + c), c * c - 1.0, (1.0 - c) * (1.0 - c)];
        let (bx, by) = (bern(cx), bern(cy));
        let r2 = cx * cx + cy * cy;
        let net: Vec<Value> = (0..3)
            .flat_map(|i| {
                (0..3).map(move |j| json!([i as f64 - 1.0, j as f64 - 1.0, bx[i] + by[j] - r2]))
            })
            .collect();
        let bowl = json!({"kind": "bezier", "degree": [2, 2], "points": net});
        let (scene, report) = run(json!({"surfaces": [quadrants.clone(), bowl],
                                         "options": {"method": "both"}}));
        closed_and_proven(&what, &report);
        assert_eq!(report.result.curves.len(), 1, "{what}");
        check_corners(&what, &report, &[[0.0, 0.0, 0.0]]);
        let r = r2.sqrt();
        let circle = |t: f64| [cx + r * t.cos(), cy + r * t.sin(), 0.0];
        let off = |q: &[f64; 3]| {
            let d = ((q[0] - cx).powi(2) + (q[1] - cy).powi(2)).sqrt();
            (d - r).abs() + q[2].abs()
        };
        let e = edges(&what, &scene, &report);
        assert_eq!(e.len(), 1, "{what}");
        assert!(e[0].closed, "{what}");
        check_edge(&what, &e[0], &scene.shells, &off, &around(circle));
    }
}
