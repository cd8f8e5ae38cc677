//! Issue 12: a marched branch of two points (a short arc across a corner of the domain) is
//! certified with both ends proven.
//!
//! The pair of soak seed 1 004 448 (`oracle_random`: a bicubic P and a biquadratic Q as height
//! fields over `[0,1]²`). Besides a long branch, the curve cuts the corner `σ = t = 0` in an arc
//! about 3e-4 long, which the marcher gives two points, one on each edge. The chain starts at a
//! marched point; with two, either start is an end, one half had nothing to walk, and that end
//! was reported unproven ("start at the last marched point"), as on 13 of the 20 000 soak pairs.
//! Now such a branch gets a third guide point between the two (Newton from their middle) and the
//! chain starts there, so both halves walk out of the domain.

mod common;

use common::surfaces::unit_height_patch as patch;
use ssitrace::{intersect, Method, Options};

/// Heights of P (bicubic, row `i` for `σ = i/3`).
const F: [f64; 16] = [
    -0.06005597535848173,
    -0.018804092349286483,
    -0.2052861449368144,
    -0.010606280685953706,
    -0.2634456535448688,
    0.014817326394037933,
    -0.23968818675441816,
    -0.25526903030648396,
    -0.09270274736232875,
    -0.28810023519146494,
    0.1717191885134436,
    0.2691715617177865,
    -0.13318214479949952,
    -0.2111965123698028,
    0.1826645445409339,
    0.1351211539610549,
];

/// Heights of Q (biquadratic, row `i` for `σ = i/2`).
const G: [f64; 9] = [
    -0.06012513602235853,
    0.10352191125384391,
    -0.16055711449463986,
    -0.23496302692362944,
    -0.11939350260134007,
    -0.11123659095559449,
    0.10478518745103166,
    -0.14109685856733445,
    -0.06339879367055962,
];

#[test]
fn two_point_branch_has_both_ends_proven() {
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&patch(3, &F), &patch(2, &G), &opts).unwrap();
    let short = r
        .branches
        .iter()
        .filter(|b| b.marched.points.len() == 2)
        .count();
    assert!(short > 0, "the two-point corner branch is gone");
    for b in &r.branches {
        let c = b.certified().expect("every branch certified");
        assert!(
            c.ends.iter().all(|e| e.kind() == "boundary"),
            "branch {} ({} marched points): ends {} / {}",
            b.id(),
            b.marched.points.len(),
            c.ends[0],
            c.ends[1]
        );
    }
}
