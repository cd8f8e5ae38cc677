//! Marching throughput (points per second) on a bicubic pair, circular vs tangent steps, on
//! analytic closures and on the same surfaces as rational Bézier patches; and the time of the
//! start-point search against the marching time on the same pair (ratios in one process).

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::{Domain, PowerSurface, RationalBezierPatch};
use ssitrace::march::{trace_branch, MarchOptions, StepMethod};
use ssitrace::search::start_points::{find_start_points, SearchOptions};
use ssitrace::topology::intersect::intersect;

/// z = (u² + v² − 0.5)(1 + 0.1uv) − 0.05u³ against z = 0.05 u³v³ over [−1, 1]²: both bicubic;
/// one closed loop near the circle of radius √0.5.
fn bezier_pair() -> (RationalBezierPatch, RationalBezierPatch) {
    let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
    let graph = |z: Vec<(u32, u32, f64)>| {
        PowerSurface::graph(d, z)
            .to_bezier()
            .expect("valid surface")
    };
    let p = graph(vec![
        (2, 0, 1.0),
        (0, 2, 1.0),
        (0, 0, -0.5),
        (3, 1, 0.1),
        (1, 3, 0.1),
        (1, 1, -0.05),
        (3, 0, -0.05),
        (3, 3, 0.0),
    ]);
    let q = graph(vec![(3, 3, 0.05)]);
    (p, q)
}

fn bench_marching(c: &mut Criterion) {
    let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
    let pa = AnalyticSurface::new(d, |u: Jet2, v: Jet2| {
        [
            u,
            v,
            (u * u + v * v - 0.5) * (1.0 + 0.1 * u * v) - 0.05 * u.powi(3),
        ]
    });
    let qa = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, 0.05 * u.powi(3) * v.powi(3)]);
    let (pb, qb) = bezier_pair();
    let start = [0.0, 0.5f64.sqrt(), 0.0, 0.5f64.sqrt()];
    let mut group = c.benchmark_group("marching_bicubic_loop");
    for (name, method) in [
        ("circular", StepMethod::Circular),
        ("tangent", StepMethod::Tangent),
    ] {
        let opts = MarchOptions {
            step: 0.02,
            method,
            ..MarchOptions::default()
        };
        let points = trace_branch(&pb, &qb, start, &opts)
            .map(|b| b.branch.points.len())
            .unwrap_or(1);
        group.throughput(Throughput::Elements(points as u64));
        group.bench_function(format!("{name}/analytic"), |b| {
            b.iter(|| trace_branch(black_box(&pa), black_box(&qa), black_box(start), &opts))
        });
        group.bench_function(format!("{name}/bezier"), |b| {
            b.iter(|| trace_branch(black_box(&pb), black_box(&qb), black_box(start), &opts))
        });
    }
    group.finish();

    let opts = MarchOptions {
        step: 0.02,
        ..MarchOptions::default()
    };
    let search = SearchOptions::default();
    let mut group = c.benchmark_group("branch_search_vs_march_bicubic");
    group.bench_function("march_one_branch", |b| {
        b.iter(|| trace_branch(black_box(&pb), black_box(&qb), black_box(start), &opts))
    });
    group.bench_function("start_point_search", |b| {
        b.iter(|| find_start_points(black_box(&pb), black_box(&qb), &search))
    });
    group.bench_function("intersect_all", |b| {
        b.iter(|| intersect(black_box(&pb), black_box(&qb), &opts, &search))
    });
    group.finish();
}

criterion_group!(benches, bench_marching);
criterion_main!(benches);
