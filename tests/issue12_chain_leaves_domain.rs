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
//!
//! Since then `intersect` traces the arm such a jump leaves uncertified again with a finer step
//! and drops the jumping branches as duplicates (`solve/repair.rs`), so its result no longer holds
//! them: the walker is tested on the marcher's branches certified one by one, and the whole run
//! must give the two true curves, each certified from boundary to boundary.

mod common;

use common::near_crossing::{patch, F, G};
use ssitrace::solve::certify_marched_branch;
use ssitrace::{intersect, Method, Options};

#[test]
fn lost_half_stops_at_the_domain() {
    let (p, q) = (patch(&F), patch(&G));
    let march = Options {
        method: Method::March,
        ..Options::default()
    };
    let validated = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let marched = intersect(&p, &q, &march).unwrap();
    let mut certified = 0;
    for b in &marched.branches {
        let cert = certify_marched_branch(&p, &q, &b.marched, &validated);
        let Ok(c) = &cert.result else { continue };
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

/// The whole run: the two curves (left edge to top edge, bottom edge to right edge), each one
/// branch certified from boundary to boundary, the jumping branches traced again and dropped.
#[test]
fn the_two_curves_are_certified_once_each() {
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&patch(&F), &patch(&G), &opts).unwrap();
    assert_eq!(r.branches.len(), 2);
    for b in &r.branches {
        let c = b.certified().expect("certified");
        assert!(
            c.ends.iter().all(|e| e.kind() == "boundary"),
            "ends {} / {}",
            c.ends[0],
            c.ends[1]
        );
    }
    let stats = r.stats.certify.as_ref().expect("certified run");
    assert!(stats.retraced_branches >= 1 && stats.duplicate_branches >= 2);
}
