//! Evaluation and enclosure costs of rational Bézier patches.

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use ssitrace::geometry::{Domain, ParametricSurface, RationalBezierPatch};
use ssitrace::numeric::scalar::{interval, point};

fn patch(deg: usize) -> RationalBezierPatch {
    let mut pts = Vec::new();
    let mut ws = Vec::new();
    for i in 0..=deg {
        for j in 0..=deg {
            pts.push([i as f64, j as f64, ((i * j) as f64).sin()]);
            ws.push(1.0 + 0.1 * (i + j) as f64);
        }
    }
    RationalBezierPatch::from_f64_points([deg, deg], &pts, Some(&ws), Domain::UNIT)
        .expect("valid patch")
}

fn bench(c: &mut Criterion) {
    for deg in [2, 3, 5] {
        let s = patch(deg);
        c.bench_function(&format!("derivs f64 deg {deg}"), |b| {
            b.iter(|| s.derivs(black_box(0.3), black_box(0.6)))
        });
        c.bench_function(&format!("point f64 deg {deg}"), |b| {
            b.iter(|| s.point(black_box(0.3), black_box(0.6)))
        });
        let (u, v) = (interval(0.3, 0.31).unwrap(), interval(0.6, 0.61).unwrap());
        c.bench_function(&format!("enclose deg {deg}"), |b| {
            b.iter(|| s.enclose(black_box(u), black_box(v)))
        });
        c.bench_function(&format!("enclose_derivs deg {deg}"), |b| {
            b.iter(|| s.enclose_derivs(black_box(u), black_box(point(0.6))))
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
