//! The certified tangential contact of the example scene, as the whole run (`intersect` with the
//! default options: marcher events, then the contact certifier) produces it, checked against the
//! scene's contact in closed form.
//!
//! `scenes/cubic_quadratic_tangential.json`: P and Q are graphs over the same square with
//! `P − Q = (1 + 0.3x)·(y − x/2)² ≥ 0`, so they meet exactly where `y = x/2` (and `1 + 0.3x > 0`
//! on the square), at equal parameters: the intersection is the curve `(x, x/2, x, x/2)`,
//! `x ∈ [−1, 1]`, with model point `(x, x/2, 0.9x²)`. The reference is independent of the
//! certifier: closed-form points, sampled densely, and P − Q evaluated in f64 off the curve.

mod common;

use common::scenes::scene;
use ssitrace::certify::contact::{ContactEnd, StepCase};
use ssitrace::solve::{intersect, Options};

fn curve(x: f64) -> [f64; 4] {
    [x, 0.5 * x, x, 0.5 * x]
}

#[test]
fn whole_run_contact_covers_the_closed_form_curve() {
    let s = scene("cubic_quadratic_tangential.json");
    let [p, q] = &s.surfaces;
    let r = intersect(p, q, &Options::default()).expect("run");
    assert!(r.contact_error.is_none(), "{:?}", r.contact_error);
    assert_eq!(r.contacts.len(), 1, "one contact curve");
    let c = &r.contacts[0];
    assert_eq!(c.start_case, StepCase::TangentialCurve);
    assert!(c.steps.iter().all(|s| s.case == StepCase::TangentialCurve));
    for e in &c.ends {
        assert!(matches!(e, ContactEnd::Boundary { .. }), "{e:?}");
    }
    assert!(c.cover.resolved);

    // The reference: P − Q vanishes on the curve and nowhere else nearby (f64, a sanity check
    // of the closed form itself).
    for k in 0..=40 {
        let x = -1.0 + k as f64 / 20.0;
        let on = (p.point_f64(x, 0.5 * x)[2] - q.point_f64(x, 0.5 * x)[2]).abs();
        let off = p.point_f64(x, 0.5 * x + 0.1)[2] - q.point_f64(x, 0.5 * x + 0.1)[2];
        assert!(on < 1e-14 && off > 0.005, "x = {x}: {on:e}, {off:e}");
    }

    // Every curve point lies in the searched region (the trace spans the whole curve), in a
    // kept cover box whose model box holds its model point, and in some step's a-priori box.
    let n = 4000;
    for k in 0..=n {
        let x = -1.0 + 2.0 * k as f64 / n as f64;
        let y = curve(x);
        let xyz = [x, 0.5 * x, 0.9 * x * x];
        assert!(
            c.cover
                .region
                .iter()
                .any(|b| b.iter().zip(&y).all(|(i, v)| i.contains(*v))),
            "{y:?} outside the searched region"
        );
        assert!(
            c.cover
                .boxes
                .iter()
                .any(|b| b.contains(&y) && b.xyz.iter().zip(&xyz).all(|(i, v)| i.contains(*v))),
            "{y:?} not covered"
        );
        assert!(
            c.steps
                .iter()
                .any(|s| s.apriori.iter().zip(&y).all(|(i, v)| i.contains(*v))),
            "{y:?} outside the tube's a-priori boxes"
        );
    }

    // The tube is the solution of the tangential field from the start box (a located marcher
    // point, within about 1e-9 of the curve), not the curve itself: it follows the curve as
    // closely as the start allows, not within its own radius.
    let start_off = {
        let y = c.start.map(|x| x.mid());
        (y[1] - 0.5 * y[0])
            .abs()
            .max((y[2] - y[0]).abs())
            .max((y[3] - 0.5 * y[0]).abs())
    };
    let mut tube_off = 0.0f64;
    for t in &c.tubes {
        for k in 0..=8 {
            let y = t.eval(t.h * k as f64 / 8.0);
            let off = (y[1] - 0.5 * y[0])
                .abs()
                .max((y[2] - y[0]).abs())
                .max((y[3] - 0.5 * y[0]).abs());
            tube_off = tube_off.max(off - 4.0 * t.radius_param);
        }
    }
    println!("start {start_off:.2e} off the curve, tube at most {tube_off:.2e} beyond its radius");
    assert!(
        start_off < 1e-7 && tube_off < 1e-6,
        "{start_off:e}, {tube_off:e}"
    );
    println!("{}", c.proven_statement);
}
