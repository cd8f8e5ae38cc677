//! The published reference run: the planar circular restricted three-body problem to
//! T = 3.082119126376508 with order 30 (CAPD, Taylor method with doubleton sets, reports final
//! widths ≈ 6.5e-12, 1.8e-12, 1.5e-11, 6.3e-12). We require widths at least as small, and check
//! soundness independently through the Jacobi integral, which is conserved along the flow and
//! equals 3.03 by construction of the initial condition: its interval evaluation over every end box
//! and every a-priori box must contain 3.03.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

use ssitrace::validated::reference::{decimal, Pcr3bp, PCR3BP_CAPD_WIDTHS, PCR3BP_T_END};
mod common;

use common::odes::integrator_of_order;

#[test]
fn pcr3bp_reference_run_matches_or_beats_capd() {
    let sys = Pcr3bp::reference();
    let c = decimal("3.03");
    let y0 = sys.initial_state();
    assert!(sys.jacobi(&y0).contains(3.03));
    let mut integ = integrator_of_order(&sys, 30);
    let traj = integ.integrate(&y0, 0.0, PCR3BP_T_END).unwrap();
    let capd = PCR3BP_CAPD_WIDTHS;
    println!("steps = {}", traj.steps.len());
    println!("{:>6} {:>12} {:>12}", "coord", "ours", "CAPD");
    for (j, name) in ["x", "y", "p", "q"].iter().enumerate() {
        println!("{name:>6} {:>12.3e} {:>12.1e}", traj.end[j].wid(), capd[j]);
    }
    for (j, step) in traj.steps.iter().enumerate() {
        // Jacobi constant 3.03 (a decimal: its enclosure c must meet the evaluation).
        assert!(
            !sys.jacobi(&step.end).intersection(c).is_empty(),
            "end box of step {j}"
        );
        assert!(
            !sys.jacobi(&step.apriori).intersection(c).is_empty(),
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
