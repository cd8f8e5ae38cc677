//! The planar circular restricted three-body problem (PCR3BP), a published reference run:
//! μ = 0.0009537, x0 = 0.9208034913207400196, y = p = 0, q0 from the Jacobi constant 3.03,
//! integrated to T = 3.082119126376508 with order 30. Prints `name = value` lines.
//!
//! Usage: `cargo run --release --example pcr3bp [ORDER] [TOLERANCE]` (defaults 30 and 1e-16).
//! CAPD (Taylor method, doubleton sets) reports final widths ≈ 6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12.

use inari::Interval;
use ssitrace::scalar::interval;
use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem};
use ssitrace::Scalar;

/// An interval enclosing the decimal number `s` (its nearest double widened by one ulp each side).
fn decimal(s: &str) -> Interval {
    let x: f64 = s.parse().expect("a decimal literal");
    interval(x.next_down(), x.next_up()).expect("finite")
}

/// PCR3BP in the rotating frame, state (x, y, p, q).
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

fn main() {
    let order: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(30);
    let tolerance: f64 = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1e-16);
    let mu = decimal("0.0009537");
    let x0 = decimal("0.9208034913207400196");
    let one = ssitrace::scalar::point(1.0);
    let c = decimal("3.03");
    let q0 = (x0.sqr()
        + ssitrace::scalar::point(2.0)
            * ((one - mu) / (x0 + mu).abs() + mu / (x0 - one + mu).abs())
        + mu * (one - mu)
        - c)
        .sqrt();
    let zero = ssitrace::scalar::point(0.0);
    let y0 = [x0, zero, zero, q0];
    let t_end = 3.082119126376508;
    let options = IntegratorOptions {
        order,
        tolerance,
        ..IntegratorOptions::default()
    };
    let mut integrator = match Integrator::new(&Pcr3bp { mu }, options) {
        Ok(i) => i,
        Err(e) => {
            eprintln!("error = {e}");
            std::process::exit(1);
        }
    };
    let start = std::time::Instant::now();
    match integrator.integrate(&y0, 0.0, t_end) {
        Ok(traj) => {
            let secs = start.elapsed().as_secs_f64();
            println!("order = {order}");
            println!("steps = {}", traj.steps.len());
            let names = ["x", "y", "p", "q"];
            for (n, v) in names.iter().zip(&traj.end) {
                println!("{n} = [{:.17e}, {:.17e}]", v.inf(), v.sup());
            }
            for (n, v) in names.iter().zip(&traj.end) {
                println!("width_{n} = {:.3e}", v.wid());
            }
            println!("capd_widths = 6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12");
            println!("seconds = {secs:.4}");
        }
        Err(e) => {
            eprintln!("error = {e}");
            std::process::exit(1);
        }
    }
}
