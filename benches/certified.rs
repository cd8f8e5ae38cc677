//! Benchmarks of certified branch tracing: one whole branch of the sphere-patch/plane circle, of
//! the bicubic transversal scene and of S31/S32, and an arc of Fig. 7, at the default
//! `CertifyOptions`, next to the marcher on the same branch and the certified trace without
//! contraction / re-anchoring (ratios in one process), and one Taylor expansion of the
//! intersection ODE (order 20, with and without Jacobians) over a small box. Under load from
//! other processes prefer `tests/certified_perf_compare.rs` (thread CPU time).

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use ssitrace::certify::ode::TransversalOde;
use ssitrace::certify::{certify_branch, CertifyOptions, StepBudget};
use ssitrace::io::scene::Scene;
use ssitrace::march::{trace_branch, MarchOptions};
use ssitrace::numeric::scalar::interval;
use ssitrace::pipeline::{run_scene, RunOptions};
use ssitrace::validated::tape::Tape;
use ssitrace::validated::{Expansion, TaylorAd};
use std::hint::black_box;
use std::path::Path;

fn scene_and_start(file: &str) -> (Scene, [f64; 4]) {
    let scene = Scene::from_path(Path::new(file)).expect("scene");
    let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("march");
    let b = &outcome.branches[0].marched;
    let pt = b.points[b.points.len() / 2];
    (scene, [pt.p[0], pt.p[1], pt.q[0], pt.q[1]])
}

fn bench_certify(c: &mut Criterion) {
    let mut group = c.benchmark_group("certify_branch");
    group.sample_size(10);
    // (Fig. 7 as an arc of arc length 1: its whole loops take seconds per iteration.)
    for (name, file, max_length) in [
        (
            "sphere_patch_plane",
            "scenes/sphere_patch_plane.json",
            f64::INFINITY,
        ),
        (
            "bicubic_transversal",
            "scenes/bicubic_transversal.json",
            f64::INFINITY,
        ),
        (
            "two_loops_s31_s32",
            "scenes/two_loops_s31_s32.json",
            f64::INFINITY,
        ),
        ("wu_andrade_fig7_arc", "scenes/wu_andrade_fig7.json", 0.5),
    ] {
        let (scene, start) = scene_and_start(file);
        let [p, q] = &scene.surfaces;
        let opts = CertifyOptions {
            steps: StepBudget {
                max_length,
                ..StepBudget::CERTIFY
            },
            ..CertifyOptions::default()
        };
        let steps = certify_branch(p, q, start, &opts)
            .expect("certify")
            .boxes
            .len();
        println!("{name}: {steps} steps per branch");
        group.bench_function(name, |b| {
            b.iter(|| certify_branch(p, q, black_box(start), &opts).expect("certify"))
        });
        // Baselines in the same process: the marcher on the same branch, and the certified
        // trace without the contraction onto P = Q.
        let march = MarchOptions {
            step: scene.options.step,
            ..MarchOptions::default()
        };
        group.bench_function(format!("{name}/march_same_branch"), |b| {
            b.iter(|| trace_branch(p, q, black_box(start), &march).expect("march"))
        });
        let plain = CertifyOptions {
            contract: false,
            ..opts
        };
        group.bench_function(format!("{name}/no_contraction"), |b| {
            b.iter(|| certify_branch(p, q, black_box(start), &plain).expect("certify"))
        });
    }
    group.finish();
}

fn bench_expand(c: &mut Criterion) {
    let (scene, start) = scene_and_start("scenes/sphere_patch_plane.json");
    let [p, q] = &scene.surfaces;
    let ode = TransversalOde {
        p,
        q,
        orientation: 1.0,
    };
    let mut ad = TaylorAd::new(Tape::record(&ode).expect("tape"));
    let y0: Vec<_> = start
        .iter()
        .map(|x| interval(x - 1e-3, x + 1e-3).expect("box"))
        .collect();
    let mut out = Expansion::default();
    c.bench_function("transversal_expand_order20", |b| {
        b.iter(|| {
            ad.expand(black_box(&y0), 20, false, &mut out)
                .expect("expand")
        })
    });
    c.bench_function("transversal_expand_order20_jacobian", |b| {
        b.iter(|| {
            ad.expand(black_box(&y0), 20, true, &mut out)
                .expect("expand")
        })
    });
}

criterion_group!(benches, bench_certify, bench_expand);
criterion_main!(benches);
