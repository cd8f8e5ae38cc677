//! Benchmarks of the validated Taylor engine: the PCR3BP reference run (to T = 3.0821…) at orders
//! 10, 20 and 30 (throughput in steps per second, final width printed), and one expansion to
//! order 30 by the tape recurrences versus the naive series evaluation.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use inari::Interval;
use ssitrace::scalar::{interval, point};
use ssitrace::validated::series::naive_expand;
use ssitrace::validated::tape::Tape;
use ssitrace::validated::{Expansion, Integrator, IntegratorOptions, OdeSystem, TaylorAd};
use ssitrace::Scalar;
use std::hint::black_box;

fn decimal(s: &str) -> Interval {
    let x: f64 = s.parse().unwrap();
    interval(x.next_down(), x.next_up()).unwrap()
}

struct Pcr3bp {
    mu: Interval,
}

impl OdeSystem for Pcr3bp {
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, s: &[S]) -> Vec<S> {
        let (x, y, p, q) = (s[0], s[1], s[2], s[3]);
        let mu = S::from_interval(self.mu);
        let one = S::one();
        let y2 = y.sqr();
        let d1 = x + mu;
        let d2 = x - one + mu;
        let r1 = d1.sqr() + y2;
        let r2 = d2.sqr() + y2;
        let a = (one - mu) / (r1 * r1.sqrt());
        let b = mu / (r2 * r2.sqrt());
        let two = S::from_f64(2.0);
        vec![
            p,
            q,
            x - d1 * a - d2 * b + two * q,
            y * (one - a - b) - two * p,
        ]
    }
}

fn initial(mu: Interval) -> [Interval; 4] {
    let x0 = decimal("0.9208034913207400196");
    let one = point(1.0);
    let q0 = (x0.sqr()
        + point(2.0) * ((one - mu) / (x0 + mu).abs() + mu / (x0 - one + mu).abs())
        + mu * (one - mu)
        - decimal("3.03"))
    .sqrt();
    [x0, point(0.0), point(0.0), q0]
}

const T_END: f64 = 3.082119126376508;

fn pcr3bp_orders(c: &mut Criterion) {
    let mu = decimal("0.0009537");
    let sys = Pcr3bp { mu };
    let y0 = initial(mu);
    let mut group = c.benchmark_group("pcr3bp_to_T");
    group.sample_size(10);
    for order in [10usize, 20, 30] {
        let mut integ = Integrator::new(
            &sys,
            IntegratorOptions {
                order,
                ..Default::default()
            },
        )
        .unwrap();
        let traj = integ.integrate(&y0, 0.0, T_END).unwrap();
        let widths: Vec<String> = traj
            .end
            .iter()
            .map(|v| format!("{:.3e}", v.wid()))
            .collect();
        println!(
            "order {order}: steps = {}, final widths = [{}]",
            traj.steps.len(),
            widths.join(", ")
        );
        group.throughput(Throughput::Elements(traj.steps.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(order), &order, |b, _| {
            b.iter(|| {
                black_box(
                    integ
                        .integrate(black_box(&y0), 0.0, T_END)
                        .unwrap()
                        .steps
                        .len(),
                )
            })
        });
    }
    group.finish();
}

fn expansion_schemes(c: &mut Criterion) {
    let mu = decimal("0.0009537");
    let sys = Pcr3bp { mu };
    let y0 = initial(mu);
    let mut ad = TaylorAd::new(Tape::record(&sys).unwrap());
    let mut e = Expansion::default();
    let mut group = c.benchmark_group("expand_order_30");
    group.bench_function("tape_coefficients", |b| {
        b.iter(|| ad.expand(black_box(&y0), 30, false, &mut e).unwrap())
    });
    group.bench_function("tape_with_jacobians", |b| {
        b.iter(|| ad.expand(black_box(&y0), 30, true, &mut e).unwrap())
    });
    group.bench_function("naive_series", |b| {
        b.iter(|| naive_expand(&sys, black_box(&y0), 30).unwrap())
    });
    group.finish();
}

criterion_group!(benches, pcr3bp_orders, expansion_schemes);
criterion_main!(benches);
