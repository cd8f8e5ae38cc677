//! Issue 12: a curve that grazes the boundary is certified once, not run on into the next
//! marched piece.
//!
//! The pair of soak seed 1 001 569 (`oracle_random`, without its rotation: a bicubic P and a
//! biquadratic Q as height fields). The curve runs from the right edge down to the bottom edge
//! `t = 0`, touches it near `σ ≈ 0.2494`, dipping just outside, and runs on left to the left edge
//! close above it. The marcher ends two branches at the touching point. The chain of the left
//! piece walked past its marched end to a curve point found beyond the boundary, which lay back
//! inside the domain (the curve only dips out there); the walk never ended with a slice wholly
//! outside the domain at its target, so it ran on up the right piece to the right edge: that arc
//! was certified by two branches. Now the first link whose end slice lies wholly outside the
//! domain, on the bound where the marched branch ends, proves the boundary end there.
//!
//! Checked: every branch certified with both ends on the boundary, and no curve point (sign
//! changes of `f − g` on grid lines, refined by bisection) in the boxes of two of them.

mod common;

use common::surfaces::unit_height_patch as patch;
use ssitrace::{intersect, Method, Options};

/// Heights of P (bicubic, row `i` for `σ = i/3`).
const F: [f64; 16] = [
    -0.26502688849684314,
    -0.13159121667389645,
    0.12344551592120301,
    0.13572196711009976,
    -0.17356320732433825,
    -0.0397090700211537,
    -0.17956288477251567,
    -0.04386500342464855,
    -0.10469257650230937,
    -0.209124072958298,
    -0.09569394701341769,
    -0.2184876185728601,
    0.04001447518007256,
    -0.2604670464486441,
    -0.28332191422400893,
    -0.2123068683307357,
];

/// Heights of Q (biquadratic, row `i` for `σ = i/2`).
const G: [f64; 9] = [
    -0.2832922112004176,
    0.28767146900284596,
    0.014633412628385245,
    -0.07091275389040463,
    0.1149829368390467,
    -0.07008170524634832,
    -0.21102242660286838,
    -0.1031114016336192,
    0.09155847450735716,
];

/// A height field at `(x, y)` (de Casteljau in `f64`).
fn height(m: usize, z: &[f64], x: f64, y: f64) -> f64 {
    let lerp = |mut c: Vec<f64>, t: f64| {
        for r in 1..c.len() {
            for k in 0..c.len() - r {
                c[k] = (1.0 - t) * c[k] + t * c[k + 1];
            }
        }
        c[0]
    };
    let col = (0..=m)
        .map(|i| lerp((0..=m).map(|j| z[i * (m + 1) + j]).collect(), y))
        .collect();
    lerp(col, x)
}

/// Curve points on the lines `σ = k/16` and `t = k/16`: sign changes of `f − g` refined by
/// bisection, as `(σ range, t range)`.
fn samples() -> Vec<([f64; 2], [f64; 2])> {
    let h = |x: f64, y: f64| height(3, &F, x, y) - height(2, &G, x, y);
    let mut out = Vec::new();
    for k in 1..16 {
        let c = k as f64 / 16.0;
        for along_x in [true, false] {
            let at = |s: f64| if along_x { h(s, c) } else { h(c, s) };
            for i in 0..200 {
                let (mut a, mut b) = (i as f64 / 200.0, (i + 1) as f64 / 200.0);
                if at(a).signum() == at(b).signum() {
                    continue;
                }
                let sa = at(a).signum();
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break;
                    }
                    if at(m).signum() == sa {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                out.push(if along_x {
                    ([a, b], [c, c])
                } else {
                    ([c, c], [a, b])
                });
            }
        }
    }
    out
}

#[test]
fn grazing_curve_certified_once() {
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&patch(3, &F), &patch(2, &G), &opts).unwrap();
    assert!(!r.branches.is_empty());
    for b in &r.branches {
        let c = b.certified().expect("every branch certified");
        assert!(
            c.ends.iter().all(|e| e.kind() == "boundary"),
            "branch {}: ends {} / {}",
            b.id(),
            c.ends[0],
            c.ends[1]
        );
    }
    let pts = samples();
    assert!(pts.len() > 10);
    for (x, y) in pts {
        let holders: Vec<usize> = r
            .branches
            .iter()
            .filter(|b| {
                b.certified().is_some_and(|c| {
                    c.boxes.iter().any(|bx| {
                        bx.p[0].inf() <= x[1]
                            && x[0] <= bx.p[0].sup()
                            && bx.p[1].inf() <= y[1]
                            && y[0] <= bx.p[1].sup()
                    })
                })
            })
            .map(|b| b.id())
            .collect();
        assert!(
            holders.len() <= 1,
            "curve point {x:?} × {y:?} in the boxes of branches {holders:?}"
        );
    }
}
