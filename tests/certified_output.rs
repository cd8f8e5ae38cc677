//! Certified output: the pipeline's `validated` / `both` methods, the `"certified"` member of the
//! result JSON, certified events, the SVG overlay and the command-line summary.
//!
//! Every box is checked against a closed form of its scene (not against numbers the code
//! produced): a short parabola arc (paraboloid against a plane, both ends on P's boundary) and a
//! budgeted stretch of the circle of `scenes/sphere_patch_plane.json`.

mod common;

use common::intervals::meets;
use common::scenes::{scene, scene_path};
use inari::Interval;
use serde_json::Value;
use ssitrace::certify::{CertifiedBranch, CertifiedEnd, EnclosureBox};
use ssitrace::io::intersection_json::certificate_json;
use ssitrace::io::result_json::{
    enclosures_from_json, interval_from_json, result_from_json, result_to_json,
};
use ssitrace::io::scene::{Method, Scene};
use ssitrace::io::svg::{certified_overlay, render_svg_with_overlay};
use ssitrace::march::branch::{Branch, BranchStatus, CurvePoint, EndReason};
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::pipeline::{run, RunOptions, RunReport};
use ssitrace::solve::certify_marched_branch;
use ssitrace::Engine;

/// z = x² + y² over [−1/32, 1/32]² against the plane y = 1/64: the arc
/// `(x, 1/64, x² + 1/4096)`, `x ∈ [−1/32, 1/32]`, from P's boundary to P's boundary; on Q
/// (`(u, 1/64, v)` over [−1/16, 1/16]²) it is `v = u² + 1/4096`.
const PARABOLA_ARC: &str = r#"{"surfaces": [
 {"kind": "polynomial", "domain": [[-0.03125, 0.03125], [-0.03125, 0.03125]],
  "x": [[1, 0, 1]], "y": [[0, 1, 1]], "z": [[2, 0, 1], [0, 2, 1]]},
 {"kind": "polynomial", "domain": [[-0.0625, 0.0625], [-0.0625, 0.0625]],
  "x": [[1, 0, 1]], "y": [[0, 0, 0.015625]], "z": [[0, 1, 1]]}],
 "options": {"name": "parabola-arc", "step": 0.005, "method": "validated"}}"#;

const Y0: f64 = 1.0 / 64.0;
const A: f64 = 1.0 / 32.0;

fn sphere_scene() -> Scene {
    scene("sphere_patch_plane.json")
}

/// These tests read the Taylor engine's certificate (proven arc lengths, steps): they run it.
fn run_with(scene: &Scene, method: Method, max_steps: usize) -> RunReport {
    let mut opts = RunOptions::from_scene(scene);
    opts.engine = Engine::Taylor;
    opts.method = method;
    opts.max_steps = max_steps;
    run(scene, &opts).expect("runs")
}

fn the_branch(report: &RunReport) -> &CertifiedBranch {
    let certificates = report.result.certificates();
    assert_eq!(certificates.len(), 1);
    certificates[0]
        .result
        .as_ref()
        .expect("the branch is certified")
}

/// Whether `[lo, hi]` is a finite pair with `lo <= hi`.
fn is_pair(v: &Value) -> bool {
    match v.as_array().map(|a| a.as_slice()) {
        Some([lo, hi]) => match (lo.as_f64(), hi.as_f64()) {
            (Some(lo), Some(hi)) => lo.is_finite() && hi.is_finite() && lo <= hi,
            _ => false,
        },
        _ => false,
    }
}

fn pairs(v: &Value, n: usize) -> bool {
    v.as_array()
        .is_some_and(|a| a.len() == n && a.iter().all(is_pair))
}

/// Checks the documented layout of a `"certified"` object and returns its enclosures.
fn check_certified_layout(c: &Value, steps: usize) -> Vec<EnclosureBox> {
    for key in [
        "enclosures",
        "tolerance",
        "steps",
        "end_reasons",
        "start",
        "fixed",
        "start_uniqueness",
        "max_width",
        "meets_tolerance",
        "required_tolerance",
        "start_point",
        "max_length",
        "seconds",
    ] {
        assert!(c.get(key).is_some(), "certified.{key} missing");
    }
    assert_eq!(c["steps"].as_u64(), Some(steps as u64));
    let encl = c["enclosures"].as_array().unwrap();
    assert_eq!(encl.len(), steps);
    for e in encl {
        let s = e["s"].as_array().unwrap();
        assert!(s[0].as_f64().unwrap() <= s[1].as_f64().unwrap());
        assert!(pairs(&e["p"], 2) && pairs(&e["q"], 2) && pairs(&e["xyz"], 3));
    }
    assert!(pairs(&c["start"], 4) && pairs(&c["start_uniqueness"], 4));
    assert!(c["fixed"].as_u64().unwrap() < 4);
    let tol = c["tolerance"].as_f64().unwrap();
    assert!(tol > 0.0 && tol.is_finite());
    assert!(c["max_width"].as_f64().unwrap() >= 0.0);
    assert_eq!(
        c["meets_tolerance"].as_bool(),
        Some(tol <= c["required_tolerance"].as_f64().unwrap())
    );
    let ends = c["end_reasons"].as_array().unwrap();
    assert_eq!(ends.len(), 2);
    for e in ends {
        let kind = e["kind"].as_str().unwrap();
        match kind {
            "boundary" => assert!(e["surface"].as_u64().unwrap() <= 1),
            "closed_loop" => {}
            "singular" | "close_branches" | "unproven" => {
                assert!(e["near"].as_array().unwrap().len() == 4)
            }
            other => panic!("undocumented end kind {other}"),
        }
        if kind == "unproven" {
            assert!(e["reason"].as_str().is_some_and(|r| !r.is_empty()));
        }
    }
    enclosures_from_json(c).expect("enclosures read back")
}

/// The chain covers one arc-length interval without gaps: each box starts where the last ended.
fn check_contiguous(boxes: &[EnclosureBox]) -> (f64, f64) {
    for w in boxes.windows(2) {
        assert_eq!(w[0].s[1], w[1].s[0], "arc-length gap in the chain");
        assert!(w[0].overlaps(&w[1]));
    }
    (boxes[0].s[0], boxes[boxes.len() - 1].s[1])
}

#[test]
fn parabola_arc_is_certified_end_to_end_and_every_box_holds_the_arc() {
    let scene = Scene::from_json_str(PARABOLA_ARC).unwrap();
    let report = run_with(&scene, Method::Validated, 5000);
    assert_eq!(report.result.branches.len(), 1);
    let cb = the_branch(&report);
    assert_eq!(
        cb.ends,
        [
            CertifiedEnd::Boundary { surface: 0 },
            CertifiedEnd::Boundary { surface: 0 }
        ]
    );
    // Closed form: every point of the arc has t = y = 1/64, z = x² + 1/4096, v = u² + 1/4096,
    // σ = u = x. Each box must be able to hold such a point.
    let (y0, c) = (point(Y0), point(1.0 / 4096.0));
    for b in &cb.boxes {
        assert!(b.p[1].contains(Y0) && b.xyz[1].contains(Y0));
        let x = b.xyz[0].intersection(b.p[0]).intersection(b.q[0]);
        assert!(!x.is_empty(), "σ, u and x boxes share no value");
        assert!(meets(b.xyz[2], x.sqr() + c));
        assert!(meets(b.q[1], b.q[0].sqr() + c));
        assert!(meets(b.xyz[1], y0));
    }
    // Arc length covered: at least the arc's length ∫ √(1 + 4x²) dx over [−A, A] (the last
    // boxes straddle the boundary), and not much more.
    let half = |x: f64| x * (1.0 + 4.0 * x * x).sqrt() / 2.0 + (2.0 * x).asinh() / 4.0;
    let length = half(A) - half(-A);
    let (s0, s1) = check_contiguous(&cb.boxes);
    println!(
        "parabola arc: {} steps, covered s ∈ [{s0:.6}, {s1:.6}] (arc length {length:.6}), tolerance {:.3e}, {:.0} ms",
        cb.steps(),
        cb.certified_tolerance,
        report.result.stats.certify_seconds() * 1e3
    );
    assert!(s1 - s0 >= length * (1.0 - 1e-12));
    assert!(s1 - s0 <= length + 0.01);
    // The straying check: the marched points all lie on the certified arc, which (cut where the
    // reported curve leaves the domain) is the arc's length, and they span all of it.
    let st = report.result.straying()[0];
    println!(
        "straying check: {} straying, {} unchecked, certified length {:.9} (closed form {length:.9}), covered {:.6}",
        st.straying.len(),
        st.unchecked.len(),
        st.certified_length,
        st.covered_fraction
    );
    assert!(st.straying.is_empty() && st.unchecked.is_empty() && !st.looping);
    assert!(
        (st.certified_length - length).abs() < 1e-9,
        "{}",
        st.certified_length
    );
    assert!(st.covered_fraction > 0.9999, "{}", st.covered_fraction);
    // JSON: documented fields, and the boxes read back bit for bit.
    let doc = result_to_json(&report.result.marched(), &report.meta);
    assert_eq!(doc["method"], "validated");
    let c = &doc["branches"][0]["certified"];
    let back = check_certified_layout(c, cb.steps());
    assert_eq!(back, cb.boxes);
    assert!(c.get("tubes").is_none(), "tubes only on request");
    assert_eq!(c["end_reasons"][0]["kind"], "boundary");
    assert_eq!(c["end_reasons"][0]["surface"], 0);
    let start: Vec<Interval> = c["start"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| interval_from_json(v).unwrap())
        .collect();
    assert_eq!(start, cb.start.to_vec());
    assert!(start[1].contains(Y0));
    // The whole document survives a trip through text.
    let text = serde_json::to_string(&doc).unwrap();
    let read = result_from_json(&serde_json::from_str(&text).unwrap()).unwrap();
    assert_eq!(read.meta, report.meta);
}

#[test]
fn budgeted_circle_boxes_hold_the_circle_and_ends_are_unproven() {
    let scene = sphere_scene();
    let report = run_with(&scene, Method::Both, 25);
    let cb = the_branch(&report);
    assert_eq!(cb.steps(), 50);
    for e in &cb.ends {
        assert!(matches!(e, CertifiedEnd::Unproven { .. }), "{e:?}");
    }
    // The circle y² + z² = 141/256 on x = 11/8; on Q (u − ½)² + (v − ½)² = 141/1024.
    let r2 = point(141.0 / 256.0);
    let r2q = point(141.0 / 1024.0);
    let half = point(0.5);
    for b in &cb.boxes {
        assert!(b.xyz[0].contains(11.0 / 8.0));
        assert!(meets(b.xyz[1].sqr() + b.xyz[2].sqr(), r2));
        assert!(meets((b.q[0] - half).sqr() + (b.q[1] - half).sqr(), r2q));
    }
    check_contiguous(&cb.boxes);
    let doc = result_to_json(&report.result.marched(), &report.meta);
    assert_eq!(doc["method"], "both");
    let c = &doc["branches"][0]["certified"];
    check_certified_layout(c, 50);
    assert_eq!(c["end_reasons"][0]["kind"], "unproven");
    assert_eq!(c["end_reasons"][1]["kind"], "unproven");
    assert_eq!(doc["stats"]["certified_steps"], 50);
    // Budget per half: 1.5 × the marched loop length (2π·√141/16 ≈ 4.66).
    let loop_length = 2.0 * std::f64::consts::PI * 141f64.sqrt() / 16.0;
    let budget = c["max_length"].as_f64().unwrap();
    assert!((budget / loop_length - 1.5).abs() < 0.01, "{budget}");
}

/// A marched "branch" that is not on the curve: certification fails, and the failure is a
/// per-branch `{"error": ...}`, not an error of the run.
#[test]
fn a_branch_that_cannot_be_certified_is_reported_as_an_error_object() {
    let scene = sphere_scene();
    let [p, q] = &scene.surfaces;
    let off = CurvePoint {
        p: [0.5, 0.5],
        q: [0.5, 0.5],
        xyz: [1.5, 0.0, 0.0],
    };
    let branch = Branch {
        id: 7,
        status: BranchStatus::Incomplete,
        ends: [EndReason::NewtonFailed; 2],
        points: vec![off; 3],
    };
    let opts = RunOptions::from_scene(&scene);
    let cert = certify_marched_branch(p, q, &branch, &opts.options());
    assert_eq!(cert.branch, 7);
    let err = cert.result.as_ref().expect_err("off the curve");
    let v = certificate_json(&cert, opts.required_tolerance, false);
    assert_eq!(v["error"].as_str(), Some(err.to_string().as_str()));
    assert!(v.get("enclosures").is_none() && v.get("meets_tolerance").is_none());
    assert!(enclosures_from_json(&v).is_err());
    // An empty branch fails the same way, without a start point.
    let empty = Branch {
        points: Vec::new(),
        ..branch
    };
    let cert = certify_marched_branch(p, q, &empty, &opts.options());
    let v = certificate_json(&cert, opts.required_tolerance, false);
    assert!(v["error"].as_str().is_some() && v.get("start_point").is_none());
}

/// Certified singular / close-branch ends become events with a `"box"`, survive the JSON
/// round trip, and their boxes are drawn.
#[test]
fn singular_and_close_branch_ends_become_box_events() {
    let iv = |lo: f64, hi: f64| interval(lo, hi).unwrap();
    let link = EnclosureBox {
        s: [0.0, 0.1],
        p: [iv(0.1, 0.2), iv(0.3, 0.4)],
        q: [iv(0.5, 0.6), iv(0.7, 0.8)],
        xyz: [iv(1.0, 1.1), iv(2.0, 2.1), iv(3.0, 3.1)],
    };
    let near = [iv(0.2, 0.25), iv(0.4, 0.45), iv(0.6, 0.65), iv(0.8, 0.85)];
    let cb = CertifiedBranch {
        start: link.params(),
        fixed: 0,
        start_uniqueness: link.params(),
        boxes: vec![link],
        tubes: Vec::new(),
        certified_tolerance: 1e-12,
        ends: [
            CertifiedEnd::Singular { near },
            CertifiedEnd::CloseBranches { h: 1e-9, near },
        ],
        widths: vec![1e-13],
        tolerance_limit: None,
    };
    let xyz_of = |_: &[Interval; 4]| Some([iv(1.0, 2.0), iv(3.0, 4.0), iv(5.0, 6.0)]);
    let events = ssitrace::io::result_json::certified_events_to_json(4, &cb, &xyz_of);
    assert_eq!(events.len(), 2);
    assert_eq!(events[0]["kind"], "singular_box");
    assert_eq!(events[1]["kind"], "close_branches");
    assert_eq!(events[1]["h"], 1e-9);
    for (k, e) in events.iter().enumerate() {
        assert_eq!(e["branch"], 4);
        assert_eq!(e["end"], k);
        assert!(pairs(&e["box"]["p"], 2) && pairs(&e["box"]["q"], 2));
        assert!(pairs(&e["box"]["xyz"], 3));
        assert_eq!(interval_from_json(&e["box"]["q"][1]).unwrap(), near[3]);
    }
    let mut meta = ssitrace::io::result_json::ResultMeta::new(None, "validated");
    meta.certified_events = events.clone();
    let ix = ssitrace::march::branch::Intersection::default();
    let doc = result_to_json(&ix, &meta);
    assert_eq!(doc["events"].as_array().unwrap().len(), 2);
    let back = result_from_json(&doc).unwrap();
    assert_eq!(back.meta.certified_events, events);
    assert!(back.intersection.events.is_empty());
    // A certified event without its box is rejected.
    let mut broken = doc.clone();
    broken["events"][0].as_object_mut().unwrap().remove("box");
    assert!(result_from_json(&broken).is_err());
    // The overlay: the chain's box plus both end boxes, in each parameter panel.
    let overlay = certified_overlay(&[&cb], 100);
    assert_eq!(overlay.p_boxes.len(), 3);
    assert_eq!(overlay.q_boxes.len(), 3);
    assert_eq!(overlay.xyz_boxes.len(), 1);
    assert_eq!(overlay.p_boxes[1], [[0.2, 0.25], [0.4, 0.45]]);
    assert_eq!(overlay.xyz_boxes[0], [[1.0, 2.0, 3.0], [1.1, 2.1, 3.1]]);
}

#[test]
fn overlay_merges_boxes_into_hulls_that_hold_them() {
    let scene = sphere_scene();
    let report = run_with(&scene, Method::Validated, 10);
    let cb = the_branch(&report);
    let overlay = certified_overlay(&[cb], 6);
    // 20 boxes in runs of ⌈20/6⌉ = 4: 5 hulls.
    assert_eq!(overlay.p_boxes.len(), 5);
    for (k, b) in cb.boxes.iter().enumerate() {
        let h = overlay.p_boxes[k / 4];
        let m = overlay.xyz_boxes[k / 4];
        for (hi, x) in h.iter().zip(&b.p) {
            assert!(hi[0] <= x.inf() && x.sup() <= hi[1]);
        }
        for (i, x) in b.xyz.iter().enumerate() {
            assert!(m[0][i] <= x.inf() && x.sup() <= m[1][i]);
        }
    }
    let svg = render_svg_with_overlay(
        &report.result.marched(),
        [scene.surfaces[0].domain(), scene.surfaces[1].domain()],
        "hulls",
        &overlay,
    )
    .unwrap();
    assert!(svg.contains("5 certified box(es)"));
}

/// The command line: flags, the per-branch summary, the JSON with tubes, and the SVG boxes.
#[test]
fn command_line_prints_the_certificate_and_draws_its_boxes() {
    let dir = std::env::temp_dir().join(format!("ssitrace-cert-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (out, svg) = (dir.join("r.json"), dir.join("r.svg"));
    let scene = scene_path("sphere_patch_plane.json").display().to_string();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .args(["trace", &scene, "--method", "both", "--max-steps", "10"])
        .args(["--engine", "taylor"])
        .args(["--tolerance", "1e-300", "--tubes", "--out"])
        .arg(&out)
        .arg("--svg")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(run.status.success());
    let stdout = String::from_utf8_lossy(&run.stdout);
    println!("{stdout}");
    assert!(stdout.contains("certified: 20 steps"));
    assert!(stdout.contains("does NOT meet 1.0e-300"));
    assert!(stdout.contains("ends UNPROVEN (budget spent (10 steps"));
    assert!(stdout.contains("max width"));
    assert!(stdout.contains("ratio certified/marching"));
    assert!(stdout.contains("marched points: none strays"));
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(doc["method"], "both");
    let c = &doc["branches"][0]["certified"];
    assert_eq!(c["meets_tolerance"], false);
    // The straying check: the 20 budgeted steps cover a short arc of the loop; the marched
    // points beyond the two unproven ends are unchecked, none strays.
    let st = &c["straying"];
    let n = doc["branches"][0]["points"].as_array().unwrap().len();
    let unchecked = st["unchecked_points"].as_array().unwrap().len();
    assert!(unchecked > 0 && unchecked < n, "{unchecked} of {n}");
    assert_eq!(st["straying_points"].as_array().map(Vec::len), Some(0));
    assert_eq!(st["looping"], false);
    assert_eq!(doc["stats"]["unchecked_points"], unchecked);
    assert_eq!(doc["stats"]["straying_points"], 0);
    assert_eq!(doc["stats"]["looping_branches"], 0);
    let boxes = enclosures_from_json(c).unwrap();
    // Tubes: one per step; the reported point is within radius_param of the true point, which
    // the step's box holds; and it is on the circle of Q up to that radius.
    let tubes = c["tubes"].as_array().unwrap();
    assert_eq!(tubes.len(), 20);
    for (t, b) in tubes.iter().zip(&boxes) {
        let h = t["h"].as_f64().unwrap();
        let r = t["radius_param"].as_f64().unwrap();
        assert!(r >= 0.0 && t["radius_xyz"].as_f64().unwrap() <= c["tolerance"].as_f64().unwrap());
        let coeffs: Vec<Vec<f64>> = serde_json::from_value(t["coeffs"].clone()).unwrap();
        let y: Vec<f64> = (0..4)
            .map(|i| coeffs.iter().rev().fold(0.0, |acc, cf| acc * h + cf[i]))
            .collect();
        let grown = |x: Interval| interval(x.inf() - r, x.sup() + r).unwrap();
        for (i, x) in b.params().iter().enumerate() {
            assert!(grown(*x).contains(y[i]), "tube point outside its box");
        }
        let on_q = (y[2] - 0.5).powi(2) + (y[3] - 0.5).powi(2) - 141.0 / 1024.0;
        assert!(on_q.abs() < 1e-9, "{on_q}");
    }
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.contains("20 certified box(es)"));
    let outlines = picture
        .split("<polyline")
        .skip(1)
        .map(|t| &t[..t.find("/>").unwrap_or(t.len())])
        .filter(|t| t.contains("opacity=\"0.45\"") && t.contains("stroke-width=\"4\""))
        .count();
    assert_eq!(
        outlines,
        20 * 2 + 20 * 12 + 1,
        "P and Q outlines, model edges, key"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
