//! The pieces behind the long certified steps, each checked against an independent computation:
//! the centred and scaled patch partials against the quotient rule of `eval_derivs`, the
//! cancellation-free field against the determinant form, the tape's simplification and its
//! time-constant centre against closed-form Taylor coefficients.

mod common;
use common::scenes::scene;

use common::odes::Square as PlainSquare;
use inari::Interval;
use ssitrace::geometry::{Domain, RationalBezierPatch};
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::numeric::vec3::{cross, det, norm_sqr};
use ssitrace::pair::field::{transversal_field, ScalarSurface};
use ssitrace::validated::tape::{Op, Tape};
use ssitrace::validated::{Expansion, OdeSystem, TaylorAd};
use ssitrace::Scalar;

/// A rational bicubic patch on a non-unit domain with unequal weights (a generic test patch).
fn patch() -> RationalBezierPatch {
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for i in 0..4 {
        for j in 0..3 {
            let (x, y) = (i as f64, j as f64);
            pts.push([
                x,
                y + 0.25 * x,
                0.5 * (x - 1.5).powi(2) - 0.3 * y * x + 0.125 * y,
            ]);
            w.push(1.0 + 0.25 * ((i + 2 * j) % 3) as f64);
        }
    }
    let domain = Domain {
        u: [-0.5, 1.5],
        v: [2.0, 2.25],
    };
    RationalBezierPatch::from_f64_points([3, 2], &pts, Some(&w), domain).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-10 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn scaled_and_centred_partials_match_the_quotient_rule() {
    let p = patch();
    for k in 0..40 {
        let u = -0.5 + 2.0 * ((k * 7) % 40) as f64 / 39.0;
        let v = 2.0 + 0.25 * ((k * 13) % 40) as f64 / 39.0;
        let d = p.derivs_f64(u, v);
        let (a, b, g) = p.scaled_partials(u, v);
        let (ac, bc, gc) = p.scaled_partials_centred(u, v, 0.3 - 0.01 * k as f64, 2.1);
        let first = p.first_derivs(u, v);
        for c in 0..3 {
            assert!(
                close(a[c] / g, d.su[c]) && close(b[c] / g, d.sv[c]),
                "{k} {c}"
            );
            assert!(
                close(ac[c] / gc, d.su[c]) && close(bc[c] / gc, d.sv[c]),
                "{k} {c}"
            );
            assert!(close(first[1][c], d.su[c]) && close(first[2][c], d.sv[c]));
            assert!(close(first[0][c], d.p[c]));
        }
        // Intervals enclose the f64 values, and a thin box at the centre is tight.
        let iv = |x: f64| point(x);
        let (ai, bi, gi) = p.scaled_partials_centred(iv(u), iv(v), iv(u), iv(v));
        for c in 0..3 {
            assert!(close(ai[c].mid(), ac[c]));
            assert!(bi[c].wid() < 1e-12 * (1.0 + bi[c].mag()));
        }
        assert!(gi.inf() > 0.0);
    }
}

#[test]
fn centred_partials_are_tighter_over_a_box() {
    // Over a small box the shifted power basis has far less dependency than Bernstein sums.
    let p = patch();
    let (u, v, r) = (0.4, 2.1, 1e-3);
    let bu = interval(u - r, u + r).unwrap();
    let bv = interval(v - r / 8.0, v + r / 8.0).unwrap();
    let (a0, ..) = p.scaled_partials(bu, bv);
    let (a1, ..) = p.scaled_partials_centred(bu, bv, point(u), point(v));
    let (af, ..) = p.scaled_partials(u, v);
    for c in 0..3 {
        assert!(a1[c].contains(af[c]) && a0[c].contains(af[c]));
        assert!(
            a1[c].wid() < 0.5 * a0[c].wid(),
            "{c}: {} vs {}",
            a1[c].wid(),
            a0[c].wid()
        );
    }
}

#[test]
fn evaluated_field_equals_the_determinant_form() {
    let p = patch();
    let q = RationalBezierPatch::from_f64_points(
        [1, 1],
        &[
            [0.8, -1.0, -1.0],
            [0.8, -1.0, 4.0],
            [1.2, 5.0, -1.0],
            [1.2, 5.0, 4.0],
        ],
        None,
        Domain::UNIT,
    )
    .unwrap();
    let (y, dir) = ([0.3, 2.1, 0.4, 0.6], -1.0);
    let f = transversal_field(&p, &q, &y, dir);
    // Independent evaluation: the determinant formulas of the module documentation.
    let [_, ps, pt] = p.first_order(y[0], y[1]);
    let [_, qu, qv] = q.first_order(y[2], y[3]);
    let np = cross(&ps, &pt);
    let nq = cross(&qu, &qv);
    let m = cross(&np, &nq);
    let len = norm_sqr(&m).sqrt();
    let c = m.map(|x| dir * x / len);
    let (np2, nq2) = (norm_sqr(&np), norm_sqr(&nq));
    let expected = [
        det(&c, &pt, &np) / np2,
        det(&ps, &c, &np) / np2,
        det(&c, &qv, &nq) / nq2,
        det(&qu, &c, &nq) / nq2,
    ];
    for i in 0..4 {
        assert!(
            close(f.velocity[i], expected[i]),
            "{i}: {:?} {expected:?}",
            f.velocity
        );
    }
    assert!(close(f.cross_norm_sqr, len * len));
    for (t, e) in f.tangent.iter().zip(&c) {
        assert!(close(*t, *e));
    }
}

/// y' = y², written with a dead branch, a repeated subexpression and (centred) around c as
/// (y − c)² + 2c(y − c) + c². Solution y₀/(1 − y₀t), Taylor coefficients y₀^{k+1}.
struct Square {
    centred: bool,
}

impl OdeSystem for Square {
    fn dim(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        let _dead = y[0] * y[0] + S::one();
        let a = y[0] * S::from_f64(0.5);
        let b = y[0] * S::from_f64(0.5);
        vec![(a + b).sqr()]
    }
    fn eval_centred<S: Scalar>(&self, y: &[S], c: &[S]) -> Vec<S> {
        let d = y[0] - c[0];
        vec![d.sqr() + S::from_f64(2.0) * c[0] * d + c[0].sqr()]
    }
    fn uses_centre(&self) -> bool {
        self.centred
    }
}

#[test]
fn tape_drops_dead_code_and_merges_repeats() {
    let t = Tape::record(&Square { centred: false }).unwrap();
    // Input, 0.5, y·0.5, (a + a), sqr: the dead product and the repeated y·0.5 are gone.
    assert_eq!(t.ops.len(), 5, "{:?}", t.ops);
    assert!(matches!(t.ops[0], Op::Input(0)));
}

#[test]
fn centred_tape_expands_to_the_exact_coefficients() {
    let y0 = [interval(0.49, 0.51).unwrap()];
    let mut widths = Vec::new();
    for centred in [false, true] {
        let tape = Tape::record(&Square { centred }).unwrap();
        assert_eq!(tape.ops.iter().any(|o| matches!(o, Op::Centre(0))), centred);
        let mut ad = TaylorAd::new(tape);
        let mut e = Expansion::default();
        ad.expand(&y0, 12, true, &mut e).unwrap();
        for k in 0..=12 {
            for x in [0.49, 0.5, 0.51] {
                let exact = Interval::powi(point(x), k as i32 + 1);
                assert!(e.coeff(k)[0].contains(exact.mid()), "{centred} {k} {x}");
            }
        }
        // d y_k / d y_0 = (k + 1) y₀^k.
        for k in 0..12 {
            let exact = point((k + 1) as f64) * Interval::powi(point(0.5), k as i32);
            assert!(e.jacobian(k)[0].contains(exact.mid()), "{centred} {k}");
        }
        widths.push(e.coeff(12)[0].wid());
    }
    println!(
        "order-12 widths: plain {:e}, centred {:e}",
        widths[0], widths[1]
    );
}

#[test]
fn remainder_over_pieces_is_sound() {
    use ssitrace::validated::{Integrator, IntegratorOptions};
    let y0 = [interval(0.5, 0.5 + 1e-6).unwrap()];
    let mut counts = Vec::new();
    for pieces in [1, 4] {
        let opts = IntegratorOptions {
            order: 12,
            term_target: 1e-14,
            ..Default::default()
        };
        let mut integ = Integrator::new(&PlainSquare, opts).unwrap();
        integ.set_remainder_pieces(pieces);
        let traj = integ.integrate(&y0, 0.0, 1.5).unwrap();
        // Exact solution y₀/(1 − y₀t) at every step end, for both ends of the initial box.
        for s in &traj.steps {
            for x in [0.5, 0.5 + 1e-6] {
                let exact = point(x) / (point(1.0) - point(x) * point(s.t1));
                assert!(
                    s.end[0].contains(exact.mid()),
                    "pieces {pieces} at t = {}",
                    s.t1
                );
                let half = s.enclose_on(0.0, s.h).unwrap();
                let mid = point(x) / (point(1.0) - point(x) * point(s.t0 + s.h / 2.0));
                assert!(half[0].contains(mid.mid()));
            }
        }
        counts.push(traj.steps.len());
    }
    println!(
        "y' = y², steps to t = 1.5: 1 piece {}, 4 pieces {}",
        counts[0], counts[1]
    );
}

#[test]
fn remainder_over_pieces_lengthens_steps_of_the_intersection_ode() {
    use ssitrace::certify::ode::TransversalOde;

    use ssitrace::validated::{Integrator, IntegratorOptions};
    let scene = scene("sphere_patch_plane.json");
    let [p, q] = &scene.surfaces;
    // A point of P away from (25/16, 0, 0), where the sphere's normal is the plane's, and one of
    // the plane Q: the ODE is defined there (non-parallel normals).
    let y0 = [0.85, 0.5, 0.5, 0.5].map(point);
    let ode = TransversalOde {
        p,
        q,
        orientation: 1.0,
    };
    let mut counts = Vec::new();
    for pieces in [1, 4] {
        let opts = IntegratorOptions {
            order: 20,
            term_target: 1e-13,
            h_max: 0.25,
            ..Default::default()
        };
        let mut integ = Integrator::new(&ode, opts).unwrap();
        integ.set_remainder_pieces(pieces);
        let traj = integ.integrate(&y0, 0.0, 0.5).unwrap();
        counts.push(traj.steps.len());
    }
    println!(
        "intersection ODE, steps for arc length 0.5: 1 piece {}, 4 pieces {}",
        counts[0], counts[1]
    );
    assert!(counts[1] < counts[0], "{counts:?}");
}
