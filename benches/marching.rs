//! Marching throughput (points per second) on a pair of bicubic polynomial graphs, circular vs
//! tangent steps. The surfaces are analytic closures for now (Bézier patches come later).

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::Domain;
use ssitrace::marching::{trace_branch, MarchOptions, StepMethod};

fn bench_marching(c: &mut Criterion) {
    let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
    // z = (u² + v² − 0.5)(1 + 0.1uv) − 0.05u³ (bicubic) against z = 0.05 u³v³ (bicubic):
    // a closed loop near the circle of radius √0.5.
    let p = AnalyticSurface::new(d, |u: Jet2, v: Jet2| {
        [
            u,
            v,
            (u * u + v * v - 0.5) * (1.0 + 0.1 * u * v) - 0.05 * u.powi(3),
        ]
    });
    let q = AnalyticSurface::new(d, |u: Jet2, v: Jet2| [u, v, 0.05 * u.powi(3) * v.powi(3)]);
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
        let points = trace_branch(&p, &q, start, &opts)
            .map(|b| b.branch.points.len())
            .unwrap_or(1);
        group.throughput(Throughput::Elements(points as u64));
        group.bench_function(name, |b| {
            b.iter(|| trace_branch(black_box(&p), black_box(&q), black_box(start), &opts))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_marching);
criterion_main!(benches);
