//! The cover-chain certification (the default engine) per example scene, next to the marcher
//! on the same scene and to the Taylor engine on the same branch, measured in one process.
//!
//! Before the criterion groups run, one line per scene prints: the marched time of the whole
//! scene (search and march), the chain's time over all its branches, their ratio, the links and
//! the time per link, and, for the scene's first branch alone, the Taylor engine's time over the
//! chain's (Fig. 7's Taylor run takes seconds). Under load from other processes the ratios (one
//! process, back to back) mean more than the absolute times.
//!
//! **What sizes a link** (measured with this bench, 2026-12): a link is as long as its tube
//! stays within the tolerance; the tube is the predictor's error (a septic Hermite
//! interpolant, error of order `L⁸`) plus the Taylor form's remainder (order 9 in `L`), so the
//! links are long on smooth curves (the sphere circle: 50 links) and short where the graph's
//! high derivatives are large (Fig. 7's ellipses against a nearly tangent plane: about 100
//! links per loop). A link costs two Taylor expansions in interval series of both patches along
//! the predictor (at the link's centre and over the link, for the remainder), two shorter ones
//! of their first partials, one interval Hessian over the tube, and a Krawczyk narrowing of its
//! end slice. The patches are evaluated in a centred power form truncated to the link's window
//! (`certify::lean_patch`): on Fig. 7's degree-6 height field that leaves 2 of 49 terms in `x`
//! and `y` and 25 in `z`, and took its chain from 11.5–12.6 to 6.1–6.6 ms.
//!
//! `cargo bench --bench chain`.

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

mod common;

use common::median;
use criterion::{criterion_group, criterion_main, Criterion};
use ssitrace::certify::{certify_branch, certify_chain, CertifyOptions, ChainOptions};
use ssitrace::io::scene::Scene;
use ssitrace::march::branch::Branch;
use ssitrace::solve::{intersect, Method, Options};
use std::hint::black_box;
use std::path::Path;

const SCENES: [(&str, &str); 5] = [
    ("sphere", "scenes/sphere_patch_plane.json"),
    ("bicubic", "scenes/bicubic_transversal.json"),
    ("s31_s32", "scenes/two_loops_s31_s32.json"),
    ("cylinders_full", "scenes/cylinders_full.json"),
    ("fig7", "scenes/wu_andrade_fig7.json"),
];

fn marched(scene: &Scene) -> Vec<Branch> {
    let [p, q] = &scene.surfaces;
    let opts = Options {
        method: Method::March,
        step: scene.options.step,
        ..Options::default()
    };
    intersect(p, q, &opts)
        .expect("march")
        .branches
        .into_iter()
        .map(|t| t.marched)
        .filter(|b| b.points.len() > 1)
        .collect()
}

fn middle(b: &Branch) -> [f64; 4] {
    let c = b.points[b.points.len() / 2];
    [c.p[0], c.p[1], c.q[0], c.q[1]]
}

fn print_ratios() {
    println!("scene            marched  chain    chain/marched  links  per link  taylor/chain (first branch)");
    for (name, file) in SCENES {
        let scene = Scene::from_path(Path::new(file)).expect("scene");
        let [p, q] = &scene.surfaces;
        let branches = marched(&scene);
        let opts = ChainOptions::default();
        let t_march = median(5, || {
            black_box(marched(&scene));
        });
        let mut links = 0;
        let t_chain = median(5, || {
            links = 0;
            for b in &branches {
                if let Ok(c) = certify_chain(p, q, b, middle(b), &opts) {
                    links += c.tubes.len();
                }
            }
        });
        let first = &branches[0];
        let t_first = median(3, || {
            black_box(certify_chain(p, q, first, middle(first), &opts).ok());
        });
        let t_taylor = median(1, || {
            black_box(certify_branch(p, q, middle(first), &CertifyOptions::default()).ok());
        });
        println!(
            "{name:<16} {:>6.1}ms {:>7.1}ms {:>10.1}x {:>9} {:>7.1}µs {:>14.1}x",
            t_march * 1e3,
            t_chain * 1e3,
            t_chain / t_march,
            links,
            t_chain / links.max(1) as f64 * 1e6,
            t_taylor / t_first
        );
    }
}

fn bench(c: &mut Criterion) {
    print_ratios();
    let mut g = c.benchmark_group("chain");
    g.sample_size(10);
    for (name, file) in SCENES {
        let scene = Scene::from_path(Path::new(file)).expect("scene");
        let [p, q] = &scene.surfaces;
        let branches = marched(&scene);
        let opts = ChainOptions::default();
        g.bench_function(name, |bch| {
            bch.iter(|| {
                for b in &branches {
                    black_box(certify_chain(p, q, b, middle(b), &opts).ok());
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
