//! The marcher checked against the certified tubes: a normal march on Fig. 7 has no straying
//! point; points spliced in from a neighbouring loop stray onto it; a loop marched twice loops;
//! a polyline shifted off the curve strays; a certificate that ends early leaves the rest
//! unchecked; and `both` is the command line's default method.

mod common;

use common::scenes::{scene, scene_path};
use serde_json::Value;
use ssitrace::certify::{
    certify_branch, CertifiedBranch, CertifiedEnd, CertifyOptions, StepBudget,
};
use ssitrace::check::straying::{check_branch, check_branches, StrayReport};
use ssitrace::io::scene::Scene;
use ssitrace::march::branch::{polyline_length, Branch, BranchStatus, CurvePoint, EndReason};
use ssitrace::march::MarchOptions;
use ssitrace::search::start_points::SearchOptions;
use ssitrace::topology::intersect::intersect;
use std::time::Instant;

/// The marcher's Newton tolerance, which the check compares with.
const TOL: f64 = 1e-10;

fn march(s: &Scene) -> Vec<Branch> {
    let opts = MarchOptions {
        step: s.options.step,
        newton_tolerance: TOL,
        ..MarchOptions::default()
    };
    let [p, q] = &s.surfaces;
    intersect(p, q, &opts, &SearchOptions::default())
        .intersection
        .branches
}

fn params(c: &CurvePoint) -> [f64; 4] {
    [c.p[0], c.p[1], c.q[0], c.q[1]]
}

fn certify(s: &Scene, start: &CurvePoint, max_steps: usize) -> CertifiedBranch {
    let opts = CertifyOptions {
        steps: StepBudget {
            max_steps,
            ..StepBudget::CERTIFY
        },
        ..CertifyOptions::default()
    };
    let [p, q] = &s.surfaces;
    certify_branch(p, q, params(start), &opts).expect("certifies")
}

/// Whether the point lies in some enclosure box of the chain grown by `grow` (independent of
/// the straying check: the boxes alone).
fn in_some_box(c: &CertifiedBranch, pt: &CurvePoint, grow: f64) -> bool {
    let y = params(pt);
    c.boxes.iter().any(|b| {
        b.params()
            .iter()
            .zip(&y)
            .all(|(x, v)| x.inf() - grow <= *v && *v <= x.sup() + grow)
    })
}

fn print_report(label: &str, b: &Branch, r: &StrayReport) {
    println!(
        "{label:>28}: {:>4} points, {:>3} straying, {:>4} unchecked, looping {:<5}, covered {:.4}, marched {:.4}, certified {:.4}",
        b.points.len(),
        r.straying.len(),
        r.unchecked.len(),
        r.looping,
        r.covered_fraction,
        r.marched_length,
        r.certified_length
    );
}

/// Fig. 7's level `3u² + v²` of a branch (0.5, 0.6 or 0.7).
fn level(b: &Branch) -> f64 {
    let p = b.points[0].p;
    3.0 * p[0] * p[0] + p[1] * p[1]
}

#[test]
fn fig7_normal_march_has_no_straying_point() {
    let s = scene("wu_andrade_fig7.json");
    let [p, q] = &s.surfaces;
    let branches = march(&s);
    assert_eq!(branches.len(), 3);
    let started = Instant::now();
    // Budgeted certificates (the full loops take ~20 s): 20 steps each way from the middle.
    let certs: Vec<CertifiedBranch> = branches
        .iter()
        .map(|b| certify(&s, &b.points[b.points.len() / 2], 20))
        .collect();
    let certify_seconds = started.elapsed().as_secs_f64();
    let refs: Vec<Option<&CertifiedBranch>> = certs.iter().map(Some).collect();
    let started = Instant::now();
    let reports = check_branches(p, q, &branches, &refs, TOL);
    println!(
        "Fig. 7, certified 20 steps each way: certify {certify_seconds:.2} s, check {:.1} ms",
        started.elapsed().as_secs_f64() * 1e3
    );
    for ((b, c, r), k) in branches
        .iter()
        .zip(&certs)
        .zip(&reports)
        .map(|((b, c), r)| (b, c, r))
        .zip(0..)
    {
        print_report(&format!("loop {k} (level {:.2})", level(b)), b, r);
        assert_eq!(c.ends[1].kind(), "unproven", "budgeted: {:?}", c.ends);
        assert!(r.straying.is_empty(), "{:?}", r.straying);
        assert!(!r.looping);
        // Unchecked are exactly the points outside the certified boxes (beyond both unproven
        // ends); the rest were compared.
        for (i, pt) in b.points.iter().enumerate() {
            let inside = in_some_box(c, pt, 1e-9);
            assert_eq!(r.unchecked.contains(&i), !inside, "point {i}");
        }
        let checked = b.points.len() - r.unchecked.len();
        assert!(checked >= 3, "only {checked} points compared");
        // The marcher spans the whole certified arc (leaving it through the unproven ends).
        assert!(r.covered_fraction > 0.999, "{}", r.covered_fraction);
    }
}

#[test]
fn fig7_points_spliced_from_a_neighbouring_loop_stray_onto_it() {
    let s = scene("wu_andrade_fig7.json");
    let [p, q] = &s.surfaces;
    let mut branches = march(&s);
    branches.sort_by(|a, b| level(a).total_cmp(&level(b)));
    let (inner, middle) = (&branches[0], &branches[1]);
    let i0 = middle.points.len() / 2;
    let nearest = |pt: &CurvePoint| {
        *inner
            .points
            .iter()
            .min_by(|a, b| {
                let d = |c: &CurvePoint| (c.p[0] - pt.p[0]).hypot(c.p[1] - pt.p[1]);
                d(a).total_cmp(&d(b))
            })
            .unwrap()
    };
    let own = certify(&s, &middle.points[i0], 60);
    let other = certify(&s, &nearest(&middle.points[i0]), 60);
    let mut strayed = middle.clone();
    // Either side of the certified start (the marched point i0 itself).
    let spliced = [i0 - 1, i0 + 1];
    for &i in &spliced {
        strayed.points[i] = nearest(&middle.points[i]);
    }
    let r = check_branch(p, q, &strayed, &own, &[(inner.id, &other)], TOL);
    print_report("middle loop, 2 spliced", &strayed, &r);
    let got: Vec<usize> = r.straying.iter().map(|x| x.index).collect();
    assert_eq!(got, spliced);
    for x in &r.straying {
        println!(
            "    point {}: proven distance {:.4e}, estimate {:.4e}, slack {:.2e}, onto {:?}",
            x.index, x.distance, x.estimate, x.slack, x.onto
        );
        assert_eq!(x.onto, Some(inner.id));
        // The levels 0.5 and 0.6 are at least 0.1 / max|∇(3u² + v²)| ≥ 0.1 / (6·0.46) apart in
        // (σ, t) (|u| ≤ √(0.6/3), |v| ≤ √0.6), i.e. ≥ 0.036 / √2 in the max norm.
        assert!(x.distance > 0.025 && x.distance <= x.estimate, "{x:?}");
    }
    // Spliced outside the middle loop's certified arc, the same points are unchecked.
    let far = middle.points.len() - 1 - 3;
    let mut beyond = middle.clone();
    for i in far..far + 3 {
        assert!(!in_some_box(&own, &middle.points[i], 1e-9));
        beyond.points[i] = nearest(&middle.points[i]);
    }
    let r = check_branch(p, q, &beyond, &own, &[(inner.id, &other)], TOL);
    assert!(r.straying.is_empty(), "{:?}", r.straying);
    assert!((far..far + 3).all(|i| r.unchecked.contains(&i)));
}

fn sphere_loop() -> (Scene, Branch, CertifiedBranch) {
    let s = scene("sphere_patch_plane.json");
    let branches = march(&s);
    assert_eq!(branches.len(), 1);
    let b = branches[0].clone();
    assert_eq!(b.status, BranchStatus::Closed);
    let c = certify(&s, &b.points[b.points.len() / 2], 20_000);
    assert_eq!(c.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
    (s, b, c)
}

#[test]
fn a_loop_marched_twice_is_looping_and_a_short_march_covers_part() {
    let (s, b, c) = sphere_loop();
    let [p, q] = &s.surfaces;
    let once = check_branch(p, q, &b, &c, &[], TOL);
    print_report("sphere loop", &b, &once);
    assert!(once.straying.is_empty() && once.unchecked.is_empty() && !once.looping);
    // The circle of radius √141/16 has length 2π√141/16; the certified chain is that loop.
    let perimeter = std::f64::consts::TAU * 141f64.sqrt() / 16.0;
    assert!((once.certified_length - perimeter).abs() < 1e-3 * perimeter);
    assert!(once.covered_fraction > 0.999, "{}", once.covered_fraction);

    let mut twice = b.clone();
    twice.points.extend_from_slice(&b.points[1..]);
    let r = check_branch(p, q, &twice, &c, &[], TOL);
    print_report("sphere loop marched twice", &twice, &r);
    assert!(r.looping && r.straying.is_empty());
    // Going on a quarter past the start is a second traversal too.
    let mut more = b.clone();
    more.points
        .extend_from_slice(&b.points[1..b.points.len() / 4]);
    more.points.push(b.points[0]);
    let r = check_branch(p, q, &more, &c, &[], TOL);
    print_report("sphere loop + a quarter", &more, &r);
    assert!(r.looping);

    // A march that stopped halfway covers about half of the certified loop; nothing strays.
    let half_n = b.points.len() / 2;
    let half = Branch {
        status: BranchStatus::Incomplete,
        ends: [EndReason::PointLimit; 2],
        points: b.points[..half_n].to_vec(),
        ..b.clone()
    };
    let r = check_branch(p, q, &half, &c, &[], TOL);
    print_report("sphere loop, first half", &half, &r);
    assert!(r.straying.is_empty() && r.unchecked.is_empty() && !r.looping);
    // Chords are shorter than arcs by O(step²): the polyline length is a close estimate.
    let expect = r.marched_length / r.certified_length;
    assert!(
        (r.covered_fraction - expect).abs() < 1e-3,
        "{} vs {expect}",
        r.covered_fraction
    );
    assert!((0.4..0.6).contains(&r.covered_fraction));
}

#[test]
fn a_polyline_shifted_off_the_curve_by_more_than_its_tolerance_strays() {
    let (s, b, c) = sphere_loop();
    let [p, q] = &s.surfaces;
    // Move each point's (u, v) on Q radially off the circle (u − ½)² + (v − ½)² = 141/1024 by
    // `delta`: the gap |P − Q| becomes 2·delta (Q scales parameters by 2).
    let shifted = |delta: f64| {
        let mut out = b.clone();
        for pt in &mut out.points {
            let (du, dv) = (pt.q[0] - 0.5, pt.q[1] - 0.5);
            let r = du.hypot(dv);
            pt.q = [pt.q[0] + delta * du / r, pt.q[1] + delta * dv / r];
        }
        out
    };
    let delta = 1e-7;
    assert!(2.0 * delta > 100.0 * TOL);
    let off = shifted(delta);
    let r = check_branch(p, q, &off, &c, &[], TOL);
    print_report("sphere loop shifted 1e-7", &off, &r);
    assert_eq!(r.straying.len(), off.points.len());
    let worst_slack = r.straying.iter().map(|x| x.slack).fold(0.0, f64::max);
    let (lo, hi) = r
        .straying
        .iter()
        .map(|x| x.distance)
        .fold((f64::INFINITY, 0.0f64), |(a, b), d| (a.min(d), b.max(d)));
    println!("    proven distances {lo:.3e} .. {hi:.3e} (shift {delta:e}), slack up to {worst_slack:.2e}");
    // A lower bound: never more than the shift itself (moving (u, v) back is on the curve,
    // up to the marcher's own error and the tube radius).
    assert!(hi <= delta * (1.0 + 1e-6), "{hi}");
    assert!(lo > worst_slack);
    // Within the slack, nothing strays.
    let slight = shifted(0.1 * worst_slack.min(TOL));
    let r = check_branch(p, q, &slight, &c, &[], TOL);
    assert!(
        r.straying.is_empty(),
        "{:?}",
        &r.straying[..r.straying.len().min(3)]
    );
}

#[test]
fn a_certificate_that_ends_early_leaves_the_rest_unchecked() {
    let s = scene("sphere_patch_plane.json");
    let [p, q] = &s.surfaces;
    let b = march(&s).remove(0);
    let c = certify(&s, &b.points[b.points.len() / 3], 15);
    assert_eq!(
        [c.ends[0].kind(), c.ends[1].kind()],
        ["unproven", "unproven"]
    );
    let r = check_branch(p, q, &b, &c, &[], TOL);
    print_report("sphere loop, 15 steps each way", &b, &r);
    assert!(r.straying.is_empty() && !r.looping);
    let outside: Vec<usize> = (0..b.points.len())
        .filter(|&i| !in_some_box(&c, &b.points[i], 1e-9))
        .collect();
    assert!(outside.len() > b.points.len() / 2);
    assert_eq!(r.unchecked, outside);
    assert!(r.covered_fraction > 0.95);
    // Points shifted off the curve inside the certified arc still stray.
    let mut off = b.clone();
    let i = b.points.len() / 3 + 1;
    off.points[i].q[0] += 1e-6;
    let r = check_branch(p, q, &off, &c, &[], TOL);
    let got: Vec<usize> = r.straying.iter().map(|x| x.index).collect();
    assert_eq!(got, vec![i]);
}

fn run_cli(args: &[&str]) -> (String, Value) {
    let dir = std::env::temp_dir().join(format!(
        "ssitrace-strays-{}-{}",
        std::process::id(),
        args.len()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    // The bicubic scene without its `"method"`, so the command line's default applies.
    let mut v: Value = serde_json::from_str(
        &std::fs::read_to_string(scene_path("bicubic_transversal.json")).unwrap(),
    )
    .unwrap();
    v["options"].as_object_mut().unwrap().remove("method");
    let scene_path = dir.join("scene.json");
    std::fs::write(&scene_path, v.to_string()).unwrap();
    let out = dir.join("r.json");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .arg("trace")
        .arg(&scene_path)
        .args(args)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    let doc = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (stdout, doc)
}

#[test]
fn the_command_line_defaults_to_both() {
    let (stdout, doc) = run_cli(&[]);
    println!("{stdout}");
    assert_eq!(doc["method"], "both");
    let c = &doc["branches"][0]["certified"];
    assert!(c["enclosures"].as_array().is_some_and(|a| !a.is_empty()));
    let st = &c["straying"];
    assert_eq!(st["straying_points"].as_array().map(Vec::len), Some(0));
    assert_eq!(st["unchecked_points"].as_array().map(Vec::len), Some(0));
    assert_eq!(st["looping"], false);
    assert!(st["covered_fraction"].as_f64().is_some_and(|f| f > 0.99));
    assert_eq!(doc["stats"]["straying_points"], 0);
    assert!(stdout.contains("marched points: none strays"));

    let (stdout, doc) = run_cli(&["--method", "march"]);
    assert_eq!(doc["method"], "march");
    let branches = doc["branches"].as_array().unwrap();
    assert!(!branches.is_empty());
    assert!(branches.iter().all(|b| b.get("certified").is_none()));
    assert!(doc["stats"].get("straying_points").is_none());
    assert!(!stdout.contains("certified:"));
}

#[test]
fn the_command_line_warns_when_the_march_loops() {
    // S31/S32 marched with L = 1.5, less than two steps per lap of the shorter loop: the
    // marcher goes round it almost twice before its closing test accepts the start (found by
    // trying large steps; at L = 1 it used to go round ten times, and now stops when it comes
    // back onto its own path); the fine march (the scene's L = 0.02) goes round each loop once.
    let path = scene_path("two_loops_s31_s32.json").display().to_string();
    let dir = std::env::temp_dir().join(format!("ssitrace-loops-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("r.json");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_ssitrace"))
        .args(["trace", &path, "--method", "both", "--step", "1.5", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success());
    let stdout = String::from_utf8_lossy(&run.stdout);
    println!("{stdout}");
    let doc: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    // The loop lengths, independently: the fine march's polylines.
    let fine: Vec<f64> = march(&scene("two_loops_s31_s32.json"))
        .iter()
        .map(|b| polyline_length(&b.points))
        .collect();
    assert_eq!(fine.len(), 2);
    let (mut looping, mut twice) = (0, 0);
    for b in doc["branches"].as_array().unwrap() {
        let st = &b["certified"]["straying"];
        let (marched, certified) = (
            st["marched_length"].as_f64().unwrap(),
            st["certified_length"].as_f64().unwrap(),
        );
        // The certified loop is one of the two loops.
        assert!(
            fine.iter().any(|l| (l - certified).abs() < 1e-3 * l),
            "{certified} vs {fine:?}"
        );
        assert_eq!(st["straying_points"].as_array().map(Vec::len), Some(0));
        if st["looping"] == true {
            looping += 1;
            // Chords never exceed the arcs: more than one loop's length is a second round (a
            // march of a few long chords per lap can go round twice in less).
            if marched > 1.5 * certified {
                twice += 1;
            }
        } else {
            assert!(marched <= 1.5 * certified, "{marched} vs {certified}");
        }
    }
    assert!(
        twice >= 1,
        "no march round a loop twice at L = 1.5: pick another fault"
    );
    assert_eq!(doc["stats"]["looping_branches"], looping);
    assert!(stdout.contains("warning: the march goes round the loop more than once"));
}

#[test]
fn an_open_branch_marched_part_way_and_an_uncertified_branch() {
    let s = scene("bicubic_transversal.json");
    let [p, q] = &s.surfaces;
    let b = march(&s).remove(0);
    let c = certify(&s, &b.points[b.points.len() / 2], 20_000);
    assert_eq!(
        [c.ends[0].kind(), c.ends[1].kind()],
        ["boundary", "boundary"]
    );
    // The branch is σ = 1/2, t ∈ [0, 1] on P: its length is that of the curve
    // (1/2, t, z(t)), which the fine marched polyline approximates from below.
    let full = check_branch(p, q, &b, &c, &[], TOL);
    print_report("bicubic branch", &b, &full);
    assert!(full.straying.is_empty() && full.unchecked.is_empty() && !full.looping);
    assert!(full.covered_fraction > 0.9999, "{}", full.covered_fraction);
    assert!((full.certified_length - full.marched_length).abs() < 1e-3 * full.marched_length);
    // Stopped at t ≈ 0.6: about 0.6 of the arc by length, and visible as such.
    let k = b.points.iter().position(|c| c.p[1] > 0.6).unwrap();
    let stopped = Branch {
        status: BranchStatus::Incomplete,
        ends: [b.ends[0], EndReason::NewtonFailed],
        points: b.points[..=k].to_vec(),
        ..b.clone()
    };
    let r = check_branch(p, q, &stopped, &c, &[], TOL);
    print_report("bicubic branch to t = 0.6", &stopped, &r);
    assert!(r.straying.is_empty() && r.unchecked.is_empty());
    let expect = r.marched_length / r.certified_length;
    assert!(
        (r.covered_fraction - expect).abs() < 1e-3,
        "{} vs {expect}",
        r.covered_fraction
    );
    assert!(r.covered_fraction < 0.8);
    // Without a certificate every point is unchecked and nothing is covered.
    let none = check_branches(p, q, std::slice::from_ref(&b), &[None], TOL);
    assert_eq!(none[0].unchecked, (0..b.points.len()).collect::<Vec<_>>());
    assert!(none[0].straying.is_empty() && none[0].covered_fraction == 0.0);
}
