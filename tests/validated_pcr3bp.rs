//! The published reference run: the planar circular restricted three-body problem to
//! T = 3.082119126376508 with order 30 (CAPD, Taylor method with doubleton sets, reports final
//! widths ≈ 6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12). We require widths at least as small, and check
//! soundness independently through the Jacobi integral, which is conserved along the flow and
//! equals 3.03 by construction of the initial condition: its interval evaluation over every end box
//! and every a-priori box must contain 3.03.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

use inari::Interval;
use ssitrace::scalar::{interval, point};
use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem};
use ssitrace::Scalar;

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

/// The Jacobi integral x² + y² + 2((1−μ)/r1 + μ/r2) + μ(1−μ) − (p² + q²), in intervals.
fn jacobi(mu: Interval, s: &[Interval]) -> Interval {
    let one = point(1.0);
    let r1 = ((s[0] + mu).sqr() + s[1].sqr()).sqrt();
    let r2 = ((s[0] - one + mu).sqr() + s[1].sqr()).sqrt();
    s[0].sqr() + s[1].sqr() + point(2.0) * ((one - mu) / r1 + mu / r2) + mu * (one - mu)
        - (s[2].sqr() + s[3].sqr())
}

#[test]
fn pcr3bp_reference_run_matches_or_beats_capd() {
    let mu = decimal("0.0009537");
    let c = decimal("3.03");
    let x0 = decimal("0.9208034913207400196");
    let one = point(1.0);
    let q0 = (x0.sqr()
        + point(2.0) * ((one - mu) / (x0 + mu).abs() + mu / (x0 - one + mu).abs())
        + mu * (one - mu)
        - c)
        .sqrt();
    let y0 = [x0, point(0.0), point(0.0), q0];
    assert!(jacobi(mu, &y0).contains(3.03));
    let mut integ = Integrator::new(
        &Pcr3bp { mu },
        IntegratorOptions {
            order: 30,
            ..Default::default()
        },
    )
    .unwrap();
    let traj = integ.integrate(&y0, 0.0, 3.082119126376508).unwrap();
    let capd = [6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12];
    println!("steps = {}", traj.steps.len());
    println!("{:>6} {:>12} {:>12}", "coord", "ours", "CAPD");
    for (j, name) in ["x", "y", "p", "q"].iter().enumerate() {
        println!("{name:>6} {:>12.3e} {:>12.1e}", traj.end[j].wid(), capd[j]);
    }
    for (j, step) in traj.steps.iter().enumerate() {
        // Jacobi constant 3.03 (a decimal: its enclosure c must meet the evaluation).
        assert!(
            !jacobi(mu, &step.end).intersection(c).is_empty(),
            "end box of step {j}"
        );
        assert!(
            !jacobi(mu, &step.apriori).intersection(c).is_empty(),
            "a-priori box of step {j}"
        );
    }
    // Sub-interval enclosures are far tighter than the a-priori box: on [0.5h, 0.51h] the box is
    // about the solution's motion over 0.01h, not over h.
    let mut worst_ratio = 0.0f64;
    for step in &traj.steps {
        let sub = step.enclose_on(0.5 * step.h, 0.51 * step.h).unwrap();
        for (s, a) in sub.iter().zip(&step.apriori) {
            if a.wid() > 1e-6 {
                worst_ratio = worst_ratio.max(s.wid() / a.wid());
            }
        }
    }
    // At a single instant inside a step the enclosure is as tight as the set itself.
    let at_mid = traj.steps.iter().map(|st| {
        let e = st.enclose_on(0.5 * st.h, 0.5 * st.h).unwrap();
        e.iter().map(|v| v.wid()).fold(0.0, f64::max)
    });
    let worst_point = at_mid.fold(0.0, f64::max);
    println!("largest width of enclose_on(0.5h, 0.5h) over all steps = {worst_point:.3e}");
    assert!(worst_point < 1e-10, "{worst_point}");
    println!("largest width ratio enclose_on(0.5h, 0.51h) / a-priori box = {worst_ratio:.3e}");
    assert!(worst_ratio < 0.05, "{worst_ratio}");
    for j in 0..4 {
        assert!(
            traj.end[j].wid() <= capd[j],
            "coordinate {j}: {} > CAPD {}",
            traj.end[j].wid(),
            capd[j]
        );
    }
    // At T the orbit is back on the x-axis crossing it perpendicularly (y ≈ 0, p ≈ 0): a sanity
    // check on the trajectory itself, not on the enclosure.
    assert!(traj.end[1].mag() < 1e-9 && traj.end[2].mag() < 1e-9);
}
