//! The rigorous branch search (`find_start_points`) on the repository's scenes and on a loop of
//! radius 1e-6, and, on the bicubic pair, the search time against the marching time of the same
//! scene's branches measured in the same process (printed as a ratio).

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ssitrace::geometry::{Domain, PowerSurface, RationalBezierPatch};
use ssitrace::io::scene::Scene;
use ssitrace::march::{trace_branch, MarchOptions};
use ssitrace::search::start_points::{find_start_points, SearchOptions};
use ssitrace::topology::intersect::intersect;
use std::path::Path;
use std::time::Instant;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    Scene::from_path(&path).expect("scene parses")
}

/// The paraboloid z = 1 − x² − y² on [−1, 1]² (exact biquadratic) and the plane z = 1 − r²
/// (bilinear): one loop of radius `r`.
fn bump_and_plane(r: f64) -> (RationalBezierPatch, RationalBezierPatch) {
    let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
    let bump = PowerSurface::graph(d, vec![(0, 0, 1.0), (2, 0, -1.0), (0, 2, -1.0)]);
    let plane = PowerSurface::graph(d, vec![(0, 0, 1.0 - r * r), (1, 1, 0.0)]);
    (
        bump.to_bezier().expect("valid bump"),
        plane.to_bezier().expect("valid plane"),
    )
}

/// Mean seconds of `f` over enough runs to fill about 0.3 s.
fn seconds<T>(mut f: impl FnMut() -> T) -> f64 {
    let t = Instant::now();
    let mut runs = 0u32;
    while runs < 3 || t.elapsed().as_secs_f64() < 0.3 {
        black_box(f());
        runs += 1;
    }
    t.elapsed().as_secs_f64() / f64::from(runs)
}

fn bench_search(c: &mut Criterion) {
    let search = SearchOptions::default();
    // Search against marching on the bicubic scene, in this process.
    let s = scene("bicubic_transversal.json");
    let [p, q] = &s.surfaces;
    let march = MarchOptions {
        step: s.options.step,
        ..MarchOptions::default()
    };
    let report = find_start_points(p, q, &search);
    let outcome = intersect(p, q, &march, &search);
    let starts: Vec<[f64; 4]> = outcome
        .intersection
        .branches
        .iter()
        .map(|b| {
            let c = &b.points[0];
            [c.p[0], c.p[1], c.q[0], c.q[1]]
        })
        .collect();
    let t_search = seconds(|| find_start_points(p, q, &search));
    let t_march = seconds(|| {
        starts
            .iter()
            .filter(|x| trace_branch(p, q, **x, &march).is_ok())
            .count()
    });
    println!(
        "bicubic_transversal: {} branches, search {:.2} ms, marching {:.2} ms, search/march = {:.2} \
         (pairs disjoint {}, loop-free {}, undecided regions {}, complete {})",
        starts.len(),
        1e3 * t_search,
        1e3 * t_march,
        t_search / t_march,
        report.disjoint_pairs,
        report.loop_free_pairs,
        report.undecided_regions.len(),
        report.complete
    );
    for name in [
        "sphere_patch_plane.json",
        "two_loops_s31_s32.json",
        "wu_andrade_fig7.json",
    ] {
        let s = scene(name);
        let [p, q] = &s.surfaces;
        let r = find_start_points(p, q, &search);
        let t = seconds(|| find_start_points(p, q, &search));
        println!(
            "{name}: search {:.2} ms (loop-free {}, undecided regions {}, complete {})",
            1e3 * t,
            r.loop_free_pairs,
            r.undecided_regions.len(),
            r.complete
        );
    }

    let mut group = c.benchmark_group("branch_search");
    group.sample_size(10);
    group.bench_function("bicubic_transversal", |b| {
        b.iter(|| find_start_points(black_box(p), black_box(q), &search))
    });
    group.bench_function("bicubic_transversal_march", |b| {
        b.iter(|| {
            starts
                .iter()
                .filter(|x| trace_branch(black_box(p), black_box(q), **x, &march).is_ok())
                .count()
        })
    });
    let (bump, plane) = bump_and_plane(1e-6);
    group.bench_function("loop_radius_1e-6", |b| {
        b.iter(|| find_start_points(black_box(&bump), black_box(&plane), &search))
    });
    group.finish();
}

criterion_group!(benches, bench_search);
criterion_main!(benches);
