//! Seed 004 (Wu, Aléssio, Costa) and two classic tangential intersections traced as graphs:
//! singular points are nodes, every arc between nodes (or to the boundary) is traced exactly once.
//!
//! Each case is checked against its implicit equation: every traced point lies on the curve, and
//! a dense independent sampling of the curve (sign changes of the implicit function on a grid
//! for seed 004, the closed-form parametrisation for Viviani and the cylinders) is covered by
//! exactly one arc away from the nodes. A double trace shows up as a sample covered twice, a
//! missing arc as a sample not covered.

mod common;

use common::surfaces::{fig8, height_field};
use nalgebra::Vector3;
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::{Domain, ParametricSurface, PowerSurface};
use ssitrace::march::branch::{Branch, BranchStatus, EndReason};
use ssitrace::march::{trace_branch, MarchOptions};
use ssitrace::pair::contact_quadratic::ContactCase;
use ssitrace::search::start_points::SearchOptions;
use ssitrace::topology::graph::{trace_graph, GraphOutcome};
use ssitrace::topology::intersect::intersect;
use std::f64::consts::PI;

type V = Vector3<f64>;

fn opts(step: f64) -> MarchOptions {
    MarchOptions {
        step,
        max_points: 4000,
        ..MarchOptions::default()
    }
}

/// Samples of `h(u, v) = 0` in `[a, b] × [c, d]`: sign changes of `h` along grid rows and
/// columns (spacing `gap`), refined by bisection.
fn implicit_samples(h: &dyn Fn(f64, f64) -> f64, dom: [f64; 4], gap: f64) -> Vec<[f64; 2]> {
    let [a, b, c, d] = dom;
    let root = |f: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64| {
        let flo = f(lo);
        for _ in 0..60 {
            let m = 0.5 * (lo + hi);
            if f(m) * flo > 0.0 {
                lo = m;
            } else {
                hi = m;
            }
        }
        0.5 * (lo + hi)
    };
    let mut out = Vec::new();
    let (nu, nv) = (((b - a) / gap) as usize, ((d - c) / gap) as usize);
    let fine = gap / 8.0;
    for j in 0..=nv {
        let v = c + (d - c) * j as f64 / nv as f64;
        let f = |u: f64| h(u, v);
        let n = ((b - a) / fine) as usize;
        for k in 0..n {
            let (u0, u1) = (
                a + (b - a) * k as f64 / n as f64,
                a + (b - a) * (k + 1) as f64 / n as f64,
            );
            if f(u0) * f(u1) < 0.0 {
                out.push([root(&f, u0, u1), v]);
            }
        }
    }
    for i in 0..=nu {
        let u = a + (b - a) * i as f64 / nu as f64;
        let f = |v: f64| h(u, v);
        let n = ((d - c) / fine) as usize;
        for k in 0..n {
            let (v0, v1) = (
                c + (d - c) * k as f64 / n as f64,
                c + (d - c) * (k + 1) as f64 / n as f64,
            );
            if f(v0) * f(v1) < 0.0 {
                out.push([u, root(&f, v0, v1)]);
            }
        }
    }
    out
}

fn seg_dist(c: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    let ac: Vec<f64> = a.iter().zip(c).map(|(x, y)| y - x).collect();
    let l2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if l2 > 0.0 {
        (ab.iter().zip(&ac).map(|(x, y)| x * y).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a.iter()
        .zip(&ab)
        .zip(c)
        .map(|((x, d), y)| (x + t * d - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// How many branches pass within `tol` of `c` (coordinates picked by `coord`).
fn cover_count(
    branches: &[Branch],
    c: &[f64],
    tol: f64,
    coord: &dyn Fn(&ssitrace::march::branch::CurvePoint) -> Vec<f64>,
) -> usize {
    branches
        .iter()
        .filter(|b| {
            b.points
                .windows(2)
                .any(|w| seg_dist(c, &coord(&w[0]), &coord(&w[1])) <= tol)
        })
        .count()
}

/// Coverage of `samples` (in the coordinates of `coord`) by the branches, samples within
/// `exclude` of a node left out: returns (samples checked, uncovered, covered more than once).
fn coverage(
    branches: &[Branch],
    samples: &[Vec<f64>],
    nodes: &[Vec<f64>],
    exclude: f64,
    tol: f64,
    coord: &dyn Fn(&ssitrace::march::branch::CurvePoint) -> Vec<f64>,
) -> (usize, usize, usize) {
    let (mut checked, mut missing, mut double) = (0, 0, 0);
    for s in samples {
        let near = nodes.iter().any(|n| {
            n.iter()
                .zip(s)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
                < exclude
        });
        if near {
            continue;
        }
        checked += 1;
        match cover_count(branches, s, tol, coord) {
            0 => missing += 1,
            1 => {}
            _ => double += 1,
        }
    }
    (checked, missing, double)
}

fn arc_length(b: &Branch) -> f64 {
    b.points
        .windows(2)
        .map(|w| (V::from(w[1].xyz) - V::from(w[0].xyz)).norm())
        .sum()
}

/// One row of the printed table.
struct Row {
    example: &'static str,
    closed: usize,
    node_arcs: usize,
    open: usize,
    nodes: String,
    turning: String,
    points: usize,
    coverage: (usize, usize, usize),
    traversals: f64,
}

fn print_row(r: &Row) {
    println!(
        "{:<22} loops {:>2}  node arcs {:>2}  boundary arcs {:>2}  nodes {:<36} single trace turning {:<22} points {:>5}  samples {:>5} missing {} double {}  traversals {:.3}",
        r.example, r.closed, r.node_arcs, r.open, r.nodes, r.turning, r.points, r.coverage.0, r.coverage.1, r.coverage.2, r.traversals
    );
}

fn describe_nodes(g: &GraphOutcome) -> String {
    g.nodes
        .iter()
        .map(|n| {
            let c = match n.case {
                ContactCase::BranchPoint => "branch",
                ContactCase::IsolatedPoint => "isolated",
                ContactCase::TangentialCurve => "tacnode",
                ContactCase::HigherOrder => "higher",
            };
            format!("{c}/{}", n.exits.len())
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// The arcs of a graph outcome: closed loops, arcs with a node end, arcs boundary to boundary.
fn kinds(branches: &[Branch]) -> (usize, usize, usize) {
    let closed = branches
        .iter()
        .filter(|b| b.status == BranchStatus::Closed)
        .count();
    let node = branches
        .iter()
        .filter(|b| b.ends.contains(&EndReason::Singular))
        .count();
    let open = branches
        .iter()
        .filter(|b| {
            b.ends
                .iter()
                .all(|e| matches!(e, EndReason::Boundary { .. }))
        })
        .count();
    (closed, node, open)
}

/// Graph surfaces `(u, v, f)` and `(s, w, g)` over the same domain: the curve is `f − g = 0` in
/// either parameter domain.
struct Seed004 {
    example: &'static str,
    domain: [f64; 4],
    starts: Vec<[f64; 2]>,
    step: f64,
    /// Expected (closed loops, arcs at nodes, boundary-to-boundary arcs).
    expect: (usize, usize, usize),
    /// Expected node kinds (case, exits), in any order.
    expect_nodes: Vec<(ContactCase, usize)>,
    /// Rotation index of the closed curve through the first start (|turning| / 2π).
    index: f64,
    /// Which fraction of the arcs at nodes that curve makes up.
    fraction: f64,
}

fn run_seed004<F, G>(case: &Seed004, f: F, g: G, h: &dyn Fn(f64, f64) -> f64) -> GraphOutcome
where
    F: Fn(Jet2, Jet2) -> Jet2 + Copy,
    G: Fn(Jet2, Jet2) -> Jet2 + Copy,
{
    let [a, b, c, d] = case.domain;
    let dom = Domain::new(a, b, c, d);
    let s1 = AnalyticSurface::new(dom, move |u: Jet2, v: Jet2| [u, v, f(u, v)]);
    let s2 = AnalyticSurface::new(dom, move |u: Jet2, v: Jet2| [u, v, g(u, v)]);
    let starts: Vec<[f64; 4]> = case
        .starts
        .iter()
        .map(|s| [s[0], s[1], s[0], s[1]])
        .collect();
    let out = trace_graph(&s1, &s2, &starts, &opts(case.step));
    // Every point on the curve (node points to the located precision).
    for br in &out.branches {
        for pt in &br.points {
            assert!(
                h(pt.p[0], pt.p[1]).abs() < 1e-8,
                "{}: point {:?} off the curve by {:e}",
                case.example,
                pt.p,
                h(pt.p[0], pt.p[1])
            );
        }
    }
    let samples: Vec<Vec<f64>> = implicit_samples(h, case.domain, 0.01)
        .into_iter()
        .map(|s| s.to_vec())
        .collect();
    let nodes: Vec<Vec<f64>> = out.nodes.iter().map(|n| vec![n.x[0], n.x[1]]).collect();
    let cov = coverage(&out.branches, &samples, &nodes, 0.15, 5e-3, &|p| {
        p.p.to_vec()
    });
    let k = kinds(&out.branches);
    // The single-trace API with crossing on, from the first start: once round the closed curve.
    let crossing = MarchOptions {
        cross_singular: 16,
        ..opts(case.step)
    };
    let single = trace_branch(&s1, &s2, starts[0], &crossing).expect("the start refines");
    let at_nodes: f64 = out
        .branches
        .iter()
        .filter(|b| b.ends.contains(&EndReason::Singular))
        .map(arc_length)
        .sum();
    let traversals = arc_length(&single.branch) / (case.fraction * at_nodes);
    print_row(&Row {
        example: case.example,
        closed: k.0,
        node_arcs: k.1,
        open: k.2,
        nodes: describe_nodes(&out),
        turning: format!(
            "{:.3} (index {:.2})",
            single.turning,
            single.turning / (2.0 * PI)
        ),
        points: out.branches.iter().map(|b| b.points.len()).sum(),
        coverage: cov,
        traversals,
    });
    assert_eq!(
        single.branch.status,
        BranchStatus::Closed,
        "{}",
        case.example
    );
    assert!(
        (single.turning.abs() - 2.0 * PI * case.index).abs() < 0.3,
        "{}: turning {}",
        case.example,
        single.turning
    );
    assert!(
        (traversals - 1.0).abs() < 0.02,
        "{}: {traversals}",
        case.example
    );
    for pt in &single.branch.points {
        assert!(
            h(pt.p[0], pt.p[1]).abs() < 1e-8,
            "{}: single trace off the curve",
            case.example
        );
    }
    assert_eq!(
        k, case.expect,
        "{}: (loops, node arcs, open arcs)",
        case.example
    );
    assert_eq!(out.stats.unmatched_arrivals, 0, "{}", case.example);
    assert!(cov.0 > 100, "{}: too few samples", case.example);
    assert_eq!(
        (cov.1, cov.2),
        (0, 0),
        "{}: coverage (missing, double)",
        case.example
    );
    let mut got: Vec<(ContactCase, usize)> =
        out.nodes.iter().map(|n| (n.case, n.exits.len())).collect();
    let mut want = case.expect_nodes.clone();
    let key = |x: &(ContactCase, usize)| format!("{x:?}");
    got.sort_by_key(key);
    want.sort_by_key(key);
    assert_eq!(got, want, "{}: nodes", case.example);
    // Every exit was traced.
    assert!(out.exits_used.iter().flatten().all(|&u| u));
    out
}

fn s11_h(u: f64, v: f64) -> f64 {
    0.2 * u.powi(4) + 0.1 * v.powi(4) - 0.3 * u * u * v + 0.1 * v * v - 0.2 * v.powi(3)
}

#[test]
fn seed004_examples_as_graphs_each_arc_once() {
    // S11/S12: one closed curve (rotation index 2) through the branch point (0, 1) and the
    // tacnode (0, 0): two nodes of four exits each, four arcs.
    let s11 = Seed004 {
        example: "S11/S12",
        domain: [-2.0, 2.0, -0.5, 2.5],
        starts: vec![[1.20, 0.97]],
        step: 0.1,
        expect: (0, 4, 0),
        expect_nodes: vec![
            (ContactCase::BranchPoint, 4),
            (ContactCase::TangentialCurve, 4),
        ],
        index: 2.0,
        fraction: 1.0,
    };
    let out = run_seed004(
        &s11,
        |u, v| 0.2 * u.powi(4) + 0.1 * v.powi(4),
        |s, w| 0.3 * s * s * w - 0.1 * w * w + 0.2 * w.powi(3),
        &s11_h,
    );
    // The branch point is (0, 1), the tacnode (0, 0).
    for n in &out.nodes {
        let want = if n.case == ContactCase::BranchPoint {
            [0.0, 1.0]
        } else {
            [0.0, 0.0]
        };
        assert!(
            (n.x[0] - want[0]).abs() + (n.x[1] - want[1]).abs() < 1e-6,
            "{:?}",
            n.x
        );
    }

    // S21/S22: the trifolium (u² + v²)² + 3u²v − v³ = 0, a triple point at the origin (Δ = 0,
    // all b = 0: undecidable at second order, exits found on the circle): three petals.
    let s21 = Seed004 {
        example: "S21/S22 triple point",
        domain: [-1.5, 1.5, -1.5, 1.5],
        starts: vec![[0.14, 0.88]],
        step: 0.1,
        expect: (0, 3, 0),
        expect_nodes: vec![(ContactCase::HigherOrder, 6)],
        index: 2.0,
        fraction: 1.0,
    };
    run_seed004(
        &s21,
        |u, v| (u * u + v * v).powi(2) + 3.0 * u * u * v - v.powi(3),
        |_, _| Jet2::constant(0.0),
        &|u, v| (u * u + v * v).powi(2) + 3.0 * u * u * v - v.powi(3),
    );

    // S31/S32 is checked in marching_loops.rs (different parametrisation of S32).

    // S41/S42: the Devil's curve v⁴ − v² + 2u² − u⁴ = 0: two open branches and an eight
    // through the node at the origin (two arcs from the node back to it).
    let s41 = Seed004 {
        example: "S41/S42 Devil's curve",
        domain: [-2.0, 2.0, -2.0, 2.0],
        starts: vec![[-0.34, 0.83], [1.38, 0.50], [-1.37, 0.82]],
        step: 0.1,
        expect: (0, 2, 2),
        expect_nodes: vec![(ContactCase::BranchPoint, 4)],
        index: 0.0,
        fraction: 1.0,
    };
    run_seed004(
        &s41,
        |u, v| v.powi(4) - v * v + 2.0 * u * u,
        |s, _| s.powi(4),
        &|u, v| v.powi(4) - v * v + 2.0 * u * u - u.powi(4),
    );

    // S51/S52: (u² − ½)² + (v² − ½)² = ¼, two closed curves crossing at four nodes
    // (0, ±1/√2), (±1/√2, 0): eight arcs. The paper's program went round four times.
    let s51 = Seed004 {
        example: "S51/S52 two curves",
        domain: [-1.5, 1.5, -1.5, 1.5],
        starts: vec![[std::f64::consts::FRAC_1_SQRT_2, 1.0]],
        step: 0.1,
        expect: (0, 8, 0),
        expect_nodes: vec![(ContactCase::BranchPoint, 4); 4],
        index: 1.0,
        fraction: 0.5,
    };
    run_seed004(
        &s51,
        |u, v| u.powi(4) - u * u + v.powi(4) - v * v,
        |_, _| Jet2::constant(-0.25),
        &|u, v| u.powi(4) - u * u + v.powi(4) - v * v + 0.25,
    );
}

/// Fig. 8 of seed 000 (the S11/S12 curve on a smaller domain) from both of its start points:
/// the graph run ends with every exit traced and no budget spent.
#[test]
fn fig8_graph_run_does_not_spend_the_budget() {
    let (fs, gs) = fig8();
    let u0 = 1.5f64.sqrt();
    let out = trace_graph(
        &fs,
        &gs,
        &[[u0, 1.0, u0, 1.0], [-u0, 1.0, -u0, 1.0]],
        &opts(0.05),
    );
    let points: usize = out.branches.iter().map(|b| b.points.len()).sum();
    println!(
        "Fig. 8: {} arcs, nodes {}, {points} points, skipped starts {}",
        out.branches.len(),
        describe_nodes(&out),
        out.stats.skipped_covered
    );
    assert_eq!(out.branches.len(), 4);
    assert!(out
        .branches
        .iter()
        .all(|b| b.ends == [EndReason::Singular, EndReason::Singular]));
    let samples: Vec<Vec<f64>> = implicit_samples(&s11_h, [-1.8, 1.8, -0.3, 2.3], 0.01)
        .into_iter()
        .map(|s| s.to_vec())
        .collect();
    let nodes: Vec<Vec<f64>> = out.nodes.iter().map(|n| vec![n.x[0], n.x[1]]).collect();
    let cov = coverage(&out.branches, &samples, &nodes, 0.15, 5e-3, &|p| {
        p.p.to_vec()
    });
    println!("   samples {} missing {} double {}", cov.0, cov.1, cov.2);
    assert_eq!((cov.1, cov.2), (0, 0));
    let total: f64 = out.branches.iter().map(arc_length).sum();
    println!("   total polygon length {total:.4}");
    assert!(points < 2000, "{points} points");
}

/// Sphere of radius 2 (stereographic from (−2, 0, 0)) against the cylinder (x − 1)² + y² = 1
/// touching it inside at (2, 0, 0): Viviani's curve, a figure eight crossing itself there. The
/// patches cover a neighbourhood of the crossing: four arcs from the node to the cylinder's
/// boundary, each once.
#[test]
fn viviani_crossing_is_a_node_with_four_arcs() {
    let sphere = PowerSurface {
        domain: Domain::new(-0.45, 0.45, -0.45, 0.45),
        x: vec![(0, 0, 2.0), (2, 0, -2.0), (0, 2, -2.0)],
        y: vec![(1, 0, 4.0)],
        z: vec![(0, 1, 4.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0), (0, 2, 1.0)]),
    }
    .to_bezier()
    .unwrap();
    // (x, y) = (1, 0) + ((1 − s²), 2s)/(1 + s²), z = t.
    let cylinder = PowerSurface {
        domain: Domain::new(-0.6, 0.6, -1.5, 1.5),
        x: vec![(0, 0, 2.0)],
        y: vec![(1, 0, 2.0)],
        z: vec![(0, 1, 1.0), (2, 1, 1.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0)]),
    }
    .to_bezier()
    .unwrap();
    let out = intersect(&sphere, &cylinder, &opts(0.05), &SearchOptions::default());
    let br = &out.intersection.branches;
    for b in br {
        for pt in &b.points {
            let x = V::from(pt.xyz);
            assert!((x.norm_squared() - 4.0).abs() < 1e-7);
            assert!(((x.x - 1.0).powi(2) + x.y * x.y - 1.0).abs() < 1e-7);
        }
    }
    // z = ±2 sin(φ/2) on the cylinder point (1 + cos φ, sin φ), |φ| ≤ 2 atan 0.6.
    let phi_max = 2.0 * 0.6f64.atan();
    let samples: Vec<Vec<f64>> = (0..=400)
        .flat_map(|k| {
            let phi = -phi_max + 2.0 * phi_max * k as f64 / 400.0;
            [1.0, -1.0].map(|s| vec![1.0 + phi.cos(), phi.sin(), s * 2.0 * (phi / 2.0).sin()])
        })
        .collect();
    let nodes: Vec<Vec<f64>> = out.nodes.iter().map(|n| n.xyz.to_vec()).collect();
    let cov = coverage(br, &samples, &nodes, 0.1, 5e-3, &|p| p.xyz.to_vec());
    let k = kinds(br);
    println!(
        "Viviani: arcs at node {}, loops {}, open {}, nodes {:?}, points {}, samples {} missing {} double {}",
        k.1,
        k.0,
        k.2,
        out.nodes.iter().map(|n| (n.case, n.exits.len(), n.xyz)).collect::<Vec<_>>(),
        out.stats.points,
        cov.0,
        cov.1,
        cov.2
    );
    assert_eq!(out.nodes.len(), 1);
    assert_eq!(out.nodes[0].case, ContactCase::BranchPoint);
    assert!((V::from(out.nodes[0].xyz) - V::new(2.0, 0.0, 0.0)).norm() < 1e-6);
    assert_eq!(k, (0, 4, 0));
    assert_eq!((cov.1, cov.2), (0, 0));
    assert!(cov.0 > 700);
}

/// Two unit cylinders with perpendicular axes (x² + z² = 1 along y, y² + z² = 1 along x) over
/// patches round the top: the ellipses x = ±y meet at the tangent point (0, 0, 1); four arcs
/// leave it, each traced once.
#[test]
fn crossing_cylinders_meet_at_a_tangent_point_with_four_arcs() {
    // Along y: (x, z) = (2s, 1 − s²)/(1 + s²), y = t.
    let a = PowerSurface {
        domain: Domain::new(-0.6, 0.6, -1.2, 1.2),
        x: vec![(1, 0, 2.0)],
        y: vec![(0, 1, 1.0), (2, 1, 1.0)],
        z: vec![(0, 0, 1.0), (2, 0, -1.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0)]),
    }
    .to_bezier()
    .unwrap();
    // Along x: (y, z) = (2s, 1 − s²)/(1 + s²), x = t.
    let b = PowerSurface {
        domain: Domain::new(-0.5, 0.5, -1.2, 1.2),
        x: vec![(0, 1, 1.0), (2, 1, 1.0)],
        y: vec![(1, 0, 2.0)],
        z: vec![(0, 0, 1.0), (2, 0, -1.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0)]),
    }
    .to_bezier()
    .unwrap();
    let out = intersect(&a, &b, &opts(0.05), &SearchOptions::default());
    let br = &out.intersection.branches;
    for b in br {
        for pt in &b.points {
            let x = V::from(pt.xyz);
            assert!((x.x * x.x + x.z * x.z - 1.0).abs() < 1e-7);
            assert!((x.y * x.y + x.z * x.z - 1.0).abs() < 1e-7);
        }
    }
    // (sin θ, ±sin θ, cos θ) with |y| = |sin θ| ≤ sin(2 atan 0.5) (B's boundary comes first).
    let th_max = 2.0 * 0.5f64.atan();
    let samples: Vec<Vec<f64>> = (0..=400)
        .flat_map(|k| {
            let th = -th_max + 2.0 * th_max * k as f64 / 400.0;
            [1.0, -1.0].map(|s| vec![th.sin(), s * th.sin(), th.cos()])
        })
        .collect();
    let nodes: Vec<Vec<f64>> = out.nodes.iter().map(|n| n.xyz.to_vec()).collect();
    let cov = coverage(br, &samples, &nodes, 0.1, 5e-3, &|p| p.xyz.to_vec());
    let k = kinds(br);
    println!(
        "Crossing cylinders: arcs at node {}, loops {}, open {}, nodes {:?}, points {}, samples {} missing {} double {}",
        k.1,
        k.0,
        k.2,
        out.nodes.iter().map(|n| (n.case, n.exits.len(), n.xyz)).collect::<Vec<_>>(),
        out.stats.points,
        cov.0,
        cov.1,
        cov.2
    );
    assert_eq!(out.nodes.len(), 1);
    assert_eq!(out.nodes[0].case, ContactCase::BranchPoint);
    assert!((V::from(out.nodes[0].xyz) - V::new(0.0, 0.0, 1.0)).norm() < 1e-6);
    assert_eq!(k, (0, 4, 0));
    assert_eq!((cov.1, cov.2), (0, 0));
    assert!(cov.0 > 700);
    let _ = (PI, ParametricSurface::domain(&a));
}

/// The single-trace API with crossing on: through each node the march goes straight on through
/// an unused exit (each arc once). Fig. 8 of seed 000 (the S11/S12 curve) from both of its starts
/// closes once with turning 4π (rotation index 2; the paper's 12.554) and the length of all the
/// graph's arcs together; before, from the left start the march went round until the budget.
#[test]
fn single_trace_with_crossing_closes_once_with_the_rotation_index() {
    let (fs, gs) = fig8();
    let u0 = 1.5f64.sqrt();
    let check = |label: &str,
                 b: &ssitrace::march::TracedBranch,
                 index: f64,
                 h: &dyn Fn(f64, f64) -> f64,
                 graph_length: f64| {
        let len = arc_length(&b.branch);
        println!(
            "{label}: {} points, ends {:?}, turning {:.3} (index {:.2}), length {len:.3} (graph {graph_length:.3})",
            b.branch.points.len(),
            b.branch.ends,
            b.turning,
            b.turning / (2.0 * PI)
        );
        assert_eq!(b.branch.status, BranchStatus::Closed, "{label}");
        assert!(
            (b.turning - 2.0 * PI * index).abs() < 0.3
                || (b.turning + 2.0 * PI * index).abs() < 0.3,
            "{label}"
        );
        for pt in &b.branch.points {
            assert!(h(pt.p[0], pt.p[1]).abs() < 1e-8, "{label}: off the curve");
        }
        // Once round: the same length as the graph's arcs together (within chord effects).
        assert!(
            (len - graph_length).abs() < 0.02 * graph_length,
            "{label}: length {len} vs {graph_length}"
        );
    };
    let graph = trace_graph(&fs, &gs, &[[u0, 1.0, u0, 1.0]], &opts(0.05));
    let glen: f64 = graph.branches.iter().map(arc_length).sum();
    for start in [[u0, 1.0, u0, 1.0], [-u0, 1.0, -u0, 1.0]] {
        let o = MarchOptions {
            cross_singular: 8,
            ..opts(0.05)
        };
        let b = trace_branch(&fs, &gs, start, &o).unwrap();
        check(
            &format!("Fig. 8 from ({:+.3}, 1)", start[0]),
            &b,
            2.0,
            &s11_h,
            glen,
        );
    }
}

/// The S11/S12 curve through the whole pipeline front end: Bézier patches (exact conversions of
/// the polynomial graphs), the start-point search, then the graph: the same four arcs and two
/// nodes as from the paper's start, each arc once.
#[test]
fn s11_s12_from_the_start_point_search_gives_the_same_graph() {
    let d = Domain::new(-2.0, 2.0, -0.5, 2.5);
    let p = height_field(d, vec![(4, 0, 0.2), (0, 4, 0.1)]);
    let q = height_field(d, vec![(2, 1, 0.3), (0, 2, -0.1), (0, 3, 0.2)]);
    let out = intersect(&p, &q, &opts(0.1), &SearchOptions::default());
    let br = &out.intersection.branches;
    for b in br {
        for pt in &b.points {
            assert!(s11_h(pt.p[0], pt.p[1]).abs() < 1e-8);
        }
    }
    let samples: Vec<Vec<f64>> = implicit_samples(&s11_h, [-2.0, 2.0, -0.5, 2.5], 0.01)
        .into_iter()
        .map(|s| s.to_vec())
        .collect();
    let nodes: Vec<Vec<f64>> = out.nodes.iter().map(|n| vec![n.x[0], n.x[1]]).collect();
    let cov = coverage(br, &samples, &nodes, 0.15, 5e-3, &|p| p.p.to_vec());
    let k = kinds(br);
    println!(
        "S11/S12 via intersect: {} starts ({} skipped), arcs {:?}, nodes {:?}, samples {} missing {} double {}",
        out.stats.boundary_starts + out.stats.interior_candidates,
        out.stats.skipped_covered,
        k,
        out.nodes.iter().map(|n| (n.case, n.exits.len())).collect::<Vec<_>>(),
        cov.0,
        cov.1,
        cov.2
    );
    assert_eq!(k, (0, 4, 0));
    assert_eq!(out.nodes.len(), 2);
    assert_eq!((cov.1, cov.2), (0, 0));
}
