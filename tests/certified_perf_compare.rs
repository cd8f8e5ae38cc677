//! Certified tracing against the marcher on the same branch, in thread CPU time.
//!
//! `cargo test --release --test certified_perf_compare -- --nocapture` prints, per scene and
//! branch: certified steps, CPU time (the best of `SSITRACE_PERF_REPS` runs, default 1), the
//! marcher's CPU time on the same branch from the same start, their ratio, and the certified
//! tolerance. Fig. 7 is an arc of arc length 1 (both halves together) to keep the suite fast.
//! Uses only `certify_branch` and `trace_branch`, so the same file (with `tests/common/`)
//! measures older versions.

use ssitrace::certify::{certify_branch, CertifyOptions, StepBudget};
use ssitrace::march::{trace_branch, MarchOptions};
use ssitrace::pipeline::{run_scene, RunOptions};

mod common;
use common::clock::cpu_seconds;
use common::scenes::scene;

fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (T, f64) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps.max(1) {
        let t0 = cpu_seconds();
        let r = f();
        best = best.min(cpu_seconds() - t0);
        out = Some(r);
    }
    (out.expect("one run"), best)
}

#[test]
fn certified_against_marching_cpu_time() {
    let reps = std::env::var("SSITRACE_PERF_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    for (file, max_length) in [
        ("sphere_patch_plane.json", f64::INFINITY),
        ("bicubic_transversal.json", f64::INFINITY),
        ("two_loops_s31_s32.json", f64::INFINITY),
        ("wu_andrade_fig7.json", 0.5),
    ] {
        let scene = scene(file);
        let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("march");
        let [p, q] = &scene.surfaces;
        let branches = &outcome.marched().branches;
        let take = if max_length.is_finite() {
            1
        } else {
            branches.len()
        };
        for b in branches.iter().take(take) {
            let pt = b.points[b.points.len() / 2];
            let start = [pt.p[0], pt.p[1], pt.q[0], pt.q[1]];
            let opts = CertifyOptions {
                steps: StepBudget {
                    max_length,
                    ..StepBudget::CERTIFY
                },
                ..CertifyOptions::default()
            };
            let (c, cert) = best_of(reps, || {
                certify_branch(p, q, start, &opts).expect("certify")
            });
            let march = MarchOptions {
                step: scene.options.step,
                ..MarchOptions::default()
            };
            let (_, marched) = best_of(reps.max(3), || trace_branch(p, q, start, &march));
            println!(
                "{file} branch {}: {} certified steps, {:.1} ms ({:.3} ms/step); marcher {:.2} ms; \
                 ratio {:.0}x; tolerance {:.1e}",
                b.id,
                c.steps(),
                1e3 * cert,
                1e3 * cert / c.steps() as f64,
                1e3 * marched,
                cert / marched.max(1e-9),
                c.certified_tolerance
            );
            assert!(
                c.certified_tolerance < 1e-9,
                "tolerance {}",
                c.certified_tolerance
            );
        }
    }
}
