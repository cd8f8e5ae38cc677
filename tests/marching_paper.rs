//! Seed 000 (Wu–Andrade): Table 1 (circular vs tangent steps on S1–S3, Newton iterations per
//! point) and Figs. 6–8 (rational surfaces, three nested loops, a singular point).

mod common;

use common::surfaces::{fig8, plane_z0, SQUARE};
use nalgebra::Vector3;
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::{Domain, ParametricSurface};
use ssitrace::march::branch::{BranchStatus, EndReason, EventKind};
use ssitrace::march::{trace_branch, MarchOptions, StepMethod, TracedBranch};
use std::f64::consts::PI;

type V = Vector3<f64>;

fn opts(step: f64, method: StepMethod) -> MarchOptions {
    opts_tol(step, method, 1e-8)
}

fn opts_tol(step: f64, method: StepMethod, newton_tolerance: f64) -> MarchOptions {
    MarchOptions {
        step,
        method,
        newton_tolerance,
        ..MarchOptions::default()
    }
}

/// Percentages of the marched points (the start excluded) needing 1, 2, 3, ≥4 Newton corrections,
/// and the mean.
fn iteration_profile(b: &TracedBranch) -> ([f64; 4], f64) {
    let its: Vec<usize> = b
        .newton_iterations
        .iter()
        .copied()
        .filter(|&k| k > 0)
        .collect();
    let n = its.len().max(1) as f64;
    let mut pc = [0.0; 4];
    for &k in &its {
        pc[(k - 1).min(3)] += 100.0 / n;
    }
    (pc, its.iter().sum::<usize>() as f64 / n)
}

fn table1_row<S1: ParametricSurface, S2: ParametricSurface>(
    name: &str,
    p: &S1,
    q: &S2,
    start: [f64; 4],
    paper: [(&str, f64, usize, [f64; 3]); 4],
) {
    // The paper does not state its Newton tolerance; the table is given for two.
    for tol in [1e-4, 1e-6] {
        println!("-- Newton tolerance {tol:.0e}");
        table1_rows(name, p, q, start, &paper, tol);
    }
}

fn table1_rows<S1: ParametricSurface, S2: ParametricSurface>(
    name: &str,
    p: &S1,
    q: &S2,
    start: [f64; 4],
    paper: &[(&str, f64, usize, [f64; 3]); 4],
    tol: f64,
) {
    for pair in paper.chunks(2) {
        let l = pair[0].1;
        let mut means = Vec::new();
        for &(label, _, paper_points, paper_pc) in pair {
            let method = if label == "Circular" {
                StepMethod::Circular
            } else {
                StepMethod::Tangent
            };
            let b = trace_branch(p, q, start, &opts_tol(l, method, tol)).expect("start refines");
            let (pc, mean) = iteration_profile(&b);
            println!(
                "{name}  {l:.2}  {label:<8} | ours {:>5} pts  {:>5.1}% {:>5.1}% {:>5.1}% {:>5.1}%(≥4)  mean {mean:.2}  ends {:?} | paper {paper_points:>5} pts  {:>5.1}% {:>5.1}% {:>5.1}%",
                b.branch.points.len(),
                pc[0], pc[1], pc[2], pc[3],
                b.branch.ends,
                paper_pc[0], paper_pc[1], paper_pc[2],
            );
            assert!(
                !b.branch.ends.contains(&EndReason::NewtonFailed)
                    && !b.branch.ends.contains(&EndReason::PointLimit),
                "{name} {label} {l}: {:?}",
                b.branch.ends
            );
            means.push(mean);
        }
        assert!(
            means[0] < means[1],
            "{name} L={l}: circular mean {} not below tangent mean {}",
            means[0],
            means[1]
        );
    }
}

#[test]
fn table1_circular_steps_need_fewer_newton_iterations() {
    println!("pair  L     method   | our branch (start points chosen by us, see source)            | Wu–Andrade Table 1");
    // S1: cylinder against paraboloid. Start: F(0, 0) = G(0, 0) = (0, 0, 9).
    let cyl = AnalyticSurface::new(Domain::new(-PI, PI, -9.0, 9.0), |u: Jet2, v: Jet2| {
        [v + 4.0 * u.sin(), 1.5 * v, 5.0 + v + 4.0 * u.cos()]
    });
    let par = AnalyticSurface::new(Domain::new(-7.5, 7.5, -7.5, 7.5), |u: Jet2, v: Jet2| {
        [u, v, 9.0 - (u * u + v * v) / 5.0]
    });
    table1_row(
        "S1",
        &cyl,
        &par,
        [0.0, 0.0, 0.0, 0.0],
        [
            ("Circular", 0.05, 556, [73.7, 26.3, 0.0]),
            ("Tangent", 0.05, 350, [0.3, 99.7, 0.0]),
            ("Circular", 0.20, 377, [2.6, 97.4, 0.0]),
            ("Tangent", 0.20, 233, [0.0, 74.3, 25.7]),
        ],
    );

    // S2: two tori. Start on the symmetric plane x = z: x = z = 0.5, ρ = 3 + √0.75.
    let ta = AnalyticSurface::new(Domain::new(-PI, PI, -PI, PI), |u: Jet2, v: Jet2| {
        [
            (3.0 + u.cos()) * v.sin(),
            (3.0 + u.cos()) * v.cos(),
            u.sin(),
        ]
    });
    let tb = AnalyticSurface::new(Domain::new(-PI, PI, -PI, PI), |u: Jet2, v: Jet2| {
        [
            u.sin(),
            (3.0 + u.cos()) * v.sin(),
            (3.0 + u.cos()) * v.cos(),
        ]
    });
    let rho = 3.0 + 0.75f64.sqrt();
    let y = (rho * rho - 0.25).sqrt();
    let s2 = [PI / 6.0, (0.5 / rho).asin(), PI / 6.0, y.atan2(0.5)];
    table1_row(
        "S2",
        &ta,
        &tb,
        s2,
        [
            ("Circular", 0.05, 431, [23.7, 76.3, 0.0]),
            ("Tangent", 0.05, 314, [0.3, 99.7, 0.0]),
            ("Circular", 0.20, 212, [4.2, 95.8, 0.0]),
            ("Tangent", 0.20, 106, [0.0, 47.2, 52.8]),
        ],
    );

    // S3: torus (major radius 10, tube 5; the OCR lost the sign, "10 − 5 sin u" is used) against
    // the cylinder of radius 5 about the x axis. Start (√200, 0, 5).
    let tor = AnalyticSurface::new(
        Domain::new(0.0, 2.0 * PI, 0.0, 2.0 * PI),
        |u: Jet2, v: Jet2| {
            let r = 10.0 - 5.0 * u.sin();
            [r * v.sin(), 5.0 * u.cos(), r * v.cos()]
        },
    );
    let cyl3 = AnalyticSurface::new(
        Domain::new(0.0, 2.0 * PI, -20.0, 20.0),
        |u: Jet2, v: Jet2| [v, 5.0 * u.cos(), 5.0 * u.sin()],
    );
    let x = 200f64.sqrt();
    table1_row(
        "S3",
        &tor,
        &cyl3,
        [1.5 * PI, x.atan2(5.0), 0.5 * PI, x],
        [
            ("Circular", 0.05, 1259, [100.0, 0.0, 0.0]),
            ("Tangent", 0.05, 495, [8.0, 92.0, 0.0]),
            ("Circular", 0.20, 846, [38.5, 61.5, 0.0]),
            ("Tangent", 0.20, 240, [1.7, 98.3, 0.0]),
        ],
    );
}

/// Fig. 7: F = (u, v, f(u, v)) with f = (0.5 − r²)(0.6 − r²)(0.7 − r²), r² = 3u² + v², against
/// the plane z = 0: three nested ellipses 3u² + v² = 0.5, 0.6, 0.7.
#[test]
fn fig7_three_nested_loops_each_closed_once() {
    let sextic = AnalyticSurface::new(Domain::new(-1.0, 1.0, -1.0, 1.0), |u: Jet2, v: Jet2| {
        let (u2, v2) = (u * u, v * v);
        let z = 0.21 - 3.21 * u2 - 1.07 * v2 + 16.2 * u2 * u2 + 10.8 * u2 * v2 + 1.8 * v2 * v2
            - 27.0 * u2.powi(3)
            - 27.0 * u2 * u2 * v2
            - 9.0 * u2 * v2 * v2
            - v2.powi(3);
        [u, v, z]
    });
    let plane = plane_z0(SQUARE);
    let levels: [f64; 3] = [0.5, 0.6, 0.7];
    let mut loops = Vec::new();
    for &c in &levels {
        // Start on the v axis, nudged off the curve: Newton finds it.
        let v0: f64 = c.sqrt();
        let b = trace_branch(
            &sextic,
            &plane,
            [0.0, v0 + 0.01, 0.0, v0],
            &opts(0.05, StepMethod::Circular),
        )
        .expect("start refines");
        let off = b
            .branch
            .points
            .iter()
            .map(|pt| (3.0 * pt.p[0] * pt.p[0] + pt.p[1] * pt.p[1] - c).abs())
            .fold(0.0, f64::max);
        let first = b.branch.points.first().unwrap();
        let last = b.branch.points.last().unwrap();
        println!(
            "ellipse 3u²+v²={c}: {} points, status {:?}, turning {:.4} (2π = {:.4}), max |3u²+v²−c| {off:.1e}, closing gap {:.1e}",
            b.branch.points.len(),
            b.branch.status,
            b.turning,
            2.0 * PI,
            (V::from(first.xyz) - V::from(last.xyz)).norm()
        );
        assert_eq!(b.branch.status, BranchStatus::Closed);
        assert!(off < 1e-6, "a point strayed off its own ellipse: {off}");
        assert!((b.turning.abs() - 2.0 * PI).abs() < 0.05);
        assert_eq!(first, last);
        // Traced once: apart from the closing copy, no point comes back near the start
        // except its immediate neighbours along the curve.
        let p0 = V::from(first.xyz);
        let n = b.branch.points.len();
        let arc: Vec<f64> = b
            .branch
            .points
            .windows(2)
            .scan(0.0, |s, w| {
                *s += (V::from(w[1].xyz) - V::from(w[0].xyz)).norm();
                Some(*s)
            })
            .collect();
        let total = arc[n - 2];
        let perimeter = ellipse_perimeter((c / 3.0).sqrt(), c.sqrt());
        println!("   arc length {total:.5}, exact perimeter {perimeter:.5}");
        assert!((total - perimeter).abs() < 1e-3 * perimeter);
        for (i, pt) in b.branch.points.iter().enumerate().skip(1).take(n - 2) {
            let along = arc[i - 1].min(total - arc[i - 1]);
            let d = (V::from(pt.xyz) - p0).norm();
            assert!(d > 0.5 * along, "point {i} revisits the start region");
        }
        loops.push(b);
    }
    // No loop strays onto a neighbour: minimal distances between traced loops.
    for i in 0..2 {
        let dmin = loops[i]
            .branch
            .points
            .iter()
            .flat_map(|a| {
                loops[i + 1]
                    .branch
                    .points
                    .iter()
                    .map(move |b| (V::from(a.xyz) - V::from(b.xyz)).norm())
            })
            .fold(f64::INFINITY, f64::min);
        println!(
            "min distance between traced loops {i} and {}: {dmin:.5}",
            i + 1
        );
        assert!(dmin >= 0.03);
    }
}

/// Ramanujan's approximation of an ellipse's perimeter (relative error < 1e-9 here).
fn ellipse_perimeter(a: f64, b: f64) -> f64 {
    let h = ((a - b) / (a + b)).powi(2);
    PI * (a + b) * (1.0 + 3.0 * h / (10.0 + (4.0 - 3.0 * h).sqrt()))
}

/// Fig. 6: F = (u, v, 10(u² − v²)/(2 + u⁴ + v⁴)) against G = (u/(v² + 1), v, (u − 1)/2). Start
/// points are found by scanning h(x, y) = x(y² + 1) − 1 − 2 f(x, y) for sign changes.
#[test]
fn fig6_rational_surfaces_trace_without_failure() {
    let fsurf = AnalyticSurface::new(Domain::new(-4.0, 4.0, -4.0, 4.0), |u: Jet2, v: Jet2| {
        [u, v, 10.0 * (u * u - v * v) / (2.0 + u.powi(4) + v.powi(4))]
    });
    let gsurf = AnalyticSurface::new(Domain::new(-4.0, 5.0, -4.0, 4.0), |u: Jet2, v: Jet2| {
        [u / (v * v + 1.0), v, (u - 1.0) * 0.5]
    });
    let f = |x: f64, y: f64| 10.0 * (x * x - y * y) / (2.0 + x.powi(4) + y.powi(4));
    let h = |x: f64, y: f64| x * (y * y + 1.0) - 1.0 - 2.0 * f(x, y);
    let mut starts = Vec::new();
    for j in 0..=16 {
        let y = -4.0 + 0.5 * j as f64;
        for i in 0..160 {
            let (mut a, mut b) = (-4.0 + 0.05 * i as f64, -4.0 + 0.05 * (i + 1) as f64);
            if h(a, y) * h(b, y) > 0.0 {
                continue;
            }
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if h(a, y) * h(m, y) <= 0.0 {
                    b = m
                } else {
                    a = m
                }
            }
            let s = a * (y * y + 1.0);
            if (-4.0..=5.0).contains(&s) {
                starts.push([a, y, s, y]);
            }
        }
    }
    let mut traced: Vec<TracedBranch> = Vec::new();
    for st in starts {
        let here = V::new(st[0], st[1], f(st[0], st[1]));
        let seen = traced.iter().any(|b| {
            b.branch
                .points
                .iter()
                .any(|p| (V::from(p.xyz) - here).norm() < 0.05)
        });
        if seen {
            continue;
        }
        let b = trace_branch(&fsurf, &gsurf, st, &opts(0.05, StepMethod::Circular))
            .expect("start refines");
        let worst = b
            .branch
            .points
            .iter()
            .map(|p| h(p.p[0], p.p[1]).abs())
            .fold(0.0, f64::max);
        println!(
            "branch from ({:+.3}, {:+.3}): {} points, ends {:?}, max |h| {worst:.1e}, retried steps {}",
            st[0],
            st[1],
            b.branch.points.len(),
            b.branch.ends,
            b.stats.retried_steps
        );
        assert!(worst < 1e-5);
        assert!(b
            .branch
            .ends
            .iter()
            .all(|e| matches!(e, EndReason::Boundary { .. } | EndReason::ClosedLoop)));
        traced.push(b);
    }
    assert!(!traced.is_empty());
}

/// Fig. 8: F = (u, v, (2u⁴ + v⁴)/10) against G = (r, s, (3r²s − s² + 2s³)/10), tangent at the
/// origin (both normals vertical): the singular point must be reported.
#[test]
fn fig8_singular_point_at_origin_is_reported() {
    let (fs, gs) = fig8();
    let u0 = 1.5f64.sqrt(); // h(u0, 1) = 0 exactly
    let mut near_origin = false;
    for start in [[u0, 1.0, u0, 1.0], [-u0, 1.0, -u0, 1.0]] {
        let b = trace_branch(&fs, &gs, start, &opts(0.05, StepMethod::Circular)).expect("refines");
        let sing: Vec<_> = b
            .events
            .iter()
            .filter(|e| e.kind == EventKind::Singular)
            .collect();
        println!(
            "from ({:+.3}, 1): {} points, ends {:?}, singular events at {:?}",
            start[0],
            b.branch.points.len(),
            b.branch.ends,
            sing.iter().map(|e| e.xyz).collect::<Vec<_>>()
        );
        assert!(b.branch.ends.contains(&EndReason::Singular));
        assert!(!sing.is_empty());
        // The curve 2u⁴ + v⁴ − 3u²v + v² − 2v³ = 0 has two singular points (gradient zero):
        // the tacnode at the origin (the paper's) and the crossing at (0, 1).
        for e in &sing {
            let d0 = V::from(e.xyz).norm();
            let d1 = (V::from(e.xyz) - V::new(0.0, 1.0, 0.1)).norm();
            assert!(
                d0.min(d1) < 0.01,
                "singular event at {:?} is not a singular point",
                e.xyz
            );
        }
        near_origin |= sing.iter().any(|e| V::from(e.xyz).norm() < 0.01);
    }
    assert!(
        near_origin,
        "the singular point at the origin was not reported"
    );
}
