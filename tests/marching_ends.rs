//! Stop rules at the ends of a branch: exact boundary landing, one-way marching from a boundary
//! start, point budget, and typed errors for bad input.

mod common;

use common::surfaces::{plane_z0, Analytic};
use ssitrace::error::Error;
use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::Domain;
use ssitrace::march::branch::{BranchStatus, EndReason, EventKind};
use ssitrace::march::{trace_branch, MarchOptions, StepMethod};

/// P: the graph z = u − 0.3 + 0.2 v² on [0,1]²; Q: the plane z = 0 on [−1,2]². The curve is
/// u = 0.3 − 0.2 v², v ∈ [0, 1], leaving P's domain through v = 0 and v = 1.
fn pair() -> (Analytic, Analytic) {
    (
        AnalyticSurface::new(Domain::UNIT, |u, v| [u, v, u - 0.3 + 0.2 * v * v]),
        plane_z0(Domain::new(-1.0, 2.0, -1.0, 2.0)),
    )
}

#[test]
fn lands_exactly_on_both_boundaries() {
    let (p, q) = pair();
    for method in [StepMethod::Circular, StepMethod::Dqoc, StepMethod::Tangent] {
        let opts = MarchOptions {
            step: 0.07,
            method,
            ..MarchOptions::default()
        };
        let b = trace_branch(&p, &q, [0.25, 0.5, 0.25, 0.5], &opts).unwrap();
        assert_eq!(b.branch.status, BranchStatus::Open);
        assert_eq!(b.branch.ends, [EndReason::Boundary { surface: 0 }; 2]);
        let (first, last) = (b.branch.points[0], *b.branch.points.last().unwrap());
        let mut ends = [first.p[1], last.p[1]];
        ends.sort_by(f64::total_cmp);
        assert_eq!(ends, [0.0, 1.0], "{method:?}: not exactly on the boundary");
        for pt in &b.branch.points {
            assert!((pt.p[0] - (0.3 - 0.2 * pt.p[1] * pt.p[1])).abs() < 1e-9);
        }
        assert_eq!(
            b.events
                .iter()
                .filter(|e| e.kind == EventKind::BoundaryEnd)
                .count(),
            2
        );
        // Ordered along the curve: v increases or decreases monotonically.
        let v: Vec<f64> = b.branch.points.iter().map(|c| c.p[1]).collect();
        let up = v.windows(2).all(|w| w[1] > w[0]);
        let down = v.windows(2).all(|w| w[1] < w[0]);
        assert!(up || down, "{method:?}: points not ordered");
    }
}

#[test]
fn start_on_a_boundary_marches_one_way() {
    let (p, q) = pair();
    let b = trace_branch(&p, &q, [0.3, 0.0, 0.3, 0.0], &MarchOptions::default()).unwrap();
    assert_eq!(b.branch.ends, [EndReason::Boundary { surface: 0 }; 2]);
    assert_eq!(b.branch.points[0].p[1], 0.0);
    assert_eq!(b.branch.points.last().unwrap().p[1], 1.0);
    // From the far end too.
    let b = trace_branch(&p, &q, [0.1, 1.0, 0.1, 1.0], &MarchOptions::default()).unwrap();
    assert_eq!(b.branch.points[0].p[1], 1.0);
    assert_eq!(b.branch.points.last().unwrap().p[1], 0.0);
}

#[test]
fn point_budget_is_reported() {
    let (p, q) = pair();
    let opts = MarchOptions {
        max_points: 5,
        ..MarchOptions::default()
    };
    let b = trace_branch(&p, &q, [0.25, 0.5, 0.25, 0.5], &opts).unwrap();
    assert!(b.branch.points.len() <= 5);
    assert!(b.branch.ends.contains(&EndReason::PointLimit));
    assert_eq!(b.branch.status, BranchStatus::Incomplete);
}

#[test]
fn bad_input_gives_typed_errors() {
    let (p, q) = pair();
    let bad_step = MarchOptions {
        step: f64::NAN,
        ..MarchOptions::default()
    };
    assert!(matches!(
        trace_branch(&p, &q, [0.25, 0.5, 0.25, 0.5], &bad_step),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        trace_branch(
            &p,
            &q,
            [f64::INFINITY, 0.5, 0.25, 0.5],
            &MarchOptions::default()
        ),
        Err(Error::InvalidInput { .. })
    ));
    // Two parallel planes never meet: the start cannot be refined.
    let far = AnalyticSurface::new(Domain::UNIT, |u: Jet2, v: Jet2| [u, v, Jet2::constant(1.0)]);
    assert!(matches!(
        trace_branch(&far, &q, [0.5, 0.5, 0.5, 0.5], &MarchOptions::default()),
        Err(Error::NewtonFailed { .. })
    ));
}
