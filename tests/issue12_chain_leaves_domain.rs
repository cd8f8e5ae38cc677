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
//! and drops the jumping branches as duplicates (`solve/repair.rs`), and the marcher refuses a
//! step that lands on a curve running the other way along `N^P × N^Q` (`march/trace.rs`,
//! `jumped`): here the two curves run opposite ways past each other, so it no longer jumps at
//! all. The walker is tested on the jumping branch rebuilt from the two curves' marched points
//! (the left edge's curve up to where they pass closest, then the other on to the right edge;
//! its chain now ends where the curves pass closest, "close branches"): its boxes must stay by
//! the domains. The whole run must give the two true curves, each certified from boundary to
//! boundary.

mod common;

use common::near_crossing::{patch, F, G};
use ssitrace::march::branch::{Branch, BranchStatus, CurvePoint, EndReason};
use ssitrace::solve::certify_marched_branch;
use ssitrace::{intersect, Method, Options};

/// The branch the marcher used to trace: from the left edge along its curve to where the two
/// curves pass closest, then along the other curve to the right edge.
fn jumping_branch(branches: &[&Branch]) -> Branch {
    let touching = |b: &Branch, side: f64| {
        [b.points[0], *b.points.last().unwrap()]
            .iter()
            .position(|c| (c.p[0] - side).abs() < 1e-9)
    };
    let (left, at_left) = branches
        .iter()
        .find_map(|b| touching(b, 0.0).map(|k| (*b, k)))
        .expect("a curve from the left edge");
    let (right, at_right) = branches
        .iter()
        .find_map(|b| touching(b, 1.0).map(|k| (*b, k)))
        .expect("a curve to the right edge");
    let mut first: Vec<CurvePoint> = left.points.clone();
    if at_left == 1 {
        first.reverse();
    }
    let mut second: Vec<CurvePoint> = right.points.clone();
    if at_right == 0 {
        second.reverse();
    }
    let d = |a: &CurvePoint, b: &CurvePoint| (a.p[0] - b.p[0]).hypot(a.p[1] - b.p[1]);
    let (i, k) = (0..first.len())
        .flat_map(|i| (0..second.len()).map(move |k| (i, k)))
        .min_by(|x, y| d(&first[x.0], &second[x.1]).total_cmp(&d(&first[y.0], &second[y.1])))
        .unwrap();
    let mut points = first[..=i].to_vec();
    points.extend_from_slice(&second[k + 1..]);
    Branch {
        id: 0,
        status: BranchStatus::Open,
        ends: [
            EndReason::Boundary { surface: 0 },
            EndReason::Boundary { surface: 0 },
        ],
        points,
    }
}

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
    let curves: Vec<&Branch> = marched.branches.iter().map(|b| &b.marched).collect();
    let mut certified = 0;
    let jumping = jumping_branch(&curves);
    for b in curves.into_iter().chain([&jumping]) {
        let cert = certify_marched_branch(&p, &q, b, &validated);
        let Ok(c) = &cert.result else { continue };
        certified += 1;
        // Every box meets the unit square widened by 0.05 (a link past the boundary ends some
        // way outside it, never far).
        for bx in &c.boxes {
            for v in bx.p.iter().chain(bx.q.iter()) {
                assert!(
                    v.inf() <= 1.05 && v.sup() >= -0.05,
                    "branch of {} points: box {:?} far outside the domains (ends {} / {})",
                    b.points.len(),
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
/// branch marched once and certified from boundary to boundary.
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
    // Each marched once: nothing to trace again, no copy to drop.
    let stats = r.stats.certify.as_ref().expect("certified run");
    assert_eq!((stats.retraced_branches, stats.duplicate_branches), (0, 0));
}
