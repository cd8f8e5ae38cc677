//! Shell scenes: NURBS faces split into Bézier pieces, every piece of A against every piece of
//! B, the `"pair"` of faces on every branch, and the same result as before for two plain
//! surfaces.

use serde_json::{json, Value};
use ssitrace::error::Error;
use ssitrace::io::intersection_json::shell_result;
use ssitrace::io::result_json::{result_from_json, result_to_json};
use ssitrace::io::scene::{Scene, ShellScene};
use ssitrace::march::branch::EndReason;
use ssitrace::pipeline::{run_shells, RunOptions};
use ssitrace::shell::intersect_shells;
use ssitrace::{intersect, Method, Options};
use std::path::PathBuf;

fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

fn scene_value(name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(scene_path(name)).unwrap()).unwrap()
}

fn march() -> Options {
    Options {
        method: Method::March,
        ..Options::default()
    }
}

#[test]
fn two_plain_surfaces_give_the_same_result_through_the_shell_driver() {
    for name in ["sphere_patch_plane.json", "wu_andrade_fig7.json"] {
        let shells = ShellScene::from_path(&scene_path(name)).unwrap();
        let pair = Scene::from_path(&scene_path(name)).unwrap();
        assert_eq!(shells.as_pair().as_ref(), Some(&pair), "{name}");
        let [p, q] = &pair.surfaces;
        let direct = intersect(p, q, &march()).unwrap();
        let s = intersect_shells(&shells.shells[0], &shells.shells[1], &march()).unwrap();
        assert_eq!((s.piece_pairs, s.skipped_pairs, s.pairs.len()), (1, 0, 1));
        let via = &s.pairs[0].result;
        assert_eq!(via.branches.len(), direct.branches.len(), "{name}");
        for (a, b) in via.branches.iter().zip(&direct.branches) {
            assert_eq!(a.marched, b.marched, "{name}");
        }
    }
}

/// The distance of `x` from the circle x² + y² = 1 − h², z = h.
fn circle_distance(x: [f64; 3], h: f64) -> f64 {
    let r = (1.0 - h * h).sqrt();
    let rho = x[0].hypot(x[1]);
    (rho - r).hypot(x[2] - h)
}

#[test]
fn nurbs_sphere_against_a_plane_gives_one_branch_per_piece_on_the_circle() {
    // The standard 9 × 5 NURBS sphere (weights √2/2 and 1/2 as intervals enclosing them)
    // against the plane z = 0.3: the circle crosses the four u-spans of the v-span [1, 2].
    let scene = ShellScene::from_path(&scene_path("nurbs_sphere_plane.json")).unwrap();
    assert!(scene.as_pair().is_none());
    assert_eq!(scene.shells[0][0].pieces().len(), 8);
    let opts = RunOptions::from_scene_options(&scene.options);
    assert_eq!(opts.method, Method::Both);
    let report = run_shells(&scene, &opts).unwrap();
    let r = &report.result;
    assert!(r.is_complete());
    assert_eq!(r.piece_pairs, 8);
    assert_eq!(r.branch_count(), 4, "one branch per Bézier piece crossed");
    let mut spans = Vec::new();
    for p in &r.pairs {
        assert_eq!(p.faces, [0, 0]);
        for b in &p.result.branches {
            let m = &b.marched;
            assert!(m
                .ends
                .iter()
                .all(|e| matches!(e, EndReason::Boundary { surface: 0 })));
            let mut lo = f64::INFINITY;
            let mut hi = f64::NEG_INFINITY;
            for pt in &m.points {
                let d = circle_distance(pt.xyz, 0.3);
                assert!(
                    d < 1e-9,
                    "piece {:?}: {:?} is {d:e} off the circle",
                    p.pieces,
                    pt.xyz
                );
                // Parameters are the NURBS's own: u in the piece's knot span, v in [1, 2].
                assert!((1.0..=2.0).contains(&pt.p[1]), "{:?}", pt.p);
                lo = lo.min(pt.p[0]);
                hi = hi.max(pt.p[0]);
            }
            let c = b.certified().expect("certified");
            assert!(c.certified_tolerance <= 1e-9, "{}", c.certified_tolerance);
            spans.push([lo, hi]);
        }
    }
    // Together the four arcs cover the circle: their u-ranges tile [0, 4] knot span by span.
    spans.sort_by(|a, b| a[0].total_cmp(&b[0]));
    for (k, [lo, hi]) in spans.iter().enumerate() {
        assert!(
            (lo - k as f64).abs() < 1e-9 && (hi - (k + 1) as f64).abs() < 1e-9,
            "{spans:?}"
        );
    }
    // Every branch of the document carries its pair, and the document reads back.
    let doc = result_to_json(&report.curves, &report.meta);
    let branches = doc["branches"].as_array().unwrap();
    assert_eq!(branches.len(), 4);
    for (k, b) in branches.iter().enumerate() {
        assert_eq!(b["id"], k);
        assert_eq!(b["pair"], json!([0, 0]));
        assert!(b["certified"].is_object());
    }
    let back = result_from_json(&doc).unwrap();
    assert_eq!(back.intersection, report.curves);
}

#[test]
fn shells_of_several_faces_pair_every_face() {
    let mut v = scene_value("nurbs_sphere_plane.json");
    let sphere = v["surfaces"][0].clone();
    let plane = v["surfaces"][1].clone();
    let far = json!({"kind": "bezier", "degree": [1, 1],
        "points": [[10, 10, 0], [10, 11, 0], [11, 10, 0], [11, 11, 1]]});
    let mut low = plane.clone();
    for p in low["points"].as_array_mut().unwrap() {
        p[2] = json!(-0.5);
    }
    v["surfaces"] = json!([[far, sphere], [plane, low]]);
    v["options"]["method"] = json!("march");
    let scene = ShellScene::from_json_value(&v).unwrap();
    assert_eq!((scene.shells[0].len(), scene.shells[1].len()), (2, 2));
    let r = intersect_shells(&scene.shells[0], &scene.shells[1], &march()).unwrap();
    // 2 faces × 2 faces, the sphere in 8 pieces: 2 + 16 piece pairs; the far patch and the
    // sphere pieces away from each plane are filtered out by their boxes.
    assert_eq!(r.piece_pairs, 18);
    assert!(r.pairs.iter().all(|p| p.faces[0] == 1));
    assert_eq!(r.branch_count(), 8);
    let (curves, meta) = shell_result(None, &r, false);
    let doc = result_to_json(&curves, &meta);
    let mut per_pair = [0; 2];
    for b in doc["branches"].as_array().unwrap() {
        let pair = b["pair"].as_array().unwrap();
        assert_eq!(pair[0], 1);
        let j = pair[1].as_u64().unwrap() as usize;
        per_pair[j] += 1;
        let h = [0.3, -0.5][j];
        for pt in b["points"].as_array().unwrap() {
            let x: Vec<f64> = pt["xyz"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| c.as_f64().unwrap())
                .collect();
            assert!(circle_distance([x[0], x[1], x[2]], h) < 1e-9);
        }
    }
    assert_eq!(per_pair, [4, 4]);
    assert_eq!(
        doc["stats"]["pairs"].as_array().unwrap().len(),
        r.pairs.len()
    );
    // The pair-only reader refuses a shell scene, naming the field.
    match Scene::from_json_value(&v) {
        Err(Error::InvalidInput { field, .. }) => assert_eq!(field, "surfaces"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_faces_in_a_shell_name_the_side_face_and_field() {
    let mut v = scene_value("nurbs_sphere_plane.json");
    let sphere = v["surfaces"][0].clone();
    let mut bad = sphere.clone();
    bad["knots"][0][4] = json!(0.5);
    v["surfaces"][0] = json!([sphere.clone(), bad]);
    match ShellScene::from_json_value(&v) {
        Err(Error::InvalidInput { surface, field, .. }) => {
            assert_eq!((surface, field.as_str()), (Some(0), "face[1].knots[0][4]"));
        }
        other => panic!("{other:?}"),
    }
    let mut bad = sphere.clone();
    bad["weights"][7] = json!(-1.0);
    v["surfaces"][0] = bad;
    match ShellScene::from_json_value(&v) {
        Err(Error::InvalidInput { surface, field, .. }) => {
            assert_eq!((surface, field.as_str()), (Some(0), "weights[7]"));
        }
        other => panic!("{other:?}"),
    }
    let mut bad = sphere.clone();
    bad["points"].as_array_mut().unwrap().pop();
    v["surfaces"] = json!([v["surfaces"][1].clone(), [bad]]);
    match ShellScene::from_json_value(&v) {
        Err(Error::InvalidInput { surface, field, .. }) => {
            assert_eq!((surface, field.as_str()), (Some(1), "face[0].points"));
        }
        other => panic!("{other:?}"),
    }
    v["surfaces"] = json!([[], v["surfaces"][0].clone()]);
    assert!(matches!(
        ShellScene::from_json_value(&v),
        Err(Error::InvalidInput {
            surface: Some(0),
            ..
        })
    ));
}
