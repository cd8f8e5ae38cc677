//! Seed 000 (Wu–Andrade), Table 2: distance at `s0 + L` of the parabola (2nd-order Taylor) and of
//! the exact osculating circle to three arc-length parametrised curves F, G, H.
//!
//! Derivatives come from the crate's `Jet2` (exact forward mode), the reference values are the
//! paper's printed 6-decimal numbers. An extra column `d_c` reports the Wu–Andrade approximate
//! circle (built from the points at `s0 − L` and `s0` with their tangents) advanced by arc `L`.

use nalgebra::Vector3;
use ssitrace::geometry::analytic::Jet2;
use ssitrace::march::circle_step::{approximate_circle, rotate};

type V = Vector3<f64>;

fn eval(curve: fn(Jet2) -> [Jet2; 3], s: f64) -> (V, V, V) {
    let c = curve(Jet2::var_x(s));
    (
        V::new(c[0].val, c[1].val, c[2].val),
        V::new(c[0].grad[0], c[1].grad[0], c[2].grad[0]),
        V::new(c[0].hess[0], c[1].hess[0], c[2].hess[0]),
    )
}

fn f_curve(s: Jet2) -> [Jet2; 3] {
    let a = s * (1.0 / 2f64.sqrt());
    [a.cos(), a.sin(), a]
}

fn g_curve(s: Jet2) -> [Jet2; 3] {
    let (p, m) = (1.0 + s, 1.0 - s);
    [
        p * p.sqrt() / 3.0,
        m * m.sqrt() / 3.0,
        s * (1.0 / 2f64.sqrt()),
    ]
}

fn h_curve(s: Jet2) -> [Jet2; 3] {
    let w = s + (s * s + 1.0).sqrt();
    [w * 0.5, 0.5 / w, w.ln() * (2f64.sqrt() / 2.0)]
}

/// (d_p, d_g, d_c) at s0 + L.
fn distances(curve: fn(Jet2) -> [Jet2; 3], s0: f64, l: f64) -> (f64, f64, f64) {
    let (a0, t, acc) = eval(curve, s0);
    let (exact, _, _) = eval(curve, s0 + l);
    let parabola = a0 + t * l + acc * (0.5 * l * l);
    let kappa = acc.norm();
    let n = acc / kappa;
    let circle = a0 + t * ((kappa * l).sin() / kappa) + n * ((1.0 - (kappa * l).cos()) / kappa);
    let (am, tm, _) = eval(curve, s0 - l);
    let approx = approximate_circle(&am, &tm.normalize(), &a0, &t.normalize(), 1e-12)
        .expect("tangents are not parallel");
    let stepped = approx.centre + rotate(&(a0 - approx.centre), &approx.axis, l / approx.radius);
    (
        (parabola - exact).norm(),
        (circle - exact).norm(),
        (stepped - exact).norm(),
    )
}

#[test]
fn curves_are_arc_length_parametrised() {
    for (name, c) in [
        ("F", f_curve as fn(Jet2) -> [Jet2; 3]),
        ("G", g_curve),
        ("H", h_curve),
    ] {
        for s in [-0.6, -0.5, -0.3, 0.0, 0.4, 0.6] {
            let (_, t, _) = eval(c, s);
            assert!(
                (t.norm() - 1.0).abs() < 1e-14,
                "{name}({s}): |α'| = {}",
                t.norm()
            );
        }
    }
}

#[test]
fn table2_parabola_and_osculating_circle_errors() {
    // (curve, s0, L, printed d_p, printed d_g)
    let printed: [(&str, f64, f64, f64, f64); 12] = [
        ("F", -0.5, 0.05, 0.000007, 0.000005),
        ("F", -0.5, 0.10, 0.000059, 0.000042),
        ("F", 0.5, 0.05, 0.000007, 0.000005),
        ("F", 0.5, 0.10, 0.000059, 0.000042),
        ("G", -0.5, 0.05, 0.000007, 0.000006),
        ("G", -0.5, 0.10, 0.000056, 0.000049),
        ("G", 0.5, 0.05, 0.000008, 0.000007),
        ("G", 0.5, 0.10, 0.000065, 0.000058),
        ("H", -0.5, 0.05, 0.000013, 0.000012),
        ("H", -0.5, 0.10, 0.000108, 0.000093),
        ("H", 0.5, 0.05, 0.000013, 0.000012),
        ("H", 0.5, 0.10, 0.000105, 0.000092),
    ];
    println!(
        "curve   s0     L   |  d_p ours   d_p paper |  d_g ours   d_g paper |  d_c (approx circle)"
    );
    let mut mismatches = Vec::new();
    for (name, s0, l, dp_paper, dg_paper) in printed {
        let c: fn(Jet2) -> [Jet2; 3] = match name {
            "F" => f_curve,
            "G" => g_curve,
            _ => h_curve,
        };
        let (dp, dg, dc) = distances(c, s0, l);
        println!(
            "  {name}   {s0:+.1}  {l:.2}  |  {dp:.6}   {dp_paper:.6}  |  {dg:.6}   {dg_paper:.6}  |  {dc:.6}"
        );
        let round6 = |x: f64| (x * 1e6).round();
        if round6(dp) != round6(dp_paper) {
            mismatches.push(format!("{name} s0={s0} L={l}: d_p {dp:.7} vs {dp_paper}"));
        }
        if round6(dg) != round6(dg_paper) {
            mismatches.push(format!("{name} s0={s0} L={l}: d_g {dg:.7} vs {dg_paper}"));
        }
        // The paper's observation: the circle is closer than the parabola in every case.
        assert!(dg < dp, "{name} {s0} {l}: d_g {dg} !< d_p {dp}");
        // The approximate circle (from the point one step back) has an error of the same order
        // L³ as the parabola's, a small factor larger (it only tends to the osculating circle).
        assert!(
            dc < 4.0 * dp,
            "{name} {s0} {l}: approximate circle off by {dc}"
        );
    }
    println!("mismatches after rounding to 6 decimals: {mismatches:?}");
    assert!(mismatches.is_empty());
}
