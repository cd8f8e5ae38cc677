//! The wrapping test: the rotation `x' = −y, y' = x` from a box over 100 revolutions. With
//! Lohner's QR method the width must stay near its initial size; with a plain interval Taylor
//! method (the set kept as a box) it must blow up. Both numbers are printed.

mod common;

use common::odes::Rotation;
use ssitrace::numeric::scalar::interval;
use ssitrace::validated::{Integrator, IntegratorOptions};
use ssitrace::Error;

/// Largest final width after 100 revolutions (or at the point where the run had to stop).
fn width_after_100_revolutions(qr: bool) -> (f64, f64) {
    let y0 = [
        interval(0.999, 1.001).unwrap(),
        interval(-0.001, 0.001).unwrap(),
    ];
    let t_end = 200.0 * std::f64::consts::PI;
    let mut integ = Integrator::new(
        &Rotation,
        IntegratorOptions {
            order: 20,
            qr,
            ..Default::default()
        },
    )
    .unwrap();
    match integ.integrate(&y0, 0.0, t_end) {
        Ok(traj) => (traj.end_width(), t_end),
        Err(Error::StepFailed { time, state, .. }) => {
            (state.iter().map(|v| v.wid()).fold(0.0, f64::max), time)
        }
        Err(e) => panic!("unexpected error {e}"),
    }
}

#[test]
fn qr_keeps_width_while_plain_box_method_wraps() {
    let (w_qr, t_qr) = width_after_100_revolutions(true);
    let (w_plain, t_plain) = width_after_100_revolutions(false);
    println!("initial width = 2.0e-3");
    println!("width_qr    = {w_qr:.6e} (reached t = {t_qr:.4})");
    println!("width_plain = {w_plain:.6e} (reached t = {t_plain:.4})");
    // The exact set after 100 revolutions is the initial box rotated by 200π (≈ the identity);
    // its hull has width 2e-3. QR must stay within 1% of it.
    assert!(t_qr == 200.0 * std::f64::consts::PI);
    assert!((2.0e-3..2.02e-3).contains(&w_qr), "QR width {w_qr}");
    // The box method wraps by a factor ≈ (|cos h| + |sin h|) per step: expect astronomical growth.
    assert!(w_plain > 1e10, "plain width {w_plain}");
}
