//! No missed branches (issue #5): small interior loops are found by the start-point search with
//! its rigorous loop-exclusion test, down to a loop of radius 1e-6 in a unit-size model, and the
//! search says whether it settled every region or which boxes it left undecided; the marcher
//! (default options, step 0.05) closes each of those loops once. At r = 1e-8 the plane
//! z = 1 − r² rounds to 1 − 2⁻⁵³ and the search honestly reports undecided boxes holding the
//! circle. Close loops (0.002 apart, step 0.05) are each traced once.
//!
//! Each case checks against closed forms: the paraboloid z = 1 − x² − y² (an exact biquadratic
//! Bézier patch) cut by the plane z = c is the circle of radius √(1 − c) about the z axis.

mod common;

use common::surfaces::{height_field, SQUARE};
use ssitrace::geometry::piece::Piece;
use ssitrace::geometry::RationalBezierPatch;
use ssitrace::march::branch::{Branch, BranchStatus};
use ssitrace::march::MarchOptions;
use ssitrace::search::loop_exclusion::{prove_loop_free, LoopFree};
use ssitrace::search::start_points::{find_start_points, SearchOptions, SearchReport};
use ssitrace::topology::intersect::intersect;

fn patch(terms: Vec<(u32, u32, f64)>) -> RationalBezierPatch {
    height_field(SQUARE, terms)
}

/// z = 1 − x² − y² over [−1, 1]² (biquadratic).
fn bump() -> RationalBezierPatch {
    patch(vec![(0, 0, 1.0), (2, 0, -1.0), (0, 2, -1.0)])
}

/// The plane z = c over [−1, 1]² (bilinear).
fn plane(c: f64) -> RationalBezierPatch {
    patch(vec![(0, 0, c), (1, 1, 0.0)])
}

/// Smallest and largest distance of a branch's points from the z axis.
fn radius_range(b: &Branch) -> (f64, f64) {
    b.points
        .iter()
        .map(|p| p.xyz[0].hypot(p.xyz[1]))
        .fold((f64::INFINITY, 0.0), |(lo, hi), r| (lo.min(r), hi.max(r)))
}

/// Whether some undecided region of the report contains the circle of radius `r` about the
/// origin in P's parameters (its box reaches both inside and outside the circle).
fn undecided_box_holds_circle(report: &SearchReport, r: f64) -> bool {
    report.undecided_regions.iter().any(|reg| {
        let [x, y] = reg.p;
        let near = |v: f64, lo: f64, hi: f64| v.clamp(lo, hi);
        let dmin = near(0.0, x[0], x[1]).hypot(near(0.0, y[0], y[1]));
        let dmax = x[0].abs().max(x[1].abs()).hypot(y[0].abs().max(y[1].abs()));
        dmin <= r && r <= dmax
    })
}

/// Relative radius error of the start points, and how many of the four quadrants about the
/// loop's centre they reach.
fn starts_on_circle(report: &SearchReport, r: f64) -> (f64, usize) {
    let starts: Vec<[f64; 4]> = report
        .interior
        .iter()
        .chain(&report.boundary)
        .map(|s| s.params)
        .collect();
    let err = starts
        .iter()
        .map(|x| (x[0].hypot(x[1]) - r).abs() / r)
        .fold(0.0, f64::max);
    let mut quadrants = [false; 4];
    for x in &starts {
        quadrants[usize::from(x[0] >= 0.0) + 2 * usize::from(x[1] >= 0.0)] = true;
    }
    (err, quadrants.iter().filter(|&&q| q).count())
}

#[test]
fn loops_of_radius_1e2_1e4_1e6_are_found_or_boxed() {
    let bump = bump();
    println!(
        "radius  complete pairs disjoint loop-free undecided starts start-err quadrants \
         marched   points radius-err search-ms"
    );
    for r in [1e-2f64, 1e-4, 1e-6, 1e-8] {
        let c = 1.0 - r * r;
        // 1 − c is exact in f64 (Sterbenz), so the true radius of the patches used is:
        let exact_r = (1.0 - c).sqrt();
        let q = plane(c);
        let t0 = std::time::Instant::now();
        let report = find_start_points(&bump, &q, &SearchOptions::default());
        let ms = 1e3 * t0.elapsed().as_secs_f64();
        let (start_err, quadrants) = starts_on_circle(&report, exact_r);
        // Default options (step L = 0.05, tolerance 1e-10) at every radius: the marcher's steps
        // follow the curvature, and its Newton stops on corrections below the tolerance (or the
        // f64 position noise, ε/2r here), not on the residual alone (the normals meet at an
        // angle of about 2r, so a residual τ would only hold the curve to τ / 2r).
        let march = MarchOptions::default();
        let out = intersect(&bump, &q, &march, &SearchOptions::default());
        let closed: Vec<&Branch> = out
            .intersection
            .branches
            .iter()
            .filter(|b| b.status == BranchStatus::Closed)
            .collect();
        let err = closed
            .iter()
            .map(|b| {
                let (lo, hi) = radius_range(b);
                ((lo - exact_r).abs().max((hi - exact_r).abs())) / exact_r
            })
            .fold(f64::NAN, f64::max);
        let marched = match out.intersection.branches.first() {
            Some(b) => format!("{:?}", b.ends[0]),
            None => "none".into(),
        };
        println!(
            "{r:<6.0e}  {:<8} {:<5} {:<8} {:<9} {:<9} {:<6} {start_err:<9.1e} {quadrants:<9} \
             {marched:<9} {:<6} {err:<10.1e} {ms:.1}",
            report.complete,
            report.pairs,
            report.disjoint_pairs,
            report.loop_free_pairs,
            report.undecided_regions.len(),
            report.boundary.len() + report.interior.len(),
            closed.iter().map(|b| b.points.len()).sum::<usize>(),
        );
        if report.complete {
            // Settled everywhere: the loop must have been found. Its start points (proven
            // crossings of pair faces, Newton-polished) lie on the circle all around it.
            assert!(report.undecided_regions.is_empty());
            assert!(
                start_err < 1e-3,
                "r = {r}: start points off the circle by {start_err}"
            );
            assert!(
                quadrants >= 3,
                "r = {r}: starts in {quadrants} quadrants only"
            );
            // Marched: one closed branch on the circle, traced once, at every radius (the
            // marcher's steps are capped by the radius of curvature, ~r here, not by L).
            assert_eq!(closed.len(), 1, "r = {r}: {:?}", out.stats);
            assert_eq!(out.intersection.branches.len(), 1);
            assert!(err < 1e-3, "r = {r}: relative radius error {err}");
            // A full turn in angle steps of about L = 0.05 rad: ~2π/L points, not thousands.
            let pts = closed[0].points.len();
            assert!((100..=400).contains(&pts), "r = {r}: {pts} points");
        } else {
            // Not settled: the loop is either found anyway, or an undecided box holds it.
            println!("  r = {r}: search not complete; checking the undecided boxes");
            let found = start_err < 1e-3 && quadrants >= 3;
            assert!(
                found || undecided_box_holds_circle(&report, exact_r),
                "r = {r}: loop neither found nor inside an undecided region"
            );
        }
    }
}

#[test]
fn two_loops_0_002_apart_are_both_found() {
    // z = −g₁·g₂ with gᵢ = (x ∓ c)² + y² − ρ²: a bump with two close peaks whose cut by z = 0
    // is exactly the two circles of radius ρ = 0.2 about (±c, 0), c = 0.201: 0.002 apart.
    // Expanded: g₁g₂ = (w + k)² − 4c²x², w = x² + y², k = c² − ρ².
    let (rho, c) = (0.2f64, 0.201f64);
    let k = c * c - rho * rho;
    let p = patch(vec![
        (4, 0, -1.0),
        (2, 2, -2.0),
        (0, 4, -1.0),
        (2, 0, -(2.0 * k - 4.0 * c * c)),
        (0, 2, -2.0 * k),
        (0, 0, -k * k),
    ]);
    let q = plane(0.0);
    let t0 = std::time::Instant::now();
    let report = find_start_points(&p, &q, &SearchOptions::default());
    println!(
        "two loops 0.002 apart: complete {}, pairs {}, loop-free {}, undecided {}, starts {}, \
         {:.1} ms",
        report.complete,
        report.pairs,
        report.loop_free_pairs,
        report.undecided_regions.len(),
        report.interior.len() + report.boundary.len(),
        1e3 * t0.elapsed().as_secs_f64()
    );
    assert!(
        report.complete,
        "{} undecided regions",
        report.undecided_regions.len()
    );
    // Start points on both circles.
    let dist = |x: f64, y: f64, cx: f64| (x - cx).hypot(y);
    for cx in [-c, c] {
        assert!(
            report
                .interior
                .iter()
                .any(|s| (dist(s.params[0], s.params[1], cx) - rho).abs() < 1e-6),
            "no start on the circle about ({cx}, 0)"
        );
    }
    // Both traced as closed loops, each on its own circle.
    let march = MarchOptions {
        step: 0.02,
        ..MarchOptions::default()
    };
    let out = intersect(&p, &q, &march, &SearchOptions::default());
    let closed: Vec<&Branch> = out
        .intersection
        .branches
        .iter()
        .filter(|b| b.status == BranchStatus::Closed)
        .collect();
    assert_eq!(closed.len(), 2, "{:?}", out.stats);
    let mut centres = Vec::new();
    for b in closed {
        let cx = if b.points[0].xyz[0] > 0.0 { c } else { -c };
        let worst = b
            .points
            .iter()
            .map(|pt| (dist(pt.xyz[0], pt.xyz[1], cx) - rho).abs())
            .fold(0.0, f64::max);
        println!(
            "loop about ({cx}, 0): {} points, worst radius error {worst:.1e}",
            b.points.len()
        );
        assert!(worst < 1e-6);
        centres.push(cx);
    }
    centres.sort_by(f64::total_cmp);
    assert_eq!(centres, vec![-c, c]);
}

#[test]
fn exclusion_test_never_clears_a_pair_holding_a_loop() {
    // The bump against z = 0.91: a loop of radius 0.3 about the origin, held by the whole
    // pieces (the first halving cuts through it). Both orders of the surfaces.
    let (p, q) = (bump(), plane(0.91));
    let (a, b) = (Piece::whole(&p), Piece::whole(&q));
    assert!(prove_loop_free(&p, &a, &q, &b).is_none());
    assert!(prove_loop_free(&q, &b, &p, &a).is_none());
    // A loop away from the split lines: 1 − 0.13 + 0.6x + 0.4y − x² − y² = 0.99 is
    // (x − 0.3)² + (y − 0.2)² = 0.01, normalised centre (0.65, 0.6), radius 0.05. Every piece
    // pair on the way down to [0.5, 0.75]² holds it and must not be cleared.
    let p = patch(vec![
        (0, 0, 1.0 - 0.13),
        (2, 0, -1.0),
        (0, 2, -1.0),
        (1, 0, 0.6),
        (0, 1, 0.4),
    ]);
    let q = plane(0.99);
    let (mut a, mut b) = (Piece::whole(&p), Piece::whole(&q));
    let mut tried = 0;
    for (dir, half) in [(0, 1), (1, 1), (0, 0), (1, 0), (9, 9)] {
        for (x, y) in [(&a, &b), (&a, &Piece::whole(&q))] {
            assert!(
                prove_loop_free(&p, x, &q, y).is_none(),
                "{:?} {:?}",
                x.s,
                x.r
            );
            assert!(prove_loop_free(&q, y, &p, x).is_none());
            tried += 1;
        }
        if dir > 1 {
            break;
        }
        a = a.split(dir)[half].clone();
        b = b.split(dir)[half].clone();
    }
    assert_eq!((a.s, a.r), ([0.5, 0.75], [0.5, 0.75]));
    // Whereas a pair crossed by an arc only (x ∈ [0.375, 0.4375] ∋ 0.4, y ∋ 0.2) is cleared.
    for (dir, half) in [(0, 1), (1, 0), (0, 1), (1, 1), (0, 0), (1, 1), (1, 0)] {
        a = a.split(dir)[half].clone();
        b = b.split(dir)[half].clone();
    }
    assert_eq!((a.s, a.r), ([0.6875, 0.71875], [0.59375, 0.609375]));
    assert!(prove_loop_free(&p, &a, &q, &b).is_some());
    println!("pairs holding a loop tried: {tried}, none cleared");
}

#[test]
fn exclusion_test_clears_a_monotone_pair() {
    // z = 0 against the tilted plane z = 0.3x − 0.2y + 0.05: a straight line, no loop possible.
    let flat = plane(0.0);
    let tilted = patch(vec![(1, 0, 0.3), (0, 1, -0.2), (0, 0, 0.05)]);
    let proof = prove_loop_free(&flat, &Piece::whole(&flat), &tilted, &Piece::whole(&tilted))
        .expect("monotone pair cleared");
    // The intersection line has direction (0.2, 0.3, 0)/|·|: d must not be orthogonal to it.
    let LoopFree::Along(d) = proof else {
        panic!("a model direction: {proof:?}")
    };
    assert!((0.2 * d[0] + 0.3 * d[1]).abs() > 0.05, "{d:?}");
    let report = find_start_points(&flat, &tilted, &SearchOptions::default());
    assert!(report.complete && report.loop_free_pairs >= 1);
    assert_eq!(report.boundary.len(), 2);
}

#[test]
fn touching_point_is_reported_as_undecided_not_dropped() {
    // The bump touches the plane z = 1 at its apex only: no exclusion test can settle a
    // tangency, so the search must say it is not complete and name a box holding the apex.
    let report = find_start_points(&bump(), &plane(1.0), &SearchOptions::default());
    println!(
        "touching: complete {}, pairs {}, undecided regions {}, starts {}",
        report.complete,
        report.pairs,
        report.undecided_regions.len(),
        report.interior.len()
    );
    assert!(!report.complete);
    let holds_apex =
        |b: &[[f64; 2]; 2]| b[0][0] <= 0.0 && 0.0 <= b[0][1] && b[1][0] <= 0.0 && 0.0 <= b[1][1];
    assert!(report
        .undecided_regions
        .iter()
        .any(|r| holds_apex(&r.p) && holds_apex(&r.q)));
    // Every undecided region is small and near the apex (the rest was settled).
    for r in &report.undecided_regions {
        let far = r.p[0][0]
            .abs()
            .min(r.p[0][1].abs())
            .max(r.p[1][0].abs().min(r.p[1][1].abs()));
        assert!(far < 1e-3, "undecided region away from the apex: {r:?}");
    }
}

#[test]
fn concentric_loops_0_002_apart_are_each_traced_once_with_the_default_step() {
    // z = K(w − a)(w − b), w = x² + y², cut by z = 0: exactly the concentric circles of radius
    // 0.3 and 0.302 (a = 0.3², b = 0.302²), 0.002 apart, far closer than the step L = 0.05
    // (chords ≈ 0.015 long). K = 100 makes the surfaces meet at a slope of about 0.07.
    let (r1, r2, k) = (0.3f64, 0.302f64, 100.0);
    let (a, b) = (r1 * r1, r2 * r2);
    let p = patch(vec![
        (4, 0, k),
        (2, 2, 2.0 * k),
        (0, 4, k),
        (2, 0, -k * (a + b)),
        (0, 2, -k * (a + b)),
        (0, 0, k * a * b),
    ]);
    let q = plane(0.0);
    let out = intersect(&p, &q, &MarchOptions::default(), &SearchOptions::default());
    println!(
        "concentric loops: search complete {} ({} undecided regions), starts {}, skipped {}, branches {}",
        out.stats.search_complete,
        out.stats.undecided_regions.len(),
        out.stats.interior_candidates + out.stats.boundary_starts,
        out.stats.skipped_covered,
        out.intersection.branches.len()
    );
    // Between the circles z has a ring of minima (w = (a + b)/2, z = −K(b − a)²/4 < 0) where the
    // normals are parallel: the search may leave boxes there undecided, but only there.
    for reg in &out.stats.undecided_regions {
        let [x, y] = reg.p;
        let near = |lo: f64, hi: f64| 0.0f64.clamp(lo, hi);
        let dmin = near(x[0], x[1]).hypot(near(y[0], y[1]));
        let dmax = x[0].abs().max(x[1].abs()).hypot(y[0].abs().max(y[1].abs()));
        assert!(
            dmin <= r2 + 0.01 && dmax >= r1 - 0.01,
            "undecided box away from the annulus: {reg:?}"
        );
    }
    assert_eq!(
        out.intersection.branches.len(),
        2,
        "skipped {} of {} starts",
        out.stats.skipped_covered,
        out.stats.interior_candidates
    );
    let mut found = Vec::new();
    for br in &out.intersection.branches {
        assert_eq!(br.status, BranchStatus::Closed);
        let (lo, hi) = radius_range(br);
        let r = if (lo - r1).abs() < 1e-3 { r1 } else { r2 };
        let worst = (lo - r).abs().max((hi - r).abs());
        println!(
            "  loop r = {r}: {} points, radius range [{lo:.12}, {hi:.12}], worst error {worst:.1e}",
            br.points.len()
        );
        assert!(worst < 1e-8, "branch off its circle: [{lo}, {hi}]");
        // Once round: ~2π/L points (about 127), not twice that.
        assert!((100..=200).contains(&br.points.len()));
        found.push(r);
    }
    found.sort_by(f64::total_cmp);
    assert_eq!(found, vec![r1, r2], "each circle traced exactly once");
}
