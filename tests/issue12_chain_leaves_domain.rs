//! Issue 12: a half of a cover chain that has lost its marched path stops where its curve
//! leaves the domain, instead of walking that curve far outside the patches.
//!
//! The pair of `issue12_chain_soundness.rs` (seed 1 005 497 of the soak, without its rotation):
//! two curves nearly cross near `(σ, t) ≈ (0.631, 0.680)`, and the marched branch from the left
//! edge jumps there onto the other curve (left arm, then right arm). Its chain, walked back from
//! the right arm, could not reach the marched nodes on the left arm; the split links followed
//! the curve they were on down to the bottom edge and on below it, to `t ≈ −5.7` (some 1900
//! links), and the half ended with a singular box there. Now the half stops at the first link
//! towards a split point whose end slice lies wholly outside a domain while the marched node it
//! heads for is inside: an unproven end near the bottom edge.

use inari::{interval, Interval};
use ssitrace::geometry::{Domain, RationalBezierPatch};
use ssitrace::{intersect, Method, Options};

/// Heights of P (bicubic, row `i` for `σ = i/3`).
const F: [f64; 16] = [
    -0.15508506196974167,
    -0.23859780711928655,
    -0.28015772179560555,
    0.2540426435672631,
    0.13808578799750737,
    -0.09488688252111602,
    -0.10499270602065844,
    0.2864442249019779,
    -0.2778684719332966,
    0.12077925209189444,
    0.07551622685773807,
    0.09824896593714516,
    0.08082110293703099,
    -0.05174394139229191,
    0.15187937015288316,
    -0.18028144937220153,
];

/// Heights of Q (bicubic).
const G: [f64; 16] = [
    0.07392655611752857,
    -0.10783668076099179,
    -0.003995702505873389,
    -0.17867774666638914,
    0.28556229901688907,
    0.10956565997194923,
    -0.14581992773512623,
    0.08584199449860519,
    0.04288993518996126,
    0.014209406668136526,
    0.07911441792246243,
    0.23329262893614694,
    -0.11496530533119895,
    -0.005637415291305348,
    -0.08255162307743522,
    0.056983838910329876,
];

fn point(x: f64) -> Interval {
    interval!(x, x).unwrap()
}

fn patch(z: &[f64; 16]) -> RationalBezierPatch {
    let points = (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| [i as f64 / 3.0, j as f64 / 3.0, z[i * 4 + j]].map(point))
        .collect();
    RationalBezierPatch::new([3, 3], points, None, Domain::new(0.0, 1.0, 0.0, 1.0)).unwrap()
}

#[test]
fn lost_half_stops_at_the_domain() {
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&patch(&F), &patch(&G), &opts).unwrap();
    let mut certified = 0;
    for b in &r.branches {
        let Some(c) = b.certified() else { continue };
        certified += 1;
        // Every box meets the unit square widened by 0.05 (a link past the boundary ends some
        // way outside it, never far).
        for bx in &c.boxes {
            for v in bx.p.iter().chain(bx.q.iter()) {
                assert!(
                    v.inf() <= 1.05 && v.sup() >= -0.05,
                    "branch {}: box {:?} far outside the domains (ends {} / {})",
                    b.id(),
                    bx.p,
                    c.ends[0],
                    c.ends[1]
                );
            }
        }
    }
    assert!(certified >= 3, "{certified} certified branches");
}
