//! Step length and cost of certified branch tracing on the example scenes.
//!
//! `cargo test --release --test certified_perf -- --nocapture` prints, per scene and branch:
//! the number of validated steps, the mean / median step, ms per step and the total time. The
//! checks are on closed forms (the circle of the sphere/plane scene, the line σ = ½ of the
//! bicubic scene, the implicit equation of the two loops on Q), and the steps must be long (the
//! purpose of the centred field): before it the median steps were 2.8e-3 (sphere) and 1.1e-3
//! (bicubic).

mod common;

use common::scenes::scene;
use inari::Interval;
use ssitrace::certify::{certify_branch, CertifiedBranch, CertifiedEnd, CertifyOptions};
use ssitrace::numeric::scalar::point;
use ssitrace::pipeline::{run_scene, RunOptions};
use std::time::Instant;

struct Run {
    branch: CertifiedBranch,
    seconds: f64,
}

fn certify_scene(file: &str, opts: &CertifyOptions) -> Vec<Run> {
    let scene = scene(file);
    let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("march");
    let [p, q] = &scene.surfaces;
    let mut runs = Vec::new();
    for b in &outcome.marched().branches {
        let pt = b.points[b.points.len() / 2];
        let start = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
        let t0 = Instant::now();
        let branch = certify_branch(p, q, start, opts).expect("certify");
        let seconds = t0.elapsed().as_secs_f64();
        let steps = branch.boxes.len();
        let mut hs: Vec<f64> = branch.boxes.iter().map(|b| b.s[1] - b.s[0]).collect();
        hs.sort_by(f64::total_cmp);
        let len: f64 = hs.iter().sum();
        println!(
            "{file} branch {}: {steps} steps, length {len:.4}, mean h {:.3e}, median h {:.3e}, \
             min h {:.3e}, {:.3} ms/step, total {:.1} ms, tol {:.1e}, ends {:?}",
            b.id,
            len / steps as f64,
            hs[steps / 2],
            hs[0],
            1e3 * seconds / steps as f64,
            1e3 * seconds,
            branch.certified_tolerance,
            branch.ends.clone().map(|e| match e {
                CertifiedEnd::Unproven { .. } => "unproven".to_string(),
                e => format!("{e:?}").chars().take(24).collect(),
            }),
        );
        runs.push(Run { branch, seconds });
    }
    runs
}

fn median_step(b: &CertifiedBranch) -> f64 {
    let mut hs: Vec<f64> = b.boxes.iter().map(|b| b.s[1] - b.s[0]).collect();
    hs.sort_by(f64::total_cmp);
    hs[hs.len() / 2]
}

#[test]
fn sphere_patch_plane_circle_in_long_steps() {
    let runs = certify_scene("sphere_patch_plane.json", &CertifyOptions::default());
    assert_eq!(runs.len(), 1);
    let b = &runs[0].branch;
    assert_eq!(b.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
    // Every box meets the circle on Q: (u − ½)² + (v − ½)² = 141/1024 is attained in the box.
    let r2 = point(141.0) / point(1024.0);
    for bx in &b.boxes {
        let d = (bx.q[0] - point(0.5)).sqr() + (bx.q[1] - point(0.5)).sqr();
        assert!(!d.disjoint(r2), "box off the circle: {bx:?}");
    }
    // The loop's arc length is 2π·√141/16 (model radius √141/16): the chain runs once around and
    // ends with the step that crosses the start again.
    let first = b.boxes[0].s[0];
    let last = b.boxes.last().unwrap().s;
    let exact = 2.0 * std::f64::consts::PI * 141f64.sqrt() / 16.0;
    assert!(
        last[1] - first >= exact - 1e-9 && last[0] - first <= exact + 1e-9,
        "chain [{first}, {}] vs loop length {exact}",
        last[1]
    );
    // The reported tube polynomials lie on the circle up to their proven radii: on Q within
    // radius_param (max norm, so √2·radius in the plane) of (u − ½)² + (v − ½)² = 141/1024.
    let rq = 141f64.sqrt() / 32.0;
    for t in &b.tubes {
        for f in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let y = t.eval(f * t.h);
            let d = (y[2] - 0.5).hypot(y[3] - 0.5);
            assert!(
                (d - rq).abs() <= 2f64.sqrt() * t.radius_param + 1e-12,
                "tube off the circle by {} (radius {})",
                (d - rq).abs(),
                t.radius_param
            );
        }
    }
    assert!(median_step(b) > 0.02, "median step {}", median_step(b));
    println!("sphere: {:.1} ms", 1e3 * runs[0].seconds);
}

#[test]
fn bicubic_branch_in_long_steps() {
    let runs = certify_scene("bicubic_transversal.json", &CertifyOptions::default());
    assert_eq!(runs.len(), 1);
    let b = &runs[0].branch;
    // P(σ, t) has x = σ (linear precision of the net's x = i/3) and Q is the plane x = ½, so the
    // curve is σ = ½ from t = 0 to t = 1.
    for bx in &b.boxes {
        assert!(bx.p[0].contains(0.5), "box misses σ = ½: {bx:?}");
    }
    for t in &b.tubes {
        for f in [0.0, 0.5, 1.0] {
            let y = t.eval(f * t.h);
            assert!((y[0] - 0.5).abs() <= t.radius_param + 1e-12);
        }
    }
    assert!(matches!(b.ends[0], CertifiedEnd::Boundary { .. }));
    assert!(matches!(b.ends[1], CertifiedEnd::Boundary { .. }));
    assert!(median_step(b) > 0.05, "median step {}", median_step(b));
}

#[test]
fn two_loops_in_long_steps() {
    let runs = certify_scene("two_loops_s31_s32.json", &CertifyOptions::default());
    assert_eq!(runs.len(), 2);
    for r in &runs {
        let b = &r.branch;
        assert_eq!(b.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
        // On Q the loops satisfy 3(s² + (5(s² + w²) − 1)²) = w + 1.
        for bx in &b.boxes {
            let [s, w]: [Interval; 2] = bx.q;
            let inner = point(5.0) * (s.sqr() + w.sqr()) - point(1.0);
            let f = point(3.0) * (s.sqr() + inner.sqr()) - w - point(1.0);
            assert!(f.contains(0.0), "box off the loop: {bx:?}");
        }
        assert!(median_step(b) > 0.02, "median step {}", median_step(b));
    }
}
