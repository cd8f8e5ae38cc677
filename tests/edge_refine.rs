//! Edges whose requested tolerance cannot be met (issue 11): the refinement of the coarse
//! curves stops, and the edge states what it proved and why that is above the request
//! ([`Shortfall`]), in the API and in the edge document.
//!
//! - A request below the certificate's own tolerance (sphere patch / plane, closed-form
//!   circle): [`Shortfall::Certificate`]; the curves aim a quarter above the certificate's
//!   floor, and the curve is still within its proven tolerance of the circle.
//! - A request the certificate meets but one degree-8 piece per fine span cannot (the bicubic
//!   pair's long links, asked for twice the certificate's floor, about 1e-14):
//!   [`Shortfall::FitStalled`], the stated
//!   level being the proven tolerance.
//! - The run's own request (1e-9): no shortfall.

mod common;

use common::scenes::scene;
use common::spline::samples;
use ssitrace::certify::CertifiedBranch;
use ssitrace::edge::{edge_from_certified_within, Edge, Shortfall};
use ssitrace::io::edge_json::edge_to_json;
use ssitrace::io::scene::Scene;
use ssitrace::pipeline::RunOptions;
use ssitrace::{intersect, Method, Options, SurfaceIntersection};

fn run(s: &Scene) -> SurfaceIntersection {
    let [p, q] = &s.surfaces;
    let opts = Options {
        method: Method::Validated,
        ..RunOptions::from_scene(s).options()
    };
    intersect(p, q, &opts).expect("runs")
}

fn cert(r: &SurfaceIntersection) -> &CertifiedBranch {
    assert_eq!(r.branches.len(), 1);
    r.branches[0].certified().expect("certified")
}

fn edge(s: &Scene, c: &CertifiedBranch, requested: f64) -> Edge {
    let [p, q] = &s.surfaces;
    edge_from_certified_within(p, q, c, 0, Some(requested)).expect("an edge")
}

/// Distance from `x` to the circle `x = 1.375`, `y² + z² = 141/256`.
fn off_circle(x: &[f64; 3]) -> f64 {
    let r = (141.0f64 / 256.0).sqrt();
    let rho = (x[1] * x[1] + x[2] * x[2]).sqrt();
    ((x[0] - 1.375).powi(2) + (rho - r).powi(2)).sqrt()
}

#[test]
fn a_request_below_the_certificate_is_a_certificate_shortfall() {
    let s = scene("sphere_patch_plane.json");
    let r = run(&s);
    let c = cert(&r);
    let requested = 0.5 * c.certified_tolerance;
    let e = edge(&s, c, requested);
    eprintln!(
        "below the certificate: {} control points, tolerance {:.3e}, {:?}",
        e.curve.points.len(),
        e.edge_tolerance,
        e.shortfall
    );
    assert_eq!(e.requested, Some(requested));
    assert!(e.edge_tolerance > requested);
    let Some(Shortfall::Certificate { floor }) = e.shortfall else {
        panic!("{:?}", e.shortfall)
    };
    assert!(floor >= c.certified_tolerance && floor > requested);
    // The curves aimed a quarter above the floor, and met that.
    assert!(e.edge_tolerance <= 1.25 * floor, "{:e}", e.edge_tolerance);
    for x in samples(&e.curve, 32).iter().map(|&t| e.curve.eval(t)) {
        assert!(off_circle(&x) <= e.edge_tolerance + 1e-13);
    }
    // The document states it.
    let v = edge_to_json(&e);
    assert_eq!(v["shortfall"]["reason"], "certificate");
    assert_eq!(v["requested_tolerance"].as_f64(), Some(requested));
    assert_eq!(v["shortfall"]["floor"].as_f64(), Some(floor));
}

#[test]
fn a_fit_that_cannot_reach_the_request_stops_and_says_so() {
    let s = scene("bicubic_transversal.json");
    let r = run(&s);
    let c = cert(&r);
    // Twice the certificate's floor (its tolerance, or the cuts' share where that is higher).
    let floor = match edge(&s, c, c.certified_tolerance).shortfall {
        Some(Shortfall::Certificate { floor }) => floor,
        _ => c.certified_tolerance,
    };
    let requested = 2.0 * floor;
    let e = edge(&s, c, requested);
    eprintln!(
        "below the fit's reach: {} control points ({} links), tolerance {:.3e}, {:?}",
        e.curve.points.len(),
        e.links,
        e.edge_tolerance,
        e.shortfall
    );
    assert!(e.edge_tolerance > requested);
    let Some(Shortfall::FitStalled { spans, level }) = e.shortfall else {
        panic!("{:?}", e.shortfall)
    };
    // Fine spans: two per link, four in links that stalled with two (`FINE_PER_LINK`,
    // `DENSE_FINE_PER_LINK` in src/edge/build.rs).
    assert!(spans >= 1 && spans <= 4 * e.links);
    // The level stated is what the worst span proves: the edge's tolerance (the other bounds
    // are the certificate's, far lower).
    assert!(level > requested && level <= e.edge_tolerance);
    assert!(level >= 0.5 * e.edge_tolerance, "{level:e}");
    // At most one degree-8 piece per fine span (plus its end points): refinement did not run
    // on.
    assert!(e.curve.points.len() <= 32 * e.links + 1);
    let v = edge_to_json(&e);
    assert_eq!(v["shortfall"]["reason"], "fit_stalled");
    assert_eq!(v["shortfall"]["spans"].as_u64(), Some(spans as u64));
}

#[test]
fn the_runs_own_request_is_met_without_a_shortfall() {
    let s = scene("bicubic_transversal.json");
    let r = run(&s);
    let c = cert(&r);
    let requested = r.options.required_tolerance;
    let e = edge(&s, c, requested);
    assert!(e.edge_tolerance <= requested, "{:e}", e.edge_tolerance);
    assert_eq!(e.shortfall, None);
    assert!(edge_to_json(&e)["shortfall"].is_null());
}

#[test]
fn a_request_at_the_certificate_ends_close_to_it() {
    // Aimed at exactly the floor, the coarse curves' bounds had no room: every region stalled
    // and the edge ended at 1.49x the request (6.35e-10 for 4.25e-10); aimed 2% above, it
    // ends within a few per cent of the request.
    let s = scene("sphere_patch_plane.json");
    let r = run(&s);
    let c = cert(&r);
    for factor in [1.0, 1.02, 1.05] {
        let requested = factor * c.certified_tolerance;
        let e = edge(&s, c, requested);
        eprintln!(
            "at {factor} x the certificate: {} control points, tolerance {:.3e} ({:.3} x the \
             request), {:?}",
            e.curve.points.len(),
            e.edge_tolerance,
            e.edge_tolerance / requested,
            e.shortfall
        );
        assert!(
            e.edge_tolerance <= 1.1 * requested,
            "{factor}: {:e}",
            e.edge_tolerance
        );
        // A shortfall is stated exactly when the request is missed.
        assert_eq!(e.shortfall.is_some(), e.edge_tolerance > requested);
        for x in samples(&e.curve, 32).iter().map(|&t| e.curve.eval(t)) {
            assert!(off_circle(&x) <= e.edge_tolerance + 1e-13);
        }
    }
}

#[test]
fn a_request_five_per_cent_above_the_certificate_is_met() {
    // Each branch of two scenes asked for 1.05x its own certificate: the stalls depend on the
    // aim, and aimed at the request some regions stalled above it (Viviani's arcs at 1.09x,
    // Fig. 7's third loop at 1.06x); a missed request is aimed again at 2% above the floor,
    // and the closer edge kept.
    for name in ["viviani.json", "two_loops_s31_s32.json"] {
        let s = scene(name);
        let [p, q] = &s.surfaces;
        let r = run(&s);
        assert!(!r.branches.is_empty(), "{name}");
        for (i, b) in r.branches.iter().enumerate() {
            let c = b.certified().expect("certified");
            let requested = 1.05 * c.certified_tolerance;
            let e = edge_from_certified_within(p, q, c, i, Some(requested)).expect("an edge");
            eprintln!(
                "{name} branch {i}: {} control points, tolerance {:.3e} ({:.3} x the request)",
                e.curve.points.len(),
                e.edge_tolerance,
                e.edge_tolerance / requested
            );
            assert!(
                e.edge_tolerance <= requested,
                "{name} {i}: {:e} > {requested:e}",
                e.edge_tolerance
            );
            assert_eq!(e.shortfall, None);
        }
    }
}
