//! The whole marching pipeline on the example scenes, checked against closed forms: every branch
//! found, each traced once, every point on the known curve.

mod common;

use common::scenes::scene;
use ssitrace::march::branch::{Branch, BranchStatus, EndReason, Intersection};
use ssitrace::pipeline::{run_scene, RunOptions};

fn run(file: &str) -> Intersection {
    let scene = scene(file);
    let (outcome, _) = run_scene(&scene, &RunOptions::from_scene(&scene)).expect("runs");
    assert_eq!(outcome.stats.search.failed_starts, 0);
    assert_eq!(outcome.stats.search.undecided_leaves, 0);
    assert!(!outcome.stats.search.search_truncated);
    outcome.marched()
}

/// Smallest model-space distance between points of two branches.
fn gap(a: &Branch, b: &Branch) -> f64 {
    let mut best = f64::INFINITY;
    for p in &a.points {
        for q in &b.points {
            let d = (0..3)
                .map(|i| (p.xyz[i] - q.xyz[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            best = best.min(d);
        }
    }
    best
}

/// A closed loop: ends are `ClosedLoop`, the last point repeats the first, and no other point
/// comes back to the start (it was traced once, not one and a half times).
fn assert_closed_once(b: &Branch, step: f64) {
    assert_eq!(b.status, BranchStatus::Closed);
    assert_eq!(b.ends, [EndReason::ClosedLoop; 2]);
    let first = b.points.first().unwrap();
    let last = b.points.last().unwrap();
    assert_eq!(first.p, last.p);
    let n = b.points.len();
    for pt in &b.points[2..n - 2] {
        let d = (0..3)
            .map(|i| (pt.xyz[i] - first.xyz[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(d > 0.2 * step, "loop passes its start again: {d}");
    }
}

#[test]
fn fig7_three_nested_loops_none_strays() {
    let ix = run("wu_andrade_fig7.json");
    assert_eq!(ix.branches.len(), 3);
    // Each loop lies on exactly one of the ellipses 3u² + v² = 0.5, 0.6, 0.7.
    let mut levels = Vec::new();
    for b in &ix.branches {
        assert_closed_once(b, 0.05);
        let w = |p: &[f64; 2]| 3.0 * p[0] * p[0] + p[1] * p[1];
        let level = w(&b.points[0].p);
        for pt in &b.points {
            assert!(
                (w(&pt.p) - level).abs() < 1e-9,
                "strayed: {} vs {level}",
                w(&pt.p)
            );
            assert!((pt.p[0] - pt.q[0]).abs() < 1e-9 && (pt.p[1] - pt.q[1]).abs() < 1e-9);
            assert!(pt.xyz[2].abs() < 1e-9);
        }
        levels.push(level);
    }
    levels.sort_by(f64::total_cmp);
    for (got, want) in levels.iter().zip([0.5, 0.6, 0.7]) {
        assert!((got - want).abs() < 1e-9, "{levels:?}");
    }
    assert!(gap(&ix.branches[0], &ix.branches[1]) > 0.03);
    assert!(gap(&ix.branches[1], &ix.branches[2]) > 0.03);
}

#[test]
fn s31_s32_two_disjoint_loops_each_once() {
    let ix = run("two_loops_s31_s32.json");
    assert_eq!(ix.branches.len(), 2);
    for b in &ix.branches {
        assert_closed_once(b, 0.02);
        for pt in &b.points {
            // F = (u, v, 3u² + 3v²), G = (s, 5(s² + w²) − 1, w + 1).
            let [u, v] = pt.p;
            let [s, w] = pt.q;
            assert!((u - s).abs() < 1e-9);
            assert!((v - (5.0 * (s * s + w * w) - 1.0)).abs() < 1e-9);
            assert!((3.0 * (u * u + v * v) - (w + 1.0)).abs() < 1e-9);
        }
    }
    assert!(gap(&ix.branches[0], &ix.branches[1]) > 0.5);
}

#[test]
fn bicubic_pair_one_open_branch_boundary_to_boundary() {
    let ix = run("bicubic_transversal.json");
    assert_eq!(
        ix.branches.len(),
        1,
        "{:?}",
        ix.branches.iter().map(|b| b.ends).collect::<Vec<_>>()
    );
    let b = &ix.branches[0];
    assert_eq!(b.status, BranchStatus::Open);
    assert!(
        matches!(b.ends[0], EndReason::Boundary { .. })
            && matches!(b.ends[1], EndReason::Boundary { .. })
    );
    for pt in &b.points {
        assert!((pt.p[0] - 0.5).abs() < 1e-9, "σ = {}", pt.p[0]);
        assert!((pt.xyz[0] - 0.5).abs() < 1e-9);
    }
    // Exact landing on the boundary t = 0 and t = 1 of P.
    let mut ts = [b.points[0].p[1], b.points.last().unwrap().p[1]];
    ts.sort_by(f64::total_cmp);
    assert_eq!(ts, [0.0, 1.0]);
}

#[test]
fn rational_sphere_patch_against_plane_is_one_circle() {
    let ix = run("sphere_patch_plane.json");
    assert_eq!(ix.branches.len(), 1);
    let b = &ix.branches[0];
    assert_closed_once(b, 0.02);
    for pt in &b.points {
        let [x, y, z] = pt.xyz;
        assert!((x - 1.375).abs() < 1e-9);
        assert!((y * y + z * z - 141.0 / 256.0).abs() < 1e-9);
    }
}

#[test]
fn cylinder_lying_on_a_plane_reports_the_contact_line() {
    // A 90° arc of the cylinder x² + (z − ½)² = ¼ around its lowest line, extruded along y, on
    // the plane z = 0: they touch along x = z = 0. The middle weight is the interval around
    // √2/2, so the patch family holds the exact cylinder and the contact is real.
    use ssitrace::geometry::{Domain, RationalBezierPatch};
    use ssitrace::march::MarchOptions;
    use ssitrace::numeric::scalar::{interval, point};
    use ssitrace::search::start_points::SearchOptions;
    use ssitrace::topology::intersect::intersect;
    let (h, c) = (
        std::f64::consts::FRAC_1_SQRT_2,
        0.5 * std::f64::consts::FRAC_1_SQRT_2,
    );
    let mut pts = Vec::new();
    for (x, z) in [(-c, 0.5 - c), (0.0, 0.5 - h), (c, 0.5 - c)] {
        for y in [-1.0, 1.0] {
            pts.push([point(x), point(y), point(z)]);
        }
    }
    // The control data above are rounded; widen them so the family holds the exact cylinder.
    let widen = |x: inari::Interval| interval(x.inf() - 1e-15, x.sup() + 1e-15).unwrap();
    let pts: Vec<_> = pts.into_iter().map(|p| p.map(widen)).collect();
    let w = interval(h.next_down(), h.next_up()).unwrap();
    let weights = vec![point(1.0), point(1.0), w, w, point(1.0), point(1.0)];
    let p = RationalBezierPatch::new([2, 1], pts, Some(weights), Domain::UNIT).unwrap();
    let plane = [
        [-1.0, -2.0, 0.0],
        [-1.0, 2.0, 0.0],
        [1.0, -2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    let q = RationalBezierPatch::from_f64_points([1, 1], &plane, None, Domain::UNIT).unwrap();
    let out = intersect(&p, &q, &MarchOptions::default(), &SearchOptions::default());
    let ix = &out.intersection;
    // Never "no intersection": the contact is reported, as singular events along the line.
    assert!(
        !ix.events.is_empty(),
        "contact not reported: {:?}",
        out.stats
    );
    for e in &ix.events {
        assert!(
            e.xyz[0].abs() < 1e-4 && e.xyz[2].abs() < 1e-7,
            "event off the contact line: {:?}",
            e.xyz
        );
    }
    let ys: Vec<f64> = ix.events.iter().map(|e| e.xyz[1]).collect();
    let (lo, hi) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(*y), b.max(*y))
        });
    assert!(
        lo < -0.8 && hi > 0.8,
        "the events span the contact line: [{lo}, {hi}]"
    );
    println!(
        "contact line: {} events, {} branches, stats {:?}",
        ix.events.len(),
        ix.branches.len(),
        out.stats
    );
}
