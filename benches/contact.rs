//! Benchmarks of the certified tangential contact on `scenes/cubic_quadratic_tangential.json`
//! (P − Q = (1 + 0.3x)(y − x/2)², contact along the parabola (x, x/2, 0.9x²)), with the ideas
//! that made it faster measured against each other in one run:
//!
//! - `contact_half/*`: one validated half of the tangential trace, from x = 0.25 to the boundary
//!   x = 1, for each form of the field: the scaled form on the Bézier patches' own centred
//!   second-order data at order 16 / 1e-14 (the form before), the same on the lean polynomial
//!   patches ([`ContactPatch`]), the ratio form ([`RatioTangentialOde`]), with the adaptive
//!   phase-I guess, and at the contact budget's order 20 / 5e-15;
//! - `certify_contact/*`: the whole certified contact (both halves, cases, cover) at the
//!   pipeline's cover options, on the global thread pool and on one thread;
//! - `contact_cover/*`: the cover alone over the same region, on the pool and on one thread.
//!
//! **What sizes the contact steps** (printed per variant before the groups; AMD EPYC Zen 3,
//! 2 cores, stop 21). The validated remainder over the a-priori box, not the solution: at
//! order 20 / 5e-15 (ratio form, adaptive guess) 83 steps of mean length 0.0148, 79 of them cut
//! short by the remainder; the point series over the thin initial set has a radius of
//! convergence of about 0.71, while the interval remainder coefficient over the a-priori box
//! behaves as if the radius were 0.077 — about 10× less, the wrapping of the interval Taylor
//! recurrences over a box that spans the step in every coordinate. Splitting the remainder's
//! box in time (`set_remainder_pieces`) lifts that radius only to 0.098 (2 pieces) and 0.120
//! (4 pieces): steps 1.3× and 1.6× longer, each costing more, 1.3× and 1.5× the time. Orders
//! 12 / 1e-13, 16 / 1e-14 and 20 / 5e-15 take 124, 99 and 83 steps and the same whole-process
//! time on the tangential scene (0.19-0.21 s wall, five runs each, taking turns), with tubes
//! of 2.3e-10, 2.1e-11 and 1.0e-11.
//!
//! Before the groups it prints each variant's steps and the median ratios of one quick timing
//! (thread CPU time is not available here: under load from other processes the wall-clock
//! ratios of the one-thread rows are the reliable ones).

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

mod common;

use common::median;
use criterion::{criterion_group, criterion_main, Criterion};
use ssitrace::certify::contact::{certify_contact, ContactOptions};
use ssitrace::certify::contact_cover::{contact_cover, CoverOptions};
use ssitrace::certify::contact_patch::ContactPatch;
use ssitrace::certify::tangential_ode::{pivot_sign, RatioTangentialOde, TangentialOde};
use ssitrace::certify::StepBudget;
use ssitrace::geometry::RationalBezierPatch;
use ssitrace::io::scene::Scene;
use ssitrace::numeric::scalar::point;
use ssitrace::pair::centred_second_order::CentredSecondOrder;
use ssitrace::pair::contact_quadratic::{contact_quadratic, TangentialFormula};
use ssitrace::solve::{COVER_EVALUATIONS, COVER_LEAF};
use ssitrace::validated::{Integrator, IntegratorOptions, IntegratorWork, OdeSystem};
use std::hint::black_box;
use std::path::Path;

/// The start on the contact curve, x = 0.25.
const START: [f64; 4] = [0.25, 0.125, 0.25, 0.125];

fn patches() -> (RationalBezierPatch, RationalBezierPatch) {
    let scene = Scene::from_path(Path::new("scenes/cubic_quadratic_tangential.json"))
        .expect("scene parses");
    let [p, q] = scene.surfaces;
    (p, q)
}

fn options(order: usize, term_target: f64) -> IntegratorOptions {
    IntegratorOptions {
        order,
        term_target,
        h_min: 1e-8,
        h_max: 0.125,
        qr: true,
        max_steps: usize::MAX,
    }
}

/// Integrates `f` from [`START`] until the end box leaves σ ≤ 1; returns the integrator's
/// work (its step count among it).
fn half<F: OdeSystem>(f: &F, opts: IntegratorOptions, guess: bool) -> IntegratorWork {
    let mut integ = Integrator::new(f, opts).expect("integrator");
    integ.set_adaptive_guess(guess);
    let mut state = integ.start(&START.map(point), 0.0).expect("start");
    let mut steps = 0;
    loop {
        let limit = state.t() + 1.0;
        let rec = integ.step(&mut state, limit).expect("step");
        steps += 1;
        if rec.end[0].inf() > 1.0 || steps > 5000 {
            return integ.work();
        }
    }
}

/// The scaled field oriented along +σ on surfaces `p`, `q`.
fn scaled<'a, P: CentredSecondOrder + ?Sized, Q: CentredSecondOrder + ?Sized>(
    p: &'a P,
    q: &'a Q,
    formula: TangentialFormula,
) -> TangentialOde<'a, P, Q> {
    let f = TangentialOde {
        p,
        q,
        formula,
        orientation: 1.0,
    };
    let orientation = f.velocity(&START)[0].signum();
    TangentialOde { orientation, ..f }
}

/// The half-trace variants, each a closure returning its step count.
type Variant<'a> = (&'static str, Box<dyn Fn() -> IntegratorWork + 'a>);

fn variants<'a>(
    p: &'a RationalBezierPatch,
    q: &'a RationalBezierPatch,
    lp: &'a ContactPatch<'a>,
    lq: &'a ContactPatch<'a>,
) -> Vec<Variant<'a>> {
    let formula = TangentialFormula::choose(&contact_quadratic(p, q, &START));
    let sign = pivot_sign(lp, lq, formula, &START.map(point)).expect("pivot sign");
    let ratio = move || RatioTangentialOde {
        field: scaled(lp, lq, formula),
        pivot_sign: sign,
    };
    vec![
        (
            "scaled_bezier_o16",
            Box::new(move || half(&scaled(p, q, formula), options(16, 1e-14), false)),
        ),
        (
            "scaled_lean_o16",
            Box::new(move || half(&scaled(lp, lq, formula), options(16, 1e-14), false)),
        ),
        (
            "ratio_lean_o16",
            Box::new(move || half(&ratio(), options(16, 1e-14), false)),
        ),
        (
            "ratio_lean_guess_o16",
            Box::new(move || half(&ratio(), options(16, 1e-14), true)),
        ),
        (
            "ratio_lean_guess_o20",
            Box::new(move || half(&ratio(), options(20, 5e-15), true)),
        ),
    ]
}

fn pipeline_contact() -> ContactOptions {
    ContactOptions {
        cover: CoverOptions {
            leaf_fraction: COVER_LEAF,
            max_evaluations: COVER_EVALUATIONS,
        },
        ..ContactOptions::default()
    }
}

fn one_thread<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool")
        .install(f)
}

fn print_ratios() {
    let (p, q) = patches();
    let (lp, lq) = (ContactPatch::new(&p), ContactPatch::new(&q));
    let vs = variants(&p, &q, &lp, &lq);
    let base = median(3, || {
        black_box((vs[0].1)());
    });
    println!(
        "contact half x = 0.25 → 1 (median of 3; ratio to {}):",
        vs[0].0
    );
    for (name, f) in &vs {
        let w = f();
        let t = median(3, || {
            black_box(f());
        });
        // What sized the steps: the mean step, and the two radii of `IntegratorWork` (the
        // point series' own radius of convergence, and the radius the validated remainder over
        // the a-priori box behaves as if it had), with the steps the remainder cut short.
        let per = |x: f64| x / w.steps.max(1) as f64;
        println!(
            "  {name:<22} {:>4} steps {:>8.1} ms  ×{:.2}   mean h {:.4}, radius: point {:.3}, \
             a-priori {:.3}; {} cut by the remainder",
            w.steps,
            t * 1e3,
            base / t,
            per(w.h_sum),
            per(w.radius_point_sum),
            per(w.radius_apriori_sum),
            w.remainder_cuts
        );
    }
    let opts = pipeline_contact();
    let old = ContactOptions {
        steps: StepBudget {
            order: 16,
            term_target: 1e-14,
            ..StepBudget::CONTACT
        },
        ..opts
    };
    let r = certify_contact(&p, &q, START, &opts).expect("contact");
    println!(
        "certify_contact: {} steps, tube radius {:.2e}, {} region boxes, {} cover boxes (max xyz width {:.3e})",
        r.steps.len(),
        r.tube_radius,
        r.cover.region.len(),
        r.cover.boxes.len(),
        r.cover.max_xyz_width
    );
    let whole = median(3, || {
        black_box(certify_contact(&p, &q, START, &opts).expect("contact"));
    });
    let whole_1 = median(3, || {
        one_thread(|| black_box(certify_contact(&p, &q, START, &opts).expect("contact")));
    });
    let whole_old = median(3, || {
        one_thread(|| black_box(certify_contact(&p, &q, START, &old).expect("contact")));
    });
    let cover = median(3, || {
        black_box(contact_cover(&p, &q, &r.cover.region, &opts.cover));
    });
    let cover_1 = median(3, || {
        one_thread(|| black_box(contact_cover(&p, &q, &r.cover.region, &opts.cover)));
    });
    println!(
        "certify_contact {:.1} ms (one thread {:.1} ms: ×{:.2}; one thread at order 16 / 1e-14 {:.1} ms)",
        whole * 1e3,
        whole_1 * 1e3,
        whole_1 / whole,
        whole_old * 1e3
    );
    println!(
        "contact_cover {:.1} ms (one thread {:.1} ms: ×{:.2})",
        cover * 1e3,
        cover_1 * 1e3,
        cover_1 / cover
    );
}

fn bench_contact(c: &mut Criterion) {
    print_ratios();
    let (p, q) = patches();
    let (lp, lq) = (ContactPatch::new(&p), ContactPatch::new(&q));
    let mut group = c.benchmark_group("contact_half");
    group.sample_size(10);
    for (name, f) in variants(&p, &q, &lp, &lq) {
        group.bench_function(name, |b| b.iter(|| black_box(f())));
    }
    group.finish();

    let opts = pipeline_contact();
    let mut group = c.benchmark_group("certify_contact");
    group.sample_size(10);
    group.bench_function("pool", |b| {
        b.iter(|| certify_contact(&p, &q, black_box(START), &opts).expect("contact"))
    });
    group.bench_function("one_thread", |b| {
        b.iter(|| one_thread(|| certify_contact(&p, &q, black_box(START), &opts)))
    });
    group.finish();

    let region = certify_contact(&p, &q, START, &opts)
        .expect("contact")
        .cover
        .region;
    let mut group = c.benchmark_group("contact_cover");
    group.sample_size(10);
    group.bench_function("pool", |b| {
        b.iter(|| contact_cover(&p, &q, black_box(&region), &opts.cover))
    });
    group.bench_function("one_thread", |b| {
        b.iter(|| one_thread(|| contact_cover(&p, &q, black_box(&region), &opts.cover)))
    });
    group.finish();
}

criterion_group!(benches, bench_contact);
criterion_main!(benches);
