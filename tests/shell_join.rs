//! Joining the branches of a shell intersection across knot lines, periodic seams and edges
//! shared by two faces: one curve per connected intersection curve.

use serde_json::{json, Value};
use ssitrace::io::result_json::{result_from_json, result_to_json};
use ssitrace::io::scene::ShellScene;
use ssitrace::pipeline::{run_shells, RunOptions};
use ssitrace::shell::edges::EdgeKind;
use ssitrace::shell::{intersect_shells, JoinStatus, JoinedCurve, ShellIntersection};
use ssitrace::{Method, Options};
use std::path::PathBuf;

fn scene_value(name: &str) -> Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn run(scene: &Value, method: Method) -> ShellIntersection {
    let s = ShellScene::from_json_value(scene).unwrap();
    let opts = Options {
        method,
        ..Options::default()
    };
    intersect_shells(&s.shells[0], &s.shells[1], &opts).unwrap()
}

/// Every branch is a part of exactly one curve, and consecutive parts meet at the joins.
fn check_cover(r: &ShellIntersection) {
    let mut seen = vec![0; r.branch_count()];
    for c in &r.curves {
        for p in &c.parts {
            seen[p.branch] += 1;
        }
        let n = c.parts.len();
        let self_joined = n == 1 && c.joins.len() == 1;
        let expected_joins = if c.closed && (n > 1 || self_joined) {
            n
        } else {
            n - 1
        };
        assert_eq!(c.joins.len(), expected_joins, "{c:?}");
        for (k, j) in c.joins.iter().enumerate() {
            let (a, b) = (c.parts[k], c.parts[(k + 1) % n]);
            assert_eq!(j.ends[0].branch, a.branch);
            assert_eq!(j.ends[0].end, usize::from(!a.reversed));
            assert_eq!(j.ends[1].branch, b.branch);
            assert_eq!(j.ends[1].end, usize::from(b.reversed));
        }
    }
    assert!(seen.iter().all(|&n| n == 1), "{seen:?}");
}

/// The structure of the join: per curve (sorted), the number of parts, whether it is closed,
/// the edge kinds and statuses of its joins (sorted).
fn structure(r: &ShellIntersection) -> Vec<(usize, bool, Vec<String>)> {
    let mut s: Vec<_> = r
        .curves
        .iter()
        .map(|c| {
            let mut j: Vec<String> = c
                .joins
                .iter()
                .map(|j| format!("{:?} {:?}", j.edge, j.status))
                .collect();
            j.sort();
            (c.parts.len(), c.closed, j)
        })
        .collect();
    s.sort();
    s
}

fn all_proven(c: &JoinedCurve) -> bool {
    c.joins.iter().all(|j| j.status == JoinStatus::Proven)
}

/// The coefficients `B(T[i+1], T[i+2])` of a quadratic B-spline with knots `t` for the
/// polynomial whose blossom is `blossom`.
fn coefficients(t: &[f64], blossom: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    (0..t.len() - 3)
        .map(|i| blossom(t[i + 1], t[i + 2]))
        .collect()
}

/// A biquadratic NURBS graph `(u, v, g(u) + h(v))` with knot vectors `tu`, `tv`, from the
/// blossoms of `g` and `h`.
fn nurbs_graph(
    tu: &[f64],
    tv: &[f64],
    g: impl Fn(f64, f64) -> f64,
    h: impl Fn(f64, f64) -> f64,
) -> Value {
    let mid = |a: f64, b: f64| 0.5 * (a + b);
    let (xs, gs) = (coefficients(tu, mid), coefficients(tu, g));
    let (ys, hs) = (coefficients(tv, mid), coefficients(tv, h));
    let mut points = Vec::new();
    for i in 0..xs.len() {
        for j in 0..ys.len() {
            points.push(json!([xs[i], ys[j], gs[i] + hs[j]]));
        }
    }
    json!({"kind": "nurbs", "degree": [2, 2], "knots": [tu, tv], "points": points})
}

/// The bilinear patch spanned by `origin + a·e1 + b·e2`, `a, b ∈ [0, 1]`.
fn plane(origin: [f64; 3], e1: [f64; 3], e2: [f64; 3]) -> Value {
    let at = |a: f64, b: f64| -> Vec<f64> {
        (0..3).map(|k| origin[k] + a * e1[k] + b * e2[k]).collect()
    };
    json!({"kind": "bezier", "degree": [1, 1],
           "points": [at(0.0, 0.0), at(0.0, 1.0), at(1.0, 0.0), at(1.0, 1.0)]})
}

const SPLIT: [f64; 7] = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
const WHOLE: [f64; 6] = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];

/// A NURBS graph of two u-spans cut by the plane y = 0.3 across its knot line u = 1/2.
fn knot_line_scene() -> Value {
    let g = |a: f64, b: f64| 0.5 * (a - 0.3) * (b - 0.3);
    let h = |a: f64, b: f64| 0.2 * a * b;
    json!({"surfaces": [nurbs_graph(&SPLIT, &WHOLE, g, h),
                        plane([-1.0, 0.3, -1.0], [3.0, 0.0, 0.0], [0.0, 0.0, 3.0])]})
}

/// Two bicubic Bézier faces side by side over x ∈ [0, 1] and [1, 2], sharing the edge x = 1;
/// with `flip`, the second face's parameters both run the other way. Cut by y = 0.4.
fn two_faces_scene(flip: bool) -> Value {
    let z = |x: f64, y: f64| 0.1 * x * y + 0.05 * x * x - 0.02 * y;
    let face = |x0: f64, flip: bool| {
        let mut points = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let (a, b) = if flip { (3 - i, 3 - j) } else { (i, j) };
                let (x, y) = (x0 + a as f64 / 3.0, b as f64 / 3.0);
                points.push(json!([x, y, z(x, y)]));
            }
        }
        json!({"kind": "bezier", "degree": [3, 3], "points": points})
    };
    json!({"surfaces": [[face(0.0, false), face(1.0, flip)],
                        plane([-1.0, 0.4, -1.0], [4.0, 0.0, 0.0], [0.0, 0.0, 3.0])]})
}

#[test]
fn nurbs_sphere_circle_is_one_closed_curve_of_four_parts() {
    let scene = ShellScene::from_json_value(&scene_value("nurbs_sphere_plane.json")).unwrap();
    let opts = RunOptions::from_scene_options(&scene.options);
    let report = run_shells(&scene, &opts).unwrap();
    let r = &report.result;
    assert_eq!(
        r.branch_count(),
        4,
        "the per-piece branches stay as they are"
    );
    check_cover(r);
    assert_eq!(r.curves.len(), 1, "{:?}", r.curves);
    let c = &r.curves[0];
    assert!(c.closed);
    assert_eq!(c.parts.len(), 4);
    assert!(all_proven(c), "{:?}", c.joins);
    let kinds: Vec<EdgeKind> = c.joins.iter().map(|j| j.edge).collect();
    assert_eq!(
        kinds.iter().filter(|&&k| k == EdgeKind::KnotLine).count(),
        3
    );
    assert_eq!(kinds.iter().filter(|&&k| k == EdgeKind::Seam).count(), 1);
    let tol = c.certified_tolerance.expect("certified");
    assert!(tol <= 1e-9, "{tol}");
    let parts_max = c
        .parts
        .iter()
        .map(|p| r.branch(p.branch).unwrap().1.certified_tolerance().unwrap())
        .fold(0.0, f64::max);
    assert_eq!(tol, parts_max);
    // The document: the joined curve at the top level, each branch with its curve.
    let doc = result_to_json(&report.curves, &report.meta);
    let curves = doc["joined_curves"].as_array().unwrap();
    assert_eq!(curves.len(), 1);
    assert_eq!(curves[0]["closed"], json!(true));
    assert_eq!(curves[0]["parts"].as_array().unwrap().len(), 4);
    assert_eq!(curves[0]["certified_tolerance"], json!(tol));
    for j in curves[0]["joins"].as_array().unwrap() {
        assert_eq!(j["status"], json!("proven"));
    }
    for b in doc["branches"].as_array().unwrap() {
        assert_eq!(b["curve"], json!(0));
    }
    let back = result_from_json(&doc).unwrap();
    assert_eq!(back.meta.members["joined_curves"], doc["joined_curves"]);
}

#[test]
fn marched_joins_are_flagged_as_marched_and_carry_no_tolerance() {
    let r = run(&scene_value("nurbs_sphere_plane.json"), Method::March);
    check_cover(&r);
    assert_eq!(
        structure(&r),
        vec![(
            4,
            true,
            vec!["KnotLine Marched".to_string(); 3]
                .into_iter()
                .chain(["Seam Marched".to_string()])
                .collect()
        )]
    );
    assert_eq!(r.curves[0].certified_tolerance, None);
}

#[test]
fn a_plane_across_a_knot_line_gives_one_open_curve() {
    let r = run(&knot_line_scene(), Method::Both);
    assert_eq!(r.branch_count(), 2, "one branch per knot span");
    check_cover(&r);
    assert_eq!(r.curves.len(), 1, "{:?}", r.curves);
    let c = &r.curves[0];
    assert!(!c.closed);
    assert_eq!(c.parts.len(), 2);
    assert_eq!(c.joins.len(), 1);
    assert_eq!(c.joins[0].edge, EdgeKind::KnotLine);
    assert!(all_proven(c), "{:?}", c.joins);
    assert!(c.certified_tolerance.unwrap() <= 1e-9);
    // The curve runs from u = 0 to u = 1 (or back) through the knot line.
    let ends: Vec<f64> = [(c.parts[0], 0), (c.parts[1], 1)]
        .iter()
        .map(|&(p, k)| {
            let m = &r.branch(p.branch).unwrap().1.marched;
            let outer = if (k == 0) != p.reversed {
                m.points.first()
            } else {
                m.points.last()
            };
            outer.unwrap().p[0]
        })
        .collect();
    assert!((ends[0] - ends[1]).abs() > 0.999, "{ends:?}");
}

#[test]
fn two_faces_sharing_an_edge_give_one_joined_curve() {
    for (flip, swap) in [(false, false), (true, false), (true, true)] {
        let mut scene = two_faces_scene(flip);
        if swap {
            // The two faces as the second shell: the ends lie on the boundary of surface 1.
            scene["surfaces"].as_array_mut().unwrap().reverse();
        }
        let r = run(&scene, Method::Both);
        assert_eq!(r.branch_count(), 2, "flip {flip}");
        check_cover(&r);
        assert_eq!(r.curves.len(), 1, "flip {flip}: {:?}", r.curves);
        let c = &r.curves[0];
        assert!(!c.closed);
        assert_eq!(c.parts.len(), 2);
        assert_eq!(c.joins[0].edge, EdgeKind::FaceEdge);
        assert!(all_proven(c), "flip {flip}: {:?}", c.joins);
        assert!(c.certified_tolerance.unwrap() <= 1e-9);
    }
}

/// `scene` with every control point of every surface rotated by `m`.
fn rotated(scene: &Value, m: &[[f64; 3]; 3]) -> Value {
    let mut v = scene.clone();
    let rotate = |s: &mut Value| {
        for p in s["points"].as_array_mut().unwrap() {
            let x: Vec<f64> = (0..3).map(|k| p[k].as_f64().unwrap()).collect();
            *p = json!((0..3)
                .map(|r| (0..3).map(|k| m[r][k] * x[k]).sum::<f64>())
                .collect::<Vec<f64>>());
        }
    };
    for side in v["surfaces"].as_array_mut().unwrap() {
        match side.as_array_mut() {
            Some(faces) => faces.iter_mut().for_each(rotate),
            None => rotate(side),
        }
    }
    v
}

/// The rotation by `angle` about the unit vector along `axis` (Rodrigues).
fn rotation(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let n = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [x, y, z] = axis.map(|c| c / n);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

#[test]
fn rotated_scenes_give_the_same_join_structure() {
    let scenes = [
        scene_value("nurbs_sphere_plane.json"),
        knot_line_scene(),
        two_faces_scene(true),
    ];
    let turns = [
        rotation([1.0, 2.0, 3.0], 0.7),
        rotation([-2.0, 0.5, 1.0], 2.3),
        rotation([0.0, 0.0, 1.0], 1.1),
    ];
    for (k, scene) in scenes.iter().enumerate() {
        let base = structure(&run(scene, Method::Both));
        for m in &turns {
            let r = run(&rotated(scene, m), Method::Both);
            check_cover(&r);
            assert_eq!(structure(&r), base, "scene {k}");
        }
    }
}

/// The u-span (0 or 1) of the piece of the first surface a branch was traced on (pieces of a
/// NURBS face are u-span major; here two v-spans).
fn u_span(r: &ShellIntersection, g: usize) -> usize {
    r.branch(g).unwrap().0.pieces[0] / 2
}

#[test]
fn two_curves_near_a_knot_line_are_not_joined_across_it() {
    // z = 100 (u - 1/2)² against the plane z = 1e-4: the lines u = 1/2 ± 1e-3 run beside the
    // knot line u = 1/2 (one in each u-span) and both cross the knot line v = 1/2.
    let g = |a: f64, b: f64| 100.0 * (a - 0.5) * (b - 0.5);
    let scene = json!({"surfaces": [nurbs_graph(&SPLIT, &SPLIT, g, |_, _| 0.0),
                                    plane([-1.0, -1.0, 1e-4], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0])]});
    for method in [Method::March, Method::Both] {
        let r = run(&scene, method);
        assert_eq!(r.branch_count(), 4, "{method:?}");
        check_cover(&r);
        assert_eq!(r.curves.len(), 2, "{method:?}: {:?}", r.curves);
        for c in &r.curves {
            assert!(!c.closed);
            assert_eq!(c.parts.len(), 2);
            assert_eq!(c.joins[0].edge, EdgeKind::KnotLine);
            assert_eq!(
                u_span(&r, c.parts[0].branch),
                u_span(&r, c.parts[1].branch),
                "{method:?}: joined across u = 1/2: {c:?}"
            );
            if method.certifies() {
                assert!(all_proven(c), "{:?}", c.joins);
            }
        }
    }
}

#[test]
fn a_circle_bulging_over_a_knot_line_pairs_its_two_crossings_right() {
    // The paraboloid z = (u - 0.401)² + (v - 1/2)² against z = 0.01: a circle of radius 0.1
    // that crosses the knot line u = 1/2 at two points 0.028 apart.
    let g = |a: f64, b: f64| (a - 0.401) * (b - 0.401);
    let h = |a: f64, b: f64| (a - 0.5) * (b - 0.5);
    let scene = json!({"surfaces": [nurbs_graph(&SPLIT, &WHOLE, g, h),
                                    plane([-1.0, -1.0, 0.01], [3.0, 0.0, 0.0], [0.0, 3.0, 0.0])]});
    for method in [Method::March, Method::Both] {
        let r = run(&scene, method);
        assert_eq!(r.branch_count(), 2, "{method:?}");
        check_cover(&r);
        assert_eq!(r.curves.len(), 1, "{method:?}: {:?}", r.curves);
        let c = &r.curves[0];
        assert!(c.closed);
        assert_eq!(c.parts.len(), 2);
        assert_eq!(c.joins.len(), 2);
        if method.certifies() {
            assert!(all_proven(c), "{:?}", c.joins);
            assert!(c.certified_tolerance.unwrap() <= 1e-9);
        }
    }
}

#[test]
fn joins_of_ends_that_are_not_certified_are_flagged_not_proven() {
    // Three validated steps per half: every branch stops before the knot lines, unproven, so
    // the branches are joined on their marched end points only, and the curve has no tolerance.
    let s = ShellScene::from_json_value(&scene_value("nurbs_sphere_plane.json")).unwrap();
    let opts = Options {
        method: Method::Both,
        max_steps: 3,
        ..Options::default()
    };
    let r = intersect_shells(&s.shells[0], &s.shells[1], &opts).unwrap();
    check_cover(&r);
    assert_eq!(r.curves.len(), 1);
    let c = &r.curves[0];
    assert!(c.closed);
    assert_eq!(c.parts.len(), 4);
    for j in &c.joins {
        assert!(
            matches!(j.status, JoinStatus::Unproven { .. }),
            "{:?}",
            j.status
        );
    }
    assert_eq!(c.certified_tolerance, None);
}

/// The cost of the join on the NURBS sphere scene (run by hand: `cargo test --release --test
/// shell_join join_time -- --ignored --nocapture`): the median over 20 runs of the whole shell
/// intersection and of the join alone, with both methods. No timed assertion.
#[test]
#[ignore]
fn join_time_on_the_nurbs_sphere() {
    let s = ShellScene::from_json_value(&scene_value("nurbs_sphere_plane.json")).unwrap();
    for method in [Method::March, Method::Both] {
        let opts = Options {
            method,
            ..Options::default()
        };
        let mut total = Vec::new();
        let mut join = Vec::new();
        for _ in 0..20 {
            let t = std::time::Instant::now();
            let r = intersect_shells(&s.shells[0], &s.shells[1], &opts).unwrap();
            total.push(t.elapsed().as_secs_f64());
            let t = std::time::Instant::now();
            let again = ssitrace::shell::join::join_branches(&s.shells[0], &s.shells[1], &r.pairs);
            join.push(t.elapsed().as_secs_f64());
            assert_eq!(again, r.curves);
        }
        total.sort_by(f64::total_cmp);
        join.sort_by(f64::total_cmp);
        let (t, j) = (total[10], join[10]);
        println!(
            "{method:?}: shell intersection {:.2} ms (join included), join alone {:.3} ms ({:.2} %)",
            t * 1e3,
            j * 1e3,
            100.0 * j / t
        );
    }
}

#[test]
fn a_closed_single_piece_surface_joins_its_branch_to_itself() {
    // A cubic teardrop loop (first and last control points equal) extruded along z: one Bézier
    // piece whose sides u = 0 and u = 1 are the same line. The plane z = 0.1 cuts it in one
    // loop, traced as one branch from u = 0 to u = 1 and joined to itself across the seam.
    let section = [[0.0, 0.0], [1.5, 1.5], [-1.5, 1.5], [0.0, 0.0]];
    let mut points = Vec::new();
    for xy in section {
        for z in [-1.0, 1.0] {
            points.push(json!([xy[0], xy[1], z]));
        }
    }
    let tube = json!({"kind": "bezier", "degree": [3, 1], "points": points});
    let scene = json!({"surfaces": [tube,
                                    plane([-2.0, -1.0, 0.1], [4.0, 0.0, 0.0], [0.0, 3.0, 0.0])]});
    for method in [Method::March, Method::Both] {
        let r = run(&scene, method);
        assert_eq!(r.branch_count(), 1, "{method:?}");
        check_cover(&r);
        assert_eq!(r.curves.len(), 1);
        let c = &r.curves[0];
        assert!(c.closed, "{method:?}: {c:?}");
        assert_eq!(c.parts.len(), 1);
        assert_eq!(c.joins.len(), 1);
        assert_eq!(c.joins[0].edge, EdgeKind::Seam);
        if method.certifies() {
            assert!(all_proven(c), "{:?}", c.joins);
            assert!(c.certified_tolerance.unwrap() <= 1e-9);
        }
    }
}
