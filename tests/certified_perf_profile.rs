//! Where the time of certified tracing goes, and which Taylor order is fastest.
//!
//! `cargo test --release --test certified_perf_profile -- --nocapture` prints, per scene: steps,
//! thread CPU time, the split between validated steps / re-anchoring / enclosures / loop closing,
//! phase-I attempts and the Taylor recurrence work per phase; then the same for several orders.
//! The checks are soundness checks on closed forms that hold at every order.

use ssitrace::certified::{certify_branch_profiled, CertifiedEnd, CertifyOptions, TraceProfile};
use ssitrace::io::scene::Scene;
use ssitrace::pipeline::{run_scene, RunOptions};
use ssitrace::scalar::point;
use std::path::Path;

/// CPU time of this thread in seconds (`/proc/thread-self/schedstat`), or wall time elsewhere.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map(|ns| ns * 1e-9)
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_secs_f64())
                .unwrap_or(0.0)
        })
}

fn starts(file: &str) -> (Scene, Vec<[f64; 4]>) {
    let scene = Scene::from_path(Path::new(file)).expect("scene");
    let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("march");
    let starts = outcome
        .intersection
        .branches
        .iter()
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

#[test]
fn profile_and_order_sweep_on_the_small_scenes() {
    for (name, file) in [
        ("sphere_patch_plane", "scenes/sphere_patch_plane.json"),
        ("bicubic_transversal", "scenes/bicubic_transversal.json"),
        ("two_loops_s31_s32", "scenes/two_loops_s31_s32.json"),
    ] {
        let (scene, starts) = starts(file);
        let [p, q] = &scene.surfaces;
        for order in [12, 14, 16, 18, 20, 24] {
            let opts = CertifyOptions {
                order,
                ..CertifyOptions::default()
            };
            let (mut steps, mut cpu, mut tol) = (0, 0.0, 0.0f64);
            let mut prof = TraceProfile::default();
            for s in &starts {
                let t0 = cpu_seconds();
                let (b, pr) = certify_branch_profiled(p, q, *s, &opts).expect("certified");
                cpu += cpu_seconds() - t0;
                steps += b.steps();
                tol = tol.max(b.tolerance);
                assert!(
                    b.ends
                        .iter()
                        .all(|e| !matches!(e, CertifiedEnd::Unproven { .. })),
                    "{name} order {order}: {:?}",
                    b.ends
                );
                if name == "sphere_patch_plane" {
                    // Every box meets the circle (u − ½)² + (v − ½)² = 141/1024 on Q.
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
                let (a, w) = (&mut prof.integrator, pr.integrator);
                a.steps += w.steps;
                a.phase1_attempts += w.phase1_attempts;
                a.phase1_failures += w.phase1_failures;
                a.remainder_shrinks += w.remainder_shrinks;
                a.remainder_cuts += w.remainder_cuts;
                a.box_units += w.box_units;
                a.phase1_units += w.phase1_units;
                a.phase2_units += w.phase2_units;
            }
            println!("{}", line(name, order, steps, cpu, tol, &prof));
        }
    }
}

#[test]
fn dbg_fig7() {
    let (scene, starts) = starts("scenes/wu_andrade_fig7.json");
    let [p, q] = &scene.surfaces;
    for order in [12, 14, 16, 18, 20] {
        let opts = CertifyOptions {
            max_length: 0.3,
            order,
            ..CertifyOptions::default()
        };
        let mut best = f64::INFINITY;
        let mut out = String::new();
        for _ in 0..3 {
            let t0 = cpu_seconds();
            let (b, pr) = certify_branch_profiled(p, q, starts[0], &opts).unwrap();
            let cpu = cpu_seconds() - t0;
            if cpu < best {
                best = cpu;
                out = line("fig7 arc", order, b.steps(), cpu, b.tolerance, &pr);
            }
        }
        println!("{out}");
    }
}
