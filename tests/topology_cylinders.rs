//! Two unit cylinders crossing at right angles, with BOTH tangent points inside one patch pair
//! (`scenes/cylinders_full.json`).
//!
//! P is `x² + z² = 1` along y: `(x, z) = (1 − σ², 2σ)/(1 + σ²)`, `y = t`, σ ∈ [−1.5, 1.5]
//! (225° about +x, so x ≥ −5/13), t ∈ [−1.2, 1.2]. Q is `y² + z² = 1` along x:
//! `(y, z) = (1 − s², 2s)/(1 + s²)`, `x = t`, s ∈ [−1.3, 1.3] (about 209° about +y, so
//! y ≥ −0.69/2.69), t ∈ [−1.2, 1.2]. Both need a weight `1 + σ²` whose quadratic Bernstein
//! coefficients are not all positive, so the conversion elevates both to degree 3.
//!
//! The intersection is the two ellipses `(cos φ, ±cos φ, sin φ)` (planes x = ±y) meeting at the
//! branch points (0, 0, ±1). Inside the patches that is exactly:
//! - one arc between the two nodes: x = y > 0 (through (1, 1, 0));
//! - x = y < 0, cut at y = −0.69/2.69 by Q's boundary: two arcs node → Q's boundary;
//! - x = −y > 0, cut at y = −0.69/2.69 by Q's boundary: two arcs node → Q's boundary;
//! - x = −y < 0, cut at x = −5/13 by P's boundary: two arcs node → P's boundary.
//!
//! Seven arcs in all, four leaving each node. (Four arcs between the nodes would need each patch
//! to cover the whole circle: the arcs with x < 0 reach x = −1 and those with x > 0 reach x = 1.)

mod common;

use ssitrace::certify::CertifiedEnd;
use ssitrace::io::scene::{Method, Scene};
use ssitrace::march::branch::{Branch, BranchStatus, CurvePoint, EndReason};
use ssitrace::march::MarchOptions;
use ssitrace::pair::contact_quadratic::ContactCase;
use ssitrace::pipeline::{run, RunOptions};
use ssitrace::search::start_points::SearchOptions;
use ssitrace::topology::intersect::intersect;
use std::f64::consts::PI;
use std::time::Instant;

const STEP: f64 = 0.05;
/// x on P's boundary σ = ±1.5: (1 − 2.25)/(1 + 2.25).
const X_MIN: f64 = -5.0 / 13.0;
/// y on Q's boundary s = ±1.3: (1 − 1.69)/(1 + 1.69).
const Y_MIN: f64 = -0.69 / 2.69;

fn scene() -> Scene {
    common::scenes::scene("cylinders_full.json")
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// Distance from `c` to the segment `ab`.
fn seg_dist(c: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab: [f64; 3] = std::array::from_fn(|i| b[i] - a[i]);
    let ac: [f64; 3] = std::array::from_fn(|i| c[i] - a[i]);
    let l2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if l2 > 0.0 {
        ((0..3).map(|i| ab[i] * ac[i]).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let foot: [f64; 3] = std::array::from_fn(|i| a[i] + t * ab[i]);
    dist(c, &foot)
}

/// Distance from `c` to the polyline of a branch.
fn branch_dist(b: &Branch, c: &[f64; 3]) -> f64 {
    b.points
        .windows(2)
        .map(|w| seg_dist(c, &w[0].xyz, &w[1].xyz))
        .fold(f64::INFINITY, f64::min)
}

/// Dense samples of the two ellipses inside both patches (a small margin off the boundaries).
fn ellipse_samples(n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for k in 0..n {
        let phi = 2.0 * PI * k as f64 / n as f64;
        for sign in [1.0, -1.0] {
            let p = [phi.cos(), sign * phi.cos(), phi.sin()];
            if p[0] >= X_MIN + 1e-3 && p[1] >= Y_MIN + 1e-3 {
                out.push(p);
            }
        }
    }
    out
}

/// Which of the seven arcs a traced branch is, by the signs of x and y at its middle point.
fn quadrant(b: &Branch) -> (bool, bool) {
    let m = &b.points[b.points.len() / 2].xyz;
    (m[0] > 0.0, m[1] > 0.0)
}

fn describe_end(e: &EndReason) -> &'static str {
    match e {
        EndReason::Boundary { surface: 0 } => "P-boundary",
        EndReason::Boundary { .. } => "Q-boundary",
        EndReason::Singular => "node",
        EndReason::ClosedLoop => "loop",
        EndReason::NewtonFailed => "newton-failed",
        EndReason::PointLimit => "point-limit",
        EndReason::OwnPath => "own-path",
    }
}

#[test]
fn both_tangent_points_are_branch_points_with_four_arcs_each_traced_once() {
    let scene = scene();
    let [p, q] = &scene.surfaces;
    // Least Bernstein coefficient of 1 + σ² on [−a, a] in degree 3: 1 − a²/3 (0.25 for P,
    // 0.437 for Q); in degree 2 it is 1 − a² < 0.
    assert_eq!(
        p.degree(),
        [3, 1],
        "P's weight 1 + σ² on [−1.5, 1.5] needs degree 3"
    );
    assert_eq!(
        q.degree(),
        [3, 1],
        "Q's weight 1 + s² on [−1.3, 1.3] needs degree 3"
    );
    let march = MarchOptions {
        step: STEP,
        ..MarchOptions::default()
    };
    let t0 = Instant::now();
    let out = intersect(p, q, &march, &SearchOptions::default());
    let seconds = t0.elapsed().as_secs_f64();
    let branches = &out.intersection.branches;

    println!("Crossing cylinders, both tangent points (step {STEP}): {seconds:.2} s");
    println!(
        "{:>3} {:>6} {:>11} {:>11} {:>8} {:>7} {:>10}",
        "id", "points", "start", "end", "x>0,y>0", "length", "status"
    );
    for b in branches {
        let len: f64 = b
            .points
            .windows(2)
            .map(|w| dist(&w[0].xyz, &w[1].xyz))
            .sum();
        let (xp, yp) = quadrant(b);
        println!(
            "{:>3} {:>6} {:>11} {:>11} {:>8} {:>7.3} {:>10?}",
            b.id,
            b.points.len(),
            describe_end(&b.ends[0]),
            describe_end(&b.ends[1]),
            format!("{},{}", xp as u8, yp as u8),
            len,
            b.status
        );
    }
    for n in &out.nodes {
        println!(
            "node ({:+.2e}, {:+.2e}, {:+.9}) {:?} Δ = {:.3e}, exits {}",
            n.xyz[0],
            n.xyz[1],
            n.xyz[2],
            n.case,
            n.discriminant,
            n.exits.len()
        );
    }

    // Two nodes, at (0, 0, ±1), each a branch point with four exits.
    assert_eq!(out.nodes.len(), 2);
    for z in [1.0, -1.0] {
        let n = out
            .nodes
            .iter()
            .find(|n| dist(&n.xyz, &[0.0, 0.0, z]) < 1e-6)
            .unwrap_or_else(|| panic!("no node at (0, 0, {z})"));
        assert!(n.located);
        assert_eq!(n.case, ContactCase::BranchPoint);
        assert_eq!(n.exits.len(), 4);
    }

    // The search leaves undecided only tiny boxes at the two tangent points, which are
    // (σ, t) = (±1, 0) on P and (s, t) = (±1, 0) on Q: nothing can hide elsewhere.
    let st = &out.stats;
    let off_node = |b: &[[f64; 2]; 2]| {
        let far_s = b[0]
            .iter()
            .map(|x| (x.abs() - 1.0).abs())
            .fold(0.0, f64::max);
        let far_t = b[1].iter().map(|x| x.abs()).fold(0.0, f64::max);
        far_s.max(far_t)
    };
    let spread = st
        .undecided_regions
        .iter()
        .map(|r| off_node(&r.p).max(off_node(&r.q)))
        .fold(0.0, f64::max);
    println!(
        "search: {:.2} s, complete {}, boundary starts {}, interior candidates {}, skipped {}, \
         undecided regions {} (all within {spread:.1e} of the tangent points in parameters)",
        st.search_seconds,
        st.search_complete,
        st.boundary_starts,
        st.interior_candidates,
        st.skipped_covered,
        st.undecided_regions.len()
    );
    assert_eq!(st.failed_starts, 0);
    assert!(!st.search_truncated);
    assert!(spread < 1e-3);

    // Every traced point on both cylinders and on one of the planes x = ±y. Near the nodes x and
    // y are both small, so the plane test is |x² − y²| (the product of the two plane distances).
    let mut worst_cyl = 0.0f64;
    let mut worst_plane = 0.0f64;
    for pt in branches.iter().flat_map(|b| &b.points) {
        let [x, y, z] = pt.xyz;
        worst_cyl = worst_cyl
            .max((x * x + z * z - 1.0).abs())
            .max((y * y + z * z - 1.0).abs());
        let plane = (x - y).abs().min((x + y).abs());
        let far_from_nodes = (x.abs() + y.abs()) > STEP;
        worst_plane = worst_plane.max(if far_from_nodes {
            plane
        } else {
            ((x - y) * (x + y)).abs()
        });
    }
    println!("worst cylinder residual {worst_cyl:.2e}, worst plane residual {worst_plane:.2e}");
    assert!(worst_cyl <= 1e-8);
    assert!(worst_plane <= 1e-7);

    // The seven arcs: one node–node arc (x = y > 0), two node–boundary arcs in each other
    // quadrant, ending on Q (x = y < 0 and x = −y > 0) or on P (x = −y < 0).
    assert_eq!(branches.len(), 7);
    let mut node_node = 0;
    let mut boundary_ends = [0usize; 2];
    for b in branches {
        assert_eq!(b.status, BranchStatus::Open, "branch {}", b.id);
        let singular = b.ends.iter().filter(|e| **e == EndReason::Singular).count();
        let (xp, yp) = quadrant(b);
        match (xp, yp) {
            (true, true) => {
                assert_eq!(
                    singular, 2,
                    "branch {}: the x = y > 0 arc joins the nodes",
                    b.id
                );
                node_node += 1;
            }
            _ => {
                assert_eq!(singular, 1, "branch {}", b.id);
                let want = if (xp, yp) == (false, true) { 0 } else { 1 };
                assert!(
                    b.ends.contains(&EndReason::Boundary { surface: want }),
                    "branch {} {:?} should end on surface {want}",
                    b.id,
                    b.ends
                );
                boundary_ends[want] += 1;
            }
        }
    }
    assert_eq!((node_node, boundary_ends), (1, [2, 4]));

    // Dense closed-form samples: each within half a step of exactly one arc (none missing, none
    // traced twice), except within a step of the nodes; and the nearest arc is much closer.
    let samples = ellipse_samples(4000);
    let (mut checked, mut missing, mut double, mut worst) = (0, 0, 0, 0.0f64);
    for s in &samples {
        if out.nodes.iter().any(|n| dist(&n.xyz, s) < STEP) {
            continue;
        }
        checked += 1;
        let d: Vec<f64> = branches.iter().map(|b| branch_dist(b, s)).collect();
        worst = worst.max(d.iter().cloned().fold(f64::INFINITY, f64::min));
        match d.iter().filter(|&&x| x <= 0.5 * STEP).count() {
            0 => missing += 1,
            1 => {}
            _ => double += 1,
        }
    }
    println!(
        "ellipse samples {checked} (of {}): missing {missing}, covered twice {double}, \
         farthest from the trace {worst:.2e}",
        samples.len()
    );
    assert!(checked as f64 > 0.9 * samples.len() as f64);
    assert_eq!((missing, double), (0, 0));
    assert!(worst < 1e-3);

    // Each arc's length against the closed form: on both ellipses x = cos φ, z = sin φ and
    // |dp/dφ| = √(1 + sin²φ); φ at the ends from atan2(z, x) (Simpson's rule, 2000 panels).
    let mut worst_len = 0.0f64;
    for b in branches {
        let phi = |pt: &CurvePoint| pt.xyz[2].atan2(pt.xyz[0]);
        let (a, c) = (phi(&b.points[0]), phi(&b.points[b.points.len() - 1]));
        let n = 2000;
        let h = (c - a) / n as f64;
        let f = |t: f64| (1.0 + t.sin().powi(2)).sqrt();
        let exact = (h / 3.0).abs()
            * (0..=n)
                .map(|k| {
                    let w = if k == 0 || k == n {
                        1.0
                    } else if k % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    w * f(a + h * k as f64)
                })
                .sum::<f64>();
        let traced: f64 = b
            .points
            .windows(2)
            .map(|w| dist(&w[0].xyz, &w[1].xyz))
            .sum();
        println!(
            "branch {}: length {traced:.5}, closed form {exact:.5}",
            b.id
        );
        worst_len = worst_len.max((traced - exact).abs());
    }
    assert!(worst_len < 2e-3, "arc length off by {worst_len}");

    // The boundary ends lie where the closed form says: x = −5/13 on P, y = −0.69/2.69 on Q.
    for b in branches {
        for (k, e) in b.ends.iter().enumerate() {
            let pt: &CurvePoint = if k == 0 {
                &b.points[0]
            } else {
                &b.points[b.points.len() - 1]
            };
            match e {
                EndReason::Boundary { surface: 0 } => assert!((pt.xyz[0] - X_MIN).abs() < 1e-8),
                EndReason::Boundary { .. } => assert!((pt.xyz[1] - Y_MIN).abs() < 1e-8),
                _ => {}
            }
        }
    }
}

#[test]
fn pipeline_both_certifies_the_arcs_and_stops_them_at_the_nodes() {
    let scene = scene();
    let mut opts = RunOptions::from_scene(&scene);
    opts.method = Method::Both;
    let t0 = Instant::now();
    let report = run(&scene, &opts).expect("runs");
    let seconds = t0.elapsed().as_secs_f64();
    println!(
        "pipeline both: {seconds:.2} s (march {:.2} s, certify {:.2} s), {} branches",
        report.result.stats.march_seconds,
        report.result.stats.certify_seconds(),
        report.result.certificates().len()
    );
    println!(
        "{:>3} {:>6} {:>10} {:>24} {:>24}",
        "id", "steps", "tolerance", "end 0", "end 1"
    );
    let mut certified = 0;
    for c in report.result.certificates() {
        match &c.result {
            Ok(cb) => {
                certified += 1;
                let end = |e: &CertifiedEnd| match e {
                    CertifiedEnd::Boundary { surface } => format!("boundary {surface}"),
                    CertifiedEnd::Singular { .. } => "singular".to_string(),
                    other => format!("{other:?}").chars().take(24).collect(),
                };
                println!(
                    "{:>3} {:>6} {:>10.2e} {:>24} {:>24}",
                    c.branch,
                    cb.steps(),
                    cb.certified_tolerance,
                    end(&cb.ends[0]),
                    end(&cb.ends[1])
                );
                // Each arc touches a node, so at least one end of its certificate is singular,
                // and no end claims a closed loop.
                assert!(
                    cb.ends
                        .iter()
                        .any(|e| matches!(e, CertifiedEnd::Singular { .. })),
                    "branch {}: {:?}",
                    c.branch,
                    cb.ends
                );
                assert!(!cb.ends.contains(&CertifiedEnd::ClosedLoop));
                assert!(cb.certified_tolerance.is_finite() && cb.certified_tolerance < 1e-6);
            }
            Err(e) => println!("{:>3} not certified: {e}", c.branch),
        }
    }
    assert_eq!(report.result.certificates().len(), 7);
    assert_eq!(certified, 7);
}
