//! Seed 003 (Bulut, DQOC) examples 1–3: the dual-quaternion step agrees with the matrix circular
//! step to rounding, and both predictions lie close to the exact curves
//! (t, t², t³), (t, t², t² + t⁴), (cos t, sin t, cos 2t). The full marcher is then run on the
//! surface pairs of the examples with both step methods.

use nalgebra::Vector3;
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::Domain;
use ssitrace::march::branch::{BranchStatus, EndReason};
use ssitrace::march::circle_step::circular_step;
use ssitrace::march::dqoc_step::dqoc_step;
use ssitrace::march::tangent_step::tangent_step;
use ssitrace::march::{trace_branch, MarchOptions, StepMethod};

type V = Vector3<f64>;
/// A curve with its derivative.
type Curve = fn(f64) -> (V, V);

fn ex1(t: f64) -> (V, V) {
    (
        V::new(t, t * t, t * t * t),
        V::new(1.0, 2.0 * t, 3.0 * t * t),
    )
}
fn ex2(t: f64) -> (V, V) {
    (
        V::new(t, t * t, t * t + t.powi(4)),
        V::new(1.0, 2.0 * t, 2.0 * t + 4.0 * t.powi(3)),
    )
}
fn ex3(t: f64) -> (V, V) {
    (
        V::new(t.cos(), t.sin(), (2.0 * t).cos()),
        V::new(-t.sin(), t.cos(), -2.0 * (2.0 * t).sin()),
    )
}

/// Distance from `a` to the curve, minimising over `t ∈ [lo, hi]` (dense sampling, then golden
/// section around the best sample).
fn dist_to_curve(curve: Curve, a: &V, lo: f64, hi: f64) -> f64 {
    let d = |t: f64| (curve(t).0 - a).norm();
    let n = 2000;
    let h = (hi - lo) / n as f64;
    let best = (0..=n)
        .map(|i| lo + h * i as f64)
        .min_by(|x, y| d(*x).total_cmp(&d(*y)))
        .unwrap();
    let (mut x0, mut x1) = (best - h, best + h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (c, e) = (x1 - g * (x1 - x0), x0 + g * (x1 - x0));
        if d(c) < d(e) {
            x1 = e
        } else {
            x0 = c
        }
    }
    d(0.5 * (x0 + x1))
}

#[test]
fn dqoc_agrees_with_circular_step_and_tracks_the_curves() {
    let examples: [(&str, Curve, [f64; 3]); 3] = [
        ("1: (t,t²,t³)", ex1, [-0.8, 0.1, 0.7]),
        ("2: (t,t²,t²+t⁴)", ex2, [-0.6, 0.2, 0.9]),
        ("3: (cos t,sin t,cos 2t)", ex3, [0.3, 1.5, 2.6]),
    ];
    println!(
        "example                   t_k    L    |circ−dqoc|   dist circ   dist dqoc   dist tangent"
    );
    for (name, curve, ts) in examples {
        for &tk in &ts {
            for &l in &[0.05, 0.1] {
                // Previous point one parameter step back so the chord is about L long.
                let dt = l / curve(tk).1.norm();
                let (pp, tp) = curve(tk - dt);
                let (pc, tc) = curve(tk);
                let (tp, tc) = (tp.normalize(), tc.normalize());
                let c = circular_step(&pp, &tp, &pc, &tc, l, 1e-9);
                let q = dqoc_step(&pp, &tp, &pc, &tc, l, 1e-9);
                let t = tangent_step(&pc, &tc, l);
                let diff = (c.point - q.point).norm();
                let scale = 1.0 + pc.norm();
                assert!(diff < 1e-14 * scale, "{name} t={tk} L={l}: {diff}");
                assert!((c.tangent - q.tangent).norm() < 1e-14);
                let range = (tk, tk + 6.0 * dt);
                let dc = dist_to_curve(curve, &c.point, range.0, range.1);
                let dq = dist_to_curve(curve, &q.point, range.0, range.1);
                let dtan = dist_to_curve(curve, &t.point, range.0, range.1);
                println!(
                    "{name:<24} {tk:+.2}  {l:.2}   {diff:.1e}     {dc:.2e}    {dq:.2e}    {dtan:.2e}"
                );
                // The circle follows the curve to second order: much closer than the tangent.
                assert!(
                    dc < 0.5 * dtan,
                    "{name} t={tk} L={l}: circle {dc} vs tangent {dtan}"
                );
            }
        }
    }
}

#[test]
fn marching_on_the_example_surfaces_with_both_methods() {
    let big = Domain::new(-1.2, 1.2, -2.0, 2.0);
    // Example 1: z = xy against z = (x³ + xy)/2; the curve y = x², z = x³ (and the line x = z = 0).
    let s1 = AnalyticSurface::new(big, |u: Jet2, v: Jet2| [u, v, u * v]);
    let s2 = AnalyticSurface::new(big, |u: Jet2, v: Jet2| [u, v, (u.powi(3) + u * v) * 0.5]);
    // Example 2: z = x² + y² against the parabolic cylinder y = x².
    let s3 = AnalyticSurface::new(big, |u: Jet2, v: Jet2| [u, v, u * u + v * v]);
    let s4 = AnalyticSurface::new(Domain::new(-1.2, 1.2, -1.0, 6.0), |u: Jet2, v: Jet2| {
        [u, u * u, v]
    });
    // Example 3: the cylinder x² + y² = 1 (angle in [−π, π]: the loop is cut at the seam)
    // against z = x² − y².
    let pi = std::f64::consts::PI;
    let s5 = AnalyticSurface::new(Domain::new(-pi, pi, -2.0, 2.0), |a: Jet2, h: Jet2| {
        [a.cos(), a.sin(), h]
    });
    let s6 = AnalyticSurface::new(Domain::new(-1.5, 1.5, -1.5, 1.5), |u: Jet2, v: Jet2| {
        [u, v, u * u - v * v]
    });

    let on1 = |x: &[f64; 3]| ((x[1] - x[0] * x[0]).abs()).max((x[2] - x[0].powi(3)).abs());
    let on2 =
        |x: &[f64; 3]| ((x[1] - x[0] * x[0]).abs()).max((x[2] - x[0] * x[0] - x[0].powi(4)).abs());
    let on3 = |x: &[f64; 3]| {
        ((x[0] * x[0] + x[1] * x[1] - 1.0).abs()).max((x[2] - x[0] * x[0] + x[1] * x[1]).abs())
    };
    for method in [StepMethod::Circular, StepMethod::Dqoc] {
        let opts = MarchOptions {
            step: 0.1,
            method,
            ..MarchOptions::default()
        };
        let b1 = trace_branch(&s1, &s2, [0.5, 0.25, 0.5, 0.25], &opts).unwrap();
        let b2 = trace_branch(&s3, &s4, [0.5, 0.25, 0.5, 0.3125], &opts).unwrap();
        let a: f64 = 0.7;
        let b3 = trace_branch(&s5, &s6, [a, (2.0 * a).cos(), a.cos(), a.sin()], &opts).unwrap();
        println!(
            "{method:?}: ex1 {} points, ends {:?}; ex2 {} points, ends {:?}; ex3 {} points, ends {:?}",
            b1.branch.points.len(),
            b1.branch.ends,
            b2.branch.points.len(),
            b2.branch.ends,
            b3.branch.points.len(),
            b3.branch.ends
        );
        let worst = |b: &ssitrace::march::TracedBranch, on: &dyn Fn(&[f64; 3]) -> f64| {
            b.branch
                .points
                .iter()
                .map(|c| on(&c.xyz))
                .fold(0.0, f64::max)
        };
        assert!(worst(&b1, &on1) < 1e-9);
        assert!(worst(&b2, &on2) < 1e-9);
        assert!(worst(&b3, &on3) < 1e-9);
        // The loop is closed in model space but cut by the seam a = ±π of the cylinder's domain:
        // both ends land exactly on it.
        assert_eq!(b3.branch.status, BranchStatus::Open);
        assert_eq!(b3.branch.ends, [EndReason::Boundary { surface: 0 }; 2]);
        for end in [
            b3.branch.points.first().unwrap(),
            b3.branch.points.last().unwrap(),
        ] {
            assert_eq!(end.p[0].abs(), pi);
        }
        assert!(b2
            .branch
            .ends
            .iter()
            .all(|e| matches!(e, EndReason::Boundary { .. })));
        // Example 1 meets the line x = z = 0 at the origin (a singular point) on one side.
        assert!(
            b1.branch.ends.contains(&EndReason::Singular),
            "{:?}",
            b1.branch.ends
        );
        let sing = b1
            .events
            .iter()
            .find(|e| e.kind == ssitrace::march::branch::EventKind::Singular)
            .expect("singular event reported");
        println!("  ex1 singular point reported at {:?}", sing.xyz);
        assert!(V::from(sing.xyz).norm() < 0.05);
    }
    // Both methods give the same points (to Newton's tolerance).
    let run = |m| {
        let o = MarchOptions {
            step: 0.1,
            method: m,
            ..MarchOptions::default()
        };
        trace_branch(&s3, &s4, [0.5, 0.25, 0.5, 0.3125], &o)
            .unwrap()
            .branch
            .points
    };
    let (pc, pd) = (run(StepMethod::Circular), run(StepMethod::Dqoc));
    assert_eq!(pc.len(), pd.len());
    let dev = pc
        .iter()
        .zip(&pd)
        .map(|(a, b)| (V::from(a.xyz) - V::from(b.xyz)).norm())
        .fold(0.0, f64::max);
    println!("circular vs DQOC marching on example 2: max point deviation {dev:.1e}");
    assert!(dev < 1e-9);
}
