//! The planar circular restricted three-body problem (PCR3BP), a published reference run:
//! μ = 0.0009537, x0 = 0.9208034913207400196, y = p = 0, q0 from the Jacobi constant 3.03,
//! integrated to T = 3.082119126376508 with order 30. Prints `name = value` lines.
//!
//! Usage: `cargo run --release --example pcr3bp [ORDER] [TOLERANCE]` (defaults 30 and 1e-16).
//! CAPD (Taylor method, doubleton sets) reports final widths ≈ 6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12.

use ssitrace::validated::reference::{Pcr3bp, PCR3BP_CAPD_WIDTHS, PCR3BP_T_END};
use ssitrace::validated::{Integrator, IntegratorOptions};

fn main() {
    let order: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(30);
    let term_target: f64 = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1e-16);
    let sys = Pcr3bp::reference();
    let y0 = sys.initial_state();
    let t_end = PCR3BP_T_END;
    let options = IntegratorOptions {
        order,
        term_target,
        ..IntegratorOptions::default()
    };
    let mut integrator = match Integrator::new(&sys, options) {
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
            let w = PCR3BP_CAPD_WIDTHS;
            println!(
                "capd_widths = {:e}, {:e}, {:e}, {:e}",
                w[0], w[1], w[2], w[3]
            );
            println!("seconds = {secs:.4}");
        }
        Err(e) => {
            eprintln!("error = {e}");
            std::process::exit(1);
        }
    }
}
