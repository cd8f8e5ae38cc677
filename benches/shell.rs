//! A shell pair of many faces, timed on one thread and on two (rayon pools built in this one
//! process, back to back).
//!
//! Shell A: the standard 9 × 5 NURBS unit sphere (`scenes/nurbs_sphere_plane.json`), its eight
//! Bézier pieces taken as eight faces. Shell B: eighteen square plane faces slicing it, six
//! each across x, y and z at ±0.2, ±0.45 and ±0.7. That is 144 face pairs; the bounding-box pre-filter
//! keeps those whose boxes meet (printed), each a certified intersection, and the circles are
//! joined across the pieces' shared edges.
//!
//! Before the criterion groups run, one line prints the pairs intersected, the branches and
//! curves, the median wall time of five runs on each pool with the CPU time per run (so the
//! cores kept busy), and the 1-thread over 2-thread ratio. On a machine shared with other work
//! the 2-thread pool cannot get two cores and the ratio says little; the cores busy still show
//! whether the pairs ran in parallel.
//!
//! `cargo bench --bench shell`.

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use ssitrace::geometry::Domain;
use ssitrace::io::scene::ShellScene;
use ssitrace::pipeline::RunOptions;
use ssitrace::shell::{intersect_shells, Face, ShellIntersection};
use ssitrace::solve::Options;
use ssitrace::RationalBezierPatch;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// The square `[-1.5, 1.5]²` of the plane `x_axis = h` as a bilinear patch.
fn plane(axis: usize, h: f64) -> Face {
    let corner = |a: f64, b: f64| {
        let mut p = [0.0; 3];
        p[axis] = h;
        p[(axis + 1) % 3] = a;
        p[(axis + 2) % 3] = b;
        p
    };
    let net = [
        corner(-1.5, -1.5),
        corner(-1.5, 1.5),
        corner(1.5, -1.5),
        corner(1.5, 1.5),
    ];
    Face::from_patch(
        RationalBezierPatch::from_f64_points([1, 1], &net, None, Domain::UNIT).expect("plane"),
    )
}

/// The two shells and the run options.
fn shells() -> (Vec<Face>, Vec<Face>, Options) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/nurbs_sphere_plane.json");
    let scene = ShellScene::from_path(&path).expect("scene");
    let a: Vec<Face> = scene.shells[0][0]
        .pieces()
        .iter()
        .map(|p| Face::from_patch(p.clone()))
        .collect();
    let b: Vec<Face> = (0..3)
        .flat_map(|axis| [-0.7, -0.45, -0.2, 0.2, 0.45, 0.7].map(|h| plane(axis, h)))
        .collect();
    let opts = RunOptions::from_scene_options(&scene.options).options();
    (a, b, opts)
}

fn run(pool: &rayon::ThreadPool, a: &[Face], b: &[Face], opts: &Options) -> ShellIntersection {
    pool.install(|| intersect_shells(a, b, opts).expect("runs"))
}

/// This process's CPU seconds so far (user + system, from `/proc/self/stat`; `None` elsewhere).
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which is in parentheses): utime, stime are 14, 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// The median wall seconds of five runs, and the CPU seconds per run (mean).
fn median_seconds(
    pool: &rayon::ThreadPool,
    a: &[Face],
    b: &[Face],
    opts: &Options,
) -> (f64, Option<f64>) {
    let cpu0 = cpu_seconds();
    let mut t: Vec<f64> = (0..5)
        .map(|_| {
            let s = Instant::now();
            black_box(run(pool, a, b, opts));
            s.elapsed().as_secs_f64()
        })
        .collect();
    let cpu = cpu_seconds().zip(cpu0).map(|(c1, c0)| (c1 - c0) / 5.0);
    t.sort_by(f64::total_cmp);
    (t[2], cpu)
}

fn bench(c: &mut Criterion) {
    let (a, b, opts) = shells();
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, 2]
        .into_iter()
        .map(|n| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .expect("pool");
            (n, pool)
        })
        .collect();
    let r = run(&pools[0].1, &a, &b, &opts);
    let t: Vec<(f64, Option<f64>)> = pools
        .iter()
        .map(|(_, p)| median_seconds(p, &a, &b, &opts))
        .collect();
    let cpu = |k: usize| {
        t[k].1
            .map(|c| format!(" ({:.0} ms CPU, {:.2} cores busy)", 1e3 * c, c / t[k].0))
            .unwrap_or_default()
    };
    println!(
        "shell: {} x {} faces, {} face pairs, {} intersected after the box filter, {} branches, \
         {} joined curves ({} closed); 1 thread {:.1} ms{}, 2 threads {:.1} ms{}, ratio {:.2}",
        a.len(),
        b.len(),
        r.piece_pairs,
        r.piece_pairs - r.skipped_pairs,
        r.branch_count(),
        r.curves.len(),
        r.curves.iter().filter(|c| c.closed).count(),
        1e3 * t[0].0,
        cpu(0),
        1e3 * t[1].0,
        cpu(1),
        t[0].0 / t[1].0
    );
    let mut g = c.benchmark_group("shell_sphere_planes");
    g.sample_size(10);
    for (n, pool) in &pools {
        g.bench_function(format!("{n}_threads"), |bch| {
            bch.iter(|| black_box(run(pool, &a, &b, &opts)))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
