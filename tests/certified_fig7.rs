//! Seed 000 Fig. 7 certified: a degree-6 surface against a plane cut in three nested ellipses
//! 3u² + v² = 0.5, 0.6, 0.7 whose minimal distances are about 0.036 and 0.039. Each must be
//! certified as a closed loop, every box must meet its own ellipse (and only it), and the tubes of
//! different loops must be disjoint — a certificate that strays onto a neighbour fails here.
//! The reported tolerance is checked against the exact ellipses both ways (dense samples of the
//! reported curve against the ellipse, dense samples of the ellipse against the reported curve),
//! and must meet the target of 1e-9 for this unit-size model.

mod common;

use common::scenes::scene;
use ssitrace::certify::{CertifiedBranch, CertifiedEnd, TubePiece};
use ssitrace::io::scene::Method;
use ssitrace::numeric::scalar::point;
use ssitrace::pipeline::{run, RunOptions};

#[test]
fn three_nested_loops_are_certified_with_disjoint_tubes() {
    let scene = scene("wu_andrade_fig7.json");
    let mut opts = RunOptions::from_scene(&scene);
    opts.method = Method::Validated;
    let report = run(&scene, &opts).expect("runs");
    let loops: Vec<&CertifiedBranch> = report
        .result
        .certificates()
        .into_iter()
        .map(|c| c.result.as_ref().expect("certified"))
        .collect();
    assert_eq!(loops.len(), 3);
    let mut levels = Vec::new();
    for c in &loops {
        assert_eq!(c.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
        // The level 3σ² + t² of this loop: every box meets exactly that ellipse.
        let level = |b: &ssitrace::certify::EnclosureBox| point(3.0) * b.p[0].sqr() + b.p[1].sqr();
        let first = level(&c.boxes[0]);
        let own = [0.5, 0.6, 0.7]
            .into_iter()
            .find(|w| first.contains(*w))
            .expect("on an ellipse");
        for b in &c.boxes {
            let l = level(b);
            assert!(l.contains(own), "a box leaves its ellipse {own}");
            for other in [0.5, 0.6, 0.7] {
                if other != own {
                    assert!(
                        !l.contains(other),
                        "a box meets the neighbouring ellipse {other}"
                    );
                }
            }
            assert!(b.xyz[2].contains(0.0));
        }
        levels.push(own);
        println!(
            "loop 3σ²+t² = {own}: {} steps, tolerance {:.2e}, max transversal width {:.2e}",
            c.steps(),
            c.certified_tolerance,
            c.widths.iter().cloned().fold(0.0, f64::max)
        );
    }
    for (c, &w) in loops.iter().zip(&levels) {
        let (to_exact, to_reported) = (reported_to_ellipse(c, w), ellipse_to_reported(c, w));
        println!(
            "loop {w}: tolerance {:.2e}; largest distance reported → exact {to_exact:.2e}, \
             exact → reported {to_reported:.2e}",
            c.certified_tolerance
        );
        assert!(
            to_exact <= c.certified_tolerance + SLACK,
            "{to_exact} > {}",
            c.certified_tolerance
        );
        assert!(
            to_reported <= c.certified_tolerance + SLACK,
            "{to_reported} > {}",
            c.certified_tolerance
        );
        assert!(
            c.certified_tolerance <= 1e-9,
            "tolerance {}",
            c.certified_tolerance
        );
    }
    levels.sort_by(f64::total_cmp);
    assert_eq!(levels, [0.5, 0.6, 0.7]);
    // Disjoint tubes: no model-space box of one loop meets a box of another.
    for i in 0..3 {
        for j in i + 1..3 {
            for a in &loops[i].boxes {
                for b in &loops[j].boxes {
                    assert!(
                        a.xyz.iter().zip(&b.xyz).any(|(x, y)| x.disjoint(*y)),
                        "tubes {i} and {j} meet"
                    );
                }
            }
        }
    }
}

/// Rounding allowance of the f64 distance computations below (the distances are ~1e-12).
const SLACK: f64 = 1e-13;

/// The reported model curve of a tube piece at τ: `P(σ(τ), t(τ)) = (σ, t, z(σ, t))` with the
/// scene's z = −(w − 0.5)(w − 0.6)(w − 0.7), w = 3σ² + t² (its z coefficients, factored).
fn reported(piece: &TubePiece, tau: f64) -> [f64; 3] {
    let y = piece.eval(tau);
    let w = 3.0 * y[0] * y[0] + y[1] * y[1];
    [y[0], y[1], -(w - 0.5) * (w - 0.6) * (w - 0.7)]
}

/// Largest distance of 16 samples per tube piece of the reported curve to the ellipse
/// 3x² + y² = w in z = 0 (first order in the level: |F|/|∇F|, exact up to O(d²)).
fn reported_to_ellipse(c: &CertifiedBranch, w: f64) -> f64 {
    let mut worst = 0.0f64;
    for piece in &c.tubes {
        for m in 0..=16 {
            let [x, y, z] = reported(piece, piece.h * m as f64 / 16.0);
            let f = 3.0 * x * x + y * y - w;
            let planar = f.abs() / (36.0 * x * x + 4.0 * y * y).sqrt();
            worst = worst.max(planar.hypot(z));
        }
    }
    worst
}

/// Largest distance of 4000 points of the ellipse 3x² + y² = w, z = 0, to the reported curve:
/// for each, the nearest point of every tube piece whose angular range holds it (golden-section
/// search over τ).
fn ellipse_to_reported(c: &CertifiedBranch, w: f64) -> f64 {
    let (a, b) = ((w / 3.0).sqrt(), w.sqrt());
    let angle = |p: [f64; 3]| (p[1] / b).atan2(p[0] / a);
    let ranges: Vec<(f64, f64)> = c
        .tubes
        .iter()
        .map(|t| (angle(reported(t, 0.0)), angle(reported(t, t.h))))
        .collect();
    let dist2 = |t: &TubePiece, tau: f64, e: [f64; 3]| {
        let r = reported(t, tau);
        (r[0] - e[0]).powi(2) + (r[1] - e[1]).powi(2) + (r[2] - e[2]).powi(2)
    };
    let n = 4000;
    let mut worst = 0.0f64;
    for j in 0..n {
        let th = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
        let e = [a * th.cos(), b * th.sin(), 0.0];
        let mut best = f64::INFINITY;
        for (t, &(p0, p1)) in c.tubes.iter().zip(&ranges) {
            // Angular range of the piece (short arc), with a little slack.
            let span = (p1 - p0 + 3.0 * std::f64::consts::PI)
                .rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
            let off = (th - p0 + 3.0 * std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
            let slack = 1e-9;
            let inside = if span >= 0.0 {
                off >= -slack && off <= span + slack
            } else {
                off <= slack && off >= span - slack
            };
            if !inside {
                continue;
            }
            let (mut lo, mut hi) = (0.0, t.h);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..80 {
                let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                if dist2(t, m1, e) <= dist2(t, m2, e) {
                    hi = m2;
                } else {
                    lo = m1;
                }
            }
            best = best.min(dist2(t, 0.5 * (lo + hi), e).sqrt());
        }
        assert!(
            best.is_finite(),
            "no tube piece near the ellipse at angle {th}"
        );
        worst = worst.max(best);
    }
    worst
}
