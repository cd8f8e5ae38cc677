//! Sections *along* the knot lines and the seam of a NURBS cylinder: a plane through the axis
//! at a knot angle (the commonest section of a body of revolution) cuts it in two lines that
//! lie on the sides of the Bézier pieces, not across them.
//!
//! The cylinder is the standard nine-point circle times a line: its pieces meet along the
//! lines at 0° (the periodic seam), 90°, 180° and 270° about the axis. The plane `n·x = e`
//! (`n` one of the two coordinate directions across the axis) with `e = 0` holds two of those
//! lines, each a side of two pieces; with `e` small it passes that close beside them. Each
//! case must give a complete search and exactly two curves, each one open certified line
//! (tolerance ≤ 1e-9) ending where the plane's patch ends, its edge within its tolerance of the
//! closed-form line both ways; the cylinder's axis on z and on x, and turned by a rational
//! rotation (interval control points) so that its joints lie off the coordinate planes.
//!
//! Before: along a knot line, Newton refined each start with the piece's side held fixed (no
//! isolated root), so every start failed and no branch was found, the search undecided along
//! the whole side (98 304 leaves, 1.7 s); within 1e-7 of a knot line likewise; once found, the
//! line came back twice (once per piece) and the two copies were glued into a closed curve.

mod common;

use common::shell_checks::{check_edge, cylinder, edges, plane, run};

/// Half the length of the cylinder (the plane's patch spans half of it).
const LEN: f64 = 2.0;

/// Runs the cylinder of radius `r` about `axis` (turned by `turn`) against the plane through
/// the axis with unit normal `n` (in the two coordinates across the axis) at distance `e`, and
/// checks the two lines.
fn check(axis: usize, r: f64, turn: Option<[f64; 2]>, n: [f64; 2], e: f64) {
    let what = format!("axis {axis}, r {r}, turn {turn:?}, n {n:?}, e {e:e}");
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    // Unit vectors: along the axis, across it in the plane (m), the plane's normal.
    let unit = |c: [f64; 2], along: f64| {
        let mut v = [0.0; 3];
        v[a] = c[0];
        v[b] = c[1];
        v[axis] = along;
        v
    };
    let m = unit([-n[1], n[0]], 0.0);
    let normal = unit(n, 0.0);
    let ax = unit([0.0, 0.0], 1.0);
    let h = LEN / 2.0;
    let origin: [f64; 3] = std::array::from_fn(|k| e * normal[k] - 2.0 * r * m[k] - h * ax[k]);
    let e1: [f64; 3] = std::array::from_fn(|k| 4.0 * r * m[k]);
    let e2: [f64; 3] = std::array::from_fn(|k| 2.0 * h * ax[k]);
    let scene =
        serde_json::json!({"surfaces": [cylinder(axis, r, LEN, turn), plane(origin, e1, e2)]});
    let (scene, report) = run(scene);
    let res = &report.result;
    assert!(res.is_complete(), "{what}: search incomplete");
    assert_eq!(res.curves.len(), 2, "{what}: {:#?}", res.curves);
    for c in &res.curves {
        assert!(!c.closed, "{what}: a line came back closed: {c:?}");
        let tol = c
            .certified_tolerance
            .unwrap_or_else(|| panic!("{what}: not certified: {c:?}"));
        assert!(tol <= 1e-9, "{what}: tolerance {tol:e}");
    }
    if e == 0.0 && turn.is_none() {
        assert_eq!(
            res.edge_copies, 2,
            "{what}: each line traced by both of its pieces"
        );
    }
    // The lines: distance `e` off the axis along `normal`, `±w` along `m`.
    let w = (r * r - e * e).sqrt();
    let dot = |x: &[f64; 3], v: &[f64; 3]| (0..3).map(|k| x[k] * v[k]).sum::<f64>();
    for edge in edges(&what, &scene, &report) {
        let side = dot(&edge.curve.eval(edge.curve.knots[0]), &m).signum();
        let off = |x: &[f64; 3]| {
            let (across, beside, height) =
                (dot(x, &normal) - e, dot(x, &m) - side * w, dot(x, &ax));
            let beyond = (height.abs() - h).max(0.0);
            (across * across + beside * beside + beyond * beyond).sqrt()
        };
        let truth: Vec<[f64; 3]> = (0..=400)
            .map(|i| {
                let t = -h + 2.0 * h * i as f64 / 400.0;
                std::array::from_fn(|k| e * normal[k] + side * w * m[k] + t * ax[k])
            })
            .collect();
        check_edge(&what, &edge, &scene.shells, &off, &truth);
    }
}

#[test]
fn planes_through_the_axis_at_the_knot_angles_cut_two_lines_each() {
    for axis in [2, 0] {
        // Normal along the first cross coordinate: the lines at 90° and 270° (knot lines);
        // along the second: at 0° (the seam) and 180° (a knot line).
        for n in [[1.0, 0.0], [0.0, 1.0]] {
            for e in [0.0, 1e-12, 0.5f64.powi(30), 1e-7, 1e-4] {
                check(axis, 1.0, None, n, e);
            }
        }
    }
}

#[test]
fn other_radii_and_a_turned_cylinder() {
    check(2, 0.37, None, [0.0, 1.0], 0.0);
    check(1, 3.0, None, [1.0, 0.0], 0.0);
    // Turned by (0.6, 0.8): its joints lie along (0.6, 0.8) and (−0.8, 0.6) across the axis.
    check(2, 1.0, Some([0.6, 0.8]), [-0.8, 0.6], 0.0);
    check(2, 1.0, Some([0.6, 0.8]), [0.6, 0.8], 0.0);
}

/// The NURBS torus about z, radii `big` (to the tube's centre) and `small` (the tube): the
/// nine-point circle times the nine-point circle (weights the products of the circles' `1` and
/// `√2/2`). Its joints: the circles at tube angles 0° (the seam: the outer equator), 90°, 180°
/// (the inner equator), 270°, and the tube circles at 0° (the seam), 90°, 180°, 270° about z.
fn torus(big: f64, small: f64) -> serde_json::Value {
    let net = common::surfaces::UNIT_CIRCLE_NET;
    let (mut points, mut weights) = (Vec::new(), Vec::new());
    for (i, &(a, b)) in net.iter().enumerate() {
        for (j, &(c, d)) in net.iter().enumerate() {
            let rad = big + small * c;
            points.push(serde_json::json!([a * rad, b * rad, small * d]));
            weights.push(match (i % 2, j % 2) {
                (1, 1) => serde_json::json!(0.5),
                (0, 0) => serde_json::json!(1.0),
                _ => common::shell_checks::half_sqrt2(),
            });
        }
    }
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    serde_json::json!({"kind": "nurbs", "degree": [2, 2], "knots": [knots, knots],
                       "points": points, "weights": weights})
}

/// A torus cut along its joints: by its equatorial plane (the outer equator on the seam, the
/// inner one on a knot line) and by a plane through its axis (the four tube circles there on
/// knot lines). Each gives two circles, each one closed curve, certified with every join
/// proven, its edge within tolerance of the circle. Before: no branch (every start failed);
/// once found, each quarter arc twice, and the kept copies joined across corners, unproven.
#[test]
fn a_torus_cut_along_its_joints_gives_closed_proven_circles() {
    use common::shell_checks::{around, closed_and_proven};
    let (big, small) = (2.0, 0.5);
    let l = 3.0;
    let equator = plane([-l, -l, 0.0], [2.0 * l, 0.0, 0.0], [0.0, 2.0 * l, 0.0]);
    let meridian = plane([0.0, -l, -l], [0.0, 2.0 * l, 0.0], [0.0, 0.0, 2.0 * l]);
    for (what, cut) in [("equator", equator), ("meridian", meridian)] {
        let (scene, report) = run(serde_json::json!({"surfaces": [torus(big, small), cut]}));
        closed_and_proven(what, &report);
        assert_eq!(report.result.curves.len(), 2, "{what}");
        assert!(report.result.edge_copies > 0, "{what}: along the joints");
        for edge in edges(what, &scene, &report) {
            let p0 = edge.curve.eval(edge.curve.knots[0]);
            if what == "equator" {
                // Circles of radius big ± small about the axis, in z = 0.
                let rad = (p0[0] * p0[0] + p0[1] * p0[1]).sqrt();
                let r = if rad > big { big + small } else { big - small };
                let off = |x: &[f64; 3]| ((x[0] * x[0] + x[1] * x[1]).sqrt() - r).hypot(x[2]);
                let c = |t: f64| [r * t.cos(), r * t.sin(), 0.0];
                check_edge(what, &edge, &scene.shells, &off, &around(c));
            } else {
                // Circles of radius small about (0, ±big, 0), in x = 0.
                let yc = big * p0[1].signum();
                let off = |x: &[f64; 3]| ((x[1] - yc).hypot(x[2]) - small).hypot(x[0]);
                let c = |t: f64| [0.0, yc + small * t.cos(), small * t.sin()];
                check_edge(what, &edge, &scene.shells, &off, &around(c));
            }
        }
    }
}

/// Along the edges two faces share, and with the NURBS surface second: a shell of four
/// quarter-cylinder faces (one rational Bézier span each) against the plane `x = 0`, whose
/// lines lie on the faces' shared edges at 90° and 270°; and the plane first, the NURBS
/// cylinder second. Two open certified lines each, every line once.
#[test]
fn lines_along_face_edges_and_with_the_surfaces_swapped() {
    use common::shell_checks::quarter_cylinders;
    let h = 0.5;
    let cut = plane([0.0, -3.0, -h], [0.0, 6.0, 0.0], [0.0, 0.0, 2.0 * h]);
    let off = |x: &[f64; 3]| {
        let beyond = (x[2].abs() - h).max(0.0);
        (x[0].hypot(x[1].abs() - 1.0)).hypot(beyond)
    };
    for (what, scene) in [
        (
            "faces",
            serde_json::json!({"surfaces": [quarter_cylinders(), cut.clone()]}),
        ),
        (
            "swapped",
            serde_json::json!({"surfaces": [cut.clone(), cylinder(2, 1.0, LEN, None)]}),
        ),
    ] {
        let (scene, report) = run(scene);
        let res = &report.result;
        assert!(res.is_complete(), "{what}: search incomplete");
        assert_eq!(
            res.edge_copies, 2,
            "{what}: each line traced by both of its pieces"
        );
        assert_eq!(res.curves.len(), 2, "{what}: {:#?}", res.curves);
        for edge in edges(what, &scene, &report) {
            let side = edge.curve.eval(edge.curve.knots[0])[1].signum();
            let truth: Vec<[f64; 3]> = (0..=400)
                .map(|i| [0.0, side, -h + 2.0 * h * i as f64 / 400.0])
                .collect();
            check_edge(what, &edge, &scene.shells, &off, &truth);
        }
    }
}

/// Not only circles and lines: the paraboloid `z = (x − 0.45)² + (y − 0.55)²` over `[0, 1]²`,
/// a non-rational biquadratic B-spline with knots 1/4, 1/2, 3/4 both ways (control points by
/// blossoming, exact), cut by the planes `x = 1/2` and `y = 3/4`, which hold its knot lines: a
/// parabola each, running along the knot line across three others, one open curve of four
/// parts joined by proven joins, within tolerance of the closed form.
#[test]
fn parabolas_along_the_knot_lines_of_a_bspline_paraboloid() {
    let bowl = common::shell_checks::bspline_paraboloid();
    // (coordinate held, its value, the other's centre): the parabola z = c + (s − s0)².
    for (k, value, s0) in [(0usize, 0.5f64, 0.55f64), (1usize, 0.75, 0.45)] {
        let what = format!("coordinate {k} = {value}");
        let c = (value - [0.45, 0.55][k]).powi(2);
        let (o, e1) = if k == 0 {
            ([value, -1.0, -1.0], [0.0, 3.0, 0.0])
        } else {
            ([-1.0, value, -1.0], [3.0, 0.0, 0.0])
        };
        let cut = plane(o, e1, [0.0, 0.0, 3.0]);
        let (scene, report) = run(serde_json::json!({"surfaces": [bowl.clone(), cut]}));
        let res = &report.result;
        assert!(res.is_complete(), "{what}: search incomplete");
        assert_eq!(res.curves.len(), 1, "{what}: {:#?}", res.curves);
        let curve = &res.curves[0];
        assert!(!curve.closed && curve.parts.len() == 4, "{what}: {curve:?}");
        let tol = curve.certified_tolerance.expect("certified, joins proven");
        assert!(tol <= 1e-9, "{what}: {tol:e}");
        // Distance to the parabola in its plane: the nearest point by Newton on
        // d/ds [(s − a)² + (c + (s − s0)² − z)²] = 0 from s = a (the curve is convex).
        let off = |x: &[f64; 3]| {
            let (a, z) = (x[1 - k], x[2]);
            let mut s = a;
            for _ in 0..50 {
                let g = (s - a) + 2.0 * (s - s0) * (c + (s - s0).powi(2) - z);
                let dg = 1.0 + 2.0 * (c + (s - s0).powi(2) - z) + 4.0 * (s - s0).powi(2);
                s -= g / dg;
            }
            // The arc ends at s = 0 and 1 (the paraboloid's domain).
            let s = s.clamp(0.0, 1.0);
            ((s - a).hypot(c + (s - s0).powi(2) - z)).hypot(x[k] - value)
        };
        let truth: Vec<[f64; 3]> = (0..=1000)
            .map(|i| {
                let s = i as f64 / 1000.0;
                let mut p = [0.0, 0.0, c + (s - s0).powi(2)];
                p[k] = value;
                p[1 - k] = s;
                p
            })
            .collect();
        let es = edges(&what, &scene, &report);
        assert_eq!(es.len(), 1, "{what}");
        check_edge(&what, &es[0], &scene.shells, &off, &truth);
    }
}

/// Two faces that meet along an edge they share, at an angle (two faces of one body, or of two
/// bodies touching along an edge): their intersection is that edge, on the boundary of both.
/// A quarter cylinder (the edge at 90°, its side `u = 1`) against the plane `x = 0` over
/// `y ∈ [1, 3]` (its side `y = 1`), either surface first, the plane's patch as long as the
/// cylinder's or shorter; and the full NURBS cylinder (the edge on a knot line). Each: the one
/// line, certified from end to end within tolerance, once. Before, the chain stopped after a
/// link or two ("close branches" at h ≈ 1e-10: the join's box across the plane's side was a few
/// 1e-46 wide, and no Krawczyk box that narrow held its image), and the repair traced the line
/// twice more.
#[test]
fn faces_meeting_along_a_shared_edge_intersect_in_it() {
    use common::shell_checks::quarter_cylinders;
    let quarter = quarter_cylinders().swap_remove(0);
    for h in [1.0, 0.5] {
        let face = plane([0.0, 1.0, -h], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0 * h]);
        let off = |x: &[f64; 3]| {
            let beyond = (x[2].abs() - h).max(0.0);
            x[0].hypot(x[1] - 1.0).hypot(beyond)
        };
        let truth: Vec<[f64; 3]> = (0..=400)
            .map(|i| [0.0, 1.0, -h + 2.0 * h * i as f64 / 400.0])
            .collect();
        for (what, scene) in [
            (
                "quarter, face",
                serde_json::json!({"surfaces": [quarter.clone(), face.clone()]}),
            ),
            (
                "face, quarter",
                serde_json::json!({"surfaces": [face.clone(), quarter.clone()]}),
            ),
            (
                "cylinder, face",
                serde_json::json!({"surfaces": [cylinder(2, 1.0, LEN, None), face.clone()]}),
            ),
        ] {
            let what = format!("{what}, half height {h}");
            let (scene, report) = run(scene);
            let res = &report.result;
            assert!(res.is_complete(), "{what}: search incomplete");
            assert_eq!(res.curves.len(), 1, "{what}: {:#?}", res.curves);
            assert_eq!(res.branch_count(), 1, "{what}: the edge once");
            let tol = res.curves[0].certified_tolerance.expect("certified");
            assert!(tol <= 1e-9, "{what}: {tol:e}");
            for pair in &res.pairs {
                for b in &pair.result.branches {
                    let c = b.certified().expect("certified");
                    assert!(
                        c.ends.iter().all(|e| e.reaches_true_end()),
                        "{what}: ends {:?}",
                        c.ends
                    );
                }
            }
            let es = edges(&what, &scene, &report);
            check_edge(&what, &es[0], &scene.shells, &off, &truth);
        }
    }
}

/// A line along knot lines of *both* surfaces: the NURBS cylinder against the plane x = 0 given
/// as a bilinear NURBS with a knot at y = 1, so the line (0, 1, z) is a knot line of both (four
/// piece pairs trace it) and (0, −1, z) of the cylinder only (two do); either surface first.
/// Two lines, each reported once (four copies dropped), certified.
#[test]
fn a_line_along_knot_lines_of_both_surfaces_is_reported_once() {
    let split_plane = serde_json::json!({"kind": "nurbs", "degree": [1, 1],
        "knots": [[-3.0, -3.0, 1.0, 3.0, 3.0], [-1.0, -1.0, 1.0, 1.0]],
        "points": [[0.0, -3.0, -1.0], [0.0, -3.0, 1.0], [0.0, 1.0, -1.0], [0.0, 1.0, 1.0],
                   [0.0, 3.0, -1.0], [0.0, 3.0, 1.0]]});
    let cyl = cylinder(2, 1.0, LEN, None);
    let off = |x: &[f64; 3]| {
        let beyond = (x[2].abs() - 1.0).max(0.0);
        x[0].hypot(x[1].abs() - 1.0).hypot(beyond)
    };
    for (what, scene) in [
        (
            "cylinder first",
            serde_json::json!({"surfaces": [cyl.clone(), split_plane.clone()]}),
        ),
        (
            "plane first",
            serde_json::json!({"surfaces": [split_plane.clone(), cyl.clone()]}),
        ),
    ] {
        let (scene, report) = run(scene);
        let res = &report.result;
        assert!(res.is_complete(), "{what}: search incomplete");
        assert_eq!(res.edge_copies, 4, "{what}");
        assert_eq!(res.branch_count(), 2, "{what}");
        assert_eq!(res.curves.len(), 2, "{what}: {:#?}", res.curves);
        for edge in edges(what, &scene, &report) {
            let side = edge.curve.eval(edge.curve.knots[0])[1].signum();
            let truth: Vec<[f64; 3]> = (0..=400)
                .map(|i| [0.0, side, -1.0 + 2.0 * i as f64 / 400.0])
                .collect();
            check_edge(what, &edge, &scene.shells, &off, &truth);
        }
    }
}
