//! The wrapping test: the rotation `x' = −y, y' = x` from the box `[0.999, 1.001] × [−0.001, 0.001]`
//! over 100 revolutions, with Lohner's QR method and with a plain interval Taylor method.
//! Prints `name = value` lines: `width_qr` and `width_plain` are the largest widths of the final
//! boxes (the plain run may stop early when its box explodes; then the time it reached is printed).
//!
//! Usage: `cargo run --release --example rotation [ORDER]` (default 20).

use ssitrace::numeric::scalar::interval;
use ssitrace::validated::{Integrator, IntegratorOptions, OdeSystem};
use ssitrace::{Error, Scalar};

struct Rotation;

impl OdeSystem for Rotation {
    fn dim(&self) -> usize {
        2
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        vec![-y[1], y[0]]
    }
}

fn run(qr: bool, order: usize, name: &str) {
    let y0 = [
        interval(0.999, 1.001).expect("valid"),
        interval(-0.001, 0.001).expect("valid"),
    ];
    let t_end = 200.0 * std::f64::consts::PI;
    let options = IntegratorOptions {
        order,
        qr,
        ..IntegratorOptions::default()
    };
    let mut integrator = match Integrator::new(&Rotation, options) {
        Ok(i) => i,
        Err(e) => {
            println!("{name} = error: {e}");
            return;
        }
    };
    match integrator.integrate(&y0, 0.0, t_end) {
        Ok(traj) => {
            println!("{name} = {:.6e}", traj.end_width());
            println!("{name}_steps = {}", traj.steps.len());
        }
        Err(Error::StepFailed {
            time,
            state,
            reason,
            ..
        }) => {
            let w = state.iter().map(|v| v.wid()).fold(0.0, f64::max);
            println!("{name} = {w:.6e}");
            println!("{name}_stopped_at_t = {time:.6}");
            println!("{name}_stopped_because = {reason}");
        }
        Err(e) => println!("{name} = error: {e}"),
    }
}

fn main() {
    let order: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20);
    println!("initial_width = 2.000000e-3");
    println!("revolutions = 100");
    run(true, order, "width_qr");
    run(false, order, "width_plain");
}
