//! Where the time of certified tracing goes, and which Taylor order is fastest.
//!
//! `cargo test --release --test certified_perf_profile -- --nocapture` prints, per scene: steps,
//! thread CPU time, the split between validated steps / re-anchoring / enclosures / loop closing,
//! phase-I attempts and the Taylor recurrence work per phase; then the same for several orders.
//! The checks are soundness checks on closed forms that hold at every order.

use ssitrace::certify::{
    certify_branch_profiled, CertifiedEnd, CertifyOptions, StepBudget, TraceProfile,
};
use ssitrace::io::scene::Scene;
use ssitrace::numeric::scalar::point;
use ssitrace::pipeline::{run_scene, RunOptions};

mod common;
use common::clock::cpu_seconds;
use common::scenes::scene;

fn starts(file: &str) -> (Scene, Vec<[f64; 4]>) {
    let scene = scene(file);
    let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("march");
    let starts = outcome
        .branches
        .iter()
        .map(|b| &b.marched)
        .map(|b| {
            let pt = b.points[b.points.len() / 2];
            [pt.p[0], pt.p[1], pt.q[0], pt.q[1]]
        })
        .collect();
    (scene, starts)
}

fn line(name: &str, order: usize, steps: usize, cpu: f64, tol: f64, pr: &TraceProfile) -> String {
    let w = &pr.integrator;
    let total = pr.step_seconds + pr.anchor_seconds + pr.enclosure_seconds + pr.closing_seconds;
    let pct = |x: f64| 100.0 * x / total.max(1e-300);
    let units = w.box_units + w.phase1_units + w.phase2_units;
    format!(
        "{name:<22} k={order:>2}: {steps:>5} steps, cpu {:>7.1} ms ({:.3} ms/step), tol {tol:.1e} | \
         steps {:.0}% anchor {:.0}% encl {:.0}% close {:.0}% | phase I {:.2}/step (fail {}, shrink {}, cut {}) | \
         work/step {:.0}: box {:.0}% ph1 {:.0}% ph2 {:.0}%",
        1e3 * cpu,
        1e3 * cpu / steps.max(1) as f64,
        pct(pr.step_seconds),
        pct(pr.anchor_seconds),
        pct(pr.enclosure_seconds),
        pct(pr.closing_seconds),
        w.phase1_attempts as f64 / w.steps.max(1) as f64,
        w.phase1_failures,
        w.remainder_shrinks,
        w.remainder_cuts,
        units / w.steps.max(1) as f64,
        100.0 * w.box_units / units,
        100.0 * w.phase1_units / units,
        100.0 * w.phase2_units / units,
    )
}

fn reps() -> usize {
    std::env::var("SSITRACE_PERF_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
}

/// Certifies every branch of `file` (arc-length budget `max_length` per half) at `order`, the
/// best of `reps()` runs; checks every end is proven unless budgeted and, on the sphere scene,
/// that every box meets the circle. Returns the printed line.
fn run(name: &str, file: &str, max_length: f64, order: usize) -> String {
    let (scene, starts) = starts(file);
    let [p, q] = &scene.surfaces;
    let opts = CertifyOptions {
        steps: StepBudget {
            order,
            max_length,
            ..StepBudget::CERTIFY
        },
        ..CertifyOptions::default()
    };
    let mut best: Option<(f64, String)> = None;
    for _ in 0..reps() {
        let (mut steps, mut cpu, mut tol) = (0, 0.0, 0.0f64);
        let mut prof = TraceProfile::default();
        for s in &starts {
            let t0 = cpu_seconds();
            let (b, pr) = certify_branch_profiled(p, q, *s, &opts).expect("certified");
            cpu += cpu_seconds() - t0;
            steps += b.steps();
            tol = tol.max(b.certified_tolerance);
            if max_length.is_infinite() {
                assert!(
                    b.ends
                        .iter()
                        .all(|e| !matches!(e, CertifiedEnd::Unproven { .. })),
                    "{name} order {order}: {:?}",
                    b.ends
                );
            }
            if name == "sphere_patch_plane" {
                let r2 = point(141.0) / point(1024.0);
                for bx in &b.boxes {
                    let d = (bx.q[0] - point(0.5)).sqr() + (bx.q[1] - point(0.5)).sqr();
                    assert!(!d.disjoint(r2), "box off the circle");
                }
            }
            prof.step_seconds += pr.step_seconds;
            prof.anchor_seconds += pr.anchor_seconds;
            prof.enclosure_seconds += pr.enclosure_seconds;
            prof.closing_seconds += pr.closing_seconds;
            prof.integrator += pr.integrator;
        }
        if best.as_ref().is_none_or(|(c, _)| cpu < *c) {
            best = Some((cpu, line(name, order, steps, cpu, tol, &prof)));
        }
    }
    best.map(|(_, l)| l).unwrap_or_default()
}

#[test]
fn profile_at_the_default_order() {
    let order = CertifyOptions::default().steps.order;
    for (name, file, len) in [
        (
            "sphere_patch_plane",
            "sphere_patch_plane.json",
            f64::INFINITY,
        ),
        (
            "bicubic_transversal",
            "bicubic_transversal.json",
            f64::INFINITY,
        ),
        ("two_loops_s31_s32", "two_loops_s31_s32.json", f64::INFINITY),
        ("wu_andrade_fig7 arc", "wu_andrade_fig7.json", 0.15),
    ] {
        println!("{}", run(name, file, len, order));
    }
}

#[test]
fn taylor_order_sweep() {
    // Lower orders cost less per step but need more steps; the totals are close (see the printed
    // lines). Every order must give a sound, closed certificate on the sphere loop.
    for order in [12, 16, 20] {
        println!(
            "{}",
            run(
                "sphere_patch_plane",
                "sphere_patch_plane.json",
                f64::INFINITY,
                order
            )
        );
    }
    if std::env::var("SSITRACE_PERF_SWEEP").is_ok() {
        for order in [12, 14, 16, 18, 20, 24] {
            for (name, file, len) in [
                (
                    "bicubic_transversal",
                    "bicubic_transversal.json",
                    f64::INFINITY,
                ),
                ("two_loops_s31_s32", "two_loops_s31_s32.json", f64::INFINITY),
                ("wu_andrade_fig7 arc", "wu_andrade_fig7.json", 0.3),
            ] {
                println!("{}", run(name, file, len, order));
            }
        }
    }
}
