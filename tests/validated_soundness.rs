//! Soundness of the validated integrator on systems with closed-form solutions, over many steps,
//! from interval initial boxes: the exact solution through every corner and through random
//! interior points must lie in every end box `[y_j]`, in every a-priori box `[ỹ_j]` at sampled
//! times inside the step, and in `StepRecord::enclose_on(a, b)` for sampled sub-intervals.
//!
//! How the exact solution is evaluated, per system:
//! * `y' = y²` and the nonlinear 4-D system: closed forms evaluated in `inari` interval arithmetic
//!   (rigorous, no margin).
//! * rotation and the linear 3×3 system: the closed forms need cos/sin/exp, which inari lacks
//!   without gmp; they are evaluated in `f64` (glibc's cos/sin/exp are accurate to about 1 ulp) and
//!   widened by a stated margin that bounds the floating-point error with a large safety factor and
//!   is still orders of magnitude below the box widths (so a wrong enclosure would be caught).

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

mod common;

use common::intervals::meets;
use common::odes::{integrator_of_order, Rotation, Square};
use inari::Interval;
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem, Trajectory};
use ssitrace::{Error, Scalar};

/// A deterministic pseudo-random sequence in [0, 1) (64-bit LCG), so failures reproduce.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Corners and `interior` random points of the box.
fn samples(b: &[Interval], interior: usize, seed: u64) -> Vec<Vec<f64>> {
    let n = b.len();
    let mut out: Vec<Vec<f64>> = (0..1usize << n)
        .map(|mask| {
            (0..n)
                .map(|j| {
                    if mask >> j & 1 == 1 {
                        b[j].sup()
                    } else {
                        b[j].inf()
                    }
                })
                .collect()
        })
        .collect();
    let mut rng = Lcg(seed);
    for _ in 0..interior {
        out.push(
            b.iter()
                .map(|v| v.inf() + rng.next() * (v.sup() - v.inf()))
                .collect(),
        );
    }
    out
}

/// Checks every step of `traj` against `exact(y0, t)`, an enclosure of the exact solution.
fn check_trajectory(
    traj: &Trajectory,
    y0: &[Interval],
    exact: &dyn Fn(&[f64], f64) -> Vec<Interval>,
    what: &str,
) {
    let pts = samples(y0, 8, 42);
    let mut checks = 0usize;
    for (j, step) in traj.steps.iter().enumerate() {
        for p in &pts {
            let at_end = exact(p, step.t1);
            for (c, (e, b)) in at_end.iter().zip(&step.end).enumerate() {
                assert!(
                    meets(*e, *b),
                    "{what}: step {j} end, component {c}: exact {e:?} not in {b:?}"
                );
            }
            for frac in [0.0, 0.25, 0.5, 0.9, 1.0] {
                let t = (step.t0 + frac * (step.t1 - step.t0)).min(step.t1);
                let e = exact(p, t);
                for (c, (ev, b)) in e.iter().zip(&step.apriori).enumerate() {
                    assert!(
                        meets(*ev, *b),
                        "{what}: step {j} a-priori at t={t}, component {c}: {ev:?} not in {b:?}"
                    );
                }
                // A short sub-interval [a, b] of the step that contains τ = t − t0.
                let tau = point(t) - point(step.t0);
                let (a, bnd) = (tau.inf().max(0.0), tau.sup().min(step.h));
                if a <= bnd {
                    let sub = step.enclose_on(a, bnd).expect("valid sub-interval");
                    for (c, (ev, b)) in e.iter().zip(&sub).enumerate() {
                        assert!(meets(*ev, *b), "{what}: step {j} enclose_on at t={t}, component {c}: {ev:?} not in {b:?}");
                    }
                    // and a wider one from the step start
                    let wide = step.enclose_on(0.0, bnd).expect("valid sub-interval");
                    for (ev, b) in e.iter().zip(&wide) {
                        assert!(meets(*ev, *b), "{what}: step {j} enclose_on(0, b) at t={t}");
                    }
                }
                checks += 1;
            }
        }
    }
    let w = traj.end_width();
    println!(
        "{what}: {} steps, {checks} sample checks, final width {w:.3e}",
        traj.steps.len()
    );
}

fn widened(x: f64, margin: f64) -> Interval {
    interval(x - margin, x + margin).expect("finite")
}

#[test]
fn rotation_box_over_ten_revolutions_contains_exact_solution() {
    let y0 = [
        interval(0.999, 1.001).unwrap(),
        interval(-0.001, 0.001).unwrap(),
    ];
    for order in [8, 20, 30] {
        let mut integ = integrator_of_order(&Rotation, order);
        let traj = integ
            .integrate(&y0, 0.0, 20.0 * std::f64::consts::PI)
            .unwrap();
        // Rotation::exact: f64 cos/sin widened by 100× their error bound.
        check_trajectory(&traj, &y0, &Rotation::exact, &format!("rotation k={order}"));
        assert!(
            traj.end_width() < 2.1e-3,
            "QR keeps the width: {}",
            traj.end_width()
        );
    }
}

/// A = V·diag(−1, −1/2, 1/4)·V⁻¹ with V = [[1,1,0],[0,1,1],[1,0,1]], V⁻¹ = ½[[1,−1,1],[1,1,−1],[−1,1,1]]:
/// all entries are short dyadic numbers, so A is exact in f64.
const V: [[f64; 3]; 3] = [[1.0, 1.0, 0.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0]];
const VINV: [[f64; 3]; 3] = [[0.5, -0.5, 0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, 0.5]];
const LAMBDA: [f64; 3] = [-1.0, -0.5, 0.25];

fn linear_a() -> [[f64; 3]; 3] {
    let mut a = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            a[i][j] = (0..3).map(|l| V[i][l] * LAMBDA[l] * VINV[l][j]).sum();
        }
    }
    a
}

struct Linear3([[f64; 3]; 3]);
impl OdeSystem for Linear3 {
    fn dim(&self) -> usize {
        3
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        (0..3)
            .map(|i| (0..3).fold(S::zero(), |acc, j| acc + S::from_f64(self.0[i][j]) * y[j]))
            .collect()
    }
}

#[test]
fn linear_three_by_three_distinct_eigenvalues_contains_exact_solution() {
    let a = linear_a();
    // A·V = V·D checks the dyadic construction (exact in f64).
    for i in 0..3 {
        for l in 0..3 {
            let av: f64 = (0..3).map(|j| a[i][j] * V[j][l]).sum();
            assert_eq!(av, V[i][l] * LAMBDA[l]);
        }
    }
    let y0 = [
        interval(0.99, 1.01).unwrap(),
        interval(-0.51, -0.49).unwrap(),
        interval(1.99, 2.01).unwrap(),
    ];
    let mut integ = integrator_of_order(&Linear3(a), 20);
    let traj = integ.integrate(&y0, 0.0, 10.0).unwrap();
    // y(t) = V·diag(e^{λt})·V⁻¹·y0 in f64: exp is ≤ 1 ulp, the rest ~20 roundings of numbers bounded
    // by 2·e^{2.5}·‖y0‖₁ ≈ 60: error < 1e-12. Margin 1e-11 (box widths are ≥ 1e-3 here).
    let exact = |p: &[f64], t: f64| {
        let w: Vec<f64> = (0..3)
            .map(|l| (LAMBDA[l] * t).exp() * (0..3).map(|j| VINV[l][j] * p[j]).sum::<f64>())
            .collect();
        (0..3)
            .map(|i| widened((0..3).map(|l| V[i][l] * w[l]).sum(), 1e-11))
            .collect()
    };
    check_trajectory(&traj, &y0, &exact, "linear 3x3");
}

#[test]
fn y_squared_contains_rational_solution_up_to_near_blow_up() {
    let y0 = [interval(0.9, 0.91).unwrap()];
    for order in [5, 15, 30] {
        let mut integ = integrator_of_order(&Square, order);
        let traj = integ.integrate(&y0, 0.0, 1.0).unwrap();
        // y(t) = y0/(1 − y0 t), evaluated in intervals: rigorous, no margin.
        check_trajectory(&traj, &y0, &Square::exact, &format!("y'=y² k={order}"));
    }
}

#[test]
fn y_squared_past_blow_up_reports_typed_error_with_state() {
    let mut integ = Integrator::new(
        &Square,
        IntegratorOptions {
            order: 20,
            h_min: 1e-6,
            ..Default::default()
        },
    )
    .unwrap();
    match integ.integrate(&[point(1.0)], 0.0, 2.0) {
        Err(Error::StepFailed { time, state, .. }) => {
            // The solution 1/(1 − t) blows up at t = 1: the integrator stops before, and the state
            // it reports encloses the exact solution at that time.
            assert!(time < 1.0, "stopped at {time}");
            let e = point(1.0) / (point(1.0) - point(time));
            assert!(meets(e, state[0]), "{e:?} not in {:?}", state[0]);
            println!(
                "y'=y² from 1 stopped at t = {time} with y in [{}, {}]",
                state[0].inf(),
                state[0].sup()
            );
        }
        other => panic!("expected StepFailed, got {other:?}"),
    }
}

/// x' = x², y' = x·y, z' = √z, u' = y/x; exact: x = x0/(1−x0 t), y = y0/(1−x0 t),
/// z = (√z0 + t/2)², u = u0 + t·y0/x0.
struct Nonlinear;
impl OdeSystem for Nonlinear {
    fn dim(&self) -> usize {
        4
    }
    fn eval<S: Scalar>(&self, s: &[S]) -> Vec<S> {
        vec![s[0].sqr(), s[0] * s[1], s[2].sqrt(), s[1] / s[0]]
    }
}

#[test]
fn nonlinear_four_dimensional_system_contains_exact_solution() {
    let y0 = [
        interval(0.5, 0.51).unwrap(),
        interval(1.0, 1.01).unwrap(),
        interval(1.0, 1.01).unwrap(),
        interval(0.0, 0.01).unwrap(),
    ];
    let mut integ = integrator_of_order(&Nonlinear, 25);
    let traj = integ.integrate(&y0, 0.0, 1.5).unwrap();
    let exact = |p: &[f64], t: f64| {
        let (x0, y0, z0, u0) = (point(p[0]), point(p[1]), point(p[2]), point(p[3]));
        let tt = point(t);
        let d = point(1.0) - x0 * tt;
        vec![
            x0 / d,
            y0 / d,
            (z0.sqrt() + tt / point(2.0)).sqr(),
            u0 + tt * y0 / x0,
        ]
    };
    check_trajectory(&traj, &y0, &exact, "nonlinear 4-D");
}

#[test]
fn point_initial_condition_stays_tight_and_sound() {
    // y' = y² from the point 0.5 to t = 1.5 (solution 0.5/(1 − 0.5t) = 2 at the end).
    let mut integ = integrator_of_order(&Square, 30);
    let traj = integ.integrate(&[point(0.5)], 0.0, 1.5).unwrap();
    check_trajectory(&traj, &[point(0.5)], &Square::exact, "y'=y² point");
    assert!(traj.end[0].contains(2.0));
    assert!(traj.end_width() < 1e-12, "width {}", traj.end_width());
}

#[test]
fn bad_inputs_give_typed_errors() {
    assert!(matches!(
        Integrator::new(
            &Square,
            IntegratorOptions {
                order: 0,
                ..Default::default()
            }
        ),
        Err(Error::BadIntegratorSetup(_))
    ));
    assert!(matches!(
        Integrator::new(
            &Square,
            IntegratorOptions {
                term_target: -1.0,
                ..Default::default()
            }
        ),
        Err(Error::BadIntegratorSetup(_))
    ));
    let mut integ = Integrator::new(&Square, IntegratorOptions::default()).unwrap();
    assert!(matches!(
        integ.integrate(&[point(0.5), point(1.0)], 0.0, 1.0),
        Err(Error::InvalidInput { .. })
    ));
    assert!(integ.integrate(&[point(0.5)], 1.0, 0.0).is_err());
    let traj = integ.integrate(&[point(0.5)], 0.0, 0.1).unwrap();
    let s = &traj.steps[0];
    assert!(s.enclose_on(-0.1, 0.0).is_err());
    assert!(s.enclose_on(0.0, s.h * 2.0).is_err());
    assert!(s.enclose_on(f64::NAN, 0.0).is_err());
    // Stepping towards a time not after the current one, and expanding a box of the wrong size.
    let mut state = integ.start(&[point(0.5)], 1.0).unwrap();
    assert!(matches!(
        integ.step(&mut state, 1.0),
        Err(Error::BadIntegratorSetup(_))
    ));
    assert!(matches!(
        integ.step(&mut state, f64::NAN),
        Err(Error::BadIntegratorSetup(_))
    ));
    let mut e = ssitrace::validated::Expansion::default();
    assert_eq!(
        integ
            .ad()
            .expand(&[point(0.5), point(0.5)], 5, true, &mut e),
        Err(ssitrace::validated::DomainError::WrongDimension)
    );
    // √ of a negative value: the field is undefined there, typed error.
    struct Bad;
    impl OdeSystem for Bad {
        fn dim(&self) -> usize {
            1
        }
        fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
            vec![y[0].sqrt()]
        }
    }
    let mut integ = Integrator::new(&Bad, IntegratorOptions::default()).unwrap();
    assert!(matches!(
        integ.integrate(&[interval(-1.0, 1.0).unwrap()], 0.0, 1.0),
        Err(Error::StepFailed { .. })
    ));
}

#[test]
fn phase_one_never_proves_an_enclosure_past_a_blow_up() {
    use ssitrace::validated::enclosure::prove_apriori;
    use ssitrace::validated::tape::Tape;
    use ssitrace::validated::{Expansion, TaylorAd};
    // y' = y², y(0) = 1: y = 1/(1 − t) blows up at t = 1.
    let mut ad = TaylorAd::new(Tape::record(&Square).unwrap());
    for order in [1, 4, 12, 30] {
        let (mut exp, mut scratch) = (Expansion::default(), Expansion::default());
        ad.expand(&[point(1.0)], order, false, &mut exp).unwrap();
        for h in [0.05, 0.2, 0.5, 0.9, 0.999, 1.0, 1.001, 1.5, 4.0] {
            match prove_apriori(&mut ad, &[point(1.0)], &exp, order, h, &mut scratch) {
                Ok(a) => {
                    assert!(
                        h < 1.0,
                        "order {order}: 'proved' an enclosure over [0, {h}]"
                    );
                    for frac in [0.0, 0.3, 0.7, 1.0] {
                        let t = h * frac;
                        let exact = point(1.0) / (point(1.0) - point(t));
                        assert!(meets(exact, a.boxed[0]), "order {order}, h {h}, t {t}");
                    }
                    println!(
                        "order {order}: h = {h} proven ({:?}), box [{}, {}]",
                        a.method,
                        a.boxed[0].inf(),
                        a.boxed[0].sup()
                    );
                }
                Err(e) => println!("order {order}: h = {h} rejected ({e:?})"),
            }
        }
    }
}

#[test]
fn low_orders_with_loose_tolerance_are_sound() {
    // Low orders take many small steps (the test prints how many the first-order test proved).
    let y0 = [
        interval(0.999, 1.001).unwrap(),
        interval(-0.001, 0.001).unwrap(),
    ];
    for order in [2, 3, 4] {
        let options = IntegratorOptions {
            order,
            term_target: 1e-6,
            h_min: 1e-12,
            ..Default::default()
        };
        let mut integ = Integrator::new(&Rotation, options).unwrap();
        let traj = integ.integrate(&y0, 0.0, 2.0).unwrap();
        let first_order = traj
            .steps
            .iter()
            .filter(|s| s.method == ssitrace::validated::EnclosureMethod::FirstOrder)
            .count();
        println!(
            "rotation k={order}: {first_order} of {} steps proven by the first-order test",
            traj.steps.len()
        );
        check_trajectory(&traj, &y0, &Rotation::exact, &format!("rotation k={order}"));
    }
}

#[test]
fn field_of_wrong_length_is_a_setup_error() {
    struct Wrong;
    impl OdeSystem for Wrong {
        fn dim(&self) -> usize {
            2
        }
        fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
            vec![y[0]]
        }
    }
    assert!(matches!(
        Integrator::new(&Wrong, IntegratorOptions::default()),
        Err(Error::BadIntegratorSetup(_))
    ));
}
