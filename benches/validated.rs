//! Benchmarks of the validated Taylor engine: the PCR3BP reference run (to T = 3.0821…) at orders
//! 10, 20 and 30 (throughput in steps per second, final width printed), and one expansion to
//! order 30 by the tape recurrences versus the naive series evaluation.

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use ssitrace::validated::reference::{Pcr3bp, PCR3BP_T_END};
use ssitrace::validated::series::naive_expand;
use ssitrace::validated::tape::Tape;
use ssitrace::validated::{Expansion, Integrator, IntegratorOptions, TaylorAd};
use std::hint::black_box;

const T_END: f64 = PCR3BP_T_END;

fn pcr3bp_orders(c: &mut Criterion) {
    let sys = Pcr3bp::reference();
    let y0 = sys.initial_state();
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
    let sys = Pcr3bp::reference();
    let y0 = sys.initial_state();
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
