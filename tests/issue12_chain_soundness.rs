//! Issue 12: the one soundness flag of the random-pair soak with the cover chain (seed
//! 1 005 497 of `oracle_random`'s soak), reduced to its pair and explained.
//!
//! The two bicubic height fields below (the soak moves both by one rotation; the curve in the
//! parameter plane and the flag are the same without it, so the test uses them as they are) meet
//! in two curves that nearly cross near `(σ, t) ≈ (0.631, 0.680)`: `f − g` has a saddle there with
//! value about `−4.4e-5`. One curve runs from the left edge to the top edge (L–U), the other from
//! the bottom edge to the right edge (D–R). The marcher jumps the gap (its branches run L→R and
//! U→D), the chain follows the true curves, and proves D–R from boundary to boundary.
//!
//! The oracle's last check flags a reference point on L–U near the saddle: it lies within 0.02
//! of the marched points of the D–R branch, whose certificate claims both ends, yet in none of
//! that branch's boxes. The flag is not a false certificate. This test proves, independently of
//! the code under test, that `f − g < 0` along a polyline from the left edge through the saddle
//! to the corner `(1, 1)`; no curve crosses it, so the point (above it) and the D–R certificate
//! (which reaches below `t = 0.5`, where everything is under the polyline) lie on different
//! curves. The oracle's "near a marched branch" rule (distance 0.02 to marched points) cannot
//! tell two curves apart that come closer than that; the soak counts such a flag as a
//! violation, and it must be read with this in mind.
//!
//! Now the arm a jump leaves uncertified is traced again with a finer step (`solve/repair.rs`):
//! the L–U curve is certified too, and the flagged point lies in its boxes.

mod common;

use common::near_crossing::{patch, point, F, G};
use inari::{interval, Interval};
use ssitrace::{intersect, Method, Options};

/// `f − g` over a box, in interval arithmetic (de Casteljau, rows first).
fn h(x: Interval, y: Interval) -> Interval {
    let one = point(1.0);
    let eval = |z: &[f64; 16]| {
        let lerp = |c: &mut [Interval; 4], t: Interval| {
            for r in 1..4 {
                for k in 0..4 - r {
                    c[k] = (one - t) * c[k] + t * c[k + 1];
                }
            }
            c[0]
        };
        let mut col: [Interval; 4] = std::array::from_fn(|i| {
            let mut row: [Interval; 4] = std::array::from_fn(|j| point(z[i * 4 + j]));
            lerp(&mut row, y)
        });
        lerp(&mut col, x)
    };
    eval(&F) - eval(&G)
}

/// `f − g < 0` proven on the segment from `a` to `b` (its pieces' bounding boxes, bisected
/// until each is proven or `depth` runs out).
fn negative_on(a: [f64; 2], b: [f64; 2], depth: u32) -> bool {
    let bbox = |u: f64, v: f64| {
        let p = |w: f64, k: usize| a[k] + (b[k] - a[k]) * w;
        let iv = |x: f64, y: f64| interval!(x.min(y), x.max(y)).unwrap();
        // Widen by a little more than the rounding of `p`.
        let pad = |i: Interval| interval!(i.inf() - 1e-15, i.sup() + 1e-15).unwrap();
        (pad(iv(p(u, 0), p(v, 0))), pad(iv(p(u, 1), p(v, 1))))
    };
    let mut stack = vec![(0.0, 1.0, 0)];
    while let Some((u, v, d)) = stack.pop() {
        let (x, y) = bbox(u, v);
        if h(x, y).sup() < 0.0 {
            continue;
        }
        if d >= depth {
            return false;
        }
        let m = 0.5 * (u + v);
        stack.push((u, m, d + 1));
        stack.push((m, v, d + 1));
    }
    true
}

/// The polyline of `f − g < 0`: left edge, the saddle at about (0.6306, 0.6801), the corner.
const CHANNEL: [[f64; 2]; 7] = [
    [0.0, 0.5],
    [0.55, 0.66],
    [0.6206, 0.6656],
    [0.6306, 0.6801],
    [0.6406, 0.6946],
    [0.8, 0.8],
    [1.0, 1.0],
];

/// The polyline's `t` at `σ` (it is a graph over `σ`).
fn channel_t(s: f64) -> f64 {
    CHANNEL
        .windows(2)
        .find(|w| w[0][0] <= s && s <= w[1][0])
        .map(|w| w[0][1] + (w[1][1] - w[0][1]) * (s - w[0][0]) / (w[1][0] - w[0][0]))
        .unwrap()
}

#[test]
fn near_crossing_flag_is_two_curves_not_a_false_certificate() {
    // The flagged reference point: a sign change of f − g on the line t = 0.6875.
    let (s0, s1, t) = (0.6244042309212248, 0.6244042309215152, 0.6875);
    let (a, b) = (h(point(s0), point(t)), h(point(s1), point(t)));
    assert!(
        (a.sup() < 0.0 && b.inf() > 0.0) || (a.inf() > 0.0 && b.sup() < 0.0),
        "{a:?} {b:?}"
    );

    // No curve crosses the channel polyline, and the point is above it.
    for w in CHANNEL.windows(2) {
        assert!(
            negative_on(w[0], w[1], 24),
            "f − g < 0 not proven from {:?} to {:?}",
            w[0],
            w[1]
        );
    }
    assert!(t > channel_t(s1) + 1e-3);

    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&patch(&F), &patch(&G), &opts).unwrap();
    // The branch that claims both ends (D–R) and whose marched points come near the flagged
    // point: the oracle's trigger.
    let near = |br: &ssitrace::march::branch::Branch| {
        br.points
            .iter()
            .map(|p| (p.p[0] - 0.5 * (s0 + s1)).hypot(p.p[1] - t))
            .fold(f64::INFINITY, f64::min)
            < 0.02
    };
    let claims: Vec<_> = r
        .branches
        .iter()
        .filter(|br| {
            br.certified().is_some_and(|c| {
                c.ends
                    .iter()
                    .all(|e| e.kind() == "boundary" || e.kind() == "closed_loop")
            })
        })
        .filter(|br| near(&br.marched))
        .collect();
    // Each such branch is one of the two curves: the D–R curve, connected and reaching below
    // t = 0.5 (under the channel), whose boxes miss the flagged point (what the oracle saw); or,
    // since the arm a jump leaves uncertified is traced again (`solve/repair.rs`), the L–U
    // curve, whose boxes hold it and stay above the channel.
    let mut holders = 0;
    for br in claims {
        let c = br.certified().unwrap();
        let below = c.boxes.iter().any(|bx| bx.p[1].sup() < 0.5);
        let holds = c.boxes.iter().any(|bx| {
            bx.p[0].inf() <= s1 && s0 <= bx.p[0].sup() && bx.p[1].inf() <= t && t <= bx.p[1].sup()
        });
        assert!(
            below != holds,
            "branch {}: reaches below the channel {below}, holds the point {holds}",
            br.id()
        );
        holders += usize::from(holds);
    }
    assert_eq!(holders, 1, "the flagged point's curve is certified once");
}
